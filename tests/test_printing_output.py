"""LaTeX printing and compiled numeric functions."""

import numpy as np
import pytest
import sympy as sp

import symkin
from symkin import schemes
from symkin import symbols as S


def test_latex_prints_a_ratio_as_the_paper_does():
    law = schemes.two_row("AA", teeth=True).ratio("1", "H", fixed="4")
    assert symkin.latex(law) == r"i_{1H}^{(4)} = 1 - \frac{z_{2} z_{4}}{z_{1} z_{3}}"


def test_latex_greek_indices_numbers_and_alignment():
    speeds = schemes.two_row("AI").speeds({"1": S.omega("1"), "4": S.omega("4")})
    tex = symkin.latex(speeds, number=["23a.1", "23a.2"])
    assert tex.startswith(r"\begin{align}") and r"\omega_{23} &=" in tex and r"\tag{23a.2}" in tex
    tex = symkin.latex(speeds, symbol_names={S.omega("23"): r"\omega_{\mathrm{sat}}"})
    assert r"\omega_{\mathrm{sat}} &=" in tex and r"\begin{aligned}" in tex


def test_latex_round_trips_through_sympys_parser():
    pytest.importorskip("antlr4")
    from sympy.parsing.latex import parse_latex

    law = schemes.two_row("AI", teeth=True).ratio("1", "H", fixed="4")
    assert parse_latex(symkin.latex(law.rhs)) is not None


def test_compiled_function_states_argument_order_and_matches_exact_values():
    law = schemes.two_row("AI").speeds({"1": S.omega("1"), "4": S.omega("4")}).law("H")
    f = symkin.compile(law)
    assert f.args == ("omega_1", "omega_4", "r_1", "r_2", "r_3", "r_4")
    assert "omega_1, omega_4, r_1, r_2, r_3, r_4" in f.__doc__
    rng = np.random.default_rng(1)
    vals = rng.uniform(1, 10, size=(6, 100))
    got = f(*vals)
    for i in range(0, 100, 17):
        exact = law.rhs.subs(dict(zip(sp.symbols(f.args, real=True), vals[:, i])))
        exact = law.rhs.subs({s: sp.Float(v, 30) for s, v in zip(sorted(law.free_symbols, key=str), vals[:, i])})
        assert got[i] == pytest.approx(float(exact), rel=1e-13)


def test_compile_refuses_missing_arguments():
    law = schemes.two_row("AI").ratio("1", "H", fixed="4")
    with pytest.raises(symkin.InputError, match="depends on r_4"):
        symkin.compile(law, args=[S.radius("1"), S.radius("2"), S.radius("3")])
