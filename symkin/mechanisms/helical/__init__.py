"""Two-row planetary trains with a stepped helical planet (Kladova, Saprykin, Shebanov 2010).

- :mod:`.geometry`: helical gear and mesh geometry (transverse module and pressure angle,
  working pitch radii, leads, involute), and helical gears for the model;
- :mod:`.train`: :class:`HelicalTrain`, a two-row train whose planet rims mesh helically,
  and its ratio law from the engine;
- :mod:`.balanced`: tooth numbers and helix angles for a target ratio with the planet's
  axial forces balanced (derived conditions, existence regions, the search).

The forces themselves (torque balance, axial forces, balancing hands) are statics:
:mod:`symkin.statics`.  The synthesis's user-facing names are importable from here too
(the last names of ``__all__``; they load on first use, the synthesis costing about 0.1 s more
to import than the geometry and the train):

    >>> from symkin.mechanisms.helical import synthesize_helical
    >>> synthesize_helical(scheme="AI", ratio=12, satellites=3, normal_modules=(2, 2.5), teeth_max=80).designs[0].teeth
    (17, 51, 21, 77)
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from symkin.mechanisms.helical.geometry import (
    DEFAULT_PRESSURE_ANGLE,
    LEFT,
    RIGHT,
    SCHEME_MESHES,
    HelicalMesh,
    base_helix_angle,
    hand_name,
    helical_gear,
    inverse_involute,
    involute,
    lead,
    pitch_radius,
    transverse_pressure_angle,
    working_pitch_radius,
    working_pressure_angle,
)
from symkin.mechanisms.helical.train import HelicalTrain, ratio_function, ratio_law

if TYPE_CHECKING:  # what the names loaded on first use are, for type checkers
    from symkin.mechanisms.helical.balanced import (
        ExistenceBounds,
        HelicalDesign,
        HelicalRequest,
        HelicalResult,
        ToothEquations,
        balance_condition,
        existence_bounds,
        existence_interval,
        existence_range,
        synthesize_helical,
        tooth_equations,
    )

__all__ = [
    "RIGHT",
    "LEFT",
    "DEFAULT_PRESSURE_ANGLE",
    "SCHEME_MESHES",
    "hand_name",
    "transverse_pressure_angle",
    "pitch_radius",
    "working_pitch_radius",
    "base_helix_angle",
    "lead",
    "involute",
    "inverse_involute",
    "working_pressure_angle",
    "helical_gear",
    "HelicalMesh",
    "HelicalTrain",
    "ratio_law",
    "ratio_function",
    "synthesize_helical",
    "HelicalRequest",
    "HelicalDesign",
    "HelicalResult",
    "tooth_equations",
    "ToothEquations",
    "balance_condition",
    "existence_bounds",
    "existence_interval",
    "existence_range",
    "ExistenceBounds",
]


def __getattr__(name: str) -> Any:  # the synthesis loads on first use: its names are those of __all__ not yet here
    if name == "balanced" or name in __all__:
        balanced = importlib.import_module(f"{__name__}.balanced")
        return balanced if name == "balanced" else getattr(balanced, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__) | {"balanced"})
