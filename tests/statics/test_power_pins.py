"""Planet bearing (pin) loads against hand statics and the carrier's torque balance.

- Simple set, sun driving, ring held (hand): the sun's and the ring's tangential forces on a
  planet are equal and point the same way, their separating forces cancel, so each pin takes
  |T_C| / (arm x planets) across the arm: 4 / (24 x 3) per unit sun torque.
- Any train (double pinion, Ravigneaux, Wolfrom): the pins carry the carrier's torque, the
  sum over planets of copies x (position x pin load) equals the carrier's mesh torque.
- The power split at an operating point: 100 N m on the carrier over four pins at 27 mm.
"""

from __future__ import annotations

import pytest
import sympy as sp

from symkin.model import LinkKind
from symkin.statics import operating_point, statics
from symkin.trains import load_train


def test_simple_set_pin_by_hand():
    res = statics(load_train("simple"), input="S", output="C", fixed=("R",), efficiency=1)
    assert res.pins == {"P": (0, sp.Rational(4, 24 * 3))}  # the planet at angle 0: the load across the arm (+y)


@pytest.mark.parametrize("name, state", [("double-pinion", None), ("ravigneaux", "first"), ("wolfrom", "drive"),
                                         ("simpson", "first")])
def test_pins_carry_the_carrier_torque(name, state):
    train = load_train(name)
    st = train.state(state) if state else None
    res = (statics(train, input=st.input, output=st.output, fixed=st.brakes, joined=st.clutches, efficiency=1) if st
           else statics(train, input="S", output="R", fixed=("C",), efficiency=1))
    carriers = {train.link(p).carrier for p in res.pins} - {L.name for L in train.links if L.gears}
    assert carriers  # (a carrier with gears of its own balances their meshes too: not this check)
    for c in carriers:
        planets = [L for L in train.links if L.kind is LinkKind.PLANET and L.carrier == c]
        moment = 0
        for L in planets:
            x, y = train.axis_position(L.name)
            fx, fy = res.pins[L.name]
            moment += L.count * (x * fy - y * fx)
        # the carrier's external torque balances what its pins take (a carrier without a shaft: zero)
        assert sp.simplify(moment + res.torques[c]) == 0, c


def test_power_split_pins_at_an_operating_point():
    op = operating_point(load_train("power-split"), {"C": 200, "R": 150}, {"C": 100}, efficiency=1)
    x, y = op.pins["P"]
    assert y == -sp.Rational(100 * 1000, 27 * 4)    # N: 100 N m over 4 pins at 27 mm, resisting the engine
    assert abs(float(x)) < 0.01 * abs(float(y))      # the shifted meshes' separating forces nearly cancel
