"""Reproduce the papers: derive, compare, and write a report folder atomically.

The report is built in a temporary folder beside the target and renamed into place
only when complete, so an interrupted or failing run leaves the previous report intact.

    >>> from symkin.reproduce import paper_names
    >>> "alyushin2009" in paper_names()
    True
"""

from __future__ import annotations

import importlib
import json
import os
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterable, TextIO

from .atomic import write_atomically
from .errors import InputError
from .report import Check

__all__ = ["paper_names", "load", "PaperResult", "run", "check_target", "write_atomically", "format_table"]


def paper_names() -> tuple[str, ...]:
    """The papers symkin reproduces, by key."""
    from symkin.derivations import PAPERS

    return tuple(PAPERS)


def load(name: str) -> Any:
    """The derivation module of paper ``name``."""
    from symkin.derivations import PAPERS

    if name not in PAPERS:
        raise InputError(f"no paper called {name!r}; choose all or one of {', '.join(PAPERS)}")
    return importlib.import_module(PAPERS[name])


@dataclass
class PaperResult:
    key: str
    citation: str
    checks: list[Check]
    figures: list[Path] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return all(c.verdict.ok for c in self.checks)


class Progress:
    """A one-line progress display on a terminal, plain lines otherwise."""

    def __init__(self, total: int, stream: TextIO | None = None):
        self.total, self.done = total, 0
        self.stream = stream if stream is not None else sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()

    def step(self, message: str) -> None:
        self.done += 1
        width = 24
        filled = int(width * (self.done - 1) / max(self.total, 1))
        line = f"[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} {message}"
        if self.tty:
            self.stream.write("\r\x1b[2K" + line)
        else:
            self.stream.write(line + "\n")
        self.stream.flush()

    def close(self) -> None:
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()


def run(
    names: Iterable[str],
    out: Path,
    *,
    progress: TextIO | None = None,
    quiet: bool = False,
    pdf: bool = True,
) -> list[PaperResult]:
    """Derive and check each paper and write the report folder ``out``.

    Writes ``report.json``, ``report.txt``, ``equations.tex`` (all derived equations
    beside the published ones), ``equations.pdf`` (compiled with pdflatex when ``pdf``
    and pdflatex is installed; see :data:`symkin.texbuild.MISSING`) and ``figures/``
    (PNG and PDF); see :func:`write_atomically` for the guarantee on ``out``.

    Raises
    ------
    InputError
        ``out`` cannot be written, or an unknown paper is named.
    ToolError
        pdflatex is installed but fails on the document (``out`` is left as it was).
    """
    from .latex_report import equations_document
    from .texbuild import compile_pdf, find_pdflatex

    names = list(names)
    modules = [load(n) for n in names]
    check_target(out)
    pdflatex = find_pdflatex() if pdf else None
    results: list[PaperResult] = []

    def build(tmp: Path) -> None:
        with open(os.devnull, "w") as devnull:
            bar = Progress(2 * len(modules) + 1 + (pdflatex is not None), devnull if quiet else progress)
            figures_dir = tmp / "figures"
            figures_dir.mkdir()
            for name, mod in zip(names, modules):
                start = time.perf_counter()
                bar.step(f"{name}: deriving and comparing")
                checks = list(mod.checks())
                bar.step(f"{name}: drawing figures")
                figures = list(mod.figures(figures_dir))
                notes = list(getattr(mod, "notes", lambda: [])())
                results.append(
                    PaperResult(name, mod.CITATION, checks, figures, notes, time.perf_counter() - start)
                )
            bar.step("writing report.json, report.txt, equations.tex")
            data = report_json(results, tmp)
            data["equations"] = {"tex": "equations.tex", "pdf": "equations.pdf" if pdflatex else None}
            (tmp / "report.json").write_text(json.dumps(data, indent=2, ensure_ascii=False))
            (tmp / "report.txt").write_text(format_table(results))
            (tmp / "equations.tex").write_text(equations_document(results, root=tmp))
            if pdflatex is not None:
                bar.step("compiling equations.pdf with pdflatex")
                compile_pdf(tmp / "equations.tex", pdflatex=pdflatex)
            for hook in _POST_BUILD:
                hook(tmp, results)
            bar.close()

    write_atomically(out, build)
    return results


#: Functions called with (folder, results) after the report files are written, before
#: the folder is renamed into place.
_POST_BUILD: list[Callable[[Path, list[PaperResult]], None]] = []


def report_json(results: list[PaperResult], root: Path) -> dict[str, Any]:
    from . import __version__

    checks = [c for r in results for c in r.checks]
    return {
        "symkin_version": __version__,
        "summary": {
            "checks": len(checks),
            "ok": sum(c.verdict.ok for c in checks),
            "differs": sum(not c.verdict.ok for c in checks),
            "by_verdict": {v: sum(c.verdict.value == v for c in checks) for v in sorted({c.verdict.value for c in checks})},
        },
        "papers": {
            r.key: {
                "citation": r.citation,
                "ok": r.ok,
                "seconds": round(r.seconds, 3),
                "checks": [c.to_json() for c in r.checks],
                "figures": [str(p.relative_to(root)) for p in r.figures],
                "notes": r.notes,
            }
            for r in results
        },
    }


def check_target(out: Path) -> None:
    """Refuse a report folder symkin must not replace: a file, the current folder or one
    holding it, or a non-empty folder that is not a previous symkin report.

    >>> check_target(Path("/"))
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: --out / holds the current folder; choose a new folder such as ./symkin-out
    """
    out = Path(out)
    target = out.resolve()
    if target.exists() and not target.is_dir():
        raise InputError(f"--out {out} is a file, not a folder; choose another --out")
    if target == Path.cwd().resolve() or target in Path.cwd().resolve().parents:
        raise InputError(f"--out {out} holds the current folder; choose a new folder such as ./symkin-out")
    parent = target.parent
    if not parent.exists():
        raise InputError(f"cannot write {out}: its parent folder {parent} does not exist; create it or choose another --out")
    if not parent.is_dir():
        raise InputError(f"cannot write {out}: {parent} is a file, not a folder; choose another --out")
    if target.is_dir() and any(target.iterdir()) and not _is_report(target):
        raise InputError(
            f"--out {out} is a folder that is not a symkin report and symkin replaces the whole folder; "
            "choose a new or empty folder"
        )


def _is_report(folder: Path) -> bool:
    try:
        data = json.loads((folder / "report.json").read_text())
    except (OSError, ValueError):
        return False
    return isinstance(data, dict) and "symkin_version" in data


def _short(text: str, width: int) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= width else text[: width - 3] + "..."


def format_table(results: list[PaperResult]) -> str:
    """The verification table: paper, equation, derived, published, verdict."""
    rows = [("paper", "result", "derived", "published", "verdict")]
    for r in results:
        for c in r.checks:
            rows.append((r.key, c.label, _short(_plain(c.derived), 38), _short(_plain(c.published), 38), c.verdict.value))
    widths = [max(len(row[i]) for row in rows) for i in range(5)]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    checks = [c for r in results for c in r.checks]
    bad = [c for c in checks if not c.verdict.ok]
    lines.append("")
    lines.append(
        f"{len(checks)} checks: {len(checks) - len(bad)} reproduced"
        + (f", {len(bad)} differ: " + ", ".join(f"{c.paper} {c.label}" for c in bad) if bad else "")
    )
    for r in results:
        slips = [c for c in r.checks if c.verdict.value.startswith("paper slip") or c.verdict.value.startswith("match (")]
        for c in slips:
            lines.append(f"  {r.key} {c.label}: {c.verdict.value}: {c.comparison.detail}")
    return "\n".join(lines) + "\n"


def _plain(value: Any) -> str:
    if isinstance(value, (list, tuple)):
        return "; ".join(_plain(v) for v in value)
    return str(value)
