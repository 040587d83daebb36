(** * Section 3 at fixed [N]: [L²] bounds ([prop:L2-micro], in part).

    The paper's norm is [‖v‖² = (1/N) Σ v_i²] ([sqnorm v / N]); for the
    piecewise constant interpolation it is [‖V_N(t)‖²_{L²(0,1)}]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Projection Dynamics Multipliers DynamicsIsProjK
  VelocityBound InclHSN S3Linf S3Positions.
Import ListNotations.
Open Scope Q_scope.

(** The paper's [‖v‖² = (1/N) Σ_i v_i²]. *)
Definition wnorm2 (v : list Q) : Q := sqnorm v / qn (length v).

Lemma sqnorm_free_flight (x0 u0 : list Q) (t : Q) :
  length u0 = length x0 -> sqnorm (vsub (free_flight x0 u0 t) x0) == t * t * sqnorm u0.
Proof.
  unfold free_flight. revert u0.
  induction x0 as [|a x0 IH]; intros [|b u0] L; simpl in *; try ring; try lia.
  rewrite IH by lia. ring.
Qed.

Lemma sqnorm_split (a b : list Q) :
  length a = length b -> sqnorm a <= 2 * sqnorm b + 2 * sqnorm (vsub a b).
Proof.
  revert b. induction a as [|x a IH]; intros [|y b] L; simpl in *; try lia; [lra|].
  specialize (IH b ltac:(lia)). assert (0 <= (x - 2 * y) * (x - 2 * y)) by apply Qsq_nonneg.
  nra.
Qed.

(** [Σ_i (x_i(t) − x⁰_i)² ≤ t² Σ_i (u⁰_i)²]: [P_K] is 1-Lipschitz and fixes [x⁰]. *)
Lemma position_l2_lipschitz (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  sqnorm (vsub (positions (dynamics x0 u0 r t)) x0) <= t * t * sqnorm u0.
Proof.
  intros Ht HK L.
  set (z := free_flight x0 u0 t).
  assert (Lz : length z = length x0) by (apply free_flight_length, L).
  pose proof (proj_K_lipschitz r z x0 ltac:(lia)) as P.
  rewrite (sqnorm_qeq _ _ (qeq_list_vsub _ _ _ _ (qeq_list_refl _) (proj_K_fixed r x0 HK))) in P.
  rewrite (sqnorm_qeq _ _ (qeq_list_vsub _ _ _ _ (dynamics_is_proj_K x0 u0 r t Ht HK L) (qeq_list_refl x0))).
  unfold z in P. rewrite sqnorm_free_flight in P by exact L. exact P.
Qed.

(** Paper, [prop:L2-micro] (the first and third norms): for every [N ≥ 1],
    [x⁰ ∈ K^N], any [u⁰] and rational [0 ≤ t ≤ T], with
    [‖x⁰‖², ‖u⁰‖² ≤ C₀²] (implied by [‖x⁰‖ + ‖u⁰‖ ≤ C₀]):
    [‖X_N(t)‖²_{L²} ≤ 2(1 + T²) C₀²] and [‖∂_t X_N(t)‖²_{L²} = ‖u(t)‖² ≤ C₀²].
    Ledger claim: [prop:L2-micro]. *)
Theorem L2_micro_XN_UN (x0 u0 : list Q) (r t T C0 : Q) :
  0 <= t -> t <= T -> InK r x0 -> length u0 = length x0 -> (1 <= length x0)%nat ->
  wnorm2 x0 <= C0 * C0 -> wnorm2 u0 <= C0 * C0 ->
  wnorm2 (positions (dynamics x0 u0 r t)) <= 2 * (1 + T * T) * (C0 * C0) /\
  wnorm2 (velocities (dynamics x0 u0 r t)) <= C0 * C0.
Proof.
  intros Ht HtT HK L HN Hx Hu.
  pose proof (qn_pos (length x0) HN) as HNq.
  pose proof (positions_length x0 u0 r t Ht HK L) as Lx.
  pose proof (velocities_length x0 u0 r t Ht HK L) as Lu.
  unfold wnorm2 in *. rewrite Lx, Lu. rewrite L in Hu.
  pose proof (position_l2_lipschitz x0 u0 r t Ht HK L) as P.
  pose proof (sqnorm_split (positions (dynamics x0 u0 r t)) x0 Lx) as S.
  pose proof (velocity_bound x0 u0 r t Ht HK L) as V.
  pose proof (sqnorm_nonneg u0). pose proof (sqnorm_nonneg x0).
  set (n := qn (length x0)) in *.
  assert (Dv : forall a b, a <= b -> a / n <= b / n).
  { intros a b Hab. apply Qmult_le_compat_r; [exact Hab|]. apply Qlt_le_weak, Qinv_lt_0_compat, HNq. }
  set (X := sqnorm x0 / n) in *. set (U := sqnorm u0 / n) in *.
  assert (HX0 : 0 <= X) by (apply Qle_shift_div_l; lra).
  assert (HU0 : 0 <= U) by (apply Qle_shift_div_l; lra).
  assert (Htt : t * t <= T * T) by nra.
  split.
  - apply (Qle_trans _ ((2 * sqnorm x0 + 2 * (t * t * sqnorm u0)) / n)); [apply Dv; lra|].
    setoid_replace ((2 * sqnorm x0 + 2 * (t * t * sqnorm u0)) / n) with (2 * X + 2 * (t * t) * U)
      by (unfold X, U; field; lra).
    assert (t * t * U <= T * T * (C0 * C0)) by nra. lra.
  - apply (Qle_trans _ U); [apply Dv; exact V|exact Hu].
Qed.
