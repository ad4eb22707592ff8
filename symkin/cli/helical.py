"""``symkin helical``: tooth numbers and helix angles for a stepped helical planet without axial load."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from symkin.cli.common import Progress, add_command, add_quiet_flag, emit, parse_integer, parse_number
from symkin.errors import InputError

if TYPE_CHECKING:
    from symkin.mechanisms.helical.balanced import HelicalRequest

#: Relative axial residual every listed design must meet in the independent force check.
FORCE_TOLERANCE = 1e-12


def register(sub: Any) -> None:
    """Add the ``helical`` command to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "helical",
        help="synthesise a two-row train whose helical stepped planet carries no axial force",
        description=(
            "List integer tooth numbers Z1..Z4 and the helix angles beta12, beta34 (unshifted meshes) for which "
            "the axial forces on the stepped planet cancel, the ratio i_1H^(4) = omega_1/omega_H (gear 4 fixed) is "
            "within the tolerance of the target, and the train is coaxial, assembles with k equally spaced "
            "satellites and leaves room between them.  Ranked by ratio error, then planet envelope diameter.  "
            "Every listed design is re-checked by an independent 3-D force computation (unit input torque).  "
            "Angles are in degrees, lengths in mm."
        ),
        run=run_helical,
    )
    p.add_argument("scheme", help="AI, AA or II (A external, I internal central gear; first letter gear 1)")
    p.add_argument("--ratio", required=True, help="target i_1H^(4), exact (25, 0.02, 1/50)")
    p.add_argument("--tolerance", default="0.01", help="relative ratio tolerance (default 0.01 = 1 %%)")
    p.add_argument("--satellites", "-k", required=True, help="number of equally spaced planets")
    p.add_argument("--mn12", required=True, help="normal module of mesh 1-2 (mm)")
    p.add_argument("--mn34", required=True, help="normal module of mesh 3-4 (mm)")
    p.add_argument("--beta-min", default="8", metavar="DEG", help="least helix angle, in degrees (default 8)")
    p.add_argument("--beta-max", default="30", metavar="DEG", help="largest helix angle, in degrees, below 45 (default 30)")
    p.add_argument("--zmin", default="17", help="least tooth number of every gear (default 17)")
    p.add_argument("--zmax", default="150", help="largest tooth number of every gear (default 150)")
    p.add_argument("--alpha-n", default="20", metavar="DEG", help="normal pressure angle, in degrees (default 20)")
    p.add_argument("--addendum", default="1", help="addendum coefficient h_a* for tip circles (default 1)")
    p.add_argument("--min-ring-difference", default="8",
                   help="least tooth difference of an internal gear and its rim (default 8)")
    p.add_argument("--top", default="20", help="how many designs to list, or 'all' (default 20)")
    add_quiet_flag(p)


def _request(args: Any) -> HelicalRequest:
    from symkin.mechanisms.helical.balanced import SCHEMES, HelicalRequest

    if args.scheme not in SCHEMES:
        raise InputError(f"unknown scheme {args.scheme!r}; choose one of {', '.join(SCHEMES)}")
    top = None if args.top.strip().lower() == "all" else parse_integer(args.top, what="--top")
    return HelicalRequest(
        scheme=args.scheme,
        ratio=parse_number(args.ratio, what="--ratio"),
        tolerance=parse_number(args.tolerance, what="--tolerance"),
        satellites=parse_integer(args.satellites, what="--satellites"),
        normal_modules=(parse_number(args.mn12, what="--mn12"), parse_number(args.mn34, what="--mn34")),
        beta_min_deg=parse_number(args.beta_min, what="--beta-min"),
        beta_max_deg=parse_number(args.beta_max, what="--beta-max"),
        teeth_min=parse_integer(args.zmin, what="--zmin"),
        teeth_max=parse_integer(args.zmax, what="--zmax"),
        alpha_n_deg=parse_number(args.alpha_n, what="--alpha-n"),
        addendum=parse_number(args.addendum, what="--addendum"),
        min_ring_difference=parse_integer(args.min_ring_difference, what="--min-ring-difference"),
        top=top,
    )


def run_helical(args: Any) -> Any:
    """Run ``symkin helical`` with the parsed ``args``: the synthesis of helical stepped-planet trains with balanced axial forces; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.mechanisms.helical.balanced import synthesize_helical
    from symkin.statics import planet_forces

    req = _request(args)
    bar = Progress(enabled=not args.quiet)
    try:
        result = synthesize_helical(req, progress=lambda done, total: bar.show(f"searching: Z2 {done}/{total}"))
    finally:
        bar.close()
    checks = []
    for d in result.designs:
        f = planet_forces(d.train, 1.0)
        passed = f.axial_residual <= FORCE_TOLERANCE and f.hand_mismatch == 0
        checks.append({"axial_residual": f.axial_residual, "ratio_from_statics": f.ratio, "passed": passed})
    data = result.to_json()
    for design, check in zip(data["designs"], checks):
        design["force_check"] = check
    data["seconds"] = round(result.seconds, 3)
    return emit(_text(result, checks), data, 0 if all(c["passed"] for c in checks) else 1)


def _text(result: Any, checks: list[dict[str, Any]]) -> str:
    req = result.request
    m12, m34 = req.normal_modules
    lines = [
        f"{req.scheme}: i_1H^(4) = {req.ratio} +- {float(req.tolerance) * 100:g} %, k = {req.satellites}, "
        f"m_n12 = {m12} mm, m_n34 = {m34} mm, beta in [{float(req.beta_min_deg):g}, {float(req.beta_max_deg):g}] deg, "
        f"Z in [{req.teeth_min}, {req.teeth_max}], unshifted meshes",
        f"tooth sets found ({result.seconds:.2f} s):",
    ]
    width = max(len(str(n)) for _, n in result.stages)
    lines += [f"  {n:>{width}}  {name}" for name, n in result.stages]
    if not result.designs:
        lines.append(f"no designs: {result.reason}")
        return "\n".join(lines)
    lines.append(f"{result.message()} (hands: R right, L left, gears 1-4):")
    header = ("#", "Z1", "Z2", "Z3", "Z4", "i_1H^(4)", "error %", "beta12", "beta34", "hands", "P", "Q",
              "a_w mm", "dw2/dw3", "env. mm", "axial check")
    rows: list[tuple[str, ...]] = [header]
    for n, (d, c) in enumerate(zip(result.designs, checks), 1):
        b12, b34 = d.betas_deg
        hands = "".join("R" if h > 0 else "L" for h in d.train.hands)
        ratio = str(d.ratio) if d.ratio.denominator == 1 else f"{float(d.ratio):.6g}"
        rows.append((
            str(n), *(str(z) for z in d.teeth), ratio, f"{float(d.relative_error) * 100:.4f}",
            f"{b12:.4f}" + ("*" if d.helix_free else ""), f"{b34:.4f}", hands, str(d.assembly[0]), str(d.assembly[1]),
            f"{d.centre_distance:.3f}", f"{d.train.working_diameter_ratio:.4f}", f"{d.envelope_diameter:.2f}",
            f"{c['axial_residual']:.1e} " + ("ok" if c["passed"] else "FAILED"),
        ))
    widths = [max(len(r[i]) for r in rows) for i in range(len(header))]
    for r in rows:
        lines.append("  ".join(cell.rjust(w) for cell, w in zip(r, widths)))
    if any(d.helix_free for d in result.designs):
        lines.append("* equal leads and centre distances at any common helix angle: set to beta-min")
    lines.append(f"axial check: |F_a2 + F_a3| / max|F_a| on the planet for a unit input torque, independent 3-D "
                 f"force computation (ok below {FORCE_TOLERANCE:g})")
    return "\n".join(lines)
