"""sticky.Scene.from_macro: a [macro] scene built from Python is the scene of
the same [macro] section in TOML (docs/guide/scenes.md), and its errors are
the TOML section's."""

import re
from fractions import Fraction

import pytest

import sticky
from conftest import ROOT

TWO_BLOCKS = ROOT / "docs" / "guide" / "examples" / "two-blocks.toml"


def same_scene(a, b):
    assert a.n == b.n
    assert a.radius == b.radius
    assert a.exact_positions() == b.exact_positions()
    assert a.exact_velocities() == b.exact_velocities()


def test_the_guide_example_from_python():
    """The guide's two-blocks.toml, as tuples, as dicts, and with Fractions
    and floats (exact binary values) in place of strings."""
    from_file = sticky.Scene.load(TWO_BLOCKS)
    tuples = sticky.Scene.from_macro(
        8, [("0", "1", "1/2", ("0", "1")), ("2", "5/2", "1", "-1")]
    )
    same_scene(tuples, from_file)
    dicts = sticky.Scene.from_macro(
        8,
        [
            {"from": 0, "to": 1, "density": Fraction(1, 2), "velocity": [0, 1]},
            {"from": 2, "to": 2.5, "density": 1, "velocity": -1.0},
        ],
        name="two-blocks",
        t_end=1,
    )
    same_scene(dicts, from_file)
    assert [e.to_dict() for e in dicts.events()] == [e.to_dict() for e in from_file.events()]


def test_one_congested_block():
    """rho0 = 1 on [0, 1), u0 = 0, N = 4: 2r = 1/N and the quantile
    positions are 1/N apart."""
    s = sticky.Scene.from_macro(4, [(0, 1, 1, 0)])
    assert s.n == 4
    assert s.radius == Fraction(1, 8)
    x = s.exact_positions()
    assert x == [Fraction(i, 4) for i in range(1, 5)]  # X0(i/N), i = 1 … N
    assert s.exact_velocities() == [0] * 4


@pytest.mark.parametrize(
    "blocks, message",
    [
        ([(0, 1, "1/2", 0)], "total mass 1/2, not 1"),
        ([(0, 1, 2, 0)], "macro.blocks[0]: density 2 is not in (0, 1]"),
        ([(0, 1, 1, (0, 1))], "macro.blocks[0]: an affine velocity is not allowed"),
    ],
)
def test_errors_are_the_toml_sections(blocks, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        sticky.Scene.from_macro(4, blocks)


def test_bad_arguments():
    with pytest.raises(TypeError):
        sticky.Scene.from_macro(4.0, [(0, 1, 1, 0)])
    with pytest.raises(ValueError, match="blocks\\[0\\]"):
        sticky.Scene.from_macro(4, [(0, 1, 1)])
    with pytest.raises(ValueError, match="unknown keys"):
        sticky.Scene.from_macro(4, [{"from": 0, "to": 1, "density": 1, "velocity": 0, "rho": 1}])
    with pytest.raises(ValueError):
        sticky.Scene.from_macro(4, [(0, 1, float("nan"), 0)])
