"""What a synthesis is asked, in request objects: each checked on construction.

- :class:`Target`: the ratio within a tolerance, or a range;
- :class:`Options`: what every design meets beyond its ratio, the planets and the limits of the
  derived conditions (tooth limits, pressure angle and addendum, tip clearance, profile shift,
  ring difference);
- :class:`SynthesisRequest`: all that decides the designs, the target, the ratio of which links
  (driver, driven, held links, or a gear state), the options, how many designs to list and in
  which order;
- :class:`RunOptions`: how the search runs (here or on Dask, chunks, time limit, progress), which
  never changes its designs.

:func:`symkin.synthesize` takes a request, or builds one from its keywords
(:meth:`SynthesisRequest.of`):

    >>> from fractions import Fraction
    >>> request = SynthesisRequest(Target.of(Fraction(12, 5), 0), driver="S1", driven="R", fixed="C",
    ...                            options=Options(planets=3, zmax=72))
    >>> request == SynthesisRequest.of(ratio=Fraction(12, 5), tolerance=0, driver="S1", driven="R", fixed="C",
    ...                                planets=3, zmax=72)
    True
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, fields
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin._util.budget import seconds_limit
from symkin.errors import InputError
from symkin.model import MAX_PLANETS
from symkin.synthesis.efficiency import rank_order
from symkin.values import as_fraction, as_integer, as_rational

__all__ = ["Target", "Options", "SynthesisRequest", "RunOptions", "undercut_minimum", "MAX_TEETH", "MAX_TOP",
           "PRESSURE_ANGLES"]

#: The largest tooth number a search accepts.
MAX_TEETH = 10_000
#: The most designs a result lists.
MAX_TOP = 100_000


@dataclass(frozen=True)
class Target:
    """The ratios a design may have: ``ratio`` within a relative ``tolerance``, or a range.

    >>> from fractions import Fraction
    >>> Target.of(Fraction(12, 5), 0.005).window
    (Fraction(597, 250), Fraction(603, 250))
    >>> Target.range(2, 3).error(Fraction(5, 2))
    Fraction(0, 1)
    """

    lo: Fraction
    hi: Fraction
    ratio: Fraction | None = None
    tolerance: Fraction | None = None

    @classmethod
    def of(cls, ratio: Any, tolerance: Any = Fraction(1, 100)) -> Target:
        """A target ratio with a relative tolerance (``0.01`` is 1 %), exact.

        >>> Target.of(4, 0.01).window
        (Fraction(99, 25), Fraction(101, 25))
        """
        r = as_fraction(ratio, what="the target ratio")
        t = as_fraction(tolerance, what="the ratio tolerance")
        if r == 0:
            raise InputError("the target ratio is 0: no train turns its output infinitely fast; give a non-zero ratio")
        if not 0 <= t < 1:
            raise InputError(f"the relative tolerance must be from 0 to less than 1, got {t}; 0.01 is 1 %")
        span = abs(r) * t
        return cls(r - span, r + span, r, t)

    @classmethod
    def range(cls, lo: Any, hi: Any) -> Target:
        """A target range ``lo <= i <= hi`` of ratios, exact."""
        a = as_fraction(lo, what="the least ratio")
        b = as_fraction(hi, what="the largest ratio")
        if a > b:
            raise InputError(f"the ratio range {a} .. {b} is empty; give the smaller ratio first")
        return cls(a, b)

    @property
    def window(self) -> tuple[Fraction, Fraction]:
        """The admissible ratios, ``(lo, hi)``."""
        return self.lo, self.hi

    def error(self, value: Fraction) -> Fraction:
        """Relative error from the target ratio (0 inside a range)."""
        if self.ratio is None:
            return Fraction(0)
        return abs(value - self.ratio) / abs(self.ratio)

    def text(self) -> str:
        """The target in words: ``i = R +- T %`` or ``lo <= i <= hi``."""
        if self.ratio is None:
            return f"{self.lo} <= i <= {self.hi}"
        return f"i = {self.ratio} +- {float(self.tolerance or 0) * 100:g} %"


#: Pressure angles of involute gears, degrees: below 5 the undercut-free minimum runs to hundreds of
#: teeth and beyond (1e-300 degrees: about 10^604), above 45 the teeth are pointed.
PRESSURE_ANGLES = (5, 45)


def undercut_minimum(pressure_angle_deg: Any = 20, addendum: Any = 1) -> int:
    """The least tooth number cut without undercut by a rack: ``z sin^2(alpha) >= 2 h_a*``.

    >>> undercut_minimum(20), undercut_minimum(14.5), undercut_minimum(25), undercut_minimum(20, 0.8)
    (18, 32, 12, 14)
    """
    alpha = as_rational(pressure_angle_deg, what="the pressure angle")
    h = as_rational(addendum, what="the addendum coefficient h_a*")
    if not PRESSURE_ANGLES[0] <= alpha <= PRESSURE_ANGLES[1]:
        raise InputError(f"the pressure angle must be between {PRESSURE_ANGLES[0]} and {PRESSURE_ANGLES[1]} degrees "
                         f"(usual: 20), got {alpha}")
    if not 0 < h <= 2:
        raise InputError(f"the addendum coefficient h_a* must be positive and at most 2, got {h}; the usual value is 1")
    bound = 2 * h / sp.sin(alpha * sp.pi / 180) ** 2
    n = int(sp.ceiling(bound))
    if n > 1 and (n - 1) * sp.sin(alpha * sp.pi / 180) ** 2 >= 2 * h:  # ceiling decided by digits: confirm exactly
        n -= 1
    return max(n, 1)


@dataclass(frozen=True)
class Options:
    """What a synthesis asks of every design beyond its ratio.

    Parameters
    ----------
    planets : int or None
        Equally spaced copies of every planet kind (k); None keeps each planet's ``count``.
    zmin, zmax : int, optional
        Tooth limits of every unknown gear; ``zmin`` defaults to :func:`undercut_minimum`.
    pressure_angle : number
        Pressure angle in degrees (for the undercut limit), default 20.
    addendum : number
        Addendum coefficient h_a* (tip radius = pitch radius + h_a* m), default 1.
    clearance : number
        Least gap between the tip circles of neighbouring planets, in modules, default 0.
    shift : number
        Profile shift allowed: the largest ``|a_w - a| / m`` of a mesh (centre-distance
        modification coefficient y), default 0 (meshes on their pitch circles).
    ring_difference : int
        Least tooth difference of an internal gear and a gear meshing it, default 8.

    >>> Options(planets=3).zmin, Options(planets=3, pressure_angle=25).zmin
    (18, 12)
    """

    planets: Any = 3
    zmin: Any = None
    zmax: Any = 150
    pressure_angle: Any = 20
    addendum: Any = 1
    clearance: Any = 0
    shift: Any = 0
    ring_difference: Any = 8

    def __post_init__(self) -> None:
        def put(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        if self.planets is not None:
            put("planets", int(as_integer(self.planets, what="the number of planets k", minimum=1,
                                          maximum=MAX_PLANETS)))
        put("pressure_angle", as_rational(self.pressure_angle, what="the pressure angle"))
        put("addendum", as_rational(self.addendum, what="the addendum coefficient h_a*"))
        default_min = undercut_minimum(self.pressure_angle, self.addendum)
        zmin = default_min if self.zmin is None else int(as_integer(self.zmin, what="zmin", minimum=1,
                                                                    maximum=MAX_TEETH))
        put("zmin", zmin)
        put("zmax", int(as_integer(self.zmax, what="zmax", minimum=1, maximum=MAX_TEETH)))
        if self.zmax < self.zmin:
            raise InputError(f"zmin = {self.zmin} is larger than zmax = {self.zmax}; give zmin <= zmax")
        put("clearance", as_rational(self.clearance, what="the tip clearance"))
        if not 0 <= self.clearance <= 10:
            raise InputError(f"the tip clearance between planets must be from 0 to 10 modules, got {self.clearance}")
        put("shift", as_rational(self.shift, what="the profile shift limit"))
        if not 0 <= self.shift <= 2:
            raise InputError(f"the profile shift limit |a_w - a|/m must be from 0 to 2 modules, got {self.shift}")
        put("ring_difference", int(as_integer(self.ring_difference, what="the ring difference",
                                              minimum=0, maximum=MAX_TEETH)))


@dataclass(frozen=True)
class SynthesisRequest:
    """What a synthesis asks for: everything that decides its designs and their order.

    Parameters
    ----------
    target : Target
        The ratio within a tolerance (:meth:`Target.of`) or a range (:meth:`Target.range`).
    driver, driven, fixed : str
        The ratio omega_driver / omega_driven with the ``fixed`` link(s) held; or
    state : str
        A gear state of the train (its brakes and clutches).
    options : Options
        The planets and the limits every design meets.
    top : int or None
        How many designs to list (None: all).
    rank : str or sequence of str, optional
        The order of the designs: keys among ``"error"``, ``"efficiency"`` (largest first),
        ``"size"`` and ``"teeth"`` (tooth sum), the rest of error, size, teeth following
        (:func:`symkin.synthesis.efficiency.rank_order`); ties go by the tooth numbers.
        Ranking by efficiency evaluates the train's efficiency law, derived from its statics,
        exactly at every design found.
    mesh_efficiency : str, number or dict
        The meshes' efficiencies when ranking by efficiency (:func:`symkin.statics.statics`'
        ``efficiency``): ``"default"`` (the train file's value where a mesh has one, else 0.98
        external and 0.99 internal), one number, or ``{"a-b": value}``; rational numbers (a
        decimal, a fraction), since the order is exact. The values used are in
        :attr:`~symkin.synthesis.result.SynthesisResult.mesh_efficiency`; a design whose
        efficiency is zero or below is marked (:attr:`~symkin.synthesis.result.Design.locks`:
        the driver cannot drive the driven) and, with efficiency the first key, ranks after
        every design that drives.
    """

    target: Target
    driver: str | None = None
    driven: str | None = None
    fixed: str | Sequence[str] | None = None
    state: str | None = None
    options: Options = field(default_factory=Options)
    top: int | None = 10
    rank: Any = None
    mesh_efficiency: Any = "default"

    def __post_init__(self) -> None:
        object.__setattr__(self, "rank", rank_order(self.rank))  # first: a bad key is refused before anything else
        if not isinstance(self.target, Target):
            raise InputError(f"the target is a Target (Target.of(ratio, tolerance) or Target.range(lo, hi)), got "
                             f"{self.target!r}")
        if not isinstance(self.options, Options):
            raise InputError(f"the options are an Options (Options(planets=3, zmax=150, ...)), got {self.options!r}")
        if self.fixed is not None and not isinstance(self.fixed, str):
            object.__setattr__(self, "fixed", tuple(self.fixed))
        if self.top is not None:
            object.__setattr__(self, "top", int(as_integer(self.top, what="top", minimum=1, maximum=MAX_TOP)))

    @classmethod
    def of(cls, *, ratio: Any = None, tolerance: Any = Fraction(1, 100), ratio_range: Sequence[Any] | None = None,
           driver: str | None = None, driven: str | None = None, fixed: str | Sequence[str] | None = None,
           state: str | None = None, top: int | None = 10, rank: Any = None, mesh_efficiency: Any = "default",
           **options: Any) -> SynthesisRequest:
        """The request the keywords of :func:`symkin.synthesize` ask for: the target from ``ratio`` and
        ``tolerance`` or from ``ratio_range``, the :class:`Options` from their fields."""
        rank = rank_order(rank)
        target = _target(ratio, tolerance, ratio_range)
        return cls(target, driver, driven, fixed, state, Options(**options), top, rank, mesh_efficiency)


def _target(ratio: Any, tolerance: Any, ratio_range: Sequence[Any] | None) -> Target:
    if ratio_range is not None:
        if ratio is not None:
            raise InputError("give either a target ratio (with a tolerance) or a ratio range, not both")
        try:
            lo, hi = ratio_range
        except (TypeError, ValueError):
            raise InputError(f"a ratio range is two numbers (lo, hi), got {ratio_range!r}") from None
        return Target.range(lo, hi)
    if ratio is not None:
        return Target.of(ratio, tolerance)
    raise InputError("give the target ratio (and a tolerance), or a ratio range")


@dataclass(frozen=True)
class RunOptions:
    """How a search runs; its designs are the same however it runs (any chunking, here or on Dask).

    Parameters
    ----------
    scheduler : str, optional
        Run the chunks on Dask: ``"local"`` (a local cluster of ``workers`` processes) or a
        scheduler's address.
    workers : int, optional
        Processes of a local cluster (default: the machine's cores).
    chunk : int, optional
        Outer tuples per chunk (default: about 64 chunks, 256 to 32768 tuples each).
    time_limit : float, optional
        Seconds; a longer search raises :class:`~symkin.errors.TimeLimitError` with bounds to try.
    progress : callable(done, total, found), optional
        Called as chunks finish: chunks done, chunks in all, designs found so far.
    allow_empty : bool
        Return a result without designs (its ``reason`` says why) instead of raising when
        nothing is found.
    """

    scheduler: str | None = None
    workers: int | None = None
    chunk: int | None = None
    time_limit: float | None = None
    progress: Callable[[int, int, int], None] | None = None
    allow_empty: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "time_limit", seconds_limit(self.time_limit))
        if self.workers is not None:
            object.__setattr__(self, "workers", int(as_integer(self.workers, what="the number of workers", minimum=1,
                                                               maximum=1024)))
        if self.chunk is not None:
            object.__setattr__(self, "chunk", int(as_integer(self.chunk, what="the chunk size", minimum=1,
                                                             maximum=1 << 24)))


#: The keywords of :func:`symkin.synthesize` that are :class:`RunOptions` fields.
RUN_FIELDS = frozenset(f.name for f in fields(RunOptions))
