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
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import sympy as sp
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from symkin.errors import InputError
from symkin.model import FRAME, LinkKind, Mechanism
from symkin.viz import labels, style
from symkin.viz.lever_diagram import _IN, _INK, _ON, _OUT, _name, _state_of, lever_figure

__all__ = ["diagram", "scheme_figure", "lever_figure", "scheme_svg", "text_as_text", "LENGTH_UNITS"]

#: Units a drawn length may be given in, as a factor from millimetres (the module's unit).
LENGTH_UNITS = {"mm": 1.0, "cm": 0.1, "m": 0.001, "in": 1 / 25.4}
_GREY = "0.6"
#: A one-way clutch that overruns in the state shown (dashed; one that holds has the highlight colour).
_OVERRUN = style.PALETTE[5]
#: A gear label's box: white under the text, so that lines behind it do not cross it.
_CLEAR = {"boxstyle": "square,pad=0.1", "facecolor": "white", "edgecolor": "none", "alpha": 0.85}


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
        self.y0: dict[str, float] = {L.name: self._axis_radius(L.name) for L in mech.links}
        self.gears = self._spur_gears()
        self.R = self._outer_radius()
        self.band = 0.07 * self.R
        for gg in self.gears.values():
            if gg.internal:
                gg.lo, gg.hi = gg.r, gg.r + self.band
            elif gg.y0 > 0:
                gg.lo, gg.hi = gg.y0 - gg.r, gg.y0 + gg.r
            else:
                gg.lo, gg.hi = 0.0, gg.r
        self._columns()
        self._levels()

    def _spur_gears(self) -> dict[str, _Gear]:
        """The gears drawn in the section: all but the bevel pinions' and the bevel side gears."""
        gears: dict[str, _Gear] = {}
        for L in self.mech.links:
            if L.axis == "radial":
                continue
            for g in L.gears:
                if g.bevel:  # a side gear: drawn beside its pinions
                    continue
                r = _number(g.radius, f"the pitch radius of gear {g.name}")
                gears[g.name] = _Gear(g.name, L.name, r, self.y0[L.name], g.internal, 0.0, 0.0)
        return gears

    def _outer_radius(self) -> float:
        """How far the section reaches from the main axis: the gears' outer pitch circles, the bevel meshes."""
        R = max([g.y0 + g.r for g in self.gears.values()] + [1e-9])
        for L in self.radial:  # bevel pinions reach out to their side gears
            for mesh in self.mech.meshes:
                geo = self.mech.mesh_geometry(mesh)
                if geo.kind == "bevel" and L.name in (geo.link_a.name, geo.link_b.name):
                    R = max(R, _number(geo.centre_distance, "a bevel mesh's radius"))
        return R

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
        placed = self._place_gears()
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
        self._column_positions(len(order))

    def _place_gears(self) -> dict[int, list[_Gear]]:
        """Each spur gear in a column (a mesh's gears in one where they fit), by column."""
        placed: dict[int, list[_Gear]] = {}
        done: set[str] = set()
        bevel = {m for m in self.mech.meshes if self.mech.mesh_geometry(m).kind == "bevel"}
        for mesh in self.mech.meshes:
            if mesh in bevel:
                continue
            a, b = self.gears[mesh.a], self.gears[mesh.b]
            if a.name not in done and b.name not in done:
                self._put(a, max(placed, default=-1) + 1, placed, done)
            if a.name not in done:
                a, b = b, a
            if b.name not in done:
                self._put(b, a.column, placed, done)
        for g in self.gears.values():
            if g.name not in done:
                self._put(g, max(placed, default=-1) + 1, placed, done)
        return placed

    def _put(self, g: _Gear, near: int, placed: dict[int, list[_Gear]], done: set[str]) -> None:
        """Gear ``g`` in the column nearest ``near`` where it fits (tried on either side in turn)."""
        for step in range(0, 4 * len(self.gears) + 2):
            c = near + (step + 1) // 2 * (1 if step % 2 else -1) if step else near
            if self._fits(g, c, placed):
                break
        g.column = c
        placed.setdefault(c, []).append(g)
        done.add(g.name)

    def _column_positions(self, columns: int) -> None:
        """The columns' widths (a bevel pinion's holds its pitch diameter) and their centres ``x``."""
        self.W = 0.45 * self.R
        self.w = 0.3 * self.W
        self.gap = 0.09 * self.W
        widths = [self.W] * columns
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


@dataclass
class _Drawing:
    """What the parts of a scheme share: its layout, the axes, the unit's scale ``k``, the state's
    input and output links, where each link meets its shaft (``reach``) and where links are named."""

    mech: Mechanism
    sc: _Scheme
    ax: Any
    k: float
    inp: str | None = None
    out: str | None = None
    reach: dict[str, list[float]] = field(default_factory=dict)
    label_at: dict[str, tuple[float, float, str]] = field(default_factory=dict)

    def colour(self, link: str) -> str:
        return _IN if link == self.inp else _OUT if link == self.out else _INK

    def line(self, xs: list[float], ys: list[float], gid: str | None = None, **kw: Any) -> Any:
        return _line(self.ax, xs, ys, self.k, gid, **kw)

    def rect(self, x0: float, y0: float, w: float, h: float, gid: str, **kw: Any) -> Any:
        return _rect(self.ax, x0, y0, w, h, gid, self.k, **kw)

    def ground(self, x: float) -> None:
        """Fixed to the housing at ``x``."""
        _ground(self.ax, x, self.sc.housing, self.sc.w / 2, self.k)

    def gear_name(self, gear: str, x: float, y: float, ha: str, va: str) -> None:
        self.ax.annotate(f"{gear} ({_teeth(self.mech, gear)})", (x * self.k, y * self.k), fontsize=style.SMALL, ha=ha,
                         va=va, color="0.25", bbox=_CLEAR)


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
    one_ways = tuple(getattr(mech, "one_ways", ()))
    x_ctrl, at = _control_columns(sc, brakes, clutches, one_ways)
    x_left = -0.9 * sc.W
    fig, ax = _scheme_axes(sc, x_left, at, length_unit)
    _line(ax, [x_left, at], [0, 0], k, gid="axis:main", lw=0.6, ls=(0, (8, 2, 1, 2)), color=_GREY)
    shift = mech.shift(st) if st is not None and one_ways else None  # type: ignore[attr-defined]
    status = dict(shift.drive.status) if shift is not None and shift.drive is not None else {}
    engaged_b = {mech.link(b).name for b in st.brakes} if st else set()
    engaged_k = {frozenset((mech.link(a).name, mech.link(b).name)) for a, b in st.clutches} if st else set()
    d = _Drawing(mech, sc, ax, k, mech.link(st.input).name if st else None, mech.link(st.output).name if st else None,
                 {L.name: [] for L in mech.links})  # x where each link meets its shaft
    for g in sc.gears.values():
        (_draw_ring if g.internal else _draw_gear)(d, g)
    _draw_planets(d)
    for L in sc.radial:
        _draw_bevel(d, L)
    _draw_meshes(d)
    for b in brakes:
        _draw_brake(d, b, x_ctrl[("B", b)], f"B{brakes.index(b) + 1}", b in engaged_b)
    for pair in clutches:
        _draw_clutch(d, pair, x_ctrl[("K", pair)], f"K{clutches.index(pair) + 1}", frozenset(pair) in engaged_k)
    for ow in one_ways:
        _draw_one_way(d, ow, x_ctrl[("F", ow.name)], status.get(ow.name))
    _draw_shafts(d, x_left, bool(brakes) or any(FRAME in (ow.link, ow.other) for ow in one_ways))
    ax.set_xlim((x_left - 2.2 * sc.W) * k, (at + 0.2 * sc.W) * k)
    ax.set_ylim(-0.04 * sc.R * k, (sc.housing + 1.5 * sc.band) * k)
    _place_names(fig, d, x_left)
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


def _control_columns(sc: _Scheme, brakes: list[str], clutches: list[tuple[str, str]],
                     one_ways: tuple[Any, ...]) -> tuple[dict[Any, float], float]:
    """A column after the gears for each brake, clutch and one-way clutch; and where the last ends."""
    x_ctrl: dict[Any, float] = {}
    at = sc.x_end
    for key in [("B", b) for b in brakes] + [("K", p) for p in clutches] + [("F", ow.name) for ow in one_ways]:
        x_ctrl[key] = at + sc.W / 2
        at += sc.W
    return x_ctrl, at


def _scheme_axes(sc: _Scheme, x_left: float, at: float, length_unit: str) -> tuple[Figure, Any]:
    """A figure the page wide, as high as the section needs, and its axes: radius up, no x axis."""
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
    return fig, ax


def _draw_ring(d: _Drawing, g: _Gear) -> None:
    """A ring gear: a hatched band from its pitch radius out, on its shaft or on the housing."""
    sc = d.sc
    x = sc.x[g.column]
    c = d.colour(g.link)
    d.rect(x - sc.w / 2, g.lo, sc.w, g.hi - g.lo, f"gear:{g.name}", color=c, hatch="////", lw=1.1)
    xs = x + sc.w / 2 + sc.gap
    if g.link == FRAME:
        d.line([x, x], [g.hi, sc.housing], color=c)
        d.ground(x)
    else:
        d.line([x + sc.w / 2, xs, xs], [g.hi, g.hi, sc.level[g.link]], color=c)
        d.reach[g.link].append(xs)
    d.gear_name(g.name, x, g.hi + 0.3 * sc.band, "center", "bottom")


def _draw_gear(d: _Drawing, g: _Gear) -> None:
    """An external gear: on the main axis a narrow bar from its shaft, a planet a wide tinted bar."""
    sc = d.sc
    x = sc.x[g.column]
    c = d.colour(g.link)
    bottom = g.lo if g.y0 > 0 or g.link == FRAME else sc.level.get(g.link, 0.0)
    wide = sc.w if g.y0 > 0 else 0.6 * sc.w  # planets wide and tinted, gears on the main axis narrow
    patch = d.rect(x - wide / 2, bottom, wide, g.hi - bottom, f"gear:{g.name}", color=c, lw=1.3)
    if g.y0 > 0:
        patch.set(fill=True, facecolor="0.92", zorder=1.5)
    if g.link == FRAME:
        xs = x + sc.w / 2 + sc.gap
        d.line([x + wide / 2, xs, xs], [g.hi, g.hi, sc.housing], color=c)
        d.ground(xs)
    elif g.y0 == 0:
        d.reach[g.link].append(x)
    d.gear_name(g.name, x + sc.w / 2 + 1.6 * sc.gap, g.hi - 0.5 * sc.delta, "left", "top")


def _draw_planets(d: _Drawing) -> None:
    """Planets: axles through their gears, arms from their carriers."""
    sc = d.sc
    for L in d.mech.links:
        if L.kind is not LinkKind.PLANET or L.axis == "radial":
            continue
        cols = [sc.x[g.column] for g in sc.gears.values() if g.link == L.name]
        if not cols:
            continue
        assert L.carrier is not None
        xa = min(cols) - sc.w / 2 - sc.gap
        y = sc.y0[L.name]
        d.line([xa, max(cols) + sc.w / 2 + sc.gap / 2], [y, y], gid=f"axle:{L.name}", color=d.colour(L.name), lw=0.8)
        d.line([xa, xa], [sc.level[L.carrier], y], gid=f"arm:{L.name}", color=d.colour(L.carrier), lw=1.3)
        d.reach[L.carrier].append(xa)
        d.reach[L.name].append(max(cols))
        d.label_at[L.name] = (xa - sc.gap / 2, y, "right")


def _draw_bevel(d: _Drawing, L: Any) -> None:
    """A bevel pinion on its radial axis, its side gears on either side, its carrier's arm."""
    sc, mech = d.sc, d.mech
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
            d.rect(xc - rim, y_rim, 2 * rim, sc.w, f"gear:{pin.name}", color=d.colour(L.name), lw=1.3)
            d.gear_name(pin.name, xc - rim, y_rim + sc.w * 1.15, "right", "bottom")
            rims += [pin.name, yc]
        offset = side.side * sides.count(side.side) * (sc.w + sc.gap)  # a second side gear on one side: beside
        sides.append(side.side)
        xs = xc + side.side * rim + offset
        _draw_side_gear(d, side, side_link.name, xs, yc)
        d.line([xs - offset, xs], [yc, yc], gid=f"mesh:{mesh.a}-{mesh.b}", lw=1.0, ls=":", color=_INK, marker="o",
               markersize=2.5)
    top = max(y for y in rims[1::2]) + sc.w
    d.line([xc, xc], [sc.level.get(L.carrier, 0.0), top], gid=f"arm:{L.name}", color=d.colour(L.carrier), lw=1.3)
    d.reach[L.carrier].append(xc)
    d.label_at[L.name] = (xc - sc.gap, top + 0.3 * sc.band, "right")


def _draw_side_gear(d: _Drawing, side: Any, link: str, xs: float, yc: float) -> None:
    """A bevel side gear at ``xs``, from its shaft up to the pinions' axis ``yc`` (on the housing if fixed)."""
    sc = d.sc
    c = d.colour(link)
    d.rect(min(xs, xs + side.side * sc.w), sc.level.get(link, 0.0), sc.w, yc - sc.level.get(link, 0.0),
           f"gear:{side.name}", color=c, lw=1.3)
    if link == FRAME:
        xg = xs + side.side * (sc.w + sc.gap)
        d.line([xs + side.side * sc.w, xg, xg], [yc, yc, sc.housing], color=c)
        d.ground(xg)
    else:
        d.reach[link].append(xs + side.side * sc.w / 2)
    d.gear_name(side.name, xs + side.side * sc.w * 1.3, yc * 0.55, "left" if side.side > 0 else "right", "center")


def _draw_meshes(d: _Drawing) -> None:
    """Gears that mesh in one column touch at their pitch point; in two, a dotted line joins them."""
    sc = d.sc
    for mesh in d.mech.meshes:
        if mesh.a not in sc.gears or mesh.b not in sc.gears:
            continue
        ga, gb = sc.gears[mesh.a], sc.gears[mesh.b]
        xa, xb = sc.x[ga.column], sc.x[gb.column]
        if ga.column == gb.column:  # touching: the pitch point
            y = ga.hi if abs(ga.hi - gb.lo) < abs(gb.hi - ga.lo) else ga.lo
            if ga.internal or gb.internal:
                y = (ga if ga.internal else gb).lo
            d.line([xa - sc.w / 2, xa + sc.w / 2], [y, y], gid=f"mesh:{mesh.a}-{mesh.b}", lw=2.4, color=_INK)
        else:  # the pitch circles meet out of the section: a dotted line between the two
            ya = (ga.lo + ga.hi) / 2 if not ga.internal else ga.lo
            yb = (gb.lo + gb.hi) / 2 if not gb.internal else gb.lo
            sa = sc.w / 2 if xb > xa else -sc.w / 2
            d.line([xa + sa, xb - sa], [ya, yb], gid=f"mesh:{mesh.a}-{mesh.b}", lw=1.0, ls=":", color=_INK, marker="o",
                   markersize=2.5)


def _draw_brake(d: _Drawing, b: str, x: float, tag: str, on: bool) -> None:
    """Brake ``tag`` from link ``b``'s shaft up to the housing: two plates, highlighted when ``on``."""
    sc = d.sc
    c, lw = (_ON, 2.0) if on else (_GREY, 1.0)
    y = sc.level[b]
    mid = (y + sc.housing) / 2
    d.line([x, x], [y, mid - sc.band / 2], gid=f"brake:{b}", color=c, lw=lw)
    d.line([x - sc.w / 2, x + sc.w / 2], [mid - sc.band / 2] * 2, color=c, lw=lw + 0.6)
    d.line([x - sc.w / 2, x + sc.w / 2], [mid + sc.band / 2] * 2, color=c, lw=lw + 0.6)
    d.line([x, x], [mid + sc.band / 2, sc.housing], color=c, lw=lw)
    d.ground(x)
    d.reach[b].append(x)
    d.ax.annotate(tag, ((x + sc.w / 2 + sc.gap / 2) * d.k, mid * d.k), fontsize=style.SMALL, ha="left", va="center",
                  color=c if on else "0.3")


def _draw_clutch(d: _Drawing, pair: tuple[str, str], x: float, tag: str, on: bool) -> None:
    """Clutch ``tag`` between the shafts of ``pair``: two plates, highlighted when ``on``."""
    sc = d.sc
    c, lw = (_ON, 2.0) if on else (_GREY, 1.0)
    ya, yb = sorted((sc.level[pair[0]], sc.level[pair[1]]))
    mid = (ya + yb) / 2
    h = min(sc.delta / 4, (yb - ya) / 4)
    d.line([x, x], [ya, mid - h], gid=f"clutch:{pair[0]}+{pair[1]}", color=c, lw=lw)
    d.line([x, x], [mid + h, yb], color=c, lw=lw)
    for yy in (mid - h, mid + h):
        d.line([x - sc.w / 2, x + sc.w / 2], [yy, yy], color=c, lw=lw + 0.6)
    for n in pair:
        d.reach[n].append(x)
    d.ax.annotate(tag, ((x + sc.w / 2 + sc.gap / 2) * d.k, mid * d.k), fontsize=style.SMALL, ha="left", va="center",
                  color=c if on else "0.3")


def _draw_one_way(d: _Drawing, ow: Any, x: float, part: str | None) -> None:
    """A one-way clutch like a brake or a clutch, with a roller between its races (a freewheel):
    highlighted if it holds in the state shown, dashed if it overruns."""
    sc, mech = d.sc, d.mech
    c, lw, ls = {"holds": (_ON, 2.0, "-"), "overruns": (_OVERRUN, 1.2, "--")}.get(part or "", (_GREY, 1.0, "-"))
    ends = [sc.housing if n == FRAME else sc.level[mech.link(n).name] for n in (ow.link, ow.other)]
    ya, yb = sorted(ends)
    mid = (ya + yb) / 2
    h = min(sc.delta / 3, (yb - ya) / 4) if FRAME not in (ow.link, ow.other) else sc.band
    d.line([x, x], [ya, mid - h], gid=f"oneway:{ow.name}", color=c, lw=lw, ls=ls)
    d.line([x, x], [mid + h, yb], color=c, lw=lw, ls=ls)
    for yy in (mid - h, mid + h):
        d.line([x - sc.w / 2, x + sc.w / 2], [yy, yy], color=c, lw=lw + 0.6)
    d.line([x - sc.w / 3, x + sc.w / 3], [mid - 0.7 * h, mid + 0.7 * h], color=c, lw=0.8)  # the sprag
    d.ax.plot([x * d.k], [mid * d.k], marker="o", markersize=3.5, markerfacecolor="white", color=c)  # the roller
    for n in (ow.link, ow.other):
        if n == FRAME:
            d.ground(x)
        else:
            d.reach[mech.link(n).name].append(x)
    t = d.ax.text((x + sc.w / 2 + sc.gap / 2) * d.k, mid * d.k, f"{ow.name} (one-way)", fontsize=style.SMALL,
                  ha="left", va="center", color=c if part in ("holds", "overruns") else "0.3")
    t.set_gid(f"oneway-name:{ow.name}")


def _draw_shafts(d: _Drawing, x_left: float, housing: bool) -> None:
    """The shafts of the links on the main axis, out to where their parts meet them; the links
    named at their left ends (and the frame at the housing's, if ``housing`` or a gear holds it)."""
    sc = d.sc
    for L in d.mech.links:
        if L.kind is not LinkKind.CENTRAL:
            continue
        y = sc.level[L.name]
        ends = d.reach[L.name] or [0.0]
        d.line([x_left, max(ends)], [y, y], gid=f"shaft:{L.name}", color=d.colour(L.name),
               lw=1.6 if L.name in (d.inp, d.out) else 1.0)
        d.label_at[L.name] = (x_left - sc.gap / 2, y, "right")
    if any(L.kind is LinkKind.FRAME and L.gears for L in d.mech.links) or housing:
        d.label_at[FRAME] = (x_left - sc.gap / 2, sc.housing, "right")
        d.line([x_left, x_left + sc.w], [sc.housing, sc.housing], lw=0.6, color=_GREY)
    for name, (x, y, ha) in d.label_at.items():
        word = _name(name) + (" (in)" if name == d.inp else " (out)" if name == d.out else "")
        t = d.ax.text(x * d.k, y * d.k, word, fontsize=style.FONT, ha=ha, va="center", fontweight="bold",
                      color=d.colour(name))
        t.set_gid(f"link:{_name(name)}")


def _place_names(fig: Figure, d: _Drawing, x_left: float) -> None:
    """Shaft names in the shafts' order a line apart, then every text clear of the others; where
    names moved, each shaft's name on a leader to its shaft."""
    sc, ax, k = d.sc, d.ax, d.k
    shafts = {f"link:{L.name}": sc.level[L.name] for L in d.mech.links if L.kind is LinkKind.CENTRAL}
    texts = [t for t in ax.texts if t.get_text()]
    spread = labels.stack(fig, ax, sorted((t for t in texts if t.get_gid() in shafts),
                                          key=lambda t: shafts[str(t.get_gid())]), k)
    if labels.declutter(fig, ax, texts) or spread:
        for t in texts:
            if t.get_gid() in shafts:
                y_text = t.get_position()[1]
                t.set_x((x_left - 0.45 * sc.W) * k)
                d.line([x_left - 0.42 * sc.W, x_left - 0.2 * sc.W, x_left], [y_text / k, y_text / k,
                       shafts[str(t.get_gid())]], color="0.6", lw=0.4)


def _teeth(mech: Mechanism, gear: str) -> str:
    z = mech.gear(gear).teeth
    return f"z={z}" if z is not None else "r"


def _unit(length_unit: str) -> float:
    if length_unit not in LENGTH_UNITS:
        raise InputError(f"unknown length unit {length_unit!r}; choose one of {', '.join(LENGTH_UNITS)}")
    return LENGTH_UNITS[length_unit]


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
