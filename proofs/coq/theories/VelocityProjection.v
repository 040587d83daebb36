(** * The velocity is the projection of [u⁰] onto [H_{x(t)}]
      ([prop:proj-micro#u-in-H], [eq:proj-micro-u]).

    Paper, [prop:proj-micro]: "Denoting u(t) := ẋ(t), one has
    u(t) ∈ H^N_{x(t)} for a.e. t ≥ 0, and more precisely
    u(t) = P_{H^N_{x(t)}}(u_0)", with ([df:H-micro])
    "H^N_x = {u ∈ R^N ; u_{j+1} = u_j for j ∈ Ω^N_x}".

    Our [u(t)] is the right derivative of [x] (the cluster velocities);
    both statements hold at every [t > 0]. At [t = 0] they need
    [u⁰ ∈ H_{x⁰}]: see [Contacts.v]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers Neighbours Contacts.
Import ListNotations.
Open Scope Q_scope.

(** [u ∈ H_x]: equal velocities across every contact of [x]. *)
Definition InH (r : Q) (x u : list Q) : Prop :=
  forall j, (S j < length x)%nat -> Contact r x j -> nth j u 0 == nth (S j) u 0.

(** Two consecutive clusters at [t > 0] that touch have one velocity:
    they are in order at time 0, so they did not separate, and they do not
    meet at [t], so they do not approach. *)
Lemma touching_same_velocity (t : Q) (a b : cluster) :
  0 < t -> Nonempty a -> Nonempty b -> center 0 a <= center 0 b ->
  (approaching a b = true -> t < meeting_time a b) ->
  center t a == center t b -> velocity a == velocity b.
Proof.
  intros Ht Na Nb H0 HF Hc.
  destruct (approaching a b) eqn:E.
  - specialize (HF eq_refl). pose proof (gap_meeting t a b Na Nb E) as G.
    pose proof (approaching_velocity a b E).
    assert (0 < (velocity a - velocity b) * (meeting_time a b - t))
      by (apply Qmult_lt_0_compat; lra).
    lra.
  - pose proof (not_approaching_velocity a b E).
    rewrite (center_linear t a Na), (center_linear t b Nb) in Hc.
    assert (0 <= t * (velocity b - velocity a)) by (apply Qmult_le_0_compat; lra).
    assert (t * (velocity b - velocity a) <= 0) by lra.
    assert (velocity b - velocity a <= 0).
    { apply Qnot_lt_le. intro Hlt.
      assert (0 < t * (velocity b - velocity a)) by (apply Qmult_lt_0_compat; lra). lra. }
    lra.
Qed.

(** Neighbours [i − 1], [i] in contact at [t > 0]: one translated position
    and one velocity. *)
Lemma contact_neighbours (x0 u0 : list Q) (r t : Q) (i : nat) :
  0 < t -> InK r x0 -> length u0 = length x0 -> (0 < i < length x0)%nat ->
  Contact r (positions (dynamics x0 u0 r t)) (i - 1) ->
  let cs := clusters x0 u0 r t in
  nth (i - 1) (spread velocity cs) 0 == nth i (spread velocity cs) 0.
Proof.
  intros Ht HK L Hi Hc cs.
  assert (Ht0 : 0 <= t) by lra.
  pose proof (position_gap x0 u0 r t i Ht0 HK L Hi) as G. cbv zeta in G.
  unfold Contact in Hc. replace (S (i - 1)) with i in Hc by lia.
  destruct (clusters_facts x0 u0 r t Ht0 HK L) as ((HN & _ & _) & _ & _).
  fold cs in HN, G.
  pose proof (clusters_ordered_at_0 x0 u0 r t HK) as HO0. fold cs in HO0.
  pose proof (clusters_final x0 u0 r t Ht0 HK) as HF. fold cs in HF.
  pose proof (adjacent_combine (fun a b => center 0 a <= center 0 b)
                (fun a b => approaching a b = true -> t < meeting_time a b)
                (fun a b => (Nonempty a /\ Nonempty b) /\ center 0 a <= center 0 b /\
                            (approaching a b = true -> t < meeting_time a b))
                cs HN HO0 HF ltac:(intros a b Na Nb H1 H2; cbv beta in *; tauto)) as HP.
  destruct (clusters_facts x0 u0 r t Ht0 HK L) as (_ & _ & Hl). fold cs in Hl.
  destruct (neighbours _ cs HN HP i ltac:(lia)) as [Hs|(a & b & ((Na & Nb) & H0 & H1) & Hf)].
  - apply Hs.
  - destruct (Hf velocity) as [-> ->]. destruct (Hf (center t)) as [E1 E2].
    rewrite E1, E2 in G. apply (touching_same_velocity t); auto. lra.
Qed.

(** Paper, [prop:proj-micro]: "u(t) ∈ H^N_{x(t)} for a.e. t ≥ 0". For every
    [N], [x⁰ ∈ K^N], any [u⁰], every rational [t > 0].
    Ledger claim: [prop:proj-micro#u-in-H]. *)
Theorem velocity_in_H (x0 u0 : list Q) (r t : Q) :
  0 < t -> InK r x0 -> length u0 = length x0 ->
  InH r (positions (dynamics x0 u0 r t)) (velocities (dynamics x0 u0 r t)).
Proof.
  intros Ht HK L j Hj Hc.
  assert (Lx : length (positions (dynamics x0 u0 r t)) = length x0).
  { rewrite positions_spread. unfold untranslate. rewrite untranslate_from_length, spread_length.
    apply (clusters_facts x0 u0 r t ltac:(lra) HK L). }
  rewrite Lx in Hj.
  pose proof (contact_neighbours x0 u0 r t (S j) Ht HK L ltac:(lia)) as H.
  replace (S j - 1)%nat with j in H by lia. rewrite velocities_spread. apply H. exact Hc.
Qed.

(** ** Orthogonality *)

(** A sum [Σ d_j w_j] vanishes when the partial sums of [d] vanish at every
    [k] where [w] jumps, and at the end (summation by parts). *)
Lemma dot_by_parts (d : list Q) :
  forall w c wp, length w = length d ->
  (forall k, (k < length d)%nat ->
     c + psum k d == 0 \/ nth k (wp :: w) 0 == nth k w 0) ->
  c + qsum d == 0 ->
  c * wp + dot d w == 0.
Proof.
  induction d as [|d1 d IH]; intros w c wp Lw Hk Hend.
  - destruct w; [|discriminate]. simpl in *. setoid_replace c with 0 by lra. ring.
  - destruct w as [|w1 w]; [discriminate|]. simpl in Lw, Hend |- *.
    assert (Hstep : c * wp == c * w1).
    { destruct (Hk 0%nat ltac:(simpl; lia)) as [H|H].
      - rewrite psum_0 in H. setoid_replace c with 0 by lra. ring.
      - simpl in H. rewrite H. reflexivity. }
    specialize (IH w (c + d1) w1 ltac:(lia)).
    assert (IH' : (c + d1) * w1 + dot d w == 0).
    { apply IH; [|lra].
      intros k Hk'. destruct (Hk (S k) ltac:(simpl; lia)) as [H|H].
      - left. rewrite psum_cons in H. lra.
      - right. exact H. }
    rewrite Hstep. lra.
Qed.

Lemma psum_vsub (k : nat) (a b : list Q) :
  length a = length b -> psum k (vsub a b) == psum k a - psum k b.
Proof.
  revert k b. induction a as [|x a IH]; intros k b L; destruct b as [|y b]; try discriminate.
  - unfold psum. rewrite !firstn_nil. simpl. ring.
  - destruct k as [|k]; [unfold psum; simpl; ring|].
    simpl vsub. rewrite !psum_cons, IH by (simpl in L; lia). ring.
Qed.

(** Paper, [eq:proj-micro-u]: "u(t) = P_{H^N_{x(t)}}(u_0)". [H_{x(t)}] is a
    linear subspace, so the projection is the [u ∈ H] with [u⁰ − u ⊥ H]:
    this is what we prove, for every [N], [x⁰ ∈ K^N], any [u⁰], every
    rational [t > 0] ([velocity_in_H] is the first half).
    Ledger claim: [eq:proj-micro-u]. *)
Theorem velocity_orthogonal (x0 u0 : list Q) (r t : Q) (w : list Q) :
  0 < t -> InK r x0 -> length u0 = length x0 -> length w = length x0 ->
  InH r (positions (dynamics x0 u0 r t)) w ->
  dot (vsub u0 (velocities (dynamics x0 u0 r t))) w == 0.
Proof.
  intros Ht HK L Lw HH.
  assert (Ht0 : 0 <= t) by lra.
  set (u := velocities (dynamics x0 u0 r t)).
  assert (Lu : length u = length x0).
  { unfold u. rewrite velocities_spread, spread_length. apply (clusters_facts x0 u0 r t Ht0 HK L). }
  assert (Lx : length (positions (dynamics x0 u0 r t)) = length x0).
  { rewrite positions_spread. unfold untranslate. rewrite untranslate_from_length, spread_length.
    apply (clusters_facts x0 u0 r t Ht0 HK L). }
  setoid_replace (dot (vsub u0 u) w) with (0 * 0 + dot (vsub u0 u) w) by ring.
  apply dot_by_parts.
  - rewrite vsub_length; lia.
  - intros k Hk. rewrite vsub_length in Hk by lia. rewrite psum_vsub by lia.
    destruct (multiplier_gap x0 u0 r t k Ht0 HK L ltac:(lia)) as [_ [H|H]].
    + left. fold u in H. lra.
    + destruct k as [|k]; [left; unfold psum; simpl; lra|]. right.
      simpl nth at 1.
      (* particles k and k+1 share a cluster: they are in contact *)
      assert (Hc : Contact r (positions (dynamics x0 u0 r t)) k).
      { unfold Contact.
        pose proof (position_gap x0 u0 r t (S k) Ht0 HK L ltac:(lia)) as G. cbv zeta in G.
        replace (S k - 1)%nat with k in G, H by lia. rewrite G, (H (center t)). ring. }
      apply HH; [lia|exact Hc].
  - rewrite <- psum_all, vsub_length, psum_vsub by lia. rewrite L.
    destruct (multiplier_ends x0 u0 r t Ht0 HK L) as [_ HN]. unfold multiplier in HN.
    fold u in HN. destruct (length x0) as [|n] eqn:E.
    + unfold psum. simpl. ring.
    + assert (Hn : 0 < qn (S n)) by (apply qn_pos; lia).
      setoid_replace (psum (S n) u0 - psum (S n) u)
        with ((psum (S n) u0 - psum (S n) u) / qn (S n) * qn (S n)) by (field; lra).
      rewrite HN. ring.
Qed.
