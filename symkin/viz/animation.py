"""Animation of a mechanism: carrier, gears turning, particles tracing their paths.

Everything drawn comes from the derived laws: each link's axis is a particle of its
carrier (eq. 4) and its orientation is read from a second particle of the link, so a
moving frame (a drill head on a manipulator) animates too.  Frames are drawn with
matplotlib's object API, gears with involute teeth (:mod:`symkin.viz.teeth`) where
their tooth numbers are known, and written as GIF (Pillow, always available), MP4 (needs
ffmpeg) or a self-contained HTML page with playback controls (:meth:`Frames.html`,
matplotlib's ``to_jshtml``); the file is written under a temporary name and renamed when
complete.

    >>> from symkin import schemes
    >>> from symkin.viz.animation import Frames
    >>> mech = schemes.single_row_AI(radii=(1, 1, 3))
    >>> frames = Frames.build(mech.motion({"4": 0, "H": 1}), [("2", (1, 0))], t_end=6.3, frames=4)
    >>> frames.particle_xy.shape   # particles, frames, (x, y)
    (1, 4, 2)
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from symkin.errors import InputError, ToolError
from symkin.model import FRAME, LinkKind
from symkin.numeric.sampling import on_grid, time_grid
from symkin.values import as_values, substitute
from symkin.viz import style
from symkin.viz.teeth import involute_outline, mesh_phases, rear_gears

__all__ = ["Frames", "draw_frame", "frame_figure", "animate", "WRITERS", "ffmpeg_available"]

#: File suffix -> matplotlib writer name.
WRITERS = {".gif": "pillow", ".mp4": "ffmpeg", ".html": "jshtml"}
#: Largest frame rate and resolution :func:`animate` accepts.
MAX_FPS, MAX_DPI = 1000, 1000

# links in the Okabe-Ito colours (told apart with any colour vision), paths in black and vermilion
_COLOURS = (style.PALETTE[0], style.PALETTE[2], style.PALETTE[4], style.PALETTE[3], style.PALETTE[5], "#7f7f7f")
_PATH_COLOURS = ("#000000", style.PALETTE[1], style.PALETTE[3], style.PALETTE[0])


def ffmpeg_available() -> bool:
    """Whether matplotlib can write MP4 (an ffmpeg executable is installed)."""
    from matplotlib import animation

    return bool(animation.writers.is_available("ffmpeg"))


@dataclass(frozen=True)
class Frames:
    """Numeric samples of a mechanism's motion, ready to draw.

    Attributes
    ----------
    t : array (frames,)
    links : tuple of (link name, kind, gears as (name, radius, internal), carrier name)
        Every link drawn: the frame when it holds gears (a fixed ring), carriers, gears.
    axis_xy : array (links, frames, 2)
        Where each link's axis is.
    angle : array (links, frames)
        Each link's orientation (0 at t = 0 for a still frame).
    main_xy : array (frames, 2)
        The main axis (moves only with the frame).
    particle_xy : array (particles, frames, 2)
    labels : tuple of str
    title : str
    teeth : dict
        Gear name -> (tooth number, angle of a tooth centre at t = 0): the gears drawn with
        involute teeth, phased so that they mesh (:func:`symkin.viz.teeth.mesh_phases`).
    length : str
        The unit of the coordinates, for the axis labels (bare numbers are metres).
    rear : frozenset of str
        The gears of a second row (:func:`symkin.viz.teeth.rear_gears`): drawn dashed, without
        teeth or fill, so that they stand apart from the front row they overlap.
    """

    t: np.ndarray
    links: tuple[tuple[str, str, tuple[tuple[str, float, bool], ...], str | None], ...]
    axis_xy: np.ndarray
    angle: np.ndarray
    main_xy: np.ndarray
    particle_xy: np.ndarray
    labels: tuple[str, ...]
    title: str
    teeth: Mapping[str, tuple[int, float]] = field(default_factory=dict)
    length: str = "m"
    rear: frozenset[str] = frozenset()

    @classmethod
    def build(
        cls,
        motion: Any,
        particles: Sequence[tuple[str, Sequence[Any]]] = (),
        *,
        t_end: float,
        frames: int = 120,
        relative_to: str = "pole",
        values: Mapping[Any, Any] | None = None,
        labels: Sequence[str] | None = None,
        title: str | None = None,
        teeth: bool = True,
        length: str = "m",
    ) -> Frames:
        """Sample ``motion`` at ``frames`` equal steps of [0, t_end].

        ``particles`` are (link, (a, b)) pairs, by default relative to the link's axis at
        t = 0 (``relative_to="pole"``); ``values`` gives numbers for every symbol but t.
        With ``teeth``, gears with tooth numbers are drawn with involute teeth; ``length``
        is the unit of the axes.
        """
        t = time_grid(t_end, samples=frames)
        subs = as_values(values)
        mech = motion.mechanism
        exprs: list[sp.Expr] = []
        origin = motion.particle(FRAME, (0, 0), relative_to="pole")
        exprs += list(origin.position)
        links = []
        for link in mech.links:
            if link.axis == "radial":  # a bevel pinion spins across the plane: not drawn as a circle
                continue
            gears = tuple((g.name, _number(g.radius, subs, f"pitch radius of gear {g.name}"), g.internal) for g in link.gears)
            if not gears and (link.kind is LinkKind.FRAME or not _carries(mech, link.name)):
                continue
            axis = motion.particle(link.name, (0, 0), relative_to="pole")
            marker = motion.particle(link.name, (1, 0), relative_to="pole")
            exprs += list(axis.position) + list(marker.position)
            links.append((link.name, link.kind.value, gears, link.carrier))
        for link, point in particles:  # seen from +z: a path in space is drawn by its x and y
            exprs += list(motion.particle(link, point, relative_to=relative_to).position)[:2]
        columns = np.array(on_grid(exprs, t, subs, what="animate the mechanism"))
        main_xy = columns[0:2].T
        n = len(links)
        block = columns[2 : 2 + 4 * n].reshape(n, 4, frames)
        axis_xy = np.stack([block[:, 0], block[:, 1]], axis=-1)
        angle = np.unwrap(np.arctan2(block[:, 3] - block[:, 1], block[:, 2] - block[:, 0]), axis=-1)
        rest = columns[2 + 4 * n :].reshape(len(particles), 2, frames)
        particle_xy = np.stack([rest[:, 0], rest[:, 1]], axis=-1)
        links, axis_xy, angle = _copies(mech, links, axis_xy, angle, main_xy)
        names = tuple(labels) if labels else tuple(f"link {name}, point {tuple(p)}" for name, p in particles)
        phases = mesh_phases(mech, subs) if teeth else {}
        toothed = {name: (int(mech.gear(name).teeth), phase) for name, phase in phases.items()}
        return cls(t, tuple(links), axis_xy, angle, main_xy, particle_xy, names, title or mech.name or "mechanism",
                   toothed, length, rear_gears(mech))

    def _repr_html_(self) -> str:
        """In Jupyter, frames show as the animation with its playback controls (:meth:`html`)."""
        return self.html(dpi=60, size=5.0)

    def html(self, *, fps: int = 20, dpi: int = 80, size: float = 6.0) -> str:
        """The animation as a self-contained HTML page with playback controls (matplotlib's
        ``to_jshtml``, frames embedded as PNG), to open in a browser or show in Jupyter.

        >>> from symkin import schemes
        >>> frames = Frames.build(schemes.single_row_AI(teeth=(20, 30, 80), module=1).motion({"4": 0, "H": 1}),
        ...                       [("2", (15, 0))], t_end=6.3, frames=3)
        >>> page = frames.html(dpi=20)
        >>> page.startswith("<!DOCTYPE html>"), "play_animation" in page, page.count("data:image/png;base64")
        (True, True, 3)
        """
        fig, anim = _animation(self, size)
        try:
            fig.set_dpi(dpi)
            body = anim.to_jshtml(fps=fps, embed_frames=True, default_mode="loop")
        finally:
            anim._draw_was_started = True  # no "deleted without rendering" warning (a private attribute)
        return ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + _html_escape(self.title)
                + "</title></head><body>\n" + body + "\n</body></html>\n")

    def limits(self) -> tuple[float, float, float, float]:
        """Axis limits that hold every gear and path over the whole motion."""
        pts = [self.main_xy]
        for i, (_, _, gears, _) in enumerate(self.links):
            reach = max((r for _, r, _ in gears), default=0.0) * (1.15 if any(g[2] for g in gears) else 1.0)
            c = self.axis_xy[i]
            pts += [c + [reach, reach], c - [reach, reach]]
        pts += [p for p in self.particle_xy]
        allpts = np.concatenate(pts)
        lo, hi = allpts.min(axis=0), allpts.max(axis=0)
        pad = 0.06 * max(hi - lo) + 1e-9
        cx, cy = (lo + hi) / 2
        half = max(hi - lo) / 2 + pad
        return cx - half, cx + half, cy - half, cy + half


def _copies(mech: Any, links: list, axis_xy: np.ndarray, angle: np.ndarray, main_xy: np.ndarray) -> tuple[list, np.ndarray, np.ndarray]:
    """The other planets of each kind (``count`` equally spaced): the drawn planet turned
    about the main axis by 2 pi j / count, with its orientation (the set of planets is
    symmetric, so each copy moves as the first one turned)."""
    extra_links, extra_xy, extra_angle = [], [], []
    for i, (name, kind, gears, carrier) in enumerate(links):
        count = mech.link(name).count if kind == "planet" else 1
        carried_by_main = carrier is None or mech.link(carrier).kind is not LinkKind.PLANET
        if count < 2 or not carried_by_main:
            continue
        offset = axis_xy[i] - main_xy
        for j in range(1, count):
            phi = 2 * np.pi * j / count
            c, s = np.cos(phi), np.sin(phi)
            turned = np.stack([c * offset[:, 0] - s * offset[:, 1], s * offset[:, 0] + c * offset[:, 1]], axis=-1)
            extra_links.append((f"{name}#{j + 1}", kind, gears, carrier))
            extra_xy.append(main_xy + turned)
            extra_angle.append(angle[i] + phi)
    if not extra_links:
        return links, axis_xy, angle
    return links + extra_links, np.concatenate([axis_xy, np.array(extra_xy)]), np.concatenate([angle, np.array(extra_angle)])


def _number(expr: Any, subs: Mapping[Any, Any], what: str) -> float:
    value = substitute(sp.sympify(expr), subs)
    if not value.is_number:
        raise InputError(f"give values for {', '.join(sorted(map(str, value.free_symbols)))} ({what}) to animate")
    return float(value)


def _carries(mech: Any, name: str) -> bool:
    return any(L.kind is LinkKind.PLANET and L.carrier == name for L in mech.links)


# --------------------------------------------------------------------------- drawing
class _Artists:
    """The matplotlib artists of one animation, updated frame by frame."""

    def __init__(self, ax: Any, frames: Frames, trail: bool = True):
        from matplotlib.patches import Polygon

        self.frames, self.trail = frames, trail
        self.gear_lines: list[tuple[int, float, bool, Line2D, Line2D, np.ndarray | None, Any]] = []
        self.arms: list[tuple[int, int, Line2D]] = []
        index = {name: i for i, (name, *_rest) in enumerate(frames.links)}
        for i, (name, kind, gears, carrier) in enumerate(frames.links):
            colour = _COLOURS[index[name.split("#")[0]] % len(_COLOURS)]  # a planet's copies in its colour
            for gname, radius, internal in gears:
                outline = None
                rear = gname in frames.rear  # a second row: dashed pitch circle, no teeth, no fill
                if gname in frames.teeth and not rear:
                    z, phase = frames.teeth[gname]
                    outline = np.array(involute_outline(radius, z, internal=internal, phase=phase))
                (circle,) = ax.plot([], [], color=colour, lw=1.1 if internal else 0.9, ls=(0, (4, 2)) if rear else "-")
                (marks,) = ax.plot([], [], color=colour, lw=0.9, ls=":" if rear else "-")
                face = None
                if not internal and not rear:  # external gears filled lightly, so that overlapping outlines read as meshing
                    face = Polygon(np.zeros((1, 2)), closed=True, facecolor=colour, alpha=0.18, lw=0)
                    ax.add_patch(face)
                self.gear_lines.append((i, radius, internal, circle, marks, outline, face))
            if kind == "planet" and carrier is not None:
                (arm,) = ax.plot([], [], color="0.25", lw=3.2, solid_capstyle="round", zorder=4)
                self.arms.append((index.get(carrier, -1), i, arm))
        self.paths = []
        self.dots = []
        for k, label in enumerate(frames.labels):
            colour = _PATH_COLOURS[k % len(_PATH_COLOURS)]
            (path,) = ax.plot([], [], color=colour, lw=1.3, label=label, zorder=5)  # solid: the legend shows it so
            (dot,) = ax.plot([], [], "o", color=colour, ms=5, zorder=6)
            self.paths.append(path)
            self.dots.append(dot)
        (self.hub,) = ax.plot([], [], "o", color="0.1", ms=4, zorder=6)
        self.clock = ax.text(0.02, 0.97, "", transform=ax.transAxes, va="top", fontsize=style.FONT)

    def update(self, n: int) -> list[Any]:
        sc = self.frames
        theta = np.linspace(0, 2 * np.pi, 121)
        for i, radius, internal, circle, marks, outline, face in self.gear_lines:
            cx, cy = sc.axis_xy[i, n]
            phi = sc.angle[i, n]
            if outline is not None:  # the teeth turn with the link
                c, s = np.cos(phi), np.sin(phi)
                xs, ys = cx + c * outline[0] - s * outline[1], cy + s * outline[0] + c * outline[1]
            else:
                xs, ys = cx + radius * np.cos(theta), cy + radius * np.sin(theta)
            circle.set_data(xs, ys)
            if face is not None:
                face.set_xy(np.column_stack([xs, ys]))
            if internal:  # short marks outside the ring show its rotation
                k = np.arange(12) * 2 * np.pi / 12 + phi
                r0, r1 = radius * 1.1, radius * 1.16
            else:  # three spokes from the axis show the gear's rotation
                k = np.arange(3) * 2 * np.pi / 3 + phi
                r0, r1 = 0.0, radius * (0.8 if outline is not None else 1.0)
            mx = np.column_stack([cx + r0 * np.cos(k), cx + r1 * np.cos(k), np.full_like(k, np.nan)]).ravel()
            my = np.column_stack([cy + r0 * np.sin(k), cy + r1 * np.sin(k), np.full_like(k, np.nan)]).ravel()
            marks.set_data(mx, my)
        for c, p, arm in self.arms:
            start = sc.axis_xy[c, n] if c >= 0 else sc.main_xy[n]
            arm.set_data([start[0], sc.axis_xy[p, n, 0]], [start[1], sc.axis_xy[p, n, 1]])
        for k, (path, dot) in enumerate(zip(self.paths, self.dots)):
            xy = sc.particle_xy[k, : n + 1] if self.trail else sc.particle_xy[k]
            path.set_data(xy[:, 0], xy[:, 1])
            dot.set_data([sc.particle_xy[k, n, 0]], [sc.particle_xy[k, n, 1]])
        self.hub.set_data([sc.main_xy[n, 0]], [sc.main_xy[n, 1]])
        self.clock.set_text(f"t = {sc.t[n]:.3g} s")
        return ([g[3] for g in self.gear_lines] + [g[4] for g in self.gear_lines]
                + [g[6] for g in self.gear_lines if g[6] is not None] + [a for *_, a in self.arms] + self.paths + self.dots)


def draw_frame(ax: Any, frames: Frames, n: int, *, trail: bool = True) -> None:
    """Draw frame ``n`` of ``frames`` on ``ax`` (the path traced so far with ``trail``)."""
    _setup(ax, frames)
    artists = _Artists(ax, frames, trail)
    artists.update(n)
    if frames.labels:
        style.legend_outside(ax)


def _setup(ax: Any, frames: Frames) -> None:
    x0, x1, y0, y1 = frames.limits()
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.tick_params(labelsize=style.SMALL)
    ax.set_xlabel(style.label("x", frames.length), fontsize=style.FONT)
    ax.set_ylabel(style.label("y", frames.length), fontsize=style.FONT)
    ax.set_title(frames.title, fontsize=style.FONT)


def _html_escape(text: str) -> str:
    import html

    return html.escape(text)


def _animation(frames: Frames, size: float) -> tuple[Figure, Any]:
    """The figure and the FuncAnimation of ``frames`` (``size`` inches wide)."""
    from matplotlib import animation

    fig = style.new_figure(size, size + (0.5 if frames.labels else 0.2))
    ax = fig.add_subplot()
    _setup(ax, frames)
    artists = _Artists(ax, frames, trail=True)
    artists.update(0)
    if frames.labels:
        style.legend_outside(ax)
    style.finish(fig)
    return fig, animation.FuncAnimation(fig, artists.update, frames=len(frames.t), blit=False)


def frame_figure(frames: Frames, n: int, *, trail: bool = True, size: float = 5.0) -> Figure:
    """One frame as a figure (to look at, or to save as a PNG).

    >>> from symkin import schemes
    >>> frames = Frames.build(schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1}),
    ...                     [("2", (1, 0))], t_end=6.3, frames=3)
    >>> len(frame_figure(frames, 2).axes[0].lines) > 4
    True
    """
    fig = style.new_figure(size, size + (0.5 if frames.labels else 0.2))
    draw_frame(fig.add_subplot(), frames, n, trail=trail)
    return style.finish(fig)


def animate(
    frames: Frames,
    out: str | os.PathLike[str],
    *,
    fps: int = 20,
    dpi: int = 100,
    size: float = 6.0,
    progress: Callable[[int, int], None] | None = None,
) -> Path:
    """Write the animation of ``frames`` to ``out``: ``.gif``, ``.mp4`` (with ffmpeg), or
    ``.html`` (a self-contained page with playback controls, :meth:`Frames.html`).

    The default is 600 pixels square (6 in at 100 dpi).  ``progress(done, total)`` is called
    as each frame of a GIF or MP4 is drawn (``symkin animate`` shows a bar with it).

    The file appears only when complete: frames go to a temporary file beside ``out``
    that is renamed at the end; on any error or interrupt the temporary file is removed
    and an existing ``out`` is left as it was.

    Raises
    ------
    InputError
        An unknown suffix, a folder that does not exist, bad fps or dpi.
    ToolError
        MP4 asked for but ffmpeg is not installed.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from symkin import schemes
    >>> frames = Frames.build(schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1}),
    ...                     [("2", (1, 0))], t_end=6.3, frames=3)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     path = animate(frames, pathlib.Path(d) / "ai1.gif", dpi=30)
    ...     path.read_bytes()[:6]
    b'GIF89a'
    """
    from matplotlib import animation

    out = Path(out)
    suffix = out.suffix.lower()
    if suffix not in WRITERS:
        raise InputError(f"cannot write {out.name}: give a file ending in {' or '.join(WRITERS)}")
    for name, value, low, high in (("fps", fps, 1, MAX_FPS), ("dpi", dpi, 10, MAX_DPI)):
        if not isinstance(value, int) or isinstance(value, bool) or not low <= value <= high:
            raise InputError(f"{name} must be an integer from {low} to {high}, got {value!r}")
    if suffix == ".mp4" and not ffmpeg_available():
        raise ToolError(
            "ffmpeg was not found, so an MP4 cannot be written; write a GIF instead (a file ending in .gif) "
            "or install ffmpeg (Debian/Ubuntu: sudo apt-get install ffmpeg)"
        )
    if not out.resolve().parent.is_dir():
        raise InputError(f"cannot write {out}: the folder {out.resolve().parent} does not exist")
    if suffix == ".html":
        out.write_text(frames.html(fps=fps, dpi=dpi, size=size), encoding="utf-8")
        return out
    _fig, anim = _animation(frames, size)
    writer = animation.writers[WRITERS[suffix]](fps=fps)
    try:
        anim.save(str(out), writer=writer, dpi=dpi,
                  progress_callback=None if progress is None else lambda i, n: progress(i + 1, n))
    except Exception as err:
        # an interrupt before the first frame: the writer, finishing, fails on no frames (pillow's
        # IndexError) over it; it stays the interrupt it was
        anim._draw_was_started = True
        if isinstance(err.__context__, KeyboardInterrupt):
            raise err.__context__ from None
        raise
    except BaseException:
        # no "deleted without rendering" warning on top of the error (a private attribute)
        anim._draw_was_started = True
        raise
    return out
