"""The NumPy compiled path (``symkin.compile(law, backend="numpy")``; the default where numba is not installed) against sympy.lambdify,
before and after a change, side by side in one run; ``--backend numba`` measures the numba backend the same way.

    python benchmarks/default_path.py                  # this tree against 513222f
    python benchmarks/default_path.py --before REF --rounds 3 --json out.json
    python benchmarks/default_path.py --before REF --backend numba --sizes 1,1000,100000

The tree at REF (``git archive``) and this tree are measured in alternating child processes
(before, after, before, after, ...), each timing lambdify and symkin on the same inputs, so
both rows of a law come from the same moments of a shared machine.  Laws: the earlier benchmark
set (AA ratio in teeth, II differential with r4 substituted, AI planet acceleration,
elliptical-drive slider acceleration) and the II differential in radii as the README compiles it
(unsubstituted: denominator r1 r3 - r2 r4).  benchmarks/run.py is the one runner of every method
side by side (docs/numerics.md); this script compares two trees of symkin.  Times are CPU time
(time.process_time), medians over rounds x repeats; the spread is (max - min) / median.  With
``--backend numba`` each child process starts with an empty kernel cache folder, and the CPU
time of each law's first call on the smallest array (which compiles its kernel) is reported too.
On a busy machine whole processes run slower or faster: the last column, each tree's time over
its own processes' lambdify time, compares the trees without that.
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
ROOT = HERE.parent
SIZES = (1, 10**3, 10**5, 10**6)


def child(tree: str, sizes: tuple[int, ...], backend: str) -> None:
    """Measure every law in this process with symkin imported from ``tree``."""
    os.environ["SYMKIN_CACHE_DIR"] = tempfile.mkdtemp(prefix="symkin-bench-kernels-")  # (numba: a first call compiles)
    sys.meta_path[:] = [f for f in sys.meta_path if "__editable__" not in repr(f)]  # not the installed tree
    sys.path.insert(0, tree)
    sys.path.insert(1, str(HERE))
    import laws as L
    import numpy as np
    import sympy as sp

    import symkin
    from symkin import schemes
    from symkin import symbols as S

    assert Path(symkin.__file__).resolve().is_relative_to(Path(tree).resolve()), symkin.__file__
    rng = np.random.default_rng(7)
    nmax = max(sizes)
    w1, w4 = S.omega("1"), S.omega("4")
    unsub = schemes.two_row("II").speeds({"1": w1, "4": w4}).law("H").rhs
    cases = {
        "ratio i_1H (AA, teeth)": (L.ratio_law(), [S.teeth(i) for i in "1234"],
                                   [rng.integers(20, 200, nmax) for _ in range(4)]),
        "differential omega_H (II, r4 substituted)": (
            L.differential_law(), [w1, w4, S.radius("1"), S.radius("2"), S.radius("3")],
            [rng.uniform(5, 10, nmax), rng.uniform(-1, 1, nmax), rng.uniform(5, 10, nmax), rng.uniform(1, 2, nmax),
             rng.uniform(2.5, 4, nmax)]),
        "differential omega_H (II, radii, as in the README)": (
            unsub, [w1, w4, *(S.radius(i) for i in "1234")],
            [rng.uniform(-1, 1, nmax), rng.uniform(-1, 1, nmax), rng.uniform(5, 10, nmax), rng.uniform(1, 2, nmax),
             rng.uniform(2.5, 4, nmax), rng.uniform(1, 2, nmax)]),
        "planet-particle acceleration w_x (AI)": (
            L.planet_acceleration()[0], [w1, *(S.radius(i) for i in "1234"), S.t],
            [2.0, 2.0, 1.5, 1.0, 4.5, rng.uniform(0, 10, nmax)]),
        "elliptical-drive slider acceleration a_s": (
            L.slider_acceleration(), [L.E, L.L, L.M, L.W, L.THETA2, L.THETA0, S.t],
            [rng.uniform(0.05, 0.95, nmax), 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, rng.uniform(0, 10, nmax)]),
    }

    def cpu(fn, n: int) -> float:
        k = max(1, 200_000 // max(n, 1000)) if n > 1 else 20_000
        fn()
        t0 = time.process_time()
        for _ in range(k):
            fn()
        return (time.process_time() - t0) / k

    rows = []
    for title, (expr, args, values) in cases.items():
        t0 = time.process_time()
        f = symkin.compile(expr, args, backend=backend, ranges=L.RANGES)
        compile_s = time.process_time() - t0
        g = sp.lambdify(args, expr, modules="numpy")
        first = min([n for n in sizes if n > 1], default=max(sizes))
        t0 = time.process_time()
        f(*[x[:first] if np.ndim(x) else x for x in values])  # numba: compiles the kernel
        first_s = time.process_time() - t0
        for n in sizes:
            if n == 1:
                v = [float(x[0]) if np.ndim(x) else x for x in values]
            else:
                v = [x[:n] if np.ndim(x) else x for x in values]
            times = {"lambdify": [], "symkin": []}
            with np.errstate(all="ignore"):
                for _ in range(3):
                    times["lambdify"].append(cpu(lambda v=v: g(*v), n))
                    times["symkin"].append(cpu(lambda v=v: f(*v), n))
            rows.append(dict(law=title, n=n, compile_s=compile_s, first_s=first_s, **times))
    print(json.dumps(rows))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", default="513222f", help="git ref of the tree to compare with (default 513222f)")
    ap.add_argument("--rounds", type=int, default=2, help="alternating rounds of before/after child processes")
    ap.add_argument("--sizes", default=",".join(map(str, SIZES)))
    ap.add_argument("--backend", default="numpy", choices=("numpy", "numba"), help="the backend measured (default numpy)")
    ap.add_argument("--json", help="also write the rows to this file")
    ap.add_argument("--markdown", help="also write the table to this file (docs/numerics-default-path.md)")
    ap.add_argument("--child", help=argparse.SUPPRESS)
    opts = ap.parse_args()
    sizes = tuple(int(s) for s in opts.sizes.split(","))
    if opts.child:
        return child(opts.child, sizes, opts.backend)
    load0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", opts.before, "symkin"], capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        results: dict[str, list] = {"before": [], "after": []}
        for _ in range(opts.rounds):
            for label, tree in (("before", tmp), ("after", str(ROOT))):
                out = subprocess.run([sys.executable, __file__, "--child", tree, "--sizes", opts.sizes, "--backend", opts.backend],
                                     capture_output=True, text=True, check=True).stdout
                results[label].extend(json.loads(out.strip().splitlines()[-1]))
    load1 = os.getloadavg()[0]
    table = {}
    for label, rows in results.items():
        for r in rows:
            cell = table.setdefault((r["law"], r["n"]), {})
            for method in ("lambdify", "symkin"):
                cell.setdefault((label, method), []).extend(r[method])
            cell.setdefault((label, "compile"), []).append(r["compile_s"])
            cell.setdefault((label, "first"), []).append(r["first_s"])

    def med(xs):
        return statistics.median(xs)

    def spread(xs):
        return (max(xs) - min(xs)) / med(xs)

    lines = [f"backend {opts.backend}; before = {opts.before}, after = this tree; CPU-time medians (spread); 1-minute load "
             f"{load0:.1f} at the start, {load1:.1f} at the end; {opts.rounds} rounds x 3 repeats", "",
             "| law | points | lambdify | symkin before | symkin after | before / lambdify | after / lambdify | after / before "
             "| the same, each over its lambdify |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    out_rows = []
    for (law, n), cell in table.items():
        lam = cell[("before", "lambdify")] + cell[("after", "lambdify")]
        b, a = cell[("before", "symkin")], cell[("after", "symkin")]
        lb, la = med(cell[("before", "lambdify")]), med(cell[("after", "lambdify")])

        def fmt(x):
            return f"{x * 1e6:.1f} us" if x < 1e-3 else f"{x * 1e3:.1f} ms"

        lines.append(f"| {law} | {n:.0e} | {fmt(med(lam))} ({spread(lam):.0%}) | {fmt(med(b))} ({spread(b):.0%}) | "
                     f"{fmt(med(a))} ({spread(a):.0%}) | {med(b) / lb:.2f} | {med(a) / la:.2f} | {med(a) / med(b):.2f} "
                     f"| {(med(a) / la) / (med(b) / lb):.2f} |")
        out_rows.append(dict(law=law, n=n, lambdify=med(lam), before=med(b), after=med(a), before_ratio=med(b) / lb,
                             after_ratio=med(a) / la))
    lines += ["", "The first call on the smallest array (CPU time; numba: the kernel's compilation, from an empty cache folder)", "",
              "| law | before | after | after / before |", "|---|---:|---:|---:|"]
    for (law, _n), cell in table.items():
        if _n == sizes[0]:
            b, a = med(cell[("before", "first")]), med(cell[("after", "first")])
            lines.append(f"| {law} | {b:.3g} s | {a:.3g} s | {a / b:.2f} |")
    print("\n".join(lines))
    if opts.markdown:
        head = ["# The default compiled path against sympy.lambdify, before and after", "",
                "Generated by `python benchmarks/default_path.py --markdown docs/numerics-default-path.md` (do not edit",
                "by hand). Each cell is the CPU time of one call (process_time); `symkin` is `symkin.compile(law, backend=\"numpy\")`,",
                "the NumPy float64 path (the default until numba became it where installed) with its stable forms and checks; a ratio below 1 is faster than",
                "lambdify. Sizes are points per call (1: a call with Python floats).", ""]
        Path(opts.markdown).write_text("\n".join(head + lines) + "\n")
    if opts.json:
        Path(opts.json).write_text(json.dumps(dict(load=[load0, load1], rows=out_rows), indent=1))


if __name__ == "__main__":
    sys.exit(main())
