"""Torques, tooth forces, power flow and efficiency of any train, in closed form.

**Ideal statics.**  The contact condition of each mesh is linear in the link speeds:
``c_a (omega_a - omega_k) + c_b (omega_b - omega_k) = 0`` in the frame of the link ``k``
that holds both gears' axes (a planet's carrier), where ``c`` are the pitch-point levers.
By virtual power, the tangential tooth force ``F`` of the mesh puts the torques ``F c_a``
on gear a's link, ``F c_b`` on gear b's and ``-F (c_a + c_b)`` on ``k`` (through the
planet's bearing).  Every moving link is in equilibrium: the torques of its meshes and
the external torque on it (1 on the input, the unknown load on the output, the reactions
of the held links, a clutch's torque) sum to zero.  Solving these equations gives every
torque per unit input torque and every tooth force, symbolically.

**Losses: the basic-train (relative-power) method** (Müller; Kudryavtsev; Pennestrì and
Freudenstein 1993; del Castillo 2002).  In the frame of ``k`` a mesh transmits the
relative power ``F c_a (omega_a - omega_k)``; the gear that delivers it drives, and the
driven gear receives ``eta`` times its force: ``F_driven = eta F_driving``.  Which gear
drives is decided from the ideal solution and the kinematics (the sign of the relative
power for a positive input power); where it depends on the tooth numbers the efficiency
law is piecewise and says on what.  The efficiency is ``-T_out omega_out / (T_in
omega_in)``; driven backwards (output to input), a train whose efficiency would be zero
or negative locks itself.

    >>> from symkin.trains import load_train
    >>> st = statics(load_train("simple"), input="S", output="C", fixed=("R",))
    >>> st.torques["C"], st.torques["R"]        # per unit torque on the sun
    (-4, 3)
    >>> st.efficiency.rhs                       # each mesh's efficiency a symbol
    (3*eta_pr*eta_sp + 1)/4
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin._util.display import html_table, short_repr
from symkin._util.jsonout import exact_json, float_text
from symkin.errors import InputError, ModelError, UnderdeterminedError
from symkin.kinematics import solve_speeds
from symkin.laws import Law
from symkin.model import FRAME, LinkKind, Mechanism, Mesh
from symkin.values import as_real

__all__ = ["MeshPower", "Statics", "statics", "efficiency_symbol", "DEFAULT_EFFICIENCY"]

#: Default mesh efficiencies (per mesh, when none is given): an external spur mesh loses
#: more than an internal one of the same teeth (more sliding); override per mesh.
DEFAULT_EFFICIENCY = {"external": sp.Rational(98, 100), "internal": sp.Rational(99, 100)}
#: The default pressure angle for radial tooth forces.
DEFAULT_PRESSURE_ANGLE = sp.pi / 9  # 20 degrees


def efficiency_symbol(mesh: Mesh) -> sp.Symbol:
    """eta_ab, the efficiency of the mesh of gears a and b.

    >>> efficiency_symbol(Mesh("s", "p"))
    eta_sp
    """
    return sp.Symbol(f"eta_{mesh.a}{mesh.b}", positive=True)


@dataclass(frozen=True)
class _Side:
    """A mesh seen by the statics: its gears' links, the link holding their axes, the levers."""

    mesh: Mesh
    a: str
    b: str
    holder: str
    c_a: sp.Expr
    c_b: sp.Expr
    relative_b: bool  # gear b's link speed is already relative to the holder (a bevel pinion)
    relative_a: bool
    internal: bool


def _sides(mech: Mechanism) -> list[_Side]:
    out = []
    for mesh in mech.meshes:
        geo = mech.mesh_geometry(mesh)
        if geo.kind == "bevel":
            pinion_is_a = geo.link_a.axis == "radial"
            c_side, c_pin = geo.centre_distance, geo.pitch_y
            c_a, c_b = (c_pin, c_side) if pinion_is_a else (c_side, c_pin)
            out.append(_Side(mesh, geo.link_a.name, geo.link_b.name, geo.holder, c_a, c_b, not pinion_is_a, pinion_is_a, False))
            continue
        # velocities relative to the holder at the pitch point (eq. 5 in its frame): the condition
        # -pitch_y (w_a - w_k) + (pitch_y - d) (w_b - w_k) = 0 of symkin.kinematics, term by term
        c_a, c_b = -geo.pitch_y, geo.pitch_y - geo.centre_distance
        out.append(_Side(mesh, geo.link_a.name, geo.link_b.name, geo.holder, c_a, c_b, False, False,
                         geo.gear_a.internal or geo.gear_b.internal))
    return out


@dataclass(frozen=True)
class MeshPower:
    """What one mesh carries, per unit input torque and unit input speed.

    Attributes
    ----------
    mesh : Mesh
    tangential : sympy expression
        The tangential tooth force on gear a's side (on the driving side with losses),
        for all planets of the kind together; ``per_planet`` divides by their count.
    per_planet : sympy expression
    radial : sympy expression
        ``|tangential| tan(alpha)`` at the pressure angle (the separating force).
    relative_power : sympy expression
        Power out of gear a into the mesh in the frame of the link holding both axes
        (what the mesh loses a share of): positive when gear a drives.
    power : sympy expression
        Power through the contact: the tooth force times the pitch point's velocity relative
        to the link holding both axes, counted from the driving gear (non-negative; ``Abs``
        where the driver depends on the teeth).  It depends on neither the order of the
        meshes nor the order of a mesh's gears.
    driver : str or None
        The gear that drives in the relative motion (None where no power passes, or where
        which one drives depends on the teeth).
    """

    mesh: Mesh
    tangential: sp.Expr
    per_planet: sp.Expr
    radial: sp.Expr
    relative_power: sp.Expr
    power: sp.Expr
    driver: str | None

    def to_json(self) -> dict[str, Any]:
        """The mesh as JSON: its tangential, per-planet and radial forces, the power relative to the carrier, the power, and which gear drives."""
        return {"mesh": [self.mesh.a, self.mesh.b], "tangential": exact_json(self.tangential),
                "per_planet": exact_json(self.per_planet), "radial": exact_json(self.radial),
                "relative_power": exact_json(self.relative_power), "power": exact_json(self.power), "driver": self.driver}


@dataclass(frozen=True)
class Statics:
    """The statics and efficiency of a train in one configuration (see :func:`statics`).

    Attributes
    ----------
    mechanism : Mechanism
    input, output : str
    fixed : tuple of str
    joined : tuple of (str, str)
    speeds : dict
        Each link's speed per unit input speed.
    torques : dict
        The external torque on each link per unit input torque, ideal: 1 on the input, the
        output's load, the held links' reactions; 0 on links without a shaft.
    meshes : tuple of MeshPower
        Ideal tooth forces and powers.
    efficiency : Law
        ``eta = -T_out omega_out / (T_in omega_in)`` with the mesh efficiencies (symbols
        ``eta_ab`` unless given): piecewise where the power flow depends on the teeth.
    lossy_torques : dict
        The external torques with the mesh losses.
    efficiencies : dict
        Each mesh's efficiency as used (a symbol or a number).
    circulating : sympy expression
        The largest power through a mesh (relative to its carrier, :attr:`MeshPower.power`)
        per unit input power: above 1, the meshes roll more power than the train transmits.
    housing, housing_with_losses : sympy expression
        The torque the housing (the frame, through the brakes and the gears fixed to it)
        puts on the train per unit input torque, ideal and with losses: ``-(T_in + T_out)``.
    pins : dict
        Planet -> ``(x, y)``: the force one planet's tooth forces put on its pin (bearing),
        ideal, per unit input torque over the radii's unit, in its carrier's frame at t = 0;
        derived when first asked for (with symbolic tooth numbers its simplification is long,
        and the efficiency of a synthesis does not need it).
    """

    mechanism: Mechanism
    input: str
    output: str
    fixed: tuple[str, ...]
    joined: tuple[tuple[str, str], ...]
    speeds: dict[str, sp.Expr]
    torques: dict[str, sp.Expr]
    meshes: tuple[MeshPower, ...]
    efficiency: Law
    lossy_torques: dict[str, sp.Expr]
    efficiencies: dict[str, sp.Expr]
    circulating: sp.Expr
    housing: sp.Expr = sp.Integer(0)
    housing_with_losses: sp.Expr = sp.Integer(0)
    pin_loads: Callable[[], dict[str, tuple[sp.Expr, sp.Expr]]] | None = field(default=None, repr=False, compare=False)
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    @property
    def pins(self) -> dict[str, tuple[sp.Expr, sp.Expr]]:
        """Planet -> ``(x, y)``, the load on its pin (see the class's attributes), derived once when asked."""
        if "pins" not in self._cache:
            self._cache["pins"] = {} if self.pin_loads is None else self.pin_loads()
        return self._cache["pins"]

    def __repr__(self) -> str:
        """``Statics('AI1', 1 -> H, fixed 4, eta = ...)``, under 200 characters."""
        return short_repr("Statics", repr(self.mechanism.name), f"{self.input} -> {self.output}",
                          f"fixed {', '.join(self.fixed) or '-'}", f"eta = {self.efficiency.rhs}")

    @property
    def backward(self) -> Statics:
        """The same train driven from the output (the input becomes the load)."""
        if "backward" not in self._cache:
            self._cache["backward"] = statics(self.mechanism, input=self.output, output=self.input, fixed=self.fixed,
                                              joined=self.joined, efficiency=self.efficiencies)
        return self._cache["backward"]

    @property
    def self_locking(self) -> sp.Expr | bool:
        """True when, driven from the output, the train's efficiency would be zero or below (it
        cannot be driven backwards); with symbolic efficiencies, the condition under which it does."""
        eta = self.backward.efficiency.rhs
        if eta.is_number:
            return bool(eta <= 0)
        condition = sp.Le(eta, 0) if isinstance(eta, sp.Piecewise) else sp.simplify(sp.Le(eta, 0))
        return bool(condition) if condition in (sp.true, sp.false) else condition

    def to_json(self) -> dict[str, Any]:
        """The result as JSON: torques, tooth forces, the power through each mesh and the efficiency both ways."""
        backward = self.backward
        locks = self.self_locking
        return {
            "input": self.input, "output": self.output, "fixed": list(self.fixed), "joined": [list(j) for j in self.joined],
            "ratio": exact_json(sp.cancel(1 / self.speeds[self.output])),
            "efficiency": exact_json(self.efficiency.rhs) if self.efficiency.rhs.is_number else str(self.efficiency.rhs),
            "efficiency_backward": exact_json(backward.efficiency.rhs) if backward.efficiency.rhs.is_number
            else str(backward.efficiency.rhs),
            "self_locking": locks if isinstance(locks, bool) else str(locks),
            "circulating_power": exact_json(self.circulating) if self.circulating.is_number else str(self.circulating),
            "mesh_efficiencies": {k: exact_json(v) if v.is_number else str(v) for k, v in self.efficiencies.items()},
            "torques": {k: exact_json(v) for k, v in self.torques.items()},
            "torques_with_losses": {k: exact_json(v) if v.is_number else str(v) for k, v in self.lossy_torques.items()},
            "housing_torque": exact_json(self.housing),
            "pin_loads": _pins_json(self.pins),
            "housing_torque_with_losses": exact_json(self.housing_with_losses) if self.housing_with_losses.is_number
            else str(self.housing_with_losses),
            "meshes": [m.to_json() for m in self.meshes],
        }

    def _repr_html_(self) -> str:
        """Efficiency both ways, self-locking and the meshes as HTML tables, for Jupyter.

        >>> from symkin import schemes
        >>> from symkin.statics import statics
        >>> "<td>self-locking</td>" in statics(schemes.single_row_AI(teeth=(20, 30, 80)), input="1", output="H",
        ...                                      fixed="4", efficiency=0.98)._repr_html_()
        True
        """

        def shown(v: Any) -> str:
            return f"${sp.latex(v)}$" + (f" = {float_text(v)}" if v.is_number else "")

        locks = self.self_locking
        held = f", {', '.join(self.fixed)} held" if self.fixed else ""
        rows = [(f"efficiency {self.input} &rarr; {self.output}", shown(self.efficiency.rhs)),
                (f"driven back {self.output} &rarr; {self.input}", shown(self.backward.efficiency.rhs)),
                ("self-locking", "yes" if locks is True else "no" if locks is False else f"when ${sp.latex(locks)}$"),
                ("circulating power / input power", shown(self.circulating))]
        summary = html_table(["", "per unit input torque and speed"], rows, raw_columns=(0, 1),
                             caption=f"{self.mechanism.name or 'train'}: {self.input} drives {self.output}{held}")
        meshes = html_table(["mesh", "tangential force", "per planet", "power", "driver"],
                            [(f"{m.mesh.a}-{m.mesh.b}", f"${sp.latex(m.tangential)}$", f"${sp.latex(m.per_planet)}$",
                              f"${sp.latex(m.power)}$", m.driver or "-") for m in self.meshes], raw_columns=(1, 2, 3))
        return summary + meshes

    def text(self) -> str:
        """The result as ``symkin efficiency`` prints it."""
        name = self.mechanism.name or "train"
        held = f", {', '.join(self.fixed)} held" if self.fixed else ""
        lines = [f"{name}: {self.input} drives {self.output}{held}; per unit input torque and speed"]
        eta, back = self.efficiency.rhs, self.backward.efficiency.rhs
        lines.append(f"efficiency   {self.input} -> {self.output}: {eta}" + (f" = {float_text(eta)}" if eta.is_number else ""))
        lines.append(f"driven back  {self.output} -> {self.input}: {back}" + (f" = {float_text(back)}" if back.is_number else ""))
        locks = self.self_locking
        lines.append("self-locking: " + ("yes, it cannot be driven from the output" if locks is True else "no" if locks is False
                                         else f"when {locks}"))
        if eta.is_number and eta <= 0:
            other = f"; {self.output} can drive {self.input}" if back.is_number and back > 0 else ""
            lines.append(f"this way it locks: {self.input} cannot drive {self.output} (efficiency zero or below){other}")
        if self.circulating.is_number and self.circulating > 1:
            lines.append(f"circulating power: a mesh carries {float_text(self.circulating)} times the input power "
                         "(relative to its carrier)")
        lines.append("torques (ideal): " + ", ".join(f"{k} {v}" for k, v in self.torques.items() if v != 0)
                     + f"; housing {self.housing}")
        lines.append("mesh           tangential    per planet    power      driver")
        for m in self.meshes:
            lines.append(f"{m.mesh.a}-{m.mesh.b:<10}  {_short(m.tangential):<12}  {_short(m.per_planet):<12}  {_short(m.power):<9}  "
                         f"{m.driver or ('-' if m.power == 0 else '(depends)')}")
        lines += pins_text(self.pins)
        return "\n".join(lines)


def pins_text(pins: Mapping[str, tuple[sp.Expr, sp.Expr]], unit: str = "") -> list[str]:
    """One line per planet: the force on its pin, x and y in its carrier's frame, and its size."""
    return [f"pin load on {n}{unit}: x {_short(x)}, y {_short(y)}, size {_short(sp.sqrt(x**2 + y**2))}"
            for n, (x, y) in pins.items()]


def _pins_json(pins: Mapping[str, tuple[sp.Expr, sp.Expr]]) -> dict[str, Any]:
    return {n: {k: exact_json(v) if v.is_number else str(v) for k, v in (("x", x), ("y", y))} for n, (x, y) in pins.items()}


def _short(value: sp.Expr) -> str:
    text = str(value)
    return text if len(text) <= 12 else float_text(value) or text[:12]


def mesh_efficiencies(mech: Mechanism, efficiency: Any = None) -> dict[str, sp.Expr]:
    """Each mesh's efficiency, keyed ``"a-b"``, as :func:`statics` takes ``efficiency``.

    >>> from symkin import schemes
    >>> mesh_efficiencies(schemes.two_row("II", teeth=(200, 99, 100, 201)), "default")
    {'1-2': 99/100, '3-4': 99/100}
    """
    return _efficiencies(mech, _sides(mech), efficiency)


def _efficiencies(mech: Mechanism, sides: Sequence[_Side], efficiency: Any) -> dict[str, sp.Expr]:
    out: dict[str, sp.Expr] = {}
    for s in sides:
        key = f"{s.mesh.a}-{s.mesh.b}"
        given: Any = None
        if isinstance(efficiency, Mapping):
            given = efficiency.get(key, efficiency.get(f"{s.mesh.b}-{s.mesh.a}"))
        elif efficiency == "default":
            given = s.mesh.efficiency or DEFAULT_EFFICIENCY["internal" if s.internal else "external"]
        elif efficiency is not None:
            given = efficiency
        if given is None and s.mesh.efficiency is not None:
            given = s.mesh.efficiency
        if given is None:
            out[key] = efficiency_symbol(s.mesh)
            continue
        value = given if isinstance(given, sp.Symbol) else as_real(given, what=f"the efficiency of mesh {key}")
        if value.is_number and not (0 < value <= 1):
            raise InputError(f"the efficiency of mesh {key} must lie in (0, 1], got {given!r}")
        out[key] = value
    if isinstance(efficiency, Mapping):
        unknown = set(efficiency) - set(out) - {f"{b}-{a}" for a, b in (k.split("-", 1) for k in out)}
        if unknown:
            raise InputError(f"no mesh {sorted(unknown)[0]!r}; the meshes are {', '.join(out)}")
    return out


def _decide(value: sp.Expr) -> int | None:
    """+1, -1 or 0 when the sign of ``value`` is known (positive tooth numbers and radii), else None."""
    value = sp.factor(sp.cancel(value))
    if value.is_zero:
        return 0
    if value.is_positive:
        return 1
    if value.is_negative:
        return -1
    return None


def statics(
    mech: Mechanism,
    *,
    input: str,
    output: str,
    fixed: Sequence[str] = (),
    joined: Sequence[tuple[str, str]] = (),
    efficiency: Any = None,
    pressure_angle: Any = DEFAULT_PRESSURE_ANGLE,
) -> Statics:
    """Torques, tooth forces, power flow and efficiency of ``mech`` with ``input`` driving
    ``output`` while the ``fixed`` links are held and the ``joined`` pairs turn together.

    ``symkin.statics.statics`` (:func:`symkin.statics.operating.statics`) also takes
    ``speeds=`` and ``torques=`` instead of ``input`` and ``output``: an operating point.

    Parameters
    ----------
    mech : Mechanism
        Any train the model holds (a ready-made scheme, a train file, nested or bevel).
    input, output : str
    fixed : sequence of str
        Links held (brakes); the frame is always held.
    joined : sequence of (str, str)
        Clutches.
    efficiency : None, number, ``"default"`` or mapping
        Mesh efficiencies: None keeps a symbol ``eta_ab`` per mesh (or the train file's
        ``efficiency``), a number applies to every mesh, ``"default"`` takes the train
        file's value where it gives one, else :data:`DEFAULT_EFFICIENCY`, a mapping
        ``{"a-b": value}`` sets meshes one by one.
    pressure_angle : angle in radians
        For the radial tooth forces (default 20 degrees).

    Returns
    -------
    Statics

    Examples
    --------
    >>> from symkin import schemes
    >>> st = statics(schemes.two_row("II", teeth=(200, 99, 100, 201)), input="H", output="1", fixed=("4",),
    ...              efficiency="default")
    >>> round(float(st.efficiency.rhs), 4)      # the 2009 paper's II train, carrier driving (0.99 per internal mesh)
    0.2032
    >>> st.self_locking                         # gear 1 cannot drive the carrier: it locks
    True
    """
    inp, out = mech.link(input).name, mech.link(output).name
    held = tuple(dict.fromkeys(mech.link(f).name for f in fixed if mech.link(f).name != FRAME))
    pairs = tuple((mech.link(a).name, mech.link(b).name) for a, b in joined)
    speeds = _unit_speeds(mech, inp, out, held, pairs)
    sides = _sides(mech)
    etas = _efficiencies(mech, sides, efficiency)
    forces, torques = _solve(mech, sides, [sp.Integer(1)] * len(sides), [0] * len(sides), inp, out, held, pairs)
    meshes = _mesh_powers(mech, sides, forces, speeds, pressure_angle)
    # which gear drives each mesh (relative power out of gear a for a positive input power)
    powers_a = [m.relative_power for m in meshes]
    signs = [_decide(p) for p in powers_a]
    eta_law, lossy_torques = _with_losses(mech, sides, etas, powers_a, signs, speeds, inp, out, held, pairs)
    held_text = ", ".join(held) or "nothing"
    law = Law(sp.Symbol(f"eta_{inp}{out}" + (f"^({','.join(held)})" if held else ""), positive=True), eta_law,
              f"efficiency, {inp} driving {out}, {held_text} held")
    circulating = max((sp.Abs(m.power) for m in meshes), key=lambda v: float(v) if v.is_number else math.inf, default=sp.Integer(0))
    housing = sp.cancel(-(torques[inp] + torques[out]))
    lossy_out = lossy_torques[out]
    housing_lossy = sp.piecewise_fold(-1 - lossy_out) if isinstance(lossy_out, sp.Piecewise) else sp.cancel(-1 - lossy_out)
    return Statics(mech, inp, out, held, pairs, speeds, torques, tuple(meshes), law, lossy_torques, etas, circulating,
                   housing, housing_lossy, functools.partial(_pin_loads, mech, sides, forces, pressure_angle))


def _mesh_powers(mech: Mechanism, sides: Sequence[_Side], forces: Sequence[sp.Expr], speeds: Mapping[str, sp.Expr],
                 pressure_angle: Any) -> list[MeshPower]:
    """Each mesh's forces and the power through it (relative to the link holding both axes)."""
    tan_alpha = sp.tan(as_real(pressure_angle, what="the pressure angle"))
    meshes = []
    for s, F in zip(sides, forces):
        pa = sp.cancel(-F * s.c_a * (speeds[s.a] - (0 if s.relative_a else speeds[s.holder])))
        sign = _decide(pa)
        count = _count(mech, s)
        meshes.append(MeshPower(
            s.mesh, F, sp.cancel(F / count), sp.Abs(F) * tan_alpha / count if not F.is_number else abs(F) * tan_alpha / count,
            pa, sp.Abs(pa) if sign is None else sign * pa, None if not sign else (s.mesh.a if sign > 0 else s.mesh.b)))
    return meshes


def _pin_loads(mech: Mechanism, sides: Sequence[_Side], forces: Sequence[sp.Expr],
               pressure_angle: Any) -> dict[str, tuple[sp.Expr, sp.Expr]]:
    """The force each planet's tooth forces put on its pin (on one copy), ``(x, y)`` in its carrier's
    frame at t = 0: each mesh's tangential force across the line of centres (its torque on the
    planet over the lever) and its separating force ``|F| tan(alpha)`` along it."""
    tan_alpha = sp.tan(as_real(pressure_angle, what="the pressure angle"))
    out: dict[str, list[sp.Expr]] = {}
    for s, F in zip(sides, forces):
        if s.relative_a or s.relative_b:  # a bevel mesh: not in the plane
            continue
        geo = mech.mesh_geometry(s.mesh)
        ax, ay = mech.axis_position(s.a)
        bx, by = mech.axis_position(s.b)
        d = sp.sqrt((bx - ax) ** 2 + (by - ay) ** 2)
        uy = ((bx - ax) / d, (by - ay) / d)  # along the line of centres, a to b
        ux = (uy[1], -uy[0])                 # across it: the tangential force on gear a is +F along ux
        for link, gear, sign, to_centre in ((s.a, geo.gear_a, 1, -geo.pitch_y), (s.b, geo.gear_b, -1, geo.centre_distance - geo.pitch_y)):
            if mech.link(link).kind is not LinkKind.PLANET:
                continue
            f = F / _count(mech, s)
            radial = sp.Abs(f) * tan_alpha * sp.sign(to_centre) * (-1 if gear.internal else 1)
            acc = out.setdefault(link, [sp.Integer(0), sp.Integer(0)])
            acc[0] += sign * f * ux[0] + radial * uy[0]
            acc[1] += sign * f * ux[1] + radial * uy[1]
    return {n: (sp.simplify(x), sp.simplify(y)) for n, (x, y) in out.items()}


def _unit_speeds(mech: Mechanism, inp: str, out: str, held: tuple[str, ...],
                 pairs: tuple[tuple[str, str], ...]) -> dict[str, sp.Expr]:
    """Every link's speed for a unit speed of the input, the ``held`` links still, ``pairs`` joined."""
    if inp == out:
        raise InputError(f"the input and the output are the same link {inp}")
    if inp in held or out in held:
        raise InputError(f"link {inp if inp in held else out} cannot be held and drive or be driven")
    try:
        speeds_law = solve_speeds(mech, {**{h: 0 for h in held}, inp: S.omega(inp)}, joined=pairs)
    except UnderdeterminedError as err:  # (a locked train, or one over-determined, keeps the solver's own message)
        in_clutches = {n for pair in pairs for n in pair}
        candidates = [n for n in mech.link_names if n not in (inp, out, *held, FRAME) and n not in in_clutches]
        central = [n for n in candidates if mech.link(n).kind is not LinkKind.PLANET]
        example = f"; for example {(central or candidates)[0]}" if central or candidates else ""
        raise UnderdeterminedError(
            f"with {inp} driving and {', '.join(held) or 'no link'} held the train still turns freely: hold more "
            f"links (fixed=, --fixed{example}) or join links (a clutch, joined=)", dof=err.dof, admissible=err.admissible,
        ) from None
    unit = {S.omega(inp): 1}
    speeds = {n: sp.cancel(speeds_law[n].subs(unit)) for n in mech.link_names}
    speeds[FRAME] = sp.Integer(0)
    if speeds[out] == 0:
        raise ModelError(f"the output {out} stands still when {inp} turns; nothing to drive")
    return speeds


def _with_losses(mech: Mechanism, sides: list[_Side], etas: dict[str, Any], powers_a: list[sp.Expr],
                 signs: list[int | None], speeds: dict[str, sp.Expr], inp: str, out: str, held: tuple[str, ...],
                 pairs: tuple[tuple[str, str], ...]) -> tuple[sp.Expr, dict[str, sp.Expr]]:
    """The efficiency law and the torques with losses: one branch for each direction of power
    through the meshes whose direction the dimensions decide (a Piecewise when there are several)."""
    undecided = [k for k, v in enumerate(signs) if v is None]
    ratios = [etas[f"{s.mesh.a}-{s.mesh.b}"] for s in sides]
    branches = []
    for pattern in itertools.product((1, -1), repeat=len(undecided)):
        chosen = [0 if v is None else v for v in signs]
        for k, v in zip(undecided, pattern):
            chosen[k] = v
        _, lossy = _solve(mech, sides, ratios, chosen, inp, out, held, pairs)
        eta = sp.factor(sp.cancel(-lossy[out] * speeds[out]))
        cond = sp.And(*[sp.Gt(powers_a[k], 0) if v == 1 else sp.Lt(powers_a[k], 0) for k, v in zip(undecided, pattern)])
        branches.append((eta, cond, lossy))
    if len(branches) == 1:
        return branches[0][0], branches[0][2]
    eta_law = sp.Piecewise(*[(e, c) for e, c, _ in branches])
    return eta_law, {k: sp.Piecewise(*[(b[2][k], b[1]) for b in branches]) for k in branches[0][2]}


def _count(mech: Mechanism, s: _Side) -> int:
    counts = [mech.link(n).count for n in (s.a, s.b) if mech.link(n).kind is LinkKind.PLANET]
    return max(counts, default=1)


def _solve(
    mech: Mechanism, sides: Sequence[_Side], eta: Sequence[sp.Expr], drivers: Sequence[int], inp: str, out: str,
    held: Sequence[str], pairs: Sequence[tuple[str, str]],
) -> tuple[list[sp.Expr], dict[str, sp.Expr]]:
    """Tooth forces (on the driving side) and external torques from the equilibrium of every
    moving link; ``drivers[k]`` is +1 when gear a drives mesh k, -1 when gear b does, 0 ideal."""
    forces, found = _balance(mech, sides, eta, drivers, {inp: sp.Integer(1)}, [out, *held], pairs)
    torques = {n: sp.Integer(0) for n in mech.link_names}
    torques.update(found)
    return forces, torques  # a clutch's torque is internal: not an external torque on its links


def _balance(
    mech: Mechanism, sides: Sequence[_Side], eta: Sequence[sp.Expr], drivers: Sequence[int], given: Mapping[str, Any],
    unknown: Sequence[str], pairs: Sequence[tuple[str, str]],
) -> tuple[list[sp.Expr], dict[str, sp.Expr]]:
    """Tooth forces and the external torques on the ``given`` and ``unknown`` links from the
    equilibrium of every moving link (``drivers`` as for :func:`_solve`)."""
    links = list(mech.link_names)
    row = {n: i for i, n in enumerate(links)}
    F = sp.symbols(f"F_0:{len(sides)}")
    ports = {n: sp.Symbol(f"T_{n}") for n in unknown}
    clutch = [sp.Symbol(f"tau_{k}") for k in range(len(pairs))]
    sums = [sp.Integer(0)] * len(links)

    def add(link: str, value: sp.Expr) -> None:
        if link != FRAME:
            sums[row[link]] += value

    for k, (s, e, d) in enumerate(zip(sides, eta, drivers)):
        f_a = F[k] if d >= 0 else e * F[k]  # the driven side receives eta times the driving side's force
        f_b = F[k] if d <= 0 else e * F[k]
        if d == 0:
            f_a = f_b = F[k]
        add(s.a, f_a * s.c_a)
        add(s.b, f_b * s.c_b)
        on_holder = (0 if s.relative_a else f_a * s.c_a) + (0 if s.relative_b else f_b * s.c_b)
        add(s.holder, -on_holder)
    for n, value in given.items():
        add(n, value)
    for n, r in ports.items():
        add(n, r)
    for (a, b), tau in zip(pairs, clutch):
        add(a, tau)
        add(b, -tau)
    unknowns = [*F, *ports.values(), *clutch]
    # a linear system: solved as one (Gauss-Jordan over the fraction field) rather than through
    # sp.solve's general machinery, about 3x faster; the values are cancelled below either way
    solution = sp.linsolve(sums, unknowns)
    if solution == sp.S.EmptySet:
        raise ModelError("the links cannot all be in equilibrium in this configuration (a locked or free train, or "
                         "more torques given than the balance leaves free)")
    (values,) = solution
    sol = {u: v for u, v in zip(unknowns, values) if v != u}  # an unknown left free stands for itself
    free = [u for u in unknowns if u not in sol]
    loose = [n for n, r in ports.items() if r in free or sol[r].free_symbols & set(free)]
    if loose:
        raise ModelError(f"the balance leaves the torques on {', '.join(loose)} free: give more torques (torques=, "
                         "--torque LINK=VALUE; 0 for a link without a shaft of its own)")
    if free:
        raise ModelError(f"the tooth forces are statically indeterminate here ({', '.join(map(str, free))} free): "
                         "redundant meshes share the load in a way the rigid model cannot decide")
    return [sp.cancel(sol[f]) for f in F], {**{n: sp.sympify(v) for n, v in given.items()},
                                             **{n: sp.cancel(sol[r]) for n, r in ports.items()}}
