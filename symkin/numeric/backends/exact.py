"""The ``exact`` backend: rational laws in exact rational arithmetic (:class:`fractions.Fraction`)."""

from __future__ import annotations

import functools
import operator
from collections.abc import Callable, Mapping
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import InputError, UnsupportedError
from symkin.numeric.backends.pointwise import PointwiseBackend
from symkin.numeric.codegen import ExactPrinter
from symkin.values import refuse_text

__all__ = ["ExactBackend", "exact_form", "exact_value"]


class ExactBackend(PointwiseBackend):
    """Exact rational arithmetic on :class:`fractions.Fraction` (rational laws only)."""

    key = "exact"
    precisions = ("exact",)

    def generate(self, exprs: list[sp.Expr]) -> Callable[..., Any]:
        """The laws as one function of Fractions; an UnsupportedError for a law that is not rational."""
        for e in exprs:
            bad = [n for n in sp.preorder_traversal(e)
                   if not (n.is_Symbol or n.is_Rational or n.is_Add or n.is_Mul or (n.is_Pow and n.exp.is_Integer))]
            if bad:
                raise UnsupportedError(
                    f"the exact backend evaluates rational laws only, and this one contains {bad[0]}; "
                    "use backend='mpmath' with digits=... instead"
                )
        return sp.lambdify(list(self.plan.args), exprs, modules=[{"Fraction": Fraction}], printer=ExactPrinter(),
                           cse=self.plan.cse, docstring_limit=0)

    def convert(self, value: Any, name: str) -> Any:
        """One input as a Fraction (an InputError for a float: it is not exact)."""
        return _to_fraction(value, name)


    def result(self, value: Any) -> Any:
        """An output as a Fraction (a law that is an integer constant gives an int)."""
        return value if type(value) is Fraction else Fraction(value)


def _to_fraction(v: Any, name: str) -> Any:
    kind = type(v)
    if kind is Fraction:  # the common cases first: this runs once per argument and call
        return v
    if kind is int:
        return Fraction(v)
    if isinstance(v, (bool, np.bool_)):
        raise InputError(f"{name} must be a number, got {v!r}")
    if isinstance(v, (int, np.integer)):
        return Fraction(int(v))  # so that / stays exact
    if isinstance(v, Fraction):
        return v
    if isinstance(v, sp.Rational):
        return Fraction(int(v.p), int(v.q))
    if isinstance(v, str):
        raise refuse_text(v, name)
    raise InputError(
        f"{name} must be exact for the exact backend (int or Fraction), got {v!r}; "
        "use backend='mpmath' for floats"
    )


@functools.lru_cache(maxsize=1024)
def exact_form(expr: sp.Expr) -> Callable[[Mapping[sp.Symbol, int]], Fraction | None] | None:
    """``expr``, a rational function of integers (tooth numbers) with rational coefficients, as a
    function of their values in exact integer arithmetic, or None for an expression that is not one.

    Its numerator and denominator become polynomials with integer coefficients, compiled once per
    process (on a Dask worker too) and called without the checks of a compiled function's call
    (the synthesis's inner loop, where the values are tooth numbers it made): a value is then a
    few products of Python integers and one :class:`~fractions.Fraction`, microseconds where
    SymPy's substitution and cancellation take a millisecond or more.  The function takes whole
    numbers only (a TypeError for others) and returns None where the denominator of the cancelled
    form vanishes (a common factor that vanishes too is cancelled first: the value is its limit).

    >>> z1, z2 = sp.symbols("z1 z2")
    >>> f = exact_form(z1 / (z1 + z2) + sp.Rational(1, 2))
    >>> f({z1: 30, z2: 18}), f({z1: 3, z2: -3})
    (Fraction(9, 8), None)
    >>> exact_form(z1 / 2 + z2 / 2)({z1: 19, z2: 30})
    Fraction(49, 2)
    >>> exact_form(sp.sqrt(z1)) is None
    True
    """
    args = tuple(sorted(expr.free_symbols, key=str))
    try:
        num, den = sp.fraction(sp.cancel(sp.together(expr)))
        gens = args or (sp.Dummy(),)
        cn, pn = sp.Poly(num, *gens).clear_denoms()
        cd, pd = sp.Poly(den, *gens).clear_denoms()
    except sp.PolynomialError:
        return None
    if not all(q.domain.is_ZZ or q.domain.is_QQ for q in (pn, pd)):  # (cleared, a QQ polynomial has integer coefficients)
        return None
    # dummify: two symbols of one name (other assumptions) are two arguments
    polynomials = sp.lambdify(args, (pn.as_expr(), pd.as_expr()), modules=[], dummify=True, docstring_limit=0)
    ratio = sp.Rational(cd, cn)
    factor = Fraction(int(ratio.p), int(ratio.q))

    def value(values: Mapping[sp.Symbol, int]) -> Fraction | None:
        top, bottom = polynomials(*[operator.index(values[z]) for z in args])  # Python integers (no overflow), whole only
        return None if bottom == 0 else Fraction(top, bottom) * factor

    return value


def exact_value(expr: sp.Expr, values: Mapping[sp.Symbol, int]) -> Fraction | None:
    """The exact value of ``expr`` at the whole numbers ``values``: by :func:`exact_form` where
    ``expr`` is rational in them, else SymPy's substitution; None where it has no rational value
    (a zero denominator, an irrational number).

    >>> z = sp.Symbol("z")
    >>> exact_value(z / 2 + 1, {z: 3}), exact_value(sp.sqrt(z) / 2, {z: 9}), exact_value(1 / (z - 3), {z: 3})
    (Fraction(5, 2), Fraction(3, 2), None)
    """
    exact = exact_form(expr)
    if exact is not None:
        return exact(values)
    value = sp.cancel(expr.xreplace({z: sp.Integer(v) for z, v in values.items()}))  # not rational in them
    return Fraction(int(value.p), int(value.q)) if value.is_Rational else None
