"""symkin: symbolic kinematics of planetary gear mechanisms.

Describe a mechanism by its links, gears and meshes (or take a ready-made scheme),
and symkin derives its closed-form laws with SymPy: ratios, the speed of every link,
the position, velocity and acceleration of any particle; prints them as LaTeX and
compiles them into fast numeric functions.

    >>> import symkin
    >>> aa = symkin.schemes.two_row("AA", teeth=(100, 100, 101, 99))
    >>> aa.ratio("H", "1", fixed="4").rhs
    101/2

The package, from the bottom up (``docs/architecture.md`` gives the path of data):

- the engine: :mod:`~symkin.model` (gears, links, meshes), :mod:`~symkin.superposition`
  and :mod:`~symkin.particles` (eqs. 4-6), :mod:`~symkin.kinematics` (contact conditions,
  speeds, ratios), :mod:`~symkin.vectorloop`, :mod:`~symkin.drives`, with
  :mod:`~symkin.laws`, :mod:`~symkin.symbols` and :mod:`~symkin.errors`;
- :mod:`~symkin.schemes`: the catalogue of ready-made schemes; :mod:`~symkin.trains`: any
  train from a file, its gear states and shift table (:func:`load_train`);
- :mod:`~symkin.values`: the values functions take (numbers, SymPy expressions, Fractions, pint
  quantities, :mod:`~symkin.units`); :mod:`~symkin.parsing`: the one parser of text
  (:func:`parse`), used where text enters (the command line, train files, the reports);
- :mod:`~symkin.numeric`: the one place laws become numbers; :mod:`~symkin.printing`:
  LaTeX; :mod:`~symkin.study`: derive, compile and evaluate what a request needs;
- :mod:`~symkin.statics`; :mod:`~symkin.synthesis`: tooth numbers of any train for a
  target ratio (:func:`synthesize`); the families in :mod:`~symkin.mechanisms` (Cardan,
  multistage, helical);
- :mod:`~symkin.viz` (figures, animation), :mod:`~symkin.papers` (checks, reports) and
  :mod:`~symkin.cli` (the ``symkin`` command).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from symkin import _deprecated
from symkin._version import __version__
from symkin.errors import *  # noqa: F403  (every error and warning class)
from symkin.errors import __all__ as _ERRORS

if TYPE_CHECKING:  # what the lazy attributes below are, for type checkers and IDEs
    from symkin import (
        drives,
        mechanisms,
        numeric,
        schemes,
        statics,
        symbols,
        synthesis,
        trains,
        vectorloop,
        viz,
    )
    from symkin.kinematics import Speeds, ratio, solve_speeds
    from symkin.laws import Law
    from symkin.model import FRAME, Gear, Link, Mechanism, Mesh
    from symkin.numeric import NumericFunction, compile
    from symkin.parsing import parse
    from symkin.particles import FrameMotion, Motion, Particle
    from symkin.printing import latex
    from symkin.study import Study
    from symkin.synthesis import synthesize
    from symkin.trains import Train, load_train

_deprecated.install()  # the module paths of symkin 0.1 keep importing for one release

#: Names of the package loaded on first use (module __getattr__), so that ``import symkin``
#: costs little more than importing its errors: name -> (module, attribute).
_LAZY: dict[str, tuple[str, str]] = {
    "Speeds": ("kinematics", "Speeds"),
    "ratio": ("kinematics", "ratio"),
    "solve_speeds": ("kinematics", "solve_speeds"),
    "Law": ("laws", "Law"),
    "FRAME": ("model", "FRAME"),
    "Gear": ("model", "Gear"),
    "Link": ("model", "Link"),
    "Mechanism": ("model", "Mechanism"),
    "Mesh": ("model", "Mesh"),
    "NumericFunction": ("numeric", "NumericFunction"),
    "compile": ("numeric", "compile"),
    "Study": ("study", "Study"),
    "parse": ("parsing", "parse"),
    "FrameMotion": ("particles", "FrameMotion"),
    "Motion": ("particles", "Motion"),
    "Particle": ("particles", "Particle"),
    "latex": ("printing", "latex"),
    "load_train": ("trains", "load_train"),
    "Train": ("trains", "Train"),
    "synthesize": ("synthesis", "synthesize"),
}

#: Subpackages and modules reachable as ``symkin.NAME`` without importing them first.
_SUBMODULES = frozenset({
    "cli", "drives", "errors", "kinematics", "laws", "mechanisms", "model", "numeric", "papers", "parsing",
    "particles", "printing", "units", "values", "schemes", "statics", "study", "superposition", "symbols", "synthesis", "trains", "vectorloop", "viz",
})
#: Modules of symkin 0.1 that moved (see :mod:`symkin._deprecated`), as ``symkin.NAME``.
_MOVED = frozenset(name.split(".")[1] for name in _deprecated.MODULES if name.count(".") == 1)


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        module, attribute = _LAZY[name]
        value = getattr(importlib.import_module(f"{__name__}.{module}"), attribute)
        globals()[name] = value
        return value
    if name in _SUBMODULES or name in _MOVED:
        return importlib.import_module(f"{__name__}.{name}")
    if f"{__name__}.{name}" in _deprecated.NAMES:
        return _deprecated.renamed(f"{__name__}.{name}", _deprecated.NAMES[f"{__name__}.{name}"])
    if name == "derivations":  # the papers, installed beside the library (never imported by it)
        return importlib.import_module(f"{__name__}.derivations")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | _SUBMODULES)


__all__ = [
    "FRAME",
    "Gear",
    "Link",
    "Mesh",
    "Mechanism",
    "Law",
    "Speeds",
    "Motion",
    "Particle",
    "FrameMotion",
    "NumericFunction",
    "Study",
    "Train",
    "load_train",
    "synthesize",
    "ratio",
    "solve_speeds",
    "latex",
    "compile",
    "parse",
    "schemes",
    "trains",
    "drives",
    "vectorloop",
    "mechanisms",
    "statics",
    "synthesis",
    "numeric",
    "viz",
    "symbols",
    "__version__",
    *_ERRORS,
]
