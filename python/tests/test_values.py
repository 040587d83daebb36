"""The package's values behave: exceptions typed and carrying their facts,
read-only arrays, pickling, equality, reprs with decimals, dir() of a
report, notebook views, and compare's verdict on a correctly rounded
answer."""

import copy
import inspect
import pickle
from fractions import Fraction

import numpy as np
import pytest

import sticky

from conftest import SCENES


def test_overlap_is_an_overlap_error_and_a_value_error():
    with pytest.raises(sticky.OverlapError) as e:
        sticky.Scene([0, 0.3, 1], [0, 0, 0], radius="1/6")
    assert isinstance(e.value, ValueError) and isinstance(e.value, sticky.StickyError)
    assert (e.value.i, e.value.two_r) == (0, Fraction(1, 3))
    assert e.value.gap == Fraction(0.3)
    # The 54-bit gap comes with its decimal.
    assert "(≈ 0.3)" in str(e.value)


def test_unsorted_positions_say_so():
    with pytest.raises(sticky.NotSortedError, match="not sorted") as e:
        sticky.Scene([0, 2, 1], [0, 0, 0])
    assert e.value.i == 1 and e.value.gap == -1
    assert isinstance(e.value, sticky.OverlapError)


def test_velocity_cone_and_lengths_and_time():
    with pytest.raises(sticky.VelocityConeError) as e:
        sticky.Scene([0, "1/2"], [1, 0], radius="1/4")
    assert (e.value.i, e.value.left, e.value.right) == (0, 1, 0)
    with pytest.raises(sticky.LengthMismatchError) as e:
        sticky.Scene([0, 1, 2], [0, 0])
    assert (e.value.positions, e.value.velocities) == (3, 2)
    with pytest.raises(sticky.NegativeTimeError) as e:
        sticky.Scene([0, 1], [0, 0]).state("-1/3")
    assert e.value.t == Fraction(-1, 3)


def test_files_and_formats():
    with pytest.raises(sticky.SceneReadError) as e:
        sticky.Scene.load("nowhere.toml")
    assert isinstance(e.value, OSError)
    with pytest.raises(sticky.SceneFormatError) as e:
        sticky.Scene.from_toml('[particles]\nradius = "1/4"\npositions = ["0"]\n')
    assert e.value.field == "particles.velocities"
    with pytest.raises(sticky.MacroError) as e:
        sticky.Scene.from_macro(4, [(0, 1, "3/2", 0)])
    assert e.value.block == 0


def test_work_limit(monkeypatch):
    # Word-sized data take the streaming merge, which needs no work check;
    # a denominator beyond 64 bits sends the scene to the general engines,
    # whose work check the cap of 1 refuses.
    monkeypatch.setenv("STICKY_MAX_WORK", "1")
    big = 2**70 + 1
    scene = sticky.Scene([0, Fraction(big + 1, big), 2], [Fraction(1, 3), 0, -1], "1/4")
    with pytest.raises(sticky.WorkLimitError) as e:
        scene.events()
    assert e.value.cap == 1 and e.value.work > 1


def test_bools_are_refused_everywhere():
    with pytest.raises(sticky.ArgumentTypeError) as e:
        sticky.Scene([0, 1], [True, 0])
    assert e.value.argument == "velocities[0]" and isinstance(e.value, TypeError)
    with pytest.raises(TypeError, match="velocities"):
        sticky.Scene([0, 1], np.array([True, False]))
    with pytest.raises(TypeError, match="radius"):
        sticky.Scene([0, 1], [0, 0], radius=True)
    with pytest.raises(TypeError, match="clusters"):
        sticky.compare(sticky.Scene([0, 1], [0, 0]), 1, [0, 1], clusters=[(0, True), (1, 1)])
    with pytest.raises(TypeError, match="blocks"):
        sticky.Scene.from_macro(4, [(0, 1, True, 0)])
    with pytest.raises(TypeError, match="particles"):
        sticky.Scene.from_macro(True, [(0, 1, 1, 0)])


def test_conversion_errors_name_their_argument():
    scene = sticky.Scene([0, 1], [0, 0], "1/4")
    with pytest.raises(sticky.ArgumentError, match=r"clusters\[1\]") as e:
        sticky.compare(scene, 1, [0, 1], clusters=[(0, 1), (1, 2**64)])
    assert isinstance(e.value, ValueError)
    with pytest.raises(sticky.ArgumentError, match="cases"):
        sticky.claims(cases=-1)
    with pytest.raises(sticky.ArgumentError, match=r"positions\[1\]"):
        sticky.Scene([0, float("nan")], [0, 0])


def test_state_arrays_are_read_only():
    scene = sticky.Scene(np.array([0.0, 0.3, 1.0]), np.array([1.0, 0.0, -1.0]), radius="1/10")
    s = scene.state(0.7)
    before = s.positions.copy()
    for name in ("positions", "velocities", "multipliers"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(s, name)[0] += 1
    with pytest.raises(ValueError):
        p = s.positions
        p += 1
    assert np.array_equal(s.positions, before)
    assert np.array_equal(scene.state(0.7).positions, before)
    # A scene's arrays are copies.
    x = scene.positions
    x += 1
    assert scene.positions[0] == 0.0


def test_correctly_rounded_answer_is_rounding():
    scene = sticky.Scene([0, "1/3", "2/3"], [0, 0, 0], radius="1/6")
    s = scene.state(1)
    report = sticky.compare(scene, 1, s.positions, s.velocities, multipliers=s.multipliers)
    assert report.verdict == "rounding"
    assert len(report.overlaps) == 2  # the rounding's overlaps, forgiven
    # One ulp below the nearest double: invalid, as before.
    x = s.positions.copy()
    x[1] = np.nextafter(x[1], 0)
    assert sticky.compare(scene, 1, x).verdict == "invalid"


def test_pickle_and_deepcopy():
    scene = sticky.Scene.load(SCENES / "three-cluster-simultaneous.toml")
    s = scene.state("1/2")
    report = sticky.compare(scene, "1/2", s.positions, clusters=s.clusters, contact_tol="1/10")
    for obj in (scene, s, report):
        for again in (pickle.loads(pickle.dumps(obj)), copy.deepcopy(obj)):
            assert type(again) is type(obj)
    assert pickle.loads(pickle.dumps(scene)) == scene
    assert copy.deepcopy(s).exact_positions() == s.exact_positions()
    again = pickle.loads(pickle.dumps(report))
    assert again.to_dict() == report.to_dict()


def test_scene_equality_is_by_value():
    a = sticky.Scene([0, 1], [0, 0], "1/4")
    assert a == sticky.Scene(["0", "1"], [0.0, 0], Fraction(1, 4))
    assert a != sticky.Scene([0, 1], [0, 0], "1/8")
    assert a != sticky.Scene([0, 2], [0, 0], "1/4")
    assert hash(a) == hash(sticky.Scene([0, 1], [0, 0], "1/4"))


def test_friendly_values():
    assert sticky.__version__.count(".") == 2
    s = sticky.Scene([0, 1], [0, 0]).state(0.3)
    assert "(≈ 0.3)" in repr(s)
    # Messages too: a long fraction has its decimal beside it.
    with pytest.raises(sticky.NegativeTimeError) as caught:
        sticky.Scene([0, 1], [0, 0]).state(-0.1)
    assert str(caught.value) == "time -3602879701896397/36028797018963968 (≈ -0.1) is negative"
    assert caught.value.t == Fraction(-0.1)
    assert "contact_tol=0" in str(inspect.signature(sticky.compare))
    report = sticky.compare(sticky.Scene([0, 1], [0, 0]), 1, [0, 1])
    assert {"position_max", "overlaps", "oleinik", "verdict"} <= set(dir(report))


def test_notebook_views():
    scene = sticky.Scene([0, 1, 2], [1, 0, -1])
    assert "<table" in scene._repr_html_() and "radius" in scene._repr_html_()
    assert "clusters" in scene.state(1)._repr_html_()
    html = sticky.compare(scene, 1, [0, 1, 2])._repr_html_()
    assert "color:#cf222e" in html or "color:#bf8700" in html


def test_plot_draws_one_worldline_per_particle():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    scene = sticky.Scene([0, 1, 2, 5], [1, 0, -1, 0])
    fig = scene.plot(3)
    (lines,) = fig.axes[0].collections
    segments = lines.get_segments()
    assert len(segments) == 4
    # 2r = 1/4: particles 0, 1, 2 meet at t = 3/4 and stop (momentum 0);
    # each worldline goes through 0, the collision instant and t_end.
    assert [t for _, t in segments[0]] == [0, 0.75, 3]
    assert [x for x, _ in segments[0]] == [0, 0.75, 0.75]
    colours = lines.get_colors()
    assert (colours[0] == colours[2]).all() and not (colours[0] == colours[3]).all()
