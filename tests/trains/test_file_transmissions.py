"""The ready-made transmissions against their published ratios and hand levers.

- The eight-speed automatic (ZF 8HP layout, 8HP70 tooth numbers): the published ratio set
  4.696, 3.130, 2.104, 1.667, 1.285, 1.000, 0.839, 0.667, R -3.297 (ZF data sheets), typed here;
  first gear by hand: brakes A and B stop set 1, so ring 4 stands and sun 4 turns with the
  input: 1 + 85/23.
- The power split's mechanical point: the generator (sun) standing, the ring turns
  (30 + 78)/78 times the engine's carrier (Willis, typed).
(Willis per mesh for every state of every ready-made train is in test_train.py.)
"""

from __future__ import annotations

import sympy as sp

from symkin.trains import load_train

PUBLISHED_8HP = {"first": 4.696, "second": 3.130, "third": 2.104, "fourth": 1.667, "fifth": 1.285, "sixth": 1.000,
                 "seventh": 0.839, "eighth": 0.667, "reverse": -3.297}


def test_the_eight_speed_gives_the_published_ratio_set():
    table = {s.state.name: s.ratio.rhs for s in load_train("eight-speed").shift_table()}
    assert set(table) == set(PUBLISHED_8HP)
    for name, published in PUBLISHED_8HP.items():
        assert abs(float(table[name]) - published) < 0.0005, name
    assert table["first"] == 1 + sp.Rational(85, 23)


def test_the_power_split_mechanical_point():
    assert load_train("power-split").shift("mechanical-point").ratio.rhs == sp.Rational(78, 30 + 78)
