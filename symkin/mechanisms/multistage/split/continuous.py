"""The continuous split: each u_i in its bounds, the product fixed, solved in ln u.

In x_i = ln u_i the constraint is linear (sum x_i = ln U) and the bounds are boxes;
SciPy's SLSQP solves it from several feasible starts with the exact (symbolic) gradient,
and the result carries its KKT analysis: which bounds are active, their multipliers, and
the derivative of the optimum with respect to ln U.  When the objective is a posynomial
in the u_i (checked symbolically), it is convex in x and the KKT point is the global
minimum.

    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    >>> optimize_split(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1)).active
    ('free', 'upper')
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp

from symkin._util.jsonout import exact_json, exact_json_list
from symkin.errors import SymkinError
from symkin.mechanisms.multistage.lostmotion import StageErrorModel  # noqa: F401  (the doctests use it)
from symkin.mechanisms.multistage.split.problem import _BOUND_TOL, SplitProblem

__all__ = ["ContinuousSplit", "optimize_split", "solve_continuous", "profile"]


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
        The largest violation of stationarity or multiplier sign, relative to ``|g|``.
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

        >>> r = optimize_split(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
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
        """The optimum as JSON: ratios (exact where known), objective, active bounds, multipliers and the KKT residual."""
        return {
            "ratios": list(self.ratios),
            "exact_ratios": exact_json_list(self.exact_ratios),
            "objective": self.objective,
            "exact_objective": exact_json(self.exact_objective),
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


def _minimize(problem: SplitProblem, lo: np.ndarray, hi: np.ndarray, L: float) -> tuple[np.ndarray, int, str]:
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


def solve_continuous(problem: SplitProblem) -> ContinuousSplit:
    """The continuous optimum of a built problem, with its KKT analysis.

    >>> p = SplitProblem.build(1000, 3, lower=2, upper=12, model=StageErrorModel.linear(1, 1))
    >>> solve_continuous(p).exact_ratios
    (125/18, 12, 12)
    """
    lo = np.array([math.log(float(v)) for v in problem.lower])
    hi = np.array([math.log(float(v)) for v in problem.upper])
    L = math.log(float(problem.total))
    x, starts, method = _minimize(problem, lo, hi, L)
    active, g, nu, mult, resid = _kkt(problem, x, lo, hi)
    exact, exact_obj = _exact(problem, active)
    ratios = tuple(float(v) for v in np.exp(x))
    obj = problem.value(ratios)
    if exact is not None:
        assert exact_obj is not None  # _exact gives both or neither
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


def _exact(
    problem: SplitProblem, active: Sequence[str]
) -> tuple[tuple[sp.Rational, ...], sp.Expr] | tuple[None, None]:
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
    ratios = tuple(values)  # every stage has its ratio now: the one free stage, if any, was set above
    return ratios, problem.exact_value(ratios)


def optimize_split(total: Any, stages: int, *, lower: Any, upper: Any, model: Any) -> ContinuousSplit:
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
    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    >>> r = optimize_split(1000, 3, lower=2, upper=12, model=StageErrorModel.linear(1, 1))
    >>> r.exact_ratios, r.active, r.global_optimum
    ((125/18, 12, 12), ('free', 'upper', 'upper'), True)
    """
    return solve_continuous(SplitProblem.build(total, stages, lower=lower, upper=upper, model=model))


def profile(problem: SplitProblem, stage: int, values: Iterable[float]) -> np.ndarray:
    """The least objective with u_stage held at each value (nan where infeasible).

    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
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
        xs, _, _ = _minimize(problem, lo, hi, L)
        out.append(problem.value(np.exp(xs)))
    return np.array(out, dtype=float)

