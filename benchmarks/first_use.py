"""First use: from a fresh process to the first result and to the end of the README's
numeric example (the AA ratio compiled and called once, the AI planet acceleration of a Study
evaluated at 10^5 times), with the backend unnamed (the default: numba in jit="auto" where it
is installed), named numpy, and named numba (compiled at the first call), each with an empty
kernel cache and with a warm one.

    python benchmarks/first_use.py               # 3 rounds, modes interleaved; prints a table
    python benchmarks/first_use.py --json out.json

Each measurement is its own child process (``python first_use.py child MODE CACHE``); the
rounds alternate the modes (numpy, default, numba, numpy, ...) so that a busy moment of the
shared machine hits them all.  Times are CPU time of the child (``time.process_time``, all its
threads) and wall time, from before ``import symkin``; medians over the rounds, and each
mode's median over the numpy mode's.  benchmarks/run.py puts these rows into docs/numerics.md.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
MODES = ("numpy", "default", "numba")
CACHES = ("empty", "warm")


def child(mode: str, cache: str) -> None:
    """The README example in this process; prints its timings as JSON."""
    cpu0, wall0 = time.process_time(), time.perf_counter()
    import numpy as np

    import symkin
    from symkin import schemes
    from symkin import symbols as S

    backend = None if mode == "default" else mode
    law = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4")
    f = symkin.compile(law, backend=backend)
    first = f(100, 99, 100, 101)
    cpu1, wall1 = time.process_time(), time.perf_counter()
    study = symkin.Study(schemes.two_row("AI"), particles=[("23", (S.radius("1"), 0), ("acceleration",))],
                         inputs={"1": S.omega("1"), "4": 0}, backend=backend)
    out = study.evaluate({"omega_1": 1, "r_1": 1, "r_2": 2, "r_3": 1, "r_4": 4}, t=np.linspace(0, 10, 10**5))
    cpu2, wall2 = time.process_time(), time.perf_counter()
    assert float(first) == 10000.0 and all(np.all(np.isfinite(v)) for v in out.values())
    print(json.dumps(dict(first_cpu=cpu1 - cpu0, first_wall=wall1 - wall0, total_cpu=cpu2 - cpu0, total_wall=wall2 - wall0,
                          compiled=bool(getattr(study.function._evaluator, "kernels", None)))))


def measure(rounds: int) -> dict:
    """Every mode and cache state, ``rounds`` times, interleaved; the medians and ratios."""
    raw: dict[str, list[dict]] = {f"{m} {c}": [] for c in CACHES for m in MODES}
    for _ in range(rounds):
        for cache in CACHES:
            for mode in MODES:
                folder = tempfile.mkdtemp(prefix="symkin-first-use-")
                env = dict(os.environ, SYMKIN_CACHE_DIR=folder)
                env.pop("SYMKIN_BACKEND", None)
                if cache == "warm":  # the same example once before, in another process
                    subprocess.run([sys.executable, __file__, "child", mode, cache], env=env, check=True, capture_output=True)
                done = subprocess.run([sys.executable, __file__, "child", mode, cache], env=env, check=True,
                                      capture_output=True, text=True)
                raw[f"{mode} {cache}"].append(json.loads(done.stdout.strip().splitlines()[-1]))
    rows = []
    for cache in CACHES:
        base = {k: statistics.median(r[k] for r in raw[f"numpy {cache}"]) for k in ("first_cpu", "total_cpu", "first_wall", "total_wall")}
        for mode in MODES:
            runs = raw[f"{mode} {cache}"]
            med = {k: statistics.median(r[k] for r in runs) for k in base}
            rows.append(dict(mode=mode, cache=cache, **med, **{f"{k}_ratio": med[k] / base[k] for k in base},
                             compiled=any(r["compiled"] for r in runs)))
    return dict(rounds=rounds, rows=rows)


def main() -> None:
    if len(sys.argv) >= 2 and sys.argv[1] == "child":
        child(sys.argv[2], sys.argv[3])
        return
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--json", type=Path)
    a = ap.parse_args()
    load = os.getloadavg()[0]
    res = measure(a.rounds)
    res["load"] = [load, os.getloadavg()[0]]
    print(f"load {res['load'][0]:.2f} -> {res['load'][1]:.2f}; medians of {a.rounds} rounds, CPU s (wall s), ratio to numpy")
    for r in res["rows"]:
        print(f"{r['mode']:8s} {r['cache']:5s} first {r['first_cpu']:6.2f} ({r['first_wall']:6.2f}) x{r['first_cpu_ratio']:.2f}   "
              f"total {r['total_cpu']:6.2f} ({r['total_wall']:6.2f}) x{r['total_cpu_ratio']:.2f}   kernel compiled: {r['compiled']}")
    if a.json:
        a.json.write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
