"""``symkin synthesize``: tooth numbers of any train for a target ratio."""

from __future__ import annotations

import dataclasses
from typing import Any

from symkin.cli.common import Progress, add_command, add_quiet_flag, add_train_argument, emit
from symkin.errors import InputError, SymkinError

__all__ = ["register"]


def register(sub: Any) -> None:
    """Add the ``synthesize`` command to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "synthesize",
        help="tooth numbers of any train for a target ratio (k planets assembled, clear and coaxial)",
        description=(
            "Find tooth numbers for a train file whose teeth are symbols (teeth = \"z1\"; a file that gives every "
            "tooth number has them all searched) that give the ratio omega_driver/omega_driven with the --fixed links "
            "held (or a --state of the file) within the tolerance, with --planets equally spaced copies of every "
            "planet kind that can be assembled and clear each other, every planet's meshes coaxial (or within --shift "
            "of one working centre distance), and every tooth number within the limits (--zmin defaults to the least "
            "number cut without undercut at the pressure angle). The conditions are derived from the train's model "
            "and printed (--latex as LaTeX). Designs are ranked by ratio error, then size, then tooth sum (--rank "
            "changes the order, efficiency included); each is "
            "re-checked by building its train and deriving its ratio and planet positions again. --scheduler runs "
            "the search on Dask; the result is the same."
        ),
        run=run_synthesize,
    )
    add_train_argument(p, required=True)
    p.add_argument("--driver", help="the driving link (or gear)")
    p.add_argument("--driven", help="the driven link (or gear)")
    p.add_argument("--fixed", action="append", default=[], metavar="LINK",
                   help="a link held still (repeat, or LINK,LINK); the frame's gears are held already")
    p.add_argument("--state", help="instead of --driver/--driven/--fixed: a gear state of the train file")
    p.add_argument("--ratio", help="target ratio omega_driver/omega_driven, exact (2.4, 12/5, -3)")
    p.add_argument("--ratios", metavar="STATE=R,...",
                   help="a whole transmission: a target ratio for each named state of the train file, searched at once "
                   "(first=4.696,second=3.130,...); every set's conditions, pruned state by state; each design's gear "
                   "geometry checked as for one ratio (--allow-undercut, --min-contact-ratio)")
    p.add_argument("--absolute", action="store_true", help="with --ratios: --tolerance is absolute, not relative")
    p.add_argument("--tolerance", default="0.01", help="relative ratio tolerance (default 0.01 = 1 %%)")
    p.add_argument("--ratio-range", metavar="LO,HI", help="instead of --ratio: every ratio from LO to HI (-120,-30 for a negative range)")
    p.add_argument("--planets", "-k", required=True,
                   help="equally spaced planets of each kind, or 'file' for each planet's count in the train file")
    p.add_argument("--zmin", help="least tooth number of every unknown gear (default: the least without undercut)")
    p.add_argument("--zmax", default="150", help="largest tooth number of every unknown gear (default 150)")
    p.add_argument("--pressure-angle", default="20", metavar="DEG",
                   help="pressure angle in degrees, for the undercut limit (default 20)")
    p.add_argument("--addendum", default="1", help="addendum coefficient h_a* of the tip circles (default 1)")
    p.add_argument("--clearance", default="0", help="least gap between neighbouring planets' tip circles, in modules "
                   "(default 0)")
    p.add_argument("--shift", default="0", metavar="Y",
                   help="profile shift allowed: largest |a_w - a|/m of a mesh to a planet (default 0: pitch circles)")
    p.add_argument("--ring-difference", default="8",
                   help="least tooth difference of an internal gear and a gear meshing it (default 8)")
    p.add_argument("--top", default="10", help="how many designs to list, or 'all' (default 10)")
    p.add_argument("--time-limit", default="60", metavar="SECONDS", help="stop a longer search (default 60)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the search on Dask: a scheduler's address (tcp://host:8786), 'local' (a local cluster), or "
                        "'auto' (a local cluster only where the search is long enough to pay for starting one)")
    p.add_argument("--workers", help="processes of a local Dask cluster (default: the machine's cores)")
    p.add_argument("--efficiency", nargs="?", const="default", metavar="ETA",
                   help="also give each listed design's efficiency (its statics, driver driving driven): every mesh "
                        "ETA, or without ETA the train file's value where a mesh has one, else 0.98 per external and "
                        "0.99 per internal mesh; '(locks)' marks an efficiency of zero or below")
    p.add_argument("--rank", metavar="KEYS",
                   help="order of the designs: keys among error, efficiency (largest first), size, teeth (tooth sum), "
                        "separated by commas; the rest of error,size,teeth follow (default error,size,teeth). "
                        "Ranking by efficiency evaluates the train's efficiency law exactly at every design, with the "
                        "mesh efficiencies of --efficiency")
    p.add_argument("--min-contact-ratio", metavar="EPS",
                   help="leave out designs with a mesh whose transverse contact ratio is below EPS (each listed design's "
                        "gear geometry is worked out as symkin geometry does, with the shifts its centre distances need)")
    p.add_argument("--allow-undercut", action="store_true",
                   help="keep designs with a gear the rack undercuts even with the shifts chosen for it (left out by "
                        "default; a --zmin below the undercut-free minimum lists small gears only where a shift saves them)")
    p.add_argument("--latex", action="store_true", help="also print the derived conditions in LaTeX")
    add_quiet_flag(p)


def _ratio_range(text: str) -> tuple[Any, Any]:
    from symkin.parsing import parse_number

    parts = [x.strip() for x in text.split(",")]
    if len(parts) != 2:
        raise InputError(f"--ratio-range takes LO,HI (two numbers), got {text!r}")
    return parse_number(parts[0], what="--ratio-range LO"), parse_number(parts[1], what="--ratio-range HI")


def run_synthesize(args: Any) -> Any:
    """Run ``symkin synthesize`` with the parsed ``args``: tooth numbers of a train file for a target ratio; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin._util.jsonout import exact_json
    from symkin.parsing import parse_integer, parse_number
    from symkin.synthesis import synthesize

    if args.ratios is not None:
        return _transmission(args)
    if args.absolute:
        raise InputError("--absolute belongs to --ratios (a whole transmission)")
    if args.ratio is None and args.ratio_range is None:
        raise InputError("give --ratio R (with --tolerance), --ratio-range LO,HI or --ratios STATE=R,...")
    if args.ratio is not None and args.ratio_range is not None:
        raise InputError("give either --ratio or --ratio-range, not both")
    if args.state is None and (args.driver is None or args.driven is None):
        raise InputError("name --driver and --driven (and --fixed links), or a --state of the train file")
    fixed = [f.strip() for item in args.fixed for f in item.split(",")]
    if any(not f for f in fixed):
        raise InputError("--fixed names a link, e.g. --fixed C")
    planets = None if args.planets.strip().lower() == "file" else int(parse_integer(args.planets, what="--planets"))
    top = None if args.top.strip().lower() == "all" else int(parse_integer(args.top, what="--top"))
    mesh = "default"
    if args.efficiency is not None and args.efficiency != "default":
        mesh = parse_number(args.efficiency, what="--efficiency")
    eps_min, wanted, top = _geometry_limits(args, top)
    bar = Progress(enabled=not args.quiet)
    try:
        result = synthesize(
            args.train,
            ratio=None if args.ratio is None else parse_number(args.ratio, what="--ratio"),
            tolerance=parse_number(args.tolerance, what="--tolerance"),
            ratio_range=None if args.ratio_range is None else _ratio_range(args.ratio_range),
            driver=args.driver, driven=args.driven, fixed=fixed or None, state=args.state,
            planets=planets,
            zmin=None if args.zmin is None else int(parse_integer(args.zmin, what="--zmin")),
            zmax=int(parse_integer(args.zmax, what="--zmax")),
            pressure_angle=parse_number(args.pressure_angle, what="--pressure-angle"),
            addendum=parse_number(args.addendum, what="--addendum"),
            clearance=parse_number(args.clearance, what="--clearance"),
            shift=parse_number(args.shift, what="--shift"),
            ring_difference=int(parse_integer(args.ring_difference, what="--ring-difference")),
            top=top,
            scheduler=args.scheduler,
            workers=None if args.workers is None else int(parse_integer(args.workers, what="--workers")),
            time_limit=float(parse_number(args.time_limit, what="--time-limit")),
            progress=lambda done, total, found: bar.show(f"searching: {done}/{total} chunks, {found} designs"),
            rank=args.rank, mesh_efficiency=mesh,
        )
    finally:
        bar.close()
    data = result.to_json()
    geometry = [_design_geometry(d) for d in result.designs]
    examined = len(geometry)
    keep = _makeable(geometry, args.allow_undercut, eps_min)
    left_out = len(geometry) - len(keep)
    keep = keep[:wanted]
    result = dataclasses.replace(result, designs=tuple(result.designs[i] for i in keep))
    data["designs"] = [{**data["designs"][i], "geometry": _geometry_json(geometry[i])} for i in keep]
    geometry = [geometry[i] for i in keep]
    notes = _geometry_notes(result, geometry, (left_out, examined), eps_min, args.allow_undercut)
    data["notes"] = [*data.get("notes", []), *notes]
    checks = [d.check() for d in result.designs]
    etas = None  # a column of efficiencies that do not rank (ranked ones are in the table and each check)
    meshes = dict(result.mesh_efficiency)
    if args.efficiency is not None and "efficiency" not in result.rank:
        from symkin.statics.power import mesh_efficiencies
        from symkin.synthesis.result import locks

        etas = [_efficiency(d, mesh) for d in result.designs]
        meshes = mesh_efficiencies(result.problem.train, mesh)
        data["mesh_efficiencies"] = {m: exact_json(v) for m, v in meshes.items()}
    for i, (design, check) in enumerate(zip(data["designs"], checks)):
        design["check"] = check.to_json()
        if etas is not None:
            design["efficiency"] = exact_json(etas[i])
            design["locks"] = locks(etas[i])
    text = _text(result, checks, args.latex, etas, meshes, geometry)
    text += "".join(f"\nnote: {n}" for n in notes)
    return emit(text, data, 0 if all(c.passed for c in checks) else 1)


def _design_geometry(design: Any) -> dict[str, Any] | None:
    """A design's gear geometry with the shifts its centre distances need (symkin geometry --choose-shifts):
    the least contact ratio, the shifts, whether a gear is undercut, the problems; None without one
    (a train without a module in mm, a bevel train)."""
    return _train_geometry(design.train)


def _train_geometry(build: Any) -> dict[str, Any] | None:
    """:func:`_design_geometry` of the train ``build()`` gives."""
    from symkin.geometry import coaxial_shifts, train_geometry

    try:
        train = build()
        shifts = coaxial_shifts(train)
        geo = train_geometry(train, shifts=shifts)
    except SymkinError:
        return None
    if not geo.meshes:
        return None
    return {"shifts": {g: shifts[g] for g in geo.gears if g in shifts and shifts[g] != 0},
            "contact_ratio_min": min(float(m.pair.contact_ratio) for m in geo.meshes),
            "undercut": any(g.undercut for g in geo.gears.values()), "problems": geo.problems + list(shifts.notes)}


def _geometry_limits(args: Any, top: int | None) -> tuple[Any, int | None, int | None]:
    """--min-contact-ratio, the designs wanted (--top) and how many to ask the search for: designs the geometry
    may leave out (undercut, a low contact ratio) are made up for by asking for 4 times as many."""
    from symkin.parsing import parse_number

    eps_min = None if args.min_contact_ratio is None else parse_number(args.min_contact_ratio, what="--min-contact-ratio")
    if eps_min is not None and not eps_min > 0:
        raise InputError(f"--min-contact-ratio must be positive, got {args.min_contact_ratio}")
    filtering = eps_min is not None or (not args.allow_undercut and args.zmin is not None)
    return eps_min, top, (4 * top if filtering and top is not None else top)


def _makeable(geometry: list[Any], allow_undercut: bool, eps_min: Any) -> list[int]:
    """The indices of the designs the geometry keeps: none undercut (unless allowed), every contact ratio at least
    ``eps_min``; a design without geometry (no module, bevel gears) is kept."""
    return [i for i, g in enumerate(geometry) if g is None or (
        (allow_undercut or not g["undercut"]) and (eps_min is None or g["contact_ratio_min"] >= eps_min))]


def _geometry_line(g: dict[str, Any] | None) -> str | None:
    """A design's least contact ratio and shifts, as printed under it."""
    if g is None:
        return None
    return f"least contact ratio {g['contact_ratio_min']:.3f}" + ("; profile shifts " + ", ".join(
        f"{n} {float(x):+.4f}" for n, x in g["shifts"].items()) if g["shifts"] else "")


def _geometry_json(geometry: dict[str, Any] | None) -> dict[str, Any] | None:
    if geometry is None:
        return None
    return {**geometry, "shifts": {g: float(x) for g, x in geometry["shifts"].items()}}


def _geometry_notes(result: Any, geometry: list[Any], counts: tuple[int, int], eps_min: Any,
                    allow_undercut: bool) -> list[str]:
    from symkin.synthesis import undercut_minimum

    o = result.problem.options
    notes = []
    limit = undercut_minimum(o.pressure_angle, o.addendum)
    if o.zmin < limit:
        notes.append(f"gears of fewer than {limit} teeth are undercut unshifted (alpha = {o.pressure_angle} deg, h_a* = "
                     f"{o.addendum}); each design is given the shifts its centre distances allow that keep its gears "
                     "free of undercut" + ("" if allow_undercut else "; designs still undercut are left out "
                                           "(--allow-undercut keeps them)"))
    left_out, examined = counts
    if left_out:
        why = " or ".join(w for w, on in (("undercut", not allow_undercut),
                                            (f"a contact ratio below {eps_min}", eps_min is not None)) if on)
        notes.append(f"{left_out} of the best {examined} designs {'was' if left_out == 1 else 'were'} left out for {why} "
                     "(a larger --top or --zmin lists others)")
    flagged = [f"design {i}: {p}" for i, g in enumerate(geometry, 1) if g for p in g["problems"]]
    notes += flagged[:20]
    if len(flagged) > 20:
        notes.append(f"... and {len(flagged) - 20} more geometry problems (symkin geometry on a design's train lists them)")
    return notes


def _transmission(args: Any) -> Any:
    """symkin synthesize --ratios STATE=R,...: every state's ratio at once."""
    from symkin.parsing import parse_integer, parse_number
    from symkin.synthesis.transmission import synthesize_transmission
    from symkin.trains import load_train

    if args.ratio is not None or args.ratio_range is not None or args.state or args.driver or args.driven or args.fixed:
        raise InputError("--ratios names the states and their ratios: give no --ratio, --ratio-range, --state, "
                         "--driver, --driven or --fixed with it")
    if args.rank is not None or args.efficiency is not None:
        raise InputError("--ratios ranks by ratio error, steps and size: give no --rank or --efficiency with it")
    ratios = {}
    for item in args.ratios.split(","):
        state, sep, value = item.partition("=")
        if not sep or not state.strip():
            raise InputError(f"--ratios takes STATE=RATIO,... (first=4.696,second=3.130), got {item!r}")
        if state.strip() in ratios:
            raise InputError(f"--ratios names state {state.strip()} twice")
        ratios[state.strip()] = parse_number(value, what=f"--ratios {state.strip()}")
    train = load_train(args.train)
    for state in ratios:
        train.state(state)  # raises with the states' names
    top = None if args.top.strip().lower() == "all" else int(parse_integer(args.top, what="--top"))
    eps_min, wanted, top = _geometry_limits(args, top)
    result = synthesize_transmission(
        train, ratios, tolerance=parse_number(args.tolerance, what="--tolerance"), absolute=args.absolute,
        planets=None if args.planets.strip().lower() == "file" else int(parse_integer(args.planets, what="--planets")),
        zmin=None if args.zmin is None else int(parse_integer(args.zmin, what="--zmin")),
        zmax=int(parse_integer(args.zmax, what="--zmax")), top=top,
        time_limit=float(parse_number(args.time_limit, what="--time-limit")), scheduler=args.scheduler,
        workers=None if args.workers is None else int(parse_integer(args.workers, what="--workers")),
        pressure_angle=parse_number(args.pressure_angle, what="--pressure-angle"),
        addendum=parse_number(args.addendum, what="--addendum"), clearance=parse_number(args.clearance, what="--clearance"),
        shift=parse_number(args.shift, what="--shift"),
        ring_difference=int(parse_integer(args.ring_difference, what="--ring-difference")))
    if not result.designs:
        raise InputError(f"no design gives every state its ratio within the tolerance (kept after each state: "
                         f"{', '.join(f'{s} {n}' for s, n in zip(result.order, result.kept))}); widen the tolerance or "
                         "the limits")
    # the gear geometry of every design, as for one ratio: undercut left out unless allowed, --min-contact-ratio
    geometry = [_train_geometry(lambda d=d: result.train(d)) for d in result.designs]
    keep = _makeable(geometry, args.allow_undercut, eps_min)
    left_out = len(geometry) - len(keep)
    keep = keep[:wanted]
    examined = len(geometry)
    result = dataclasses.replace(result, designs=tuple(result.designs[i] for i in keep))
    geometry = [geometry[i] for i in keep]
    data = result.to_json()
    for d, g in zip(data["designs"], geometry):
        d["geometry"] = _geometry_json(g)
    notes = _geometry_notes(result, geometry, (left_out, examined), eps_min, args.allow_undercut)
    data["notes"] = notes
    text = result.text([_geometry_line(g) for g in geometry]) + "".join(f"\nnote: {n}" for n in notes)
    return emit(text, data)


def _efficiency(design: Any, mesh: Any) -> Any:
    """The design's efficiency from its statics, None where its train has none (a degenerate one)."""
    try:
        return design.efficiency(mesh)
    except SymkinError:
        return None


def _text(result: Any, checks: list[Any], latex: bool, etas: list[Any] | None = None,
          meshes: dict[str, Any] | None = None, geometry: list[Any] | None = None) -> str:
    from symkin._util.jsonout import float_text
    from symkin.synthesis.result import describe_designs, efficiency_text

    p = result.problem
    o = p.options
    counts = ", ".join(f"{n} x {k}" for n, k in p.counts)
    lines = [
        f"{p.train.name or 'train'}: {p.ratio.lhs} = {p.ratio.rhs}, target {result.target.text()}, planets {counts}, "
        f"{o.zmin} <= z <= {o.zmax}" + (f", profile shift up to {o.shift} m" if o.shift else ", meshes on their pitch circles"),
    ]
    lines += [f"note: {n}" for n in result.notes]
    lines.append("conditions derived from the model:")
    for c in result.conditions:
        lines.append(f"  {c}")
        if latex:
            lines.append(f"    {c.latex()}")
    ex = result.execution
    lines.append(f"search: {result.search}; {result.made} tuples made, {ex.get('chunks', 0)} chunks {ex.get('scheduler', '')}, "
                 f"{result.seconds:.2f} s in all")
    width = max(len(str(n)) for _, n in result.funnel)
    lines += [f"  {n:>{width}}  {name}" for name, n in result.funnel]
    lines.append(f"{result.message()}:")
    table = describe_designs(result.designs)
    for i, (row, check) in enumerate(zip(table, [None, *checks])):
        mark = "check" if check is None else ("ok" if check.passed else f"FAILED {check.problem}")
        if etas is not None:
            row += "  efficiency" if i == 0 else f"  {efficiency_text(etas[i - 1]):>10}"
        lines.append(f"  {row}  {mark}")
        g = None if geometry is None or i == 0 else _geometry_line(geometry[i - 1])
        if g is not None:
            lines.append(f"      {g}")
    lines.append("check: each train built with its teeth; ratio derived again, coaxiality and planet positions from "
                 "the model, the least gap between planet copies measured" +
                 ("; efficiency from each train's statics (basic-train method), not a ranking key" if etas else "") +
                 ("; efficiency ranked by the train's law, evaluated exactly, and derived again from each train's "
                  "statics (basic-train method)" if "efficiency" in result.rank else ""))
    if meshes:
        lines.append("mesh efficiencies: " + ", ".join(f"{m} {float_text(v) or v}" for m, v in meshes.items()))
    return "\n".join(lines)
