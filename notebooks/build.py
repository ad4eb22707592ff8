"""Build the notebooks from their readable sources, and execute them.

Each notebook is written as a plain Python file in ``notebooks/src/`` ("percent" format:
``# %%`` starts a code cell, ``# %% [markdown]`` a markdown cell whose lines start with
``# ``).  This script turns each into ``notebooks/<name>.ipynb`` and, with ``--execute``,
runs it so that the stored notebook shows its outputs (figures, LaTeX, tables)::

    python notebooks/build.py --execute          # rebuild and execute every notebook
    python notebooks/build.py --execute tutorial  # just one

The tests (tests/project/test_notebooks.py) execute every notebooks/*.ipynb again and fail when
its stored outputs or its cells differ from what its source gives now.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent
SOURCES = HERE / "src"
KERNEL = {"display_name": "Python 3", "language": "python", "name": "python3"}


def cells_from_source(text: str) -> list[nbformat.NotebookNode]:
    """Notebook cells from a percent-format Python source."""
    cells = []
    kind, lines = None, []

    def flush() -> None:
        body = "\n".join(lines).strip("\n")
        if kind is None or not body:
            return
        if kind == "markdown":
            md = "\n".join(re.sub(r"^# ?", "", line) for line in body.splitlines())
            cells.append(nbformat.v4.new_markdown_cell(md))
        else:
            cells.append(nbformat.v4.new_code_cell(body))

    for line in text.splitlines():
        m = re.match(r"^# %%( \[markdown\])?\s*$", line)
        if m:
            flush()
            kind, lines = ("markdown" if m.group(1) else "code"), []
        elif kind is not None:
            lines.append(line)
    flush()
    for i, cell in enumerate(cells):  # stable ids: the same source gives the same notebook
        cell["id"] = f"cell-{i:02d}"
    return cells


def notebook_from_source(path: Path) -> nbformat.NotebookNode:
    nb = nbformat.v4.new_notebook()
    nb.cells = cells_from_source(path.read_text())
    nb.metadata["kernelspec"] = dict(KERNEL)
    nb.metadata["language_info"] = {"name": "python"}
    nb.metadata["symkin"] = {"source": f"notebooks/src/{path.name}", "built_by": "notebooks/build.py"}
    return nb


def execute(nb: nbformat.NotebookNode, cwd: Path, timeout: int = 600) -> nbformat.NotebookNode:
    """Run every cell of ``nb`` in a fresh kernel, in folder ``cwd``; raises on a failing cell."""
    from jupyter_client.manager import KernelManager
    from nbclient import NotebookClient

    # the kernel talks over local socket files, not TCP ports
    km = KernelManager(kernel_name="python3", transport="ipc", ip=str(cwd / "kernel"))
    client = NotebookClient(nb, km=km, timeout=timeout, kernel_name="python3", record_timing=False,
                            resources={"metadata": {"path": str(cwd)}})
    try:
        client.execute()
    finally:
        if km.has_kernel:
            km.shutdown_kernel(now=True)
    nb.metadata["language_info"] = {"name": "python"}  # no interpreter version: the stored file stays stable
    # widget state is not stored: a widget needs a live kernel, and its state would repeat the outputs
    nb.metadata.pop("widgets", None)
    return nb


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="notebooks to build (default: every source in notebooks/src)")
    parser.add_argument("--execute", action="store_true", help="run the notebooks and store their outputs")
    args = parser.parse_args(argv)
    sources = sorted(SOURCES.glob("*.py"))
    if args.names:
        sources = [s for s in sources if s.stem in args.names]
        missing = set(args.names) - {s.stem for s in sources}
        if missing:
            parser.error(f"no source for {', '.join(sorted(missing))} in {SOURCES}")
    import tempfile

    for src in sources:
        nb = notebook_from_source(src)
        if args.execute:
            with tempfile.TemporaryDirectory() as tmp:
                execute(nb, Path(tmp))
        target = HERE / f"{src.stem}.ipynb"
        nbformat.write(nb, target)
        print(f"wrote {target.relative_to(HERE.parent)}" + (" (executed)" if args.execute else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
