(** * Section 3 at fixed [N]: the bound on the pressure
      ([prop:pressure-bound]), through [Λ̃_N(T)] and the velocity bound.

    [P̃_N = ∂_t Λ̃_N] is a non-negative measure in [t]: every [λ_i] is
    non-decreasing ([Pressure.multiplier_nondecreasing]) and piecewise
    constant. Its pairing with a function [φ ≥ 0] of [t] over [[0, T]] is
    the limit of the Riemann–Stieltjes sums [Σ_j φ(τ_j) (M(s_{j+1}) − M(s_j))]
    of [M(s) = ∫_0^1 Λ̃_N(s,w) dw] over partitions [0 ≤ s_0 ≤ … ≤ s_m ≤ T]
    (equal to it once every collision instant is a partition point and
    the tag of the interval ending at it is that instant). We bound every
    such sum, for every partition and every tags, by [sup φ · 2 sup|u⁰|]:
    the bound holds for the pairing with any [φ ≥ 0], no regularity used.
    The paper's route through the exclusion relation is not used (it is
    false as printed: ledger [prop:pressure-bound#exclusion]). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List Qabs.
From Sticky Require Import Prelude Kkt Dynamics Multipliers Pressure S3Linf S3Positions.
Import ListNotations.
Open Scope Q_scope.

(** [∫_0^1 Ṽ_N(w) dw = Σ_{i=1}^N (v_{i−1} + v_i) / (2N)] (exact: [Ṽ_N] is
    affine on each cell of length [1/N]). *)
Definition integral_affine (v : seqQ) (N : nat) : Q :=
  qsum (map (fun i => (v (i - 1)%nat + v i) / (2 * qn N)) (seq 1 N)).

(** The times [s_0 ≤ s_1 ≤ … ≤ s_m]. *)
Fixpoint Ascending (ts : list Q) : Prop :=
  match ts with
  | a :: ((b :: _) as rest) => a <= b /\ Ascending rest
  | _ => True
  end.

(** The Riemann–Stieltjes sum [Σ_j φ_j (F(s_{j+1}) − F(s_j))], the tag
    [φ_j] of the [j]-th interval (from [j0]). *)
Fixpoint rs_sum (F : Q -> Q) (phi : nat -> Q) (j : nat) (ts : list Q) : Q :=
  match ts with
  | a :: ((b :: _) as rest) => phi j * (F b - F a) + rs_sum F phi (S j) rest
  | _ => 0
  end.

Lemma qsum_map_le (f g : nat -> Q) (s n : nat) :
  (forall i, (s <= i < s + n)%nat -> f i <= g i) ->
  qsum (map f (seq s n)) <= qsum (map g (seq s n)).
Proof.
  revert s. induction n as [|n IH]; intros s H; simpl; [apply Qle_refl|].
  pose proof (H s ltac:(lia)). pose proof (IH (S s) ltac:(intros; apply H; lia)). lra.
Qed.

Lemma qsum_map_const (c : Q) (s n : nat) : qsum (map (fun _ => c) (seq s n)) == qn n * c.
Proof.
  revert s. induction n as [|n IH]; intro s; simpl; [rewrite qn_0; ring|].
  rewrite IH, qn_S. ring.
Qed.

Lemma last_default (q : Q) (ts : list Q) (a b : Q) : last (q :: ts) a = last (q :: ts) b.
Proof.
  revert q. induction ts as [|c ts IH]; intro q; [reflexivity|].
  change (last (c :: ts) a = last (c :: ts) b). apply IH.
Qed.

(** For a non-decreasing [F] on [[0, T]] and tags in [[0, Φ]], every sum
    over ascending times of [[0, T]] lies in [[0, Φ (F(s_m) − F(s_0))]]. *)
Lemma rs_sum_bound (F : Q -> Q) (phi : nat -> Q) (T Φ : Q) (ts : list Q) (a : Q) :
  (forall s t, 0 <= s -> s <= t -> t <= T -> F s <= F t) ->
  (forall j, 0 <= phi j /\ phi j <= Φ) ->
  Ascending (a :: ts) -> Forall (fun s => 0 <= s /\ s <= T) (a :: ts) ->
  forall j, 0 <= rs_sum F phi j (a :: ts) /\
            rs_sum F phi j (a :: ts) <= Φ * (F (last ts a) - F a).
Proof.
  intros HF Hphi. revert a. induction ts as [|b ts IH]; intros a Hasc Hin j.
  - simpl. split; lra.
  - destruct Hasc as [Hab Hasc]. inversion Hin as [|? ? Ha Hin']; subst.
    inversion Hin' as [|? ? Hb _]; subst.
    destruct (IH b Hasc Hin' (S j)) as [A B].
    assert (Hl : last (b :: ts) a = last ts b) by (destruct ts as [|q ts]; [reflexivity|exact (last_default q ts a b)]).
    change (rs_sum F phi j (a :: b :: ts)) with (phi j * (F b - F a) + rs_sum F phi (S j) (b :: ts)).
    rewrite Hl. destruct (Hphi j) as [P1 P2].
    assert (D : 0 <= F b - F a) by (pose proof (HF a b ltac:(lra) Hab ltac:(lra)); lra).
    assert (P3 : 0 <= phi j * (F b - F a)) by (apply Qmult_le_0_compat; lra).
    assert (P4 : phi j * (F b - F a) <= Φ * (F b - F a)) by (apply Qmult_le_compat_r; lra).
    setoid_replace (Φ * (F (last ts b) - F a))
      with (Φ * (F b - F a) + Φ * (F (last ts b) - F b)) by ring.
    split; lra.
Qed.

Lemma last_in (ts : list Q) (a : Q) : In (last ts a) (a :: ts).
Proof.
  revert a. induction ts as [|b ts IH]; intro a; [left; reflexivity|].
  right. destruct ts as [|c ts]; [left; reflexivity|].
  change (In (last (c :: ts) a) (b :: c :: ts)). rewrite (last_default c ts a b). apply IH.
Qed.

(** [M(s) = ∫_0^1 Λ̃_N(s,w) dw] is non-decreasing and [0 ≤ M(s) ≤ 2 sup|u⁰|]. *)
Lemma integral_lambda_facts (x0 u0 : list Q) (r M : Q) :
  InK r x0 -> length u0 = length x0 -> SupBound M u0 -> (1 <= length x0)%nat ->
  let F := fun s => integral_affine (lambdas x0 u0 r s) (length x0) in
  (forall s t, 0 <= s -> s <= t -> F s <= F t) /\
  (forall s, 0 <= s -> 0 <= F s /\ F s <= 2 * M).
Proof.
  intros HK L HB HN F.
  pose proof (qn_pos (length x0) HN) as HNq.
  assert (Hterm : forall a b, 0 <= a + b -> 0 <= (a + b) / (2 * qn (length x0)))
    by (intros a b H; apply Qle_shift_div_l; lra).
  split.
  - intros s t Hs Hst. unfold F, integral_affine. apply qsum_map_le. intros i Hi.
    unfold lambdas.
    pose proof (multiplier_nondecreasing x0 u0 r s t (i - 1) Hs Hst HK L ltac:(lia)).
    pose proof (multiplier_nondecreasing x0 u0 r s t i Hs Hst HK L ltac:(lia)).
    apply Qmult_le_compat_r; [lra|]. apply Qlt_le_weak, Qinv_lt_0_compat. lra.
  - intros s Hs.
    assert (Hb : forall i, (1 <= i < 1 + length x0)%nat ->
               0 <= (lambdas x0 u0 r s (i - 1)%nat + lambdas x0 u0 r s i) / (2 * qn (length x0)) /\
               (lambdas x0 u0 r s (i - 1)%nat + lambdas x0 u0 r s i) / (2 * qn (length x0))
                 <= 2 * M / qn (length x0)).
    { intros i Hi.
      destruct (multiplier_sup_bound x0 u0 r s M (i - 1) Hs HK L HB HN ltac:(lia)) as [A1 A2].
      destruct (multiplier_sup_bound x0 u0 r s M i Hs HK L HB HN ltac:(lia)) as [B1 B2].
      split; [apply Hterm; lra|].
      apply Qle_shift_div_r; [lra|].
      setoid_replace (2 * M / qn (length x0) * (2 * qn (length x0))) with (2 * (2 * M))
        by (field; lra). lra. }
    unfold F, integral_affine. split.
    + apply (Qle_trans _ (qsum (map (fun _ => 0) (seq 1 (length x0))))).
      * rewrite qsum_map_const. lra.
      * apply qsum_map_le. intros i Hi. apply (Hb i Hi).
    + apply (Qle_trans _ (qsum (map (fun _ => 2 * M / qn (length x0)) (seq 1 (length x0))))).
      * apply qsum_map_le. intros i Hi. apply (Hb i Hi).
      * rewrite qsum_map_const. setoid_replace (qn (length x0) * (2 * M / qn (length x0)))
          with (2 * M) by (field; lra). lra.
Qed.

(** The same bound for any [F] non-decreasing with values in [[0, B]]. *)
Lemma rs_sum_total (F : Q -> Q) (phi : nat -> Q) (T Φ B : Q) (ts : list Q) :
  (forall s t, 0 <= s -> s <= t -> F s <= F t) ->
  (forall s, 0 <= s -> 0 <= F s /\ F s <= B) ->
  0 <= Φ -> (forall j, 0 <= phi j /\ phi j <= Φ) ->
  Ascending ts -> Forall (fun s => 0 <= s /\ s <= T) ts ->
  0 <= rs_sum F phi 0 ts /\ rs_sum F phi 0 ts <= B * Φ.
Proof.
  intros Hmono Hbd HΦ Hphi Hasc Hin.
  destruct (Hbd 0 (Qle_refl 0)) as [B0 B1].
  destruct ts as [|a ts].
  - split; [apply Qle_refl|]. apply Qmult_le_0_compat; lra.
  - destruct (rs_sum_bound F phi T Φ ts a ltac:(intros; apply Hmono; lra) Hphi Hasc Hin 0) as [A C].
    rewrite Forall_forall in Hin.
    destruct (Hin a (or_introl eq_refl)) as [Ha _].
    destruct (Hin (last ts a) (last_in ts a)) as [Hl _].
    destruct (Hbd a Ha) as [Fa _]. destruct (Hbd (last ts a) Hl) as [_ Fl].
    split; [exact A|]. apply (Qle_trans _ _ _ C).
    rewrite (Qmult_comm Φ). apply Qmult_le_compat_r; lra.
Qed.

(** Paper, [prop:pressure-bound]: "‖P̃_N‖_{M(0,T;L¹(0,1))} ≤ C" with [C]
    independent of [N]; here [C = 2 sup_i |u⁰_i| ≤ 2C'_0]: for every
    [N ≥ 1], [x⁰ ∈ K^N], any [u⁰] with [sup_i |u⁰_i| ≤ M], every partition
    [0 ≤ s_0 ≤ … ≤ s_m ≤ T] and every tags [0 ≤ φ_j ≤ Φ], the
    Riemann–Stieltjes sum of [∫_0^T φ d(∫_0^1 P̃_N dw)] lies in
    [[0, 2MΦ]] (non-negative: [P̃_N ≥ 0]). Ledger claim: [prop:pressure-bound]. *)
Theorem pressure_bound (x0 u0 : list Q) (r T M Φ : Q) (phi : nat -> Q) (ts : list Q) :
  InK r x0 -> length u0 = length x0 -> SupBound M u0 -> (1 <= length x0)%nat ->
  0 <= Φ -> (forall j, 0 <= phi j /\ phi j <= Φ) ->
  Ascending ts -> Forall (fun s => 0 <= s /\ s <= T) ts ->
  let F := fun s => integral_affine (lambdas x0 u0 r s) (length x0) in
  0 <= rs_sum F phi 0 ts /\ rs_sum F phi 0 ts <= 2 * M * Φ.
Proof.
  intros HK L HB HN HΦ Hphi Hasc Hin F.
  destruct (integral_lambda_facts x0 u0 r M HK L HB HN) as [Hmono Hbd]. 
  assert (Hm : forall s t, 0 <= s -> s <= t -> F s <= F t) by exact Hmono.
  assert (Hb : forall s, 0 <= s -> 0 <= F s /\ F s <= 2 * M) by exact Hbd.
  clearbody F.
  exact (rs_sum_total F phi T Φ (2 * M) ts Hm Hb HΦ Hphi Hasc Hin).
Qed.
