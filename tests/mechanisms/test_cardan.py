"""The Cardan slider: vector loop against superposition, the line conditions, paths, drives, numbers."""

import numpy as np
import pytest
import sympy as sp

from symkin import InputError, ModelError
from symkin import symbols as S
from symkin.drives import AngleLaw, ConstantSpeed, EllipticalGears
from symkin.mechanisms import cardan
from symkin.mechanisms.cardan import CardanSlider, l, theta_2, theta_10, theta_H0
from tests.support.zero import zero

t = S.t
w = S.omega("H")
z1, z3 = S.teeth("1"), S.teeth("3")
l1 = sp.Symbol("l_1", positive=True)


def test_vector_loop_and_superposition_give_the_same_pin_for_any_ratio_pin_and_installation():
    """General ratio z3/z1, pin anywhere on the planet, any angles: two independent routes."""
    slider = CardanSlider.build(l, drive=w, teeth=(z1, z3), pin_radius=l1, pin_angle=theta_10,
                                guide_angle=theta_2, carrier_angle=theta_H0)
    loop_route = slider.pin_position
    particle = slider.pin.position
    assert zero(loop_route[0] - particle[0]) and zero(loop_route[1] - particle[1])
    # the displacement is the particle's component along the guide
    along = particle[0] * sp.cos(theta_2) + particle[1] * sp.sin(theta_2)
    assert zero(slider.displacement - along)


@pytest.mark.parametrize("drive", [ConstantSpeed(w), EllipticalGears(sp.Symbol("omega", positive=True), sp.Rational(2, 5), 3)])
def test_slider_velocity_and_acceleration_agree_with_the_particle_route(drive):
    """v, a by differentiating the loop's s against eqs. (5)-(6) for the pin particle, on the guide."""
    slider = CardanSlider.build(l, drive=drive, guide_angle=sp.pi / 5, carrier_angle=sp.Rational(1, 3))
    assert slider.path().kind == "line"
    u = sp.Matrix([sp.cos(sp.pi / 5), sp.sin(sp.pi / 5)])
    v_particle = (slider.pin.velocity.T * u)[0]
    a_particle = (slider.pin.acceleration.T * u)[0]
    values = {l: 0.02, sp.Symbol("omega", positive=True): 2.5, w: 2.5}
    f = sp.lambdify(t, [e.subs(values) for e in (slider.velocity - v_particle, slider.acceleration - a_particle, slider.deviation)])
    for ti in np.linspace(0, 7, 29):
        assert np.allclose(f(ti), 0, atol=1e-12)


def test_elliptical_v_and_a_are_time_derivatives_by_finite_differences():
    drive = EllipticalGears(sp.Rational(4, 5) * sp.pi, sp.Rational(1, 2), 2)
    slider = CardanSlider.build(sp.Rational(1, 50), drive=drive, carrier_angle=sp.pi / 3)
    h = 1e-5
    ts = np.linspace(0.05, 5, 40)
    d = slider.evaluate(ts)
    plus, minus = slider.evaluate(ts + h), slider.evaluate(ts - h)
    assert np.allclose((plus["s"] - minus["s"]) / (2 * h), d["v"], rtol=1e-7, atol=1e-9)
    assert np.allclose((plus["v"] - minus["v"]) / (2 * h), d["a"], rtol=1e-6, atol=1e-7)
    # and the paper's chain-rule form v = 2 l omega_H(t) sin(theta_2 - theta_H(t)), with the ratio-law speed
    chain = sp.lambdify(t, 2 * slider.arm * drive.speed(t) * sp.sin(-slider.carrier_angle))
    assert np.allclose(chain(ts), d["v"], atol=1e-12)


def test_zero_eccentricity_recovers_the_constant_speed_laws():
    omega, e = sp.Symbol("omega", positive=True), sp.Symbol("e", nonnegative=True)
    kw = dict(guide_angle=theta_2, carrier_angle=theta_H0)
    elliptical = CardanSlider.build(l, drive=EllipticalGears(omega, e, 2), **kw)
    uniform = CardanSlider.build(l, drive=ConstantSpeed(omega), **kw)
    point = {omega: 2, l: 1, theta_2: sp.Rational(1, 5), theta_H0: sp.Rational(1, 7), t: sp.Rational(1, 3)}
    for a, b in zip(elliptical.laws(), uniform.laws()):
        assert zero(a.rhs.subs(e, 0) - b.rhs)
        assert abs(sp.N((a.rhs - b.rhs).subs(e, sp.Rational(1, 10)).subs(point))) > 1e-3  # not vacuous


def test_line_conditions_are_derived():
    c = cardan.line_conditions()
    r1, r3 = S.radius("1"), S.radius("3")
    assert c.ratio == sp.Eq(r3, 2 * r1)
    assert c.lengths.rhs == sp.Symbol("l_H", positive=True)
    assert sp.simplify(c.installation.rhs - 2 * (theta_2 - theta_H0)) == 0
    assert {str(eq.rhs) for eq, _ in c.excluded} == {"0", "r_1"}
    assert zero(c.deviation.subs(c.substitutions()))


def test_each_line_condition_is_necessary_a_counter_example_without_each():
    base = dict(guide_angle=0, carrier_angle=0, drive=w)
    good = CardanSlider.build(l, **base)
    assert good.deviation == 0 and good.path().kind == "line"
    counter = {
        "ratio": CardanSlider.build(l, teeth=(20, 60), pin_radius=l, **base),  # l_1 = l_H, installed as derived
        "lengths": CardanSlider.build(l, pin_radius=l / 2, **base),
        "installation": CardanSlider.build(l, pin_angle=sp.pi, **base),  # allowed by the paper's (13)
    }
    for broken, slider in counter.items():
        met = slider.conditions_met()
        assert [k for k, v in met.items() if not v] == [broken]
        value = sp.N(slider.deviation.subs({l: 1, w: 1, t: sp.Rational(1, 3)}))
        assert abs(value) > 0.1, broken
    assert counter["ratio"].path().kind == "hypotrochoid"
    assert counter["lengths"].path().kind == "ellipse"
    assert counter["installation"].path().kind == "line off the guide"


def test_true_paths_off_the_line():
    ellipse = CardanSlider.build(3, drive=1, pin_radius=1)
    x, y = ellipse.pin_position
    assert zero((x / 4) ** 2 + (y / 2) ** 2 - 1)  # semi-axes l_H + l_1 and l_H - l_1
    assert ellipse.path().parameters["semi_major"] == 4 and ellipse.path().parameters["semi_minor"] == 2
    hypo = CardanSlider.build(2, drive=1, teeth=(20, 60))  # ring 3, planet 1, arm 2: deltoid
    path = hypo.path()
    assert path.kind == "hypocycloid" and "3 cusps" in path.description and not path.on_guide
    x, y = hypo.pin_position  # deltoid: x = 2 cos t + cos 2t, y = 2 sin t - sin 2t
    assert zero(x - (2 * sp.cos(t) + sp.cos(2 * t))) and zero(y - (2 * sp.sin(t) - sp.sin(2 * t)))
    assert "closing after 2 carrier turns" in CardanSlider.build(1, drive=1, teeth=(20, 50)).path().description
    wrong = CardanSlider.build(1, drive=1, pin_angle=sp.pi / 2)
    assert wrong.path().kind == "line off the guide" and "pi/4" in wrong.path().description


def test_symbolic_parameters_leave_the_path_undecided_and_say_what_decides_it():
    path = CardanSlider.build(l, teeth=(z1, z3)).path()
    assert path.kind == "undecided" and "ratio and lengths conditions" in path.description and not path.on_guide
    assert "installation condition" in CardanSlider.build(l, pin_angle=sp.Symbol("x")).path().description


def test_stroke_times():
    uniform = CardanSlider.build(sp.Rational(1, 50), drive=sp.Rational(4, 5) * sp.pi)
    st = uniform.stroke_times()
    assert st.forward == pytest.approx(1.25) and st.back == pytest.approx(1.25) and st.ratio == pytest.approx(1)
    drive = EllipticalGears(sp.Rational(4, 5) * sp.pi, sp.Rational(2, 5), 1)
    quick = CardanSlider.build(sp.Rational(1, 50), drive=drive, carrier_angle=sp.pi / 2)
    closed = quick.stroke_times()
    assert closed.forward + closed.back == pytest.approx(2.5)
    # same carrier law, inverted numerically: the closed-form inverse agrees
    numeric = CardanSlider.build(sp.Rational(1, 50), drive=AngleLaw(drive.angle(t)), carrier_angle=sp.pi / 2).stroke_times()
    assert numeric.forward == pytest.approx(closed.forward, abs=1e-10) and numeric.back == pytest.approx(closed.back, abs=1e-10)
    # with the carrier fastest mid-stroke the forward stroke (v > 0) is the slow one here: a quick return
    t_s = np.linspace(0, 2.5, 20001)
    v = quick.evaluate(t_s)["v"]
    assert closed.forward == pytest.approx(np.mean(v > 0) * 2.5, abs=1e-3)
    assert closed.ratio > 2.5
    even = CardanSlider.build(1, drive=EllipticalGears(1, sp.Rational(1, 2), 2), carrier_angle=sp.pi / 3).stroke_times()
    assert even.ratio == pytest.approx(1)  # an even order has no quick return
    with pytest.raises(InputError, match="no strokes"):
        CardanSlider.build(1, drive=1, pin_radius=sp.Rational(1, 2)).stroke_times()


def test_period_follows_the_drive():
    assert CardanSlider.build(1, drive=sp.Rational(4, 5) * sp.pi).period() == sp.Rational(5, 2)
    assert CardanSlider.build(1, drive=EllipticalGears(2, sp.Rational(1, 3), 3)).period() == sp.pi
    # a non-whole order has no closed pitch curve: refused (cardan --order 1.5 ran, its motion not periodic)
    with pytest.raises(InputError, match="whole number"):
        EllipticalGears(2, sp.Rational(1, 3), sp.Rational(1, 2))
    with pytest.raises(InputError, match="whole number"):  # (exactly: as a float it would look whole)
        EllipticalGears(2, sp.Rational(1, 3), sp.Integer(10) ** 20 + sp.Rational(1, 2))
    assert CardanSlider.build(1, drive=AngleLaw(t**2)).period() is None


def test_evaluate_checks_its_grid_and_values():
    slider = CardanSlider.build(l, drive=1)
    with pytest.raises(InputError, match="give values for l"):
        slider.evaluate([0, 1])
    good = CardanSlider.build(1, drive=1)
    with pytest.raises(InputError, match="empty"):
        good.evaluate([])
    with pytest.raises(InputError, match="increasing"):
        good.evaluate([0, 2, 1])
    out = good.evaluate([0.0])
    assert out["s"][0] == pytest.approx(2) and out["v"][0] == pytest.approx(0)


def test_bad_geometry():
    with pytest.raises(ModelError, match="more teeth"):
        CardanSlider.build(1, teeth=(40, 20))
    with pytest.raises(ModelError, match="positive"):
        CardanSlider.build(-1)
    with pytest.raises(ModelError, match="positive"):
        CardanSlider.build(1, pin_radius=0)


def test_laws_are_fast_to_derive_and_compile():
    import time

    start = time.process_time()  # CPU time of this process: other jobs on a shared machine do not count
    slider = CardanSlider.build(sp.Rational(1, 50), drive=EllipticalGears(sp.Rational(4, 5) * sp.pi, sp.Rational(2, 5), 2))
    slider.evaluate(np.linspace(0, 2.5, 1000))
    assert time.process_time() - start < 2.0  # typically ~0.1 s


def test_a_number_far_from_whole_turns_is_decided_without_simplifying_it():
    # a carrier angle nested 30 functions deep: simplifying the installation condition would use up
    # its whole budget; 50 digits say at once that the pin angle 0 is not a whole number of turns
    # from the one the guide needs, so the pin draws a line off the guide
    import time

    import mpmath

    nested = sp.sympify("sin(" * 30 + "1" + ")" * 30)
    slider = CardanSlider.build(1, drive=1, pin_angle=0, carrier_angle=nested)
    start = time.process_time()
    assert slider.conditions_met()["installation"] is False
    assert time.process_time() - start < 1.0  # (the simplification budget is 2 s)
    # independently: the pin angle the guide needs is 2 theta_2 - 2 theta_H0 (Luo 2018), here -2 x with x the
    # nested sine; the pin angle 0 is x/pi turns from it, far from a whole number
    with mpmath.workdps(30):
        x = mpmath.mpf(1)
        for _ in range(30):
            x = mpmath.sin(x)
        turns = x / mpmath.pi
    assert abs(turns - round(turns)) > 0.01
    # a whole number of turns in disguise is still recognised (by simplification)
    exact = CardanSlider.build(1, drive=1, pin_angle=4 * sp.pi * (sp.sin(1) ** 2 + sp.cos(1) ** 2))
    assert exact.conditions_met()["installation"] is True


def test_a_pin_radius_far_from_the_arm_is_decided_without_simplifying_it_and_its_description_is_quick():
    # a pin radius nested 30 functions deep: 50 digits say at once that it is off the pitch circle (the
    # lengths condition and the JSON's pin_on_pitch_circle), and the texts' tidier angles get a short budget
    import time
    import warnings

    import mpmath

    nested = sp.sympify("sin(" * 30 + "1" + ")" * 30)
    slider = CardanSlider.build(sp.Rational(1, 50), teeth=(20, 40), drive=1, pin_radius=nested)
    start = time.process_time()
    assert slider.conditions_met()["lengths"] is False
    assert time.process_time() - start < 1.0  # (the simplification budget is 2 s)
    x = mpmath.mpf(1)
    with mpmath.workdps(30):
        for _ in range(30):
            x = mpmath.sin(x)
        assert abs(x - mpmath.mpf(1) / 50) > 0.1  # independently: the pin is far off the pitch circle
    on_circle = sp.Rational(1, 50) * (sp.sin(1) ** 2 + sp.cos(1) ** 2)  # on it, in disguise: still recognised
    assert CardanSlider.build(sp.Rational(1, 50), teeth=(20, 40), drive=1, pin_radius=on_circle).conditions_met()["lengths"] is True
    # a carrier angle as deep: the path's description tidies two angles for its text, within 0.5 s each
    slider = CardanSlider.build(1, drive=1, pin_angle=0, carrier_angle=nested)
    start = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (a budget used up says so)
        path = slider.path()
    assert path.kind == "line off the guide"
    assert time.process_time() - start < 2.5  # it took two budgets of 2 s before
