(** * The lexicographic PAVA gives the right derivative of the projection.

    [src/projection.rs] reports as velocity at [t] the block means of [u⁰]
    over the blocks of the PAVA run on the pairs [(y_i, u_i)] in
    lexicographic order, [y = x̃⁰ + t u⁰]: "PAVA in the ordered field
    [R(ε)] at the time [t + ε]". This file proves that this is the right
    derivative: with [Y] the [y]-part and [V] the [u]-part of that PAVA,
    there is [δ > 0] with [P_{K̃}(y + h u) = Y + h V] for every
    [0 < h ≤ δ] (theorem [pava_right_derivative]), hence
    [lim_{h↓0} (P(y + h u) − P(y))/h = V].

    Proof: the blocks keep the prefix property in the lexicographic order
    (pairs compared first by [y], then by [u]); a pair [(a, b)] that is
    lexicographically [≥ 0] has [a + h b ≥ 0] for all small [h > 0]; the
    blocks evaluated at [y + h u] therefore meet the invariant of [Pava.v]
    for all small [h], and [chain_kkt] gives the KKT conditions. *)

From Coq Require Import QArith Qring Lqa Lia List Morphisms.
From Sticky Require Import Prelude Kkt Pava Projection Oracle.
Import ListNotations.
Open Scope Q_scope.

(** ** The lexicographic order on pairs of rationals *)

(** [(a, b) ≥ 0] lexicographically. *)
Definition lexnn (a b : Q) : Prop := 0 < a \/ (a == 0 /\ 0 <= b).

Lemma lexnn_proper (a b a' b' : Q) : a == a' -> b == b' -> lexnn a b -> lexnn a' b'.
Proof. intros E F [H|[H1 H2]]; [left|right]; lra. Qed.

#[export] Instance lexnn_Proper : Proper (Qeq ==> Qeq ==> iff) lexnn.
Proof.
  intros a a' E b b' F. split; apply lexnn_proper; try assumption; symmetry; assumption.
Qed.

Lemma lexnn_add (a b c d : Q) : lexnn a b -> lexnn c d -> lexnn (a + c) (b + d).
Proof. intros [H|[H1 H2]] [G|[G1 G2]]; try (left; lra). right; lra. Qed.

Lemma lexnn_scale (k a b : Q) : 0 <= k -> lexnn a b -> lexnn (k * a) (k * b).
Proof.
  intros Hk H. destruct (Qle_lt_or_eq _ _ Hk) as [Kp|K0].
  - destruct H as [H|[H1 H2]].
    + left. apply Qmult_lt_0_compat; assumption.
    + right. split; [rewrite H1; ring|apply Qmult_le_0_compat; lra].
  - right. rewrite <- K0. split; [ring|lra].
Qed.

Lemma lexnn_reg (k a b : Q) : 0 < k -> lexnn (k * a) (k * b) -> lexnn a b.
Proof.
  intros Hk [H|[H1 H2]].
  - left. apply Qnot_le_lt. intro Ha.
    assert (k * a <= 0); [|lra].
    setoid_replace (k * a) with (- (k * (- a))) by ring.
    assert (0 <= k * (- a)) by (apply Qmult_le_0_compat; lra). lra.
  - right. split.
    + assert (Hk' : ~ k == 0) by (intro E; rewrite E in Hk; discriminate).
      destruct (Qmult_integral _ _ H1) as [E|E]; [contradiction|exact E].
    + apply (Qmult_pos_le_reg k); assumption.
Qed.

(** A lexicographically non-negative pair stays non-negative along
    [a + h b] for all small [h > 0]. *)
Definition Eventually (P : Q -> Prop) : Prop :=
  exists d, 0 < d /\ forall h, 0 < h -> h <= d -> P h.

Lemma eventually_and (P R : Q -> Prop) :
  Eventually P -> Eventually R -> Eventually (fun h => P h /\ R h).
Proof.
  intros (d1 & D1 & H1) (d2 & D2 & H2).
  destruct (Qlt_le_dec d1 d2) as [L|L].
  - exists d1. split; [exact D1|]. intros h Hh Hd. split; [apply H1|apply H2]; lra.
  - exists d2. split; [exact D2|]. intros h Hh Hd. split; [apply H1|apply H2]; lra.
Qed.

Lemma eventually_impl (P R : Q -> Prop) :
  (forall h, P h -> R h) -> Eventually P -> Eventually R.
Proof. intros I (d & D & H). exists d. split; [exact D|]. intros h Hh Hd. auto. Qed.

Lemma eventually_lexnn (a b : Q) : lexnn a b -> Eventually (fun h => 0 <= a + h * b).
Proof.
  intros [H|[H1 H2]].
  - destruct (Qlt_le_dec b 0) as [Hb|Hb].
    + exists (a / (- b)). split.
      * apply Qlt_shift_div_l; lra.
      * intros h Hh Hd.
        assert (h * (- b) <= a).
        { apply (Qmult_le_compat_r _ _ (- b)) in Hd; [|lra].
          setoid_replace (a / - b * - b) with a in Hd; [exact Hd|].
          field. intro E. lra. }
        lra.
    + exists 1. split; [reflexivity|]. intros h Hh _.
      assert (0 <= h * b) by (apply Qmult_le_0_compat; lra). lra.
  - exists 1. split; [reflexivity|]. intros h Hh _.
    assert (0 <= h * b) by (apply Qmult_le_0_compat; lra). lra.
Qed.

Lemma eventually_true : Eventually (fun _ => True).
Proof. exists 1. split; [reflexivity|auto]. Qed.

Lemma eventually_upto (n : nat) (P : nat -> Q -> Prop) :
  (forall k, (k <= n)%nat -> Eventually (P k)) ->
  Eventually (fun h => forall k, (k <= n)%nat -> P k h).
Proof.
  induction n as [|n IH]; intro H.
  - apply (eventually_impl (P 0%nat)); [|apply H; lia].
    intros h Hp k Hk. replace k with 0%nat by lia. exact Hp.
  - apply (eventually_impl (fun h => (forall k, (k <= n)%nat -> P k h) /\ P (S n) h)).
    + intros h [H1 H2] k Hk. destruct (Nat.eq_dec k (S n)) as [->|Ne]; [exact H2|].
      apply H1. lia.
    + apply eventually_and; [apply IH; intros k Hk; apply H; lia|apply H; lia].
Qed.

(** ** The PAVA invariant in the lexicographic order *)

(** Every prefix of the segment has a lexicographically larger mean pair. *)
Definition Pooled2 (seg : list (Q * Q)) : Prop :=
  forall k, (k <= length seg)%nat ->
    lexnn (qn (length seg) * psum k (map fst seg) - qn k * qsum (map fst seg))
          (qn (length seg) * psum k (map snd seg) - qn k * qsum (map snd seg)).

(** Block [b] stands for the non-empty segment of pairs [seg]. *)
Definition Rep2 (seg : list (Q * Q)) (b : block) : Prop :=
  seg <> [] /\ bsum b == qsum (map fst seg) /\ bsum_u b == qsum (map snd seg) /\
  Z.of_nat (length seg) = Z.pos (bsize b) /\ Pooled2 seg.

(** The mean pair of [a] is lexicographically at most that of [b]. *)
Definition LexLe (a b : block) : Prop :=
  lexnn (bsum b * psize a - bsum a * psize b) (bsum_u b * psize a - bsum_u a * psize b).

Notation Chain2 := (ChainBy LexLe).

Lemma pools_true2 (a b : block) : pools a b = true -> LexLe b a.
Proof.
  unfold pools, LexLe. destruct (Qcompare _ _) eqn:E; intro H.
  - apply Qeq_alt in E. apply Qle_bool_iff in H. right. split; lra.
  - discriminate.
  - apply Qgt_alt in E. left. lra.
Qed.

Lemma pools_false2 (a b : block) : pools a b = false -> LexLe a b.
Proof.
  unfold pools, LexLe. destruct (Qcompare _ _) eqn:E; intro H.
  - apply Qeq_alt in E. right. split; [lra|].
    destruct (Qlt_le_dec (bsum_u a * psize b) (bsum_u b * psize a)) as [L|L]; [lra|].
    apply Qle_bool_iff in L. rewrite L in H. discriminate.
  - apply Qlt_alt in E. left. lra.
  - discriminate.
Qed.

Lemma merge_left2 (nA nB k sA sB P sA' sB' P' : Q) :
  0 < nA -> 0 <= nB -> 0 <= k ->
  lexnn (nA * P - k * sA) (nA * P' - k * sA') ->
  lexnn (nB * sA - nA * sB) (nB * sA' - nA * sB') ->
  lexnn ((nA + nB) * P - k * (sA + sB)) ((nA + nB) * P' - k * (sA' + sB')).
Proof.
  intros HA HB Hk H1 H2. apply (lexnn_reg nA); [exact HA|].
  apply (lexnn_proper ((nA + nB) * (nA * P - k * sA) + k * (nB * sA - nA * sB))
                      ((nA + nB) * (nA * P' - k * sA') + k * (nB * sA' - nA * sB')));
    [ring|ring|].
  apply lexnn_add; apply lexnn_scale; try assumption; lra.
Qed.

Lemma merge_right2 (nA nB j sA sB P sA' sB' P' : Q) :
  0 <= nA -> 0 < nB -> 0 <= nB - j ->
  lexnn (nB * P - j * sB) (nB * P' - j * sB') ->
  lexnn (nB * sA - nA * sB) (nB * sA' - nA * sB') ->
  lexnn ((nA + nB) * (sA + P) - (nA + j) * (sA + sB))
        ((nA + nB) * (sA' + P') - (nA + j) * (sA' + sB')).
Proof.
  intros HA HB Hj H1 H2. apply (lexnn_reg nB); [exact HB|].
  apply (lexnn_proper ((nA + nB) * (nB * P - j * sB) + (nB - j) * (nB * sA - nA * sB))
                      ((nA + nB) * (nB * P' - j * sB') + (nB - j) * (nB * sA' - nA * sB')));
    [ring|ring|].
  apply lexnn_add; apply lexnn_scale; try assumption; lra.
Qed.

Lemma rep2_single (e : Q * Q) : Rep2 [e] (single e).
Proof.
  split; [discriminate|split; [simpl; ring|split; [simpl; ring|split; [reflexivity|]]]].
  intros k Hk. simpl in Hk. right.
  destruct k as [|[|k]]; [| |lia]; unfold qn, psum, inject_Z; simpl; split; lra.
Qed.

Lemma rep2_psize (seg : list (Q * Q)) (b : block) : Rep2 seg b -> psize b == qn (length seg).
Proof. intros (_ & _ & _ & Hl & _). unfold psize, qn. rewrite Hl. reflexivity. Qed.

Lemma rep2_merge (sa sb : list (Q * Q)) (a b : block) :
  Rep2 sa a -> Rep2 sb b -> pools a b = true -> Rep2 (sa ++ sb) (merge a b).
Proof.
  intros Ha Hb Hp.
  pose proof (rep2_psize _ _ Ha) as Pa. pose proof (rep2_psize _ _ Hb) as Pb.
  destruct Ha as (Na & Sa & Ua & La & Qa). destruct Hb as (Nb & Sb & Ub & Lb & Qb).
  apply pools_true2 in Hp. unfold LexLe in Hp.
  assert (HnA : 0 < qn (length sa)).
  { apply qn_pos. destruct sa; [contradiction|simpl; lia]. }
  assert (HnB : 0 < qn (length sb)).
  { apply qn_pos. destruct sb; [contradiction|simpl; lia]. }
  assert (Hp' : lexnn (qn (length sb) * qsum (map fst sa) - qn (length sa) * qsum (map fst sb))
                      (qn (length sb) * qsum (map snd sa) - qn (length sa) * qsum (map snd sb))).
  { revert Hp. apply lexnn_proper; rewrite ?Pa, ?Pb, ?Sa, ?Sb, ?Ua, ?Ub; ring. }
  split; [destruct sa; [contradiction|discriminate]|].
  split; [unfold merge; cbn [bsum]; rewrite Qred_correct, map_app, qsum_app, Sa, Sb; reflexivity|].
  split; [unfold merge; cbn [bsum_u]; rewrite Qred_correct, map_app, qsum_app, Ua, Ub; reflexivity|].
  split; [simpl; rewrite app_length, Nat2Z.inj_add, La, Lb; reflexivity|].
  intros k Hk. rewrite app_length in Hk. rewrite !map_app, !qsum_app, app_length, qn_add.
  destruct (Nat.le_gt_cases k (length sa)) as [Hle|Hgt].
  - rewrite !psum_app_le by (rewrite map_length; exact Hle).
    specialize (Qa k Hle).
    apply merge_left2; [exact HnA|lra|apply qn_nonneg|exact Qa|exact Hp'].
  - rewrite !psum_app_ge by (rewrite map_length; lia). rewrite !map_length.
    set (j := (k - length sa)%nat).
    assert (Hk' : k = (length sa + j)%nat) by (unfold j; lia).
    assert (Hj : (j <= length sb)%nat) by (unfold j; lia).
    rewrite Hk', qn_add.
    specialize (Qb j Hj). pose proof (qn_le _ _ Hj).
    apply merge_right2; [lra|exact HnB|lra|exact Qb|exact Hp'].
Qed.

Lemma pava_blocks_inv2 (es : list (Q * Q)) :
  exists segs, Forall2 Rep2 segs (pava_blocks es) /\ Chain2 (pava_blocks es) /\
    concat segs = es.
Proof.
  destruct (pava_blocks_invariant Rep2 LexLe rep2_merge pools_false2 (fun e => e) rep2_single es)
    as (segs & H1 & H2 & H3).
  exists segs. rewrite map_id in H3. auto.
Qed.

(** ** The blocks evaluated at [y + h u] *)

(** The entries [y_i + h u_i] of a list of pairs. *)
Definition at_h (h : Q) (es : list (Q * Q)) : list Q := map (fun e => fst e + h * snd e) es.

(** A block of pairs read at [y + h u]: its sum is [Σy + h Σu]. *)
Definition block_at (h : Q) (b : block) : block :=
  mkblock (bsum b + h * bsum_u b) 0 (bsize b).

Lemma psum_at_h (h : Q) (seg : list (Q * Q)) : forall k,
  psum k (at_h h seg) == psum k (map fst seg) + h * psum k (map snd seg).
Proof.
  induction seg as [|e seg IH]; intros [|k]; unfold at_h in *; cbn [map];
    try (unfold psum; simpl; ring).
  rewrite !psum_cons, IH. ring.
Qed.

Lemma qsum_at_h (h : Q) (seg : list (Q * Q)) :
  qsum (at_h h seg) == qsum (map fst seg) + h * qsum (map snd seg).
Proof.
  induction seg as [|e seg IH]; unfold at_h in *; cbn [map qsum]; [ring|].
  rewrite IH. ring.
Qed.

Lemma rep_at (seg : list (Q * Q)) (b : block) :
  Rep2 seg b -> Eventually (fun h => Rep (at_h h seg) (block_at h b)).
Proof.
  intros (Hn & Hs & Hu & Hl & Hp).
  assert (E : Eventually (fun h => forall k, (k <= length seg)%nat ->
     0 <= (qn (length seg) * psum k (map fst seg) - qn k * qsum (map fst seg))
          + h * (qn (length seg) * psum k (map snd seg) - qn k * qsum (map snd seg)))).
  { apply (eventually_upto (length seg)
             (fun k h => 0 <= (qn (length seg) * psum k (map fst seg) - qn k * qsum (map fst seg))
                + h * (qn (length seg) * psum k (map snd seg) - qn k * qsum (map snd seg)))).
    intros k Hk. apply eventually_lexnn, Hp, Hk. }
  revert E. apply eventually_impl. intros h E.
  split; [destruct seg; [contradiction|discriminate]|].
  split; [cbn [block_at bsum]; rewrite qsum_at_h, Hs, Hu; reflexivity|].
  split; [unfold at_h; rewrite map_length; exact Hl|].
  intros k Hk. unfold at_h in Hk. rewrite map_length in Hk.
  specialize (E k Hk). unfold at_h. rewrite map_length.
  fold (at_h h seg). rewrite psum_at_h, qsum_at_h.
  setoid_replace (qn k * (qsum (map fst seg) + h * qsum (map snd seg)))
    with (qn k * qsum (map fst seg) + h * (qn k * qsum (map snd seg))) by ring.
  setoid_replace (qn (length seg) * (psum k (map fst seg) + h * psum k (map snd seg)))
    with (qn (length seg) * psum k (map fst seg) + h * (qn (length seg) * psum k (map snd seg)))
    by ring.
  lra.
Qed.

Lemma reps_at (segs : list (list (Q * Q))) (bs : list block) :
  Forall2 Rep2 segs bs ->
  Eventually (fun h => Forall2 Rep (map (at_h h) segs) (map (block_at h) bs)).
Proof.
  induction 1 as [|seg b segs bs Hr Hf IH].
  - apply (eventually_impl (fun _ => True)); [intros; constructor|apply eventually_true].
  - apply (eventually_impl (fun h => Rep (at_h h seg) (block_at h b) /\
                                   Forall2 Rep (map (at_h h) segs) (map (block_at h) bs))).
    + intros h [H1 H2]. simpl. constructor; assumption.
    + apply eventually_and; [apply rep_at, Hr|exact IH].
Qed.

Lemma chain_at (bs : list block) :
  Chain2 bs -> Eventually (fun h => Chain (map (block_at h) bs)).
Proof.
  induction bs as [|b1 bs IH]; intro Hc.
  - apply (eventually_impl (fun _ => True)); [intros; exact I|apply eventually_true].
  - destruct bs as [|b2 bs].
    + apply (eventually_impl (fun _ => True)); [intros; exact I|apply eventually_true].
    + destruct Hc as [H12 Hc].
      apply (eventually_impl
               (fun h => 0 <= (bsum b2 * psize b1 - bsum b1 * psize b2)
                              + h * (bsum_u b2 * psize b1 - bsum_u b1 * psize b2) /\
                         Chain (map (block_at h) (b2 :: bs)))).
      * intros h [H1 H2]. cbn [map ChainBy]. split; [|exact H2]. unfold MeanLe.
        unfold psize in *. cbn [block_at bsum bsize]. fold (psize b1). fold (psize b2).
        fold (psize b1) in H1. fold (psize b2) in H1.
        setoid_replace ((bsum b1 + h * bsum_u b1) * psize b2)
          with (bsum b1 * psize b2 + h * (bsum_u b1 * psize b2)) by ring.
        setoid_replace ((bsum b2 + h * bsum_u b2) * psize b1)
          with (bsum b2 * psize b1 + h * (bsum_u b2 * psize b1)) by ring.
        lra.
      * apply eventually_and; [apply eventually_lexnn, H12|apply IH, Hc].
Qed.

(** ** The theorem *)

Lemma blocks_at_kkt_rec (es : list (Q * Q)) :
  Eventually (fun h => kkt_rec (at_h h es) (flat_map expand (map (block_at h) (pava_blocks es)))).
Proof.
  destruct (pava_blocks_inv2 es) as (segs & Hf & Hc & Hz).
  apply (eventually_impl (fun h => Forall2 Rep (map (at_h h) segs)
                                     (map (block_at h) (pava_blocks es)) /\
                                   Chain (map (block_at h) (pava_blocks es)))).
  2: { apply eventually_and; [apply reps_at, Hf|apply chain_at, Hc]. }
  intros h [Hr Hch].
  assert (Ez : at_h h es = concat (map (at_h h) segs)).
  { rewrite <- Hz. unfold at_h. rewrite concat_map. reflexivity. }
  rewrite Ez.
  destruct (map (block_at h) (pava_blocks es)) as [|b bs] eqn:E.
  - inversion Hr. reflexivity.
  - destruct (Pos2Nat.is_succ (bsize b)) as [n Hn].
    assert (Hy : flat_map expand (b :: bs) = mean b :: (repeat (mean b) n ++ flat_map expand bs)).
    { simpl. unfold expand at 1. rewrite Hn. reflexivity. }
    rewrite Hy. unfold kkt_rec. rewrite <- Hy.
    apply chain_kkt; [exact Hr|exact Hch|].
    intros b' Hb'. simpl in Hb'. injection Hb' as <-. apply Qle_refl.
Qed.

(** [Y + h V], entrywise. *)
Fixpoint affine (h : Q) (Y V : list Q) : list Q :=
  match Y, V with
  | a :: Y', b :: V' => (a + h * b) :: affine h Y' V'
  | _, _ => []
  end.

(** The [u]-part of the lexicographic PAVA: the block means of [u]. *)
Definition pava_lex_u (y u : list Q) : list Q :=
  flat_map expand_u (pava_blocks (combine y u)).

Lemma affine_app (h : Q) (Y1 V1 Y2 V2 : list Q) :
  length Y1 = length V1 -> affine h (Y1 ++ Y2) (V1 ++ V2) = affine h Y1 V1 ++ affine h Y2 V2.
Proof.
  revert V1. induction Y1 as [|a Y1 IH]; intros [|b V1] L; simpl in *; try discriminate.
  - reflexivity.
  - f_equal. apply IH. lia.
Qed.

Lemma affine_repeat (h m v : Q) (n : nat) :
  affine h (repeat m n) (repeat v n) = repeat (m + h * v) n.
Proof. induction n as [|n IH]; simpl; [reflexivity|f_equal; exact IH]. Qed.

Lemma mean_block_at (h : Q) (b : block) : mean (block_at h b) == mean b + h * mean_u b.
Proof.
  unfold mean, mean_u, block_at. cbn [bsum bsum_u].
  unfold psize. cbn [bsize]. field.
  intro E. pose proof (psize_pos b) as P. unfold psize in P. rewrite E in P. discriminate.
Qed.

Lemma expand_at (h : Q) (bs : list block) :
  qeq_list (flat_map expand (map (block_at h) bs))
           (affine h (flat_map expand bs) (flat_map expand_u bs)).
Proof.
  induction bs as [|b bs IH]; simpl; [constructor|].
  rewrite affine_app by (unfold expand, expand_u; rewrite !repeat_length; reflexivity).
  apply Forall2_app; [|exact IH].
  unfold expand, expand_u. rewrite affine_repeat. cbn [block_at bsize].
  apply qeq_list_repeat. apply mean_block_at.
Qed.

(** The KKT conditions only see the values of the candidate, too. *)
Lemma kkt_qeq_r (z y y' : list Q) : qeq_list y y' -> Kkt z y -> Kkt z y'.
Proof.
  intros E (L & M & P & T & C). pose proof (qeq_list_length _ _ E) as Ly.
  pose proof (qeq_list_nth _ _ E) as N. pose proof (qeq_list_psum _ _ E) as S.
  split; [congruence|split; [|split; [|split]]].
  - intros i Hi. rewrite <- !N. apply M. lia.
  - intros k Hk. rewrite <- S. apply P, Hk.
  - rewrite <- S. exact T.
  - intros k Hk Hl. rewrite <- !N in Hl. rewrite <- S. apply C; assumption.
Qed.

Lemma at_h_combine (h : Q) (y u : list Q) :
  length u = length y -> at_h h (combine y u) = affine h y u.
Proof.
  revert u. induction y as [|a y IH]; intros [|b u] L; simpl in *; try discriminate.
  - reflexivity.
  - f_equal. apply IH. lia.
Qed.

(** The lexicographic PAVA's [y]-part is the projection of [y]. *)
Corollary pava_lex_is_pava (y u : list Q) :
  length u = length y -> qeq_list (pava_lex y u) (pava y).
Proof. intro L. apply (kkt_unique y); [apply pava_lex_kkt, L|apply pava_kkt]. Qed.

(** Main theorem ([prop:proj-micro], [eq:proj-u-micro]: the velocity is the
    right derivative of [x(t) = P_K(x⁰ + t u⁰)]; ledger: [prop:proj-micro];
    the block means are [eq:proj-u-micro]'s cluster means in the ledger's
    corrected reading — read literally, with [J_k] runs of contact indices,
    the ledger records a counterexample): for every [N] and [y, u ∈ Q^N] there is [δ > 0] such
    that for every [0 < h ≤ δ], [P_{K̃}(y + h u) = Y + h V] entrywise, with
    [Y = pava_lex y u] ([= P_{K̃}(y)]) and [V = pava_lex_u y u] the block
    means of [u]. With [y = x̃⁰ + t u⁰], [u = u⁰]: [x̃(t + h) = x̃(t) + h V],
    so [V] is the right derivative [u(t)]. *)
Theorem pava_right_derivative (y u : list Q) :
  length u = length y ->
  Eventually (fun h => qeq_list (pava (affine h y u)) (affine h (pava_lex y u) (pava_lex_u y u))).
Proof.
  intro L. apply (eventually_impl (fun h => kkt_rec (at_h h (combine y u))
      (flat_map expand (map (block_at h) (pava_blocks (combine y u)))))).
  2: apply blocks_at_kkt_rec.
  intros h H. apply kkt_rec_iff in H.
  rewrite (at_h_combine h y u L) in H.
  apply (kkt_qeq_r _ _ _ (expand_at h _)) in H.
  apply (kkt_unique (affine h y u)); [apply pava_kkt|exact H].
Qed.

(** ** The oracle's velocities are the right derivative of its positions *)

Lemma pava_qeq (a b : list Q) : qeq_list a b -> qeq_list (pava a) (pava b).
Proof.
  intro E. apply (kkt_unique b); [|apply pava_kkt].
  apply (kkt_qeq a); [exact E|apply pava_kkt].
Qed.

Lemma affine_qeq (h : Q) (Y Y' V V' : list Q) :
  qeq_list Y Y' -> qeq_list V V' -> qeq_list (affine h Y V) (affine h Y' V').
Proof.
  intro E. revert V V'. induction E as [|a a' Y Y' Ea E IH]; intros V V' F;
    inversion F as [|b b' V1 V1' Eb F']; subst; simpl; constructor.
  - rewrite Ea, Eb. reflexivity.
  - apply IH. exact F'.
Qed.

Lemma translate_free_flight_h (x : list Q) : forall u k r t h,
  qeq_list (translate_from k r (free_flight (t + h) x u))
           (affine h (translate_from k r (free_flight t x u)) u).
Proof.
  induction x as [|a x IH]; intros [|b u] k r t h; simpl; constructor.
  - ring.
  - apply IH.
Qed.

Lemma untranslate_affine (Y : list Q) : forall V k r h,
  qeq_list (untranslate_from k r (affine h Y V)) (affine h (untranslate_from k r Y) V).
Proof.
  induction Y as [|a Y IH]; intros [|b V] k r h; simpl; constructor.
  - ring.
  - apply IH.
Qed.

Lemma map_qred (l : list Q) : qeq_list (map Qred l) l.
Proof. induction l; simpl; constructor; [apply Qred_correct|assumption]. Qed.

(** Main theorem for the oracle ([prop:proj-micro], [eq:proj-u-micro];
    ledger: [prop:proj-micro]): the velocities it prints
    are the right derivative of [x(t) = P_K(x⁰ + t u⁰)]: for every [N],
    radius, rational [t] and data [x⁰, u⁰ ∈ Q^N] there is [δ > 0] such that
    for every [0 < h ≤ δ], [P_K(x⁰ + (t + h) u⁰) = x(t) + h u(t)] entrywise,
    [x(t)], [u(t)] the oracle's positions and velocities. *)
Theorem state_velocities_spec (r t : Q) (x0 u0 : list Q) :
  length u0 = length x0 ->
  Eventually (fun h =>
    qeq_list (proj_K r (free_flight (t + h) x0 u0))
             (affine h (st_positions (state_at r t x0 u0))
                       (st_velocities (state_at r t x0 u0)))).
Proof.
  intro L.
  set (y := shifted_free 0 (2 * r) t x0 u0).
  assert (Ey : qeq_list y (translate r (free_flight t x0 u0))).
  { unfold y, translate. apply shifted_free_spec. unfold qn. simpl. ring. }
  assert (Ly : length u0 = length y).
  { unfold y. rewrite shifted_free_length; exact L. }
  apply (eventually_impl (fun h => qeq_list (pava (affine h y u0))
                                      (affine h (pava_lex y u0) (pava_lex_u y u0)))).
  2: apply pava_right_derivative, Ly.
  intros h H. unfold state_at. cbn [st_positions st_velocities]. fold y.
  unfold proj_K, untranslate.
  eapply qeq_list_trans.
  { apply untranslate_from_qeq. apply pava_qeq.
    eapply qeq_list_trans; [apply translate_free_flight_h|].
    apply affine_qeq; [apply qeq_list_sym, Ey|apply qeq_list_refl]. }
  eapply qeq_list_trans; [apply untranslate_from_qeq, H|].
  eapply qeq_list_trans; [apply untranslate_affine|].
  apply affine_qeq.
  - apply qeq_list_sym. apply (unshift_spec _ 0%nat). unfold qn. simpl. ring.
  - apply qeq_list_sym, map_qred.
Qed.
