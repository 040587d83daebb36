#!/usr/bin/env bash
# The test suite in two parts (issue 28 item 8), run from the repo root:
#   1. `cargo test --release`             README's test command: everything but
#                                          the campaigns (ends in minutes, cold);
#   2. `cargo test --release -- --ignored` the campaigns, each marked
#                                          #[ignore = "campaign: …"]: the
#                                          bounded-exhaustive proofs, the
#                                          symbolic proofs at N <= 3, the whole
#                                          ledger vs CLAIMS.md, the peer solvers,
#                                          the long random campaigns.
# Together they are exactly the old `cargo test --release`: nothing is skipped.
# tests/prove.rs fails under CI=true without z3, so z3 is installed first.
set -euo pipefail
cd "$(dirname "$0")/../.."

if ! command -v z3 >/dev/null 2>&1; then
  echo "== installing z3 (tests/prove.rs)"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq z3
fi

echo "== tests: cargo test --release (README's command; campaigns left out)"
start=$SECONDS
cargo test --release
echo "-- fast suite: $((SECONDS - start)) s"

echo "== campaigns: cargo test --release -- --ignored"
start=$SECONDS
cargo test --release -- --ignored
echo "-- campaigns: $((SECONDS - start)) s"
