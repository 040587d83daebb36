(** * [P_K] is 1-Lipschitz in the sup norm.

    The atlas measures errors in the maximum norm. The projection onto the
    monotone cone is order-preserving ([z₁ ≤ z₂] entrywise ⇒
    [P z₁ ≤ P z₂]) and commutes with adding a constant, hence
    [max_i |P(z₁)_i − P(z₂)_i| ≤ max_i |z₁_i − z₂_i|]; with the translation
    [df:translat-x] the same holds for [P_K] on positions. *)

From Coq Require Import QArith Qabs Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection Oracle RightDerivative.
Import ListNotations.
Open Scope Q_scope.

(** ** Entrywise minimum and maximum *)

Definition qmin (x y : Q) : Q := if Qle_bool x y then x else y.
Definition qmax (x y : Q) : Q := if Qle_bool x y then y else x.

Lemma qmin_cases (x y : Q) : (x <= y /\ qmin x y = x) \/ (y < x /\ qmin x y = y).
Proof.
  unfold qmin. destruct (Qle_bool x y) eqn:E.
  - left. split; [apply Qle_bool_iff; exact E|reflexivity].
  - right. split; [|reflexivity]. apply Qnot_le_lt. intro H.
    apply Qle_bool_iff in H. congruence.
Qed.

Lemma qmax_cases (x y : Q) : (x <= y /\ qmax x y = y) \/ (y < x /\ qmax x y = x).
Proof.
  unfold qmax. destruct (Qle_bool x y) eqn:E.
  - left. split; [apply Qle_bool_iff; exact E|reflexivity].
  - right. split; [|reflexivity]. apply Qnot_le_lt. intro H.
    apply Qle_bool_iff in H. congruence.
Qed.

Lemma qmin_mono (a b c d : Q) : a <= c -> b <= d -> qmin a b <= qmin c d.
Proof.
  intros H1 H2. destruct (qmin_cases a b) as [[L E]|[L E]]; rewrite E;
    destruct (qmin_cases c d) as [[L' E']|[L' E']]; rewrite E'; lra.
Qed.

Lemma qmax_mono (a b c d : Q) : a <= c -> b <= d -> qmax a b <= qmax c d.
Proof.
  intros H1 H2. destruct (qmax_cases a b) as [[L E]|[L E]]; rewrite E;
    destruct (qmax_cases c d) as [[L' E']|[L' E']]; rewrite E'; lra.
Qed.

(** [f] entry by entry on two lists (as long as the shorter); [vmin] and
    [vmax] are its two instances. *)
Fixpoint vzip (f : Q -> Q -> Q) (a b : list Q) : list Q :=
  match a, b with
  | x :: a', y :: b' => f x y :: vzip f a' b'
  | _, _ => []
  end.

Notation vmin := (vzip qmin).
Notation vmax := (vzip qmax).

Section Entrywise.
  (** An operation monotone in both arguments that maps [0, 0] (the
      default of [nth]) to [0]. *)
  Variable f : Q -> Q -> Q.
  Hypothesis f_mono : forall a b c d, a <= c -> b <= d -> f a b <= f c d.
  Hypothesis f_zero : f 0 0 = 0.

  Lemma nth_vzip (a : list Q) : forall b i,
    length b = length a -> nth i (vzip f a b) 0 = f (nth i a 0) (nth i b 0).
  Proof.
    induction a as [|x a IH]; intros [|y b] i L; simpl in L; try discriminate.
    - destruct i; symmetry; exact f_zero.
    - destruct i; simpl; [reflexivity|apply IH; lia].
  Qed.

  Lemma vzip_length (a : list Q) : forall b, length b = length a -> length (vzip f a b) = length a.
  Proof.
    induction a as [|x a IH]; intros [|y b] L; simpl in *; try discriminate; [reflexivity|].
    f_equal. apply IH. lia.
  Qed.

  Lemma vzip_monotone (a b : list Q) :
    length b = length a -> Monotone a -> Monotone b -> Monotone (vzip f a b).
  Proof.
    intros L Ha Hb i Hi. rewrite vzip_length in Hi by exact L.
    rewrite !nth_vzip by exact L. apply f_mono; [apply Ha|apply Hb]; lia.
  Qed.
End Entrywise.

Definition nth_vmin := nth_vzip qmin eq_refl.
Definition nth_vmax := nth_vzip qmax eq_refl.
Definition vmin_length := vzip_length qmin.
Definition vmax_length := vzip_length qmax.
Definition vmin_monotone := vzip_monotone qmin qmin_mono eq_refl.
Definition vmax_monotone := vzip_monotone qmax qmax_mono eq_refl.

(** Entrywise [a ≤ b]. *)
Definition LeList (a b : list Q) : Prop := forall i, nth i a 0 <= nth i b 0.

(** Exchanging the larger entries of [y₁] with those of [y₂] does not
    increase [Σ(z₁ − ·)² + Σ(z₂ − ·)²] when [z₁ ≤ z₂]. *)
Lemma lattice_sq (z1 : list Q) : forall z2 y1 y2,
  length z2 = length z1 -> length y1 = length z1 -> length y2 = length z1 ->
  LeList z1 z2 ->
  sqnorm (vsub z1 (vmin y1 y2)) + sqnorm (vsub z2 (vmax y1 y2)) <=
  sqnorm (vsub z1 y1) + sqnorm (vsub z2 y2).
Proof.
  induction z1 as [|a z1 IH]; intros [|b z2] [|c y1] [|d y2] L1 L2 L3 Hz;
    simpl in *; try discriminate; try lra.
  assert (Hab : a <= b) by apply (Hz 0%nat).
  assert (Hrest : LeList z1 z2) by (intro i; apply (Hz (S i))).
  specialize (IH z2 y1 y2 ltac:(lia) ltac:(lia) ltac:(lia) Hrest).
  destruct (qmin_cases c d) as [[Lm Em]|[Lm Em]]; rewrite Em;
    destruct (qmax_cases c d) as [[LM EM]|[LM EM]]; rewrite EM; try lra.
  assert (0 <= (b - a) * (c - d)) by (apply Qmult_le_0_compat; lra).
  setoid_replace ((a - c) * (a - c) + sqnorm (vsub z1 y1) + ((b - d) * (b - d) + sqnorm (vsub z2 y2)))
    with ((a - d) * (a - d) + (b - c) * (b - c) + 2 * ((b - a) * (c - d))
          + (sqnorm (vsub z1 y1) + sqnorm (vsub z2 y2))) by ring.
  lra.
Qed.

(** ** Order preservation and shifts *)

(** The projection onto the monotone cone preserves the entrywise order. *)
Theorem kkt_order (z1 z2 y1 y2 : list Q) :
  Kkt z1 y1 -> Kkt z2 y2 -> length z2 = length z1 -> LeList z1 z2 -> LeList y1 y2.
Proof.
  intros H1 H2 L Hz.
  pose proof (proj1 H1) as L1. pose proof (proj1 H2) as L2.
  pose proof (proj1 (proj2 H1)) as M1. pose proof (proj1 (proj2 H2)) as M2.
  assert (Lm : length (vmin y1 y2) = length z1) by (rewrite vmin_length; lia).
  assert (LM : length (vmax y1 y2) = length z2) by (rewrite vmax_length; lia).
  pose proof (kkt_minimiser z1 y1 (vmin y1 y2) H1 (vmin_monotone y1 y2 ltac:(lia) M1 M2) Lm).
  pose proof (kkt_minimiser z2 y2 (vmax y1 y2) H2 (vmax_monotone y1 y2 ltac:(lia) M1 M2) LM).
  pose proof (lattice_sq z1 z2 y1 y2 L L1 ltac:(lia) Hz).
  pose proof (sqnorm_nonneg (vsub y2 (vmax y1 y2))).
  pose proof (sqnorm_nonneg (vsub y1 (vmin y1 y2))).
  assert (E : qeq_list y1 (vmin y1 y2)).
  { apply sqnorm_zero; [rewrite vmin_length; lia|lra]. }
  intro i. pose proof (qeq_list_nth _ _ E i) as Ei.
  rewrite nth_vmin in Ei by lia. rewrite Ei.
  destruct (qmin_cases (nth i y1 0) (nth i y2 0)) as [[Lc Ec]|[Lc Ec]]; rewrite Ec; lra.
Qed.

(** [l + c], every entry shifted by [c]. *)
Definition vshift (c : Q) (l : list Q) : list Q := map (fun a => a + c) l.

Lemma vshift_length (c : Q) (l : list Q) : length (vshift c l) = length l.
Proof. apply map_length. Qed.

Lemma nth_vshift (c : Q) (l : list Q) : forall i,
  (i < length l)%nat -> nth i (vshift c l) 0 == nth i l 0 + c.
Proof.
  induction l as [|a l IH]; intros i Hi; simpl in Hi; [lia|].
  destruct i as [|i]; simpl; [reflexivity|apply IH; lia].
Qed.

Lemma psum_vshift (c : Q) (l : list Q) : forall k,
  psum k (vshift c l) == psum k l + qn (Nat.min k (length l)) * c.
Proof.
  induction l as [|a l IH]; intros [|k]; unfold vshift in *; cbn [map length Nat.min];
    try (unfold psum; simpl; rewrite ?qn_0; ring).
  rewrite !psum_cons. fold (vshift c l). rewrite IH, qn_S. ring.
Qed.

(** Adding a constant commutes with the projection (KKT form). *)
Lemma kkt_shift (c : Q) (z y : list Q) : Kkt z y -> Kkt (vshift c z) (vshift c y).
Proof.
  intros (L & M & P & T & C).
  assert (Sh : forall k, psum k (vshift c z) - psum k (vshift c y) == psum k z - psum k y).
  { intro k. rewrite !psum_vshift, L. ring. }
  unfold Kkt. rewrite !vshift_length. split; [exact L|split; [|split; [|split]]].
  - intros i Hi. rewrite vshift_length in Hi. rewrite !nth_vshift by lia.
    pose proof (M i Hi). lra.
  - intros k Hk. rewrite Sh. apply P, Hk.
  - pose proof (Sh (length z)). lra.
  - intros k Hk Hl. rewrite !nth_vshift in Hl by lia.
    assert (nth k y 0 < nth (S k) y 0) by lra.
    pose proof (Sh (S k)). pose proof (C k Hk H). lra.
Qed.

(** ** The sup-norm bound *)

(** [|a_i − b_i| ≤ e] for every index of [a]. *)
Definition SupWithin (e : Q) (a b : list Q) : Prop :=
  forall i, (i < length a)%nat -> Qabs (nth i a 0 - nth i b 0) <= e.

Lemma below_shift (e : Q) (z1 z2 : list Q) :
  length z2 = length z1 -> SupWithin e z1 z2 -> LeList (vshift (- e) z2) z1.
Proof.
  intros L H i. destruct (Nat.lt_ge_cases i (length z1)) as [Hi|Hi].
  - rewrite nth_vshift by lia. specialize (H i Hi).
    apply Qabs_Qle_condition in H. lra.
  - rewrite !nth_overflow by (rewrite ?vshift_length; lia). apply Qle_refl.
Qed.

Lemma above_shift (e : Q) (z1 z2 : list Q) :
  length z2 = length z1 -> SupWithin e z1 z2 -> LeList z1 (vshift e z2).
Proof.
  intros L H i. destruct (Nat.lt_ge_cases i (length z1)) as [Hi|Hi].
  - rewrite nth_vshift by lia. specialize (H i Hi).
    apply Qabs_Qle_condition in H. lra.
  - rewrite !nth_overflow by (rewrite ?vshift_length; lia). apply Qle_refl.
Qed.

(** The projection onto the monotone cone is 1-Lipschitz in the sup norm:
    [max_i |P(z₁)_i − P(z₂)_i| ≤ max_i |z₁_i − z₂_i|] (issue 26 item 8, the
    norm of the atlas's errors). *)
Theorem kkt_sup_lipschitz (e : Q) (z1 z2 y1 y2 : list Q) :
  Kkt z1 y1 -> Kkt z2 y2 -> length z2 = length z1 -> SupWithin e z1 z2 -> SupWithin e y1 y2.
Proof.
  intros H1 H2 L H.
  pose proof (kkt_order _ _ _ _ (kkt_shift (- e) _ _ H2) H1
                ltac:(rewrite vshift_length; lia) (below_shift e z1 z2 L H)) as Lo.
  pose proof (kkt_order _ _ _ _ H1 (kkt_shift e _ _ H2)
                ltac:(rewrite vshift_length; lia) (above_shift e z1 z2 L H)) as Hi.
  intros i Hi'. rewrite (proj1 H1) in Hi'.
  specialize (Lo i). specialize (Hi i).
  rewrite nth_vshift in Lo, Hi by (rewrite (proj1 H2); lia).
  apply Qabs_Qle_condition. lra.
Qed.

Lemma nth_translate_diff (x1 x2 : list Q) (k : nat) (r : Q) : forall i,
  length x2 = length x1 -> (i < length x1)%nat ->
  nth i (translate_from k r x1) 0 - nth i (translate_from k r x2) 0 == nth i x1 0 - nth i x2 0.
Proof.
  intros i L Hi. rewrite !nth_translate_from by lia. ring.
Qed.

Lemma nth_untranslate_diff (x1 x2 : list Q) (k : nat) (r : Q) : forall i,
  length x2 = length x1 -> (i < length x1)%nat ->
  nth i (untranslate_from k r x1) 0 - nth i (untranslate_from k r x2) 0 ==
  nth i x1 0 - nth i x2 0.
Proof.
  intros i L Hi. rewrite !nth_untranslate_from by lia. ring.
Qed.

(** [P_K] on positions is 1-Lipschitz in the sup norm (issue 26 item 8):
    a solver whose input is within [e] of [x⁰ + t u⁰] in every entry lands
    within [e] of [x(t) = P_K(x⁰ + t u⁰)] in every entry ([prop:proj-micro]). *)
Theorem proj_K_sup_lipschitz (e r : Q) (x1 x2 : list Q) :
  length x2 = length x1 -> SupWithin e x1 x2 -> SupWithin e (proj_K r x1) (proj_K r x2).
Proof.
  intros L H i Hi. rewrite proj_K_length in Hi.
  assert (Lp : length (pava (translate r x2)) = length (pava (translate r x1))).
  { rewrite (proj1 (pava_kkt _)), (proj1 (pava_kkt (translate r x1))).
    unfold translate. rewrite !translate_from_length. exact L. }
  assert (Lp1 : length (pava (translate r x1)) = length x1).
  { rewrite (proj1 (pava_kkt _)). unfold translate. apply translate_from_length. }
  unfold proj_K, untranslate. rewrite nth_untranslate_diff by lia.
  apply (kkt_sup_lipschitz e (translate r x1) (translate r x2)); try apply pava_kkt.
  - unfold translate. rewrite !translate_from_length. exact L.
  - intros j Hj. unfold translate in *. rewrite translate_from_length in Hj.
    rewrite nth_translate_diff by lia. apply H, Hj.
  - lia.
Qed.
