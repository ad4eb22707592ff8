"""Figures: particle trajectories, speed and acceleration curves, mechanism outlines.

Figures are built with matplotlib's object API (no pyplot state, no display needed).
A planet particle on the pitch circle traces an epicycloid (planet outside a fixed
gear) or a hypocycloid (inside a fixed ring); inside a ring twice its size, the Cardan
straight line.

    >>> from symkin import schemes
    >>> m = schemes.single_row_AI(radii=(1, 1, 3))
    >>> fig = trajectory_figure(m, {"4": 0, "H": 1}, [("2", (1, 0))], t_end=6.3)
    >>> len(fig.axes)
    1
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from symkin.errors import InputError
from symkin.model import LinkKind, Mechanism
from symkin.values import as_values, substitute
from symkin.viz import style
from symkin.viz.teeth import involute_outline, mesh_phases, rear_gears

__all__ = [
    "space_figure",
    "default_particles",
    "draw_pitch_circles",
    "draw_trajectories",
    "trajectory_figure",
    "label_plane",
    "kinematics_figure",
    "save",
    "FORMATS",
]

#: File suffixes :func:`save` writes: raster PNG and the vector formats PDF, SVG and EPS.
FORMATS = ("png", "pdf", "svg", "eps")
#: Where each gear's name is put on its pitch circle (degrees), gear by gear, so that the
#: names of concentric gears of nearly equal size (a two-row AA's 1 and 4) stand apart.
_LABEL_ANGLES = (40, 140, 220, 320, 90, 270, 180, 0)


def default_particles(mech: Mechanism) -> list[tuple[str, tuple[sp.Expr, sp.Expr]]]:
    """The particles shown when none are named: on the first planet, the point of its first
    rim's pitch circle farthest from the main axis at t = 0, and the point at half that
    radius (an epicycloid or hypocycloid, and a trochoid), relative to the planet's axis.

    >>> from symkin import schemes
    >>> default_particles(schemes.two_row("AI", radii=(20, 30, 20, 70)))
    [('23', (30, 0)), ('23', (15, 0))]
    """
    planets = [L for L in mech.moving_links if L.kind is LinkKind.PLANET and L.gears]
    if not planets:
        raise InputError("this mechanism has no planet; name the particles (--point LINK:a,b)")
    planet = planets[0]
    r = planet.gears[0].radius
    return [(planet.name, (r, sp.Integer(0))), (planet.name, (r / 2, sp.Integer(0)))]


def draw_pitch_circles(ax: Any, mech: Mechanism, values: Mapping[Any, Any] | None = None, *,
                       teeth: bool = False) -> None:
    """Pitch circles of every gear at t = 0 (planets at their initial position), thin grey,
    each named at its own angle; with ``teeth``, gears with a tooth number are drawn with
    involute teeth (:mod:`symkin.viz.teeth`) phased so that they mesh.

    >>> from matplotlib.figure import Figure
    >>> from symkin import schemes
    >>> ax = Figure().add_subplot()
    >>> draw_pitch_circles(ax, schemes.single_row_AI(teeth=(20, 30, 80), module=1), teeth=True)
    >>> sorted(t.get_text() for t in ax.texts)
    ['1', '2', '4']
    """
    named = as_values(values)
    phases = mesh_phases(mech, named) if teeth else {}
    rear = rear_gears(mech)  # a second row: dashed, without teeth, behind the first it overlaps
    n = 0
    for link in mech.links:
        centre = (0.0, 0.0)
        if link.axis == "radial":  # a bevel pinion's pitch circle stands across the plane: seen edge on
            _draw_pinion(ax, mech, link, named)
            continue
        if link.kind is LinkKind.PLANET:
            x, y = (float(substitute(sp.sympify(c), named)) for c in mech.axis_position(link.name))
            centre = (x, y)
        for gear in link.gears:
            r = float(substitute(gear.radius, named))
            if gear.name in rear:
                ax.add_patch(Circle(centre, r, fill=False, lw=0.7, ls=(0, (4, 2)), color="0.45"))
            elif gear.name in phases:
                gx, gy = involute_outline(r, int(sp.sympify(gear.teeth)), internal=gear.internal, phase=phases[gear.name])
                ax.plot(centre[0] + gx, centre[1] + gy, lw=0.5, color="0.45", ls="-")
                ax.add_patch(Circle(centre, r, fill=False, lw=0.4, ls=":", color="0.6"))
            else:
                ax.add_patch(Circle(centre, r, fill=False, lw=0.6, ls="--" if gear.internal else "-", color="0.6"))
            angle = np.radians(_LABEL_ANGLES[n % len(_LABEL_ANGLES)])
            n += 1
            out = r * (1.08 if gear.internal else 0.86)  # inside a gear, outside a ring: clear of its teeth
            ax.annotate(gear.name,
                        (centre[0] + out * np.cos(angle), centre[1] + out * np.sin(angle)), color="0.3",
                        fontsize=style.SMALL, ha="center", va="center", zorder=6,  # over the paths, on a white box
                        bbox={"boxstyle": "round,pad=0.15", "facecolor": "white", "edgecolor": "none", "alpha": 0.8})


def _draw_pinion(ax: Any, mech: Mechanism, link: Any, named: Mapping[str, Any]) -> None:
    """A bevel pinion seen from +z: its pitch circle edge on, a segment across its axis at
    the side gears' radius."""
    alpha = float(substitute(sp.sympify(mech.position_angle(link.name)), named))
    x0, y0 = (float(substitute(sp.sympify(c), named)) for c in mech.axis_position(link.carrier))
    for mesh in mech.meshes:
        geo = mech.mesh_geometry(mesh)
        if geo.kind != "bevel" or link.name not in (geo.link_a.name, geo.link_b.name):
            continue
        reach = float(substitute(geo.centre_distance, named))
        cx, cy = x0 + reach * np.cos(alpha), y0 + reach * np.sin(alpha)
        half = abs(float(substitute(geo.pitch_y, named)))
        dx, dy = -np.sin(alpha) * half, np.cos(alpha) * half
        ax.plot([cx - dx, cx + dx], [cy - dy, cy + dy], lw=0.8, color="0.6", ls="-")
        ax.plot([x0, cx], [y0, cy], lw=0.5, ls=":", color="0.6")
        gear = geo.gear_a if geo.link_a.name == link.name else geo.gear_b
        ax.annotate(gear.name, (cx + dx, cy + dy), color="0.3", fontsize=style.SMALL)


def draw_trajectories(
    ax: Any,
    motion: Any,
    particles: Iterable[tuple[str, Sequence[Any]]],
    t_end: float,
    *,
    relative_to: str = "frame",
    values: Mapping[Any, Any] | None = None,
    labels: Sequence[str] | None = None,
    samples: int = 1441,
) -> None:
    """Draw the path of each (link, point) particle from t = 0 to ``t_end`` (a dot at t = 0).

    >>> from matplotlib.figure import Figure
    >>> from symkin import schemes
    >>> ax = Figure().add_subplot()
    >>> motion = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1})
    >>> draw_trajectories(ax, motion, [("2", (1, 0))], 6.3)
    >>> len(ax.lines)
    2
    """
    for i, (link, point) in enumerate(particles):
        p = motion.particle(link, point, relative_to=relative_to)
        x, y = p.trajectory(t_end, samples=samples, values=values)[1:3]  # seen from +z for a path in space
        label = labels[i] if labels else f"link {link}, point {tuple(point)}"
        (line,) = ax.plot(x, y, lw=1.1, label=label)
        ax.plot(x[:1], y[:1], "o", ms=3, color=line.get_color(), ls="none")


def trajectory_figure(
    mech: Mechanism,
    inputs: Mapping[str, Any],
    particles: Sequence[tuple[str, Sequence[Any]]],
    t_end: float,
    *,
    relative_to: str = "frame",
    values: Mapping[Any, Any] | None = None,
    title: str | None = None,
    labels: Sequence[str] | None = None,
    teeth: bool = True,
    length: str = "m",
) -> Figure:
    """One axes: the gears (at t = 0, with teeth where tooth numbers are known) and particle
    paths of ``mech`` under ``inputs``; axes in ``length`` units (bare numbers are metres).

    >>> from symkin import schemes
    >>> m = schemes.single_row_AI(teeth=(20, 30, 80), module=1)
    >>> fig = trajectory_figure(m, {"4": 0, "H": 1}, [("2", (15, 0))], 6.3, length="mm")
    >>> fig.axes[0].get_xlabel()
    'x [mm]'
    """
    fig = style.new_figure(style.COLUMN, style.COLUMN + 0.9)
    ax = fig.add_subplot()
    style.style_axes(ax)
    draw_pitch_circles(ax, mech, values, teeth=teeth)
    draw_trajectories(ax, mech.motion(inputs), particles, t_end, relative_to=relative_to, values=values, labels=labels)
    label_plane(ax, length)
    ax.set_title(title or mech.name, fontsize=style.FONT)
    style.legend_outside(ax)
    return style.finish(fig)


def label_plane(ax: Any, length: str = "m") -> None:
    """Equal scales and the axes ``x``, ``y`` labelled in ``length`` units.

    >>> from matplotlib.figure import Figure
    >>> ax = Figure().add_subplot()
    >>> label_plane(ax, "mm")
    >>> ax.get_ylabel()
    'y [mm]'
    """
    ax.set_aspect("equal")
    ax.set_xlabel(style.label("x", length), fontsize=style.FONT)
    ax.set_ylabel(style.label("y", length), fontsize=style.FONT)


def space_figure(
    motion: Any,
    particles: Sequence[tuple[str, Sequence[Any]]],
    t_end: float,
    *,
    relative_to: str = "pole",
    values: Mapping[Any, Any] | None = None,
    labels: Sequence[str] | None = None,
    title: str | None = None,
    samples: int = 1441,
    length: str = "m",
) -> Figure:
    """Particle paths in space (the frame moving in space, or bevel pinions), in 3-D axes,
    with the path of the main axis point O when the frame moves.

    >>> from symkin import schemes, symbols as S
    >>> from symkin.particles import SpaceFrame
    >>> motion = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1}, frame=SpaceFrame(z=S.t))
    >>> fig = space_figure(motion, [("2", (1, 0))], 6.3)
    >>> fig.axes[0].name
    '3d'
    """
    fig = style.new_figure(style.PAGE * 0.75, style.PAGE * 0.75)
    ax = fig.add_subplot(projection="3d")
    style.style_axes(ax)
    space = getattr(motion, "space", None)
    if space is not None and not space.still:
        from symkin.numeric.sampling import on_grid, time_grid

        t = time_grid(t_end, samples=samples)
        ox, oy, oz = on_grid([space.x, space.y, space.z], t, values, what="sample the frame's motion")
        ax.plot(ox, oy, oz, lw=0.8, ls="--", color="0.5", label="main axis point O")
    for i, (link, point) in enumerate(particles):
        p = motion.particle(link, tuple(point) + ((0,) if len(point) == 2 else ()), relative_to=relative_to)
        _, x, y, z = p.trajectory(t_end, samples=samples, values=values)
        label = labels[i] if labels else f"link {link}, point {tuple(point)}"
        (line,) = ax.plot(x, y, z, lw=1.0, label=label)
        ax.plot(x[:1], y[:1], z[:1], "o", ms=3, color=line.get_color(), ls="none")
    for name, set_label in (("x", ax.set_xlabel), ("y", ax.set_ylabel), ("z", ax.set_zlabel)):
        set_label(style.label(name, length), fontsize=style.FONT, labelpad=8)
    ax.set_title(title or motion.mechanism.name or "paths in space", fontsize=style.FONT)
    style.legend_outside(ax)
    return style.finish(fig)


def kinematics_figure(
    motion: Any,
    particles: Sequence[tuple[str, Sequence[Any]]],
    t_end: float,
    *,
    relative_to: str = "frame",
    values: Mapping[Any, Any] | None = None,
    labels: Sequence[str] | None = None,
    title: str | None = None,
    samples: int = 721,
    length: str = "m",
    time: str = "s",
) -> Figure:
    """Speed and acceleration of each particle against time (two stacked axes), in
    ``length`` and ``time`` units (bare numbers are metres and seconds).

    The acceleration is ``a`` here and ``w`` in the 2009 paper (eq. 6).

    >>> from symkin import schemes
    >>> motion = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1})
    >>> fig = kinematics_figure(motion, [("2", (1, 0))], 6.3)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['speed |V| [m/s]', 'acceleration |a| [m/s$^2$]']
    """
    units = style.units_of(length, time)
    fig = style.new_figure(style.COLUMN * 1.5, style.COLUMN * 1.5)
    ax_v, ax_a = fig.subplots(2, 1, sharex=True)
    for ax in (ax_v, ax_a):
        style.style_axes(ax)
    for i, (link, point) in enumerate(particles):
        p = motion.particle(link, point, relative_to=relative_to)
        data = p.sample(t_end, samples=samples, values=values)
        label = labels[i] if labels else f"link {link}, point {tuple(point)}"
        ax_v.plot(data["t"], data["speed"], lw=1.1, label=label)
        ax_a.plot(data["t"], data["acceleration"], lw=1.1, label=label)
    ax_v.set_ylabel(style.label("speed |V|", units["speed"]), fontsize=style.FONT)
    ax_a.set_ylabel(style.label("acceleration |a|", units["acceleration"]), fontsize=style.FONT)
    ax_a.set_xlabel(style.label("time t", time), fontsize=style.FONT)
    for ax in (ax_v, ax_a):
        ax.set_ylim(bottom=0)
    style.legend_outside(ax_a)
    fig.suptitle(title or "speed and acceleration of the particles, eqs. (5), (6)", fontsize=style.FONT)
    return style.finish(fig)


def save(fig: Figure, path: Path, formats: Sequence[str] | None = None) -> list[Path]:
    """Save ``fig`` as ``path``; returns the files written.

    The format is the suffix of ``path`` when it is one of :data:`FORMATS` (``.pdf``, ``.svg``
    and ``.eps`` are vector files, ``.png`` is raster at 200 dpi); a path without one gets a PNG
    and a PDF, or each suffix in ``formats``.  A figure with a layout engine is laid out once,
    for the first file; the others keep that layout.  The files are written as matplotlib writes
    them (the command line writes under a temporary name and renames, so that a failure keeps an
    earlier file: :mod:`symkin._io.atomic`).

    >>> import tempfile
    >>> from matplotlib.figure import Figure
    >>> fig = Figure()
    >>> _ = fig.add_subplot().plot([0, 1])
    >>> with tempfile.TemporaryDirectory() as d:
    ...     [p.name for p in save(fig, Path(d) / "curve.svg")]
    ['curve.svg']
    """
    path = Path(path)
    if formats is None:
        formats = (path.suffix[1:].lower(),) if path.suffix[1:].lower() in FORMATS else ("png", "pdf")
    unknown = [f for f in formats if f.lower() not in FORMATS]
    if unknown:
        raise InputError(f"cannot save a figure as {', '.join(unknown)}: give one of {', '.join(FORMATS)}")
    targets = [path if path.suffix[1:].lower() == fmt.lower() else path.with_suffix("." + fmt.lower())
               for fmt in formats]
    # a figure laid out by matplotlib's constrained layout already fits its page: no second
    # draw to find a tight box (which doubles the time of saving)
    tight = None if fig.get_layout_engine() is not None else "tight"
    for k, target in enumerate(targets):
        kind = target.suffix[1:].lower()
        dpi = 200 if kind == "png" else 150
        if tight is None and kind in ("png", "pdf") and _savefig_defaults():
            # after the first file, its layout: the axes stay where it put them (a layout costs as much as a draw)
            with _layout_kept(fig) if k else contextlib.nullcontext():
                _print_once(fig, target, kind, dpi)
        else:
            extra: dict[str, Any] = {"pil_kwargs": dict(_PNG_OPTIONS)} if kind == "png" else {}
            fig.savefig(target, dpi=dpi, bbox_inches=tight, format=kind, **extra)
    return targets


#: zlib level 3 for PNGs: the same pixels as the default level 6 at about half the
#: compression time, in files about 3 % larger (line art compresses well either way).
_PNG_OPTIONS = {"compress_level": 3}


@contextlib.contextmanager
def _layout_kept(fig: Figure) -> Iterator[None]:
    """``fig`` drawn as it is laid out now: its layout engine set aside (for a placeholder
    that keeps its compatibility with colorbars), then restored."""
    engine = fig.get_layout_engine()
    fig.set_layout_engine("none")
    try:
        yield
    finally:
        fig.set_layout_engine(engine)


def _savefig_defaults() -> bool:
    """Whether the ``savefig.*`` settings :func:`_print_once` does not apply are matplotlib's
    defaults (a user's ``savefig.facecolor`` or ``transparent`` sends the figure through ``savefig``)."""
    import matplotlib as mpl

    return all(mpl.rcParams[k] == mpl.rcParamsDefault[k] for k in
               ("savefig.facecolor", "savefig.edgecolor", "savefig.transparent", "savefig.bbox",
                "savefig.orientation"))


def _print_once(fig: Figure, path: Path, fmt: str, dpi: float) -> None:
    """Write ``fig`` (which has a layout engine) as PNG or PDF with one layout and one draw.

    ``Figure.savefig`` draws a figure with a layout engine twice for each file: once with
    drawing switched off, to lay it out, and once to render it.  The format's own canvas
    lays the figure out in the draw that renders it, with the same renderer (hence the same
    text metrics), so the file is the same at half the drawing.  The PDF canvas would lay the
    page out with a renderer of its own, measuring (and parsing each math string) anew: it is
    given the one that draws the page.  The figure's canvas and dpi are restored afterwards.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.backends.backend_pdf import FigureCanvasPdf

    canvas, figure_dpi = fig.canvas, fig.dpi
    try:
        fig.dpi = dpi
        if fmt == "png":
            FigureCanvasAgg(fig).print_png(path, pil_kwargs=dict(_PNG_OPTIONS))
        else:
            pdf = FigureCanvasPdf(fig)
            draw = fig.draw

            def drawing(renderer: Any) -> None:
                pdf.get_renderer = lambda: renderer  # type: ignore[attr-defined]
                draw(renderer)

            fig.draw = drawing  # type: ignore[method-assign]
            try:
                pdf.print_pdf(path)
            finally:
                del fig.draw
    finally:
        fig.set_canvas(canvas)
        fig.dpi = figure_dpi
