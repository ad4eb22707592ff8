"""Helical cylindrical gears: mesh geometry, and helical gears for the model.

A helical gear of ``z`` teeth, normal module ``m_n`` and helix angle ``beta`` (on the
reference cylinder) has the transverse module ``m_n / cos(beta)`` and reference pitch
radius ``m_n z / (2 cos(beta))``.  Its transverse pressure angle follows from the normal
one, ``tan(alpha_t) = tan(alpha_n) / cos(beta)``; profile shift moves the working
transverse pressure angle of a mesh to ``alpha_tw`` (``inv(alpha_tw) = inv(alpha_t) +
2 x_sum tan(alpha_n) / z_sum``) and each working pitch radius to
``r cos(alpha_t) / cos(alpha_tw)``.  The kinematics needs only the working pitch
radii, so a helical gear enters the model as a plain :class:`~symkin.model.Gear`
(:func:`helical_gear`); the model itself is unchanged.

The functions work on SymPy expressions (for derivations) and on floats (for design):

    >>> import math, sympy as sp
    >>> round(math.degrees(transverse_pressure_angle(math.radians(20), math.radians(15))), 6)
    20.646896
    >>> beta = sp.Symbol("beta", positive=True)
    >>> pitch_radius(20, 2, beta)
    20/cos(beta)

:class:`HelicalMesh` holds the numeric geometry of one mesh, :class:`HelicalTrain` a
two-row planetary train with a stepped planet whose rims 2 and 3 are helical.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import sympy as sp

from symkin.errors import ModelError
from symkin.model import Gear
from symkin.schemes import TWO_ROW
from symkin.values import as_expr, as_float, as_integer

__all__ = [
    "RIGHT",
    "LEFT",
    "hand_name",
    "transverse_pressure_angle",
    "pitch_radius",
    "working_pitch_radius",
    "base_helix_angle",
    "lead",
    "involute",
    "inverse_involute",
    "working_pressure_angle",
    "helical_gear",
    "HelicalMesh",
    "SCHEME_MESHES",
]

#: Helix hands: +1 right-handed (a right-hand screw), -1 left-handed.
RIGHT, LEFT = 1, -1

#: For each two-row scheme: is the central gear of mesh 1-2, and of mesh 3-4, internal?
#: (the schemes' own table, :data:`symkin.schemes.TWO_ROW`)
SCHEME_MESHES = TWO_ROW

DEFAULT_PRESSURE_ANGLE = math.radians(20)


def hand_name(hand: int) -> str:
    """'right' for +1, 'left' for -1.

    >>> hand_name(-1)
    'left'
    """
    if hand not in (RIGHT, LEFT):
        raise ModelError(f"a helix hand is +1 (right) or -1 (left), got {hand!r}")
    return "right" if hand == RIGHT else "left"


def _is_sym(*values: Any) -> bool:
    """Symbolic work when any value is a SymPy object; every value must be a finite real number or a
    SymPy expression (a string would be parsed as Python by SymPy's functions)."""
    symbolic = any(isinstance(v, sp.Basic) for v in values)
    for v in values:
        if symbolic:
            expr = _expr(v, "helical gear geometry")
            bad = expr.is_number and (expr.is_finite is False or expr.is_extended_real is False)
        else:
            try:
                bad = isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(float(v))
            except OverflowError:
                bad = True
        if bad:
            raise ModelError(f"helical gear geometry takes finite real numbers or SymPy expressions, got {v!r}")
    return symbolic


def _expr(value: Any, what: str) -> sp.Expr:
    """A SymPy expression from a number or expression, never by parsing a string."""
    return as_expr(value, what=what, finite=False, error=ModelError)


def transverse_pressure_angle(alpha_n: Any, beta: Any) -> Any:
    """Transverse pressure angle: ``tan(alpha_t) = tan(alpha_n) / cos(beta)`` (radians).

    >>> transverse_pressure_angle(sp.Symbol("alpha_n"), 0)
    alpha_n
    """
    if _is_sym(alpha_n, beta):
        if _expr(beta, "the helix angle") == 0:
            return _expr(alpha_n, "the normal pressure angle")
        return sp.atan(sp.tan(alpha_n) / sp.cos(beta))
    return math.atan(math.tan(alpha_n) / math.cos(beta))


def pitch_radius(teeth: Any, normal_module: Any, beta: Any) -> Any:
    """Reference pitch radius ``m_n z / (2 cos(beta))``.

    >>> pitch_radius(20, 2, 0.0)
    20.0
    """
    if _is_sym(teeth, normal_module, beta):
        return _expr(normal_module, "the normal module") * teeth / (2 * sp.cos(beta))
    return float(normal_module) * teeth / (2 * math.cos(beta))


def working_pitch_radius(teeth: Any, normal_module: Any, beta: Any, alpha_t: Any, alpha_tw: Any) -> Any:
    """Working pitch radius ``m_n z cos(alpha_t) / (2 cos(beta) cos(alpha_tw))``.

    >>> a_t, a_tw = sp.symbols("alpha_t alpha_tw", positive=True)
    >>> working_pitch_radius(20, 2, 0, a_t, a_tw)
    20*cos(alpha_t)/cos(alpha_tw)
    """
    if _is_sym(teeth, normal_module, beta, alpha_t, alpha_tw):
        r = _expr(normal_module, "the normal module") * teeth / (2 * sp.cos(beta))
        return r * sp.cos(alpha_t) / sp.cos(alpha_tw)
    return pitch_radius(teeth, normal_module, beta) * math.cos(alpha_t) / math.cos(alpha_tw)


def base_helix_angle(beta: Any, alpha_t: Any) -> Any:
    """Helix angle on the base cylinder: ``tan(beta_b) = tan(beta) cos(alpha_t)``.

    >>> b, a_n = math.radians(15), math.radians(20)
    >>> beta_b = base_helix_angle(b, transverse_pressure_angle(a_n, b))
    >>> abs(math.sin(beta_b) - math.sin(b) * math.cos(a_n)) < 1e-15   # the usual identity
    True
    """
    if _is_sym(beta, alpha_t):
        return sp.atan(sp.tan(beta) * sp.cos(alpha_t))
    return math.atan(math.tan(beta) * math.cos(alpha_t))


def lead(teeth: Any, normal_module: Any, beta: Any) -> Any:
    """Lead of the helix (axial advance per turn): ``pi m_n z / sin(beta)``.

    The same on every cylinder of one gear, so profile shift does not change it.

    >>> round(lead(20, 2, math.radians(30)), 9) == round(80 * math.pi, 9)
    True
    """
    if _is_sym(teeth, normal_module, beta):
        return sp.pi * _expr(normal_module, "the normal module") * teeth / sp.sin(beta)
    return math.pi * float(normal_module) * teeth / math.sin(beta)


def involute(angle: float) -> float:
    """The involute function ``tan(a) - a``.

    >>> round(involute(math.radians(20)), 9)
    0.014904384
    """
    return math.tan(angle) - angle


def inverse_involute(value: float) -> float:
    """The angle ``a`` in [0, pi/2) with ``tan(a) - a = value`` (Newton, to machine precision).

    >>> a = inverse_involute(involute(0.4))
    >>> abs(a - 0.4) < 1e-15
    True
    """
    if not math.isfinite(value) or value < 0:
        raise ModelError(f"the involute function takes values >= 0 only, got {value!r}; reduce the profile shift")
    if value == 0:
        return 0.0
    a = (3 * value) ** (1 / 3) if value < 0.5 else math.atan(value)  # inv(a) ~ a^3 / 3 near 0
    a = min(a, 1.5)
    for _ in range(100):
        step = (math.tan(a) - a - value) / math.tan(a) ** 2
        a_new = a - step
        if not 0 < a_new < math.pi / 2:
            a_new = (a + (0 if a_new <= 0 else math.pi / 2)) / 2
        if abs(a_new - a) <= 4e-16 * max(a, 1.0):
            return a_new
        a = a_new
    return a


def working_pressure_angle(
    teeth_sum: int, shift_sum: float, alpha_n: float, beta: float
) -> float:
    """Working transverse pressure angle of a mesh with profile shift.

    ``inv(alpha_tw) = inv(alpha_t) + 2 shift_sum tan(alpha_n) / teeth_sum``, where for an
    external mesh ``teeth_sum = z_a + z_b`` and ``shift_sum = x_a + x_b``, and for an internal
    mesh ``teeth_sum = z_ring - z_pinion`` and ``shift_sum = x_ring - x_pinion``.

    >>> a_t = transverse_pressure_angle(math.radians(20), 0.2)
    >>> working_pressure_angle(60, 0.0, math.radians(20), 0.2) == a_t
    True
    """
    alpha_t = transverse_pressure_angle(alpha_n, beta)
    if shift_sum == 0:
        return alpha_t
    if teeth_sum <= 0:
        raise ModelError(f"the tooth sum of a mesh must be positive, got {teeth_sum}")
    return inverse_involute(involute(alpha_t) + 2 * shift_sum * math.tan(alpha_n) / teeth_sum)


def helical_gear(
    name: str,
    teeth: Any,
    normal_module: Any,
    beta: Any,
    *,
    internal: bool = False,
    alpha_n: Any = None,
    alpha_t: Any = None,
    alpha_tw: Any = None,
) -> Gear:
    """A :class:`~symkin.model.Gear` whose radius is the helical gear's working pitch radius.

    ``alpha_tw`` is the working transverse pressure angle of the mesh the gear works in
    (default: the transverse pressure angle, i.e. no profile shift, where the working pitch
    radius is the reference one).  ``alpha_t`` defaults to the transverse pressure angle
    of ``alpha_n`` (a symbol when not given).  Symbols are welcome: the derivations use them.

    >>> b = sp.Symbol("beta_12", positive=True)
    >>> helical_gear("2", 30, 2, b).radius
    30/cos(beta_12)
    """
    if alpha_tw is None:
        radius = pitch_radius(teeth, normal_module, beta)
    else:
        if alpha_t is None:
            a_n = sp.Symbol("alpha_n", positive=True) if alpha_n is None else alpha_n
            alpha_t = transverse_pressure_angle(a_n, beta)
        radius = working_pitch_radius(teeth, normal_module, beta, alpha_t, alpha_tw)
    return Gear(name, radius, teeth=teeth, internal=internal)


def _angle(value: Any, what: str, low: float, high: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ModelError(f"{what} must be a number of radians, got {value!r}") from None
    if not (math.isfinite(v) and low <= v < high):
        raise ModelError(
            f"{what} must lie in [{math.degrees(low):g}, {math.degrees(high):g}) degrees, got {math.degrees(v):g} degrees"
        )
    return v


@dataclass(frozen=True)
class HelicalMesh:
    """The numeric geometry of one helical mesh between an external gear and its mate.

    Parameters
    ----------
    teeth_external : int
        Teeth of the external gear (the planet rim, in a planetary train).
    teeth_mate : int
        Teeth of its mate (a central gear), internal when ``internal`` is True.
    normal_module : float
        Normal module m_n (mm).
    beta : float
        Helix angle on the reference cylinder, radians, in [0, 90 deg).
    internal : bool
        True when the mate is an internal (ring) gear.
    alpha_n : float
        Normal pressure angle, radians (default 20 degrees).
    shift_external, shift_mate : float
        Profile shift coefficients x (of the normal module).
    addendum : float
        Addendum coefficient h_a* (tip diameters for the neighbour condition).

    Examples
    --------
    >>> m = HelicalMesh(20, 40, 2.0, math.radians(10))
    >>> round(m.reference_centre_distance, 6) == round(60 / math.cos(math.radians(10)), 6)
    True
    >>> m.centre_distance == m.reference_centre_distance
    True
    """

    teeth_external: int
    teeth_mate: int
    normal_module: float
    beta: float
    internal: bool = False
    alpha_n: float = DEFAULT_PRESSURE_ANGLE
    shift_external: float = 0.0
    shift_mate: float = 0.0
    addendum: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "teeth_external", int(as_integer(self.teeth_external, what="teeth of the external gear", error=ModelError, minimum=1)))
        object.__setattr__(self, "teeth_mate", int(as_integer(self.teeth_mate, what="teeth of the mating gear", error=ModelError, minimum=1)))
        object.__setattr__(self, "normal_module", as_float(self.normal_module, what="the normal module", positive=True, error=ModelError))
        object.__setattr__(self, "beta", _angle(self.beta, "the helix angle", 0.0, math.pi / 2))
        object.__setattr__(self, "alpha_n", _angle(self.alpha_n, "the normal pressure angle", 1e-9, math.pi / 2))
        if not isinstance(self.internal, bool):
            raise ModelError(f"internal must be True or False, got {self.internal!r}")
        if self.internal and self.teeth_mate <= self.teeth_external:
            raise ModelError(
                f"an internal gear of {self.teeth_mate} teeth cannot hold a gear of {self.teeth_external} teeth; "
                "give the internal gear more teeth"
            )
        for name in ("shift_external", "shift_mate", "addendum"):
            v = float(getattr(self, name))
            if not math.isfinite(v):
                raise ModelError(f"{name.replace('_', ' ')} must be finite, got {v!r}")
            object.__setattr__(self, name, v)
        _ = self.alpha_tw  # a shift the involute cannot take is refused now, not later

    # ---- sums that differ for external and internal meshes
    @property
    def teeth_sum(self) -> int:
        """z_mate + z_external (external mesh) or z_ring - z_external (internal)."""
        return self.teeth_mate - self.teeth_external if self.internal else self.teeth_mate + self.teeth_external

    @property
    def shift_sum(self) -> float:
        """x_mate + x_external (external) or x_ring - x_external (internal)."""
        return self.shift_mate - self.shift_external if self.internal else self.shift_mate + self.shift_external

    # ---- angles
    @cached_property
    def alpha_t(self) -> float:
        """Transverse pressure angle (radians)."""
        return transverse_pressure_angle(self.alpha_n, self.beta)

    @cached_property
    def alpha_tw(self) -> float:
        """Working transverse pressure angle (radians)."""
        return working_pressure_angle(self.teeth_sum, self.shift_sum, self.alpha_n, self.beta)

    @cached_property
    def beta_base(self) -> float:
        """Helix angle on the base cylinders (radians)."""
        return base_helix_angle(self.beta, self.alpha_t)

    # ---- lengths
    @property
    def transverse_module(self) -> float:
        """The transverse module ``m_n / cos(beta)`` (mm)."""
        return self.normal_module / math.cos(self.beta)

    def pitch_radius(self, which: str) -> float:
        """Reference pitch radius of ``"external"`` or ``"mate"``."""
        return pitch_radius(self._teeth(which), self.normal_module, self.beta)

    def working_radius(self, which: str) -> float:
        """Working pitch radius of ``"external"`` or ``"mate"``."""
        return self.pitch_radius(which) * math.cos(self.alpha_t) / math.cos(self.alpha_tw)

    def base_radius(self, which: str) -> float:
        """Base circle radius of ``"external"`` or ``"mate"``."""
        return self.pitch_radius(which) * math.cos(self.alpha_t)

    def tip_radius(self, which: str) -> float:
        """Tip radius of an external gear, ``r + (h_a* + x) m_n`` (no tip shortening)."""
        shift = self.shift_external if which == "external" else self.shift_mate
        if which == "mate" and self.internal:
            return self.pitch_radius(which) - (self.addendum - shift) * self.normal_module
        return self.pitch_radius(which) + (self.addendum + shift) * self.normal_module

    def lead(self, which: str) -> float:
        """Lead of the helix of ``"external"`` or ``"mate"``."""
        return lead(self._teeth(which), self.normal_module, self.beta)

    @property
    def reference_centre_distance(self) -> float:
        """``m_n teeth_sum / (2 cos(beta))``."""
        return self.normal_module * self.teeth_sum / (2 * math.cos(self.beta))

    @property
    def centre_distance(self) -> float:
        """Working centre distance ``a cos(alpha_t) / cos(alpha_tw)``."""
        if self.alpha_tw == self.alpha_t:
            return self.reference_centre_distance
        return self.reference_centre_distance * math.cos(self.alpha_t) / math.cos(self.alpha_tw)

    def _teeth(self, which: str) -> int:
        if which == "external":
            return self.teeth_external
        if which == "mate":
            return self.teeth_mate
        raise ModelError(f"name a gear of the mesh as 'external' or 'mate', got {which!r}")
