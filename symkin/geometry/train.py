"""The geometry of every spur gear and mesh of a train, the problems found, and the shifts a coaxial set needs.

A train file gives each gear's tooth form (``{ teeth = 20, shift = 0.25 }``, see
:class:`~symkin.geometry.ToothForm`) and each mesh its working centre distance where the
pitch circles do not give it.  :func:`train_geometry` puts them together:

- a mesh with a working centre distance (``centre_distance``, or pitch radii given in the
  file) works at it, ``cos(alpha_w) = a cos(alpha) / a_w`` exactly, and its gears' shifts
  must give it (the involute equation): when they do not (within :data:`SHIFT_TOLERANCE`),
  the problem names the shift sum the distance needs;
- a mesh without one works where its shifts put it: a shift sum other than 0 moves the gears
  apart, and the problem asks for that ``centre_distance`` in the file (the kinematics and
  the drawings place the gears where the file says).

:func:`coaxial_shifts` chooses shifts that give every mesh the centre distance the train
puts it at (every planet mesh of a coaxial set shares its planet's arm): each mesh fixes
the sum ``x1 + x2`` (internal: ``x2 - x1``), which leaves one free shift per connected set
of gears; it is chosen to make the largest shift of the set least while every external gear
stays free of undercut (``x >= x_min``) and every mesh of the set free of the interferences
the report checks (involute; internal meshes also tip and trimming): the smallest shifts that
build the set.  Moving the free shift keeps every mesh's working pressure angle and moves the
tip circles only: a ring and its planet move together (``x2 - x1`` fixed), and a larger ring
shift shortens the ring's teeth, which clears its involute interference while the planet's
partners (a sun of ``x_s = S - x_p``) lose shift.  Where no shift within -1 and 1 clears the
interference without undercut, the choice is the least largest shift without undercut, and
:attr:`CoaxialShifts.notes` (and the report) says in one line what no shift clears and what to
change.  Bevel gears are left out (spur geometry only).

    >>> from symkin.trains import load_train
    >>> geo = train_geometry(load_train("simple"))
    >>> [round(float(m.pair.contact_ratio), 3) for m in geo.meshes]
    [1.602, 1.931]
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from symkin.errors import InputError
from symkin.geometry.gear import GearGeometry, ToothForm, gear_geometry
from symkin.geometry.mesh import DIGITS, MIN_CONTACT_RATIO, PairGeometry, interferences, pair_geometry, shift_sum_for
from symkin.geometry.outline import mesh_phases

__all__ = ["TrainGeometry", "MeshReport", "train_geometry", "coaxial_shifts", "CoaxialShifts", "SHIFT_TOLERANCE",
           "SHIFT_LIMIT", "SCAN_STEP"]

#: Shifts whose sum is this close to the one a centre distance needs give that distance.
SHIFT_TOLERANCE = sp.Rational(1, 10**4)
#: The shifts the scan for interference looks at: every shift of the set within -SHIFT_LIMIT and SHIFT_LIMIT.
SHIFT_LIMIT = 1
#: The step of that scan (in the free shift); a clear stretch is then bisected to its end.
SCAN_STEP = 0.005


@dataclass(frozen=True)
class MeshReport:
    """One mesh: its gears by name (the internal one second), its geometry and its problems."""

    gears: tuple[str, str]
    pair: PairGeometry
    problems: tuple[str, ...]


@dataclass(frozen=True)
class TrainGeometry:
    """Every spur gear and mesh of a train (lengths in mm), with what keeps it from being made or run."""

    gears: dict[str, GearGeometry]
    meshes: tuple[MeshReport, ...]
    #: Where each gear's axis is at t = 0 (mm) and the turn (rad) that meshes its teeth with its partners'.
    placement: dict[str, tuple[float, float, float]]
    notes: tuple[str, ...] = ()
    gear_problems: dict[str, tuple[str, ...]] = field(default_factory=dict)

    @property
    def problems(self) -> list[str]:
        """Every problem, each naming its gear or mesh."""
        out = [f"gear {g}: {p}" for g, ps in self.gear_problems.items() for p in ps]
        out += [f"mesh {m.gears[0]}-{m.gears[1]}: {p}" for m in self.meshes for p in m.problems]
        return out


def _forms(train: Any) -> dict[str, dict[str, Any]]:
    return {g: dict(keys) for g, keys in getattr(train, "tooth_forms", ())}


def _spur_gears(train: Any, shifts: Mapping[str, Any] | None) -> tuple[dict[str, GearGeometry], list[str]]:
    forms = _forms(train)
    gears: dict[str, GearGeometry] = {}
    notes = []
    for link in train.links:
        for gear in link.gears:
            if gear.bevel or link.axis == "radial":
                notes.append(f"gear {gear.name} is a bevel gear; its geometry is not covered (spur gears only)")
                continue
            if gear.teeth is None or not gear.teeth.is_Integer:
                raise InputError(f"gear {gear.name} has no tooth number ({gear.teeth}); give it one in the train file")
            if gear.module is None or not gear.module.is_number:
                raise InputError(f"gear {gear.name} has no module in mm; give the train a module (module = 2)")
            keys = dict(forms.get(gear.name, {}))
            tip = keys.pop("tip_diameter", None)
            if shifts is not None and gear.name in shifts:
                keys["shift"] = shifts[gear.name]
            gears[gear.name] = gear_geometry(gear.teeth, gear.module, ToothForm(**keys), internal=gear.internal,
                                             tip_diameter=tip)
    return gears, notes


def _gear_problems(g: GearGeometry) -> tuple[str, ...]:
    out = []
    if g.undercut:
        out.append(f"undercut: shift {float(g.shift):.4f} is below {float(g.minimum_shift or 0):.4f}, the least that cuts none")
    if g.pointed:
        out.append("pointed tip: the flanks meet below the tip circle (lower the shift or turn the tip down)")
    elif g.thin_tip:
        out.append(f"thin tip: {float(g.tip_thickness or 0):.3f} mm, below 0.2 m")
    if g.tip_inside_base:
        out.append("the tip circle lies inside the base circle: no involute at the tip (raise the shift)")
    return tuple(out)


def _ordered(train: Any, a: str, b: str) -> tuple[str, str]:
    return (b, a) if train.gear(a).internal else (a, b)


def train_geometry(train: Any, *, shifts: Mapping[str, Any] | None = None,
                   min_contact_ratio: Any = MIN_CONTACT_RATIO) -> TrainGeometry:
    """The geometry of ``train``'s spur gears and meshes (see the module docstring).

    ``shifts`` (gear name -> x) replaces the file's shifts (e.g. :func:`coaxial_shifts`'s choice, whose notes
    join the report's).
    """
    gears, notes = _spur_gears(train, shifts)
    meshes = []
    for mesh in train.meshes:
        if mesh.a not in gears or mesh.b not in gears:
            continue
        a, b = _ordered(train, mesh.a, mesh.b)
        g1, g2 = gears[a], gears[b]
        placed = sp.nsimplify(train.mesh_geometry(mesh).centre_distance)
        problems = []
        x_sum = (g2.shift - g1.shift) if g2.internal else (g1.shift + g2.shift)
        try:
            reference = pair_geometry(g1, g2)
            if placed != reference.reference_centre_distance:
                pair = pair_geometry(g1, g2, placed)
                needed = shift_sum_for(g1, g2, placed)
                if abs(sp.N(needed - x_sum, DIGITS)) > SHIFT_TOLERANCE:
                    which = f"x_{b} - x_{a}" if g2.internal else f"x_{a} + x_{b}"
                    problems.append(f"the centre distance {placed} mm needs {which} = {float(needed):.4f}, the shifts give "
                                    f"{float(x_sum):.4f} (symkin geometry --choose-shifts picks them)")
            else:
                pair = reference
                if x_sum != 0:
                    problems.append(f"the shifts move the gears to {float(pair.centre_distance):.4f} mm apart; add "
                                    f"centre_distance = {float(pair.centre_distance):.4f} to this mesh in the train file")
        except InputError as err:
            raise InputError(f"mesh {a}-{b}: {err}") from None
        problems += pair.problems(min_contact_ratio)
        meshes.append(MeshReport((a, b), pair, tuple(problems)))
    geo_problems = {name: p for name, g in gears.items() if (p := _gear_problems(g))}
    notes += getattr(shifts, "notes", ())  # what coaxial_shifts could not clear
    return TrainGeometry(gears, tuple(meshes), _placement(train, gears, meshes), tuple(notes), geo_problems)


def _placement(train: Any, gears: Mapping[str, GearGeometry], meshes: list[MeshReport]) -> dict[str, tuple[float, float, float]]:
    """Axis positions at t = 0 and turns that put a tooth of one gear of each mesh in a space of the other."""
    owner = {g.name: link.name for link in train.links for g in link.gears}
    centre: dict[str, tuple[float, float]] = {}
    for name in gears:
        x, y = train.axis_position(owner[name])
        centre[name] = (float(x), float(y))
    phase = mesh_phases({n: (int(g.teeth), g.internal, centre[n]) for n, g in gears.items()}, [m.gears for m in meshes])
    return {name: (centre[name][0], centre[name][1], phase[name]) for name in gears}


class CoaxialShifts(dict):
    """:func:`coaxial_shifts`'s choice, gear name -> shift (a dict), with ``notes``: one line for each set of
    gears whose interference no shift along the coaxial condition clears (what the designer can change)."""

    notes: tuple[str, ...] = ()


def coaxial_shifts(train: Any, *, digits: int = 5) -> CoaxialShifts:
    """Shift coefficients that give every spur mesh of ``train`` the centre distance the train places it at.

    Each mesh fixes a sum (external) or a difference (internal); one shift per connected set of
    gears is free, chosen to make the largest shift least with no external gear undercut and no mesh of the set
    with involute, tip (trochoid) or trimming interference (see the module docstring).  Where no shift clears the
    interference, the choice is the least largest shift without undercut, and ``notes`` says so.  The shifts
    are rounded to ``digits`` decimals (exact Rationals); gears in no spur mesh are not in the result.
    """
    gears, _ = _spur_gears(train, None)
    meshes = _spur_meshes(train, gears)
    rules = _shift_rules(gears, meshes)
    affine: dict[str, tuple[sp.Expr, int]] = {}  # x = c + k t
    chosen = CoaxialShifts()
    notes = []
    for start in gears:
        if start in affine or not any(start in r[:2] for r in rules):
            continue
        component, fixed = _spread(start, rules, affine)
        if fixed and max(fixed) - min(fixed) > SHIFT_TOLERANCE:
            raise InputError(f"the meshes around gear {start} ask for two different shifts: their centre distances "
                             "cannot all be met by profile shift; change a centre distance or a tooth number")
        lines = {g: (float(sp.N(affine[g][0], DIGITS)), affine[g][1]) for g in component}
        if fixed:
            t = fixed[0]
        else:
            scan = _InterferenceScan(gears, lines, [m for m in meshes if m[0] in lines])
            t = _least_shifts(scan.limits, margin=10.0**-digits)
            t, note = scan.clear(t, margin=10.0**-digits)
            notes += [note] if note else []
        for g, (c, k) in lines.items():
            chosen[g] = sp.Rational(f"{c + k * t:.{digits}f}")
    chosen.notes = tuple(notes)
    return chosen


def _spur_meshes(train: Any, gears: Mapping[str, GearGeometry]) -> list[tuple[str, str, sp.Expr]]:
    """Each spur mesh as ``(a, b, centre distance)``, the internal gear second, at the distance the train places it."""
    out = []
    for mesh in train.meshes:
        if mesh.a in gears and mesh.b in gears:
            a, b = _ordered(train, mesh.a, mesh.b)
            out.append((a, b, sp.nsimplify(train.mesh_geometry(mesh).centre_distance)))
    return out


def _shift_rules(gears: Mapping[str, GearGeometry], meshes: list[tuple[str, str, sp.Expr]]) -> list[tuple[str, str, int, sp.Expr]]:
    """For each spur mesh a-b (the internal gear second), ``(a, b, sign, value)``: ``x_b = sign * x_a + value``
    gives the mesh the centre distance the train places it at."""
    rules = []
    for a, b, placed in meshes:
        needed = shift_sum_for(gears[a], gears[b], placed)
        rules.append((a, b, 1, needed) if gears[b].internal else (a, b, -1, needed))
    return rules


def _spread(start: str, rules: list[tuple[str, str, int, sp.Expr]],
            affine: dict[str, tuple[sp.Expr, int]]) -> tuple[list[str], list[float]]:
    """The gears the ``rules`` join to ``start``, each one's shift put in ``affine`` as ``x = c + k t`` (``x_start =
    t``), and the values of t that loops of meshes fix."""
    component = [start]
    affine[start] = (sp.Integer(0), 1)
    fixed: list[float] = []  # t where a loop of meshes fixes it
    queue = [start]
    while queue:
        here = queue.pop()
        for a, b, sign, value in rules:
            if here not in (a, b):
                continue
            if here == a:
                there, c, k = b, sign * affine[a][0] + value, sign * affine[a][1]
            else:  # x_a = sign * (x_b - value)
                there, c, k = a, sign * (affine[b][0] - value), sign * affine[b][1]
            if there in affine:
                gap = float(sp.N(affine[there][0] - c, DIGITS))
                if affine[there][1] != k:
                    fixed.append(gap / (k - affine[there][1]))
                elif abs(gap) > SHIFT_TOLERANCE:
                    raise InputError(f"the meshes of gear {there} ask for two different shifts: its centre distances "
                                     "cannot all be met by profile shift; change a centre distance or a tooth number")
                continue
            affine[there] = (c, k)
            component.append(there)
            queue.append(there)
    return component, fixed


def _least_shifts(lines: list[tuple[float, int, float | None]], margin: float = 0.0) -> float:
    """The free shift t of x = c + k t (k = +-1) that makes the largest |x| least with every
    external gear free of undercut (x >= x_min); when no t keeps them all free, the middle
    of the two limits.  ``margin`` keeps t that far inside its limits (for the rounding of the shifts)."""
    low = max((xm - c for c, k, xm in lines if xm is not None and k == 1), default=-math.inf)
    high = min((c - xm for c, k, xm in lines if xm is not None and k == -1), default=math.inf)
    if high - low > 2 * margin:
        low, high = low + margin, high - margin
    if low > high:
        return (low + high) / 2
    candidates = {-c * k for c, k, _ in lines}
    candidates |= {-(c1 + c2) / (k1 + k2) for c1, k1, _ in lines for c2, k2, _ in lines if k1 + k2}
    candidates |= {(c2 - c1) / 2 * k1 for c1, k1, _ in lines for c2, k2, _ in lines if k1 == -k2}
    feasible = [min(max(t, low), high) for t in candidates]
    return min(feasible, key=lambda t: (max(abs(c + k * t) for c, k, _ in lines), abs(t)))


_NAMES = {"involute": "involute interference", "involute 1": "involute interference",
          "involute 2": "involute interference", "tip": "tip (trochoid) interference",
          "trimming": "trimming interference"}


class _InterferenceScan:
    """The interferences of a set's meshes as its free shift t moves (every shift ``x = c + k t``): each mesh
    keeps its working pressure angle and centre distance (the coaxial condition fixes ``x1 + x2``, internal
    ``x2 - x1``), only the tip circles move with the shifts.  Floats: the report checks the choice again exactly."""

    def __init__(self, gears: Mapping[str, GearGeometry], lines: Mapping[str, tuple[float, int]],
                 meshes: list[tuple[str, str, sp.Expr]]) -> None:
        self.lines = lines
        #: (c, k, x_min) of each gear (x_min None for an internal gear), as :func:`_least_shifts` takes them
        self.minimum = {g: None if gears[g].internal else float(gears[g].minimum_shift or 0) for g in lines}
        self.limits = [(c, k, self.minimum[g]) for g, (c, k) in lines.items()]
        self.tips = {g: _tip_radius_line(gears[g]) for g in lines}
        self.meshes = []
        for a, b, placed in meshes:
            g1, g2 = gears[a], gears[b]
            pair = pair_geometry(g1, g2, placed)
            self.meshes.append((f"{a}-{b}", a, b, (float(g1.teeth), float(g2.teeth), g2.internal, float(g1.base_diameter) / 2,
                                                   float(g2.base_diameter) / 2), float(placed), float(pair.working_pressure_angle)))

    def found(self, t: float) -> dict[str, tuple[str, ...]]:
        """Mesh name -> the interferences it has at t (every mesh with any)."""
        out = {}
        for name, a, b, (z1, z2, internal, rb1, rb2), placed, aw in self.meshes:
            ra1, ra2 = (r0 + slope * (self.lines[g][0] + self.lines[g][1] * t) for g, (r0, slope) in
                        ((a, self.tips[a]), (b, self.tips[b])))
            try:
                kinds = interferences(z1, z2, internal, rb1, rb2, ra1, ra2, placed, aw)
            except (ValueError, ZeroDivisionError):  # a tip circle inside the base circle: no involute there
                kinds = ("involute",)
            if kinds:
                out[name] = kinds
        return out

    def clear(self, t0: float, margin: float) -> tuple[float, str | None]:
        """The free shift nearest ``t0`` (the least largest shift without undercut) that clears every interference
        with no external gear undercut, and None; or ``t0`` and the line that says what no shift clears."""
        at_t0 = self.found(t0)
        if not at_t0:
            return t0, None
        limits = self.limits
        low = max((xm - c for c, k, xm in limits if xm is not None and k == 1), default=-math.inf) + margin
        high = min((c - xm for c, k, xm in limits if xm is not None and k == -1), default=math.inf) - margin
        lo = max(min((-SHIFT_LIMIT - c) * k, (SHIFT_LIMIT - c) * k) for c, k, _ in limits)
        hi = min(max((-SHIFT_LIMIT - c) * k, (SHIFT_LIMIT - c) * k) for c, k, _ in limits)
        grid = [lo + i * SCAN_STEP for i in range(int((hi - lo) / SCAN_STEP) + 1)] if hi > lo else []
        at = {t: self.found(t) for t in grid}
        clear = [t for t in grid if not at[t]]
        # a clear stretch narrower than a step: at an undercut limit, or where the interferences change
        # between two neighbouring points (each is one stretch of t: they change at its ends)
        clear += [t for t in (low, high) if lo <= t <= hi and not self.found(t)]
        for a, b in itertools.pairwise(grid):
            if at[a] and at[b] and at[a] != at[b]:
                clear += self._clear_between(a, at[a], b, at[b])
        best = []
        for side in (-1, 1):
            ok = [t for t in clear if low <= t <= high and (t - t0) * side > 0]
            if ok:
                best.append(self._edge(t0, min(ok, key=lambda t: abs(t - t0)), side, margin))
        if best:
            largest = lambda t: max(abs(c + k * t) for c, k, _ in limits)  # noqa: E731
            return min(best, key=largest), None
        meshes = ", ".join(f"mesh {m} ({', '.join(dict.fromkeys(_NAMES[k] for k in kinds))})" for m, kinds in at_t0.items())
        elsewhere = [t for t in grid if not set(at[t]) & set(at_t0)]
        if elsewhere:  # what the nearest shift that clears these meshes runs into
            t = min(elsewhere, key=lambda t: abs(t - t0))
            undercut = [g for g, (c, k) in self.lines.items() if (xm := self.minimum[g]) is not None and c + k * t < xm]
            others = list(self.found(t))
            why = " or ".join(w for w, on in ((f"undercutting gear{'s' * (len(undercut) > 1)} {', '.join(undercut)}", undercut),
                                                (f"interference at mesh{'es' * (len(others) > 1)} {', '.join(others)}", others)) if on)
            why = f"without {why}"
        else:
            why = f"with every shift within -{SHIFT_LIMIT} and {SHIFT_LIMIT}"
        return t0, (f"{meshes}: no profile shift along the coaxial condition clears it {why}; change the tooth numbers, "
                    "take a larger pressure angle or a shorter addendum of the ring (tip_diameter in the train file)")

    def _clear_between(self, a: float, at_a: dict, b: float, at_b: dict) -> list[float]:
        """A point between ``a`` and ``b`` with no interference, if the stretch between holds one
        wider than a millionth (halving where the interferences differ at the two ends)."""
        if at_a == at_b or b - a < 1e-6:
            return []
        mid = (a + b) / 2
        at_mid = self.found(mid)
        if not at_mid:
            return [mid]
        return self._clear_between(a, at_a, mid, at_mid) or self._clear_between(mid, at_mid, b, at_b)

    def _edge(self, t0: float, t: float, side: int, margin: float) -> float:
        """The end of the clear stretch around grid point ``t`` nearest ``t0`` (bisected), ``margin`` inside it."""
        bad = max(t - SCAN_STEP, t0) if side == 1 else min(t + SCAN_STEP, t0)
        good = t
        for _ in range(40):
            mid = (bad + good) / 2
            bad, good = (bad, mid) if not self.found(mid) else (mid, good)
        inside = good + side * margin
        return inside if not self.found(inside) else t


def _tip_radius_line(g: GearGeometry) -> tuple[float, float]:
    """``(r_a at x = 0, dr_a/dx)``: the tip radius is affine in the shift (0 where the tip diameter is given)."""
    r0, r1 = (float(GearGeometry(g.teeth, g.module, replace(g.form, shift=x), internal=g.internal, tip=g.tip).tip_diameter) / 2
              for x in (0, 1))
    return r0, r1 - r0
