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

import decimal
import enum
import re
from collections import OrderedDict
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin._util.budget import simplify_within
from symkin.errors import CoaxialityWarning, ModelError, warn_user
from symkin.values import as_expr, as_rational, sign_of

__all__ = ["FRAME", "MAIN_AXIS", "LinkKind", "Gear", "Link", "Mesh", "Mechanism", "as_length", "as_teeth"]

#: Name of the mechanism frame (the fixed link that holds the main axis).
FRAME = "0"
#: The most equal planets of one kind a carrier may hold.
MAX_PLANETS = 64
#: The name of the main axis in :meth:`Mechanism.axis_of`.
MAIN_AXIS = "O"


# --------------------------------------------------------------------------- checks


def as_length(value: Any, what: str) -> sp.Expr:
    """Check and return a positive length (a pitch radius, a module, an arm).

    >>> as_length(2, "radius")
    2
    >>> as_length(-1, "pitch radius of gear 1")
    Traceback (most recent call last):
    ...
    symkin.errors.ModelError: pitch radius of gear 1 must be positive, got -1; give a positive pitch radius
    >>> as_length(0, "module of gear 1")
    Traceback (most recent call last):
    ...
    symkin.errors.ModelError: module of gear 1 must be positive, got 0; give a positive module
    """
    expr = as_expr(value, what=what, finite=False, error=ModelError)
    if expr.is_number:
        if expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or not expr.is_finite:
            raise ModelError(f"{what} must be a finite number, got {value!r}")
        if expr.is_extended_real is False:
            raise ModelError(f"{what} must be real, got {value!r}")
        # decided on intervals, not by SymPy's assumptions (which leave sin(1)**2 + cos(1)**2 - 1 open)
        sign = sign_of(expr, what=what, error=ModelError)
        if sign is None:
            raise ModelError(f"{what} must be positive, got {value!r}, which is 0 to 1300 digits; give a positive "
                             f"{what.split(' of ')[0]}")
        if sign != 1:
            raise ModelError(f"{what} must be positive, got {value!r}; give a positive {what.split(' of ')[0]}")
    elif expr.is_positive is False:
        raise ModelError(f"{what} must be positive, got {value!r}; give a positive {what.split(' of ')[0]}")
    return expr


def as_teeth(value: Any, what: str) -> sp.Expr:
    """Check and return a tooth number: a positive integer or an integer symbol.

    >>> as_teeth(20, "teeth of gear 1")
    20
    >>> as_teeth(20.5, "teeth of gear 1")
    Traceback (most recent call last):
    ...
    symkin.errors.ModelError: teeth of gear 1 must be a whole number, got 20.5; tooth numbers are positive integers
    """
    exact = value
    if isinstance(value, decimal.Decimal):  # an exact decimal, as a Fraction is: Decimal("20") is 20
        exact = as_rational(value, what=what, error=ModelError)
    expr = as_expr(exact, what=what, finite=False, error=ModelError)
    if expr.is_number:
        if not expr.is_Integer:
            if expr.is_finite and expr.is_integer:  # e.g. Float 20.0: still refuse, it is not exact
                pass
            raise ModelError(
                f"{what} must be a whole number, got {value!r}; tooth numbers are positive integers"
            )
        if expr <= 0:
            raise ModelError(f"{what} must be positive, got {value!r}; tooth numbers are positive integers")
    elif expr.is_integer is False or expr.is_positive is False:
        raise ModelError(f"{what} must be a positive integer symbol, got {value!r}")
    return expr


#: A link or gear name: ASCII letters and digits, joined by single ``_ - .``, maybe ending in
#: primes.  Names go into symbol names (``omega_<link>``, ``r_<gear>``) and from there into
#: LaTeX; these characters print as themselves in a subscript with base TeX Live, where a
#: backslash, a brace, ``% & # $ ^ ~``, a blank or a non-ASCII letter would run a command,
#: break the document, or need fonts it has not.
_NAME = re.compile(r"[A-Za-z0-9]+(?:[_.\-][A-Za-z0-9]+)*'*", re.ASCII)


def _name(value: Any, what: str) -> str:
    r"""``value`` if it is a valid link or gear name (see :data:`_NAME`).

    >>> _name("planet-2", "link name")
    'planet-2'
    >>> _name("\\input{/etc/hostname}", "link name")
    Traceback (most recent call last):
    ...
    symkin.errors.ModelError: link name must be ASCII letters and digits, joined by single _ - . and perhaps ending in ', such as 1, H, sun or planet-2; got '\\input{/etc/hostname}' (names are printed in LaTeX)
    """
    if not isinstance(value, str) or not value:
        raise ModelError(f"{what} must be a non-empty name such as 1, H, sun or planet-2, got {value!r}")
    if not _NAME.fullmatch(value):
        shown = value if len(value) <= 40 else value[:37] + "..."
        raise ModelError(
            f"{what} must be ASCII letters and digits, joined by single _ - . and perhaps ending in ', such as 1, H, "
            f"sun or planet-2; got {shown!r} (names are printed in LaTeX)"
        )
    return value


# --------------------------------------------------------------------------- parts
@dataclass(frozen=True)
class Gear:
    """A gear rim: its pitch radius, tooth number and whether it is internal.

    Parameters
    ----------
    name : str
        Gear name, e.g. ``"1"``; the paper's indices are 1 and 4 (central) and 2, 3 (planet).
    radius : sympy expression
        Working pitch radius.  The kinematic laws depend only on the ratio of the two
        radii of each mesh, so ``teeth`` (with a common module) can stand for it.
    teeth : int or integer symbol, optional
    internal : bool
        True for an internal (ring) gear.
    module : sympy expression, optional
        Module of a gear built from its tooth number.
    bevel : bool
        A bevel gear: it meshes a bevel gear whose axis crosses its own (a pinion on a
        radial axis, :attr:`Link.axis`); ``radius`` is its pitch radius at the contact.
    side : {+1, -1, 0}
        For a bevel gear turning about its carrier's axis (a side gear): whether it meets
        the pinions above (+1, towards +z) or below (-1) the plane of their axes.

    Notes
    -----
    ``radius`` need not equal ``module * teeth / 2``: a gear of a profile-shifted mesh
    works on a pitch circle other than its reference one, so ``Gear("1", 5, teeth=20,
    module=1)`` is accepted as given.  The kinematics uses ``radius`` only; ``teeth``
    and ``module`` are kept for synthesis and printing.  :meth:`from_teeth` builds the
    reference radius from them.

    >>> Gear("1", 5, teeth=20, module=1).radius   # a working radius, not m z / 2 = 10
    5
    """

    name: str
    radius: sp.Expr
    teeth: sp.Expr | None = None
    internal: bool = False
    module: sp.Expr | None = None
    bevel: bool = False
    side: int = 0

    def __post_init__(self) -> None:
        _name(self.name, "gear name")
        object.__setattr__(self, "radius", as_length(self.radius, f"pitch radius of gear {self.name}"))
        if self.teeth is not None:
            object.__setattr__(self, "teeth", as_teeth(self.teeth, f"tooth number of gear {self.name}"))
        if not isinstance(self.internal, bool):
            raise ModelError(f"internal of gear {self.name} must be True or False, got {self.internal!r}")
        if self.module is not None:
            object.__setattr__(self, "module", as_length(self.module, f"module of gear {self.name}"))
        if not isinstance(self.bevel, bool):
            raise ModelError(f"bevel of gear {self.name} must be True or False, got {self.bevel!r}")
        if self.side not in (-1, 0, 1) or isinstance(self.side, bool):
            raise ModelError(f"side of gear {self.name} is +1 (above the bevel pinions), -1 (below) or 0, got {self.side!r}")
        if self.side and not self.bevel:
            raise ModelError(f"gear {self.name} has a side but is not a bevel gear; a side belongs to a bevel side gear")
        if self.bevel and self.internal:
            raise ModelError(f"gear {self.name}: symkin's bevel gears are external (a crown or an internal bevel gear "
                             "is not modelled)")

    @classmethod
    def from_teeth(cls, name: str, teeth: Any, *, internal: bool = False, module: Any = None, bevel: bool = False,
                   side: int = 0) -> Gear:
        """A gear of ``teeth`` teeth and pitch radius ``module * teeth / 2``.

        The module defaults to the symbol ``m``; it cancels from every ratio.

        >>> Gear.from_teeth("1", 20).radius
        10*m
        """
        z = as_teeth(teeth, f"tooth number of gear {name}")
        m = S.module() if module is None else as_length(module, f"module of gear {name}")
        return cls(name, m * z / 2, teeth=z, internal=internal, module=m, bevel=bevel, side=side)

    @classmethod
    def symbolic(cls, name: str, *, internal: bool = False) -> Gear:
        """A gear whose pitch radius is the symbol ``r_name``.

        >>> Gear.symbolic("4", internal=True)
        Gear(name='4', radius=r_4, teeth=None, internal=True, module=None, bevel=False, side=0)
        """
        return cls(name, S.radius(name), internal=internal)


class LinkKind(str, enum.Enum):
    """What a link's axis is attached to."""

    FRAME = "frame"  #: the fixed link; its pole is the main axis O
    CENTRAL = "central"  #: turns about the main axis (sun, ring, carrier)
    PLANET = "planet"  #: its axis is carried by another link (a carrier)


@dataclass(frozen=True)
class Link:
    """A rigid link and the gear rims it carries.

    Build links with :meth:`central`, :meth:`planet` or :meth:`frame`.  A central link
    that carries planets is a carrier; it may hold gears too (the carrier of one stage
    holding the sun of the next).

    Attributes
    ----------
    name : str
    kind : LinkKind
    gears : tuple of Gear
    carrier : str or None
        For a planet: the link that carries its axis (a central link or the frame).
    arm : sympy expression or None
        For a planet: the distance of its axis from its carrier's axis (the main axis for
        a carrier on the main axis).  ``None`` derives it from the planet's first mesh with
        a gear that turns about the carrier's axis; ``0`` puts its axis on the carrier's:
        a link carried by a planet that turns about that planet's axis (the sun of a
        second level).
    position_angle : sympy expression or None
        For a planet: the angle of its axis on the carrier at t = 0 (0 = +x axis).
        ``None`` lets the mechanism place it (:meth:`Mechanism.position_angle`): from
        its mesh with a planet already placed (the triangle of the two arms and their
        centre distance), or at 0.
    count : int
        For a planet: how many equal planets of this kind the carrier holds, equally
        spaced (one link for kinematics; they share the load and are drawn).
    axis : {"parallel", "radial"}
        For a planet: its axis is parallel to the carrier's (the usual planet), or radial:
        perpendicular to it, pointing away from it at the position angle (a bevel pinion,
        whose gears are bevel gears).  The angular velocity of a radial planet is its spin
        about its own axis relative to its carrier.
    """

    name: str
    kind: LinkKind
    gears: tuple[Gear, ...] = ()
    carrier: str | None = None
    arm: sp.Expr | None = None
    position_angle: sp.Expr | None = None
    count: int = 1
    axis: str = "parallel"

    def __post_init__(self) -> None:
        _name(self.name, "link name")
        if not isinstance(self.kind, LinkKind):
            raise ModelError(f"kind of link {self.name} must be a LinkKind, got {self.kind!r}")
        gears = tuple(self.gears)
        for g in gears:
            if not isinstance(g, Gear):
                raise ModelError(f"link {self.name} holds {g!r}, which is not a Gear")
        object.__setattr__(self, "gears", gears)
        if self.kind is LinkKind.PLANET:
            if self.carrier is None:
                raise ModelError(f"planet {self.name} needs a carrier: name the link that carries its axis")
            _name(self.carrier, f"carrier of planet {self.name}")
            if self.carrier == self.name:
                raise ModelError(f"planet {self.name} cannot carry its own axis; name another link as its carrier")
            if self.arm is not None and not (isinstance(self.arm, (int, sp.Integer)) and self.arm == 0):
                object.__setattr__(self, "arm", as_length(self.arm, f"arm of planet {self.name}"))
            elif self.arm is not None:  # arm 0: the link turns about its carrier's own axis
                object.__setattr__(self, "arm", sp.Integer(0))
            if self.position_angle is not None:
                object.__setattr__(
                    self, "position_angle",
                    as_expr(self.position_angle, what=f"position angle of planet {self.name}", error=ModelError),
                )
            if isinstance(self.count, bool) or not isinstance(self.count, int) or not 1 <= self.count <= MAX_PLANETS:
                raise ModelError(f"count of planet {self.name} must be a whole number from 1 to {MAX_PLANETS}, got {self.count!r}")
            if self.axis not in ("parallel", "radial"):
                raise ModelError(f"axis of planet {self.name} is 'parallel' or 'radial', got {self.axis!r}")
            if self.axis == "radial":
                if not all(g.bevel for g in gears):
                    raise ModelError(f"planet {self.name} has a radial axis (a bevel pinion): its gears must be bevel gears")
                if self.arm is not None:
                    raise ModelError(f"bevel pinion {self.name} takes no arm: its axis passes through its carrier's axis")
        elif (self.carrier is not None or self.arm is not None or self.position_angle is not None or self.count != 1
              or self.axis != "parallel"):
            raise ModelError(
                f"{self.kind.value} link {self.name} turns about the main axis: it takes no carrier, arm, position "
                "angle or planet count"
            )
        if self.kind is LinkKind.FRAME and self.name != FRAME:
            raise ModelError(f"the frame must be named {FRAME!r}, got {self.name!r}")

    @classmethod
    def central(cls, name: str, *gears: Gear) -> Link:
        """A link turning about the main axis: a sun, a ring, or a carrier."""
        return cls(name, LinkKind.CENTRAL, gears)

    @classmethod
    def planet(
        cls, name: str, *gears: Gear, carrier: str = "H", arm: Any = None, position_angle: Any = None, count: int = 1,
        axis: str = "parallel",
    ) -> Link:
        """A planet (satellite) carried by ``carrier``; a stepped planet has two gears.

        ``position_angle`` places its axis on the carrier at t = 0; left out, the
        mechanism places it (at 0, or from its mesh with another planet).  ``count``
        equal planets of this kind are equally spaced on the carrier.
        """
        return cls(name, LinkKind.PLANET, gears, carrier=carrier, arm=arm,
                   position_angle=position_angle, count=count, axis=axis)

    @classmethod
    def frame(cls, *gears: Gear) -> Link:
        """The fixed frame, optionally holding fixed gears (a fixed ring)."""
        return cls(FRAME, LinkKind.FRAME, gears)


@dataclass(frozen=True)
class Mesh:
    """Two gears in mesh, by name, and optionally their working centre distance.

    ``efficiency`` (optional) is the mesh's efficiency for :mod:`symkin.statics`; the
    kinematics ignores it.  Without ``centre_distance`` the gears work on their pitch
    circles (their radii).  A
    ``centre_distance`` other than that reference distance is a profile-shifted mesh:
    both gears then work on circles in the ratio of their pitch radii (of their teeth,
    for a common module) that fit that distance.  Only positions change: the ratio of a
    mesh is the ratio of its working radii, which is that of its pitch radii.

    >>> Mesh("p", "s2", centre_distance=60).centre_distance
    60
    """

    a: str
    b: str
    centre_distance: sp.Expr | None = None
    efficiency: sp.Expr | None = None

    def __post_init__(self) -> None:
        _name(self.a, "gear name in a mesh")
        _name(self.b, "gear name in a mesh")
        if self.a == self.b:
            raise ModelError(f"a gear cannot mesh with itself ({self.a}); name two different gears")
        if self.centre_distance is not None:
            object.__setattr__(self, "centre_distance",
                               as_length(self.centre_distance, f"centre distance of mesh {self.a}-{self.b}"))
        if self.efficiency is not None:
            eta = as_expr(self.efficiency, what=f"efficiency of mesh {self.a}-{self.b}", error=ModelError)
            if eta.is_number and not (0 < eta <= 1):
                raise ModelError(f"the efficiency of mesh {self.a}-{self.b} must lie in (0, 1], got {self.efficiency!r}")
            object.__setattr__(self, "efficiency", eta)


@dataclass(frozen=True)
class MeshGeometry:
    """Where a mesh is, in the mesh's own frame (the paper's fig. 2: y along the line of centres).

    The first gear's axis A is the origin, the second's B is at (0, centre_distance) and the
    pitch point P at (0, pitch_y).  Each mesh uses its own centre distance, so its contact
    condition depends only on the ratio of its two pitch radii.
    """

    mesh: Mesh
    gear_a: Gear
    gear_b: Gear
    link_a: Link
    link_b: Link
    centre_distance: sp.Expr
    pitch_y: sp.Expr
    #: The link on which both gears' axes are fixed: the mesh's contact condition holds in
    #: its frame (a planet's carrier, the frame for fixed axes, a planet for a second level).
    holder: str = FRAME
    #: ``"bevel"`` for a bevel side gear and a radial pinion: the pinion's axis crosses the
    #: side gear's; ``centre_distance`` is then the contact's distance from the side gear's
    #: axis and ``pitch_y`` the pinion's pitch radius there, times the side (+1 or -1).
    kind: str = "parallel"


# --------------------------------------------------------------------------- mechanism
@dataclass(frozen=True)
class Mechanism:
    """A planar gear mechanism: links, the gears they hold, and the meshes between gears.

    The frame (link ``"0"``) is added when not given.  Objects are immutable; the laws a
    mechanism is asked for are derived on first use and cached.

    Parameters
    ----------
    links : sequence of Link
    meshes : sequence of Mesh or (gear, gear) pairs
    name : str, optional
        A label used in reports (e.g. ``"AA"``).

    Notes
    -----
    Coaxiality: every mesh between a planet and a gear turning about the main axis puts
    the planet's axis at a centre distance from the main axis; all of them must agree.
    :attr:`coaxiality` lists these conditions; when tooth numbers with a common module
    violate one, a :class:`~symkin.errors.CoaxialityWarning` is issued (the laws remain
    valid for the working pitch radii, which profile shift makes coaxial).
    """

    links: tuple[Link, ...]
    meshes: tuple[Mesh, ...]
    name: str = ""
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self) -> None:
        for what in ("links", "meshes"):
            value = getattr(self, what)
            if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
                raise ModelError(f"{what} must be a sequence, got {value!r}")
        links = tuple(self.links)
        if not any(isinstance(L, Link) and L.kind is LinkKind.FRAME for L in links):
            links = (Link.frame(),) + links
        meshes = tuple(m if isinstance(m, Mesh) else Mesh(*_pair(m)) for m in self.meshes)
        object.__setattr__(self, "links", links)
        object.__setattr__(self, "meshes", meshes)
        self._validate()
        object.__setattr__(self, "_cache", _shared_cache((links, meshes)))
        self._warn_coaxiality()
        self.position_angles  # noqa: B018  (places every planet now: a contradiction is a ModelError here)

    # ---- lookups
    @cached_property
    def _links_by_name(self) -> dict[str, Link]:
        return {L.name: L for L in self.links}

    @cached_property
    def _gears(self) -> dict[str, tuple[Gear, Link]]:
        return {g.name: (g, L) for L in self.links for g in L.gears}

    @property
    def moving_links(self) -> tuple[Link, ...]:
        """Every link but the frame, in the order given."""
        return tuple(L for L in self.links if L.kind is not LinkKind.FRAME)

    @property
    def link_names(self) -> tuple[str, ...]:
        """The names of the moving links, in the order they were given.

        >>> from symkin import schemes
        >>> schemes.two_row("AA").link_names
        ('1', '23', 'H', '4')
        """
        return tuple(L.name for L in self.moving_links)

    def gear(self, name: str) -> Gear:
        """The gear called ``name``."""
        try:
            return self._gears[name][0]
        except (KeyError, TypeError):
            raise ModelError(f"no gear {name!r} in this mechanism; its gears are {', '.join(self._gears)}") from None

    def link(self, name: str) -> Link:
        """The link called ``name``, or the link that holds the gear called ``name``.

        The paper speaks of "gear 2" for the planet carrying rim 2: both names work.

        >>> from symkin import schemes
        >>> schemes.two_row("AI").link("3").name
        '23'
        """
        if isinstance(name, str):
            if name in self._links_by_name:
                return self._links_by_name[name]
            if name in self._gears:
                return self._gears[name][1]
        valid = sorted(set(self.link_names) | set(self._gears))  # not the frame: it is no driver, driven or moving link
        raise ModelError(f"no link {name!r} in this mechanism; name one of {', '.join(valid)}")

    # ---- validation
    def _validate(self) -> None:
        seen: set[str] = set()
        for L in self.links:
            if not isinstance(L, Link):
                raise ModelError(f"{L!r} is not a Link; build links with Link.central, Link.planet or Link.frame")
            if L.name in seen:
                raise ModelError(f"two links are called {L.name!r}; give every link its own name")
            seen.add(L.name)
        gear_names: set[str] = set()
        for L in self.links:
            for g in L.gears:
                if g.name in gear_names:
                    raise ModelError(f"two gears are called {g.name!r}; give every gear its own name")
                gear_names.add(g.name)
        by_name = {L.name: L for L in self.links}
        for L in self.links:
            if L.kind is LinkKind.PLANET:
                assert L.carrier is not None  # Link.__post_init__ gives every planet a carrier
                c = by_name.get(L.carrier)
                if c is None:
                    raise ModelError(f"planet {L.name} names carrier {L.carrier!r}, which is not a link of this mechanism")
                chain = [L.name]
                while c.kind is LinkKind.PLANET:  # a planet of a planet: the chain must end on the main axis
                    chain.append(c.name)
                    if c.name in chain[:-1]:
                        raise ModelError(f"carrier cycle: {' -> '.join(chain)}; a chain of carriers must end on a link "
                                         "that turns about the main axis")
                    assert c.carrier is not None
                    c = by_name[c.carrier]
        if len({(frozenset((m.a, m.b))) for m in self.meshes}) != len(self.meshes):
            raise ModelError("a mesh is listed twice; list each pair of gears once")
        cones: dict[str, list[tuple[str, sp.Expr]]] = {}
        for mesh in self.meshes:
            geo = self.mesh_geometry(mesh)  # raises on an impossible mesh
            if geo.kind == "bevel":
                pinion_gear = geo.gear_a if geo.link_a.axis == "radial" else geo.gear_b
                side_gear = geo.gear_b if pinion_gear is geo.gear_a else geo.gear_a
                cones.setdefault(pinion_gear.name, []).append((side_gear.name, side_gear.radius))
        for pin, sides in cones.items():  # one pitch cone (apex on the carrier's axis) meets side gears of one size
            for other, radius in sides[1:]:
                if sp.expand(radius - sides[0][1]) != 0:
                    raise ModelError(
                        f"bevel pinion gear {pin} meshes side gears {sides[0][0]} and {other} of different pitch radii "
                        f"({sides[0][1]} and {radius}): one pitch cone cannot; give the pinion a gear for each")

    def mesh_geometry(self, mesh: Mesh) -> MeshGeometry:
        """Centre distance and pitch point of a mesh (see :class:`MeshGeometry`)."""
        ga, la = self._gear_and_link(mesh.a)
        gb, lb = self._gear_and_link(mesh.b)
        if la.name == lb.name:
            raise ModelError(f"gears {ga.name} and {gb.name} are on the same link {la.name}; they cannot mesh")
        if ga.bevel or gb.bevel or la.axis == "radial" or lb.axis == "radial":
            return self._bevel_geometry(mesh, ga, la, gb, lb)
        if ga.internal and gb.internal:
            raise ModelError(
                f"gears {ga.name} and {gb.name} are both internal and cannot mesh; "
                "an internal gear meshes with an external one"
            )
        if self.axis_of(la.name) == self.axis_of(lb.name):
            where = "the main axis" if self.axis_of(la.name) == MAIN_AXIS else f"the axis of {self.axis_of(la.name)}"
            raise ModelError(
                f"gears {ga.name} and {gb.name} both turn about {where} and cannot mesh; "
                "put one of them on a planet"
            )
        holder = self._holder(la, lb)
        if holder is None:
            raise ModelError(
                f"gears {ga.name} (link {la.name}) and {gb.name} (link {lb.name}) cannot stay in mesh: no link holds "
                "both their axes (two planets mesh when one carrier holds both, or one turns about the other's carrier)"
            )
        # sigma = -1 flips a pitch point to the far side when the partner is internal
        sa = -1 if gb.internal else 1
        sb = -1 if ga.internal else 1
        d = sp.expand(sa * ga.radius + sb * gb.radius)
        if d.is_positive is False or d.is_zero:
            big, small = (ga, gb) if ga.internal else (gb, ga)
            raise ModelError(
                f"internal gear {big.name} (pitch radius {big.radius}) must be larger than gear {small.name} "
                f"(pitch radius {small.radius}) that meshes inside it"
            )
        if mesh.centre_distance is None:
            return MeshGeometry(mesh, ga, gb, la, lb, d, sa * ga.radius, holder)
        # profile shift: the working circles keep the ratio of the pitch circles and fit the distance
        scale = sp.cancel(mesh.centre_distance / d)
        return MeshGeometry(mesh, ga, gb, la, lb, mesh.centre_distance, sa * ga.radius * scale, holder)

    def _bevel_geometry(self, mesh: Mesh, ga: Gear, la: Link, gb: Gear, lb: Link) -> MeshGeometry:
        """A bevel side gear on its carrier's axis and a bevel pinion on a radial axis."""
        if not (ga.bevel and gb.bevel):
            spur = ga.name if not ga.bevel else gb.name
            raise ModelError(f"gears {ga.name} and {gb.name}: gear {spur} is not a bevel gear; a bevel gear meshes a "
                             "bevel gear (give both bevel = true)")
        radial = [L for L in (la, lb) if L.axis == "radial"]
        if len(radial) != 1:
            raise ModelError(f"bevel gears {ga.name} and {gb.name}: one must be on a bevel pinion (a planet with a radial "
                             f"axis) and the other on its carrier's axis; {'both are' if radial else 'neither is'}")
        (pinion,) = radial
        side_gear, side_link, pin_gear = (gb, lb, ga) if pinion is la else (ga, la, gb)
        assert pinion.carrier is not None
        if self.axis_of(side_link.name) != self.axis_of(pinion.carrier):
            raise ModelError(f"bevel gear {side_gear.name} must turn about the axis of pinion {pinion.name}'s carrier "
                             f"{pinion.carrier} to mesh it")
        if side_gear.side == 0:
            raise ModelError(f"bevel side gear {side_gear.name} needs side = +1 (it meets the pinions above their "
                             "axes, towards +z) or -1 (below)")
        if mesh.centre_distance is not None:
            raise ModelError(f"mesh {mesh.a}-{mesh.b} is a bevel mesh: it takes no centre distance")
        return MeshGeometry(mesh, ga, gb, la, lb, side_gear.radius, side_gear.side * pin_gear.radius, pinion.carrier,
                            "bevel")

    # ---- axes
    def axis_of(self, link: str) -> str:
        """Which axis a link turns about: ``"O"`` (the main axis) for the frame and central
        links, a planet's own name, or its carrier's axis for a planet with ``arm = 0``.

        >>> from symkin import schemes
        >>> schemes.two_row("AI").axis_of("H"), schemes.two_row("AI").axis_of("23")
        ('O', '23')
        """
        L = self._links_by_name[link] if link in self._links_by_name else self.link(link)
        if L.kind is not LinkKind.PLANET:
            return MAIN_AXIS
        assert L.carrier is not None  # a planet has a carrier (Link.__post_init__)
        if L.arm is not None and L.arm == 0:
            return self.axis_of(L.carrier)
        return L.name

    def _fixed_axes(self, link: Link) -> set[str]:
        """The axes that stay fixed on ``link``: its own and those of the links it carries."""
        return {self.axis_of(link.name)} | {self.axis_of(X.name) for X in self.links
                                            if X.kind is LinkKind.PLANET and X.carrier == link.name}

    def _holder(self, la: Link, lb: Link) -> str | None:
        """A link on which both links' axes are fixed (their mesh's frame), or None."""
        axes = {self.axis_of(la.name), self.axis_of(lb.name)}
        candidates: list[str] = []
        for link in (la, lb):  # each link and the chain of its carriers
            at: Link | None = link
            while at is not None:
                candidates.append(at.name)
                at = self._links_by_name.get(at.carrier) if at.carrier is not None else None
        for name in dict.fromkeys(candidates):
            if axes <= self._fixed_axes(self._links_by_name[name]):
                return name
        if axes == {MAIN_AXIS}:
            return FRAME
        frame = self._links_by_name[FRAME]
        return FRAME if axes <= self._fixed_axes(frame) else None

    def _gear_and_link(self, name: str) -> tuple[Gear, Link]:
        self.gear(name)
        return self._gears[name]

    # ---- geometry
    @cached_property
    def planet_centre_distances(self) -> dict[str, tuple[tuple[Mesh, sp.Expr], ...]]:
        """For each planet with an axis of its own, the distance of its axis from its
        carrier's axis implied by each mesh between a gear on its axis (its own, or of a link
        turning about it) and a gear on the carrier's axis."""
        out: dict[str, list[tuple[Mesh, sp.Expr]]] = {}
        for mesh in self.meshes:
            geo = self.mesh_geometry(mesh)
            if geo.kind == "bevel":
                continue
            axes = (self.axis_of(geo.link_a.name), self.axis_of(geo.link_b.name))
            for planet, other in (axes, axes[::-1]):
                if planet == MAIN_AXIS:
                    continue
                carrier = self._links_by_name[planet].carrier  # an axis of its own is a planet's name
                assert carrier is not None
                if self.axis_of(carrier) == other:
                    out.setdefault(planet, []).append((mesh, geo.centre_distance))
        return {k: tuple(v) for k, v in out.items()}

    def arm(self, planet: str) -> sp.Expr:
        """Distance of a planet's axis from its carrier's axis (the main axis for a carrier on it).

        The planet's own ``arm`` if given, else the centre distance of its first mesh with
        a gear turning about its carrier's axis.

        >>> from symkin import schemes
        >>> schemes.two_row("AI").arm("23")
        r_1 + r_2
        """
        L = self.link(planet)
        if L.kind is not LinkKind.PLANET or L.axis == "radial":  # a bevel pinion's axis meets its carrier's
            return sp.Integer(0)
        if L.arm is not None:
            return L.arm
        dists = self.planet_centre_distances.get(L.name)
        if not dists:
            raise ModelError(
                f"planet {L.name} meshes with no gear on its carrier's axis, so its arm is unknown; "
                "give it with Link.planet(..., arm=...) (arm in a train file)"
            )
        return dists[0][1]

    @cached_property
    def position_angles(self) -> dict[str, sp.Expr]:
        """Where each planet's axis is on its carrier at t = 0: angle from the +x axis.

        A planet's given ``position_angle`` is kept.  Otherwise a planet that meshes a
        planet already placed is put where the two centre distances and the arms form a
        triangle (counter-clockwise from it: give the angle for the other solution), and
        any other planet at 0.  Every mesh between two planets is then checked: a given
        angle that puts two meshing planets at the wrong distance, or arms that no
        triangle can join, are a :class:`~symkin.errors.ModelError`.

        >>> from symkin.model import Gear, Link, Mechanism
        >>> m = Mechanism([Link.central("S", Gear("s", 4)), Link.central("C"), Link.central("R", Gear("r", 12, internal=True)),
        ...                Link.planet("A", Gear("a", 2), carrier="C"), Link.planet("B", Gear("b", 3), carrier="C")],
        ...               [("s", "a"), ("a", "b"), ("b", "r")])
        >>> m.position_angles["B"]   # arms 6 and 9, centre distance 5: cos = (36 + 81 - 25)/(2 6 9)
        acos(23/27)
        """
        planets = [L for L in self.links if L.kind is LinkKind.PLANET]
        angles: dict[str, sp.Expr] = {L.name: L.position_angle for L in planets if L.position_angle is not None}
        neighbours: dict[str, list[tuple[str, sp.Expr]]] = {L.name: [] for L in planets}
        for mesh in self.meshes:
            geo = self.mesh_geometry(mesh)
            la, lb = geo.link_a, geo.link_b
            if (geo.kind != "bevel" and la.kind is LinkKind.PLANET and lb.kind is LinkKind.PLANET and la.carrier == lb.carrier
                    and la.arm != 0 and lb.arm != 0):
                neighbours[la.name].append((lb.name, geo.centre_distance))
                neighbours[lb.name].append((la.name, geo.centre_distance))
        pending = [L.name for L in planets if L.name not in angles]
        while pending:
            for name in pending:
                placed = [(other, d) for other, d in neighbours[name] if other in angles]
                if placed:
                    other, d = placed[0]
                    angles[name] = angles[other] + self._triangle_angle(name, other, d)
                    break
            else:  # nothing to place from: start a group of meshing planets at 0
                angles[pending[0]] = sp.Integer(0)
                name = pending[0]
            pending.remove(name)
        for L in planets:
            for other, d in neighbours[L.name]:
                if L.name < other:
                    self._check_planet_distance(L.name, other, d, angles)
        return angles

    def axis_position(self, link: str) -> tuple[sp.Expr, sp.Expr]:
        """Where a link's axis is at t = 0, in the mechanism's own coordinates (the main axis
        at the origin): a planet's carrier's axis plus its arm at its position angle.

        >>> from symkin.trains import load_train
        >>> load_train("nested").axis_position("Q")   # a tool on a head: 45 + 15 along x
        (60, 0)
        """
        L = self.link(link)
        if L.kind is not LinkKind.PLANET:
            return sp.Integer(0), sp.Integer(0)
        assert L.carrier is not None
        x0, y0 = self.axis_position(L.carrier)
        arm, angle = self.arm(L.name), self.position_angle(L.name)
        return x0 + arm * sp.cos(angle), y0 + arm * sp.sin(angle)

    def position_angle(self, planet: str) -> sp.Expr:
        """The angle of a planet's axis on its carrier at t = 0 (see :attr:`position_angles`)."""
        L = self.link(planet)
        if L.kind is not LinkKind.PLANET:
            return sp.Integer(0)
        return self.position_angles[L.name]

    def _triangle_angle(self, planet: str, other: str, d: sp.Expr) -> sp.Expr:
        """The angle at the main axis between two meshing planets' axes (law of cosines)."""
        a, b = self.arm(planet), self.arm(other)
        cosine = sp.cancel((a**2 + b**2 - d**2) / (2 * a * b))
        if cosine.is_number and not (-1 <= cosine <= 1):
            raise ModelError(
                f"planets {other} and {planet} cannot mesh: their axes are at {b} and {a} from the main axis, "
                f"and no position puts them {d} apart (the arms differ by more than the centre distance, or add "
                "up to less); change the gears or the arms"
            )
        return sp.acos(cosine)

    def _check_planet_distance(self, p: str, q: str, d: sp.Expr, angles: Mapping[str, sp.Expr]) -> None:
        a, b = self.arm(p), self.arm(q)
        gap = a**2 + b**2 - 2 * a * b * sp.cos(angles[p] - angles[q]) - d**2
        if gap.is_number and gap.free_symbols == set():
            value = sp.N(gap, 30)
            if value.is_real and abs(value) > sp.Float(1e-20) * (1 + abs(sp.N(d**2, 30))):
                wanted = sp.acos(sp.cancel((a**2 + b**2 - d**2) / (2 * a * b)))
                raise ModelError(
                    f"planets {p} and {q} mesh but their given position angles put their axes "
                    f"{sp.N(sp.sqrt(gap + d**2), 6)} apart instead of the centre distance {d}; leave one angle out "
                    f"to have it placed, or make their angles differ by +-{wanted} = +-{sp.N(wanted, 6)} rad"
                )

    def _centre_distance_pairs(self) -> list[tuple[str, sp.Expr, sp.Expr]]:
        """(planet, reference distance, another distance) for every planet with two or more."""
        pairs = []
        for L in self.moving_links:
            if L.kind is not LinkKind.PLANET:
                continue
            dists = [d for _, d in self.planet_centre_distances.get(L.name, ())]
            ref = L.arm if L.arm is not None else (dists[0] if dists else None)
            pairs += [(L.name, ref, d) for d in dists if d != ref]
        return pairs

    @cached_property
    def coaxiality(self) -> tuple[sp.Eq, ...]:
        """The conditions under which every planet axis is where all its meshes put it.

        >>> from symkin import schemes
        >>> schemes.two_row("AI").coaxiality
        (Eq(r_1 + r_2, -r_3 + r_4),)
        """
        return tuple(sp.Eq(ref, d, evaluate=False) for _, ref, d in self._centre_distance_pairs())

    def coaxiality_defects(self) -> tuple[tuple[str, sp.Expr, sp.Expr], ...]:
        """Coaxiality conditions that fail: (planet, first centre distance, other one).

        Only conditions that can be decided (numbers, or a common module symbol that scales
        both sides) are listed.
        """
        defects = []
        for planet, ref, d in self._centre_distance_pairs():
            diff = sp.expand(ref - d)  # decides the usual linear combinations of radii at once
            if diff.free_symbols - self._module_symbols:
                continue  # symbolic dimensions: the condition is reported, not decided
            if diff.is_zero is None:  # e.g. cos(beta) in helical radii
                diff = simplify_within(diff, what=f"the coaxiality condition of planet {planet}")
            if diff.is_zero is False or (diff.is_zero is None and not diff.equals(0)):
                defects.append((planet, ref, d))
        return tuple(defects)

    @cached_property
    def _module_symbols(self) -> set[sp.Symbol]:
        return {s for L in self.links for g in L.gears if g.module is not None for s in g.module.free_symbols}

    def _warn_coaxiality(self) -> None:
        for planet, d1, d2 in self.coaxiality_defects():
            warn_user(
                f"planet {planet} is not coaxial: its meshes put its axis at {d1} and at {d2} from the "
                "main axis; the kinematic laws hold for working pitch radii in the tooth ratios "
                "(profile shift), positions use the first distance",
                CoaxialityWarning,
            )

    # ---- derived laws (delegated to the derivation modules; cached here)
    @property
    def dof(self) -> int:
        """Degrees of freedom: moving links minus independent contact conditions."""
        from symkin.kinematics import kinematic_system

        return kinematic_system(self).dof

    def contact_conditions(self) -> tuple[sp.Eq, ...]:
        """One equation per mesh: equal velocities of both gears at the pitch point (eq. 5)."""
        from symkin.kinematics import kinematic_system

        return kinematic_system(self).equations

    def speeds(self, known: Mapping[str, Any]) -> Any:
        """Angular velocity of every link, given the speeds of some links.

        See :func:`symkin.kinematics.solve_speeds`.
        """
        from symkin.kinematics import solve_speeds

        return solve_speeds(self, known)

    def ratio(self, driver: str, driven: str, fixed: str | Sequence[str] | None = None) -> Any:
        """The ratio i_ab^(c) = omega_a / omega_b with link(s) c fixed.

        See :func:`symkin.kinematics.ratio`.
        """
        from symkin.kinematics import ratio

        return ratio(self, driver, driven, fixed)

    def motion(self, inputs: Mapping[str, Any], frame: Any = None) -> Any:
        """The motion of every link for given input drives; see :class:`symkin.particles.Motion`."""
        from symkin.particles import Motion

        motion = Motion.build(self, inputs, frame)
        try:
            return self._memo(("motion", motion.inputs, motion.frame, motion.space), lambda: motion)
        except TypeError:  # an input that cannot be hashed: not shared
            return motion

    def _memo(self, key: Any, compute: Any) -> Any:
        """Return ``compute()`` for ``key``, computing it once per mechanism value: equal
        mechanisms (the same links and meshes) share what is derived from them."""
        try:
            return self._cache[key]
        except KeyError:
            value = self._cache[key] = compute()
            return value


#: Derived laws of mechanisms by value (links, meshes): the most recently used are kept.
_CACHES: OrderedDict[Any, dict] = OrderedDict()
_CACHE_SIZE = 256


def _shared_cache(key: Any) -> dict:
    """The cache of derived laws shared by every mechanism equal to ``key``."""
    try:
        cache = _CACHES.pop(key)
    except KeyError:
        cache = {}
    except TypeError:  # unhashable parts: a cache of its own
        return {}
    _CACHES[key] = cache
    while len(_CACHES) > _CACHE_SIZE:
        _CACHES.popitem(last=False)
    return cache


def _pair(m: Iterable[str]) -> tuple[str, str]:
    try:
        a, b = m
    except (TypeError, ValueError):
        raise ModelError(f"a mesh is a pair of gear names, got {m!r}") from None
    return a, b
