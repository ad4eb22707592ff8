"""equations.tex: contents, bookmarks and links (hyperref), a bibliography of the papers, each
section citing its paper; Table 1's interval ends labelled. (Compiled where pdflatex is:
tests/papers/test_reproduce_folder.py.)"""

from __future__ import annotations

from types import SimpleNamespace

from symkin.papers.document import PREAMBLE, equations_document, math_rows

RESULTS = [SimpleNamespace(key="alyushin2009", citation="Alyushin, Yu. A. (2009)", checks=[], notes=[], items=[]),
           SimpleNamespace(key="luo2018", citation="Luo et al. (2018)", checks=[], notes=[], items=[])]


def test_the_document_has_contents_bookmarks_and_links():
    assert r"{hyperref}" in PREAMBLE and r"\tableofcontents" in PREAMBLE
    assert PREAMBLE.index("{hyperref}") > PREAMBLE.index("{graphicx}")  # hyperref last, as it asks


def test_each_paper_is_cited_by_its_section_and_listed_in_the_bibliography():
    tex = equations_document(RESULTS)
    for r in RESULTS:
        assert rf"\cite{{{r.key}}}" in tex and rf"\bibitem{{{r.key}}}" in tex
    assert tex.index(r"\begin{thebibliography}") > tex.index(r"\section{\texorpdfstring{Luo")
    assert r"\addcontentsline{toc}{section}{References}" in tex
    assert r"\texorpdfstring{Alyushin,\allowbreak{} Yu. A. (2009)}{Alyushin, Yu. A. (2009)}" in tex


def test_interval_ends_are_labelled():
    from derivations import kladova2010

    lower, upper = kladova2010._bounds(1, 2)
    assert math_rows([lower, upper]) == [r"i_{min} = 1", r"i_{max} = 2"]
