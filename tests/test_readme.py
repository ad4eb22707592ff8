"""README: its Python examples run and print what they say; its commands exist; the two
fresh-machine commands that .ci/run reads are there."""

import contextlib
import io
import re
import shlex
import warnings
from pathlib import Path

import pytest

from symkin.cli import build_parser

README = (Path(__file__).resolve().parent.parent / "README.md").read_text()
BLOCKS = re.findall(r"```python\n(.*?)```", README, re.S)


def run_block(code: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        exec(compile(code, "README.md", "exec"), {})
    return out.getvalue()


def test_ten_line_example_prints_what_its_comments_say():
    block = re.search(r"## Ten lines\n\n```python\n(.*?)```", README, re.S).group(1)
    assert len(block.strip().splitlines()) <= 11
    printed = run_block(block)
    assert r"i_{1H}^{(4)} = 1 - \frac{z_{2} z_{4}}{z_{1} z_{3}}" in printed
    assert "\n10000\n" in printed


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_every_python_block_runs(index):
    assert run_block(BLOCKS[index]) is not None


def test_latex_block_breaks_the_long_law():
    block = next(b for b in BLOCKS if "width=60" in b)
    printed = run_block(block)
    assert r"\tag{23a.2}" in printed and r"\Omega_c = \dfrac" in printed and r"\begin{aligned}" in printed


def test_every_command_line_example_parses():
    parser = build_parser()
    lines, fence = [], None
    for line in README.splitlines():
        if line.startswith("```"):
            fence = None if fence is not None else line[3:].strip()
        elif fence == "" and line.startswith("symkin "):
            lines.append(line.split("#")[0].strip())
    assert len(lines) >= 6
    for line in lines:
        argv = [a for a in shlex.split(re.sub(r"\[[^\]]*\]", "", line))[1:]]
        args = parser.parse_args(argv)  # exits (a test failure) on an unknown command or option
        assert callable(args.run)


def test_fresh_machine_commands_are_marked_for_ci():
    for tag in ("main", "test"):
        assert re.search(rf"<!-- ci:{tag} -->\n```bash\n.+\n```", README), tag
    main = re.search(r"<!-- ci:main -->\n```bash\n(.+)\n```", README).group(1)
    assert main.endswith("symkin reproduce")
