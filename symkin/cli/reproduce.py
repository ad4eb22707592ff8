"""``symkin reproduce``: derive and check the papers, write the report folder."""

from __future__ import annotations

import argparse
import json
import warnings
from pathlib import Path
from typing import Any

from symkin.cli.common import add_command, add_out_argument, add_quiet_flag, emit
from symkin.errors import InputError, SymkinWarning


class _PapersHelp(argparse.HelpFormatter):
    """Names the registered papers in the help of PAPER when the help is printed: finding
    them reads every installed distribution's entry points, which ``symkin --help`` need not."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = super()._get_help_string(action)
        if action.dest == "papers" and text is not None:
            from symkin.papers.registry import paper_names

            text += ", ".join(paper_names())
        return text


def register(sub: Any) -> None:
    """Add the ``reproduce`` command to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "reproduce",
        help="derive every result of the papers and compare with the published ones",
        description="Derive and compare every result of one paper or all, print the verification table and "
        "write DIR/report.json, DIR/report.txt, DIR/equations.tex, DIR/equations.pdf (with pdflatex) and "
        "DIR/figures/. The folder is replaced only when the run completes: an interrupted or failed run "
        "leaves the previous report as it was. Every verdict is computed: match, match (published value "
        "rounded), paper slip (explained: an alternative reproduces the printed item), paper error "
        "(confirmed by an independent route), or differs. A part of a derivation that raises (a broken "
        "engine) is a failure check that differs; the report is still written. A weak verdict (kind column: "
        "weak) rests on a chosen parameter or the paper's text and says so; reconstructed: the form compared "
        "was rebuilt where the OCR lost it. Exit 1 when a check differs, 0 otherwise, 2 on "
        "bad input. With --json the report (symkin/papers/report.schema.json) is printed instead of the table.",
        run=run_reproduce,
    )
    p.formatter_class = _PapersHelp
    p.add_argument("papers", nargs="*", default=["all"], metavar="PAPER", help="all (default) or any of: ")
    add_out_argument(p, "DIR: the report folder, written whole or not at all (default ./symkin-out)", required=False,
                     default="symkin-out")
    add_quiet_flag(p)
    p.add_argument("--no-pdf", action="store_true", help="do not compile equations.tex to equations.pdf")
    p.add_argument("--jobs", type=_jobs, default=None, metavar="N",
                   help="N: worker processes for the papers' checks and figures (default: one per core; 1: none)")


def _jobs(text: str) -> int:
    """The --jobs value: a whole number of at least 1."""
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        raise argparse.ArgumentTypeError(f"--jobs takes a whole number of at least 1, not {text!r}")
    return n


def run_reproduce(args: Any) -> Any:
    """Run ``symkin reproduce`` with the parsed ``args``: derive and check the papers named, print the table and write the report folder; returns its output (exit status 1 when some check differs)."""
    from symkin.papers.registry import paper_names
    from symkin.papers.reproduce import run
    from symkin.papers.texbuild import MISSING, find_pdflatex

    names = list(dict.fromkeys(args.papers))
    known = paper_names()  # read from the installed metadata: once
    if "all" in names:
        if len(names) > 1:
            raise InputError("give either all or paper names, not both")
        names = list(known)
    for n in names:
        if n not in known:
            raise InputError(f"no paper called {n!r}; choose all or one of {', '.join(known)}")
    out = Path(args.out)
    pdf = not args.no_pdf
    results = run(names, out, quiet=args.quiet, pdf=pdf, jobs=args.jobs)
    pdf_note = MISSING if pdf and find_pdflatex() is None else ""
    # the report as written (its figure paths are relative to the folder it was built in)
    data = json.loads((out / "report.json").read_text()) if args.json else {}
    data["equations"] = {"tex": "equations.tex", "pdf": "equations.pdf" if (out / "equations.pdf").exists() else None}
    if pdf_note:
        data["equations"]["note"] = pdf_note
        warnings.warn(pdf_note, SymkinWarning, stacklevel=1)
    written = ["report.json", "report.txt", "equations.tex"] + (["equations.pdf"] if (out / "equations.pdf").exists() else []) + ["figures/"]
    table = (out / "report.txt").read_text()  # format_table(results), as written
    return emit(table + f"report written to {out}/: {', '.join(written)}\n", data, 0 if all(r.ok for r in results) else 1)
