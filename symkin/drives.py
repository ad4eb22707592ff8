"""Input drives: how a known link turns in time.

A drive gives the angle its link has turned since t = 0 as a closed form in t; its speed
and acceleration follow by differentiation.  Any law of t a user gives is a drive too.

    >>> import sympy as sp
    >>> from symkin import drives, symbols as S
    >>> drives.ConstantSpeed(3).angle(S.t)
    3*t
    >>> drives.SpeedLaw(S.t**2).angle(S.t)
    t**3/3
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import sympy as sp

from . import symbols as S
from .errors import InputError

__all__ = ["Drive", "ConstantSpeed", "AngleLaw", "SpeedLaw", "as_drive"]


class Drive(ABC):
    """Base class: the angle turned since t = 0, its speed and its acceleration."""

    @abstractmethod
    def angle(self, t: sp.Symbol) -> sp.Expr:
        """Angle turned since t = 0 (zero at t = 0)."""

    def speed(self, t: sp.Symbol) -> sp.Expr:
        """Angular velocity: d angle / dt."""
        return sp.diff(self.angle(t), t)

    def acceleration(self, t: sp.Symbol) -> sp.Expr:
        """Angular acceleration: d^2 angle / dt^2."""
        return sp.diff(self.angle(t), t, 2)


def _expr(value: Any, what: str) -> sp.Expr:
    if isinstance(value, str):
        from .parsing import parse_expression

        return parse_expression(value, names=("t",), what=what)
    if isinstance(value, bool):
        raise InputError(f"{what} must be a number or an expression, got {value!r}")
    try:
        expr = sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError):
        raise InputError(f"{what} must be a number or an expression, got {value!r}") from None
    if not isinstance(expr, sp.Expr):
        raise InputError(f"{what} must be a scalar expression, got {value!r}")
    if expr.is_number and (expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or expr.is_extended_real is False):
        raise InputError(f"{what} must be finite and real, got {value!r}")
    return expr


@dataclass(frozen=True)
class ConstantSpeed(Drive):
    """Turning at constant angular velocity ``omega``."""

    omega: sp.Expr

    def __post_init__(self) -> None:
        object.__setattr__(self, "omega", _expr(self.omega, "constant speed"))
        if S.t in self.omega.free_symbols:
            raise InputError("a constant speed cannot depend on t; use SpeedLaw for a speed that varies")

    def angle(self, t: sp.Symbol) -> sp.Expr:
        return self.omega * t


@dataclass(frozen=True)
class AngleLaw(Drive):
    """A given rotation law theta(t); the angle turned is theta(t) - theta(0).

    ``law`` is written in :data:`symkin.symbols.t`.
    """

    law: sp.Expr

    def __post_init__(self) -> None:
        object.__setattr__(self, "law", _expr(self.law, "angle law"))

    def angle(self, t: sp.Symbol) -> sp.Expr:
        law = self.law.subs(S.t, t)
        return law - law.subs(t, 0)


@dataclass(frozen=True)
class SpeedLaw(Drive):
    """A given angular velocity omega(t); the angle is its integral from 0 to t."""

    law: sp.Expr

    def __post_init__(self) -> None:
        object.__setattr__(self, "law", _expr(self.law, "speed law"))

    def angle(self, t: sp.Symbol) -> sp.Expr:
        tau = sp.Dummy("tau", real=True)
        integral = sp.integrate(self.law.subs(S.t, tau), (tau, 0, t))
        return integral

    def speed(self, t: sp.Symbol) -> sp.Expr:
        return self.law.subs(S.t, t)


def as_drive(value: Any, what: str = "drive") -> Drive:
    """A drive from a Drive, or a speed: a number, an expression in t, or safe text.

    >>> as_drive(0)
    ConstantSpeed(omega=0)
    """
    if isinstance(value, Drive):
        return value
    expr = _expr(value, what)
    return SpeedLaw(expr) if S.t in expr.free_symbols else ConstantSpeed(expr)
