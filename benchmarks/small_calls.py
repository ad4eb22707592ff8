"""Per-call cost of the NumPy backend against sympy.lambdify for small calls, two trees in one run
(issue 34 item 4): ``python benchmarks/small_calls.py BEFORE_TREE AFTER_TREE [ROUNDS]`` runs each tree
in its own process, alternating, ROUNDS times (3), and prints the medians (microseconds) as a markdown
table; ``python benchmarks/small_calls.py --one TREE`` is one such process (json).  A tree is a folder
holding symkin/ and benchmarks/ (e.g. ``git archive <commit> symkin benchmarks | tar -x -C /tmp/x``).
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time

SIZES = (1, 100, 1000, 10**5)


def timed(fn, vals) -> float:
    """Seconds per call, from a loop of at least 5 ms."""
    loops = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(loops):
            fn(*vals)
        dt = time.perf_counter() - t0
        if dt >= 5e-3:
            return dt / loops
        loops *= 4


def one(tree: str) -> None:
    """The medians of 5 timings of each law, size and method in this process, as json (us)."""
    sys.path[:0] = [tree, tree + "/benchmarks"]
    import laws
    import numpy as np
    import sympy as sp

    import symkin
    from symkin import schemes
    from symkin import symbols as S

    w1, w4 = S.omega("1"), S.omega("4")
    radii = [S.radius(i) for i in "1234"]
    rng = np.random.default_rng(7)
    n = 10**5
    ratio = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4").rhs
    z = [rng.integers(20, 200, n) for _ in range(4)]
    z[3] = np.where(z[0] * z[2] == z[1] * z[3], z[3] + 1, z[3])  # away from the poles, as run.py
    sub = laws.differential_law()
    cases = {
        "II (run.py)": (schemes.two_row("II").speeds({"1": w1, "4": w4}).law("H").rhs, [w1, w4, *radii],
                        [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(5, 10, n), rng.uniform(1, 2, n),
                         rng.uniform(2.5, 4, n), rng.uniform(1, 2, n)]),
        "AA ratio (teeth)": (ratio, sorted(ratio.free_symbols, key=lambda s: s.name), z),
        "II r4 substituted": (sub, sorted(sub.free_symbols, key=lambda s: s.name),
                              [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(5, 10, n), rng.uniform(1, 2, n),
                               rng.uniform(2.5, 4, n)]),
    }
    out = {}
    for title, (expr, args, values) in cases.items():
        fns = {"symkin numpy": symkin.compile(expr, args, backend="numpy"), "lambdify": sp.lambdify(args, expr, "numpy")}
        for size in SIZES:
            vals = [v[0].item() for v in values] if size == 1 else [v[:size] for v in values]
            for name, fn in fns.items():
                fn(*vals)
                out[f"{title}|{size}|{name}"] = statistics.median(timed(fn, vals) for _ in range(5)) * 1e6
    print(json.dumps(out))


def compare(trees: dict[str, str], rounds: int) -> None:
    """Both trees, alternating, ``rounds`` times; the medians as a markdown table."""
    res: dict[str, list[dict]] = {k: [] for k in trees}
    for _ in range(rounds):
        for k, t in trees.items():
            o = subprocess.run([sys.executable, os.path.abspath(__file__), "--one", t], capture_output=True, text=True,
                               cwd="/tmp", check=True)
            res[k].append(json.loads(o.stdout.splitlines()[-1]))
    print("load", os.getloadavg())
    keys = list(res["before"][0])
    med = {k: {key: statistics.median(r[key] for r in res[k]) for key in keys} for k in trees}
    print("| law | points | before: symkin us | lambdify us | ratio | after: symkin us | lambdify us | ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for key in keys:
        law, size, method = key.split("|")
        if method != "symkin numpy":
            continue
        b, bl = med["before"][key], med["before"][f"{law}|{size}|lambdify"]
        a, al = med["after"][key], med["after"][f"{law}|{size}|lambdify"]
        print(f"| {law} | {size} | {b:.2f} | {bl:.2f} | {b / bl:.2f} | {a:.2f} | {al:.2f} | {a / al:.2f} |")


if __name__ == "__main__":
    if sys.argv[1] == "--one":
        one(sys.argv[2])
    else:
        compare({"before": sys.argv[1], "after": sys.argv[2]}, int(sys.argv[3]) if len(sys.argv) > 3 else 3)
