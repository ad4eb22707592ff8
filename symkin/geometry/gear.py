"""Involute spur gears of the ISO 53 basic rack: one gear's diameters, tooth thickness and undercut.

A gear is cut by the basic rack of ISO 53 (profile A by default: pressure angle 20 degrees,
addendum ``h_a* = 1``, dedendum ``h_f* = 1.25``, root fillet radius ``rho_f* = 0.38``, all
times the module), shifted by ``x m`` away from the gear's axis (ISO 21771).  Lengths are in
millimetres (the module, ISO 54); every value is exact (SymPy) as far as the formulas are:
diameters and the reference thickness are rational multiples of the module and of
``cos``/``tan`` of the pressure angle; the tip thickness holds an ``acos``.

External gear (ISO 21771, the formulas typed in ``tests/geometry/test_gear.py``)::

    d = m z,  d_b = d cos(alpha),  d_a = d + 2 m (h_a* + x),  d_f = d - 2 m (h_f* - x)
    s = m (pi/2 + 2 x tan(alpha)),  s_y = d_y (s/d + inv(alpha) - inv(alpha_y)),  cos(alpha_y) = d_b/d_y

Internal gear (the same rack, its teeth the spaces of an external gear; ``x > 0`` moves the
profile away from the axis, as for an external gear)::

    d_a = d - 2 m (h_a* - x),  d_f = d + 2 m (h_f* + x),  s = m (pi/2 - 2 x tan(alpha)),
    s_y = d_y (s/d - inv(alpha) + inv(alpha_y))

    >>> g = gear_geometry(12, 3)
    >>> g.tip_diameter, g.root_diameter
    (42, 57/2)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from symkin.errors import InputError
from symkin.values import as_integer, as_rational

__all__ = ["ToothForm", "GearGeometry", "gear_geometry", "involute", "THIN_TIP"]

#: A tip thinner than this many modules is reported (0.2 m, the usual least tip land of a
#: through-hardened gear; 0: a pointed tip).
THIN_TIP = sp.Rational(1, 5)


def involute(angle: Any) -> sp.Expr:
    """``inv(a) = tan(a) - a``, exact.

    >>> involute(sp.pi / 9)
    -pi/9 + tan(pi/9)
    """
    return sp.tan(angle) - angle


def _coefficient(value: Any, what: str, *, positive: bool = True) -> sp.Rational:
    number = as_rational(value, what=what)
    if positive and number <= 0:
        raise InputError(f"{what} must be positive, got {value!r}")
    return number


@dataclass(frozen=True)
class ToothForm:
    """The basic rack a gear is cut with and the gear's profile shift (ISO 53, ISO 21771).

    Parameters
    ----------
    shift : number
        Profile shift coefficient ``x`` (times the module; positive: away from the axis).
    addendum : number
        ``h_a*``, the addendum coefficient (1).
    dedendum : number
        ``h_f*``, the dedendum coefficient (1.25): the rack's addendum.
    pressure_angle : number
        In degrees (20).
    fillet : number
        ``rho_f*``, the tip radius of the generating rack (0.38, ISO 53 profile A), which cuts
        the trochoidal root fillet.

    >>> ToothForm(shift=0.25).shift
    1/4
    """

    shift: Any = 0
    addendum: Any = 1
    dedendum: Any = sp.Rational(5, 4)
    pressure_angle: Any = 20
    fillet: Any = sp.Rational(19, 50)

    def __post_init__(self) -> None:
        object.__setattr__(self, "shift", _coefficient(self.shift, "the profile shift coefficient", positive=False))
        if abs(self.shift) > 5:
            raise InputError(f"the profile shift coefficient is {self.shift}; it lies within -5 and 5 (usually -1 to 1)")
        object.__setattr__(self, "addendum", _coefficient(self.addendum, "the addendum coefficient h_a*"))
        object.__setattr__(self, "dedendum", _coefficient(self.dedendum, "the dedendum coefficient h_f*"))
        object.__setattr__(self, "fillet", _coefficient(self.fillet, "the root fillet coefficient rho_f*", positive=False))
        if self.fillet < 0:
            raise InputError(f"the root fillet coefficient rho_f* must be 0 or more, got {self.fillet}")
        angle = _coefficient(self.pressure_angle, "the pressure angle (degrees)")
        if not 5 <= angle <= 45:
            raise InputError(f"the pressure angle is {angle} degrees; give one from 5 to 45 (usually 20)")
        object.__setattr__(self, "pressure_angle", angle)
        if self.fillet * (1 - sp.sin(self.alpha)) >= self.dedendum:
            raise InputError(f"the root fillet rho_f* = {self.fillet} is too large for the dedendum h_f* = "
                             f"{self.dedendum}; give rho_f* <= h_f* / (1 - sin alpha)")

    @property
    def alpha(self) -> sp.Expr:
        """The pressure angle in radians, exact."""
        return sp.pi * self.pressure_angle / 180

    @property
    def rack_flank_depth(self) -> sp.Expr:
        """``h_f* - rho_f* (1 - sin alpha)``: how deep below the rack's datum line its straight flank
        reaches (times the module), where its tip fillet begins; the undercut limit uses it."""
        return self.dedendum - self.fillet * (1 - sp.sin(self.alpha))


@dataclass(frozen=True)
class GearGeometry:
    """One gear's geometry (lengths in mm, exact); see the module docstring for the formulas."""

    teeth: sp.Integer
    module: sp.Expr
    form: ToothForm
    internal: bool = False
    #: A tip diameter other than the rack's (a tip turned down to keep the clearance); None: the formula's.
    tip: Any = None
    reference_diameter: sp.Expr = field(init=False)
    base_diameter: sp.Expr = field(init=False)
    tip_diameter: sp.Expr = field(init=False)
    root_diameter: sp.Expr = field(init=False)
    reference_thickness: sp.Expr = field(init=False)

    def __post_init__(self) -> None:
        m, z, f = self.module, self.teeth, self.form
        d = m * z
        sign = -1 if self.internal else 1
        object.__setattr__(self, "reference_diameter", d)
        object.__setattr__(self, "base_diameter", d * sp.cos(f.alpha))
        tip = d + sign * 2 * m * (f.addendum + sign * f.shift) if self.tip is None else as_rational(self.tip, what="the tip diameter (mm)")
        object.__setattr__(self, "tip_diameter", tip)
        object.__setattr__(self, "root_diameter", d - sign * 2 * m * (f.dedendum - sign * f.shift))
        object.__setattr__(self, "reference_thickness", m * (sp.pi / 2 + sign * 2 * f.shift * sp.tan(f.alpha)))

    @property
    def shift(self) -> sp.Rational:
        """The profile shift coefficient x."""
        return self.form.shift

    @property
    def pitch(self) -> sp.Expr:
        """The base pitch ``p_b = pi m cos(alpha)``."""
        return sp.pi * self.module * sp.cos(self.form.alpha)

    def thickness_at(self, diameter: Any) -> sp.Expr:
        """Tooth thickness (arc) on the circle of ``diameter`` (on or outside the base circle).

        >>> g = gear_geometry(20, 2)
        >>> g.thickness_at(g.reference_diameter) == g.reference_thickness
        True
        """
        dy = sp.sympify(diameter)
        alpha_y = sp.acos(self.base_diameter / dy)
        sign = -1 if self.internal else 1
        return dy * (self.reference_thickness / self.reference_diameter
                     + sign * (involute(self.form.alpha) - involute(alpha_y)))

    @property
    def tip_thickness(self) -> sp.Expr | None:
        """The tooth thickness on the tip circle (None for an internal gear whose tip lies inside its base circle)."""
        if self.tip_inside_base:
            return None
        return self.thickness_at(self.tip_diameter)

    @property
    def tip_inside_base(self) -> bool:
        """True for an internal gear whose tip circle lies inside its base circle (no involute there)."""
        return bool(self.tip_diameter < self.base_diameter)

    @property
    def pointed(self) -> bool:
        """True when the tooth comes to a point at or below the tip circle."""
        s = self.tip_thickness
        return s is not None and bool(s <= 0)

    @property
    def thin_tip(self) -> bool:
        """True when the tip land is thinner than :data:`THIN_TIP` modules (pointed tips included)."""
        s = self.tip_thickness
        return s is not None and bool(s < THIN_TIP * self.module)

    @property
    def minimum_shift(self) -> sp.Expr | None:
        """The least profile shift that cuts no undercut with the rack (external gears; None for internal).

        ``x_min = h_a0* - z sin^2(alpha) / 2`` with ``h_a0* = h_f* - rho_f* (1 - sin alpha)`` the
        depth of the rack's straight flank: the generating flank must not pass the
        interference point, where the line of action touches the base circle.
        """
        if self.internal:
            return None
        return self.form.rack_flank_depth - self.teeth * sp.sin(self.form.alpha) ** 2 / 2

    @property
    def undercut(self) -> bool:
        """True when the rack undercuts the flank (``x < x_min``); False for internal gears."""
        x_min = self.minimum_shift
        return x_min is not None and bool(self.shift < x_min)


def gear_geometry(teeth: Any, module: Any, form: ToothForm | None = None, *, internal: bool = False,
                  tip_diameter: Any = None) -> GearGeometry:
    """The geometry of a gear of ``teeth`` teeth and ``module`` (mm) cut with ``form`` (:class:`ToothForm`);
    ``tip_diameter`` (mm) replaces the formula's (a tip turned down).

    >>> gear_geometry(20, 2, ToothForm(shift=0.5)).tip_diameter
    46
    """
    z = as_integer(teeth, what="the tooth number")
    if z < 3:
        raise InputError(f"a gear has at least 3 teeth, got {z}")
    m = as_rational(module, what="the module (mm)")
    if m <= 0:
        raise InputError(f"the module (mm) must be positive, got {module!r}")
    form = ToothForm() if form is None else form
    g = GearGeometry(sp.Integer(z), m, form, internal=bool(internal), tip=tip_diameter)
    if tip_diameter is not None and (g.tip_diameter <= 0 or (g.tip_diameter >= g.root_diameter) != (not internal)):
        raise InputError(f"the tip diameter {g.tip_diameter} mm lies on the wrong side of the root circle "
                         f"({g.root_diameter} mm); give one {'inside' if internal else 'outside'} it")
    if g.root_diameter <= 0:
        raise InputError(f"a gear of {z} teeth with shift {form.shift} has no root circle (root diameter "
                         f"{g.root_diameter} mm); give more teeth or a larger shift")
    return g
