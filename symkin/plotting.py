"""Figures: particle trajectories, speed and acceleration curves, mechanism outlines.

Figures are built with matplotlib's object API (no pyplot state, no display needed).
A planet particle on the pitch circle traces an epicycloid (planet outside a fixed
gear) or a hypocycloid (inside a fixed ring); inside a ring twice its size, the Cardan
straight line.

    >>> from symkin import schemes, plotting
    >>> m = schemes.single_row_AI(radii=(1, 1, 3))
    >>> fig = plotting.trajectory_figure(m, {"4": 0, "H": 1}, [("2", (1, 0))], t_end=6.3)
    >>> len(fig.axes)
    1
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Iterable, Mapping, Sequence

import numpy as np
import sympy as sp
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from . import symbols as S
from .errors import InputError
from .model import LinkKind, Mechanism
from .parsing import as_values, substitute

#: The most samples :func:`sample` takes (ten million points: hundreds of MB of arrays).
MAX_SAMPLES = 10_000_000

__all__ = [
    "draw_pitch_circles",
    "draw_trajectories",
    "trajectory_figure",
    "kinematics_figure",
    "sample",
    "turn_time",
    "save",
]


def draw_pitch_circles(ax: Any, mech: Mechanism, values: Mapping[Any, Any] | None = None) -> None:
    """Pitch circles of every gear at t = 0 (planets at their initial position), thin grey."""
    named = as_values(values)
    for link in mech.links:
        centre = (0.0, 0.0)
        if link.kind is LinkKind.PLANET:
            arm = float(substitute(sp.sympify(mech.arm(link.name)), named))
            ang = float(substitute(sp.sympify(link.position_angle), named))
            centre = (arm * np.cos(ang), arm * np.sin(ang))
        for gear in link.gears:
            r = float(substitute(gear.radius, named))
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


def sample(
    particle: Any, t_end: float, *, samples: int = 721, values: Mapping[Any, Any] | None = None
) -> dict[str, np.ndarray]:
    """Sample a particle's position, velocity and acceleration on ``samples`` steps of [0, t_end].

    Returns arrays ``t, x, y, vx, vy, speed, ax, ay, acceleration`` (magnitudes for speed
    and acceleration).  ``values`` gives numbers for every symbol other than t.

    >>> from symkin import schemes
    >>> p = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1}).particle("2", (2, 1))
    >>> data = sample(p, 6.0, samples=5)
    >>> # axis velocity (0, 2) plus omega_2 = -2 turning the offset (0, 1): V = (2, 2)
    >>> round(float(data["speed"][0]), 12)
    2.828427124746
    """
    t_end = _positive_float(t_end, "the time span")
    if not isinstance(samples, int) or isinstance(samples, bool) or not 2 <= samples <= MAX_SAMPLES:
        raise InputError(f"samples must be an integer from 2 to {MAX_SAMPLES}, got {samples!r}")
    subs = as_values(values)
    exprs = [substitute(c, subs) for vec in (particle.position, particle.velocity, particle.acceleration) for c in vec]
    free = set().union(*(e.free_symbols for e in exprs)) - {S.t}
    if free:
        raise InputError(f"give values for {', '.join(sorted(map(str, free)))} to sample the particle")
    f = sp.lambdify(S.t, exprs, modules="numpy", cse=True)
    t = np.linspace(0.0, float(t_end), samples)
    x, y, vx, vy, ax, ay = (np.array(np.broadcast_to(np.asarray(c, dtype=float), t.shape)) for c in f(t))
    return {"t": t, "x": x, "y": y, "vx": vx, "vy": vy, "speed": np.hypot(vx, vy),
            "ax": ax, "ay": ay, "acceleration": np.hypot(ax, ay)}


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
        data = sample(p, t_end, samples=samples, values=values)
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


def turn_time(motion: Any, turns: float = 1.0, link: str | None = None, values: Mapping[Any, Any] | None = None) -> float:
    """The time ``link`` takes to make ``turns`` turns at its (constant) speed.

    Without ``link``: the carrier H when it moves, otherwise the fastest link.

    >>> from symkin import schemes
    >>> motion = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 2})
    >>> round(turn_time(motion, 1), 6)
    3.141593
    """
    turns = _positive_float(turns, "the number of turns")
    subs = as_values(values)
    mech = motion.mechanism

    def speed(name: str) -> float:
        w = substitute(sp.sympify(motion.omega(name)), subs)
        if S.t in w.free_symbols or not w.is_number:
            raise InputError(f"link {name} has no constant numeric speed ({w}); give the time span instead of turns")
        return abs(float(w))

    if link is None:
        names = [n for n in mech.link_names]
        moving = {n: speed(n) for n in names if not substitute(sp.sympify(motion.omega(n)), subs).has(S.t)}
        if "H" in moving and moving["H"] > 0:
            link = "H"
        elif moving and max(moving.values()) > 0:
            link = max(moving, key=lambda n: moving[n])
        else:
            raise InputError("no link turns at a constant non-zero speed; give the time span instead of turns")
    w = speed(mech.link(link).name)
    if w == 0:
        raise InputError(f"link {link} does not turn; count turns of a moving link or give the time span")
    return float(2 * np.pi * turns / w)


def _positive_float(value: Any, what: str) -> float:
    """A positive finite float from a number (exact numbers too), else InputError."""
    if isinstance(value, (bool, str)) or not isinstance(value, (int, float, np.number, sp.Expr)):
        raise InputError(f"{what} must be a positive number, got {value!r}")
    try:
        number = float(value)
    except (TypeError, ValueError, OverflowError):
        raise InputError(f"{what} must be a positive finite number, got {value!r}") from None
    if not (math.isfinite(number) and number > 0):
        raise InputError(f"{what} must be positive and finite, got {value!r}")
    return number


def save(fig: Figure, path: Path, formats: Sequence[str] = ("png", "pdf")) -> list[Path]:
    """Save ``fig`` as ``path`` with each suffix in ``formats``; returns the files written.

    The files appear together when all are written (:func:`symkin.atomic.replacing`): a
    failure leaves any earlier ones as they were.
    """
    from .atomic import replacing

    targets = [Path(path).with_suffix("." + fmt) for fmt in formats]
    with replacing(*targets) as temps:
        for tmp in temps:
            fig.savefig(tmp, dpi=150, bbox_inches="tight")
    return targets
