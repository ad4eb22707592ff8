"""The values symkin's functions take: numbers, SymPy expressions, Fractions and pint quantities.

The library computes exactly, so every value a function is given becomes an exact SymPy
object here, once, where it comes in:

- an ``int``, a :class:`fractions.Fraction`, a SymPy rational or a NumPy integer exactly;
- a ``float`` (or a NumPy float, a :class:`decimal.Decimal`, a SymPy ``Float``) as the
  decimal it prints as (``0.1`` is 1/10, never ``3602879701896397/36028797018963968``), so what
  a user wrote is what symkin computes with;
- a SymPy expression as it is (``sp.pi / 6``, ``2 * sp.sin(t)``);
- a pint quantity converted exactly into the unit the value is in (:mod:`symkin.units`).

Text is not a value: ``"300 rpm"`` or ``"pi/6"`` is parsed by :func:`symkin.parse` (the one
parser of what a user types, bounded in size, digits and time), at the command line, in train
files and in the papers' reports.  A string given to a library function is refused with a
:class:`~symkin.errors.TextInputError` that says so:

    >>> from symkin import schemes
    >>> schemes.two_row("AA", teeth=(54, 45, 44, 55)).speeds({"1": "300 rpm", "4": 0})
    Traceback (most recent call last):
    ...
    symkin.errors.TextInputError: speed of link 1 is the text '300 rpm'; symkin's functions take numbers, SymPy expressions and pint quantities: parse text with symkin.parse('300 rpm', unit='rad/s')

NaN, infinities and complex numbers are refused where a finite real is meant.  Sizes are not
bounded here: a Python caller gets what SymPy computes (the parser bounds what is typed).
"""

from __future__ import annotations

import decimal
import math
import numbers
from collections.abc import Mapping
from fractions import Fraction
from typing import Any

import sympy as sp
from sympy.core.evalf import PrecisionExhausted

from symkin.errors import InputError, TextInputError

__all__ = [
    "as_expr",
    "as_rational",
    "as_integer",
    "as_fraction",
    "as_real",
    "as_float",
    "as_values",
    "substitute",
    "sign_of",
    "refuse_text",
    "nearest_float",
    "is_quantity",
    "unit_factor",
]


def _show(value: Any) -> str:
    """``repr(value)`` for a message, shortened; never fails (an int of 10^5000 has no repr)."""
    try:
        text = repr(value)
    except ValueError:
        return "a number of more than 4300 digits"
    return text if len(text) <= 80 else text[:77] + "..."


def refuse_text(value: str, what: str, unit: str | None = None) -> TextInputError:
    """The error for text given where a value is meant: it names :func:`symkin.parse`.

    >>> print(refuse_text("pi/6", "the carrier angle", "rad"))
    the carrier angle is the text 'pi/6'; symkin's functions take numbers, SymPy expressions and pint quantities: parse text with symkin.parse('pi/6', unit='rad')
    """
    shown = value if len(value) <= 60 else value[:57] + "..."
    call = f"symkin.parse({shown!r}" + (f", unit={unit!r})" if unit else ")")
    return TextInputError(
        f"{what} is the text {shown!r}; symkin's functions take numbers, SymPy expressions and pint quantities: "
        f"parse text with {call}"
    )


def _decimal(text: str, what: str, error: type[Exception]) -> sp.Rational:
    try:
        value = Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise error(f"{what} must be a finite number, got {text}") from None
    return sp.Rational(value.numerator, value.denominator)


def as_rational(value: Any, *, what: str = "value", error: type[Exception] = InputError) -> sp.Rational:
    """An exact rational from a number: the gate for values that must be exact.

    Integers, fractions and decimals are taken exactly; a float is the decimal it prints as
    (its ``repr``).  NaN, infinities, irrational numbers, text and anything that is not a
    number are refused.

    Parameters
    ----------
    value : int, float, Fraction, Decimal, SymPy Rational or Float, NumPy number
    what : str
        What the value is, for error messages.
    error : exception class
        Raised on a bad value (a :class:`~symkin.errors.SymkinError` subclass).

    Examples
    --------
    >>> as_rational(0.7071067811865476)
    1767766952966369/2500000000000000
    >>> as_rational(Fraction(3, 4)), as_rational(10), as_rational(sp.Rational(9, 4))
    (3/4, 10, 9/4)
    >>> as_rational(float("inf"), what="the total ratio")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the total ratio must be a finite number, got inf
    """
    if type(value) is int:
        return sp.Integer(value)
    if isinstance(value, str):
        raise refuse_text(value, what)
    if isinstance(value, bool) or value is None:
        raise error(f"{what} must be a number, got {_show(value)}")
    if isinstance(value, sp.Basic):
        if isinstance(value, sp.Rational):
            return value
        if isinstance(value, sp.Float):
            if not value.is_finite:
                raise error(f"{what} must be a finite number, got {value}")
            # the decimal the Float prints as; a double-precision Float by its shortest repr
            return _decimal(repr(float(value)) if value._prec <= 53 else str(value), what, error)
        if isinstance(value, sp.Expr) and value.is_number and value.is_extended_real and value.is_finite:
            raise error(f"{what} must be a rational number (a decimal or a fraction), got {value}")
        raise error(f"{what} must be a finite number, got {_show(value)}")
    if isinstance(value, numbers.Rational):  # Fraction, NumPy integers
        return sp.Rational(int(value.numerator), int(value.denominator))
    if isinstance(value, decimal.Decimal):
        if not value.is_finite():
            raise error(f"{what} must be a finite number, got {value}")
        return _decimal(str(value), what, error)
    if isinstance(value, numbers.Real):  # float, NumPy floats: the decimal they print as
        if not math.isfinite(float(value)):
            raise error(f"{what} must be a finite number, got {_show(value)}")
        # (repr of a NumPy 2 float64, a float subclass, is 'np.float64(0.1)': the float's own repr)
        return _decimal(repr(float(value)) if isinstance(value, float) else str(value), what, error)
    raise error(f"{what} must be a number, got {_show(value)}")


def as_integer(
    value: Any,
    *,
    what: str = "value",
    error: type[Exception] = InputError,
    minimum: int | None = None,
    maximum: int | None = None,
) -> sp.Integer:
    """An exact integer: :func:`as_rational` that refuses fractions and floats (counts are not
    measured), within ``[minimum, maximum]`` when they are given.

    >>> as_integer(12), as_integer(sp.Integer(3))
    (12, 3)
    >>> as_integer(3.0, what="the number of satellites")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the number of satellites must be a whole number, got 3.0
    >>> as_integer(0, what="the number of satellites", minimum=1)
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the number of satellites must be at least 1, got 0
    """
    if isinstance(value, (float, sp.Float)) or (isinstance(value, numbers.Real) and not isinstance(value, numbers.Rational)):
        raise error(f"{what} must be a whole number, got {_show(value)}")
    number = as_rational(value, what=what, error=error)
    if not number.is_Integer:
        raise error(f"{what} must be a whole number, got {_show(value)}")
    if minimum is not None and maximum is not None and not minimum <= number <= maximum:
        raise error(f"{what} must be between {minimum} and {maximum}, got {number}")
    if minimum is not None and number < minimum:
        raise error(f"{what} must be at least {minimum}, got {number}")
    if maximum is not None and number > maximum:
        raise error(f"{what} must be at most {maximum}, got {number}")
    return number


def as_fraction(value: Any, *, what: str = "value", error: type[Exception] = InputError) -> Fraction:
    """:func:`as_rational` as a :class:`fractions.Fraction` (for exact arithmetic in loops).

    >>> as_fraction(0.25)
    Fraction(1, 4)
    """
    r = as_rational(value, what=what, error=error)
    return Fraction(int(r.p), int(r.q))


def as_expr(
    value: Any,
    *,
    what: str,
    finite: bool = True,
    error: type[Exception] = InputError,
    unit: str | None = None,
) -> sp.Expr:
    """A SymPy scalar from a number, a SymPy expression or a pint quantity.

    Parameters
    ----------
    value : number, SymPy expression or pint quantity
    what : str
        What the value is, for error messages.
    finite : bool
        Refuse NaN, infinities and complex numbers.
    error : exception class
        Raised on a bad value (a :class:`~symkin.errors.SymkinError` subclass).
    unit : str, optional
        The unit the value is in (pint's spelling, e.g. ``"rad/s"``): a pint quantity is
        converted to it exactly; a bare number is taken to be in it already.

    Examples
    --------
    >>> as_expr(sp.pi / 6, what="angle"), as_expr(Fraction(1, 2), what="angle")
    (pi/6, 1/2)
    >>> as_expr(float("nan"), what="speed")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: speed must be a finite real number, got nan
    """
    if isinstance(value, str):
        raise refuse_text(value, what, unit)
    if is_quantity(value):
        return _quantity(value, unit, what, error)
    if isinstance(value, bool) or value is None:
        raise error(f"{what} must be a number or an expression, got {_show(value)}")
    if finite and isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
        raise error(f"{what} must be a real number, got {_show(value)}")  # (sympify drops an imaginary part of 0)
    if isinstance(value, (numbers.Real, decimal.Decimal)) and not isinstance(value, (numbers.Rational, sp.Basic)) \
            and math.isfinite(float(value)):
        return as_rational(value, what=what, error=error)  # a float is the decimal it prints: 0.1 is 1/10
    try:
        expr = sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError, ValueError):
        raise error(f"{what} must be a number or an expression, got {_show(value)}") from None
    if not isinstance(expr, sp.Expr):
        raise error(f"{what} must be a scalar expression, got {_show(value)}")
    if finite and expr.is_number and (expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or expr.is_extended_real is False):
        raise error(f"{what} must be a finite real number, got {_show(value)}")
    return expr


def _quantity(value: Any, unit: str | None, what: str, error: type[Exception]) -> sp.Expr:
    if unit is None:
        raise error(f"{what} takes a bare number, got the quantity {value:~}")
    magnitude = value.magnitude
    if not isinstance(magnitude, (numbers.Real, decimal.Decimal)) or isinstance(magnitude, bool):
        raise error(f"{what} must be a single real quantity, got {value!r}")
    try:
        return as_rational(magnitude, what=what, error=error) * unit_factor(value.units, unit, what=what)
    except InputError as err:
        raise (err if error is InputError else error(str(err))) from None


def as_real(value: Any, *, what: str = "value", error: type[Exception] = InputError, positive: bool = False,
            unit: str | None = None) -> sp.Expr:
    """An exact finite real constant: :func:`as_rational` for numbers, and exact SymPy
    constants such as ``sqrt(2)/2`` or ``pi/6`` kept as they are.

    >>> as_real(sp.pi / 6), as_real(0.5), as_real(sp.sqrt(2) / 2)
    (pi/6, 1/2, sqrt(2)/2)
    >>> as_real(sp.Symbol("t") + 1, what="the guide angle")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the guide angle must be a finite real number, got t + 1
    """
    if is_quantity(value) or isinstance(value, str) or (isinstance(value, sp.Expr) and not value.is_Float):
        expr = as_expr(value, what=what, error=error, unit=unit)
    else:
        expr = as_rational(value, what=what, error=error)
    if not expr.is_number or expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
        raise error(f"{what} must be a finite real number, got {_show(value)}")
    if positive and sign_of(expr, what=what, error=error) != 1:
        raise error(f"{what} must be positive, got {_show(value)}")
    return expr


#: Digits to which SymPy's evalf may work to decide a sign or a float.
_DIGITS = 1300


def sign_of(expr: sp.Expr, *, what: str = "value", error: type[Exception] = InputError) -> int | None:
    """The sign of a constant expression: -1, 0, 1, or None for a number that is 0 to
    :data:`_DIGITS` digits without being written as 0 (SymPy's ``evalf`` with ``strict``).

    >>> sign_of(sp.pi - 3), sign_of(sp.Integer(0)), sign_of(sp.sin(1)**2 + sp.cos(1)**2 - 1) is None
    (1, 0, True)
    """
    if expr.is_Rational:
        return (expr.p > 0) - (expr.p < 0)
    if not expr.is_number:
        raise error(f"{what} must be a number, got {_show(expr)}")
    try:
        value = expr.evalf(15, strict=True, maxn=_DIGITS)
    except PrecisionExhausted:
        return None
    if not value.is_extended_real:
        raise error(f"{what} must be a real number, got {_show(expr)}")
    return 1 if value > 0 else -1 if value < 0 else 0


def as_float(value: Any, *, what: str, positive: bool = False, error: type[Exception] = InputError) -> float:
    """A finite float from a number or a constant SymPy expression.

    >>> as_float(sp.pi / 2, what="time")
    1.5707963267948966
    """
    if isinstance(value, bool):
        raise error(f"{what} must be a number, got {value!r}")
    if type(value) is not float and not isinstance(value, numbers.Rational):
        expr = as_expr(value, what=what, error=error)
        if not expr.is_number:
            raise error(f"{what} must be a number, got {_show(value)}")
        try:
            number = nearest_float(expr)
        except TypeError:
            raise error(f"{what} must be a real number, got {_show(value)}") from None
    else:
        try:
            number = float(value)
        except OverflowError:
            number = math.inf
    if not math.isfinite(number):
        raise error(f"{what} must be a finite number, got {_show(value)}")
    if positive and not number > 0:
        raise error(f"{what} must be positive, got {_show(value)}")
    return number


def nearest_float(expr: sp.Expr) -> float:
    """The float of a constant SymPy expression: exact rationals rounded once, other constants
    by SymPy's ``evalf`` with ``strict`` (17 correct digits, or 0.0 for a number that is 0 to
    1300 digits: below every float); inf beyond the float range.  TypeError when it is not real.

    >>> nearest_float(sp.Rational(1, 3)), nearest_float(sp.sin(1)**2 + sp.cos(1)**2 - 1)
    (0.3333333333333333, 0.0)
    """
    if expr.is_Rational:
        try:
            return int(expr.p) / int(expr.q)
        except OverflowError:
            return math.copysign(math.inf, expr.p)
    try:
        evaluated = expr.evalf(17, strict=True, maxn=_DIGITS)
    except PrecisionExhausted:  # 0 to 1300 digits (a zero not written as 0)
        return 0.0
    if not evaluated.is_extended_real:
        raise TypeError(f"{expr} is not real")
    try:
        return float(evaluated)
    except OverflowError:
        return math.copysign(math.inf, float(sp.sign(evaluated)))


def as_values(values: Any, *, what: str = "values") -> dict[str, sp.Expr]:
    """Numbers for symbols, keyed by name: from a mapping whose keys are SymPy symbols or names.

    Keys are matched by name, so ``Symbol("r_1")`` finds the engine's positive ``r_1``;
    every value passes :func:`as_expr`.

    >>> as_values({"r_1": Fraction(3, 2), sp.Symbol("t"): 2})
    {'r_1': 3/2, 't': 2}
    """
    if values is None:
        return {}
    if not isinstance(values, Mapping):
        raise InputError(f"{what} are a mapping of symbol (or its name) to value, got {_show(values)}")
    out: dict[str, sp.Expr] = {}
    for key, value in values.items():
        if isinstance(key, sp.Symbol):
            name = key.name
        elif isinstance(key, str) and key.strip():
            name = key.strip()
        else:
            raise InputError(f"{what}: a key is a SymPy symbol or its name, got {_show(key)}")
        out[name] = as_expr(value, what=f"the value of {name}")
    return out


def substitute(expr: Any, values: Mapping[Any, Any] | None) -> Any:
    """``expr`` (a SymPy expression or matrix) with the :func:`as_values` of ``values`` put in.

    >>> r = sp.Symbol("r_1", positive=True)
    >>> substitute(2 * r, {"r_1": 5})
    10
    """
    named = values if _is_named(values) else as_values(values)
    if not named:
        return expr
    return expr.xreplace({s: named[s.name] for s in expr.free_symbols if getattr(s, "name", None) in named})


def _is_named(values: Any) -> bool:
    return isinstance(values, dict) and all(isinstance(k, str) and isinstance(v, sp.Expr) for k, v in values.items())


# --------------------------------------------------------------------------- pint quantities
def is_quantity(value: Any) -> bool:
    """Whether ``value`` is a pint quantity (without importing pint when it is not one).

    >>> is_quantity(3), is_quantity("3 rpm"), is_quantity(sp.Function("Theta")(1))  # an undefined function's class has no module
    (False, False, False)
    """
    module = getattr(type(value), "__module__", None)
    return isinstance(module, str) and module.split(".")[0] == "pint" and hasattr(value, "units") \
        and hasattr(value, "magnitude")


def _registry(value: Any = None) -> Any:
    import pint

    if value is not None and getattr(value, "_REGISTRY", None) is not None:
        return value._REGISTRY
    return pint.get_application_registry()


#: Units to suggest for a quantity given in a unit of the wrong kind.
_SUGGESTED = {"rad/s": "rps (turns a second), rpm, rad/s, deg/s", "rad/s^2": "rad/s^2, deg/s^2, rpm/s", "rad": "deg, rad, turn"}


def unit_factor(unit_from: Any, unit_to: str, *, what: str = "value") -> sp.Expr:
    """The exact factor that turns a value in ``unit_from`` (a pint unit, or its name) into one
    in ``unit_to``.

    pint gives the factor as a float; it is made exact when it is a rational, or a rational
    times pi (angles: degrees, revolutions), with a denominator up to 10^6 that reproduces
    the float to 14 digits, and taken as the float's exact value otherwise.

    >>> unit_factor("rpm", "rad/s"), unit_factor("deg", "rad"), unit_factor("mm", "m")
    (pi/30, pi/180, 1/1000)
    >>> unit_factor("s", "rad/s")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: value: s is not a unit of rad/s (it is a [time], rad/s is 1 / [time])
    >>> unit_factor("Hz", "rad/s")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: value: Hz gives no angle, and rad/s measures one (is 1 Hz one turn a second, 2 pi rad/s, or 1 rad/s?); write it in a unit such as rps (turns a second), rpm, rad/s, deg/s
    """
    import pint

    reg = _registry(unit_from if not isinstance(unit_from, str) else None)
    src = _unit(reg, unit_from, what) if isinstance(unit_from, str) else unit_from
    dst = _unit(reg, unit_to, what)
    try:
        f = float(reg.Quantity(1.0, src).to(dst).magnitude)
        offset = float(reg.Quantity(0.0, src).to(dst).magnitude)
    except pint.DimensionalityError:
        raise InputError(
            f"{what}: {src:~} is not a unit of {unit_to} (it is a {reg.get_dimensionality(src)}, "
            f"{unit_to} is {reg.get_dimensionality(dst)})".replace("dimensionless", "pure number")
        ) from None
    if not math.isfinite(f) or f == 0:
        raise InputError(f"{what}: the unit {src:~} is out of range in {unit_to}")
    if offset != 0:  # degC to K is no factor: 0 degC is 273.15 K
        raise InputError(f"{what}: {src:~} has an offset from {unit_to} (0 {src:~} is {offset:g} {unit_to}), so no "
                         f"factor converts it; give a difference (delta_{src}) or {unit_to}")
    to_angle, from_angle = _angle_power(reg, dst), _angle_power(reg, src)
    if to_angle != from_angle:
        # pint takes the radian for a pure number, so 5 Hz would pass as 5 rad/s, not 5 turns a second
        if to_angle > from_angle:
            why = f"{f'{src:~}' or 'a pure number'} gives no angle, and {unit_to} measures one" + (
                " (is 1 Hz one turn a second, 2 pi rad/s, or 1 rad/s?)" if unit_to == "rad/s" else "")
        else:
            why = f"{src:~} measures an angle, and {unit_to} does not"
        raise InputError(f"{what}: {why}; write it in a unit such as {_SUGGESTED.get(unit_to, unit_to)}")
    decimal_factor = Fraction(repr(f))  # a metric factor is the decimal it prints (1e-09 for nm to m)
    if decimal_factor.denominator <= 10**12:
        return sp.Rational(decimal_factor.numerator, decimal_factor.denominator)
    for power in (0, 1, -1):
        r = Fraction(f / math.pi**power).limit_denominator(10**6)
        if r and abs(float(r) * math.pi**power - f) <= 1e-14 * abs(f):
            return sp.Rational(r.numerator, r.denominator) * sp.pi**power
    return sp.Rational(*Fraction(f).as_integer_ratio())


def _angle_power(reg: Any, unit: Any) -> float:
    """The power of the radian in ``unit``'s root units (1 for rad/s and rpm, 0 for Hz and mm)."""
    return float(dict(reg.get_root_units(unit)[1]._units).get("radian", 0))


def _unit(reg: Any, name: str, what: str) -> Any:
    try:
        return reg.parse_units(name.strip())
    except Exception:  # pint raises several classes for an unknown or malformed unit
        raise InputError(f"{what}: unknown unit {name!r}; write a unit such as rpm, rad/s, deg/s, deg, mm, m, s, ms") from None
