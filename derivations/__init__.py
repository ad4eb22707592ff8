"""Reproductions of the published papers, one module per paper (installed as symkin.derivations).

Each module builds the paper's mechanisms with symkin, derives its equations, and
returns a list of :class:`symkin.report.Check` (derived form, published form, verdict).
Published formulas live here and in the tests, never in the library.

A module provides ``KEY``, ``CITATION``, ``checks() -> list[Check]`` and
``figures(folder) -> list[Path]``; optionally ``notes() -> list[str]``.
"""

#: Paper key -> module, in the order `symkin reproduce all` runs them.
PAPERS = {
    "alyushin2009": "symkin.derivations.alyushin2009",
    "kladova2010": "symkin.derivations.kladova2010",
    "khai2014": "symkin.derivations.khai2014",
    "luo2018": "symkin.derivations.luo2018",
}
