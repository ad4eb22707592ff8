"""Counts of a reproduction: printed items by verdict, checks by kind, and the summary line.

    >>> from symkin.papers.checks import Check, PrintedItem, compare_exact
    >>> from types import SimpleNamespace
    >>> paper = SimpleNamespace(checks=[Check.make("p", "(1)", "", 2, 2, compare_exact(2, 2))],
    ...                         items=[PrintedItem("(1)", "a law"), PrintedItem("(2)", "a claim", "not derivable")])
    >>> summarize([paper]).line()
    '1 of 2 paper items reproduced genuinely, 0 slips explained, 0 paper errors confirmed, 0 differ, 1 not checked; 0 consistency checks; 0 extensions'
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from symkin._util.display import html_table
from symkin.papers.checks import ItemResult, Kind, PrintedItem, Verdict, item_results

__all__ = ["Summary", "summarize", "paper_items"]


def paper_items(result: Any) -> list[ItemResult]:
    """A paper's printed items with their checks (``result`` has ``checks`` and ``items``).

    A paper that lists no items gets one per distinct ``item`` of its paper checks.
    """
    items = list(getattr(result, "items", None) or [])
    if not items:
        items = [
            PrintedItem(name, "(not listed by the paper module)")
            for name in dict.fromkeys(c.item for c in result.checks if c.kind is Kind.PAPER)
        ]
    return item_results(items, result.checks)


@dataclass(frozen=True)
class Summary:
    """Counts over papers: printed items by verdict (and how many of each rest on a chosen
    parameter or the paper's text: ``weak``), and checks by kind.

    The line counts the genuine reproductions apart from the weak ones, and says how many
    parts of the derivations failed (their checks could not be made) when any did.

    >>> Summary(items=3, reproduced=2, slips=1).line()
    '2 of 3 paper items reproduced genuinely, 1 slip explained, 0 paper errors confirmed, 0 differ; 0 consistency checks; 0 extensions'
    >>> Summary(items=3, reproduced=2, reproduced_weak=1, errors=1, errors_weak=1, failures=1).line()
    '1 of 3 paper items reproduced genuinely, 1 more weakly, 0 slips explained, 1 paper error confirmed (1 weakly), 0 differ; 0 consistency checks; 0 extensions; 1 part failed'
    """

    items: int = 0
    reproduced: int = 0
    slips: int = 0
    errors: int = 0
    differ: int = 0
    not_checked: int = 0
    paper_checks: int = 0
    consistency: int = 0
    consistency_differ: int = 0
    extensions: int = 0
    extensions_differ: int = 0
    checks: int = 0
    differs: int = 0
    reproduced_weak: int = 0
    slips_weak: int = 0
    errors_weak: int = 0
    failures: int = 0

    def line(self) -> str:
        """The one-line summary: paper items apart from consistency checks and extensions."""

        def plural(n: int, word: str, words: str | None = None) -> str:
            return f"{n} {word if n == 1 else (words or word + 's')}"

        def more(n: int, bad: int) -> str:
            return f" ({bad} differ)" if bad else ""

        def weakly(n: int) -> str:
            return f" ({n} weakly)" if n else ""

        parts = [f"{self.reproduced - self.reproduced_weak} of {self.items} paper items reproduced genuinely"]
        if self.reproduced_weak:
            parts.append(f"{self.reproduced_weak} more weakly")
        parts += [
            plural(self.slips, "slip") + " explained" + weakly(self.slips_weak),
            plural(self.errors, "paper error") + " confirmed" + weakly(self.errors_weak),
            f"{self.differ} differ",
        ]
        if self.not_checked:
            parts.append(f"{self.not_checked} not checked")
        return (
            ", ".join(parts)
            + "; " + plural(self.consistency, "consistency check") + more(self.consistency, self.consistency_differ)
            + "; " + plural(self.extensions, "extension") + more(self.extensions, self.extensions_differ)
            + (f"; {plural(self.failures, 'part')} failed" if self.failures else "")
        )

    def _repr_html_(self) -> str:
        """The counts as a table, for Jupyter.

        >>> "<td>reproduced</td><td>2</td>" in Summary(items=3, reproduced=2)._repr_html_()
        True
        """
        rows = [("paper items", self.items), ("reproduced", self.reproduced),
                ("of them weakly", self.reproduced_weak), ("slips explained", self.slips),
                ("paper errors confirmed", self.errors), ("differ", self.differ), ("not checked", self.not_checked),
                ("consistency checks", f"{self.consistency} ({self.consistency_differ} differ)"),
                ("extensions", f"{self.extensions} ({self.extensions_differ} differ)"), ("parts failed", self.failures)]
        return html_table(["", "count"], rows, caption=self.line())

    def to_json(self) -> dict[str, Any]:
        """The summary as JSON: the counts of items by verdict and of checks by kind, and the summary line."""
        return {
            "line": self.line(),
            "paper_items": {"total": self.items, "reproduced": self.reproduced, "slips": self.slips,
                            "errors": self.errors, "differ": self.differ, "not_checked": self.not_checked,
                            "weak": {"reproduced": self.reproduced_weak, "slips": self.slips_weak,
                                     "errors": self.errors_weak}},
            "paper_checks": self.paper_checks,
            "consistency": {"checks": self.consistency, "differ": self.consistency_differ},
            "extension": {"checks": self.extensions, "differ": self.extensions_differ},
            "checks": self.checks,
            "ok": self.checks - self.differs,
            "differs": self.differs,
            "failures": self.failures,
        }


def summarize(results: Iterable[Any]) -> Summary:
    """Count printed items by their combined verdict and checks by kind (``results``: objects with
    ``checks`` and ``items``, such as :class:`~symkin.papers.reproduce.PaperResult`)."""
    results = list(results)
    items = [r for res in results for r in paper_items(res)]
    checks = [c for res in results for c in res.checks]

    def count(kind: Kind, bad: bool = False) -> int:
        return sum(c.kind is kind and (not bad or not c.verdict.ok) for c in checks)

    def weak(*verdicts: Verdict) -> int:
        return sum(r.verdict in verdicts and r.strength == "weak" for r in items)

    return Summary(
        items=len(items),
        reproduced=sum(r.verdict is not None and r.verdict.agrees for r in items),
        slips=sum(r.verdict is Verdict.SLIP for r in items),
        errors=sum(r.verdict is Verdict.ERROR for r in items),
        differ=sum(r.verdict is Verdict.DIFFERS for r in items),
        not_checked=sum(r.verdict is None for r in items),
        paper_checks=count(Kind.PAPER),
        consistency=count(Kind.CONSISTENCY),
        consistency_differ=count(Kind.CONSISTENCY, True),
        extensions=count(Kind.EXTENSION),
        extensions_differ=count(Kind.EXTENSION, True),
        checks=len(checks),
        differs=sum(not c.verdict.ok for c in checks),
        reproduced_weak=weak(Verdict.MATCH, Verdict.ROUNDED),
        slips_weak=weak(Verdict.SLIP),
        errors_weak=weak(Verdict.ERROR),
        failures=count(Kind.FAILURE),
    )


