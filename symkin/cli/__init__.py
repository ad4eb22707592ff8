"""The ``symkin`` command line.

Each command lives in its own module under :mod:`symkin.cli` with a ``register``
function; :data:`COMMANDS` lists them.  Every command takes ``--json``; bad input gives
a one-line message on stderr and exit status 2, never a traceback.

Exit status: 0 success; 1 a reproduction found a result that differs; 2 bad input;
3 an internal error (set SYMKIN_DEBUG=1 for the traceback).
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import warnings
from typing import NoReturn, Sequence

from ..errors import SymkinError

__all__ = ["main", "COMMANDS", "ArgumentParser"]

#: Modules of symkin.cli that define commands, in the order --help lists them.
COMMANDS = ("reproduce", "gears", "plots", "cardan", "multistage", "helical")

EXIT_OK, EXIT_DIFFERS, EXIT_USAGE, EXIT_INTERNAL = 0, 1, 2, 3


class ArgumentParser(argparse.ArgumentParser):
    """argparse with a one-line error message."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> ArgumentParser:
    from .. import __version__

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


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status.

    A failure prints one line on stderr; a Python warning raised on the way (for example
    a NumPy overflow) becomes a one-line note after a success and is dropped after a
    failure, whose message says what went wrong.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    prog = f"symkin {args.command}"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("default")
        code = _run(args, prog)
    if code in (EXIT_OK, EXIT_DIFFERS):
        for w in dict.fromkeys(f"{w.category.__name__}: {w.message}" for w in caught):
            print(f"{prog}: note: {one_line(w)}", file=sys.stderr)
    return code


def _run(args: argparse.Namespace, prog: str) -> int:
    try:
        return int(args.run(args) or EXIT_OK)
    except SymkinError as err:
        print(f"{prog}: error: {one_line(err)}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print(f"{prog}: interrupted; nothing was written", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return EXIT_OK
    except Exception as err:  # a bug: say so in one line, keep the traceback for debugging
        if os.environ.get("SYMKIN_DEBUG"):
            raise
        print(f"{prog}: internal error: {type(err).__name__}: {one_line(err)} (set SYMKIN_DEBUG=1 for details; "
              "please report)", file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
