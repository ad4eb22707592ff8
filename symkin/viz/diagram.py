"""Pictures of a train itself: its kinematic scheme in half section and its lever diagram.

:func:`diagram` draws what a train file says, so that a wrong carrier or mesh is seen
before a number looks odd:

- the **kinematic scheme** (VDI 2157 style, the papers' Fig. 1): the main axis at the
  bottom, only the half above it drawn, radii to scale in the unit of the module (mm).
  Each gear is its pitch outline in section: a gear on the main axis a bar from its
  shaft up to its pitch radius, a ring a band from its pitch radius out, a planet a bar
  across its pitch diameter about its axis; gears that mesh stand in one column and touch
  at their pitch radii, or (when they cannot share a column: two planets that mesh, two
  suns) are joined by a dotted mesh line.  Every link on the main axis has a shaft at a
  level of its own under the suns; a carrier's arms rise from its shaft to its planets'
  axles; gears on the frame and brakes reach up to the housing; a clutch joins two
  shafts.  Bevel pinions stand on radial axes, their side gears on either side.
- the **lever diagram** (Benford and Leising 1981, :mod:`symkin.trains.lever`): each
  lever a vertical bar with a node for each link, spaced by tooth numbers; for a state
  the held nodes are grounded and each node's speed per unit input speed is drawn as a
  horizontal arrow: the arrow tips lie on a straight line.

One-way clutches are drawn like a brake or a clutch with a roller between the races; with a
state, one that holds is highlighted and one that overruns dashed.  Planetary sets joined by a
single link (the ZF 8HP's four) are separate levers side by side on one speed scale; a state
no one-way clutch holds is free and drawn without speeds.

Elements carry SVG ids (``gear:NAME``, ``mesh:A-B``, ``link:NAME``, ``brake:LINK``,
``clutch:A+B``, ``oneway:NAME``, ``node:NAME``, ``speed:NAME``, ``ground:NAME``; on a diagram
of several levers ``node:NAME@K`` for lever K) so that a drawing can be read back.

    >>> from symkin.trains import load_train
    >>> fig = diagram(load_train("simple"), state="low")
    >>> sorted(t.get_text() for t in fig.axes[0].texts if t.get_gid() and t.get_gid().startswith("link:"))
    ['C (out)', 'P', 'R', 'S (in)', 'frame']
"""

from __future__ import annotations

import contextlib
import itertools
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import sympy as sp
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from symkin import symbols as S
from symkin.errors import InputError
from symkin.model import FRAME, LinkKind, Mechanism
from symkin.viz import style

__all__ = ["diagram", "scheme_figure", "lever_figure", "scheme_svg", "text_as_text", "LENGTH_UNITS"]

#: Units a drawn length may be given in, as a factor from millimetres (the module's unit).
LENGTH_UNITS = {"mm": 1.0, "cm": 0.1, "m": 0.001, "in": 1 / 25.4}
_INK, _GREY, _ON = "#000000", "0.6", style.PALETTE[1]
_IN, _OUT = style.PALETTE[0], style.PALETTE[2]
#: A one-way clutch that overruns in the state shown (dashed; one that holds has the highlight colour).
_OVERRUN = style.PALETTE[5]
#: A gear label's box: white under the text, so that lines behind it do not cross it.
_CLEAR = {"boxstyle": "square,pad=0.1", "facecolor": "white", "edgecolor": "none", "alpha": 0.85}


def _name(link: str) -> str:
    return "frame" if link == FRAME else link


def _number(value: Any, what: str) -> float:
    value = sp.sympify(value)
    if value.free_symbols:
        raise InputError(f"{what} is {value}, not a number: a train with symbolic tooth numbers or module cannot be "
                         "drawn; give numbers (symkin synthesize finds them)")
    return float(value)


@dataclass
class _Gear:
    name: str
    link: str
    r: float
    y0: float  # radial position of its axis
    internal: bool
    lo: float  # radial extent in the half section
    hi: float
    column: int = 0


# --------------------------------------------------------------------------- the scheme
class _Scheme:
    """Where every element of a train's half section goes (in mm, before the unit's scale)."""

    def __init__(self, mech: Mechanism):
        self.mech = mech
        self.radial = [L for L in mech.links if L.axis == "radial"]
        self.y0: dict[str, float] = {}
        for L in mech.links:
            self.y0[L.name] = self._axis_radius(L.name)
        gears: dict[str, _Gear] = {}
        for L in mech.links:
            if L.axis == "radial":
                continue
            for g in L.gears:
                if g.bevel:  # a side gear: drawn beside its pinions
                    continue
                r = _number(g.radius, f"the pitch radius of gear {g.name}")
                gears[g.name] = _Gear(g.name, L.name, r, self.y0[L.name], g.internal, 0.0, 0.0)
        self.gears = gears
        self.R = max([g.y0 + g.r for g in gears.values()] + [1e-9])
        for L in self.radial:  # bevel pinions reach out to their side gears
            for mesh in mech.meshes:
                geo = mech.mesh_geometry(mesh)
                if geo.kind == "bevel" and L.name in (geo.link_a.name, geo.link_b.name):
                    self.R = max(self.R, _number(geo.centre_distance, "a bevel mesh's radius"))
        self.band = 0.07 * self.R
        for gg in gears.values():
            if gg.internal:
                gg.lo, gg.hi = gg.r, gg.r + self.band
            elif gg.y0 > 0:
                gg.lo, gg.hi = gg.y0 - gg.r, gg.y0 + gg.r
            else:
                gg.lo, gg.hi = 0.0, gg.r
        self._columns()
        self._levels()

    def _axis_radius(self, link: str) -> float:
        """A planet's axis at its carrier's radius plus its arm (nested carriers unfolded in the section)."""
        L = self.mech.link(link)
        if L.kind is not LinkKind.PLANET or L.axis == "radial":
            return 0.0
        assert L.carrier is not None
        return self._axis_radius(L.carrier) + _number(self.mech.arm(L.name), f"the arm of planet {L.name}")

    def _fits(self, g: _Gear, column: int, placed: dict[int, list[_Gear]]) -> bool:
        tol = 1e-9 * self.R
        return all(min(g.hi, o.hi) - max(g.lo, o.lo) <= tol and o.link != g.link
                   for o in placed.get(column, []))

    def _columns(self) -> None:
        placed: dict[int, list[_Gear]] = {}
        done: set[str] = set()

        def put(g: _Gear, near: int) -> None:
            for step in range(0, 4 * len(self.gears) + 2):
                c = near + (step + 1) // 2 * (1 if step % 2 else -1) if step else near
                if self._fits(g, c, placed):
                    break
            g.column = c
            placed.setdefault(c, []).append(g)
            done.add(g.name)

        bevel = {m for m in self.mech.meshes if self.mech.mesh_geometry(m).kind == "bevel"}
        for mesh in self.mech.meshes:
            if mesh in bevel:
                continue
            a, b = self.gears[mesh.a], self.gears[mesh.b]
            if a.name not in done and b.name not in done:
                put(a, max(placed, default=-1) + 1)
            if a.name not in done:
                a, b = b, a
            if b.name not in done:
                put(b, a.column)
        for g in self.gears.values():
            if g.name not in done:
                put(g, max(placed, default=-1) + 1)
        # bevel pinions: a wide column each, after the others
        self.pinion_column: dict[str, int] = {}
        for L in self.radial:
            self.pinion_column[L.name] = max(placed, default=-1) + 1
            placed[self.pinion_column[L.name]] = []
        order = sorted(placed)
        renumber = {c: k for k, c in enumerate(order)}
        for g in self.gears.values():
            g.column = renumber[g.column]
        self.pinion_column = {n: renumber[c] for n, c in self.pinion_column.items()}
        self.W = 0.45 * self.R
        self.w = 0.3 * self.W
        self.gap = 0.09 * self.W
        widths = [self.W] * len(order)
        self.pinions: dict[str, float] = {}
        for L in self.radial:
            rp = max(_number(g.radius, f"the pitch radius of gear {g.name}") for g in L.gears)
            self.pinions[L.name] = rp
            widths[self.pinion_column[L.name]] = 2 * rp + 2 * self.W
        self.x: list[float] = []
        at = 0.0
        for wd in widths:
            self.x.append(at + wd / 2)
            at += wd
        self.x_end = at

    def _levels(self) -> None:
        """A shaft level for each link on the main axis (inner shafts of the smaller gears lowest)."""
        central = [L for L in self.mech.links if L.kind is LinkKind.CENTRAL]

        def key(L: Any) -> tuple[float, int]:
            ext = [g.r for g in self.gears.values() if g.link == L.name and not g.internal]
            ring = [g.r for g in self.gears.values() if g.link == L.name and g.internal]
            return (min(ext) if ext else (2 * self.R + min(ring) if ring else self.R), 0)

        central.sort(key=key)
        inner = min([g.r for g in self.gears.values() if g.y0 == 0 and not g.internal] + [0.6 * self.R])
        self.delta = inner / (len(central) + 1)
        self.level = {L.name: (k + 1) * self.delta for k, L in enumerate(central)}
        for L in self.mech.links:
            if L.kind is LinkKind.PLANET:
                self.level[L.name] = self.y0[L.name]
        self.housing = 1.12 * self.R + self.band


def _rect(ax: Any, x0: float, y0: float, w: float, h: float, gid: str, k: float, **kw: Any) -> Any:
    patch = Rectangle((x0 * k, y0 * k), w * k, h * k, fill=False, lw=kw.pop("lw", 1.0), **kw)
    patch.set_gid(gid)
    ax.add_patch(patch)
    return patch


def _line(ax: Any, xs: list[float], ys: list[float], k: float, gid: str | None = None, **kw: Any) -> Any:
    (line,) = ax.plot([x * k for x in xs], [y * k for y in ys], **{"color": _INK, "lw": 0.9, **kw})
    if gid:
        line.set_gid(gid)
    return line


def _ground(ax: Any, x: float, y: float, size: float, k: float) -> None:
    """A short hatched line: fixed to the frame (the housing)."""
    _line(ax, [x - size, x + size], [y, y], k, lw=1.2)
    for j in range(4):
        xx = x - size + j * size * 2 / 3
        _line(ax, [xx, xx + size * 0.5], [y, y + size * 0.6], k, lw=0.6)


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


def _controls(mech: Mechanism) -> tuple[list[str], list[tuple[str, str]]]:
    """Every brake and clutch the train's states use, in file order (links by their own names)."""
    brakes: list[str] = []
    clutches: list[tuple[str, str]] = []
    for st in getattr(mech, "states", ()):
        for b in st.brakes:
            name = mech.link(b).name
            if name != FRAME and name not in brakes:
                brakes.append(name)
        for a, b in st.clutches:
            pair = (mech.link(a).name, mech.link(b).name)
            if pair not in clutches and pair[::-1] not in clutches:
                clutches.append(pair)
    return brakes, clutches


def scheme_figure(mech: Mechanism, state: Any = None, *, length_unit: str = "mm", title: str | None = None) -> Figure:
    """The kinematic scheme of ``mech`` in half section (see the module docstring).

    ``state`` (a name or a :class:`~symkin.trains.State`) highlights its engaged brakes and
    clutches and marks its input and output; lengths are drawn in ``length_unit`` (the
    module's numbers are millimetres).
    """
    k = _unit(length_unit)
    st = _state_of(mech, state)
    sc = _Scheme(mech)
    brakes, clutches = _controls(mech)
    x_ctrl: dict[Any, float] = {}
    at = sc.x_end
    for b in brakes:
        x_ctrl[("B", b)] = at + sc.W / 2
        at += sc.W
    for pair in clutches:
        x_ctrl[("K", pair)] = at + sc.W / 2
        at += sc.W
    one_ways = tuple(getattr(mech, "one_ways", ()))
    for ow in one_ways:
        x_ctrl[("F", ow.name)] = at + sc.W / 2
        at += sc.W
    x_left = -0.9 * sc.W
    height = sc.housing + sc.band
    width_in = style.PAGE
    height_in = min(6.5, max(2.6, 0.92 * width_in * height / (at - x_left + 1.8 * sc.W) + 0.75))
    fig = style.new_figure(width_in, height_in)
    ax = fig.add_subplot()
    ax.set_aspect("equal", adjustable="box")
    for edge in ("top", "right", "bottom"):
        ax.spines[edge].set_visible(False)
    ax.xaxis.set_visible(False)
    ax.tick_params(labelsize=style.SMALL)
    ax.set_ylabel(style.label("radius", length_unit), fontsize=style.FONT)
    _line(ax, [x_left, at], [0, 0], k, gid="axis:main", lw=0.6, ls=(0, (8, 2, 1, 2)), color=_GREY)
    shift = mech.shift(st) if st is not None and one_ways else None  # type: ignore[attr-defined]
    status = dict(shift.drive.status) if shift is not None and shift.drive is not None else {}
    engaged_b = {mech.link(b).name for b in st.brakes} if st else set()
    engaged_k = {frozenset((mech.link(a).name, mech.link(b).name)) for a, b in st.clutches} if st else set()
    inp = mech.link(st.input).name if st else None
    out = mech.link(st.output).name if st else None

    def colour(link: str) -> str:
        return _IN if link == inp else _OUT if link == out else _INK

    reach: dict[str, list[float]] = {L.name: [] for L in mech.links}  # x where each link meets its shaft
    # gears
    for g in sc.gears.values():
        x = sc.x[g.column]
        c = colour(g.link)
        if g.internal:
            _rect(ax, x - sc.w / 2, g.lo, sc.w, g.hi - g.lo, f"gear:{g.name}", k, color=c, hatch="////", lw=1.1)
            xs = x + sc.w / 2 + sc.gap
            if g.link == FRAME:
                _line(ax, [x, x], [g.hi, sc.housing], k, color=c)
                _ground(ax, x, sc.housing, sc.w / 2, k)
            else:
                _line(ax, [x + sc.w / 2, xs, xs], [g.hi, g.hi, sc.level[g.link]], k, color=c)
                reach[g.link].append(xs)
            ax.annotate(f"{g.name} ({_teeth(mech, g.name)})", (x * k, (g.hi + 0.3 * sc.band) * k), fontsize=style.SMALL,
                        ha="center", va="bottom", color="0.25", bbox=_CLEAR)
        else:
            bottom = g.lo if g.y0 > 0 or g.link == FRAME else sc.level.get(g.link, 0.0)
            wide = sc.w if g.y0 > 0 else 0.6 * sc.w  # planets wide and tinted, gears on the main axis narrow
            patch = _rect(ax, x - wide / 2, bottom, wide, g.hi - bottom, f"gear:{g.name}", k, color=c, lw=1.3)
            if g.y0 > 0:
                patch.set(fill=True, facecolor="0.92", zorder=1.5)
            if g.link == FRAME:
                xs = x + sc.w / 2 + sc.gap
                _line(ax, [x + wide / 2, xs, xs], [g.hi, g.hi, sc.housing], k, color=c)
                _ground(ax, xs, sc.housing, sc.w / 2, k)
            elif g.y0 == 0:
                reach[g.link].append(x)
            ax.annotate(f"{g.name} ({_teeth(mech, g.name)})", ((x + sc.w / 2 + 1.6 * sc.gap) * k, (g.hi - 0.5 * sc.delta) * k),
                        fontsize=style.SMALL, ha="left", va="top", color="0.25", bbox=_CLEAR)
    # planets: axles through their gears, arms from their carriers
    label_at: dict[str, tuple[float, float, str]] = {}
    for L in mech.links:
        if L.kind is not LinkKind.PLANET or L.axis == "radial":
            continue
        cols = [sc.x[g.column] for g in sc.gears.values() if g.link == L.name]
        if not cols:
            continue
        assert L.carrier is not None
        xa = min(cols) - sc.w / 2 - sc.gap
        y = sc.y0[L.name]
        c_carrier = colour(L.carrier)
        _line(ax, [xa, max(cols) + sc.w / 2 + sc.gap / 2], [y, y], k, gid=f"axle:{L.name}", color=colour(L.name), lw=0.8)
        _line(ax, [xa, xa], [sc.level[L.carrier], y], k, gid=f"arm:{L.name}", color=c_carrier, lw=1.3)
        reach[L.carrier].append(xa)
        reach[L.name].append(max(cols))
        label_at[L.name] = (xa - sc.gap / 2, y, "right")
    # bevel pinions and their side gears
    for L in sc.radial:
        xc = sc.x[sc.pinion_column[L.name]]
        assert L.carrier is not None
        rims: list[Any] = []
        sides: list[int] = []
        for mesh in mech.meshes:
            geo = mech.mesh_geometry(mesh)
            if geo.kind != "bevel" or L.name not in (geo.link_a.name, geo.link_b.name):
                continue
            pin, side, side_link = (geo.gear_a, geo.gear_b, geo.link_b) if geo.link_a.name == L.name else \
                (geo.gear_b, geo.gear_a, geo.link_a)
            rim = _number(pin.radius, f"the pitch radius of gear {pin.name}")
            yc = _number(geo.centre_distance, "a bevel mesh's radius")
            up = pin.name not in rims and all(abs(yc - y) > sc.w for y in rims[1::2])
            if pin.name not in rims:
                y_rim = yc if up else yc - sc.w
                _rect(ax, xc - rim, y_rim, 2 * rim, sc.w, f"gear:{pin.name}", k, color=colour(L.name), lw=1.3)
                ax.annotate(f"{pin.name} ({_teeth(mech, pin.name)})", ((xc - rim) * k, (y_rim + sc.w * 1.15) * k),
                            fontsize=style.SMALL, ha="right", va="bottom", color="0.25", bbox=_CLEAR)
                rims += [pin.name, yc]
            offset = side.side * sides.count(side.side) * (sc.w + sc.gap)  # a second side gear on one side: beside
            sides.append(side.side)
            xs = xc + side.side * rim + offset
            c = colour(side_link.name)
            _rect(ax, min(xs, xs + side.side * sc.w), sc.level.get(side_link.name, 0.0), sc.w,
                  yc - sc.level.get(side_link.name, 0.0), f"gear:{side.name}", k, color=c, lw=1.3)
            if side_link.name == FRAME:
                xg = xs + side.side * (sc.w + sc.gap)
                _line(ax, [xs + side.side * sc.w, xg, xg], [yc, yc, sc.housing], k, color=c)
                _ground(ax, xg, sc.housing, sc.w / 2, k)
            else:
                reach[side_link.name].append(xs + side.side * sc.w / 2)
            ax.annotate(f"{side.name} ({_teeth(mech, side.name)})", ((xs + side.side * sc.w * 1.3) * k, yc * 0.55 * k),
                        fontsize=style.SMALL, ha="left" if side.side > 0 else "right", va="center", color="0.25", bbox=_CLEAR)
            _line(ax, [xs - offset, xs], [yc, yc], k, gid=f"mesh:{mesh.a}-{mesh.b}", lw=1.0, ls=":", color=_INK,
                  marker="o", markersize=2.5)
        top = max(y for y in rims[1::2]) + sc.w
        _line(ax, [xc, xc], [sc.level.get(L.carrier, 0.0), top], k, gid=f"arm:{L.name}",
              color=colour(L.carrier), lw=1.3)
        reach[L.carrier].append(xc)
        label_at[L.name] = (xc - sc.gap, top + 0.3 * sc.band, "right")
    # meshes
    for mesh in mech.meshes:
        if mesh.a not in sc.gears or mesh.b not in sc.gears:
            continue
        ga, gb = sc.gears[mesh.a], sc.gears[mesh.b]
        xa, xb = sc.x[ga.column], sc.x[gb.column]
        if ga.column == gb.column:  # touching: the pitch point
            y = ga.hi if abs(ga.hi - gb.lo) < abs(gb.hi - ga.lo) else ga.lo
            if ga.internal or gb.internal:
                y = (ga if ga.internal else gb).lo
            _line(ax, [xa - sc.w / 2, xa + sc.w / 2], [y, y], k, gid=f"mesh:{mesh.a}-{mesh.b}", lw=2.4, color=_INK)
        else:  # the pitch circles meet out of the section: a dotted line between the two
            ya = (ga.lo + ga.hi) / 2 if not ga.internal else ga.lo
            yb = (gb.lo + gb.hi) / 2 if not gb.internal else gb.lo
            sa = sc.w / 2 if xb > xa else -sc.w / 2
            _line(ax, [xa + sa, xb - sa], [ya, yb], k, gid=f"mesh:{mesh.a}-{mesh.b}", lw=1.0, ls=":", color=_INK,
                  marker="o", markersize=2.5)
    # brakes and clutches
    for b in brakes:
        x = x_ctrl[("B", b)]
        on = b in engaged_b
        c, lw = (_ON, 2.0) if on else (_GREY, 1.0)
        y = sc.level[b]
        mid = (y + sc.housing) / 2
        _line(ax, [x, x], [y, mid - sc.band / 2], k, gid=f"brake:{b}", color=c, lw=lw)
        _line(ax, [x - sc.w / 2, x + sc.w / 2], [mid - sc.band / 2] * 2, k, color=c, lw=lw + 0.6)
        _line(ax, [x - sc.w / 2, x + sc.w / 2], [mid + sc.band / 2] * 2, k, color=c, lw=lw + 0.6)
        _line(ax, [x, x], [mid + sc.band / 2, sc.housing], k, color=c, lw=lw)
        _ground(ax, x, sc.housing, sc.w / 2, k)
        reach[b].append(x)
        ax.annotate(f"B{brakes.index(b) + 1}", ((x + sc.w / 2 + sc.gap / 2) * k, mid * k), fontsize=style.SMALL,
                    ha="left", va="center", color=c if on else "0.3")
    for pair in clutches:
        x = x_ctrl[("K", pair)]
        on = frozenset(pair) in engaged_k
        c, lw = (_ON, 2.0) if on else (_GREY, 1.0)
        ya, yb = sorted((sc.level[pair[0]], sc.level[pair[1]]))
        mid = (ya + yb) / 2
        h = min(sc.delta / 4, (yb - ya) / 4)
        _line(ax, [x, x], [ya, mid - h], k, gid=f"clutch:{pair[0]}+{pair[1]}", color=c, lw=lw)
        _line(ax, [x, x], [mid + h, yb], k, color=c, lw=lw)
        for yy in (mid - h, mid + h):
            _line(ax, [x - sc.w / 2, x + sc.w / 2], [yy, yy], k, color=c, lw=lw + 0.6)
        for n in pair:
            reach[n].append(x)
        ax.annotate(f"K{clutches.index(pair) + 1}", ((x + sc.w / 2 + sc.gap / 2) * k, mid * k), fontsize=style.SMALL,
                    ha="left", va="center", color=c if on else "0.3")
    for ow in one_ways:  # like a brake or a clutch, with a roller between its races: a freewheel
        x = x_ctrl[("F", ow.name)]
        part = status.get(ow.name)
        c, lw, ls = {"holds": (_ON, 2.0, "-"), "overruns": (_OVERRUN, 1.2, "--")}.get(part or "", (_GREY, 1.0, "-"))
        ends = [sc.housing if n == FRAME else sc.level[mech.link(n).name] for n in (ow.link, ow.other)]
        ya, yb = sorted(ends)
        mid = (ya + yb) / 2
        h = min(sc.delta / 3, (yb - ya) / 4) if FRAME not in (ow.link, ow.other) else sc.band
        _line(ax, [x, x], [ya, mid - h], k, gid=f"oneway:{ow.name}", color=c, lw=lw, ls=ls)
        _line(ax, [x, x], [mid + h, yb], k, color=c, lw=lw, ls=ls)
        for yy in (mid - h, mid + h):
            _line(ax, [x - sc.w / 2, x + sc.w / 2], [yy, yy], k, color=c, lw=lw + 0.6)
        _line(ax, [x - sc.w / 3, x + sc.w / 3], [mid - 0.7 * h, mid + 0.7 * h], k, color=c, lw=0.8)  # the sprag
        ax.plot([x * k], [mid * k], marker="o", markersize=3.5, markerfacecolor="white", color=c)  # the roller
        for n in (ow.link, ow.other):
            if n == FRAME:
                _ground(ax, x, sc.housing, sc.w / 2, k)
            else:
                reach[mech.link(n).name].append(x)
        t = ax.text((x + sc.w / 2 + sc.gap / 2) * k, mid * k, f"{ow.name} (one-way)", fontsize=style.SMALL, ha="left",
                    va="center", color=c if part in ("holds", "overruns") else "0.3")
        t.set_gid(f"oneway-name:{ow.name}")
    # shafts of the links on the main axis, named at their left ends
    for L in mech.links:
        if L.kind is not LinkKind.CENTRAL:
            continue
        y = sc.level[L.name]
        ends = reach[L.name] or [0.0]
        _line(ax, [x_left, max(ends)], [y, y], k, gid=f"shaft:{L.name}", color=colour(L.name),
              lw=1.6 if L.name in (inp, out) else 1.0)
        label_at[L.name] = (x_left - sc.gap / 2, y, "right")
    if any(L.kind is LinkKind.FRAME and L.gears for L in mech.links) or brakes or \
            any(FRAME in (ow.link, ow.other) for ow in one_ways):
        label_at[FRAME] = (x_left - sc.gap / 2, sc.housing, "right")
        _line(ax, [x_left, x_left + sc.w], [sc.housing, sc.housing], k, lw=0.6, color=_GREY)
    for name, (x, y, ha) in label_at.items():
        word = _name(name) + (" (in)" if name == inp else " (out)" if name == out else "")
        t = ax.text(x * k, y * k, word, fontsize=style.FONT, ha=ha, va="center", fontweight="bold", color=colour(name))
        t.set_gid(f"link:{_name(name)}")
    ax.set_xlim((x_left - 2.2 * sc.W) * k, (at + 0.2 * sc.W) * k)
    ax.set_ylim(-0.04 * sc.R * k, (sc.housing + 1.5 * sc.band) * k)
    shafts = {f"link:{L.name}": sc.level[L.name] for L in mech.links if L.kind is LinkKind.CENTRAL}
    texts = [t for t in ax.texts if t.get_text()]
    stack = sorted((t for t in texts if t.get_gid() in shafts), key=lambda t: shafts[str(t.get_gid())])
    renderer = _renderer(fig)
    tall = max([t.get_window_extent(renderer).height for t in stack] + [0.0]) * 1.15
    tall = (ax.transData.inverted().transform((0, tall))[1] - ax.transData.inverted().transform((0, 0))[1]) / k
    spread = False
    for below, t in itertools.pairwise(stack):  # shaft names in the shafts' order, a line apart
        y_text = max(t.get_position()[1] / k, below.get_position()[1] / k + tall)
        spread = spread or y_text > t.get_position()[1] / k + 1e-9
        t.set_y(y_text * k)
    if _declutter(fig, ax, texts) or spread:  # names moved apart: each shaft's name on a leader to its shaft
        for t in texts:
            if t.get_gid() in shafts:
                y_text = t.get_position()[1]
                t.set_x((x_left - 0.45 * sc.W) * k)
                _line(ax, [x_left - 0.42 * sc.W, x_left - 0.2 * sc.W, x_left], [y_text / k, y_text / k,
                      shafts[str(t.get_gid())]], k, color="0.6", lw=0.4)
    name = getattr(mech, "name", "") or "mechanism"
    head = title or f"{name}: kinematic scheme (half section)"
    if st is not None:
        parts = [f"B{brakes.index(b) + 1} holds {b}" for b in brakes if b in engaged_b]
        parts += [f"K{clutches.index(p) + 1} joins {p[0]}+{p[1]}" for p in clutches if frozenset(p) in engaged_k]
        parts += [f"{name} {part}" for name, part in status.items()]
        head += f"\nstate {st.name}: {', '.join(parts) or 'no brake or clutch'}"
        if shift is not None and shift.speeds is None:
            head += "; free: no one-way clutch holds it in drive, no ratio"
    ax.set_title(head, fontsize=style.FONT)
    return style.finish(fig)


def _renderer(fig: Figure) -> Any:
    """``fig`` drawn (laid out), and its renderer to measure text with."""
    if not hasattr(fig.canvas, "get_renderer"):
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        FigureCanvasAgg(fig)
    fig.canvas.draw()
    return fig.canvas.get_renderer()  # type: ignore[attr-defined]


def _declutter(fig: Figure, ax: Any, texts: list[Any], pad: float = 2.0) -> bool:
    """Move overlapping texts of ``ax`` apart vertically (each pair by half its overlap, in a few
    rounds), as drawn in ``fig``; True if any moved."""
    renderer = _renderer(fig)
    to_data = ax.transData.inverted()
    floor = ax.transData.transform((0, 0))[1]  # none goes below the main axis
    moved = False
    for _ in range(80):
        boxes = [t.get_window_extent(renderer) for t in texts]
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


def _teeth(mech: Mechanism, gear: str) -> str:
    z = mech.gear(gear).teeth
    return f"z={z}" if z is not None else "r"


def _unit(length_unit: str) -> float:
    if length_unit not in LENGTH_UNITS:
        raise InputError(f"unknown length unit {length_unit!r}; choose one of {', '.join(LENGTH_UNITS)}")
    return LENGTH_UNITS[length_unit]


# --------------------------------------------------------------------------- the levers
def _spread(ys: list[float], gap: float) -> list[float]:
    """``ys`` (sorted) moved apart to at least ``gap``, as little as possible, centred as they were."""
    out = list(ys)
    for i in range(1, len(out)):
        out[i] = max(out[i], out[i - 1] + gap)
    shift = (sum(ys) - sum(out)) / len(out) if out else 0.0
    return [y + shift for y in out]


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
    speeds: dict[str, Any] = {}
    free = False
    held = {FRAME}
    joined_pairs: list[tuple[str, str]] = []
    if st is not None:
        shift = mech.shift(st)  # type: ignore[attr-defined]
        brakes, joined_pairs = _engaged(mech, st, shift)
        held |= {mech.link(b).name for b in brakes}
        free = shift.speeds is None  # no one-way clutch holds it in drive: no ratio, no speeds
        if not free:
            w_in = S.omega(mech.link(st.input).name)
            speeds = {n: sp.cancel(v / w_in) for n, v in shift.speeds.items()}
            speeds[FRAME] = sp.Integer(0)
    inp = mech.link(st.input).name if st else None
    out = mech.link(st.output).name if st else None
    n = len(found)
    fig = style.new_figure(min(style.PAGE, 2.4 * n + 1.2), 3.4)
    axes = fig.subplots(1, n, squeeze=False, sharex=True)[0]  # one speed scale: joined nodes' arrows compare
    numeric = {nm: float(v) for nm, v in speeds.items() if not sp.sympify(v).free_symbols}
    wmax = max([abs(numeric[nm]) for lv in found for nm in lv.positions if nm in numeric] + [1.0])
    for index, (lever, ax) in enumerate(zip(found, axes), 1):
        tag = f"@{index}" if n > 1 else ""  # a link on two levers (a single link joins them): one id per lever
        pos = lever.positions
        lo, hi = min(pos.values()), max(pos.values())
        span = hi - lo or 1
        ys = {nm: (x - lo) / span for nm, x in pos.items()}  # 0 .. 1, to scale
        ax.set_ylim(-0.12, 1.12)
        for edge in ("top", "right", "left"):
            ax.spines[edge].set_visible(False)
        ax.yaxis.set_visible(False)
        ax.tick_params(labelsize=style.SMALL)
        ax.plot([0, 0], [0, 1], color=_INK, lw=2.2, solid_capstyle="round")
        vals = {nm: numeric[nm] for nm in pos if nm in numeric}
        ax.set_xlim(-2.3 * wmax, 1.4 * wmax)
        order = sorted(pos, key=lambda nm: ys[nm])
        label_y = _spread([ys[nm] for nm in order], 0.075)
        for nm, ly in zip(order, label_y):
            y = ys[nm]
            (node,) = ax.plot([-0.06 * wmax, 0.06 * wmax], [y, y], color=_INK, lw=1.2)
            node.set_gid(f"node:{_name(nm)}{tag}")
            word = _name(nm) + (" (in)" if nm == inp else " (out)" if nm == out else "")
            c = _IN if nm == inp else _OUT if nm == out else _INK
            t = ax.text(-0.95 * wmax, ly, word, fontsize=style.FONT, ha="right", va="center", color=c, fontweight="bold")
            ax.plot([-0.92 * wmax, -0.75 * wmax, -0.08 * wmax], [ly, ly, y], color="0.6", lw=0.4)  # a leader
            t.set_gid(f"name:{_name(nm)}{tag}")
            if nm in held and st is not None:
                (ground,) = ax.plot([-0.3 * wmax, -0.1 * wmax], [y, y], color=_ON, lw=2.0)
                ground.set_gid(f"ground:{_name(nm)}{tag}")
                for j in range(3):
                    xx = -0.3 * wmax + j * 0.08 * wmax
                    ax.plot([xx, xx - 0.05 * wmax], [y, y - 0.03], color=_ON, lw=0.7)
            if nm in vals:
                (arrow,) = ax.plot([0, vals[nm]], [y, y], color=c if c != _INK else style.PALETTE[3], lw=1.6)
                arrow.set_gid(f"speed:{_name(nm)}{tag}")
                ax.plot([vals[nm]], [y], marker=">" if vals[nm] >= 0 else "<", color=arrow.get_color(), markersize=4)
        # spacing of neighbouring nodes, in tooth-number units, between the names and the bar
        gaps = [(a, b) for a, b in itertools.pairwise(order) if pos[b] != pos[a]]
        gap_y = _spread([(ys[a] + ys[b]) / 2 for a, b in gaps], 0.075)
        for (a, b), gy in zip(gaps, gap_y):
            ax.text(-0.4 * wmax, gy, f"{pos[b] - pos[a]}", fontsize=style.SMALL, color="0.35", ha="right", va="center",
                    fontstyle="italic")
        if len(vals) >= 2:
            line = lever.speed_line({nm: speeds[nm] for nm in pos if nm in vals})
            if line is not None:
                a0, b0 = (float(v) for v in line)
                xs = [a0 + b0 * (lo + span * y) for y in (0.0, 1.0)]
                ax.plot(xs, [0, 1], color="0.4", lw=0.7, ls="--")
        if n > 1:
            ax.set_title(f"lever {index}", fontsize=style.SMALL)
        if st is not None and not free:
            ax.set_xlabel(style.label("speed / input speed", "-"), fontsize=style.FONT)
            ax.axvline(0, color="0.85", lw=0.5, zorder=0)
        else:
            ax.xaxis.set_visible(False)
            ax.spines["bottom"].set_visible(False)
    name = getattr(mech, "name", "") or "mechanism"
    head = title or f"{name}: lever diagram (node spacing by tooth numbers)"
    if st is not None:
        head += f"\nstate {st.name}: {_name(inp or '')} drives, {_name(out or '')} driven"
        joined = [f"{_name(mech.link(a).name)}+{_name(mech.link(b).name)}" for a, b in joined_pairs]
        if joined:
            head += f", {', '.join(joined)} joined"
        if free:
            head += "; free: no one-way clutch holds it in drive, no ratio, no node speeds"
    if n > 1:
        head += "\n(a link on two levers joins them: its nodes turn at one speed)"
    fig.suptitle(head, fontsize=style.FONT)
    return style.finish(fig)


def diagram(train: Mechanism, state: Any = None, *, lever: bool = False, length_unit: str = "mm") -> Figure:
    """The kinematic scheme of ``train`` (or with ``lever``, its lever diagram), for ``state`` if given.

    A :class:`~symkin.trains.Train` from a file, or any :class:`~symkin.model.Mechanism`
    with numeric radii; ``length_unit`` is the unit of the scheme's radii (the module's
    numbers are millimetres).  Returns a matplotlib figure (save it with
    :func:`symkin.viz.figures.save`; SVG with :func:`text_as_text` keeps the names as text).
    """
    if lever:
        return lever_figure(train, state)
    return scheme_figure(train, state, length_unit=length_unit)


@contextlib.contextmanager
def text_as_text() -> Iterator[None]:
    """Inside, SVG files keep text as ``<text>`` elements (searchable, read back by tests) and
    get ids that do not change from run to run."""
    import matplotlib as mpl

    with mpl.rc_context({"svg.fonttype": "none", "svg.hashsalt": "symkin"}):
        yield


def scheme_svg(mech: Mechanism, state: Any = None) -> str:
    """The kinematic scheme as SVG text (for Jupyter, ``_repr_html_``), or ``""`` where it cannot be
    drawn (symbolic tooth numbers or radii).

    >>> from symkin.trains import load_train
    >>> scheme_svg(load_train("simple")).startswith("<svg")
    True
    """
    import io

    try:
        fig = scheme_figure(mech, state)
    except InputError:
        return ""
    buffer = io.StringIO()
    with text_as_text():
        fig.savefig(buffer, format="svg", metadata={"Date": None})
    text = buffer.getvalue()
    return text[text.index("<svg"):]
