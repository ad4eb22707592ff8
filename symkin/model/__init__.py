"""The mechanism model: gears, links, meshes and the mechanism that holds them.

These are small immutable value objects.  They validate what they are given and
know their own geometry (where each gear's axis is, where each pitch point lies);
they derive no kinematics.  The derivation methods live in :mod:`symkin.kinematics`
and :mod:`symkin.particles` and consume this model, so a new method needs no change
here.

Conventions (those of the 2009 paper): every link turns in one plane; central links
(suns, rings, carriers) turn about the main axis O; a planet's axis is carried by a
carrier at a distance ``arm`` from the main axis; angles are counter-clockwise seen
from +z.

    >>> from symkin.model import Gear, Link, Mechanism
    >>> m = Mechanism(
    ...     links=[Link.central("1", Gear.from_teeth("1", 20)),
    ...            Link.planet("2", Gear.from_teeth("2", 30), carrier="H"),
    ...            Link.central("H"),
    ...            Link.frame(Gear.from_teeth("4", 80, internal=True))],
    ...     meshes=[("1", "2"), ("2", "4")])
    >>> m.dof
    1
"""

from __future__ import annotations

from symkin.model.mechanism import Mechanism
from symkin.model.parts import (
           FRAME,
           MAIN_AXIS,
           MAX_PLANETS,
           Gear,
           Link,
           LinkKind,
           Mesh,
           MeshGeometry,
           as_length,
           as_teeth,
)

__all__ = ["FRAME", "MAIN_AXIS", "MAX_PLANETS", "LinkKind", "Gear", "Link", "Mesh", "MeshGeometry", "Mechanism",
           "as_length", "as_teeth"]

# the public classes are known by the package's path (reprs, pickles, the API reference), as before the split
for _cls in (Gear, Link, LinkKind, Mesh, MeshGeometry, Mechanism):
    _cls.__module__ = __name__
del _cls
