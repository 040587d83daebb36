"""Type stubs of the sticky package (the native module sticky._sticky)."""

from fractions import Fraction
from os import PathLike
from typing import Any, Iterable, Iterator, List, Literal, Mapping, Optional, Sequence, Tuple, Union, final, overload


import numpy as np
import numpy.typing as npt

from . import errors as errors
from .errors import (
    ArgumentError as ArgumentError,
    ArgumentTypeError as ArgumentTypeError,
    CompareError as CompareError,
    InvalidDataError as InvalidDataError,
    LengthMismatchError as LengthMismatchError,
    MacroError as MacroError,
    NegativeTimeError as NegativeTimeError,
    NotSortedError as NotSortedError,
    OverlapError as OverlapError,
    SceneFormatError as SceneFormatError,
    SceneReadError as SceneReadError,
    StickyError as StickyError,
    UnsupportedError as UnsupportedError,
    VelocityConeError as VelocityConeError,
    WorkLimitError as WorkLimitError,
)

__version__: str

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

# The verdict of a comparison, best first.
Verdict = Literal["exact", "rounding", "inexact", "invalid"]
# Where a scene's initial data came from.
SceneKindName = Literal["particles", "macro"]

# A number read exactly: a float (its binary value), an int, a Fraction, or
# an exact string such as "1/3", "0.125", "1e-3".
# Bools are refused.
_Number = Union[float, int, Fraction, str, np.floating, np.integer]
_Numbers = Union[npt.ArrayLike, Sequence[_Number], Iterable[_Number]]
_FloatArray = npt.NDArray[np.float64]

@final
class State:
    """The state at one time t (indices from 0); its arrays are read-only."""

    @property
    def scene(self) -> Scene:
        """The scene this is a state of."""
    @property
    def t(self) -> Fraction:
        """The time, exact."""
    @property
    def n(self) -> int:
        """The number of particles N."""
    @property
    def positions(self) -> _FloatArray:
        """x(t), the nearest double of each exact value."""
    @property
    def velocities(self) -> _FloatArray:
        """u(t) (right derivative), nearest doubles."""
    @property
    def multipliers(self) -> _FloatArray:
        """λ(t), N - 1 values (entry i: the pair (i, i+1)), nearest doubles."""
    @property
    def clusters(self) -> List[Tuple[int, int]]:
        """Contact clusters as (first, size), left to right."""
    def exact_positions(self) -> List[Fraction]:
        """x(t), exact."""
    def exact_velocities(self) -> List[Fraction]:
        """u(t), exact."""
    def exact_multipliers(self) -> List[Fraction]:
        """λ(t), exact."""
    def to_dict(self) -> dict[str, Any]:
        """The state as `sticky run --json` prints it (exact strings)."""
    def _repr_html_(self) -> str: ...

@final
class States:
    """The states of a scene at several times, each computed on first read."""

    def __len__(self) -> int: ...
    @overload
    def __getitem__(self, index: int, /) -> State: ...
    @overload
    def __getitem__(self, index: slice, /) -> List[State]: ...
    def __iter__(self) -> Iterator[State]: ...
    @property
    def times(self) -> List[Fraction]:
        """The times, exact, in order."""
    @property
    def scene(self) -> Scene:
        """The scene these are states of."""

@final
class Event:
    """A cluster formed by a collision."""

    @property
    def t(self) -> Fraction:
        """The collision time, exact."""
    @property
    def t_float(self) -> float:
        """The collision time, nearest double."""
    @property
    def first(self) -> int:
        """The first particle of the cluster formed (from 0)."""
    @property
    def size(self) -> int:
        """The size of the cluster formed."""
    @property
    def parts(self) -> List[int]:
        """The sizes of the clusters that merged, left to right."""
    def to_dict(self) -> dict[str, Any]:
        """The event as `sticky events --json` prints it."""

@final
class Scene:
    """N particles of radius r on a line, validated; exact answers on demand."""

    def __new__(cls, positions: _Numbers, velocities: _Numbers, radius: Optional[_Number] = None) -> Scene:
        """Raises OverlapError, NotSortedError, VelocityConeError, ArgumentError
        (NaN, infinity), LengthMismatchError (all ValueError), ArgumentTypeError
        (a bool, a string: TypeError)."""
    @staticmethod
    def load(path: Union[str, PathLike[str]]) -> Scene:
        """A TOML scene file ([particles] inline, CSV or NPY columns, or [macro])."""
    @staticmethod
    def from_toml(text: str) -> Scene:
        """A scene from the text of a TOML scene file."""
    @staticmethod
    def from_macro(
        particles: int,
        blocks: Sequence[Union[Tuple[Any, Any, Any, Any], Mapping[str, Any]]],
        *,
        name: Optional[str] = None,
        t_end: Optional[_Number] = None,
    ) -> Scene:
        """A [macro] scene: blocks (from, to, density, velocity) of a piecewise
        constant density, velocity a number or a pair (a, b) (affine), sampled
        with N = particles at the quantiles (thm:main); the same validation as
        a TOML [macro] section."""
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def _repr_html_(self) -> str: ...
    def plot(self, t_end: _Number, ax: Any = None) -> Any:
        """The worldlines x_i(t), 0 ≤ t ≤ t_end, coloured by cluster at t_end:
        a matplotlib Figure (matplotlib is an optional extra)."""
    @property
    def n(self) -> int:
        """The number of particles N."""
    def __len__(self) -> int: ...
    @property
    def radius(self) -> Fraction:
        """The radius r, exact."""
    @property
    def name(self) -> Optional[str]:
        """The scene's name field."""
    @property
    def kind(self) -> SceneKindName:
        """"particles" or "macro"."""
    @property
    def positions(self) -> _FloatArray:
        """x⁰, nearest doubles."""
    @property
    def velocities(self) -> _FloatArray:
        """u⁰, nearest doubles."""
    def exact_positions(self) -> List[Fraction]:
        """x⁰, exact."""
    def exact_velocities(self) -> List[Fraction]:
        """u⁰, exact."""
    def state(self, t: _Number) -> State:
        """The exact state at t ≥ 0."""
    def states(self, ts: _Numbers) -> States:
        """The exact state at every t of ts: a sequence computed lazily (each
        state on first read, then kept); the times are checked now."""
    def explain(self) -> str:
        """The engine the library chooses for this scene and why: the line `sticky run --explain` prints."""
        ...
    def events(self) -> List[Event]:
        """Every cluster formed by a collision, by time then first particle."""
    def project(self, z: _Numbers, exact: bool = False) -> Union[_FloatArray, List[Fraction]]:
        """P_K(z), the exact projection onto K = {x : x[i+1] - x[i] ≥ 2r}."""

def from_macro(
    particles: int,
    blocks: Sequence[Union[Tuple[Any, Any, Any, Any], Mapping[str, Any]]],
    *,
    name: Optional[str] = None,
    t_end: Optional[_Number] = None,
) -> Scene:
    """Scene.from_macro."""

def isotonic(z: _Numbers, exact: bool = False) -> Union[_FloatArray, List[Fraction]]:
    """Exact isotonic regression (non-decreasing, equal weights)."""

def claims(
    cases: Optional[int] = None,
    max_n: Optional[int] = None,
    scaling_max_n: Optional[int] = None,
    seed: Optional[int] = None,
) -> List[dict[str, Any]]:
    """The ledger of the paper's claims, checked now."""

def export(scene: Scene) -> dict[str, Any]:
    """The scene's data rounded to doubles, as `sticky export --format json`."""

_MaxError = Tuple[Fraction, Optional[float], int]

@final
class CompareFrame:
    """One time of a comparison: every figure exact and as a float (indices from 0)."""

    @property
    def t(self) -> Fraction: ...
    @property
    def verdict(self) -> Verdict:
        """"exact", "rounding", "inexact" or "invalid"."""
    @property
    def exact(self) -> bool: ...
    @property
    def position_max(self) -> Fraction: ...
    @property
    def position_max_float(self) -> Optional[float]: ...
    @property
    def position_max_index(self) -> int: ...
    @property
    def position_l2_squared(self) -> Fraction: ...
    @property
    def position_l2_float(self) -> Optional[float]: ...
    @property
    def velocity_max(self) -> Optional[_MaxError]: ...
    @property
    def velocity_l2_squared(self) -> Optional[Fraction]: ...
    @property
    def velocity_l2_float(self) -> Optional[float]: ...
    @property
    def multiplier_max(self) -> Optional[_MaxError]: ...
    @property
    def overlaps(self) -> List[Tuple[int, Fraction, Optional[float]]]:
        """[(pair j, depth 2r - gap, depth as float)]."""
    @property
    def missed_contacts(self) -> int: ...
    @property
    def spurious_contacts(self) -> int: ...
    @property
    def missed_clusters(self) -> List[Tuple[int, int]]: ...
    @property
    def spurious_clusters(self) -> List[Tuple[int, int]]: ...
    @property
    def negative_multipliers(self) -> List[Tuple[int, Fraction]]: ...
    @property
    def complementarity(self) -> List[Tuple[int, Fraction]]: ...
    @property
    def oleinik(self) -> Optional[List[int]]: ...

@final
class CompareReport:
    """The verdict and the figures; with one time, the frame's figures are attributes too."""

    @property
    def verdict(self) -> Verdict: ...
    @property
    def frames(self) -> List[CompareFrame]: ...
    def text(self) -> str:
        """The text report of `sticky compare`."""
    def summary(self) -> str:
        """The verdict line."""
    def to_dict(self) -> dict[str, Any]:
        """The JSON of `sticky compare --json`."""
    def __getattr__(self, name: str) -> Any: ...
    def _repr_html_(self) -> str: ...

def compare(
    scene: Scene,
    t: _Number,
    positions: _Numbers,
    velocities: Optional[_Numbers] = None,
    *,
    multipliers: Optional[_Numbers] = None,
    clusters: Optional[Sequence[Tuple[int, int]]] = None,
    contact_tol: Optional[_Number] = 0,
    overlap_tol: Optional[_Number] = 0,
) -> CompareReport:
    """Another solver's answer at t against the exact one, as `sticky compare` measures it."""
