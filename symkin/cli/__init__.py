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


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    prog = f"symkin {args.command}"
    try:
        return int(args.run(args) or EXIT_OK)
    except SymkinError as err:
        print(f"{prog}: error: {err}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print(f"{prog}: interrupted; nothing was written", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return EXIT_OK
    except Exception as err:  # a bug: say so in one line, keep the traceback for debugging
        if os.environ.get("SYMKIN_DEBUG"):
            raise
        print(f"{prog}: internal error: {type(err).__name__}: {err} (set SYMKIN_DEBUG=1 for details; please report)",
              file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
