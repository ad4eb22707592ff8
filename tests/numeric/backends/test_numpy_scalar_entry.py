"""The common scalar call's generated function (NumpyBackend.scalar_entry, issue 34): on random
points it returns what the general scalar path returns, bit for bit, and the array path's value (numba's kernel: within a few units);
any other input falls back to the general path."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import symkin
from symkin import schemes
from symkin import symbols as S
from symkin.numeric.backends import numba_available

W1, W4 = S.omega("1"), S.omega("4")
R = [S.radius(i) for i in "1234"]


@pytest.mark.parametrize("backend", ["numpy"] + (["numba"] if numba_available() else []))
def test_scalar_calls_equal_the_general_path_and_the_arrays(backend):
    rng = np.random.default_rng(341)
    ii = symkin.compile(schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs, [W1, W4, *R], backend=backend)
    ratio = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4").rhs
    aa = symkin.compile(ratio, sorted(ratio.free_symbols, key=lambda s: s.name), backend=backend)
    both = symkin.compile([ratio, 1 / ratio], sorted(ratio.free_symbols, key=lambda s: s.name), backend=backend)
    for _ in range(200):
        w = [float(x) for x in rng.uniform(-1, 1, 2)] + [float(x) for x in rng.uniform(1, 10, 4)]
        z = [int(x) for x in rng.integers(12, 200, 4)]
        for f, point in ((ii, w), (aa, z), (both, z)):
            got = f(*point)
            general = f._evaluator.evaluate_scalar(point)
            arrays = f(*[np.array([p]) for p in point])
            got = got if isinstance(got, tuple) else (got,)
            arrays = arrays if isinstance(arrays, tuple) else (arrays,)
            assert [type(g) for g in got] == [np.float64] * len(got)
            assert [float(g) for g in got] == [float(g) for g in general]
            # (numba's kernel sums every point in double-double, the scalar code only where the plain sum is not certified)
            assert np.allclose([float(a[0]) for a in arrays], general, rtol=16 * 2.0**-53, atol=0)
            if backend == "numpy":
                assert [float(g) for g in got] == [float(a[0]) for a in arrays]
    assert ii._entry is not False and aa._entry is not False


def test_other_scalars_take_the_general_path():
    ratio = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4").rhs
    f = symkin.compile(ratio, sorted(ratio.free_symbols, key=lambda s: s.name), backend="numpy")
    assert float(f(20.0, 31, 40, np.int64(70))) == float(f(20, 31, 40, 70))  # floats and NumPy integers as tooth numbers
    with pytest.warns(symkin.errors.PoleWarning):
        assert not np.isfinite(f(20, 40, 40, 20))  # a pole: reported by the array path


@pytest.mark.parametrize("backend", ["numpy"] + (["numba"] if numba_available() else []))
def test_several_outputs_come_back_as_a_tuple_on_every_scalar_path(backend):
    # a constant output is not a float in the generated code, so the call goes the general way: its answer is still a
    # tuple of numbers, as from the fast path and from arrays (the synthesis tells one output from several by it)
    r1, r2, r3 = (S.radius(i) for i in "123")
    f = symkin.compile([r1 * r2 + 1, 3 + 0 * r1, r1 / r3], [r1, r2, r3], backend=backend)
    for point in ((2.0, 3.0, 4.0), (np.float64(2.0), np.float64(3.0), np.float64(4.0)), (2, 3, 4)):
        got = f(*point)
        assert type(got) is tuple and [float(v) for v in got] == [7.0, 3.0, 0.5]
    arrays = f(np.array([2.0]), np.array([3.0]), np.array([4.0]))
    assert type(arrays) is tuple and [a.shape for a in arrays] == [(1,)] * 3


def test_a_pole_of_a_compensated_sum_given_a_numpy_float_is_a_pole_warning_only():
    # the written-out compensated sum gives a Python float whatever the inputs: with an np.float64
    # input the division by a zero sum raised NumPy's RuntimeWarning (an error under -W error)
    # before the PoleWarning the general path gives; the exact value is 1/0, a pole
    import sympy as sp

    a, b, c, d, e, f = sp.symbols("a b c d e f")
    F = symkin.compile([1 / (a * b - c * d + e * f)], [a, b, c, d, e, f], backend="numpy", on_pole="return")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert F(np.float64(1.0), 1.0, 1.0, 1.0, 0.0, 0.0) == np.inf
        assert F(np.float64(2.0), 3.0, 1.0, 5.0, 0.5, 2.0) == 1 / (2 * 3 - 1 * 5 + 0.5 * 2)
