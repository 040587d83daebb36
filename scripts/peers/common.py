"""Shared by the peer drivers: read a `sticky export --format json` file,
parse the requested times, write a SOLUTION that `sticky compare` reads.

Every driver is run as

    PYTHON DRIVER.py EXPORT.json --at T [--at T2 ...] --out SOLUTION.json [driver options]

with times as exact strings ("3/2", "0.125"); the solver gets the nearest
double of each time, and the SOLUTION repeats the exact string, so that
`sticky compare` compares at the time that was asked. Positions and
velocities are written as JSON numbers (Python's repr: the shortest decimal
that reads back as the same double), which `sticky compare` reads as the
exact doubles the solver computed.

A driver whose solver is not installed prints `SKIP <peer>: <reason>` and
exits with status 3 (SKIP_STATUS).
"""
import argparse
import json
import sys
import time
from fractions import Fraction

SKIP_STATUS = 3


def skip(peer, reason):
    print("SKIP %s: %s" % (peer, reason))
    sys.exit(SKIP_STATUS)


def args(description, extra=None):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("export", help="sticky export --format json output")
    p.add_argument("--at", action="append", required=True, help="a time t >= 0 (exact string)")
    p.add_argument("--out", required=True, help="SOLUTION file to write (JSON lines)")
    if extra:
        extra(p)
    return p.parse_args()


def load(path):
    """(n, r, x0, u0) as Python floats: the nearest doubles of the scene."""
    with open(path) as f:
        d = json.load(f)
    return d["n"], float(d["radius"]["f64"]), [float(v) for v in d["positions"]["f64"]], \
        [float(v) for v in d["velocities"]["f64"]]


def time_of(text):
    """The nearest double of an exact time string."""
    q = Fraction(text.strip())
    if q < 0:
        raise SystemExit("time %s is negative" % text)
    return float(q)


# The one contact rule of every driver: the pair (j, j+1) of an answer is in
# contact when its gap x_{j+1} - x_j - 2r is at most CONTACT_TOL * 2r. A
# contact is a gap of zero (df:Omega-micro), whatever the force: a resting
# contact has a zero multiplier. A double cannot hold x_j + 2r exactly, so
# "zero" is "within a millionth of a diameter", the threshold below which the
# atlas counts an overlap as rounding (report::atlas::OVERLAP_TOLERANCE) and
# with which it classifies the gaps of an answer without a contact set.
CONTACT_TOL = 1e-6


def contacts(x, two_r):
    """[gap_j <= CONTACT_TOL * 2r for each pair j] of positions x."""
    tol = CONTACT_TOL * two_r
    return [bool(x[j + 1] - x[j] - two_r <= tol) for j in range(len(x) - 1)]


def clusters_from(contacts):
    """[[first, size], ...] from a list of booleans for the pairs."""
    out, first = [], 0
    n = len(contacts) + 1
    for j in range(n):
        if j + 1 == n or not contacts[j]:
            out.append([first, j + 1 - first])
            first = j + 1
    return out


def write(path, frames, peer, setting, velocity_method, timing):
    """frames: list of dicts with t (exact string), positions, [velocities],
    [multipliers], [clusters]; timing: the Timing of the solver call
    (see `timed`)."""
    with open(path + ".tmp", "w") as f:
        for fr in frames:
            obj = {"t": fr["t"], "positions": [float(v) for v in fr["positions"]]}
            if fr.get("velocities") is not None:
                obj["velocities"] = [float(v) for v in fr["velocities"]]
            if fr.get("multipliers") is not None:
                obj["multipliers"] = [float(v) for v in fr["multipliers"]]
            if fr.get("clusters") is not None:
                obj["clusters"] = fr["clusters"]
            obj["peer"] = peer
            obj["setting"] = setting
            obj["velocity_method"] = velocity_method
            obj["solve_seconds"] = timing.solve_seconds
            obj["solve_repetitions"] = timing.repetitions
            obj["setup_seconds"] = timing.setup_seconds
            # Last (report::peers reads it at the end of the line): the first
            # call, its set-up included, imports and file reading not.
            obj["wall_seconds"] = timing.first_seconds
            f.write(json.dumps(obj, allow_nan=True) + "\n")
    import os
    os.replace(path + ".tmp", path)


# The clock discipline of `sticky bench`, applied to the solver call alone
# (the interpreter's start-up, the imports and the file input/output are
# outside it): one warm-up call, whose answer is the one written; then
# repetitions of the same call until at least MIN_REPETITIONS of them and
# MIN_SECONDS in all, or MAX_SECONDS in all; the median is reported. A
# warm-up call of LONG_SECONDS or more is its own single measurement (its
# first-call costs are negligible beside it, and repeating it would only
# spend the peer's budget in the atlas).
MIN_REPETITIONS = 3
MIN_SECONDS = 0.2
MAX_SECONDS = 0.5
LONG_SECONDS = 0.25
MAX_REPETITIONS = 1000


class Timing:
    """solve_seconds: median of the timed calls; repetitions: how many;
    setup_seconds: median set-up (None when the peer has none apart);
    first_seconds: the warm-up call, set-up included."""

    def __init__(self, solve_seconds, repetitions, setup_seconds, first_seconds):
        self.solve_seconds = solve_seconds
        self.repetitions = repetitions
        self.setup_seconds = setup_seconds
        self.first_seconds = first_seconds


def median(values):
    v = sorted(values)
    k = len(v) // 2
    return v[k] if len(v) % 2 else (v[k - 1] + v[k]) / 2.0


def timed(solve, setup=None):
    """(answer, Timing) of the call solve() -- or solve(setup()) when the peer
    needs a set-up (a model to build, a factorisation), timed apart before
    each call. The answer is the warm-up call's."""
    def once():
        t0 = time.perf_counter()
        state = setup() if setup is not None else None
        t1 = time.perf_counter()
        answer = solve(state) if setup is not None else solve()
        t2 = time.perf_counter()
        return answer, t1 - t0, t2 - t1

    answer, s0, c0 = once()
    setups, calls = [s0], [c0]
    if c0 < LONG_SECONDS:
        calls, setups = [], []
        while len(calls) < MAX_REPETITIONS:
            total = sum(calls)
            if total >= MAX_SECONDS or (len(calls) >= MIN_REPETITIONS and total >= MIN_SECONDS):
                break
            _, s, c = once()
            setups.append(s)
            calls.append(c)
    return answer, Timing(median(calls), len(calls),
                          median(setups) if setup is not None else None, s0 + c0)
