(** * Section 3 at fixed [N]: the positions ([prop:Linf-micro],
      [eq:BV_XN], [prop:cvg1#XN-L1], [eq:Oleinik-tUN]).

    The interpolations are those of [S3Linf.v]: cell [i = 1..N],
    [x_0 = x_1 − 1/N − δ] ([df:x0]), [u_0 = u_1]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List Qabs.
From Sticky Require Import Prelude Kkt Pava Projection SupNorm Dynamics ClusterAlgebra
  DynamicsInvariant DynamicsProjection Multipliers DynamicsIsProjK Oleinik S3Linf.
Import ListNotations.
Open Scope Q_scope.

(** ** Lists equal up to [Qeq] *)

Lemma sqnorm_vsub_self (a : list Q) : sqnorm (vsub a a) == 0.
Proof. induction a as [|x a IH]; simpl; [reflexivity|rewrite IH; ring]. Qed.

Lemma sqnorm_zero_qeq (a b : list Q) :
  length a = length b -> sqnorm (vsub a b) == 0 -> qeq_list a b.
Proof.
  revert b. induction a as [|x a IH]; intros [|y b] L H; simpl in *; try discriminate.
  - constructor.
  - pose proof (sqnorm_nonneg (vsub a b)). pose proof (Qsq_nonneg (x - y)).
    constructor.
    + assert (E : (x - y) * (x - y) == 0) by lra.
      apply Qmult_integral in E. destruct E; lra.
    + apply IH; [lia|lra].
Qed.

(** [P_K(x) = x] on [K^N]. *)
Lemma proj_K_fixed (r : Q) (x : list Q) : InK r x -> qeq_list (proj_K r x) x.
Proof.
  intro HK. pose proof (proj_K_minimiser r x x HK eq_refl) as H.
  rewrite sqnorm_vsub_self in H.
  pose proof (sqnorm_nonneg (vsub x (proj_K r x))).
  pose proof (sqnorm_nonneg (vsub (proj_K r x) x)).
  apply sqnorm_zero_qeq; [apply proj_K_length|lra].
Qed.

(** ** The positions stay in [K^N] and move at speed at most [sup |u⁰|] *)

Lemma positions_length (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  length (positions (dynamics x0 u0 r t)) = length x0.
Proof.
  intros Ht HK L. rewrite (qeq_list_length _ _ (dynamics_is_proj_K x0 u0 r t Ht HK L)).
  rewrite proj_K_length. apply free_flight_length, L.
Qed.

Lemma positions_inK (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> InK r (positions (dynamics x0 u0 r t)).
Proof.
  intros Ht HK L i Hi. pose proof (dynamics_is_proj_K x0 u0 r t Ht HK L) as E.
  rewrite !(qeq_list_nth _ _ E). rewrite (qeq_list_length _ _ E) in Hi.
  apply proj_K_in_K, Hi.
Qed.

(** [|x_i(t) − x⁰_i| ≤ t sup_j |u⁰_j|] for every particle: [P_K] is
    1-Lipschitz in the sup norm and fixes [x⁰]. *)
Theorem position_sup_lipschitz (x0 u0 : list Q) (r t M : Q) (i : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 -> (i < length x0)%nat ->
  Qabs (nth i (positions (dynamics x0 u0 r t)) 0 - nth i x0 0) <= t * M.
Proof.
  intros Ht HK L HB Hi.
  set (z := free_flight x0 u0 t).
  assert (Lz : length z = length x0) by (apply free_flight_length, L).
  assert (HS : SupWithin (t * M) z x0).
  { intros j Hj. rewrite Lz in Hj. unfold z. rewrite free_flight_nth by assumption.
    setoid_replace (nth j x0 0 + t * nth j u0 0 - nth j x0 0) with (t * nth j u0 0) by ring.
    rewrite Qabs_Qmult, (Qabs_pos t Ht).
    pose proof (forall_nth _ _ j HB ltac:(lia)) as A. cbv beta in A.
    nra. }
  pose proof (proj_K_sup_lipschitz (t * M) r z x0 ltac:(lia) HS i) as P.
  rewrite proj_K_length, Lz in P. specialize (P Hi).
  rewrite (qeq_list_nth _ _ (dynamics_is_proj_K x0 u0 r t Ht HK L)).
  fold z. rewrite (qeq_list_nth _ _ (proj_K_fixed r x0 HK) i) in P. exact P.
Qed.

(** ** Monotone sequences and telescoping sums over the cells *)

Lemma telescope (f : nat -> Q) (v : seqQ) (c : Q) (n : nat) :
  (forall j, (1 <= j <= n)%nat -> f j == c * (v j - v (j - 1)%nat)) ->
  qsum (map f (seq 1 n)) == c * (v n - v 0%nat).
Proof.
  induction n as [|n IH]; intro Hf; [simpl; ring|].
  rewrite seq_S, map_app, qsum_app. cbn [map qsum].
  rewrite IH by (intros; apply Hf; lia).
  replace (1 + n)%nat with (S n) by lia. rewrite (Hf (S n)) by lia.
  replace (S n - 1)%nat with n by lia. ring.
Qed.

Lemma mono_le (v : seqQ) (n : nat) :
  (forall j, (1 <= j <= n)%nat -> v (j - 1)%nat <= v j) ->
  forall a b, (a <= b <= n)%nat -> v a <= v b.
Proof.
  intros Hm a b. induction b as [|b IH]; intro Hab.
  - replace a with 0%nat by lia. apply Qle_refl.
  - destruct (Nat.eq_dec a (S b)) as [->|Hne]; [apply Qle_refl|].
    apply (Qle_trans _ (v b)); [apply IH; lia|].
    specialize (Hm (S b) ltac:(lia)). replace (S b - 1)%nat with b in Hm by lia. exact Hm.
Qed.

(** The artificial particle and [K^N] make [x_0 < x_1 ≤ … ≤ x_N]. *)
Lemma xs_mono (δ r : Q) (x : list Q) :
  0 <= δ -> 0 <= r -> InK r x ->
  forall j, (1 <= j <= length x)%nat -> xs δ x (j - 1)%nat <= xs δ x j.
Proof.
  intros Hδ Hr HK [|[|j]] Hj; [lia| |].
  - simpl. assert (0 < qn (length x)) by (apply qn_pos; lia).
    assert (0 <= 1 / qn (length x)) by (apply Qle_shift_div_l; lra). lra.
  - simpl. specialize (HK j ltac:(lia)). lra.
Qed.

(** [∫_0^1 |∂_w Ṽ_N(w)| dw = Σ_{i=1}^N (1/N)|N(v_i − v_{i−1})|]: the slope
    is constant on each cell, of length [1/N]. *)
Definition bv (v : seqQ) (N : nat) : Q :=
  qsum (map (fun i => 1 / qn N * Qabs (pslope v N i)) (seq 1 N)).

(** [∫_0^1 |Ṽ_N(w) − V_N(w)| dw = Σ_{i=1}^N |v_i − v_{i−1}| / (2N)]: on the
    cell [i], [Ṽ_N − V_N = (v_i − v_{i−1})(θ − 1)] ([S3Linf.diffLambda_identity])
    and [∫ |θ − 1| dw = 1/(2N)]. *)
Definition l1_gap (v : seqQ) (N : nat) : Q :=
  qsum (map (fun i => Qabs (v i - v (i - 1)%nat) / (2 * qn N)) (seq 1 N)).

Lemma positions_first_last (x0 u0 : list Q) (r t M : Q) (n : nat) :
  0 <= t -> InK r x0 -> length u0 = length x0 -> SupBound M u0 -> length x0 = S n ->
  let x := positions (dynamics x0 u0 r t) in
  nth n x 0 <= nth n x0 0 + t * M /\ nth 0 x0 0 - t * M <= nth 0 x 0.
Proof.
  intros Ht HK L HB En x.
  pose proof (position_sup_lipschitz x0 u0 r t M n Ht HK L HB ltac:(lia)) as A.
  pose proof (position_sup_lipschitz x0 u0 r t M 0 Ht HK L HB ltac:(lia)) as B.
  apply Qabs_Qle_condition in A, B. fold x in A, B. lra.
Qed.

(** Paper, [eq:BV_XN] and its proof: "∫_0^1 |∂_w X̃_N(t,w)| dw =
    x_N(t) − x_0(t) ≤ (x_N(0) − x_0(0)) + T(sup|u_N| + sup|u_1|)": here
    [≤ (x⁰_N − x⁰_0) + 2t sup_i |u⁰_i|], and under [cond:Linfty]
    ([x⁰_N − x⁰_0 + sup_i |u⁰_i| ≤ C'_0]) and [t ≤ T], [≤ (1 + 2T) C'_0].
    Every [N ≥ 1], [r ≥ 0], [δ > 0], [x⁰ ∈ K^N], rational [0 ≤ t ≤ T].
    Ledger claims: [eq:BV_XN], [prop:Linf-micro]. *)
Theorem BV_XN (x0 u0 : list Q) (r t T M δ C0' : Q) :
  0 <= t -> t <= T -> 0 <= r -> 0 < δ -> InK r x0 -> length u0 = length x0 ->
  SupBound M u0 -> (1 <= length x0)%nat ->
  xs δ x0 (length x0) - xs δ x0 0%nat + M <= C0' ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  let N := length x0 in
  bv x N == x N - x 0%nat /\
  x N - x 0%nat <= (xs δ x0 N - xs δ x0 0%nat) + 2 * t * M /\
  bv x N <= (1 + 2 * T) * C0'.
Proof.
  intros Ht HtT Hr Hδ HK L HB HN1 HC x N.
  destruct (Nat.lt_exists_pred 0 (length x0) ltac:(lia)) as (n & En & _).
  assert (HM : 0 <= M) by (apply (supbound_nonneg M u0 HB); destruct u0; simpl in L; [lia|discriminate]).
  pose proof (positions_length x0 u0 r t Ht HK L) as Lx. rewrite En in Lx.
  pose proof (positions_inK x0 u0 r t Ht HK L) as HKx.
  pose proof (qn_pos (S n) ltac:(lia)) as HNq.
  pose proof (qn_pos (length x0) ltac:(lia)) as HNq'.
  assert (E : bv x N == x N - x 0%nat).
  { unfold bv. setoid_replace (x N - x 0%nat) with (1 * (x N - x 0%nat)) by ring.
    apply telescope. intros j Hj. unfold pslope.
    pose proof (xs_mono δ r _ ltac:(lra) Hr HKx j ltac:(rewrite Lx; unfold N in Hj; lia)) as Hm.
    fold x in Hm. rewrite Qabs_pos by (apply Qmult_le_0_compat; [apply qn_nonneg|lra]).
    unfold N. field. lra. }
  destruct (positions_first_last x0 u0 r t M n Ht HK L HB En) as [A B].
  assert (D : x N - x 0%nat <= (xs δ x0 N - xs δ x0 0%nat) + 2 * t * M).
  { unfold x, N, xs. rewrite Lx, En. lra. }
  split; [exact E|split; [exact D|]].
  assert (S0 : 0 <= xs δ x0 N - xs δ x0 0%nat).
  { pose proof (mono_le (xs δ x0) (length x0) (xs_mono δ r x0 ltac:(lra) Hr HK) 0 (length x0)
                  ltac:(lia)) as Hm. unfold N. lra. }
  unfold N in *. rewrite E. nra.
Qed.

(** Paper, [prop:Linf-micro] (the positions): "we may assume x⁰_0 = 0 …
    ‖X_N‖_{L^∞((0,T)×(0,1))} + ‖X̃_N‖_{L^∞((0,T)×(0,1))} ≤ C'", with
    [C' = 2(1 + T) C'_0] under [cond:Linfty]: on every cell and every [w]
    of it. Every [N ≥ 1], [r ≥ 0], [δ > 0], [x⁰ ∈ K^N], rational
    [0 ≤ t ≤ T]. Ledger claim: [prop:Linf-micro]. *)
Theorem XN_Linf (x0 u0 : list Q) (r t T M δ C0' : Q) (i : nat) (w : Q) :
  0 <= t -> t <= T -> 0 <= r -> 0 < δ -> InK r x0 -> length u0 = length x0 ->
  SupBound M u0 -> xs δ x0 0%nat == 0 ->
  xs δ x0 (length x0) - xs δ x0 0%nat + M <= C0' ->
  InCell (length x0) i w ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  Qabs (pconst x i) + Qabs (paffine x (length x0) i w) <= 2 * ((1 + T) * C0').
Proof.
  intros Ht HtT Hr Hδ HK L HB H0 HC Hw x.
  pose proof Hw as (Hi & _ & _).
  destruct (Nat.lt_exists_pred 0 (length x0) ltac:(lia)) as (n & En & _).
  assert (HM : 0 <= M) by (apply (supbound_nonneg M u0 HB); destruct u0; simpl in L; [lia|discriminate]).
  pose proof (positions_length x0 u0 r t Ht HK L) as Lx. rewrite En in Lx.
  pose proof (positions_inK x0 u0 r t Ht HK L) as HKx.
  rewrite En in HC, Hw, Hi |- *.
  pose proof (mono_le x (S n) ltac:(intros j Hj; apply (xs_mono δ r _ ltac:(lra) Hr HKx j);
                                    rewrite Lx; lia)) as Hm.
  destruct (positions_first_last x0 u0 r t M n Ht HK L HB En) as [A B].
  assert (S0 : 0 <= xs δ x0 (S n) - xs δ x0 0%nat).
  { pose proof (mono_le (xs δ x0) (length x0) (xs_mono δ r x0 ltac:(lra) Hr HK) 0 (length x0)
                  ltac:(lia)) as Hm0. rewrite En in Hm0. lra. }
  assert (Lo : x 0%nat == xs δ x0 0%nat + (nth 0 (positions (dynamics x0 u0 r t)) 0 - nth 0 x0 0))
    by (unfold x, xs; rewrite Lx, En; ring).
  assert (Hi0 : xs δ x0 (S n) == nth n x0 0) by reflexivity.
  assert (Hn : forall j, (j <= S n)%nat -> Qabs (x j) <= (1 + T) * C0').
  { rewrite Hi0 in HC, S0. rewrite H0 in HC, S0, Lo.
    assert (HMC : M <= C0') by lra.
    assert (HTM : t * M <= T * C0') by nra.
    assert (HT0 : 0 <= T * C0') by nra.
    intros j Hj. pose proof (Hm 0%nat j ltac:(lia)). pose proof (Hm j (S n) ltac:(lia)).
    change (x (S n)) with (nth n (positions (dynamics x0 u0 r t)) 0) in *.
    apply Qabs_Qle_condition. split; lra. }
  assert (P1 : Qabs (pconst x i) <= (1 + T) * C0') by (apply Hn; lia).
  assert (P2 : Qabs (paffine x (S n) i w) <= (1 + T) * C0')
    by (apply paffine_abs; [exact Hw|apply Hn; lia|apply Hn; lia]).
  lra.
Qed.

(** Paper, proof of [prop:cvg1]: "∫_0^1 |X̃_N(t,w) − X_N(t,w)| dw =
    (1/2N) Σ_{i=0}^{N−1} (x_{i+1}(t) − x_i(t)) = (1/2N)(x_N(t) − x_0(t))
    ≤ C/N", with [C = (1 + 2T) C'_0 / 2] under [cond:Linfty]. The
    left-hand side is [l1_gap], its cell-by-cell closed form. Every
    [N ≥ 1], [r ≥ 0], [δ > 0], [x⁰ ∈ K^N], rational [0 ≤ t ≤ T].
    Ledger claim: [prop:cvg1#XN-L1]. *)
Theorem XN_L1 (x0 u0 : list Q) (r t T M δ C0' : Q) :
  0 <= t -> t <= T -> 0 <= r -> 0 < δ -> InK r x0 -> length u0 = length x0 ->
  SupBound M u0 -> (1 <= length x0)%nat ->
  xs δ x0 (length x0) - xs δ x0 0%nat + M <= C0' ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  let N := length x0 in
  l1_gap x N == (x N - x 0%nat) / (2 * qn N) /\
  l1_gap x N <= (1 + 2 * T) * C0' / 2 / qn N.
Proof.
  intros Ht HtT Hr Hδ HK L HB HN1 HC x N.
  destruct (BV_XN x0 u0 r t T M δ C0' Ht HtT Hr Hδ HK L HB HN1 HC) as (E & _ & Bd).
  fold x N in E, Bd.
  pose proof (qn_pos N HN1) as HNq.
  pose proof (positions_length x0 u0 r t Ht HK L) as Lx.
  pose proof (positions_inK x0 u0 r t Ht HK L) as HKx.
  assert (E2 : l1_gap x N == (x N - x 0%nat) / (2 * qn N)).
  { unfold l1_gap. setoid_replace ((x N - x 0%nat) / (2 * qn N))
      with (1 / (2 * qn N) * (x N - x 0%nat)) by (field; lra).
    apply telescope. intros j Hj.
    pose proof (xs_mono δ r _ ltac:(lra) Hr HKx j ltac:(rewrite Lx; unfold N in Hj; lia)) as Hm.
    fold x in Hm. rewrite Qabs_pos by lra. field. lra. }
  split; [exact E2|]. rewrite E2, <- E.
  setoid_replace ((1 + 2 * T) * C0' / 2 / qn N) with ((1 + 2 * T) * C0' / (2 * qn N))
    by (field; lra).
  apply Qmult_le_compat_r; [exact Bd|]. apply Qlt_le_weak, Qinv_lt_0_compat. lra.
Qed.

(** Paper, [eq:Oleinik-tUN]: "∂_w Ũ_N < ∂_w X̃_N / t" on every cell
    [i = 1..N] (the artificial particle's cell included: [u_0 = u_1],
    [x_1 − x_0 = 1/N + δ]), for [t > 0]. Every [N ≥ 1], [r > 0], [δ > 0],
    [x⁰ ∈ K^N], any [u⁰], rational [t > 0]. Ledger claim: [eq:Oleinik-tUN]. *)
Theorem Oleinik_tUN (x0 u0 : list Q) (r t δ : Q) (i : nat) :
  0 < t -> 0 < r -> 0 < δ -> InK r x0 -> length u0 = length x0 ->
  (1 <= i <= length x0)%nat ->
  let x := xs δ (positions (dynamics x0 u0 r t)) in
  let u := us (velocities (dynamics x0 u0 r t)) in
  pslope u (length x0) i < pslope x (length x0) i / t.
Proof.
  intros Ht Hr Hδ HK L Hi x u.
  assert (Ht0 : 0 <= t) by lra.
  pose proof (positions_length x0 u0 r t Ht0 HK L) as Lx.
  pose proof (positions_inK x0 u0 r t Ht0 HK L) as HKx.
  pose proof (qn_pos (length x0) ltac:(lia)) as HNq.
  unfold pslope. destruct i as [|[|i]]; [lia| |].
  - set (p := positions (dynamics x0 u0 r t)) in *.
    change (x 1%nat) with (nth 0 p 0).
    change (x (1 - 1)%nat) with (nth 0 p 0 - 1 / qn (length p) - δ).
    change (u 1%nat) with (nth 0 (velocities (dynamics x0 u0 r t)) 0).
    change (u (1 - 1)%nat) with (nth 0 (velocities (dynamics x0 u0 r t)) 0).
    rewrite Lx.
    setoid_replace (qn (length x0) * (nth 0 (velocities (dynamics x0 u0 r t)) 0 -
                                       nth 0 (velocities (dynamics x0 u0 r t)) 0)) with 0 by ring.
    apply Qlt_shift_div_l; [exact Ht|].
    assert (0 < 1 / qn (length x0)) by (apply Qlt_shift_div_l; lra). nra.
  - pose proof (oleinik x0 u0 r t (S i) Ht Hr HK L ltac:(lia)) as O. cbv zeta in O.
    replace (S i - 1)%nat with i in O by lia.
    change (u (S (S i))) with (nth (S i) (velocities (dynamics x0 u0 r t)) 0).
    change (u (S (S i) - 1)%nat) with (nth i (velocities (dynamics x0 u0 r t)) 0).
    change (x (S (S i))) with (nth (S i) (positions (dynamics x0 u0 r t)) 0).
    change (x (S (S i) - 1)%nat) with (nth i (positions (dynamics x0 u0 r t)) 0).
    set (du := nth (S i) (velocities (dynamics x0 u0 r t)) 0 - nth i (velocities (dynamics x0 u0 r t)) 0) in *.
    set (dx := nth (S i) (positions (dynamics x0 u0 r t)) 0 - nth i (positions (dynamics x0 u0 r t)) 0) in *.
    assert (Hdx : 0 < dx) by (unfold dx; specialize (HKx i ltac:(lia)); lra).
    assert (Hdu : du < dx / t).
    { setoid_replace du with (du / dx * dx) by (field; lra).
      setoid_replace (dx / t) with (1 / t * dx) by (field; lra).
      apply Qmult_lt_r; assumption. }
    setoid_replace (qn (length x0) * dx / t) with (qn (length x0) * (dx / t)) by (field; lra).
    apply Qmult_lt_l; assumption.
Qed.
