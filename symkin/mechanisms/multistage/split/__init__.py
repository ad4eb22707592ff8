"""Split a total ratio over the stages of a common-ring train for the least lost motion.

The objective is the derived lost motion at the output (:mod:`symkin.mechanisms.multistage.lostmotion`) with a
stage error model Phi/d(u).  Two problems are solved:

- *continuous*: each u_i in its bounds, the product of the u_i fixed.  In x_i = ln u_i
  the constraint is linear (sum x_i = ln U) and the bounds are boxes; SciPy's SLSQP
  solves it from several feasible starts with the exact (symbolic) gradient, and the
  result carries its KKT analysis: which bounds are active, their multipliers, and the
  derivative of the optimum with respect to ln U.  When the objective is a posynomial
  in the u_i (checked symbolically), it is convex in x and the KKT point is the global
  minimum.
- *discrete*: each stage taken from a set of feasible stages (:mod:`symkin.mechanisms.multistage.stages`),
  the total ratio within a relative tolerance; a depth-first branch and bound from the
  output stage ranks the designs by the objective, exactly.  When no design meets the
  tolerance, the nearest designs are returned instead, and the result says so.

    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    >>> best = optimize_split(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
    >>> best.exact_ratios, best.active
    ((5, 20), ('free', 'upper'))

The problem (:mod:`.problem`), the continuous solver (:mod:`.continuous`) and the
discrete search (:mod:`.discrete`) are separate modules; every public name is importable
from here.
"""

from __future__ import annotations

from symkin.mechanisms.multistage.split.continuous import (
    ContinuousSplit,
    optimize_split,
    profile,
    solve_continuous,
)
from symkin.mechanisms.multistage.split.discrete import (
    DiscreteSplit,
    SplitDesign,
    best_designs,
)
from symkin.mechanisms.multistage.split.problem import MAX_STAGES, SplitProblem

_solve = solve_continuous  # the former private name

__all__ = [
    "SplitProblem",
    "ContinuousSplit",
    "SplitDesign",
    "DiscreteSplit",
    "optimize_split",
    "solve_continuous",
    "profile",
    "best_designs",
    "MAX_STAGES",
]
