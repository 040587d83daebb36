"""``Scene.states(ts)``: a lazy sequence of the states at several times.

The times are read and checked when it is made; each state is computed
when it is first read and kept, so reading one state of many costs one.
"""

import copy
import pickle
from fractions import Fraction as F

import pytest

import sticky

TIMES = [0, "1/2", 3, "7/4"]


def scene():
    return sticky.Scene([0, 1, 2, 4], [1, 0, -1, -1], "1/4")


def test_a_state_is_computed_only_when_read():
    states = scene().states(TIMES)
    assert repr(states) == "States(4 times, 0 computed so far)"
    assert states[2].t == 3
    assert repr(states) == "States(4 times, 1 computed so far)"
    assert states[2] is states[2]  # kept, not computed again
    assert repr(states) == "States(4 times, 1 computed so far)"
    list(states)
    assert repr(states) == "States(4 times, 4 computed so far)"


def test_the_states_are_those_of_state():
    s = scene()
    states = s.states(TIMES)
    assert len(states) == 4
    assert states.times == [F(0), F(1, 2), F(3), F(7, 4)]
    for got, t in zip(states, TIMES):
        want = s.state(t)
        assert got.t == want.t
        assert got.exact_positions() == want.exact_positions()
        assert got.exact_velocities() == want.exact_velocities()
        assert got.clusters == want.clusters
    assert states.scene == s


def test_indexing_as_a_sequence():
    states = scene().states(TIMES)
    assert states[-1].t == F(7, 4)
    assert states[-4].t == 0
    assert [x.t for x in states[1:4:2]] == [F(1, 2), F(7, 4)]
    assert [x.t for x in states[::-1]] == [F(7, 4), F(3), F(1, 2), F(0)]
    assert states[5:] == []
    for bad in (4, -5, 2**64, -(2**70)):
        with pytest.raises(IndexError, match="out of range for 4 states"):
            states[bad]
    for bad in (True, 1.0, "1"):
        with pytest.raises(TypeError, match="integers or slices"):
            states[bad]
    it = iter(states)
    assert [x.t for x in it] == [F(0), F(1, 2), F(3), F(7, 4)]
    assert list(it) == []  # an iterator stays exhausted
    assert list(scene().states([])) == []


def test_times_are_checked_at_once():
    with pytest.raises(sticky.NegativeTimeError, match="time -1/2 is negative"):
        scene().states([1, "-1/2"])
    with pytest.raises(sticky.ArgumentTypeError, match=r"ts\[1\]"):
        scene().states([1, True])


def test_pickling_and_copies_compute_nothing():
    states = scene().states(TIMES)
    states[0]
    for again in (pickle.loads(pickle.dumps(states)), copy.deepcopy(states)):
        assert isinstance(again, sticky.States)
        assert repr(again) == "States(4 times, 0 computed so far)"
        assert again.times == states.times
        assert again[3].exact_positions() == states[3].exact_positions()
