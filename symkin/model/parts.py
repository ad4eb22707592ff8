"""The parts of a mechanism: gears, links and meshes, and the checks of what they are given.

Small immutable values (frozen dataclasses): they validate their inputs (names, radii, tooth
numbers, carriers) and derive nothing; :class:`~symkin.model.Mechanism` holds them.
"""

from __future__ import annotations

import decimal
import enum
import numbers
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.errors import ModelError
from symkin.values import as_expr, as_rational, sign_of

__all__ = ["FRAME", "MAIN_AXIS", "MAX_PLANETS", "LinkKind", "Gear", "Link", "Mesh", "MeshGeometry", "as_length",
           "as_teeth", "as_property", "mesh_pair"]

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
    # a float (20.0 too) is refused: a count is given as an integer (the gate would make 20.0 exact)
    floating = isinstance(value, numbers.Real) and not isinstance(value, (numbers.Rational, sp.Basic, decimal.Decimal))
    expr = sp.Float(value) if floating else as_expr(exact, what=what, finite=False, error=ModelError)
    if expr.is_number:
        if not expr.is_Integer:
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


def as_property(value: Any, what: str, unit: str) -> sp.Expr | None:
    """A mass property or a stiffness (``unit``, SI): a number >= 0 or a symbol; None stays None.

    >>> as_property(0.01, "inertia of link S", "kg*m**2")
    1/100
    >>> as_property(-1, "mass of planet P", "kg")
    Traceback (most recent call last):
    ...
    symkin.errors.ModelError: mass of planet P must be 0 or more (kg), got -1
    """
    if value is None:
        return None
    if isinstance(value, float):  # exact, as its decimal
        value = as_rational(value, what=what, error=ModelError)
    expr = as_expr(value, what=what, error=ModelError, unit=unit)
    if expr.is_negative or (expr.is_number and expr.is_extended_real is False):
        raise ModelError(f"{what} must be 0 or more ({unit.replace('**', '^')}), got {value!r}")
    return expr


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
    inertia : sympy expression or None
        Moment of inertia about the link's own axis (kg m^2; of one planet), for
        :mod:`symkin.dynamics`.
    mass : sympy expression or None
        For a planet: the mass of one planet (kg), whose centre moves with its axis.
    stiffness : sympy expression or None
        For a link about the main axis: the torsional stiffness of a shaft holding it to the
        frame (N m/rad), for the torsional model of :mod:`symkin.dynamics`.
    """

    name: str
    kind: LinkKind
    gears: tuple[Gear, ...] = ()
    carrier: str | None = None
    arm: sp.Expr | None = None
    position_angle: sp.Expr | None = None
    count: int = 1
    axis: str = "parallel"
    # out of the repr (which the stored notebooks show): mass properties are for symkin.dynamics
    inertia: sp.Expr | None = field(default=None, repr=False)
    mass: sp.Expr | None = field(default=None, repr=False)
    stiffness: sp.Expr | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        _name(self.name, "link name")
        self._check_mass_properties()
        if not isinstance(self.kind, LinkKind):
            raise ModelError(f"kind of link {self.name} must be a LinkKind, got {self.kind!r}")
        object.__setattr__(self, "gears", self._checked_gears())
        if self.kind is LinkKind.PLANET:
            self._check_carrier()
            self._check_placement()
            self._check_count()
            self._check_axis()
        elif (self.carrier is not None or self.arm is not None or self.position_angle is not None or self.count != 1
              or self.axis != "parallel"):
            raise ModelError(
                f"{self.kind.value} link {self.name} turns about the main axis: it takes no carrier, arm, position "
                "angle or planet count"
            )
        if self.kind is LinkKind.FRAME and self.name != FRAME:
            raise ModelError(f"the frame must be named {FRAME!r}, got {self.name!r}")

    def _check_mass_properties(self) -> None:
        """Check inertia, mass and stiffness, and that the link's kind takes each one given."""
        for key, unit in (("inertia", "kg*m**2"), ("mass", "kg"), ("stiffness", "N*m/rad")):
            object.__setattr__(self, key, as_property(getattr(self, key), f"{key} of link {self.name}", unit))
        if self.kind is LinkKind.FRAME and (self.inertia is not None or self.mass is not None or self.stiffness is not None):
            raise ModelError("the frame does not move: it takes no inertia, mass or stiffness")
        if self.kind is LinkKind.CENTRAL and self.mass is not None:
            raise ModelError(f"link {self.name} turns about the main axis, so its mass adds nothing: give its inertia "
                             "only (mass is for planets, whose centres move)")
        if self.kind is LinkKind.PLANET and self.stiffness is not None:
            raise ModelError(f"planet {self.name} takes no shaft stiffness: a stiffness holds a link about the main "
                             "axis to the frame")

    def _checked_gears(self) -> tuple[Gear, ...]:
        """The link's gears as a tuple, each a :class:`Gear`."""
        gears = tuple(self.gears)
        for g in gears:
            if not isinstance(g, Gear):
                raise ModelError(f"link {self.name} holds {g!r}, which is not a Gear")
        return gears

    def _check_carrier(self) -> None:
        """A planet's carrier: a link named, not the planet itself."""
        if self.carrier is None:
            raise ModelError(f"planet {self.name} needs a carrier: name the link that carries its axis")
        _name(self.carrier, f"carrier of planet {self.name}")
        if self.carrier == self.name:
            raise ModelError(f"planet {self.name} cannot carry its own axis; name another link as its carrier")

    def _check_placement(self) -> None:
        """A planet's arm (a positive length, or 0) and position angle, as expressions."""
        if self.arm is not None and not (isinstance(self.arm, (int, sp.Integer)) and self.arm == 0):
            object.__setattr__(self, "arm", as_length(self.arm, f"arm of planet {self.name}"))
        elif self.arm is not None:  # arm 0: the link turns about its carrier's own axis
            object.__setattr__(self, "arm", sp.Integer(0))
        if self.position_angle is not None:
            object.__setattr__(
                self, "position_angle",
                as_expr(self.position_angle, what=f"position angle of planet {self.name}", error=ModelError),
            )

    def _check_count(self) -> None:
        """How many planets of this kind: a whole number from 1 to :data:`MAX_PLANETS`."""
        if isinstance(self.count, bool) or not isinstance(self.count, int) or not 1 <= self.count <= MAX_PLANETS:
            raise ModelError(f"count of planet {self.name} must be a whole number from 1 to {MAX_PLANETS}, got {self.count!r}")

    def _check_axis(self) -> None:
        """A planet's axis: parallel, or radial (a bevel pinion: bevel gears only, no arm)."""
        if self.axis not in ("parallel", "radial"):
            raise ModelError(f"axis of planet {self.name} is 'parallel' or 'radial', got {self.axis!r}")
        if self.axis == "radial":
            if not all(g.bevel for g in self.gears):
                raise ModelError(f"planet {self.name} has a radial axis (a bevel pinion): its gears must be bevel gears")
            if self.arm is not None:
                raise ModelError(f"bevel pinion {self.name} takes no arm: its axis passes through its carrier's axis")

    @classmethod
    def central(cls, name: str, *gears: Gear, inertia: Any = None, stiffness: Any = None) -> Link:
        """A link turning about the main axis: a sun, a ring, or a carrier."""
        return cls(name, LinkKind.CENTRAL, gears, inertia=inertia, stiffness=stiffness)

    @classmethod
    def planet(
        cls, name: str, *gears: Gear, carrier: str = "H", arm: Any = None, position_angle: Any = None, count: int = 1,
        axis: str = "parallel", inertia: Any = None, mass: Any = None,
    ) -> Link:
        """A planet (satellite) carried by ``carrier``; a stepped planet has two gears.

        ``position_angle`` places its axis on the carrier at t = 0; left out, the
        mechanism places it (at 0, or from its mesh with another planet).  ``count``
        equal planets of this kind are equally spaced on the carrier.
        """
        return cls(name, LinkKind.PLANET, gears, carrier=carrier, arm=arm,
                   position_angle=position_angle, count=count, axis=axis, inertia=inertia, mass=mass)

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

    ``stiffness`` (optional, N/m) is the mesh's stiffness along its line of action, for the
    torsional model of :mod:`symkin.dynamics`.

    >>> Mesh("p", "s2", centre_distance=60).centre_distance
    60
    """

    a: str
    b: str
    centre_distance: sp.Expr | None = None
    efficiency: sp.Expr | None = None
    stiffness: sp.Expr | None = field(default=None, repr=False)

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
        object.__setattr__(self, "stiffness", as_property(self.stiffness, f"stiffness of mesh {self.a}-{self.b}", "N/m"))


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


def mesh_pair(m: Iterable[str]) -> tuple[str, str]:
    """The two gear names of a mesh given as a pair, or a ModelError.

    >>> mesh_pair(["1", "2"])
    ('1', '2')
    """
    try:
        a, b = m
    except (TypeError, ValueError):
        raise ModelError(f"a mesh is a pair of gear names, got {m!r}") from None
    return a, b
