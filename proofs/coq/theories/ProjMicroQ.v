(** * The real solution of [prop:proj-micro] at rational data and times is
      the rational dynamics.

    [ProjMicroR.proj_micro] builds the solution over [R]; [Dynamics.v]
    computes the sticky dynamics over [Q]. For rational [x⁰ ∈ K^N], [u⁰]
    and rational [t ≥ 0], the rational positions read in [R] are the
    projection of [x⁰ + t u⁰] onto [K^N] over [R]
    ([dynamics_is_projection_R]: feasibility from [S3Positions], the
    multipliers of [KktIntegral.kkt_multiplier_kkt] carried by [Q2R] give
    the normal cone), so the real solution equals them there
    ([proj_micro_is_dynamics]). Over Coq's real numbers: rests on the
    standard real-number axioms only. *)

From Coq Require Import Reals QArith Qreals Lra Lia List.
From Sticky Require Import Prelude Kkt Dynamics KktIntegral S3Positions
  Uniqueness UniquenessAC NormalConeR ProjMicroR.
Open Scope R_scope.

(** A rational vector read in [R]. *)
Definition readR (l : list Q) : nat -> R := fun i => Q2R (nth i l 0%Q).

(** [K^N] over [Q], read in [R]. *)
Lemma inK_R (r : Q) (x : list Q) : InK r x -> InKR (length x) (Q2R r) (readR x).
Proof.
  intros HK i Hi. specialize (HK i Hi). apply Qle_Rle in HK.
  unfold readR. rewrite Q2R_minus, Q2R_mult, Q2R_2 in HK. exact HK.
Qed.

(** The rational dynamics is, in [R], the projection of [x⁰ + t u⁰]. *)
Theorem dynamics_is_projection_R (x0 u0 : list Q) (r t : Q) :
  (0 <= t)%Q -> InK r x0 -> length u0 = length x0 ->
  IsProjectionK (length x0) (Q2R r) (fun i => readR x0 i + Q2R t * readR u0 i)
    (readR (positions (dynamics x0 u0 r t))).
Proof.
  intros Ht HK L.
  pose proof (positions_length x0 u0 r t Ht HK L) as Lx.
  pose proof (positions_inK x0 u0 r t Ht HK L) as Kx.
  pose proof (kkt_multiplier_kkt x0 u0 r t Ht HK L) as H. cbv zeta in H.
  destruct H as (Hst & H0 & HN & Hpos & Hcomp).
  apply normal_cone_projection.
  - rewrite <- Lx. apply inK_R, Kx.
  - apply (normal_cone_of_multipliers (length x0) (Q2R r) (Q2R (qn (length x0))) _ _
             (fun k => Q2R (kkt_multiplier x0 u0 r t k))).
    + rewrite <- Q2R_0. apply Qle_Rle, qn_nonneg.
    + rewrite <- Q2R_0. apply Qeq_eqR. exact H0.
    + rewrite <- Q2R_0. apply Qeq_eqR. exact HN.
    + intros k Hk. rewrite <- Q2R_0. apply Qle_Rle, Hpos, Hk.
    + intros k Hk. pose proof (Hcomp k Hk) as C. apply Qeq_eqR in C.
      rewrite Q2R_mult, !Q2R_minus, Q2R_mult, Q2R_2, Q2R_0 in C. exact C.
    + intros i Hi. pose proof (Hst i Hi) as S. apply Qeq_eqR in S.
      pose proof (free_flight_nth x0 u0 t i L Hi) as F. apply Qeq_eqR in F.
      rewrite Q2R_plus, Q2R_mult in F.
      rewrite Q2R_plus, Q2R_minus, Q2R_mult, Q2R_minus, Q2R_0, F in S.
      unfold readR. lra.
Qed.

(** Paper, [prop:proj-micro]: the unique solution over [R], at rational
    data and rational times [t ≥ 0], is the sticky dynamics computed over
    [Q], entry by entry. *)
Theorem proj_micro_is_dynamics (x0 u0 : list Q) (r : Q) (x : R -> nat -> R) :
  InK r x0 -> length u0 = length x0 ->
  (forall t, 0 <= t -> IsProjectionK (length x0) (Q2R r) (fun i => readR x0 i + t * readR u0 i) (x t)) ->
  forall t : Q, (0 <= t)%Q -> forall i, (i < length x0)%nat ->
    x (Q2R t) i = readR (positions (dynamics x0 u0 r t)) i.
Proof.
  intros HK L Hx t Ht i Hi.
  pose proof (dynamics_is_projection_R x0 u0 r t Ht HK L) as (Kd & Md & Ud).
  assert (Ht' : 0 <= Q2R t) by (rewrite <- Q2R_0; apply Qle_Rle, Ht).
  destruct (Hx (Q2R t) Ht') as (Kx & Mx & Ux).
  apply (Ud (x (Q2R t)) Kx); [|exact Hi].
  apply Mx. exact Kd.
Qed.

(** [proj_micro] at rational data: its solution, in the class
    [SolutionAC] on every [[0, T]], is at every rational [t ≥ 0] the
    rational sticky dynamics [Dynamics.dynamics], read in [R]. *)
Corollary proj_micro_rational (x0 u0 : list Q) (r : Q) :
  InK r x0 -> length u0 = length x0 ->
  exists x : R -> nat -> R,
    (forall T, SolutionAC (length x0) (Q2R r) T (readR x0) (readR u0) x) /\
    forall t : Q, (0 <= t)%Q -> forall i, (i < length x0)%nat ->
      x (Q2R t) i = readR (positions (dynamics x0 u0 r t)) i.
Proof.
  intros HK L.
  destruct (proj_micro (length x0) (Q2R r) (readR x0) (readR u0) (inK_R r x0 HK))
    as (x & Hsol & _ & Hproj & _).
  exists x. split; [exact Hsol|]. exact (proj_micro_is_dynamics x0 u0 r x HK L Hproj).
Qed.
