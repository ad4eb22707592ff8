"""The parts of a synthesis problem, derived from the train: the values the conditions are made of.

Each planet's place (:class:`PlanetArm`, its meshes with the main axis :class:`CentreMesh`),
the coaxiality rows (:class:`CoaxialRow`), the assembly's integer rows by carrier
(:class:`AssemblyGroup` of :class:`AssemblyRow`), the planets' rims and the pairs of meshing
planets for the neighbour and placement conditions (:class:`Rim`, :class:`PlanetPair`), and
the internal meshes (:class:`InternalMesh`).  :mod:`symkin.synthesis.problem` derives them;
:mod:`symkin.synthesis.conditions` prints them; the search compiles them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin.errors import InputError
from symkin.model import Mechanism, Mesh

__all__ = ["K", "CentreMesh", "PlanetArm", "CoaxialRow", "AssemblyRow", "AssemblyGroup", "Rim", "PlanetPair",
           "InternalMesh", "mesh_module"]

#: The number of equally spaced copies of each planet kind, while deriving.
K = sp.Symbol("k", positive=True, integer=True)


def mesh_module(train: Mechanism, mesh: Mesh) -> sp.Rational:
    """The module of a mesh: its two gears' common module (meshing gears share one)."""
    ma, mb = train.gear(mesh.a).module, train.gear(mesh.b).module
    if ma != mb:
        raise InputError(f"gears {mesh.a} and {mesh.b} mesh but have modules {ma} and {mb}; meshing gears share "
                         "one module")
    return ma


@dataclass(frozen=True)
class CentreMesh:
    """A planet's mesh with a gear turning about the main axis.

    ``reference`` is the centre distance of the pitch circles (the model's mesh geometry
    without a working distance), ``working`` the distance the train gives (profile shift),
    or None; ``module`` that of the mesh.
    """

    mesh: Mesh
    reference: sp.Expr
    working: sp.Expr | None
    module: sp.Rational


@dataclass(frozen=True)
class PlanetArm:
    """Where a planet's axis is: its meshes with gears on the main axis, and a given arm.

    ``fixed`` is the planet's given arm or a given working centre distance, else None (the
    arm is the common centre distance of its meshes).
    """

    planet: str
    carrier: str
    meshes: tuple[CentreMesh, ...]
    fixed: sp.Expr | None

    @property
    def arm(self) -> sp.Expr:
        """The arm without profile shift (the model's :meth:`~symkin.model.Mechanism.arm`)."""
        if self.fixed is not None:
            return self.fixed
        return self.meshes[0].reference


@dataclass(frozen=True)
class CoaxialRow:
    """``|expr| <= tolerance``: two distances of one planet axis agree (within a profile shift).

    ``expr`` is linear in the tooth numbers (a length), ``lhs`` and ``rhs`` the two distances;
    ``pivot`` is False for a pair that the other rows do not imply (three or more meshes with
    profile shift), which the search checks rather than solves for.
    """

    planet: str
    lhs: sp.Expr
    rhs: sp.Expr
    tolerance: sp.Rational
    pivot: bool = True

    @property
    def expr(self) -> sp.Expr:
        """The coaxiality condition as one expression that must vanish, ``lhs - rhs`` expanded."""
        return sp.expand(self.lhs - self.rhs)


@dataclass(frozen=True)
class AssemblyRow:
    """``sum(G_i n_i) = R / (q k)`` for some integers n_i.

    ``kind`` says how it is decided: ``"integral"`` (an unknown of its own with coefficient
    +-1: ``R / (q k)`` must be a whole number), ``"divisible"`` (every unknown its own:
    ``R / (q k)`` a multiple of the gcd of the G_i), ``"zero"`` (no unknown: ``R = 0``) or
    ``"system"`` (unknowns shared with other rows: decided together).
    """

    coefficients: tuple[tuple[sp.Symbol, sp.Expr], ...]
    numerator: sp.Expr
    denominator: int
    kind: str

    def rhs(self, k: Any = K) -> sp.Expr:
        """The right-hand side of the assembly condition, ``numerator / (denominator k)`` for ``k`` planets."""
        return self.numerator / (self.denominator * k)


@dataclass(frozen=True)
class AssemblyGroup:
    """The assembly of one carrier's connected planets (planets meshing planets form one group)."""

    carrier: str
    planets: tuple[str, ...]
    rows: tuple[AssemblyRow, ...]

    @property
    def integers(self) -> tuple[sp.Symbol, ...]:
        """The integer unknowns of the group's rows, each once, in order of appearance."""
        seen: dict[sp.Symbol, None] = {}
        for row in self.rows:
            for n, _ in row.coefficients:
                seen[n] = None
        return tuple(seen)


@dataclass(frozen=True)
class Rim:
    """A gear of a planet: its pitch and tip radius (``addendum`` modules above the pitch circle)."""

    planet: str
    gear: str
    radius: sp.Expr
    tip_radius: sp.Expr
    module: sp.Rational


@dataclass(frozen=True)
class PlanetPair:
    """Two planet kinds on one carrier whose gears mesh: placed by the law of cosines."""

    first: str
    second: str
    gears: tuple[str, str]
    centre_distance: sp.Expr
    tip_radii: tuple[sp.Expr, sp.Expr]
    module: sp.Rational
    angle: sp.Expr


@dataclass(frozen=True)
class InternalMesh:
    """An internal gear and the gear meshing it (their tooth numbers)."""

    internal: str
    external: str
    internal_teeth: sp.Expr
    external_teeth: sp.Expr
