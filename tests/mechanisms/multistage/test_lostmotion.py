"""The lost-motion laws of a common-ring train: derived transfers against independent routes."""

from fractions import Fraction

import pytest
import sympy as sp

from symkin import schemes
from symkin import symbols as S
from symkin.errors import InputError
from symkin.mechanisms.multistage.lostmotion import (
    StageErrorModel,
    U,
    lost_motion,
    max_lost_motion,
    probable_max_backlash,
    train_speeds,
)
from symkin.parsing import parse


@pytest.mark.parametrize("n", [1, 2, 3])
def test_train_speeds_agree_with_solve_speeds(n):
    train = schemes.common_ring_train(n)
    direct = train_speeds(train)
    general = train.speeds({"s1": S.omega("s1"), "4": 0})
    for link in train.link_names:
        assert sp.cancel(direct[link] - general[link]) == 0, link


@pytest.mark.parametrize("n", [1, 2, 3, 4, 5])
def test_transfers_are_the_products_of_the_later_stage_ratios(n):
    lm = lost_motion(n)
    u = lm.ratios
    assert sp.cancel(lm.total_ratio - sp.Mul(*u)) == 0
    for i in range(n):
        assert sp.cancel(lm.sun_transfers[i] * sp.Mul(*u[i:]) - 1) == 0
        assert sp.cancel(lm.carrier_transfers[i] * sp.Mul(*u[i + 1:]) - 1) == 0


def test_the_transfers_hold_for_a_train_built_from_teeth():
    # a 3-stage train from tooth numbers: the engine's numeric speeds against the law in u,
    # with each u from the single-row scheme of the 2009 paper (an independent mechanism)
    teeth, ring = [(18, 81), (54, 63), (36, 72)], 180
    train = schemes.common_ring_train(teeth=teeth, ring=ring)
    speeds = train.speeds({"s1": 1, "4": 0})
    u = [schemes.single_row_AI(teeth=(z1, z2, ring)).ratio("1", "H", fixed="4").rhs for z1, z2 in teeth]
    lm = lost_motion(3)
    subs = dict(zip(lm.ratios, u))
    for i in range(3):
        sun_link = train.link(f"s{i + 1}").name
        assert lm.sun_transfers[i].subs(subs) == speeds["H3"] / speeds[sun_link]
    assert lm.total_ratio.subs(subs) == 1 / speeds["H3"] == sp.Rational(11 * 13 * 6, 3)


def test_objective_by_perturbation():
    # an angular error delta at sun i reaches H_n as delta * d(phi_Hn)/d(phi_si): check
    # the objective of a numeric train against a direct sum over the stages
    teeth, ring = [(18, 81), (54, 63)], 180
    train = schemes.common_ring_train(teeth=teeth, ring=ring)
    speeds = train.speeds({"s1": 1, "4": 0})
    F = [sp.Rational(3, 2), sp.Rational(5, 7)]
    direct = sum(F[i] * speeds["H2"] / speeds[train.link(f"s{i + 1}").name] for i in range(2))
    lm = lost_motion(2)
    u = [sp.Rational(180 + z1, z1) for z1, _ in teeth]
    model = [StageErrorModel(f) for f in F]  # constant Phi/d per stage
    assert lm.objective_with(model).subs(dict(zip(lm.ratios, u))) == direct


def test_backlash_line_model_against_a_hand_computation():
    m, ring, c0, c1 = Fraction(1, 2), 180, 50, Fraction(7, 18)
    model = StageErrorModel.from_backlash_line(c0, sp.Rational(7, 18), module=sp.Rational(1, 2), ring=ring)
    for z1 in (18, 54, 144):
        z2 = (ring - z1) // 2
        a12 = m * (z1 + z2) / 2
        a23 = m * (ring - z2) / 2
        phi = (c0 + c1 * a12) + (c0 + c1 * a23)
        expected = phi / (m * z1)
        assert model.at(sp.Rational(ring + z1, z1)) == sp.Rational(expected.numerator, expected.denominator)
    assert sp.Poly(model.expr, sp.Symbol("u", positive=True)).degree() == 1  # exactly linear in u


def test_tolerance_stacks():
    assert probable_max_backlash(10, 30, 40, 5) == 10 + sp.sqrt(1300)
    assert max_lost_motion(-20, 30, 30, 40, 5, 3, 4) == sp.Rational(7) + sp.sqrt(1325)
    lam = sp.Symbol("lam", positive=True)
    xs = sp.symbols("a b c d", positive=True)
    f = probable_max_backlash(*xs)
    assert sp.simplify(f.subs({x: lam * x for x in xs}, simultaneous=True) - lam * f) == 0  # a length
    with pytest.raises(InputError):
        probable_max_backlash(10, -1, 40, 5)


def test_models_and_bad_input():
    assert StageErrorModel(parse("0.854 + 0.858*u", symbols={"u": U})).expr == StageErrorModel.linear(Fraction("0.854"), Fraction("0.858")).expr
    with pytest.raises(InputError, match="not allowed"):
        StageErrorModel(parse("x + u", symbols={"u": U}))
    with pytest.raises(InputError, match="not positive"):
        StageErrorModel.linear(-3, 1).check_positive(2, 11)
    with pytest.raises(InputError, match="positive whole number"):
        lost_motion(0)
    with pytest.raises(InputError, match="module must be positive"):
        StageErrorModel.from_backlash_line(50, 1, module=0, ring=180)


# ---- positivity is decided on intervals, not on samples
TOUCH = "Abs(u - 5.123456789)"


def test_a_model_that_touches_zero_between_samples_is_refused():
    import numpy as np

    model = StageErrorModel(parse(TOUCH, symbols={"u": U}))
    # 401 samples of [2, 12], as the check used to take, all see a positive value: sampling misses the touch
    grid = np.linspace(2.0, 12.0, 401)
    assert (np.abs(grid - 5.123456789) > 1e-3).all()
    with pytest.raises(InputError, match=r"not positive over \[2, 12\]: at u = 5.12346 it is not shown to be positive"):
        model.check_positive(2, 12)
    # a model that is positive everywhere, however closely it comes to 0, is shown so
    StageErrorModel(parse("(u - 5.123456789)**2 + 1e-12", symbols={"u": U})).check_positive(2, 12)
    # at a bound, the bound is named
    with pytest.raises(InputError, match="at u = 12 it is not positive"):
        StageErrorModel(parse("12 - u", symbols={"u": U})).check_positive(2, 12)
    with pytest.raises(InputError, match="at u = 5 a divisor in it vanishes"):
        StageErrorModel(parse("1/(u - 5)**2", symbols={"u": U})).check_positive(2, 12)


def test_the_split_command_refuses_a_model_that_touches_zero(capsys):
    from symkin.cli import main

    code = main(["split", "--total", "500", "--stages", "3", "--umin", "2", "--umax", "12", "--model", TOUCH])
    err = capsys.readouterr().err
    assert code == 2 and "is not positive over [2, 12]" in err and len(err.strip().splitlines()) == 1
