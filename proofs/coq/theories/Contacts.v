(** * Contacts do not always persist from time 0 ([df:H-micro#contacts-grow]).

    Paper, after [df:H-micro]: "In particular the set of active constraints
    is non-decreasing in time. […] if t ↦ x(t) is a solution of the
    microscopic dynamics, then for all s ≤ t, ∂I_{K^N}(x(s)) ⊂ ∂I_{K^N}(x(t)),
    or, equivalently, N_{x(s)}K^N ⊂ N_{x(t)}K^N for all s ≤ t", for
    [x⁰ ∈ K^N] and [u⁰ ∈ C^N_{x⁰}] as in [prop:proj-micro].

    The inclusion of normal cones is the inclusion of the sets of active
    constraints [Ω_{x(s)} ⊂ Ω_{x(t)}] ([df:Omega-micro]). It fails at
    [s = 0] for data of [C_{x⁰} \ H_{x⁰}]: two particles touching at time 0
    whose velocities separate them. *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Dynamics.
Import ListNotations.
Open Scope Q_scope.

(** Particles [j] and [j+1] (indices from 0) are in contact
    ([df:Omega-micro]: [x_{j+1} = x_j + 2r]). *)
Definition Contact (r : Q) (x : list Q) (j : nat) : Prop :=
  nth (S j) x 0 - nth j x 0 == 2 * r.

(** The cone [C^N_x] of admissible initial velocities: particles in
    contact do not interpenetrate, [u_j ≤ u_{j+1}] wherever they touch. *)
Definition InC (r : Q) (x u : list Q) : Prop :=
  forall j, (S j < length x)%nat -> Contact r x j -> nth j u 0 <= nth (S j) u 0.

(** The printed statement: for data [x⁰ ∈ K^N], [u⁰ ∈ C_{x⁰}], every
    contact present at time [s ≥ 0] is present at every [t ≥ s]. *)
Definition ContactsGrowFromZero : Prop :=
  forall (x0 u0 : list Q) (r s t : Q) (j : nat),
    length u0 = length x0 -> 0 < r -> InK r x0 -> InC r x0 u0 -> 0 <= s -> s <= t ->
    (S j < length x0)%nat ->
    Contact r (positions (dynamics x0 u0 r s)) j ->
    Contact r (positions (dynamics x0 u0 r t)) j.

(** The ledger's witness ([df:H-micro#contacts-grow], N = 2): radius 1/4,
    positions (0, 1/2), velocities (−8, 3); particles 0 and 1 touch at
    [s = 0] and are apart at [t = 1]. *)
Definition witness_x0 : list Q := [0; 1 # 2].
Definition witness_u0 : list Q := [-8; 3].
Definition witness_r : Q := 1 # 4.

(** Ledger claim [df:H-micro#contacts-grow] (counterexample): the printed
    statement is false. *)
Theorem contacts_grow_from_zero_false : ~ ContactsGrowFromZero.
Proof.
  intro H.
  assert (HK : InK witness_r witness_x0).
  { intros i Hi. destruct i as [|i]; [|simpl in Hi; lia].
    unfold witness_r. simpl. unfold Qle. simpl. lia. }
  assert (HC : InC witness_r witness_x0 witness_u0).
  { intros j Hj _. destruct j as [|j]; [|simpl in Hj; lia].
    simpl. unfold Qle. simpl. lia. }
  assert (H0 : Contact witness_r (positions (dynamics witness_x0 witness_u0 witness_r 0)) 0).
  { unfold Contact. vm_compute. reflexivity. }
  specialize (H witness_x0 witness_u0 witness_r 0 1 0%nat eq_refl
                ltac:(unfold witness_r, Qlt; simpl; lia) HK HC
                ltac:(apply Qle_refl) ltac:(unfold Qle; simpl; lia)
                ltac:(simpl; lia) H0).
  unfold Contact in H. vm_compute in H. discriminate H.
Qed.
