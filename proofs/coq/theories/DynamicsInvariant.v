(** * What every step of the dynamics keeps: stable clusters in order.

    [Invariant τ cs]: the clusters are non-empty, each is stable at [τ]
    ([ClusterAlgebra.Stable]) and their translated positions at [τ] are
    non-decreasing. It holds at time 0 for the data of [K^N], is kept by
    every merge, and when no pair meets before [t] it holds at [t]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra.
Import ListNotations.
Open Scope Q_scope.

(** A property of every adjacent pair of clusters. *)
Fixpoint Adjacent (P : cluster -> cluster -> Prop) (cs : list cluster) : Prop :=
  match cs with
  | a :: ((b :: _) as rest) => P a b /\ Adjacent P rest
  | _ => True
  end.

(** The clusters are in order at time [τ]. *)
Definition Ordered (τ : Q) : list cluster -> Prop :=
  Adjacent (fun a b => center τ a <= center τ b).

(** No adjacent pair meets before [τ]. *)
Definition NoMeetingBefore (τ : Q) : list cluster -> Prop :=
  Adjacent (fun a b => approaching a b = true -> τ <= meeting_time a b).

(** No adjacent pair meets at or before [t]: the run is over. *)
Definition Final (t : Q) : list cluster -> Prop :=
  Adjacent (fun a b => approaching a b = true -> t < meeting_time a b).

Definition Invariant (τ : Q) (cs : list cluster) : Prop :=
  Forall Nonempty cs /\ Forall (Stable τ) cs /\ Ordered τ cs.

Lemma adjacent_combine (P Q' R : cluster -> cluster -> Prop) (cs : list cluster) :
  Forall Nonempty cs -> Adjacent P cs -> Adjacent Q' cs ->
  (forall a b, Nonempty a -> Nonempty b -> P a b -> Q' a b -> R a b) ->
  Adjacent R cs.
Proof.
  intros HN HP HQ HR. induction cs as [|a rest IH]; [exact I|].
  destruct rest as [|b rest]; [exact I|].
  inversion HN as [|? ? Na HN']. inversion HN' as [|? ? Nb _].
  destruct HP as [P1 P2], HQ as [Q1 Q2].
  split; [apply HR; assumption|apply IH; assumption].
Qed.

Lemma adjacent_weaken (P Q' : cluster -> cluster -> Prop) (cs : list cluster) :
  Adjacent P cs -> (forall a b, P a b -> Q' a b) -> Adjacent Q' cs.
Proof.
  intros HP H. induction cs as [|a rest IH]; [exact I|].
  destruct rest as [|b rest]; [exact I|].
  destruct HP as [H1 H2]. split; [apply H; exact H1|apply IH; exact H2].
Qed.

(** ** The earliest meeting *)

Lemma next_meeting_pair (a b : cluster) (rest : list cluster) :
  next_meeting (a :: b :: rest) =
  if approaching a b then
    match next_meeting (b :: rest) with
    | Some m => Some (earlier (meeting_time a b) m)
    | None => Some (meeting_time a b)
    end
  else next_meeting (b :: rest).
Proof. reflexivity. Qed.

Lemma merge_at_pair (τ : Q) (a b : cluster) (rest : list cluster) :
  merge_at τ (a :: b :: rest) =
  if approaching a b && Qeq_bool (meeting_time a b) τ
  then (a ++ b) :: rest
  else a :: merge_at τ (b :: rest).
Proof. reflexivity. Qed.

(** Without a meeting time, no pair approaches. *)
Lemma next_meeting_none (cs : list cluster) :
  next_meeting cs = None -> Adjacent (fun a b => approaching a b = false) cs.
Proof.
  intro H. induction cs as [|a rest IH]; [exact I|]. destruct rest as [|b rest]; [exact I|].
  rewrite next_meeting_pair in H.
  destruct (approaching a b) eqn:E; [destruct (next_meeting (b :: rest)); discriminate|].
  split; [exact E|apply IH; exact H].
Qed.

Lemma earlier_le_l (a b : Q) : earlier a b <= a.
Proof.
  unfold earlier. destruct (Qle_bool a b) eqn:E; [apply Qle_refl|].
  apply Qlt_le_weak, Qnot_le_lt. rewrite <- Qle_bool_iff, E. discriminate.
Qed.

Lemma earlier_le_r (a b : Q) : earlier a b <= b.
Proof.
  unfold earlier. destruct (Qle_bool a b) eqn:E; [apply Qle_bool_iff; exact E|apply Qle_refl].
Qed.

(** No pair meets before the earliest meeting time. *)
Lemma next_meeting_some (cs : list cluster) :
  forall τ, next_meeting cs = Some τ -> NoMeetingBefore τ cs.
Proof.
  induction cs as [|a rest IH]; intros τ H; [exact I|]. destruct rest as [|b rest]; [exact I|].
  rewrite next_meeting_pair in H.
  destruct (approaching a b) eqn:E.
  - destruct (next_meeting (b :: rest)) as [m|] eqn:Em; injection H as <-.
    + split; [intros _; apply earlier_le_l|].
      apply (adjacent_weaken _ _ _ (IH m eq_refl)).
      intros c d Hcd Hap. specialize (Hcd Hap). pose proof (earlier_le_r (meeting_time a b) m). lra.
    + split; [intros _; apply Qle_refl|].
      apply (adjacent_weaken _ _ _ (next_meeting_none _ Em)).
      intros c d H1 H2. congruence.
  - split; [intro Hap; congruence|apply IH; exact H].
Qed.

(** The earliest meeting comes no earlier than the time the clusters are
    known to be in order. *)
Lemma next_meeting_after (τ : Q) (cs : list cluster) :
  Forall Nonempty cs -> Ordered τ cs ->
  forall m, next_meeting cs = Some m -> τ <= m.
Proof.
  intros HN HO. induction cs as [|a rest IH]; intros m H; [discriminate|].
  destruct rest as [|b rest]; [discriminate|].
  rewrite next_meeting_pair in H.
  inversion HN as [|? ? Na HN']. inversion HN' as [|? ? Nb _]. destruct HO as [Hab HO].
  destruct (approaching a b) eqn:E.
  - pose proof (meeting_after τ a b Na Nb Hab E).
    destruct (next_meeting (b :: rest)) as [m'|] eqn:Em; injection H as <-.
    + unfold earlier. destruct (Qle_bool _ _); [assumption|apply IH; auto].
    + assumption.
  - apply IH; auto.
Qed.

(** ** Merging *)

Lemma merge_at_concat (τ : Q) (cs : list cluster) : concat (merge_at τ cs) = concat cs.
Proof.
  induction cs as [|a rest IH]; [reflexivity|]. destruct rest as [|b rest]; [reflexivity|].
  rewrite merge_at_pair. destruct (_ && _).
  - simpl. rewrite app_assoc. reflexivity.
  - change (concat (a :: merge_at τ (b :: rest))) with (a ++ concat (merge_at τ (b :: rest))).
    rewrite IH. reflexivity.
Qed.

(** Each merge removes one cluster. *)
Lemma merge_at_length (cs : list cluster) :
  forall τ, next_meeting cs = Some τ -> S (length (merge_at τ cs)) = length cs.
Proof.
  induction cs as [|a rest IH]; intros τ H; [discriminate|].
  destruct rest as [|b rest]; [discriminate|].
  rewrite next_meeting_pair in H. rewrite merge_at_pair.
  destruct (approaching a b) eqn:E; simpl andb.
  - destruct (next_meeting (b :: rest)) as [m|] eqn:Em; injection H as <-.
    + unfold earlier. destruct (Qle_bool (meeting_time a b) m) eqn:L.
      * rewrite (proj2 (Qeq_bool_iff _ _) (Qeq_refl _)). reflexivity.
      * destruct (Qeq_bool (meeting_time a b) m); [reflexivity|].
        change (length (a :: merge_at m (b :: rest))) with (S (length (merge_at m (b :: rest)))).
        rewrite (IH m eq_refl). reflexivity.
    + rewrite (proj2 (Qeq_bool_iff _ _) (Qeq_refl _)). reflexivity.
  - cbv iota. change (length (a :: merge_at τ (b :: rest))) with (S (length (merge_at τ (b :: rest)))).
    rewrite (IH τ H). reflexivity.
Qed.

(** The first cluster's position bounds the rest from below. *)
Definition LowerBound (τ m : Q) (cs : list cluster) : Prop :=
  match cs with
  | c :: _ => m <= center τ c
  | [] => True
  end.

Lemma ordered_cons (τ : Q) (a : cluster) (cs : list cluster) :
  Ordered τ (a :: cs) <-> LowerBound τ (center τ a) cs /\ Ordered τ cs.
Proof. unfold Ordered. destruct cs; simpl; tauto. Qed.

(** Merging the pair that meets at [τ] keeps the invariant at [τ]. *)
Lemma merge_invariant (τ : Q) (cs : list cluster) :
  Invariant τ cs ->
  Invariant τ (merge_at τ cs) /\
  (forall m, LowerBound τ m cs -> LowerBound τ m (merge_at τ cs)).
Proof.
  induction cs as [|a rest IH]; intros (HN & HS & HO); [split; [split; auto|auto]|].
  destruct rest as [|b rest]; [split; [split; auto|auto]|].
  rewrite merge_at_pair.
  - inversion HN as [|? ? Na HN']. inversion HN' as [|? ? Nb HN''].
    inversion HS as [|? ? Sa HS']. inversion HS' as [|? ? Sb HS''].
    destruct HO as [Hab HO].
    destruct (approaching a b && Qeq_bool (meeting_time a b) τ) eqn:E.
    + apply andb_prop in E. destruct E as [Eap Eq]. apply Qeq_bool_iff in Eq.
      pose proof (gap_meeting τ a b Na Nb Eap) as G. rewrite Eq in G.
      pose proof (approaching_velocity a b Eap).
      assert (Hc : center τ b <= center τ a) by lra.
      assert (Nab : Nonempty (a ++ b)) by (destruct a; [contradiction|discriminate]).
      split; [split; [|split]|].
      * constructor; auto.
      * constructor; [apply stable_merge; auto; lra|auto].
      * apply ordered_cons. apply ordered_cons in HO. destruct HO as [Hb HO].
        split; [|exact HO]. destruct rest as [|c rest]; simpl in *; auto.
        apply center_app_le; auto; lra.
      * intros m Hm. simpl in Hm |- *. apply center_app_ge; auto; lra.
    + destruct (IH (conj HN' (conj HS' HO))) as ((HN2 & HS2 & HO2) & HL).
      split; [split; [|split]|].
      * constructor; auto.
      * constructor; auto.
      * apply ordered_cons. split; [apply HL; exact Hab|exact HO2].
      * intros m Hm. exact Hm.
Qed.

(** At the earliest meeting [m], everything known at [τ ≤ m] still holds. *)
Lemma invariant_later (τ τ' : Q) (cs : list cluster) :
  Invariant τ cs -> τ <= τ' -> NoMeetingBefore τ' cs -> Invariant τ' cs.
Proof.
  intros (HN & HS & HO) Ht HM. split; [exact HN|split].
  - eapply Forall_impl; [|exact HS]. intros c. apply stable_later. exact Ht.
  - apply (adjacent_combine _ _ _ cs HN HO HM).
    intros a b Na Nb Hab Hm. apply (ordered_later τ); assumption.
Qed.

(** ** The run *)

(** The run ends in a state where the invariant holds at some [τ ≤ t] and
    no pair meets at or before [t]; the particles are unchanged. The number
    of clusters is enough fuel: each merge removes one. *)
Lemma run_invariant (t : Q) (fuel : nat) :
  forall cs τ, Invariant τ cs -> τ <= t -> (length cs <= fuel)%nat ->
  exists τ', Invariant τ' (run fuel t cs) /\ τ' <= t /\ Final t (run fuel t cs) /\
             concat (run fuel t cs) = concat cs.
Proof.
  induction fuel as [|f IH]; intros cs τ HI Ht Hl.
  - destruct cs; [|simpl in Hl; lia]. exists τ. simpl. repeat split; auto.
  - simpl. destruct (next_meeting cs) as [m|] eqn:Em.
    + pose proof (next_meeting_after τ cs (proj1 HI) (proj2 (proj2 HI)) m Em) as Hm.
      pose proof (next_meeting_some cs m Em) as HM.
      destruct (Qle_bool m t) eqn:L.
      * apply Qle_bool_iff in L.
        pose proof (invariant_later τ m cs HI Hm HM) as HIm.
        destruct (merge_invariant m cs HIm) as [HI2 _].
        pose proof (merge_at_length cs m Em).
        destruct (IH (merge_at m cs) m HI2 L ltac:(lia)) as (τ' & A & B & C & D).
        exists τ'. rewrite D, merge_at_concat. auto.
      * assert (t < m) by (apply Qnot_le_lt; rewrite <- Qle_bool_iff, L; discriminate).
        exists τ. repeat split; auto; try apply HI.
        apply (adjacent_weaken _ _ _ HM). intros a b H1 H2. specialize (H1 H2). lra.
    + exists τ. repeat split; auto; try apply HI.
      apply (adjacent_weaken _ _ _ (next_meeting_none cs Em)).
      intros a b H1 H2. congruence.
Qed.
