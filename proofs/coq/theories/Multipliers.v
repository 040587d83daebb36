(** * The multipliers of the sticky dynamics ([eq:dyn-micro]).

    Paper, [prop:proj-micro]: "there exist non-negative multipliers
    (λ_i)_{i=0,…,N} such that u(t) = u_0 − N Σ_{i=1}^{N−1} λ_i(t)(e_i − e_{i+1}),
    λ_0(t) = λ_N(t) = 0, and λ_i(t)(x_{i+1}(t) − x_i(t) − 2r) = 0."

    Reading the identity entry by entry, [u_i = u⁰_i − N(λ_i − λ_{i−1})]
    (1-based), so [λ_k = (1/N) Σ_{j ≤ k} (u⁰_j − u_j)]: that is our
    definition ([multiplier], [k = 0..N]); the theorems are the identity,
    [λ_0 = λ_N = 0], [λ ≥ 0] and the complementarity. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection.
Import ListNotations.
Open Scope Q_scope.

(** ** Vectors constant on clusters *)

(** The value [f c] of each cluster given to each of its members. *)
Definition spread (f : cluster -> Q) (cs : list cluster) : list Q :=
  concat (map (fun c => repeat (f c) (length c)) cs).

(** Entries [i] and [j] belong to one cluster: every vector constant on
    clusters takes one value there. *)
Definition SameCluster (cs : list cluster) (i j : nat) : Prop :=
  forall f, nth i (spread f cs) 0 == nth j (spread f cs) 0.

Lemma nth_repeat_lt (a d : Q) (m n : nat) : (n < m)%nat -> nth n (repeat a m) d = a.
Proof.
  revert n. induction m as [|m IH]; intros n H; [lia|].
  destruct n; simpl; [reflexivity|apply IH; lia].
Qed.

Lemma spread_length (f : cluster -> Q) (cs : list cluster) :
  length (spread f cs) = length (concat cs).
Proof.
  induction cs as [|c cs IH]; [reflexivity|].
  unfold spread in *. simpl. rewrite !app_length, repeat_length, IH. reflexivity.
Qed.

(** The gap [D_k = Σ_{j<k} (u⁰_j − u_j)] between the partial sums of the
    initial velocities and of the cluster velocities: non-negative, and zero
    unless entries [k − 1] and [k] share a cluster. *)
Lemma velocity_gaps (cs : list cluster) :
  Forall Nonempty cs -> Forall (fun c => Pooled (map snd c)) cs ->
  forall k, (k <= length (concat cs))%nat ->
  0 <= psum k (map snd (concat cs)) - psum k (spread velocity cs) /\
  (psum k (map snd (concat cs)) - psum k (spread velocity cs) == 0 \/
   SameCluster cs (k - 1) k).
Proof.
  induction cs as [|c cs IH]; intros HN HP k Hk.
  - simpl in Hk. replace k with 0%nat by lia. unfold psum. simpl. split; [lra|left; lra].
  - inversion HN as [|? ? Nc HN']; inversion HP as [|? ? Pc HP']; subst.
    assert (Hm : velocity c == qsum (map snd c) / qn (length (map snd c)))
      by (rewrite map_length; reflexivity).
    assert (Hseg : map snd c <> []) by (destruct c; [contradiction|discriminate]).
    pose proof (size_pos c Nc) as Hpos. unfold size in Hpos.
    assert (Htot : qsum (map snd c) - qn (length c) * velocity c == 0)
      by (rewrite (sum_velocity c Nc); unfold size; ring).
    simpl concat in Hk |- *. rewrite app_length in Hk.
    unfold spread. simpl map. simpl concat. fold (spread velocity cs).
    rewrite map_app.
    destruct (Nat.le_gt_cases k (length c)) as [Hle|Hgt].
    + rewrite !psum_app_le by (rewrite ?map_length, ?repeat_length; exact Hle).
      rewrite psum_repeat by exact Hle.
      pose proof (pooled_prefix (map snd c) Hseg Pc k ltac:(rewrite map_length; exact Hle)) as Hpre.
      rewrite <- Hm in Hpre. split; [exact Hpre|].
      destruct k as [|k]; [left; rewrite psum_0, qn_0; ring|].
      destruct (Nat.eq_dec (S k) (length c)) as [Heq|Hne].
      * left. rewrite Heq. unfold psum. rewrite firstn_all2 by (rewrite map_length; lia).
        exact Htot.
      * right. intros f. simpl Nat.sub. rewrite Nat.sub_0_r.
        unfold spread. simpl map. simpl concat.
        rewrite !app_nth1 by (rewrite repeat_length; lia).
        rewrite !nth_repeat_lt by lia. apply Qeq_refl.
    + rewrite !psum_app_ge by (rewrite ?map_length, ?repeat_length; lia).
      rewrite map_length, repeat_length, qsum_repeat.
      destruct (IH HN' HP' (k - length c)%nat ltac:(lia)) as [H0 H1].
      split; [lra|]. destruct H1 as [H1|H1]; [left; lra|right].
      intros f. specialize (H1 f). unfold spread in H1 |- *. simpl map. simpl concat.
      rewrite !app_nth2 by (rewrite repeat_length; lia). rewrite repeat_length.
      replace (k - 1 - length c)%nat with (k - length c - 1)%nat by lia. exact H1.
Qed.

(** ** The multipliers *)

(** [λ_k(t) = (1/N) Σ_{j<k} (u⁰_j − u_j(t))], [k = 0..N] (partial sums over
    the first [k] particles; the paper's [λ_k] with its 1-based [j ≤ k]). *)
Definition multiplier (x0 u0 : list Q) (r t : Q) (k : nat) : Q :=
  (psum k u0 - psum k (velocities (dynamics x0 u0 r t))) / qn (length x0).

Lemma map_snd_combine (y u : list Q) :
  length y = length u -> map snd (combine y u) = u.
Proof.
  revert u. induction y as [|a y IH]; intros [|b u] L; simpl in *; try discriminate.
  - reflexivity.
  - f_equal. apply IH. lia.
Qed.

Lemma translate_from_length (k : nat) (r : Q) (x : list Q) :
  length (translate_from k r x) = length x.
Proof. revert k. induction x; intro k; simpl; auto. Qed.

Lemma untranslate_from_length (k : nat) (r : Q) (x : list Q) :
  length (untranslate_from k r x) = length x.
Proof. revert k. induction x; intro k; simpl; auto. Qed.

Lemma particles_u0 (x0 u0 : list Q) (r : Q) :
  length u0 = length x0 -> map snd (particles x0 u0 r) = u0.
Proof.
  intro L. unfold particles. apply map_snd_combine.
  unfold translate. rewrite translate_from_length. auto.
Qed.

Lemma particles_length (x0 u0 : list Q) (r : Q) :
  length u0 = length x0 -> length (particles x0 u0 r) = length x0.
Proof.
  intro L. unfold particles. rewrite combine_length. unfold translate.
  rewrite translate_from_length. lia.
Qed.

Lemma nth_untranslate_from (r : Q) (y : list Q) :
  forall k i, (i < length y)%nat ->
  nth i (untranslate_from k r y) 0 == nth i y 0 + 2 * r * qn (k + i).
Proof.
  induction y as [|a y IH]; intros k i Hi; simpl in Hi; [lia|].
  destruct i as [|i]; simpl.
  - rewrite Nat.add_0_r. reflexivity.
  - rewrite IH by lia. rewrite Nat.add_succ_r. reflexivity.
Qed.

(** The facts on the clusters at [t] the theorems below rest on. *)
Lemma clusters_facts (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  let cs := clusters x0 u0 r t in
  Invariant t cs /\ map snd (concat cs) = u0 /\ length (concat cs) = length x0.
Proof.
  intros Ht HK L cs. destruct (clusters_invariant x0 u0 r t Ht HK) as [HI Hc].
  split; [exact HI|]. unfold cs. rewrite Hc. split.
  - apply particles_u0. exact L.
  - apply particles_length. exact L.
Qed.

Lemma velocities_spread (x0 u0 : list Q) (r t : Q) :
  velocities (dynamics x0 u0 r t) = spread velocity (clusters x0 u0 r t).
Proof. reflexivity. Qed.

Lemma positions_spread (x0 u0 : list Q) (r t : Q) :
  positions (dynamics x0 u0 r t) = untranslate r (spread (center t) (clusters x0 u0 r t)).
Proof. reflexivity. Qed.

Lemma multiplier_gap (x0 u0 : list Q) (r t : Q) (k : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (k <= length x0)%nat ->
  let cs := clusters x0 u0 r t in
  0 <= psum k u0 - psum k (velocities (dynamics x0 u0 r t)) /\
  (psum k u0 - psum k (velocities (dynamics x0 u0 r t)) == 0 \/ SameCluster cs (k - 1) k).
Proof.
  intros Ht HK L Hk cs. destruct (clusters_facts x0 u0 r t Ht HK L) as ((HN & HS & _) & Hu & Hl).
  fold cs in HN, HS, Hu, Hl.
  assert (HP : Forall (fun c => Pooled (map snd c)) cs)
    by (eapply Forall_impl; [|exact HS]; intros c (_ & H); exact H).
  pose proof (velocity_gaps cs HN HP k ltac:(lia)) as G. rewrite Hu in G. exact G.
Qed.

Lemma psum_succ (l : list Q) :
  forall i, (i < length l)%nat -> psum (S i) l == psum i l + nth i l 0.
Proof.
  induction l as [|a l IH]; intros i Hi; simpl in Hi; [lia|].
  destruct i as [|i].
  - unfold psum. simpl. ring.
  - rewrite !psum_cons, IH by lia. simpl. ring.
Qed.

(** Paper, [eq:dyn-micro]: "u(t) = u_0 − N Σ_{i=1}^{N−1} λ_i(t)(e_i − e_{i+1})",
    entry by entry: [u_i = u⁰_i − N(λ_i − λ_{i−1})] (1-based; here the
    0-based entry [i] and [λ_{i+1} − λ_i]). Ledger claim: [eq:dyn-micro]. *)
Theorem dyn_micro_identity (x0 u0 : list Q) (r t : Q) (i : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (i < length x0)%nat ->
  nth i (velocities (dynamics x0 u0 r t)) 0 ==
  nth i u0 0 - qn (length x0) * (multiplier x0 u0 r t (S i) - multiplier x0 u0 r t i).
Proof.
  intros Ht HK L Hi.
  assert (HN : 0 < qn (length x0)) by (apply qn_pos; lia).
  assert (Lv : length (velocities (dynamics x0 u0 r t)) = length x0).
  { rewrite velocities_spread, spread_length. apply (clusters_facts x0 u0 r t Ht HK L). }
  unfold multiplier.
  set (v := velocities (dynamics x0 u0 r t)) in *.
  rewrite (psum_succ u0) by lia. rewrite (psum_succ v) by lia. field. lra.
Qed.

(** [λ_0 = λ_N = 0]. Ledger claim: [eq:dyn-micro]. *)
Theorem multiplier_ends (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  multiplier x0 u0 r t 0 == 0 /\ multiplier x0 u0 r t (length x0) == 0.
Proof.
  intros Ht HK L. split.
  - unfold multiplier, psum. simpl. unfold Qdiv. ring.
  - destruct (clusters_facts x0 u0 r t Ht HK L) as ((HN & HS & _) & Hu & Hl).
    destruct (multiplier_gap x0 u0 r t (length x0) Ht HK L (le_n _)) as [_ [H|H]].
    + unfold multiplier. rewrite H. unfold Qdiv. ring.
    + (* at k = N the partial sums are the totals, equal for each cluster *)
      assert (HP : Forall (fun c => Pooled (map snd c)) (clusters x0 u0 r t))
        by (eapply Forall_impl; [|exact HS]; intros c (_ & Hc); exact Hc).
      clear H. unfold multiplier.
      set (cs := clusters x0 u0 r t) in *.
      assert (T : psum (length x0) u0 == psum (length x0) (velocities (dynamics x0 u0 r t))).
      { rewrite velocities_spread. fold cs. unfold psum. rewrite !firstn_all2.
        2: { rewrite spread_length. lia. }
        2: lia.
        rewrite <- Hu. clear - HN HP. induction cs as [|c cs IH]; [reflexivity|].
        inversion HN as [|? ? Nc HN']; inversion HP; subst.
        unfold spread. simpl. rewrite map_app, !qsum_app, qsum_repeat. fold (spread velocity cs).
        rewrite <- IH by assumption. rewrite (sum_velocity c Nc). unfold size. ring. }
      rewrite T. unfold Qdiv. ring.
Qed.

(** [λ_k ≥ 0]. Ledger claim: [eq:dyn-micro]. *)
Theorem multiplier_nonneg (x0 u0 : list Q) (r t : Q) (k : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (k <= length x0)%nat ->
  0 <= multiplier x0 u0 r t k.
Proof.
  intros Ht HK L Hk. destruct (multiplier_gap x0 u0 r t k Ht HK L Hk) as [H _].
  unfold multiplier. destruct (length x0) as [|n] eqn:E.
  - unfold qn. simpl. unfold Qdiv, Qinv. simpl. lra.
  - apply Qle_shift_div_l; [apply qn_pos; lia|]. lra.
Qed.

(** Paper: "λ_i(t)(x_{i+1}(t) − x_i(t) − 2r) = 0", [i = 1..N−1]: here
    [λ_k (x_k − x_{k−1} − 2r) = 0] for the 0-based [x], [0 < k < N].
    Ledger claim: [eq:dyn-micro]. *)
Theorem multiplier_complementarity (x0 u0 : list Q) (r t : Q) (k : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (0 < k < length x0)%nat ->
  let x := positions (dynamics x0 u0 r t) in
  multiplier x0 u0 r t k * (nth k x 0 - nth (k - 1) x 0 - 2 * r) == 0.
Proof.
  intros Ht HK L Hk x.
  destruct (multiplier_gap x0 u0 r t k Ht HK L ltac:(lia)) as [_ [H|H]].
  - unfold multiplier. rewrite H. unfold Qdiv. ring.
  - destruct (clusters_facts x0 u0 r t Ht HK L) as (_ & _ & Hl).
    specialize (H (center t)).
    set (cs := clusters x0 u0 r t) in *.
    assert (Ly : length (spread (center t) cs) = length x0) by (rewrite spread_length; exact Hl).
    unfold x. rewrite positions_spread. fold cs.
    unfold untranslate. rewrite !nth_untranslate_from by lia.
    assert (Hq : qn k == qn (k - 1) + 1)
      by (rewrite <- qn_S; replace (S (k - 1)) with k by lia; reflexivity).
    rewrite H, !Nat.add_0_l, Hq. ring.
Qed.
