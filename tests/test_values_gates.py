"""One gate per kind of value, one JSON shape, one return type per kind of result."""

from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from symkin.errors import InputError, ModelError
from symkin.mechanisms.multistage.lostmotion import U
from symkin.parsing import parse
from symkin.values import as_integer, as_rational, as_real


# ---- exact numbers: a float is the decimal it prints as, never a guessed surd
@pytest.mark.parametrize("value, expected", [
    (0.1, sp.Rational(1, 10)),
    (0.7071067811865476, sp.Rational(7071067811865476, 10**16)),
    (1e-05, sp.Rational(1, 100000)),
    (np.float32(0.1), sp.Rational(1, 10)),
    (np.int64(7), sp.Integer(7)),
    (Fraction(3, 4), sp.Rational(3, 4)),
    (Decimal("2.50"), sp.Rational(5, 2)),
    (sp.Float(0.25), sp.Rational(1, 4)),
    (12, sp.Integer(12)),
])
def test_as_rational_takes_what_the_user_wrote(value, expected):
    assert as_rational(value) == expected


@pytest.mark.parametrize("value", [float("nan"), float("inf"), np.float64("-inf"), Decimal("NaN"), sp.oo, sp.nan,
                                   True, None, [1], "x", "6000/1331", sp.Symbol("x")])
def test_as_rational_refuses_what_is_not_a_finite_number(value):
    with pytest.raises(InputError):
        as_rational(value, what="v")


def test_as_rational_refuses_an_irrational_and_says_so():
    with pytest.raises(InputError, match="rational"):
        as_rational(sp.sqrt(2))
    with pytest.raises(ModelError):
        as_rational(float("nan"), error=ModelError)


def test_as_integer_and_as_real():
    assert as_integer(12) == 12 and as_integer(np.int32(3)) == 3
    for bad in (3.0, Fraction(5, 2), Fraction(1, 2)):
        with pytest.raises(InputError, match="whole number"):
            as_integer(bad)
    assert as_real(sp.pi / 6) == sp.pi / 6 and as_real(sp.sqrt(2) / 2) == sp.sqrt(2) / 2 and as_real(0.5) == sp.Rational(1, 2)
    for bad in ("t", sp.Symbol("x"), sp.zoo, sp.sqrt(-1, evaluate=False), "pi/6"):
        with pytest.raises(InputError):
            as_real(bad)


def test_existence_interval_of_a_float_is_that_of_its_decimal_not_of_sqrt2_over_2():
    from symkin.mechanisms.helical.balanced import existence_interval

    decimal = existence_interval("II", 3, 0.7071067811865476)
    assert decimal == existence_interval("II", 3, sp.Rational(7071067811865476, 10**16))
    surd = existence_interval("II", 3, sp.sqrt(2) / 2)
    assert decimal != surd and sp.N(decimal[1] - surd[1], 30) != 0
    assert abs(float(decimal[1] - surd[1])) < 1e-15  # the same to float precision, as it should be


def test_floats_given_to_every_gate_are_their_decimals():
    from symkin.mechanisms.helical import HelicalTrain
    from symkin.mechanisms.helical.balanced import HelicalRequest
    from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    from symkin.mechanisms.multistage.split import SplitProblem
    from symkin.mechanisms.multistage.stages import enumerate_stages

    assert StageErrorModel.linear(0.854, 0.858).expr == sp.Rational(854, 1000) + sp.Rational(858, 1000) * sp.Symbol("u", positive=True)
    p = SplitProblem.build(100.5, 2, lower=2.25, upper=11, model=StageErrorModel.linear(1, 1))
    assert p.total == sp.Rational(201, 2) and p.lower[0] == sp.Rational(9, 4)
    assert HelicalRequest(scheme="AI", ratio=25.1, tolerance=0.02).ratio == Fraction(251, 10)
    assert HelicalTrain("AI", (20, 40, 20, 80), (2.5, 0.1), (0.1, 0.1)).normal_modules == (Fraction(5, 2), Fraction(1, 10))
    assert enumerate_stages(80, 3, zmin=17, ha=0.8).ha == sp.Rational(4, 5)
    with pytest.raises(InputError):
        enumerate_stages(80, 3.0)


# ---- the "why" of the active bounds is said only when it is true
def test_why_sentence_matches_the_active_set():
    from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    from symkin.mechanisms.multistage.split import optimize_split

    both_free = optimize_split(100, 2, lower=2, upper=20, model=StageErrorModel(parse("sin(u) + 2", symbols={"u": U})))
    assert both_free.active == ("free", "free")
    g = both_free.log_gradient
    assert abs(g[0] - g[1]) <= 1e-6 * max(map(abs, g))  # equal gradients: no direction is preferred
    text = "\n".join(both_free.explain())
    assert "g_j - g_(j+1) > 0" not in text and "free stages share one gradient value" in text

    khai = optimize_split(6000, 4, lower=Fraction("2.25"), upper=11, model=StageErrorModel.linear(Fraction("0.854"), Fraction("0.858")))
    assert khai.active == ("free", "upper", "upper", "upper")
    assert all(a - b > 0 for a, b in zip(khai.log_gradient, khai.log_gradient[1:]))
    assert any(line.startswith("why: g_j - g_(j+1) > 0") for line in khai.explain())


# ---- a derived law is a Law wherever it is returned as such; conditions stay Eq
def test_laws_are_laws_and_conditions_are_equations():
    from symkin import schemes
    from symkin import symbols as S
    from symkin.laws import Law
    from symkin.mechanisms.cardan import line_conditions
    from symkin.mechanisms.helical.balanced import RATIO, ratio_law
    from symkin.mechanisms.multistage.stages import stage_laws

    mech = schemes.two_row("II", teeth=True)
    direct = mech.ratio("1", "H", fixed="4")
    law = ratio_law("II")
    assert isinstance(direct, Law) and isinstance(law, Law) and law.lhs == RATIO
    assert sp.simplify(law.rhs - direct.rhs) == 0
    z1, z4 = S.teeth("1"), S.teeth("4")
    stage = stage_laws()
    assert isinstance(stage.ratio, Law) and sp.simplify(stage.ratio.rhs - (1 + z4 / z1)) == 0  # 2009 paper (13b)
    assert isinstance(stage.coaxiality, sp.Eq)
    c = line_conditions()
    assert all(isinstance(e, sp.Eq) for e in (c.ratio, c.lengths, c.installation))


def test_helical_train_ratio_is_the_mechanisms_ratio():
    from fractions import Fraction

    from symkin.mechanisms.helical import HelicalTrain

    train = HelicalTrain("AI", (18, 80, 20, 108), (2, sp.Rational(5, 2)), (0.49, 0.15))
    assert train.ratio == Fraction(25) == 1 + Fraction(80 * 108, 18 * 20)  # 1 + z2 z4/(z1 z3)
    law = train.mechanism.ratio("1", "H", fixed="4").rhs
    assert train.ratio == Fraction(int(sp.numer(law)), int(sp.denom(law)))


def test_scene_values_accept_names_and_symbols():
    import symkin
    from symkin import schemes
    from symkin import symbols as S

    scene = symkin.Study(schemes.two_row("AI"), ratios=[("1", "H", "4")])
    by_name = scene.evaluate({"r_1": 1, "r_2": 2, "r_3": 1, "r_4": 4})
    by_symbol = scene.evaluate({S.radius("1"): 1, S.radius("2"): 2, S.radius("3"): 1, S.radius("4"): 4})
    assert list(by_name.values()) == list(by_symbol.values()) == [9.0]  # 1 + r2 r4/(r1 r3)


# ---- import symkin is cheap; every public name is still there on first use
def test_import_symkin_loads_no_sympy_and_every_name_resolves():
    import subprocess
    import sys

    code = ("import sys, symkin; assert 'sympy' not in sys.modules, 'sympy loaded'; "
            "assert all(getattr(symkin, n) is not None for n in symkin.__all__); "
            "assert symkin.numeric.dask_map and symkin.mechanisms.helical.balanced.synthesize_helical and symkin.Gear.__module__ == 'symkin.model'; "
            "print(symkin.schemes.two_row('AA', teeth=(100, 100, 101, 99)).ratio('H', '1', fixed='4').rhs)")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "101/2"  # the 2009 paper's 50.5
    import symkin

    with pytest.raises(AttributeError):
        symkin.no_such_name
    assert "Mechanism" in dir(symkin) and "mechanisms" in dir(symkin) and "Study" in dir(symkin)
