"""The LaTeX document of a reproduction: each derived equation beside the published one.

The document uses only what TeX Live's base packages hold (amsmath, amssymb, geometry,
graphicx), breaks long laws over lines at ``+`` and ``-`` and escapes every piece of
text, so it compiles with pdflatex without overfull lines.

    >>> doc = equations_document([])
    >>> doc.startswith("\\\\documentclass")
    True
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import sympy as sp

from symkin._version import __version__
from symkin.laws import Law
from symkin.papers.summary import paper_items, summarize
from symkin.printing import escape_text, estimated_width, latex, latex_lines

__all__ = ["equations_document", "escape", "math_text", "math_rows", "LINE_WIDTH"]

#: Width (in the estimate of :func:`symkin.printing.estimated_width`) of one line of a law
#: beside its "derived:" / "published:" label on a 16 cm text block.
LINE_WIDTH = 58


def escape(text: str) -> str:
    """Text safe to put in a LaTeX paragraph, with line breaks allowed after / * = , ;

    >>> print(escape("z_1 = 100%"))
    z\\_1 =\\allowbreak{} 100\\%
    """
    return escape_text(text, breakable=True)


_GREEK = ["alpha", "beta", "gamma", "delta", "epsilon", "eps", "zeta", "eta", "theta", "iota", "kappa", "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "phi", "chi", "psi", "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Phi", "Psi", "Omega"]
_INDEX = r"(?:\{[^{}]*\}|\([^()]*\)|[A-Za-z0-9]+)"
#: A symbol of the papers' ASCII notation: a Greek name, or a letter with a subscript or
#: superscript (omega_H, i_1H^(4), d_w2, Phi_i, theta_H(0), pi).
_SYMBOL = re.compile(
    rf"(?<![A-Za-z0-9\\])(?P<base>{'|'.join(sorted(_GREEK, key=len, reverse=True))}|[A-Za-z])"
    rf"(?:_(?P<sub>{_INDEX}))?(?:\^(?P<sup>{_INDEX}))?(?P<arg>\((?:0|t)\))?(?![A-Za-z0-9])"
)


def _index(text: str, keep_parentheses: bool = False) -> str:
    if text[0] == "{" or (text[0] == "(" and not keep_parentheses):
        text = text[1:-1]
    return "{" + text + "}"


def math_text(text: str) -> str:
    """Text with the papers' ASCII symbols typeset as math, the rest escaped (for headings).

    >>> print(math_text("(23a) omega_H: speed from omega_1, i_1H^(4) = 1 - d_w2/d_w3"))
    (23a) $\\omega_{H}$: speed from $\\omega_{1}$,\\allowbreak{} $i_{1H}^{(4)}$ =\\allowbreak{} 1 - $d_{w2}$/\\allowbreak{}$d_{w3}$
    >>> print(math_text("Table 1 v max, 2 pi s, theta_H(0) = pi/6, 50%"))
    Table 1 v max,\\allowbreak{} 2 $\\pi$ s,\\allowbreak{} $\\theta_{H}(0)$ =\\allowbreak{} $\\pi$/\\allowbreak{}6,\\allowbreak{} 50\\%
    """
    out, end = [], 0
    for m in _SYMBOL.finditer(text):
        base, sub, sup, arg = m.group("base", "sub", "sup", "arg")
        if base not in _GREEK and sub is None and sup is None:
            continue  # a plain letter stays text
        out.append(_plain_text(text[end : m.start()]))
        symbol = "\\varepsilon" if base == "eps" else (f"\\{base}" if base in _GREEK else base)
        symbol += f"_{_index(sub)}" if sub else ""
        symbol += f"^{_index(sup, keep_parentheses=True)}" if sup else ""
        out.append(f"${symbol}{arg or ''}$")
        end = m.end()
    out.append(_plain_text(text[end:]))
    return "".join(out)


_RELATION = re.compile(r"(<=|>=|!=)")
_RELATION_TEX = {"<=": r"$\le$", ">=": r"$\ge$", "!=": r"$\ne$"}


def _plain_text(text: str) -> str:
    """Escaped text, with <=, >= and != as their signs."""
    return "".join(_RELATION_TEX.get(part) or escape_text(part, breakable=True) for part in _RELATION.split(text))


#: How the document names each kind of check.
KIND_NAMES = {"paper": "paper item", "consistency": "consistency check", "extension": "extension"}


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
    if isinstance(value, str):  # long text wraps at spaces, about as wide as a line of a law
        chunks = textwrap.wrap(value, width=max(int(width), 20), break_long_words=True) or [""]
        return [rf"\text{{{escape_text(chunk)}}}" for chunk in chunks]
    if isinstance(value, (Law, sp.Equality)):
        lhs = latex(value.lhs)
        lines = latex_lines(value.rhs, max(width - estimated_width(lhs) - 2, 20))
        return [f"{lhs} = {lines[0]}"] + [rf"\qquad {line}" for line in lines[1:]]
    try:
        expr = value if isinstance(value, sp.Basic) else sp.sympify(value, strict=True)
    except (sp.SympifyError, TypeError):
        return math_rows(str(value), width)
    lines = latex_lines(expr, width)
    return lines[:1] + [rf"\qquad {line}" for line in lines[1:]]


def _check_block(check: Any) -> str:
    rows = []
    for label, value in (("derived", check.derived), ("published", check.published)):
        for n, row in enumerate(math_rows(value)):
            head = rf"\text{{{label}:}}\quad " if n == 0 else ""
            rows.append(f"{head}& {row}")
    kind = getattr(check, "kind", "paper")
    kind = KIND_NAMES.get(getattr(kind, "value", kind), str(kind))
    if getattr(check, "source", "printed") == "reconstructed":
        kind += " (form reconstructed where the OCR lost it)"
    lines = [
        rf"\subsection*{{{math_text(check.label)}: {math_text(check.description)}}}",
        r"\begin{align*}",
        " \\\\\n".join(rows),
        r"\end{align*}",
        # sloppy: the evidence quotes formulas as text, whose long tokens need looser lines
        rf"{{\sloppy \textit{{{escape(kind)}}}, \textbf{{{escape(check.verdict.value)}}}: {escape(check.comparison.detail)}\par}}",
        "",
    ]
    alt = getattr(check.comparison, "alternative", None)
    if alt is not None:
        state = "reproduces the published item" if alt.matches_published else "does not reproduce the published item"
        lines += [rf"\textit{{Alternative}} ({escape(alt.assumption)}): \[ {_row(alt.value)} \] {escape(state)}.", ""]
    conf = getattr(check.comparison, "confirmation", None)
    if conf is not None:
        state = "agrees with the derived value" if conf.agrees_with_derived else "does not agree with the derived value"
        lines += [rf"\textit{{Independent route}} ({escape(conf.route)}): \[ {_row(conf.value)} \] {escape(state)}.", ""]
    return "\n".join(lines)


def _row(value: Any) -> str:
    """Display math for an alternative's or a confirmation's value (one row per piece)."""
    return r"\begin{gathered} " + r" \\ ".join(math_rows(value)) + r" \end{gathered}"


def _summary(results: list[Any]) -> str:
    text = (
        f"symkin {__version__} derived every result below with its own engine and compared it with the "
        f"published form: {summarize(results).line()}. A paper item is an item the paper prints; a consistency "
        "check compares two routes of the engine; an extension goes beyond the paper."
    )
    return escape(text) + "\n"


def _items(result: Any) -> list[str]:
    """The paper's printed items with their verdicts, as a list."""
    items = paper_items(result)
    if not items:
        return []
    out = [r"\subsection*{Printed items and their verdicts}", r"\begin{itemize}"]
    for it in items:
        verdict = it.verdict.value if it.verdict is not None else "not checked: " + (it.item.not_checked or "no reason given")
        labels = ", ".join(c.label for c in it.checks)
        out.append(rf"\item {math_text(it.item.item)} ({math_text(it.item.what)}): \textbf{{{escape(verdict)}}}"
                   + (f" [{math_text(labels)}]" if labels else ""))
    out.append(r"\end{itemize}")
    return out


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
        parts += _items(r)
        for note in getattr(r, "notes", []) or []:
            parts.append(r"\textit{Note:} " + escape(note) + "\n")
    if root is not None:
        figures = _figures(results, Path(root))
        if figures:
            parts.append(r"\clearpage" + "\n" + r"\section*{Figures}")
            parts += figures
    parts.append(r"\end{document}")
    return "\n".join(parts) + "\n"
