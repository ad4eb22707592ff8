"""The search: the derived conditions turned into a pruned, chunked enumeration of tooth numbers.

A :class:`~symkin.synthesis.plan.SearchPlan` is built once from a
:class:`~symkin.synthesis.problem.Problem` and a :class:`~symkin.synthesis.request.Target`
(:mod:`symkin.synthesis.plan`):

1. the coaxiality equations are solved for some tooth numbers (the *dependents*: an
   internal gear from its planet and sun, say), each within a slack of a few teeth when
   profile shift is allowed; the others are *free*;
2. the ratio law, with the dependents put in, is linear-fractional in one free tooth
   number ``x`` (ratio laws are, tooth by tooth): for the other free numbers (the *outer*
   tuple) the ratio window gives the values of ``x`` in closed form, so only tuples with
   the ratio are ever made (:mod:`symkin.synthesis.tuples`);
3. every tuple made is checked against the other conditions, vectorised and exactly:
   integers are evaluated in binary floating point only where every value is an integer
   below 2^53 (so exactly), the ratio is reduced to a fraction and compared exactly,
   geometry in scaled integers, and an inequality with sin(pi/k) or a cosine is decided in
   floating point only with a margin, else at 60 digits (:mod:`symkin.synthesis.funnel`).

The outer tuples are numbered; a chunk is a range of those numbers, and
:func:`evaluate_chunk` (a pure function of the plan and the range) returns the count of
tuples that pass each condition and the best designs of the chunk in the one exact order
(ratio error, then size, then tooth sum, then the tooth numbers; or the plan's ``rank``,
efficiency included: :mod:`symkin.synthesis.efficiency`), so any split into
chunks, run anywhere, merges to the same result.

    >>> from symkin.trains import load_train
    >>> from symkin.synthesis.plan import SearchPlan
    >>> from symkin.synthesis.problem import derive
    >>> from symkin.synthesis.request import Target
    >>> plan = SearchPlan.build(derive(load_train("simple"), driver="S", driven="C", fixed="R", planets=3, zmax=80),
    ...                         Target.of(4, 0.01), top=3)
    >>> plan.last, plan.outer, plan.dependents
    ('z_p', ('z_s',), ('z_r',))
    >>> found = evaluate_chunk(plan, 0, plan.size)
    >>> [r.teeth for r in found.top], found.found, found.counts   # made with the ratio, then each condition
    ([(18, 18, 54), (21, 21, 63), (24, 24, 72)], 3, [9, 9, 9, 3, 3, 3])
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from symkin.synthesis.funnel import Record, check_batch
from symkin.synthesis.plan import STAGES, SearchPlan
from symkin.synthesis.tuples import make_tuples

__all__ = ["ChunkResult", "evaluate_chunk", "merge"]


@dataclass
class ChunkResult:
    """What one chunk found (see :func:`evaluate_chunk`)."""

    start: int
    stop: int
    counts: list[int]
    found: int
    top: list[Record]
    reach: tuple[float, float]
    made: int = 0
    exact_calls: int = 0
    seconds: float = 0.0


def evaluate_chunk(plan: SearchPlan, start: int, stop: int) -> ChunkResult:
    """Every tuple of outer numbers ``start`` to ``stop - 1``: the counts of the funnel and the best designs.

    A pure function of its arguments: Dask runs it on any worker.
    """
    began = time.perf_counter()
    counts = [0] * len(STAGES)
    top: list[Record] = []
    found = 0
    reach = (math.inf, -math.inf)
    made = 0
    exact_calls = [0]
    if stop <= start:
        return ChunkResult(start, stop, counts, 0, [], reach, 0, 0, 0.0)
    idx = np.arange(start, stop, dtype=np.int64)
    sizes = [h - lo + 1 for lo, h in zip(plan.lows, plan.highs)]
    if sizes:
        parts = np.unravel_index(idx, sizes)
        outer = [np.asarray(p, dtype=np.int64) + lo for p, lo in zip(parts, plan.lows)]
    else:
        outer = []
    tuples, r_lo, r_hi = make_tuples(plan, outer, len(idx))
    reach = (r_lo, r_hi)
    for batch in tuples:
        made += len(next(iter(batch[0].values())))
        f, rec, c, (lo, hi) = check_batch(plan, batch, exact_calls)
        reach = (min(reach[0], lo), max(reach[1], hi))
        found += f
        for i, n in enumerate(c):
            counts[i] += n
        top = _best(plan, top + rec)
    return ChunkResult(start, stop, counts, found, top, reach, made, exact_calls[0], time.perf_counter() - began)


def _best(plan: SearchPlan, records: list[Record]) -> list[Record]:
    records.sort(key=lambda r: r.key)
    return records if plan.top is None else records[: plan.top]


def merge(plan: SearchPlan, results: Sequence[ChunkResult]) -> ChunkResult:
    """The chunks' results as one (the same for any split of the outer tuples)."""
    counts = [sum(r.counts[i] for r in results) for i in range(len(STAGES))]
    top = _best(plan, [rec for r in results for rec in r.top])
    lo = min((r.reach[0] for r in results), default=math.inf)
    hi = max((r.reach[1] for r in results), default=-math.inf)
    return ChunkResult(min((r.start for r in results), default=0), max((r.stop for r in results), default=0), counts,
                       sum(r.found for r in results), top, (lo, hi), sum(r.made for r in results),
                       sum(r.exact_calls for r in results), sum(r.seconds for r in results))
