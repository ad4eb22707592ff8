"""Where the input is at fault, the answer is one line and exit 2, within seconds; never an
internal error (exit 3), a silent -inf, or a message that blames the wrong thing."""

import json
import re
import time
import warnings

import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin import symbols as S
from symkin.cli import main
from symkin.errors import FloatOverflowWarning, PoleWarning

AA = ["AA", "--teeth", "54,45,44,55"]
AI1 = ["AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1"]
TOWER = "(sqrt(2)**999)**999"  # 2^(999*999/2), about 10^150214


def run(capsys, *argv):
    start = time.perf_counter()
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err, time.perf_counter() - start


def one_line_error(err):
    lines = err.strip().splitlines()
    return len(lines) == 1 and "error:" in lines[0] and "Traceback" not in err


@pytest.mark.parametrize("argv", [
    ["speeds", *AA, "--omega", f"1={TOWER}", "--omega", "4=0"],
    ["trajectory", *AI1, "--point", f"2:{TOWER},0", "--out", "t.png"],
    ["cardan", "--length", "1", "--speed", TOWER, "--samples", "3"],
    ["cardan", "--length", "1", "--carrier-angle", TOWER, "--speed", "1", "--samples", "3"],
    ["cardan", "--length", "1", "--angle-law", f"t + {TOWER}", "--times", "0,1"],
    ["split", "--total", "100", "--stages", "2", "--umin", "2", "--umax", "12", "--model", f"1 + u/{TOWER}"],
], ids=["speeds --omega", "trajectory --point", "cardan --speed", "cardan --carrier-angle", "cardan --angle-law",
        "split --model"])
def test_a_tower_is_refused_with_its_size(argv, capsys, tmp_path, monkeypatch):
    # on c69a8be: speeds and trajectory ended in an internal error (int-to-str ValueError), cardan
    # blamed an empty time span
    monkeypatch.chdir(tmp_path)
    code, _, err, seconds = run(capsys, *argv)
    assert code == 2 and one_line_error(err) and seconds < 8
    assert "is about 10^150214; numbers from 1e-300 to 1e300 in size are accepted" in err


def test_speeds_refuses_a_speed_beyond_the_bounds_instead_of_printing_minus_infinity(capsys):
    # on c69a8be: exit 0, speeds of -inf, and an empty warnings list
    code, out, err, _ = run(capsys, "speeds", *AA, "--omega", "1=exp(1000)", "--omega", "4=0", "--json")
    assert code == 2 and one_line_error(err) and "exp(1000) is about 10^434" in err
    assert json.loads(out)["exit"] == 2


def test_cardan_says_the_speed_is_too_large_not_that_the_times_do_not_increase(capsys):
    code, _, err, _ = run(capsys, "cardan", "--length", "0.02", "--speed", "exp(1000)", "--samples", "3")
    assert code == 2 and one_line_error(err) and "exp(1000) is about 10^434" in err and "increas" not in err


def test_a_speed_whose_square_is_beyond_floats_is_an_input_error_not_an_overflow(capsys):
    # on c69a8be: exit 3, OverflowError: int too large to convert to float (the law holds 10^600)
    for option in (["--speed", "1e300"], ["--speed", "1", "-e", "0.5", "--order", "1e300"]):
        code, _, err, _ = run(capsys, "cardan", "--length", "0.02", *option, "--samples", "3")
        assert code == 2 and one_line_error(err) and "beyond the float64 range" in err


@pytest.mark.parametrize("option", [["--t-end", "sin(1)**2 + cos(1)**2 - 1"], ["-e", "sin(1)**2 + cos(1)**2 - 1"]],
                         ids=["--t-end", "-e"])
def test_zero_in_disguise_is_decided_not_a_type_error(option, capsys):
    # on c69a8be: exit 3, TypeError: cannot determine truth value of Relational
    code, _, err, _ = run(capsys, "cardan", "--length", "0.02", "--speed", "1", *option, "--samples", "3")
    assert code == 2 and one_line_error(err) and "to 1233 digits" in err


@pytest.mark.parametrize("option", [["--guide-angle", "1e-300"], ["--pin-angle", "1e-300"], ["-e", "exp(-690)"]])
def test_tiny_angles_and_eccentricities_are_computed_within_seconds(option, capsys):
    # on c69a8be: longer than 20 s (factoring 4*pi*t/5 - 1e-300 over ZZ[pi, t]; exp(-690) as a
    # polynomial of degree 690 in E)
    code, out, err, seconds = run(capsys, "cardan", "--length", "0.02", "--speed", "0.8*pi", *option, "--samples", "3",
                                  "--json")
    assert code == 0 and seconds < 8, err
    assert len(json.loads(out)["table"]) == 3 if "table" in json.loads(out) else True


def test_an_overflow_is_not_blamed_on_a_vanishing_denominator():
    # on c69a8be: 'a denominator vanishes there' (a PoleWarning) for a speed of 1e200 rad/s, whose
    # particle acceleration is about 1e400, beyond float64
    mech = schemes.two_row("AI")
    study = symkin.Study(mech, particles=[("23", (S.radius("1"), 0), ("acceleration",))], inputs={"1": S.omega("1"), "4": 0})
    values = {"omega_1": 1e200, "r_1": 1.0, "r_2": 2.0, "r_3": 1.0, "r_4": 4.0}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = study.evaluate(values, t=np.array([0.0]))
    kinds = {w.category for w in caught if issubclass(w.category, symkin.SymkinWarning)}
    assert kinds == {FloatOverflowWarning}
    message = str(next(w.message for w in caught if w.category is FloatOverflowWarning))
    # the exact law at t = 0, an independent route to the size the message gives
    wx = mech.motion({"1": S.omega("1"), "4": 0}).particle("23", (S.radius("1"), 0)).acceleration[0]
    exact = wx.subs({S.t: 0, **{sp.Symbol(k, positive=True) if k != "omega_1" else S.omega("1"): sp.Rational(v) for k, v
                                 in values.items()}})
    assert f"about 10^{int(sp.floor(sp.log(abs(exact), 10)))}" in message and "not a pole" in message
    assert not np.isfinite(next(v for k, v in out.items() if k.startswith("wx"))).all()
    # a true pole is still called one
    f = symkin.compile(schemes.two_row("AI", teeth=True).ratio("1", "H", fixed="4"))
    with pytest.warns(PoleWarning, match="a denominator vanishes"):
        f(0.0, 30, 20, 70)


def test_zero_in_disguise_prints_the_float_zero_not_a_rounding_residue(capsys):
    # before: omega_H = -1/5 + cos(1)**2/5 + sin(1)**2/5 = 8.397345134e-140 (SymPy's evalf at 17
    # digits); the exact value is 0, and the float beside it is decided on intervals
    zero = "sin(1)**2+cos(1)**2-1"
    code, out, _, _ = run(capsys, "speeds", "AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", f"1={zero}")
    assert code == 0 and "e-1" not in out
    assert [line.split("=")[-1].split("(")[0].strip() for line in out.splitlines() if line.startswith("omega_H")] == ["0"]
    code, out, _, _ = run(capsys, "speeds", "AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", f"1={zero}", "--json")
    speeds = json.loads(out)["speeds"]
    assert code == 0 and {name: s["float"] for name, s in speeds.items()} == {"1": 0.0, "2": 0.0, "H": 0.0, "4": 0.0}
    # and a number beside zero is still printed as itself
    code, out, _, _ = run(capsys, "speeds", "AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "1=sin(1)**2+cos(1)**2-1+1e-200",
                          "--json")
    assert code == 0 and json.loads(out)["speeds"]["1"]["float"] == pytest.approx(1e-200, rel=1e-12)


@pytest.mark.parametrize("text, char", [("2\u00b7pi", "U+00B7"), ("\u22121", "U+2212"), ("sin\uff081\uff09", "U+FF08"),
                                        ("1\u00a0+ 1", "U+00A0")])
def test_a_unicode_look_alike_is_named_in_the_refusal(text, char):
    # before: "'2·pi' is not a valid expression", which does not say what is wrong with it
    from symkin.parsing import parse_expression

    with pytest.raises(symkin.InputError, match=re.escape(f"({char}) is not allowed; write it in ASCII")):
        parse_expression(text, what="the speed")
