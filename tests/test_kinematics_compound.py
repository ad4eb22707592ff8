"""Trains beyond the paper's schemes: planet-planet meshes, ordinary trains, three DOF."""

import sympy as sp

from symkin import Gear, Link, Mechanism, schemes
from symkin import symbols as S

z1, za, zb, z4 = sp.symbols("z_1 z_a z_b z_4", positive=True, integer=True)


def double_planet(teeth=(z1, za, zb, z4)):
    """Sun 1, planets a and b on one carrier (a meshes the sun and b, b meshes the ring 4)."""
    g1, ga, gb, g4 = (Gear.from_teeth(n, z, internal=(n == "4")) for n, z in zip("1ab4", teeth))
    return Mechanism(
        links=[
            Link.central("1", g1),
            Link.planet("a", ga, carrier="H"),
            Link.planet("b", gb, carrier="H", position_angle=sp.pi / 5),
            Link.central("H"),
            Link.central("4", g4),
        ],
        meshes=[("1", "a"), ("a", "b"), ("b", "4")],
        name="double planet",
    )


def test_double_planet_train_reverses_the_sign_of_the_willis_ratio():
    m = double_planet()
    assert m.dof == 2
    # independent route: the carrier-fixed train 1 -> a -> b -> 4 is an ordinary train with an
    # idler: omega_1/omega_4 = (-z_a/z_1)(-z_b/z_a)(+z_4/z_b) = +z_4/z_1
    assert sp.cancel(m.ratio("1", "4", fixed="H").rhs - z4 / z1) == 0
    assert sp.cancel(m.ratio("1", "H", fixed="4").rhs - (1 - z4 / z1)) == 0


def test_ordinary_train_on_the_frame():
    # gears on fixed axes: a planet carried by the frame is an idler on a fixed axis
    m = Mechanism(
        links=[Link.central("1", Gear("1", 2)), Link.planet("i", Gear("i", 7), carrier="0"), Link.central("4", Gear("4", 5))],
        meshes=[("1", "i"), ("i", "4")],
    )
    assert m.dof == 1
    assert m.ratio("1", "4").rhs == sp.Rational(5, 2)  # 5/2 with no sign change: two external meshes
    assert m.speeds({"1": 7})["i"] == -2


def test_two_stage_AA_reducer_ratio_is_the_product():
    aa = schemes.two_row("AA", teeth=(54, 45, 44, 55)).ratio("1", "H", fixed="4").rhs
    g = {n: Gear.from_teeth(n, z, internal=False) for n, z in
         [("1", 54), ("2", 45), ("3", 44), ("4", 55), ("5", 54), ("6", 45), ("7", 44), ("8", 55)]}
    m = Mechanism(
        links=[
            Link.central("1", g["1"]), Link.planet("23", g["2"], g["3"], carrier="H"), Link.central("H", g["5"]),
            Link.planet("67", g["6"], g["7"], carrier="K"), Link.central("K"), Link.frame(g["4"], g["8"]),
        ],
        meshes=[("1", "2"), ("3", "4"), ("5", "6"), ("7", "8")],
    )
    assert m.dof == 1
    assert m.ratio("1", "K").rhs == aa**2 == sp.Rational(1, 576)


def test_three_degrees_of_freedom_need_three_inputs():
    m = double_planet((20, 10, 12, 60))
    w = S.omega
    full = Mechanism(links=m.links + (Link.central("X", Gear("x", 3)),), meshes=m.meshes)
    assert full.dof == 3
    speeds = full.speeds({"1": w("1"), "4": w("4"), "X": 5})
    assert speeds["X"] == 5
