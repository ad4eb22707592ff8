"""Existence regions: the ratios a scheme can realise for k satellites and d_w2/d_w3.

Ratio, coaxiality and the neighbour condition on pitch circles, over the free size of
gear 1 (the 2010 paper's Table 1, derived).

    >>> existence_range("AI")
    ((1, oo),)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError, UnsupportedError
from symkin.mechanisms.helical.balanced.conditions import (
    _S,
    DELTA,
    SIN_PI_K,
    K,
    _scheme,
)
from symkin.numeric import NumericFunction, compile
from symkin.schemes import two_row
from symkin.values import as_integer, as_real

__all__ = ["ExistenceBounds", "existence_bounds", "existence_interval", "existence_range"]


@dataclass(frozen=True)
class _RegionSetup:
    ratio: sp.Expr  # i as a function of r_1 (r_3 = 1, r_2 = delta)
    constraints: tuple[tuple[str, sp.Expr], ...]  # expressions in r_1 that must be positive
    neighbour: tuple[sp.Expr, sp.Expr]  # arm, and the larger rim is max(delta, 1)


R1 = S.radius("1")


@cache
def _region_setup(scheme: str) -> _RegionSetup:
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


@cache
def _numeric(expr: sp.Expr) -> NumericFunction:
    return compile(expr, [DELTA, _S, K], backend="numpy")


@cache
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
    k = int(as_integer(satellites, what="the number of satellites"))
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
    empty, lower = _least_r1(items, subs)
    if empty:
        return None
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


def _least_r1(items: list[tuple[str, sp.Expr]], subs: dict[sp.Symbol, Any]) -> tuple[bool, Any]:
    """The least r_1 the constraints (each ``expr > 0``, linear in r_1) leave; whether one constant
    constraint fails for every r_1 (the interval is then empty)."""
    lower = None
    for _name, expr in items:
        e = sp.expand(expr.subs(subs))
        poly = sp.Poly(e, R1)
        a, b = poly.all_coeffs() if poly.degree() == 1 else (sp.Integer(0), e)
        if a == 0:
            if not (b > 0):
                return True, None
            continue
        bound = -b / a
        lower = bound if lower is None or bool(bound > lower) else lower
    return False, lower


def _as_float(v: sp.Expr) -> float:
    if v == sp.oo:
        return math.inf
    if v == -sp.oo:
        return -math.inf
    return float(v)


@cache
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

