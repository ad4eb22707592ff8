"""The elliptical-gear drive: the carrier angle is branch-free, integrates the speed law, and inverts."""

import mpmath
import numpy as np
import pytest
import sympy as sp

from symkin import InputError
from symkin import symbols as S
from symkin.drives import AngleLaw, ConstantSpeed, EllipticalGears
from tests.support.zero import shown, zero

t = S.t
omega, e, m = sp.Symbol("omega", positive=True), sp.Symbol("e", nonnegative=True), sp.Symbol("m", positive=True)


def principal(drive):
    """The textbook form (2/m) atan(((1+e)/(1-e)) tan(m omega t/2)): right on the principal branch only."""
    E, M, W = drive.eccentricity, drive.order, drive.omega
    return 2 / M * sp.atan((1 + E) / (1 - E) * sp.tan(M * W * t / 2))


def test_derivative_of_the_angle_is_the_ratio_law_and_the_angle_starts_at_zero():
    d = EllipticalGears(omega, e, m)
    law = omega * (1 - e**2) / (1 - 2 * e * sp.cos(m * omega * t) + e**2)  # rolling radii r/(2a - r)
    assert zero(residual := d.angle(t).diff(t) - law), shown(residual)  # by values: a wrong law fails in seconds
    assert zero(residual := d.speed(t) - law), shown(residual)
    assert d.angle(t).subs(t, 0) == 0
    assert zero(residual := d.acceleration(t) - law.diff(t)), shown(residual)


def test_speed_ratio_comes_from_the_pitch_curves():
    d = EllipticalGears(1, sp.Rational(3, 10), 2)
    alpha = sp.Symbol("alpha", real=True)
    r = d.pitch_radius(alpha, semi_major=5)
    # rolling without slip at the pitch point, centres 2a = 10 apart: omega_in r = omega_out (10 - r)
    assert zero(residual := d.ratio(alpha) - (10 - r) / r), shown(residual)
    assert sp.simplify(d.pitch_radius(0, 5) - 5 * (1 + sp.Rational(3, 10))) == 0  # longest radius at alpha = 0


@pytest.mark.parametrize("ecc, order", [(0.3, 1), (0.6, 2), (0.9, 3), (0.5, 4)])
def test_angle_equals_the_numerical_integral_of_the_speed_over_several_input_turns(ecc, order):
    w = 0.8 * np.pi
    d = EllipticalGears(sp.Float(w), sp.Float(ecc), sp.Float(order))
    angle = sp.lambdify(t, d.angle(t), "numpy")
    mpmath.mp.dps = 30
    speed = lambda x: w * (1 - ecc**2) / (1 - 2 * ecc * mpmath.cos(order * w * x) + ecc**2)  # noqa: E731
    period = 2 * np.pi / (order * w)
    for end in np.linspace(0.1, 3 * 2 * np.pi / w, 7):  # up to three input turns
        # integrate piecewise, split at every quarter period (the speed peaks sharply for e near 1)
        nodes = [float(b) for b in np.arange(0.0, end, period / 4)] + [end]
        reference = float(mpmath.quad(speed, nodes))
        assert abs(angle(end) - reference) < 1e-10, (end, angle(end), reference)


@pytest.mark.parametrize("order", [1, 2, 3])
def test_angle_is_continuous_at_every_branch_point_of_the_principal_arctan(order):
    d = EllipticalGears(sp.Rational(4, 5) * sp.pi, sp.Rational(2, 5), order)
    derived = sp.lambdify(t, d.angle(t), "mpmath")
    textbook = sp.lambdify(t, principal(d), "mpmath")
    mpmath.mp.dps = 30
    h = mpmath.mpf("1e-15")
    for j in range(6):  # m omega t = (2j + 1) pi
        tj = (2 * j + 1) * mpmath.pi / (order * mpmath.mpf(4) / 5 * mpmath.pi)
        assert abs(derived(tj + h) - derived(tj - h)) < 1e-12
        # the principal form does jump there (so the test can fail), by 2 pi/m
        assert abs(textbook(tj + h) - textbook(tj - h) + 2 * mpmath.pi / order) < 1e-12
    # and the two agree on the principal branch
    for x in np.linspace(-0.5, 0.5, 5) * float(2 * np.pi / (order * 0.8 * np.pi)) * 0.99:
        assert abs(derived(mpmath.mpf(x)) - textbook(mpmath.mpf(x))) < 1e-20


def test_time_of_angle_inverts_the_angle():
    for d in (EllipticalGears(sp.Rational(3, 2), sp.Rational(7, 10), 3), ConstantSpeed(sp.Rational(5, 2))):
        angle = sp.lambdify(t, d.angle(t))
        for psi in np.linspace(0, 13, 9):
            assert angle(float(d.time_of_angle(psi))) == pytest.approx(psi, abs=1e-12)


def test_zero_eccentricity_is_a_constant_speed():
    d = EllipticalGears(omega, 0, m)
    assert d.angle(t) == ConstantSpeed(omega).angle(t)
    assert d.speed(t) == omega and d.acceleration(t) == 0


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(omega=1, eccentricity=1), r"\[0, 1\)"),
        (dict(omega=1, eccentricity=-0.1), r"\[0, 1\)"),
        (dict(omega=1, eccentricity=0.5, order=0), "order .* positive"),
        (dict(omega=1, eccentricity=0.5, order=-2), "order .* positive"),
        (dict(omega=0, eccentricity=0.5), "speed .* positive"),
        (dict(omega=1, eccentricity=t), "cannot depend on t"),
        (dict(omega="pi", eccentricity=0.5), r"the text 'pi'.*symkin.parse"),  # text is the parser's
        (dict(omega=sp.pi, eccentricity=0.5), None),
    ],
)
def test_bad_parameters_are_refused(kwargs, message):
    if message is None:
        assert EllipticalGears(**kwargs).omega == sp.pi
        return
    with pytest.raises(InputError, match=message):
        EllipticalGears(**kwargs)


def test_a_drive_without_closed_inverse_says_so():
    from symkin import UnsupportedError

    with pytest.raises(UnsupportedError):
        AngleLaw(t**2).time_of_angle(1)


def test_an_eccentricity_within_1e_300_of_1_is_decided_by_its_digits():
    # SymPy leaves sqrt(1 - 10**-300) < 1 undecided (a TypeError); 1 - e is 5e-301 and 1 + e - 2 is 5e-301 above
    tiny = sp.Rational(1, 10**300)
    assert EllipticalGears(1, sp.sqrt(1 - tiny)).eccentricity == sp.sqrt(1 - tiny)
    for e in (sp.sqrt(1 + tiny), -tiny, sp.Integer(1)):
        with pytest.raises(InputError, match=r"must lie in \[0, 1\)"):
            EllipticalGears(1, e)
