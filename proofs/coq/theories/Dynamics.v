(** * The sticky dynamics, event by event, as a computable function.

    Paper, section "Sticky dynamics and reduction to first order":
    "Collisions in the system are perfectly inelastic: whenever two particles
    collide they stick together and subsequently move with the same
    velocity. As a consequence, clusters of particles can only grow in time
    and never break apart."

    We follow that description literally, in translated coordinates
    ([df:translat-x]: [x̃_i = x_i − 2r(i−1)], 1-based), where touching
    particles have equal translated positions:
    - a particle is the pair [(x̃⁰_i, u⁰_i)];
    - a cluster is a run of consecutive particles; it moves with the mean
      initial velocity of its members (momentum is conserved), so its
      translated position at time [τ] is [(Σx̃⁰ + τ Σu⁰) / k], [k] its size;
    - two adjacent clusters meet when their translated positions coincide
      while the left one is faster; the pair meeting first merges (ties:
      the leftmost pair first, then the others at the same instant, one by
      one), and so on until no pair meets before the time [t] asked for.

    [clusters x0 u0 r t] is the list of clusters at time [t];
    [positions] and [velocities] spell out [x(t)] and [u(t)]. Everything is
    exact over [Q]; times are rational. *)

From Coq Require Import QArith Qring Qfield Lqa Lia List.
From Sticky Require Import Prelude Kkt.
Import ListNotations.
Open Scope Q_scope.

(** ** Particles and clusters *)

(** A particle: its translated initial position [x̃⁰_i] and initial
    velocity [u⁰_i]. *)
Notation particle := (Q * Q)%type.

(** The translated position at time [τ] of a particle in free flight,
    [z_i(τ) = x̃⁰_i + τ u⁰_i]. *)
Definition free_position (τ : Q) (p : particle) : Q := fst p + τ * snd p.

(** A cluster: a run of consecutive particles (never empty in a state). *)
Notation cluster := (list particle).

(** The number of particles of a cluster, as a rational. *)
Definition size (c : cluster) : Q := qn (length c).

(** The cluster's velocity: the mean initial velocity of its members. *)
Definition velocity (c : cluster) : Q := qsum (map snd c) / size c.

(** The cluster's translated position at time [τ]: the mean of its
    members' free positions, [(Σx̃⁰ + τ Σu⁰) / k]. *)
Definition center (τ : Q) (c : cluster) : Q := qsum (map (free_position τ) c) / size c.

(** The left cluster [a] is faster than its right neighbour [b]. *)
Definition approaching (a b : cluster) : bool :=
  negb (Qle_bool (velocity a) (velocity b)).

(** The instant at which two approaching adjacent clusters meet. *)
Definition meeting_time (a b : cluster) : Q :=
  (center 0 b - center 0 a) / (velocity a - velocity b).

(** The smaller of two instants. *)
Definition earlier (a b : Q) : Q := if Qle_bool a b then a else b.

(** The earliest meeting time of two adjacent clusters, if any pair
    approaches. *)
Fixpoint next_meeting (cs : list cluster) : option Q :=
  match cs with
  | a :: ((b :: _) as rest) =>
      let later := next_meeting rest in
      if approaching a b then
        match later with
        | Some m => Some (earlier (meeting_time a b) m)
        | None => Some (meeting_time a b)
        end
      else later
  | _ => None
  end.

(** Merge the leftmost approaching pair that meets at [τ]. *)
Fixpoint merge_at (τ : Q) (cs : list cluster) : list cluster :=
  match cs with
  | a :: ((b :: rest') as rest) =>
      if approaching a b && Qeq_bool (meeting_time a b) τ
      then (a ++ b) :: rest'
      else a :: merge_at τ rest
  | _ => cs
  end.

(** Merge, collision after collision, until no pair meets at or before [t];
    [fuel] bounds the number of merges (the number of clusters suffices,
    lemma [run_final] in [DynamicsProjection.v]). *)
Fixpoint run (fuel : nat) (t : Q) (cs : list cluster) : list cluster :=
  match fuel with
  | O => cs
  | S f =>
      match next_meeting cs with
      | Some τ => if Qle_bool τ t then run f t (merge_at τ cs) else cs
      | None => cs
      end
  end.

(** The particles of the data [(x⁰, u⁰)], in translated coordinates. *)
Definition particles (x0 u0 : list Q) (r : Q) : list particle :=
  combine (translate r x0) u0.

(** The clusters at time [t]: every particle alone at time 0, then the
    collisions up to [t]. *)
Definition clusters (x0 u0 : list Q) (r t : Q) : list cluster :=
  let ps := particles x0 u0 r in
  run (length ps) t (map (fun p => [p]) ps).

(** Each member of a cluster at the cluster's translated position. *)
Definition translated_positions (t : Q) (cs : list cluster) : list Q :=
  concat (map (fun c => repeat (center t c) (length c)) cs).

(** Each member of a cluster at the cluster's velocity. *)
Definition cluster_velocities (cs : list cluster) : list Q :=
  concat (map (fun c => repeat (velocity c) (length c)) cs).

(** The state of the sticky dynamics at time [t]. *)
Record state := mkstate {
  positions : list Q;   (** [x(t)] *)
  velocities : list Q   (** [u(t)], the right derivative of [x] at [t] *)
}.

(** The sticky dynamics: the state at time [t] of the data [(x⁰, u⁰)] with
    radius [r]. *)
Definition dynamics (x0 u0 : list Q) (r t : Q) : state :=
  let cs := clusters x0 u0 r t in
  mkstate (untranslate r (translated_positions t cs)) (cluster_velocities cs).

(** Free flight [x⁰ + t u⁰], entry by entry (the point the paper projects
    onto [K^N]). *)
Definition free_flight (x0 u0 : list Q) (t : Q) : list Q :=
  map (fun p => fst p + t * snd p) (combine x0 u0).

Lemma free_flight_length (x0 u0 : list Q) (t : Q) :
  length u0 = length x0 -> length (free_flight x0 u0 t) = length x0.
Proof. intro L. unfold free_flight. rewrite map_length, combine_length. lia. Qed.

Lemma free_flight_nth (x0 u0 : list Q) (t : Q) (i : nat) :
  length u0 = length x0 -> (i < length x0)%nat ->
  nth i (free_flight x0 u0 t) 0 == nth i x0 0 + t * nth i u0 0.
Proof.
  unfold free_flight. revert u0 i.
  induction x0 as [|a x0 IH]; intros [|b u0] i L Hi; simpl in *; try lia.
  destruct i as [|i]; [reflexivity|]. apply IH; lia.
Qed.

(** The index of the first particle and the size of every cluster at time
    [t] (indices from 0). *)
Fixpoint cluster_spans_from (first : nat) (cs : list cluster) : list (nat * nat) :=
  match cs with
  | [] => []
  | c :: cs' => (first, length c) :: cluster_spans_from (first + length c) cs'
  end.

Definition cluster_spans (x0 u0 : list Q) (r t : Q) : list (nat * nat) :=
  cluster_spans_from 0 (clusters x0 u0 r t).
