"""Safe parsing of numbers and expressions typed by a user.

``sympy.sympify`` and ``parse_expr`` evaluate Python, so a string from a user must never
reach them.  Here a string is parsed by :mod:`ast` and rebuilt node by node from an
allow-list of operators, names and functions; nothing is evaluated by Python.

    >>> parse_number("0.8")
    4/5
    >>> parse_expression("2*pi*sin(t)", names=("t",))
    2*pi*sin(t)
    >>> parse_expression("__import__('os').system('echo hi')")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: expression: calling "__import__('os').system" is not allowed; allowed names: E, pi; functions: ...
"""

from __future__ import annotations

import ast
import decimal
import math
import numbers
import re
import sys
from collections.abc import Callable, Iterable, Mapping
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError

__all__ = [
    "as_expr",
    "as_values",
    "substitute",
    "as_float",
    "as_rational",
    "as_integer",
    "as_fraction",
    "as_real",
    "parse_number",
    "parse_integer",
    "parse_expression",
    "parse_quantity",
    "is_quantity",
    "unit_factor",
    "FUNCTIONS",
    "CONSTANTS",
]

#: Functions a user expression may call.
FUNCTIONS: Mapping[str, Callable[..., sp.Expr]] = {
    "sin": sp.sin,
    "cos": sp.cos,
    "tan": sp.tan,
    "asin": sp.asin,
    "acos": sp.acos,
    "atan": sp.atan,
    "atan2": sp.atan2,
    "sinh": sp.sinh,
    "cosh": sp.cosh,
    "tanh": sp.tanh,
    "exp": sp.exp,
    "log": sp.log,
    "sqrt": sp.sqrt,
    "Abs": sp.Abs,
}
#: Constants a user expression may name.
CONSTANTS: Mapping[str, sp.Expr] = {"pi": sp.pi, "E": sp.E}

MAX_LENGTH = 2000
MAX_DEPTH = 60
MAX_EXPONENT = 1000
#: Exact numbers are accepted between 10^-MAX_DIGITS and 10^MAX_DIGITS in size (or 0), so
#: every number a user gives also has a finite, non-zero float (floats end near 1.8e308).
MAX_DIGITS = 300
_HUGE = sp.Integer(10) ** MAX_DIGITS

_NUMBER = re.compile(r"^[+-]?(\d+(_?\d+)*)?(\.\d*)?([eE][+-]?\d+)?$|^[+-]?\d+\s*/\s*\d+$", re.ASCII)

#: The largest finite float64; an exact input beyond it has no numeric law to go to.
_FLOAT64_MAX = sys.float_info.max


def _check_text(text: object, what: str) -> str:
    if not isinstance(text, str):
        raise InputError(f"{what} must be text, got {type(text).__name__}")
    stripped = text.strip()
    if not stripped:
        raise InputError(f"{what} is empty; give a value")
    if len(stripped) > MAX_LENGTH:
        raise InputError(f"{what} is {len(stripped)} characters long; at most {MAX_LENGTH} are accepted")
    return stripped


def parse_number(text: str, *, what: str = "value") -> sp.Rational:
    """An exact rational from a decimal, scientific or fraction literal.

    >>> parse_number("1e3"), parse_number("-3/4"), parse_number("2.25")
    (1000, -3/4, 9/4)
    >>> parse_number("nan")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: value must be a finite number, got 'nan'
    """
    s = _check_text(text, what)
    if s.lower().lstrip("+-") in {"nan", "inf", "infinity"}:
        raise InputError(f"{what} must be a finite number, got {text!r}")
    if not _NUMBER.match(s) or s in {".", "+", "-"}:
        raise InputError(f"{what} must be a number such as 12, 0.8, 1e-3 or 3/4, got {text!r}")
    mantissa, _, exponent = s.lower().partition("e")
    if exponent and abs(int(exponent)) > 2 * MAX_DIGITS:
        raise InputError(f"{what} has exponent {exponent}; numbers from 1e-{MAX_DIGITS} to 1e{MAX_DIGITS} in size are accepted")
    if len(re.sub(r"\D", "", mantissa)) > MAX_DIGITS:
        raise InputError(f"{what} has more than {MAX_DIGITS} digits")
    try:
        value = Fraction(s.replace(" ", ""))
    except (ValueError, ZeroDivisionError) as err:
        raise InputError(f"{what} must be a finite number, got {text!r} ({err})") from None
    return _bounded(sp.Rational(value.numerator, value.denominator), what)


def _bounded(value: sp.Expr, what: str) -> sp.Expr:
    """``value`` unless it is an exact number too large or too small (but not 0) to use."""
    if value.is_Rational and value != 0:
        size = abs(value)
        if size > _HUGE or size * _HUGE < 1:
            raise InputError(
                f"{what} holds a number of about 10^{_exponent(size)}; numbers from 1e-{MAX_DIGITS} to "
                f"1e{MAX_DIGITS} in size are accepted"
            )
    return value


def _exponent(size: sp.Rational) -> int:
    return round((int(size.p).bit_length() - int(size.q).bit_length()) * math.log10(2))


def parse_integer(text: str, *, what: str = "value") -> sp.Integer:
    """An exact integer; a fraction or decimal with a fractional part is refused.

    >>> parse_integer("100")
    100
    """
    value = parse_number(text, what=what)
    if not value.is_Integer:
        raise InputError(f"{what} must be a whole number, got {text!r}")
    return value


def as_rational(value: Any, *, what: str = "value", text: bool = True, error: type[Exception] = InputError) -> sp.Rational:
    """An exact rational from a user's number: the one gate for values that must be exact.

    Integers, fractions (:class:`fractions.Fraction`, SymPy rationals) and decimals are
    taken exactly; text is parsed by :func:`parse_number` (``"0.8"`` is 4/5); a float is
    the decimal it prints as, its ``repr`` (``0.1`` is 1/10, never a guessed
    ``sqrt(2)/2``), so what a user typed is what symkin computes with.  NaN, infinities,
    irrational numbers and anything that is not a number are refused, as are numbers
    outside the size :func:`parse_number` accepts.

    Parameters
    ----------
    value : int, float, Fraction, Decimal, SymPy Rational or Float, or str
    what : str
        What the value is, for error messages.
    text : bool
        Accept text (False: numbers only).
    error : exception class
        Raised on a bad value (a :class:`~symkin.errors.SymkinError` subclass).

    Examples
    --------
    >>> as_rational(0.7071067811865476)
    1767766952966369/2500000000000000
    >>> as_rational("2.25"), as_rational(Fraction(3, 4)), as_rational(10)
    (9/4, 3/4, 10)
    >>> as_rational(float("inf"), what="the total ratio")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the total ratio must be a finite number, got inf
    """
    try:
        return _rational(value, what, text)
    except InputError as err:
        if error is InputError:
            raise
        raise error(str(err)) from None


#: Plain integers this size or smaller need no size check (the common case, in hot loops).
_SMALL_INT = 10**18


def _rational(value: Any, what: str, text: bool) -> sp.Rational:
    if type(value) is int and -_SMALL_INT <= value <= _SMALL_INT:
        return sp.Integer(value)
    if isinstance(value, str):
        if not text:
            raise InputError(f"{what} must be a number, not the string {value!r}")
        return parse_number(value, what=what)
    if isinstance(value, bool) or value is None:
        raise InputError(f"{what} must be a number, got {value!r}")
    if isinstance(value, sp.Basic):
        if isinstance(value, sp.Rational):
            return _bounded(value, what)
        if isinstance(value, sp.Float):
            if not value.is_finite:
                raise InputError(f"{what} must be a finite number, got {value}")
            # the decimal the Float prints as; a double-precision Float by its shortest repr
            decimal_text = repr(float(value)) if value._prec <= 53 else str(value)
            return parse_number(decimal_text, what=what)
        if isinstance(value, sp.Expr) and value.is_number and value.is_extended_real and value.is_finite:
            raise InputError(f"{what} must be a rational number (a decimal or a fraction), got {value}")
        raise InputError(f"{what} must be a finite number, got {value}")
    if isinstance(value, numbers.Rational):  # int, Fraction, NumPy integers
        return _bounded(sp.Rational(int(value.numerator), int(value.denominator)), what)
    if isinstance(value, decimal.Decimal):
        if not value.is_finite():
            raise InputError(f"{what} must be a finite number, got {value}")
        return parse_number(str(value), what=what)
    if isinstance(value, numbers.Real):  # float, NumPy floats: the decimal they print as
        f = float(value)
        if not math.isfinite(f):
            raise InputError(f"{what} must be a finite number, got {value!r}")
        return parse_number(repr(f) if isinstance(value, float) else str(value), what=what)
    raise InputError(f"{what} must be a number, got {value!r}")


def as_integer(
    value: Any,
    *,
    what: str = "value",
    text: bool = True,
    error: type[Exception] = InputError,
    minimum: int | None = None,
    maximum: int | None = None,
) -> sp.Integer:
    """An exact integer: :func:`as_rational` that refuses fractions and floats (counts are
    not measured), within ``[minimum, maximum]`` when they are given.

    >>> as_integer("12"), as_integer(3)
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
    if type(value) is int and -_SMALL_INT <= value <= _SMALL_INT:  # the common case, in hot loops
        if (minimum is not None and value < minimum) or (maximum is not None and value > maximum):
            pass  # the message below
        else:
            return sp.Integer(value)
    if isinstance(value, (float, sp.Float)) or (isinstance(value, numbers.Real) and not isinstance(value, numbers.Rational)):
        raise error(f"{what} must be a whole number, got {value!r}")
    number = as_rational(value, what=what, text=text, error=error)
    if not number.is_Integer:
        raise error(f"{what} must be a whole number, got {value!r}")
    if minimum is not None and maximum is not None and not minimum <= number <= maximum:
        raise error(f"{what} must be between {minimum} and {maximum}, got {number}")
    if minimum is not None and number < minimum:
        raise error(f"{what} must be at least {minimum}, got {number}")
    if maximum is not None and number > maximum:
        raise error(f"{what} must be at most {maximum}, got {number}")
    return number


def as_fraction(value: Any, *, what: str = "value", error: type[Exception] = InputError) -> Fraction:
    """:func:`as_rational` as a :class:`fractions.Fraction` (for exact arithmetic in loops).

    >>> as_fraction("0.25")
    Fraction(1, 4)
    """
    r = as_rational(value, what=what, error=error)
    return Fraction(int(r.p), int(r.q))


def as_real(value: Any, *, what: str = "value", error: type[Exception] = InputError, positive: bool = False,
            unit: str | None = None) -> sp.Expr:
    """An exact finite real constant: :func:`as_rational` for numbers, and exact SymPy
    constants such as ``sqrt(2)/2`` or ``pi/6`` (given as SymPy objects or as text, parsed
    by :func:`parse_expression`) kept as they are.

    >>> as_real("pi/6"), as_real(0.5), as_real(sp.sqrt(2) / 2)
    (pi/6, 1/2, sqrt(2)/2)
    >>> as_real("10 deg", unit="rad")            # with ``unit``, a quantity is converted to it
    pi/18
    >>> as_real("t + 1", what="the guide angle")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the guide angle: 't' is not allowed here; allowed names: E, pi; functions: ...
    """
    if unit is not None and (isinstance(value, str) or is_quantity(value)):
        try:
            expr = parse_quantity(value, unit, what=what)
        except InputError as err:
            raise (err if error is InputError else error(str(err))) from None
    elif isinstance(value, str):
        expr = parse_expression(value, what=what)
    elif isinstance(value, sp.Expr) and not isinstance(value, (sp.Rational, sp.Float)):
        expr = value
    else:
        expr = as_rational(value, what=what, error=error)
    if not expr.is_number or expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or expr.is_extended_real is False or not expr.is_finite:
        raise error(f"{what} must be a finite real number, got {value!r}")
    if positive and not expr.is_positive:
        raise error(f"{what} must be positive, got {value!r}")
    if abs(expr.evalf(15)) > _FLOAT64_MAX:  # exact, but no numeric law can take it
        raise error(f"{what} is {value!r}, beyond the float64 range (about 1.8e308); give a smaller value")
    return expr


def parse_expression(
    text: str,
    *,
    names: Iterable[str] = (),
    symbols: Mapping[str, sp.Expr] | None = None,
    what: str = "expression",
) -> sp.Expr:
    """A SymPy expression from text, built from an allow-list only.

    Parameters
    ----------
    text : str
        Numbers, + - * / ** (or ^), parentheses, the constants pi and E, the functions
        in :data:`FUNCTIONS`, and the names allowed below.
    names : iterable of str
        Names allowed as symbols (``"t"`` maps to :data:`symkin.symbols.t`).
    symbols : mapping of str to expression, optional
        Names allowed with the value to put in their place.
    what : str
        What the expression is, for error messages.
    """
    s = _check_text(text, what)
    allowed: dict[str, sp.Expr] = dict(CONSTANTS)
    for n in names:
        allowed[n] = S.t if n == "t" else sp.Symbol(n, real=True)
    allowed.update(symbols or {})
    source = s.replace("^", "**")
    try:
        tree = ast.parse(source, mode="eval")
    except (SyntaxError, ValueError):
        raise InputError(f"{what} {text!r} is not a valid expression") from None
    return _Builder(allowed, what, source).build(tree.body, 0)


class _Builder:
    def __init__(self, allowed: Mapping[str, sp.Expr], what: str, source: str):
        self.allowed = allowed
        self.what = what
        self.source = source

    def fail(self, message: str) -> InputError:
        names = ", ".join(sorted(self.allowed, key=str.lower))
        return InputError(
            f"{self.what}: {message}; allowed names: {names}; functions: {', '.join(sorted(FUNCTIONS, key=str.lower))}"
        )

    def build(self, node: ast.AST, depth: int) -> sp.Expr:
        if depth > MAX_DEPTH:
            raise InputError(f"{self.what} is nested more than {MAX_DEPTH} levels deep")
        if isinstance(node, ast.Constant):
            v = node.value
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise self.fail(f"{v!r} is not a number")
            # the literal as typed, exactly (a float would round long decimals and 1e-400)
            literal = ast.get_source_segment(self.source, node) or ""
            if not _NUMBER.match(literal) or "/" in literal:
                raise InputError(f"{self.what}: write numbers with decimal digits 0-9, got {literal!r}")
            return parse_number(literal, what=self.what)
        if isinstance(node, ast.Name):
            if node.id in self.allowed:
                return self.allowed[node.id]
            raise self.fail(f"{node.id!r} is not allowed here")
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
            operand = self.build(node.operand, depth + 1)
            return operand if isinstance(node.op, ast.UAdd) else -operand
        if isinstance(node, ast.BinOp):
            return _bounded(self.binop(node, depth), self.what)
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                raise self.fail(f"calling {_show(node.func)} is not allowed")
            if node.keywords:
                raise self.fail("functions take no keyword arguments")
            args = [self.build(a, depth + 1) for a in node.args]
            try:
                return FUNCTIONS[node.func.id](*args)
            except TypeError:
                raise InputError(f"{self.what}: wrong number of arguments to {node.func.id}") from None
        raise self.fail(f"{_show(node)} ({type(node).__name__.lower()}) is not allowed")

    def binop(self, node: ast.BinOp, depth: int) -> sp.Expr:
        left = self.build(node.left, depth + 1)
        right = self.build(node.right, depth + 1)
        op = type(node.op)
        if op is ast.Add:
            return left + right
        if op is ast.Sub:
            return left - right
        if op is ast.Mult:
            return left * right
        if op is ast.Div:
            if right == 0:
                raise InputError(f"{self.what} divides by zero")
            return left / right
        if op is ast.Pow:
            if right.is_number and (not right.is_finite or abs(right) > MAX_EXPONENT):
                raise InputError(f"{self.what} has an exponent larger than {MAX_EXPONENT}")
            if left == 0 and right.is_number and right.is_negative:
                raise InputError(f"{self.what} divides by zero")
            return left**right
        raise self.fail(f"the operator {type(node.op).__name__} is not allowed")


def _show(node: ast.AST) -> str:
    text = ast.unparse(node)
    return repr(text if len(text) <= 40 else text[:37] + "...")


def as_expr(
    value: Any,
    *,
    what: str,
    names: Iterable[str] = (),
    text: bool = True,
    finite: bool = True,
    error: type[Exception] = InputError,
    unit: str | None = None,
) -> sp.Expr:
    """A SymPy scalar from a number, a SymPy expression, or text parsed by :func:`parse_expression`.

    The one gate through which library functions take a user's value: a string is never
    given to ``sympify`` (which evaluates Python).

    Parameters
    ----------
    value : number, SymPy expression or str
    what : str
        What the value is, for error messages.
    names : iterable of str
        Names text may use (``"t"`` is :data:`symkin.symbols.t`).
    text : bool
        Accept text at all (False: SymPy objects and numbers only).
    finite : bool
        Refuse NaN, infinities and complex numbers.
    error : exception class
        Raised on a bad value (a :class:`~symkin.errors.SymkinError` subclass).
    unit : str, optional
        The unit of the value (pint's spelling, e.g. ``"rad/s"``): a pint quantity, or text
        with a unit (``"300 rpm"``), is converted to it exactly (:func:`parse_quantity`); a
        bare number is taken to be in it already.

    >>> as_expr("pi/6", what="angle")
    pi/6
    >>> as_expr(float("nan"), what="speed")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: speed must be a finite real number, got nan
    >>> as_expr("300 rpm", what="speed", unit="rad/s")
    10*pi
    """
    if unit is not None and (is_quantity(value) or (text and isinstance(value, str))):
        try:
            return parse_quantity(value, unit, what=what, names=names)
        except InputError as err:
            raise (err if error is InputError else error(str(err))) from None
    if isinstance(value, str):
        if not text:
            raise error(
                f"{what} must be a number or a SymPy expression, not the string {value!r}; "
                "parse text with symkin._util.parsing.parse_expression"
            )
        return parse_expression(value, names=names, what=what)
    if isinstance(value, bool) or value is None:
        raise error(f"{what} must be a number or an expression, got {value!r}")
    try:
        expr = sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError, ValueError):
        raise error(f"{what} must be a number or an expression, got {value!r}") from None
    if not isinstance(expr, sp.Expr):
        raise error(f"{what} must be a scalar expression, got {value!r}")
    if finite and expr.is_number and (expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or expr.is_extended_real is False):
        raise error(f"{what} must be a finite real number, got {value!r}")
    return expr


#: The text of a unit: a name and products, quotients and integer powers of names.
_UNIT_TEXT = re.compile(r"^[A-Za-z_°µ][A-Za-z0-9_°µ]*(\s*(\*\*|[*/^])?\s*[A-Za-z0-9_°µ.-]+)*$")
#: Where a unit may start: a letter after a digit, a closing parenthesis or a space.
_UNIT_START = re.compile(r"(?<=[0-9.)\s])\s*(?=[A-Za-z_°µ])")
MAX_UNIT_LENGTH = 40


def is_quantity(value: Any) -> bool:
    """Whether ``value`` is a pint quantity (without importing pint when it is not one).

    >>> import sympy as sp
    >>> is_quantity(3), is_quantity("3 rpm"), is_quantity(sp.Function("Theta")(1))  # an undefined function's class has no module
    (False, False, False)
    """
    module = getattr(type(value), "__module__", None)
    return isinstance(module, str) and module.split(".")[0] == "pint" and hasattr(value, "units") \
        and hasattr(value, "magnitude")


def _registry(value: Any = None) -> Any:
    try:
        import pint
    except ImportError:  # pragma: no cover - pint is a dependency
        raise InputError("values with units need pint: pip install pint") from None
    if value is not None and getattr(value, "_REGISTRY", None) is not None:
        return value._REGISTRY
    return pint.get_application_registry()


def unit_factor(unit_from: Any, unit_to: str, *, what: str = "value") -> sp.Expr:
    """The exact factor that turns a value in ``unit_from`` into one in ``unit_to``.

    pint gives the factor as a float; it is made exact when it is a rational, or a rational
    times pi (angles: degrees, revolutions), with a denominator up to 10^6 that reproduces
    the float to 14 digits, and taken as the float's exact value otherwise.

    >>> unit_factor("rpm", "rad/s"), unit_factor("deg", "rad"), unit_factor("mm", "m")
    (pi/30, pi/180, 1/1000)
    >>> unit_factor("s", "rad/s")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: value: s is not a unit of rad/s (it is a [time], rad/s is 1 / [time])
    """
    import pint

    reg = _registry(unit_from if not isinstance(unit_from, str) else None)
    src = _parse_unit(reg, unit_from, what) if isinstance(unit_from, str) else unit_from
    dst = _parse_unit(reg, unit_to, what)
    try:
        f = float(reg.Quantity(1.0, src).to(dst).magnitude)
    except pint.DimensionalityError:
        raise InputError(
            f"{what}: {src:~} is not a unit of {unit_to} (it is a {reg.get_dimensionality(src)}, "
            f"{unit_to} is {reg.get_dimensionality(dst)})".replace("dimensionless", "pure number")
        ) from None
    if not math.isfinite(f) or f == 0:
        raise InputError(f"{what}: the unit {src:~} is out of range in {unit_to}")
    for power in (0, 1, -1):
        r = Fraction(f / math.pi**power).limit_denominator(10**6)
        if r and abs(float(r) * math.pi**power - f) <= 1e-14 * abs(f):
            return sp.Rational(r.numerator, r.denominator) * sp.pi**power
    return sp.Rational(*Fraction(f).as_integer_ratio())


def _parse_unit(reg: Any, text: str, what: str) -> Any:
    text = text.strip()
    if len(text) > MAX_UNIT_LENGTH or not _UNIT_TEXT.match(text):
        raise InputError(f"{what}: {text[:60]!r} is not a unit; write a number and a unit such as 300 rpm, 10 deg, 5 mm")
    try:
        unit = reg.parse_units(text)
    except Exception:  # pint raises several classes for an unknown or malformed unit
        raise InputError(f"{what}: unknown unit {text!r}; write a unit such as rpm, rad/s, deg/s, deg, mm, m, s, ms") from None
    return unit


def parse_quantity(value: Any, unit: str, *, what: str = "value", names: Iterable[str] = ()) -> sp.Expr:
    """An exact value in ``unit`` from a pint quantity, or from text: a number or constant
    expression followed by a unit (``"300 rpm"``, ``"10deg"``, ``"2*pi rad/s"``, ``"5 mm"``).

    Text without a unit is a value in ``unit`` already.  The number is parsed by
    :func:`parse_expression` (exact, from the allow-list); the unit by pint's own parser after
    an allow-list check (letters, digits, ``* / ^ **``; never Python), so a quantity's text
    is as safe as a number's.

    >>> parse_quantity("300 rpm", "rad/s"), parse_quantity("90deg", "rad"), parse_quantity("5 mm", "m")
    (10*pi, pi/2, 1/200)
    >>> parse_quantity("2", "rad/s")
    2
    >>> parse_quantity("3 kg", "m", what="--length")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: --length: kg is not a unit of m (it is a [mass], m is [length])
    """
    if is_quantity(value):
        magnitude = value.magnitude
        if not isinstance(magnitude, numbers.Real) or isinstance(magnitude, bool):
            raise InputError(f"{what} must be a single real quantity, got {value!r}")
        return as_rational(magnitude, what=what) * unit_factor(value.units, unit, what=what)
    s = _check_text(value, what)
    try:
        return parse_expression(s, names=names, what=what)
    except InputError as plain:
        error = plain
    if _well_formed(s):  # a well-formed expression that was refused (out of range, a name not allowed) has no unit
        raise error
    refused: InputError | None = None
    for m in _UNIT_START.finditer(s):  # the unit starts at the first place where both halves parse
        number, unit_text = s[: m.start()].strip(), s[m.end():].strip()
        if not number:
            continue
        try:
            magnitude = parse_expression(number, names=names, what=what)
        except InputError as err:
            if _well_formed(number):  # a number refused (out of range, ...): say that, not "unknown unit"
                refused = err
            continue
        try:  # a number, then what must be a unit (_parse_unit checks its allow-list first)
            return magnitude * unit_factor(unit_text, unit, what=what)
        except InputError as err:
            error = err
    raise refused or error


def _well_formed(text: str) -> bool:
    try:
        ast.parse(text.replace("^", "**"), mode="eval")
    except SyntaxError:
        return False
    return True


def as_values(values: Any, *, what: str = "values") -> dict[str, sp.Expr]:
    """Numbers for symbols, keyed by name: from a mapping whose keys are SymPy symbols or names.

    Keys are matched by name, so ``Symbol("r_1")`` finds the engine's positive ``r_1``;
    every value passes :func:`as_expr` (text is parsed safely, never by sympify).

    >>> import sympy as sp
    >>> as_values({"r_1": "3/2", sp.Symbol("t"): 2})
    {'r_1': 3/2, 't': 2}
    """
    if values is None:
        return {}
    if not isinstance(values, Mapping):
        raise InputError(f"{what} are a mapping of symbol (or its name) to value, got {values!r}")
    out: dict[str, sp.Expr] = {}
    for key, value in values.items():
        if isinstance(key, sp.Symbol):
            name = key.name
        elif isinstance(key, str) and key.strip():
            name = key.strip()
        else:
            raise InputError(f"{what}: a key is a SymPy symbol or its name, got {key!r}")
        out[name] = as_expr(value, what=f"the value of {name}", names=())
    return out


def substitute(expr: Any, values: Mapping[Any, Any] | None) -> Any:
    """``expr`` (a SymPy expression or matrix) with the :func:`as_values` of ``values`` put in.

    >>> import sympy as sp
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


def as_float(value: Any, *, what: str, positive: bool = False, error: type[Exception] = InputError) -> float:
    """A finite float from a number, a constant expression or safe text (``"2*pi"``).

    >>> as_float("pi/2", what="time")
    1.5707963267948966
    """
    if type(value) is float or (type(value) is int and -_SMALL_INT <= value <= _SMALL_INT):  # no parsing needed
        if not math.isfinite(value):
            raise error(f"{what} must be a finite number, got {value!r}")
        if positive and not value > 0:
            raise error(f"{what} must be positive, got {value!r}")
        return float(value)
    try:
        expr = as_expr(value, what=what)
    except InputError as err:
        raise (err if error is InputError else error(str(err))) from None
    if not expr.is_number:
        raise error(f"{what} must be a number, got {value!r}")
    try:
        number = float(expr)
    except (TypeError, ValueError, OverflowError):
        raise error(f"{what} must be a real number, got {value!r}") from None
    if not math.isfinite(number):
        raise error(f"{what} must be a finite number, got {value!r}")
    if positive and not number > 0:
        raise error(f"{what} must be positive, got {value!r}")
    return number
