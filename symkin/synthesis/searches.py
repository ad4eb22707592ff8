"""What symkin's searches share: a request in, ranked designs out, and the reason when none fits.

Three searches list designs:

- :func:`symkin.synthesize`, tooth numbers of any train for a target ratio: a
  :class:`~symkin.synthesis.request.SynthesisRequest` in, a
  :class:`~symkin.synthesis.result.SynthesisResult` out;
- :func:`symkin.mechanisms.helical.synthesize_helical`, a stepped helical planet with its
  axial forces balanced: a :class:`~symkin.mechanisms.helical.balanced.request.HelicalRequest`
  in, a :class:`~symkin.mechanisms.helical.balanced.request.HelicalResult` out;
- :func:`symkin.mechanisms.multistage.best_designs`, the stages of a common-ring train for a
  total ratio: its arguments (total, stages, model, tolerance, ...) in, a
  :class:`~symkin.mechanisms.multistage.split.discrete.DiscreteSplit` out.

Each takes ``progress=`` (a callable the search calls as it goes) and ``time_limit=``
(seconds; a longer search raises :class:`~symkin.errors.TimeLimitError` that says how far
it got), and returns a :class:`SearchResult`: its ``designs`` best first (iterating the
result gives them), ``reason`` (why no design fits the request, empty when some do),
``message()`` (that, or how many designs there are, in one line) and ``to_json()``.

What differs stays as it is: the arguments of ``progress`` (chunks done, chunks, designs
found; Z2 values done, Z2 values; fraction done, nodes visited), the order of the designs
(ratio error then size, or a ``rank``; ratio error then envelope diameter; the objective),
what else a result carries (the conditions and the funnel, the stages of the sieve, the
nearest designs when none meets the tolerance), and what happens when nothing fits:
:func:`~symkin.synthesize` raises unless ``allow_empty``, the other two return the result.

    >>> from symkin.mechanisms.multistage import StageErrorModel, best_designs, enumerate_stages
    >>> split = best_designs(30, enumerate_stages(60, 3, zmin=12), 2, model=StageErrorModel.linear(1, 1),
    ...                      tolerance=0.05, time_limit=60)
    >>> isinstance(split, SearchResult), split.reason[:34], [d.total for d in split][:2]
    (True, 'no design meets the tolerance 0.05', [26, 36])
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any, Protocol, runtime_checkable

__all__ = ["SearchResult"]


@runtime_checkable
class SearchResult(Protocol):
    """The shape of every search's result (see the module docstring)."""

    @property
    def designs(self) -> tuple[Any, ...]:
        """The designs, best first."""

    @property
    def reason(self) -> str:
        """Why no design fits the request; empty when some do."""

    def message(self) -> str:
        """One line: how many designs there are and in which order, or the reason there are none."""

    def to_json(self) -> dict[str, Any]:
        """The result as JSON."""

    def __iter__(self) -> Iterator[Any]:
        """The designs, best first."""
