"""``symkin efficiency``: torques, tooth forces, power flow and efficiency of a scheme or a train."""

from __future__ import annotations

from typing import Any

from symkin.cli.common import add_command, add_scheme_argument, add_teeth_argument, emit, mechanism_of
from symkin.errors import InputError

__all__ = ["register"]


def register(sub: Any) -> None:
    """Add the ``efficiency`` command to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "efficiency",
        help="efficiency (both ways), torques, tooth forces and power flow, in closed form",
        description="The efficiency of a scheme or a train with one link driving another while links are held "
        "(and clutches joined), by the basic-train method: each mesh's efficiency applies to the power it carries "
        "relative to the carrier, in the direction the kinematics and the load give. Prints the efficiency both "
        "ways (exact and as a float), whether the train locks itself when driven from the output, every link's "
        "torque and every tooth force per unit input torque, the power through each mesh (relative to its carrier), "
        "the housing's torque and each planet's pin load; --latex adds the law with the mesh efficiencies as symbols. "
        "With --omega and --torque instead of --driver/--driven: an operating point (as many speeds as degrees of "
        "freedom, the torques the balance leaves free): every link's speed, torque and power, ideal and with losses, "
        "the loss and the power flow.",
        run=run_efficiency,
    )
    add_scheme_argument(p, train=True)
    add_teeth_argument(p, "200,99,100,201", required=False)
    p.add_argument("--state", metavar="NAME", help="a train file's gear state (its input, output, brakes, clutches)")
    p.add_argument("--driver", help="the input link (not with --state)")
    p.add_argument("--driven", help="the output link (not with --state)")
    p.add_argument("--fixed", action="append", default=[], metavar="LINK", help="a held link (repeat)")
    p.add_argument("--mesh-efficiency", action="append", default=[], metavar="ETA or A-B=ETA",
                   help="every mesh's efficiency (one number), or one mesh's (A-B=0.97, repeat); default: the train "
                   "file's, else 0.98 external and 0.99 internal")
    p.add_argument("--latex", action="store_true", help="print the efficiency law in LaTeX, mesh efficiencies as symbols")
    p.add_argument("--omega", action="append", default=[], metavar="LINK=VALUE",
                   help="an operating point: a link's speed, rad/s or with a unit (C=2000rpm; repeat, as many as the "
                   "degrees of freedom the held links leave); with --torque, instead of --driver/--driven")
    p.add_argument("--torque", action="append", default=[], metavar="LINK=VALUE",
                   help="an operating point: the external torque on a link about the main axis, N m or with a unit "
                   "(C=100; repeat: as many as the balance leaves free, 0 for a link without a shaft)")


def run_efficiency(args: Any) -> Any:
    """Run ``symkin efficiency`` with the parsed ``args``: torques, power flow and efficiency of a train both ways; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.printing import latex
    from symkin.statics import statics

    mech, about, title = mechanism_of(args)
    joined: tuple = ()
    if args.omega or args.torque:
        return _operating_point(args, mech, about, title)
    if args.state is not None:
        if args.driver or args.driven or args.fixed:
            raise InputError("give either --state NAME or --driver/--driven/--fixed, not both")
        if not hasattr(mech, "state"):
            raise InputError("--state belongs to a train file (--train FILE)")
        st = mech.state(args.state)
        inp, out = st.input, st.output
        fixed, joined = mech.engaged(st)  # its brakes and clutches, and the one-way clutches that hold it
    else:
        if not args.driver or not args.driven:
            raise InputError("name the input and the output: --driver LINK --driven LINK (and --fixed LINK), or --state")
        inp, out, fixed = args.driver, args.driven, tuple(args.fixed)
    efficiency = _efficiency(args, mech)
    result = statics(mech, input=inp, output=out, fixed=fixed, joined=joined, efficiency=efficiency)
    data = {**about, **result.to_json()}
    text = f"{title}\n{result.text()}"
    if args.state is not None and getattr(mech, "one_ways", None):
        shift = mech.shift(args.state)
        assert shift.drive is not None and shift.coast is not None  # a train with one-way clutches says both
        data.update(one_way=shift.drive.to_json()["one_way"], coast=shift.coast.to_json())
        text += f"\none-way clutches: {shift.drive.text()}; coast (the output driving): {shift.coast.text()}"
        if shift.coast.free:  # no efficiency driven back: the output cannot drive the input
            free = shift.coast.text()  # "free (F overruns)"
            text = "\n".join(f"driven back  {out} -> {inp}: {free}: the output cannot drive the input in this state"
                              if line.startswith("driven back ") else line for line in text.splitlines())
            data["efficiency_backward"] = free
    if args.latex:
        symbolic = statics(mech, input=inp, output=out, fixed=fixed, joined=joined)
        data["latex"] = latex(symbolic.efficiency)
        data["latex_backward"] = latex(symbolic.backward.efficiency)
        text += f"\nLaTeX: {data['latex']}\nLaTeX, driven back: {data['latex_backward']}"
    return emit(text, data)


def _efficiency(args: Any, mech: Any) -> Any:
    """The mesh efficiencies --mesh-efficiency gives: "default", one number, or one per mesh."""
    from symkin.parsing import parse_number

    efficiency: Any = "default"
    per_mesh: dict[str, Any] = {}
    for item in args.mesh_efficiency:
        if "=" in item:
            key, _, value = item.partition("=")
            per_mesh[key.strip()] = parse_number(value, what=f"--mesh-efficiency {key.strip()}")
        else:
            if len(args.mesh_efficiency) > 1:
                raise InputError("give one --mesh-efficiency ETA for every mesh, or A-B=ETA for each mesh, not both")
            efficiency = parse_number(item, what="--mesh-efficiency")
    if per_mesh:
        from symkin.statics.power import DEFAULT_EFFICIENCY, _sides

        filled = {}
        for s in _sides(mech):
            key = f"{s.mesh.a}-{s.mesh.b}"
            default = s.mesh.efficiency or DEFAULT_EFFICIENCY["internal" if s.internal else "external"]
            filled[key] = per_mesh.pop(key, per_mesh.pop(f"{s.mesh.b}-{s.mesh.a}", default))
        if per_mesh:
            raise InputError(f"no mesh {sorted(per_mesh)[0]!r}; the meshes are {', '.join(filled)}")
        efficiency = filled
    return efficiency


def _operating_point(args: Any, mech: Any, about: dict[str, Any], title: str) -> Any:
    """symkin efficiency --omega LINK=VALUE ... --torque LINK=VALUE ...: the train at an operating point."""
    from symkin.cli.common import link_values
    from symkin.statics import statics

    if args.driver or args.driven or args.latex:
        raise InputError("an operating point (--omega, --torque) takes no --driver, --driven or --latex")
    if not args.omega or not args.torque:
        raise InputError("an operating point needs speeds and torques: --omega LINK=VALUE (repeat) and --torque "
                         "LINK=VALUE (repeat)")
    fixed, joined = tuple(args.fixed), ()
    if args.state is not None:
        if not hasattr(mech, "state"):
            raise InputError("--state belongs to a train file (--train FILE)")
        if args.fixed:
            raise InputError("give either --state NAME or --fixed, not both")
        fixed, joined = mech.engaged(mech.state(args.state))
    speeds = link_values(args.omega)
    torques = link_values(args.torque, what="--torque", unit="N*m")
    efficiency = _efficiency(args, mech)
    result = statics(mech, speeds=speeds, torques=torques, fixed=fixed, joined=joined, efficiency=efficiency)
    if args.state is not None and getattr(mech, "one_ways", None):
        inp = mech.link(mech.state(args.state).input).name
        if result.powers[inp] < 0:  # the output drives the input: the one-way clutches that hold on coast
            fixed, joined = mech.engaged(args.state, coast=True)
            result = statics(mech, speeds=speeds, torques=torques, fixed=fixed, joined=joined, efficiency=efficiency)
    return emit(f"{title}\n{result.text()}", {**about, **result.to_json()})
