"""Gear teeth as involute outlines, phased so that meshing gears interleave.

A gear with a tooth number is drawn with standard involute teeth (pressure angle 20
degrees, addendum one module, dedendum 1.25 modules) cut on its working pitch circle:
the module is ``2 r / z``, so the pitch circle the kinematics uses is the one the teeth
roll on.  :func:`mesh_phases` turns each gear at t = 0 so that a tooth of one gear of every
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

__all__ = ["involute_outline", "mesh_phases", "rear_gears", "PRESSURE_ANGLE"]

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
    m = 2 * radius / z
    rb = radius * np.cos(pressure_angle)
    inner, outer = (radius - m, radius + 1.25 * m) if internal else (radius - 1.25 * m, radius + m)
    inner = max(inner, 1e-9)
    lo = max(inner, rb)
    rho = np.linspace(lo, outer, points)
    alpha_rho = np.arccos(np.clip(rb / rho, -1, 1))
    # half the angular width of an external gear's tooth at radius rho; for a ring, of its space
    half = np.pi / (2 * z) + _inv(pressure_angle) - _inv(alpha_rho)
    if internal:
        half = np.pi / z - half  # the ring's tooth is the space of the external gear
    pitch = 2 * np.pi / z
    ang: list[np.ndarray] = []
    rad: list[np.ndarray] = []
    for k in range(z):
        c = phase + k * pitch
        # tooth k: one flank up (root to tip for an external gear, tip to root for a ring), across, the other down
        flank_r = np.concatenate([[inner], rho]) if lo > inner else rho
        flank_h = np.concatenate([[half[0]], half]) if lo > inner else half
        if internal:
            flank_r, flank_h = flank_r[::-1], flank_h[::-1]
        ang += [c - flank_h, c + flank_h[::-1]]
        rad += [flank_r, flank_r[::-1]]
    a, r = np.concatenate(ang), np.concatenate(rad)
    a, r = np.append(a, a[0] + 2 * np.pi), np.append(r, r[0])
    # the arcs between the points of neighbouring flanks are short for any practical tooth number
    return r * np.cos(a), r * np.sin(a)


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
    phases: dict[str, float] = {}
    edges: dict[str, list[str]] = {name: [] for name in toothed}
    for mesh in mech.meshes:
        if mesh.a in toothed and mesh.b in toothed:
            edges[mesh.a].append(mesh.b)
            edges[mesh.b].append(mesh.a)
    for start in toothed:
        if start in phases:
            continue
        phases[start] = 0.0
        queue = [start]
        while queue:
            a = queue.pop(0)
            ga, la = toothed[a]
            for b in edges[a]:
                if b in phases:
                    continue
                gb, lb = toothed[b]
                ca, cb = centre(la), centre(lb)
                d = cb - ca
                if float(np.hypot(*d)) < 1e-12:
                    continue
                beta = float(np.arctan2(d[1], d[0]))  # direction from a's axis to b's axis
                za, zb = int(ga.teeth), int(gb.teeth)
                # the contact point seen from each axis: towards the other axis, or away for a ring
                # that holds the other gear inside
                seen_a = beta + (np.pi if gb.internal else 0.0)
                seen_b = beta + (0.0 if ga.internal else np.pi)
                # a's tooth offset at its contact direction, in a's pitches
                offset_a = ((seen_a - phases[a]) / (2 * np.pi / za)) % 1.0
                # b shows a space (a half pitch off a tooth) where a shows a tooth, mirrored by the rolling
                phases[b] = seen_b + (offset_a - 0.5) * 2 * np.pi / zb * (1 if ga.internal or gb.internal else -1)
                queue.append(b)
    return phases


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
