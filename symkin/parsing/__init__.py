"""Text to exact values: the one parser of what a user types.

symkin's functions take numbers, SymPy expressions, Fractions and pint quantities
(:mod:`symkin.values`); text enters at three borders only, the command line, train files and
the papers' reports, and is read here.  A string is never given to ``sympify`` (which
evaluates Python): it is parsed by :mod:`ast` and rebuilt from an allow-list of operators,
names and functions.  This is where the bounds on what a user types hold: at most
:data:`MAX_LENGTH` characters and :data:`MAX_DEPTH` levels of nesting, every number in an
expression (irrational ones and the results of powers and functions included) 0 or between
1e-300 and 1e300 in size, decided on intervals as it is built (:mod:`symkin._util.bounds`),
every exact number of at most :data:`MAX_EXACT_DIGITS` digits above and below its fraction bar,
a law of t smooth and its second derivative at most :data:`MAX_LAW_SIZE` nodes, and at most
:data:`SECONDS` seconds of CPU time to read one value.

    >>> import symkin
    >>> symkin.parse("2*pi*sin(t)", names=("t",))
    2*pi*sin(t)
    >>> symkin.parse("300 rpm", unit="rad/s"), symkin.parse("0.8")
    (10*pi, 4/5)
    >>> symkin.parse("exp(exp(9))")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: expression: exp(exp(9)) is about 10^3519; numbers from 1e-300 to 1e300 in size are accepted (this one is beyond the float64 range, about 1.8e308)
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import sympy as sp

from symkin.errors import InputError
from symkin.parsing.expressions import CONSTANTS, FUNCTIONS, MAX_DEPTH, MAX_EXPONENT, MAX_LAW_SIZE, parse_expression
from symkin.parsing.numbers import MAX_DIGITS, MAX_EXACT_DIGITS, MAX_LENGTH, SECONDS, parse_integer, parse_number
from symkin.parsing.quantities import parse_quantity
from symkin.values import sign_of

__all__ = [
    "parse",
    "parse_real",
    "parse_number",
    "parse_integer",
    "parse_expression",
    "parse_quantity",
    "FUNCTIONS",
    "CONSTANTS",
    "MAX_LENGTH",
    "MAX_DEPTH",
    "MAX_DIGITS",
    "MAX_EXACT_DIGITS",
    "MAX_EXPONENT",
    "MAX_LAW_SIZE",
    "SECONDS",
]


def parse(
    text: str,
    *,
    names: Iterable[str] = (),
    symbols: Mapping[str, sp.Expr] | None = None,
    unit: str | None = None,
    what: str = "expression",
) -> sp.Expr:
    """An exact SymPy expression from text a user typed.

    Parameters
    ----------
    text : str
        Numbers (exact as typed: ``0.1`` is 1/10), ``+ - * / **`` (or ``^``), parentheses,
        the constants ``pi`` and ``E``, the functions of :data:`FUNCTIONS`, and ``names``;
        with ``unit``, a unit may follow (``"300 rpm"``).
    names : iterable of str
        Names allowed as symbols (``"t"`` is :data:`symkin.symbols.t`, the time).
    symbols : mapping of str to expression, optional
        Names allowed with the value to put in their place.
    unit : str, optional
        The unit of the value in pint's spelling (``"rad/s"``, ``"rad"``, ``"m"``, ``"s"``):
        a unit in the text is converted to it exactly; a bare number is in it already.
    what : str
        What the value is, for error messages.

    Raises
    ------
    InputError
        One line that says what is wrong: a name or function not allowed, a number out of
        range, a malformed expression, an unknown unit or one of another kind.
    """
    if unit is None:
        return parse_expression(text, names=names, symbols=symbols, what=what)
    return parse_quantity(text, unit, what=what, names=names)


def parse_real(text: str, *, what: str = "value", unit: str | None = None, positive: bool = False,
               error: type[Exception] = InputError) -> sp.Expr:
    """An exact finite real constant from text (``"pi/6"``, ``"0.02"``, with ``unit`` also
    ``"20mm"``), positive when asked.

    >>> parse_real("pi/6"), parse_real("10 deg", unit="rad")
    (pi/6, pi/18)
    >>> parse_real("t + 1", what="the guide angle")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the guide angle: 't' is not allowed here; allowed names: E, pi; functions: ...
    """
    try:
        expr = parse(text, unit=unit, what=what)
    except InputError as err:
        raise (err if error is InputError else error(str(err))) from None
    if not expr.is_number:
        raise error(f"{what} must be a number, got {text!r}")
    if positive and sign_of(expr, what=what, error=error) != 1:
        raise error(f"{what} must be positive, got {text!r}")
    return expr
