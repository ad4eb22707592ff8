"""Value mappings (values=...) never reach SymPy's string parser, and keys match by name."""

import pytest
import sympy as sp

from symkin import InputError, schemes
from symkin import symbols as S
from symkin.parsing import parse
from symkin.values import as_values, substitute

INJECTION = "__import__('os').system('touch PWNED') or 1"


@pytest.fixture
def particle():
    return schemes.single_row_AI().motion({"4": 0, "H": 1}).particle("2", (S.radius("1"), 0))


def test_trajectory_values_are_never_executed(particle, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError, match="is the text .*symkin.parse"):
        particle.trajectory(1.0, values={"r_1": INJECTION, "r_2": 1, "r_4": 3})
    with pytest.raises(InputError, match="not allowed"):
        parse(INJECTION)
    assert not (tmp_path / "PWNED").exists()


def test_keys_match_by_name_whatever_the_assumptions(particle):
    plain = {sp.Symbol("r_1"): 1, "r_2": sp.Rational(1), sp.Symbol("r_4", real=True): 3.0}
    _t, x, y = particle.trajectory(2.0, samples=3, values=plain)
    exact = substitute(particle.position, {"r_1": 1, "r_2": 1, "r_4": 3})
    assert x[-1] == pytest.approx(float(exact[0].subs(S.t, 2)))
    assert y[-1] == pytest.approx(float(exact[1].subs(S.t, 2)))


@pytest.mark.parametrize("bad", ["1", None, [1], {1: 2}])
def test_bad_time_spans_and_mappings_are_symkin_errors(particle, bad):
    with pytest.raises(InputError):
        if isinstance(bad, (dict, list)):
            particle.trajectory(1.0, values=bad)
        else:
            particle.trajectory(bad, t_start=2.0, values={"r_1": 1, "r_2": 1, "r_4": 3})


def test_as_values_refuses_strange_keys():
    with pytest.raises(InputError, match="key"):
        as_values({3.5: 1})


@pytest.mark.parametrize("text", ["E**1000", "-exp(800)"])
def test_typed_values_beyond_float64_are_refused_with_the_range(text):
    from symkin.parsing import parse_real

    with pytest.raises(InputError, match="beyond the float64 range"):
        parse_real(text, what="--carrier-angle")
    assert parse_real("E**690") == sp.E**690  # large, still within the 1e300 bound on every number (E**700 is 1e304)


def test_numpy_floats_offset_units_and_complex_numbers_at_the_gate():
    # found in review: NumPy 2 prints a float64 as np.float64(0.1), which the decimal reader refused
    import numpy as np
    import pint

    from symkin.units import factor, quantity
    from symkin.values import as_expr, as_float, as_rational

    assert as_rational(np.float64(0.1)) == sp.Rational(1, 10) == as_rational(np.float32(0.1))
    ureg = pint.UnitRegistry()
    assert quantity(ureg.Quantity(np.float64(300), "rpm"), "rad/s") == 10 * sp.pi
    # a float is the decimal it prints wherever a value enters: the AA train with w_4 = 0 by Willis,
    # w_1 / w_H = 1 - z2 z4 / (z1 z3), exactly (it came out as a SymPy Float)
    speeds = schemes.two_row("AA", teeth=(54, 45, 44, 55)).speeds({"1": 0.1, "4": 0})
    assert speeds["H"] == sp.Rational(1, 10) / (1 - sp.Rational(45 * 55, 54 * 44))
    assert as_expr(np.float64(2.5), what="x") == sp.Rational(5, 2)
    # an offset unit has no factor (0 degC is 273.15 K): refused, a difference is fine
    for call in (lambda: quantity(ureg.Quantity(5, "degC"), "K"), lambda: factor("degC", "K")):
        with pytest.raises(InputError, match="has an offset from K"):
            call()
    assert quantity(ureg.Quantity(5, "delta_degC"), "K") == 5
    # a complex number is refused even with an imaginary part of 0 (sympify drops it)
    for value in (1 + 0j, np.complex128(1)):
        with pytest.raises(InputError, match="must be a real number"):
            as_expr(value, what="x")
        with pytest.raises(InputError, match="must be a real number"):
            as_float(value, what="x")
