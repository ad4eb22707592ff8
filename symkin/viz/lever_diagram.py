"""The lever diagram of a train (Benford and Leising 1981, :mod:`symkin.trains.lever`): each lever a
vertical bar with a node for each link, spaced by tooth numbers; for a state the held nodes are
grounded and each node's speed per unit input speed is drawn as a horizontal arrow, the arrow tips
on a straight line.  Planetary sets joined by a single link are levers side by side on one speed
scale; a state no one-way clutch holds is free and drawn without speeds.

:func:`symkin.viz.diagram.diagram` draws it with ``lever=True`` (and :func:`lever_figure` is
importable from :mod:`symkin.viz.diagram` too); the names, colours and states this module reads
are shared with the kinematic scheme there.

    >>> from symkin.trains import load_train
    >>> fig = lever_figure(load_train("simple"), "low")
    >>> sorted(t.get_text() for t in fig.axes[0].texts if (t.get_gid() or "").startswith("name:"))
    ['C (out)', 'R', 'S (in)']
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

import sympy as sp
from matplotlib.figure import Figure

from symkin import symbols as S
from symkin.errors import InputError
from symkin.model import FRAME, Mechanism
from symkin.viz import style

__all__ = ["lever_figure"]

#: Ink, the highlight of what holds, and the input's and output's colours (the scheme's too).
_INK, _ON = "#000000", style.PALETTE[1]
_IN, _OUT = style.PALETTE[0], style.PALETTE[2]


def _name(link: str) -> str:
    return "frame" if link == FRAME else link


def _state_of(mech: Mechanism, state: Any) -> Any:
    if state is None:
        return None
    if not hasattr(mech, "state"):
        raise InputError("a mechanism without states has no state to show; load a train file")
    return mech.state(state) if isinstance(state, str) else state


def _engaged(mech: Mechanism, st: Any, shift: Any) -> tuple[tuple[str, ...], list[tuple[str, str]]]:
    """The brakes and clutch pairs that hold ``st`` in drive: its own and the one-way clutches that
    engage (:meth:`~symkin.trains.Train.engaged`); its own alone when it is free."""
    if getattr(mech, "one_ways", ()) and shift.speeds is not None:
        brakes, clutches = mech.engaged(st)  # type: ignore[attr-defined]
    else:
        brakes, clutches = st.brakes, st.clutches
    return tuple(brakes), [(mech.link(a).name, mech.link(b).name) for a, b in clutches]


def _spread(ys: list[float], gap: float) -> list[float]:
    """``ys`` (sorted) moved apart to at least ``gap``, as little as possible, centred as they were."""
    out = list(ys)
    for i in range(1, len(out)):
        out[i] = max(out[i], out[i - 1] + gap)
    shift = (sum(ys) - sum(out)) / len(out) if out else 0.0
    return [y + shift for y in out]


@dataclass
class _Speeds:
    """What the levers of one state share: each link's speed per unit input speed (``numeric``: those
    that are numbers), the held links, the input and output, and the speed scale ``wmax``."""

    speeds: dict[str, Any] = field(default_factory=dict)
    numeric: dict[str, float] = field(default_factory=dict)
    held: set[str] = field(default_factory=lambda: {FRAME})
    joined: list[tuple[str, str]] = field(default_factory=list)
    shown: bool = False  # a state is shown
    free: bool = False  # no one-way clutch holds it in drive: no ratio, no speeds
    inp: str | None = None
    out: str | None = None
    wmax: float = 1.0


def _lever_speeds(mech: Mechanism, st: Any) -> _Speeds:
    """The speeds, held links and joined pairs of state ``st`` (none if it is None)."""
    sv = _Speeds()
    if st is None:
        return sv
    shift = mech.shift(st)  # type: ignore[attr-defined]
    brakes, sv.joined = _engaged(mech, st, shift)
    sv.held |= {mech.link(b).name for b in brakes}
    sv.shown, sv.free = True, shift.speeds is None
    if not sv.free:
        w_in = S.omega(mech.link(st.input).name)
        sv.speeds = {n: sp.cancel(v / w_in) for n, v in shift.speeds.items()}
        sv.speeds[FRAME] = sp.Integer(0)
    sv.inp, sv.out = mech.link(st.input).name, mech.link(st.output).name
    sv.numeric = {nm: float(v) for nm, v in sv.speeds.items() if not sp.sympify(v).free_symbols}
    return sv


def lever_figure(mech: Mechanism, state: Any = None, *, title: str | None = None) -> Figure:
    """The lever diagram of ``mech`` (Benford and Leising): one bar per lever, nodes spaced by
    tooth numbers; with ``state``, held nodes grounded and each node's speed per unit input
    speed as a horizontal arrow, the arrow tips on one straight line."""
    from symkin.trains.lever import levers

    st = _state_of(mech, state)
    found = levers(mech)
    if not found:
        raise InputError("this train has no lever to draw (its tooth numbers are symbolic, or no set of meshes "
                         "shares a carrier)")
    sv = _lever_speeds(mech, st)
    n = len(found)
    fig = style.new_figure(min(style.PAGE, 2.4 * n + 1.2), 3.4)
    axes = fig.subplots(1, n, squeeze=False, sharex=True)[0]  # one speed scale: joined nodes' arrows compare
    sv.wmax = max([abs(sv.numeric[nm]) for lv in found for nm in lv.positions if nm in sv.numeric] + [1.0])
    for index, (lever, ax) in enumerate(zip(found, axes), 1):
        _draw_lever(ax, lever, sv, f"@{index}" if n > 1 else "")  # a link on two levers: one id per lever
        if n > 1:
            ax.set_title(f"lever {index}", fontsize=style.SMALL)
        if st is not None and not sv.free:
            ax.set_xlabel(style.label("speed / input speed", "-"), fontsize=style.FONT)
            ax.axvline(0, color="0.85", lw=0.5, zorder=0)
        else:
            ax.xaxis.set_visible(False)
            ax.spines["bottom"].set_visible(False)
    name = getattr(mech, "name", "") or "mechanism"
    head = title or f"{name}: lever diagram (node spacing by tooth numbers)"
    if st is not None:
        head += f"\nstate {st.name}: {_name(sv.inp or '')} drives, {_name(sv.out or '')} driven"
        joined = [f"{_name(mech.link(a).name)}+{_name(mech.link(b).name)}" for a, b in sv.joined]
        if joined:
            head += f", {', '.join(joined)} joined"
        if sv.free:
            head += "; free: no one-way clutch holds it in drive, no ratio, no node speeds"
    if n > 1:
        head += "\n(a link on two levers joins them: its nodes turn at one speed)"
    fig.suptitle(head, fontsize=style.FONT)
    return style.finish(fig)


def _draw_lever(ax: Any, lever: Any, sv: _Speeds, tag: str) -> None:
    """One lever in ``ax``: its bar, its named nodes to scale, the node spacing in tooth numbers,
    and for a state held nodes grounded, speed arrows and the straight line through their tips."""
    pos = lever.positions
    lo, hi = min(pos.values()), max(pos.values())
    span = hi - lo or 1
    ys = {nm: (x - lo) / span for nm, x in pos.items()}  # 0 .. 1, to scale
    wmax = sv.wmax
    ax.set_ylim(-0.12, 1.12)
    for edge in ("top", "right", "left"):
        ax.spines[edge].set_visible(False)
    ax.yaxis.set_visible(False)
    ax.tick_params(labelsize=style.SMALL)
    ax.plot([0, 0], [0, 1], color=_INK, lw=2.2, solid_capstyle="round")
    vals = {nm: sv.numeric[nm] for nm in pos if nm in sv.numeric}
    ax.set_xlim(-2.3 * wmax, 1.4 * wmax)
    order = sorted(pos, key=lambda nm: ys[nm])
    for nm, ly in zip(order, _spread([ys[nm] for nm in order], 0.075)):
        _draw_node(ax, nm, ys[nm], ly, vals.get(nm), sv, tag)
    # spacing of neighbouring nodes, in tooth-number units, between the names and the bar
    gaps = [(a, b) for a, b in itertools.pairwise(order) if pos[b] != pos[a]]
    gap_y = _spread([(ys[a] + ys[b]) / 2 for a, b in gaps], 0.075)
    for (a, b), gy in zip(gaps, gap_y):
        ax.text(-0.4 * wmax, gy, f"{pos[b] - pos[a]}", fontsize=style.SMALL, color="0.35", ha="right", va="center",
                fontstyle="italic")
    if len(vals) >= 2:
        line = lever.speed_line({nm: sv.speeds[nm] for nm in pos if nm in vals})
        if line is not None:
            a0, b0 = (float(v) for v in line)
            xs = [a0 + b0 * (lo + span * y) for y in (0.0, 1.0)]
            ax.plot(xs, [0, 1], color="0.4", lw=0.7, ls="--")


def _draw_node(ax: Any, nm: str, y: float, ly: float, speed: float | None, sv: _Speeds, tag: str) -> None:
    """Node ``nm`` at ``y`` on the bar, its name at ``ly`` on a leader, grounded if held, its speed an arrow."""
    wmax = sv.wmax
    (node,) = ax.plot([-0.06 * wmax, 0.06 * wmax], [y, y], color=_INK, lw=1.2)
    node.set_gid(f"node:{_name(nm)}{tag}")
    word = _name(nm) + (" (in)" if nm == sv.inp else " (out)" if nm == sv.out else "")
    c = _IN if nm == sv.inp else _OUT if nm == sv.out else _INK
    t = ax.text(-0.95 * wmax, ly, word, fontsize=style.FONT, ha="right", va="center", color=c, fontweight="bold")
    ax.plot([-0.92 * wmax, -0.75 * wmax, -0.08 * wmax], [ly, ly, y], color="0.6", lw=0.4)  # a leader
    t.set_gid(f"name:{_name(nm)}{tag}")
    if nm in sv.held and sv.shown:
        (ground,) = ax.plot([-0.3 * wmax, -0.1 * wmax], [y, y], color=_ON, lw=2.0)
        ground.set_gid(f"ground:{_name(nm)}{tag}")
        for j in range(3):
            xx = -0.3 * wmax + j * 0.08 * wmax
            ax.plot([xx, xx - 0.05 * wmax], [y, y - 0.03], color=_ON, lw=0.7)
    if speed is not None:
        (arrow,) = ax.plot([0, speed], [y, y], color=c if c != _INK else style.PALETTE[3], lw=1.6)
        arrow.set_gid(f"speed:{_name(nm)}{tag}")
        ax.plot([speed], [y], marker=">" if speed >= 0 else "<", color=arrow.get_color(), markersize=4)
