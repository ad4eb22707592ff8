"""Quantities typed by a user: a number or constant expression followed by a unit.

The number is read by :func:`~symkin.parsing.expressions.parse_expression` (exact, from the
allow-list); the unit by pint's own parser after an allow-list check (letters, digits,
``* / ^ **``; never Python), and converted exactly (:func:`symkin.values.unit_factor`).

    >>> parse_quantity("300 rpm", "rad/s"), parse_quantity("90deg", "rad"), parse_quantity("5 mm", "m")
    (10*pi, pi/2, 1/200)
"""

from __future__ import annotations

import ast
import re
from collections.abc import Iterable
from typing import Any

import sympy as sp

from symkin.errors import InputError
from symkin.parsing.expressions import parse_expression
from symkin.parsing.numbers import _BARE_EXPONENT, _check_text
from symkin.values import as_expr, is_quantity, unit_factor

__all__ = ["parse_quantity", "unit_of", "MAX_UNIT_LENGTH"]

#: The text of a unit: a name and products, quotients and integer powers of names.
_UNIT_TEXT = re.compile(r"^[A-Za-z_°µ][A-Za-z0-9_°µ]*(\s*(\*\*|[*/^])?\s*[A-Za-z0-9_°µ.-]+)*$")
#: Where a unit may start: a letter after a digit, a closing parenthesis or a space.
_UNIT_START = re.compile(r"(?<=[0-9.)\s])\s*(?=[A-Za-z_°µ])")
MAX_UNIT_LENGTH = 40


def _unit_factor(text: str, unit: str, what: str) -> sp.Expr:
    """The exact factor of a unit typed by a user (checked against the allow-list first)."""
    text = text.strip()
    if len(text) > MAX_UNIT_LENGTH or not _UNIT_TEXT.match(text):
        raise InputError(f"{what}: {text[:60]!r} is not a unit; write a number and a unit such as 300 rpm, 10 deg, 5 mm")
    return unit_factor(text, unit, what=what)


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
        return as_expr(value, what=what, unit=unit)
    return _read(_check_text(value, what), unit, what, names)[0]


def unit_of(text: str, unit: str) -> str | None:
    """The unit a user typed after a number (``"rpm"`` in ``"300 rpm"``), a unit of ``unit``'s
    kind, or None for a bare number (or text that is not a quantity).

    >>> unit_of("300 rpm", "rad/s"), unit_of("2*pi", "rad/s"), unit_of("90deg/s", "rad/s")
    ('rpm', None, 'deg/s')
    """
    try:
        return _read(_check_text(text, "value"), unit, "value", ())[1]
    except InputError:
        return None


def _read(s: str, unit: str, what: str, names: Iterable[str]) -> tuple[sp.Expr, str | None]:
    """The value of ``s`` in ``unit`` and the unit as typed (None for a bare number)."""
    try:
        return parse_expression(s, names=names, what=what), None
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
        try:  # a number, then what must be a unit (_unit_factor checks its allow-list first)
            return magnitude * _unit_factor(unit_text, unit, what=what), unit_text
        except InputError as err:
            error = err
    raise refused or error


def _well_formed(text: str) -> bool:
    try:
        ast.parse(text.replace("^", "**"), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):  # (a byte that is not UTF-8: UnicodeEncodeError)
        return False
    return True
