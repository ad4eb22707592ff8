"""Kinematic schemes and lever diagrams (symkin.viz.diagram), read back from the SVG files.

The references are the train files themselves, read here with tomllib (not symkin's reader):
- every link the file names is named once in the scheme, and "frame" where something is
  fixed to it; every mesh the file lists is drawn;
- geometry: each gear's pitch outline measured in the SVG (pixels, converted by the scale
  that one gear fixes) against module * teeth / 2 from the file: a gear on the main axis
  reaches its pitch radius, a ring starts there, a planet spans its pitch diameter, and
  gears drawn touching touch at their pitch circles;
- lever diagrams: node spacing against the tooth numbers of a simple set (Benford and
  Leising: |S-C| : |C-R| = z_R : z_S), and the arrow tips of the speeds collinear (the
  lever's linearity) for every state of every ready-made train;
- the figures pass symkin's layout check (:func:`symkin.viz.style.layout_problems`).
"""

from __future__ import annotations

import re
import sys
import xml.etree.ElementTree as ET
from fractions import Fraction
from importlib.resources import files
from pathlib import Path

import pytest

from symkin.errors import InputError
from symkin.trains import load_train, ready_made
from symkin.viz.diagram import diagram, text_as_text
from symkin.viz.figures import save
from symkin.viz.style import layout_problems
from tests.support.train_texts import SYMBOLIC_SIMPLE

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

READY = sorted(ready_made())
SVG = "{http://www.w3.org/2000/svg}"


def _file(name):
    return tomllib.loads(files("symkin.trains").joinpath("library", f"{name}.toml").read_text())


def _svg(fig, path):
    with text_as_text():
        save(fig, path)
    root = ET.parse(path).getroot()
    return {g.get("id"): g for g in root.iter(f"{SVG}g") if g.get("id") and ":" in g.get("id")}


def _points(group):
    """The (x, y) points of the first path in an SVG group (pixels, y down)."""
    path = next(group.iter(f"{SVG}path"))
    nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", path.get("d"))]
    return list(zip(nums[0::2], nums[1::2]))


def _text(group):
    return "".join(next(group.iter(f"{SVG}text")).itertext())


def _gears(data):
    """gear name -> (link, pitch radius, internal, bevel) from the file's own numbers."""
    module = Fraction(str(data.get("module", 1)))
    out = {}
    for link, table in data["links"].items():
        for gear, spec in table.get("gears", {}).items():
            spec = spec if isinstance(spec, dict) else {"teeth": spec}
            m = Fraction(str(spec.get("module", module)))
            out[gear] = (link, m * spec["teeth"] / 2, spec.get("internal", False), spec.get("bevel", False))
    return out


@pytest.mark.parametrize("name", READY)
def test_the_scheme_names_every_link_once_and_draws_every_mesh(name, tmp_path):
    data = _file(name)
    ids = _svg(diagram(load_train(name)), tmp_path / f"{name}.svg")
    names = [_text(g) for key, g in ids.items() if key.startswith("link:")]
    braked = any(s.get("brakes") for s in data.get("states", {}).values())
    expected = {n for n in data["links"] if n != "frame"} | ({"frame"} if "frame" in data["links"] or braked else set())
    assert sorted(names) == sorted(expected)
    for mesh in data["meshes"]:
        a, b = mesh["gears"] if isinstance(mesh, dict) else mesh
        assert f"mesh:{a}-{b}" in ids, (a, b)
    for gear in _gears(data):
        assert f"gear:{gear}" in ids, gear


@pytest.mark.parametrize("name", READY)
def test_the_scheme_s_pitch_outlines_are_the_file_s_radii(name, tmp_path):
    data = _file(name)
    gears = _gears(data)
    ids = _svg(diagram(load_train(name)), tmp_path / f"{name}.svg")
    axis_y = _points(ids["axis:main"])[0][1]
    boxes = {}
    for gear in gears:
        pts = _points(ids[f"gear:{gear}"])
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        boxes[gear] = (min(xs), max(xs), axis_y - max(ys), axis_y - min(ys))  # heights above the main axis
    # the scale: the largest radius among gears on the main axis, pixels per mm
    on_axis = [g for g, (link, r, internal, bevel) in gears.items() if "carrier" not in data["links"][link]]
    ref = max(on_axis, key=lambda g: gears[g][1])
    scale = (boxes[ref][2] if gears[ref][2] else boxes[ref][3]) / float(gears[ref][1])
    for gear, (link, r, internal, bevel) in gears.items():
        lo, hi = boxes[gear][2] / scale, boxes[gear][3] / scale
        width = (boxes[gear][1] - boxes[gear][0]) / scale
        planet = "carrier" in data["links"][link]
        if bevel and planet:  # a bevel pinion: its pitch circle seen edge on across the drawing
            assert width == pytest.approx(2 * float(r), rel=1e-3), gear
        elif bevel or (not planet and not internal):
            assert hi == pytest.approx(float(r), rel=1e-3), gear
        elif internal:
            assert lo == pytest.approx(float(r), rel=1e-3), gear
        else:
            assert hi - lo == pytest.approx(2 * float(r), rel=1e-3), gear
    # gears drawn in one column touch at their pitch circles
    for mesh in data["meshes"]:
        a, b = mesh["gears"] if isinstance(mesh, dict) else mesh
        if isinstance(mesh, dict) and "centre_distance" in mesh:
            continue  # a shifted mesh works on other circles than the pitch circles drawn
        if gears[a][3] or abs((boxes[a][0] + boxes[a][1]) - (boxes[b][0] + boxes[b][1])) > 1e-6:
            continue
        edges_a, edges_b = boxes[a][2:], boxes[b][2:]
        assert min(abs(x - y) for x in edges_a for y in edges_b) < 1e-3 * scale, (a, b)


def test_a_scheme_in_metres_has_its_radii_in_metres():
    fig = diagram(load_train("simple"), length_unit="m")
    ax = fig.axes[0]
    assert ax.get_ylabel() == "radius [m]"
    assert 0.036 < ax.get_ylim()[1] < 0.1  # the ring's pitch radius, 36 mm, is in view


def test_a_state_highlights_its_brakes_and_clutches_and_names_input_and_output(tmp_path):
    ids = _svg(diagram(load_train("ravigneaux"), "second"), tmp_path / "r.svg")
    assert _text(ids["link:S1"]) == "S1 (in)" and _text(ids["link:R"]) == "R (out)"
    on = "stroke: #d55e00"  # the highlight colour
    assert on in ET.tostring(ids["brake:S2"]).decode()
    assert on not in ET.tostring(ids["brake:C"]).decode()
    assert on not in ET.tostring(ids["clutch:S1+S2"]).decode()


@pytest.mark.parametrize("name", READY)
def test_the_lever_diagram_is_linear_in_every_state(name, tmp_path):
    """Each lever's arrow tips on one straight line over its own nodes (the lever's linearity),
    held nodes at rest, and a link on two levers (sets joined by a single link, as the 8HP's four
    levers are) at one speed on both: its two arrows equally long on the shared speed scale."""
    train = load_train(name)
    for state in train.states:
        ids = _svg(diagram(train, state.name, lever=True), tmp_path / f"{name}-{state.name}.svg")
        tips: dict[str, list[tuple[float, float]]] = {}
        length: dict[str, list[float]] = {}
        for key, group in ids.items():
            if key.startswith("speed:"):
                (x0, y0), (x1, y1) = _points(group)[:2]
                assert y0 == pytest.approx(y1)
                link, _, lever = key[6:].partition("@")
                tips.setdefault(lever, []).append((x1, y0))
                length.setdefault(link, []).append(x1 - x0)
                node = _points(ids[f"node:{key[6:]}"])
                assert node[0][1] == pytest.approx(y0)
        assert tips
        for lever, points in tips.items():
            assert len(points) >= 2, (state.name, lever)
            points.sort(key=lambda p: p[1])
            (xa, ya), (xb, yb) = points[0], points[-1]
            for x, y in points[1:-1]:  # every tip on the line through the outermost two
                assert abs((x - xa) * (yb - ya) - (xb - xa) * (y - ya)) < 1e-3 * abs(yb - ya) * max(1.0, abs(xb - xa)), \
                    (state.name, lever, x, y)
        for link, arrows in length.items():
            assert max(arrows) - min(arrows) < 1e-3 * max(1.0, *map(abs, arrows)), (state.name, link, arrows)
        for b in state.brakes:
            for arrow in length[train.link(b).name]:
                assert arrow == pytest.approx(0, abs=1e-6)


def test_the_8hp_s_levers_are_its_four_sets_joined_by_single_links(tmp_path):
    """The ZF 8HP's four simple sets share one link pairwise, never two: four levers, each with
    |S - C| : |C - R| = z_R : z_S typed from the file, joined where a link recurs."""
    data = _file("eight-speed")
    ids = _svg(diagram(load_train("eight-speed"), "first", lever=True), tmp_path / "8hp.svg")
    sets = {1: ("S12", "C1", "R1", "s1", "r1"), 2: ("S12", "IN", "R2", "s2", "r2"),
            3: ("R2", "C3", "R3", "s3", "r3"), 4: ("R3", "OUT", "C1", "s4", "r4")}
    teeth = {g: (t if isinstance(t, int) else t["teeth"]) for link in data["links"].values()
             for g, t in link.get("gears", {}).items()}
    for k, (sun, carrier, ring, zs, zr) in sets.items():
        y = {n: _points(ids[f"node:{n}@{k}"])[0][1] for n in (sun, carrier, ring)}
        assert (y[sun] - y[carrier]) * (y[ring] - y[carrier]) < 0, k
        assert abs(y[sun] - y[carrier]) / abs(y[carrier] - y[ring]) == pytest.approx(teeth[zr] / teeth[zs]), k
    assert not any(key.startswith("node:") and "@" not in key for key in ids)


def test_the_lever_s_node_spacing_is_the_tooth_numbers_of_a_simple_set(tmp_path):
    data = _file("simple")
    z_s, z_r = data["links"]["S"]["gears"]["s"], data["links"]["R"]["gears"]["r"]["teeth"]
    ids = _svg(diagram(load_train("simple"), lever=True), tmp_path / "lever.svg")
    y = {n: _points(ids[f"node:{n}"])[0][1] for n in ("S", "C", "R")}
    assert (y["S"] - y["C"]) * (y["R"] - y["C"]) < 0  # the carrier between sun and ring
    assert abs(y["S"] - y["C"]) / abs(y["C"] - y["R"]) == pytest.approx(z_r / z_s)


@pytest.mark.parametrize("name", READY)
def test_the_pictures_pass_the_layout_check(name, tmp_path):
    train = load_train(name)
    state = train.states[0].name
    for lever in (False, True):
        fig = diagram(train, state, lever=lever)
        save(fig, tmp_path / "d.png")
        assert layout_problems(fig) == [], (name, lever)


def test_what_cannot_be_drawn_is_a_clear_error():
    from symkin.trains import read_train

    with pytest.raises(InputError, match="symbolic tooth numbers"):
        diagram(read_train(SYMBOLIC_SIMPLE))
    with pytest.raises(InputError, match="unknown length unit"):
        diagram(load_train("simple"), length_unit="furlong")
    with pytest.raises(Exception, match="no state 'x'"):
        diagram(load_train("simple"), "x")


def test_a_mechanism_without_states_is_drawn_too():
    from symkin import schemes

    fig = diagram(schemes.two_row("AI", teeth=(20, 30, 20, 70), module=1))
    texts = sorted(t.get_text() for t in fig.axes[0].texts if (t.get_gid() or "").startswith("link:"))
    assert texts == sorted(n for n in ("1", "23", "4", "H"))


def test_docs_show_every_ready_made_train_s_scheme_and_lever_as_symkin_draws_them_today(tmp_path):
    docs = Path(__file__).resolve().parents[2] / "docs"
    page = (docs / "trains.md").read_text()
    for name in READY:
        train = load_train(name)
        for kind in ("scheme", "lever"):
            picture = docs / "trains" / f"{name}-{kind}.svg"
            assert f"](trains/{name}-{kind}.svg)" in page and picture.is_file(), picture
            if name not in ("simple", "ravigneaux", "nested", "bevel-epicyclic"):
                continue  # (a few redrawn: each takes a moment)
            tracked = ET.parse(picture).getroot()
            fresh = _svg(diagram(train, lever=kind == "lever"), tmp_path / "fresh.svg")
            ids = {g.get("id") for g in tracked.iter(f"{SVG}g") if g.get("id") and ":" in g.get("id")}
            assert ids == set(fresh), f"{picture.name} is stale: python docs/gallery.py --trains"
            texts = sorted("".join(t.itertext()) for t in tracked.iter(f"{SVG}text"))
            assert texts == sorted("".join(t.itertext()) for t in ET.parse(tmp_path / "fresh.svg").getroot().iter(
                f"{SVG}text")), f"{picture.name} is stale: python docs/gallery.py --trains"
