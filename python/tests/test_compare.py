"""sticky.compare: the library's comparison, from Python."""

import json
import random
import subprocess
from fractions import Fraction as F

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import sticky
from conftest import SCENES, random_scene, scene_toml
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


def test_to_dict_is_the_cli_json(sticky_bin, tmp_path):
    """`report.to_dict()` builds its long lists (overlaps, λ < 0,
    complementarity, wrong clusters, Oleinik) as Python objects and the
    rest through JSON text: the whole equals `sticky compare --json`."""
    rng = random.Random(38)
    seen = {"overlaps": 0, "negative_multipliers": 0, "complementarity": 0,
            "missed_clusters": 0, "spurious_clusters": 0, "oleinik": 0}
    for k in range(40):
        x, u, r = random_scene(rng)
        if len(x) < 3:
            continue
        scene = sticky.Scene(x, u, r)
        t = F(rng.randint(1, 8), rng.randint(1, 3))
        s = scene.state(t)
        xs = [v + F(rng.randint(-3, 3), 7) * r for v in s.exact_positions()]
        us = [v + F(rng.randint(-2, 2), 5) for v in s.exact_velocities()]
        ls = [v + F(rng.randint(-2, 1), 3) for v in s.exact_multipliers()]
        scene_file, answer = tmp_path / f"c{k}.toml", tmp_path / f"c{k}.json"
        scene_file.write_text(scene_toml(x, u, r))
        text = lambda vs: [str(v) for v in vs]
        answer.write_text(json.dumps(
            {"t": str(t), "positions": text(xs), "velocities": text(us), "multipliers": text(ls)}
        ))
        out = subprocess.run(
            [sticky_bin, "compare", str(scene_file), str(answer), "--json"],
            capture_output=True, text=True,
        ).stdout
        cli = json.loads(out)
        d = sticky.compare(scene, t, xs, us, multipliers=ls).to_dict()
        # Only the CLI names its files and the answer's line.
        assert (d["scene"], d["solution"]) == (None, None)
        cli["scene"] = cli["solution"] = None
        cli["times"][0]["line"] = 0
        assert d == cli
        for key in seen:
            seen[key] += bool(d["times"][0][key])
    assert all(seen.values()), seen
