"""Long times by default: the planet laws at t = 1e6 s keep 1e-13 normwise, because the phase
c t is reduced mod 2 pi with c = omega_1 r1 r3/(r1 r3 + r2 r4) evaluated in double-double from
the inputs (not rounded to a float first); and a float32 request whose rounded inputs land
near a pole says so.  References: the mpmath backend at 50 digits on the same binary inputs."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as hs

import symkin
from symkin import schemes
from symkin import symbols as S
from symkin.numeric import stable as st
from symkin.numeric.backends import numba_available

FLOAT_BACKENDS = ["numpy"] + (["numba"] if numba_available() else [])
W1, T = S.omega("1"), S.t
R = [S.radius(i) for i in "1234"]
ARGS = [W1, *R, S.t]


def planet_laws():
    """AI, gear 4 fixed: the planet particle's velocity and acceleration (x and y)."""
    motion = schemes.two_row("AI").motion({"1": W1, "4": 0})
    particle = motion.particle("23", (R[0], 0))
    return [*particle.velocity, *particle.acceleration]


def normwise(got, ref):
    return float(np.max(np.abs(got - ref)) / np.max(np.abs(ref)))


@pytest.fixture(scope="module")
def reference():
    laws = planet_laws()
    rng = np.random.default_rng(41)
    t = 1e6 + rng.uniform(0, 20, 60)
    values = [2.0, 2.0, 1.5, 1.0, 4.5, t]
    ref = symkin.compile(laws, ARGS, backend="mpmath", digits=50)(*values)
    return laws, values, [np.array([float(x) for x in r]) for r in ref]


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_planet_laws_at_a_million_seconds_keep_1e13_by_default(reference, backend):
    laws, values, ref = reference
    got = symkin.compile(laws, ARGS, backend=backend)(*values)
    for g, r in zip(got, ref):
        assert normwise(g, r) <= 1e-13
    plain = symkin.compile(laws, ARGS, backend=backend, reduce_phase=())(*values)
    assert max(normwise(g, r) for g, r in zip(plain, ref)) > 1e-11  # what the reduction avoids (1.6e-10)


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_a_coefficient_whose_inputs_change_from_point_to_point_is_computed_for_each_point(backend):
    """The numba kernel keeps a long phase's double-double coefficient while its inputs repeat
    (runs of equal speeds, a scalar radius): runs, changes back, short phases between, and one
    radius changing alone must each give the coefficient of their own point."""
    laws = planet_laws()
    rng = np.random.default_rng(5)
    f = symkin.compile(laws, ARGS, backend=backend)
    reference = symkin.compile(laws, ARGS, backend="mpmath", digits=50)
    for n in (2600, 40_000):  # three blocks of the kernel's loop; enough points for its threads
        w = np.repeat(rng.choice([2.0, 3.0, -1.25], n // 10), 10)
        r3 = np.where(np.arange(n) % 7 == 3, 1.25, 1.0)  # one input alone differs now and then
        t = 1e6 + rng.uniform(0, 20, n)
        t[::11] = rng.uniform(0, 1, t[::11].size)  # short phases: the plain product, nothing kept
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # no quiet fallback to NumPy
            got = f(w, 2.0, 1.5, r3, 4.5, t)
        pick = np.r_[0:40, 1020:1040, rng.choice(n, 60, replace=False)]
        ref = reference(w[pick], 2.0, 1.5, r3[pick], 4.5, t[pick])
        for g, r in zip(got, ref):
            r = np.array([float(x) for x in r])
            assert normwise(g[pick], r) <= 1e-13
    if backend == "numba":
        assert "_mv0" in f.source  # the kept coefficient is in the kernel


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_a_tooth_number_in_a_long_phase_s_coefficient(backend):
    # the coefficient holds an exact ratio of tooth numbers; its double-double code takes the
    # inputs themselves (the numba kernel generated it from a ratio variable and failed)
    w, t = sp.Symbol("w", positive=True), sp.Symbol("t", real=True)
    z = sp.Symbol("z", integer=True, positive=True)
    law = sp.sin(w * z / (z + 3) * t)
    f = symkin.compile(law, [w, z, t], backend=backend)
    ts = np.array([0.5, 1e6, 3e7, 1e6 + 0.25])
    zs = np.array([20, 20, 21, 97])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = f(2.0, zs, ts)
    ref = symkin.compile(law, [w, z, t], backend="mpmath", digits=50)(2.0, zs, ts)
    assert np.max(np.abs(got - np.array([float(x) for x in ref]))) <= 4e-16


def test_the_scalar_path_reduces_the_phase_too(reference):
    laws, values, ref = reference
    f = symkin.compile(laws, ARGS)
    for i in range(5):
        point = [*values[:5], float(values[5][i])]
        got = f(*point)
        assert all(isinstance(g, np.float64) for g in got)  # the scalar path, not the arrays
        for g, r in zip(got, ref):
            assert abs(g - r[i]) <= 1e-13 * np.max(np.abs(r))


def test_short_phases_are_the_plain_product_and_long_ones_are_reduced():
    w, t = sp.Symbol("w", positive=True), sp.Symbol("t", real=True)
    r1, r2 = sp.symbols("r1 r2", positive=True)
    law = sp.sin(w * r1 * t / (r1 + r2))
    f = symkin.compile(law, [w, r1, r2, t])
    assert any(isinstance(n, st.LongPhase) for n in sp.preorder_traversal(f.stable_exprs[0]))
    assert sp.simplify(st.plain_form(f.stable_exprs[0]) - law) == 0
    ref = symkin.compile(law, [w, r1, r2, t], backend="mpmath", digits=50)
    ts = np.array([0.0, 1.0, 3.0, 1e3, 1e6, 1e8])
    got = f(0.7, 0.3, 0.1, ts)
    exact = np.array([float(x) for x in ref(0.7, 0.3, 0.1, ts)])
    assert np.max(np.abs(got - exact)) <= 4e-16
    # no times at all: an empty result of the same shape (the long-phase test took the maximum
    # of nothing and raised ValueError)
    assert f(0.7, 0.3, 0.1, np.array([])).shape == (0,) and f(0.7, 0.3, 0.1, np.zeros((0, 3))).shape == (0, 3)
    # a coefficient holding pi is held in double-double (to 2^-106) and reduced; a Float is not exact: left as it is
    assert any(isinstance(n, st.LongPhase) for n in sp.preorder_traversal(st.reduce_phases(sp.sin(sp.pi * w * t / (r1 + r2)), [t])))
    assert not any(isinstance(n, st.LongPhase) for n in sp.preorder_traversal(st.reduce_phases(sp.sin(0.1 * w * t / (r1 + r2)), [t])))


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_float32_near_a_pole_from_float64_inputs_warns(backend):
    aa = schemes.two_row("AA").ratio("H", "1", fixed="4")  # r1 r3/(r1 r3 - r2 r4)
    f = symkin.compile(aa, backend=backend, precision="float32")
    with pytest.warns(symkin.PrecisionWarning, match="float32 cannot hold"):
        f(0.7, 0.1, 0.3, 2.1)  # r1 r3 - r2 r4 = -4.2e-17 in float64, its float32 rounding is another point
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f(np.float32(0.7), np.float32(0.1), np.float32(0.3), np.float32(2.1))  # the float32 point itself: exact
        f(0.5, 0.25, 1.0, 1.0)  # far from the pole: float32 holds it


# ---------------------------------------------------------------- exact speeds: multiples of pi, surds
M = sp.Symbol("m", positive=True)
CONSTANTS = [sp.pi, sp.sqrt(2), sp.pi / sp.sqrt(3), sp.E, sp.Integer(1)]


@settings(deadline=None, max_examples=20, derandomize=True)
@given(hs.integers(1, 2000), hs.integers(1, 2000), hs.sampled_from(CONSTANTS), hs.booleans())
def test_phases_of_any_exact_speed_are_reduced_within_1e13_at_long_times(p, q, constant, with_input):
    """sin(w t) and sin(w m t) for an exact speed w = p/q * constant: the phase is reduced in
    double-double whatever the constant (the rounding of w to a float is not multiplied by
    t = 1e6 s), against mpmath at 50 digits on the same binary inputs."""
    w = sp.Rational(p, q) * constant
    law, args = (sp.sin(w * M * T), [M, T]) if with_input else (sp.sin(w * T), [T])
    t = 1e6 + np.linspace(0, 3, 25)
    values = ([1.25] if with_input else []) + [t]
    ref = np.array([float(x) for x in symkin.compile(law, args, backend="mpmath", digits=50)(*values)])
    got = symkin.compile(law, args, backend="numpy")(*values)
    assert np.max(np.abs(got - ref)) <= 1e-13
    assert abs(symkin.compile(law, args, backend="numpy")(*[v if np.ndim(v) == 0 else v[7] for v in values]) - ref[7]) <= 1e-13


@pytest.mark.parametrize("backend", FLOAT_BACKENDS)
def test_the_2018_drive_at_its_exact_speed_0_8_pi_keeps_1e13_at_its_peaks(backend):
    """Luo & Li 2018's elliptical drive at its own exact speed 4 pi/5 rad/s and e = 0.999999:
    the phases 4 pi m t/5 in double-double (before: 2e-9 normwise, as without reduction)."""
    from symkin.drives import EllipticalGears
    from symkin.mechanisms.cardan import CardanSlider

    e, length, w, th2, th0 = sp.Symbol("e", positive=True), sp.Symbol("l", positive=True), sp.Symbol("omega"), \
        sp.Symbol("theta_2", real=True), sp.Symbol("theta_H0", real=True)
    slider = CardanSlider.build(length, drive=EllipticalGears(w, e, M), guide_angle=th2, carrier_angle=th0)
    laws = [x.subs(w, 4 * sp.pi / 5) for x in (slider.displacement, slider.velocity, slider.acceleration)]
    args = [e, length, M, th2, th0, T]
    k = np.arange(9)
    t = np.concatenate([2.5 * k, 2.5 * k + 1e-6, 2.5 * k + 1e-3, 2.5 * k[1:] - 1e-3])  # the speed peaks
    values = [0.999999, 0.02, 1.0, 0.3, 0.1, t]
    ref = symkin.compile(laws, args, backend="mpmath", digits=50)(*values)
    got = symkin.compile(laws, args, backend=backend, ranges={e: (0, 1)})(*values)
    for g, r in zip(got, ref):
        assert normwise(g, np.array([float(x) for x in r])) <= 1e-13
