"""``symkin trajectory``, ``symkin curves`` and ``symkin animate``: look at a scheme's motion.

Particles are given as ``LINK:a,b``, coordinates relative to the link's axis at t = 0
(pitch radii are module * teeth / 2, the module 1 mm by default). Lengths are drawn in
millimetres, the module's unit (``--length-unit m`` for metres), speeds in mm/s.  Without ``--point`` the
planet's particles on the pitch circle of its first rim and at half that radius are
shown: an epicycloid or hypocycloid (the Cardan line for a planet in a ring twice its size).
"""

from __future__ import annotations

import math
from fractions import Fraction
from pathlib import Path
from typing import Any

from symkin.cli.common import (
    add_command,
    add_omega_argument,
    add_out_argument,
    add_quiet_flag,
    add_scheme_argument,
    add_teeth_argument,
    emit,
    figure_file,
    link_values,
    mechanism_of,
    parse_expression,
    parse_integer,
    parse_number,
    save_figure,
)
from symkin.errors import InputError

__all__ = ["register"]

MAX_FRAMES = 5000


def _common(p: Any, out_help: str) -> None:
    add_scheme_argument(p, train=True)
    add_teeth_argument(p, "20,30,20,70", required=False)
    add_omega_argument(p, "a known angular velocity LINK=VALUE in rad/s (repeat; as many as the scheme's degrees of "
                       "freedom, 0 fixes a link); VALUE may vary in time t (s), such as 1=10*t (then give --t-end)")
    p.add_argument("--point", action="append", default=[], metavar="LINK:a,b",
                   help="a particle of LINK at (a, b) from the link's axis at t = 0, or (a, b, c) with a height c "
                   "(repeat); default: planet particles on the pitch circle of its first rim and at half its radius")
    base = p.add_argument_group("a base moving in space (the main axis point O and the frame's turn, in t)")
    for key, what in (("x", "x of O"), ("y", "y of O"), ("z", "z of O"), ("yaw", "turn about z, rad"),
                      ("pitch", "then about the new y, rad"), ("roll", "then about the newest x, rad")):
        base.add_argument(f"--base-{key}", metavar="EXPR", help=f"{what}, an expression in t (default 0; a train "
                          "file's [base] table otherwise)")
    p.add_argument("--module", default=None, help="gear module of a scheme in mm, or with a unit (1.5mm, 0.06in): pitch "
                   "radius = module * teeth / 2 (default 1 mm)")
    p.add_argument("--length-unit", default="mm", metavar="UNIT",
                   help="the unit of lengths drawn and of --point: mm (default: the module's unit) or m")
    span = p.add_mutually_exclusive_group()
    span.add_argument("--turns", default=None, help="time span: turns of the carrier H (or of the fastest link), default 1, at most 10^6")
    span.add_argument("--t-end", default=None, help="time span in seconds, or with a unit (500ms, 2min)")
    add_out_argument(p, out_help)


def register(sub: Any) -> None:
    """Add the ``trajectory``, ``curves`` and ``animate`` commands to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(
        sub, "trajectory",
        help="plot the paths of chosen particles of a scheme (PNG, PDF, SVG or EPS)",
        description="Plot the paths of particles of a scheme's links over a time span, with the pitch circles "
        "at t = 0, eq. (4), axes in mm (the module's unit; --length-unit m for metres). Writes FILE (.png, or vector .pdf, .svg, .eps).",
        run=run_trajectory,
    )
    _common(p, "a figure, .png, .pdf, .svg or .eps")

    q = add_command(
        sub, "curves",
        help="plot speed and acceleration of chosen particles against time",
        description="Plot the speed |V| and the acceleration |a| (|w| in the 2009 paper) of particles of a "
        "scheme's links against time, eqs. (5) and (6), in mm/s and mm/s^2 (the module in mm; --length-unit m: m/s). "
        "Writes FILE (.png, or vector .pdf, .svg, .eps).",
        run=run_curves,
    )
    _common(q, "a figure, .png, .pdf, .svg or .eps")

    a = add_command(
        sub, "animate",
        help="animate a scheme: carrier, gears turning, particles tracing their paths (GIF, MP4 or HTML)",
        description="Animate a scheme over a time span: the carrier, every gear turning, and particles tracing "
        "their paths, gears with involute teeth. Writes FILE.gif (always available), FILE.mp4 (needs ffmpeg) "
        "or FILE.html (a self-contained page with playback controls); the file appears only when complete.",
        run=run_animate,
    )
    _common(a, "an animation, .gif, .html or .mp4 (needs ffmpeg)")
    a.add_argument("--fps", default="20", help="frames per second (default 20)")
    a.add_argument("--frames", default=None, help=f"number of frames, 2 to {MAX_FRAMES} (default: 4 s of animation per turn)")
    a.add_argument("--dpi", default="100", help="resolution in dots per inch of a 6 in frame (default 100: 600 px)")
    add_quiet_flag(a)


# --------------------------------------------------------------------------- parsing
def _point(text: str, mech: Any) -> tuple[str, tuple[Any, ...]]:
    if not isinstance(text, str) or ":" not in text:
        raise InputError(f"--point takes LINK:a,b (for example 23:-15,0), got {text!r}")
    link, _, coords = text.partition(":")
    link = link.strip()
    parts = [c.strip() for c in coords.split(",")]
    if len(parts) not in (2, 3) or not all(parts):
        raise InputError(f"--point {text!r} needs two coordinates after the colon (three with a height), as in 23:-15,0")
    values = tuple(parse_expression(c, what="--point coordinate") for c in parts)
    for v in values:
        if not v.is_number or not v.is_real:
            raise InputError(f"--point {text!r}: coordinates are real numbers, got {v}")
    mech.link(link)  # raises with the valid names
    return link, values


def _setup(args: Any) -> tuple[Any, Any, list, float, list[str], dict[str, Any], str]:
    known = link_values(args.omega, names=("t",))  # a number (rad/s), or an expression in t (s) such as 10*t
    if args.length_unit not in LENGTH_UNITS:
        raise InputError(f"--length-unit {args.length_unit!r}: choose one of {', '.join(LENGTH_UNITS)}")
    scale = LENGTH_UNITS[args.length_unit]  # millimetres -> the unit drawn
    module: Any = None if getattr(args, "train", None) is not None else 1
    if args.module is not None:
        from symkin.parsing import parse_real

        module = parse_real(args.module, what="--module", unit="mm", positive=True)
    mech, about, title = mechanism_of(args, module)
    if module is not None and scale != 1:  # a scheme: its module in the unit drawn
        mech, _, _ = mechanism_of(args, module * scale)
    elif scale != 1:  # a train file: its lengths are millimetres
        mech = _scaled(mech, scale)
    frame = _base(args, mech)
    motion = mech.motion(known, frame)
    from symkin.viz.figures import default_particles

    points = [_point(p, mech) for p in args.point] or default_particles(mech)
    if args.t_end is not None:
        from symkin.parsing import parse_real
        from symkin.values import sign_of

        t_end = parse_real(args.t_end, what="--t-end", unit="s")
        if sign_of(t_end, what="--t-end") != 1:  # on intervals: a 0 in disguise is not positive
            raise InputError(f"--t-end must be positive, got {args.t_end}")
        t_end = float(t_end)
    else:
        t_end = motion.turn_time(_turns(args))
    # the paths are drawn from a few thousand samples: a span of more turns than MAX_TURNS (of the fastest link),
    # or beyond MAX_TIME, would be noise between them (and overflows the reduction of the phases)
    fastest = max((_fastest(w, t_end) for w in mech.speeds(known).values()), default=0.0)
    turns = fastest * t_end / (2 * math.pi)
    if turns > MAX_TURNS or t_end > MAX_TIME:
        raise InputError(f"the time span 0 ... {t_end:.3g} s covers {turns:.3g} turns of the fastest link; at most "
                         f"{MAX_TURNS:.0e} turns and {MAX_TIME:.0e} s are drawn (a picture of more would be noise "
                         "between its samples): shorten --t-end or --turns")
    labels = [f"link {mech.link(name).name} at ({', '.join(_fmt(c) for c in xy)}) {args.length_unit} from its axis"
              for name, xy in points]
    return mech, motion, points, t_end, labels, about, title


def _fastest(speed: Any, t_end: float) -> float:
    """The largest |speed| over 0 ... t_end (a speed in t sampled at 257 times), in rad/s."""
    import numpy as np

    from symkin import symbols as S
    from symkin.numeric import compile as compile_law

    if not speed.has(S.t):
        return abs(float(speed)) if speed.is_number else 0.0
    f = compile_law(speed, [S.t], backend="numpy", on_pole="return")
    with np.errstate(all="ignore"):
        values = np.abs(np.asarray(f(np.linspace(0.0, t_end, 257)), dtype=float)) * np.ones(257)
    if not np.all(np.isfinite(values)):
        raise InputError(f"a speed {speed} is not finite on 0 ... {t_end:.3g} s; give --omega a speed finite over the span")
    return float(values.max())


def _base(args: Any, mech: Any) -> Any:
    """The frame's motion in space from --base-* (over a train file's [base] table), or None."""
    given = {k: getattr(args, f"base_{k}") for k in ("x", "y", "z", "yaw", "pitch", "roll")}
    train_base = getattr(mech, "base", None)
    if all(v is None for v in given.values()):
        return train_base
    from symkin.particles import SpaceFrame

    values = {k: parse_expression(v, names=("t",), what=f"--base-{k}") for k, v in given.items() if v is not None}
    if train_base is not None:
        raise InputError("the train file gives its base's motion ([base]); change it there, or leave out --base-*")
    return SpaceFrame.euler(values.get("x", 0), values.get("y", 0), values.get("z", 0), yaw=values.get("yaw", 0),
                            pitch=values.get("pitch", 0), roll=values.get("roll", 0))


def _in_space(motion: Any, points: list) -> bool:
    """Whether the paths leave the plane: the base moves in space, or a point is on a bevel pinion."""
    return motion.space is not None or any(motion.mechanism.link(name).axis == "radial" for name, _ in points)


def _turns(args: Any) -> float:
    if args.turns is None:
        return 1.0
    turns = parse_number(args.turns, what="--turns")
    if turns <= 0:
        raise InputError(f"--turns must be positive, got {args.turns}")
    if turns > MAX_TURNS:  # (the paths are drawn from a few thousand samples: fewer than one a turn beyond)
        raise InputError(f"--turns is at most {MAX_TURNS:.0e}, got {args.turns}; a picture of more turns would be "
                         "noise between its samples")
    return float(turns)


#: The units --length-unit takes, as factors from millimetres (a module is in millimetres, ISO 54).
LENGTH_UNITS = {"mm": Fraction(1), "m": Fraction(1, 1000)}


def _scaled(mech: Any, scale: Any) -> Any:
    """``mech`` with every length times ``scale`` (pitch radii, modules, arms, centre distances)."""
    from dataclasses import replace

    def times(v: Any) -> Any:
        return None if v is None else v * scale

    links = tuple(replace(L, gears=tuple(replace(g, radius=g.radius * scale, module=times(g.module)) for g in L.gears),
                          arm=L.arm if L.arm is None or L.arm == 0 else L.arm * scale) for L in mech.links)
    meshes = tuple(replace(m, centre_distance=times(m.centre_distance)) for m in mech.meshes)
    return replace(mech, links=links, meshes=meshes)


#: The most turns (of the fastest link) and the longest time span trajectory, curves and animate draw.
MAX_TURNS = 10**6
MAX_TIME = 1e12


def _fmt(v: Any) -> str:
    return f"{float(v):g}"


def _report(args: Any, kind: str, out: Path, mech: Any, points: list, t_end: float, about: dict[str, Any], title: str,
            extra: dict | None = None) -> Any:
    data = {
        "command": kind,
        **about,
        "file": str(out),
        "t_end": t_end,
        "units": {"t_end": "s", "length": args.length_unit, "speed": f"{args.length_unit}/s"},
        "particles": [{"link": mech.link(name).name, **{k: float(c) for k, c in zip("abc", xy)}} for name, xy in points],
        **(extra or {}),
    }
    return emit(f"{kind} of {title} over t = 0 ... {t_end:.4g} s written to {out}", data)


# --------------------------------------------------------------------------- commands
def run_trajectory(args: Any) -> Any:
    """Run ``symkin trajectory`` with the parsed ``args``: writes the particles' paths to ``--out``; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.viz import style
    from symkin.viz.figures import draw_pitch_circles, draw_trajectories, label_plane

    out = figure_file(args.out)
    mech, motion, points, t_end, labels, about, title = _setup(args)
    if _in_space(motion, points):
        from symkin.viz.figures import space_figure

        fig = space_figure(motion, points, t_end, relative_to="pole", labels=labels, length=args.length_unit,
                           title=f"{title}: particle paths in space, t = 0 ... {t_end:.3g} s")
        save_figure(fig, out)
        return _report(args, "trajectory", out, mech, points, t_end, about, title)
    fig = style.new_figure(style.COLUMN, style.COLUMN + 0.9)
    ax = fig.add_subplot()
    style.style_axes(ax)
    draw_pitch_circles(ax, mech, teeth=True)
    draw_trajectories(ax, motion, points, t_end, relative_to="pole", labels=labels)
    label_plane(ax, args.length_unit)
    ax.set_title(f"{title}: particle paths,\nt = 0 ... {t_end:.3g} s", fontsize=style.FONT)
    style.legend_outside(ax)
    save_figure(style.finish(fig), out)
    return _report(args, "trajectory", out, mech, points, t_end, about, title)


def run_curves(args: Any) -> Any:
    """Run ``symkin curves`` with the parsed ``args``: writes the particles' speed and acceleration against time to ``--out``; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.viz.figures import kinematics_figure

    out = figure_file(args.out)
    mech, motion, points, t_end, labels, about, title = _setup(args)
    fig = kinematics_figure(motion, points, t_end, relative_to="pole", labels=labels, length=args.length_unit,
                            title=f"{title}: speed and acceleration, eqs. (5), (6)")
    save_figure(fig, out)
    return _report(args, "curves", out, mech, points, t_end, about, title)


def run_animate(args: Any) -> Any:
    """Run ``symkin animate`` with the parsed ``args``: writes the mechanism's animation (GIF, or MP4 with ffmpeg) to ``--out``; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.viz.animation import MAX_DPI, MAX_FPS, WRITERS, Frames, animate

    out = Path(args.out)
    if out.suffix.lower() not in WRITERS:
        raise InputError(f"--out {args.out}: give a file ending in {' or '.join(WRITERS)}")
    fps = int(parse_integer(args.fps, what="--fps", minimum=1, maximum=MAX_FPS))
    dpi = int(parse_integer(args.dpi, what="--dpi", minimum=10, maximum=MAX_DPI))
    frames = int(parse_integer(args.frames, what="--frames", minimum=2, maximum=MAX_FRAMES)) if args.frames is not None else None
    mech, motion, points, t_end, labels, about, title = _setup(args)
    if motion.space is not None:
        from symkin.errors import UnsupportedError

        raise UnsupportedError("animate draws the mechanism's plane; for a base moving in space use trajectory, "
                               "which draws the paths in 3-D")
    if frames is None:
        turns = _turns(args) if args.t_end is None else 1.0
        frames = max(2, min(2000, round(4 * fps * turns)))
    sampled = Frames.build(motion, points, t_end=t_end, frames=frames, labels=labels, length=args.length_unit,
                           title=title)
    from symkin._io.atomic import replacing
    from symkin._io.progress import Progress

    bar = Progress(frames, enabled=not args.quiet)
    try:
        with replacing(out) as (tmp,):  # (its checks of out first: then the frames are drawn)
            animate(sampled, tmp, fps=fps, dpi=dpi, progress=lambda done, total: bar.step(f"drawing {out.name}"))
    finally:
        bar.close()
    return _report(args, "animation", out, mech, points, t_end, about, title, {"frames": frames, "fps": fps})
