"""``symkin synthesize`` (one ratio or a whole transmission, --ratios) reports each design's gear geometry and leaves
out what cannot be made:
undercut gears (unless --allow-undercut) and contact ratios below --min-contact-ratio."""

from __future__ import annotations

import json
import math

import pytest

from symkin.cli import main
from symkin.geometry import gear_geometry, pair_geometry
from tests.support.gears import least_ring_shift

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


# A whole transmission (--ratios): the same geometry checks on every design.
LOW_OVERDRIVE = ("synthesize", "--train", "simple", "--ratios", "low=4,overdrive=0.75", "--tolerance", "0", "--absolute",
                 "--planets", "3", "--quiet", "--json")


def textbook_contact_ratio(z1: int, z2: int, internal: bool = False) -> float:
    """Unshifted spur gears of module 1 and the 20 degree rack (Niemann and Winter; Shigley): the length of
    contact over the base pitch, ra = r + m (an internal gear's tip circle r - m)."""
    alpha = math.radians(20)
    r1, r2 = z1 / 2, z2 / 2
    a = r2 - r1 if internal else r1 + r2
    reach1 = math.sqrt((r1 + 1) ** 2 - (r1 * math.cos(alpha)) ** 2)
    reach2 = math.sqrt(((r2 - 1) if internal else (r2 + 1)) ** 2 - (r2 * math.cos(alpha)) ** 2)
    length = reach1 - reach2 + a * math.sin(alpha) if internal else reach1 + reach2 - a * math.sin(alpha)
    return length / (math.pi * math.cos(alpha))


def test_a_transmission_with_a_12_tooth_sun_is_refused_unless_undercut_is_allowed(capsys):
    assert main([*LOW_OVERDRIVE, "--zmin", "12", "--zmax", "60", "--allow-undercut"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["designs"][0]["teeth"] == {"z_s": 12, "z_p": 12, "z_r": 36}  # 1 + 36/12 = 4, 36/48 = 0.75
    assert data["designs"][0]["geometry"]["undercut"] is True
    assert any(n.startswith("design 1: gear s: undercut") for n in data["notes"])
    assert main([*LOW_OVERDRIVE, "--zmin", "12", "--zmax", "60"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [d["teeth"]["z_s"] for d in data["designs"]] == [18]  # 12 and 15 undercut even shifted
    assert "2 of the best 3 designs were left out for undercut (a larger --top or --zmin lists others)" in data["notes"]


def test_a_transmission_gives_each_design_its_least_contact_ratio(capsys):
    assert main([*LOW_OVERDRIVE, "--zmax", "80"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [d["teeth"]["z_s"] for d in data["designs"]] == [18, 21, 24]
    for d in data["designs"]:
        s, p, r = d["teeth"]["z_s"], d["teeth"]["z_p"], d["teeth"]["z_r"]
        hand = min(textbook_contact_ratio(s, p), textbook_contact_ratio(p, r, internal=True))
        assert d["geometry"]["shifts"] == {} and d["geometry"]["contact_ratio_min"] == pytest.approx(hand, abs=1e-12)
    assert main([*LOW_OVERDRIVE[:-1], "--zmax", "80", "--min-contact-ratio", "1.55"]) == 0
    out = capsys.readouterr().out
    assert "z_s=18" not in out and "z_s=21" in out and "least contact ratio 1.5" in out
    assert "note: 1 of the best 3 designs was left out for undercut or a contact ratio below 31/20" in out


def test_a_wolfrom_design_with_rings_on_18_and_19_tooth_planets_gets_the_shifts_that_clear_them(capsys):
    # 38/19/18/75/76 (every mesh at its reference arm 28.5): unshifted, both rings meet their planets' flanks (involute
    # interference); the rings' least shifts by the published condition, typed in tests/support/gears.py
    code = main(["synthesize", "--train", "wolfrom", "--state", "drive", "--ratio", "76", "--tolerance", "0.02",
                 "--planets", "3", "--zmax", "80", "--quiet", "--json"])
    data = json.loads(capsys.readouterr().out)
    (design,) = [d for d in data["designs"] if d["teeth"] == {"s": 38, "p1": 19, "p2": 18, "r2": 75, "r1": 76}]
    assert code == 0 and design["geometry"]["problems"] == []
    shifts = design["geometry"]["shifts"]
    assert 0 < shifts["r1"] - least_ring_shift(19, 76) < 1e-4 and shifts["p1"] == shifts["r1"] == -shifts["s"]
    assert 0 < shifts["r2"] - least_ring_shift(18, 75) < 1e-4 and shifts["p2"] == shifts["r2"]
