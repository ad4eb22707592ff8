"""The 2014 KhAI paper reproduced, and the stages / split commands."""

import json

import pytest
import sympy as sp

from symkin.cli import main
from symkin.derivations import khai2014
from symkin.papers.checks import Kind, Verdict
from symkin.papers.reproduce import run


@pytest.fixture(scope="module")
def checks():
    return khai2014.checks()


def test_every_check_is_reproduced_and_the_slips_are_the_known_ones(checks):
    bad = [(c.label, c.comparison.detail) for c in checks if not c.verdict.ok]
    assert not bad
    explained = {c.label: c.verdict for c in checks if c.verdict in (Verdict.SLIP, Verdict.ERROR)}
    assert explained == {
        "fig. 4 FF value": Verdict.SLIP, "(6)": Verdict.SLIP, "(2) closed sum": Verdict.ERROR,
        "fig. 1 regression line": Verdict.ERROR, "fig. 3 optimisation result": Verdict.ERROR,
    }
    by_label = {c.label: c for c in checks}
    # checks that do not reproduce a printed item are kept apart
    assert by_label["(6)"].kind is Kind.EXTENSION and by_label["(8)"].kind is Kind.EXTENSION
    # (7)'s slope is arithmetic on the paper's own two points: a consistency check, not a reproduction
    assert {c.label for c in checks if c.kind is Kind.CONSISTENCY} == {"fig. 4 optimum (MathCAD)", "(7) slope"}
    # the figure references are settled by the captions, not by the engine: weak, and said so
    for label in ("fig. 1 regression line", "fig. 3 optimisation result"):
        assert by_label[label].strength == "weak" and "captions" in by_label[label].comparison.detail
    assert {c.label for c in checks if c.strength == "weak"} == {"fig. 1 regression line", "fig. 3 optimisation result"}
    assert all(by_label[f"KKT g_{j} - g_{j + 1}"].kind is Kind.EXTENSION for j in (1, 2, 3))
    assert by_label["stages: count"].derived == 22
    assert by_label["fig. 4 u_1"].derived == sp.Rational(6000, 1331)
    assert by_label["fig. 4 u_1"].verdict.value == "match (published value rounded)"


def test_the_gap_in_the_objective_value_is_the_frozen_mathcad_assignment(checks):
    by_label = {c.label: c for c in checks}
    a, b, U = sp.Rational("0.854"), sp.Rational("0.858"), 6000
    u1 = sp.Rational(6000, 1331)
    partial = 1 + u1 + u1 * 11 + u1 * 121  # 1 + u1 + u1 u2 + u1 u2 u3
    # the objective as (5) defines it, and as MathCAD evaluated it with Fd = a + 3 b for every stage
    value = by_label["fig. 4 FF value"]
    assert value.derived == b + (a + (a + b) * (partial - 1)) / U
    assert value.comparison.alternative.value == (a + 3 * b) * partial / U
    assert value.comparison.alternative.matches_published
    assert round(float(value.comparison.alternative.value), 3) == 0.343
    assert float(value.derived) == pytest.approx(1.0292137, abs=1e-7)


def test_the_printed_closed_sum_is_a_confirmed_error(checks):
    by_label = {c.label: c for c in checks}
    c = by_label["(2) closed sum"]
    assert c.verdict is Verdict.ERROR and c.comparison.confirmation.agrees_with_derived
    # by hand for two stages: Phi_1/(d_1 u_1 u_2) + Phi_2/(d_4 u_2); the printed limit j <= i gives Phi_2/d_4 instead
    u1, u2, p1, p2, d1, d4 = sp.symbols("u_1 u_2 Phi_1 Phi_2 d_1 d_4", positive=True)
    printed = (p1 / d1 + p2 / d4 * u1 * u2) / (u1 * u2)
    assert sp.simplify(printed - (p1 / (d1 * u1 * u2) + p2 / (d4 * u2))) != 0


def test_the_backlash_sum_3_and_the_centre_distances(checks):
    by_label = {c.label: c for c in checks}
    assert by_label["(3)"].verdict is Verdict.MATCH
    assert by_label["step 1 centre distances"].verdict is Verdict.MATCH
    assert by_label["(4)"].verdict is Verdict.MATCH


def test_figure_references_are_checked_against_the_captions(checks):
    by_label = {c.label: c for c in checks}
    assert (by_label["fig. 1 regression line"].derived, by_label["fig. 1 regression line"].published) == (2, 1)
    assert (by_label["fig. 3 optimisation result"].derived, by_label["fig. 3 optimisation result"].published) == (4, 3)


def test_reproduce_writes_report_and_figures(tmp_path):
    out = tmp_path / "r"
    (result,) = run(["khai2014"], out, quiet=True)
    assert result.ok
    data = json.loads((out / "report.json").read_text())
    assert data["papers"]["khai2014"]["ok"]
    for name in ("khai2014_stages.png", "khai2014_split.png"):
        assert (out / "figures" / name).stat().st_size > 10_000
    notes = " ".join(result.notes)
    assert "Discrete designs, tolerance 0.01: no design meets the tolerance" in notes
    assert "144/18: 9/4" in notes


def cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_stages_command(capsys):
    code, out, _ = cli(capsys, "stages", "--ring", "180", "--satellites", "3", "--zmin", "18", "--zmax", "180")
    assert code == 0 and "22 feasible, u from 9/4 to 11" in out and "assembly 42" in out
    code, out, _ = cli(capsys, "stages", "--ring", "180", "--zmin", "18", "--json")
    data = json.loads(out)
    assert data["count"] == 22 and data["stages"][-1]["ratio"] == {"exact": "11", "float": 11.0}
    assert data["stages"][-1]["sun"] == 18 and data["stages"][-1]["planet"] == 81


def test_split_command_text_json_and_plot(capsys, tmp_path):
    code, out, _ = cli(capsys, "split", "--total", "6000", "--stages", "4", "--umin", "2.25", "--umax", "11",
                       "--model", "0.854 + 0.858*u")
    assert code == 0 and "(6000/1331, 11, 11, 11)" in out and "global minimum" in out
    plot = tmp_path / "split.png"
    code, out, _ = cli(capsys, "split", "--total", "6000", "--stages", "4", "--model", "0.854 + 0.858*u",
                       "--ring", "180", "--zmin", "18", "--tolerance", "0.05", "--top", "3", "--json", "--plot", str(plot))
    data = json.loads(out)
    assert data["umin"]["exact"] == "9/4" and data["umax"]["exact"] == "11"  # from the feasible stages
    assert [r["exact"] for r in data["continuous"]["exact_ratios"]] == ["6000/1331", "11", "11", "11"]
    assert data["discrete"]["meets_tolerance"] is True
    best = data["discrete"]["designs"][0]
    assert best["teeth"] == [[54, 63, 180], [18, 81, 180], [18, 81, 180], [18, 81, 180]]
    assert plot.stat().st_size > 10_000 and not plot.with_suffix(".pdf").exists()  # the suffix chooses the format
    assert data["plot"] == [str(plot)]
    code, out, _ = cli(capsys, "split", "--total", "6000", "--stages", "4", "--model", "0.854 + 0.858*u",
                       "--ring", "180", "--zmin", "18", "--tolerance", "0.01", "--top", "2")
    assert code == 0 and "no design meets the tolerance 0.01; the nearest total ratio is 5929" in out
    code, out, _ = cli(capsys, "split", "--total", "6000", "--stages", "4", "--backlash-line", "50,7/18",
                       "--module", "0.5", "--ring", "180", "--zmin", "18", "--tolerance", "0.05")
    assert code == 0 and "Phi/d = 47*u/36 - 10/9" in out


SPLIT = ["split", "--total", "6000", "--stages", "4", "--model", "0.854 + 0.858*u"]
BAD = [
    (["stages", "--ring", "30", "--zmin", "18", "--zmax", "180"], "use a ring of at least 54 teeth"),
    (["stages", "--ring", "60", "--satellites", "7", "--zmin", "18"], "7 satellites cannot fit"),
    (["stages", "--ring", "180", "--satellites", "0"], "--satellites must be at least 1"),
    (["stages", "--ring", "180", "--satellites", "-2"], "--satellites must be at least 1"),
    (["stages", "--ring", "180", "--ha", "0"], "must be positive"),
    (["stages", "--ring", "180", "--ha", "-1"], "must be positive"),
    (["stages", "--ring", "18x"], "must be a number"),
    (SPLIT + ["--umin", "11", "--umax", "2.25"], "reversed"),
    (["split", "--total", "6000", "--stages", "4", "--backlash-line", "50,7/18", "--module", "0.5"],
     "--backlash-line needs --ring too"),
    (SPLIT + ["--umin", "2.25", "--umax", "5"], "outside what 4 stages"),
    (["split", "--total", "6000", "--stages", "2", "--umin", "2.25", "--umax", "11", "--model", "u"], "outside what 2 stages"),
    (SPLIT + ["--ring", "180", "--satellites", "0"], "--satellites must be at least 1"),
    (SPLIT + ["--ring", "180", "--ha", "0"], "must be positive"),
    (SPLIT + ["--ring", "200", "--zmin", "18", "--zmax", "180"], "outside the limits"),
    (SPLIT + ["--ring", "40", "--zmin", "18"], "use a ring of at least 54 teeth"),
    (SPLIT + ["--umin", "2.25"], "give --umin and --umax"),
    (SPLIT + ["--ring", "180", "--tolerance", "-0.01"], "must not be negative"),
    (["split", "--total", "6000", "--stages", "0", "--model", "u"], "between 1 and"),
    (["split", "--total", "6000", "--stages", "4", "--umin", "2", "--umax", "11"], "give the stage error model"),
    (["split", "--total", "6000", "--stages", "4", "--umin", "2", "--umax", "11", "--model", "__import__('os')"], "not allowed"),
    (["split", "--total", "6000", "--stages", "4", "--umin", "2", "--umax", "11", "--model", "1 - u"], "not positive"),
]


@pytest.mark.parametrize("argv, message", BAD)
def test_bad_input_one_line_exit_2(capsys, argv, message):
    code, _out, err = cli(capsys, *argv)
    assert code == 2, err
    assert message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
