"""The command line: ratio, speeds, reproduce; bad input gives one line and a non-zero exit."""

import json
import subprocess
import sys

import pytest
import sympy as sp

from symkin.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_ratio_text_and_json(capsys):
    code, out, _ = run(capsys, "ratio", "AA", "--teeth", "100,100,101,99", "--driver", "H", "--driven", "1", "--fixed", "4")
    assert code == 0 and "i_H1^(4) = omega_H/omega_1 = 101/2 = 50.5" in out
    code, out, _ = run(capsys, "ratio", "II", "--teeth", "200,99,100,201", "--driver", "H", "--driven", "1", "--fixed", "4", "--json")
    data = json.loads(out)
    assert data["ratio"] == {"exact": "20000/101", "float": pytest.approx(198.0198019801980)}
    assert data["coaxial"] is True and data["warnings"] == []


def test_ratio_non_coaxial_set_is_computed_with_a_note(capsys):
    code, out, err = run(capsys, "ratio", "AA", "--teeth", "100,99,100,101", "--driver", "H", "--driven", "1", "--fixed", "4")
    assert code == 0 and "= 10000" in out and "not coaxial" in err


def test_single_row_takes_three_teeth(capsys):
    code, out, _ = run(capsys, "ratio", "AI1", "--teeth", "20,30,80", "--driver", "1", "--driven", "H", "--fixed", "4")
    assert code == 0 and "= 5" in out


def test_speeds(capsys):
    _code, out, _ = run(capsys, "speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=100", "--omega", "4=0", "--json")
    data = json.loads(out)
    assert data["speeds"]["H"]["exact"] == "-2400" and data["speeds"]["1"]["given"] is True


BAD = [
    (["ratio", "AX", "--teeth", "1,2,3,4", "--driver", "H", "--driven", "1", "--fixed", "4"], "unknown scheme"),
    (["ratio", "AA", "--teeth", "100,0,101,99", "--driver", "H", "--driven", "1", "--fixed", "4"], "must be positive"),
    (["ratio", "AA", "--teeth", "100,-3,101,99", "--driver", "H", "--driven", "1", "--fixed", "4"], "must be positive"),
    (["ratio", "AA", "--teeth", "100,2.5,101,99", "--driver", "H", "--driven", "1", "--fixed", "4"], "whole number"),
    (["ratio", "AA", "--teeth", "100,x,101,99", "--driver", "H", "--driven", "1", "--fixed", "4"], "must be a number"),
    (["ratio", "AA", "--teeth", "100,nan,101,99", "--driver", "H", "--driven", "1", "--fixed", "4"], "finite"),
    (["ratio", "AA", "--teeth", "100,100,101,99", "--driver", "Q", "--driven", "1", "--fixed", "4"], "no link 'Q'"),
    (["ratio", "AA", "--teeth", "100,100,101,99", "--driver", "H", "--driven", "H", "--fixed", "4"], "same link"),
    (["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=100"], "2 degrees of freedom"),
    (["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=1", "--omega", "4=0", "--omega", "H=3"], "but 3"),
    (["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=inf", "--omega", "4=0"], "not allowed"),
    # a link given twice under one name was taken at its last value
    (["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=100", "--omega", "1=3", "--omega", "4=0"], "gives link 1 twice"),
    (["trajectory", "AA", "--teeth", "54,45,44,55", "--omega", "1=1", "--omega", "1=2", "--omega", "4=0", "--out", "t.png"],
     "gives link 1 twice"),
    (["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=__import__('os').system('touch PWNED')", "--omega", "4=0"], "not allowed"),
    (["speeds", "AA", "--teeth", "54,45,44,55", "--omega", "oops"], "LINK=VALUE"),
    (["reproduce", "nosuchpaper"], "choose all or one of alyushin2009"),
]


@pytest.mark.parametrize("argv, message", BAD)
def test_bad_input_one_line_non_zero_exit(capsys, tmp_path, monkeypatch, argv, message):
    monkeypatch.chdir(tmp_path)
    code, _out, err = run(capsys, *argv)
    assert code == 2
    assert message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not (tmp_path / "PWNED").exists()


def test_console_script_runs_as_a_process():
    proc = subprocess.run(
        [sys.executable, "-m", "symkin", "ratio", "AI", "--teeth", "20,30,20,70", "--driver", "1", "--driven", "H", "--fixed", "4"],
        capture_output=True, text=True, timeout=120,
    )
    assert proc.returncode == 0 and "= 25/4 = 6.25" in proc.stdout  # 1 + 30*70/(20*20)


def test_the_program_ends_with_its_status_its_output_and_its_exit_handlers(tmp_path):
    # console_main: everything printed (to a pipe, block-buffered), the status, the atexit handlers
    marker = tmp_path / "atexit-ran"
    code = ("import atexit, pathlib, sys; from symkin.cli import console_main; "
            f"atexit.register(pathlib.Path({str(marker)!r}).write_text, 'yes'); sys.argv[1:] = sys.argv[2:]; console_main()")
    ok = subprocess.run([sys.executable, "-c", code, "-", "ratio", "AI", "--teeth", "20,30,20,70", "--driver", "1",
                         "--driven", "H", "--fixed", "4"], capture_output=True, text=True, timeout=120)
    assert ok.returncode == 0 and "= 25/4 = 6.25" in ok.stdout and marker.read_text() == "yes"
    bad = subprocess.run([sys.executable, "-c", code, "-", "ratio", "AA", "--teeth", "1,2,3,4"], capture_output=True,
                         text=True, timeout=120)
    assert bad.returncode == 2 and "required" in bad.stderr and bad.stdout == ""


# ---- conventions shared by every command (symkin.cli.common)
def test_with_json_an_error_is_also_json_on_stdout(capsys):
    code, out, err = run(capsys, "ratio", "AA", "--teeth", "100,100,101,99", "--driver", "Q", "--driven", "1", "--fixed", "4",
                         "--json")
    assert code == 2 and len(err.strip().splitlines()) == 1
    data = json.loads(out)
    assert data["exit"] == 2 and data["error"] in err and "no link 'Q'" in data["error"]
    with pytest.raises(SystemExit) as exc:  # argparse's refusal too
        main(["ratio", "AA", "--teeth", "1,2,3,4", "--json"])
    out, err = capsys.readouterr()
    assert exc.value.code == 2 and json.loads(out)["exit"] == 2 and "required" in json.loads(out)["error"]


def test_the_no_link_message_does_not_offer_the_frame(capsys):
    code, _, err = run(capsys, "ratio", "AA", "--teeth", "100,100,101,99", "--driver", "Q", "--driven", "1", "--fixed", "4")
    assert code == 2 and "name one of 1, 2, 23, 3, 4, H" in err and " 0," not in err


def test_warnings_are_in_the_json_and_notes_in_the_text(capsys):
    argv = ["ratio", "AA", "--teeth", "100,99,100,101", "--driver", "H", "--driven", "1", "--fixed", "4"]
    code, out, err = run(capsys, *argv, "--json")
    data = json.loads(out)
    assert code == 0 and any("not coaxial" in w for w in data["warnings"]) and not err
    code, out, err = run(capsys, *argv)
    assert code == 0 and "= 10000" in out and "symkin ratio: note:" in err and "not coaxial" in err


def _options():
    from symkin.cli import build_parser

    parser = build_parser()
    for name, sub in parser._subparsers._group_actions[0].choices.items():
        for action in sub._actions:
            yield name, action


def test_every_command_has_json_and_every_angle_states_its_unit():
    from symkin.cli import build_parser

    commands = set(build_parser()._subparsers._group_actions[0].choices)
    assert {name for name, a in _options() if "--json" in a.option_strings} == commands
    angles = [(name, a) for name, a in _options()
              if any(w in a.dest for w in ("angle", "beta", "alpha")) and a.help != "==SUPPRESS=="]
    assert len(angles) >= 7
    for name, a in angles:
        assert "degrees" in a.help or "radians" in a.help, (name, a.option_strings)


def test_progress_commands_take_quiet_and_omega_is_always_link_value():
    quiet = {name for name, a in _options() if "--quiet" in a.option_strings}
    assert quiet == {"reproduce", "helical", "split", "synthesize", "animate"}
    for name, a in _options():
        if "--omega" in a.option_strings and a.help != "==SUPPRESS==":
            assert a.metavar == "LINK=VALUE", name
        if "--out" in a.option_strings:
            assert a.metavar in ("FILE", "DIR"), name


def test_an_option_value_may_begin_with_a_minus(capsys):
    """argparse took '-pi/6' for an option ('expected one argument'); a value that is not an
    option of the command is read as the value (plain negative numbers always were)."""
    code, out, err = run(capsys, "cardan", "--length", "20mm", "--speed", "1", "--carrier-angle", "-pi/6",
                         "--guide-angle", "-pi/4", "--samples", "3", "--json")
    assert code == 0, err
    mech = json.loads(out)["mechanism"]
    assert mech["carrier_angle_rad"]["exact"] == "-pi/6" and mech["guide_angle_rad"]["exact"] == "-pi/4"
    # an option name after an option is still an option: argparse says what is missing
    with pytest.raises(SystemExit) as exc:
        main(["cardan", "--length", "--speed", "1"])
    assert exc.value.code == 2 and "--length: expected one argument" in capsys.readouterr().err


def test_a_json_float_that_is_null_says_why(capsys):
    """omega_1 = -1e600 has no float: its "float" is null, and the warnings say so (they were empty)."""
    code, out, _ = run(capsys, "speeds", "AA", "--teeth", "1,1e300,1,1", "--omega", "H=1e300", "--omega", "4=0", "--json")
    data = json.loads(out)
    assert code == 0 and data["speeds"]["1"]["float"] is None
    assert sp.Integer(data["speeds"]["1"]["exact"]) == -(10**600) + 10**300  # omega_1 = omega_H (1 - z2 z4/(z1 z3))
    assert any("beyond the float range" in w for w in data["warnings"])
    # without --json no JSON is written: no note about its floats
    code, out, err = run(capsys, "speeds", "AA", "--teeth", "1,1e300,1,1", "--omega", "H=1e300", "--omega", "4=0")
    assert code == 0 and "JSON float" not in err
    # and the note says why: not finite, not real, or too large
    from symkin._util.jsonout import exact_json
    from symkin.errors import NullFloatWarning

    for value, why in ((float("inf"), "is not a finite number"), (sp.zoo, "is not a finite number"), (1 + sp.I, "is not real"),
                       (sp.Integer(10) ** 400, "is beyond the float range")):
        with pytest.warns(NullFloatWarning, match=why):
            assert exact_json(value)["float"] is None
