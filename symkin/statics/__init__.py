"""Statics: torques and tooth forces, derived from the model where they can be.

:mod:`.power` holds the statics of any train: every link's torque per unit input torque
and every tooth force from the equilibrium of the links (virtual power on the contact
conditions), the power through each mesh, and the efficiency in closed form by the
basic-train method, both ways, with self-locking and circulating power (:func:`statics`).
:mod:`.operating` holds a train at an operating point: given speeds and torques, every
link's torque and power, ideal and with losses, and the loss (:func:`operating_point`).

:mod:`.planet` holds the statics of a stepped planet: its torque balance and helical
axial forces derived from the mesh geometry (:func:`planet_statics`), the hands that
cancel the axial forces (:func:`balancing_hands`, :func:`mesh_hand_relation`), and an
independent numeric computation of the 3-D tooth forces (:func:`planet_forces`).

    >>> from symkin import schemes
    >>> planet_statics(schemes.two_row("AI")).condition
    Eq(tan(beta_w2)/tan(beta_w3), r_2/r_3)
"""

from __future__ import annotations

from symkin.statics.operating import OperatingPoint, operating_point, statics
from symkin.statics.planet import (
    PlanetForces,
    PlanetStatics,
    balancing_hands,
    mesh_hand_relation,
    planet_forces,
    planet_statics,
)
from symkin.statics.power import DEFAULT_EFFICIENCY, MeshPower, Statics, efficiency_symbol, mesh_efficiencies

__all__ = ["statics", "Statics", "operating_point", "OperatingPoint", "MeshPower", "efficiency_symbol", "mesh_efficiencies", "DEFAULT_EFFICIENCY", "PlanetStatics", "planet_statics", "mesh_hand_relation", "balancing_hands", "PlanetForces", "planet_forces"]
