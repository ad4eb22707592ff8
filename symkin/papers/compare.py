"""Comparisons of a derived object with a published one, and the verdicts judged from them.

Published items arrive as the text the paper prints (``"198"``, ``"0.080"``), read with the
parser (:mod:`symkin.parsing`), or as SymPy objects; equality is decided by exact rewriting
before ``simplify`` (:func:`proven_zero`, :func:`vanishes`), a rounded decimal by its printed
digits.

    >>> import sympy as sp
    >>> compare_rounded(sp.Rational(20000, 101), "198").verdict
    <Verdict.ROUNDED: 'match (published value rounded)'>
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from decimal import ROUND_HALF_UP, Decimal, InvalidOperation
from typing import Any

import sympy as sp

from symkin.papers.verdicts import Alternative, Comparison, Confirmation, Verdict
from symkin.parsing import parse, parse_number
from symkin.values import as_expr

__all__ = [
    "compare_symbolic", "compare_exact", "compare_rounded", "compare_inequality", "compare_digits", "compare_claim",
    "compare_each", "annotate", "alternative", "confirmation", "judge", "nonzero_somewhere", "vanishes",
    "proven_zero", "as_float",
]


# ---------------------------------------------------------------------------- numbers and text
def _expr(value: Any) -> Any:
    """A SymPy object from a value; text (a published item as printed) is parsed with the
    allow-list, never by Python."""
    if isinstance(value, str):
        return parse(value, what="a compared value")
    return as_expr(value, what="a compared value", finite=False)


def _exact(value: Any) -> sp.Expr:
    """An exact SymPy value: a Python float is read as the decimal it prints, a SymPy
    Float as its exact binary value; nothing is guessed (no nsimplify)."""
    if isinstance(value, float):
        return parse_number(repr(value), what="a compared value")
    expr = _expr(value)
    return expr.xreplace({f: sp.Rational(f) for f in expr.atoms(sp.Float)}) if isinstance(expr, sp.Basic) else expr


def as_float(value: Any) -> float | None:
    """The value as a float when it is one real number, else None.

    Text is read as a decimal (``"12.34e-3"``); an expression must be a real number.

    >>> as_float("12.34e-3"), as_float(sp.pi / 2), as_float("?00"), as_float(sp.Symbol("x"))
    (0.01234, 1.5707963267948966, None, None)
    """
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, (int, float)):
        return float(value) if math.isfinite(float(value)) else None
    if isinstance(value, str):
        try:
            d = Decimal(value.strip())
        except (InvalidOperation, ValueError):
            return None
        return float(d) if d.is_finite() else None
    if isinstance(value, sp.Basic) and isinstance(value, sp.Expr) and value.is_number:
        try:
            number = complex(sp.N(value, 30))
        except (TypeError, ValueError):
            return None
        if number.imag != 0 or not math.isfinite(number.real):
            return None
        return number.real
    return None


def _difference(derived: Any, published: Any, under: Mapping[Any, Any] | None) -> sp.Expr:
    d, p = _expr(derived), _expr(published)
    if under:
        d, p = d.subs(under), p.subs(under)
    diff = sp.cancel(sp.together(d - p))
    if diff != 0 and diff.has(sp.sin, sp.cos, sp.tan, sp.exp, sp.atan, sp.sqrt, sp.log) and not nonzero_somewhere(diff):
        diff = sp.Integer(0) if proven_zero(diff) else sp.simplify(diff)
    return diff


def nonzero_somewhere(expr: Any, tries: int = 2) -> bool:
    """True when ``expr`` is shown not identically zero by its value at random points.

    Every symbol gets a random rational in [1/2, 5/2] (positive, as lengths and tooth
    numbers are), evaluated with 30 digits; a value above 1e-15 proves the expression is
    not zero, so the exact (slow) simplification can be skipped.  False means undecided:
    an expression with undefined functions, or one that vanished at the points tried.

    >>> x = sp.Symbol("x")
    >>> nonzero_somewhere(sp.sin(x)**2 + sp.cos(x)**2 - 1), nonzero_somewhere(sp.sin(x) - x)
    (False, True)
    """
    import random

    if not isinstance(expr, sp.Expr) or expr.atoms(sp.core.function.AppliedUndef) or expr.has(sp.Derivative):
        return False
    rng = random.Random(20260101)
    symbols = sorted(expr.free_symbols, key=str)
    for _ in range(tries):
        point = {s: sp.Rational(rng.randint(50, 250), 100) for s in symbols}
        try:
            value = complex(expr.subs(point).evalf(30))
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if math.isfinite(abs(value)) and abs(value) > 1e-15:
            return True
    return False


def proven_zero(expr: Any) -> bool:
    """True when ``expr`` is shown identically zero by rewriting alone: cancelled as a rational
    function of its atoms, after expanding the trigonometric functions (sums of angles,
    multiples; sin(a)**2 written 1 - cos(a)**2) or writing them with the tangent of the half
    angle.  Every step is an identity,
    so True is a proof; False decides nothing (see :func:`vanishes`).

    >>> x, y = sp.symbols("x y")
    >>> proven_zero(sp.sin(x + y) - sp.sin(x) * sp.cos(y) - sp.cos(x) * sp.sin(y))
    True
    >>> proven_zero(sp.sqrt(x**2) - x)  # x may be negative: not zero
    False
    """
    e = sp.sympify(expr)
    if not isinstance(e, sp.Expr):
        return False
    if sp.cancel(sp.together(e)) == 0:
        return True
    if not e.has(sp.sin, sp.cos, sp.tan):
        return False
    numerator = sp.fraction(sp.cancel(sp.together(sp.expand_trig(e))))[0]
    if numerator == 0 or _pythagoras(sp.expand(numerator)) == 0:
        return True
    return bool(sp.cancel(sp.together(e.rewrite(sp.tan))) == 0)


def _pythagoras(poly: sp.Expr) -> sp.Expr:
    """``poly`` with every sin(a)**n, n >= 2, written with 1 - cos(a)**2, expanded (an identity)."""
    def lower(p: sp.Pow) -> sp.Expr:
        a, n = p.base.args[0], int(p.exp)
        return (1 - sp.cos(a) ** 2) ** (n // 2) * sp.sin(a) ** (n % 2)

    even = poly.replace(lambda x: x.is_Pow and isinstance(x.base, sp.sin) and x.exp.is_Integer and x.exp >= 2, lower)
    return sp.expand(even)


def vanishes(expr: Any) -> bool:
    """Whether ``expr`` is identically zero, decided by the cheapest exact means that decide it.

    A rational function with rational coefficients of symbols and of functions of further
    symbols (each its own, as ``cos(beta)``) is decided by cancelling it (exact both ways,
    the functions being independent variables); an expression that rewriting alone cancels is zero
    (:func:`proven_zero`); anything else is left to :func:`sympy.simplify`, which the
    answer then equals.

    >>> x, y = sp.symbols("x y")
    >>> vanishes((x**2 - y**2) / (x - y) - x - y), vanishes(x / sp.cos(y) - 1), vanishes(sp.sin(x)**2 + sp.cos(x)**2 - 1)
    (True, False, True)
    """
    e = sp.sympify(expr)
    if not isinstance(e, sp.Expr):
        return bool(sp.simplify(e) == 0)
    cancelled = sp.cancel(sp.together(e))
    if cancelled == 0:
        return True
    # functions of distinct symbols found nowhere else (cos(beta_1), cos(beta_2)) are
    # independent variables: the expression is then a rational function of them too
    calls = cancelled.atoms(sp.Function)
    inner = [f.args[0] for f in calls if len(f.args) == 1 and f.args[0].is_Symbol]
    rational = cancelled.xreplace({f: sp.Dummy() for f in calls})
    independent = len(inner) == len(calls) == len(set(inner)) and not set(inner) & rational.free_symbols
    plain = (independent and rational.free_symbols and rational.is_rational_function()
             and not rational.atoms(sp.NumberSymbol, sp.Float) and not rational.has(sp.I)
             and all(p.exp.is_Integer for p in rational.atoms(sp.Pow)))
    if plain:
        return False
    if proven_zero(e):
        return True
    return bool(sp.simplify(e) == 0)


# ---------------------------------------------------------------------------- comparators
def compare_symbolic(derived: Any, published: Any, *, under: Mapping[Any, Any] | None = None) -> Comparison:
    """Match when derived - published cancels to zero (after substituting ``under``).

    ``under`` states a condition the published form assumes (e.g. coaxiality
    ``{r_4: r_1 + r_2 + r_3}``); it is named in the detail.

    >>> r = sp.Symbol("r")
    >>> compare_symbolic(2 * r, r + r).verdict.value
    'match'
    """
    diff = _difference(derived, published, under)
    cond = ""
    if under:
        cond = " under " + ", ".join(f"{k} = {v}" for k, v in under.items())
    if diff == 0:
        return Comparison(Verdict.MATCH, f"derived - published = 0{cond}")
    return Comparison(Verdict.DIFFERS, f"derived - published = {_shorten(diff)}{cond}")


def _shorten(value: Any, limit: int = 400) -> str:
    """An expression as text, cut at ``limit`` characters (the report holds both objects whole)."""
    text = str(value)
    return text if len(text) <= limit else text[:limit] + " ... (not zero)"


def compare_exact(derived: Any, published: Any) -> Comparison:
    """Match when two exact numbers are equal; a float is taken as exactly what it is.

    >>> compare_exact(0.5, "1/2").verdict.value
    'match'
    >>> compare_exact(0.3333333333333333, "1/3").verdict.value
    'differs'
    """
    d, p = _exact(derived), _exact(published)
    if sp.simplify(d - p) == 0:
        return Comparison(Verdict.MATCH, f"exactly {d}")
    shown = f"{d} = {sp.N(d, 12)}" if isinstance(d, sp.Expr) and d.is_number else f"{d}"
    return Comparison(Verdict.DIFFERS, f"derived {shown}, published {p}")


def compare_rounded(derived: Any, published: str) -> Comparison:
    """Match when the published decimal is the derived value rounded half up to its printed digits.

    Exact equality is reported as a plain match; a published ``"12.34e-3"`` is read
    with its exponent (its printed digits are those of the mantissa).

    >>> compare_rounded(sp.Rational(5, 2), "3").verdict.value
    'match (published value rounded)'
    >>> compare_rounded(sp.Rational(5, 2), "2").verdict.value
    'differs'
    >>> compare_rounded(4 * sp.pi / 125, "100.53e-3").verdict.value
    'match (published value rounded)'
    """
    d = _exact(derived)
    text = str(published).strip()
    mantissa, _, exponent = text.lower().partition("e")
    scale = int(exponent) if exponent else 0
    if not (isinstance(d, sp.Expr) and d.is_number and d.is_real is not False):
        return Comparison(Verdict.DIFFERS, f"derived {d} is not a real number, published {text}")
    p = Decimal(mantissa)
    scaled = d * sp.Integer(10) ** (-scale)
    if _exact(mantissa) == scaled:
        return Comparison(Verdict.MATCH, f"exactly {d}")
    digits = p.as_tuple().exponent
    assert isinstance(digits, int)  # a finite decimal
    value = Decimal(str(sp.N(scaled, 60)))
    rounded = value.quantize(Decimal(1).scaleb(digits), rounding=ROUND_HALF_UP)
    unit = f" (x 1e{scale})" if scale else ""
    if rounded == p:
        places = f"{-digits} decimal{'s' * (digits != -1)}" if digits < 0 else "a whole number"
        return Comparison(
            Verdict.ROUNDED,
            f"derived {d} = {sp.N(scaled, 10)}{unit}; rounded half up to {places} it is the published {mantissa}{unit}",
        )
    return Comparison(Verdict.DIFFERS, f"derived {d} = {sp.N(scaled, 10)}{unit}, published {mantissa}{unit}")


_RELATIONS: dict[str, Callable[[Any, Any], Any]] = {
    ">": lambda a, b: a > b, ">=": lambda a, b: a >= b, "<": lambda a, b: a < b, "<=": lambda a, b: a <= b,
}


def compare_inequality(derived: Any, relation: str, bound: Any) -> Comparison:
    """Match when the derived number satisfies a published inequality ``derived <relation> bound``.

    >>> compare_inequality(sp.Rational(101, 2), ">", 50).verdict.value
    'match'
    >>> compare_inequality(40, ">", 50).verdict.value
    'differs'
    """
    if relation not in _RELATIONS:
        raise ValueError(f"relation must be one of {', '.join(_RELATIONS)}, got {relation!r}")
    d, b = _exact(derived), _exact(bound)
    if not (isinstance(d, sp.Expr) and d.is_number and d.is_real):
        return Comparison(Verdict.DIFFERS, f"derived {d} is not a real number; published {relation} {b}")
    holds = bool(_RELATIONS[relation](d, b))
    return Comparison(Verdict.MATCH if holds else Verdict.DIFFERS,
                      f"derived {d} = {sp.N(d, 10)} {'satisfies' if holds else 'does not satisfy'} {relation} {b}")


def compare_digits(derived: Any, published: str, illegible: str = "?") -> Comparison:
    """Match when a derived whole number agrees with every legible digit of a printed one.

    For numbers the OCR damaged (``"?00"``): the derived number must have as many digits
    and agree wherever a digit is legible.

    >>> compare_digits(200, "?00").verdict.value
    'match'
    >>> compare_digits(199, "?00").verdict.value
    'differs'
    """
    d = _exact(derived)
    if not (isinstance(d, sp.Expr) and d.is_Integer):
        return Comparison(Verdict.DIFFERS, f"derived {d} is not a whole number, printed {published}")
    digits, text = str(d), str(published)
    legible = [(a, b) for a, b in zip(digits, text) if b != illegible]
    if len(digits) == len(text) and legible and all(a == b for a, b in legible):
        lost = sum(b == illegible for b in text)
        return Comparison(Verdict.MATCH, f"derived {d} agrees with every legible digit of the printed {text} "
                                         f"({lost} digit{'s' * (lost != 1)} lost in the OCR)")
    return Comparison(Verdict.DIFFERS, f"derived {d} does not fit the printed {text}")


def compare_claim(holds: bool, detail: str) -> Comparison:
    """Match when a published claim, tested on the derived objects, holds.

    >>> compare_claim(1 + 1 == 2, "the sum is 2").verdict.value
    'match'
    """
    return Comparison(Verdict.MATCH if holds else Verdict.DIFFERS, ("holds: " if holds else "does not hold: ") + detail)


def compare_each(
    derived: Sequence[Any], published: Sequence[Any], compare: Callable[[Any, Any], Comparison] = compare_symbolic,
    names: Sequence[str] | None = None,
) -> Comparison:
    """Compare item by item; match when every pair agrees (rounded when one is rounded).

    >>> compare_each([1, 2], ["1", "2.0"], compare_rounded).verdict.value
    'match'
    """
    if len(derived) != len(published):
        return Comparison(Verdict.DIFFERS, f"{len(derived)} derived items, {len(published)} published")
    names = list(names) if names is not None else [str(n) for n in range(1, len(derived) + 1)]
    parts = [(n, compare(d, p)) for n, d, p in zip(names, derived, published)]
    detail = "; ".join(f"{n}: {c.detail}" for n, c in parts)
    if not all(c.verdict.agrees for _, c in parts):
        return Comparison(Verdict.DIFFERS, detail)
    rounded = any(c.verdict is Verdict.ROUNDED for _, c in parts)
    return Comparison(Verdict.ROUNDED if rounded else Verdict.MATCH, detail)


def annotate(comparison: Comparison, note: str) -> Comparison:
    """The same comparison with ``note`` added to its detail (the verdict is unchanged).

    >>> annotate(compare_exact(1, 1), "as printed").detail
    'exactly 1; as printed'
    """
    return Comparison(comparison.verdict, f"{comparison.detail}; {note}", comparison.alternative, comparison.confirmation)


# ---------------------------------------------------------------------------- verdicts
def alternative(
    assumption: str, value: Any, published: Any, compare: Callable[[Any, Any], Comparison] = compare_symbolic
) -> Alternative:
    """The derivation's value under ``assumption``, compared with the published item.

    >>> alternative("omega = 1", 2 * sp.pi, 2 * sp.pi, compare_exact).matches_published
    True
    """
    return Alternative(assumption, value, compare(value, published))


def confirmation(
    route: str, value: Any, derived: Any, compare: Callable[[Any, Any], Comparison] = compare_symbolic
) -> Confirmation:
    """The value of a second, independent route, compared with the derived value.

    >>> confirmation("by hand", sp.Rational(1, 2), sp.Rational(2, 4)).agrees_with_derived
    True
    """
    return Confirmation(route, value, compare(value, derived))


def judge(
    primary: Comparison,
    *,
    alternative: Alternative | None = None,
    confirmation: Confirmation | None = None,
    hypothesis: str = "",
) -> Comparison:
    """The verdict of a check from its primary comparison and the evidence offered.

    ``primary`` compares the derived with the published object (a ``compare_*``
    result).  When it agrees, that is the verdict.  Otherwise: ``paper slip
    (explained)`` when ``alternative`` reproduces the published item; else ``paper error
    (confirmed)`` when ``confirmation`` agrees with the derived value; else ``differs``,
    naming ``hypothesis`` (a cause that is not computed) as a hypothesis.

    >>> bad = compare_exact(3, 4)
    >>> judge(bad, hypothesis="a typo").verdict.value
    'differs'
    >>> judge(bad, confirmation=confirmation("counted by hand", 3, 3, compare_exact)).verdict.value
    'paper error (confirmed)'
    """
    if primary.verdict is Verdict.SLIP or primary.verdict is Verdict.ERROR:
        raise ValueError("judge takes the primary comparison of derived and published, not a verdict already judged")
    if primary.verdict.agrees:
        return primary
    parts = [primary.detail]
    if alternative is not None:
        state = "reproduces the published item" if alternative.matches_published else "does not reproduce it either"
        parts.append(f"alternative ({alternative.assumption}) {state}: {alternative.comparison.detail}")
        if alternative.matches_published:
            return Comparison(Verdict.SLIP, "; ".join(parts), alternative, confirmation)
    if confirmation is not None:
        state = "agrees with the derived value" if confirmation.agrees_with_derived else "does not agree with the derived value"
        parts.append(f"independent route ({confirmation.route}) {state}: {confirmation.comparison.detail}")
        if confirmation.agrees_with_derived:
            if hypothesis:
                parts.append(f"possible cause (a hypothesis, not computed): {hypothesis}")
            return Comparison(Verdict.ERROR, "; ".join(parts), alternative, confirmation)
    if hypothesis:
        parts.append(f"possible cause (a hypothesis, not computed): {hypothesis}")
    return Comparison(Verdict.DIFFERS, "; ".join(parts), alternative, confirmation)
