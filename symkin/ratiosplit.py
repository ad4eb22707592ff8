"""Split a total ratio over the stages of a common-ring train for the least lost motion.

The objective is the derived lost motion at the output (:mod:`symkin.lostmotion`) with a
stage error model Phi/d(u).  Two problems are solved:

- *continuous*: each u_i in its bounds, the product of the u_i fixed.  In x_i = ln u_i
  the constraint is linear (sum x_i = ln U) and the bounds are boxes; SciPy's SLSQP
  solves it from several feasible starts with the exact (symbolic) gradient, and the
  result carries its KKT analysis: which bounds are active, their multipliers, and the
  derivative of the optimum with respect to ln U.  When the objective is a posynomial
  in the u_i (checked symbolically), it is convex in x and the KKT point is the global
  minimum.
- *discrete*: each stage taken from a set of feasible stages (:mod:`symkin.stages`),
  the total ratio within a relative tolerance; a depth-first branch and bound from the
  output stage ranks the designs by the objective, exactly.  When no design meets the
  tolerance, the nearest designs are returned instead, and the result says so.

    >>> from symkin.lostmotion import StageErrorModel
    >>> best = optimise_split(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
    >>> best.exact_ratios, best.active
    ((5, 20), ('free', 'upper'))
"""

from __future__ import annotations

import heapq
import math
import re
import time
import warnings
from bisect import bisect_left, bisect_right
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any, Callable, Sequence

import numpy as np
import sympy as sp

from .budget import simplify_within
from .errors import InputError, SymkinError, UnsupportedError
from .lostmotion import LostMotion, StageErrorModel, lost_motion
from .parsing import as_rational

__all__ = [
    "SplitProblem",
    "ContinuousSplit",
    "Design",
    "DiscreteSplit",
    "optimise_split",
    "profile",
    "best_designs",
]

#: The most stages a split problem takes (the symbolic derivation grows fast with the train).
MAX_STAGES = 20

_BOUND_TOL = 1e-7  # in ln u: a stage this close to a bound is on it
_TABLE_SIZE = 200_000  # largest table of completion products the discrete search keeps per depth


# --------------------------------------------------------------------------- inputs
def _rational(value: Any, what: str) -> sp.Rational:
    return as_rational(value, what=what)


def _per_stage(value: Any, n: int, what: str) -> tuple[sp.Rational, ...]:
    if isinstance(value, (list, tuple)):
        if len(value) != n:
            raise InputError(f"{what} gives {len(value)} values for {n} stages; give one value or one per stage")
        return tuple(_rational(v, f"{what} of stage {i}") for i, v in enumerate(value, 1))
    return (_rational(value, what),) * n


@dataclass(frozen=True)
class SplitProblem:
    """Minimise the lost motion at the output over the ratio split.

    Attributes
    ----------
    total : sympy.Rational
        The total ratio U = u_1 ... u_n (exact).
    stages : int
    lower, upper : tuple of sympy.Rational
        Bounds of each u_i.
    models : tuple of StageErrorModel
        Phi/d of each stage as a function of its ratio.
    """

    total: sp.Rational
    stages: int
    lower: tuple[sp.Rational, ...]
    upper: tuple[sp.Rational, ...]
    models: tuple[StageErrorModel, ...]

    @classmethod
    def build(cls, total: Any, stages: int, *, lower: Any, upper: Any, model: Any) -> "SplitProblem":
        """Check the inputs and build the problem.

        ``lower``/``upper`` are one value or one per stage; ``model`` one
        :class:`~symkin.lostmotion.StageErrorModel` or one per stage.

        >>> SplitProblem.build(100, 2, lower=12, upper=20, model=StageErrorModel.linear(1, 1))
        Traceback (most recent call last):
        ...
        symkin.errors.InputError: the total ratio 100 is outside what 2 stages with these bounds allow (144 to 400); change the total, the bounds or the number of stages
        """
        if isinstance(stages, bool) or not isinstance(stages, (int, sp.Integer)) or not 1 <= int(stages) <= MAX_STAGES:
            raise InputError(f"the number of stages must be a positive whole number, at most {MAX_STAGES}, got {stages!r}")
        n = int(stages)
        U = _rational(total, "the total ratio")
        if U <= 0:
            raise InputError(f"the total ratio must be positive, got {U}")
        lo, hi = _per_stage(lower, n, "the lower bound"), _per_stage(upper, n, "the upper bound")
        for i, (a, b) in enumerate(zip(lo, hi), 1):
            if a <= 0:
                raise InputError(f"the lower bound of stage {i} must be positive, got {a}")
            if a > b:
                raise InputError(f"the bounds of stage {i} are reversed: lower {a} > upper {b}; give lower <= upper")
        pmin, pmax = sp.Mul(*lo), sp.Mul(*hi)
        if not pmin <= U <= pmax:
            raise InputError(
                f"the total ratio {U} is outside what {n} stage{'s' * (n > 1)} with these bounds allow "
                f"({_show(pmin)} to {_show(pmax)}); change the total, the bounds or the number of stages"
            )
        if isinstance(model, StageErrorModel):
            models = (model,) * n
        else:
            try:
                models = tuple(model)
            except TypeError:
                raise InputError(f"model must be a StageErrorModel or one per stage, got {model!r}") from None
            if len(models) != n or not all(isinstance(m, StageErrorModel) for m in models):
                raise InputError(f"give one StageErrorModel or {n} of them, got {model!r}")
        for m, a, b in zip(models, lo, hi):
            m.check_positive(a, b)
        return cls(U, n, lo, hi, models)

    # ---- derived, compiled once
    @cached_property
    def lost_motion(self) -> LostMotion:
        return lost_motion(self.stages)

    @cached_property
    def objective(self) -> sp.Expr:
        """The objective in u_1 ... u_n (the derived law with the models substituted)."""
        return self.lost_motion.objective_with(self.models)

    @cached_property
    def log_gradient(self) -> tuple[sp.Expr, ...]:
        """d objective / d ln u_j = u_j d objective / d u_j, symbolically."""
        return tuple(sp.together(u * sp.diff(self.objective, u)) for u in self.lost_motion.ratios)

    @cached_property
    def _f(self) -> Callable[..., float]:
        return sp.lambdify(self.lost_motion.ratios, self.objective, "numpy")

    @cached_property
    def _g(self) -> Callable[..., Any]:
        return sp.lambdify(self.lost_motion.ratios, list(self.log_gradient), "numpy")

    def value(self, ratios: Sequence[Any]) -> float:
        """The objective at a split (floats)."""
        return float(self._f(*[float(r) for r in ratios]))

    def exact_value(self, ratios: Sequence[Any]) -> sp.Expr:
        """The objective at a split, exactly (rationals in, a rational out for rational models)."""
        subs = {u: r if isinstance(r, sp.Basic) else _rational(r, "a stage ratio") for u, r in zip(self.lost_motion.ratios, ratios)}
        return sp.cancel(self.objective.xreplace(subs))

    @cached_property
    def posynomial(self) -> bool:
        """True when the objective, on the constraint surface, is a posynomial in the u_i.

        A posynomial is convex in x = ln u, so a KKT point is the global minimum.  The
        monomial 1/(u_1 ... u_n) equals the constant 1/U on the surface, so its sign does
        not matter.
        """
        us = self.lost_motion.ratios
        full = sp.Mul(*us)
        expr = sp.expand(self.objective)
        for term in sp.Add.make_args(expr):
            coeff, rest = term.as_coeff_Mul()
            if not (rest.is_Mul or rest.is_Pow or rest.is_Symbol or rest == 1):
                return False
            powers = rest.as_powers_dict()
            if any(not (b in us and e.is_number) for b, e in powers.items() if b != 1):
                return False
            if simplify_within(rest * full, what="a term of the stage error model") == 1:
                continue
            if coeff < 0:
                return False
        return True


def _show(x: sp.Expr) -> str:
    return str(x) if x.is_Integer or (x.is_Rational and x.q < 1000) else f"{float(x):.6g}"


# --------------------------------------------------------------------------- continuous
@dataclass(frozen=True)
class ContinuousSplit:
    """The optimal continuous split and why it is optimal.

    Attributes
    ----------
    problem : SplitProblem
    ratios : tuple of float
        The optimal u_i, input stage first.
    objective : float
    exact_ratios : tuple of sympy.Rational or None
        The optimum exactly, when all stages but at most one sit on a bound (the free
        stage then takes U over the product of the others).
    exact_objective : sympy expression or None
    active : tuple of str
        ``"lower"``, ``"upper"``, ``"fixed"`` (lower = upper) or ``"free"``, per stage.
    log_gradient : tuple of float
        g_j = d objective / d ln u_j at the optimum.
    nu : float
        The multiplier of the product constraint: d objective* / d ln U (on a bound
        everywhere, the midpoint of its admissible interval).
    multipliers : tuple of float
        Per stage: nu - g_j on an upper bound, g_j - nu on a lower bound, 0 if free;
        d objective* / d ln(bound) is minus this (upper) or plus this (lower).
    kkt_residual : float
        The largest violation of stationarity or multiplier sign, relative to |g|.
    global_optimum : bool
        True when the objective is a posynomial (convex in ln u).
    starts, method : int, str
    """

    problem: SplitProblem
    ratios: tuple[float, ...]
    objective: float
    exact_ratios: tuple[sp.Rational, ...] | None
    exact_objective: sp.Expr | None
    active: tuple[str, ...]
    log_gradient: tuple[float, ...]
    nu: float
    multipliers: tuple[float, ...]
    kkt_residual: float
    global_optimum: bool
    starts: int
    method: str

    def explain(self) -> list[str]:
        """Sentences saying which bounds are active and why.

        >>> r = optimise_split(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
        >>> r.explain()[:2]
        ['stage 1: u = 5, free (inside its bounds)', 'stage 2: u = 20, on its upper bound 20']
        """
        p, n = self.problem, self.problem.stages
        lines = []
        for i, (u, a) in enumerate(zip(self.ratios, self.active), 1):
            exact = f" = {self.exact_ratios[i - 1]}" if self.exact_ratios and not self.exact_ratios[i - 1].is_Integer else ""
            where = {"lower": f"on its lower bound {p.lower[i - 1]}", "upper": f"on its upper bound {p.upper[i - 1]}",
                     "fixed": "fixed (lower = upper)", "free": "free (inside its bounds)"}[a]
            lines.append(f"stage {i}: u = {u:.6g}{exact}, {where}")
        g = self.log_gradient
        lines.append(
            "gradient in x = ln u at the optimum: g = (" + ", ".join(f"{v:.4g}" for v in g) + "); "
            f"product multiplier nu = dF*/d ln U = {self.nu:.4g} (a 1% larger total ratio changes the objective by "
            f"about {self.nu * 0.01:.3g})"
        )
        for i, (a, mu) in enumerate(zip(self.active, self.multipliers), 1):
            if a == "upper":
                lines.append(f"stage {i} upper bound: multiplier {mu:.4g} >= 0; raising it by 1% lowers the objective by about {mu * 0.01:.3g}")
            elif a == "lower":
                lines.append(f"stage {i} lower bound: multiplier {mu:.4g} >= 0; lowering it by 1% lowers the objective by about {mu * 0.01:.3g}")
        if n > 1:
            lines.append(_why(self.active, g))
        lines.append(
            "the objective is a posynomial in the u_i, hence convex in ln u: this KKT point is the global minimum"
            if self.global_optimum
            else "the objective is not a posynomial; the best of several starts is reported (a local minimum)"
        )
        return lines

    def to_json(self) -> dict[str, Any]:
        return {
            "ratios": list(self.ratios),
            "exact_ratios": [str(r) for r in self.exact_ratios] if self.exact_ratios else None,
            "objective": self.objective,
            "exact_objective": str(self.exact_objective) if self.exact_objective is not None else None,
            "active": list(self.active),
            "log_gradient": list(self.log_gradient),
            "nu": self.nu,
            "multipliers": list(self.multipliers),
            "kkt_residual": self.kkt_residual,
            "global_optimum": self.global_optimum,
            "explanation": self.explain(),
        }


#: Gradient differences smaller than this, relative to the largest |g_j|, count as equal.
_GRADIENT_RTOL = 1e-6


def _why(active: Sequence[str], g: Sequence[float]) -> str:
    """Why the bounds are active, said only when the active set agrees with the reason.

    >>> _why(("free", "upper"), (2.0, 1.0))[:40]
    'why: g_j - g_(j+1) > 0 along the whole t'
    >>> _why(("free", "free"), (0.03465, 0.03465000001))
    'why: the free stages share one gradient value nu; each bound holds because its multiplier is non-negative'
    """
    tol = _GRADIENT_RTOL * max(max(abs(v) for v in g), 1e-300)
    diffs = [g[j] - g[j + 1] for j in range(len(g) - 1)]
    pattern = "".join({"lower": "l", "upper": "u", "fixed": "x", "free": "f"}[a] for a in active)
    if all(d > tol for d in diffs) and re.fullmatch(r"[lx]*f?[ux]*", pattern):
        return (
            "why: g_j - g_(j+1) > 0 along the whole train, so moving ln-ratio from any stage to a later one lowers "
            "the objective; hence the stages nearest the output sit on their upper bounds, those nearest the input "
            "on their lower bounds, and at most one stage is free to meet the product"
        )
    if all(d < -tol for d in diffs) and re.fullmatch(r"[ux]*f?[lx]*", pattern):
        return (
            "why: g_j - g_(j+1) < 0 along the whole train, so ratio is best moved toward the input: the stages "
            "nearest the input sit on their upper bounds, those nearest the output on their lower bounds"
        )
    if "f" in pattern:
        return "why: the free stages share one gradient value nu; each bound holds because its multiplier is non-negative"
    return "why: every stage is on a bound; each bound holds because its multiplier is non-negative"


def _fill(lo: np.ndarray, hi: np.ndarray, L: float, order: Sequence[int]) -> np.ndarray:
    x = lo.copy()
    budget = L - lo.sum()
    for j in order:
        step = min(budget, hi[j] - lo[j])
        x[j] += step
        budget -= step
    return x


def _equal(lo: np.ndarray, hi: np.ndarray, L: float) -> np.ndarray:
    a, b = lo.min() - 1, hi.max() + 1
    for _ in range(200):
        c = 0.5 * (a + b)
        if np.clip(c, lo, hi).sum() < L:
            a = c
        else:
            b = c
    return np.clip(0.5 * (a + b), lo, hi)


def _kkt(problem: SplitProblem, x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[tuple[str, ...], np.ndarray, float, np.ndarray, float]:
    u = np.exp(x)
    g = np.array(problem._g(*u), dtype=float)
    active = []
    for j in range(len(x)):
        if hi[j] - lo[j] <= _BOUND_TOL:
            active.append("fixed")
        elif x[j] - lo[j] <= _BOUND_TOL:
            active.append("lower")
        elif hi[j] - x[j] <= _BOUND_TOL:
            active.append("upper")
        else:
            active.append("free")
    free = [j for j, a in enumerate(active) if a == "free"]
    scale = max(np.abs(g).max(), 1e-300)
    if free:
        nu = float(np.mean(g[free]))
        resid = float(np.ptp(g[free])) / scale if len(free) > 1 else 0.0
    else:
        upper = [g[j] for j, a in enumerate(active) if a == "upper"]
        lower = [g[j] for j, a in enumerate(active) if a == "lower"]
        low_end = max(upper) if upper else (min(lower) if lower else 0.0)
        high_end = min(lower) if lower else low_end
        nu = 0.5 * (low_end + high_end)
        resid = 0.0
    mult = np.zeros(len(x))
    for j, a in enumerate(active):
        if a == "upper":
            mult[j] = nu - g[j]
        elif a == "lower":
            mult[j] = g[j] - nu
    resid = max(resid, float(max(0.0, -mult.min())) / scale)
    return tuple(active), g, nu, mult, resid


def _minimise(problem: SplitProblem, lo: np.ndarray, hi: np.ndarray, L: float) -> tuple[np.ndarray, int, str]:
    from scipy.optimize import minimize

    n = len(lo)

    def fun(x: np.ndarray) -> float:
        return float(problem._f(*np.exp(x)))

    def jac(x: np.ndarray) -> np.ndarray:
        return np.array(problem._g(*np.exp(x)), dtype=float)

    starts = [_fill(lo, hi, L, range(n - 1, -1, -1)), _fill(lo, hi, L, range(n)), _equal(lo, hi, L)]
    cons = [{"type": "eq", "fun": lambda x: np.array([x.sum() - L]), "jac": lambda x: np.ones((1, n))}]
    best, best_f, method = None, math.inf, "SLSQP"

    def consider(x: np.ndarray, how: str) -> None:
        nonlocal best, best_f, method
        x = np.clip(x, lo, hi)
        x = x + (L - x.sum()) * _slack(x, lo, hi)
        if abs(x.sum() - L) > 1e-9 * max(1.0, abs(L)):
            return
        f = fun(x)
        if best is None or f < best_f - 1e-15 * abs(best_f):
            best, best_f, method = x, f, how

    for x0 in starts:
        if np.all(hi - lo <= _BOUND_TOL):
            consider(x0, "bounds")
            continue
        # SLSQP may report a failed line search at a point that is already optimal: the
        # KKT check below decides, not its status
        res = minimize(fun, x0, jac=jac, method="SLSQP", bounds=list(zip(lo, hi)), constraints=cons,
                       options={"ftol": 1e-15, "maxiter": 1000})
        consider(res.x, "SLSQP")
    if best is not None and _kkt(problem, best, lo, hi)[4] > 1e-6:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = minimize(fun, best, jac=jac, method="trust-constr", bounds=list(zip(lo, hi)), constraints=cons,
                           options={"gtol": 1e-12, "xtol": 1e-14, "maxiter": 3000})
        consider(res.x, "trust-constr")
    if best is None:
        raise SymkinError("the optimiser found no feasible split; please report this problem")
    return best, len(starts), method


def _slack(x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Weights that spread a tiny constraint residual over stages not on a bound."""
    room = (x - lo > _BOUND_TOL) & (hi - x > _BOUND_TOL)
    w = room.astype(float)
    return w / w.sum() if w.sum() else np.full(len(x), 1.0 / len(x))


def _solve(problem: SplitProblem) -> ContinuousSplit:
    lo = np.array([math.log(float(v)) for v in problem.lower])
    hi = np.array([math.log(float(v)) for v in problem.upper])
    L = math.log(float(problem.total))
    x, starts, method = _minimise(problem, lo, hi, L)
    active, g, nu, mult, resid = _kkt(problem, x, lo, hi)
    exact, exact_obj = _exact(problem, active)
    ratios = tuple(float(v) for v in np.exp(x))
    obj = problem.value(ratios)
    if exact is not None:
        exact_float = float(exact_obj)
        if exact_float <= obj * (1 + 1e-9) + 1e-300:
            ratios, obj = tuple(float(r) for r in exact), exact_float
            active, g, nu, mult, resid = _kkt(problem, np.log(np.array(ratios)), lo, hi)
        else:
            exact, exact_obj = None, None
    if resid > 1e-5:
        raise SymkinError(
            f"the optimiser stopped at a point that fails the optimality conditions (residual {resid:.2g}); "
            "please report this problem with its inputs"
        )
    return ContinuousSplit(problem, ratios, obj, exact, exact_obj, active, tuple(float(v) for v in g), float(nu),
                           tuple(float(v) for v in mult), resid, problem.posynomial, starts, method)


def _exact(problem: SplitProblem, active: Sequence[str]) -> tuple[tuple[sp.Rational, ...] | None, sp.Expr | None]:
    free = [j for j, a in enumerate(active) if a == "free"]
    if len(free) > 1:
        return None, None
    values: list[sp.Rational | None] = []
    for j, a in enumerate(active):
        values.append(problem.upper[j] if a == "upper" else problem.lower[j] if a in ("lower", "fixed") else None)
    known = sp.Mul(*[v for v in values if v is not None])
    if free:
        values[free[0]] = problem.total / known
        v = values[free[0]]
        if not problem.lower[free[0]] <= v <= problem.upper[free[0]]:
            return None, None
    elif known != problem.total:
        return None, None
    ratios = tuple(values)  # type: ignore[arg-type]
    return ratios, problem.exact_value(ratios)


def optimise_split(total: Any, stages: int, *, lower: Any, upper: Any, model: Any) -> ContinuousSplit:
    """The continuous split of least lost motion, with its KKT explanation.

    Parameters
    ----------
    total : number
        The total ratio U (exact: ``"5000"``, ``1e4``, ``Fraction``).
    stages : int
    lower, upper : number or sequence of numbers
        Bounds of each stage ratio.
    model : StageErrorModel or sequence of them
        Phi/d of a stage as a function of its ratio.

    Examples
    --------
    >>> from symkin.lostmotion import StageErrorModel
    >>> r = optimise_split(1000, 3, lower=2, upper=12, model=StageErrorModel.linear(1, 1))
    >>> r.exact_ratios, r.active, r.global_optimum
    ((125/18, 12, 12), ('free', 'upper', 'upper'), True)
    """
    return _solve(SplitProblem.build(total, stages, lower=lower, upper=upper, model=model))


def profile(problem: SplitProblem, stage: int, values: Sequence[float]) -> np.ndarray:
    """The least objective with u_stage held at each value (nan where infeasible).

    >>> from symkin.lostmotion import StageErrorModel
    >>> p = SplitProblem.build(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
    >>> [round(float(v), 4) for v in profile(p, 1, [5, 10, 60])]
    [1.11, 1.21, nan]
    """
    out = []
    lo0 = np.array([math.log(float(v)) for v in problem.lower])
    hi0 = np.array([math.log(float(v)) for v in problem.upper])
    L = math.log(float(problem.total))
    for value in values:
        lo, hi = lo0.copy(), hi0.copy()
        x = math.log(float(value))
        if not lo[stage - 1] - 1e-12 <= x <= hi[stage - 1] + 1e-12:
            out.append(math.nan)
            continue
        lo[stage - 1] = hi[stage - 1] = x
        if lo.sum() > L + 1e-12 or hi.sum() < L - 1e-12:
            out.append(math.nan)
            continue
        xs, _, _ = _minimise(problem, lo, hi, L)
        out.append(problem.value(np.exp(xs)))
    return np.array(out, dtype=float)


# --------------------------------------------------------------------------- discrete
@dataclass(frozen=True)
class Design:
    """One discrete design: a feasible stage per position, input stage first.

    Attributes
    ----------
    stages : tuple of symkin.stages.Stage
    total : sympy.Rational
        The product of the stage ratios (exact).
    deviation : sympy.Rational
        (total - target) / target.
    objective : sympy expression
        The derived objective at the stage ratios (exact for rational models).
    """

    stages: tuple[Any, ...]
    total: sp.Rational
    deviation: sp.Rational
    objective: sp.Expr

    @property
    def ratios(self) -> tuple[sp.Rational, ...]:
        return tuple(s.ratio for s in self.stages)

    def to_json(self) -> dict[str, Any]:
        return {
            "stages": [s.to_json() for s in self.stages],
            "teeth": [[s.sun, s.planet, s.ring] for s in self.stages],
            "ratios": [str(r) for r in self.ratios],
            "total": {"exact": str(self.total), "float": float(self.total)},
            "deviation": {"exact": str(self.deviation), "float": float(self.deviation)},
            "objective": {"exact": str(self.objective), "float": float(self.objective)},
        }


@dataclass(frozen=True)
class DiscreteSplit:
    """The best discrete designs, or the nearest ones when none meets the tolerance.

    Attributes
    ----------
    problem : SplitProblem
    tolerance : sympy.Rational
        The relative tolerance on the total ratio.
    designs : tuple of Design
        Ranked by objective (within tolerance) or by |deviation| then objective (nearest).
    meets_tolerance : bool
    nodes : int
        Search nodes visited (a measure of the work done).
    distinct : bool
        True when each multiset of stages appears once, in its best order.
    """

    problem: SplitProblem
    tolerance: sp.Rational
    designs: tuple[Design, ...]
    meets_tolerance: bool
    nodes: int
    distinct: bool

    def message(self) -> str:
        if self.meets_tolerance:
            return f"{len(self.designs)} best design(s) with the total ratio within {float(self.tolerance):.4g} (relative)"
        best = self.designs[0] if self.designs else None
        if best is None:
            return "no design found"
        total = str(best.total) if best.total.is_Integer else f"{best.total} = {float(best.total):.6g}"
        return (
            f"no design meets the tolerance {float(self.tolerance):.4g}; the nearest total ratio is {total} "
            f"(deviation {float(best.deviation):+.4%}); the nearest designs follow"
        )

    def to_json(self) -> dict[str, Any]:
        return {
            "tolerance": str(self.tolerance),
            "meets_tolerance": self.meets_tolerance,
            "message": self.message(),
            "nodes": self.nodes,
            "distinct": self.distinct,
            "designs": [d.to_json() for d in self.designs],
        }


class _Search:
    """Depth-first branch and bound from the output stage (stage n) to the input (stage 1)."""

    def __init__(self, problem: SplitProblem, stages: Sequence[Any], top: int, distinct: bool,
                 progress: Callable[[float, int], None] | None):
        lm = problem.lost_motion
        n = problem.stages
        self.n, self.top, self.distinct, self.progress = n, top, distinct, progress
        self.stages = sorted(stages, key=lambda s: s.ratio, reverse=True)
        self.r = [float(s.ratio) for s in self.stages]
        self.exact = [Fraction(int(s.ratio.p), int(s.ratio.q)) for s in self.stages]
        # each stage's transfer must be a monomial in the ratios of it and later stages
        self.exponents = []
        for i, t in enumerate(lm.sun_transfers):
            powers = sp.Mul.make_args(t)
            e = [0] * n
            for f in powers:
                base, exp = f.as_base_exp()
                if base in lm.ratios and exp.is_Integer:
                    e[lm.ratios.index(base)] += int(exp)
                elif f != 1:
                    raise UnsupportedError(f"the transfer of stage {i + 1} is not a monomial in the stage ratios: {t}")
            if any(e[j] for j in range(i)):
                raise UnsupportedError(f"the transfer of stage {i + 1} depends on earlier stages: {t}")
            self.exponents.append(e)
        F = [m.numeric() for m in problem.models]
        self.F = [[F[i](r) for r in self.r] for i in range(n)]  # model value of stage i at each ratio
        # lower bounds: min over the set of F_i(u) u^e_ii, and of u^e for each exponent used
        self.min_self = [min(self.F[i][k] * self.r[k] ** self.exponents[i][i] for k in range(len(self.r))) for i in range(n)]
        self.min_pow = {e: min(r**e for r in self.r) for row in self.exponents for e in set(row)}
        self.log_r = [math.log(r) for r in self.r]
        self._tables: dict[tuple[int, int], np.ndarray] = {}
        m = len(self.r)
        self.table_depth = max(r for r in range(0, n + 1) if math.comb(m + r - 1, r) <= _TABLE_SIZE)
        # serial transfers (each stage's error divided by its own and every later ratio, as
        # derived): the best objective of the first r stages for each product is then a
        # dynamic programme, an exact bound for the deepest levels of the search
        self.serial = all(e[j] == (-1 if j >= i else 0) for i, e in enumerate(self.exponents) for j in range(n))
        self.prefix_best = self._prefix_best() if self.serial else []
        # best order of a stage set: swapping adjacent stages p (input side) and q changes only
        # their two terms, F(p)/(p q) + F(q)/q against F(q)/(q p) + F(p)/p (times the later
        # ratios); with u > 1 the first is no larger iff F(p)/(p - 1) >= F(q)/(q - 1).  So
        # with one model for every stage the best order sorts the stages by this key, and
        # when each stage set is wanted once only that order is searched (ties by index).
        same_model = all(m.expr == problem.models[0].expr for m in problem.models)
        self.order_key = None
        if distinct and self.serial and same_model and min(self.r) > 1:
            self.order_key = [self.F[0][k] / (self.r[k] - 1) for k in range(len(self.r))]
        self.nodes = 0
        self.last_report = time.perf_counter()

    def in_order(self, k_input: int, k_output: int) -> bool:
        """May ratio k_input sit just before (on the input side of) ratio k_output?"""
        if self.order_key is None:
            return True
        a, b = self.order_key[k_input], self.order_key[k_output]
        return a > b or (a == b and k_input <= k_output)

    def _prefix_best(self) -> list[tuple[np.ndarray, np.ndarray]]:
        """For r = 1, 2, ...: sorted ln(product) of the first r stages and the least objective
        sum_(j<r) F_j(u_j) / (u_j ... u_(r-1)) over the sequences with that product.

        Adding stage r - 1 with ratio u divides every earlier term by u and adds F(u)/u, so
        best_r(P) = min_u [best_(r-1)(P/u) + F_(r-1)(u)] / u.  Products equal to 1e-9 in ln
        share an entry (their minimum), which keeps every value a lower bound.
        """
        out: list[tuple[np.ndarray, np.ndarray]] = []
        log_r = np.array(self.log_r)
        r_arr = np.array(self.r)
        prev_log, prev_val = np.zeros(1), np.zeros(1)
        for depth in range(min(self.table_depth, self.n - 1)):
            F = np.array(self.F[depth])
            logs = (prev_log[None, :] + log_r[:, None]).ravel()
            vals = ((prev_val[None, :] + F[:, None]) / r_arr[:, None]).ravel()
            keys = np.round(logs * 1e9).astype(np.int64)
            uniq, inverse = np.unique(keys, return_inverse=True)
            best = np.full(len(uniq), np.inf)
            np.minimum.at(best, inverse, vals)
            first_log = np.zeros(len(uniq))
            first_log[inverse] = logs
            if len(uniq) > _TABLE_SIZE:
                break
            prev_log, prev_val = first_log, best
            out.append((prev_log, prev_val))
        return out

    def prefix_bound(self, r: int, low: float, high: float) -> float | None:
        """The least objective of the first r stages with ln(product) in [low, high] (inf if none), or None beyond the tables."""
        if r == 0 or r > len(self.prefix_best):
            return None
        logs, vals = self.prefix_best[r - 1]
        a = int(np.searchsorted(logs, low - 1e-9))
        b = int(np.searchsorted(logs, high + 1e-9, side="right"))
        return float(vals[a:b].min()) if b > a else math.inf

    def table(self, r: int, k: int) -> np.ndarray:
        """Sorted ln-products of every multiset of r stages taken from indices >= k."""
        key = (r, k)
        if key not in self._tables:
            if r == 0:
                value = np.zeros(1)
            else:
                parts = [self.log_r[j] + self.table(r - 1, j) for j in range(k, len(self.r))]
                value = np.sort(np.concatenate(parts)) if parts else np.zeros(0)
            self._tables[key] = value
        return self._tables[key]

    def completes(self, r: int, k: int, low: float, high: float) -> bool:
        """Can r more stages (indices >= k) bring ln of the product into [low, high]?"""
        if r <= self.table_depth:
            t = self.table(r, k)
            i = int(np.searchsorted(t, low - 1e-12))
            return i < len(t) and t[i] <= high + 1e-12
        return r * min(self.log_r[k:]) <= high + 1e-12 and r * max(self.log_r[k:]) >= low - 1e-12

    def nearest_gap(self, r: int, k: int, need: float) -> float:
        """The least |ln(product) - need| that r more stages (indices >= k) can reach (a lower bound beyond the tables)."""
        if r <= self.table_depth:
            t = self.table(r, k)
            i = int(np.searchsorted(t, need))
            near = [abs(t[j] - need) for j in (i - 1, i) if 0 <= j < len(t)]
            return min(near) if near else math.inf
        lo, hi = r * min(self.log_r[k:]), r * max(self.log_r[k:])
        return max(0.0, lo - need, need - hi)

    # -- progress: fraction of the first two levels done
    def _tick(self, k0: int, k1: int) -> None:
        if self.progress is None:
            return
        now = time.perf_counter()
        if now - self.last_report > 0.2:
            self.last_report = now
            m = len(self.r)
            self.progress((k0 + k1 / m) / m, self.nodes)

    def _term(self, i: int, k: int, chosen: dict[int, int]) -> float:
        """Stage i's contribution with u_i = ratio k and the later stages in ``chosen``."""
        e = self.exponents[i]
        value = self.F[i][k]
        for j in range(i, self.n):
            if e[j]:
                value *= (self.r[k] if j == i else self.r[chosen[j]]) ** e[j]
        return value

    def _bound(self, i_next: int, chosen: dict[int, int]) -> float:
        """A lower bound on the objective of stages 0..i_next (not chosen yet)."""
        total = 0.0
        for j in range(i_next + 1):
            e = self.exponents[j]
            b = self.min_self[j]
            for l in range(j + 1, self.n):
                if e[l]:
                    b *= self.r[chosen[l]] ** e[l] if l > i_next else self.min_pow[e[l]]
            total += b
        return total

    def run_tolerance(self, U: Fraction, tol: Fraction) -> list[tuple[float, tuple[int, ...]]]:
        lo_f, hi_f = float(U * (1 - tol)), float(U * (1 + tol))
        lo_x, hi_x = U * (1 - tol), U * (1 + tol)
        asc = sorted(range(len(self.r)), key=lambda k: self.r[k])
        asc_r = [self.r[k] for k in asc]
        log_lo, log_hi = math.log(lo_f), math.log(hi_f) if hi_f > 0 else -math.inf
        best: dict[Any, tuple[float, tuple[int, ...]]] = {}
        threshold = [math.inf]
        n = self.n

        def record(obj: float, design: tuple[int, ...]) -> None:
            key = tuple(sorted(design)) if self.distinct else design
            old = best.get(key)
            if old is None or obj < old[0]:
                best[key] = (obj, design)
                if len(best) >= self.top:
                    values = heapq.nsmallest(self.top, (v[0] for v in best.values()))
                    threshold[0] = values[-1]
                    if len(best) > 4 * self.top:
                        keep = heapq.nsmallest(self.top, best.items(), key=lambda kv: kv[1][0])
                        best.clear()
                        best.update(keep)

        def visit(i: int, chosen: dict[int, int], Q: float, Qx: Fraction, partial: float, top_index: tuple[int, int]) -> None:
            # stages i+1..n-1 chosen (0-based), product Q; now choose stage i
            remaining = i  # stages after this one still to choose: 0..i-1
            if i == 0:
                lo_u, hi_u = lo_f / Q, hi_f / Q
                a = bisect_left(asc_r, lo_u * (1 - 1e-12))
                b = bisect_right(asc_r, hi_u * (1 + 1e-12))
                for k in asc[a:b]:
                    self.nodes += 1
                    if n > 1 and not self.in_order(k, chosen[1]):
                        continue
                    if not lo_x <= Qx * self.exact[k] <= hi_x:
                        continue
                    chosen[0] = k
                    obj = partial + self._term(0, k, chosen)
                    if obj <= threshold[0] * (1 + 1e-12):
                        record(obj, tuple(chosen[j] for j in range(n)))
                chosen.pop(0, None)
                return
            for k in range(len(self.r)):
                self.nodes += 1
                if i < n - 1 and not self.in_order(k, chosen[i + 1]):
                    continue
                if i == n - 1:
                    top_index = (k, 0)
                elif i == n - 2:
                    top_index = (top_index[0], k)
                    self._tick(*top_index)
                q = Q * self.r[k]
                lq = math.log(q)
                chosen[i] = k
                part = partial + self._term(i, k, chosen)
                exact_tail = self.prefix_bound(remaining, log_lo - lq, log_hi - lq)
                if exact_tail is not None:
                    if exact_tail == math.inf or part + exact_tail / q * (1 - 1e-12) > threshold[0] * (1 + 1e-12):
                        continue
                elif not self.completes(remaining, 0, log_lo - lq, log_hi - lq):
                    continue
                elif part + self._bound(i - 1, chosen) > threshold[0] * (1 + 1e-12):
                    continue
                visit(i - 1, chosen, q, Qx * self.exact[k], part, top_index)
            chosen.pop(i, None)

        visit(n - 1, {}, 1.0, Fraction(1), 0.0, (0, 0))
        return sorted(best.values())[: self.top]

    def nearest_multisets(self, U: Fraction) -> list[tuple[int, ...]]:
        """The ``top`` multisets of stages whose product is nearest the target in |ln(total/U)|."""
        logU = math.log(float(U))
        found: list[tuple[float, tuple[int, ...]]] = []  # max-heap by gap (negated)
        n, top = self.n, self.top

        def threshold() -> float:
            return -found[0][0] if len(found) >= top else math.inf

        def visit(start: int, picked: list[int], logQ: float) -> None:
            rem = n - len(picked) - 1
            for k in range(start, len(self.r)):  # ratios descending: later picks are not larger
                self.nodes += 1
                lq = logQ + self.log_r[k]
                gap = self.nearest_gap(rem, k, logU - lq)
                if gap > threshold() * (1 + 1e-12) + 1e-15:
                    continue
                if rem == 0:
                    item = (-gap, tuple(picked + [k]))
                    if len(found) < top:
                        heapq.heappush(found, item)
                    elif gap < threshold():
                        heapq.heapreplace(found, item)
                else:
                    visit(k, picked + [k], lq)

        visit(0, [], 0.0)
        return [m for _, m in sorted(found, key=lambda t: -t[0])]

    def orders(self, multiset: Sequence[int]) -> list[tuple[float, tuple[int, ...]]]:
        """The orders of a multiset of stages worth listing (all, or the best one), with objectives."""
        from itertools import permutations

        out = []
        if self.order_key is not None:  # the best order sorts the stages by the swap key
            key = self.order_key
            orders = [tuple(sorted(multiset, key=lambda k: (-key[k], k)))]
        else:
            orders = list(set(permutations(multiset)))
        for order in orders:
            chosen = dict(enumerate(order))
            out.append((sum(self._term(i, chosen[i], chosen) for i in range(self.n)), order))
        return sorted(out)


def best_designs(total: Any, stage_set: Any, stages: int, *, model: Any, tolerance: Any, top: int = 10,
                 lower: Any = None, upper: Any = None, distinct: bool = True,
                 progress: Callable[[float, int], None] | None = None) -> DiscreteSplit:
    """The best discrete designs: every stage from ``stage_set``, the total within ``tolerance``.

    Parameters
    ----------
    total : number
        The target total ratio U.
    stage_set : symkin.stages.StageSet or sequence of Stage
        The feasible stages (e.g. :func:`symkin.stages.enumerate_stages`).
    stages : int
        Number of stages n.
    model : StageErrorModel or sequence
    tolerance : number
        Relative tolerance on the total: |total - U| <= tolerance * U.
    top : int
        How many designs to return.
    lower, upper : number, optional
        Keep only stages with ratios in these bounds (default: all).
    distinct : bool
        Show each multiset of stages once, in its best order (default); False lists every order.
    progress : callable(fraction, nodes), optional
        Called at most every 0.2 s during the search.

    Returns
    -------
    DiscreteSplit
        Designs ranked by the exact objective; when no design meets the tolerance,
        ``meets_tolerance`` is False and the designs nearest the target are returned.

    Examples
    --------
    >>> from symkin.stages import enumerate_stages
    >>> from symkin.lostmotion import StageErrorModel
    >>> found = enumerate_stages(72, 3, zmin=12, zmax=72)
    >>> r = best_designs(20, found, 2, model=StageErrorModel.linear(1, 1), tolerance="0.05", top=3)
    >>> r.meets_tolerance, [d.ratios for d in r.designs], [d.objective for d in r.designs]
    (True, [(3, 7), (19/7, 7), (4, 5)], [4/3, 178/133, 29/20])
    >>> r = best_designs(30, enumerate_stages(60, 3, zmin=12), 2, model=StageErrorModel.linear(1, 1), tolerance="0.05")
    >>> r.meets_tolerance, r.designs[0].ratios, r.designs[0].total
    (False, (13/3, 6), 26)
    """
    stage_list = list(getattr(stage_set, "stages", stage_set))
    if not stage_list:
        raise InputError("no feasible stages were given; enumerate them with symkin.stages.enumerate_stages")
    if isinstance(top, bool) or not isinstance(top, (int, sp.Integer)) or int(top) < 1:
        raise InputError(f"top must be a positive whole number, got {top!r}")
    tol = _rational(tolerance, "the tolerance")
    if tol < 0:
        raise InputError(f"the tolerance must not be negative, got {tol}")
    if tol >= 1:
        raise InputError(f"the tolerance is relative (0.01 = 1%) and must be below 1, got {tol}")
    ratios = [s.ratio for s in stage_list]
    lo = _rational(lower, "the lower bound") if lower is not None else min(ratios)
    hi = _rational(upper, "the upper bound") if upper is not None else max(ratios)
    if lo > hi:
        raise InputError(f"the bounds are reversed: lower {lo} > upper {hi}; give lower <= upper")
    stage_list = [s for s in stage_list if lo <= s.ratio <= hi]
    if not stage_list:
        raise InputError(f"no feasible stage has a ratio between {lo} and {hi}; widen the bounds")
    usable_lo, usable_hi = min(s.ratio for s in stage_list), max(s.ratio for s in stage_list)
    problem = SplitProblem.build(total, stages, lower=usable_lo, upper=usable_hi, model=model)
    search = _Search(problem, stage_list, int(top), distinct, progress)
    U = Fraction(int(problem.total.p), int(problem.total.q))
    found = search.run_tolerance(U, Fraction(int(tol.p), int(tol.q)))
    meets = bool(found)
    if not meets:
        found = []
        for multiset in search.nearest_multisets(U):
            orders = search.orders(multiset)
            found += orders[:1] if distinct else orders
    designs = []
    for _, idx in found:
        chosen = tuple(search.stages[k] for k in idx)
        total_exact = sp.Mul(*[s.ratio for s in chosen])
        designs.append(Design(chosen, total_exact, (total_exact - problem.total) / problem.total,
                              problem.exact_value([s.ratio for s in chosen])))
    if meets:
        designs.sort(key=lambda d: float(d.objective))
    else:
        designs.sort(key=lambda d: (abs(float(d.deviation)), float(d.objective)))
    if progress is not None:
        progress(1.0, search.nodes)
    return DiscreteSplit(problem, tol, tuple(designs[: int(top)]), meets, search.nodes, distinct)
