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


def write(path, frames, peer, setting, velocity_method, seconds):
    """frames: list of dicts with t (exact string), positions, [velocities],
    [multipliers], [clusters]."""
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
            obj["wall_seconds"] = seconds
            f.write(json.dumps(obj, allow_nan=True) + "\n")
    import os
    os.replace(path + ".tmp", path)


class Timer:
    def __enter__(self):
        self.t0 = time.perf_counter()
        return self

    def __exit__(self, *a):
        self.seconds = time.perf_counter() - self.t0
