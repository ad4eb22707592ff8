"""What a notebook shows for symkin's objects: a repr under 200 characters (the 1-3 KB
dataclass dumps and the 18.6 KB shift table of before), and HTML where a table says more:
a mechanism or a train as its kinematic scheme (SVG) with its links and shift table.

References: the names each repr must hold are typed here from the train files' contents;
the SVG is parsed as XML by the standard library.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

from symkin import schemes, statics
from symkin._util.display import REPR_LIMIT, short_repr
from symkin.statics import planet_statics
from symkin.trains import load_train


def _objects():
    train = load_train("ravigneaux")
    ai1 = schemes.single_row_AI(teeth=(20, 30, 80), module=1)
    motion = ai1.motion({"4": 0, "H": 1})
    return {
        "train": train,
        "mechanism": ai1,
        "state": train.states[2],
        "shift": train.shift("first"),
        "shift table": train.shift_table(),
        "motion": motion,
        "particle": motion.particle("2", (15, 0)),
        "speeds": ai1.speeds({"4": 0, "H": 1}),
        "statics": statics.statics(train, input="S1", output="R", fixed=["C"]),
        "planet statics": planet_statics(schemes.two_row("AA", teeth=(54, 45, 44, 55), module=1)),
    }


def test_every_repr_is_short():
    for name, obj in _objects().items():
        assert len(repr(obj)) <= REPR_LIMIT, (name, len(repr(obj)))


def test_the_reprs_say_what_the_object_is():
    o = _objects()
    assert repr(o["train"]) == "Train('Ravigneaux', links S1, S2, C, P1, P2, R, states first, second, third, fourth, reverse)"
    assert repr(o["mechanism"]) == "Mechanism('AI1', links 1, 2, H, 4, meshes 1-2, 2-4)"
    assert repr(o["state"]) == "State('third', S1 -> R, brakes -, clutches S1+S2)"
    assert repr(o["shift"]) == "Shift('first', ratio 12/5)"
    assert repr(o["shift table"]) == "ShiftTable('Ravigneaux', first 12/5, second 22/15, third 1, fourth 2/3, reverse -2)"
    assert repr(o["particle"]) == "Particle(link 2 at (15, 0, 0), mechanism 'AI1')" or \
        repr(o["particle"]) == "Particle(link 2 at (15, 0), mechanism 'AI1')"
    assert repr(o["motion"]).startswith("Motion(mechanism 'AI1', inputs ")


def test_a_train_displays_as_its_scheme_its_links_and_its_shift_table():
    html = load_train("simpson")._repr_html_()
    svg = html[html.index("<svg"): html.index("</svg>") + len("</svg>")]
    root = ET.fromstring(svg)
    texts = {"".join(t.itertext()) for t in root.iter("{http://www.w3.org/2000/svg}text")}
    assert {"S", "R1", "C1", "C2", "P1", "P2"} <= texts
    assert "<th>ratio</th>" in html and "<th>gears (teeth)</th>" in html
    assert len(html) < 60_000


def test_a_mechanism_that_cannot_be_drawn_still_shows_its_table():
    html = schemes.two_row("AI")._repr_html_()  # symbolic radii: no picture
    assert "<svg" not in html and "<table>" in html


def test_a_state_and_a_shift_show_as_tables():
    train = load_train("simple")
    assert "<td>low</td>" in train.state("low")._repr_html_()
    assert "state low: ratio 4" in train.shift("low")._repr_html_()


@pytest.mark.parametrize("parts, expected", [
    (("a", "b"), "X(a, b)"),
    (("y" * 300,), "X(" + "y" * (REPR_LIMIT - 6) + "...)"),
])
def test_short_repr_cuts_at_the_limit(parts, expected):
    assert short_repr("X", *parts) == expected


def test_a_design_and_a_synthesis_show_their_teeth_in_short():
    import symkin

    result = symkin.synthesize("simple", driver="S", driven="C", fixed="R", ratio=4, planets=3, zmax=80, top=2)
    design = result.designs[0]
    assert len(repr(result)) <= REPR_LIMIT and len(repr(design)) <= REPR_LIMIT
    assert repr(design).startswith("Design(z_s=") and "ratio 4" in repr(design)
    html = design._repr_html_()
    assert "<td>ratio</td><td>4</td>" in html and html.startswith("<table>")
