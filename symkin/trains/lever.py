"""The lever analogy of a train (Benford and Leising, SAE 810102, 1981): positions by tooth numbers.

In the frame of a link that holds the axes of a set of meshes (a carrier, or the frame
for fixed axes), every gear turns at a speed relative to that link fixed by the tooth
ratios alone: across an external mesh ``-z_a/z_b``, across an internal one ``+z_a/z_b``
(pitch radii where no teeth are given).  So the speeds of the links of a planetary set
are a linear function of one coordinate, the position of each link's node on a lever:
``omega_L = omega_C + k x_L``, the carrier ``C`` at 0.  For a simple set the sun and
the ring sit on either side of the carrier at distances in the ratio ``z_R : z_S``;
for a double-pinion set both on one side.  Two levers that share two links (Simpson's
sun and its front carrier, a nested carrier and its sun) are one lever: their positions
are mapped onto each other by the affine map the two shared nodes fix.

A node is every link on the lever's axis and every link a state names (or that carries
planets); plain planets and bevel pinions join the nodes but are not drawn.  Positions
are whole numbers with no common factor, so that they read as tooth-number spacings.

    >>> from symkin.trains import load_train
    >>> [lever.positions for lever in levers(load_train("simple"))]   # sun 24, ring 72
    [{'R': -1, 'C': 0, 'S': 3}]
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from symkin.model import FRAME, LinkKind, Mechanism

__all__ = ["Lever", "levers"]


@dataclass(frozen=True)
class Lever:
    """One lever: each node's position (a whole number), sorted from the lowest.

    ``carriers`` are the links whose frames the lever was built in (position 0 in one of
    them before the levers were joined).
    """

    positions: dict[str, int]
    carriers: tuple[str, ...] = field(default=())

    def speed_line(self, speeds: Mapping[str, Any]) -> tuple[sp.Expr, sp.Expr] | None:
        """``(a, b)`` with ``speed = a + b x`` through the nodes whose speeds are given, or None
        when fewer than two distinct positions have one."""
        known = [(sp.Integer(x), sp.sympify(speeds[n])) for n, x in self.positions.items() if n in speeds]
        distinct = {x: w for x, w in known}
        if len(distinct) < 2:
            return None
        (x0, w0), (x1, w1) = sorted(distinct.items())[0], sorted(distinct.items())[-1]
        b = sp.cancel((w1 - w0) / (x1 - x0))
        return sp.cancel(w0 - b * x0), b


def _relative_speeds(mech: Mechanism, meshes: list[Any]) -> dict[str, sp.Expr]:
    """Each link's speed relative to the meshes' holder, up to a common factor (tooth ratios)."""
    edges: dict[str, list[tuple[str, sp.Expr]]] = {}
    for geo in meshes:
        la, lb, ga, gb = geo.link_a.name, geo.link_b.name, geo.gear_a, geo.gear_b
        if geo.kind == "bevel":  # pinion spin -> side gear: side * r_pinion / r_side
            pin, side = (ga, gb) if geo.link_a.axis == "radial" else (gb, ga)
            lp, ls = (la, lb) if geo.link_a.axis == "radial" else (lb, la)
            f = side.side * pin.radius / side.radius
            edges.setdefault(lp, []).append((ls, f))
            edges.setdefault(ls, []).append((lp, 1 / f))
            continue
        ratio = _ratio(ga, gb)
        sign = 1 if (ga.internal or gb.internal) else -1
        edges.setdefault(la, []).append((lb, sign * ratio))
        edges.setdefault(lb, []).append((la, sign / ratio))
    rel: dict[str, sp.Expr] = {}
    for start in edges:
        if start in rel:
            continue
        rel[start] = sp.Integer(1)
        todo = [start]
        while todo:
            a = todo.pop()
            for b, f in edges[a]:
                if b not in rel:
                    rel[b] = sp.cancel(rel[a] * f)
                    todo.append(b)
    return rel


def _ratio(ga: Any, gb: Any) -> sp.Expr:
    """z_a / z_b by tooth numbers (pitch radii where a gear has none or the modules differ)."""
    if ga.teeth is not None and gb.teeth is not None and (ga.module == gb.module):
        return sp.cancel(ga.teeth / gb.teeth)
    return sp.cancel(ga.radius / gb.radius)


def _shown(mech: Mechanism, named: set[str]) -> set[str]:
    """Links drawn as nodes: all but bevel pinions and plain planets nobody names."""
    carriers = {L.carrier for L in mech.links if L.kind is LinkKind.PLANET}
    out = set()
    for L in mech.links:
        if L.axis == "radial":
            continue
        plain = L.kind is LinkKind.PLANET and L.arm != 0 and L.name not in carriers
        if not plain or L.name in named:
            out.add(L.name)
    return out


def _join(a: dict[str, sp.Expr], b: dict[str, sp.Expr]) -> dict[str, sp.Expr] | None:
    """``a`` and ``b`` as one lever (``b`` mapped onto ``a`` by two shared nodes), or None."""
    shared = [n for n in a if n in b]
    for u in shared:
        for v in shared:
            if sp.simplify(b[u] - b[v]) == 0:
                continue
            scale = sp.cancel((a[u] - a[v]) / (b[u] - b[v]))
            shift = sp.cancel(a[u] - scale * b[u])
            mapped = {n: sp.cancel(scale * x + shift) for n, x in b.items()}
            if all(sp.simplify(mapped[n] - a[n]) == 0 for n in shared):
                return {**mapped, **a}
            return None
    return None


def _whole(positions: Mapping[str, sp.Expr]) -> dict[str, int] | None:
    """Positions as whole numbers with no common factor, the lowest first; None if symbolic."""
    values = {n: sp.nsimplify(x) for n, x in positions.items()}
    if not all(x.is_Rational for x in values.values()):
        return None
    lcm = sp.ilcm(*[sp.Rational(x).q for x in values.values()]) if values else 1
    ints = {n: int(x * lcm) for n, x in values.items()}
    g = 0
    for x in ints.values():
        g = sp.igcd(g, x)
    ints = {n: x // g for n, x in ints.items()} if g else ints
    return dict(sorted(ints.items(), key=lambda kv: kv[1]))


def levers(mech: Mechanism, named: set[str] | None = None) -> list[Lever]:
    """The levers of ``mech`` (a :class:`~symkin.trains.Train` names the links of its states).

    Positions come from tooth numbers only (the kinematic engine is not asked): the
    speeds a state solves lie on a straight line over each lever's positions.  A train
    with symbolic tooth numbers has no drawable lever: its levers are left out.

    >>> from symkin.trains import load_train
    >>> levers(load_train("ravigneaux"))[0].positions   # 1st: C held, S1 at 12 and R at 5: ratio 12/5
    {'S2': -10, 'C': 0, 'R': 5, 'S1': 12}
    """
    if named is None:
        named = _named(mech)
    shown = _shown(mech, named)
    found: list[tuple[dict[str, sp.Expr], list[str]]] = []
    for holder, meshes in _meshes_by_holder(mech).items():
        rel = _relative_speeds(mech, meshes)
        nodes = {n: x for n, x in rel.items() if n in shown}
        nodes[holder] = sp.Integer(0)
        if holder == FRAME:
            nodes.pop(FRAME, None) if not mech.link(FRAME).gears and FRAME not in named else None
        found.append((nodes, [holder]))
    _merge(found)
    out = []
    for nodes, holders in found:
        whole = _whole(nodes)
        if whole is not None and len(whole) >= 2:
            out.append(Lever(whole, tuple(holders)))
    return out


def _named(mech: Mechanism) -> set[str]:
    """The links a train's states name (inputs, outputs, brakes, clutches), by their model names."""
    named = {n for st in getattr(mech, "states", ()) for n in (st.input, st.output, *st.brakes,
                                                                *(x for pair in st.clutches for x in pair))}
    return {mech.link(n).name for n in named}


def _meshes_by_holder(mech: Mechanism) -> dict[str, list[Any]]:
    """The meshes' geometries by the link that holds both their axes (none on that link itself)."""
    groups: dict[str, list[Any]] = {}
    for mesh in mech.meshes:
        geo = mech.mesh_geometry(mesh)
        if geo.holder in (geo.link_a.name, geo.link_b.name):
            continue  # a gear on the holder itself: nothing turns relative to it
        groups.setdefault(geo.holder, []).append(geo)
    return groups


def _merge(found: list[tuple[dict[str, sp.Expr], list[str]]]) -> None:
    """Join, in place, the levers that share a link (:func:`_join`) until none can be joined."""
    merged = True
    while merged:
        merged = False
        for i in range(len(found)):
            for j in range(i + 1, len(found)):
                joined = _join(found[i][0], found[j][0])
                if joined is not None:
                    found[i] = (joined, found[i][1] + found[j][1])
                    del found[j]
                    merged = True
                    break
            if merged:
                break
