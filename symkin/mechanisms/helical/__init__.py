"""Two-row planetary trains with a stepped helical planet (Kladova, Saprykin, Shebanov 2010).

- :mod:`.geometry`: helical gear and mesh geometry (transverse module and pressure angle,
  working pitch radii, leads, involute), and helical gears for the model;
- :mod:`.train`: :class:`HelicalTrain`, a two-row train whose planet rims mesh helically,
  and its ratio law from the engine;
- :mod:`.balanced`: tooth numbers and helix angles for a target ratio with the planet's
  axial forces balanced (derived conditions, existence regions, the search).

The forces themselves (torque balance, axial forces, balancing hands) are statics:
:mod:`symkin.statics`.
"""

from __future__ import annotations

import importlib
from typing import Any

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
]


def __getattr__(name: str) -> Any:  # the synthesis loads on first use
    if name == "balanced":
        return importlib.import_module(f"{__name__}.balanced")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
