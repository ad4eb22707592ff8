"""Mechanism families built on the engine, one home each.

A family is a kind of mechanism with machinery of its own beyond ratios, speeds and
particle laws (which every mechanism gets from the engine):

========================  ===========================================================
:mod:`.cardan`            the Cardan-circle straight-line mechanism: slider, vector
                          loop, line conditions, elliptical-gear drive (Luo & Li 2018)
:mod:`.multistage`        common-ring trains of single-row AI stages: feasible stages,
                          lost motion, the ratio split (KhAI 2014)
:mod:`.helical`           two-row trains with a stepped helical planet: gear geometry,
                          the train, axial-force-free synthesis (Kladova et al. 2010)
========================  ===========================================================

A family builds its mechanisms from :mod:`symkin.schemes` (the catalogue) and derives
everything with the engine; it never types a published formula.  Its command lives in
:mod:`symkin.cli` and its figures in :mod:`symkin.viz`.  How to add a family:
``symkin/mechanisms/README.md``.
"""

from __future__ import annotations

import importlib
from typing import Any

#: The families, importable as ``symkin.mechanisms.NAME`` without importing them first.
FAMILIES = ("cardan", "helical", "multistage")


def __getattr__(name: str) -> Any:
    if name in FAMILIES:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
