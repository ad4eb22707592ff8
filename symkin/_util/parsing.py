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
from collections.abc import Callable, Iterable, Mapping
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin._util import bounds
from symkin._util.budget import time_limit
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
    "check_numbers",
    "sign_of",
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
#: Nesting allowed in an expression (a flat sum or product of many terms counts as one level).
MAX_DEPTH = 60
MAX_EXPONENT = 1000
#: Numbers are accepted between 10^-MAX_DIGITS and 10^MAX_DIGITS in size (or 0), so every
#: number a user gives also has a finite, non-zero float (floats end near 1.8e308).  This
#: holds for every number in an expression, irrational ones and the results of powers and
#: functions included, each checked as it is built (:mod:`symkin._util.bounds`).
MAX_DIGITS = bounds.MAX_DIGITS
_HUGE = sp.Integer(10) ** MAX_DIGITS
_SAFE_BITS = int(MAX_DIGITS * math.log2(10))  # 2^996 < 10^300
#: Seconds the parsing and bounding of one expression may take.
SECONDS = 3.0

#: 1,5 (a decimal comma, read by Python as a tuple) and 1e (an exponent without digits).
_COMMA_DECIMAL = re.compile(r"^\s*[+-]?\d+,\d+\s*$")
_BARE_EXPONENT = re.compile(r"^\s*[+-]?(\d+\.?\d*|\.\d+)[eE][+-]?\s*$")
_NUMBER = re.compile(r"^[+-]?(\d+(_?\d+)*)?(\.\d*)?([eE][+-]?\d+)?$|^[+-]?\d+\s*/\s*\d+$", re.ASCII)


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


def _bounded(value: sp.Expr, what: str, error: type[Exception] = InputError) -> sp.Expr:
    """``value`` unless it is an exact number too large or too small (but not 0) to use."""
    if value.is_Rational and int(value.p).bit_length() <= _SAFE_BITS and int(value.q).bit_length() <= _SAFE_BITS:
        return value  # |p| and q below 2^996 < 10^300: within the bounds, no comparison needed (the common case)
    if value.is_Rational and value != 0:
        size = abs(value)
        if size > _HUGE or size * _HUGE < 1:
            raise error(
                f"{what} holds a number of about 10^{_exponent(size)}; numbers from 1e-{MAX_DIGITS} to "
                f"1e{MAX_DIGITS} in size are accepted"
            )
    return value


def _repr(value: Any) -> str:
    """``repr(value)`` for a message, shortened; never fails (an int of 10^5000 has no repr)."""
    try:
        text = repr(value)
    except ValueError:
        return bounds.show(value)
    return text if len(text) <= 80 else text[:77] + "..."


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
            raise InputError(f"{what} must be a number, not the string {_repr(value)}")
        return parse_number(value, what=what)
    if isinstance(value, bool) or value is None:
        raise InputError(f"{what} must be a number, got {_repr(value)}")
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
            raise InputError(f"{what} must be a finite number, got {_repr(value)}")
        return parse_number(repr(f) if isinstance(value, float) else str(value), what=what)
    raise InputError(f"{what} must be a number, got {_repr(value)}")


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
        raise error(f"{what} must be a whole number, got {_repr(value)}")
    number = as_rational(value, what=what, text=text, error=error)
    if not number.is_Integer:
        raise error(f"{what} must be a whole number, got {_repr(value)}")
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
    if not expr.is_number or expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
        raise error(f"{what} must be a finite real number, got {_repr(value)}")
    if not expr.is_Rational:
        check_numbers(expr, what, error)  # real, finite, and bounded
    if positive and sign_of(expr, what=what, error=error) != 1:
        raise error(f"{what} must be positive, got {_repr(value)}")
    return expr


def sign_of(expr: sp.Expr, *, what: str = "value", error: type[Exception] = InputError) -> int | None:
    """The sign of a constant expression, decided on intervals (:mod:`symkin._util.bounds`),
    not by SymPy's assumptions: -1, 0, 1, or None for a number that is 0 to 1233 digits
    without being written as 0.

    >>> sign_of(sp.pi - 3), sign_of(sp.Integer(0)), sign_of(sp.sin(1)**2 + sp.cos(1)**2 - 1) is None
    (1, 0, True)
    """
    if expr.is_Rational:
        return (expr.p > 0) - (expr.p < 0)
    try:
        with time_limit(SECONDS, f"{what} took longer than {SECONDS:g} s to evaluate; give a simpler value", error):
            return bounds.sign(expr)
    except bounds.NotReal as err:
        raise error(f"{what}: {bounds.show(err.node)} is not a real number: {err.reason}") from None
    except bounds.NotConstant:
        raise error(f"{what} must be a number, got {bounds.show(expr)}") from None


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
    if _COMMA_DECIMAL.match(s):
        raise InputError(f"{what} {text!r} is not a number: write a decimal point, as in {s.replace(',', '.', 1)}")
    if _BARE_EXPONENT.match(s):
        raise InputError(f"{what} {text!r} is not a number: an exponent needs its digits, as in {s.strip()}3")
    try:
        tree = ast.parse(source, mode="eval")
    except (SyntaxError, ValueError):
        odd = next((c for c in source if not c.isascii() or not c.isprintable()), None)
        if odd is not None:  # a look-alike of an operator or a bracket: name it
            raise InputError(
                f"{what} {text!r} is not a valid expression: the character {odd!r} (U+{ord(odd):04X}) is "
                "not allowed; write it in ASCII (* for a product, - for minus, ( ) for brackets)"
            ) from None
        raise InputError(f"{what} {text!r} is not a valid expression") from None
    except (RecursionError, MemoryError):
        raise InputError(f"{what} is nested too deeply to read; at most {MAX_DEPTH} levels are accepted") from None
    with time_limit(SECONDS, f"{what} took longer than {SECONDS:g} s to build and bound; write a simpler expression"):
        return _Builder(allowed, what, source).build(tree.body, 0)


#: Operators of one precedence level: a chain of them (a + b - c + ...) is one level of nesting.
_SUMS = (ast.Add, ast.Sub)
_PRODUCTS = (ast.Mult, ast.Div)


class _Builder:
    """Builds the SymPy expression node by node; every constant node is bounded before SymPy
    evaluates it (so neither its size nor the work to evaluate it can grow without limit)."""

    def __init__(self, allowed: Mapping[str, sp.Expr], what: str, source: str):
        self.allowed = allowed
        self.what = what
        self.source = source
        self.memo: dict[int, bounds.Encloser] = {}

    def fail(self, message: str) -> InputError:
        names = ", ".join(sorted(self.allowed, key=str.lower))
        return InputError(
            f"{self.what}: {message}; allowed names: {names}; functions: {', '.join(sorted(FUNCTIONS, key=str.lower))}"
        )

    def bounded(self, unevaluated: sp.Expr) -> None:
        """Refuse a constant that is not real, or is beyond 1e300 or below 1e-300 in size (not 0)."""
        if unevaluated.is_Rational:
            _bounded(unevaluated, self.what)
        elif not unevaluated.free_symbols:
            bounds.check(unevaluated, self.what, memo=self.memo)

    def sign(self, value: sp.Expr) -> int | None:
        """The sign of a constant (None for a symbolic value or one that is 0 to 1233 digits)."""
        if value.free_symbols:
            return None
        return bounds.sign(value, memo=self.memo)

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
            if isinstance(node.op, _SUMS + _PRODUCTS):
                return self.chain(node, depth)
            return self.binop(node, depth)
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                raise self.fail(f"calling {_show(node.func)} is not allowed")
            if node.keywords:
                raise self.fail("functions take no keyword arguments")
            args = [self.build(a, depth + 1) for a in node.args]
            function = FUNCTIONS[node.func.id]
            try:
                unevaluated = function(*args, evaluate=False)
            except TypeError:
                raise InputError(f"{self.what}: wrong number of arguments to {node.func.id}") from None
            self.bounded(unevaluated)
            return function(*args)
        raise self.fail(f"{_show(node)} ({type(node).__name__.lower()}) is not allowed")

    def chain(self, node: ast.BinOp, depth: int) -> sp.Expr:
        """A flat chain of + and - (or of * and /): one level of nesting however long, each
        partial result bounded."""
        kinds = _SUMS if isinstance(node.op, _SUMS) else _PRODUCTS
        steps: list[tuple[type, ast.AST]] = []
        first: ast.AST = node
        while isinstance(first, ast.BinOp) and isinstance(first.op, kinds):
            steps.append((type(first.op), first.right))
            first = first.left
        value = self.build(first, depth + 1)
        if kinds is _SUMS:
            terms = [value]
            for op, right in reversed(steps):
                term = self.build(right, depth + 1)
                terms.append(term if op is ast.Add else -term)
            total = sp.Add(*terms)  # at most MAX_LENGTH / 2 terms each below 1e300: only the total needs a bound
            self.bounded(total)
            return total
        for op, right in reversed(steps):
            factor = self.build(right, depth + 1)
            if op is ast.Div:
                if factor == 0 or self.sign(factor) == 0:
                    raise InputError(f"{self.what} divides by zero")
                inverse = sp.Pow(factor, -1, evaluate=False)
                self.bounded(inverse)
                self.bounded(sp.Mul(value, inverse, evaluate=False))
                value = value / factor
            else:
                self.bounded(sp.Mul(value, factor, evaluate=False))
                value = value * factor
        return value

    def binop(self, node: ast.BinOp, depth: int) -> sp.Expr:
        left = self.build(node.left, depth + 1)
        right = self.build(node.right, depth + 1)
        if isinstance(node.op, ast.Pow):
            if not right.free_symbols and self.sign(sp.Add(sp.Abs(right, evaluate=False), -MAX_EXPONENT, evaluate=False)) == 1:
                raise InputError(f"{self.what} has an exponent larger than {MAX_EXPONENT}")
            if (left == 0 or self.sign(left) == 0) and self.sign(right) == -1:
                raise InputError(f"{self.what} divides by zero")
            self.bounded(sp.Pow(left, right, evaluate=False))
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
                f"{what} must be a number or a SymPy expression, not the string {_repr(value)}; "
                "parse text with symkin._util.parsing.parse_expression"
            )
        return parse_expression(value, names=names, what=what)
    if isinstance(value, bool) or value is None:
        raise error(f"{what} must be a number or an expression, got {_repr(value)}")
    try:
        expr = sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError, ValueError):
        raise error(f"{what} must be a number or an expression, got {_repr(value)}") from None
    if not isinstance(expr, sp.Expr):
        raise error(f"{what} must be a scalar expression, got {_repr(value)}")
    if expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
        if finite and expr.is_number:
            raise error(f"{what} must be a finite real number, got {_repr(value)}")
        return expr  # the caller words its own message (finite=False)
    check_numbers(expr, what, error)
    if finite and expr.is_number and expr.is_extended_real is False:
        raise error(f"{what} must be a finite real number, got {_repr(value)}")
    return expr


def check_numbers(expr: sp.Expr, what: str, error: type[Exception] = InputError, *, rationals: bool = True) -> None:
    """Refuse a number in ``expr`` (every constant part of it) that is not real or is beyond
    1e300 or below 1e-300 in size (and not 0), as :func:`parse_expression` does for text.

    With ``rationals=False`` an exact rational on its own is taken at any size (it is finite
    and exact; whether a float can hold it is the caller's question, as in ``compile``).

    >>> t = sp.Symbol("t")
    >>> check_numbers(t * sp.exp(2), "the law")
    >>> check_numbers(t + sp.tan(sp.pi / 2, evaluate=False), "the law")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the law: tan(pi/2) is infinite or cannot be bounded (a pole or an overflow); numbers from 1e-300 to 1e300 in size are accepted
    """
    if expr.is_Atom:
        if expr.is_Rational:
            if rationals:
                _bounded(expr, what, error)
        elif expr.is_Float:
            bounds.check(expr, what, error=error)
        elif expr.is_number and expr.is_extended_real is False:
            raise error(f"{what} must be a finite real number, got {expr}")
        return
    memo: dict[int, bounds.Encloser] = {}
    try:
        with time_limit(SECONDS, f"{what} took longer than {SECONDS:g} s to bound; give a simpler value", error):
            _constant_parts(expr, what, error, memo, rationals)
    except RecursionError:
        raise error(f"{what} is nested too deeply to check") from None


def _constant_parts(
    e: Any, what: str, error: type[Exception], memo: dict[int, bounds.Encloser], rationals: bool = True
) -> bool:
    """Whether ``e`` is a constant; every constant part of it is bounded on the way."""
    if e.is_Atom:
        if e.is_Rational:
            if rationals:
                _bounded(e, what, error)
        elif e.is_Float:
            bounds.check(e, what, memo=memo, error=error)
        return isinstance(e, sp.Expr) and bool(e.is_number)
    parts = [_constant_parts(a, what, error, memo, rationals) for a in e.args]
    if isinstance(e, sp.Expr) and all(parts) and e.is_number:
        bounds.check(e, what, memo=memo, error=error)
        return True
    return False


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
    >>> unit_factor("Hz", "rad/s")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: value: Hz gives no angle, and rad/s measures one (is 1 Hz one turn a second, 2 pi rad/s, or 1 rad/s?); write it in a unit such as rps (turns a second), rpm, rad/s, deg/s
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
    to_angle, from_angle = _angle_power(reg, dst), _angle_power(reg, src)
    if to_angle != from_angle:
        # pint takes the radian for a pure number, so 5 Hz would pass as 5 rad/s, not 5 turns a second
        if to_angle > from_angle:
            why = f"{src:~} gives no angle, and {unit_to} measures one" + (
                " (is 1 Hz one turn a second, 2 pi rad/s, or 1 rad/s?)" if unit_to == "rad/s" else "")
        else:
            why = f"{src:~} measures an angle, and {unit_to} does not"
        raise InputError(f"{what}: {why}; write it in a unit such as {_SUGGESTED.get(unit_to, unit_to)}")
    for power in (0, 1, -1):
        r = Fraction(f / math.pi**power).limit_denominator(10**6)
        if r and abs(float(r) * math.pi**power - f) <= 1e-14 * abs(f):
            return sp.Rational(r.numerator, r.denominator) * sp.pi**power
    return sp.Rational(*Fraction(f).as_integer_ratio())


#: Units to suggest for a quantity given in a unit of the wrong kind.
_SUGGESTED = {"rad/s": "rps (turns a second), rpm, rad/s, deg/s", "rad/s^2": "rad/s^2, deg/s^2, rpm/s", "rad": "deg, rad, turn"}


def _angle_power(reg: Any, unit: Any) -> float:
    """The power of the radian in ``unit``'s root units (1 for rad/s and rpm, 0 for Hz and mm)."""
    return float(dict(reg.get_root_units(unit)[1]._units).get("radian", 0))


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
    # a well-formed expression that was refused (out of range, a name not allowed) has no unit; nor has
    # 1e (not 1 of the unit e, the elementary charge)
    if _well_formed(s) or _BARE_EXPONENT.match(s):
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
            raise error(f"{what} must be a finite number, got {_repr(value)}")
        if positive and not value > 0:
            raise error(f"{what} must be positive, got {_repr(value)}")
        return float(value)
    try:
        expr = as_expr(value, what=what)
    except InputError as err:
        raise (err if error is InputError else error(str(err))) from None
    if not expr.is_number:
        raise error(f"{what} must be a number, got {_repr(value)}")
    try:
        with time_limit(SECONDS, f"{what} took longer than {SECONDS:g} s to evaluate; give a simpler value", error):
            number = bounds.to_float(expr)
    except (bounds.NotReal, bounds.Undecided):
        raise error(f"{what} must be a real number, got {_repr(value)}") from None
    except (bounds.Unbounded, bounds.OutOfRange, bounds.NotConstant):
        raise error(f"{what} must be a finite number, got {_repr(value)}") from None
    if not math.isfinite(number):
        raise error(f"{what} must be a finite number, got {_repr(value)}")
    if positive and not number > 0:
        raise error(f"{what} must be positive, got {_repr(value)}")
    return number
