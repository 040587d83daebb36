(** * Uniqueness for absolutely continuous solutions
      ([prop:proj-micro], uniqueness part), over [R].

    Paper, [prop:proj-micro]: "there exists a unique solution x to
    (eq:micro-f0-lagr)", [ẋ(t) ∈ u⁰ − ∂I_{K^N}(x(t))] for a.e. [t],
    [x(0) = x⁰]. The class of solutions of a differential inclusion is the
    absolutely continuous paths satisfying it almost everywhere; this file
    proves uniqueness in that class ([SolutionAC]) with elementary
    definitions of null sets ([NullSet]) and absolute continuity
    ([AbsCont]), no Lebesgue theory.

    The key lemma ([nonincreasing_ac]): an absolutely continuous [φ] on
    [[a, b]] with [φ' ≤ 0] at every [t ∈ (a, b)] off a null set does not
    increase. Its proof is a continuous induction (a supremum argument with
    [completeness]): for [ε > 0], [δ] from absolute continuity and a cover
    of the null set by intervals of total length [≤ δ/2], the points [s]
    reached with [φ(s) − φ(a) ≤ ε (s − a) + Σ (increments of φ over a
    non-overlapping family of subintervals of [a, s], each inside one
    interval of the cover, of total length within the cover's length left
    of s)] form a set whose supremum is [b]; then [φ(b) − φ(a) ≤ ε(b − a) + ε].

    Over Coq's real numbers (with Coquelicot's derivatives): the theorems
    rest on the standard real-number axioms and no other, which
    [check-assumptions.sh] checks. *)

From Coq Require Import Reals Lra Lia Arith Classical List.
From Coquelicot Require Import Coquelicot.
From Sticky Require Import Uniqueness.
Open Scope R_scope.

(** ** Finite sums *)

Lemma sumN_zero_fun (n : nat) : sumN n (fun _ => 0) = 0.
Proof. induction n as [|n IH]; simpl; [reflexivity|rewrite IH; ring]. Qed.

Lemma sumN_le (n : nat) (f g : nat -> R) :
  (forall i, (i < n)%nat -> f i <= g i) -> sumN n f <= sumN n g.
Proof.
  induction n as [|n IH]; intro H; simpl; [lra|].
  pose proof (H n ltac:(lia)). pose proof (IH (fun i Hi => H i ltac:(lia))). lra.
Qed.

Lemma sumN_mono_n (n m : nat) (f : nat -> R) :
  (forall i, 0 <= f i) -> (n <= m)%nat -> sumN n f <= sumN m f.
Proof.
  intros Hf Hnm. induction m as [|m IH].
  - replace n with 0%nat by lia. lra.
  - destruct (Nat.eq_dec n (S m)) as [->|Hne]; [lra|].
    simpl. pose proof (IH ltac:(lia)). pose proof (Hf m). lra.
Qed.

(** Raising one term [k < n] of a sum whose terms only grow. *)
Lemma sumN_bump (n k : nat) (g h : nat -> R) :
  (forall j, (j < n)%nat -> g j <= h j) -> (k < n)%nat ->
  sumN n g + (h k - g k) <= sumN n h.
Proof.
  induction n as [|n IH]; intros H Hk; [lia|]. simpl.
  destruct (Nat.eq_dec k n) as [->|Hne].
  - pose proof (sumN_le n g h (fun j Hj => H j ltac:(lia))). lra.
  - pose proof (IH (fun j Hj => H j ltac:(lia)) ltac:(lia)). pose proof (H n ltac:(lia)). lra.
Qed.

(** ** Null sets and absolute continuity *)

(** [E] is null: for every [ε > 0], a sequence of intervals [(c_k, d_k)]
    ([c_k ≤ d_k]) covers [E] and every partial sum of their lengths is
    [≤ ε]. *)
Definition NullSet (E : R -> Prop) : Prop :=
  forall eps, 0 < eps -> exists c d : nat -> R,
    (forall k, c k <= d k) /\
    (forall t, E t -> exists k, c k < t < d k) /\
    (forall n, sumN n (fun k => d k - c k) <= eps).

(** [n] non-overlapping subintervals [[p_i, q_i]] of [[a, b]], listed from
    left to right. *)
Definition Chain (a b : R) (n : nat) (p q : nat -> R) : Prop :=
  (forall i, (i < n)%nat -> a <= p i /\ p i <= q i /\ q i <= b) /\
  (forall i, (S i < n)%nat -> q i <= p (S i)).

(** [f] is absolutely continuous on [[a, b]]: for every [ε > 0] there is
    [δ > 0] such that every finite family of non-overlapping subintervals
    [[p_i, q_i]] of [[a, b]] with [Σ (q_i − p_i) < δ] has
    [Σ |f(q_i) − f(p_i)| < ε]. *)
Definition AbsCont (a b : R) (f : R -> R) : Prop :=
  forall eps, 0 < eps -> exists delta, 0 < delta /\
    forall n p q, Chain a b n p q -> sumN n (fun i => q i - p i) < delta ->
      sumN n (fun i => Rabs (f (q i) - f (p i))) < eps.

Lemma NullSet_union (E1 E2 : R -> Prop) :
  NullSet E1 -> NullSet E2 -> NullSet (fun t => E1 t \/ E2 t).
Proof.
  intros H1 H2 eps Heps.
  destruct (H1 (eps / 2) ltac:(lra)) as (c1 & d1 & Hcd1 & Hcov1 & Hs1).
  destruct (H2 (eps / 2) ltac:(lra)) as (c2 & d2 & Hcd2 & Hcov2 & Hs2).
  set (c := fun k => if Nat.even k then c1 (Nat.div2 k) else c2 (Nat.div2 k)).
  set (d := fun k => if Nat.even k then d1 (Nat.div2 k) else d2 (Nat.div2 k)).
  assert (Ev : forall k, Nat.even (2 * k) = true) by (intro k; exact (Nat.even_add_mul_2 0 k)).
  assert (Od : forall k, Nat.even (S (2 * k)) = false) by (intro k; exact (Nat.even_add_mul_2 1 k)).
  assert (Cev : forall k, c (2 * k)%nat = c1 k /\ d (2 * k)%nat = d1 k).
  { intro k. unfold c, d. rewrite Ev, Nat.div2_double. split; reflexivity. }
  assert (Cod : forall k, c (S (2 * k)) = c2 k /\ d (S (2 * k)) = d2 k).
  { intro k. unfold c, d. rewrite Od, Nat.div2_succ_double. split; reflexivity. }
  assert (Hnn : forall k, 0 <= d k - c k).
  { intro k. unfold c, d. destruct (Nat.even k); [pose proof (Hcd1 (Nat.div2 k))|pose proof (Hcd2 (Nat.div2 k))]; lra. }
  assert (Hdouble : forall n, sumN (2 * n) (fun k => d k - c k) =
                             sumN n (fun k => d1 k - c1 k) + sumN n (fun k => d2 k - c2 k)).
  { induction n as [|n IH]; [simpl; ring|].
    replace (2 * S n)%nat with (S (S (2 * n))) by lia.
    change (sumN (S (S (2 * n))) (fun k => d k - c k))
      with (sumN (2 * n) (fun k => d k - c k) + (d (2 * n)%nat - c (2 * n)%nat) +
            (d (S (2 * n)) - c (S (2 * n)))).
    rewrite IH. destruct (Cev n) as [-> ->]. destruct (Cod n) as [-> ->]. simpl. ring. }
  exists c, d. split; [|split].
  - intro k. pose proof (Hnn k). lra.
  - intros t [Ht|Ht].
    + destruct (Hcov1 t Ht) as (k & Hk). exists (2 * k)%nat. destruct (Cev k) as [-> ->]. exact Hk.
    + destruct (Hcov2 t Ht) as (k & Hk). exists (S (2 * k)). destruct (Cod k) as [-> ->]. exact Hk.
  - intro n. pose proof (sumN_mono_n n (2 * n) _ Hnn ltac:(lia)).
    rewrite Hdouble in H. pose proof (Hs1 n). pose proof (Hs2 n). lra.
Qed.

(** A point is null, hence (by [NullSet_union]) every finite set: a path
    differentiable off finitely many times is differentiable off a null
    set. *)
Lemma NullSet_point (x : R) : NullSet (fun t => t = x).
Proof.
  intros eps Heps.
  exists (fun k => match k with O => x - eps / 4 | S _ => 0 end),
         (fun k => match k with O => x + eps / 4 | S _ => 0 end).
  split; [|split].
  - intros [|k]; lra.
  - intros t ->. exists O. lra.
  - intros n. destruct n as [|n]; simpl; [lra|].
    induction n as [|n IH]; simpl in *; lra.
Qed.

Lemma NullSet_finite (l : list R) : NullSet (fun t => In t l).
Proof.
  induction l as [|x l IH].
  - intros eps Heps. exists (fun _ => 0), (fun _ => 0). split; [|split].
    + intros; lra.
    + intros t [].
    + intros n. rewrite (sumN_ext n _ (fun _ => 0)) by (intros; ring).
      rewrite sumN_zero_fun. lra.
  - intros eps Heps.
    destruct (NullSet_union _ _ (NullSet_point x) IH eps Heps) as (c & d & H1 & H2 & H3).
    exists c, d. split; [exact H1|split; [|exact H3]].
    intros t [Ht|Ht]; apply H2; [left; symmetry; exact Ht|right; exact Ht].
Qed.

(** ** Closure properties of absolute continuity *)

Lemma Chain_sub (a b a' b' : R) (n : nat) (p q : nat -> R) :
  a <= a' -> b' <= b -> Chain a' b' n p q -> Chain a b n p q.
Proof.
  intros Ha Hb [H1 H2]. split; [|exact H2].
  intros i Hi. destruct (H1 i Hi) as (A & B & C). lra.
Qed.

Lemma AbsCont_sub (a b a' b' : R) (f : R -> R) :
  a <= a' -> b' <= b -> AbsCont a b f -> AbsCont a' b' f.
Proof.
  intros Ha Hb H eps Heps. destruct (H eps Heps) as (δ & Hδ & Hf).
  exists δ. split; [exact Hδ|]. intros n p q Hc. apply Hf. exact (Chain_sub a b a' b' n p q Ha Hb Hc).
Qed.

Lemma AbsCont_const (a b k : R) : AbsCont a b (fun _ => k).
Proof.
  intros eps Heps. exists 1. split; [lra|]. intros n p q _ _.
  rewrite (sumN_ext n _ (fun _ => 0)); [rewrite sumN_zero_fun; exact Heps|].
  intros i _. replace (k - k) with 0 by ring. apply Rabs_R0.
Qed.

Lemma AbsCont_plus (a b : R) (f g : R -> R) :
  AbsCont a b f -> AbsCont a b g -> AbsCont a b (fun s => f s + g s).
Proof.
  intros Hf Hg eps Heps.
  destruct (Hf (eps / 2) ltac:(lra)) as (δf & Hδf & Hf').
  destruct (Hg (eps / 2) ltac:(lra)) as (δg & Hδg & Hg').
  exists (Rmin δf δg). split; [apply Rmin_glb_lt; assumption|]. intros n p q Hc Hs.
  pose proof (Hf' n p q Hc ltac:(pose proof (Rmin_l δf δg); lra)).
  pose proof (Hg' n p q Hc ltac:(pose proof (Rmin_r δf δg); lra)).
  assert (sumN n (fun i => Rabs (f (q i) + g (q i) - (f (p i) + g (p i)))) <=
          sumN n (fun i => Rabs (f (q i) - f (p i)) + Rabs (g (q i) - g (p i)))).
  { apply sumN_le. intros i _.
    replace (f (q i) + g (q i) - (f (p i) + g (p i)))
      with ((f (q i) - f (p i)) + (g (q i) - g (p i))) by ring. apply Rabs_triang. }
  rewrite sumN_plus in H1. lra.
Qed.

(** [−f] has the same increments in absolute value. *)
Lemma AbsCont_opp (a b : R) (f : R -> R) : AbsCont a b f -> AbsCont a b (fun s => - f s).
Proof.
  intros Hf eps Heps. destruct (Hf eps Heps) as (δ & Hδ & H). exists δ. split; [exact Hδ|].
  intros n p q Hc Hs.
  rewrite (sumN_ext n _ (fun i => Rabs (f (q i) - f (p i)))); [apply H; assumption|].
  intros i _. rewrite <- Rabs_Ropp. f_equal. ring.
Qed.

(** [f − g] is [f + (−g)] ([Rminus] unfolds to it). *)
Lemma AbsCont_minus (a b : R) (f g : R -> R) :
  AbsCont a b f -> AbsCont a b g -> AbsCont a b (fun s => f s - g s).
Proof. intros Hf Hg. exact (AbsCont_plus a b f (fun s => - g s) Hf (AbsCont_opp a b g Hg)). Qed.

Lemma AbsCont_sumN (a b : R) (N : nat) (g : nat -> R -> R) :
  (forall i, (i < N)%nat -> AbsCont a b (g i)) ->
  AbsCont a b (fun s => sumN N (fun i => g i s)).
Proof.
  induction N as [|N IH]; intro H; simpl.
  - apply AbsCont_const.
  - apply (AbsCont_plus a b (fun s => sumN N (fun i => g i s)) (g N)).
    + apply IH. intros i Hi. apply H. lia.
    + apply H. lia.
Qed.

(** A Lipschitz function on [[a, b]] is absolutely continuous there (the
    projection path is Lipschitz with constant [‖u⁰‖]). *)
Lemma AbsCont_lipschitz (a b L : R) (f : R -> R) :
  0 <= L -> (forall s t, a <= s -> s <= t -> t <= b -> Rabs (f t - f s) <= L * (t - s)) ->
  AbsCont a b f.
Proof.
  intros HL Hf eps Heps. exists (eps / (L + 1)). split; [apply Rdiv_lt_0_compat; lra|].
  intros n p q Hc Hs.
  assert (Hle : sumN n (fun i => Rabs (f (q i) - f (p i))) <= sumN n (fun i => (L + 1) * (q i - p i))).
  { apply sumN_le. intros i Hi. destruct (proj1 Hc i Hi) as (A & B & C).
    pose proof (Hf (p i) (q i) A B C). nra. }
  rewrite sumN_scal in Hle.
  assert ((L + 1) * sumN n (fun i => q i - p i) < (L + 1) * (eps / (L + 1)))
    by (apply Rmult_lt_compat_l; [lra|exact Hs]).
  replace ((L + 1) * (eps / (L + 1))) with eps in H by (field; lra). lra.
Qed.

(** One interval [[s, t]]. *)
Lemma AbsCont_interval (a b : R) (f : R -> R) :
  AbsCont a b f -> forall eps, 0 < eps -> exists delta, 0 < delta /\
    forall s t, a <= s -> s <= t -> t <= b -> t - s < delta -> Rabs (f t - f s) < eps.
Proof.
  intros H eps Heps. destruct (H eps Heps) as (δ & Hδ & Hf). exists δ. split; [exact Hδ|].
  intros s t Hs Hst Ht Hl.
  assert (Hc : Chain a b 1 (fun _ => s) (fun _ => t)).
  { split; [intros i _; lra|intros i Hi; lia]. }
  pose proof (Hf 1%nat _ _ Hc ltac:(simpl; lra)) as R1. simpl in R1. lra.
Qed.

Lemma AbsCont_bounded (a b : R) (f : R -> R) :
  a <= b -> AbsCont a b f -> exists M, forall t, a <= t <= b -> Rabs (f t) <= M.
Proof.
  intros Hab H. destruct (AbsCont_interval a b f H 1 ltac:(lra)) as (δ & Hδ & Hf).
  assert (Step : forall n t, a <= t <= b -> t - a <= INR n * (δ / 2) -> Rabs (f t - f a) <= INR n).
  { induction n as [|n IH]; intros t Ht Hl.
    - simpl in Hl. replace t with a by lra. replace (f a - f a) with 0 by ring.
      rewrite Rabs_R0. simpl; lra.
    - rewrite S_INR in Hl |- *. set (t' := Rmax a (t - δ / 2)).
      assert (a <= t' <= t) by (unfold t', Rmax; destruct Rle_dec; lra).
      assert (t - t' <= δ / 2) by (unfold t', Rmax; destruct Rle_dec; lra).
      assert (t' - a <= INR n * (δ / 2)).
      { pose proof (pos_INR n). rewrite Rmult_plus_distr_r in Hl.
        assert (0 <= INR n * (δ / 2)) by (apply Rmult_le_pos; lra).
        unfold t', Rmax; destruct Rle_dec; lra. }
      pose proof (IH t' ltac:(lra) ltac:(lra)).
      pose proof (Hf t' t ltac:(lra) ltac:(lra) ltac:(lra) ltac:(lra)).
      replace (f t - f a) with ((f t - f t') + (f t' - f a)) by ring.
      pose proof (Rabs_triang (f t - f t') (f t' - f a)). lra. }
  destruct (nfloor_ex ((b - a) / (δ / 2))) as (n & Hn1 & Hn2).
  { apply Rdiv_le_0_compat; lra. }
  exists (Rabs (f a) + INR (S n)). intros t Ht.
  assert (t - a <= INR (S n) * (δ / 2)).
  { rewrite S_INR. assert (b - a = (b - a) / (δ / 2) * (δ / 2)) by (field; lra).
    assert ((b - a) / (δ / 2) * (δ / 2) <= (INR n + 1) * (δ / 2))
      by (apply Rmult_le_compat_r; lra). lra. }
  pose proof (Step (S n) t Ht H0).
  replace (f t) with (f a + (f t - f a)) by ring.
  pose proof (Rabs_triang (f a) (f t - f a)). lra.
Qed.

Lemma AbsCont_sq (a b : R) (f : R -> R) :
  a <= b -> AbsCont a b f -> AbsCont a b (fun s => f s * f s).
Proof.
  intros Hab H. destruct (AbsCont_bounded a b f Hab H) as (M & HM).
  assert (HM0 : 0 <= M) by (pose proof (HM a ltac:(lra)); pose proof (Rabs_pos (f a)); lra).
  intros eps Heps. set (k := 2 * M + 1).
  destruct (H (eps / k) ltac:(unfold k; apply Rdiv_lt_0_compat; lra)) as (δ & Hδ & Hf).
  exists δ. split; [exact Hδ|]. intros n p q Hc Hs.
  pose proof (Hf n p q Hc Hs) as Hlt.
  assert (Hle : sumN n (fun i => Rabs (f (q i) * f (q i) - f (p i) * f (p i))) <=
                sumN n (fun i => k * Rabs (f (q i) - f (p i)))).
  { apply sumN_le. intros i Hi. destruct (proj1 Hc i Hi) as (A & B & C).
    replace (f (q i) * f (q i) - f (p i) * f (p i))
      with ((f (q i) + f (p i)) * (f (q i) - f (p i))) by ring.
    rewrite Rabs_mult. apply Rmult_le_compat_r; [apply Rabs_pos|].
    pose proof (Rabs_triang (f (q i)) (f (p i))).
    pose proof (HM (q i) ltac:(lra)). pose proof (HM (p i) ltac:(lra)). unfold k. lra. }
  rewrite sumN_scal in Hle.
  assert (k * sumN n (fun i => Rabs (f (q i) - f (p i))) < k * (eps / k))
    by (apply Rmult_lt_compat_l; [unfold k; lra|exact Hlt]).
  replace (k * (eps / k)) with eps in H0 by (field; unfold k; lra). lra.
Qed.

(** ** The key lemma: [φ' ≤ 0] off a null set *)

Section Nonincreasing.

Variables (φ : R -> R) (a eps : R) (c d : nat -> R).

(** The length of [(c_j, d_j) ∩ [a, s]]. *)
Let len (j : nat) (s : R) : R := Rmax 0 (Rmin s (d j) - Rmax a (c j)).

(** The invariant of the continuous induction at [s]. *)
Let Inv (s : R) : Prop :=
  exists n m p q, Chain a s m p q /\
    sumN m (fun i => q i - p i) <= sumN n (fun j => len j s) /\
    φ s - φ a <= eps * (s - a) + sumN m (fun i => φ (q i) - φ (p i)).

Lemma len_nonneg j s : 0 <= len j s.
Proof. apply Rmax_l. Qed.

Lemma len_mono j s s' : s <= s' -> len j s <= len j s'.
Proof. intro H. unfold len, Rmax, Rmin. repeat destruct Rle_dec; lra. Qed.

Lemma len_le j s : c j <= d j -> len j s <= d j - c j.
Proof. intro H. unfold len, Rmax, Rmin. repeat destruct Rle_dec; lra. Qed.

Lemma len_step j s s' : a <= s -> c j <= s -> s <= s' -> s' <= d j -> len j s + (s' - s) <= len j s'.
Proof. intros. unfold len, Rmax, Rmin. repeat destruct Rle_dec; lra. Qed.

Lemma Inv_start : Inv a.
Proof.
  exists 0%nat, 0%nat, (fun _ => a), (fun _ => a). simpl. split; [split; intros; lia|]. split; lra.
Qed.

(** A tag [t] off the null set: [φ] grows at most at rate [ε] near [t]. *)
Lemma Inv_step_free s t s' :
  0 < eps -> a <= s -> s <= t -> t <= s' ->
  φ s' - φ t <= eps * (s' - t) -> φ t - φ s <= eps * (t - s) -> Inv s -> Inv s'.
Proof.
  intros He Ha H1 H2 D1 D2 (n & m & p & q & Hc & Hl & Hφ).
  exists n, m, p, q. split; [|split].
  - exact (Chain_sub a s' a s m p q ltac:(lra) ltac:(lra) Hc).
  - pose proof (sumN_le n (fun j => len j s) (fun j => len j s')
                  (fun j _ => len_mono j s s' ltac:(lra))). lra.
  - lra.
Qed.

(** A tag in the interval [(c_k, d_k)] of the cover: [[s, s']] joins the
    family. *)
Lemma Inv_step_cover k s s' :
  0 < eps -> a <= s -> s <= s' -> c k <= s -> s' <= d k -> Inv s -> Inv s'.
Proof.
  intros He Ha Hs Hc1 Hd1 (n & m & p & q & [Hc Hadj] & Hl & Hφ).
  set (p' := fun i => if Nat.eqb i m then s else p i).
  set (q' := fun i => if Nat.eqb i m then s' else q i).
  assert (Old : forall i, (i < m)%nat -> p' i = p i /\ q' i = q i).
  { intros i Hi. unfold p', q'. rewrite (proj2 (Nat.eqb_neq i m)) by lia. split; reflexivity. }
  assert (New : p' m = s /\ q' m = s') by (unfold p', q'; rewrite Nat.eqb_refl; split; reflexivity).
  exists (Nat.max n (S k)), (S m), p', q'. split; [split|split].
  - intros i Hi. destruct (Nat.eq_dec i m) as [->|Hne].
    + destruct New as [-> ->]. lra.
    + destruct (Old i ltac:(lia)) as [-> ->]. destruct (Hc i ltac:(lia)) as (A & B & C). lra.
  - intros i Hi. destruct (Nat.eq_dec (S i) m) as [Hm|Hne].
    + rewrite Hm. destruct New as [-> _]. destruct (Old i ltac:(lia)) as [_ ->].
      destruct (Hc i ltac:(lia)) as (A & B & C). lra.
    + destruct (Old i ltac:(lia)) as [_ ->]. destruct (Old (S i) ltac:(lia)) as [-> _].
      apply Hadj. lia.
  - change (sumN (S m) (fun i => q' i - p' i)) with (sumN m (fun i => q' i - p' i) + (q' m - p' m)).
    rewrite (sumN_ext m _ (fun i => q i - p i))
      by (intros i Hi; destruct (Old i Hi) as [-> ->]; reflexivity).
    destruct New as [-> ->].
    pose proof (sumN_mono_n n (Nat.max n (S k)) (fun j => len j s)
                  (fun j => len_nonneg j s) ltac:(lia)).
    pose proof (sumN_bump (Nat.max n (S k)) k (fun j => len j s) (fun j => len j s')
                  (fun j _ => len_mono j s s' Hs) ltac:(lia)).
    pose proof (len_step k s s' Ha Hc1 Hs Hd1). simpl in *. lra.
  - change (sumN (S m) (fun i => φ (q' i) - φ (p' i)))
      with (sumN m (fun i => φ (q' i) - φ (p' i)) + (φ (q' m) - φ (p' m))).
    rewrite (sumN_ext m _ (fun i => φ (q i) - φ (p i)))
      by (intros i Hi; destruct (Old i Hi) as [-> ->]; reflexivity).
    destruct New as [-> ->].
    assert (eps * (s - a) <= eps * (s' - a)) by (apply Rmult_le_compat_l; lra). lra.
Qed.

Lemma Inv_end b delta :
  (forall k, c k <= d k) -> (forall n, sumN n (fun k => d k - c k) <= delta / 2) -> 0 < delta ->
  (forall n p q, Chain a b n p q -> sumN n (fun i => q i - p i) < delta ->
     sumN n (fun i => Rabs (φ (q i) - φ (p i))) < eps) ->
  Inv b -> φ b - φ a <= eps * (b - a) + eps.
Proof.
  intros Hcd Hs Hδ Hac (n & m & p & q & Hc & Hl & Hφ).
  pose proof (sumN_le n (fun j => len j b) (fun j => d j - c j) (fun j _ => len_le j b (Hcd j))).
  pose proof (Hs n).
  pose proof (Hac m p q Hc ltac:(lra)).
  pose proof (sumN_le m (fun i => φ (q i) - φ (p i)) (fun i => Rabs (φ (q i) - φ (p i)))
                (fun i _ => Rle_abs _)). lra.
Qed.

End Nonincreasing.

(** Near a point where [φ' ≤ 0], [φ] grows at most at rate [ε]. *)
Lemma deriv_gauge (φ : R -> R) (t l eps : R) :
  is_derive φ t l -> l <= 0 -> 0 < eps -> exists γ, 0 < γ /\
    forall s, Rabs (s - t) < γ ->
      (t <= s -> φ s - φ t <= eps * (s - t)) /\ (s <= t -> φ t - φ s <= eps * (t - s)).
Proof.
  intros Hd Hl He. apply is_derive_Reals in Hd. destruct (Hd eps He) as (γ & Hγ).
  exists γ. split; [apply cond_pos|]. intros s Hs.
  destruct (Req_dec s t) as [->|Hne]; [split; intros; lra|].
  pose proof (Hγ (s - t) ltac:(lra) Hs) as H.
  replace (t + (s - t)) with s in H by ring.
  set (qt := (φ s - φ t) / (s - t)) in H.
  apply Rabs_def2 in H. destruct H as [H _].
  split; intro Hts.
  - replace (φ s - φ t) with (qt * (s - t)) by (unfold qt; field; lra).
    apply Rmult_le_compat_r; lra.
  - replace (φ t - φ s) with (qt * (t - s)) by (unfold qt; field; lra).
    apply Rmult_le_compat_r; lra.
Qed.

(** The derivative hypothesis on the closed interval. *)
Lemma nonincreasing_ac_closed (φ dφ : R -> R) (E : R -> Prop) (a b : R) :
  a <= b -> AbsCont a b φ -> NullSet E ->
  (forall t, a <= t <= b -> ~ E t -> is_derive φ t (dφ t) /\ dφ t <= 0) ->
  φ b <= φ a.
Proof.
  intros Hab Hac Hnull Hd.
  apply le_epsilon. intros η Hη.
  set (eps := η / (b - a + 1)).
  assert (He : 0 < eps) by (unfold eps; apply Rdiv_lt_0_compat; lra).
  destruct (Hac eps He) as (δ & Hδ & Hac').
  destruct (Hnull (δ / 2) ltac:(lra)) as (c & d & Hcd & Hcov & Hs).
  set (S := fun s => a <= s <= b /\
    exists n m p q, Chain a s m p q /\
      sumN m (fun i => q i - p i) <= sumN n (fun j => Rmax 0 (Rmin s (d j) - Rmax a (c j))) /\
      φ s - φ a <= eps * (s - a) + sumN m (fun i => φ (q i) - φ (p i))).
  destruct (completeness S) as (t & Hub & Hlub).
  { exists b. intros s Hs'. apply Hs'. }
  { exists a. split; [lra|]. exact (Inv_start φ a eps c d). }
  assert (Hat : a <= t) by (apply Hub; split; [lra|exact (Inv_start φ a eps c d)]).
  assert (Htb : t <= b) by (apply Hlub; intros s Hs'; apply Hs').
  (* the gauge at t *)
  assert (Hg : exists γ, 0 < γ /\ forall s s', a <= s -> s <= t -> t <= s' -> s' <= b ->
              t - γ < s -> s' < t + γ -> S s -> S s').
  { destruct (classic (E t)) as [HE|HE].
    - destruct (Hcov t HE) as (k & Hk).
      exists (Rmin (t - c k) (d k - t)). split; [apply Rmin_glb_lt; lra|].
      intros s s' H1 H2 H3 H4 H5 H6 [_ Hi]. split; [lra|].
      pose proof (Rmin_l (t - c k) (d k - t)). pose proof (Rmin_r (t - c k) (d k - t)).
      exact (Inv_step_cover φ a eps c d k s s' He H1 ltac:(lra) ltac:(lra) ltac:(lra) Hi).
    - destruct (Hd t ltac:(lra) HE) as [Hder Hneg].
      destruct (deriv_gauge φ t (dφ t) eps Hder Hneg He) as (γ & Hγ & Hgt).
      exists γ. split; [exact Hγ|].
      intros s s' H1 H2 H3 H4 H5 H6 [_ Hi]. split; [lra|].
      apply (Inv_step_free φ a eps c d s t s' He H1 H2 H3); [ | | exact Hi].
      + apply (Hgt s'); [apply Rabs_def1; lra|lra].
      + apply (Hgt s); [apply Rabs_def1; lra|lra]. }
  destruct Hg as (γ & Hγ & Hstep).
  assert (Hs0 : exists s, S s /\ t - γ < s).
  { apply not_all_not_ex. intro Hn.
    assert (t <= t - γ); [|lra].
    apply Hlub. intros s Hs'. apply Rnot_lt_le. intro Hlt. exact (Hn s (conj Hs' Hlt)). }
  destruct Hs0 as (s & Hs' & Hst).
  assert (Hsa : a <= s) by apply Hs'.
  assert (Hts : s <= t) by (apply Hub; exact Hs').
  assert (HSt : S t) by (apply (Hstep s t); lra || exact Hs').
  assert (Hteq : t = b).
  { destruct (Rle_lt_or_eq_dec t b Htb) as [Hlt|Heq]; [|exact Heq].
    set (s' := Rmin b (t + γ / 2)).
    assert (t < s') by (unfold s'; apply Rmin_glb_lt; lra).
    assert (s' <= b) by apply Rmin_l.
    assert (s' <= t + γ / 2) by apply Rmin_r.
    assert (S s') by (apply (Hstep s s'); lra || exact Hs').
    pose proof (Hub s' H2). lra. }
  subst t. destruct HSt as [_ Hi].
  pose proof (Inv_end φ a eps c d b δ Hcd Hs Hδ Hac' Hi).
  assert (eps * (b - a) + eps = η) by (unfold eps; field; lra). lra.
Qed.

(** The key lemma: [φ] absolutely continuous on [[a, b]], differentiable
    with [φ' ≤ 0] at every [t ∈ (a, b)] off a null set [E]: [φ(b) ≤ φ(a)]. *)
Lemma nonincreasing_ac (φ dφ : R -> R) (E : R -> Prop) (a b : R) :
  a <= b -> AbsCont a b φ -> NullSet E ->
  (forall t, a < t < b -> ~ E t -> is_derive φ t (dφ t) /\ dφ t <= 0) ->
  φ b <= φ a.
Proof.
  intros Hab Hac Hnull Hd.
  destruct (Req_dec a b) as [->|Hne]; [lra|].
  apply le_epsilon. intros η Hη.
  destruct (AbsCont_interval a b φ Hac (η / 2) ltac:(lra)) as (δ & Hδ & Hf).
  set (h := Rmin (δ / 2) ((b - a) / 3)).
  assert (0 < h) by (unfold h; apply Rmin_glb_lt; lra).
  assert (h <= δ / 2) by apply Rmin_l.
  assert (h <= (b - a) / 3) by apply Rmin_r.
  assert (Hin : φ (b - h) <= φ (a + h)).
  { apply (nonincreasing_ac_closed φ dφ E (a + h) (b - h)); [lra| |exact Hnull|].
    - apply (AbsCont_sub a b); [lra|lra|exact Hac].
    - intros t Ht HE. apply Hd; [lra|exact HE]. }
  pose proof (Hf a (a + h) ltac:(lra) ltac:(lra) ltac:(lra) ltac:(lra)).
  pose proof (Hf (b - h) b ltac:(lra) ltac:(lra) ltac:(lra) ltac:(lra)).
  pose proof (Rle_abs (φ b - φ (b - h))).
  pose proof (Rle_abs (φ (a + h) - φ a)). lra.
Qed.

(** ** The differential inclusion, absolutely continuous solutions *)

(** A solution of [eq:micro-f0-lagr] on [[0, T]] in the class of
    absolutely continuous paths: [x(0) = x⁰]; [x(t) ∈ K^N] for
    [t ∈ [0, T]]; each coordinate [t ↦ x_i(t)] absolutely continuous on
    [[0, T]]; and off a null set [E] of times, at every [t ∈ (0, T)], [x]
    is differentiable with [u⁰ − ẋ(t) ∈ N_{x(t)} K^N]
    ([ẋ(t) ∈ u⁰ − ∂I_{K^N}(x(t))] for a.e. [t]). *)
Definition SolutionAC (N : nat) (r T : R) (x0 u0 : nat -> R) (x : R -> nat -> R) : Prop :=
  (forall i, (i < N)%nat -> x 0 i = x0 i) /\
  (forall t, 0 <= t <= T -> InKR N r (x t)) /\
  (forall i, (i < N)%nat -> AbsCont 0 T (fun s => x s i)) /\
  exists (E : R -> Prop) (v : R -> nat -> R), NullSet E /\
    forall t, 0 < t < T -> ~ E t ->
      (forall i, (i < N)%nat -> is_derive (fun s => x s i) t (v t i)) /\
      InNormalConeR N r (x t) (fun i => u0 i - v t i).

(** Paper, [prop:proj-micro]: "there exists a unique solution x to
    (eq:micro-f0-lagr)" — the uniqueness, in the class of absolutely
    continuous solutions: two solutions of the class [SolutionAC] on
    [[0, T]] with the same data [x⁰], [u⁰] are equal on [[0, T]], for every
    [N], [r], [T], [x⁰], [u⁰]. By the monotonicity of the normal cone,
    [d/dt ‖x − y‖² = 2⟨ẋ − ẏ, x − y⟩ ≤ 0] off a null set, and [‖x − y‖²]
    is absolutely continuous, so [nonincreasing_ac] applies.
    Ledger claim: [prop:proj-micro]. *)
Theorem solution_unique_ac (N : nat) (r T : R) (x0 u0 : nat -> R) (x y : R -> nat -> R) :
  SolutionAC N r T x0 u0 x -> SolutionAC N r T x0 u0 y ->
  forall t, 0 <= t <= T -> forall i, (i < N)%nat -> x t i = y t i.
Proof.
  intros (Hx0 & HxK & Hxc & Ex & v & HEx & Hxd) (Hy0 & HyK & Hyc & Ey & w & HEy & Hyd) t Ht.
  set (φ := fun s => sumN N (fun i => (x s i - y s i) * (x s i - y s i))).
  set (dφ := fun s => sumN N (fun i => 2 * (x s i - y s i) * (v s i - w s i))).
  assert (Hφ0 : φ 0 = 0).
  { unfold φ. rewrite (sumN_ext N _ (fun _ => 0)); [apply sumN_zero_fun|].
    intros i Hi. rewrite Hx0, Hy0 by exact Hi. ring. }
  assert (Hle : φ t <= φ 0).
  { apply (nonincreasing_ac φ dφ (fun s => Ex s \/ Ey s) 0 t); [lra| |apply NullSet_union; assumption|].
    - apply (AbsCont_sub 0 T); [lra|lra|]. unfold φ.
      apply (AbsCont_sumN 0 T N (fun i s => (x s i - y s i) * (x s i - y s i))).
      intros i Hi. apply (AbsCont_sq 0 T (fun s => x s i - y s i)); [lra|].
      apply (AbsCont_minus 0 T (fun s => x s i) (fun s => y s i)); [apply Hxc|apply Hyc]; exact Hi.
    - intros s Hs Hn.
      assert (Hnx : ~ Ex s) by (intro H; apply Hn; left; exact H).
      assert (Hny : ~ Ey s) by (intro H; apply Hn; right; exact H).
      destruct (Hxd s ltac:(lra) Hnx) as [Dx Nx].
      destruct (Hyd s ltac:(lra) Hny) as [Dy Ny].
      exact (sqdist_derive_nonpos N r u0 x y v w s
               (HxK s ltac:(lra)) (HyK s ltac:(lra)) Dx Nx Dy Ny). }
  assert (Hz : forall i, (i < N)%nat -> (x t i - y t i) * (x t i - y t i) = 0).
  { apply sumN_zero; [intros i _; apply Rle_0_sqr|]. fold (φ t). lra. }
  intros i Hi. specialize (Hz i Hi). apply Rmult_integral in Hz. destruct Hz; lra.
Qed.
