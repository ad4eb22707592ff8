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

Every condition prints as LaTeX (:meth:`~symkin.synthesis.conditions.Condition.latex`).  The
parts the conditions are made of are :mod:`symkin.synthesis.parts`; the assembly is derived
in :mod:`symkin.synthesis.assembly`, the options in :mod:`symkin.synthesis.request`.

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
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError, UnsupportedError
from symkin.laws import Law
from symkin.model import Gear, LinkKind, Mechanism, Mesh
from symkin.synthesis.assembly import assembly_groups
from symkin.synthesis.conditions import Condition, derived_conditions
from symkin.synthesis.parts import (
    AssemblyGroup,
    CentreMesh,
    CoaxialRow,
    InternalMesh,
    PlanetArm,
    PlanetPair,
    Rim,
    mesh_module,
)
from symkin.synthesis.request import Options

__all__ = ["Problem", "derive", "symbolic_train"]


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
        """Every derived condition, the planet count substituted (see :class:`~symkin.synthesis.conditions.Condition`)."""
        return derived_conditions(self)


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
    assembly = tuple(assembly_groups(sym, counts))
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


def _arms(train: Mechanism) -> tuple[PlanetArm, ...]:
    out = []
    for L in train.links:
        if L.kind is not LinkKind.PLANET:
            continue
        meshes = []
        for mesh, _ in train.planet_centre_distances.get(L.name, ()):
            reference = train.mesh_geometry(Mesh(mesh.a, mesh.b)).centre_distance
            meshes.append(CentreMesh(mesh, reference, mesh.centre_distance, mesh_module(train, mesh)))
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
    """Every pair of distances one planet axis is put at must agree, within the profile shift ``y``."""
    y = options.shift
    rows = [row for arm in arms for row in _arm_rows(arm, y)]
    # meshes between planets with a given working distance
    for mesh in train.meshes:
        geo = train.mesh_geometry(mesh)
        if mesh.centre_distance is not None and geo.link_a.kind is LinkKind.PLANET and geo.link_b.kind is LinkKind.PLANET:
            reference = train.mesh_geometry(Mesh(mesh.a, mesh.b)).centre_distance
            rows.append(CoaxialRow(f"{geo.link_a.name}-{geo.link_b.name}", mesh.centre_distance, reference,
                                   y * mesh_module(train, mesh)))
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


def _arm_rows(arm: PlanetArm, y: sp.Rational) -> list[CoaxialRow]:
    """The coaxiality rows of one planet: its given arm against each mesh, or its first mesh against the
    others (and, with profile shift, every other pair, which the search checks)."""
    ms = arm.meshes
    rows = []
    if arm.fixed is not None:
        for m in ms:
            if m.working is not None:
                rows.append(CoaxialRow(arm.planet, arm.fixed, m.working, sp.Integer(0)))
                rows.append(CoaxialRow(arm.planet, m.working, m.reference, y * m.module))
            else:
                rows.append(CoaxialRow(arm.planet, arm.fixed, m.reference, y * m.module))
        return rows
    for j in range(1, len(ms)):
        rows.append(CoaxialRow(arm.planet, ms[0].reference, ms[j].reference, y * (ms[0].module + ms[j].module)))
    if y:
        for i in range(1, len(ms)):
            for j in range(i + 1, len(ms)):
                rows.append(CoaxialRow(arm.planet, ms[i].reference, ms[j].reference,
                                       y * (ms[i].module + ms[j].module), pivot=False))
    return rows


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
                              (ga.radius + h * ga.module, gb.radius + h * gb.module), mesh_module(train, mesh),
                              angles[lb.name] - angles[la.name]))
    return out
