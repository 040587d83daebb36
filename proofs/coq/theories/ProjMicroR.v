(** * [prop:proj-micro] over [R]: existence, uniqueness, projection
      formula, Lipschitz bound.

    Paper, [prop:proj-micro]: "Let x_0 ∈ K^N and u_0 ∈ C^N_{x_0}. Then
    there exists a unique solution x to (eq:micro-f0-lagr). It is given by
    the projection formula x(t) = P_{K^N}(x_0 + t u_0), t ≥ 0 [...]
    Moreover x is Lipschitz continuous".

    [proj_micro] states that sentence over Coq's real numbers, for every
    [N], every radius [r], every real [x⁰ ∈ K^N] and every real [u⁰]
    ([u⁰ ∈ C_{x⁰}] is not needed): a path [x] exists that
    - is a solution of [eq:micro-f0-lagr] on every [[0, T]] in the class of
      absolutely continuous solutions ([UniquenessAC.SolutionAC]);
    - is the only one: every solution of that class with the same data
      equals it on [[0, T]] ([UniquenessAC.solution_unique_ac]);
    - is, at every [t ≥ 0], the Euclidean projection of [x⁰ + t u⁰] onto
      [K^N]: the unique minimiser of the distance ([IsProjectionK]);
    - has [‖x(t) − x(s)‖² ≤ (t − s)² ‖u⁰‖²];
    - off finitely many instants [t > 0] (its collisions), is
      differentiable with [u⁰ − ẋ(t) ∈ N_{x(t)} K^N].
    The path is the sticky dynamics of [DynamicsR.v]; the projection
    property gives the Lipschitz bound (the projection onto a convex set
    does not expand distances), hence absolute continuity
    ([AbsCont_lipschitz]); the dynamics is differentiable off its finitely
    many collision instants, a null set ([NullSet_finite]).

    Over Coq's real numbers: rests on the standard real-number axioms only
    ([check-assumptions.sh]). *)

From Coq Require Import Reals Lra Lia List.
From Coquelicot Require Import Coquelicot.
From Sticky Require Import Uniqueness UniquenessAC DynamicsR.
Open Scope R_scope.

(** ** The projection onto [K^N] *)

(** The squared Euclidean distance of [R^N]. *)
Definition sqdistR (N : nat) (a b : nat -> R) : R := sumN N (fun i => (a i - b i) * (a i - b i)).

(** [q = P_{K^N}(z)]: [q ∈ K^N] is at least as close to [z] as every point
    of [K^N], and every point of [K^N] as close as [q] is [q]. *)
Definition IsProjectionK (N : nat) (r : R) (z q : nat -> R) : Prop :=
  InKR N r q /\
  (forall c, InKR N r c -> sqdistR N z q <= sqdistR N z c) /\
  (forall c, InKR N r c -> sqdistR N z c <= sqdistR N z q -> forall i, (i < N)%nat -> c i = q i).

(** [lem:proj-characterization], the direction used: [z − q ∈ N_q K^N]
    makes [q] the projection. [‖z − c‖² = ‖z − q‖² + ‖q − c‖²
    − 2⟨z − q, c − q⟩ ≥ ‖z − q‖² + ‖q − c‖²]. *)
Lemma normal_cone_projection (N : nat) (r : R) (z q : nat -> R) :
  InKR N r q -> InNormalConeR N r q (fun i => z i - q i) -> IsProjectionK N r z q.
Proof.
  intros HK Hn.
  assert (Hc : forall c, InKR N r c -> sqdistR N z q + sqdistR N q c <= sqdistR N z c).
  { intros c Hc. pose proof (Hn c Hc) as D. unfold dotR in D. unfold sqdistR.
    assert (E : sumN N (fun i => (z i - c i) * (z i - c i)) =
                sumN N (fun i => (z i - q i) * (z i - q i)) + sumN N (fun i => (q i - c i) * (q i - c i))
                - 2 * sumN N (fun i => (z i - q i) * (c i - q i))).
    { rewrite <- sumN_scal, <- sumN_plus, <- sumN_minus. apply sumN_ext. intros; ring. }
    lra. }
  split; [exact HK|split].
  - intros c Hc'. pose proof (Hc c Hc').
    assert (0 <= sqdistR N q c) by (apply sumN_nonneg; intros; apply Rle_0_sqr). lra.
  - intros c Hc' Hle i Hi. pose proof (Hc c Hc') as H.
    assert (Z : forall j, (j < N)%nat -> (q j - c j) * (q j - c j) = 0).
    { apply sumN_zero; [intros; apply Rle_0_sqr|]. unfold sqdistR in *. lra. }
    specialize (Z i Hi). apply Rmult_integral in Z. destruct Z; lra.
Qed.

(** The projection does not expand distances:
    [‖q₁ − q₂‖² ≤ ‖z₁ − z₂‖²] when [z_k − q_k ∈ N_{q_k} K^N]. *)
Lemma projection_nonexpansive (N : nat) (r : R) (z1 z2 q1 q2 : nat -> R) :
  InKR N r q1 -> InNormalConeR N r q1 (fun i => z1 i - q1 i) ->
  InKR N r q2 -> InNormalConeR N r q2 (fun i => z2 i - q2 i) ->
  sqdistR N q1 q2 <= sqdistR N z1 z2.
Proof.
  intros K1 N1 K2 N2. pose proof (N1 q2 K2) as D1. pose proof (N2 q1 K1) as D2.
  unfold dotR in D1, D2. unfold sqdistR.
  (* With [a = q₁ − q₂], [b = z₁ − z₂]: [Σ a² − ab ≤ 0] and [Σ (a − b)² ≥ 0]. *)
  assert (H1 : sumN N (fun i => (q1 i - q2 i) * (q1 i - q2 i) - (q1 i - q2 i) * (z1 i - z2 i)) <= 0).
  { rewrite (sumN_ext N _ (fun i => (z1 i - q1 i) * (q2 i - q1 i) + (z2 i - q2 i) * (q1 i - q2 i)))
      by (intros; ring).
    rewrite sumN_plus. lra. }
  assert (H2 : 0 <= sumN N (fun i => ((q1 i - q2 i) - (z1 i - z2 i)) * ((q1 i - q2 i) - (z1 i - z2 i))))
    by (apply sumN_nonneg; intros; apply Rle_0_sqr).
  assert (E : sumN N (fun i => (z1 i - z2 i) * (z1 i - z2 i)) - sumN N (fun i => (q1 i - q2 i) * (q1 i - q2 i)) =
              sumN N (fun i => ((q1 i - q2 i) - (z1 i - z2 i)) * ((q1 i - q2 i) - (z1 i - z2 i))) -
              2 * sumN N (fun i => (q1 i - q2 i) * (q1 i - q2 i) - (q1 i - q2 i) * (z1 i - z2 i))).
  { rewrite <- sumN_scal, <- !sumN_minus. apply sumN_ext. intros; ring. }
  lra.
Qed.

(** One term of a sum of nonnegative terms is at most the sum. *)
Lemma sumN_term (n i : nat) (f : nat -> R) :
  (forall j, (j < n)%nat -> 0 <= f j) -> (i < n)%nat -> f i <= sumN n f.
Proof.
  induction n as [|n IH]; intros H Hi; [lia|]. simpl.
  pose proof (H n ltac:(lia)).
  destruct (Nat.eq_dec i n) as [->|Hne].
  - pose proof (sumN_nonneg n f (fun j Hj => H j ltac:(lia))). lra.
  - pose proof (IH (fun j Hj => H j ltac:(lia)) ltac:(lia)). lra.
Qed.

(** ** The theorem *)

(** Paper, [prop:proj-micro]: "Let x_0 ∈ K^N and u_0 ∈ C^N_{x_0}. Then
    there exists a unique solution x to (eq:micro-f0-lagr). It is given by
    the projection formula x(t) = P_{K^N}(x_0 + t u_0), t ≥ 0, [...]
    Moreover x is Lipschitz continuous" — over [R], for every [N], [r],
    real [x⁰ ∈ K^N] and real [u⁰] (no [u⁰ ∈ C_{x⁰}] needed), solutions in
    the class of absolutely continuous paths ([SolutionAC]) on every
    [[0, T]]; the inclusion holds at every [t > 0] but finitely many.
    Ledger claim: [prop:proj-micro]. *)
Theorem proj_micro (N : nat) (r : R) (x0 u0 : nat -> R) :
  InKR N r x0 ->
  exists x : R -> nat -> R,
    (forall T, SolutionAC N r T x0 u0 x) /\
    (forall T y, SolutionAC N r T x0 u0 y ->
       forall t, 0 <= t <= T -> forall i, (i < N)%nat -> y t i = x t i) /\
    (forall t, 0 <= t -> IsProjectionK N r (fun i => x0 i + t * u0 i) (x t)) /\
    (forall s t, 0 <= s -> 0 <= t ->
       sqdistR N (x t) (x s) <= (t - s) * (t - s) * sumN N (fun i => u0 i * u0 i)) /\
    (exists (E : list R) (v : R -> nat -> R), forall t, 0 < t -> ~ In t E ->
       (forall i, (i < N)%nat -> is_derive (fun s => x s i) t (v t i)) /\
       InNormalConeR N r (x t) (fun i => u0 i - v t i)).
Proof.
  intro HK.
  destruct (evolves N r x0 u0 _ (fun _ => false) 0 x0 u0 eq_refl (inv_start N r x0 u0 HK))
    as (x & Hx0 & Hproj & E & V & Hd).
  assert (Hlip : forall s t, 0 <= s -> 0 <= t ->
            sqdistR N (x t) (x s) <= (t - s) * (t - s) * sumN N (fun i => u0 i * u0 i)).
  { intros s t Hs Ht. destruct (Hproj t Ht) as [Kt Nt]. destruct (Hproj s Hs) as [Ks Ns].
    eapply Rle_trans; [exact (projection_nonexpansive N r _ _ _ _ Kt Nt Ks Ns)|].
    unfold sqdistR, flight. rewrite <- sumN_scal. apply Req_le, sumN_ext. intros; ring. }
  assert (Hsol : forall T, SolutionAC N r T x0 u0 x).
  { intro T. split; [intros i _; apply Hx0|split; [|split]].
    - intros t Ht. apply Hproj. lra.
    - intros i Hi. set (Su := sumN N (fun i => u0 i * u0 i)).
      assert (HS : 0 <= Su) by (apply sumN_nonneg; intros; apply Rle_0_sqr).
      apply (AbsCont_lipschitz 0 T (sqrt Su)); [apply sqrt_pos|].
      intros s t Hs Hst HtT.
      assert (Hsq : (x t i - x s i) * (x t i - x s i) <= ((t - s) * sqrt Su) * ((t - s) * sqrt Su)).
      { replace ((t - s) * sqrt Su * ((t - s) * sqrt Su)) with ((t - s) * (t - s) * (sqrt Su * sqrt Su)) by ring.
        rewrite sqrt_sqrt by exact HS.
        eapply Rle_trans; [|exact (Hlip s t Hs ltac:(lra))].
        apply (sumN_term N i (fun i => (x t i - x s i) * (x t i - x s i))); [intros; apply Rle_0_sqr|exact Hi]. }
      pose proof (Rsqr_le_abs_0 _ _ Hsq) as A.
      rewrite (Rabs_right ((t - s) * sqrt Su)) in A; [rewrite Rmult_comm; exact A|].
      apply Rle_ge, Rmult_le_pos; [lra|apply sqrt_pos].
    - exists (fun t => In t E), V. split; [apply NullSet_finite|].
      intros t Ht Hn. apply Hd; [lra|exact Hn]. }
  exists x. split; [exact Hsol|split; [|split; [|split; [exact Hlip|exists E, V; exact Hd]]]].
  - intros T y Hy t Ht i Hi. exact (solution_unique_ac N r T x0 u0 y x Hy (Hsol T) t Ht i Hi).
  - intros t Ht. destruct (Hproj t Ht) as [Kt Nt]. apply normal_cone_projection; [exact Kt|].
    exact Nt.
Qed.
