(** * [H_{x(t)} ⊥ x⁰ + t u⁰ − x(t)] ([lem:incl-HSN], second inclusion).

    Paper, [lem:incl-HSN]: "for all t ≥ 0, we have the inclusion
    H^N_{x(t)} ⊂ T_{x(t)}K^N ∩ [x⁰ + t u⁰ − x(t)]^⊥". The orthogonality is
    proved here for every [N] (the printed step of its proof, without
    [− x(t)], is refuted in [Errata.v]). *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers Neighbours Contacts VelocityProjection.
Import ListNotations.
Open Scope Q_scope.

(** Translated coordinates: [x⁰ + t u⁰ − x(t) = x̃⁰ + t u⁰ − x̃(t)], entry by
    entry ([z − y] below). *)
Lemma vsub_untranslate (r : Q) (a : list Q) :
  forall b k, length a = length b ->
  qeq_list (vsub (untranslate_from k r a) (untranslate_from k r b)) (vsub a b).
Proof.
  induction a as [|x a IH]; intros [|y b] k L; simpl in L; try discriminate; constructor.
  - ring.
  - apply IH. lia.
Qed.

Lemma free_flight_untranslate (r t : Q) (x0 : list Q) :
  forall u0 k, length u0 = length x0 ->
  qeq_list (free_flight x0 u0 t)
           (untranslate_from k r (map (free_position t) (combine (translate_from k r x0) u0))).
Proof.
  induction x0 as [|a x0 IH]; intros [|b u0] k L; simpl in L; try discriminate; constructor.
  - unfold free_position. simpl. ring.
  - apply IH. lia.
Qed.

Lemma qeq_list_vsub (a a' b b' : list Q) :
  qeq_list a a' -> qeq_list b b' -> qeq_list (vsub a b) (vsub a' b').
Proof.
  intro Ha. revert b b'. induction Ha as [|x x' a a' Hx _ IH]; intros b b' Hb.
  - constructor.
  - destruct Hb as [|y y' b b' Hy Hb]; simpl; constructor.
    + rewrite Hx, Hy. reflexivity.
    + apply IH. exact Hb.
Qed.

Lemma dot_qeq (a a' w : list Q) : qeq_list a a' -> dot a w == dot a' w.
Proof.
  intro Ha. revert w. induction Ha as [|x x' a a' Hx _ IH]; intros [|y w]; simpl; try reflexivity.
  rewrite Hx, IH. reflexivity.
Qed.

(** Ledger claim [lem:incl-HSN] (the second inclusion, with [− x(t)]; also
    the corrected [eq:w-Hs-perp] and [lem:incl-HSN#proof-second-inclusion]):
    for every [N], [x⁰ ∈ K^N], any [u⁰], rational [t ≥ 0] and
    [w ∈ H_{x(t)}]: [⟨x⁰ + t u⁰ − x(t), w⟩ = 0]. *)
Theorem incl_HSN (x0 u0 : list Q) (r t : Q) (w : list Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> length w = length x0 ->
  InH r (positions (dynamics x0 u0 r t)) w ->
  dot (vsub (free_flight x0 u0 t) (positions (dynamics x0 u0 r t))) w == 0.
Proof.
  intros Ht HK L Lw HH.
  set (z := map (free_position t) (particles x0 u0 r)).
  set (y := translated_positions t (clusters x0 u0 r t)).
  pose proof (dynamics_is_projection x0 u0 r t Ht HK) as Hk. fold z y in Hk.
  destruct Hk as (Ly & M & P & T & C).
  assert (Lz : length z = length x0).
  { unfold z, particles. rewrite map_length, combine_length. unfold translate.
    rewrite translate_from_length. lia. }
  assert (E : qeq_list (vsub (free_flight x0 u0 t) (positions (dynamics x0 u0 r t))) (vsub z y)).
  { apply (qeq_list_trans _ (vsub (untranslate r z) (untranslate r y))).
    - apply qeq_list_vsub; [apply free_flight_untranslate; exact L|apply qeq_list_refl].
    - apply vsub_untranslate. congruence. }
  rewrite (dot_qeq _ _ w E).
  setoid_replace (dot (vsub z y) w) with (0 * 0 + dot (vsub z y) w) by ring.
  apply dot_by_parts.
  - rewrite vsub_length; lia.
  - intros k Hk. rewrite vsub_length in Hk by lia. rewrite psum_vsub by lia.
    destruct k as [|k]; [left; unfold psum; simpl; lra|].
    destruct (Qlt_le_dec (nth k y 0) (nth (S k) y 0)) as [Hlt|Hge].
    + left. rewrite (C k ltac:(lia) Hlt). ring.
    + right. simpl nth at 1.
      assert (Hy : nth k y 0 == nth (S k) y 0) by (pose proof (M k ltac:(lia)); lra).
      apply HH.
      * assert (Lx : length (positions (dynamics x0 u0 r t)) = length x0).
        { change (length (untranslate r y) = length x0).
          unfold untranslate. rewrite untranslate_from_length. congruence. }
        lia.
      * unfold Contact.
        pose proof (position_gap x0 u0 r t (S k) Ht HK L ltac:(lia)) as G. cbv zeta in G.
        replace (S k - 1)%nat with k in G by lia.
        unfold translated_positions in y. fold (spread (center t) (clusters x0 u0 r t)) in y.
        change (spread (center t) (clusters x0 u0 r t)) with y in G.
        rewrite G, Hy. ring.
  - rewrite <- psum_all, vsub_length, psum_vsub by lia. rewrite Lz, <- Lz, T. ring.
Qed.
