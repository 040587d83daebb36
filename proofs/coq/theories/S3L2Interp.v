(** * Section 3 at fixed [N]: the other five [L²] norms of [prop:L2-micro].

    [S3L2.L2_micro_XN_UN] bounds [‖X_N‖] and [‖∂_t X_N‖]; here are
    [‖X̃_N‖], [‖∂_t X̃_N‖], [‖Λ_N‖], [‖Λ̃_N‖] and [‖∂_w Λ̃_N‖] in
    [L²(0,1)] at every rational [t ∈ [0, T]], written as finite sums
    ([S3Linf]'s interpolations): on the cell [i] (length [1/N]) a piecewise
    constant [V_N = v_i] has [∫ V_N² = v_i²/N], a piecewise affine [Ṽ_N]
    from [v_{i−1}] to [v_i] has [∫ Ṽ_N² = (v_{i−1}² + v_{i−1}v_i + v_i²)/(3N)]
    exactly. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Dynamics Multipliers VelocityBound VelocityProjection
  S3Linf S3Positions S3Pressure S3L2 ProjMicroSolves.
Import ListNotations.
Open Scope Q_scope.

(** [‖V_N‖²_{L²(0,1)} = (1/N) Σ_{i=1}^N v_i²] for the piecewise constant
    interpolation of [v_1, …, v_N]. *)
Definition l2_const (v : seqQ) (N : nat) : Q :=
  qsum (map (fun i => v i * v i) (seq 1 N)) / qn N.

(** [‖Ṽ_N‖²_{L²(0,1)} = (1/N) Σ_{i=1}^N (v_{i−1}² + v_{i−1}v_i + v_i²)/3]
    for the piecewise affine interpolation of [v_0, …, v_N]. *)
Definition l2_affine (v : seqQ) (N : nat) : Q :=
  qsum (map (fun i => (v (i - 1)%nat * v (i - 1)%nat + v (i - 1)%nat * v i + v i * v i) / 3)
            (seq 1 N)) / qn N.

(** ** Sums over the cells *)

Lemma qsum_seq_last (f : nat -> Q) (n : nat) :
  qsum (map f (seq 1 (S n))) == qsum (map f (seq 1 n)) + f (S n).
Proof. rewrite seq_S, map_app, qsum_app. simpl. replace (1 + n)%nat with (S n) by lia. ring. Qed.

(** [Σ_{i=1}^N (g_{i−1} + g_i)/2 = g_0/2 + Σ_{i=1}^N g_i − g_N/2]. *)
Lemma qsum_pairs (g : nat -> Q) (n : nat) :
  qsum (map (fun i => (g (i - 1)%nat + g i) / 2) (seq 1 n)) ==
  g 0%nat / 2 + qsum (map g (seq 1 n)) - g n / 2.
Proof.
  induction n as [|n IH]; [simpl; field|].
  rewrite !qsum_seq_last, IH. replace (S n - 1)%nat with n by lia. field.
Qed.

(** The entries of a list, read by the 1-based index. *)
Lemma qsum_seq_sqnorm (d : list Q) (f : nat -> Q) :
  (forall i, (1 <= i <= length d)%nat -> f i == nth (i - 1) d 0 * nth (i - 1) d 0) ->
  qsum (map f (seq 1 (length d))) == sqnorm d.
Proof.
  revert f. induction d as [|a d IH]; intros f H; [reflexivity|].
  simpl length. simpl seq. simpl map. simpl qsum. simpl sqnorm.
  rewrite <- seq_shift, map_map.
  rewrite (H 1%nat ltac:(simpl; lia)). simpl nth.
  rewrite (IH (fun i => f (S i))); [ring|].
  intros i Hi. rewrite (H (S i) ltac:(simpl; lia)).
  replace (S i - 1)%nat with (S (i - 1)) by lia. reflexivity.
Qed.

Lemma affine_sq_le (a b : Q) : (a * a + a * b + b * b) / 3 <= (a * a + b * b) / 2.
Proof.
  assert (0 <= (a - b) * (a - b)) by apply Qsq_nonneg.
  setoid_replace ((a * a + a * b + b * b) / 3) with ((a * a + a * b + b * b) * (1 # 3)) by field.
  setoid_replace ((a * a + b * b) / 2) with ((a * a + b * b) * (1 # 2)) by field.
  nra.
Qed.

(** The affine interpolation is controlled by the constant one and its
    first value: [‖Ṽ_N‖² ≤ (1/N) Σ_{i=1}^N v_i² + v_0²/(2N)]. *)
Lemma l2_affine_le (v : seqQ) (N : nat) :
  (1 <= N)%nat ->
  l2_affine v N <= qsum (map (fun i => v i * v i) (seq 1 N)) / qn N + v 0%nat * v 0%nat / (2 * qn N).
Proof.
  intro HN. pose proof (qn_pos N HN) as Hn. unfold l2_affine.
  set (g := fun i => v i * v i).
  apply (Qle_trans _ (qsum (map (fun i => (g (i - 1)%nat + g i) / 2) (seq 1 N)) / qn N)).
  - apply Qmult_le_compat_r; [|apply Qlt_le_weak, Qinv_lt_0_compat, Hn].
    apply qsum_map_le. intros i _. unfold g. apply affine_sq_le.
  - rewrite qsum_pairs. unfold g.
    set (S := qsum (map (fun i => v i * v i) (seq 1 N))).
    assert (0 <= v N * v N) by apply Qsq_nonneg.
    apply (Qle_trans _ ((v 0%nat * v 0%nat * (1 # 2) + S) / qn N)).
    + apply Qmult_le_compat_r; [|apply Qlt_le_weak, Qinv_lt_0_compat, Hn].
      setoid_replace (v 0%nat * v 0%nat / 2) with (v 0%nat * v 0%nat * (1 # 2)) by field.
      setoid_replace (v N * v N / 2) with (v N * v N * (1 # 2)) by field.
      lra.
    + apply Qle_lteq. right. field. lra.
Qed.

(** Cauchy–Schwarz: [(Σ d_i)² ≤ n Σ d_i²]. *)
Lemma qsum_sq_le (d : list Q) : qsum d * qsum d <= qn (length d) * sqnorm d.
Proof.
  induction d as [|a d IH]; simpl; [lra|]. rewrite qn_S.
  pose proof (qn_nonneg (length d)) as Hn. pose proof (sqnorm_nonneg d) as Hs.
  set (n := qn (length d)) in *. set (s := qsum d) in *. set (S := sqnorm d) in *.
  (* 2as ≤ S + n a² since (s − n a)² ≥ 0 and s² ≤ n S *)
  assert (H2 : 0 <= (s - n * a) * (s - n * a)) by apply Qsq_nonneg.
  destruct (Qlt_le_dec 0 n) as [Hp|Hz].
  - assert (H3 : 0 <= n * (S + n * (a * a) - 2 * a * s)) by nra.
    apply (Qmult_pos_le_reg n) in H3; [|exact Hp].
    nra.
  - assert (n == 0) by lra. assert (s * s <= 0) by (rewrite H in IH; lra).
    assert (s == 0) by nra. rewrite H, H1. nra.
Qed.

Lemma sqnorm_firstn (k : nat) (d : list Q) : sqnorm (firstn k d) <= sqnorm d.
Proof.
  revert k. induction d as [|a d IH]; intros [|k]; simpl; try lra.
  - pose proof (Qsq_nonneg a). pose proof (sqnorm_nonneg d). lra.
  - specialize (IH k). lra.
Qed.

(** [‖a‖² = ‖a − b‖² + 2⟨a − b, b⟩ + ‖b‖²]. *)
Lemma sqnorm_vsub_expand (a b : list Q) :
  length a = length b -> sqnorm a == sqnorm (vsub a b) + 2 * dot (vsub a b) b + sqnorm b.
Proof.
  revert b. induction a as [|x a IH]; intros [|y b] L; simpl in *; try lia; [ring|].
  specialize (IH b ltac:(lia)). rewrite IH. ring.
Qed.

(** [Σ_i (u⁰_i − u_i(t))² ≤ Σ_i (u⁰_i)²]: [u⁰ − u ⊥ u] ([velocity_step1]). *)
Lemma velocity_defect_l2 (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  sqnorm (vsub u0 (velocities (dynamics x0 u0 r t))) <= sqnorm u0.
Proof.
  intros Ht HK L. pose proof (velocities_length x0 u0 r t Ht HK L) as Lu.
  pose proof (velocity_step1 x0 u0 r t Ht HK L) as D.
  pose proof (sqnorm_vsub_expand u0 (velocities (dynamics x0 u0 r t)) ltac:(lia)) as E.
  rewrite D in E. pose proof (sqnorm_nonneg (velocities (dynamics x0 u0 r t))). lra.
Qed.

(** [λ_k(t)² ≤ ‖u⁰‖² = (1/N) Σ (u⁰_i)²] for [k = 0..N]. *)
Lemma multiplier_sq_bound (x0 u0 : list Q) (r t : Q) (k : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (1 <= length x0)%nat ->
  multiplier x0 u0 r t k * multiplier x0 u0 r t k <= wnorm2 u0.
Proof.
  intros Ht HK L HN. pose proof (qn_pos _ HN) as Hn.
  pose proof (velocities_length x0 u0 r t Ht HK L) as Lu.
  set (u := velocities (dynamics x0 u0 r t)) in *. set (d := vsub u0 u).
  assert (E : multiplier x0 u0 r t k == psum k d / qn (length x0)).
  { unfold multiplier, d. fold u. rewrite psum_vsub by lia. reflexivity. }
  rewrite E. unfold wnorm2. rewrite L.
  assert (Ld : length d = length x0) by (unfold d; rewrite vsub_length; lia).
  assert (CS : psum k d * psum k d <= qn (length x0) * sqnorm d).
  { unfold psum. eapply Qle_trans; [apply qsum_sq_le|].
    pose proof (sqnorm_nonneg (firstn k d)). pose proof (sqnorm_firstn k d).
    pose proof (qn_le (length (firstn k d)) (length x0)
                  ltac:(rewrite firstn_length; lia)) as Hl.
    pose proof (qn_nonneg (length (firstn k d))). nra. }
  pose proof (velocity_defect_l2 x0 u0 r t Ht HK L) as V. fold u d in V.
  set (n := qn (length x0)) in *. set (p := psum k d) in *.
  setoid_replace (p / n * (p / n)) with (p * p / (n * n)) by (field; lra).
  apply Qle_shift_div_r; [nra|].
  setoid_replace (sqnorm u0 / n * (n * n)) with (n * sqnorm u0) by (field; lra).
  nra.
Qed.

Lemma nth_first_sq (x : list Q) : nth 0 x 0 * nth 0 x 0 <= sqnorm x.
Proof. destruct x as [|a x]; simpl; [lra|]. pose proof (sqnorm_nonneg x). lra. Qed.

(** ** The five norms *)

(** Paper, [prop:L2-micro] ([X̃_N], [∂_t X̃_N]): for every [N ≥ 1],
    [x⁰ ∈ K^N], any [u⁰], rational [0 ≤ t ≤ T], [δ ≥ 0], with
    [‖x⁰‖², ‖u⁰‖² ≤ C₀²]: [‖X̃_N(t)‖²_{L²} ≤ 4(1 + T²)C₀² + (1 + δ)²]
    (the artificial particle [x_0 = x_1 − 1/N − δ] of [df:x0] brings the
    [δ]) and [‖∂_t X̃_N(t)‖²_{L²} ≤ (3/2) C₀²] ([u_0 = u_1]).
    Ledger claim: [prop:L2-micro]. *)
Theorem L2_micro_tXN_tUN (x0 u0 : list Q) (r t T C0 δ : Q) :
  0 <= t -> t <= T -> 0 <= δ -> InK r x0 -> length u0 = length x0 -> (1 <= length x0)%nat ->
  wnorm2 x0 <= C0 * C0 -> wnorm2 u0 <= C0 * C0 ->
  let N := length x0 in
  l2_affine (xs δ (positions (dynamics x0 u0 r t))) N <= 4 * (1 + T * T) * (C0 * C0) + (1 + δ) * (1 + δ) /\
  l2_affine (us (velocities (dynamics x0 u0 r t))) N <= (3 # 2) * (C0 * C0).
Proof.
  intros Ht HtT Hd HK L HN Hx Hu N.
  destruct (L2_micro_XN_UN x0 u0 r t T C0 Ht HtT HK L HN Hx Hu) as [BX BU].
  pose proof (positions_length x0 u0 r t Ht HK L) as Lx.
  pose proof (velocities_length x0 u0 r t Ht HK L) as Lu.
  pose proof (qn_pos _ HN) as Hn. fold N in Hn, Lx, Lu.
  set (x := positions (dynamics x0 u0 r t)) in *. set (u := velocities (dynamics x0 u0 r t)) in *.
  unfold wnorm2 in BX, BU. rewrite Lx in BX. rewrite Lu in BU.
  assert (SX : qsum (map (fun i => xs δ x i * xs δ x i) (seq 1 N)) == sqnorm x).
  { rewrite <- Lx. apply qsum_seq_sqnorm. intros i Hi. destruct i as [|i]; [lia|].
    simpl. rewrite Nat.sub_0_r. reflexivity. }
  assert (SU : qsum (map (fun i => us u i * us u i) (seq 1 N)) == sqnorm u).
  { rewrite <- Lu. apply qsum_seq_sqnorm. intros i Hi. destruct i as [|i]; [lia|].
    simpl. rewrite Nat.sub_0_r. reflexivity. }
  pose proof (nth_first_sq x) as F1. pose proof (nth_first_sq u) as F2.
  assert (Hinv : 1 / qn N <= 1).
  { apply Qle_shift_div_r; [exact Hn|]. pose proof (qn_le 1 N HN) as H1.
    assert (E1 : qn 1 == 1) by reflexivity. lra. }
  assert (Hinv0 : 0 <= 1 / qn N) by (apply Qle_shift_div_l; lra).
  split.
  - eapply Qle_trans; [apply l2_affine_le, HN|]. rewrite SX.
    simpl xs at 1 2. fold N. rewrite Lx.
    set (a := nth 0 x 0) in *. set (e := 1 / qn N + δ).
    setoid_replace (a - 1 / qn N - δ) with (a - e) by (unfold e; ring).
    assert (He : e * e <= (1 + δ) * (1 + δ)) by (unfold e; nra).
    assert (Sq : (a - e) * (a - e) <= 2 * (a * a) + 2 * (e * e))
      by (assert (0 <= (a + e) * (a + e)) by apply Qsq_nonneg; nra).
    assert (A1 : (a - e) * (a - e) / (2 * qn N) <= sqnorm x / qn N + (1 + δ) * (1 + δ)).
    { apply Qle_shift_div_r; [lra|].
      setoid_replace ((sqnorm x / qn N + (1 + δ) * (1 + δ)) * (2 * qn N))
        with (2 * sqnorm x + 2 * qn N * ((1 + δ) * (1 + δ))) by (field; lra).
      assert ((1 + δ) * (1 + δ) <= qn N * ((1 + δ) * (1 + δ))).
      { pose proof (qn_le 1 N HN) as H1. assert (E1 : qn 1 == 1) by reflexivity.
        assert (0 <= (1 + δ) * (1 + δ)) by apply Qsq_nonneg. nra. }
      nra. }
    lra.
  - eapply Qle_trans; [apply l2_affine_le, HN|]. rewrite SU.
    simpl us at 1 2. set (a := nth 0 u 0) in *.
    assert (A1 : a * a / (2 * qn N) <= sqnorm u / qn N / 2).
    { apply Qle_shift_div_r; [lra|].
      setoid_replace (sqnorm u / qn N / 2 * (2 * qn N)) with (sqnorm u) by (field; lra). lra. }
    set (X := sqnorm u / qn N) in *.
    setoid_replace (X / 2) with (X * (1 # 2)) in A1 by field.
    setoid_replace ((3 # 2) * (C0 * C0)) with (C0 * C0 + C0 * C0 * (1 # 2)) by ring.
    lra.
Qed.

(** Paper, [prop:L2-micro] ([Λ_N], [Λ̃_N], [∂_w Λ̃_N]): for every [N ≥ 1],
    [x⁰ ∈ K^N], any [u⁰], rational [t ≥ 0], with [‖u⁰‖² ≤ C₀²]: each of
    [‖Λ_N(t)‖²_{L²}], [‖Λ̃_N(t)‖²_{L²}] and [‖∂_w Λ̃_N(t)‖²_{L²}] is
    [≤ C₀²] ([λ_k² ≤ ‖u⁰‖²] by Cauchy–Schwarz, [∂_w Λ̃_N = u⁰_i − u_i] on
    the cell [i] and [‖u⁰ − u‖ ≤ ‖u⁰‖]). Ledger claim: [prop:L2-micro]. *)
Theorem L2_micro_Lambda (x0 u0 : list Q) (r t C0 : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (1 <= length x0)%nat ->
  wnorm2 u0 <= C0 * C0 ->
  let N := length x0 in
  let l := lambdas x0 u0 r t in
  l2_const l N <= C0 * C0 /\ l2_affine l N <= C0 * C0 /\
  l2_const (pslope l N) N <= C0 * C0.
Proof.
  intros Ht HK L HN Hu N l.
  pose proof (qn_pos _ HN) as Hn. fold N in Hn.
  assert (Hl : forall k, l k * l k <= wnorm2 u0)
    by (intro k; apply multiplier_sq_bound; assumption).
  assert (Cst : l2_const l N <= wnorm2 u0).
  { unfold l2_const. apply Qle_shift_div_r; [exact Hn|].
    eapply Qle_trans; [apply (qsum_map_le _ (fun _ => wnorm2 u0)); intros; apply Hl|].
    rewrite qsum_map_const. rewrite Qmult_comm. apply Qle_refl. }
  split; [|split].
  - lra.
  - eapply Qle_trans; [apply l2_affine_le, HN|].
    destruct (multiplier_ends x0 u0 r t Ht HK L) as [E0 _].
    unfold l at 3 4, lambdas. rewrite E0.
    setoid_replace (0 * 0 / (2 * qn N)) with 0 by (field; lra).
    unfold l2_const in Cst. lra.
  - pose proof (velocities_length x0 u0 r t Ht HK L) as Lu.
    set (u := velocities (dynamics x0 u0 r t)) in *.
    assert (Ld : length (vsub u0 u) = N) by (rewrite vsub_length; unfold N; lia).
    assert (S : qsum (map (fun i => pslope l N i * pslope l N i) (seq 1 N)) == sqnorm (vsub u0 u)).
    { replace (seq 1 N) with (seq 1 (length (vsub u0 u))) by (rewrite Ld; reflexivity).
      apply qsum_seq_sqnorm. intros i Hi. rewrite Ld in Hi.
      unfold pslope, l, N. rewrite (multiplier_increment x0 u0 r t i Ht HK L Hi).
      rewrite nth_vsub by lia. fold u. reflexivity. }
    unfold l2_const. rewrite S. pose proof (velocity_defect_l2 x0 u0 r t Ht HK L) as V.
    fold u in V. apply (Qle_trans _ (wnorm2 u0)); [|exact Hu].
    unfold wnorm2. rewrite L. apply Qmult_le_compat_r; [exact V|].
    apply Qlt_le_weak, Qinv_lt_0_compat, Hn.
Qed.
