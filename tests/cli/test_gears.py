"""``symkin speeds`` prints the derived speeds in the unit the known ones were given in.

Reference: 1 rpm = pi/30 rad/s typed here, applied to the command's own rad/s values.
"""

from __future__ import annotations

import json
from fractions import Fraction

from symkin.cli import main

AA = ("speeds", "AA", "--teeth", "54,45,44,55")


def _run(capsys, *argv):
    code = main(list(argv))
    return code, capsys.readouterr().out


def test_rpm_in_gives_rpm_beside_rad_s_out(capsys):
    code, text = _run(capsys, *AA, "--omega", "1=300rpm", "--omega", "4=0")
    assert code == 0
    assert "omega_H   = -240*pi = -753.9822369 rad/s = -7200 rpm   (derived)" in text
    code, out = _run(capsys, *AA, "--omega", "1=300rpm", "--omega", "4=0", "--json")
    data = json.loads(out)
    assert data["units"] == {"speeds": "rad/s", "speeds_in_unit": "rpm"}
    for name, rpm in data["speeds_in_unit"].items():  # rad/s * 30/pi, by hand
        rad_s = data["speeds"][name]["float"]
        assert abs(rad_s * 30 / 3.141592653589793 - rpm["float"]) <= 1e-9 * (1 + abs(rpm["float"]))
    assert Fraction(data["speeds_in_unit"]["H"]["exact"]) == -7200


def test_bare_numbers_and_mixed_units_print_rad_s_only(capsys):
    for omega in (("1=100", "4=0"), ("1=300rpm", "4=1rad/s"), ("1=300rpm", "4=6deg/s")):
        code, out = _run(capsys, *AA, *(x for o in omega for x in ("--omega", o)), "--json")
        data = json.loads(out)
        assert code == 0 and "speeds_in_unit" not in data
        if omega[1] == "4=0":
            assert data["units"] == {"speeds": "rad/s"}
