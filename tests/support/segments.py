"""Whether polylines cross: every pair of segments tested by orientation signs (NumPy, in blocks)."""

from __future__ import annotations

import numpy as np


def _orient(ax, ay, bx, by, cx, cy):
    return np.sign((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))


def crossings(x1, y1, x2=None, y2=None, *, tol: float = 1e-9) -> int:
    """The number of proper crossings between the segments of polyline 1 and of polyline 2 (of polyline
    1 with itself when 2 is not given: neighbouring segments, which share a point, are not counted)."""
    same = x2 is None
    if same:
        x2, y2 = x1, y1
    p = np.stack([x1[:-1], y1[:-1], x1[1:], y1[1:]], axis=1)
    q = np.stack([x2[:-1], y2[:-1], x2[1:], y2[1:]], axis=1)
    count = 0
    for start in range(0, len(p), 256):
        a = p[start:start + 256, None, :]
        b = q[None, :, :]
        d1 = _orient(a[..., 0], a[..., 1], a[..., 2], a[..., 3], b[..., 0], b[..., 1])
        d2 = _orient(a[..., 0], a[..., 1], a[..., 2], a[..., 3], b[..., 2], b[..., 3])
        d3 = _orient(b[..., 0], b[..., 1], b[..., 2], b[..., 3], a[..., 0], a[..., 1])
        d4 = _orient(b[..., 0], b[..., 1], b[..., 2], b[..., 3], a[..., 2], a[..., 3])
        hit = (d1 * d2 < 0) & (d3 * d4 < 0)
        if same:
            i = np.arange(start, start + hit.shape[0])[:, None]
            j = np.arange(hit.shape[1])[None, :]
            n = len(p)
            hit &= (np.abs(i - j) > 1) & (np.abs(i - j) != n - 1) & (j > i)
        count += int(hit.sum())
    return count
