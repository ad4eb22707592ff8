"""Decide cheaply whether a symbolic residual is zero, for the tests.

``sp.simplify`` of a residual that is zero returns quickly; of one that is not (an engine
bug), it may never return: a hand-made bug in eq. (6) kept a test busy for more than nine
CPU-minutes.  :func:`zero` decides instead by values: every undefined function of time
(``theta_1(t)``) becomes a polynomial with random rational coefficients, so that its
derivatives are independent random numbers, and every symbol a random rational of the sign
its assumptions give; the residual is then evaluated at 50 digits at a few such points.  A
residual that is identically zero gives 0 (to rounding) at every point; one that is not is
non-zero at random points with probability 1.  :func:`shown` simplifies a residual under a
time budget, only to print it in a failure message.
"""

from __future__ import annotations

import random
import warnings
from typing import Any

import sympy as sp

from symkin._util.budget import simplify_within

#: Points tried, significant digits, and the size below which a value counts as 0.
POINTS = 3
DIGITS = 50
TOLERANCE = sp.Float("1e-30", DIGITS)


def _value(sym: sp.Symbol, rng: random.Random) -> sp.Expr:
    if sym.is_integer:
        n = sp.Integer(rng.randint(3, 40))
        return -n if sym.is_negative else n
    x = sp.Rational(rng.randint(11, 97), rng.randint(23, 61))  # about 0.2 to 4, not a round number
    if sym.is_negative or sym.is_nonpositive:
        return -x
    return x


def _functions_to_polynomials(expr: Any, t_values: dict[sp.Symbol, sp.Expr], rng: random.Random) -> Any:
    """Every undefined function applied to symbols, as a random polynomial of degree 6 in them."""
    calls = {f for f in expr.atoms(sp.core.function.AppliedUndef)}
    if not calls:
        return expr
    repl = {}
    for call in calls:
        poly = sp.Integer(0)
        for arg in call.args:
            for k in range(7):
                poly += sp.Rational(rng.randint(-40, 40), rng.randint(7, 19)) * arg**k
        repl[call] = poly
    return expr.subs(repl).doit()


def zero(expr: Any, *, points: int = POINTS, seed: int = 2009) -> bool:
    """Whether ``expr`` (a SymPy expression or matrix) is identically 0, decided by values.

    >>> x = sp.Symbol("x", positive=True)
    >>> zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1), zero(sp.sin(x) ** 2 - sp.cos(x) ** 2)
    (True, False)
    """
    items = list(expr) if isinstance(expr, sp.MatrixBase) else [sp.sympify(expr)]
    rng = random.Random(seed)
    for _ in range(points):
        for item in items:
            symbols = sorted(item.free_symbols, key=lambda s: s.name)
            values = {s: _value(s, rng) for s in symbols}
            value = _functions_to_polynomials(item, values, rng).subs(values)
            number = sp.N(value, DIGITS)
            if number.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
                continue  # a pole at this point: another point decides
            # cancellation among the terms of a sum leaves rounding of the largest term's size
            scale = max([sp.Float(1, DIGITS)] + [abs(sp.N(a, DIGITS)) for a in sp.Add.make_args(value)[:50]])
            if abs(number) > TOLERANCE * scale:
                return False
    return True


def shown(expr: Any, seconds: float = 5.0) -> str:
    """``expr`` simplified within ``seconds`` (as it stands past them), for a failure message."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the budget's warning when it runs out
            return str(simplify_within(expr, seconds=seconds))[:2000]
    except Exception as err:  # printing must never hide the failure it reports
        return f"{str(expr)[:2000]} (not simplified: {type(err).__name__})"
