"""``symkin geometry``: the involute geometry of a train's gears and meshes, its problems, and CAD outlines."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from symkin.cli.common import add_command, add_train_argument, emit
from symkin.errors import InputError

__all__ = ["register"]


def register(sub: Any) -> None:
    """Add the ``geometry`` command to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "geometry",
        help="gear geometry of a train: diameters, shifts, contact ratios, undercut, interference; DXF/SVG outlines",
        description="The involute geometry (ISO 53 basic rack, ISO 21771; lengths in mm) of every spur gear and mesh "
        "of a train file: per gear the profile shift, reference, base, tip and root diameters, the tooth thickness "
        "at the tip and the least shift against undercut; per mesh the working pressure angle (from the involute "
        "equation), the working centre distance and the transverse contact ratio, with the interference checks of "
        "internal meshes. Problems (undercut, pointed or thin tips, contact ratio below the limit, interference, "
        "shifts that do not give the centre distance) are listed; the exit status is 0 with problems printed. "
        "A gear's tooth form is set in the train file: { teeth = 20, shift = 0.25, addendum = 1, dedendum = 1.25, "
        "pressure_angle = 20 }.",
        run=run_geometry,
    )
    add_train_argument(p, required=True)
    p.add_argument("--out", metavar="FILE", help="write the tooth outlines, placed as in the train: FILE.dxf (CAD, one "
                   "layer per gear, mm; needs ezdxf) or FILE.svg")
    p.add_argument("--choose-shifts", action="store_true",
                   help="replace the file's shifts by the ones that give every mesh its centre distance (the least "
                   "largest shift with no external gear undercut and no mesh interference; where no shift clears an "
                   "interference, a note says so), and report them")
    p.add_argument("--min-contact-ratio", default="1.2", metavar="EPS",
                   help="report meshes whose transverse contact ratio is below EPS (default 1.2)")


def _f(value: Any, digits: int = 12) -> float:
    return round(float(value), digits)


def run_geometry(args: Any) -> Any:
    """Run ``symkin geometry`` with the parsed ``args``; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    import sympy as sp

    from symkin.geometry import coaxial_shifts, train_geometry
    from symkin.parsing import parse_number
    from symkin.trains import load_train

    out = Path(args.out) if args.out else None
    if out is not None and out.suffix.lower() not in (".dxf", ".svg"):
        raise InputError(f"--out {args.out}: give a file ending in .dxf or .svg")
    eps_min = parse_number(args.min_contact_ratio, what="--min-contact-ratio")
    if not eps_min > 0:
        raise InputError(f"--min-contact-ratio must be positive, got {args.min_contact_ratio}")
    train = load_train(args.train)
    shifts = coaxial_shifts(train) if args.choose_shifts else None
    geo = train_geometry(train, shifts=shifts, min_contact_ratio=eps_min)
    written = []
    if out is not None and not geo.gears:
        raise InputError(f"--out {args.out}: the train has no spur gears to draw (bevel gears are not covered)")
    if out is not None:
        from symkin._io.atomic import replacing
        from symkin.geometry.export import dxf_text, svg_text

        text = dxf_text(geo) if out.suffix.lower() == ".dxf" else svg_text(geo)
        with replacing(out) as (tmp,):
            tmp.write_text(text, encoding="utf-8")
        written.append(str(out))
    gears = {}
    for name, g in geo.gears.items():
        gears[name] = {
            "teeth": int(g.teeth), "internal": g.internal, "shift": _f(g.shift, 6), "module": _f(g.module, 6),
            "pressure_angle_deg": _f(g.form.pressure_angle, 6),
            "reference_diameter": _f(g.reference_diameter), "base_diameter": _f(g.base_diameter),
            "tip_diameter": _f(g.tip_diameter), "root_diameter": _f(g.root_diameter),
            "reference_thickness": _f(g.reference_thickness),
            "tip_thickness": None if g.tip_thickness is None else _f(g.tip_thickness),
            "minimum_shift": None if g.minimum_shift is None else _f(g.minimum_shift),
            "undercut": g.undercut, "pointed_tip": g.pointed,
        }
    meshes = [{"gears": list(m.gears), "internal": m.pair.internal, "centre_distance": _f(m.pair.centre_distance, 6),
               "reference_centre_distance": _f(m.pair.reference_centre_distance, 6),
               "working_pressure_angle_deg": _f(sp.deg(m.pair.working_pressure_angle), 6),
               "contact_ratio": _f(m.pair.contact_ratio), "problems": list(m.problems)} for m in geo.meshes]
    data = {"train": train.name or str(args.train), "units": {"length": "mm", "angle": "deg"}, "gears": gears,
            "meshes": meshes, "problems": geo.problems, "notes": list(geo.notes), "written": written}
    if shifts is not None:
        data["chosen_shifts"] = {g: _f(x, 6) for g, x in shifts.items()}
    return emit(_text(data), data)


def _text(data: dict[str, Any]) -> str:
    lines = [f"{data['train']}: gear geometry (ISO 53 rack, lengths in mm)", ""]
    head = ["gear", "z", "x", "d", "d_b", "d_a", "d_f", "s_a", "x_min"]
    rows = [[n, str(g["teeth"]) + (" int" if g["internal"] else ""), f"{g['shift']:.4f}", f"{g['reference_diameter']:.3f}",
             f"{g['base_diameter']:.3f}", f"{g['tip_diameter']:.3f}", f"{g['root_diameter']:.3f}",
             "-" if g["tip_thickness"] is None else f"{g['tip_thickness']:.3f}",
             "-" if g["minimum_shift"] is None else f"{g['minimum_shift']:.4f}"] for n, g in data["gears"].items()]
    lines += _table(head, rows)
    lines.append("")
    head = ["mesh", "a_w", "a", "alpha_w (deg)", "eps_alpha"]
    rows = [[f"{m['gears'][0]}-{m['gears'][1]}" + (" int" if m["internal"] else ""), f"{m['centre_distance']:.4f}",
             f"{m['reference_centre_distance']:.4f}", f"{m['working_pressure_angle_deg']:.4f}", f"{m['contact_ratio']:.3f}"]
            for m in data["meshes"]]
    lines += _table(head, rows)
    if "chosen_shifts" in data:
        lines += ["", "chosen shifts: " + ", ".join(f"{g} {x:+.5f}" for g, x in data["chosen_shifts"].items())]
    lines += [""] + ([f"problem: {p}" for p in data["problems"]] or ["no problems found"])
    lines += [f"note: {n}" for n in data["notes"]]
    lines += [f"wrote {w}" for w in data["written"]]
    return "\n".join(lines)


def _table(head: list[str], rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[i]) for r in [head, *rows]) for i in range(len(head))]
    return ["  ".join(c.rjust(w) if i else c.ljust(w) for i, (c, w) in enumerate(zip(r, widths))) for r in [head, *rows]]
