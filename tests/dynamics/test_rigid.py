"""symkin.dynamics.rigid against independent routes: the kinetic energy worked by hand, models
written here with sympy.physics.mechanics (frames, points, rolling constraints typed by hand),
a finite difference of the kinetic energy, and the energy balance of a simulation."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from sympy.physics import mechanics as me

from symkin import symbols as S
from symkin.dynamics import equations_of_motion
from symkin.errors import InputError
from symkin.trains import load_train, read_train
from tests.support.dynamics import NESTED_ONE

J = lambda name: sp.Symbol(f"J_{name}", positive=True)  # noqa: E731
m = lambda name: sp.Symbol(f"m_{name}", positive=True)  # noqa: E731
MM = sp.Rational(1, 1000)  # metres per millimetre


def test_ring_held_simple_planetary_matches_the_energy_worked_by_hand():
    # 24/24/72, ring held: omega_C = omega_S/4, omega_P = -omega_S/2, planet centres at 24 mm
    eom = equations_of_motion(load_train("simple"), state="low")
    r_c = 24 * MM
    by_hand = J("S") + J("C") / 16 + 3 * (J("P") / 4 + m("P") * r_c**2 / 16)
    assert sp.simplify(eom.mass_matrix[0, 0] - by_hand) == 0


# ----------------------------------------------------------------- mechanics models, typed by hand
t = me.dynamicsymbols._t


def _planar(N, O, name, angle):
    A = N.orientnew(name, "Axis", (angle, N.z))
    return A


def _body(name, frame, centre, mass, inertia):
    return me.RigidBody(name, centre, frame, mass, (me.inertia(frame, 0, 0, inertia), centre))


def _rolling(N, point_a, centre_a, frame_a, point_b, centre_b, frame_b, tangent):
    """Equal velocities of the contact point as a point of either body (tangential component)."""
    va = point_a.v2pt_theory(centre_a, N, frame_a)
    vb = point_b.v2pt_theory(centre_b, N, frame_b)
    return sp.trigsimp((va - vb).dot(tangent))


def _reduce(T, constraints, independent, dependent):
    """The kinetic energy in the independent speeds, the dependent ones solved from the constraints."""
    sol = sp.solve(constraints, dependent, dict=True)[0]
    sol = {k: sp.trigsimp(v) for k, v in sol.items()}
    T = sp.trigsimp(sp.expand(T.subs(sol)))
    return sp.Matrix(len(independent), len(independent), lambda i, j: sp.simplify(sp.diff(T, independent[i], independent[j])))


def _speeds(*names):
    q = me.dynamicsymbols(" ".join(f"q_{n}" for n in names))
    q = q if isinstance(q, list) else [q]
    return q, [qi.diff(t) for qi in q]


def test_two_degree_of_freedom_simple_planetary_matches_a_mechanics_model():
    # sun s 24, planets p 24 (three), ring r 72, module 1 mm; coordinates S and R, no brake
    (qs, qr, qc, qp), (us, ur, uc, up) = _speeds("S", "R", "C", "P")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    rs, rp, a = 12 * MM, 12 * MM, 24 * MM
    Sf, Rf, Cf = (_planar(N, O, n, q) for n, q in (("Sf", qs), ("Rf", qr), ("Cf", qc)))
    bodies = [_body("sun", Sf, O, 0, J("S")), _body("ring", Rf, O, 0, J("R")), _body("carrier", Cf, O, 0, J("C"))]
    constraints = []
    for k in range(3):
        Ck = N.orientnew(f"C{k}", "Axis", (qc + 2 * sp.pi * k / 3, N.z))
        Pf = N.orientnew(f"P{k}", "Axis", (qp + 2 * sp.pi * k / 3, N.z))
        centre = O.locatenew(f"Pc{k}", a * Ck.x)
        centre.set_vel(N, centre.pos_from(O).dt(N))
        bodies.append(_body(f"planet{k}", Pf, centre, m("P"), J("P")))
        if k == 0:
            inner = O.locatenew("X1", rs * Ck.x)
            inner_p = O.locatenew("X1p", rs * Ck.x)
            outer = O.locatenew("X2", (a + rp) * Ck.x)
            outer_p = O.locatenew("X2p", (a + rp) * Ck.x)
            constraints.append(_rolling(N, inner, O, Sf, inner_p, centre, Pf, Ck.y))
            constraints.append(_rolling(N, outer, O, Rf, outer_p, centre, Pf, Ck.y))
    T = sum(b.kinetic_energy(N) for b in bodies)
    M_ref = _reduce(T, constraints, [us, ur], [uc, up])
    eom = equations_of_motion(load_train("simple"), coordinates=["S", "R"])
    assert (eom.mass_matrix - M_ref).applyfunc(sp.simplify) == sp.zeros(2, 2)


def test_double_pinion_compound_set_matches_a_mechanics_model():
    # sun 30, inner pinions P1 and outer pinions P2 of 18 (three each), ring 90, module 1 mm; P1 at 24 mm on
    # the carrier's x axis, P2 at 36 mm where its 18 mm centre distance to P1 puts it (law of cosines, by hand)
    (qs, qr, qc, q1, q2), (us, ur, uc, u1, u2) = _speeds("S", "R", "C", "P1", "P2")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    Sf, Rf, Cf = (N.orientnew(n, "Axis", (q, N.z)) for n, q in (("Sf", qs), ("Rf", qr), ("Cf", qc)))
    bodies = [_body("sun", Sf, O, 0, J("S")), _body("ring", Rf, O, 0, J("R")), _body("carrier", Cf, O, 0, J("C"))]
    cos_b = sp.Rational(24**2 + 36**2 - 18**2, 2 * 24 * 36)
    sin_b = sp.sqrt(1 - cos_b**2)
    constraints = []
    for k in range(3):
        Ck = N.orientnew(f"C{k}", "Axis", (qc + 2 * sp.pi * k / 3, N.z))
        F1 = N.orientnew(f"F1{k}", "Axis", (q1 + 2 * sp.pi * k / 3, N.z))
        F2 = N.orientnew(f"F2{k}", "Axis", (q2 + 2 * sp.pi * k / 3, N.z))
        c1 = O.locatenew(f"c1{k}", 24 * MM * Ck.x)
        c2 = O.locatenew(f"c2{k}", 36 * MM * (cos_b * Ck.x + sin_b * Ck.y))
        for c in (c1, c2):
            c.set_vel(N, c.pos_from(O).dt(N))
        bodies += [_body(f"p1{k}", F1, c1, m("P1"), J("P1")), _body(f"p2{k}", F2, c2, m("P2"), J("P2"))]
        if k == 0:
            mid = (c1.pos_from(O) + c2.pos_from(O)) / 2  # equal pinions: the pitch point halfway
            e12 = (c2.pos_from(O) - c1.pos_from(O)) / (18 * MM)
            e2 = c2.pos_from(O) / (36 * MM)
            pairs = [((O, Sf), (c1, F1), 15 * MM * Ck.x, Ck.y), ((c1, F1), (c2, F2), mid, Ck.z.cross(e12)),
                     ((c2, F2), (O, Rf), 45 * MM * (cos_b * Ck.x + sin_b * Ck.y), Ck.z.cross(e2))]
            for n, ((pa, fa), (pb, fb), at, tangent) in enumerate(pairs):
                A, B = O.locatenew(f"A{n}", at), O.locatenew(f"B{n}", at)
                constraints.append(_rolling(N, A, pa, fa, B, pb, fb, tangent))
    T = sum(b.kinetic_energy(N) for b in bodies)
    M_ref = _reduce(T, constraints, [us, ur], [uc, u1, u2])
    eom = equations_of_motion(load_train("double-pinion"), coordinates=["S", "R"])
    assert (eom.mass_matrix - M_ref).applyfunc(sp.simplify) == sp.zeros(2, 2)


def test_kanes_method_on_the_same_model_gives_the_same_accelerations():
    # ring held, torque T_S on the sun; KanesMethod with the carrier and planet speeds dependent
    (qs, qc, qp), _ = _speeds("S", "C", "P")
    u = me.dynamicsymbols("u_S u_C u_P")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    rs, rp, a = 12 * MM, 12 * MM, 24 * MM
    Sf = N.orientnew("Sf", "Axis", (qs, N.z))
    Cf = N.orientnew("Cf", "Axis", (qc, N.z))
    Pf = N.orientnew("Pf", "Axis", (qp, N.z))
    Sf.set_ang_vel(N, u[0] * N.z)
    Cf.set_ang_vel(N, u[1] * N.z)
    Pf.set_ang_vel(N, u[2] * N.z)
    centre = O.locatenew("Pc", a * Cf.x)
    centre.v2pt_theory(O, N, Cf)
    inner, inner_p = O.locatenew("X1", rs * Cf.x), O.locatenew("X1p", rs * Cf.x)
    outer_p = O.locatenew("X2p", (a + rp) * Cf.x)
    c1 = (inner.v2pt_theory(O, N, Sf) - inner_p.v2pt_theory(centre, N, Pf)).dot(Cf.y)
    c2 = outer_p.v2pt_theory(centre, N, Pf).dot(Cf.y)  # the ring is held
    bodies = [_body("sun", Sf, O, 0, J("S")), _body("carrier", Cf, O, 0, J("C")),
              _body("planets", Pf, centre, 3 * m("P"), 3 * J("P"))]  # three equal planets, energy alike
    torque = sp.Symbol("T_S")
    kane = me.KanesMethod(N, q_ind=[qs, qc, qp], u_ind=[u[0]], u_dependent=[u[1], u[2]],
                          kd_eqs=[qs.diff(t) - u[0], qc.diff(t) - u[1], qp.diff(t) - u[2]],
                          velocity_constraints=[c1, c2])
    kane.kanes_equations(bodies, [(Sf, torque * N.z)])
    rhs = kane.rhs()
    acc_ref = sp.simplify(rhs[3])  # d u_S / dt
    eom = equations_of_motion(load_train("simple"), state="low", torques={"S": torque})
    assert sp.simplify(eom.accelerations[0] - acc_ref) == 0


def test_bevel_differential_matches_a_mechanics_model_in_space():
    # case C about z, two pinions P (10 teeth) on a radial axis, side gears L (+z side) and R (16 teeth)
    (ql, qr, qc, qp), (ul, ur, uc, up) = _speeds("L", "R", "C", "P")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    rs, rp = 8 * MM, 5 * MM  # pitch radii at the contact
    Lf, Rf, Cf = N.orientnew("Lf", "Axis", (ql, N.z)), N.orientnew("Rf", "Axis", (qr, N.z)), N.orientnew("Cf", "Axis", (qc, N.z))
    bodies = [_body("L", Lf, O, 0, J("L")), _body("R", Rf, O, 0, J("R")), _body("C", Cf, O, 0, J("C"))]
    constraints = []
    for k in range(2):
        Ck = N.orientnew(f"C{k}", "Axis", (qc + sp.pi * k, N.z))
        Pf = Ck.orientnew(f"P{k}", "Axis", (qp, Ck.x))  # spin about the radial axis, relative to the case
        centre = O.locatenew(f"Pc{k}", rs * Ck.x)
        centre.v2pt_theory(O, N, Ck)
        # a thin disc: J about its axis, J/2 about a diameter (symkin's stated assumption)
        bodies.append(me.RigidBody(f"pin{k}", centre, Pf, m("P"), (me.inertia(Pf, J("P"), J("P") / 2, J("P") / 2), centre)))
        if k == 0:
            up_pt, up_p = O.locatenew("U", rs * Ck.x + rp * Ck.z), O.locatenew("Up", rs * Ck.x + rp * Ck.z)
            dn_pt, dn_p = O.locatenew("D", rs * Ck.x - rp * Ck.z), O.locatenew("Dp", rs * Ck.x - rp * Ck.z)
            constraints.append((up_pt.v2pt_theory(O, N, Lf) - up_p.v2pt_theory(centre, N, Pf)).dot(Ck.y))
            constraints.append((dn_pt.v2pt_theory(O, N, Rf) - dn_p.v2pt_theory(centre, N, Pf)).dot(Ck.y))
    T = sum(b.kinetic_energy(N) for b in bodies)
    M_ref = _reduce(T, [sp.trigsimp(c) for c in constraints], [ul, ur], [uc, up])
    eom = equations_of_motion(load_train("bevel-differential"), coordinates=["L", "R"])
    assert (eom.mass_matrix - M_ref).applyfunc(sp.simplify) == sp.zeros(2, 2)





def test_a_single_planet_carrying_a_planet_has_a_configuration_dependent_mass_matrix_as_mechanics_gives():
    # one head P (arm 45 mm) on the arm C, one tool Q (15 mm from the head's axis) on it; coordinates C and G
    train = read_train(NESTED_ONE)
    eom = equations_of_motion(train, coordinates=["C", "G"])
    (qc, qg, qp, qq), (uc, ug, up, uq) = _speeds("C", "G", "P", "Q")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    Cf, Pf, Gf, Qf = (N.orientnew(n, "Axis", (q, N.z)) for n, q in (("Cf", qc), ("Pf", qp), ("Gf", qg), ("Qf", qq)))
    head = O.locatenew("H", 45 * MM * Cf.x)
    head.v2pt_theory(O, N, Cf)
    tool = head.locatenew("T", 15 * MM * Pf.x)
    tool.v2pt_theory(head, N, Pf)
    bodies = [_body("C", Cf, O, 0, J("C")), _body("P", Pf, head, m("P"), J("P")), _body("G", Gf, head, m("G"), J("G")),
              _body("Q", Qf, tool, m("Q"), J("Q"))]
    c1 = (O.locatenew("A", 30 * MM * Cf.x).v2pt_theory(O, N, N.orientnew("F", "Axis", (0, N.z)))
          - O.locatenew("Ap", 30 * MM * Cf.x).v2pt_theory(head, N, Pf)).dot(Cf.y)
    # g (9 mm) and q (6 mm) meet on the line from the head's axis to the tool's, in the head's frame
    c2 = (head.locatenew("B", 9 * MM * Pf.x).v2pt_theory(head, N, Gf)
          - head.locatenew("Bp", 9 * MM * Pf.x).v2pt_theory(tool, N, Qf)).dot(Pf.y)
    T = sum(b.kinetic_energy(N) for b in bodies)
    sol = sp.solve([sp.trigsimp(c1), sp.trigsimp(c2)], [up, uq], dict=True)[0]
    T_ref = sp.trigsimp(sp.expand(T.subs(sol)))
    # compare the energies at a configuration: the tool arm's angle to the head arm is varphi_P - varphi_C
    wc, wg = sp.Rational(3, 2), sp.Rational(-2, 7)
    x = sp.Rational(7, 10)
    omega_p = eom.speeds["P"].subs({S.omega("C"): 1, S.omega("G"): 0})  # d varphi_P / d varphi_C
    omega_pg = eom.speeds["P"].subs({S.omega("C"): 0, S.omega("G"): 1})
    # pick angles with qp - qc = the turn symkin's angle law gives
    ours = eom.kinetic_energy.subs({S.omega("C"): wc, S.omega("G"): wg, S.angle("C"): x, S.angle("G"): 0})
    ref = T_ref.subs({uc: wc, ug: wg, qc: x, qg: 0, qp: omega_p * x + omega_pg * 0}).doit()
    assert sp.N(ours - ref, 30) == pytest.approx(0, abs=1e-25)
    assert eom.mass_matrix.free_symbols & {S.angle("C"), S.angle("G")}  # M depends on the configuration
    assert not equations_of_motion(load_train("nested"), coordinates=["C"]).mass_matrix.free_symbols & {S.angle("C")}


def test_forcing_holds_lagranges_equations_by_finite_differences():
    # d/dt dT/du - dT/dq = Q along a motion, the time derivative by a central difference
    train = read_train(NESTED_ONE)
    eom = equations_of_motion(train, coordinates=["C", "G"], torques={"C": 3, "G": -1})
    values = {J(n): v for n, v in (("C", 2), ("P", 1), ("G", sp.Rational(1, 2)), ("Q", sp.Rational(1, 3)))}
    values.update({m(n): v for n, v in (("P", 40), ("G", 10), ("Q", 20))})
    q0, u0, a0 = [0.3, -0.2], [1.1, 0.4], [0.7, -0.9]
    qs, us = list(eom.angles), list(eom.speeds_symbols)
    T = eom.kinetic_energy.subs(values)
    dTdu = [sp.lambdify([*qs, *us], sp.diff(T, ui)) for ui in us]
    dTdq = [sp.lambdify([*qs, *us], sp.diff(T, qi)) for qi in qs]
    M = sp.lambdify([*qs], eom.mass_matrix.subs(values))
    f = sp.lambdify([*qs, *us], eom.forcing.subs(values))
    h = 1e-6
    state = lambda s: [*(q + u * s + a * s * s / 2 for q, u, a in zip(q0, u0, a0)), *(u + a * s for u, a in zip(u0, a0))]  # noqa: E731
    for i in range(2):
        ddt = (dTdu[i](*state(h)) - dTdu[i](*state(-h))) / (2 * h)
        lhs = ddt - dTdq[i](*q0, *u0)
        rhs = (np.array(M(*q0)) @ np.array(a0))[i] - f(*q0, *u0)[i][0]
        # M a - f = (d/dt dT/du - dT/dq) - Q, and Q is the applied torques' share
        Q = float(eom.generalised_forces[i])
        assert lhs - Q == pytest.approx(rhs, rel=1e-6, abs=1e-9)


def test_a_free_run_keeps_its_energy_and_torques_balance_power():
    eom = equations_of_motion(load_train("ravigneaux"), coordinates=["S1", "S2"])
    values = {s.name: 1 + k / 7 for k, s in enumerate(sorted(eom.mass_matrix.free_symbols, key=str))}
    run = eom.simulate((0, 2), initial_speeds=[10, -3], values=values, t_eval=np.linspace(0, 2, 11))
    assert np.ptp(run.kinetic_energy) <= 1e-8 * run.kinetic_energy[0]
    # power balance: with a torque on S1 only, dT/dt = T_S1 * omega_S1
    driven = equations_of_motion(load_train("ravigneaux"), coordinates=["S1", "S2"], torques={"S1": 5})
    run = driven.simulate((0, 1), initial_speeds=[1, 2], values=values, t_eval=np.linspace(0, 1, 201))
    dT = np.gradient(run.kinetic_energy, run.t)
    assert dT[50:150] == pytest.approx(5 * run.speeds["S1"][50:150], rel=1e-4)


@pytest.mark.parametrize(("name", "coordinates"), [("double-pinion", ["S", "R"]), ("nested-one", ["C", "Q"])])
def test_mechanics_bridge_gives_the_same_mass_matrix_and_forcing(name, coordinates):
    # a sympy.physics.mechanics System formed by Lagrange's method from the kinetic energy and the
    # torques on frames turning with the coordinates; nested-one's M depends on the configuration,
    # so its forcing carries the velocity terms
    train = read_train(NESTED_ONE) if name == "nested-one" else load_train(name)
    torques = {coordinates[0]: sp.Symbol("T_1"), coordinates[1]: sp.sin(S.t)}
    eom = equations_of_motion(train, coordinates=coordinates, torques=torques)
    system = eom.to_mechanics()
    assert isinstance(system, me.System)
    q = [me.dynamicsymbols(str(a)) for a in eom.angles]
    assert list(system.q) == q and len(system.u) == len(q) and len(system.kdes) == len(q)
    back = {**{qi.diff(t): w for qi, w in zip(q, eom.speeds_symbols)}, **dict(zip(q, eom.angles))}
    n = len(q)
    assert (system.mass_matrix.subs(back) - eom.mass_matrix).applyfunc(sp.simplify) == sp.zeros(n, n)
    assert (system.forcing.subs(back).subs(t, S.t) - eom.forcing).applyfunc(sp.simplify) == sp.zeros(n, 1)
    assert eom.forcing.has(sp.sin(S.t))


def test_bad_requests_are_one_line_errors():
    train = load_train("simple")
    with pytest.raises(InputError, match="does not move in this state"):
        equations_of_motion(train, state="low", coordinates=["R"])
    with pytest.raises(InputError, match="named twice"):
        equations_of_motion(train, coordinates=["S", "S"])
    with pytest.raises(InputError, match="torque on link S must be a finite"):
        equations_of_motion(train, torques={"S": float("nan")})
    with pytest.raises(InputError, match="give values to"):
        equations_of_motion(train, state="low").simulate((0, 1))


ON_A_BASE = """
module = 1
meshes = [["s", "p"], ["p", "r"]]
[links.S]
gears = { s = 24 }
[links.C]
[links.P]
carrier = "C"
gears = { p = 24 }
[links.R]
gears = { r = { teeth = 72, internal = true } }
[base]
x = "5*t**2"
y = "3*sin(t)"
yaw = "t**2/2"
pitch = "t/3"
[states.low]
input = "S"
output = "C"
brakes = ["R"]
"""


def test_a_moving_base_gives_the_equations_of_a_mechanics_model_on_that_base():
    # one planet (so that nothing cancels over copies), the ring held on a base that moves and tilts;
    # the rolling constraints integrated by hand: varphi_C = varphi_S/4, varphi_P = -varphi_S/2
    qs = me.dynamicsymbols("q_S")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Body", (t**2 / 2, t / 3, 0), "ZYX")
    O = me.Point("O")
    O.set_vel(N, (10 * t * N.x + 3 * sp.cos(t) * N.y) * MM)
    Sf, Cf, Pf = (B.orientnew(n, "Axis", (q, B.z)) for n, q in (("Sf", qs), ("Cf", qs / 4), ("Pf", -qs / 2)))
    centre = O.locatenew("Pc", 24 * MM * Cf.x)
    centre.set_vel(N, O.vel(N) + centre.pos_from(O).dt(N))
    Jt = sp.Symbol("J_t", positive=True)  # a transverse moment: in T, in no equation
    bodies = [me.RigidBody("S", O, Sf, 0, (me.inertia(Sf, Jt, Jt, J("S")), O)),
              me.RigidBody("C", O, Cf, 0, (me.inertia(Cf, Jt, Jt, J("C")), O)),
              me.RigidBody("P", centre, Pf, m("P"), (me.inertia(Pf, Jt, Jt, J("P")), centre))]
    torque = sp.Symbol("T_S")
    lm = me.LagrangesMethod(sum(b.kinetic_energy(N) for b in bodies), [qs], forcelist=[(Sf, torque * B.z)], frame=N)
    lm.form_lagranges_equations()
    eom = equations_of_motion(read_train(ON_A_BASE), state="low", torques={"S": torque})
    point = {qs: sp.Rational(7, 10), qs.diff(t): sp.Rational(-3, 2), t: sp.Rational(11, 10)}
    ours = {S.angle("S"): point[qs], S.omega("S"): point[qs.diff(t)], S.t: point[t]}
    values = {J("S"): 2, J("C"): 3, J("P"): 1, m("P"): 5000, Jt: 7, torque: sp.Rational(1, 3)}
    for mine, theirs in ((eom.mass_matrix[0], lm.mass_matrix[0]), (eom.forcing[0], lm.forcing[0])):
        a = sp.N(mine.subs(values).subs(ours), 30)
        b = sp.N(theirs.subs(values).subs(point).doit(), 30)
        assert a == pytest.approx(float(b), rel=1e-12)
    # and the base's motion matters: the still frame gives another forcing
    still = equations_of_motion(read_train(ON_A_BASE), state="low", torques={"S": torque}, base=False)
    assert sp.N(still.forcing[0].subs(values).subs(ours)) != pytest.approx(float(sp.N(eom.forcing[0].subs(values).subs(ours))))


def test_bevel_pinions_on_a_turning_tilting_base_match_mechanics():
    # the bevel differential with R held (case C drives), on a base that yaws and pitches; the pinion's
    # and L's speeds per case speed from the rolling constraints written here in the still frame
    rs, rp = 8 * MM, 5 * MM
    wc, wl, wp = sp.symbols("w_c w_l w_p")
    N0 = me.ReferenceFrame("N0")
    O0 = me.Point("O0")
    O0.set_vel(N0, 0)
    C0 = N0.orientnew("C0", "Axis", (0, N0.z))
    C0.set_ang_vel(N0, wc * N0.z)
    L0 = N0.orientnew("L0", "Axis", (0, N0.z))
    L0.set_ang_vel(N0, wl * N0.z)
    P0 = C0.orientnew("P0", "Axis", (0, C0.x))
    P0.set_ang_vel(C0, wp * C0.x)
    c0 = O0.locatenew("c0", rs * C0.x)
    c0.v2pt_theory(O0, N0, C0)
    up = (O0.locatenew("U", rs * C0.x + rp * C0.z).v2pt_theory(O0, N0, L0)
          - O0.locatenew("Up", rs * C0.x + rp * C0.z).v2pt_theory(c0, N0, P0)).dot(C0.y)
    down = O0.locatenew("Dp", rs * C0.x - rp * C0.z).v2pt_theory(c0, N0, P0).dot(C0.y)  # on R, held
    ratio = sp.solve([up, down], [wl, wp], dict=True)[0]
    kl, kp = ratio[wl] / wc, ratio[wp] / wc
    q = me.dynamicsymbols("q_C")
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Body", (t**2 / 2, t / 3, 0), "ZYX")
    O = me.Point("O")
    O.set_vel(N, 0)
    Cf, Lf = B.orientnew("Cf", "Axis", (q, B.z)), B.orientnew("Lf", "Axis", (kl * q, B.z))
    Jt = sp.Symbol("J_t", positive=True)
    bodies = [me.RigidBody("C", O, Cf, 0, (me.inertia(Cf, Jt, Jt, J("C")), O)),
              me.RigidBody("L", O, Lf, 0, (me.inertia(Lf, Jt, Jt, J("L")), O))]
    for k in range(2):
        Ck = B.orientnew(f"C{k}", "Axis", (q + sp.pi * k, B.z))
        Pk = Ck.orientnew(f"P{k}", "Axis", (kp * q, Ck.x))
        centre = O.locatenew(f"c{k}", rs * Ck.x)
        centre.set_vel(N, centre.pos_from(O).dt(N))
        bodies.append(me.RigidBody(f"P{k}", centre, Pk, m("P"), (me.inertia(Pk, J("P"), J("P") / 2, J("P") / 2), centre)))
    lm = me.LagrangesMethod(sum(b.kinetic_energy(N) for b in bodies), [q], frame=N)
    lm.form_lagranges_equations()
    train = read_train(_bevel_on_a_base())
    eom = equations_of_motion(train, state="one-wheel-stuck")
    point = {q: sp.Rational(2, 5), q.diff(t): sp.Rational(9, 4), t: sp.Rational(3, 4)}
    ours = {S.angle("C"): point[q], S.omega("C"): point[q.diff(t)], S.t: point[t]}
    values = {J("C"): 2, J("L"): 3, J("R"): 4, J("P"): 1, m("P"): 3000, Jt: 7}
    for mine, theirs in ((eom.mass_matrix[0], lm.mass_matrix[0]), (eom.forcing[0], lm.forcing[0])):
        a = sp.N(mine.subs(values).subs(ours), 30)
        b = sp.N(theirs.subs(values).subs(point).doit(), 30)
        assert a == pytest.approx(float(b), rel=1e-12)


def _bevel_on_a_base() -> str:
    from importlib.resources import files

    text = (files("symkin.trains") / "library" / "bevel-differential.toml").read_text()
    return text.replace("[states.straight]", '[base]\nyaw = "t**2/2"\npitch = "t/3"\n\n[states.straight]')


def test_a_clutch_that_locks_the_set_makes_it_one_rigid_body():
    # double-pinion, sun and carrier joined: everything turns at omega_S, the pinion centres at 24 and 36 mm
    eom = equations_of_motion(load_train("double-pinion"), state="direct")
    by_hand = (J("S") + J("C") + J("R") + 3 * J("P1") + 3 * J("P2")
               + 3 * m("P1") * (24 * MM) ** 2 + 3 * m("P2") * (36 * MM) ** 2)
    assert eom.coordinates == ("S",)
    assert sp.simplify(eom.mass_matrix[0, 0] - by_hand) == 0
