"""Every entry point of the Python package at N = 10^6 on a notebook user's
data, against scipy.optimize.isotonic_regression on the same arrays, in one
process (issue 38, item 2).

Not a test: a measurement. Run after `pip install ./python`:

    python benches/python_api.py [N] [--skip NAME,NAME...] [--only NAME,NAME...]

Data (what a notebook user types): positions `np.cumsum` of exponential
gaps (mean 1e-6) on top of the contact distance 2r, radius 4e-7, velocities
uniform in [-1, 1], the time t = 0.01 as a Python float (a full 53-bit
mantissa). Every value is a double, hence a dyadic rational: sticky reads
them exactly. These data are dense: with gaps of 1e-6 and displacements of
0.01, the blocks at t hold about 250 particles each, past what the
certified filter takes, so the exact dyadic path answers.
`benches/python_state.py`'s notebook data have gaps of mean 1 (numpy's
default scale): few contacts, the filter's case.

The reference is scipy's `isotonic_regression` on the shifted free flight
`x0 + t u0 - 2r i` (the projection's kernel, floating point, one array),
the median of five calls. Each entry point is timed once (the median of
three when a call takes under a second), wall clock (`time.perf_counter`);
the table gives the time and its ratio to the reference, and the issue's
target where it states one. A call can be left out with `--skip` (the
names of the first column, or their beginnings: a name holding a comma is
given by the part before it), or the table restricted to some with `--only`.
"""

import statistics
import sys
import time
from fractions import Fraction

import numpy as np
from scipy.optimize import isotonic_regression

import sticky

RADIUS = 4e-7
T = 0.01


def notebook_data(n, seed=38):
    """The notebook's arrays: exponential gaps above contact, u in [-1, 1]."""
    rng = np.random.default_rng(seed)
    # 2r times (1 + 1e-9) keeps every rounded gap at or above 2r.
    gaps = 2 * RADIUS * (1 + 1e-9) + rng.exponential(1e-6, size=n)
    return np.cumsum(gaps), rng.uniform(-1.0, 1.0, size=n)


def once(f):
    """Wall seconds of one call of f, and its result."""
    start = time.perf_counter()
    out = f()
    return time.perf_counter() - start, out


def timed(f):
    """The wall time of f: one call, or the median of three under a second."""
    first, out = once(f)
    if first >= 1.0:
        return first, out
    rest = [once(f)[0] for _ in range(2)]
    return statistics.median([first, *rest]), out


def entries(x0, u0):
    """(name, call, target ratio or None, what the target says) in order.

    Each call builds what it needs from the scene made first, so that the
    time is the entry point's own."""
    n = len(x0)
    scene = sticky.Scene(x0, u0, RADIUS)
    state = scene.state(T)
    z = x0 + T * u0 - 2 * RADIUS * np.arange(n)
    ts20 = [T * (k + 1) / 20 for k in range(20)]
    kept = {}

    def report():
        kept["report"] = sticky.compare(
            scene, T, state.positions, state.velocities, multipliers=state.multipliers
        )
        return kept["report"]

    return [
        ("Scene(x, u, r)", lambda: sticky.Scene(x0, u0, RADIUS), None, ""),
        ("Scene + state(t).positions", lambda: sticky.Scene(x0, u0, RADIUS).state(T).positions, 1.0, "<= 1.0x"),
        ("state(t).positions", lambda: scene.state(T).positions, 2.0, "<= 2x"),
        ("state(t), 3 arrays", lambda: _three(scene.state(T)), 1.5, "<= 1.5x (with Scene)"),
        ("state(Fraction(1,100)).positions", lambda: scene.state(Fraction(1, 100)).positions, None, ""),
        ("states(20 times), positions", lambda: [s.positions for s in scene.states(ts20)], None, ""),
        ("states(20 times)[7].positions", lambda: scene.states(ts20)[7].positions, None, ""),
        ("isotonic(z)", lambda: sticky.isotonic(z), 1.0, "<= 1x"),
        ("project(z)", lambda: scene.project(z + 2 * RADIUS * np.arange(n)), 1.0, "<= 1x"),
        ("compare(scene, t, own answer)", report, None, "<= 1 s"),
        ("report.to_dict()", lambda: kept["report"].to_dict() if "report" in kept else report().to_dict(), None, "<= 1 s"),
        ("events()", lambda: scene.events(), None, "<= 1 s or streaming"),
        ("export(scene)", lambda: sticky.export(scene), None, "<= 1 s"),
        ("state.exact_positions()", lambda: state.exact_positions(), None, "<= 1 s"),
        ("state.to_dict()", lambda: state.to_dict(), None, "<= 1 s"),
        ("scene.explain()", lambda: scene.explain(), None, ""),
    ]


def _three(s):
    return s.positions, s.velocities, s.multipliers


def main():
    args = sys.argv[1:]
    chosen = {}
    for flag in ("--skip", "--only"):
        if flag in args:
            i = args.index(flag)
            chosen[flag] = set(args[i + 1].split(","))
            del args[i : i + 2]
    skip = chosen.get("--skip", set())
    only = chosen.get("--only")
    n = int(args[0]) if args else 10**6
    x0, u0 = notebook_data(n)
    z = x0 + T * u0 - 2 * RADIUS * np.arange(n)
    ref = statistics.median(once(lambda: isotonic_regression(z))[0] for _ in range(5))
    print(f"N = {n}, radius = {RADIUS}, t = {T}; scipy isotonic_regression {ref * 1e3:.1f} ms")
    print(f"{'entry point':36} {'ms':>10} {'x scipy':>9}  target")
    for name, call, target, says in entries(x0, u0):
        if any(name.startswith(k) for k in skip) or (
            only is not None and not any(name.startswith(k) for k in only)
        ):
            print(f"{name:36} {'skipped':>10}")
            continue
        wall, _ = timed(call)
        ratio = wall / ref
        met = ""
        if target is not None:
            met = "met" if ratio <= target else "not met"
        elif says.startswith("<= 1 s"):
            met = "met" if wall <= 1.0 else "not met"
        print(f"{name:36} {wall * 1e3:10.1f} {ratio:9.2f}  {says} {met}".rstrip())
        sys.stdout.flush()


if __name__ == "__main__":
    main()
