"""The LaTeX document of a reproduction: each derived equation beside the published one.

    >>> doc = equations_document([])
    >>> doc.startswith("\\\\documentclass")
    True
"""

from __future__ import annotations

from typing import Any, Iterable

__all__ = ["equations_document", "escape"]

_SPECIAL = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
            "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}"}


def escape(text: str) -> str:
    """Text safe to put in a LaTeX paragraph."""
    return "".join(_SPECIAL.get(ch, ch) for ch in str(text))


PREAMBLE = r"""\documentclass[10pt]{article}
\usepackage[T1]{fontenc}
\usepackage{amsmath,amssymb}
\allowdisplaybreaks
\setlength{\parindent}{0pt}
\setlength{\textwidth}{16cm}\setlength{\oddsidemargin}{0cm}\setlength{\evensidemargin}{0cm}
\title{symkin: derived laws beside the published ones}
\date{}
\begin{document}
\maketitle
"""


def _check_block(check: Any) -> str:
    lines = [
        rf"\subsection*{{{escape(check.label)}: {escape(check.description)}}}",
        r"\begin{align*}",
        rf"\text{{derived:}}\quad & {check.derived_latex} \\",
        rf"\text{{published:}}\quad & {check.published_latex}",
        r"\end{align*}",
        rf"\textbf{{{escape(check.verdict.value)}}}: {escape(check.comparison.detail)}",
        "",
    ]
    return "\n".join(lines)


def equations_document(results: Iterable[Any]) -> str:
    """A complete LaTeX document for a list of :class:`~symkin.reproduce.PaperResult`."""
    parts = [PREAMBLE]
    for r in results:
        parts.append(rf"\section{{{escape(r.citation)}}}")
        for c in r.checks:
            parts.append(_check_block(c))
    parts.append(r"\end{document}")
    return "\n".join(parts) + "\n"
