(** * The projection path solves the differential inclusion and is
      Lipschitz ([prop:proj-micro], existence part).

    Paper, [prop:proj-micro]: "there exists a unique solution x to
    (eq:micro-f0-lagr) [ẋ(t) ∈ u⁰ − ∂I_{K^N}(x(t)), x(0) = x⁰] … given by
    x(t) = P_{K^N}(x⁰ + t u⁰) … Moreover x is Lipschitz continuous".

    Over [Q], for the path [x(t)] of the dynamics (which is
    [P_K(x⁰ + t u⁰)], [DynamicsIsProjK.dynamics_is_proj_K]):
    - [path_affine_between_collisions]: on each collision interval [[a, b)]
      ([KktIntegral.collision_intervals], which partition [[0, t]]) the path
      is affine, [x(s) = x(a) + (s − a) u(a)] and [u(s) = u(a)], so on the
      open interval [ẋ = u];
    - [velocity_in_normal_cone]: [u⁰ − u(s) ∈ N_{x(s)} K^N] for every
      [s ≥ 0], i.e. [⟨u⁰ − u(s), c − x(s)⟩ ≤ 0] for every [c ∈ K^N];
    - [path_lipschitz]: [‖x(t) − x(s)‖ ≤ |t − s| ‖u⁰‖] (squared).
    Uniqueness is not here. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers Neighbours VelocityProjection Semigroup DynamicsIsProjK
  KktIntegral.
Import ListNotations.
Open Scope Q_scope.

(** ** Affine between collisions *)

Lemma untranslate_affine_from (r h : Q) (a : list Q) : forall v m,
  length v = length a ->
  qeq_list (untranslate_from m r (map (fun p => fst p + h * snd p) (combine a v)))
           (map (fun p => fst p + h * snd p) (combine (untranslate_from m r a) v)).
Proof.
  induction a as [|x a IH]; intros [|y v] m L; simpl in *; try discriminate; constructor.
  - ring.
  - apply IH. lia.
Qed.

Lemma spread_qeq (f g : cluster -> Q) (cs : list cluster) :
  (forall c, In c cs -> f c == g c) -> qeq_list (spread f cs) (spread g cs).
Proof.
  intro H. induction cs as [|c cs IH]; [constructor|].
  unfold spread in *. simpl. apply Forall2_app.
  - apply qeq_list_repeat. apply H. left. reflexivity.
  - apply IH. intros d Hd. apply H. right. exact Hd.
Qed.

(** The start of a collision interval is a time [≥ 0]. *)
Lemma collision_interval_start (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 ->
  forall a b, In (a, b) (collision_intervals x0 u0 r t) -> 0 <= a /\ a <= b.
Proof.
  intros Ht HK a b Hin. unfold collision_intervals in Hin.
  apply in_map_iff in Hin. destruct Hin as (((a' & b') & c) & Ee & Hin').
  simpl in Ee. injection Ee as -> ->.
  pose proof (singletons_invariant x0 u0 r HK) as HI0.
  exact (pieces_ordered t _ 0 _ HI0 Ht a b c Hin').
Qed.

(** On each collision interval [[a, b)] the path moves at the velocity
    [u(a)]: [x(s) = x(a) + (s − a) u(a)] and [u(s) = u(a)] entry by entry,
    for every [N], [x⁰ ∈ K^N], any [u⁰], rational [t ≥ 0]. Ledger claim:
    [prop:proj-micro]. *)
Theorem path_affine_between_collisions (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  forall a b, In (a, b) (collision_intervals x0 u0 r t) -> forall s, a <= s -> s < b ->
  qeq_list (positions (dynamics x0 u0 r s))
           (map (fun p => fst p + (s - a) * snd p)
                (combine (positions (dynamics x0 u0 r a)) (velocities (dynamics x0 u0 r a)))) /\
  velocities (dynamics x0 u0 r s) = velocities (dynamics x0 u0 r a).
Proof.
  intros Ht HK L a b Hin s Ha Hb.
  destruct (kkt_multiplier_is_integral x0 u0 r t 0 Ht HK L) as (_ & Hc & _).
  pose proof (Hc a b Hin s Ha Hb) as E.
  rewrite !positions_spread, !velocities_spread, E. split; [|reflexivity].
  destruct (collision_interval_start x0 u0 r t Ht HK a b Hin) as [Ha0 _].
  set (cs := clusters x0 u0 r a).
  assert (HN : Forall Nonempty cs) by apply (clusters_invariant x0 u0 r a Ha0 HK).
  unfold untranslate.
  eapply qeq_list_trans; [|apply untranslate_affine_from; rewrite !spread_length; reflexivity].
  apply untranslate_qeq.
  change (spread (center a) cs) with (translated_positions a cs).
  rewrite moved_spread. apply spread_qeq.
  intros c Hin'. rewrite Forall_forall in HN. symmetry. apply moved_center, HN, Hin'.
Qed.

(** ** The inclusion [u⁰ − u ∈ N_x K^N] *)

(** Summation by parts, as an inequality: with [c] the partial sum so far
    and [wp] the previous entry of [w], [c·wp + ⟨d, w⟩ ≤ 0] when every
    partial sum is non-negative, vanishes at the end, and is zero unless
    [w] does not decrease there. *)
Lemma dot_by_parts_le (d : list Q) : forall w c wp,
  length w = length d ->
  (forall k, (k < length d)%nat ->
     0 <= c + psum k d /\ (c + psum k d == 0 \/ nth k (wp :: w) 0 <= nth k w 0)) ->
  c + qsum d == 0 -> c * wp + dot d w <= 0.
Proof.
  induction d as [|d1 d IH]; intros w c wp Lw Hk Hend.
  - destruct w; [|discriminate]. simpl in *. setoid_replace c with 0 by lra. lra.
  - destruct w as [|w1 w]; [discriminate|]. simpl in Lw, Hend |- *.
    destruct (Hk 0%nat ltac:(simpl; lia)) as [H0 H1]. rewrite psum_0 in H0, H1.
    simpl nth in H1.
    assert (Hstep : c * (wp - w1) <= 0).
    { destruct H1 as [H1|H1].
      - setoid_replace c with 0 by lra. lra.
      - assert (0 <= c * (w1 - wp)) by (apply Qmult_le_0_compat; lra). lra. }
    assert (Hrest : (c + d1) * w1 + dot d w <= 0).
    { apply IH; [lia| |lra].
      intros k Hk'. destruct (Hk (S k) ltac:(simpl; lia)) as [A B].
      rewrite psum_cons in A, B. split; [lra|].
      destruct B as [B|B]; [left; lra|right; exact B]. }
    setoid_replace (c * wp + (d1 * w1 + dot d w))
      with (c * (wp - w1) + ((c + d1) * w1 + dot d w)) by ring.
    lra.
Qed.

(** Paper, [eq:micro-f0-lagr]: [u⁰ − u(s) ∈ ∂I_{K^N}(x(s)) = N_{x(s)} K^N],
    i.e. [⟨u⁰ − u(s), c − x(s)⟩ ≤ 0] for every [c ∈ K^N], for every [N],
    [x⁰ ∈ K^N], any [u⁰] and rational [s ≥ 0] ([u(s)] the right
    derivative). Ledger claim: [prop:proj-micro]. *)
Theorem velocity_in_normal_cone (x0 u0 : list Q) (r s : Q) (c : list Q) :
  0 <= s -> InK r x0 -> length u0 = length x0 -> InK r c -> length c = length x0 ->
  dot (vsub u0 (velocities (dynamics x0 u0 r s))) (vsub c (positions (dynamics x0 u0 r s))) <= 0.
Proof.
  intros Hs HK L Hc Lc.
  set (u := velocities (dynamics x0 u0 r s)). set (x := positions (dynamics x0 u0 r s)).
  destruct (clusters_facts x0 u0 r s Hs HK L) as (_ & _ & Hl).
  assert (Lu : length u = length x0).
  { unfold u. rewrite velocities_spread, spread_length. exact Hl. }
  assert (Lx : length x = length x0).
  { unfold x. rewrite positions_spread. unfold untranslate.
    rewrite untranslate_from_length, spread_length. exact Hl. }
  assert (Ld : length (vsub u0 u) = length x0) by (rewrite vsub_length; lia).
  setoid_replace (dot (vsub u0 u) (vsub c x)) with (0 * 0 + dot (vsub u0 u) (vsub c x)) by ring.
  apply dot_by_parts_le.
  - rewrite !vsub_length; lia.
  - intros k Hk. rewrite Ld in Hk. rewrite psum_vsub by lia.
    destruct (multiplier_gap x0 u0 r s k Hs HK L ltac:(lia)) as [G0 G].
    fold u in G0, G. split; [lra|]. destruct G as [G|G]; [left; lra|].
    destruct k as [|k]; [left; unfold psum; simpl; lra|]. right.
    simpl nth at 1.
    pose proof (position_gap x0 u0 r s (S k) Hs HK L ltac:(lia)) as P. cbv zeta in P.
    fold x in P. replace (S k - 1)%nat with k in P, G by lia.
    rewrite (G (center s)) in P.
    rewrite !nth_vsub by lia.
    pose proof (Hc k ltac:(lia)). lra.
  - rewrite <- psum_all, Ld, psum_vsub by lia.
    destruct (multiplier_ends x0 u0 r s Hs HK L) as [_ E].
    unfold multiplier in E. fold u in E.
    destruct (length x0) as [|n] eqn:En; [unfold psum; simpl; lra|].
    assert (Hn : 0 < qn (S n)) by (apply qn_pos; lia).
    setoid_replace (psum (S n) u0 - psum (S n) u)
      with ((psum (S n) u0 - psum (S n) u) / qn (S n) * qn (S n)) by (field; lra).
    rewrite E. lra.
Qed.

(** ** Lipschitz with constant [‖u⁰‖] *)

Lemma sqnorm_free_positions (s t : Q) (ps : list particle) :
  sqnorm (vsub (map (free_position t) ps) (map (free_position s) ps)) ==
  (t - s) * (t - s) * sqnorm (map snd ps).
Proof.
  induction ps as [|p ps IH]; simpl; [ring|]. rewrite IH. unfold free_position. ring.
Qed.

(** Paper, [prop:proj-micro]: "x is Lipschitz continuous", with constant
    [‖u⁰‖]: [‖x(t) − x(s)‖² ≤ (t − s)² ‖u⁰‖²] for every [N], [x⁰ ∈ K^N],
    any [u⁰] and rational [s, t ≥ 0] (Euclidean norm; the paper's
    [(1/N)]-weighted norm scales both sides alike). Ledger claim:
    [prop:proj-micro]. *)
Theorem path_lipschitz (x0 u0 : list Q) (r s t : Q) :
  0 <= s -> 0 <= t -> InK r x0 -> length u0 = length x0 ->
  sqnorm (vsub (positions (dynamics x0 u0 r t)) (positions (dynamics x0 u0 r s))) <=
  (t - s) * (t - s) * sqnorm u0.
Proof.
  intros Hs Ht HK L. unfold dynamics, positions, untranslate.
  rewrite sqnorm_untranslate_both.
  set (ps := particles x0 u0 r).
  pose proof (dynamics_is_projection x0 u0 r t Ht HK) as Kt.
  pose proof (dynamics_is_projection x0 u0 r s Hs HK) as Ks. fold ps in Kt, Ks.
  pose proof (kkt_lipschitz _ _ _ _ Kt Ks ltac:(rewrite !map_length; reflexivity)) as H.
  rewrite sqnorm_free_positions in H. unfold ps in H. rewrite particles_u0 in H by exact L.
  exact H.
Qed.
