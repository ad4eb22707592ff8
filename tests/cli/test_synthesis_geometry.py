"""``symkin synthesize`` reports each design's gear geometry and leaves out what cannot be made:
undercut gears (unless --allow-undercut) and contact ratios below --min-contact-ratio."""

from __future__ import annotations

import json

from symkin.cli import main
from symkin.geometry import gear_geometry, pair_geometry

SIMPLE = ("synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R", "--ratio", "4",
          "--planets", "3", "--zmax", "80", "--quiet")


def run(capsys, *argv):
    code = main([*SIMPLE, *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_zmin_12_warns_of_undercut_and_leaves_undercut_designs_out(capsys):
    code, out, _ = run(capsys, "--zmin", "12")
    assert code == 0
    assert "note: gears of fewer than 18 teeth are undercut unshifted" in out
    assert "note: 2 of the best 5 designs were left out for undercut" in out
    code, out, _ = run(capsys, "--zmin", "12", "--allow-undercut", "--json")
    data = json.loads(out)
    teeth = [d["teeth"]["s"] for d in data["designs"]]
    assert code == 0 and teeth[:2] == [12, 15]
    assert data["designs"][0]["geometry"]["undercut"] is True
    assert "design 1: gear s: undercut: shift 0.0000 is below 0.2981, the least that cuts none" in data["notes"]


def test_each_design_comes_with_its_contact_ratios_and_min_contact_ratio_filters(capsys):
    code, out, _ = run(capsys, "--zmin", "18", "--min-contact-ratio", "1.55", "--json")
    data = json.loads(out)
    assert code == 0
    for d in data["designs"]:
        z = d["teeth"]
        # the textbook contact ratios of the two meshes, from the published formula (tests/geometry/test_mesh.py)
        eps = [float(pair_geometry(gear_geometry(z["s"], 1), gear_geometry(z["p"], 1)).contact_ratio),
               float(pair_geometry(gear_geometry(z["p"], 1), gear_geometry(z["r"], 1, internal=True)).contact_ratio)]
        assert d["geometry"]["contact_ratio_min"] == min(eps) >= 1.55
    assert [d["teeth"]["s"] for d in data["designs"]] == [21, 24]  # 18/18/54 has 1.530
    assert any("left out for undercut or a contact ratio below 31/20" in n for n in data["notes"])


def test_ravigneaux_designs_come_with_contact_ratios(capsys):
    code = main(["synthesize", "--train", "ravigneaux", "--driver", "S1", "--driven", "R", "--fixed", "C",
                 "--ratio-range", "2.3,2.4", "--planets", "3", "--zmax", "60", "--top", "2", "--quiet", "--json"])
    data = json.loads(capsys.readouterr().out)
    assert code == 0 and len(data["designs"]) == 2
    assert all(1.2 < d["geometry"]["contact_ratio_min"] < 2 for d in data["designs"])
