"""Operating points: every torque, power and loss of a train at given speeds and torques.

A train (or a state of it) with ``n`` degrees of freedom left by its brakes and clutches is
at an operating point when ``n`` speeds are given (every other speed follows) and enough
external torques to close the balance: a power-split drive with the engine on the carrier,
the generator on the sun and the wheels on the ring has two degrees of freedom, so two
speeds and one torque (the engine's) fix it.

Every link about the main axis (a sun, a ring, a carrier) is a port that may carry an
external torque (0 where it has no shaft: give it); the held links carry the reactions;
the housing takes what the free ports leave, ``-(sum of their torques)``: the held links'
reactions (0 with no link held).  The ideal torques
come from the equilibrium of every moving link (as in :func:`symkin.statics.statics`); with
losses, each mesh's direction of relative power is decided at this operating point (the
basic-train method) and its driven gear receives ``eta`` times the driving gear's force,
the given torques held.  Powers are ``T omega`` into the train (W for N m and rad/s); the
loss is the power the ports put in, with losses: never negative.

    >>> from symkin.trains import load_train
    >>> op = operating_point(load_train("power-split"), speeds={"C": 200, "R": 150}, torques={"C": 100}, efficiency=1)
    >>> op.speeds["S"], op.torques["S"], op.torques["R"]   # Willis: sun 30, ring 78
    (330, -250/9, -650/9)
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin._util.jsonout import exact_json, float_text
from symkin.errors import InputError, ModelError
from symkin.kinematics import solve_speeds
from symkin.model import FRAME, LinkKind, Mechanism
from symkin.statics import power
from symkin.statics.power import (
    DEFAULT_PRESSURE_ANGLE,
    MeshPower,
    _balance,
    _efficiencies,
    _mesh_powers,
    _pin_loads,
    _pins_json,
    _sides,
    pins_text,
)
from symkin.values import as_real

__all__ = ["OperatingPoint", "operating_point", "statics"]

#: The tooth forces are torques over pitch radii in millimetres: this makes them newtons.
_PER_MM = 1000


@dataclass(frozen=True)
class OperatingPoint:
    """A train at one operating point (see :func:`operating_point`); SI units (rad/s, N m, W, N).

    Attributes
    ----------
    mechanism : Mechanism
    fixed : tuple of str
    joined : tuple of (str, str)
    speeds : dict
        Every link's speed, rad/s.
    torques, torques_with_losses : dict
        The external torque on every port (link about the main axis), ideal and with losses.
    powers, powers_with_losses : dict
        ``T omega`` into the train at each port, W.
    loss : sympy expression
        The power lost in the meshes: the sum of the powers with losses (0 ideal).
    housing, housing_with_losses : sympy expression
        The housing's torque on the train through its brakes: ``-(sum of the torques of the ports
        not held)``, the sum of the held links' reactions (as :attr:`Statics.housing`).
    meshes : tuple of MeshPower
        Ideal tooth forces (N, radii in mm) and the power through each contact (W), with the
        gear that drives.
    efficiencies : dict
        Each mesh's efficiency as used.
    pins : dict
        Planet -> ``(x, y)``: the force on one planet's pin, N, in its carrier's frame at t = 0.
    """

    mechanism: Mechanism
    fixed: tuple[str, ...]
    joined: tuple[tuple[str, str], ...]
    speeds: dict[str, sp.Expr]
    torques: dict[str, sp.Expr]
    torques_with_losses: dict[str, sp.Expr]
    powers: dict[str, sp.Expr]
    powers_with_losses: dict[str, sp.Expr]
    loss: sp.Expr
    housing: sp.Expr
    housing_with_losses: sp.Expr
    meshes: tuple[MeshPower, ...]
    efficiencies: dict[str, sp.Expr]
    pins: dict[str, tuple[sp.Expr, sp.Expr]]

    def flow(self) -> list[str]:
        """The power flow, port by port: which put power in and which take it out (with losses)."""
        lines = []
        for n, p in self.powers_with_losses.items():
            if p.is_number and p != 0:
                lines.append(f"{n} {'puts in' if p > 0 else 'takes out'} {float_text(abs(p))} W")
        return lines

    def text(self) -> str:
        """The operating point as ``symkin efficiency --omega ... --torque ...`` prints it."""
        held = f", {', '.join(self.fixed)} held" if self.fixed else ""
        lines = [f"{self.mechanism.name or 'train'} at an operating point{held} (rad/s, N m, W)",
                 "link   speed         torque        with losses   power         with losses"]
        for n in self.torques:
            lines.append(f"{n:<5}  {_num(self.speeds[n]):<12}  {_num(self.torques[n]):<12}  "
                         f"{_num(self.torques_with_losses[n]):<12}  {_num(self.powers[n]):<12}  {_num(self.powers_with_losses[n])}")
        lines.append(f"housing torque: {_num(self.housing)} ideal, {_num(self.housing_with_losses)} with losses")
        lines.append(f"loss: {_num(self.loss)} W; power flow: " + ("; ".join(self.flow()) or "none"))
        lines.append("mesh           tangential N  power W       driver")
        for m in self.meshes:
            lines.append(f"{m.mesh.a}-{m.mesh.b:<10}  {_num(m.tangential):<12}  {_num(m.power):<12}  {m.driver or '-'}")
        lines += pins_text(self.pins, " (N)")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """The operating point as JSON: speeds, torques (ideal and with losses), powers, loss, housing, meshes."""
        def values(d: Mapping[str, sp.Expr]) -> dict[str, Any]:
            return {k: _json(v) for k, v in d.items()}

        return {
            "fixed": list(self.fixed), "joined": [list(j) for j in self.joined],
            "units": {"speeds": "rad/s", "torques": "N*m", "powers": "W", "tangential": "N"},
            "speeds": values(self.speeds), "torques": values(self.torques),
            "torques_with_losses": values(self.torques_with_losses), "powers": values(self.powers),
            "powers_with_losses": values(self.powers_with_losses), "loss": _json(self.loss),
            "housing_torque": _json(self.housing), "housing_torque_with_losses": _json(self.housing_with_losses),
            "mesh_efficiencies": values(self.efficiencies), "flow": self.flow(),
            "meshes": [m.to_json() for m in self.meshes], "pin_loads": _pins_json(self.pins),
        }


def _json(v: sp.Expr) -> Any:
    return exact_json(v) if v.is_number else str(v)


def _num(v: sp.Expr) -> str:
    return float_text(v) if v.is_number else str(v)


def operating_point(
    mech: Mechanism,
    speeds: Mapping[str, Any],
    torques: Mapping[str, Any],
    *,
    fixed: Sequence[str] = (),
    joined: Sequence[tuple[str, str]] = (),
    efficiency: Any = None,
    pressure_angle: Any = DEFAULT_PRESSURE_ANGLE,
) -> OperatingPoint:
    """Every speed, torque, power and the loss of ``mech`` at the given ``speeds`` (rad/s, or
    pint quantities) and ``torques`` (N m) while the ``fixed`` links are held and the
    ``joined`` pairs turn together; ``efficiency`` as for :func:`symkin.statics.statics`.

    Give as many speeds as the train (with its brakes and clutches) has degrees of freedom,
    and the torques the balance leaves free (an error says which are missing).
    """
    held = tuple(dict.fromkeys(mech.link(f).name for f in fixed if mech.link(f).name != FRAME))
    pairs = tuple((mech.link(a).name, mech.link(b).name) for a, b in joined)
    given_speeds = {mech.link(n).name: as_real(v, what=f"the speed of {n}", unit="rad/s") for n, v in speeds.items()}
    ports = [L.name for L in mech.links if L.kind is LinkKind.CENTRAL]
    given: dict[str, sp.Expr] = {}
    for n, v in torques.items():
        name = mech.link(n).name
        if name not in ports:
            raise InputError(f"link {n} has no shaft of its own (a planet or the frame): give torques on links about "
                             f"the main axis ({', '.join(ports)})")
        given[name] = as_real(v, what=f"the torque on {n}", unit="N*m")
    for n in given_speeds:
        if n in held:
            raise InputError(f"link {n} is held: give no speed for it")
    all_speeds = solve_speeds(mech, {**{h: 0 for h in held}, **given_speeds}, joined=pairs)
    w = {n: all_speeds[n] for n in mech.link_names}
    w[FRAME] = sp.Integer(0)
    sides = _sides(mech)
    etas = _efficiencies(mech, sides, efficiency)
    unknown = [n for n in ports if n not in given]
    forces, ideal = _balance(mech, sides, [sp.Integer(1)] * len(sides), [0] * len(sides), given, unknown, pairs)
    meshes = _mesh_powers(mech, sides, [f * _PER_MM for f in forces], w, pressure_angle)
    signs = []
    for m in meshes:  # the relative power in W: its sign decides the driver (numbers here)
        pa = m.relative_power / _PER_MM
        if not pa.is_number:
            raise ModelError(f"the power through mesh {m.mesh.a}-{m.mesh.b} is not a number ({pa}); give numbers")
        signs.append(int(sp.sign(pa)))
    meshes = [MeshPower(m.mesh, m.tangential, m.per_planet, m.radial, m.relative_power / _PER_MM, m.power / _PER_MM,
                        m.driver) for m in meshes]
    _, lossy = _balance(mech, sides, [etas[f"{s.mesh.a}-{s.mesh.b}"] for s in sides], signs, given, unknown, pairs)
    order = ports
    torques_ideal = {n: sp.cancel(ideal[n]) for n in order}
    torques_lossy = {n: sp.cancel(lossy[n]) for n in order}
    powers = {n: sp.cancel(torques_ideal[n] * w[n]) for n in order}
    powers_lossy = {n: sp.cancel(torques_lossy[n] * w[n]) for n in order}
    if sp.simplify(sum(powers.values())) != 0:  # the ideal torques do no work: a check of the balance
        raise ModelError("the ideal torques do not balance the power; the train is not determined here")
    return OperatingPoint(
        mech, held, pairs, {n: w[n] for n in mech.link_names}, torques_ideal, torques_lossy, powers, powers_lossy,
        sp.cancel(sum(powers_lossy.values())), sp.cancel(-sum(t for n, t in torques_ideal.items() if n not in held)),
        sp.cancel(-sum(t for n, t in torques_lossy.items() if n not in held)), tuple(meshes), etas,
        _pin_loads(mech, sides, [f * _PER_MM for f in forces], pressure_angle))


def statics(mech: Mechanism, *, input: str | None = None, output: str | None = None, speeds: Mapping[str, Any] | None = None,
            torques: Mapping[str, Any] | None = None, **keywords: Any) -> Any:
    """``symkin.statics.statics``: per unit input torque with ``input`` and ``output``
    (:func:`symkin.statics.power.statics`, a :class:`~symkin.statics.power.Statics`), or at an
    operating point with ``speeds`` and ``torques`` (:func:`operating_point`, an
    :class:`OperatingPoint`); ``fixed``, ``joined``, ``efficiency``, ``pressure_angle`` for both.

    >>> from symkin.trains import load_train
    >>> statics(load_train("simple"), input="S", output="C", fixed=("R",)).torques["C"]
    -4
    >>> statics(load_train("simple"), speeds={"S": 4}, torques={"S": 1}, fixed=("R",)).torques
    {'S': 1, 'C': -4, 'R': 3}
    """
    if speeds is not None or torques is not None:
        if input is not None or output is not None:
            raise InputError("give either input= and output= (per unit input torque), or speeds= and torques= (an "
                             "operating point), not both")
        return operating_point(mech, speeds or {}, torques or {}, **keywords)
    if input is None or output is None:
        raise InputError("name the input and the output links (input=, output=), or give speeds= and torques=")
    return power.statics(mech, input=input, output=output, **keywords)
