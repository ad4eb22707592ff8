"""How results show in Jupyter: HTML and Markdown tables, LaTeX math (not public API).

Results define ``_repr_latex_`` (laws), ``_repr_html_`` or ``_repr_markdown_`` (tables)
with these helpers; IPython calls them when a result is the value of a cell.

    >>> print(markdown_table(["a", "b"], [["1", "x|y"]]))
    | a | b |
    |---|---|
    | 1 | x\\|y |
"""

from __future__ import annotations

import html
from collections.abc import Iterable, Sequence
from typing import Any

__all__ = ["html_table", "markdown_table", "math", "short_repr", "REPR_LIMIT"]


def math(tex: str) -> str:
    """Inline math for an HTML or Markdown cell (MathJax typesets ``$...$`` in Jupyter).

    >>> math(r"\\omega_{H}")
    '$\\\\omega_{H}$'
    """
    return f"${tex}$"


def _cell(value: Any, raw: bool) -> str:
    text = "" if value is None else str(value)
    return text if raw else html.escape(text)


def html_table(headers: Sequence[str], rows: Iterable[Sequence[Any]], *, caption: str = "",
               raw_columns: Iterable[int] = ()) -> str:
    """An HTML table; cells are escaped except in ``raw_columns`` (math or markup made here).

    >>> html_table(["x"], [["<1>"]], caption="c")
    '<table><caption>c</caption><thead><tr><th>x</th></tr></thead><tbody><tr><td>&lt;1&gt;</td></tr></tbody></table>'
    """
    raw = set(raw_columns)
    head = "".join(f"<th>{html.escape(h)}</th>" for h in headers)
    body = "".join("<tr>" + "".join(f"<td>{_cell(v, i in raw)}</td>" for i, v in enumerate(row)) + "</tr>" for row in rows)
    cap = f"<caption>{html.escape(caption)}</caption>" if caption else ""
    return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def markdown_table(headers: Sequence[str], rows: Iterable[Sequence[Any]]) -> str:
    """A Markdown (GitHub) table; ``|`` in cells is escaped and line breaks become spaces."""

    def cell(v: Any) -> str:
        return ("" if v is None else str(v)).replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(headers) + " |", "|" + "|".join("---" for _ in headers) + "|"]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in rows]
    return "\n".join(lines)


#: The longest repr of a symkin object (a notebook shows it when nothing richer is there).
REPR_LIMIT = 199


def short_repr(name: str, *parts: object, limit: int = REPR_LIMIT) -> str:
    """``name(part, part, ...)`` cut to ``limit`` characters with ``...`` where it is cut.

    >>> short_repr("Train", "'simple'", "links S, C, P, R", "3 states")
    "Train('simple', links S, C, P, R, 3 states)"
    >>> len(short_repr("X", "y" * 500))
    199
    """
    text = f"{name}({', '.join(str(p) for p in parts)})"
    return text if len(text) <= limit else text[: limit - 4] + "...)"
