"""Near and at a pole: a denominator a b - c d of real inputs is evaluated in double-double
arithmetic, so the AA ratio in radii keeps its digits however close r1 r3 is to r2 r4, and
is inf (with a PoleWarning) exactly where r1 r3 = r2 r4 for the binary inputs given.
References: mpmath at 50 digits on the same binary inputs."""

from __future__ import annotations

import time
import warnings

import mpmath
import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin.numeric import stable as st
from symkin.numeric.backends import numba_available

FLOAT_BACKENDS = ["numpy"] + (["numba"] if numba_available() else [])
U64 = 2.0**-53
AA_H1 = schemes.two_row("AA").ratio("H", "1", fixed="4")  # r1 r3/(r1 r3 - r2 r4)
AA_1H = schemes.two_row("AA").ratio("1", "H", fixed="4")  # 1 - r2 r4/(r1 r3)


def exact(law, *values):
    """The law at the binary values, at 50 digits (inf at a pole)."""
    syms = sorted(law.rhs.free_symbols, key=lambda s: s.name)
    g = sp.lambdify(syms, law.rhs, modules="mpmath")
    out = []
    with mpmath.workdps(50):
        shape = np.broadcast_shapes(*(np.shape(x) for x in values)) or (1,)
        for point in zip(*(np.broadcast_to(np.asarray(v, dtype=float), shape) for v in values)):
            try:
                out.append(float(g(*(mpmath.mpf(float(x)) for x in point))))
            except ZeroDivisionError:
                out.append(np.inf)
    return np.array(out)


def near_pole_radii(n, rng, spread=60):
    """r4 within a few dozen ulps of r1 r3/r2, so that r1 r3 - r2 r4 keeps a few bits."""
    r1, r2, r3 = rng.uniform(0.1, 3, n), rng.uniform(0.1, 3, n), rng.uniform(0.1, 3, n)
    r4 = r1 * r3 / r2 * (1 + rng.integers(-spread, spread + 1, n) * U64)
    return r1, r2, r3, r4


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_the_reviewers_point_is_right_to_the_last_digits(backend):
    point = (0.7, 0.1, 0.3, 2.1)  # r1 r3 - r2 r4 is -4.16e-17 for these binary values
    (ref,) = exact(AA_H1, *point)
    f = symkin.compile(AA_H1, backend=backend)
    assert "double-double" in f.__doc__
    assert abs(f(*point) - ref) <= 3 * U64 * abs(ref)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plain = symkin.compile(AA_H1, backend=backend, stable=False)(*point)
    assert abs(plain - ref) > 0.4 * abs(ref)  # -7.57e15 for -5.04e15: what the stable form avoids


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_random_near_singular_points_keep_full_relative_accuracy(backend):
    rng = np.random.default_rng(17)
    r = near_pole_radii(2000, rng)
    ref = exact(AA_H1, *r)
    f = symkin.compile(AA_H1, backend=backend)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no pole among them
        got = f(*r)
    finite = np.isfinite(ref)
    assert finite.all()
    assert np.max(np.abs(got - ref) / np.abs(ref)) <= 3 * U64  # numerator, difference and quotient: one rounding each
    assert np.median(np.abs(ref)) > 1e14  # these points are near the pole indeed
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        plain = symkin.compile(AA_H1, backend=backend, stable=False)(*r)
    assert np.max(np.abs(plain - ref) / np.abs(ref)) > 0.1  # where not inf: a "pole" the binary inputs do not have
    assert [w.category for w in caught] == [symkin.PoleWarning]


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_exact_poles_give_inf_and_their_neighbours_stay_finite_and_right(backend):
    rng = np.random.default_rng(23)
    r1, r3 = rng.uniform(0.1, 3, 500), rng.uniform(0.1, 3, 500)
    r2, r4 = 2 * r1, r3 / 2  # r1 r3 = r2 r4 exactly
    f = symkin.compile(AA_H1, backend=backend)
    with pytest.warns(symkin.PoleWarning, match="500 of 500 points"):
        assert np.all(np.isinf(f(r1, r2, r3, r4)))
    with pytest.raises(symkin.PoleError):
        symkin.compile(AA_H1, backend=backend, on_pole="raise")(r1, r2, r3, r4)
    for direction in (np.inf, -np.inf):
        beside = np.nextafter(r4, direction)  # one ulp off the pole
        ref = exact(AA_H1, r1, r2, r3, beside)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            got = f(r1, r2, r3, beside)
        assert np.max(np.abs(got - ref) / np.abs(ref)) <= 3 * U64


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_float32_keeps_every_float32_digit_near_the_pole(backend):
    rng = np.random.default_rng(29)
    r = [x.astype(np.float32) for x in near_pole_radii(1000, rng)]
    ref = exact(AA_H1, *r)
    ok = np.isfinite(ref) & (np.abs(ref) < 1e37)  # float32 ends near 3.4e38
    got = symkin.compile(AA_H1, backend=backend, precision="float32")(*r)
    assert got.dtype == np.float32
    assert np.max(np.abs(got[ok] - ref[ok]) / np.abs(ref[ok])) <= 3 * 2.0**-24


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_one_minus_a_ratio_of_products_keeps_its_digits_near_its_zero(backend):
    rng = np.random.default_rng(31)
    r = near_pole_radii(1000, rng, spread=5)  # i_1H = 1 - r2 r4/(r1 r3) near 0
    ref = exact(AA_1H, *r)
    ok = ref != 0
    got = symkin.compile(AA_1H, backend=backend)(*r)
    assert np.max(np.abs(got[ok] - ref[ok]) / np.abs(ref[ok])) <= 3 * U64  # difference, product, quotient
    assert np.all(got[~ok] == 0)


def test_the_rule_leaves_sums_alone_that_cannot_cancel_or_round_once():
    r1, r2, r3, r4 = sp.symbols("r1:5", positive=True)
    x, y = sp.symbols("x y", real=True)
    z1, z2 = sp.symbols("z1 z2", integer=True)
    for e in (r1 * r3 + r2 * r4, x - y, 2 * x - 1, z1 * z2 - 1, r1 * r2 * r3 - x * y):
        assert st.difference_of_products(e) == e
    for e in (r1 * r3 - r2 * r4, x * y + r1 * r2, 3 * x - y, 1 - x * y / (r1 * r2), 2 * x * y - 1, (x * y - 1) / (x - r1 * r2)):
        rewritten = st.difference_of_products(e)
        assert rewritten.has(st.ProductDifference)
        assert sp.simplify(st.plain_form(rewritten) - e) == 0


def _denominator_sums(expr):
    """Sums that the float code divides by (ExactRatio and ProductDifference are exact or
    double-double, and are not looked into)."""
    for node in sp.preorder_traversal(expr):
        if node.is_Pow and node.exp.is_negative:
            for factor in sp.Mul.make_args(node.base):
                base = factor.as_base_exp()[0]
                if base.is_Add:
                    yield base


def _guaranteed(add):
    terms = [t.as_coeff_mul() for t in add.args]
    if len(terms) == 2 and all(abs(c) == 1 and len(f) <= 1 and all(x.is_Symbol for x in f) for c, f in terms):
        return True  # x - y or x + y: zero exactly when it should be, one rounding
    signs = {st._sign(t, None) for t in add.args}
    return len(signs) == 1 and None not in signs  # like-signed: cannot cancel


def test_every_two_row_ratio_and_speed_law_has_only_guaranteed_denominators():
    # what README and docs/numerics.md promise: inf at a pole, never a finite number, and
    # no digits lost near one, for every ratio and speed law of the two-row schemes
    from itertools import combinations, permutations

    from symkin import symbols as S

    checked = 0
    for kind in ("AA", "AI", "II"):
        for teeth in (False, True):
            mech = schemes.two_row(kind, teeth=teeth)
            laws = [mech.ratio(a, b, fixed=c).rhs for a, b, c in permutations(("1", "4", "H"), 3)]
            for known in combinations(("1", "4", "H"), 2):
                solved = mech.speeds({k: S.omega(k) for k in known})
                laws += [solved.law(n).rhs for n in ("1", "4", "H", "23")]
            for law in laws:
                for add in _denominator_sums(st.stable_form(law)):
                    assert _guaranteed(add), (kind, teeth, law, add)
                checked += 1
    assert checked == 3 * 2 * (6 + 3 * 4)


def test_factoring_splits_small_rational_polynomials_and_skips_huge_exact_coefficients():
    e, x = sp.symbols("e x", positive=True)
    for poly, factor in ((1 - e**2, e - 1), (x**2 - 2 * x * e + e**2, e - x)):
        split = st.factor_differences(poly)
        assert split != poly and sp.expand(split - poly) == 0
        assert any(sp.expand(f.as_base_exp()[0] - factor) == 0 or sp.expand(f.as_base_exp()[0] + factor) == 0
                   for f in sp.Mul.make_args(split))
    # a coefficient such as E**1000 (an angle typed by a user) once sent factor() into
    # Wang's algorithm for 20 s; such sums are left as they are
    huge = sp.E**1000 * e**2 - 1
    start = time.process_time()
    assert st.factor_differences(huge) == huge
    assert time.process_time() - start < 1


@pytest.mark.skipif(not numba_available(), reason="needs numba")
def test_the_numba_kernel_redoes_only_the_uncertified_points_of_a_plain_first_pass(tmp_path, monkeypatch):
    # a few near-pole points and one exact pole among far ones, over several blocks of the
    # kernel's loop, with a scalar among the arguments: the plain pass counts the uncertified
    # points, the second redoes them in double-double (mpmath at 50 digits is the reference)
    from symkin.numeric.kernel import KERNEL_BLOCK

    monkeypatch.setenv("SYMKIN_CACHE_DIR", str(tmp_path))  # kernels of this test only
    law = 2 * AA_H1.rhs  # a kernel no other test loads (kernels are shared by their source); x2 is exact
    rng = np.random.default_rng(29)
    n = 2 * KERNEL_BLOCK + 77
    r1, r3 = rng.uniform(0.5, 3, n), rng.uniform(0.5, 3, n)
    r2 = 1.25  # a scalar
    r4 = r1 * r3 / r2 * rng.uniform(0.05, 0.3, n)  # far from the pole: certified
    near = np.arange(5, n, 397)
    r4[near] = r1[near] * r3[near] / r2 * (1 + rng.integers(-40, 41, near.size) * U64)
    pole = near[-1] + 3
    r1[pole], r3[pole], r4[pole] = 2.0, 1.875, 3.0  # 2 * 1.875 = 1.25 * 3 exactly
    ref = 2 * exact(AA_H1, r1, np.full(n, r2), r3, r4)
    f = symkin.compile(law, backend="numba")
    # without near points the plain pass is the answer, and the redo pass is not compiled
    far = np.setdiff1d(np.arange(n), np.r_[near, pole])
    plain = f(r1[far], r2, r3[far], r4[far])
    assert np.max(np.abs(plain - ref[far]) / np.abs(ref[far])) <= 3 * U64
    [(kernel, redo)] = f._evaluator.kernels.values()
    assert kernel.signatures and not redo.signatures
    with pytest.warns(symkin.PoleWarning, match=f"at 1 of {n} points"):
        got = f(r1, r2, r3, r4)
    assert redo.signatures
    assert np.isinf(got[pole]) and np.isinf(ref[pole])
    ok = np.isfinite(ref)
    assert ok.sum() == n - 1
    assert np.max(np.abs(got[ok] - ref[ok]) / np.abs(ref[ok])) <= 3 * U64
    assert np.min(np.abs(ref[near[:-1]])) > 1e12  # the near points are near indeed
    assert np.array_equal(plain, got[far])  # the far points as the plain pass left them
