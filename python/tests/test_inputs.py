"""Every kind of input a Scene takes, and every bad input, one test each
with its message (the command line's, through the library)."""

import math
from fractions import Fraction as F

import numpy as np
import pytest

import sticky
from conftest import ROOT, SCENES

X = [0, F(1, 2), 1]
U = [1, 0, -1]
R = F(1, 10)
# The exact state of (X, U, R) at t = 1/2: the three meet and stick.
WANT = [F(3, 10), F(1, 2), F(7, 10)]


def positions_at_half(x, u, radius=R):
    return sticky.Scene(x, u, radius).state(F(1, 2)).exact_positions()


def test_numpy_float64_arrays():
    assert positions_at_half(np.array([0.0, 0.5, 1.0]), np.array([1.0, 0.0, -1.0]), 0.1) != WANT
    # 0.1 is not 1/10: the double is read exactly, as its binary value.
    s = sticky.Scene(np.array([0.0, 0.5, 1.0]), np.array([1.0, 0.0, -1.0]), 0.1)
    assert s.radius == F(0.1) != F(1, 10)
    assert positions_at_half(np.array([0.0, 0.5, 1.0]), np.array([1.0, 0.0, -1.0]), "1/10") == WANT


def test_a_double_is_its_exact_binary_value():
    s = sticky.Scene(np.array([0.1, 0.7]), np.array([0.0, 0.0]), "1/8")
    assert s.exact_positions() == [F(0.1), F(0.7)]
    assert s.state(0).exact_positions() == [F(0.1), F(0.7)]


def test_lists_of_float():
    assert positions_at_half([0.0, 0.5, 1.0], [1.0, 0.0, -1.0], "1/10") == WANT


def test_ints_fractions_and_strings():
    assert positions_at_half([0, "1/2", 1], ["1", 0, F(-1)], "0.1") == WANT
    assert positions_at_half(("0", "0.5", "1e0"), (1, 0, -1), F(1, 10)) == WANT


def test_numpy_integer_and_float32_arrays():
    x = np.array([0, 3, 6], dtype=np.int64)
    u = np.array([1.0, 0.0, -1.0], dtype=np.float32)
    s = sticky.Scene(x, u, np.int32(1))
    assert s.exact_positions() == [0, 3, 6] and s.exact_velocities() == [1, 0, -1]
    assert s.radius == 1


def test_default_radius_is_the_papers():
    s = sticky.Scene([0, 1, 2, 3], [0, 0, 0, 0])
    assert s.radius == F(1, 8)  # 2r = 1/N


def test_times_of_every_kind():
    s = sticky.Scene(X, U, R)
    for t in [0.5, F(1, 2), "1/2", "0.5", np.float64(0.5)]:
        assert s.state(t).exact_positions() == WANT
    assert s.state(2).exact_positions() == WANT


def test_load_toml_csv_npy_and_macro(tmp_path):
    toml = sticky.Scene.load(SCENES / "three-cluster-simultaneous.toml")
    x, u = toml.exact_positions(), toml.exact_velocities()
    (tmp_path / "p.csv").write_text("position,velocity\n" + "".join(f"{a},{b}\n" for a, b in zip(x, u)))
    (tmp_path / "c.toml").write_text('[particles]\nradius = "1/2"\ndata = "p.csv"\n')
    np.save(tmp_path / "p.npy", np.array([[float(a), float(b)] for a, b in zip(x, u)]))
    (tmp_path / "n.toml").write_text('[particles]\nradius = "1/2"\ndata = "p.npy"\n')
    for path in [tmp_path / "c.toml", str(tmp_path / "n.toml")]:
        s = sticky.Scene.load(path)
        assert s.state(3).exact_positions() == toml.state(3).exact_positions()
    macro = sticky.Scene.load(SCENES / "riemann-compression.toml")
    assert macro.kind == "macro" and macro.n == 64
    text = (SCENES / "riemann-compression.toml").read_text()
    assert sticky.Scene.from_toml(text).state(1).exact_positions() == macro.state(1).exact_positions()


# ---- bad input: one test each, with the message --------------------------


def test_overlap():
    with pytest.raises(ValueError, match=r"^positions\[1\] and positions\[2\] overlap: gap 1/10 < 2r = 1/5$"):
        sticky.Scene([0, 1, "11/10"], [0, 0, 0], R)


def test_overlap_of_doubles():
    with pytest.raises(ValueError, match=r"^positions\[0\] and positions\[1\] overlap: gap 1/8 < 2r = 1/4$"):
        sticky.Scene(np.array([0.0, 0.125]), np.array([0.0, 0.0]), 0.125)


def test_velocity_cone():
    with pytest.raises(ValueError, match=r"^particles 0 and 1 \(indices from 0\) are in contact and approach each other: velocities\[0\] = 1 > velocities\[1\] = 0 \(u⁰ outside the velocity cone\)$"):
        sticky.Scene([0, "1/5"], [1, 0], R)


def test_nan():
    with pytest.raises(ValueError, match=r"^positions\[1\] is NaN: every value must be a finite number$"):
        sticky.Scene(np.array([0.0, math.nan]), np.array([0.0, 0.0]))


def test_nan_in_a_list_of_mixed_numbers():
    with pytest.raises(ValueError, match=r"^velocities\[2\] is NaN: every value must be a finite number$"):
        sticky.Scene([0, 1, 2], [0, "1/2", float("nan")])


def test_infinity():
    with pytest.raises(ValueError, match=r"^positions\[0\] is -inf: every value must be a finite number$"):
        sticky.Scene([-math.inf, 1.0], [0.0, 0.0])


def test_length_mismatch():
    with pytest.raises(ValueError, match=r"^length mismatch: 3 positions but 2 velocities$"):
        sticky.Scene([0, 1, 2], [0, 0])


def test_no_particles():
    with pytest.raises(ValueError, match=r"^no particles: N must be at least 1$"):
        sticky.Scene([], [])


def test_non_positive_radius():
    with pytest.raises(ValueError, match=r"^radius must be positive, got 0$"):
        sticky.Scene([0, 1], [0, 0], 0)


def test_bad_string():
    with pytest.raises(ValueError, match=r'^positions\[1\]: "1/0" is refused: zero denominator$'):
        sticky.Scene([0, "1/0"], [0, 0])


def test_wrong_type():
    with pytest.raises(TypeError, match=r"^velocities\[0\]: expected a float, an int, a fractions.Fraction or an exact string such as \"1/3\", got NoneType$"):
        sticky.Scene([0], [None])


def test_negative_time():
    with pytest.raises(ValueError, match=r"^time -1 is negative$"):
        sticky.Scene([0], [0]).state(-1)


def test_missing_file():
    with pytest.raises(OSError, match=r"^cannot read the scene: .*nowhere.toml: No such file"):
        sticky.Scene.load(ROOT / "nowhere.toml")


def test_toml_float_in_a_scene():
    with pytest.raises(ValueError, match=r"field `particles.radius` is the TOML float 0.5, which would be rounded"):
        sticky.Scene.from_toml("[particles]\nradius = 0.5\npositions = [\"0\"]\nvelocities = [\"0\"]\n")


def test_project_length():
    with pytest.raises(ValueError, match=r"^z has 2 values but the scene has N = 3 particles$"):
        sticky.Scene(X, U, R).project([0, 1])
