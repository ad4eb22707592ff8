"""Every notebook in notebooks/ is executed, and its stored outputs must be what it gives now.

Notebooks are found automatically (notebooks/*.ipynb), so one added later is run too.
A notebook built from a source in notebooks/src/ must also match that source.  When a
change to symkin changes a notebook's output on purpose, rebuild the stored notebooks:
``python notebooks/build.py --execute``.
"""

import copy
import difflib
import importlib.util
import re
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat", reason="the notebook tests need the test extra: pip install -e .[test]")
pytest.importorskip("nbclient", reason="the notebook tests need the test extra: pip install -e .[test]")
pytest.importorskip("ipykernel", reason="the notebook tests need the test extra: pip install -e .[test]")

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
SOURCES = sorted((ROOT / "notebooks" / "src").glob("*.py"))
REBUILD = "rebuild it with: python notebooks/build.py --execute"


def _build_module():
    spec = importlib.util.spec_from_file_location("notebooks_build", ROOT / "notebooks" / "build.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


build = _build_module()


def outputs(nb) -> list[list[str]]:
    """What each code cell shows, as comparable text: streams merged, object addresses and
    image bytes left out (an image counts by its presence)."""
    shown = []
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        items: list[str] = []
        for out in cell.get("outputs", []):
            if out.output_type == "stream":
                text = f"[{out.name}] {out.text}"
                if items and items[-1].startswith(f"[{out.name}] "):
                    items[-1] += out.text
                else:
                    items.append(text)
            elif out.output_type in ("execute_result", "display_data"):
                data = out.get("data", {})
                for kind in sorted(data):
                    if kind.startswith("image/"):
                        items.append(f"<{kind}>")
                    elif kind in ("text/plain", "text/latex", "text/markdown"):
                        items.append(f"{kind}: " + re.sub(r" at 0x[0-9a-f]+", "", str(data[kind])))
            elif out.output_type == "error":
                items.append(f"error: {out.ename}: {out.evalue}")
        shown.append(items)
    return shown


def test_notebooks_exist_for_every_source():
    assert NOTEBOOKS, "notebooks/ holds no notebook"
    for src in SOURCES:
        assert (ROOT / "notebooks" / f"{src.stem}.ipynb").exists(), f"notebooks/src/{src.name} was never built; {REBUILD}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_cells_match_their_source(path):
    src = ROOT / "notebooks" / "src" / f"{path.stem}.py"
    if not src.exists():
        pytest.skip(f"{path.name} has no source in notebooks/src (edited as a notebook)")
    stored = [(c.cell_type, c.source) for c in nbformat.read(path, as_version=4).cells]
    fresh = [(c.cell_type, c.source) for c in build.notebook_from_source(src).cells]
    assert stored == fresh, f"notebooks/{path.name} differs from notebooks/src/{src.name}; {REBUILD}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_and_its_stored_outputs_are_current(path, tmp_path):
    stored = nbformat.read(path, as_version=4)
    nb = copy.deepcopy(stored)
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
    try:
        build.execute(nb, tmp_path, timeout=300)
    except Exception as err:  # a failing cell: show which, in one message
        pytest.fail(f"notebooks/{path.name} failed to run: {type(err).__name__}: {str(err)[-1500:]}")
    got, want = outputs(nb), outputs(stored)
    if got != want:
        diff = "\n".join(difflib.unified_diff(
            [line for cell in want for item in cell for line in item.splitlines()],
            [line for cell in got for item in cell for line in item.splitlines()],
            "stored", "now", lineterm="", n=1))
        pytest.fail(f"notebooks/{path.name} shows different outputs now than it stores; {REBUILD}\n{diff[:4000]}")
