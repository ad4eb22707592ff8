"""Figures: particle trajectories and mechanism outlines.

Figures are built with matplotlib's object API (no pyplot state, no display needed).

    >>> from symkin import schemes, plotting
    >>> m = schemes.single_row_AI(radii=(1, 1, 3))
    >>> fig = plotting.trajectory_figure(m, {"4": 0, "H": 1}, [("2", (1, 0))], t_end=6.3)
    >>> len(fig.axes)
    1
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterable, Mapping, Sequence

import numpy as np
import sympy as sp
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from .model import LinkKind, Mechanism

__all__ = ["draw_pitch_circles", "draw_trajectories", "trajectory_figure", "save"]


def draw_pitch_circles(ax: Any, mech: Mechanism, values: Mapping[Any, Any] | None = None) -> None:
    """Pitch circles of every gear at t = 0 (planets at their initial position), thin grey."""
    for link in mech.links:
        centre = (0.0, 0.0)
        if link.kind is LinkKind.PLANET:
            arm = float(sp.sympify(mech.arm(link.name)).subs(dict(values or {})))
            ang = float(sp.sympify(link.position_angle).subs(dict(values or {})))
            centre = (arm * np.cos(ang), arm * np.sin(ang))
        for gear in link.gears:
            r = float(gear.radius.subs(dict(values or {})))
            ax.add_patch(Circle(centre, r, fill=False, lw=0.6, ls="--" if gear.internal else "-", color="0.6"))
            ax.annotate(gear.name, (centre[0] + r * 0.7071, centre[1] + r * 0.7071), color="0.45", fontsize=7)


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
        _, x, y = p.trajectory(t_end, samples=samples, values=values)
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
) -> Figure:
    """One axes: pitch circles and particle paths of ``mech`` under ``inputs``."""
    fig = Figure(figsize=(5, 5))
    ax = fig.add_subplot()
    draw_pitch_circles(ax, mech, values)
    draw_trajectories(ax, mech.motion(inputs), particles, t_end, relative_to=relative_to, values=values)
    ax.set_aspect("equal")
    ax.set_title(title or mech.name)
    ax.legend(fontsize=7, loc="upper right")
    return fig


def save(fig: Figure, path: Path, formats: Sequence[str] = ("png", "pdf")) -> list[Path]:
    """Save ``fig`` as ``path`` with each suffix in ``formats``; returns the files written."""
    out = []
    for fmt in formats:
        target = Path(path).with_suffix("." + fmt)
        fig.savefig(target, dpi=150, bbox_inches="tight")
        out.append(target)
    return out
