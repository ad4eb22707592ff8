"""Luo, Li, Feng & Hua (2018), Cardan-circle mechanism driven through elliptical gears, reproduced.

The mechanism is built with symkin (:func:`symkin.schemes.cardan`, :class:`symkin.mechanisms.cardan.CardanSlider`):
the planet's turn relative to the carrier comes from the engine's contact condition,
the slider's law from the vector loop (eqs. 17-20, :mod:`symkin.vectorloop`), the
conditions for straight-line motion from the loop's harmonics, and the elliptical drive
from the gears' pitch curves (:class:`symkin.drives.EllipticalGears`).  The published
forms below are transcribed from the paper (OCR in shared/papers); where the OCR lost a
formula, the form the paper's text implies is used and the check says
``source="reconstructed"``.  They are what is compared against, never used to derive.

Figures 7-8 are described in words only and the paper gives neither the baseline
eccentricity and order nor the carrier's initial angle: the claims are tested on curves
for stated parameters, with their sensitivity to the parameter the paper leaves open.
"""

from __future__ import annotations

import functools
import itertools
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp
from sympy.calculus.util import function_range

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
from symkin.numeric import compile
from symkin.papers.checks import (
    Check,
    Comparison,
    Kind,
    PrintedItem,
    alternative,
    annotate,
    compare_claim,
    compare_each,
    compare_exact,
    compare_inequality,
    compare_rounded,
    compare_symbolic,
    confirmation,
    gather,
    judge,
    nonzero_somewhere,
    proven_zero,
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
PUBLISHED_SPIN_TEXT = "planet 1 spins clockwise (omega_1) while it revolves counter-clockwise (omega_H)"
PUBLISHED_3 = theta_H0 + omega_H * S.t  # (3): theta_H -> theta_H + omega_H t
PUBLISHED_TEETH = (1, 2)  # z1 : z3 = 1 : 2, after (14)
PUBLISHED_14 = sp.Eq(l_1, l_H)
PUBLISHED_13_TEXT = "theta_1(0) = -(k + 1) pi, theta_2 free"  # (13) z = pi + k pi, "theta_H, theta_2 as needed"
PUBLISHED_15 = "angle O_H O O_1 + angle O O_H O_1 + pi - theta_1 = pi"
PUBLISHED_16 = 2 * (theta_2 - theta_H)
PUBLISHED_18 = (l_H * sp.exp(sp.I * theta_H) + l_1 * sp.exp(sp.I * (theta_H + theta_1)), s * sp.exp(sp.I * theta_2))
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
#: The time step of the sampled extremes the alternative reading of Table 1's velocity assumes (s).
TABLE1_SAMPLING_STEP = "0.01"
#: Fig. 5: "without gravity the contact force between bar 2 and housing 4 is always zero".
PUBLISHED_GUIDE_FORCE = 0

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
    "a": "e up: higher peaks, longer plateau, larger a extremes, quick return",
    "b": "m down: longer period, longer low-speed plateau, smaller slope between v extremes",
    "c": "theta_H(0) up: longer plateau, equal a extremes",
}
# The curves drawn here (the paper's parameter values are not in the text): Table 1's mechanism, baseline e, m, theta_H0.
BASE_E, BASE_M, BASE_THETA0 = sp.Rational(2, 5), 1, sp.pi / 6
SWEEPS = {
    "a": ("e", [sp.Integer(0), sp.Rational(1, 5), sp.Rational(2, 5), sp.Rational(3, 5)]),
    "b": ("m", [3, 2, 1]),
    "c": ("theta_H0", [sp.Integer(0), sp.pi / 6, sp.pi / 3, sp.pi / 2]),
}
#: The parameter the paper leaves open for each panel, and the values its claims are also tested at.
SENSITIVITY = {
    "a": ("theta_H0", [sp.Integer(0), sp.pi / 12, sp.pi / 6, sp.pi / 4, sp.pi / 3, 5 * sp.pi / 12, sp.pi / 2]),
    "b": ("theta_H0", [sp.Integer(0), sp.pi / 6, sp.pi / 3]),
    "c": ("e", [sp.Rational(1, 5), sp.Rational(2, 5), sp.Rational(3, 5)]),
}

PRINTED_ITEMS = (
    PrintedItem("(1), (4)-(12), (17)", "the pin's coordinates and the continuity analysis",
                "lost in the OCR; the conditions they lead to, (13), (14) and z1 : z3 = 1 : 2, are checked"),
    PrintedItem("(15)", "the angles of the triangle O_H O O_1: angle O_H O O_1 + angle O O_H O_1 + pi - theta_1 = pi"),
    PrintedItem("(2)", "the planet's speed relative to the carrier (lost in the OCR)"),
    PrintedItem("planet spin", "planet 1 spins clockwise while it revolves counter-clockwise"),
    PrintedItem("(3)", "theta_H -> theta_H + omega_H t"),
    PrintedItem("(13)", "z = pi + k pi: initial installation angle theta_1 = -(k + 1) pi, theta_H and theta_2 free"),
    PrintedItem("(14)", "l_1 = l_H"),
    PrintedItem("z1 : z3 = 1 : 2", "planet and ring teeth 1 : 2 with equal modules"),
    PrintedItem("(16)", "theta_1 = 2 (theta_2 - theta_H)"),
    PrintedItem("(18)", "the complex vector loop l_H e^(i theta_H) + l_1 e^(i (theta_H + theta_1)) = s e^(i theta_2)"),
    PrintedItem("(19)", "real part of (18)"),
    PrintedItem("(20)", "imaginary part of (18)"),
    PrintedItem("(21)", "s^2 = 2 l^2 (1 + cos theta_1)"),
    PrintedItem("(22)", "slider displacement (lost in the OCR)"),
    PrintedItem("(23)", "V_s = 2 l omega_H sin(theta_2 - omega_H t)"),
    PrintedItem("(24)", "slider acceleration (lost in the OCR)"),
    *(PrintedItem(f"Table 1 {q} {w}", f"theory row: {n} {w}") for q, n in (("s", "displacement"), ("v", "velocity"),
                                                                          ("a", "acceleration"))
      for w in ("initial", "max", "min")),
    PrintedItem("Table 1 simulation row", "SolidWorks Motion values: as the theory row, v(0) = -3.39e-16"),
    PrintedItem("period", "the slider moves with period T = 2 pi s"),
    PrintedItem("stroke", "stroke 80 mm"),
    PrintedItem("fig. 5", "without gravity the contact force between the bar and the housing is always zero"),
    PrintedItem("(25)", "ratio of the elliptical gears (lost in the OCR)"),
    PrintedItem("(26)", "carrier speed through the elliptical gears (lost in the OCR)"),
    PrintedItem("(27)-(28)", "carrier angle (lost in the OCR)"),
    PrintedItem("(29)", "slider displacement for a carrier law theta_H(t) (lost in the OCR)"),
    PrintedItem("(30)-(31)", "slider velocity (lost in the OCR)"),
    PrintedItem("(32)", "slider acceleration (lost in the OCR)"),
    PrintedItem("(33)-(35)", "carrier angular acceleration (lost in the OCR)"),
    PrintedItem("fig. 7(a)/8(a)", "larger e: higher velocity peak, longer steady share, larger acceleration extremes, quick return"),
    PrintedItem("fig. 7(b)", "smaller m: longer period, longer low-speed plateau, smaller slope between the velocity extremes"),
    PrintedItem("fig. 8(b)", "smaller m: more acceleration fluctuations, 'so changing m can improve smoothness'",
                "the sentence pairs more fluctuations with smoother motion, so the direction of the claimed change is "
                "ambiguous; the derived counts are in the note on fig. 8(b) (report.json, equations.pdf)"),
    PrintedItem("fig. 7(c)/8(c)", "larger theta_H(0): longer steady share, forward and reverse acceleration extremes tend to equal"),
    PrintedItem("conclusions", "the curves agree with the simulation; elliptical gears give uniform motion and quick return",
                "no simulation is run here; the quick return is fig. 7(a), checked"),
)


def _check(label, description, derived, published, comparison, **kw) -> Check:
    return Check.make(KEY, label, description, derived, published, comparison, **kw)


def _symbolic_slider(**kw) -> CardanSlider:
    """Carrier length l, ratio 1:2, pin on the pitch circle, installed as derived."""
    kw.setdefault("guide_angle", theta_2)
    kw.setdefault("carrier_angle", theta_H0)
    return CardanSlider.build(l, **kw)


def table1_slider(omega: sp.Expr | None = None) -> CardanSlider:
    """Section 2: l = 20 mm, z = 20/40, omega_H = 0.8 pi (or ``omega``), theta_1(0) = 0, theta_2 = 0."""
    drive = TABLE1_OMEGA if omega is None else omega
    return CardanSlider.build(TABLE1_LENGTH, drive=drive, teeth=TABLE1_TEETH, pin_angle=0, guide_angle=0)


def elliptical_slider(ecc, order, theta0) -> CardanSlider:
    """Table 1's mechanism driven through elliptical gears (input speed 0.8 pi rad/s)."""
    return CardanSlider.build(
        TABLE1_LENGTH, drive=EllipticalGears(TABLE1_OMEGA, ecc, order), teeth=TABLE1_TEETH, guide_angle=0, carrier_angle=theta0
    )


# --------------------------------------------------------------------------- checks
def checks() -> list[Check]:
    """Every equation, Table 1, fig. 5 and the claims of figures 7-8, derived and compared."""
    return gather(KEY, _structure, _continuity, _laws, _table1, _guide_force, _elliptical, _figure_claims)


RECONSTRUCTED = {"source": "reconstructed"}


def _structure() -> list[Check]:
    out = []
    mech = cardan.CardanSlider.build(l, teeth=(z1, z3)).mechanism
    speeds = mech.speeds({"H": omega_H})
    spin = sp.simplify(speeds["1"] - omega_H)
    out.append(_check("(2)", "planet 1 turns relative to the carrier (contact with the fixed ring 3)", spin, PUBLISHED_SPIN,
                      compare_symbolic(spin, PUBLISHED_SPIN), **RECONSTRUCTED))
    paper = table1_slider()
    absolute = paper.mechanism.speeds({"H": omega_H})["1"]
    relative = sp.simplify(absolute - omega_H)
    clockwise = [bool((w / omega_H).is_negative) for w in (relative, absolute)]
    out.append(_check("planet spin", "z = 20/40, carrier counter-clockwise (omega_H > 0): the planet's spin relative to the "
                      "carrier and its absolute speed", [relative, absolute], PUBLISHED_SPIN_TEXT,
                      compare_claim(all(clockwise), f"relative {relative}, absolute {absolute}: both clockwise for omega_H > 0")))
    uniform = _symbolic_slider(drive=omega_H)
    out.append(_check("(3)", "carrier angle under a constant carrier speed", uniform.carrier_angle, PUBLISHED_3,
                      compare_symbolic(uniform.carrier_angle, PUBLISHED_3)))
    out += _loop_checks(uniform)
    return out


def _loop_checks(uniform: CardanSlider) -> list[Check]:
    """(18)-(20): the pin's position as the engine's gear train gives it (the pin a particle of the
    planet, eq. (4) of the 2009 paper: superposition, no vector loop) against the printed loop's
    left side with the engine's carrier and planet angles.  The loop as symkin's model types it
    (its input, not a result) against the printed (18) is a consistency check."""
    pin = sp.Matrix(list(uniform.pin.position))
    lhs18, rhs18 = PUBLISHED_18
    angles = {l_H: uniform.arm, l_1: uniform.pin_radius, theta_H: uniform.carrier_angle, theta_1: uniform.planet_angle}
    printed = sp.expand_complex(lhs18.subs(angles))
    parts = (sp.re(printed), sp.im(printed))
    where = f"the printed left side with the engine's theta_H(t) = {uniform.carrier_angle}, theta_1(t) = {uniform.planet_angle}"
    out = [_check("(18)", "the pin's position x + i y from the gear train (the pin a particle of the planet, eq. 4 of the "
                  f"2009 paper), against the printed loop: {where}", pin[0] + sp.I * pin[1], lhs18,
                  compare_symbolic(pin[0] + sp.I * pin[1], printed))]
    for label, n, published in (("(19)", 0, PUBLISHED_19), ("(20)", 1, PUBLISHED_20)):
        out.append(_check(label, f"{'x' if n == 0 else 'y'} of the pin from the gear train, against the "
                          f"{'real' if n == 0 else 'imaginary'} part of (18) ({where})", pin[n], published,
                          compare_symbolic(pin[n], parts[n])))
    complex_loop = cardan.loop().complex_equation()
    out.append(_check("(18) model loop", "the loop symkin's slider model is built on (its input, typed from the "
                      "paper's geometry) against the printed (18): circular, so a consistency check", complex_loop,
                      sp.Eq(lhs18, rhs18), compare_symbolic((complex_loop.lhs - complex_loop.rhs).rewrite(sp.cos),
                                                            (lhs18 - rhs18).rewrite(sp.cos)), kind=Kind.CONSISTENCY))
    return out


def pin_deviation_by_hand(theta_10, guide, carrier0) -> sp.Expr:
    """The pin's distance from the guide for a 1 : 2 Cardan pair, typed here (not the engine).

    The planet axis is at l e^{i theta_H}; the pin at l e^{i (theta_H + theta_1)} from it;
    the planet rolls inside a ring twice its size, so relative to the carrier it turns at
    -2 omega_H: theta_1 = theta_10 - 2 omega_H t.  The deviation is the component of the
    pin's position across the guide.
    """
    tt = sp.Symbol("t", real=True)
    th_H = carrier0 + omega_H * tt
    th_1 = theta_10 - 2 * omega_H * tt
    pin = l * sp.exp(sp.I * th_H) + l * sp.exp(sp.I * (th_H + th_1))
    deviation = sp.im(sp.expand(pin * sp.exp(-sp.I * guide))).subs(tt, S.t)
    if proven_zero(deviation):
        return sp.Integer(0)
    return deviation if nonzero_somewhere(deviation) else sp.simplify(deviation)


def _continuity() -> list[Check]:
    out = []
    c = cardan.line_conditions()
    ratio = sp.cancel(c.ratio.rhs / S.radius("1"))
    out.append(_check("(13)-(14) ratio", "ring : planet for which the pin's harmonic can cancel the carrier's",
                      f"z1 : z3 = 1 : {ratio}", "z1 : z3 = 1 : 2", compare_exact(ratio, sp.Rational(*PUBLISHED_TEETH[::-1])),
                      item="z1 : z3 = 1 : 2", excluded="; ".join(f"{eq}: {why}" for eq, why in c.excluded)))
    out.append(_check("(14)", "pin radius equals carrier length", c.lengths, PUBLISHED_14,
                      compare_symbolic(c.lengths.rhs, PUBLISHED_14.rhs)))
    zero = sp.simplify(c.deviation.subs(c.substitutions()))
    out.append(_check("(12) identity", "deviation from the guide under the derived conditions, for every carrier angle",
                      zero, 0, compare_exact(zero, 0), kind=Kind.CONSISTENCY))
    # (13): the installation angle.  Derived: theta_1(0) = 2 (theta_2 - theta_H(0)) mod 2 pi.
    rule = c.installation.rhs
    cases = [(sp.Integer(0), sp.Integer(0)), (sp.pi / 6, sp.Integer(0)), (sp.pi / 4, sp.pi / 12)]
    printed_angles = (sp.Integer(0), sp.pi)  # (13): theta_1(0) = -(k + 1) pi, any k, theta_2 and theta_H(0) free
    derived_on_guide = {f"theta_2 = {g}, theta_H(0) = {h}": sp.Mod(rule.subs({theta_2: g, theta_H0: h}), 2 * sp.pi)
                        for g, h in cases}
    printed_ok = {key: [a for a in printed_angles if sp.Mod(a - v, 2 * sp.pi) == 0] for key, v in derived_on_guide.items()}
    agrees = all(len(v) == len(printed_angles) for v in printed_ok.values())  # (13) admits both 0 and pi in each case
    hand = {}
    for (g, h), key in zip(cases, derived_on_guide):
        candidates = sorted({derived_on_guide[key], *printed_angles}, key=float)
        hand[key] = [a for a in candidates if pin_deviation_by_hand(a, g, h) == 0]
    same_as_rule = {k: v for k, v in hand.items()}
    rule_sets = {k: [v] for k, v in derived_on_guide.items()}
    out.append(_check(
        "(13)", "installation angle theta_1(0) for motion along the guide", c.installation, PUBLISHED_13_TEXT,
        judge(compare_claim(agrees, f"the derived rule {c.installation.lhs} = {rule} (mod 2 pi), the paper's own (16) at "
                                    f"t = 0, keeps the pin on the guide only at {derived_on_guide}; (13) admits "
                                    f"theta_1(0) = 0 and pi for any theta_2, theta_H(0)"),
              confirmation=confirmation(
                  "the pin's position typed by hand (planet axis l e^(i theta_H), pin l e^(i (theta_H + theta_1)), "
                  "theta_1 = theta_1(0) - 2 omega_H t): the installation angles among the derived one, 0 and pi whose "
                  "deviation from the guide vanishes for all t", same_as_rule, rule_sets,
                  lambda v, d: compare_claim(v == d, f"on the guide: {v}; derived rule: {d}")),
              hypothesis="(13) was derived for theta_2 - theta_H(0) a multiple of pi/2, as in Table 1"),
    ))
    return out


def _triangle_check(slider: CardanSlider) -> Check:
    """(15): the triangle O_H O O_1 (carrier centre, pin, planet centre) with its corners where the engine's gear
    train puts them (the pin and the planet centre particles of the planet), its angles at O and O_H measured there
    (arccos of the sides' directions, 40 digits), against pi - (pi - theta_1) with the engine's planet angle theta_1
    (the interior angle at O_1; theta_1 taken in (0, pi], mirrored when the triangle turns over)."""
    centre = slider.motion.particle("1", (0, 0), relative_to="pole").position
    values = {l: 1, theta_2: sp.Rational(7, 10), theta_H0: sp.Rational(1, 5), omega_H: 1}

    def angle(u, v):
        return sp.acos((u[0] * v[0] + u[1] * v[1]) / sp.sqrt((u[0]**2 + u[1]**2) * (v[0]**2 + v[1]**2)))

    gaps = []
    for when in (sp.Rational(1, 10), sp.Rational(2, 5), sp.Rational(4, 5), sp.Rational(6, 5), sp.Rational(8, 5)):
        at = {**values, t: when}
        o1 = [sp.N(c.subs(at), 40) for c in centre]
        o = [sp.N(c.subs(at), 40) for c in slider.pin.position]
        theta1 = sp.N(sp.Mod(slider.planet_angle.subs(at), 2 * sp.pi), 40)
        inner = theta1 if theta1 <= sp.pi else 2 * sp.pi - theta1
        at_o = angle([-o[0], -o[1]], [o1[0] - o[0], o1[1] - o[1]])
        at_h = angle(o, o1)
        gaps.append(sp.N(at_o + at_h - inner, 40))
    worst = max(abs(g) for g in gaps)
    return _check(
        "(15)", "the angles of the triangle O_H O O_1 at O and O_H (engine's positions) against theta_1 (engine's planet "
        "angle), l = 1, theta_2 = 0.7, theta_H(0) = 0.2, omega_H = 1, t = 0.1 ... 1.6 s",
        [sp.Float(g, 5) for g in gaps], PUBLISHED_15,
        compare_claim(bool(worst < sp.Float("1e-30")), f"angle at O + angle at O_H - theta_1 = {float(worst):.1e} at most "
                                                     "over the five instants (40 digits)"))


def _laws() -> list[Check]:
    out = []
    # (21): the loop solved for the slider vector's length and angle (same vector), squared
    solution = cardan.loop().solve(s, theta_2)[0]
    s2 = sp.factor(sp.trigsimp(sp.expand(solution[s] ** 2).subs({l_1: l, l_H: l})))
    out.append(_check("(21)", "s^2 from the loop (unknowns s, theta_2), l = l_1 = l_H", s2, PUBLISHED_21,
                      compare_symbolic(s2, PUBLISHED_21)))
    uniform = _symbolic_slider(drive=omega_H)
    theta_now = theta_H0 + omega_H * t
    out.append(_triangle_check(uniform))
    out.append(_check("(16)", "pin angle on the planet during the motion", uniform.planet_angle, PUBLISHED_16.subs(theta_H, theta_now),
                      compare_symbolic(uniform.planet_angle, PUBLISHED_16.subs(theta_H, theta_now))))
    out.append(_check("(22)", "slider displacement (vector loop along the guide)", uniform.displacement,
                      PUBLISHED_22.subs(theta_H, theta_now), compare_symbolic(uniform.displacement, PUBLISHED_22.subs(theta_H, theta_now)),
                      **RECONSTRUCTED))
    start = _symbolic_slider(drive=omega_H, carrier_angle=0)
    out.append(_check("(23)", "slider velocity, theta_H(0) = 0", start.velocity, PUBLISHED_23,
                      compare_symbolic(start.velocity, PUBLISHED_23)))
    out.append(_check("(24)", "slider acceleration, theta_H(0) = 0", start.acceleration, PUBLISHED_24,
                      compare_symbolic(start.acceleration, PUBLISHED_24), **RECONSTRUCTED))
    # the second route: the pin as a planet particle (superposition), projected on the guide
    along = uniform.pin.position[0] * sp.cos(theta_2) + uniform.pin.position[1] * sp.sin(theta_2)
    out.append(_check("(22) superposition", "slider displacement: pin as a planet particle, eqs. (4)-(6) of the 2009 paper, "
                      "against the vector loop", along, uniform.displacement,
                      compare_symbolic(along, uniform.displacement), kind=Kind.CONSISTENCY))
    return out


def _table1() -> list[Check]:
    out = []
    slider = table1_slider()
    T = slider.period()
    span = sp.Interval(0, T)
    laws = {"s": slider.displacement, "v": slider.velocity, "a": slider.acceleration}
    # maximum and minimum are the sup and inf of function_range: one range per law gives both
    ranges = {k: function_range(f, t, span) for k, f in laws.items()}
    derived = {k: (f.subs(t, 0), ranges[k].sup, ranges[k].inf) for k, f in laws.items()}
    sampled, sampling_table = _sampled_extremes(slider, T)
    for q, names in (("s", "displacement"), ("v", "velocity"), ("a", "acceleration")):
        for which, value, printed in zip(("initial", "max", "min"), derived[q], TABLE1[q]):
            label = f"Table 1 {q} {which}"
            evidence, rests = {}, ""
            if q == "v" and which != "initial":
                n = 0 if which == "max" else 1
                alt_value = sampled[TABLE1_SAMPLING_STEP][n]
                evidence["alternative"] = alternative(
                    f"the extremes of v sampled every {TABLE1_SAMPLING_STEP} s over one period (the derived law "
                    f"evaluated by symkin.numeric; sampled extremes by step: {sampling_table})",
                    alt_value, printed, compare_rounded)
                fits = [step for step, ext in sampled.items() if compare_rounded(ext[n], printed).verdict.agrees]
                misses = [step for step in sampled if step not in fits]
                rests = (f"the sampling step {TABLE1_SAMPLING_STEP} s, chosen after the fact because it reproduces the "
                         f"printed value: the paper states no step; steps of {', '.join(fits)} s reproduce it, steps of "
                         f"{', '.join(misses)} s do not")
            out.append(_check(label, f"{names} {which} (l = 20 mm, omega_H = 0.8 pi rad/s)", value, printed,
                              judge(compare_rounded(value, printed), **evidence), rests_on=rests))
    out.append(_simulation_row(derived, sampled, sampling_table))
    stroke = derived["s"][1] - derived["s"][2]
    out.append(_check("stroke", "slider stroke (80 mm)", stroke, PUBLISHED_STROKE, compare_exact(stroke, sp.Rational(PUBLISHED_STROKE))))
    unit_speed = table1_slider(sp.Integer(1)).period()
    out.append(_check(
        "period", "period of the slider motion, s (omega_H = 0.8 pi rad/s)", T, PUBLISHED_PERIOD,
        annotate(judge(compare_exact(T, PUBLISHED_PERIOD),
                       alternative=alternative("the carrier at omega_H = 1 rad/s (2 pi is the period in carrier angle, rad)",
                                               unit_speed, PUBLISHED_PERIOD, compare_exact)),
                 f"the table's extremes fall at a quarter and three quarters of {T} s: v is extreme at t = "
                 f"{', '.join(str(x) for x in _extreme_times(slider))} s"),
    ))
    return out


def _simulation_row(derived: dict, sampled: dict, sampling_table: str) -> Check:
    """Table 1's simulation row (SolidWorks Motion) against the derived values: each cell rounded as printed;
    v(0) = -3.39e-16 within half a unit of the table's last velocity digit (1e-5 m/s) of the derived 0."""
    cells = [(q, n) for q in "sva" for n in range(3)]
    printed = [TABLE1_SIMULATED_V0 if cell == ("v", 0) else TABLE1[cell[0]][cell[1]] for cell in cells]
    names = [f"{q} {('initial', 'max', 'min')[n]}" for q, n in cells]
    noise = sp.Rational(5, 10**6)  # m/s: half a unit of the last digit of 100.52e-3

    def cell(value, text):
        if text == TABLE1_SIMULATED_V0:
            gap = abs(sp.Rational(text) - value)
            return compare_inequality(gap, "<", noise)
        return compare_rounded(value, text)

    values = [derived[q][n] for q, n in cells]
    at_step = [sampled[TABLE1_SAMPLING_STEP][n - 1] if (q, n) in (("v", 1), ("v", 2)) else v
               for (q, n), v in zip(cells, values)]
    return _check(
        "Table 1 simulation row", "the simulation row (SolidWorks Motion; l = 20 mm, omega_H = 0.8 pi rad/s) against "
        "the derived laws: s, v, a initial, max, min", values, printed,
        judge(compare_each(values, printed, cell, names),
              alternative=alternative(f"the velocity extremes sampled every {TABLE1_SAMPLING_STEP} s, as a simulation "
                                      f"reports them at its frames (sampled extremes by step: {sampling_table})",
                                      at_step, printed, lambda d, p: compare_each(d, p, cell, names))),
        rests_on=f"the sampling step {TABLE1_SAMPLING_STEP} s of the velocity extremes, as for the theory row: the "
                 "paper states no frame rate")


def _extreme_times(slider: CardanSlider) -> list[sp.Expr]:
    period = slider.period()
    return sorted(x for x in sp.solve(sp.diff(slider.velocity, t), t) if 0 < x < period)


def _sampled_extremes(slider: CardanSlider, period) -> tuple[dict[str, tuple[float, float]], str]:
    """Extremes of the derived v sampled on time grids of several steps (numbers from symkin.numeric)."""
    out = {}
    for step in ("0.001", "0.005", TABLE1_SAMPLING_STEP, "0.02", "0.04", "0.05"):
        ts = np.arange(0, float(period) + 1e-12, float(step))
        v = slider.evaluate(ts)["v"]
        out[step] = (float(v.max()), float(v.min()))
    table = ", ".join(f"{step} s: {hi * 1e3:.3f}/{lo * 1e3:.3f}e-3" for step, (hi, lo) in out.items())
    return out, table


def _guide_force() -> list[Check]:
    """Fig. 5: the force across the guide, from the pin's acceleration (the 2009 paper's eq. 6)."""
    slider = table1_slider()
    pin = slider.pin
    normal = (-sp.sin(slider.guide_angle), sp.cos(slider.guide_angle))
    across = sp.simplify(pin.acceleration[0] * normal[0] + pin.acceleration[1] * normal[1])
    mass = sp.Symbol("M", positive=True)
    force = sp.simplify(mass * across)
    return [_check(
        "fig. 5", "force the guide must exert across itself on a slider of mass M carried by the pin (no gravity): "
        "M times the pin's acceleration across the guide (particle law, eq. 6)", force, PUBLISHED_GUIDE_FORCE,
        annotate(compare_exact(force, PUBLISHED_GUIDE_FORCE),
                 "the pin's path is the guide line by the gearing alone, so the guide is a redundant constraint and "
                 "carries nothing in the rigid model; with gravity across the guide it would carry M g"),
    )]


def _elliptical() -> list[Check]:
    out = []
    gears = EllipticalGears(omega, e, m)
    ratio = gears.ratio(alpha_in)
    out.append(_check("(25)", "transmission ratio of identical elliptical gears (from the pitch curves)", ratio, PUBLISHED_25,
                      compare_symbolic(ratio, PUBLISHED_25), **RECONSTRUCTED))
    speed = gears.speed(t)
    out.append(_check("(26)", "carrier speed through the elliptical gears", speed, PUBLISHED_26, compare_symbolic(speed, PUBLISHED_26),
                      **RECONSTRUCTED))
    angle = theta_H0 + gears.angle(t)
    out.append(_check("(27)-(28)", "carrier angle, on |m omega t| < pi where the arctan form is continuous", angle, PUBLISHED_27,
                      _branch_comparison(angle), **RECONSTRUCTED))
    general = _symbolic_slider(drive=AngleLaw(Theta(t)), carrier_angle=Theta(0))
    for label, derived, published in (
        ("(29)", general.displacement, PUBLISHED_29),
        ("(30)-(31)", general.velocity, PUBLISHED_30),
        ("(32)", general.acceleration, PUBLISHED_32),
    ):
        out.append(_check(label, "slider law for a carrier law theta_H(t) (vector loop, differentiated)", derived, published,
                          compare_symbolic(derived, published), **RECONSTRUCTED))
    eps = gears.acceleration(t)
    out.append(_check("(33)-(35)", "carrier angular acceleration through the elliptical gears", eps, PUBLISHED_EPS,
                      compare_symbolic(eps, PUBLISHED_EPS), **RECONSTRUCTED))
    drive0 = EllipticalGears(omega, 0, m)
    ell, uni = _symbolic_slider(drive=drive0, carrier_angle=0), _symbolic_slider(drive=ConstantSpeed(omega), carrier_angle=0)
    for label, derived, published in (
        ("e = 0: (22)", ell.displacement, uni.displacement),
        ("e = 0: (23)", ell.velocity, uni.velocity),
        ("e = 0: (24)", ell.acceleration, uni.acceleration),
    ):
        out.append(_check(label, "circular gears (e = 0) against the constant-speed drive", derived, published,
                          compare_symbolic(derived, published), kind=Kind.CONSISTENCY))
    return out


def _branch_comparison(angle: sp.Expr) -> Comparison:
    """The textbook arctan form of the carrier angle against the derived continuous one, on |m omega t| < pi.

    Equal derivatives and equal values at t = 0 make two functions equal on the interval
    around 0 where both are smooth; beyond it the principal arctan jumps by -2 pi/m.
    """
    slope, at_zero = (sp.Integer(0) if proven_zero(x) else sp.simplify(x)
                      for x in (sp.diff(PUBLISHED_27 - angle, t), (PUBLISHED_27 - angle).subs(t, 0)))
    values = {omega: 1, e: sp.Rational(1, 2), m: 2, theta_H0: 0}
    # the published form as printed (compile's stable forms would unwrap its principal arctan)
    published = compile(PUBLISHED_27.subs(values), [t], backend="numpy", stable=False, on_pole="return")
    derived = compile(angle.subs(values), [t], backend="numpy")
    branch = np.pi / 2  # m omega t = pi
    pub_before, pub_after = (published(branch - 1e-9), published(branch + 1e-9))
    der_before, der_after = (derived(branch - 1e-9), derived(branch + 1e-9))
    return compare_claim(
        slope == 0 and at_zero == 0,
        f"d/dt(published - derived) = {slope} and (published - derived)(0) = {at_zero}, so they are equal on "
        f"|m omega t| < pi; at every t = (2j+1) pi/(m omega) the principal arctan jumps by -2 pi/m while the derived angle "
        f"is continuous (e = 1/2, m = 2, omega = 1 at t = pi/2: published {float(pub_before):.6f} -> {float(pub_after):.6f}, "
        f"derived {float(der_before):.6f} -> {float(der_after):.6f})",
    )


# --------------------------------------------------------------------------- figures 7-8
_E, _THETA0 = sp.Symbol("e", nonnegative=True), sp.Symbol("theta_H0", real=True)


def _family(order) -> Any:
    """s, v, a, theta_H and omega_H of Table 1's mechanism through elliptical gears of one order,
    compiled once (symkin.numeric) with the eccentricity and theta_H(0) as arguments."""
    # one key per order: functools.cache tells the int 3 from SymPy's 3 (the curves of fig. 7
    # give the order as an int, the drives as SymPy's), which compiled every law twice
    return _compiled_family(sp.sympify(order))


@functools.cache
def _compiled_family(order: sp.Expr) -> Any:
    slider = elliptical_slider(_E, order, _THETA0)
    angle = slider.carrier_angle
    return compile([slider.displacement, slider.velocity, slider.acceleration, angle, sp.diff(angle, t)], [t, _E, _THETA0], backend="numpy")


@functools.cache
def _velocity_law() -> Any:
    """The derived slider velocity for any carrier law (the vector loop differentiated, (30)),
    of Table 1's mechanism, compiled as a function of the carrier angle and speed."""
    general = _symbolic_slider(drive=AngleLaw(Theta(t)), carrier_angle=Theta(0), guide_angle=0)
    angle, speed = sp.symbols("theta_H omega_H", real=True)
    law = general.velocity.subs(sp.Derivative(Theta(t), t), speed).subs(Theta(t), angle).subs(l, TABLE1_LENGTH)
    return compile(law, [angle, speed], backend="numpy")


def sample_curve(ecc, order, theta0, times) -> dict[str, np.ndarray]:
    """The derived laws of one curve of figures 7-8 on a time grid (t, s, v, a, theta, omega)."""
    ts = np.asarray(times, dtype=float)
    columns = _family(order)(ts, float(ecc), float(theta0))
    return {"t": ts, **{k: np.broadcast_to(np.asarray(c, dtype=float), ts.shape)
                        for k, c in zip(("s", "v", "a", "theta", "omega"), columns)}}


def _sweep(panel: str, **fixed) -> list:
    """One panel's curves: (value, slider, samples, stroke times, stats) for each swept value.

    ``fixed`` overrides the baseline of the other parameters (``e``, ``m``, ``theta_H0``).
    """
    name, values = SWEEPS[panel]
    base = {"e": BASE_E, "m": BASE_M, "theta_H0": BASE_THETA0, **fixed}
    rows = []
    for value in values:
        params = {**base, name: value}
        slider = elliptical_slider(params["e"], params["m"], params["theta_H0"])
        T = float(slider.period())
        data = sample_curve(params["e"], params["m"], params["theta_H0"], np.linspace(0.0, T, 1201))
        stroke = slider.stroke_times()
        rows.append((value, slider, data, stroke, _stats(data, T)))
    return rows


def _curves():
    """For each panel a (e), b (m), c (theta_H0): (label value, slider, samples, stroke times, stats)."""
    return {panel: _sweep(panel) for panel in SWEEPS}


def steady_share(v: np.ndarray, tolerance: float = 0.1) -> float:
    """The longest stretch of one period (samples over [0, T), periodic) in which v stays
    within ``tolerance`` of its full range, as a share of the period: the flat part of
    the velocity curve.

    For every start at once, the longest stretch is grown by halving steps (2^k samples,
    k falling, each step taken while the stretch stays within the band and one period
    long), on tables of the largest and smallest value of every 2^k samples.
    """
    v = np.asarray(v, dtype=float)
    n = len(v)
    band = tolerance * float(v.max() - v.min())
    highs, lows = [np.concatenate([v, v])], [np.concatenate([v, v])]  # level k: max/min of w[i : i + 2^k]
    while 2 ** len(highs) <= n:
        half = 2 ** (len(highs) - 1)
        highs.append(np.maximum(highs[-1][:-half], highs[-1][half:]))
        lows.append(np.minimum(lows[-1][:-half], lows[-1][half:]))
    starts = np.arange(n)
    length = np.zeros(n, dtype=np.int64)
    high, low = np.full(n, -np.inf), np.full(n, np.inf)
    for k in range(len(highs) - 1, -1, -1):
        step = 2**k
        at = np.minimum(starts + length, len(highs[k]) - 1)
        new_high, new_low = np.maximum(high, highs[k][at]), np.minimum(low, lows[k][at])
        grow = (length + step <= n) & (new_high - new_low <= band)
        length = np.where(grow, length + step, length)
        high, low = np.where(grow, new_high, high), np.where(grow, new_low, low)
    return int(length.max()) / n


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


def _decreasing(xs) -> bool:
    return all(b < a for a, b in itertools.pairwise(xs))


def _column(rows, key):
    return [x[key] for *_, x in rows]


def _table(rows, name):
    return "; ".join(
        f"{name} = {sp.sstr(v)}: K = {st.ratio:.3f}, v {x['v_min'] * 1e3:.1f}..{x['v_max'] * 1e3:.1f} mm/s "
        f"(peak at {x['t_v_max']:.2f} s), a {x['a_min'] * 1e3:.0f}..{x['a_max'] * 1e3:.0f} mm/s^2, "
        f"steady share {x['steady_share']:.2f}"
        for v, _, _, st, x in rows
    )


def _shown(claims: dict[str, bool]) -> str:
    return "; ".join(f"{k}: {'shown' if v else 'NOT shown'}" for k, v in claims.items())


def claims_a(rows) -> dict[str, bool]:
    """Fig. 7(a)/8(a), e increasing: each sub-claim tested on the curves."""
    peaks = [max(hi, -lo) for hi, lo in zip(_column(rows, "v_max"), _column(rows, "v_min"))]
    acc = [max(hi, -lo) for hi, lo in zip(_column(rows, "a_max"), _column(rows, "a_min"))]
    ratios = [st.ratio for _, _, _, st, _ in rows]
    return {
        "higher velocity peak": _increasing(peaks),
        "longer steady stretch": _increasing(_column(rows, "steady_share")),
        "larger acceleration extremes": _increasing(acc),
        "quick return (K grows from 1)": _increasing(ratios) and abs(ratios[0] - 1) < 1e-9,
    }


def claims_c(rows) -> dict[str, bool]:
    """Fig. 7(c)/8(c), theta_H(0) increasing."""
    asym = [abs(hi + lo) / max(hi, -lo) for hi, lo in zip(_column(rows, "a_max"), _column(rows, "a_min"))]
    return {
        "longer steady stretch": _increasing(_column(rows, "steady_share")),
        "forward and reverse acceleration extremes approach each other": _decreasing(asym) and asym[-1] < 1e-9,
    }


def order_stats(slider: CardanSlider, principal: bool, samples: int = 2400) -> dict[str, float]:
    """Period, low-speed plateau (s) and slope between the velocity extremes of one curve of fig. 7(b).

    ``principal``: the carrier angle of the engine's continuous law folded onto the
    principal branch of the arctan form (27), theta - (2 pi/m) floor((m omega t + pi)/(2 pi));
    the curve then repeats every 2 pi/(m omega).  Otherwise the derived law itself.
    """
    drive = slider.drive
    order, w = float(drive.order), float(drive.omega)
    period = 2 * np.pi / (order * w) if principal else float(slider.period())
    ts = np.linspace(0.0, period, samples + 1)[:-1]
    curve = sample_curve(drive.eccentricity, drive.order, slider.carrier_angle0, ts)
    theta, speed = curve["theta"], curve["omega"]
    if principal:
        theta = theta - (2 * np.pi / order) * np.floor((order * w * ts + np.pi) / (2 * np.pi))
    v = np.broadcast_to(np.asarray(_velocity_law()(theta, speed), dtype=float), ts.shape)  # the derived law (30)
    hi, lo = int(np.argmax(v)), int(np.argmin(v))
    dv = np.diff(np.append(v, v[0]))  # a's sign, sampled; the acceleration's extrema are where its slope turns
    turns = int(np.count_nonzero(np.sign(np.diff(dv)) != np.sign(np.roll(np.diff(dv), 1))))
    return {"period": period, "plateau": steady_share(v) * period,
            "slope": abs(v[hi] - v[lo]) / abs(ts[hi] - ts[lo]), "a_extrema": turns}


def claims_b(stats: list[dict[str, float]]) -> dict[str, bool]:
    """Fig. 7(b), m decreasing (3, 2, 1)."""
    return {
        "longer period": _increasing([x["period"] for x in stats]),
        "longer low-speed plateau": _increasing([x["plateau"] for x in stats]),
        "smaller slope between the velocity extremes": _decreasing([x["slope"] for x in stats]),
    }


@functools.cache
def _sensitivity(panel: str) -> list[tuple[sp.Expr, dict[str, bool]]]:
    """The panel's claims at each value of the parameter the paper leaves open."""
    name, values = SENSITIVITY[panel]
    out = []
    for value in values:
        if panel == "b":
            sliders = [row[1] for row in _sweep("b", **{name: value})]
            out.append((value, {"continuous": claims_b([order_stats(sl, False) for sl in sliders]),
                                "principal": claims_b([order_stats(sl, True) for sl in sliders])}))
        else:
            rows = _sweep(panel, **{name: value})
            out.append((value, claims_a(rows) if panel == "a" else claims_c(rows)))
    return out


def _sensitivity_text(panel: str) -> str:
    name = SENSITIVITY[panel][0]

    def held(claims: dict) -> str:
        if all(isinstance(c, dict) for c in claims.values()):  # fig. 7(b): both readings
            return "; ".join(f"{reading}: {held(c)}" for reading, c in claims.items())
        failed = [k for k, ok in claims.items() if not ok]
        return "all hold" if not failed else "not shown: " + ", ".join(failed)

    return " | ".join(f"{name} = {sp.sstr(v)}: {held(claims)}" for v, claims in _sensitivity(panel))


def _figure_claims() -> list[Check]:
    """What the text says figures 7-8 show, tested on curves drawn from the derived laws.

    The paper gives neither its baseline parameters nor the initial carrier angle; the
    curves use Table 1's mechanism with e = 2/5, m = 1, theta_H(0) = pi/6, and each check
    also reports its claims at other values of the parameter left open.
    """
    data = curves()
    out = []
    base = {"e": sp.sstr(BASE_E), "m": sp.sstr(BASE_M), "theta_H0": sp.sstr(BASE_THETA0)}
    claims = claims_a(data["a"])
    out.append(_check(
        "fig. 7(a)/8(a)", f"effect of the eccentricity e (m = {base['m']}, theta_H(0) = {base['theta_H0']}, chosen: the paper "
        "gives neither)", _ratios(data["a"], "e"), SHORT_CLAIMS["a"],
        annotate(compare_claim(all(claims.values()), f"at the stated parameters {_shown(claims)}. {_table(data['a'], 'e')}"),
                 f"sensitivity to the initial carrier angle (not given in the paper): {_sensitivity_text('a')}"),
        claim=FIGURE_CLAIMS["a"], parameters=base,
        sensitivity=[{"theta_H0": sp.sstr(v), **c} for v, c in _sensitivity("a")],
    ))

    rows_b = data["b"]
    continuous = [order_stats(sl, False) for _, sl, *_ in rows_b]
    principal = [order_stats(sl, True) for _, sl, *_ in rows_b]
    claims_cont, claims_pb = claims_b(continuous), claims_b(principal)

    def fmt(stats):
        return "; ".join(f"m = {sp.sstr(v)}: period {x['period']:.3f} s, plateau {x['plateau']:.3f} s, slope "
                         f"{x['slope'] * 1e3:.1f} mm/s^2" for (v, *_), x in zip(rows_b, stats))

    out.append(_check(
        "fig. 7(b)", f"effect of the order m (e = {base['e']}, theta_H(0) = {base['theta_H0']}, chosen)",
        _ratios(rows_b, "m"), SHORT_CLAIMS["b"],
        annotate(judge(
            compare_claim(all(claims_cont.values()), f"with the derived (continuous) carrier angle: {_shown(claims_cont)} "
                                                     f"({fmt(continuous)})"),
            alternative=alternative(
                "curves drawn with the principal-branch arctan form (27) of the carrier angle, each over its own period "
                "2 pi/(m omega) (the derived angle folded onto that branch)", fmt(principal), SHORT_CLAIMS["b"],
                lambda v, p: compare_claim(all(claims_pb.values()), f"{_shown(claims_pb)} ({v})")),
        ), f"sensitivity to the initial carrier angle: {_sensitivity_text('b')}. Even orders give equal stroke times "
           f"(K = 1). {_table(rows_b, 'm')}"),
        claim=FIGURE_CLAIMS["b"], parameters=base,
        sensitivity=[{"theta_H0": sp.sstr(v), **{f"{r} {k}": ok for r, c in cs.items() for k, ok in c.items()}}
                     for v, cs in _sensitivity("b")],
    ))

    claims = claims_c(data["c"])
    asym = [abs(hi + lo) / max(hi, -lo) for hi, lo in zip(_column(data["c"], "a_max"), _column(data["c"], "a_min"))]
    out.append(_check(
        "fig. 7(c)/8(c)", f"effect of the initial carrier angle (e = {base['e']}, m = {base['m']}, chosen)",
        _ratios(data["c"], "theta_H(0)"), SHORT_CLAIMS["c"],
        annotate(compare_claim(all(claims.values()), f"at the stated parameters {_shown(claims)} (|a_max + a_min| / max|a|: "
                                                     f"{', '.join(f'{x:.3f}' for x in asym)}). {_table(data['c'], 'theta_H(0)')}"),
                 f"sensitivity to the eccentricity: {_sensitivity_text('c')}"),
        claim=FIGURE_CLAIMS["c"], parameters=base,
        sensitivity=[{"e": sp.sstr(v), **c} for v, c in _sensitivity("c")],
    ))
    return out


# --------------------------------------------------------------------------- figures
#: Captions of the figures in the report, and the checks (label prefixes) each illustrates.
REPORT_FIGURES = {
    "luo2018_paths": ("What the pin traces for four Cardan mechanisms, from the 2009 superposition laws "
                      "(pitch circles drawn with involute teeth).", ("(22) superposition",)),
    "luo2018_fig4_constant_speed": ("Fig. 4 / Table 1: displacement, velocity and acceleration of the slider at "
                                    "constant carrier speed.", ("Table 1", "stroke")),
    "luo2018_fig7_velocity": ("Fig. 7: slider velocity through elliptical gears for varying e, m and theta_H0.",
                              ("(26)", "fig. 7")),
    "luo2018_fig8_acceleration": ("Fig. 8: slider acceleration through elliptical gears for varying e, m and theta_H0.",
                                  ("(33)-(35)",)),
    "luo2018_carrier_angle_branches": ("The carrier angle through elliptical gears: the derived continuous angle "
                                       "beside the principal-arctan form (27)-(28).", ("(27)-(28)",)),
}


def figures(folder: Path) -> list[Path]:
    """Pin paths; Table 1's curves (fig. 4); figures 7 and 8; the carrier angle across a branch point."""
    return _paths_figure(folder) + _table1_figure(folder) + _sweep_figures(folder) + _branch_figure(folder)


def _paths_figure(folder: Path) -> list[Path]:
    from symkin.viz import figures, style

    cases = [
        ("z = 20/40, pin on the pitch circle", dict(teeth=(20, 40))),
        ("z = 20/40, pin at 0.5 l_H", dict(teeth=(20, 40), pin_radius=sp.Rational(1, 2))),
        ("z = 20/40, pin on the pitch circle, theta_1(0) = pi", dict(teeth=(20, 40), pin_angle=sp.pi)),
        ("z = 20/60, pin on the pitch circle", dict(teeth=(20, 60))),
    ]
    fig = style.new_figure(style.PAGE, style.PAGE * 1.05)
    for n, (title, kw) in enumerate(cases, 1):
        slider = CardanSlider.build(1, drive=1, **kw)
        ax = fig.add_subplot(2, 2, n)
        style.style_axes(ax)
        figures.draw_pitch_circles(ax, slider.mechanism, teeth=True)
        _, x, y = slider.pin.trajectory(float(2 * sp.pi), samples=721)
        ax.plot(x, y, lw=1.3, label="pin O (superposition)")
        ax.plot(x[:1], y[:1], "o", ms=3, ls="none", color=style.PALETTE[0])
        ax.axline((0, 0), (1, 0), lw=0.6, ls=":", color="k", label=r"guide, $\theta_2 = 0$")
        ax.set_aspect("equal")
        ax.set_xlabel(r"$x / l_H$ [-]", fontsize=style.FONT)
        ax.set_ylabel(r"$y / l_H$ [-]", fontsize=style.FONT)
        ax.set_title(f"{title}\nderived path: {slider.path().kind}".replace("theta_1(0)", r"$\theta_1(0)$")
                     .replace("l_H", "$l_H$"), fontsize=style.FONT)
    handles, labels = fig.axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=style.SMALL, frameon=False)
    fig.suptitle("Luo et al. 2018: what the pin traces ($l_H$ = 1, one carrier turn)", fontsize=style.FONT)
    return figures.save(style.finish(fig), folder / "luo2018_paths")


def _table1_figure(folder: Path) -> list[Path]:
    from symkin.viz import figures, style

    slider = table1_slider()
    ts = np.linspace(0, float(slider.period()), 501)
    d = slider.evaluate(ts)
    fig = style.new_figure(style.COLUMN * 1.5, 4.6)
    axes = fig.subplots(3, 1, sharex=True)
    for ax, (key, unit, name) in zip(axes, (("s", "mm", "displacement"), ("v", "mm/s", "velocity"), ("a", "mm/s$^2$", "acceleration"))):
        style.style_axes(ax)
        ax.plot(ts, d[key] * 1e3, lw=1.2)
        ax.set_ylabel(f"{name} {key} [{unit}]", fontsize=style.FONT)
    axes[-1].set_xlabel("time t [s]", fontsize=style.FONT)
    fig.suptitle("Luo et al. 2018, fig. 4 / Table 1: l = 20 mm,\n"
                 r"$\omega_H$ = 0.8$\pi$ rad/s (period 2.5 s)", fontsize=style.FONT)
    return figures.save(style.finish(fig), folder / "luo2018_fig4_constant_speed")


def _sweep_figures(folder: Path) -> list[Path]:
    from symkin.viz import figures, style

    data = curves()
    names = {"a": "e", "b": "m", "c": r"$\theta_{H0}$"}
    out = []
    for key, fig_no, unit, quantity in (("v", 7, "mm/s", "velocity"), ("a", 8, "mm/s$^2$", "acceleration")):
        fig = style.new_figure(style.PAGE, 7.6)
        axes = fig.subplots(3, 1, sharex=True)
        for ax, panel in zip(axes, ("a", "b", "c")):
            style.style_axes(ax)
            for value, _, d, stroke, _ in data[panel]:
                ax.plot(d["t"], d[key] * 1e3, lw=1.1, label=f"{names[panel]} = ${sp.latex(value)}$, K = {stroke.ratio:.2f}")
            ax.set_ylabel(f"{quantity} {key} [{unit}]", fontsize=style.FONT)
            style.legend_outside(ax, where="right")
            fixed = {"a": "m = 1, $\\theta_{H0} = \\pi/6$", "b": "e = 2/5, $\\theta_{H0} = \\pi/6$", "c": "e = 2/5, m = 1"}[panel]
            ax.set_title(f"({panel}) varying {names[panel]}; {fixed}", fontsize=style.FONT)
        axes[-1].set_xlabel("time t [s]   (K = forward / return stroke time)", fontsize=style.FONT)
        fig.suptitle(
            f"Luo et al. 2018, fig. {fig_no}: slider {quantity} through elliptical gears\n"
            r"l = 20 mm, input 0.8$\pi$ rad/s, $\theta_2$ = 0, pin installed for the guide",
            fontsize=style.FONT,
        )
        out += figures.save(style.finish(fig), folder / f"luo2018_fig{fig_no}_{quantity}")
    return out


def _branch_figure(folder: Path) -> list[Path]:
    from symkin.viz import figures, style

    values = {omega: TABLE1_OMEGA, e: BASE_E, m: 2, theta_H0: 0}
    ts = np.linspace(0, 2.5, 1001)
    derived = compile((EllipticalGears(omega, e, m).angle(t)).subs(values), [t], backend="numpy")(ts)
    # as printed: no stable rewriting (which would unwrap the principal arctan's jumps)
    published = compile(PUBLISHED_27.subs(values), [t], backend="numpy", stable=False, on_pole="return")(ts)
    fig = style.new_figure(style.COLUMN * 1.5, 3.6)
    ax = fig.add_subplot()
    style.style_axes(ax)
    ax.plot(ts, derived, lw=1.4, label="derived: continuous")
    ax.plot(ts, published, lw=1.0, label="(27)-(28) principal arctan (reconstructed)")
    ax.set_xlabel("time t [s]", fontsize=style.FONT)
    ax.set_ylabel(r"$\theta_H - \theta_{H0}$ [rad]", fontsize=style.FONT)
    style.legend_outside(ax)
    ax.set_title("carrier angle through elliptical gears,\ne = 2/5, m = 2, input 0.8$\\pi$ rad/s", fontsize=style.FONT)
    return figures.save(style.finish(fig), folder / "luo2018_carrier_angle_branches")


def notes() -> list[str]:
    """Remarks printed under the paper's checks in the report: how the slider law and the straight-line conditions are derived, and the stroke times of the curves of figures 7-8."""
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
        "The paper's figs. 7-8 are redrawn from the derived laws (the paper's parameter values are not in the text): Table 1's "
        "mechanism, input 0.8 pi rad/s, baseline e = 2/5, m = 1, theta_H(0) = pi/6, chosen here; each figure check "
        "also tests its claims at other values of the parameter the paper leaves open. 'Steady share' is the fraction "
        "of the period, the longest stretch in which the velocity stays within 10% of its full range (the flat part "
        "of the curve); the plateau of fig. 7(b) is that stretch in seconds.",
        "Fig. 8(b), acceleration extrema per period for m = 3, 2, 1 (theta_H(0) = pi/6): derived law "
        + ", ".join(str(order_stats(sl, False)["a_extrema"]) for _, sl, *_ in curves()["b"])
        + "; principal-branch reading " + ", ".join(str(order_stats(sl, True)["a_extrema"]) for _, sl, *_ in curves()["b"])
        + ": fewer or as many for smaller m, while the text says 'more'; the text then calls the change an improvement "
        "of smoothness, so the intended direction is unclear and the item is not given a verdict.",
        "Stroke times (forward: slider moving towards +theta_2) per curve: " + "; ".join(rows),
    ]
