"""One-way clutches in the kinematic scheme and the lever diagram (symkin.viz.diagram), read back from SVG.

The reference is not symkin's engagement search: which one-way clutch holds and which overruns
is worked out here from the train file's tooth numbers (read with tomllib) by Willis' equation
of each simple set, ``(w_S - w_C) / (w_R - w_C) = -z_R / z_S``, solved with sympy:
- a state its brakes and clutches fix: the freewheel's relative speed says idle (zero) or
  overrunning (the free way);
- a state they leave free (one degree of freedom): in drive the freewheel holds when, with the
  output standing (held by its load) and the input turning forwards, its link would turn the
  way it blocks (the reaction it carries);
- the hub's pawls: the hub may not turn slower than any engaged pawl's driver, so the fastest
  driver's pawls drive it and the others overrun.
"""

from __future__ import annotations

import sys
import xml.etree.ElementTree as ET
from importlib.resources import files

import pytest
import sympy as sp

from symkin.trains import load_train, read_train
from symkin.viz.diagram import diagram
from tests.viz.test_diagram import SVG, _svg

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

HOLDS, OVERRUNS = "stroke: #d55e00", "stroke: #56b4e9"


def _text(name):
    return files("symkin.trains").joinpath("library", f"{name}.toml").read_text()


def _teeth(data):
    return {g: (t if isinstance(t, int) else t["teeth"]) for link in data["links"].values()
            for g, t in link.get("gears", {}).items()}


def _simpson_speeds(data, fixed):
    """Every link's speed of the Simpson (front set s1/r1 on C1, rear s2/r2 on C2; S common, the
    rear ring on C1) with ``fixed`` pairs (link, speed or link joined to it); None when they leave it free."""
    z = _teeth(data)
    w = dict(zip(("R1", "C1", "S", "C2"), sp.symbols("R1 C1 S C2")))
    eqs = [sp.Eq((w["S"] - w["C1"]) * z["s1"], -z["r1"] * (w["R1"] - w["C1"])),
           sp.Eq((w["S"] - w["C2"]) * z["s2"], -z["r2"] * (w["C1"] - w["C2"]))]
    eqs += [sp.Eq(w[a], v if not isinstance(v, str) else w[v]) for a, v in fixed]
    sol = sp.solve(eqs, list(w.values()), dict=True)
    if len(sol) != 1 or any(x not in sol[0] for x in w.values()):
        return None
    return {n: sol[0][x] for n, x in w.items()}


def _simpson_expected(data, state):
    fixed = [(b, 0) for b in state.get("brakes", [])] + [tuple(c) for c in state.get("clutches", [])]
    fixed.append((state["input"], 1))
    speeds = _simpson_speeds(data, fixed)
    if speeds is not None:  # fixed by its own brakes and clutches
        return "idle" if speeds["C2"] == 0 else "overruns" if speeds["C2"] > 0 else "locks"
    loaded = _simpson_speeds(data, [*fixed, (state["output"], 0)])
    return "holds" if loaded["C2"] < 0 else "free"  # F blocks C2 turning backwards


def _styles(ids, key):
    return ET.tostring(ids[key]).decode()


def _named(path, word):
    return sum("".join(t.itertext()) == word for t in ET.parse(path).getroot().iter(f"{SVG}text"))


def test_the_simpson_s_freewheel_holds_first_gear_and_overruns_where_willis_says(tmp_path):
    data = tomllib.loads(_text("simpson-oneway"))
    train = load_train("simpson-oneway")
    seen = set()
    for name, state in data["states"].items():
        expected = _simpson_expected(data, state)
        seen.add(expected)
        path = tmp_path / f"{name}.svg"
        ids = _svg(diagram(train, name), path)
        assert _named(path, "F (one-way)") == 1
        style = _styles(ids, "oneway:F")
        assert (HOLDS in style) == (expected == "holds"), (name, expected)
        assert (OVERRUNS in style and "stroke-dasharray" in style) == (expected == "overruns"), (name, expected)
        # the lever: F grounds C2 only where it holds (or a band holds C2 beside it)
        levers = _svg(diagram(train, name, lever=True), tmp_path / f"{name}-lever.svg")
        grounded = expected == "holds" or "C2" in state.get("brakes", [])
        assert ("ground:C2" in levers) == grounded, name
    assert seen == {"holds", "idle", "overruns"}  # every case met


def test_the_hub_s_fastest_driver_drives_it_through_its_pawls(tmp_path):
    data = tomllib.loads(_text("hub-3speed"))
    z = _teeth(data)
    ring_per_cage = sp.Rational(z["r"] + z["s"], z["r"])  # the sun fixed: w_R = (1 + z_S/z_R) w_C
    train = load_train("hub-3speed")
    pawls = {name: spec["links"][1] for name, spec in data["one_way"].items()}  # pawl -> its driver
    for name, state in data["states"].items():
        (_, driven), = state["clutches"]  # the driver D turns the ring or the cage
        w = {"R": 1, "C": 1 / ring_per_cage} if driven == "R" else {"C": 1, "R": ring_per_cage}
        engaged = {p: d for p, d in pawls.items() if p not in state.get("released", [])}
        fastest = max(engaged, key=lambda p: w[engaged[p]])
        path = tmp_path / f"{name}.svg"
        ids = _svg(diagram(train, name), path)
        for p in pawls:
            assert _named(path, f"{p} (one-way)") == 1
            style = _styles(ids, f"oneway:{p}")
            assert (HOLDS in style) == (p == fastest), (name, p)
            assert (OVERRUNS in style) == (p in engaged and p != fastest), (name, p)


def test_a_free_state_is_drawn_without_speeds_and_says_so(tmp_path):
    text = _text("simpson-oneway").replace('blocks = "negative"', 'blocks = "positive"')
    text = text[:text.index("[states.L1]")]  # only D1: a freewheel the wrong way round cannot hold it
    data = tomllib.loads(text)
    loaded = _simpson_speeds(data, [("R1", 1), ("C1", 0)])
    assert loaded["C2"] < 0  # loaded, C2 would turn backwards: a freewheel blocking forwards carries nothing
    train = read_train(text)
    assert train.shift("D1").free
    levers = diagram(train, "D1", lever=True)
    ids = _svg(levers, tmp_path / "lever.svg")
    assert not any(key.startswith(("speed:", "ground:C2")) for key in ids)
    assert "free" in levers.get_suptitle()
    scheme = diagram(train, "D1")
    assert "free" in scheme.axes[0].get_title()
    style = _styles(_svg(scheme, tmp_path / "scheme.svg"), "oneway:F")
    assert HOLDS not in style


@pytest.mark.parametrize("name", ["simpson-oneway", "hub-3speed"])
def test_without_a_state_the_one_way_clutches_are_drawn_plain(name, tmp_path):
    path = tmp_path / "s.svg"
    ids = _svg(diagram(load_train(name)), path)
    for ow in tomllib.loads(_text(name))["one_way"]:
        style = _styles(ids, f"oneway:{ow}")
        assert HOLDS not in style and OVERRUNS not in style
