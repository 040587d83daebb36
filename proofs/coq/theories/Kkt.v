(** * The set K, the translated coordinates, and the KKT conditions of
      the projection onto the monotone cone (index form).

    Everything is over [Q]: positions, velocities, radius and times are
    exact rationals, as in the Rust crate. Vectors are lists indexed from 0:
    the paper's [x_i] ([i = 1..N]) is [nth (i-1) x 0]. *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude.
Import ListNotations.
Open Scope Q_scope.

(** ** The admissible set [K^N] ([df:KN])

    Paper, [df:KN]:
    "K^N = {x ∈ R^N ; x_{i+1} − x_i ≥ 2r, i = 1, …, N−1}". *)
Definition InK (r : Q) (x : list Q) : Prop :=
  forall i, (S i < length x)%nat -> 2 * r <= nth (S i) x 0 - nth i x 0.

(** ** Translated coordinates ([df:translat-x])

    Paper, [df:translat-x]:
    "x̃ = (x_1, x_2 − 2r, …, x_N − 2r(N−1))".
    [translate_from k r x] translates a tail whose first entry has index [k]
    (0-based), so [translate r x] is the paper's [x̃]. *)
Fixpoint translate_from (k : nat) (r : Q) (x : list Q) : list Q :=
  match x with
  | [] => []
  | a :: x' => (a - 2 * r * qn k) :: translate_from (S k) r x'
  end.

Definition translate (r : Q) (x : list Q) : list Q := translate_from 0 r x.

(** The inverse translation [x_i = x̃_i + 2r·i] (0-based [i]). *)
Fixpoint untranslate_from (k : nat) (r : Q) (x : list Q) : list Q :=
  match x with
  | [] => []
  | a :: x' => (a + 2 * r * qn k) :: untranslate_from (S k) r x'
  end.

Definition untranslate (r : Q) (x : list Q) : list Q := untranslate_from 0 r x.

(** ** The monotone cone [K̃^N] ([df:tKN])

    Paper, [df:tKN]: "K̃^N = {x̃ ∈ R^N ; x̃_{i+1} − x̃_i ≥ 0}, i.e. K̃^N is the
    cone of monotone (non-decreasing) vectors". *)
Definition Monotone (y : list Q) : Prop :=
  forall i, (S i < length y)%nat -> nth i y 0 <= nth (S i) y 0.

(** ** The KKT conditions of [y = P_{K̃}(z)], index form

    Paper, [lem:proj-characterization]: "Let C ⊂ R^N be a closed convex set.
    Then, for every z ∈ R^N and y ∈ C, y = P_C(z) ⟺ z − y ∈ ∂I_C(y) = N_y C."
    and Appendix A ([app:KKT]), corrected as in the ledger: the multipliers of
    the position projection [min ½‖x − (x⁰ + t u⁰)‖²] over [K^N] are
    [μ_i = (1/N) Σ_{j ≤ i} (z_j − y_j)], i.e. [μ = ∫ λ], not [λ].

    For the cone of non-decreasing vectors the normal-cone condition reads,
    with the partial sums [D_k = Σ_{j<k} (z_j − y_j)] (0-based, [k] entries):
    - [y] is non-decreasing;
    - [D_k ≥ 0] for every [k] (the multipliers are non-negative);
    - [D_N = 0];
    - [D_{k+1} = 0] wherever [y_k < y_{k+1}] (complementarity: a multiplier
      vanishes where the constraint is not active). *)
Definition Kkt (z y : list Q) : Prop :=
  length y = length z /\
  Monotone y /\
  (forall k, (k <= length z)%nat -> 0 <= psum k z - psum k y) /\
  psum (length z) z == psum (length z) y /\
  (forall k, (S k < length z)%nat ->
     nth k y 0 < nth (S k) y 0 -> psum (S k) z == psum (S k) y).

(** The same conditions read left to right along the lists, the form the
    proofs run on: [kkt_from c yp z y] holds on a tail [z, y] after a prefix
    whose [z − y] sums to [c] and whose last [y] entry is [yp]. *)
Fixpoint kkt_from (c yp : Q) (z y : list Q) : Prop :=
  match z, y with
  | [], [] => c == 0
  | zi :: z', yi :: y' =>
      0 <= c /\ yp <= yi /\ (yp < yi -> c == 0) /\
      kkt_from (c + (zi - yi)) yi z' y'
  | _, _ => False
  end.

(** The recursive form of [Kkt]: the empty prefix has sum 0, and the
    predecessor of the first entry is taken to be the entry itself. *)
Definition kkt_rec (z y : list Q) : Prop :=
  match y with
  | [] => z = []
  | y1 :: _ => kkt_from 0 y1 z y
  end.

(** ** The two forms agree *)

Lemma kkt_from_qeq (z : list Q) : forall y c c' yp,
  c == c' -> kkt_from c yp z y -> kkt_from c' yp z y.
Proof.
  induction z as [|zi z IH]; intros y c c' yp Hc H; destruct y as [|yi y];
    simpl in *; try contradiction.
  - lra.
  - destruct H as (H1 & H2 & H3 & H4). split; [lra|split; [exact H2|split]].
    + intro Hl. specialize (H3 Hl). lra.
    + apply (IH y (c + (zi - yi))); [lra|exact H4].
Qed.

(** The index form of [kkt_from]: [yp :: y] lists the predecessors. *)
Definition IdxFrom (c yp : Q) (z y : list Q) : Prop :=
  length y = length z /\
  (forall k, (k < length z)%nat -> nth k (yp :: y) 0 <= nth k y 0) /\
  (forall k, (k <= length z)%nat -> 0 <= c + psum k z - psum k y) /\
  c + psum (length z) z - psum (length z) y == 0 /\
  (forall k, (k < length z)%nat ->
     nth k (yp :: y) 0 < nth k y 0 -> c + psum k z - psum k y == 0).

Lemma kkt_from_idx (z : list Q) : forall c yp y, kkt_from c yp z y -> IdxFrom c yp z y.
Proof.
  induction z as [|zi z IH]; intros c yp y H; destruct y as [|yi y];
    simpl in H; try contradiction.
  - repeat split.
    + intros k Hk. simpl in Hk. lia.
    + intros k Hk. simpl in Hk. replace k with 0%nat by lia. unfold psum. simpl. lra.
    + unfold psum. simpl. lra.
    + intros k Hk. simpl in Hk. lia.
  - destruct H as (H0 & H1 & H2 & H3).
    destruct (IH _ _ _ H3) as (L & M & P & T & C).
    split; [|split; [|split; [|split]]].
    + simpl. f_equal. exact L.
    + intros [|k] Hk; simpl in Hk |- *; [exact H1|]. apply M. lia.
    + intros [|k] Hk; simpl in Hk.
      * unfold psum. simpl. lra.
      * rewrite !psum_cons. specialize (P k ltac:(lia)). lra.
    + simpl length. rewrite !psum_cons. lra.
    + intros [|k] Hk; simpl in Hk |- *.
      * intro Hl. specialize (H2 Hl). unfold psum. simpl. lra.
      * intro Hl. rewrite !psum_cons. specialize (C k ltac:(lia) Hl). lra.
Qed.

Lemma idx_kkt_from (z : list Q) : forall c yp y, IdxFrom c yp z y -> kkt_from c yp z y.
Proof.
  induction z as [|zi z IH]; intros c yp y (L & M & P & T & C);
    destruct y as [|yi y]; simpl in L |- *; try discriminate.
  - unfold psum in T. simpl in T. lra.
  - split; [|split; [|split]].
    + specialize (P 0%nat ltac:(lia)). unfold psum in P. simpl in P. lra.
    + apply (M 0%nat). simpl. lia.
    + intro Hl. specialize (C 0%nat ltac:(simpl; lia) Hl). unfold psum in C. simpl in C. lra.
    + apply IH. split; [|split; [|split; [|split]]].
      * lia.
      * intros k Hk. apply (M (S k)). simpl. lia.
      * intros k Hk. specialize (P (S k) ltac:(simpl; lia)). rewrite !psum_cons in P. lra.
      * simpl length in T. rewrite !psum_cons in T. lra.
      * intros k Hk Hl. specialize (C (S k) ltac:(simpl; lia) Hl).
        rewrite !psum_cons in C. lra.
Qed.

Lemma kkt_idx_head (z y : list Q) (y1 : Q) :
  Kkt z (y1 :: y) <-> IdxFrom 0 y1 z (y1 :: y).
Proof.
  split.
  - intros (L & M & P & T & C). split; [exact L|split; [|split; [|split]]].
    + intros [|k] Hk; simpl; [apply Qle_refl|]. apply (M k). rewrite L. exact Hk.
    + intros k Hk. specialize (P k Hk). lra.
    + lra.
    + intros [|k] Hk Hl; simpl in Hl.
      * exfalso. apply (Qlt_irrefl _ Hl).
      * rewrite (C k Hk Hl). lra.
  - intros (L & M & P & T & C). split; [exact L|split; [|split; [|split]]].
    + intros i Hi. apply (M (S i)). rewrite <- L. exact Hi.
    + intros k Hk. specialize (P k Hk). lra.
    + lra.
    + intros k Hk Hl. specialize (C (S k) Hk Hl). lra.
Qed.

(** The index form [Kkt] and the left-to-right form [kkt_rec] are the same
    conditions. *)
Theorem kkt_rec_iff (z y : list Q) : kkt_rec z y <-> Kkt z y.
Proof.
  destruct y as [|y1 y]; simpl.
  - split.
    + intros ->. split; [reflexivity|split; [|split; [|split]]].
      * intros i Hi. simpl in Hi. lia.
      * intros k Hk. simpl in Hk. replace k with 0%nat by lia. unfold psum. simpl. lra.
      * unfold psum. simpl. lra.
      * intros k Hk. simpl in Hk. lia.
    + intros (L & _). destruct z; [reflexivity|discriminate].
  - rewrite kkt_idx_head. split; [apply kkt_from_idx|apply idx_kkt_from].
Qed.
