"""exact_form (the exact backend's integer form of a law rational in whole numbers) against
SymPy's substitution and cancellation on the same values, and against Fractions by hand."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from symkin.numeric.backends.exact import exact_form, exact_value

Z = sp.symbols("z1:4", positive=True, integer=True)


@settings(max_examples=150, deadline=None)
@given(st.lists(st.integers(-6, 6), min_size=6, max_size=6), st.lists(st.integers(-40, 40), min_size=3, max_size=3))
def test_random_rational_laws_equal_sympys_substitution(c, z):
    assume(any(c[2:5]))  # a denominator that is not 0 everywhere
    # numerator and denominator with rational coefficients, negative leading terms included
    law = (sp.Rational(c[0], 3) * Z[0] * Z[1] + c[1] * Z[2] + sp.Rational(1, 7)) / (c[2] * Z[0] - sp.Rational(c[3], 2) * Z[2] + c[4]) \
        + sp.Rational(c[5], 5) * Z[1]
    f = exact_form(law)
    assert f is not None
    values = dict(zip(Z, z))
    expected = sp.cancel(law.xreplace({k: sp.Integer(v) for k, v in values.items()}))
    got = f(values)
    if expected.is_Rational:
        assert got == Fraction(int(expected.p), int(expected.q))
    else:
        assert got is None  # a pole: no finite value


def test_what_exact_form_takes_and_gives():
    z1, z2 = Z[:2]
    assert exact_form(z1 / z2)({z1: np.int64(3), z2: sp.Integer(4)}) == Fraction(3, 4)
    with pytest.raises(TypeError):
        exact_form(z1 / z2)({z1: 2.9, z2: 1})  # whole numbers only: never truncated
    # two symbols of one name and other assumptions are two arguments
    plain, whole = sp.Symbol("z"), sp.Symbol("z", integer=True)
    assert exact_form(plain + 2 * whole)({plain: 1, whole: 2}) == 5
    # a common factor that vanishes is cancelled first: the value is the limit, 1 (SymPy's
    # substitution gives nan there)
    assert exact_form(z1 / (z1 - z2) - z2 / (z1 - z2))({z1: 3, z2: 3}) == 1
    assert exact_form(sp.Integer(0))({}) == 0
    assert exact_form(sp.sqrt(z1)) is None and exact_form(sp.pi * z1) is None and exact_form(z1 ** z2) is None


def test_the_exact_ratio_in_integers_is_sympys_substitution():
    # exact_value evaluates a law's numerator and denominator as integer polynomials; a second route is
    # SymPy's substitution and cancellation, a third the same law written here in Fractions
    a, b, c = sp.symbols("z_a z_b z_c", positive=True, integer=True)
    law = sp.Rational(3, 2) * a / (b - c) + sp.Rational(1, 7) * b * c / a - 1

    @settings(max_examples=200, deadline=None)
    @given(st.integers(1, 200), st.integers(1, 200), st.integers(1, 200))
    def check(x, y, z):
        values = {a: x, b: y, c: z}
        got = exact_value(law, values)
        if y == z:
            assert got is None  # a zero denominator: no finite ratio
            return
        assert got == Fraction(3, 2) * x / (y - z) + Fraction(1, 7) * y * z / x - 1
        assert sp.Rational(got.numerator, got.denominator) == sp.cancel(law.xreplace(values))

    check()
    assert exact_value(sp.Integer(1), {}) == 1  # a direct gear: no tooth number at all
    assert exact_value(sp.sqrt(a) / b, {a: 9, b: 2}) == Fraction(3, 2)  # not rational in the teeth: SymPy's route

