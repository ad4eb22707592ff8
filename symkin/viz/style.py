"""The look every symkin figure shares: a colour-blind-safe palette, journal sizes, units.

Figures are sized for a journal column (:data:`COLUMN`, 3.5 in) or a page (:data:`PAGE`,
7.2 in) so that their text is printed at :data:`FONT` points without scaling, use the
Okabe-Ito palette (:data:`PALETTE`, told apart with any colour vision and in grey by
line style), label every axis with its unit, and keep legends off the drawing.

    >>> fig = new_figure(COLUMN, 3)
    >>> ax = fig.add_subplot()
    >>> style_axes(ax)
    >>> ax.set_xlabel(label("time t", "s"))
    Text(...)
    >>> finish(fig) is fig
    True
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
from matplotlib.figure import Figure

__all__ = [
    "PALETTE", "LINESTYLES", "COLUMN", "PAGE", "FONT", "SMALL", "MIN_FONT", "UNITS",
    "new_figure", "style_axes", "label", "legend_outside", "finish", "units_of", "layout_problems",
]

#: Okabe & Ito's palette, safe for every kind of colour vision (blue, vermilion, green,
#: reddish purple, orange, sky blue, black, yellow).
PALETTE = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442")
#: Line styles cycled with the colours, so curves stay apart in grey and where they coincide.
LINESTYLES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1)), (0, (1, 1)), "-", "--")
#: Width of a journal column and of a full page, in inches.
COLUMN, PAGE = 3.5, 7.2
#: Font sizes in points: labels and titles, tick labels and legends; nothing is printed smaller than MIN_FONT.
FONT, SMALL, MIN_FONT = 8.0, 7.0, 6.5
#: The units bare numbers have in symkin (length, time, angle), as printed on axes.
UNITS = {"length": "m", "time": "s", "angle": "rad"}


def units_of(length: str = "m", time: str = "s") -> dict[str, str]:
    """The units of a particle's kinematics drawn in ``length`` and ``time`` units.

    >>> units_of("mm")["acceleration"]
    'mm/s$^2$'
    """
    return {"length": length, "time": time, "speed": f"{length}/{time}", "acceleration": f"{length}/{time}$^2$"}


def label(name: str, unit: str) -> str:
    """An axis label with its unit in brackets (``"-"`` for a number without a unit).

    >>> label("speed |V|", "m/s")
    'speed |V| [m/s]'
    """
    return f"{name} [{unit}]"


def new_figure(width: float = COLUMN, height: float | None = None) -> Figure:
    """A figure ``width`` inches wide (at most :data:`PAGE`) with constrained layout.

    >>> new_figure(PAGE).get_size_inches().tolist()
    [7.2, 5.4]
    """
    width = min(float(width), PAGE)
    return Figure(figsize=(width, height if height is not None else 0.75 * width), layout="constrained")


def style_axes(ax: Any) -> None:
    """Give ``ax`` the palette with line styles, small ticks and a light grid (call before plotting).

    >>> fig = new_figure()
    >>> ax = fig.add_subplot()
    >>> style_axes(ax)
    >>> ax.plot([0, 1])[0].get_color() == PALETTE[0]
    True
    """
    from cycler import cycler

    ax.set_prop_cycle(cycler(color=list(PALETTE)) + cycler(linestyle=list(LINESTYLES)))
    ax.tick_params(labelsize=SMALL)
    ax.grid(True, lw=0.4, alpha=0.5)


def legend_outside(ax: Any, *, ncol: int = 1, where: str = "below") -> Any:
    """A legend off the drawing (returns it): below the figure (``where="below"``, a figure
    legend for a figure of one panel, placed by the constrained layout) or right of ``ax``.

    >>> fig = new_figure()
    >>> ax = fig.add_subplot()
    >>> _ = ax.plot([0, 1], label="a")
    >>> legend_outside(ax).get_texts()[0].get_text()
    'a'
    """
    handles, labels = ax.get_legend_handles_labels()
    if where == "below":
        return ax.figure.legend(handles, labels, fontsize=SMALL, loc="outside lower center", ncol=ncol,
                                frameon=False, handlelength=2.4)
    return ax.legend(handles, labels, fontsize=SMALL, loc="center left", bbox_to_anchor=(1.02, 0.5), ncol=ncol,
                     frameon=False, borderaxespad=0.0, handlelength=2.4)


def finish(fig: Figure) -> Figure:
    """Lift any text smaller than :data:`MIN_FONT` to it and return ``fig``.

    >>> fig = new_figure()
    >>> t = fig.text(0, 0, "tiny", fontsize=3)
    >>> finish(fig).texts[0].get_fontsize()
    6.5
    """
    from matplotlib.text import Text

    for text in fig.findobj(Text):
        if text.get_text() and float(text.get_fontsize()) < MIN_FONT:
            text.set_fontsize(MIN_FONT)
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis, getattr(ax, "zaxis", None)):
            if axis is not None and axis.get_ticklabels() and float(axis.get_ticklabels()[0].get_fontsize()) < MIN_FONT:
                axis.set_tick_params(labelsize=MIN_FONT)
    return fig


_UNIT = re.compile(r"\[[^\[\]]+\]")


def _texts(fig: Figure) -> list[Any]:
    """Every text drawn: titles, labels, legends, annotations, and the tick labels in view."""
    from matplotlib.text import Text

    ticks, shown = _tick_labels(fig)
    out, seen = [], set()
    for text in fig.findobj(Text):
        if id(text) in seen or not text.get_visible() or not text.get_text().strip():
            continue
        seen.add(id(text))
        if id(text) in ticks and id(text) not in shown:
            continue
        out.append(text)
    return out


def _tick_labels(fig: Figure) -> tuple[set[int], set[int]]:
    """The ids of every tick label (and of the label of a hidden axis), and of the tick labels in view."""
    ticks: set[int] = set()
    shown: set[int] = set()
    for ax in fig.axes:
        for key in ("x", "y", "z"):
            axis = getattr(ax, f"{key}axis", None)
            if axis is None:
                continue
            lo, hi = sorted(getattr(ax, f"get_{key}lim")())
            pad = 1e-9 * (abs(hi - lo) + 1)
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                for t in (tick.label1, tick.label2):
                    ticks.add(id(t))
                    if axis.get_visible() and lo - pad <= tick.get_loc() <= hi + pad:
                        shown.add(id(t))
            if not axis.get_visible():
                ticks.add(id(axis.get_label()))
    return ticks, shown


def layout_problems(fig: Figure, *, width: float = PAGE) -> list[str]:
    """What keeps ``fig`` from print: axes without a label or a unit, overlapping text,
    legends over drawn lines, text too small at ``width`` inches, log axes with fewer than
    three labelled ticks.  An empty list means none was found.

    Every axis that shows tick labels needs a label with its unit in brackets (``[m/s]``,
    ``[-]`` for a pure number).  Text boxes are measured by matplotlib's renderer
    (``get_window_extent``) after a draw.

    >>> fig = new_figure()
    >>> ax = fig.add_subplot()
    >>> _ = ax.plot([0, 1], [0, 1])
    >>> layout_problems(fig)
    ['axes 1: the x axis has no label with a unit in brackets', 'axes 1: the y axis has no label with a unit in brackets']
    """
    if not hasattr(fig.canvas, "get_renderer"):  # a Figure built without pyplot: give it a canvas to measure
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    problems: list[str] = []
    scale = min(1.0, width / fig.get_size_inches()[0])
    if scale < 1:
        problems.append(f"the figure is {fig.get_size_inches()[0]:.3g} in wide, more than {width:.3g} in")
    for n, ax in enumerate(fig.axes, 1):
        if not ax.get_visible() or not ax.axison:
            continue
        name = f"axes {n}" + (f" ({ax.get_title()[:40]!r})" if ax.get_title() else "")
        problems += _axis_problems(ax, name)
        problems += _legend_problems(ax, name, renderer)
    return problems + _text_problems(fig, renderer, scale, width)


def _axis_problems(ax: Any, name: str) -> list[str]:
    """Each axis of ``ax`` that shows tick labels: a label with a unit, and (log) at least three labelled ticks."""
    problems = []
    axes = [("x", ax.xaxis), ("y", ax.yaxis)] + ([("z", ax.zaxis)] if hasattr(ax, "zaxis") else [])
    for key, axis in axes:
        shown = [t for t in axis.get_ticklabels() if axis.get_visible() and t.get_visible() and t.get_text().strip()]
        lo, hi = sorted(getattr(ax, f"get_{key}lim")())
        shown_in = [t for t, v in zip(axis.get_ticklabels(), axis.get_ticklocs()) if t.get_visible()
                    and t.get_text().strip() and lo - 1e-12 * abs(hi - lo) <= v <= hi + 1e-12 * abs(hi - lo)]
        if not shown:
            continue
        text = axis.get_label().get_text()
        if not _UNIT.search(text):
            problems.append(f"{name}: the {key} axis has no label with a unit in brackets")
        if axis.get_scale() == "log" and len(shown_in) < 3:
            problems.append(f"{name}: the {key} axis is logarithmic with {len(shown_in)} labelled ticks")
    return problems


def _legend_problems(ax: Any, name: str, renderer: Any) -> list[str]:
    """The first drawn line of ``ax`` (2-D) that its legend covers, if any."""
    legend = ax.get_legend()
    if legend is None or not legend.get_visible():
        return []
    box = legend.get_window_extent(renderer)
    for line in ax.get_lines():
        xy = np.asarray(line.get_xydata(), dtype=float)
        if not line.get_visible() or (str(line.get_label()).startswith("_") and len(xy) < 2):
            continue
        if hasattr(ax, "zaxis") or not len(xy):
            continue
        pts = line.get_transform().transform(xy[np.all(np.isfinite(xy), axis=1)])
        inside = (pts[:, 0] > box.x0) & (pts[:, 0] < box.x1) & (pts[:, 1] > box.y0) & (pts[:, 1] < box.y1)
        if inside.any():
            return [f"{name}: the legend covers a drawn line ({str(line.get_label())[:30]!r})"]
    return []


def _text_problems(fig: Figure, renderer: Any, scale: float, width: float) -> list[str]:
    """Text smaller than :data:`MIN_FONT` at ``scale``, and texts whose boxes overlap."""
    problems = []
    texts = _texts(fig)
    boxes = [t.get_window_extent(renderer) for t in texts]
    for t in texts:
        if t.get_fontsize() * scale < MIN_FONT - 1e-9:
            problems.append(f"text {t.get_text()[:30]!r} is {t.get_fontsize() * scale:.3g} pt at {width:.3g} in wide")
    for i in range(len(texts)):
        for j in range(i + 1, len(texts)):
            a, b = boxes[i], boxes[j]
            if min(a.x1, b.x1) - max(a.x0, b.x0) > 1 and min(a.y1, b.y1) - max(a.y0, b.y0) > 1:
                problems.append(f"texts {texts[i].get_text()[:30]!r} and {texts[j].get_text()[:30]!r} overlap")
    return problems
