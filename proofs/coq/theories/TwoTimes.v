(** * Two instants [s ≤ t]: the dynamics to [t] continues the dynamics to
      [s], and the clusters at [t] are unions of clusters at [s].

    Paper, section "Sticky dynamics and reduction to first order":
    "clusters of particles can only grow in time and never break apart". *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant.
Import ListNotations.
Open Scope Q_scope.

(** ** Fuel *)

Lemma next_meeting_short (cs : list cluster) :
  (length cs <= 1)%nat -> next_meeting cs = None.
Proof. intro H. destruct cs as [|a [|b cs]]; [reflexivity|reflexivity|simpl in H; lia]. Qed.

Lemma run_length (t : Q) (fuel : nat) :
  forall cs, (length (run fuel t cs) <= length cs)%nat.
Proof.
  induction fuel as [|f IH]; intro cs; simpl; [lia|].
  destruct (next_meeting cs) as [m|] eqn:E; [|lia].
  destruct (Qle_bool m t); [|lia].
  pose proof (merge_at_length cs m E). specialize (IH (merge_at m cs)). lia.
Qed.

(** One more unit of fuel than clusters changes nothing. *)
Lemma run_extra_fuel (t : Q) (f : nat) :
  forall cs, (length cs <= S f)%nat -> run (S f) t cs = run f t cs.
Proof.
  induction f as [|f IH]; intros cs H.
  - simpl. rewrite next_meeting_short by exact H. reflexivity.
  - change (run (S (S f)) t cs) with
      (match next_meeting cs with
       | Some τ => if Qle_bool τ t then run (S f) t (merge_at τ cs) else cs
       | None => cs
       end).
    change (run (S f) t cs) with
      (match next_meeting cs with
       | Some τ => if Qle_bool τ t then run f t (merge_at τ cs) else cs
       | None => cs
       end).
    destruct (next_meeting cs) as [m|] eqn:E; [|reflexivity].
    destruct (Qle_bool m t); [|reflexivity].
    pose proof (merge_at_length cs m E). apply IH. lia.
Qed.

(** ** The run to [t] goes through the state at [s] *)

Lemma run_split (s t : Q) :
  s <= t -> forall fuel cs, (length cs <= fuel)%nat ->
  run fuel t cs = run fuel t (run fuel s cs).
Proof.
  intros Hst. induction fuel as [|f IH]; intros cs Hl; [reflexivity|].
  change (run (S f) s cs) with
    (match next_meeting cs with
     | Some τ => if Qle_bool τ s then run f s (merge_at τ cs) else cs
     | None => cs
     end).
  destruct (next_meeting cs) as [m|] eqn:E; [|reflexivity].
  destruct (Qle_bool m s) eqn:Ls; [|reflexivity].
  assert (Lt : Qle_bool m t = true).
  { apply Qle_bool_iff. apply Qle_bool_iff in Ls. lra. }
  change (run (S f) t cs) with
    (match next_meeting cs with
     | Some τ => if Qle_bool τ t then run f t (merge_at τ cs) else cs
     | None => cs
     end).
  rewrite E, Lt.
  pose proof (merge_at_length cs m E).
  rewrite (IH (merge_at m cs)) by lia.
  symmetry. apply run_extra_fuel.
  pose proof (run_length s f (merge_at m cs)). lia.
Qed.

(** ** Coarser partitions *)

(** [big] groups the clusters of [small]: each cluster of [big] is the
    union of a non-empty run of consecutive clusters of [small]. *)
Definition Coarser (small big : list cluster) : Prop :=
  exists gs : list (list cluster),
    map (@concat particle) gs = big /\ concat gs = small /\ Forall (fun g => g <> []) gs.

Lemma coarser_refl (cs : list cluster) : Coarser cs cs.
Proof.
  exists (map (fun c => [c]) cs). split; [|split].
  - rewrite map_map. simpl. induction cs as [|c cs IH]; simpl; f_equal; auto.
    apply app_nil_r.
  - induction cs as [|c cs IH]; simpl; f_equal; auto.
  - apply Forall_forall. intros g Hg. apply in_map_iff in Hg.
    destruct Hg as (c & <- & _). discriminate.
Qed.

Lemma merge_at_coarser (τ : Q) (gs : list (list cluster)) :
  Forall (fun g => g <> []) gs ->
  exists gs', map (@concat particle) gs' = merge_at τ (map (@concat particle) gs) /\
              concat gs' = concat gs /\ Forall (fun g => g <> []) gs'.
Proof.
  induction gs as [|g rest IH]; intro HN; [exists []; auto|].
  inversion HN as [|? ? Ng HN']. subst.
  destruct rest as [|h rest]; [exists [g]; auto|].
  inversion HN' as [|? ? Nh HN'']. subst.
  change (map (@concat particle) (g :: h :: rest))
    with (concat g :: concat h :: map (@concat particle) rest).
  rewrite merge_at_pair.
  destruct (approaching (concat g) (concat h) && Qeq_bool (meeting_time (concat g) (concat h)) τ).
  - exists ((g ++ h) :: rest). split; [|split].
    + simpl. rewrite concat_app. reflexivity.
    + simpl. rewrite app_assoc. reflexivity.
    + constructor; [destruct g; [contradiction|discriminate]|exact HN''].
  - destruct (IH HN') as (gs' & H1 & H2 & H3). exists (g :: gs'). split; [|split].
    + simpl. rewrite H1. reflexivity.
    + simpl. rewrite H2. reflexivity.
    + constructor; assumption.
Qed.

Lemma run_coarser (t : Q) (fuel : nat) :
  forall small big, Coarser small big -> Coarser small (run fuel t big).
Proof.
  induction fuel as [|f IH]; intros small big H; simpl; [exact H|].
  destruct (next_meeting big) as [m|]; [|exact H].
  destruct (Qle_bool m t); [|exact H].
  apply IH. destruct H as (gs & <- & H2 & H3).
  destruct (merge_at_coarser m gs H3) as (gs' & E1 & E2 & E3).
  exists gs'. split; [exact E1|split; [congruence|exact E3]].
Qed.

(** Paper: "clusters of particles can only grow in time and never break
    apart": for [0 ≤ s ≤ t] the clusters at [t] are unions of consecutive
    clusters at [s], and the clusters at [t] are what the dynamics makes
    of the clusters at [s]. *)
Theorem clusters_grow (x0 u0 : list Q) (r s t : Q) :
  s <= t ->
  clusters x0 u0 r t = run (length (particles x0 u0 r)) t (clusters x0 u0 r s) /\
  Coarser (clusters x0 u0 r s) (clusters x0 u0 r t).
Proof.
  intro Hst.
  assert (E : clusters x0 u0 r t = run (length (particles x0 u0 r)) t (clusters x0 u0 r s)).
  { unfold clusters. apply run_split; [exact Hst|]. rewrite map_length. lia. }
  split; [exact E|]. rewrite E. apply run_coarser, coarser_refl.
Qed.
