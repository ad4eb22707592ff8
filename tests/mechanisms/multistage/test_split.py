"""The ratio split: the optimiser against exhaustive grids, the discrete search against brute force."""

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from symkin import schemes
from symkin.errors import InputError
from symkin.mechanisms.multistage.lostmotion import StageErrorModel, U
from symkin.mechanisms.multistage.split import (
    SplitProblem,
    best_designs,
    optimize_split,
    profile,
)
from symkin.mechanisms.multistage.stages import enumerate_stages
from symkin.parsing import parse


def objective_by_hand(u, F):
    """sum_i F(u_i) / (u_i ... u_n), written out here for the tests."""
    u = np.asarray(u, dtype=float)
    total = 0.0
    for i in range(u.shape[0]):
        total = total + F(u[i]) / np.prod(u[i:], axis=0)
    return total


MODELS = {
    "linear (paper)": ("0.854 + 0.858*u", lambda u: 0.854 + 0.858 * u),
    "quadratic": ("u**2", lambda u: u**2),
    "reversed (a + b < 0)": ("-3 + 2*u", lambda u: -3 + 2 * u),
    "falling": ("1 + 5/u", lambda u: 1 + 5 / u),
}


@pytest.mark.parametrize("name", MODELS)
@pytest.mark.parametrize("total, lower, upper", [(60, 2.25, 11), (40, 2, 10), (99, 3, 12)])
def test_two_stages_against_a_grid(name, total, lower, upper):
    text, F = MODELS[name]
    best = optimize_split(total, 2, lower=lower, upper=upper, model=StageErrorModel(parse(text, symbols={"u": U})))
    lo, hi = max(lower, total / upper), min(upper, total / lower)
    u1 = np.geomspace(lo, hi, 200001)
    values = objective_by_hand([u1, total / u1], F)
    k = int(np.argmin(values))
    assert best.objective <= values[k] + 1e-12
    assert best.objective == pytest.approx(values[k], rel=1e-8)
    assert best.ratios[0] == pytest.approx(u1[k], rel=2e-3, abs=2e-3)
    assert best.kkt_residual < 1e-5 and min(best.multipliers) >= -1e-9


@pytest.mark.parametrize("name", MODELS)
@pytest.mark.parametrize("total, lower, upper", [(600, 2.25, 11), (100, 2, 9)])
def test_three_stages_against_a_grid(name, total, lower, upper):
    text, F = MODELS[name]
    best = optimize_split(total, 3, lower=lower, upper=upper, model=StageErrorModel(parse(text, symbols={"u": U})))
    # a grid over two of the three ln u_i (bounds included), the third from the product;
    # each of the three pairs in turn, so an optimum with two stages on bounds is a grid point
    x = np.linspace(math.log(lower), math.log(upper), 801)
    xa, xb = np.meshgrid(x, x, indexing="ij")
    xc = math.log(total) - xa - xb
    ok = (xc >= math.log(lower) - 1e-12) & (xc <= math.log(upper) + 1e-12)
    grid_min = np.inf
    for free in range(3):
        cols = [xa, xb]
        cols.insert(free, xc)
        values = np.where(ok, objective_by_hand(np.exp(np.array(cols)), F), np.inf)
        grid_min = min(grid_min, float(values.min()))
    assert best.objective <= grid_min + 1e-12
    assert best.objective == pytest.approx(grid_min, rel=1e-5)
    assert np.prod(best.ratios) == pytest.approx(total, rel=1e-9)


def test_linear_models_fill_from_the_output_and_the_explanation_says_why():
    best = optimize_split(6000, 4, lower=Fraction("2.25"), upper=11, model=StageErrorModel.linear(Fraction("0.854"), Fraction("0.858")))
    assert best.exact_ratios == (sp.Rational(6000, 1331), 11, 11, 11)
    assert best.active == ("free", "upper", "upper", "upper") and best.global_optimum
    g = best.log_gradient
    assert all(g[j] > g[j + 1] for j in range(3))
    assert all(m > 0 for m in best.multipliers[1:])
    a, b, U = sp.Rational("0.854"), sp.Rational("0.858"), 6000
    u1 = sp.Rational(6000, 1331)
    # on u_1...u_4 = U the objective is b + (a + (a + b)(u1 + u1 u2 + u1 u2 u3))/U
    assert best.exact_objective == b + (a + (a + b) * (u1 + u1 * 11 + u1 * 121)) / U
    text = " ".join(best.explain())
    assert "upper bound" in text and "global minimum" in text and "g_j - g_(j+1) > 0" in text
    # the derivative of the optimum with respect to ln U is nu: a finite difference
    h = 1e-4
    up = optimize_split(6000 * math.exp(h), 4, lower=Fraction("2.25"), upper=11, model=StageErrorModel.linear(Fraction("0.854"), Fraction("0.858")))
    assert (up.objective - best.objective) / h == pytest.approx(best.nu, rel=1e-3)


def test_a_reversed_linear_model_fills_from_the_input():
    # g_j - g_(j+1) = (a + b)/(u_(j+1)...u_n) < 0 when a + b < 0: ratio goes to the input
    best = optimize_split(100, 3, lower=2, upper=10, model=StageErrorModel.linear(-3, 2))
    assert best.exact_ratios == (10, 5, 2) and best.active == ("upper", "free", "lower")
    assert all(best.log_gradient[j] < best.log_gradient[j + 1] for j in range(2))
    assert "toward the input" in " ".join(best.explain())
    assert not best.global_optimum  # the objective has terms -1/(u_2 u_3) and -1/u_3: not a posynomial
    assert best.kkt_residual < 1e-9


def test_profile_touches_the_optimum():
    p = SplitProblem.build(6000, 4, lower=Fraction("2.25"), upper=11, model=StageErrorModel.linear(Fraction("0.854"), Fraction("0.858")))
    best = optimize_split(6000, 4, lower=Fraction("2.25"), upper=11, model=StageErrorModel.linear(Fraction("0.854"), Fraction("0.858")))
    for i in range(1, 5):
        values = profile(p, i, [best.ratios[i - 1], 3.0])
        assert values[0] == pytest.approx(best.objective, rel=1e-9)
        assert np.isnan(values[1]) or values[1] >= best.objective


SPLIT_BAD = [
    (dict(total=6000, stages=4, lower=11, upper=Fraction("2.25")), "reversed"),
    (dict(total=6000, stages=2, lower=Fraction("2.25"), upper=11), "outside what 2 stages"),
    (dict(total=-5, stages=2, lower=2, upper=11), "must be positive"),
    (dict(total=60, stages=0, lower=2, upper=11), "positive whole number"),
    (dict(total=60, stages=2, lower=0, upper=11), "must be positive"),
    (dict(total=60, stages=2, lower=[2, 3, 4], upper=11), "one value or one per stage"),
]


@pytest.mark.parametrize("kwargs, message", SPLIT_BAD)
def test_bad_split_input(kwargs, message):
    with pytest.raises(InputError, match=message):
        optimize_split(model=StageErrorModel.linear(1, 1), **kwargs)
    with pytest.raises(InputError, match="not positive"):
        optimize_split(60, 2, lower=1, upper=60, model=StageErrorModel.linear(-3, 2))


# ---------------------------------------------------------------------------- discrete
PAPER = enumerate_stages(180, 3, zmin=18, zmax=180)
MODEL = StageErrorModel.linear(Fraction("0.854"), Fraction("0.858"))


def brute_force(stages, n, total, tol, F):
    """Every ordered design (all 22^n), products in floats with exact Fractions near the edge."""
    r = np.array([float(s.ratio) for s in stages])
    grids = np.meshgrid(*([r] * n), indexing="ij")
    prod = np.prod(grids, axis=0)
    near = np.abs(prod - total) <= float(tol) * total * (1 + 1e-9)
    exact = [Fraction(int(s.ratio.p), int(s.ratio.q)) for s in stages]
    tol_x = Fraction(str(tol))
    out = []
    objective = objective_by_hand(grids, F)
    for idx in zip(*np.nonzero(near)):
        p = math.prod(exact[k] for k in idx)
        if abs(p - total) <= tol_x * total:
            out.append((float(objective[idx]), tuple(stages[k] for k in idx)))
    return sorted(out, key=lambda t: t[0])


@pytest.mark.parametrize("name", MODELS)
@pytest.mark.parametrize("n, total, tol", [(2, 60, "0.02"), (3, 600, "0.05"), (3, 250, "0.01"), (4, 6000, "0.05"), (4, 3000, "0.01")])
def test_discrete_search_equals_brute_force(name, n, total, tol):
    text, F = MODELS[name]
    model = StageErrorModel(parse(text, symbols={"u": U}))
    expected = brute_force(PAPER.stages, n, total, sp.Rational(tol), F)
    got = best_designs(total, PAPER, n, model=model, tolerance=Fraction(tol), top=8, distinct=False)
    assert got.meets_tolerance == bool(expected)
    if expected:
        assert [float(d.objective) for d in got.designs] == pytest.approx([e[0] for e in expected[:8]], rel=1e-12)
        assert got.designs[0].stages == expected[0][1]
        assert got.nodes < 22**n  # pruned, not enumerated
    distinct = best_designs(total, PAPER, n, model=model, tolerance=Fraction(tol), top=8)
    keys = [tuple(sorted(d.ratios)) for d in distinct.designs]
    assert len(keys) == len(set(keys))
    if expected:
        # each stage set once, in its best order, the sets ranked as brute force ranks them
        best_by_set = {}
        for obj, combo in expected:
            best_by_set.setdefault(tuple(sorted(s.ratio for s in combo)), (obj, combo))
        ranked = sorted(best_by_set.values(), key=lambda t: t[0])[:8]
        assert [d.stages for d in distinct.designs] == [c for _, c in ranked]


def test_no_design_in_tolerance_gives_the_nearest():
    got = best_designs(6000, PAPER, 4, model=MODEL, tolerance=Fraction("0.01"), top=3)
    assert not got.meets_tolerance and "no design meets the tolerance" in got.message()
    ratios = [s.ratio for s in PAPER]
    products = {sp.Mul(*c) for c in itertools.combinations_with_replacement(ratios, 4)}
    nearest = min(products, key=lambda p: abs(math.log(float(p) / 6000)))
    assert got.designs[0].total == nearest == 5929
    assert abs(float(got.designs[0].deviation)) > 0.01


def test_the_best_design_recomputed_from_its_teeth():
    got = best_designs(60000, PAPER, 5, model=MODEL, tolerance=Fraction("0.01"), top=3)
    best = got.designs[0]
    teeth = [(s.sun, s.planet) for s in best.stages]
    train = schemes.common_ring_train(teeth=teeth, ring=180)
    assert train.ratio("s1", "H5", fixed="4").rhs == best.total
    speeds = train.speeds({"s1": 1, "4": 0})
    a, b = sp.Rational("0.854"), sp.Rational("0.858")
    recomputed = 0
    for i in range(5):
        sun = train.link(f"s{i + 1}").name
        u_i = speeds[sun] / speeds[f"H{i + 1}"]
        recomputed += (a + b * u_i) * speeds["H5"] / speeds[sun]
    assert recomputed == best.objective
    assert abs(best.total - 60000) <= sp.Rational(1, 100) * 60000


def test_progress_is_reported():
    calls = []
    best_designs(6000, PAPER, 4, model=MODEL, tolerance=Fraction("0.05"), progress=lambda f, nodes: calls.append((f, nodes)))
    assert calls and calls[-1][0] == 1.0 and calls[-1][1] > 0


@pytest.mark.parametrize("kwargs, message", [
    (dict(tolerance=Fraction("-0.1")), "must not be negative"),
    (dict(tolerance=Fraction("1.5")), "below 1"),
    (dict(top=0), "positive whole number"),
    (dict(lower=12, upper=20), "no feasible stage"),
    (dict(lower=5, upper=3), "reversed"),
])
def test_bad_discrete_input(kwargs, message):
    args = dict(model=MODEL, tolerance=Fraction("0.01"))
    args.update(kwargs)
    with pytest.raises(InputError, match=message):
        best_designs(6000, PAPER, 4, **args)
