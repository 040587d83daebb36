(** * Section 3 at fixed [N]: the interpolations and their [L^∞] bounds
      ([eq:bound-UN-Linf], [eq:sup-micro-u-L], [eq:diffLambda_N],
      [eq:Oleinik-tUN]).

    Paper, [ssec:interpol1]: on the cell [w ∈ ((i−1)/N, i/N]] the piecewise
    constant interpolations take the values [x_i, u_i, λ_i] ([df:XN],
    [df:UN], [df:LN]) and the piecewise affine ones are
    [Ṽ_N(t,w) = N(v_i − v_{i−1})(w − (i−1)/N) + v_{i−1}], with the
    artificial particle [x_0 = x_1 − 1/N − δ] ([df:x0]) and [λ_0 = 0].
    The paper leaves [u_0] implicit; the artificial particle moves with
    particle 1 ([∂_t x_0 = ∂_t x_1]), so [u_0 = u_1].

    Everything at fixed [t] is a function of the cell index [i = 1..N]
    and of [w]; a bound for every [i] and every [w] of the cell is the
    [L^∞((0,1))] bound, and for every rational [t ∈ [0, T]] the
    [L^∞((0,T)×(0,1))] bound (the state is affine in [t] between
    collisions and the collision instants of rational data are rational). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List Qabs.
From Sticky Require Import Prelude Kkt Pava Projection SupNorm Dynamics ClusterAlgebra
  DynamicsInvariant DynamicsProjection Multipliers DynamicsIsProjK Oleinik.
Import ListNotations.
Open Scope Q_scope.

(** ** The interpolations *)

(** A sequence [v_0, …, v_N] read by index (the paper's 1-based particles,
    index 0 for the artificial particle or [λ_0]). *)
Definition seqQ := nat -> Q.

(** The paper's [x_i] ([i = 0..N]): [x_0 = x_1 − 1/N − δ] ([df:x0]),
    [x_i] the [i]-th particle for [i ≥ 1]. *)
Definition xs (δ : Q) (x : list Q) : seqQ :=
  fun i => match i with
           | O => nth 0 x 0 - 1 / qn (length x) - δ
           | S j => nth j x 0
           end.

(** The paper's [u_i] ([i = 0..N]), [u_0 = u_1]. *)
Definition us (u : list Q) : seqQ :=
  fun i => match i with
           | O => nth 0 u 0
           | S j => nth j u 0
           end.

(** The paper's [λ_i(t)], [i = 0..N] ([eq:dyn-micro]). *)
Definition lambdas (x0 u0 : list Q) (r t : Q) : seqQ := multiplier x0 u0 r t.

(** [w] lies in the closed cell [[(i−1)/N, i/N]]. *)
Definition InCell (N i : nat) (w : Q) : Prop :=
  (1 <= i <= N)%nat /\ qn (i - 1) / qn N <= w /\ w <= qn i / qn N.

(** The piecewise constant interpolation ([df:XN], [df:UN], [df:LN]):
    [V_N(w) = v_i] on the cell [i]. *)
Definition pconst (v : seqQ) (i : nat) : Q := v i.

(** The piecewise affine interpolation on the cell [i]:
    [Ṽ_N(w) = N(v_i − v_{i−1})(w − (i−1)/N) + v_{i−1}]. *)
Definition paffine (v : seqQ) (N i : nat) (w : Q) : Q :=
  qn N * (v i - v (i - 1)%nat) * (w - qn (i - 1) / qn N) + v (i - 1)%nat.

(** Its slope [∂_w Ṽ_N = N(v_i − v_{i−1})] on the cell [i]. *)
Definition pslope (v : seqQ) (N i : nat) : Q := qn N * (v i - v (i - 1)%nat).

(** ** Elementary facts *)

(** [sup_i |v_i| ≤ M]. *)
Definition SupBound (M : Q) (v : list Q) : Prop := Forall (fun a => Qabs a <= M) v.

(** The local coordinate [θ = N(w − (i−1)/N)] of a cell lies in [[0, 1]]. *)
Lemma cell_theta (N i : nat) (w : Q) :
  InCell N i w -> 0 <= qn N * (w - qn (i - 1) / qn N) <= 1.
Proof.
  intros (Hi & H1 & H2).
  assert (HN : 0 < qn N) by (apply qn_pos; lia).
  assert (Hq : qn i == qn (i - 1) + 1)
    by (rewrite <- qn_S; replace (S (i - 1)) with i by lia; reflexivity).
  assert (E : qn N * (w - qn (i - 1) / qn N) == qn N * w - qn (i - 1)) by (field; lra).
  rewrite E. split.
  - apply (Qmult_le_compat_r _ _ (qn N)) in H1; [|lra].
    setoid_replace (qn (i - 1) / qn N * qn N) with (qn (i - 1)) in H1 by (field; lra).
    lra.
  - apply (Qmult_le_compat_r _ _ (qn N)) in H2; [|lra].
    setoid_replace (qn i / qn N * qn N) with (qn i) in H2 by (field; lra).
    lra.
Qed.

(** The affine interpolation is the convex combination
    [(1 − θ) v_{i−1} + θ v_i]. *)
Lemma paffine_theta (v : seqQ) (N i : nat) (w : Q) :
  paffine v N i w == v (i - 1)%nat + qn N * (w - qn (i - 1) / qn N) * (v i - v (i - 1)%nat).
Proof. unfold paffine. ring. Qed.

Lemma convex_abs (a b θ M : Q) :
  0 <= θ <= 1 -> Qabs a <= M -> Qabs b <= M -> Qabs (a + θ * (b - a)) <= M.
Proof.
  intros Hθ Ha Hb. apply Qabs_Qle_condition in Ha, Hb. apply Qabs_Qle_condition. nra.
Qed.

(** On every cell, [|Ṽ_N| ≤ max(|v_{i−1}|, |v_i|)]: a bound on the nodes
    bounds the affine interpolation. *)
Lemma paffine_abs (v : seqQ) (N i : nat) (w M : Q) :
  InCell N i w -> Qabs (v (i - 1)%nat) <= M -> Qabs (v i) <= M ->
  Qabs (paffine v N i w) <= M.
Proof.
  intros Hw Ha Hb. rewrite paffine_theta. apply convex_abs; auto. apply (cell_theta N i w Hw).
Qed.

Lemma forall_nth (P : Q -> Prop) (v : list Q) (i : nat) :
  Forall P v -> (i < length v)%nat -> P (nth i v 0).
Proof. intros H Hi. rewrite Forall_forall in H. apply H, nth_In, Hi. Qed.

Lemma supbound_nonneg (M : Q) (v : list Q) : SupBound M v -> v <> [] -> 0 <= M.
Proof.
  intros H Hv. destruct v as [|a v]; [contradiction|]. inversion H; subst.
  pose proof (Qabs_nonneg a). lra.
Qed.

Lemma qsum_bound (M : Q) (v : list Q) :
  SupBound M v -> - (qn (length v) * M) <= qsum v /\ qsum v <= qn (length v) * M.
Proof.
  induction 1 as [|a v Ha _ IH]; simpl.
  - rewrite qn_0. lra.
  - rewrite qn_S. apply Qabs_Qle_condition in Ha.
    setoid_replace ((qn (length v) + 1) * M) with (qn (length v) * M + M) by ring. lra.
Qed.

Lemma forall_firstn (P : Q -> Prop) (k : nat) (v : list Q) :
  Forall P v -> Forall P (firstn k v).
Proof.
  revert v. induction k as [|k IH]; intros v H; [constructor|].
  destruct v as [|a v]; [constructor|]. inversion H; subst. simpl. constructor; auto.
Qed.

Lemma psum_bound (M : Q) (v : list Q) (k : nat) :
  SupBound M v -> (k <= length v)%nat ->
  - (qn k * M) <= psum k v /\ psum k v <= qn k * M.
Proof.
  intros H Hk. unfold psum.
  pose proof (qsum_bound M (firstn k v) (forall_firstn _ k v H)) as B.
  rewrite firstn_length_le in B by exact Hk. exact B.
Qed.

(** ** [eq:bound-UN-Linf]: the velocities are cluster means *)

Lemma cluster_velocity_abs (M : Q) (c : cluster) :
  Nonempty c -> SupBound M (map snd c) -> Qabs (velocity c) <= M.
Proof.
  intros Hc HB. pose proof (size_pos c Hc) as Hs.
  destruct (qsum_bound M _ HB) as [H1 H2]. rewrite map_length in H1, H2.
  unfold velocity. fold (size c) in *.
  apply Qabs_Qle_condition. split.
  - apply Qle_shift_div_l; [exact Hs|]. unfold size in *. lra.
  - apply Qle_shift_div_r; [exact Hs|]. unfold size in *. lra.
Qed.

Lemma spread_velocity_abs (M : Q) (cs : list cluster) :
  Forall Nonempty cs -> SupBound M (map snd (concat cs)) -> SupBound M (spread velocity cs).
Proof.
  induction cs as [|c cs IH]; intros HN HB; [constructor|].
  inversion HN; subst. simpl in HB. rewrite map_app in HB.
  apply Forall_app in HB as [Hc Hr].
  unfold spread. simpl. apply Forall_app. split.
  - apply Forall_forall. intros a Ha. apply repeat_spec in Ha. subst.
    apply cluster_velocity_abs; assumption.
  - apply IH; assumption.
Qed.

Lemma velocities_length (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  length (velocities (dynamics x0 u0 r t)) = length x0.
Proof.
  intros Ht HK L. rewrite velocities_spread, spread_length.
  apply (clusters_facts x0 u0 r t Ht HK L).
Qed.

(** Paper, [eq:bound-UN-Linf] (the maximum principle on the velocities):
    [sup_i |u_i(t)| ≤ sup_i |u⁰_i|] for every [N], [x⁰ ∈ K^N], any [u⁰],
    rational [t ≥ 0]: [u(t)] is made of cluster means of [u⁰].
    Ledger claims: [eq:bound-UN-Linf], [eq:sup-micro-u-L#velocity-and-increments]. *)
Theorem bound_UN_Linf (x0 u0 : list Q) (r t M : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 ->
  SupBound M (velocities (dynamics x0 u0 r t)).
Proof.
  intros Ht HK L HB. destruct (clusters_facts x0 u0 r t Ht HK L) as ((HN & _) & Hu & _).
  rewrite velocities_spread. apply spread_velocity_abs; [exact HN|]. rewrite Hu. exact HB.
Qed.

(** Paper, [eq:bound-UN-Linf]: "‖U_N‖_{L^∞((0,T)×(0,1))} +
    ‖Ũ_N‖_{L^∞((0,T)×(0,1))} ≤ C" with [C = 2 sup_i |u⁰_i| ≤ 2C'_0]: on
    every cell [i = 1..N] and every [w] of it, [|U_N(t,w)| + |Ũ_N(t,w)|
    ≤ 2M] when [sup_i |u⁰_i| ≤ M], for every [N ≥ 1], [x⁰ ∈ K^N], rational
    [t ≥ 0]. Ledger claim: [eq:bound-UN-Linf]. *)
Theorem bound_UN_tUN_Linf (x0 u0 : list Q) (r t M : Q) (i : nat) (w : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 ->
  InCell (length x0) i w ->
  let u := us (velocities (dynamics x0 u0 r t)) in
  Qabs (pconst u i) + Qabs (paffine u (length x0) i w) <= 2 * M.
Proof.
  intros Ht HK L HB Hw u.
  pose proof (bound_UN_Linf x0 u0 r t M Ht HK L HB) as Hv.
  pose proof (velocities_length x0 u0 r t Ht HK L) as Lv.
  destruct Hw as (Hi & Hw1 & Hw2).
  assert (Hn : forall j, (j <= length x0)%nat -> Qabs (u j) <= M).
  { intros [|j] Hj; unfold u, us; apply forall_nth; auto; lia. }
  assert (A : Qabs (pconst u i) <= M) by (apply Hn; lia).
  assert (B : Qabs (paffine u (length x0) i w) <= M)
    by (apply paffine_abs; [split; auto|apply Hn; lia|apply Hn; lia]).
  lra.
Qed.

(** ** [eq:sup-micro-u-L]: the multipliers and their increments *)

(** [N(λ_i − λ_{i−1}) = u⁰_i − u_i(t)] (1-based [i = 1..N]). *)
Lemma multiplier_increment (x0 u0 : list Q) (r t : Q) (i : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> (1 <= i <= length x0)%nat ->
  qn (length x0) * (lambdas x0 u0 r t i - lambdas x0 u0 r t (i - 1)%nat) ==
  nth (i - 1) u0 0 - nth (i - 1) (velocities (dynamics x0 u0 r t)) 0.
Proof.
  intros Ht HK L Hi. unfold lambdas.
  pose proof (dyn_micro_identity x0 u0 r t (i - 1) Ht HK L ltac:(lia)) as H.
  replace (S (i - 1)) with i in H by lia. lra.
Qed.

(** Paper, [eq:sup-micro-u-L] (the increments): "sup_i |N(λ_i(t) −
    λ_{i−1}(t))| ≤ C'" with [C' = 2 sup_i |u⁰_i|], and hence
    [|λ_i − λ_{i−1}| ≤ 2 sup_i |u⁰_i| / N]. Every [N], [x⁰ ∈ K^N],
    rational [t ≥ 0], [i = 1..N].
    Ledger claim: [eq:sup-micro-u-L#velocity-and-increments]. *)
Theorem multiplier_increment_bound (x0 u0 : list Q) (r t M : Q) (i : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 ->
  (1 <= i <= length x0)%nat ->
  Qabs (qn (length x0) * (lambdas x0 u0 r t i - lambdas x0 u0 r t (i - 1)%nat)) <= 2 * M /\
  Qabs (lambdas x0 u0 r t i - lambdas x0 u0 r t (i - 1)%nat) <= 2 * M / qn (length x0).
Proof.
  intros Ht HK L HB Hi.
  assert (HN : 0 < qn (length x0)) by (apply qn_pos; lia).
  pose proof (bound_UN_Linf x0 u0 r t M Ht HK L HB) as Hv.
  pose proof (velocities_length x0 u0 r t Ht HK L) as Lv.
  pose proof (forall_nth _ _ (i - 1) HB ltac:(lia)) as A.
  pose proof (forall_nth _ _ (i - 1) Hv ltac:(lia)) as B. cbv beta in A, B.
  rewrite (multiplier_increment x0 u0 r t i Ht HK L Hi).
  assert (C : Qabs (nth (i - 1) u0 0 - nth (i - 1) (velocities (dynamics x0 u0 r t)) 0) <= 2 * M).
  { apply Qabs_Qle_condition in A, B. apply Qabs_Qle_condition. lra. }
  split; [exact C|].
  set (d := lambdas x0 u0 r t i - lambdas x0 u0 r t (i - 1)%nat).
  assert (E : Qabs d == Qabs (qn (length x0) * d) / qn (length x0)).
  { rewrite Qabs_Qmult, (Qabs_pos (qn (length x0))) by lra. field. lra. }
  rewrite E. unfold d. rewrite (multiplier_increment x0 u0 r t i Ht HK L Hi).
  apply Qmult_le_compat_r; [exact C|]. apply Qlt_le_weak, Qinv_lt_0_compat, HN.
Qed.

(** The corrected [eq:sup-micro-u-L] (ledger): [0 ≤ λ_k(t) ≤ 2 sup_i |u⁰_i|]
    for [k = 0..N] — the printed [N|λ_k|] is refuted in [S3Refute.v].
    Every [N ≥ 1], [x⁰ ∈ K^N], rational [t ≥ 0].
    Ledger claim: [eq:sup-micro-u-L#N-lambda] (corrected). *)
Theorem multiplier_sup_bound (x0 u0 : list Q) (r t M : Q) (k : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 ->
  (1 <= length x0)%nat -> (k <= length x0)%nat ->
  0 <= lambdas x0 u0 r t k /\ lambdas x0 u0 r t k <= 2 * M.
Proof.
  intros Ht HK L HB HN1 Hk.
  assert (HN : 0 < qn (length x0)) by (apply qn_pos; lia).
  pose proof (bound_UN_Linf x0 u0 r t M Ht HK L HB) as Hv.
  pose proof (velocities_length x0 u0 r t Ht HK L) as Lv.
  assert (HM : 0 <= M) by (apply (supbound_nonneg M u0 HB); destruct u0; simpl in L; [lia|discriminate]).
  split; [apply multiplier_nonneg; assumption|].
  destruct (psum_bound M u0 k HB ltac:(lia)) as [_ A].
  destruct (psum_bound M _ k Hv ltac:(lia)) as [B _].
  assert (Hk' : qn k <= qn (length x0)) by (apply qn_le; exact Hk).
  unfold lambdas, multiplier. apply Qle_shift_div_r; [exact HN|].
  assert (qn k * M <= qn (length x0) * M) by (apply Qmult_le_compat_r; assumption).
  lra.
Qed.

(** Paper, [prop:Linf-micro] (the multipliers): "‖Λ_N‖_{L^∞((0,T)×(0,1))} +
    ‖Λ̃_N‖_{L^∞((0,T)×(0,1))} ≤ C'" with [C' = 4 sup_i |u⁰_i| ≤ 4C'_0]:
    on every cell and every [w] of it, for every [N ≥ 1], [x⁰ ∈ K^N],
    rational [t ≥ 0]. Ledger claim: [prop:Linf-micro]. *)
Theorem Lambda_Linf (x0 u0 : list Q) (r t M : Q) (i : nat) (w : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 ->
  InCell (length x0) i w ->
  let l := lambdas x0 u0 r t in
  Qabs (pconst l i) + Qabs (paffine l (length x0) i w) <= 4 * M.
Proof.
  intros Ht HK L HB Hw l. destruct Hw as (Hi & Hw1 & Hw2).
  assert (Hn : forall j, (j <= length x0)%nat -> Qabs (l j) <= 2 * M).
  { intros j Hj. destruct (multiplier_sup_bound x0 u0 r t M j Ht HK L HB ltac:(lia) Hj) as [A B].
    unfold l. rewrite Qabs_pos by exact A. exact B. }
  assert (A : Qabs (pconst l i) <= 2 * M) by (apply Hn; lia).
  assert (B : Qabs (paffine l (length x0) i w) <= 2 * M)
    by (apply paffine_abs; [split; auto|apply Hn; lia|apply Hn; lia]).
  lra.
Qed.

(** ** [eq:diffLambda_N], corrected *)

(** The exact difference on the cell [i]: [Λ̃_N − Λ_N = (λ_i − λ_{i−1})(θ − 1)],
    [θ = N(w − (i−1)/N)] (the printed right-hand side
    [N(λ_i − λ_{i−1})(w − (i−1)/N)] is [Λ̃_N − λ_{i−1}], the ledger's
    re-indexed [Λ_N]). Any sequence. *)
Lemma diffLambda_identity (l : seqQ) (N i : nat) (w : Q) :
  paffine l N i w - pconst l i ==
  (l i - l (i - 1)%nat) * (qn N * (w - qn (i - 1) / qn N) - 1) /\
  paffine l N i w - l (i - 1)%nat == qn N * (l i - l (i - 1)%nat) * (w - qn (i - 1) / qn N).
Proof. unfold paffine, pconst. split; ring. Qed.

Lemma abs_mult_le (d s : Q) : Qabs s <= 1 -> Qabs (d * s) <= Qabs d.
Proof.
  intro H. rewrite Qabs_Qmult. pose proof (Qabs_nonneg d). pose proof (Qabs_nonneg s). nra.
Qed.

(** Paper, [eq:diffLambda_N] as the ledger corrects it: on the cell [i],
    [|Λ̃_N(t,w) − Λ_N(t,w)| = |λ_i − λ_{i−1}| · |1 − N(w − (i−1)/N)|
    ≤ |λ_i − λ_{i−1}| ≤ 2 sup_i |u⁰_i| / N]; with the re-indexed
    [Λ_N := λ_{i−1}] the printed equality
    [|Λ̃_N − Λ_N| = |N(λ_i − λ_{i−1})(w − (i−1)/N)|] holds, with the same
    bound. Every [N ≥ 1], [x⁰ ∈ K^N], rational [t ≥ 0], [w] in the cell.
    Ledger claim: [eq:diffLambda_N] (corrected). *)
Theorem diffLambda_N (x0 u0 : list Q) (r t M : Q) (i : nat) (w : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 ->
  InCell (length x0) i w ->
  let l := lambdas x0 u0 r t in
  let N := length x0 in
  Qabs (paffine l N i w - pconst l i) <= 2 * M / qn N /\
  Qabs (paffine l N i w - l (i - 1)%nat) <= 2 * M / qn N.
Proof.
  intros Ht HK L HB Hw l N.
  pose proof (cell_theta N i w Hw) as Hθ.
  destruct Hw as (Hi & _ & _).
  destruct (multiplier_increment_bound x0 u0 r t M i Ht HK L HB Hi) as [_ D].
  fold l N in D. destruct (diffLambda_identity l N i w) as [E1 E2].
  set (θ := qn N * (w - qn (i - 1) / qn N)) in *.
  rewrite E1, E2. split.
  - eapply Qle_trans; [apply abs_mult_le; apply Qabs_Qle_condition; lra|exact D].
  - setoid_replace (qn N * (l i - l (i - 1)%nat) * (w - qn (i - 1) / qn N))
      with ((l i - l (i - 1)%nat) * θ) by (unfold θ; ring).
    eapply Qle_trans; [apply abs_mult_le; apply Qabs_Qle_condition; lra|exact D].
Qed.
