(** * Neighbouring particles: in one cluster, or at the border of two
      consecutive clusters, and what is known of those two clusters.

    Used by the statements on pairs of neighbours ([prop:Oleinik],
    [prop:proj-micro#u-in-H]). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers.
Import ListNotations.
Open Scope Q_scope.

(** ** Merging keeps the clusters in order at every instant *)

(** The clusters in order at any instant [τ'] stay in order when any two
    neighbours merge (the merged center lies between the two). *)
Lemma merge_ordered (τ τ' : Q) (cs : list cluster) :
  Forall Nonempty cs -> Ordered τ' cs ->
  (Forall Nonempty (merge_at τ cs) /\ Ordered τ' (merge_at τ cs)) /\
  (forall m, LowerBound τ' m cs -> LowerBound τ' m (merge_at τ cs)).
Proof.
  induction cs as [|a rest IH]; intros HN HO; [split; [split; auto|auto]|].
  destruct rest as [|b rest]; [split; [split; auto|auto]|].
  rewrite merge_at_pair.
  inversion HN as [|? ? Na HN']. inversion HN' as [|? ? Nb HN''].
  destruct HO as [Hab HO].
  destruct (approaching a b && Qeq_bool (meeting_time a b) τ).
  - assert (Nab : Nonempty (a ++ b)) by (destruct a; [contradiction|discriminate]).
    split; [split|].
    + constructor; auto.
    + apply ordered_cons. apply ordered_cons in HO. destruct HO as [Hb HO].
      split; [|exact HO]. destruct rest as [|c rest]; simpl in *; auto.
      apply center_app_le; auto; lra.
    + intros m Hm. simpl in Hm |- *. apply center_app_ge; auto; lra.
  - destruct (IH HN' HO) as ((HN2 & HO2) & HL). split; [split|].
    + constructor; auto.
    + apply ordered_cons. split; [apply HL; exact Hab|exact HO2].
    + intros m Hm. exact Hm.
Qed.

Lemma run_ordered (τ' t : Q) (fuel : nat) :
  forall cs, Forall Nonempty cs -> Ordered τ' cs ->
  Forall Nonempty (run fuel t cs) /\ Ordered τ' (run fuel t cs).
Proof.
  induction fuel as [|f IH]; intros cs HN HO; simpl; [auto|].
  destruct (next_meeting cs) as [m|]; [|auto].
  destruct (Qle_bool m t); [|auto].
  destruct (merge_ordered m τ' cs HN HO) as ((HN2 & HO2) & _). apply IH; assumption.
Qed.

(** The clusters at [t] are in order at time 0 too: their mean initial
    translated positions are non-decreasing. *)
Lemma clusters_ordered_at_0 (x0 u0 : list Q) (r t : Q) :
  InK r x0 -> Ordered 0 (clusters x0 u0 r t).
Proof.
  intro HK. unfold clusters.
  apply run_ordered; [|apply (singletons_invariant x0 u0 r HK)].
  apply (singletons_invariant x0 u0 r HK).
Qed.

(** The clusters at [t]: no pair meets at or before [t]. *)
Lemma clusters_final (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> Final t (clusters x0 u0 r t).
Proof.
  intros Ht HK. unfold clusters.
  destruct (run_invariant t (length (particles x0 u0 r)) _ 0
              (singletons_invariant x0 u0 r HK) Ht ltac:(rewrite map_length; lia))
    as (τ & _ & _ & HF & _).
  exact HF.
Qed.

(** ** Two neighbours *)

Lemma nth_spread_head (f : cluster -> Q) (b : cluster) (cs : list cluster) :
  Nonempty b -> nth 0 (spread f (b :: cs)) 0 = f b.
Proof. intro H. destruct b as [|p b]; [contradiction|reflexivity]. Qed.

(** Particles [i − 1] and [i] (indices from 0) are in one cluster, or [i − 1]
    is the last of a cluster [a] and [i] the first of the next one [b]; any
    property [P] of all neighbouring clusters holds of [(a, b)]. *)
Lemma neighbours (P : cluster -> cluster -> Prop) (cs : list cluster) :
  Forall Nonempty cs -> Adjacent P cs ->
  forall i, (0 < i < length (concat cs))%nat ->
  SameCluster cs (i - 1) i \/
  exists a b, P a b /\
    forall f, nth (i - 1) (spread f cs) 0 = f a /\ nth i (spread f cs) 0 = f b.
Proof.
  induction cs as [|c rest IH]; intros HN HP i Hi; simpl in Hi; [lia|].
  inversion HN as [|? ? Nc HN']. rewrite app_length in Hi.
  assert (Hsp : forall f, spread f (c :: rest) = repeat (f c) (length c) ++ spread f rest)
    by reflexivity.
  destruct (Nat.lt_trichotomy i (length c)) as [Hlt|[Heq|Hgt]].
  - left. intro f. rewrite Hsp. rewrite !app_nth1 by (rewrite repeat_length; lia).
    rewrite !nth_repeat_lt by lia. apply Qeq_refl.
  - right. destruct rest as [|b rest']; [simpl in Hi; lia|].
    inversion HN' as [|? ? Nb _]. destruct HP as [Hab _].
    exists c, b. split; [exact Hab|]. intro f. rewrite Hsp. split.
    + rewrite app_nth1 by (rewrite repeat_length; lia). apply nth_repeat_lt. lia.
    + rewrite app_nth2 by (rewrite repeat_length; lia).
      rewrite repeat_length, Heq, Nat.sub_diag. apply nth_spread_head. exact Nb.
  - assert (HP' : Adjacent P rest) by (destruct rest; [exact I|apply HP]).
    destruct (IH HN' HP' (i - length c)%nat ltac:(lia)) as [Hs|(a & b & Hab & Hf)].
    + left. intro f. specialize (Hs f). rewrite Hsp.
      rewrite !app_nth2 by (rewrite repeat_length; lia). rewrite repeat_length.
      replace (i - 1 - length c)%nat with (i - length c - 1)%nat by lia. exact Hs.
    + right. exists a, b. split; [exact Hab|]. intro f. destruct (Hf f) as [H1 H2].
      rewrite Hsp. rewrite !app_nth2 by (rewrite repeat_length; lia). rewrite repeat_length.
      replace (i - 1 - length c)%nat with (i - length c - 1)%nat by lia. split; assumption.
Qed.

(** The gap between particles [i − 1] and [i] in the original coordinates
    is the gap of their translated positions plus [2r]. *)
Lemma position_gap (x0 u0 : list Q) (r t : Q) (i : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (0 < i < length x0)%nat ->
  let x := positions (dynamics x0 u0 r t) in
  let y := spread (center t) (clusters x0 u0 r t) in
  nth i x 0 - nth (i - 1) x 0 == nth i y 0 - nth (i - 1) y 0 + 2 * r.
Proof.
  intros Ht HK L Hi x y.
  destruct (clusters_facts x0 u0 r t Ht HK L) as (_ & _ & Hl).
  assert (Ly : length y = length x0) by (unfold y; rewrite spread_length; exact Hl).
  unfold x. rewrite positions_spread. fold y.
  unfold untranslate. rewrite !nth_untranslate_from by lia.
  assert (Hq : qn i == qn (i - 1) + 1)
    by (rewrite <- qn_S; replace (S (i - 1)) with i by lia; reflexivity).
  rewrite !Nat.add_0_l, Hq. ring.
Qed.
