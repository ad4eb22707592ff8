"""What a synthesis is asked: the target ratio, and the options every design must meet beyond it.

:class:`Target` is the ratio within a tolerance or a range; :class:`Options` holds the planets
and the limits of the derived conditions (tooth limits, pressure angle and addendum, tip
clearance, profile shift, ring difference).  Each is checked on construction.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin.errors import InputError
from symkin.model import MAX_PLANETS
from symkin.values import as_fraction, as_integer, as_rational

__all__ = ["Target", "Options", "undercut_minimum", "MAX_TEETH", "PRESSURE_ANGLES"]

#: The largest tooth number a search accepts.
MAX_TEETH = 10_000


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

