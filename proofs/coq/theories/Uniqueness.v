(** * Uniqueness of the solution of the differential inclusion
      ([prop:proj-micro], uniqueness part), over [R].

    Paper, [prop:proj-micro]: "there exists a unique solution x to
    (eq:micro-f0-lagr)", [ẋ(t) ∈ u⁰ − ∂I_{K^N}(x(t))], [x(0) = x⁰].
    Uniqueness is the monotonicity of the normal cone: for two solutions
    [x], [y], [d/dt ½‖x − y‖² = ⟨ẋ − ẏ, x − y⟩ ≤ 0] wherever both are
    differentiable, so [‖x − y‖²] does not increase from its value 0 at
    [t = 0].

    This file is over Coq's real numbers (with Coquelicot's derivatives and
    mean value theorem), as are [UniquenessAC.v] and [NormalConeR.v]: its theorem
    rests on the four axioms of the standard library's real numbers
    ([ClassicalDedekindReals.sig_not_dec], [sig_forall_dec],
    [functional_extensionality_dep], [Classical_Prop.classic]) and no
    other; [check-assumptions.sh] checks exactly that.

    The class of solutions ([SolutionR]): continuous paths in [K^N],
    differentiable outside a finite set of times, satisfying the inclusion
    where differentiable. It contains the piecewise-C¹ paths with finitely
    many pieces on [[0, T]]. Uniqueness among the absolutely continuous
    solutions, the paper's setting, is [UniquenessAC.solution_unique_ac]. *)

From Coq Require Import Reals Lra Lia List.
From Coquelicot Require Import Coquelicot.
Open Scope R_scope.

Fixpoint sumN (n : nat) (f : nat -> R) : R :=
  match n with
  | O => 0
  | S n => sumN n f + f n
  end.

Lemma sumN_ext (n : nat) (f g : nat -> R) :
  (forall i, (i < n)%nat -> f i = g i) -> sumN n f = sumN n g.
Proof.
  induction n as [|n IH]; intro H; simpl; [reflexivity|].
  rewrite IH, H; [reflexivity|lia|intros i Hi; apply H; lia].
Qed.

Lemma sumN_plus (n : nat) (f g : nat -> R) :
  sumN n (fun i => f i + g i) = sumN n f + sumN n g.
Proof. induction n as [|n IH]; simpl; [ring|rewrite IH; ring]. Qed.

Lemma sumN_scal (n : nat) (k : R) (f : nat -> R) :
  sumN n (fun i => k * f i) = k * sumN n f.
Proof. induction n as [|n IH]; simpl; [ring|rewrite IH; ring]. Qed.

Lemma sumN_nonneg (n : nat) (f : nat -> R) :
  (forall i, (i < n)%nat -> 0 <= f i) -> 0 <= sumN n f.
Proof.
  induction n as [|n IH]; intro H; simpl; [lra|].
  pose proof (H n ltac:(lia)). pose proof (IH (fun i Hi => H i ltac:(lia))). lra.
Qed.

Lemma sumN_zero (n : nat) (f : nat -> R) :
  (forall i, (i < n)%nat -> 0 <= f i) -> sumN n f <= 0 -> forall i, (i < n)%nat -> f i = 0.
Proof.
  induction n as [|n IH]; intros H Hs i Hi; [lia|]. simpl in Hs.
  pose proof (H n ltac:(lia)) as Hn.
  pose proof (sumN_nonneg n f (fun j Hj => H j ltac:(lia))) as Hr.
  destruct (Nat.eq_dec i n) as [->|Hne]; [lra|].
  apply IH; [intros j Hj; apply H; lia|lra|lia].
Qed.

Lemma is_derive_sumN (n : nat) (g dg : nat -> R -> R) (t : R) :
  (forall i, (i < n)%nat -> is_derive (g i) t (dg i t)) ->
  is_derive (fun s => sumN n (fun i => g i s)) t (sumN n (fun i => dg i t)).
Proof.
  induction n as [|n IH]; intro H; simpl.
  - apply (is_derive_const 0).
  - apply (is_derive_plus (fun s => sumN n (fun i => g i s)) (g n)).
    + apply IH. intros i Hi. apply H. lia.
    + apply H. lia.
Qed.

Lemma is_derive_sqdiff (f g : R -> R) (t df dg : R) :
  is_derive f t df -> is_derive g t dg ->
  is_derive (fun s => (f s - g s) * (f s - g s)) t (2 * (f t - g t) * (df - dg)).
Proof.
  intros Hf Hg.
  assert (Hd : is_derive (fun s => f s - g s) t (df - dg)) by (apply (is_derive_minus f g); assumption).
  pose proof (is_derive_mult _ _ t _ _ Hd Hd (fun n m => Rmult_comm n m)) as H.
  replace (2 * (f t - g t) * (df - dg))
    with (plus (mult (df - dg) (f t - g t)) (mult (f t - g t) (df - dg))).
  - exact H.
  - cbn. ring.
Qed.

Lemma continuity_sumN (n : nat) (g : nat -> R -> R) (t : R) :
  (forall i, (i < n)%nat -> continuity_pt (g i) t) ->
  continuity_pt (fun s => sumN n (fun i => g i s)) t.
Proof.
  induction n as [|n IH]; intro H; simpl.
  - apply continuity_pt_const. intros a b. reflexivity.
  - apply (continuity_pt_plus (fun s => sumN n (fun i => g i s)) (g n)).
    + apply IH. intros i Hi. apply H. lia.
    + apply H. lia.
Qed.

(** A continuous function on [[a, b]] whose derivative exists and is
    [≤ 0] on [(a, b)] off a finite set [E] does not increase: [φ(b) ≤ φ(a)]. *)
Lemma nonincreasing_off_finite (φ dφ : R -> R) (E : list R) :
  forall a b, a <= b ->
  (forall t, a <= t <= b -> continuity_pt φ t) ->
  (forall t, a < t < b -> ~ In t E -> is_derive φ t (dφ t) /\ dφ t <= 0) ->
  φ b <= φ a.
Proof.
  induction E as [|e E IH]; intros a b Hab Hc Hd.
  - destruct (Req_dec a b) as [->|Hne]; [lra|].
    destruct (MVT_gen φ a b (fun t => Rmin (dφ t) 0)) as (c & Hcab & Hm).
    + rewrite Rmin_left, Rmax_right by lra. intros x Hx.
      destruct (Hd x Hx (fun h => h)) as [H1 H2]. rewrite Rmin_left by exact H2. exact H1.
    + rewrite Rmin_left, Rmax_right by lra. exact Hc.
    + assert (Rmin (dφ c) 0 <= 0) by apply Rmin_r.
      assert (0 <= (0 - Rmin (dφ c) 0) * (b - a)) by (apply Rmult_le_pos; lra). lra.
  - destruct (Rlt_dec a e) as [H1|H1]; [destruct (Rlt_dec e b) as [H2|H2]|].
    + assert (φ e <= φ a).
      { apply IH; [lra|intros t Ht; apply Hc; lra|].
        intros t Ht Hn. apply Hd; [lra|]. intros [He|He]; [subst; lra|contradiction]. }
      assert (φ b <= φ e).
      { apply IH; [lra|intros t Ht; apply Hc; lra|].
        intros t Ht Hn. apply Hd; [lra|]. intros [He|He]; [subst; lra|contradiction]. }
      lra.
    + apply IH; [lra|exact Hc|]. intros t Ht Hn. apply Hd; [exact Ht|].
      intros [He|He]; [subst; lra|contradiction].
    + apply IH; [lra|exact Hc|]. intros t Ht Hn. apply Hd; [exact Ht|].
      intros [He|He]; [subst; lra|contradiction].
Qed.

(** ** The differential inclusion over [R] *)

(** Vectors of [R^N] are functions [nat -> R] read at [0 … N − 1]. *)
Definition dotR (N : nat) (a b : nat -> R) : R := sumN N (fun i => a i * b i).

(** [K^N] ([df:KN]). *)
Definition InKR (N : nat) (r : R) (x : nat -> R) : Prop :=
  forall i, (S i < N)%nat -> 2 * r <= x (S i) - x i.

(** [v ∈ N_x K^N]: [⟨v, c − x⟩ ≤ 0] for every [c ∈ K^N]. *)
Definition InNormalConeR (N : nat) (r : R) (x v : nat -> R) : Prop :=
  forall c, InKR N r c -> dotR N v (fun i => c i - x i) <= 0.

(** A solution of [eq:micro-f0-lagr] on [[0, T]]:
    [ẋ(t) ∈ u⁰ − ∂I_{K^N}(x(t))], [x(0) = x⁰], in the class of continuous
    paths in [K^N] differentiable at every [t ∈ (0, T)] outside a finite set
    [E] (every piecewise-C¹ path with finitely many pieces is one), with
    [u⁰ − ẋ(t) ∈ N_{x(t)} K^N] there. Continuity is asked of [x] as a
    function on [R] at each [t ∈ [0, T]]; at [0] and [T] this holds for the
    extension of a path on [[0, T]] by constants. *)
Definition SolutionR (N : nat) (r T : R) (x0 u0 : nat -> R) (x : R -> nat -> R) : Prop :=
  (forall i, (i < N)%nat -> x 0 i = x0 i) /\
  (forall t, 0 <= t <= T -> InKR N r (x t)) /\
  (forall i, (i < N)%nat -> forall t, 0 <= t <= T -> continuity_pt (fun s => x s i) t) /\
  exists (E : list R) (v : R -> nat -> R),
    forall t, 0 < t < T -> ~ In t E ->
      (forall i, (i < N)%nat -> is_derive (fun s => x s i) t (v t i)) /\
      InNormalConeR N r (x t) (fun i => u0 i - v t i).

(** The step both uniqueness theorems share: at a time where two paths in
    [K^N] are differentiable with [u⁰ − ẋ ∈ N_x K^N] and [u⁰ − ẏ ∈ N_y K^N],
    [‖x − y‖²] has the derivative [2⟨ẋ − ẏ, x − y⟩], and it is [≤ 0]: the
    normal cone is monotone ([⟨u⁰ − ẋ, y − x⟩ ≤ 0] and
    [⟨u⁰ − ẏ, x − y⟩ ≤ 0] add up to [⟨ẋ − ẏ, x − y⟩ ≤ 0]). *)
Lemma sqdist_derive_nonpos (N : nat) (r : R) (u0 : nat -> R) (x y v w : R -> nat -> R) (s : R) :
  InKR N r (x s) -> InKR N r (y s) ->
  (forall i, (i < N)%nat -> is_derive (fun s => x s i) s (v s i)) ->
  InNormalConeR N r (x s) (fun i => u0 i - v s i) ->
  (forall i, (i < N)%nat -> is_derive (fun s => y s i) s (w s i)) ->
  InNormalConeR N r (y s) (fun i => u0 i - w s i) ->
  is_derive (fun s => sumN N (fun i => (x s i - y s i) * (x s i - y s i))) s
            (sumN N (fun i => 2 * (x s i - y s i) * (v s i - w s i))) /\
  sumN N (fun i => 2 * (x s i - y s i) * (v s i - w s i)) <= 0.
Proof.
  intros HxK HyK Dx Nx Dy Ny. split.
  - apply (is_derive_sumN N (fun i s => (x s i - y s i) * (x s i - y s i))
             (fun i s => 2 * (x s i - y s i) * (v s i - w s i))).
    intros i Hi. apply (is_derive_sqdiff (fun s => x s i) (fun s => y s i)); auto.
  - pose proof (Nx (y s) HyK) as A. pose proof (Ny (x s) HxK) as B.
    unfold dotR in A, B.
    assert (E : sumN N (fun i => 2 * (x s i - y s i) * (v s i - w s i)) =
                2 * (sumN N (fun i => (u0 i - v s i) * (y s i - x s i)) +
                     sumN N (fun i => (u0 i - w s i) * (x s i - y s i)))).
    { rewrite <- sumN_plus, <- sumN_scal. apply sumN_ext. intros i _. ring. }
    rewrite E. lra.
Qed.

(** Paper, [prop:proj-micro]: "there exists a unique solution x to
    (eq:micro-f0-lagr)" — the uniqueness, by the monotonicity argument
    [d/dt ½‖x − y‖² = ⟨ẋ − ẏ, x − y⟩ ≤ 0]: two solutions of the class
    [SolutionR] on [[0, T]] with the same data are equal on [[0, T]], for
    every [N], [r], [x⁰], [u⁰]. Ledger claim: [prop:proj-micro]. *)
Theorem solution_unique (N : nat) (r T : R) (x0 u0 : nat -> R) (x y : R -> nat -> R) :
  SolutionR N r T x0 u0 x -> SolutionR N r T x0 u0 y ->
  forall t, 0 <= t <= T -> forall i, (i < N)%nat -> x t i = y t i.
Proof.
  intros (Hx0 & HxK & Hxc & Ex & v & Hxd) (Hy0 & HyK & Hyc & Ey & w & Hyd) t Ht.
  set (φ := fun s => sumN N (fun i => (x s i - y s i) * (x s i - y s i))).
  set (dφ := fun s => sumN N (fun i => 2 * (x s i - y s i) * (v s i - w s i))).
  assert (Hφ0 : φ 0 = 0).
  { unfold φ. rewrite (sumN_ext N _ (fun _ => 0)).
    - clear. induction N; simpl; [reflexivity|rewrite IHN; ring].
    - intros i Hi. rewrite Hx0, Hy0 by exact Hi. ring. }
  assert (Hle : φ t <= φ 0).
  { apply (nonincreasing_off_finite φ dφ (Ex ++ Ey) 0 t); [lra| |].
    - intros s Hs. unfold φ.
      apply (continuity_sumN N (fun i s => (x s i - y s i) * (x s i - y s i))).
      intros i Hi.
      apply (continuity_pt_mult (fun s => x s i - y s i) (fun s => x s i - y s i));
        apply (continuity_pt_minus (fun s => x s i) (fun s => y s i));
        [apply Hxc|apply Hyc|apply Hxc|apply Hyc]; (assumption || lra).
    - intros s Hs Hn.
      assert (Hnx : ~ In s Ex) by (intro H; apply Hn, in_or_app; left; exact H).
      assert (Hny : ~ In s Ey) by (intro H; apply Hn, in_or_app; right; exact H).
      destruct (Hxd s ltac:(lra) Hnx) as [Dx Nx].
      destruct (Hyd s ltac:(lra) Hny) as [Dy Ny].
      exact (sqdist_derive_nonpos N r u0 x y v w s
               (HxK s ltac:(lra)) (HyK s ltac:(lra)) Dx Nx Dy Ny). }
  assert (Hz : forall i, (i < N)%nat -> (x t i - y t i) * (x t i - y t i) = 0).
  { apply sumN_zero; [intros i _; apply Rle_0_sqr|]. fold (φ t). lra. }
  intros i Hi. specialize (Hz i Hi). apply Rmult_integral in Hz. destruct Hz; lra.
Qed.
