(** * The projection onto a convex set: [lem:proj-characterization] for
      every convex [C], both directions.

    Paper, [lem:proj-characterization]: "Let C ⊂ R^N be a closed convex
    set. Then, for every z ∈ R^N and y ∈ C, y = P_C(z) ⟺ z − y ∈ ∂I_C(y)
    = N_y C", with [N_y C = {v ; ⟨v, c − y⟩ ≤ 0 for all c ∈ C}].

    Here vectors are lists of rationals of length [N] and [C] is any
    predicate on them that is convex; [y = P_C(z)] means [y ∈ C] minimises
    [‖z − ·‖²] over [C] (closedness only serves the existence of [P_C(z)],
    which the lemma does not assert). Then the corollary for the monotone
    cone [K̃^N]: its normal cone is the index form [Kkt.Kkt] of the KKT
    conditions, and [y = P_{K̃}(z) ⟺ Kkt z y]. *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection RightDerivative.
Import ListNotations.
Open Scope Q_scope.

(** The point [a + θ (b − a)] of the segment [[a, b]]. *)
Fixpoint lerp (θ : Q) (a b : list Q) : list Q :=
  match a, b with
  | x :: a', y :: b' => (x + θ * (y - x)) :: lerp θ a' b'
  | _, _ => []
  end.

(** [C] is a convex set of vectors of [Q^N]. *)
Definition Convex (N : nat) (C : list Q -> Prop) : Prop :=
  (forall c, C c -> length c = N) /\
  (forall a b θ, C a -> C b -> 0 <= θ -> θ <= 1 -> C (lerp θ a b)).

(** [y = P_C(z)]: [y ∈ C] and no point of [C] is nearer to [z]. *)
Definition IsProjection (C : list Q -> Prop) (z y : list Q) : Prop :=
  C y /\ forall c, C c -> sqnorm (vsub z y) <= sqnorm (vsub z c).

(** [v ∈ N_y C]: [⟨v, c − y⟩ ≤ 0] for every [c ∈ C]. *)
Definition InNormalCone (C : list Q -> Prop) (y v : list Q) : Prop :=
  forall c, C c -> dot v (vsub c y) <= 0.

(** ** Two identities of the squared norm *)

Lemma sqnorm_lerp (z : list Q) : forall y c θ,
  length y = length z -> length c = length z ->
  sqnorm (vsub z (lerp θ y c)) ==
  sqnorm (vsub z y) - 2 * θ * dot (vsub z y) (vsub c y) + θ * θ * sqnorm (vsub c y).
Proof.
  induction z as [|a z IH]; intros [|b y] [|d c] θ Ly Lc; simpl in *; try discriminate.
  - ring.
  - rewrite (IH y c θ) by lia. ring.
Qed.

Lemma sqnorm_split (z : list Q) : forall y c,
  length y = length z -> length c = length z ->
  sqnorm (vsub z c) ==
  sqnorm (vsub z y) + sqnorm (vsub c y) - 2 * dot (vsub z y) (vsub c y).
Proof.
  induction z as [|a z IH]; intros [|b y] [|d c] Ly Lc; simpl in *; try discriminate.
  - ring.
  - rewrite (IH y c) by lia. ring.
Qed.

(** A quadratic [θ² s − 2θ d ≥ 0] on [(0, 1]] forces [d ≤ 0]. *)
Lemma small_steps (d s : Q) :
  0 <= s -> (forall θ, 0 < θ -> θ <= 1 -> 0 <= θ * θ * s - 2 * θ * d) -> d <= 0.
Proof.
  intros Hs H. apply Qnot_lt_le. intro Hd.
  destruct (Qlt_le_dec s d) as [Hsd|Hds].
  - specialize (H 1 ltac:(lra) (Qle_refl 1)). lra.
  - (* θ = d / s ∈ (0, 1] *)
    assert (Hs0 : 0 < s) by lra.
    specialize (H (d / s)).
    assert (Hθ : 0 < d / s) by (apply Qlt_shift_div_l; lra).
    assert (Hθ1 : d / s <= 1) by (apply Qle_shift_div_r; lra).
    specialize (H Hθ Hθ1).
    assert (E : d / s * (d / s) * s - 2 * (d / s) * d == - (d * (d / s))).
    { field. lra. }
    rewrite E in H. assert (0 < d * (d / s)) by (apply Qmult_lt_0_compat; lra). lra.
Qed.

(** ** The lemma *)

(** Paper, [lem:proj-characterization]: for every convex [C ⊂ Q^N], every
    [z ∈ Q^N] and [y ∈ C]: [y = P_C(z) ⟺ z − y ∈ N_y C]. Ledger claim:
    [lem:proj-characterization]. *)
Theorem proj_characterization (N : nat) (C : list Q -> Prop) (z y : list Q) :
  Convex N C -> length z = N -> C y ->
  IsProjection C z y <-> InNormalCone C y (vsub z y).
Proof.
  intros (HL & HC) Lz Hy. pose proof (HL y Hy) as Ly. split.
  - intros (_ & Hmin) c Hc. pose proof (HL c Hc) as Lc.
    apply (small_steps _ (sqnorm (vsub c y)) (sqnorm_nonneg _)).
    intros θ H0 H1.
    pose proof (Hmin (lerp θ y c) (HC y c θ Hy Hc ltac:(lra) H1)) as Hm.
    rewrite (sqnorm_lerp z y c θ) in Hm by lia. lra.
  - intros HN. split; [exact Hy|]. intros c Hc. pose proof (HL c Hc) as Lc.
    rewrite (sqnorm_split z y c) by lia. specialize (HN c Hc).
    pose proof (sqnorm_nonneg (vsub c y)). lra.
Qed.

(** ** The monotone cone *)

(** [K̃^N]: the non-decreasing vectors of [Q^N] ([df:tKN]). *)
Definition MonotoneN (N : nat) (w : list Q) : Prop := Monotone w /\ length w = N.

Lemma lerp_length (θ : Q) (a : list Q) : forall b,
  length b = length a -> length (lerp θ a b) = length a.
Proof. induction a as [|x a IH]; intros [|y b] L; simpl in *; try discriminate; auto. Qed.

Lemma nth_lerp (θ : Q) (a : list Q) : forall b i,
  length b = length a -> (i < length a)%nat ->
  nth i (lerp θ a b) 0 == nth i a 0 + θ * (nth i b 0 - nth i a 0).
Proof.
  induction a as [|x a IH]; intros [|y b] i L Hi; simpl in *; try discriminate; [lia|].
  destruct i as [|i]; [reflexivity|]. apply IH; lia.
Qed.

Lemma monotone_convex (N : nat) : Convex N (MonotoneN N).
Proof.
  split; [intros c (_ & L); exact L|].
  intros a b θ (Ma & La) (Mb & Lb) H0 H1. split.
  - intros i Hi. rewrite lerp_length in Hi by lia.
    rewrite !nth_lerp by lia.
    pose proof (Ma i Hi). pose proof (Mb i ltac:(lia)).
    assert (0 <= (1 - θ) * (nth (S i) a 0 - nth i a 0)) by (apply Qmult_le_0_compat; lra).
    assert (0 <= θ * (nth (S i) b 0 - nth i b 0)) by (apply Qmult_le_0_compat; lra).
    lra.
  - rewrite lerp_length; lia.
Qed.

(** The KKT conditions in index form are the projection onto [K̃^N]: for
    every [N], [z ∈ Q^N] and non-decreasing [y ∈ Q^N],
    [Kkt z y ⟺ y = P_{K̃}(z)]. *)
Theorem kkt_iff_projection (z y : list Q) :
  MonotoneN (length z) y -> Kkt z y <-> IsProjection (MonotoneN (length z)) z y.
Proof.
  intros (My & Ly). split.
  - intros Hk. split; [split; assumption|]. intros c (Mc & Lc).
    pose proof (kkt_minimiser z y c Hk Mc Lc).
    pose proof (sqnorm_nonneg (vsub y c)). lra.
  - intros (_ & Hmin).
    pose proof (pava_kkt z) as Hp.
    assert (Lp : length (pava z) = length z) by exact (proj1 Hp).
    pose proof (Hmin (pava z) (conj (proj1 (proj2 Hp)) Lp)) as H1.
    pose proof (kkt_unique_minimiser z (pava z) y Hp My Ly H1) as E.
    apply (kkt_qeq_r z (pava z) y E Hp).
Qed.

(** Corollary of [proj_characterization] for [C = K̃^N]: its normal cone at
    [y] is the index form of the KKT conditions, [z − y ∈ N_y K̃ ⟺ Kkt z y].
    Ledger claim: [lem:proj-characterization]. *)
Corollary kkt_iff_normal_cone (z y : list Q) :
  MonotoneN (length z) y -> Kkt z y <-> InNormalCone (MonotoneN (length z)) y (vsub z y).
Proof.
  intros Hy. rewrite (kkt_iff_projection z y Hy).
  apply (proj_characterization (length z)); [apply monotone_convex|reflexivity|exact Hy].
Qed.
