"""Luo, Li, Feng & Hua (2018), Cardan-circle mechanism driven through elliptical gears, reproduced.

The mechanism is built with symkin (:func:`symkin.schemes.cardan`, :class:`symkin.mechanisms.cardan.CardanSlider`):
the planet's turn relative to the carrier comes from the engine's contact condition,
the slider's law from the vector loop (eqs. 17-20, :mod:`symkin.vectorloop`), the
conditions for straight-line motion from the loop's harmonics, and the elliptical drive
from the gears' pitch curves (:class:`symkin.drives.EllipticalGears`).  The published
forms below are transcribed from the paper (OCR in shared/papers); where the OCR lost a
formula, the form the paper's text implies is used and marked "reconstructed".  They
are what is compared against, never used to derive.
"""

from __future__ import annotations

import functools
import itertools
from pathlib import Path

import numpy as np
import sympy as sp
from sympy.calculus.util import maximum, minimum

from symkin import symbols as S
from symkin.drives import AngleLaw, ConstantSpeed, EllipticalGears
from symkin.mechanisms import cardan
from symkin.mechanisms.cardan import (
    CardanSlider,
    l,
    l_1,
    l_H,
    s,
    theta_1,
    theta_2,
    theta_H,
    theta_H0,
)
from symkin.papers.checks import (
    Check,
    Comparison,
    Verdict,
    compare_exact,
    compare_rounded,
    compare_symbolic,
    slip,
)

KEY = "luo2018"
CITATION = (
    "Luo Jingbo, Li Meiqiu, Feng Xiaogang, Hua Jian, Kinematic analysis and simulation of noncircular gear - "
    "Cardan circle planetary mechanism, Food & Machinery, 2018 (DOI 10.13652/j.issn.1003-5788.2018.01.016)"
)

t = S.t
omega_H = S.omega("H")
omega, e, m = sp.Symbol("omega", positive=True), sp.Symbol("e", nonnegative=True), sp.Symbol("m", positive=True)
z1, z3 = S.teeth("1"), S.teeth("3")
Theta = sp.Function("theta_H", real=True)  # an arbitrary carrier law theta_H(t)

# ---- published forms (the paper's equations, for comparison only)
PUBLISHED_SPIN = -omega_H * z3 / z1  # (2), reconstructed: planet 1 turns against the carrier (text: clockwise)
PUBLISHED_TEETH = (1, 2)  # z1 : z3 = 1 : 2, after (14)
PUBLISHED_14 = sp.Eq(l_1, l_H)
PUBLISHED_13_TEXT = "theta_1(0) = -(k + 1) pi, theta_2 free"  # (13) z = pi + k pi, "theta_H, theta_2 as needed"
PUBLISHED_16 = 2 * (theta_2 - theta_H)
PUBLISHED_19 = sp.Eq(l_H * sp.cos(theta_H) + l_1 * sp.cos(theta_H + theta_1), s * sp.cos(theta_2))
PUBLISHED_20 = sp.Eq(l_H * sp.sin(theta_H) + l_1 * sp.sin(theta_H + theta_1), s * sp.sin(theta_2))
PUBLISHED_21 = 2 * l**2 * (1 + sp.cos(theta_1))  # s^2, with l = l_1 = l_H
PUBLISHED_22 = 2 * l * sp.cos(theta_2 - theta_H)
PUBLISHED_23 = 2 * l * omega_H * sp.sin(theta_2 - omega_H * t)
PUBLISHED_24 = -2 * l * omega_H**2 * sp.cos(theta_2 - omega_H * t)

# Section 2 and Table 1: l1 = lH = 20 mm, z1 = 20, z3 = 40, omega_H = 0.8 pi rad/s, theta_1(0) = 0, theta_2 = 0.
TABLE1_LENGTH = sp.Rational(20, 1000)  # m
TABLE1_OMEGA = sp.Rational(8, 10) * sp.pi  # rad/s
TABLE1_TEETH = (20, 40)
TABLE1 = {  # quantity -> (initial, max, min) as printed (theory row; the simulation row is the same but v(0))
    "s": ("0.04", "0.04", "-0.04"),
    "v": ("0", "100.52e-3", "-100.52e-3"),
    "a": ("-252.66e-3", "252.66e-3", "-252.66e-3"),
}
TABLE1_SIMULATED_V0 = "-3.39e-16"
PUBLISHED_STROKE = "0.080"  # 80 mm
PUBLISHED_PERIOD = 2 * sp.pi  # "T = 2 pi s"

# Section 3 (the OCR lost eqs. 25-35; the forms below are those of the shared guide, reconstructed from the text)
alpha_in = sp.Symbol("alpha", real=True)
PUBLISHED_25 = (1 - 2 * e * sp.cos(m * alpha_in) + e**2) / (1 - e**2)
PUBLISHED_26 = omega * (1 - e**2) / (1 - 2 * e * sp.cos(m * omega * t) + e**2)
PUBLISHED_27 = theta_H0 + 2 / m * sp.atan((1 + e) / (1 - e) * sp.tan(m * omega * t / 2))
# (29)-(35): (22) with theta_H(t), differentiated; written with theta_H(t), omega_H(t), eps_H(t)
PUBLISHED_29 = 2 * l * sp.cos(theta_2 - Theta(t))
PUBLISHED_30 = 2 * l * Theta(t).diff(t) * sp.sin(theta_2 - Theta(t))
PUBLISHED_32 = 2 * l * (Theta(t).diff(t, 2) * sp.sin(theta_2 - Theta(t)) - Theta(t).diff(t) ** 2 * sp.cos(theta_2 - Theta(t)))
PUBLISHED_EPS = -2 * e * m * omega**2 * (1 - e**2) * sp.sin(m * omega * t) / (1 - 2 * e * sp.cos(m * omega * t) + e**2) ** 2

# Figures 7-8: what the text says each panel shows (section 3.2, items 1-3)
FIGURE_CLAIMS = {
    "a": "e larger: higher velocity peak, peak time moves, larger share of the period in a steady (flat) stretch; "
    "larger acceleration extremes; quick return",
    "b": "m smaller (within a range): longer slider period, longer low-speed plateau, smaller slope between the "
    "velocity extremes; more acceleration fluctuations",
    "c": "initial carrier angle larger (within a range): larger share of steady same-direction motion; forward and "
    "reverse acceleration extremes tend to the same size",
}
SHORT_CLAIMS = {
    "a": "e up: higher peaks, longer plateau, quick return",
    "b": "m down: longer period, longer plateau",
    "c": "theta_H(0) up: longer plateau, equal a extremes",
}
# The curves drawn here (the paper's parameter values are not in the text): Table 1's mechanism, baseline e, m, theta_H0.
BASE_E, BASE_M, BASE_THETA0 = sp.Rational(2, 5), 1, sp.pi / 6
SWEEPS = {
    "a": ("e", [sp.Integer(0), sp.Rational(1, 5), sp.Rational(2, 5), sp.Rational(3, 5)]),
    "b": ("m", [3, 2, 1]),
    "c": ("theta_H0", [sp.Integer(0), sp.pi / 6, sp.pi / 3, sp.pi / 2]),
}


def _check(label, description, derived, published, comparison, **extra) -> Check:
    return Check.make(KEY, label, description, derived, published, comparison, **extra)


def _symbolic_slider(**kw) -> CardanSlider:
    """Carrier length l, ratio 1:2, pin on the pitch circle, installed as derived."""
    kw.setdefault("guide_angle", theta_2)
    kw.setdefault("carrier_angle", theta_H0)
    return CardanSlider.build(l, **kw)


def table1_slider() -> CardanSlider:
    """Section 2: l = 20 mm, z = 20/40, omega_H = 0.8 pi, theta_1(0) = 0, theta_2 = 0."""
    return CardanSlider.build(TABLE1_LENGTH, drive=TABLE1_OMEGA, teeth=TABLE1_TEETH, pin_angle=0, guide_angle=0)


def elliptical_slider(ecc, order, theta0) -> CardanSlider:
    """Table 1's mechanism driven through elliptical gears (input speed 0.8 pi rad/s)."""
    return CardanSlider.build(
        TABLE1_LENGTH, drive=EllipticalGears(TABLE1_OMEGA, ecc, order), teeth=TABLE1_TEETH, guide_angle=0, carrier_angle=theta0
    )


# --------------------------------------------------------------------------- checks
def checks() -> list[Check]:
    """Every equation, Table 1 and the claims of figures 7-8, derived and compared."""
    return _structure() + _continuity() + _laws() + _table1() + _elliptical() + _figure_claims()


def _structure() -> list[Check]:
    out = []
    mech = cardan.CardanSlider.build(l, teeth=(z1, z3)).mechanism
    speeds = mech.speeds({"H": omega_H})
    spin = sp.simplify(speeds["1"] - omega_H)
    out.append(_check("(2)", "planet 1 turns relative to the carrier (contact with the fixed ring 3)", spin, PUBLISHED_SPIN,
                      compare_symbolic(spin, PUBLISHED_SPIN)))
    paper = table1_slider()
    absolute = paper.mechanism.speeds({"H": omega_H})["1"]
    out.append(_check("(2) z = 20/40", "the text: planet 1 spins clockwise at the carrier's rate", absolute, -omega_H,
                      compare_symbolic(absolute, -omega_H)))
    x_eq, y_eq = cardan.loop().components()
    for label, derived, published in (("(19)", x_eq, PUBLISHED_19), ("(20)", y_eq, PUBLISHED_20)):
        out.append(_check(label, "real / imaginary part of the loop (18)", derived, published,
                          compare_symbolic(derived.lhs - derived.rhs, published.lhs - published.rhs)))
    return out


def _continuity() -> list[Check]:
    out = []
    c = cardan.line_conditions()
    ratio = sp.cancel(c.ratio.rhs / S.radius("1"))
    out.append(_check("(13)-(14) ratio", "ring : planet for which the pin's harmonic can cancel the carrier's",
                      f"z1 : z3 = 1 : {ratio}", "z1 : z3 = 1 : 2", compare_exact(ratio, sp.Rational(*PUBLISHED_TEETH[::-1])),
                      excluded="; ".join(f"{eq}: {why}" for eq, why in c.excluded)))
    out.append(_check("(14)", "pin radius equals carrier length", c.lengths, PUBLISHED_14,
                      compare_symbolic(c.lengths.rhs, PUBLISHED_14.rhs)))
    zero = sp.simplify(c.deviation.subs(c.substitutions()))
    out.append(_check("(12) identity", "deviation from the guide under the derived conditions, for every carrier angle",
                      zero, 0, compare_exact(zero, 0)))
    # (13): the installation angle.  Derived: theta_1(0) = 2 (theta_2 - theta_H(0)) mod 2 pi.
    off = _symbolic_slider(guide_angle=0, carrier_angle=0, pin_angle=sp.pi)  # allowed by (13) with k = 0
    deviation = sp.simplify(off.deviation)
    tilted = _symbolic_slider(guide_angle=sp.pi / 6, carrier_angle=0)  # installed as derived
    tilted_dev = sp.simplify(tilted.deviation)
    evidence = (
        f"the derived condition is {c.installation.lhs} = {c.installation.rhs} (mod 2 pi), the paper's own (16) at t = 0; "
        f"(13) allows theta_1(0) = pi with theta_2 = theta_H(0) = 0, where the pin leaves the guide by {deviation} "
        f"({off.path().kind}, direction {off.path().parameters['direction']}); and with theta_2 = pi/6, theta_H(0) = 0 "
        f"the pin stays on the guide (deviation {tilted_dev}) at theta_1(0) = {tilted.pin_angle}, not a multiple of pi. "
        "So (13) is neither sufficient nor necessary; it agrees with the derived rule only when theta_2 - theta_H(0) "
        "is a multiple of pi/2, as in Table 1"
    )
    out.append(_check("(13)", "installation angle for motion along the guide", c.installation, PUBLISHED_13_TEXT, slip(evidence)))
    return out


def _laws() -> list[Check]:
    out = []
    # (21): the loop solved for the slider vector's length and angle (same vector), squared
    solution = cardan.loop().solve(s, theta_2)[0]
    s2 = sp.factor(sp.trigsimp(sp.expand(solution[s] ** 2).subs({l_1: l, l_H: l})))
    out.append(_check("(21)", "s^2 from the loop (unknowns s, theta_2), l = l_1 = l_H", s2, PUBLISHED_21,
                      compare_symbolic(s2, PUBLISHED_21)))
    uniform = _symbolic_slider(drive=omega_H)
    theta_now = theta_H0 + omega_H * t
    out.append(_check("(16)", "pin angle on the planet during the motion", uniform.planet_angle, PUBLISHED_16.subs(theta_H, theta_now),
                      compare_symbolic(uniform.planet_angle, PUBLISHED_16.subs(theta_H, theta_now))))
    out.append(_check("(22)", "slider displacement (vector loop along the guide)", uniform.displacement,
                      PUBLISHED_22.subs(theta_H, theta_now), compare_symbolic(uniform.displacement, PUBLISHED_22.subs(theta_H, theta_now))))
    start = _symbolic_slider(drive=omega_H, carrier_angle=0)
    for label, derived, published in (("(23)", start.velocity, PUBLISHED_23), ("(24)", start.acceleration, PUBLISHED_24)):
        out.append(_check(label, f"slider {'velocity' if label == '(23)' else 'acceleration'}, theta_H(0) = 0",
                          derived, published, compare_symbolic(derived, published)))
    # the second route: the pin as a planet particle (superposition), projected on the guide
    along = uniform.pin.position[0] * sp.cos(theta_2) + uniform.pin.position[1] * sp.sin(theta_2)
    out.append(_check("(22) superposition", "slider displacement: pin as a planet particle, eqs. (4)-(6) of the 2009 paper",
                      along, PUBLISHED_22.subs(theta_H, theta_now), compare_symbolic(along, PUBLISHED_22.subs(theta_H, theta_now))))
    return out


def _table1() -> list[Check]:
    out = []
    slider = table1_slider()
    T = slider.period()
    span = sp.Interval(0, T)
    laws = {"s": slider.displacement, "v": slider.velocity, "a": slider.acceleration}
    derived = {k: (f.subs(t, 0), maximum(f, t, span), minimum(f, t, span)) for k, f in laws.items()}
    grids, grid_evidence = _sampling_evidence(slider, T, derived["v"][1])
    for q, names in (("s", "displacement"), ("v", "velocity"), ("a", "acceleration")):
        for which, value, printed in zip(("initial", "max", "min"), derived[q], TABLE1[q]):
            label = f"Table 1 {q} {which}"
            comparison = _rounded_e(value, printed) if "e" in printed else compare_rounded(value, printed)
            if not comparison.verdict.ok and q == "v" and which != "initial" and grids:
                # a slip only when sampling the derived law on some time grid gives exactly the printed pair
                comparison = slip(grid_evidence)
            out.append(_check(label, f"{names} {which} (l = 20 mm, omega_H = 0.8 pi rad/s)", value, printed, comparison))
    stroke = derived["s"][1] - derived["s"][2]
    out.append(_check("stroke", "slider stroke (80 mm)", stroke, PUBLISHED_STROKE, compare_exact(stroke, sp.Rational(PUBLISHED_STROKE))))
    out.append(
        _check(
            "period",
            "period of the slider motion",
            T,
            "2*pi s",
            slip(
                f"the text says T = 2 pi s; with omega_H = 0.8 pi rad/s one carrier turn takes 2 pi/omega_H = {T} s "
                f"(the table's extremes agree: v is extreme at t = {sp.Rational(5, 8)} and {sp.Rational(15, 8)} s, a quarter "
                "and three quarters of 2.5 s); 2 pi is the period in carrier angle (rad), or in time only for omega_H = 1 rad/s"
            ),
        )
    )
    return out


def _rounded_e(value, printed: str) -> Comparison:
    mantissa, exponent = printed.split("e")
    scaled = sp.sympify(value) * sp.Integer(10) ** (-int(exponent))
    c = compare_rounded(scaled, mantissa)
    return Comparison(c.verdict, c.detail + f" (x 1e{exponent})")


def _sampling_evidence(slider: CardanSlider, period, extreme) -> tuple[list[str], str]:
    """Time steps on which the sampled extremes of the derived v print as Table 1's pair.

    Returns the steps that reproduce the printed (max, min) and the evidence text.
    """
    f = sp.lambdify(t, slider.velocity, "numpy")
    printed_pair = tuple(float(x) * 1e3 for x in TABLE1["v"][1:])  # in 1e-3 m/s, as printed
    hits, misses = [], []
    for step in ("0.001", "0.005", "0.01", "0.02", "0.04", "0.05"):
        ts = np.arange(0, float(period) + 1e-12, float(step))
        v = f(ts)
        sampled = (round(v.max() * 1e5) / 100, round(v.min() * 1e5) / 100)
        (hits if sampled == printed_pair else misses).append(f"{step} s: {sampled[0]:.2f}/{sampled[1]:.2f}")
    exact = float(extreme)
    peak_times = [float(x) for x in sp.solve(sp.diff(slider.velocity, t), t) if 0 < float(x) < float(period)]
    text = (
        f"the derived extreme speed is {extreme} = {exact:.8f} m/s, which rounds to {exact * 1e3:.2f}e-3 (truncation "
        f"gives {int(exact * 1e5) / 100:.2f}e-3 too), not the printed {TABLE1['v'][1]}. The printed pair is the extreme "
        f"of v sampled on a time grid: the peaks of v (t = {', '.join(f'{x:g}' for x in peak_times)} s) fall between "
        f"the samples. Sampled extremes (x 1e-3) by step: the table is reproduced for "
        f"{', '.join(hits) or 'no step'}; not for {', '.join(misses) or 'no step'}. The acceleration extremes sit on "
        "such grids (t = 0 and half a period) and match"
    )
    return hits, text


def _elliptical() -> list[Check]:
    out = []
    gears = EllipticalGears(omega, e, m)
    ratio = gears.ratio(alpha_in)
    out.append(_check("(25)", "transmission ratio of identical elliptical gears (from the pitch curves)", ratio, PUBLISHED_25,
                      compare_symbolic(ratio, PUBLISHED_25)))
    speed = gears.speed(t)
    out.append(_check("(26)", "carrier speed through the elliptical gears", speed, PUBLISHED_26, compare_symbolic(speed, PUBLISHED_26)))
    angle = theta_H0 + gears.angle(t)
    out.append(_check("(27)-(28)", "carrier angle", angle, PUBLISHED_27, _branch_comparison(angle)))
    general = _symbolic_slider(drive=AngleLaw(Theta(t)), carrier_angle=Theta(0))
    for label, derived, published in (
        ("(29)", general.displacement, PUBLISHED_29),
        ("(30)-(31)", general.velocity, PUBLISHED_30),
        ("(32)", general.acceleration, PUBLISHED_32),
    ):
        out.append(_check(label, "slider law for a carrier law theta_H(t) (vector loop, differentiated)", derived, published,
                          compare_symbolic(derived, published)))
    eps = gears.acceleration(t)
    out.append(_check("(33)-(35)", "carrier angular acceleration through the elliptical gears", eps, PUBLISHED_EPS,
                      compare_symbolic(eps, PUBLISHED_EPS)))
    drive0 = EllipticalGears(omega, 0, m)
    ell, uni = _symbolic_slider(drive=drive0, carrier_angle=0), _symbolic_slider(drive=ConstantSpeed(omega), carrier_angle=0)
    for label, derived, published in (
        ("e = 0: (22)", ell.displacement, PUBLISHED_22.subs(theta_H, omega * t)),
        ("e = 0: (23)", ell.velocity, PUBLISHED_23.subs(omega_H, omega)),
        ("e = 0: (24)", ell.acceleration, PUBLISHED_24.subs(omega_H, omega)),
    ):
        out.append(_check(label, "circular gears (e = 0) give the constant-speed law", derived, published,
                          compare_symbolic(derived, published)))
    same = sp.simplify(ell.displacement - uni.displacement)
    out.append(_check("e = 0 drives", "elliptical drive at e = 0 vs constant speed: displacement difference", same, 0,
                      compare_exact(same, 0)))
    return out


def _branch_comparison(angle: sp.Expr) -> Comparison:
    """The published (principal-branch) carrier angle against the derived continuous one."""
    slope = sp.simplify(sp.diff(PUBLISHED_27 - angle, t))
    at_zero = sp.simplify((PUBLISHED_27 - angle).subs(t, 0))
    values = {omega: 1, e: sp.Rational(1, 2), m: 2, theta_H0: 0}
    f_pub = sp.lambdify(t, PUBLISHED_27.subs(values))
    f_der = sp.lambdify(t, angle.subs(values))
    branch = np.pi / 2  # m omega t = pi
    before, after = branch - 1e-9, branch + 1e-9
    gap = f_der(after) - f_pub(after)
    if slope != 0 or at_zero != 0:
        return Comparison(Verdict.DIFFERS, f"d/dt(published - derived) = {slope}, at t = 0: {at_zero}")
    return slip(
        "reconstructed (the OCR lost eqs. 27-28): the principal-branch arctan form has the same derivative as the "
        f"derived angle (d/dt of the difference = {slope}) and the same value at t = 0, so the two agree on "
        "|m omega t| < pi; at every t = (2j+1) pi/(m omega) the principal arctan jumps by -2 pi/m. For e = 1/2, m = 2, "
        f"omega = 1 at t = pi/2: published {f_pub(before):.6f} -> {f_pub(after):.6f}, derived {f_der(before):.6f} -> "
        f"{f_der(after):.6f} (gap {gap:.6f} = 2 pi/m = {2 * np.pi / 2:.6f}). The derived form "
        "omega t + (2/m) atan(e sin(m omega t)/(1 - e cos(m omega t))) is continuous for every t"
    )


# --------------------------------------------------------------------------- figures 7-8
def _curves():
    """For each panel a (e), b (m), c (theta_H0): (label value, slider, samples, stroke times, stats)."""
    out = {}
    for panel, (name, values) in SWEEPS.items():
        rows = []
        for value in values:
            ecc = value if name == "e" else BASE_E
            order = value if name == "m" else BASE_M
            theta0 = value if name == "theta_H0" else BASE_THETA0
            slider = elliptical_slider(ecc, order, theta0)
            T = float(slider.period())
            ts = np.linspace(0.0, T, 1201)
            data = slider.evaluate(ts)
            stroke = slider.stroke_times()
            rows.append((value, slider, data, stroke, _stats(data, T)))
        out[panel] = rows
    return out


def steady_share(v: np.ndarray, tolerance: float = 0.1) -> float:
    """The longest stretch of one period (samples over [0, T), periodic) in which v stays
    within ``tolerance`` of its full range, as a share of the period: the flat part of
    the velocity curve."""
    from collections import deque

    n = len(v)
    band = tolerance * float(v.max() - v.min())
    vv = np.concatenate([v, v])
    highs: deque[int] = deque()
    lows: deque[int] = deque()
    start, best = 0, 0
    for j in range(2 * n):
        while highs and vv[highs[-1]] <= vv[j]:
            highs.pop()
        highs.append(j)
        while lows and vv[lows[-1]] >= vv[j]:
            lows.pop()
        lows.append(j)
        while vv[highs[0]] - vv[lows[0]] > band or j - start >= n:
            start += 1
            if highs[0] < start:
                highs.popleft()
            if lows[0] < start:
                lows.popleft()
        best = max(best, j - start + 1)
    return best / n


def _stats(data, period: float) -> dict[str, float]:
    v, a = data["v"], data["a"]
    vmax, vmin = float(v.max()), float(v.min())
    steady = steady_share(v[:-1])  # the last sample repeats the first
    return {
        "period": period,
        "v_max": vmax,
        "v_min": vmin,
        "t_v_max": float(data["t"][np.argmax(v)]),
        "a_max": float(a.max()),
        "a_min": float(a.min()),
        "steady_share": steady,
    }


@functools.cache
def curves():
    """The sampled curves of figures 7-8 (computed once per process)."""
    return _curves()


def _ratios(rows, name: str) -> str:
    """Short form for the report table: the stroke-time ratio of each curve."""
    return f"K = {', '.join(f'{st.ratio:.2f}' for _, _, _, st, _ in rows)} for {name} = {', '.join(sp.sstr(v) for v, *_ in rows)}"


def _increasing(xs) -> bool:
    return all(b > a for a, b in itertools.pairwise(xs))


def _figure_claims() -> list[Check]:
    """What the text says figures 7-8 show, measured on the derived curves."""
    data = curves()
    a_rows, b_rows, c_rows = data["a"], data["b"], data["c"]

    def table(rows, name):
        return "; ".join(
            f"{name} = {sp.sstr(v)}: K = {st.ratio:.3f}, v {x['v_min'] * 1e3:.1f}..{x['v_max'] * 1e3:.1f} mm/s "
            f"(peak at {x['t_v_max']:.2f} s), a {x['a_min'] * 1e3:.0f}..{x['a_max'] * 1e3:.0f} mm/s^2, "
            f"steady share {x['steady_share']:.2f}"
            for v, _, _, st, x in rows
        )

    def column(rows, key):
        return [x[key] for *_, x in rows]

    def shown(flag):
        return "shown" if flag else "NOT shown"

    out = []
    peaks = [max(hi, -lo) for hi, lo in zip(column(a_rows, "v_max"), column(a_rows, "v_min"))]
    acc = [max(hi, -lo) for hi, lo in zip(column(a_rows, "a_max"), column(a_rows, "a_min"))]
    ratios = [st.ratio for _, _, _, st, _ in a_rows]
    steady = column(a_rows, "steady_share")
    claims = {
        "higher velocity peak": _increasing(peaks),
        "longer steady stretch": _increasing(steady),
        "larger acceleration extremes": _increasing(acc),
        "quick return (K grows from 1)": _increasing(ratios) and abs(ratios[0] - 1) < 1e-9,
    }
    detail = "; ".join(f"{k}: {shown(v)}" for k, v in claims.items()) + f". {table(a_rows, 'e')}"
    out.append(_check("fig. 7(a)/8(a)", "effect of the eccentricity e (m = 1, theta_H(0) = pi/6)", _ratios(a_rows, "e"),
                      SHORT_CLAIMS["a"], Comparison(Verdict.MATCH if all(claims.values()) else Verdict.DIFFERS, detail),
                      claim=FIGURE_CLAIMS["a"]))

    periods = column(b_rows, "period")
    evidence = (
        f"with the continuous carrier angle the motion repeats after one carrier turn for every whole order (periods "
        f"for m = 3, 2, 1: {', '.join(f'{p:.3f}' for p in periods)} s), so a smaller m does not lengthen the period, and "
        f"the steady share is not monotonic in m ({', '.join(f'{x:.2f}' for x in column(b_rows, 'steady_share'))}). "
        "The principal-branch angle (27) repeats every 2 pi/(m omega) = 2.5/m s and sweeps only 2 pi/m of carrier angle "
        "per repetition: curves drawn with it have the longer period for smaller m that the text describes, and jump "
        "at every branch point for m >= 2. Even orders give equal stroke times (K = 1). " + table(b_rows, "m")
    )
    out.append(_check("fig. 7(b)/8(b)", "effect of the order m (e = 2/5, theta_H(0) = pi/6)", _ratios(b_rows, "m"),
                      SHORT_CLAIMS["b"], slip(evidence), claim=FIGURE_CLAIMS["b"]))

    steady_c = column(c_rows, "steady_share")
    asym = [abs(hi + lo) / max(hi, -lo) for hi, lo in zip(column(c_rows, "a_max"), column(c_rows, "a_min"))]
    claims_c = {
        "longer steady stretch": _increasing(steady_c),
        "forward and reverse acceleration extremes approach each other": all(b < a for a, b in itertools.pairwise(asym)) and asym[-1] < 1e-9,
    }
    detail_c = (
        "; ".join(f"{k}: {shown(v)}" for k, v in claims_c.items())
        + f" (|a_max + a_min| / max|a|: {', '.join(f'{x:.3f}' for x in asym)}). {table(c_rows, 'theta_H(0)')}"
    )
    out.append(_check("fig. 7(c)/8(c)", "effect of the initial carrier angle (e = 2/5, m = 1)", _ratios(c_rows, "theta_H(0)"),
                      SHORT_CLAIMS["c"], Comparison(Verdict.MATCH if all(claims_c.values()) else Verdict.DIFFERS, detail_c),
                      claim=FIGURE_CLAIMS["c"]))
    return out


# --------------------------------------------------------------------------- figures
def figures(folder: Path) -> list[Path]:
    """Pin paths; Table 1's curves (fig. 4); figures 7 and 8; the carrier angle across a branch point."""
    return _paths_figure(folder) + _table1_figure(folder) + _sweep_figures(folder) + _branch_figure(folder)


def _paths_figure(folder: Path) -> list[Path]:
    from matplotlib.figure import Figure

    from symkin.viz import figures

    cases = [
        ("z = 20/40, pin on the pitch circle", dict(teeth=(20, 40))),
        ("z = 20/40, pin at 0.5 l_H", dict(teeth=(20, 40), pin_radius=sp.Rational(1, 2))),
        ("z = 20/40, pin on the pitch circle, theta_1(0) = pi", dict(teeth=(20, 40), pin_angle=sp.pi)),
        ("z = 20/60, pin on the pitch circle", dict(teeth=(20, 60))),
    ]
    fig = Figure(figsize=(9, 9))
    for n, (title, kw) in enumerate(cases, 1):
        slider = CardanSlider.build(1, drive=1, **kw)
        ax = fig.add_subplot(2, 2, n)
        figures.draw_pitch_circles(ax, slider.mechanism)
        _, x, y = slider.pin.trajectory(float(2 * sp.pi), samples=721)
        ax.plot(x, y, lw=1.3, label="pin O (superposition)")
        ax.plot(x[:1], y[:1], "o", ms=3)
        ax.axline((0, 0), (1, 0), lw=0.6, ls=":", color="k", label="guide, theta_2 = 0")
        ax.set_aspect("equal")
        ax.set_title(f"{title}\nderived path: {slider.path().kind}", fontsize=9)
        ax.legend(fontsize=7, loc="lower left")
        ax.tick_params(labelsize=7)
    fig.suptitle("Luo et al. 2018: what the pin traces (l_H = 1, one carrier turn)")
    return figures.save(fig, folder / "luo2018_paths")


def _table1_figure(folder: Path) -> list[Path]:
    from matplotlib.figure import Figure

    from symkin.viz import figures

    slider = table1_slider()
    ts = np.linspace(0, float(slider.period()), 501)
    d = slider.evaluate(ts)
    fig = Figure(figsize=(7, 6))
    for n, (key, unit, _name) in enumerate((("s", "mm", "displacement"), ("v", "mm/s", "velocity"), ("a", "mm/s$^2$", "acceleration")), 1):
        ax = fig.add_subplot(3, 1, n)
        ax.plot(ts, d[key] * 1e3, lw=1.2)
        ax.set_ylabel(f"{key} [{unit}]", fontsize=8)
        ax.grid(lw=0.3)
        ax.tick_params(labelsize=7)
    ax.set_xlabel("t [s]", fontsize=8)
    fig.suptitle("Luo et al. 2018, fig. 4 / Table 1: l = 20 mm, omega_H = 0.8 pi rad/s (period 2.5 s)", fontsize=10)
    return figures.save(fig, folder / "luo2018_fig4_constant_speed")


def _sweep_figures(folder: Path) -> list[Path]:
    from matplotlib.figure import Figure

    from symkin.viz import figures

    data = curves()
    names = {"a": "e", "b": "m", "c": r"$\theta_{H0}$"}
    out = []
    for key, fig_no, unit, quantity in (("v", 7, "mm/s", "velocity"), ("a", 8, "mm/s$^2$", "acceleration")):
        fig = Figure(figsize=(10, 10))
        for n, panel in enumerate(("a", "b", "c"), 1):
            ax = fig.add_subplot(3, 1, n)
            for value, _, d, stroke, _ in data[panel]:
                ax.plot(d["t"], d[key] * 1e3, lw=1.1, label=f"{names[panel]} = ${sp.latex(value)}$, K = {stroke.ratio:.2f}")
            ax.set_ylabel(f"{key} [{unit}]", fontsize=8)
            ax.grid(lw=0.3)
            ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
            ax.tick_params(labelsize=7)
            fixed = {"a": "m = 1, $\\theta_{H0} = \\pi/6$", "b": "e = 2/5, $\\theta_{H0} = \\pi/6$", "c": "e = 2/5, m = 1"}[panel]
            ax.set_title(f"({panel}) varying {names[panel]}; {fixed}", fontsize=9)
        ax.set_xlabel("t [s]  (K = forward / return stroke time)", fontsize=8)
        fig.suptitle(
            f"Luo et al. 2018, fig. {fig_no}: slider {quantity} through elliptical gears\n"
            "l = 20 mm, input 0.8 pi rad/s, theta_2 = 0, pin installed for the guide",
            fontsize=10,
        )
        out += figures.save(fig, folder / f"luo2018_fig{fig_no}_{quantity}")
    return out


def _branch_figure(folder: Path) -> list[Path]:
    from matplotlib.figure import Figure

    from symkin.viz import figures

    values = {omega: TABLE1_OMEGA, e: BASE_E, m: 2, theta_H0: 0}
    ts = np.linspace(0, 2.5, 1001)
    derived = sp.lambdify(t, (EllipticalGears(omega, e, m).angle(t)).subs(values))(ts)
    published = sp.lambdify(t, PUBLISHED_27.subs(values))(ts)
    fig = Figure(figsize=(7, 4))
    ax = fig.add_subplot()
    ax.plot(ts, derived, lw=1.4, label="derived: continuous")
    ax.plot(ts, published, lw=1.0, ls="--", label="(27)-(28) principal arctan (reconstructed)")
    ax.set_xlabel("t [s]", fontsize=8)
    ax.set_ylabel(r"$\theta_H - \theta_{H0}$ [rad]", fontsize=8)
    ax.grid(lw=0.3)
    ax.legend(fontsize=8)
    ax.set_title("carrier angle through elliptical gears, e = 2/5, m = 2, input 0.8 pi rad/s", fontsize=9)
    return figures.save(fig, folder / "luo2018_carrier_angle_branches")


def notes() -> list[str]:
    rows = []
    for panel, entries in curves().items():
        name = SWEEPS[panel][0]
        for value, _, _, stroke, _ in entries:
            rows.append(f"{name} = {sp.sstr(value)}: forward {stroke.forward:.4f} s, return {stroke.back:.4f} s, K = {stroke.ratio:.4f}")
    return [
        "The slider law is derived by the vector loop (17)-(20) with the planet's turn from the contact condition at the "
        "ring; the superposition route (the pin as a planet particle) gives the same displacement.",
        "Conditions (13)-(14) are derived from the harmonics of the pin's deviation from the guide: the frequencies must "
        "coincide (z3 = 2 z1), then amplitude (l_1 = l_H) and phase (theta_1(0) = 2 (theta_2 - theta_H(0)) mod 2 pi).",
        "Figures 7-8 are drawn from the derived laws (the paper's parameter values are not in the text): Table 1's "
        "mechanism, input 0.8 pi rad/s, baseline e = 2/5, m = 1, theta_H(0) = pi/6. 'Steady share' is the fraction of "
        "the period, the longest stretch in which the velocity stays within 10% of its full range (the flat part "
        "of the curve).",
        "Stroke times (forward: slider moving towards +theta_2) per curve: " + "; ".join(rows),
    ]
