"""The stable-form nodes: expressions equal to their plain form that the float backends evaluate their own way.

The rules of :mod:`symkin.numeric.stable` write laws with these nodes; the printers of
:mod:`symkin.numeric.codegen` and the kernels of :mod:`symkin.numeric.kernel` generate their
float code (exact integer arithmetic, double-double products and sums, reduced phases); every
other use (SymPy's evaluation, derivatives, LaTeX, :func:`plain_form`) sees the plain expression.
Every name is importable from :mod:`symkin.numeric.stable` too.

    >>> import sympy as sp
    >>> z = sp.Symbol("z", integer=True)
    >>> ExactRatio(z - 1, z).doit()
    (z - 1)/z
"""

from __future__ import annotations

from typing import Any

import sympy as sp

__all__ = [
    "Group",
    "ExactRatio",
    "ReducedPhase",
    "LongPhase",
    "CompensatedSum",
    "ProductDifference",
    "long_phase",
    "compensated_sum",
    "plain_form",
]


class Group(sp.Function):
    """Its argument, evaluated as one unit (printed in parentheses, never merged into
    an enclosing sum): keeps ``(1 - e)`` from being summed as ``1 - e + ...`` term by term."""

    nargs = 1

    @classmethod
    def eval(cls, arg: sp.Expr) -> sp.Expr | None:
        """An atom needs no grouping: return it as it is (SymPy's automatic evaluation)."""
        return arg if arg.is_Atom else None

    def doit(self, **hints: Any) -> sp.Expr:
        """The grouped expression itself."""
        return self.args[0]

    def _eval_evalf(self, prec: int) -> sp.Expr:
        return self.args[0]._eval_evalf(prec)

    def _eval_derivative(self, s: sp.Symbol) -> sp.Expr:
        return sp.diff(self.args[0], s)

    def _eval_is_real(self) -> bool | None:
        return self.args[0].is_real

    def _latex(self, printer: Any) -> str:
        return printer._print(self.args[0])


class _Deferred(sp.Function):
    """A float-evaluation form that is, symbolically, just its ``doit()``."""

    def _eval_evalf(self, prec: int) -> sp.Expr:
        return self.doit()._eval_evalf(prec)

    def _eval_derivative(self, s: sp.Symbol) -> sp.Expr:
        return sp.diff(self.doit(), s)

    def _latex(self, printer: Any) -> str:
        return printer._print(self.doit())


class ExactRatio(_Deferred):
    """``N/D`` with ``N`` and ``D`` integer polynomials of integer-valued symbols.

    Float backends evaluate ``N`` and ``D`` in exact integer arithmetic (int64, or
    Python integers when int64 could overflow; numba's float64 kernels in float64 where a
    bound of every partial sum is below 2^53, which is exact there) and divide once; the
    quotient is then within about one unit in the last place of the exact rational
    (correctly rounded below 2^53; beyond it two integers rounded to float64 are divided).
    """

    nargs = 2
    is_real = True

    @classmethod
    def eval(cls, num: sp.Expr, den: sp.Expr) -> sp.Expr | None:
        """Two numbers divide at once (SymPy's automatic evaluation)."""
        if num.is_Number and den.is_Number:
            return num / den
        return None

    def doit(self, **hints: Any) -> sp.Expr:
        """The plain quotient ``num / den``."""
        return self.args[0] / self.args[1]

    def _eval_evalf(self, prec: int) -> sp.Expr:
        return (self.args[0] / self.args[1])._eval_evalf(prec)

    def _eval_derivative(self, s: sp.Symbol) -> sp.Expr:
        return sp.diff(self.doit(), s)

    def _latex(self, printer: Any) -> str:
        return printer._print(self.doit())


class ReducedPhase(sp.Function):
    """``p/q * x1 * x2 * x3`` reduced to [-pi, pi) in double-double arithmetic.

    Arguments: the integers ``p``, ``q`` and up to three factors.  Equal to the product
    modulo 2 pi; its error is about 2^-52 pi whatever the number of turns, where the
    plain product loses ``|x1 x2 x3| 2^-53`` radians.
    """

    is_real = True

    def doit(self, **hints: Any) -> sp.Expr:
        """The plain phase ``p/q x1 x2 ...`` without reduction."""
        p, q, *xs = self.args
        return sp.Rational(p, q) * sp.Mul(*xs)


class LongPhase(_Deferred):
    """``c * t`` for a rational function ``c`` of inputs, reduced mod 2 pi where it is long.

    Arguments: a key (an integer digest of ``c``, naming the generated double-double code),
    ``c``, ``t``, and the symbols of ``c`` in order.  Float backends evaluate ``c t`` as
    written where ``|c t| <= 8`` rad, and elsewhere ``c`` in double-double arithmetic
    from the inputs (so the rounding of ``c`` to a float is not multiplied by ``t``),
    the product reduced modulo 2 pi: the phase keeps about 2^-52 pi at any number of
    turns below 2^27 (the plain product loses ``|c t| 2^-53`` radians and more).
    """

    is_real = True

    def doit(self, **hints: Any) -> sp.Expr:
        """The plain phase ``c t``."""
        return self.args[1] * self.args[2]

    @property
    def name(self) -> str:
        """The name of the generated double-double function."""
        return f"_symkin_phase_{int(self.args[0]):016x}"


def long_phase(coeff: sp.Expr, t: sp.Symbol) -> LongPhase:
    """The :class:`LongPhase` of ``coeff * t`` (its key a digest of ``coeff``)."""
    import hashlib

    key = int(hashlib.sha256(sp.srepr(coeff).encode()).hexdigest()[:15], 16)
    syms = sorted(coeff.free_symbols, key=lambda s: s.name)
    return LongPhase(sp.Integer(key), coeff, t, *syms)


class CompensatedSum(_Deferred):
    """A polynomial ``p`` of inputs whose terms can cancel (``w1 r1 r3 - w4 r2 r4``), evaluated
    by the float64 backends in double-double arithmetic and rounded once.

    Arguments: a key (an integer digest of ``p``, naming the generated code), ``p``, and its
    symbols in order.  Each term's product is split exactly (Dekker's TwoProduct, every input
    split once) and the terms summed error-free (Sum2 of Ogita, Rump & Oishi), so the float64
    result is within one rounding and a few units of ``n^2 2^-106`` (``n`` terms) of the sum of
    the terms' magnitudes of the exact ``p`` of the binary inputs: a few units in the last place
    unless the terms cancel to 2^-45 of their size (:func:`symkin.numeric.runtime.sum_source`).  Holds while the inputs are below 2^995
    and the products above 2^-969 in magnitude; float32 evaluates the plain ``p``.
    """

    is_real = True

    def doit(self, **hints: Any) -> sp.Expr:
        """The plain polynomial."""
        return self.args[1]

    @property
    def name(self) -> str:
        """The name of the generated double-double function."""
        return f"_symkin_sum_{int(self.args[0]):016x}"


def compensated_sum(poly: sp.Expr) -> CompensatedSum:
    """The :class:`CompensatedSum` of ``poly`` (its key a digest of ``poly``)."""
    import hashlib

    key = int(hashlib.sha256(sp.srepr(poly).encode()).hexdigest()[:15], 16)
    return CompensatedSum(sp.Integer(key), poly, *sorted(poly.free_symbols, key=lambda s: s.name))


class ProductDifference(_Deferred):
    """``a*b - c*d``, evaluated in double-double arithmetic by the float backends where
    the two products cancel.

    Where ``2 |a b - c d| < |a b + c d|`` both products are split exactly into a double and
    its rounding error (Dekker), and the four parts are summed in double-double
    arithmetic; elsewhere the plain difference is within 3 units of 2^-53 already.  So the
    float64 result is within 3 units of 2^-53 of the exact ``a b - c d`` of the binary
    inputs, whatever the cancellation, and zero exactly where it is (float32: the
    products are exact in float64).
    This holds while the inputs are below 2^995 and the products above 2^-969 in
    magnitude (or zero); outside that range the plain ``a*b - c*d`` is used.
    """

    nargs = 4
    is_real = True

    @classmethod
    def eval(cls, a: sp.Expr, b: sp.Expr, c: sp.Expr, d: sp.Expr) -> sp.Expr | None:
        """Numbers evaluate at once to ``a b - c d`` (SymPy's automatic evaluation)."""
        if all(x.is_Number for x in (a, b, c, d)):
            return a * b - c * d
        return None

    def doit(self, **hints: Any) -> sp.Expr:
        """The plain difference ``a b - c d``."""
        a, b, c, d = self.args
        return a * b - c * d


def plain_form(expr: sp.Expr) -> sp.Expr:
    """``expr`` with every :class:`ExactRatio` and :class:`ReducedPhase` written out.

    >>> z = sp.Symbol("z", integer=True)
    >>> plain_form(ExactRatio(z - 1, z))
    (z - 1)/z
    """
    return expr.replace(lambda e: isinstance(e, (Group, ExactRatio, ReducedPhase, ProductDifference, LongPhase, CompensatedSum)),
                        lambda e: e.doit())
