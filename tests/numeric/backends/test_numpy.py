"""The fast paths of the default NumPy float64 code keep the guarantees they shortcut.

- The cancellation test of ``a b - c d`` is one ratio ``g = a b/(a b - c d)`` and its minimum and
  maximum over the call: points near the pole in an array of points far from it are still redone
  in double-double (against mpmath at 50 digits), including the points just outside the certified
  interval; the II differential divides once (``ProductQuotient``).
- Tooth arrays are bounded by one bitwise-or reduction each: negative values, values whose bound
  is too coarse, values beyond int64's safe range and -2^63 still take the exact paths.
- Long phases with numbers as coefficient inputs are reduced for every point of the call,
  branch-free: short and long phases of one array, negative times, against mpmath.
"""

from __future__ import annotations

import warnings
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin import symbols as S
from symkin.numeric import runtime
from tests.numeric.backends.test_numpy_scalar import _exact_difference  # a b - c d at 60 digits

U64 = 2.0**-53
W1, W4 = S.omega("1"), S.omega("4")
R = [S.radius(i) for i in "1234"]


def test_near_points_among_far_ones_are_redone_and_the_margin_too():
    rng = np.random.default_rng(5)
    n = 4000
    a, b, c = rng.uniform(0.5, 2, n), rng.uniform(0.5, 2, n), rng.uniform(0.5, 2, n)
    rho = rng.uniform(0.01, 0.2, n)  # c d / a b: far from cancellation almost everywhere
    rho[::400] = 1 + rng.integers(-40, 41, 10) * U64  # within 40 ulps of the pole
    rho[1::400] = 1 / 3 * (1 + rng.uniform(-2e-3, 2e-3, 10))  # on the edge of the certified interval
    rho[2::400] = 3 * (1 + rng.uniform(-2e-3, 2e-3, 10))
    d = a * b * rho / c
    got = runtime.product_difference(a, b, c, d)
    ref = np.array([_exact_difference(*x) for x in zip(a, b, c, d)])
    ok = ref != 0
    assert np.all(got[~ok] == 0)
    assert np.max(np.abs(got[ok] - ref[ok]) / np.abs(ref[ok])) <= 3 * U64
    scalar = np.array([runtime.product_difference_scalar(*map(float, x)) for x in zip(a, b, c, d)])
    assert np.array_equal(scalar, got)  # the scalar path decides the same way


def test_the_differential_stays_exact_near_its_pole():
    law = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    args = [W1, W4, *R]
    f = symkin.compile(law, args)
    # the numerator summed in double-double, over the certified difference
    assert "_symkin_sum_" in f.source and "_symkin_product_difference(r_1, r_3, r_2, r_4)" in f.source
    scalar = [f(*map(float, x)) for x in zip([1.5] * 5, [-0.5] * 5, [1.0] * 5, [2.0] * 5, [3.0] * 5, np.linspace(1, 2, 5))]
    assert np.array_equal(f(1.5, -0.5, 1.0, 2.0, 3.0, np.linspace(1, 2, 5)), scalar)  # scalar and array agree
    rng = np.random.default_rng(9)
    n = 3000
    r1, r2, r3 = rng.uniform(0.1, 3, n), rng.uniform(0.1, 3, n), rng.uniform(0.1, 3, n)
    r4 = rng.uniform(0.1, 3, n)
    near = np.arange(n) % 100 == 0  # 1 point in 100 within 60 ulps of the pole r1 r3 = r2 r4
    r4[near] = (r1 * r3 / r2 * (1 + rng.integers(-60, 61, n) * U64))[near]
    w1, w4 = rng.uniform(1, 2, n), rng.uniform(-1, 0, n)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        got = f(w1, w4, r1, r2, r3, r4)
    ref = symkin.compile(law, args, backend="mpmath", digits=50)(w1, w4, r1, r2, r3, r4)
    ref = np.array([float(x) for x in ref])
    finite = np.isfinite(ref)
    assert np.all(np.isinf(got[~finite]) | np.isnan(got[~finite]))
    err = np.abs(got[finite] - ref[finite]) / np.abs(ref[finite])
    assert np.max(err[near[finite]]) <= 8 * U64  # near the pole: the relative accuracy of the far points
    assert np.max(err) <= 12 * U64  # at the zeros of the numerator too (the plain numerator lost digits there: 1e-13)


def test_tooth_arrays_take_the_exact_paths_the_bound_calls_for():
    aa = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4")
    f = symkin.compile(aa)

    def exact(z1, z2, z3, z4):
        return [float(Fraction(int(a) * int(c), int(a) * int(c) - int(b) * int(d))) for a, b, c, d in zip(z1, z2, z3, z4)]

    # all >= 0 and small: the bitwise-or bound holds
    z = [np.array([20, 31, 100]), np.array([30, 17, 99]), np.array([20, 40, 100]), np.array([70, 72, 101])]
    assert list(f(*z)) == exact(*z)
    # negative tooth numbers (internal gears written negative): the |z| bound
    zn = [-v for v in z[:1]] + z[1:]
    assert list(f(*zn)) == exact(*zn)
    # or-bound too coarse (2^31 - 1) but the maximum 2^30 safe: int64, and the same values
    big = [np.array([2**30, 2**30 - 1]), np.array([2**30 - 3, 5]), np.array([2**30, 7]), np.array([2**30 - 2, 11])]
    assert list(f(*big)) == pytest.approx(exact(*big), rel=2 * U64)
    # beyond int64's safe range: Python integers, exact
    huge = [np.array([2**40, 3]), np.array([2**40 - 1, 2]), np.array([2**40, 5]), np.array([2**40 + 1, 7])]
    assert list(f(*huge)) == exact(*huge)
    # -2^63 among small values: |z| is taken without int64's abs (which leaves -2^63 negative
    # and let the maximum be 2, so the products wrapped: -1.0 instead of 1.0)
    edge = [np.array([-2**63, 2]), np.array([3, 3]), np.array([5, 5]), np.array([7, 7])]
    assert list(f(*edge)) == exact(*edge)
    # a pole of whole numbers is still a pole
    with pytest.warns(symkin.PoleWarning):
        assert np.isinf(f(np.array([10, 20]), np.array([10, 30]), np.array([10, 20]), np.array([10, 1]))[0])
    # float tooth arrays that are not whole are still refused
    with pytest.raises(symkin.InputError):
        f(np.array([20.5, 30.0]), z[1][:2], z[2][:2], z[3][:2])


def test_long_and_short_phases_of_one_array_are_reduced_branch_free():
    w, t = sp.Symbol("w", positive=True), sp.Symbol("t", real=True)
    r1, r2 = sp.symbols("r1 r2", positive=True)
    law = sp.cos(w * r1 * t / (r1 + r2)) + sp.sin(w * r2 * t / (r1 + r2))
    f = symkin.compile(law, [w, r1, r2, t])
    ref = symkin.compile(law, [w, r1, r2, t], backend="mpmath", digits=50)
    rng = np.random.default_rng(3)
    ts = np.concatenate([rng.uniform(-5, 5, 50), rng.uniform(-1e6, 1e6, 50), [0.0, -0.0, 1e7, -1e7]])
    got = f(0.7, 0.3, 0.1, ts)
    want = np.array([float(x) for x in ref(0.7, 0.3, 0.1, ts)])
    assert np.max(np.abs(got - want)) <= 1e-15
    # non-finite times stay non-finite (and are reported as such)
    with pytest.warns(symkin.NonFiniteInputWarning):
        out = f(0.7, 0.3, 0.1, np.array([1.0, 20.0, np.inf, np.nan]))
    assert np.all(np.isfinite(out[:2])) and np.all(np.isnan(out[2:]))


def test_quotients_by_a_product_difference_compile_and_take_empty_arrays():
    # a law x/(a b - c d) whose numerator lacks a or b (i_H4 of the AA and II trains with gear 1 fixed), and calls
    # with no points at all
    w = sp.Symbol("w", positive=True)
    f = symkin.compile(w / (R[0] * R[2] - R[1] * R[3]), [w, *R])
    assert f(2.0, 1.0, 2.0, 3.0, 1.0) == 2.0
    for kind in ("AA", "II"):
        law = schemes.two_row(kind).ratio("H", "4", fixed="1").rhs
        g = symkin.compile(law)
        values = dict(zip(sorted(law.free_symbols, key=str), (1, 2, 3, 5)))  # r_1..r_4
        expected = float(law.subs(values))
        by_name = {str(k): v for k, v in values.items()}
        got = g(*[np.array([float(by_name[str(a)])] * 2) for a in g.args])
        assert np.allclose(got, expected, rtol=1e-15, atol=0) and np.isfinite(expected)
    law = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    h = symkin.compile(law, [W1, W4, *R])
    assert h(*[np.array([])] * 6).shape == (0,)
    assert h(*[np.zeros((0, 3))] * 6).shape == (0, 3)


def test_long_phases_of_a_whole_array_keep_their_digits_beyond_two_to_the_27_turns():
    # the branch-free reduction of a whole array against mpmath: the phase c t mod 2 pi at t up to 1e12 s
    c = 1.2345678901234567
    rng = np.random.default_rng(5)
    for top in (1e9, 1e12):
        t = rng.uniform(top / 10, top, 200)
        got = runtime._reduce_turns_all(runtime._turns(lambda *a: (c, 0.0), ()), t.copy())
        with mpmath.workdps(60):
            ref = np.array([float(mpmath.fmod(mpmath.mpf(c) * mpmath.mpf(float(x)), 2 * mpmath.pi)) for x in t])
        err = np.abs(np.angle(np.exp(1j * (got - ref))))
        assert err.max() <= 4e-15, (top, err.max())  # was 2.6e-12 at 1e12 before the split of c


def test_a_willis_ratio_takes_the_certified_quotient_and_a_shared_difference_is_left_whole():
    """omega_4 + (omega_1 - omega_4) r1 r3/(r1 r3 - r2 r4) is evaluated as omega_4 + (omega_1 -
    omega_4) g with g = r1 r3/difference, which certifying the difference computes anyway
    (1.33 -> 1.05 x lambdify at 10^5 points, benchmarks/numpy_floor.py); one point and an
    array give the same bits, and a difference used elsewhere too is computed once, as a
    difference."""
    from symkin.numeric.codegen import ProductRatio, product_ratios
    from symkin.numeric.stable import ProductDifference

    r1, r2, r3, r4 = R
    pd = ProductDifference(r1, r3, r2, r4)
    assert product_ratios([W1 * r1 * r3 / pd]) == [W1 * ProductRatio(r1, r3, r2, r4)]
    assert product_ratios([r1**2 * r3 / pd]) == [r1 * ProductRatio(r1, r3, r2, r4)]
    assert product_ratios([W1 * r1 * r3 / pd, 1 / pd]) == [W1 * r1 * r3 / pd, 1 / pd]  # shared: left whole
    assert product_ratios([W1 * r1 / pd]) == [W1 * r1 / pd]  # no r3: nothing to take
    law = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    f = symkin.compile(law, [W1, W4, *R])
    rng = np.random.default_rng(3)
    pts = [rng.uniform(-2, 2, 300), rng.uniform(-2, 2, 300), *(rng.uniform(0.5, 3, 300) for _ in range(4))]
    pts[5][::10] = (pts[2] * pts[4] / pts[3])[::10] * (1 + rng.integers(-40, 41, 300)[::10] * U64)  # near the pole
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        array = f(*pts)
        one = np.array([f(*map(float, p)) for p in zip(*pts)])
    assert np.array_equal(array, one, equal_nan=True)
    ref = np.array([float(x) for x in symkin.compile(law, [W1, W4, *R], backend="mpmath", digits=50)(*pts)])
    scale = np.abs(ref)
    assert np.max(np.abs(array - ref) / np.maximum(scale, 1e-3 * scale.max())) <= 1e-13
