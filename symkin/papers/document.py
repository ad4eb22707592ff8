"""The LaTeX document of a reproduction: each derived equation beside the published one.

The document uses only what TeX Live's base packages hold (amsmath, amssymb, geometry,
graphicx, hyperref: a table of contents, PDF bookmarks and internal links, a bibliography of
the papers each section cites; :func:`~symkin.papers.texbuild.compile_pdf` runs pdflatex twice
to resolve them), breaks long laws over lines at ``+`` and ``-`` and escapes every piece of
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
KIND_NAMES = {"paper": "paper item", "consistency": "consistency check", "extension": "extension",
              "failure": "failed part of the derivation"}


PREAMBLE = r"""\documentclass[10pt,a4paper]{article}
\usepackage{amsmath,amssymb}
\usepackage[margin=2.5cm]{geometry}
\usepackage{graphicx}
\allowdisplaybreaks
\setlength{\parindent}{0pt}
\setlength{\parskip}{4pt}
\emergencystretch=3em
\usepackage[hidelinks,bookmarksnumbered,pdftitle={symkin: derived laws beside the published ones}]{hyperref}
\title{symkin: derived laws beside the published ones}
\date{}
\begin{document}
\maketitle
\tableofcontents
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


def check_rows(check: Any) -> dict[str, list[str]]:
    """The display-math rows of a check's derived and published values, and the gathered rows of
    its alternative's and its confirmation's values: made once per check (kept on a
    :class:`~symkin.papers.checks.Check`), so that the worker process that derived the check
    can print them for the document (:func:`symkin.papers.reproduce.run`)."""

    def make() -> dict[str, list[str]]:
        rows = {"derived": math_rows(check.derived), "published": math_rows(check.published)}
        for part in ("alternative", "confirmation"):
            extra = getattr(check.comparison, part, None)
            if extra is not None:
                rows[part] = [_row(extra.value)]
        return rows

    once = getattr(check, "once", None)
    rows: dict[str, list[str]] = once("document_rows", make) if once is not None else make()
    return rows


def _check_block(check: Any, figure: int = 0, number: int = 0) -> str:
    """A check's subsection; ``number`` (from 1) heads it as ``[number]``, the index names it so,
    and ``figure`` is the number of the figure it points to: both are printed, not ``\\ref``-ed,
    so that they need no cross-reference file (the contents, citations and bookmarks do:
    :func:`~symkin.papers.texbuild.compile_pdf` runs pdflatex twice for them)."""
    rows = []
    printed = check_rows(check)
    for label in ("derived", "published"):
        for n, row in enumerate(printed[label]):
            head = rf"\text{{{label}:}}\quad " if n == 0 else ""
            rows.append(f"{head}& {row}")
    kind = getattr(check, "kind", "paper")
    kind = KIND_NAMES.get(getattr(kind, "value", kind), str(kind))
    if getattr(check, "source", "printed") == "reconstructed":
        kind += " (form reconstructed where the OCR lost it)"
    if getattr(check, "rests_on", ""):
        kind += " (weak: the verdict rests on a chosen parameter or the paper's text)"
    lines = [
        (rf"\subsection*{{[{number}] " if number else r"\subsection*{") + rf"{math_text(check.label)}: {math_text(_heading_text(check))}}}",
        r"\begin{align*}",
        " \\\\\n".join(rows),
        r"\end{align*}",
        # sloppy: the evidence quotes formulas as text, whose long tokens need looser lines
        rf"{{\sloppy \textit{{{escape(kind)}}}, \textbf{{{escape(check.verdict.value)}}}: {escape(check.comparison.detail)}"
        + (rf" (Figure~{figure})" if figure else "") + r"\par}",
        "",
    ]
    alt = getattr(check.comparison, "alternative", None)
    if alt is not None:
        state = "reproduces the published item" if alt.matches_published else "does not reproduce the published item"
        lines += [rf"\textit{{Alternative}} ({escape(alt.assumption)}): \[ {printed['alternative'][0]} \] {escape(state)}.", ""]
    conf = getattr(check.comparison, "confirmation", None)
    if conf is not None:
        state = "agrees with the derived value" if conf.agrees_with_derived else "does not agree with the derived value"
        lines += [rf"\textit{{Independent route}} ({escape(conf.route)}): \[ {printed['confirmation'][0]} \] {escape(state)}.", ""]
    return "\n".join(lines)


def _heading_text(check: Any) -> str:
    """The description after the label in a check's heading, without the words the label
    just said ("coaxiality AI1: AI1: the planet axis ..." reads "coaxiality AI1: the planet axis ...").

    >>> from types import SimpleNamespace as C
    >>> _heading_text(C(label="coaxiality AI1", description="AI1: the planet axis")), _heading_text(C(label="(8)", description="(8) as printed"))
    ('the planet axis', 'as printed')
    """
    label, text = check.label.strip(), check.description
    last = label.split()[-1] if label else ""
    if last and text.startswith(f"{last}: "):
        return text[len(last) + 2:]
    if label.startswith("(") and text.startswith(f"{label} "):
        return text[len(label) + 1:]
    return text


def _row(value: Any) -> str:
    """Display math for an alternative's or a confirmation's value (one row per piece)."""
    return r"\begin{gathered} " + r" \\ ".join(math_rows(value)) + r" \end{gathered}"


def _summary(results: list[Any]) -> str:
    text = (
        f"symkin {__version__} derived every result below with its own engine and compared it with the "
        f"published form: {summarize(results).line()}. A paper item is an item the paper prints; a consistency "
        "check compares two routes of the engine (or is circular, or arithmetic on the paper's own numbers); an "
        "extension goes beyond the paper. A weak verdict rests on a parameter chosen so that the item is "
        "reproduced, or on the paper's own text, and says so."
    )
    return escape(text) + "\n"


def _items(result: Any, check_numbers: dict[int, int]) -> list[str]:
    """The paper's printed items with their verdicts and the numbers of their checks, as a list."""
    items = paper_items(result)
    if not items:
        return []
    out = [r"\begin{itemize}"]
    for it in items:
        verdict = it.verdict.value if it.verdict is not None else "not checked: " + (it.item.not_checked or "no reason given")
        refs = ", ".join(rf"{math_text(c.label)} [{check_numbers[id(c)]}]" for c in it.checks if id(c) in check_numbers)
        out.append(rf"\item {math_text(it.item.item)} ({math_text(it.item.what)}): \textbf{{{escape(verdict)}}}"
                   + (f"; {refs}" if refs else ""))
    out.append(r"\end{itemize}")
    return out


def _figure(fig: Path, root: Path, caption: str, label: str) -> list[str]:
    rel = fig.resolve().relative_to(root.resolve())
    return [
        r"\begin{figure}[!htbp]",
        r"\centering",
        rf"\includegraphics[width=\linewidth,height=0.62\textheight,keepaspectratio]{{{rel.as_posix()}}}",
        rf"\caption{{{caption}}}",
        rf"\label{{{label}}}",
        r"\end{figure}",
        "",
    ]


_Placed = tuple[dict[int, list[tuple[Path, str, str]]], list[tuple[Path, str, str]], dict[int, str]]


def _placed_figures(result: Any, root: Path | None) -> _Placed:
    """Each PDF figure of ``result`` with its caption and label: after the last check its
    caption names (by label prefix, ``REPORT_FIGURES`` of the paper), or unplaced; and the
    figure each check points to."""
    figure_of: dict[int, str] = {}
    if root is None:
        return {}, [], figure_of
    captions = getattr(result, "captions", {}) or {}
    after: dict[int, list[tuple[Path, str, str]]] = {}
    loose: list[tuple[Path, str, str]] = []
    for fig in getattr(result, "figures", []):
        fig = Path(fig)
        if fig.suffix.lower() != ".pdf":
            continue
        try:
            fig.resolve().relative_to(Path(root).resolve())
        except ValueError:
            continue
        text, prefixes = captions.get(fig.stem, ("", ()))
        checks = [c for c in result.checks if any(c.label.startswith(p) for p in prefixes)]
        label = "fig:" + re.sub(r"[^A-Za-z0-9]", "-", fig.stem)
        named = ", ".join(dict.fromkeys(c.label for c in checks))
        caption = math_text(text or fig.stem.replace("_", " "))
        if checks:
            caption += r" \emph{Checks:} " + math_text(named) + "."
        entry = (fig, caption, label)
        if checks:
            after.setdefault(id(checks[-1]), []).append(entry)
            for c in checks:
                figure_of.setdefault(id(c), label)
        else:
            loose.append(entry)
    return after, loose, figure_of


def _cite_key(key: str) -> str:
    """A paper's key as a LaTeX citation key (letters and digits only).

    >>> _cite_key("alyushin2009")
    'alyushin2009'
    """
    return re.sub(r"[^A-Za-z0-9]", "", key) or "paper"


def _bibliography(results: list[Any]) -> list[str]:
    """The papers reproduced, each cited by its section; listed in the contents and the bookmarks."""
    out = [r"\clearpage", r"\phantomsection", r"\addcontentsline{toc}{section}{References}",
           r"\begin{thebibliography}{9}"]
    out += [rf"\bibitem{{{_cite_key(r.key)}}} {escape(r.citation)}" for r in results]
    return out + [r"\end{thebibliography}"]


def _items_index(results: list[Any], check_numbers: dict[int, int]) -> list[str]:
    """An index of every paper's printed items: verdict, and the numbers of the checks."""
    out = [r"\clearpage", r"\phantomsection", r"\addcontentsline{toc}{section}{Index of paper items}",
           r"\section*{Index of paper items}",
           "Every item each paper prints, with its verdict and the numbers [n] of the checks that compare it." + "\n"]
    for r in results:
        block = _items(r, check_numbers)
        if block:
            out += [rf"\subsection*{{{escape(r.key)}}}"] + block
    return out


def equations_document(results: Iterable[Any], root: Path | None = None) -> str:
    """A complete LaTeX document for a list of :class:`~symkin.papers.reproduce.PaperResult`.

    With ``root`` (the report folder), the papers' PDF figures inside it are included as
    numbered figures with captions, each after the checks it illustrates (the paper's
    ``REPORT_FIGURES``: figure name -> caption and check-label prefixes), and each of
    those checks points to it.  The document ends with an index of every printed item.
    """
    results = list(results)
    parts = [PREAMBLE, _summary(results)]
    check_numbers: dict[int, int] = {}  # check -> its number
    figures = 0  # figures placed so far: LaTeX numbers them in the order of their captions
    for r in results:
        parts.append(rf"\section{{\texorpdfstring{{{escape(r.citation)}}}{{{escape_text(r.citation)}}}}}")  # (a bookmark: no breaks)
        parts.append(rf"Paper key: \texttt{{{escape(r.key)}}} \cite{{{_cite_key(r.key)}}}." + "\n")
        after, loose, figure_of = _placed_figures(r, root)
        placed = [label for c in r.checks for _, _, label in after.get(id(c), [])] + [label for _, _, label in loose]
        figure_numbers = {label: figures + k for k, label in enumerate(placed, 1)}
        figures += len(placed)
        for c in r.checks:
            check_numbers[id(c)] = len(check_numbers) + 1
            parts.append(_check_block(c, figure_numbers.get(figure_of.get(id(c), ""), 0), check_numbers[id(c)]))
            for fig, caption, label in after.get(id(c), []):
                parts += _figure(fig, Path(root or "."), caption, label)
        for fig, caption, label in loose:
            parts += _figure(fig, Path(root or "."), caption, label)
        if paper_items(r):
            parts.append(r"\subsection*{Printed items and their verdicts}" + "\n"
                         + "See the index of paper items at the end.")
        for note in getattr(r, "notes", []) or []:
            parts.append(r"\textit{Note:} " + escape(note) + "\n")
    if any(paper_items(r) for r in results):
        parts += _items_index(results, check_numbers)
    if results:
        parts += _bibliography(results)
    parts.append(r"\end{document}")
    return "\n".join(parts) + "\n"
