(** * The oracle's state is the event-driven dynamics' state.

    For [t > 0] the positions and the velocities that the extracted PAVA
    prints ([Oracle.state_at]) are, entry by entry, those of the sticky
    dynamics defined event by event ([Dynamics.dynamics]): the positions
    because both are [P_K(x⁰ + t u⁰)]; the velocities because both are the
    right derivative — the dynamics moves rigidly just after [t]
    ([Semigroup.semigroup], with [u(t) ∈ H_{x(t)}] from
    [VelocityProjection.velocity_in_H]), and the oracle's velocities are the
    right derivative of [P_K(x⁰ + t u⁰)] ([state_velocities_spec]). *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection Oracle RightDerivative.
From Sticky Require Import Dynamics ClusterAlgebra DynamicsInvariant DynamicsProjection
  Multipliers Contacts VelocityProjection Semigroup DynamicsIsProjK.
Import ListNotations.
Open Scope Q_scope.

Lemma free_flight_same (t : Q) (x u : list Q) :
  Dynamics.free_flight x u t = Oracle.free_flight t x u.
Proof.
  revert u. induction x as [|a x IH]; intros [|b u]; simpl; try reflexivity.
  unfold Dynamics.free_flight in *. simpl. f_equal. apply IH.
Qed.

Lemma eventually_impl_pos (P R : Q -> Prop) :
  (forall h, 0 < h -> P h -> R h) -> Eventually P -> Eventually R.
Proof. intros I (d & D & H). exists d. split; [exact D|]. intros h Hh Hd. auto. Qed.

Lemma kkt_self (z : list Q) : Monotone z -> Kkt z z.
Proof.
  intro M. split; [reflexivity|split; [exact M|split; [|split]]].
  - intros k _. lra.
  - reflexivity.
  - intros k _ _. reflexivity.
Qed.

Lemma affine_length (h : Q) (Y : list Q) : forall V,
  length V = length Y -> length (affine h Y V) = length Y.
Proof.
  induction Y as [|a Y IH]; intros [|b V] L; simpl in *; try discriminate; [reflexivity|].
  f_equal. apply IH. lia.
Qed.

Lemma nth_affine (h : Q) (Y : list Q) : forall V i,
  length V = length Y -> (i < length Y)%nat ->
  nth i (affine h Y V) 0 = nth i Y 0 + h * nth i V 0.
Proof.
  induction Y as [|a Y IH]; intros [|b V] i L Hi; simpl in *; try discriminate; try lia.
  destruct i as [|i]; [reflexivity|]. apply IH; lia.
Qed.

Lemma affine_h_qeq (h h' : Q) (Y V : list Q) :
  h == h' -> qeq_list (affine h Y V) (affine h' Y V).
Proof.
  intro E. revert V. induction Y as [|a Y IH]; intros [|b V]; simpl; constructor.
  - rewrite E. reflexivity.
  - apply IH.
Qed.

Lemma affine_cancel (h : Q) (Y : list Q) : forall Y' V V',
  0 < h -> length V = length Y -> length V' = length Y' ->
  qeq_list Y Y' -> qeq_list (affine h Y V) (affine h Y' V') -> qeq_list V V'.
Proof.
  induction Y as [|a Y IH]; intros Y' V V' Hh L L' E A; inversion E as [|a' b' Y1 Y1' Ea E']; subst.
  - destruct V; [|discriminate]. destruct V'; [constructor|discriminate].
  - destruct V as [|v V]; [discriminate|]. destruct V' as [|v' V']; [discriminate|].
    simpl in A. inversion A as [|c c' l l' Ec A']; subst. constructor.
    + assert (h * (v - v') == 0) by (rewrite Ea in Ec; ring_simplify; lra).
      destruct (Qmult_integral _ _ H) as [H0|H0]; [rewrite H0 in Hh; discriminate|lra].
    + apply (IH Y1' V V'); try (simpl in *; lia); assumption.
Qed.

(** For [t > 0] the dynamics moves rigidly just after [t]:
    [x(t + h) = x(t) + h u(t)] for all small [h > 0]. *)
Lemma dynamics_rigid_after (x0 u0 : list Q) (r t : Q) :
  0 < t -> InK r x0 -> length u0 = length x0 ->
  Eventually (fun h => qeq_list (positions (dynamics x0 u0 r (t + h)))
                                (affine h (positions (dynamics x0 u0 r t))
                                          (velocities (dynamics x0 u0 r t)))).
Proof.
  intros Ht HK L.
  set (ys := translated_positions t (clusters x0 u0 r t)).
  set (us := velocities (dynamics x0 u0 r t)).
  destruct (clusters_facts x0 u0 r t ltac:(lra) HK L) as (_ & _ & Hl).
  assert (Ly : length ys = length x0).
  { unfold ys, translated_positions. fold (spread (center t) (clusters x0 u0 r t)).
    rewrite spread_length. exact Hl. }
  assert (Lu : length us = length x0).
  { unfold us. rewrite velocities_spread, spread_length. exact Hl. }
  assert (My : Monotone ys) by apply (dynamics_is_projection x0 u0 r t ltac:(lra) HK).
  pose proof (velocity_in_H x0 u0 r t Ht HK L) as HH. fold us in HH.
  assert (Ep : positions (dynamics x0 u0 r t) = untranslate r ys) by reflexivity.
  rewrite Ep in HH.
  assert (Hlex : forall j, (j <= length x0)%nat ->
            Eventually (fun h => (S j < length x0)%nat ->
              0 <= (nth (S j) ys 0 - nth j ys 0) + h * (nth (S j) us 0 - nth j us 0))).
  { intros j _. destruct (Nat.lt_ge_cases (S j) (length x0)) as [Hj|Hj].
    - apply (eventually_impl (fun h => 0 <= (nth (S j) ys 0 - nth j ys 0)
                                         + h * (nth (S j) us 0 - nth j us 0))).
      { intros h H _. exact H. }
      apply eventually_lexnn.
      pose proof (My j ltac:(lia)) as Mj.
      destruct (Qle_lt_or_eq _ _ Mj) as [Lt|Eq]; [left; lra|right; split; [lra|]].
      assert (C : Contact r (untranslate r ys) j).
      { unfold Contact, untranslate. rewrite !nth_untranslate_from by lia.
        simpl. rewrite qn_S. rewrite <- Eq. ring. }
      specialize (HH j ltac:(unfold untranslate; rewrite untranslate_from_length; lia) C).
      lra.
    - apply (eventually_impl (fun _ => True)); [intros h _ H; lia|apply eventually_true]. }
  apply eventually_upto in Hlex.
  revert Hlex. apply eventually_impl_pos. intros h Hh Hm.
  assert (Hmono : Monotone (affine h ys us)).
  { intros i Hi. rewrite affine_length in Hi by lia.
    rewrite !nth_affine by lia. specialize (Hm i ltac:(lia) ltac:(lia)). lra. }
  pose proof (semigroup x0 u0 r t (t + h) ltac:(lra) ltac:(lra) HK) as Hs.
  cbv zeta in Hs. fold ys in Hs. fold us in Hs.
  change (map (fun p => fst p + (t + h - t) * snd p) (combine ys us))
    with (at_h (t + h - t) (combine ys us)) in Hs.
  rewrite at_h_combine in Hs by lia.
  apply (kkt_qeq _ (affine h ys us)) in Hs; [|apply affine_h_qeq; ring].
  pose proof (kkt_unique _ _ _ Hs (kkt_self _ Hmono)) as E.
  rewrite Ep. change (positions (dynamics x0 u0 r (t + h)))
    with (untranslate r (translated_positions (t + h) (clusters x0 u0 r (t + h)))).
  unfold untranslate. eapply qeq_list_trans; [apply untranslate_from_qeq, E|].
  apply untranslate_affine.
Qed.

Lemma expand_u_length (bs : list block) :
  length (flat_map expand_u bs) = length (flat_map expand bs).
Proof.
  induction bs as [|b bs IH]; simpl; [reflexivity|].
  rewrite !app_length, IH. unfold expand, expand_u. rewrite !repeat_length. reflexivity.
Qed.

(** The oracle's positions are the dynamics' ([prop:proj-micro]; ledger:
    [prop:proj-micro]), for every [N], [x⁰ ∈ K^N], any [u⁰], [t ≥ 0]. *)
Theorem oracle_positions_are_dynamics (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  qeq_list (st_positions (state_at r t x0 u0)) (positions (dynamics x0 u0 r t)).
Proof.
  intros Ht HK L. eapply qeq_list_trans; [apply state_positions_spec, L|].
  apply qeq_list_sym. rewrite <- free_flight_same. apply dynamics_is_proj_K; assumption.
Qed.

(** The oracle's velocities are the dynamics' ([prop:proj-micro]: "the
    velocity is the right derivative"; ledger: [prop:proj-micro]), for every
    [N], [x⁰ ∈ K^N], any [u⁰], [t > 0]. So the multipliers and clusters the
    oracle computes from them are the dynamics' too. *)
Theorem oracle_velocities_are_dynamics (x0 u0 : list Q) (r t : Q) :
  0 < t -> InK r x0 -> length u0 = length x0 ->
  qeq_list (st_velocities (state_at r t x0 u0)) (velocities (dynamics x0 u0 r t)).
Proof.
  intros Ht HK L.
  destruct (eventually_and _ _ (dynamics_rigid_after x0 u0 r t Ht HK L)
              (state_velocities_spec r t x0 u0 L)) as (h & Hh & H).
  destruct (H h Hh (Qle_refl h)) as [Hd Ho].
  pose proof (dynamics_is_proj_K x0 u0 r (t + h) ltac:(lra) HK L) as Hp.
  rewrite free_flight_same in Hp.
  pose proof (oracle_positions_are_dynamics x0 u0 r t ltac:(lra) HK L) as Ep.
  destruct (clusters_facts x0 u0 r t ltac:(lra) HK L) as (_ & _ & Hl).
  assert (Lu : length (velocities (dynamics x0 u0 r t)) = length x0).
  { rewrite velocities_spread, spread_length. exact Hl. }
  assert (Lx : length (positions (dynamics x0 u0 r t)) = length x0).
  { rewrite positions_spread. unfold untranslate.
    rewrite untranslate_from_length, spread_length. exact Hl. }
  assert (Lso : length (st_positions (state_at r t x0 u0)) = length x0).
  { rewrite (qeq_list_length _ _ Ep). exact Lx. }
  assert (Lsv : length (st_velocities (state_at r t x0 u0)) = length x0).
  { unfold state_at. cbn [st_velocities]. rewrite map_length, expand_u_length.
    set (y := shifted_free 0 (2 * r) t x0 u0).
    assert (Ly : length u0 = length y) by (unfold y; rewrite shifted_free_length; lia).
    change (length (pava_lex y u0) = length x0).
    rewrite (proj1 (pava_lex_kkt y u0 Ly)). unfold y. apply shifted_free_length. exact L. }
  apply qeq_list_sym.
  apply (affine_cancel h (positions (dynamics x0 u0 r t)) (st_positions (state_at r t x0 u0)));
    [exact Hh|lia|lia|apply qeq_list_sym, Ep|].
  eapply qeq_list_trans; [apply qeq_list_sym, Hd|].
  eapply qeq_list_trans; [exact Hp|exact Ho].
Qed.
