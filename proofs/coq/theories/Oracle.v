(** * The state at time [t] computed by the oracle, and what is proved of it.

    [state_at r t x⁰ u⁰] is the function extracted to OCaml
    ([Extract.v], [proofs/coq/oracle]). It runs the lexicographic PAVA on
    the pairs [(x̃⁰_i + t u⁰_i, u⁰_i)] exactly as [src/projection.rs] does:
    - positions: the [y]-part of the blocks, translated back. Proved:
      [state_positions_spec], they equal [P_K(x⁰ + t u⁰)] ([prop:proj-micro],
      [eq:proj-micro-x]) entrywise, for every [N].
    - velocities: the block means of [u⁰] ([eq:proj-u-micro]). Proved in
      [RightDerivative.v] ([state_velocities_spec]): they are the right
      derivative of [t ↦ P_K(x⁰ + t u⁰)], for every [N].
    - multipliers: [λ_i = Σ_{j ≤ i} (u⁰_j − u_j) / N], [i = 1 … N−1]
      ([eq:dyn-micro], [u − u⁰ = −N(λ_i − λ_{i−1})], [λ_0 = 0]): a definition.
    - clusters: the maximal runs of equal translated positions (gap exactly
      [2r]), as [(first, size)] with [first] from 0: a definition.
    Every number is returned in lowest terms ([Qred]). *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection.
Import ListNotations.
Open Scope Q_scope.

(** ** Definitions *)

(** The free flight [x⁰ + t u⁰]. *)
Fixpoint free_flight (t : Q) (x u : list Q) : list Q :=
  match x, u with
  | a :: x', b :: u' => (a + t * b) :: free_flight t x' u'
  | _, _ => []
  end.

(** The translated free flight [x̃⁰_i + t u⁰_i], the shift [off = 2r·i]
    carried along (no cast of [i] at every entry). *)
Fixpoint shifted_free (off step t : Q) (x u : list Q) : list Q :=
  match x, u with
  | a :: x', b :: u' => Qred (a - off + t * b) :: shifted_free (Qred (off + step)) step t x' u'
  | _, _ => []
  end.

(** Translating back, [x_i = x̃_i + 2r·i], the shift carried along. *)
Fixpoint unshift (off step : Q) (y : list Q) : list Q :=
  match y with
  | a :: y' => Qred (a + off) :: unshift (Qred (off + step)) step y'
  | [] => []
  end.

(** [λ_i = λ_{i−1} + (u⁰_i − u_i)/N], [λ_0 = 0]; [λ_N] (zero) is not listed. *)
Fixpoint multipliers_from (acc n : Q) (u0 u : list Q) : list Q :=
  match u0, u with
  | [_], [_] => []
  | a :: u0', b :: u' =>
      let acc' := Qred (acc + (a - b) / n) in acc' :: multipliers_from acc' n u0' u'
  | _, _ => []
  end.

(** The maximal runs of equal entries, as [(first, size)], [first] from 0. *)
Fixpoint runs_from (first size : nat) (prev : Q) (l : list Q) : list (nat * nat) :=
  match l with
  | [] => [(first, size)]
  | a :: l' =>
      if Qeq_bool prev a then runs_from first (S size) a l'
      else (first, size) :: runs_from (first + size)%nat 1 a l'
  end.

Definition runs (l : list Q) : list (nat * nat) :=
  match l with
  | [] => []
  | a :: l' => runs_from 0 1 a l'
  end.

(** The state of [prop:proj-micro] at time [t]. *)
Record state := mkstate {
  st_positions : list Q;
  st_velocities : list Q;
  st_multipliers : list Q;
  st_clusters : list (nat * nat)
}.

Definition state_at (r t : Q) (x0 u0 : list Q) : state :=
  let y := shifted_free 0 (2 * r) t x0 u0 in
  let bs := pava_blocks (combine y u0) in
  let xt := flat_map expand bs in
  let u := map Qred (flat_map expand_u bs) in
  mkstate (unshift 0 (2 * r) xt) u
          (multipliers_from 0 (inject_Z (Z.of_nat (length u0))) u0 u)
          (runs xt).

(** The KKT conditions only see the entries' values. *)
Lemma kkt_qeq (z z' y : list Q) : qeq_list z z' -> Kkt z y -> Kkt z' y.
Proof.
  intros E (L & M & P & T & C). pose proof (qeq_list_length _ _ E) as Lz.
  split; [congruence|split; [exact M|split; [|split]]].
  - intros k Hk. rewrite <- (qeq_list_psum _ _ E). apply P. lia.
  - rewrite <- Lz, <- (qeq_list_psum _ _ E). exact T.
  - intros k Hk Hl. rewrite <- (qeq_list_psum _ _ E). apply C; [lia|exact Hl].
Qed.

(** ** The efficient forms equal the paper's *)

Lemma shifted_free_spec (x : list Q) : forall u k off r t,
  off == 2 * r * qn k ->
  qeq_list (shifted_free off (2 * r) t x u) (translate_from k r (free_flight t x u)).
Proof.
  induction x as [|a x IH]; intros [|b u] k off r t Hoff;
    cbn [shifted_free translate_from free_flight]; try constructor.
  - rewrite Qred_correct, Hoff. ring.
  - apply IH. rewrite Qred_correct, Hoff, qn_S. ring.
Qed.

Lemma unshift_spec (y : list Q) : forall k off r,
  off == 2 * r * qn k -> qeq_list (unshift off (2 * r) y) (untranslate_from k r y).
Proof.
  induction y as [|a y IH]; intros k off r Hoff; cbn [unshift untranslate_from]; constructor.
  - rewrite Qred_correct, Hoff. reflexivity.
  - apply IH. rewrite Qred_correct, Hoff, qn_S. ring.
Qed.

Lemma untranslate_from_qeq (a : list Q) : forall b k r,
  qeq_list a b -> qeq_list (untranslate_from k r a) (untranslate_from k r b).
Proof.
  induction a as [|x a IH]; intros b k r E; inversion E; subst; simpl; constructor.
  - rewrite H1. reflexivity.
  - apply IH. assumption.
Qed.

Lemma free_flight_length (t : Q) (x : list Q) : forall u,
  length u = length x -> length (free_flight t x u) = length x.
Proof.
  induction x as [|a x IH]; intros [|b u] L; simpl in *; try discriminate; [reflexivity|].
  f_equal. apply IH. lia.
Qed.

Lemma shifted_free_length (x : list Q) : forall u off step t,
  length u = length x -> length (shifted_free off step t x u) = length x.
Proof.
  induction x as [|a x IH]; intros [|b u] off step t L; simpl in *; try discriminate;
    [reflexivity|].
  f_equal. apply IH. lia.
Qed.

(** ** The oracle's positions are [P_K(x⁰ + t u⁰)]

    [prop:proj-micro], [eq:proj-micro-x]: "x(t) = P_{K^N}(x⁰ + t u⁰)" —
    ledger: [prop:proj-micro]. For every [N], every radius, every rational
    [t] and data [x⁰, u⁰ ∈ Q^N], the positions the oracle prints are, entry
    by entry, the projection [proj_K] of the free flight, which
    [proj_K_minimiser] proves is the nearest point of [K^N]. *)
Theorem state_positions_spec (r t : Q) (x0 u0 : list Q) :
  length u0 = length x0 ->
  qeq_list (st_positions (state_at r t x0 u0)) (proj_K r (free_flight t x0 u0)).
Proof.
  intro L. simpl.
  set (y := shifted_free 0 (2 * r) t x0 u0).
  set (z := translate r (free_flight t x0 u0)).
  assert (Eyz : qeq_list y z).
  { unfold y, z, translate. apply shifted_free_spec. unfold qn. simpl. ring. }
  assert (Ly : length u0 = length y).
  { unfold y. rewrite shifted_free_length; [exact L|exact L]. }
  pose proof (pava_lex_kkt y u0 Ly) as Hk. apply (kkt_qeq _ _ _ Eyz) in Hk.
  pose proof (kkt_unique _ _ _ Hk (pava_kkt z)) as Hu.
  unfold pava_lex in Hu.
  eapply qeq_list_trans.
  - apply (unshift_spec _ 0%nat). unfold qn. simpl. ring.
  - unfold proj_K, untranslate. apply untranslate_from_qeq. exact Hu.
Qed.
