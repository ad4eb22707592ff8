"""The discrete split: every stage from a set of feasible stages, the total within a tolerance.

A depth-first branch and bound from the output stage ranks the designs by the objective,
exactly.  When no design meets the tolerance, the nearest designs are returned instead,
and the result says so.
"""

from __future__ import annotations

import heapq
import math
import time
from bisect import bisect_left, bisect_right
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from symkin._util.budget import seconds_limit
from symkin._util.jsonout import exact_json, exact_json_list
from symkin.errors import InputError, TimeLimitError, UnsupportedError
from symkin.mechanisms.multistage.lostmotion import StageErrorModel  # noqa: F401  (the doctests use it)
from symkin.mechanisms.multistage.split.problem import (
    _TABLE_SIZE,
    SplitProblem,
)
from symkin.values import as_rational

__all__ = ["SplitDesign", "DiscreteSplit", "best_designs"]


@dataclass(frozen=True)
class SplitDesign:
    """One discrete design: a feasible stage per position, input stage first.

    Attributes
    ----------
    stages : tuple of symkin.mechanisms.multistage.stages.Stage
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
        """The stage ratios, stage 1 first (exact)."""
        return tuple(s.ratio for s in self.stages)

    def to_json(self) -> dict[str, Any]:
        """The design as JSON: each stage's teeth and ratio, the total, its deviation and the objective."""
        return {
            "stages": [s.to_json() for s in self.stages],
            "teeth": [[s.sun, s.planet, s.ring] for s in self.stages],
            "ratios": exact_json_list(self.ratios),
            "total": exact_json(self.total),
            "deviation": exact_json(self.deviation),
            "objective": exact_json(self.objective),
        }


@dataclass(frozen=True)
class DiscreteSplit:
    """The best discrete designs, or the nearest ones when none meets the tolerance.

    A :class:`~symkin.synthesis.searches.SearchResult`: iterating it gives the designs, and
    :attr:`reason` says that none meets the tolerance when the designs are the nearest ones.

    Attributes
    ----------
    problem : SplitProblem
    tolerance : sympy.Rational
        The relative tolerance on the total ratio.
    designs : tuple of SplitDesign
        Ranked by objective (within tolerance) or by ``|deviation|`` then objective (nearest).
    meets_tolerance : bool
    nodes : int
        Search nodes visited (a measure of the work done).
    distinct : bool
        True when each multiset of stages appears once, in its best order.
    """

    problem: SplitProblem
    tolerance: sp.Rational
    designs: tuple[SplitDesign, ...]
    meets_tolerance: bool
    nodes: int
    distinct: bool

    def __iter__(self) -> Iterator[SplitDesign]:
        return iter(self.designs)

    @property
    def reason(self) -> str:
        """Why no design meets the tolerance (the designs are then the nearest ones); empty when some do."""
        return "" if self.meets_tolerance else self.message()

    def message(self) -> str:
        """One line that says whether the designs meet the tolerance, or which is nearest when none does."""
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
        """The search as JSON: the designs, whether they meet the tolerance, and the nodes searched."""
        return {
            "tolerance": exact_json(self.tolerance),
            "meets_tolerance": self.meets_tolerance,
            "message": self.message(),
            "nodes": self.nodes,
            "distinct": self.distinct,
            "designs": [d.to_json() for d in self.designs],
        }


class _Best:
    """The best designs met so far, each multiset of stages once when ``distinct``, and the objective a
    new design must beat once ``top`` are known."""

    def __init__(self, top: int, distinct: bool) -> None:
        self.top, self.distinct = top, distinct
        self.found: dict[Any, tuple[float, tuple[int, ...]]] = {}
        self.threshold = math.inf

    def record(self, obj: float, design: tuple[int, ...]) -> None:
        key = tuple(sorted(design)) if self.distinct else design
        old = self.found.get(key)
        if old is None or obj < old[0]:
            self.found[key] = (obj, design)
            if len(self.found) >= self.top:
                values = heapq.nsmallest(self.top, (v[0] for v in self.found.values()))
                self.threshold = values[-1]
                if len(self.found) > 4 * self.top:
                    keep = heapq.nsmallest(self.top, self.found.items(), key=lambda kv: kv[1][0])
                    self.found.clear()
                    self.found.update(keep)

    def ranked(self) -> list[tuple[float, tuple[int, ...]]]:
        return sorted(self.found.values())[: self.top]


class _Search:
    """Depth-first branch and bound from the output stage (stage n) to the input (stage 1)."""

    def __init__(self, problem: SplitProblem, stages: Sequence[Any], top: int, distinct: bool,
                 progress: Callable[[float, int], None] | None, time_limit: float | None = None):
        lm = problem.lost_motion
        n = problem.stages
        self.n, self.top, self.distinct, self.progress = n, top, distinct, progress
        self.time_limit, self.started = time_limit, time.perf_counter()
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

    # -- progress: fraction of the first two levels done; the time limit
    def _tick(self, k0: int, k1: int) -> None:
        if self.progress is None and self.time_limit is None:
            return
        now = time.perf_counter()
        m = len(self.r)
        self._check_time(now, (k0 + k1 / m) / m)
        if self.progress is not None and now - self.last_report > 0.2:
            self.last_report = now
            self.progress((k0 + k1 / m) / m, self.nodes)

    def _check_time(self, now: float, fraction: float) -> None:
        if self.time_limit is not None and now - self.started > self.time_limit:
            raise TimeLimitError(f"the split search did {fraction:.0%} ({self.nodes} nodes) in {now - self.started:.1f} s, "
                                 f"more than the time limit of {self.time_limit:g} s; narrow the stage ratio bounds, "
                                 "use fewer stages or raise the time limit")

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
            for k in range(j + 1, self.n):
                if e[k]:
                    b *= self.r[chosen[k]] ** e[k] if k > i_next else self.min_pow[e[k]]
            total += b
        return total

    def run_tolerance(self, U: Fraction, tol: Fraction) -> list[tuple[float, tuple[int, ...]]]:
        """The ``top`` designs of least objective whose total is within ``tol`` of ``U`` (objective, stage indices)."""
        lo_f, hi_f = float(U * (1 - tol)), float(U * (1 + tol))
        lo_x, hi_x = U * (1 - tol), U * (1 + tol)
        asc = sorted(range(len(self.r)), key=lambda k: self.r[k])
        asc_r = [self.r[k] for k in asc]
        log_lo, log_hi = math.log(lo_f), math.log(hi_f) if hi_f > 0 else -math.inf
        best = _Best(self.top, self.distinct)
        n = self.n

        def last(chosen: dict[int, int], Q: float, Qx: Fraction, partial: float) -> None:
            # stages 1..n-1 chosen (0-based), product Q: the input stage brings the total into the window
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
                if obj <= best.threshold * (1 + 1e-12):
                    best.record(obj, tuple(chosen[j] for j in range(n)))
            chosen.pop(0, None)

        def visit(i: int, chosen: dict[int, int], Q: float, Qx: Fraction, partial: float, top_index: tuple[int, int]) -> None:
            # stages i+1..n-1 chosen (0-based), product Q; now choose stage i
            if i == 0:
                last(chosen, Q, Qx, partial)
                return
            remaining = i  # stages after this one still to choose: 0..i-1
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
                    if exact_tail == math.inf or part + exact_tail / q * (1 - 1e-12) > best.threshold * (1 + 1e-12):
                        continue
                elif not self.completes(remaining, 0, log_lo - lq, log_hi - lq) or part + self._bound(i - 1, chosen) > best.threshold * (1 + 1e-12):
                    continue
                visit(i - 1, chosen, q, Qx * self.exact[k], part, top_index)
            chosen.pop(i, None)

        visit(n - 1, {}, 1.0, Fraction(1), 0.0, (0, 0))
        return best.ranked()

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
                if not picked:
                    self._check_time(time.perf_counter(), k / len(self.r))
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
                 progress: Callable[[float, int], None] | None = None, time_limit: float | None = None) -> DiscreteSplit:
    """The best discrete designs: every stage from ``stage_set``, the total within ``tolerance``.

    Parameters
    ----------
    total : number
        The target total ratio U.
    stage_set : symkin.mechanisms.multistage.stages.StageSet or sequence of Stage
        The feasible stages (e.g. :func:`symkin.mechanisms.multistage.stages.enumerate_stages`).
    stages : int
        Number of stages n.
    model : StageErrorModel or sequence
    tolerance : number
        Relative tolerance on the total: ``|total - U| <= tolerance * U``.
    top : int
        How many designs to return.
    lower, upper : number, optional
        Keep only stages with ratios in these bounds (default: all).
    distinct : bool
        Show each multiset of stages once, in its best order (default); False lists every order.
    progress : callable(fraction, nodes), optional
        Called at most every 0.2 s during the search.
    time_limit : float, optional
        Seconds; a longer search raises :class:`~symkin.errors.TimeLimitError`.

    Returns
    -------
    DiscreteSplit
        Designs ranked by the exact objective; when no design meets the tolerance,
        ``meets_tolerance`` is False, ``reason`` says so and the designs nearest the target are
        returned (a :class:`~symkin.synthesis.searches.SearchResult`).

    Examples
    --------
    >>> from symkin.mechanisms.multistage.stages import enumerate_stages
    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    >>> found = enumerate_stages(72, 3, zmin=12, zmax=72)
    >>> r = best_designs(20, found, 2, model=StageErrorModel.linear(1, 1), tolerance=0.05, top=3)
    >>> r.meets_tolerance, [d.ratios for d in r.designs], [d.objective for d in r.designs]
    (True, [(3, 7), (19/7, 7), (4, 5)], [4/3, 178/133, 29/20])
    >>> r = best_designs(30, enumerate_stages(60, 3, zmin=12), 2, model=StageErrorModel.linear(1, 1), tolerance=0.05)
    >>> r.meets_tolerance, r.designs[0].ratios, r.designs[0].total
    (False, (13/3, 6), 26)
    """
    stage_list = list(getattr(stage_set, "stages", stage_set))
    if not stage_list:
        raise InputError("no feasible stages were given; enumerate them with symkin.mechanisms.multistage.enumerate_stages")
    if isinstance(top, bool) or not isinstance(top, (int, sp.Integer)) or int(top) < 1:
        raise InputError(f"top must be a positive whole number, got {top!r}")
    tol = _tolerance(tolerance)
    stage_list = _within(stage_list, lower, upper)
    usable_lo, usable_hi = min(s.ratio for s in stage_list), max(s.ratio for s in stage_list)
    problem = SplitProblem.build(total, stages, lower=usable_lo, upper=usable_hi, model=model)
    search = _Search(problem, stage_list, int(top), distinct, progress, seconds_limit(time_limit))
    U = Fraction(int(problem.total.p), int(problem.total.q))
    found = search.run_tolerance(U, Fraction(int(tol.p), int(tol.q)))
    meets = bool(found)
    if not meets:
        found = []
        for multiset in search.nearest_multisets(U):
            orders = search.orders(multiset)
            found += orders[:1] if distinct else orders
    designs = _ranked(search, problem, found, meets)
    if progress is not None:
        progress(1.0, search.nodes)
    return DiscreteSplit(problem, tol, tuple(designs[: int(top)]), meets, search.nodes, distinct)


def _ranked(search: _Search, problem: SplitProblem, found: list[tuple[float, tuple[int, ...]]],
            meets: bool) -> list[SplitDesign]:
    """The designs found, exact, ranked by the objective (within the tolerance) or by |deviation|, then the
    objective (the nearest ones)."""
    designs = []
    for _, idx in found:
        chosen = tuple(search.stages[k] for k in idx)
        total_exact = sp.Mul(*[s.ratio for s in chosen])
        designs.append(SplitDesign(chosen, total_exact, (total_exact - problem.total) / problem.total,
                                   problem.exact_value([s.ratio for s in chosen])))
    if meets:
        designs.sort(key=lambda d: float(d.objective))
    else:
        designs.sort(key=lambda d: (abs(float(d.deviation)), float(d.objective)))
    return designs


def _tolerance(tolerance: Any) -> sp.Rational:
    tol = as_rational(tolerance, what="the tolerance")
    if tol < 0:
        raise InputError(f"the tolerance must not be negative, got {tol}")
    if tol >= 1:
        raise InputError(f"the tolerance is relative (0.01 = 1%) and must be below 1, got {tol}")
    return tol


def _within(stage_list: list[Any], lower: Any, upper: Any) -> list[Any]:
    """The stages with ratios within the bounds (default: all)."""
    ratios = [s.ratio for s in stage_list]
    lo = as_rational(lower, what="the lower bound") if lower is not None else min(ratios)
    hi = as_rational(upper, what="the upper bound") if upper is not None else max(ratios)
    if lo > hi:
        raise InputError(f"the bounds are reversed: lower {lo} > upper {hi}; give lower <= upper")
    stage_list = [s for s in stage_list if lo <= s.ratio <= hi]
    if not stage_list:
        raise InputError(f"no feasible stage has a ratio between {lo} and {hi}; widen the bounds")
    return stage_list
