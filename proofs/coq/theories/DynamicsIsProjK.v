(** * The event-driven dynamics equals [P_K(x⁰ + t u⁰)] computed by PAVA.

    [DynamicsProjection.dynamics_is_projection] gives the KKT conditions;
    [Projection.kkt_unique] (two solutions of the KKT conditions are equal)
    turns them into the identity [x(t) = proj_K r (x⁰ + t u⁰)], entry by
    entry, where [proj_K] is the projection computed by PAVA and proved to
    be the unique nearest point of [K^N] ([Projection.proj_K_minimiser]). *)

From Coq Require Import QArith Qring Lqa Lia List.
From Sticky Require Import Prelude Kkt Pava Projection Dynamics DynamicsProjection.
Import ListNotations.
Open Scope Q_scope.

(** The KKT conditions depend on [z] only entry by entry, up to [==]. *)
Lemma kkt_qeq_z (z z' y : list Q) : qeq_list z z' -> Kkt z y -> Kkt z' y.
Proof.
  intros Hz (L & M & P & T & C).
  pose proof (qeq_list_length _ _ Hz) as Lz.
  split; [congruence|split; [exact M|split; [|split]]].
  - intros k Hk. rewrite <- (qeq_list_psum _ _ Hz k). apply P. lia.
  - rewrite <- Lz, <- (qeq_list_psum _ _ Hz). exact T.
  - intros k Hk Hl. rewrite <- (qeq_list_psum _ _ Hz). apply C; [lia|exact Hl].
Qed.

Lemma untranslate_qeq (r : Q) (a b : list Q) :
  qeq_list a b -> forall k, qeq_list (untranslate_from k r a) (untranslate_from k r b).
Proof.
  induction 1 as [|x y a b Hxy _ IH]; intro k; constructor; [rewrite Hxy; reflexivity|apply IH].
Qed.

(** The free positions of the particles are the translated free flight. *)
Lemma free_positions_translate (r t : Q) (x0 : list Q) :
  forall u0 k, length u0 = length x0 ->
  qeq_list (map (free_position t) (combine (translate_from k r x0) u0))
           (translate_from k r (free_flight x0 u0 t)).
Proof.
  induction x0 as [|a x0 IH]; intros [|b u0] k L; simpl in L; try discriminate; constructor.
  - unfold free_position. simpl. ring.
  - apply IH. lia.
Qed.

(** For every [N], [x⁰ ∈ K^N], any [u⁰] and rational [t ≥ 0], the sticky
    dynamics is at [P_K(x⁰ + t u⁰)]: [x(t) = proj_K r (x⁰ + t u⁰)] entry by
    entry ([prop:proj-micro], [eq:proj-micro-x]; ledger: [prop:proj-micro]). *)
Theorem dynamics_is_proj_K (x0 u0 : list Q) (r t : Q) :
  0 <= t -> InK r x0 -> length u0 = length x0 ->
  qeq_list (positions (dynamics x0 u0 r t)) (proj_K r (free_flight x0 u0 t)).
Proof.
  intros Ht HK L.
  set (z := translate r (free_flight x0 u0 t)).
  assert (Hz : Kkt z (translated_positions t (clusters x0 u0 r t))).
  { apply (kkt_qeq_z (map (free_position t) (particles x0 u0 r))).
    - apply free_positions_translate. exact L.
    - apply dynamics_is_projection; assumption. }
  pose proof (kkt_unique z _ _ Hz (pava_kkt z)) as E.
  unfold proj_K. fold z. unfold dynamics, positions, untranslate.
  apply untranslate_qeq. exact E.
Qed.
