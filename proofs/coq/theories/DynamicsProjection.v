(** * The sticky dynamics is the projection ([prop:proj-micro]).

    The clusters of [Dynamics.clusters] at time [t] are stable and in order
    ([DynamicsInvariant.run_invariant]); stable clusters in order are
    exactly the blocks of the KKT conditions of the projection of
    [z = x̃⁰ + t u⁰] onto the monotone cone ([Kkt.Kkt]), so the translated
    positions of the dynamics are [P_{K̃}(x̃⁰ + t u⁰)]: in the original
    coordinates, [x(t) = P_K(x⁰ + t u⁰)]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant.
Import ListNotations.
Open Scope Q_scope.

(** ** Time 0 *)

Lemma center_single (τ : Q) (p : particle) : center τ [p] == free_position τ p.
Proof.
  unfold center, size. change (length [p]) with 1%nat. rewrite qn_S, qn_0.
  simpl qsum. field.
Qed.

Lemma inK_cons (r a : Q) (x : list Q) : InK r (a :: x) -> InK r x.
Proof. intros H i Hi. apply (H (S i)). simpl. lia. Qed.

Lemma inK_head (r a b : Q) (x : list Q) : InK r (a :: b :: x) -> 2 * r <= b - a.
Proof. intro H. apply (H 0%nat). simpl. lia. Qed.

(** Data of [K^N], each particle alone: the clusters are in order. *)
Lemma singletons_ordered (r : Q) (x : list Q) :
  forall k u, InK r x -> Ordered 0 (map (fun p => [p]) (combine (translate_from k r x) u)).
Proof.
  induction x as [|a x IH]; intros k u H; [exact I|].
  destruct x as [|b x]; [destruct u; exact I|].
  destruct u as [|ua [|ub u]]; [exact I|exact I|].
  pose proof (inK_head r a b x H) as Hab.
  split.
  - rewrite !center_single. unfold free_position. cbn [fst snd].
    rewrite qn_S. lra.
  - apply (IH (S k) (ub :: u)). exact (inK_cons r a _ H).
Qed.

Lemma singletons_invariant (x0 u0 : list Q) (r : Q) :
  InK r x0 -> Invariant 0 (map (fun p => [p]) (particles x0 u0 r)).
Proof.
  intro H. split; [|split].
  - apply Forall_forall. intros c Hc. apply in_map_iff in Hc.
    destruct Hc as (p & <- & _). discriminate.
  - apply Forall_forall. intros c Hc. apply in_map_iff in Hc.
    destruct Hc as (p & <- & _). apply stable_singleton.
  - apply singletons_ordered. exact H.
Qed.

(** ** Stable clusters in order meet the KKT conditions *)

Lemma pooled_prefix (seg : list Q) :
  seg <> [] -> Pooled seg ->
  forall k, (k <= length seg)%nat -> 0 <= psum k seg - qn k * (qsum seg / qn (length seg)).
Proof.
  intros Hn Hp k Hk.
  assert (Hpos : 0 < qn (length seg)) by (apply qn_pos; destruct seg; [contradiction|simpl; lia]).
  apply (Qmult_pos_le_reg (qn (length seg))); [exact Hpos|].
  setoid_replace (qn (length seg) * (psum k seg - qn k * (qsum seg / qn (length seg))))
    with (qn (length seg) * psum k seg - qn k * qsum seg) by (field; lra).
  specialize (Hp k Hk). lra.
Qed.

(** One stable cluster: the KKT conditions hold across it. *)
Lemma cluster_kkt (t yp : Q) (c : cluster) (rz ry : list Q) :
  Nonempty c -> Stable t c -> yp <= center t c ->
  kkt_from 0 (center t c) rz ry ->
  kkt_from 0 yp (map (free_position t) c ++ rz) (repeat (center t c) (length c) ++ ry).
Proof.
  intros Hn (Hx & _) Hyp Hrest.
  set (seg := map (free_position t) c).
  assert (Hseg : seg <> []) by (unfold seg; destruct c; [contradiction|discriminate]).
  assert (Hl : length seg = length c) by apply map_length.
  assert (Hm : center t c == qsum seg / qn (length seg)) by (rewrite Hl; reflexivity).
  pose proof (pooled_prefix seg Hseg Hx) as Hpre.
  assert (Hpos : 0 < qn (length seg)) by (apply qn_pos; destruct seg; [contradiction|simpl; lia]).
  assert (Htot : qsum seg - qn (length seg) * center t c == 0) by (rewrite Hm; field; lra).
  rewrite <- Hl. clearbody seg.
  destruct seg as [|s seg]; [contradiction|].
  simpl. split; [apply Qle_refl|split; [exact Hyp|split; [intros _; reflexivity|]]].
  apply block_inner; [|simpl length in Htot; rewrite qn_S in Htot; simpl in Htot; lra|exact Hrest].
  intros k Hk. specialize (Hpre (S k) ltac:(simpl; lia)).
  rewrite psum_cons, qn_S, <- Hm in Hpre. lra.
Qed.

(** Stable clusters in order: the KKT conditions hold along the whole line. *)
Lemma clusters_kkt (t : Q) (cs : list cluster) :
  Forall Nonempty cs -> Forall (Stable t) cs -> Ordered t cs ->
  forall yp, LowerBound t yp cs ->
  kkt_from 0 yp (concat (map (map (free_position t)) cs)) (translated_positions t cs).
Proof.
  induction cs as [|c cs IH]; intros HN HS HO yp Hyp.
  - reflexivity.
  - inversion HN; inversion HS; subst. apply ordered_cons in HO. destruct HO as [Hc HO].
    unfold translated_positions. simpl. apply cluster_kkt; [assumption..|].
    apply IH; assumption.
Qed.

(** At the end of the run the invariant holds at [t] itself. *)
Lemma final_invariant (τ t : Q) (cs : list cluster) :
  Invariant τ cs -> τ <= t -> Final t cs -> Invariant t cs.
Proof.
  intros HI Ht HF. apply (invariant_later τ t cs HI Ht).
  apply (adjacent_weaken _ _ _ HF). intros a b H1 H2. specialize (H1 H2). lra.
Qed.

(** The clusters at time [t]: the invariant at [t], and the particles. *)
Lemma clusters_invariant (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 ->
  Invariant t (clusters x0 u0 r t) /\
  concat (clusters x0 u0 r t) = particles x0 u0 r.
Proof.
  intros Ht HK. unfold clusters.
  destruct (run_invariant t (length (particles x0 u0 r)) _ 0
              (singletons_invariant x0 u0 r HK) Ht ltac:(rewrite map_length; lia))
    as (τ & HI & Hτ & HF & Hc).
  split; [apply (final_invariant τ t); assumption|].
  rewrite Hc. clear. induction (particles x0 u0 r); simpl; congruence.
Qed.

(** Stable clusters in order meet the KKT conditions (index form). *)
Lemma invariant_kkt (t : Q) (cs : list cluster) :
  Invariant t cs ->
  Kkt (map (free_position t) (concat cs)) (translated_positions t cs).
Proof.
  intros (HN & HS & HO). apply kkt_rec_iff. rewrite concat_map.
  destruct cs as [|c cs]; [reflexivity|].
  inversion HN; subst. destruct c as [|p c]; [contradiction|].
  pose proof (clusters_kkt t ((p :: c) :: cs) HN HS HO (center t (p :: c)) (Qle_refl _)) as H.
  unfold translated_positions in H |- *. simpl in H |- *. exact H.
Qed.

(** ** The theorem *)

(** Paper, [prop:proj-micro] ([eq:proj-micro-x]): "Let x_0 ∈ K^N and
    u_0 ∈ C^N_{x_0}. Then there exists a unique solution x to
    (eq:micro-f0-lagr). It is given by the projection formula
    x(t) = P_{K^N}(x_0 + t u_0), t ≥ 0."

    Ledger claim: [prop:proj-micro]. For every [N], every [x⁰ ∈ K^N] and
    every [u⁰] (the hypothesis [u⁰ ∈ C_{x⁰}] is not needed: particles
    touching at time 0 and separating are two clusters), every rational
    [t ≥ 0]: the translated positions of the sticky dynamics meet the KKT
    conditions of the projection of [x̃⁰ + t u⁰] onto the monotone cone
    [K̃^N] — that is [x̃(t) = P_{K̃}(x̃⁰ + t u⁰)], i.e.
    [x(t) = P_K(x⁰ + t u⁰)] ([df:translat-x]). *)
Theorem dynamics_is_projection (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 ->
  Kkt (map (free_position t) (particles x0 u0 r))
      (translated_positions t (clusters x0 u0 r t)).
Proof.
  intros Ht HK. destruct (clusters_invariant x0 u0 r t Ht HK) as [HI Hc].
  rewrite <- Hc. apply invariant_kkt. exact HI.
Qed.
