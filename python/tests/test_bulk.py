"""The bulk outputs (issue 38): `exact_positions()` and its siblings,
`state.to_dict()` and `export` built straight from the library's values —
the same values, types and keys as the general path and the command line's
JSON, and Ctrl-C honoured inside the loops that hold the GIL."""

import json
import os
import signal
import subprocess
import sys
import time
from fractions import Fraction

import numpy as np
import pytest

import sticky

RADIUS = 4e-7
T = 0.01


def notebook(n, seed=38):
    """Doubles as a notebook makes them (benches/python_api.py)."""
    rng = np.random.default_rng(seed)
    gaps = 2 * RADIUS * (1 + 1e-9) + rng.exponential(1e-6, size=n)
    return np.cumsum(gaps), rng.uniform(-1.0, 1.0, size=n)


def two_ways(n):
    """The same scene from doubles (the dyadic path) and from Fractions of
    the same values (the general path)."""
    x, u = notebook(n)
    fast = sticky.Scene(x, u, RADIUS)
    general = sticky.Scene([Fraction(v) for v in x], [Fraction(v) for v in u], Fraction(RADIUS))
    return fast, general


def test_exact_lists_are_the_general_paths_fractions():
    fast, general = two_ways(3000)
    for t in (T, Fraction(1, 3), 0):
        a, b = fast.state(t), general.state(t)
        for name in ("exact_positions", "exact_velocities", "exact_multipliers"):
            got, want = getattr(a, name)(), getattr(b, name)()
            assert got == want, name
            assert all(type(f) is Fraction for f in got)
            # Lowest terms and a positive denominator, as Fraction keeps them.
            assert all(Fraction(f.numerator, f.denominator) == f for f in got)
            assert [hash(f) for f in got] == [hash(f) for f in want]


def test_fractions_behave_as_the_constructors():
    x, u = notebook(50)
    got = sticky.Scene(x, u, RADIUS).state(T).exact_positions()
    for f in got:
        again = Fraction(f.numerator, f.denominator)
        assert (f.numerator, f.denominator, str(f), repr(f)) == (
            again.numerator,
            again.denominator,
            str(again),
            repr(again),
        )
        assert f + 1 == again + 1 and float(f) == float(again)
    assert isinstance(got, list)


def test_state_dict_is_the_command_lines_json(tmp_path):
    fast, general = two_ways(2000)
    state = fast.state(T)
    d = state.to_dict()
    assert d == general.state(T).to_dict()
    assert list(d) == ["n", "radius", "t", "positions", "velocities", "multipliers", "clusters"]
    assert d["positions"] == [str(f) for f in state.exact_positions()]
    assert d["multipliers"] == [str(f) for f in state.exact_multipliers()]
    assert d["clusters"] == [list(c) for c in state.clusters]
    assert d["t"] == str(Fraction(T)) and d["radius"] == str(Fraction(RADIUS))
    # The command line's object, through its text.
    assert json.loads(json.dumps(d)) == d


def test_export_of_doubles_is_the_general_export():
    fast, general = two_ways(2000)
    a, b = sticky.export(fast), sticky.export(general)
    assert a == b
    assert json.dumps(a) == json.dumps(b)  # keys in the same order too
    assert a["positions"]["error"][0] == "0" and a["f64_admissible"] is True


def test_export_of_signed_zeros_and_overlapping_doubles():
    # -0.0 is the value 0 (its double 0.0); a radius just under half the
    # smallest gap, not a double: its rounding error is exported too.
    x = [-1.0, -0.0, 1 / 3, 2 / 3]
    u = [0.5, -0.0, 0.0, -0.25]
    r = (Fraction(1 / 3) - Fraction(1, 10**30)) / 2
    a = sticky.export(sticky.Scene(x, u, r))
    b = sticky.export(sticky.Scene([Fraction(v) for v in x], [Fraction(v) for v in u], r))
    assert json.dumps(a) == json.dumps(b)
    assert a["velocities"]["f64"][1] == 0.0 and str(a["velocities"]["f64"][1]) == "0.0"


def interrupted_after(call, delay):
    """Seconds from a real SIGINT (sent by another process `delay` seconds
    after the call starts) to KeyboardInterrupt; None when the call ended
    first. The call holds the GIL: only the signal's C handler runs. The
    other process says when it has started, so its start-up is not counted
    in the delay."""
    script = (
        "import os, sys, time; print(flush=True); sys.stdin.readline(); "
        f"time.sleep({delay}); os.kill({os.getpid()}, {int(signal.SIGINT)})"
    )
    killer = subprocess.Popen(
        [sys.executable, "-c", script], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    killer.stdout.readline()
    killer.stdin.write("\n")
    killer.stdin.flush()
    start = time.monotonic()
    try:
        call()
    except KeyboardInterrupt:
        return time.monotonic() - start - delay
    finally:
        killer.wait()
    # Ended before the signal: let it arrive here, outside the call.
    try:
        time.sleep(5)
    except KeyboardInterrupt:
        pass
    return None


@pytest.mark.skipif(not hasattr(signal, "SIGINT") or os.name != "posix", reason="POSIX signals")
def test_bulk_loops_stop_on_ctrl_c():
    x, u = notebook(400_000)
    scene = sticky.Scene(x, u, RADIUS)
    state = scene.state(T)
    state.exact_velocities()  # the exact state, computed once
    for call in (state.exact_positions, state.to_dict, lambda: sticky.export(scene)):
        start = time.monotonic()
        call()
        whole = time.monotonic() - start
        if whole < 0.2:
            continue  # too fast here to be cut short
        late = interrupted_after(call, whole / 4)
        assert late is not None and late < whole / 3, (call, whole, late)
