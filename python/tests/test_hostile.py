"""Hostile arguments for every public function and method: only the
documented exceptions come out (a ``sticky.StickyError`` — each also a
ValueError, OSError or TypeError — or a plain TypeError from argument
parsing), never a PanicException, an OverflowError or a crash.

The budget is fixed (``EXAMPLES`` per entry point) so that the suite stays
within about a minute in CI.
"""

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import sticky

EXAMPLES = 500

# Numbers and non-numbers a caller might pass where one number is expected.
scalars = st.one_of(
    st.integers(min_value=-(2**70), max_value=2**70),
    st.sampled_from([2**64 - 1, 2**64, -1, 0, 1, 2**63]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.booleans(),
    st.none(),
    st.fractions(max_denominator=10**6),
    st.sampled_from(["1/3", "0.5", "1/0", "nan", "", "1e99999999", "x", "-1", "1e-3"]),
    st.sampled_from([np.float64("nan"), np.float32(0.5), np.int64(3), np.bool_(True), 1j, object()]),
    st.sampled_from([np.array(1.0), np.array([]), np.array([[1.0]])]),
)

# Columns: lists (ragged too), numpy arrays of every dtype, 0-d arrays.
columns = st.one_of(
    st.lists(scalars, max_size=4),
    st.lists(st.lists(scalars, max_size=2), max_size=3),
    st.lists(st.fractions(max_denominator=50), min_size=0, max_size=5),
    st.sampled_from(
        [
            np.array([]),
            np.array(2.0),
            np.array([0.0, 1.0]),
            np.array([1.0, 0.0]),
            np.array([0, 1], dtype=np.int64),
            np.array([True, False]),
            np.array([0.5, np.nan]),
            np.array([0.0, np.inf]),
            np.array([[0.0, 1.0]]),
            np.array(["0", "1"]),
            np.array([0, 1], dtype=np.uint8),
            np.array([1 + 0j, 2]),
            np.array([0.0, 1.0], dtype=np.float32),
            np.array([0.0, 1.0])[::-1],
        ]
    ),
    scalars,
)

# Cluster fields: near the scene's N = 2, and at the edges of machine words.
counts = st.one_of(
    st.integers(min_value=-1, max_value=3),
    st.sampled_from([2**64 - 1, 2**64 - 2, 2**63, 2**64]),
)

ACCEPTED = (sticky.StickyError, TypeError)

SCENE = sticky.Scene([0, 1], [0, 0], "1/4")

quick = settings(
    max_examples=EXAMPLES,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)


def calls(f, *args, **kwargs):
    """Calls f; a documented exception is an answer too."""
    try:
        return f(*args, **kwargs)
    except ACCEPTED:
        return None


def test_every_error_class_is_documented():
    for name in sticky.errors.__all__:
        cls = getattr(sticky, name)
        assert issubclass(cls, sticky.StickyError)
        if cls is not sticky.StickyError:
            assert issubclass(cls, (ValueError, OSError, TypeError)), name


@quick
@given(columns, columns, scalars)
def test_scene(x, u, r):
    scene = calls(sticky.Scene, x, u, r)
    if scene is not None:
        calls(scene.state, 0)
        calls(sticky.export, scene)


@quick
@given(scalars)
def test_state(t):
    s = calls(SCENE.state, t)
    if s is not None:
        s.positions, s.velocities, s.multipliers, s.exact_positions(), s.to_dict()


@quick
@given(columns)
def test_states_project_isotonic(z):
    states = calls(SCENE.states, z)
    if states is not None:
        calls(list, states)  # each state is computed when read
    calls(SCENE.project, z)
    calls(SCENE.project, z, exact=True)
    calls(sticky.isotonic, z)
    calls(sticky.isotonic, z, True)


@quick
@given(st.one_of(scalars, st.slices(5)))
def test_states_index(index):
    states = SCENE.states([0, "1/2", 1])
    try:
        states[index]
    except (IndexError, *ACCEPTED):  # IndexError: as a list's
        pass


@quick
@given(
    scalars,
    columns,
    st.one_of(st.none(), columns),
    st.one_of(st.none(), columns),
    st.one_of(
        st.none(),
        st.lists(st.tuples(counts, counts), min_size=1, max_size=3),
        st.lists(st.tuples(scalars, scalars), max_size=3),
        st.lists(st.lists(scalars, max_size=3), max_size=3),
        scalars,
    ),
    st.one_of(st.none(), scalars),
    st.one_of(st.none(), scalars),
)
def test_compare(t, x, u, lam, clusters, contact_tol, overlap_tol):
    calls(
        sticky.compare,
        SCENE,
        t,
        x,
        u,
        multipliers=lam,
        clusters=clusters,
        contact_tol=contact_tol,
        overlap_tol=overlap_tol,
    )


@quick
@given(st.lists(st.tuples(counts, counts), min_size=1, max_size=3))
def test_compare_clusters(clusters):
    # A valid answer, so that the clusters are what is checked.
    calls(sticky.compare, SCENE, 1, [0, 1], [0, 0], clusters=clusters)


@quick
@given(st.integers(min_value=0, max_value=6), st.lists(st.tuples(scalars, scalars, scalars, scalars), max_size=3))
def test_from_macro(n, blocks):
    calls(sticky.Scene.from_macro, n, blocks)


@quick
@given(st.text(max_size=60))
def test_from_toml(text):
    calls(sticky.Scene.from_toml, text)
    calls(sticky.Scene.from_toml, "[particles]\n" + text)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from([-1, 2**64, 2**70, True, 1.5, "3", None, np.int64(-3)]))
def test_claims_arguments(bad):
    # Only refusals: a valid budget runs the ledger (minutes).
    if bad is None:
        return
    for key in ("cases", "max_n", "scaling_max_n", "seed"):
        with pytest.raises(ACCEPTED):
            sticky.claims(**{key: bad})


def test_the_cluster_overflow_of_the_issue():
    with pytest.raises(sticky.ArgumentError) as e:
        sticky.compare(SCENE, 1, [0, 1], clusters=[(0, 1), (1, 2**64 - 1)])
    assert e.value.argument == "clusters[1]"
    with pytest.raises(sticky.ArgumentError, match=r"clusters\[1\]"):
        sticky.compare(SCENE, 1, [0, 1], clusters=[(0, 1), (1, 2**64)])
