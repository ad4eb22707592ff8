"""A table-driven harness that feeds hostile values to every ``symkin`` command.

For each command, :data:`COMMANDS` holds one valid argument list.  :func:`cases` takes
each value in it (every positional argument and every option's value) and puts each
of :data:`HOSTILE` in its place.  :func:`run` runs one argument list in this process
(``symkin.cli.main``), under a hard time limit, in a scratch folder, and
:func:`verdict` says what is wrong with the outcome:

- the exit status is 0 (the value was valid) or 2 (bad input); 3 is an internal error,
  a bug; 1 only where the command means "a result differs";
- a failure prints exactly one line on stderr, naming the command, without "Traceback";
- a success with ``--json`` prints strict JSON (no NaN or Infinity) with a ``"warnings"`` list;
  a failure with ``--json`` prints ``{"error": ..., "exit": status}`` on stdout;
- no injected code ran: the marker file the injection strings try to create is absent;
- the run ends within :data:`LIMIT` seconds of CPU time (the process's own: a machine shared
  with other jobs slows the wall clock, not the work a command does), or within a hostile
  shape's own bound (:data:`SHAPES`).

``python tests/support/hostile.py`` runs the whole table and prints the counts per command and
every problem found (the test module runs the same table).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import signal
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

#: The file the injection strings try to create; it must never appear.
MARKER = "PWNED"

#: Hostile values put in place of every argument value.
HOSTILE: tuple[str, ...] = (
    "",
    "   ",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e400",
    "1e-400",
    "1e100",
    "10**100",
    "10**10**10",
    "9" * 401,
    "-5",
    "0",
    "-0",
    "1/0",
    "١٢",  # Arabic-Indic digits
    "１２",  # fullwidth digits
    "ＮａＮ",
    "1_000",
    "0x10",
    "(",
    "1,2,3,4,5,6,7,8,9",
    "None",
    "True",
    "x",
    "\x00",
    "\u202e12",  # right-to-left override
    "💥",
    f"__import__('os').system('touch {MARKER}')",
    "().__class__.__bases__[0].__subclasses__()",
    "lambda: 0",
    f"open('{MARKER}','w')",
    "a" * 5000,
    "(" * 200 + "1" + ")" * 200,
    "E**1000",
    "exp(700)",
    "2**-999",
)

#: Hostile shapes of expressions (not only values), each with the seconds its run may take:
#: nested functions whose value needs millions of digits, towers of powers, long flat sums,
#: zero in disguise, Unicode look-alikes of names and operators, and numbers at the edge of
#: the accepted sizes.  A refusal must come within the bound, as one line and exit 2.
SHAPES: dict[str, float] = {
    "sin(exp(exp(exp(3))))": 8.0,  # the sine of a number of 230 million digits
    "cos(exp(exp(exp(2.9))))": 8.0,
    "tan(exp(exp(9)))": 8.0,
    "sin(" * 30 + "1" + ")" * 30: 8.0,  # nested 30 deep: accepted, and quick
    "exp(" * 61 + "1" + ")" * 61: 8.0,  # nested past the limit
    "((sqrt(2)**999)**999)**999": 8.0,  # a tower of an irrational base: 10^150000
    "(pi**999)**999": 8.0,
    "E**E**E**E": 8.0,
    "2**2**2**2**2": 8.0,
    "10**300*10": 8.0,
    "exp(-800)": 8.0,  # below 1e-300
    "+".join(["1"] * 999): 8.0,  # a flat sum of 999 terms (999): one level, not 999
    "+".join(["sin(1)"] * 300): 8.0,
    "sin(1)**2+cos(1)**2-1": 8.0,  # zero in disguise
    "1/(sin(1)**2+cos(1)**2-1)": 8.0,
    "sqrt(-1)": 8.0,
    "acos(2)": 8.0,
    "log(0)": 8.0,
    "tan(pi/2)": 8.0,
    "atan2(0,0)": 8.0,
    "\u0455in(1)": 8.0,  # Cyrillic s
    "2\u00b7pi": 8.0,  # middle dot
    "\u03c0": 8.0,  # the letter pi
    "\u22121": 8.0,  # the minus sign U+2212
    "sin\uff081\uff09": 8.0,  # fullwidth parentheses
    "1e300": 8.0,
    "-1e300": 8.0,
    "1e-300": 8.0,
    "exp(690)": 8.0,
    "exp(-690)": 8.0,
    # exact numbers near 1 raised to a power: within the size bounds, but 300,000 digits (issue 35)
    "(1-10**-300)**1000": 8.0,
    "(1+1e-300)**999": 8.0,
    "(999999/1000000)**1000": 8.0,
    # exact constants beyond int64 in the numeric code: NumPy's sqrt met a Python integer (exit 3), and
    # a phase reduction of a 900-digit rational frequency was refused as a number of 10^900 (issue 35)
    "sqrt(10**40+1)": 8.0,
    "(1-10**-300)**(1/2)": 8.0,
    "(1-10**-300)**3": 8.0,
    "(2+cos(10**30))*sqrt(10**30+7)": 8.0,
    # laws of t: a kink (no acceleration), and nesting whose acceleration explodes (issue 35)
    "Abs(t)": 8.0,
    "t*Abs(sin(t))": 8.0,
    "sin(" * 55 + "t" + ")" * 55: 8.0,
    "exp(t*" * 20 + "t" + ")" * 20: 8.0,
    # constructs whose message recursed (ast.unparse), and a byte that is not UTF-8 (issue 35)
    "~" * 400 + "1": 8.0,
    "x" + ".a" * 400: 8.0,
    b"1\xff".decode("utf-8", "surrogateescape"): 8.0,
}
HOSTILE = HOSTILE + tuple(SHAPES)

#: Seconds one run may take before it counts as a hang (a value of SHAPES: its own bound).
LIMIT = 20.0
#: A command that waits (sleeps, blocks) without using CPU is stopped after this many times LIMIT of wall clock.
WALL_FACTOR = 5


def many_planets(n: int) -> str:
    """A train file of ``n`` planets, each a link of its own on one carrier (sun 30, ring 90, state a: ring held)."""
    lines = ['meshes = [' + ", ".join(f'["s", "p{i}"], ["p{i}", "r"]' for i in range(n)) + ']',
             '[links.S]', 'gears = { s = 30 }', '[links.C]', '[links.R]', 'gears = { r = { teeth = 90, internal = true } }']
    for i in range(n):
        lines += [f'[links.P{i}]', 'carrier = "C"', f'gears = {{ p{i} = 30 }}']
    return "\n".join(lines + ['[states.a]', 'input = "S"', 'output = "C"', 'brakes = ["R"]']) + "\n"


def seconds_for(value: str) -> float:
    """The wall-clock bound of a run with ``value`` in it."""
    return SHAPES.get(value, LIMIT)


@dataclass(frozen=True)
class Command:
    """One command's valid argument list.

    ``skip`` holds indices of values not to replace; ``slow`` (index, value) pairs that are
    valid and only slow (a thousand animation frames), left out to keep the suite fast.
    """

    argv: tuple[str, ...]
    skip: frozenset[int] = field(default_factory=frozenset)
    ok_codes: frozenset[int] = frozenset({0, 2})
    slow: frozenset[tuple[int, str]] = field(default_factory=frozenset)

    @property
    def name(self) -> str:
        return self.argv[0]

    def positions(self) -> list[int]:
        """Indices of the values to replace: positionals and option values, not flags."""
        out = []
        for i, token in enumerate(self.argv[1:], 1):
            if token.startswith("-") and not _is_number(token):
                continue
            if i not in self.skip:
                out.append(i)
        return out


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


_AI1 = ("AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1")

#: One valid, quick argument list per command (every command of ``symkin --help``).
COMMANDS: dict[str, Command] = {
    "reproduce": Command(("reproduce", "alyushin2009", "--out", "report", "--quiet", "--no-pdf", "--json"),
                         # a valid paper name or folder runs the whole reproduction: the folder is
                         # fuzzed separately (tests/papers/test_reproduce_folder.py) with paths, not numbers
                         skip=frozenset({3}), ok_codes=frozenset({2})),
    "ratio": Command(("ratio", "AA", "--teeth", "100,100,101,99", "--driver", "H", "--driven", "1", "--fixed", "4", "--json")),
    "speeds": Command(("speeds", "AA", "--teeth", "54,45,44,55", "--omega", "1=100", "--omega", "4=0", "--json")),
    "ratio-train": Command(("ratio", "--train", "ravigneaux", "--driver", "S1", "--driven", "R", "--fixed", "C", "--json")),
    "speeds-train": Command(("speeds", "--train", "simple", "--omega", "S=1", "--omega", "R=0", "--json")),
    "efficiency": Command(("efficiency", "II", "--teeth", "200,99,100,201", "--driver", "H", "--driven", "1", "--fixed", "4",
                           "--mesh-efficiency", "0.98", "--json")),
    "efficiency-train": Command(("efficiency", "--train", "ravigneaux", "--state", "second", "--mesh-efficiency", "p2-r=0.99",
                                 "--json")),
    "states": Command(("states", "--train", "simple", "--state", "low", "--json")),
    "trains": Command(("trains", "--json")),
    "dynamics": Command(("dynamics", "--train", "simple", "--state", "low", "--coordinates", "S", "--torque", "S=2",
                         "--json")),
    "modes": Command(("modes", "--train", "simple", "--state", "low", "--value", "J_S=0.01", "--json")),
    "geometry": Command(("geometry", "--train", "simple", "--min-contact-ratio", "1.2", "--out", "g.svg", "--json")),
    "diagram": Command(("diagram", "--train", "simple", "--state", "low", "--length-unit", "mm", "--out", "d.svg", "--json")),
    "diagram-lever": Command(("diagram", "--train", "simpson", "--state", "second", "--lever", "--out", "l.png", "--json")),
    "trajectory": Command(("trajectory", *_AI1, "--point", "2:10,0", "--module", "1", "--turns", "1", "--out", "t.png", "--json")),
    "trajectory-space": Command(("trajectory", *_AI1, "--point", "2:10,0,1", "--base-z", "5*t", "--base-pitch", "t/10",
                                 "--turns", "1", "--out", "t.png", "--json")),
    "trajectory-train": Command(("trajectory", "--train", "simple", "--omega", "S=1", "--omega", "R=0", "--turns", "1",
                                 "--out", "t.png", "--json")),
    "curves": Command(("curves", *_AI1, "--point", "2:10,0", "--module", "1", "--t-end", "2", "--out", "c.png", "--json")),
    "animate": Command(("animate", *_AI1, "--point", "2:10,0", "--module", "1", "--turns", "1", "--frames", "2", "--fps", "5",
                        "--dpi", "20", "--out", "a.gif", "--json"), slow=frozenset({(15, "1_000")})),
    "cardan": Command(("cardan", "--length", "0.02", "--speed", "0.8*pi", "--guide-angle", "0", "--carrier-angle", "0",
                       "--teeth", "20,40", "--pin-radius", "0.02", "--pin-angle", "0", "--t-start", "0", "--t-end", "1",
                       "--samples", "3", "--json")),
    "cardan-elliptical": Command(("cardan", "--length", "0.02", "--speed", "1", "-e", "0.4", "--order", "1", "--samples", "3", "--json")),
    # the former name of --speed, kept as a deprecated alias
    "cardan-omega": Command(("cardan", "--length", "0.02", "--omega", "1", "--samples", "3", "--json")),
    "cardan-law": Command(("cardan", "--length", "1", "--angle-law", "t + sin(t)", "--times", "0,0.5,1", "--json")),
    "stages": Command(("stages", "--ring", "180", "--satellites", "3", "--zmin", "18", "--zmax", "180", "--ha", "1", "--json")),
    "split": Command(("split", "--total", "5000", "--stages", "3", "--umin", "2", "--umax", "12", "--model", "1 + u/10",
                      "--tolerance", "0.01", "--top", "3", "--json")),
    "split-ring": Command(("split", "--total", "100", "--stages", "2", "--ring", "60", "--satellites", "3", "--zmin", "12",
                           "--model", "1 + u/10", "--top", "2", "--plot", "s.png", "--quiet", "--json")),
    "split-backlash": Command(("split", "--total", "100", "--stages", "2", "--ring", "60", "--backlash-line", "0.01,0.001",
                               "--module", "1", "--top", "2", "--json")),
    "helical": Command(("helical", "AI", "--ratio", "25", "--tolerance", "0.01", "-k", "3", "--mn12", "2", "--mn34", "2",
                        "--beta-min", "8", "--beta-max", "30", "--zmin", "17", "--zmax", "60", "--alpha-n", "20",
                        "--addendum", "1", "--min-ring-difference", "8", "--top", "3", "--quiet", "--json"),
                        ok_codes=frozenset({0, 1, 2})),
    "synthesize": Command(("synthesize", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R", "--ratio",
                           "4", "--tolerance", "0.01", "--planets", "3", "--zmin", "18", "--zmax", "60", "--pressure-angle",
                           "20", "--addendum", "1", "--clearance", "0", "--shift", "0", "--ring-difference", "8", "--top",
                           "3", "--time-limit", "15", "--quiet", "--json"), ok_codes=frozenset({0, 1, 2})),
    "synthesize-state": Command(("synthesize", "--train", "wolfrom", "--state", "drive", "--ratio-range", "70,80",
                                 "--planets", "3", "--zmax", "50", "--top", "2", "--time-limit", "10", "--quiet",
                                 "--json"),
                                ok_codes=frozenset({0, 1, 2})),
}


def cases(name: str) -> Iterator[tuple[int, str, tuple[str, ...]]]:
    """(index, value, argv): command ``name`` with the value at index replaced by a hostile one."""
    cmd = COMMANDS[name]
    for i in cmd.positions():
        for value in HOSTILE:
            if (i, value) in cmd.slow:
                continue
            argv = list(cmd.argv)
            argv[i] = value
            yield i, value, tuple(argv)


class Hang(BaseException):
    """Raised by the alarm: a run took longer than its limit (not an Exception, so main() lets it through)."""


@dataclass
class Outcome:
    argv: tuple[str, ...]
    code: int | None
    out: str
    err: str
    seconds: float
    hung: bool = False
    limit: float = LIMIT


@contextlib.contextmanager
def _alarm(seconds: float) -> Iterator[None]:
    def handler(signum, frame):
        raise Hang(f"longer than {seconds} s")

    # ITIMER_PROF counts this process's CPU time (all its threads), not the wall clock; a wall-clock
    # alarm at WALL_FACTOR times the limit still stops a command that waits without working.  An
    # outer wall-clock timer (pytest-timeout's per-test limit) is put back with what is left of it.
    # symkin's own time budgets (ITIMER_PROF too) keep this timer as their outer one and re-arm it.
    outer_left, outer_interval = signal.getitimer(signal.ITIMER_REAL)
    start = time.monotonic()
    previous = {sig: signal.signal(sig, handler) for sig in (signal.SIGPROF, signal.SIGALRM)}
    signal.setitimer(signal.ITIMER_PROF, seconds)
    signal.setitimer(signal.ITIMER_REAL, seconds * WALL_FACTOR)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.setitimer(signal.ITIMER_REAL, 0)
        for sig, old in previous.items():
            signal.signal(sig, old)
        if outer_left > 0:
            signal.setitimer(signal.ITIMER_REAL, max(outer_left - (time.monotonic() - start), 1e-6), outer_interval)


def run(argv: tuple[str, ...], folder: Path, limit: float = LIMIT) -> Outcome:
    """Run ``symkin *argv`` in this process, in ``folder``, with a time limit (seconds)."""
    from symkin.cli import main

    out, err = io.StringIO(), io.StringIO()
    cwd = os.getcwd()
    start = time.process_time()
    code, hung = None, False
    os.chdir(folder)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), _alarm(limit):
            try:
                code = main(list(argv))
            except SystemExit as exc:  # argparse
                code = exc.code if isinstance(exc.code, int) else 2
    except Hang:
        hung = True
    finally:
        os.chdir(cwd)
    return Outcome(argv, code, out.getvalue(), err.getvalue(), time.process_time() - start, hung, limit)


def _no_nan(token: str) -> None:
    raise ValueError(f"JSON holds {token}")


def verdict(outcome: Outcome, folder: Path, ok_codes: frozenset[int] = frozenset({0, 2})) -> str | None:
    """What is wrong with ``outcome``, or None."""
    if outcome.hung or outcome.seconds > outcome.limit:
        return f"did not finish within {outcome.limit:g} s of CPU time"
    if (folder / MARKER).exists():
        return "an injected command ran (the marker file exists)"
    if outcome.code not in ok_codes:
        return f"exit status {outcome.code}: {outcome.err.strip()[:300]}"
    if "Traceback" in outcome.err:
        return "a traceback on stderr"
    if outcome.code != 0:
        lines = outcome.err.strip().splitlines()
        if len(lines) != 1:
            return f"{len(lines)} lines on stderr: {outcome.err[:300]!r}"
        if "error" not in lines[0]:
            return f"the message does not say error: {lines[0][:200]!r}"
        if len(lines[0]) > 2000:
            return f"a {len(lines[0])}-character message"
        if "--json" in outcome.argv and outcome.code in (2, 3):
            try:
                data = json.loads(outcome.out, parse_constant=_no_nan)
            except ValueError as exc:
                return f"exit {outcome.code} with --json but stdout is not strict JSON ({exc})"
            if not isinstance(data, dict) or data.get("exit") != outcome.code or not data.get("error"):
                return f"exit {outcome.code} with --json but stdout is not {{'error': ..., 'exit': {outcome.code}}}"
    elif "--json" in outcome.argv:
        try:
            data = json.loads(outcome.out, parse_constant=_no_nan)
        except ValueError as exc:
            return f"exit 0 but the JSON output is not strict JSON ({exc})"
        if not isinstance(data, dict) or not isinstance(data.get("warnings"), list):
            return "exit 0 but the JSON output has no warnings list"
    return None


def sweep(names: list[str] | None = None, root: Path | None = None, *, echo: bool = False) -> tuple[dict[str, int], list[str]]:
    """Run every case of the named commands; returns inputs tried per command and the problems."""
    import tempfile

    counts: dict[str, int] = {}
    problems: list[str] = []
    with tempfile.TemporaryDirectory(dir=root) as tmp:
        for name in names or list(COMMANDS):
            cmd = COMMANDS[name]
            for n, (i, value, argv) in enumerate(cases(name)):
                folder = Path(tmp) / f"{name}-{n}"
                folder.mkdir()
                outcome = run(argv, folder, seconds_for(value))
                counts[name] = counts.get(name, 0) + 1
                problem = verdict(outcome, folder, cmd.ok_codes)
                if echo and outcome.code == 0 and not problem:
                    print(f"  accepted: {name}: {argv[i - 1] if argv[i - 1].startswith('-') else i} = {value!r:.40}"
                          f" ({outcome.seconds:.1f} s){' note: ' + outcome.err.strip()[:150] if outcome.err.strip() else ''}")
                if problem or outcome.seconds > 5:
                    where = argv[i - 1] if argv[i - 1].startswith("-") else f"argument {i}"
                    line = f"{name}: {where} = {value!r:.60}: {problem or 'slow'} ({outcome.seconds:.1f} s)"
                    if problem:
                        problems.append(line)
                    if echo:
                        print(line, flush=True)
    return counts, problems


if __name__ == "__main__":  # pragma: no cover
    import matplotlib

    matplotlib.use("Agg")
    counts, problems = sweep(sys.argv[1:] or None, echo=True)
    print(json.dumps(counts, indent=1))
    print(f"{sum(counts.values())} runs, {len(problems)} problems")
