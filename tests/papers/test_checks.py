"""Verdicts are computed: the rules of judge(), the guards on slips and errors, the kinds of
check, the printed items of every paper, the summary line and report.json against its schema."""

from __future__ import annotations

import ast
import copy
import json
import re
from pathlib import Path

import jsonschema
import pytest
import sympy as sp

from symkin.papers.checks import (
    Check,
    Comparison,
    Kind,
    PrintedItem,
    Verdict,
    alternative,
    compare_digits,
    compare_exact,
    compare_inequality,
    compare_rounded,
    confirmation,
    item_results,
    judge,
)
from symkin.papers.document import equations_document, math_text
from symkin.papers.registry import load
from symkin.papers.reproduce import SCHEMA_VERSION, PaperResult, format_table, report_json, report_schema, summarize

ROOT = Path(__file__).resolve().parents[2]
PAPERS = ("alyushin2009", "kladova2010", "khai2014", "luo2018")


@pytest.fixture(scope="module")
def results() -> list[PaperResult]:
    out = []
    for name in PAPERS:
        mod = load(name)
        out.append(PaperResult(name, mod.CITATION, mod.checks(), items=list(mod.PRINTED_ITEMS)))
    return out


# ---------------------------------------------------------------------------- the rules
def test_a_match_needs_agreement():
    assert judge(compare_exact(3, 3)).verdict is Verdict.MATCH
    assert judge(compare_rounded(sp.Rational(1, 3), "0.333")).verdict is Verdict.ROUNDED
    assert judge(compare_rounded(sp.Rational(1, 3), "0.334")).verdict is Verdict.DIFFERS


def test_a_slip_needs_a_disagreement_and_an_alternative_that_reproduces_the_item():
    period = lambda omega: 2 * sp.pi / omega  # noqa: E731 - one derivation, run under two assumptions
    printed = 2 * sp.pi
    ok = alternative("omega = 1", period(1), printed, compare_exact)
    bad = alternative("omega = 2", period(2), printed, compare_exact)
    assert judge(compare_exact(period(sp.Rational(4, 5) * sp.pi), printed), alternative=ok).verdict is Verdict.SLIP
    assert judge(compare_exact(period(sp.Rational(4, 5) * sp.pi), printed), alternative=bad).verdict is Verdict.DIFFERS
    # agreement wins: the alternative is not consulted
    assert judge(compare_exact(period(1), printed), alternative=ok).verdict is Verdict.MATCH


def test_an_error_needs_a_confirmation_and_no_reproducing_alternative():
    derived, printed = sp.Rational(1, 2), sp.Rational(1, 3)
    agrees = confirmation("by hand", sp.Rational(2, 4), derived)
    disagrees = confirmation("by hand", sp.Rational(3, 4), derived)
    assert judge(compare_exact(derived, printed), confirmation=agrees).verdict is Verdict.ERROR
    assert judge(compare_exact(derived, printed), confirmation=disagrees).verdict is Verdict.DIFFERS
    reproduces = alternative("a typo", printed, printed, compare_exact)
    assert judge(compare_exact(derived, printed), alternative=reproduces, confirmation=agrees).verdict is Verdict.SLIP
    c = judge(compare_exact(derived, printed), hypothesis="OCR damage")
    assert c.verdict is Verdict.DIFFERS and "a hypothesis, not computed): OCR damage" in c.detail


def test_a_slip_or_an_error_cannot_be_attached():
    with pytest.raises(ValueError, match="computed alternative"):
        Comparison(Verdict.SLIP, "a typo")
    with pytest.raises(ValueError, match="independent route"):
        Comparison(Verdict.ERROR, "wrong")
    failing = alternative("x", 1, 2, compare_exact)
    with pytest.raises(ValueError, match="computed alternative"):
        Comparison(Verdict.SLIP, "a typo", alternative=failing)
    with pytest.raises(ValueError, match="already judged"):
        judge(Comparison(Verdict.SLIP, "", alternative=alternative("x", 2, 2, compare_exact)))


def test_comparators_can_fail():
    assert compare_inequality(sp.Rational(101, 2), ">", 50).verdict is Verdict.MATCH
    assert compare_inequality(49, ">", 50).verdict is Verdict.DIFFERS
    assert compare_digits(200, "?00").verdict is Verdict.MATCH
    assert compare_digits(201, "?00").verdict is Verdict.DIFFERS and compare_digits(1200, "?00").verdict is Verdict.DIFFERS
    assert compare_rounded(4 * sp.pi / 125, "100.53e-3").verdict is Verdict.ROUNDED
    assert compare_rounded(4 * sp.pi / 125, "100.52e-3").verdict is Verdict.DIFFERS


def _calls_in(path: Path) -> list[tuple[str, int]]:
    tree = ast.parse(path.read_text())
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("Comparison", "slip"):
            found.append((node.func.id, node.lineno))
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "Verdict":
            found.append((f"Verdict.{node.attr}", node.lineno))
    return found


@pytest.mark.parametrize("paper", PAPERS)
def test_derivations_never_set_a_verdict_by_hand(paper):
    """Verdicts come from the compare_* functions and judge(), never from Comparison(...) or a Verdict literal."""
    assert _calls_in(ROOT / "derivations" / f"{paper}.py") == []


# ---------------------------------------------------------------------------- the papers
def test_every_check_has_a_kind_and_every_paper_check_a_printed_item(results):
    for r in results:
        labels = [c.label for c in r.checks]
        assert len(labels) == len(set(labels)), r.key
        items = r.item_results  # raises for a paper check whose item is not listed
        for it in items:
            assert it.verdict is not None or it.item.not_checked, (r.key, it.item.item)
        assert {c.kind for c in r.checks} <= set(Kind)


def test_slips_and_errors_carry_their_evidence(results):
    for c in (c for r in results for c in r.checks):
        alt, conf = c.comparison.alternative, c.comparison.confirmation
        if c.verdict is Verdict.SLIP:
            assert alt is not None and alt.matches_published and alt.assumption, c.label
        if c.verdict is Verdict.ERROR:
            assert conf is not None and conf.agrees_with_derived and conf.route, c.label


def test_the_summary_counts_paper_items_apart(results):
    s = summarize(results)
    assert s.items == sum(len(r.items) for r in results)
    assert s.reproduced + s.slips + s.errors + s.differ + s.not_checked == s.items
    assert s.paper_checks + s.consistency + s.extensions == s.checks and s.failures == 0
    assert s.differs == 0 and s.differ == 0
    assert re.fullmatch(
        r"\d+ of \d+ paper items reproduced genuinely, \d+ more weakly, \d+ slips explained( \(\d+ weakly\))?, "
        r"\d+ paper errors confirmed( \(\d+ weakly\))?, 0 differ, \d+ not checked; \d+ consistency checks; \d+ extensions",
        s.line())
    # the genuine reproductions counted apart: an item is weak when every check that compares it is
    weak = [it for r in results for it in r.item_results if it.strength == "weak"]
    assert s.reproduced_weak + s.slips_weak + s.errors_weak == len(weak) > 0
    assert all(c.rests_on and c.rests_on in c.comparison.detail for it in weak for c in it.checks)
    table = format_table(results)
    assert s.line() in table and table.splitlines()[0].split()[:3] == ["paper", "kind", "result"]
    assert "printed items not checked:" in table


def test_an_item_takes_the_worst_verdict_of_its_checks():
    good = Check.make("p", "a", "", 1, 1, compare_exact(1, 1), item="(1)")
    bad = Check.make("p", "b", "", 1, 2, compare_exact(1, 2), item="(1)")
    other = Check.make("p", "c", "", 1, 2, compare_exact(1, 2), kind=Kind.EXTENSION)
    (result,) = item_results([PrintedItem("(1)", "a law")], [good, bad, other])
    assert result.verdict is Verdict.DIFFERS and [c.label for c in result.checks] == ["a", "b"]
    with pytest.raises(ValueError, match="not in the list"):
        item_results([PrintedItem("(2)", "another")], [good])
    # an item compared by a paper check cannot also say why it is not checked (the drill head did)
    with pytest.raises(ValueError, match="says it is not checked"):
        item_results([PrintedItem("(1)", "a law", "a method stated in words")], [good])
    (unchecked,) = item_results([PrintedItem("(1)", "a law", "a method stated in words")], [other])
    assert unchecked.verdict is None and unchecked.item.not_checked


# ---------------------------------------------------------------------------- report.json
def test_report_json_validates_against_its_schema(results, tmp_path):
    data = report_json(results, tmp_path)
    data["equations"] = {"tex": "equations.tex", "pdf": None}
    assert data["schema_version"] == SCHEMA_VERSION
    jsonschema.Draft202012Validator.check_schema(report_schema())
    jsonschema.validate(json.loads(json.dumps(data)), report_schema())
    checks = [c for p in data["papers"].values() for c in p["checks"]]
    number = next(c for c in checks if c["label"] == "Table 1 v max")
    assert number["derived_float"] == pytest.approx(0.10053096) and number["published_float"] == pytest.approx(0.10052)
    assert number["alternative"]["matches_published"] and number["alternative"]["value_float"] == pytest.approx(0.1005230)
    error = next(c for c in checks if c["label"] == "(13)" and c["paper"] == "luo2018")
    assert error["confirmation"]["agrees_with_derived"] and error["verdict"] == "paper error (confirmed)"
    assert {c["kind"] for c in checks} == {"paper", "consistency", "extension"}


def test_the_schema_rejects_a_slip_without_its_alternative(results, tmp_path):
    data = json.loads(json.dumps(report_json(results[:1], tmp_path)))
    broken = copy.deepcopy(data)
    slip = next(c for c in broken["papers"]["alyushin2009"]["checks"] if c["verdict"] == "paper slip (explained)")
    slip["alternative"] = None
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(broken, report_schema())
    broken = copy.deepcopy(data)
    broken["papers"]["alyushin2009"]["checks"][0]["kind"] = "paper-ish"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(broken, report_schema())


# ---------------------------------------------------------------------------- report.txt and the PDF
def test_the_document_shows_kind_and_verdict_and_typesets_headings(results):
    tex = equations_document(results)
    headings = [line for line in tex.splitlines() if line.startswith(r"\subsection*")]
    assert len(headings) > 100
    assert not [h for h in headings if re.search(r"(omega|theta|lambda|alpha|beta|Phi)\\_", h)]
    assert r"$\omega_{H}$" in tex and r"$i_{1H}^{(4)}$" in tex
    assert r"\textit{paper item}, \textbf{paper error (confirmed)}" in tex and r"\textit{consistency check}" in tex
    assert r"\textit{Alternative}" in tex and r"\textit{Independent route}" in tex


def test_math_text_leaves_words_alone():
    assert math_text("the pitch circle of rim 2") == "the pitch circle of rim 2"
    assert math_text("omega_23 and pi") == r"$\omega_{23}$ and $\pi$"
