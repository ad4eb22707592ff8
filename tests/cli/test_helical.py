"""``symkin helical``: text and JSON output, the force check column, bad input."""

import json

import pytest

from symkin.cli import main

BASE = ["helical", "AI", "--ratio", "12", "--tolerance", "0.01", "--satellites", "3", "--mn12", "2", "--mn34", "2.5",
        "--zmax", "80", "--quiet"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_text_output_lists_designs_with_the_force_check(capsys):
    code, out, _ = run(capsys, *BASE, "--top", "3")
    assert code == 0
    assert "14 designs; the best 3" in out
    lines = [line for line in out.splitlines() if line.strip().startswith("1 ")]
    assert lines and lines[0].split()[1:5] == ["17", "51", "21", "77"] and lines[0].endswith("ok")


def test_json_output_is_exact_and_checked(capsys):
    code, out, _ = run(capsys, *BASE, "--top", "all", "--json")
    data = json.loads(out)
    assert code == 0 and data["found"] == data["listed"] == 14
    first = data["designs"][0]
    assert first["teeth"] == [17, 51, 21, 77] and first["ratio"]["exact"] == "12"
    assert first["hands"] == ["left", "right", "right", "right"]
    assert all(d["force_check"]["passed"] and d["force_check"]["axial_residual"] <= 1e-12 for d in data["designs"])
    assert all(abs(d["force_check"]["ratio_from_statics"] - d["ratio"]["float"]) < 1e-9 for d in data["designs"])


def test_an_empty_result_is_reported_not_an_error(capsys):
    code, out, _ = run(capsys, "helical", "II", "--ratio", "1/50", "--tolerance", "0.05", "-k", "3", "--mn12", "2",
                       "--mn34", "2", "--zmax", "80", "--quiet")
    assert code == 0 and "no designs:" in out and "helix angles" in out
    code, out, _ = run(capsys, "helical", "II", "--ratio", "1/50", "--tolerance", "0.05", "-k", "3", "--mn12", "2",
                       "--mn34", "2", "--zmax", "80", "--quiet", "--json")
    data = json.loads(out)
    assert code == 0 and data["found"] == 0 and data["designs"] == [] and "helix angles" in data["reason"]


BAD = [
    (["--beta-max", "45"], "strictly between 0 and 45"),
    (["--beta-min", "0"], "strictly between 0 and 45"),
    (["--beta-min", "35", "--beta-max", "20"], "exclude every design"),
    (["--zmin", "90", "--zmax", "20"], "exclude every design"),
    (["--mn12", "0"], "must be positive"),
    (["--mn34", "-2"], "must be positive"),
    (["--satellites", "0"], "at least 1"),
    (["--satellites", "2.5"], "whole number"),
    (["--ratio", "0.5"], "no existence region of scheme AI"),
    (["--ratio", "x"], "must be a number"),
    (["--tolerance", "-1"], "from 0 to less than 1"),
    # from 1 on the window holds every ratio of the sign: the search ran for minutes (as synthesize, refused)
    (["--tolerance", "1"], "from 0 to less than 1"),
    (["--top", "0"], "at least 1"),
]


@pytest.mark.parametrize("change, message", BAD)
def test_bad_input_one_line_exit_2(capsys, change, message):
    argv = list(BASE)
    for i in range(0, len(change), 2):
        flag, value = change[i], change[i + 1]
        if flag in argv:
            argv[argv.index(flag) + 1] = value
        else:
            argv += [flag, value]
    code, out, err = run(capsys, *argv)
    assert code == 2 and message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err and out == ""


def test_unknown_scheme(capsys):
    code, _, err = run(capsys, "helical", "AX", "--ratio", "2", "-k", "3", "--mn12", "2", "--mn34", "2")
    assert code == 2 and "unknown scheme" in err
