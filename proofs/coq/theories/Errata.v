(** * Errata of section 2, disproved with the ledger's in-domain witnesses.

    Each statement below is a printed sentence of the paper about one
    datum [(x⁰, u⁰, r)] and one time [t], formalised on the dynamics of
    [Dynamics.v] (which is the paper's solution: [DynamicsProjection.v]);
    each is refuted by the ledger's witness (CLAIMS.md), evaluated exactly
    by [vm_compute]. The witnesses lie in the statement's domain: [N ≥ 2],
    [x⁰ ∈ K^N], [u⁰ ∈ C_{x⁰}], and for a statement that holds "for a.e. t"
    the failure is shown at two times of one open interval free of
    collisions ([FailsAe]), so neither time is a collision instant and the
    failure is not an isolated coincidence. The corrected statements are
    proved in the files named in each comment. *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Dynamics Multipliers Contacts VelocityProjection
  KktIntegral ProjMicroSolves.
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

(** ** Times that are not collision instants *)

(** No collision in the open interval [(a, b)]: on [[a, b)] the clusters
    are those at [a], and the path is affine,
    [x(s) = x(a) + (s − a) u(a)], so on [(a, b)] the path is differentiable
    with [ẋ = u(a)], and [u], [λ] are constant. *)
Definition CollisionFree (x0 u0 : list Q) (r a b : Q) : Prop :=
  a < b /\
  forall s, a <= s -> s < b ->
    clusters x0 u0 r s = clusters x0 u0 r a /\
    qeq_list (positions (dynamics x0 u0 r s))
             (map (fun p => fst p + (s - a) * snd p)
                  (combine (positions (dynamics x0 u0 r a)) (velocities (dynamics x0 u0 r a)))).

(** Every non-empty collision interval of [KktIntegral.collision_intervals]
    is free of collisions in its interior. *)
Lemma collision_free_of_interval (x0 u0 : list Q) (r T a b : Q) :
  0 <= T -> InK r x0 -> length u0 = length x0 ->
  In (a, b) (collision_intervals x0 u0 r T) -> a < b -> CollisionFree x0 u0 r a b.
Proof.
  intros HT HK L Hin Hab. split; [exact Hab|]. intros s Ha Hb. split.
  - pose proof (kkt_multiplier_is_integral x0 u0 r T 0 HT HK L) as H. cbv zeta in H.
    destruct H as (_ & Hc & _). exact (Hc a b Hin s Ha Hb).
  - exact (proj1 (path_affine_between_collisions x0 u0 r T HT HK L a b Hin s Ha Hb)).
Qed.

(** A statement [P t] about one datum, printed "for a.e. t", fails at the
    two times [t₁ < t₂] of one collision-free open interval. *)
Definition FailsAe (x0 u0 : list Q) (r t1 t2 : Q) (P : Q -> Prop) : Prop :=
  (exists a b, a < t1 /\ t1 < t2 /\ t2 < b /\ CollisionFree x0 u0 r a b) /\
  ~ P t1 /\ ~ P t2.

(** Proves [CollisionFree] for a closed datum from its collision intervals
    up to [T], [a] and [b] written as [vm_compute] prints them. *)
Ltac collision_free_closed T :=
  eapply (collision_free_of_interval _ _ _ T);
  [ qle_closed
  | intros i Hi; destruct i as [|[|i]]; simpl in Hi; try lia; qle_closed
  | reflexivity
  | vm_compute; tauto
  | vm_compute; reflexivity ].

(** The interval part of [FailsAe] for closed times: [a < t₁ < t₂ < b]
    by computation, then [tac] proves [CollisionFree]. *)
Ltac interval_closed tac :=
  refine (conj _ (conj _ (conj _ _))); [vm_compute; reflexivity ..| tac].

(** The shared datum [D0] of the ledger: N = 2, r = 1/4, x⁰ = (0, 3/2),
    u⁰ = (−8, −9); its only collision is at [t = 1], after which both
    particles move at [−17/2]. *)
Definition d0_x : list Q := [0; 3 # 2].
Definition d0_u : list Q := [-8; -9].
Definition d0_r : Q := 1 # 4.

Lemma d0_admissible : Admissible d0_x d0_u d0_r.
Proof. unfold d0_x, d0_u, d0_r. admissible_closed. Qed.

(** [D0] has no collision in [(0, 9/10)]. *)
Lemma d0_free_before : CollisionFree d0_x d0_u d0_r 0 (9 # 10).
Proof. unfold d0_x, d0_u, d0_r. collision_free_closed (9 # 10). Qed.

(** [D0] has no collision in [(1, 4)] (the interval is [(32#32, 4)] as
    [vm_compute] writes it, [32#32 = 1]). *)
Lemma d0_free_after : CollisionFree d0_x d0_u d0_r (32 # 32) 4.
Proof. unfold d0_x, d0_u, d0_r. collision_free_closed 4. Qed.

(** [w ∈ H_x] for a closed configuration of two particles apart. *)
Ltac in_H_closed :=
  let j := fresh "j" in let Hj := fresh "Hj" in let Hc := fresh "Hc" in
  intros j Hj Hc; destruct j as [|j];
  [ unfold Contact in Hc; vm_compute in Hc; discriminate Hc
  | vm_compute in Hj; lia ].

(** ** [lem:incl-HSN#proof-second-inclusion] and [eq:w-Hs-perp]

    Paper, proof of [lem:incl-HSN] (for every [t ≥ 0]): "Let us now show
    the second inclusion H^N_{x̃(t)} ⊂ [x⁰ + t u⁰]^⊥", and [eq:w-Hs-perp]
    (for a.e. [t]): "We also know by the previous lemma that
    ⟨x⁰ + t u⁰, w⟩ = 0" for [w ∈ H^N_{x(t)}]. Corrected
    ([⟨x⁰ + t u⁰ − x(t), w⟩ = 0]): [InclHSN.incl_HSN]. *)
Definition FreeFlightOrthogonalToHAt (x0 u0 : list Q) (r t : Q) : Prop :=
  forall w : list Q, length w = length x0 ->
    InH r (positions (dynamics x0 u0 r t)) w ->
    dot (free_flight x0 u0 t) w == 0.

Definition FreeFlightOrthogonalToH : Prop :=
  forall (x0 u0 : list Q) (r t : Q),
    Admissible x0 u0 r -> 0 <= t -> FreeFlightOrthogonalToHAt x0 u0 r t.

(** Ledger claim [lem:incl-HSN#proof-second-inclusion] (counterexample,
    the lemma is for every [t ≥ 0]): [D0] at [t = 0], [w = (0, 1)] (the
    cluster of particle 1): [⟨x⁰ + t u⁰, w⟩ = 3/2]. *)
Theorem free_flight_orthogonal_to_H_false : ~ FreeFlightOrthogonalToH.
Proof.
  intro H.
  specialize (H d0_x d0_u d0_r 0 d0_admissible (Qle_refl 0) [0; 1] eq_refl).
  assert (HH : InH d0_r (positions (dynamics d0_x d0_u d0_r 0)) [0; 1]) by in_H_closed.
  specialize (H HH). vm_compute in H. discriminate H.
Qed.

(** Ledger claim [eq:w-Hs-perp] (counterexample, a.e. [t]): [D0] at
    [t = 1/3] and [t = 2/3] in [(0, 9/10)], before the collision,
    [w = (1, 0)]: [⟨x⁰ + t u⁰, w⟩ = −8/3], [−16/3]. *)
Theorem w_Hs_perp_false :
  Admissible d0_x d0_u d0_r /\
  FailsAe d0_x d0_u d0_r (1 # 3) (2 # 3) (FreeFlightOrthogonalToHAt d0_x d0_u d0_r).
Proof.
  split; [exact d0_admissible|]. split; [|split].
  - exists 0, (9 # 10). interval_closed ltac:(apply d0_free_before).
  - intro H. specialize (H [1; 0] eq_refl).
    assert (HH : InH d0_r (positions (dynamics d0_x d0_u d0_r (1 # 3))) [1; 0]) by in_H_closed.
    specialize (H HH). vm_compute in H. discriminate H.
  - intro H. specialize (H [1; 0] eq_refl).
    assert (HH : InH d0_r (positions (dynamics d0_x d0_u d0_r (2 # 3))) [1; 0]) by in_H_closed.
    specialize (H HH). vm_compute in H. discriminate H.
Qed.

(** ** [prop:bound-micro#position-contraction]

    Paper, proof of [prop:bound-micro]: "From the projection formula we
    obtain ‖x(t)‖ ≤ ‖x⁰ + t u⁰‖" (every [t]). Witness (N = 2): r = 1/2,
    x⁰ = (0, 2), u⁰ = (−8, −9), t = 2 (its collision is at [t = 1]):
    [‖x(t)‖² = 1025/4 > ‖x⁰ + t u⁰‖² = 256]. *)
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

    Paper, proofs of [prop:bound-micro] and [prop:Linf-micro] (a.e. [t]):
    "using the relation N(λ_i(t) − λ_{i−1}(t)) = u_i(t) − u⁰_i".
    Corrected (the sign of [eq:dyn-micro]): [Multipliers.dyn_micro_identity]. *)
Definition MultiplierRelationAt (x0 u0 : list Q) (r t : Q) : Prop :=
  forall i : nat, (i < length x0)%nat ->
    qn (length x0) * (multiplier x0 u0 r t (S i) - multiplier x0 u0 r t i) ==
    nth i (velocities (dynamics x0 u0 r t)) 0 - nth i u0 0.

(** Ledger claim [prop:bound-micro#multiplier-relation] (counterexample,
    a.e. [t]): [D0] at [t = 2] and [t = 3] in [(1, 4)], after the
    collision, particle 0: [N(λ_1 − λ_0) = 1/2] but [u_1 − u⁰_1 = −1/2]. *)
Theorem multiplier_relation_false :
  Admissible d0_x d0_u d0_r /\ FailsAe d0_x d0_u d0_r 2 3 (MultiplierRelationAt d0_x d0_u d0_r).
Proof.
  split; [exact d0_admissible|]. split; [|split].
  - exists (32 # 32), 4. interval_closed ltac:(apply d0_free_after).
  - intro H. specialize (H 0%nat ltac:(simpl; lia)). vm_compute in H. discriminate H.
  - intro H. specialize (H 0%nat ltac:(simpl; lia)). vm_compute in H. discriminate H.
Qed.

(** ** [app:KKT]

    Paper, Appendix A: the KKT conditions "yield the existence of
    multipliers λ_i(t) ≥ 0 such that x(t) − (x⁰ + t u⁰) + N Σ λ_i(t)(e_i −
    e_{i+1}) = 0, λ_i(t)(x_{i+1} − x_i − 2r) = 0. This provides directly the
    multipliers and the Signorini condition introduced in the main text."
    Read as the ledger does, with the main text's [λ] of [eq:dyn-micro]
    (entry [j]: [x_j − (x⁰_j + t u⁰_j) + N(λ_{j+1} − λ_j) = 0], 0-based),
    for a.e. [t]. Corrected: the KKT multipliers are [μ = ∫λ]
    ([KktIntegral.kkt_multiplier_is_integral]). *)
Definition KktMultipliersAreLambdaAt (x0 u0 : list Q) (r t : Q) : Prop :=
  forall j : nat, (j < length x0)%nat ->
    nth j (positions (dynamics x0 u0 r t)) 0 - nth j (free_flight x0 u0 t) 0 +
    qn (length x0) * (multiplier x0 u0 r t (S j) - multiplier x0 u0 r t j) == 0.

(** The ledger's datum for [app:KKT]: N = 3, r = 1/6, x⁰ = (0, 4/3, 8/3),
    u⁰ = (7, −8, −9); collisions at [t = 1/15] and [t = 3/17]. *)
Definition kkt_x : list Q := [0; 4 # 3; 8 # 3].
Definition kkt_u : list Q := [7; -8; -9].
Definition kkt_r : Q := 1 # 6.

(** Ledger claim [app:KKT] (counterexample, a.e. [t]): the datum above at
    [t = 79/765] and [t = 107/765] in [(1/15, 3/17)], entry 0: the KKT
    multipliers are [μ = (14/153, 0)], [(28/153, 0)], but [λ = (5/2, 0)]. *)
Theorem kkt_multipliers_are_lambda_false :
  Admissible kkt_x kkt_u kkt_r /\
  FailsAe kkt_x kkt_u kkt_r (79 # 765) (107 # 765) (KktMultipliersAreLambdaAt kkt_x kkt_u kkt_r).
Proof.
  unfold kkt_x, kkt_u, kkt_r. split; [admissible_closed|]. split; [|split].
  - exists (108 # 1620), (11664 # 66096).
    interval_closed ltac:(collision_free_closed (3 # 17)).
  - intro H. specialize (H 0%nat ltac:(simpl; lia)). vm_compute in H. discriminate H.
  - intro H. specialize (H 0%nat ltac:(simpl; lia)). vm_compute in H. discriminate H.
Qed.

(** ** [eq:proj-u-micro]

    Paper, [prop:proj-velo-micro] (for a.e. [t]): "writing
    Ω^N_{x(t)} = ∪_k J_k(t), with J_k(t) = ⟦j_k(t), j_k(t) + L_k(t)⟧ […]
    u_i(t) = (1/L_k) Σ_{l=1}^{L_k} u⁰_{j_k+l} if i ∈ J_k, u_i(t) = u⁰_i
    if i ∉ Ω^N_{x(t)}" (read literally, as the ledger does: [J_k] is a
    maximal run of contact indices, [i] a particle index; contact [m]
    (0-based) joins particles [m] and [m + 1], the paper's contact index
    [m + 1]). Corrected: [VelocityProjection.velocity_orthogonal]. *)

(** The branch [i ∉ Ω]: particle [i] (0-based; the paper's [i + 1]) whose
    contact index [i + 1] is not a contact keeps its initial velocity. *)
Definition ProjUMicroOutsideAt (x0 u0 : list Q) (r t : Q) : Prop :=
  forall i : nat, (i < length x0)%nat ->
    ((S i < length x0)%nat -> ~ Contact r (positions (dynamics x0 u0 r t)) i) ->
    nth i (velocities (dynamics x0 u0 r t)) 0 == nth i u0 0.

(** Ledger claim [eq:proj-u-micro] (counterexample, a.e. [t]): [D0] at
    [t = 2] and [t = 3] in [(1, 4)], particle 1 (the paper's [i = 2 ∉ Ω]):
    the printed [u⁰_2 = −9] but [u_2(t) = −17/2]. *)
Theorem proj_u_micro_outside_false :
  Admissible d0_x d0_u d0_r /\ FailsAe d0_x d0_u d0_r 2 3 (ProjUMicroOutsideAt d0_x d0_u d0_r).
Proof.
  split; [exact d0_admissible|]. split; [|split].
  - exists (32 # 32), 4. interval_closed ltac:(apply d0_free_after).
  - intro H. specialize (H 1%nat ltac:(simpl; lia) ltac:(simpl; lia)).
    vm_compute in H. discriminate H.
  - intro H. specialize (H 1%nat ltac:(simpl; lia) ltac:(simpl; lia)).
    vm_compute in H. discriminate H.
Qed.

(** The branch [i ∈ J_k], in 0-based indices: the contacts [a, …, a + L]
    form a maximal run, particle [i ∈ ⟦a, a + L⟧],
    [u_i = (1/L) Σ_{l=1}^{L} u⁰_{a+l}]. *)
Definition ContactRun (r : Q) (x : list Q) (a L : nat) : Prop :=
  (S (a + L) < length x)%nat /\
  (forall m, (a <= m <= a + L)%nat -> Contact r x m) /\
  (a = 0%nat \/ ~ Contact r x (a - 1)) /\
  (S (S (a + L)) = length x \/ ~ Contact r x (S (a + L))).

Definition ProjUMicroFormulaAt (x0 u0 : list Q) (r t : Q) : Prop :=
  forall a L i : nat,
    ContactRun r (positions (dynamics x0 u0 r t)) a L -> (a <= i <= a + L)%nat ->
    nth i (velocities (dynamics x0 u0 r t)) 0 ==
    1 / qn L * qsum (map (fun l => nth (a + l) u0 0) (seq 1 L)).

(** The run [a = 0], [L = 1] of the datum N = 3, r = 1/2, x⁰ = (0, 2, 4),
    u⁰ = (2, 0, −1) at a closed time after its last collision. *)
Ltac contact_run_closed :=
  split; [vm_compute; lia|split; [|split; [left; reflexivity|left; reflexivity]]];
  let m := fresh "m" in let Hm := fresh "Hm" in
  intros m Hm; unfold Contact;
  destruct m as [|[|m]]; [vm_compute; reflexivity|vm_compute; reflexivity|lia].

(** Ledger claim [eq:proj-u-micro] (counterexample of the branch [i ∈ J_k],
    without any division by zero, a.e. [t]): N = 3, r = 1/2,
    x⁰ = (0, 2, 4), u⁰ = (2, 0, −1) (collisions at [t = 1/2] and
    [t = 3/4]), at [t = 1] and [t = 2] in [(3/4, 3)]: one cluster of three
    particles, contacts 0 and 1 ([a = 0], [L = 1]); the printed mean is
    [u⁰_1 = 0] but [u_0(t) = 1/3]. *)
Theorem proj_u_micro_formula_false_nonzero_run :
  Admissible [0; 2; 4] [2; 0; -1] (1 # 2) /\
  FailsAe [0; 2; 4] [2; 0; -1] (1 # 2) 1 2 (ProjUMicroFormulaAt [0; 2; 4] [2; 0; -1] (1 # 2)).
Proof.
  split; [admissible_closed|]. split; [|split].
  - exists (48 # 64), 3. interval_closed ltac:(collision_free_closed 3).
  - intro H.
    assert (HR : ContactRun (1 # 2) (positions (dynamics [0; 2; 4] [2; 0; -1] (1 # 2) 1)) 0 1)
      by contact_run_closed.
    specialize (H 0%nat 1%nat 0%nat HR ltac:(lia)). vm_compute in H. discriminate H.
  - intro H.
    assert (HR : ContactRun (1 # 2) (positions (dynamics [0; 2; 4] [2; 0; -1] (1 # 2) 2)) 0 1)
      by contact_run_closed.
    specialize (H 0%nat 1%nat 0%nat HR ltac:(lia)). vm_compute in H. discriminate H.
Qed.

(** ** [prop:proj-micro#uniqueness-identity]

    Paper, proof of [prop:proj-micro] (uniqueness, for a.e. [t]): for two
    solutions [x¹], [x²] with the same [u⁰] and [ξ^a = u⁰ − ẋ^a],
    "(N²/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩", with the paper's norm
    [‖v‖² = (1/N) Σ v_i²] and [⟨·,·⟩] the plain sum. Off the collision
    instants both paths are affine ([CollisionFree]) with [ẋ^a = u^a], so
    [d/dt ‖x¹ − x²‖² = (2/N) Σ (u¹_i − u²_i)(x¹_i − x²_i)]; that is the
    left side's derivative below. The corrected factor is [N/2]
    (the ledger's corrected row). *)
Definition UniquenessIdentityAt (x0 y0 u0 : list Q) (r t : Q) : Prop :=
  let x1 := positions (dynamics x0 u0 r t) in
  let x2 := positions (dynamics y0 u0 r t) in
  let v1 := velocities (dynamics x0 u0 r t) in
  let v2 := velocities (dynamics y0 u0 r t) in
  let n := qn (length x0) in
  n * n / 2 * (2 / n * dot (vsub v1 v2) (vsub x1 x2)) ==
  - dot (vsub (vsub u0 v1) (vsub u0 v2)) (vsub x1 x2).

(** The ledger's data: N = 2, r = 1/2, u⁰ = (−8/5, −9/5),
    x⁰ = (0, 6/5) (collision at [t = 1]) and the second datum
    x⁰ + (0, r) = (0, 17/10) (collision at [t = 7/2]). *)
Definition uniq_x : list Q := [0; 6 # 5].
Definition uniq_y : list Q := [0; 17 # 10].
Definition uniq_u : list Q := [-8 # 5; -9 # 5].
Definition uniq_r : Q := 1 # 2.

(** Ledger claim [prop:proj-micro#uniqueness-identity] (counterexample,
    a.e. [t]): at [t = 2] and [t = 3], both in [(1, 7/2)] where neither
    path has a collision, [(N²/2) d/dt ‖x¹ − x²‖² = −3/50] but
    [−⟨ξ¹ − ξ², x¹ − x²⟩ = −3/100] ([t = 2]), and [−1/50] vs [−1/100]
    ([t = 3]). *)
Theorem uniqueness_identity_false :
  Admissible uniq_x uniq_u uniq_r /\ Admissible uniq_y uniq_u uniq_r /\
  (exists a b, a < 2 /\ 3 < b /\ CollisionFree uniq_y uniq_u uniq_r a b) /\
  FailsAe uniq_x uniq_u uniq_r 2 3 (UniquenessIdentityAt uniq_x uniq_y uniq_u uniq_r).
Proof.
  unfold uniq_x, uniq_y, uniq_u, uniq_r.
  split; [admissible_closed|]. split; [admissible_closed|]. split; [|split; [|split]].
  - exists 0, (17500 # 5000).
    refine (conj _ (conj _ _)); [vm_compute; reflexivity ..| collision_free_closed (7 # 2)].
  - exists (2500 # 2500), (7 # 2). interval_closed ltac:(collision_free_closed (7 # 2)).
  - intro H. vm_compute in H. discriminate H.
  - intro H. vm_compute in H. discriminate H.
Qed.
