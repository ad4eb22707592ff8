r"""The conditions of tooth-number synthesis, derived from the model of any train.

:func:`derive` takes a train whose tooth numbers are symbols (a train file with
``teeth = "z1"``; a file that gives every tooth number as a number has them all made
unknown) and a ratio (driver, driven and held links, or a gear state), and derives from
the model, never per scheme:

- **coaxiality**: each planet's meshes with gears on the main axis put its axis at one
  distance (:attr:`~symkin.model.Mechanism.planet_centre_distances`); with profile shift
  allowed, the reference centre distances may differ from one working distance by
  ``shift`` modules each;
- **assembly** of ``k`` equally spaced copies of every planet kind: turn the whole train
  by ``2 pi / k`` (a copy then stands where the next one goes) and turn each gear on the
  main axis back by ``2 pi / k`` less a whole number of its pitches, the carrier held;
  the engine's contact conditions (:func:`symkin.kinematics.contact_condition`), written
  for these turns, must hold with some turn of each planet kind.  Eliminating the planet
  turns leaves integer conditions in the tooth numbers (stepped planets and planets
  meshing planets included);
- **neighbours**: adjacent copies of a planet clear each other with tip clearance
  ``c`` modules, ``2 a_w sin(pi/k) > d_a + c m`` for each of its gears; copies of two
  meshing planet kinds are placed from their arms and centre distance (law of cosines,
  as :attr:`~symkin.model.Mechanism.position_angles`) and clear the copies they do not
  mesh;
- **limits**: every tooth number in ``[zmin, zmax]`` (``zmin`` by default the least
  number without undercut, ``2 h_a* / sin^2 alpha``), and internal gears at least
  ``ring_difference`` teeth larger than the gears meshing them.

Every condition prints as LaTeX (:meth:`Condition.latex`).

    >>> from symkin.trains import load_train
    >>> problem = derive(load_train("simple"), driver="S", driven="C", fixed="R", planets=3)
    >>> problem.unknowns
    (z_s, z_p, z_r)
    >>> print(problem.ratio)
    i_{SC}^{(R)} = z_r/z_s + 1
    >>> for c in problem.conditions()[:4]:
    ...     print(c)
    limits (every gear): 18 <= z <= 150
    internal gear (r): z_r >= z_p + 8
    coaxiality (planet P): z_p/2 + z_s/2 = -z_p/2 + z_r/2
    assembly (P on carrier C): (z_r + z_s)/3 is an integer
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.errors import CoaxialityWarning, InputError, UnsupportedError
from symkin.kinematics import contact_condition
from symkin.laws import Law
from symkin.model import FRAME, MAX_PLANETS, Gear, Link, LinkKind, Mechanism, Mesh
from symkin.values import as_integer, as_rational

__all__ = [
    "K", "Options", "Condition", "CentreMesh", "PlanetArm", "CoaxialRow", "AssemblyRow", "AssemblyGroup", "Rim",
    "PlanetPair", "InternalMesh", "Problem", "derive", "symbolic_train", "undercut_minimum", "MAX_TEETH",
]

#: The number of equally spaced copies of each planet kind, while deriving.
K = sp.Symbol("k", positive=True, integer=True)
#: The largest tooth number a search accepts.
MAX_TEETH = 10_000
#: The link that holds the frame's gears while the assembly is derived (they turn back like any central gear).
_FREED = "frame-gears"  # a valid link name (names go into LaTeX: symkin.model checks them)


class gcd(sp.Function):
    """The greatest common divisor of integers, as printed in a condition (never evaluated)."""

    def _latex(self, printer: Any) -> str:
        return r"\gcd\left(" + ", ".join(printer._print(a) for a in self.args) + r"\right)"

    def _sympystr(self, printer: Any) -> str:
        return "gcd(" + ", ".join(printer._print(a) for a in self.args) + ")"


# --------------------------------------------------------------------------- options
#: Pressure angles of involute gears, degrees: below 5 the undercut-free minimum runs to hundreds of
#: teeth and beyond (1e-300 degrees: about 10^604), above 45 the teeth are pointed.
PRESSURE_ANGLES = (5, 45)


def undercut_minimum(pressure_angle_deg: Any = 20, addendum: Any = 1) -> int:
    """The least tooth number cut without undercut by a rack: ``z sin^2(alpha) >= 2 h_a*``.

    >>> undercut_minimum(20), undercut_minimum(14.5), undercut_minimum(25), undercut_minimum(20, 0.8)
    (18, 32, 12, 14)
    """
    alpha = as_rational(pressure_angle_deg, what="the pressure angle")
    h = as_rational(addendum, what="the addendum coefficient h_a*")
    if not PRESSURE_ANGLES[0] <= alpha <= PRESSURE_ANGLES[1]:
        raise InputError(f"the pressure angle must be between {PRESSURE_ANGLES[0]} and {PRESSURE_ANGLES[1]} degrees "
                         f"(usual: 20), got {alpha}")
    if not 0 < h <= 2:
        raise InputError(f"the addendum coefficient h_a* must be positive and at most 2, got {h}; the usual value is 1")
    bound = 2 * h / sp.sin(alpha * sp.pi / 180) ** 2
    n = int(sp.ceiling(bound))
    if n > 1 and (n - 1) * sp.sin(alpha * sp.pi / 180) ** 2 >= 2 * h:  # ceiling decided by digits: confirm exactly
        n -= 1
    return max(n, 1)


@dataclass(frozen=True)
class Options:
    """What a synthesis asks of every design beyond its ratio.

    Parameters
    ----------
    planets : int or None
        Equally spaced copies of every planet kind (k); None keeps each planet's ``count``.
    zmin, zmax : int, optional
        Tooth limits of every unknown gear; ``zmin`` defaults to :func:`undercut_minimum`.
    pressure_angle : number
        Pressure angle in degrees (for the undercut limit), default 20.
    addendum : number
        Addendum coefficient h_a* (tip radius = pitch radius + h_a* m), default 1.
    clearance : number
        Least gap between the tip circles of neighbouring planets, in modules, default 0.
    shift : number
        Profile shift allowed: the largest ``|a_w - a| / m`` of a mesh (centre-distance
        modification coefficient y), default 0 (meshes on their pitch circles).
    ring_difference : int
        Least tooth difference of an internal gear and a gear meshing it, default 8.

    >>> Options(planets=3).zmin, Options(planets=3, pressure_angle=25).zmin
    (18, 12)
    """

    planets: Any = 3
    zmin: Any = None
    zmax: Any = 150
    pressure_angle: Any = 20
    addendum: Any = 1
    clearance: Any = 0
    shift: Any = 0
    ring_difference: Any = 8

    def __post_init__(self) -> None:
        def put(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        if self.planets is not None:
            put("planets", int(as_integer(self.planets, what="the number of planets k", minimum=1,
                                          maximum=MAX_PLANETS)))
        put("pressure_angle", as_rational(self.pressure_angle, what="the pressure angle"))
        put("addendum", as_rational(self.addendum, what="the addendum coefficient h_a*"))
        default_min = undercut_minimum(self.pressure_angle, self.addendum)
        zmin = default_min if self.zmin is None else int(as_integer(self.zmin, what="zmin", minimum=1,
                                                                    maximum=MAX_TEETH))
        put("zmin", zmin)
        put("zmax", int(as_integer(self.zmax, what="zmax", minimum=1, maximum=MAX_TEETH)))
        if self.zmax < self.zmin:
            raise InputError(f"zmin = {self.zmin} is larger than zmax = {self.zmax}; give zmin <= zmax")
        put("clearance", as_rational(self.clearance, what="the tip clearance"))
        if not 0 <= self.clearance <= 10:
            raise InputError(f"the tip clearance between planets must be from 0 to 10 modules, got {self.clearance}")
        put("shift", as_rational(self.shift, what="the profile shift limit"))
        if not 0 <= self.shift <= 2:
            raise InputError(f"the profile shift limit |a_w - a|/m must be from 0 to 2 modules, got {self.shift}")
        put("ring_difference", int(as_integer(self.ring_difference, what="the ring difference",
                                              minimum=0, maximum=MAX_TEETH)))


# --------------------------------------------------------------------------- conditions
@dataclass(frozen=True)
class Condition:
    """One derived condition, printable as text and LaTeX.

    Attributes
    ----------
    kind : str
        ``"limits"``, ``"internal gear"``, ``"coaxiality"``, ``"assembly"``, ``"neighbours"``,
        ``"placement"`` or ``"ratio"``.
    subject : str
        What it is about (a planet, a carrier and its planets, a gear).
    relation : sympy relation
        The condition (an equation, an inequality, or ``Contains(x, Integers)``).
    description : str
    integers : tuple of Symbol
        Integers that must exist for the relation to hold (assembly).
    """

    kind: str
    subject: str
    relation: Any
    description: str = ""
    integers: tuple[sp.Symbol, ...] = ()

    def text(self) -> str:
        """The relation as one line of text."""
        rel = self.relation
        if isinstance(rel, sp.Contains):
            body = f"{sp.sstr(rel.args[0])} is an integer"
        elif isinstance(rel, sp.And) and _is_range(rel):
            lo, x, hi = _range_parts(rel)
            body = f"{lo} <= {x} <= {hi}"
        elif isinstance(rel, sp.Equality):
            body = f"{sp.sstr(rel.lhs)} = {sp.sstr(rel.rhs)}"
        else:
            body = sp.sstr(rel)
        if self.integers:
            body += f" for some integers {', '.join(map(str, self.integers))}"
        return body

    def latex(self) -> str:
        r"""The relation in LaTeX (:func:`symkin.latex`).

        >>> from symkin.trains import load_train
        >>> print(derive(load_train("simple"), driver="S", driven="C", fixed="R").conditions()[3].latex())
        \frac{z_{r} + z_{s}}{3} \in \mathbb{Z}
        """
        from symkin.printing import latex

        rel = self.relation
        if isinstance(rel, sp.And) and _is_range(rel):
            lo, x, hi = _range_parts(rel)
            tex = rf"{latex(lo)} \leq {latex(x)} \leq {latex(hi)}"
        elif isinstance(rel, sp.Contains):
            tex = latex(rel.args[0]) + r" \in \mathbb{Z}"
        else:
            tex = latex(rel)
        if self.integers:
            tex += r", \quad " + ", ".join(latex(n) for n in self.integers) + r" \in \mathbb{Z}"
        return tex

    def __str__(self) -> str:
        return f"{self.kind} ({self.subject}): {self.text()}" if self.subject else f"{self.kind}: {self.text()}"

    def to_json(self) -> dict[str, Any]:
        """The condition as JSON: its kind, subject, text, LaTeX and description."""
        return {"kind": self.kind, "subject": self.subject, "text": self.text(), "latex": self.latex(),
                "description": self.description}


def _is_range(rel: sp.And) -> bool:
    a, b = rel.args if len(rel.args) == 2 else (None, None)
    return isinstance(a, sp.LessThan) and isinstance(b, sp.LessThan) and (a.rhs == b.lhs or a.lhs == b.rhs)


def _range_parts(rel: sp.And) -> tuple[Any, Any, Any]:
    a, b = rel.args
    if a.rhs == b.lhs:
        return a.lhs, a.rhs, b.rhs
    return b.lhs, b.rhs, a.rhs


# --------------------------------------------------------------------------- derived parts
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


@dataclass(frozen=True)
class Problem:
    """Everything a search needs, derived from a train (see the module docstring).

    Attributes
    ----------
    train : Mechanism
        The train with symbolic tooth numbers.
    unknowns : tuple of Symbol
        The tooth numbers to find, in the order of the file's gears.
    gears : tuple of (Symbol, tuple of str)
        The gears each unknown stands for.
    ratio : Law
        The ratio law in the unknowns (derived by the kinematics).
    arms, coaxiality, assembly, rims, pairs, internal_meshes
        The derived parts of the conditions.
    options : Options
    notes : tuple of str
        What was assumed (e.g. every tooth number of the file made unknown).
    """

    train: Mechanism
    unknowns: tuple[sp.Symbol, ...]
    gears: tuple[tuple[sp.Symbol, tuple[str, ...]], ...]
    ratio: Law
    arms: tuple[PlanetArm, ...]
    coaxiality: tuple[CoaxialRow, ...]
    assembly: tuple[AssemblyGroup, ...]
    rims: tuple[Rim, ...]
    pairs: tuple[PlanetPair, ...]
    internal_meshes: tuple[InternalMesh, ...]
    options: Options
    counts: tuple[tuple[str, int], ...]
    notes: tuple[str, ...] = ()
    request: tuple[Any, ...] = ()

    def ratio_of(self, train: Mechanism) -> Law:
        """The same ratio (driver, driven and held links, or state) of another train, e.g. one with numbers."""
        driver, driven, fixed, state = self.request
        return _ratio_law(train, driver, driven, fixed, state)

    @property
    def count(self) -> dict[str, int]:
        """Copies of each planet kind."""
        return dict(self.counts)

    def gears_of(self, z: sp.Symbol) -> tuple[str, ...]:
        """The names of the gears whose tooth number is the unknown ``z``."""
        return dict(self.gears)[z]

    def arm_of(self, planet: str) -> PlanetArm:
        """The arm of the planet named ``planet`` (a ``KeyError`` when the problem has none)."""
        for a in self.arms:
            if a.planet == planet:
                return a
        raise KeyError(planet)

    def assembles(self, teeth: Mapping[Any, int]) -> bool:
        """True when the derived assembly conditions hold for these tooth numbers (decided exactly).

        >>> from symkin.trains import load_train
        >>> p = derive(load_train("simple"), driver="S", driven="C", fixed="R", planets=4)
        >>> p.assembles({"z_s": 20, "z_p": 30, "z_r": 80}), p.assembles({"z_s": 21, "z_p": 30, "z_r": 81})
        (True, False)
        """
        from fractions import Fraction

        from symkin.synthesis.integers import solvable

        values = {z: int(teeth[z] if z in teeth else teeth[str(z)]) for z in self.unknowns}
        for group in self.assembly:
            k = self.count[group.planets[0]]
            if k < 2:
                continue
            names = list(group.integers)
            G, h = [], []
            for row in group.rows:
                coeff = {n: int(c.subs(values)) for n, c in row.coefficients}
                G.append([coeff.get(n, 0) for n in names])
                h.append(Fraction(int(row.numerator.subs(values)), row.denominator * k))
            if not solvable(G, h):
                return False
        return True

    def conditions(self) -> tuple[Condition, ...]:
        """Every derived condition, the planet count substituted (see :class:`Condition`)."""
        o = self.options
        out: list[Condition] = []
        z = sp.Symbol("z", positive=True, integer=True)
        out.append(Condition("limits", "every gear", sp.And(sp.Le(o.zmin, z), sp.Le(z, o.zmax)),
                             f"every unknown tooth number; z >= {undercut_minimum(o.pressure_angle, o.addendum)} "
                             f"cuts no undercut at alpha = {o.pressure_angle} deg, h_a* = {o.addendum}"))
        for im in self.internal_meshes:
            if o.ring_difference and (im.internal_teeth.free_symbols or im.external_teeth.free_symbols):
                out.append(Condition("internal gear", im.internal,
                                     sp.Ge(im.internal_teeth, im.external_teeth + o.ring_difference),
                                     f"internal gear {im.internal} at least {o.ring_difference} teeth more than "
                                     f"{im.external} (no tip interference)"))
        for row in self.coaxiality:
            if row.tolerance == 0:
                rel: Any = sp.Eq(row.lhs, row.rhs, evaluate=False)
                what = "both meshes put the planet axis at one distance"
            else:
                rel = sp.Le(sp.Abs(row.expr), row.tolerance)
                what = f"the reference centre distances within {row.tolerance} of each other (profile shift)"
            if rel is not sp.true:
                out.append(Condition("coaxiality", f"planet {row.planet}", rel, what))
        for group in self.assembly:
            k = self.count[group.planets[0]]
            if k < 2:
                continue
            for arow in group.rows:
                out.append(_assembly_condition(group, arow, k))
        for rim in self.rims:
            k = self.count[rim.planet]
            if k < 2:
                continue
            arm = self.arm_of(rim.planet)
            a = arm.arm if o.shift == 0 else sp.Symbol(f"a_w{rim.planet}", positive=True)
            rel = sp.StrictGreaterThan(2 * a * sp.sin(sp.pi / k), 2 * rim.tip_radius + o.clearance * rim.module)
            out.append(Condition("neighbours", f"planet {rim.planet}, gear {rim.gear}", rel,
                                 f"{k} copies of {rim.planet}: the chord between neighbouring axes exceeds the tip "
                                 f"diameter of {rim.gear}" + (f" plus a clearance of {o.clearance} m" if o.clearance else "")))
        for pair in self.pairs:
            k = self.count[pair.first]
            a, b = self.arm_of(pair.first).arm, self.arm_of(pair.second).arm
            d = pair.centre_distance
            out.append(Condition("placement", f"planets {pair.first}, {pair.second}",
                                 sp.And(sp.Le(sp.Abs(a - b), d), sp.Le(d, a + b)),
                                 f"the arms of {pair.first} and {pair.second} and their centre distance form a triangle"))
            if k >= 2:
                gamma = sp.Symbol(f"gamma_{pair.first}{pair.second}")
                t = sp.Symbol("t", positive=True, integer=True)
                A, B = sp.Symbol(f"a_{pair.first}", positive=True), sp.Symbol(f"a_{pair.second}", positive=True)
                ra, rb = pair.tip_radii
                dist2 = A**2 + B**2 - 2 * A * B * sp.cos(gamma + 2 * sp.pi * t / k)
                rel = sp.StrictGreaterThan(dist2, (ra + rb + o.clearance * pair.module) ** 2)
                out.append(Condition("neighbours", f"planets {pair.first}, {pair.second}", rel,
                                     f"for t = 1 .. {k - 1}: copy t of {pair.second} clears {pair.first} (tip circles "
                                     f"of {pair.gears[0]} and {pair.gears[1]}); {A} = {sp.sstr(a)}, {B} = {sp.sstr(b)}, "
                                     f"{gamma} = {sp.sstr(pair.angle)} (the angle between their axes)"))
        return tuple(out)


def _assembly_condition(group: AssemblyGroup, row: AssemblyRow, k: int) -> Condition:
    subject = f"{', '.join(group.planets)} on carrier {group.carrier if group.carrier != FRAME else 'the frame'}"
    rhs = sp.factor_terms(row.rhs(k))
    coeffs = [c for _, c in row.coefficients]
    if row.kind == "integral":
        return Condition("assembly", subject, sp.Contains(rhs, sp.Integers, evaluate=False),
                         f"{k} copies can be assembled (whole pitches of the gears on the main axis)")
    if row.kind == "divisible":
        g = coeffs[0] if len(coeffs) == 1 else gcd(*coeffs)
        return Condition("assembly", subject, sp.Contains(sp.factor_terms(row.numerator / (row.denominator * k * g)),
                                                          sp.Integers, evaluate=False),
                         f"{k} copies can be assembled: the pitches to make up are a multiple of the gcd")
    if row.kind == "zero":
        return Condition("assembly", subject, sp.Eq(row.numerator, 0), f"{k} copies can be assembled")
    lhs = sp.Add(*(c * n for n, c in row.coefficients))
    return Condition("assembly", subject, sp.Eq(lhs, rhs, evaluate=False),
                     f"{k} copies can be assembled (these integers are shared with the other rows of the group)",
                     integers=tuple(n for n, _ in row.coefficients))


# --------------------------------------------------------------------------- derivation
def symbolic_train(train: Mechanism) -> tuple[Mechanism, tuple[str, ...]]:
    """The train with symbolic tooth numbers, and notes on what was made unknown.

    A train whose file names symbols (``teeth = "z1"``) is kept; one that gives every tooth
    number as a number has every one made unknown (``z_<gear>``).

    >>> from symkin.trains import load_train
    >>> t, notes = symbolic_train(load_train("simple"))
    >>> [g.teeth for L in t.links for g in L.gears], notes[0][:38]
    ([z_s, z_p, z_r], 'the train gives every tooth number, so')
    """
    gears = [g for L in train.links for g in L.gears]
    for g in gears:
        if g.teeth is None:
            raise InputError(f"gear {g.name} gives a radius and no tooth number; synthesis chooses tooth numbers, so "
                             "give every gear its teeth (a number or a name such as \"z1\")")
        if not (g.teeth.is_Integer or isinstance(g.teeth, sp.Symbol)):
            raise UnsupportedError(f"gear {g.name} has {g.teeth} teeth; give each tooth number as a number or one "
                                   "symbol")
        if g.module is None or not g.module.is_Rational:
            raise InputError(f"gear {g.name} has no numeric module; give the train a module (module = 1)")
        if sp.simplify(g.radius - g.module * g.teeth / 2) != 0:
            raise InputError(f"gear {g.name} gives its radius {g.radius}, not module x teeth / 2; synthesis works on "
                             "reference pitch circles: leave the radius out (a mesh may give a working centre_distance)")
    if any(isinstance(g.teeth, sp.Symbol) for g in gears):
        return train, ()
    links = []
    for L in train.links:
        new = tuple(Gear.from_teeth(g.name, S.teeth(g.name), internal=g.internal, module=g.module) for g in L.gears)
        links.append(dataclasses.replace(L, gears=new))
    note = ("the train gives every tooth number, so every one is searched (write teeth = \"z1\" in the file for "
            "those to find and numbers for those to keep)")
    if isinstance(train, _train_class()):
        return dataclasses.replace(train, links=tuple(links)), (note,)
    return Mechanism(tuple(links), train.meshes, name=train.name), (note,)


def _train_class() -> type:
    from symkin.trains import Train

    return Train


def derive(train: Mechanism, *, driver: str | None = None, driven: str | None = None,
           fixed: str | Sequence[str] | None = None, state: str | None = None, options: Options | None = None,
           **option_fields: Any) -> Problem:
    """Derive the conditions of a synthesis from a train (see the module docstring).

    Parameters
    ----------
    train : Mechanism or Train
        Symbolic tooth numbers are the unknowns; without any, every tooth number is.
    driver, driven, fixed : str
        The ratio omega_driver / omega_driven with the ``fixed`` link(s) held; or
    state : str
        A gear state of the train (its brakes and clutches).
    options : Options, or its fields as keyword arguments

    Raises
    ------
    InputError, ModelError, UnsupportedError
        A train that cannot be synthesised, or a ratio the unknowns do not change.

    Examples
    --------
    >>> from symkin.trains import load_train
    >>> p = derive(load_train("ravigneaux"), driver="S1", driven="R", fixed="C", planets=3)
    >>> print(p.ratio)
    i_{S1R}^{(C)} = z_r/z_s1
    >>> [c.text() for c in p.conditions() if c.kind == "assembly"]
    ['(z_s1 + z_s2)/3 is an integer', '(z_r - z_s1)/3 is an integer']
    """
    if options is None:
        options = Options(**option_fields)
    elif option_fields:
        raise InputError("give either options or their fields, not both")
    if not isinstance(train, Mechanism):
        raise InputError(f"a synthesis needs a train or a mechanism, got {train!r}")
    fixed_key = (fixed,) if isinstance(fixed, str) or fixed is None else tuple(fixed)
    return _derive(train, driver, driven, fixed_key, state, options)


@lru_cache(maxsize=16)
def _derive(train: Mechanism, driver: str | None, driven: str | None, fixed: tuple, state: str | None,
            options: Options) -> Problem:
    sym, notes = symbolic_train(train)
    gears_of: dict[sp.Symbol, list[str]] = {}
    for L in sym.links:
        for g in L.gears:
            if isinstance(g.teeth, sp.Symbol):
                gears_of.setdefault(g.teeth, []).append(g.name)
    unknowns = tuple(gears_of)
    ratio = _ratio_law(sym, driver, driven, fixed, state)
    if not ratio.rhs.free_symbols & set(unknowns):
        raise InputError(f"the ratio {ratio.lhs} = {ratio.rhs} does not depend on the unknown tooth numbers "
                         f"({', '.join(map(str, unknowns))}); make the teeth that set it unknown (\"z1\")")
    extra = ratio.rhs.free_symbols - set(unknowns)
    if extra:
        raise UnsupportedError(f"the ratio depends on {', '.join(sorted(map(str, extra)))}, which are not tooth "
                               "numbers; give numeric modules and radii from teeth")
    counts = _counts(sym, options)
    arms = _arms(sym)
    coax = _coaxial_rows(arms, sym, options)
    assembly = tuple(_assembly_groups(sym, counts))
    rims = tuple(Rim(L.name, g.name, g.radius, g.radius + options.addendum * g.module, g.module)
                 for L in sym.links if L.kind is LinkKind.PLANET for g in L.gears)
    pairs = tuple(_pairs(sym, options))
    internal = []
    for mesh in sym.meshes:
        ga, gb = sym.gear(mesh.a), sym.gear(mesh.b)
        if ga.internal or gb.internal:
            gi, ge = (ga, gb) if ga.internal else (gb, ga)
            internal.append(InternalMesh(gi.name, ge.name, gi.teeth, ge.teeth))
    return Problem(sym, unknowns, tuple((z, tuple(v)) for z, v in gears_of.items()), ratio, arms, coax, assembly,
                   rims, pairs, tuple(internal), options, tuple(counts.items()), notes, (driver, driven, fixed, state))


def _ratio_law(train: Mechanism, driver: Any, driven: Any, fixed: tuple, state: str | None) -> Law:
    if state is not None:
        if driver is not None or driven is not None or fixed not in ((None,), ()):
            raise InputError("give either a state or driver, driven and fixed links, not both")
        if not hasattr(train, "shift"):
            raise InputError("a state needs a train with states (a train file)")
        return train.shift(state).ratio
    if driver is None or driven is None:
        raise InputError("name the driver and the driven link (and the held ones), or a state of the train")
    held = tuple(f for f in fixed if f is not None)
    return train.ratio(driver, driven, held)


def _counts(train: Mechanism, options: Options) -> dict[str, int]:
    out = {}
    for L in train.links:
        if L.kind is LinkKind.PLANET:
            out[L.name] = L.count if options.planets is None else options.planets
    return out


def _module_of(train: Mechanism, mesh: Mesh) -> sp.Rational:
    ma, mb = train.gear(mesh.a).module, train.gear(mesh.b).module
    if ma != mb:
        raise InputError(f"gears {mesh.a} and {mesh.b} mesh but have modules {ma} and {mb}; meshing gears share "
                         "one module")
    return ma


def _arms(train: Mechanism) -> tuple[PlanetArm, ...]:
    out = []
    for L in train.links:
        if L.kind is not LinkKind.PLANET:
            continue
        meshes = []
        for mesh, _ in train.planet_centre_distances.get(L.name, ()):
            reference = train.mesh_geometry(Mesh(mesh.a, mesh.b)).centre_distance
            meshes.append(CentreMesh(mesh, reference, mesh.centre_distance, _module_of(train, mesh)))
        fixed = L.arm
        if fixed is None:
            given = [m.working for m in meshes if m.working is not None]
            fixed = given[0] if given else None
        if not meshes and fixed is None:
            raise UnsupportedError(f"planet {L.name} meshes no gear on the main axis and has no arm; give its arm")
        assert L.carrier is not None
        out.append(PlanetArm(L.name, L.carrier, tuple(meshes), fixed))
    return tuple(out)


def _coaxial_rows(arms: Sequence[PlanetArm], train: Mechanism, options: Options) -> tuple[CoaxialRow, ...]:
    y = options.shift
    rows = []
    for arm in arms:
        ms = arm.meshes
        if arm.fixed is not None:
            for m in ms:
                if m.working is not None:
                    rows.append(CoaxialRow(arm.planet, arm.fixed, m.working, sp.Integer(0)))
                    rows.append(CoaxialRow(arm.planet, m.working, m.reference, y * m.module))
                else:
                    rows.append(CoaxialRow(arm.planet, arm.fixed, m.reference, y * m.module))
            continue
        for j in range(1, len(ms)):
            rows.append(CoaxialRow(arm.planet, ms[0].reference, ms[j].reference, y * (ms[0].module + ms[j].module)))
        if y:
            for i in range(1, len(ms)):
                for j in range(i + 1, len(ms)):
                    rows.append(CoaxialRow(arm.planet, ms[i].reference, ms[j].reference,
                                           y * (ms[i].module + ms[j].module), pivot=False))
    # meshes between planets with a given working distance
    for mesh in train.meshes:
        geo = train.mesh_geometry(mesh)
        if mesh.centre_distance is not None and geo.link_a.kind is LinkKind.PLANET and geo.link_b.kind is LinkKind.PLANET:
            reference = train.mesh_geometry(Mesh(mesh.a, mesh.b)).centre_distance
            rows.append(CoaxialRow(f"{geo.link_a.name}-{geo.link_b.name}", mesh.centre_distance, reference,
                                   y * _module_of(train, mesh)))
    out = []
    for row in rows:
        value = row.expr
        if not value.free_symbols:  # a constant: either always true or the train is inconsistent
            if abs(value) > row.tolerance:
                raise InputError(f"planet {row.planet}: the train gives distances {row.lhs} and {row.rhs} for its "
                                 "axis, which no tooth numbers change; correct the arm or the centre distances")
            continue
        out.append(row)
    return tuple(out)


def _pairs(train: Mechanism, options: Options) -> list[PlanetPair]:
    out = []
    angles = train.position_angles
    for mesh in train.meshes:
        geo = train.mesh_geometry(mesh)
        la, lb = geo.link_a, geo.link_b
        if la.kind is not LinkKind.PLANET or lb.kind is not LinkKind.PLANET:
            continue
        if la.position_angle is not None or lb.position_angle is not None:
            raise UnsupportedError(f"planets {la.name} and {lb.name} mesh and one has a given angle; leave the angles "
                                   "of meshing planets out, the synthesis places them from their arms")
        ga, gb = geo.gear_a, geo.gear_b
        h = options.addendum
        out.append(PlanetPair(la.name, lb.name, (ga.name, gb.name), geo.centre_distance,
                              (ga.radius + h * ga.module, gb.radius + h * gb.module), _module_of(train, mesh),
                              angles[lb.name] - angles[la.name]))
    return out


# --------------------------------------------------------------------------- assembly
def _freed(train: Mechanism) -> Mechanism:
    """The train with the frame's gears on a link of their own (turning like any central gear)
    and every mesh on its pitch circles: the tooth pitches of the assembly are counted there."""
    frame = next(L for L in train.links if L.kind is LinkKind.FRAME)
    links = [Link.frame()] + [L for L in train.links if L.kind is not LinkKind.FRAME]
    if frame.gears:
        links.append(Link.central(_FREED, *frame.gears))
    with warnings.catch_warnings():  # the pitch circles of shifted meshes are not coaxial: that is expected here
        warnings.simplefilter("ignore", CoaxialityWarning)
        return Mechanism(tuple(links), tuple(Mesh(m.a, m.b) for m in train.meshes))


def _clusters(train: Mechanism) -> list[tuple[str, list[str]]]:
    planets = [L for L in train.links if L.kind is LinkKind.PLANET]
    parent = {L.name: L.name for L in planets}

    def find(x: str) -> str:
        while parent[x] != x:
            x = parent[x]
        return x

    for mesh in train.meshes:
        geo = train.mesh_geometry(mesh)
        if geo.link_a.kind is LinkKind.PLANET and geo.link_b.kind is LinkKind.PLANET:
            parent[find(geo.link_a.name)] = find(geo.link_b.name)
    groups: dict[str, list[str]] = {}
    for L in planets:
        groups.setdefault(find(L.name), []).append(L.name)
    carrier = {L.name: L.carrier for L in planets}
    return [(str(carrier[members[0]]), members) for members in groups.values()]


def _assembly_groups(train: Mechanism, counts: Mapping[str, int]) -> list[AssemblyGroup]:
    freed = _freed(train)
    out = []
    for carrier, planets in _clusters(train):
        ks = {counts[p] for p in planets}
        if len(ks) > 1:
            raise InputError(f"planets {', '.join(planets)} mesh each other but have different counts; give meshing "
                             "planets one count")
        out.append(AssemblyGroup(carrier, tuple(planets), _assembly_rows(freed, carrier, planets)))
    return out


def _assembly_rows(train: Mechanism, carrier: str, planets: Sequence[str]) -> tuple[AssemblyRow, ...]:
    """The integer conditions for k equally spaced copies of a group of planets (module docstring)."""
    cluster = set(planets)
    turn = {p: sp.Symbol(f"u_{p}", real=True) for p in planets}  # extra turn of each planet kind, in revolutions
    back: dict[str, sp.Symbol] = {}  # extra turn of each central link, in revolutions
    gear_rows: list[sp.Expr] = []
    mesh_rows: list[sp.Expr] = []
    integers: list[sp.Symbol] = []
    seen_gears: set[str] = set()
    for mesh in train.meshes:
        geo = train.mesh_geometry(mesh)
        links = (geo.link_a, geo.link_b)
        if not any(L.name in cluster for L in links):
            continue
        eq = contact_condition(train, mesh)
        expr = eq.lhs - eq.rhs
        subs: dict[sp.Symbol, sp.Expr] = {S.omega(carrier): sp.Integer(0)} if carrier != FRAME else {}
        for L, g in zip(links, (geo.gear_a, geo.gear_b)):
            if L.kind is LinkKind.PLANET:
                subs[S.omega(L.name)] = 2 * sp.pi * turn[L.name]
            elif L.name == carrier:
                raise UnsupportedError(f"gear {g.name} on carrier {carrier} meshes its own planets; symkin derives the "
                                       "assembly of planets meshing gears on other links")
            else:
                back.setdefault(L.name, sp.Symbol(f"t_{L.name}", real=True))
                subs[S.omega(L.name)] = 2 * sp.pi * (-1 / K + back[L.name])
                if g.name not in seen_gears:
                    seen_gears.add(g.name)
                    n = sp.Symbol(f"n_{g.name}", integer=True)
                    integers.append(n)
                    gear_rows.append(g.teeth * back[L.name] - n)  # the link turns back by whole pitches of g
        row = sp.expand(expr.subs(subs) / (sp.pi * _module_of(train, mesh)))
        if all(L.kind is LinkKind.PLANET for L in links):
            n = sp.Symbol(f"n_{geo.gear_a.name}{geo.gear_b.name}", integer=True)
            integers.append(n)
            row -= n  # two copies mesh alike when their mesh differs by whole pitches
        mesh_rows.append(row)
    reals = set(turn.values()) | set(back.values())
    known: dict[sp.Symbol, sp.Expr] = {}
    pending = gear_rows + mesh_rows
    progress = True
    while progress:
        progress = False
        for i, row in enumerate(pending):
            row = sp.expand(row.subs(known))
            unknown = [r for r in reals if r not in known and row.has(r)]
            if len(unknown) == 1:
                r = unknown[0]
                c = row.coeff(r)
                known[r] = sp.expand(-(row - c * r) / c)
                pending.pop(i)
                progress = True
                break
    leftover = [r for r in reals if r not in known]
    if leftover:
        raise UnsupportedError(f"planets {', '.join(planets)} mesh no gear on the main axis; symkin derives the assembly "
                               "of planets that do")
    rows = []
    for row in pending:
        row = sp.expand(row.subs(known))
        if row == 0:
            continue
        rows.append(_integer_row(row, integers))
    return _classify(rows)


def _integer_row(row: sp.Expr, integers: Sequence[sp.Symbol]) -> tuple[dict[sp.Symbol, sp.Expr], sp.Expr, int]:
    """``row = 0`` written as ``sum(G_i n_i) = R / (q k)`` with integer polynomials G_i, R."""
    # the integers come from whole pitches, the constants from turns of 1/k: k row = k sum(a_i n_i) + b
    num, den = sp.fraction(sp.together(sp.expand(row * K)))
    num = sp.expand(num)
    for f in sp.Mul.make_args(den):  # products of tooth numbers and positive constants: never zero
        base = f.base if f.is_Pow else f
        if not (base.is_positive and (base.is_number or isinstance(base, sp.Symbol))) or base == K:
            raise UnsupportedError(f"the assembly condition divides by {f}")  # pragma: no cover
    coeffs = {n: sp.expand(num.coeff(n)) for n in integers if num.has(n)}
    constant = sp.expand(num - sum(c * n for n, c in coeffs.items()))
    gs = {n: sp.cancel(c / K) for n, c in coeffs.items()}
    if any(g.has(K) for g in gs.values()) or constant.has(K):
        raise UnsupportedError("the assembly condition is not linear in 1/k")  # pragma: no cover
    rhs = sp.expand(-constant)
    lcm = 1
    for e in [*gs.values(), rhs]:
        for c in _coefficients(e):
            lcm = math.lcm(lcm, int(sp.Rational(c).q))
    gs = {n: sp.expand(g * lcm) for n, g in gs.items()}
    rhs = sp.expand(rhs * lcm)
    content = 0
    for g in gs.values():
        for c in _coefficients(g):
            content = math.gcd(content, int(c))
    content = content or 1
    gs = {n: sp.expand(g / content) for n, g in gs.items()}
    lead = _coefficients(rhs)[0] if rhs != 0 else (_coefficients(next(iter(gs.values())))[0] if gs else 1)
    if lead < 0:
        gs = {n: -g for n, g in gs.items()}
        rhs = -rhs
    return gs, rhs, content


def _coefficients(expr: sp.Expr) -> list[sp.Rational]:
    if not expr.free_symbols:
        return [sp.Rational(expr)]
    return sp.Poly(expr, *sorted(expr.free_symbols, key=str)).coeffs()


def _classify(rows: list[tuple[dict[sp.Symbol, sp.Expr], sp.Expr, int]]) -> tuple[AssemblyRow, ...]:
    """Decide how each row is checked: rows with an unknown of their own need no system."""
    kinds: list[str | None] = [None] * len(rows)
    changed = True
    while changed:
        changed = False
        for i, (gs, _, _) in enumerate(rows):
            if kinds[i] is not None:
                continue
            others = {n for j, (g2, _, _) in enumerate(rows) if j != i and kinds[j] is None for n in g2}
            own = [n for n in gs if n not in others]
            if not gs:
                kinds[i] = "zero"
            elif any(gs[n] in (1, -1) for n in own):
                kinds[i] = "integral"
            elif len(own) == len(gs):
                kinds[i] = "divisible"
            else:
                continue
            changed = True
    out = []
    for (gs, rhs, q), kind in zip(rows, kinds):
        out.append(AssemblyRow(tuple(gs.items()), rhs, q, kind or "system"))
    return tuple(out)
