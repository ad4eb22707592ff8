"""Helpers shared by the CLI commands: registering the common options, parsing values,
and handing the output (text or JSON) to :func:`symkin.cli.main`.

Conventions every command follows:

- ``--json`` prints one JSON object on stdout; it always has a ``"warnings"`` list, and
  every exact number in it is ``{"exact": text, "float": number or null}``
  (:func:`symkin._util.jsonout.exact_json`).  A failure with ``--json`` prints
  ``{"error": message, "exit": status}`` on stdout besides the one-line message on stderr.
- ``--omega LINK=VALUE`` is a known angular velocity of a named link: a bare number is in
  rad/s, and a value may carry a unit (``1=300rpm``, ``H=90deg/s``); a plain speed has
  another name (``symkin cardan --speed``).
- Values with a unit are accepted wherever a quantity is meant (speeds, lengths, angles of
  motion, times; parsed by :func:`symkin.parsing.parse_quantity` through pint); bare
  numbers keep the unit each option states.  With ``--json``, ``"units"`` gives the unit of
  every dimensional key of the output.
- ``--out`` names what a command writes: a folder (``--out DIR``, reproduce) or a file
  whose suffix chooses the format (``--out FILE``); an extra figure beside a command's
  printed result is ``--plot FILE`` (split).  Files appear whole or not at all.
- Every angle option states its unit in its help and in its JSON key (``_deg`` or
  ``_rad``): gear-design angles (helix, pressure) in degrees, angles of motion (guide,
  carrier, pin) in radians.
- ``--quiet`` turns off the progress display of a command that has one.
- A command's run function returns its :class:`Output` (``return emit(text, data)``), which
  :func:`symkin.cli.main` prints.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from symkin._io.progress import Progress
from symkin.errors import InputError


def _on_first_call(module: str, name: str) -> Callable[..., Any]:
    """``module.name``, imported when first called: the parsers and the JSON helpers need
    SymPy, which ``symkin --help`` and the parser never load (commands import what they use)."""

    def call(*args: Any, **kwargs: Any) -> Any:
        import importlib

        return getattr(importlib.import_module(module), name)(*args, **kwargs)

    call.__name__ = call.__qualname__ = name
    call.__doc__ = f"``{module}.{name}`` (imported on first call)."
    return call


exact_json = _on_first_call("symkin._util.jsonout", "exact_json")
float_text = _on_first_call("symkin._util.jsonout", "float_text")
parse_expression = _on_first_call("symkin.parsing", "parse_expression")
parse_integer = _on_first_call("symkin.parsing", "parse_integer")
parse_number = _on_first_call("symkin.parsing", "parse_number")
parse_quantity = _on_first_call("symkin.parsing", "parse_quantity")
parse_real = _on_first_call("symkin.parsing", "parse_real")
sign_of = _on_first_call("symkin.values", "sign_of")

__all__ = [
    "teeth_list",
    "scheme_mechanism",
    "mechanism_of",
    "add_train_argument",
    "link_value",
    "exact_json",
    "emit",
    "Output",
    "add_command",
    "add_json_flag",
    "add_quiet_flag",
    "add_scheme_argument",
    "add_teeth_argument",
    "add_omega_argument",
    "add_out_argument",
    "float_text",
    "figure_file",
    "Progress",
    "save_figure",
    "SCHEME_HELP",
]

SCHEME_HELP = "AI1 (single-row AI, teeth Z1,Z2,Z4), AI, AA or II (two-row, teeth Z1,Z2,Z3,Z4)"


def add_command(sub: Any, name: str, *, help: str, description: str, run: Callable[[Any], Output]) -> argparse.ArgumentParser:
    """A subcommand with ``--json``; ``run(args)`` is called with the parsed arguments."""
    p = sub.add_parser(name, help=help, description=description)
    add_json_flag(p)
    p.set_defaults(run=run)
    return p


def add_json_flag(parser: Any) -> None:
    """Add ``--json`` (print one JSON object instead of text) to ``parser``."""
    parser.add_argument("--json", action="store_true",
                        help="print machine-readable JSON instead of text (errors too, as {\"error\": ..., \"exit\": 2})")


def add_quiet_flag(parser: Any) -> None:
    """Add ``--quiet`` (no progress display) to ``parser``."""
    parser.add_argument("--quiet", action="store_true", help="no progress display")


def add_scheme_argument(parser: Any, *, train: bool = False) -> None:
    """The SCHEME positional; with ``train``, optional, and ``--train FILE`` beside it."""
    if not train:
        parser.add_argument("scheme", help=SCHEME_HELP)
        return
    parser.add_argument("scheme", nargs="?", default=None, help=SCHEME_HELP + "; or give --train")
    add_train_argument(parser)


def add_train_argument(parser: Any, *, required: bool = False) -> None:
    """Add ``--train FILE`` (a train file, or a ready-made train by name) to ``parser``."""
    parser.add_argument("--train", required=required, metavar="FILE",
                        help="a train file (TOML), or a ready-made train by name (symkin trains lists them)")


def add_teeth_argument(parser: Any, example: str, *, required: bool = True, default: str | None = None,
                       metavar: str | None = None, help: str | None = None) -> None:
    """Add ``--teeth Z1,Z2,...`` to ``parser``; ``example`` shows a valid value in the help."""
    parser.add_argument("--teeth", required=required, default=default, metavar=metavar,
                        help=help or f"comma-separated tooth numbers, e.g. {example}")


def add_omega_argument(parser: Any, help: str = "a known angular velocity LINK=VALUE, in rad/s or with a unit "
                       "(1=300rpm, H=90deg/s; repeat)") -> None:
    """Add the repeatable ``--omega LINK=VALUE`` (a known angular velocity, rad/s or with a unit) to ``parser``."""
    parser.add_argument("--omega", action="append", default=[], metavar="LINK=VALUE", help=help)


def add_out_argument(parser: Any, what: str, *, required: bool = True, default: str | None = None) -> None:
    """``--out FILE`` (``what`` says which suffixes) or ``--out DIR``."""
    folder = what.upper().startswith("DIR")
    parser.add_argument("--out", required=required, default=default, metavar="DIR" if folder else "FILE",
                        help=what if folder else f"write FILE: {what}; the suffix chooses the format")


def figure_file(text: str, option: str = "--out") -> Path:
    """The figure file an option names: a .png, .pdf, .svg or .eps in an existing folder.

    >>> figure_file("plot.png")
    PosixPath('plot.png')
    """
    out = Path(text)
    if out.suffix.lower() not in (".png", ".pdf", ".svg", ".eps"):
        raise InputError(f"{option} {text}: give a file ending in .png, .pdf, .svg or .eps")
    if not out.resolve().parent.is_dir():
        raise InputError(f"{option} {text}: the folder {out.resolve().parent} does not exist")
    if out.is_dir():
        raise InputError(f"{option} {text} is a folder; give a file name ending in .png, .pdf, .svg or .eps")
    return out


def save_figure(fig: Any, out: Path) -> list[Path]:
    """Save under a temporary name beside ``out``, then rename (never a half-written file, and
    an earlier file kept when saving fails)."""
    from symkin._io.atomic import replacing
    from symkin.viz.figures import save

    with replacing(out) as (tmp,):
        save(fig, tmp)
    return [out]


def mechanism_of(args: Any, module: Any = None) -> tuple[Any, dict[str, Any], str]:
    """The mechanism a command names: a ready-made scheme with ``--teeth`` (and ``--module``),
    or a train with ``--train``; with what to say about it in JSON, and a title.
    """
    train = getattr(args, "train", None)
    if train is not None:
        if args.scheme is not None or getattr(args, "teeth", None) is not None:
            raise InputError("give either SCHEME --teeth ... or --train FILE, not both")
        if module is not None and module != 1:
            raise InputError("--module applies to a scheme; a train file gives its own module")
        from symkin.trains import load_train

        mech = load_train(train)
        return mech, {"train": mech.name or train, "source": mech.source}, mech.name or str(train)
    if args.scheme is None:
        raise InputError("name a scheme (AI1, AI, AA, II) with --teeth, or a train with --train FILE")
    if getattr(args, "teeth", None) is None:
        raise InputError(f"the scheme {args.scheme} needs --teeth, e.g. --teeth 20,30,20,70")
    mech, teeth = scheme_mechanism(args.scheme, args.teeth, module)
    return mech, {"scheme": args.scheme, "teeth": [int(z) for z in teeth]}, \
        f"{args.scheme} z = {', '.join(map(str, teeth))}"


def scheme_mechanism(scheme: str, teeth_text: str, module: Any = None) -> tuple[Any, list[Any]]:
    """The mechanism of a ready-made scheme (``AI1``, ``AI``, ``AA``, ``II``) from ``--teeth``
    (and ``--module``), and its tooth numbers."""
    from symkin import schemes

    if scheme not in schemes.SCHEMES:
        raise InputError(f"unknown scheme {scheme!r}; choose one of {', '.join(schemes.SCHEMES)}")
    counts = (3, 4) if scheme == "AI1" else (4,)
    teeth = teeth_list(teeth_text, counts)
    if scheme == "AI1" and len(teeth) == 4:
        if teeth[1] != teeth[2]:
            raise InputError("AI1 has one planet gear: give Z1,Z2,Z4 (or Z1,Z2,Z3,Z4 with Z2 = Z3)")
        teeth = [teeth[0], teeth[1], teeth[3]]
    options = {} if module is None else {"module": module}
    return schemes.scheme(scheme, teeth=tuple(teeth), **options), teeth


def teeth_list(text: str, counts: tuple[int, ...], what: str = "--teeth") -> list[Any]:
    """Comma-separated tooth numbers, exactly ``counts`` of them."""
    if not isinstance(text, str) or not text.strip():
        raise InputError(f"{what} is empty; give {' or '.join(map(str, counts))} comma-separated tooth numbers")
    parts = [p.strip() for p in text.split(",")]
    if len(parts) not in counts:
        raise InputError(f"{what} needs {' or '.join(map(str, counts))} comma-separated tooth numbers, got {len(parts)}")
    values = [parse_integer(p, what=f"tooth number {i} in {what}") for i, p in enumerate(parts, 1)]
    for i, v in enumerate(values, 1):
        if v <= 0:
            raise InputError(f"tooth number {i} in {what} must be positive, got {v}")
    return values


def link_value(text: str, what: str = "--omega", names: Sequence[str] = (), unit: str = "rad/s") -> tuple[str, Any]:
    """``LINK=VALUE``; VALUE is a number or a constant expression such as 2*pi (rad/s), or a
    speed with a unit such as 300rpm (converted to rad/s, exactly); ``names`` are the
    symbols it may hold (``("t",)``: a speed that varies in time, such as 10*t); ``unit``
    the unit of a bare number (``"N*m"`` for ``--torque``).

    >>> link_value("1=300rpm")
    ('1', 10*pi)
    """
    if not isinstance(text, str) or "=" not in text:
        raise InputError(f"{what} takes LINK=VALUE (for example 1=100), got {text!r}")
    link, _, value = text.partition("=")
    link = link.strip()
    if not link:
        raise InputError(f"{what} {text!r} names no link; write LINK=VALUE, for example 1=100")
    return link, parse_quantity(value, unit, what=f"{what} value for link {link}", names=names)


def link_values(items: Sequence[str], what: str = "--omega", names: Sequence[str] = (),
                unit: str = "rad/s") -> dict[str, Any]:
    """``{link: value}`` from repeated ``LINK=VALUE`` options (:func:`link_value`); a link given
    twice under one name is an error (the engine refuses one given under two names).

    >>> link_values(["1=300rpm", "4=0"])
    {'1': 10*pi, '4': 0}
    >>> link_values(["1=100", "1=3"])
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: --omega gives link 1 twice (1=100 and 1=3); give each link once
    """
    known: dict[str, Any] = {}
    texts: dict[str, str] = {}
    for item in items:
        link, value = link_value(item, what, names, unit)
        if link in known:
            raise InputError(f"{what} gives link {link} twice ({texts[link]} and {item.strip()}); give each link once")
        known[link], texts[link] = value, item.strip()
    return known


@dataclass(frozen=True)
class Output:
    """What a command's run function returns to :func:`symkin.cli.main`, which prints it after
    the run: ``text`` (and the warnings as notes on stderr), or with ``--json`` ``data`` as JSON
    with its ``"warnings"``; ``code`` is the exit status (1: a check failed)."""

    text: str
    data: dict[str, Any]
    code: int = 0


def emit(text: str, data: dict[str, Any], code: int = 0) -> Output:
    """The command's output, for its run function to return: ``return emit(text, data)``."""
    return Output(text, data, code)
