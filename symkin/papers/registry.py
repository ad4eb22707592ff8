"""The papers ``symkin reproduce`` knows: the entry-point group ``symkin.papers``.

A paper is a module registered under that group by any installed distribution; symkin's
own four are the modules of ``derivations/`` (installed as ``symkin.derivations``).  The
library never imports a paper by name: it asks the installed metadata, so a
researcher's package adds its paper to ``symkin reproduce`` with one entry in its own
``pyproject.toml``::

    [project.entry-points."symkin.papers"]
    smith2025 = "mypackage.smith2025"

A paper module provides ``CITATION`` (str), ``checks() -> list[Check]`` and
``figures(folder) -> list[Path]``, and optionally ``notes() -> list[str]``.  Papers run in
the order of the year that ends their key (``alyushin2009`` before ``luo2018``), then by key.

    >>> "alyushin2009" in paper_names()
    True
"""

from __future__ import annotations

import re
from importlib.metadata import EntryPoint, entry_points
from types import ModuleType

from symkin.errors import InputError

__all__ = ["GROUP", "paper_names", "load"]

#: The entry-point group papers register under.
GROUP = "symkin.papers"


def _order(name: str) -> tuple[int, str]:
    year = re.search(r"(\d{4})$", name)
    return (int(year.group(1)) if year else 10**6, name)


def _entries() -> dict[str, EntryPoint]:
    found: dict[str, EntryPoint] = {}
    for ep in entry_points(group=GROUP):
        found.setdefault(ep.name, ep)  # the first distribution that registers a key keeps it
    return {name: found[name] for name in sorted(found, key=_order)}


def paper_names() -> tuple[str, ...]:
    """The keys of the registered papers, in the order ``symkin reproduce all`` runs them."""
    return tuple(_entries())


def load(name: str) -> ModuleType:
    """The module of paper ``name`` (an :class:`~symkin.errors.InputError` for an unknown key)."""
    entries = _entries()
    if name not in entries:
        choices = ", ".join(entries) or "(none registered: is symkin installed with pip?)"
        raise InputError(f"no paper called {name!r}; choose all or one of {choices}")
    module = entries[name].load()
    for attribute in ("CITATION", "checks", "figures"):
        if not hasattr(module, attribute):
            raise InputError(f"paper {name!r} ({entries[name].value}) has no {attribute}; see symkin.papers.registry")
    return module
