"""Dynamics of any train: mass properties, equations of motion in closed form, torsional vibration.

- :func:`equations_of_motion` (:mod:`symkin.dynamics.rigid`): the rigid-body equations
  ``M q'' = f`` of a train in any gear state, from the engine's speed laws (every link's spin,
  every planet's spin and the motion of its centre, nested carriers and bevel pinions).
- :func:`torsional_model` and :func:`natural_modes` (:mod:`symkin.dynamics.torsional`): a purely
  rotational lumped-parameter model (each planet its own coordinate, meshes as springs along
  their lines of action, shafts to the frame) and its natural frequencies and mode shapes.
- :func:`planar_model` and :func:`planar_modes` (:mod:`symkin.dynamics.planar`): Lin and Parker's
  rotational-translational model of a simple planetary set (every body also translates on its
  bearings), derived from its energies; :func:`planar_geometry` takes its radii and planet places
  from a train.

Mass properties come from the links (``inertia``, ``mass``, ``stiffness``) and meshes
(``stiffness``), SI units; the model's lengths are millimetres (a train file's module, ISO 54),
converted to metres.  docs/dynamics.md explains the model and its assumptions.
"""

from symkin.dynamics.bodies import MILLIMETRE
from symkin.dynamics.planar import PlanarModel, planar_geometry, planar_model, planar_modes
from symkin.dynamics.rigid import EquationsOfMotion, Simulation, equations_of_motion
from symkin.dynamics.torsional import Modes, TorsionalModel, modes_of, natural_modes, torsional_model

__all__ = ["MILLIMETRE", "EquationsOfMotion", "Simulation", "equations_of_motion", "Modes", "TorsionalModel",
           "natural_modes", "torsional_model", "modes_of", "PlanarModel", "planar_model", "planar_modes",
           "planar_geometry"]
