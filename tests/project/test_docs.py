"""The documentation builds with Sphinx, warnings as errors, and covers what it must: every
public module in the API reference, every notebook as a page, every figure type in the gallery.

CI runs only the test command of the README, so the docs build is this test.  The build is
the one a user runs (``python -m sphinx -W -b html docs OUT``), into a temporary folder; the
gallery images are drawn by symkin into ``docs/gallery/`` (untracked) and redrawn only when a
source file of symkin is newer.
"""

import ast
import importlib.util
import os
import re
import resource
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"


def _needs(module: str) -> None:
    if importlib.util.find_spec(module) is None:
        message = f"the docs build needs {module}: pip install -e .[test] (or .[docs])"
        if os.environ.get("CI"):
            pytest.fail(message + "; CI must have it")
        pytest.skip(message)


def _gallery():
    spec = importlib.util.spec_from_file_location("docs_gallery", DOCS / "gallery.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("docs_gallery", module)  # its dataclass looks its module up
    spec.loader.exec_module(module)
    return module


def _public_modules() -> set[str]:
    found = set()
    for package, folder in (("symkin", ROOT / "symkin"), ("symkin.derivations", ROOT / "derivations")):
        for path in folder.rglob("*.py"):
            parts = list(path.relative_to(folder).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            if not any(p.startswith("_") for p in parts):
                found.add(".".join([package, *parts]))
    return found


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    _needs("sphinx")
    _needs("myst_nb")
    out = tmp_path_factory.mktemp("html")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(DOCS), str(out)],
                         capture_output=True, text=True, timeout=900, cwd=ROOT)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    print(f"docs build: {time.perf_counter() - start:.1f} s wall, {cpu:.1f} s CPU")
    return run, out, cpu


def test_the_docs_build_without_a_warning(built):
    run, out, cpu = built
    problems = [line for line in run.stderr.splitlines() if "WARNING" in line or "ERROR" in line]
    assert run.returncode == 0 and not problems, "sphinx -W failed:\n" + "\n".join(problems or run.stderr.splitlines()[-30:])
    assert (out / "index.html").is_file()
    # measured at about 25-30 s of CPU on the development machine (the gallery drawn once more
    # adds about 11 s); the bound leaves room for a slower machine, not for a build twice as heavy
    assert cpu < 90, f"the docs build took {cpu:.0f} s of CPU"


def test_every_public_module_is_in_the_api_reference():
    documented = set()
    for page in (DOCS / "api").glob("*.rst"):
        documented |= set(re.findall(r"^\.\. automodule:: (\S+)", page.read_text(), flags=re.M))
    assert _public_modules() - documented == set(), "add these modules to a page of docs/api/"
    assert documented - _public_modules() == set(), "docs/api/ names modules that do not exist"


def test_every_notebook_is_a_page():
    index = (DOCS / "index.md").read_text()
    for nb in (ROOT / "notebooks").glob("*.ipynb"):
        assert f"notebooks/{nb.stem}\n" in index, f"add notebooks/{nb.stem} to a toctree of docs/index.md"


def test_the_gallery_shows_every_figure_type():
    gallery = _gallery()
    shown = {f for entry in gallery.GALLERY for f in entry.functions}
    page = (DOCS / "gallery.md").read_text()
    for module in ("figures", "animation", "split"):
        path = ROOT / "symkin" / "viz" / f"{module}.py"
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_") and (
                    node.name.endswith("_figure") or node.name.startswith("draw_") or node.name == "animate"):
                name = f"symkin.viz.{module}.{node.name}"
                assert name in shown, f"{name} draws a figure: add it to GALLERY in docs/gallery.py"
                assert node.name in page, f"{name} draws a figure: show it on docs/gallery.md"
    for entry in gallery.GALLERY:
        assert f"gallery/{entry.name}." in page, f"docs/gallery.md does not show gallery/{entry.name}"


def test_the_built_pages_hold_the_gallery_the_api_and_the_stored_notebooks(built):
    run, out, _ = built
    assert run.returncode == 0
    images = {p.name for p in (out / "_images").iterdir()}
    for entry in _gallery().GALLERY:
        assert any(name.startswith(entry.name) for name in images), f"{entry.name} is not in the built gallery"
    engine = (out / "api" / "engine.html").read_text()
    assert 'id="symkin.model.Mechanism.ratio"' in engine and 'id="symkin.kinematics.solve_speeds"' in engine
    assert 'id="symkin.units.quantity"' in (out / "api" / "printing.html").read_text()
    tutorial = (out / "notebooks" / "tutorial.html").read_text()
    assert "<img" in tutorial  # a stored figure output, shown without executing the notebook
