(** * Pool-adjacent-violators over [Q], and its correctness.

    PAVA computes the projection onto the cone of non-decreasing vectors
    [K̃^N] ([df:tKN]): a stack of blocks (sum, size), each new entry pooled
    with the block below while the mean below is larger. The pooling
    decision is lexicographic on [(y, u)], exactly as in the Rust crate
    ([src/projection.rs], [pools]): it is the order at time [t + ε] that
    makes the reported velocity the right derivative. Ties of [y] are
    decided by [u]; the [y]-part of the result is the projection of [y]
    whatever [u] is (theorem [pava_lex_kkt]), and [pava] is the plain
    projection ([u = 0]). *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt.
Import ListNotations.
Open Scope Q_scope.

(** ** The algorithm *)

(** A pooled block: the sums of the two keys over its entries and its size. *)
Record block := mkblock { bsum : Q; bsum_u : Q; bsize : positive }.

(** The size of a block as a rational. *)
Definition psize (b : block) : Q := Z.pos (bsize b) # 1.

(** The mean of the primary key over a block: the projection's value there. *)
Definition mean (b : block) : Q := bsum b / psize b.

(** The mean of the secondary key (the initial velocities) over a block. *)
Definition mean_u (b : block) : Q := bsum_u b / psize b.

(** The block of one entry. *)
Definition single (e : Q * Q) : block := mkblock (fst e) (snd e) 1.

(** Two adjacent blocks pooled into one. The sums are kept in lowest terms
    ([Qred], equal to the sum by [Qred_correct]) so that the extracted code's
    numbers stay as small as the data's. *)
Definition merge (a b : block) : block :=
  mkblock (Qred (bsum a + bsum b)) (Qred (bsum_u a + bsum_u b)) (bsize a + bsize b).

(** The left block [a] pools with the right block [b] iff its mean is [≥]
    in the lexicographic order on (mean, mean_u); means cross-multiplied. *)
Definition pools (a b : block) : bool :=
  match Qcompare (bsum a * psize b) (bsum b * psize a) with
  | Gt => true
  | Lt => false
  | Eq => Qle_bool (bsum_u b * psize a) (bsum_u a * psize b)
  end.

(** Push a block on the stack (top first), pooling while the top violates. *)
Fixpoint push (stack : list block) (cur : block) : list block :=
  match stack with
  | [] => [cur]
  | top :: rest => if pools top cur then push rest (merge top cur)
                   else cur :: top :: rest
  end.

(** Run PAVA on the remaining entries, from a stack. *)
Fixpoint pava_stack (stack : list block) (es : list (Q * Q)) : list block :=
  match es with
  | [] => stack
  | e :: es' => pava_stack (push stack (single e)) es'
  end.

(** The blocks of PAVA on the pairs [(y_i, u_i)], left to right. *)
Definition pava_blocks (es : list (Q * Q)) : list block :=
  rev (pava_stack [] es).

(** A block spelled out: its mean repeated [size] times. *)
Definition expand (b : block) : list Q := repeat (mean b) (Pos.to_nat (bsize b)).

(** The same for the secondary key. *)
Definition expand_u (b : block) : list Q := repeat (mean_u b) (Pos.to_nat (bsize b)).

(** The projection of [y] computed by the lexicographic PAVA on [(y, u)]. *)
Definition pava_lex (y u : list Q) : list Q :=
  flat_map expand (pava_blocks (combine y u)).

(** The plain PAVA: the projection of [z] onto [K̃^N]. *)
Definition pava (z : list Q) : list Q :=
  flat_map expand (pava_blocks (map (fun a => (a, 0)) z)).

(** ** The invariant: blocks represent consecutive segments of the input *)

(** Every prefix of a pooled segment has mean at least the segment's mean
    ([k·Σseg ≤ |seg|·Σ_{j<k} seg_j]). *)
Definition Pooled (seg : list Q) : Prop :=
  forall k, (k <= length seg)%nat -> qn k * qsum seg <= qn (length seg) * psum k seg.

(** Block [b] stands for the non-empty segment [seg] of the input. *)
Definition Rep (seg : list Q) (b : block) : Prop :=
  seg <> [] /\ bsum b == qsum seg /\ Z.of_nat (length seg) = Z.pos (bsize b) /\
  Pooled seg.

(** Adjacent blocks of a stack (top first) are in the order [le]:
    [le below top]. *)
Fixpoint OrderedBy (le : block -> block -> Prop) (stack : list block) : Prop :=
  match stack with
  | top :: ((below :: _) as rest) => le below top /\ OrderedBy le rest
  | _ => True
  end.

(** The same, left to right. *)
Fixpoint ChainBy (le : block -> block -> Prop) (bs : list block) : Prop :=
  match bs with
  | b1 :: ((b2 :: _) as rest) => le b1 b2 /\ ChainBy le rest
  | _ => True
  end.

(** PAVA's order on blocks: non-decreasing means, cross-multiplied. *)
Definition MeanLe (a b : block) : Prop := bsum a * psize b <= bsum b * psize a.

Notation Ordered := (OrderedBy MeanLe).
Notation Chain := (ChainBy MeanLe).

Lemma psize_pos (b : block) : 0 < psize b.
Proof. unfold psize, Qlt. simpl. lia. Qed.

Lemma rep_psize (seg : list Q) (b : block) : Rep seg b -> psize b == qn (length seg).
Proof.
  intros (_ & _ & Hl & _). unfold psize, qn. rewrite Hl. reflexivity.
Qed.

Lemma mean_mul (b : block) : mean b * psize b == bsum b.
Proof.
  unfold mean. field. pose proof (psize_pos b). intro H0. rewrite H0 in H. discriminate.
Qed.

Lemma pools_true (a b : block) :
  pools a b = true -> bsum b * psize a <= bsum a * psize b.
Proof.
  unfold pools. destruct (Qcompare _ _) eqn:E; intro H.
  - apply Qeq_alt in E. rewrite E. apply Qle_refl.
  - discriminate.
  - apply Qgt_alt in E. apply Qlt_le_weak. exact E.
Qed.

Lemma pools_false (a b : block) :
  pools a b = false -> bsum a * psize b <= bsum b * psize a.
Proof.
  unfold pools. destruct (Qcompare _ _) eqn:E; intro H.
  - apply Qeq_alt in E. rewrite E. apply Qle_refl.
  - apply Qlt_alt in E. apply Qlt_le_weak. exact E.
  - discriminate.
Qed.

(** The two inequalities of pooling, as plain algebra over [Q]. Left part:
    [nA·((nA+nB)P − k(sA+sB)) = (nA+nB)(nA P − k sA) + k(nB sA − nA sB)]. *)
Lemma merge_left (nA nB k sA sB P : Q) :
  0 < nA -> 0 <= nB -> 0 <= k -> 0 <= nA * P - k * sA -> 0 <= nB * sA - nA * sB ->
  0 <= (nA + nB) * P - k * (sA + sB).
Proof.
  intros HA HB Hk H1 H2. apply (Qmult_pos_le_reg nA); [exact HA|].
  setoid_replace (nA * ((nA + nB) * P - k * (sA + sB)))
    with ((nA + nB) * (nA * P - k * sA) + k * (nB * sA - nA * sB)) by ring.
  assert (0 <= (nA + nB) * (nA * P - k * sA)) by (apply Qmult_le_0_compat; lra).
  assert (0 <= k * (nB * sA - nA * sB)) by (apply Qmult_le_0_compat; lra).
  lra.
Qed.

(** Right part, [k = |a| + j]:
    [nB·((nA+nB)(sA+P) − (nA+j)(sA+sB)) = (nA+nB)(nB P − j sB) + (nB−j)(nB sA − nA sB)]. *)
Lemma merge_right (nA nB j sA sB P : Q) :
  0 <= nA -> 0 < nB -> 0 <= nB - j -> 0 <= nB * P - j * sB -> 0 <= nB * sA - nA * sB ->
  0 <= (nA + nB) * (sA + P) - (nA + j) * (sA + sB).
Proof.
  intros HA HB Hj H1 H2. apply (Qmult_pos_le_reg nB); [exact HB|].
  setoid_replace (nB * ((nA + nB) * (sA + P) - (nA + j) * (sA + sB)))
    with ((nA + nB) * (nB * P - j * sB) + (nB - j) * (nB * sA - nA * sB)) by ring.
  assert (0 <= (nA + nB) * (nB * P - j * sB)) by (apply Qmult_le_0_compat; lra).
  assert (0 <= (nB - j) * (nB * sA - nA * sB)) by (apply Qmult_le_0_compat; lra).
  lra.
Qed.

Lemma rep_single (e : Q * Q) : Rep [fst e] (single e).
Proof.
  repeat split.
  - discriminate.
  - simpl. ring.
  - intros k Hk. simpl in Hk. destruct k as [|[|k]]; [| |lia].
    + unfold qn, psum, inject_Z. simpl. lra.
    + unfold qn, psum, inject_Z. simpl. lra.
Qed.

(** Pooling two adjacent blocks keeps the invariant. *)
Lemma rep_merge (sa sb : list Q) (a b : block) :
  Rep sa a -> Rep sb b -> pools a b = true -> Rep (sa ++ sb) (merge a b).
Proof.
  intros Ha Hb Hp.
  pose proof (rep_psize _ _ Ha) as Pa. pose proof (rep_psize _ _ Hb) as Pb.
  destruct Ha as (Na & Sa & La & Qa). destruct Hb as (Nb & Sb & Lb & Qb).
  apply pools_true in Hp. rewrite Pa, Pb, Sa, Sb in Hp.
  assert (HnA : 0 < qn (length sa)).
  { apply qn_pos. destruct sa; [contradiction|simpl; lia]. }
  assert (HnB : 0 < qn (length sb)).
  { apply qn_pos. destruct sb; [contradiction|simpl; lia]. }
  repeat split.
  - destruct sa; [contradiction|discriminate].
  - unfold merge. cbn [bsum]. rewrite Qred_correct, qsum_app, Sa, Sb. reflexivity.
  - simpl. rewrite app_length, Nat2Z.inj_add, La, Lb. reflexivity.
  - intros k Hk. rewrite app_length in Hk. rewrite qsum_app, app_length, qn_add.
    destruct (Nat.le_gt_cases k (length sa)) as [Hle|Hgt].
    + rewrite psum_app_le by exact Hle.
      specialize (Qa k Hle).
      pose proof (merge_left (qn (length sa)) (qn (length sb)) (qn k)
                    (qsum sa) (qsum sb) (psum k sa)) as M.
      lapply M; [clear M; intro M|exact HnA].
      pose proof (qn_nonneg k). lra.
    + rewrite psum_app_ge by lia.
      set (j := (k - length sa)%nat).
      assert (Hk' : k = (length sa + j)%nat) by (unfold j; lia).
      assert (Hj : (j <= length sb)%nat) by (unfold j; lia).
      rewrite Hk', qn_add.
      specialize (Qb j Hj). pose proof (qn_le _ _ Hj).
      pose proof (merge_right (qn (length sa)) (qn (length sb)) (qn j)
                    (qsum sa) (qsum sb) (psum j sb)) as M.
      lapply M; [clear M; intro M|lra].
      pose proof (qn_nonneg j). lra.
Qed.

Lemma forall2_rev {A B} (R : A -> B -> Prop) (l1 : list A) (l2 : list B) :
  Forall2 R l1 l2 -> Forall2 R (rev l1) (rev l2).
Proof.
  induction 1; simpl.
  - constructor.
  - apply Forall2_app; [assumption|constructor; [assumption|constructor]].
Qed.

(** ** The stack's invariant, for any reading of a block

    [R seg b] reads block [b] as the segment [seg] of the input, and [le] is
    the order that two adjacent blocks left unpooled keep. When pooling
    keeps [R] and refusing to pool gives [le], the stack stays ordered and
    the final blocks spell the input. Used below for the means ([Rep],
    [MeanLe]) and in RightDerivative.v for the mean pairs ([Rep2], [LexLe]). *)
Section StackInvariant.
  Context {A : Type} (R : list A -> block -> Prop) (le : block -> block -> Prop).
  Hypothesis R_merge : forall sa sb a b,
    R sa a -> R sb b -> pools a b = true -> R (sa ++ sb) (merge a b).
  Hypothesis le_unpooled : forall a b, pools a b = false -> le a b.

  (** Pushing a block on a stack keeps the invariant; the segments of the
      new stack spell the old ones followed by the new block's. *)
  Lemma push_invariant (stack : list block) (segs : list (list A)) (cur : block)
    (seg : list A) :
    Forall2 R segs stack -> OrderedBy le stack -> R seg cur ->
    exists segs', Forall2 R segs' (push stack cur) /\ OrderedBy le (push stack cur) /\
      concat (rev segs') = concat (rev segs) ++ seg.
  Proof.
    revert segs cur seg.
    induction stack as [|top rest IH]; intros segs cur seg Hf Ho Hr.
    - inversion Hf; subst. exists [seg]. simpl.
      split; [constructor; [exact Hr|constructor]|split; [exact I|apply app_nil_r]].
    - inversion Hf as [|st b srest rest' Hst Hsrest]; subst. simpl.
      destruct (pools top cur) eqn:Hp.
      + assert (Ho' : OrderedBy le rest) by (destruct rest; simpl in *; tauto).
        destruct (IH srest (merge top cur) (st ++ seg) Hsrest Ho'
                    (R_merge _ _ _ _ Hst Hr Hp)) as (segs' & H1 & H2 & H3).
        exists segs'. split; [exact H1|split; [exact H2|]].
        rewrite H3. simpl. rewrite concat_app. simpl. rewrite app_nil_r, app_assoc. reflexivity.
      + exists (seg :: st :: srest). split; [|split].
        * constructor; [exact Hr|constructor; assumption].
        * simpl. split; [apply le_unpooled; exact Hp|exact Ho].
        * simpl. rewrite !concat_app. simpl. rewrite !app_nil_r. reflexivity.
  Qed.

  Lemma chain_snoc (l : list block) (a b : block) :
    ChainBy le (l ++ [a]) -> le a b -> ChainBy le (l ++ [a; b]).
  Proof.
    induction l as [|x l IH]; intros Hc Hab.
    - simpl. auto.
    - destruct l as [|y l].
      + simpl in *. tauto.
      + simpl in Hc |- *. destruct Hc as [H1 H2]. split; [exact H1|].
        apply IH; assumption.
  Qed.

  Lemma ordered_chain (stack : list block) : OrderedBy le stack -> ChainBy le (rev stack).
  Proof.
    induction stack as [|top rest IH]; intro Ho.
    - exact I.
    - destruct rest as [|below rest].
      + exact I.
      + simpl in Ho. destruct Ho as [H1 H2].
        specialize (IH H2). simpl in IH |- *.
        rewrite <- app_assoc. simpl. apply chain_snoc; assumption.
  Qed.

  (** [f e] is what the input's entry [e] contributes to a segment. *)
  Variable f : Q * Q -> A.
  Hypothesis R_single : forall e, R [f e] (single e).

  Lemma pava_stack_invariant (stack : list block) (segs : list (list A)) (es : list (Q * Q)) :
    Forall2 R segs stack -> OrderedBy le stack ->
    exists segs', Forall2 R segs' (pava_stack stack es) /\
      OrderedBy le (pava_stack stack es) /\ concat (rev segs') = concat (rev segs) ++ map f es.
  Proof.
    revert stack segs. induction es as [|e es IH]; intros stack segs Hf Ho; simpl.
    - exists segs. rewrite app_nil_r. auto.
    - destruct (push_invariant stack segs (single e) [f e] Hf Ho (R_single e))
        as (segs1 & H1 & H2 & H3).
      destruct (IH _ _ H1 H2) as (segs2 & G1 & G2 & G3).
      exists segs2. split; [exact G1|split; [exact G2|]].
      rewrite G3, H3, <- app_assoc. reflexivity.
  Qed.

  (** The blocks of PAVA read as consecutive segments spelling the input,
      in the order [le]. *)
  Lemma pava_blocks_invariant (es : list (Q * Q)) :
    exists segs, Forall2 R segs (pava_blocks es) /\ ChainBy le (pava_blocks es) /\
      concat segs = map f es.
  Proof.
    destruct (pava_stack_invariant [] [] es (Forall2_nil _) I) as (segs & H1 & H2 & H3).
    exists (rev segs). unfold pava_blocks. split; [|split].
    - apply forall2_rev. exact H1.
    - apply ordered_chain. exact H2.
    - rewrite H3. reflexivity.
  Qed.
End StackInvariant.

(** The blocks of PAVA represent consecutive segments spelling the input,
    with non-decreasing means. *)
Lemma pava_blocks_inv (es : list (Q * Q)) :
  exists segs, Forall2 Rep segs (pava_blocks es) /\ Chain (pava_blocks es) /\
    concat segs = map fst es.
Proof. exact (pava_blocks_invariant Rep MeanLe rep_merge pools_false fst rep_single es). Qed.

(** ** From the invariant to the KKT conditions *)

Lemma mean_le (a b : block) :
  bsum a * psize b <= bsum b * psize a -> mean a <= mean b.
Proof.
  intro H. pose proof (psize_pos a). pose proof (psize_pos b).
  assert (0 <= mean b - mean a); [|lra].
  apply (Qmult_pos_le_reg (psize a * psize b)).
  { apply Qmult_lt_0_compat; assumption. }
  setoid_replace (psize a * psize b * (mean b - mean a))
    with (psize a * (mean b * psize b) - psize b * (mean a * psize a)) by ring.
  rewrite !mean_mul. lra.
Qed.

(** Inside a block the prefix sums of the input stay above those of the mean. *)
Lemma rep_prefix (seg : list Q) (b : block) :
  Rep seg b -> forall k, (k <= length seg)%nat -> 0 <= psum k seg - qn k * mean b.
Proof.
  intros Hr k Hk. pose proof (rep_psize _ _ Hr) as Hp.
  destruct Hr as (Hn & Hs & _ & Hpool).
  assert (Hpos : 0 < qn (length seg)).
  { apply qn_pos. destruct seg; [contradiction|simpl; lia]. }
  apply (Qmult_pos_le_reg (qn (length seg))); [exact Hpos|].
  setoid_replace (qn (length seg) * (psum k seg - qn k * mean b))
    with (qn (length seg) * psum k seg - qn k * (mean b * qn (length seg))) by ring.
  assert (Hm : mean b * qn (length seg) == qsum seg) by (rewrite <- Hp, mean_mul, Hs; reflexivity).
  rewrite Hm. specialize (Hpool k Hk). lra.
Qed.

Lemma rep_total (seg : list Q) (b : block) :
  Rep seg b -> qsum seg - qn (length seg) * mean b == 0.
Proof.
  intro Hr. pose proof (rep_psize _ _ Hr) as Hp. destruct Hr as (_ & Hs & _).
  rewrite <- Hp. setoid_replace (psize b * mean b) with (mean b * psize b) by ring.
  rewrite mean_mul, Hs. ring.
Qed.

Lemma block_inner (seg : list Q) : forall c m rz ry,
  (forall k, (k <= length seg)%nat -> 0 <= c + psum k seg - qn k * m) ->
  c + qsum seg - qn (length seg) * m == 0 ->
  kkt_from 0 m rz ry ->
  kkt_from c m (seg ++ rz) (repeat m (length seg) ++ ry).
Proof.
  induction seg as [|a seg IH]; intros c m rz ry Hk Hs Hr.
  - simpl in Hs |- *. rewrite qn_0 in Hs. apply (kkt_from_qeq rz ry 0); [lra|exact Hr].
  - simpl. split; [|split; [apply Qle_refl|split]].
    + specialize (Hk 0%nat ltac:(lia)). rewrite psum_0, qn_0 in Hk. lra.
    + intro Hl. exfalso. apply (Qlt_irrefl _ Hl).
    + apply IH; [|simpl length in Hs; rewrite qn_S in Hs; simpl in Hs; lra|exact Hr].
      intros k Hk'. specialize (Hk (S k) ltac:(simpl; lia)).
      rewrite psum_cons, qn_S in Hk. lra.
Qed.

Lemma rep_length (seg : list Q) (b : block) :
  Rep seg b -> Pos.to_nat (bsize b) = length seg.
Proof.
  intros (_ & _ & Hl & _). apply Nat2Z.inj. rewrite positive_nat_Z. symmetry. exact Hl.
Qed.

(** One block of PAVA meets the KKT conditions on its segment. *)
Lemma block_kkt (seg : list Q) (b : block) (yp : Q) (rz ry : list Q) :
  Rep seg b -> yp <= mean b -> kkt_from 0 (mean b) rz ry ->
  kkt_from 0 yp (seg ++ rz) (expand b ++ ry).
Proof.
  intros Hr Hyp Hrest. unfold expand. rewrite (rep_length _ _ Hr).
  pose proof (rep_prefix _ _ Hr) as Hpre. pose proof (rep_total _ _ Hr) as Htot.
  destruct seg as [|a seg]; [destruct Hr; contradiction|].
  simpl. split; [apply Qle_refl|split; [exact Hyp|split; [intros _; reflexivity|]]].
  apply block_inner; [|simpl length in Htot; rewrite qn_S in Htot; simpl in Htot; lra|exact Hrest].
  intros k Hk. specialize (Hpre (S k) ltac:(simpl; lia)).
  rewrite psum_cons, qn_S in Hpre. lra.
Qed.

Lemma chain_kkt (segs : list (list Q)) (bs : list block) :
  Forall2 Rep segs bs -> Chain bs ->
  forall yp, (forall b, hd_error bs = Some b -> yp <= mean b) ->
  kkt_from 0 yp (concat segs) (flat_map expand bs).
Proof.
  induction 1 as [|seg b segs bs Hr Hf IH]; intros Hc yp Hyp.
  - simpl. reflexivity.
  - simpl. apply block_kkt; [exact Hr|apply Hyp; reflexivity|].
    apply IH.
    + destruct bs; simpl in Hc; tauto.
    + intros b2 Hb2. destruct bs as [|b' bs]; [discriminate|].
      simpl in Hb2. injection Hb2 as <-. apply mean_le. simpl in Hc. tauto.
Qed.

(** ** Correctness of PAVA *)

(** The lexicographic PAVA on [(y_i, u_i)] projects [y]: its output meets
    the KKT conditions of [P_{K̃}(y)] (left-to-right form). *)
Lemma pava_blocks_kkt_rec (es : list (Q * Q)) :
  kkt_rec (map fst es) (flat_map expand (pava_blocks es)).
Proof.
  destruct (pava_blocks_inv es) as (segs & Hf & Hc & Hz). rewrite <- Hz.
  destruct (pava_blocks es) as [|b bs] eqn:E.
  - inversion Hf. reflexivity.
  - destruct (Pos2Nat.is_succ (bsize b)) as [n Hn].
    assert (Hy : flat_map expand (b :: bs) = mean b :: (repeat (mean b) n ++ flat_map expand bs)).
    { simpl. unfold expand at 1. rewrite Hn. reflexivity. }
    rewrite Hy. unfold kkt_rec. rewrite <- Hy.
    apply chain_kkt; [exact Hf|exact Hc|].
    intros b' Hb'. simpl in Hb'. injection Hb' as <-. apply Qle_refl.
Qed.

Lemma map_fst_combine (y u : list Q) :
  length u = length y -> map fst (combine y u) = y.
Proof.
  revert u. induction y as [|a y IH]; intros [|b u] L; simpl in *; try discriminate.
  - reflexivity.
  - f_equal. apply IH. lia.
Qed.

(** Main theorem ([lem:proj-characterization], [app:KKT] corrected, [df:tKN];
    ledger: [lem:proj-characterization], [app:KKT]): for every [N] and every
    [y, u ∈ Q^N], the lexicographic PAVA's output [pava_lex y u] meets the
    KKT conditions of the projection of [y] onto the cone of non-decreasing
    vectors — it is non-decreasing, the partial sums of [y − pava_lex y u]
    are [≥ 0], vanish at [N] and wherever the output jumps. *)
Theorem pava_lex_kkt (y u : list Q) :
  length u = length y -> Kkt y (pava_lex y u).
Proof.
  intro L. apply kkt_rec_iff. unfold pava_lex.
  replace y with (map fst (combine y u)) at 1.
  - apply pava_blocks_kkt_rec.
  - apply map_fst_combine. exact L.
Qed.

(** The plain PAVA computes the projection of [z] onto [K̃^N] in KKT form. *)
Theorem pava_kkt (z : list Q) : Kkt z (pava z).
Proof.
  apply kkt_rec_iff. unfold pava.
  replace z with (map fst (map (fun a => (a, 0)) z)) at 1.
  - apply pava_blocks_kkt_rec.
  - rewrite map_map. simpl. apply map_id.
Qed.

(** In particular PAVA's output is non-decreasing ([df:tKN]). *)
Corollary pava_monotone (z : list Q) : Monotone (pava z).
Proof. apply pava_kkt. Qed.
