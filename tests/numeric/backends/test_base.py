"""What the float backends accept as inputs, what they refuse, and what they say when an
input is not finite; the small-array path and the float tooth-number path give the same
numbers as the general one, without its copies."""

from __future__ import annotations

import tracemalloc
import warnings
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin.numeric import NonFiniteInputWarning
from symkin.numeric.backends import numba_available
from symkin.numeric.backends import numpy as numpy_backend

FLOAT_BACKENDS = ["numpy"] + (["numba"] if numba_available() else [])
RADII = schemes.two_row("AA").ratio("H", "1", fixed="4")  # r1 r3/(r1 r3 - r2 r4)
TEETH = schemes.two_row("AA", teeth=True).ratio("1", "H", fixed="4")  # 1 - z2 z4/(z1 z3)


def one_sentence(err: Exception) -> bool:
    text = str(err)
    return "\n" not in text and text.count(". ") == 0 and len(text) < 300


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
@pytest.mark.parametrize(
    "bad, words",
    [
        (1 + 5j, "complex"),
        (np.array([1.0, 2 + 0j]), "complex"),
        (None, "None"),
        (np.array([1.0, None], dtype=object), "None"),
        ([1.0, None], "None"),
        (True, "boolean"),
        (np.array([1.0, True], dtype=object), "True"),
        ("abc", "text"),
        (sp.I, "I"),
        ([[1.0, 2.0], [3.0]], "rectangular"),
    ],
)
def test_real_inputs_refuse_complex_none_bool_and_text(backend, bad, words):
    f = symkin.compile(RADII, backend=backend)
    with pytest.raises(symkin.InputError, match="r_1") as info:
        f(bad, 0.1, 0.3, 2.1)
    assert words in str(info.value) and one_sentence(info.value)


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_real_inputs_take_exact_numbers_of_every_kind(backend):
    f = symkin.compile(RADII, backend=backend)
    expected = f(0.75, 0.5, 2.0, 1.0)
    assert expected == 1.5
    for r1 in (Fraction(3, 4), sp.Rational(3, 4), np.float32(0.75), np.array([0.75], dtype=object)):
        assert f(r1, 0.5, 2.0, 1.0) == expected
    assert f(3, 1, 1, 1) == 1.5  # Python and NumPy integers are real numbers


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
@pytest.mark.parametrize(
    "bad, words",
    [(100.5, "100.5"), (np.array([100.0, np.nan]), "nan"), (np.array([np.inf]), "inf"), (1 + 0j, "complex"),
     (None, "None"), (True, "boolean"), (np.array([100, True], dtype=object), "True"), (Fraction(201, 2), "201"),
     (np.array([100.0, 2.0**70]), "2^63"), ("100", "text")],
)
def test_tooth_numbers_refuse_what_is_not_a_whole_number(backend, bad, words):
    f = symkin.compile(TEETH, backend=backend)
    with pytest.raises(symkin.InputError, match="z_1 is a tooth number") as info:
        f(bad, 99, 100, 101)
    assert words in str(info.value) and one_sentence(info.value)


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_tooth_numbers_as_floats_ints_and_python_integers_agree(backend):
    rng = np.random.default_rng(1)
    z = [rng.integers(20, 200, 40_000) for _ in range(4)]
    f = symkin.compile(TEETH, backend=backend, chunk=4096)
    ints = f(*z)
    assert np.array_equal(f(*(v.astype(np.float64) for v in z)), ints)
    assert np.array_equal(f(*(v.astype(np.float32) for v in z)), ints)
    assert np.array_equal(f(z[0].astype(np.uint16), z[1].astype(object), z[2].astype(np.float64), z[3]), ints)
    assert np.array_equal(f(float(z[0][0]), z[1], z[2], z[3]), f(int(z[0][0]), z[1], z[2], z[3]))
    big = 3 * 10**9
    exact = Fraction(big * big - (big - 1) * (big + 1), big * big)
    assert f(float(big), float(big - 1), float(big), float(big + 1)) == float(exact)
    huge = np.array([10**20, 10**20], dtype=object)  # beyond int64: Python integers
    assert f(huge, huge - 1, huge, huge + 1)[0] == float(Fraction(1, 10**40))
    assert f(np.uint64(2**63 + 1), 1, 1, 1) == 1 - 1 / (2**63 + 1)


def test_float_tooth_arrays_are_checked_and_cast_chunk_by_chunk():
    # before: each float array was checked and cast whole (several full-size temporaries)
    z = [np.full(10**6, 100.0), np.full(10**6, 99.0), np.full(10**6, 100.0), np.arange(10**6) + 50.0]
    f = symkin.compile(TEETH)
    f(*(v[:10] for v in z))
    tracemalloc.start()
    try:
        out = f(*z)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # the output and a few chunks of 2^17 points (1 MiB each); the four arrays cast whole would take 32 MB more
    assert peak < out.nbytes + 12 * 2**20
    assert out[0] == 1 - 99 * 50 / 100**2


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_a_nan_output_from_a_nan_input_is_never_silent(backend):
    f = symkin.compile(RADII, backend=backend)
    for r1 in (np.nan, np.inf, np.array([0.7, np.nan, 0.75])):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            out = f(r1, 0.5, 2.0, 1.0)
        assert not np.all(np.isfinite(out))
        kinds = [w.category for w in caught]
        assert kinds == [NonFiniteInputWarning], kinds
        assert "where an input is nan or infinite" in str(caught[0].message)
    # a pole and a nan input in one call: each is named
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = f(np.array([0.5, np.nan, 0.7]), 1.0, 2.0, 1.0)
    assert np.isinf(out[0]) and np.isnan(out[1]) and np.isfinite(out[2])
    assert sorted(w.category.__name__ for w in caught) == ["NonFiniteInputWarning", "PoleWarning"]
    assert issubclass(NonFiniteInputWarning, symkin.SymkinWarning)


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_finite_inputs_at_finite_points_warn_nothing(backend):
    f = symkin.compile(RADII, backend=backend)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f(np.linspace(1, 2, 1000), 0.5, 1.0, 0.5)


def test_small_calls_skip_the_chunk_machinery_and_give_the_same_numbers(monkeypatch):
    rng = np.random.default_rng(2)
    r = [rng.uniform(1, 2, 1000), rng.uniform(0.2, 0.5, 1000), rng.uniform(1, 2, (1, 1000)), 0.3]
    general = symkin.compile(RADII, chunk=7)(*r)  # chunks of 7 points
    f = symkin.compile(RADII)

    def refuse(*a, **k):
        raise AssertionError("a small call went through the chunked path")

    monkeypatch.setattr(numpy_backend, "allocate", refuse)
    small = f(*r)
    assert small.shape == (1, 1000) and np.array_equal(small, general)
    assert f(0.75, 0.5, 2.0, 1.0) == 1.5 and np.ndim(f(0.75, 0.5, 2.0, 1.0)) == 0
    with pytest.warns(symkin.PoleWarning, match="1 of 3 points"):
        out = f(np.array([0.5, 0.6, 0.7]), 1.0, 2.0, 1.0)
    assert np.isinf(out[0]) and np.all(np.isfinite(out[1:]))
    x, y = sp.symbols("x y", real=True)
    both = symkin.compile([x, sp.Integer(2) + 0 * y, y], [x, y])
    a = np.arange(3.0)
    ox, oc, oy = both(a, np.ones(3))
    assert np.array_equal(ox, a) and not np.shares_memory(ox, a)  # a copy, not the input itself
    assert np.array_equal(oc, [2.0, 2.0, 2.0]) and oy.dtype == np.float64


@pytest.mark.parametrize("backend", [*FLOAT_BACKENDS, "mpmath"])
def test_equal_laws_come_back_as_separate_arrays(backend):
    # [x y, x y] is one array in the generated code: before, both outputs were that array, and
    # writing into one changed the other
    x, y = sp.symbols("x y")
    xs = np.arange(3.0)
    first, second, third = symkin.compile([x * y, x * y, x], backend=backend)(xs, 2.0)
    first[0] = 99.0
    assert list(second) == [0.0, 2.0, 4.0] and not np.shares_memory(first, second)
    assert not np.shares_memory(third, xs)  # nor is an output the caller's input


@pytest.mark.skipif(not numba_available(), reason="numba not installed")
def test_numba_keeps_a_scalar_s_block_only_for_the_same_number_and_sign():
    """A scalar argument reaches the numba kernel as a block of copies of it, kept for the next
    call with the same value: -0.0 after 0.0 (equal, another sign) and nan after nan (equal to
    nothing) must not reuse it."""
    x, y = sp.symbols("x y", real=True)
    f = symkin.compile(sp.atan2(y, x), [x, y], backend="numba")
    g = symkin.compile(1 / x + y, [x, y], backend="numba")
    ys = np.array([0.0, 1.0])
    assert f(0.0, ys)[0] == 0.0 and f(-0.0, ys)[0] == np.pi and f(0.0, ys)[0] == 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert np.all(g(0.0, ys) == np.inf) and np.all(g(-0.0, ys) == -np.inf)
        assert np.all(np.isnan(g(np.nan, ys))) and np.all(np.isnan(g(np.nan, ys)))
        assert np.array_equal(g(2.0, ys), [0.5, 1.5]) and np.array_equal(g(np.float64(4.0), ys), [0.25, 1.25])
