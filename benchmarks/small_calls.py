"""Per-call cost of the NumPy backend against sympy.lambdify for small calls, two trees in one run
(issue 34 item 4): ``python benchmarks/small_calls.py BEFORE_TREE AFTER_TREE [ROUNDS]`` runs each tree
in its own process, alternating, ROUNDS times (3), and prints the medians (microseconds) as a markdown
table; ``python benchmarks/small_calls.py --one TREE`` is one such process (json).  A tree is a folder
holding symkin/ and benchmarks/ (e.g. ``git archive <commit> symkin benchmarks | tar -x -C /tmp/x``).

``python benchmarks/small_calls.py --numba BEFORE_TREE AFTER_TREE [ROUNDS]`` (issue 34 item 4a): the same
laws as a plain hand-written ``@numba.njit`` function (the law as SymPy prints it, nothing else) and a plain
``@njit`` loop over 100 points, against symkin's ``backend="numba"`` and its default (``jit="auto"``, driven
by calls of 1000 points until it has compiled its kernel), for a scalar call and a 100-point call; in each
process (``--numba-one TREE ROUNDS``) the methods in turn, 5 rounds, medians; the trees' processes
alternating ROUNDS (3) times, medians (microseconds) and the ratios to the plain ``@njit`` function (its
median over both trees) as a markdown table.

``python benchmarks/small_calls.py --tradeoff [ROUNDS]`` (item 4b): speed and accuracy of the NumPy backend
with and without its stable forms, the numba backend and lambdify, in one process (see :func:`tradeoff`);
``--scalar-floor``: what symkin's scalar wrapper costs around a bare law (see :func:`scalar_floor`).
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
import timeit

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


def in_turn(fns: dict, vals, rounds: int) -> dict:
    """Seconds per call of each function on ``vals``: each called once, then timed in turn ``rounds``
    times, the medians."""
    samples: dict[str, list[float]] = {k: [] for k in fns}
    for fn in fns.values():
        fn(*vals)
    for _ in range(rounds):
        for k, fn in fns.items():
            samples[k].append(timed(fn, vals))
    return {k: statistics.median(v) for k, v in samples.items()}


def plain_njit(expr, args):
    """The law as a plain ``@njit`` scalar function and a plain ``@njit`` loop allocating its output
    (written from ``sympy.pycode`` of the law: no symkin code)."""
    import numba
    import numpy as np
    import sympy as sp

    names = [f"a{k}" for k in range(len(args))]
    body = sp.pycode(expr.xreplace({s: sp.Symbol(n) for s, n in zip(args, names)}))
    src = (f"def law({', '.join(names)}):\n    return {body}\n\n"
           f"def loop({', '.join(names)}):\n    n = a0.shape[0]\n    out = numpy.empty(n)\n    for i in range(n):\n"
           f"        out[i] = law({', '.join(f'{n}[i]' for n in names)})\n    return out\n")
    ns: dict = {"numpy": np}
    exec(src, ns)
    law = numba.njit(ns["law"])
    ns["law"] = law
    return law, numba.njit(ns["loop"])


def numba_one(tree: str, rounds: int) -> None:
    """Item 4a in one process of ``tree``: :func:`numba_rows` as json."""
    sys.path[:0] = [tree, tree + "/benchmarks"]
    print(json.dumps(numba_rows(rounds)))


def numba_rows(rounds: int) -> dict:
    """Item 4a in this process: ``{"law|points|method": median us}`` of each law, size (1, 100) and
    method (plain @njit, symkin numba, symkin default once switched), and ``{"law|switch": CPU s}``,
    the NumPy time the default spent before it compiled its kernel."""
    import numpy as np

    import symkin

    out = {}
    for title, (expr, args, values) in cases(np.random.default_rng(7), 1000).items():
        law, loop = plain_njit(expr, args)
        eager = symkin.compile(expr, args, backend="numba")
        auto = symkin.compile(expr, args)  # the default: NumPy until compiling the kernel pays
        start = time.process_time()
        while not auto._evaluator.kernels and time.process_time() - start < 120:
            auto(*values)
        out[f"{title}|switch"] = time.process_time() - start
        for size in (1, 100):
            vals = [v[0].item() for v in values] if size == 1 else [np.ascontiguousarray(v[:size]) for v in values]
            fns = {"plain @njit": law if size == 1 else loop, "symkin numba": eager, "symkin default (auto)": auto}
            for k, v in in_turn(fns, vals, rounds).items():
                out[f"{title}|{size}|{k}"] = v * 1e6
    return out


def numba_compare(trees: dict[str, str], rounds: int) -> None:
    """Item 4a: both trees, alternating processes, ``rounds`` times; the medians as a markdown table."""
    res: dict[str, list[dict]] = {k: [] for k in trees}
    print("load at start", os.getloadavg(), flush=True)
    for _ in range(rounds):
        for k, t in trees.items():
            o = subprocess.run([sys.executable, os.path.abspath(__file__), "--numba-one", t, "5"], capture_output=True,
                               text=True, cwd="/tmp", check=True)
            res[k].append(json.loads(o.stdout.splitlines()[-1]))
    print("load at end", os.getloadavg())
    med = {k: {key: statistics.median(r[key] for r in res[k]) for key in res[k][0]} for k in trees}
    print("| law | points | plain @njit us | " + " | ".join(f"{k}: symkin numba us | ratio | default (auto) us | ratio"
                                                         for k in trees) + " |")
    print("|---|---:|---:|" + "---:|---:|---:|---:|" * len(trees))
    for key in med[next(iter(trees))]:
        law, *rest = key.split("|")
        if rest[-1] != "plain @njit":
            continue
        size = rest[0]
        p = statistics.median([med[k][key] for k in trees])
        cells = []
        for k in trees:
            e, a = med[k][f"{law}|{size}|symkin numba"], med[k][f"{law}|{size}|symkin default (auto)"]
            cells.append(f"{e:.2f} | {e / p:.2f} | {a:.2f} | {a / p:.2f}")
        print(f"| {law} | {size} | {p:.2f} | " + " | ".join(cells) + " |")
    print("(the default switched to its kernel after " + "; ".join(
        f"{k}: " + ", ".join(f"{key.split('|')[0]} {v:.1f} s" for key, v in med[k].items() if key.endswith("|switch"))
        for k in trees) + " of CPU)")


def tradeoff(rounds: int) -> None:
    """Item 4b: the NumPy backend with its stable forms, with ``stable=False``, the numba backend and
    lambdify at 10^3, 10^4 and 10^5 points, in one process (methods in turn, ``rounds`` rounds, medians,
    ratios to lambdify), with each method's largest relative error against exact rational arithmetic
    (Fraction) on the first 10^4 points; and the II law on inputs where no term cancels (every point
    of its sum certified: the least any certificate can cost), as a markdown table."""
    from fractions import Fraction

    import numpy as np
    import sympy as sp

    import symkin

    print("load at start", os.getloadavg(), flush=True)
    rng = np.random.default_rng(7)
    all_cases = cases(rng, 10**5)
    ii = all_cases["II (run.py)"]
    same_sign = [rng.uniform(0.5, 1, 10**5), rng.uniform(-1, -0.5, 10**5), *ii[2][2:]]  # w1 r1 r3 - w4 r2 r4: no cancellation
    all_cases["II, no cancellation (every point certified)"] = (ii[0], ii[1], same_sign)
    table = []
    for title, (expr, args, values) in all_cases.items():
        fns = {"lambdify": sp.lambdify(args, expr, "numpy"),
               "symkin numpy": symkin.compile(expr, args, backend="numpy"),
               "symkin numpy, stable=False": symkin.compile(expr, args, backend="numpy", stable=False),
               "symkin numba": symkin.compile(expr, args, backend="numba")}
        m = 10**4
        exact_f = sp.lambdify(args, expr, "math")
        points = list(zip(*(map(Fraction, v[:m].tolist()) for v in values)))
        exact = [exact_f(*p) for p in points]  # rational arithmetic: Fraction in, Fraction out
        errors = {}
        for k, fn in fns.items():
            got = np.asarray(fn(*(v[:m] for v in values)), dtype=float).tolist()
            errors[k] = max(float(abs(Fraction(g) - x) / abs(x)) for g, x in zip(got, exact) if x)
        for size in (10**3, 10**4, 10**5):
            med = in_turn(fns, [v[:size] for v in values], rounds)
            table.append((title, size, med, errors))
            print(title, size, {k: f"{v / med['lambdify']:.2f}" for k, v in med.items()}, flush=True)
    print("load at end", os.getloadavg())
    names = list(table[0][2])
    print("| law | points | lambdify us | " + " | ".join(f"{k}: ratio" for k in names[1:]) + " |")
    print("|---|---:|---:|" + "---:|" * (len(names) - 1))
    for title, size, med, _ in table:
        lam = med["lambdify"]
        print(f"| {title} | {size} | {lam * 1e6:.1f} | " + " | ".join(f"{med[k] / lam:.2f}" for k in names[1:]) + " |")
    print()
    print("| law | " + " | ".join(f"{k}: max relative error" for k in names) + " |")
    print("|---|" + "---:|" * len(names))
    for title, size, _, errors in table:
        if size == 10**3:
            print(f"| {title} | " + " | ".join(f"{errors[k]:.1e}" for k in names) + " |")


def scalar_floor() -> None:
    """Item 4a, the scalar floor: the II law as a bare expression, as a plain ``@njit`` function, and
    behind a copy of symkin's scalar wrapper (``NumericFunction.__call__``'s tests and a generated entry:
    a type test per argument, the finiteness test, a NumPy float64 result) around the bare expression,
    not symkin's stable-form code: what a call with symkin's guarantees costs before its law does.
    Minimum of 5 loops of 2*10^5 calls (microseconds), 3 times."""
    import numba
    import numpy as np

    f64, nd = np.float64, np.ndarray

    def law(w1, w4, r1, r2, r3, r4):
        return (w1 * r1 * r3 - w4 * r2 * r4) / (r1 * r3 - r2 * r4)

    def entry(values):
        v0, v1, v2, v3, v4, v5 = values
        if ((type(v0) is float or type(v0) is f64) and (type(v1) is float or type(v1) is f64)
                and (type(v2) is float or type(v2) is f64) and (type(v3) is float or type(v3) is f64)
                and (type(v4) is float or type(v4) is f64) and (type(v5) is float or type(v5) is f64)):
            try:
                r0 = law(v0, v1, v2, v3, v4, v5)
            except ArithmeticError:
                return None
            if type(r0) is float and r0 - r0 == 0.0:
                return f64(r0)
        return None

    class Wrapper:
        _arity = 6
        _entry = staticmethod(entry)

        def __call__(self, *values, out=None):
            if len(values) != self._arity:
                raise TypeError("arguments")
            if out is None and not (values and type(values[0]) is nd) and self._entry is not False:
                r = self._entry(values)
                if r is not None:
                    return r
            return None

    jit, wrapped = numba.njit(law), Wrapper()
    sv = [0.3, -0.5, 7.0, 1.5, 3.0, 1.2]
    jit(*sv)
    print("load", os.getloadavg())
    for _ in range(3):
        print({name: round(min(timeit.repeat(lambda c=c: c(*sv), number=200000, repeat=5)) / 200000 * 1e6, 3)
               for name, c in (("plain @njit", jit), ("bare law", law), ("wrapper + bare law", wrapped))})


def cases(rng, n: int) -> dict:
    """The benchmark laws, each ``(expr, args, values)`` with ``n`` points."""
    import laws
    import numpy as np

    from symkin import schemes
    from symkin import symbols as S

    w1, w4 = S.omega("1"), S.omega("4")
    radii = [S.radius(i) for i in "1234"]
    ratio = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4").rhs
    z = [rng.integers(20, 200, n) for _ in range(4)]
    z[3] = np.where(z[0] * z[2] == z[1] * z[3], z[3] + 1, z[3])  # away from the poles, as run.py
    sub = laws.differential_law()
    return {
        "II (run.py)": (schemes.two_row("II").speeds({"1": w1, "4": w4}).law("H").rhs, [w1, w4, *radii],
                        [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(5, 10, n), rng.uniform(1, 2, n),
                         rng.uniform(2.5, 4, n), rng.uniform(1, 2, n)]),
        "AA ratio (teeth)": (ratio, sorted(ratio.free_symbols, key=lambda s: s.name), z),
        "II r4 substituted": (sub, sorted(sub.free_symbols, key=lambda s: s.name),
                              [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(5, 10, n), rng.uniform(1, 2, n),
                               rng.uniform(2.5, 4, n)]),
    }


def one(tree: str) -> None:
    """The medians of 5 timings of each law, size and method in this process, as json (us)."""
    sys.path[:0] = [tree, tree + "/benchmarks"]
    import numpy as np
    import sympy as sp

    import symkin

    out = {}
    for title, (expr, args, values) in cases(np.random.default_rng(7), 10**5).items():
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
    if sys.argv[1] == "--numba":
        numba_compare({"before": sys.argv[2], "after": sys.argv[3]}, int(sys.argv[4]) if len(sys.argv) > 4 else 3)
    elif sys.argv[1] == "--scalar-floor":
        scalar_floor()
    elif sys.argv[1] == "--tradeoff":
        tradeoff(int(sys.argv[2]) if len(sys.argv) > 2 else 5)
    elif sys.argv[1] == "--numba-one":
        numba_one(sys.argv[2], int(sys.argv[3]))
    elif sys.argv[1] == "--one":
        one(sys.argv[2])
    else:
        compare({"before": sys.argv[1], "after": sys.argv[2]}, int(sys.argv[3]) if len(sys.argv) > 3 else 3)
