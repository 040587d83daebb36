"""sticky.isotonic against scipy's isotonic regression (equal up to scipy's
rounding) and against a plain exact PAVA on Fractions (equal exactly)."""

import random
from fractions import Fraction as F

import numpy as np
import pytest

import sticky


def pava(z):
    """Pool-adjacent-violators on exact Fractions: the textbook algorithm."""
    blocks = []  # [sum, count]
    for v in z:
        blocks.append([F(v), 1])
        while len(blocks) > 1 and blocks[-2][0] * blocks[-1][1] > blocks[-1][0] * blocks[-2][1]:
            s, c = blocks.pop()
            blocks[-1][0] += s
            blocks[-1][1] += c
    return [s / c for s, c in blocks for _ in range(c)]


def test_exact_against_a_fraction_pava():
    rng = np.random.default_rng(1)
    for n in [1, 2, 3, 10, 100, 1000]:
        z = rng.normal(size=n)
        assert sticky.isotonic(z, exact=True) == pava([F(v) for v in z])
    pyrng = random.Random(3)
    for _ in range(50):
        z = [F(pyrng.randint(-20, 20), pyrng.randint(1, 7)) for _ in range(pyrng.randint(1, 30))]
        assert sticky.isotonic(z, exact=True) == pava(z)


def test_against_scipy():
    scipy_optimize = pytest.importorskip("scipy.optimize")
    rng = np.random.default_rng(2)
    for n in [1, 5, 50, 1000, 20000]:
        z = np.cumsum(rng.normal(size=n)) + rng.normal(scale=3, size=n)
        ours = sticky.isotonic(z)
        theirs = scipy_optimize.isotonic_regression(z).x
        assert ours.dtype == np.float64 and ours.shape == z.shape
        # scipy averages in floating point: a few ulps of its rounding.
        np.testing.assert_allclose(ours, theirs, rtol=1e-12, atol=1e-12)
        # Ours is the nearest double of the exact answer.
        exact = sticky.isotonic(z, exact=True)
        assert list(ours) == [float(v) for v in exact]


def test_project_is_isotonic_in_shifted_coordinates():
    scene = sticky.Scene([0, 1, 2, 3], [0, 0, 0, 0], "1/4")
    z = [3, F(1, 3), 0, 5]
    shifted = [F(v) - F(1, 2) * i for i, v in enumerate(z)]
    want = [v + F(1, 2) * i for i, v in enumerate(pava(shifted))]
    assert scene.project(z, exact=True) == want


def test_doubles_of_the_filter_are_the_nearest_of_the_exact_answer():
    # Notebook-like data (the certified filter proves most of them), a
    # signed zero, and a radius that is a double with a full mantissa.
    rng = np.random.default_rng(38)
    radius = 4e-7
    x = np.cumsum(rng.exponential(1.0, size=3000) + 4 * radius)
    z = x + 0.5 * rng.uniform(-1.0, 1.0, size=3000)
    z[0] = -0.0
    ours = sticky.isotonic(z)
    assert [v.hex() for v in ours] == [float(v).hex() for v in sticky.isotonic(z, exact=True)]
    scene = sticky.Scene(x, np.zeros(3000), radius)
    ours = scene.project(z)
    assert [v.hex() for v in ours] == [float(v).hex() for v in scene.project(z, exact=True)]
