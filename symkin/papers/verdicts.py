"""The verdict of a comparison and the evidence it rests on: kinds of check, verdicts, and the
:class:`Comparison` that refuses a slip or an error without its computed evidence (see
:mod:`symkin.papers.checks`)."""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import Any

__all__ = ["Kind", "Verdict", "SEVERITY", "Alternative", "Confirmation", "Comparison"]


class Kind(str, enum.Enum):
    """What a check compares.

    ``paper``: an item printed in the paper (an equation, a number, a claim) against its
    derivation; ``consistency``: two routes of the engine against each other;
    ``extension``: a result beyond the paper (a generalisation, a check the paper does
    not make); ``failure``: a part of a paper's derivation that raised an exception instead
    of producing its checks (its verdict is ``differs``, the error its evidence; see
    :func:`symkin.papers.checks.gather`).  Only ``paper`` checks count as reproductions.
    A comparison that is circular (the model's own input against the printed item) or
    arithmetic on the paper's own numbers is a ``consistency`` check, not a ``paper`` one.
    """

    PAPER = "paper"
    CONSISTENCY = "consistency"
    EXTENSION = "extension"
    FAILURE = "failure"


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
