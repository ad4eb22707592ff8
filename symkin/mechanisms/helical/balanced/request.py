"""What a designer asks of the synthesis, and what it answers: request, design and result types.

    >>> HelicalRequest(scheme="AI", ratio=25, tolerance=0.02).ratio_window
    (Fraction(49, 2), Fraction(51, 2))
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from symkin._util.jsonout import exact_json, exact_json_list
from symkin.errors import InputError
from symkin.mechanisms.helical import HelicalTrain, hand_name
from symkin.mechanisms.helical.balanced.conditions import _scheme
from symkin.values import as_fraction, as_integer

__all__ = ["HelicalRequest", "HelicalDesign", "HelicalResult"]


@dataclass(frozen=True)
class HelicalRequest:
    """What a designer asks for; every field is checked on construction.

    Parameters
    ----------
    scheme : {"AI", "AA", "II"}
    ratio : number
        Target i_1H^(4) = omega_1 / omega_H with gear 4 fixed (exact: "1/50" is 1/50).
    tolerance : number
        Admissible relative ratio error ``|i - target| / |target|`` (0.02 = 2 %).
    satellites : int
        Number k of equally spaced planets.
    normal_modules : (number, number)
        m_n12 and m_n34 (mm).
    beta_min_deg, beta_max_deg : number
        Limits on both helix angles, inside (0, 45) degrees.
    teeth_min, teeth_max : int
        Limits on every tooth number.
    alpha_n_deg : number
        Normal pressure angle (degrees).
    addendum : number
        Addendum coefficient h_a* (tip circles in the neighbour condition).
    min_ring_difference : int
        Least tooth difference between an internal gear and its planet rim (interference).
    top : int or None
        How many designs to list (all when None).
    """

    scheme: str
    ratio: Any
    tolerance: Any = Fraction(1, 100)
    satellites: Any = 3
    normal_modules: tuple[Any, Any] = (2, 2)
    beta_min_deg: Any = 8
    beta_max_deg: Any = 30
    teeth_min: Any = 17
    teeth_max: Any = 150
    alpha_n_deg: Any = 20
    addendum: Any = 1
    min_ring_difference: Any = 8
    top: Any = 20

    MAX_SPAN = 600  # tooth numbers per gear searched; the work grows as the cube

    def __post_init__(self) -> None:
        def put(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        _scheme(self.scheme)
        put("ratio", as_fraction(self.ratio, what="the target ratio"))
        if self.ratio == 0:
            raise InputError("the target ratio i_1H^(4) must not be 0 (the carrier would not turn); give a non-zero ratio")
        put("tolerance", as_fraction(self.tolerance, what="the ratio tolerance"))
        if not 0 <= self.tolerance < 1:  # (as symkin.synthesis: from 1 on the window holds every ratio of the sign)
            raise InputError(f"the relative ratio tolerance must be from 0 to less than 1, got {self.tolerance}; 0.01 is 1 %")
        put("satellites", _whole(self.satellites, "the number of satellites"))
        put("normal_modules", _normal_modules(self.normal_modules))
        put("beta_min_deg", as_fraction(self.beta_min_deg, what="beta-min"))
        put("beta_max_deg", as_fraction(self.beta_max_deg, what="beta-max"))
        _check_helix_limits(self.beta_min_deg, self.beta_max_deg)
        zmin, zmax = _teeth_limits(self.teeth_min, self.teeth_max, self.MAX_SPAN)
        put("teeth_min", zmin)
        put("teeth_max", zmax)
        a_n = as_fraction(self.alpha_n_deg, what="the normal pressure angle")
        if not 0 < a_n < 45:
            raise InputError(f"the normal pressure angle must lie between 0 and 45 degrees, got {float(a_n):g}")
        put("alpha_n_deg", a_n)
        ha = as_fraction(self.addendum, what="the addendum coefficient")
        if ha < 0:
            raise InputError(f"the addendum coefficient must be >= 0, got {ha}")
        put("addendum", ha)
        put("min_ring_difference", _whole(self.min_ring_difference, "the least ring-planet tooth difference"))
        if self.top is not None:
            put("top", _whole(self.top, "top"))

    @property
    def ratio_window(self) -> tuple[Fraction, Fraction]:
        """The admissible ratios, exact: ``target -+ tolerance |target|``."""
        half = self.tolerance * abs(self.ratio)
        return self.ratio - half, self.ratio + half

    def to_json(self) -> dict[str, Any]:
        """The request as JSON (scheme, ratio window, modules, angles, limits)."""
        return {
            "scheme": self.scheme,
            "ratio": exact_json(self.ratio),
            "tolerance": exact_json(self.tolerance),
            "satellites": self.satellites,
            "normal_modules_mm": exact_json_list(self.normal_modules),
            "beta_min_deg": exact_json(self.beta_min_deg),
            "beta_max_deg": exact_json(self.beta_max_deg),
            "teeth": [self.teeth_min, self.teeth_max],
            "alpha_n_deg": exact_json(self.alpha_n_deg),
            "addendum": exact_json(self.addendum),
            "min_ring_difference": self.min_ring_difference,
            "top": self.top,
        }


def _whole(value: Any, what: str) -> int:
    """A whole number of at least 1."""
    n = int(as_integer(value, what=what))
    if n < 1:
        raise InputError(f"{what} must be at least 1, got {n}")
    return n


def _normal_modules(modules: Any) -> tuple[Fraction, Fraction]:
    try:
        m12, m34 = modules
    except (TypeError, ValueError):
        raise InputError("give two normal modules, m_n12 and m_n34") from None
    mods = (as_fraction(m12, what="the normal module m_n12"), as_fraction(m34, what="the normal module m_n34"))
    for name, m in zip(("m_n12", "m_n34"), mods):
        if m <= 0:
            raise InputError(f"the normal module {name} must be positive, got {m}")
    return mods


def _check_helix_limits(lo: Fraction, hi: Fraction) -> None:
    for name, b in (("beta-min", lo), ("beta-max", hi)):
        if not 0 < b < 45:
            raise InputError(f"{name} must lie strictly between 0 and 45 degrees, got {float(b):g}")
    if lo >= hi:
        raise InputError(f"beta-min ({float(lo):g} deg) must be less than beta-max ({float(hi):g} deg): these limits exclude every design")


def _teeth_limits(teeth_min: Any, teeth_max: Any, span: int) -> tuple[int, int]:
    zmin, zmax = int(as_integer(teeth_min, what="zmin")), int(as_integer(teeth_max, what="zmax"))
    if zmin < 1:
        raise InputError(f"zmin must be at least 1, got {zmin}")
    if zmin > zmax:
        raise InputError(f"zmin ({zmin}) is larger than zmax ({zmax}): these limits exclude every design")
    if zmax - zmin + 1 > span:
        raise InputError(f"zmin..zmax spans {zmax - zmin + 1} tooth numbers; at most {span} are searched, narrow the range")
    return zmin, zmax


@dataclass(frozen=True)
class HelicalDesign:
    """One synthesised train: integers, helix angles, and how well it meets the target.

    Attributes
    ----------
    train : HelicalTrain
        Teeth, modules, helix angles (radians), balancing hands, satellites.
    ratio : Fraction
        i_1H^(4), exact.
    relative_error : Fraction
        ``|ratio - target| / |target|``, exact.
    assembly : (int, int)
        The integers (P, Q) of the assembly condition.
    helix_free : bool
        True when the rims have equal leads and both meshes equal centre distances at any
        helix angle (then the angles are set to beta-min).
    """

    train: HelicalTrain
    ratio: Fraction
    relative_error: Fraction
    assembly: tuple[int, int]
    helix_free: bool = False

    @property
    def teeth(self) -> tuple[int, int, int, int]:
        """The tooth numbers (Z1, Z2, Z3, Z4)."""
        return self.train.teeth

    @property
    def betas_deg(self) -> tuple[float, float]:
        """The helix angles (beta12, beta34) in degrees."""
        return math.degrees(self.train.betas[0]), math.degrees(self.train.betas[1])

    @property
    def centre_distance(self) -> float:
        """The common centre distance of both meshes (mm)."""
        return self.train.centre_distances[0]

    @property
    def envelope_diameter(self) -> float:
        """The diameter of the circle that encloses the train (mm)."""
        return self.train.envelope_diameter

    def to_json(self) -> dict[str, Any]:
        """The design as JSON: teeth, exact ratio and its error, helix angles and hands, P, Q, centre distance, and the independent force check."""
        t = self.train
        assert t.hands is not None  # HelicalTrain.__post_init__ sets the balancing hands when none are given
        return {
            "teeth": list(t.teeth),
            "ratio": exact_json(self.ratio),
            "relative_error": exact_json(self.relative_error),
            "beta12_deg": self.betas_deg[0],
            "beta34_deg": self.betas_deg[1],
            "helix_free": self.helix_free,
            "hands": [hand_name(h) for h in t.hands],
            "P": self.assembly[0],
            "Q": self.assembly[1],
            "centre_distance_mm": self.centre_distance,
            "d_w2/d_w3": t.working_diameter_ratio,
            "envelope_diameter_mm": self.envelope_diameter,
            "neighbour_margin_mm": t.neighbour_margin if math.isfinite(t.neighbour_margin) else None,
        }


@dataclass(frozen=True)
class HelicalResult:
    """The designs found, best first, and how many tooth sets passed each condition.

    ``reason`` says why nothing was found (empty when designs were found).  A
    :class:`~symkin.synthesis.searches.SearchResult`: iterating it gives the designs.
    """

    request: HelicalRequest
    designs: tuple[HelicalDesign, ...]
    found: int
    stages: tuple[tuple[str, int], ...]
    reason: str
    seconds: float

    def __iter__(self) -> Iterator[HelicalDesign]:
        return iter(self.designs)

    def message(self) -> str:
        """How many designs were found and which are listed, in what order; or why there are none."""
        if not self.found:
            return self.reason
        shown = len(self.designs)
        return (f"{self.found} designs; {'all' if shown == self.found else f'the best {shown}'} by ratio error, "
                "then envelope diameter")

    def to_json(self) -> dict[str, Any]:
        """The result as JSON: the request, the designs, and what removed the last candidates when none is left."""
        return {
            "request": self.request.to_json(),
            "found": self.found,
            "listed": len(self.designs),
            "stages": [{"condition": name, "tooth_sets": n} for name, n in self.stages],
            "reason": self.reason,
            "designs": [d.to_json() for d in self.designs],
        }

