"""symkin.dynamics.torsional against K and M assembled here by hand (the rotational model of
Lin and Parker 1999: mesh deflections of base-circle displacements in the carrier's frame),
eigenvalues by scipy.linalg.eigh on those matrices, and a two-gear closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from scipy.linalg import eigh

from symkin.dynamics import natural_modes, torsional_model
from symkin.errors import InputError
from symkin.trains import read_train

SIMPLE = """
module = 2
meshes = [{ gears = ["s", "p"], stiffness = 5e8 }, { gears = ["p", "r"], stiffness = 6e8 }]
[links.S]
gears = { s = 24 }
inertia = 0.01
[links.C]
inertia = 0.05
[links.P]
carrier = "C"
count = 3
gears = { p = 24 }
inertia = 0.002
mass = 0.5
[links.R]
gears = { r = { teeth = 72, internal = true } }
inertia = 0.1
stiffness = 2e6
[states.low]
input = "S"
output = "C"
brakes = ["R"]
"""


def _by_hand(ring_free: bool) -> tuple[np.ndarray, np.ndarray]:
    """M and K of the sun, carrier, (ring,) three planets: base-circle deflections in the carrier's frame."""
    c = math.cos(math.radians(20))
    rs, rp, rr, a = 0.024, 0.024, 0.072, 0.048  # module 2 mm, in metres
    ksp, krp = 5e8, 6e8
    names = ["S", "C", *(["R"] if ring_free else []), "P1", "P2", "P3"]
    n = len(names)
    idx = {k: i for i, k in enumerate(names)}
    M = np.zeros((n, n))
    M[idx["S"], idx["S"]], M[idx["C"], idx["C"]] = 0.01, 0.05 + 3 * 0.5 * a**2
    if ring_free:
        M[idx["R"], idx["R"]] = 0.1
    K = np.zeros((n, n))
    for k in ("P1", "P2", "P3"):
        M[idx[k], idx[k]] = 0.002
        # sun-planet: r_s (th_s - th_c) + r_p (th_p - th_c); ring-planet: r_r (th_r - th_c) - r_p (th_p - th_c)
        d1 = np.zeros(n)
        d1[idx["S"]], d1[idx[k]], d1[idx["C"]] = rs, rp, -rs - rp
        d2 = np.zeros(n)
        d2[idx[k]], d2[idx["C"]] = -rp, rp - rr
        if ring_free:
            d2[idx["R"]] = rr
        K += ksp * c**2 * np.outer(d1, d1) + krp * c**2 * np.outer(d2, d2)
    if ring_free:
        K[idx["R"], idx["R"]] += 2e6
    return M, K


@pytest.mark.parametrize("state", [None, "low"])
def test_simple_planetary_frequencies_match_eigh_on_matrices_assembled_by_hand(state):
    modes = natural_modes(read_train(SIMPLE), state=state)
    M, K = _by_hand(ring_free=state is None)
    lam = eigh(K, M, eigvals_only=True)
    expected = np.sqrt(np.clip(lam, 0, None)) / (2 * math.pi)
    expected[expected < 1e-3] = 0
    assert modes.frequencies_hz == pytest.approx(sorted(expected), rel=1e-9, abs=1e-6)
    assert len(modes.frequencies_hz) == len(M)
    # Lin and Parker (1999): with equally spaced planets, the planet modes are of multiplicity N - 1 = 2
    f = np.array(modes.frequencies_hz)
    assert any(np.isclose(f[i], f[i + 1], rtol=1e-9) for i in range(len(f) - 1))


def test_mode_shapes_solve_the_eigenproblem():
    modes = natural_modes(read_train(SIMPLE))
    M = np.array(modes.model.mass_matrix.evalf().tolist(), dtype=float)
    K = np.array(modes.model.stiffness_matrix.evalf().tolist(), dtype=float)
    for f, shape in zip(modes.frequencies_hz, modes.shapes):
        v = np.array(shape)
        assert max(abs(v)) == pytest.approx(1)
        w2 = (2 * math.pi * f) ** 2
        assert np.linalg.norm(K @ v - w2 * M @ v) <= 1e-6 * np.linalg.norm(K) * np.linalg.norm(v)


def test_every_mesh_deflection_vanishes_in_rigid_motions():
    # the engine's rigid speeds, as turns, leave no potential energy (no brake: 2 free motions)
    from symkin.kinematics import solve_speeds

    train = read_train(SIMPLE)
    model = torsional_model(train)
    speeds = solve_speeds(train, {"S": sp.Rational(3), "R": sp.Rational(-2)})
    theta = sp.Matrix([speeds[n.split("_")[0]] for n in model.names])
    shaft = sp.Matrix([2 * 10**6 * speeds["R"] if n == "R" else 0 for n in model.names])
    assert (model.stiffness_matrix * theta - shaft).applyfunc(sp.simplify) == sp.zeros(len(theta), 1)


def test_two_gears_in_closed_form():
    # omega^2 = k cos^2(alpha) (r_a^2/J_a + r_b^2/J_b), by hand
    train = read_train("""
module = 1
meshes = [{ gears = ["a", "b"], stiffness = "k" }]
[links.A]
gears = { a = 20 }
inertia = "J_a"
[links.B]
carrier = "frame"
gears = { b = 30 }
inertia = "J_b"
""")
    model = torsional_model(train)
    k, Ja, Jb = sp.symbols("k J_a J_b", positive=True)
    lam = sp.Symbol("lambda")
    roots = sp.solve(model.characteristic_polynomial(lam), lam)
    ra, rb = sp.Rational(10, 1000), sp.Rational(15, 1000)
    hand = k * sp.cos(sp.pi / 9) ** 2 * (ra**2 / Ja + rb**2 / Jb)
    assert 0 in roots and any(sp.simplify(r - hand) == 0 for r in roots)
    assert natural_modes(train).frequencies_hz is None


def test_bad_models_are_one_line_errors():
    massless = SIMPLE.replace("inertia = 0.002", "inertia = 0")
    with pytest.raises(InputError, match="mass matrix is singular"):
        natural_modes(read_train(massless))


def test_planet_modes_have_lin_and_parkers_closed_form():
    # Lin and Parker (1999), the rotational planet modes: sun, carrier and ring still, the planets'
    # deflections summing to zero, multiplicity N - 1, at omega^2 = (k_sp + k_rp) c^2 r_p^2 / J_p
    modes = natural_modes(read_train(SIMPLE), state="low")
    omega2 = (5e8 + 6e8) * math.cos(math.radians(20)) ** 2 * 0.024**2 / 0.002
    f = omega2**0.5 / (2 * math.pi)
    planet = [k for k, x in enumerate(modes.frequencies_hz) if x == pytest.approx(f, rel=1e-9)]
    assert len(planet) == 2
    for k in planet:
        shape = dict(zip(modes.model.names, modes.shapes[k]))
        assert abs(shape["S"]) < 1e-9 and abs(shape["C"]) < 1e-9
        assert shape["P_1"] + shape["P_2"] + shape["P_3"] == pytest.approx(0, abs=1e-9)


@pytest.mark.parametrize("name", ["nested", "nested-one", "ravigneaux", "double-pinion", "bevel-epicyclic", "simpson"])
def test_every_copy_summed_gives_the_rigid_mass_matrix(name):
    # a second route to the rigid M: the torsional model's kinetic energy sums every planet copy at its
    # place (no cancellation rule); in a rigid motion each body turns by the engine's law
    from symkin import symbols as S
    from symkin.dynamics import equations_of_motion
    from symkin.trains import load_train
    from tests.support.dynamics import NESTED_ONE

    train = read_train(NESTED_ONE) if name == "nested-one" else load_train(name)
    eom = equations_of_motion(train)
    model = torsional_model(train)
    G = sp.Matrix([[sp.diff(eom.speeds[n.rsplit("_", 1)[0] if n not in eom.speeds else n], S.omega(c))
                    for c in eom.coordinates] for n in model.names])
    at_rest = eom.mass_matrix.subs({S.angle(c): 0 for c in eom.coordinates})  # the torsional model's place
    assert (G.T * model.mass_matrix * G - at_rest).applyfunc(sp.simplify) == sp.zeros(*eom.mass_matrix.shape)


KAHRAMAN = """
module = 2
meshes = [{ gears = ["s", "p"], stiffness = 4e8 }, { gears = ["p", "r"], stiffness = 6e8 }]
[links.S]
gears = { s = 30 }
inertia = 0.012
[links.C]
inertia = 0.3
[links.P]
carrier = "C"
count = 4
gears = { p = 21 }
inertia = 0.004
mass = 0
[links.R]
gears = { r = { teeth = 72, internal = true } }
inertia = 0.5
[states.low]
input = "S"
output = "C"
brakes = ["R"]
"""


@pytest.mark.parametrize("count", [3, 4, 5])
def test_fixed_ring_frequencies_have_kahramans_closed_form(count):
    # Kahraman, "Natural modes of planetary gear trains", J. Sound Vib. 173(1) (1994) 125-130: the
    # purely torsional model with the ring fixed, in the equivalent masses m = J / r^2 (r the base
    # radius; the carrier's at r_c = r_s + r_p) and the mesh deflections u_s + u_p - u_c and
    # u_p + u_c: a rigid mode, the planet modes omega^2 = (k_r + k_s) / m_p (multiplicity N - 1) and
    # the two roots of l1 lambda^2 + l2 lambda + l3 = 0.  The closed form as typed (citing the paper)
    # in gfsReboucas/Drivetrain-python, tests/test_kahraman_1994.py; the paper itself was not reachable.
    # Zero pressure angle: symkin's base radius is then the pitch radius, as in the closed form.
    train = read_train(KAHRAMAN.replace("count = 4", f"count = {count}"))
    modes = natural_modes(train, state="low", pressure_angle=0)
    rs, rp = 0.030, 0.021  # module 2 mm, 30 and 21 teeth, in metres
    ms, mp, mc = 0.012 / rs**2, 0.004 / rp**2, 0.3 / (rs + rp) ** 2
    ks, kr, n = 4e8, 6e8, count
    l1 = mp * mc * ms
    l2 = -(n * ks * mp * mc + (kr + ks) * mc * ms + n * (kr + ks) * mp * ms)
    l3 = n * kr * ks * (n * mp + mc + 4 * ms)
    root = math.sqrt(l2**2 - 4 * l1 * l3)
    lam = [0.0, *[(kr + ks) / mp] * (n - 1), (-l2 - root) / (2 * l1), (-l2 + root) / (2 * l1)]
    expected = sorted(math.sqrt(x) / (2 * math.pi) for x in lam)
    assert modes.model.names == ("S", "C", *(f"P_{k + 1}" for k in range(n)))
    assert modes.frequencies_hz == pytest.approx(expected, rel=1e-12, abs=1e-9)


def _two_gears(form_a: str, form_b: str, mesh: str = "") -> str:
    return f"""
module = 1
meshes = [{{ gears = ["a", "b"], stiffness = 1e8{mesh} }}]
[links.A]
gears = {{ a = {{ teeth = 20{form_a} }} }}
inertia = 0.01
[links.B]
carrier = "frame"
gears = {{ b = {{ teeth = 40{form_b} }} }}
inertia = 0.04
"""


def _two_gear_stiffness(alpha_degrees: float) -> np.ndarray:
    """K of two gears on fixed axes by hand: k [r_bA^2, r_bA r_bB; r_bA r_bB, r_bB^2], with the
    base radii m z cos(alpha) / 2 (ISO 21771) in metres; the sign of the coupling is that of
    external gears turning opposite ways."""
    rb = [z / 2 * math.cos(math.radians(alpha_degrees)) / 1000 for z in (20, 40)]
    return 1e8 * np.array([[rb[0] ** 2, rb[0] * rb[1]], [rb[0] * rb[1], rb[1] ** 2]])


def test_the_train_files_pressure_angle_is_the_models():
    # written in the file: the mesh's base circles are cos 25 degrees of its pitch circles
    model = torsional_model(read_train(_two_gears(", pressure_angle = 25", ", pressure_angle = 25")))
    K = np.array(model.stiffness_matrix.evalf(30).tolist(), dtype=float)
    assert np.allclose(K, _two_gear_stiffness(25), rtol=1e-14, atol=0)
    # none written: 20 degrees, the basic rack's; one given in Python: it, for every mesh
    plain = read_train(_two_gears("", ""))
    K20 = np.array(torsional_model(plain).stiffness_matrix.evalf(30).tolist(), dtype=float)
    assert np.allclose(K20, _two_gear_stiffness(20), rtol=1e-14, atol=0)
    given = torsional_model(plain, pressure_angle=sp.pi * 25 / 180)
    assert given.stiffness_matrix == model.stiffness_matrix


def test_a_shifted_mesh_keeps_its_base_circles():
    # a working centre distance of 31 mm for a reference 30: the working circles are 31/30 of the
    # pitch circles, the base circles stay m z cos(alpha) / 2, so K is that of the unshifted pair
    model = torsional_model(read_train(_two_gears("", "", ", centre_distance = 31")))
    K = np.array(model.stiffness_matrix.evalf(30).tolist(), dtype=float)
    assert np.allclose(K, _two_gear_stiffness(20), rtol=1e-14, atol=0)


def test_gears_of_one_mesh_with_different_pressure_angles_are_refused():
    with pytest.raises(InputError, match=r"gears a and b mesh but have different pressure angles \(25 and 20 degrees"):
        torsional_model(read_train(_two_gears(", pressure_angle = 25", "")))


def test_gears_given_by_working_radii_keep_the_base_circles_of_their_teeth():
    # radii 31/3 and 62/3 mm given directly for 20 and 40 teeth of module 1 (a mesh at 31 mm
    # whose reference is 30): the base circles are m z cos(alpha) / 2 all the same
    train = read_train("""
module = 1
meshes = [{ gears = ["a", "b"], stiffness = 1e8 }]
[links.A]
gears = { a = { teeth = 20, radius = "31/3" } }
inertia = 0.01
[links.B]
carrier = "frame"
gears = { b = { teeth = 40, radius = "62/3" } }
inertia = 0.04
""")
    K = np.array(torsional_model(train).stiffness_matrix.evalf(30).tolist(), dtype=float)
    assert np.allclose(K, _two_gear_stiffness(20), rtol=1e-14, atol=0)


def test_a_centre_distance_nearer_than_the_base_circles_is_refused():
    # 20 and 40 teeth, module 1: the base circles' distance is 30 cos 20 deg = 28.19 mm
    with pytest.raises(InputError, match="mesh a-b works at 28, nearer than its base circles allow"):
        torsional_model(read_train(_two_gears("", "", ", centre_distance = 28")))
