"""Plane motion of a rigid link as the superposition of its pole's motion and a rotation.

These are the 2009 paper's equations (4)-(6), the only kinematic primitives symkin uses.
Vectors are 2 x 1 SymPy matrices; (a, b) are Lagrange (initial) coordinates, (x, y)
Euler (current) coordinates, ``dphi`` the link's rotation since t = 0.

    >>> import sympy as sp
    >>> from symkin.superposition import vec, velocity
    >>> w, r = sp.symbols("omega r")
    >>> velocity(vec(0, 0), w, vec(0, r), vec(0, 0)).T  # a point at (0, r) on a link turning about O
    Matrix([[-omega*r, 0]])
"""

from __future__ import annotations

import sympy as sp

__all__ = ["vec", "rotation", "position", "velocity", "acceleration"]


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
