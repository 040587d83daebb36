(** * The KKT multipliers of the position projection are [μ = ∫₀ᵗ λ]
      ([app:KKT], corrected).

    Paper, Appendix A ([app:KKT]): the KKT conditions of
    [min ½‖x − (x⁰ + t u⁰)‖²] over [K^N] "yield the existence of
    multipliers λ_i(t) ≥ 0 such that
    x(t) − (x⁰ + t u⁰) + N Σ_{i=1}^{N−1} λ_i(t)(e_i − e_{i+1}) = 0,
    λ_i(t)(x_{i+1}(t) − x_i(t) − 2r) = 0", and calls them the multipliers
    of [eq:dyn-micro]. They are not (the ledger refutes it, see
    [Errata.kkt_multipliers_are_lambda_false]): the multipliers of the
    position projection are [μ(t) = ∫₀ᵗ λ(s) ds], the time integral of the
    velocity multipliers [λ] of [eq:dyn-micro] ([Multipliers.multiplier]).

    Read entry by entry, the stationarity identity fixes the multipliers:
    [μ_k = (1/N) Σ_{j<k} (x⁰_j + t u⁰_j − x_j(t))] (0-based, [k] entries),
    our [kkt_multiplier]. [kkt_multiplier_kkt] proves they are KKT
    multipliers (stationarity, [μ_0 = μ_N = 0], [μ ≥ 0], complementarity);
    [kkt_multiplier_is_integral] proves [μ(t) = ∫₀ᵗ λ(s) ds] where [λ] is a
    step function: the collision instants of the dynamics cut [[0, t]] into
    finitely many intervals [[a, b)] on which the clusters, hence [λ], are
    constant, and the integral is the finite sum [Σ (b − a) λ(a)].

    The proof follows the event-driven run ([Dynamics.run]): between two
    collisions the partial sums [D_k = Σ_{j<k} (x̃⁰_j + τ u⁰_j − x̃_j(τ))]
    grow at the rate [N λ_k]; at a collision the two clusters that merge are
    at one position, so [x(τ)] and [D_k] do not jump. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers DynamicsIsProjK Neighbours.
Import ListNotations.
Open Scope Q_scope.

(** ** The collision intervals *)

(** The run of [Dynamics.run] from the clusters [cs] at time [from], cut
    at its collision instants: each piece is [(a, b, cs)], the clusters
    [cs] on [[a, b)]. The last piece ends at [t]. *)
Fixpoint pieces (fuel : nat) (from t : Q) (cs : list cluster) : list (Q * Q * list cluster) :=
  match fuel with
  | O => [(from, t, cs)]
  | S f =>
      match next_meeting cs with
      | Some τ =>
          if Qle_bool τ t then (from, τ, cs) :: pieces f τ t (merge_at τ cs)
          else [(from, t, cs)]
      | None => [(from, t, cs)]
      end
  end.

(** The collision intervals of the data [(x⁰, u⁰)] on [[0, t]]: the
    intervals between consecutive collision instants, in order. *)
Definition collision_intervals (x0 u0 : list Q) (r t : Q) : list (Q * Q) :=
  let ps := particles x0 u0 r in
  map fst (pieces (length ps) 0 t (map (fun p => [p]) ps)).

(** [ps] cuts [[a, t]] into consecutive intervals [[a_i, b_i]],
    [a_0 = a], [b_i = a_{i+1}], [b_last = t], each with [a_i ≤ b_i]. *)
Fixpoint Partition (a t : Q) (ps : list (Q * Q)) : Prop :=
  match ps with
  | [] => False
  | (a', b) :: ps' =>
      a' = a /\ a <= b /\
      match ps' with
      | [] => b = t
      | _ => Partition b t ps'
      end
  end.

(** The integral over the intervals [ps] of a function constant on each
    [[a_i, b_i)]: [Σ (b_i − a_i) f(a_i)]. *)
Definition step_integral (f : Q -> Q) (ps : list (Q * Q)) : Q :=
  qsum (map (fun p => (snd p - fst p) * f (fst p)) ps).

(** The KKT multipliers of [P_K(x⁰ + t u⁰)] read off the stationarity
    identity: [μ_k = (1/N) Σ_{j<k} (x⁰_j + t u⁰_j − x_j(t))], [k = 0..N]. *)
Definition kkt_multiplier (x0 u0 : list Q) (r t : Q) (k : nat) : Q :=
  (psum k (free_flight x0 u0 t) - psum k (positions (dynamics x0 u0 r t))) / qn (length x0).

(** ** One step of the run *)

Lemma step_invariant (from m : Q) (cs : list cluster) :
  Invariant from cs -> next_meeting cs = Some m ->
  from <= m /\ Invariant m (merge_at m cs).
Proof.
  intros HI Em.
  pose proof (next_meeting_after from cs (proj1 HI) (proj2 (proj2 HI)) m Em) as Hm.
  split; [exact Hm|].
  apply (merge_invariant m cs). apply (invariant_later from m cs HI Hm).
  apply next_meeting_some. exact Em.
Qed.

(** Every piece starts no earlier than [from] and ends no earlier than it
    starts. *)
Lemma pieces_ordered (t : Q) (fuel : nat) :
  forall from cs, Invariant from cs -> from <= t ->
  forall a b c, In (a, b, c) (pieces fuel from t cs) -> from <= a /\ a <= b.
Proof.
  induction fuel as [|f IH]; intros from cs HI Ht a b c Hin; simpl in Hin.
  - destruct Hin as [E|[]]. injection E as <- <- <-. lra.
  - destruct (next_meeting cs) as [m|] eqn:Em.
    + destruct (step_invariant from m cs HI Em) as [Hm HI2].
      destruct (Qle_bool m t) eqn:L.
      * apply Qle_bool_iff in L. destruct Hin as [E|Hin].
        -- injection E as <- <- <-. lra.
        -- destruct (IH m _ HI2 L a b c Hin). lra.
      * destruct Hin as [E|[]]. injection E as <- <- <-. lra.
    + destruct Hin as [E|[]]. injection E as <- <- <-. lra.
Qed.

Lemma pieces_partition (t : Q) (fuel : nat) :
  forall from cs, Invariant from cs -> from <= t ->
  Partition from t (map fst (pieces fuel from t cs)).
Proof.
  induction fuel as [|f IH]; intros from cs HI Ht; simpl.
  - repeat split; auto.
  - destruct (next_meeting cs) as [m|] eqn:Em.
    + destruct (step_invariant from m cs HI Em) as [Hm HI2].
      destruct (Qle_bool m t) eqn:L.
      * apply Qle_bool_iff in L. simpl. split; [reflexivity|split; [exact Hm|]].
        pose proof (IH m _ HI2 L) as P.
        destruct (map fst (pieces f m t (merge_at m cs))); [contradiction|exact P].
      * simpl. repeat split; auto.
    + simpl. repeat split; auto.
Qed.

(** On each piece [[a, b)], the run to any [s] in it stops at the piece's
    clusters. *)
Lemma pieces_run (t : Q) (fuel : nat) :
  forall from cs, Invariant from cs -> from <= t ->
  forall a b c, In (a, b, c) (pieces fuel from t cs) ->
  forall s, a <= s -> s < b -> run fuel s cs = c.
Proof.
  induction fuel as [|f IH]; intros from cs HI Ht a b c Hin s Ha Hb; simpl in Hin |- *.
  - destruct Hin as [E|[]]. injection E as <- <- <-. reflexivity.
  - destruct (next_meeting cs) as [m|] eqn:Em.
    + destruct (step_invariant from m cs HI Em) as [Hm HI2].
      destruct (Qle_bool m t) eqn:L.
      * apply Qle_bool_iff in L. destruct Hin as [E|Hin].
        -- injection E as <- <- <-.
           destruct (Qle_bool m s) eqn:Ls; [apply Qle_bool_iff in Ls; lra|reflexivity].
        -- destruct (pieces_ordered t f m _ HI2 L a b c Hin) as [Hma _].
           rewrite (proj2 (Qle_bool_iff m s)) by lra.
           apply (IH m _ HI2 L a b c Hin s Ha Hb).
      * destruct Hin as [E|[]]. injection E as <- <- <-.
        destruct (Qle_bool m s) eqn:Ls; [|reflexivity].
        apply Qle_bool_iff in Ls.
        assert (t < m) by (apply Qnot_le_lt; rewrite <- Qle_bool_iff, L; discriminate).
        lra.
    + destruct Hin as [E|[]]. injection E as <- <- <-. reflexivity.
Qed.

Lemma pieces_concat (t : Q) (fuel : nat) :
  forall from cs a b c, In (a, b, c) (pieces fuel from t cs) -> concat c = concat cs.
Proof.
  induction fuel as [|f IH]; intros from cs a b c Hin; simpl in Hin.
  - destruct Hin as [E|[]]. injection E as <- <- <-. reflexivity.
  - destruct (next_meeting cs) as [m|] eqn:Em; [destruct (Qle_bool m t)|].
    + destruct Hin as [E|Hin]; [injection E as <- <- <-; reflexivity|].
      rewrite (IH _ _ _ _ _ Hin). apply merge_at_concat.
    + destruct Hin as [E|[]]. injection E as <- <- <-. reflexivity.
    + destruct Hin as [E|[]]. injection E as <- <- <-. reflexivity.
Qed.

(** ** The partial sums [D_k] along the run *)

(** Each member of each cluster, as a list of its clusters. *)
Definition members (cs : list cluster) : list cluster :=
  concat (map (fun c => repeat c (length c)) cs).

Lemma map_repeat_eq {A B : Type} (f : A -> B) (x : A) (n : nat) :
  map f (repeat x n) = repeat (f x) n.
Proof. induction n as [|n IH]; simpl; [reflexivity|rewrite IH; reflexivity]. Qed.

Lemma spread_members (f : cluster -> Q) (cs : list cluster) :
  spread f cs = map f (members cs).
Proof.
  induction cs as [|c cs IH]; [reflexivity|].
  unfold spread, members in *. simpl. rewrite map_app, IH, map_repeat_eq. reflexivity.
Qed.

Lemma in_members (c : cluster) (cs : list cluster) : In c (members cs) -> In c cs.
Proof.
  unfold members. intro H. apply in_concat in H. destruct H as (l & Hl & Hc).
  apply in_map_iff in Hl. destruct Hl as (d & <- & Hd).
  apply repeat_spec in Hc. subst. exact Hd.
Qed.

Lemma psum_map_affine {A : Type} (f g v : A -> Q) (h : Q) (l : list A) :
  (forall x, In x l -> f x == g x + h * v x) ->
  forall k, psum k (map f l) == psum k (map g l) + h * psum k (map v l).
Proof.
  induction l as [|x l IH]; intros H k; [unfold psum; destruct k; simpl; ring|].
  destruct k as [|k]; [unfold psum; simpl; ring|].
  simpl map. rewrite !psum_cons, IH by (intros y Hy; apply H; right; exact Hy).
  rewrite (H x (or_introl eq_refl)). ring.
Qed.

(** [D_k(τ)] for the clusters [cs]: the partial sum of the translated free
    flight minus that of the translated positions. *)
Definition gap_sum (k : nat) (τ : Q) (cs : list cluster) : Q :=
  psum k (map (free_position τ) (concat cs)) - psum k (translated_positions τ cs).

(** [N λ_k] for the clusters [cs]. *)
Definition rate (k : nat) (cs : list cluster) : Q :=
  psum k (map snd (concat cs)) - psum k (spread velocity cs).

(** Between collisions [D_k] grows at the rate [N λ_k]. *)
Lemma gap_sum_affine (k : nat) (a b : Q) (cs : list cluster) :
  Forall Nonempty cs -> gap_sum k b cs - gap_sum k a cs == (b - a) * rate k cs.
Proof.
  intro HN. unfold gap_sum, rate, translated_positions.
  fold (spread (center b) cs). fold (spread (center a) cs).
  rewrite !spread_members.
  rewrite (psum_map_affine (free_position b) (free_position a) snd (b - a) (concat cs))
    by (intros p _; unfold free_position; ring).
  rewrite (psum_map_affine (center b) (center a) velocity (b - a) (members cs)).
  - ring.
  - intros c Hc. apply in_members in Hc. rewrite Forall_forall in HN.
    pose proof (HN c Hc) as Nc. rewrite (center_linear b c Nc), (center_linear a c Nc). ring.
Qed.

(** The two clusters merging at [τ] are at one position at [τ]: merging
    them moves nobody. *)
Lemma merge_positions (τ : Q) (cs : list cluster) :
  Forall Nonempty cs ->
  qeq_list (translated_positions τ (merge_at τ cs)) (translated_positions τ cs).
Proof.
  induction cs as [|a rest IH]; intro HN; [constructor|].
  destruct rest as [|b rest]; [apply qeq_list_refl|].
  inversion HN as [|? ? Na HN']. inversion HN' as [|? ? Nb _].
  rewrite merge_at_pair.
  destruct (approaching a b && Qeq_bool (meeting_time a b) τ) eqn:E.
  - apply andb_prop in E. destruct E as [Eap Eq]. apply Qeq_bool_iff in Eq.
    pose proof (gap_meeting τ a b Na Nb Eap) as G. rewrite Eq in G.
    assert (Hab : center τ b == center τ a) by lra.
    assert (Hc : center τ (a ++ b) == center τ a).
    { apply Qle_antisym; [apply center_app_le|apply center_app_ge]; auto; lra. }
    unfold translated_positions. simpl map. simpl concat. rewrite app_assoc.
    apply Forall2_app; [|apply qeq_list_refl].
    rewrite app_length, repeat_app. apply Forall2_app; apply qeq_list_repeat; lra.
  - unfold translated_positions in *. simpl map. simpl concat.
    apply Forall2_app; [apply qeq_list_refl|]. apply IH. exact HN'.
Qed.

Lemma merge_nonempty (τ : Q) (cs : list cluster) :
  Forall Nonempty cs -> Forall Nonempty (merge_at τ cs).
Proof.
  induction cs as [|a rest IH]; intro HN; [constructor|].
  destruct rest as [|b rest]; [exact HN|].
  inversion HN as [|? ? Na HN']. inversion HN' as [|? ? Nb HN''].
  rewrite merge_at_pair. destruct (_ && _).
  - constructor; [destruct a; [contradiction|discriminate]|exact HN''].
  - constructor; [exact Na|apply IH; exact HN'].
Qed.

(** A merge at [τ] leaves [D_k(τ)] unchanged. *)
Lemma gap_sum_merge (k : nat) (τ : Q) (cs : list cluster) :
  Forall Nonempty cs -> gap_sum k τ (merge_at τ cs) == gap_sum k τ cs.
Proof.
  intro HN. unfold gap_sum. rewrite merge_at_concat.
  rewrite (qeq_list_psum _ _ (merge_positions τ cs HN)). ring.
Qed.

(** Along the run, [D_k] at the end minus [D_k] at the start is the sum
    over the pieces of [(b − a) N λ_k]. *)
Lemma pieces_sum (k : nat) (t : Q) (fuel : nat) :
  forall from cs, Forall Nonempty cs ->
  gap_sum k t (run fuel t cs) - gap_sum k from cs ==
  qsum (map (fun p => (snd (fst p) - fst (fst p)) * rate k (snd p)) (pieces fuel from t cs)).
Proof.
  induction fuel as [|f IH]; intros from cs HN; simpl.
  - rewrite (gap_sum_affine k from t cs HN). ring.
  - destruct (next_meeting cs) as [m|] eqn:Em; [destruct (Qle_bool m t)|]; simpl.
    + pose proof (IH m (merge_at m cs) (merge_nonempty m cs HN)) as H.
      rewrite (gap_sum_merge k m cs HN) in H.
      rewrite <- H. rewrite <- (gap_sum_affine k from m cs HN). ring.
    + rewrite (gap_sum_affine k from t cs HN). ring.
    + rewrite (gap_sum_affine k from t cs HN). ring.
Qed.

(** ** From the run to the data *)

Lemma gap_sum_start (k : nat) (ps : list particle) :
  gap_sum k 0 (map (fun p => [p]) ps) == 0.
Proof.
  unfold gap_sum. enough (E : qeq_list (translated_positions 0 (map (fun p => [p]) ps))
                                       (map (free_position 0) (concat (map (fun p => [p]) ps)))).
  { rewrite (qeq_list_psum _ _ E). ring. }
  induction ps as [|p ps IH]; [constructor|].
  unfold translated_positions in *. simpl. constructor; [apply center_single|exact IH].
Qed.

Lemma psum_translate_untranslate (r : Q) (a : list Q) :
  forall b m k, length a = length b ->
  psum k a - psum k (untranslate_from m r b) == psum k (translate_from m r a) - psum k b.
Proof.
  induction a as [|x a IH]; intros [|y b] m k L; simpl in L; try discriminate.
  - unfold psum. destruct k; simpl; ring.
  - destruct k as [|k]; [unfold psum; simpl; ring|].
    simpl. rewrite !psum_cons.
    pose proof (IH b (S m) k ltac:(lia)). lra.
Qed.

(** [N μ_k(t) = D_k(t)]: the translation cancels in the difference. *)
Lemma kkt_gap_sum (x0 u0 : list Q) (r t : Q) (k : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  psum k (free_flight x0 u0 t) - psum k (positions (dynamics x0 u0 r t)) ==
  gap_sum k t (clusters x0 u0 r t).
Proof.
  intros Ht HK L. destruct (clusters_facts x0 u0 r t Ht HK L) as (_ & _ & Hl).
  destruct (clusters_invariant x0 u0 r t Ht HK) as [_ Hc].
  unfold gap_sum. rewrite Hc. unfold particles.
  rewrite (qeq_list_psum _ _ (free_positions_translate r t x0 u0 0 L)).
  unfold dynamics, positions, untranslate.
  rewrite psum_translate_untranslate; [reflexivity|].
  rewrite free_flight_length by exact L. unfold translated_positions.
  fold (spread (center t) (clusters x0 u0 r t)). rewrite spread_length. lia.
Qed.

Lemma qsum_map_ext_in {A : Type} (f g : A -> Q) (l : list A) :
  (forall x, In x l -> f x == g x) -> qsum (map f l) == qsum (map g l).
Proof.
  induction l as [|x l IH]; intro H; [reflexivity|]. simpl.
  rewrite (H x (or_introl eq_refl)), IH by (intros y Hy; apply H; right; exact Hy). reflexivity.
Qed.

Lemma qsum_map_div {A : Type} (f : A -> Q) (n : Q) (l : list A) :
  qsum (map (fun x => f x / n) l) == qsum (map f l) / n.
Proof. induction l as [|x l IH]; simpl; [unfold Qdiv; ring|rewrite IH; unfold Qdiv; ring]. Qed.

(** ** The theorems *)

(** Paper, Appendix A ([app:KKT]), corrected: the KKT multipliers of
    [x(t) = P_{K^N}(x⁰ + t u⁰)] are [μ(t) = ∫₀ᵗ λ(s) ds]. For every [N],
    [x⁰ ∈ K^N], any [u⁰], rational [t ≥ 0] and [k = 0..N]: the collision
    intervals partition [[0, t]]; on each of them, [[a, b)], the clusters
    (hence [λ], [Multipliers.multiplier]) are those at [a]; and
    [μ_k(t) = Σ (b − a) λ_k(a)], the integral of the step function [λ_k]
    over [[0, t]]. Ledger claim: [app:KKT] (corrected). *)
Theorem kkt_multiplier_is_integral (x0 u0 : list Q) (r t : Q) (k : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  let P := collision_intervals x0 u0 r t in
  Partition 0 t P /\
  (forall a b, In (a, b) P -> forall s, a <= s -> s < b ->
     clusters x0 u0 r s = clusters x0 u0 r a) /\
  kkt_multiplier x0 u0 r t k == step_integral (fun s => multiplier x0 u0 r s k) P.
Proof.
  intros Ht HK L P.
  set (ps := particles x0 u0 r). set (cs0 := map (fun p => [p]) ps).
  pose proof (singletons_invariant x0 u0 r HK) as HI0. fold ps cs0 in HI0.
  assert (Ec : forall s, clusters x0 u0 r s = run (length ps) s cs0) by reflexivity.
  split; [|split].
  - apply pieces_partition; assumption.
  - intros a b Hin s Ha Hb. unfold P, collision_intervals in Hin. fold ps cs0 in Hin.
    apply in_map_iff in Hin. destruct Hin as (((a' & b') & c) & E & Hin).
    simpl in E. injection E as -> ->.
    rewrite !Ec. rewrite (pieces_run t _ 0 cs0 HI0 Ht a b c Hin s Ha Hb).
    symmetry. apply (pieces_run t _ 0 cs0 HI0 Ht a b c Hin a (Qle_refl a)). lra.
  - unfold kkt_multiplier, step_integral, P, collision_intervals. fold ps cs0.
    rewrite (kkt_gap_sum x0 u0 r t k Ht HK L), Ec.
    pose proof (pieces_sum k t (length ps) 0 cs0 (proj1 HI0)) as H.
    pose proof (gap_sum_start k ps) as H0. fold cs0 in H0.
    rewrite map_map.
    apply Qeq_trans with (qsum (map (fun p => (snd (fst p) - fst (fst p)) * rate k (snd p))
                                      (pieces (length ps) 0 t cs0)) / qn (length x0)).
    { rewrite <- H, H0. unfold Qdiv. ring. }
    eapply Qeq_trans; [apply Qeq_sym, qsum_map_div|]. apply qsum_map_ext_in.
    intros [[a b] c] Hin. simpl.
    destruct (pieces_ordered t _ 0 cs0 HI0 Ht a b c Hin) as [_ Hab].
    destruct (Qlt_le_dec a b) as [Hlt|Hge].
    + assert (Ea : clusters x0 u0 r a = c)
        by (rewrite Ec; apply (pieces_run t _ 0 cs0 HI0 Ht a b c Hin a (Qle_refl a) Hlt)).
      unfold multiplier, rate. rewrite velocities_spread, Ea.
      rewrite (pieces_concat t _ 0 cs0 a b c Hin).
      assert (Hu : map snd (concat cs0) = u0).
      { unfold cs0. rewrite <- (particles_u0 x0 u0 r L). fold ps. f_equal.
        clear. induction ps as [|p ps IH]; simpl; congruence. }
      rewrite Hu. unfold Qdiv. ring.
    + assert (E0 : b - a == 0) by lra. rewrite E0. unfold Qdiv. ring.
Qed.

(** Paper, Appendix A ([app:KKT]): [μ] are the KKT multipliers of
    [x(t) = P_{K^N}(x⁰ + t u⁰)]. For every [N], [x⁰ ∈ K^N], any [u⁰] and
    rational [t ≥ 0], with [z = x⁰ + t u⁰]: stationarity
    [x(t) − z + N Σ_{i=1}^{N−1} μ_i (e_i − e_{i+1}) = 0] entry by entry
    (0-based entry [i]: [x_i − z_i + N(μ_{i+1} − μ_i) = 0]),
    [μ_0 = μ_N = 0], [μ ≥ 0], and complementarity
    [μ_k (x_k − x_{k−1} − 2r) = 0] ([0 < k < N], 0-based pair [(k−1, k)]).
    Stationarity determines [μ], so these are the multipliers; with
    [kkt_multiplier_is_integral], [μ = ∫₀ᵗ λ]. Ledger claim: [app:KKT]
    (corrected). *)
Theorem kkt_multiplier_kkt (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  let x := positions (dynamics x0 u0 r t) in
  let z := free_flight x0 u0 t in
  let N := length x0 in
  let μ := kkt_multiplier x0 u0 r t in
  (forall i, (i < N)%nat -> nth i x 0 - nth i z 0 + qn N * (μ (S i) - μ i) == 0) /\
  μ 0%nat == 0 /\ μ N == 0 /\
  (forall k, (k <= N)%nat -> 0 <= μ k) /\
  (forall k, (0 < k < N)%nat -> μ k * (nth k x 0 - nth (k - 1) x 0 - 2 * r) == 0).
Proof.
  intros Ht HK L x z N μ.
  destruct (clusters_facts x0 u0 r t Ht HK L) as (_ & _ & Hl).
  destruct (clusters_invariant x0 u0 r t Ht HK) as [_ Hc].
  set (cs := clusters x0 u0 r t) in *.
  set (Y := translated_positions t cs).
  set (Z := map (free_position t) (concat cs)).
  assert (HKkt : Kkt Z Y).
  { unfold Z, Y. rewrite Hc. apply dynamics_is_projection; assumption. }
  destruct HKkt as (LY & M & P & T & C).
  assert (LZ : length Z = N).
  { unfold Z. rewrite map_length. exact Hl. }
  assert (HD : forall k, μ k == (psum k Z - psum k Y) / qn N).
  { intro k. unfold μ, kkt_multiplier. fold N. rewrite (kkt_gap_sum x0 u0 r t k Ht HK L).
    reflexivity. }
  assert (Lx : length x = N).
  { unfold x. rewrite positions_spread. unfold untranslate.
    rewrite untranslate_from_length, spread_length. exact Hl. }
  assert (Lz : length z = N) by (apply free_flight_length; exact L).
  split; [|split; [|split; [|split]]].
  - intros i Hi. assert (HN : 0 < qn N) by (apply qn_pos; lia).
    unfold μ, kkt_multiplier. fold N x z.
    rewrite (psum_succ z) by lia. rewrite (psum_succ x) by lia. field. lra.
  - unfold μ, kkt_multiplier, psum. simpl. unfold Qdiv. ring.
  - rewrite HD. rewrite LZ in T. rewrite T. unfold Qdiv. ring.
  - intros k Hk. rewrite HD. destruct N as [|n] eqn:EN.
    + unfold qn. simpl. unfold Qdiv, Qinv. simpl. lra.
    + apply Qle_shift_div_l; [apply qn_pos; lia|].
      specialize (P k ltac:(lia)). lra.
  - intros k Hk.
    pose proof (position_gap x0 u0 r t k Ht HK L Hk) as G. cbv zeta in G.
    fold x cs in G. unfold translated_positions in Y. fold (spread (center t) cs) in Y.
    fold Y in G.
    assert (Hm : nth (k - 1) Y 0 <= nth k Y 0).
    { pose proof (M (k - 1)%nat) as Mk. replace (S (k - 1)) with k in Mk by lia.
      apply Mk. lia. }
    destruct (Qle_lt_or_eq _ _ Hm) as [Hlt|Heq].
    + pose proof (C (k - 1)%nat) as Ck. replace (S (k - 1)) with k in Ck by lia.
      specialize (Ck ltac:(lia) Hlt). rewrite HD, Ck. unfold Qdiv. ring.
    + rewrite G, Heq. ring.
Qed.
