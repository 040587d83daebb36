(** * Averaging a list over consecutive segments.

    A list cut into segments, each replaced by its mean ([flat]): the
    partial sums of the averaged list stay below those of the list when
    every segment is pooled (prefix means at least the segment's mean), and
    averaging keeps a pooled list pooled (the partial sums of the average
    interpolate linearly between those of the list at the cuts). With
    pooled segments of non-decreasing means the averaged list is the
    projection onto the monotone cone (KKT form). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava.
Import ListNotations.
Open Scope Q_scope.

(** Blocks [(m, ℓ)]: the value [m] repeated [ℓ] times. *)
Definition flat (bs : list (Q * nat)) : list Q :=
  concat (map (fun b => repeat (fst b) (snd b)) bs).

(** The block [b] is the average of the segment [s]. *)
Definition Averages (s : list Q) (b : Q * nat) : Prop :=
  length s = snd b /\ qsum s == qn (snd b) * fst b.

Lemma flat_cons (b : Q * nat) (bs : list (Q * nat)) :
  flat (b :: bs) = repeat (fst b) (snd b) ++ flat bs.
Proof. reflexivity. Qed.

Lemma flat_length (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> length (flat bs) = length (concat segs).
Proof.
  induction 1 as [|s b segs bs (Hl & _) _ IH]; [reflexivity|].
  rewrite flat_cons. simpl. rewrite !app_length, repeat_length, IH, Hl. reflexivity.
Qed.

Lemma flat_qsum (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> qsum (flat bs) == qsum (concat segs).
Proof.
  induction 1 as [|s b segs bs (Hl & Hs) _ IH]; [reflexivity|].
  rewrite flat_cons. simpl. rewrite !qsum_app, qsum_repeat, IH, Hs. reflexivity.
Qed.

(** Inside a pooled segment the prefix sums stay above those of its mean. *)
Lemma pooled_mean_prefix (s : list Q) (m : Q) :
  s <> [] -> Pooled s -> qsum s == qn (length s) * m ->
  forall k, (k <= length s)%nat -> qn k * m <= psum k s.
Proof.
  intros Hn Hp Hs k Hk.
  assert (Hpos : 0 < qn (length s)) by (apply qn_pos; destruct s; [contradiction|simpl; lia]).
  assert (0 <= psum k s - qn k * m); [|lra].
  apply (Qmult_pos_le_reg (qn (length s))); [exact Hpos|].
  specialize (Hp k Hk). rewrite Hs in Hp.
  setoid_replace (qn (length s) * (psum k s - qn k * m))
    with (qn (length s) * psum k s - qn k * (qn (length s) * m)) by ring.
  lra.
Qed.

(** The partial sums of the averaged list are at most those of the list. *)
Lemma psum_flat_le (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> Forall (fun s => s <> []) segs -> Forall Pooled segs ->
  forall k, (k <= length (concat segs))%nat -> psum k (flat bs) <= psum k (concat segs).
Proof.
  induction 1 as [|s b segs bs (Hl & Hs) Hf IH]; intros HN HP k Hk.
  - simpl in Hk. replace k with 0%nat by lia. apply Qle_refl.
  - inversion HN; inversion HP; subst. rewrite flat_cons. simpl concat in Hk |- *.
    rewrite app_length in Hk.
    destruct (Nat.le_gt_cases k (length s)) as [Hle|Hgt].
    + rewrite !psum_app_le by (rewrite ?repeat_length; lia).
      rewrite psum_repeat by lia. apply pooled_mean_prefix; auto. rewrite Hl. exact Hs.
    + rewrite !psum_app_ge by (rewrite ?repeat_length; lia).
      rewrite repeat_length, qsum_repeat.
      specialize (IH ltac:(assumption) ltac:(assumption) (k - length s)%nat ltac:(lia)).
      rewrite Hl in IH |- *. lra.
Qed.

(** Averaging keeps a list pooled. [Above n S K B L]: every prefix of [L],
    after [K] entries of sum [B], keeps the mean [S/n] below its own. *)
Definition Above (n S K B : Q) (L : list Q) : Prop :=
  forall k, (k <= length L)%nat -> (K + qn k) * S <= n * (B + psum k L).

(** The linear interpolation of the prefix condition inside a segment:
    [ℓ·(n(B + k m) − (K + k)S) = (ℓ − k)(nB − KS) + k(n(B + ℓm) − (K + ℓ)S)]. *)
Lemma interpolate (n S K B m l k : Q) :
  0 < l -> 0 <= k -> k <= l ->
  K * S <= n * B -> (K + l) * S <= n * (B + l * m) ->
  (K + k) * S <= n * (B + k * m).
Proof.
  intros Hl Hk Hkl H0 H1.
  assert (0 <= n * (B + k * m) - (K + k) * S); [|lra].
  apply (Qmult_pos_le_reg l); [exact Hl|].
  setoid_replace (l * (n * (B + k * m) - (K + k) * S))
    with ((l - k) * (n * B - K * S) + k * (n * (B + l * m) - (K + l) * S)) by ring.
  assert (0 <= (l - k) * (n * B - K * S)) by (apply Qmult_le_0_compat; lra).
  assert (0 <= k * (n * (B + l * m) - (K + l) * S)) by (apply Qmult_le_0_compat; lra).
  lra.
Qed.

Lemma above_flat (n S : Q) (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> Forall (fun s => s <> []) segs ->
  forall K B, Above n S K B (concat segs) -> Above n S K B (flat bs).
Proof.
  induction 1 as [|s b segs bs (Hl & Hs) Hf IH]; intros HN K B H; [exact H|].
  inversion HN as [|? ? Ns HN']; subst.
  assert (Hlpos : 0 < qn (length s)) by (apply qn_pos; destruct s; [contradiction|simpl; lia]).
  intros k Hk. rewrite flat_cons in Hk |- *. rewrite app_length, repeat_length in Hk.
  rewrite (flat_length _ _ Hf) in Hk.
  assert (H0 := H 0%nat ltac:(lia)). rewrite psum_0, qn_0 in H0.
  assert (H1 := H (length s) ltac:(simpl; rewrite app_length; lia)).
  simpl concat in H1. rewrite psum_app_le, psum_all in H1 by lia.
  destruct (Nat.le_gt_cases k (snd b)) as [Hle|Hgt].
  - rewrite psum_app_le by (rewrite repeat_length; lia). rewrite psum_repeat by lia.
    rewrite Hs, Hl in H1.
    apply (interpolate n S K B (fst b) (qn (snd b)) (qn k)).
    + rewrite <- Hl. exact Hlpos.
    + apply qn_nonneg.
    + apply qn_le. exact Hle.
    + lra.
    + exact H1.
  - rewrite psum_app_ge by (rewrite repeat_length; lia).
    rewrite repeat_length, qsum_repeat.
    assert (HA : Above n S (K + qn (length s)) (B + qsum s) (concat segs)).
    { intros j Hj. specialize (H (length s + j)%nat ltac:(simpl; rewrite app_length; lia)).
      simpl concat in H. rewrite psum_app_ge in H by lia.
      replace (length s + j - length s)%nat with j in H by lia.
      rewrite qn_add in H.
      setoid_replace (K + qn (length s) + qn j) with (K + (qn (length s) + qn j)) by ring.
      setoid_replace (B + qsum s + psum j (concat segs))
        with (B + (qsum s + psum j (concat segs))) by ring.
      exact H. }
    specialize (IH HN' _ _ HA (k - snd b)%nat ltac:(rewrite (flat_length _ _ Hf); lia)).
    replace k with (snd b + (k - snd b))%nat at 1 by lia. rewrite qn_add.
    rewrite Hs, <- Hl in IH. rewrite <- Hl.
    setoid_replace (K + (qn (length s) + qn (k - length s)))
      with (K + qn (length s) + qn (k - length s)) by ring.
    setoid_replace (B + (qn (length s) * fst b + psum (k - length s) (flat bs)))
      with (B + qn (length s) * fst b + psum (k - length s) (flat bs)) by ring.
    exact IH.
Qed.

(** Averaging a pooled list over segments gives a pooled list. *)
Lemma pooled_flat (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> Forall (fun s => s <> []) segs ->
  Pooled (concat segs) -> Pooled (flat bs).
Proof.
  intros Hf HN Hp k Hk.
  rewrite (flat_length _ _ Hf), (flat_qsum _ _ Hf) in *.
  assert (HA : Above (qn (length (concat segs))) (qsum (concat segs)) 0 0 (concat segs)).
  { intros j Hj. specialize (Hp j Hj). setoid_replace (0 + qn j) with (qn j) by ring.
    setoid_replace (0 + psum j (concat segs)) with (psum j (concat segs)) by ring. exact Hp. }
  specialize (above_flat _ _ _ _ Hf HN 0 0 HA k ltac:(rewrite (flat_length _ _ Hf); exact Hk)).
  intro H. setoid_replace (0 + qn k) with (qn k) in H by ring.
  setoid_replace (0 + psum k (flat bs)) with (psum k (flat bs)) in H by ring. exact H.
Qed.

(** ** The KKT conditions *)

(** The block values are non-decreasing. *)
Fixpoint MeansUp (bs : list (Q * nat)) : Prop :=
  match bs with
  | b1 :: ((b2 :: _) as rest) => fst b1 <= fst b2 /\ MeansUp rest
  | _ => True
  end.

Lemma flat_kkt_from (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> Forall (fun s => s <> []) segs -> Forall Pooled segs ->
  MeansUp bs ->
  forall yp, (match bs with b :: _ => yp <= fst b | [] => True end) ->
  kkt_from 0 yp (concat segs) (flat bs).
Proof.
  induction 1 as [|s b segs bs (Hl & Hs) Hf IH]; intros HN HP HM yp Hyp; [reflexivity|].
  inversion HN as [|? ? Ns HN']; inversion HP as [|? ? Ps HP']; subst.
  rewrite flat_cons. simpl concat.
  assert (Hrest : kkt_from 0 (fst b) (concat segs) (flat bs)).
  { apply IH; auto.
    - destruct bs as [|b2 bs]; [exact I|apply HM].
    - destruct bs as [|b2 bs]; [exact I|apply HM]. }
  pose proof (pooled_mean_prefix s (fst b) Ns Ps ltac:(rewrite Hl; exact Hs)) as Hpre.
  rewrite <- Hl. destruct s as [|a s]; [contradiction|].
  simpl. split; [apply Qle_refl|split; [exact Hyp|split; [intros _; reflexivity|]]].
  apply block_inner; [|simpl length in Hl; rewrite <- Hl in Hs; rewrite qn_S in Hs; simpl in Hs; lra|exact Hrest].
  intros k Hk. specialize (Hpre (S k) ltac:(simpl; lia)).
  rewrite psum_cons, qn_S in Hpre. lra.
Qed.

(** Pooled segments with non-decreasing means: their averaged list is the
    projection of the list onto the monotone cone (KKT conditions). *)
Theorem flat_kkt (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> Forall (fun s => s <> []) segs -> Forall Pooled segs ->
  MeansUp bs -> Kkt (concat segs) (flat bs).
Proof.
  intros Hf HN HP HM. apply kkt_rec_iff.
  pose proof (flat_kkt_from segs bs Hf HN HP HM) as H.
  destruct bs as [|b bs'].
  - inversion Hf; subst. reflexivity.
  - inversion Hf as [|s b' segs' bs'' (Hl & _) _]; subst. inversion HN as [|? ? Ns _]; subst.
    specialize (H (fst b) (Qle_refl _)).
    destruct (snd b) as [|l] eqn:Eb; [destruct s; [contradiction|discriminate]|].
    rewrite flat_cons, Eb in *. exact H.
Qed.
