"""The numba backend's common small call of arrays (issue 34, item 4): one generated function
straight to the serial kernel once it has run, every other call by the general path.  Results
against exact rational arithmetic on the same inputs (Willis's formula in Fractions); what the
general path does (refusals, pole reports, other types) must not change."""

from __future__ import annotations

import itertools
import types
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import PoleWarning, schemes
from symkin.numeric.backends import numba as numba_backend
from symkin.numeric.backends import numba_available
from symkin.numeric.backends.numba import COMPILE_PAYBACK, compile_estimate
from tests.support.willis import exact, law

pytestmark = pytest.mark.skipif(not numba_available(), reason="needs numba")


def test_small_calls_of_arrays_take_the_entry_and_equal_exact_arithmetic():
    f = symkin.compile(law(), backend="numba")
    z = np.arange(20, 120)
    values = (z, z - 1, z + 2, z + 3)
    assert f._evaluator.array_entry is None
    assert f(*values).tolist() == exact(*values)  # the first call runs the kernel: the entry is built then
    assert f._evaluator.array_entry is not None
    got = f(*values)
    assert type(got) is np.ndarray and got.shape == (100,) and got.tolist() == exact(*values)
    assert got is not f(*values)  # a fresh array each call
    # what the entry does not take goes the general path, with the same results
    assert f(z[::2], (z - 1)[::2], (z + 2)[::2], (z + 3)[::2]).tolist() == exact(z[::2], (z - 1)[::2], (z + 2)[::2], (z + 3)[::2])
    assert f(*(v.astype(np.float64) for v in values)).tolist() == exact(*values)
    assert f(z, 19, 22, z + 3).tolist() == exact(z, [19] * 100, [22] * 100, z + 3)
    assert f(z.reshape(10, 10), (z - 1).reshape(10, 10), 22, 23).shape == (10, 10)
    with pytest.raises(symkin.InputError):
        f(z, z[:50], z, z)
    with pytest.raises(symkin.InputError):
        f(z, z - 1, z + 0.5, z)


def test_a_pole_in_a_small_call_is_reported_as_by_the_general_path():
    f = symkin.compile(schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4"), backend="numba")  # z1 z3/(z1 z3 - z2 z4)
    z = np.array([20, 30, 40])
    f(z, z, z, z + 1)
    assert f._evaluator.array_entry is not None
    z2, z4 = np.array([20, 20, 40]), np.array([21, 45, 41])  # z1 z3 = z2 z4 = 900 at the second point
    with pytest.warns(PoleWarning, match="at 1 of 3 points"):
        got = f(z, z2, z, z4)
    assert np.isinf(got[1])
    assert got[[0, 2]].tolist() == [float(Fraction(a * c, a * c - b * d)) for a, b, c, d in [(20, 20, 20, 21), (40, 40, 40, 41)]]


def test_several_outputs_come_back_as_a_tuple_of_fresh_arrays():
    x, y = sp.symbols("x y", real=True)
    f = symkin.compile([x * y, x + y], [x, y], backend="numba")
    a, b = np.linspace(0.5, 2.0, 50), np.linspace(-1.0, 3.0, 50)
    f(a, b)
    assert f._evaluator.array_entry is not None
    p, s = f(a, b)
    assert p.tolist() == [float(Fraction(u) * Fraction(v)) for u, v in zip(a, b)]  # one rounding of an exact value
    assert s.tolist() == [float(Fraction(u) + Fraction(v)) for u, v in zip(a, b)]
    assert p is not s


def test_after_the_switch_the_default_runs_small_calls_without_deciding_again(monkeypatch):
    monkeypatch.delenv("SYMKIN_BACKEND", raising=False)
    clock = itertools.count()
    monkeypatch.setattr(numba_backend, "time", types.SimpleNamespace(process_time=lambda: next(clock) * 1e-3))
    f = symkin.compile(law())
    z = np.arange(20, 420)
    values = (z, z - 1, z, z + 3)
    f(*values)
    ev = f._evaluator
    ev.numpy_seconds[False] = COMPILE_PAYBACK * compile_estimate(ev._operations, False)  # as if it had done that much
    assert f(*values).tolist() == exact(*values)  # compiles the serial kernel
    assert ev.kernels and ev.array_entry is not None

    def deciding(*_args):
        raise AssertionError("a small call after the switch decided again")

    monkeypatch.setattr(ev, "_numpy_until_it_pays", deciding)
    assert f(*values).tolist() == exact(*values)  # the entry


def test_a_discarded_kernel_takes_its_entry_with_it():
    # a damaged cache entry of the serial kernel is discarded (compiled again); the entry that
    # called it goes too and is made again from the new kernel once that has run
    f = symkin.compile(law(), backend="numba")
    z = np.arange(20, 60)
    values = (z, z - 1, z + 2, z + 3)
    f(*values)
    backend = f._evaluator
    old = backend.array_entry
    assert old is not None
    backend._from_disk.add(backend._serial_key)  # as if the kernel had come from the disk cache
    with pytest.warns(symkin.SymkinWarning, match="damaged entry"):
        assert backend._discard(backend._serial_key, EOFError("truncated"))
    assert backend.array_entry is None
    assert f(*values).tolist() == exact(*values)  # the general path compiles the kernel again
    assert backend.array_entry is not None and backend.array_entry is not old
    assert f(*values).tolist() == exact(*values)
