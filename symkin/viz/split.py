"""Figures of the ratio split: the objective against each stage's ratio, and discrete designs.

Built with matplotlib's object API; save with :func:`symkin.viz.figures.save`.

    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    >>> from symkin.mechanisms.multistage.split import optimize_split
    >>> best = optimize_split(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
    >>> fig = split_figure(best, points=9)
    >>> len(fig.axes)
    1
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from symkin.mechanisms.multistage.split import ContinuousSplit, DiscreteSplit, profile
from symkin.viz import style

__all__ = ["split_figure", "stage_model_figure", "OBJECTIVE_LABEL"]

#: The objective's axis label: the lost motion at the output, in the unit of the stage
#: models' Phi/d (both panels of :func:`split_figure` use it).
OBJECTIVE_LABEL = r"least objective $\overline{\Delta\varphi}_\Sigma$ [unit of $\Phi/d$]"


def split_figure(best: ContinuousSplit, discrete: DiscreteSplit | None = None, *, points: int = 41,
                 title: str | None = None) -> Figure:
    """The least objective with one stage's ratio held fixed, for every stage.

    Each curve is min F over the other ratios (product fixed, bounds kept) as u_i varies;
    the continuous optimum is marked.  With ``discrete``, a second panel shows the
    designs' objectives against their total ratio, beside the continuous minimum.  Both
    panels share the objective's label; curves differ in line style and marker, so a stage
    whose curve coincides with another's stays visible.
    """
    p = best.problem
    fig = style.new_figure(style.PAGE if discrete is not None else style.COLUMN * 1.5, 3.8)
    ax = fig.add_subplot(1, 2 if discrete is not None else 1, 1)
    style.style_axes(ax)
    markers = "osD^vP*X"
    for i in range(1, p.stages + 1):
        lo, hi = float(p.lower[i - 1]), float(p.upper[i - 1])
        grid = np.geomspace(lo, hi, points) if hi > lo else np.array([lo])
        values = profile(p, i, grid)
        (line,) = ax.plot(grid, values, lw=1.3 + 0.5 * (p.stages - i), label=f"stage {i}",
                          marker=markers[(i - 1) % len(markers)], markevery=max(1, points // 6), ms=3 + (p.stages - i))
        ax.plot([best.ratios[i - 1]], [best.objective], "o", ms=7, color=line.get_color(), mfc="none", ls="none")
    ax.axhline(best.objective, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("stage ratio $u_i$ [-]\n(the others re-optimised, product fixed)", fontsize=style.FONT)
    ax.set_ylabel(OBJECTIVE_LABEL, fontsize=style.FONT)
    ax.set_title(title or f"{p.stages} stages, U = {p.total}: optimum (circles) {_fmt(best.ratios)}", fontsize=style.FONT)
    if discrete is None:
        style.legend_outside(ax, ncol=min(p.stages, 4))
    else:
        ax.legend(fontsize=style.SMALL, loc="upper right", frameon=True, framealpha=0.9)
    if discrete is not None:
        ax2 = fig.add_subplot(1, 2, 2)
        style.style_axes(ax2)
        totals = [float(d.total) for d in discrete.designs]
        objs = [float(d.objective) for d in discrete.designs]
        ax2.plot(totals, objs, "s", ms=4, ls="none", color=style.PALETTE[0], label="discrete designs")
        for rank, d in enumerate(discrete.designs[:5], 1):
            ax2.annotate(str(rank), (float(d.total), float(d.objective)), fontsize=style.SMALL, xytext=(3, 3),
                         textcoords="offset points")
        ax2.axhline(best.objective, color="0.4", lw=0.8, ls="--", label="continuous minimum")
        ax2.axvline(float(p.total), color="0.6", lw=0.8, ls=":")
        kind = "within tolerance" if discrete.meets_tolerance else "nearest (none within tolerance)"
        ax2.set_title(f"best {len(discrete.designs)} designs, {kind}", fontsize=style.FONT)
        ax2.set_xlabel("total ratio of the design [-]", fontsize=style.FONT)
        ax2.set_ylabel(OBJECTIVE_LABEL, fontsize=style.FONT)
        ax2.legend(fontsize=style.SMALL, loc="upper right", framealpha=0.9)
        ax2.ticklabel_format(axis="y", useOffset=False)
    return style.finish(fig)


def stage_model_figure(stage_set: Any, models: dict[str, Any], *, module: float | None = None,
                       title: str | None = None, length: str = "mm") -> Figure:
    """Phi/d of each model at the feasible stages' ratios, and the centre distance a_w(u).

    ``models`` maps a label to a :class:`~symkin.mechanisms.multistage.lostmotion.StageErrorModel`; with
    ``module`` (in ``length`` units), a right axis shows each stage's centre distance.

    >>> from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    >>> from symkin.mechanisms.multistage.stages import enumerate_stages
    >>> fig = stage_model_figure(enumerate_stages(100, 4, zmin=15), {"a + b u": StageErrorModel.linear(1, 1)}, module=1)
    >>> len(fig.axes)
    2
    """
    fig = style.new_figure(style.COLUMN * 1.6, 4.0)
    ax = fig.add_subplot()
    style.style_axes(ax)
    u = np.array([float(s.ratio) for s in stage_set])
    grid = np.linspace(u.min(), u.max(), 200)
    for label, model in models.items():
        f = model.numeric()
        (line,) = ax.plot(grid, [f(x) for x in grid], lw=1.2, label=label)
        ax.plot(u, [f(x) for x in u], "o", ms=3, color=line.get_color(), ls="none")
    ax.set_xlabel("stage ratio u [-]", fontsize=style.FONT)
    ax.set_ylabel(r"$\Phi_i / d_{3i-2}$ [model's unit]", fontsize=style.FONT)
    handles, labels = ax.get_legend_handles_labels()
    if module is not None:
        ax2 = ax.twinx()
        aw = [float(s.centre_distance) * module for s in stage_set]
        (line,) = ax2.plot(u, aw, "k^--", ms=3, lw=0.8, label="centre distance $a_w$")
        ax2.set_ylabel(f"centre distance $a_w$ [{length}]", fontsize=style.FONT)
        ax2.tick_params(labelsize=style.SMALL)
        handles.append(line)
        labels.append(line.get_label())
    fig.legend(handles, labels, fontsize=style.SMALL, loc="outside lower center", ncol=1, frameon=False)
    ax.set_title(title or f"{len(stage_set)} feasible stages", fontsize=style.FONT)
    return style.finish(fig)


def _fmt(values: Any) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in values) + ")"
