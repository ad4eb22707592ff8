"""Compile a LaTeX document to PDF with pdflatex (TeX Live's base is enough).

pdflatex is an optional system tool: :func:`find_pdflatex` says whether it is there,
and :data:`MISSING` is the message to show when it is not.

    >>> from symkin.papers.texbuild import overfull_boxes
    >>> overfull_boxes("Overfull \\\\hbox (12.5pt too wide) in paragraph at lines 3--4\\n")
    [12.5]
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

from symkin.errors import ToolError

__all__ = ["find_pdflatex", "compile_pdf", "PdfBuild", "overfull_boxes", "MISSING"]

#: What to tell a user who has no pdflatex.
MISSING = (
    "pdflatex was not found, so equations.pdf was not written (equations.tex was); install TeX Live's "
    "base packages (Debian/Ubuntu: sudo apt-get install texlive-latex-base) and run again"
)


def find_pdflatex() -> str | None:
    """The pdflatex executable on PATH (or ``$SYMKIN_PDFLATEX``; empty means none), or None.

    >>> exe = find_pdflatex()
    >>> exe is None or "pdflatex" in exe
    True
    """
    override = os.environ.get("SYMKIN_PDFLATEX")
    if override is not None:
        return shutil.which(override) if override else None
    return shutil.which("pdflatex")


@dataclass(frozen=True)
class PdfBuild:
    """A compiled document: the PDF and the widths (pt) of any overfull boxes in the log."""

    pdf: Path
    overfull: tuple[float, ...]
    log: str


def overfull_boxes(log: str) -> list[float]:
    """How far each overfull box in a pdflatex log sticks out, in points."""
    return [float(m) for m in re.findall(r"Overfull \\[hv]box \(([\d.]+)pt too (?:wide|high)\)", log)]


def _first_error(log: str) -> str:
    lines = log.splitlines()
    for i, line in enumerate(lines):
        if line.startswith("!") or re.match(r"^\S+\.tex:\d+: ", line):
            context = " ".join(s.strip() for s in lines[i : i + 3] if s.strip())
            return context[:300]
    return (lines[-1] if lines else "no log")[:300]


def compile_pdf(tex: Path, *, pdflatex: str | None = None, timeout: float = 180.0, keep_log: bool = False) -> PdfBuild:
    """Run pdflatex on ``tex`` in its own folder and return the PDF beside it.

    Shell escape is off and pdflatex never waits for input; an interrupt (Ctrl-C) ends it.
    Auxiliary files are removed (the log too unless ``keep_log``).

    Raises
    ------
    ToolError
        When pdflatex is missing, times out, or cannot compile the document.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> tex = pathlib.Path(tempfile.mkdtemp()) / "x.tex"
    >>> _ = tex.write_text(r"\\documentclass{article}\\begin{document}$z_1 + z_2$\\end{document}")
    >>> find_pdflatex() is None or compile_pdf(tex).pdf.read_bytes().startswith(b"%PDF")
    True
    """
    tex = Path(tex).resolve()
    exe = pdflatex or find_pdflatex()
    if exe is None:
        raise ToolError(MISSING)
    folder, job = tex.parent, tex.stem
    # a table of contents, citations and PDF bookmarks are read from the first pass's files by the second
    text = tex.read_text(errors="replace") if tex.exists() else ""
    passes = 2 if any(word in text for word in (r"\tableofcontents", r"\cite{", "{hyperref}")) else 1
    for _ in range(passes):
        try:
            proc = subprocess.run(
                [exe, "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "-file-line-error", tex.name],
                cwd=folder, stdin=subprocess.DEVNULL, capture_output=True, timeout=timeout,
                env={**os.environ, "TEXINPUTS": f"{folder}{os.pathsep}"},
            )
        except subprocess.TimeoutExpired:
            raise ToolError(f"pdflatex did not finish {tex.name} within {timeout:.0f} s; check the TeX installation") from None
        except OSError as err:
            raise ToolError(f"pdflatex could not be started ({err.strerror}); check the TeX installation") from None
        if proc.returncode != 0:
            break
    log_file = folder / f"{job}.log"
    log = log_file.read_text(errors="replace") if log_file.exists() else proc.stdout.decode(errors="replace")
    for suffix in (".aux", ".out", ".toc") + (() if keep_log else (".log",)):
        (folder / f"{job}{suffix}").unlink(missing_ok=True)
    pdf = folder / f"{job}.pdf"
    if proc.returncode != 0 or not pdf.exists():
        raise ToolError(f"pdflatex could not compile {tex.name}: {_first_error(log)} (a symkin bug: please report it)")
    return PdfBuild(pdf, tuple(overfull_boxes(log)), log)
