"""A scene of float64 arrays keeps its own copies in numpy arrays and runs
the certified filter on them: the caller's arrays may change after, the
scene does not, and every answer is the exact engines' one."""

import threading
from fractions import Fraction

import numpy as np

import sticky


def notebook(n, seed=7, r=4e-7):
    rng = np.random.default_rng(seed)
    xs = np.cumsum(rng.exponential(1.0 / n, n) + 2 * r)
    us = rng.uniform(-1.0, 1.0, n)
    return xs, us, r


def test_the_callers_arrays_may_change_after():
    xs, us, r = notebook(3000)
    scene = sticky.Scene(xs, us, r)
    want = scene.state(0.01)
    x0, u0 = xs.copy(), us.copy()
    xs[:] = 0.0
    us[:] = np.nan
    assert np.array_equal(scene.positions, x0)
    assert np.array_equal(scene.velocities, u0)
    got = scene.state(0.01)
    assert np.array_equal(got.positions, want.positions)
    assert np.array_equal(got.velocities, want.velocities)
    # The copies handed out are the caller's to change.
    scene.positions[:] = 1.0
    assert np.array_equal(scene.positions, x0)


def test_filtered_arrays_are_the_exact_nearest_doubles():
    xs, us, r = notebook(400, seed=11)
    scene = sticky.Scene(xs, us, r)
    t = 0.05
    s = scene.state(t)
    exact = sticky.Scene(list(map(Fraction, xs)), list(map(Fraction, us)), Fraction(r))
    e = exact.state(Fraction(t))
    assert len(e.clusters) < 400, "some particles collided"
    for got, want in [
        (s.positions, e.exact_positions()),
        (s.velocities, e.exact_velocities()),
        (s.multipliers, e.exact_multipliers()),
    ]:
        assert [float(w) for w in want] == list(got)
    assert s.clusters == e.clusters
    assert s.exact_positions() == e.exact_positions()


def test_exact_paths_and_threads_build_the_solver_once():
    xs, us, r = notebook(2000, seed=3)
    scene = sticky.Scene(xs, us, r)
    out = []

    def work():
        out.append(len(scene.events()))

    threads = [threading.Thread(target=work) for _ in range(3)]
    for th in threads:
        th.start()
    s = scene.state(Fraction(1, 3))
    for th in threads:
        th.join()
    assert len(set(out)) == 1 and out[0] > 0
    assert len(s.positions) == 2000
    assert scene.n == 2000 and scene.radius == Fraction(r)
