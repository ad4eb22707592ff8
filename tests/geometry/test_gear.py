"""One gear's geometry against the ISO 21771 formulas typed here, a published worked example, and
an undercut found by moving the rack numerically."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from symkin.errors import InputError
from symkin.geometry import ToothForm, gear_geometry

ALPHA = sp.pi / 9  # 20 degrees


def test_external_gear_diameters_and_thickness_are_the_iso_21771_formulas_exactly():
    g = gear_geometry(20, 2, ToothForm(shift=sp.Rational(1, 4)))
    # d = m z, d_b = d cos a, d_a = d + 2 m (h_a* + x), d_f = d - 2 m (h_f* - x), s = m (pi/2 + 2 x tan a)
    assert g.reference_diameter == 40
    assert sp.simplify(g.base_diameter - 40 * sp.cos(ALPHA)) == 0
    assert g.tip_diameter == 40 + 2 * 2 * (1 + sp.Rational(1, 4)) == 45
    assert g.root_diameter == 40 - 2 * 2 * (sp.Rational(5, 4) - sp.Rational(1, 4)) == 36
    assert sp.simplify(g.reference_thickness - 2 * (sp.pi / 2 + 2 * sp.Rational(1, 4) * sp.tan(ALPHA))) == 0


def test_internal_gear_forms_are_the_published_ones():
    # adams.thisaray.com "Standard involute profile", internal gear: tip radius r - m (1 - x), root radius
    # r + m (1.25 + x), tooth thickness pi m / 2 - 2 x m tan a
    m, z, x = 3, 60, sp.Rational(3, 10)
    g = gear_geometry(z, m, ToothForm(shift=x), internal=True)
    r = sp.Rational(m * z, 2)
    assert g.tip_diameter / 2 == r - m * (1 - x)
    assert g.root_diameter / 2 == r + m * (sp.Rational(5, 4) + x)
    assert sp.simplify(g.reference_thickness - (sp.pi * m / 2 - 2 * x * m * sp.tan(ALPHA))) == 0


def test_the_khk_worked_example_of_a_shifted_pair():
    # KHK Gear Technical Reference, profile shifted spur gears (reproduced at
    # bolsover.com/utilitiesforalibre/profile-shifted-external-spur-gears.html): m 3, 20 deg, z 12 and 24,
    # x 0.6 and 0.36: pitch diameters 36 and 72, base 33.8289 and 67.6579, root 32.100 and 66.660
    g1 = gear_geometry(12, 3, ToothForm(shift=0.6))
    g2 = gear_geometry(24, 3, ToothForm(shift=0.36))
    assert (g1.reference_diameter, g2.reference_diameter) == (36, 72)
    assert float(g1.base_diameter) == pytest.approx(33.8289, abs=5e-5)
    assert float(g2.base_diameter) == pytest.approx(67.6579, abs=5e-5)
    assert (float(g1.root_diameter), float(g2.root_diameter)) == (32.1, 66.66)


def test_tip_thickness_and_pointed_tips():
    # s_a = d_a (s / d + inv a - inv a_a), a_a = acos(d_b / d_a), typed here for z 12, m 1, x 0.5
    g = gear_geometry(12, 1, ToothForm(shift=0.5))
    da, db = 15.0, 12 * math.cos(math.pi / 9)
    aa = math.acos(db / da)
    inv = lambda a: math.tan(a) - a  # noqa: E731
    s = math.pi / 2 + 2 * 0.5 * math.tan(math.pi / 9)
    assert float(g.tip_thickness) == pytest.approx(da * (s / 12 + inv(math.pi / 9) - inv(aa)), rel=1e-12)
    assert not g.pointed
    # a 6-tooth pinion shifted by 1 comes to a point: its flanks meet inside the tip circle
    assert gear_geometry(6, 1, ToothForm(shift=1)).pointed
    assert gear_geometry(6, 1, ToothForm(shift=1)).thin_tip


def test_minimum_shift_is_the_textbook_limit():
    for z in (8, 12, 14, 17, 30):
        g = gear_geometry(z, 1)
        # the textbook limit 1 - z sin^2(a) / 2 (KHK; h_a0* = 1) and, exactly, Autodesk Inventor's form with the
        # rack's fillet: h_a0* = h_a* + c* - r_f* (1 - sin a)
        assert float(g.minimum_shift) == pytest.approx(1 - z * math.sin(math.pi / 9) ** 2 / 2, abs=1e-4)
        a0 = 1 + sp.Rational(1, 4) - sp.Rational(19, 50) * (1 - sp.sin(ALPHA))
        assert sp.simplify(g.minimum_shift - (a0 - z * sp.sin(ALPHA) ** 2 / 2)) == 0
    # z_min = 2 / sin^2(20 deg) = 17.1: 17 teeth unshifted are (barely) undercut, 18 are not
    assert gear_geometry(17, 1).undercut and not gear_geometry(18, 1).undercut
    assert gear_geometry(12, 1, internal=True).minimum_shift is None


def _rack_cuts_the_flank(z: int, x: float) -> bool:
    """Move the rack's flank end (the corner where its straight flank ends, depth h_a0* m) past the gear
    and see whether it enters the tooth beyond the involute flank (an undercut): by plain kinematics."""
    m, a = 1.0, math.pi / 9
    r, rb = z * m / 2, z * m / 2 * math.cos(a)
    a0 = 1.25 - 0.38 * (1 - math.sin(a))
    datum = r + x * m
    u, y = math.pi * m / 4 - a0 * m * math.tan(a), datum - a0 * m  # the corner, rack frame (y away from the axis)
    phi = np.linspace(-1.5, 1.5, 200001)
    gx = (u - r * phi) * np.cos(phi) + y * np.sin(phi)
    gy = -(u - r * phi) * np.sin(phi) + y * np.cos(phi)
    rho, theta = np.hypot(gx, gy), np.arctan2(gx, gy)
    s = math.pi * m / 2 + 2 * x * m * math.tan(a)
    on = rho > rb
    ay = np.arccos(rb / rho[on])
    flank = math.pi / z - (s / (2 * r) + (math.tan(a) - a) - (np.tan(ay) - ay))
    return bool((theta[on] > flank + 1e-9).any())


@pytest.mark.parametrize("z", [10, 12, 15])
def test_undercut_limit_agrees_with_moving_the_rack(z):
    x_min = float(gear_geometry(z, 1).minimum_shift)
    assert _rack_cuts_the_flank(z, x_min - 0.01)
    assert not _rack_cuts_the_flank(z, x_min + 0.01)
    assert gear_geometry(z, 1, ToothForm(shift=sp.Rational(str(round(x_min - 0.01, 4))))).undercut
    assert not gear_geometry(z, 1, ToothForm(shift=sp.Rational(str(round(x_min + 0.01, 4))))).undercut


@pytest.mark.parametrize("kwargs, message", [
    ({"shift": 7}, "within -5 and 5"),
    ({"pressure_angle": 60}, "from 5 to 45"),
    ({"addendum": 0}, "must be positive"),
    ({"fillet": 3}, "too large"),
])
def test_bad_tooth_forms_are_one_line_errors(kwargs, message):
    with pytest.raises(InputError, match=message):
        ToothForm(**kwargs)


def test_bad_gears_are_one_line_errors():
    with pytest.raises(InputError, match="at least 3 teeth"):
        gear_geometry(2, 1)
    with pytest.raises(InputError, match="no root circle"):
        gear_geometry(3, 1, ToothForm(shift=-1))
    with pytest.raises(InputError, match="wrong side of the root circle"):
        gear_geometry(20, 1, tip_diameter=10)
