"""States of numpy float64 scenes (the dyadic path): the positions at once,
the velocities and multipliers on first access, every double the nearest
double of the exact value, on one thread and on two (N ≥ 2^16)."""

import numpy as np
import pytest

import sticky


def scene_of_doubles(n, seed):
    """Grid-like positions with contacts and random full-precision
    velocities: large blocks at t = 1/4."""
    rng = np.random.default_rng(seed)
    r = 2.0**-21
    x = (2 * np.arange(n) + np.cumsum(rng.integers(0, 3, size=n))) * 2.0**-20
    u = rng.random(n) * 2 - 1
    return sticky.Scene(x, u, r)


@pytest.mark.parametrize("n", [1, 2, 1000, 1 << 17])
def test_lazy_arrays_are_the_nearest_doubles_of_the_exact_state(n):
    scene = scene_of_doubles(n, n)
    s = scene.state(0.25)
    x = s.positions
    # The same arrays on every access (cached), of the right lengths.
    u, lam = s.velocities, s.multipliers
    assert s.velocities is u and s.multipliers is lam
    assert (len(x), len(u), len(lam)) == (n, n, n - 1)
    # float(Fraction) is the correctly rounded double.
    assert list(x) == [float(v) for v in s.exact_positions()]
    assert list(u) == [float(v) for v in s.exact_velocities()]
    assert list(lam) == [float(v) for v in s.exact_multipliers()]
    if n > 1000:
        # The scene has large blocks: the test sees pooled multipliers.
        assert np.count_nonzero(lam) > n // 2


def test_arrays_read_in_any_order_agree():
    scene = scene_of_doubles(1 << 17, 5)
    a, b = scene.state(0.25), scene.state(0.25)
    lam_first = a.multipliers
    assert np.array_equal(lam_first, b.multipliers)
    assert np.array_equal(a.velocities, b.velocities)
    assert np.array_equal(a.positions, b.positions)
