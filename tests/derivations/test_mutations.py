"""Mutation tests: break one engine result the derivations use, and the verdicts that rest on it
turn to "differs"; no broken engine is ever explained away as a slip or a paper error.

Each mutation (tests/support/mutations.py) runs in a fresh process, so no cache of another run
hides it; a mutation runs only the parts of a paper whose mechanisms it can still build.
The expected sets are what a referee would call affected: the checks whose derived side
comes from the patched result, compared with a fixed published item.  Checks whose both
sides come from the engine (consistency checks of the rigid-body laws, say) legitimately
survive a patch elsewhere.
"""

from __future__ import annotations

import json
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
import sympy as sp

from symkin.papers.checks import Verdict

HERE = Path(__file__).resolve().parents[1] / "support"

#: mutation: (what runs, {paper: labels that must turn to "differs"})
MUTATIONS: dict[str, tuple[tuple[str, ...], dict[str, set[str]]]] = {
    "pitch point": (("alyushin2009", "luo2018:_structure", "khai2014:_backlash_check"), {
        "alyushin2009": {
            "(1)", "(2)", "(3) i_14^(H)", "(3) i_1H^(4)", "(10)", "(14a)", "(19)", "(13) form 1", "(13) form 2", "(17)",
            "(22)", "(13a)", "(13b)", "(22a) AA", "(22a) II", "(13) direction", "(17), (22) direction",
            *(f"({n}) eq. {k}" for n in (23, 24, 25) for k in (1, 2)),
            *(f"({n}a) {w}" for n in (23, 24, 25) for w in ("omega_H", "omega_23", "at omega_4 = 0")),
            "example AA 100/100/101/99", "example AA 100/99/100/101", "example AA 54/45/44/55 (i_1H)",
            "example AA 54/45/44/55 arithmetic", "example AA 54/45/44/55 (i_H1)", "example II 200/99/100/201",
            "example II z1", "example II z4", "example II arithmetic",
            "AI ratios and efficiency", "II efficiency", "II against AA efficiency",
        },
        "luo2018": {"(2)"},
        "khai2014": {"(3)"},
    }),
    "particle laws": (("alyushin2009:_particle_checks", "alyushin2009:_engine_law_checks", "luo2018:_structure",
                       "luo2018:_laws", "luo2018:_guide_force"), {
        "alyushin2009": {"(4)", "(5)", "(6)", "(5)-(6) engine", "(5) engine law", "(6) engine law"},
        "luo2018": {"(22) superposition", "fig. 5", "(18)", "(19)", "(20)"},
    }),
    "coaxiality defects": (("alyushin2009",), {
        "alyushin2009": {
            "coaxiality AI1", "coaxiality AI", "coaxiality AA", "coaxiality II", "(10)", "(14a)", "(19)", "(13) form 1",
            "(23) eq. 2", "(24) eq. 2", "(25) eq. 2",
            *(f"({n}a) {w}" for n in (23, 24, 25) for w in ("omega_H", "omega_23", "at omega_4 = 0")),
            "example AA 100/99/100/101 centre-distance gap", "example II z1", "example II z4",
        },
    }),
    "slider displacement": (("luo2018:_laws", "luo2018:_table1", "luo2018:_elliptical"), {
        "luo2018": {
            "(22)", "(23)", "(24)", "(22) superposition", "stroke", "(29)", "(30)-(31)", "(32)",
            *(f"Table 1 {q} {w}" for q in "sa" for w in ("initial", "max", "min")), "Table 1 v max", "Table 1 v min",
            "Table 1 simulation row",
        },
    }),
    "line conditions": (("luo2018:_continuity",), {"luo2018": {"(12) identity", "(13)"}}),
    "slider period": (("luo2018:_table1",), {"luo2018": {"period"}}),
    "elliptical drive": (("luo2018:_elliptical", "luo2018:_figure_claims"), {
        "luo2018": {"(25)", "(26)", "(27)-(28)", "(33)-(35)"},
    }),
    "stage ratio": (("khai2014:_train_checks", "khai2014:_stage_checks"), {
        "khai2014": {"stage ratio", "stages: u min", "stages: u max"},
    }),
    "lost motion": (("khai2014:_objective_checks", "khai2014:_optimum_checks"), {
        "khai2014": {
            "(1) n = 2", "(1) n = 3", "(1) n = 4", "(1) n = 5", "(1) Delta phi_H4", "(2) line 1", "(2) line 2",
            "(2) closed sum", "fig. 4 FF", "fig. 4 FF value",
        },
    }),
    "helical ratio": (("kladova2010:_section_11_checks", "kladova2010:_section_12_checks"), {
        "kladova2010": {"1.1 heading", "(1)", "(3)"},
    }),
    "tooth equations": (("kladova2010:_section_11_checks", "kladova2010:_section_12_checks"), {
        "kladova2010": {"(6) step", "(6) step solved", "(6)", "(9)"},
    }),
    "diameter ratio": (("kladova2010:_section_11_checks",), {
        "kladova2010": {"(6) step", "(6) step solved", "(6) identity"},
    }),
    "helical coaxiality": (("kladova2010:_section_11_checks",), {
        "kladova2010": {"1.1 heading", "(2)", "(6) step", "(6) step solved"},
    }),
    "existence bounds": (("kladova2010:_table_checks",), {
        "kladova2010": {f"Table 1 {kd}, delta {c} 1" for kd in ("AA", "II", "AI") for c in "<>"},
    }),
}

#: The slips and confirmed errors of the unpatched papers.
EXPLAINED = {
    ("alyushin2009", "example AA 100/99/100/101 centre-distance gap"),
    ("kladova2010", "from (34)"),
    *(("kladova2010", label) for label in ("1.1 heading", "(6) step solved", "(6) identity", "(6)", "(9)",
                                           "Table 1 AA, delta < 1", "Table 1 AA, delta > 1")),
    *(("khai2014", label) for label in ("fig. 4 FF value", "(6)", "(2) closed sum", "fig. 1 regression line",
                                        "fig. 3 optimisation result")),
    *(("luo2018", label) for label in ("Table 1 v max", "Table 1 v min", "Table 1 simulation row", "period", "fig. 7(b)",
                                       "(13)")),
}
#: Slips and errors no engine result enters; tested below by changing what they rest on.
ENGINE_FREE = {("kladova2010", "from (34)"), ("khai2014", "fig. 1 regression line"),
               ("khai2014", "fig. 3 optimisation result"), ("khai2014", "(6)"), ("luo2018", "fig. 7(b)")}


def _run(name: str) -> list[dict]:
    specs, _ = MUTATIONS[name]
    proc = subprocess.run([sys.executable, str(HERE / "mutations.py"), name, *specs], capture_output=True, text=True,
                          timeout=900, cwd=HERE.parent)
    assert proc.returncode == 0, f"{name}: {proc.stderr[-2000:]}"
    return [json.loads(line) for line in proc.stdout.splitlines()]


@pytest.fixture(scope="module")
def outcomes() -> dict[str, list[dict]]:
    with ThreadPoolExecutor(max_workers=2) as pool:
        return dict(zip(MUTATIONS, pool.map(_run, MUTATIONS)))


@pytest.mark.parametrize("name", list(MUTATIONS))
def test_a_mutated_engine_result_turns_the_affected_verdicts_to_differs(outcomes, name):
    rows = outcomes[name]
    verdicts = {(r["paper"], r["label"]): r["verdict"] for r in rows}
    _, expected = MUTATIONS[name]
    for paper, labels in expected.items():
        for label in labels:
            assert (paper, label) in verdicts, (name, paper, label)
            assert verdicts[paper, label] == Verdict.DIFFERS.value, (name, paper, label, verdicts[paper, label])
    new = [key for key, v in verdicts.items() if v in (Verdict.SLIP.value, Verdict.ERROR.value) and key not in EXPLAINED]
    assert not new, f"{name}: a broken engine was explained away: {new}"


def test_every_slip_and_error_that_rests_on_the_engine_is_caught_by_a_mutation():
    caught = {(paper, label) for _, expected in MUTATIONS.values() for paper, labels in expected.items() for label in labels}
    assert caught >= EXPLAINED - ENGINE_FREE, sorted(EXPLAINED - ENGINE_FREE - caught)


# ---------------------------------------------------------------------------- the engine-free ones
def test_a_caption_that_does_not_hold_the_line_leaves_the_figure_reference_unexplained(monkeypatch):
    from symkin.derivations import khai2014

    monkeypatch.setitem(khai2014.FIGURE_CAPTIONS, 2, "j_n max(a_w): GOST data only")
    checks = {c.label: c for c in khai2014._figure_reference_checks()}
    assert checks["fig. 1 regression line"].verdict is Verdict.DIFFERS
    assert checks["fig. 3 optimisation result"].verdict is Verdict.ERROR


def test_the_34_reference_is_explained_only_while_3_and_4_give_the_line(monkeypatch):
    from symkin.derivations import kladova2010

    z1, x, i = kladova2010.z1, kladova2010.x, kladova2010.i
    monkeypatch.setitem(kladova2010.PUBLISHED, "(4)", z1 * (i - 2) / x)  # a different (4): (3) with it is not the line
    (check,) = [c for c in kladova2010._section_11_checks() if c.label == "from (34)"]
    assert check.derived == "(3) with (1)" and check.verdict is Verdict.DIFFERS


def test_the_printed_6_is_a_slip_only_while_the_short_radical_reproduces_it(monkeypatch):
    from symkin.derivations import khai2014

    j, t1, t2, fa = sp.symbols("j_min T_H1 T_H2 f_a", positive=True)
    monkeypatch.setattr(khai2014, "_published_6", lambda: j + sp.sqrt(sp.Rational(1, 2) * (t1**2 + t2**2)) + 3 * fa**2)
    (check,) = [c for c in khai2014._model_checks() if c.label == "(6)"]
    assert check.verdict is Verdict.DIFFERS


def test_fig_7b_is_a_slip_only_through_its_principal_branch_alternative(monkeypatch):
    from symkin.derivations import luo2018

    order_stats = luo2018.order_stats
    monkeypatch.setattr(luo2018, "order_stats", lambda slider, principal, **kw: order_stats(slider, False, **kw))
    monkeypatch.setattr(luo2018, "_sensitivity_text", lambda panel: "")
    (check,) = [c for c in luo2018._figure_claims() if c.label == "fig. 7(b)"]
    assert check.verdict is Verdict.DIFFERS and not check.comparison.alternative.matches_published
