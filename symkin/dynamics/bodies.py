"""The moving bodies of a train and their mass properties, for the dynamics.

A link is one rigid body, or ``count`` equal bodies for a planet (the product of the counts
down a chain of carriers for a planet of a planet).  Each body's kinetic energy is its spin
about its own axis and, for a planet, the motion of its centre, which moves with its axis on
its carrier (the chain of carriers of :meth:`~symkin.model.Mechanism.axis_position`).

Units: inertias in kg m^2, masses in kg, torques in N m; the model's lengths (pitch radii and
arms from the module, in millimetres in a train file) are multiplied by ``length`` (metres per
model length unit, 1/1000 by default) wherever a length enters an energy.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError
from symkin.model import FRAME, LinkKind, Mechanism

__all__ = ["MILLIMETRE", "Arm", "inertia_of", "mass_of", "carrier_chain", "multiplicity", "pinion_distance", "by_name"]

#: Metres per millimetre: the model's lengths (module in mm, ISO 54) in SI.
MILLIMETRE = sp.Rational(1, 1000)


def by_name(expr: Any, values: Mapping[Any, Any] | None) -> Any:
    """``expr`` with each symbol named in ``values`` (by its name, or the symbol itself) replaced by
    its value (a number, an expression, or a pint quantity in SI units); a positive symbol (a mass
    property, a stiffness) takes no negative value.

    >>> by_name(sp.Symbol("J_S", positive=True) + 1, {"J_S": 0.01})
    101/100
    """
    if not values:
        return expr
    from symkin.values import as_rational

    given = {}
    for key, value in values.items():
        name = key.name if isinstance(key, sp.Symbol) else key
        if not isinstance(name, str):
            raise InputError(f"values are given by symbol name, such as 'J_S', got {key!r}")
        if isinstance(value, float):
            value = as_rational(value, what=f"value of {name}")
        given[name] = value
    swap = {}
    for sym in expr.free_symbols:
        if sym.name in given:
            from symkin.values import as_expr

            swap[sym] = as_expr(given[sym.name], what=f"value of {sym.name}")
            if sym.is_positive and swap[sym].is_negative:
                raise InputError(f"{sym.name} is a mass property or a stiffness: give it a value of 0 or more, "
                                 f"got {given[sym.name]}")
    return expr.xreplace(swap)


def inertia_of(mech: Mechanism, link: str) -> sp.Expr:
    """A link's moment of inertia about its own axis (of one planet): as given, else the symbol ``J_<link>``.

    >>> from symkin.trains import load_train
    >>> inertia_of(load_train("simple"), "S")
    J_S
    """
    value = mech.link(link).inertia
    return sp.Symbol(f"J_{link}", positive=True) if value is None else value


def mass_of(mech: Mechanism, link: str) -> sp.Expr:
    """A planet's mass (of one planet): as given, else the symbol ``m_<link>``; 0 for a link on the main axis.

    >>> from symkin.trains import load_train
    >>> mass_of(load_train("simple"), "P"), mass_of(load_train("simple"), "S")
    (m_P, 0)
    """
    L = mech.link(link)
    if L.kind is not LinkKind.PLANET:
        return sp.Integer(0)
    return sp.Symbol(f"m_{link}", positive=True) if L.mass is None else L.mass


@dataclass(frozen=True)
class Arm:
    """One step from the main axis towards a planet's centre: ``planet`` sits at ``length``
    from the axis of ``carrier``, at ``angle`` on it at t = 0 (its position angle), and
    ``count`` equal planets of its kind are equally spaced on the carrier."""

    planet: str
    carrier: str
    length: sp.Expr
    angle: sp.Expr
    count: int


def pinion_distance(mech: Mechanism, pinion: str) -> sp.Expr:
    """Where a bevel pinion's centre is taken: on its axis at the pitch radius of the side gear it meshes
    (the distance of the contact from the main axis).

    >>> from symkin.trains import load_train
    >>> pinion_distance(load_train("bevel-differential"), "P")
    8
    """
    gears = {g.name for g in mech.link(pinion).gears}
    for mesh in mech.meshes:
        if mesh.a in gears or mesh.b in gears:
            geo = mech.mesh_geometry(mesh)
            if geo.kind == "bevel":
                return geo.centre_distance
    raise InputError(f"bevel pinion {pinion} meshes no side gear, so where its centre is is unknown")


def carrier_chain(mech: Mechanism, link: str) -> tuple[Arm, ...]:
    """The arms from the main axis to a planet's centre, outermost first (empty for a link on the main axis).

    >>> from symkin.trains import load_train
    >>> [(a.planet, a.carrier, a.length, a.count) for a in carrier_chain(load_train("nested"), "Q")]
    [('P', 'C', 45, 2), ('Q', 'P', 15, 3)]
    """
    chain = []
    at = mech.link(link)
    while at.kind is LinkKind.PLANET:
        assert at.carrier is not None
        carrier = mech.link(at.carrier)
        if carrier.axis == "radial":
            raise InputError(f"link {at.name} is carried by bevel pinion {carrier.name}; the dynamics takes the links "
                             "a bevel pinion carries as not modelled: carry them on a link with a parallel axis")
        length = pinion_distance(mech, at.name) if at.axis == "radial" else mech.arm(at.name)
        chain.append(Arm(at.name, carrier.name, length, mech.position_angle(at.name), at.count))
        at = carrier
    return tuple(reversed(chain))


def multiplicity(mech: Mechanism, link: str) -> int:
    """How many bodies a link is: the product of the counts down its chain of carriers.

    >>> from symkin.trains import load_train
    >>> multiplicity(load_train("nested"), "Q"), multiplicity(load_train("nested"), "G")
    (6, 2)
    """
    n = 1
    for arm in carrier_chain(mech, link):
        n *= arm.count
    return n


def rigid_kinetic_energy(mech: Mechanism, speeds: Mapping[str, sp.Expr], angles: Mapping[str, sp.Expr],
                         length: sp.Expr) -> sp.Expr:
    """The kinetic energy of every moving body when each link turns at ``speeds[link]`` and has turned
    by ``angles[link]`` since t = 0 (both linear in the coordinates), the equal planets of a kind
    summed: their centres' cross terms cancel over the equally spaced copies (a sum of cosines
    over the n-th roots of unity) wherever a count between two arms exceeds 1.
    """
    def omega(name: str) -> sp.Expr:
        return sp.Integer(0) if name == FRAME else speeds[name]

    def angle(name: str) -> sp.Expr:
        return sp.Integer(0) if name == FRAME else angles[name]

    total = sp.Integer(0)
    for L in mech.moving_links:
        n = multiplicity(mech, L.name)
        J = inertia_of(mech, L.name)
        if L.axis == "radial":
            # spin relative to the carrier about the radial axis, and the carrier's turn about a
            # diameter of the pinion (a thin disc: half the axial moment)
            assert L.carrier is not None
            total += n * J * (omega(L.name) ** 2 + omega(L.carrier) ** 2 / 2) / 2
        else:
            total += n * J * omega(L.name) ** 2 / 2
        if L.kind is not LinkKind.PLANET:
            continue
        m = mass_of(mech, L.name)
        chain = carrier_chain(mech, L.name)
        v2 = sp.Integer(0)
        for i, outer in enumerate(chain):
            v2 += (outer.length * length) ** 2 * omega(outer.carrier) ** 2
            for j in range(i + 1, len(chain)):
                inner = chain[j]
                if any(a.count > 1 for a in chain[i + 1: j + 1]):
                    continue  # the equally spaced copies cancel this cross term
                phase = angle(inner.carrier) + inner.angle - angle(outer.carrier) - outer.angle
                v2 += 2 * outer.length * inner.length * length ** 2 * omega(outer.carrier) * omega(inner.carrier) * sp.cos(phase)
        total += n * m * v2 / 2
    return total


def angles_of(speeds: Mapping[str, sp.Expr], coordinates: tuple[str, ...]) -> dict[str, sp.Expr]:
    """Each link's turn since t = 0 from its speed law, linear with constant coefficients in the
    coordinates' speeds: omega_c replaced by varphi_c."""
    swap = {S.omega(c): S.angle(c) for c in coordinates}
    return {name: sp.sympify(w).xreplace(swap) for name, w in speeds.items()}


def link_speeds(mech: Mechanism, known: Mapping[str, Any], joined: Any) -> dict[str, sp.Expr]:
    """Every moving link's speed (the engine's laws) from the known speeds and the joined pairs."""
    from symkin.kinematics import solve_speeds

    speeds = solve_speeds(mech, known, joined=joined)
    return {L.name: sp.expand(speeds[L.name]) for L in mech.moving_links}
