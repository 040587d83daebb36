(** * Extraction of the oracle to OCaml ([proofs/coq/oracle]).

    Extracted: [state_at] (PAVA, translation, multipliers, clusters) and the
    rational operations the driver uses to check its input ([Qle_bool],
    [Qeq_bool], [Qplus], [Qminus], [Qmult], [Qred]). Integers are zarith's
    ([ExtrOcamlZBigInt]), [nat] is OCaml's [int] ([ExtrOcamlNatInt]; indices
    and sizes are below [2^62]). Trusted besides Coq and OCaml: the
    realizers of those two libraries, and [Z.ggcd] realized below by
    zarith's gcd and exact divisions (Coq's own [Z.ggcd] walks the binary
    digits one match at a time, quadratic on big integers; the realizers are
    in [Realizers.v]). *)

From Coq Require Import Extraction QArith.
From Sticky Require Import Realizers Oracle.

Cd "extraction".
Extraction "sticky_oracle" state_at Qred Qle_bool Qeq_bool Qplus Qminus Qmult.
Cd "..".
