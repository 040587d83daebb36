(** * The contact clusters of a position vector, and the oracle's clusters.

    A cluster, as [sticky run --json] prints it, is a maximal run of
    consecutive particles each touching the next: [x_{i+1} − x_i = 2r]
    ([Contacts.Contact]). [contact_clusters r x] lists them as
    [(first, size)], particles indexed from 0, left to right;
    [contact_clusters_spec] proves they are exactly that: the spans tile the
    particles in order, and two neighbours share a span iff they touch.

    [Oracle.state_at] computes its clusters differently, as the runs of equal
    translated positions [x̃_i = x_i − 2r·i] before translating back
    ([Oracle.runs]). [state_clusters_spec]: the two are equal, for every
    input — the clusters the oracle prints are the contact clusters of the
    positions it prints. *)

From Coq Require Import QArith Qring Lqa Lia List Bool.
From Sticky Require Import Prelude Kkt Pava Oracle Dynamics Contacts.
Import ListNotations.
Open Scope Q_scope.

(** ** Definitions *)

(** The gaps [x_{i+1} − x_i], [i = 0 … N−2]. *)
Fixpoint gaps (x : list Q) : list Q :=
  match x with
  | a :: ((b :: _) as x') => (b - a) :: gaps x'
  | _ => []
  end.

(** Consecutive particles grouped by [joined] (entry [i]: particle [i + 1]
    belongs to particle [i]'s group): the spans [(first, size)] of the
    groups, the current group starting at [first] with [size] members so
    far. *)
Fixpoint spans_from (first size : nat) (joined : list bool) : list (nat * nat) :=
  match joined with
  | [] => [(first, size)]
  | true :: joined' => spans_from first (S size) joined'
  | false :: joined' => (first, size) :: spans_from (first + size) 1 joined'
  end.

(** Pair [(i, i + 1)] is in contact: its gap is exactly [2r]. *)
Definition in_contact (r : Q) (x : list Q) : list bool :=
  map (fun g => Qeq_bool g (2 * r)) (gaps x).

(** The contact clusters of [x]: the maximal runs of particles in contact,
    as [(first, size)], [first] from 0. *)
Definition contact_clusters (r : Q) (x : list Q) : list (nat * nat) :=
  match x with
  | [] => []
  | _ :: _ => spans_from 0 1 (in_contact r x)
  end.

(** ** The definition reads [Contacts.Contact] *)

Lemma gaps_length (x : list Q) : length (gaps x) = (length x - 1)%nat.
Proof.
  induction x as [|a [|b x] IH]; [reflexivity|reflexivity|].
  change (length (gaps (a :: b :: x))) with (S (length (gaps (b :: x)))).
  rewrite IH. simpl. lia.
Qed.

Lemma nth_gaps (x : list Q) : forall j,
  (S j < length x)%nat -> nth j (gaps x) 0 == nth (S j) x 0 - nth j x 0.
Proof.
  induction x as [|a [|b x] IH]; intros j Hj; simpl in Hj; try lia.
  destruct j as [|j]; [reflexivity|].
  change (nth (S j) (gaps (a :: b :: x)) 0) with (nth j (gaps (b :: x)) 0).
  rewrite IH by (simpl; lia). reflexivity.
Qed.

(** Entry [j] of [in_contact r x] says that particles [j] and [j + 1]
    touch, [Contact r x j], for every pair [S j < N]. *)
Lemma in_contact_spec (r : Q) (x : list Q) (j : nat) :
  (S j < length x)%nat -> (nth j (in_contact r x) false = true <-> Contact r x j).
Proof.
  intro Hj. unfold in_contact, Contact. set (f := fun g => Qeq_bool g (2 * r)).
  rewrite nth_indep with (d' := f 0) by (rewrite map_length, gaps_length; lia).
  rewrite map_nth. unfold f. rewrite Qeq_bool_iff, nth_gaps by exact Hj. reflexivity.
Qed.

(** Contact clusters only see the entries' values. *)
Lemma gaps_qeq (x y : list Q) : qeq_list x y -> qeq_list (gaps x) (gaps y).
Proof.
  intro E. induction E as [|a b x y Eab E IH]; [constructor|].
  destruct E as [|c d x' y' Ecd E']; [constructor|].
  cbn [gaps]. constructor; [rewrite Eab, Ecd; reflexivity|exact IH].
Qed.

Lemma in_contact_qeq (r : Q) (x y : list Q) : qeq_list x y -> in_contact r x = in_contact r y.
Proof.
  intro E. unfold in_contact. apply gaps_qeq in E.
  induction E as [|g h x' y' Egh E IH]; [reflexivity|].
  cbn [map]. rewrite IH. f_equal.
  apply eq_iff_eq_true. rewrite !Qeq_bool_iff, Egh. reflexivity.
Qed.

Lemma contact_clusters_qeq (r : Q) (x y : list Q) :
  qeq_list x y -> contact_clusters r x = contact_clusters r y.
Proof.
  intro E. unfold contact_clusters. rewrite (in_contact_qeq r x y E).
  destruct E; reflexivity.
Qed.

(** ** The spans are the maximal runs of contacts

    [contact_clusters_spec]: the spans tile the particles [0 … N−1] in
    order, and two neighbours [j], [j + 1] lie in one span iff they touch.
    So the spans are the maximal runs of particles in contact, whatever
    [spans_from] looks like inside. *)

(** Particle [i] and its right neighbour lie in one span. *)
Definition SameSpan (spans : list (nat * nat)) (i : nat) : Prop :=
  exists f s, In (f, s) spans /\ (f <= i)%nat /\ (S i < f + s)%nat.

(** The particles a list of spans covers, in order. *)
Definition covered (spans : list (nat * nat)) : list nat :=
  flat_map (fun p => seq (fst p) (snd p)) spans.

Lemma spans_from_covered (joined : list bool) : forall first size,
  covered (spans_from first size joined) = seq first (size + length joined).
Proof.
  induction joined as [|[|] joined IH]; intros first size; cbn [spans_from length].
  - unfold covered. simpl. rewrite app_nil_r, Nat.add_0_r. reflexivity.
  - rewrite IH. f_equal. lia.
  - unfold covered in *. cbn [flat_map fst snd]. rewrite IH.
    replace (size + S (length joined))%nat with (size + (1 + length joined))%nat by lia.
    rewrite (seq_app size (1 + length joined) first). reflexivity.
Qed.

Lemma spans_from_first (joined : list bool) : forall first size f s,
  In (f, s) (spans_from first size joined) -> (first <= f)%nat.
Proof.
  induction joined as [|[|] joined IH]; intros first size f s H; cbn [spans_from] in H.
  - destruct H as [H|[]]. inversion H. lia.
  - exact (IH _ _ _ _ H).
  - destruct H as [H|H]; [inversion H; lia|]. apply IH in H. lia.
Qed.

Lemma spans_from_head (joined : list bool) : forall first size,
  exists s rest, spans_from first size joined = (first, s) :: rest /\ (size <= s)%nat.
Proof.
  induction joined as [|[|] joined IH]; intros first size; cbn [spans_from].
  - exists size, []. split; [reflexivity|lia].
  - destruct (IH first (S size)) as (s & rest & E & L). exists s, rest. split; [exact E|lia].
  - exists size, (spans_from (first + size) 1 joined). split; [reflexivity|lia].
Qed.

Lemma spans_from_same (joined : list bool) : forall first size k,
  (1 <= size)%nat -> (k < length joined)%nat ->
  (nth k joined false = true <-> SameSpan (spans_from first size joined) (first + size - 1 + k)).
Proof.
  induction joined as [|b joined IH]; intros first size k Hs Hk; [simpl in Hk; lia|].
  destruct b; cbn [spans_from].
  - destruct k as [|k].
    + split; [intros _|reflexivity].
      destruct (spans_from_head joined first (S size)) as (s & rest & E & L).
      exists first, s. rewrite E. split; [left; reflexivity|lia].
    + cbn [nth]. simpl in Hk.
      replace (first + size - 1 + S k)%nat with (first + S size - 1 + k)%nat by lia.
      apply IH; lia.
  - assert (Head : forall i rest, (first + size <= i)%nat ->
              (SameSpan ((first, size) :: rest) i <-> SameSpan rest i)).
    { intros i rest Hi. split.
      - intros (f & s & [E|H] & L1 & L2); [inversion E; subst; lia|].
        exists f, s. auto.
      - intros (f & s & H & L1 & L2). exists f, s. split; [right; exact H|auto]. }
    destruct k as [|k].
    + cbn [nth]. split; [discriminate|].
      intros (f & s & [E|H] & L1 & L2); [inversion E; subst; lia|].
      apply spans_from_first in H. lia.
    + cbn [nth]. simpl in Hk. rewrite Head by lia.
      replace (first + size - 1 + S k)%nat with (first + size + 1 - 1 + k)%nat by lia.
      apply IH; lia.
Qed.

(** For every [N ≥ 1]: the contact clusters cover [0 … N−1] in order, and
    [j], [j + 1] are in one of them iff they are in contact. *)
Theorem contact_clusters_spec (r : Q) (x : list Q) :
  x <> [] ->
  covered (contact_clusters r x) = seq 0 (length x) /\
  forall j, (S j < length x)%nat -> (Contact r x j <-> SameSpan (contact_clusters r x) j).
Proof.
  intro Hx. assert (Lc : length (in_contact r x) = (length x - 1)%nat)
    by (unfold in_contact; rewrite map_length; apply gaps_length).
  destruct x as [|a x']; [contradiction|]. set (x := a :: x') in *.
  assert (Hc : contact_clusters r x = spans_from 0 1 (in_contact r x)) by reflexivity.
  rewrite Hc. split.
  - rewrite spans_from_covered, Lc. f_equal. simpl. lia.
  - intros j Hj. rewrite <- in_contact_spec by exact Hj.
    replace j with (0 + 1 - 1 + j)%nat at 2 by lia.
    apply spans_from_same; lia.
Qed.

(** ** The oracle's clusters are the contact clusters of its positions *)

(** Two entries of [x̃] are equal iff the translated-back entries, [2r]
    apart in their shifts, are in contact. *)
Lemma runs_from_contact (r : Q) (l : list Q) : forall first size prev off,
  runs_from first size prev l =
  spans_from first size (in_contact r (Qred (prev + off) :: unshift (Qred (off + 2 * r)) (2 * r) l)).
Proof.
  induction l as [|a l IH]; intros first size prev off; [reflexivity|].
  cbn [runs_from unshift]. unfold in_contact. cbn [gaps map]. fold (in_contact r).
  replace (Qeq_bool (Qred (a + Qred (off + 2 * r)) - Qred (prev + off)) (2 * r))
    with (Qeq_bool prev a).
  - destruct (Qeq_bool prev a); cbn [spans_from];
      rewrite (IH _ _ a (Qred (off + 2 * r))); reflexivity.
  - apply eq_iff_eq_true. rewrite !Qeq_bool_iff, !Qred_correct.
    split; intro H; lra.
Qed.

(** For every input, the clusters the oracle prints are the contact
    clusters of the positions it prints. *)
Theorem state_clusters_spec (r t : Q) (x0 u0 : list Q) :
  st_clusters (state_at r t x0 u0) = contact_clusters r (st_positions (state_at r t x0 u0)).
Proof.
  unfold state_at. cbn [st_clusters st_positions].
  generalize (flat_map expand (pava_blocks (combine (shifted_free 0 (2 * r) t x0 u0) u0))).
  intros [|a l]; [reflexivity|].
  cbn [runs unshift contact_clusters]. apply runs_from_contact.
Qed.
