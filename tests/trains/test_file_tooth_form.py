"""The tooth form keys of a gear table in a train file: read exactly, checked with one-line errors."""

from __future__ import annotations

import pytest
import sympy as sp

from symkin.errors import TrainFileError
from symkin.trains import read_train

TRAIN = """
module = 2
meshes = [["s", "p"]]
[links.S]
gears = {{ s = {{ teeth = 20, {keys} }} }}
[links.C]
[links.P]
carrier = "C"
gears = {{ p = 30 }}
"""


def test_the_keys_are_read_exactly():
    train = read_train(TRAIN.format(keys="shift = 0.25, addendum = 0.8, dedendum = 1.1, pressure_angle = 25, "
                                    "fillet = 0.3, tip_diameter = 43.5"))
    assert dict(train.tooth_forms) == {"s": (("addendum", sp.Rational(4, 5)), ("dedendum", sp.Rational(11, 10)),
                                             ("fillet", sp.Rational(3, 10)), ("pressure_angle", 25),
                                             ("shift", sp.Rational(1, 4)), ("tip_diameter", sp.Rational(87, 2)))}
    assert read_train(TRAIN.format(keys="internal = false")).tooth_forms == ()


@pytest.mark.parametrize("keys, message", [
    ('shift = "x"', "gears.s shift"),
    ("shift = 9", "within -5 and 5"),
    ("pressure_angle = 90", "in degrees, from 5 to 45"),
    ("addendum = -1", "must be positive"),
    ('dedendum = "pi/3"', "a plain number"),
    ("fillet = 0", "must be positive"),
    ("shift = true", "must be a number"),
    ("bend = 1", "unknown key 'bend'"),
])
def test_bad_values_are_one_line_errors_naming_the_key(keys, message):
    with pytest.raises(TrainFileError, match=message) as err:
        read_train(TRAIN.format(keys=keys))
    assert "\n" not in str(err.value)
