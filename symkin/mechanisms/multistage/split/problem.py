"""The ratio-split problem: the objective over the stage ratios, its bounds and models.

The objective is the derived lost motion at the output (:mod:`symkin.mechanisms.multistage.lostmotion`) with a
stage error model Phi/d(u) per stage, compiled once for the solvers.

    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    >>> p = SplitProblem.build(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
    >>> p.exact_value([5, 20])
    111/100
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import sympy as sp

from symkin._util.budget import simplify_within
from symkin.errors import InputError
from symkin.mechanisms.multistage.lostmotion import (
    LostMotion,
    StageErrorModel,
    lost_motion,
)
from symkin.numeric import NumericFunction, compile
from symkin.values import as_rational

__all__ = ["SplitProblem", "MAX_STAGES"]

#: The most stages a split problem takes (the symbolic derivation grows fast with the train).
MAX_STAGES = 20

_BOUND_TOL = 1e-7  # in ln u: a stage this close to a bound is on it
_TABLE_SIZE = 200_000  # largest table of completion products the discrete search keeps per depth


# --------------------------------------------------------------------------- inputs
def _models(model: Any, n: int) -> tuple[StageErrorModel, ...]:
    """One stage error model per stage, from one model or ``n`` of them."""
    if isinstance(model, StageErrorModel):
        return (model,) * n
    try:
        models = tuple(model)
    except TypeError:
        raise InputError(f"model must be a StageErrorModel or one per stage, got {model!r}") from None
    if len(models) != n or not all(isinstance(m, StageErrorModel) for m in models):
        raise InputError(f"give one StageErrorModel or {n} of them, got {model!r}")
    return models


def _per_stage(value: Any, n: int, what: str) -> tuple[sp.Rational, ...]:
    if isinstance(value, (list, tuple)):
        if len(value) != n:
            raise InputError(f"{what} gives {len(value)} values for {n} stages; give one value or one per stage")
        return tuple(as_rational(v, what=f"{what} of stage {i}") for i, v in enumerate(value, 1))
    return (as_rational(value, what=what),) * n


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
    def build(cls, total: Any, stages: int, *, lower: Any, upper: Any, model: Any) -> SplitProblem:
        """Check the inputs and build the problem.

        ``lower``/``upper`` are one value or one per stage; ``model`` one
        :class:`~symkin.mechanisms.multistage.lostmotion.StageErrorModel` or one per stage.

        >>> SplitProblem.build(100, 2, lower=12, upper=20, model=StageErrorModel.linear(1, 1))
        Traceback (most recent call last):
        ...
        symkin.errors.InputError: the total ratio 100 is outside what 2 stages with these bounds allow (144 to 400); change the total, the bounds or the number of stages
        """
        if isinstance(stages, bool) or not isinstance(stages, (int, sp.Integer)) or not 1 <= int(stages) <= MAX_STAGES:
            raise InputError(f"the number of stages must be a positive whole number, at most {MAX_STAGES}, got {stages!r}")
        n = int(stages)
        U = as_rational(total, what="the total ratio")
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
        models = _models(model, n)
        for m, a, b in zip(models, lo, hi):
            m.check_positive(a, b)
        return cls(U, n, lo, hi, models)

    # ---- derived, compiled once
    @cached_property
    def lost_motion(self) -> LostMotion:
        """The lost-motion laws of a train with this many stages (derived from the engine, cached)."""
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
    def _f(self) -> NumericFunction:
        """The objective compiled (float64), for the solvers."""
        return compile(self.objective, self.lost_motion.ratios, backend="numpy")

    @cached_property
    def _g(self) -> NumericFunction:
        """The log-gradient compiled (float64), for the solvers."""
        return compile(list(self.log_gradient), self.lost_motion.ratios, backend="numpy")

    def value(self, ratios: Sequence[Any]) -> float:
        """The objective at a split (floats)."""
        return float(self._f(*[float(r) for r in ratios]))

    def exact_value(self, ratios: Sequence[Any]) -> sp.Expr:
        """The objective at a split, exactly (rationals in, a rational out for rational models)."""
        subs = {u: r if isinstance(r, sp.Basic) else as_rational(r, what="a stage ratio") for u, r in zip(self.lost_motion.ratios, ratios)}
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

