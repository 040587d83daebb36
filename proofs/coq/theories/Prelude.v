(** * Prelude: lists of rationals, their sums and the casts used everywhere.

    Vectors of [R^N] are lists of [Q] of length [N], indexed from 0
    (the program's convention); the paper's [x_i], [i = 1..N], is
    [nth (i-1) x 0] here. *)

From Coq Require Import QArith Qring Lqa Lia List.
Import ListNotations.
Open Scope Q_scope.

(** The sum of the entries of a list. *)
Fixpoint qsum (v : list Q) : Q :=
  match v with
  | [] => 0
  | a :: v' => a + qsum v'
  end.

(** The partial sum of the first [k] entries, [v_1 + ... + v_k] in the
    paper's 1-based notation. *)
Definition psum (k : nat) (v : list Q) : Q := qsum (firstn k v).

(** A natural number as a rational. *)
Definition qn (n : nat) : Q := inject_Z (Z.of_nat n).

Lemma qn_0 : qn 0 == 0.
Proof. reflexivity. Qed.

Lemma qn_S (n : nat) : qn (S n) == qn n + 1.
Proof.
  unfold qn. rewrite Nat2Z.inj_succ, <- Z.add_1_r, inject_Z_plus. reflexivity.
Qed.

Lemma qn_add (a b : nat) : qn (a + b) == qn a + qn b.
Proof. unfold qn. rewrite Nat2Z.inj_add, inject_Z_plus. reflexivity. Qed.

Lemma qn_sub (a b : nat) : (b <= a)%nat -> qn (a - b) == qn a - qn b.
Proof.
  intro H. unfold qn. rewrite Nat2Z.inj_sub by exact H.
  unfold Z.sub. rewrite inject_Z_plus, inject_Z_opp. reflexivity.
Qed.

Lemma qn_nonneg (n : nat) : 0 <= qn n.
Proof.
  unfold qn, Qle. simpl. lia.
Qed.

Lemma qn_pos (n : nat) : (0 < n)%nat -> 0 < qn n.
Proof.
  intro H. unfold qn, Qlt. simpl. lia.
Qed.

Lemma qn_le (a b : nat) : (a <= b)%nat -> qn a <= qn b.
Proof. intro H. unfold qn, Qle. simpl. lia. Qed.

Lemma qsum_app (a b : list Q) : qsum (a ++ b) == qsum a + qsum b.
Proof.
  induction a as [|x a IH]; simpl.
  - ring.
  - rewrite IH. ring.
Qed.

Lemma qsum_repeat (m : Q) (n : nat) : qsum (repeat m n) == qn n * m.
Proof.
  induction n as [|n IH]; simpl.
  - reflexivity.
  - rewrite IH, qn_S. ring.
Qed.

Lemma psum_0 (v : list Q) : psum 0 v == 0.
Proof. reflexivity. Qed.

Lemma psum_cons (k : nat) (a : Q) (v : list Q) :
  psum (S k) (a :: v) == a + psum k v.
Proof. reflexivity. Qed.

Lemma psum_all (v : list Q) : psum (length v) v == qsum v.
Proof. unfold psum. rewrite firstn_all. reflexivity. Qed.

Lemma psum_app_le (k : nat) (a b : list Q) :
  (k <= length a)%nat -> psum k (a ++ b) == psum k a.
Proof.
  intro H. unfold psum. rewrite firstn_app.
  replace (k - length a)%nat with 0%nat by lia. simpl.
  rewrite app_nil_r. reflexivity.
Qed.

Lemma psum_app_ge (k : nat) (a b : list Q) :
  (length a <= k)%nat -> psum k (a ++ b) == qsum a + psum (k - length a) b.
Proof.
  intro H. unfold psum. rewrite firstn_app, qsum_app.
  rewrite firstn_all2 by exact H. reflexivity.
Qed.

Lemma psum_repeat (k n : nat) (m : Q) :
  (k <= n)%nat -> psum k (repeat m n) == qn k * m.
Proof.
  revert n. induction k as [|k IH]; intros n H.
  - reflexivity.
  - destruct n as [|n]; [lia|]. simpl repeat.
    rewrite psum_cons, IH by lia. rewrite qn_S. ring.
Qed.

(** Multiplying by a positive rational reflects [<=]. *)
Lemma Qmult_pos_le_reg (a x : Q) : 0 < a -> 0 <= a * x -> 0 <= x.
Proof.
  intros Ha H. apply Qnot_lt_le. intro Hx.
  assert (a * x < 0).
  { setoid_replace 0 with (a * 0) by ring.
    apply Qmult_lt_l; assumption. }
  apply (Qlt_not_le _ _ H0 H).
Qed.

(** A sum of squares. *)
Fixpoint sqnorm (v : list Q) : Q :=
  match v with
  | [] => 0
  | a :: v' => a * a + sqnorm v'
  end.

(** The entrywise difference of two lists (of equal length). *)
Fixpoint vsub (a b : list Q) : list Q :=
  match a, b with
  | x :: a', y :: b' => (x - y) :: vsub a' b'
  | _, _ => []
  end.

(** The scalar product [<a, b> = Σ a_i b_i]. *)
Fixpoint dot (a b : list Q) : Q :=
  match a, b with
  | x :: a', y :: b' => x * y + dot a' b'
  | _, _ => 0
  end.

Lemma Qsq_nonneg (a : Q) : 0 <= a * a.
Proof. nra. Qed.

Lemma sqnorm_nonneg (v : list Q) : 0 <= sqnorm v.
Proof.
  induction v as [|a v IH]; simpl.
  - apply Qle_refl.
  - pose proof (Qsq_nonneg a). lra.
Qed.

(** Entrywise equality of two lists of rationals (up to [Qeq]). *)
Definition qeq_list (a b : list Q) : Prop := Forall2 Qeq a b.

(** ** Lists equal entrywise *)

Lemma qeq_list_refl (a : list Q) : qeq_list a a.
Proof. induction a; constructor; [reflexivity|assumption]. Qed.

Lemma qeq_list_sym (a b : list Q) : qeq_list a b -> qeq_list b a.
Proof. induction 1; constructor; [symmetry|]; assumption. Qed.

Lemma qeq_list_trans (a b c : list Q) : qeq_list a b -> qeq_list b c -> qeq_list a c.
Proof.
  intro H. revert c. induction H as [|x y a b Hxy _ IH]; intros c Hc; inversion Hc; subst;
    constructor; [rewrite Hxy; assumption|apply IH; assumption].
Qed.

Lemma qeq_list_length (a b : list Q) : qeq_list a b -> length a = length b.
Proof. induction 1; simpl; congruence. Qed.

Lemma qeq_list_psum (a b : list Q) : qeq_list a b -> forall k, psum k a == psum k b.
Proof.
  induction 1; intros [|k]; unfold psum; simpl; try reflexivity.
  fold (psum k l). fold (psum k l'). rewrite H, IHForall2. reflexivity.
Qed.

Lemma qeq_list_nth (a b : list Q) : qeq_list a b -> forall i, nth i a 0 == nth i b 0.
Proof.
  induction 1 as [|x y a b Hxy Hab IH]; intros [|i]; simpl; try reflexivity.
  - exact Hxy.
  - apply IH.
Qed.

Lemma qeq_list_repeat (a b : Q) (n : nat) : a == b -> qeq_list (repeat a n) (repeat b n).
Proof. intro E. induction n; simpl; constructor; assumption. Qed.

Lemma vsub_length (a b : list Q) : length a = length b -> length (vsub a b) = length a.
Proof.
  revert b. induction a as [|x a IH]; intros [|y b] L; simpl in *; try discriminate; auto.
Qed.

(** Entry [k] of [a − b]. *)
Lemma nth_vsub (a b : list Q) (k : nat) :
  length a = length b -> (k < length a)%nat -> nth k (vsub a b) 0 = nth k a 0 - nth k b 0.
Proof.
  revert b k. induction a as [|x a IH]; intros [|y b] k L Hk; simpl in *; try lia.
  destruct k; [reflexivity|]. apply IH; lia.
Qed.
