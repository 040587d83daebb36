"""Speed of sticky.Scene.state(t) on numpy arrays of 10^6 doubles, against
scipy.optimize.isotonic_regression on the same arrays, in one process.

Not a test: a measurement (issue 27). Run after `pip install ./python`:

    python benches/python_state.py [N] [REPEATS]

Data: N particles, r = 2^-21. "Grid doubles": positions x0_i =
(2i + g_0 + ... + g_i) 2^-20 with g_j uniform in {0, ..., 3}, velocities u0_i = k_i / 64
with k_i uniform in {-64, ..., 64} (doubles with short binary denominators,
as a solver's grid data are). "Random doubles": x0_i = 4r i + r v_i,
u0_i = 2 w_i - 1 with v_i, w_i uniform in [0, 1) (53-bit mantissas at
every scale: the first positions have denominators beyond 64 bits). Both
take the dyadic path (sticky.fast::dyadic: i128 columns over dyadic
scales, one rounding per value, no big number). sticky answers
x(t) = P_K(x0 + t u0) exactly, then rounds to the nearest doubles; scipy
gets the shifted free flight y = x0 + t u0 - 2r i, already computed, and
runs its floating-point PAVA and returns one array (the projection).

Two figures for sticky, never to be mixed up:
* `state(t).positions`: the state with its positions only, the like-for-like
  figure against scipy (the velocities and multipliers of a State are
  computed on first access);
* `state(t)`, all three arrays read: positions, velocities, multipliers.
"Notebook doubles" (issue 38): x0 = np.cumsum of exponential gaps (scale 1)
plus 4r each, so every gap exceeds 2r with room for the rounding of the
cumsum, u0 uniform in [-1, 1], radius = 4e-7 and t = 0.01, both Python
floats with full mantissas: t and r are doubles, the data stay dyadic and
take the dyadic path on wider sums. There the build counts too: a fresh
`Scene(x0, u0, 4e-7)` plus `state(0.01).positions`, timed as one call, as
a notebook user runs it once. Beside it, numpy's copies of the two
columns: a fresh Scene moves its columns through memory more than once,
scipy's PAVA mostly computes, so the ratio moves with the memory's pace
of the moment (on a shared machine it changes from minute to minute).

Each timing is the median of REPEATS runs, the tools alternating; wall time
(`time.perf_counter`) and the process's CPU time (`time.process_time`, all
threads: sticky uses two cores above 2^16 particles, scipy one).
"""

import statistics
import sys
import time

import numpy as np
from scipy.optimize import isotonic_regression

import sticky


def timed(f):
    """(wall, cpu) seconds of one call of f."""
    wall, cpu = time.perf_counter(), time.process_time()
    f()
    return time.perf_counter() - wall, time.process_time() - cpu


def median(pairs):
    return tuple(statistics.median(p[i] for p in pairs) for i in range(2))


def all_three(scene, t):
    s = scene.state(t)
    return s.positions, s.velocities, s.multipliers


def fresh(x0, u0, radius, t):
    """A fresh Scene and the positions of its state at t."""
    return sticky.Scene(x0, u0, radius).state(t).positions


def compare(label, x0, u0, radius, t, repeats, with_build=False):
    n = len(x0)
    start = time.perf_counter()
    scene = sticky.Scene(x0, u0, radius)
    build = time.perf_counter() - start
    y = x0 + t * u0 - 2 * radius * np.arange(n)
    pos, full, theirs, built, copies = [], [], [], [], []
    for _ in range(repeats):
        if with_build:
            built.append(timed(lambda: fresh(x0, u0, radius, t)))
            copies.append(timed(lambda: (x0.copy(), u0.copy())))
        pos.append(timed(lambda: scene.state(t).positions))
        full.append(timed(lambda: all_three(scene, t)))
        theirs.append(timed(lambda: isotonic_regression(y)))
    (a, a_cpu), (f, f_cpu), (b, b_cpu) = median(pos), median(full), median(theirs)
    s = scene.state(t)
    check = isotonic_regression(y).x + 2 * radius * np.arange(n)
    err = np.max(np.abs(s.positions - check))
    print(f"{label}: N = {n}, t = {t}")
    print(f"  Scene(...)               {build * 1e3:9.1f} ms (validation, once)")
    print("                              wall ms    CPU ms")
    if with_build:
        (c, c_cpu) = median(built)
        print(f"  Scene + state(t).positions{c * 1e3:8.1f} {c_cpu * 1e3:9.1f} (fresh Scene each time)")
        (m, m_cpu) = median(copies)
        print(f"  x0.copy(), u0.copy()     {m * 1e3:9.1f} {m_cpu * 1e3:9.1f} (numpy: the memory's pace)")
    print(f"  state(t).positions       {a * 1e3:9.1f} {a_cpu * 1e3:9.1f} (exact, rounded to float64)")
    print(f"  state(t), all 3 arrays   {f * 1e3:9.1f} {f_cpu * 1e3:9.1f} (x, u, lambda)")
    print(f"  scipy isotonic_regression{b * 1e3:9.1f} {b_cpu * 1e3:9.1f} (float64, x only)")
    if with_build:
        print(f"  ratio Scene + pos / scipy{c / b:9.2f} (wall)")
    print(f"  ratio positions / scipy  {a / b:9.2f} (wall; like for like)")
    print(f"  ratio all 3 / scipy      {f / b:9.2f} (wall)")
    print(f"  max |sticky - scipy|     {err:9.2e} (scipy's rounding)")
    return a / b


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 10**6
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    rng = np.random.default_rng(27)
    radius = 2.0**-21
    x0 = (2 * np.arange(n) + np.cumsum(rng.integers(0, 4, size=n))) * 2.0**-20
    u0 = rng.integers(-64, 65, size=n) / 64
    compare("grid doubles", x0, u0, radius, 0.25, repeats)
    xr = 4 * radius * np.arange(n) + radius * rng.random(n)
    ur = rng.random(n) * 2 - 1
    compare("random doubles", xr, ur, radius, 0.25, repeats)
    radius = 4e-7
    xn = np.cumsum(rng.exponential(1.0, size=n) + 4 * radius)
    un = rng.uniform(-1.0, 1.0, size=n)
    assert np.min(np.diff(xn)) >= 2 * radius
    compare("notebook doubles", xn, un, radius, 0.01, repeats, with_build=True)


if __name__ == "__main__":
    main()
