"""Two involute gears in mesh: working pressure angle, centre distance, contact ratio, interference.

The working pressure angle solves the involute equation (ISO 21771, external; internal: the
shift difference over the tooth difference, the internal gear second)::

    inv(alpha_w) = inv(alpha) + 2 tan(alpha) (x1 + x2) / (z1 + z2)      external
    inv(alpha_w) = inv(alpha) + 2 tan(alpha) (x2 - x1) / (z2 - z1)      internal (gear 2 internal)
    a_w = a cos(alpha) / cos(alpha_w),  a = m (z1 + z2) / 2  (internal: m (z2 - z1) / 2)

The inputs are exact; ``inv`` is inverted numerically (mpmath's Newton iteration at
:data:`DIGITS` significant digits, to a relative tolerance of ``10**-(DIGITS - 5)``); the
angle and what follows from it are SymPy Floats of that precision.  Given a working centre
distance instead, ``cos(alpha_w) = a cos(alpha) / a_w`` is exact and the shift sum it needs
is :func:`shift_sum_for`.

Transverse contact ratio (the path of contact over the base pitch)::

    eps = (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a_w sin(alpha_w)) / (pi m cos(alpha))   external
    eps = (sqrt(r_a1^2 - r_b1^2) - sqrt(r_a2^2 - r_b2^2) + a_w sin(alpha_w)) / (pi m cos(alpha))   internal

Interference, with ``alpha_a = acos(d_b / d_a)`` at each tip (KHK / SDP-SI, Elements of
Metric Gear Technology, eqs. 5-5 to 5-10; Niemann/Winter vol. 2 the same conditions):

- *involute*: a tip reaches past the partner's interference point (where the line of action
  touches its base circle); internal: ``z1/z2 >= 1 - tan(alpha_a2)/tan(alpha_w)``;
- *tip* (trochoid) interference of an internal mesh: ``theta1 z1/z2 + inv(alpha_w) -
  inv(alpha_a2) >= theta2``;
- *trimming* of an internal mesh (the pinion cannot be pulled out radially; assemble it
  axially, and a pinion cutter cannot cut the ring): ``theta1 + inv(alpha_a1) - inv(alpha_w)
  >= z2/z1 (theta2 + inv(alpha_a2) - inv(alpha_w))``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy as sp

from symkin.errors import InputError
from symkin.geometry.gear import GearGeometry, involute

__all__ = ["PairGeometry", "pair_geometry", "inverse_involute", "shift_sum_for", "DIGITS", "MIN_CONTACT_RATIO"]

#: Significant digits of the numeric inverse of the involute function.
DIGITS = 30
#: A contact ratio below this is reported (1.2: the usual least for a spur mesh to run smoothly).
MIN_CONTACT_RATIO = sp.Rational(6, 5)


def inverse_involute(value: Any) -> sp.Float:
    """The angle ``a`` in [0, pi/2) with ``tan(a) - a = value``, to :data:`DIGITS` digits.

    >>> a = inverse_involute(involute(sp.Rational(2, 5)))
    >>> abs(a - sp.Rational(2, 5)) < 1e-28
    True
    """
    v = sp.sympify(value)
    with mpmath.workdps(DIGITS + 10):
        target = mpmath.mpf(sp.N(v, DIGITS + 10))
        if target < 0:
            raise InputError(f"the involute function is never negative, got {float(target):.6g}: the profile shifts "
                             "are too negative for the tooth numbers; raise them")
        if target == 0:
            return sp.Float(0, DIGITS)
        start = mpmath.cbrt(3 * target) if target < 1 else mpmath.atan(target)  # inv(a) ~ a^3/3 near 0
        start = min(start, mpmath.mpf("1.5"))
        root = mpmath.findroot(lambda a: mpmath.tan(a) - a - target, start, tol=mpmath.mpf(10) ** (-2 * (DIGITS - 5)))
        return sp.Float(root, DIGITS)


def shift_sum_for(gear1: GearGeometry, gear2: GearGeometry, centre_distance: Any) -> sp.Expr:
    """The shift sum ``x1 + x2`` (internal: ``x2 - x1``) that makes two gears mesh without backlash at
    ``centre_distance`` (mm), exact.

    >>> from symkin.geometry.gear import gear_geometry
    >>> shift_sum_for(gear_geometry(20, 1), gear_geometry(40, 1), 30)
    0
    """
    a_w = sp.sympify(centre_distance)
    alpha = gear1.form.alpha
    a = _reference_distance(gear1, gear2)
    cos_w = a * sp.cos(alpha) / a_w
    if not cos_w < 1:
        raise InputError(f"gears of {gear1.teeth} and {gear2.teeth} teeth cannot mesh at {a_w} mm: the base circles "
                         f"would overlap; give a centre distance above {sp.N(a * sp.cos(alpha), 8)} mm")
    teeth = (gear2.teeth - gear1.teeth) if gear2.internal else (gear1.teeth + gear2.teeth)
    return sp.nsimplify(0) if a_w == a else (involute(sp.acos(cos_w)) - involute(alpha)) * teeth / (2 * sp.tan(alpha))


def _reference_distance(g1: GearGeometry, g2: GearGeometry) -> sp.Expr:
    return (g2.reference_diameter - g1.reference_diameter) / 2 if g2.internal else \
        (g1.reference_diameter + g2.reference_diameter) / 2


@dataclass(frozen=True)
class PairGeometry:
    """Two gears in mesh (gear 2 the internal one of an internal mesh); see the module docstring."""

    gear1: GearGeometry
    gear2: GearGeometry
    working_pressure_angle: sp.Expr
    centre_distance: sp.Expr

    @property
    def internal(self) -> bool:
        """True for an internal mesh."""
        return self.gear2.internal

    @property
    def reference_centre_distance(self) -> sp.Expr:
        """``m (z1 + z2) / 2``, internal ``m (z2 - z1) / 2``."""
        return _reference_distance(self.gear1, self.gear2)

    def _paths(self) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
        g1, g2 = self.gear1, self.gear2
        r1 = sp.sqrt((g1.tip_diameter / 2) ** 2 - (g1.base_diameter / 2) ** 2)
        r2 = sp.sqrt(sp.Max(0, (g2.tip_diameter / 2) ** 2 - (g2.base_diameter / 2) ** 2))
        return r1, r2, self.centre_distance * sp.sin(self.working_pressure_angle)

    @property
    def contact_ratio(self) -> sp.Expr:
        """The transverse contact ratio ``eps_alpha``."""
        r1, r2, line = self._paths()
        path = r1 - r2 + line if self.internal else r1 + r2 - line
        return sp.N(path / self.gear1.pitch, DIGITS)

    def problems(self, min_contact_ratio: Any = MIN_CONTACT_RATIO) -> list[str]:
        """What keeps this mesh from running: each problem one short sentence."""
        out = []
        g1, g2 = self.gear1, self.gear2
        eps = self.contact_ratio
        if eps < min_contact_ratio:
            out.append(f"contact ratio {float(eps):.3f} below {float(min_contact_ratio):g}")
        found = self.interferences()
        if "involute" in found:
            out.append("involute interference: the ring's tip reaches past the pinion's interference point (where "
                       "the line of action touches its base circle); raise the ring's shift or its tip diameter")
        if "tip" in found:
            out.append("tip interference (trochoid): the pinion's tip strikes the ring's teeth as it leaves the "
                       "mesh; give a larger tooth difference or ring shift")
        if "trimming" in found:
            out.append("trimming interference: the pinion cannot be taken out radially (assemble it axially; a "
                       "pinion cutter of these teeth cannot cut the ring)")
        for key, (tip, other) in (("involute 1", (g1, g2)), ("involute 2", (g2, g1))):
            if key in found:
                out.append(f"involute interference: the tip of the {tip.teeth}-tooth gear reaches past the interference "
                           f"point (on the base circle) of the {other.teeth}-tooth gear")
        # each problem once: two gears of one tooth number (a sun and its planet of 12) say the same sentence
        return list(dict.fromkeys(out))

    def interferences(self) -> tuple[str, ...]:
        """The interferences of this mesh (:func:`interferences`, at :data:`DIGITS` digits)."""
        g1, g2 = self.gear1, self.gear2
        values = [g1.base_diameter / 2, g2.base_diameter / 2, g1.tip_diameter / 2, g2.tip_diameter / 2,
                  self.centre_distance, self.working_pressure_angle]
        with mpmath.workdps(DIGITS):
            rb1, rb2, ra1, ra2, a, aw = (mpmath.mpf(str(sp.N(v, DIGITS + 5))) for v in values)
            return interferences(mpmath.mpf(int(g1.teeth)), mpmath.mpf(int(g2.teeth)), self.internal, rb1, rb2, ra1, ra2,
                                 a, aw, lib=mpmath)

    def _involute_ok(self) -> bool:
        return "involute" not in self.interferences()

    def _trochoid_ok(self) -> bool:
        return "tip" not in self.interferences()

    def _trimming_ok(self) -> bool:
        return "trimming" not in self.interferences()


def interferences(z1: Any, z2: Any, internal: bool, rb1: Any, rb2: Any, ra1: Any, ra2: Any, a: Any, aw: Any,
                  lib: Any = math) -> tuple[str, ...]:
    """The interferences of a mesh (gear 2 the internal one of an internal mesh) from its teeth, base and tip
    radii, working centre distance ``a`` and pressure angle ``aw`` (KHK / SDP-SI eqs. 5-5 to 5-10; see the
    module docstring): ``"involute 1"``/``"involute 2"`` (external: that gear's tip reaches past the other's
    interference point), ``"involute"``, ``"tip"`` (trochoid) and ``"trimming"`` (internal).

    ``lib`` is :mod:`math` (floats: fast, for a scan) or :mod:`mpmath` (every number an ``mpf``, at mpmath's
    working precision).

    >>> import math
    >>> rb = lambda z: z / 2 * math.cos(math.pi / 9)
    >>> interferences(18, 72, True, rb(18), rb(72), 10, 35, 27, math.pi / 9)
    ('involute',)
    """
    line = a * lib.sin(aw)
    if not internal:
        found = []
        for key, ra, rb in (("involute 1", ra1, rb1), ("involute 2", ra2, rb2)):
            if lib.sqrt(ra**2 - rb**2) - line > 0:
                found.append(key)
        return tuple(found)
    inv = lambda angle: lib.tan(angle) - angle  # noqa: E731
    a1, a2 = lib.acos(rb1 / ra1), lib.acos(min(1, rb2 / ra2))
    found = []
    if ra2 < rb2 or z1 / z2 - (1 - lib.tan(a2) / lib.tan(aw)) < 0:
        found.append("involute")
    theta1 = lib.acos(_clip((ra2**2 - ra1**2 - a**2) / (2 * a * ra1))) + inv(a1) - inv(aw)
    theta2 = lib.acos(_clip((a**2 + ra2**2 - ra1**2) / (2 * a * ra2)))
    if theta1 * z1 / z2 + inv(aw) - inv(a2) - theta2 < 0:
        found.append("tip")
    theta1 = lib.asin(lib.sqrt(_clip((1 - (lib.cos(a1) / lib.cos(a2)) ** 2) / (1 - (z1 / z2) ** 2), 0)))
    theta2 = lib.asin(lib.sqrt(_clip(((lib.cos(a2) / lib.cos(a1)) ** 2 - 1) / ((z2 / z1) ** 2 - 1), 0)))
    if theta1 + inv(a1) - inv(aw) - z2 / z1 * (theta2 + inv(a2) - inv(aw)) < 0:
        found.append("trimming")
    return tuple(found)


def _clip(value: Any, low: int = -1) -> Any:
    """``value`` within [low, 1]: a circle that misses another."""
    return max(low, min(1, value))


def pair_geometry(gear1: GearGeometry, gear2: GearGeometry, centre_distance: Any = None) -> PairGeometry:
    """Two gears in mesh: from their shifts (the involute equation), or at a given ``centre_distance`` (mm).

    ``gear2`` is the internal gear of an internal mesh.  The gears must share their module and
    pressure angle.

    >>> from symkin.geometry.gear import gear_geometry, ToothForm
    >>> p = pair_geometry(gear_geometry(20, 2), gear_geometry(40, 2))
    >>> p.centre_distance, round(float(p.contact_ratio), 3)
    (60, 1.635)
    """
    if gear1.internal:
        gear1, gear2 = gear2, gear1
    if gear1.internal:
        raise InputError("two internal gears cannot mesh; an internal gear meshes with an external one")
    if gear1.module != gear2.module:
        raise InputError(f"gears in mesh share their module, got {gear1.module} and {gear2.module} mm")
    if gear1.form.pressure_angle != gear2.form.pressure_angle:
        raise InputError(f"gears in mesh share their pressure angle, got {gear1.form.pressure_angle} and "
                         f"{gear2.form.pressure_angle} degrees")
    if gear2.internal and gear2.teeth <= gear1.teeth:
        raise InputError(f"an internal gear of {gear2.teeth} teeth cannot hold a gear of {gear1.teeth}; it needs more teeth")
    alpha = gear1.form.alpha
    a = _reference_distance(gear1, gear2)
    if centre_distance is not None:
        a_w = sp.nsimplify(centre_distance)
        shift_sum_for(gear1, gear2, a_w)  # the check that the base circles do not overlap
        return PairGeometry(gear1, gear2, sp.acos(a * sp.cos(alpha) / a_w), a_w)
    x_sum = (gear2.shift - gear1.shift) if gear2.internal else (gear1.shift + gear2.shift)
    if x_sum == 0:
        return PairGeometry(gear1, gear2, alpha, a)
    teeth = (gear2.teeth - gear1.teeth) if gear2.internal else (gear1.teeth + gear2.teeth)
    alpha_w = inverse_involute(involute(alpha) + 2 * sp.tan(alpha) * x_sum / teeth)
    return PairGeometry(gear1, gear2, alpha_w, sp.N(a * sp.cos(alpha) / sp.cos(alpha_w), DIGITS))
