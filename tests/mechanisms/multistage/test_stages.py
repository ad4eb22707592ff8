"""Single-row AI stage synthesis: the enumeration against a brute force of the conditions."""

import math
from fractions import Fraction

import pytest
import sympy as sp

from symkin.errors import InputError
from symkin.mechanisms.multistage.stages import (
    check_stage,
    enumerate_stages,
    max_satellites,
    neighbours_clear,
    stage_laws,
)


def brute_force(ring, k, zmin, zmax, ha):
    """Every (sun, planet) pair within the limits, checked with the textbook conditions typed here.

    Coaxiality z3 = z1 + 2 z2, assembly (z1 + z3)/k whole, neighbours
    (z1 + z2) sin(pi/k) > z2 + 2 ha, evaluated in floats; a case within 1e-9 of the
    neighbour boundary is returned separately so the test can decide it by hand.
    """
    found, borderline = set(), set()
    for z1 in range(zmin, zmax + 1):
        for z2 in range(zmin, zmax + 1):
            if ring != z1 + 2 * z2 or not zmin <= ring <= zmax:
                continue
            if (z1 + ring) % k:
                continue
            if k > 1:
                margin = (z1 + z2) * math.sin(math.pi / k) - z2 - 2 * ha
                if abs(margin) < 1e-9:
                    borderline.add((z1, z2))
                    continue
                if margin <= 0:
                    continue
            found.add((z1, z2))
    return found, borderline


CASES = [(ring, k, zmin, ha) for ring in (24, 37, 60, 81, 100, 150, 180, 211) for k in (1, 2, 3, 4, 5, 6, 7) for zmin, ha in ((1, 1), (12, 1), (17, Fraction(4, 5)))]


@pytest.mark.parametrize("ring, k, zmin, ha", CASES)
def test_enumeration_equals_brute_force(ring, k, zmin, ha):
    expected, borderline = brute_force(ring, k, zmin, ring, float(ha))
    for z1, z2 in borderline:  # equality in the neighbour condition is not clearance
        assert not neighbours_clear(z1, z2, k, ha)
    got = enumerate_stages(ring, k, zmin=zmin, zmax=ring, ha=ha, allow_empty=True)
    assert {(s.sun, s.planet) for s in got} == expected
    for s in got:
        assert s.ratio == sp.Rational(ring + s.sun, s.sun)  # u = 1 + z3/z1, exact
        assert all(check_stage(s.sun, s.planet, ring, k, zmin=zmin, zmax=ring, ha=ha).values())
    assert list(got.ratios) == sorted(got.ratios)
    assert sum(got.rejected.values()) + len(got) == ring - 1  # every candidate sun is accounted for


def test_the_papers_case_gives_22_stages_from_9_4_to_11():
    got = enumerate_stages(180, 3, zmin=18, zmax=180)
    # by hand: z1 even (coaxiality with an even ring), a multiple of 3 (assembly), z2 = (180 - z1)/2 >= 18
    assert [s.sun for s in reversed(got.stages)] == list(range(18, 145, 6))
    assert [s.ratio for s in got] == sorted(sp.Rational(180 + z1, z1) for z1 in range(18, 145, 6))
    assert (got[0].ratio, got[-1].ratio) == (sp.Rational(9, 4), 11)
    assert got.rejected["neighbours"] == 0  # the neighbour condition does not bind for k = 3 and z >= 18
    assert got[-1].centre_distance == sp.Rational(18 + 81, 2)


def test_neighbour_condition_is_decided_exactly_at_equality():
    # k = 6: sin(pi/6) = 1/2, so (z1 + z2)/2 = z2 + 2 h_a exactly when z1 = z2 + 4 h_a
    assert not neighbours_clear(24, 20, 6) and neighbours_clear(25, 20, 6)
    assert not neighbours_clear(22, 20, 6, ha=Fraction(1, 2)) and neighbours_clear(23, 20, 6, ha=0.5)
    # k = 2: the chord is the full diameter: z1 > 2 h_a
    assert not neighbours_clear(2, 30, 2) and neighbours_clear(3, 30, 2)
    # k = 3: (z1 + z2) sqrt(3)/2 vs z2 + 2 is never equal; a close case checked with 50 digits
    z1, z2 = 15, 100
    exact = ((z1 + z2) * sp.sqrt(3) / 2 - z2 - 2).evalf(50)
    assert neighbours_clear(z1, z2, 3) == bool(exact > 0)
    assert max_satellites(18, 81) == 3 and max_satellites(144, 18) > 3


def test_the_laws_come_from_the_engine():
    laws = stage_laws()
    z1, z2, z4 = sp.symbols("z_1 z_2 z_4", positive=True, integer=True)
    assert sp.simplify(laws.ratio.rhs - (1 + z4 / z1)) == 0
    assert sp.simplify(laws.ring_from_coaxiality - (z1 + 2 * z2)) == 0
    assert sp.simplify(laws.centre_distance - (z1 + z2) / 2) == 0


BAD = [
    (dict(ring=30, satellites=3, zmin=18, zmax=180), "use a ring of at least 54 teeth"),
    (dict(ring=60, satellites=7, zmin=18, zmax=180), "7 satellites cannot fit"),
    (dict(ring=180, satellites=0, zmin=18, zmax=180), "at least 1"),
    (dict(ring=180, satellites=-3, zmin=18, zmax=180), "at least 1"),
    (dict(ring=180, satellites=3, zmin=18, zmax=180, ha=0), "must be positive"),
    (dict(ring=180, satellites=3, zmin=18, zmax=180, ha=-1), "must be positive"),
    (dict(ring=180, satellites=3, zmin=100, zmax=50), "larger than zmax"),
    (dict(ring=181, satellites=3, zmin=18, zmax=180), "outside the limits"),
    (dict(ring=180.0, satellites=3), "whole number"),
    (dict(ring=180, satellites=2.5), "whole number"),
    (dict(ring=56, satellites=3, zmin=18, zmax=56), "no coaxial sun meets the assembly condition"),
]


@pytest.mark.parametrize("kwargs, message", BAD)
def test_bad_input_is_one_clear_sentence(kwargs, message):
    with pytest.raises(InputError) as err:
        enumerate_stages(**kwargs)
    assert message in str(err.value) and "\n" not in str(err.value)
