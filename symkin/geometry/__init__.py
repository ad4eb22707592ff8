"""Gear geometry a designer can make: involute gears of the ISO 53 basic rack with profile shift,
their meshes (working pressure angle, centre distance, contact ratio, undercut and interference),
the shifts a coaxial planetary set needs, and tooth outlines for CAD (DXF, SVG).

Lengths are in millimetres (the module, ISO 54); the user's view is ``docs/geometry.md``.
"""

from symkin.geometry.gear import GearGeometry, ToothForm, gear_geometry, involute
from symkin.geometry.mesh import PairGeometry, interferences, inverse_involute, pair_geometry, shift_sum_for
from symkin.geometry.outline import tooth_outline
from symkin.geometry.train import CoaxialShifts, MeshReport, TrainGeometry, coaxial_shifts, train_geometry

__all__ = ["ToothForm", "GearGeometry", "gear_geometry", "involute", "PairGeometry", "pair_geometry",
           "inverse_involute", "shift_sum_for", "tooth_outline", "TrainGeometry", "MeshReport", "train_geometry",
           "coaxial_shifts", "CoaxialShifts", "interferences"]
