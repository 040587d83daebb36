(** * The sticky dynamics over [R], event by event ([prop:proj-micro],
      existence).

    Paper, section "Sticky dynamics and reduction to first order":
    "whenever two particles collide they stick together and subsequently
    move with the same velocity"; [prop:proj-micro]: "there exists a
    unique solution x to (eq:micro-f0-lagr)". [Dynamics.v] computes that
    dynamics over [Q]; here it is built over [R], for real data and real
    times, as an existence proof: from any state satisfying [Inv], there
    is a path ([Evolves]) that solves [eq:micro-f0-lagr] off finitely many
    instants and is the projection [P_K(x⁰ + s u⁰)] at every later time
    [s].

    A state at time [t]: positions [z] and velocities [v] of the [N]
    particles, and which adjacent pairs are stuck ([L i] for the pair
    [(i, i+1)], 0-based). [Inv] asks
    - [z ∈ K^N]; a stuck pair touches ([z_{i+1} − z_i = 2r]) and has one
      velocity;
    - the impulses [λ_j = Σ_{i<j} (x⁰_i + t u⁰_i − z_i)] are [≥ 0], vanish
      at [j = N] and at every free pair: [x⁰ + t u⁰ − z ∈ N_z K^N], so [z]
      is [P_K(x⁰ + t u⁰)] ([lem:proj-characterization]);
    - the forces [μ_j = Σ_{i<j} (u⁰_i − v_i)] are [≥ 0], vanish at [j = N]
      and at every free pair: [u⁰ − v ∈ N_z K^N] ([eq:dyn-micro], with
      [N λ] there our [μ]).
    Free flight [z + (s − t) v] keeps [Inv] until the first free pair
    closes ([inv_free_flight]); that pair then sticks and the two clusters
    it joins take their mean velocity ([merge_inv]: the forces stay
    [≥ 0] because the left cluster was the faster). Each merge removes a
    free pair, so the induction ([evolves]) ends.

    Over Coq's real numbers: decisions by [Rle_dec], [Rlt_dec] and
    [classic]; the theorems rest on the standard real-number axioms only
    ([check-assumptions.sh]). *)

From Coq Require Import Reals Lra Lia List Arith Classical Wf_nat.
From Coquelicot Require Import Coquelicot.
From Sticky Require Import Uniqueness NormalConeR.
Open Scope R_scope.

(** ** Sums over a range of indices *)

Lemma sumN_minus (n : nat) (f g : nat -> R) :
  sumN n (fun i => f i - g i) = sumN n f - sumN n g.
Proof. induction n as [|n IH]; simpl; [ring|rewrite IH; ring]. Qed.

(** A constant [c] on [[a, b)] adds [(b − a) c]. *)
Lemma sumN_const_range (f : nat -> R) (c : R) (a b : nat) :
  (a <= b)%nat -> (forall i, (a <= i < b)%nat -> f i = c) ->
  sumN b f = sumN a f + (INR b - INR a) * c.
Proof.
  induction b as [|b IH]; intros Hab Hc.
  - replace a with 0%nat by lia. simpl. ring.
  - destruct (Nat.eq_dec a (S b)) as [->|Hne]; [ring|].
    change (sumN (S b) f) with (sumN b f + f b).
    rewrite IH by (lia || (intros i Hi; apply Hc; lia)).
    rewrite Hc by lia. rewrite S_INR. ring.
Qed.

(** Two functions equal on [[a, b)] add the same over [[a, b)]. *)
Lemma sumN_eq_range (f g : nat -> R) (a b : nat) :
  (a <= b)%nat -> (forall i, (a <= i < b)%nat -> f i = g i) ->
  sumN b f - sumN a f = sumN b g - sumN a g.
Proof.
  induction b as [|b IH]; intros Hab Hc.
  - replace a with 0%nat by lia. ring.
  - destruct (Nat.eq_dec a (S b)) as [->|Hne]; [ring|].
    simpl. pose proof (IH ltac:(lia) (fun i Hi => Hc i ltac:(lia))).
    rewrite (Hc b) by lia. lra.
Qed.

(** A function whose consecutive values agree on [[a, b)] is constant there. *)
Lemma run_const (f : nat -> R) (a b : nat) :
  (forall i, (a <= i)%nat -> (S i < b)%nat -> f (S i) = f i) ->
  forall i, (a <= i < b)%nat -> f i = f a.
Proof.
  intros H i. induction i as [|i IH]; intro Hi.
  - replace a with 0%nat by lia. reflexivity.
  - destruct (Nat.eq_dec a (S i)) as [->|Hne]; [reflexivity|].
    rewrite H by lia. apply IH. lia.
Qed.

(** ** Finite choices *)

(** Among the indices [< n] satisfying [P], one minimises [θ] (or none
    satisfies [P]). *)
Lemma first_index (P : nat -> Prop) (θ : nat -> R) (n : nat) :
  (forall i, (i < n)%nat -> ~ P i) \/
  exists k, (k < n)%nat /\ P k /\ forall i, (i < n)%nat -> P i -> θ k <= θ i.
Proof.
  induction n as [|n IH]; [left; intros i Hi; lia|].
  destruct (classic (P n)) as [Pn|Pn].
  - right. destruct IH as [Hno|(k & Hk & Pk & Hmin)].
    + exists n. split; [lia|split; [exact Pn|]]. intros i Hi Pi.
      destruct (Nat.eq_dec i n) as [->|Hne]; [lra|]. exfalso. apply (Hno i); [lia|exact Pi].
    + destruct (Rle_dec (θ k) (θ n)) as [Hle|Hgt].
      * exists k. split; [lia|split; [exact Pk|]]. intros i Hi Pi.
        destruct (Nat.eq_dec i n) as [->|Hne]; [exact Hle|apply Hmin; [lia|exact Pi]].
      * exists n. split; [lia|split; [exact Pn|]]. intros i Hi Pi.
        destruct (Nat.eq_dec i n) as [->|Hne]; [lra|].
        pose proof (Hmin i ltac:(lia) Pi). lra.
  - destruct IH as [Hno|(k & Hk & Pk & Hmin)].
    + left. intros i Hi. destruct (Nat.eq_dec i n) as [->|Hne]; [exact Pn|apply Hno; lia].
    + right. exists k. split; [lia|split; [exact Pk|]]. intros i Hi Pi.
      destruct (Nat.eq_dec i n) as [->|Hne]; [contradiction|apply Hmin; [lia|exact Pi]].
Qed.

(** ** Stuck pairs *)

(** Stick the pair [(k, k+1)]. *)
Definition link (L : nat -> bool) (k : nat) : nat -> bool :=
  fun i => if Nat.eq_dec i k then true else L i.

(** The number of free pairs among the first [n] (the induction measure). *)
Fixpoint free_pairs (n : nat) (L : nat -> bool) : nat :=
  match n with
  | O => O
  | S n => (free_pairs n L + if L n then 0 else 1)%nat
  end.

Lemma free_pairs_ext (n : nat) (L L' : nat -> bool) :
  (forall i, (i < n)%nat -> L i = L' i) -> free_pairs n L = free_pairs n L'.
Proof.
  induction n as [|n IH]; intro H; [reflexivity|]. simpl.
  rewrite IH, H; [reflexivity|lia|intros i Hi; apply H; lia].
Qed.

Lemma free_pairs_link (n : nat) (L : nat -> bool) (k : nat) :
  (k < n)%nat -> L k = false -> S (free_pairs n (link L k)) = free_pairs n L.
Proof.
  induction n as [|n IH]; intros Hk HL; [lia|]. simpl.
  unfold link at 2. destruct (Nat.eq_dec n k) as [->|Hne].
  - rewrite HL. rewrite (free_pairs_ext k (link L k) L); [lia|].
    intros i Hi. unfold link. destruct (Nat.eq_dec i k); [lia|reflexivity].
  - rewrite <- IH by (lia || exact HL). lia.
Qed.

(** The cluster of particle [k] starts at [a]: the pairs [a … k − 1] are
    stuck, and [a] is particle 0 or the pair [(a − 1, a)] is free. *)
Lemma cluster_start (L : nat -> bool) (k : nat) :
  exists a, (a <= k)%nat /\ (a = O \/ L (pred a) = false) /\
            forall i, (a <= i < k)%nat -> L i = true.
Proof.
  induction k as [|k IH].
  - exists O. split; [lia|split; [left; reflexivity|intros; lia]].
  - destruct (L k) eqn:E.
    + destruct IH as (a & Ha & Hb & Hi). exists a. split; [lia|split; [exact Hb|]].
      intros i Hai. destruct (Nat.eq_dec i k) as [->|Hne]; [exact E|apply Hi; lia].
    + exists (S k). split; [lia|split; [right; exact E|intros; lia]].
Qed.

(** The cluster of particle [k < N] ends before [b]: the pairs [k … b − 2]
    are stuck, and [b = N] or the pair [(b − 1, b)] is free. *)
Lemma cluster_end (L : nat -> bool) (N : nat) :
  forall d k, (k + d = N)%nat -> (k < N)%nat ->
  exists b, (k < b <= N)%nat /\ (b = N \/ L (pred b) = false) /\
            forall i, (k <= i)%nat -> (S i < b)%nat -> L i = true.
Proof.
  induction d as [|d IH]; intros k Hd Hk; [lia|].
  destruct (Nat.eq_dec (S k) N) as [He|Hne].
  - exists N. split; [lia|split; [left; reflexivity|intros; lia]].
  - destruct (L k) eqn:E.
    + destruct (IH (S k) ltac:(lia) ltac:(lia)) as (b & Hb & Hf & Hi).
      exists b. split; [lia|split; [exact Hf|]].
      intros i Hki Hib. destruct (Nat.eq_dec i k) as [->|Hne']; [exact E|apply Hi; lia].
    + exists (S k). split; [lia|split; [right; exact E|intros; lia]].
Qed.

Section Dynamics.

Variables (N : nat) (r : R) (x0 u0 : nat -> R).

(** ** The invariant *)

(** Free flight [x⁰ + t u⁰], the point [prop:proj-micro] projects. *)
Definition flight (t : R) (i : nat) : R := x0 i + t * u0 i.

(** The impulses [λ_j] at time [t] of positions [z]. *)
Definition impulse (t : R) (z : nat -> R) (j : nat) : R := sumN j (fun i => flight t i - z i).

(** The forces [μ_j] of velocities [v]. *)
Definition force (v : nat -> R) (j : nat) : R := sumN j (fun i => u0 i - v i).

(** Index-form multipliers of a vector [w] for the stuck pairs [L]. *)
Definition Multipliers (L : nat -> bool) (w : nat -> R) : Prop :=
  (forall j, (j <= N)%nat -> 0 <= sumN j w) /\ sumN N w = 0 /\
  (forall i, (S i < N)%nat -> L i = false -> sumN (S i) w = 0).

Definition Inv (t : R) (z v : nat -> R) (L : nat -> bool) : Prop :=
  InKR N r z /\
  (forall i, (S i < N)%nat -> L i = true -> z (S i) - z i = 2 * r /\ v (S i) = v i) /\
  Multipliers L (fun i => flight t i - z i) /\
  Multipliers L (fun i => u0 i - v i).

(** Multipliers give the normal cone ([NormalConeR.normal_cone_of_multipliers]). *)
Lemma multipliers_normal_cone (L : nat -> bool) (z w : nat -> R) :
  (forall i, (S i < N)%nat -> L i = true -> z (S i) - z i = 2 * r) ->
  Multipliers L w -> InNormalConeR N r z w.
Proof.
  intros Hl (Hpos & HN & Hfree).
  apply (normal_cone_of_multipliers N r 1 z w (fun j => sumN j w)).
  - lra.
  - reflexivity.
  - exact HN.
  - exact Hpos.
  - intros j Hj. destruct j as [|i]; [lia|]. replace (S i - 1)%nat with i by lia.
    destruct (L i) eqn:E.
    + rewrite (Hl i ltac:(lia) E). ring.
    + rewrite (Hfree i ltac:(lia) E). ring.
  - intros i Hi. simpl. ring.
Qed.

(** Under [Inv], [x⁰ + t u⁰ − z ∈ N_z K^N] and [u⁰ − v ∈ N_z K^N]. *)
Lemma inv_normal_cones (t : R) (z v : nat -> R) (L : nat -> bool) :
  Inv t z v L ->
  InKR N r z /\ InNormalConeR N r z (fun i => flight t i - z i) /\
  InNormalConeR N r z (fun i => u0 i - v i).
Proof.
  intros (HK & Hl & Hλ & Hμ). split; [exact HK|split].
  - apply (multipliers_normal_cone L); [|exact Hλ]. intros i Hi E. apply Hl; assumption.
  - apply (multipliers_normal_cone L); [|exact Hμ]. intros i Hi E. apply Hl; assumption.
Qed.

(** Every particle alone, at time 0, from [x⁰ ∈ K^N]. *)
Lemma inv_start : InKR N r x0 -> Inv 0 x0 u0 (fun _ => false).
Proof.
  intro HK.
  assert (M : forall w : nat -> R, (forall i, w i = 0) -> Multipliers (fun _ => false) w).
  { intros w Hw. assert (Z : forall j, sumN j w = 0).
    { intro j. rewrite (sumN_ext j w (fun _ => 0)) by (intros; apply Hw).
      induction j as [|j IH]; simpl; [reflexivity|rewrite IH; ring]. }
    split; [intros j _; rewrite Z; lra|split; [apply Z|intros; apply Z]]. }
  split; [exact HK|split; [intros i _ E; discriminate|split; apply M]].
  - intro i. unfold flight. ring.
  - intro i. ring.
Qed.

(** ** Free flight *)

(** Each particle at its velocity from time [t]: [z + (s − t) v]. *)
Definition cluster_flight (t : R) (z v : nat -> R) (s : R) (i : nat) : R := z i + (s - t) * v i.

Lemma cluster_flight_derive (t : R) (z v : nat -> R) (i : nat) (s : R) :
  is_derive (fun s => cluster_flight t z v s i) s (v i).
Proof. unfold cluster_flight. auto_derive; [exact I|ring]. Qed.

(** Free flight keeps [K^N] while no free pair that closes has closed. *)
Lemma cluster_flight_in_K (t s : R) (z v : nat -> R) (L : nat -> bool) :
  Inv t z v L -> t <= s ->
  (forall i, (S i < N)%nat -> L i = false -> v (S i) < v i ->
     (s - t) * (v i - v (S i)) <= z (S i) - z i - 2 * r) ->
  InKR N r (cluster_flight t z v s).
Proof.
  intros (HK & Hl & _) Hs Hm i Hi. unfold cluster_flight.
  destruct (L i) eqn:E.
  - destruct (Hl i Hi E) as [A B]. rewrite B. lra.
  - pose proof (HK i Hi). destruct (Rlt_dec (v (S i)) (v i)) as [Hlt|Hge].
    + pose proof (Hm i Hi E Hlt). lra.
    + assert (0 <= (s - t) * (v (S i) - v i)) by (apply Rmult_le_pos; lra). lra.
Qed.

(** Free flight keeps the invariant while it stays in [K^N]: the
    impulses grow by [(s − t) μ]. *)
Lemma inv_free_flight (t s : R) (z v : nat -> R) (L : nat -> bool) :
  Inv t z v L -> t <= s -> InKR N r (cluster_flight t z v s) ->
  Inv s (cluster_flight t z v s) v L.
Proof.
  intros (HK & Hl & (Hλ0 & HλN & Hλf) & Hμ) Hs HK'.
  pose proof Hμ as (Hμ0 & HμN & Hμf).
  assert (E : forall j, sumN j (fun i => flight s i - cluster_flight t z v s i) =
                        sumN j (fun i => flight t i - z i) + (s - t) * sumN j (fun i => u0 i - v i)).
  { intro j. rewrite <- sumN_scal, <- sumN_plus. apply sumN_ext. intros i _.
    unfold flight, cluster_flight. ring. }
  split; [exact HK'|split; [|split; [split; [|split]|exact Hμ]]].
  - intros i Hi HL. destruct (Hl i Hi HL) as [A B]. unfold cluster_flight. rewrite B. lra.
  - intros j Hj. rewrite E. pose proof (Hλ0 j Hj). pose proof (Hμ0 j Hj).
    assert (0 <= (s - t) * sumN j (fun i => u0 i - v i)) by (apply Rmult_le_pos; lra). lra.
  - rewrite E, HλN, HμN. ring.
  - intros i Hi HL. rewrite E, (Hλf i Hi HL), (Hμf i Hi HL). ring.
Qed.

(** ** Merging a pair that meets *)

(** The velocities after the clusters [[a, b)] join: their mean initial
    velocity [m] there, unchanged elsewhere. *)
Definition merged (v : nat -> R) (a b : nat) (m : R) : nat -> R :=
  fun i => if andb (Nat.leb a i) (Nat.ltb i b) then m else v i.

(** The pair [(k, k+1)] touches at [t], its left particle is the faster:
    stick it; the two clusters [[a, k]] and [[k+1, b)] move on at their
    mean velocity, and the invariant holds with the pair stuck. *)
Lemma merge_inv (t : R) (z v : nat -> R) (L : nat -> bool) (k : nat) :
  Inv t z v L -> (S k < N)%nat -> L k = false -> v (S k) < v k ->
  z (S k) - z k = 2 * r ->
  exists v', Inv t z v' (link L k).
Proof.
  intros (HK & Hl & Hλ & (Hμ0 & HμN & Hμf)) Hk HLk Hv Hz.
  destruct (cluster_start L k) as (a & Hak & Ha & Hla).
  destruct (cluster_end L N (N - S k) (S k) ltac:(lia) Hk) as (b & Hkb & Hb & Hlb).
  set (U := fun j => sumN j u0). set (W := fun j => sumN j v).
  assert (Hμ : forall j, sumN j (fun i => u0 i - v i) = U j - W j) by (intro; apply sumN_minus).
  (* The two clusters move at one velocity each. *)
  assert (Va : forall i, (a <= i < S k)%nat -> v i = v a).
  { apply run_const. intros i Hai Hik. apply Hl; [lia|]. apply Hla. lia. }
  assert (Vb : forall i, (S k <= i < b)%nat -> v i = v (S k)).
  { apply run_const. intros i Hki Hib. apply Hl; [lia|]. apply Hlb; lia. }
  assert (Wa : forall j, (a <= j <= S k)%nat -> W j = W a + (INR j - INR a) * v a).
  { intros j Hj. apply sumN_const_range; [lia|]. intros i Hi. apply Va. lia. }
  assert (Wb : forall j, (S k <= j <= b)%nat -> W j = W (S k) + (INR j - INR (S k)) * v (S k)).
  { intros j Hj. apply sumN_const_range; [lia|]. intros i Hi. apply Vb. lia. }
  (* The forces vanish at the clusters' ends. *)
  assert (Fa : U a - W a = 0).
  { rewrite <- Hμ. destruct Ha as [->|Ha]; [reflexivity|].
    destruct a as [|a']; [reflexivity|]. apply Hμf; [lia|exact Ha]. }
  assert (Fk : U (S k) - W (S k) = 0) by (rewrite <- Hμ; apply Hμf; assumption).
  assert (Fb : U b - W b = 0).
  { rewrite <- Hμ. destruct (Nat.eq_dec b N) as [->|HbN]; [exact HμN|].
    destruct Hb as [Hb|Hb]; [lia|].
    destruct b as [|b']; [lia|]. apply Hμf; [lia|exact Hb]. }
  assert (Hvk : v k = v a) by (apply Va; lia).
  set (A := INR (S k) - INR a). set (B := INR b - INR (S k)).
  assert (HA : 0 < A) by (unfold A; apply Rlt_Rminus, lt_INR; lia).
  assert (HB : 0 < B) by (unfold B; apply Rlt_Rminus, lt_INR; lia).
  set (m := (U b - U a) / (INR b - INR a)).
  assert (Hm : (A + B) * m = A * v a + B * v (S k)).
  { assert (HU : U b - U a = A * v a + B * v (S k)).
    { pose proof (Wb b ltac:(lia)). pose proof (Wa (S k) ltac:(lia)). unfold A, B. lra. }
    assert (HAB : A + B = INR b - INR a) by (unfold A, B; ring).
    unfold m. rewrite <- HAB, <- HU. field. lra. }
  set (v' := merged v a b m).
  set (W' := fun j => sumN j v').
  assert (W'lo : forall j, (j <= a)%nat -> W' j = W j).
  { intros j Hj. apply sumN_ext. intros i Hi. unfold v', merged.
    destruct (Nat.leb_spec a i); [lia|reflexivity]. }
  assert (W'mid : forall j, (a <= j <= b)%nat -> W' j = W a + (INR j - INR a) * m).
  { intros j Hj. rewrite <- (W'lo a) by lia. apply sumN_const_range; [lia|].
    intros i Hi. unfold v', merged.
    destruct (Nat.leb_spec a i), (Nat.ltb_spec i b); [reflexivity|lia..]. }
  assert (W'hi : forall j, (b <= j)%nat -> W' j = W j).
  { intros j Hj.
    assert (Hb' : W' b = W b).
    { rewrite W'mid by lia. rewrite (Wb b ltac:(lia)), (Wa (S k) ltac:(lia)).
      unfold A, B in Hm. lra. }
    pose proof (sumN_eq_range v' v b j Hj) as D.
    lapply D; [intro D'; unfold W, W' in *; lra|].
    intros i Hi. unfold v', merged. destruct (Nat.ltb_spec i b); [lia|].
    rewrite Bool.andb_false_r. reflexivity. }
  exists v'.
  split; [exact HK|split; [|split; [|split; [|split]]]].
  - (* Stuck pairs touch and share a velocity. *)
    intros i Hi HL. unfold link in HL. destruct (Nat.eq_dec i k) as [->|Hne].
    + split; [exact Hz|]. unfold v', merged.
      destruct (Nat.leb_spec a k), (Nat.ltb_spec k b), (Nat.leb_spec a (S k)), (Nat.ltb_spec (S k) b);
        simpl; lia || reflexivity.
    + destruct (Hl i Hi HL) as [Hzi Hvi]. split; [exact Hzi|]. unfold v', merged.
      destruct (Nat.leb_spec a i), (Nat.ltb_spec i b), (Nat.leb_spec a (S i)), (Nat.ltb_spec (S i) b);
        simpl; try reflexivity; try lia; try exact Hvi.
      * (* [S i = b]: the pair [(b − 1, b)] would be stuck. *)
        destruct Hb as [Hb|Hb]; [lia|]. replace (pred b) with i in Hb by lia. congruence.
      * (* [S i = a]: the pair [(a − 1, a)] would be stuck. *)
        destruct Ha as [Ha|Ha]; [lia|]. replace (pred a) with i in Ha by lia. congruence.
  - (* The impulses do not change; a pair free after the merge was free before. *)
    destruct Hλ as (H1 & H2 & H3). split; [exact H1|split; [exact H2|]].
    intros i Hi HL. unfold link in HL. destruct (Nat.eq_dec i k); [discriminate|]. apply H3; assumption.
  - (* The forces stay nonnegative: the left cluster was the faster. *)
    intros j Hj. rewrite sumN_minus. fold (U j). fold (W' j).
    pose proof (Hμ0 j Hj) as P. rewrite Hμ in P.
    destruct (Nat.le_gt_cases j a) as [Hja|Hja]; [rewrite W'lo by lia; lra|].
    destruct (Nat.le_gt_cases b j) as [Hjb|Hjb]; [rewrite W'hi by lia; lra|].
    rewrite W'mid by lia.
    destruct (Nat.le_gt_cases j (S k)) as [Hjk|Hjk].
    + rewrite (Wa j ltac:(lia)) in P.
      assert (HJ : 0 <= INR j - INR a) by (assert (INR a <= INR j) by (apply le_INR; lia); lra).
      assert (Hma : m <= v a).
      { apply (Rmult_le_reg_l (A + B)); [lra|]. rewrite Hm. rewrite Hvk in Hv. nra. }
      assert (0 <= (INR j - INR a) * (v a - m)) by (apply Rmult_le_pos; lra). nra.
    + rewrite (Wb j ltac:(lia)), (Wa (S k) ltac:(lia)) in P.
      set (J := INR j - INR (S k)).
      assert (HJ : 0 <= J <= B).
      { unfold J, B. assert (INR (S k) <= INR j) by (apply le_INR; lia).
        assert (INR j <= INR b) by (apply le_INR; lia). lra. }
      assert (Hd : (A + B) * (A * v a + J * v (S k) - (A + J) * m) = A * (B - J) * (v a - v (S k))).
      { replace ((A + B) * (A * v a + J * v (S k) - (A + J) * m))
          with ((A + B) * (A * v a + J * v (S k)) - (A + J) * ((A + B) * m)) by ring.
        rewrite Hm. ring. }
      assert (0 <= A * (B - J) * (v a - v (S k))).
      { rewrite Hvk in Hv. apply Rmult_le_pos; [apply Rmult_le_pos|]; lra. }
      assert (0 <= A * v a + J * v (S k) - (A + J) * m).
      { apply (Rmult_le_reg_l (A + B)); [lra|]. rewrite Rmult_0_r, Hd. exact H. }
      replace (INR j - INR a) with (A + J) by (unfold A, J; ring). unfold A, J in *. lra.
  - rewrite sumN_minus. fold (U N). fold (W' N). rewrite W'hi by lia.
    rewrite <- Hμ. exact HμN.
  - intros i Hi HL. unfold link in HL. destruct (Nat.eq_dec i k) as [->|Hne]; [discriminate|].
    rewrite sumN_minus. fold (U (S i)). fold (W' (S i)).
    pose proof (Hμf i Hi HL) as F. rewrite Hμ in F.
    destruct (Nat.le_gt_cases (S i) a) as [H1|H1]; [rewrite W'lo by lia; lra|].
    destruct (Nat.le_gt_cases b (S i)) as [H2|H2]; [rewrite W'hi by lia; lra|].
    exfalso. destruct (Nat.lt_ge_cases i k) as [H3|H3].
    + rewrite (Hla i ltac:(lia)) in HL. discriminate.
    + rewrite (Hlb i ltac:(lia) ltac:(lia)) in HL. discriminate.
Qed.

(** ** The path *)

(** [p] evolves from the state [z] at time [t]: [p(t) = z]; at every
    [s ≥ t], [p(s) ∈ K^N] and [x⁰ + s u⁰ − p(s) ∈ N_{p(s)} K^N]; off a
    finite set of times [s > t], [p] is differentiable with
    [u⁰ − ṗ(s) ∈ N_{p(s)} K^N]. *)
Definition Evolves (t : R) (z : nat -> R) (p : R -> nat -> R) : Prop :=
  (forall i, p t i = z i) /\
  (forall s, t <= s -> InKR N r (p s) /\ InNormalConeR N r (p s) (fun i => flight s i - p s i)) /\
  exists (E : list R) (V : R -> nat -> R), forall s, t < s -> ~ In s E ->
    (forall i, (i < N)%nat -> is_derive (fun s => p s i) s (V s i)) /\
    InNormalConeR N r (p s) (fun i => u0 i - V s i).

(** From every state of [Inv], a path evolves: free flight to the first
    meeting of a free pair, then a merge, by induction on the number of
    free pairs. *)
Lemma evolves :
  forall n L t z v, free_pairs N L = n -> Inv t z v L -> exists p, Evolves t z p.
Proof.
  induction n as [n IH] using lt_wf_ind. intros L t z v Hn HI.
  set (P := fun i => (S i < N)%nat /\ L i = false /\ v (S i) < v i).
  set (θ := fun i => (z (S i) - z i - 2 * r) / (v i - v (S i))).
  destruct (first_index P θ N) as [Hnone|(k & Hk & (HkN & HLk & Hvk) & Hmin)].
  - (* No free pair closes: free flight for ever. *)
    assert (Hs : forall s, t <= s -> Inv s (cluster_flight t z v s) v L).
    { intros s Hs. apply inv_free_flight; [exact HI|exact Hs|].
      apply (cluster_flight_in_K t s z v L HI Hs).
      intros i Hi HL Hlt. exfalso. apply (Hnone i); [lia|]. unfold P. auto. }
    exists (cluster_flight t z v). split; [|split].
    + intro i. unfold cluster_flight. ring.
    + intros s Hts. destruct (inv_normal_cones _ _ _ _ (Hs s Hts)) as (A & B & _). auto.
    + exists nil, (fun _ => v). intros s Hts _. split.
      * intros i _. apply cluster_flight_derive.
      * apply (inv_normal_cones _ _ _ _ (Hs s ltac:(lra))).
  - (* The pair [k] meets first, at [t' = t + θ k]. *)
    pose proof (proj1 HI k HkN) as Gk.
    assert (Hθ : 0 <= θ k) by (unfold θ; apply Rle_mult_inv_pos; lra).
    set (t' := t + θ k).
    assert (Ht' : t <= t') by (unfold t'; lra).
    assert (Hfly : forall s, t <= s <= t' -> InKR N r (cluster_flight t z v s)).
    { intros s Hs. apply (cluster_flight_in_K t s z v L HI ltac:(lra)).
      intros i Hi HL Hlt. pose proof (Hmin i ltac:(lia) (conj Hi (conj HL Hlt))) as Hm.
      assert (E : θ i * (v i - v (S i)) = z (S i) - z i - 2 * r) by (unfold θ; field; lra).
      assert ((s - t) * (v i - v (S i)) <= θ i * (v i - v (S i))).
      { apply Rmult_le_compat_r; [lra|]. unfold t' in Hs. lra. }
      lra. }
    assert (Hinv : forall s, t <= s <= t' -> Inv s (cluster_flight t z v s) v L).
    { intros s Hs. apply inv_free_flight; [exact HI|lra|apply Hfly; exact Hs]. }
    assert (Hmeet : cluster_flight t z v t' (S k) - cluster_flight t z v t' k = 2 * r).
    { unfold cluster_flight, t', θ. field. lra. }
    destruct (merge_inv t' _ v L k (Hinv t' ltac:(lra)) HkN HLk Hvk Hmeet) as (v' & HI').
    pose proof (free_pairs_link N L k ltac:(lia) HLk) as Hc.
    destruct (IH (free_pairs N (link L k)) ltac:(lia) (link L k) t' _ v' eq_refl HI')
      as (p' & Hp0 & Hpp & E & V & Hpd).
    exists (fun s i => if Rle_dec s t' then cluster_flight t z v s i else p' s i).
    split; [|split].
    + intro i. destruct (Rle_dec t t') as [_|Hn']; [|lra]. unfold cluster_flight. ring.
    + intros s Hts. destruct (Rle_dec s t') as [Hst|Hst].
      * destruct (inv_normal_cones _ _ _ _ (Hinv s ltac:(lra))) as (A & B & _). auto.
      * apply Hpp. lra.
    + exists (t' :: E), (fun s => if Rle_dec s t' then v else V s).
      intros s Hts HE. assert (Hne : s <> t') by (intro; apply HE; left; auto).
      destruct (Rle_dec s t') as [Hst|Hst].
      * split.
        -- intros i _. apply (is_derive_ext_loc (fun s => cluster_flight t z v s i)).
           ++ apply (filter_imp (fun y => y < t')); [|apply open_lt; lra].
              intros y Hy. destruct (Rle_dec y t'); [reflexivity|lra].
           ++ apply cluster_flight_derive.
        -- apply (inv_normal_cones _ _ _ _ (Hinv s ltac:(lra))).
      * assert (Hs' : t' < s) by lra. destruct (Hpd s Hs' (fun H => HE (or_intror H))) as [D Nc].
        split; [|exact Nc].
        intros i Hi. apply (is_derive_ext_loc (fun s => p' s i)); [|apply D; exact Hi].
        apply (filter_imp (fun y => t' < y)); [|apply open_gt; exact Hs'].
        intros y Hy. destruct (Rle_dec y t'); [lra|reflexivity].
Qed.

End Dynamics.
