#!/usr/bin/env bash
# The assumption check of the Coq development (run from proofs/coq, after
# `make`): fails on Admitted/admit/Axiom/Parameter/Conjecture outside
# comments in theories/*.v, and unless `Print Assumptions` answers
# "Closed under the global context" for every theorem of main-theorems.txt.
set -euo pipefail
cd "$(dirname "$0")"

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
{
  echo "From Sticky Require Import $(sed -n 's/^theories\/\(.*\)\.v$/\1/p' _CoqProject | tr '\n' ' ')."
  { grep -vE '^\s*(#|$)' main-theorems.txt || true; } | while read -r thm; do
    echo "Print Assumptions $thm."
  done
} > "$tmp/Assumptions.v"
coqc -R theories Sticky "$tmp/Assumptions.v" > "$tmp/out.txt"
total=$(grep -cvE '^\s*(#|$)' main-theorems.txt || true)
closed=$(grep -c 'Closed under the global context' "$tmp/out.txt" || true)
echo "  $closed of $total theorems closed under the global context"
if [ "$closed" != "$total" ]; then
  cat "$tmp/out.txt" >&2
  exit 1
fi
