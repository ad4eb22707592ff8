"""The mechanism: links and meshes validated together, their geometry, and the derived laws cached.

A :class:`Mechanism` places every axis (planets on their carriers, planets that mesh planets
from the triangle of their arms), checks coaxiality, and caches what is derived from it by
value, so that equal mechanisms share their laws.  ``speeds``, ``ratio`` and ``motion`` are the
convenience layer: they call the engine (:mod:`symkin.kinematics`, :mod:`symkin.particles`),
imported inside them.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import sympy as sp

from symkin._util.budget import simplify_within
from symkin._util.display import html_table, short_repr
from symkin.errors import CoaxialityWarning, ModelError, warn_user
from symkin.model.parts import FRAME, MAIN_AXIS, Gear, Link, LinkKind, Mesh, MeshGeometry, mesh_pair

if TYPE_CHECKING:  # the engine's result types, for annotations only (the engine imports the model)
    from symkin.kinematics import Speeds
    from symkin.laws import Law
    from symkin.particles import Motion

__all__ = ["Mechanism"]


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

    def __repr__(self) -> str:
        """A short repr (under 200 characters): the name, the links and the meshes.

        >>> from symkin import schemes
        >>> schemes.single_row_AI(teeth=(20, 30, 80))
        Mechanism('AI1', links 1, 2, H, 4, meshes 1-2, 2-4)
        """
        return short_repr(type(self).__name__, repr(self.name), "links " + ", ".join(L.name for L in self.moving_links),
                          "meshes " + ", ".join(f"{m.a}-{m.b}" for m in self.meshes))

    def _repr_html_(self) -> str:
        """For Jupyter: the kinematic scheme (SVG, :func:`symkin.viz.diagram`) and a table of the links."""
        from symkin.viz.diagram import scheme_svg

        rows = []
        for L in self.links:
            if L.kind.value == "frame" and not L.gears:
                continue
            gears = ", ".join(f"{g.name} ({g.teeth if g.teeth is not None else g.radius}{', internal' if g.internal else ''})"
                              for g in L.gears)
            rows.append((L.name, L.kind.value, L.carrier or "", gears or "-"))
        table = html_table(["link", "kind", "carrier", "gears (teeth)"], rows,
                           caption=f"{self.name or 'mechanism'}: meshes " + ", ".join(f"{m.a}-{m.b}" for m in self.meshes))
        return scheme_svg(self) + table

    def __post_init__(self) -> None:
        for what in ("links", "meshes"):
            value = getattr(self, what)
            if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
                raise ModelError(f"{what} must be a sequence, got {value!r}")
        links = tuple(self.links)
        if not any(isinstance(L, Link) and L.kind is LinkKind.FRAME for L in links):
            links = (Link.frame(),) + links
        meshes = tuple(m if isinstance(m, Mesh) else Mesh(*mesh_pair(m)) for m in self.meshes)
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
            if name == "frame" and FRAME in self._links_by_name:  # train files name the frame [links.frame]
                return self._links_by_name[FRAME]
        valid = sorted(set(self.link_names) | set(self._gears))  # not the frame: it is no driver, driven or moving link
        raise ModelError(f"no link {name!r} in this mechanism; name one of {', '.join(valid)}")

    # ---- validation
    def _validate(self) -> None:
        self._check_link_names()
        self._check_gear_names()
        self._check_carriers()
        self._check_meshes()

    def _check_link_names(self) -> None:
        """Every link a :class:`Link`, of its own name, none named as the frame or the main axis but the frame."""
        seen: set[str] = set()
        for L in self.links:
            if not isinstance(L, Link):
                raise ModelError(f"{L!r} is not a Link; build links with Link.central, Link.planet or Link.frame")
            if (L.name == FRAME and L.kind is not LinkKind.FRAME) or L.name == MAIN_AXIS:
                raise ModelError(f"the link name {L.name!r} is reserved (symkin's name for the "
                                 f"{'frame' if L.name == FRAME else 'main axis'}); give the link another name")
            if L.name in seen:
                raise ModelError(f"two links are called {L.name!r}; give every link its own name")
            seen.add(L.name)

    def _check_gear_names(self) -> None:
        gear_names: set[str] = set()
        for L in self.links:
            for g in L.gears:
                if g.name in gear_names:
                    raise ModelError(f"two gears are called {g.name!r}; give every gear its own name")
                gear_names.add(g.name)

    def _check_carriers(self) -> None:
        """Every planet's carrier a link of this mechanism, each chain of carriers ending on the main axis."""
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

    def _check_meshes(self) -> None:
        """Each pair of gears listed once, every mesh possible (:meth:`mesh_geometry`), and each bevel pinion gear
        meeting side gears of one size."""
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

    def speeds(self, known: Mapping[str, Any]) -> Speeds:
        """Angular velocity of every link, given the speeds of some links.

        See :func:`symkin.kinematics.solve_speeds`.
        """
        from symkin.kinematics import solve_speeds

        return solve_speeds(self, known)

    def ratio(self, driver: str, driven: str, fixed: str | Sequence[str] | None = None) -> Law:
        """The ratio i_ab^(c) = omega_a / omega_b with link(s) c fixed.

        See :func:`symkin.kinematics.ratio`.
        """
        from symkin.kinematics import ratio

        return ratio(self, driver, driven, fixed)

    def motion(self, inputs: Mapping[str, Any], frame: Any = None) -> Motion:
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
