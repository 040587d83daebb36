(** * [⟨u⁰ − u(t), u(t)⟩ = 0] and [‖u(t)‖ ≤ ‖u⁰‖]
      ([prop:proj-velo-micro#step1], [prop:bound-micro#velocity-bound]). *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection Dynamics ClusterAlgebra
  DynamicsInvariant DynamicsProjection Multipliers VelocityProjection.
Import ListNotations.
Open Scope Q_scope.

(** Paper, proof of [prop:proj-velo-micro], "Step 1. ⟨u⁰ − u(t), u(t)⟩ ≥ 0":
    it is [= 0], for every [N], [x⁰ ∈ K^N], any [u⁰], rational [t ≥ 0]
    ([u(t)] is constant on clusters, where the partial sums of [u⁰ − u(t)]
    do not vanish). Ledger claim: [prop:proj-velo-micro#step1]. *)
Theorem velocity_step1 (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  dot (vsub u0 (velocities (dynamics x0 u0 r t))) (velocities (dynamics x0 u0 r t)) == 0.
Proof.
  intros Ht HK L.
  set (u := velocities (dynamics x0 u0 r t)).
  assert (Lu : length u = length x0).
  { unfold u. rewrite velocities_spread, spread_length. apply (clusters_facts x0 u0 r t Ht HK L). }
  setoid_replace (dot (vsub u0 u) u) with (0 * 0 + dot (vsub u0 u) u) by ring.
  apply dot_by_parts.
  - rewrite vsub_length; lia.
  - intros k Hk. rewrite vsub_length in Hk by lia. rewrite psum_vsub by lia.
    destruct (multiplier_gap x0 u0 r t k Ht HK L ltac:(lia)) as [_ [H|H]].
    + left. fold u in H. lra.
    + destruct k as [|k]; [left; unfold psum; simpl; lra|]. right. simpl nth at 1.
      specialize (H velocity). replace (S k - 1)%nat with k in H by lia.
      unfold u. rewrite velocities_spread. exact H.
  - rewrite <- psum_all, vsub_length, psum_vsub by lia. rewrite L.
    destruct (multiplier_ends x0 u0 r t Ht HK L) as [_ HN]. unfold multiplier in HN.
    fold u in HN. destruct (length x0) as [|n] eqn:E; [unfold psum; simpl; ring|].
    assert (Hn : 0 < qn (S n)) by (apply qn_pos; lia).
    setoid_replace (psum (S n) u0 - psum (S n) u)
      with ((psum (S n) u0 - psum (S n) u) / qn (S n) * qn (S n)) by (field; lra).
    rewrite HN. ring.
Qed.

Lemma vsub_zeros (a : list Q) : qeq_list (vsub a (repeat 0 (length a))) a.
Proof. induction a as [|x a IH]; constructor; [simpl; ring|exact IH]. Qed.

Lemma sqnorm_qeq (a b : list Q) : qeq_list a b -> sqnorm a == sqnorm b.
Proof. induction 1 as [|x y a b H _ IH]; simpl; [reflexivity|rewrite H, IH; reflexivity]. Qed.

Lemma dot_qeq_r (a b b' : list Q) : qeq_list b b' -> dot a b == dot a b'.
Proof.
  intro H. revert a. induction H as [|x y b b' Hxy _ IH]; intros [|z a]; simpl; try reflexivity.
  rewrite Hxy, IH. reflexivity.
Qed.

(** Paper, [prop:bound-micro] (the velocity part, "‖u(t)‖ ≤ ‖u⁰‖"): for
    every [N], [x⁰ ∈ K^N], any [u⁰], rational [t ≥ 0], [Σ u_i(t)² ≤ Σ (u⁰_i)²].
    Ledger claim: [prop:bound-micro#velocity-bound]. *)
Theorem velocity_bound (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  sqnorm (velocities (dynamics x0 u0 r t)) <= sqnorm u0.
Proof.
  intros Ht HK L.
  set (u := velocities (dynamics x0 u0 r t)).
  assert (Lu : length u = length x0).
  { unfold u. rewrite velocities_spread, spread_length. apply (clusters_facts x0 u0 r t Ht HK L). }
  pose proof (pythagoras u0 u (repeat 0 (length u)) ltac:(lia) ltac:(rewrite repeat_length; lia)) as P.
  rewrite (sqnorm_qeq _ _ (vsub_zeros u)), (dot_qeq_r _ _ _ (vsub_zeros u)) in P.
  replace (length u) with (length u0) in P by lia.
  rewrite (sqnorm_qeq _ _ (vsub_zeros u0)) in P.
  pose proof (velocity_step1 x0 u0 r t Ht HK L) as S1. fold u in S1. rewrite S1 in P.
  pose proof (sqnorm_nonneg (vsub u0 u)). lra.
Qed.
