"""symkin: symbolic kinematics of planetary gear mechanisms.

Describe a mechanism by its links, gears and meshes (or take a ready-made scheme),
and symkin derives its closed-form laws with SymPy: ratios, the speed of every link,
the position, velocity and acceleration of any particle; prints them as LaTeX and
compiles them into fast numeric functions.

    >>> import symkin
    >>> aa = symkin.schemes.two_row("AA", teeth=(100, 100, 101, 99))
    >>> aa.ratio("H", "1", fixed="4").rhs
    101/2
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from .errors import *  # noqa: F403  (every error and warning class)
from .errors import __all__ as _ERRORS

if TYPE_CHECKING:  # what the lazy attributes below are, for type checkers and IDEs
    from . import cardan, drives, lostmotion, ratiosplit, schemes, stages, symbols, vectorloop
    from .kinematics import Speeds, ratio, solve_speeds
    from .laws import Law
    from .model import FRAME, Gear, Link, Mechanism, Mesh
    from .numeric import NumericFunction, compile
    from .numeric.scene import Scene
    from .particles import FrameMotion, Motion, Particle
    from .printing import latex

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
    "Scene": ("numeric.scene", "Scene"),
    "FrameMotion": ("particles", "FrameMotion"),
    "Motion": ("particles", "Motion"),
    "Particle": ("particles", "Particle"),
    "latex": ("printing", "latex"),
}

#: Subpackages and modules reachable as ``symkin.NAME`` without importing them first.
_SUBMODULES = frozenset({
    "animation", "atomic", "budget", "cardan", "cli", "derivations", "drives", "helical", "helical_synthesis",
    "jsonout", "kinematics", "latex_report", "laws", "lostmotion", "model", "numeric", "parsing", "particles",
    "plotting", "printing", "ratiosplit", "report", "reproduce", "schemes", "splitplot", "stages", "statics",
    "superposition", "symbols", "texbuild", "vectorloop",
})


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        module, attribute = _LAZY[name]
        value = getattr(importlib.import_module(f"{__name__}.{module}"), attribute)
        globals()[name] = value
        return value
    if name in _SUBMODULES:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | _SUBMODULES)


__version__ = "0.1.0"

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
    "Scene",
    "ratio",
    "solve_speeds",
    "latex",
    "compile",
    "schemes",
    "drives",
    "cardan",
    "vectorloop",
    "stages",
    "lostmotion",
    "ratiosplit",
    "symbols",
    *_ERRORS,
]
