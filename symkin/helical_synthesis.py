"""Synthesis of two-row planetary trains whose stepped helical planet carries no axial load.

Everything here is derived from the engine and then used:

* :func:`ratio_law`, :func:`assembly_condition`, :func:`working_coaxiality` and
  :func:`helical_coaxiality` come from the mechanism model (contact conditions, mesh
  geometry);
* :func:`balance_condition` comes from the planet statics (:mod:`symkin.statics`),
  restated for reference helix angles;
* :func:`tooth_equations` solves ratio, coaxiality, balance and assembly for the tooth
  numbers, given the ratio i, x = Z2/Z3, k, the assembly integers P, Q and
  delta = d_w2/d_w3;
* :func:`existence_bounds` and :func:`existence_interval` give, for k satellites and a
  diameter ratio delta, the ratios a scheme can realise (ratio, coaxiality and the
  neighbour condition on pitch circles);
* :func:`synthesise` enumerates integer tooth sets for a target ratio, with the helix
  angles that cancel the planet's axial forces for unshifted (zero) meshes, and keeps
  those that are coaxial, can be assembled and leave room between the planets.

    >>> eqs = tooth_equations("AI")
    >>> eqs.chain[Z[1]]
    k*(P + Q*x)/i_{1H}^{(4)}
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import sympy as sp

from . import symbols as S
from .errors import InputError, UnsupportedError
from .helical import SCHEME_MESHES, HelicalTrain, hand_name, helical_gear
from .parsing import as_integer, as_rational, as_real

__all__ = [
    "RATIO",
    "X",
    "K",
    "P",
    "Q",
    "DELTA",
    "LAMBDA",
    "Z",
    "SCHEMES",
    "ratio_law",
    "assembly_condition",
    "assembly_integers",
    "working_coaxiality",
    "helical_coaxiality",
    "balance_condition",
    "helix_angle_solution",
    "coaxial_cosine_ratio",
    "working_diameter_ratio",
    "ToothEquations",
    "tooth_equations",
    "existence_bounds",
    "existence_interval",
    "existence_range",
    "SynthesisRequest",
    "HelicalDesign",
    "SynthesisResult",
    "synthesise",
]

SCHEMES = tuple(SCHEME_MESHES)

#: i_1H^(4): gear 1 drives, carrier H driven, gear 4 fixed.
RATIO = S.ratio_symbol("1", "H", ("4",))
#: x = Z2 / Z3.
X = sp.Symbol("x", positive=True)
#: Number of satellites.
K = sp.Symbol("k", positive=True, integer=True)
#: Assembly integers.
P, Q = sp.Symbol("P", integer=True), sp.Symbol("Q", integer=True)
#: delta = d_w2 / d_w3, the working pitch diameters of the planet's rims.
DELTA = sp.Symbol("delta", positive=True)
#: The paper's module ratio in the coaxiality condition.
LAMBDA = sp.Symbol("lambda", positive=True)
#: Tooth numbers Z[1] .. Z[4] (the engine's z_1 .. z_4).
Z = {n: S.teeth(str(n)) for n in (1, 2, 3, 4)}
#: Normal modules, helix angles, transverse and working transverse pressure angles.
M12, M34 = sp.Symbol("m_n12", positive=True), sp.Symbol("m_n34", positive=True)
BETA12, BETA34 = sp.Symbol("beta_12", positive=True), sp.Symbol("beta_34", positive=True)
ALPHA_T12, ALPHA_T34 = sp.Symbol("alpha_t12", positive=True), sp.Symbol("alpha_t34", positive=True)
ALPHA_TW12, ALPHA_TW34 = sp.Symbol("alpha_tw12", positive=True), sp.Symbol("alpha_tw34", positive=True)
#: sin(pi/k) in the neighbour condition.
SIN_PI_K = sp.sin(sp.pi / K)
_S = sp.Symbol("s", positive=True)  # sin(pi/k) while deriving (positive for k >= 2)


def _scheme(scheme: Any) -> str:
    if not isinstance(scheme, str) or scheme not in SCHEME_MESHES:
        raise InputError(f"unknown scheme {scheme!r}; choose one of {', '.join(SCHEMES)}")
    return scheme


# --------------------------------------------------------------------------- derived laws
@lru_cache(maxsize=None)
def ratio_law(scheme: str) -> sp.Expr:
    """i_1H^(4) in tooth numbers, from the engine's contact conditions.

    >>> ratio_law("II")
    1 - z_2*z_4/(z_1*z_3)
    """
    from .schemes import two_row

    return two_row(_scheme(scheme), teeth=True).ratio("1", "H", fixed="4").rhs


@lru_cache(maxsize=None)
def assembly_condition(scheme: str) -> sp.Eq:
    """The assembly condition for k equally spaced planets: ``Z1 i / k - Q Z2/Z3 = P``.

    Derivation: turn the carrier by 2 pi / k with gear 4 fixed; the engine's speeds give
    gear 1's turn, ``i / k`` of a revolution, so ``Z1 i / k`` of its pitches pass the
    station the planet left.  A planet put there meshes with gear 4 at any whole number
    ``Q`` of rim-3 pitches, which shifts rim 2 by ``Q Z2 / Z3`` of its pitches; the two
    must differ by a whole number ``P`` of pitches.  ``i`` is the symbol ``RATIO``; the
    law :func:`ratio_law` gives its value.

    >>> assembly_condition("AI")
    Eq(-Q*z_2/z_3 + i_{1H}^{(4)}*z_1/k, P)
    """
    from .schemes import two_row

    mech = two_row(_scheme(scheme), teeth=True)
    turn_H = sp.Integer(1)
    turns_1 = mech.speeds({"H": turn_H, "4": 0})["1"]  # revolutions of gear 1 per carrier revolution
    if sp.simplify(turns_1 - ratio_law(scheme)) != 0:
        raise UnsupportedError("the speed of gear 1 per carrier turn is not the ratio i_1H^(4)")
    pitches_1 = Z[1] * RATIO / K  # turns_1 = RATIO, per 1/k of a carrier turn
    return sp.Eq(pitches_1 - Q * Z[2] / Z[3], P)


def assembly_integers(scheme: str, teeth: Sequence[int], satellites: int) -> tuple[int, int] | None:
    """Integers (P, Q) of the assembly condition for a tooth set, or None if it cannot be assembled.

    Q is the smallest non-negative one; every other solution is
    ``(P - n Z2/g, Q + n Z3/g)``, g = gcd(Z2, Z3).

    >>> assembly_integers("AI", (20, 40, 20, 80), 3)   # i = 9: 60*20 + 0*40 = 20*20*9/3
    (60, 0)
    >>> assembly_integers("AI", (20, 40, 20, 80), 7) is None
    True
    """
    z1, z2, z3, z4 = (int(z) for z in teeth)
    i = _ratio_fraction(scheme)(z1, z2, z3, z4)
    # Z1 Z3 i / k = P Z3 + Q Z2: integer, and a multiple of gcd(Z2, Z3)
    m = Fraction(z1 * z3) * i / satellites
    if m.denominator != 1:
        return None
    m_int = m.numerator
    g = math.gcd(z2, z3)
    if m_int % g:
        return None
    z2g, z3g = z2 // g, z3 // g
    q = (m_int // g) * pow(z2g, -1, z3g) % z3g if z3g > 1 else 0
    p, rest = divmod(m_int - q * z2, z3)
    if rest:
        raise UnsupportedError("assembly integers: internal inconsistency")  # pragma: no cover
    return p, q


@lru_cache(maxsize=None)
def _ratio_fraction(scheme: str) -> Callable[..., Fraction]:
    """The engine's ratio law as a function of four integers returning an exact Fraction."""
    law = ratio_law(scheme)
    f = sp.lambdify([Z[1], Z[2], Z[3], Z[4]], law, modules=[{}, "math"])

    def ratio(z1: int, z2: int, z3: int, z4: int) -> Fraction:
        return Fraction(f(Fraction(z1), Fraction(z2), Fraction(z3), Fraction(z4)))

    return ratio


@lru_cache(maxsize=None)
def working_coaxiality(scheme: str) -> sp.Expr:
    """Coaxiality in tooth numbers and delta = d_w2/d_w3, as an expression equal to zero.

    The engine's coaxiality in working pitch radii, with the radii of each mesh in its
    tooth ratio (r_w1 = r_w2 Z1/Z2, r_w4 = r_w3 Z4/Z3) and r_w2 = delta r_w3.

    >>> working_coaxiality("AI")
    delta*z_1*z_3 + delta*z_2*z_3 + z_2*z_3 - z_2*z_4
    """
    from .schemes import two_row

    (coax,) = two_row(_scheme(scheme)).coaxiality
    r1, r2, r3, r4 = (S.radius(str(n)) for n in (1, 2, 3, 4))
    expr = (coax.lhs - coax.rhs).subs({r1: r2 * Z[1] / Z[2], r4: r3 * Z[4] / Z[3]}).subs(r2, DELTA * r3)
    num = sp.numer(sp.together(sp.expand(expr / r3)))
    lead = sp.Poly(num, DELTA, *Z.values()).LC()  # a number: fix the overall sign
    return sp.expand(num if lead > 0 else -num)


def _helical_radii(scheme: str, shifted: bool) -> dict[sp.Symbol, sp.Expr]:
    """The engine's radius symbols r_1..r_4 -> working pitch radii of helical gears."""
    in1, in4 = SCHEME_MESHES[_scheme(scheme)]
    a12 = (ALPHA_T12, ALPHA_TW12) if shifted else (None, None)
    a34 = (ALPHA_T34, ALPHA_TW34) if shifted else (None, None)
    gears = [
        helical_gear("1", Z[1], M12, BETA12, internal=in1, alpha_t=a12[0], alpha_tw=a12[1]),
        helical_gear("2", Z[2], M12, BETA12, alpha_t=a12[0], alpha_tw=a12[1]),
        helical_gear("3", Z[3], M34, BETA34, alpha_t=a34[0], alpha_tw=a34[1]),
        helical_gear("4", Z[4], M34, BETA34, internal=in4, alpha_t=a34[0], alpha_tw=a34[1]),
    ]
    return {S.radius(g.name): g.radius for g in gears}


@lru_cache(maxsize=None)
def helical_coaxiality(scheme: str, shifted: bool = True) -> sp.Eq:
    """Coaxiality of helical meshes: a_w12 = a_w34, from the engine with helical gears.

    The engine's coaxiality of the scheme (where each mesh puts the planet axis), with the
    working pitch radii of helical gears (:func:`symkin.helical.helical_gear`).  With
    ``shifted`` the radii carry the transverse and working transverse pressure angles;
    without, the meshes are unshifted (working = reference cylinders).

    >>> helical_coaxiality("AA", shifted=False)
    Eq(m_n12*z_1/(2*cos(beta_12)) + m_n12*z_2/(2*cos(beta_12)), m_n34*z_3/(2*cos(beta_34)) + m_n34*z_4/(2*cos(beta_34)))
    """
    from .schemes import two_row

    (coax,) = two_row(_scheme(scheme)).coaxiality
    radii = _helical_radii(scheme, shifted)
    return sp.Eq(sp.expand(coax.lhs.subs(radii)), sp.expand(coax.rhs.subs(radii)), evaluate=False)


@lru_cache(maxsize=None)
def working_diameter_ratio(shifted: bool = True) -> sp.Expr:
    """d_w2 / d_w3 of helical rims (normal modules, helix angles, pressure angles).

    >>> working_diameter_ratio(shifted=False)
    m_n12*z_2*cos(beta_34)/(m_n34*z_3*cos(beta_12))
    """
    radii = _helical_radii("AI", shifted)
    return sp.simplify(radii[S.radius("2")] / radii[S.radius("3")])


@lru_cache(maxsize=None)
def balance_condition() -> sp.Eq:
    """Axial balance with the reference helix angles: ``tan(beta12)/tan(beta34) = d2/d3``.

    From :func:`symkin.statics.planet_statics` (``tan(beta_w2)/tan(beta_w3) = r_w2/r_w3``
    on the working cylinders) with the helix angle on a cylinder of radius r_y,
    ``tan(beta_y) = tan(beta) r_y / r`` (one lead per gear).  Scheme-independent.

    >>> balance_condition()
    Eq(tan(beta_12)/tan(beta_34), m_n12*z_2*cos(beta_34)/(m_n34*z_3*cos(beta_12)))
    """
    from .schemes import two_row
    from .statics import planet_statics

    st = planet_statics(two_row("AI"))
    bw2, bw3 = sp.Symbol("beta_w2", positive=True), sp.Symbol("beta_w3", positive=True)
    rw2, rw3 = S.radius("2"), S.radius("3")  # the engine's radii are the working ones
    ref2, ref3 = (helical_gear(g, Z[n], m, b).radius for g, n, m, b in (("2", 2, M12, BETA12), ("3", 3, M34, BETA34)))
    at_reference = {sp.tan(bw2): sp.tan(BETA12) * rw2 / ref2, sp.tan(bw3): sp.tan(BETA34) * rw3 / ref3}
    lhs = st.condition.lhs.subs(at_reference)
    rhs = st.condition.rhs
    rhs_ref = sp.simplify(rhs / (lhs / (sp.tan(BETA12) / sp.tan(BETA34))))
    return sp.Eq(sp.tan(BETA12) / sp.tan(BETA34), rhs_ref, evaluate=False)


MU, NU, U34 = sp.Symbol("mu", positive=True), sp.Symbol("nu", positive=True), sp.Symbol("u", positive=True)


@dataclass(frozen=True)
class HelixAngleSolution:
    """Unshifted helix angles from balance and coaxiality.

    With ``mu = sin(beta12)/sin(beta34)`` (balance) and ``nu = cos(beta12)/cos(beta34)``
    (coaxiality, :func:`coaxial_cosine_ratio`): ``sin2_34`` and ``sin2_12`` are
    sin^2 of the two angles in mu and nu; ``nu2_of_sin2_34`` is nu^2 in mu and
    u = sin^2(beta34).
    """

    mu: sp.Expr
    sin2_34: sp.Expr
    sin2_12: sp.Expr
    nu2_of_sin2_34: sp.Expr


@lru_cache(maxsize=None)
def helix_angle_solution() -> HelixAngleSolution:
    """Solve the balance and (unshifted) coaxiality conditions for the helix angles.

    >>> sol = helix_angle_solution()
    >>> sol.mu
    m_n12*z_2/(m_n34*z_3)
    >>> sol.sin2_34
    -(nu - 1)*(nu + 1)/((mu - nu)*(mu + nu))
    """
    bal = balance_condition()
    # tan(b12)/tan(b34) * cos(b12)/cos(b34) = sin(b12)/sin(b34)
    factor = sp.cos(BETA12) / sp.cos(BETA34)
    if sp.simplify(bal.lhs * factor - sp.sin(BETA12) / sp.sin(BETA34)) != 0:
        raise UnsupportedError("the balance condition is not a ratio of tangents")  # pragma: no cover
    mu = sp.simplify(bal.rhs * factor)
    # sin b12 = mu sin b34, cos b12 = nu cos b34, and sin^2 + cos^2 = 1 for both angles
    v12 = sp.Symbol("v", positive=True)
    sol = sp.solve([v12 - MU**2 * U34, (1 - v12) - NU**2 * (1 - U34)], [v12, U34], dict=True)[0]
    (nu2,) = sp.solve((1 - MU**2 * U34) - NU**2 * (1 - U34), NU**2)
    return HelixAngleSolution(mu, sp.factor(sol[U34]), sp.factor(sol[v12]), sp.factor(nu2))


@lru_cache(maxsize=None)
def coaxial_cosine_ratio(scheme: str) -> sp.Expr:
    """``cos(beta12)/cos(beta34)`` that makes unshifted helical meshes coaxial.

    >>> coaxial_cosine_ratio("II")
    -m_n12*(z_1 - z_2)/(m_n34*(z_3 - z_4))
    """
    coax = helical_coaxiality(scheme, shifted=False)
    c12 = sp.Symbol("c_12", positive=True)
    (c12_solved,) = sp.solve((coax.lhs - coax.rhs).subs(sp.cos(BETA12), c12), c12)
    num, den = sp.fraction(sp.factor(c12_solved / sp.cos(BETA34)))
    if sp.Poly(den, *Z.values()).LC() < 0:
        num, den = -num, -den
    return num / den


# --------------------------------------------------------------------------- tooth equations
@dataclass(frozen=True)
class ToothEquations:
    """Tooth numbers from the ratio, x = Z2/Z3, k, P, Q and delta = d_w2/d_w3.

    Attributes
    ----------
    scheme : str
    equations : tuple of sympy.Eq
        What was solved: the ratio law, x = Z2/Z3, coaxiality in working radii (delta
        carries the helix and pressure angles, and the balance fixes it:
        tan(beta_w12)/tan(beta_w34) = delta), and the assembly condition.
    solution : dict
        Z1..Z4 in terms of i, x, k, P, Q, delta.
    chain : dict
        The same as the paper writes it, each number in terms of the one before:
        Z1 from assembly, Z4 from Z1 (ratio), Z2 from Z1 (coaxiality), Z3 from Z2.
    """

    scheme: str
    equations: tuple[sp.Eq, ...]
    solution: dict[sp.Symbol, sp.Expr]
    chain: dict[sp.Symbol, sp.Expr]


@lru_cache(maxsize=None)
def tooth_equations(scheme: str) -> ToothEquations:
    """Solve ratio, coaxiality, balance and assembly for Z1..Z4 (cached).

    >>> eqs = tooth_equations("AA")
    >>> eqs.chain[Z[2]]
    -z_1*(delta + i_{1H}^{(4)} - 1)/(delta - 1)
    """
    scheme = _scheme(scheme)
    z1, z2, z3, z4 = (Z[n] for n in (1, 2, 3, 4))
    law = ratio_law(scheme)
    asm = assembly_condition(scheme)
    equations = (
        sp.Eq(RATIO, law),
        sp.Eq(X, z2 / z3),
        sp.Eq(working_coaxiality(scheme), 0),
        asm,
    )
    # eliminate one unknown per equation, each linear in it: Z3 from x, Z4 from the
    # ratio, Z1 from assembly, Z2 from coaxiality
    (z3_of_z2,) = sp.solve(equations[1].lhs - equations[1].rhs, z3)
    (z4_of_z1,) = sp.solve(sp.numer(sp.together((law - RATIO).subs(z2, X * z3))), z4)
    (z1_of_asm,) = sp.solve(sp.numer(sp.together((asm.lhs - asm.rhs).subs(z2, X * z3))), z1)
    coax = working_coaxiality(scheme).subs({z3: z2 / X, z4: z4_of_z1})
    (z2_of_z1,) = sp.solve(sp.numer(sp.together(coax)), z2)
    chain = {z1: sp.factor(z1_of_asm), z4: sp.factor(z4_of_z1), z2: sp.factor(z2_of_z1), z3: z3_of_z2}
    solution = {z1: chain[z1]}
    solution[z4] = sp.factor(chain[z4].subs(z1, solution[z1]))
    solution[z2] = sp.factor(chain[z2].subs(z1, solution[z1]))
    solution[z3] = sp.factor(chain[z3].subs(z2, solution[z2]))
    for eq in equations:  # the solution satisfies all four conditions
        if sp.simplify(sp.together((eq.lhs - eq.rhs).subs(solution))) != 0:
            raise UnsupportedError(f"{scheme}: the tooth numbers do not satisfy {eq}")  # pragma: no cover
    return ToothEquations(scheme, equations, solution, chain)


# --------------------------------------------------------------------------- existence regions
@dataclass(frozen=True)
class _RegionSetup:
    ratio: sp.Expr  # i as a function of r_1 (r_3 = 1, r_2 = delta)
    constraints: tuple[tuple[str, sp.Expr], ...]  # expressions in r_1 that must be positive
    neighbour: tuple[sp.Expr, sp.Expr]  # arm, and the larger rim is max(delta, 1)


R1 = S.radius("1")


@lru_cache(maxsize=None)
def _region_setup(scheme: str) -> _RegionSetup:
    from .schemes import two_row

    mech = two_row(_scheme(scheme))
    r2, r3, r4 = (S.radius(str(n)) for n in (2, 3, 4))
    (coax,) = mech.coaxiality
    (r4_solved,) = sp.solve(coax, r4)
    subs = {r4: r4_solved}
    scale = {r2: DELTA, r3: sp.Integer(1)}
    ratio = sp.cancel(mech.ratio("1", "H", fixed="4").rhs.subs(subs).subs(scale))
    arm = sp.expand(mech.arm("23").subs(subs).subs(scale))
    constraints = [("r_4 > 0", sp.expand(r4_solved.subs(scale))), ("r_1 > 0", R1)]
    for mesh in mech.meshes:  # an internal gear is larger than the gear inside it
        constraints.append((f"centre distance {mesh.a}-{mesh.b} > 0",
                            sp.expand(mech.mesh_geometry(mesh).centre_distance.subs(subs).subs(scale))))
    return _RegionSetup(ratio, tuple(constraints), (arm, sp.Max(DELTA, 1)))


def _lower_bounds(setup: _RegionSetup, larger_rim: sp.Expr, sin_pi_k: sp.Expr) -> list[tuple[str, sp.Expr]]:
    """Each constraint a r1 + b > 0 as a lower bound on r1 (a > 0 in every scheme here)."""
    arm, _ = setup.neighbour
    items = list(setup.constraints) + [("neighbour", arm * sin_pi_k - larger_rim)]
    bounds = []
    for name, expr in items:
        a, b = sp.Poly(expr, R1).all_coeffs() if sp.Poly(expr, R1).degree() == 1 else (0, expr)
        if a == 0:
            continue  # no bound on r1 (a condition on delta alone, checked by the caller)
        if not (sp.sympify(a).is_positive):
            raise UnsupportedError(f"constraint {name} bounds r_1 from above; existence regions expect lower bounds")
        bounds.append((name, sp.cancel(-b / a)))
    return bounds


@dataclass(frozen=True)
class ExistenceBounds:
    """The existence region of a scheme for one case of delta = d_w2/d_w3.

    ``lower < i < upper`` with i = i_1H^(4); ``binding`` names the constraint that ends
    the range (the other end is the limit of ever larger central gears, r_1 -> oo).
    """

    scheme: str
    case: str  # "delta < 1" or "delta > 1"
    lower: sp.Expr
    upper: sp.Expr
    binding: str


_SAMPLES = {  # delta values and satellite counts on which the binding constraint is decided and verified
    "delta < 1": [sp.Rational(n, 20) for n in (1, 3, 7, 10, 13, 17, 19)],
    "delta > 1": [sp.Rational(n, 10) for n in (11, 13, 17, 25, 40, 90)],
}


@lru_cache(maxsize=None)
def _numeric(expr: sp.Expr) -> Callable[[float, float, int], float]:
    return sp.lambdify([DELTA, _S, K], expr, "numpy")


@lru_cache(maxsize=None)
def existence_bounds(scheme: str) -> tuple[ExistenceBounds, ExistenceBounds]:
    """Closed-form existence regions (the paper's Table 1) for delta < 1 and delta > 1.

    Over the free size r_1 of gear 1 (r_3 = 1, r_2 = delta, r_4 from coaxiality), the ratio
    is monotone (a + b / r_1); its range runs from the limit r_1 -> oo to its value where
    the first constraint binds: positive radii, internal gears larger than their mates,
    and the neighbour condition ``a_w sin(pi/k) > max(r_w2, r_w3)`` on pitch circles (the
    paper's choice, as for unshifted spur gears).  The binding constraint is picked on
    sample values of delta and k and verified on all of them.

    >>> lo_hi = existence_bounds("AI")[0]
    >>> lo_hi.lower, lo_hi.upper
    (delta + 1, -(delta + 1)/(delta*sin(pi/k) - 1))
    """
    setup = _region_setup(_scheme(scheme))
    r_times_i = sp.expand(sp.cancel(setup.ratio * R1))
    if sp.diff(r_times_i, R1, 2) != 0:
        raise UnsupportedError("the ratio is not of the form a + b / r_1; cannot bound it")
    limit_inf = sp.limit(setup.ratio, R1, sp.oo)
    out = []
    for case, larger in (("delta < 1", sp.Integer(1)), ("delta > 1", DELTA)):
        bounds = _lower_bounds(setup, larger, _S)
        samples = [(d, kk) for d in _SAMPLES[case] for kk in (2, 3, 4, 5, 6, 8, 12)]

        def value(expr: sp.Expr, d: sp.Expr, kk: int) -> float:
            f = _numeric(expr)
            with np.errstate(divide="ignore", invalid="ignore"):
                v = float(f(float(d), math.sin(math.pi / kk), kk))
            return v if math.isfinite(v) else math.inf  # k = 2 may leave a range unbounded

        best = {(d, kk): max(value(b, d, kk) for _, b in bounds) for d, kk in samples}
        always = [nb for nb in bounds if all(value(nb[1], d, kk) >= best[d, kk] - 1e-12 for d, kk in samples)]
        if not always:
            raise UnsupportedError(f"{scheme}, {case}: the binding constraint changes with delta and k")
        binding = always[-1]  # the neighbour condition when it ties with another
        at_bound = sp.factor(sp.cancel(setup.ratio.subs(R1, binding[1]))).subs(_S, SIN_PI_K)
        lower, upper = limit_inf, at_bound
        d0, k0 = _SAMPLES[case][0], 3
        if value(lower, d0, k0) > value(upper, d0, k0):
            lower, upper = upper, lower
        out.append(ExistenceBounds(scheme, case, sp.factor(lower), upper if upper == at_bound else sp.factor(upper), binding[0]))
    return out[0], out[1]


def existence_interval(scheme: str, satellites: int, delta: Any) -> tuple[sp.Expr, sp.Expr] | None:
    """The open interval of i_1H^(4) a scheme can realise for k satellites and d_w2/d_w3 = delta.

    Evaluated exactly from the constraints (not from the closed form), so it also covers
    delta = 1 and k = 1.  ``None`` when the interval is empty.

    >>> existence_interval("II", 3, sp.Rational(1, 2))
    ((8 - 2*sqrt(3))/13, 1/2)
    >>> existence_interval("AA", 3, 1) is None
    True
    """
    scheme = _scheme(scheme)
    d = as_real(delta, what="d_w2/d_w3")  # a float is its decimal, never a guessed surd
    if not d.is_positive:
        raise InputError(f"d_w2/d_w3 must be a positive number, got {delta!r}")
    k = _whole(satellites, "the number of satellites")
    if k < 1:
        raise InputError(f"the number of satellites must be a positive whole number, got {satellites!r}")
    setup = _region_setup(scheme)
    subs = {DELTA: d}
    larger = sp.Max(d, 1)
    s = sp.sin(sp.pi / k) if k > 1 else None
    arm, _ = setup.neighbour
    items = list(setup.constraints)
    if s is not None:
        items.append(("neighbour", arm * s - larger))
    lower = None
    for _name, expr in items:
        e = sp.expand(expr.subs(subs))
        poly = sp.Poly(e, R1)
        a, b = poly.all_coeffs() if poly.degree() == 1 else (sp.Integer(0), e)
        if a == 0:
            if not (b > 0):
                return None
            continue
        bound = -b / a
        lower = bound if lower is None or bool(bound > lower) else lower
    num, den = sp.fraction(sp.cancel(setup.ratio.subs(subs)))
    pn, pd = sp.Poly(num, R1), sp.Poly(den, R1)
    if pn.is_zero:  # i = 0 for every size: the carrier cannot be driven
        return None
    if pn.degree() != pd.degree():
        raise UnsupportedError("the ratio is not of the form a + b / r_1")  # pragma: no cover
    at_infinity = sp.cancel(pn.LC() / pd.LC())  # large central gears
    den_at = pd.eval(lower)
    if den_at == 0:  # a pole at the bound (k = 2): the range is unbounded there
        at_bound = sp.oo * sp.sign(pn.eval(lower) * pd.diff(R1).eval(lower))
    else:
        at_bound = sp.radsimp(sp.cancel(pn.eval(lower) / den_at))
    ends = [at_infinity, at_bound]
    lo, hi = sorted(ends, key=_as_float)
    if sp.simplify(hi - lo) == 0:
        return None
    return lo, hi


def _as_float(v: sp.Expr) -> float:
    if v == sp.oo:
        return math.inf
    if v == -sp.oo:
        return -math.inf
    return float(v)


@lru_cache(maxsize=None)
def existence_range(scheme: str) -> tuple[tuple[sp.Expr, sp.Expr], ...]:
    """The ratios a scheme can realise for some delta: the union of its existence regions.

    Each case's interval moves continuously with delta, so its union over delta is the
    open interval between the extreme ends (the limits at the ends of the delta range and
    any stationary point in between).  Evaluated for k = 3, 4, 6, 12 and merged; fewer
    satellites only widen each region within the same union.

    >>> existence_range("AI")
    ((1, oo),)
    >>> existence_range("AA")
    ((-oo, 0), (0, 1))
    """
    spans = []
    for b, (d_lo, d_hi) in zip(existence_bounds(_scheme(scheme)), ((0, 1), (1, sp.oo))):
        ends = []
        for expr in (b.lower, b.upper):
            for kk in (3, 4, 6, 12):
                e = sp.nsimplify(expr.subs(K, kk))
                ends += [sp.limit(e, DELTA, d_lo, "+"), sp.limit(e, DELTA, d_hi, "-")]
                crit = [c for c in sp.solve(sp.diff(e, DELTA), DELTA) if c.is_real and d_lo < c < d_hi]
                ends += [e.subs(DELTA, c) for c in crit]
        spans.append((min(ends, key=_as_float), max(ends, key=_as_float)))
    spans.sort(key=lambda ab: _as_float(ab[0]))
    merged: list[tuple[sp.Expr, sp.Expr]] = []
    for a, b in spans:  # regions that only touch at an excluded point stay apart
        if merged and _as_float(a) < _as_float(merged[-1][1]):
            merged[-1] = (merged[-1][0], max(b, merged[-1][1], key=_as_float))
        else:
            merged.append((a, b))
    return tuple(merged)


# --------------------------------------------------------------------------- synthesis
def _fraction(value: Any, what: str) -> Fraction:
    """An exact number from a user value (text is parsed safely, never evaluated)."""
    r = as_rational(value, what=what)
    return Fraction(int(r.p), int(r.q))


def _whole(value: Any, what: str) -> int:
    return int(as_integer(value, what=what))


@dataclass(frozen=True)
class SynthesisRequest:
    """What a designer asks for; every field is checked on construction.

    Parameters
    ----------
    scheme : {"AI", "AA", "II"}
    ratio : number
        Target i_1H^(4) = omega_1 / omega_H with gear 4 fixed (exact: "1/50" is 1/50).
    tolerance : number
        Admissible relative ratio error |i - target| / |target| (0.02 = 2 %).
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
        put("ratio", _fraction(self.ratio, "the target ratio"))
        if self.ratio == 0:
            raise InputError("the target ratio i_1H^(4) must not be 0 (the carrier would not turn); give a non-zero ratio")
        put("tolerance", _fraction(self.tolerance, "the ratio tolerance"))
        if self.tolerance < 0:
            raise InputError(f"the ratio tolerance must be >= 0 (a relative error), got {self.tolerance}")
        k = _whole(self.satellites, "the number of satellites")
        if k < 1:
            raise InputError(f"the number of satellites must be at least 1, got {k}")
        put("satellites", k)
        try:
            m12, m34 = self.normal_modules
        except (TypeError, ValueError):
            raise InputError("give two normal modules, m_n12 and m_n34") from None
        mods = (_fraction(m12, "the normal module m_n12"), _fraction(m34, "the normal module m_n34"))
        for name, m in zip(("m_n12", "m_n34"), mods):
            if m <= 0:
                raise InputError(f"the normal module {name} must be positive, got {m}")
        put("normal_modules", mods)
        lo, hi = _fraction(self.beta_min_deg, "beta-min"), _fraction(self.beta_max_deg, "beta-max")
        for name, b in (("beta-min", lo), ("beta-max", hi)):
            if not 0 < b < 45:
                raise InputError(f"{name} must lie strictly between 0 and 45 degrees, got {float(b):g}")
        if lo >= hi:
            raise InputError(f"beta-min ({float(lo):g} deg) must be less than beta-max ({float(hi):g} deg): these limits exclude every design")
        put("beta_min_deg", lo)
        put("beta_max_deg", hi)
        zmin, zmax = _whole(self.teeth_min, "zmin"), _whole(self.teeth_max, "zmax")
        if zmin < 1:
            raise InputError(f"zmin must be at least 1, got {zmin}")
        if zmin > zmax:
            raise InputError(f"zmin ({zmin}) is larger than zmax ({zmax}): these limits exclude every design")
        if zmax - zmin + 1 > self.MAX_SPAN:
            raise InputError(
                f"zmin..zmax spans {zmax - zmin + 1} tooth numbers; at most {self.MAX_SPAN} are searched, narrow the range"
            )
        put("teeth_min", zmin)
        put("teeth_max", zmax)
        a_n = _fraction(self.alpha_n_deg, "the normal pressure angle")
        if not 0 < a_n < 45:
            raise InputError(f"the normal pressure angle must lie between 0 and 45 degrees, got {float(a_n):g}")
        put("alpha_n_deg", a_n)
        ha = _fraction(self.addendum, "the addendum coefficient")
        if ha < 0:
            raise InputError(f"the addendum coefficient must be >= 0, got {ha}")
        put("addendum", ha)
        dmin = _whole(self.min_ring_difference, "the least ring-planet tooth difference")
        if dmin < 1:
            raise InputError(f"the least ring-planet tooth difference must be at least 1, got {dmin}")
        put("min_ring_difference", dmin)
        if self.top is not None:
            top = _whole(self.top, "top")
            if top < 1:
                raise InputError(f"top must be at least 1, got {top}")
            put("top", top)

    @property
    def ratio_window(self) -> tuple[Fraction, Fraction]:
        """The admissible ratios, exact: target -+ tolerance |target|."""
        half = self.tolerance * abs(self.ratio)
        return self.ratio - half, self.ratio + half

    def to_json(self) -> dict[str, Any]:
        return {
            "scheme": self.scheme,
            "ratio": str(self.ratio),
            "tolerance": str(self.tolerance),
            "satellites": self.satellites,
            "normal_modules": [str(m) for m in self.normal_modules],
            "beta_deg": [float(self.beta_min_deg), float(self.beta_max_deg)],
            "teeth": [self.teeth_min, self.teeth_max],
            "alpha_n_deg": float(self.alpha_n_deg),
            "addendum": float(self.addendum),
            "min_ring_difference": self.min_ring_difference,
            "top": self.top,
        }


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
        |ratio - target| / |target|, exact.
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
        return self.train.teeth

    @property
    def betas_deg(self) -> tuple[float, float]:
        return math.degrees(self.train.betas[0]), math.degrees(self.train.betas[1])

    @property
    def centre_distance(self) -> float:
        return self.train.centre_distances[0]

    @property
    def envelope_diameter(self) -> float:
        return self.train.envelope_diameter

    def to_json(self) -> dict[str, Any]:
        t = self.train
        return {
            "teeth": list(t.teeth),
            "ratio": {"exact": str(self.ratio), "float": float(self.ratio)},
            "relative_error": {"exact": str(self.relative_error), "float": float(self.relative_error)},
            "beta12_deg": self.betas_deg[0],
            "beta34_deg": self.betas_deg[1],
            "helix_free": self.helix_free,
            "hands": [hand_name(h) for h in t.hands],
            "P": self.assembly[0],
            "Q": self.assembly[1],
            "centre_distance": self.centre_distance,
            "d_w2/d_w3": t.working_diameter_ratio,
            "envelope_diameter": self.envelope_diameter,
            "neighbour_margin": t.neighbour_margin if math.isfinite(t.neighbour_margin) else None,
        }


@dataclass(frozen=True)
class SynthesisResult:
    """The designs found, best first, and how many tooth sets passed each condition.

    ``reason`` says why nothing was found (empty when designs were found).
    """

    request: SynthesisRequest
    designs: tuple[HelicalDesign, ...]
    found: int
    stages: tuple[tuple[str, int], ...]
    reason: str
    seconds: float

    def to_json(self) -> dict[str, Any]:
        return {
            "request": self.request.to_json(),
            "found": self.found,
            "listed": len(self.designs),
            "stages": [{"condition": name, "tooth_sets": n} for name, n in self.stages],
            "reason": self.reason,
            "designs": [d.to_json() for d in self.designs],
        }


@dataclass(frozen=True)
class _Compiled:
    """Derived laws compiled for the search (NumPy for the sieve, Fractions for exact checks)."""

    ratio: Callable[..., Fraction]
    z4_of_ratio: Callable[..., Any]
    z4_of_nu: Callable[..., Any]
    mu: Callable[..., Any]
    nu: Callable[..., Any]
    sin2_34: Callable[..., Any]
    nu2_of_sin2_34: Callable[..., Any]
    internal1: bool
    internal4: bool


@lru_cache(maxsize=None)
def _compiled(scheme: str) -> _Compiled:
    z1, z2, z3, z4 = (Z[n] for n in (1, 2, 3, 4))
    law = ratio_law(scheme)
    (z4_of_ratio,) = sp.solve(sp.Eq(law, RATIO), z4)
    nu = coaxial_cosine_ratio(scheme)
    (z4_of_nu,) = sp.solve(sp.Eq(nu, NU), z4)
    sol = helix_angle_solution()
    exact = [{}, "math"]
    in1, in4 = SCHEME_MESHES[scheme]
    return _Compiled(
        ratio=_ratio_fraction(scheme),
        z4_of_ratio=sp.lambdify([RATIO, z1, z2, z3], z4_of_ratio, "numpy"),
        z4_of_nu=sp.lambdify([NU, M12, M34, z1, z2, z3], z4_of_nu, "numpy"),
        mu=sp.lambdify([M12, M34, z2, z3], sol.mu, exact),
        nu=sp.lambdify([M12, M34, z1, z2, z3, z4], nu, exact),
        sin2_34=sp.lambdify([MU, NU], sol.sin2_34, exact),
        nu2_of_sin2_34=sp.lambdify([MU, U34], sol.nu2_of_sin2_34, "numpy"),
        internal1=in1,
        internal4=in4,
    )


def _nearest_region(scheme: str, ratio: Fraction) -> str:
    spans = existence_range(scheme)
    text = " or ".join(f"{lo} < i < {hi}" for lo, hi in spans)
    best = None
    for lo, hi in spans:
        for end in (lo, hi):
            if end.is_finite:
                d = abs(float(end) - float(ratio))
                if best is None or d < best[0]:
                    best = (d, end)
    others = [s for s in SCHEMES if s != scheme and any(_as_float(lo) < float(ratio) < _as_float(hi) for lo, hi in existence_range(s))]
    where = f"; scheme{'s' if len(others) > 1 else ''} {' and '.join(others)} realise{'s' if len(others) == 1 else ''} it" if others else ""
    return (
        f"the target ratio i_1H^(4) = {ratio} lies in no existence region of scheme {scheme} ({text}); "
        f"the nearest is its end i = {best[1]}{where}"
    )


def synthesise(request: SynthesisRequest | None = None, *, progress: Callable[[int, int], None] | None = None,
               **kwargs: Any) -> SynthesisResult:
    """Integer tooth sets and balancing helix angles for a target ratio.

    For every tooth set with Z in [teeth_min, teeth_max]: the ratio must lie within the
    tolerance; both meshes unshifted, the helix angles are those that cancel the planet's
    axial forces (equal leads) and make the two centre distances equal
    (:func:`helix_angle_solution`), and both must lie within the limits; the set must be
    assemblable with k satellites (:func:`assembly_integers`); neighbouring planets' tip
    circles must clear (``2 a_w sin(pi/k) > max(d_a2, d_a3)``); internal gears must have
    at least ``min_ring_difference`` more teeth than their rims.  Designs are ranked by
    ratio error, then by envelope diameter.

    A NumPy sieve bounds Z4 for each (Z1, Z2, Z3) from the ratio window and the helix
    limits (each bound is monotone in the parameter it comes from); every survivor is then
    checked exactly (integers, Fractions).

    Parameters
    ----------
    request : SynthesisRequest, optional
        Or give its fields as keyword arguments.
    progress : callable(done, total), optional
        Called after each value of Z2.

    Raises
    ------
    InputError
        Bad input, or a target ratio in no existence region of the scheme.

    Examples
    --------
    >>> res = synthesise(scheme="AI", ratio=12, tolerance="0.01", satellites=3, normal_modules=(2, "2.5"),
    ...                  teeth_min=17, teeth_max=80, top=3)
    >>> res.found, res.designs[0].teeth, [round(b, 3) for b in res.designs[0].betas_deg]
    (14, (17, 51, 21, 77), [15.905, 8.109])
    """
    if request is None:
        request = SynthesisRequest(**kwargs)
    elif kwargs:
        raise InputError("give either a SynthesisRequest or its fields, not both")
    start = time.perf_counter()
    req = request
    scheme = req.scheme
    if not any(_as_float(lo) < float(req.ratio) < _as_float(hi) for lo, hi in existence_range(scheme)):
        raise InputError(_nearest_region(scheme, req.ratio))
    c = _compiled(scheme)
    m12, m34 = req.normal_modules
    m12f, m34f = float(m12), float(m34)
    i_lo, i_hi = req.ratio_window
    s_min, s_max = math.sin(math.radians(req.beta_min_deg)), math.sin(math.radians(req.beta_max_deg))
    u_min, u_max = s_min**2, s_max**2
    k, dmin = req.satellites, req.min_ring_difference
    zmin, zmax = req.teeth_min, req.teeth_max
    teeth = np.arange(zmin, zmax + 1, dtype=float)
    z1c, z3r = teeth[:, None], teeth[None, :]
    eps = 1e-9
    alpha_n = math.radians(req.alpha_n_deg)
    # "ratio window" is counted by the sieve; the others by the exact checks
    counts = dict.fromkeys(("ratio window", "ratio", "helix", "assembly", "neighbour"), 0)
    records: list[tuple] = []
    total = len(teeth)
    for n2, z2 in enumerate(teeth):
        z2i = int(z2)
        col_ok = z1c >= z2 + dmin if c.internal1 else np.ones_like(z1c, dtype=bool)
        # Z4 from the ratio window (linear in i)
        with np.errstate(divide="ignore", invalid="ignore"):
            za, zb = c.z4_of_ratio(float(i_lo), z1c, z2, z3r), c.z4_of_ratio(float(i_hi), z1c, z2, z3r)
        r_lo, r_hi = np.minimum(za, zb), np.maximum(za, zb)
        floor4 = np.maximum(zmin, z3r + dmin) if c.internal4 else np.full_like(z3r, zmin)
        lo_r = np.ceil(np.maximum(r_lo * (1 - eps) - eps, floor4))
        hi_r = np.floor(np.minimum(r_hi * (1 + eps) + eps, zmax))
        in_window = col_ok & (lo_r <= hi_r)
        counts["ratio window"] += int(np.where(in_window, hi_r - lo_r + 1, 0).sum())
        # helix limits -> sin(beta34) interval -> nu interval -> Z4 interval
        mu = m12f * z2 / (m34f * z3r)
        s_lo, s_hi = np.maximum(s_min, s_min / mu), np.minimum(s_max, s_max / mu)
        row_ok = s_lo <= s_hi * (1 + eps)
        with np.errstate(divide="ignore", invalid="ignore"):
            nu2a, nu2b = c.nu2_of_sin2_34(mu, s_lo**2), c.nu2_of_sin2_34(mu, s_hi**2)
            nu_lo, nu_hi = np.sqrt(np.minimum(nu2a, nu2b)), np.sqrt(np.maximum(nu2a, nu2b))
            ya, yb = c.z4_of_nu(nu_lo, m12f, m34f, z1c, z2, z3r), c.z4_of_nu(nu_hi, m12f, m34f, z1c, z2, z3r)
        h_lo, h_hi = np.minimum(ya, yb), np.maximum(ya, yb)
        lo4 = np.maximum(lo_r, np.ceil(h_lo * (1 - eps) - eps))
        hi4 = np.minimum(hi_r, np.floor(h_hi * (1 + eps) + eps))
        cand = in_window & row_ok & (lo4 <= hi4)
        for a, b in zip(*np.nonzero(cand)):
            z1i, z3i = int(teeth[a]), int(teeth[b])
            for z4i in range(int(lo4[a, b]), int(hi4[a, b]) + 1):
                rec = _check_candidate(req, c, (z1i, z2i, z3i, z4i), counts, u_min, u_max, alpha_n)
                if rec is not None:
                    records.append(rec)
        if progress is not None:
            progress(n2 + 1, total)
    records.sort(key=lambda r: (r[0], r[1], r[2]))
    listed = records if req.top is None else records[: req.top]
    designs = tuple(_design(req, r, alpha_n) for r in listed)
    ring = f" (internal gears >= {dmin} teeth more than their rims)" if c.internal1 or c.internal4 else ""
    stages = (
        ("ratio within tolerance" + ring, counts["ratio window"]),
        ("and balancing coaxial helix angles within limits", counts["helix"]),
        (f"and assembly with k = {k} satellites", counts["assembly"]),
        ("and neighbouring planets clear", counts["neighbour"]),
    )
    reason = "" if records else _empty_reason(req, counts)
    return SynthesisResult(req, designs, len(records), stages, reason, time.perf_counter() - start)


def _check_candidate(req: SynthesisRequest, c: _Compiled, teeth: tuple[int, int, int, int], counts: dict[str, int],
                     u_min: float, u_max: float, alpha_n: float) -> tuple | None:
    z1, z2, z3, z4 = teeth
    ratio = c.ratio(z1, z2, z3, z4)
    error = abs(ratio - req.ratio) / abs(req.ratio)
    if error > req.tolerance:
        return None
    counts["ratio"] += 1
    m12, m34 = req.normal_modules
    F = Fraction
    mu = F(c.mu(m12, m34, F(z2), F(z3)))
    nu = F(c.nu(m12, m34, F(z1), F(z2), F(z3), F(z4)))
    free = False
    if mu == 1 and nu == 1:  # equal leads and centre distances at any common helix angle
        u, free = F(repr(u_min)), True
    elif mu == nu or nu <= 0:
        return None
    else:
        u = F(c.sin2_34(mu, nu))
    v = mu * mu * u
    if not (0 < u < 1 and 0 < v < 1):
        return None
    uf, vf = float(u), float(v)
    if not (u_min <= uf <= u_max and u_min <= vf <= u_max):
        return None
    counts["helix"] += 1
    pq = assembly_integers(req.scheme, teeth, req.satellites)
    if pq is None:
        return None
    counts["assembly"] += 1
    b12, b34 = math.asin(math.sqrt(vf)), math.asin(math.sqrt(uf))
    train = HelicalTrain(req.scheme, teeth, req.normal_modules, (b12, b34), satellites=req.satellites,
                         alpha_n=alpha_n, addendum=float(req.addendum))
    if not train.neighbour_margin > 0:
        return None
    counts["neighbour"] += 1
    return (error, train.envelope_diameter, teeth, b12, b34, pq, ratio, free)


def _design(req: SynthesisRequest, rec: tuple, alpha_n: float) -> HelicalDesign:
    error, _, teeth, b12, b34, pq, ratio, free = rec
    train = HelicalTrain(req.scheme, teeth, req.normal_modules, (b12, b34), satellites=req.satellites,
                         alpha_n=alpha_n, addendum=float(req.addendum))
    return HelicalDesign(train, ratio, error, pq, free)


def _empty_reason(req: SynthesisRequest, counts: Mapping[str, int]) -> str:
    lo, hi = req.ratio_window
    if counts["ratio window"] == 0:
        return (
            f"no tooth set with every Z in [{req.teeth_min}, {req.teeth_max}] gives i_1H^(4) in [{lo}, {hi}] "
            f"for scheme {req.scheme}; widen the tolerance or the tooth limits"
        )
    if counts["helix"] == 0:
        return (
            f"{counts['ratio window']} tooth sets give the ratio, but for none are the helix angles that balance the axial "
            f"forces and make unshifted meshes coaxial within [{float(req.beta_min_deg):g}, {float(req.beta_max_deg):g}] "
            f"degrees with m_n12 = {req.normal_modules[0]}, m_n34 = {req.normal_modules[1]}; widen the helix-angle "
            "limits or change the module ratio"
        )
    if counts["assembly"] == 0:
        return (
            f"{counts['helix']} tooth sets have the ratio and balancing coaxial helix angles, but none can be "
            f"assembled with k = {req.satellites} equally spaced satellites; try another k"
        )
    return (
        f"{counts['assembly']} tooth sets have the ratio, balancing helix angles and assemble, but in none do "
        f"{req.satellites} planets fit side by side (neighbour condition); use fewer satellites or other limits"
    )
