#!/bin/sh
# End-to-end rows of issue 13 (part 5), in one run: file -> answer -> file at
# N particles (default 10^6) for TOML, CSV and NPY input to `sticky run --at 1
# --json` and `sticky events --json`, beside scipy's own pipeline on the same
# files (scripts/peers/e2e_scipy.py: numpy.loadtxt -> isotonic_regression ->
# numpy.savetxt on CSV; numpy.load -> ... -> numpy.save on NPY). Wall time and
# peak memory from /usr/bin/time (whole processes); peak bytes per particle.
#
#   scripts/bench_e2e.sh [N] [STICKY]      # STICKY defaults to target/release/sticky
#
# The CSV both read is a decimal file (3 decimals, so numpy reads it too);
# the NPY is `sticky generate --format npy` (doubles on the grid 2^-32).
set -eu
N=${1:-1000000}
STICKY=${2:-target/release/sticky}
HERE=$(cd "$(dirname "$0")" && pwd)
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
python3 - "$N" "$DIR" <<'PY'
import random, sys
n, d = int(sys.argv[1]), sys.argv[2]
random.seed(7)
x = 0; prev = None; contact = False
with open(f"{d}/dec.csv", "w") as f:
    f.write("position,velocity\n")
    for i in range(n):
        u = random.randint(-5000, 5000)
        if contact and u < prev:
            u = prev
        f.write(f"{x/1000:.3f},{u/1000:.3f}\n")
        g = random.choice([0, 0, 0, 1, 2, 5, 10, 40])
        contact = g == 0
        x += 2 + g; prev = u
open(f"{d}/dec.toml", "w").write('[particles]\nradius = "0.001"\ndata = "dec.csv"\n')
PY
"$STICKY" generate --n "$N" --seed 7 --format npy --out "$DIR" >/dev/null
"$STICKY" generate --n "$N" --seed 7 > "$DIR/g.toml"
NPY_TOML=$(ls "$DIR"/random-*-f64.toml)
NPY=$(ls "$DIR"/random-*-f64.npy)
row() { # name command...
    name=$1; shift
    /usr/bin/time -f "%e %M" -o "$DIR/time" "$@" > "$DIR/out" 2>/dev/null || true
    read -r wall kb < "$DIR/time"
    echo "$name $wall $kb"
}
{
    row "scipy-csv" python3 "$HERE/peers/e2e_scipy.py" csv "$DIR/dec.csv" "$DIR/o.csv" --two-r 0.002
    row "sticky-run-csv" "$STICKY" run "$DIR/dec.toml" --at 1 --json
    row "sticky-events-csv" "$STICKY" events "$DIR/dec.toml" --json
    row "scipy-npy" python3 "$HERE/peers/e2e_scipy.py" npy "$NPY" "$DIR/o.npy" --two-r 1/32
    row "sticky-run-npy" "$STICKY" run "$NPY_TOML" --at 1 --json
    row "sticky-events-npy" "$STICKY" events "$NPY_TOML" --json
    row "sticky-run-toml" "$STICKY" run "$DIR/g.toml" --at 1 --json
    row "sticky-events-toml" "$STICKY" events "$DIR/g.toml" --json
} > "$DIR/rows"
awk -v n="$N" '
    { wall[$1] = $2; kb[$1] = $3; order[++k] = $1 }
    END {
        printf "| pipeline (N = %d) | wall s | vs scipy (same input) | peak MiB | bytes/particle |\n", n
        print "|---|---:|---:|---:|---:|"
        for (i = 1; i <= k; i++) {
            r = order[i]; ref = (r ~ /npy/) ? "scipy-npy" : "scipy-csv"
            ratio = (r ~ /toml/) ? "—" : sprintf("%.2f×", wall[r] / wall[ref])
            printf "| %s | %.2f | %s | %.0f | %.0f |\n", r, wall[r], ratio, kb[r] / 1024, kb[r] * 1024 / n
        }
    }' "$DIR/rows"
