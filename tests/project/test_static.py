"""Static checks run with the tests, so CI runs them: ruff (lint) and mypy (types).

The rule sets and their reasons are in pyproject.toml ([tool.ruff], [tool.mypy]).  Both
tools are in the test extra; without them (a bare environment) the checks are skipped,
except in CI (the environment variable CI set), where a missing tool is a failure.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _tool(module: str) -> list[str]:
    try:
        __import__(module)
    except ImportError:
        if os.environ.get("CI"):
            pytest.fail(f"{module} is not installed: pip install -e '.[test]'")
        pytest.skip(f"{module} is not installed (pip install -e '.[test]')")
    return [sys.executable, "-m", module]


def test_ruff_finds_nothing():
    exe = shutil.which("ruff", path=str(Path(sys.executable).parent)) or shutil.which("ruff")
    command = [exe] if exe else _tool("ruff")
    proc = subprocess.run([*command, "check", "--no-cache", "."], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_mypy_finds_nothing():
    command = _tool("mypy")
    proc = subprocess.run([*command, "--no-incremental"], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_mypy_checks_the_readme_examples_and_the_engine_s_results_are_typed(tmp_path):
    """The README's Python examples type-check as a user's code would, and what a user gets from
    ``ratio``, ``speeds``, ``motion`` and ``particle`` has a type mypy knows (not Any)."""
    import re
    import textwrap

    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    assert blocks
    code = "".join(f"def example_{i}() -> None:\n{textwrap.indent(b, '    ')}    pass\n\n\n" for i, b in enumerate(blocks))
    code += textwrap.dedent('''
        def results() -> None:
            from symkin import schemes

            aa = schemes.two_row("AA", teeth=(54, 45, 44, 55))
            reveal_type(aa.ratio("H", "1", fixed="4"))
            reveal_type(aa.speeds({"1": 1, "4": 0}))
            reveal_type(aa.motion({"1": 1, "4": 0}))
            reveal_type(aa.motion({"1": 1, "4": 0}).particle("23", (1, 0)))
        ''')
    (tmp_path / "readme_examples.py").write_text(code)
    proc = subprocess.run([*_tool("mypy"), "--no-incremental", "--cache-dir", str(tmp_path / "cache"),
                           "--config-file", str(ROOT / "pyproject.toml"), str(tmp_path / "readme_examples.py")],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    revealed = re.findall(r'Revealed type is "([^"]+)"', proc.stdout)
    assert revealed == ["symkin.laws.Law", "symkin.kinematics.Speeds", "symkin.particles.Motion",
                        "symkin.particles.Particle | symkin.particles.SpaceParticle"], proc.stdout
    assert "error" not in proc.stdout, proc.stdout
