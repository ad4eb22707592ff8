"""Checks of derived results against published ones, and their computed verdicts.

A derivation module (``symkin.derivations.<paper>``) returns a list of :class:`Check`.
Each holds a derived object, a published object, its :class:`Kind` (an item printed in
the paper, a consistency check between two routes of the engine, or an extension beyond
the paper) and a :class:`Comparison` whose verdict is a function of the two objects,
computed on every run:

- ``match``: the two agree exactly (a symbolic difference that cancels, equal exact
  numbers, a claim that holds);
- ``match (published value rounded)``: the published decimal is the derived value
  rounded to its printed digits;
- ``paper slip (explained)``: they disagree, and a computed *alternative* (the same
  derivation under a stated assumption, e.g. another input value) reproduces the
  published item (:class:`Alternative`);
- ``paper error (confirmed)``: they disagree, no alternative reproduces the printed
  item, and a second, independent route confirms the derived value
  (:class:`Confirmation`);
- ``differs``: anything else.  Only this verdict makes ``symkin reproduce`` exit 1.

:func:`judge` is the only way to reach the last three: a slip or an error cannot be
attached by hand (:class:`Comparison` refuses one without its evidence).

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> compare_symbolic((x**2 - 1) / (x - 1), x + 1).verdict
    <Verdict.MATCH: 'match'>
    >>> compare_rounded(sp.Rational(20000, 101), "198").verdict
    <Verdict.ROUNDED: 'match (published value rounded)'>
    >>> period = lambda omega: 2 * sp.pi / omega  # a derivation, run under two assumptions
    >>> c = judge(compare_exact(period(sp.Rational(4, 5) * sp.pi), 2 * sp.pi),
    ...           alternative=alternative("omega_H = 1 rad/s", period(1), 2 * sp.pi, compare_exact))
    >>> c.verdict.value, c.alternative.matches_published
    ('paper slip (explained)', True)
"""

from __future__ import annotations

import enum
import math
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from decimal import ROUND_HALF_UP, Decimal, InvalidOperation
from typing import Any

import sympy as sp

from symkin._util.display import markdown_table
from symkin.parsing import parse, parse_number
from symkin.printing import latex
from symkin.values import as_expr

__all__ = [
    "Kind",
    "Verdict",
    "Comparison",
    "Alternative",
    "Confirmation",
    "Check",
    "PrintedItem",
    "ItemResult",
    "compare_symbolic",
    "compare_exact",
    "compare_rounded",
    "compare_inequality",
    "compare_digits",
    "compare_claim",
    "compare_each",
    "annotate",
    "alternative",
    "confirmation",
    "judge",
    "item_results",
    "nonzero_somewhere",
    "vanishes",
    "proven_zero",
    "as_float",
]


class Kind(str, enum.Enum):
    """What a check compares.

    ``paper``: an item printed in the paper (an equation, a number, a claim) against its
    derivation; ``consistency``: two routes of the engine against each other;
    ``extension``: a result beyond the paper (a generalisation, a check the paper does
    not make).  Only ``paper`` checks count as reproductions.
    """

    PAPER = "paper"
    CONSISTENCY = "consistency"
    EXTENSION = "extension"


class Verdict(str, enum.Enum):
    """The verdict of a check, computed by :func:`judge` from the comparison and its evidence.

    ``MATCH`` and ``ROUNDED``: derived and published agree (exactly, or the published decimal is
    the derived value rounded); ``SLIP``: they disagree and an :class:`Alternative` reproduces the
    published item; ``ERROR``: they disagree, nothing reproduces it, and a :class:`Confirmation`
    confirms the derived value; ``DIFFERS``: anything else.

    >>> Verdict.SLIP.value, Verdict.DIFFERS.ok
    ('paper slip (explained)', False)
    """
    MATCH = "match"
    ROUNDED = "match (published value rounded)"
    SLIP = "paper slip (explained)"
    ERROR = "paper error (confirmed)"
    DIFFERS = "differs"

    @property
    def ok(self) -> bool:
        """True unless the verdict is ``differs`` (the only verdict that fails a run)."""
        return self is not Verdict.DIFFERS

    @property
    def agrees(self) -> bool:
        """True for ``match`` and ``match (published value rounded)``."""
        return self in (Verdict.MATCH, Verdict.ROUNDED)


#: Verdicts from the best to the worst: an item with several checks takes the worst.
SEVERITY = (Verdict.MATCH, Verdict.ROUNDED, Verdict.SLIP, Verdict.ERROR, Verdict.DIFFERS)


@dataclass(frozen=True)
class Alternative:
    """The derivation under another assumption, compared with the published item.

    Build it with :func:`alternative`, which runs the comparison.
    """

    assumption: str
    value: Any
    comparison: Comparison

    @property
    def matches_published(self) -> bool:
        """Whether the derivation under the alternative assumption reproduces the published item."""
        return self.comparison.verdict.agrees


@dataclass(frozen=True)
class Confirmation:
    """A second, independent route to the derived value, compared with it.

    Build it with :func:`confirmation`, which runs the comparison.
    """

    route: str
    value: Any
    comparison: Comparison

    @property
    def agrees_with_derived(self) -> bool:
        """Whether the independent route gives the derived value."""
        return self.comparison.verdict.agrees


@dataclass(frozen=True)
class Comparison:
    """A verdict and what it rests on.

    ``paper slip (explained)`` needs an :class:`Alternative` that reproduces the
    published item; ``paper error (confirmed)`` a :class:`Confirmation` that agrees with
    the derived value and no alternative that reproduces the item.  Anything else raises
    :class:`ValueError`: such a verdict cannot be attached, only reached by :func:`judge`.

    >>> Comparison(Verdict.SLIP, "a typo")
    Traceback (most recent call last):
    ...
    ValueError: a paper slip needs a computed alternative that reproduces the published item (a typo)
    """

    verdict: Verdict
    detail: str = ""
    alternative: Alternative | None = None
    confirmation: Confirmation | None = None

    def __post_init__(self) -> None:
        explained = self.alternative is not None and self.alternative.matches_published
        if self.verdict is Verdict.SLIP and not explained:
            raise ValueError(f"a paper slip needs a computed alternative that reproduces the published item ({self.detail})")
        if self.verdict is Verdict.ERROR and (
            explained or self.confirmation is None or not self.confirmation.agrees_with_derived
        ):
            raise ValueError(
                "a confirmed paper error needs an independent route that agrees with the derived value, "
                f"and no alternative that reproduces the printed item ({self.detail})"
            )


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


# ---------------------------------------------------------------------------- checks and items
@dataclass(frozen=True)
class Check:
    """One comparison of a derived object with a published (or second derived) one.

    Attributes
    ----------
    paper, label : str
        The paper's key and a label unique within the paper.
    description : str
    derived, published : Any
        The two objects compared (laws, expressions, numbers, text).
    comparison : Comparison
        The computed verdict and its evidence.
    derived_latex, published_latex : str
    extra : mapping
        Further data shown in the report (parameters, sensitivity, ...).
    kind : Kind
        ``paper``, ``consistency`` or ``extension``.
    item : str
        The printed item a ``paper`` check compares (see :class:`PrintedItem`); the label
        when not given.
    source : str
        ``"printed"`` when the published object is what the paper prints (in its OCR),
        ``"reconstructed"`` when the OCR lost it and the form compared is reconstructed
        from the paper's text.
    """

    paper: str
    label: str
    description: str
    derived: Any
    published: Any
    comparison: Comparison
    derived_latex: str = ""
    published_latex: str = ""
    extra: Mapping[str, Any] = field(default_factory=dict)
    kind: Kind = Kind.PAPER
    item: str = ""
    source: str = "printed"

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", Kind(self.kind))
        if self.source not in ("printed", "reconstructed"):
            raise ValueError(f"source is 'printed' or 'reconstructed', got {self.source!r}")
        if not self.item:
            object.__setattr__(self, "item", self.label)

    @classmethod
    def make(
        cls,
        paper: str,
        label: str,
        description: str,
        derived: Any,
        published: Any,
        comparison: Comparison,
        *,
        kind: Kind | str = Kind.PAPER,
        item: str = "",
        source: str = "printed",
        **extra: Any,
    ) -> Check:
        """A check from its parts, with the LaTeX of the derived and the published objects printed once here."""
        return cls(paper, label, description, derived, published, comparison, _tex(derived), _tex(published), extra,
                   Kind(kind), item, source)

    @property
    def verdict(self) -> Verdict:
        """The computed verdict of the check's comparison."""
        return self.comparison.verdict

    def once(self, key: str, compute: Callable[[], Any]) -> Any:
        """``compute()``, kept on the check after the first call under ``key`` (a check does not
        change): the printed forms of its values, which ``symkin reproduce`` has the worker
        process that derived the check make, and which travel with it to the report.

        >>> c = Check.make("p", "(1)", "one", 1, 1, compare_exact(1, 1))
        >>> c.once("x", lambda: "printed"), c.once("x", lambda: "again")
        ('printed', 'printed')
        """
        kept = self.__dict__.setdefault("_kept", {})
        if key not in kept:
            kept[key] = compute()
        return kept[key]

    @property
    def derived_text(self) -> str:
        """The derived value as plain text (the items of a sequence joined by a semicolon and a space)."""
        return str(self.once("derived_text", lambda: _plain(self.derived)))

    @property
    def published_text(self) -> str:
        """The published value as plain text (the items of a sequence joined by a semicolon and a space)."""
        return str(self.once("published_text", lambda: _plain(self.published)))

    def _repr_markdown_(self) -> str:
        """The check for Jupyter: its heading, derived and published as math, the verdict.

        >>> print(Check.make("p", "(1)", "one", 1, 1, compare_exact(1, 1))._repr_markdown_())
        **(1)**: one
        <BLANKLINE>
        |  | value |
        |---|---|
        | derived | $1$ |
        | published | $1$ |
        | verdict | **match** (paper item): exactly 1 |
        """
        rows = [["derived", f"${self.derived_latex}$" if self.derived_latex else str(self.derived)],
                ["published", f"${self.published_latex}$" if self.published_latex else str(self.published)],
                ["verdict", f"**{self.verdict.value}** ({self.kind.value} item): {self.comparison.detail}"
                 if self.kind is Kind.PAPER else f"**{self.verdict.value}** ({self.kind.value}): {self.comparison.detail}"]]
        return f"**{self.label}**: {self.description}\n\n" + markdown_table(["", "value"], rows)

    def to_json(self) -> dict[str, Any]:
        """The check as report.json holds it (see ``symkin/papers/report.schema.json``)."""
        alt, conf = self.comparison.alternative, self.comparison.confirmation
        return {
            "paper": self.paper,
            "label": self.label,
            "item": self.item,
            "kind": self.kind.value,
            "source": self.source,
            "description": self.description,
            "derived": self.derived_text,
            "derived_latex": self.derived_latex,
            "derived_float": as_float(self.derived),
            "published": self.published_text,
            "published_latex": self.published_latex,
            "published_float": as_float(self.published),
            "verdict": self.verdict.value,
            "ok": self.verdict.ok,
            "detail": self.comparison.detail,
            "alternative": None if alt is None else {
                "assumption": alt.assumption,
                "value": self.once("alternative_text", lambda: _plain(alt.value)),
                "value_latex": self.once("alternative_latex", lambda: _tex(alt.value)),
                "value_float": as_float(alt.value),
                "matches_published": alt.matches_published,
                "detail": alt.comparison.detail,
            },
            "confirmation": None if conf is None else {
                "route": conf.route,
                "value": self.once("confirmation_text", lambda: _plain(conf.value)),
                "value_latex": self.once("confirmation_latex", lambda: _tex(conf.value)),
                "value_float": as_float(conf.value),
                "agrees_with_derived": conf.agrees_with_derived,
                "detail": conf.comparison.detail,
            },
            "extra": {k: _json(v) for k, v in self.extra.items()},
        }


@dataclass(frozen=True)
class PrintedItem:
    """An item the paper prints: an equation, a number, a table cell, a claim.

    A derivation module lists them all (``PRINTED_ITEMS``), so that coverage shows: every
    item is compared by at least one ``paper`` check, or says in ``not_checked`` why not.
    """

    item: str
    what: str
    not_checked: str = ""


@dataclass(frozen=True)
class ItemResult:
    """A printed item with the checks that compare it and their combined verdict.

    ``verdict`` is the worst verdict of its ``paper`` checks, None when none compares it.
    """

    item: PrintedItem
    checks: tuple[Check, ...]
    verdict: Verdict | None

    def to_json(self) -> dict[str, Any]:
        """The printed item as JSON: the item and what it is, the labels of the checks that compare it, its verdict (the worst of theirs, or "not checked") and why none does."""
        return {
            "item": self.item.item,
            "what": self.item.what,
            "checks": [c.label for c in self.checks],
            "verdict": self.verdict.value if self.verdict is not None else "not checked",
            "not_checked": self.item.not_checked or None,
        }


def item_results(items: Iterable[PrintedItem], checks: Iterable[Check]) -> list[ItemResult]:
    """Every printed item with its ``paper`` checks and their worst verdict.

    Raises ValueError for a paper check whose item is not listed, an item listed twice, or an
    item compared by a paper check that also says why it is not checked.

    >>> c = Check.make("p", "(1)", "", 1, 1, compare_exact(1, 1))
    >>> [r.verdict.value for r in item_results([PrintedItem("(1)", "a law")], [c])]
    ['match']
    """
    items = list(items)
    names = [i.item for i in items]
    if len(set(names)) != len(names):
        raise ValueError(f"a printed item is listed twice: {sorted({n for n in names if names.count(n) > 1})}")
    paper_checks = [c for c in checks if c.kind is Kind.PAPER]
    unknown = sorted({c.item for c in paper_checks} - set(names))
    if unknown:
        raise ValueError(f"paper checks compare items that are not in the list of printed items: {unknown}")
    out = []
    for it in items:
        mine = tuple(c for c in paper_checks if c.item == it.item)
        if mine and it.not_checked:
            raise ValueError(f"printed item {it.item!r} is compared by a paper check and says it is not checked "
                             f"({it.not_checked}): drop one")
        verdict = max((c.verdict for c in mine), key=SEVERITY.index) if mine else None
        out.append(ItemResult(it, mine, verdict))
    return out


# ---------------------------------------------------------------------------- text and LaTeX
def _plain(value: Any) -> str:
    if isinstance(value, str):
        return value
    if isinstance(value, (list, tuple)):
        return "; ".join(_plain(v) for v in value)
    return str(value)


def _json(value: Any) -> Any:
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    if isinstance(value, Mapping):
        return {str(k): _json(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json(v) for v in value]
    return str(value)


_TEXT_SPECIAL = re.compile(r"[\\{}]")


def _tex(value: Any) -> str:
    if isinstance(value, str):
        return r"\text{" + _TEXT_SPECIAL.sub("", value) + "}"
    if isinstance(value, (list, tuple)):
        return r",\quad ".join(_tex(v) for v in value)
    try:
        return latex(value)
    except Exception:  # a value SymPy cannot print is shown as text
        return r"\text{" + _TEXT_SPECIAL.sub("", str(value)) + "}"
