"""``symkin dynamics`` (a train's rigid equations of motion) and ``symkin modes`` (its torsional natural modes)."""

from __future__ import annotations

import re
from typing import Any

from symkin.cli.common import add_command, add_train_argument, emit, parse_quantity
from symkin.errors import InputError

__all__ = ["register"]

_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]{0,40}$")


def register(sub: Any) -> None:
    """Add the ``dynamics`` and ``modes`` commands to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "dynamics",
        help="rigid-body equations of motion M q'' = f of a train, in closed form",
        description="The generalised mass matrix M, the forcing f and the equations M q'' = f of a train file in a "
        "gear state (brakes hold links, clutches join them), from the exact speed laws: every link's spin, every "
        "planet's spin and the motion of its centre (module in mm, converted to m). Inertias (kg m^2) and planet "
        "masses (kg) come from the file's inertia and mass keys, else they are symbols J_LINK and m_LINK. Prints the "
        "coordinates, M exact and as floats, f, and the accelerations when every value is a number.",
        run=run_dynamics,
    )
    add_train_argument(p, required=True)
    p.add_argument("--state", metavar="NAME", help="a gear state of the file (default: none, every link free)")
    p.add_argument("--coordinates", metavar="A,B", help="the links whose turns are the coordinates (default: the "
                   "state's input, or the fewest links that fix the motion)")
    p.add_argument("--torque", action="append", default=[], metavar="LINK=VALUE",
                   help="a torque on a link, in N m or with a unit (20, 1.5kN*m), or a symbol name (T_in); repeat")
    p.add_argument("--latex", action="store_true", help="print the equations in LaTeX (an align* body)")
    _add_value_argument(p)

    q = add_command(
        sub, "modes",
        help="torsional natural frequencies and mode shapes of a train",
        description="A purely rotational lumped-parameter model of a train file: every link a rotational coordinate "
        "(each of count planets its own), each mesh a spring (its stiffness, N/m) along its line of action between "
        "the base circles (the pressure angle of the gears in the file, 20 degrees where it gives none), each main-axis link's shaft stiffness (N m/rad) to the frame; "
        "brakes hold links, clutches join them. Prints the natural frequencies (Hz; rigid-body modes as 0) and the "
        "mode shapes by link (normalised to the largest entry).",
        run=run_modes,
    )
    add_train_argument(q, required=True)
    q.add_argument("--state", metavar="NAME", help="a gear state of the file (default: none)")
    _add_value_argument(q)


def _add_value_argument(parser: Any) -> None:
    parser.add_argument("--value", action="append", default=[], metavar="NAME=NUMBER",
                        help="a number for a symbol the file leaves, in SI units (J_S=0.01, m_P=0.5, k_s_p=5e8); repeat")


def _values(items: list[str]) -> dict[str, Any]:
    from symkin.parsing import parse_number

    out: dict[str, Any] = {}
    for item in items:
        name, _, value = item.partition("=")
        name = name.strip()
        if not _NAME.match(name) or not value.strip():
            raise InputError(f"--value takes NAME=NUMBER (for example J_S=0.01), got {item!r}")
        if name in out:
            raise InputError(f"--value gives {name} twice; give each symbol once")
        out[name] = parse_number(value, what=f"--value {name}")
    return out


def _torques(items: list[str]) -> dict[str, Any]:
    import sympy as sp

    out: dict[str, Any] = {}
    for item in items:
        if "=" not in item:
            raise InputError(f"--torque takes LINK=VALUE (for example S=20), got {item!r}")
        link, _, value = item.partition("=")
        link, value = link.strip(), value.strip()
        if not link:
            raise InputError(f"--torque {item!r} names no link; write LINK=VALUE, for example S=20")
        if link in out:
            raise InputError(f"--torque gives link {link} twice; give each link once")
        if _NAME.match(value) and value not in ("pi", "E", "e", "inf", "nan", "oo", "I"):
            out[link] = sp.Symbol(value, real=True)
        else:
            out[link] = parse_quantity(value, "N*m", what=f"--torque value for link {link}")
    return out


def run_dynamics(args: Any) -> Any:
    """Run ``symkin dynamics`` with the parsed ``args``: the equations of motion of a train; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.dynamics import equations_of_motion
    from symkin.trains import load_train

    train = load_train(args.train)
    coordinates = None
    if args.coordinates is not None:
        coordinates = [c.strip() for c in args.coordinates.split(",")]
        if not all(coordinates):
            raise InputError(f"--coordinates takes link names separated by commas, got {args.coordinates!r}")
    eom = equations_of_motion(train, state=args.state, coordinates=coordinates, torques=_torques(args.torque),
                              values=_values(args.value))
    data = eom.to_json()
    text = eom.text()
    if args.latex:
        data["latex"] = eom.latex()
        text += "\n\n" + data["latex"]
    return emit(text, data)


def run_modes(args: Any) -> Any:
    """Run ``symkin modes`` with the parsed ``args``: the torsional natural frequencies and modes of a train; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.dynamics import natural_modes
    from symkin.trains import load_train

    modes = natural_modes(load_train(args.train), state=args.state, values=_values(args.value))
    return emit(modes.text(), modes.to_json())
