"""One-way clutches (freewheels, sprags, hub pawls): which hold and which overrun, state by state.

A one-way clutch between two links stops the first turning in one direction (``blocks``:
"negative" or "positive") relative to the second (the frame, for a one-way brake).  It
carries torque only one way, so whether it holds depends on the load:

- In a state whose brakes and clutches already fix every speed, a one-way clutch carries
  nothing: it **overruns** where its links turn apart the free way, it is **idle** where they
  turn together (a brake beside it holds), and a state that would turn it the blocked way
  is locked (an error naming it).
- In a state left free by its brakes and clutches, the one-way clutches close it: a set of
  them is engaged (each as a brake, or a clutch between its links) when every engaged one
  carries torque the way it can.  By virtual power the torque an engaged one-way clutch
  carries is ``T = -T_in omega_in' / (omega_a' - omega_b')`` in the motion where the output
  stands (held by its load), the clutch is released and the input turns (``omega_in' = 1``):
  in drive (``T_in > 0``) it holds when that motion turns its link the blocked way; in coast
  (the output driving, ``T_in < 0``) when it turns it the free way.  One whose release leaves
  the output's speed fixed by the input all the same, and its links free to turn apart (on a
  link that carries no load), carries nothing: it is **idle**, engaged unloaded.  The others
  must then overrun.
- A state no set of one-way clutches can hold is **free**: it has no ratio.  A one-way clutch
  whose motion the input's speed fixes through the state's brakes and clutches alone
  overruns or is idle as above, or locks the train (an error); one that, engaged alone,
  would carry the wrong way **overruns**; of any other nothing is known: **undetermined**.
  A one-way brake on the input is never engaged (it would stop the input).

Nothing here needs the statics: the signs come from the kinematics alone (the same
torques :func:`symkin.statics.statics` gives, a second route the tests compare).

    >>> from symkin.trains import load_train
    >>> shift = load_train("simpson-oneway").shift("D1")
    >>> shift.drive.holding, shift.coast.free        # the freewheel holds C2; on coast it overruns
    (('F',), True)
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin.errors import DeterminacyError, ModelError, OverdeterminedError, UnderdeterminedError
from symkin.kinematics import Speeds, kinematic_system, solve_speeds
from symkin.model import FRAME

__all__ = ["OneWay", "Engagement", "engage"]

#: The directions a one-way clutch may block.
BLOCKS = ("negative", "positive")


@dataclass(frozen=True)
class OneWay:
    """A one-way clutch: it stops ``link`` turning the ``blocks`` way relative to ``other``.

    Parameters
    ----------
    name : str
    link, other : str
        The links it joins (``other`` the frame for a one-way brake: ``"0"``).
    blocks : str
        ``"negative"`` (the usual freewheel: ``link`` may not turn backwards relative to
        ``other``) or ``"positive"``.
    """

    name: str
    link: str
    other: str = FRAME
    blocks: str = "negative"

    def __post_init__(self) -> None:
        if self.blocks not in BLOCKS:
            raise ModelError(f"one-way clutch {self.name}: blocks is \"negative\" or \"positive\", got {self.blocks!r}")
        if self.link == self.other:
            raise ModelError(f"one-way clutch {self.name}: it joins {self.link} to itself; name two links")

    @property
    def blocked(self) -> int:
        """-1 when it blocks negative relative turning, +1 when positive."""
        return -1 if self.blocks == "negative" else 1


@dataclass(frozen=True)
class Engagement:
    """What the one-way clutches do in one state, driving (``drive``) or coasting.

    Attributes
    ----------
    status : tuple of (name, str)
        Each one-way clutch's part: "holds", "overruns", "idle" (its links turn
        together and it carries nothing: a brake or clutch of the state holds them, or
        the output's speed is fixed without it), "released" (the state holds it out of
        engagement) or, in a free state, "undetermined" (nothing fixes its motion).
    free : bool
        No set of one-way clutches holds the state: it has no ratio this way.
    speeds : Speeds or None
        Every link's speed with the holding ones engaged (None when free).
    engaged : tuple of str
        The one-way clutches engaged in ``speeds``: those that hold, and those idle that
        keep a link carrying no load still (what the statics take as brakes or clutches).
    """

    status: tuple[tuple[str, str], ...]
    free: bool
    speeds: Speeds | None
    engaged: tuple[str, ...] = ()

    @property
    def holding(self) -> tuple[str, ...]:
        """The one-way clutches that hold."""
        return tuple(n for n, s in self.status if s == "holds")

    def text(self) -> str:
        """``F holds, G overruns`` (``free`` first when nothing holds the state)."""
        parts = ", ".join(f"{n} {s}" for n, s in self.status)
        return f"free ({parts})" if self.free else parts

    def to_json(self) -> dict[str, Any]:
        """``{"free": bool, "one_way": {name: status}}``."""
        return {"free": self.free, "one_way": dict(self.status)}


def _sign(value: Any, what: str) -> int:
    value = sp.cancel(sp.sympify(value))
    if value.is_zero:
        return 0
    if value.is_positive:
        return 1
    if value.is_negative:
        return -1
    raise ModelError(f"{what} depends on the tooth numbers ({value}); give them as numbers")


def _joints(engaged: Sequence[OneWay]) -> tuple[list[str], list[tuple[str, str]]]:
    """The links ``engaged`` one-way clutches hold (one-way brakes) and the pairs they join."""
    brakes = [ow.other if ow.link == FRAME else ow.link for ow in engaged if FRAME in (ow.link, ow.other)]
    return brakes, [(ow.link, ow.other) for ow in engaged if FRAME not in (ow.link, ow.other)]


def _solve(train: Any, known: Mapping[str, Any], joined: Sequence[tuple[str, str]], engaged: Sequence[OneWay]) -> Speeds:
    brakes, pairs = _joints(engaged)
    turning = [b for b in brakes if not sp.sympify(known.get(b, 0)).is_zero]
    if turning:  # a one-way brake on the input: it would stop it
        raise OverdeterminedError(f"a one-way brake would hold {turning[0]}, which turns", dof=0, admissible=())
    return solve_speeds(train, {**known, **dict.fromkeys(brakes, 0)}, joined=[*joined, *pairs])


def _per_input(train: Any, held: Sequence[str], pairs: Sequence[tuple[str, str]], inp: str, of: Any) -> Any:
    """``of(omega)`` (linear in the speeds) per unit speed of ``inp`` when the links ``held``
    still and the ``pairs`` joined fix it by the input's speed alone, else None (other links
    may stay free)."""
    links = kinematic_system(train).links

    def unit(n: str) -> list[int]:
        return [int(m == n) for m in links]  # the frame: no column, all zero

    rows = [list(r) for r in kinematic_system(train).matrix.tolist()]
    rows += [unit(n) for n in held] + [[x - y for x, y in zip(unit(a), unit(b))] for a, b in pairs]
    motions = sp.Matrix(len(rows), len(links), [x for r in rows for x in r]).nullspace()  # every motion they allow
    values = [(sp.cancel(of(dict(zip(links, v)))), sp.cancel(v[links.index(inp)])) for v in motions]
    per = next((q / w for q, w in values if not w.is_zero), None)
    if per is None or any(not sp.cancel(q - per * w).is_zero for q, w in values):
        return None
    return sp.cancel(per)


def _locks(where: str, ow: OneWay) -> ModelError:
    return ModelError(f"{where}: one-way clutch {ow.name} would turn {ow.link} {ow.blocks}ly relative to "
                      f"{ow.other if ow.other != FRAME else 'the frame'}, which it blocks: it locks the train; "
                      "release a brake or clutch, or turn the one-way clutch round")


def _relative(speeds: Mapping[str, Any], ow: OneWay) -> Any:
    def w(n: str) -> Any:
        return 0 if n == FRAME else speeds[n]

    return w(ow.link) - w(ow.other)


def engage(train: Any, state: Any, sense: int, *, inp: str, out: str, known: Mapping[str, Any],
           joined: Sequence[tuple[str, str]]) -> Engagement:
    """The one-way clutches of ``train`` in ``state``: driving (``sense`` +1, the input's torque
    along its speed) or coasting (-1, the output drives); ``known`` and ``joined`` are the
    state's own brakes (and the input's speed) and clutches."""
    one_ways = tuple(ow for ow in train.one_ways if ow.name not in state.released)
    where = f"state {state.name!r}"
    try:
        speeds = solve_speeds(train, known, joined=joined)
    except DeterminacyError as err:
        if not one_ways or not isinstance(err, UnderdeterminedError):
            raise
        return _released(train, state, _search(one_ways, train, state, sense, inp, out, known, joined))
    status = []
    for ow in one_ways:
        rel = _sign(_relative(speeds, ow) / speeds[inp], f"{where}: whether one-way clutch {ow.name} overruns")
        if rel == ow.blocked:
            raise _locks(where, ow)
        status.append((ow.name, "idle" if rel == 0 else "overruns"))
    return _released(train, state, Engagement(tuple(status), False, speeds))


def _released(train: Any, state: Any, found: Engagement) -> Engagement:
    """``found`` with the state's released one-way clutches in the train's order."""
    status = dict(found.status)
    return Engagement(tuple((ow.name, status.get(ow.name, "released")) for ow in train.one_ways), found.free, found.speeds,
                      found.engaged)


def _search(one_ways: tuple[OneWay, ...], train: Any, state: Any, sense: int, inp: str, out: str,
            known: Mapping[str, Any], joined: Sequence[tuple[str, str]]) -> Engagement:
    where = f"state {state.name!r}"
    for size in range(1, len(one_ways) + 1):
        for combo in itertools.combinations(one_ways, size):
            try:
                speeds = _solve(train, known, joined, combo)
            except DeterminacyError:
                continue
            parts = {ow: _carries(train, state, sense, inp, out, known, joined, combo, ow) for ow in combo}
            carried = {ow: part for ow, part in parts.items() if part is not None and part != "overruns"}
            if len(carried) < len(combo):  # each holds, or carries nothing
                continue
            status, consistent = [], True
            for ow in one_ways:
                if ow in combo:
                    status.append((ow.name, carried[ow]))
                    continue
                rel = _sign(_relative(speeds, ow) / speeds[inp], f"{where}: whether one-way clutch {ow.name} overruns")
                if rel == ow.blocked:
                    consistent = False
                    break
                status.append((ow.name, "idle" if rel == 0 else "overruns"))
            if consistent:
                return Engagement(tuple(status), False, speeds, tuple(ow.name for ow in combo))
    return Engagement(tuple((ow.name, _unheld(train, state, sense, inp, out, known, joined, ow)) for ow in one_ways),
                      True, None)


def _unheld(train: Any, state: Any, sense: int, inp: str, out: str, known: Mapping[str, Any],
            joined: Sequence[tuple[str, str]], ow: OneWay) -> str:
    """``ow``'s part in a state nothing holds: what the input's speed makes of it through the
    state's brakes and clutches, else "overruns" if engaged it would carry the wrong way (its
    turning per input turning fixed with the output standing), else "undetermined"."""
    held = [k for k in known if k != inp]
    rel = _per_input(train, held, joined, inp, lambda w: _relative(w, ow))
    if rel is not None:
        rel = _sign(rel, f"state {state.name!r}: whether one-way clutch {ow.name} overruns")
        if rel == ow.blocked:
            raise _locks(f"state {state.name!r}", ow)
        return "idle" if rel == 0 else "overruns"
    load = _per_input(train, [*held, out], joined, inp, lambda w: _relative(w, ow))
    if load is None or load.is_zero:
        return "undetermined"
    load = _sign(load, f"state {state.name!r}: whether one-way clutch {ow.name} holds")
    return "overruns" if sense * load != ow.blocked else "undetermined"


def _carries(train: Any, state: Any, sense: int, inp: str, out: str, known: Mapping[str, Any],
             joined: Sequence[tuple[str, str]], combo: Sequence[OneWay], ow: OneWay) -> str | None:
    """How ``ow``, engaged with ``combo``, carries its torque: released, with the output standing
    and the input turning, it would turn the blocked way in drive ("holds"; "overruns" the other
    way); "idle" when released the output's speed is fixed by the input all the same (it carries
    nothing: with the input still its links can turn apart); None when that motion does not
    turn it (the output would stand) or when another clutch shares its load."""
    held = {k: v for k, v in known.items() if k != inp}
    rest = [c for c in combo if c is not ow]
    try:
        speeds = _solve(train, {**held, out: 0, inp: 1}, joined, rest)
    except DeterminacyError:
        brakes, pairs = _joints(rest)
        brakes, pairs = [*held, *brakes], [*joined, *pairs]
        fixed = _per_input(train, brakes, pairs, inp, lambda w: w[out])
        loose = _per_input(train, brakes, pairs, inp, lambda w: _relative(w, ow)) is None  # (else another holds it too)
        return "idle" if fixed is not None and not fixed.is_zero and loose else None
    rel = _sign(_relative(speeds, ow), f"state {state.name!r}: whether one-way clutch {ow.name} holds")
    return None if rel == 0 else "holds" if sense * rel == ow.blocked else "overruns"
