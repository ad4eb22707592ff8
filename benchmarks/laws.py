"""The four laws the numeric benchmarks measure, each behind one function.

``slider_laws`` builds the elliptical-drive slider laws from the drive law of Luo & Li
(2018) section 3 as given in the papers guide (theta_H(t) with the principal arctan,
omega_H(t) = omega (1 - e^2)/(1 - 2 e cos(m omega t) + e^2)) substituted into
s = 2 l cos(theta_2 - theta_H) and differentiated by SymPy: the naive route whose float
forms lose digits (the extremes table), and, with the branch corrected, the independent
50-digit reference.  ``slider_acceleration`` is the engine's own derived law
(symkin.mechanisms.cardan with symkin.drives.EllipticalGears), the one the throughput table times.
"""

from __future__ import annotations

import sympy as sp

from symkin import schemes
from symkin import symbols as S

E = sp.Symbol("e", positive=True)  # eccentricity, 0 < e < 1
M = sp.Symbol("m", positive=True)  # order of the elliptical gears
W = sp.Symbol("omega", positive=True)  # input speed
L = sp.Symbol("l", positive=True)  # carrier length = planet radius
THETA2 = sp.Symbol("theta_2", real=True)  # slider line angle
THETA0 = sp.Symbol("theta_H0", real=True)  # initial carrier angle
RANGES = {E: (0, 1)}


def ratio_law() -> sp.Expr:
    """AA, i_1H^(4) in tooth numbers (the 2009 paper's numeric examples)."""
    return schemes.two_row("AA", teeth=True).ratio("1", "H", fixed="4").rhs


def differential_law() -> sp.Expr:
    """II, omega_H given omega_1 and omega_4, with r_4 from coaxiality (r4 = r1 - r2 + r3)."""
    law = schemes.two_row("II").speeds({"1": S.omega("1"), "4": S.omega("4")}).law("H").rhs
    r1, r2, r3, r4 = (S.radius(i) for i in "1234")
    return sp.factor(law.subs(r4, r1 - r2 + r3))


def planet_acceleration() -> sp.ImmutableMatrix:
    """AI two-row, gear 4 fixed, sun 1 at omega_1: acceleration of the planet particle at
    the pitch point with gear 1 at t = 0, (r_1, 0)."""
    motion = schemes.two_row("AI").motion({"1": S.omega("1"), "4": 0})
    return motion.particle("23", (S.radius("1"), 0)).acceleration


def slider_laws() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """(s, V_s, a_s) of the Cardan slider driven by an elliptical gear pair."""
    t = S.t
    theta = THETA0 + 2 / M * sp.atan((1 + E) / (1 - E) * sp.tan(M * W * t / 2))
    omega_h = W * (1 - E**2) / (1 - 2 * E * sp.cos(M * W * t) + E**2)
    th = sp.Function("theta_H")(t)
    s = 2 * L * sp.cos(THETA2 - th)
    v, a = sp.diff(s, t), sp.diff(s, t, 2)
    subs = [(sp.Derivative(th, (t, 2)), sp.diff(omega_h, t)), (sp.Derivative(th, t), omega_h), (th, theta)]
    return tuple(x.subs(subs) for x in (s, v, a))  # type: ignore[return-value]


def slider_acceleration() -> sp.Expr:
    """a_s as the engine derives it: symkin.mechanisms.cardan.CardanSlider under symkin.drives.EllipticalGears
    (the benchmarks' reference is built independently, from the papers guide, by
    :func:`slider_laws_continuous`)."""
    from symkin.drives import EllipticalGears
    from symkin.mechanisms.cardan import CardanSlider

    slider = CardanSlider.build(L, drive=EllipticalGears(W, E, M), guide_angle=THETA2, carrier_angle=THETA0)
    return slider.acceleration


def slider_laws_continuous() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """The same laws with the principal arctan corrected by its branch number: the
    continuous reference the benchmarks compare with (independent of symkin's rewriting)."""
    u = M * W * S.t / 2
    fix = lambda x: x.replace(sp.atan, lambda arg: sp.atan(arg) + sp.pi * sp.floor(u / sp.pi + sp.Rational(1, 2)))  # noqa: E731
    return tuple(fix(x) for x in slider_laws())  # type: ignore[return-value]


def timed_cases(n: int, seed: int = 7) -> dict:
    """The four laws as the speed comparisons of two trees time them, each ``(expr, args, values)``
    with ``n`` points (arrays; the planet's and the slider's parameters as numbers, t an array):
    the AA ratio in teeth, the II differential in radii as the README compiles it (denominator
    r1 r3 - r2 r4), the AI planet acceleration w_x and the engine's slider acceleration a_s."""
    import numpy as np

    rng = np.random.default_rng(seed)
    w1, w4 = S.omega("1"), S.omega("4")
    radii = [S.radius(i) for i in "1234"]
    return {
        "AA ratio, teeth": (ratio_law(), [S.teeth(i) for i in "1234"], [rng.integers(20, 200, n) for _ in range(4)]),
        "II differential, radii": (
            schemes.two_row("II").speeds({"1": w1, "4": w4}).law("H").rhs, [w1, w4, *radii],
            [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(5, 10, n), rng.uniform(1, 2, n),
             rng.uniform(2.5, 4, n), rng.uniform(1, 2, n)]),
        "planet acceleration w_x": (planet_acceleration()[0], [w1, *radii, S.t], [2.0, 2.0, 1.5, 1.0, 4.5, rng.uniform(0, 10, n)]),
        "slider acceleration a_s": (
            slider_acceleration(), [E, L, M, W, THETA2, THETA0, S.t],
            [rng.uniform(0.05, 0.95, n), 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, rng.uniform(0, 10, n)]),
    }
