"""Derived laws of a two-row train with a stepped helical planet, and its tooth equations.

Every law comes from the engine: the ratio, the assembly condition and coaxiality from
the mechanism model (contact conditions, mesh geometry), the balance condition from the
planet statics (:mod:`symkin.statics`); :func:`tooth_equations` solves them for the
tooth numbers.

    >>> print(ratio_law("II"))
    i_{1H}^{(4)} = 1 - z_2*z_4/(z_1*z_3)
    >>> ratio_function("AI")(18, 80, 20, 108)
    Fraction(25, 1)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cache

import sympy as sp

from symkin import symbols as S
from symkin.errors import UnsupportedError
from symkin.mechanisms.helical.geometry import SCHEME_MESHES, helical_gear
from symkin.mechanisms.helical.train import SCHEMES, _scheme, ratio_function, ratio_law
from symkin.schemes import two_row
from symkin.statics import planet_statics

__all__ = [
    "RATIO", "X", "K", "P", "Q", "DELTA", "LAMBDA", "Z", "M12", "M34", "BETA12", "BETA34", "ALPHA_T12", "ALPHA_T34",
    "ALPHA_TW12", "ALPHA_TW34", "SIN_PI_K", "MU", "NU", "U34", "SCHEMES",
    "ratio_law", "ratio_function", "assembly_condition", "assembly_integers", "working_coaxiality",
    "helical_coaxiality", "working_diameter_ratio", "balance_condition", "HelixAngleSolution",
    "helix_angle_solution", "coaxial_cosine_ratio", "ToothEquations", "tooth_equations",
]

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


# --------------------------------------------------------------------------- derived laws
@cache
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
    mech = two_row(_scheme(scheme), teeth=True)
    turn_H = sp.Integer(1)
    turns_1 = mech.speeds({"H": turn_H, "4": 0})["1"]  # revolutions of gear 1 per carrier revolution
    if sp.simplify(turns_1 - ratio_law(scheme).rhs) != 0:
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
    i = ratio_function(scheme)(z1, z2, z3, z4)
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


@cache
def working_coaxiality(scheme: str) -> sp.Expr:
    """Coaxiality in tooth numbers and delta = d_w2/d_w3, as an expression equal to zero.

    The engine's coaxiality in working pitch radii, with the radii of each mesh in its
    tooth ratio (r_w1 = r_w2 Z1/Z2, r_w4 = r_w3 Z4/Z3) and r_w2 = delta r_w3.

    >>> working_coaxiality("AI")
    delta*z_1*z_3 + delta*z_2*z_3 + z_2*z_3 - z_2*z_4
    """
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


@cache
def helical_coaxiality(scheme: str, shifted: bool = True) -> sp.Eq:
    """Coaxiality of helical meshes: a_w12 = a_w34, from the engine with helical gears.

    The engine's coaxiality of the scheme (where each mesh puts the planet axis), with the
    working pitch radii of helical gears (:func:`symkin.mechanisms.helical.helical_gear`).  With
    ``shifted`` the radii carry the transverse and working transverse pressure angles;
    without, the meshes are unshifted (working = reference cylinders).

    >>> helical_coaxiality("AA", shifted=False)
    Eq(m_n12*z_1/(2*cos(beta_12)) + m_n12*z_2/(2*cos(beta_12)), m_n34*z_3/(2*cos(beta_34)) + m_n34*z_4/(2*cos(beta_34)))
    """
    (coax,) = two_row(_scheme(scheme)).coaxiality
    radii = _helical_radii(scheme, shifted)
    return sp.Eq(sp.expand(coax.lhs.subs(radii)), sp.expand(coax.rhs.subs(radii)), evaluate=False)


@cache
def working_diameter_ratio(shifted: bool = True) -> sp.Expr:
    """d_w2 / d_w3 of helical rims (normal modules, helix angles, pressure angles).

    >>> working_diameter_ratio(shifted=False)
    m_n12*z_2*cos(beta_34)/(m_n34*z_3*cos(beta_12))
    """
    radii = _helical_radii("AI", shifted)
    return sp.simplify(radii[S.radius("2")] / radii[S.radius("3")])


@cache
def balance_condition() -> sp.Eq:
    """Axial balance with the reference helix angles: ``tan(beta12)/tan(beta34) = d2/d3``.

    From :func:`symkin.statics.planet_statics` (``tan(beta_w2)/tan(beta_w3) = r_w2/r_w3``
    on the working cylinders) with the helix angle on a cylinder of radius r_y,
    ``tan(beta_y) = tan(beta) r_y / r`` (one lead per gear).  Scheme-independent.

    >>> balance_condition()
    Eq(tan(beta_12)/tan(beta_34), m_n12*z_2*cos(beta_34)/(m_n34*z_3*cos(beta_12)))
    """
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


@cache
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


@cache
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


@cache
def tooth_equations(scheme: str) -> ToothEquations:
    """Solve ratio, coaxiality, balance and assembly for Z1..Z4 (cached).

    >>> eqs = tooth_equations("AA")
    >>> eqs.chain[Z[2]]
    -z_1*(delta + i_{1H}^{(4)} - 1)/(delta - 1)
    """
    scheme = _scheme(scheme)
    z1, z2, z3, z4 = (Z[n] for n in (1, 2, 3, 4))
    law = ratio_law(scheme).rhs
    asm = assembly_condition(scheme)
    equations = (
        sp.Eq(RATIO, law),
        sp.Eq(X, z2 / z3),
        sp.Eq(working_coaxiality(scheme), 0),
        asm,
    )
    # eliminate one unknown per equation, each linear in it: Z3 from x, Z4 from the
    # ratio, Z1 from assembly, Z2 from coaxiality (roots not simplified by sp.solve: each
    # is factored below, which gives one form whatever form the root comes in)
    (z3_of_z2,) = sp.solve(equations[1].lhs - equations[1].rhs, z3, simplify=False)
    (z4_of_z1,) = sp.solve(sp.numer(sp.together((law - RATIO).subs(z2, X * z3))), z4, simplify=False)
    (z1_of_asm,) = sp.solve(sp.numer(sp.together((asm.lhs - asm.rhs).subs(z2, X * z3))), z1, simplify=False)
    coax = working_coaxiality(scheme).subs({z3: z2 / X, z4: z4_of_z1})
    (z2_of_z1,) = sp.solve(sp.numer(sp.together(coax)), z2, simplify=False)
    chain = {z1: sp.factor(z1_of_asm), z4: sp.factor(z4_of_z1), z2: sp.factor(z2_of_z1), z3: z3_of_z2}
    solution = {z1: chain[z1]}
    solution[z4] = sp.factor(chain[z4].subs(z1, solution[z1]))
    solution[z2] = sp.factor(chain[z2].subs(z1, solution[z1]))
    solution[z3] = sp.factor(chain[z3].subs(z2, solution[z2]))
    for eq in equations:  # the solution satisfies all four conditions (cancelled first: zero decides)
        residual = sp.together((eq.lhs - eq.rhs).subs(solution))
        if sp.cancel(residual) != 0 and sp.simplify(residual) != 0:
            raise UnsupportedError(f"{scheme}: the tooth numbers do not satisfy {eq}")  # pragma: no cover
    return ToothEquations(scheme, equations, solution, chain)

