"""Speed and accuracy of symkin's compiled laws against the usual alternatives, side by side,
in one run; writes docs/numerics.md and benchmarks/results.json from that run.

    python benchmarks/run.py                 # about 3-6 minutes on 2 shared cores
    python benchmarks/run.py --quick         # 1, 100 and 10^3 points only (a smoke run; docs not written)

Laws (as the README derives them, nothing substituted): the AA ratio i_H1^(4) in tooth numbers,
the II general differential omega_H(omega_1, omega_4, r1..r4) in radii (denominator
r1 r3 - r2 r4), the AI planet-particle acceleration w_x(omega_1, r1..r4, t) and the
elliptical-drive Cardan slider acceleration a_s (symkin.mechanisms.cardan).

Methods, every one timed on the same inputs in the same rounds (round robin, so that a busy
moment of the shared machine hits them all): hand-written NumPy, sympy.lambdify,
lambdify(cse=True), numexpr (if installed), symkin.compile(law, backend="numpy") (NumPy float64
with its stable forms and checks) and symkin.compile(law, backend="numba") (if installed);
symkin.compile(law) without a backend is the numba one where numba is installed, else NumPy.
Each cell is the median wall time of one call over the rounds, with the spread
(max - min)/median; the 1-minute load average is recorded at the start and the end.

Accuracy: every method against symkin's mpmath backend at 50 digits on the same binary
inputs (1000 points), and the hard regions: the elliptical drive at e = 0.999999 including
its carrier-speed peaks, the planet laws at t = 10^6 s, the AA ratio and the II differential
within 60 ulps of their poles, float32 near a pole.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import sympy as sp

os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")  # as symkin's numba backend does
HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

import laws as L  # noqa: E402

import symkin  # noqa: E402
from symkin import schemes  # noqa: E402
from symkin import symbols as S  # noqa: E402
from symkin.numeric.backends import numba_available  # noqa: E402

HAS_NUMBA = numba_available()
#: The backend symkin.compile takes when none is named (symkin.numeric.default_backend).
DEFAULT = "numba" if HAS_NUMBA else "numpy"


def label(backend: str) -> str:
    """A method's name in the tables: the default backend says so."""
    return f"symkin {backend} (default)" if backend == DEFAULT else f"symkin {backend}"
try:
    import numexpr  # noqa: F401

    HAS_NUMEXPR = True
except ImportError:
    HAS_NUMEXPR = False

SIZES = (1, 100, 10**3, 10**5, 10**6)
#: The NumPy backend without the stable-form rewriting: the user's speed-for-accuracy trade.
UNSTABLE = "symkin numpy, stable=False"
W1, W4 = S.omega("1"), S.omega("4")
R = [S.radius(i) for i in "1234"]
Z = [S.teeth(i) for i in "1234"]
SLIDER_ARGS = [L.E, L.L, L.M, L.W, L.THETA2, L.THETA0, S.t]

#: The issue's figures (issue 18, "before"), by the row of this run they correspond to.
BEFORE = {
    "speed differential": "0.27x lambdify speed at 10^7 points (25.5 vs 94.5 Mpt/s), i.e. 3.7x its time",
    "slider peaks": "4.0e-9 (default); 3.1e-15 with the opt-in reduce_phase=[t]",
    "planet 1e6": "1.6e-10 with or without reduce_phase",
    "exact speed": "2.2e-9 to 5.2e-9 (issue 34); 1.9e-8 before this change in one run",
    "float32 pole": "relative error 1.0, finite, no warning",
    "scalar call": "37 us per scalar call (lambdify 0.3 us)",
}


# --------------------------------------------------------------------------- hand-written forms
def hand_ratio(z1, z2, z3, z4):  # i_H1^(4) = z1 z3/(z1 z3 - z2 z4)
    return z1 * z3 / (z1 * z3 - z2 * z4)


def hand_differential(w1, w4, r1, r2, r3, r4):  # II: omega_H = (w1 r1 r3 - w4 r2 r4)/(r1 r3 - r2 r4)
    return (w1 * r1 * r3 - w4 * r2 * r4) / (r1 * r3 - r2 * r4)


def hand_planet(w1, r1, r2, r3, r4, t):
    wh = w1 * r1 * r3 / (r1 * r3 + r2 * r4)
    w23 = -wh * (r4 - r3) / r3
    return -wh**2 * (r1 + r2) * np.cos(wh * t) + w23**2 * r2 * np.cos(w23 * t)


def hand_slider(e, l, m, w, th2, th0, t):
    k = (1 + e) / (1 - e)
    theta = th0 + 2 / m * np.arctan(k * np.tan(m * w * t / 2))
    c = np.cos(m * w * t)
    d = 1 - 2 * e * c + e**2
    wh = w * (1 - e**2) / d
    eh = -w * (1 - e**2) * 2 * e * m * w * np.sin(m * w * t) / d**2
    return -2 * l * np.cos(th2 - theta) * wh**2 + 2 * l * np.sin(th2 - theta) * eh


NUMEXPR = {
    "ratio": "z1 * z3 / (z1 * z3 - z2 * z4)",
    "differential": "(w1 * r1 * r3 - w4 * r2 * r4) / (r1 * r3 - r2 * r4)",
}


def slider():
    from symkin.drives import EllipticalGears
    from symkin.mechanisms.cardan import CardanSlider

    return CardanSlider.build(L.L, drive=EllipticalGears(L.W, L.E, L.M), guide_angle=L.THETA2, carrier_angle=L.THETA0)


def teeth(rng, n: int) -> list[np.ndarray]:
    """Tooth numbers 20..199 away from the poles z1 z3 = z2 z4 (a pole is timed as a pole report:
    the hard regions measure poles; here z4 + 1 where z1 z3 = z2 z4, which cannot be one again)."""
    z = [rng.integers(20, 200, n) for _ in range(4)]
    z[3] = np.where(z[0] * z[2] == z[1] * z[3], z[3] + 1, z[3])
    return z


def cases(nmax: int) -> dict:
    rng = np.random.default_rng(7)
    speeds = schemes.two_row("II").speeds({"1": W1, "4": W4})
    return {
        "ratio i_H1 (AA, teeth)": dict(
            key="ratio", expr=schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4").rhs, args=Z, hand=hand_ratio,
            values=teeth(rng, nmax), normwise=False),
        "differential omega_H (II, radii)": dict(
            key="differential", expr=speeds.law("H").rhs, args=[W1, W4, *R], hand=hand_differential,
            values=[rng.uniform(-1, 1, nmax), rng.uniform(-1, 1, nmax), rng.uniform(5, 10, nmax), rng.uniform(1, 2, nmax),
                    rng.uniform(2.5, 4, nmax), rng.uniform(1, 2, nmax)], normwise=False),
        "planet acceleration w_x (AI)": dict(
            key="planet", expr=L.planet_acceleration()[0], args=[W1, *R, S.t], hand=hand_planet,
            values=[2.0, 2.0, 1.5, 1.0, 4.5, rng.uniform(0, 10, nmax)], normwise=True),
        "slider acceleration a_s (elliptical drive)": dict(
            key="slider", expr=slider().acceleration, args=SLIDER_ARGS, hand=hand_slider,
            values=[rng.uniform(0.05, 0.95, nmax), 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, rng.uniform(0, 10, nmax)], normwise=True,
            reference=L.slider_laws_continuous()[2]),
    }


def methods(case: dict) -> dict:
    expr, args = case["expr"], case["args"]
    out = {
        "hand NumPy": case["hand"],
        "sympy.lambdify": sp.lambdify(args, expr, modules="numpy"),
        "lambdify(cse=True)": sp.lambdify(args, expr, modules="numpy", cse=True),
    }
    if HAS_NUMEXPR and case["key"] in NUMEXPR:
        import numexpr as ne

        text = NUMEXPR[case["key"]]
        names = ["z1", "z2", "z3", "z4"] if case["key"] == "ratio" else ["w1", "w4", "r1", "r2", "r3", "r4"]
        out["numexpr"] = lambda *v: ne.evaluate(text, local_dict=dict(zip(names, (np.asarray(x, float) for x in v))))
    out[label("numpy")] = symkin.compile(expr, args, backend="numpy", ranges=L.RANGES)
    out[UNSTABLE] = symkin.compile(expr, args, backend="numpy", ranges=L.RANGES, stable=False)
    if HAS_NUMBA:
        out[label("numba")] = symkin.compile(expr, args, backend="numba", ranges=L.RANGES)
    return out


# --------------------------------------------------------------------------- timing
def timed(fn, values, n: int) -> float:
    """Wall seconds of one call, as the mean of a loop long enough to be timed (>= 5 ms)."""
    loops = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(loops):
            fn(*values)
        dt = time.perf_counter() - t0
        if dt >= 5e-3 or loops >= 1 << 16:
            return dt / loops
        loops *= 4 if dt < 1e-3 else 2


def point(values, n: int) -> list:
    if n == 1:  # Python numbers: tooth numbers as Python integers, the rest as floats
        return [v[0].item() if np.ndim(v) else v for v in values]
    return [v[:n] if np.ndim(v) else v for v in values]


def speed(all_cases: dict, sizes, rounds: int) -> list[dict]:
    rows = []
    for title, case in all_cases.items():
        fns = methods(case)
        for n in sizes:
            vals = point(case["values"], n)
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                for fn in fns.values():
                    fn(*vals)  # warm: numba's first call compiles (or loads its disk cache)
                samples: dict[str, list[float]] = {name: [] for name in fns}
                for _ in range(rounds if n < 10**6 else max(3, rounds - 2)):
                    for name, fn in fns.items():
                        samples[name].append(timed(fn, vals, n))
            for name, xs in samples.items():
                med = statistics.median(xs)
                rows.append(dict(law=title, method=name, n=n, median_s=med, spread=(max(xs) - min(xs)) / med))
            lam = statistics.median(samples["sympy.lambdify"])
            print(f"{title:45s} {n:>8d}  " + "  ".join(f"{k} {statistics.median(v) / lam:.2f}" for k, v in samples.items()), flush=True)
    return rows


# --------------------------------------------------------------------------- random points, exact
def random_points(n: int = 10**5) -> list[dict]:
    """Relative error of every method on ``n`` random points of the II differential (as the README
    derives it, and with r4 = r1 - r2 + r3 substituted and factored), against exact rational
    arithmetic (Fraction) on the same binary inputs: the benchmark radii, and radii of one range
    whose products r1 r3 and r2 r4 overlap (numerator and denominator both cancel)."""
    from fractions import Fraction

    law = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    sub = sp.factor(law.subs(R[3], R[0] - R[1] + R[2]))
    rng = np.random.default_rng(34)
    w = [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)]
    bench = [rng.uniform(5, 10, n), rng.uniform(1, 2, n), rng.uniform(2.5, 4, n), rng.uniform(1, 2, n)]
    overlap = [rng.uniform(1, 2, n) for _ in range(4)]
    rows = []
    for title, expr, args, values in (
        ("II in radii, benchmark radii", law, [W1, W4, *R], w + bench),
        ("II in radii, overlapping products", law, [W1, W4, *R], w + overlap),
        ("II, r4 substituted, benchmark radii", sub, [W1, W4, *R[:3]], w + bench[:3]),
    ):
        points = list(zip(*(map(Fraction, v.tolist()) for v in values)))
        if len(args) == 5:
            points = [(a, b, c, d, e, c - d + e) for a, b, c, d, e in points]
        exact = [(a * r1 * r3 - b * r2 * r4) / (r1 * r3 - r2 * r4) for a, b, r1, r2, r3, r4 in points]
        fns = {"sympy.lambdify": sp.lambdify(args, expr), "lambdify(cse=True)": sp.lambdify(args, expr, cse=True),
               label("numpy"): symkin.compile(expr, args, backend="numpy"),
               UNSTABLE: symkin.compile(expr, args, backend="numpy", stable=False)}
        if HAS_NUMBA:
            fns[label("numba")] = symkin.compile(expr, args, backend="numba")
            fns["symkin default, first calls (NumPy code)"] = symkin.compile(expr, args, jit="auto", backend="numba")
        for name, fn in fns.items():
            got = np.asarray(fn(*values), dtype=float).tolist()
            err = sorted(float(abs(Fraction(g) - x) / abs(x)) for g, x in zip(got, exact) if x)
            rows.append(dict(law=title, method=name, max=err[-1], median=err[len(err) // 2], n=n))
            print(f"{title:40s} {name:42s} max {err[-1]:.2e} median {err[len(err) // 2]:.2e}", flush=True)
    return rows


def first_use(rounds: int) -> dict:
    """benchmarks/first_use.py's measurement (fresh processes, empty and warm kernel cache)."""
    import first_use as F

    load = os.getloadavg()[0]
    res = F.measure(rounds)
    res["load"] = [load, os.getloadavg()[0]]
    return res


# --------------------------------------------------------------------------- accuracy
def mp(expr, args, values) -> list[np.ndarray]:
    f = symkin.compile(expr, args, backend="mpmath", digits=50)
    out = f(*values)
    out = out if isinstance(out, tuple) else (out,)
    return [np.array([float(x) for x in np.reshape(o, -1)]) for o in out]


def error(got, ref: np.ndarray, normwise: bool, floor: float = 0.0) -> float:
    got = np.asarray(got, dtype=float).reshape(-1)
    if normwise:
        return float(np.max(np.abs(got - ref)) / np.max(np.abs(ref)))
    with np.errstate(all="ignore"):  # relative, floored at ``floor`` times the largest value (a law's zeros)
        err = np.abs(got - ref) / np.maximum(np.abs(ref), floor * np.max(np.abs(ref[np.isfinite(ref)])))
    return float(np.max(np.where(np.isnan(err), np.inf, err)))


def accuracy(all_cases: dict) -> list[dict]:
    rows = []
    for title, case in all_cases.items():
        vals = point(case["values"], 1000)
        (ref,) = mp(case.get("reference", case["expr"]), case["args"], vals)
        for name, fn in methods(case).items():
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                got = fn(*vals)
            rows.append(dict(law=title, method=name, error=error(got, ref, case["normwise"], floor=1e-3),
                             metric="normwise" if case["normwise"] else "relative"))
    return rows


def hard_regions() -> list[dict]:
    rows = []
    rng = np.random.default_rng(11)
    float_backends = ["numpy"] + (["numba"] if HAS_NUMBA else [])

    def add(region, method, err, metric, warned=None, before=None):
        rows.append(dict(region=region, method=method, error=err, metric=metric, warned=warned, before=before))

    # elliptical drive at e = 0.999999: the carrier speed peaks at t = 2.5 k (cos(m omega t) = 1)
    cs = slider()
    laws = [cs.displacement, cs.velocity, cs.acceleration]
    k = np.arange(9)
    t = np.concatenate([2.5 * k, 2.5 * k + 1e-6, 2.5 * k + 1e-3, 2.5 * k[1:] - 1e-3, np.linspace(0, 20, 41)])
    vals = [0.999999, 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, t]
    ref = mp(list(L.slider_laws_continuous()), SLIDER_ARGS, vals)
    region = "slider s, V_s, a_s at e = 0.999999, m = 1, omega = 0.8 pi rad/s (a float input), t on and beside the speed peaks (max of the 3)"
    raw = sp.lambdify(SLIDER_ARGS, laws, modules="numpy", cse=True)(*vals)
    add(region, "lambdify(cse=True)", max(error(g, r, True) for g, r in zip(raw, ref)), "normwise")
    for b in float_backends:
        got = symkin.compile(laws, SLIDER_ARGS, backend=b, ranges=L.RANGES)(*vals)
        add(region, label(b), max(error(g, r, True) for g, r in zip(got, ref)), "normwise",
            before=BEFORE["slider peaks"] if b == "numpy" else None)
    # the same at the 2018 paper's own exact speed 4 pi/5 rad/s (substituted: the phase 4 pi m t/5)
    exact_args = [a for a in SLIDER_ARGS if a != L.W]
    exact_laws = [x.subs(L.W, 4 * sp.pi / 5) for x in laws]
    evals = [v for a, v in zip(SLIDER_ARGS, vals) if a != L.W]
    ref = mp([x.subs(L.W, 4 * sp.pi / 5) for x in L.slider_laws_continuous()], exact_args, evals)
    region = "slider s, V_s, a_s at e = 0.999999, m = 1, omega = 4 pi/5 = 0.8 pi rad/s exactly (substituted, the 2018 drive), on and beside the speed peaks (max of the 3)"
    raw = sp.lambdify(exact_args, exact_laws, modules="numpy", cse=True)(*evals)
    add(region, "lambdify(cse=True)", max(error(g, r, True) for g, r in zip(raw, ref)), "normwise")
    for b in float_backends:
        got = symkin.compile(exact_laws, exact_args, backend=b, ranges=L.RANGES)(*evals)
        add(region, label(b), max(error(g, r, True) for g, r in zip(got, ref)), "normwise",
            before=BEFORE["exact speed"] if b == "numpy" else None)
    # planet laws at t = 10^6 s
    motion = schemes.two_row("AI").motion({"1": W1, "4": 0})
    particle = motion.particle("23", (R[0], 0))
    plaws = [*particle.velocity, *particle.acceleration]
    pargs = [W1, *R, S.t]
    vals = [2.0, 2.0, 1.5, 1.0, 4.5, 1e6 + rng.uniform(0, 20, 200)]
    ref = mp(plaws, pargs, vals)
    region = "planet velocity and acceleration (x, y; AI) at t = 1e6 s + [0, 20] s (max of the 4)"
    raw = sp.lambdify(pargs, plaws, modules="numpy")(*vals)
    add(region, "sympy.lambdify", max(error(g, r, True) for g, r in zip(raw, ref)), "normwise")
    plain = symkin.compile(plaws, pargs, backend="numpy", reduce_phase=())(*vals)
    add(region, "symkin numpy, reduce_phase=() (off)", max(error(g, r, True) for g, r in zip(plain, ref)), "normwise")
    for b in float_backends:
        got = symkin.compile(plaws, pargs, backend=b)(*vals)
        add(region, label(b), max(error(g, r, True) for g, r in zip(got, ref)), "normwise",
            before=BEFORE["planet 1e6"] if b == "numpy" else None)
    # AA ratio in radii and II differential within 60 ulps of their poles
    r1, r2, r3 = (rng.uniform(0.1, 3, 1000) for _ in range(3))
    r4 = r1 * r3 / r2 * (1 + rng.integers(-60, 61, 1000) * 2.0**-53)
    aa = schemes.two_row("AA").ratio("H", "1", fixed="4").rhs
    ii = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    w1, w4 = rng.uniform(1, 2, 1000), rng.uniform(-1, 0, 1000)
    for region, expr, args, vals in (
        ("AA ratio r1 r3/(r1 r3 - r2 r4) in radii, r2 r4 within 60 ulps of r1 r3", aa, R, [r1, r2, r3, r4]),
        ("II differential omega_H in radii, r2 r4 within 60 ulps of r1 r3", ii, [W1, W4, *R], [w1, w4, r1, r2, r3, r4]),
    ):
        (ref,) = mp(expr, args, vals)
        with warnings.catch_warnings(), np.errstate(all="ignore"):
            warnings.simplefilter("ignore")
            add(region, "sympy.lambdify", error(sp.lambdify(args, expr, modules="numpy")(*vals), ref, False), "relative")
        for b in float_backends:
            add(region, label(b), error(symkin.compile(expr, args, backend=b)(*vals), ref, False), "relative")
    # float32 near the pole, from float64 inputs: the rounding to float32 moves the point
    region = "AA ratio in radii, float32 requested, float64 inputs within 60 ulps of the pole"
    (ref,) = mp(aa, R, [r1, r2, r3, r4])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = symkin.compile(aa, R, backend="numpy", precision="float32")(r1, r2, r3, r4)
    add(region, "symkin numpy float32", error(got, ref, False), "relative",
        warned=", ".join(sorted({w.category.__name__ for w in caught})) or "no", before=BEFORE["float32 pole"])
    return rows


# --------------------------------------------------------------------------- 10^7 points
def issue_size(rounds: int = 3) -> dict:
    """The II differential in radii at 10^7 points, as issue 18 measured it: lambdify and the
    float backends in round robin (median wall time of one call)."""
    n = 10**7
    rng = np.random.default_rng(7)
    vals = [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(5, 10, n), rng.uniform(1, 2, n),
            rng.uniform(2.5, 4, n), rng.uniform(1, 2, n)]
    expr = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    fns = {"sympy.lambdify": sp.lambdify([W1, W4, *R], expr, modules="numpy"),
           label("numpy"): symkin.compile(expr, [W1, W4, *R], backend="numpy")}
    if HAS_NUMBA:
        fns[label("numba")] = symkin.compile(expr, [W1, W4, *R], backend="numba")
    samples: dict[str, list[float]] = {k: [] for k in fns}
    with np.errstate(all="ignore"):
        for fn in fns.values():
            fn(*vals)
        for _ in range(rounds):
            for k, fn in fns.items():
                t0 = time.perf_counter()
                fn(*vals)
                samples[k].append(time.perf_counter() - t0)
    return {k: statistics.median(v) for k, v in samples.items()} | {"n": n, "load": os.getloadavg()[0]}


# --------------------------------------------------------------------------- fixed costs
def best(fn, loops: int = 2000, repeat: int = 7) -> float:
    """Seconds per call: the minimum over ``repeat`` loops of ``loops`` calls (fixed costs of a
    few microseconds: the minimum is the cost without the machine's interruptions)."""
    out = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(loops):
            fn()
        out.append((time.perf_counter() - t0) / loops)
    return min(out)


def fixed_costs(all_cases: dict) -> list[dict]:
    """Where the time of a small call goes, per law: the whole call, lambdify, the generated code
    alone (its own checks inside: the cancellation test's two reductions, the long phases' two),
    and each check the NumPy path adds around it, timed on its own (10^3 points and one point)."""
    from symkin.numeric.backends import NumpyBackend

    rows = []
    for title, case in all_cases.items():
        f = symkin.compile(case["expr"], case["args"], backend="numpy", ranges=L.RANGES)
        lam = sp.lambdify(case["args"], case["expr"], modules="numpy")
        ev = f._evaluator
        assert isinstance(ev, NumpyBackend)
        for n in (1, 10**3):
            vals = point(case["values"], n)
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                f(*vals)
                row = dict(law=title, n=n, call=best(lambda: f(*vals)), lambdify=best(lambda: lam(*vals)))
                if n == 1:
                    code = ev._scalar_code
                    flo = [float(v) for v in vals]
                    ints = [int(v) for v, i in zip(vals, ev.integer_flags) if i]
                    row["generated"] = best(lambda: code(*flo, *ints))
                else:
                    _shape, floats, ints = ev.prepare(vals)
                    ints = ev.integer_chunk(ints)
                    out = list(ev.func(*floats, *ints))
                    row["generated"] = best(lambda: ev.func(*floats, *ints))
                    def enter_exit():
                        with np.errstate(all="ignore"):  # (as the call does: a new context each time)
                            pass

                    row["errstate"] = best(enter_exit)
                    row["finite"] = best(lambda: [np.add.reduce(r, axis=None) for r in out])
                    row["bound"] = best(lambda: ev.bound.overflows(ints)) if ints else 0.0
                    row["reduction"] = best(lambda: np.minimum.reduce(out[0], axis=None))
            rows.append(row)
    return rows


# --------------------------------------------------------------------------- report
def fmt_time(s: float) -> str:
    if s < 1e-3:
        return f"{s * 1e6:.1f} us"
    return f"{s * 1e3:.1f} ms" if s < 1 else f"{s:.2f} s"


def markdown(res: dict) -> str:
    load = res["load"]
    sizes = sorted({r["n"] for r in res["speed"]})
    lines = [
        "# Numerics: speed and accuracy",
        "",
        "Generated by `python benchmarks/run.py` from one run (do not edit by hand; rerun to refresh).",
        f"Machine: {res['machine']}; 1-minute load average {load[0]:.1f} at the start and {load[1]:.1f} at the end",
        "(2 cores shared with other work: compare the methods of one row, as ratios, not absolute times across runs).",
        "",
        "Laws as the README derives them, nothing substituted: the AA ratio i_H1 in tooth numbers, the II general",
        "differential omega_H(omega_1, omega_4, r1..r4) in radii (denominator r1 r3 - r2 r4, evaluated in double-double",
        "where its products cancel), the AI planet-particle acceleration w_x(omega_1, r1..r4, t) and the",
        "elliptical-drive slider acceleration a_s. `symkin numpy` is `symkin.compile(law, backend=\"numpy\")` (NumPy",
        "float64, stable forms, input and pole checks); `symkin numba` is `backend=\"numba\"` (one fused loop, all",
        f"threads from 2^15 points); `(default)` marks what `symkin.compile(law)` takes on this machine ({DEFAULT}:",
        "numba where it is installed). Each cell is the median wall time of one call over the rounds (methods in",
        "round robin), spread = (max - min)/median. A call with 1 point passes Python numbers (the one-point path,",
        "the same for both backends: the type test of each argument and the finiteness test of each output, which",
        "a bare lambdify expression does not make). NumPy evaluates a call of up to 2^17 points in one piece, larger",
        "calls in chunks of 2^17 points.",
        "",
        "## Time per call, as a ratio to sympy.lambdify (below 1: faster than lambdify)",
        "",
    ]
    methods_seen = list(dict.fromkeys(r["method"] for r in res["speed"]))
    for law in dict.fromkeys(r["law"] for r in res["speed"]):
        lines += [f"### {law}", "", "| method | " + " | ".join(f"{n:.0e} points" for n in sizes) + " |",
                  "|---|" + "---:|" * len(sizes)]
        cell = {(r["method"], r["n"]): r for r in res["speed"] if r["law"] == law}
        for m in methods_seen:
            if not any((m, n) in cell for n in sizes):
                continue
            parts = []
            for n in sizes:
                r, lam = cell.get((m, n)), cell.get(("sympy.lambdify", n))
                parts.append(f"{r['median_s'] / lam['median_s']:.2f} ({fmt_time(r['median_s'])}, ±{r['spread']:.0%})" if r and lam else "")
            lines.append(f"| {m} | " + " | ".join(parts) + " |")
        lines.append("")
    lines += [
        "## Error against mpmath at 50 digits (1000 points of the timed inputs)",
        "",
        "Relative error (floored at 1e-3 of the largest value: the differential has zeros) for the ratio and the",
        "differential, normwise (max |error| / max |value|) for the laws in time, whose zeros make pointwise",
        "errors meaningless. Near the poles (hard regions) the values are huge and the floor does not act.",
        "",
        "| law | " + " | ".join(dict.fromkeys(r["method"] for r in res["accuracy"])) + " |",
        "|---|" + "---:|" * len(dict.fromkeys(r["method"] for r in res["accuracy"])),
    ]
    acc_methods = list(dict.fromkeys(r["method"] for r in res["accuracy"]))
    for law in dict.fromkeys(r["law"] for r in res["accuracy"]):
        by = {r["method"]: r["error"] for r in res["accuracy"] if r["law"] == law}
        lines.append(f"| {law} | " + " | ".join(f"{by[m]:.1e}" if m in by else "" for m in acc_methods) + " |")
    if res.get("random"):
        rnd = res["random"]
        lines += [
            "", f"## Random points against exact rational arithmetic ({rnd[0]['n']:.0e} points)", "",
            "Relative error, pointwise (no floor), against `fractions.Fraction` arithmetic on the same binary inputs:",
            "max and median over the points. The II differential's numerator `w1 r1 r3 - w4 r2 r4` cancels wherever",
            "the result is small; the float64 backends sum it error-free (numba: always; NumPy: where the plain",
            "sum is not certified within 8 units), so the law is within a few units in the last place at every point.",
            "`stable=False` evaluates the law as written (lambdify's arithmetic, with symkin's common subexpressions).",
            "",
            "| law | method | max | median |", "|---|---|---:|---:|",
        ]
        lines += [f"| {r['law']} | {r['method']} | {r['max']:.1e} | {r['median']:.1e} |" for r in rnd]
    lines += njit_section(res) + choice_section(res)
    if res.get("first_use"):
        fu = res["first_use"]
        lines += [
            "", f"## First use: a fresh process to the README's numeric example ({fu['rounds']} rounds"
            + (f", load {fu['load'][0]:.1f} -> {fu['load'][1]:.1f})" if "load" in fu else ")"), "",
            "`python benchmarks/first_use.py`: each figure its own child process, from before `import symkin`: the AA",
            "ratio compiled and called once (first result), then a Study of the AI planet acceleration evaluated at",
            "10^5 times (total). `default` names no backend (numba in `jit=\"auto\"`: the NumPy code until the time",
            "spent there pays for compiling), `numba` names it (compiled at the first call). Empty: a new kernel",
            "cache folder; warm: the same example run once before with that folder. CPU seconds of the child (all",
            "threads), wall seconds in brackets, medians; ratio: over the numpy mode's CPU time in the same rounds.",
            "",
            "| backend | kernel cache | first result | ratio | total | ratio | kernel compiled |",
            "|---|---|---:|---:|---:|---:|---|",
        ]
        for r in fu["rows"]:
            lines.append(f"| {r['mode']} | {r['cache']} | {r['first_cpu']:.2f} s ({r['first_wall']:.2f} s) | "
                         f"{r['first_cpu_ratio']:.2f} | {r['total_cpu']:.2f} s ({r['total_wall']:.2f} s) | "
                         f"{r['total_cpu_ratio']:.2f} | {'yes' if r['compiled'] else 'no'} |")
    lines += [
        "",
        "## Hard regions, against mpmath at 50 digits",
        "",
        "`before` is the figure issue 18 (issue 34 for the exact speed) reported for the default path before that work.",
        "",
        "| region | method | error | metric | warning | before (issue 18) |",
        "|---|---|---:|---|---|---|",
    ]
    for r in res["hard"]:
        lines.append(f"| {r['region']} | {r['method']} | {r['error']:.1e} | {r['metric']} | {r['warned'] or ''} | {r['before'] or ''} |")
    # the issue's speed figures beside this run's
    if res.get("fixed"):
        us = lambda x: f"{x * 1e6:.2f}"  # noqa: E731
        lines += [
            "", "## Where the time of a small NumPy call goes (microseconds, this run)", "",
            "Each piece timed on its own, the minimum of 7 loops (the cost without interruptions), so the pieces",
            "need not add up to the call exactly. `generated` is the generated code alone: at one point the",
            "Python-float code (the call adds the type test of each argument, the finiteness test of each output",
            "and the conversion to a NumPy float64); at 10^3 points the NumPy code, with the tests inside it (the",
            "cancellation test of `a b - c d`: two reductions; a long phase: two reductions, and its reduction",
            "where a phase is long). Around it the call adds one `np.errstate` context, one finiteness sum per",
            "output and, for tooth numbers, the int64 bound (one bitwise-or reduction per array); `reduction` is",
            "one min-reduction of the output's size, the unit of those tests.",
            "",
            "| law | points | call | lambdify | generated | errstate | finiteness | tooth bound | one reduction |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for r in res["fixed"]:
            cells = [us(r["call"]), us(r["lambdify"]), us(r["generated"])]
            cells += [us(r[k]) if k in r else "" for k in ("errstate", "finite")]
            cells += [us(r["bound"]) if r.get("bound") else ("" if r["n"] == 1 else "-"), us(r["reduction"]) if "reduction" in r else ""]
            lines.append(f"| {r['law']} | {r['n']} | " + " | ".join(cells) + " |")
    lines += ["", "## The issue's figures beside this run's", ""]
    cell = {(r["law"], r["method"], r["n"]): r for r in res["speed"]}
    big = max(sizes)
    diff = "differential omega_H (II, radii)"
    d_l = cell.get((diff, "sympy.lambdify", big))
    for b in dict.fromkeys([DEFAULT, "numpy"]):
        d_s = cell.get((diff, label(b), big))
        if d_s and d_l:
            lines.append(f"- II differential in radii, {label(b)}: before (the default path, NumPy), "
                         f"{BEFORE['speed differential']}; this run, {d_s['median_s'] / d_l['median_s']:.2f}x lambdify's "
                         f"time at {big:.0e} points.")
    big7 = res.get("issue_size")
    if big7:
        l7 = big7["sympy.lambdify"]
        for b in dict.fromkeys([DEFAULT, "numpy"]):
            if label(b) in big7:
                s7 = big7[label(b)]
                lines.append(f"- The same law at 10^7 points, as the issue measured it (3 rounds, round robin, load "
                             f"{big7['load']:.1f}), {label(b)}: {s7 / l7:.2f}x lambdify's time ({fmt_time(s7)} against "
                             f"{fmt_time(l7)}; {l7 / s7:.2f}x its speed).")
    s1 = [r for r in res["speed"] if r["n"] == 1 and r["method"] in (label(DEFAULT), "sympy.lambdify")]
    if s1:
        per = {(r["law"], r["method"]): r["median_s"] for r in s1}
        text = "; ".join(f"{law}: {fmt_time(per[(law, label(DEFAULT))])} (lambdify {fmt_time(per[(law, 'sympy.lambdify')])})"
                         for law in dict.fromkeys(r["law"] for r in s1))
        lines.append(f"- Scalar calls: before, {BEFORE['scalar call']}; this run, {text}.")
    lines += [
        "",
        "The NumPy path of this tree against commit 513222f (before issue 18's work), in alternating processes",
        "and CPU time, is a separate run of `benchmarks/default_path.py`: [numerics-default-path.md](numerics-default-path.md).",
        "",
    ]
    return "\n".join(lines) + "\n" + STATIC


def njit_section(res: dict) -> list[str]:
    """Small calls against a plain @njit function and loop (issue 34, item 4a)."""
    nj = res.get("njit")
    if not nj:
        return []
    rows = nj["rows"]
    lines = [
        "", "## Small calls against a plain `@numba.njit` loop (load "
        f"{nj['load'][0]:.1f} -> {nj['load'][1]:.1f})", "",
        "`benchmarks/small_calls.py` (`numba_rows`), in this process: each law as a plain `@njit` function (the law",
        "as `sympy.pycode` prints it, nothing else: no stable forms, no checks) called with Python numbers, and a",
        "plain `@njit` loop over 100 points allocating its output, against `symkin.compile(law, backend=\"numba\")` and",
        "the default `symkin.compile(law)` once it has compiled its kernel (`jit=\"auto\"`, driven there by calls of",
        "1000 points). Medians of 5 rounds (methods in turn), microseconds; ratio: over the plain `@njit` time.",
        "A scalar call of either symkin function is the Python-float code (the numba kernel is not called for one",
        "point): its type test of each argument, its finiteness test and its NumPy float64 result are the",
        "guarantees a bare `@njit` call does not give.",
        "",
        "| law | points | plain @njit | symkin numba | ratio | symkin default (after the switch) | ratio |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for key, plain in rows.items():
        law, *rest = key.split("|")
        if rest[-1] != "plain @njit":
            continue
        e, a = rows[f"{law}|{rest[0]}|symkin numba"], rows[f"{law}|{rest[0]}|symkin default (auto)"]
        lines.append(f"| {law} | {rest[0]} | {plain:.2f} | {e:.2f} | {e / plain:.2f} | {a:.2f} | {a / plain:.2f} |")
    switch = ", ".join(f"{k.split('|')[0]} {v:.1f} s" for k, v in rows.items() if k.endswith("|switch"))
    lines += ["", f"The default compiled its kernel after this much NumPy time (CPU): {switch}."]
    return lines


def choice_section(res: dict) -> list[str]:
    """Speed or accuracy: what each choice gives on this run's figures (issue 34, item 4b)."""
    cell = {(r["law"], r["method"], r["n"]): r["median_s"] for r in res["speed"]}
    diff = "differential omega_H (II, radii)"
    sizes = [n for n in (10**3, 10**5) if (diff, "sympy.lambdify", n) in cell]
    if not sizes or (diff, UNSTABLE, sizes[0]) not in cell:
        return []

    def ratios(method: str) -> str:
        return ", ".join(f"{cell[(diff, method, n)] / cell[(diff, 'sympy.lambdify', n)]:.2f}x at {n:.0e} points"
                         for n in sizes if (diff, method, n) in cell)

    worst = {}
    for r in res.get("random", []):
        worst[r["method"]] = max(worst.get(r["method"], 0.0), r["max"])
    acc = lambda m: f"{worst[m]:.1e}" if m in worst else "-"  # noqa: E731
    lines = [
        "", "## Speed or accuracy: what to choose", "",
        "On this run's figures for the II differential (its numerator `w1 r1 r3 - w4 r2 r4` cancels at about",
        "half the benchmark points), time as a ratio to `sympy.lambdify`, and the largest relative error on the",
        "random points above (every law and input set of that table):",
        "",
        f"- `symkin.compile(law)` (the default), or `backend=\"numba\"`: {ratios(label('numba'))}; error "
        f"{acc(label('numba'))}. The error-free sum is inlined in one compiled loop; the default starts with the",
        "  NumPy code and compiles once that pays (first use above).",
        f"- `backend=\"numpy\"` (stable forms): {ratios(label('numpy'))}; error {acc(label('numpy'))}. Where",
        "  the plain sum is not certified within 8 units the error-free sum (TwoProduct and Sum2) costs about 58",
        "  NumPy operations for the II law's two terms against lambdify's 10, and below about 10^4 points each",
        "  operation's call costs more than its work: that is the floor, not overhead (benchmarks/notes/numpy_floor.md).",
        "  A cheaper certificate would certify fewer points or give up the 8-unit bound.",
        f"- `backend=\"numpy\", stable=False`: {ratios(UNSTABLE)}; error {acc(UNSTABLE)} (lambdify's: "
        f"{acc('sympy.lambdify')}, with cse {acc('lambdify(cse=True)')}). The law as written, with symkin's input and pole checks but none of the stable",
        "  forms: no certified difference of products near a pole, no phase reduction for long times, no",
        "  error-free sums. Choose it for NumPy speed on small arrays when a few lost digits do not matter.",
        "",
        "Laws whose sums do not cancel (the AA ratio in teeth, the planet and the slider) pay no error-free sum;",
        "there the NumPy backend's cost over lambdify is its checks (the tables above).",
    ]
    return lines


STATIC = """## What the float backends guarantee (tested, not measured here)

`symkin.compile(laws, args, backend=..., precision=..., digits=...)` is the one entry point; backends
`numpy` (float64/float32), `numba` (fused loop, threads; optional extra), `mpmath` (n digits), `exact`
(rationals). Without `backend` it takes `symkin.numeric.default_backend()`: numba where it is installed,
else numpy (`SYMKIN_BACKEND=numpy` or `numba` chooses). Float backends evaluate stable forms
(`symkin.numeric.stable`; `f.stable_exprs` shows them).

- First use: with no backend named (neither `backend=` nor `SYMKIN_BACKEND`) a function is numba's in
  `jit="auto"`: it runs the NumPy code, timing it, and compiles the kernel (serial for calls below 2^15
  points, parallel above) only once that time reaches five times the kernel's estimated compile time
  (`symkin.numeric.backends.numba.compile_pays`; estimate 0.5 s + 0.05 s per operation, ten times that for
  the parallel kernel, on the high side of what the benchmark laws took with an empty cache: 0.3-3 s and
  1.3-27 s). Whatever follows, first use costs at most a fifth more than the NumPy path; a long run of work
  reaches the kernel's speed. Numba is not even imported before (0.2-0.3 s). A named numba backend
  (`jit="eager"`) compiles at its first call, as before. `symkin animate` and the other drawings evaluate
  with NumPy.
- Accuracy at every point: sums of products that can cancel in a rational law of real inputs (the II
  differential's numerator `w1 r1 r3 - w4 r2 r4`; a numerator given as products of sums is expanded) are
  summed error-free (each product split exactly by TwoProduct, the terms by Sum2) and rounded once
  (`CompensatedSum`): within one unit of their exact value in the
  numba kernel, within 8 units in the NumPy code (the plain sum where its error bound certifies that, the
  error-free sum at the other points, or at every point of a call of up to 4096 points), so the law is within a few units in the last place of exact
  rational arithmetic on the same inputs at every point (the table above), never less accurate than
  lambdify there. Sums of more than 8 terms or of terms of more than 4 factors, and laws with functions
  (sin, sqrt), are evaluated as written. float32 evaluates such a sum in float64 and rounds it.

- Complex, boolean, text and None inputs are refused (InputError); tooth numbers must be whole.
- No nan or inf output is silent: where an input is nan or infinite a `NonFiniteInputWarning` counts the
  points; anywhere else a `PoleWarning` does (`on_pole="raise"`: `PoleError`).
- Denominators evaluated exactly or to full relative accuracy: integer polynomials of tooth numbers (exact
  integer arithmetic), differences of two inputs, differences of two products of inputs `a b - c d`
  (double-double where they cancel: within 3 units of 2^-53 while the inputs are below 2^995 and the products
  above 2^-969 in magnitude), sums of terms of one known sign, and products of these. Where every
  denominator is of these kinds the float backends return inf or nan with a PoleWarning at a pole, never a
  finite number (tests/numeric/test_stable.py).
- Other denominators are evaluated in float64 as written and can lose digits near their poles; check such
  laws against `backend="mpmath"`.
- Phases of the arguments named `t` are reduced modulo 2 pi by default (`reduce_phase=()` turns it off):
  `c t` with `c` a rational constant times inputs in double-double; `c t` with `c` any rational function of
  inputs (the planet's omega_1 r1 r3/(r1 r3 + r2 r4)) with exact coefficients, rationals or exact constants
  such as the 2018 drive's 4 pi/5 rad/s or sqrt(2) (held in double-double to 2^-106), or such a constant
  alone (`sin(4 pi t/5)`), plainly where |c t| <= 8 rad and, beyond, with `c` evaluated in double-double
  from the inputs and the product reduced, so the rounding of `c` is not multiplied by t
  (tests/numeric/test_stable_long_phase.py: a property test over random exact speeds against mpmath at 50
  digits). A Float coefficient (`0.8*pi` typed as a float) is not exact and is not reduced. Exact while the phase is below 2^27 turns. When `c`'s
  inputs are numbers (an array of times), `c` is computed once and, if any phase of the call is long, every
  phase of the call is reduced, branch-free (tests/numeric/backends/test_numpy.py).
- Where the products of `a b - c d` may cancel is decided per call from `g = a b/(a b - c d)`: its minimum
  and maximum in [-0.499, 1.499] certify every point (the plain difference is within 3 units there); only
  uncertified points are redone in double-double. A law that multiplies by `a b` and divides by the
  difference (the Willis forms, `r1 r3/(r1 r3 - r2 r4)`) takes `g` itself: no second product, no division.
- Tooth-number arrays are bounded by one bitwise-or reduction each (all >= 0: the or bounds the maximum); only
  where that bound could overflow int64 are |z| and its maximum taken, and beyond it Python integers are used.
  The numba kernels evaluate the integer parts in float64 where a bound of every partial sum is below 2^53
  (exact there, a loop that vectorises) and redo the other points with integers
  (tests/numeric/test_numeric.py).
- The numba backend (`backend="numba"`) runs one compiled loop per law over blocks of 1024 points, every
  argument read as a contiguous slice (a scalar as a block of copies of it), so that LLVM vectorises the
  inner loop; there `a b - c d` is taken plainly, the certification test of each point counting the
  uncertified ones, which a second kernel, compiled on the first call that needs it, redoes in double-double
  (tests/numeric/test_stable.py). Where a long phase's coefficient depends on scalar arguments only (a
  sweep of t), it is computed once per block in double-double and every phase of the block reduced, a loop
  without branches; elsewhere it is computed at the first point of a block that needs it and kept while its
  inputs repeat (tests/numeric/test_stable_long_phase.py). sin and cos are libm's scalar functions (as fast here as
  NumPy's), so laws in time gain least (the planet law above). Rational laws gain most. A scalar argument's
  block of copies is kept for the next call with the same value. Compiling a kernel takes 0.3-3 s of CPU
  on this machine (the parallel one 1.3-27 s) with an empty cache; it is kept on disk (`$SYMKIN_CACHE_DIR`,
  else `kernels` in the user's cache folder, `platformdirs.user_cache_dir("symkin")`: `~/.cache/symkin/kernels`
  on Linux), and another process loads it after importing numba (0.2-0.3 s; the first-use table above).
  Numba's cache files are pickles, which run code when loaded, so the folder is made private (0700) and a
  folder another user owns or others can write is not used: a warning says so and kernels are compiled in
  memory. An entry that fails to load (truncated, damaged) is removed and compiled again.
- Speed, what lambdify keeps ahead on: one point, and small NumPy calls. A call of one point pays what a
  bare lambdify expression does not (the type test of each argument, the finiteness test of each output,
  a NumPy float64 result): about a microsecond with either backend, one generated function of Python
  floats (the tables above). The numba backend's call of flat contiguous arrays of one length below 2^15
  points (float64, int64 for tooth numbers) goes straight to its compiled loop once that has run: one
  generated function testing each array's type, dtype, layout and length (the small-call table above);
  any other call takes the general path. On the NumPy backend a call of up to about 10^4 points
  also pays one `np.errstate`, the finiteness sum of each output, the tooth-number bound and the
  cancellation test: 15-30 us at 10^3 points (the table above); the numba kernel does these tests in its
  loop. Loops over many small calls are faster with one call on an array.
- Memory: before its first call of more than 8192 points, the NumPy path allocates and frees one 16 MiB
  block (never written), once per process. glibc's malloc then keeps freed temporaries instead of
  unmapping them after each operation, as it does in any process that has freed a 16 MiB array; without
  it, in a fresh process, repeated calls of 10^5 points took 1.5-2.5x as long and the II differential at
  10^7 points 1.6x (benchmarks/notes/numeric-backends.md, `python benchmarks/allocator_priming.py`).
  Up to 32 MiB of freed memory may stay with the process; other allocators ignore it.
- float32: inputs that are float32 keep the guarantees above in float32; inputs given in float64 are rounded
  to float32, and where that moves a result by more than 2^-16 of the call's largest value (near a pole) a
  `PrecisionWarning` says so (checked by one float64 evaluation, paid only for such inputs).
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="1, 100 and 10^3 points only, 3 rounds; docs not written")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--no-docs", action="store_true")
    ap.add_argument("--docs-from", type=Path, metavar="JSON",
                    help="write docs/numerics.md from the results of an earlier run (its results.json), measuring nothing")
    ap.add_argument("--first-use-rounds", type=int, default=2, help="rounds of benchmarks/first_use.py (0: none)")
    opts = ap.parse_args()
    if opts.docs_from:
        (ROOT / "docs" / "numerics.md").write_text(markdown(json.loads(opts.docs_from.read_text())))
        return
    sizes = (1, 100, 10**3) if opts.quick else SIZES
    rounds = 3 if opts.quick else opts.rounds
    t0 = time.perf_counter()
    load0 = os.getloadavg()[0]
    all_cases = cases(max(sizes))
    res: dict = dict(
        machine=f"{os.cpu_count()} cores, Python {platform.python_version()}, numpy {np.__version__}, sympy {sp.__version__}"
        + (f", numba {__import__('numba').__version__}" if HAS_NUMBA else ", numba not installed")
        + ("" if HAS_NUMEXPR else ", numexpr not installed"),
    )
    res["speed"] = speed(all_cases, sizes, rounds)
    res["accuracy"] = accuracy(all_cases)
    res["hard"] = hard_regions()
    res["fixed"] = fixed_costs(all_cases)
    res["random"] = random_points(10**4 if opts.quick else 10**5)
    if HAS_NUMBA:
        import small_calls

        res["njit"] = dict(load=[os.getloadavg()[0]], rows=small_calls.numba_rows(5))
        res["njit"]["load"].append(os.getloadavg()[0])
    if not opts.quick:
        res["issue_size"] = issue_size()
        if opts.first_use_rounds:
            res["first_use"] = first_use(opts.first_use_rounds)
    res["load"] = [load0, os.getloadavg()[0]]
    res["seconds"] = time.perf_counter() - t0
    for r in res["accuracy"]:
        print(f"{r['law']:45s} {r['method']:25s} {r['error']:.2e}")
    for r in res["hard"]:
        print(f"{r['region'][:60]:60s} {r['method']:36s} {r['error']:.2e} {r['warned'] or ''}")
    print(f"load {res['load'][0]:.1f} -> {res['load'][1]:.1f}; {res['seconds']:.0f} s")
    if opts.quick or opts.no_docs:
        return
    (HERE / "results.json").write_text(json.dumps(res, indent=1))
    (ROOT / "docs" / "numerics.md").write_text(markdown(res))
    print(f"wrote {ROOT / 'docs' / 'numerics.md'} and {HERE / 'results.json'}")


if __name__ == "__main__":
    main()
