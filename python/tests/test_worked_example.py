"""README's worked example, reproduced from Python."""

from fractions import Fraction as F

import numpy as np

import sticky
from conftest import SCENES

SCENE = SCENES / "three-cluster-simultaneous.toml"


def fr(texts):
    return [F(t) for t in texts]


def test_state_at_one_half_and_three():
    scene = sticky.Scene.load(SCENE)
    assert scene.n == 8 and scene.radius == F(1, 2)
    s = scene.state("1/2")
    assert s.t == F(1, 2)
    assert s.exact_positions() == fr(["3/2", "5/2", "7/2", "9/2", "11/2", "13/2", "15/2", "23/2"])
    assert s.exact_velocities() == fr(["1"] * 7 + ["-1"])
    assert s.exact_multipliers() == fr(["1/4", "1/2", "3/4", "5/8", "1/2", "1/4", "0"])
    assert s.clusters == [(0, 7), (7, 1)]
    np.testing.assert_array_equal(s.positions, [1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5, 11.5])
    s = scene.state(3)
    assert s.exact_positions() == [F(15 + 4 * i, 4) for i in range(8)]
    assert s.exact_velocities() == [F(3, 4)] * 8
    assert s.exact_multipliers() == fr(["9/32", "9/16", "27/32", "3/4", "21/32", "7/16", "7/32"])
    assert s.clusters == [(0, 8)]
    assert s.velocities.dtype == np.float64 and list(s.velocities) == [0.75] * 8


def test_events():
    events = sticky.Scene.load(SCENE).events()
    got = [(e.t, e.first, e.size, e.parts) for e in events]
    assert got == [(F(1, 2), 0, 7, [3, 2, 2]), (F(2), 0, 8, [7, 1])]
    assert events[0].to_dict() == {"t": "1/2", "first": 0, "size": 7, "parts": [3, 2, 2]}


def test_to_dict_is_run_json():
    s = sticky.Scene.load(SCENE).state("1/2")
    assert s.to_dict() == {
        "n": 8,
        "radius": "1/2",
        "t": "1/2",
        "positions": ["3/2", "5/2", "7/2", "9/2", "11/2", "13/2", "15/2", "23/2"],
        "velocities": ["1", "1", "1", "1", "1", "1", "1", "-1"],
        "multipliers": ["1/4", "1/2", "3/4", "5/8", "1/2", "1/4", "0"],
        "clusters": [[0, 7], [7, 1]],
    }


def test_states_many_times():
    scene = sticky.Scene.load(SCENE)
    states = scene.states(["1/2", 3])
    assert [s.t for s in states] == [F(1, 2), F(3)]
    assert states[1].clusters == [(0, 8)]


def test_export_and_claims():
    e = sticky.export(sticky.Scene(["0", "1/3"], [1, -1], "1/8"))
    assert e["positions"]["exact"] == ["0", "1/3"]
    assert e["positions"]["f64"] == [0.0, 1 / 3]
    assert F(e["positions"]["error"][1]) == F(1, 3) - F(1 / 3)  # exact minus double


def test_reprs():
    scene = sticky.Scene.load(SCENE)
    assert repr(scene) == "Scene(n=8, radius=1/2)"
    assert repr(scene.state("1/2")) == "State(t=1/2, n=8, clusters=[(0, 7), (7, 1)])"
    assert repr(scene.events()[1]) == "Event(t=2, first=0, size=8, parts=[7, 1])"
