"""``symkin diagram``: the files it writes, read back, its JSON, and its refusals.

The SVG is read back with the standard library's XML parser: every link of the train file
(read here with tomllib) named once as text, the state's input and output marked, and the
JSON's lever positions against the spacing Benford and Leising give a simple set.
"""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

import pytest

from symkin.cli import main

SVG = "{http://www.w3.org/2000/svg}"


def _run(capsys, *argv):
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_the_scheme_is_written_as_svg_with_every_link_named_as_text(tmp_path, capsys):
    out = tmp_path / "simple.svg"
    code, text, _ = _run(capsys, "diagram", "--train", "simple", "--state", "low", "--out", str(out))
    assert code == 0 and "kinematic scheme of simple planetary, state low written to" in text
    root = ET.parse(out).getroot()
    names = ["".join(t.itertext()) for g in root.iter(f"{SVG}g") if (g.get("id") or "").startswith("link:")
             for t in g.iter(f"{SVG}text")]
    assert sorted(names) == ["C (out)", "P", "R", "S (in)", "frame"]
    assert any("radius [mm]" in "".join(t.itertext()) for t in root.iter(f"{SVG}text"))


def test_the_json_gives_the_levers_and_the_state_s_speeds(tmp_path, capsys):
    out = tmp_path / "lever.png"
    code, text, _ = _run(capsys, "diagram", "--train", "simple", "--state", "low", "--lever", "--out", str(out), "--json")
    data = json.loads(text)
    assert code == 0 and out.stat().st_size > 1000 and out.read_bytes()[:4] == b"\x89PNG"
    assert data["kind"] == "lever" and data["state"] == "low"
    (lever,) = data["levers"]
    pos = lever["positions"]  # sun 24, ring 72: |S - C| : |C - R| = 72 : 24, C between
    assert (pos["S"] - pos["C"]) * (pos["R"] - pos["C"]) < 0
    assert abs(pos["S"] - pos["C"]) * 24 == abs(pos["R"] - pos["C"]) * 72
    assert data["speeds_per_input"]["C"]["exact"] == "1/4"  # low: 1 + z_R/z_S = 4
    assert data["units"]["length"] == "mm"


def test_length_unit_changes_the_radius_axis(tmp_path, capsys):
    out = tmp_path / "m.svg"
    code, _, _ = _run(capsys, "diagram", "--train", "wolfrom", "--length-unit", "m", "--out", str(out))
    assert code == 0
    texts = ["".join(t.itertext()) for t in ET.parse(out).getroot().iter(f"{SVG}text")]
    assert "radius [m]" in texts


@pytest.mark.parametrize("argv, message", [
    (("--train", "simple", "--state", "nope", "--out", "x.svg"), "no state 'nope'"),
    (("--train", "simple", "--out", "x.txt"), "give a file ending in .png, .pdf, .svg or .eps"),
    (("--train", "no-such-train", "--out", "x.svg"), "no ready-made train of that name"),
])
def test_bad_input_is_one_line_exit_2_and_no_file(argv, message, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = _run(capsys, "diagram", *argv)
    assert code == 2 and message in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_an_unknown_length_unit_is_refused(tmp_path, capsys):
    code, _, err = _run(capsys, "diagram", "--train", "simple", "--length-unit", "furlong", "--out", str(tmp_path / "x.svg"))
    assert code == 2 and "--length-unit 'furlong': choose one of mm, cm, m, in" in err
    assert list(tmp_path.iterdir()) == []


def test_the_json_says_which_one_way_clutch_holds_and_a_free_state_has_no_speeds(tmp_path, capsys):
    """The hub in low: its ring pawls held out, the cage (slower than the ring it is driven by) drives
    the hub through its pawls: ratio w_D / w_H = w_R / w_C = 1 + z_S / z_R = 4/3 (sun 18, ring 54)."""
    out = tmp_path / "hub.svg"
    code, text, _ = _run(capsys, "diagram", "--train", "hub-3speed", "--state", "low", "--out", str(out), "--json")
    data = json.loads(text)
    assert code == 0 and data["free"] is False
    assert data["one_way"] == {"ring_pawls": "released", "cage_pawls": "holds"}
    assert data["speeds_per_input"]["H"]["exact"] == "3/4"
