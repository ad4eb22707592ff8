"""The Cardan-circle mechanism: a slider pinned to a planet rolling inside a ring.

Carrier H turns about O_H and carries planet 1, which rolls inside the fixed internal
gear 3 (:func:`symkin.schemes.cardan`).  Slider 2 is pinned to the planet at a point O
at distance ``l_1`` from the planet axis and runs in a guide through O_H at the angle
``theta_2``.  Names follow the 2018 paper: ``l_H`` the carrier length (the planet's arm,
``r_3 - r_1``), ``theta_H`` the carrier angle, ``theta_1`` the angle of O_1 -> O measured
from the carrier, ``s`` the slider's signed position along its guide.

Two routes give the pin's motion:

- the vector loop ``l_H e^{i theta_H} + l_1 e^{i(theta_H + theta_1)} = s e^{i theta_2}``
  (:func:`loop`, solved by :mod:`symkin.vectorloop`) with the planet's turn relative to
  the carrier taken from the engine's contact condition;
- superposition: the pin is a particle of the planet (:attr:`CardanSlider.pin`).

The pin stays on the guide for every carrier angle only under the conditions that
:func:`line_conditions` derives; otherwise its path is an ellipse, a line in another
direction, or a hypocycloid/hypotrochoid (:meth:`CardanSlider.path`).

    >>> import sympy as sp
    >>> from symkin import symbols as S
    >>> slider = CardanSlider.build(l, drive=S.omega("H"))
    >>> slider.displacement
    2*l*cos(omega_H*t)
    >>> slider.path().kind
    'line'
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
import sympy as sp

from symkin import schemes
from symkin import symbols as S
from symkin._util.budget import simplify_within
from symkin._util.jsonout import exact_json
from symkin.drives import AngleLaw, ConstantSpeed, Drive, EllipticalGears, as_drive
from symkin.errors import InputError, ModelError, UnsupportedError
from symkin.laws import Law
from symkin.model import Mechanism, as_length, as_teeth
from symkin.numeric import compile
from symkin.numeric.sampling import as_times, on_grid, time_grid
from symkin.values import (
    as_expr,
    as_rational,
    as_real,
    as_values,
    is_quantity,
    sign_of,
    substitute,
)
from symkin.vectorloop import LinkVector, VectorLoop, harmonics, solve_linear

__all__ = [
    "l",
    "l_H",
    "l_1",
    "s",
    "alpha",
    "theta_H",
    "theta_1",
    "theta_2",
    "theta_H0",
    "theta_10",
    "loop",
    "planet_turn_ratio",
    "LineConditions",
    "line_conditions",
    "Path",
    "StrokeTimes",
    "CardanSlider",
    "SliderTable",
]

#: Common length of carrier and crank when they are equal (the paper's l).
l = sp.Symbol("l", positive=True)
#: Carrier length (the planet's arm) and the pin's distance from the planet axis.
l_H, l_1 = sp.symbols("l_H l_1", positive=True)
#: Slider position along its guide (signed).
s = sp.Symbol("s", real=True)
#: Carrier turn since t = 0.
alpha = sp.Symbol("alpha", real=True)
#: Carrier angle, pin angle on the planet (from the carrier), guide angle.
theta_H, theta_1, theta_2 = sp.symbols("theta_H theta_1 theta_2", real=True)
#: Carrier angle and pin angle at t = 0.
theta_H0, theta_10 = sp.symbols("theta_H0 theta_10", real=True)


def loop() -> VectorLoop:
    """The loop O_H -> O_1 -> O = O_H -> O along the guide (the paper's eqs. 17-18).

    >>> loop().complex_equation()
    Eq(l_1*exp(I*(theta_1 + theta_H)) + l_H*exp(I*theta_H), s*exp(I*theta_2))
    """
    return VectorLoop(
        (LinkVector(l_H, theta_H, "carrier H"), LinkVector(l_1, theta_H + theta_1, "planet 1: O_1 -> O")),
        (LinkVector(s, theta_2, "slider 2"),),
    )


def planet_turn_ratio(mech: Mechanism) -> sp.Expr:
    """The planet's turn relative to the carrier per carrier turn, from the contact
    condition with the fixed ring (the engine's speed solution).

    >>> from symkin import schemes
    >>> planet_turn_ratio(schemes.cardan())
    -r_3/r_1
    """
    speeds = mech.speeds({"H": S.omega("H")})
    return sp.cancel((speeds["1"] - S.omega("H")) / S.omega("H"))


# --------------------------------------------------------------------------- conditions
@dataclass(frozen=True)
class LineConditions:
    """When the pin stays on the guide for every carrier angle, as derived.

    Attributes
    ----------
    deviation : sympy expression
        The pin's distance from the guide line as a function of the carrier turn
        ``alpha``, for any ratio (radii ``r_1``, ``r_3``), lengths and angles.
    frequencies : tuple of sympy expressions
        The harmonics e^{i nu alpha} the deviation is made of.
    ratio : sympy.Eq
        The ring radius for which the pin's harmonic can cancel the carrier's.  Like
        ``lengths`` and ``installation`` it is a condition (an equation the mechanism
        must satisfy), not a derived law, so it is a ``sympy.Eq`` and not a
        :class:`~symkin.laws.Law`.
    excluded : tuple of (sympy.Eq, str)
        Other coincidences of frequencies, and why the model refuses them.
    lengths, installation : sympy.Eq
        The amplitude and phase conditions; the installation angle holds modulo 2 pi.
    """

    deviation: sp.Expr
    frequencies: tuple[sp.Expr, ...]
    ratio: sp.Eq
    excluded: tuple[tuple[sp.Eq, str], ...]
    lengths: sp.Eq
    installation: sp.Eq

    def substitutions(self) -> dict[sp.Symbol, sp.Expr]:
        """All three conditions as substitutions (r_3, l_1 and theta_10)."""
        return {self.ratio.lhs: self.ratio.rhs, self.lengths.lhs: self.lengths.rhs, self.installation.lhs: self.installation.rhs}


def _vanishing_pair(coefficient: sp.Expr) -> tuple[sp.Eq, sp.Eq]:
    """``A e^{i a} + B e^{i b} = 0`` with A, B of known argument: equal moduli and a phase
    difference of pi (mod 2 pi); returns (l_1 = ..., theta_10 = ...)."""
    terms = sp.Add.make_args(sp.expand(coefficient))
    if len(terms) != 2:
        raise UnsupportedError(f"expected two harmonics to cancel, got {coefficient}")
    polar = []
    for term in terms:
        factors = sp.Mul.make_args(sp.powsimp(term))
        phase = sp.Add(*(f.exp for f in factors if isinstance(f, sp.exp))) / sp.I
        amplitude = sp.Mul(*(f for f in factors if not isinstance(f, sp.exp)))
        polar.append((sp.Abs(amplitude), sp.expand(phase + sp.arg(amplitude))))
    (m1, p1), (m2, p2) = polar
    length = solve_linear(m1 - m2, l_1, 0)
    angle = sp.expand(solve_linear(p1 - p2 - sp.pi, theta_10, 0))  # modulo 2 pi: drop whole turns
    turns = sp.floor(angle.subs({x: 0 for x in angle.free_symbols}) / (2 * sp.pi) + sp.Rational(1, 2))
    return sp.Eq(l_1, length), sp.Eq(theta_10, angle - 2 * sp.pi * turns)


@functools.cache
def line_conditions() -> LineConditions:
    """Derive when the pin moves on the guide line for every carrier angle.

    The loop's component across the guide is the pin's deviation from the line.  With
    the carrier at ``theta_H0 + alpha`` and the planet turned relative to the carrier as
    the contact condition with the fixed ring requires, it is a sum of harmonics
    e^{i nu alpha}.  Harmonics of different frequencies are independent, so the deviation
    vanishes for every ``alpha`` only if the carrier's and the pin's frequencies
    coincide (lengths are positive), which fixes the ratio, and then their coefficients
    cancel, which fixes the lengths (amplitude) and the installation angle (phase).

    >>> c = line_conditions()
    >>> c.ratio, c.lengths, c.installation
    (Eq(r_3, 2*r_1), Eq(l_1, l_H), Eq(theta_10, 2*theta_2 - 2*theta_H0))
    """
    r1, r3 = S.radius("1"), S.radius("3")
    turn = planet_turn_ratio(schemes.cardan()) * alpha
    (sol,) = loop().solve(s)
    deviation = sol.conditions[0].subs({theta_H: theta_H0 + alpha, theta_1: theta_10 + turn})
    parts = harmonics(deviation, alpha)
    carrier = sp.diff(theta_H0 + alpha, alpha)
    pin = sp.expand(sp.diff(theta_H0 + alpha + theta_10 + turn, alpha))
    candidates, excluded = [], []
    for target, why in ((-carrier, "opposite"), (carrier, "equal"), (sp.Integer(0), "zero")):
        for value in (sp.cancel(solve_linear(pin - target, r3, 0)),):
            try:
                schemes.cardan(radii=(r1, value))
            except ModelError as err:
                excluded.append((sp.Eq(r3, value, evaluate=False), f"{why} frequency: {err}"))
            else:
                candidates.append(sp.Eq(r3, value))
    if len(candidates) != 1:
        raise UnsupportedError(f"expected one admissible ratio, found {candidates}")
    (ratio,) = candidates
    balanced = harmonics(deviation.subs(ratio.lhs, ratio.rhs), alpha)
    lengths, installation = _vanishing_pair(balanced[carrier])
    return LineConditions(deviation, tuple(parts), ratio, tuple(excluded), lengths, installation)


# --------------------------------------------------------------------------- results
@dataclass(frozen=True)
class Path:
    """What the pin traces, in words and numbers.

    ``kind`` is ``"line"`` (on the guide), ``"line off the guide"``, ``"ellipse"``,
    ``"hypocycloid"`` (pin on the pitch circle) or ``"hypotrochoid"``.
    """

    kind: str
    description: str
    parameters: Mapping[str, Any] = field(default_factory=dict)

    @property
    def on_guide(self) -> bool:
        """True when the slider can follow the pin (straight line along the guide)."""
        return self.kind == "line"


@dataclass(frozen=True)
class StrokeTimes:
    """Durations of the forward stroke (slider moving towards +theta_2) and the return."""

    forward: float
    back: float

    @property
    def ratio(self) -> float:
        """Forward time / return time (1 for a uniformly turning carrier)."""
        return self.forward / self.back




#: CPU seconds a simplification only for the text of a result may take (the tidier form of an
#: angle the description prints); a decision keeps the full budget of simplify_within.
_DISPLAY_SECONDS = 0.5


def _decide(expr: sp.Expr, what: str = "a condition") -> bool | None:
    """True/False when ``expr`` is decidably zero / non-zero, else None."""
    if not expr.free_symbols and _clearly_away_from(expr, 0):  # a number: no simplification needed to say no
        return False
    zero = simplify_within(expr, what=what).is_zero
    return None if zero is None else bool(zero)


def _is_multiple(expr: sp.Expr, period: sp.Expr, what: str = "a condition") -> bool | None:
    """True/False when ``expr`` is decidably / decidably not a whole multiple of ``period``, else None."""
    q = expr / period
    if not q.free_symbols and _clearly_away_from(q, None):  # a number, no simplification needed to say no
        return False
    q = simplify_within(q, simplifier=lambda e: sp.nsimplify(sp.simplify(e)), what=what)
    if q.is_number:
        integer = q.is_integer
        if integer is None:  # not simplified in time: 50 digits decide unless q is within 1e-30 of a whole number
            value = q.evalf(50)
            if value.is_real and abs(value - round(value)) > sp.Rational(1, 10**30):
                return False
        return None if integer is None else bool(integer)
    return None


def _clearly_away_from(q: sp.Expr, target: int | None) -> bool:
    """True when the number ``q`` is, to 50 digits, more than 1e-30 from ``target`` (None:
    from every whole number); decided only for |q| < 1e15, where those digits leave 35 after
    the point; evaluation given up past 500 digits of working precision counts as undecided.

    >>> _clearly_away_from(sp.sin(sp.sin(1)) - sp.Rational(1, 50), 0), _clearly_away_from(sp.sin(1)**2 + sp.cos(1)**2 - 1, 0)
    (True, False)
    """
    try:
        value = q.evalf(50, maxn=500)
    except (ValueError, TypeError, ArithmeticError):
        return False
    if not (value.is_Float and abs(value) < 10**15):
        return False
    nearest = round(value) if target is None else target
    return bool(abs(value - nearest) > sp.Rational(1, 10**30))


def _in(value: Any, unit: str, what: str) -> Any:
    """A pint quantity in ``unit``; anything else as it is (text refused: read it with symkin.parse)."""
    return as_expr(value, what=what, unit=unit) if isinstance(value, str) or is_quantity(value) else value


@dataclass(frozen=True)
class CardanSlider:
    """A slider pinned to the planet of a Cardan mechanism, under a carrier drive.

    Build it with :meth:`build`.  Every law is derived on first use and cached.

    Attributes
    ----------
    mechanism : Mechanism
        Carrier ``"H"``, planet ``"1"``, fixed ring ``"3"`` (:func:`symkin.schemes.cardan`).
    drive : Drive
        How the carrier turns.
    pin_radius : sympy expression
        ``l_1``: the pin's distance from the planet axis.
    pin_angle : sympy expression
        ``theta_1(0)``: angle of O_1 -> O measured from the carrier at t = 0.
    guide_angle : sympy expression
        ``theta_2``: direction of the slider's guide through O_H.
    teeth : (z1, z3)
        Planet and ring tooth numbers (1 : 2 when not given).
    """

    mechanism: Mechanism
    drive: Drive
    pin_radius: sp.Expr
    pin_angle: sp.Expr
    guide_angle: sp.Expr
    teeth: tuple[sp.Expr, sp.Expr] = (sp.Integer(1), sp.Integer(2))

    @classmethod
    def build(
        cls,
        length: Any = l,
        *,
        drive: Any = None,
        teeth: Sequence[Any] | None = None,
        pin_radius: Any = None,
        pin_angle: Any = None,
        guide_angle: Any = 0,
        carrier_angle: Any = 0,
    ) -> CardanSlider:
        """A Cardan slider from the carrier length and the drive.

        Parameters
        ----------
        length : positive number or expression
            ``l_H``, the carrier length (planet arm).
        drive : Drive or speed, optional
            The carrier's drive; a number or expression is a constant speed
            (default ``omega_H``).
        teeth : (z1, z3), optional
            Planet and ring tooth numbers (default 1 : 2); the pitch radii follow from
            the carrier length: ``r_1 = l_H z1/(z3 - z1)``, ``r_3 = l_H z3/(z3 - z1)``.
        pin_radius : optional
            ``l_1``; default the planet's pitch radius (the pin on the pitch circle).
        pin_angle : optional
            ``theta_1(0)``; default the installation angle that :func:`line_conditions`
            requires for this guide and carrier angle.
        guide_angle, carrier_angle :
            ``theta_2`` and ``theta_H(0)``.

        Notes
        -----
        Lengths are in m and angles in rad, or pint quantities with a unit (:mod:`symkin.units`);
        the drive's speed in rad/s, or a pint quantity.

        Examples
        --------
        >>> CardanSlider.build(20, teeth=(20, 60)).path().kind
        'hypocycloid'
        >>> import pint
        >>> q = pint.get_application_registry().Quantity
        >>> CardanSlider.build(q(20, "mm"), drive=q(24, "rpm"), carrier_angle=q(30, "deg")).laws()[0].rhs
        cos(4*pi*t/5 + pi/6)/25
        """
        length, pin_radius = _in(length, "m", "carrier length l_H"), _in(pin_radius, "m", "pin radius l_1")
        carrier_angle, guide_angle = _in(carrier_angle, "rad", "carrier angle"), _in(guide_angle, "rad", "guide angle")
        pin_angle = _in(pin_angle, "rad", "pin angle")
        arm = as_length(length, "carrier length l_H")
        if teeth is None:
            z1, z3 = sp.Integer(1), sp.Integer(2)
        else:
            if isinstance(teeth, (str, bytes)) or not hasattr(teeth, "__len__") or len(teeth) != 2:
                raise InputError(f"teeth are two tooth numbers (planet, ring), got {teeth!r}")
            z1, z3 = (as_teeth(z, f"tooth number of gear {g}") for z, g in zip(teeth, ("1", "3")))
            if (z3 - z1).is_positive is False:
                raise ModelError(f"the ring (z3 = {z3}) must have more teeth than the planet (z1 = {z1})")
        mech = schemes.cardan(
            radii=(arm * z1 / (z3 - z1), arm * z3 / (z3 - z1)), carrier_angle=as_expr(carrier_angle, what="carrier angle theta_H(0)")
        )
        radius = mech.gear("1").radius if pin_radius is None else as_length(pin_radius, "pin radius l_1")
        guide = as_expr(guide_angle, what="guide angle theta_2")
        if pin_angle is None:
            rule = line_conditions().installation
            pin_angle = rule.rhs.subs({theta_2: guide, theta_H0: mech.position_angle("1")})
        drive = as_drive(S.omega("H") if drive is None else drive, "carrier drive")
        return cls(mech, drive, radius, as_expr(pin_angle, what="pin angle theta_1(0)"), guide, (z1, z3))

    # ---- geometry
    @property
    def arm(self) -> sp.Expr:
        """``l_H``: distance of the planet axis from O_H."""
        return self.mechanism.arm("1")

    @property
    def carrier_angle0(self) -> sp.Expr:
        """``theta_H(0)``."""
        return self.mechanism.position_angle("1")

    @cached_property
    def ring_ratio(self) -> sp.Expr:
        """``r_3 / r_1`` (= z3/z1 with equal modules); a float radius counts as the decimal it prints as."""
        ratio = sp.cancel(self.mechanism.gear("3").radius / self.mechanism.gear("1").radius)
        return sp.cancel(ratio.xreplace({f: as_rational(f, what="a pitch radius") for f in ratio.atoms(sp.Float)}))

    # ---- angles in time
    @cached_property
    def motion(self) -> Any:
        """The mechanism's motion with the carrier H turned by the slider's drive (for particle laws beside the slider's)."""
        return self.mechanism.motion({"H": self.drive})

    @cached_property
    def carrier_angle(self) -> sp.Expr:
        """``theta_H(t)``."""
        return self.carrier_angle0 + self.motion.angle("H")

    @cached_property
    def planet_angle(self) -> sp.Expr:
        """``theta_1(t)``: the pin's angle on the planet, measured from the carrier."""
        return self.pin_angle + planet_turn_ratio(self.mechanism) * self.motion.angle("H")

    # ---- the vector-loop route
    @cached_property
    def loop(self) -> VectorLoop:
        """The loop with this mechanism's lengths and angle laws substituted."""
        return loop().subs(
            {l_H: self.arm, l_1: self.pin_radius, theta_H: self.carrier_angle, theta_1: self.planet_angle, theta_2: self.guide_angle}
        )

    @cached_property
    def _along(self):
        (sol,) = self.loop.solve(s)
        return sol[s], sol.conditions[0]

    @property
    def displacement(self) -> sp.Expr:
        """``s(t)``: the pin's position along the guide (the slider's, when :meth:`path` is on the guide)."""
        return self._along[0]

    @property
    def deviation(self) -> sp.Expr:
        """The pin's signed distance from the guide line; identically zero only on the line."""
        return self._along[1]

    @cached_property
    def velocity(self) -> sp.Expr:
        """``ds/dt``."""
        return sp.diff(self.displacement, S.t)

    @cached_property
    def acceleration(self) -> sp.Expr:
        """``d^2 s/dt^2``."""
        return sp.diff(self.velocity, S.t)

    @cached_property
    def pin_position(self) -> sp.ImmutableMatrix:
        """(x, y) of the pin by the vector loop: the sum of the carrier and crank vectors."""
        return sp.ImmutableMatrix([sp.Add(*(v.x for v in self.loop.left)), sp.Add(*(v.y for v in self.loop.left))])

    # ---- the superposition route
    @cached_property
    def pin(self) -> Any:
        """The pin as a particle of the planet (eqs. 4-6 of the 2009 paper)."""
        angle = self.carrier_angle0 + self.pin_angle
        return self.motion.particle("1", (self.pin_radius * sp.cos(angle), self.pin_radius * sp.sin(angle)), relative_to="pole")

    def laws(self) -> tuple[Law, Law, Law]:
        """``s``, ``v`` and ``a`` of the slider as laws in t."""
        v, a = sp.Symbol("v", real=True), sp.Symbol("a", real=True)
        return (
            Law(s, self.displacement, "slider position along the guide"),
            Law(v, self.velocity, "slider velocity"),
            Law(a, self.acceleration, "slider acceleration"),
        )

    # ---- what the pin traces
    def conditions_met(self) -> dict[str, bool | None]:
        """Each derived line condition for this mechanism: True, False, or None (undecidable)."""
        c = line_conditions()
        return {
            "ratio": _decide(self.ring_ratio - c.ratio.rhs / S.radius("1"), "the 1:2 ratio condition"),
            "lengths": _decide(self.pin_radius - self.arm, "the pin-on-pitch-circle condition"),
            "installation": _is_multiple(
                self.pin_angle - c.installation.rhs.subs({theta_2: self.guide_angle, theta_H0: self.carrier_angle0}), 2 * sp.pi,
                "the installation-angle condition",
            ),
        }

    @property
    def required_pin_angle(self) -> sp.Expr:
        """The installation angle theta_1(0) that keeps the pin on this guide (mod 2 pi)."""
        rule = line_conditions().installation
        return simplify_within(rule.rhs.subs({theta_2: self.guide_angle, theta_H0: self.carrier_angle0}),
                               _DISPLAY_SECONDS, what="the required pin angle")

    def path(self) -> Path:
        """The curve the pin traces, and whether the slider can follow it.

        >>> CardanSlider.build(3, drive=1, pin_radius=1).path().description
        'an ellipse with semi-axes 4 (along angle 0) and 2, not a line: the pin is off the pitch circle (l_1 = 1, l_H = 3)'
        """
        met = self.conditions_met()
        lh, l1, ratio = self.arm, self.pin_radius, self.ring_ratio
        if None in met.values():
            undecided = [k for k, v in met.items() if v is None]
            return Path(
                "undecided",
                f"for these symbols the {' and '.join(undecided)} condition{'s' if len(undecided) > 1 else ''} cannot be "
                "decided: the pin moves on the guide exactly when "
                f"ring : planet = 2, l_1 = l_H and theta_1(0) = {self.required_pin_angle} (mod 2 pi); otherwise it traces "
                "a hypotrochoid (an ellipse or a line off the guide when the ratio is 2)",
            )
        if met["ratio"]:
            direction = simplify_within(self.carrier_angle0 + self.pin_angle / 2, _DISPLAY_SECONDS, what="the ellipse's direction")
            if not met["lengths"]:
                major, minor = lh + l1, sp.Abs(lh - l1)
                return Path(
                    "ellipse",
                    f"an ellipse with semi-axes {major} (along angle {direction}) and {minor}, not a line: the pin is off "
                    f"the pitch circle (l_1 = {l1}, l_H = {lh})",
                    {"semi_major": major, "semi_minor": minor, "direction": direction},
                )
            if not met["installation"]:
                return Path(
                    "line off the guide",
                    f"a straight line through O_H at angle {direction}, not along the guide (theta_2 = {self.guide_angle}): "
                    f"the slider cannot follow; the pin angle theta_1(0) must be {self.required_pin_angle} (mod 2 pi)",
                    {"direction": direction, "stroke": 4 * lh},
                )
            return Path("line", f"a straight line along the guide (theta_2 = {self.guide_angle}), stroke {4 * lh}",
                        {"direction": direction, "stroke": 4 * lh})
        params = {"ring_ratio": ratio, "arm": lh, "pin_radius": l1}
        reason = f"ring : planet = {ratio}, a straight line needs 2"
        if _decide(l1 - self.mechanism.gear("1").radius):
            p, q = sp.fraction(ratio) if ratio.is_Rational else (None, None)
            shape = f"{p} cusps, closing after {q} carrier turn{'s' if q != 1 else ''}" if p is not None else "not closing"
            return Path("hypocycloid", f"a hypocycloid ({shape}), not a line: {reason}", params)
        return Path("hypotrochoid", f"a hypotrochoid (pin at {l1} from the planet axis), not a line: {reason}", params)

    # ---- numbers
    def evaluate(self, times: Any, values: Mapping[Any, Any] | None = None) -> dict[str, np.ndarray]:
        """s, v, a, the pin's x, y and its distance from the guide on a time grid.

        Parameters
        ----------
        times : array of strictly increasing times
        values : mapping, optional
            Numbers for every symbol other than t.

        >>> import numpy as np
        >>> slider = CardanSlider.build(sp.Rational(1, 50), drive=sp.pi)
        >>> [round(float(s), 12) + 0.0 for s in slider.evaluate([0, 0.5, 1])["s"]]
        [0.04, 0.0, -0.04]
        """
        ts = as_times(times)
        x, y = self.pin_position
        names = ("s", "v", "a", "x", "y", "deviation")
        exprs = [self.displacement, self.velocity, self.acceleration, x, y, self.deviation]
        words = ("the slider's displacement s", "the slider's velocity v", "the slider's acceleration a",
                 "the pin's x", "the pin's y", "the pin's distance from the guide")
        out = dict(zip(names, on_grid(exprs, ts, values, what="evaluate the mechanism", names=words)))
        out["t"] = ts
        return out

    def times(self, *, t_start: Any = 0, t_end: Any = None, samples: Any = 9) -> np.ndarray:
        """``samples`` equally spaced times from ``t_start`` to ``t_end`` (default: one
        :meth:`period` after the start; one sample is the start alone).

        >>> CardanSlider.build(1, drive=sp.pi).times(samples=3)
        array([0., 1., 2.])
        """
        start = as_real(t_start, what="the start time", unit="s")
        if t_end is not None:
            end = as_real(t_end, what="the end time", unit="s")
        else:
            period = self.period()
            if period is None:
                raise InputError("this drive has no known period; give --t-end (t_end), the last time")
            end = start + period
        if isinstance(samples, int) and samples == 1:
            return np.array([float(start)])
        later = sign_of(end - start, what="the end time")
        if later is None:
            raise InputError(f"the end time ({end}) is the start ({start}) to 1233 digits: the time grid must increase")
        if later != 1:
            raise InputError(f"the end time ({end}) must be larger than the start ({start}): the time grid must increase")
        return time_grid(end, t_start=start, samples=samples)

    def turns_forward(self, t_end: Any) -> bool:
        """True when the carrier turns counter-clockwise all the way from 0 to ``t_end``
        (always for a constant or elliptical drive; sampled for a law the user gives).

        >>> from symkin.drives import AngleLaw
        >>> CardanSlider.build(1, drive=AngleLaw(sp.sin(S.t))).turns_forward(3)
        False
        """
        if not isinstance(self.drive, AngleLaw):
            return True
        grid = time_grid(max(float(t_end), 1e-9), samples=2001)
        (speed,) = on_grid([self.drive.speed(S.t)], grid, what="sample the carrier speed")
        return bool(np.all(speed > 0))

    def table(self, times: Any, values: Mapping[Any, Any] | None = None) -> SliderTable:
        """The slider on a time grid with its path, period and stroke times: what ``symkin
        cardan`` prints (:meth:`SliderTable.text`) or writes as JSON (:meth:`SliderTable.to_json`).

        >>> table = CardanSlider.build(sp.Rational(1, 50), drive=sp.pi).table([0, 0.5, 1])
        >>> table.path.kind, table.period, round(table.strokes.ratio, 12)
        ('line', 2, 1.0)
        """
        columns = self.evaluate(times, values)
        path = self.path()
        ts = columns["t"]
        strokes = self.stroke_times(values) if path.on_guide and self.turns_forward(ts[-1]) else None
        return SliderTable(self, columns, path, self.period(), strokes)

    def period(self) -> sp.Expr | None:
        """Time after which the whole motion repeats, when the drive makes it periodic.

        A uniform carrier: one turn.  Elliptical gears of order m = p/q: the speed repeats
        every 2 pi/(m omega) and the carrier turns on average at omega, so the motion
        repeats after 2 pi q/omega.  None for other drives.
        """
        if isinstance(self.drive, ConstantSpeed):
            return 2 * sp.pi / sp.Abs(self.drive.omega)
        if isinstance(self.drive, EllipticalGears) and self.drive.order.is_Rational:
            return 2 * sp.pi * sp.fraction(self.drive.order)[1] / self.drive.omega
        return None

    def stroke_times(self, values: Mapping[Any, Any] | None = None) -> StrokeTimes:
        """Durations of the first full forward stroke and return stroke after t = 0.

        The slider is at its far end (s = +stroke/2) when the carrier points along the
        guide; the return stroke lasts until the carrier has turned half a turn more, the
        forward stroke the next half turn.  Requires a straight path on the guide and a
        carrier turning counter-clockwise.
        """
        if not self.path().on_guide:
            raise InputError("the pin does not move along the guide, so the slider has no strokes; see path()")
        subs = as_values(values)
        start = float(sp.N(substitute(sp.Mod(self.guide_angle - self.carrier_angle0, 2 * sp.pi), subs)))
        times = [self._time_of_turn(start + k * math.pi, subs) for k in range(3)]
        return StrokeTimes(forward=times[2] - times[1], back=times[1] - times[0])

    def _time_of_turn(self, angle: float, subs: Mapping[Any, Any]) -> float:
        try:
            return float(sp.N(substitute(self.drive.time_of_angle(sp.Float(angle, 30)), subs), 20))
        except UnsupportedError:
            pass
        f = compile(substitute(self.motion.angle("H"), subs) - angle, [S.t], backend="numpy", on_pole="raise")
        lo, hi, step = 0.0, 1e-3, 1e-3
        while f(hi) < 0:
            lo, hi, step = hi, hi + step, step * 2
            if hi > 1e9:
                raise InputError("the carrier does not turn far enough forward to complete a stroke")
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
        return 0.5 * (lo + hi)


# --------------------------------------------------------------------------- the table
def drive_description(drive: Drive) -> dict[str, Any]:
    """The carrier drive as JSON: its kind and parameters, each unit in its key.

    >>> drive_description(ConstantSpeed(sp.pi))["speed_rad_s"]
    {'exact': 'pi', 'float': 3.141592653589793}
    """
    if isinstance(drive, EllipticalGears):
        return {"kind": "elliptical", "speed_rad_s": exact_json(drive.omega), "eccentricity": exact_json(drive.eccentricity),
                "order": exact_json(drive.order)}
    if isinstance(drive, ConstantSpeed):
        return {"kind": "constant", "speed_rad_s": exact_json(drive.omega)}
    if isinstance(drive, AngleLaw):
        return {"kind": "law", "angle_law_rad": str(drive.law)}
    return {"kind": type(drive).__name__}


def _fmt(x: float) -> str:
    return f"{x + 0.0:.10g}" if math.isfinite(x) else "nan"  # + 0.0: no "-0"


def _drive_text(key: str, value: Any) -> str:
    """'speed_rad_s', {'exact': '4*pi/5', ...} -> 'speed 4*pi/5 rad/s'."""
    text = value["exact"] if isinstance(value, dict) else str(value)
    for suffix, unit in (("_rad_s", " rad/s"), ("_rad", " rad")):
        if key.endswith(suffix):
            return f"{key[: -len(suffix)].replace('_', ' ')} {text}{unit}"
    return f"{key.replace('_', ' ')} {text}"


@dataclass(frozen=True)
class SliderTable:
    """A Cardan slider on a time grid, with its path, period and stroke times.

    Attributes
    ----------
    slider : CardanSlider
    columns : mapping of str to array
        ``t, s, v, a, x, y, deviation`` on the grid.
    path : Path
    period : sympy expression or None
    strokes : StrokeTimes or None
        When the pin moves on the guide and the carrier turns forward.
    """

    slider: CardanSlider
    columns: Mapping[str, np.ndarray]
    path: Path
    period: sp.Expr | None
    strokes: StrokeTimes | None

    @property
    def shown(self) -> list[str]:
        """The columns a reader needs: s, v, a; and x, y, deviation when the pin leaves the guide."""
        return ["t", "s", "v", "a"] + ([] if self.path.on_guide else ["x", "y", "deviation"])

    def to_json(self) -> dict[str, Any]:
        """The table as JSON: the mechanism, the drive, the path, period, stroke times, the laws s, v, a and the sampled columns."""
        sl = self.slider
        return {
            "mechanism": {
                "length": exact_json(sl.arm),
                "teeth": [int(z) for z in sl.teeth],
                "pin_radius": exact_json(sl.pin_radius),
                "pin_on_pitch_circle": _decide(sl.pin_radius - sl.mechanism.gear("1").radius, "the pin radius") is True,
                "pin_angle_rad": exact_json(sl.pin_angle),
                "guide_angle_rad": exact_json(sl.guide_angle),
                "carrier_angle_rad": exact_json(sl.carrier_angle0),
            },
            "drive": drive_description(sl.drive),
            "path": {"kind": self.path.kind, "on_guide": self.path.on_guide, "description": self.path.description},
            "period_s": exact_json(self.period),
            "stroke_times": None if self.strokes is None else {
                "forward": self.strokes.forward, "return": self.strokes.back, "ratio": self.strokes.ratio},
            "laws": {k: str(law.rhs) for k, law in zip("sva", sl.laws())},
            "columns": {k: [float(x) for x in self.columns[k]] for k in self.shown},
        }

    def _repr_html_(self) -> str:
        """The table for Jupyter: the path and stroke times, then the columns (SI units).

        >>> import numpy as np
        >>> html = CardanSlider.build(1, drive=1).table(np.linspace(0, 1, 3))._repr_html_()
        >>> "<th>s [m]</th>" in html
        True
        """
        from symkin._util.display import html_table

        units = {"t": "s", "s": "m", "v": "m/s", "a": "m/s²", "x": "m", "y": "m", "deviation": "m"}
        head = [f"{k} [{units[k]}]" for k in self.shown]
        rows = [[f"{self.columns[k][i]:.6g}" for k in self.shown] for i in range(len(self.columns["t"]))]
        caption = f"path: {self.path.kind}: {self.path.description}"
        if self.strokes is not None:
            caption += f"; stroke times {self.strokes.forward:.4g} s forward, {self.strokes.back:.4g} s back"
        return html_table(head, rows, caption=caption)

    def text(self) -> str:
        """The table as ``symkin cardan`` prints it: the mechanism, drive, path, period, stroke times, s(t) and the columns."""
        sl = self.slider
        z1, z3 = sl.teeth
        drive = drive_description(sl.drive)
        lines = [
            f"Cardan mechanism: l_H = {sl.arm}, z1:z3 = {z1}:{z3}, pin radius {sl.pin_radius}, pin angle {sl.pin_angle}, "
            f"guide angle {sl.guide_angle}, carrier angle {sl.carrier_angle0}",
            "drive: " + ", ".join(_drive_text(k, v) for k, v in drive.items() if k != "kind") + f" ({drive['kind']})",
            f"path: {self.path.kind}: {self.path.description}",
        ]
        if not self.path.on_guide:
            lines.append("note: no slider on the guide can follow this pin; s, v, a are the pin's components along the guide")
        if self.period is not None:
            lines.append(f"period: {self.period} = {_fmt(float(self.period))} s")
        if self.strokes is not None:
            st = self.strokes
            lines.append(f"stroke times: forward {_fmt(st.forward)} s, return {_fmt(st.back)} s, ratio K = {_fmt(st.ratio)}")
        lines.append(f"s(t) = {sl.laws()[0].rhs}")
        columns = self.shown
        lines.append("  ".join(f"{c:>16}" for c in columns))
        for i in range(len(self.columns["t"])):
            lines.append("  ".join(f"{_fmt(float(self.columns[c][i])):>16}" for c in columns))
        return "\n".join(lines)
