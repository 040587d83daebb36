(** * The semigroup property ([eq:semigroup], [eq:projortho-sg]).

    Paper, [eq:semigroup]: "x(t) = P_{K^N}(x(s) + (t − s) u(s)) for all
    0 ≤ s ≤ t". The dynamics restarted at [s] from its own state is the
    dynamics: in translated coordinates, [x̃(t)] is the projection onto the
    monotone cone of [x̃(s) + (t − s) u(s)] (translation commutes with
    adding [(t − s)u(s)], so this is the paper's statement). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers Neighbours Contacts VelocityProjection TwoTimes Segments
  Pressure.
Import ListNotations.
Open Scope Q_scope.

(** The state at [s] moved freely until [t]: each cluster at [s] at its
    position at [s] plus [(t − s)] times its velocity. *)
Definition moved (s t : Q) (c : cluster) : Q := center s c + (t - s) * velocity c.

Lemma moved_center (s t : Q) (c : cluster) : Nonempty c -> moved s t c == center t c.
Proof.
  intro N. unfold moved. rewrite (center_linear s c N), (center_linear t c N). ring.
Qed.

Lemma combine_spread (f g : cluster -> Q) (cs : list cluster) :
  combine (spread f cs) (spread g cs) = concat (map (fun c => repeat (f c, g c) (length c)) cs).
Proof.
  induction cs as [|c cs IH]; [reflexivity|].
  unfold spread in *. simpl. rewrite <- IH.
  generalize (concat (map (fun c0 => repeat (f c0) (length c0)) cs)).
  generalize (concat (map (fun c0 => repeat (g c0) (length c0)) cs)).
  intros l2 l1. induction (length c) as [|n IHn]; [reflexivity|]. simpl. rewrite IHn. reflexivity.
Qed.

(** [x̃(s) + (t − s) u(s)], entry by entry, is [moved s t] spread over the
    clusters at [s]. *)
Lemma moved_spread (s t : Q) (cs : list cluster) :
  map (fun p => fst p + (t - s) * snd p)
      (combine (translated_positions s cs) (spread velocity cs)) = spread (moved s t) cs.
Proof.
  unfold translated_positions. fold (spread (center s) cs).
  rewrite (combine_spread (center s) velocity cs).
  induction cs as [|c cs IH]; [reflexivity|].
  unfold spread in *. simpl. rewrite map_app, IH. f_equal.
  induction (length c) as [|n IHn]; [reflexivity|]. simpl. rewrite IHn. reflexivity.
Qed.

(** A group of clusters at [s] forming one cluster at [t]: the values
    [moved s t] over the group average to the center at [t] of the union,
    and they are pooled since the union is stable at [t]. *)
Lemma group_positions (s t : Q) (g : list cluster) :
  Forall Nonempty g -> g <> [] -> Stable t (concat g) ->
  Averages (spread (moved s t) g) (center t (concat g), length (concat g)) /\
  spread (moved s t) g <> [] /\ Pooled (spread (moved s t) g).
Proof.
  intros HN Hg (Hx & _).
  pose proof (nonempty_concat g HN Hg) as Nc.
  assert (HA : Forall2 Averages (map (map (free_position t)) g)
                 (map (fun c => (moved s t c, length c)) g)).
  { clear - HN. induction g as [|c g IH]; constructor; inversion HN; subst.
    - split; [apply map_length|]. simpl. rewrite moved_center by assumption.
      rewrite (sum_center t c) by assumption. unfold size. reflexivity.
    - apply IH. assumption. }
  split; [split|split].
  - apply spread_length.
  - simpl. rewrite spread_flat, (flat_qsum _ _ HA), <- concat_map.
    rewrite (sum_center t _ Nc). unfold size. reflexivity.
  - intro E. apply (f_equal (@length Q)) in E. rewrite spread_length in E.
    destruct (concat g); [contradiction|discriminate].
  - rewrite spread_flat. apply (pooled_flat (map (map (free_position t)) g)); [exact HA| |].
    + apply Forall_forall. intros x Hx'. apply in_map_iff in Hx'. destruct Hx' as (c & <- & Hc).
      rewrite Forall_forall in HN. specialize (HN c Hc). destruct c; [contradiction|discriminate].
    + rewrite <- concat_map. exact Hx.
Qed.

Lemma ordered_means_up (t : Q) (gs : list (list cluster)) :
  Ordered t (map (@concat particle) gs) ->
  MeansUp (map (fun g => (center t (concat g), length (concat g))) gs).
Proof.
  induction gs as [|g gs IH]; intro H; [exact I|].
  destruct gs as [|h gs]; [exact I|].
  destruct H as [H1 H2]. split; [exact H1|apply IH; exact H2].
Qed.

(** The clusters at [t] cut [x̃(s) + (t − s)u(s)] into pooled segments
    whose averages are [x̃(t)], with non-decreasing means. *)
Lemma semigroup_segments (x0 u0 : list Q) (r s t : Q) :
  0 <= s -> s <= t -> InK r x0 ->
  exists segs bs,
    Forall2 Averages segs bs /\ Forall (fun l => l <> []) segs /\ Forall Pooled segs /\
    MeansUp bs /\
    concat segs = spread (moved s t) (clusters x0 u0 r s) /\
    flat bs = spread (center t) (clusters x0 u0 r t).
Proof.
  intros Hs Hst HK.
  assert (Ht : 0 <= t) by lra.
  destruct (clusters_grow x0 u0 r s t Hst) as [_ (gs & Ebig & Esmall & Hgs)].
  destruct (clusters_invariant x0 u0 r t Ht HK) as [(HNt & HSt & HOt) _].
  destruct (clusters_invariant x0 u0 r s Hs HK) as [(HNs & _ & _) _].
  rewrite <- Ebig, <- Esmall. rewrite <- Ebig in HNt, HSt, HOt. rewrite <- Esmall in HNs.
  exists (map (spread (moved s t)) gs), (map (fun g => (center t (concat g), length (concat g))) gs).
  assert (HNg : Forall (fun g => Forall Nonempty g) gs).
  { apply Forall_forall. intros g Hg. rewrite Forall_forall in HNs |- *. intros c Hc.
    apply HNs. apply in_concat. exists g. auto. }
  assert (HG : Forall2 Averages (map (spread (moved s t)) gs)
                 (map (fun g => (center t (concat g), length (concat g))) gs) /\
               Forall (fun l => l <> []) (map (spread (moved s t)) gs) /\
               Forall Pooled (map (spread (moved s t)) gs)).
  { clear - HNg Hgs HSt. induction gs as [|g gs IH]; [split; [constructor|split; constructor]|].
    inversion HNg; inversion Hgs; inversion HSt; subst.
    destruct (group_positions s t g) as (A & B & C); auto.
    destruct IH as (A' & B' & C'); auto. split; [|split]; constructor; auto. }
  destruct HG as (HA & HNe & HP).
  split; [exact HA|split; [exact HNe|split; [exact HP|split; [|split]]]].
  - apply ordered_means_up. exact HOt.
  - rewrite spread_concat. reflexivity.
  - rewrite spread_flat, map_map. reflexivity.
Qed.

(** Paper, lemma "Semi-group property", [eq:semigroup]: "For any
    0 ≤ s < t, the solution satisfies x(t) = P_{K^N}(x(s) + (t − s)u(s))".
    For every [N], [x⁰ ∈ K^N], any [u⁰], rational [0 ≤ s ≤ t]: [x̃(t)]
    meets the KKT conditions of the projection of [x̃(s) + (t − s) u(s)]
    onto the monotone cone. Ledger claim: [eq:semigroup]. *)
Theorem semigroup (x0 u0 : list Q) (r s t : Q) :
  0 <= s -> s <= t -> InK r x0 ->
  let ys := translated_positions s (clusters x0 u0 r s) in
  let us := velocities (dynamics x0 u0 r s) in
  Kkt (map (fun p => fst p + (t - s) * snd p) (combine ys us))
      (translated_positions t (clusters x0 u0 r t)).
Proof.
  intros Hs Hst HK ys us.
  unfold ys, us. rewrite velocities_spread, moved_spread.
  unfold translated_positions. fold (spread (center t) (clusters x0 u0 r t)).
  destruct (semigroup_segments x0 u0 r s t Hs Hst HK)
    as (segs & bs & HA & HNe & HP & HM & <- & <-).
  apply (flat_kkt _ _ HA HNe HP HM).
Qed.

(** Paper, [eq:projortho-sg]: "For any 0 ≤ s < t, … u(t) = P_{H^N_{x(t)}}(u(s))".
    [H_{x(t)}] is a linear subspace and [u(t) ∈ H_{x(t)}] for [t > 0]
    ([VelocityProjection.velocity_in_H]); what is left is [u(s) − u(t) ⊥
    H_{x(t)}], proved here for every [N], [x⁰ ∈ K^N], any [u⁰], rational
    [0 ≤ s ≤ t]. Ledger claim: [eq:projortho-sg]. *)
Theorem velocity_semigroup (x0 u0 : list Q) (r s t : Q) (w : list Q) :
  0 <= s -> s <= t -> InK r x0 -> length u0 = length x0 -> length w = length x0 ->
  InH r (positions (dynamics x0 u0 r t)) w ->
  dot (vsub (velocities (dynamics x0 u0 r s)) (velocities (dynamics x0 u0 r t))) w == 0.
Proof.
  intros Hs Hst HK L Lw HH.
  assert (Ht0 : 0 <= t) by lra.
  set (us := velocities (dynamics x0 u0 r s)). set (ut := velocities (dynamics x0 u0 r t)).
  assert (Lus : length us = length x0).
  { unfold us. rewrite velocities_spread, spread_length. apply (clusters_facts x0 u0 r s Hs HK L). }
  assert (Lut : length ut = length x0).
  { unfold ut. rewrite velocities_spread, spread_length. apply (clusters_facts x0 u0 r t Ht0 HK L). }
  assert (Hls : length (concat (clusters x0 u0 r s)) = length x0)
    by apply (clusters_facts x0 u0 r s Hs HK L).
  (* the partial sums of u(s) − u(t) vanish unless k − 1 and k share a cluster at t *)
  assert (Hk : forall k, (k <= length x0)%nat ->
            psum k us - psum k ut == 0 \/ SameCluster (clusters x0 u0 r t) (k - 1) k).
  { intros k Hk.
    destruct (multiplier_gap x0 u0 r t k Ht0 HK L Hk) as [_ [H|H]]; [left|right; exact H].
    destruct (multiplier_gap x0 u0 r s k Hs HK L Hk) as [Hs0 _].
    pose proof (velocity_psum_decreasing x0 u0 r s t Hs Hst HK k ltac:(lia)) as Hd.
    fold us ut in H, Hs0, Hd. lra. }
  setoid_replace (dot (vsub us ut) w) with (0 * 0 + dot (vsub us ut) w) by ring.
  apply dot_by_parts.
  - rewrite vsub_length; lia.
  - intros k Hk'. rewrite vsub_length in Hk' by lia. rewrite psum_vsub by lia.
    destruct (Hk k ltac:(lia)) as [H|H]; [left; lra|].
    destruct k as [|k]; [left; unfold psum; simpl; lra|]. right. simpl nth at 1.
    assert (Hc : Contact r (positions (dynamics x0 u0 r t)) k).
    { unfold Contact.
      pose proof (position_gap x0 u0 r t (S k) Ht0 HK L ltac:(lia)) as G. cbv zeta in G.
      replace (S k - 1)%nat with k in G, H by lia. rewrite G, (H (center t)). ring. }
    apply HH; [|exact Hc].
    assert (Lx : length (positions (dynamics x0 u0 r t)) = length x0).
    { rewrite positions_spread. unfold untranslate. rewrite untranslate_from_length, spread_length.
      apply (clusters_facts x0 u0 r t Ht0 HK L). }
    lia.
  - rewrite <- psum_all, vsub_length, psum_vsub by lia. rewrite Lus.
    destruct (Hk (length x0) (le_n _)) as [H|H]; [lra|].
    (* at k = N both partial sums are the total momentum *)
    destruct (multiplier_ends x0 u0 r s Hs HK L) as [_ Es].
    destruct (multiplier_ends x0 u0 r t Ht0 HK L) as [_ Et].
    unfold multiplier in Es, Et. fold us in Es. fold ut in Et.
    destruct (length x0) as [|n] eqn:E; [unfold psum; simpl; ring|].
    assert (Hn : 0 < qn (S n)) by (apply qn_pos; lia).
    setoid_replace (psum (S n) us - psum (S n) ut)
      with ((psum (S n) u0 - psum (S n) ut) / qn (S n) * qn (S n) -
            (psum (S n) u0 - psum (S n) us) / qn (S n) * qn (S n)) by (field; lra).
    rewrite Es, Et. ring.
Qed.
