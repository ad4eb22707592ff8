"""The assembly of k equally spaced planets, derived from the engine's contact conditions.

Turn the whole train by ``2 pi / k`` (a copy of the planets then stands where the next one
goes) and turn each gear on the main axis back by ``2 pi / k`` less a whole number of its
pitches, the carrier held: the contact conditions (:func:`symkin.kinematics.contact_condition`)
written for these turns must hold with some turn of each planet kind.  The planet turns are
eliminated one mesh at a time, leaving integer rows ``sum(G_i n_i) = R / (q k)`` in the
tooth numbers (:class:`~symkin.synthesis.parts.AssemblyRow`), classified by how each is
decided.

    >>> from symkin.trains import load_train
    >>> from symkin.synthesis.problem import symbolic_train
    >>> train, _ = symbolic_train(load_train("simple"))
    >>> [[str(row.numerator) for row in g.rows] for g in assembly_groups(train, {"P": 3})]
    [['z_r + z_s']]
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence

import sympy as sp

from symkin import symbols as S
from symkin.errors import CoaxialityWarning, InputError, UnsupportedError
from symkin.kinematics import contact_condition
from symkin.model import FRAME, Link, LinkKind, Mechanism, Mesh
from symkin.synthesis.parts import AssemblyGroup, AssemblyRow, K, mesh_module

__all__ = ["assembly_groups"]

#: The link that holds the frame's gears while the assembly is derived (they turn back like any central gear).
_FREED = "frame-gears"  # a valid link name (names go into LaTeX: symkin.model checks them)


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


def assembly_groups(train: Mechanism, counts: Mapping[str, int]) -> list[AssemblyGroup]:
    """The assembly conditions of every group of meshing planets, by carrier (module docstring)."""
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
    rows, integers, turns = _turned_contacts(train, carrier, planets)
    known, pending = _eliminate(rows, turns)
    leftover = [r for r in turns if r not in known]
    if leftover:
        raise UnsupportedError(f"planets {', '.join(planets)} mesh no gear on the main axis; symkin derives the assembly "
                               "of planets that do")
    out = []
    for row in pending:
        row = sp.expand(row.subs(known))
        if row == 0:
            continue
        out.append(_integer_row(row, integers))
    return _classify(out)


def _turned_contacts(train: Mechanism, carrier: str, planets: Sequence[str]
                     ) -> tuple[list[sp.Expr], list[sp.Symbol], set[sp.Symbol]]:
    """The contact condition of every mesh of the group written for the turns of the assembly.

    Each planet kind turns by ``u_P`` revolutions, each link on the main axis back by
    ``1/k`` less ``t_L`` revolutions, a whole number ``n_g`` of pitches of each of its gears,
    the carrier held.  Returns the rows (the gears' pitch rows first), the integers they
    bring, and the real turns to eliminate.
    """
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
        subs: dict[sp.Symbol, sp.Expr] = {S.omega(carrier): sp.Integer(0)} if carrier != FRAME else {}
        for L, g in zip(links, (geo.gear_a, geo.gear_b)):
            subs[S.omega(L.name)] = _turn(L, g.name, carrier, turn, back)
            if L.kind is not LinkKind.PLANET and g.name not in seen_gears:
                seen_gears.add(g.name)
                n = sp.Symbol(f"n_{g.name}", integer=True)
                integers.append(n)
                gear_rows.append(g.teeth * back[L.name] - n)  # the link turns back by whole pitches of g
        row = sp.expand((eq.lhs - eq.rhs).subs(subs) / (sp.pi * mesh_module(train, mesh)))
        if all(L.kind is LinkKind.PLANET for L in links):
            n = sp.Symbol(f"n_{geo.gear_a.name}{geo.gear_b.name}", integer=True)
            integers.append(n)
            row -= n  # two copies mesh alike when their mesh differs by whole pitches
        mesh_rows.append(row)
    return gear_rows + mesh_rows, integers, set(turn.values()) | set(back.values())


def _turn(link: Link, gear: str, carrier: str, turn: dict[str, sp.Symbol], back: dict[str, sp.Symbol]) -> sp.Expr:
    """The angle a link turns by in the assembly: a planet kind by its ``u``, a link on the main axis back by
    ``2 pi/k`` less its ``t`` (a new symbol on its first mesh)."""
    if link.kind is LinkKind.PLANET:
        return 2 * sp.pi * turn[link.name]
    if link.name == carrier:
        raise UnsupportedError(f"gear {gear} on carrier {carrier} meshes its own planets; symkin derives the "
                               "assembly of planets meshing gears on other links")
    back.setdefault(link.name, sp.Symbol(f"t_{link.name}", real=True))
    return 2 * sp.pi * (-1 / K + back[link.name])


def _eliminate(rows: list[sp.Expr], unknowns: set[sp.Symbol]) -> tuple[dict[sp.Symbol, sp.Expr], list[sp.Expr]]:
    """Solve the rows for the unknowns one at a time (a row with one unknown left gives it): the
    unknowns solved, and the rows left."""
    known: dict[sp.Symbol, sp.Expr] = {}
    pending = list(rows)
    progress = True
    while progress:
        progress = False
        for i, row in enumerate(pending):
            row = sp.expand(row.subs(known))
            unknown = [r for r in unknowns if r not in known and row.has(r)]
            if len(unknown) == 1:
                r = unknown[0]
                c = row.coeff(r)
                known[r] = sp.expand(-(row - c * r) / c)
                pending.pop(i)
                progress = True
                break
    return known, pending


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
