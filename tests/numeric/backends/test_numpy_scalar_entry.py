"""The common scalar call's generated function (NumpyBackend.scalar_entry, issue 34): on random
points it returns what the general scalar path returns, bit for bit, and the array path's value (numba's kernel: within a few units);
any other input falls back to the general path."""

from __future__ import annotations

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
