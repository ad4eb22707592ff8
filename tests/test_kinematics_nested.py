"""Nested carriers: a planet that carries planets, against independent references.

Speeds against Willis' formula applied by hand in each carrier's frame; particle position,
velocity and acceleration of a tool on a planet of a planet against a model built with
sympy.physics.mechanics (frames turning about N.z, points located on them, v and a by
differentiation in N), at random rational tooth numbers and speeds.
"""

from __future__ import annotations

import random

import pytest
import sympy as sp
from sympy.physics import mechanics as me

from symkin import symbols as S
from symkin.errors import ModelError
from symkin.model import Gear, Link, Mechanism
from symkin.trains import load_train


def polisher(z_s0a, z_p, z_s0b, z_g1, z_g2, z_q, angle_q=None):
    """The two-level train of the ready-made file 'nested', with any tooth numbers (module 1)."""
    return Mechanism(
        links=(
            Link.frame(Gear.from_teeth("s0a", z_s0a, module=1), Gear.from_teeth("s0b", z_s0b, module=1)),
            Link.central("C"),
            Link.planet("P", Gear.from_teeth("p", z_p, module=1), carrier="C"),
            Link.planet("G", Gear.from_teeth("g1", z_g1, module=1), Gear.from_teeth("g2", z_g2, module=1), carrier="P", arm=0),
            Link.planet("Q", Gear.from_teeth("q", z_q, module=1), carrier="P", position_angle=angle_q),
        ),
        meshes=(("s0a", "p"), ("s0b", "g1"), ("g2", "q")),
    )


def willis(z_s0a, z_p, z_s0b, z_g1, z_g2, z_q, w_c):
    """By hand: p rolls on the fixed s0a in C's frame, g1 on the fixed s0b in C's frame, q on
    g2 in P's frame (external meshes: relative speeds opposite, inverse to the teeth)."""
    w_p = w_c - sp.Rational(z_s0a, z_p) * (0 - w_c)
    w_g = w_c - sp.Rational(z_s0b, z_g1) * (0 - w_c)
    w_q = w_p - sp.Rational(z_g2, z_q) * (w_g - w_p)
    return w_p, w_g, w_q


def test_the_ready_made_nested_train_by_hand():
    train = load_train("nested")
    w = S.omega("C")
    w_p, w_g, w_q = willis(60, 30, 66, 24, 18, 12, w)
    speeds = train.speeds({"C": w})
    assert (speeds["P"], speeds["G"], speeds["Q"]) == (w_p, w_g, w_q) == (3 * w, sp.Rational(15, 4) * w, sp.Rational(15, 8) * w)
    assert train.shift("drive").ratio.rhs == sp.Rational(8, 15)
    assert (train.arm("P"), train.arm("Q"), train.axis_of("G")) == (45, 15, "P")
    assert train.axis_position("Q") == (60, 0)


@pytest.mark.parametrize("seed", range(4))
def test_a_tool_on_a_planet_of_a_planet_against_sympy_mechanics(seed):
    rng = random.Random(seed)
    z_p, z_q, z_g2 = rng.randint(15, 40), rng.randint(10, 25), rng.randint(12, 30)
    z_s0a = rng.randint(40, 90)
    z_g1 = rng.randint(12, 40)
    z_s0b = z_s0a + z_p - z_g1  # the second sun puts g1 on the head's axis
    w_c = sp.Rational(rng.randint(1, 9), rng.randint(2, 7)) * rng.choice((1, -1))
    angle_q = sp.Rational(rng.randint(0, 60), 10)
    mech = polisher(z_s0a, z_p, z_s0b, z_g1, z_g2, z_q, angle_q)
    a, b = sp.Rational(rng.randint(-9, 9), 3), sp.Rational(rng.randint(-9, 9), 4)
    ours = mech.motion({"C": w_c}).particle("Q", (a, b), relative_to="pole")

    w_p, _, w_q = willis(z_s0a, z_p, z_s0b, z_g1, z_g2, z_q, w_c)
    arm_p, arm_q = sp.Rational(z_s0a + z_p, 2), sp.Rational(z_g2 + z_q, 2)
    t = me.dynamicsymbols._t
    N = me.ReferenceFrame("N")
    C = N.orientnew("C", "Axis", [w_c * t, N.z])
    P = N.orientnew("P", "Axis", [w_p * t, N.z])
    Q = N.orientnew("Q", "Axis", [w_q * t, N.z])
    O = me.Point("O")
    head = O.locatenew("A_P", arm_p * C.x)
    tool_axis = head.locatenew("A_Q", arm_q * (sp.cos(angle_q) * P.x + sp.sin(angle_q) * P.y))
    point = tool_axis.locatenew("X", a * Q.x + b * Q.y)
    r = point.pos_from(O)
    v = r.dt(N)
    acc = v.dt(N)
    for tt in (0, sp.Rational(3, 7), sp.Rational(29, 5)):
        for law, ref in ((ours.position, r), (ours.velocity, v), (ours.acceleration, acc)):
            for k, e in enumerate((N.x, N.y)):
                got, want = sp.N(law[k].subs(S.t, tt), 30), sp.N(ref.dot(e).subs(t, tt), 30)
                assert abs(got - want) < 1e-20 * (1 + abs(want)), (seed, tt, k, got, want)


def test_nested_carriers_refused_where_they_cannot_work():
    with pytest.raises(ModelError, match="carrier cycle: A -> B -> A"):
        Mechanism((Link.central("C"), Link.planet("A", Gear("a", 1), carrier="B", arm=2),
                   Link.planet("B", Gear("b", 1), carrier="A", arm=2)), ())
    # a planet of a planet cannot mesh a gear on the main axis: no link holds both axes
    with pytest.raises(ModelError, match="cannot stay in mesh: no link holds both their axes"):
        Mechanism((Link.central("S", Gear("s", 10)), Link.central("C"), Link.planet("P", Gear("p", 5), carrier="C"),
                   Link.planet("Q", Gear("q", 2), carrier="P", arm=4)), (("s", "p"), ("s", "q")))
