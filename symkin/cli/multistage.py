"""``symkin stages`` and ``symkin split``: feasible single-row AI stages of a ring, and the
ratio split of least lost motion over a common-ring train (continuous and discrete)."""

from __future__ import annotations

from typing import Any

from symkin.cli.common import (
    Progress,
    add_command,
    add_quiet_flag,
    emit,
    exact_json,
    figure_file,
    parse_expression,
    parse_integer,
    parse_number,
    save_figure,
)
from symkin.errors import InputError

#: More stages than this take long to derive symbolically (benchmarks/notes/cli.md).
MAX_STAGES = 8


def register(sub: Any) -> None:
    """Add the ``stages`` and ``split`` commands to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "stages",
        help="every feasible single-row AI stage for a ring (exact ratios)",
        description="Enumerate every single-row AI stage (sun, planets, fixed ring) for a ring of --ring teeth: "
        "coaxiality z_ring = z_sun + 2 z_planet, assembly (z_sun + z_ring)/k whole, neighbour condition "
        "(z_sun + z_planet) sin(pi/k) > z_planet + 2 h_a*, and zmin <= z <= zmax for every gear.",
        run=run_stages,
    )
    _stage_arguments(p, required=True)

    q = add_command(
        sub, "split",
        help="split a total ratio over common-ring stages for the least lost motion",
        description="Minimise the lost motion carried to the output carrier over the ratio split of a "
        "common-ring train of single-row AI stages. Without --ring: the continuous optimum (each u_i in "
        "[umin, umax], product fixed) with its active bounds and multipliers. With --ring: also the best discrete "
        "designs, every stage from the ring's feasible tooth sets, the total within --tolerance, ranked by the "
        "objective (or the nearest designs when none meets it).",
        run=run_split,
    )
    q.add_argument("--total", required=True, help="total ratio U, e.g. 5000")
    q.add_argument("--stages", required=True, help=f"number of stages n (1 to {MAX_STAGES})")
    q.add_argument("--umin", help="lower bound of every stage ratio (default: the smallest feasible stage with --ring)")
    q.add_argument("--umax", help="upper bound of every stage ratio (default: the largest feasible stage with --ring)")
    q.add_argument("--model", metavar="EXPR", help="Phi/d of a stage as an expression in u, e.g. 'A + B*u' (the linear model)")
    q.add_argument("--backlash-line", metavar="C0,C1",
                   help="instead of --model: each mesh's backlash j = C0 + C1 a_w (needs --module and --ring)")
    q.add_argument("--module", help="gear module for --backlash-line, in the length unit of a_w")
    _stage_arguments(q, required=False)
    q.add_argument("--tolerance", default="0.01", help="relative tolerance on the total ratio (default 0.01 = 1%%)")
    q.add_argument("--top", default="10", help="how many discrete designs to list (default 10)")
    q.add_argument("--all-orders", action="store_true", help="list every stage order, not only the best order of each stage set")
    q.add_argument("--plot", metavar="FILE",
                   help="also write a figure of the objective against the split to FILE; .png or .pdf, the suffix "
                   "chooses the format (the result itself is printed)")
    add_quiet_flag(q)


def _stage_arguments(p: Any, required: bool) -> None:
    p.add_argument("--ring", required=required, help="tooth number of the common fixed ring")
    p.add_argument("--satellites", default="3", help="planets per stage k (default 3)")
    p.add_argument("--zmin", default="1", help="smallest tooth number of any gear (default 1)")
    p.add_argument("--zmax", help="largest tooth number of any gear (default: the ring)")
    p.add_argument("--ha", default="1", help="tip-height coefficient h_a* of the neighbour condition (default 1)")


def _stage_set(args: Any):
    from symkin.mechanisms.multistage.stages import enumerate_stages

    ring = parse_integer(args.ring, what="--ring")
    k = parse_integer(args.satellites, what="--satellites")
    if k < 1:
        raise InputError(f"--satellites must be at least 1, got {k}")
    if ring < 1:
        raise InputError(f"--ring must be a positive tooth number, got {ring}")
    zmin = parse_integer(args.zmin, what="--zmin")
    zmax = parse_integer(args.zmax, what="--zmax") if args.zmax is not None else None
    if zmin < 1 or (zmax is not None and zmax < 1):
        raise InputError("--zmin and --zmax must be positive tooth numbers")
    ha = parse_number(args.ha, what="--ha")
    return enumerate_stages(int(ring), int(k), zmin=int(zmin), zmax=None if zmax is None else int(zmax), ha=ha)


def _stage_table(found: Any) -> str:
    head = (
        f"single-row AI stages, ring {found.ring}, {found.satellites} satellite{'s' * (found.satellites != 1)}, "
        f"{found.zmin} <= z <= {found.zmax}, h_a* = {found.ha}: {len(found)} feasible, "
        f"u from {found[0].ratio} to {found[-1].ratio}"
    )
    rows = [("#", "z_sun", "z_planet", "z_ring", "u exact", "u", "a_w/m")]
    for i, s in enumerate(found, 1):
        rows.append((str(i), str(s.sun), str(s.planet), str(s.ring), str(s.ratio), f"{float(s.ratio):.6g}", str(s.centre_distance)))
    widths = [max(len(r[c]) for r in rows) for c in range(len(rows[0]))]
    lines = [head] + ["  " + "  ".join(cell.rjust(w) for cell, w in zip(r, widths)) for r in rows]
    rej = found.rejected
    lines.append(
        "candidate suns rejected (first failing condition): "
        + ", ".join(f"{k} {v}" for k, v in rej.items())
    )
    return "\n".join(lines)


def run_stages(args: Any) -> Any:
    """Run ``symkin stages`` with the parsed ``args``: every feasible single-row AI stage of a ring; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    found = _stage_set(args)
    return emit(_stage_table(found), found.to_json())


def _model(args: Any):
    from symkin.mechanisms.multistage.lostmotion import StageErrorModel, U

    if args.model and args.backlash_line:
        raise InputError("give either --model or --backlash-line, not both")
    if args.model:
        expr = parse_expression(args.model, symbols={"u": U}, what="the stage error model Phi/d")
        return StageErrorModel(expr, f"Phi/d = {expr}")
    if args.backlash_line:
        if args.module is None or args.ring is None:
            missing = " and ".join(o for o, v in (("--module", args.module), ("--ring", args.ring)) if v is None)
            raise InputError(f"--backlash-line needs {missing} too, to turn each mesh's backlash into Phi/d(u)")
        parts = [p.strip() for p in args.backlash_line.split(",")]
        if len(parts) != 2:
            raise InputError(f"--backlash-line takes C0,C1 (j = C0 + C1 a_w), got {args.backlash_line!r}")
        c0, c1 = (parse_number(p, what="--backlash-line") for p in parts)
        return StageErrorModel.from_backlash_line(c0, c1, module=parse_number(args.module, what="--module"),
                                                  ring=int(parse_integer(args.ring, what="--ring")))
    raise InputError("give the stage error model: --model 'A + B*u' (Phi/d as a function of the stage ratio u) "
                     "or --backlash-line C0,C1 with --module and --ring")


def run_split(args: Any) -> Any:
    """Run ``symkin split`` with the parsed ``args``: the split of a total ratio over a common-ring train for the least lost motion; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.mechanisms.multistage.split import (
        SplitProblem,
        best_designs,
        solve_continuous,
    )

    n = parse_integer(args.stages, what="--stages")
    if not 1 <= n <= MAX_STAGES:
        raise InputError(
            f"--stages must be between 1 and {MAX_STAGES}, got {n}; longer trains take too long to derive symbolically"
        )
    n = int(n)
    total = parse_number(args.total, what="--total")
    model = _model(args)
    found = _stage_set(args) if args.ring is not None else None
    if (args.umin is None or args.umax is None) and found is None:
        raise InputError("give --umin and --umax, or --ring to take the bounds from the feasible stages")
    if args.umin is not None:
        umin = parse_number(args.umin, what="--umin")
    else:
        assert found is not None  # checked just above
        umin = found[0].ratio
    if args.umax is not None:
        umax = parse_number(args.umax, what="--umax")
    else:
        assert found is not None  # checked just above
        umax = found[-1].ratio
    tolerance = parse_number(args.tolerance, what="--tolerance")
    top = parse_integer(args.top, what="--top")
    plot = figure_file(args.plot, "--plot") if args.plot else None
    problem = SplitProblem.build(total, n, lower=umin, upper=umax, model=model)
    best = solve_continuous(problem)
    discrete = None
    if found is not None:
        progress = Progress(enabled=not args.quiet)
        try:
            discrete = best_designs(total, found, n, model=model, tolerance=tolerance, top=int(top), lower=umin,
                                    upper=umax, distinct=not args.all_orders,
                                    progress=lambda done, nodes: progress.show(f"searching designs: {done:4.0%} ({nodes} nodes)"))
        finally:
            progress.close()
    plots: list[str] = []
    if plot is not None:
        from symkin.viz.split import split_figure

        plots = [str(p) for p in save_figure(split_figure(best, discrete), plot)]
    data = {
        "total": exact_json(problem.total),
        "stages": n,
        "umin": exact_json(umin),
        "umax": exact_json(umax),
        "model": str(model.expr),
        "continuous": best.to_json(),
        "discrete": discrete.to_json() if discrete is not None else None,
        "stage_set": {"ring": found.ring, "satellites": found.satellites, "count": len(found)} if found is not None else None,
        "plot": plots,
    }
    return emit(_split_text(problem, best, discrete, found, plots), data)


def _split_text(problem: Any, best: Any, discrete: Any, found: Any, plots: list[str]) -> str:
    exact = f" = ({', '.join(map(str, best.exact_ratios))})" if best.exact_ratios else ""
    lines = [
        f"total ratio {problem.total} over {problem.stages} stages, {problem.lower[0]} <= u <= {problem.upper[0]}, "
        f"Phi/d = {problem.models[0].expr}",
        f"continuous optimum: u = ({', '.join(f'{u:.6g}' for u in best.ratios)}){exact}, objective {best.objective:.6g}"
        + (f" (exact {best.exact_objective})" if best.exact_objective is not None else ""),
    ]
    lines += ["  " + s for s in best.explain()]
    if discrete is not None:
        lines.append(
            f"discrete designs from {len(found)} stages of ring {found.ring} ({found.satellites} satellites), "
            f"{discrete.message()}"
        )
        rows = [("rank", "teeth sun/planet, input stage first", "ratios", "total", "deviation", "objective")]
        for i, d in enumerate(discrete.designs, 1):
            rows.append((
                str(i),
                " ".join(f"{s.sun}/{s.planet}" for s in d.stages),
                " ".join(str(r) for r in d.ratios),
                str(d.total) if d.total.is_Integer else f"{float(d.total):.6g}",
                f"{float(d.deviation):+.3%}",
                f"{float(d.objective):.6f}",
            ))
        widths = [max(len(r[c]) for r in rows) for c in range(len(rows[0]))]
        lines += ["  " + "  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip() for r in rows]
        lines.append(f"  ({discrete.nodes} search nodes)")
    if plots:
        lines.append("plot written to " + ", ".join(plots))
    return "\n".join(lines)
