"""The scalar path of the float backends (one point in Python floats, no arrays) and the
product difference that redoes in double-double only the points whose products cancel:
both checked against the array path and against 50-digit mpmath."""

from __future__ import annotations

import warnings

import mpmath
import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin import symbols as S
from symkin.numeric import runtime
from symkin.numeric.backends import numba_available
from tests.numeric.test_numeric import CASES, SLIDER_ARGS

FLOAT_BACKENDS = ["numpy"] + (["numba"] if numba_available() else [])
U64 = 2.0**-53


def _no_arrays(f, monkeypatch):
    """Make the array path of ``f`` fail, so that a scalar call shows it did not use it."""

    def refuse(*args, **kwargs):
        raise AssertionError("the array path was used")

    monkeypatch.setattr(f._evaluator, "evaluate", refuse)


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_a_scalar_call_takes_no_arrays_and_agrees_with_the_array_path(case, backend, monkeypatch):
    laws, args, values, _ref, _floor = CASES[case]
    f = symkin.compile(laws, args, backend=backend, ranges={sp.Symbol("e", positive=True): (0, 1)})
    g = symkin.compile(laws, args, backend=backend, ranges={sp.Symbol("e", positive=True): (0, 1)})
    for k in range(5):
        point = [v[k].item() if np.ndim(v) else v for v in values]
        want = g(*[np.array([x]) for x in point])
        want = want if isinstance(want, tuple) else (want,)
        with monkeypatch.context() as m:
            _no_arrays(f, m)
            got = f(*point)
        got = got if isinstance(got, tuple) else (got,)
        assert all(type(x) is np.float64 for x in got)
        scale = max(abs(float(w[0])) for w in want)
        for x, w in zip(got, want):  # libm and NumPy's sin/cos may differ in the last bit
            assert abs(float(x) - float(w[0])) <= 8 * U64 * scale


def test_a_scalar_call_at_a_pole_warns_or_raises_as_an_array_call_does():
    aa = schemes.two_row("AA").ratio("H", "1", fixed="4")  # r1 r3/(r1 r3 - r2 r4)
    with pytest.warns(symkin.PoleWarning, match="1 of 1 points"):
        assert np.isinf(symkin.compile(aa)(1.0, 2.0, 4.0, 2.0))
    with pytest.raises(symkin.PoleError):
        symkin.compile(aa, on_pole="raise")(1.0, 2.0, 4.0, 2.0)
    teeth = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4")
    with pytest.warns(symkin.PoleWarning):
        assert np.isinf(symkin.compile(teeth)(10, 20, 40, 20))
    with pytest.raises(symkin.InputError, match="whole numbers"):
        symkin.compile(teeth)(10.5, 20, 40, 21)
    with pytest.raises(symkin.InputError):
        symkin.compile(teeth)(True, 20, 40, 21)


def test_a_scalar_tooth_ratio_is_exact_for_python_integers(monkeypatch):
    teeth = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4")
    f = symkin.compile(teeth)
    _no_arrays(f, monkeypatch)
    z = (10**8, 10**8 - 1, 10**8, 10**8 + 1)  # z1 z3 - z2 z4 = 1
    assert f(*z) == 1e16
    assert f(*(float(x) for x in z)) == 1e16


def test_scalar_inputs_of_other_types_take_the_array_path_with_its_checks():
    f = symkin.compile(schemes.two_row("AI").ratio("1", "H", fixed="4"))
    assert f(np.float32(1), 2, 1, 4) == 9.0
    with pytest.raises(symkin.InputError):
        f(1 + 2j, 2, 1, 4)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert np.isnan(f(float("nan"), 2, 1, 4))
    assert [w.category for w in caught] == [symkin.NonFiniteInputWarning]


def _exact_difference(a, b, c, d):
    with mpmath.workdps(60):
        return float(mpmath.mpf(a) * mpmath.mpf(b) - mpmath.mpf(c) * mpmath.mpf(d))


def test_the_product_difference_is_within_3_units_whether_or_not_its_products_cancel():
    rng = np.random.default_rng(41)
    n = 3000
    a, b, c = rng.uniform(0.1, 3, n), rng.uniform(0.1, 3, n), rng.uniform(0.1, 3, n)
    # d from far away (no cancellation) to within a few ulps of a b / c (all digits cancel)
    closeness = 10.0 ** rng.uniform(-16, 0.5, n) * rng.choice([-1, 1], n)
    d = a * b / c * (1 + closeness)
    got = runtime.product_difference(a, b, c, d)
    ref = np.array([_exact_difference(*x) for x in zip(a, b, c, d)])
    ok = ref != 0
    assert np.all(got[~ok] == 0)
    assert np.max(np.abs(got[ok] - ref[ok]) / np.abs(ref[ok])) <= 3 * U64
    near = np.abs(closeness) < 0.3
    assert near.sum() > 1000 and (~near).sum() > 100  # both branches are exercised
    scalar = np.array([runtime.product_difference_scalar(*map(float, x)) for x in zip(a, b, c, d)])
    assert np.array_equal(scalar, got)


def test_the_product_difference_of_broadcast_and_zero_d_inputs():
    a = np.array([[0.7], [1.5]])
    got = runtime.product_difference(a, np.array([0.3, 0.6]), 0.1, 2.1)
    want = np.array([[_exact_difference(x, y, 0.1, 2.1) for y in (0.3, 0.6)] for x in (0.7, 1.5)])
    assert np.array_equal(got, want)
    assert float(runtime.product_difference(0.7, 0.3, 0.1, 2.1)) == _exact_difference(0.7, 0.3, 0.1, 2.1)


def test_the_slider_scalar_path_reduces_the_phase_like_the_array_path(monkeypatch):
    laws = CASES["slider"][0]
    f = symkin.compile(laws, SLIDER_ARGS, reduce_phase=[S.t])
    point = [0.5, 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, 1e6]
    want = f(*[np.array([x]) for x in point])
    _no_arrays(f, monkeypatch)
    got = f(*point)
    scale = max(abs(float(w[0])) for w in want)
    assert all(abs(float(x) - float(w[0])) <= 8 * U64 * scale for x, w in zip(got, want))


_CACHED = """
import numpy as np, symkin
from symkin import schemes
f = symkin.compile(schemes.two_row("AA").ratio("H", "1", fixed="4"), backend="numba")
x = np.linspace(1, 2, 1000)
values = [f(x, 0.3, 2.0, 0.5), f(x, x, 2.0, 0.5), f(1.5, x, x, 0.5), f(1.5, 0.3, x, 0.5)]  # four mixes of scalars and arrays
kernels = [k for k, _redo in f._evaluator.kernels.values()]
print(len(kernels), sum(sum(k.stats.cache_hits.values()) for k in kernels), sum(sum(k.stats.cache_misses.values()) for k in kernels))
print(float(values[0][0]), float(values[3][-1]))
"""


@pytest.mark.skipif(not numba_available(), reason="numba is an optional extra")
def test_numba_compiles_one_kernel_per_law_and_the_next_process_loads_it_from_disk(tmp_path):
    import os
    import subprocess
    import sys

    env = {**os.environ, "SYMKIN_CACHE_DIR": str(tmp_path)}
    runs = [subprocess.run([sys.executable, "-c", _CACHED], env=env, capture_output=True, text=True, check=True).stdout.split("\n")
            for _ in range(2)]
    assert runs[0][0] == "1 0 1"  # one kernel for the four mixes, compiled once
    assert runs[1][0] == "1 1 0"  # the second process loads it
    assert runs[0][1] == runs[1][1] == f"{1 * 2.0 / (2.0 - 0.3 * 0.5)!r} {1.5 * 2.0 / (1.5 * 2.0 - 0.3 * 0.5)!r}"
    assert list(tmp_path.glob("symkin_kernel_*.py")) and list(tmp_path.glob("__pycache__/*.nbi"))
