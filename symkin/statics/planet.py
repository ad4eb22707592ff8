"""Forces on a stepped planet: torque balance, helical axial forces, and their balance.

Two routes, kept apart on purpose:

* :func:`planet_statics` *derives* (SymPy) from the mechanism's mesh geometry the
  planet's torque balance (the two tangential forces), the axial force of each helical
  rim, and the condition under which the axial forces cancel;
  :func:`mesh_hand_relation` derives from the helix tangency at a pitch point whether
  two meshing gears have equal or opposite hands.
* :func:`planet_forces` *computes* (NumPy) the 3-D tooth forces on the planet of a
  :class:`~symkin.mechanisms.helical.HelicalTrain` for a given input torque, from base circles,
  base helix angles and moment equilibrium; it shares no formula with the derivation or
  with the synthesis, and is the independent check of every synthesised design.

    >>> from symkin import schemes
    >>> st = planet_statics(schemes.two_row("AI"))
    >>> st.magnitudes
    Eq(2*F_t2*r_2, 2*F_t3*r_3)
    >>> st.condition
    Eq(tan(beta_w2)/tan(beta_w3), r_2/r_3)
    >>> st.same_hand, st.same_direction
    (True, True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
import sympy as sp

from symkin._util.budget import simplify_within
from symkin._util.display import short_repr
from symkin.errors import ModelError, UnsupportedError
from symkin.model import LinkKind, Mechanism, Mesh
from symkin.schemes import TWO_ROW, two_row

__all__ = ["PlanetStatics", "planet_statics", "mesh_hand_relation", "balancing_hands", "PlanetForces", "planet_forces"]


def _planet_and_meshes(mech: Mechanism, planet: str | None) -> tuple[Any, list[tuple[Any, Mesh]]]:
    if planet is None:
        planets = [L for L in mech.moving_links if L.kind is LinkKind.PLANET]
        if len(planets) != 1:
            raise ModelError("name the planet: this mechanism has " + str(len(planets)) + " planets")
        link = planets[0]
    else:
        link = mech.link(planet)
        if link.kind is not LinkKind.PLANET:
            raise ModelError(f"link {link.name} is not a planet; name the stepped planet (e.g. '23')")
    if len(link.gears) != 2:
        raise UnsupportedError(f"planet {link.name} has {len(link.gears)} rims; the statics here is for a stepped planet with two")
    rows = []
    for gear in link.gears:
        meshes = [m for m in mech.meshes if gear.name in (m.a, m.b)]
        if len(meshes) != 1:
            raise UnsupportedError(f"rim {gear.name} is in {len(meshes)} meshes; each rim of the stepped planet must mesh once")
        geo = mech.mesh_geometry(meshes[0])
        partner = geo.link_a if geo.link_b.name == link.name else geo.link_b
        if partner.kind is LinkKind.PLANET:
            raise UnsupportedError(f"rim {gear.name} meshes another planet; the statics here is for a planet between central gears")
        rows.append((gear, meshes[0]))
    return link, rows


def _pitch_offset(mech: Mechanism, mesh: Mesh, planet: str) -> sp.Expr:
    """Signed distance of the mesh's pitch point from the planet axis, outward (away
    from the main axis) positive, in the mesh frame of :class:`~symkin.model.MeshGeometry`."""
    geo = mech.mesh_geometry(mesh)
    planet_is_b = geo.link_b.name == planet
    y_planet = geo.centre_distance if planet_is_b else sp.Integer(0)
    outward = 1 if planet_is_b else -1  # the main axis sits at the other gear's axis
    return sp.expand((geo.pitch_y - y_planet) * outward)


@dataclass(frozen=True)
class PlanetStatics:
    """The derived statics of a stepped planet between two central gears.

    Forces are those the central gears exert on the planet at the pitch points, in the
    planet frame (planet axis at the origin, main axis on the -y side): ``tangential`` are
    their x components, the first a free symbol, the second from the torque balance.

    Attributes
    ----------
    planet : str
    rims : (str, str)
        The planet's gears, in the order of the link.
    offsets : (expr, expr)
        Pitch point of each rim: signed distance from the planet axis, outward positive.
    torque_balance : sympy.Eq
        Sum of the moments about the planet axis = 0.
    tangential : (expr, expr)
        The tangential force on each rim; the second solved from the torque balance.
    magnitudes : sympy.Eq
        ``F_t2 d_w2 = F_t3 d_w3`` with F_t the magnitudes.
    same_direction : bool
        Whether the two tangential forces point the same way.
    axial : (expr, expr)
        Axial force on each rim, ``-h F_theta tan(beta_w)``, for hands h and helix angles
        beta_w on the working pitch cylinders.
    axial_sum : expr
    same_hand : bool
        Whether the axial forces can cancel only with rims of the same hand.
    condition : sympy.Eq
        The balance condition ``tan(beta_w2) / tan(beta_w3) = r_w2 / r_w3``.
    """

    planet: str
    rims: tuple[str, str]
    offsets: tuple[sp.Expr, sp.Expr]
    torque_balance: sp.Eq
    tangential: tuple[sp.Expr, sp.Expr]
    magnitudes: sp.Eq
    same_direction: bool
    axial: tuple[sp.Expr, sp.Expr]
    axial_sum: sp.Expr

    def __repr__(self) -> str:
        """``PlanetStatics('23', rims 2, 3, same direction)``, under 200 characters."""
        return short_repr("PlanetStatics", repr(self.planet), f"rims {', '.join(self.rims)}",
                          "same direction" if self.same_direction else "opposite directions")
    same_hand: bool
    condition: sp.Eq

    @property
    def symbols(self) -> dict[str, sp.Symbol]:
        """The symbols the laws are written in: tangential force, hands, working helix angles."""
        a, b = self.rims
        return {
            "F": sp.Symbol(f"F_x{a}", real=True),
            "h_" + a: sp.Symbol(f"h_{a}", nonzero=True),
            "h_" + b: sp.Symbol(f"h_{b}", nonzero=True),
            "beta_w" + a: sp.Symbol(f"beta_w{a}", positive=True),
            "beta_w" + b: sp.Symbol(f"beta_w{b}", positive=True),
        }


def planet_statics(mech: Mechanism, planet: str | None = None) -> PlanetStatics:
    """Derive the torque balance and the axial-force balance of a stepped planet.

    Each central gear pushes its rim at the pitch point with a tangential force (normal to
    the line of centres); the planet turns freely on its axis, so the moments of the two
    forces about it cancel.  On a helical rim the tooth force is normal to the helix on
    the working pitch cylinder, so its axial component is ``-h F_theta tan(beta_w)``.  The
    sum of the two axial forces vanishes when the condition holds.

    Cached per mechanism.

    Examples
    --------
    >>> from symkin import schemes
    >>> st = planet_statics(schemes.two_row("AA"))
    >>> st.tangential
    (F_x2, -F_x2*r_2/r_3)
    >>> st.condition
    Eq(tan(beta_w2)/tan(beta_w3), r_2/r_3)
    """

    def build() -> PlanetStatics:
        link, rows = _planet_and_meshes(mech, planet)
        (g2, m2), (g3, m3) = rows
        a, b = g2.name, g3.name
        rho2, rho3 = (_pitch_offset(mech, m, link.name) for m in (m2, m3))
        F2, F3 = sp.Symbol(f"F_x{a}", real=True), sp.Symbol(f"F_x{b}", real=True)
        # moment about the planet axis of a force (F, 0) at (0, rho): x F_y - y F_x = -rho F
        moments = -rho2 * F2 - rho3 * F3
        balance = sp.Eq(moments, 0)
        (F3_solved,) = sp.solve(balance, F3)
        # circumferential (counter-clockwise about the planet axis) component at (0, rho)
        ft2, ft3 = (-sp.sign(rho) * F for rho, F in ((rho2, F2), (rho3, F3_solved)))
        # a tooth force is normal to the helix, whose tangent on the cylinder is
        # t = h sin(beta) e_theta + cos(beta) e_z, i.e. along h tan(beta) e_theta + e_z
        h, tan_beta = sp.Symbol("h", nonzero=True), sp.Symbol("tan_beta", positive=True)
        f_theta, f_z = sp.symbols("f_theta f_z", real=True)
        (axial_law,) = sp.solve(sp.Eq(h * tan_beta * f_theta + f_z, 0), f_z)
        h2, h3 = sp.Symbol(f"h_{a}", nonzero=True), sp.Symbol(f"h_{b}", nonzero=True)
        bw2, bw3 = sp.Symbol(f"beta_w{a}", positive=True), sp.Symbol(f"beta_w{b}", positive=True)
        fa2 = axial_law.subs({h: h2, tan_beta: sp.tan(bw2), f_theta: ft2})
        fa3 = axial_law.subs({h: h3, tan_beta: sp.tan(bw3), f_theta: ft3})
        total = sp.factor(sp.together(fa2 + fa3))
        T2, T3 = sp.symbols("T_2 T_3", positive=True)  # tan(beta_w2), tan(beta_w3)
        (T2_solved,) = sp.solve(total.subs({sp.tan(bw2): T2, sp.tan(bw3): T3}), T2)
        ratio = sp.cancel(T2_solved / T3)  # the tangent ratio the balance needs
        same = ratio.subs({h2: 1, h3: 1}).is_positive
        opposite = ratio.subs({h2: 1, h3: -1}).is_positive
        if same is None or opposite is None or same == opposite:
            raise UnsupportedError("the axial balance does not single out a pair of hands for this planet")
        r_ratio = sp.cancel(ratio.subs({h2: 1, h3: 1 if same else -1}))
        condition = sp.Eq(sp.tan(bw2) / sp.tan(bw3), r_ratio, evaluate=False)
        Ft2, Ft3 = sp.Symbol(f"F_t{a}", positive=True), sp.Symbol(f"F_t{b}", positive=True)
        magnitudes = sp.Eq(Ft2 * 2 * sp.Abs(rho2), Ft3 * 2 * sp.Abs(rho3), evaluate=False)
        direction = sp.cancel(F3_solved / F2).is_positive
        if direction is None:
            raise UnsupportedError("cannot decide whether the planet's tangential forces point the same way")
        same_direction = bool(direction)
        return PlanetStatics(
            link.name, (a, b), (rho2, rho3), balance, (F2, F3_solved), magnitudes, same_direction,
            (fa2, fa3), total, bool(same), condition,
        )

    key = ("planet_statics", planet)
    return mech._memo(key, build)


def mesh_hand_relation(mech: Mechanism, mesh: Mesh | tuple[str, str]) -> int:
    """+1 when the two gears of ``mesh`` must have the same helix hand, -1 when opposite.

    At the pitch point both helices touch along a common tangent, ``h_a sin(beta)
    e_theta,a = h_b sin(beta) e_theta,b``, where e_theta is each gear's circumferential
    direction there.

    >>> from symkin import schemes
    >>> ai = schemes.two_row("AI")
    >>> mesh_hand_relation(ai, ("1", "2")), mesh_hand_relation(ai, ("3", "4"))
    (-1, 1)
    """
    if not isinstance(mesh, Mesh):
        mesh = Mesh(*mesh)
    geo = mech.mesh_geometry(mesh)
    # e_theta = z x (P - axis); P - axis is along y, so e_theta_x = -(P_y - axis_y)
    ea = -(geo.pitch_y - 0)
    eb = -(geo.pitch_y - geo.centre_distance)
    sign = sp.sign(simplify_within(ea * eb, what=f"the pitch-point geometry of mesh {mesh.a}-{mesh.b}"))
    if sign not in (1, -1):
        raise ModelError(f"cannot decide the helix hands of mesh {mesh.a}-{mesh.b} for these radii")
    return int(sign)


@cache
def balancing_hands(scheme: str, rim_hand: int = 1) -> tuple[int, int, int, int]:
    """Hands (+1 right, -1 left) of gears 1-4 of a two-row scheme whose planet's axial
    forces can cancel, with rims 2 and 3 of hand ``rim_hand``.

    >>> balancing_hands("AA"), balancing_hands("II"), balancing_hands("AI", -1)
    ((-1, 1, 1, -1), (1, 1, 1, 1), (1, -1, -1, -1))
    """
    if rim_hand not in (1, -1):
        raise ModelError(f"a helix hand is +1 (right) or -1 (left), got {rim_hand!r}")
    mech = two_row(scheme)
    st = planet_statics(mech)
    h2 = rim_hand
    h3 = h2 if st.same_hand else -h2
    h1 = mesh_hand_relation(mech, ("1", "2")) * h2
    h4 = mesh_hand_relation(mech, ("3", "4")) * h3
    return (h1, h2, h3, h4)


# --------------------------------------------------------------------------- numbers
@dataclass(frozen=True)
class PlanetForces:
    """Tooth forces on one planet of a helical train for a given input torque on gear 1.

    Lengths are those of the train (mm when modules are in mm); forces are in torque
    units per length unit (N for N mm).  The planet frame has the planet axis along z
    through the origin and the main axis at (0, -a_w, 0).

    Attributes
    ----------
    contact_2, contact_3 : ndarray
        Pitch points of meshes 1-2 and 3-4.
    force_2, force_3 : ndarray
        Forces of gears 1 and 4 on rims 2 and 3 (x tangential, y radial, z axial).
    axial_sum : float
        ``force_2[2] + force_3[2]``: the axial load on the planet bearings.
    axial_residual : float
        ``|axial_sum| / max(|force_2[2]|, |force_3[2]|)``.
    carrier_torque : float
        Torque all planets exert on the carrier.
    ratio : float
        Carrier torque per input torque: i_1H^(4) by statics (virtual work).
    hand_mismatch : float
        How far the axial force on each central gear, from its own hand, misses Newton's
        third law (0 when the hands of every mesh fit).
    """

    contact_2: np.ndarray
    contact_3: np.ndarray
    force_2: np.ndarray
    force_3: np.ndarray
    axial_sum: float

    def __repr__(self) -> str:
        """``PlanetForces(F2 = [...], F3 = [...], axial sum ...)``, under 200 characters."""
        return short_repr("PlanetForces", f"F2 = {np.round(self.force_2, 4).tolist()}",
                          f"F3 = {np.round(self.force_3, 4).tolist()}", f"axial sum {self.axial_sum:.4g}")
    axial_residual: float
    carrier_torque: float
    ratio: float
    hand_mismatch: float

    def balanced(self, tolerance: float = 1e-12) -> bool:
        """True when the axial forces cancel to ``tolerance`` (relative)."""
        return self.axial_residual <= tolerance


def _tooth_force(tangential_x: float, point: np.ndarray, centre: np.ndarray, hand: int, alpha_tw: float,
                 beta_base: float, separating: float) -> np.ndarray:
    """The 3-D normal tooth force with the given tangential (x) component at ``point``.

    It lies in the plane of action: in the transverse plane along the line of action
    (inclined at alpha_tw, its radial part ``separating`` pushing the gears apart), and
    out of it at the base helix angle, towards the side the gear's hand dictates.
    """
    transverse = abs(tangential_x) / math.cos(alpha_tw)
    u = np.array([tangential_x, separating * transverse * math.sin(alpha_tw), 0.0]) / transverse
    # sense of the line of action about this gear's axis (+1 counter-clockwise)
    c = math.copysign(1.0, np.cross(point - centre, u)[2])
    # normal of a helicoid in the plane of action: cos(beta_b) t - h sin(beta_b) e_z, t the CCW tangent
    axial = -hand * c * transverse * math.tan(beta_base)
    return np.array([u[0] * transverse, u[1] * transverse, axial])


def planet_forces(train: Any, input_torque: float = 1.0) -> PlanetForces:
    """The forces on a planet of ``train`` when gear 1 carries ``input_torque`` (gear 4 fixed).

    Independent of the derivation: gear 1's equilibrium with ``k`` planets gives the
    tangential force at mesh 1-2; the planet's moment equilibrium about its axis (3-D
    cross products) gives the force at mesh 3-4; each normal force is built on the base
    cylinder from the working pressure angle, the base helix angle and the gear's hand.

    Parameters
    ----------
    train : HelicalTrain
    input_torque : float

    Examples
    --------
    >>> import math
    >>> from symkin.mechanisms.helical import HelicalTrain
    >>> t = HelicalTrain("AI", (20, 40, 20, 80), (2, 2), (math.radians(12), math.radians(12)), satellites=3)
    >>> f = planet_forces(t)
    >>> f.balanced(), round(f.ratio, 12)
    (False, 9.0)
    """
    try:
        torque = float(input_torque)
    except (TypeError, ValueError):
        raise ModelError(f"the input torque must be a number, got {input_torque!r}") from None
    if not math.isfinite(torque) or torque == 0:
        raise ModelError(f"the input torque must be finite and non-zero, got {input_torque!r}")
    internal1, internal4 = TWO_ROW[train.scheme]
    h1, h2, h3, h4 = train.hands
    k = train.satellites
    m12, m34 = train.mesh12, train.mesh34
    a12, a34 = m12.centre_distance, m34.centre_distance
    origin = np.zeros(3)

    def pitch_point(mesh: Any, internal_mate: bool) -> np.ndarray:
        r_rim = mesh.working_radius("external")
        return np.array([0.0, r_rim if internal_mate else -r_rim, 0.0])  # an internal mate touches the far side

    p2, p3 = pitch_point(m12, internal1), pitch_point(m34, internal4)
    c1, c4 = np.array([0.0, -a12, 0.0]), np.array([0.0, -a34, 0.0])
    ex = np.array([1.0, 0.0, 0.0])
    # gear 1: the k planets react its input torque equally: moment of (F_x, ., .) about c1
    arm1 = np.cross(p2 - c1, ex)[2]
    f1x = -(torque / k) / arm1
    sep2 = -math.copysign(1.0, p2[1])  # the radial force on the rim points to the planet axis
    force2 = _tooth_force(-f1x, p2, origin, h2, m12.alpha_tw, m12.beta_base, sep2)
    # planet: moments about its own axis cancel
    moment2 = np.cross(p2, force2)[2]
    f3x = -moment2 / np.cross(p3, ex)[2]
    sep3 = -math.copysign(1.0, p3[1])
    force3 = _tooth_force(f3x, p3, origin, h3, m34.alpha_tw, m34.beta_base, sep3)
    # Newton's third law seen from the central gears' own hands
    on1 = _tooth_force(-force2[0], p2, c1, h1, m12.alpha_tw, m12.beta_base, -sep2)
    on4 = _tooth_force(-force3[0], p3, c4, h4, m34.alpha_tw, m34.beta_base, -sep3)
    scale = max(abs(force2[2]), abs(force3[2]), 1e-300)
    mismatch = max(abs(on1[2] + force2[2]), abs(on4[2] + force3[2])) / scale
    axial_sum = float(force2[2] + force3[2])
    residual = abs(axial_sum) / scale
    # the planet pushes the carrier pin with force2 + force3, at the planet axis
    carrier = k * np.cross(origin - c1, force2 + force3)[2]
    return PlanetForces(p2, p3, force2, force3, axial_sum, float(residual), float(carrier), float(carrier / torque),
                        float(mismatch))
