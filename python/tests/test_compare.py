"""sticky.compare: the library's comparison, from Python."""

from fractions import Fraction as F

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import sticky
from conftest import SCENES
from test_properties import scenes, times


def test_a_planted_error_of_one_thousandth():
    scene = sticky.Scene.load(SCENES / "three-cluster-simultaneous.toml")
    x = scene.state(3).exact_positions()
    x[7] += F(1, 1000)  # the last particle leaves the cluster of 8
    report = sticky.compare(scene, 3, x)
    assert report.position_max == F(1, 1000)
    assert report.position_max_index == 7
    assert report.position_max_float == 0.001
    assert report.verdict == "inexact"  # admissible, one contact lost
    assert report.missed_contacts == 1 and report.missed_clusters == [(0, 8)]
    assert report.frames[0].position_l2_squared == F(1, 1000) ** 2 / 8
    d = report.to_dict()
    assert d["verdict"] == "inexact"
    assert "1/1000" in report.text()
    assert repr(report) == (
        'CompareReport(verdict="inexact", frames=[CompareFrame(t=3, verdict="inexact", '
        "position_max=1/1000 at 7, overlaps=0, missed_contacts=1, spurious_contacts=0)])"
    )


def test_an_overlap_is_invalid_with_its_depth():
    scene = sticky.Scene.load(SCENES / "three-cluster-simultaneous.toml")
    x = scene.state("1/2").exact_positions()
    x[7] = x[6] + F(1, 2)  # 2r = 1: depth 1/2
    report = sticky.compare(scene, "1/2", x)
    assert report.verdict == "invalid"
    assert report.overlaps == [(6, F(1, 2), 0.5)]


def test_velocities_clusters_and_tolerances():
    scene = sticky.Scene([0, 2], [1, -1], "1/4")
    s = scene.state(1)
    ok = sticky.compare(scene, 1, s.positions, s.velocities, clusters=[(0, 2)])
    assert ok.verdict == "exact" and ok.velocity_max == (0, 0.0, 0)
    wrong = sticky.compare(scene, 1, s.positions, [0, F(1, 8)], clusters=[(0, 1), (1, 1)])
    assert wrong.velocity_max == (F(1, 8), 0.125, 1)
    assert wrong.missed_clusters == [(0, 2)] and wrong.missed_contacts == 1
    early = scene.state("1/2")  # before the collision at t = 3/4
    glued = sticky.compare(scene, "1/2", early.positions, clusters=[(0, 2)])
    assert glued.spurious_clusters == [(0, 2)] and glued.spurious_contacts == 1
    with pytest.raises(ValueError, match=r"^clusters\[1\] = \(3, 1\)"):
        sticky.compare(scene, 1, s.positions, clusters=[(0, 1), (3, 1)])


def test_wrong_length():
    scene = sticky.Scene([0, 2], [1, -1], "1/4")
    with pytest.raises(ValueError, match="2"):
        sticky.compare(scene, 1, [0.75])


@settings(max_examples=100, deadline=None)
@given(scenes(), times)
def test_the_exact_answer_is_exact(data, t):
    x0, u0, r = data
    scene = sticky.Scene(x0, u0, r)
    s = scene.state(t)
    report = sticky.compare(scene, t, s.exact_positions(), s.exact_velocities(), multipliers=s.exact_multipliers())
    assert report.verdict == "exact" and report.exact
    assert report.position_max == 0
