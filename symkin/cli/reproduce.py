"""``symkin reproduce``: derive and check the papers, write the report folder."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..reproduce import format_table, paper_names, report_json, run


def register(sub: Any) -> None:
    p = sub.add_parser(
        "reproduce",
        help="derive every result of the papers and compare with the published ones",
        description="Derive and compare every result of one paper or all, print the verification table and "
        "write DIR/report.json, DIR/report.txt, DIR/equations.tex and DIR/figures/. The folder is replaced "
        "only when the run completes. Exit 0 when every check matches or is an explained paper slip, 1 otherwise.",
    )
    p.add_argument("papers", nargs="*", default=["all"], metavar="PAPER", help=f"all (default) or any of: {', '.join(paper_names())}")
    p.add_argument("--out", default="symkin-out", metavar="DIR", help="report folder (default ./symkin-out)")
    p.add_argument("--json", action="store_true", help="print the JSON report instead of the table")
    p.add_argument("--quiet", action="store_true", help="no progress display")
    p.set_defaults(run=run_reproduce)


def run_reproduce(args: Any) -> int:
    names = list(dict.fromkeys(args.papers))
    if "all" in names:
        if len(names) > 1:
            raise InputError("give either all or paper names, not both")
        names = list(paper_names())
    for n in names:
        if n not in paper_names():
            raise InputError(f"no paper called {n!r}; choose all or one of {', '.join(paper_names())}")
    out = Path(args.out)
    results = run(names, out, quiet=args.quiet)
    if args.json:
        json.dump(report_json(results, out), sys.stdout, indent=2, ensure_ascii=False)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(format_table(results))
        sys.stdout.write(f"report written to {out}/\n")
    return 0 if all(r.ok for r in results) else 1
