"""The JSON shape of an exact number, shared by every ``to_json`` and the CLI.

An exact value (a tooth ratio, a total, a period of ``2*pi/omega``) is written as
``{"exact": text, "float": number or null}``: the text is exact and can be read back
with :func:`symkin.parsing.parse_expression`; the float is for plotting and sorting, and
``null`` where the value has none (a symbol, an infinity), so the JSON stays strict.

    >>> from fractions import Fraction
    >>> exact_json(Fraction(22, 7))
    {'exact': '22/7', 'float': 3.142857142857143}
    >>> import sympy as sp
    >>> exact_json(2 * sp.pi / 5)
    {'exact': '2*pi/5', 'float': 1.2566370614359172}
    >>> exact_json(None) is None
    True
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin.values import nearest_float as _float_of

__all__ = ["exact_json", "exact_json_list", "float_text"]


def exact_json(value: Any) -> dict[str, Any] | None:
    """``{"exact": str(value), "float": float or None}``; None stays None.

    Integers, :class:`fractions.Fraction`, SymPy numbers and constant expressions are
    accepted; a float is written as it is (its own exact value is its decimal).
    """
    if value is None:
        return None
    number: float | None = None
    if isinstance(value, Fraction):
        text = str(value)
        try:
            number = value.numerator / value.denominator
        except OverflowError:
            number = None
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        text, number = repr(value), float(value)
    else:
        expr = sp.sympify(value, strict=True)
        text = str(expr)
        if getattr(expr, "is_number", False):
            try:
                number = _float_of(expr)
            except (TypeError, ValueError, OverflowError):
                number = None
    finite = number is not None and math.isfinite(number)
    if not finite and (number is not None or getattr(value, "is_number", False) or isinstance(value, Fraction)):
        import warnings

        from symkin.errors import NullFloatWarning

        shown = text if len(text) <= 60 else text[:57] + "..."
        if text in ("zoo", "oo", "-oo", "nan") or number is not None:  # (a float that is there is inf or nan)
            why = "is not a finite number"
        elif getattr(value, "is_number", False) and sp.sympify(value).is_extended_real is False:
            why = "is not real"
        else:
            why = "is beyond the float range (the exact value stands)"
        warnings.warn(f"{shown} {why}: its JSON float is null", NullFloatWarning, stacklevel=2)
    return {"exact": text, "float": number if finite else None}


def exact_json_list(values: Iterable[Any] | None) -> list[dict[str, Any] | None] | None:
    """:func:`exact_json` of each value; None stays None.

    >>> exact_json_list([1, Fraction(1, 2)])
    [{'exact': '1', 'float': 1.0}, {'exact': '1/2', 'float': 0.5}]
    """
    return None if values is None else [exact_json(v) for v in values]


def float_text(value: Any) -> str:
    """The float beside an exact number, as text for a reader (10 significant digits);
    empty for a value that is not a number.

    >>> float_text(sp.Rational(7, 2)), float_text(sp.Symbol("x"))
    ('3.5', '')
    """
    expr = sp.sympify(value, strict=True)
    if not expr.is_number:
        return ""
    try:
        return f"{_float_of(expr):.10g}"
    except (TypeError, ValueError, OverflowError):
        return str(sp.N(expr, 10))
