(** * Extraction of the event-driven dynamics to OCaml.

    [dynamics] (positions and velocities at [t]) and [cluster_spans]
    (clusters as [(first, size)], indices from 0) of [Dynamics.v], proved
    equal to [P_K(x⁰ + t u⁰)] ([DynamicsIsProjK.dynamics_is_proj_K]) and to
    the paper's statements on them (the files after [Dynamics.v]). Written
    to [extraction/sticky_dynamics.ml] with the realizers of [Realizers.v]
    (zarith integers, OCaml ints for [nat], [Z.ggcd] by zarith's gcd).

    This is an independent second implementation for cross-checks on small
    scenes: it recomputes cluster sums at every step and keeps rationals
    unreduced, so it is quadratic in [N] at best; the oracle stays on PAVA,
    which [dynamics_is_proj_K] proves equal to it. *)

From Coq Require Import Extraction QArith.
From Sticky Require Import Realizers Dynamics.

Cd "extraction".
Extraction "sticky_dynamics" dynamics cluster_spans Qred.
Cd "..".
