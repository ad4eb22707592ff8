"""Lost motion of a common-ring train of single-row AI stages, carried to the output.

Each stage i loses motion in its two meshes (sun-planet, planet-ring).  Referred to the
stage's sun it is the relative angular error ``Phi_i / d_(3i-2)`` (the 2014 KhAI paper's
symbols: ``Phi_i`` the summed probable maximum backlash of the stage, ``d_(3i-2)`` the
sun's pitch diameter).  An angular error of a link reaches the output carrier H_n
multiplied by d phi_Hn / d phi_link, which the engine derives from the train
(:func:`symkin.schemes.common_ring_train`): the speeds of every carrier for a driven
first sun and a fixed ring.  Summing over the stages gives the objective

    Delta phi = sum_i (Phi_i / d_(3i-2)) * omega_Hn / omega_sun_i,

written in the stage ratios u_i = omega_sun_i / omega_Hi (also derived), with nothing
typed in by hand.  Stage error models give ``Phi_i / d_(3i-2)`` as a function of u_i;
:func:`probable_max_backlash` and :func:`max_lost_motion` are the tolerance stacks of the
standards the paper uses (GOST 9178-81, appendix 4; GOST 21098-82).

    >>> lm = lost_motion(2)
    >>> lm.total_ratio
    u_1*u_2
    >>> lm.objective
    Phi_1/(d_1*u_1*u_2) + Phi_2/(d_4*u_2)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import sympy as sp
from mpmath.libmp import fzero, mpf_gt, mpf_le, round_nearest
from mpmath.libmp import to_float as mpf_to_float

from symkin import symbols as S
from symkin._util.bounds import MAX_DIGITS, Encloser, NotReal, OutOfRange, Unbounded, Undecided
from symkin._util.budget import time_limit
from symkin.errors import InputError
from symkin.mechanisms.multistage.stages import stage_laws
from symkin.numeric import compile
from symkin.schemes import common_ring_train, single_row_AI
from symkin.values import as_expr, as_rational, as_real, sign_of

__all__ = [
    "stage_ratio_symbol",
    "backlash_symbol",
    "diameter_symbol",
    "U",
    "LostMotion",
    "lost_motion",
    "train_speeds",
    "StageErrorModel",
    "probable_max_backlash",
    "max_lost_motion",
]

#: The generic stage ratio a stage error model is written in.
U = sp.Symbol("u", positive=True)


def stage_ratio_symbol(i: int) -> sp.Symbol:
    """u_i, the ratio omega_sun / omega_carrier of stage i with the ring fixed.

    >>> stage_ratio_symbol(2)
    u_2
    """
    return sp.Symbol(f"u_{i}", positive=True)


def backlash_symbol(i: int) -> sp.Symbol:
    """Phi_i, the summed probable maximum backlash of stage i's two meshes.

    >>> backlash_symbol(2)
    Phi_2
    """
    return sp.Symbol(f"Phi_{i}", positive=True)


def diameter_symbol(i: int) -> sp.Symbol:
    """d_(3i-2), the pitch diameter of stage i's sun (gears are numbered 3i-2, 3i-1, 3i).

    >>> diameter_symbol(2)
    d_4
    """
    return sp.Symbol(f"d_{3 * i - 2}", positive=True)


@dataclass(frozen=True)
class LostMotion:
    """The lost-motion laws of an n-stage common-ring train, derived by the engine.

    Attributes
    ----------
    stages : int
    ratios : tuple of Symbol
        u_1 ... u_n.
    stage_ratios_radii : tuple of sympy expression
        Each u_i as the engine derives it, in pitch radii (r_s<i>, r_4).
    total_ratio : sympy expression
        omega_s1 / omega_Hn with the ring fixed, in the u_i.
    sun_transfers : tuple of sympy expression
        omega_Hn / omega_sun_i: how an angular error of stage i's sun reaches the output.
    carrier_transfers : tuple of sympy expression
        omega_Hn / omega_Hi: how an angular error of stage i's carrier reaches the output.
    carrier_errors : tuple of sympy expression
        The relative angular error of carrier H_i from its own stage's backlash,
        (Phi_i / d_(3i-2)) * omega_Hi / omega_sun_i.
    """

    stages: int
    ratios: tuple[sp.Symbol, ...]
    stage_ratios_radii: tuple[sp.Expr, ...]
    total_ratio: sp.Expr
    sun_transfers: tuple[sp.Expr, ...]
    carrier_transfers: tuple[sp.Expr, ...]
    carrier_errors: tuple[sp.Expr, ...]

    @property
    def backlash(self) -> tuple[sp.Symbol, ...]:
        """The symbols of each stage's backlash, stage 1 first."""
        return tuple(backlash_symbol(i) for i in range(1, self.stages + 1))

    @property
    def diameters(self) -> tuple[sp.Symbol, ...]:
        """The symbols of each stage's sun diameter, stage 1 first."""
        return tuple(diameter_symbol(i) for i in range(1, self.stages + 1))

    @property
    def sun_errors(self) -> tuple[sp.Expr, ...]:
        """Phi_i / d_(3i-2): each stage's error referred to its sun."""
        return tuple(p / d for p, d in zip(self.backlash, self.diameters))

    @property
    def objective(self) -> sp.Expr:
        """The relative total angular error at the output: each carrier's error carried on.

        >>> lost_motion(1).objective
        Phi_1/(d_1*u_1)
        """
        return sp.Add(*(e * t for e, t in zip(self.carrier_errors, self.carrier_transfers)))

    def terms(self, model: StageErrorModel | Sequence[StageErrorModel]) -> tuple[sp.Expr, ...]:
        """Each stage's contribution to the objective with Phi_i / d_(3i-2) from ``model``.

        ``model`` is one model for every stage or one per stage.

        >>> lost_motion(2).terms(StageErrorModel.linear(1, 2))
        ((2*u_1 + 1)/(u_1*u_2), (2*u_2 + 1)/u_2)
        """
        models = _models(model, self.stages)
        return tuple(
            m.at(u) * t for m, u, t in zip(models, self.ratios, self.sun_transfers)
        )

    def objective_with(self, model: StageErrorModel | Sequence[StageErrorModel]) -> sp.Expr:
        """The objective with the stage error model(s) substituted, in the u_i only.

        >>> lost_motion(2).objective_with(StageErrorModel.linear(1, 2))
        (2*u_2 + 1)/u_2 + (2*u_1 + 1)/(u_1*u_2)
        """
        return sp.Add(*self.terms(model))

    def substitute(self, model: StageErrorModel | Sequence[StageErrorModel]) -> dict[sp.Symbol, sp.Expr]:
        """{Phi_i: d_(3i-2) * model(u_i)}: the substitution that puts a model into :attr:`objective`.

        >>> lost_motion(1).substitute(StageErrorModel.linear(1, 2))
        {Phi_1: d_1*(2*u_1 + 1)}
        """
        models = _models(model, self.stages)
        return {p: d * m.at(u) for p, d, m, u in zip(self.backlash, self.diameters, models, self.ratios)}


def train_speeds(train: Any) -> dict[str, sp.Expr]:
    """Every link's speed of a common-ring train for a driven first sun and a fixed ring.

    The engine's speeds (:meth:`~symkin.model.Mechanism.speeds` with omega_4 = 0), each
    a constant factor times omega_s1, factored.

    >>> from symkin.schemes import common_ring_train
    >>> train_speeds(common_ring_train(1))["H1"]
    omega_s1*r_s1/(r_4 + r_s1)
    """
    from symkin.kinematics import _factored_coefficient

    w = S.omega("s1")
    speeds = train.speeds({"s1": w, "4": 0})
    # factored from the product of the stages' factors the engine composed (each factor alone),
    # not from the cancelled coefficient (one multivariate factorisation of n stages, 0.5 s at n = 5)
    return {name: sp.factor(_factored_coefficient(train, ("s1", "4"), name, "s1")) * w for name in speeds}


@lru_cache(maxsize=16)
def lost_motion(stages: int) -> LostMotion:
    """Derive the lost-motion laws of an ``stages``-stage common-ring train (cached).

    The engine's contact conditions of the train are solved once, for a driven first
    sun and a fixed ring (:func:`train_speeds`); every stage ratio, transfer and the total ratio are quotients of the
    speeds it returns, rewritten in the u_i by solving each stage's ratio law for its
    sun's radius.

    >>> lm = lost_motion(3)
    >>> lm.sun_transfers
    (1/(u_1*u_2*u_3), 1/(u_2*u_3), 1/u_3)
    >>> lm.carrier_errors[0]
    Phi_1/(d_1*u_1)
    """
    if isinstance(stages, bool) or not isinstance(stages, int) or stages < 1:
        raise InputError(f"the number of stages must be a positive whole number, got {stages!r}")
    n = stages
    train = common_ring_train(n)
    speeds = train_speeds(train)
    sun_speed = [speeds[train.link(f"s{i}").name] for i in range(1, n + 1)]
    carrier_speed = [speeds[f"H{i}"] for i in range(1, n + 1)]
    u = tuple(stage_ratio_symbol(i) for i in range(1, n + 1))
    radii_laws = tuple(sp.factor(s / c) for s, c in zip(sun_speed, carrier_speed))
    to_u: dict[sp.Symbol, sp.Expr] = {}
    for i, law in enumerate(radii_laws, 1):
        r_sun = train.gear(f"s{i}").radius
        (solution,) = sp.solve(sp.Eq(u[i - 1], law), r_sun)
        to_u[r_sun] = solution

    def in_u(expr: sp.Expr) -> sp.Expr:
        return sp.factor(sp.together(sp.factor(expr).subs(to_u)))

    total = in_u(sun_speed[0] / carrier_speed[-1])
    sun_transfers = tuple(in_u(carrier_speed[-1] / s) for s in sun_speed)
    carrier_transfers = tuple(in_u(carrier_speed[-1] / c) for c in carrier_speed)
    errors = tuple(
        backlash_symbol(i) / diameter_symbol(i) * in_u(carrier_speed[i - 1] / sun_speed[i - 1])
        for i in range(1, n + 1)
    )
    return LostMotion(n, u, radii_laws, total, sun_transfers, carrier_transfers, errors)


# --------------------------------------------------------------------------- stage models
@dataclass(frozen=True)
class StageErrorModel:
    """Phi / d of one stage (its error referred to its sun) as a function of its ratio u.

    Attributes
    ----------
    expr : sympy expression
        In the symbol :data:`U` (``u``).
    description : str
    """

    expr: sp.Expr
    description: str = ""

    def __post_init__(self) -> None:
        expr = as_expr(self.expr, what="a stage error model")
        if expr.free_symbols - {U}:
            raise InputError(f"a stage error model is an expression in u only, got {self.expr!r}")
        object.__setattr__(self, "expr", expr)

    @classmethod
    def linear(cls, a: Any, b: Any) -> StageErrorModel:
        """Phi / d = a + b u, the paper's linear model (5).

        >>> StageErrorModel.linear(0.5, 2).expr
        2*u + 1/2
        """
        av, bv = as_real(a, what="a"), as_real(b, what="b")
        return cls(av + bv * U, f"linear model Phi/d = {av} + {bv} u")

    @classmethod
    def from_backlash_line(cls, intercept: Any, slope: Any, *, module: Any, ring: int) -> StageErrorModel:
        """Phi / d from a straight line j(a_w) = intercept + slope * a_w of each mesh's backlash.

        The 2014 paper's (7) is such a line.  Phi is the sum over the stage's two meshes (its
        (3)); each mesh's centre distance comes from the engine's single-row AI geometry,
        the sun's diameter is its pitch diameter, and the sun's teeth follow from u and the
        common ring.  With one ring the result is exactly linear in u.

        >>> StageErrorModel.from_backlash_line(40, sp.Rational(1, 2), module=1, ring=100).expr
        21*u/20 - 4/5
        """
        c0, c1 = as_real(intercept, what="the intercept"), as_real(slope, what="the slope")
        m = as_real(module, what="the module", positive=True)
        if isinstance(ring, bool) or not isinstance(ring, (int, sp.Integer)) or ring < 3:
            raise InputError(f"the ring's tooth number must be a whole number of at least 3, got {ring!r}")
        z1, z2, z4 = S.teeth("1"), S.teeth("2"), S.teeth("4")
        mech = single_row_AI(teeth=True, module=m)
        distances = [d for _, d in mech.planet_centre_distances["2"]]  # mesh 1-2 and mesh 2-4
        backlash = sum(c0 + c1 * a for a in distances)
        sun_diameter = 2 * mech.gear("1").radius
        laws = stage_laws()
        (sun_teeth,) = sp.solve(sp.Eq(U, laws.ratio.rhs), z1)
        planet = laws.planet_from_coaxiality
        expr = (backlash / sun_diameter).subs(z2, planet).subs(z1, sun_teeth).subs(z4, ring)
        expr = sp.expand(sp.cancel(expr))
        return cls(expr, f"Phi/d from j(a_w) = {c0} + {c1} a_w per mesh, module {m}, ring {ring}")

    def at(self, u: Any) -> sp.Expr:
        """The model at a ratio (a number or a symbol).

        >>> StageErrorModel.linear(1, 2).at(3)
        7
        """
        return self.expr.subs(U, u)

    def numeric(self) -> Callable[[float], float]:
        """A float function of u.

        >>> StageErrorModel(U**2).numeric()(1.5)
        2.25
        """
        f = compile(self.expr, [U], backend="numpy")
        return lambda x: float(f(float(x)))

    def check_positive(self, lower: Any, upper: Any) -> None:
        """Raise unless Phi/d > 0 over [lower, upper] (a lost motion is positive).

        Decided on intervals (:func:`_positive_on`), not on samples: a
        model that touches 0 between samples, such as ``Abs(u - 5.123456789)``, is refused.

        >>> StageErrorModel.linear(-3, 1).check_positive(2, 10)
        Traceback (most recent call last):
        ...
        symkin.errors.InputError: the stage error model u - 3 is not positive over [2, 10]: at u = 2 it is not positive; a lost motion must be positive over the whole ratio range, so change the model or the bounds
        """
        lo = as_rational(lower, what="the lower ratio bound")
        hi = as_rational(upper, what="the upper ratio bound")
        with time_limit(POSITIVE_SECONDS, f"deciding whether the stage error model {self.expr} is positive took "
                        f"longer than {POSITIVE_SECONDS:g} s of CPU time; write a simpler model"):
            found = _positive_on(self.expr, U, lo, hi)
        if found is not None:
            at, problem = found
            raise InputError(
                f"the stage error model {self.expr} is not positive over [{float(lo):.6g}, {float(hi):.6g}]: at u = "
                f"{at:.6g} {problem}; a lost motion must be positive over the whole ratio range, so change the model "
                "or the bounds"
            )


#: CPU seconds :meth:`StageErrorModel.check_positive` may take to decide.
POSITIVE_SECONDS = 3.0


def _models(model: Any, n: int) -> tuple[StageErrorModel, ...]:
    if isinstance(model, StageErrorModel):
        return (model,) * n
    models = tuple(model)
    if len(models) != n or not all(isinstance(m, StageErrorModel) for m in models):
        raise InputError(f"give one StageErrorModel for every stage or {n} of them, got {model!r}")
    return models


# --------------------------------------------------------------------------- tolerance stacks
def probable_max_backlash(j_min: Any, T_H1: Any, T_H2: Any, f_a: Any) -> sp.Expr:
    """Probable maximum backlash of a mesh (GOST 9178-81, appendix 4): a standard's formula,
    given here as an input to the objective, not derived (the KhAI paper quotes it as (6)).

    The guaranteed backlash plus the probabilistic (root-sum-square) sum of the random
    parts: the tolerances T_H1, T_H2 on the shift of each gear's basic rack (weight 1/2
    each) and the centre-distance deviation f_a (weight 2).  Give lengths in one unit.

    >>> probable_max_backlash(*sp.symbols("j_min T_H1 T_H2 f_a", positive=True))
    j_min + sqrt(T_H1**2/2 + T_H2**2/2 + 2*f_a**2)
    >>> probable_max_backlash(10, 30, 40, 5)
    10 + 10*sqrt(13)
    """
    j, t1, t2, fa = (_tolerance(v) for v in (j_min, T_H1, T_H2, f_a))
    return j + sp.sqrt(sp.Rational(1, 2) * (t1**2 + t2**2) + 2 * fa**2)


def max_lost_motion(E_HS1: Any, E_HS2: Any, T_H1: Any, T_H2: Any, f_a: Any, G_r1: Any = 0, G_r2: Any = 0) -> sp.Expr:
    """Maximum lost motion J_t max of a cylindrical gear pair (GOST 21098-82): a standard's
    formula, given here as an input, not derived (the KhAI paper quotes it as (8)).

    0.7 (E_HS1 + E_HS2) plus the root-sum-square of the rack-shift tolerances, the
    centre-distance deviation and the radial clearances G_r1, G_r2 in the bearings.  The
    E_HS are taken as given (the paper signs them minus for external, plus for internal
    gears).

    >>> max_lost_motion(*sp.symbols("E_HS1 E_HS2 T_H1 T_H2 f_a G_r1 G_r2"))
    7*E_HS1/10 + 7*E_HS2/10 + sqrt(G_r1**2 + G_r2**2 + T_H1**2/2 + T_H2**2/2 + 2*f_a**2)
    """
    e1, e2 = (_tolerance(v, signed=True) for v in (E_HS1, E_HS2))
    t1, t2, fa, g1, g2 = (_tolerance(v) for v in (T_H1, T_H2, f_a, G_r1, G_r2))
    return sp.Rational(7, 10) * (e1 + e2) + sp.sqrt(sp.Rational(1, 2) * (t1**2 + t2**2) + 2 * fa**2 + g1**2 + g2**2)


def _tolerance(value: Any, signed: bool = False) -> sp.Expr:
    if isinstance(value, sp.Symbol):
        return value
    v = as_real(value, what="a tolerance")
    if not signed and sign_of(v, what="a tolerance") == -1:
        raise InputError(f"a tolerance must not be negative, got {v}")
    return v


# --------------------------------------------------------------------------- positivity on intervals
def _positive_on(
    expr: Any, symbol: Any, lower: Any, upper: Any, *, boxes: int = 4000, prec: int = 64
) -> tuple[float, str] | None:
    """None if ``expr`` > 0 for every ``symbol`` in [lower, upper], else (a point, what is wrong there).

    The two ends are tried first, then branch and bound on intervals: a sub-interval whose
    enclosure is positive is done; one whose enclosure is nowhere positive, or whose
    midpoint value is not positive, gives the point; the others are halved, up to ``boxes``
    sub-intervals.  A function that touches 0 (``Abs(u - 5.123456789)``) is never shown
    positive, whatever samples would say: the point nearest the touch is returned.

    >>> u = sp.Symbol("u", positive=True)
    >>> _positive_on(1 + u / 10, u, 2, 12) is None
    True
    >>> _positive_on(u - 3, u, 2, 10)
    (2.0, 'it is not positive')
    >>> _positive_on(sp.Abs(u - sp.Rational(5123456789, 10**9)), u, 2, 12)
    (5.123456789..., 'it is not shown to be positive (it comes within ... of 0)')
    """
    lo, hi = sp.Rational(lower), sp.Rational(upper)
    for end in (lo, hi):
        problem, _ = _value_at(expr, symbol, end, prec)
        if problem:
            return (float(end), problem)
    stack = [(lo, hi)]
    tried = 0
    while stack:
        a, b = stack.pop()
        tried += 1
        shown, box = _enclosed(expr, symbol, a, b, prec)
        if shown:
            continue
        if shown is False:
            return (float((a + b) / 2), "it is not positive")
        mid = (a + b) / 2
        problem, top = _value_at(expr, symbol, mid, prec)
        if problem:
            return (float(mid), problem)
        if tried >= boxes or b - a <= (hi - lo) / 2**60:
            if box is not None:  # a pole or a domain edge the midpoints straddle without meeting
                return (float(mid), box)
            near = f" (it comes within {float(mpf_to_float(top, rnd=round_nearest)):.3g} of 0)" if top is not None else ""
            return (float(mid), f"it is not shown to be positive{near}")
        stack += [(mid, b), (a, mid)]
    return None


def _value_at(expr: Any, symbol: Any, point: Any, prec: int) -> tuple[str | None, Any]:
    """What is wrong with ``expr`` at ``symbol = point`` (None: nothing shown), and the upper end of its
    enclosure there (None when there is none)."""
    try:
        x = Encloser(prec, {symbol: (point, point)}).enclose(expr)
    except NotReal:
        return "it is not a real number", None
    except Unbounded:
        return "it is infinite (a pole)", None
    except OutOfRange as err:
        if err.large:
            return f"it is larger than 1e{MAX_DIGITS}", None
        x = err.interval
    except Undecided:
        return None, None
    return ("it is not positive" if mpf_le(x[1], fzero) else None), x[1]


def _enclosed(expr: Any, symbol: Any, a: Any, b: Any, prec: int) -> tuple[bool | None, str | None]:
    """What the enclosure of ``expr`` for ``symbol`` in [a, b] shows: True (positive throughout), False
    (nowhere positive) or None (neither), and why no enclosure was found (a pole, not real; else None)."""
    try:
        x = Encloser(prec, {symbol: (a, b)}).enclose(expr)
        if mpf_gt(x[0], fzero):
            return True, None
        if mpf_le(x[1], fzero):
            return False, None
    except Unbounded:
        return None, "it is infinite (a pole)"
    except NotReal:
        return None, "it is not a real number"
    except Undecided as err:
        return None, "a divisor in it vanishes (a pole)" if err.question == "is zero" else None
    except OutOfRange:
        pass
    return None, None
