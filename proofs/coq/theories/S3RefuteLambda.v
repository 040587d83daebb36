(** * [eq:sup-micro-u-L#N-lambda] refuted for every bound: the Riemann
      compression sampled at [N = 2m].

    Data: the congested block [x⁰_i = i/N] ([2r = 1/N], [S3Refute.block])
    with [u⁰ = (1, …, 1, −1, …, −1)] ([m] of each): [sup|u⁰| = 1],
    [‖x⁰‖ ≤ 1], [‖u⁰‖ = 1], [x⁰_N − x⁰_0 + sup|u⁰| = 2 + δ], uniformly in [N].
    The block never moves ([x(t) = x⁰]: [x⁰] satisfies the variational
    inequality of [P_K] at [x⁰ + t u⁰]), so [u(t) = 0] for [t > 0] and
    [λ_m(t) = 1/2]: [N λ_m(t) = m]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List Qabs Qround.
From Sticky Require Import Prelude Kkt Projection RightDerivative Dynamics Multipliers
  DynamicsIsProjK OracleIsDynamics S3Linf S3Positions S3Refute.
Import ListNotations.
Open Scope Q_scope.

Lemma dot_vsub_swap (a x p : list Q) :
  length x = length p -> dot a (vsub x p) == - dot a (vsub p x).
Proof.
  revert x p. induction a as [|c a IH]; intros [|y x] [|q p] L; simpl in *; try ring; try lia.
  rewrite IH by lia. ring.
Qed.

Lemma sqnorm_vsub_swap (x p : list Q) : length x = length p -> sqnorm (vsub x p) == sqnorm (vsub p x).
Proof.
  revert p. induction x as [|y x IH]; intros [|q p] L; simpl in *; try reflexivity; try lia.
  rewrite IH by lia. ring.
Qed.

(** A point of [K^N] satisfying the variational inequality at [z] is [P_K(z)]. *)
Lemma proj_fixed_variational (r : Q) (x z : list Q) :
  InK r x -> length z = length x ->
  (forall y, InK r y -> length y = length x -> dot (vsub z x) (vsub y x) <= 0) ->
  qeq_list (proj_K r z) x.
Proof.
  intros HK L HV.
  set (p := proj_K r z).
  assert (Lp : length p = length x) by (unfold p; rewrite proj_K_length; exact L).
  pose proof (proj_K_minimiser r z x HK (eq_sym L)) as Hm. fold p in Hm.
  pose proof (pythagoras z x p ltac:(lia) ltac:(lia)) as Py.
  pose proof (HV p (proj_K_in_K r z) Lp) as V.
  rewrite (dot_vsub_swap _ x p ltac:(lia)) in Py.
  rewrite (sqnorm_vsub_swap x p ltac:(lia)) in Py.
  pose proof (sqnorm_nonneg (vsub p x)).
  apply sqnorm_zero_qeq; [exact Lp|lra].
Qed.

(** ** The compression *)

Definition compression (m : nat) : list Q := repeat 1 m ++ repeat (-1) m.

Lemma compression_length (m : nat) : length (compression m) = (m + m)%nat.
Proof. unfold compression. rewrite app_length, !repeat_length. reflexivity. Qed.

Lemma dot_free_flight (x0 u0 d : list Q) (t : Q) :
  length u0 = length x0 -> dot (vsub (free_flight x0 u0 t) x0) d == t * dot u0 d.
Proof.
  unfold free_flight. revert u0 d.
  induction x0 as [|a x0 IH]; intros [|b u0] [|c d] L; simpl in *; try ring; try lia.
  rewrite IH by lia. ring.
Qed.

Lemma dot_app (a1 a2 d : list Q) :
  dot (a1 ++ a2) d == dot a1 (firstn (length a1) d) + dot a2 (skipn (length a1) d).
Proof.
  revert d. induction a1 as [|c a1 IH]; intros d; simpl; [destruct a2, d; simpl; ring|].
  destruct d as [|e d]; simpl; [destruct a1, a2; simpl; ring|]. rewrite IH. ring.
Qed.

Lemma dot_repeat (c : Q) (n : nat) (d : list Q) :
  (n <= length d)%nat -> dot (repeat c n) d == c * qsum (firstn n d).
Proof.
  revert d. induction n as [|n IH]; intros [|e d] H; simpl in *; try ring; try lia.
  rewrite IH by lia. ring.
Qed.

Lemma qsum_le_const (D : Q) (a : list Q) :
  Forall (fun v => v <= D) a -> qsum a <= qn (length a) * D.
Proof.
  induction 1 as [|v a Hv _ IH]; simpl; [rewrite qn_0; lra|].
  rewrite qn_S. setoid_replace ((qn (length a) + 1) * D) with (qn (length a) * D + D) by ring. lra.
Qed.

Lemma qsum_ge_const (D : Q) (a : list Q) :
  Forall (fun v => D <= v) a -> qn (length a) * D <= qsum a.
Proof.
  induction 1 as [|v a Hv _ IH]; simpl; [rewrite qn_0; lra|].
  rewrite qn_S. setoid_replace ((qn (length a) + 1) * D) with (qn (length a) * D + D) by ring. lra.
Qed.

Lemma nth_firstn_lt (n k : nat) (d : list Q) : (k < n)%nat -> nth k (firstn n d) 0 = nth k d 0.
Proof.
  revert k d. induction n as [|n IH]; intros k [|e d] H; simpl; try lia; try (destruct k; reflexivity).
  destruct k; [reflexivity|]. apply IH. lia.
Qed.

Lemma nth_skipn_add (n k : nat) (d : list Q) : nth k (skipn n d) 0 = nth (n + k) d 0.
Proof.
  revert d. induction n as [|n IH]; intros [|e d]; simpl; try reflexivity.
  - destruct k; reflexivity.
  - apply IH.
Qed.

(** [⟨u⁰, d⟩ ≤ 0] for every non-decreasing [d]: the left half is below
    [d_m], the right half above. *)
Lemma compression_dot_mono (m : nat) (d : list Q) :
  length d = (m + m)%nat ->
  (forall k, (S k < length d)%nat -> nth k d 0 <= nth (S k) d 0) ->
  dot (compression m) d <= 0.
Proof.
  intros L Hm. unfold compression. rewrite dot_app, repeat_length.
  pose proof (dot_repeat 1 m (firstn m d) ltac:(rewrite firstn_length_le; lia)) as R1.
  rewrite firstn_firstn, Nat.min_id in R1.
  pose proof (dot_repeat (-1) m (skipn m d) ltac:(rewrite skipn_length; lia)) as R2.
  apply (Qle_trans _ (1 * qsum (firstn m d) + (-1) * qsum (firstn m (skipn m d))));
    [rewrite R1, R2; apply Qle_refl|].
  set (v := fun k => nth k d 0).
  assert (Mono : forall a b, (a <= b <= m + m - 1)%nat -> v a <= v b).
  { apply mono_le. intros j Hj. unfold v. replace j with (S (j - 1)) at 2 by lia. apply Hm. lia. }
  destruct m as [|m]; [simpl; lra|].
  set (D := v (S m)).
  assert (A : Forall (fun x => x <= D) (firstn (S m) d)).
  { apply Forall_forall. intros x Hx. apply (In_nth _ _ 0) in Hx. destruct Hx as (k & Hk & <-).
    rewrite firstn_length_le in Hk by lia. rewrite nth_firstn_lt by lia. apply Mono. lia. }
  assert (B : Forall (fun x => D <= x) (firstn (S m) (skipn (S m) d))).
  { apply Forall_forall. intros x Hx. apply (In_nth _ _ 0) in Hx. destruct Hx as (k & Hk & <-).
    rewrite firstn_length_le in Hk by (rewrite skipn_length; lia).
    rewrite nth_firstn_lt, nth_skipn_add by lia. apply Mono. lia. }
  apply qsum_le_const in A. apply qsum_ge_const in B.
  rewrite firstn_length_le in A by lia.
  rewrite firstn_length_le in B by (rewrite skipn_length; lia).
  lra.
Qed.

Lemma vsub_len (a b : list Q) : length a = length b -> length (vsub a b) = length a.
Proof. revert b. induction a as [|x a IH]; intros [|y b] L; simpl in *; try lia. f_equal. apply IH. lia. Qed.

Lemma qeq_list_trans (a b c : list Q) : qeq_list a b -> qeq_list b c -> qeq_list a c.
Proof.
  intro H. revert c. induction H as [|x y a b Hxy _ IH]; intros c H'; inversion H'; subst;
    constructor; [rewrite Hxy; assumption|apply IH; assumption].
Qed.

(** [y − x⁰] is non-decreasing for every [y ∈ K^N] ([x⁰] is congested). *)
Lemma block_gap_mono (N : nat) (y : list Q) :
  (1 <= N)%nat -> InK (block_radius N) y -> length y = N ->
  forall k, (S k < length (vsub y (block N)))%nat ->
  nth k (vsub y (block N)) 0 <= nth (S k) (vsub y (block N)) 0.
Proof.
  intros HN HK L k Hk.
  assert (Lb : length y = length (block N)) by (rewrite block_length; exact L).
  rewrite vsub_len in Hk by exact Lb.
  rewrite !nth_vsub by lia. rewrite !block_nth by lia.
  specialize (HK k Hk). unfold block_radius in HK.
  pose proof (qn_pos N ltac:(lia)).
  assert (E : qn (S (S k)) / qn N - qn (S k) / qn N == 2 * (1 / (2 * qn N)))
    by (rewrite (qn_S (S k)); field; lra).
  lra.
Qed.

(** The compressed block never moves: [x(t) = x⁰] for every [t ≥ 0]. *)
Theorem compression_still (m : nat) (t : Q) :
  (1 <= m)%nat -> 0 <= t ->
  qeq_list (positions (dynamics (block (m + m)) (compression m) (block_radius (m + m)) t))
           (block (m + m)).
Proof.
  intros Hm Ht. set (N := (m + m)%nat).
  assert (L : length (compression m) = length (block N))
    by (rewrite compression_length, block_length; reflexivity).
  pose proof (block_inK N ltac:(unfold N; lia)) as HK.
  apply (qeq_list_trans _ _ _ (dynamics_is_proj_K _ _ _ t Ht HK L)).
  apply proj_fixed_variational; [exact HK|apply free_flight_length, L|].
  intros y Hy Ly. rewrite dot_free_flight by exact L.
  assert (D : dot (compression m) (vsub y (block N)) <= 0).
  { apply compression_dot_mono.
    - rewrite (vsub_len _ _ Ly), Ly, block_length; reflexivity.
    - apply block_gap_mono; [unfold N; lia|exact Hy|rewrite Ly, block_length; reflexivity]. }
  clearbody N.
  setoid_replace 0 with (t * 0) by ring. 
  rewrite !(Qmult_comm t). apply Qmult_le_compat_r; assumption.
Qed.

(** Hence [u(t) = 0] for [t > 0] (the dynamics moves rigidly just after [t]). *)
Lemma compression_velocities (m : nat) (t : Q) (k : nat) :
  (1 <= m)%nat -> 0 < t -> (k < m + m)%nat ->
  nth k (velocities (dynamics (block (m + m)) (compression m) (block_radius (m + m)) t)) 0 == 0.
Proof.
  intros Hm Ht Hk. set (N := (m + m)%nat) in *.
  assert (L : length (compression m) = length (block N))
    by (rewrite compression_length, block_length; reflexivity).
  pose proof (block_inK N ltac:(unfold N; lia)) as HK.
  destruct (dynamics_rigid_after _ _ _ t Ht HK L) as (d & Hd & H).
  specialize (H d Hd (Qle_refl d)).
  set (x := positions (dynamics (block N) (compression m) (block_radius N) t)) in *.
  set (u := velocities (dynamics (block N) (compression m) (block_radius N) t)) in *.
  pose proof (positions_length _ _ _ t ltac:(lra) HK L) as Lx. fold x in Lx.
  pose proof (velocities_length _ _ _ t ltac:(lra) HK L) as Lu. fold u in Lu.
  rewrite block_length in Lx, Lu.
  pose proof (qeq_list_nth _ _ H k) as E. rewrite nth_affine in E by lia.
  pose proof (qeq_list_nth _ _ (compression_still m (t + d) Hm ltac:(lra)) k) as A.
  pose proof (qeq_list_nth _ _ (compression_still m t Hm ltac:(lra)) k) as B. fold N x in B.
  assert (Z : d * nth k u 0 == 0) by (fold N in A; lra).
  apply Qmult_integral in Z. destruct Z as [Z|Z]; [lra|exact Z].
Qed.

Lemma psum_zeros (u : list Q) (k : nat) :
  (forall j, (j < length u)%nat -> nth j u 0 == 0) -> psum k u == 0.
Proof.
  revert k. induction u as [|a u IH]; intros [|k] H; try reflexivity.
  rewrite psum_cons. rewrite (H 0%nat ltac:(simpl; lia)), IH; [ring|].
  intros j Hj. apply (H (S j)). simpl. lia.
Qed.

(** [λ_m(t) = 1/2] for every [t > 0]. *)
Lemma compression_lambda (m : nat) (t : Q) :
  (1 <= m)%nat -> 0 < t ->
  multiplier (block (m + m)) (compression m) (block_radius (m + m)) t m == 1 / 2.
Proof.
  intros Hm Ht. unfold multiplier. rewrite block_length.
  assert (U : psum m (velocities (dynamics (block (m + m)) (compression m) (block_radius (m + m)) t)) == 0).
  { apply psum_zeros. intros j Hj.
    assert (L : length (compression m) = length (block (m + m)))
      by (rewrite compression_length, block_length; reflexivity).
    pose proof (velocities_length _ _ _ t ltac:(lra) (block_inK (m + m) ltac:(lia)) L) as Lu.
    rewrite block_length in Lu. apply compression_velocities; [lia|exact Ht|lia]. }
  assert (P : psum m (compression m) == qn m).
  { unfold compression. rewrite psum_app_le by (rewrite repeat_length; lia).
    rewrite psum_repeat by lia. ring. }
  rewrite U, P, qn_add. pose proof (qn_pos m ltac:(lia)). field. lra.
Qed.

(** Paper, [eq:sup-micro-u-L]: "sup_{t ∈ [0,T]} … sup_i N|λ_i(t)| ≤ C'
    for some C' independent of N" under [sup_i |u⁰_i| ≤ C'_0]. Refuted
    for every bound: for every [C] and every [T > 0] there is [N = 2m]
    such that the compression sampled at [N] ([x⁰ ∈ K^N] congested,
    [sup_i |u⁰_i| ≤ 1]) has [N λ_m(T) = m > C].
    Ledger claim: [eq:sup-micro-u-L#N-lambda]. *)
Theorem sup_micro_N_lambda_false (C T : Q) :
  0 < T ->
  exists m, (1 <= m)%nat /\
    InK (block_radius (m + m)) (block (m + m)) /\ SupBound 1 (compression m) /\
    qn (m + m) * multiplier (block (m + m)) (compression m) (block_radius (m + m)) T m > C.
Proof.
  intros HT.
  exists (S (Z.to_nat (Qceiling C))).
  set (m := S (Z.to_nat (Qceiling C))).
  split; [unfold m; lia|]. split; [apply block_inK; unfold m; lia|]. split.
  - unfold compression. apply Forall_app. split; apply Forall_forall; intros a Ha;
      apply repeat_spec in Ha; subst; unfold Qabs, Qle; simpl; lia.
  - rewrite compression_lambda by (unfold m; lia || exact HT).
    rewrite qn_add.
    assert (Hc : C < qn m).
    { apply (Qle_lt_trans _ (inject_Z (Qceiling C))); [apply Qle_ceiling|].
      unfold qn, m. rewrite <- Zlt_Qlt. lia. }
    apply (Qlt_le_trans _ (qn m) _ Hc). apply Qle_lteq. right. field.
Qed.
