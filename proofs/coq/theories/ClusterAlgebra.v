(** * The algebra of clusters: centers move linearly, stability lasts,
      stable clusters that meet merge into a stable cluster.

    A cluster is *stable* at time [τ] when every prefix of it has mean
    translated position (at [τ]) and mean initial velocity at least the
    cluster's ([Pooled], as in [Pava.v]): then it stays together under the
    projection — this is what makes the dynamics a projection. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics.
Import ListNotations.
Open Scope Q_scope.

(** ** Sums of free positions *)

Lemma qsum_free (τ : Q) (c : cluster) :
  qsum (map (free_position τ) c) == qsum (map fst c) + τ * qsum (map snd c).
Proof.
  induction c as [|p c IH]; simpl.
  - ring.
  - rewrite IH. unfold free_position. ring.
Qed.

Lemma psum_free (τ : Q) (k : nat) (c : cluster) :
  psum k (map (free_position τ) c) == psum k (map fst c) + τ * psum k (map snd c).
Proof. unfold psum. rewrite !firstn_map. apply qsum_free. Qed.

(** ** Sizes and centers *)

(** A cluster is never empty. *)
Definition Nonempty (c : cluster) : Prop := c <> [].

Lemma size_pos (c : cluster) : Nonempty c -> 0 < size c.
Proof. intro H. apply qn_pos. destruct c; [contradiction|simpl; lia]. Qed.

Lemma size_app (a b : cluster) : size (a ++ b) == size a + size b.
Proof. unfold size. rewrite app_length. apply qn_add. Qed.

Lemma sum_center (τ : Q) (c : cluster) :
  Nonempty c -> qsum (map (free_position τ) c) == size c * center τ c.
Proof. intro H. pose proof (size_pos c H). unfold center. field. lra. Qed.

Lemma sum_velocity (c : cluster) :
  Nonempty c -> qsum (map snd c) == size c * velocity c.
Proof. intro H. pose proof (size_pos c H). unfold velocity. field. lra. Qed.

(** A cluster moves at its velocity: [center τ = center 0 + τ·velocity]. *)
Lemma center_linear (τ : Q) (c : cluster) :
  Nonempty c -> center τ c == center 0 c + τ * velocity c.
Proof.
  intro H. pose proof (size_pos c H).
  unfold center, velocity. rewrite !qsum_free. field. lra.
Qed.

(** The gap between two approaching clusters closes at their meeting time. *)
Lemma gap_meeting (τ : Q) (a b : cluster) :
  Nonempty a -> Nonempty b -> approaching a b = true ->
  center τ b - center τ a == (velocity a - velocity b) * (meeting_time a b - τ).
Proof.
  intros Ha Hb Hab. unfold approaching in Hab.
  destruct (Qle_bool _ _) eqn:E; [discriminate|].
  assert (Hv : ~ velocity a <= velocity b) by (rewrite <- Qle_bool_iff, E; discriminate).
  apply Qnot_le_lt in Hv.
  rewrite (center_linear τ a Ha), (center_linear τ b Hb). unfold meeting_time.
  field. intro H0. lra.
Qed.

Lemma approaching_velocity (a b : cluster) :
  approaching a b = true -> velocity b < velocity a.
Proof.
  unfold approaching. destruct (Qle_bool _ _) eqn:E; [discriminate|]. intros _.
  apply Qnot_le_lt. rewrite <- Qle_bool_iff, E. discriminate.
Qed.

Lemma not_approaching_velocity (a b : cluster) :
  approaching a b = false -> velocity a <= velocity b.
Proof.
  unfold approaching. destruct (Qle_bool _ _) eqn:E; [|discriminate]. intros _.
  apply Qle_bool_iff. exact E.
Qed.

(** Two clusters ordered at [τ] are still ordered at [τ' ≥ τ] unless they
    meet strictly between. *)
Lemma ordered_later (τ τ' : Q) (a b : cluster) :
  Nonempty a -> Nonempty b -> center τ a <= center τ b -> τ <= τ' ->
  (approaching a b = true -> τ' <= meeting_time a b) ->
  center τ' a <= center τ' b.
Proof.
  intros Ha Hb Hord Ht Hm. destruct (approaching a b) eqn:E.
  - pose proof (gap_meeting τ' a b Ha Hb E) as G.
    pose proof (approaching_velocity a b E).
    specialize (Hm eq_refl).
    assert (0 <= (velocity a - velocity b) * (meeting_time a b - τ'))
      by (apply Qmult_le_0_compat; lra).
    lra.
  - pose proof (not_approaching_velocity a b E).
    rewrite (center_linear τ' a Ha), (center_linear τ' b Hb).
    rewrite (center_linear τ a Ha), (center_linear τ b Hb) in Hord.
    assert (0 <= (τ' - τ) * (velocity b - velocity a))
      by (apply Qmult_le_0_compat; lra).
    lra.
Qed.

(** Two clusters ordered at [τ] that approach meet at or after [τ]. *)
Lemma meeting_after (τ : Q) (a b : cluster) :
  Nonempty a -> Nonempty b -> center τ a <= center τ b -> approaching a b = true ->
  τ <= meeting_time a b.
Proof.
  intros Ha Hb Hord E. pose proof (gap_meeting τ a b Ha Hb E) as G.
  pose proof (approaching_velocity a b E) as V.
  apply Qnot_lt_le. intro Hlt.
  assert ((velocity a - velocity b) * (τ - meeting_time a b) > 0)
    by (apply Qmult_lt_0_compat; lra).
  lra.
Qed.

(** The center of two clusters joined lies between theirs. *)
Lemma center_app_le (τ m : Q) (a b : cluster) :
  Nonempty a -> Nonempty b -> center τ a <= m -> center τ b <= m ->
  center τ (a ++ b) <= m.
Proof.
  intros Ha Hb H1 H2. pose proof (size_pos a Ha). pose proof (size_pos b Hb).
  unfold center at 1. rewrite map_app, qsum_app, size_app, !sum_center by assumption.
  apply Qle_shift_div_r; [lra|].
  assert (size a * center τ a <= size a * m) by (apply Qmult_le_l; assumption).
  assert (size b * center τ b <= size b * m) by (apply Qmult_le_l; assumption).
  lra.
Qed.

Lemma center_app_ge (τ m : Q) (a b : cluster) :
  Nonempty a -> Nonempty b -> m <= center τ a -> m <= center τ b ->
  m <= center τ (a ++ b).
Proof.
  intros Ha Hb H1 H2. pose proof (size_pos a Ha). pose proof (size_pos b Hb).
  unfold center at 1. rewrite map_app, qsum_app, size_app, !sum_center by assumption.
  apply Qle_shift_div_l; [lra|].
  assert (size a * m <= size a * center τ a) by (apply Qmult_le_l; assumption).
  assert (size b * m <= size b * center τ b) by (apply Qmult_le_l; assumption).
  lra.
Qed.

(** ** Stability *)

(** A cluster stable at [τ]: every prefix has mean free position (at [τ])
    and mean initial velocity at least the cluster's. *)
Definition Stable (τ : Q) (c : cluster) : Prop :=
  Pooled (map (free_position τ) c) /\ Pooled (map snd c).

Lemma pooled_singleton (x : Q) : Pooled [x].
Proof.
  intros k Hk; simpl in Hk; destruct k as [|[|k]]; try lia;
    unfold psum; simpl firstn; simpl qsum; simpl length.
  - rewrite qn_0. lra.
  - apply Qle_refl.
Qed.

Lemma stable_singleton (τ : Q) (p : particle) : Stable τ [p].
Proof. split; apply pooled_singleton. Qed.

(** A stable cluster stays stable: both prefix conditions are linear in
    time and the velocity one makes the position one grow. *)
Lemma stable_later (τ τ' : Q) (c : cluster) :
  τ <= τ' -> Stable τ c -> Stable τ' c.
Proof.
  intros Ht (Hx & Hu). split; [|exact Hu].
  intros k Hk. rewrite map_length in Hk |- *.
  specialize (Hx k ltac:(rewrite map_length; exact Hk)).
  specialize (Hu k ltac:(rewrite map_length; exact Hk)).
  rewrite map_length in Hx, Hu.
  rewrite qsum_free, psum_free. rewrite qsum_free, psum_free in Hx.
  set (n := qn (length c)) in *. set (m := qn k) in *.
  set (X := qsum (map fst c)) in *. set (U := qsum (map snd c)) in *.
  set (PX := psum k (map fst c)) in *. set (PU := psum k (map snd c)) in *.
  change (qn (length c)) with n in Hu.
  assert (0 <= (τ' - τ) * (n * PU - m * U)) by (apply Qmult_le_0_compat; lra).
  setoid_replace (n * (PX + τ' * PU)) with
    (n * (PX + τ * PU) + (τ' - τ) * (n * PU - m * U) + m * (τ' - τ) * U) by ring.
  setoid_replace (m * (X + τ' * U)) with (m * (X + τ * U) + m * (τ' - τ) * U) by ring.
  lra.
Qed.

(** Two pooled segments, the left one of larger mean, pool into one. *)
Lemma pooled_app (a b : list Q) :
  a <> [] -> b <> [] -> Pooled a -> Pooled b ->
  qn (length a) * qsum b <= qn (length b) * qsum a ->
  Pooled (a ++ b).
Proof.
  intros Na Nb Qa Qb Hp.
  assert (HnA : 0 < qn (length a)) by (apply qn_pos; destruct a; [contradiction|simpl; lia]).
  assert (HnB : 0 < qn (length b)) by (apply qn_pos; destruct b; [contradiction|simpl; lia]).
  intros k Hk. rewrite app_length in Hk. rewrite qsum_app, app_length, qn_add.
  destruct (Nat.le_gt_cases k (length a)) as [Hle|Hgt].
  - rewrite psum_app_le by exact Hle.
    specialize (Qa k Hle).
    pose proof (merge_left (qn (length a)) (qn (length b)) (qn k)
                  (qsum a) (qsum b) (psum k a)) as M.
    pose proof (qn_nonneg k). lapply M; [clear M; intro M|exact HnA]. lra.
  - rewrite psum_app_ge by lia.
    set (j := (k - length a)%nat).
    assert (Hk' : k = (length a + j)%nat) by (unfold j; lia).
    assert (Hj : (j <= length b)%nat) by (unfold j; lia).
    rewrite Hk', qn_add.
    specialize (Qb j Hj). pose proof (qn_le _ _ Hj).
    pose proof (merge_right (qn (length a)) (qn (length b)) (qn j)
                  (qsum a) (qsum b) (psum j b)) as M.
    pose proof (qn_nonneg j). lapply M; [clear M; intro M|lra]. lra.
Qed.

(** Cross-multiplied form of a comparison of means. *)
Lemma mean_cross (sa sb ka kb : Q) :
  0 < ka -> 0 < kb -> sb / kb <= sa / ka -> ka * sb <= kb * sa.
Proof.
  intros Ha Hb H.
  setoid_replace (ka * sb) with (ka * kb * (sb / kb)) by (field; lra).
  setoid_replace (kb * sa) with (ka * kb * (sa / ka)) by (field; lra).
  apply Qmult_le_l; [apply Qmult_lt_0_compat|]; assumption.
Qed.

(** Two stable clusters meeting at [τ] (equal centers), the left one faster,
    merge into a stable cluster. *)
Lemma stable_merge (τ : Q) (a b : cluster) :
  Nonempty a -> Nonempty b -> Stable τ a -> Stable τ b ->
  center τ b <= center τ a -> velocity b <= velocity a ->
  Stable τ (a ++ b).
Proof.
  intros Na Nb (Xa & Ua) (Xb & Ub) Hc Hv.
  pose proof (size_pos a Na) as Pa. pose proof (size_pos b Nb) as Pb.
  assert (Ma : map (free_position τ) a <> []) by (destruct a; [contradiction|discriminate]).
  assert (Mb : map (free_position τ) b <> []) by (destruct b; [contradiction|discriminate]).
  assert (Sa : map snd a <> []) by (destruct a; [contradiction|discriminate]).
  assert (Sb : map snd b <> []) by (destruct b; [contradiction|discriminate]).
  split; rewrite map_app; apply pooled_app; auto; rewrite !map_length; apply mean_cross; auto.
Qed.
