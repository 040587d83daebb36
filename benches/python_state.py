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
runs its floating-point PAVA. Each timing is the median of REPEATS runs,
the two tools alternating.
"""

import statistics
import sys
import time

import numpy as np
from scipy.optimize import isotonic_regression

import sticky


def timed(f):
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


def compare(label, x0, u0, radius, t, repeats):
    n = len(x0)
    start = time.perf_counter()
    scene = sticky.Scene(x0, u0, radius)
    build = time.perf_counter() - start
    y = x0 + t * u0 - 2 * radius * np.arange(n)
    ours, theirs = [], []
    for _ in range(repeats):
        ours.append(timed(lambda: scene.state(t)))
        theirs.append(timed(lambda: isotonic_regression(y)))
    a, b = statistics.median(ours), statistics.median(theirs)
    s = scene.state(t)
    check = isotonic_regression(y).x + 2 * radius * np.arange(n)
    err = np.max(np.abs(s.positions - check))
    print(f"{label}: N = {n}, t = {t}")
    print(f"  Scene(...)               {build * 1e3:9.1f} ms (validation, once)")
    print(f"  scene.state(t)           {a * 1e3:9.1f} ms (exact, rounded to float64)")
    print(f"  scipy isotonic_regression{b * 1e3:9.1f} ms (float64)")
    print(f"  ratio sticky / scipy     {a / b:9.2f}")
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
    compare("random doubles", xr, ur, radius, 0.25, max(1, repeats // 3))


if __name__ == "__main__":
    main()
