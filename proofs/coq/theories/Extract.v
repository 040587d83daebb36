(** * Extraction of the oracle to OCaml ([proofs/coq/oracle]).

    Extracted: [state_at] (PAVA, translation, multipliers, clusters) and the
    rational operations the driver uses to check its input ([Qle_bool],
    [Qeq_bool], [Qplus], [Qminus], [Qmult], [Qred]). Integers are zarith's
    ([ExtrOcamlZBigInt]), [nat] is OCaml's [int] ([ExtrOcamlNatInt]; indices
    and sizes are below [2^62]). Trusted besides Coq and OCaml: the
    realizers of those two libraries, and [Z.ggcd] realized below by
    zarith's gcd and exact divisions (Coq's own [Z.ggcd] walks the binary
    digits one match at a time, quadratic on big integers). *)

From Coq Require Import Extraction ExtrOcamlBasic ExtrOcamlNatInt ExtrOcamlZBigInt.
From Coq Require Import QArith.
From Sticky Require Import Oracle.

Extract Constant Z.ggcd =>
  "(fun a b -> let g = Big_int_Z.gcd_big_int a b in
     if Big_int_Z.sign_big_int g = 0
     then (g, (Big_int_Z.zero_big_int, Big_int_Z.zero_big_int))
     else (g, (Big_int_Z.div_big_int a g, Big_int_Z.div_big_int b g)))".

Cd "extraction".
Extraction "sticky_oracle" state_at Qred Qle_bool Qeq_bool Qplus Qminus Qmult.
Cd "..".
