(** * The oracle's multipliers are the multipliers [λ] of [eq:dyn-micro].

    [Oracle.state_at] lists [λ_1 … λ_{N−1}] computed incrementally,
    [λ_i = λ_{i−1} + (u⁰_i − u_i)/N] ([Oracle.multipliers_from]);
    [Multipliers.multiplier] defines [λ_k = (1/N) Σ_{j<k} (u⁰_j − u_j(t))]
    from the dynamics. For [t > 0] they are equal entry by entry. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection Oracle RightDerivative Dynamics
  OracleIsDynamics Multipliers VelocityProjection.
Import ListNotations.
Open Scope Q_scope.

(** The incremental sum is the partial sum: entry [j] of
    [multipliers_from acc n u0 u] is [acc + Σ_{i ≤ j} (u⁰_i − u_i)/n]; there
    are [N − 1] entries. *)
Lemma multipliers_from_spec (u0 : list Q) : forall u acc n,
  length u = length u0 -> (0 < length u0)%nat ->
  length (multipliers_from acc n u0 u) = (length u0 - 1)%nat /\
  forall j, (S j < length u0)%nat ->
    nth j (multipliers_from acc n u0 u) 0 == acc + psum (S j) (vsub u0 u) / n.
Proof.
  induction u0 as [|a u0 IH]; intros u acc n L Hpos; [simpl in Hpos; lia|].
  destruct u as [|b u]; [discriminate|].
  destruct u0 as [|a' u0].
  - destruct u as [|b' u]; [|discriminate]. split; [reflexivity|].
    intros j Hj. simpl in Hj. lia.
  - destruct u as [|b' u]; [discriminate|].
    change (multipliers_from acc n (a :: a' :: u0) (b :: b' :: u)) with
      (Qred (acc + (a - b) / n) :: multipliers_from (Qred (acc + (a - b) / n)) n (a' :: u0) (b' :: u)).
    simpl in L.
    destruct (IH (b' :: u) (Qred (acc + (a - b) / n)) n ltac:(simpl; lia) ltac:(simpl; lia))
      as [IL IN].
    split; [simpl in IL |- *; lia|].
    intros [|j] Hj.
    + cbn [nth]. eapply Qeq_trans; [apply Qred_correct|]. unfold psum. simpl. unfold Qdiv. ring.
    + cbn [nth]. eapply Qeq_trans; [apply (IN j); simpl in Hj |- *; lia|].
      pose proof (Qred_correct (acc + (a - b) / n)) as Hq. rewrite Hq.
      change (vsub (a :: a' :: u0) (b :: b' :: u)) with ((a - b) :: vsub (a' :: u0) (b' :: u)).
      rewrite psum_cons. unfold Qdiv. ring.
Qed.

(** For every [N ≥ 1], [x⁰ ∈ K^N], any [u⁰] and rational [t > 0], the
    oracle's multipliers are [λ_1(t) … λ_{N−1}(t)] of [Multipliers.multiplier]
    entry by entry ([eq:dyn-micro]; [λ_0 = λ_N = 0] are not listed). *)
Theorem oracle_multipliers_are_multiplier (x0 u0 : list Q) (r t : Q) :
  0 < t -> InK r x0 -> length u0 = length x0 -> (0 < length x0)%nat ->
  let m := st_multipliers (state_at r t x0 u0) in
  length m = (length x0 - 1)%nat /\
  forall j, (S j < length x0)%nat -> nth j m 0 == multiplier x0 u0 r t (S j).
Proof.
  intros Ht HK L Hpos m.
  pose proof (oracle_velocities_are_dynamics x0 u0 r t Ht HK L) as E.
  set (u := st_velocities (state_at r t x0 u0)) in E.
  assert (Lv : length (velocities (dynamics x0 u0 r t)) = length x0).
  { rewrite velocities_spread, spread_length.
    apply (clusters_facts x0 u0 r t ltac:(lra) HK L). }
  assert (Lu : length u = length u0) by (rewrite (qeq_list_length _ _ E); lia).
  assert (Hm : m = multipliers_from 0 (qn (length u0)) u0 u) by reflexivity.
  rewrite Hm. rewrite L in Lu |- *.
  destruct (multipliers_from_spec u0 u 0 (qn (length x0)) ltac:(lia) ltac:(lia)) as [ML MN].
  rewrite L in ML, MN. split; [exact ML|].
  intros j Hj. rewrite (MN j Hj), psum_vsub by lia.
  unfold multiplier. rewrite (qeq_list_psum _ _ E). ring.
Qed.
