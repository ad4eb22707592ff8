"""Plane motion of a rigid link as the superposition of its pole's motion and a rotation.

These are the 2009 paper's equations (4)-(6), the only kinematic primitives symkin uses,
and the same superposition in space (a motion carried by a frame that moves and turns in
space; a rotation about an axis that is not the main axis, for bevel pinions).
Plane vectors are 2 x 1 SymPy matrices, vectors in space 3 x 1; (a, b) are Lagrange (initial) coordinates, (x, y)
Euler (current) coordinates, ``dphi`` the link's rotation since t = 0.

    >>> import sympy as sp
    >>> from symkin.superposition import vec, velocity
    >>> w, r = sp.symbols("omega r")
    >>> velocity(vec(0, 0), w, vec(0, r), vec(0, 0)).T  # a point at (0, r) on a link turning about O
    Matrix([[-omega*r, 0]])
"""

from __future__ import annotations

import sympy as sp

__all__ = ["vec", "rotation", "position", "velocity", "acceleration", "vec3", "rotation_about", "spin_velocity",
           "spin_acceleration", "carried"]


def vec(x, y) -> sp.ImmutableMatrix:
    """A plane vector."""
    return sp.ImmutableMatrix([x, y])


def rotation(phi) -> sp.ImmutableMatrix:
    """Counter-clockwise rotation by ``phi``."""
    c, s = sp.cos(phi), sp.sin(phi)
    return sp.ImmutableMatrix([[c, -s], [s, c]])


def position(pole_now, pole_initial, point_initial, dphi) -> sp.ImmutableMatrix:
    """Eq. (4): x = x_P + (a - a_P) cos(dphi) - (b - b_P) sin(dphi), y likewise."""
    return sp.ImmutableMatrix(pole_now + rotation(dphi) * (point_initial - pole_initial))


def _perp(v) -> sp.ImmutableMatrix:
    """k x v: the vector turned a quarter turn counter-clockwise."""
    return vec(-v[1], v[0])


def velocity(pole_velocity, omega, point, pole) -> sp.ImmutableMatrix:
    """Eq. (5): V_x = (V_x)_P - omega (y - y_P),  V_y = (V_y)_P + omega (x - x_P)."""
    return sp.ImmutableMatrix(pole_velocity + omega * _perp(point - pole))


def acceleration(pole_acceleration, omega, epsilon, point, pole) -> sp.ImmutableMatrix:
    """Eq. (6): w = w_P + eps k x (X - X_P) - omega^2 (X - X_P)."""
    rel = point - pole
    return sp.ImmutableMatrix(pole_acceleration + epsilon * _perp(rel) - omega**2 * rel)


# --------------------------------------------------------------------------- in space
def vec3(x, y, z) -> sp.ImmutableMatrix:
    """A vector in space."""
    return sp.ImmutableMatrix([x, y, z])


def rotation_about(axis, phi) -> sp.ImmutableMatrix:
    """Rotation by ``phi`` about the unit vector ``axis`` (right hand; Rodrigues' formula).

    >>> rotation_about(vec3(0, 0, 1), sp.pi / 2) * vec3(1, 0, 0)
    Matrix([
    [0],
    [1],
    [0]])
    """
    u = sp.ImmutableMatrix(axis)
    K = sp.ImmutableMatrix([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])
    return sp.ImmutableMatrix(sp.eye(3) + sp.sin(phi) * K + (1 - sp.cos(phi)) * K * K)


def spin_velocity(omega, axis, rel) -> sp.ImmutableMatrix:
    """Velocity of a point at ``rel`` from a fixed axis through the origin, turning at
    ``omega`` about the unit vector ``axis``: omega axis x rel (eq. 5 in space)."""
    return sp.ImmutableMatrix(omega * sp.Matrix(axis).cross(sp.Matrix(rel)))


def spin_acceleration(epsilon, omega, axis, rel) -> sp.ImmutableMatrix:
    """eps axis x rel + omega^2 axis x (axis x rel): eq. (6) in space (tangential and centripetal)."""
    a, r = sp.Matrix(axis), sp.Matrix(rel)
    return sp.ImmutableMatrix(epsilon * a.cross(r) + omega**2 * a.cross(a.cross(r)))


def carried(origin, R, dR, ddR, rel) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
    """A motion ``rel`` (position, velocity, acceleration in a moving frame) superposed on the
    frame's own motion: the frame's origin ``origin`` (position, velocity, acceleration) and
    orientation ``R`` with its derivatives ``dR``, ``ddR``:

    r = O + R rho,  v = v_O + R' rho + R rho',  a = a_O + R'' rho + 2 R' rho' + R rho''
    (transport, relative and Coriolis parts).
    """
    (o, vo, ao), (rho, v, a) = origin, rel
    return (sp.ImmutableMatrix(o + R * rho),
            sp.ImmutableMatrix(vo + dR * rho + R * v),
            sp.ImmutableMatrix(ao + ddR * rho + 2 * dR * v + R * a))
