"""Meshes against published worked examples (KHK, SDP-SI tables), the textbook contact ratio, and a
second route: the line of action cut by the tip circles numerically."""

from __future__ import annotations

import math

import pytest
import sympy as sp
from scipy.optimize import brentq

from symkin.errors import InputError
from symkin.geometry import (
    ToothForm,
    gear_geometry,
    interferences,
    inverse_involute,
    involute,
    pair_geometry,
    shift_sum_for,
)


def _inv(a: float) -> float:
    return math.tan(a) - a


def test_the_contact_ratio_of_20_40_module_2_is_the_textbook_value():
    # eps = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin a) / (pi m cos a), z 20/40, m 2: 1.635
    a = math.radians(20)
    ra1, ra2, rb1, rb2 = 22, 42, 20 * math.cos(a), 40 * math.cos(a)
    by_hand = (math.sqrt(ra1**2 - rb1**2) + math.sqrt(ra2**2 - rb2**2) - 60 * math.sin(a)) / (math.pi * 2 * math.cos(a))
    eps = float(pair_geometry(gear_geometry(20, 2), gear_geometry(40, 2)).contact_ratio)
    assert eps == pytest.approx(by_hand, rel=1e-14)
    assert round(eps, 3) == 1.635


def test_the_khk_worked_example_working_pressure_angle_centre_distance_and_contact_ratio():
    # KHK Gear Technical Reference (as reproduced at bolsover.com/utilitiesforalibre/profile-shifted-external-
    # spur-gears.html): m 3, z 12/24, x 0.6/0.36: inv a_w 0.034317, a_w 26.0888 deg, a 56.4999 (56.500), and with
    # the tips turned down to 44.840 and 79.400 mm, a contact ratio of 1.202
    g1 = gear_geometry(12, 3, ToothForm(shift=0.6), tip_diameter=44.84)
    g2 = gear_geometry(24, 3, ToothForm(shift=0.36), tip_diameter=79.4)
    p = pair_geometry(g1, g2)
    assert float(involute(p.working_pressure_angle)) == pytest.approx(0.034317, abs=1e-6)  # (printed rounded up)
    assert float(sp.deg(p.working_pressure_angle)) == pytest.approx(26.0888, abs=3e-4)  # (from the rounded inv)
    assert float(p.centre_distance) == pytest.approx(56.4999, abs=5e-5)
    assert round(float(p.contact_ratio), 3) == 1.202


# SDP-SI (KHK), Elements of Metric Gear Technology, Table 5-4: internal gears with small differences in
# numbers of teeth, m 1, 20 deg, z2 = 50, x1 = 0: (z1, x2, a_w in degrees, a, eps); none has involute or
# trochoid interference, every one has trimming interference
TABLE_5_4 = [(49, "1.00", 61.0605, 0.971, 1.105), (48, "0.60", 46.0324, 1.354, 1.512), (47, "0.40", 37.4155, 1.775, 1.726),
             (46, "0.30", 32.4521, 2.227, 1.835), (45, "0.20", 28.2019, 2.666, 1.933), (44, "0.11", 24.5356, 3.099, 2.014),
             (43, "0.06", 22.3755, 3.557, 2.053), (42, "0.01", 20.3854, 4.010, 2.088)]


@pytest.mark.parametrize("z1, x2, alpha_w, a, eps", TABLE_5_4)
def test_internal_meshes_of_small_tooth_difference_match_the_published_table(z1, x2, alpha_w, a, eps):
    p = pair_geometry(gear_geometry(z1, 1), gear_geometry(50, 1, ToothForm(shift=sp.Rational(x2)), internal=True))
    assert float(sp.deg(p.working_pressure_angle)) == pytest.approx(alpha_w, abs=5e-5)
    assert round(float(p.centre_distance), 3) == a
    assert round(float(p.contact_ratio), 3) == eps
    problems = p.problems(min_contact_ratio=1)
    assert [q.split(":")[0] for q in problems] == ["trimming interference"]


# SDP-SI Table 5-3a: the least internal gear a pinion cutter (addendum 1.25 m, x = 0) cuts without trimming
@pytest.mark.parametrize("zc, z2", [(17, 35), (20, 38), (28, 46), (40, 58), (64, 82), (100, 118)])
def test_trimming_limits_of_a_pinion_cutter_match_the_published_table(zc, z2):
    cutter = gear_geometry(zc, 1, ToothForm(addendum=sp.Rational(5, 4)))
    assert pair_geometry(cutter, gear_geometry(z2, 1, internal=True))._trimming_ok()
    assert not pair_geometry(cutter, gear_geometry(z2 - 1, 1, internal=True))._trimming_ok()


# Table 5-3a in full: every (zc, z2) row; SDP-SI 5.2 (c) under it: "there will be an involute interference between
# the internal gear and the pinion cutter if the number of teeth of the pinion cutter ranges from 15 to 22"
TABLE_5_3A = [(15, 34), (16, 34), (17, 35), (18, 36), (19, 37), (20, 38), (21, 39), (22, 40), (24, 42), (25, 43),
              (27, 45), (28, 46), (30, 48), (31, 49), (32, 50), (33, 51), (34, 52), (35, 53), (38, 56), (40, 58),
              (42, 60), (44, 62), (48, 66), (50, 68), (56, 74), (60, 78), (64, 82), (66, 84), (80, 98), (96, 114),
              (100, 118)]


def _ring_clears_by_hand(z1: int, z2: int, x2: float = 0.0, alpha_w: float = math.pi / 9) -> bool:
    """SDP-SI eq. (5-5) typed here: z1/z2 >= 1 - tan(alpha_a2)/tan(alpha_w), cos(alpha_a2) = d_b2/d_a2, with the
    internal gear's tip d_a2 = m (z2 - 2 + 2 x2) (m = 1)."""
    alpha_a2 = math.acos(z2 * math.cos(math.pi / 9) / (z2 - 2 + 2 * x2))
    return z1 / z2 >= 1 - math.tan(alpha_a2) / math.tan(alpha_w)


@pytest.mark.parametrize("zc, z2", TABLE_5_3A)
def test_involute_interference_of_a_pinion_cutter_and_its_ring_matches_the_published_statement(zc, z2):
    cutter = gear_geometry(zc, 1, ToothForm(addendum=sp.Rational(5, 4)))
    found = pair_geometry(cutter, gear_geometry(z2, 1, internal=True)).interferences()
    assert ("involute" in found) == (zc <= 22) == (not _ring_clears_by_hand(zc, z2))
    assert "trimming" not in found  # the row is the least ring without trimming


def test_a_shifted_pinion_cutter_matches_table_5_3b():
    # Table 5-3b (x2 = 0, the cutter shifted by xc = 0.0075 zc + 0.05): its first row, zc 15, xc 0.1625, z2 36 (the
    # least ring without trimming); under it: involute interference for cutters of 15 to 19 teeth, none from 20
    def least_ring(zc: int) -> tuple[int, tuple[str, ...]]:
        cutter = gear_geometry(zc, 1, ToothForm(addendum=sp.Rational(5, 4), shift=sp.Rational(75, 10000) * zc + sp.Rational(1, 20)))
        z2 = zc + 12
        while "trimming" in (found := pair_geometry(cutter, gear_geometry(z2, 1, internal=True)).interferences()):
            z2 += 1
        return z2, found
    assert least_ring(15)[0] == 36
    assert [zc for zc in range(15, 26) if "involute" in least_ring(zc)[1]] == [15, 16, 17, 18, 19]


@pytest.mark.parametrize("z1, x2, alpha_w, a, eps", TABLE_5_4[::3])
def test_the_float_route_of_the_interference_checks_agrees_with_the_exact_one(z1, x2, alpha_w, a, eps):
    # interferences() with math floats (coaxial_shifts scans with it) against the mpmath route at 30 digits
    p = pair_geometry(gear_geometry(z1, 1), gear_geometry(50, 1, ToothForm(shift=sp.Rational(x2)), internal=True))
    values = [float(v) for v in (p.gear1.base_diameter / 2, p.gear2.base_diameter / 2, p.gear1.tip_diameter / 2,
                                 p.gear2.tip_diameter / 2, p.centre_distance, p.working_pressure_angle)]
    assert interferences(float(z1), 50.0, True, *values) == p.interferences() == ("trimming",)


def test_trochoid_interference_of_standard_internal_gears_needs_a_small_tooth_difference():
    # SDP-SI 5.2 (b): with a standard internal gear at 20 deg, trochoid interference is avoided when z2 - z1 > 9
    for z1 in (20, 40, 60):
        assert pair_geometry(gear_geometry(z1, 1), gear_geometry(z1 + 10, 1, internal=True))._trochoid_ok()
        p = pair_geometry(gear_geometry(z1, 1), gear_geometry(z1 + 7, 1, internal=True))
        assert any(q.startswith("tip interference") for q in p.problems())


def test_involute_interference_of_an_internal_mesh_is_named():
    # SDP-SI 5.2: a pinion cutter of 15 to 22 teeth meets a standard internal gear with involute interference
    p = pair_geometry(gear_geometry(18, 1), gear_geometry(72, 1, internal=True))
    assert any(q.startswith("involute interference") for q in p.problems())
    assert not any(q.startswith("involute") for q in pair_geometry(gear_geometry(30, 1),
                                                                      gear_geometry(72, 1, internal=True)).problems())


def _tip_reaches_past(z_tip: int, z_other: int, m: float = 2) -> bool:
    """By hand (KHK / SDP-SI 5.2): the tip of the z_tip gear reaches past the interference point of the other,
    where the line of action touches its base circle: sqrt(r_a^2 - r_b^2) > a sin(alpha), standard gears at 20 deg."""
    a = math.radians(20)
    ra, rb = m * z_tip / 2 + m, m * z_tip / 2 * math.cos(a)
    return math.sqrt(ra**2 - rb**2) > m * (z_tip + z_other) / 2 * math.sin(a)


@pytest.mark.parametrize("z1, z2", [(12, 12), (10, 11), (11, 10)])
def test_each_involute_interference_of_an_external_mesh_is_named_once(z1, z2):
    # two 12-tooth gears (a sun and its planet): both tips reach past the other's interference point, and the two
    # sentences, naming the gears by their teeth, were one sentence printed twice
    by_hand = [_tip_reaches_past(z1, z2), _tip_reaches_past(z2, z1)]
    assert by_hand == [True, True]
    problems = pair_geometry(gear_geometry(z1, 2), gear_geometry(z2, 2)).problems()
    found = [q for q in problems if q.startswith("involute interference")]
    assert len(found) == len({z1, z2})
    assert len(problems) == len(set(problems))


def _contact_ratio_by_intersection(p) -> float:
    """The line of action (through the pitch point, at a_w to the tangent of the pitch circles) cut by the tip
    circles, each cut found by root finding along the line; the path of contact over the base pitch."""
    g1, g2 = p.gear1, p.gear2
    aw, a = float(p.working_pressure_angle), float(p.centre_distance)
    z1, z2 = int(g1.teeth), int(g2.teeth)
    rw1 = a * z1 / ((z2 - z1) if p.internal else (z1 + z2))
    o1, o2 = (0.0, 0.0), ((-a, 0.0) if p.internal else (a, 0.0))
    pitch_point, d = (rw1, 0.0), (-math.sin(aw), math.cos(aw))

    def dist(o, s):
        return math.hypot(pitch_point[0] + s * d[0] - o[0], pitch_point[1] + s * d[1] - o[1])

    def cuts(o, r):
        foot = (o[0] - pitch_point[0]) * d[0] + (o[1] - pitch_point[1]) * d[1]
        return (brentq(lambda s: dist(o, s) - r, foot - 10 * r, foot), brentq(lambda s: dist(o, s) - r, foot, foot + 10 * r))

    lo1, hi1 = cuts(o1, float(g1.tip_diameter) / 2)
    lo2, hi2 = cuts(o2, float(g2.tip_diameter) / 2)
    if p.internal:  # inside the pinion's tip circle and outside the ring's, on the pitch point's side
        lo, hi = (lo1, min(hi1, lo2)) if lo2 > 0 else (max(lo1, hi2), hi1)
    else:
        lo, hi = max(lo1, lo2), min(hi1, hi2)
    return (hi - lo) / (math.pi * float(g1.module) * math.cos(float(g1.form.alpha)))


@pytest.mark.parametrize("z1, x1, z2, x2, internal", [(12, "0.4", 30, "0.1", False), (17, "0", 55, "-0.2", False),
                                                      (20, "0", 60, "0.3", True), (24, "0.2", 80, "0", True)])
def test_contact_ratio_by_cutting_the_line_of_action_with_the_tip_circles(z1, x1, z2, x2, internal):
    p = pair_geometry(gear_geometry(z1, 2, ToothForm(shift=sp.Rational(x1))),
                      gear_geometry(z2, 2, ToothForm(shift=sp.Rational(x2)), internal=internal))
    assert float(p.contact_ratio) == pytest.approx(_contact_ratio_by_intersection(p), rel=1e-9)


def test_inverse_involute_agrees_with_a_float_root_finder():
    for a in (0.05, 0.3, 0.6, 1.2):
        assert float(inverse_involute(_inv(a))) == pytest.approx(brentq(lambda t: _inv(t) - _inv(a), 1e-9, 1.5), abs=1e-12)
    with pytest.raises(InputError, match="never negative"):
        inverse_involute(-0.01)


def test_shift_sum_for_a_centre_distance_gives_that_distance_back():
    g1, g2 = gear_geometry(20, 1), gear_geometry(99, 1)
    needed = shift_sum_for(g1, g2, 60)
    # inv a_w = inv a + 2 tan a (x1 + x2) / (z1 + z2), a_w = a cos a / cos a_w, typed here with floats
    aw = brentq(lambda t: _inv(t) - (_inv(math.pi / 9) + 2 * math.tan(math.pi / 9) * float(needed) / 119), 0.1, 1.2)
    assert 59.5 * math.cos(math.pi / 9) / math.cos(aw) == pytest.approx(60, abs=1e-12)
    p = pair_geometry(gear_geometry(20, 1, ToothForm(shift=sp.Rational(f"{float(needed):.12f}"))), g2)
    assert float(p.centre_distance) == pytest.approx(60, abs=1e-9)
    with pytest.raises(InputError, match="base circles would overlap"):
        shift_sum_for(g1, g2, 50)


def test_mismatched_gears_are_refused():
    with pytest.raises(InputError, match="share their module"):
        pair_geometry(gear_geometry(20, 1), gear_geometry(30, 2))
    with pytest.raises(InputError, match="share their pressure angle"):
        pair_geometry(gear_geometry(20, 1), gear_geometry(30, 1, ToothForm(pressure_angle=25)))
    with pytest.raises(InputError, match="cannot hold"):
        pair_geometry(gear_geometry(40, 1), gear_geometry(30, 1, internal=True))
    with pytest.raises(InputError, match="two internal gears"):
        pair_geometry(gear_geometry(40, 1, internal=True), gear_geometry(30, 1, internal=True))
