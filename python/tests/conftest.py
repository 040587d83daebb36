"""Shared helpers of the sticky Python tests: paths and random scenes."""

import copy
import os
import random
from fractions import Fraction
from pathlib import Path

import pytest

import sticky

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"


def random_scene(rng: random.Random, n_max: int = 12):
    """Random admissible data (x0 in K, u0 in the velocity cone), exact.

    Gaps are 2r plus a small non-negative fraction (zero often: contacts
    at t = 0), velocities small fractions, raised across a contact so that
    touching particles never approach.
    """
    n = rng.randint(1, n_max)
    radius = Fraction(rng.randint(1, 4), rng.randint(1, 8))
    x = [Fraction(rng.randint(-8, 8), rng.randint(1, 4))]
    u = [Fraction(rng.randint(-6, 6), rng.randint(1, 3))]
    for _ in range(n - 1):
        extra = Fraction(0) if rng.random() < 0.3 else Fraction(rng.randint(0, 12), rng.randint(1, 6))
        x.append(x[-1] + 2 * radius + extra)
        v = Fraction(rng.randint(-6, 6), rng.randint(1, 3))
        if extra == 0 and v < u[-1]:
            v = u[-1] + Fraction(rng.randint(0, 3), 2)
        u.append(v)
    return x, u, radius


def scene_toml(x, u, radius) -> str:
    """The data as a [particles] scene file, every value an exact string."""
    q = lambda v: ", ".join(f'"{f}"' for f in v)
    return f'[particles]\nradius = "{radius}"\npositions = [{q(x)}]\nvelocities = [{q(u)}]\n'


@pytest.fixture
def sticky_bin():
    """The built command line: $STICKY_BIN, or target/release/sticky."""
    path = os.environ.get("STICKY_BIN") or str(ROOT / "target" / "release" / "sticky")
    if not os.access(path, os.X_OK):
        pytest.skip(f"no sticky binary at {path}: build it (cargo build --release) or set STICKY_BIN")
    return path


# The ledger costs about a minute of CPU at its smallest budget: a session
# runs it once per budget (test_claims.py checks it; the guide's example
# calls it too). A call that raises (Ctrl-C, a bad argument) is not kept.
_ledgers = {}
_claims = sticky.claims


def _claims_once(*args, **kwargs):
    key = (args, tuple(sorted(kwargs.items())))
    if key not in _ledgers:
        _ledgers[key] = _claims(*args, **kwargs)
    return copy.deepcopy(_ledgers[key])


sticky.claims = _claims_once
