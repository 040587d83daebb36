(** * The oracle's [--dynamics] path: the whole state from the event-driven
    dynamics.

    [dynamics_state r t x⁰ u⁰] is the state the oracle prints with
    [--dynamics], in the record of [Oracle.state_at] (one printed state for
    both paths): the positions and velocities of [Dynamics.dynamics] in
    lowest terms, the multipliers by the same incremental sum as the oracle
    ([Oracle.multipliers_from]), the contact clusters of the positions
    ([ContactClusters.contact_clusters]). Proved:
    - [dynamics_state_multipliers]: its multipliers are
      [Multipliers.multiplier] ([eq:dyn-micro]), for [t ≥ 0];
    - [dynamics_state_clusters]: its clusters are the contact clusters of its
      positions;
    - [dynamics_state_is_state_at]: for [t > 0] it is, field by field, the
      state [Oracle.state_at] prints (positions and velocities entrywise,
      multipliers entrywise, clusters equal).

    [Dynamics.state] (positions and velocities) stays the dynamics' own
    record: every theorem on the dynamics reads it, and the multipliers are
    defined from it ([Multipliers.multiplier]). *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection Oracle RightDerivative Dynamics
  Multipliers VelocityProjection OracleIsDynamics OracleMultipliers ContactClusters.
Import ListNotations.
Open Scope Q_scope.

(** The state of the event-driven dynamics at time [t], as the oracle
    prints it. *)
Definition dynamics_state (r t : Q) (x0 u0 : list Q) : Oracle.state :=
  let d := dynamics x0 u0 r t in
  let x := map Qred (positions d) in
  let u := map Qred (velocities d) in
  Oracle.mkstate x u (multipliers_from 0 (qn (length u0)) u0 u) (contact_clusters r x).

Lemma qeq_list_map_Qred (l : list Q) : qeq_list (map Qred l) l.
Proof. induction l; constructor; [apply Qred_correct|assumption]. Qed.

Lemma multipliers_from_cons (acc n a b : Q) (u0 u : list Q) :
  u0 <> [] \/ u <> [] ->
  multipliers_from acc n (a :: u0) (b :: u) =
  Qred (acc + (a - b) / n) :: multipliers_from (Qred (acc + (a - b) / n)) n u0 u.
Proof. intro H. destruct u0, u; [destruct H; congruence|reflexivity..]. Qed.

(** The incremental sum only sees the values of its arguments. *)
Lemma multipliers_from_qeq (u0 : list Q) : forall u u' acc acc' n n',
  acc == acc' -> n == n' -> qeq_list u u' ->
  qeq_list (multipliers_from acc n u0 u) (multipliers_from acc' n' u0 u').
Proof.
  induction u0 as [|a u0 IH]; intros u u' acc acc' n n' Ea En E; [destruct E; constructor|].
  destruct E as [|b b' u u' Eb E]; [destruct u0; simpl; constructor|].
  assert (Eacc : Qred (acc + (a - b) / n) == Qred (acc' + (a - b') / n'))
    by (rewrite !Qred_correct, Ea, En, Eb; reflexivity).
  destruct u0 as [|a2 u0]; destruct E as [|c c' u u' Ec E];
    [apply Forall2_nil| | |];
    rewrite (multipliers_from_cons acc n a b), (multipliers_from_cons acc' n' a b')
      by (first [left; discriminate|right; discriminate]);
    (constructor; [exact Eacc|apply IH; [exact Eacc|exact En|]]);
    [constructor; assumption|apply Forall2_nil|constructor; assumption].
Qed.

(** For every [N ≥ 1], [x⁰ ∈ K^N], any [u⁰] and rational [t ≥ 0], the
    multipliers of the [--dynamics] path are [λ_1(t) … λ_{N−1}(t)] of
    [Multipliers.multiplier], entry by entry ([eq:dyn-micro]). *)
Theorem dynamics_state_multipliers (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (0 < length x0)%nat ->
  let m := st_multipliers (dynamics_state r t x0 u0) in
  length m = (length x0 - 1)%nat /\
  forall j, (S j < length x0)%nat -> nth j m 0 == multiplier x0 u0 r t (S j).
Proof.
  intros Ht HK L Hpos m.
  set (v := velocities (dynamics x0 u0 r t)).
  assert (Lv : length v = length x0).
  { unfold v. rewrite velocities_spread, spread_length.
    apply (clusters_facts x0 u0 r t Ht HK L). }
  assert (Hm : m = multipliers_from 0 (qn (length u0)) u0 (map Qred v)) by reflexivity.
  rewrite Hm, L.
  destruct (multipliers_from_spec u0 (map Qred v) 0 (qn (length x0))
              ltac:(rewrite map_length; lia) ltac:(lia)) as [ML MN].
  rewrite L in ML, MN. split; [exact ML|].
  intros j Hj. rewrite (MN j Hj), psum_vsub by (rewrite map_length; lia).
  unfold multiplier. fold v. rewrite (qeq_list_psum _ _ (qeq_list_map_Qred v)). ring.
Qed.

(** The clusters of the [--dynamics] path are the contact clusters of its
    positions (by construction), for every input. *)
Theorem dynamics_state_clusters (r t : Q) (x0 u0 : list Q) :
  st_clusters (dynamics_state r t x0 u0) =
  contact_clusters r (st_positions (dynamics_state r t x0 u0)).
Proof. reflexivity. Qed.

(** For every [N], [x⁰ ∈ K^N], any [u⁰] and rational [t > 0], the two
    extracted paths print the same state: positions, velocities and
    multipliers entry by entry, clusters equal. *)
Theorem dynamics_state_is_state_at (x0 u0 : list Q) (r t : Q) :
  0 < t -> InK r x0 -> length u0 = length x0 ->
  qeq_list (st_positions (dynamics_state r t x0 u0)) (st_positions (state_at r t x0 u0)) /\
  qeq_list (st_velocities (dynamics_state r t x0 u0)) (st_velocities (state_at r t x0 u0)) /\
  qeq_list (st_multipliers (dynamics_state r t x0 u0)) (st_multipliers (state_at r t x0 u0)) /\
  st_clusters (dynamics_state r t x0 u0) = st_clusters (state_at r t x0 u0).
Proof.
  intros Ht HK L.
  assert (Ep : qeq_list (st_positions (dynamics_state r t x0 u0))
                        (st_positions (state_at r t x0 u0))).
  { eapply qeq_list_trans; [apply qeq_list_map_Qred|].
    apply qeq_list_sym, oracle_positions_are_dynamics; [lra|exact HK|exact L]. }
  assert (Ev : qeq_list (st_velocities (dynamics_state r t x0 u0))
                        (st_velocities (state_at r t x0 u0))).
  { eapply qeq_list_trans; [apply qeq_list_map_Qred|].
    apply qeq_list_sym, oracle_velocities_are_dynamics; [exact Ht|exact HK|exact L]. }
  split; [exact Ep|split; [exact Ev|split]].
  - apply multipliers_from_qeq; [reflexivity|reflexivity|exact Ev].
  - rewrite dynamics_state_clusters, state_clusters_spec. apply contact_clusters_qeq, Ep.
Qed.
