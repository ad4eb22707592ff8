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
        *(f"({n}) {s}" for n in (1, 2) for s in ("AI1", "AI", "AA", "II")), "(5)-(6) engine",
        "drill head"}  # the paper's recipe, stated in words, applied by hand to the engine's own laws
    assert {k for k, v in kinds.items() if v is Kind.EXTENSION} == {
        "coaxiality AI1", "(24a) at omega_4 = 0", "(25a) at omega_4 = 0", "drill head in space"}


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
    eta0 = alyushin2009.ETA0
    assert sp.cancel(alyushin2009.basic_train_law(m, "H", "1") - eta0 * (i - 1) / (i - eta0)) == 0


# ---------------------------------------------------------------------------- efficiency statements
def test_the_efficiency_laws_are_the_textbook_ones():
    """The basic-train method by hand (Kudryavtsev): K = i_14^(H), gear 4 held."""
    eta0, K = alyushin2009.ETA0, sp.Rational(99 * 201, 200 * 100)
    ii = schemes.two_row("II", teeth=(200, 99, 100, 201))
    # 0 < K < 1: the sun driving the carrier passes (1 - K/eta0)/(1 - K); the carrier driving the sun (1 - K)/(1 - K eta0)
    assert sp.cancel(alyushin2009.basic_train_law(ii, "1", "H") - (1 - K / eta0) / (1 - K)) == 0
    assert sp.cancel(alyushin2009.basic_train_law(ii, "H", "1") - (1 - K) / (1 - K * eta0)) == 0
    # AI, K < 0: the sun driving the carrier, 1 - (1 - eta0)(1 - 1/i_1H)
    ai = schemes.two_row("AI", teeth=(20, 30, 20, 70))
    i = 1 + sp.Rational(30 * 70, 20 * 20)
    assert sp.cancel(alyushin2009.basic_train_law(ai, "1", "H") - (1 - (1 - eta0) * (1 - 1 / i))) == 0


def test_the_efficiency_statements_have_computed_verdicts(checks):
    ai, ii, vs = checks["AI ratios and efficiency"], checks["II efficiency"], checks["II against AA efficiency"]
    assert ai.verdict is ii.verdict is vs.verdict is Verdict.MATCH
    # by hand at the default meshes (0.98 external, 0.99 internal): eta0 = 0.9702, (1 + eta0 (i - 1))/i
    assert "0.9801 at i_1H = 3 and 0.9722 at i_1H = 15" in ai.derived
    assert "no one basic-train efficiency gives both printed ends" in ai.comparison.detail
    # II: (20000 eta0 - 19899)/(101 eta0) at eta0 = 0.99^2 is below zero: the siren direction locks
    assert "-3.0003" in ii.derived and "0.2032" in ii.derived
    assert "9801/10000" in vs.derived and "2401/2500" in vs.derived


def test_the_drill_head_follows_the_paper_recipe_and_sympy_mechanics(checks):
    assert checks["drill head"].verdict is Verdict.MATCH and checks["drill head"].kind is Kind.CONSISTENCY
    # the paper gives no case to compare: its printed item says so, and no paper check compares it
    (item,) = [it for it in alyushin2009.PRINTED_ITEMS if it.item == "drill head"]
    assert item.not_checked and "no case" in item.not_checked
    assert checks["drill head in space"].verdict is Verdict.MATCH
    # the tooth is at its place at t = 0: planet axis at r1 + r2 = 36 mm, the tooth 10 mm further, 30 mm ahead
    assert list(alyushin2009.drill_head_motion().particle("2", (10, 0, 30), relative_to="pole").position.subs(S.t, 0)) \
        == [46, 0, 30]


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
    assert (out / "figures" / "alyushin2009_drill_head.png").stat().st_size > 10_000
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


def test_the_expanded_lines_12_16_21_are_the_willis_ratios_by_hand(checks):
    r1, r2, r3 = (S.radius(str(i)) for i in (1, 2, 3))
    wH = S.omega("H")
    # by hand, gear 4 fixed: omega_1 = omega_H i_1H^(4), i_1H^(4) = 1 -+ r2 r4/(r1 r3) with r4 from coaxiality
    by_hand = {"(12)": (1 + r2 * (r1 + r2 + r3) / (r1 * r3)), "(16)": (1 - r2 * (r1 + r2 - r3) / (r1 * r3)),
               "(21)": (1 - r2 * (r1 - r2 + r3) / (r1 * r3))}
    for label, ratio in by_hand.items():
        c = checks[label]
        assert c.kind is Kind.PAPER and c.source == "reconstructed" and c.verdict is Verdict.MATCH
        for form in c.published:
            assert sp.cancel(form - (-r1 * wH * ratio)) == 0, label


def test_a_wrong_centripetal_term_turns_the_engine_law_item_and_only_it(monkeypatch):
    from collections import OrderedDict

    import symkin.model.mechanism
    import symkin.particles
    from symkin.superposition import vec

    def flipped(pole_acc, w, eps, point, pole):  # w_P + eps k x r + omega^2 r: the centripetal sign flipped
        rel = point - pole
        return sp.ImmutableMatrix(pole_acc + eps * vec(-rel[1], rel[0]) + w**2 * rel)

    monkeypatch.setattr(symkin.particles, "acceleration", flipped)
    monkeypatch.setattr(symkin.model.mechanism, "_CACHES", OrderedDict())  # no law derived before the patch
    laws = {c.label: c for c in alyushin2009._engine_law_checks()}
    assert laws["(6) engine law"].verdict is Verdict.DIFFERS and laws["(6) engine law"].kind is Kind.PAPER
    assert laws["(5) engine law"].verdict is Verdict.MATCH
    # the printed (6) against the derivatives of the positions holds for any rigid motion: blind to the engine's law
    assert {c.label: c.verdict for c in alyushin2009._particle_checks()}["(6)"] is Verdict.MATCH


def test_matches_that_rest_on_a_chosen_value_say_so(checks):
    weak = {label for label, c in checks.items() if c.strength == "weak"}
    assert weak == {"example II z1", "example II z4", "II against AA efficiency"}
    assert "searched for" in checks["example II z1"].comparison.detail
    assert "0.99 for an internal mesh" in checks["II against AA efficiency"].comparison.detail
