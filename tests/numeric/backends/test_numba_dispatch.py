"""The default backend's dispatch (jit="auto"): the NumPy code first, the numba kernel once the
time spent in NumPy pays for compiling it.  The decision is checked on given numbers (not on
timings); the results against exact rational arithmetic on the same inputs."""

from __future__ import annotations

import itertools
import sys
import types

import numpy as np
import pytest

import symkin
from symkin.numeric.backends import numba as numba_backend
from symkin.numeric.backends import numba_available
from symkin.numeric.backends.numba import COMPILE_PAYBACK, compile_estimate, compile_pays
from tests.support.willis import exact, law

pytestmark = pytest.mark.skipif(not numba_available(), reason="needs numba")


def test_the_kernel_is_compiled_once_numpy_time_is_five_times_its_compile_estimate():
    for ops in (1, 6, 44, 274):
        for parallel in (False, True):
            cost = compile_estimate(ops, parallel)
            assert not compile_pays(0.0, ops, parallel)
            assert not compile_pays(COMPILE_PAYBACK * cost * 0.999, ops, parallel)
            assert compile_pays(COMPILE_PAYBACK * cost, ops, parallel)
    assert COMPILE_PAYBACK == 5.0  # at most a fifth more than NumPy alone, whatever follows
    assert compile_estimate(6, True) > compile_estimate(6, False) > compile_estimate(1, False)


def test_the_unnamed_default_starts_with_numpy_and_compiles_when_the_time_pays(monkeypatch):
    monkeypatch.delenv("SYMKIN_BACKEND", raising=False)
    # the NumPy time is read from a clock that advances 1 ms a reading: the kernel's CPU clock may count in ticks of
    # a few ms, so a short call can measure 0 (the test failed so, now and then)
    clock = itertools.count()
    monkeypatch.setattr(numba_backend, "time", types.SimpleNamespace(process_time=lambda: next(clock) * 1e-3))
    f = symkin.compile(law())
    assert f.backend == "numba" and f._plan.jit == "auto"
    z = np.arange(20, 420)
    values = (z, z - 1, z, z + 3)
    assert list(f(*values)) == exact(*values)
    ev = f._evaluator
    assert not ev.kernels and ev.numpy_seconds[False] == pytest.approx(1e-3)  # NumPy did the work, timed
    ev.numpy_seconds[False] = COMPILE_PAYBACK * compile_estimate(ev._operations, False)  # as if it had done that much
    assert list(f(*values)) == exact(*values)
    assert ev.kernels and "_kernel" in f.source and "numba" in sys.modules
    assert not ev.numpy_seconds[True]  # large calls would pay for the parallel kernel on their own


def test_a_named_backend_compiles_at_once(monkeypatch):
    monkeypatch.delenv("SYMKIN_BACKEND", raising=False)
    assert symkin.compile(law(), backend="numba")._plan.jit == "eager"
    monkeypatch.setenv("SYMKIN_BACKEND", "numba")
    assert symkin.compile(law())._plan.jit == "eager"
    with pytest.raises(symkin.InputError, match="^jit must be 'auto' or 'eager', got 'soon'$"):
        symkin.compile(law(), jit="soon")
