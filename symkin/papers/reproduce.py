"""Reproduce the papers: derive, compare, and write a report folder atomically.

The report is built in a temporary folder beside the target and renamed into place
only when complete, so an interrupted run leaves the previous report intact.  A fault
of the engine or of a paper's module (an exception while it loads, derives, notes or draws)
is a ``failure`` check of that paper with verdict ``differs``: the other checks and papers
still run and the report is written (see :func:`symkin.papers.checks.gather`).

    >>> from symkin.papers.reproduce import paper_names
    >>> "alyushin2009" in paper_names()
    True
"""

from __future__ import annotations

import copyreg
import json
import multiprocessing
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path
from types import ModuleType
from typing import Any, TextIO

from symkin._io.atomic import STOP_SIGNALS, check_replaceable, recover, stop_signals_held, write_atomically
from symkin._io.progress import Progress
from symkin._version import __version__
from symkin.errors import InputError
from symkin.papers.checks import Check, ItemResult, PrintedItem, Verdict, failure, gather
from symkin.papers.document import check_rows, equations_document
from symkin.papers.registry import load, paper_names
from symkin.papers.summary import Summary, paper_items, summarize
from symkin.papers.texbuild import compile_pdf, find_pdflatex

__all__ = [
    "paper_names", "load", "PaperResult", "Summary", "summarize", "run", "check_target", "write_atomically",
    "format_table", "report_json", "report_schema", "SCHEMA_VERSION",
]

#: The version of the layout of report.json, described by ``report.schema.json`` beside this
#: module (:func:`report_schema`).  A new key raises the minor number, a changed or removed
#: one the major number.
SCHEMA_VERSION = "1.1"


@dataclass
class PaperResult:
    """One paper's checks, its list of printed items, figures and notes; ``captions`` maps a
    figure's name (its file stem) to its caption and the label prefixes of the checks it
    illustrates (the paper module's ``REPORT_FIGURES``)."""

    key: str
    citation: str
    checks: list[Check]
    figures: list[Path] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    seconds: float = 0.0
    items: list[PrintedItem] = field(default_factory=list)
    captions: dict[str, tuple[str, tuple[str, ...]]] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        """True when no check differs (``differs`` is the only failing verdict)."""
        return all(c.verdict.ok for c in self.checks)

    def _repr_html_(self) -> str:
        """The paper's checks and printed items as tables, for Jupyter (math typeset by MathJax).

        >>> from symkin.papers.checks import compare_exact
        >>> r = PaperResult("p", "A paper", [Check.make("p", "(1)", "one", 1, 1, compare_exact(1, 1))])
        >>> "<td>(1)</td>" in r._repr_html_()
        True
        """
        from symkin._util.display import html_table

        checks = html_table(
            ["check", "item", "kind", "verdict", "derived", "published", "detail"],
            [(c.label, c.item, c.kind.value, c.verdict.value, f"${c.derived_latex}$" if c.derived_latex else "",
              f"${c.published_latex}$" if c.published_latex else "", c.comparison.detail) for c in self.checks],
            caption=f"{self.citation}: {summarize([self]).line()}", raw_columns=(4, 5))
        items = self.item_results
        if not items:
            return checks
        table = html_table(["printed item", "what", "verdict", "checks"],
                           [(it.item.item, it.item.what,
                             it.verdict.value if it.verdict is not None else "not checked: " + it.item.not_checked,
                             ", ".join(c.label for c in it.checks)) for it in items], caption="Printed items")
        return checks + table

    @property
    def item_results(self) -> list[ItemResult]:
        """Every printed item with its paper checks (see :func:`~symkin.papers.summary.paper_items`)."""
        return paper_items(self)


@cache
def report_schema() -> dict[str, Any]:
    """The JSON Schema of report.json (``symkin/papers/report.schema.json``).

    >>> report_schema()["properties"]["schema_version"]["const"] == SCHEMA_VERSION
    True
    """
    text = resources.files("symkin.papers").joinpath("report.schema.json").read_text(encoding="utf-8")
    schema: dict[str, Any] = json.loads(text)
    return schema


def run(
    names: Iterable[str],
    out: Path,
    *,
    progress: TextIO | None = None,
    quiet: bool = False,
    pdf: bool = True,
    jobs: int | None = None,
) -> list[PaperResult]:
    """Derive and check each paper and write the report folder ``out``.

    Writes ``report.json``, ``report.txt``, ``equations.tex`` (all derived equations
    beside the published ones), ``equations.pdf`` (compiled with pdflatex when ``pdf``
    and pdflatex is installed; see :data:`symkin.papers.texbuild.MISSING`) and ``figures/``
    (PNG and PDF); see :func:`write_atomically` for the guarantee on ``out``.

    The papers' checks and figures run in ``jobs`` worker processes (default: one per
    core; 1 runs everything in this process); the results do not depend on ``jobs``.

    Raises
    ------
    InputError
        ``out`` cannot be written, or an unknown paper is named.
    ToolError
        pdflatex is installed but fails on the document (``out`` is left as it was).
    """
    names = list(names)
    modules = {n: _load(n) for n in names}
    check_target(out)
    pdflatex = find_pdflatex() if pdf else None
    results: list[PaperResult] = []
    if jobs is None:  # one worker per core this process may run on (only Linux has workers)
        jobs = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else 1
    previous = _previous_seconds(out)

    def build(tmp: Path) -> None:
        bar = Progress(2 * len(modules) + 1 + (pdflatex is not None), stream=progress, enabled=not quiet, lines=True)
        figures_dir = tmp / "figures"
        figures_dir.mkdir()
        found: dict[str, PaperResult] = {}

        def done(name: str, value: tuple[list[Check], list[str], list[Path], float]) -> None:
            checks, notes, figures, seconds = value
            mod = modules[name]
            found[name] = PaperResult(name, mod.CITATION, checks, figures, notes, seconds,
                                      list(getattr(mod, "PRINTED_ITEMS", ())), dict(getattr(mod, "REPORT_FIGURES", {})))
            _print_ahead(checks)
            bar.step(f"{name}: derived and compared")
            bar.step(f"{name}: figures drawn")

        # the slowest paper first, so that no worker is left alone with it at the end: slowest
        # in the report already in ``out``, else the one with the most figures
        order = sorted(names, key=lambda n: (-previous.get(n, 0.0), -len(getattr(modules[n], "REPORT_FIGURES", {}))))
        run_papers(modules, order, figures_dir, jobs=max(1, int(jobs)), done=done)
        results.extend(found[name] for name in names)
        bar.step("writing report.json, report.txt, equations.tex")
        document = equations_document(results, root=tmp)
        (tmp / "equations.tex").write_text(document)
        data = report_json(results, tmp)
        data["equations"] = {"tex": "equations.tex", "pdf": "equations.pdf" if pdflatex else None}
        (tmp / "report.json").write_text(json.dumps(data, indent=2, ensure_ascii=False))
        (tmp / "report.txt").write_text(format_table(results))
        if pdflatex:
            bar.step("compiling equations.pdf with pdflatex")
            compile_pdf(tmp / "equations.tex", pdflatex=pdflatex)
        for hook in _POST_BUILD:
            hook(tmp, results)
        bar.close()

    write_atomically(out, build, version=__version__)
    return results


def _load(name: str) -> ModuleType:
    """The module of paper ``name``; one that raises while it loads stands in as a module whose
    ``checks()`` raises that error (an unknown name is still an :class:`InputError`)."""
    if name not in paper_names():
        return load(name)  # the InputError that names the choices
    try:
        return load(name)
    except Exception as error:  # a broken paper module is a failing check, not a lost report
        stand_in, caught = ModuleType(name), error  # ``error`` itself is unbound when the block ends

        def checks() -> list[Check]:
            raise caught

        stand_in.__dict__.update(CITATION=name, checks=checks, figures=lambda folder: [])
        return stand_in


#: The papers' modules a worker process runs (set in each worker by :func:`_start_worker`).
_MODULES: dict[str, ModuleType] = {}


def _paper(mod: ModuleType, figures_dir: Path, key: str = "") -> tuple[list[Any], list[str], list[Path], float]:
    """One paper's checks, notes and figures, and the seconds they took, in this process; each of
    the three that raises gives a ``failure`` check instead (:func:`~symkin.papers.checks.gather`)."""
    start = time.perf_counter()
    key = key or str(getattr(mod, "KEY", mod.__name__.rsplit(".", 1)[-1]))
    notes: list[str] = []
    figures: list[Path] = []

    def checks() -> list[Check]:
        return list(mod.checks())

    def notes_() -> list[Check]:  # its failure is labelled "notes: failed"
        notes.extend(getattr(mod, "notes", lambda: [])())
        return []

    def figures_() -> list[Check]:
        figures.extend(mod.figures(figures_dir))
        return []

    found = gather(key, checks, notes_, figures_)
    return found, notes, figures, time.perf_counter() - start


def _paper_in_worker(name: str, figures_dir: Path) -> tuple[list[Any], list[str], list[Path], float]:
    return _paper(_MODULES[name], figures_dir, name)


def run_papers(modules: dict[str, ModuleType], order: list[str], figures_dir: Path, *, jobs: int,
               done: Callable[[str, Any], None]) -> None:
    """Run each paper of ``order`` (its checks, then its figures: one task, so that what its
    module caches is computed once) and call ``done(name, (checks, notes, figures, seconds))``
    in this process as each ends.  A worker that dies gives its paper a ``failure`` check.

    With ``jobs`` > 1, on Linux and from a process running one thread, the papers run in a
    process pool whose workers are forked: they run the modules as this process has them
    (patched, as tests patch the engine or a paper) and find them without pickling.  A fork from
    a process running threads can deadlock, and elsewhere fork is unsafe or missing: there, as
    with ``jobs`` 1, the papers run here one after the other.
    """
    jobs = min(jobs, len(order))
    can_fork = sys.platform.startswith("linux") and threading.active_count() == 1
    if jobs <= 1 or not can_fork:
        for name in order:
            done(name, _paper(modules[name], figures_dir, name))
        return
    _import_figures()  # once here, not once in each worker
    before = set(multiprocessing.active_children())
    # a Ctrl-C while the workers are forked would be raised in the fork's own callbacks, where
    # Python drops it: held until they are started, then raised here
    with stop_signals_held():
        pool = ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("fork"), initializer=_start_worker,
                                   initargs=(modules, os.getpid()))
        futures = {pool.submit(_paper_in_worker, name, figures_dir): name for name in order}
    workers = set(multiprocessing.active_children()) - before
    try:
        for future in as_completed(futures):
            try:
                value = future.result()
            except Exception as error:
                value = ([failure(futures[future], "worker", error)], [], [], 0.0)
            done(futures[future], value)
    except BaseException:
        for worker in workers:  # a failure or an interrupt ends the other papers at once
            worker.kill()
        raise
    finally:
        pool.shutdown(cancel_futures=True)


def _start_worker(modules: dict[str, ModuleType], parent: int) -> None:
    """Set up a worker process: the papers' modules; Ctrl-C left to the calling process (which
    ends its workers) and SIGTERM ending it; its relations sent back as they are; its end when
    the calling process ends (killed, it cannot end its workers)."""
    _MODULES.update(modules)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)  # held by the calling process while it forked
    import sympy as sp

    for cls in (sp.Eq, sp.Ne, sp.Lt, sp.Le, sp.Gt, sp.Ge):
        copyreg.pickle(cls, _reduce_relation)
    threading.Thread(target=_end_with, args=(parent,), daemon=True).start()


def _end_with(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(0.2)
    os._exit(1)


def _reduce_relation(rel: Any) -> tuple[Any, tuple[Any, ...]]:
    """SymPy's relations travel from a worker as they are: by default ``Eq(lhs, rhs)`` is called
    again when one is loaded, which decides it (an unevaluated ``Eq(2, 2)`` arrives as ``True``),
    and the results would depend on ``--jobs``."""
    return _relation, (type(rel), rel.lhs, rel.rhs)


def _relation(cls: type, lhs: Any, rhs: Any) -> Any:
    return cls(lhs, rhs, evaluate=False)


def _import_figures() -> None:
    """Import what the papers' figures are drawn with (matplotlib's figure, its PNG and PDF
    backends) in the calling process, before the workers are forked."""
    import matplotlib.backends.backend_agg
    import matplotlib.backends.backend_pdf  # noqa: F401

    import symkin.viz.figures  # noqa: F401


def _print_ahead(checks: list[Check]) -> None:
    """Print a paper's checks for the report (their text for report.json and report.txt, their
    rows for equations.tex) as they arrive, while the workers derive the other papers."""
    for check in checks:
        if isinstance(check, Check):
            check.to_json()
            check_rows(check)


def _previous_seconds(out: Path) -> dict[str, float]:
    """The seconds each paper took in the report already in ``out`` (empty when there is none)."""
    try:
        papers = json.loads((Path(out) / "report.json").read_text(encoding="utf-8"))["papers"]
        return {str(k): float(v["seconds"]) for k, v in papers.items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return {}


#: Functions called with (folder, results) after the report files are written, before
#: the folder is renamed into place.
_POST_BUILD: list[Callable[[Path, list[PaperResult]], None]] = []


def report_json(results: list[PaperResult], root: Path) -> dict[str, Any]:
    """The content of report.json (``root``: the folder the figure paths are relative to).

    Every check carries its kind, verdict, derived and published objects as text and
    LaTeX (and as floats when they are numbers), and the alternative or confirmation a
    slip or an error rests on; every paper lists its printed items with their verdicts.
    ``report.schema.json`` (:func:`report_schema`) describes the whole layout.
    """
    checks = [c for r in results for c in r.checks]
    summary = summarize(results).to_json()
    summary["by_verdict"] = {v: sum(c.verdict.value == v for c in checks) for v in sorted({c.verdict.value for c in checks})}
    return {
        "schema_version": SCHEMA_VERSION,
        "symkin_version": __version__,
        "summary": summary,
        "papers": {
            r.key: {
                "citation": r.citation,
                "ok": r.ok,
                "seconds": round(r.seconds, 3),
                "summary": summarize([r]).to_json(),
                "items": [i.to_json() for i in r.item_results],
                "checks": [c.to_json() for c in r.checks],
                "figures": [str(p.relative_to(root)) for p in r.figures],
                "notes": r.notes,
            }
            for r in results
        },
    }


def check_target(out: Path) -> None:
    """Refuse a report folder symkin must not replace: a file, the current folder or one
    holding it, a non-empty folder that is not a report symkin wrote (one with symkin's
    manifest of the files it wrote, :data:`symkin._io.atomic.MANIFEST`), or a report
    whose files were changed since.  Files a user added to a report are kept (carried into
    the new one).  What a killed run left beside ``out`` is tidied first
    (:func:`symkin._io.atomic.recover`).

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
    try:
        recover(target)
    except OSError as err:
        raise InputError(f"cannot tidy the folder {parent}: {err.strerror}; choose a writable --out") from None
    if target.is_dir():
        check_replaceable(out, "a symkin report")


def _short(text: str, width: int) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= width else text[: width - 3] + "..."


def _kind_cell(check: Check) -> str:
    """The check's kind, with ``reconstructed`` and ``weak`` when they apply."""
    marks = [m for m, on in (("reconstructed", check.source == "reconstructed"), ("weak", bool(check.rests_on))) if on]
    return check.kind.value + (f" ({', '.join(marks)})" if marks else "")


def format_table(results: list[PaperResult]) -> str:
    """The verification table (paper, kind, result, derived, published, verdict), the
    summary line, the checks compared with a reconstructed form, the evidence of every verdict
    other than a plain match and of every weak one, and the printed items no check compares.

    The kind column says ``reconstructed`` for a check whose published side is reconstructed
    where the OCR lost the printed form, and ``weak`` for one whose verdict rests on a chosen
    parameter or the paper's own text (:attr:`Check.rests_on`)."""
    rows = [("paper", "kind", "result", "derived", "published", "verdict")]
    for r in results:
        for c in r.checks:
            rows.append((r.key, _kind_cell(c), c.label, _short(c.derived_text, 38), _short(c.published_text, 38),
                         c.verdict.value))
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(row, widths)).rstrip() for row in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    summary = summarize(results)
    lines.append("")
    lines.append(summary.line())
    bad = [c for r in results for c in r.checks if not c.verdict.ok]
    if bad:
        lines.append("differ: " + ", ".join(f"{c.paper} {c.label}" for c in bad))
    rebuilt = [f"{c.paper} {c.label}" for r in results for c in r.checks if c.source == "reconstructed"]
    if rebuilt:
        lines.append("compared with a form reconstructed from the paper's text (the OCR lost the printed one): "
                     + ", ".join(rebuilt))
    for r in results:
        for c in r.checks:
            if c.verdict is not Verdict.MATCH or c.rests_on:
                lines.append(f"  {r.key} {c.label} [{_kind_cell(c)}]: {c.verdict.value}: {c.comparison.detail}")
    unchecked = [(r.key, i) for r in results for i in r.item_results if i.verdict is None]
    if unchecked:
        lines.append("printed items not checked:")
        lines += [f"  {key} {i.item.item} ({i.item.what}): {i.item.not_checked or 'no reason given'}" for key, i in unchecked]
    return "\n".join(lines) + "\n"
