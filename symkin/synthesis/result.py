"""What a synthesis returns: designs (each re-checked by building its train), and the search's account.

A :class:`Design` knows its tooth numbers, exact ratio and error, its size and working
centre distances; :meth:`Design.train` builds the train with those numbers (a
:class:`~symkin.trains.Train` like any other: ratios, speeds, figures), and
:meth:`Design.check` re-derives the ratio from that train with the kinematics, asks the
model for its coaxiality and planet positions, and measures the gap between every pair
of planet copies that could touch: a route independent of the compiled search.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin._util.display import html_table, short_repr
from symkin._util.jsonout import exact_json, float_text
from symkin.errors import CoaxialityWarning, ModelError, SymkinError
from symkin.model import Gear, LinkKind, Mechanism
from symkin.numeric.backends.exact import exact_value
from symkin.synthesis.conditions import Condition
from symkin.synthesis.efficiency import DEFAULT_RANK
from symkin.synthesis.funnel import Record
from symkin.synthesis.plan import STAGES, SearchPlan
from symkin.synthesis.problem import Problem
from symkin.synthesis.request import Target
from symkin.synthesis.search import ChunkResult

__all__ = ["Design", "DesignCheck", "SynthesisResult"]


def _rational(value: Fraction | int) -> sp.Rational:
    value = Fraction(value)
    return sp.Rational(value.numerator, value.denominator)


@dataclass(frozen=True)
class DesignCheck:
    """A design re-checked from its own train (see the module docstring).

    Attributes
    ----------
    ratio : sympy.Rational or None
        The ratio the kinematics derives for the train with these teeth.
    ratio_ok, coaxial, placed, assembles : bool
        The ratio equals the design's; no planet axis is put at two distances; every
        planet could be placed (meshing planets form a triangle); the copies of every
        planet kind were placed tooth by tooth (:func:`assembles_tooth_by_tooth`).
    gap : float or None
        The least gap between tip circles of planet copies that could touch, in modules
        (positive: clear), after the tip clearance asked for; None with one planet.
    passed : bool
    efficiency : sympy.Rational or None
        The efficiency from the statics of the design's own train, when the search ranked by
        efficiency; ``efficiency_ok`` says whether it equals the ranked one.
    """

    ratio: sp.Rational | None
    ratio_ok: bool
    coaxial: bool
    placed: bool
    gap: float | None
    passed: bool
    problem: str = ""
    assembles: bool = True
    efficiency: sp.Rational | None = None
    efficiency_ok: bool = True

    def to_json(self) -> dict[str, Any]:
        """The independent check as JSON: the ratio and whether it is in the window, coaxiality, placement, assembly, the least gap in modules, the efficiency when ranked by it, and the verdict."""
        out = {"ratio": exact_json(self.ratio), "ratio_ok": self.ratio_ok, "coaxial": self.coaxial, "placed": self.placed,
               "assembles": self.assembles,
               "gap_modules": None if self.gap is None else round(self.gap, 9), "passed": self.passed,
               "problem": self.problem}
        if self.efficiency is not None:
            out |= {"efficiency": exact_json(self.efficiency), "efficiency_ok": self.efficiency_ok}
        return out


@dataclass(frozen=True)
class Design:
    """One design: tooth numbers, exact ratio and error, size and working centre distances.

    Attributes
    ----------
    teeth : tuple of (str, int)
        Each unknown and its tooth number.
    gear_teeth : tuple of (str, int)
        Each gear and its tooth number (the unknowns and the numbers the train gave).
    ratio, error : sympy.Rational
        The exact ratio and its relative error from the target (0 inside a range).
    size : sympy.Rational
        Envelope diameter (length units of the module): the largest of the external
        central gears' tip circles, the internal gears' pitch circles and the planets'
        tip circles about the main axis.
    arms : tuple of (str, sympy.Rational)
        Each planet's working arm (distance of its axis from the main axis).
    shifts : tuple of (str, sympy.Rational)
        Meshes worked at a centre distance other than their pitch circles give, with
        y = (a_w - a) / m.
    planets : tuple of (str, int)
        Copies of each planet kind.
    ranked_efficiency : sympy.Rational or None
        The exact efficiency the search ranked the design by, from the train's efficiency
        law (:mod:`symkin.synthesis.efficiency`); :meth:`check` derives it again from the
        statics of the design's own train. None unless the search ranked by efficiency, or
        where the design has none (a degenerate train: a mesh's relative power has a pole).
    mesh_efficiency : tuple of (str, sympy.Rational)
        Each mesh's efficiency that efficiency was worked with (``"a-b"``, value); empty
        unless the search ranked by efficiency (:attr:`ranked_by_efficiency`).
    """

    problem: Problem
    teeth: tuple[tuple[str, int], ...]
    gear_teeth: tuple[tuple[str, int], ...]
    ratio: sp.Rational
    error: sp.Rational
    size: sp.Rational
    arms: tuple[tuple[str, sp.Rational], ...]
    shifts: tuple[tuple[str, sp.Rational], ...]
    planets: tuple[tuple[str, int], ...]
    ranked_efficiency: sp.Rational | None = None
    mesh_efficiency: tuple[tuple[str, sp.Expr], ...] = ()

    def __repr__(self) -> str:
        """``Design(z1=30, z2=18, ratio 12/5, error 0, size 78)``, under 200 characters."""
        return short_repr("Design", *(f"{n}={z}" for n, z in self.teeth), f"ratio {self.ratio}", f"error {self.error}",
                          f"size {self.size}")

    def _repr_html_(self) -> str:
        """The design as a compact HTML table (each gear's teeth, the ratio, its error, the size), for Jupyter."""
        rows: list[tuple[str, Any]] = [(g, z) for g, z in self.gear_teeth]
        rows += [("ratio", self.ratio), ("error", float_text(self.error)), ("size", self.size)]
        rows += [(f"arm {n}", a) for n, a in self.arms] + [(f"shift {n}", y) for n, y in self.shifts]
        return html_table(["", "value"], rows, caption="design")

    @classmethod
    def from_record(cls, plan: SearchPlan, record: Record) -> Design:
        """A design from a search record: every gear's tooth number, the exact ratio and its error, the size, the planets' arms and the profile shifts."""
        problem = plan.problem
        values = {z: int(v) for z, v in zip(problem.unknowns, record.teeth)}
        gear_teeth = [(g.name, int(_at(g.teeth, values))) for L in problem.train.links for g in L.gears]
        y = problem.options.shift
        arms, shifts = [], []
        for arm in problem.arms:
            refs = [_at(m.reference, values) for m in arm.meshes]
            if arm.fixed is not None:
                a_w = sp.Rational(arm.fixed)
            elif y:
                lo = max(r - y * m.module for r, m in zip(refs, arm.meshes))
                hi = min(r + y * m.module for r, m in zip(refs, arm.meshes))
                a_w = (lo + hi) / 2
            else:
                a_w = refs[0]
            arms.append((arm.planet, a_w))
            for r, m in zip(refs, arm.meshes):
                if r != a_w:
                    shifts.append((f"{m.mesh.a}-{m.mesh.b}", (a_w - r) / m.module))
        eta = None if record.efficiency is None else _rational(record.efficiency)
        mesh = plan.efficiency.meshes if plan.efficiency is not None else ()
        return cls(problem, tuple((str(z), v) for z, v in values.items()), tuple(gear_teeth), _rational(record.ratio),
                   _rational(record.error), sp.Rational(record.size, plan.scale), tuple(arms), tuple(shifts),
                   tuple(problem.counts), eta, mesh)

    @property
    def ranked_by_efficiency(self) -> bool:
        """Whether the search that found the design ranked by efficiency (then :attr:`mesh_efficiency` holds the meshes' values)."""
        return bool(self.mesh_efficiency)

    @property
    def locks(self) -> bool:
        """Whether the ranked efficiency is zero or below: the driver cannot drive the driven (the train locks)."""
        return locks(self.ranked_efficiency)

    @property
    def values(self) -> dict[str, int]:
        """The unknowns' tooth numbers, by name."""
        return dict(self.teeth)

    def train(self) -> Mechanism:
        """The train with these tooth numbers, the planets' counts and the working centre distances.

        >>> from symkin.synthesis import synthesize
        >>> best = synthesize("simple", driver="S", driven="C", fixed="R", ratio=4, zmax=80).designs[0]
        >>> best.train().ratio("S", "C", fixed="R").rhs, best.gear_teeth
        (4, (('s', 18), ('p', 18), ('r', 54)))
        """
        problem = self.problem
        teeth = dict(self.gear_teeth)
        arm_of = dict(self.arms)
        working: dict[frozenset[str], sp.Rational] = {}
        for arm in problem.arms:
            for m in arm.meshes:
                ref = sp.Rational(m.reference.subs({z: v for z, v in zip(problem.unknowns, (v for _, v in self.teeth))}))
                if m.working is not None or ref != arm_of[arm.planet]:
                    working[frozenset((m.mesh.a, m.mesh.b))] = arm_of[arm.planet]
        links = []
        count = dict(self.planets)
        for L in problem.train.links:
            gears = tuple(Gear.from_teeth(g.name, teeth[g.name], internal=g.internal, module=g.module) for g in L.gears)
            changes: dict[str, Any] = {"gears": gears}
            if L.kind is LinkKind.PLANET:
                changes["count"] = count[L.name]
            links.append(dataclasses.replace(L, **changes))
        meshes = tuple(dataclasses.replace(m, centre_distance=working.get(frozenset((m.a, m.b)), m.centre_distance))
                       for m in problem.train.meshes)
        return dataclasses.replace(problem.train, links=tuple(links), meshes=meshes)

    def efficiency(self, mesh_efficiency: Any = "default") -> sp.Expr:
        """The efficiency of the searched ratio's power path, exact, from the statics of :meth:`train`.

        ``mesh_efficiency`` is :func:`symkin.statics.statics`' ``efficiency``: ``"default"``
        (the train file's value where a mesh has one, else 0.98 an external mesh and 0.99 an
        internal one), one number for every mesh, or ``{"a-b": value}``.  Driver driving
        driven with the searched links held (or the state's brakes and clutches). A train
        whose statics has no efficiency (a degenerate one) raises a
        :class:`~symkin.errors.SymkinError`.

        >>> from symkin.synthesis import synthesize
        >>> best = synthesize("simple", driver="S", driven="C", fixed="R", ratio=4, zmax=80).designs[0]
        >>> best.efficiency(), best.efficiency(0.97)
        (19553/20000, 38227/40000)
        """
        from symkin.statics import statics
        from symkin.synthesis.efficiency import power_path

        train = self.train()
        driver, driven, held, joined = power_path(self.problem, train)
        eta = statics(train, input=driver, output=driven, fixed=held, joined=joined, efficiency=mesh_efficiency)
        return eta.efficiency.rhs

    def check(self) -> DesignCheck:
        """Re-derive the ratio, coaxiality and planet positions from :meth:`train` (module docstring).

        >>> from symkin.synthesis import synthesize
        >>> synthesize("simple", driver="S", driven="C", fixed="R", ratio=4, zmax=80).designs[0].check().passed
        True
        """
        problem = self.problem
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                train = self.train()
        except ModelError as err:
            return DesignCheck(None, False, False, False, None, False, f"the train cannot be built: {err}")
        coaxial = not any(issubclass(w.category, CoaxialityWarning) for w in caught) and not train.coaxiality_defects()
        ratio = sp.Rational(problem.ratio_of(train).rhs)
        ratio_ok = ratio == self.ratio
        try:
            angles = train.position_angles
            placed = True
        except ModelError:
            return DesignCheck(ratio, ratio_ok, coaxial, False, None, False, "the planets cannot be placed")
        gap = _least_gap(problem, train, angles)
        count = problem.count
        assembles = all(assembles_tooth_by_tooth(train, g.planets, count[g.planets[0]]) for g in problem.assembly)
        eta, eta_ok = None, True
        if self.ranked_by_efficiency:
            try:
                eta = sp.sympify(self.efficiency(dict(self.mesh_efficiency)))
            except SymkinError:  # no efficiency for this train: the ranking must have found none either
                eta = None
            if eta is not None and not eta.is_Rational:
                eta = None
            eta_ok = eta == self.ranked_efficiency
        passed = ratio_ok and coaxial and placed and assembles and (gap is None or gap > 0) and eta_ok
        failed = [name for name, ok in (("ratio", ratio_ok), ("coaxiality", coaxial), ("assembly", assembles),
                                        ("clearance", gap is None or gap > 0), ("efficiency", eta_ok)) if not ok]
        return DesignCheck(ratio, ratio_ok, coaxial, placed, gap, passed, ", ".join(failed), assembles, eta, eta_ok)

    def to_json(self) -> dict[str, Any]:
        """The design as JSON: teeth by gear and by unknown, the exact ratio, error and size, the arms, the shifts and the planets."""
        return {
            "teeth": dict(self.gear_teeth),
            "unknowns": dict(self.teeth),
            "ratio": exact_json(self.ratio),
            "error": exact_json(self.error),
            "size": exact_json(self.size),
            "arms": {p: exact_json(a) for p, a in self.arms},
            "shifts": {m: exact_json(y) for m, y in self.shifts},
            "planets": dict(self.planets),
        } | ({"efficiency": exact_json(self.ranked_efficiency), "locks": self.locks} if self.ranked_by_efficiency
             else {})


def assembles_tooth_by_tooth(train: Mechanism, planets: Sequence[str], k: int) -> bool:
    """Can ``k`` equally spaced copies of these (meshing) planets be put in, tooth by tooth?

    An independent route to the assembly condition, from the tooth positions alone.  At a
    pitch point the tooth phase of a gear, ``z (phi - d)`` in pitches (phi the angle of one of
    its teeth, d the direction of the pitch point from its axis, in turns), and that of its
    mate add up (an external pair; an internal gear's subtracts) to half a pitch, whole
    pitches apart.  Copy j stands where copy 0 would after the carrier's turn by j/k, the
    gears on the main axis staying where they are: its pitch points are turned by j/k, and
    the copy may be turned by j/k plus some e_P.  So a mesh of copy j holds when, whole
    pitches apart, ``z_p e_P - z_g j/k`` (external central gear g), ``z_p e_P + z_g j/k``
    (internal g), or ``z_p e_P + z_q e_Q`` (two planets) is whole.  Each e_P is tried at
    every one of the ``z_p`` spins its first mesh allows, and the copy fits when some choice
    satisfies every mesh.

    >>> from symkin.trains import load_train
    >>> assembles_tooth_by_tooth(load_train("simple"), ["P"], 3), assembles_tooth_by_tooth(load_train("simple"), ["P"], 5)
    (True, False)
    """
    cluster = list(planets)
    inside = set(cluster)
    meshes = []
    for mesh in train.meshes:
        geo = train.mesh_geometry(mesh)
        la, lb = geo.link_a, geo.link_b
        if la.name not in inside and lb.name not in inside:
            continue
        meshes.append(geo)
    order: list[str] = []
    pending = list(cluster)
    while pending:  # planets meshing a central gear first, then planets meshing planets already placed
        for p in pending:
            touches = [g for g in meshes if p in (g.link_a.name, g.link_b.name)]
            if any((g.link_a.kind is not LinkKind.PLANET or g.link_b.kind is not LinkKind.PLANET) or
                   ({g.link_a.name, g.link_b.name} - {p}) <= set(order) for g in touches):
                order.append(p)
                pending.remove(p)
                break
        else:
            return False  # planets meshing no central gear: not handled here
    for j in range(1, k):
        turn = Fraction(j, k)
        if not _fits(meshes, order, {}, turn):
            return False
    return True


def _term(geo: Any, side: str, spins: dict[str, Fraction], turn: Fraction) -> Fraction | None:
    """How far one gear's tooth phase at the pitch point of copy j is from copy 0's, in pitches,
    signed as it enters the mesh (an internal gear's phase subtracts); None while unknown."""
    link = geo.link_a if side == "a" else geo.link_b
    gear = geo.gear_a if side == "a" else geo.gear_b
    z = int(gear.teeth)
    if link.kind is LinkKind.PLANET:
        if link.name not in spins:
            return None
        change = z * spins[link.name]  # turned with the copy (turn) and by its own e; its pitch point by turn
    else:
        change = -z * turn  # its pitch point turned by j/k, the gear did not
    return -change if gear.internal else change


def _mesh_value(geo: Any, spins: dict[str, Fraction], turn: Fraction) -> Fraction | None:
    a, b = _term(geo, "a", spins, turn), _term(geo, "b", spins, turn)
    return None if a is None or b is None else a + b


def _fits(meshes: list[Any], order: list[str], spins: dict[str, Fraction], turn: Fraction) -> bool:
    if len(spins) == len(order):
        values = [_mesh_value(g, spins, turn) for g in meshes]
        return all(v is not None and v.denominator == 1 for v in values)
    planet = order[len(spins)]
    anchor = None
    for g in meshes:
        if planet not in (g.link_a.name, g.link_b.name):
            continue
        other = g.link_b if g.link_a.name == planet else g.link_a
        if other.kind is not LinkKind.PLANET or other.name in spins:
            anchor = g
            break
    assert anchor is not None  # the order puts a planet after what it meshes
    side = "a" if anchor.link_a.name == planet else "b"
    gear = anchor.gear_a if side == "a" else anchor.gear_b
    z = int(gear.teeth)
    rest = _term(anchor, "b" if side == "a" else "a", spins, turn)
    assert rest is not None
    sign = -1 if gear.internal else 1
    for n in range(z):  # sign z e + rest = n: every spin of the copy that fits this mesh
        trial = {**spins, planet: Fraction(n - rest, z) * sign}
        partial = [_mesh_value(g, trial, turn) for g in meshes]
        if all(v is None or v.denominator == 1 for v in partial) and _fits(meshes, order, trial, turn):
            return True
    return False


def _least_gap(problem: Problem, train: Mechanism, angles: dict[str, sp.Expr]) -> float | None:
    """The least gap (modules) between tip circles of planet copies that could touch: copies of one kind
    (each gear against the same gear) and copies of two meshing kinds that are not the meshing pair."""
    o = problem.options
    count = problem.count
    gaps: list[float] = []

    def centre(planet: str, j: int) -> tuple[sp.Expr, sp.Expr]:
        a = train.arm(planet)
        phi = angles[planet] + 2 * sp.pi * j / count[planet]
        return a * sp.cos(phi), a * sp.sin(phi)

    def distance(p: tuple[sp.Expr, sp.Expr], q: tuple[sp.Expr, sp.Expr]) -> float:
        return float(sp.N(sp.sqrt((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2), 30))

    for L in train.links:
        if L.kind is not LinkKind.PLANET or count[L.name] < 2:
            continue
        k = count[L.name]
        for g in L.gears:
            tip = g.radius + o.addendum * sp.sympify(g.module)
            for j in range(1, k):
                d = distance(centre(L.name, 0), centre(L.name, j))
                gaps.append((d - float(2 * tip + o.clearance * sp.sympify(g.module))) / float(sp.sympify(g.module)))
    for pair in problem.pairs:
        k = count[pair.first]
        ga, gb = train.gear(pair.gears[0]), train.gear(pair.gears[1])
        ma, mb = sp.sympify(ga.module), sp.sympify(gb.module)
        reach = float(ga.radius + gb.radius + o.addendum * (ma + mb) + o.clearance * ma)
        for j in range(1, k):
            d = distance(centre(pair.first, 0), centre(pair.second, j))
            gaps.append((d - reach) / float(ma))
    return min(gaps) if gaps else None


@dataclass(frozen=True)
class SynthesisResult:
    """A synthesis: the designs (best first), the funnel of conditions, and how the search ran.

    A :class:`~symkin.synthesis.searches.SearchResult`: iterating it gives the designs.

    Attributes
    ----------
    problem : Problem
    target : Target
    designs : tuple of Design
        The best ``top`` designs by ratio error, then size, then tooth sum.
    found : int
        Designs meeting every condition.
    funnel : tuple of (str, int)
        Tuples made with the ratio in the window, then how many pass each further condition.
    reach : tuple of float
        The least and largest ratio met among coaxial tooth numbers within the limits.
    seconds : float
        Time of the search (the conditions' derivation and compiling included).
    search : str
        How the space was searched.
    execution : dict
        Where the chunks ran.
    notes : tuple of str
    reason : str
        Why there is no design, when there is none.
    made : int
        Tuples made in all.
    rank : tuple of str
        The ranking keys, in order (:func:`symkin.synthesis.efficiency.rank_order`).
    mesh_efficiency : tuple of (str, sympy.Rational)
        Each mesh's efficiency the ranking used, when it ranked by efficiency.
    """

    problem: Problem
    target: Target
    designs: tuple[Design, ...]
    found: int
    funnel: tuple[tuple[str, int], ...]
    reach: tuple[float, float]
    seconds: float
    search: str
    execution: dict[str, Any]
    notes: tuple[str, ...] = ()
    reason: str = ""
    made: int = 0
    rank: tuple[str, ...] = DEFAULT_RANK
    mesh_efficiency: tuple[tuple[str, sp.Expr], ...] = ()

    def __repr__(self) -> str:
        """``SynthesisResult(3 designs of 12 found, best ratio 12/5, 0.4 s)``, under 200 characters."""
        best = f"best ratio {self.designs[0].ratio}" if self.designs else "no design"
        return short_repr("SynthesisResult", f"{len(self.designs)} designs of {self.found} found", best,
                          f"{self.seconds:.3g} s")

    def __iter__(self) -> Iterator[Design]:
        return iter(self.designs)

    def message(self) -> str:
        """How many designs were found and which are listed, in what order; or why there are none.

        >>> from symkin.synthesis import synthesize
        >>> synthesize("simple", driver="S", driven="C", fixed="R", ratio=4, zmax=100, top=2).message()
        '6 designs; the best 2 by ratio error, then size (envelope diameter), then tooth sum'
        """
        if not self.found:
            return self.reason
        shown = len(self.designs)
        return f"{self.found} designs; {'all' if shown == self.found else f'the best {shown}'} by {self.order}"

    @property
    def order(self) -> str:
        """The ranking in words: "ratio error, then size (envelope diameter), then tooth sum"."""
        words = {"error": "ratio error", "efficiency": "efficiency (largest first)",
                 "size": "size (envelope diameter)", "teeth": "tooth sum"}
        return ", then ".join(words[k] for k in self.rank)

    @property
    def conditions(self) -> tuple[Condition, ...]:
        """The conditions of the problem the designs satisfy (ratio window, coaxiality, assembly, neighbours)."""
        return self.problem.conditions()

    def to_json(self) -> dict[str, Any]:
        """The result as JSON: the train, the ratio law, the target, the options, the conditions and the designs."""
        o = self.problem.options
        return {
            "train": self.problem.train.name,
            "ratio_law": {"lhs": str(self.problem.ratio.lhs), "rhs": str(self.problem.ratio.rhs)},
            "target": {"ratio": exact_json(self.target.ratio), "tolerance": exact_json(self.target.tolerance),
                       "lo": exact_json(self.target.lo), "hi": exact_json(self.target.hi)},
            "options": {"planets": self.problem.count, "zmin": o.zmin, "zmax": o.zmax,
                        "pressure_angle_deg": exact_json(o.pressure_angle), "addendum": exact_json(o.addendum),
                        "clearance_modules": exact_json(o.clearance), "shift_modules": exact_json(o.shift),
                        "ring_difference": o.ring_difference},
            "unknowns": [str(z) for z in self.problem.unknowns],
            "conditions": [c.to_json() for c in self.conditions],
            "search": self.search,
            "funnel": [{"stage": s, "count": n} for s, n in self.funnel],
            "tuples_made": self.made,
            "found": self.found,
            "reach": [v if math.isfinite(v) else None for v in self.reach],
            "seconds": round(self.seconds, 4),
            "execution": self.execution,
            "notes": list(self.notes),
            "rank": list(self.rank),
            **({"mesh_efficiencies": {m: exact_json(v) for m, v in self.mesh_efficiency}} if self.mesh_efficiency
               else {}),
            "designs": [d.to_json() for d in self.designs],
        }


def funnel_of(plan: SearchPlan, merged: ChunkResult) -> tuple[tuple[str, int], ...]:
    """The stages that apply to this plan, with the tuples passing each."""
    o = plan.problem.options
    k = sorted(set(plan.k.values())) or [1]
    ks = "/".join(map(str, k))
    names = {
        "ratio": f"coaxial, {o.zmin} <= z <= {o.zmax}, ratio in range",
        "internal gears": f"internal gears at least {o.ring_difference} teeth larger than their mates",
        "coaxiality": f"the meshes of every planet within {o.shift} m of one working distance",
        "assembly": f"{ks} planets of each kind can be assembled",
        "neighbours": "neighbouring planets clear each other" + (f" by {o.clearance} m" if o.clearance else ""),
        "placement": "meshing planets placed, clear of the copies they do not mesh",
    }
    applies = {
        "ratio": True,
        "internal gears": bool(plan.internal_pairs),
        "coaxiality": bool(plan.filter_bounds),
        "assembly": bool(plan.assembly),
        "neighbours": any(plan.k[plan.planets[r[0]]] >= 2 for r in plan.geometry.rims),
        "placement": bool(plan.geometry.pairs),
    }
    return tuple((names[s], n) for s, n in zip(STAGES, merged.counts) if applies[s])


def empty_reason(plan: SearchPlan, merged: ChunkResult) -> str:
    """Which condition removed the last candidates, and how to relax it."""
    o = plan.problem.options
    t = plan.target
    lo, hi = merged.reach
    law = f"{plan.problem.ratio.lhs} = {sp.sstr(plan.problem.ratio.rhs)}"
    counts = dict(zip(STAGES, merged.counts))
    limits = f"{o.zmin} <= z <= {o.zmax}"
    if counts["ratio"] == 0:
        if math.isfinite(lo) and math.isfinite(hi) and (float(t.hi) < lo * (1 - 1e-12) - 1e-12 or float(t.lo) > hi * (1 + 1e-12) + 1e-12):
            return (f"the ratio {t.text()} is outside what this train gives with {limits}: {law} ranges from "
                    f"{lo:.6g} to {hi:.6g} over coaxial tooth numbers; ask for a ratio in that range or widen the limits")
        where = f" (it gives {lo:.6g} to {hi:.6g} here)" if math.isfinite(lo) else ""
        return (f"no coaxial tooth numbers with {limits} give {t.text()}{where}; widen the tolerance or the tooth "
                "limits")
    k = "/".join(map(str, sorted(set(plan.k.values()))))
    n = counts["ratio"]
    head = f"{n} tuple{'s' * (n != 1)} of coaxial tooth numbers with {limits} give{'s' * (n == 1)} {t.text()}"
    previous, passed = n, ""
    for s in STAGES[1:]:
        if counts[s] == 0:
            why = {
                "internal gears": (f"in none is every internal gear at least {o.ring_difference} teeth larger than the "
                                   "gear meshing it; lower the ring difference or widen the limits"),
                "coaxiality": (f"in none do the meshes of every planet come within {o.shift} modules of one working "
                               "centre distance; allow more profile shift"),
                "assembly": (f"none can be assembled with {k} equally spaced planets (the assembly conditions); try "
                             "another number of planets, or widen the tolerance"),
                "neighbours": (f"in none do {k} planets fit side by side with their tip circles clear (neighbour "
                               "condition); use fewer planets or larger central gears"),
                "placement": ("in none can the meshing planets be placed clear of each other's copies; use fewer planets "
                              "or other limits"),
            }[s]
            return f"{head}{passed}, but {why}"
        if counts[s] != previous:
            passed = f"; {counts[s]} of them pass the {s} condition"
        previous = counts[s]
    return "no design"  # pragma: no cover - some stage is empty when nothing is found


def locks(eta: Any) -> bool:
    """Whether an efficiency (None where there is none) is zero or below: the driver cannot drive the driven."""
    return eta is not None and bool(eta <= 0)


def efficiency_text(eta: Any) -> str:
    """An efficiency for a table: five decimals, "(locks)" at zero or below, "-" where there is none."""
    if eta is None:
        return "-"
    return f"{float(eta):.5f}" + (" (locks)" if locks(eta) else "")


def describe_designs(designs: Sequence[Design]) -> list[str]:
    """A table of designs (best first)."""
    if not designs:
        return []
    problem = designs[0].problem
    names = [str(z) for z in problem.unknowns]
    ranked = any(d.ranked_by_efficiency for d in designs)
    header = ["#", *names, "ratio", "error %", "size", "shift"] + (["efficiency"] if ranked else [])
    rows = [header]
    for n, d in enumerate(designs, 1):
        values = d.values
        ratio = str(d.ratio) if len(str(d.ratio)) <= 12 else float_text(d.ratio)
        shift = ", ".join(f"{m} {float(y):+.3g}" for m, y in d.shifts) or "-"
        rows.append([str(n), *(str(values[z]) for z in names), ratio, f"{float(d.error) * 100:.4f}",
                     float_text(d.size), shift]
                    + ([efficiency_text(d.ranked_efficiency)] if ranked else []))
    widths = [max(len(r[i]) for r in rows) for i in range(len(header))]
    return ["  ".join(c.rjust(w) for c, w in zip(r, widths)).rstrip() for r in rows]


def _at(expr: Any, values: Mapping[sp.Symbol, int]) -> sp.Rational:
    """The exact value of ``expr`` (a tooth number or a centre distance, rational in the unknown
    tooth numbers) at ``values`` (:func:`~symkin.numeric.backends.exact.exact_value`: integer
    arithmetic compiled once per expression)."""
    expr = sp.sympify(expr)
    value = exact_value(expr, values)
    if value is None:
        return sp.Rational(expr.subs(values))
    return sp.Rational(value.numerator, value.denominator)
