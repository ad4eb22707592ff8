"""Tooth-number synthesis of any train: the pruned search against making every tuple, and the
search on Dask with one and two workers.

Run: python benchmarks/synthesis.py [repeats]

1. Pruning, side by side in one run: ``synthesize`` (coaxiality solved for the ring, the ratio
   window solved for one pinion) and the same checks on every tuple of the five tooth numbers
   in the limits (``check_batch`` of the plan on the whole box).  Both must find the same designs;
   prints medians and the ratio.
2. Ravigneaux up to 150 teeth (the issue's large space), two requests: the search here, and on
   local Dask clusters of one and two worker processes (started once, before timing; the
   workers rebuild the compiled plan on their first chunk, so a warm-up run comes first).
   Runs are interleaved; medians of ``repeats`` and the ratio 1 worker / 2 workers.
3. The same at 200 teeth (the largest that fits a sensible time here).
4. Ranking by efficiency: the second-gear request (its efficiency law is a Piecewise in the
   teeth) ranked by error and by efficiency, interleaved; medians and the ratio.

``python benchmarks/synthesis.py [repeats] [rank]``: only part 4 with ``rank``.
"""

from __future__ import annotations

import statistics
import sys
import time
from fractions import Fraction

import numpy as np

from symkin.synthesis import synthesize
from symkin.synthesis.api import _plan
from symkin.synthesis.funnel import check_batch
from symkin.synthesis.problem import derive
from symkin.synthesis.request import Target

FIRST = dict(driver="S1", driven="R", fixed="C", ratio=Fraction(12, 5), tolerance=Fraction(1, 200), planets=3)
SECOND = dict(state="second", ratio=Fraction(22, 15), tolerance=Fraction(1, 50), planets=3)


def every_tuple(zmax: int, request: dict) -> tuple[set, int]:
    """The plan's own checks on every tuple of the five tooth numbers (no pruning): the
    coaxiality rows evaluated on each, then ``check_batch`` (ratio, internal gears, assembly,
    neighbours, placement)."""
    import symkin

    kw = {k: v for k, v in request.items() if k not in ("ratio", "tolerance")}
    planets = kw.pop("planets")
    problem = derive(symkin.load_train("ravigneaux"), planets=planets, zmax=zmax, **kw)
    plan = _plan(problem, Target.of(request["ratio"], request["tolerance"]), None, 1 << 15)
    rows = symkin.compile([row.expr for row in problem.coaxiality], list(problem.unknowns), backend="numpy", stable=False)
    names = plan.unknowns
    teeth = np.arange(problem.options.zmin, zmax + 1)
    grid = np.stack(np.meshgrid(*([teeth] * (len(names) - 1)), indexing="ij"), axis=-1).reshape(-1, len(names) - 1)
    found: set = set()
    made = 0
    for z0 in teeth:  # one plane of tuples at a time
        cols = {names[0]: np.full(len(grid), z0, dtype=np.int64)}
        cols |= {n: grid[:, i].astype(np.int64) for i, n in enumerate(names[1:])}
        made += len(grid)
        values = rows(*[cols[n].astype(float) for n in names])
        values = values if isinstance(values, tuple) else (values,)
        coaxial = np.logical_and.reduce([np.asarray(v) == 0 for v in values])
        cols = {n: c[coaxial] for n, c in cols.items()}
        _, records, _, _ = check_batch(plan, (cols,), [0])
        found |= {r.teeth for r in records}
    return found, made


def timed(f, *args, **kw):
    start = time.perf_counter()
    out = f(*args, **kw)
    return time.perf_counter() - start, out


def pruning(repeats: int) -> None:
    zmax = 60
    request = dict(FIRST, tolerance=Fraction(1, 50))
    synthesize("ravigneaux", zmax=zmax, top=None, **request)  # derive and compile once
    pruned, plain = [], []
    for _ in range(repeats):
        t, res = timed(synthesize, "ravigneaux", zmax=zmax, top=None, **request)
        pruned.append(t)
        t, (found, made) = timed(every_tuple, zmax, request)
        plain.append(t)
        assert found == {tuple(d.values[n] for n in map(str, res.problem.unknowns)) for d in res.designs}
    mp, mb = statistics.median(pruned), statistics.median(plain)
    print(f"Ravigneaux, i = 12/5 +- 2 %, k = 3, 18 <= z <= {zmax}: {made} tuples of five tooth numbers, "
          f"{res.made} made by the pruned search, {res.found} designs; median of {repeats}:")
    print(f"  pruned search (derivation cached)  {mp:8.3f} s")
    print(f"  the same checks on every tuple     {mb:8.3f} s   ({mb / mp:.0f} x)")


def scaling(zmax: int, request: dict, repeats: int, label: str) -> None:
    from symkin.synthesis.runner import local_cluster

    clusters = {n: local_cluster(n) for n in (1, 2)}
    try:
        kw = dict(zmax=zmax, top=10, **request)
        res = synthesize("ravigneaux", **kw)  # derive and compile here once
        for c in clusters.values():  # the workers rebuild the plan once
            synthesize("ravigneaux", scheduler=c.scheduler_address, **kw)
        times: dict[str, list[float]] = {"here": [], "1 worker": [], "2 workers": []}
        for _ in range(repeats):
            for name, sched in (("here", None), ("1 worker", clusters[1].scheduler_address),
                                ("2 workers", clusters[2].scheduler_address)):
                r = synthesize("ravigneaux", scheduler=sched, **kw)
                assert [d.gear_teeth for d in r.designs] == [d.gear_teeth for d in res.designs] and r.found == res.found
                times[name].append(r.execution["seconds"])
        med = {k: statistics.median(v) for k, v in times.items()}
        space = (zmax - 18 + 1) ** 5
        print(f"{label}, 18 <= z <= {zmax} ({space:.2e} tuples of five tooth numbers; {res.search.split(',')[0]}; "
              f"{res.made} made, {res.found} designs, {res.execution['chunks']} chunks); search seconds, median of "
              f"{repeats}:")
        for k, v in med.items():
            print(f"  {k:10s} {v:8.3f} s   (min {min(times[k]):.3f}, max {max(times[k]):.3f})")
        print(f"  1 worker / 2 workers: {med['1 worker'] / med['2 workers']:.2f} x;  here / 2 workers: "
              f"{med['here'] / med['2 workers']:.2f} x")
    finally:
        for c in clusters.values():
            c.close()


def ranking(zmax: int, request: dict, repeats: int, label: str) -> None:
    kw = dict(zmax=zmax, top=10, **request)
    plain = synthesize("ravigneaux", **kw)  # derive and compile both plans once
    ranked = synthesize("ravigneaux", rank="efficiency", **kw)
    assert plain.found == ranked.found
    times: dict[str, list[float]] = {"by error": [], "by efficiency": []}
    for _ in range(repeats):
        for name, rank in (("by error", None), ("by efficiency", "efficiency")):
            t, _ = timed(synthesize, "ravigneaux", rank=rank, **kw)
            times[name].append(t)
    med = {k: statistics.median(v) for k, v in times.items()}
    print(f"{label}, 18 <= z <= {zmax}: {plain.found} designs; seconds, median of {repeats}:")
    for k, v in med.items():
        print(f"  {k:14s} {v:8.3f} s   (min {min(times[k]):.3f}, max {max(times[k]):.3f})")
    per = (med["by efficiency"] - med["by error"]) / plain.found * 1e6
    print(f"  by efficiency / by error: {med['by efficiency'] / med['by error']:.2f} x  ({per:.1f} us per design)")
    print(f"  best by efficiency: {ranked.designs[0].gear_teeth} eta = {float(ranked.designs[0].ranked_efficiency):.5f};"
          f" best by error: {plain.designs[0].gear_teeth} eta = {float(plain.designs[0].efficiency()):.5f}")


def main(repeats: int = 3, only: str = "") -> None:
    with open("/proc/loadavg") as f:
        print(f"load average before: {f.read().split()[:3]} on {__import__('os').cpu_count()} cores")
    if only == "rank":
        ranking(150, SECOND, repeats, "Ravigneaux second gear, i = 22/15 +- 2 %, k = 3")
        return
    pruning(repeats)
    scaling(150, FIRST, repeats, "Ravigneaux first gear, i = 12/5 +- 0.5 %, k = 3")
    scaling(150, SECOND, repeats, "Ravigneaux second gear, i = 22/15 +- 2 %, k = 3")
    scaling(200, SECOND, repeats, "Ravigneaux second gear, i = 22/15 +- 2 %, k = 3")
    ranking(150, SECOND, repeats, "Ravigneaux second gear, i = 22/15 +- 2 %, k = 3")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3, sys.argv[2] if len(sys.argv) > 2 else "")
