"""Tooth-number synthesis of a single-row AI stage (sun, planets, fixed ring).

A stage is feasible when its tooth numbers satisfy four conditions, each derived here
from the engine's single-row AI scheme (:func:`symkin.schemes.single_row_AI`) rather
than typed in:

- *coaxiality*: the planet axis is where both meshes put it; with equal modules the
  engine's condition solves to ``z_ring = z_sun + 2 z_planet``;
- *assembly*: ``k`` planets spaced evenly fit the teeth of sun and ring,
  ``(z_sun + z_ring) / k`` a whole number;
- *neighbours*: adjacent planet tips clear each other; the chord between planet axes
  ``2 a_w sin(pi/k)`` (``a_w`` the engine's planet arm) exceeds the planet tip diameter
  ``m (z_planet + 2 h_a*)``;
- *limits*: every tooth number in ``[zmin, zmax]``.

The ratio of a stage (input sun, output carrier, ring fixed) is the engine's law
evaluated exactly.  :func:`enumerate_stages` lists every feasible stage for a ring.

    >>> from symkin.mechanisms.multistage.stages import enumerate_stages
    >>> found = enumerate_stages(80, 3, zmin=17, zmax=80)
    >>> [(s.sun, s.planet, s.ratio) for s in found]
    [(46, 17, 63/23), (40, 20, 3), (34, 23, 57/17), (28, 26, 27/7), (22, 29, 51/11)]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin._util.jsonout import exact_json, exact_json_list
from symkin.errors import InputError, ModelError
from symkin.laws import Law
from symkin.numeric import compile
from symkin.schemes import single_row_AI
from symkin.values import as_integer, as_rational

__all__ = [
    "Stage",
    "StageSet",
    "stage_laws",
    "planet_teeth",
    "stage_ratio",
    "coaxial",
    "assembles",
    "neighbours_clear",
    "max_satellites",
    "check_stage",
    "enumerate_stages",
]

Z_SUN, Z_PLANET, Z_RING = S.teeth("1"), S.teeth("2"), S.teeth("4")
#: The largest ring :func:`enumerate_stages` takes: it visits every candidate sun (about 2.5 s at this size).
MAX_RING = 100_000

#: The tip-height coefficient h_a* and the satellite count k, as symbols.
HA, K = sp.Symbol("h_a^*", positive=True), sp.Symbol("k", positive=True, integer=True)


# --------------------------------------------------------------------------- derived laws
@dataclass(frozen=True)
class StageLaws:
    """The single-row AI laws the synthesis uses, all derived by the engine.

    Attributes
    ----------
    ratio : Law
        i_1H^(4) in z_1 (sun) and z_4 (ring), the engine's law.
    coaxiality : sympy.Eq
        The engine's coaxiality condition, in teeth with a common module.
    ring_from_coaxiality : sympy expression
        That condition solved for z_4.
    planet_from_coaxiality : sympy expression
        That condition solved for z_2.
    neighbour_margin : sympy expression
        Chord between adjacent planet axes minus the planet tip diameter, in modules;
        positive when neighbours clear each other.
    centre_distance : sympy expression
        The planet arm a_w in modules.
    """

    ratio: Law
    coaxiality: sp.Eq
    ring_from_coaxiality: sp.Expr
    planet_from_coaxiality: sp.Expr
    neighbour_margin: sp.Expr
    centre_distance: sp.Expr


def compile_exact(expr: sp.Expr, args: Sequence[sp.Symbol]) -> Callable[..., Fraction]:
    """An exact function of tooth numbers (ints and Fractions in, a Fraction out)."""
    return compile(expr, list(args), backend="exact")


@lru_cache(maxsize=1)
def _compiled() -> dict[str, Callable[..., Fraction]]:
    laws = stage_laws()
    s = sp.sin(sp.pi / K)
    slope = laws.neighbour_margin.coeff(s)
    rest = sp.expand(laws.neighbour_margin - slope * s)
    if rest.has(s) or slope.has(s):
        raise ModelError("the neighbour margin is not linear in sin(pi/k)")  # pragma: no cover
    return {
        "planet": compile_exact(laws.planet_from_coaxiality, (Z_SUN, Z_RING)),
        "ring": compile_exact(laws.ring_from_coaxiality, (Z_SUN, Z_PLANET)),
        "ratio": compile_exact(laws.ratio.rhs, (Z_SUN, Z_RING)),
        "arm": compile_exact(laws.centre_distance, (Z_SUN, Z_PLANET)),
        "margin_constant": compile_exact(rest, (Z_SUN, Z_PLANET, HA)),
        "margin_slope": compile_exact(slope, (Z_SUN, Z_PLANET)),
    }


@lru_cache(maxsize=1)
def stage_laws() -> StageLaws:
    """Derive the stage laws once from :func:`symkin.schemes.single_row_AI`.

    >>> laws = stage_laws()
    >>> print(laws.ratio)
    i_{1H}^{(4)} = 1 + z_4/z_1
    >>> laws.ring_from_coaxiality
    z_1 + 2*z_2
    >>> laws.neighbour_margin
    -2*h_a^* - z_2 + (z_1 + z_2)*sin(pi/k)
    """
    mech = single_row_AI(teeth=True)
    m = S.module()
    ratio = mech.ratio("1", "H", fixed="4")
    (cond,) = mech.coaxiality
    (ring,) = sp.solve(cond, Z_RING)
    (planet,) = sp.solve(cond, Z_PLANET)
    arm = mech.arm("2")
    tip_diameter = 2 * mech.gear("2").radius + 2 * HA * m  # d_a = d + 2 h_a* m
    margin = sp.expand((2 * arm * sp.sin(sp.pi / K) - tip_diameter) / m)
    margin = sp.collect(margin, sp.sin(sp.pi / K), sp.factor)
    return StageLaws(ratio, cond, ring, planet, margin, sp.expand(arm / m))


def _tip_height(ha: Any) -> sp.Rational:
    value = as_rational(ha, what="the tip-height coefficient h_a*")
    if value <= 0:
        raise InputError(f"the tip-height coefficient h_a* must be positive, got {value}; the usual value is 1")
    return value


# --------------------------------------------------------------------------- conditions
def planet_teeth(sun: int, ring: int) -> int | None:
    """The planet's tooth number that makes a sun and ring coaxial, or None if not whole.

    >>> planet_teeth(20, 100), planet_teeth(21, 100)
    (40, None)
    """
    value = _compiled()["planet"](sun, ring)
    return int(value) if value.denominator == 1 else None


def stage_ratio(sun: int, ring: int) -> sp.Rational:
    """The exact ratio omega_sun / omega_carrier with the ring fixed (the engine's law).

    >>> stage_ratio(20, 100), stage_ratio(60, 100)
    (6, 8/3)
    """
    value = _compiled()["ratio"](sun, ring)
    return sp.Rational(value.numerator, value.denominator)


def coaxial(sun: int, planet: int, ring: int) -> bool:
    """True when both meshes put the planet axis at one distance (equal modules).

    >>> coaxial(20, 40, 100), coaxial(20, 41, 100)
    (True, False)
    """
    return _compiled()["ring"](sun, planet) == ring


def assembles(sun: int, ring: int, satellites: int) -> bool:
    """True when ``satellites`` evenly spaced planets can be assembled: (z_sun + z_ring)/k whole.

    >>> assembles(20, 100, 4), assembles(22, 100, 4)
    (True, False)
    """
    return (sun + ring) % satellites == 0


def _sign(constant: Fraction, slope: Fraction, k: int) -> int:
    """Exact sign of constant + slope * sin(pi/k) (rationals constant and slope).

    sin(pi/k) is rational only for k = 1, 2, 6; for every other k it is irrational, so
    the sum is zero only when both parts are, and enough digits decide its sign.
    """
    exact_sin = {1: Fraction(0), 2: Fraction(1), 6: Fraction(1, 2)}
    if k in exact_sin or slope == 0:
        value = constant + slope * exact_sin.get(k, Fraction(0))
        return (value > 0) - (value < 0)
    try:
        approx = float(constant) + float(slope) * math.sin(math.pi / k)
        if abs(approx) > 1e-9 * (abs(float(constant)) + abs(float(slope))):
            return 1 if approx > 0 else -1
    except OverflowError:  # beyond floats: decide with exact arithmetic below
        pass
    precise = (sp.Rational(constant.numerator, constant.denominator)
               + sp.Rational(slope.numerator, slope.denominator) * sp.sin(sp.pi / k)).evalf(60)
    return 1 if precise > 0 else -1


def neighbours_clear(sun: int, planet: int, satellites: int, ha: Any = 1) -> bool:
    """True when adjacent planet tips clear each other (decided exactly).

    One planet has no neighbour, so the condition holds for ``satellites = 1``.

    >>> neighbours_clear(20, 40, 4), neighbours_clear(16, 42, 4)
    (True, False)
    >>> neighbours_clear(24, 20, 6), neighbours_clear(25, 20, 6)  # equality is not clearance
    (False, True)
    """
    k = int(as_integer(satellites, what="the number of satellites", minimum=1))
    if k == 1:
        return True
    h = _tip_height(ha)
    c = _compiled()
    constant = c["margin_constant"](sun, planet, Fraction(int(h.p), int(h.q)))
    return _sign(constant, c["margin_slope"](sun, planet), k) > 0


def max_satellites(sun: int, planet: int, ha: Any = 1) -> int:
    """The largest satellite count whose neighbours clear each other (assembly not checked).

    >>> max_satellites(20, 40)
    4
    """
    k = 1
    while neighbours_clear(sun, planet, k + 1, ha):
        k += 1
    return k


def check_stage(sun: int, planet: int, ring: int, satellites: int, *, zmin: int = 1, zmax: int | None = None,
                ha: Any = 1) -> dict[str, bool]:
    """Each condition of a stage: coaxiality, assembly, neighbours, limits.

    >>> check_stage(16, 42, 100, 4, zmin=15, zmax=100)
    {'coaxiality': True, 'assembly': True, 'neighbours': False, 'limits': True}
    """
    zmax = max(sun, planet, ring) if zmax is None else zmax
    return {
        "coaxiality": coaxial(sun, planet, ring),
        "assembly": assembles(sun, ring, satellites),
        "neighbours": neighbours_clear(sun, planet, satellites, ha),
        "limits": all(zmin <= z <= zmax for z in (sun, planet, ring)),
    }


# --------------------------------------------------------------------------- stages
@dataclass(frozen=True, order=True)
class Stage:
    """One feasible single-row AI stage.

    Attributes
    ----------
    ratio : sympy.Rational
        omega_sun / omega_carrier with the ring fixed (exact).
    sun, planet, ring : int
        Tooth numbers (the 2014 paper's z_{3i-2}, z_{3i-1}, z_{3i}).
    satellites : int
    """

    ratio: sp.Rational
    sun: int
    planet: int
    ring: int
    satellites: int

    @property
    def centre_distance(self) -> sp.Rational:
        """The planet arm a_w in modules, (z_sun + z_planet)/2."""
        value = _compiled()["arm"](self.sun, self.planet)
        return sp.Rational(value.numerator, value.denominator)

    def to_json(self) -> dict[str, Any]:
        """The stage as JSON: sun, planet and ring teeth, satellites, the exact ratio and the centre distance in modules."""
        return {
            "sun": self.sun,
            "planet": self.planet,
            "ring": self.ring,
            "satellites": self.satellites,
            "ratio": exact_json(self.ratio),
            "centre_distance_modules": exact_json(self.centre_distance),
        }


@dataclass(frozen=True)
class StageSet:
    """Every feasible stage for one ring, in increasing ratio, and why the others fail.

    Attributes
    ----------
    ring, satellites, zmin, zmax : int
    ha : sympy.Rational
        Tip-height coefficient h_a*.
    stages : tuple of Stage
    rejected : dict
        How many candidate suns each condition rejected, in the order checked
        (limits, coaxiality, assembly, neighbours); a sun is counted by its first failure.
    """

    ring: int
    satellites: int
    zmin: int
    zmax: int
    ha: sp.Rational
    stages: tuple[Stage, ...]
    rejected: dict[str, int] = field(default_factory=dict)

    def __iter__(self) -> Iterator[Stage]:
        return iter(self.stages)

    def __len__(self) -> int:
        return len(self.stages)

    def __getitem__(self, i: int) -> Stage:
        return self.stages[i]

    @property
    def ratios(self) -> tuple[sp.Rational, ...]:
        """The stages' exact ratios, in the order of the stages.

        >>> from symkin.mechanisms.multistage.stages import enumerate_stages
        >>> enumerate_stages(180, 3, zmin=18, zmax=180).ratios[:2]
        (9/4, 53/23)
        """
        return tuple(s.ratio for s in self.stages)

    def by_ratio(self, ratio: Any) -> Stage:
        """The stage with this exact ratio.

        >>> enumerate_stages(100, 4, zmin=15).by_ratio(6).sun
        20
        """
        r = sp.Rational(ratio)
        for s in self.stages:
            if s.ratio == r:
                return s
        raise InputError(f"no feasible stage has ratio {r}; the feasible ratios are {', '.join(map(str, self.ratios))}")

    def to_json(self) -> dict[str, Any]:
        """The stages as JSON, with the ring, satellites and limits they were found for."""
        return {
            "ring": self.ring,
            "satellites": self.satellites,
            "zmin": self.zmin,
            "zmax": self.zmax,
            "ha": exact_json(self.ha),
            "count": len(self.stages),
            "ratio_range": exact_json_list([self.stages[0].ratio, self.stages[-1].ratio]) if self.stages else None,
            "rejected": dict(self.rejected),
            "stages": [s.to_json() for s in self.stages],
        }


def enumerate_stages(ring: int, satellites: int, *, zmin: int = 1, zmax: int | None = None, ha: Any = 1,
                     allow_empty: bool = False) -> StageSet:
    """Every feasible single-row AI stage for a ring of ``ring`` teeth, exactly.

    Parameters
    ----------
    ring : int
        Tooth number of the fixed ring, shared by every stage of a common-ring train.
    satellites : int
        Planets per stage, k >= 1.
    zmin, zmax : int
        Limits on every tooth number (sun, planet and ring); ``zmax`` defaults to ``ring``.
    ha : number
        Tip-height coefficient h_a* of the neighbour condition (positive, default 1).
    allow_empty : bool
        Return an empty set instead of raising when no stage is feasible.

    Returns
    -------
    StageSet
        Stages in increasing ratio, with the count of candidates each condition rejected.

    Raises
    ------
    InputError
        On bad input, or when no stage is feasible (unless ``allow_empty``): the message
        names the condition that rejects the last candidates and how to relax it.

    Examples
    --------
    >>> s = enumerate_stages(100, 4, zmin=15)
    >>> len(s), s[0].ratio, s[-1].ratio, (s[-1].sun, s[-1].planet), s.rejected["neighbours"]
    (13, 42/17, 6, (20, 40), 1)
    >>> enumerate_stages(40, 4, zmin=15, zmax=100)
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: no single-row AI stage fits a ring of 40 teeth with 15 <= z <= 100: coaxiality z_ring = z_sun + 2 z_planet leaves no sun and planet of at least 15 teeth each; use a ring of at least 45 teeth or lower zmin
    """
    ring, k, zmin, zmax, ha_value = _limits(ring, satellites, zmin, zmax, ha)
    rejected = {"limits": 0, "coaxiality": 0, "assembly": 0, "neighbours": 0}
    candidates = _coaxial_candidates(ring, k, zmin, zmax, ha_value, rejected)
    found: list[Stage] = []
    for sun, planet, fits_assembly, fits_neighbours in candidates:
        if not fits_assembly:
            rejected["assembly"] += 1
        elif not fits_neighbours:
            rejected["neighbours"] += 1
        else:
            found.append(Stage(stage_ratio(sun, ring), sun, planet, ring, k))
    found.sort()
    result = StageSet(ring, k, zmin, zmax, ha_value, tuple(found), rejected)
    if not found and not allow_empty:
        raise InputError(_why_empty(result, candidates))
    return result


def _limits(ring: Any, satellites: Any, zmin: Any, zmax: Any, ha: Any) -> tuple[int, int, int, int, sp.Rational]:
    """The ring, the satellites, the tooth limits and h_a*, checked."""
    ring = int(as_integer(ring, what="the ring's tooth number", minimum=1))
    if ring > MAX_RING:
        raise InputError(f"the ring has {ring} teeth; the enumeration visits every sun, so at most {MAX_RING} are accepted")
    k = int(as_integer(satellites, what="the number of satellites", minimum=1))
    zmin = int(as_integer(zmin, what="zmin", minimum=1))
    zmax = ring if zmax is None else int(as_integer(zmax, what="zmax", minimum=1))
    ha_value = _tip_height(ha)
    if zmax < zmin:
        raise InputError(f"zmin = {zmin} is larger than zmax = {zmax}; give zmin <= zmax")
    if not zmin <= ring <= zmax:
        raise InputError(f"the ring's {ring} teeth are outside the limits {zmin} <= z <= {zmax}; widen the limits")
    return ring, k, zmin, zmax, ha_value


def _coaxial_candidates(ring: int, k: int, zmin: int, zmax: int, ha: sp.Rational,
                        rejected: dict[str, int]) -> list[tuple[int, int, bool, bool]]:
    """Every sun whose planet is coaxial and within the limits, with whether the stage assembles and its
    neighbours clear (sun, planet, assembly, neighbours); the others counted in ``rejected``."""
    planet_of = _compiled()["planet"]
    candidates: list[tuple[int, int, bool, bool]] = []
    for sun in range(1, ring):
        planet_value = planet_of(sun, ring)
        if not (zmin <= sun <= zmax and zmin <= planet_value <= zmax):
            rejected["limits"] += 1
        elif planet_value.denominator != 1:
            rejected["coaxiality"] += 1
        else:
            planet = int(planet_value)
            candidates.append((sun, planet, assembles(sun, ring, k), neighbours_clear(sun, planet, k, ha)))
    return candidates


def _why_empty(result: StageSet, candidates: Sequence[tuple[int, int, bool, bool]]) -> str:
    ring, k, zmin, zmax = result.ring, result.satellites, result.zmin, result.zmax
    head = f"no single-row AI stage fits a ring of {ring} teeth with {zmin} <= z <= {zmax}"
    if not candidates and result.rejected["coaxiality"] == 0:
        if ring < 3 * zmin:
            return (
                f"{head}: coaxiality z_ring = z_sun + 2 z_planet leaves no sun and planet of at least {zmin} teeth "
                f"each; use a ring of at least {3 * zmin} teeth or lower zmin"
            )
        return f"{head}: no sun and planet within the limits are coaxial with this ring; widen the limits"
    if not candidates:
        return (
            f"{head}: coaxiality needs z_ring - z_sun even, which no sun within the limits gives; widen the limits"
        )
    if not any(n for *_, n in candidates):
        most = max(max_satellites(s, p, result.ha) for s, p, *_ in candidates)
        return (
            f"{head}: {k} satellites cannot fit, the neighbour condition (z_sun + z_planet) sin(pi/k) > "
            f"z_planet + 2 h_a* fails for every coaxial sun (at most {most} fit); use fewer satellites"
        )
    if not any(a for _, _, a, _ in candidates):
        return (
            f"{head} and {k} satellites: no coaxial sun meets the assembly condition (z_sun + z_ring)/{k} whole; "
            "try another ring or satellite count"
        )
    return (
        f"{head} and {k} satellites: every coaxial sun fails the assembly condition (z_sun + z_ring)/{k} whole "
        "or the neighbour condition; try another ring or satellite count"
    )
