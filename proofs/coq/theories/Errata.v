(** * Errata of section 2, disproved with the ledger's witnesses.

    Each statement below is a printed sentence of the paper about one
    datum [(x⁰, u⁰, r)] and one time [t], formalised on the dynamics of
    [Dynamics.v] (which is the paper's solution: [DynamicsProjection.v]);
    each is refuted by the ledger's witness (CLAIMS.md), evaluated exactly
    by [vm_compute]. The corrected statements are proved in the files
    named in each comment. *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Dynamics Multipliers Contacts VelocityProjection.
Import ListNotations.
Open Scope Q_scope.

(** Admissible data: [x⁰ ∈ K^N], [u⁰ ∈ C_{x⁰}], [r > 0]. *)
Definition Admissible (x0 u0 : list Q) (r : Q) : Prop :=
  length u0 = length x0 /\ 0 < r /\ InK r x0 /\ InC r x0 u0.

(** Decides [a ≤ b] on closed rationals. *)
Ltac qle_closed := apply Qle_bool_iff; vm_compute; reflexivity.

(** Admissibility of a closed datum of at most three particles. *)
Ltac admissible_closed :=
  split; [reflexivity|split; [vm_compute; reflexivity|split]];
  [ intros i Hi; destruct i as [|[|i]]; simpl in Hi; try lia; qle_closed
  | intros j Hj Hc; destruct j as [|[|j]]; simpl in Hj; try lia;
    first [qle_closed | (unfold Contact in Hc; vm_compute in Hc; discriminate Hc)] ].

(** ** [lem:incl-HSN#proof-second-inclusion] and [eq:w-Hs-perp]

    Paper, proof of [lem:incl-HSN]: "Let us now show the second inclusion
    H^N_{x̃(t)} ⊂ [x⁰ + t u⁰]^⊥", and [eq:w-Hs-perp]: "We also know by the
    previous lemma that ⟨x⁰ + t u⁰, w⟩ = 0" for [w ∈ H^N_{x(t)}].
    Witness (N = 1): r = 1/2, x⁰ = (0), u⁰ = (−8), t = 1, w = (1):
    [⟨x⁰ + t u⁰, w⟩ = −8]. Corrected ([⟨x⁰ + t u⁰ − x(t), w⟩ = 0]): the
    KKT conditions of [DynamicsProjection.dynamics_is_projection]. *)
Definition FreeFlightOrthogonalToH : Prop :=
  forall (x0 u0 : list Q) (r t : Q) (w : list Q),
    Admissible x0 u0 r -> 0 <= t -> length w = length x0 ->
    InH r (positions (dynamics x0 u0 r t)) w ->
    dot (free_flight x0 u0 t) w == 0.

(** Ledger claims [lem:incl-HSN#proof-second-inclusion] and [eq:w-Hs-perp]
    (counterexamples). *)
Theorem free_flight_orthogonal_to_H_false : ~ FreeFlightOrthogonalToH.
Proof.
  intro H.
  specialize (H [0] [-8] (1 # 2) 1 [1] ltac:(admissible_closed) ltac:(qle_closed) eq_refl).
  assert (HH : InH (1 # 2) (positions (dynamics [0] [-8] (1 # 2) 1)) [1]).
  { intros j Hj. vm_compute in Hj. lia. }
  specialize (H HH). vm_compute in H. discriminate H.
Qed.

(** ** [prop:bound-micro#position-contraction]

    Paper, proof of [prop:bound-micro]: "From the projection formula we
    obtain ‖x(t)‖ ≤ ‖x⁰ + t u⁰‖". Witness (N = 2): r = 1/2, x⁰ = (0, 2),
    u⁰ = (−8, −9), t = 2: [‖x(t)‖² = 1025/4 > ‖x⁰ + t u⁰‖² = 256]. *)
Definition PositionContraction : Prop :=
  forall (x0 u0 : list Q) (r t : Q),
    Admissible x0 u0 r -> 0 <= t ->
    sqnorm (positions (dynamics x0 u0 r t)) <= sqnorm (free_flight x0 u0 t).

(** Ledger claim [prop:bound-micro#position-contraction] (counterexample). *)
Theorem position_contraction_false : ~ PositionContraction.
Proof.
  intro H.
  specialize (H [0; 2] [-8; -9] (1 # 2) 2 ltac:(admissible_closed) ltac:(qle_closed)).
  apply Qle_bool_iff in H. vm_compute in H. discriminate H.
Qed.

(** ** [prop:bound-micro#multiplier-relation]

    Paper, proofs of [prop:bound-micro] and [prop:Linf-micro]: "using the
    relation N(λ_i(t) − λ_{i−1}(t)) = u_i(t) − u⁰_i". Witness (N = 2):
    r = 1/4, x⁰ = (0, 3/2), u⁰ = (−8, −9), t = 1, i = 1 (the first
    particle, index 0): [N(λ_1 − λ_0) = 1/2] but [u_1 − u⁰_1 = −1/2].
    Corrected (the sign of [eq:dyn-micro]): [Multipliers.dyn_micro_identity]. *)
Definition MultiplierRelation : Prop :=
  forall (x0 u0 : list Q) (r t : Q) (i : nat),
    Admissible x0 u0 r -> 0 <= t -> (i < length x0)%nat ->
    qn (length x0) * (multiplier x0 u0 r t (S i) - multiplier x0 u0 r t i) ==
    nth i (velocities (dynamics x0 u0 r t)) 0 - nth i u0 0.

(** Ledger claim [prop:bound-micro#multiplier-relation] (counterexample). *)
Theorem multiplier_relation_false : ~ MultiplierRelation.
Proof.
  intro H.
  specialize (H [0; 3 # 2] [-8; -9] (1 # 4) 1 0%nat
                ltac:(admissible_closed) ltac:(qle_closed) ltac:(simpl; lia)).
  vm_compute in H. discriminate H.
Qed.

(** ** [app:KKT]

    Paper, Appendix A: the KKT conditions "yield the existence of
    multipliers λ_i(t) ≥ 0 such that x(t) − (x⁰ + t u⁰) + N Σ λ_i(t)(e_i −
    e_{i+1}) = 0, λ_i(t)(x_{i+1} − x_i − 2r) = 0. This provides directly the
    multipliers and the Signorini condition introduced in the main text."
    Read as the ledger does, with the main text's [λ] of [eq:dyn-micro]
    (entry [j]: [x_j − (x⁰_j + t u⁰_j) + N(λ_{j+1} − λ_j) = 0], 0-based).
    Witness (N = 2): r = 1/4, x⁰ = (0, 3/2), u⁰ = (−8, −9), t = 1: the
    stationarity needs multipliers (0) but [λ(1) = (1/4)]. Corrected: the
    KKT multipliers are [μ = ∫λ] ([Kkt.Kkt], partial sums of [z − y]). *)
Definition KktMultipliersAreLambda : Prop :=
  forall (x0 u0 : list Q) (r t : Q) (j : nat),
    Admissible x0 u0 r -> 0 <= t -> (j < length x0)%nat ->
    nth j (positions (dynamics x0 u0 r t)) 0 - nth j (free_flight x0 u0 t) 0 +
    qn (length x0) * (multiplier x0 u0 r t (S j) - multiplier x0 u0 r t j) == 0.

(** Ledger claim [app:KKT] (counterexample). *)
Theorem kkt_multipliers_are_lambda_false : ~ KktMultipliersAreLambda.
Proof.
  intro H.
  specialize (H [0; 3 # 2] [-8; -9] (1 # 4) 1 0%nat
                ltac:(admissible_closed) ltac:(qle_closed) ltac:(simpl; lia)).
  vm_compute in H. discriminate H.
Qed.

(** ** [eq:proj-u-micro]

    Paper, [prop:proj-velo-micro]: "writing Ω^N_{x(t)} = ∪_k J_k(t), with
    J_k(t) = ⟦j_k(t), j_k(t) + L_k(t)⟧ […] u_i(t) = (1/L_k) Σ_{l=1}^{L_k}
    u⁰_{j_k+l} if i ∈ J_k" (read literally, as the ledger does: [J_k] is a
    maximal run of contact indices, [i] a particle index). In 0-based
    indices: the contacts [a, …, a + L] (contact [m] joins particles [m]
    and [m + 1]), particle [i ∈ ⟦a, a + L⟧], [u_i = (1/L) Σ_{l=1}^{L} u⁰_{a+l}]. *)
Definition ContactRun (r : Q) (x : list Q) (a L : nat) : Prop :=
  (S (a + L) < length x)%nat /\
  (forall m, (a <= m <= a + L)%nat -> Contact r x m) /\
  (a = 0%nat \/ ~ Contact r x (a - 1)) /\
  (S (S (a + L)) = length x \/ ~ Contact r x (S (a + L))).

Definition ProjUMicroFormula : Prop :=
  forall (x0 u0 : list Q) (r t : Q) (a L i : nat),
    Admissible x0 u0 r -> 0 < t ->
    ContactRun r (positions (dynamics x0 u0 r t)) a L -> (a <= i <= a + L)%nat ->
    nth i (velocities (dynamics x0 u0 r t)) 0 ==
    1 / qn L * qsum (map (fun l => nth (a + l) u0 0) (seq 1 L)).

(** Ledger claim [eq:proj-u-micro] (counterexample), with the ledger's
    witness (N = 2): r = 1/4, x⁰ = (0, 3/2), u⁰ = (−8, −9), t = 1, one
    contact ([a = 0], [L = 0]), particle 0: the printed mean is [0/0] (0 in
    Coq's [Q]) while [u_0(1) = −17/2]. *)
Theorem proj_u_micro_formula_false : ~ ProjUMicroFormula.
Proof.
  intro H.
  specialize (H [0; 3 # 2] [-8; -9] (1 # 4) 1 0%nat 0%nat 0%nat
                ltac:(admissible_closed) ltac:(vm_compute; reflexivity)).
  assert (HR : ContactRun (1 # 4) (positions (dynamics [0; 3 # 2] [-8; -9] (1 # 4) 1)) 0 0).
  { split; [vm_compute; lia|split; [|split; [left; reflexivity|left; reflexivity]]].
    intros m Hm. replace m with 0%nat by lia. unfold Contact. vm_compute. reflexivity. }
  specialize (H HR ltac:(lia)). vm_compute in H. discriminate H.
Qed.

(** The same formula is false without any division by zero (a particle is
    left out of the mean): N = 3, r = 1/2, x⁰ = (0, 2, 4), u⁰ = (2, 0, −1),
    t = 1: one cluster of three particles, contacts 0 and 1 ([a = 0],
    [L = 1]); the printed mean is [u⁰_1 = 0] but [u_0(1) = 1/3]. *)
Theorem proj_u_micro_formula_false_nonzero_run : ~ ProjUMicroFormula.
Proof.
  intro H.
  specialize (H [0; 2; 4] [2; 0; -1] (1 # 2) 1 0%nat 1%nat 0%nat
                ltac:(admissible_closed) ltac:(vm_compute; reflexivity)).
  assert (HR : ContactRun (1 # 2) (positions (dynamics [0; 2; 4] [2; 0; -1] (1 # 2) 1)) 0 1).
  { split; [vm_compute; lia|split; [|split; [left; reflexivity|left; reflexivity]]].
    intros m Hm. unfold Contact.
    destruct m as [|[|m]]; [vm_compute; reflexivity|vm_compute; reflexivity|lia]. }
  specialize (H HR ltac:(lia)). vm_compute in H. discriminate H.
Qed.
