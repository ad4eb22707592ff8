"""A train: a mechanism with its gear states (brakes and clutches), and its shift table.

A :class:`Train` is a :class:`~symkin.model.Mechanism` (everything that takes a
mechanism takes a train) that also knows its :class:`State` s: in each, an input link,
an output link, the links held by brakes and the pairs of links joined by clutches.
:meth:`Train.shift` derives a state's ratio and every link's speed; :meth:`Train.shift_table`
all of them.

    >>> from symkin.trains import load_train
    >>> train = load_train("ravigneaux")
    >>> [(s.state.name, s.ratio.rhs) for s in train.shift_table()][:2]
    [('first', 12/5), ('second', 22/15)]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin._util.display import html_table, short_repr
from symkin._util.jsonout import exact_json, float_text
from symkin.errors import DeterminacyError, ModelError
from symkin.kinematics import Speeds, solve_speeds
from symkin.laws import Law
from symkin.model import FRAME, Mechanism
from symkin.trains.one_way import Engagement, OneWay, engage

__all__ = ["State", "Train", "Shift", "ShiftTable", "OneWay", "Engagement"]


@dataclass(frozen=True)
class State:
    """A gear state: which link drives, which is driven, which are held and joined.

    Parameters
    ----------
    name : str
    input, output : str
        Links (or gears, for the link holding them).
    brakes : tuple of str
        Links held to the frame.
    clutches : tuple of (str, str)
        Pairs of links made to turn together.
    description : str
    released : tuple of str
        One-way clutches held out of engagement in this state (a hub's pawls lifted).
    """

    name: str
    input: str
    output: str
    brakes: tuple[str, ...] = ()
    clutches: tuple[tuple[str, str], ...] = ()
    description: str = ""
    released: tuple[str, ...] = ()

    def __repr__(self) -> str:
        """``State('first', S1 -> R, brakes C, clutches -)``, under 200 characters."""
        return short_repr("State", repr(self.name), f"{self.input} -> {self.output}",
                          f"brakes {', '.join(self.brakes) or '-'}",
                          f"clutches {', '.join(f'{a}+{b}' for a, b in self.clutches) or '-'}")

    def _repr_html_(self) -> str:
        """The state as a one-row HTML table, for Jupyter."""
        return html_table(["state", "input", "output", "brakes", "clutches", "description"],
                          [(self.name, self.input, self.output, ", ".join(self.brakes) or "-",
                            ", ".join(f"{a}+{b}" for a, b in self.clutches) or "-", self.description)])


@dataclass(frozen=True)
class Shift:
    """A state solved: its ratio ``omega_input / omega_output`` and every link's speed.

    With one-way clutches in the train, ``drive`` and ``coast`` say which hold and which
    overrun (:class:`~symkin.trains.one_way.Engagement`), driving and with the output
    driving; a state no one-way clutch can hold in drive is ``free``: no ratio, no speeds.
    """

    state: State
    ratio: Law | None
    speeds: Speeds | None
    drive: Engagement | None = None
    coast: Engagement | None = None

    @property
    def free(self) -> bool:
        """True when nothing holds the state in drive (a one-way clutch overruns): no ratio."""
        return self.ratio is None

    def __repr__(self) -> str:
        """``Shift('first', ratio 12/5)``, under 200 characters."""
        return short_repr("Shift", repr(self.state.name), "free" if self.ratio is None else f"ratio {self.ratio.rhs}")

    def _repr_html_(self) -> str:
        """The state's ratio and every link's speed per unit input speed, for Jupyter."""
        if self.ratio is None or self.speeds is None:  # nothing holds it in drive (a one-way clutch overruns)
            return html_table(["link", "speed / input speed"], [], caption=f"state {self.state.name}: free, no ratio")
        w_in = S.omega(self.state.input)
        rows = [(n, f"${sp.latex(sp.cancel(v / w_in))}$") for n, v in self.speeds.items()]
        return html_table(["link", "speed / input speed"], rows, raw_columns=(1,),
                          caption=f"state {self.state.name}: ratio {self.ratio.rhs}")

    def to_json(self) -> dict[str, Any]:
        """The gear state as JSON: input, output, brakes, clutches and the exact ratio (null when free)."""
        out: dict[str, Any] = {
            "state": self.state.name,
            "input": self.state.input,
            "output": self.state.output,
            "brakes": list(self.state.brakes),
            "clutches": [list(c) for c in self.state.clutches],
            "ratio": None if self.ratio is None else exact_json(self.ratio.rhs),
            "speeds_per_input": {} if self.speeds is None else
            {n: exact_json(sp.cancel(v / S.omega(self.state.input))) for n, v in self.speeds.items()},
        }
        if self.drive is not None and self.coast is not None:
            out.update(free=self.free, one_way=self.drive.to_json()["one_way"], coast=self.coast.to_json())
        return out


@dataclass(frozen=True)
class ShiftTable:
    """Every state of a train solved, in the file's order (what ``symkin states`` prints)."""

    train: Train
    shifts: tuple[Shift, ...]

    def __repr__(self) -> str:
        """``ShiftTable('simple planetary', low 4, reverse -3, overdrive 3/4)``, under 200 characters."""
        return short_repr("ShiftTable", repr(self.train.name), *(f"{s.state.name} {'free' if s.ratio is None else s.ratio.rhs}"
                                                                        for s in self.shifts))

    def __iter__(self) -> Any:
        return iter(self.shifts)

    def __len__(self) -> int:
        return len(self.shifts)

    def __getitem__(self, k: int) -> Shift:
        return self.shifts[k]

    def text(self) -> str:
        """The shift table as ``symkin states`` prints it, one row per state."""
        one_way = bool(self.train.one_ways)
        rows = [("state", "input", "output", "brakes", "clutches", "ratio", "float")
                + (("one-way clutches (drive)", "coast (output driving)") if one_way else ())]
        for s in self.shifts:
            st = s.state
            value = None if s.ratio is None else s.ratio.rhs
            rows.append((st.name, st.input, st.output, ", ".join(st.brakes) or "-",
                         ", ".join(f"{a}+{b}" for a, b in st.clutches) or "-", "free" if value is None else str(value),
                         "-" if value is None else float_text(value))
                        + ((s.drive.text(), s.coast.text()) if one_way and s.drive and s.coast else ()))
        widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
        lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
        lines.insert(1, "  ".join("-" * w for w in widths).rstrip())
        title = self.train.name or "train"
        return f"{title}: {len(self.shifts)} state{'s' * (len(self.shifts) != 1)}, ratio = omega_input/omega_output\n" + \
            "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """The shift table as JSON: the train's name and each state."""
        return {"train": self.train.name, "states": [s.to_json() for s in self.shifts]}

    def _repr_html_(self) -> str:
        """The shift table as an HTML table with the ratios as math, for Jupyter.

        >>> from symkin.trains import load_train
        >>> "<th>ratio</th>" in load_train("simpson").shift_table()._repr_html_()
        True
        """
        rows = [(s.state.name, s.state.input, s.state.output, ", ".join(s.state.brakes) or "-",
                 ", ".join(f"{a}+{b}" for a, b in s.state.clutches) or "-",
                 "free" if s.ratio is None else f"${sp.latex(s.ratio.rhs)}$",
                 "-" if s.ratio is None else float_text(s.ratio.rhs)) for s in self.shifts]
        return html_table(["state", "input", "output", "brakes", "clutches", "ratio", "float"], rows,
                          caption=f"{self.train.name or 'train'}: ratio = omega_input/omega_output", raw_columns=(5,))


def _named(items: Any, kind: type, what: str) -> tuple[Any, ...]:
    """``items`` as a tuple, each a ``kind`` with a name of its own."""
    seen: set[str] = set()
    for item in items:
        if not isinstance(item, kind):
            raise ModelError(f"{item!r} is not a {kind.__name__}")
        name: str = getattr(item, "name")  # noqa: B009 - State and OneWay both have one
        if name in seen:
            raise ModelError(f"two {what} are called {name!r}; give each its own name")
        seen.add(name)
    return tuple(items)


@dataclass(frozen=True)
class Train(Mechanism):
    """A mechanism with named gear states (see the module docstring).

    Parameters
    ----------
    links, meshes, name
        As for :class:`~symkin.model.Mechanism`.
    states : tuple of State
    description : str
    source : str
        Where it was read from (a file, or a ready-made train's name).
    base : SpaceFrame, optional
        The base's motion in space the file gives ([base]): the drawing commands use it.
    tooth_forms : tuple of (gear name, ((key, value), ...))
        The tooth form keys a gear's table gives (``shift``, ``addendum``, ``dedendum``,
        ``pressure_angle``, ``fillet``, ``tip_diameter``), exact; :mod:`symkin.geometry` reads them.
    one_ways : tuple of OneWay
        One-way clutches ([one_way.NAME]): each state engages those that can hold it.
    """

    states: tuple[State, ...] = ()
    description: str = ""
    source: str = ""
    base: Any = None
    tooth_forms: tuple[tuple[str, tuple[tuple[str, Any], ...]], ...] = ()
    one_ways: tuple[OneWay, ...] = ()

    def __repr__(self) -> str:
        """``Train('simple planetary', links S, C, P, R, states low, reverse, overdrive)``, under 200 characters."""
        return short_repr("Train", repr(self.name), "links " + ", ".join(L.name for L in self.moving_links),
                          "states " + (", ".join(self.state_names) or "-"))

    def _repr_html_(self) -> str:
        """For Jupyter: the kinematic scheme, the links and the shift table (a state that cannot be
        solved is left out of it)."""
        try:
            table = self.shift_table()._repr_html_() if self.states else ""
        except ModelError:
            table = ""
        return super()._repr_html_() + table

    def __post_init__(self) -> None:
        super().__post_init__()
        object.__setattr__(self, "states", _named(self.states, State, "states"))
        for st in self.states:
            self._check_state(st)
        object.__setattr__(self, "one_ways", _named(self.one_ways, OneWay, "one-way clutches"))
        for st in self.states:
            unknown = sorted(set(st.released) - {ow.name for ow in self.one_ways})
            if unknown:
                raise ModelError(f"state {st.name!r}: releases no one-way clutch {unknown[0]!r}; the one-way clutches are "
                                 f"{', '.join(ow.name for ow in self.one_ways) or '(none)'}")
        for ow in self.one_ways:
            for n in (ow.link, ow.other):
                if n != FRAME:
                    try:
                        self.link(n)
                    except ModelError as err:
                        raise ModelError(f"one-way clutch {ow.name}: {err}") from None

    def _check_state(self, st: State) -> None:
        where = f"state {st.name!r}"
        names = [st.input, st.output, *st.brakes, *(x for pair in st.clutches for x in pair)]
        for n in names:
            try:
                self.link(n)
            except ModelError as err:
                raise ModelError(f"{where}: {err}") from None
        inp, out = self.link(st.input).name, self.link(st.output).name
        held = {self.link(b).name for b in st.brakes}
        if inp == out:
            raise ModelError(f"{where}: the input and the output are the same link {inp}; name two links")
        if FRAME in (inp, out):
            raise ModelError(f"{where}: the frame cannot be the input or the output")
        if held & {inp, out}:
            raise ModelError(f"{where}: link {sorted(held & {inp, out})[0]} is both held by a brake and the "
                             f"{'input' if inp in held else 'output'}")

    @property
    def state_names(self) -> tuple[str, ...]:
        """The names of the train's gear states, in file order.

        >>> from symkin.trains import load_train
        >>> load_train("simple").state_names
        ('low', 'reverse', 'overdrive')
        """
        return tuple(s.name for s in self.states)

    def state(self, name: str) -> State:
        """The state called ``name``."""
        for s in self.states:
            if s.name == name:
                return s
        raise ModelError(f"no state {name!r} in this train; its states are {', '.join(self.state_names) or '(none)'}")

    def shift(self, state: str | State) -> Shift:
        """The ratio ``omega_input / omega_output`` of a state and every link's speed.

        A brake holds its link (speed 0), a clutch makes two links turn together; with
        the input turning, every link must then be determined exactly once: a state that
        leaves a link free or locks the train is a
        :class:`~symkin.errors.DeterminacyError` naming the state and the links.

        >>> from symkin.trains import load_train
        >>> print(load_train("wolfrom").shift("drive").ratio)
        i_{SR2} = 76
        """
        st = self.state(state) if isinstance(state, str) else state
        return self._memo(("shift", st, self.one_ways), lambda: self._shift(st))

    def engaged(self, state: str | State, *, coast: bool = False) -> tuple[tuple[str, ...], tuple[tuple[str, str], ...]]:
        """The brakes and clutches that hold ``state`` in drive (with ``coast``, when its output
        drives its input): its own, and the one-way clutches engaged (as a brake against the
        frame, else as a clutch: those that hold, and an idle one that keeps a link carrying no
        load still); what the statics take.

        >>> from symkin.trains import load_train
        >>> load_train("simpson-oneway").engaged("D1")
        (('C2',), ())
        >>> load_train("simpson-oneway").engaged("D1", coast=True)
        Traceback (most recent call last):
        ...
        symkin.errors.ModelError: state 'D1' is free when its output drives its input (F overruns): nothing carries the torque back
        """
        shift = self.shift(state)
        st = shift.state
        if shift.free:
            raise ModelError(f"state {st.name!r} is free: no one-way clutch can hold it in drive")
        way = shift.coast if coast else shift.drive
        if coast and way is not None and way.free:
            raise ModelError(f"state {st.name!r} is free when its output drives its input {way.text().removeprefix('free ')}"
                             ": nothing carries the torque back")
        brakes, clutches = list(st.brakes), list(st.clutches)
        for ow in self.one_ways:
            if way is not None and ow.name in way.engaged:
                if FRAME in (ow.link, ow.other):
                    brakes.append(ow.other if ow.link == FRAME else ow.link)
                else:
                    clutches.append((ow.link, ow.other))
        return tuple(brakes), tuple(clutches)

    def _shift(self, st: State) -> Shift:
        inp, out = self.link(st.input).name, self.link(st.output).name
        known: dict[str, Any] = {self.link(b).name: 0 for b in st.brakes if self.link(b).name != FRAME}
        known[inp] = S.omega(inp)
        joined = [(self.link(a).name, self.link(b).name) for a, b in st.clutches]
        drive = coast = None
        try:
            if self.one_ways:
                drive = engage(self, st, 1, inp=inp, out=out, known=known, joined=joined)
                coast = engage(self, st, -1, inp=inp, out=out, known=known, joined=joined)
                if drive.speeds is None:
                    return Shift(st, None, None, drive, coast)
                speeds = drive.speeds
            else:
                speeds = solve_speeds(self, known, joined=joined)
        except DeterminacyError as err:
            raise type(err)(f"state {st.name!r}: {err}", dof=err.dof, admissible=err.admissible) from None
        per_input = sp.cancel(speeds[out] / S.omega(inp))
        if per_input == 0:
            raise ModelError(f"state {st.name!r}: the output {out} stands still while {inp} turns; the ratio is infinite")
        held = tuple(self.link(b).name for b in st.brakes)
        desc = f"state {st.name}: omega_{inp}/omega_{out}" + (f", {', '.join(held)} held" if held else "") + \
            (f", {', '.join(f'{a}+{b}' for a, b in joined)} joined" if joined else "")
        ratio = Law(S.ratio_symbol(inp, out, held), sp.cancel(1 / per_input), desc)
        return Shift(st, ratio, speeds, drive, coast)

    def shift_table(self) -> ShiftTable:
        """Every state solved, in order (a :class:`ShiftTable`: iterate, print ``.text()``)."""
        return ShiftTable(self, tuple(self.shift(s) for s in self.states))
