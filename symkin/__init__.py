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

from . import cardan, drives, lostmotion, ratiosplit, schemes, stages, symbols, vectorloop
from .errors import (
    CoaxialityWarning,
    DeterminacyError,
    PoleError,
    PoleWarning,
    PrecisionWarning,
    InputError,
    ModelError,
    OverdeterminedError,
    SimplificationBudgetWarning,
    SingularConfigurationError,
    SymkinError,
    SymkinWarning,
    ToolError,
    UnderdeterminedError,
    UnsupportedError,
)
from .kinematics import Speeds, ratio, solve_speeds
from .laws import Law
from .model import FRAME, Gear, Link, Mechanism, Mesh
from .numeric import NumericFunction, compile
from .numeric.scene import Scene
from .particles import FrameMotion, Motion, Particle
from .printing import latex

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
    "SymkinError",
    "ModelError",
    "InputError",
    "DeterminacyError",
    "UnderdeterminedError",
    "OverdeterminedError",
    "SingularConfigurationError",
    "UnsupportedError",
    "ToolError",
    "SymkinWarning",
    "CoaxialityWarning",
    "PoleError",
    "PoleWarning",
    "PrecisionWarning",
    "SimplificationBudgetWarning",
]
