"""The wheel carries its licence, types, data and every module; one version everywhere;
README reads right on a package index page (no links relative to the repository)."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import symkin

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> zipfile.ZipFile:
    # built from a copy of the sources, so the build leaves nothing in the checkout
    src = tmp_path_factory.mktemp("src")
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(ROOT / name, src / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc")
    for folder in ("symkin", "derivations"):
        shutil.copytree(ROOT / folder, src / folder, ignore=ignore)
    out = tmp_path_factory.mktemp("dist")
    proc = subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "--no-build-isolation", "-w", str(out),
                           str(src)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    (path,) = out.glob("symkin-*.whl")
    return zipfile.ZipFile(path)


def test_the_wheel_carries_the_licence_with_its_spdx_expression(wheel):
    names = wheel.namelist()
    info = f"symkin-{symkin.__version__}.dist-info"
    assert f"{info}/licenses/LICENSE" in names
    metadata = wheel.read(f"{info}/METADATA").decode()
    assert re.search(r"^License-Expression: MIT$", metadata, re.M)
    assert re.search(rf"^Version: {re.escape(symkin.__version__)}$", metadata, re.M)
    assert "License :: " not in metadata  # PEP 639: the expression, not a classifier
    assert wheel.read(f"{info}/licenses/LICENSE").decode() == (ROOT / "LICENSE").read_text()


def test_the_wheel_carries_every_module_its_types_and_data(wheel):
    names = set(wheel.namelist())
    expected = {p.relative_to(ROOT).as_posix() for p in (ROOT / "symkin").rglob("*.py") if "__pycache__" not in p.parts}
    expected |= {f"symkin/derivations/{p.name}" for p in (ROOT / "derivations").glob("*.py")}
    expected |= {"symkin/py.typed", "symkin/papers/report.schema.json"}
    expected |= {p.relative_to(ROOT).as_posix() for p in (ROOT / "symkin/trains/library").glob("*.toml")}
    expected |= {p.relative_to(ROOT).as_posix() for p in (ROOT / "symkin/cli/schemas").glob("*.schema.json")}
    missing = sorted(expected - names)
    assert not missing, f"not in the wheel (add the package to [tool.setuptools] packages or package-data): {missing}"


def test_one_version_everywhere():
    version = symkin.__version__
    citation = (ROOT / "CITATION.cff").read_text()
    assert re.search(rf'^version: "{re.escape(version)}"$', citation, re.M)
    release = re.match(r"\d+\.\d+\.\d+", version).group()
    assert re.search(rf"^## {re.escape(release)}\b", (ROOT / "CHANGELOG.md").read_text(), re.M)
    assert re.search(rf"^  version = {{{re.escape(release)}}},$", (ROOT / "README.md").read_text(), re.M)  # the BibTeX entry
    project = re.search(r"^\[project\]$(.*?)^\[", (ROOT / "pyproject.toml").read_text(), re.S | re.M).group(1)
    assert 'dynamic = ["version"]' in project and not re.search(r"^version\s*=", project, re.M)  # only in _version.py


def test_readme_links_work_on_a_package_index_page():
    text = (ROOT / "README.md").read_text()
    targets = re.findall(r"\]\(([^)]+)\)", text) + re.findall(r'(?:src|href)="([^"]+)"', text)
    relative = [t for t in targets if not re.match(r"(https?://|mailto:|#)", t)]
    assert not relative, f"README links relative to the repository break on a package index page: {relative}"
