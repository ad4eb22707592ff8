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

from symkin import symbols as S
from symkin.errors import InputError, UnsupportedError
from symkin.values import as_expr, sign_of

__all__ = ["Drive", "ConstantSpeed", "AngleLaw", "SpeedLaw", "EllipticalGears", "as_drive"]


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

    def time_of_angle(self, angle: Any) -> sp.Expr:
        """The time at which the link has turned ``angle`` (the inverse of :meth:`angle`).

        Drives with a closed-form inverse override this; others raise
        :class:`~symkin.errors.UnsupportedError` (invert them numerically).
        """
        raise UnsupportedError(f"{type(self).__name__} has no closed-form inverse; find the time numerically")




def _as_expr(value: Any, what: str, unit: str | None = None) -> sp.Expr:
    return as_expr(value, what=what, unit=unit)


@dataclass(frozen=True)
class ConstantSpeed(Drive):
    """Turning at constant angular velocity ``omega``."""

    omega: sp.Expr

    def __post_init__(self) -> None:
        object.__setattr__(self, "omega", _as_expr(self.omega, "constant speed", "rad/s"))
        if S.t in self.omega.free_symbols:
            raise InputError("a constant speed cannot depend on t; use SpeedLaw for a speed that varies")

    def angle(self, t: sp.Symbol) -> sp.Expr:
        """The turned angle ``omega t`` at time ``t``.

        >>> from symkin import symbols as S
        >>> ConstantSpeed(2).angle(S.t)
        2*t
        """
        return self.omega * t

    def time_of_angle(self, angle: Any) -> sp.Expr:
        """``angle / omega``.

        >>> ConstantSpeed(2).time_of_angle(sp.pi)
        pi/2
        """
        if self.omega == 0:
            raise InputError("a link standing still never turns; give a non-zero speed")
        return _as_expr(angle, "angle", "rad") / self.omega


@dataclass(frozen=True)
class AngleLaw(Drive):
    """A given rotation law theta(t); the angle turned is theta(t) - theta(0).

    ``law`` is written in :data:`symkin.symbols.t`.
    """

    law: sp.Expr

    def __post_init__(self) -> None:
        object.__setattr__(self, "law", _as_expr(self.law, "angle law", "rad"))

    def angle(self, t: sp.Symbol) -> sp.Expr:
        """The angle law at time ``t``, shifted so that the angle is 0 at t = 0."""
        law = self.law.subs(S.t, t)
        return law - law.subs(t, 0)


@dataclass(frozen=True)
class SpeedLaw(Drive):
    """A given angular velocity omega(t); the angle is its integral from 0 to t."""

    law: sp.Expr

    def __post_init__(self) -> None:
        object.__setattr__(self, "law", _as_expr(self.law, "speed law", "rad/s"))

    def angle(self, t: sp.Symbol) -> sp.Expr:
        """The integral of the speed law from 0 to ``t``.

        >>> from symkin import symbols as S
        >>> SpeedLaw(2 * S.t).angle(S.t)
        t**2
        """
        tau = sp.Dummy("tau", real=True)
        integral = sp.integrate(self.law.subs(S.t, tau), (tau, 0, t))
        return integral

    def speed(self, t: sp.Symbol) -> sp.Expr:
        """The speed law at time ``t``."""
        return self.law.subs(S.t, t)


def _positive(value: Any, what: str) -> sp.Expr:
    expr = _as_expr(value, what)
    if expr.is_number and not expr.is_positive:
        raise InputError(f"{what} must be positive, got {value}")
    return expr


@dataclass(frozen=True)
class EllipticalGears(Drive):
    """The driven gear of a pair of identical elliptical gears, the driver at constant speed.

    Each gear's pitch curve, polar about its centre of rotation, is the order-``m``
    ellipse ``r(phi) = a (1 - e^2) / (1 - e cos(m phi))`` (``m = 1``: an ellipse turning
    about a focus); the centres are ``2 a`` apart, so the two radii at the pitch point
    add up to ``2 a``.  The driver turns at ``omega``; at t = 0 its longest radius
    ``a (1 + e)`` is at the pitch point, so the driven gear starts at its fastest.

    Parameters
    ----------
    omega : positive number or expression
        Driver speed (rad/s).
    eccentricity : number in [0, 1) or expression
        ``e``; 0 gives two circles (the driven gear turns at ``omega``).
    order : positive whole number or expression
        ``m``; the pitch curve closes for whole numbers only (another number is refused).

    Notes
    -----
    Speed.  Rolling without slip at the pitch point: ``omega r(alpha) = omega_out (2a - r(alpha))``
    with ``alpha = omega t``; :meth:`ratio` and :meth:`speed` are derived from the pitch curve.

    Angle.  With ``u = m omega t`` the speed is ``omega P(u)``, ``P`` the Poisson kernel
    ``(1 - e^2) / (1 - 2 e cos u + e^2) = 1 + 2 sum_n e^n cos(n u)``.  Term by term,
    ``int_0^u P = u + 2 sum_n e^n sin(n u) / n = u + 2 arg(1 / (1 - e e^{iu}))``, and since
    ``1 - e cos u > 0`` for ``e < 1`` that argument is ``atan(e sin u / (1 - e cos u))``
    with no branch cut: the angle is continuous for every t.  (The textbook form
    ``(2/m) atan(((1+e)/(1-e)) tan(u/2))`` is the same function on ``|u| < pi`` only; it
    falls behind by ``2 pi/m`` at each odd multiple of ``pi``.)

    >>> import sympy as sp
    >>> from symkin import symbols as S
    >>> d = EllipticalGears(1, sp.Rational(1, 2), 2)
    >>> d.speed(S.t)
    3/(5 - 4*cos(2*t))
    >>> d.angle(S.t)
    t + atan(sin(2*t)/(2 - cos(2*t)))
    >>> sp.simplify(d.angle(S.t).diff(S.t) - d.speed(S.t))
    0
    """

    omega: sp.Expr
    eccentricity: sp.Expr
    order: sp.Expr = sp.Integer(1)

    def __post_init__(self) -> None:
        object.__setattr__(self, "omega", _positive(self.omega, "driver speed of the elliptical gears"))
        e = _as_expr(self.eccentricity, "eccentricity")
        # signs to many digits (sign_of): SymPy's e < 1 is undecided for sqrt(1 - 10**-300) (a TypeError)
        if e.is_number and not (sign_of(e, what="the eccentricity") in (0, 1)
                                and sign_of(1 - e, what="the eccentricity") == 1):
            raise InputError(f"the eccentricity must lie in [0, 1), got {self.eccentricity}; 0 gives circular gears")
        object.__setattr__(self, "eccentricity", e)
        object.__setattr__(self, "order", _positive(self.order, "order of the elliptical gears"))
        m = self.order
        if m.is_number and not (m.is_Integer or (m.is_Float and float(m).is_integer())):  # (a float 2.0 is whole)
            raise InputError(f"the order of elliptical gears is a whole number (only then does the pitch curve close), "
                             f"got {self.order}")
        for name in ("omega", "eccentricity", "order"):
            if S.t in getattr(self, name).free_symbols:
                raise InputError(f"the {name} of elliptical gears cannot depend on t")

    def pitch_radius(self, phi: Any, semi_major: Any = 1) -> sp.Expr:
        """Radius of the pitch curve at polar angle ``phi`` (from the longest radius)."""
        e, m = self.eccentricity, self.order
        return semi_major * (1 - e**2) / (1 - e * sp.cos(m * phi))

    def ratio(self, alpha: Any) -> sp.Expr:
        """Transmission ratio omega_in / omega_out at driver angle ``alpha``.

        >>> EllipticalGears(1, 0).ratio(sp.Symbol("alpha"))
        1
        """
        driver, driven = self._radii(alpha)
        return driven / driver

    def _radii(self, alpha: Any) -> tuple[sp.Expr, sp.Expr]:
        # the radii at the pitch point, over a common denominator: r and 2a - r (a = 1)
        numerator, denominator = sp.fraction(self.pitch_radius(alpha))
        return numerator, sp.expand(2 * denominator - numerator)

    def speed(self, t: sp.Symbol) -> sp.Expr:
        """The driven gear's angular velocity at time ``t``: the input speed times the ratio of the gears' instantaneous radii."""
        driver, driven = self._radii(self.omega * t)
        return self.omega * driver / driven

    def acceleration(self, t: sp.Symbol) -> sp.Expr:
        """The driven gear's angular acceleration at time ``t`` (the derivative of :meth:`speed`)."""
        return sp.diff(self.speed(t), t)

    def angle(self, t: sp.Symbol) -> sp.Expr:
        """The driven gear's angle at time ``t``, in closed form without a branch jump (continuous in ``t``)."""
        e, m, u = self.eccentricity, self.order, self.order * self.omega * t
        return self.omega * t + 2 / m * sp.atan(sp.together(e * sp.sin(u) / (1 - e * sp.cos(u))))

    def time_of_angle(self, angle: Any) -> sp.Expr:
        """The time at which the driven gear has turned ``angle`` (continuous, no branch).

        The inverse pair runs the same law with ``e -> -e``: the driven gear's longest
        radius meets the driver's shortest.

        >>> d = EllipticalGears(2, sp.Rational(1, 3), 1)
        >>> d.time_of_angle(2 * sp.pi)
        pi
        """
        e, m = self.eccentricity, self.order
        psi = _as_expr(angle, "angle", "rad")
        v = m * psi
        return (psi - 2 / m * sp.atan(sp.together(e * sp.sin(v) / (1 + e * sp.cos(v))))) / self.omega


def as_drive(value: Any, what: str = "drive") -> Drive:
    """A drive from a Drive, or a speed: a number (rad/s), an expression in t, or a pint
    quantity (converted to rad/s).

    >>> import pint
    >>> as_drive(0)
    ConstantSpeed(omega=0)
    >>> as_drive(300 * pint.get_application_registry().rpm)
    ConstantSpeed(omega=10*pi)
    """
    if isinstance(value, Drive):
        return value
    expr = _as_expr(value, what, "rad/s")
    return SpeedLaw(expr) if S.t in expr.free_symbols else ConstantSpeed(expr)
