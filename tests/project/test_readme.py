"""README: its Python examples run and print what they say; its commands exist; the two
fresh-machine commands that .ci/run reads are there.

A line of an example whose comment holds ``-> OUTPUT`` states what it prints: OUTPUT is
matched as a doctest with ``...`` for any text (``< X``: a number below X), for Python
statements and for command lines alike.
"""

import ast
import contextlib
import doctest
import io
import re
import shlex
import warnings
from pathlib import Path

import pytest

from symkin.cli import build_parser, main

README = (Path(__file__).resolve().parents[2] / "README.md").read_text()
BLOCKS = re.findall(r"```python\n(.*?)```", README, re.S)
ARROW = re.compile(r"#[^#]*?->\s?(.*)$")


def matches(expected: str, printed: str) -> bool:
    """Does ``printed`` show what ``-> expected`` says?"""
    printed = printed.strip()
    if expected.startswith("< "):
        return float(printed) < float(expected[2:])
    checker = doctest.OutputChecker()
    return checker.check_output(expected.strip() + "\n", printed + "\n", doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)


def stated_outputs(code: str) -> list[tuple[int, str, str]]:
    """(line, expected, printed) for every statement of ``code`` whose line states its output."""
    lines = code.splitlines()
    scope: dict = {}
    found = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for stmt in ast.parse(code).body:
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                exec(compile(ast.Module([stmt], []), "README.md", "exec"), scope)
            arrow = ARROW.search(lines[stmt.lineno - 1]) if stmt.lineno == stmt.end_lineno else None
            if arrow:
                found.append((stmt.lineno, arrow.group(1), out.getvalue()))
    return found


def test_the_arrow_check_can_fail():
    assert matches("(18, 80, 20, 108) (28.22..., 8.49...)", "(18, 80, 20, 108) (28.2212796, 8.49797)")
    assert not matches("(18, 80, 20, 108) (28.22..., 8.49...)", "(18, 80, 20, 107) (28.2212796, 8.49797)")
    assert matches("< 1e-15", "1.98e-16") and not matches("< 1e-15", "2e-15")
    assert stated_outputs("print(1 + 1)  # two -> 2\nx = 3\nprint(x)  # -> 4") == [(1, "2", "2\n"), (3, "4", "3\n")]


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_every_stated_output_of_a_python_block_is_printed(index):
    stated = stated_outputs(BLOCKS[index])
    wrong = [f"line {n}: says -> {e!r}, printed {p.strip()!r}" for n, e, p in stated if not matches(e, p)]
    assert not wrong, "\n".join(wrong)


def test_the_examples_state_their_key_results():
    stated = [e for b in BLOCKS for _, e, _ in stated_outputs(b)]
    for result in ("10000", "(6000/1331, 11, 11, 11) ('free', 'upper', 'upper', 'upper')", "22 9/4 11",
                   "(18, 80, 20, 108) (28.22..., 8.49...)", "< 1e-15", "... 10000.0"):
        assert result in stated, result


def command_lines() -> list[str]:
    lines, fence = [], None
    for line in README.splitlines():
        if line.startswith("```"):
            fence = None if fence is not None else line[3:].strip()
        elif fence == "" and line.startswith("symkin "):
            lines.append(line)
    return lines


def test_command_lines_print_what_their_comments_state(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    stated = [(line.split("#")[0].strip(), ARROW.search(line).group(1)) for line in command_lines() if ARROW.search(line)]
    assert len(stated) >= 3
    for command, expected in stated:
        argv = shlex.split(re.sub(r"\[[^\]]*\]", "", command))[1:]
        assert main(argv) == 0, command
        printed = capsys.readouterr().out
        assert matches(expected, printed), f"{command}: says -> {expected!r}, printed {printed!r}"


def run_block(code: str) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        exec(compile(code, "README.md", "exec"), {})
    return out.getvalue()


def test_ten_line_example_prints_what_its_comments_say():
    block = re.search(r"## Ten lines\n\n```python\n(.*?)```", README, re.S).group(1)
    assert len(block.strip().splitlines()) <= 11
    assert [e for _, e, _ in stated_outputs(block)] == [r"i_{1H}^{(4)} = 1 - \frac{z_{2} z_{4}}{z_{1} z_{3}}", "10000"]
    assert all(matches(e, p) for _, e, p in stated_outputs(block))


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_every_python_block_runs(index):
    assert run_block(BLOCKS[index]) is not None


def test_latex_block_breaks_the_long_law():
    block = next(b for b in BLOCKS if "width=60" in b)
    printed = run_block(block)
    assert r"\tag{23a.2}" in printed and r"\Omega_c = \dfrac" in printed and r"\begin{aligned}" in printed


def test_every_command_line_example_parses():
    parser = build_parser()
    lines = [line.split("#")[0].strip() for line in command_lines()]
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
