"""The lever analogy (symkin.trains.lever) against Benford and Leising's rules typed here,
and against the engine's speeds by the lever's linearity.

- Node spacing: a simple set's sun and ring lie on either side of the carrier at distances
  in the ratio z_R : z_S; a double-pinion set's on one side, in the same ratio (Benford and
  Leising 1981, SAE 810102). The Ravigneaux and Simpson levers are the two sets' levers
  joined; each set's rule is checked on the joined lever.
- Speeds: for every state of every ready-made train, the engine's speeds (Train.shift,
  solved from the contact conditions) lie on a straight line over the lever's positions,
  which come from tooth numbers only.
"""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy as sp

from symkin import symbols as S
from symkin.model import FRAME
from symkin.trains import load_train, ready_made
from symkin.trains.lever import Lever, levers
from tests.support.train_texts import SYMBOLIC_SIMPLE

READY = sorted(ready_made())


def _one(name):
    found = levers(load_train(name))
    assert len(found) == 1
    return found[0].positions


def _simple_set(pos, sun, carrier, ring, z_sun, z_ring):
    """A simple set: sun and ring on either side of the carrier, |S-C| : |C-R| = z_R : z_S."""
    s, c, r = pos[sun] - pos[carrier], 0, pos[ring] - pos[carrier]
    assert (s > c) != (r > c)
    assert Fraction(abs(s), abs(r)) == Fraction(z_ring, z_sun)


def _double_pinion_set(pos, sun, carrier, ring, z_sun, z_ring):
    """A double-pinion set: sun and ring on one side of the carrier, |S-C| : |R-C| = z_R : z_S."""
    s, r = pos[sun] - pos[carrier], pos[ring] - pos[carrier]
    assert (s > 0) == (r > 0)
    assert Fraction(abs(s), abs(r)) == Fraction(z_ring, z_sun)


def test_a_simple_set_has_the_carrier_between_sun_and_ring_spaced_by_their_teeth():
    _simple_set(_one("simple"), "S", "C", "R", 24, 72)


def test_a_double_pinion_set_has_sun_and_ring_on_one_side():
    _double_pinion_set(_one("double-pinion"), "S", "C", "R", 30, 90)


def test_the_ravigneaux_lever_joins_a_double_pinion_and_a_simple_set():
    pos = _one("ravigneaux")  # s1 - p1 - p2 - r: double pinion; s2 - p2 - r: simple
    _double_pinion_set(pos, "S1", "C", "R", 30, 72)
    _simple_set(pos, "S2", "C", "R", 36, 72)
    assert len(pos) == 4


def test_the_simpson_lever_joins_its_two_simple_sets_at_the_sun_and_the_front_carrier():
    pos = _one("simpson")  # front: S, C1, R1; rear: S, C2 and ring r2 on C1
    _simple_set(pos, "S", "C1", "R1", 30, 72)
    _simple_set(pos, "S", "C2", "C1", 30, 72)


def test_a_bevel_differential_has_the_case_midway_between_the_side_gears():
    pos = _one("bevel-differential")
    assert pos["C"] - pos["L"] == pos["R"] - pos["C"] != 0


def test_the_positions_are_whole_numbers_without_a_common_factor():
    for name in READY:
        for lever in levers(load_train(name)):
            values = list(lever.positions.values())
            assert all(isinstance(x, int) for x in values)
            assert sp.igcd(*values) == 1 if len(values) > 1 else True
            assert values == sorted(values)


@pytest.mark.parametrize("name", READY)
def test_every_state_s_speeds_lie_on_a_straight_line_over_the_lever(name):
    train = load_train(name)
    found = levers(train)
    assert found
    for state in train.states:
        speeds = dict(train.shift(state).speeds)
        speeds[FRAME] = sp.Integer(0)
        for lever in found:
            nodes = [(sp.Integer(x), speeds[n]) for n, x in lever.positions.items() if n in speeds]
            assert len(nodes) >= 2
            (x0, w0), (x1, w1) = nodes[0], nodes[-1]
            for x, w in nodes[1:-1]:  # collinear: the same slope from the first node
                assert sp.simplify((w - w0) * (x1 - x0) - (w1 - w0) * (x - x0)) == 0, (state.name, x)


def test_the_speed_line_through_the_nodes_gives_the_state_s_ratio():
    train = load_train("ravigneaux")
    (lever,) = levers(train)
    for state in train.states:
        shift = train.shift(state)
        a, b = lever.speed_line(shift.speeds)
        w_in = a + b * lever.positions[state.input]
        w_out = a + b * lever.positions[state.output]
        assert sp.cancel(w_in / w_out - shift.ratio.rhs) == 0
        assert sp.cancel(w_in - S.omega(state.input)) == 0


def test_a_lever_needs_two_speeds_for_its_line():
    assert Lever({"A": 0, "B": 1}).speed_line({"A": 1}) is None


def test_a_train_with_symbolic_teeth_has_no_lever():
    from symkin.trains import read_train

    assert levers(read_train(SYMBOLIC_SIMPLE)) == []
