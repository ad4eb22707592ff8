"""The ``symkin`` command line.

Each command lives in its own module under :mod:`symkin.cli` with a ``register``
function; :data:`COMMANDS` lists them.  Every command takes ``--json``; bad input gives
a one-line message on stderr and exit status 2, never a traceback (with ``--json``, also
``{"error": message, "exit": 2}`` on stdout).  The conventions the commands share are
in :mod:`symkin.cli.common`.

Exit status: 0 success; 1 a reproduction found a result that differs; 2 bad input;
3 an internal error (set SYMKIN_DEBUG=1 for the traceback).
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import signal
import sys
import warnings
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any, NoReturn

from symkin.cli.common import Output
from symkin.errors import SymkinError, SymkinWarning

__all__ = ["main", "console_main", "COMMANDS", "ArgumentParser", "output_schema", "JSON_SCHEMA_VERSION"]

#: Modules of symkin.cli that define commands, in the order --help lists them.
COMMANDS = ("reproduce", "gears", "trains", "diagram", "efficiency", "dynamics", "plots", "cardan", "multistage", "helical",
            "synthesis", "geometry")

EXIT_OK, EXIT_DIFFERS, EXIT_USAGE, EXIT_INTERNAL = 0, 1, 2, 3


class UsageExit(SystemExit):
    """A command line argparse refused; ``message`` is the one line printed on stderr."""

    def __init__(self, message: str):
        super().__init__(EXIT_USAGE)
        self.message = message


class ArgumentParser(argparse.ArgumentParser):
    """argparse with a one-line error message."""

    def error(self, message: str) -> NoReturn:
        """Print ``message`` as one line on stderr, pointing at ``--help``, and exit with status 2 (:class:`UsageExit`)."""
        message = f"{message} (see {self.prog} --help)"
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        raise UsageExit(message)


def build_parser() -> ArgumentParser:
    """The parser of every command.

    >>> build_parser().parse_args(["ratio", "AA", "--teeth", "1,2,3,4", "--driver", "H", "--driven", "1", "--fixed", "4"]).scheme
    'AA'
    """
    from symkin._version import __version__

    parser = ArgumentParser(
        prog="symkin",
        description="Symbolic kinematics of planetary gear mechanisms: derive, compare with papers, evaluate.",
    )
    parser.add_argument("--version", action="version", version=f"symkin {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=ArgumentParser)
    sub.required = True
    for name in COMMANDS:
        importlib.import_module(f"{__name__}.{name}").register(sub)
    return parser


def one_line(message: object, word: int = 80) -> str:
    r"""``message`` on one line, each overlong word (an echoed value) shortened.

    >>> one_line("no link 'aaaaaaaaaaaa'\n  choose 1", word=8)
    "no link 'aaa...(14 characters) choose 1"
    """
    words = str(message).split()
    return " ".join(w if len(w) <= word else f"{w[: word * 3 // 4]}...({len(w)} characters)" for w in words)


def _negative_values_attached(argv: list[str], parser: ArgumentParser) -> list[str]:
    """``--carrier-angle -pi/6`` read as ``--carrier-angle=-pi/6`` (and ``--ratio-range -120,-30``
    as ``--ratio-range=-120,-30``).

    argparse takes a token that begins with ``-`` for an option unless it is one plain negative
    number, and then refuses it ("expected one argument").  After an option that takes a value, a
    token that begins with one minus and is not an option of the command is that value.

    >>> _negative_values_attached(["cardan", "--carrier-angle", "-pi/6", "-e", "0.3", "--json"], build_parser())
    ['cardan', '--carrier-angle=-pi/6', '-e', '0.3', '--json']
    """
    command = next((a for a in argv if not a.startswith("-")), "")
    actions = list(parser._actions)
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) and command in action.choices:
            actions += action.choices[command]._actions
    known = {option for action in actions for option in action.option_strings}
    taking = {option for action in actions if action.nargs != 0 for option in action.option_strings}
    out: list[str] = []
    for token in argv:
        if out and out[-1] in taking and token[:1] == "-" and token[1:2] not in ("", "-") and token not in known \
                and token[:2] not in known:
            out[-1] = f"{out[-1]}={token}"
        else:
            out.append(token)
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status.

    The command's result is printed after it has run: its text, with every warning
    raised on the way (a :class:`~symkin.errors.SymkinWarning`, a NumPy overflow) as a
    one-line note on stderr, or with ``--json`` one JSON object whose ``"warnings"`` list
    holds the same notes.  A failure prints one line on stderr (and with ``--json``
    ``{"error": ..., "exit": ...}`` on stdout); its warnings are dropped, the message
    says what went wrong.  A command line argparse refuses raises :class:`UsageExit`
    (a ``SystemExit`` with status 2) after the same output.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    wants_json = "--json" in argv
    parser = build_parser()
    argv = _negative_values_attached(argv, parser)
    try:
        args = parser.parse_args(argv)
    except UsageExit as exc:
        if wants_json:
            _print_json({"error": exc.message, "exit": EXIT_USAGE, "warnings": []})
        raise
    prog = f"symkin {args.command}"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        output = _run(args, prog)
    if isinstance(output, int):  # a failure, already reported
        return output
    from symkin.errors import NullFloatWarning

    json_out = getattr(args, "json", False)  # (a null JSON float is news only where JSON is written)
    notes = list(dict.fromkeys(_note(w) for w in caught if json_out or not issubclass(w.category, NullFloatWarning)))
    try:
        if json_out:
            _print_json({**output.data, "warnings": list(dict.fromkeys([*output.data.get("warnings", []), *notes]))})
        else:
            sys.stdout.write(output.text if output.text.endswith("\n") else output.text + "\n")
        sys.stdout.flush()
    except BrokenPipeError:  # the reader stopped (| head): nothing more to say
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return output.code
    if not json_out:
        for note in notes:
            print(f"{prog}: note: {note}", file=sys.stderr)
    return output.code


def console_main() -> NoReturn:
    """The ``symkin`` program (and ``python -m symkin``): :func:`main` with the command line;
    the process ends with its status."""
    sys.exit(main())


def _note(w: warnings.WarningMessage) -> str:
    """A warning as one line: symkin's own by their message, others with their category."""
    if issubclass(w.category, SymkinWarning):
        return one_line(w.message)
    return one_line(f"{w.category.__name__}: {w.message}")


#: The version of the layouts of every ``--json`` output (``symkin/cli/schemas/*.schema.json``) but
#: ``reproduce``'s, which prints the report with its own version (:data:`symkin.papers.reproduce.SCHEMA_VERSION`).
JSON_SCHEMA_VERSION = "1.0"


def output_schema(command: str) -> dict:
    """The JSON Schema of ``symkin COMMAND --json``'s output (``"error"``: of any failure).

    ``reproduce`` prints the report, whose schema is
    :func:`symkin.papers.reproduce.report_schema`.

    >>> schema = output_schema("ratio")
    >>> schema["properties"]["schema_version"]["const"], "ratio" in schema["required"]
    ('1.0', True)
    """
    from importlib.resources import files

    if command == "reproduce":
        from symkin.papers.reproduce import report_schema

        return report_schema()
    path = files("symkin.cli").joinpath("schemas").joinpath(f"{command}.schema.json")
    if not path.is_file():
        known = sorted(p.name.removesuffix(".schema.json") for p in files("symkin.cli").joinpath("schemas").iterdir())
        raise ValueError(f"no output schema for {command!r}; known: {', '.join([*known, 'reproduce'])}")
    return json.loads(path.read_text())


def _print_json(data: dict) -> None:
    data = {"schema_version": JSON_SCHEMA_VERSION, **data}  # the report carries its own (report.schema.json's)
    json.dump(data, sys.stdout, indent=2, ensure_ascii=False, allow_nan=False)
    sys.stdout.write("\n")


@contextmanager
def _terminate_as_interrupt() -> Iterator[None]:
    """SIGTERM unwinds like Ctrl-C: a half-written output (a report folder, a figure, an animation) is
    removed and what was there before is kept."""

    def handler(signum: int, frame: Any) -> None:
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGTERM, handler)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _run(args: argparse.Namespace, prog: str) -> Output | int:
    """The command's output, or the exit status of its failure (reported here)."""
    from symkin._io.atomic import PLACED, placed

    before = len(PLACED)
    try:
        with _terminate_as_interrupt():
            return args.run(args)
    except SymkinError as err:
        return _fail(args, prog, "error", one_line(err), EXIT_USAGE)
    except KeyboardInterrupt:
        return _fail(args, prog, "interrupted", _what_was_written(placed(before)), 130)
    except BrokenPipeError:
        return EXIT_OK
    except Exception as err:  # a bug: say so in one line, keep the traceback for debugging
        if os.environ.get("SYMKIN_DEBUG"):
            raise
        return _fail(args, prog, "internal error", f"{type(err).__name__}: {one_line(err)} (set SYMKIN_DEBUG=1 for "
                     "details; please report)", EXIT_INTERNAL)


def _what_was_written(paths: Sequence[Any]) -> str:
    """What an interrupted command leaves: the outputs it had put in place (whole), or nothing.

    >>> _what_was_written([]), _what_was_written(["report"])
    ('nothing was written', 'report was written in full before the interrupt; nothing else was written')
    """
    if not paths:
        return "nothing was written"
    return f"{', '.join(map(str, dict.fromkeys(paths)))} was written in full before the interrupt; nothing else was written"


def _fail(args: argparse.Namespace, prog: str, kind: str, message: str, code: int) -> int:
    """One line on stderr; with --json also {"error": message, "exit": code} on stdout."""
    print(f"{prog}: {kind}: {message}" if kind != "interrupted" else f"{prog}: interrupted; {message}", file=sys.stderr)
    if getattr(args, "json", False):
        _print_json({"error": message, "exit": code, "warnings": []})
    return code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
