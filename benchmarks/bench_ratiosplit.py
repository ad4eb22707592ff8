"""How long the lost-motion derivation and the discrete ratio-split search take as n grows.

Run on demand (not a test):  python benchmarks/bench_ratiosplit.py [--repeat 3]

For each n: the symbolic derivation of the n-stage lost-motion law from the engine
(lost_motion(n), first call, uncached by clearing the cache), and the branch-and-bound
search over the 22 stages of a 180-tooth ring with 3 satellites (z >= 18), total
ratio 5.5^n (so the split stays inside the stages' range), tolerance 1%, top 10, linear
model Phi/d = 0.854 + 0.858 u, against the 22^n designs a plain enumeration would visit.
Then harder cases (a quadratic and a falling model, tolerance 0 where only the nearest
designs exist).  Medians of --repeat runs; the machine is shared, so compare ratios,
not absolute times.
"""

from __future__ import annotations

import argparse
import statistics
import time
from fractions import Fraction

from symkin import parse
from symkin.mechanisms.multistage import StageErrorModel, best_designs, enumerate_stages, lost_motion
from symkin.mechanisms.multistage.lostmotion import U


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--max-stages", type=int, default=8)
    args = parser.parse_args()
    stages = enumerate_stages(180, 3, zmin=18, zmax=180)
    model = StageErrorModel.linear(Fraction("0.854"), Fraction("0.858"))
    print(f"{'n':>2} {'derive s':>9} {'search s':>9} {'nodes':>8} {'22^n':>12} {'nodes/22^n':>11}  best design")
    for n in range(2, args.max_stages + 1):
        derive, search, nodes = [], [], 0
        for _ in range(args.repeat):
            lost_motion.cache_clear()
            t = time.perf_counter()
            lost_motion(n)
            derive.append(time.perf_counter() - t)
            t = time.perf_counter()
            result = best_designs(Fraction(11, 2)**n, stages, n, model=model, tolerance=Fraction(1, 100), top=10)
            search.append(time.perf_counter() - t)
            nodes = result.nodes
        best = result.designs[0]
        print(f"{n:>2} {statistics.median(derive):9.2f} {statistics.median(search):9.3f} {nodes:>8} {22**n:>12} "
              f"{nodes / 22**n:11.2e}  {' '.join(map(str, best.ratios))} ({float(best.deviation):+.2%})")
    print()
    print("harder cases: total 5.5^n + 0.37 (tolerance 0 has no design: the nearest ones are searched)")
    print(f"{'model':>16} {'n':>2} {'tol':>6} {'search s':>9} {'nodes':>8}  in tolerance")
    for text in ("0.854 + 0.858*u", "u**2", "1 + 5/u"):
        m = StageErrorModel(parse(text, symbols={"u": U}))
        for n in range(4, args.max_stages + 1, 2):
            lost_motion(n)
            for tol in (Fraction(0), Fraction("0.001"), Fraction("0.1")):
                times = []
                for _ in range(args.repeat):
                    t = time.perf_counter()
                    result = best_designs(Fraction(11, 2)**n + Fraction(37, 100), stages, n, model=m, tolerance=tol, top=10)
                    times.append(time.perf_counter() - t)
                print(f"{text:>16} {n:>2} {float(tol):>6g} {statistics.median(times):9.3f} {result.nodes:>8}  {result.meets_tolerance}")


if __name__ == "__main__":
    main()
