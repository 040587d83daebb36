#!/usr/bin/env bash
# The assumption check of the Coq development (run from proofs/coq, after
# `make`): fails on Admitted/admit/Axiom/Parameter/Conjecture outside
# comments in theories/*.v, and unless `Print Assumptions` answers
# "Closed under the global context" for every theorem of main-theorems.txt
# over Q. The theorems of the files over R (REAL_MODULES) may rest on the
# axioms of Coq's standard real numbers (REAL_AXIOMS) and on nothing else.
set -euo pipefail
cd "$(dirname "$0")"

REAL_MODULES="Sticky.Uniqueness Sticky.UniquenessAC Sticky.NormalConeR Sticky.DynamicsR Sticky.ProjMicroR Sticky.ProjMicroQ"
REAL_AXIOMS="ClassicalDedekindReals.sig_not_dec ClassicalDedekindReals.sig_forall_dec
FunctionalExtensionality.functional_extensionality_dep Classical_Prop.classic"
is_real() { local m; for m in $REAL_MODULES; do [[ "$1" == "$m".* ]] && return 0; done; return 1; }

echo "check: no Admitted, admit, Axiom, Parameter, Conjecture in theories/*.v"
bad=0
for f in theories/*.v; do
  # Strip (* ... *) comments (nested ones included) before grepping.
  stripped=$(perl -0777 -pe '1 while s/\(\*(?:(?!\(\*|\*\)).)*\*\)//gs' "$f")
  if grep -nwE 'Admitted|admit|Axiom|Axioms|Parameter|Parameters|Conjecture' <<<"$stripped"; then
    echo "  $f: forbidden keyword above" >&2
    bad=1
  fi
done
[ "$bad" = 0 ] || exit 1

echo "check: Print Assumptions on every theorem of main-theorems.txt"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
imports="From Sticky Require Import $(sed -n 's/^theories\/\(.*\)\.v$/\1/p' _CoqProject | tr '\n' ' ')."
theorems=$(grep -vE '^\s*(#|$)' main-theorems.txt || true)
{
  echo "$imports"
  for thm in $theorems; do is_real "$thm" || echo "Print Assumptions $thm."; done
} > "$tmp/Assumptions.v"
coqc -R theories Sticky "$tmp/Assumptions.v" > "$tmp/out.txt"
total=0
for thm in $theorems; do is_real "$thm" || total=$((total + 1)); done
closed=$(grep -c 'Closed under the global context' "$tmp/out.txt" || true)
echo "  $closed of $total theorems over Q closed under the global context"
if [ "$closed" != "$total" ]; then
  cat "$tmp/out.txt" >&2
  exit 1
fi

for thm in $theorems; do
  is_real "$thm" || continue
  { echo "$imports"; echo "Print Assumptions $thm."; } > "$tmp/Real.v"
  coqc -R theories Sticky "$tmp/Real.v" > "$tmp/real.txt"
  # Axiom names start a line (their types are indented below them).
  used=$(sed -n 's/^\([A-Za-z_][A-Za-z0-9_.'"'"']*\)\( :.*\)\?$/\1/p' "$tmp/real.txt" | grep -v '^Axioms$' || true)
  for ax in $used; do
    if ! grep -qxF "$ax" <<<"$(tr ' ' '\n' <<<"$REAL_AXIOMS")"; then
      echo "  $thm rests on $ax, not an axiom of the standard real numbers" >&2
      cat "$tmp/real.txt" >&2
      exit 1
    fi
  done
  echo "  $thm: over R, rests only on the standard real-number axioms ($(echo $used | wc -w))"
done
