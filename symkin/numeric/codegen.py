"""Printers of the compiled laws.

:class:`FloatPrinter` prints NumPy code (vectorised) or, with ``kernel=True``, scalar
code for a Numba loop (:mod:`symkin.numeric.kernel` writes the loop around it); it knows the
stable-form nodes of :mod:`symkin.numeric.stable`.  :class:`ScalarPrinter` prints Python
code on floats for one point, :class:`ExactPrinter` rational arithmetic on
:class:`fractions.Fraction`.

    >>> import sympy as sp
    >>> from symkin.numeric.nodes import ExactRatio
    >>> z = sp.Symbol("z", integer=True)
    >>> FloatPrinter().doprint(ExactRatio(z - 1, z) + sp.Rational(1, 3))
    '_symkin_exact_ratio(z - 1, z) + 1/3'
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.pycode import PythonCodePrinter

from symkin.numeric.nodes import (
    CompensatedSum,
    ExactRatio,
    Group,
    LongPhase,
    ProductDifference,
    ReducedPhase,
    plain_form,
)
from symkin.numeric.runtime import LONG_PHASE

__all__ = ["FloatPrinter", "ScalarPrinter", "ExactPrinter", "abs_bound", "phase_sources", "product_ratios"]


class ProductRatio(sp.Function):
    """``a*b / (a*b - c*d)`` with the difference a :class:`ProductDifference`: what the NumPy
    float64 code computes anyway to certify the difference (``g`` of
    :func:`symkin.numeric.runtime.product_difference`), so a law that multiplies by ``a*b``
    and divides by the difference takes it as it is (:func:`product_ratios`)."""

    nargs = 4
    is_real = True

    def doit(self, **hints: Any) -> sp.Expr:
        """The ratio with its difference: ``a*b / ProductDifference(a, b, c, d)``."""
        a, b, c, d = self.args
        return a * b / ProductDifference(a, b, c, d)


def product_ratios(exprs: Sequence[sp.Expr]) -> list[sp.Expr]:
    """``exprs`` with each product ``a*b*X / ProductDifference(a, b, c, d)`` written
    ``X * ProductRatio(a, b, c, d)``: two passes over the points fewer (the product ``a*b``
    again, and a division) for the Willis forms ``r1 r3/(r1 r3 - r2 r4)``.  A difference
    that also appears elsewhere is left as it is (it would be computed twice); so is every
    one inside a :class:`LongPhase`, whose coefficient stays whole.

    >>> r1, r2, r3, r4, w = sp.symbols("r1:5 w")
    >>> product_ratios([w * r1 * r3 / ProductDifference(r1, r3, r2, r4)])
    [w*ProductRatio(r1, r3, r2, r4)]
    """
    skip: set[tuple[sp.Expr, ...]] = set()
    while True:
        out = [_with_ratios(e, skip) for e in exprs]
        taken = {n.args for e in out for n in sp.preorder_traversal(e) if isinstance(n, ProductRatio)}
        shared = (taken & set().union(*(_bare_differences(e) for e in out))) - skip
        if not shared:
            return out
        skip |= shared


def _without(factors: list[sp.Expr] | None, x: sp.Expr) -> list[sp.Expr] | None:
    """``factors`` with one factor ``x`` taken out (``x**k`` becomes ``x**(k-1)``), or None."""
    if factors is None or x.is_Number:
        return None
    for k, f in enumerate(factors):
        if f == x:
            return factors[:k] + factors[k + 1:]
        base, exp = f.as_base_exp()
        if base == x and exp.is_Integer and exp > 1:
            return factors[:k] + [base ** (exp - 1)] + factors[k + 1:]
    return None


def _with_ratios(e: sp.Expr, skip: set[tuple[sp.Expr, ...]]) -> sp.Expr:
    """``e`` with every product ``a*b*X / ProductDifference(a, b, c, d)`` (not in ``skip``)
    written ``X * ProductRatio(a, b, c, d)``, innermost first."""
    if e.is_Atom or isinstance(e, (LongPhase, CompensatedSum)):
        return e
    args = [_with_ratios(a, skip) for a in e.args]
    e = e.func(*args) if any(x is not y for x, y in zip(args, e.args)) else e
    if not e.is_Mul:
        return e
    factors = list(e.args)
    for k, f in enumerate(factors):
        if not (f.is_Pow and f.exp == -1 and isinstance(f.base, ProductDifference)) or f.base.args in skip:
            continue
        a, b, c, d = f.base.args
        rest = _without(_without(factors[:k] + factors[k + 1:], a), b)
        if rest is not None:
            return sp.Mul(*rest) * ProductRatio(a, b, c, d)
    return e


def _bare_differences(e: sp.Expr) -> set[tuple[sp.Expr, ...]]:
    """The arguments of every :class:`ProductDifference` of ``e`` outside a ratio or a long phase."""
    if isinstance(e, ProductDifference):
        return {e.args}
    if e.is_Atom or isinstance(e, (LongPhase, ProductRatio, CompensatedSum)):
        return set()
    return set().union(*(_bare_differences(a) for a in e.args))


def phase_sources(exprs: Sequence[sp.Expr]) -> dict[str, str]:
    """The double-double source of every :class:`LongPhase` coefficient and every
    :class:`CompensatedSum` in ``exprs``, by function name (see
    :func:`symkin.numeric.runtime.dd_source`)."""
    from symkin.numeric.runtime import dd_source, sum_source

    out: dict[str, str] = {}
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, LongPhase) and node.name not in out:
                _key, coeff, _t, *syms = node.args
                out[node.name] = dd_source(node.name, plain_form(coeff), syms)
            elif isinstance(node, CompensatedSum) and node.name not in out:
                _key, poly, *syms = node.args
                poly = plain_form(poly)
                out[node.name] = sum_source(node.name, poly, syms) or dd_source(node.name, poly, syms)
    return out


def compensated_bound(poly: sp.Expr) -> sp.Expr | None:
    """``K (|t_1| + ... + |t_m|)`` for the terms ``t_k`` of ``poly``: where the plain float64
    sum ``v`` has ``|v| >= K sum |t_k|`` it is within 8 units of 2^-53 of the exact sum (its
    error is at most ``(f + m - 1) 2^-53 sum |t_k|`` to first order, ``f`` the most roundings
    in one term, so ``K = 1.01 (f + m - 1)/8``); None where ``K >= 1`` (never certified)."""
    terms = sp.Add.make_args(poly)
    rounds = 0
    for t in terms:
        coeff, factors = t.as_coeff_mul()
        n = sum(int(f.as_base_exp()[1]) for f in factors)
        rounds = max(rounds, n - 1 + (0 if abs(coeff) == 1 else 1))
    k = sp.Rational(101, 100) * (rounds + len(terms) - 1) / 8
    if k >= 1:
        return None
    return sp.Float(k, 17) * sp.Add(*(abs(t.as_coeff_mul()[0]) * sp.Mul(*(sp.Abs(f) for f in t.as_coeff_mul()[1])) for t in terms))


def _print_compensated_sum(printer: Any, expr: CompensatedSum, precision: str, kernel: bool = False) -> str:
    """The high part of the double-double sum (the NumPy code: the plain sum where it is
    certified, see :func:`compensated_bound`); in float32 of the inputs in float64, rounded
    (a kernel's double-double code converts its inputs itself)."""
    args = [printer._print(a) for a in expr.args[2:]]
    if precision == "float64":
        bound = None if kernel else compensated_bound(expr.args[1])
        if bound is None:
            return f"{expr.name}({', '.join(args)})[0]"
        return (f"_symkin_compensated_sum({printer._print(expr.args[1])}, {printer._print(bound)}, {expr.name}, "
                f"{', '.join(args)})")
    if kernel:
        return f"_F({expr.name}({', '.join(args)})[0])"
    return f"numpy.float32({expr.name}({', '.join(f'numpy.float64({a})' for a in args)})[0])"


def _print_long_phase(printer: Any, expr: LongPhase, kernel: bool) -> str:
    _key, coeff, t, *syms = expr.args
    plain = f"({printer._print(coeff)})*{printer._print(t)}"
    args = [printer._print(a) for a in syms]
    call = f"_dd_reduce_pair({expr.name}({', '.join(args)}), {printer._print(t)})"
    fixed = getattr(printer, "phase_fixed", None) if kernel else None
    if fixed is not None:  # a block whose coefficients are its inputs' at its first point: every phase reduced
        return f"_dd_reduce(_mh{fixed[expr.name]}, _ml{fixed[expr.name]}, {printer._print(t)})"
    memo = getattr(printer, "phase_memo", None) if kernel else None
    if memo is not None:  # a kernel's loop: the coefficient kept while its inputs repeat (below)
        k = memo.setdefault(expr.name, (len(memo), len(args)))[0]
        same = " and ".join([f"_mv{k}"] + [f"{a} == _mk{k}_{i}" for i, a in enumerate(args)])
        lines = [f"if not abs({plain}) <= {LONG_PHASE!r} and not ({same}):",
                 f"    _mh{k}, _ml{k} = {expr.name}({', '.join(args)})",
                 f"    _mv{k} = True"]
        lines += [f"    _mk{k}_{i} = {a}" for i, a in enumerate(args)]
        if lines[0] not in printer.pending:
            printer.pending += lines
        return f"(({plain}) if abs({plain}) <= {LONG_PHASE!r} else _dd_reduce(_mh{k}, _ml{k}, {printer._print(t)}))"
    if kernel:  # one point: the double-double path only where the phase is long (see runtime.LONG_PHASE)
        return f"(({plain}) if abs({plain}) <= {LONG_PHASE!r} else {call})"
    return f"_symkin_long_phase({plain}, {expr.name}, {', '.join(printer._print(a) for a in (t, *syms))})"


class _ProductCalls:
    """The float printers' calls of the runtime's differences and ratios of products."""

    _print: Any

    def _print_ProductDifference(self, expr: ProductDifference) -> str:
        return f"_symkin_product_difference({', '.join(self._print(a) for a in expr.args)})"

    def _print_ProductRatio(self, expr: ProductRatio) -> str:
        return f"_symkin_product_ratio({', '.join(self._print(a) for a in expr.args)})"


class FloatPrinter(_ProductCalls, NumPyPrinter):
    """NumPy printer for float32/float64 code, vectorised or scalar (``kernel=True``)."""

    def __init__(self, precision: str = "float64", kernel: bool = False, settings: dict | None = None):
        super().__init__(settings or {})
        self.precision = precision
        self.kernel = kernel
        self._integer_mode = False
        #: In a kernel's blocked loop: the long phases met, by name -> (index of their memo
        #: variables, number of coefficient inputs) (``None``: no memo), and the statements
        #: to put before the line printed.
        self.phase_memo: dict[str, tuple[int, int]] | None = None
        #: In a kernel's blocked loop where every long phase's coefficient is the same at every
        #: point (its inputs scalars): the phases by name -> index of their coefficient variables.
        self.phase_fixed: dict[str, int] | None = None
        #: In a float64 kernel's second pass: exact ratios in int64 (else in float64, exact below 2^53).
        self.exact_ints = False
        self.pending: list[str] = []

    # numbers: a float32 kernel wraps constants so that Numba keeps float32
    def _wrap(self, text: str) -> str:
        if self.kernel and self.precision == "float32" and not self._integer_mode:
            return f"_F({text})"
        return text

    def _print_Integer(self, expr: sp.Integer) -> str:
        return self._wrap(str(expr.p))

    def _print_Rational(self, expr: sp.Rational) -> str:
        return self._wrap(f"{expr.p}/{expr.q}")

    def _print_Float(self, expr: sp.Float) -> str:
        return self._wrap(repr(float(expr)))

    def _print_NumberSymbol(self, expr: Any) -> str:
        return self._wrap(repr(float(expr)))

    _print_Pi = _print_NumberSymbol
    _print_Exp1 = _print_NumberSymbol

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exp = expr.as_base_exp()
        if self.kernel and exp.is_Integer and 0 < abs(int(exp)) <= 4:
            b = self.parenthesize(base, 100)
            prod = "*".join([b] * abs(int(exp)))
            return f"({prod})" if exp > 0 else f"({self._print(sp.Integer(1))}/({prod}))"
        if self.kernel and self.precision == "float32" and not (exp.is_Rational and exp.q == 2):
            return f"{self.parenthesize(base, 100)}**{self._print(exp)}"
        return super()._print_Pow(expr, rational=rational)

    def _print_Group(self, expr: Group) -> str:
        return f"({self._print(expr.args[0])})"

    def _print_ExactRatio(self, expr: ExactRatio) -> str:
        saved, self._integer_mode = self._integer_mode, True
        try:
            num, den = (self._print(a) for a in expr.args)
        finally:
            self._integer_mode = saved
        if self.kernel:
            bn, bd = (self._print(abs_bound(a)) for a in expr.args)
            if self.precision == "float64" and not self.exact_ints:  # in the float twins: exact in a block the kernel found below 2^53
                twins = {s: sp.Symbol(FLOAT_TWIN + s.name) for a in expr.args for s in a.free_symbols}
                num, den = (self._print(a.xreplace(twins)) for a in expr.args)
                return f"(({num})/({den}))"
            return f"_symkin_exact_ratio({num}, {den}, {bn}, {bd})"
        return f"_symkin_exact_ratio({num}, {den})"

    def _print_ReducedPhase(self, expr: ReducedPhase) -> str:
        p, q, *xs = expr.args
        xs = list(xs) + [sp.Integer(1)] * (3 - len(xs))
        saved, self._integer_mode = self._integer_mode, True
        try:
            parts = [self._print(x) for x in xs]
        finally:
            self._integer_mode = saved
        return f"_symkin_reduced_phase({int(p)}, {int(q)}, {', '.join(parts)})"

    def _print_LongPhase(self, expr: LongPhase) -> str:
        return _print_long_phase(self, expr, self.kernel)

    def _print_CompensatedSum(self, expr: CompensatedSum) -> str:
        return _print_compensated_sum(self, expr, self.precision, self.kernel)


#: Name prefix of the float twin of an integer symbol inside a kernel.
FLOAT_TWIN = "_f_"


def abs_bound(poly: sp.Expr) -> sp.Expr:
    """``sum |c| prod |z|^d`` over the terms of an integer polynomial, in the float twins of
    its symbols: an upper bound of every partial sum met while evaluating it."""
    terms = []
    for term in sp.Add.make_args(sp.expand(poly)):
        coeff, factors = term.as_coeff_mul()
        mags = []
        for f in factors:
            base, exp = f.as_base_exp()
            mags.append(sp.Abs(sp.Symbol(FLOAT_TWIN + base.name)) ** exp)
        terms.append(sp.Float(abs(float(coeff))) * sp.Mul(*mags))
    return sp.Add(*terms)


class ScalarPrinter(_ProductCalls, PythonCodePrinter):
    """Python code on floats (the ``math`` module) for one point of a float64 law: the
    scalar path of a compiled law, with the stable-form nodes of :mod:`symkin.numeric.stable`
    called as scalar helpers (exact ratios on Python integers are correctly rounded).

    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> ScalarPrinter().doprint(sp.sin(x) / 3 + ProductDifference(x, y, y, 2))
    '(1/3)*math.sin(x) + _symkin_product_difference(x, y, y, 2)'
    """

    def _print_Rational(self, expr: sp.Rational) -> str:
        return f"{expr.p}/{expr.q}"  # one correctly rounded division of exact integers

    def _print_Float(self, expr: sp.Float) -> str:
        return repr(float(expr))

    def _print_NumberSymbol(self, expr: Any) -> str:
        return repr(float(expr))

    _print_Pi = _print_NumberSymbol
    _print_Exp1 = _print_NumberSymbol

    def _print_Group(self, expr: Group) -> str:
        return f"({self._print(expr.args[0])})"

    def _print_ExactRatio(self, expr: ExactRatio) -> str:
        return f"_symkin_exact_ratio({', '.join(self._print(a) for a in expr.args)})"

    def _print_ReducedPhase(self, expr: ReducedPhase) -> str:
        p, q, *xs = expr.args
        xs = list(xs) + [sp.Integer(1)] * (3 - len(xs))
        return f"_symkin_reduced_phase({int(p)}, {int(q)}, {', '.join(self._print(x) for x in xs)})"

    def _print_LongPhase(self, expr: LongPhase) -> str:
        return _print_long_phase(self, expr, False)

    def _print_CompensatedSum(self, expr: CompensatedSum) -> str:
        bound = compensated_bound(expr.args[1])
        if bound is None:
            return _print_compensated_sum(self, expr, "float64")
        # runtime's scalar compensated sum written out (one call less per point: issue 34, item 4)
        v = f"_v{expr.name}"
        # float(): a Python float whatever the inputs (an np.float64 input would make a division by
        # the sum a NumPy warning, not the ZeroDivisionError that sends the call to the general path)
        return (f"float({v} if abs({v} := {self._print(expr.args[1])}) >= {self._print(bound)} else "
                f"{expr.name}({', '.join(self._print(a) for a in expr.args[2:])})[0])")


class ExactPrinter(PythonCodePrinter):
    """Python code on :class:`fractions.Fraction`: rationals stay exact.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> ExactPrinter().doprint(x / 3 + sp.Rational(1, 2))
    '(Fraction(1, 3))*x + Fraction(1, 2)'
    """

    def _print_Rational(self, expr: sp.Rational) -> str:
        return f"Fraction({expr.p}, {expr.q})" if expr.q != 1 else str(expr.p)

    def _print_Integer(self, expr: sp.Integer) -> str:
        return str(expr.p)

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exp = expr.as_base_exp()
        return f"{self.parenthesize(base, 100)}**({int(exp)})"
