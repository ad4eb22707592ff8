"""Every command of ``symkin --help`` against hostile values (the table in tests/support/hostile.py),
and the installed console script against code injection."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

from symkin.cli import build_parser
from tests.support.hostile import COMMANDS, HOSTILE, MARKER, Outcome, cases, run, seconds_for, verdict


def test_the_table_covers_every_command():
    parser = build_parser()
    choices = parser._subparsers._group_actions[0].choices  # the registered commands
    assert set(choices) == {c.name for c in COMMANDS.values()}


@pytest.mark.parametrize("name", list(COMMANDS))
def test_hostile_values_give_an_answer_or_one_line_and_exit_2(name, tmp_path):
    if not COMMANDS[name].positions():
        pytest.skip(f"{name} takes no values to replace (only flags)")
    problems, tried = [], 0
    for n, (i, value, argv) in enumerate(cases(name)):
        folder = tmp_path / str(n)
        folder.mkdir()
        outcome = run(argv, folder, seconds_for(value))
        tried += 1
        problem = verdict(outcome, folder, COMMANDS[name].ok_codes)
        if problem:
            problems.append(f"{argv[i - 1]} {value!r:.50}: {problem}")
    assert tried >= len(HOSTILE)
    assert not problems, "\n".join(problems)


def test_the_verdict_catches_what_it_should(tmp_path):
    ok = Outcome(("ratio", "--json"), 0, '{"a": 1, "warnings": []}', "", 0.1)
    assert verdict(ok, tmp_path) is None
    assert "exit status 3" in verdict(Outcome(("ratio",), 3, "", "symkin ratio: internal error: x\n", 0.1), tmp_path)
    assert "2 lines" in verdict(Outcome(("ratio",), 2, "", "warning\nsymkin ratio: error: x\n", 0.1), tmp_path)
    assert "strict JSON" in verdict(Outcome(("ratio", "--json"), 0, '{"a": NaN}', "", 0.1), tmp_path)
    assert "warnings list" in verdict(Outcome(("ratio", "--json"), 0, '{"a": 1}', "", 0.1), tmp_path)
    assert "stdout is not" in verdict(Outcome(("ratio", "--json"), 2, "", "symkin ratio: error: x\n", 0.1), tmp_path)
    assert "'error'" in verdict(Outcome(("ratio", "--json"), 2, '{"exit": 2}', "symkin ratio: error: x\n", 0.1), tmp_path)
    assert "did not finish" in verdict(Outcome(("ratio",), None, "", "", 30, hung=True), tmp_path)
    (tmp_path / MARKER).touch()
    assert "injected" in verdict(ok, tmp_path)


def test_a_hang_is_stopped_by_the_time_limit(tmp_path, monkeypatch):
    from symkin.cli import gears

    def forever(args):
        while True:
            sum(range(1000))  # busy: the limit counts CPU time

    monkeypatch.setattr(gears, "run_ratio", forever)
    outcome = run(COMMANDS["ratio"].argv, tmp_path, limit=0.3)
    assert outcome.hung and 0.25 <= outcome.seconds < 5  # CPU time, counted in ticks of a few ms


# ---- huge tooth numbers: exact, quick, and the same as the closed form typed here
def test_a_googol_of_teeth_gives_the_exact_ratio_quickly(tmp_path):
    z = [10**100, 10**100 + 1, 10**100 + 3, 10**100 - 2]  # AA: z1 + z2 = z3 + z4, coaxial
    argv = ("ratio", "AA", "--teeth", ",".join(map(str, z)), "--driver", "1", "--driven", "H", "--fixed", "4", "--json")
    outcome = run(argv, tmp_path, limit=10)
    assert outcome.code == 0 and outcome.seconds < 5
    data = json.loads(outcome.out)
    expected = 1 - sp.Rational(z[1] * z[3], z[0] * z[2])  # i_1H^(4) of the AA scheme, 2009 paper eq. (22a)
    assert sp.Rational(data["ratio"]["exact"]) == expected
    assert data["ratio"]["float"] == pytest.approx(float(expected), rel=1e-12)


def test_teeth_beyond_the_accepted_size_are_refused_with_the_limit(tmp_path):
    argv = ("ratio", "AA", "--teeth", "1e301,1,1,1", "--driver", "1", "--driven", "H", "--fixed", "4")
    outcome = run(argv, tmp_path)
    assert outcome.code == 2 and "1e300" in outcome.err


# ---- the installed console script, as a process
SCRIPT = shutil.which("symkin", path=str(Path(sys.executable).parent)) or shutil.which("symkin")
INJECTIONS = [
    ["speeds", "AA", "--teeth", "54,45,44,55", "--omega", f"1=__import__('os').system('touch {MARKER}')", "--omega", "4=0"],
    ["cardan", "--length", "1", "--angle-law", f"t + __import__('os').system('touch {MARKER}')", "--t-end", "1"],
    ["split", "--total", "100", "--stages", "2", "--umin", "2", "--umax", "12",
     "--model", "[c for c in ().__class__.__base__.__subclasses__()]"],
    ["trajectory", "AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1",
     "--point", f"2:open('{MARKER}').read(),0", "--out", "t.png"],
]


@pytest.mark.skipif(SCRIPT is None, reason="the symkin console script is not installed")
@pytest.mark.parametrize("argv", INJECTIONS, ids=lambda a: a[0])
def test_the_console_script_refuses_injected_code(argv, tmp_path):
    proc = subprocess.run([SCRIPT, *argv], capture_output=True, text=True, timeout=120, cwd=tmp_path,
                          env={**os.environ, "SYMKIN_DEBUG": ""})
    assert proc.returncode == 2, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "not allowed" in proc.stderr
    assert "Traceback" not in proc.stderr and not proc.stdout
    assert not (tmp_path / MARKER).exists() and not (tmp_path / "t.png").exists()
