(** * The one-sided Lipschitz bound on the velocities ([prop:Oleinik]). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers Neighbours.
Import ListNotations.
Open Scope Q_scope.

(** The bound for two consecutive clusters [a], [b], in order at time 0
    and at time [t]. *)
Lemma oleinik_pair (r t : Q) (a b : cluster) :
  0 < t -> 0 < r -> Nonempty a -> Nonempty b ->
  center 0 a <= center 0 b -> center t a <= center t b ->
  (velocity b - velocity a) / (center t b - center t a + 2 * r) < 1 / t.
Proof.
  intros Ht Hr Na Nb H0 Htb.
  rewrite (center_linear t a Na), (center_linear t b Nb) in *.
  apply Qlt_shift_div_r; [lra|].
  setoid_replace (1 / t * (center 0 b + t * velocity b - (center 0 a + t * velocity a) + 2 * r))
    with ((center 0 b + t * velocity b - (center 0 a + t * velocity a) + 2 * r) / t)
    by (field; lra).
  apply Qlt_shift_div_l; [exact Ht|].
  setoid_replace ((velocity b - velocity a) * t) with (t * velocity b - t * velocity a) by ring.
  lra.
Qed.

(** Paper, [prop:Oleinik] ([eq:Oleinik-micro]): "(u_i(t) − u_{i−1}(t)) /
    (x_i(t) − x_{i−1}(t)) < 1/t for all t > 0, i ∈ ⟦1, N⟧" (for [i ≥ 2]:
    [x_0] does not exist). Here for the 0-based neighbours [i − 1], [i],
    [0 < i < N], every [N], [x⁰ ∈ K^N] with [r > 0] (the paper's proof uses
    [x_i(0) ≥ x_{i−1}(0) + 2r > x_{i−1}(0)]), any [u⁰], rational [t > 0].
    Ledger claim: [prop:Oleinik]. *)
Theorem oleinik (x0 u0 : list Q) (r t : Q) (i : nat) :
  0 < t -> 0 < r -> InK r x0 -> length u0 = length x0 -> (0 < i < length x0)%nat ->
  let x := positions (dynamics x0 u0 r t) in
  let u := velocities (dynamics x0 u0 r t) in
  (nth i u 0 - nth (i - 1) u 0) / (nth i x 0 - nth (i - 1) x 0) < 1 / t.
Proof.
  intros Ht Hr HK L Hi x u.
  assert (Ht0 : 0 <= t) by lra.
  pose proof (position_gap x0 u0 r t i Ht0 HK L Hi) as G. cbv zeta in G. fold x in G.
  destruct (clusters_facts x0 u0 r t Ht0 HK L) as ((HN & _ & HO) & _ & Hl).
  set (cs := clusters x0 u0 r t) in *.
  pose proof (clusters_ordered_at_0 x0 u0 r t HK) as HO0. fold cs in HO0.
  pose proof (adjacent_combine _ _
                (fun a b => (Nonempty a /\ Nonempty b) /\
                            center 0 a <= center 0 b /\ center t a <= center t b)
                cs HN HO0 HO ltac:(intros a b Na Nb H1 H2; simpl; tauto)) as HP.
  unfold u. rewrite velocities_spread. fold cs.
  destruct (neighbours _ cs HN HP i ltac:(lia)) as [Hs|(a & b & ((Na & Nb) & H0 & H1) & Hf)].
  - rewrite (Hs velocity). setoid_replace (nth i (spread velocity cs) 0 - nth i (spread velocity cs) 0)
      with 0 by ring. unfold Qdiv. rewrite Qmult_0_l.
    apply Qlt_shift_div_l; [exact Ht|]. lra.
  - rewrite G. destruct (Hf velocity) as [-> ->]. destruct (Hf (center t)) as [-> ->].
    apply oleinik_pair; assumption.
Qed.
