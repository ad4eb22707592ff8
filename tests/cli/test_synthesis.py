"""``symkin synthesize``: the simple planetary, Wolfrom and Ravigneaux files from the command line,
text and JSON checked against ratios worked by hand, the check column, Dask, and bad input."""

import json
from fractions import Fraction

import pytest

from symkin.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def table_rows(out):
    """The rows of the designs table (after its header, which starts with '#')."""
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.strip().startswith("#"))
    return [line.split() for line in lines[start + 1:] if line.strip()[:1].isdigit()]


def test_simple_planetary_from_the_command_line(capsys):
    code, out, _ = run(capsys, "synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R",
                       "--ratio", "4", "--tolerance", "0", "--planets", "3", "--zmax", "80", "--quiet")
    assert code == 0 and "3 designs; all by ratio error" in out
    assert "assembly (P on carrier C): (z_r + z_s)/3 is an integer" in out
    rows = table_rows(out)
    assert [r[1:4] for r in rows] == [["18", "18", "54"], ["21", "21", "63"], ["24", "24", "72"]]
    assert all(r[-1] == "ok" for r in rows)


def test_efficiency_of_each_design_against_the_textbook_formula(capsys):
    code, out, _ = run(capsys, "synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R",
                       "--ratio", "4.5", "--tolerance", "0.05", "--planets", "3", "--zmax", "90", "--top", "all",
                       "--efficiency", "0.97", "--quiet", "--json")
    data = json.loads(out)
    assert code == 0 and len(data["designs"]) > 3
    eta = Fraction(97, 100)
    for d in data["designs"]:
        t = d["teeth"]
        # sun driving the carrier, ring held, by hand: basic-train efficiency eta0 = eta_sp eta_pr (both meshes
        # carry power the same way in the carrier's frame), eta = (1 + eta0 z_r/z_s) / (1 + z_r/z_s)
        u = Fraction(t["r"], t["s"])
        assert Fraction(d["efficiency"]["exact"]) == (1 + eta * eta * u) / (1 + u)
    code, out, _ = run(capsys, "synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R",
                       "--ratio", "4", "--tolerance", "0", "--planets", "3", "--zmax", "80", "--efficiency", "--quiet")
    rows = table_rows(out)
    # default 0.98 external, 0.99 internal: (1 + 0.98*0.99*3)/4 for every 4:1 set
    assert code == 0 and [r[-2] for r in rows] == ["0.97765"] * 3 and "not a ranking key" in out


def test_wolfrom_from_the_command_line_in_json(capsys):
    code, out, _ = run(capsys, "synthesize", "--train", "wolfrom", "--state", "drive", "--ratio", "76", "--tolerance",
                       "0.02", "--planets", "3", "--zmax", "80", "--top", "all", "--quiet", "--json")
    data = json.loads(out)
    assert code == 0 and data["found"] == len(data["designs"]) > 0
    for d in data["designs"]:
        t = d["teeth"]
        # Willis with the fixed ring r1: i = (1 + z_r1/z_s) / (1 - z_r1 z_p2 / (z_p1 z_r2)), worked here
        i = (1 + Fraction(t["r1"], t["s"])) / (1 - Fraction(t["r1"] * t["p2"], t["p1"] * t["r2"]))
        assert Fraction(d["ratio"]["exact"]) == i and abs(i - 76) <= Fraction(76 * 2, 100)
        assert d["check"]["passed"] and d["check"]["assembles"]
    kinds = [c["kind"] for c in data["conditions"]]
    assert kinds.count("coaxiality") == 2 and kinds.count("assembly") == 2
    assert all(c["latex"] for c in data["conditions"]) and data["warnings"] == []


def test_ravigneaux_from_the_command_line_with_latex(capsys):
    code, out, _ = run(capsys, "synthesize", "--train", "ravigneaux", "--driver", "S1", "--driven", "R", "--fixed", "C",
                       "--ratio", "12/5", "--tolerance", "0.005", "--planets", "3", "--zmax", "100", "--top", "5",
                       "--latex", "--quiet")
    assert code == 0 and r"\frac{z_{s1} + z_{s2}}{3} \in \mathbb{Z}" in out
    assert "z_p2 from the ratio window, z_r from coaxiality" in out
    rows = table_rows(out)
    assert len(rows) == 5 and all(r[-1] == "ok" for r in rows)
    for r in rows:  # z_s1 z_s2 z_p1 z_p2 z_r ratio: carrier held, i = z_r / z_s1; the ring coaxial with the long pinion
        s1, s2, _, p2, zr = map(int, r[1:6])
        assert Fraction(r[6]) == Fraction(zr, s1) and zr == s2 + 2 * p2


def test_the_same_answer_on_a_local_dask_cluster(capsys):
    pytest.importorskip("distributed")
    argv = ["synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R", "--ratio", "4.5",
            "--planets", "4", "--zmax", "120", "--top", "all", "--quiet", "--json"]
    code, here, _ = run(capsys, *argv)
    code2, there, _ = run(capsys, *argv, "--scheduler", "local", "--workers", "2")
    assert code == code2 == 0
    a, b = json.loads(here), json.loads(there)
    assert a["designs"] == b["designs"] and a["funnel"] == b["funnel"] and a["found"] == b["found"] > 0
    assert b["execution"]["scheduler"].startswith("local cluster of 2 workers") and b["warnings"] == []


BAD = [
    ([], "give --ratio"),
    (["--ratio", "4", "--ratio-range", "1,2"], "not both"),
    (["--ratio-range", "1"], "LO,HI"),
    (["--ratio", "40"], "outside what this train gives"),
    (["--ratio", "4", "--planets", "9"], "neighbour condition"),
    (["--ratio", "4", "--zmin", "60", "--zmax", "30"], "larger than zmax"),
    (["--ratio", "4", "--fixed", ","], "--fixed names a link"),
    (["--ratio", "4", "--time-limit", "0"], "positive number of seconds"),
    (["--ratio", "4", "--scheduler", "tcp://127.0.0.1:1"], "no Dask scheduler answered"),
    (["--ratio", "4", "--workers", "2"], "for a local Dask cluster"),
    (["--ratio", "x"], "must be a number"),
    (["--ratio", "4", "--efficiency", "1.5"], "must lie in (0, 1]"),
]


@pytest.mark.parametrize("extra, words", BAD)
def test_bad_input_is_one_line_and_exit_2(capsys, monkeypatch, extra, words):
    from symkin.synthesis import runner

    monkeypatch.setattr(runner, "CONNECT_TIMEOUT", 1)
    base = ["synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R", "--planets", "3",
            "--zmax", "100", "--quiet"]
    if "--planets" in extra:
        base = base[:base.index("--planets")] + base[base.index("--planets") + 2:]
    code, out, err = run(capsys, *base, *extra)
    assert code == 2 and len(err.strip().splitlines()) == 1 and words in err and "Traceback" not in err
    code, out, _ = run(capsys, *base, *extra, "--json")
    assert code == 2 and json.loads(out)["exit"] == 2


def test_a_state_and_a_driver_are_refused(capsys):
    code, _, err = run(capsys, "synthesize", "--train", "simple", "--state", "low", "--driver", "S", "--ratio", "4",
                       "--planets", "3", "--quiet")
    assert code == 2 and "not both" in err


def test_ranking_by_efficiency_from_the_command_line(capsys):
    # sun driving the carrier, ring held, every mesh 0.97: eta = (1 + 0.97^2 u)/(1 + u), u = z_r/z_s (by hand);
    # the designs come largest efficiency first, and each check derives it again from its own train's statics
    code, out, _ = run(capsys, "synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R",
                       "--ratio-range", "3,6", "--planets", "3", "--zmax", "60", "--top", "6", "--rank", "efficiency",
                       "--efficiency", "0.97", "--quiet", "--json")
    data = json.loads(out)
    assert code == 0 and data["rank"] == ["efficiency", "error", "size", "teeth"] and len(data["designs"]) == 6
    values = []
    for d in data["designs"]:
        u = Fraction(d["teeth"]["r"], d["teeth"]["s"])
        eta = Fraction(d["efficiency"]["exact"])
        assert eta == (1 + Fraction(97, 100) ** 2 * u) / (1 + u) == Fraction(d["check"]["efficiency"]["exact"])
        assert d["check"]["efficiency_ok"] and d["check"]["passed"]
        values.append(eta)
    assert values == sorted(values, reverse=True)
    code, out, _ = run(capsys, "synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R",
                       "--ratio-range", "3,6", "--planets", "3", "--zmax", "60", "--top", "3", "--rank",
                       "efficiency,size", "--quiet")
    assert code == 0 and "by efficiency (largest first), then size (envelope diameter), then ratio error" in out
    rows = table_rows(out)  # z_s z_p z_r ratio error size shift efficiency check; default meshes 0.98 and 0.99
    expected = [(1 + Fraction(98 * 99, 10000) * Fraction(int(r[3]), int(r[1]))) / (1 + Fraction(int(r[3]), int(r[1])))
                for r in rows]
    assert [r[-2] for r in rows] == [f"{float(e):.5f}" for e in expected] and expected == sorted(expected)[::-1]
    code, _, err = run(capsys, "synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R",
                       "--ratio", "4", "--planets", "3", "--rank", "cost", "--quiet")
    assert code == 2 and "cannot rank by 'cost'" in err and len(err.strip().splitlines()) == 1


def test_hostile_rank_keys_are_one_line_and_exit_2(capsys):
    # the hostile table's values in place of --rank's (in process: the key is refused before any derivation)
    from tests.support.hostile import HOSTILE

    for value in HOSTILE:
        code, _, err = run(capsys, "synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed",
                             "R", "--ratio", "4", "--planets", "3", "--zmax", "40", f"--rank={value}", "--quiet")
        assert code == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err, (value, err)


def test_locking_and_degenerate_designs_from_the_command_line(capsys, tmp_path):
    # a two-row II train driven from gear 1 (gear 4 held) near i0 = z2 z4/(z1 z3) = 1: designs whose efficiency
    # (1 - i0/eta0)/(1 - i0) is below zero lock, and at i0 = 1 (ratio 0) the train has no efficiency at all;
    # both ways of asking (a column, a ranking key) say so in the table and in JSON valid against the schema
    import jsonschema

    from symkin.cli import output_schema
    from tests.synthesis.test_search import TWO_ROW_II

    path = tmp_path / "ii.toml"
    path.write_text(TWO_ROW_II)
    # "--ratio-range -0.03,0.03" as two tokens: argparse alone would take "-0.03,0.03" for an option
    base = ["synthesize", "--train", str(path), "--driver", "A", "--driven", "H", "--ratio-range", "-0.03,0.03",
            "--planets", "1", "--zmin", "20", "--zmax", "30", "--top", "all", "--efficiency", "0.99", "--quiet"]
    eta0 = Fraction(99, 100) ** 2
    for extra in ([], ["--rank", "efficiency"]):
        code, out, _ = run(capsys, *base, *extra, "--json")
        data = json.loads(out)
        jsonschema.Draft202012Validator(output_schema("synthesize")).validate(data)
        assert code == 0 and data["mesh_efficiencies"] == {"g1-g2": {"exact": "99/100", "float": 0.99},
                                                           "g3-g4": {"exact": "99/100", "float": 0.99}}
        kinds = set()
        for d in data["designs"]:
            t = d["teeth"]
            i0 = Fraction(t["g2"] * t["g4"], t["g1"] * t["g3"])
            if i0 == 1:
                assert d["efficiency"] is None and d["locks"] is False
                kinds.add("none")
                continue
            eta = (1 - i0 / eta0) / (1 - i0) if i0 < 1 else (1 - i0 * eta0) / (1 - i0)
            assert Fraction(d["efficiency"]["exact"]) == eta and d["locks"] == (eta <= 0)
            kinds.add("locks" if eta <= 0 else "drives")
        assert kinds == {"none", "locks", "drives"}
        code, out, _ = run(capsys, *base, *extra)
        assert code == 0 and "(locks)" in out and "mesh efficiencies: g1-g2 0.99, g3-g4 0.99" in out
