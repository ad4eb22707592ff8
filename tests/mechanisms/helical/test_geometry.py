"""Helical mesh geometry and the statics of the stepped planet.

The derived balance (symkin.statics.planet_statics) is tested against the independent
3-D force computation (symkin.statics.planet_forces) on random trains, shifted and not;
the geometry against textbook identities and a direct involute construction.
"""

import math
import random
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from symkin import ModelError, schemes
from symkin.mechanisms.helical import (
    HelicalMesh,
    HelicalTrain,
    helical_gear,
    inverse_involute,
    involute,
    lead,
)
from symkin.statics import (
    balancing_hands,
    mesh_hand_relation,
    planet_forces,
    planet_statics,
)

RNG = random.Random(2010)
SCHEMES = ("AI", "AA", "II")


def random_train(scheme, *, balanced, shifted=False, hands=None, rng=RNG):
    """A random train; balanced: beta12 from equal leads (the textbook lead pi m_n z / sin(beta))."""
    while True:
        z2, z3 = rng.randint(17, 60), rng.randint(17, 60)
        z1 = rng.randint(17, 90) if scheme != "II" else z2 + rng.randint(8, 80)
        z4 = rng.randint(17, 90) if scheme == "AA" else z3 + rng.randint(8, 80)
        m12, m34 = rng.choice([1, 1.5, 2, 2.5, 3]), rng.choice([1, 1.5, 2, 2.5, 3])
        b34 = math.radians(rng.uniform(5, 35))
        if balanced:
            s = math.sin(b34) * m12 * z2 / (m34 * z3)  # equal leads
            if not 0.05 < s < 0.7:
                continue
            b12 = math.asin(s)
        else:
            b12 = math.radians(rng.uniform(5, 35))
        shifts = tuple(rng.uniform(-0.3, 0.5) for _ in range(4)) if shifted else (0, 0, 0, 0)
        try:
            return HelicalTrain(scheme, (z1, z2, z3, z4), (m12, m34), (b12, b34), hands=hands,
                                satellites=rng.choice([1, 3, 4]), shifts=shifts)
        except ModelError:
            continue


# ---------------------------------------------------------------- geometry
def test_transverse_and_base_angles_against_textbook_identities():
    m = HelicalMesh(23, 71, 2.5, math.radians(17), alpha_n=math.radians(20))
    # tan(alpha_t) = tan(alpha_n)/cos(beta); sin(beta_b) = sin(beta) cos(alpha_n)
    assert math.tan(m.alpha_t) == pytest.approx(math.tan(math.radians(20)) / math.cos(math.radians(17)), rel=1e-15)
    assert math.sin(m.beta_base) == pytest.approx(math.sin(math.radians(17)) * math.cos(math.radians(20)), rel=1e-14)
    # base pitch in the transverse plane is the same on both gears: 2 pi r_b / z
    assert 2 * math.pi * m.base_radius("external") / 23 == pytest.approx(2 * math.pi * m.base_radius("mate") / 71, rel=1e-14)


def test_profile_shift_moves_the_centre_distance_as_the_involute_construction_says():
    """Working centre distance from the tooth thicknesses: the two gears' tooth thicknesses on
    the working circles must fill the working circular pitch (no backlash)."""
    z1, z2, mn, beta, an = 19, 41, 3.0, math.radians(12), math.radians(20)
    x1, x2 = 0.4, 0.25
    m = HelicalMesh(z1, z2, mn, beta, alpha_n=an, shift_external=x1, shift_mate=x2)
    at, atw = m.alpha_t, m.alpha_tw
    mt = mn / math.cos(beta)

    def thickness_on(r_w, z, x):  # transverse tooth thickness on radius r_w
        r = mt * z / 2
        s = mt * (math.pi / 2 + 2 * x * math.tan(an))
        return 2 * r_w * (s / (2 * r) + involute(at) - involute(atw))

    rw1, rw2 = m.working_radius("external"), m.working_radius("mate")
    pitch_w = 2 * math.pi * rw1 / z1
    assert thickness_on(rw1, z1, x1) + thickness_on(rw2, z2, x2) == pytest.approx(pitch_w, rel=1e-12)
    assert rw1 + rw2 == pytest.approx(m.centre_distance, rel=1e-14)
    assert m.centre_distance > m.reference_centre_distance  # positive shift spreads the gears


def test_internal_mesh_centre_distance_and_shift_sign():
    m = HelicalMesh(20, 80, 2.0, math.radians(10), internal=True)
    assert m.centre_distance == pytest.approx(2.0 * 60 / (2 * math.cos(math.radians(10))), rel=1e-15)
    shifted = HelicalMesh(20, 80, 2.0, math.radians(10), internal=True, shift_mate=0.5)
    assert shifted.centre_distance > m.centre_distance
    assert shifted.working_radius("mate") - shifted.working_radius("external") == pytest.approx(shifted.centre_distance, rel=1e-14)


def test_inverse_involute_round_trip():
    for a in np.linspace(1e-3, 1.4, 50):
        assert inverse_involute(involute(float(a))) == pytest.approx(float(a), rel=1e-13)
    with pytest.raises(ModelError, match="involute"):
        inverse_involute(-0.1)


def test_helical_gear_enters_the_model_with_its_working_radius():
    g = helical_gear("2", 30, 2, math.radians(20))
    assert float(g.radius) == pytest.approx(30 / math.cos(math.radians(20)), rel=1e-14)
    assert g.teeth == 30


def test_lead_is_the_same_on_every_cylinder():
    z, mn, beta, an = 31, 2.0, math.radians(22), math.radians(20)
    m = HelicalMesh(z, 60, mn, beta, alpha_n=an)
    # on the base cylinder: lead = 2 pi r_b / tan(beta_b)
    assert 2 * math.pi * m.base_radius("external") / math.tan(m.beta_base) == pytest.approx(lead(z, mn, beta), rel=1e-14)


@pytest.mark.parametrize("bad, message", [
    (dict(teeth_external=0), "at least 1"),
    (dict(normal_module=-2), "positive"),
    (dict(beta=math.radians(95)), "helix angle"),
    (dict(internal=True, teeth_mate=15), "internal gear"),
])
def test_mesh_rejects_bad_input(bad, message):
    args = dict(teeth_external=20, teeth_mate=40, normal_module=2.0, beta=0.2)
    args.update(bad)
    with pytest.raises(ModelError, match=message):
        HelicalMesh(**args)


def test_train_rejects_bad_input():
    with pytest.raises(ModelError, match="unknown two-row scheme"):
        HelicalTrain("AX", (20, 30, 20, 70), (2, 2), (0.2, 0.2))
    with pytest.raises(ModelError, match="positive"):
        HelicalTrain("AI", (20, 30, 20, 70), (2, 0), (0.2, 0.2))
    with pytest.raises(ModelError, match="hand"):
        HelicalTrain("AI", (20, 30, 20, 70), (2, 2), (0.2, 0.2), hands=(1, 1, 2, 1))


# ---------------------------------------------------------------- statics: derived vs direct
def test_torque_balance_is_derived_from_the_mesh_geometry():
    r2, r3 = sp.symbols("r_2 r_3", positive=True)
    for kind, same in (("AI", True), ("AA", False), ("II", False)):
        st = planet_statics(schemes.two_row(kind))
        assert st.same_direction is same
        F = st.tangential[0]
        assert sp.simplify(sp.Abs(st.tangential[1]) * r3 - sp.Abs(F) * r2) == 0  # F_t2 r_w2 = F_t3 r_w3
        assert st.same_hand is True
        assert sp.simplify(st.condition.rhs - r2 / r3) == 0


@pytest.mark.parametrize("kind", SCHEMES)
def test_derived_axial_sum_equals_the_direct_force_computation_on_random_trains(kind):
    """The symbolic axial force sum, evaluated at a random train's numbers, equals the axial
    sum of the independent 3-D computation (random helix angles and hands, shifted meshes)."""
    st = planet_statics(schemes.two_row(kind))
    rng = random.Random(hash(kind) % 1000)
    for _ in range(12):
        hands = tuple(rng.choice((1, -1)) for _ in range(4))
        t = random_train(kind, balanced=False, shifted=rng.random() < 0.5, hands=hands, rng=rng)
        f = planet_forces(t, input_torque=rng.uniform(0.5, 50))
        m12, m34 = t.mesh12, t.mesh34
        rw2, rw3 = m12.working_radius("external"), m34.working_radius("external")
        # helix angle on the working cylinder: tan(beta_w) = tan(beta) r_w / r
        tw2 = math.tan(m12.beta) * rw2 / m12.pitch_radius("external")
        tw3 = math.tan(m34.beta) * rw3 / m34.pitch_radius("external")
        values = {sp.Symbol("F_x2", real=True): f.force_2[0], sp.Symbol("h_2", nonzero=True): hands[1],
                  sp.Symbol("h_3", nonzero=True): hands[2], sp.Symbol("r_2", positive=True): rw2,
                  sp.Symbol("r_3", positive=True): rw3,
                  sp.tan(sp.Symbol("beta_w2", positive=True)): tw2, sp.tan(sp.Symbol("beta_w3", positive=True)): tw3}
        derived = float(st.axial_sum.subs(values))
        assert derived == pytest.approx(f.axial_sum, rel=1e-12, abs=1e-15 * abs(f.force_2[2]))
        # and the derived tangential force at mesh 3-4 is the direct one
        assert float(st.tangential[1].subs(values)) == pytest.approx(f.force_3[0], rel=1e-12)


@pytest.mark.parametrize("kind", SCHEMES)
def test_balanced_designs_carry_no_axial_load_and_unbalanced_ones_do(kind):
    rng = random.Random(7 + len(kind))
    for _ in range(15):
        t = random_train(kind, balanced=True, shifted=rng.random() < 0.5, rng=rng)
        f = planet_forces(t)
        assert f.axial_residual < 1e-13 and f.hand_mismatch == 0
        # the derived condition holds on the working cylinders, shifted or not
        tw2 = math.tan(t.betas[0]) * t.mesh12.working_radius("external") / t.mesh12.pitch_radius("external")
        tw3 = math.tan(t.betas[1]) * t.mesh34.working_radius("external") / t.mesh34.pitch_radius("external")
        assert tw2 / tw3 == pytest.approx(t.working_diameter_ratio, rel=1e-13)
        assert t.leads[0] == pytest.approx(t.leads[1], rel=1e-13)
    for _ in range(15):
        t = random_train(kind, balanced=False, rng=rng)
        if abs(t.leads[0] / t.leads[1] - 1) > 1e-3:
            assert planet_forces(t).axial_residual > 1e-4


def test_reference_angles_with_working_diameters_leave_a_residual_when_shifted():
    """The paper's tan(beta12)/tan(beta34) = d_w2/d_w3 with reference angles is exact only
    without profile shift: with the two meshes shifted differently it leaves an axial load."""
    z, mods = (20, 40, 25, 90), (2.0, 2.0)
    shifts = (0.0, 0.5, -0.2, 0.0)
    b34 = math.radians(12)
    probe = HelicalTrain("AI", z, mods, (0.3, b34), shifts=shifts)
    ratio = probe.working_diameter_ratio  # depends on beta12 only weakly; iterate to the fixed point
    for _ in range(50):
        b12 = math.atan(math.tan(b34) * ratio)
        ratio = HelicalTrain("AI", z, mods, (b12, b34), shifts=shifts).working_diameter_ratio
    t = HelicalTrain("AI", z, mods, (b12, b34), shifts=shifts)
    assert math.tan(b12) / math.tan(b34) == pytest.approx(t.working_diameter_ratio, rel=1e-12)
    assert planet_forces(t).axial_residual > 1e-3
    # the same construction without shift balances exactly: there d_w = d
    for _ in range(50):
        b12 = math.atan(math.tan(b34) * HelicalTrain("AI", z, mods, (b12, b34)).working_diameter_ratio)
    assert planet_forces(HelicalTrain("AI", z, mods, (b12, b34))).axial_residual < 1e-12


def test_wrong_hands_are_caught_by_the_force_check():
    t = random_train("AI", balanced=True)
    assert planet_forces(t).hand_mismatch == 0
    h1, h2, h3, h4 = t.hands
    flipped_rim = HelicalTrain(t.scheme, t.teeth, t.normal_modules, t.betas, hands=(h1, h2, -h3, h4))
    assert planet_forces(flipped_rim).axial_residual == pytest.approx(2, rel=1e-12)  # the forces add
    assert planet_forces(flipped_rim).hand_mismatch > 1  # rim 3 no longer fits gear 4
    wrong_mesh = HelicalTrain(t.scheme, t.teeth, t.normal_modules, t.betas, hands=(-h1, h2, h3, h4))
    assert planet_forces(wrong_mesh).hand_mismatch > 1


def test_hands_from_the_helix_tangency():
    for kind in SCHEMES:
        mech = schemes.two_row(kind)
        h = balancing_hands(kind)
        assert h[1] == h[2] == 1
        assert h[0] == (1 if mech.gear("1").internal else -1)  # internal mesh: same hand
        assert h[3] == (1 if mech.gear("4").internal else -1)
        assert mesh_hand_relation(mech, ("1", "2")) * mesh_hand_relation(mech, ("2", "1")) == 1


def test_statics_ratio_is_the_engines_ratio_for_coaxial_trains():
    """Virtual work: carrier torque per input torque is i_1H^(4), exactly the engine's ratio."""
    from symkin.mechanisms.helical.balanced import synthesize_helical

    res = synthesize_helical(scheme="II", ratio=Fraction("1/50"), tolerance=Fraction("0.05"), satellites=3, normal_modules=(2, Fraction("2.5")),
                     teeth_max=100, top=None)
    assert res.designs
    for d in res.designs:
        assert planet_forces(d.train).ratio == pytest.approx(float(d.ratio), rel=1e-11)
    d = res.designs[0]
    assert d.train.mechanism.ratio("1", "H", fixed="4").rhs == sp.Rational(d.ratio.numerator, d.ratio.denominator)
