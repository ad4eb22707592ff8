"""Gear teeth as involute outlines, phased so that meshing gears interleave.

A gear with a tooth number is drawn with standard involute teeth (pressure angle 20
degrees, addendum one module, dedendum 1.25 modules) cut on its working pitch circle:
the module is ``2 r / z``, so the pitch circle the kinematics uses is the one the teeth
roll on.  The outline is :func:`symkin.geometry.tooth_outline`'s, the one ``symkin geometry``
exports to CAD: involute flanks, and the root fillet the ISO 53 rack cuts.  :func:`mesh_phases` turns each gear at t = 0 so that a tooth of one gear of every
mesh sits in a space of the other; as the derived motion turns the links, they stay meshed.

    >>> x, y = involute_outline(10, 20)
    >>> round(float(np.hypot(x, y).max()), 6), round(float(np.hypot(x, y).min()), 6)   # tip r + m, root r - 1.25 m
    (11.0, 8.75)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import InputError
from symkin.values import as_values, substitute

__all__ = ["involute_outline", "mesh_phases", "outline_figure", "rear_gears", "PRESSURE_ANGLE"]

#: Pressure angle of the drawn teeth, in radians (20 degrees).
PRESSURE_ANGLE = float(np.radians(20))


def _inv(alpha: Any) -> Any:
    return np.tan(alpha) - alpha


def involute_outline(
    radius: float,
    teeth: int,
    *,
    internal: bool = False,
    phase: float = 0.0,
    pressure_angle: float = PRESSURE_ANGLE,
    points: int = 8,
) -> tuple[np.ndarray, np.ndarray]:
    """The closed outline of a gear with ``teeth`` involute teeth on a pitch circle of ``radius``.

    Parameters
    ----------
    radius : float
        Pitch radius; the module is ``2 radius / teeth``.
    teeth : int
        Number of teeth, at least 3.
    internal : bool
        An internal (ring) gear: its teeth point inwards (tips at ``radius - m``).
    phase : float
        Angle (rad) of the centre of a tooth.
    pressure_angle : float
        Pressure angle (rad) on the pitch circle.
    points : int
        Points on each flank.

    Returns
    -------
    x, y : arrays
        The outline about the gear's axis, closed (the last point is the first).

    Examples
    --------
    >>> x, y = involute_outline(30, 60, internal=True)
    >>> round(float(np.hypot(x, y).min()), 6)   # a ring's tips point inwards: r - m
    29.0
    """
    z = int(teeth)
    if z < 3 or not np.isfinite(radius) or radius <= 0:
        raise InputError(f"cannot draw {teeth} teeth on a pitch radius {radius}: give at least 3 teeth and a positive radius")
    from symkin.geometry import ToothForm, gear_geometry, tooth_outline

    module = sp.Rational(repr(float(2 * radius / z)))
    degrees = sp.Rational(repr(round(float(np.degrees(pressure_angle)), 9)))
    gear = gear_geometry(z, module, ToothForm(pressure_angle=degrees), internal=internal)
    return tooth_outline(gear, phase=phase, points=points)


def mesh_phases(mech: Any, values: Mapping[Any, Any] | None = None) -> dict[str, float]:
    """The angle (rad) of a tooth centre of each toothed gear at t = 0, so that every mesh interleaves.

    Gears are visited along the meshes from the first toothed gear (phase 0): across a mesh,
    the second gear gets a space where the first has a tooth, on the line of centres.  Gears
    without a tooth number, and bevel meshes, are left out.

    >>> from symkin import schemes
    >>> phases = mesh_phases(schemes.single_row_AI(teeth=(20, 30, 80), module=1))
    >>> sorted(phases)
    ['1', '2', '4']
    """
    named = as_values(values)

    def centre(link: Any) -> np.ndarray:
        position = [substitute(sp.sympify(c), named) for c in mech.axis_position(link.name)]
        free = set().union(*(c.free_symbols for c in position))
        if free:  # (a train file may leave a tooth number as a symbol: a drawing needs its value)
            raise InputError(f"give values for {', '.join(sorted(map(str, free)))} to draw the gears")
        return np.array([float(c) for c in position])

    toothed = {}
    for link in mech.links:
        if link.axis == "radial":
            continue
        for g in link.gears:
            if g.teeth is not None and not g.bevel and sp.sympify(g.teeth).is_Integer:
                toothed[g.name] = (g, link)
    from symkin.geometry.outline import mesh_phases as phases_of

    gears = {name: (int(g.teeth), g.internal, tuple(float(c) for c in centre(link))) for name, (g, link) in toothed.items()}
    return phases_of(gears, [(m.a, m.b) for m in mech.meshes])  # type: ignore[arg-type]


def outline_figure(geometry: Any, *, title: str | None = None, zoom: tuple[float, float, float] | None = None) -> Any:
    """The tooth outlines of a :class:`~symkin.geometry.TrainGeometry`, placed as the train puts them
    (the ones ``symkin geometry --out`` writes to DXF and SVG), each gear named, in mm.

    ``zoom = (x, y, half_width)`` adds a second panel around a point (a mesh's pitch point).

    >>> from symkin.geometry import train_geometry
    >>> from symkin.trains import load_train
    >>> fig = outline_figure(train_geometry(load_train("simple")))
    >>> len(fig.axes)
    1
    """
    from symkin.geometry.export import placed_outlines
    from symkin.viz.style import PALETTE, new_figure, style_axes

    shapes = placed_outlines(geometry, points=16)
    panels = 2 if zoom else 1
    fig = new_figure(width=3.4 * panels, height=3.4)
    axes = [fig.add_subplot(1, panels, k + 1) for k in range(panels)]
    for ax in axes:
        style_axes(ax)
    for k, (name, (x, y)) in enumerate(shapes.items()):
        for ax in axes:
            ax.plot(x, y, lw=0.7, color=PALETTE[k % len(PALETTE)], linestyle="-", label=name)
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlabel("x, mm")
    axes[0].set_ylabel("y, mm")
    axes[0].legend(loc="upper left", fontsize="small", frameon=False)
    if zoom:
        cx, cy, half = zoom
        axes[1].set_xlim(cx - half, cx + half)
        axes[1].set_ylim(cy - half, cy + half)
    if title:
        axes[0].set_title(title)
    return fig


def rear_gears(mech: Any) -> frozenset[str]:
    """The gears of a train's second row, seen from +z behind the first: every rim of a link
    after its first (a stepped planet's second rim) and every gear meshing a rear rim, so that
    figures draw them apart (dashed, without teeth) from the front row they overlap.

    >>> from symkin import schemes
    >>> sorted(rear_gears(schemes.two_row("AA", teeth=(54, 45, 44, 55), module=1)))
    ['3', '4']
    """
    rear = {g.name for L in mech.links for g in L.gears[1:]}
    for mesh in mech.meshes:  # a gear meshing a rear rim is in the rear row too (one pass: a row is one mesh deep)
        if mesh.a in rear or mesh.b in rear:
            rear |= {mesh.a, mesh.b} - {g.name for L in mech.links for g in L.gears[:1] if len(L.gears) > 1}
    return frozenset(rear)
