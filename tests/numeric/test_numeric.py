"""The numeric layer: every backend against a 50-digit reference, the stable forms at
the extremes where naive formulas lose their digits, scenes, chunks and Dask."""

from __future__ import annotations

import pickle
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin import symbols as S
from symkin.numeric import stable as st
from symkin.numeric.backends import numba_available

HAS_NUMBA = numba_available()
FLOAT_BACKENDS = ["numpy"] + (["numba"] if HAS_NUMBA else [])

# ---------------------------------------------------------------- the laws (built here)
Z = [S.teeth(i) for i in "1234"]
R = [S.radius(i) for i in "1234"]
W1, W4 = S.omega("1"), S.omega("4")
E = sp.Symbol("e", positive=True)
M = sp.Symbol("m", positive=True)
W = sp.Symbol("omega", positive=True)
L = sp.Symbol("l", positive=True)
TH2, TH0 = sp.Symbol("theta_2", real=True), sp.Symbol("theta_H0", real=True)
SLIDER_ARGS = [E, L, M, W, TH2, TH0, S.t]


def ratio_law():
    return schemes.two_row("AA", teeth=True).ratio("1", "H", fixed="4")


def differential_law():
    law = schemes.two_row("II").speeds({"1": W1, "4": W4}).law("H").rhs
    return sp.factor(law.subs(R[3], R[0] - R[1] + R[2]))


def planet_acceleration():
    return schemes.two_row("AI").motion({"1": W1, "4": 0}).particle("23", (R[0], 0)).acceleration


def slider_laws(continuous_reference=False):
    """s, V_s, a_s of the elliptical-gear-driven Cardan slider (Luo & Li 2018, section 3,
    drive law as given in the papers guide), by SymPy differentiation."""
    t = S.t
    u = M * W * t / 2
    atan_part = sp.atan((1 + E) / (1 - E) * sp.tan(u))
    if continuous_reference:  # the principal arctan corrected by its branch number
        atan_part += sp.pi * sp.floor(u / sp.pi + sp.Rational(1, 2))
    theta = TH0 + 2 / M * atan_part
    omega_h = W * (1 - E**2) / (1 - 2 * E * sp.cos(M * W * t) + E**2)
    th = sp.Function("theta_H")(t)
    s = 2 * L * sp.cos(TH2 - th)
    subs = [(sp.Derivative(th, (t, 2)), sp.diff(omega_h, t)), (sp.Derivative(th, t), omega_h), (th, theta)]
    return [x.subs(subs) for x in (s, sp.diff(s, t), sp.diff(s, t, 2))]


def rel_error(got, ref, floor=1e-3):
    """Max error relative to each reference value, floored at ``floor`` times the law's
    largest value (pointwise relative error is meaningless at the law's own zeros; a law
    of time such as cos(omega t) is judged normwise, floor=1)."""
    got = np.asarray(got, dtype=float)
    ref = np.asarray(ref, dtype=float)
    scale = np.maximum(np.abs(ref), floor * np.max(np.abs(ref)))
    return float(np.max(np.abs(got - ref) / scale))


def reference(laws, args, values, digits=50):
    out = symkin.compile(laws, args, backend="mpmath", digits=digits)(*values)
    out = out if isinstance(out, tuple) else (out,)
    return [np.array(o, dtype=float) for o in out]


rng = np.random.default_rng(20240601)
N = 60


def _cases():
    ratio = ratio_law()
    zs = [rng.integers(20, 200, N) for _ in range(4)]
    diff = differential_law()
    r1, r2 = rng.uniform(5, 10, N), rng.uniform(1, 4, N)
    dvals = [rng.uniform(-10, 10, N), rng.uniform(-10, 10, N), r1, r2, rng.uniform(0.5, 4, N)]
    acc = list(planet_acceleration())
    acc_args = sorted(set().union(*(a.free_symbols for a in acc)) - {S.t}, key=str) + [S.t]
    avals = [rng.uniform(0.5, 3, N) for _ in acc_args[:-1]] + [rng.uniform(0, 5, N)]
    slider = slider_laws()
    svals = [rng.uniform(0.05, 0.95, N), 0.02, rng.integers(1, 4, N).astype(float), 0.8 * np.pi, 0.3, 0.1, rng.uniform(0, 10, N)]
    sref = slider_laws(continuous_reference=True)
    return {
        "ratio": ([ratio], Z, zs, [ratio.rhs], 1e-3),
        "differential": ([diff], [W1, W4, R[0], R[1], R[2]], dvals, [diff], 1e-3),
        "planet acceleration": (acc, acc_args, avals, acc, 1.0),
        "slider": (slider, SLIDER_ARGS, svals, sref, 1.0),
    }


CASES = _cases()


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
@pytest.mark.parametrize("cse", [True, False])
def test_float64_backends_match_the_50_digit_reference(case, backend, cse):
    laws, args, values, ref_laws, floor = CASES[case]
    f = symkin.compile(laws, args, backend=backend, cse=cse, ranges={E: (0, 1)})
    got = f(*values)
    got = got if isinstance(got, tuple) else (got,)
    for g, r in zip(got, reference(ref_laws, args, values)):
        assert g.dtype == np.float64
        assert rel_error(g, r, floor) <= 1e-14
    other = symkin.compile(laws, args, backend=backend, cse=not cse, ranges={E: (0, 1)})(*values)
    other = other if isinstance(other, tuple) else (other,)
    for g, h in zip(got, other):  # with and without cse: equal up to the order of roundings
        assert rel_error(g, h, floor) <= 1e-14


@pytest.mark.parametrize("case", list(CASES))
def test_float32_and_mpmath_and_cse_agree_with_the_reference(case):
    laws, args, values, ref_laws, floor = CASES[case]
    ref = reference(ref_laws, args, values)
    for backend in FLOAT_BACKENDS:
        f32 = symkin.compile(laws, args, backend=backend, precision="float32", ranges={E: (0, 1)})
        got = f32(*values)
        got = got if isinstance(got, tuple) else (got,)
        for g, r in zip(got, ref):
            assert g.dtype == np.float32
            assert rel_error(g, r, floor) <= 2e-5
    few = [v[:5] if np.ndim(v) else v for v in values]
    for cse in (True, False):
        mp = symkin.compile(ref_laws, args, backend="mpmath", digits=30, cse=cse)(*few)
        mp = mp if isinstance(mp, tuple) else (mp,)
        for g, r in zip(mp, reference(ref_laws, args, few)):
            assert rel_error(np.array(g, dtype=float), r) <= 1e-15


def test_exact_backend_gives_rationals_equal_to_sympy():
    law = ratio_law()
    f = symkin.compile(law, backend="exact")
    assert f.precision == "exact"
    assert f(100, 99, 100, 101) == Fraction(1, 10000)
    zs = [rng.integers(1, 10**6, 20) for _ in range(4)]
    got = f(*zs)
    for i in range(20):
        expected = law.rhs.subs(dict(zip(Z, [int(z[i]) for z in zs])))
        assert got[i] == Fraction(int(expected.p), int(expected.q))
    diff = symkin.compile(differential_law(), [W1, W4, R[0], R[1], R[2]], backend="exact")
    assert diff(1, 1, 3, Fraction(1, 2), sp.Rational(3, 4)) == 1  # omega_1 = omega_4: the carrier turns with them
    with pytest.raises(symkin.TextInputError, match="symkin.parse"):  # text is read by the parser, not here
        diff(1, 1, "3", Fraction(1, 2), "0.75")


def test_exact_backend_refuses_floats_and_transcendental_laws():
    with pytest.raises(symkin.InputError, match="exact"):
        symkin.compile(ratio_law(), backend="exact")(1.5, 2, 3, 4)
    with pytest.raises(symkin.UnsupportedError, match="rational laws only"):
        symkin.compile(sp.sin(W), backend="exact")


# ---------------------------------------------------------------- stable forms
def test_every_rewrite_equals_its_input_at_random_points():
    laws = [ratio_law().rhs, differential_law(), *slider_laws(), 1 - E * sp.cos(W), 1 + E**2 + 2 * E * sp.cos(W)]
    local = np.random.default_rng(5)
    checked = 0
    for law in laws:
        rewritten = st.stable_form(law, ranges={E: (0, 1)})
        plain = st.plain_form(rewritten)
        for _ in range(3):
            point = {s: sp.Rational(int(local.integers(1, 90)), 100) if not s.is_integer else int(local.integers(20, 99)) for s in law.free_symbols}
            if S.t in point:
                point[S.t] = sp.Rational(int(local.integers(1, 90)), 1000)  # inside the first branch
            value = sp.N(law.subs(point), 40)
            if not value.is_finite:  # a random point on a pole
                continue
            assert abs(value - sp.N(plain.subs(point), 40)) < 1e-30
            checked += 1
    assert checked >= 15


def test_ratio_from_tooth_numbers_is_exact_up_to_1e8_teeth():
    law = ratio_law()  # 1 - z2 z4/(z1 z3): a difference of nearly equal products
    n = 200
    z1 = rng.integers(10**7, 10**8, n)
    z3 = z1 + rng.integers(-2, 3, n)
    k = rng.integers(0, 4, n)
    z2, z4 = z1 - k, z3 + k  # z1 z3 - z2 z4 = k (z3 - z1 + k): a few units out of 10^16
    exact = [Fraction(int(a * c - b * d), int(a * c)) for a, b, c, d in zip(z1, z2, z3, z4)]
    ref = np.array([float(x) for x in exact])  # correctly rounded
    naive = sp.lambdify(Z, law.rhs)(z1.astype(float), z2.astype(float), z3.astype(float), z4.astype(float))
    assert np.nanmax(np.abs(naive - ref) / np.maximum(np.abs(ref), 1e-300)) > 1e-3  # the naive form loses them
    for backend in FLOAT_BACKENDS:
        got = symkin.compile(law, backend=backend)(z1, z2, z3, z4)
        ok = ref != 0
        assert np.max(np.abs(got[ok] - ref[ok]) / np.abs(ref[ok])) <= 2.3e-16  # within one rounding
        assert np.all(got[~ok] == 0)


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_tooth_ratios_on_both_sides_of_2_53_in_one_call_are_within_one_rounding(backend):
    """numba evaluates the integer parts in float64 where every partial sum is below 2^53 (exact
    there) and redoes the other points with integers: one array holding both kinds (z1 z3 near
    10^4 and near 10^16, the products nearly equal)."""
    law = ratio_law()
    n = 400
    big = rng.integers(0, 2, n).astype(bool)
    z1 = np.where(big, rng.integers(10**7, 10**8, n), rng.integers(20, 200, n))
    z3 = z1 + rng.integers(-2, 3, n)
    k = rng.integers(1, 4, n)
    z2, z4 = z1 - k, z3 + k
    ref = np.array([float(Fraction(int(a * c - b * d), int(a * c))) for a, b, c, d in zip(z1, z2, z3, z4)])
    got = symkin.compile(law, backend=backend)(z1, z2, z3, z4)
    ok = ref != 0
    assert np.max(np.abs(got[ok] - ref[ok]) / np.abs(ref[ok])) <= 2.3e-16  # within one rounding
    assert np.all(got[~ok] == 0)
    assert big[ok].sum() > 100 and (~big).sum() > 100


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_a_four_stage_tooth_law_beyond_2_53_is_within_one_rounding(backend):
    """Four AA stages in series: products of eight tooth numbers (about 10^16, beyond 2^53 and
    within int64), which numba's kernel computes in int64 for the whole block."""
    zs = sp.symbols("a0:4 b0:4 c0:4 d0:4", positive=True, integer=True)
    a, b, c, d = zs[0:4], zs[4:8], zs[8:12], zs[12:16]
    law = sp.Mul(*[a[k] * c[k] / (a[k] * c[k] - b[k] * d[k]) for k in range(4)])
    n = 300
    values = [rng.integers(90, 130, n) for _ in zs]
    ok = np.logical_and.reduce([values[k] * values[8 + k] != values[4 + k] * values[12 + k] for k in range(4)])
    values = [v[ok] for v in values]
    got = symkin.compile(law, list(zs), backend=backend)(*values)
    exact = [float(sp.Mul(*[Fraction(int(v[k][i]) * int(v[8 + k][i]), int(v[k][i]) * int(v[8 + k][i]) - int(v[4 + k][i]) * int(v[12 + k][i]))
                             for k in range(4)]))
             for i in range(len(values[0])) for v in [values]]
    assert np.max(np.abs(got - exact) / np.abs(exact)) <= 2.3e-16


def test_integer_parts_switch_to_python_integers_where_int64_would_overflow():
    law = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4")
    z = [3 * 10**9, 3 * 10**9 - 1, 3 * 10**9, 3 * 10**9 + 1]  # z1 z3 = 9e18 > int64 range
    exact = Fraction(z[0] * z[2], z[0] * z[2] - z[1] * z[3])
    for backend in FLOAT_BACKENDS:
        assert symkin.compile(law, backend=backend)(*z) == float(exact)


def test_removable_singularity_of_the_ii_differential_cancels():
    law = differential_law()
    args = [W1, W4, R[0], R[1], R[2]]
    r2 = 1.0 + rng.uniform(0, 1, 50)
    r3 = r2 * (1 + rng.uniform(1e-15, 1e-13, 50))  # r3 -> r2
    w1 = rng.uniform(1, 2, 50)
    values = [w1, w1, 3.0, r2, r3]  # omega_1 = omega_4: omega_H = omega_1 exactly
    raw = sp.lambdify(args, law)(*values)
    assert np.max(np.abs(raw - w1) / w1) > 1e-4  # the raw form loses its digits
    for backend in FLOAT_BACKENDS:
        f = symkin.compile(law, args, backend=backend)
        assert np.max(np.abs(f(*values) - w1) / w1) <= 1e-15
        near = [w1, w1 * (1 + 1e-9), 3.0, r2, r3]  # close to the pole, but not at it
        (r,) = reference([law], args, near)
        assert rel_error(f(*near), r) <= 1e-14


def test_a_true_pole_gives_inf_with_a_warning_or_a_clear_error():
    law = differential_law()
    args = [W1, W4, R[0], R[1], R[2]]
    for backend in FLOAT_BACKENDS:
        f = symkin.compile(law, args, backend=backend)
        with pytest.warns(symkin.PoleWarning, match="1 of 3 points"):
            out = f(np.array([1.0, 2.0, 1.0]), 1.5, 3.0, 1.0, np.array([2.0, 1.0, 2.5]))
        assert np.isinf(out[1]) and np.all(np.isfinite(out[[0, 2]]))
        with pytest.raises(symkin.PoleError, match="pole"):
            symkin.compile(law, args, backend=backend, on_pole="raise")(2.0, 1.5, 3.0, 1.0, 1.0)
    with pytest.raises(symkin.PoleError, match="pole"):
        symkin.compile(law, args, backend="exact")(2, 1, 3, 1, 1)


def test_elliptical_drive_at_e_0_999999_keeps_s_v_a_within_1e_13():
    laws = slider_laws()
    t = np.linspace(0, 6, 400)
    values = [0.999999, 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, t]
    ref = reference(slider_laws(continuous_reference=True), SLIDER_ARGS, values)
    raw = sp.lambdify(SLIDER_ARGS, laws, cse=True)(*values)
    assert max(rel_error(g, r) for g, r in zip(raw, ref)) > 1e-8  # the naive forms lose digits
    for backend in FLOAT_BACKENDS:
        got = symkin.compile(laws, SLIDER_ARGS, backend=backend, ranges={E: (0, 1)})(*values)
        for g, r in zip(got, ref):
            assert rel_error(g, r) <= 1e-13


def test_the_engines_elliptical_slider_keeps_1e_13_at_its_speed_peaks_by_default():
    # the carrier speed peaks at cos(m omega t) = 1, t = 2.5 k for m = 1, omega = 0.8 pi:
    # a uniform grid misses them; there the phase m omega t loses |m omega t| 2^-53
    from symkin.drives import EllipticalGears
    from symkin.mechanisms.cardan import CardanSlider

    slider = CardanSlider.build(L, drive=EllipticalGears(W, E, M), guide_angle=TH2, carrier_angle=TH0)
    laws = [slider.displacement, slider.velocity, slider.acceleration]
    k = np.arange(9)
    t = np.concatenate([2.5 * k, 2.5 * k + 1e-6, 2.5 * k + 1e-3, 2.5 * k[1:] - 1e-3, np.linspace(0, 20, 41)])
    values = [0.999999, 0.02, 1.0, 0.8 * np.pi, 0.3, 0.1, t]
    ref = reference(slider_laws(continuous_reference=True), SLIDER_ARGS, values)
    for backend in FLOAT_BACKENDS:
        got = symkin.compile(laws, SLIDER_ARGS, backend=backend, ranges={E: (0, 1)})(*values)
        assert max(rel_error(g, r, floor=1) for g, r in zip(got, ref)) <= 1e-13
    unreduced = symkin.compile(laws, SLIDER_ARGS, ranges={E: (0, 1)}, reduce_phase=())(*values)
    assert max(rel_error(g, r, floor=1) for g, r in zip(unreduced, ref)) > 1e-11  # what the default avoids


def test_elliptical_drive_angle_is_continuous_across_branch_points():
    laws = slider_laws()
    t = np.linspace(0, 12, 301)  # several branch points of the principal arctan for m = 2
    values = [0.5, 0.02, 2.0, 0.8 * np.pi, 0.3, 0.1, t]
    ref = reference(slider_laws(continuous_reference=True), SLIDER_ARGS, values)
    raw = sp.lambdify(SLIDER_ARGS, laws[0])(*values)
    assert rel_error(raw, ref[0]) > 0.5  # the principal branch is off by 2 pi/m after each branch point
    got = symkin.compile(laws, SLIDER_ARGS, ranges={E: (0, 1)})(*values)
    assert rel_error(got[0], ref[0], floor=1) <= 1e-14


def test_the_engines_elliptical_slider_compiles_to_the_reference_at_the_extremes():
    cardan = pytest.importorskip("symkin.mechanisms.cardan")
    from symkin.drives import EllipticalGears

    slider = cardan.CardanSlider.build(L, drive=EllipticalGears(W, E, M), guide_angle=TH2, carrier_angle=TH0)
    f = symkin.compile([slider.displacement, slider.velocity, slider.acceleration], SLIDER_ARGS, ranges={E: (0, 1)})
    t = np.linspace(0, 6, 200)
    for e, m in ((0.999999, 1.0), (0.5, 2.0), (0.3, 3.0)):
        values = [e, 0.02, m, 0.8 * np.pi, 0.3, 0.1, t]
        ref = reference(slider_laws(continuous_reference=True), SLIDER_ARGS, values)  # the papers-guide route
        for g, r in zip(f(*values), ref):
            assert rel_error(g, r, floor=1) <= 1e-13


def test_reduced_phase_keeps_digits_at_a_million_turns():
    law = sp.sin(M * W * S.t / 2)
    t = np.linspace(0, 1e6, 101) * 2 * np.pi / 0.8 + rng.uniform(0, 1, 101)
    values = [3.0, 0.8, t]
    (ref,) = reference([law], [M, W, S.t], values)
    plain = symkin.compile(law, [M, W, S.t], reduce_phase=())(*values)
    reduced = symkin.compile(law, [M, W, S.t], reduce_phase=[S.t])
    assert "reduced mod 2 pi" in reduced.__doc__
    assert symkin.compile(law, [M, W, S.t]).__doc__ == reduced.__doc__  # by default: t is time
    assert np.max(np.abs(plain - ref)) > 1e-11  # |phase| 2^-53 is lost
    assert np.max(np.abs(reduced(*values) - ref)) <= 5e-16
    if HAS_NUMBA:
        numba_reduced = symkin.compile(law, [M, W, S.t], reduce_phase=[S.t], backend="numba")
        assert np.max(np.abs(numba_reduced(*values) - ref)) <= 5e-16



@pytest.mark.parametrize("law", [
    sp.sqrt(10**40 + 1) * sp.cos(S.t),  # NumPy's sqrt met a Python integer beyond int64 (TypeError)
    sp.sqrt(1 - sp.Rational(1, 10**300)) * sp.sin(S.t) + sp.cbrt(sp.Integer(10**30 + 7)),
    sp.cos((1 - sp.Rational(1, 10**300)) ** 3 * S.t),  # a reduced phase of 900-digit integers (refused as 10^900)
    sp.sin(sp.Rational(10**20 + 1, 10**19 - 3) * S.t),  # p and q beyond 2^53, not beyond floats
    sp.cos(sp.Rational(1, 10**299) * S.t) + sp.sin(sp.Rational(3, 10**298) * S.t),  # no float power of 2 as q
])
@pytest.mark.parametrize("backend", ["numpy", pytest.param("numba", marks=pytest.mark.skipif(not HAS_NUMBA, reason="numba"))])
def test_exact_constants_beyond_int64_are_evaluated_as_floats(law, backend):
    t = np.array([0.0, 0.5, 1.0, 2.5, 40.0, 1e3])
    got = symkin.compile(law, [S.t], backend=backend)(t)
    want = np.array([float(law.subs(S.t, sp.Float(ti, 50)).evalf(50)) for ti in t])  # mpmath under SymPy, 50 digits
    scale = np.max(np.abs(want))  # the amplitude (each law reaches it at t = 0 or 0.5 to within 2)
    # the coefficient rounded to a float moves a phase w t by up to |w t| 2^-53: within 3e-13 at t = 1000 and w = 10
    assert np.all(np.abs(got - want) <= 8e-16 * scale * np.maximum(1, 10 * t))


# ---------------------------------------------------------------- the function
def test_function_states_order_precision_backend_and_pickles():
    f = symkin.compile(symkin.Law(S.omega("H"), differential_law()), [W1, W4, R[0], R[1], R[2]], precision="float32")
    assert repr(f) == "<NumericFunction omega_H(omega_1, omega_4, r_1, r_2, r_3): numpy float32>"
    assert "Arguments, in order: omega_1, omega_4, r_1, r_2, r_3." in f.__doc__ and "float32" in f.__doc__
    g = pickle.loads(pickle.dumps(f))
    assert g.args == f.args and g(1.0, 2.0, 3.0, 1.0, 2.0) == f(1.0, 2.0, 3.0, 1.0, 2.0)


def test_chunks_and_reused_output_buffers_give_the_same_numbers():
    laws, args, values, _, _ = CASES["slider"]
    whole = symkin.compile(laws, args, chunk=10**6, ranges={E: (0, 1)})(*values)
    chunked_f = symkin.compile(laws, args, chunk=7, ranges={E: (0, 1)})
    outs = [np.empty(N) for _ in laws]
    chunked = chunked_f(*values, out=outs)
    for a, b, o in zip(whole, chunked, outs):
        assert np.array_equal(a, b) and b is o
    with pytest.raises(symkin.InputError, match="out="):
        chunked_f(*values, out=[np.empty(3)] * 3)


def test_threads_and_integer_widths_give_the_same_numbers():
    law = ratio_law()
    z = [rng.integers(20, 200, 100_000) for _ in range(4)]
    one = symkin.compile(law)(*z)
    assert np.array_equal(symkin.compile(law, threads=2)(*z), one)
    if HAS_NUMBA:
        f = symkin.compile(law, backend="numba")
        assert np.array_equal(f(*(x.astype(np.int32) for x in z)), one)
        assert np.array_equal(symkin.compile(law, backend="numba", threads=1)(*z), one)


@pytest.mark.skipif(not HAS_NUMBA, reason="needs numba")
def test_a_law_numba_cannot_compile_is_evaluated_with_numpy_and_says_so():
    x = sp.Symbol("x", real=True)
    law = sp.Piecewise((x, x < 1), (x**2, True))
    f = symkin.compile(law, backend="numba")
    with pytest.warns(symkin.PrecisionWarning, match="numba could not compile"):
        out = f(np.array([0.5, 2.0]))
    assert np.array_equal(out, [0.5, 4.0])


def test_numba_missing_falls_back_to_numpy_with_one_notice(monkeypatch):
    import symkin.numeric as numeric

    monkeypatch.setattr(numeric, "numba_available", lambda: False)
    with pytest.warns(symkin.PrecisionWarning, match="numba is not installed"):
        f = symkin.compile(ratio_law(), backend="numba")
    assert f.backend == "numpy" and f(100, 99, 100, 101) == pytest.approx(1e-4, rel=1e-15)


def test_bad_requests_say_what_to_do():
    with pytest.raises(symkin.InputError, match="unknown backend"):
        symkin.compile(ratio_law(), backend="cuda")
    with pytest.raises(symkin.InputError, match="float64 or float32"):
        symkin.compile(ratio_law(), precision="float16")
    with pytest.raises(symkin.InputError, match="tooth number"):
        symkin.compile(ratio_law())(100.5, 99, 100, 101)
    with pytest.raises(symkin.InputError, match="broadcast"):
        symkin.compile(ratio_law())(np.arange(1, 3), np.arange(1, 4), 1, 1)


# ---------------------------------------------------------------- scenes
def test_a_ratio_only_scene_derives_no_particle_or_speed_laws(monkeypatch):
    from symkin import particles

    def refuse(*a, **k):
        raise AssertionError("a ratio-only scene derived particle laws")

    from symkin.model import mechanism as model

    monkeypatch.setattr(particles.Motion, "build", classmethod(refuse))
    monkeypatch.setattr(model, "_CACHES", type(model._CACHES)())  # derivations are shared by equal mechanisms: start afresh
    mech = schemes.two_row("AA", teeth=True)
    scene = symkin.Study(mech, ratios=[("H", "1", "4")])
    assert not mech._cache  # nothing derived yet
    out = scene.evaluate({"z_1": 100, "z_2": 99, "z_3": 100, "z_4": 101})
    assert out["i_{H1}^{(4)}"] == 10000.0
    # only the one set of known links the ratio needs (H driving, 4 fixed) was solved for
    solved = {k[1] for k in mech._cache if isinstance(k, tuple) and len(k) == 2 and isinstance(k[1], tuple)}
    assert solved == {("4", "H")}


def test_a_study_compiles_once_and_caches_on_the_mechanism(monkeypatch):
    import symkin.study as study

    mech = schemes.two_row("AI")
    calls = []
    real = study.compile
    monkeypatch.setattr(study, "compile", lambda *a, **k: calls.append(1) or real(*a, **k))
    kw = dict(speeds=["H", "23"], particles=[("23", (S.radius("1"), 0), ("position", "acceleration"))], inputs={"1": W1, "4": 0})
    a = symkin.Study(mech, **kw)
    values = {"omega_1": 2.0, "r_1": 1.0, "r_2": 2.0, "r_3": 1.0, "r_4": 4.0}
    t = np.linspace(0, 3, 50)
    first = a.evaluate(values, t=t)
    second = symkin.Study(mech, **kw).evaluate(values, t=t)
    assert len(calls) == 1
    # against the laws evaluated directly
    p = mech.motion({"1": W1, "4": 0}).particle("23", (S.radius("1"), 0))
    direct = sp.lambdify([S.t, *[sp.Symbol(k, positive=True) if k.startswith("r") else S.omega("1") for k in values]], list(p.acceleration))
    wx = direct(t, *values.values())[0]
    key = next(k for k in first if k.startswith("wx"))
    assert np.allclose(first[key], wx, rtol=1e-13, atol=1e-13) and np.array_equal(first[key], second[key])
    assert first["omega_H"] == pytest.approx(2.0 / 9.0 * 1.0, rel=1e-14) or first["omega_H"] == pytest.approx(float(mech.speeds({"1": 2, "4": 0})["H"].subs({S.radius("1"): 1, S.radius("2"): 2, S.radius("3"): 1, S.radius("4"): 4})), rel=1e-14)


def test_a_scene_reuses_its_output_buffers_when_asked():
    scene = symkin.Study(schemes.two_row("AA", teeth=True), ratios=[("1", "H", "4")])
    z = {"z_1": np.full(1000, 100), "z_2": 99, "z_3": 100, "z_4": np.arange(1000) + 50}
    a = scene.evaluate(z, reuse=True)["i_{1H}^{(4)}"]
    b = scene.evaluate(z, reuse=True)["i_{1H}^{(4)}"]
    assert a is b
    with pytest.raises(symkin.InputError, match="give values for z_4"):
        scene.evaluate({"z_1": 1, "z_2": 1, "z_3": 1})


# ---------------------------------------------------------------- dask
def test_dask_array_and_bag_on_a_local_cluster():
    da = pytest.importorskip("dask.array")
    db = pytest.importorskip("dask.bag")
    distributed = pytest.importorskip("distributed")
    from symkin.numeric import dask_map

    law = differential_law()
    args = [W1, W4, R[0], R[1], R[2]]
    f = symkin.compile(law, args)
    x = np.linspace(1, 2, 10_000)
    expected = f(x, 0.5, 3.0, 1.0, 2.0)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            lazy = dask_map(f, da.from_array(x, chunks=2_500), 0.5, 3.0, 1.0, 2.0)
            assert np.array_equal(lazy.compute(), expected)
            bag = db.from_sequence([(1.0, 0.5, 3.0, 1.0, 2.0), (2.0, 0.5, 3.0, 1.0, 2.0)], npartitions=2)
            assert dask_map(f, bag).compute() == [float(expected[0]), float(expected[-1])]
            assert len(client.scheduler_info()["workers"]) == 2


@pytest.mark.parametrize("precision", ["float64", "float32"])
def test_laws_with_max_min_and_functions_numpy_lacks_evaluate_on_arrays(precision):
    # SymPy's NumPy printer writes Max/Min through functools.reduce and erf or gamma as math.<name>:
    # both used to fail on arrays with a NameError (the scalar path worked)
    x, y = sp.symbols("x y", real=True)
    laws = [sp.Max(x, y, 1), sp.Min(x, y) * sp.erf(x), sp.gamma(x) + y]
    f = symkin.compile(laws, [x, y], precision=precision)
    ref = symkin.compile(laws, [x, y], backend="mpmath", digits=30)
    xs, ys = np.array([0.25, 1.5, 2.0, 3.5]), np.array([1.25, 0.5, 3.0, -1.0])
    tol = 1e-15 if precision == "float64" else 1e-6
    for got, exact in zip(f(xs, ys), ref(xs, ys)):
        exact = np.array([float(v) for v in exact])
        assert np.allclose(got, exact, rtol=tol, atol=0)
    assert all(np.isclose(g, float(e), rtol=tol) for g, e in zip(f(0.25, 1.25), ref(0.25, 1.25)))


# ---- the default backend
def test_the_default_backend_is_numba_where_it_is_installed_else_numpy(monkeypatch):
    import importlib.util

    import symkin.numeric as numeric

    monkeypatch.delenv("SYMKIN_BACKEND", raising=False)
    installed = importlib.util.find_spec("numba") is not None
    assert numeric.default_backend() == ("numba" if installed else "numpy")
    law = ratio_law()
    if installed:
        f = symkin.compile(law)
        assert f.backend == "numba" and "numba" in repr(f)
        assert f(100, 99, 100, 101) == pytest.approx(1e-4, rel=1e-15)  # (i_1H: 1/10000)
    monkeypatch.setattr(numeric, "_numba_imports", lambda: False)  # (not installed, or not importable)
    assert numeric.default_backend() == "numpy"
    assert symkin.compile(law).backend == "numpy"


@pytest.mark.parametrize("named", ["numpy", "numba"])
def test_symkin_backend_names_the_default(monkeypatch, named):
    monkeypatch.setenv("SYMKIN_BACKEND", named)
    f = symkin.compile(ratio_law())
    assert f.backend == (named if named == "numpy" or numba_available() else "numpy")
    assert symkin.compile(ratio_law(), backend="exact").backend == "exact"  # a named backend wins


def test_symkin_backend_that_is_no_float_backend_is_one_line(monkeypatch):
    monkeypatch.setenv("SYMKIN_BACKEND", "fortran")
    with pytest.raises(symkin.InputError, match=r"^SYMKIN_BACKEND='fortran' is not a float backend; set it to numpy or numba, or unset it$"):
        symkin.compile(ratio_law())


@pytest.mark.skipif(not HAS_NUMBA or __import__("numba").get_num_threads() < 2, reason="needs numba and two threads")
def test_parallel_kernels_run_one_at_a_time_and_threads_calling_at_once_agree(monkeypatch):
    """A call of 2^15 points or more runs on every thread: calls from several threads at once
    (a Dask scheduler's) take turns, as Numba's workqueue layer requires; small calls do not wait."""
    import threading

    from symkin.numeric.backends import numba as numba_backend

    entered = []

    class Recording:
        def __enter__(self):
            entered.append(True)

        def __exit__(self, *exc):
            return False

    law = differential_law()
    args = [W1, W4, R[0], R[1], R[2]]
    f = symkin.compile(law, args, backend="numba")
    values = [rng.uniform(1, 2, 1 << 16) for _ in range(5)]
    want = f(*values)
    monkeypatch.setattr(numba_backend, "_PARALLEL_LOCK", Recording())
    f(*[v[:1000] for v in values])
    assert not entered
    f(*values)
    assert entered == [True]
    monkeypatch.undo()
    out = {}
    threads = [threading.Thread(target=lambda k=k: out.__setitem__(k, f(*values))) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(out[k], want) for k in range(4))
