(** * The contact clusters of a position vector, and the oracle's clusters.

    A cluster, as [sticky run --json] prints it, is a maximal run of
    consecutive particles each touching the next: [x_{i+1} − x_i = 2r]
    ([Contacts.Contact]). [contact_clusters r x] lists them as
    [(first, size)], particles indexed from 0, left to right.

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
