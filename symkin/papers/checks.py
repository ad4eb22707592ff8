"""Checks of derived results against published ones, and their verdicts.

A derivation module (``symkin.derivations.<paper>``) returns a list of :class:`Check`;
each holds the derived form, the published form and a verdict reached by an exact
comparison: a symbolic difference that cancels to zero, exact rational equality, or a
published decimal that is the derived value rounded.  A paper slip (typo, OCR damage,
inconsistency) is a verdict of its own and must carry its evidence.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> compare_symbolic((x**2 - 1) / (x - 1), x + 1).verdict
    <Verdict.MATCH: 'match'>
    >>> compare_rounded(sp.Rational(20000, 101), "198").verdict
    <Verdict.ROUNDED: 'match (published value rounded)'>
"""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass, field
from decimal import ROUND_HALF_UP, Decimal
from typing import Any

import sympy as sp

from symkin._util.parsing import as_expr, parse_number
from symkin.printing import latex

__all__ = ["Verdict", "Comparison", "Check", "compare_symbolic", "compare_exact", "compare_rounded", "slip"]


class Verdict(str, enum.Enum):
    MATCH = "match"
    ROUNDED = "match (published value rounded)"
    SLIP = "paper slip (explained)"
    DIFFERS = "differs"

    @property
    def ok(self) -> bool:
        """True when the reproduction counts as successful."""
        return self is not Verdict.DIFFERS


@dataclass(frozen=True)
class Comparison:
    verdict: Verdict
    detail: str = ""


def _expr(value: Any) -> Any:
    """A SymPy object from a value; text is parsed with the allow-list, never by Python."""
    return as_expr(value, what="a compared value", finite=False)


def _difference(derived: Any, published: Any, under: Mapping[Any, Any] | None) -> sp.Expr:
    d, p = _expr(derived), _expr(published)
    if under:
        d, p = d.subs(under), p.subs(under)
    diff = sp.cancel(sp.together(d - p))
    if diff != 0 and diff.has(sp.sin, sp.cos, sp.tan, sp.exp, sp.atan, sp.sqrt, sp.log):
        diff = sp.simplify(diff)
    return diff


def compare_symbolic(derived: Any, published: Any, *, under: Mapping[Any, Any] | None = None) -> Comparison:
    """Match when derived - published cancels to zero (after substituting ``under``).

    ``under`` states a condition the published form assumes (e.g. coaxiality
    ``{r_4: r_1 + r_2 + r_3}``); it is named in the detail.
    """
    diff = _difference(derived, published, under)
    cond = ""
    if under:
        cond = " under " + ", ".join(f"{k} = {v}" for k, v in under.items())
    if diff == 0:
        return Comparison(Verdict.MATCH, f"derived - published = 0{cond}")
    return Comparison(Verdict.DIFFERS, f"derived - published = {diff}{cond}")


def _exact(value: Any) -> sp.Expr:
    """An exact SymPy value: a Python float is read as the decimal it prints, a SymPy
    Float as its exact binary value; nothing is guessed (no nsimplify)."""
    if isinstance(value, float):
        return parse_number(repr(value), what="a compared value")
    expr = _expr(value)
    return expr.xreplace({f: sp.Rational(f) for f in expr.atoms(sp.Float)}) if isinstance(expr, sp.Basic) else expr


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
    return Comparison(Verdict.DIFFERS, f"derived {d} = {sp.N(d, 12)}, published {p}")


def compare_rounded(derived: Any, published: str) -> Comparison:
    """Match when the published decimal is the derived value rounded half up to its printed digits.

    Exact equality is reported as a plain match.

    >>> compare_rounded(sp.Rational(5, 2), "3").verdict.value
    'match (published value rounded)'
    >>> compare_rounded(sp.Rational(5, 2), "2").verdict.value
    'differs'
    """
    d = _exact(derived)
    p = Decimal(published)
    if not (isinstance(d, sp.Expr) and d.is_number):
        return Comparison(Verdict.DIFFERS, f"derived {d} is not a number, published {published}")
    if _exact(published) == d:
        return Comparison(Verdict.MATCH, f"exactly {d}")
    digits = p.as_tuple().exponent
    assert isinstance(digits, int)  # p is finite: _exact(published) above rejects nan and infinity
    value = Decimal(str(sp.N(d, 60)))
    rounded = value.quantize(Decimal(1).scaleb(digits), rounding=ROUND_HALF_UP)
    if rounded == p:
        places = f"{-digits} decimal{'s' * (digits != -1)}" if digits < 0 else "a whole number"
        return Comparison(
            Verdict.ROUNDED, f"derived {d} = {sp.N(d, 10)}; rounded half up to {places} it is the published {published}"
        )
    return Comparison(Verdict.DIFFERS, f"derived {d} = {sp.N(d, 10)}, published {published}")


def slip(evidence: str) -> Comparison:
    """A published form that is wrong for a reason stated in ``evidence``."""
    return Comparison(Verdict.SLIP, evidence)


@dataclass(frozen=True)
class Check:
    """One published result against its derivation."""

    paper: str
    label: str
    description: str
    derived: Any
    published: Any
    comparison: Comparison
    derived_latex: str = ""
    published_latex: str = ""
    extra: Mapping[str, Any] = field(default_factory=dict)

    @classmethod
    def make(
        cls, paper: str, label: str, description: str, derived: Any, published: Any, comparison: Comparison, **extra: Any
    ) -> Check:
        return cls(paper, label, description, derived, published, comparison, _tex(derived), _tex(published), extra)

    @property
    def verdict(self) -> Verdict:
        return self.comparison.verdict

    def to_json(self) -> dict[str, Any]:
        return {
            "paper": self.paper,
            "label": self.label,
            "description": self.description,
            "derived": _text(self.derived),
            "published": _text(self.published),
            "derived_latex": self.derived_latex,
            "published_latex": self.published_latex,
            "verdict": self.verdict.value,
            "ok": self.verdict.ok,
            "detail": self.comparison.detail,
            **{k: _text(v) for k, v in self.extra.items()},
        }


def _text(value: Any) -> Any:
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    if isinstance(value, (list, tuple)):
        return [_text(v) for v in value]
    return str(value)


def _tex(value: Any) -> str:
    if isinstance(value, str):
        return r"\text{" + value.replace("\\", "").replace("{", "").replace("}", "") + "}"
    if isinstance(value, (list, tuple)):
        return r",\quad ".join(_tex(v) for v in value)
    try:
        return latex(value)
    except Exception:  # a value SymPy cannot print is shown as text
        return r"\text{" + str(value) + "}"
