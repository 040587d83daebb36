(** * Section 3 at fixed [N]: the BV bound on [Ũ_N] away from [t = 0]
      ([pwUN-L1]), with an explicit [C_α].

    Paper, [prop:2ndorder-LagrPDE] (controls on [U_N]): "for every α > 0,
    sup_{t ∈ [α,T]} ‖∂_w Ũ_N(t)‖_{L¹(0,1)} ≤ C_α, for some constant C_α > 0
    independent of N". The proof writes [|d| = 2 d₊ − d] and bounds
    [(∂_w Ũ_N)₊ ≤ ∂_w X̃_N / t] by [eq:Oleinik-tUN]; on the cells this is
    [Σ_i |u_i − u_{i−1}| ≤ (2/t)(x_N − x_0) − (u_N − u_0)], and [eq:BV_XN]
    with [eq:bound-UN-Linf] give
    [C_α = 2(1 + 2T) C'_0 / α + 2 sup_i |u⁰_i| ≤ (2(1 + 2T)/α + 2) C'_0]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List Qabs.
From Sticky Require Import Prelude Kkt Dynamics Multipliers S3Linf S3Positions S3Pressure.
Import ListNotations.
Open Scope Q_scope.

(** [|d| = 2 d₊ − d ≤ 2b − d] when [d ≤ b] and [b ≥ 0]. *)
Lemma abs_le_positive_part (d b : Q) : d <= b -> 0 <= b -> Qabs d <= 2 * b - d.
Proof.
  intros H1 H2. destruct (Qlt_le_dec d 0) as [Hd|Hd].
  - rewrite Qabs_neg by lra. lra.
  - rewrite Qabs_pos by exact Hd. lra.
Qed.

(** Paper, [pwUN-L1]: for every [N ≥ 1], [r > 0], [δ > 0], [x⁰ ∈ K^N]
    under [cond:Linfty] ([x⁰_N − x⁰_0 + sup_i |u⁰_i| ≤ C'_0],
    [sup_i |u⁰_i| ≤ M]) and rational [0 < α ≤ t ≤ T]:
    [‖∂_w Ũ_N(t)‖_{L¹} = Σ_{i=1}^N (1/N)|N(u_i − u_{i−1})|] (the artificial
    particle's [u_0 = u_1]) is [≤ (2/t)(x_N − x_0) − (u_N − u_0)] (the
    proof's step) and [≤ C_α = 2(1 + 2T) C'_0 / α + 2M], independent of
    [N]. Ledger claim: [pwUN-L1]. *)
Theorem pwUN_L1 (x0 u0 : list Q) (r t T α M δ C0' : Q) :
  0 < α -> α <= t -> t <= T -> 0 < r -> 0 < δ -> InK r x0 -> length u0 = length x0 ->
  SupBound M u0 -> (1 <= length x0)%nat ->
  xs δ x0 (length x0) - xs δ x0 0%nat + M <= C0' ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  let u := us (velocities (dynamics x0 u0 r t)) in
  let N := length x0 in
  bv u N <= 2 / t * (x N - x 0%nat) - (u N - u 0%nat) /\
  bv u N <= 2 * (1 + 2 * T) * C0' / α + 2 * M.
Proof.
  intros Hα Hαt HtT Hr Hδ HK L HB HN HC x u N.
  assert (Ht : 0 < t) by lra. assert (Ht0 : 0 <= t) by lra.
  pose proof (qn_pos N HN) as Hn.
  pose proof (positions_length x0 u0 r t Ht0 HK L) as Lx.
  pose proof (positions_inK x0 u0 r t Ht0 HK L) as HKx.
  assert (Mono : forall j, (1 <= j <= N)%nat -> x (j - 1)%nat <= x j).
  { intros j Hj. apply (xs_mono δ r _ ltac:(lra) ltac:(lra) HKx). rewrite Lx. exact Hj. }
  assert (Step : bv u N <= 2 / t * (x N - x 0%nat) - (u N - u 0%nat)).
  { unfold bv.
    set (v := fun j => 2 / t * x j - u j).
    setoid_replace (2 / t * (x N - x 0%nat) - (u N - u 0%nat)) with (1 * (v N - v 0%nat))
      by (unfold v; ring).
    rewrite <- (telescope (fun i => 1 / qn N * (2 * (pslope x N i / t) - pslope u N i)) v 1 N).
    2: { intros j Hj. unfold v, pslope. field. split; lra. }
    apply qsum_map_le. intros i Hi.
    assert (H1 : 0 < 1 / qn N) by (apply Qlt_shift_div_l; lra).
    apply Qmult_le_l; [exact H1|].
    apply abs_le_positive_part.
    - apply Qlt_le_weak. apply (Oleinik_tUN x0 u0 r t δ i Ht Hr Hδ HK L). unfold N in Hi. lia.
    - apply Qle_shift_div_l; [exact Ht|]. unfold pslope.
      specialize (Mono i ltac:(lia)). pose proof (qn_nonneg N). nra. }
  split; [exact Step|].
  destruct (BV_XN x0 u0 r t T M δ C0' Ht0 HtT ltac:(lra) Hδ HK L HB HN HC) as [E [_ B]].
  fold x N in E, B.
  pose proof (mono_le x N Mono 0 N ltac:(lia)) as X0.
  assert (HX : x N - x 0%nat <= (1 + 2 * T) * C0') by (rewrite <- E; exact B).
  pose proof (bound_UN_Linf x0 u0 r t M Ht0 HK L HB) as HU.
  pose proof (velocities_length x0 u0 r t Ht0 HK L) as Lu.
  assert (UN : Qabs (u N) <= M).
  { destruct N as [|n] eqn:EN; [lia|]. change (u (S n)) with (nth n (velocities (dynamics x0 u0 r t)) 0).
    apply (forall_nth _ _ n HU). lia. }
  assert (U0 : Qabs (u 0%nat) <= M).
  { change (u 0%nat) with (nth 0 (velocities (dynamics x0 u0 r t)) 0).
    apply (forall_nth _ _ 0 HU). lia. }
  assert (Du : - (u N - u 0%nat) <= 2 * M).
  { pose proof (Qle_Qabs (u 0%nat)). pose proof (Qabs_opp (u N)).
    pose proof (Qle_Qabs (- u N)). lra. }
  assert (Tt : 2 / t * (x N - x 0%nat) <= 2 * (1 + 2 * T) * C0' / α).
  { apply (Qle_trans _ (2 / α * (x N - x 0%nat))).
    - apply Qmult_le_compat_r; [|lra].
      apply Qle_shift_div_r; [exact Ht|].
      setoid_replace (2 / α * t) with (2 * (t / α)) by (field; lra).
      assert (1 <= t / α) by (apply Qle_shift_div_l; lra). lra.
    - setoid_replace (2 * (1 + 2 * T) * C0' / α) with (2 / α * ((1 + 2 * T) * C0')) by (field; lra).
      apply Qmult_le_l; [|exact HX]. apply Qlt_shift_div_l; lra. }
  lra.
Qed.

(** ** The corrected [prop:2ndorder-LagrPDE#UN-L1] step away from [t = 0] *)

Lemma qsum_map_scale (c : Q) (f : nat -> Q) (l : list nat) :
  qsum (map (fun i => c * f i) l) == c * qsum (map f l).
Proof. induction l as [|a l IH]; simpl; [ring|]. rewrite IH. ring. Qed.

Lemma qsum_map_qeq (f g : nat -> Q) (l : list nat) :
  (forall i, f i == g i) -> qsum (map f l) == qsum (map g l).
Proof. intro H. induction l as [|a l IH]; simpl; [reflexivity|]. rewrite IH, H. reflexivity. Qed.

(** [∫|Ṽ_N − V_N| = Σ|v_i − v_{i−1}|/(2N)] is [‖∂_w Ṽ_N‖_{L¹}/(2N)]. *)
Lemma l1_gap_bv (v : seqQ) (N : nat) :
  (1 <= N)%nat -> l1_gap v N == 1 / (2 * qn N) * bv v N.
Proof.
  intro HN. pose proof (qn_pos N HN) as Hn. unfold l1_gap, bv.
  rewrite (qsum_map_qeq (fun i => Qabs (v i - v (i - 1)%nat) / (2 * qn N))
                        (fun i => 1 / (2 * qn N) * Qabs (v i - v (i - 1)%nat)))
    by (intro i; field; lra).
  rewrite (qsum_map_qeq (fun i => 1 / qn N * Qabs (pslope v N i))
                        (fun i => Qabs (v i - v (i - 1)%nat))).
  2: { intro i. unfold pslope. rewrite Qabs_Qmult, (Qabs_pos (qn N)) by lra. field. lra. }
  rewrite qsum_map_scale. reflexivity.
Qed.

(** Paper, [prop:2ndorder-LagrPDE#UN-L1] as the ledger corrects it
    ("(1/2N) Σ |u_i − u_{i−1}| ≤ C/N", not "= (1/2N)|u_N − u_0|"), for
    [t ∈ [α, T]]: [Σ_{i=1}^N |u_i − u_{i−1}|/(2N) ≤ C_α/(2N)] with the
    [C_α] of [pwUN_L1], same hypotheses. *)
Theorem UN_L1_away (x0 u0 : list Q) (r t T α M δ C0' : Q) :
  0 < α -> α <= t -> t <= T -> 0 < r -> 0 < δ -> InK r x0 -> length u0 = length x0 ->
  SupBound M u0 -> (1 <= length x0)%nat ->
  xs δ x0 (length x0) - xs δ x0 0%nat + M <= C0' ->
  let u := us (velocities (dynamics x0 u0 r t)) in
  let N := length x0 in
  l1_gap u N <= (2 * (1 + 2 * T) * C0' / α + 2 * M) / (2 * qn N).
Proof.
  intros Hα Hαt HtT Hr Hδ HK L HB HN HC u N.
  destruct (pwUN_L1 x0 u0 r t T α M δ C0' Hα Hαt HtT Hr Hδ HK L HB HN HC) as [_ B].
  fold u N in B. pose proof (qn_pos N HN) as Hn.
  rewrite (l1_gap_bv u N HN).
  setoid_replace ((2 * (1 + 2 * T) * C0' / α + 2 * M) / (2 * qn N))
    with (1 / (2 * qn N) * (2 * (1 + 2 * T) * C0' / α + 2 * M)) by (field; lra).
  apply Qmult_le_l; [apply Qlt_shift_div_l; lra|exact B].
Qed.
