"""Particle kinematics: eqs. (4)-(6) against differentiation, the Cardan line, moving frames."""

import numpy as np
import pytest
import sympy as sp

from symkin import FrameMotion, Gear, InputError, Link, Mechanism, drives, schemes
from symkin import symbols as S
from tests.support.zero import shown, zero

t = S.t


@pytest.mark.parametrize("kind", ["AI1", "AI", "AA", "II"])
def test_velocity_and_acceleration_are_time_derivatives_with_varying_inputs(kind):
    m = schemes.scheme(kind)
    theta1 = sp.Function("theta_1")(t)
    theta4 = sp.Function("theta_4")(t)
    motion = m.motion({"1": drives.AngleLaw(theta1), "4": drives.AngleLaw(theta4)})
    planet = "2" if kind == "AI1" else "23"
    a, b = sp.symbols("a b", real=True)
    p = motion.particle(planet, (a, b))
    # decided by values (a wrong law fails in seconds); simplified only to print it
    assert zero(residual := p.position.diff(t) - p.velocity), shown(residual)
    assert zero(residual := p.velocity.diff(t) - p.acceleration), shown(residual)
    # and the check is not vacuous: the velocity is not the position's derivative plus anything else
    assert not zero(p.position.diff(t) - p.velocity - sp.ImmutableMatrix([theta1.diff(t), 0]))


def test_superposed_frame_motion_drill_head_on_a_manipulator():
    m = schemes.two_row("AI")
    frame = FrameMotion(x=sp.cos(t) ** 2, y=t**3, angle=sp.sin(2 * t))
    motion = m.motion({"1": drives.SpeedLaw(1 + t), "4": 0}, frame=frame)
    p = motion.particle("23", (S.radius("1") + 2 * S.radius("2"), 0))
    assert zero(p.position.diff(t) - p.velocity)
    assert zero(p.velocity.diff(t) - p.acceleration)
    # a central-link particle at the main axis follows the frame's axis exactly
    axis = motion.particle("1", (1, 0), relative_to="pole")
    assert zero(axis.position.subs(t, 0) - sp.ImmutableMatrix([2, 0]))


def cardan(radius=sp.Symbol("r", positive=True)):
    """A planet of radius r rolling inside a fixed ring of radius 2r (no sun)."""
    return Mechanism(
        links=[Link.frame(Gear("3", 2 * radius, internal=True)), Link.central("H"), Link.planet("1", Gear("1", radius))],
        meshes=[("1", "3")],
    )


def test_point_on_pitch_circle_of_planet_in_ring_of_twice_its_size_moves_on_a_line():
    r = sp.Symbol("r", positive=True)
    alpha = sp.Symbol("alpha", real=True)
    motion = cardan(r).motion({"H": 1})
    # any point of the planet's pitch circle, at angle alpha around the planet axis (r, 0)
    p = motion.particle("1", (r * sp.cos(alpha), r * sp.sin(alpha)), relative_to="pole")
    x, y = p.position
    direction = (sp.cos(alpha / 2), sp.sin(alpha / 2))  # the line through the centre
    assert sp.simplify(sp.expand_trig(x * direction[1] - y * direction[0])) == 0
    # it does move: the stroke is 4r
    assert sp.simplify(x.subs({alpha: 0, t: 0}) - x.subs({alpha: 0, t: sp.pi})) == 4 * r


def test_point_off_the_pitch_circle_traces_an_ellipse_not_a_line():
    r, rho = 3, 1
    motion = cardan(r).motion({"H": 1})
    p = motion.particle("1", (rho, 0), relative_to="pole")
    x, y = p.position
    assert sp.simplify((x / (r + rho)) ** 2 + (y / (r - rho)) ** 2 - 1) == 0
    assert sp.simplify(y) != 0


def test_trajectory_samples_the_symbolic_position():
    m = schemes.single_row_AI(radii=(1, 1, 3))
    p = m.motion({"4": 0, "H": 2}).particle("2", (1, 0))
    ts, xs, ys = p.trajectory(3.0, samples=7)
    f = sp.lambdify(t, list(p.position))
    for ti, xi, yi in zip(ts, xs, ys):
        assert np.allclose(f(ti), [xi, yi])


def test_trajectory_asks_for_missing_values():
    p = schemes.two_row("AI").motion({"1": 1, "4": 0}).particle("23", (1, 0))
    with pytest.raises(InputError, match="give values for r_1, r_2, r_3, r_4"):
        p.trajectory(1.0)
    with pytest.raises(InputError, match="increasing"):
        p.trajectory(-1.0)


def test_motion_needs_exactly_dof_inputs():
    from symkin import UnderdeterminedError

    with pytest.raises(UnderdeterminedError):
        schemes.two_row("AI").motion({"1": 1})


def test_constant_inputs_give_uniform_rotation():
    m = schemes.two_row("AA", teeth=(54, 45, 44, 55))
    motion = m.motion({"1": 3, "4": 0})
    assert motion.angle("H") == 3 * t * sp.Rational(-1, 24) ** -1 / 1 or motion.angle("H") == -72 * t
    assert motion.omega("H") == -72 and motion.epsilon("H") == 0


def test_the_papers_letters_and_the_usual_ones_name_the_same_laws():
    from symkin import Study

    mech = schemes.single_row_AI(teeth=(20, 30, 80), module=1)
    p = mech.motion({"4": 0, "H": 1}).particle("2", (15, 0))
    assert p.w is p.a is p.acceleration and p.V is p.v is p.velocity
    # the acceleration is the second derivative of the position, whatever it is called
    assert sp.simplify(p.a - p.position.diff(S.t, 2)) == sp.zeros(2, 1)
    by_letter = Study(mech, particles=[("2", (15, 0), ("w", "v"))], inputs={"4": 0, "H": 1}).laws
    by_word = Study(mech, particles=[("2", (15, 0), ("acceleration", "velocity"))], inputs={"4": 0, "H": 1}).laws
    assert [law.rhs for law in by_letter] == [law.rhs for law in by_word]


def test_the_planet_answers_to_2_in_single_and_two_row_schemes():
    # single-row: link 2 is the planet; two-row: link 23 carries rims 2 and 3 (the paper's numbering),
    # and a link is also found by the name of any gear it carries
    one, two = schemes.single_row_AI(teeth=(20, 30, 80)), schemes.two_row("AI", teeth=(20, 30, 20, 70))
    assert one.link("2").name == "2" and two.link("2").name == two.link("3").name == "23"
    # Willis: (w2 - wH)/(w1 - wH) = -z1/z2 = -2/3 with wH = z1/(z1 + z4) = 1/5, so w2 = 1/5 - 8/15 = -1/3
    assert one.speeds({"1": 1, "4": 0})["2"] == sp.Rational(-1, 3)
