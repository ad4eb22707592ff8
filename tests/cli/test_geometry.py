"""``symkin geometry``: the table per gear and per mesh, problems printed with exit 0, JSON keys,
DXF and SVG written whole, bad input refused in one line with exit 2."""

from __future__ import annotations

import io
import json
import re

import ezdxf
import pytest

from symkin.cli import main
from tests.support.train_texts import SYMBOLIC_SIMPLE


def run(capsys, *argv):
    code = main(["geometry", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_the_table_lists_gears_meshes_and_problems(capsys):
    code, out, err = run(capsys, "--train", "wolfrom")
    assert code == 0 and err == ""
    assert "gear " in out and "eps_alpha" in out
    assert "problem: gear s: undercut: shift 0.0000 is below 0.2981" in out
    assert "problem: mesh s-p1: involute interference" in out


def test_json_has_the_issue_keys(capsys):
    code, out, _ = run(capsys, "--train", "simple", "--json")
    data = json.loads(out)
    assert code == 0 and data["problems"] == [] and data["units"] == {"length": "mm", "angle": "deg"}
    s = data["gears"]["s"]
    assert {"teeth", "shift", "reference_diameter", "base_diameter", "tip_diameter", "root_diameter", "tip_thickness",
            "undercut"} <= set(s)
    assert (s["teeth"], s["reference_diameter"], s["tip_diameter"], s["root_diameter"]) == (24, 24.0, 26.0, 21.5)
    mesh = data["meshes"][0]
    assert {"gears", "centre_distance", "working_pressure_angle_deg", "contact_ratio", "problems"} <= set(mesh)
    assert mesh["gears"] == ["s", "p"] and mesh["centre_distance"] == 24.0 and mesh["working_pressure_angle_deg"] == 20.0


def test_choose_shifts_makes_ferguson_buildable(capsys):
    code, out, _ = run(capsys, "--train", "ferguson", "--json")
    assert code == 0 and len(json.loads(out)["problems"]) >= 2
    code, out, _ = run(capsys, "--train", "ferguson", "--choose-shifts", "--json")
    data = json.loads(out)
    assert code == 0 and data["problems"] == []
    assert set(data["chosen_shifts"]) == {"p", "s1", "s2", "s3"}
    assert all(m["centre_distance"] == 60 for m in data["meshes"])


def test_min_contact_ratio_reports_meshes_below_it(capsys):
    _, out, _ = run(capsys, "--train", "simple", "--min-contact-ratio", "1.8", "--json")
    problems = json.loads(out)["problems"]
    assert problems == ["mesh s-p: contact ratio 1.602 below 1.8"]


def test_dxf_and_svg_are_written(capsys, tmp_path):
    dxf, svg = tmp_path / "simple.dxf", tmp_path / "simple.svg"
    code, out, _ = run(capsys, "--train", "simple", "--out", str(dxf))
    assert code == 0 and f"wrote {dxf}" in out
    doc = ezdxf.read(io.StringIO(dxf.read_text()))
    assert not doc.audit().has_errors
    assert sorted(layer.dxf.name for layer in doc.layers if layer.dxf.name.startswith("gear-")) == ["gear-p", "gear-r",
                                                                                                     "gear-s"]
    code, _, _ = run(capsys, "--train", "simple", "--out", str(svg), "--json")
    assert code == 0 and svg.read_text().startswith("<?xml")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["simple.dxf", "simple.svg"]  # no partial files left


@pytest.mark.parametrize("argv, message", [
    (("--train", "simple", "--out", "g.png"), "give a file ending in .dxf or .svg"),
    (("--train", "simple", "--min-contact-ratio", "-1"), "must be positive"),
    (("--train", "nosuch"), "no such file"),
    (("--train", "bevel-differential", "--out", "b.svg"), "no spur gears to draw"),
])
def test_bad_input_is_one_line_and_exit_2(capsys, argv, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, *argv)
    assert code == 2 and message in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_a_bevel_train_reports_that_its_gears_are_not_covered(capsys):
    code, out, _ = run(capsys, "--train", "bevel-differential", "--json")
    data = json.loads(out)
    assert code == 0 and data["gears"] == {} and data["meshes"] == []
    assert len(data["notes"]) == 3 and all("bevel gear" in n for n in data["notes"])


def test_an_earlier_file_of_another_kind_is_kept(capsys, tmp_path):
    notes = tmp_path / "notes.dxf"
    notes.write_text("my notes\n")
    code, _, err = run(capsys, "--train", "simple", "--out", str(notes))
    assert code == 2 and "is not a DXF drawing" in err and notes.read_text() == "my notes\n"


def test_a_train_file_with_shifts_and_a_centre_distance(capsys, tmp_path):
    # the KHK pair (z 12/24, m 3, x 0.6/0.36) as a train: its shifts ask for 56.4999 mm; given that distance
    # (to 4 decimals) the shifts give it within the stated 1e-4, and the table says no distance problem
    text = """
module = 3
meshes = [{ gears = ["a", "b"]DISTANCE }]
[links.A]
gears = { a = { teeth = 12, shift = 0.6 } }
[links.C]
[links.B]
carrier = "C"
gears = { b = { teeth = 24, shift = 0.36 } }
"""
    path = tmp_path / "pair.toml"
    path.write_text(text.replace("DISTANCE", ""))
    code, out, _ = run(capsys, "--train", str(path), "--json")
    data = json.loads(out)
    assert code == 0 and round(data["meshes"][0]["working_pressure_angle_deg"], 4) == 26.0886
    assert "add centre_distance = 56.4999 to this mesh" in data["meshes"][0]["problems"][0]
    path.write_text(text.replace("DISTANCE", ", centre_distance = 56.4999"))
    code, out, _ = run(capsys, "--train", str(path), "--json")
    data = json.loads(out)
    assert code == 0 and data["meshes"][0]["centre_distance"] == 56.4999
    assert not any("centre distance" in p for p in data["problems"])


def test_a_sun_and_planet_of_12_teeth_print_each_problem_once(capsys, tmp_path):
    # both 12-tooth tips reach past the other's interference point (by hand in tests/geometry/test_mesh.py); the
    # sentence names the gears by their teeth, so it is one problem, printed once (it was printed twice)
    path = tmp_path / "s12.toml"
    teeth = {'"z1"': "12", '"z2"': "12", '"z3"': "36"}
    path.write_text("module = 2\n" + re.sub('"z[123]"', lambda m: teeth[m.group()], SYMBOLIC_SIMPLE))
    code, out, _ = run(capsys, "--train", str(path))
    problems = [line for line in out.splitlines() if line.startswith("problem: ")]
    assert code == 0 and len(problems) == len(set(problems))
    assert sum(line.startswith("problem: mesh s-p: involute interference") for line in problems) == 1


def test_choose_shifts_clears_the_double_pinion_ring_and_says_why_the_ravigneaux_ring_stays(capsys):
    # double-pinion: the ring's involute interference with its 18-tooth pinion is cleared by x_r = +0.0423 (the
    # published condition by hand in tests/geometry/test_train.py); ravigneaux: no shift clears it without
    # undercutting the short pinion p1, and one line says so
    code, out, _ = run(capsys, "--train", "double-pinion")
    assert code == 0 and "problem: mesh p2-r: involute interference" in out
    code, out, _ = run(capsys, "--train", "double-pinion", "--choose-shifts", "--json")
    data = json.loads(out)
    assert code == 0 and data["problems"] == [] and data["notes"] == []
    assert data["chosen_shifts"]["r"] == pytest.approx(0.0423, abs=1e-4)
    code, out, _ = run(capsys, "--train", "ravigneaux", "--choose-shifts")
    assert code == 0 and "problem: mesh p2-r: involute interference" in out
    (note,) = [line for line in out.splitlines() if line.startswith("note: ")]
    assert note.startswith("note: mesh p2-r (involute interference): no profile shift along the coaxial condition "
                           "clears it without undercutting gear p1; change the tooth numbers")
