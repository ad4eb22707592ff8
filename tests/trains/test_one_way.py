"""One-way clutches against a textbook element chart, the full statics and hand levers.

- The Simpson three-speed's element chart (TorqueFlite A-904/A-727, Ford C4; Erjavec,
  *Automotive Technology*, typed here): in D1 only the overrunning clutch holds the rear
  carrier, and it freewheels on coast; manual 1 holds the same carrier with the band (the
  one-way clutch idle); in D2, D3 it overruns; reverse holds the carrier with the band.
- Which way the clutch must carry, by a second route: the brake reaction of the full
  equilibrium (symkin.statics, every link and mesh) on the carrier, positive in drive.
- Ratios by the lever analogy (hand, typed here); the hub gear's steps are the Sturmey-Archer
  AW's published 1 and 4/3 (top: the ring turns 1 + zs/zr times the cage).
"""

from __future__ import annotations

import importlib.resources
import json

import pytest
import sympy as sp

from symkin.cli import main
from symkin.errors import ModelError, TrainFileError
from symkin.statics import statics
from symkin.trains import load_train, read_train

_TEXT = (importlib.resources.files("symkin.trains") / "library" / "simpson-oneway.toml").read_text()


def test_the_simpson_element_chart():
    train = load_train("simpson-oneway")
    table = {s.state.name: s for s in train.shift_table()}
    chart = {  # state: (F in drive, coast free?, F on coast)
        "D1": ("holds", True, "overruns"), "L1": ("idle", False, "idle"), "D2": ("overruns", False, "overruns"),
        "D3": ("overruns", False, "overruns"), "R": ("idle", False, "idle")}
    for name, (drive, coast_free, coast) in chart.items():
        shift = table[name]
        assert dict(shift.drive.status)["F"] == drive, name
        assert shift.coast.free is coast_free and dict(shift.coast.status)["F"] == coast, name
    # lever analogy: front set 102 w_C1 = 72 w_R1 + 30 w_S, rear set (C2 still) w_S = -(72/30) w_C1
    assert table["D1"].ratio.rhs == table["L1"].ratio.rhs == sp.Rational(174, 72)
    assert table["D2"].ratio.rhs == sp.Rational(102, 72) and table["D3"].ratio.rhs == 1
    assert train.engaged("D1") == (("C2",), ())


def test_the_one_way_clutch_carries_what_the_full_statics_puts_on_the_carrier():
    train = load_train("simpson-oneway")
    drive = statics(train, input="R1", output="C1", fixed=("C2",), efficiency=1)
    assert drive.torques["C2"] > 0  # it pushes C2 forwards: what a clutch blocking "negative" carries
    coast = statics(train, input="C1", output="R1", fixed=("C2",), efficiency=1)  # the output driving
    assert coast.torques["C2"] < 0  # it would have to pull C2 backwards: it overruns


def test_turned_round_the_clutch_leaves_first_free_and_locks_second():
    text = _TEXT.replace('blocks = "negative"', 'blocks = "positive"')
    train = read_train(text.replace("[states.D2]", "[states.X]").split("[states.X]")[0])
    first = train.shift("D1")
    assert first.free and first.ratio is None and first.speeds is None
    assert first.drive.text() == "free (F overruns)"
    assert first.coast.holding == ("F",)  # it holds on coast instead: engine braking, no drive
    assert " free " in train.shift_table().text().splitlines()[3]
    with pytest.raises(ModelError, match="free"):
        train.engaged("D1")
    with pytest.raises(ModelError, match="one-way clutch F would turn C2 positively relative to the frame"):
        read_train(text).shift("D2")


def test_a_hub_gear_drives_through_pawls_and_freewheels():
    train = load_train("hub-3speed")
    normal, top, low = train.shift("normal"), train.shift("top"), train.shift("low")
    # the AW's published steps: top 4/3 faster (1 + 18/54), low 3/4 as fast (the cage at 54/(18 + 54) of the ring)
    assert normal.ratio.rhs == 1 and top.ratio.rhs == sp.Rational(3, 4) and low.ratio.rhs == sp.Rational(4, 3)
    for shift in (normal, top):
        assert dict(shift.drive.status) == {"ring_pawls": "holds", "cage_pawls": "overruns"}
        assert shift.coast.free  # the hub freewheels when the rider stops pedalling
    assert dict(low.drive.status) == {"ring_pawls": "released", "cage_pawls": "holds"} and low.coast.free
    assert train.engaged("low") == ((), (("D", "R"), ("H", "C")))
    text = (importlib.resources.files("symkin.trains") / "library" / "hub-3speed.toml").read_text()
    with pytest.raises(TrainFileError, match="releases no one-way clutch 'pawls'"):
        read_train(text.replace('released = ["ring_pawls"]', 'released = ["pawls"]'))
    with pytest.raises(TrainFileError, match="released: must be a list"):
        read_train(text.replace('released = ["ring_pawls"]', 'released = "ring_pawls"'))


def test_states_prints_the_one_way_clutches_and_json(capsys):
    assert main(["states", "--train", "simpson-oneway", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    d1 = data["states"][0]
    assert d1["one_way"] == {"F": "holds"} and d1["coast"] == {"free": True, "one_way": {"F": "overruns"}}
    assert main(["states", "--train", "simpson-oneway"]) == 0
    assert "coast (output driving)" in capsys.readouterr().out


@pytest.mark.parametrize("table, message", [
    ('[one_way.G]\nlinks = ["C2"]\n', "links: is the pair of links"),
    ('[one_way.G]\nlinks = ["C2", "Q"]\n', "names no link 'Q'"),
    ('[one_way.G]\nlinks = ["C2", "frame"]\nblocks = "back"\n', 'blocks: is "negative"'),
    ('[one_way.G]\nlinks = ["C2", "C2"]\n', "joins C2 to itself"),
    ('[one_way.G]\nlink = ["C2", "frame"]\n', "unknown key 'link'"),
])
def test_bad_one_way_tables_are_one_line_errors(table, message):
    with pytest.raises(TrainFileError, match=message) as info:
        read_train(_TEXT.replace("[states.D1]", table + "\n[states.D1]"), "bad.toml")
    assert "\n" not in str(info.value) and "[one_way.G]" in str(info.value)
