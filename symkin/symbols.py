"""The symbols symkin's laws are written in, with the 2009 paper's names.

Each function returns the same SymPy symbol (same name, same assumptions) on every
call, so a user can build expressions that match the engine's:

    >>> from symkin import symbols as S
    >>> S.omega("H")
    omega_H
    >>> S.radius("1").is_positive
    True
"""

from __future__ import annotations

import sympy as sp

__all__ = ["t", "omega", "epsilon", "angle", "radius", "teeth", "module", "ratio_symbol"]

#: Time.
t = sp.Symbol("t", real=True)


def omega(link: str) -> sp.Symbol:
    """Angular velocity of a link relative to the mechanism frame (rad/s, CCW positive)."""
    return sp.Symbol(f"omega_{link}", real=True)


def epsilon(link: str) -> sp.Symbol:
    """Angular acceleration of a link relative to the mechanism frame."""
    return sp.Symbol(f"epsilon_{link}", real=True)


def angle(link: str) -> sp.Symbol:
    """Rotation angle of a link since t = 0 (the paper's Delta phi)."""
    return sp.Symbol(f"varphi_{link}", real=True)


def radius(gear: str) -> sp.Symbol:
    """Pitch radius of a gear."""
    return sp.Symbol(f"r_{gear}", positive=True)


def teeth(gear: str) -> sp.Symbol:
    """Tooth number of a gear."""
    return sp.Symbol(f"z_{gear}", positive=True, integer=True)


def module(name: str = "") -> sp.Symbol:
    """Gear module (pitch diameter per tooth)."""
    return sp.Symbol(f"m_{name}" if name else "m", positive=True)


def ratio_symbol(driver: str, driven: str, fixed: tuple[str, ...] = ()) -> sp.Symbol:
    """The paper's i_ab^(c): omega_a / omega_b with the links c fixed."""
    sup = "^{(" + ",".join(fixed) + ")}" if fixed else ""
    return sp.Symbol(f"i_{{{driver}{driven}}}{sup}", real=True)
