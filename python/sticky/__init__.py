"""sticky: exact sticky-particle dynamics on a line, from Python.

N particles of radius r on a line stick together when they collide (C.
Perrin, "Microscopic derivation of the one-dimensional constrained Euler
equations"). Every answer is exact: inputs are read exactly (a float as the
binary value of the double), the state x(t) = P_K(x0 + t u0) is computed on
exact rationals, and returned both as numpy float64 arrays of the nearest
doubles and, on demand, as lists of fractions.Fraction.

    >>> import sticky
    >>> scene = sticky.Scene([0, 2], [1, -1], radius="1/4")
    >>> scene.state("1").exact_positions()
    [Fraction(3, 4), Fraction(5, 4)]

Particles are indexed from 0 everywhere (clusters, events, messages).
"""

from typing import Literal

from . import _notebook, _values
from ._sticky import (
    CompareFrame,
    CompareReport,
    Event,
    Scene,
    State,
    States,
    __version__,
    claims,
    compare,
    export,
    from_macro,
    isotonic,
)
from .errors import (
    ArgumentError,
    ArgumentTypeError,
    CompareError,
    InvalidDataError,
    LengthMismatchError,
    MacroError,
    NegativeTimeError,
    NotSortedError,
    OverlapError,
    SceneFormatError,
    SceneReadError,
    StickyError,
    UnsupportedError,
    VelocityConeError,
    WorkLimitError,
)

# The verdict of a comparison, best first (CompareReport.verdict).
Verdict = Literal["exact", "rounding", "inexact", "invalid"]
# Where a scene's initial data came from (Scene.kind).
SceneKindName = Literal["particles", "macro"]

Scene.__eq__ = _values.scene_eq
Scene.__hash__ = _values.scene_hash
Scene.__reduce__ = _values.scene_reduce
Scene._repr_html_ = _notebook.scene_html
Scene.plot = _notebook.plot
State.__reduce__ = _values.state_reduce
State._repr_html_ = _notebook.state_html
CompareReport.__dir__ = _values.report_dir
CompareReport._repr_html_ = _notebook.report_html


Scene.from_macro = staticmethod(from_macro)

__all__ = [
    "ArgumentError",
    "ArgumentTypeError",
    "CompareError",
    "InvalidDataError",
    "LengthMismatchError",
    "MacroError",
    "NegativeTimeError",
    "NotSortedError",
    "OverlapError",
    "SceneFormatError",
    "SceneReadError",
    "StickyError",
    "UnsupportedError",
    "VelocityConeError",
    "WorkLimitError",
    "__version__",
    "CompareFrame",
    "CompareReport",
    "Event",
    "Scene",
    "SceneKindName",
    "State",
    "States",
    "Verdict",
    "claims",
    "compare",
    "export",
    "from_macro",
    "isotonic",
]
