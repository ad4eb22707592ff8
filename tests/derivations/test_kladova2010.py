"""The 2010 paper reproduced: every check derived and compared, the printed errors confirmed."""

import json

import pytest
import sympy as sp

from symkin.derivations import kladova2010
from symkin.papers.checks import Kind, Verdict, item_results
from symkin.papers.reproduce import run


@pytest.fixture(scope="module")
def checks():
    return {c.label: c for c in kladova2010.checks()}


def test_every_kladova2010_check_is_reproduced(checks):
    bad = [(c.label, c.comparison.detail) for c in checks.values() if not c.verdict.ok]
    assert not bad
    for eq in ["balance", "(1)", "(2)", "(3)", "(4)", "(5)", "(6)", "(7)", "(8)", "(9)", "(10)", "(11)",
               "Table 1 AI, delta < 1", "Table 1 II, delta > 1", "synthesis: axial balance"]:
        assert eq in checks, eq
    explained = {label: c.verdict for label, c in checks.items() if c.verdict in (Verdict.SLIP, Verdict.ERROR)}
    assert explained == {
        "from (34)": Verdict.SLIP,
        **{label: Verdict.ERROR for label in ("1.1 heading", "(6) step solved", "(6) identity", "(6)", "(9)",
                                              "Table 1 AA, delta < 1", "Table 1 AA, delta > 1")},
    }
    assert {label for label, c in checks.items() if c.kind is Kind.PAPER} >= {"(2)", "Table 1 analysis"}
    not_paper = {label for label, c in checks.items() if c.kind is not Kind.PAPER}
    assert {"balance", "balance hands", "synthesis: axial balance", "synthesis: statics vs kinematics"} <= not_paper


def test_published_forms_that_are_damaged_really_differ_from_the_derivation():
    """An error must not hide a match: each printed form differs from the derived one."""
    from symkin.mechanisms.helical import balanced as HS
    from symkin.mechanisms.helical.balanced import Z

    z1, z2 = Z[1], Z[2]
    ai = HS.tooth_equations("AI").chain
    ii = HS.tooth_equations("II").chain
    assert sp.simplify(ai[z2] - kladova2010.PUBLISHED["(6)"]) != 0
    # the printed (9) Z1 = Z2 (1 - i d)/(1 - d) solved for Z2 is not the derived Z2
    printed_z2 = sp.solve(sp.Eq(z1, kladova2010.PUBLISHED["(9)"]), z2)[0]
    assert sp.simplify(printed_z2 - ii[z2]) != 0
    assert sp.simplify(HS.ratio_law("AA").rhs - kladova2010.PUBLISHED["(1)"]) != 0


def test_errors_rest_on_independent_routes(checks):
    for label in ("(6) step solved", "(6) identity", "(6)", "(9)", "Table 1 AA, delta < 1", "1.1 heading"):
        c = checks[label]
        assert c.comparison.confirmation is not None and c.comparison.confirmation.agrees_with_derived, label
        assert c.comparison.alternative is None or not c.comparison.alternative.matches_published, label
    # the spur-gear route by hand, for AI: z2 (d + 1) = z1 (i - 1 - d)
    i, d, z1 = kladova2010.i, kladova2010.delta, kladova2010.z1
    assert sp.simplify(kladova2010._spur_by_hand("AI") - z1 * (i - 1 - d) / (d + 1)) == 0
    assert checks["1.1 heading"].derived == "AI"


def test_lambda_of_2_is_solved_not_assumed(checks):
    c = checks["(2)"]
    assert c.verdict is Verdict.MATCH and "m_n12*cos(alpha_t12)/(m_n34*cos(alpha_t34))" in c.comparison.detail


def test_the_reference_34_is_the_pair_3_4(checks):
    c = checks["from (34)"]
    assert c.derived == "(3) with (1) or (3) with (4)"
    assert c.comparison.alternative.matches_published


def test_reproduce_writes_the_kladova2010_report(tmp_path):
    out = tmp_path / "report"
    results = run(["kladova2010"], out, quiet=True)
    assert all(r.ok for r in results)
    data = json.loads((out / "report.json").read_text())
    assert data["summary"]["differs"] == 0
    for name in ("kladova2010_existence_regions.png", "kladova2010_synthesis.png"):
        assert (out / "figures" / name).stat().st_size > 10_000
    assert "Table 1" in (out / "equations.tex").read_text()


def test_a_region_curve_is_not_drawn_across_a_pole():
    """The published AA bound (1 - d)/(1 - d sin(pi/3)) has a pole at d = 2/sqrt(3), where a
    400-point grid gets no closer than values of about +-60: a line through the samples would
    draw a vertical bar there (it did).  The figure's curve breaks at the sign change of the
    denominator, and nowhere else."""
    import numpy as np

    d = np.linspace(1.001, 3.5, 400)
    expr = (1 - kladova2010.DELTA) / (1 - kladova2010.DELTA * sp.sin(sp.pi / 3))
    v = kladova2010.region_curve(expr, d)
    pole = 2 / np.sqrt(3)
    gaps = np.flatnonzero(np.isnan(v))
    assert gaps.size == 1 and d[gaps[0] - 1] < pole < d[gaps[0]]
    assert np.nanmax(np.abs(v)) < 100  # the gap is not from the 1e3 clip
    finite = ~np.isnan(v)
    reference = np.array([float((1 - x) / (1 - x * np.sin(np.pi / 3))) for x in d])
    np.testing.assert_allclose(v[finite], reference[finite], rtol=1e-12)
    # a bound without a pole on the grid is drawn whole
    assert not np.isnan(kladova2010.region_curve(1 + kladova2010.DELTA, d)).any()


def test_lambda_is_a_weak_match_and_the_garbled_6_counts_once(checks):
    assert checks["(2)"].strength == "weak" and "solved from this very comparison" in checks["(2)"].comparison.detail
    items = {r.item.item: r for r in item_results(kladova2010.PRINTED_ITEMS, checks.values())}
    assert [c.label for c in items["(6)"].checks] == ["(6) step solved", "(6) identity", "(6)"]
    assert items["(6)"].verdict is Verdict.ERROR and "(6) identity" not in items


def test_the_lines_transforming_2_lead_to_the_derived_z2(checks, monkeypatch):
    lines = [checks[f"(2) transformed, line {n}"] for n in (1, 2, 3, 4)]
    assert all(c.item == "(2) transformed" and c.verdict is Verdict.MATCH for c in lines)
    # a line with a sign slip is caught: -Z2 read +Z2 in the third line
    printed = list(kladova2010.PUBLISHED["(2) transformed"])
    z2 = kladova2010.z2
    printed[2] = sp.Eq(printed[2].lhs, printed[2].rhs + 2 * z2)
    monkeypatch.setitem(kladova2010.PUBLISHED, "(2) transformed", tuple(printed))
    again = {c.label: c for c in kladova2010._section_11_checks()}
    assert again["(2) transformed, line 3"].verdict is Verdict.DIFFERS
    assert again["(2) transformed, line 4"].verdict is Verdict.MATCH
