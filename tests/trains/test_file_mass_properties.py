"""Train files: the mass-property keys (inertia, mass, stiffness) read exactly, and their one-line errors."""

from __future__ import annotations

import pytest
import sympy as sp

from symkin.errors import TrainFileError
from symkin.trains import read_train

BASE = """
module = 1
meshes = [{ gears = ["s", "p"], stiffness = 5e8 }, ["p", "r"]]
[links.S]
gears = { s = 24 }
inertia = 0.01
[links.C]
inertia = "J_C"
[links.P]
carrier = "C"
count = 3
gears = { p = 24 }
inertia = 0.002
mass = 0.5
[links.R]
gears = { r = { teeth = 72, internal = true } }
stiffness = 1e6
"""


def test_numbers_are_exact_and_names_are_symbols():
    train = read_train(BASE)
    assert train.link("S").inertia == sp.Rational(1, 100)
    assert train.link("C").inertia == sp.Symbol("J_C", positive=True)
    assert (train.link("P").inertia, train.link("P").mass) == (sp.Rational(1, 500), sp.Rational(1, 2))
    assert train.link("R").stiffness == 10**6 and train.link("R").inertia is None
    assert train.meshes[0].stiffness == 5 * 10**8 and train.meshes[1].stiffness is None


@pytest.mark.parametrize("old, new, message", [
    ("inertia = 0.01", "inertia = -1", "[links.S] inertia: must be 0 or more"),
    ("inertia = 0.01", "mass = 2", "[links.S] mass: only a planet takes a mass"),
    ("inertia = 0.01", "inertia = true", "[links.S] inertia: must be a number"),
    ("inertia = 0.01", 'inertia = "x y"', "[links.S] inertia"),
    ("mass = 0.5", "mass = 0.5\nstiffness = 3", "[links.P] stiffness: a planet takes no shaft stiffness"),
    ("stiffness = 5e8", 'stiffness = "1/0"', "meshes[1] stiffness"),
    ("stiffness = 5e8", "inertia = 1", "unknown key 'inertia'"),
])
def test_bad_values_are_one_line_errors_naming_the_table_and_key(old, new, message):
    with pytest.raises(TrainFileError) as err:
        read_train(BASE.replace(old, new, 1))
    assert message in str(err.value) and "\n" not in str(err.value)
