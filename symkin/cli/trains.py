"""``symkin states`` (a train's shift table) and ``symkin trains`` (the ready-made train files)."""

from __future__ import annotations

from typing import Any

from symkin.cli.common import add_command, add_train_argument, emit

__all__ = ["register"]


def register(sub: Any) -> None:
    """Add the ``states`` and ``trains`` commands to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "states",
        help="the shift table of a train: every gear state's exact ratio",
        description="Solve every gear state of a train file ([states.NAME]: input, output, brakes, clutches): the "
        "ratio omega_input/omega_output, exact and as a float, and with --json every link's speed per unit input "
        "speed. A state that leaves a link free or locks the train is an error naming the state and the links. With "
        "one-way clutches ([one_way.NAME]) it shows which hold, overrun or stand idle in each state, driving and on "
        "coast (the output driving); a state no one-way clutch can hold is free (no ratio).",
        run=run_states,
    )
    add_train_argument(p, required=True)
    p.add_argument("--state", action="append", default=[], metavar="NAME",
                   help="only this state (repeat); default every state, in the file's order")

    q = add_command(
        sub, "trains",
        help="list the ready-made train files (use their names with --train)",
        description="The train files shipped with symkin, by name, with what each is. Give a name to --train "
        "wherever a command takes a train file.",
        run=run_trains,
    )
    q.set_defaults(train=None)


def run_states(args: Any) -> Any:
    """Run ``symkin states`` with the parsed ``args``: the shift table of a train's gear states; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.trains import ShiftTable, load_train

    train = load_train(args.train)
    if not train.states:
        from symkin.errors import InputError

        raise InputError(f"{args.train}: the train has no [states.NAME] tables; add one per gear state")
    states = [train.state(n) for n in args.state] if args.state else list(train.states)
    table = ShiftTable(train, tuple(train.shift(s) for s in states))
    return emit(table.text(), table.to_json())


def run_trains(args: Any) -> Any:
    """Run ``symkin trains`` with the parsed ``args``: the ready-made train files and what each is; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.trains import ready_made

    found = ready_made()
    width = max(len(n) for n in found)
    lines = [f"{name.ljust(width)}  {text}" for name, text in found.items()]
    lines.append("use a name wherever --train FILE is taken, e.g. symkin states --train ravigneaux")
    return emit("\n".join(lines), {"trains": [{"name": n, "description": d} for n, d in found.items()]})
