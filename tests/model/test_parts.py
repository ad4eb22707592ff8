"""Link and gear names go into symbol names and from there into LaTeX: a name that would run a
TeX command (``\\input{/etc/hostname}`` printed the file into the PDF) or break the document
(``50%``, ``{``, ``&``, ``#1``, ...) is refused at the model, and every name the model takes
prints LaTeX that compiles."""

import pytest
import sympy as sp

import symkin
from symkin import ModelError
from symkin import symbols as S
from symkin.model import Gear, Link, Mechanism
from symkin.papers.texbuild import compile_pdf

HOSTILE = [r"\input{/etc/hostname}", r"\immediate\write18{touch PWNED}", "50%", "{", "}", "&", "#1", "$", "^", "~",
           "_", "a__b", "a^2", "%", "\\", "a\\b", "a b", " a", "a\n", "ω", "Кольцо", "é", "\u202e1", "", "a{b}",
           "a_", "_a", "a--b", "a..b", "'", "<", "|", '"', "a,b", "(a)", "[a]", "a/b", "a:b", "a;b", "a=b", "a+b",
           "a*b", "a?b", "a!b", "a@b", "١"]
ACCEPTED = ["1", "H", "23", "sat", "a_b", "planet-2", "x'", "a.b", "P1", "S2", "ring_gear_1", "b''"]


def ring_of(name: str) -> str:
    return "ring" + "".join(c for c in name if c.isalnum())


def mechanism(name: str) -> Mechanism:
    """An AI1 train whose sun (link and gear) is called ``name``, with a ring named after it."""
    ring = ring_of(name)
    return Mechanism(
        links=[Link.central(name, Gear(name, sp.Symbol("r_" + name, positive=True))),
               Link.planet("2", Gear.from_teeth("2", 30), carrier="C0"),
               Link.central("C0"),
               Link.central(ring, Gear.from_teeth(ring, 80, internal=True))],
        meshes=[(name, "2"), ("2", ring)],
    )


@pytest.mark.parametrize("name", HOSTILE, ids=repr)
def test_a_name_that_is_not_plain_letters_and_digits_is_refused_with_the_rule(name):
    for build in (lambda: Link.central(name), lambda: Gear(name, 1), lambda: Link.planet("2", carrier=name),
                  lambda: symkin.model.Mesh(name, "2")):
        with pytest.raises(ModelError, match="ASCII letters and digits|non-empty name") as info:
            build()
        assert "\n" not in str(info.value)


def test_every_name_the_model_takes_prints_latex_that_compiles(tmp_path, pdflatex):
    lines = []
    for name in ACCEPTED:
        mech = mechanism(name)
        ring = ring_of(name)
        lines.append(symkin.latex(mech.speeds({name: S.omega(name), ring: S.omega(ring)})))
        lines.append(symkin.latex(mech.ratio(name, "C0", fixed=ring), number=name))
        lines.append(symkin.latex(mech.motion({name: 1, ring: 0}).particle("2", (1, 0)).velocity[0], width=60))
    tex = tmp_path / "names.tex"
    body = "\n".join(line if line.startswith("\\begin{equation}") else f"\\[{line}\\]" for line in lines)
    tex.write_text("\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n" + body + "\n\\end{document}\n")
    build = compile_pdf(tex, pdflatex=pdflatex)
    assert build.pdf.exists()
    # and the names print as themselves (an underscore as a subscript space, as SymPy writes omega_a_b)
    assert r"\omega_{planet-2}" in body and r"r_{ring gear 1}" in body and r"\omega_{a.b}" in body


def test_the_issues_injection_is_refused_before_any_latex_exists(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ModelError, match=r"'\\\\input\{/etc/hostname\}'"):
        mechanism(r"\input{/etc/hostname}")
