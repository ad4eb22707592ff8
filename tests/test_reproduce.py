"""The 2009 paper reproduced, and the report folder written atomically."""

import json

import pytest
import sympy as sp

from symkin import schemes
from symkin import symbols as S
from symkin.derivations import alyushin2009
from symkin.papers.checks import Kind, Verdict
from symkin.papers.reproduce import report_schema, run, write_atomically


@pytest.fixture(scope="module")
def checks():
    return {c.label: c for c in alyushin2009.checks()}


def test_every_alyushin2009_check_is_reproduced(checks):
    bad = [(c.label, c.comparison.detail) for c in checks.values() if not c.verdict.ok]
    assert not bad
    labels = {label.split()[0] for label in checks}
    for eq in ["(1)", "(2)", "(3)", "(4)", "(5)", "(6)", "(7)", "(8)", "(9)", "(10)", "(11)", "(13)", "(13a)", "(13b)",
               "(14)", "(14a)", "(15)", "(17)", "(18)", "(19)", "(20)", "(22)", "(22a)", "(23a)", "(24a)", "(25a)"]:
        assert eq in labels, eq
    not_plain = {label: c.verdict for label, c in checks.items() if c.verdict is not Verdict.MATCH}
    assert not_plain == {
        "example AA 100/99/100/101 centre-distance gap": Verdict.SLIP,
        "example AA 54/45/44/55 (i_1H)": Verdict.ROUNDED,
        "example II 200/99/100/201": Verdict.ROUNDED,
    }


def test_checks_of_the_engine_against_itself_are_not_paper_items(checks):
    kinds = {label: c.kind for label, c in checks.items()}
    assert {k for k, v in kinds.items() if v is Kind.CONSISTENCY} == {
        *(f"({n}) {s}" for n in (1, 2) for s in ("AI1", "AI", "AA", "II")), "(5)-(6) engine"}
    assert {k for k, v in kinds.items() if v is Kind.EXTENSION} == {
        "coaxiality AI1", "(24a) at omega_4 = 0", "(25a) at omega_4 = 0"}


def test_the_gap_slip_rests_on_a_computed_alternative(checks):
    gap = checks["example AA 100/99/100/101 centre-distance gap"]
    m = S.module()
    assert gap.derived == m and gap.published == 2 * m
    alt = gap.comparison.alternative
    assert alt.matches_published and alt.value == 2 * m  # the pitch-diameter sums m(z1 + z2), m(z3 + z4)
    # by hand: centre distances m (z1 + z2)/2 and m (z3 + z4)/2 for z = 100, 99, 100, 101
    assert abs(m * (100 + 99) / 2 - m * (100 + 101) / 2) == m


def test_fifty_times_is_an_inequality_of_the_paper(checks):
    c = checks["example AA 100/100/101/99"]
    assert c.published == "i_H1 > 50" and c.derived == sp.Rational(101, 2) and c.verdict is Verdict.MATCH
    assert "50.5" not in repr(alyushin2009.EXAMPLES)


def test_ii_tooth_numbers_come_from_the_legible_data(checks):
    assert checks["example II z1"].derived == 200 and checks["example II z1"].verdict is Verdict.MATCH
    assert checks["example II z4"].derived == 201 and checks["example II z4"].verdict is Verdict.MATCH
    # by hand: i_H1 = 100 z1/(z1 - 99) with z4 = z1 + 1, z2 = 99, z3 = 100; only z1 = 200 rounds to 198
    assert [z for z in range(100, 1000) if round(100 * z / (z - 99)) == 198] == [200]


def test_paper_point_velocities_are_the_particle_laws(checks):
    r1, r2, r3 = (S.radius(str(i)) for i in (1, 2, 3))
    wH, w23 = S.omega("H"), S.omega("23")
    # (11) by hand: V_A = V_C - omega_23 (y_A - y_C) with y_A - y_C = -r2 (the paper's fig. 2)
    assert sp.expand(checks["(11)"].derived - (-wH * (r1 + r2) + w23 * r2)) == 0
    assert sp.expand(checks["(9)"].derived - (-wH * (r1 + r2) - w23 * r3)) == 0


def test_the_54_45_44_55_conditions(checks):
    c = checks["example AA 54/45/44/55 conditions"]
    assert c.verdict is Verdict.MATCH and "both for k = [3]" in c.derived
    # by hand: with the carrier driving, efficiency eta0 (i - 1)/(i - eta0), i = i_14^(H) = 2475/2376 > 1
    m = schemes.two_row("AA", teeth=(54, 45, 44, 55), module=1)
    i = sp.Rational(45 * 55, 54 * 44)
    for eta0 in (sp.Rational(9, 10), sp.Rational(96, 100), sp.Rational(99, 100)):
        value, driver = alyushin2009.carrier_driving_efficiency(m, eta0)
        assert value == eta0 * (i - 1) / (i - eta0) and driver == "4"


def test_a_wrong_published_form_is_reported_as_differs():
    import sympy as sp

    from symkin.papers.checks import compare_symbolic

    r1, r2, r3, r4 = sp.symbols("r_1 r_2 r_3 r_4", positive=True)
    assert not compare_symbolic(1 + r2 * r4 / (r1 * r3), 1 + r2 * r3 / (r1 * r4)).verdict.ok


def test_reproduce_writes_the_report(tmp_path):
    import jsonschema

    out = tmp_path / "report"
    results = run(["alyushin2009"], out, quiet=True)
    assert all(r.ok for r in results)
    data = json.loads((out / "report.json").read_text())
    assert data["summary"]["differs"] == 0 and data["summary"]["checks"] == len(results[0].checks)
    jsonschema.validate(data, report_schema())
    assert (out / "figures" / "alyushin2009_trajectories.png").stat().st_size > 10_000
    tex = (out / "equations.tex").read_text()
    assert r"\begin{document}" in tex and "(13a)" in tex


def test_a_failing_run_keeps_the_previous_report(tmp_path):
    out = tmp_path / "report"
    out.mkdir()
    (out / "keep.txt").write_text("previous")

    def broken(folder):
        (folder / "half.txt").write_text("partial")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_atomically(out, broken)
    assert (out / "keep.txt").read_text() == "previous"
    assert not (out / "half.txt").exists()
    assert [p.name for p in tmp_path.iterdir()] == ["report"]
