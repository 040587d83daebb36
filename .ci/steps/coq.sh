#!/usr/bin/env bash
# CI step (issue 26): build the Coq development, check it has no Admitted /
# axioms and that every main theorem is closed under the global context,
# build the extracted oracle, and compare every Rust engine with it.
# Run from the repository root.
set -euo pipefail

start=$(date +%s)
step() { echo "coq.sh: $*"; }

need=()
command -v coqc >/dev/null || need+=(coq)
command -v ocamlfind >/dev/null || need+=(ocaml ocaml-findlib)
ocamlfind query zarith >/dev/null 2>&1 || need+=(libzarith-ocaml-dev)
[ -d "$(coqc -where 2>/dev/null)/user-contrib/Coquelicot" ] || need+=(libcoq-coquelicot)
if [ "${#need[@]}" -gt 0 ]; then
  step "installing ${need[*]}"
  sudo_cmd=""
  [ "$(id -u)" = 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update
  $sudo_cmd apt-get install -y --no-install-recommends coq ocaml ocaml-findlib libzarith-ocaml-dev libcoq-coquelicot
fi
step "$(coqc --version | head -1)"

t0=$(date +%s)
step "make -C proofs/coq (the theories)"
make -C proofs/coq
step "theories built in $(( $(date +%s) - t0 )) s"

step "make -C proofs/coq check (no Admitted/axioms; Print Assumptions closed)"
make -C proofs/coq check

t0=$(date +%s)
step "make -C proofs/coq oracle"
make -C proofs/coq oracle
test -x proofs/coq/oracle
step "oracle built in $(( $(date +%s) - t0 )) s"

t0=$(date +%s)
step "cargo test --release --test coq_oracle (CI=true: a missing oracle fails)"
CI=true cargo test --release --test coq_oracle -- --nocapture
step "Rust test in $(( $(date +%s) - t0 )) s"

step "done in $(( $(date +%s) - start )) s"
