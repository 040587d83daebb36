(** * The set K, the translated coordinates, and the KKT conditions of
      the projection onto the monotone cone (index form).

    Everything is over [Q]: positions, velocities, radius and times are
    exact rationals, as in the Rust crate. Vectors are lists indexed from 0:
    the paper's [x_i] ([i = 1..N]) is [nth (i-1) x 0].

    Definitions here are imported by the dynamics files (coqdyn's); they are
    only ever added to, never renamed. *)

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
