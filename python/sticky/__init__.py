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

from . import _notebook, _values
from ._sticky import (
    CompareFrame,
    CompareReport,
    Event,
    Scene,
    State,
    __version__,
    claims,
    compare,
    export,
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

Scene.__eq__ = _values.scene_eq
Scene.__hash__ = _values.scene_hash
Scene.__reduce__ = _values.scene_reduce
Scene._repr_html_ = _notebook.scene_html
Scene.plot = _notebook.plot
State.__reduce__ = _values.state_reduce
State._repr_html_ = _notebook.state_html
CompareReport.__dir__ = _values.report_dir
CompareReport._repr_html_ = _notebook.report_html


def _exact_text(value, what):
    """The exact text of a number for a TOML scene: an int, a Fraction, a
    float (its exact binary value) or an exact string ("1/3", "0.25")."""
    import json
    import numbers
    from fractions import Fraction

    if isinstance(value, str):
        text = value
    elif isinstance(value, bool):
        raise TypeError(f"{what}: a number is needed, not a bool")
    elif isinstance(value, numbers.Integral):
        text = str(int(value))
    elif isinstance(value, (Fraction, numbers.Rational)):
        q = Fraction(value)
        text = f"{q.numerator}/{q.denominator}"
    elif isinstance(value, numbers.Real):
        q = Fraction(float(value))  # ValueError for NaN and infinities
        text = f"{q.numerator}/{q.denominator}"
    else:
        raise TypeError(f"{what}: {value!r} is not a number")
    return json.dumps(text)


def _from_macro(particles, blocks, *, name=None, t_end=None):
    """Scene.from_macro(particles, blocks, *, name=None, t_end=None) -> Scene

    A [macro] scene (docs/guide/scenes.md): a piecewise constant density rho0
    of blocks, sampled with N = `particles` at the quantiles (x0_i = X0(i/N),
    u0_i = U0(i/N), 2r = 1/N: the paper's thm:main). `blocks` lists, left to
    right, (from, to, density, velocity) tuples or dicts with those keys; the
    block is [from, to), density in (0, 1], the masses add up to exactly 1;
    velocity is a number, or a pair (a, b) for u0 affine from a at `from` to b
    at `to` (only where density < 1). Numbers are ints, Fractions, floats
    (their exact binary value) or exact strings. The same validation and
    messages as the [macro] section of a TOML file (ValueError).

        >>> s = sticky.Scene.from_macro(4, [(0, 1, 1, 0)])
        >>> s.exact_positions()
        [Fraction(1, 4), Fraction(1, 2), Fraction(3, 4), Fraction(1, 1)]
    """
    import numbers

    if isinstance(particles, bool) or not isinstance(particles, numbers.Integral):
        raise TypeError(f"particles: an integer is needed, got {particles!r}")
    lines = []
    if name is not None:
        lines.append(f"name = {_exact_text(str(name), 'name')}")
    if t_end is not None:
        lines.append(f"t_end = {_exact_text(t_end, 't_end')}")
    lines += ["[macro]", f"particles = {int(particles)}", "blocks = ["]
    for k, block in enumerate(blocks):
        where = f"blocks[{k}]"
        if isinstance(block, dict):
            unknown = set(block) - {"from", "to", "density", "velocity"}
            if unknown:
                raise ValueError(f"{where}: unknown keys {sorted(unknown)}")
            try:
                lo, hi, rho, u = (block[key] for key in ("from", "to", "density", "velocity"))
            except KeyError as missing:
                raise ValueError(f"{where}: missing key {missing}") from None
        else:
            try:
                lo, hi, rho, u = block
            except (TypeError, ValueError):
                raise ValueError(
                    f"{where}: a (from, to, density, velocity) tuple or a dict is needed"
                ) from None
        if isinstance(u, (tuple, list)):
            if len(u) != 2:
                raise ValueError(f"{where}.velocity: a number or a pair (a, b)")
            velocity = f"[{_exact_text(u[0], where)}, {_exact_text(u[1], where)}]"
        else:
            velocity = _exact_text(u, f"{where}.velocity")
        lines.append(
            f"  {{ from = {_exact_text(lo, where + '.from')}, to = {_exact_text(hi, where + '.to')}, "
            f"density = {_exact_text(rho, where + '.density')}, velocity = {velocity} }},"
        )
    lines.append("]")
    return Scene.from_toml("\n".join(lines) + "\n")


Scene.from_macro = staticmethod(_from_macro)

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
    "State",
    "claims",
    "compare",
    "export",
    "isotonic",
]
