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

import itertools
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError
from symkin.model import FRAME, LinkKind, Mechanism
from symkin.values import as_expr

__all__ = ["MILLIMETRE", "Arm", "inertia_of", "mass_of", "carrier_chain", "multiplicity", "pinion_distance", "by_name",
           "mesh_pressure_angle", "working_pressure_angle", "reference_radius"]

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


#: The pressure angle of a gear whose train file gives none (degrees): the standard basic rack's (ISO 53).
PRESSURE_ANGLE = 20


def reference_radius(gear: Any) -> sp.Expr:
    """A gear's reference pitch radius m z / 2 where it has a tooth number and a module, numbers
    or symbols (its ``radius`` may be a working one), else its pitch radius: its base radius is
    this times the cosine of the pressure angle."""
    if gear.teeth is not None and gear.module is not None:
        return gear.module * gear.teeth / 2
    return gear.radius


def mesh_pressure_angle(mech: Mechanism, mesh: Any, given: Any = None) -> sp.Expr:
    """A mesh's pressure angle (rad), the one of its base circles: ``given`` (radians, or a pint
    angle) when given, else the ``pressure_angle`` its gears' tooth forms in the train file
    declare (degrees; 20 for a gear that declares none), which must agree."""
    if given is not None:
        return as_expr(given, what="pressure angle", unit="rad")
    forms = {g: dict(keys) for g, keys in getattr(mech, "tooth_forms", ())}
    declared = {g: forms.get(g, {}).get("pressure_angle", PRESSURE_ANGLE) for g in (mesh.a, mesh.b)}
    if declared[mesh.a] != declared[mesh.b]:
        raise InputError(f"gears {mesh.a} and {mesh.b} mesh but have different pressure angles ({declared[mesh.a]} and "
                         f"{declared[mesh.b]} degrees; {PRESSURE_ANGLE} where the train file gives none); give both the "
                         "same pressure_angle")
    return sp.pi * sp.Rational(declared[mesh.a]) / 180


def working_pressure_angle(mech: Mechanism, mesh: Any, given: Any = None) -> sp.Expr:
    """A mesh's working pressure angle (rad), the angle of its line of action to the common
    tangent of its working circles.

    The pressure angle is ``given`` (radians, or a pint angle) for every mesh when given, else the
    ``pressure_angle`` its gears' tooth forms in the train file declare (degrees; 20 for a gear
    that declares none).  A mesh at a working centre distance a_w other than the reference a of
    its gears (m (z1 +- z2) / 2, or the pitch radii where tooth numbers are not known), a
    profile-shifted mesh or gears whose radii are given as working radii, keeps its base circles,
    so its working angle is acos(a cos(alpha) / a_w).  A bevel mesh keeps the pressure angle.

    >>> from symkin.trains import read_train
    >>> train = read_train('''
    ... module = 1
    ... meshes = [{ gears = ["a", "b"], centre_distance = 31 }]
    ... [links.A]
    ... gears = { a = { teeth = 20, pressure_angle = 25 } }
    ... [links.B]
    ... carrier = "frame"
    ... gears = { b = { teeth = 40, pressure_angle = 25 } }
    ... ''')
    >>> sp.cos(working_pressure_angle(train, train.meshes[0]))
    30*cos(5*pi/36)/31
    """
    alpha = mesh_pressure_angle(mech, mesh, given)
    ga, gb = mech.gear(mesh.a), mech.gear(mesh.b)
    if ga.bevel or gb.bevel:
        return alpha
    # the reference distance from the tooth numbers where they are known (a gear's radius may be
    # given as its working radius), else from the pitch radii; the working one from the model
    radii = [reference_radius(g) for g in (ga, gb)]
    reference = abs(radii[0] - radii[1]) if ga.internal or gb.internal else radii[0] + radii[1]
    working = mech.mesh_geometry(mesh).centre_distance
    if reference == working:
        return alpha
    cosine = reference * sp.cos(alpha) / working
    if cosine.is_number and cosine > 1:
        raise InputError(f"mesh {mesh.a}-{mesh.b} works at {working}, nearer than its base circles allow "
                         f"({sp.N(reference * sp.cos(alpha), 6)}, the reference distance {reference} times cos of the "
                         "pressure angle); give a larger centre distance, or check the gears' radii")
    return sp.acos(cosine)


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


def base_motion(base: Any, length: sp.Expr) -> tuple[sp.Matrix, sp.Matrix] | None:
    """The base's angular velocity and the velocity of its main-axis point O, both in the base's
    own axes (rad/s, m/s; O's coordinates are model lengths), or None for a base that does not move."""
    if base is None:
        return None
    R, dR, _ = base.turns
    _, dO, _ = base.origin
    if dR == sp.zeros(3, 3) and dO == sp.zeros(3, 1):
        return None
    # R^T R' is skew: the angular velocity in the base's axes
    Omega = sp.Matrix([_sin_squares((R[:, i].T * dR[:, j])[0]) for i, j in ((2, 1), (0, 2), (1, 0))])
    V = (R.T * dO).applyfunc(_sin_squares) * length
    return Omega, V


def moving_base_kinetic_energy(mech: Mechanism, speeds: Mapping[str, sp.Expr], angles: Mapping[str, sp.Expr],
                               length: sp.Expr, Omega: sp.Matrix, V: sp.Matrix) -> sp.Expr:
    """The kinetic energy on a base that turns at ``Omega`` with its point O moving at ``V`` (both in the
    base's axes), every planet copy summed at its place.  Each body is axisymmetric about its own axis;
    the terms of a main-axis or parallel link's transverse inertia depend on time only, enter no equation
    and are left out; a bevel pinion's transverse moment is half its axial one (a thin disc).
    """
    def omega(name: str) -> sp.Expr:
        return sp.Integer(0) if name == FRAME else speeds[name]

    def angle(name: str) -> sp.Expr:
        return sp.Integer(0) if name == FRAME else angles[name]

    z = sp.Matrix([0, 0, 1])
    total = sp.Integer(0)
    for L in mech.moving_links:
        J = inertia_of(mech, L.name)
        chain = carrier_chain(mech, L.name)
        if not chain:
            total += J * (omega(L.name) + Omega[2]) ** 2 / 2
            continue
        m = mass_of(mech, L.name)
        for index in itertools.product(*(range(arm.count) for arm in chain)):
            r, v, offset = sp.zeros(3, 1), sp.zeros(3, 1), sp.Integer(0)
            for k, arm in enumerate(chain):
                offset += 2 * sp.pi * sp.Integer(index[k]) / arm.count
                psi = angle(arm.carrier) + arm.angle + offset
                e = sp.Matrix([sp.cos(psi), sp.sin(psi), 0])
                r += arm.length * length * e
                v += arm.length * length * omega(arm.carrier) * z.cross(e)
            centre = V + Omega.cross(r) + v
            total += m * centre.dot(centre) / 2
            if L.axis == "radial":
                assert L.carrier is not None
                along = e  # the pinion's axis: the last arm's direction
                w = Omega + omega(L.carrier) * z + omega(L.name) * along
                spin = w.dot(along)
                total += J * spin ** 2 / 2 + J / 2 * (w.dot(w) - spin ** 2) / 2
            else:
                total += J * (omega(L.name) + Omega[2]) ** 2 / 2
    return _tidy_trig(total)


def _tidy_trig(expr: sp.Expr) -> sp.Expr:
    """Sines and cosines of sums expanded (the copies' offsets are exact angles, so their sums
    over the copies cancel) and sin^2 written as 1 - cos^2, so equal terms meet."""
    expr = expr.replace(lambda e: isinstance(e, (sp.sin, sp.cos)), lambda e: type(e)(sp.expand(e.args[0])))
    return _sin_squares(sp.expand_trig(expr))


def _sin_squares(expr: sp.Expr) -> sp.Expr:
    """``expr`` expanded with every sin(x)^n (n >= 2) written as sin(x)^(n-2) (1 - cos(x)^2): a
    polynomial in sines and cosines reduced so that sin^2 + cos^2 = 1 is used (far cheaper than
    trigsimp on a base's rotation).

    >>> x = sp.Symbol("x")
    >>> _sin_squares(sp.sin(x)**2 + sp.cos(x)**2)
    1
    """
    expr = sp.expand(expr)
    while True:
        new = sp.expand(expr.replace(
            lambda e: e.is_Pow and isinstance(e.base, sp.sin) and e.exp.is_Integer and e.exp >= 2,
            lambda e: sp.sin(e.base.args[0]) ** (e.exp - 2) * (1 - sp.cos(e.base.args[0]) ** 2)))
        if new == expr:
            return expr
        expr = new


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
