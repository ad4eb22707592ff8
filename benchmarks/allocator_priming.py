"""Does the NumPy backend's allocator priming (``backends/numpy.py``, ``_prime_allocator``) matter?

    python benchmarks/allocator_priming.py [--rounds 3] [--sizes 100000,1000000] [--laws "II differential, radii"]

Each law and size in a fresh process, ``backend="numpy"``, with the priming and without it (the
function replaced by one that does nothing), in alternation; a process calls the law 15 times.
Prints the median over rounds of each process's median call after the first, and of the first
call (milliseconds).  benchmarks/notes/numeric-backends.md holds a run.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
LAWS = ("AA ratio, teeth", "II differential, radii", "planet acceleration w_x", "slider acceleration a_s")


def child(primed: bool, n: int, law: str) -> None:
    sys.path.insert(0, str(HERE))
    import laws as L

    import symkin
    from symkin.numeric.backends import numpy as numpy_backend

    if not primed:
        numpy_backend._prime_allocator = lambda: None
    expr, args, values = L.timed_cases(n)[law]
    f = symkin.compile(expr, args, backend="numpy", ranges=L.RANGES)
    times = []
    for _ in range(15):
        t0 = time.perf_counter()
        f(*values)
        times.append(time.perf_counter() - t0)
    print(json.dumps(dict(first=times[0], median=statistics.median(times[1:]))))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--sizes", default="100000,1000000")
    ap.add_argument("--laws", default=";".join(LAWS), help="law names separated by ;")
    ap.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    opts = ap.parse_args()
    if opts.child:
        return child(opts.child[0] == "1", int(opts.child[1]), opts.child[2])
    cells: dict[tuple[str, int, str], list[dict]] = {}
    load0 = os.getloadavg()[0]
    for _ in range(opts.rounds):
        for law in opts.laws.split(";"):
            for n in map(int, opts.sizes.split(",")):
                for primed in ("1", "0"):
                    out = subprocess.run([sys.executable, __file__, "--child", primed, str(n), law], capture_output=True,
                                         text=True, check=True).stdout
                    cells.setdefault((law, n, primed), []).append(json.loads(out.strip().splitlines()[-1]))
    print(f"load {load0:.1f} -> {os.getloadavg()[0]:.1f}; {opts.rounds} rounds; milliseconds")
    print("| law | points | primed | not primed | not / primed | first call, primed | not primed | not / primed |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for (law, n, primed), rows in cells.items():
        if primed == "0":
            continue
        p, q = rows, cells[(law, n, "0")]
        m = [statistics.median(r[key] for r in side) * 1e3 for key in ("median", "first") for side in (p, q)]
        print(f"| {law} | {n:.0e} | {m[0]:.2f} | {m[1]:.2f} | {m[1] / m[0]:.2f} | {m[2]:.2f} | {m[3]:.2f} | {m[3] / m[2]:.2f} |")


if __name__ == "__main__":
    sys.exit(main())
