#!/usr/bin/env python3
"""Independent exact oracle for the `sticky` binary (DESIGN.md §3 JSON contract).

Written from the model (DESIGN.md §1, the paper's prop:proj-micro and
eq:dyn-micro), NOT from the Rust sources, and with a different algorithm:

* the Rust engine answers `run` by a pool-adjacent-violators projection and
  `events` by a priority queue of cluster collision times;
* this oracle simulates sticky (perfectly inelastic, momentum-conserving)
  collisions by repeatedly SCANNING all adjacent cluster pairs for the
  smallest meeting time, merging every chain of clusters that meet at that
  same instant.  Each boundary between particles i and i+1 gets the time at
  which it first lies inside one cluster ("join time"); the state at time t
  is then read off the partition {boundaries with join time <= t}.

Model facts used (0-based particle index i, equal masses):

* translated positions  y_i = x_i - 2r*i;  a cluster C (a run of particles)
  moves, from its formation on, with  y_i(t) = (sum_C y0 + t sum_C u0) / |C|
  (free motion of its centre of mass) and velocity mean_C u0;
* two adjacent clusters L, R collide when their translated positions meet
  with  ubar_L > ubar_R;
* at t = 0 particles in contact (y_{i+1} = y_i) with equal velocities form
  one cluster; in contact with u_{i+1} > u_i they separate at once;
* u(t) is the right derivative (all merges at times <= t are applied);
* multipliers  lambda_i = (1/N) sum_{j<=i} (u0_j - u_j(t)),  i = 1..N-1
  (eq:dyn-micro:  u_i - u0_i = -N (lambda_i - lambda_{i-1}), lambda_0 = 0);
* `clusters` are the contact clusters of x(t): maximal runs with
  x_{i+1} - x_i == 2r exactly, as [first (0-based), size].

Scenes: `[particles]` (radius default 1/(2N)) and `[macro]` (quantile
sampling x0_i = X0(i/N), u0_i = U0(i/N), i = 1..N, radius 1/(2N); X0 is
left-continuous at the mass breakpoints; an affine block velocity [a, b] is
a at `from` and b at `to`, evaluated at X0(w)).

Usage:
  python3 scripts/oracle.py run SCENE --at T [--at T ...]
  python3 scripts/oracle.py events SCENE
  python3 scripts/oracle.py batch JOBS     (JOBS: a file, or - for stdin)
  python3 scripts/oracle.py selftest SCENE...  (integer fast path == Fraction
                                                reference, at every event time)

A batch file holds one job per line, fields separated by TABs:
  run<TAB>SCENE<TAB>T1<TAB>T2...   -> one JSON line per time
  events<TAB>SCENE                 -> one JSON line
Output is the concatenation of the jobs' outputs, in order.  An invalid job
prints one line `error: ...` instead (and the exit code is 1 at the end).

Python 3.11+ standard library only.
"""

import argparse
import json
import re
import sys
import tomllib
from fractions import Fraction
from math import gcd, lcm


class OracleError(Exception):
    """Bad input (scene or time)."""


# ------------------------------------------------------------------ numbers

_FRACTION = re.compile(r"[+-]?[0-9]+/[0-9]+")
_DECIMAL = re.compile(r"[+-]?[0-9]+(\.[0-9]+)?([eE][+-]?[0-9]+)?")


def parse_number(text):
    """An exact rational from an integer, "p/q", decimal or scientific text."""
    s = text.strip()
    if _FRACTION.fullmatch(s):
        num, den = s.split("/")
        if int(den) == 0:
            raise OracleError(f"zero denominator in {text!r}")
        return Fraction(int(num), int(den))
    if _DECIMAL.fullmatch(s):
        # Fraction reads decimal and scientific text exactly.
        return Fraction(s)
    raise OracleError(f"not an exact number: {text!r}")


def exact_value(value, field):
    # bool is a subclass of int in Python: refuse it explicitly.
    if isinstance(value, bool):
        raise OracleError(f"{field}: a boolean is not a number")
    if isinstance(value, int):
        return Fraction(value)
    if isinstance(value, str):
        return parse_number(value)
    if isinstance(value, float):
        raise OracleError(f"{field}: TOML float {value!r} refused (quote it)")
    raise OracleError(f"{field}: not an exact number")


def ratio(num, den):
    """render(num/den) for integers, den > 0, without building a Fraction."""
    g = gcd(num, den)
    num //= g
    den //= g
    return str(num) if den == 1 else f"{num}/{den}"


def render(q):
    """Lowest terms, "p/q" or "p", sign on p (what str(Fraction) does)."""
    q = Fraction(q)
    if q.denominator == 1:
        return str(q.numerator)
    return f"{q.numerator}/{q.denominator}"


# ------------------------------------------------------------------- scenes


def load_scene(path):
    """(radius, positions, velocities) of a scene file, all Fractions."""
    try:
        with open(path, "rb") as f:
            doc = tomllib.load(f)
    except OSError as e:
        raise OracleError(f"{path}: {e}") from e
    except tomllib.TOMLDecodeError as e:
        raise OracleError(f"{path}: not TOML: {e}") from e
    has_p, has_m = "particles" in doc, "macro" in doc
    if has_p == has_m:
        raise OracleError(f"{path}: need exactly one of [particles], [macro]")
    if has_p:
        radius, x, u = particles_section(doc["particles"])
    else:
        radius, x, u = macro_section(doc["macro"])
    validate(radius, x, u)
    return radius, x, u


def particles_section(p):
    x = [exact_value(v, f"positions[{k}]") for k, v in enumerate(p["positions"])]
    u = [exact_value(v, f"velocities[{k}]") for k, v in enumerate(p["velocities"])]
    if len(x) != len(u):
        raise OracleError("positions and velocities differ in length")
    if not x:
        raise OracleError("no particles")
    if "radius" in p:
        radius = exact_value(p["radius"], "radius")
    else:
        radius = Fraction(1, 2 * len(x))
    return radius, x, u


def macro_section(m):
    n = exact_value(m["particles"], "particles")
    if n.denominator != 1 or n < 1:
        raise OracleError("macro.particles must be a positive integer")
    n = int(n)
    blocks = []
    for k, b in enumerate(m["blocks"]):
        lo = exact_value(b["from"], f"blocks[{k}].from")
        hi = exact_value(b["to"], f"blocks[{k}].to")
        rho = exact_value(b["density"], f"blocks[{k}].density")
        vel = b["velocity"]
        if isinstance(vel, list):
            if len(vel) != 2:
                raise OracleError(f"blocks[{k}].velocity: need [a, b]")
            va = exact_value(vel[0], f"blocks[{k}].velocity[0]")
            vb = exact_value(vel[1], f"blocks[{k}].velocity[1]")
        else:
            va = vb = exact_value(vel, f"blocks[{k}].velocity")
        if not lo < hi:
            raise OracleError(f"block {k + 1} is empty")
        if not (0 < rho <= 1):
            raise OracleError(f"block {k + 1}: density {rho} not in (0, 1]")
        if rho == 1 and va != vb:
            raise OracleError(f"block {k + 1}: congested with varying velocity")
        if blocks and lo < blocks[-1][1]:
            raise OracleError(f"block {k + 1}: unsorted or overlapping")
        blocks.append((lo, hi, rho, va, vb))
    if not blocks:
        raise OracleError("no blocks")
    # Cumulative masses m_0 = 0 < m_1 < ... < m_B.
    cum = [Fraction(0)]
    for lo, hi, rho, _, _ in blocks:
        cum.append(cum[-1] + rho * (hi - lo))
    if cum[-1] != 1:
        raise OracleError(f"total mass {render(cum[-1])} is not 1")
    x, u = [], []
    b = 0
    for i in range(1, n + 1):
        w = Fraction(i, n)
        # Block b with m_{b-1} < w <= m_b (X0 left-continuous).
        while not (cum[b] < w <= cum[b + 1]):
            b += 1
        lo, hi, rho, va, vb = blocks[b]
        xi = lo + (w - cum[b]) / rho
        ui = va + (vb - va) * (xi - lo) / (hi - lo)
        x.append(xi)
        u.append(ui)
    return Fraction(1, 2 * n), x, u


def validate(radius, x, u):
    if radius <= 0:
        raise OracleError("radius must be positive")
    two_r = 2 * radius
    for i in range(len(x) - 1):
        gap = x[i + 1] - x[i]
        if gap < two_r:
            raise OracleError(f"particles {i + 1} and {i + 2} overlap")
        if gap == two_r and u[i] > u[i + 1]:
            raise OracleError(f"particles {i + 1} and {i + 2} approach in contact")


# ---------------------------------------------------------------- dynamics


class Trajectory:
    """Sticky dynamics by repeated scanning of adjacent cluster pairs.

    All sums are kept as integers over a common denominator D (the lcm of
    the denominators of y0, u0 and 2r), so that the O(N) work per requested
    time is integer arithmetic; `state_reference` is the same computation
    with Fractions throughout (used by the `selftest` command).
    """

    def __init__(self, radius, x, u):
        self.radius = radius
        self.two_r = 2 * radius
        self.n = len(x)
        self.u0 = list(u)
        self.y0 = [x[i] - self.two_r * i for i in range(self.n)]
        d = self.two_r.denominator
        for v in self.y0 + self.u0:
            d = lcm(d, v.denominator)
        self.d = d
        self.r_int = int(self.two_r * d)
        # Prefix sums of D*y0 and D*u0: cluster [a, b) has sums pre[b] - pre[a].
        self.py = [0]
        self.pu = [0]
        for i in range(self.n):
            self.py.append(self.py[-1] + int(self.y0[i] * d))
            self.pu.append(self.pu[-1] + int(self.u0[i] * d))
        # join[i]: the time from which particles i and i+1 share a cluster;
        # None: never; -1: from the start.
        self.join = [None] * (self.n - 1)
        self.events = []
        self._simulate()

    def _sums(self, a, b):
        return self.py[b] - self.py[a], self.pu[b] - self.pu[a]

    def _meeting_time(self, a, m, b):
        """Time at which clusters [a, m) and [m, b) meet, or None."""
        sy_l, su_l = self._sums(a, m)
        sy_r, su_r = self._sums(m, b)
        kl, kr = m - a, b - m
        # Mean velocities su/k (times D): collide iff su_l/kl > su_r/kr.
        closing = su_l * kr - su_r * kl
        if closing <= 0:
            return None
        # (sy_l + t su_l)/kl = (sy_r + t su_r)/kr
        return Fraction(sy_r * kl - sy_l * kr, closing)

    def _simulate(self):
        n = self.n
        # Initial clusters: runs joined by contact with equal velocities.
        clusters = []
        start = 0
        for i in range(n - 1):
            if self.y0[i + 1] == self.y0[i] and self.u0[i + 1] == self.u0[i]:
                self.join[i] = -1
            else:
                clusters.append((start, i + 1))
                start = i + 1
        clusters.append((start, n))
        # times[k]: meeting time of clusters[k] and clusters[k+1].
        times = [self._meeting_time(clusters[k][0], clusters[k][1], clusters[k + 1][1])
                 for k in range(len(clusters) - 1)]
        now = Fraction(0)
        while True:
            t = None
            for s in times:
                if s is not None and (t is None or s < t):
                    t = s
            if t is None:
                break
            if t < now:
                raise AssertionError(f"collision in the past: {t} < {now}")
            if t == 0:
                raise AssertionError("collision at t = 0 (approaching contact)")
            now = t
            # Merge every maximal chain of pairs meeting at t.
            new_clusters, new_times, fresh = [], [], []
            k = 0
            while k < len(clusters):
                if k < len(times) and times[k] == t:
                    j = k
                    while j < len(times) and times[j] == t:
                        j += 1
                    parts = clusters[k:j + 1]
                    a, b = parts[0][0], parts[-1][1]
                    for i in range(a, b - 1):
                        if self.join[i] is None:
                            self.join[i] = t
                    self.events.append((t, a, b - a, [q - p for p, q in parts]))
                    changed, after = True, j
                else:
                    a, b = clusters[k]
                    changed, after = False, k
                if new_clusters:
                    # Pair (previous, this): unchanged only if neither moved.
                    if changed or fresh[-1]:
                        new_times.append(None)  # recomputed below
                    else:
                        new_times.append(times[k - 1])
                new_clusters.append((a, b))
                fresh.append(changed)
                k = after + 1
            for p in range(len(new_clusters) - 1):
                if fresh[p] or fresh[p + 1]:
                    (a, m), (_, b) = new_clusters[p], new_clusters[p + 1]
                    new_times[p] = self._meeting_time(a, m, b)
            clusters, times = new_clusters, new_times
        self.final_clusters = clusters

    def _bounds(self, t):
        """Cluster boundaries at time t (merges at times <= t applied)."""
        bounds = [0]
        for i in range(self.n - 1):
            j = self.join[i]
            if j is None or j > t:
                bounds.append(i + 1)
        bounds.append(self.n)
        return bounds

    def state(self, t):
        n, d, r = self.n, self.d, self.r_int
        p, q = t.numerator, t.denominator
        bounds = self._bounds(t)
        x, u, lam = [], [], []
        contact = []
        prev = None  # (translated position numerator, k) of the previous cluster
        first = 0
        for a, b in zip(bounds, bounds[1:]):
            sy, su = self._sums(a, b)
            k = b - a
            # Translated position y = (sy + t su)/(D k) = base/(D q k).
            base = sy * q + p * su
            den = d * q * k
            step = r * q * k
            for i in range(a, b):
                x.append(ratio(base + step * i, den))
            v = ratio(su, d * k)
            u.extend([v] * k)
            # lambda_i = (1/N) sum_{j<=i} (u0_j - u_j): the running sum
            # vanishes at every cluster end (u = cluster mean of u0).
            pa = self.pu[a]
            for i in range(a, min(b, n - 1)):
                lam.append(ratio((self.pu[i + 1] - pa) * k - (i + 1 - a) * su, n * d * k))
            # Contact with the previous cluster: equal translated positions.
            if prev is not None and prev[0] * k != base * prev[1]:
                contact.append([first, a - first])
                first = a
            prev = (base, k)
        contact.append([first, n - first])
        return {
            "n": n,
            "radius": render(self.radius),
            "t": render(t),
            "positions": x,
            "velocities": u,
            "multipliers": lam,
            "clusters": contact,
        }

    def state_reference(self, t):
        """`state` with Fractions throughout, straight from the model."""
        n, two_r = self.n, self.two_r
        bounds = self._bounds(t)
        x = [None] * n
        u = [None] * n
        for a, b in zip(bounds, bounds[1:]):
            k = b - a
            ybar = sum(self.y0[a:b], Fraction(0)) / k
            v = sum(self.u0[a:b], Fraction(0)) / k
            for i in range(a, b):
                x[i] = ybar + t * v + two_r * i
                u[i] = v
        lam = []
        acc = Fraction(0)
        for i in range(n - 1):
            acc += self.u0[i] - u[i]
            lam.append(acc / n)
        contact = []
        start = 0
        for i in range(n - 1):
            if x[i + 1] - x[i] != two_r:
                contact.append([start, i + 1 - start])
                start = i + 1
        contact.append([start, n - start])
        return {
            "n": n,
            "radius": render(self.radius),
            "t": render(t),
            "positions": [render(v) for v in x],
            "velocities": [render(v) for v in u],
            "multipliers": [render(v) for v in lam],
            "clusters": contact,
        }

    def events_json(self):
        ev = sorted(self.events, key=lambda e: (e[0], e[1]))
        return {"events": [{"t": render(t), "first": a, "size": k, "parts": parts}
                           for t, a, k, parts in ev]}


def dumps(obj):
    return json.dumps(obj, separators=(", ", ": "), ensure_ascii=False)


def parse_time(text):
    t = parse_number(text)
    if t < 0:
        raise OracleError(f"time {text} is negative")
    return t


def job_lines(cmd, scene, times):
    radius, x, u = load_scene(scene)
    traj = Trajectory(radius, x, u)
    if cmd == "run":
        return [dumps(traj.state(t)) for t in times]
    if cmd == "events":
        return [dumps(traj.events_json())]
    raise OracleError(f"unknown command {cmd!r}")


def selftest(scenes):
    """Compares `state` with `state_reference` at 0, every event time, the
    midpoints and one time past the last event."""
    count = 0
    for scene in scenes:
        traj = Trajectory(*load_scene(scene))
        ts = sorted({e[0] for e in traj.events})
        times = [Fraction(0)] + ts + [(a + b) / 2 for a, b in zip([Fraction(0)] + ts, ts)]
        times.append((ts[-1] if ts else Fraction(0)) + 1)
        for t in times:
            if traj.state(t) != traj.state_reference(t):
                print(f"selftest: {scene}: mismatch at t = {render(t)}", file=sys.stderr)
                return 1
            count += 1
    print(f"selftest: {len(scenes)} scenes, {count} times agree")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("scene")
    r.add_argument("--at", action="append", required=True)
    e = sub.add_parser("events")
    e.add_argument("scene")
    b = sub.add_parser("batch")
    b.add_argument("jobs")
    st = sub.add_parser("selftest", help="integer fast path == Fraction reference")
    st.add_argument("scene", nargs="+")
    args = ap.parse_args(argv)
    out = sys.stdout
    try:
        if args.cmd == "selftest":
            return selftest(args.scene)
        if args.cmd == "run":
            times = [parse_time(s) for s in args.at]
            out.write("\n".join(job_lines("run", args.scene, times)) + "\n")
        elif args.cmd == "events":
            out.write(job_lines("events", args.scene, [])[0] + "\n")
        else:
            f = sys.stdin if args.jobs == "-" else open(args.jobs, encoding="utf-8")
            failed = False
            with f:
                for line in f:
                    line = line.rstrip("\n")
                    if not line:
                        continue
                    cmd, scene, *ts = line.split("\t")
                    try:
                        lines = job_lines(cmd, scene, [parse_time(s) for s in ts])
                    except OracleError as err:
                        failed = True
                        lines = [f"error: {err}"]
                    out.write("\n".join(lines) + "\n")
            return 1 if failed else 0
    except OracleError as err:
        print(f"error: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
