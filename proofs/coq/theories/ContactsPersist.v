(** * Contacts present at [s > 0] persist (corrected
      [df:H-micro#contacts-grow]).

    The ledger's corrected statement: "Ω_{x(s)} ⊂ Ω_{x(t)} for 0 < s ≤ t"
    (the printed one, from [s = 0], is refuted in [Contacts.v]). *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Dynamics ClusterAlgebra DynamicsInvariant
  DynamicsProjection Multipliers Neighbours Contacts VelocityProjection TwoTimes Segments
  Pressure Semigroup.
Import ListNotations.
Open Scope Q_scope.

(** The last entry of a pooled segment is at most its mean, the first at
    least. *)
Lemma pooled_last (s : list Q) (m : Q) :
  s <> [] -> Pooled s -> qsum s == qn (length s) * m ->
  nth (length s - 1) s 0 <= m.
Proof.
  intros Hn Hp Hs.
  assert (En : exists l, length s = S l) by (destruct s; [contradiction|eexists; reflexivity]).
  destruct En as [l E]. rewrite E. replace (S l - 1)%nat with l by lia.
  specialize (Hp l ltac:(lia)). rewrite E in Hp, Hs.
  pose proof (psum_succ s l ltac:(lia)) as P. rewrite <- E, psum_all in P.
  rewrite qn_S in Hp, Hs. pose proof (qn_nonneg l) as Hl.
  set (L := qn l) in *. set (A := qsum s) in *. set (last := nth l s 0) in *.
  assert (H : (L + 1) * (last - m) <= 0).
  { setoid_replace ((L + 1) * (last - m)) with (L * last + last - (L + 1) * m) by ring.
    rewrite <- Hs.
    setoid_replace ((L + 1) * psum l s) with ((L + 1) * (A - last)) in Hp by (rewrite P; ring).
    lra. }
  apply Qnot_lt_le. intro Hlt.
  assert (0 < (L + 1) * (last - m)) by (apply Qmult_lt_0_compat; lra). lra.
Qed.

Lemma pooled_first (s : list Q) (m : Q) :
  s <> [] -> Pooled s -> qsum s == qn (length s) * m -> m <= nth 0 s 0.
Proof.
  intros Hn Hp Hs. destruct s as [|a s]; [contradiction|].
  specialize (Hp 1%nat ltac:(simpl; lia)). rewrite Hs in Hp.
  unfold psum in Hp. simpl in Hp |- *.
  pose proof (qn_pos (S (length s)) ltac:(lia)) as Hpos.
  setoid_replace (qn 1) with 1 in Hp by reflexivity.
  apply Qnot_lt_le. intro Hlt.
  assert (qn (S (length s)) * (a + 0) < qn (S (length s)) * m) by (apply Qmult_lt_l; lra).
  lra.
Qed.

(** Across a cut between two segments, the list is below its average on
    the left and above it on the right. *)
Lemma flat_cut (segs : list (list Q)) (bs : list (Q * nat)) :
  Forall2 Averages segs bs -> Forall (fun s => s <> []) segs -> Forall Pooled segs ->
  forall i, (0 < i < length (concat segs))%nat ->
  nth (i - 1) (flat bs) 0 == nth i (flat bs) 0 \/
  (nth (i - 1) (concat segs) 0 <= nth (i - 1) (flat bs) 0 /\
   nth i (flat bs) 0 <= nth i (concat segs) 0).
Proof.
  induction 1 as [|s b segs bs (Hl & Hs) Hf IH]; intros HN HP i Hi; simpl in Hi; [lia|].
  inversion HN as [|? ? Ns HN']; inversion HP as [|? ? Ps HP']; subst.
  rewrite app_length in Hi. rewrite flat_cons. simpl concat.
  destruct (Nat.lt_trichotomy i (length s)) as [Hlt|[Heq|Hgt]].
  - left. rewrite !app_nth1 by (rewrite repeat_length; lia).
    rewrite !nth_repeat_lt by lia. apply Qeq_refl.
  - right. destruct Hf as [|s2 b2 segs' bs' (Hl2 & Hs2) Hf'];
      [simpl in Hi; lia|].
    inversion HN' as [|? ? Ns2 _]; inversion HP' as [|? ? Ps2 _]; subst.
    split.
    + rewrite !app_nth1 by (rewrite ?repeat_length; lia).
      rewrite nth_repeat_lt by lia. apply pooled_last; auto. rewrite Hl. exact Hs.
    + rewrite !app_nth2 by (rewrite ?repeat_length; lia).
      rewrite repeat_length, <- Hl, Nat.sub_diag. rewrite flat_cons. simpl concat.
      destruct s2 as [|a s2]; [contradiction|].
      destruct (snd b2) as [|l2] eqn:E2; [simpl in Hl2; lia|]. simpl.
      apply (pooled_first (a :: s2)); auto. rewrite Hl2. exact Hs2.
  - destruct (IH HN' HP' (i - length s)%nat ltac:(lia)) as [H|[H1 H2]].
    + left. rewrite !app_nth2 by (rewrite repeat_length; lia). rewrite repeat_length, <- Hl.
      replace (i - 1 - length s)%nat with (i - length s - 1)%nat by lia. exact H.
    + right. rewrite !app_nth2 by (rewrite ?repeat_length; lia). rewrite repeat_length, <- Hl.
      replace (i - 1 - length s)%nat with (i - length s - 1)%nat by lia. split; assumption.
Qed.

Lemma nth_spread_moved (s t : Q) (cs : list cluster) (j : nat) :
  (j < length (concat cs))%nat ->
  nth j (spread (moved s t) cs) 0 ==
  nth j (spread (center s) cs) 0 + (t - s) * nth j (spread velocity cs) 0.
Proof.
  revert j. induction cs as [|c cs IH]; intros j Hj; simpl in Hj; [lia|].
  rewrite app_length in Hj. unfold spread. simpl. fold (spread (moved s t) cs).
  fold (spread (center s) cs). fold (spread velocity cs).
  destruct (Nat.lt_ge_cases j (length c)) as [Hlt|Hge].
  - rewrite !app_nth1 by (rewrite repeat_length; lia). rewrite !nth_repeat_lt by lia.
    reflexivity.
  - rewrite !app_nth2 by (rewrite repeat_length; lia). rewrite !repeat_length.
    apply IH. lia.
Qed.

(** Corrected [df:H-micro#contacts-grow]: "Ω_{x(s)} ⊂ Ω_{x(t)} for
    0 < s ≤ t". For every [N], [x⁰ ∈ K^N], any [u⁰], rational
    [0 < s ≤ t]: a contact of [x(s)] is a contact of [x(t)].
    Ledger claim: [df:H-micro#contacts-grow] (its corrected statement). *)
Theorem contacts_persist (x0 u0 : list Q) (r s t : Q) (j : nat) :
  0 < s -> s <= t -> InK r x0 -> length u0 = length x0 -> (S j < length x0)%nat ->
  Contact r (positions (dynamics x0 u0 r s)) j ->
  Contact r (positions (dynamics x0 u0 r t)) j.
Proof.
  intros Hs Hst HK L Hj Hc.
  assert (Hs0 : 0 <= s) by lra. assert (Ht0 : 0 <= t) by lra.
  set (i := S j). assert (Hi : (0 < i < length x0)%nat) by (unfold i; lia).
  replace j with (i - 1)%nat in Hc |- * by (unfold i; lia).
  (* at s: one translated position, one velocity *)
  pose proof (contact_neighbours x0 u0 r s i Hs HK L Hi Hc) as Hu. cbv zeta in Hu.
  pose proof (position_gap x0 u0 r s i Hs0 HK L Hi) as Gs. cbv zeta in Gs.
  unfold Contact in Hc. replace (S (i - 1)) with i in Hc by lia.
  rewrite Gs in Hc.
  (* at t: the cut between the clusters at t *)
  pose proof (position_gap x0 u0 r t i Ht0 HK L Hi) as Gt. cbv zeta in Gt.
  unfold Contact. replace (S (i - 1)) with i by lia. rewrite Gt.
  destruct (clusters_facts x0 u0 r s Hs0 HK L) as (_ & _ & Hls).
  destruct (semigroup_segments x0 u0 r s t Hs0 Hst HK)
    as (segs & bs & HA & HNe & HP & _ & Ez & Ey).
  assert (Hlen : length (concat segs) = length x0).
  { rewrite Ez, spread_length. exact Hls. }
  pose proof (dynamics_is_projection x0 u0 r t Ht0 HK) as (_ & Hmono & _).
  unfold translated_positions in Hmono. fold (spread (center t) (clusters x0 u0 r t)) in Hmono.
  assert (Hlt : length (spread (center t) (clusters x0 u0 r t)) = length x0).
  { rewrite <- Ey, (flat_length _ _ HA). exact Hlen. }
  specialize (Hmono (i - 1)%nat ltac:(rewrite Hlt; lia)).
  replace (S (i - 1)) with i in Hmono by lia.
  destruct (flat_cut segs bs HA HNe HP i ltac:(lia)) as [H|[H1 H2]].
  - rewrite Ey in H. rewrite H. ring.
  - rewrite Ez, Ey in *.
    rewrite !nth_spread_moved in H1, H2 by lia.
    fold (spread velocity (clusters x0 u0 r s)) in Hu.
    assert (Hy : nth (i - 1) (spread (center s) (clusters x0 u0 r s)) 0 ==
                 nth i (spread (center s) (clusters x0 u0 r s)) 0) by lra.
    rewrite Hy, Hu in H1. lra.
Qed.
