"""The exceptions sticky raises, one class per kind of mistake.

Every one is a ``StickyError``; each is also the built-in exception the
same mistake raised before this hierarchy existed (``ValueError`` for bad
data, ``OSError`` for a file that cannot be read, ``TypeError`` for an
argument of the wrong kind), so ``except ValueError`` keeps working. The
structured facts ride along as attributes: indices from 0, exact values as
``fractions.Fraction``::

    >>> import sticky
    >>> try:
    ...     sticky.Scene([0, "1/10"], [0, 0], radius="1/10")
    ... except sticky.OverlapError as e:
    ...     (e.i, e.gap, e.two_r)
    (0, Fraction(1, 10), Fraction(1, 5))

The native module raises them (``sticky/_sticky``: ``python/src/errors.rs``
maps the library's ``sticky::Error`` onto them).
"""

from fractions import Fraction
from typing import Optional


class StickyError(Exception):
    """Base of every exception sticky raises about its input."""


class SceneReadError(StickyError, OSError):
    """A scene file (or the column file it names) cannot be read."""


class SceneFormatError(StickyError, ValueError):
    """A scene's text is not a valid scene: bad TOML, a missing, unknown or
    mistyped field, a TOML float, a number that is not exact, a bad column
    file. ``field``: the dotted path of the field (None when not known)."""

    field: Optional[str] = None


class InvalidDataError(StickyError, ValueError):
    """Initial data or a request outside the model: the base of the data
    errors below, raised itself for an empty scene or a non-positive
    radius."""


class ArgumentError(InvalidDataError):
    """A number that is not a finite exact value (NaN, an infinity, "1/0",
    a bad string), or a count out of range. ``argument``: where it was, e.g.
    ``positions[3]`` or ``clusters[1]``."""

    argument: Optional[str] = None


class ArgumentTypeError(StickyError, TypeError):
    """An argument of the wrong kind (a bool, None, a string where a sequence
    of numbers is needed). ``argument``: its name, e.g. ``velocities[0]``."""

    argument: Optional[str] = None


class LengthMismatchError(InvalidDataError):
    """Columns of different lengths: ``positions`` and ``velocities`` give
    the two lengths."""

    positions: int
    velocities: int


class OverlapError(InvalidDataError):
    """Two consecutive particles overlap, ``x[i+1] - x[i] < 2r`` (``df:KN``):
    ``i`` the left one, ``gap`` and ``two_r`` exact."""

    i: int
    gap: Fraction
    two_r: Fraction


class NotSortedError(OverlapError):
    """Positions not in increasing order (``x[i+1] < x[i]``): an overlap of
    the worst kind, with the same attributes."""


class VelocityConeError(InvalidDataError):
    """Two particles in contact approach each other: ``u0`` is outside the
    velocity cone (``def:velcone``). ``i`` the left one, ``left`` and
    ``right`` their velocities, exact."""

    i: int
    left: Fraction
    right: Fraction


class MacroError(InvalidDataError):
    """A ``[macro]`` datum that is not one: a density outside (0, 1], a
    total mass other than 1, blocks empty, unsorted or overlapping.
    ``block``: its index (None for the total mass)."""

    block: Optional[int] = None


class NegativeTimeError(InvalidDataError):
    """A requested time is negative: ``t``, exact."""

    t: Fraction


class WorkLimitError(StickyError, ValueError):
    """The exact answer would need more machine work than the cap
    (``STICKY_MAX_WORK`` raises it): ``work`` and ``cap`` in word
    operations."""

    work: int
    cap: int


class UnsupportedError(StickyError, ValueError):
    """A request the engines cannot serve."""


class CompareError(StickyError, ValueError):
    """A solver's answer that cannot be compared: a wrong length, clusters
    that do not tile the particles, a negative tolerance."""


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
]
