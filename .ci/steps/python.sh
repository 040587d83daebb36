#!/usr/bin/env bash
# The Python package (issue 27): a fresh virtual environment, the package
# built and installed from ./python by pip (maturin as the PEP 517 backend),
# its pytest suite (the hypothesis suite of hostile arguments, the README's
# and the guide's Python examples among them), the stubs against the
# module (mypy.stubtest), the example, and the abi3 wheel built by maturin.
# Run from the repository root. Uses $CARGO_TARGET_DIR when set.
set -euo pipefail

say() { printf '== python.sh: %s\n' "$*"; }
t0=$SECONDS
lap() { say "$1 ($((SECONDS - t0)) s so far)"; }

target="${CARGO_TARGET_DIR:-$PWD/target}"
venv="$(mktemp -d)/venv"
out="$(mktemp -d)"
trap 'rm -rf "$(dirname "$venv")" "$out"' EXIT

say "fresh venv in $venv ($(python3 --version))"
python3 -m venv "$venv"
py="$venv/bin/python"
"$py" -m pip install --quiet --upgrade pip
"$py" -m pip install --quiet "maturin>=1.5,<2" "pytest>=8,<10" "hypothesis>=6,<7" \
    "numpy>=2,<3" "scipy>=1.12,<2" "matplotlib>=3,<4" "mypy>=1.10,<2"
lap "test tools installed"

say "pip install ./python[plot]"
"$py" -m pip install --quiet "./python[plot]"
lap "package built and installed"

# The CLI agreement tests call the built command line when there is one.
if [ -x "$target/release/sticky" ]; then
    export STICKY_BIN="$target/release/sticky"
else
    say "no $target/release/sticky: the CLI agreement tests will be skipped"
fi
say "pytest python/tests"
(cd "$out" && "$py" -m pytest -q -p no:cacheprovider "$OLDPWD/python/tests")
lap "pytest done"

say "stubs: python -m mypy.stubtest sticky"
(cd "$out" && "$py" -m mypy.stubtest sticky --allowlist "$OLDPWD/python/stubtest-allowlist.txt" \
    --mypy-config-file "$OLDPWD/python/mypy.ini")
lap "stubs checked"

say "example: examples/python/validate_a_solver.py"
MPLBACKEND=Agg "$py" examples/python/validate_a_solver.py "$out/validate-a-solver.png"
lap "example done"

say "maturin build --release (abi3 wheel)"
"$venv/bin/maturin" build --release --quiet -m python/Cargo.toml -o "$out/wheels"
for w in "$out"/wheels/*.whl; do
    say "wheel $(basename "$w"): $(du -k "$w" | cut -f1) KiB"
done
lap "all done"
