"""The LaTeX document of a reproduction: each derived equation beside the published one.

The document uses only what TeX Live's base packages hold (amsmath, amssymb, geometry,
graphicx), breaks long laws over lines at ``+`` and ``-`` and escapes every piece of
text, so it compiles with pdflatex without overfull lines.

    >>> doc = equations_document([])
    >>> doc.startswith("\\\\documentclass")
    True
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

import sympy as sp

from symkin._version import __version__
from symkin.laws import Law
from symkin.printing import escape_text, estimated_width, latex, latex_lines

__all__ = ["equations_document", "escape", "math_rows", "LINE_WIDTH"]

#: Width (in the estimate of :func:`symkin.printing.estimated_width`) of one line of a law
#: beside its "derived:" / "published:" label on a 16 cm text block.
LINE_WIDTH = 58


def escape(text: str) -> str:
    """Text safe to put in a LaTeX paragraph, with line breaks allowed after / * = , ;

    >>> print(escape("z_1 = 100%"))
    z\\_1 =\\allowbreak{} 100\\%
    """
    return escape_text(text, breakable=True)


PREAMBLE = r"""\documentclass[10pt,a4paper]{article}
\usepackage{amsmath,amssymb}
\usepackage[margin=2.5cm]{geometry}
\usepackage{graphicx}
\allowdisplaybreaks
\setlength{\parindent}{0pt}
\setlength{\parskip}{4pt}
\emergencystretch=3em
\title{symkin: derived laws beside the published ones}
\date{}
\begin{document}
\maketitle
"""


def math_rows(value: Any, width: float = LINE_WIDTH) -> list[str]:
    """Rows of display math for one derived or published value (``&``-free pieces).

    A law or equation prints ``lhs = rhs``; a sequence prints one row per item; text
    prints as escaped ``\\text``.  Long right-hand sides continue on further rows.

    >>> import sympy as sp
    >>> a, b = sp.symbols("a b")
    >>> math_rows([sp.Eq(a, b), "?00"])
    ['a = b', '\\\\text{?00}']
    """
    if isinstance(value, (list, tuple)):
        return [row for item in value for row in math_rows(item, width)]
    if isinstance(value, bool):
        return [rf"\text{{{'true' if value else 'false'}}}"]
    if isinstance(value, str):
        return [rf"\text{{{escape_text(value)}}}"]
    if isinstance(value, (Law, sp.Equality)):
        lhs = latex(value.lhs)
        lines = latex_lines(value.rhs, max(width - estimated_width(lhs) - 2, 20))
        return [f"{lhs} = {lines[0]}"] + [rf"\qquad {line}" for line in lines[1:]]
    try:
        expr = value if isinstance(value, sp.Basic) else sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError):
        return [rf"\text{{{escape_text(str(value))}}}"]
    lines = latex_lines(expr, width)
    return lines[:1] + [rf"\qquad {line}" for line in lines[1:]]


def _check_block(check: Any) -> str:
    rows = []
    for label, value in (("derived", check.derived), ("published", check.published)):
        for n, row in enumerate(math_rows(value)):
            head = rf"\text{{{label}:}}\quad " if n == 0 else ""
            rows.append(f"{head}& {row}")
    lines = [
        rf"\subsection*{{{escape(check.label)}: {escape(check.description)}}}",
        r"\begin{align*}",
        " \\\\\n".join(rows),
        r"\end{align*}",
        rf"\textbf{{{escape(check.verdict.value)}}}: {escape(check.comparison.detail)}",
        "",
    ]
    return "\n".join(lines)


def _summary(results: list[Any]) -> str:
    checks = [c for r in results for c in r.checks]
    bad = [c for c in checks if not c.verdict.ok]
    slips = [c for c in checks if c.verdict.value.startswith("paper slip")]
    text = (
        f"symkin {__version__} derived every result below with its own engine and compared it with the "
        f"published form: {len(checks)} checks, {len(checks) - len(bad)} reproduced"
        f" ({len(slips)} of them paper slips, explained), {len(bad)} differ."
    )
    return escape(text) + "\n"


def _figures(results: list[Any], root: Path) -> list[str]:
    out: list[str] = []
    for r in results:
        for fig in r.figures:
            fig = Path(fig)
            if fig.suffix.lower() != ".pdf":
                continue
            try:
                rel = fig.resolve().relative_to(root.resolve())
            except ValueError:
                continue
            out += [
                r"\begin{center}",
                rf"\includegraphics[width=\linewidth,height=0.8\textheight,keepaspectratio]{{{rel.as_posix()}}}",
                r"\end{center}",
                "",
            ]
    return out


def equations_document(results: Iterable[Any], root: Path | None = None) -> str:
    """A complete LaTeX document for a list of :class:`~symkin.papers.reproduce.PaperResult`.

    With ``root`` (the report folder), the papers' PDF figures inside it are included.
    """
    results = list(results)
    parts = [PREAMBLE, _summary(results)]
    for r in results:
        parts.append(rf"\section{{{escape(r.citation)}}}")
        parts.append(rf"Paper key: \texttt{{{escape(r.key)}}}." + "\n")
        for c in r.checks:
            parts.append(_check_block(c))
        for note in getattr(r, "notes", []) or []:
            parts.append(r"\textit{Note:} " + escape(note) + "\n")
    if root is not None:
        figures = _figures(results, Path(root))
        if figures:
            parts.append(r"\clearpage" + "\n" + r"\section*{Figures}")
            parts += figures
    parts.append(r"\end{document}")
    return "\n".join(parts) + "\n"
