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

A part of a paper's derivation that raises (a broken engine, an input the engine refuses)
does not end the run: :func:`gather` turns it into a ``failure`` check whose verdict is
``differs`` with the error as evidence, and the printed items only that part compares
turn to ``differs`` too (:func:`item_results`).  A verdict that rests on a parameter
chosen to reproduce the printed item, or on the paper's own text rather than the engine,
names it (``rests_on``) and counts as a weak one.

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

import re
import traceback
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from symkin._util.display import markdown_table
from symkin.papers.compare import (
    alternative,
    annotate,
    as_float,
    compare_claim,
    compare_digits,
    compare_each,
    compare_exact,
    compare_inequality,
    compare_rounded,
    compare_symbolic,
    confirmation,
    judge,
    nonzero_somewhere,
    proven_zero,
    vanishes,
)
from symkin.papers.verdicts import SEVERITY, Alternative, Comparison, Confirmation, Kind, Verdict
from symkin.printing import latex

__all__ = [
    "Kind",
    "Verdict",
    "Comparison",
    "Alternative",
    "Confirmation",
    "Check",
    "PrintedItem",
    "failure",
    "gather",
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
    rests_on : str
        What the verdict rests on besides the engine, when it does: a parameter chosen so
        that the item is reproduced (a value searched for, a sampling step, efficiencies
        assumed), or the paper's own text (captions) rather than a derivation.  Named in
        the evidence; such a check is ``weak`` (:attr:`strength`).
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
    rests_on: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", Kind(self.kind))
        if self.source not in ("printed", "reconstructed"):
            raise ValueError(f"source is 'printed' or 'reconstructed', got {self.source!r}")
        if not self.item:
            object.__setattr__(self, "item", self.label)
        note = f"a weak verdict: it rests on {self.rests_on}"
        if self.rests_on and note not in self.comparison.detail:
            object.__setattr__(self, "comparison", annotate(self.comparison, note))

    @property
    def strength(self) -> str:
        """``"weak"`` when the verdict rests on a chosen parameter or the paper's text (``rests_on``), else ``"genuine"``."""
        return "weak" if self.rests_on else "genuine"

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
        rests_on: str = "",
        **extra: Any,
    ) -> Check:
        """A check from its parts, with the LaTeX of the derived and the published objects printed once here."""
        return cls(paper, label, description, derived, published, comparison, _tex(derived), _tex(published), extra,
                   Kind(kind), item, source, rests_on)

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
            "strength": self.strength,
            "rests_on": self.rests_on or None,
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


def failure(paper: str, part: str, error: BaseException) -> Check:
    """The check that stands for a part of ``paper``'s derivation that raised ``error``:
    kind ``failure``, verdict ``differs``, the error (and where it was raised) as evidence.

    >>> c = failure("p", "ratios", ValueError("no root"))
    >>> c.kind.value, c.verdict.value, c.comparison.detail
    ('failure', 'differs', "the part 'ratios' raised ValueError: no root; none of its checks could be made")
    """
    frames = traceback.extract_tb(error.__traceback__)
    where = f" (in {frames[-1].name}, {frames[-1].filename.rsplit('/', 1)[-1]}:{frames[-1].lineno})" if frames else ""
    text = f"{type(error).__name__}: {error}"
    return Check(paper, f"{part}: failed", f"the part {part!r} of the derivation, which raised instead of producing its checks",
                 text, "its checks", Comparison(Verdict.DIFFERS, f"the part {part!r} raised {text}{where}; none of its "
                                                                 "checks could be made"),
                 _tex(text), _tex("its checks"), kind=Kind.FAILURE)


def gather(paper: str, *parts: Callable[[], Check | Iterable[Check]]) -> list[Check]:
    """The checks of each of ``parts`` (functions returning a check or a list of them), each run
    on its own: a part that raises gives its :func:`failure` check, and the others still run.

    >>> def broken():
    ...     raise ZeroDivisionError("division by zero")
    >>> [c.verdict.value for c in gather("p", lambda: Check.make("p", "(1)", "", 1, 1, compare_exact(1, 1)), broken)]
    ['match', 'differs']
    """
    out: list[Check] = []
    for part in parts:
        try:
            found = part()
            out += [found] if isinstance(found, Check) else list(found)
        except Exception as error:
            out.append(failure(paper, _part_name(part), error))
    return out


def _part_name(part: Callable[..., Any]) -> str:
    """A part's name for its failure check: its function's name (of a ``functools.partial``, the
    function's), without the underscores around it."""
    name = getattr(part, "__name__", None) or getattr(getattr(part, "func", None), "__name__", "part")
    return str(name).strip("_").removesuffix("_checks").replace("_", " ")


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

    ``verdict`` is the worst verdict of its ``paper`` checks, None when none compares it;
    ``differs`` when the paper lists no reason why none does and a part of its derivation
    failed (``checks`` then holds the ``failure`` checks).
    """

    item: PrintedItem
    checks: tuple[Check, ...]
    verdict: Verdict | None

    @property
    def strength(self) -> str | None:
        """None for an item no check compares; ``"weak"`` when every check that compares it is weak
        (rests on a chosen parameter or the paper's text); else ``"genuine"``."""
        if self.verdict is None:
            return None
        return "weak" if self.checks and all(c.strength == "weak" for c in self.checks) else "genuine"

    def to_json(self) -> dict[str, Any]:
        """The printed item as JSON: the item and what it is, the labels of the checks that compare it, its verdict (the worst of theirs, or "not checked") and why none does."""
        return {
            "item": self.item.item,
            "what": self.item.what,
            "checks": [c.label for c in self.checks],
            "verdict": self.verdict.value if self.verdict is not None else "not checked",
            "strength": self.strength,
            "not_checked": self.item.not_checked or None,
        }


def item_results(items: Iterable[PrintedItem], checks: Iterable[Check]) -> list[ItemResult]:
    """Every printed item with its ``paper`` checks and their worst verdict.

    An item that no check compares and that says no reason why is ``differs`` when a part of
    the paper's derivation failed (a ``failure`` check): the part that failed may be the one
    that compares it.

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
    checks = list(checks)
    paper_checks = [c for c in checks if c.kind is Kind.PAPER]
    failures = tuple(c for c in checks if c.kind is Kind.FAILURE)
    unknown = sorted({c.item for c in paper_checks} - set(names))
    if unknown:
        raise ValueError(f"paper checks compare items that are not in the list of printed items: {unknown}")
    out = []
    for it in items:
        mine = tuple(c for c in paper_checks if c.item == it.item)
        if mine and it.not_checked:
            raise ValueError(f"printed item {it.item!r} is compared by a paper check and says it is not checked "
                             f"({it.not_checked}): drop one")
        if not mine and not it.not_checked and failures:
            out.append(ItemResult(it, failures, Verdict.DIFFERS))
            continue
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
