"""The 2009 paper reproduced, and the report folder written atomically."""

import json

import pytest

from symkin.derivations import alyushin2009
from symkin.papers.reproduce import run, write_atomically


def test_every_alyushin2009_check_is_reproduced():
    checks = alyushin2009.checks()
    bad = [(c.label, c.comparison.detail) for c in checks if not c.verdict.ok]
    assert not bad
    labels = {c.label.split()[0] for c in checks}
    for eq in ["(2)", "(3)", "(10)", "(13)", "(13a)", "(13b)", "(14a)", "(17)", "(19)", "(22)", "(22a)", "(23a)", "(24a)", "(25a)"]:
        assert eq in labels, eq
    slips = [c for c in checks if c.verdict.value.startswith("paper slip")]
    assert {c.label for c in slips} == {"example AA 100/99/100/101 centre-distance gap", "example II z1"}


def test_a_wrong_published_form_is_reported_as_differs():
    import sympy as sp

    from symkin.papers.checks import compare_symbolic

    r1, r2, r3, r4 = sp.symbols("r_1 r_2 r_3 r_4", positive=True)
    assert not compare_symbolic(1 + r2 * r4 / (r1 * r3), 1 + r2 * r3 / (r1 * r4)).verdict.ok


def test_reproduce_writes_the_report(tmp_path):
    out = tmp_path / "report"
    results = run(["alyushin2009"], out, quiet=True)
    assert all(r.ok for r in results)
    data = json.loads((out / "report.json").read_text())
    assert data["summary"]["differs"] == 0 and data["summary"]["checks"] == len(results[0].checks)
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
