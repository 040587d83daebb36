#!/bin/sh
# Mutation testing of the model core with cargo-mutants (docs/mutants.md).
#
#   scripts/mutants.sh                 # projection, trajectory, contact, cluster
#   scripts/mutants.sh src/fast/int.rs # any other files (globs as cargo-mutants takes them)
#
# Needs `cargo install cargo-mutants --locked`. Not run in CI: one build of
# the library per mutant (incremental, profile `mutants`), about half an hour
# for the four core files on two cores. Each mutant is judged by the core's
# own unit tests only (`cargo test --lib` filtered to the modules named in
# TESTS), which run in well under a second: a mutant that survives them is a
# gap in those tests, whatever the slower suites would have said.
# The report lands in $OUTPUT/mutants.out/ (default target/mutants-report;
# outcomes.json, caught.txt, missed.txt, timeout.txt, unviable.txt). Extra
# cargo-mutants options (e.g. `--iterate`, `-F NAME`) go in MUTANTS_ARGS.
set -eu
cd "$(dirname "$0")/.."
# A target directory of its own: cargo-mutants builds in a copy of the tree,
# and must not wait on the lock of the worktree's target/.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target/mutants-build}"
FILES="${*:-src/projection.rs src/trajectory.rs src/contact.rs src/cluster.rs}"
TESTS="${TESTS:-projection:: trajectory:: contact:: cluster::}"
set --
for f in $FILES; do set -- "$@" --file "$f"; done
# shellcheck disable=SC2086 # TESTS and MUTANTS_ARGS are lists of words
exec cargo mutants "$@" \
    --profile mutants --no-default-features --cargo-arg=--lib \
    --timeout "${TIMEOUT:-60}" --jobs 1 \
    --output "${OUTPUT:-target/mutants-report}" ${MUTANTS_ARGS:-} \
    -- -- $TESTS
