(** * The normal-cone condition over [R] ([prop:proj-micro], [eq:micro-f0-lagr])

    [ProjMicroSolves.velocity_in_normal_cone] proves
    [⟨u⁰ − u(s), c − x(s)⟩ ≤ 0] for the rational [c ∈ K^N]. Here the same
    condition is read over [R], for every real [c ∈ K^N]
    ([InNormalConeR] of [Uniqueness.v]), from the index-form multipliers of
    [Multipliers.v] alone: [u⁰_i − u_i = N (λ_{i+1} − λ_i)] with
    [λ_0 = λ_N = 0], [λ ≥ 0] and [λ_k (x_k − x_{k−1} − 2r) = 0] give, by
    summation by parts, [⟨u⁰ − u, c − x⟩ = −N Σ_k λ_k (c_k − c_{k−1} − 2r) ≤ 0].
    A step of the transport of the rational solution to real times: the
    condition holds for real competitors [c], at rational times [s] and
    rational data. Over [R]: rests on the standard real-number axioms. *)

From Coq Require Import Reals QArith Qreals Lra Lia List.
From Sticky Require Import Prelude Kkt Dynamics Multipliers Uniqueness.

Open Scope R_scope.

Lemma sumN_by_parts (n : nat) (l y : nat -> R) :
  sumN n (fun i => (l (S i) - l i) * y i) =
  l n * y n - l O * y O - sumN n (fun i => l (S i) * (y (S i) - y i)).
Proof. induction n as [|n IH]; simpl; [ring|rewrite IH; ring]. Qed.

(** Index-form multipliers give the normal cone of [K^N], over [R]. *)
Lemma normal_cone_of_multipliers (N : nat) (r k : R) (x w l : nat -> R) :
  0 <= k -> l O = 0 -> l N = 0 -> (forall j, (j <= N)%nat -> 0 <= l j) ->
  (forall j, (0 < j < N)%nat -> l j * (x j - x (j - 1)%nat - 2 * r) = 0) ->
  (forall i, (i < N)%nat -> w i = k * (l (S i) - l i)) ->
  InNormalConeR N r x w.
Proof.
  intros Hk H0 HN Hpos Hcomp Hw c Hc. unfold dotR.
  set (y := fun i => c i - x i).
  rewrite (sumN_ext N _ (fun i => k * ((l (S i) - l i) * y i)))
    by (intros i Hi; rewrite Hw by exact Hi; unfold y; ring).
  rewrite sumN_scal, sumN_by_parts, H0, HN.
  assert (0 <= sumN N (fun i => l (S i) * (y (S i) - y i))).
  { apply sumN_nonneg. intros i Hi. destruct (Nat.eq_dec (S i) N) as [He|Hne].
    - rewrite He, HN. lra.
    - pose proof (Hcomp (S i) ltac:(lia)) as C. replace (S i - 1)%nat with i in C by lia.
      pose proof (Hc i ltac:(lia)). pose proof (Hpos (S i) ltac:(lia)).
      unfold y. nra. }
  assert (0 <= k * sumN N (fun i => l (S i) * (y (S i) - y i))) by (apply Rmult_le_pos; assumption).
  lra.
Qed.

Lemma Q2R_0 : Q2R 0 = 0.
Proof. unfold Q2R. simpl. field. Qed.

Lemma Q2R_2 : Q2R 2 = 2.
Proof. unfold Q2R. simpl. field. Qed.

(** Paper, [prop:proj-micro] / [eq:micro-f0-lagr]: at every rational
    [s ≥ 0], for rational data [x⁰ ∈ K^N], [u⁰], the path's state read in
    [R] has [u⁰ − u(s) ∈ N_{x(s)} K^N] against every real [c ∈ K^N]
    ([u] the right derivative). Ledger claim: [prop:proj-micro] (part). *)
Theorem velocity_in_normal_cone_R (x0 u0 : list Q) (r s : Q) :
  (0 <= s)%Q -> InK r x0 -> length u0 = length x0 ->
  InNormalConeR (length x0) (Q2R r)
    (fun i => Q2R (nth i (positions (dynamics x0 u0 r s)) 0%Q))
    (fun i => Q2R (nth i u0 0%Q) - Q2R (nth i (velocities (dynamics x0 u0 r s)) 0%Q)).
Proof.
  intros Hs HK Hl.
  apply (normal_cone_of_multipliers (length x0) (Q2R r) (Q2R (qn (length x0))) _ _
           (fun j => Q2R (multiplier x0 u0 r s j))).
  - rewrite <- Q2R_0. apply Qle_Rle. apply qn_nonneg.
  - rewrite <- Q2R_0. apply Qeq_eqR. apply (multiplier_ends x0 u0 r s Hs HK Hl).
  - rewrite <- Q2R_0. apply Qeq_eqR. apply (multiplier_ends x0 u0 r s Hs HK Hl).
  - intros j Hj. rewrite <- Q2R_0. apply Qle_Rle. exact (multiplier_nonneg x0 u0 r s j Hs HK Hl Hj).
  - intros j Hj. pose proof (multiplier_complementarity x0 u0 r s j Hs HK Hl Hj) as C.
    simpl in C. apply Qeq_eqR in C.
    rewrite Q2R_mult, !Q2R_minus, Q2R_mult, Q2R_2, Q2R_0 in C. exact C.
  - intros i Hi. pose proof (dyn_micro_identity x0 u0 r s i Hs HK Hl Hi) as D.
    apply Qeq_eqR in D. rewrite D, Q2R_minus, Q2R_mult, Q2R_minus. ring.
Qed.
