"""One-way clutches that carry nothing, and states nothing holds, against a hand analysis.

- A one-way brake O on a link X that no mesh loads (X joined to the carrier in one state
  only): the simple planetary's states are fixed by their brakes alone, so O is idle and the
  ratios are Willis's: (w_S - w_C)/(w_R - w_C) = -z_r/z_s = -72/24 = -3 gives S->C with R held
  1 + 3 = 4, S->R with C held -3, C->R with S held 3/4.  With X joined to C, X turns with the
  carrier, forwards: O (blocking backwards turning) overruns.  The statics on the held train
  put no torque on X (a second route: O carries nothing).
- The Simpson set's first gear with such a loose link beside it: the freewheel F still holds
  the rear carrier (ratio 29/12 by the lever: 102 w_C1 = 72 w_R1 + 30 w_S, w_S = -(72/30) w_C1).
- A one-way brake K on the input R1: the input turns forwards, so K blocking "positive"
  turning locks the train; blocking "negative", it overruns (R1 turns forwards, its free way).
"""

from __future__ import annotations

import importlib.resources
import json

import jsonschema
import pytest
import sympy as sp

from symkin.cli import main, output_schema
from symkin.errors import DeterminacyError, ModelError
from symkin.statics import statics
from symkin.trains import read_train
from symkin.trains.one_way import _solve

_LIBRARY = importlib.resources.files("symkin.trains") / "library"
#: The ready-made simple planetary (sun 24, ring 72) with a link X joined only in state xc, a one-way brake on X.
_SIMPLE = (_LIBRARY / "simple.toml").read_text().replace("[states.low]", """[links.X]

[one_way.O]
links = ["X", "frame"]
blocks = "negative"

[states.low]""") + """
[states.xc]
input = "S"
output = "X"
brakes = ["R"]
clutches = [["X", "C"]]
"""

_SIMPSON = (_LIBRARY / "simpson-oneway.toml").read_text()


def _willis(known: dict[str, sp.Expr]) -> dict[str, sp.Expr]:
    """w_S, w_C, w_R from two of them: (w_S - w_C) = -3 (w_R - w_C), typed by hand."""
    wS, wC, wR = sp.symbols("wS wC wR")
    sol = sp.solve([sp.Eq(wS - wC, -3 * (wR - wC)), *(sp.Eq({"S": wS, "C": wC, "R": wR}[k], v) for k, v in known.items())],
                   [wS, wC, wR], dict=True)[0]
    return {"S": sol[wS], "C": sol[wC], "R": sol[wR]}


def test_a_one_way_brake_on_a_loose_link_is_idle_and_the_state_keeps_its_ratio():
    train = read_train(_SIMPLE)
    for name, inp, out, held in (("low", "S", "C", "R"), ("reverse", "S", "R", "C"), ("overdrive", "C", "R", "S")):
        shift = train.shift(name)
        speeds = _willis({inp: 1, held: 0})
        assert not shift.free and shift.ratio.rhs == 1 / speeds[out], name
        assert dict(shift.drive.status) == dict(shift.coast.status) == {"O": "idle"}, name
        assert not shift.coast.free and shift.drive.text() == "O idle", name
    assert train.shift("low").ratio.rhs == 4  # Willis: 1 + 72/24
    xc = train.shift("xc")  # X turns with the carrier, forwards (S forwards, R held): O overruns
    assert xc.ratio.rhs == 4 and dict(xc.drive.status) == {"O": "overruns"}
    assert train.engaged("low") == (("R", "X"), ())  # O keeps the loose link still, unloaded
    held = statics(train, input="S", output="C", fixed=("R", "X"), efficiency=1)
    assert held.torques["X"] == 0 and held.torques["C"] == -4  # it carries nothing; the ratio 4 again


def test_the_efficiency_of_a_state_with_an_unloaded_one_way_clutch(capsys, tmp_path):
    path = tmp_path / "loose.toml"
    path.write_text(_SIMPLE)
    assert main(["efficiency", "--train", str(path), "--state", "low", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["one_way"] == {"O": "idle"} and data["coast"] == {"free": False, "one_way": {"O": "idle"}}
    assert main(["states", "--train", str(path), "--json"]) == 0
    states = {s["state"]: s for s in json.loads(capsys.readouterr().out)["states"]}
    assert states["low"]["ratio"]["exact"] == "4" and states["low"]["free"] is False


def _loose_simpson() -> str:
    text = _SIMPSON.replace("[links.C2]", "[links.X]\n\n[links.C2]").replace(
        "[states.D1]", '[one_way.G]\nlinks = ["X", "frame"]\n\n[states.D1]')
    return text + '\n[states.XC]\ninput = "R1"\noutput = "C1"\nbrakes = ["C2"]\nclutches = [["X", "C1"]]\n'


def test_first_gear_with_a_loose_link_beside_it_is_held_by_the_freewheel(capsys, tmp_path):
    train = read_train(_loose_simpson())
    first = train.shift("D1")
    assert first.ratio.rhs == sp.Rational(174, 72)  # the lever: 102 w_C1 = 72 w_R1 + 30 w_S, w_S = -(72/30) w_C1
    assert dict(first.drive.status) == {"F": "holds", "G": "idle"}
    assert train.engaged("D1") == (("C2", "X"), ())
    # on coast nothing holds: F would carry the wrong way (it overruns); nothing fixes the loose X
    assert first.coast.free and dict(first.coast.status) == {"F": "overruns", "G": "undetermined"}
    assert first.coast.text() == "free (F overruns, G undetermined)"
    path = tmp_path / "loose.toml"
    path.write_text(_loose_simpson())
    assert main(["states", "--train", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    jsonschema.Draft202012Validator(output_schema("states")).validate(data)  # "undetermined" is a published part
    assert data["states"][0]["coast"]["one_way"] == {"F": "overruns", "G": "undetermined"}


def _with_input_brake(blocks: str, freewheel: bool) -> str:
    text = _SIMPSON.split("[states.L1]")[0]  # first gear only
    k = f'[one_way.K]\nlinks = ["R1", "frame"]\nblocks = "{blocks}"\n\n'
    if not freewheel:
        head, tail = text.split("[one_way.F]")
        text = head + tail[tail.index("[states.D1]"):]
    return text.replace("[states.D1]", k + "[states.D1]")


@pytest.mark.parametrize("freewheel", [False, True])
def test_a_one_way_brake_that_stops_the_input_locks_the_train(freewheel):
    assert "[one_way.K]" in _with_input_brake("positive", freewheel)
    assert ("[one_way.F]" in _with_input_brake("positive", freewheel)) is freewheel
    train = read_train(_with_input_brake("positive", freewheel))
    with pytest.raises(ModelError, match="one-way clutch K would turn R1 positively relative to the frame.*locks the train"):
        train.shift("D1")


def test_a_one_way_brake_on_the_input_turning_its_free_way_overruns():
    train = read_train(_with_input_brake("negative", True))
    first = train.shift("D1")
    assert first.ratio.rhs == sp.Rational(174, 72)
    assert dict(first.drive.status) == {"K": "overruns", "F": "holds"}
    assert dict(first.coast.status) == {"K": "overruns", "F": "overruns"} and first.coast.free
    alone = read_train(_with_input_brake("negative", False)).shift("D1")
    # nothing holds the rear carrier: free; K's motion (the input's, forwards) is known, the output's is not
    assert alone.free and dict(alone.drive.status) == {"K": "overruns"}


def test_a_one_way_brake_on_the_input_is_never_engaged():
    train = read_train(_with_input_brake("positive", True))
    k = next(ow for ow in train.one_ways if ow.name == "K")
    w = sp.Symbol("omega_R1")
    with pytest.raises(DeterminacyError, match="would hold R1, which turns"):
        _solve(train, {"R1": w, "C2": 0}, [], [k])  # it stopped the input: every speed 0
    assert _solve(train, {"R1": w}, [], [next(ow for ow in train.one_ways if ow.name == "F")])["R1"] == w
