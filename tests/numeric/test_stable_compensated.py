"""Sums of products that cancel (stable.compensated_sums): the II differential in radii on
random points, as given and with r4 substituted, within a few units in the last place of
exact rational arithmetic on the same binary inputs (Fraction), and never less accurate than
sympy.lambdify on those points."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin import symbols as S
from symkin.numeric import stable as st
from symkin.numeric.backends import numba_available

FLOAT_BACKENDS = ["numpy"] + (["numba"] if numba_available() else [])
W1, W4 = S.omega("1"), S.omega("4")
R = [S.radius(i) for i in "1234"]
U64 = 2.0**-53


def willis(w1, w4, r1, r2, r3, r4):
    """omega_H of the II train by Willis's formula, (w1 - w_H)/(w4 - w_H) = r2 r4/(r1 r3), in Fractions."""
    w1, w4, r1, r2, r3, r4 = map(Fraction, (w1, w4, r1, r2, r3, r4))
    return (w1 * r1 * r3 - w4 * r2 * r4) / (r1 * r3 - r2 * r4)


def relative_errors(got, points):
    exact = [willis(*p) for p in points]
    return np.array([float(abs(Fraction(float(g)) - e) / abs(e)) for g, e in zip(got, exact)])


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
@pytest.mark.parametrize("overlap", [False, True])
def test_the_ii_differential_on_random_points_is_within_a_few_units(backend, overlap):
    law = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    args = [W1, W4, *R]
    rng = np.random.default_rng(34)
    n = 3000
    w = [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)]
    # the benchmark radii, or radii whose products r1 r3 and r2 r4 overlap (both cancel often)
    radii = [rng.uniform(1, 2, n) for _ in range(4)] if overlap else \
        [rng.uniform(5, 10, n), rng.uniform(1, 2, n), rng.uniform(2.5, 4, n), rng.uniform(1, 2, n)]
    values = w + radii
    f = symkin.compile(law, args, backend=backend)
    assert any(isinstance(node, st.CompensatedSum) for node in sp.preorder_traversal(f.stable_exprs[0]))
    ours = relative_errors(f(*values), list(zip(*values)))
    theirs = relative_errors(sp.lambdify(args, law)(*values), list(zip(*values)))
    # the numerator within one unit (numba: double-double) or 8 (NumPy: the plain sum where it is
    # certified so), the denominator within 3, one division: the goal is 2e-15 (18 units)
    assert ours.max() <= (4 if backend == "numba" else 12) * U64
    assert ours.max() <= theirs.max() and np.mean(ours) <= np.mean(theirs)
    one = [float(v[17]) for v in values]
    assert abs(Fraction(float(f(*one))) - willis(*one)) <= 12 * U64 * abs(willis(*one))  # the scalar path too


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_a_numerator_of_products_of_sums_is_expanded_and_summed_exactly(backend):
    r1, r2, r3 = R[:3]
    law = sp.factor(schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs.subs(R[3], r1 - r2 + r3))
    args = [W1, W4, r1, r2, r3]
    rng = np.random.default_rng(35)
    n = 2000
    values = [rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(5, 10, n), rng.uniform(1, 2, n), rng.uniform(2.5, 4, n)]
    got = symkin.compile(law, args, backend=backend)(*values)
    exact = [willis(a, b, c, d, e, Fraction(c) - Fraction(d) + Fraction(e)) for a, b, c, d, e in zip(*values)]
    err = np.array([float(abs(Fraction(float(g)) - x) / abs(x)) for g, x in zip(got, exact)])
    assert err.max() <= 12 * U64


def test_float32_and_the_rule_leave_like_signed_sums_and_tooth_numbers_alone():
    r1, r2, r3, r4 = R
    assert st.compensated_sums(r1 * r3 + r2 * r4) == r1 * r3 + r2 * r4
    z = [S.teeth(i) for i in "1234"]
    ratio = (z[0] * z[2] - z[1] * z[3]) / (z[0] * z[2])
    assert st.compensated_sums(ratio) == ratio  # integers: exact integer parts instead
    law = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    f32 = symkin.compile(law, [W1, W4, *R], backend="numpy", precision="float32")
    values = [np.float32(0.7), np.float32(-0.3), np.float32(7.5), np.float32(1.5), np.float32(3.0), np.float32(1.25)]
    exact = willis(*(float(v) for v in values))
    assert abs(float(f32(*values)) - float(exact)) <= 2.0**-23 * abs(float(exact))
