"""``symkin cardan``: s, v, a on a time grid; other paths reported, bad input refused in one line."""

import json
import math

import pytest

from symkin.cli import main


def run(capsys, *argv):
    code = main(["cardan", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_table1_mechanism_text(capsys):
    code, out, _ = run(capsys, "--length", "0.02", "--speed", "0.8*pi", "--samples", "5")
    assert code == 0
    assert "path: line" in out and "period: 5/2 = 2.5 s" in out and "ratio K = 1" in out
    rows = [line.split() for line in out.splitlines()[-5:]]
    t, s, v, a = map(float, rows[2])  # t = 1.25 s: the far end, s = -2 l, at rest, a = 2 l omega^2
    assert (t, s) == (1.25, -0.04) and abs(v) < 1e-15 and a == pytest.approx(0.04 * (0.8 * math.pi) ** 2)


def test_elliptical_json(capsys):
    code, out, _ = run(capsys, "--length", "20e-3", "--speed", "0.8*pi", "-e", "0.4", "--order", "1", "--carrier-angle", "pi/2",
                       "--times", "0,0.5,1", "--json")
    data = json.loads(out)
    assert code == 0 and data["drive"] == {"kind": "elliptical", "speed_rad_s": {"exact": "4*pi/5", "float": pytest.approx(0.8 * math.pi)},
                                  "eccentricity": {"exact": "2/5", "float": 0.4}, "order": {"exact": "1", "float": 1.0}}
    assert data["mechanism"]["pin_angle_rad"]["exact"] == "-pi" and data["path"]["on_guide"] is True
    assert data["columns"]["t"] == [0.0, 0.5, 1.0] and set(data["columns"]) == {"t", "s", "v", "a"}
    # at t = 0 the carrier is at pi/2 and fastest: v = 2 l omega (1 + e)/(1 - e) sin(-pi/2)
    assert data["columns"]["v"][0] == pytest.approx(-0.04 * 0.8 * math.pi * 1.4 / 0.6)
    assert data["stroke_times"]["ratio"] > 2.8


def test_law_drive(capsys):
    code, out, _ = run(capsys, "--length", "1", "--angle-law", "t + t**3", "--t-end", "2", "--samples", "3", "--json")
    data = json.loads(out)
    assert code == 0 and data["drive"]["kind"] == "law" and data["period_s"] is None
    assert data["columns"]["s"][2] == pytest.approx(2 * math.cos(10))


@pytest.mark.parametrize(
    "extra, kind, phrase",
    [
        (["--teeth", "20,60"], "hypocycloid", "3 cusps"),
        (["--pin-radius", "0.01"], "ellipse", "semi-axes 3/100"),
        (["--pin-angle", "pi"], "line off the guide", "must be 0"),
        (["--teeth", "20,60", "--pin-radius", "0.005"], "hypotrochoid", "ring : planet = 3"),
    ],
)
def test_other_paths_are_not_errors_and_are_named(capsys, extra, kind, phrase):
    code, out, _ = run(capsys, "--length", "0.02", "--speed", "1", "--samples", "3", *extra)
    assert code == 0 and f"path: {kind}:" in out and phrase in out
    assert "no slider on the guide can follow" in out and "deviation" in out and "stroke times" not in out


BAD = [
    (["--length", "0.02", "--speed", "1", "-e", "1"], "[0, 1)"),
    (["--length", "0.02", "--speed", "1", "-e", "-0.2"], "[0, 1)"),
    (["--length", "0.02", "--speed", "1", "-e", "0.3", "--order", "0"], "--order must be positive"),
    (["--length", "0.02", "--speed", "1", "-e", "0.3", "--order", "1.5"], "order of elliptical gears is a whole number"),
    (["--length", "0.02", "--speed", "1", "-e", "0.3", "--order", "-1"], "--order must be positive"),
    (["--length", "0", "--speed", "1"], "--length must be positive"),
    (["--length", "-0.02", "--speed", "1"], "--length must be positive"),
    (["--length", "0.02", "--speed", "0"], "--speed must be positive"),
    (["--length", "0.02", "--speed", "-1"], "--speed must be positive"),
    (["--length", "0.02", "--speed", "1", "--pin-radius", "0"], "--pin-radius must be positive"),
    (["--length", "abc", "--speed", "1"], "not allowed"),
    (["--length", "0.02", "--speed", "nan"], "not allowed"),
    (["--length", "0.02", "--speed", "1", "--times", ","], "--times is empty"),
    (["--length", "0.02", "--speed", "1", "--times", "0,2,1"], "strictly increasing"),
    (["--length", "0.02", "--speed", "1", "--times", "0,0"], "strictly increasing"),
    (["--length", "0.02", "--speed", "1", "--t-start", "3", "--t-end", "1"], "must increase"),
    (["--length", "0.02", "--speed", "1", "--samples", "0"], "at least 1"),
    (["--length", "0.02", "--speed", "1", "--samples", "2.5"], "whole number"),
    (["--length", "0.02", "--speed", "1", "--teeth", "40,20"], "more teeth"),
    (["--length", "0.02"], "needs --speed"),
    (["--length", "0.02", "--speed", "1", "--order", "2"], "belong to the elliptical drive"),
    (["--length", "0.02", "--angle-law", "t"], "has no known period; give --t-end"),
    (["--length", "0.02", "--angle-law", "__import__('os')", "--t-end", "1"], "not allowed"),
    # a slider beyond floats: the refusal names the column (it said "law 1"), v = 2 l w, 10^600
    (["--length", "1e300", "--speed", "1e300"], "the slider's velocity v holds a number of about 10^600"),
    (["--length", "0.02", "--speed", "1", "-e", "(1+10**-300)**(1/2)"], "[0, 1)"),
]


@pytest.mark.parametrize("argv, message", BAD)
def test_bad_input_one_line_exit_2(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2 and message in err, err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err and not out


def test_the_former_omega_still_works_with_a_deprecation_note(capsys):
    code, out, err = run(capsys, "--length", "0.02", "--omega", "0.8*pi", "--samples", "3", "--json")
    data = json.loads(out)
    assert code == 0 and data["drive"]["speed_rad_s"]["exact"] == "4*pi/5"
    assert any("--omega W is deprecated" in w for w in data["warnings"])
    code, out, err = run(capsys, "--length", "0.02", "--omega", "1", "--speed", "1")
    assert code == 2 and "give --speed only" in err


def test_m_is_no_longer_the_order(capsys):
    with pytest.raises(SystemExit):
        run(capsys, "--length", "0.02", "--speed", "1", "-e", "0.3", "-m", "2")
    assert "unrecognized arguments: -m" in capsys.readouterr().err


# exact values beyond int64 (issue 35): sqrt(10**40 + 1) reached NumPy's sqrt as a Python integer (exit 3), and
# a speed of 900 digits near 1 was refused as "law 0 holds a number of about 10^900"; both are ordinary floats.
@pytest.mark.parametrize("length, speed", [
    ("sqrt(10**40+1)", "1"),
    ("(1-10**-300)**(1/2)", "1"),
    ("(1-10**-300)**3", "1"),
    ("1", "(1-10**-300)**3"),
    ("2", "sqrt(10**40+1)/10**20"),
    ("(2+cos(10**30))*sqrt(10**30+7)", "(1+10**-30)**(1/3)"),
])
def test_exact_values_beyond_int64_give_the_50_digit_slider(capsys, length, speed):
    mpmath = pytest.importorskip("mpmath")
    times = [0.0, 0.5, 1.0, 2.5, 4.0]
    code, out, err = run(capsys, "--length", length, "--speed", speed, "--times", ",".join(map(str, times)), "--json")
    assert code == 0, err
    columns = json.loads(out)["columns"]
    # the textbook slider (guide and carrier at 0): s = 2 l cos(w t), v = -2 l w sin(w t), a = -2 l w^2 cos(w t),
    # with l and w typed as mpmath expressions at 50 digits
    with mpmath.workdps(50):
        env = {"sqrt": mpmath.sqrt, "cos": mpmath.cos, "mpf": mpmath.mpf}
        l, w = (eval(text.replace("10**", "mpf(10)**").replace("1/2", "mpf(1)/2").replace("1/3", "mpf(1)/3"), env)
                for text in (length, speed))
        for i, t in enumerate(times):
            wt = w * mpmath.mpf(t)
            want = {"s": 2 * l * mpmath.cos(wt), "v": -2 * l * w * mpmath.sin(wt), "a": -2 * l * w**2 * mpmath.cos(wt)}
            scale = float(2 * l * max(w, w**2))  # the amplitude: near a zero of cos or sin, digits count against it
            for key, value in want.items():
                assert abs(columns[key][i] - float(value)) <= 4e-16 * scale, (key, t)
