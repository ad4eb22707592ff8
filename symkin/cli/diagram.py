"""``symkin diagram``: the picture of a train itself, its kinematic scheme or its lever diagram.

    symkin diagram --train ravigneaux --out ravigneaux.svg
    symkin diagram --train simpson --state second --lever --out simpson-lever.png

The scheme is a half section (radii to scale, in mm by default: a train file's module is in
millimetres); the lever diagram spaces each link's node by tooth numbers and, for a state,
draws every node's speed per unit input speed (:mod:`symkin.viz.diagram`).
"""

from __future__ import annotations

from typing import Any

from symkin.cli.common import add_command, add_out_argument, add_train_argument, emit, figure_file
from symkin.errors import InputError

__all__ = ["register", "LENGTH_UNITS"]

#: The units --length-unit takes (the keys of :data:`symkin.viz.diagram.LENGTH_UNITS`).
LENGTH_UNITS = ("mm", "cm", "m", "in")


def register(sub: Any) -> None:
    """Add the ``diagram`` command to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "diagram",
        help="draw a train's kinematic scheme (half section) or, with --lever, its lever diagram",
        description="Draw what a train file says: the kinematic scheme in half section (shafts on the main axis, "
        "gears as pitch outlines to scale, carriers and their planets, brakes to the housing, clutches between "
        "shafts, every link named), or with --lever the lever diagram (Benford and Leising 1981: one bar per "
        "lever, nodes spaced by tooth numbers). With --state, that state's brakes and clutches are highlighted, its "
        "input and output marked and, on the levers, each node's speed per unit input speed drawn. Writes FILE "
        "(.svg keeps the names as text; .png, .pdf, .eps).",
        run=run_diagram,
    )
    add_train_argument(p, required=True)
    p.add_argument("--state", default=None, metavar="NAME", help="a gear state of the train to show (symkin states lists them)")
    p.add_argument("--lever", action="store_true", help="draw the lever diagram instead of the kinematic scheme")
    p.add_argument("--length-unit", default="mm", metavar="UNIT",
                   help=f"the unit of the scheme's radii: {', '.join(LENGTH_UNITS)} (default mm: the module is in millimetres)")
    add_out_argument(p, "a figure, .svg, .png, .pdf or .eps")


def run_diagram(args: Any) -> Any:
    """Run ``symkin diagram`` with the parsed ``args``: writes the scheme or the lever diagram to ``--out``; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin._util.jsonout import exact_json
    from symkin.cli.common import save_figure
    from symkin.trains import load_train
    from symkin.trains.lever import levers
    from symkin.viz.diagram import diagram, text_as_text

    out = figure_file(args.out)
    if args.length_unit not in LENGTH_UNITS:
        raise InputError(f"--length-unit {args.length_unit!r}: choose one of {', '.join(LENGTH_UNITS)}")
    train = load_train(args.train)
    state = train.state(args.state) if args.state is not None else None
    fig = diagram(train, state, lever=args.lever, length_unit=args.length_unit)
    with text_as_text():
        save_figure(fig, out)
    kind = "lever diagram" if args.lever else "kinematic scheme"
    data: dict[str, Any] = {
        "command": "diagram",
        "train": train.name or str(args.train),
        "source": train.source,
        "file": str(out),
        "kind": "lever" if args.lever else "scheme",
        "state": state.name if state is not None else None,
        "levers": [{"positions": {("frame" if n == "0" else n): x for n, x in lever.positions.items()}}
                   for lever in levers(train)],
        "units": {"length": args.length_unit, "positions": "tooth numbers (relative)"},
    }
    if state is not None:
        import sympy as sp

        from symkin import symbols as S

        shift = train.shift(state)
        w_in = S.omega(train.link(state.input).name)
        data["speeds_per_input"] = {} if shift.speeds is None else \
            {n: exact_json(sp.cancel(v / w_in)) for n, v in shift.speeds.items()}
        if shift.drive is not None:  # one-way clutches: which hold, which overrun; free: no ratio, no speeds
            data.update(free=shift.free, one_way=dict(shift.drive.status))
    title = train.name or str(args.train)
    return emit(f"{kind} of {title}{f', state {state.name}' if state else ''} written to {out}", data)
