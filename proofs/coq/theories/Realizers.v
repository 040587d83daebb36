(** * The realizers of the extraction ([Extract.v]).

    Integers are zarith's ([ExtrOcamlZBigInt]) and [nat] is OCaml's [int]
    ([ExtrOcamlNatInt]; indices and sizes are below [2^62]). [Z.ggcd] is
    realized by zarith's gcd and exact divisions: Coq's own [Z.ggcd] walks
    the binary digits one match at a time, quadratic on big integers.
    Extraction directives are kept by [Require], so [Extract.v] gets
    these. *)

From Coq Require Import Extraction ExtrOcamlBasic ExtrOcamlNatInt ExtrOcamlZBigInt.
From Coq Require Import ZArith.

Extract Constant Z.ggcd =>
  "(fun a b -> let g = Big_int_Z.gcd_big_int a b in
     if Big_int_Z.sign_big_int g = 0
     then (g, (Big_int_Z.zero_big_int, Big_int_Z.zero_big_int))
     else (g, (Big_int_Z.div_big_int a g, Big_int_Z.div_big_int b g)))".
