"""Units out: speeds given as pint quantities come back as pint quantities in the same unit.

References: 1 rpm = 2 pi / 60 rad/s typed here; the AA scheme's speeds from bare rad/s values
(the engine's own route, without units) converted by that factor by hand.
"""

from __future__ import annotations

import pint
import sympy as sp

from symkin import schemes

UREG = pint.get_application_registry()
AA = schemes.two_row("AA", teeth=(54, 45, 44, 55))


def test_speeds_given_in_rpm_come_back_in_rpm():
    speeds = AA.speeds({"1": 300 * UREG.rpm, "4": 0})
    bare = AA.speeds({"1": 300 * 2 * sp.pi / 60, "4": 0})  # the same speed typed in rad/s
    out = speeds.quantities()
    for name in bare:
        assert out[name].units == UREG.rpm
        assert sp.simplify(out[name].magnitude - bare[name] * 60 / (2 * sp.pi)) == 0
    assert out["1"].magnitude == 300


def test_bare_speeds_come_back_in_rad_s_and_any_unit_on_request():
    speeds = AA.speeds({"1": 10, "4": 0})
    assert speeds.unit is None and speeds.quantities()["H"].units == UREG("rad/s").units
    deg = speeds.in_unit("deg/s")
    assert sp.simplify(deg["H"] - speeds["H"] * 180 / sp.pi) == 0
