"""Speed and accuracy of symkin's numeric backends, side by side, in one run.

    python benchmarks/run.py            # full run (about 4 minutes on 2 cores)
    python benchmarks/run.py --quick    # 10^3 and 10^5 points only

For four laws (a ratio in tooth numbers, a general differential, a planet-particle
acceleration, the elliptical-drive slider acceleration) it measures throughput (points/s,
median of repeats) at 10^3, 10^5 and 10^7 points and the maximum relative error against
a 50-digit mpmath reference, for hand-written NumPy, plain sympy.lambdify, per-point
sympy evalf, and every symkin backend; the machine's copy bandwidth in the same run; the
extremes where naive forms lose digits; Dask scaling on this machine; the time of a
ratio-only scene after import and of `symkin reproduce`.  Writes docs/numerics.md (the
tables), docs/numerics-speed-error.png/.pdf (the plot) and benchmarks/results.json.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import sympy as sp

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")  # as symkin's numba backend does (see backends.py)
HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

import laws as L  # noqa: E402

import symkin  # noqa: E402
from symkin import symbols as S  # noqa: E402
from symkin.numeric.backends import numba_available  # noqa: E402

HAS_NUMBA = numba_available()


# --------------------------------------------------------------------------- timing
def median_time(fn, repeats: int) -> float:
    t0 = time.perf_counter()
    fn()  # warm (compilation, caches)
    if time.perf_counter() - t0 < 0.3:
        repeats = max(repeats, 7)  # cheap calls: more repeats, a steadier median on a shared machine
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def repeats_for(n: int) -> int:
    return 3 if n >= 10**7 else 7


def copy_bandwidth(n: int = 10**7) -> dict[str, float]:
    """Bytes read + written per second by a copy of n float64: one thread, two threads."""
    src = np.random.default_rng(0).random(n)
    dst = np.empty_like(src)
    one = median_time(lambda: np.copyto(dst, src), 7)
    half = n // 2

    def two_threads():
        ts = [threading.Thread(target=np.copyto, args=(dst[i * half:(i + 1) * half], src[i * half:(i + 1) * half])) for i in range(2)]
        for t in ts:
            t.start()
        for t in ts:
            t.join()

    two = median_time(two_threads, 7)
    out = {"copy_1thread_GBps": 16 * n / one / 1e9, "copy_2threads_GBps": 16 * n / two / 1e9}
    if HAS_NUMBA:
        import numba

        @numba.njit(parallel=True)
        def pcopy(a, b):
            for i in numba.prange(a.size):
                b[i] = a[i]

        out["copy_2threads_numba_GBps"] = 16 * n / median_time(lambda: pcopy(src, dst), 7) / 1e9
    out["copy_best_2threads_GBps"] = max(v for k, v in out.items() if "2threads" in k)
    return out


# --------------------------------------------------------------------------- the four laws
def hand_ratio(z1, z2, z3, z4):
    return 1 - z2 * z4 / (z1 * z3)


def hand_differential(w1, w4, r1, r2, r3):
    return (w1 * r1 * r3 - w4 * r2 * (r1 - r2 + r3)) / ((r1 - r2) * (r3 - r2))


def hand_planet(w1, r1, r2, r3, r4, t):
    wh = w1 * r1 * r3 / (r1 * r3 + r2 * r4)
    w23 = -wh * (r4 - r3) / r3
    a = r1 + r2
    return -wh**2 * a * np.cos(wh * t) + w23**2 * r2 * np.cos(w23 * t)


def hand_slider(e, l, m, w, th2, th0, t):
    k = (1 + e) / (1 - e)
    theta = th0 + 2 / m * np.arctan(k * np.tan(m * w * t / 2))
    c = np.cos(m * w * t)
    d = 1 - 2 * e * c + e**2
    wh = w * (1 - e**2) / d
    eh = -w * (1 - e**2) * 2 * e * m * w * np.sin(m * w * t) / d**2
    return -2 * l * np.cos(th2 - theta) * wh**2 + 2 * l * np.sin(th2 - theta) * eh


def build_cases(nmax: int) -> dict:
    rng = np.random.default_rng(7)
    cases = {}
    ratio = L.ratio_law()
    zargs = [S.teeth(i) for i in "1234"]
    cases["ratio i_1H (AA, teeth)"] = dict(
        expr=ratio, args=zargs, hand=hand_ratio, rational=True, bytes=40,
        values=[rng.integers(20, 200, nmax) for _ in range(4)], float_values=True,
    )
    diff = L.differential_law()
    dargs = [S.omega("1"), S.omega("4"), S.radius("1"), S.radius("2"), S.radius("3")]
    cases["differential omega_H (II)"] = dict(
        expr=diff, args=dargs, hand=hand_differential, rational=True, bytes=48,
        # omega_4 crosses zero, omega_H stays away from it (where the law itself is ill conditioned)
        values=[rng.uniform(5, 10, nmax), rng.uniform(-1, 1, nmax), rng.uniform(5, 10, nmax), rng.uniform(1, 2, nmax), rng.uniform(2.5, 4, nmax)],
    )
    acc = L.planet_acceleration()[0]
    pargs = [S.omega("1"), S.radius("1"), S.radius("2"), S.radius("3"), S.radius("4"), S.t]
    cases["planet-particle acceleration w_x (AI)"] = dict(
        expr=acc, args=pargs, hand=hand_planet, rational=False, bytes=16,
        values=[2.0, 2.0, 1.5, 1.0, 4.5, rng.uniform(0, 10, nmax)], normwise=True,
    )
    sl = L.slider_acceleration()
    sargs = [L.E, L.L, L.M, L.W, L.THETA2, L.THETA0, S.t]
    cases["elliptical-drive slider acceleration a_s"] = dict(
        expr=sl, args=sargs, hand=hand_slider, rational=False, bytes=24,
        values=[rng.uniform(0.05, 0.95, nmax), 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, rng.uniform(0, 10, nmax)], normwise=True,
    )
    return cases


def prefix(values, n):
    return [v[:n] if np.ndim(v) else v for v in values]


def rel_error(got, ref, normwise=False) -> float:
    got = np.asarray(got, dtype=float)
    ref = np.asarray(ref, dtype=float)
    floor = 1.0 if normwise else 1e-3
    scale = np.maximum(np.abs(ref), floor * np.max(np.abs(ref)))
    return float(np.max(np.abs(got - ref) / scale))


def methods_for(case: dict) -> dict:
    expr, args = case["expr"], case["args"]
    ranges = L.RANGES
    out = {
        "hand-written NumPy": case["hand"],
        "sympy.lambdify": sp.lambdify(args, expr, modules="numpy"),
        "sympy.lambdify, cse=True": sp.lambdify(args, expr, modules="numpy", cse=True),
        "symkin numpy float64": symkin.compile(expr, args, ranges=ranges),
        "symkin numpy float64, no cse": symkin.compile(expr, args, ranges=ranges, cse=False),
        "symkin numpy float64, 2 threads": symkin.compile(expr, args, ranges=ranges, threads=2),
        "symkin numpy float32": symkin.compile(expr, args, precision="float32", ranges=ranges),
        "symkin numpy float32, 2 threads": symkin.compile(expr, args, precision="float32", ranges=ranges, threads=2),
    }
    if HAS_NUMBA:
        out["symkin numba float64, 1 thread"] = symkin.compile(expr, args, backend="numba", threads=1, ranges=ranges)
        out["symkin numba float64, 2 threads"] = symkin.compile(expr, args, backend="numba", threads=2, ranges=ranges)
        out["symkin numba float32, 2 threads"] = symkin.compile(expr, args, backend="numba", precision="float32", threads=2, ranges=ranges)
    if S.t in args:  # laws in time: the phase m omega t rounded is most of the float64 error
        out["symkin numpy float64, reduce_phase=[t]"] = symkin.compile(expr, args, ranges=ranges, reduce_phase=[S.t])
        if HAS_NUMBA:
            out["symkin numba float64, 2 threads, reduce_phase=[t]"] = symkin.compile(
                expr, args, backend="numba", threads=2, ranges=ranges, reduce_phase=[S.t]
            )
    best = out.get("symkin numba float64, 2 threads", out["symkin numpy float64"])
    out["(same, into a reused out= buffer)"] = _with_out(best)
    if case.get("float_values"):  # users often pass tooth numbers as floats: run_case passes float64 arrays
        out["symkin numpy float64, float64 tooth arrays"] = out["symkin numpy float64"]
        if HAS_NUMBA:
            out["symkin numba float64, 2 threads, float64 tooth arrays"] = out["symkin numba float64, 2 threads"]
    if case.get("float_values") and HAS_NUMBA:  # tooth numbers fit int32: half the bytes to read
        out["(same, int32 tooth numbers)"] = best  # run_case passes int32 arrays
    out["symkin mpmath 30 digits"] = symkin.compile(expr, args, backend="mpmath", digits=30)
    if case["rational"]:
        out["symkin exact (Fraction)"] = symkin.compile(expr, args, backend="exact")
    return out


def _with_out(f):
    """Call ``f`` writing into a buffer kept between calls (as Study.evaluate(reuse=True) does)."""
    buffers: dict = {}

    def call(*values):
        n = max((np.size(v) for v in values), default=1)
        if n not in buffers:
            buffers[n] = np.empty(n)
        return f(*values, out=buffers[n])

    return call


SLOW = ("symkin mpmath 30 digits", "symkin exact (Fraction)", "sympy subs/evalf per point")


def evalf_points(expr, args, values, n):
    out = []
    for i in range(n):
        point = {a: (sp.Integer(int(v[i])) if np.ndim(v) and np.issubdtype(np.asarray(v).dtype, np.integer) else sp.Float(float(v[i] if np.ndim(v) else v), 17)) for a, v in zip(args, values)}
        out.append(float(expr.subs(point).evalf(17)))
    return np.array(out)


def run_case(title: str, case: dict, sizes: list[int], ref_n: int = 1000) -> list[dict]:
    rows = []
    vals_ref = prefix(case["values"], ref_n)
    ref_vals = vals_ref
    ref_expr = case["expr"]
    if title.startswith("elliptical"):
        ref_expr = L.slider_laws_continuous()[2]
    ref = np.array(symkin.compile(ref_expr, case["args"], backend="mpmath", digits=50)(*ref_vals), dtype=float)
    methods = methods_for(case)
    exact_ok = case["rational"]
    case["bandwidth"] = copy_bandwidth()  # next to this law's timings: the machine is shared
    print(title, case["bandwidth"], flush=True)
    for name, fn in methods.items():
        for n in sizes:
            if name in SLOW and n > 10**3:
                continue
            vals = prefix(case["values"], n)
            if name == "symkin exact (Fraction)":
                if not exact_ok:
                    continue
                vals = [np.asarray(v).astype(object) if np.ndim(v) else v for v in vals]
                if not title.startswith("ratio"):
                    from fractions import Fraction

                    vals = [np.array([Fraction(float(x)) for x in v], dtype=object) if np.ndim(v) else Fraction(float(v)) for v in vals]
            if name == "(same, int32 tooth numbers)":
                vals = [np.asarray(v).astype(np.int32) for v in vals]
            if name.endswith("float64 tooth arrays"):
                vals = [np.asarray(v).astype(np.float64) for v in vals]
            t = median_time(lambda: fn(*vals), repeats_for(n) if name not in SLOW else 1)
            got = fn(*prefix(vals, ref_n)) if n >= ref_n else None
            err = rel_error(np.asarray(got, dtype=float), ref, case.get("normwise", False)) if got is not None else None
            rows.append(dict(law=title, method=name, n=n, points_per_s=n / t, max_rel_error=err))
            print(f"{title:45s} {name:36s} {n:>9d} {n / t / 1e6:10.3f} Mpts/s  err {err if err is not None else '-'}", flush=True)
    # per-point sympy evalf on 200 points
    n = 200
    vals = prefix(case["values"], n)
    t0 = time.perf_counter()
    got = evalf_points(case["expr"], case["args"], vals, n)
    t = time.perf_counter() - t0
    err = rel_error(got, ref[:n], case.get("normwise", False))
    rows.append(dict(law=title, method="sympy subs/evalf per point", n=n, points_per_s=n / t, max_rel_error=err))
    print(f"{title:45s} {'sympy subs/evalf per point':36s} {n:>9d} {n / t / 1e6:10.5f} Mpts/s  err {err}", flush=True)
    return rows


# --------------------------------------------------------------------------- extremes
def extremes() -> list[dict]:
    rows = []
    rng = np.random.default_rng(11)
    law = L.ratio_law()
    Z = [S.teeth(i) for i in "1234"]
    naive = sp.lambdify(Z, law)
    f = symkin.compile(law, Z)
    fn = symkin.compile(law, Z, backend="numba") if HAS_NUMBA else f
    for big in (10**4, 10**8):
        z1 = rng.integers(big // 2, big, 1000)
        z3 = z1 + rng.integers(-2, 3, 1000)
        k = rng.integers(1, 4, 1000)
        z2, z4 = z1 - k, z3 + k
        from fractions import Fraction

        ref = np.array([float(Fraction(int(a * c - b * d), int(a * c))) for a, b, c, d in zip(z1, z2, z3, z4)])
        ok = ref != 0
        for name, g in (("sympy.lambdify", naive(*(x.astype(float) for x in (z1, z2, z3, z4)))), ("symkin numpy", f(z1, z2, z3, z4)), ("symkin numba", fn(z1, z2, z3, z4))):
            err = float(np.max(np.abs(g[ok] - ref[ok]) / np.abs(ref[ok])))
            rows.append(dict(case=f"ratio 1 - z2 z4/(z1 z3), z near 10^{int(np.log10(big))}, z1 z3 - z2 z4 of a few units", method=name, max_rel_error=err))
    # AA ratio in radii near its pole: r1 r3 - r2 r4 a few ulps of r1 r3
    aa = symkin.schemes.two_row("AA").ratio("H", "1", fixed="4").rhs
    rargs = [S.radius(i) for i in "1234"]
    r1, r2, r3 = (rng.uniform(0.1, 3, 1000) for _ in range(3))
    r4 = r1 * r3 / r2 * (1 + rng.integers(-60, 61, 1000) * 2.0**-53)
    ref = np.array(symkin.compile(aa, rargs, backend="mpmath", digits=50)(r1, r2, r3, r4), dtype=float)
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # plain float64 sees "poles" the binary inputs do not have
        naive = sp.lambdify(rargs, aa)(r1, r2, r3, r4)
    label = "AA ratio r1 r3/(r1 r3 - r2 r4) in radii, r2 r4 within 60 ulps of r1 r3"
    for name, g in (("sympy.lambdify", naive), ("symkin numpy", symkin.compile(aa, rargs)(r1, r2, r3, r4)),
                    ("symkin numba", (symkin.compile(aa, rargs, backend="numba") if HAS_NUMBA else symkin.compile(aa, rargs))(r1, r2, r3, r4))):
        err = np.abs(g - ref) / np.abs(ref)
        rows.append(dict(case=label, method=name, max_rel_error=float(np.max(np.where(np.isfinite(err), err, np.inf)))))
    # II differential, omega_1 = omega_4, r3 -> r2
    law = L.differential_law()
    args = [S.omega("1"), S.omega("4"), S.radius("1"), S.radius("2"), S.radius("3")]
    r2 = 1 + rng.uniform(0, 1, 1000)
    r3 = r2 * (1 + rng.uniform(1e-15, 1e-13, 1000))
    w = rng.uniform(1, 2, 1000)
    for name, g in (("sympy.lambdify", sp.lambdify(args, law)(w, w, 3.0, r2, r3)), ("symkin numpy", symkin.compile(law, args)(w, w, 3.0, r2, r3))):
        rows.append(dict(case="II differential, omega_1 = omega_4, r3/r2 - 1 in (1e-15, 1e-13)", method=name, max_rel_error=float(np.max(np.abs(g - w) / w))))
    # elliptical drive at e = 0.999999 (m = 1) and branch points (m = 2)
    s, v, a = L.slider_laws()
    cs, cv, ca = L.slider_laws_continuous()
    sargs = [L.E, L.L, L.M, L.W, L.THETA2, L.THETA0, S.t]
    t = np.linspace(0, 6, 500)
    for e, m, label in ((0.999999, 1.0, "e = 0.999999, m = 1"), (0.5, 2.0, "e = 0.5, m = 2, t across 4 branch points")):
        vals = [e, 0.02, m, 0.8 * np.pi, 0.3, 0.1, t]
        ref = [np.array(r, dtype=float) for r in symkin.compile([cs, cv, ca], sargs, backend="mpmath", digits=50)(*vals)]
        raw = sp.lambdify(sargs, [s, v, a], cse=True)(*vals)
        stab = symkin.compile([s, v, a], sargs, ranges=L.RANGES)(*vals)
        for name, got in (("sympy.lambdify", raw), ("symkin numpy", stab)):
            errs = [rel_error(g, r, True) for g, r in zip(got, ref)]
            rows.append(dict(case=f"slider s, V_s, a_s, {label}", method=name, max_rel_error=max(errs), detail=[float(x) for x in errs]))
    # 10^6 turns
    law = sp.sin(L.M * L.W * S.t / 2)
    tt = np.linspace(0, 1e6, 1001) * 2 * np.pi / 0.8 + rng.uniform(0, 1, 1001)
    vals = [3.0, 0.8, tt]
    ref = np.array(symkin.compile(law, [L.M, L.W, S.t], backend="mpmath", digits=50)(*vals), dtype=float)
    for name, f in (("symkin numpy (plain phase)", symkin.compile(law, [L.M, L.W, S.t])), ("symkin numpy, reduce_phase=[t]", symkin.compile(law, [L.M, L.W, S.t], reduce_phase=[S.t]))):
        rows.append(dict(case="sin(m omega t/2) up to 10^6 turns (absolute error)", method=name, max_rel_error=float(np.max(np.abs(f(*vals) - ref)))))
    return rows


# --------------------------------------------------------------------------- dask, scene, reproduce
def dask_scaling(n: int = 4 * 10**7) -> list[dict]:
    try:
        import dask.array as da
        import distributed
    except ImportError:
        return []
    from symkin.numeric import dask_map

    law = L.differential_law()
    args = [S.omega("1"), S.omega("4"), S.radius("1"), S.radius("2"), S.radius("3")]
    f = symkin.compile(law, args)
    rows = []
    for workers in (1, 2):
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            with distributed.Client(cluster):
                x = da.random.uniform(1, 2, size=n, chunks=2 * 10**6)
                job = lambda: float(dask_map(f, x, 0.5, 3.0, 1.0, 2.0).max().compute())  # noqa: E731
                t = median_time(job, 3)
                rows.append(dict(workers=workers, points=n, points_per_s=n / t))
                print(f"dask {workers} workers: {n / t / 1e6:.1f} Mpts/s", flush=True)
    return rows


def call_costs() -> list[dict]:
    """benchmarks/call_overhead.py in this run: per-call cost against plain lambdify."""
    import call_overhead

    rows = []
    rng = np.random.default_rng(3)
    for n in (10**3, 10**5, 10**7):
        for title, (law, values) in call_overhead.cases(n, rng).items():
            args = sorted(law.rhs.free_symbols, key=lambda s: s.name)
            plain = sp.lambdify(args, law.rhs, modules="numpy")
            f = symkin.compile(law)
            t_plain = call_overhead.median_us(lambda: plain(*values), n)
            t_symkin = call_overhead.median_us(lambda: f(*values), n)
            rows.append(dict(law=title, n=n, lambdify_us=t_plain, symkin_us=t_symkin))
            print(f"{title:36s} {n:>9d} lambdify {t_plain:10.1f} us symkin {t_symkin:10.1f} us", flush=True)
    return rows


def scene_after_import() -> dict[str, float]:
    """Seconds after `import symkin`: building the AA scheme, and the ratio-only scene
    (derive, compile, evaluate once) on the built scheme; medians of 3 fresh processes."""
    code = (
        "import time, symkin; t0 = time.perf_counter(); "
        "mech = symkin.schemes.two_row('AA', teeth=True); t1 = time.perf_counter(); "
        "sc = symkin.Study(mech, ratios=[('H', '1', '4')]); "
        "sc.evaluate({'z_1': 100, 'z_2': 99, 'z_3': 100, 'z_4': 101}); t2 = time.perf_counter(); "
        "print(t1 - t0, t2 - t1)"
    )
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split() for _ in range(3)]
    return {"mechanism_s": statistics.median(float(r[0]) for r in runs), "scene_s": statistics.median(float(r[1]) for r in runs)}


def reproduce_time() -> float:
    exe = Path(sys.executable).with_name("symkin")
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        subprocess.run([str(exe), "reproduce", "--out", str(Path(tmp) / "out"), "--quiet"], capture_output=True, check=False)
        return time.perf_counter() - t0


# --------------------------------------------------------------------------- report
def write_plot(rows: list[dict], n: int, folder: Path) -> None:
    from matplotlib.figure import Figure

    from symkin.viz.figures import save

    laws = list(dict.fromkeys(r["law"] for r in rows))
    fig = Figure(figsize=(11, 8.5))
    methods = list(dict.fromkeys(r["method"] for r in rows))
    markers = "os^vD<>pPX*h"
    from matplotlib import colormaps

    cmap = colormaps["tab20"]
    for k, law in enumerate(laws):
        ax = fig.add_subplot(2, 2, k + 1)
        for j, m in enumerate(methods):
            pts = [r for r in rows if r["law"] == law and r["method"] == m and r["max_rel_error"] is not None]
            if not pts:
                continue
            best = max(pts, key=lambda r: r["n"])
            err = max(best["max_rel_error"], 1e-17)
            color = cmap(j % cmap.N)
            ax.scatter(best["points_per_s"], err, marker=markers[j % len(markers)], s=40, color=color, label=f"{m} (n={best['n']:.0e})")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(law, fontsize=9)
        ax.set_xlabel("points per second")
        ax.set_ylabel("max relative error vs 50 digits")
        ax.grid(True, which="major", lw=0.3)
    handles, labels = [], []
    for ax in fig.axes:  # every method once, from whichever panel has it
        for h, lbl in zip(*ax.get_legend_handles_labels()):
            if lbl.split(" (n=")[0] not in [x.split(" (n=")[0] for x in labels]:
                handles.append(h)
                labels.append(lbl)
    fig.legend(handles, [lbl.split(" (n=")[0] for lbl in labels], loc="lower center", ncol=3, fontsize=7)
    fig.suptitle("Speed versus accuracy at the largest size measured (errors below 1e-17 drawn at 1e-17)", fontsize=10)
    fig.subplots_adjust(bottom=0.17, hspace=0.35, wspace=0.3)
    save(fig, folder / "numerics-speed-error")


def fmt_rate(x: float) -> str:
    if x >= 1e6:
        return f"{x / 1e6:.1f} M"
    if x >= 1e3:
        return f"{x / 1e3:.1f} k"
    return f"{x:.0f}"


def fmt_err(x) -> str:
    return "-" if x is None else (f"{x:.1e}" if x else "0")


def write_markdown(res: dict, path: Path) -> None:
    rows = res["throughput"]
    sizes = sorted({r["n"] for r in rows if r["method"] != "sympy subs/evalf per point"})
    lines = [
        "# Numerics: speed versus accuracy",
        "",
        "Generated by `python benchmarks/run.py` (do not edit by hand; rerun to refresh).",
        f"Machine: {res['machine']}. Medians of repeated runs, all in one run; the machine is shared",
        f"(1-minute load average {res['load_average_start']:.1f} at the start, {res['load_average_end']:.1f} at the end),",
        "so compare rows of one run, as ratios, rather than absolute rates across runs.",
        "",
        "`symkin.compile(laws, args, backend=..., precision=..., digits=...)` is the one entry point;",
        "backends `numpy` (float64/float32, cse, chunks), `numba` (fused loop, threads; optional extra),",
        "`mpmath` (n digits), `exact` (rationals). Float backends evaluate stable forms (see",
        "`symkin.numeric.stable`). Errors are the largest relative error against a 50-digit mpmath",
        "reference on the first 1000 points (floored at 1e-3 of the law's largest value for the",
        "rational laws; normwise for the laws in time, whose zeros make pointwise errors meaningless).",
        "",
        "## Choosing",
        "",
        "```python",
        "f = symkin.compile(laws, args)                               # numpy float64: the default",
        "f = symkin.compile(laws, args, threads=2)                    # chunks shared by 2 threads",
        "f = symkin.compile(laws, args, backend='numba')              # fused loop, all threads",
        "f = symkin.compile(laws, args, precision='float32')          # ~1e-6 relative",
        "f = symkin.compile(laws, args, backend='mpmath', digits=50)  # reference",
        "f = symkin.compile(laws, args, backend='exact')              # Fractions",
        "f = symkin.compile(laws, args, ranges={e: (0, 1)})  # phases of t reduced (reduce_phase=() turns it off)",
        "```",
        "",
        "- Rational laws (ratios, differentials) are memory bound: the numba loop reads the inputs once",
        "  and writes the output once; NumPy makes a temporary per operation (symkin evaluates NumPy",
        "  in chunks of 16384 points so that temporaries stay in cache and are reused).",
        "- Laws in time are bound by sin/cos/atan2: NumPy's SIMD float64 and float32 routines beat",
        "  Numba's scalar libm calls on one thread (this llvmlite has no SVML); threads help both.",
        "- float32 is the fastest and keeps about 6 digits; mpmath and exact are for references and",
        "  papers (tens of thousands of points per second); per-point `subs/evalf` is slower still.",
        "- Laws are compiled as derived: `sympy.simplify` is never called (it costs seconds on the",
        "  slider laws and produced slower code in the issue's measurement).",
        "- The numba backend compiles one loop per law (scalars pass as arrays of one value with a step",
        "  of 0) and Numba caches it on disk (`$SYMKIN_CACHE_DIR`, default `~/.cache/symkin/kernels`):",
        "  another process loads it instead of compiling (about 1.9 s -> 0.3 s of CPU for the AA ratio).",
        "- The numba backend sets `OMP_WAIT_POLICY=PASSIVE` unless already set: with GNU OpenMP's",
        "  default a parallel loop on this busy 2-core machine took 16-32 ms per call instead of 0.03 ms.",
        "- Tooth numbers may be given as float arrays of whole values: NumPy checks and casts them chunk",
        "  by chunk while the chunk is in cache, Numba in its loop (rows \"float64 tooth arrays\").",
        "- Calls of at most one chunk (16384 points) with real inputs and no `out=` make one call of the",
        "  generated code on the arrays as given and one finiteness check (table \"Per-call cost\").",
        "- A call with scalars (Python floats or ints, NumPy float64) of a float64 law runs the law as",
        "  Python code on floats (the `math` module), without arrays; other input types, a value that",
        "  is not finite and a pole take the array path with its checks and warnings.",
        "- A difference of two products of inputs, `a b - c d`, is evaluated plainly (6 NumPy operations",
        "  with the check) and redone in double-double only where the products cancel (Numba: in its loop).",
        "  `stable=False` skips every stable form.",
        "",
        "## At and near a pole: what is guaranteed",
        "",
        "A pole is a point where a denominator of the law is exactly zero for the binary values passed",
        "(0.1 is not one tenth).",
        "",
        "- Complex, boolean, text and None inputs are refused (InputError); tooth numbers must be whole",
        "  (integer arrays, or float arrays of whole values below 2^63).",
        "- No nan or inf output is silent: where an input is nan or infinite a `NonFiniteInputWarning`",
        "  counts the points; anywhere else a `PoleWarning` does (`on_pole=\"raise\"`: `PoleError`).",
        "- Denominators evaluated exactly or to full relative accuracy: integer polynomials of tooth",
        "  numbers (exact integer arithmetic), differences of two inputs `x - y` (zero exactly when",
        "  x = y, one rounding), differences of two products of inputs `a b - c d` (double-double where they cancel:",
        "  within 3 units of 2^-53 of the exact value while the inputs are below 2^995 and the",
        "  products above 2^-969 in magnitude), sums of terms of one known sign, and products of these.",
        "  Where every denominator of a law is of these kinds (every ratio and speed law of the two-row",
        "  schemes, in teeth or radii), the float backends return inf or nan with a PoleWarning at a",
        "  pole, never a finite number, and near a pole the denominator loses no digits: the AA ratio",
        "  r1 r3/(r1 r3 - r2 r4) is within 3 units of 2^-53 of 50-digit mpmath at 2000 random points",
        "  within 60 ulps of its pole (tests/test_numeric_near_poles.py; extremes table below).",
        "- Other denominators (three or more terms of unknown sign, products of three or more inputs,",
        "  sums of functions of the inputs) are evaluated in float64 as written: near their poles they",
        "  lose about log2(sum of |terms| / |sum|) bits, and at a pole whose float sum does not round",
        "  to exactly zero they give a large finite number without a warning. Check such laws against",
        "  `backend=\"mpmath\"`; `f.stable_exprs` shows what the float code evaluates.",
        "",
        "## Memory bandwidth (same run)",
        "",
    ]
    bw = res["bandwidth"]
    for k, v in bw.items():
        lines.append(f"- {k.replace('_GBps', '')}: {v:.1f} GB/s (bytes read + written)")
    lines += ["", "Measured again before each law (the machine is shared):", ""]
    for r in res.get("bandwidth_per_law", []):
        lines.append(f"- before {r['law']}: best two-thread copy {r['copy_best_2threads_GBps']:.1f} GB/s")
    lines += ["", "## Throughput (points/s) and error", ""]
    for law in dict.fromkeys(r["law"] for r in rows):
        lines += [f"### {law}", "", "| method | " + " | ".join(f"10^{int(np.log10(n))}" for n in sizes) + " | max rel. error |", "|---|" + "---:|" * (len(sizes) + 1)]
        for m in dict.fromkeys(r["method"] for r in rows if r["law"] == law):
            rs = {r["n"]: r for r in rows if r["law"] == law and r["method"] == m}
            cells = [fmt_rate(rs[n]["points_per_s"]) if n in rs else "" for n in sizes]
            if m == "sympy subs/evalf per point":
                cells = [fmt_rate(next(iter(rs.values()))["points_per_s"]) + " (200 pts)"] + [""] * (len(sizes) - 1)
            errs = [r["max_rel_error"] for r in rs.values() if r["max_rel_error"] is not None]
            lines.append(f"| {m} | " + " | ".join(cells) + f" | {fmt_err(max(errs) if errs else None)} |")
        lines.append("")
    if res.get("call_costs"):
        lines += [
            "## Per-call cost of the NumPy backend (same run)",
            "",
            "`benchmarks/call_overhead.py`: medians in microseconds, symkin's default (numpy float64, stable",
            "forms) against plain `sympy.lambdify`; inputs away from poles. The AA radii law pays for its",
            "double-double denominator; the AI law (r1 r3 + r2 r4 cannot cancel) shows the per-call cost alone.",
            "",
            "| law | points | sympy.lambdify | symkin | symkin / lambdify |",
            "|---|---:|---:|---:|---:|",
        ]
        for r in res["call_costs"]:
            lines.append(
                f"| {r['law']} | 10^{int(np.log10(r['n']))} | {r['lambdify_us']:.1f} us | {r['symkin_us']:.1f} us | {r['symkin_us'] / r['lambdify_us']:.2f} |"
            )
        lines.append("")
    lines += ["## Ratios at the largest size (targets of issue 6)", ""]
    for item in res["ratios"]:
        lines.append(f"- {item}")
    lines += ["", "## Extremes: where naive float forms lose digits", "", "| case | method | max rel. error |", "|---|---|---:|"]
    for r in res["extremes"]:
        lines.append(f"| {r['case']} | {r['method']} | {fmt_err(r['max_rel_error'])} |")
    lines += ["", "Long times: with a plain phase, sin(c omega t) loses |c omega t| 2^-53 rad (about 7e-10 rad",
              "at 10^6 turns); `reduce_phase=[t]` evaluates the product in double-double arithmetic and reduces",
              "it modulo 2 pi, leaving about 2^-52 pi at any number of turns below 2^27.", ""]
    if res["dask"]:
        lines += ["## Dask (local cluster, this machine)", "", "| workers | points | points/s | speed-up |", "|---:|---:|---:|---:|"]
        base = res["dask"][0]["points_per_s"]
        for r in res["dask"]:
            lines.append(f"| {r['workers']} | {r['points']:.0e} | {fmt_rate(r['points_per_s'])} | {r['points_per_s'] / base:.2f} |")
        lines.append("")
    lines += [
        "## Start-up",
        "",
        f"- after `import symkin`, building the AA scheme with symbolic teeth: {res['scene_s']['mechanism_s']:.3f} s (core; `import symkin`",
        "  itself is lazy, so this includes importing SymPy)",
        f"- then the ratio-only scene (derive + compile + evaluate once): {res['scene_s']['scene_s']:.3f} s (medians of 3 processes)",
        f"- `symkin reproduce` (all papers): {res['reproduce_s']:.1f} s",
        "",
        "![speed versus error](numerics-speed-error.png)",
        "",
    ]
    path.write_text("\n".join(lines))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="10^3 and 10^5 points only; no Dask")
    opts = ap.parse_args()
    sizes = [10**3, 10**5] if opts.quick else [10**3, 10**5, 10**7]
    res: dict = {
        "machine": f"{os.cpu_count()} cores, Python {platform.python_version()}, numpy {np.__version__}, sympy {sp.__version__}"
        + (f", numba {__import__('numba').__version__}" if HAS_NUMBA else ", no numba"),
    }
    res["load_average_start"] = os.getloadavg()[0]
    res["bandwidth"] = copy_bandwidth()
    print(res["bandwidth"], flush=True)
    cases = build_cases(max(sizes))
    rows = []
    for title, case in cases.items():
        rows += run_case(title, case, sizes)
    res["throughput"] = rows
    res["bandwidth_per_law"] = [dict(law=t, **c["bandwidth"]) for t, c in cases.items()]
    n = max(sizes)

    def rate(law, method):
        return next((r["points_per_s"] for r in rows if r["law"].startswith(law) and r["method"] == method and r["n"] == n), None)

    ratios = []
    best = "symkin numba float64, 2 threads" if HAS_NUMBA else "symkin numpy float64"
    for law, _key in (("ratio", "ratio"), ("differential", "differential"), ("elliptical", "elliptical")):
        title = next(t for t in cases if t.startswith(law))
        b, lam, np_ = rate(law, best), rate(law, "sympy.lambdify"), rate(law, "symkin numpy float64")
        line = f"{title}: {best} / sympy.lambdify = {b / lam:.1f}x; symkin numpy float64 / sympy.lambdify = {np_ / lam:.1f}x"
        reused = rate(law, "(same, into a reused out= buffer)")
        if reused:
            line += f"; into a reused out= buffer {reused / lam:.1f}x"
        if cases[title]["bytes"] and law != "elliptical":
            copy = cases[title]["bandwidth"]["copy_best_2threads_GBps"]
            gbps = b * cases[title]["bytes"] / 1e9
            line += f"; it moves {gbps:.1f} GB/s = {gbps / copy:.0%} of the two-thread copy bandwidth measured just before ({copy:.1f} GB/s)"
            if reused:
                line += f" ({reused * cases[title]['bytes'] / 1e9 / copy:.0%} into a reused buffer)"
        ratios.append(line)
    res["ratios"] = ratios
    res["extremes"] = extremes()
    res["call_costs"] = call_costs()
    res["dask"] = [] if opts.quick else dask_scaling()
    res["scene_s"] = scene_after_import()
    res["reproduce_s"] = reproduce_time()
    res["load_average_end"] = os.getloadavg()[0]
    (HERE / "results.json").write_text(json.dumps(res, indent=1))
    docs = ROOT / "docs"
    docs.mkdir(exist_ok=True)
    write_plot(rows, n, docs)
    write_markdown(res, docs / "numerics.md")
    print("\n".join(ratios))
    print(f"wrote {docs / 'numerics.md'}")


if __name__ == "__main__":
    main()
