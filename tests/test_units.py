"""Quantities with units at the boundary (pint): conversions against factors worked by hand
and against pint's own floats, the same results as bare numbers in symkin's units, JSON that
states its units, and one-line errors for a unit of the wrong kind or no unit at all."""

import json
import math
import subprocess
import sys

import pytest
import sympy as sp

from symkin import schemes
from symkin.cli import main
from symkin.errors import InputError, TextInputError
from symkin.parsing import parse, parse_quantity
from symkin.units import factor, quantity

pint = pytest.importorskip("pint")
ureg = pint.get_application_registry()


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# by hand: 1 rpm = 2 pi rad / 60 s; 1 deg = pi/180 rad; 1 inch = 25.4 mm exactly; 1 min = 60 s
@pytest.mark.parametrize("text, unit, exact", [
    ("300 rpm", "rad/s", 300 * 2 * sp.pi / 60),
    ("300rpm", "rad/s", 10 * sp.pi),
    ("90deg/s", "rad/s", sp.pi / 2),
    ("2*pi rad/s", "rad/s", 2 * sp.pi),
    ("0.5 revolution/s", "rad/s", sp.pi),
    ("10 deg", "rad", sp.pi / 18),
    ("0.25 turn", "rad", sp.pi / 2),
    ("5 mm", "m", sp.Rational(1, 200)),
    ("0.8 inch", "m", sp.Rational(8, 10) * sp.Rational(254, 10000)),
    ("1250ms", "s", sp.Rational(5, 4)),
    ("2 min", "s", 120),
    ("1e3rpm", "rad/s", 1000 * sp.pi / 30),
    ("sqrt(2) mm", "m", sp.sqrt(2) / 1000),
    ("3/4", "rad/s", sp.Rational(3, 4)),          # no unit: symkin's unit, as before
])
def test_text_with_a_unit_is_converted_exactly(text, unit, exact):
    assert sp.simplify(parse_quantity(text, unit) - exact) == 0


@pytest.mark.parametrize("src, dst", [("rpm", "rad/s"), ("deg/s", "rad/s"), ("deg", "rad"), ("arcminute", "rad"),
                                      ("mm", "m"), ("inch", "m"), ("foot", "m"), ("ms", "s"), ("hour", "s"),
                                      ("revolution/minute", "deg/s"), ("mm/s", "m/s")])
def test_exact_factors_agree_with_pints_floats(src, dst):
    assert math.isclose(float(factor(src, dst)), ureg.Quantity(1.0, src).to(dst).magnitude, rel_tol=1e-15)


def test_pint_quantities_are_taken_exactly_and_give_what_bare_numbers_give():
    aa = schemes.two_row("AA", teeth=(54, 45, 44, 55))
    by_hand = aa.speeds({"1": 10 * sp.pi, "4": 0})
    for given in (ureg.Quantity(300, "rpm"), parse("300 rpm", unit="rad/s"), ureg.Quantity(1800, "deg/s")):
        speeds = aa.speeds({"1": given, "4": 0})
        assert all(sp.simplify(speeds[k] - by_hand[k]) == 0 for k in ("1", "23", "H", "4"))
    # the AA ratio i_1H^(4) = 1 - z2 z4 / (z1 z3) = -1/24, so omega_H = -24 omega_1
    assert aa.speeds({"1": 300 * ureg.rpm, "4": 0})["H"] == -240 * sp.pi
    with pytest.raises(TextInputError, match=r"symkin.parse\('300 rpm', unit='rad/s'\)"):  # text is read by the parser
        aa.speeds({"1": "300 rpm", "4": 0})
    assert quantity(ureg.Quantity(1.5, "deg"), "rad") == sp.pi / 120
    motion = aa.motion({"1": ureg.Quantity(60, "rpm"), "4": 0})
    assert motion.inputs == aa.motion({"1": 2 * sp.pi, "4": 0}).inputs


@pytest.mark.parametrize("text, unit, message", [
    ("3 kg", "m", "kg is not a unit of m"),
    ("300 rpm", "s", "rpm is not a unit of s"),
    ("5 furlong", "rad/s", "not a unit of rad/s"),
    ("3 rpmx", "rad/s", "unknown unit 'rpmx'"),
    ("3 m; import os", "m", "is not a unit"),
    ("3 __import__", "m", "unknown unit"),
    ("3 " + "m*" * 40 + "m", "m", "is not a unit"),
    ("1 m^999999999", "m", "not a unit of m"),
    ("1e400 rpm", "rad/s", "about 10.400; numbers from 1e-300 to 1e300"),   # the number's fault, not the unit's
    ("1e400", "rad/s", "about 10.400; numbers from 1e-300 to 1e300"),
    ("10**10**10 rpm", "rad/s", "exponent larger than 1000"),
    # pint takes the radian for a pure number: 5 Hz passed as 5 rad/s (neither 5 turns a second nor refused)
    ("5 Hz", "rad/s", "Hz gives no angle, and rad/s measures one"),
    ("2 Hz/s", "rad/s^2", "gives no angle"),
    # a number mistyped: 1e was read as 1 of the unit e (the elementary charge), 1,5 as a tuple
    ("1e", "rad/s", "'1e' is not a number: an exponent needs its digits, as in 1e3"),
    ("2.5E-", "rad/s", "as in 2.5E-3"),
    ("1,5", "rad/s", "'1,5' is not a number: write a decimal point, as in 1.5"),
    ("3 rad*m", "m", "m \\* rad measures an angle, and m does not"),
    ("30 percent", "rad", "% gives no angle, and rad measures one; write it in a unit such as deg, rad, turn"),
])
def test_bad_units_are_one_line_errors(text, unit, message):
    with pytest.raises(InputError, match=message) as err:
        parse_quantity(text, unit, what="--length")
    assert "\n" not in str(err.value)


def test_the_command_line_takes_units_and_json_states_them(capsys):
    code, out, _ = run(capsys, "speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=300rpm", "--omega", "4=0", "--json")
    assert code == 0
    with_unit = json.loads(out)
    code, out, _ = run(capsys, "speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=10*pi", "--omega", "4=0", "--json")
    bare = json.loads(out)
    assert with_unit["speeds"] == bare["speeds"] and with_unit["speeds"]["H"]["exact"] == "-240*pi"
    assert with_unit["units"] == {"speeds": "rad/s", "speeds_in_unit": "rpm"}  # the rpm given, beside rad/s
    # 100 is still 100 rad/s
    code, out, _ = run(capsys, "speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=100", "--omega", "4=0", "--json")
    assert json.loads(out)["speeds"]["1"]["exact"] == "100"


def test_cardan_takes_lengths_speeds_angles_and_times_with_units(capsys):
    code, out, _ = run(capsys, "cardan", "--length", "20mm", "--speed", "24rpm", "--carrier-angle", "30deg",
                       "--t-end", "1250ms", "--samples", "3", "--json")
    assert code == 0
    with_units = json.loads(out)
    code, out, _ = run(capsys, "cardan", "--length", "0.02", "--speed", "0.8*pi", "--carrier-angle", "pi/6",
                       "--t-end", "1.25", "--samples", "3", "--json")
    bare = json.loads(out)
    assert with_units["columns"] == bare["columns"] and with_units["mechanism"] == bare["mechanism"]
    assert with_units["units"]["columns"] == {"t": "s", "s": "m", "v": "m/s", "a": "m/s^2", "x": "m", "y": "m",
                                              "deviation": "m"}
    assert with_units["units"]["length"] == "m"


def test_turns_a_second_are_2_pi_rad_s_and_hertz_is_refused(capsys):
    assert parse_quantity("5 rps", "rad/s") == parse_quantity("5 cycle/s", "rad/s") == 10 * sp.pi
    assert parse_quantity("90 deg/s", "rad/s") == sp.pi / 2
    code, out, err = run(capsys, "speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=5Hz", "--omega", "4=0")
    assert code == 2 and out == "" and "Hz gives no angle" in err and err.strip().count("\n") == 0


def test_a_unit_of_the_wrong_kind_on_the_command_line_is_exit_2(capsys):
    code, out, err = run(capsys, "speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=3kg", "--omega", "4=0")
    assert code == 2 and out == ""
    assert err.strip().count("\n") == 0 and "kg is not a unit of rad/s" in err
    code, _, err = run(capsys, "cardan", "--length", "2 s", "--speed", "1")
    assert code == 2 and "--length: s is not a unit of m" in err


def test_a_run_without_units_does_not_import_pint():
    code = ("import sys, symkin; from symkin import schemes; "
            "schemes.two_row('AA', teeth=(54, 45, 44, 55)).speeds({'1': symkin.parse('3/4'), '4': 0}); print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


def test_symbolic_inputs_whose_class_has_no_module_pass_through():
    # an undefined SymPy function's class has __module__ None: not a quantity, taken as it is
    import sympy as sp

    from symkin import symbols as S
    from symkin.drives import AngleLaw

    theta = sp.Function("Theta")
    assert AngleLaw(theta(S.t)).angle(S.t) == theta(S.t) - theta(0)


def test_metric_factors_are_exact_decimals_and_a_decimal_magnitude_is_taken():
    # found in review: 1e-9 (nm to m) came out as 4835703278458517/4835703278458516915501542656...
    import decimal

    import pint

    from symkin.units import factor, quantity

    assert (factor("nm", "m"), factor("pm", "m"), factor("ns", "s")) == (sp.Rational(1, 10**9), sp.Rational(1, 10**12),
                                                                         sp.Rational(1, 10**9))
    assert factor("inch", "mm") == sp.Rational(127, 5) and factor("rpm", "rad/s") == sp.pi / 30
    assert quantity(pint.UnitRegistry().Quantity(decimal.Decimal("0.5"), "m"), "mm") == 500
