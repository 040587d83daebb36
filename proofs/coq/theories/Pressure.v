(** * The pressure is a non-negative measure: each multiplier grows in
      time ([prop:micro-pressure]). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers TwoTimes Segments.
Import ListNotations.
Open Scope Q_scope.

(** ** Spread vectors as averaged lists *)

Lemma spread_flat (f : cluster -> Q) (cs : list cluster) :
  spread f cs = flat (map (fun c => (f c, length c)) cs).
Proof. induction cs as [|c cs IH]; [reflexivity|]. unfold spread in *. simpl. rewrite IH. reflexivity. Qed.

Lemma spread_concat (f : cluster -> Q) (gs : list (list cluster)) :
  spread f (concat gs) = concat (map (spread f) gs).
Proof.
  induction gs as [|g gs IH]; [reflexivity|]. simpl. rewrite <- IH.
  unfold spread. rewrite map_app, concat_app. reflexivity.
Qed.

Lemma nonempty_concat (g : list cluster) :
  Forall Nonempty g -> g <> [] -> Nonempty (concat g).
Proof.
  intros HN Hg. destruct g as [|c g]; [contradiction|]. inversion HN; subst.
  destruct c; [contradiction|discriminate].
Qed.

(** The sum of the cluster velocities over a group of clusters is the sum
    of the initial velocities: momentum is conserved. *)
Lemma qsum_spread_velocity (g : list cluster) :
  Forall Nonempty g -> qsum (spread velocity g) == qsum (map snd (concat g)).
Proof.
  induction g as [|c g IH]; intro HN; [reflexivity|]. inversion HN as [|? ? Nc HN']; subst.
  unfold spread in *. simpl. rewrite map_app, !qsum_app, qsum_repeat, IH by exact HN'.
  rewrite (sum_velocity c Nc). unfold size. reflexivity.
Qed.

(** The velocities of the clusters of a group [g], averaged over the
    group, give the velocity of the group's union; and they are pooled
    when the union is stable. *)
Lemma group_velocities (t : Q) (g : list cluster) :
  Forall Nonempty g -> g <> [] -> Stable t (concat g) ->
  Averages (spread velocity g) (velocity (concat g), length (concat g)) /\
  spread velocity g <> [] /\ Pooled (spread velocity g).
Proof.
  intros HN Hg (_ & Hu).
  pose proof (nonempty_concat g HN Hg) as Nc.
  split; [split|split].
  - apply spread_length.
  - simpl. rewrite qsum_spread_velocity by exact HN. rewrite (sum_velocity _ Nc). reflexivity.
  - intro E. apply (f_equal (@length Q)) in E. rewrite spread_length in E.
    destruct (concat g); [contradiction|discriminate].
  - rewrite spread_flat.
    apply (pooled_flat (map (map snd) g)).
    + clear - HN. induction g as [|c g IH]; constructor; inversion HN; subst.
      * split; [apply map_length|]. simpl. rewrite (sum_velocity c) by assumption.
        unfold size. reflexivity.
      * apply IH. assumption.
    + apply Forall_forall. intros s Hs. apply in_map_iff in Hs. destruct Hs as (c & <- & Hc).
      rewrite Forall_forall in HN. specialize (HN c Hc). destruct c; [contradiction|discriminate].
    + rewrite <- concat_map. exact Hu.
Qed.

(** For [0 ≤ s ≤ t], the partial sums of [u(t)] are at most those of [u(s)]. *)
Lemma velocity_psum_decreasing (x0 u0 : list Q) (r s t : Q) :
  0 <= s -> s <= t -> InK r x0 ->
  forall k, (k <= length (concat (clusters x0 u0 r s)))%nat ->
  psum k (velocities (dynamics x0 u0 r t)) <= psum k (velocities (dynamics x0 u0 r s)).
Proof.
  intros Hs Hst HK k Hk.
  assert (Ht : 0 <= t) by lra.
  destruct (clusters_grow x0 u0 r s t Hst) as [_ (gs & Ebig & Esmall & Hgs)].
  destruct (clusters_invariant x0 u0 r t Ht HK) as [(HNt & HSt & _) _].
  destruct (clusters_invariant x0 u0 r s Hs HK) as [(HNs & _ & _) _].
  rewrite !velocities_spread, <- Ebig, <- Esmall.
  rewrite <- Ebig in HNt, HSt. rewrite <- Esmall in HNs, Hk.
  rewrite spread_concat, spread_flat, map_map.
  assert (HNg : Forall (fun g => Forall Nonempty g) gs).
  { apply Forall_forall. intros g Hg. rewrite Forall_forall in HNs |- *. intros c Hc.
    apply HNs. apply in_concat. exists g. auto. }
  assert (HG : Forall2 Averages (map (spread velocity) gs)
                 (map (fun g => (velocity (concat g), length (concat g))) gs) /\
               Forall (fun s => s <> []) (map (spread velocity) gs) /\
               Forall Pooled (map (spread velocity) gs)).
  { clear - HNg Hgs HSt. induction gs as [|g gs IH]; [split; [constructor|split; constructor]|].
    inversion HNg; inversion Hgs; inversion HSt; subst.
    destruct (group_velocities t g) as (A & B & C); auto.
    destruct IH as (A' & B' & C'); auto. split; [|split]; constructor; auto. }
  destruct HG as (HA & HNe & HP).
  apply (psum_flat_le _ _ HA HNe HP).
  rewrite <- spread_concat, spread_length. exact Hk.
Qed.

(** Paper, [prop:micro-pressure]: the pressure, the measure of the
    multipliers, is non-negative: each [λ_i] is non-decreasing in time
    (the ledger's reading). Here: for every [N], [x⁰ ∈ K^N], any [u⁰],
    rational [0 ≤ s ≤ t] and [k = 0..N], [λ_k(s) ≤ λ_k(t)].
    Ledger claim: [prop:micro-pressure]. *)
Theorem multiplier_nondecreasing (x0 u0 : list Q) (r s t : Q) (k : nat) :
  0 <= s -> s <= t -> InK r x0 -> length u0 = length x0 -> (k <= length x0)%nat ->
  multiplier x0 u0 r s k <= multiplier x0 u0 r t k.
Proof.
  intros Hs Hst HK L Hk.
  destruct (clusters_facts x0 u0 r s Hs HK L) as (_ & _ & Hl).
  pose proof (velocity_psum_decreasing x0 u0 r s t Hs Hst HK k ltac:(lia)) as H.
  unfold multiplier. destruct (length x0) as [|n] eqn:E.
  - unfold qn, Qdiv, Qinv. simpl. lra.
  - assert (Hn : 0 < qn (S n)) by (apply qn_pos; lia).
    unfold Qdiv. apply Qmult_le_compat_r; [lra|].
    apply Qlt_le_weak, Qinv_lt_0_compat. exact Hn.
Qed.

(** Paper, [prop:micro-pressure] (the ledger's reading): "p_i = dλ_i/dt
    satisfies (x_{i+1} − x_i − 2r) p_i = 0": [λ_k] changes between [s] and
    [t] only if particles [k − 1] and [k] (indices from 0) are in one
    cluster at [t] — hence in contact at [t] ([Multipliers.SameCluster],
    [Multipliers.multiplier_complementarity]). For every [N], [x⁰ ∈ K^N],
    any [u⁰], rational [0 ≤ s ≤ t], [0 ≤ k ≤ N].
    Ledger claim: [prop:micro-pressure]. *)
Theorem multiplier_grows_only_in_contact (x0 u0 : list Q) (r s t : Q) (k : nat) :
  0 <= s -> s <= t -> InK r x0 -> length u0 = length x0 -> (k <= length x0)%nat ->
  multiplier x0 u0 r s k == multiplier x0 u0 r t k \/
  SameCluster (clusters x0 u0 r t) (k - 1) k.
Proof.
  intros Hs Hst HK L Hk. assert (Ht : 0 <= t) by lra.
  destruct (multiplier_gap x0 u0 r t k Ht HK L Hk) as [_ [H|H]]; [left|right; exact H].
  destruct (multiplier_gap x0 u0 r s k Hs HK L Hk) as [Hs0 _].
  destruct (clusters_facts x0 u0 r s Hs HK L) as (_ & _ & Hl).
  pose proof (velocity_psum_decreasing x0 u0 r s t Hs Hst HK k ltac:(lia)) as Hd.
  assert (E : psum k u0 - psum k (velocities (dynamics x0 u0 r s)) ==
              psum k u0 - psum k (velocities (dynamics x0 u0 r t))) by lra.
  unfold multiplier. rewrite E. reflexivity.
Qed.
