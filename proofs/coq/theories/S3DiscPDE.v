(** * Section 3 at fixed [N]: the discrete PDE systems cell by cell
      ([eq:PDE-Lagr-N-1] / [lem:discPDE1], [lem:discPDE2]), with the
      ledger's re-indexed [Λ_N := λ_{i−1}] on the cell [i] for the
      complementarity and the exclusion. [2rN = 1] as in the paper. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Dynamics Multipliers Pressure S3Linf S3Positions.
Import ListNotations.
Open Scope Q_scope.

(** On the cell [i], [N(x_i − x_{i−1}) ≥ 1], and [= 1] wherever
    [λ_{i−1} ≠ 0] ([i ≥ 2]; on the cell 1, [λ_0 = 0] and the slope is
    [1 + Nδ]). *)
Lemma slope_facts (x0 u0 : list Q) (r t δ : Q) (i : nat) :
  0 <= t -> 0 < δ -> InK r x0 -> length u0 = length x0 -> 2 * r * qn (length x0) == 1 ->
  (1 <= i <= length x0)%nat ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  let l := lambdas x0 u0 r t in
  1 <= pslope x (length x0) i /\ (pslope x (length x0) i - 1) * l (i - 1)%nat == 0.
Proof.
  intros Ht Hδ HK L Hr Hi x l.
  pose proof (positions_length x0 u0 r t Ht HK L) as Lx.
  pose proof (positions_inK x0 u0 r t Ht HK L) as HKx.
  pose proof (qn_pos (length x0) ltac:(lia)) as HN.
  set (p := positions (dynamics x0 u0 r t)) in *.
  unfold pslope. destruct i as [|[|i]]; [lia| |].
  - change (x 1%nat) with (nth 0 p 0).
    change (x (1 - 1)%nat) with (nth 0 p 0 - 1 / qn (length p) - δ).
    change (l (1 - 1)%nat) with (multiplier x0 u0 r t 0).
    destruct (multiplier_ends x0 u0 r t Ht HK L) as [E0 _]. rewrite E0, Lx.
    setoid_replace (qn (length x0) * (nth 0 p 0 - (nth 0 p 0 - 1 / qn (length x0) - δ)))
      with (1 + qn (length x0) * δ) by (field; lra).
    split; [|ring]. assert (0 <= qn (length x0) * δ) by (apply Qmult_le_0_compat; lra). lra.
  - change (x (S (S i))) with (nth (S i) p 0). change (x (S (S i) - 1)%nat) with (nth i p 0).
    change (l (S (S i) - 1)%nat) with (multiplier x0 u0 r t (S i)).
    pose proof (HKx i ltac:(lia)) as G.
    pose proof (multiplier_complementarity x0 u0 r t (S i) Ht HK L ltac:(lia)) as C.
    cbv zeta in C. fold p in C. replace (S i - 1)%nat with i in C by lia.
    split.
    + setoid_replace 1 with (qn (length x0) * (2 * r)) by (rewrite <- Hr; ring).
      apply Qmult_le_l; [exact HN|exact G].
    + setoid_replace (qn (length x0) * (nth (S i) p 0 - nth i p 0) - 1)
        with (qn (length x0) * (nth (S i) p 0 - nth i p 0 - 2 * r)) by (rewrite <- Hr; ring).
      setoid_replace (qn (length x0) * (nth (S i) p 0 - nth i p 0 - 2 * r) * multiplier x0 u0 r t (S i))
        with (qn (length x0) * (multiplier x0 u0 r t (S i) * (nth (S i) p 0 - nth i p 0 - 2 * r)))
        by ring.
      rewrite C. ring.
Qed.

(** Paper, [eq:PDE-Lagr-N-1] ([lem:discPDE1]) on the cell [i = 1..N] at
    time [t ≥ 0]: "∂_t X_N = U⁰_N − ∂_w Λ̃_N" ([∂_t X_N = u_i(t)], the
    right derivative: [OracleIsDynamics.dynamics_rigid_after]),
    "∂_w X̃_N ≥ 1", "Λ_N ≥ 0", and the corrected complementarity
    "(∂_w X̃_N − 1) Λ_N = 0" with [Λ_N := λ_{i−1}] (ledger:
    [eq:PDE-Lagr-N-1#complementarity]). Every [N ≥ 1], [2rN = 1], [δ > 0],
    [x⁰ ∈ K^N], any [u⁰]. Ledger claims: [eq:PDE-Lagr-N-1],
    [eq:PDE-Lagr-N-1#complementarity] (corrected). *)
Theorem PDE_Lagr_N_1 (x0 u0 : list Q) (r t δ : Q) (i : nat) :
  0 <= t -> 0 < δ -> InK r x0 -> length u0 = length x0 -> 2 * r * qn (length x0) == 1 ->
  (1 <= i <= length x0)%nat ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  let u := us (velocities (dynamics x0 u0 r t)) in
  let l := lambdas x0 u0 r t in
  pconst u i == pconst (us u0) i - pslope l (length x0) i /\
  1 <= pslope x (length x0) i /\
  0 <= pconst l i /\ 0 <= l (i - 1)%nat /\
  (pslope x (length x0) i - 1) * l (i - 1)%nat == 0.
Proof.
  intros Ht Hδ HK L Hr Hi x u l.
  destruct (slope_facts x0 u0 r t δ i Ht Hδ HK L Hr Hi) as [S1 S2].
  split; [|split; [exact S1|split; [|split; [|exact S2]]]].
  - pose proof (multiplier_increment x0 u0 r t i Ht HK L Hi) as E.
    destruct i as [|i]; [lia|]. rewrite Nat.sub_succ, Nat.sub_0_r in E.
    change (pconst u (S i)) with (nth i (velocities (dynamics x0 u0 r t)) 0).
    change (pconst (us u0) (S i)) with (nth i u0 0).
    unfold pslope. rewrite Nat.sub_succ, Nat.sub_0_r. fold l in E. lra.
  - apply multiplier_nonneg; [exact Ht|exact HK|exact L|lia].
  - apply multiplier_nonneg; [exact Ht|exact HK|exact L|lia].
Qed.

(** Paper, [lem:discPDE2], corrected exclusion "(∂_w X̃_N − 1) P_N = 0,
    P_N ≥ 0" with [P_N := ∂_t λ_{i−1}] on the cell [i] (ledger:
    [lem:discPDE2#exclusion]): for [0 ≤ s ≤ t], the increment
    [λ_{i−1}(t) − λ_{i−1}(s)] (the pressure mass on [(s, t]]) is [≥ 0] and
    vanishes unless [N(x_i(t) − x_{i−1}(t)) = 1]. Every [N ≥ 1], [2rN = 1],
    [δ > 0], [x⁰ ∈ K^N]. Ledger claim: [lem:discPDE2#exclusion] (corrected). *)
Theorem discPDE2_exclusion (x0 u0 : list Q) (r s t δ : Q) (i : nat) :
  0 <= s -> s <= t -> 0 < δ -> InK r x0 -> length u0 = length x0 ->
  2 * r * qn (length x0) == 1 -> (1 <= i <= length x0)%nat ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  let dl := lambdas x0 u0 r t (i - 1)%nat - lambdas x0 u0 r s (i - 1)%nat in
  0 <= dl /\ (pslope x (length x0) i - 1) * dl == 0.
Proof.
  intros Hs Hst Hδ HK L Hr Hi x dl. assert (Ht : 0 <= t) by lra.
  destruct (slope_facts x0 u0 r t δ i Ht Hδ HK L Hr Hi) as [_ S2]. fold x in S2.
  pose proof (multiplier_nondecreasing x0 u0 r s t (i - 1) Hs Hst HK L ltac:(lia)) as M.
  pose proof (multiplier_nonneg x0 u0 r s (i - 1) Hs HK L ltac:(lia)) as P.
  unfold lambdas in *. split; [unfold dl; lra|].
  destruct (Qeq_dec (multiplier x0 u0 r t (i - 1)) 0) as [Z|Z].
  - unfold dl. setoid_replace (multiplier x0 u0 r s (i - 1)) with 0 by lra. rewrite Z. ring.
  - assert (G : pslope x (length x0) i - 1 == 0).
    { apply Qmult_integral in S2. destruct S2 as [G|G]; [exact G|contradiction]. }
    rewrite G. ring.
Qed.
