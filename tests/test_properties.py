"""Properties of the engine over random valid mechanisms (hypothesis)."""

import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symkin import SingularConfigurationError, schemes
from symkin import symbols as S

KINDS = ["AI1", "AI", "AA", "II"]


def coaxial_teeth(kind, a, b, c):
    """A coaxial tooth set of the scheme, or None when these numbers cannot make one."""
    if kind == "AI1":
        return (a, b, a + 2 * b)
    if kind == "AI":
        return (a, b, c, a + b + c)
    if kind == "AA":
        return (a, b, c, a + b - c) if a + b - c > 0 else None
    return (a, b, c, a - b + c) if a > b else None


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(KINDS), st.integers(12, 400), st.integers(12, 400), st.integers(12, 400),
       st.integers(1, 10**6), st.fractions(-100, 100), st.fractions(-100, 100))
def test_laws_are_invariant_when_all_radii_are_scaled(kind, a, b, c, scale, w1, w4):
    teeth = coaxial_teeth(kind, a, b, c)
    if teeth is None:
        return
    m1 = schemes.scheme(kind, radii=teeth)
    m2 = schemes.scheme(kind, radii=tuple(sp.Integer(scale) * z / 7 for z in teeth))
    known = {"1": sp.Rational(w1.numerator, w1.denominator), "4": sp.Rational(w4.numerator, w4.denominator)}
    try:
        s1 = m1.speeds(known)
    except SingularConfigurationError:
        return
    s2 = m2.speeds(known)
    assert dict(s1) == dict(s2)
    assert m1.ratio("1", "H", fixed="4").rhs == m2.ratio("1", "H", fixed="4").rhs


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(KINDS), st.integers(12, 400), st.integers(12, 400), st.integers(12, 400))
def test_speeds_are_linear_in_the_known_speeds(kind, a, b, c):
    teeth = coaxial_teeth(kind, a, b, c)
    if teeth is None:
        return
    m = schemes.scheme(kind, teeth=teeth)
    try:
        one = m.speeds({"1": 1, "4": 0})
    except SingularConfigurationError:
        return
    other = m.speeds({"1": 0, "4": 1})
    both = m.speeds({"1": 3, "4": -2})
    for link in both:
        assert both[link] == 3 * one[link] - 2 * other[link]


def test_symbolic_laws_have_no_module():
    law = schemes.two_row("II", teeth=True).ratio("H", "1", fixed="4").rhs
    assert S.module() not in law.free_symbols
