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

from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from symkin._util.atomic import replacing
from symkin._util.parsing import as_values, substitute
from symkin.errors import InputError
from symkin.model import LinkKind, Mechanism

__all__ = [
    "space_figure",
    "default_particles",
    "draw_pitch_circles",
    "draw_trajectories",
    "trajectory_figure",
    "kinematics_figure",
    "save",
]


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


def draw_pitch_circles(ax: Any, mech: Mechanism, values: Mapping[Any, Any] | None = None) -> None:
    """Pitch circles of every gear at t = 0 (planets at their initial position), thin grey."""
    named = as_values(values)
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
            ax.add_patch(Circle(centre, r, fill=False, lw=0.6, ls="--" if gear.internal else "-", color="0.6"))
            ax.annotate(gear.name, (centre[0] + r * 0.7071, centre[1] + r * 0.7071), color="0.45", fontsize=7)


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
        ax.plot([cx - dx, cx + dx], [cy - dy, cy + dy], lw=0.8, color="0.6")
        ax.plot([x0, cx], [y0, cy], lw=0.5, ls=":", color="0.6")
        gear = geo.gear_a if geo.link_a.name == link.name else geo.gear_b
        ax.annotate(gear.name, (cx + dx, cy + dy), color="0.45", fontsize=7)


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
    """Draw the path of each (link, point) particle from t = 0 to ``t_end``."""
    for i, (link, point) in enumerate(particles):
        p = motion.particle(link, point, relative_to=relative_to)
        x, y = p.trajectory(t_end, samples=samples, values=values)[1:3]  # seen from +z for a path in space
        label = labels[i] if labels else f"link {link}, point {tuple(point)}"
        (line,) = ax.plot(x, y, lw=1.1, label=label)
        ax.plot(x[:1], y[:1], "o", ms=3, color=line.get_color())


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
) -> Figure:
    """One axes: pitch circles (at t = 0) and particle paths of ``mech`` under ``inputs``."""
    fig = Figure(figsize=(5, 5))
    ax = fig.add_subplot()
    draw_pitch_circles(ax, mech, values)
    draw_trajectories(ax, mech.motion(inputs), particles, t_end, relative_to=relative_to, values=values, labels=labels)
    ax.set_aspect("equal")
    ax.set_title(title or mech.name)
    ax.legend(fontsize=7, loc="upper right")
    return fig


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
    fig = Figure(figsize=(6, 5.5))
    ax = fig.add_subplot(projection="3d")
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
        ax.plot(x[:1], y[:1], z[:1], "o", ms=3, color=line.get_color())
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(title or motion.mechanism.name or "paths in space", fontsize=9)
    ax.legend(fontsize=7, loc="upper left")
    return fig


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
) -> Figure:
    """Speed and acceleration of each particle against time (two stacked axes).

    >>> from symkin import schemes
    >>> motion = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1})
    >>> fig = kinematics_figure(motion, [("2", (1, 0))], 6.3)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['speed |V|', 'acceleration |w|']
    """
    fig = Figure(figsize=(6.4, 5.2))
    ax_v, ax_a = fig.subplots(2, 1, sharex=True)
    for i, (link, point) in enumerate(particles):
        p = motion.particle(link, point, relative_to=relative_to)
        data = p.sample(t_end, samples=samples, values=values)
        label = labels[i] if labels else f"link {link}, point {tuple(point)}"
        ax_v.plot(data["t"], data["speed"], lw=1.1, label=label)
        ax_a.plot(data["t"], data["acceleration"], lw=1.1, label=label)
    ax_v.set_ylabel("speed |V|")
    ax_a.set_ylabel("acceleration |w|")
    ax_a.set_xlabel("time t")
    for ax in (ax_v, ax_a):
        ax.grid(True, lw=0.4, alpha=0.6)
        ax.set_ylim(bottom=0)
    ax_v.legend(fontsize=7, loc="upper right")
    fig.suptitle(title or "speed and acceleration of the particles, eqs. (5), (6)", fontsize=10)
    return fig


def save(fig: Figure, path: Path, formats: Sequence[str] = ("png", "pdf")) -> list[Path]:
    """Save ``fig`` as ``path`` with each suffix in ``formats``; returns the files written.

    The files appear together when all are written (:func:`symkin._util.atomic.replacing`): a
    failure leaves any earlier ones as they were.
    """
    targets = [Path(path).with_suffix("." + fmt) for fmt in formats]
    with replacing(*targets) as temps:
        for tmp in temps:
            fig.savefig(tmp, dpi=150, bbox_inches="tight")
    return targets
