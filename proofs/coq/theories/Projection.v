(** * The projection [P_K]: KKT ⇒ unique minimiser, PAVA computes it,
      [P_K] on positions, and [P_K] is 1-Lipschitz.

    The squared distance is [sqnorm (vsub a b) = Σ (a_i − b_i)²]; the paper's
    norm [‖x‖² = (1/N) Σ x_i²] differs by the factor [1/N], which changes none
    of the inequalities below. *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava.
Import ListNotations.
Open Scope Q_scope.

(** ** The variational inequality behind the KKT conditions *)

(** [w] non-decreasing, its first entry at least [wp]. *)
Fixpoint mono_from (wp : Q) (w : list Q) : Prop :=
  match w with
  | [] => True
  | w1 :: w' => wp <= w1 /\ mono_from w1 w'
  end.

Lemma monotone_tail (a : Q) (l : list Q) : Monotone (a :: l) -> Monotone l.
Proof. intros H i Hi. apply (H (S i)). simpl. lia. Qed.

Lemma monotone_mono_from (l : list Q) : forall a, Monotone (a :: l) -> mono_from a l.
Proof.
  induction l as [|b l IH]; intros a H; simpl; [exact I|].
  split.
  - apply (H 0%nat). simpl. lia.
  - apply IH. apply (monotone_tail a). exact H.
Qed.

(** Summation by parts: with [c] the partial sum of [z − y] so far and
    [(yp, wp)] the previous entries of [y] and [w],
    [c (yp − wp) + Σ (z_i − y_i)(y_i − w_i) ≥ 0]. *)
Lemma vi_from (z : list Q) : forall y w c yp wp,
  kkt_from c yp z y -> length w = length y -> mono_from wp w ->
  0 <= c * (yp - wp) + dot (vsub z y) (vsub y w).
Proof.
  induction z as [|zi z IH]; intros y w c yp wp Hk Hl Hw;
    destruct y as [|yi y]; simpl in Hk; try contradiction.
  - destruct w; [|discriminate]. simpl. rewrite Hk. lra.
  - destruct w as [|wi w]; [discriminate|]. simpl in Hl, Hw |- *.
    destruct Hk as (H0 & H1 & H2 & H3). destruct Hw as [Hw1 Hw2].
    specialize (IH y w (c + (zi - yi)) yi wi H3 ltac:(lia) Hw2).
    assert (Hc : c * (yp - yi) == 0).
    { destruct (Qlt_le_dec yp yi) as [Hlt|Hge].
      - rewrite (H2 Hlt). ring.
      - setoid_replace (yp - yi) with 0 by lra. ring. }
    assert (Hw' : 0 <= c * (wi - wp)) by (apply Qmult_le_0_compat; lra).
    setoid_replace (c * (yp - wp) + ((zi - yi) * (yi - wi) + dot (vsub z y) (vsub y w)))
      with (c * (yp - yi) + c * (wi - wp)
            + ((c + (zi - yi)) * (yi - wi) + dot (vsub z y) (vsub y w))) by ring.
    lra.
Qed.

(** [lem:proj-characterization], the direction used by the paper:
    "y = P_C(z) ⟸ z − y ∈ N_y C", written as the variational inequality
    [⟨z − y, y − w⟩ ≥ 0] for every [w ∈ K̃^N]. *)
Theorem kkt_variational (z y w : list Q) :
  Kkt z y -> Monotone w -> length w = length z -> 0 <= dot (vsub z y) (vsub y w).
Proof.
  intros Hk Hw Hl. pose proof (proj1 Hk) as Ly. apply kkt_rec_iff in Hk.
  destruct y as [|y1 y]; simpl in Hk.
  - subst z. simpl. apply Qle_refl.
  - destruct w as [|w1 w]; [simpl in *; lia|].
    assert (Hm : mono_from w1 (w1 :: w)).
    { split; [apply Qle_refl|apply monotone_mono_from; exact Hw]. }
    pose proof (vi_from z (y1 :: y) (w1 :: w) 0 y1 w1 Hk ltac:(lia) Hm). lra.
Qed.

(** ** KKT ⇒ the unique minimiser *)

Lemma pythagoras (z : list Q) : forall y w,
  length y = length z -> length w = length z ->
  sqnorm (vsub z w) == sqnorm (vsub z y) + sqnorm (vsub y w)
                       + 2 * dot (vsub z y) (vsub y w).
Proof.
  induction z as [|a z IH]; intros [|b y] [|c w] Ly Lw; simpl in *; try discriminate.
  - ring.
  - rewrite (IH y w) by lia. ring.
Qed.

Lemma sq_zero (a : Q) : a * a <= 0 -> a == 0.
Proof.
  intro H. destruct (Qeq_dec a 0) as [E|E]; [exact E|].
  exfalso. assert (0 < a * a); [|lra].
  destruct (Qlt_le_dec a 0) as [Hl|Hl].
  - setoid_replace (a * a) with ((- a) * (- a)) by ring.
    apply Qmult_lt_0_compat; lra.
  - apply Qmult_lt_0_compat; [|]; apply Qle_lt_or_eq in Hl; destruct Hl as [Hl|Hl];
      try exact Hl; exfalso; apply E; symmetry; exact Hl.
Qed.

Lemma sqnorm_zero (a : list Q) : forall b,
  length b = length a -> sqnorm (vsub a b) <= 0 -> qeq_list a b.
Proof.
  induction a as [|x a IH]; intros [|y b] L H; simpl in *; try discriminate.
  - constructor.
  - pose proof (Qsq_nonneg (x - y)). pose proof (sqnorm_nonneg (vsub a b)).
    constructor.
    + assert (x - y == 0) by (apply sq_zero; lra). lra.
    + apply IH; [lia|lra].
Qed.

(** [lem:proj-characterization] ("y = P_C(z) ⟺ z − y ∈ N_y C", direction ⟸,
    in KKT form, [app:KKT] corrected; ledger: [lem:proj-characterization],
    [app:KKT]): a [y] meeting the KKT conditions minimises [Σ (z_i − w_i)²]
    over the non-decreasing [w], with the margin [Σ (y_i − w_i)²]. *)
Theorem kkt_minimiser (z y w : list Q) :
  Kkt z y -> Monotone w -> length w = length z ->
  sqnorm (vsub z y) + sqnorm (vsub y w) <= sqnorm (vsub z w).
Proof.
  intros Hk Hw Hl. pose proof (kkt_variational z y w Hk Hw Hl).
  rewrite (pythagoras z y w (proj1 Hk) Hl). lra.
Qed.

(** ... and it is the only one: a non-decreasing [w] at most as far from [z]
    equals [y] entrywise. *)
Theorem kkt_unique_minimiser (z y w : list Q) :
  Kkt z y -> Monotone w -> length w = length z ->
  sqnorm (vsub z w) <= sqnorm (vsub z y) -> qeq_list y w.
Proof.
  intros Hk Hw Hl Hle. pose proof (kkt_minimiser z y w Hk Hw Hl).
  apply sqnorm_zero; [rewrite Hl; symmetry; exact (proj1 Hk)|lra].
Qed.

(** Two solutions of the KKT conditions are equal. *)
Corollary kkt_unique (z y1 y2 : list Q) : Kkt z y1 -> Kkt z y2 -> qeq_list y1 y2.
Proof.
  intros H1 H2. apply (kkt_unique_minimiser z y1 y2 H1 (proj1 (proj2 H2)) (proj1 H2)).
  pose proof (kkt_minimiser z y2 y1 H2 (proj1 (proj2 H1)) (proj1 H1)).
  pose proof (sqnorm_nonneg (vsub y2 y1)). lra.
Qed.

(** PAVA computes [P_{K̃}]: for every [N] and [z ∈ Q^N], [pava z] is
    non-decreasing and is the unique minimiser of [Σ (z_i − w_i)²] over the
    non-decreasing [w] ([df:tKN], [lem:proj-characterization];
    ledger: [lem:proj-characterization]). *)
Theorem pava_is_projection (z w : list Q) :
  Monotone w -> length w = length z ->
  sqnorm (vsub z (pava z)) + sqnorm (vsub (pava z) w) <= sqnorm (vsub z w).
Proof. apply kkt_minimiser, pava_kkt. Qed.

(** ** [P_K] on positions ([df:KN], [df:translat-x]) *)

(** [P_{K^N}(x)] for radius [r]: translate, project on the monotone cone,
    translate back (the remark on [df:translat-x]). *)
Definition proj_K (r : Q) (x : list Q) : list Q := untranslate r (pava (translate r x)).

Lemma translate_from_length (k : nat) (r : Q) (x : list Q) :
  length (translate_from k r x) = length x.
Proof. revert k. induction x; intros k; simpl; [reflexivity|f_equal; apply IHx]. Qed.

Lemma untranslate_from_length (k : nat) (r : Q) (x : list Q) :
  length (untranslate_from k r x) = length x.
Proof. revert k. induction x; intros k; simpl; [reflexivity|f_equal; apply IHx]. Qed.

Lemma nth_translate_from (x : list Q) : forall k i r,
  (i < length x)%nat -> nth i (translate_from k r x) 0 == nth i x 0 - 2 * r * qn (k + i).
Proof.
  induction x as [|a x IH]; intros k i r Hi; simpl in Hi; [lia|].
  destruct i as [|i]; simpl.
  - rewrite Nat.add_0_r. reflexivity.
  - rewrite IH by lia. rewrite Nat.add_succ_r. reflexivity.
Qed.

Lemma nth_untranslate_from (x : list Q) : forall k i r,
  (i < length x)%nat -> nth i (untranslate_from k r x) 0 == nth i x 0 + 2 * r * qn (k + i).
Proof.
  induction x as [|a x IH]; intros k i r Hi; simpl in Hi; [lia|].
  destruct i as [|i]; simpl.
  - rewrite Nat.add_0_r. reflexivity.
  - rewrite IH by lia. rewrite Nat.add_succ_r. reflexivity.
Qed.

(** [x ∈ K^N] iff its translate is non-decreasing ([df:KN] ⟺ [df:tKN]). *)
Lemma inK_translate (r : Q) (x : list Q) : InK r x -> Monotone (translate r x).
Proof.
  intros H i Hi. unfold translate in *. rewrite translate_from_length in Hi.
  rewrite !nth_translate_from by lia. specialize (H i Hi).
  simpl. rewrite qn_S. lra.
Qed.

Lemma monotone_untranslate (r : Q) (y : list Q) : Monotone y -> InK r (untranslate r y).
Proof.
  intros H i Hi. unfold untranslate in *. rewrite untranslate_from_length in Hi.
  rewrite !nth_untranslate_from by lia. specialize (H i Hi).
  simpl. rewrite qn_S. lra.
Qed.

(** Translating both lists, or one list one way and the other back, keeps
    the differences. *)
Lemma sqnorm_translate_both (a : list Q) : forall b k r,
  sqnorm (vsub (translate_from k r a) (translate_from k r b)) == sqnorm (vsub a b).
Proof.
  induction a as [|x a IH]; intros [|y b] k r; simpl; try reflexivity.
  rewrite IH. ring.
Qed.

Lemma sqnorm_untranslate_both (a : list Q) : forall b k r,
  sqnorm (vsub (untranslate_from k r a) (untranslate_from k r b)) == sqnorm (vsub a b).
Proof.
  induction a as [|x a IH]; intros [|y b] k r; simpl; try reflexivity.
  rewrite IH. ring.
Qed.

Lemma sqnorm_untranslate_right (a : list Q) : forall b k r,
  sqnorm (vsub a (untranslate_from k r b)) == sqnorm (vsub (translate_from k r a) b).
Proof.
  induction a as [|x a IH]; intros [|y b] k r; simpl; try reflexivity.
  rewrite IH. ring.
Qed.

Lemma sqnorm_untranslate_left (a : list Q) : forall b k r,
  sqnorm (vsub (untranslate_from k r a) b) == sqnorm (vsub a (translate_from k r b)).
Proof.
  induction a as [|x a IH]; intros [|y b] k r; simpl; try reflexivity.
  rewrite IH. ring.
Qed.

Lemma proj_K_length (r : Q) (x : list Q) : length (proj_K r x) = length x.
Proof.
  unfold proj_K, untranslate, translate.
  rewrite untranslate_from_length, (proj1 (pava_kkt _)), translate_from_length.
  reflexivity.
Qed.

(** [P_K(x) ∈ K^N] ([df:KN]; ledger: [df:KN]). *)
Theorem proj_K_in_K (r : Q) (x : list Q) : InK r (proj_K r x).
Proof. apply monotone_untranslate, pava_monotone. Qed.

(** [P_K(x)] is the point of [K^N] nearest to [x], uniquely
    ([df:KN], [lem:proj-characterization]; ledger: [lem:proj-characterization],
    [prop:proj-micro] for the formula [x(t) = P_K(x⁰ + t u⁰)] it evaluates):
    for every [x' ∈ K^N],
    [Σ (x_i − P_K(x)_i)² + Σ (P_K(x)_i − x'_i)² ≤ Σ (x_i − x'_i)²]. *)
Theorem proj_K_minimiser (r : Q) (x x' : list Q) :
  InK r x' -> length x' = length x ->
  sqnorm (vsub x (proj_K r x)) + sqnorm (vsub (proj_K r x) x') <= sqnorm (vsub x x').
Proof.
  intros Hk Hl. unfold proj_K, untranslate.
  rewrite sqnorm_untranslate_right, sqnorm_untranslate_left.
  rewrite <- (sqnorm_translate_both x x' 0 r).
  apply pava_is_projection; [apply inK_translate; exact Hk|].
  unfold translate. rewrite !translate_from_length. exact Hl.
Qed.

(** ** [P_K] is 1-Lipschitz (issue 26, item 8) *)

Lemma lipschitz_identity (z1 : list Q) : forall z2 y1 y2,
  length z2 = length z1 -> length y1 = length z1 -> length y2 = length z1 ->
  sqnorm (vsub z1 z2) - sqnorm (vsub y1 y2) ==
  2 * (dot (vsub z1 y1) (vsub y1 y2) + dot (vsub z2 y2) (vsub y2 y1))
  + sqnorm (vsub (vsub z1 z2) (vsub y1 y2)).
Proof.
  induction z1 as [|a z1 IH]; intros [|b z2] [|c y1] [|d y2] L1 L2 L3;
    simpl in *; try discriminate.
  - ring.
  - setoid_replace ((a - b) * (a - b) + sqnorm (vsub z1 z2) -
                    ((c - d) * (c - d) + sqnorm (vsub y1 y2)))
      with ((a - b) * (a - b) - (c - d) * (c - d)
            + (sqnorm (vsub z1 z2) - sqnorm (vsub y1 y2))) by ring.
    rewrite (IH z2 y1 y2) by lia. ring.
Qed.

(** The projection onto the monotone cone is non-expansive in the Euclidean
    norm: [‖P z₁ − P z₂‖ ≤ ‖z₁ − z₂‖] (squared, so over [Q]). *)
Theorem kkt_lipschitz (z1 z2 y1 y2 : list Q) :
  Kkt z1 y1 -> Kkt z2 y2 -> length z2 = length z1 ->
  sqnorm (vsub y1 y2) <= sqnorm (vsub z1 z2).
Proof.
  intros H1 H2 L.
  pose proof (kkt_variational z1 y1 y2 H1 (proj1 (proj2 H2))
                ltac:(rewrite (proj1 H2); exact L)).
  pose proof (kkt_variational z2 y2 y1 H2 (proj1 (proj2 H1))
                ltac:(rewrite (proj1 H1); symmetry; exact L)).
  pose proof (sqnorm_nonneg (vsub (vsub z1 z2) (vsub y1 y2))).
  pose proof (lipschitz_identity z1 z2 y1 y2 L (proj1 H1)
                ltac:(rewrite (proj1 H2); exact L)).
  lra.
Qed.

(** [P_K] on positions is 1-Lipschitz in the Euclidean norm (issue 26 item 8;
    used by the atlas: a solver whose input is within [ε] of [x⁰ + t u⁰]
    lands within [ε] of [x(t) = P_K(x⁰ + t u⁰)], [prop:proj-micro]):
    [Σ (P_K(x₁)_i − P_K(x₂)_i)² ≤ Σ (x₁_i − x₂_i)²]. *)
Theorem proj_K_lipschitz (r : Q) (x1 x2 : list Q) :
  length x2 = length x1 ->
  sqnorm (vsub (proj_K r x1) (proj_K r x2)) <= sqnorm (vsub x1 x2).
Proof.
  intro L. unfold proj_K, untranslate. rewrite sqnorm_untranslate_both.
  rewrite <- (sqnorm_translate_both x1 x2 0 r).
  apply kkt_lipschitz; [apply pava_kkt|apply pava_kkt|].
  unfold translate. rewrite !translate_from_length. exact L.
Qed.
