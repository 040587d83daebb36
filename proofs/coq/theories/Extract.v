(** * Extraction of the oracle to OCaml ([proofs/coq/oracle]).

    Extracted, to one module [extraction/sticky_oracle.ml] (one type of
    rationals, one state record for both paths):
    - [state_at] (PAVA, translation, multipliers, clusters), the default
      path;
    - [dynamics_state] ([DynamicsState.v]: the event-driven dynamics of
      [Dynamics.v] with its multipliers and contact clusters), the
      [--dynamics] path and the cross-check of the default one; it
      recomputes cluster sums at every step, quadratic in [N] at best, so it
      serves small scenes;
    - the rational operations the driver uses to check its input
      ([Qle_bool], [Qeq_bool], [Qplus], [Qminus], [Qmult], [Qred]).
    Integers are zarith's ([ExtrOcamlZBigInt]), [nat] is OCaml's [int]
    ([ExtrOcamlNatInt]; indices and sizes are below [2^62]). Trusted besides
    Coq and OCaml: the
    realizers of those two libraries, and [Z.ggcd] realized below by
    zarith's gcd and exact divisions (Coq's own [Z.ggcd] walks the binary
    digits one match at a time, quadratic on big integers; the realizers are
    in [Realizers.v]). *)

From Coq Require Import Extraction QArith.
From Sticky Require Import Realizers Oracle DynamicsState.

Cd "extraction".
Extraction "sticky_oracle" state_at dynamics_state Qred Qle_bool Qeq_bool Qplus Qminus Qmult.
Cd "..".
