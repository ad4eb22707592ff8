"""Planar vibration of a simple planetary set: the rotational-translational lumped-parameter model
of Lin and Parker (1999), derived here from its energies.

Each central member (sun, ring, carrier) translates in the plane (``x``, ``y``, fixed axes, metres)
and turns (``theta``, radians); each planet translates (``zeta`` along its radius, ``eta`` along
the tangent at its place ``psi``, metres) and turns (``theta``) about its own centre.  Every
body's kinetic energy is ``m (x'^2 + y'^2) / 2 + J theta'^2 / 2``.  The springs, each with energy
``k d^2 / 2``:

- a central member's bearing (``k`` on both translations, isotropic) and, where given, its
  torsional stiffness (N m/rad) to the frame;
- each planet's bearing on its pin, which sits at ``carrier_radius`` on the carrier: ``d`` is the
  planet centre's displacement minus the pin's (the carrier's translation plus
  ``carrier_radius x theta_c`` along the tangent);
- each mesh, along its line of action: ``d`` is the displacement of the contact point of one gear
  minus the other's along the line, the translations projected on it and each rotation times
  its base radius.  The lines are those that carry the load when the sun drives the planets
  counterclockwise: the sun-planet line at the pressure angle from the planet's tangent towards
  its radius outwards, the ring-planet line towards the centre (Lin and Parker's; both flanks
  the other way are the mirror image, with the same frequencies).

M and K are the Hessians of these energies: exact, symbolic where a value is a symbol.  The radii
are taken as given (a published model's need not be those of one tooth geometry); the carrier's
is the radius of the planets' pins.  No mesh phasing, no time-varying mesh stiffness, no
gyroscopic terms (the set at rest).

    >>> model = planar_model(3, base_radii={"sun": 0.02, "ring": 0.06, "planet": 0.02},
    ...     carrier_radius=0.04, pressure_angle=0, masses=dict(sun=1, ring=2, carrier=3, planet=1),
    ...     inertias=dict(sun=1e-4, ring=1e-3, carrier=1e-3, planet=1e-4),
    ...     bearings=dict(sun=1e8, ring=1e8, carrier=1e8, planet=1e8), mesh_stiffness=(5e8, 5e8))
    >>> model.names[:3], len(model.names)
    (('x_sun', 'y_sun', 'theta_sun'), 18)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin.dynamics.bodies import (
    MILLIMETRE,
    carrier_chain,
    inertia_of,
    mesh_pressure_angle,
    reference_radius,
    working_pressure_angle,
)
from symkin.dynamics.torsional import Modes, TorsionalModel, modes_of
from symkin.errors import InputError
from symkin.model import LinkKind, Mechanism
from symkin.values import as_expr

__all__ = ["planar_model", "planar_modes", "planar_geometry", "PlanarModel", "CENTRAL"]

#: The central members, in the order of the coordinates.
CENTRAL = ("sun", "ring", "carrier")
BODIES = (*CENTRAL, "planet")


@dataclass(frozen=True)
class PlanarModel(TorsionalModel):
    """``M q'' + K q = 0`` of a planetary set in the plane (:func:`planar_model`): the coordinates
    (``x_sun``, ``y_sun``, ``theta_sun``, ..., ``zeta_1``, ``eta_1``, ``theta_1`` for planet 1) and
    the matrices, exact; ``train`` is None (the model is built from its geometry)."""

    kind = "planar model"
    unit = "m, rad"

    def modes(self, rigid_tolerance: float = 1e-9) -> Modes:
        """Natural frequencies (Hz, rigid-body modes 0) and mode shapes (SciPy ``eigh``)."""
        return modes_of(self, rigid_tolerance)


def _by_body(given: Mapping[str, Any] | None, what: str, unit: str, needed: Sequence[str]) -> dict[str, sp.Expr]:
    given = dict(given or {})
    unknown = sorted(set(given) - set(BODIES))
    if unknown:
        raise InputError(f"{what}: unknown bodies {', '.join(unknown)}; the bodies are {', '.join(BODIES)}")
    out = {}
    for body in needed:
        if body not in given:
            raise InputError(f"{what}: give the {body}'s (in {unit})")
        out[body] = as_expr(given[body], what=f"{what} of the {body}", unit=unit)
        if out[body].is_negative:
            raise InputError(f"{what} of the {body} must be 0 or more, got {given[body]}")
    return out


def planar_model(planets: int | Sequence[Any], *, base_radii: Mapping[str, Any], carrier_radius: Any,
                 pressure_angle: Any, masses: Mapping[str, Any], inertias: Mapping[str, Any],
                 bearings: Mapping[str, Any], mesh_stiffness: Sequence[Any],
                 torsional: Mapping[str, Any] | None = None) -> PlanarModel:
    """The rotational-translational model of a simple planetary set (sun, ring, carrier, planets).

    Parameters
    ----------
    planets : int or sequence of angles
        How many planets, equally spaced from angle 0; or each planet's place ``psi`` (radians,
        counterclockwise from the x axis).
    base_radii : mapping
        ``sun``, ``ring``, ``planet`` base radii (m).
    carrier_radius : number
        The radius of the planets' pins on the carrier (m).
    pressure_angle : number or (number, number)
        Radians: one for both meshes, or (sun-planet, ring-planet).
    masses, inertias : mapping
        By body, ``sun``, ``ring``, ``carrier``, ``planet`` (one planet's): kg, kg m^2 about the own axis.
    bearings : mapping
        Translational bearing stiffness (N/m) by body; the planet's, of its bearing on its pin.
    mesh_stiffness : (number, number)
        Sun-planet and ring-planet mesh stiffness (N/m), the same for every planet.
    torsional : mapping, optional
        Torsional stiffness (N m/rad) of ``sun``, ``ring`` or ``carrier`` to the frame; 0 if not given.

    Values may be numbers, SymPy expressions (symbols keep M and K symbolic) or pint quantities.
    """
    psi = _planet_angles(planets)
    angles = pressure_angle if isinstance(pressure_angle, (tuple, list)) else (pressure_angle, pressure_angle)
    if len(angles) != 2 or len(mesh_stiffness) != 2:
        raise InputError("give the pressure angle and the mesh stiffness as (sun-planet, ring-planet) pairs")
    a_s, a_r = (as_expr(a, what="pressure angle", unit="rad") for a in angles)
    k_sp, k_rp = (as_expr(k, what="mesh stiffness", unit="N/m") for k in mesh_stiffness)
    rb = _by_body(base_radii, "base radius", "m", ("sun", "ring", "planet"))
    r_c = as_expr(carrier_radius, what="carrier radius", unit="m")
    m = _by_body(masses, "mass", "kg", BODIES)
    J = _by_body(inertias, "inertia", "kg m^2", BODIES)
    kb = _by_body(bearings, "bearing stiffness", "N/m", BODIES)
    kt = _by_body(torsional, "torsional stiffness", "N m/rad", [b for b in CENTRAL if b in (torsional or {})])
    if "planet" in (torsional or {}):
        raise InputError("torsional stiffness: a planet turns freely on its pin; give the sun's, ring's or carrier's")

    names: list[str] = []
    for body in CENTRAL:
        names += [f"x_{body}", f"y_{body}", f"theta_{body}"]
    for n in range(len(psi)):
        names += [f"zeta_{n + 1}", f"eta_{n + 1}", f"theta_{n + 1}"]
    q = [sp.Symbol(n) for n in names]
    # the energies as sums of squares: T of the bodies' rates, V = sum of k d^2 / 2 over the springs,
    # each d linear in the coordinates, so each term's Hessian is k (grad d)(grad d)^T
    springs: list[tuple[sp.Expr, sp.Expr]] = []
    inertia: list[tuple[sp.Expr, int]] = []
    where = {}
    for i, body in enumerate((*CENTRAL, *["planet"] * len(psi))):
        x, y, th = q[3 * i: 3 * i + 3]
        inertia += [(m[body], 3 * i), (m[body], 3 * i + 1), (J[body], 3 * i + 2)]
        if body != "planet":
            springs += [(kb[body], x), (kb[body], y), (kt.get(body, sp.Integer(0)), th)]
            where[body] = (sp.Matrix([x, y]), th)
    (sun, th_s), (ring, th_r), (carrier, th_c) = (where[b] for b in CENTRAL)
    for n, p in enumerate(psi):
        zeta, eta, th = q[9 + 3 * n: 12 + 3 * n]
        radial, tangent = sp.Matrix([sp.cos(p), sp.sin(p)]), sp.Matrix([-sp.sin(p), sp.cos(p)])
        centre = zeta * radial + eta * tangent
        pin = carrier + r_c * th_c * tangent
        springs += [(kb["planet"], (centre - pin)[0]), (kb["planet"], (centre - pin)[1])]
        line_s = sp.cos(a_s) * tangent + sp.sin(a_s) * radial
        line_r = sp.cos(a_r) * tangent - sp.sin(a_r) * radial
        springs.append((k_sp, line_s.dot(sun - centre) + rb["sun"] * th_s + rb["planet"] * th))
        springs.append((k_rp, line_r.dot(ring - centre) + rb["ring"] * th_r - rb["planet"] * th))
    M, K = _matrices(q, inertia, springs)
    return PlanarModel(None, tuple(names), tuple(q), M, K)  # type: ignore[arg-type]


def _planet_angles(planets: int | Sequence[Any]) -> list[sp.Expr]:
    """Each planet's place psi: ``planets`` equally spaced from angle 0, or the angles given."""
    if isinstance(planets, int):
        if planets < 1:
            raise InputError(f"a planetary set needs at least one planet, got {planets}")
        return [2 * sp.pi * k / planets for k in range(planets)]
    psi = [as_expr(p, what="planet angle", unit="rad") for p in planets]
    if not psi:
        raise InputError("no planet angles given: give at least one, or a number of planets")
    return psi


def _matrices(q: list[sp.Symbol], inertia: list[tuple[sp.Expr, int]],
              springs: list[tuple[sp.Expr, sp.Expr]]) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix]:
    """M (diagonal: the ``inertia`` by coordinate index) and K (the sum of ``k (grad d)(grad d)^T`` over the
    ``springs`` ``(k, d)``, expanded) in the coordinates ``q``."""
    size = len(q)
    M = sp.zeros(size, size)
    for value, i in inertia:
        M[i, i] = value
    K = sp.zeros(size, size)
    for k, d in springs:
        grad = sp.Matrix([d.diff(v) for v in q])
        K += k * grad * grad.T
    return sp.ImmutableMatrix(M), sp.ImmutableMatrix(K.applyfunc(sp.expand))


def planar_modes(planets: int | Sequence[Any], *, rigid_tolerance: float = 1e-9, **geometry: Any) -> Modes:
    """Natural frequencies (Hz, ascending, rigid-body modes 0) and mode shapes of
    :func:`planar_model` (same arguments)."""
    return planar_model(planets, **geometry).modes(rigid_tolerance)


def planar_geometry(train: Mechanism, planet: str | None = None, *, pressure_angle: Any = None,
                    length: Any = MILLIMETRE) -> dict[str, Any]:
    """The arguments of :func:`planar_model` that a simple planetary train's assembly gives: the
    planets' places (the planet's angle on its carrier, ``count`` copies equally spaced), the
    base radii (pitch radius x cos(pressure angle), in metres), the carrier radius (the planet's
    arm), the working pressure angles of the sun-planet and ring-planet meshes
    (:func:`~symkin.dynamics.bodies.working_pressure_angle`: ``pressure_angle`` for both when
    given, else each mesh's gears' ``pressure_angle`` in the train file, 20 degrees where it gives
    none) and the inertias of the links (``J_<link>`` symbols where not given).  Masses, bearings
    and mesh stiffnesses are the caller's.

    >>> from symkin.trains import load_train
    >>> g = planar_geometry(load_train("simple"), pressure_angle=0)
    >>> g["planets"], sorted(g["base_radii"].items()), g["carrier_radius"]
    ([0, 2*pi/3, 4*pi/3], [('planet', 3/250), ('ring', 9/250), ('sun', 3/250)], 3/125)
    """
    planets = [L.name for L in train.moving_links if L.kind is LinkKind.PLANET]
    if planet is None:
        if len(planets) != 1:
            raise InputError(f"the train has planets {', '.join(planets) or 'none'}: name the planet of the "
                             "simple planetary set (planet=...)")
        planet = planets[0]
    elif planet not in planets:
        raise InputError(f"{planet!r} is not a planet of the train; its planets are {', '.join(planets) or 'none'}")
    chain = carrier_chain(train, planet)
    if len(chain) != 1:
        raise InputError(f"planet {planet} is carried by a planet: the planar model is of a simple planetary set")
    arm = chain[0]
    length = as_expr(length, what="length (metres per model length unit)")
    radii: dict[str, sp.Expr] = {}
    base: dict[str, sp.Expr] = {}
    angles: dict[str, sp.Expr] = {}
    links: dict[str, str] = {"carrier": arm.carrier, "planet": planet}
    own = {g.name for g in train.link(planet).gears}
    for mesh in train.meshes:
        if (mesh.a in own) == (mesh.b in own):
            continue
        mine, other = (mesh.a, mesh.b) if mesh.a in own else (mesh.b, mesh.a)
        body = "ring" if train.gear(other).internal else "sun"
        if body in radii:
            raise InputError(f"planet {planet} meshes with two {body}s: the planar model is of a simple planetary set")
        radii[body] = train.gear(other).radius
        radii["planet"] = train.gear(mine).radius
        links[body] = train.link(other).name
        angles[body] = working_pressure_angle(train, mesh, pressure_angle)
        alpha = mesh_pressure_angle(train, mesh, pressure_angle)  # the base circles': the working one's at a_w = a
        base[body] = reference_radius(train.gear(other)) * sp.cos(alpha) * length
        base["planet"] = reference_radius(train.gear(mine)) * sp.cos(alpha) * length
    if set(radii) != {"sun", "ring", "planet"}:
        raise InputError(f"planet {planet} must mesh with a sun (an external gear) and a ring (an internal gear)")
    return {
        "planets": [arm.angle + 2 * sp.pi * k / arm.count for k in range(arm.count)],
        "base_radii": base,
        "carrier_radius": arm.length * length,
        "pressure_angle": angles["sun"] if angles["sun"] == angles["ring"] else (angles["sun"], angles["ring"]),
        "inertias": {b: inertia_of(train, n) for b, n in links.items()},
    }
