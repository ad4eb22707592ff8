"""``symkin ratio`` and ``symkin speeds``: the 2009 paper's schemes from tooth numbers, or any train file."""

from __future__ import annotations

from typing import Any

from symkin.cli.common import (
    SCHEME_HELP,
    add_command,
    add_omega_argument,
    add_scheme_argument,
    add_teeth_argument,
    emit,
    exact_json,
    float_text,
    link_values,
    mechanism_of,
)

__all__ = ["register", "SCHEME_HELP"]


def register(sub: Any) -> None:
    """Add the ``ratio`` and ``speeds`` commands to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "ratio",
        help="ratio i_ab^(c) = omega_a/omega_b of a scheme with link c fixed",
        description="The ratio i_ab^(c) = omega_a / omega_b (a = driver, b = driven) with link c fixed, "
        "exact and as a float. Links of a scheme: 1, 2, 3, 4, H (2 and 3 name the planet); of a train: its "
        "link names (or a gear's name for the link that holds it).",
        run=run_ratio,
    )
    add_scheme_argument(p, train=True)
    add_teeth_argument(p, "100,100,101,99", required=False)
    p.add_argument("--driver", required=True, help="link a")
    p.add_argument("--driven", required=True, help="link b")
    p.add_argument("--fixed", required=True, help="link c, held still")

    q = add_command(
        sub, "speeds",
        help="angular velocity of every link of a scheme from known speeds",
        description="Every link's angular velocity from the known ones (give as many as the scheme's "
        "degrees of freedom; a fixed link has speed 0). Values are exact, in rad/s: 100, 0.5, 3/4, 2*pi; "
        "or with a unit: 300rpm, 90deg/s.",
        run=run_speeds,
    )
    add_scheme_argument(q, train=True)
    add_teeth_argument(q, "54,45,44,55", required=False)
    add_omega_argument(q)


def run_ratio(args: Any) -> Any:
    """Run ``symkin ratio`` with the parsed ``args``: the exact ratio i_ab^(c) of a scheme or a train; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.printing import latex

    mech, about, title = mechanism_of(args)
    law = mech.ratio(args.driver, args.driven, fixed=args.fixed)
    a, b, c = (mech.link(x).name for x in (args.driver, args.driven, args.fixed))
    value = law.rhs
    data = {
        **about,
        "driver": a,
        "driven": b,
        "fixed": c,
        "ratio": exact_json(value),
        "latex": latex(law),
        "coaxial": not mech.coaxiality_defects(),
    }
    text = f"{title}\ni_{a}{b}^({c}) = omega_{a}/omega_{b} = {value}"
    f = float_text(value)
    if f and f != str(value):
        text += f" = {f}"
    return emit(text, data)


def run_speeds(args: Any) -> Any:
    """Run ``symkin speeds`` with the parsed ``args``: every link's angular velocity from the known ones; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.parsing.quantities import unit_of

    known = link_values(args.omega)
    mech, about, title = mechanism_of(args)
    speeds = mech.speeds(known)
    given = {mech.link(k).name for k in known}
    # the unit the speeds were given in, when one was (the derived ones are printed in it too)
    typed = {unit_of(item.partition("=")[2], "rad/s") for item in args.omega} - {None}
    unit = typed.pop() if len(typed) == 1 else None
    unit = None if unit in ("rad/s", "radian/second") else unit
    converted = speeds.in_unit(unit) if unit else {}
    rows, data_links = [], {}
    for name, value in speeds.items():
        tag = "given" if name in given else "derived"
        f = float_text(value)
        row = f"omega_{name:<3} = {value}" + (f" = {f}" if f and f != str(value) else "") + (" rad/s" if unit else "")
        if unit:
            there = converted[name]
            g = float_text(there)
            row += f" = {there}" + (f" = {g}" if g and g != str(there) else "") + f" {unit}"
        rows.append(row + f"   ({tag})")
        speed = exact_json(value)
        assert speed is not None  # a speed is never None
        data_links[name] = {**speed, "given": name in given}
    data = {
        **about,
        "speeds": data_links,
        "coaxial": not mech.coaxiality_defects(),
        "units": {"speeds": "rad/s", **({"speeds_in_unit": unit} if unit else {})},
    }
    if unit:
        data["speeds_in_unit"] = {name: exact_json(v) for name, v in converted.items()}
    return emit(f"{title}\n" + "\n".join(rows), data)
