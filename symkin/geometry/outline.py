"""Tooth outlines: the closed curve of a gear's teeth, as the rack cuts it, for CAD and figures.

An external gear's outline is what the ISO 53 rack of its :class:`~symkin.geometry.ToothForm`
leaves, shifted by ``x m``: the involute flanks, the tip circle, and in the root the
trochoidal fillet the rack's tip radius ``rho_f* m`` cuts, down to the root circle.  The
fillet is the envelope of the rack's tip circle: its point with normal angle ``beta`` (from
straight down to the flank's normal) is cut when that normal passes through the pitch point
(the law of gearing), which gives the gear's turn for each ``beta`` in closed form.  Where
the rack undercuts the flank, the fillet crosses the involute and the outline follows the
fillet to the crossing.

An internal gear's outline has its involute flanks between the tip circle (inside) and the
root circle; below the base circle a flank runs radially, and the root has no fillet (the
pinion cutter that would cut it is not modelled).

Angles are in radians, lengths in mm; the first tooth of an external gear is centred on the
+x axis (an internal gear's too), turned by ``phase``.

    >>> from symkin.geometry import gear_geometry
    >>> x, y = tooth_outline(gear_geometry(20, 2))
    >>> round(float(np.hypot(x, y).max()), 9), round(float(np.hypot(x, y).min()), 9)
    (22.0, 17.5)
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from symkin.geometry.gear import GearGeometry

__all__ = ["tooth_outline", "mesh_phases"]


def _inv(a: Any) -> Any:
    return np.tan(a) - a


def _flank_angle(g: GearGeometry, r: np.ndarray) -> np.ndarray:
    """Angle from the space's centre line to the flank at radius ``r`` (the involute), in one pitch."""
    z = int(g.teeth)
    s, d = float(g.reference_thickness), float(g.reference_diameter)
    alpha = float(g.form.alpha)
    rb = float(g.base_diameter) / 2
    half_tooth = s / d + (-1 if g.internal else 1) * (_inv(alpha) - _inv(np.arccos(np.clip(rb / r, -1, 1))))
    return math.pi / z - half_tooth


def _fillet(g: GearGeometry, points: int) -> tuple[np.ndarray, np.ndarray]:
    """Polar (radius, angle from the space's centre line) of the trochoidal fillet, from the root to the flank."""
    m, r = float(g.module), float(g.reference_diameter) / 2
    alpha, x = float(g.form.alpha), float(g.shift)
    hf, rho = float(g.form.dedendum) * m, float(g.form.fillet) * m
    datum = r + x * m  # the rack's datum line, in the rack frame (y up, away from the gear's axis)
    yc = datum - hf + rho  # the centre of the rack's tip radius
    uc = math.pi * m / 4 - (datum - yc) * math.tan(alpha) - rho / math.cos(alpha)
    beta = np.linspace(-math.pi / 2, -alpha, points)
    n = np.stack([np.cos(beta), np.sin(beta)])
    t = (yc - r) / n[1]  # the pitch point (on y = r) is C - t n
    phi = (uc - t * n[0]) / r  # the gear's turn while the rack moved by r phi
    qu, qy = uc + rho * n[0] - r * phi, yc + rho * n[1]  # the cutting point, fixed frame
    # into the gear's frame (turned back by phi); the space's centre line is +y
    gx = qu * np.cos(phi) + qy * np.sin(phi)
    gy = -qu * np.sin(phi) + qy * np.cos(phi)
    return np.hypot(gx, gy), np.arctan2(gx, gy)


def _half_space(g: GearGeometry, points: int) -> tuple[np.ndarray, np.ndarray]:
    """Polar points of one side of a space: from the space's centre line (root) to the tooth's centre line (tip)."""
    z = int(g.teeth)
    ra, rf, rb = float(g.tip_diameter) / 2, float(g.root_diameter) / 2, float(g.base_diameter) / 2
    half_pitch = math.pi / z
    if g.internal:
        # from the root (outside) inwards: involute down to the tip (or to the base circle, then radially)
        r_in = max(ra, rb)
        rr = np.linspace(rf, r_in, points)
        th = _flank_angle(g, rr)
        if ra < rb:
            rr, th = np.append(rr, ra), np.append(th, th[-1])
        # the space of an internal gear is the tooth of the mating outline: its centre line is where
        # the external formula's tooth centre is; the root arc runs from the space's centre to the flank
        return (np.concatenate([[rf], rr, [ra]]), np.concatenate([[0.0], th, [half_pitch]]))
    fr, fth = _fillet(g, points)
    rr = np.linspace(max(rb, float(fr.min())), ra, points)
    th = _flank_angle(g, rr)
    # where the fillet meets the involute: the fillet's end when no undercut, else their crossing
    inside = fr >= rb
    gap = np.interp(fr[inside], rr, th) - fth[inside] if inside.any() else np.array([])
    if gap.size and (gap < -1e-12).any():  # the fillet passes the flank: undercut, trim both at the crossing
        k = int(np.argmax(gap < -1e-12))
        idx = np.flatnonzero(inside)[k]
        r_cross = fr[idx]
        keep = fr < r_cross
        fr, fth = np.append(fr[keep], r_cross), np.append(fth[keep], float(np.interp(r_cross, rr, th)))
        rr = np.linspace(r_cross, ra, points)
    else:
        rr = np.linspace(float(fr[-1]), ra, points)
    th = _flank_angle(g, rr)
    radius = np.concatenate([[rf], fr, rr[1:], [ra]])
    angle = np.concatenate([[0.0], fth, th[1:], [half_pitch]])
    return radius, angle


def tooth_outline(gear: GearGeometry, *, phase: float = 0.0, points: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """The closed outline of ``gear``'s teeth (x, y in mm, the last point the first), counter-clockwise.

    ``points`` is the number of points on each flank and fillet.
    """
    z = int(gear.teeth)
    r, a = _half_space(gear, points)
    pitch = 2 * math.pi / z
    # one pitch: a space's right half, then its mirror about the tooth's centre line
    r1 = np.concatenate([r, r[::-1][1:]])
    a1 = np.concatenate([a, pitch - a[::-1][1:]])
    r_all = np.concatenate([r1[:-1] for _ in range(z)])
    a_all = np.concatenate([a1[:-1] + k * pitch for k in range(z)])
    # a space centred on angle 0 (from +y, clockwise) put a tooth at pitch/2: turn so that an
    # external gear's tooth (an internal gear's space) is on +x
    polar = pitch / 2 - a_all + phase
    x, y = r_all * np.cos(polar), r_all * np.sin(polar)
    x, y = x[::-1], y[::-1]  # the angle above runs clockwise
    return np.append(x, x[0]), np.append(y, y[0])


def mesh_phases(gears: Mapping[str, tuple[int, bool, tuple[float, float]]],
                pairs: Iterable[tuple[str, str]]) -> dict[str, float]:
    """The turn (rad) of each gear's outline (:func:`tooth_outline`'s ``phase``) that puts a tooth of one
    gear of every mesh in a space of the other, on their line of centres.

    ``gears`` maps a name to (teeth, internal, axis position); ``pairs`` are the meshes.  Gears are
    visited along the meshes from the first of each connected set (phase 0); across a mesh the second
    gear's space stands where the first one's nearest tooth is, turned as rolling carries it.

    >>> phases = mesh_phases({"s": (20, False, (0.0, 0.0)), "p": (30, False, (25.0, 0.0))}, [("s", "p")])
    >>> phases["s"], round(phases["p"], 6) == round(math.pi - math.pi / 30, 6)
    (0.0, True)
    """
    links: dict[str, list[str]] = {name: [] for name in gears}
    for a, b in pairs:
        if a in gears and b in gears:
            links[a].append(b)
            links[b].append(a)
    phase: dict[str, float] = {}
    for start in gears:
        if start in phase:
            continue
        phase[start] = 0.0
        queue = [start]
        while queue:
            here = queue.pop(0)
            for there in links[here]:
                if there not in phase:
                    phase[there] = _partner_phase(gears[here], phase[here], gears[there])
                    queue.append(there)
    return phase


def _partner_phase(a: tuple[int, bool, tuple[float, float]], pa: float, b: tuple[int, bool, tuple[float, float]]) -> float:
    (za, ia, ca), (zb, ib, cb) = a, b
    dx, dy = cb[0] - ca[0], cb[1] - ca[1]
    if math.hypot(dx, dy) < 1e-12:  # (on one axis: no line of centres)
        return 0.0
    beta = math.atan2(dy, dx)  # from a's axis to b's
    # the pitch point seen from each axis: towards the other axis, or away for a ring holding the other gear
    da = beta + (math.pi if ib else 0.0)
    db = beta + (0.0 if ia else math.pi)
    sense = 1.0 if ia or ib else -1.0  # an internal mesh turns both gears the same way
    pitch_a = 2 * math.pi / za
    off = da - pa
    e_a = off - round(off / pitch_a) * pitch_a  # a's nearest tooth is turned by -e_a from the pitch point
    return db - sense * e_a * za / zb - math.pi / zb  # b's space there, turned as rolling carries it
