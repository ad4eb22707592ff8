"""The DXF and SVG of a train's outlines read back: ezdxf's audit, one closed polyline per gear on its
own layer, radii equal to the tip and root radii, flanks on the involute, meshing teeth that do not cross."""

from __future__ import annotations

import io
import math
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest

from symkin.geometry import train_geometry
from symkin.geometry.export import dxf_text, layer_name, svg_text
from symkin.trains import load_train
from tests.geometry.test_outline import _on_the_most_common_value, flank_classes
from tests.support.segments import crossings


@pytest.fixture(scope="module")
def simple():
    return train_geometry(load_train("simple"))


@pytest.fixture(scope="module")
def drawing(simple):
    return ezdxf.read(io.StringIO(dxf_text(simple)))


def test_the_dxf_of_a_simple_planetary_passes_ezdxfs_audit(drawing):
    auditor = drawing.audit()
    assert not auditor.has_errors and not auditor.has_fixes
    assert drawing.units == ezdxf.units.MM


def test_every_gear_is_one_closed_polyline_on_its_layer_at_its_place(simple, drawing):
    lines = list(drawing.modelspace().query("LWPOLYLINE"))
    assert sorted(e.dxf.layer for e in lines) == sorted(layer_name(g) for g in simple.gears)
    for e in lines:
        name = e.dxf.layer.removeprefix("gear-")
        gear = simple.gears[name]
        cx, cy, _ = simple.placement[name]
        assert e.closed
        pts = np.array([p[:2] for p in e.get_points()])
        x, y = pts[:, 0] - cx, pts[:, 1] - cy
        r = np.hypot(x, y)
        assert r.max() == pytest.approx(float(max(gear.tip_diameter, gear.root_diameter)) / 2, abs=1e-9)
        assert r.min() == pytest.approx(float(min(gear.tip_diameter, gear.root_diameter)) / 2, abs=1e-9)
        one, other = flank_classes(gear, np.append(x, x[0]), np.append(y, y[0]))
        pitch = 2 * math.pi / int(gear.teeth)
        assert np.all(_on_the_most_common_value(one, pitch) | _on_the_most_common_value(other, pitch))
        assert crossings(np.append(x, x[0]), np.append(y, y[0])) == 0


def _distance_to(px, py, x, y):
    """Each point's distance from the polyline (x, y)."""
    ax, ay, bx, by = x[:-1], y[:-1], x[1:], y[1:]
    dx, dy = bx - ax, by - ay
    t = np.clip(((px[:, None] - ax) * dx + (py[:, None] - ay) * dy) / (dx * dx + dy * dy), 0, 1)
    return np.min(np.hypot(ax + t * dx - px[:, None], ay + t * dy - py[:, None]), axis=1)


@pytest.mark.parametrize("train", ["simple", "ravigneaux", "wolfrom"])
def test_meshing_gears_interleave(train):
    """No point of one gear's outline lies inside the other gear's teeth farther than the polylines' chords
    from its outline (the flanks touch at zero backlash; a tooth in a tooth would be a module deep), except
    where the interference checks say so."""
    from matplotlib.path import Path

    from symkin.geometry.export import placed_outlines

    geo = train_geometry(load_train(train))
    shapes = placed_outlines(geo, points=16)
    for m in geo.meshes:
        (x1, y1), (x2, y2) = shapes[m.gears[0]], shapes[m.gears[1]]
        inside = Path(np.column_stack([x2, y2])).contains_points(np.column_stack([x1, y1]))
        if geo.gears[m.gears[1]].internal:  # the ring's material is outside its outline (out to its rim)
            inside = ~inside & (np.hypot(x1, y1) > 0)
        depth = _distance_to(x1[inside], y1[inside], x2, y2).max(initial=0)
        assert depth < 0.1, m.gears  # the teeth interleave
        # and touch only, unless the checks found interference (ravigneaux's ring, wolfrom's 12-tooth sun):
        # then a tip cuts a few micrometres into the partner's flank
        interference = any("interference" in p for p in m.problems)
        assert (depth > 2e-3) == interference, (m.gears, depth)


def test_the_svg_has_a_path_per_gear(simple):
    root = ET.fromstring(svg_text(simple))
    paths = root.findall(".//{http://www.w3.org/2000/svg}path")
    assert sorted(p.get("id") for p in paths) == sorted(layer_name(g) for g in simple.gears)
    assert all(p.get("d").startswith("M ") and p.get("d").endswith(" Z") for p in paths)
