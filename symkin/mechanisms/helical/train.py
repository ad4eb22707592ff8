"""A two-row planetary train whose stepped planet meshes helically: geometry and kinematics.

:class:`HelicalTrain` holds the numeric geometry of both meshes
(:class:`~symkin.mechanisms.helical.geometry.HelicalMesh`) and enters the engine as a
two-row scheme with its exact working pitch radii.  Its ratio is the engine's law of the
scheme (:func:`ratio_law`, derived once per scheme) evaluated exactly.

    >>> ratio_law("II").rhs
    1 - z_2*z_4/(z_1*z_3)
    >>> ratio_function("AA")(100, 99, 100, 101)
    Fraction(1, 10000)
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import cache, cached_property
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError, ModelError
from symkin.laws import Law
from symkin.mechanisms.helical.geometry import (
    DEFAULT_PRESSURE_ANGLE,
    SCHEME_MESHES,
    HelicalMesh,
    _angle,
    hand_name,
)
from symkin.model import Mechanism
from symkin.numeric import compile
from symkin.schemes import two_row
from symkin.statics import balancing_hands
from symkin.values import as_integer, as_rational

__all__ = ["HelicalTrain", "ratio_law", "ratio_function", "SCHEMES"]

#: The two-row schemes a helical train can have.
SCHEMES = tuple(SCHEME_MESHES)


def _scheme(scheme: Any) -> str:
    if not isinstance(scheme, str) or scheme not in SCHEME_MESHES:
        raise InputError(f"unknown scheme {scheme!r}; choose one of {', '.join(SCHEMES)}")
    return scheme


@cache
def ratio_law(scheme: str) -> Law:
    """i_1H^(4) in tooth numbers, from the engine's contact conditions (derived once per scheme).

    >>> ratio_law("AI").rhs
    1 + z_2*z_4/(z_1*z_3)
    """
    return two_row(_scheme(scheme), teeth=True).ratio("1", "H", fixed="4")


@cache
def ratio_function(scheme: str) -> Callable[..., Fraction]:
    """:func:`ratio_law` as an exact function of the four tooth numbers (a Fraction).

    >>> ratio_function("AI")(18, 80, 20, 108)
    Fraction(25, 1)
    """
    z = [S.teeth(str(n)) for n in (1, 2, 3, 4)]
    return compile(ratio_law(scheme), z, backend="exact")


def _as_modules(values: Any) -> tuple[Fraction, Fraction]:
    try:
        m12, m34 = values
    except (TypeError, ValueError):
        raise ModelError(f"give the two normal modules (m_n12, m_n34), got {values!r}") from None
    out = []
    for m, what in ((m12, "normal module of mesh 1-2"), (m34, "normal module of mesh 3-4")):
        r = as_rational(m, what=what, error=ModelError)
        f = Fraction(int(r.p), int(r.q))
        if f <= 0:
            raise ModelError(f"{what} must be positive, got {m}")
        out.append(f)
    return out[0], out[1]


@dataclass(frozen=True)
class HelicalTrain:
    """A two-row planetary train whose stepped planet (rims 2, 3) meshes helically.

    Central gear 1 meshes rim 2 (normal module ``m_n12``, helix angle ``beta12``), rim 3
    meshes central gear 4 (``m_n34``, ``beta34``); carrier H; ``satellites`` equal planets.

    Parameters
    ----------
    scheme : {"AI", "AA", "II"}
        A = external, I = internal central gear; first letter gear 1, second gear 4.
    teeth : (int, int, int, int)
        Z1, Z2, Z3, Z4.
    normal_modules : (number, number)
        m_n12, m_n34 (exact numbers are kept exact: 2.5 is 5/2).
    betas : (float, float)
        Reference helix angles beta12 (gears 1, 2) and beta34 (gears 3, 4), radians.
    hands : (int, int, int, int), optional
        Helix hand of gears 1-4 (+1 right, -1 left); default: the hands that balance
        the planet's axial forces with right-handed rims (:func:`symkin.statics.balancing_hands`).
    satellites : int
    alpha_n : float
        Normal pressure angle (radians).
    shifts : (float, float, float, float)
        Profile shift coefficients x1..x4.
    addendum : float
        h_a*.

    Examples
    --------
    >>> t = HelicalTrain("AI", (20, 40, 20, 80), (2, 2), (math.radians(10), math.radians(10)))
    >>> t.ratio
    Fraction(9, 1)
    >>> t.hands
    (-1, 1, 1, 1)
    """

    scheme: str
    teeth: tuple[int, int, int, int]
    normal_modules: tuple[Any, Any]
    betas: tuple[float, float]
    hands: tuple[int, int, int, int] | None = None
    satellites: int = 1
    alpha_n: float = DEFAULT_PRESSURE_ANGLE
    shifts: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    addendum: float = 1.0

    def __post_init__(self) -> None:
        if self.scheme not in SCHEME_MESHES:
            raise ModelError(f"unknown two-row scheme {self.scheme!r}; choose one of {', '.join(SCHEME_MESHES)}")
        try:
            teeth = tuple(self.teeth)
            betas = tuple(self.betas)
            shifts = tuple(float(x) for x in self.shifts)
        except (TypeError, ValueError):
            raise ModelError("teeth, helix angles and shifts must be sequences of numbers") from None
        if len(teeth) != 4 or len(betas) != 2 or len(shifts) != 4:
            raise ModelError("give four tooth numbers Z1..Z4, two helix angles (beta12, beta34) and four shifts")
        teeth = tuple(int(as_integer(z, what=f"tooth number Z{n}", error=ModelError, minimum=1)) for n, z in enumerate(teeth, 1))
        object.__setattr__(self, "teeth", teeth)
        object.__setattr__(self, "normal_modules", _as_modules(self.normal_modules))
        object.__setattr__(self, "betas", tuple(_angle(b, f"helix angle {n}", 0.0, math.pi / 2) for n, b in zip(("beta12", "beta34"), betas)))
        object.__setattr__(self, "shifts", shifts)
        object.__setattr__(self, "satellites", int(as_integer(self.satellites, what="the number of satellites", error=ModelError, minimum=1)))
        if self.hands is None:
            object.__setattr__(self, "hands", balancing_hands(self.scheme))
        else:
            hands = tuple(self.hands)
            if len(hands) != 4:
                raise ModelError("give four helix hands (gears 1..4), each +1 (right) or -1 (left)")
            for h in hands:
                hand_name(h)
            object.__setattr__(self, "hands", hands)
        _ = (self.mesh12, self.mesh34)  # validate both meshes now

    # ---- meshes
    @cached_property
    def mesh12(self) -> HelicalMesh:
        """Mesh of rim 2 with central gear 1."""
        z1, z2, _, _ = self.teeth
        x1, x2, _, _ = self.shifts
        return HelicalMesh(z2, z1, float(self.normal_modules[0]), self.betas[0], SCHEME_MESHES[self.scheme][0],
                           self.alpha_n, x2, x1, self.addendum)

    @cached_property
    def mesh34(self) -> HelicalMesh:
        """Mesh of rim 3 with central gear 4."""
        _, _, z3, z4 = self.teeth
        _, _, x3, x4 = self.shifts
        return HelicalMesh(z3, z4, float(self.normal_modules[1]), self.betas[1], SCHEME_MESHES[self.scheme][1],
                           self.alpha_n, x3, x4, self.addendum)

    # ---- geometry
    @property
    def centre_distances(self) -> tuple[float, float]:
        """Working centre distances of meshes 1-2 and 3-4 (equal when coaxial)."""
        return self.mesh12.centre_distance, self.mesh34.centre_distance

    @property
    def coaxiality_residual(self) -> float:
        """(a_w12 - a_w34) / a_w12: zero for a coaxial train."""
        a12, a34 = self.centre_distances
        return (a12 - a34) / a12

    @property
    def working_diameter_ratio(self) -> float:
        """d_w2 / d_w3, the paper's balance and existence parameter."""
        return self.mesh12.working_radius("external") / self.mesh34.working_radius("external")

    @property
    def leads(self) -> tuple[float, float]:
        """Leads of rims 2 and 3 (equal when the planet's axial forces balance)."""
        return self.mesh12.lead("external"), self.mesh34.lead("external")

    @property
    def tip_diameters(self) -> tuple[float, float]:
        """Tip diameters of rims 2 and 3."""
        return 2 * self.mesh12.tip_radius("external"), 2 * self.mesh34.tip_radius("external")

    @property
    def neighbour_margin(self) -> float:
        """``2 a_w sin(pi/k) - max(d_a2, d_a3)``: positive when neighbouring planets clear.

        Infinite for a single satellite.
        """
        if self.satellites == 1:
            return math.inf
        return 2 * self.centre_distances[0] * math.sin(math.pi / self.satellites) - max(self.tip_diameters)

    @property
    def envelope_diameter(self) -> float:
        """Diameter of the circle around the planets' tip circles, ``2 a_w + max(d_a2, d_a3)``."""
        return 2 * self.centre_distances[0] + max(self.tip_diameters)

    # ---- kinematics through the engine
    @property
    def working_radii_exact(self) -> tuple[Fraction, Fraction, Fraction, Fraction]:
        """Working pitch radii of gears 1-4 in units of r_w1/Z1, exact and coaxial.

        Within a mesh the working radii are in the tooth ratio; coaxiality fixes the scale
        of mesh 3-4 against mesh 1-2.  Kinematics depends on nothing else.
        """
        z1, z2, z3, z4 = self.teeth
        s12, s34 = self.mesh12.teeth_sum, self.mesh34.teeth_sum
        scale = Fraction(s12, s34)
        return Fraction(z1), Fraction(z2), z3 * scale, z4 * scale

    @cached_property
    def mechanism(self) -> Mechanism:
        """The train as a :class:`~symkin.model.Mechanism` with its exact working pitch radii."""
        radii = tuple(sp.Rational(r.numerator, r.denominator) for r in self.working_radii_exact)
        return two_row(self.scheme, radii=radii)

    @property
    def ratio(self) -> Fraction:
        """i_1H^(4) = omega_1 / omega_H with gear 4 fixed, exact.

        The engine's law for the scheme (:func:`ratio_law`, derived once) at this
        train's tooth numbers: within each mesh the working radii
        are in the tooth ratio, and the law depends on nothing else, so this is the value
        of ``self.mechanism.ratio("1", "H", fixed="4")``.
        """
        return ratio_function(self.scheme)(*self.teeth)
