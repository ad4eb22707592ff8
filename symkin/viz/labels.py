"""Text labels of a drawing moved apart where they overlap (the kinematic scheme's names, :mod:`symkin.viz.diagram`).

Measured as drawn: the figure is laid out once with a renderer, and the texts' boxes are read in
display units, so that what the checks of :func:`symkin.viz.style.layout_problems` see is what
is moved.
"""

from __future__ import annotations

import itertools
from typing import Any

from matplotlib.figure import Figure

__all__ = ["renderer", "declutter", "stack"]


def renderer(fig: Figure) -> Any:
    """``fig`` drawn (laid out), and its renderer to measure text with."""
    if not hasattr(fig.canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    fig.canvas.draw()
    return fig.canvas.get_renderer()  # type: ignore[attr-defined]


def declutter(fig: Figure, ax: Any, texts: list[Any], pad: float = 2.0) -> bool:
    """Move overlapping texts of ``ax`` apart vertically (each pair by half its overlap, in a few
    rounds), as drawn in ``fig``; True if any moved."""
    measure = renderer(fig)
    to_data = ax.transData.inverted()
    floor = ax.transData.transform((0, 0))[1]  # none goes below the main axis
    moved = False
    for _ in range(80):
        boxes = [t.get_window_extent(measure) for t in texts]
        shift = [max(0.0, floor - box.y0) for box in boxes]
        for i, j in itertools.combinations(range(len(texts)), 2):
            a, b = boxes[i], boxes[j]
            if min(a.x1, b.x1) - max(a.x0, b.x0) > -pad and min(a.y1, b.y1) - max(a.y0, b.y0) > -pad:
                push = (min(a.y1, b.y1) - max(a.y0, b.y0) + pad) / 2 + 0.5
                up, down = (i, j) if a.y0 + a.y1 >= b.y0 + b.y1 else (j, i)
                if boxes[down].y0 - push < floor:  # the lower one on the floor: the upper one moves the whole way
                    shift[up] += 2 * push
                    continue
                shift[up] += push
                shift[down] -= push
        if not any(shift):
            break
        moved = True
        for t, box, dy in zip(texts, boxes, shift):
            if dy:
                y0 = to_data.transform((box.x0, box.y0))[1]
                y1 = to_data.transform((box.x0, box.y0 + dy))[1]
                x, y = t.get_position() if not hasattr(t, "xyann") else t.xyann
                if hasattr(t, "xyann"):
                    t.xyann = (x, y + y1 - y0)
                else:
                    t.set_y(y + y1 - y0)
    return moved


def stack(fig: Figure, ax: Any, texts: list[Any], k: float) -> bool:
    """Raise each of ``texts`` (in their order, bottom up) to at least a line above the one before,
    as drawn in ``fig``; positions in data units over ``k``.  True if any moved."""
    measure = renderer(fig)
    tall = max([t.get_window_extent(measure).height for t in texts] + [0.0]) * 1.15
    tall = (ax.transData.inverted().transform((0, tall))[1] - ax.transData.inverted().transform((0, 0))[1]) / k
    spread = False
    for below, t in itertools.pairwise(texts):
        y_text = max(t.get_position()[1] / k, below.get_position()[1] / k + tall)
        spread = spread or y_text > t.get_position()[1] / k + 1e-9
        t.set_y(y_text * k)
    return spread
