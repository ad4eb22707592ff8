"""A train file's module is in millimetres (ISO 54), as a number or as text with a unit.

References: 1 in = 25.4 mm and 1 m = 1000 mm typed here; the pitch radius module * z / 2.
"""

from __future__ import annotations

import pytest
import sympy as sp

from symkin.errors import TrainFileError
from symkin.trains import read_train

TEXT = """name = "x"
module = {module}
meshes = [["s", "p"], ["p", "r"]]
[links.S]
gears = {{ s = 20 }}
[links.C]
[links.P]
carrier = "C"
gears = {{ p = {planet} }}
[links.R]
gears = {{ r = {{ teeth = 60, internal = true }} }}
[states.low]
input = "S"
output = "C"
brakes = ["R"]
"""


@pytest.mark.parametrize("module, mm", [
    ("1.5", sp.Rational(3, 2)),
    ('"1.5 mm"', sp.Rational(3, 2)),
    ('"0.0015 m"', sp.Rational(3, 2)),
    ('"0.06 in"', sp.Rational(6, 100) * sp.Rational(254, 10)),
    ('"3/2"', sp.Rational(3, 2)),
])
def test_the_module_is_in_mm_with_or_without_a_unit(module, mm):
    train = read_train(TEXT.format(module=module, planet="20"))
    assert train.gear("s").radius == mm * 20 / 2
    assert train.gear("r").radius == mm * 60 / 2
    assert train.shift("low").ratio.rhs == 4  # 1 + 60/20: the module cancels


def test_a_gear_s_own_module_takes_a_unit_too():
    train = read_train(TEXT.format(module=1, planet='{ teeth = 20, module = "1 mm" }'))
    assert train.gear("p").radius == 10


@pytest.mark.parametrize("module, message", [
    ('"2 s"', "module: s is not a unit of mm"),
    ('"-1 mm"', "module must be positive"),
    ('"1 parsec kg"', "module"),
])
def test_a_module_in_another_dimension_is_a_clear_error(module, message):
    with pytest.raises(TrainFileError, match=message):
        read_train(TEXT.format(module=module, planet="20"))
