"""Per-call cost of symkin's NumPy backend against plain sympy.lambdify, in one run.

    python benchmarks/call_overhead.py [--json FILE]

Laws: AA i_H1^(4) in radii (denominator r1 r3 - r2 r4), AI i_H1^(4) in radii
(r1 r3 + r2 r4, no cancellation), and AA i_1H^(4) in tooth numbers fed as int64 and as
float64 arrays.  Medians of repeated calls at 10^3, 10^5 and 10^7 points (microseconds),
and the ratio symkin / lambdify.  The inputs stay away from poles.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time

import numpy as np
import sympy as sp

import symkin
from symkin import schemes


def median_us(fn, n: int) -> float:
    fn()
    repeats = 5 if n >= 10**7 else (41 if n <= 10**3 else 15)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times) * 1e6


def cases(n: int, rng: np.random.Generator) -> dict:
    aa = schemes.two_row("AA").ratio("H", "1", fixed="4")
    ai = schemes.two_row("AI").ratio("H", "1", fixed="4")
    teeth = schemes.two_row("AA", teeth=True).ratio("1", "H", fixed="4")
    radii = [rng.uniform(1, 2, n), rng.uniform(0.2, 0.5, n), rng.uniform(1, 2, n), rng.uniform(0.2, 0.5, n)]
    z = [rng.integers(20, 200, n) for _ in range(4)]
    return {
        "AA i_H1 radii (r1 r3 - r2 r4)": (aa, radii),
        "AI i_H1 radii (r1 r3 + r2 r4)": (ai, radii),
        "AA i_1H teeth, int64 arrays": (teeth, z),
        "AA i_1H teeth, float64 arrays": (teeth, [v.astype(np.float64) for v in z]),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", help="also write the rows to this file")
    ap.add_argument("--sizes", default="3,5,7", help="exponents of 10 (default 3,5,7)")
    opts = ap.parse_args()
    rng = np.random.default_rng(3)
    rows = []
    for exp in (int(e) for e in opts.sizes.split(",")):
        n = 10**exp
        for title, (law, values) in cases(n, rng).items():
            args = sorted(law.rhs.free_symbols, key=lambda s: s.name)
            plain = sp.lambdify(args, law.rhs, modules="numpy")
            f = symkin.compile(law, backend="numpy")
            vals = values
            t_plain = median_us(lambda: plain(*vals), n)
            t_symkin = median_us(lambda: f(*vals), n)
            rows.append(dict(law=title, n=n, lambdify_us=t_plain, symkin_us=t_symkin, ratio=t_symkin / t_plain))
            print(f"{title:36s} 10^{exp}  lambdify {t_plain:10.1f} us  symkin {t_symkin:10.1f} us  symkin/lambdify {t_symkin / t_plain:6.2f}", flush=True)
    if opts.json:
        with open(opts.json, "w") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    sys.exit(main())
