"""Properties on random scenes (hypothesis)."""

from fractions import Fraction as F

from hypothesis import given, settings
from hypothesis import strategies as st

import sticky

small = st.fractions(min_value=-5, max_value=5, max_denominator=6)


@st.composite
def scenes(draw):
    """Admissible data: gaps 2r + a non-negative extra, velocities raised
    across a contact."""
    n = draw(st.integers(1, 10))
    radius = draw(st.fractions(min_value=F(1, 16), max_value=1, max_denominator=16))
    x = [draw(small)]
    u = [draw(small)]
    for _ in range(n - 1):
        extra = draw(st.one_of(st.just(F(0)), st.fractions(min_value=0, max_value=4, max_denominator=8)))
        x.append(x[-1] + 2 * radius + extra)
        v = draw(small)
        u.append(max(v, u[-1]) if extra == 0 else v)
    return x, u, radius


times = st.fractions(min_value=0, max_value=10, max_denominator=12)


@settings(max_examples=200, deadline=None)
@given(scenes(), times)
def test_state_is_admissible_and_the_clusters_are_the_contacts(data, t):
    x0, u0, r = data
    s = sticky.Scene(x0, u0, r).state(t)
    x = s.exact_positions()
    gaps = [b - a for a, b in zip(x, x[1:])]
    assert all(g >= 2 * r for g in gaps)
    # Clusters are the maximal runs joined by contacts (indices from 0).
    firsts = [c[0] for c in s.clusters]
    assert firsts == [0] + [i + 1 for i, g in enumerate(gaps) if g != 2 * r]
    # The multipliers satisfy u - u0 = -N (λ_i - λ_{i-1}), λ_0 = λ_N = 0.
    lam = [F(0)] + s.exact_multipliers() + [F(0)]
    n = len(x)
    u = s.exact_velocities()
    assert all(u[i] - u0[i] == -n * (lam[i + 1] - lam[i]) for i in range(n))
    assert all(v >= 0 for v in lam)


@settings(max_examples=100, deadline=None)
@given(scenes(), times, times)
def test_semigroup(data, s_, dt):
    """x(s + dt) is the state at dt of the scene started from x(s), u(s)."""
    x0, u0, r = data
    scene = sticky.Scene(x0, u0, r)
    mid = scene.state(s_)
    later = sticky.Scene(mid.exact_positions(), mid.exact_velocities(), r).state(dt)
    assert later.exact_positions() == scene.state(s_ + dt).exact_positions()
