"""Numbers typed by a user: exact rationals, bounded in size and digits.

    >>> parse_number("0.8"), parse_number("1e3"), parse_number("-3/4")
    (4/5, 1000, -3/4)
"""

from __future__ import annotations

import math
import re
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin._util import bounds
from symkin.errors import InputError

__all__ = ["parse_number", "parse_integer", "MAX_LENGTH", "MAX_DIGITS", "MAX_EXACT_DIGITS", "SECONDS"]

MAX_LENGTH = 2000
#: Numbers are accepted between 10^-MAX_DIGITS and 10^MAX_DIGITS in size (or 0), so every
#: number a user gives also has a finite, non-zero float (floats end near 1.8e308).  This
#: holds for every number in an expression, irrational ones and the results of powers and
#: functions included, each checked as it is built (:mod:`symkin._util.bounds`).
MAX_DIGITS = bounds.MAX_DIGITS
_HUGE = sp.Integer(10) ** MAX_DIGITS
_SAFE_BITS = int(MAX_DIGITS * math.log2(10))  # 2^996 < 10^300
#: Digits of the numerator and of the denominator of every exact number in what a user types
#: (the longest literal needs about 600): a number near 1 can carry any number of digits within
#: the size bounds, ``(1 - 10**-300)**1000`` 300,000 of them, and every later step pays for them.
MAX_EXACT_DIGITS = 1000
_EXACT_BITS = int(MAX_EXACT_DIGITS * math.log2(10))  # 2^3321 < 10^1000
#: CPU seconds the parsing and bounding of one expression may take (the process's CPU time, not the clock's).
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
    """``value`` unless it is an exact number too large or too small (but not 0) to use, or
    one with more than :data:`MAX_EXACT_DIGITS` digits above or below its fraction bar."""
    if value.is_Rational and int(value.p).bit_length() <= _SAFE_BITS and int(value.q).bit_length() <= _SAFE_BITS:
        return value  # |p| and q below 2^996 < 10^300: within the bounds, no comparison needed (the common case)
    if value.is_Rational:
        exact_digits(value, what, error)
    if value.is_Rational and value != 0:
        size = abs(value)
        if size > _HUGE or size * _HUGE < 1:
            raise error(
                f"{what} holds a number of about 10^{_exponent(size)}; numbers from 1e-{MAX_DIGITS} to "
                f"1e{MAX_DIGITS} in size are accepted"
            )
    return value


def exact_digits(value: sp.Expr, what: str, error: type[Exception] = InputError, *, power: Any = 1) -> None:
    """Refuse an expression whose exact numbers (raised to ``power``, before SymPy raises them:
    a sum raised to a power is multiplied out by a later expand) have more than
    :data:`MAX_EXACT_DIGITS` digits in a numerator or a denominator.

    >>> exact_digits(sp.Rational(10**300 - 1, 10**300), "--length", power=1000)
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: --length holds an exact number of about 300000 digits (its numerator or denominator); at most 1000 are accepted: write it with fewer digits, or as a decimal
    """
    if value.is_Rational:
        numbers = [value]
    elif value.is_Mul:  # what SymPy multiplies out when it raises a product to a power
        numbers = [a for a in (value, *value.args) if a.is_Rational or (a.is_Pow and a.base.is_Rational)]
        numbers = [a.as_coeff_Mul()[0] if a.is_Mul else a.base if a.is_Pow else a for a in numbers]
    else:
        numbers = list(value.atoms(sp.Rational))
    bits = max((math.log2(abs(n)) for r in numbers for n in (int(r.p), int(r.q)) if n), default=0.0)
    if power != 1:
        bits *= math.ceil(abs(power))
    if bits > _EXACT_BITS:
        raise error(
            f"{what} holds an exact number of about {int(bits * math.log10(2))} digits (its numerator or "
            f"denominator); at most {MAX_EXACT_DIGITS} are accepted: write it with fewer digits, or as a decimal"
        )


def _repr(value: Any) -> str:
    """``repr(value)`` for a message, shortened; never fails (an int of 10^5000 has no repr)."""
    try:
        text = repr(value)
    except ValueError:
        return bounds.show(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _exponent(size: sp.Rational) -> int:
    return round((int(size.p).bit_length() - int(size.q).bit_length()) * math.log10(2))


def parse_integer(text: str, *, what: str = "value", minimum: int | None = None,
                  maximum: int | None = None) -> sp.Integer:
    """An exact integer, within ``[minimum, maximum]`` when they are given; a fraction or
    decimal with a fractional part is refused.

    >>> parse_integer("100")
    100
    >>> parse_integer("0", what="--fps", minimum=1)
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: --fps must be at least 1, got 0
    """
    from symkin.values import as_integer

    value = parse_number(text, what=what)
    if not value.is_Integer:
        raise InputError(f"{what} must be a whole number, got {text!r}")
    return as_integer(value, what=what, minimum=minimum, maximum=maximum)


