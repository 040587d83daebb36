(** * Section 3: uniform-in-[N] claims that are false, refuted for every
      bound ([prop:cvg1], [eq:sup-micro-u-L#N-lambda]).

    The data are congested blocks sampled at [N]: [x⁰_i = i/N]
    ([i = 1..N], [2r = 1/N]), the quantile sampling of [ρ⁰ = 1] on
    [[0, 1]] ([X⁰(w) = w]). They satisfy the hypotheses of
    [prop:L2-micro] and [prop:Linf-micro] uniformly in [N]:
    [‖x⁰‖ ≤ 1], [‖u⁰‖ ≤ 1], [x⁰_N − x⁰_0 + sup|u⁰| ≤ 2 + δ]. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List Qabs.
From Sticky Require Import Prelude Kkt Projection Dynamics Multipliers DynamicsIsProjK
  S3Linf S3Positions.
Import ListNotations.
Open Scope Q_scope.

(** ** The congested block *)

(** [x⁰_i = i/N], [i = 1..N] (0-based: entry [k] is [(k+1)/N]). *)
Definition block (N : nat) : list Q := map (fun k => qn (S k) / qn N) (seq 0 N).

(** The radius [r = 1/(2N)] ([2rN = 1]). *)
Definition block_radius (N : nat) : Q := 1 / (2 * qn N).

Lemma nth_map_seq (f : nat -> Q) (n k : nat) : (k < n)%nat -> nth k (map f (seq 0 n)) 0 = f k.
Proof.
  intro H. rewrite (nth_indep _ 0 (f 0%nat)) by (rewrite map_length, seq_length; exact H).
  rewrite map_nth, seq_nth by exact H. reflexivity.
Qed.

Lemma block_length (N : nat) : length (block N) = N.
Proof. unfold block. rewrite map_length, seq_length. reflexivity. Qed.

Lemma block_nth (N k : nat) : (k < N)%nat -> nth k (block N) 0 = qn (S k) / qn N.
Proof. intro H. unfold block. rewrite nth_map_seq by exact H. reflexivity. Qed.

Lemma block_inK (N : nat) : (1 <= N)%nat -> InK (block_radius N) (block N).
Proof.
  intros HN i Hi. rewrite block_length in Hi. rewrite !block_nth by lia.
  pose proof (qn_pos N ltac:(lia)). unfold block_radius.
  assert (E : qn (S (S i)) / qn N - qn (S i) / qn N == 2 * (1 / (2 * qn N)))
    by (rewrite (qn_S (S i)); field; lra).
  rewrite E. apply Qle_refl.
Qed.

(** ** [prop:cvg1]: [X̃_N → X] uniformly on [[0,T] × [0,1]] fails *)

(** Paper, [prop:cvg1]: "X̃_N → X strongly in C([0,T] × [0,1])". Refuted
    on the block at rest ([u⁰ = 0], one congested block; the ledger's
    witness family): for every [N ≥ 1], [δ > 0] and rational [t ≥ 0],
    the particles do not move, [X_N(t,w) − w ∈ [0, 1/N]] on every cell
    (so [X_N(t) → X(t) = X⁰ = w] uniformly on [(0,1]], and the limit in
    [prop:cvg1] can only be [X(t,w) = w]), but [X̃_N(t,0) = x_0(t) = −δ]:
    [sup_w |X̃_N(t,w) − X(t,w)| ≥ δ] for every [N].
    Ledger claim: [prop:cvg1]. *)
Theorem cvg1_uniform_false (N : nat) (δ t : Q) (i : nat) (w : Q) :
  (1 <= N)%nat -> 0 < δ -> 0 <= t -> InCell N i w ->
  let x := xs δ (positions (dynamics (block N) (repeat 0 N) (block_radius N) t)) in
  (0 <= pconst x i - w /\ pconst x i - w <= 1 / qn N) /\
  paffine x N 1 0 - 0 == - δ.
Proof.
  intros HN Hδ Ht Hw x.
  pose proof (qn_pos N ltac:(lia)) as HNq.
  assert (L : length (repeat 0 N) = length (block N)) by (rewrite repeat_length, block_length; reflexivity).
  assert (HB : SupBound 0 (repeat 0 N)).
  { apply Forall_forall. intros a Ha. apply repeat_spec in Ha. subst. simpl. lra. }
  pose proof (block_inK N HN) as HK.
  assert (Still : forall k, (k < N)%nat ->
            nth k (positions (dynamics (block N) (repeat 0 N) (block_radius N) t)) 0 == qn (S k) / qn N).
  { intros k Hk. pose proof (position_sup_lipschitz _ _ _ t 0 k Ht HK L HB
                                ltac:(rewrite block_length; exact Hk)) as P.
    rewrite block_nth in P by exact Hk. apply Qabs_Qle_condition in P. lra. }
  pose proof (positions_length _ _ _ t Ht HK L) as Lx. rewrite block_length in Lx.
  destruct Hw as (Hi & W1 & W2). split.
  - destruct i as [|i]; [lia|]. unfold pconst. change (x (S i)) with
      (nth i (positions (dynamics (block N) (repeat 0 N) (block_radius N) t)) 0).
    rewrite Still by lia. replace (S i - 1)%nat with i in W1 by lia.
    assert (E : qn (S i) / qn N == qn i / qn N + 1 / qn N) by (rewrite qn_S; field; lra).
    split; lra.
  - unfold paffine. replace (1 - 1)%nat with 0%nat by lia.
    change (x 1%nat) with (nth 0 (positions (dynamics (block N) (repeat 0 N) (block_radius N) t)) 0).
    change (x 0%nat) with (nth 0 (positions (dynamics (block N) (repeat 0 N) (block_radius N) t)) 0
                            - 1 / qn (length (positions (dynamics (block N) (repeat 0 N) (block_radius N) t)))
                            - δ).
    rewrite Lx, Still by lia. rewrite qn_S, qn_0. field. lra.
Qed.
