"""Reproductions of the published papers, one module per paper (installed as symkin.derivations).

Each module builds the paper's mechanisms with symkin, derives its equations, and
returns a list of :class:`symkin.papers.checks.Check` (derived form, published form,
verdict).  Published formulas live here and in the tests, never in the library.

A module provides ``CITATION``, ``checks() -> list[Check]`` and
``figures(folder) -> list[Path]``; optionally ``notes() -> list[str]``.  Each is
registered in ``pyproject.toml`` under the entry-point group ``symkin.papers``, which is
how ``symkin reproduce`` finds it (:mod:`symkin.papers.registry`); the library never
imports this package.
"""
