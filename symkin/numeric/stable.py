"""Stable forms: rewrite a law so that its float evaluation keeps its digits.

Every rule returns an expression *equal* to its input (tests check this on random
points); only the order of operations changes.  The rules, each general and
pattern-based on SymPy expressions:

* :func:`relative_form` -- a law linear and homogeneous in some inputs whose
  coefficients sum to a constant C (every speed law: all links turn together when all
  known speeds are equal) is written ``C x_ref + sum_k c_k (x_k - x_ref)``, each
  ``c_k`` factored.  The removable singularity of a differential at equal input speeds
  then cancels exactly, and differences of nearly equal radii are taken directly.
* :func:`exact_integer_parts` -- a rational subexpression of integer-valued symbols
  (tooth numbers) that contains a sum is brought to one fraction ``N/D`` of integer
  polynomials, :class:`ExactRatio`, evaluated in exact integer arithmetic before the
  one division (``1 - z2 z4/(z1 z3)`` becomes ``(z1 z3 - z2 z4)/(z1 z3)``).
* :func:`unwrap_angles` -- ``atan(k tan u)`` (principal branch: jumps by pi at each
  odd multiple of pi/2) becomes the continuous ``u + atan2((k-1) sin 2u, (k+1) + (1-k) cos 2u)``
  when ``k > 0`` can be decided.
* :func:`cosine_sums` -- ``c (1 + e^2 - 2 e cos x)`` becomes ``c ((1 - e)^2 + 4 e sin^2(x/2))``,
  and ``a + b cos x`` with ``a``, ``b`` of opposite (equal) signs becomes
  ``(a + b) - 2 b sin^2(x/2)`` (``(a - b) + 2 b cos^2(x/2)``): sums of like-signed terms.
* :func:`difference_of_products` -- a two-term sum ``a b - c d`` of real inputs whose
  terms can cancel (``1 - r2 r4/(r1 r3)`` after bringing it to one fraction) becomes
  :class:`ProductDifference`, evaluated in double-double arithmetic: its relative error
  is about 2^-53 however close ``a b`` and ``c d`` are, so a denominator near its zero
  keeps its digits (the AA ratio ``r1 r3/(r1 r3 - r2 r4)`` near its pole).
* :func:`reduce_phases` (for the arguments named ``t`` unless told otherwise) --
  ``sin``/``cos``/``tan`` of ``c * x * y * t + b`` evaluate the product in double-double
  arithmetic and reduce it modulo 2 pi before the call (:class:`ReducedPhase`), so
  ``omega t`` of 10^6 turns keeps its digits; a phase ``c t`` with ``c`` any rational
  function of inputs (``omega_1 r1 r3/(r1 r3 + r2 r4) t``) becomes :class:`LongPhase`:
  where it exceeds 8 rad, ``c`` is evaluated in double-double from the inputs and the
  product reduced, so the rounding of ``c`` is not multiplied by ``t``.

The nodes the rules write (:class:`ExactRatio`, :class:`ProductDifference`, ...) are defined in
:mod:`symkin.numeric.nodes` and importable from here as well.

Signs are decided from SymPy's assumptions, helped by ``ranges`` ({symbol: (lo, hi)}):
an eccentricity declared in (0, 1) makes ``(1 + e)/(1 - e)`` positive.

    >>> import sympy as sp
    >>> z1, z2, z3, z4 = sp.symbols("z1:5", integer=True, positive=True)
    >>> stable_form(1 - z2*z4/(z1*z3))
    ExactRatio(z1*z3 - z2*z4, z1*z3)
    >>> e = sp.Symbol("e", positive=True); x = sp.Symbol("x", real=True)
    >>> stable_form(1 + e**2 - 2*e*cos(x))
    4*e*sin(x/2)**2 + (1 - e)**2
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import sympy as sp
from sympy import atan, atan2, cos, sin, tan

from symkin._util.budget import simplify_within
from symkin.numeric.nodes import (
    CompensatedSum,
    ExactRatio,
    Group,
    LongPhase,
    ProductDifference,
    ReducedPhase,
    _Deferred,
    compensated_sum,
    long_phase,
    plain_form,
)

__all__ = [
    "Group",
    "ExactRatio",
    "ReducedPhase",
    "LongPhase",
    "CompensatedSum",
    "ProductDifference",
    "stable_form",
    "relative_form",
    "exact_integer_parts",
    "unwrap_angles",
    "cosine_sums",
    "factor_differences",
    "difference_of_products",
    "reduce_phases",
    "RULE_NOTES",
    "plain_form",
]

#: CPU seconds each rewriting rule may take on one law (:func:`stable_form`): the same on a loaded machine.
RULE_SECONDS = 2.0

_MAX_OPS = 600  # rules that expand or factor skip larger expressions (cost grows fast)
_MAX_NODE_OPS = 60  # the cosine-sum rule looks at sums up to this size
_MAX_SIGN_OPS = 40  # signs are decided by factoring expressions up to this size


# --------------------------------------------------------------------------- signs
def _sign(expr: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None) -> int | None:
    """+1, -1, or None when the sign of ``expr`` cannot be decided."""
    for candidate in (expr, _in_ranges(expr, ranges)):
        if candidate is None:
            continue
        if candidate.is_positive:
            return 1
        if candidate.is_negative:
            return -1
        if candidate.free_symbols and sp.count_ops(candidate) <= _MAX_SIGN_OPS:
            try:
                f = sp.factor(sp.cancel(candidate))
            except Exception:  # pragma: no cover - sympy failures on odd inputs
                continue
            if f.is_positive:
                return 1
            if f.is_negative:
                return -1
    return None


def _in_ranges(expr: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None) -> sp.Expr | None:
    if not ranges:
        return None
    subs = {}
    for s, (lo, hi) in ranges.items():
        if s in expr.free_symbols:
            p = sp.Dummy("p", positive=True)
            lo, hi = sp.sympify(lo), sp.sympify(hi)
            subs[s] = (lo + hi * p) / (1 + p) if hi.is_finite else lo + p
    return expr.xreplace(subs) if subs else None


# --------------------------------------------------------------------------- rule 1
def relative_form(expr: sp.Expr) -> sp.Expr:
    """Write a law linear and homogeneous in some of its symbols, whose coefficients sum
    to a constant C, as ``C x_ref + sum_k c_k (x_k - x_ref)``.

    >>> w1, w4, r1, r2, r3 = sp.symbols("omega_1 omega_4 r_1 r_2 r_3", positive=True)
    >>> relative_form((w1*r1*r3 - w4*r2*(r1 - r2 + r3)) / ((r1 - r2)*(r3 - r2)))
    omega_4 - r_1*r_3*(omega_1 - omega_4)/((r_1 - r_2)*(r_2 - r_3))
    """
    if expr.is_Atom or sp.count_ops(expr) > _MAX_OPS or expr.has(ExactRatio, ReducedPhase):
        return expr
    if not _rational_function(expr):  # sin, sqrt, ... : not a law this rule is for (and degree() may expand them)
        return expr
    num, den = sp.fraction(sp.together(expr))
    linear = _linear_symbols(expr, num, den)
    if len(linear) < 2:
        return expr
    try:
        poly = sp.Poly(sp.expand(num), *linear)
    except sp.PolynomialError:
        return expr
    if not poly.is_homogeneous or poly.total_degree() != 1:
        return expr
    coeffs = {}
    for s in linear:
        mono = tuple(1 if t == s else 0 for t in linear)
        coeffs[s] = sp.cancel(poly.coeff_monomial(mono) / den)
    total = sp.cancel(sp.Add(*coeffs.values()))
    if not total.is_number:
        return expr
    ref = max(reversed(linear), key=lambda s: sp.count_ops(coeffs[s]))
    rest = [sp.factor(coeffs[s]) * (s - ref) for s in linear if s != ref and coeffs[s] != 0]
    return total * ref + sp.Add(*rest)


def _linear_symbols(expr: sp.Expr, num: sp.Expr, den: sp.Expr) -> list[sp.Symbol]:
    """The real symbols of ``expr`` (sorted by name) of degree 1 in the numerator ``num`` and
    absent from the denominator ``den``."""
    linear = []
    for s in sorted(expr.free_symbols, key=lambda s: s.name):
        if s.is_integer or s in den.free_symbols:
            continue
        try:
            if sp.degree(num, s) == 1:
                linear.append(s)
        except (sp.PolynomialError, sp.GeneratorsNeeded):
            continue
    return linear


def _rational_function(expr: sp.Expr) -> bool:
    """Built from symbols and numbers by + * / and integer powers only."""
    for node in sp.preorder_traversal(expr):
        if isinstance(node, sp.Function) or (node.is_Pow and not node.exp.is_Integer):
            return False
    return True


# --------------------------------------------------------------------------- rule 2
def _integer_rational(e: sp.Expr) -> bool:
    """A rational function with rational coefficients of integer-valued symbols only."""
    if not e.free_symbols or not all(s.is_integer for s in e.free_symbols):
        return False
    for node in sp.preorder_traversal(e):
        if node.is_Symbol or node.is_Rational:
            continue
        if node.is_Add or node.is_Mul:
            continue
        if node.is_Pow and node.exp.is_Integer:
            continue
        return False
    return True


def exact_integer_parts(expr: sp.Expr) -> sp.Expr:
    """Bring every rational part in integer symbols that contains a sum to ``ExactRatio(N, D)``.

    Terms of a sum are first grouped by their non-integer factor, so
    ``w - w z2 z4/(z1 z3)`` becomes ``w ExactRatio(z1 z3 - z2 z4, z1 z3)``.

    >>> z1, z2 = sp.symbols("z1 z2", integer=True, positive=True); w = sp.Symbol("w")
    >>> exact_integer_parts(w - w*z2/z1)
    w*ExactRatio(z1 - z2, z1)
    """
    if expr.is_Atom or isinstance(expr, (ExactRatio, ReducedPhase)):
        return expr
    if _integer_rational(expr):
        return _one_ratio(expr) if expr.has(sp.Add) else expr
    regrouped = _grouped_sum(expr) if expr.is_Add else _integer_product(expr) if expr.is_Mul else None
    if regrouped is not None:
        return regrouped
    args = [exact_integer_parts(a) for a in expr.args]
    if all(new is old for new, old in zip(args, expr.args)):
        return expr  # unchanged: do not rebuild (rebuilding re-evaluates, e.g. inside Group)
    return expr.func(*args)


def _one_ratio(expr: sp.Expr) -> sp.Expr:
    """A rational function of integer symbols as ``ExactRatio(N, D)``, ``N`` and ``D`` integer
    polynomials (D without a leading minus sign)."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    gens = sorted(expr.free_symbols, key=lambda s: s.name)
    _, pnum = sp.Poly(num, *gens).clear_denoms()
    cden, pden = sp.Poly(den, *gens).clear_denoms()
    cnum = sp.Poly(num, *gens).clear_denoms()[0]
    num_e, den_e = pnum.as_expr() * cden, pden.as_expr() * cnum
    if (den_e.is_Number and den_e < 0) or den_e.could_extract_minus_sign():
        num_e, den_e = -num_e, -den_e
    return ExactRatio(sp.expand(num_e), sp.expand(den_e))


def _grouped_sum(expr: sp.Add) -> sp.Expr | None:
    """A sum whose terms share non-integer factors, as a sum over those factors of exact
    integer parts (``w - w z2/z1`` as ``w ExactRatio(z1 - z2, z1)``); None where no two terms
    share one with integer parts of symbols."""
    groups: dict[sp.Expr, list[sp.Expr]] = {}
    for term in expr.args:
        ints: list[sp.Expr] = []
        rest: list[sp.Expr] = []
        for f in sp.Mul.make_args(term):
            (ints if (f.is_Rational or _integer_rational(f)) else rest).append(f)
        groups.setdefault(sp.Mul(*rest), []).append(sp.Mul(*ints))
    if len(groups) < len(expr.args) and any(len(v) > 1 and any(i.free_symbols for i in v) for v in groups.values()):
        return sp.Add(*(exact_integer_parts(sp.Add(*ints)) * exact_integer_parts(rest) for rest, ints in groups.items()))
    return None


def _integer_product(expr: sp.Mul) -> sp.Expr | None:
    """A product with several integer factors, one of them a sum, as one exact integer part
    times the rest; None otherwise."""
    ints = [f for f in expr.args if f.is_Rational or _integer_rational(f)]
    if len(ints) > 1 and any(f.has(sp.Add) for f in ints):
        rest = [exact_integer_parts(f) for f in expr.args if f not in ints]
        return exact_integer_parts(sp.Mul(*ints)) * sp.Mul(*rest)
    return None


# --------------------------------------------------------------------------- rule 3
def unwrap_angles(expr: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None) -> sp.Expr:
    """Replace ``atan(k tan u)`` (jumps by pi where tan u does) by its continuous branch.

    The continuous branch is ``u + atan2((k - 1) sin 2u, (k + 1) + (1 - k) cos 2u)``;
    it equals the principal value on (-pi/2, pi/2) and needs ``k > 0``.  A fraction
    ``k = P/Q`` with ``Q > 0`` is cleared from both atan2 arguments.

    >>> u = sp.Symbol("u", real=True); e = sp.Symbol("e", positive=True)
    >>> cosine_sums(unwrap_angles(sp.atan((1 + e)/(1 - e)*sp.tan(u)), {e: (0, 1)}), {e: (0, 1)})
    u + atan2(2*e*sin(2*u), 4*e*sin(u)**2 + Group(-2*(e - 1)))
    """

    def rewrite(node: sp.Expr) -> sp.Expr:
        if not isinstance(node, atan):
            return node
        arg = node.args[0]
        tans = [f for f in sp.Mul.make_args(arg) if isinstance(f, tan)]
        if len(tans) != 1:
            return node
        u = tans[0].args[0]
        k = sp.cancel(arg / tans[0])
        if k.has(u) or _sign(k, ranges) != 1:
            return node
        p, q = sp.fraction(sp.together(k))
        if _sign(q, ranges) != 1:
            p, q = -p, -q
            if _sign(q, ranges) != 1:
                return node
        y = sp.expand(p - q) * sin(2 * u)
        x = sp.expand(p + q) + sp.expand(q - p) * cos(2 * u)
        return u + atan2(y, x)

    return expr.replace(lambda n: isinstance(n, atan), rewrite)


# --------------------------------------------------------------------------- rule 4
def cosine_sums(expr: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None) -> sp.Expr:
    """Rewrite sums ``a + b cos x`` that cancel at cos x = +-1 as sums of like-signed terms.

    >>> e = sp.Symbol("e", positive=True); x = sp.Symbol("x", real=True)
    >>> cosine_sums(1 - e*cos(x), {e: (0, 1)})
    2*e*sin(x/2)**2 + Group(1 - e)
    """

    def rewrite(node: sp.Expr) -> sp.Expr:
        if not node.is_Add or sp.count_ops(node) > _MAX_NODE_OPS:
            return node
        cosines = [f for t in node.args for f in sp.Mul.make_args(t) if isinstance(f, cos)]
        for c in dict.fromkeys(cosines):
            k = node.coeff(c)
            rest = sp.expand(node - k * c)
            if k == 0 or rest.has(c) or k.has(c) or rest == 0:
                continue
            x = c.args[0]
            squares = _squares_form(k, rest, x, ranges)
            if squares is not None:
                return squares
            sr, sk = _sign(rest, ranges), _sign(k, ranges)
            if sr is None or sk is None:
                continue
            if sr != sk:  # cancels at cos x = 1
                return Group(sp.factor(rest + k)) - 2 * k * sin(x / 2) ** 2
            return Group(sp.factor(rest - k)) + 2 * k * cos(x / 2) ** 2  # cancels at cos x = -1
        return node

    return expr.replace(lambda n: n.is_Add and n.has(cos), rewrite)


def _squares_form(k: sp.Expr, rest: sp.Expr, x: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None) -> sp.Expr | None:
    """``rest + k cos x`` as ``c0 ((1 - e)^2 + 4 e sin^2(x/2))`` (or ``cos^2``) where it is
    ``c0 (1 + e^2 -+ 2 e cos x)`` for a positive symbol e; else None."""
    for e in sorted(k.free_symbols, key=lambda s: s.name):
        for sgn in (-1, 1):
            c0 = sp.cancel(sgn * k / (2 * e))
            if c0.has(e) or sp.expand(rest - c0 * (1 + e**2)) != 0 or _sign(e, ranges) != 1:
                continue
            tail = 4 * e * (sin(x / 2) ** 2 if sgn == -1 else cos(x / 2) ** 2)
            return c0 * ((1 - e) ** 2 + tail)
    return None


# --------------------------------------------------------------------------- rule 5
def factor_differences(expr: sp.Expr) -> sp.Expr:
    """Factor small polynomial sums of real symbols that split, such as ``1 - e^2`` into
    ``(1 - e)(1 + e)``: near e = 1 the difference ``1 - e`` is exact, ``1 - e^2`` is not.

    >>> e = sp.Symbol("e", positive=True)
    >>> factor_differences(1 - e**2)
    -(e - 1)*(e + 1)
    """

    def small(node: sp.Expr) -> bool:
        if not (
            node.is_Add
            and not node.has(sp.Function)
            and 0 < len(node.free_symbols) <= 3
            and not all(s.is_integer for s in node.free_symbols)
            and sp.count_ops(node) <= 30
            and node.is_polynomial(*node.free_symbols)
        ):
            return False
        # rational coefficients and a low degree only: factoring over a domain such as ZZ[E]
        # with a coefficient E**1000 (a value typed by a user) takes minutes and never helps
        poly = sp.Poly(node, *sorted(node.free_symbols, key=sp.default_sort_key))
        return (poly.domain.is_QQ or poly.domain.is_ZZ) and 2 <= poly.total_degree() <= 8

    def rewrite(node: sp.Expr) -> sp.Expr:
        f = sp.factor(node)
        parts = [p for p in sp.Mul.make_args(f) if not p.is_Number]
        return f if len(parts) >= 2 or (len(parts) == 1 and parts[0].is_Pow) else node

    return expr.replace(small, rewrite)


# --------------------------------------------------------------------------- rule 6
def _float_exact(c: sp.Expr) -> bool:
    """A rational that float64 holds exactly (numerator below 2^53, denominator a power of 2)."""
    return bool(c.is_Rational and c != 0 and abs(c.p) < 2**53 and c.q & (c.q - 1) == 0)


def _power_of_two(c: sp.Expr) -> bool:
    return bool(_float_exact(c) and abs(c.p) & (abs(c.p) - 1) == 0)


def _product_parts(term: sp.Expr) -> tuple[sp.Expr, sp.Expr] | None:
    """``(x, y)`` with ``x * y == term`` computed exactly by one error-free product, or None.

    Accepted: ``c``, ``c*u``, ``c*u*v`` (``u**2``) for symbols u, v and a float-exact c
    (a power of two when there are two symbols, so that ``c*u`` is exact)."""
    coeff, factors = term.as_coeff_mul()
    syms: list[sp.Expr] = []
    for f in factors:
        base, e = f.as_base_exp()
        if not (base.is_Symbol and e.is_Integer and e > 0):
            return None
        syms += [base] * int(e)
    if len(syms) > 2 or not _float_exact(coeff):
        return None
    if len(syms) == 2:
        return (coeff * syms[0], syms[1]) if _power_of_two(coeff) else None
    return coeff, (syms[0] if syms else sp.Integer(1))


def _monomial(term: sp.Expr) -> bool:
    coeff, factors = term.as_coeff_mul()
    return coeff.is_Rational and all(f.as_base_exp()[0].is_Symbol and f.as_base_exp()[1].is_Integer for f in factors)


def difference_of_products(expr: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None) -> sp.Expr:
    """Rewrite two-term sums that can cancel, ``a b - c d`` of real symbols, as
    :class:`ProductDifference` (double-double arithmetic at run time).

    A sum of two monomials with denominators, such as ``1 - r2 r4/(r1 r3)``, is first
    brought to one fraction.  Sums of like-signed terms (no cancellation), sums that one
    float operation already rounds correctly (``a - b``, ``2 a - b``) and sums of integer
    symbols only (evaluated exactly, see :func:`exact_integer_parts`) are left alone.

    >>> r1, r2, r3, r4 = sp.symbols("r1:5", positive=True)
    >>> difference_of_products(r1*r3/(r1*r3 - r2*r4))
    r1*r3/ProductDifference(r1, r3, r2, r4)
    >>> difference_of_products(1 - r2*r4/(r1*r3))
    ProductDifference(r1, r3, r2, r4)/(r1*r3)
    >>> difference_of_products(r1*r3 + r2*r4)   # like-signed: nothing cancels
    r1*r3 + r2*r4
    """

    return expr.replace(lambda n: n.is_Add and len(n.args) == 2, lambda n: _difference_form(n, ranges))


def _same_sign(t1: sp.Expr, t2: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None) -> bool:
    s1 = _sign(t1, ranges)
    return s1 is not None and s1 == _sign(t2, ranges)


def _exact_sum(t1: sp.Expr, t2: sp.Expr) -> bool:
    """One float operation gives the sum correctly rounded (``a - b``, ``2 a - 1``)."""
    parts = [_product_parts(t) for t in (t1, t2)]
    return all((p is not None and p[1] == 1) or (p is not None and p[0].is_Number and _power_of_two(p[0])) for p in parts)


def _direct_difference(t1: sp.Expr, t2: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None) -> sp.Expr | None:
    """``t1 + t2`` as a :class:`ProductDifference` where both are products of one error-free
    product each and they can cancel; else None."""
    if t1.could_extract_minus_sign() and not t2.could_extract_minus_sign():
        t1, t2 = t2, t1  # the positive term first: ProductDifference(a, b, c, d) reads a b - c d
    p1, p2 = _product_parts(t1), _product_parts(t2)
    if p1 is None or p2 is None or _exact_sum(t1, t2) or _same_sign(t1, t2, ranges):
        return None
    (a, b), (c, d) = p1, p2
    return ProductDifference(a, b, -c, d)  # t1 + t2 = a b - (-c) d


def _difference_form(node: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None) -> sp.Expr:
    """A two-term sum that can cancel as a :class:`ProductDifference`, directly or once brought
    to one fraction; other nodes as they are."""
    if not node.is_Add or len(node.args) != 2 or not node.free_symbols:
        return node
    if all(s.is_integer for s in node.free_symbols):
        return node
    t1, t2 = node.args
    new = _direct_difference(t1, t2, ranges)
    if new is not None or _exact_sum(t1, t2):
        return node if new is None else new
    if not (_monomial(t1) and _monomial(t2)) or _same_sign(t1, t2, ranges):
        return node
    num, den = sp.fraction(sp.together(node))
    num = sp.expand(num)
    if not num.is_Add or len(num.args) != 2 or not _monomial(den):
        return node
    if _exact_sum(*num.args):  # 1 - x/y as (y - x)/y: one correctly rounded difference
        return num / den
    t1, t2 = num.args
    new = _direct_difference(t1, t2, ranges)
    return node if new is None else new / den


# --------------------------------------------------------------------------- rule 0
#: A polynomial of at most this many terms, each of at most this many factors, is summed
#: in double-double (:class:`CompensatedSum`); larger ones are left to the other rules.
_MAX_TERMS, _MAX_FACTORS = 8, 4


def compensated_sums(expr: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None) -> sp.Expr:
    """Write a rational function of real (not integer) inputs whose numerator or denominator
    is a sum of products that can cancel as a ratio of :class:`CompensatedSum` (a numerator
    given as products of sums is expanded first; a denominator is taken as given; ``a b - c d``
    is left to :func:`difference_of_products`).  Each is then
    evaluated within a few units in the last place of its exact value, so the law too:
    ``(w1 r1 r3 - w4 r2 r4)/(r1 r3 - r2 r4)`` within about 3 units at any point, where the
    plain form (and the relative form) lose digits wherever the result is small.

    >>> w1, w4, r1, r2, r3, r4 = sp.symbols("omega_1 omega_4 r_1 r_2 r_3 r_4", positive=True)
    >>> law = compensated_sums((w1*r1*r3 - w4*r2*r4)/(r1*r3 - r2*r4))
    >>> [type(n).__name__ for n in sp.preorder_traversal(law) if isinstance(n, CompensatedSum)]
    ['CompensatedSum']
    >>> compensated_sums(r1*r3 + r2*r4)   # like-signed: nothing cancels
    r_1*r_3 + r_2*r_4
    """
    if expr.is_Atom or sp.count_ops(expr) > _MAX_OPS or not _rational_function(expr) or expr.has(_Deferred, Group):
        return expr
    if any(s.is_integer for s in expr.free_symbols):
        return expr  # tooth numbers: exact integer parts (rule 5)
    num, den = sp.fraction(sp.together(expr))
    new_num, new_den = _compensated(sp.expand(num), ranges), _compensated(den, ranges)
    if new_num is None and new_den is None:
        return expr
    return (new_num if new_num is not None else num) / (new_den if new_den is not None else den)


def _compensated(poly: sp.Expr, ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None) -> sp.Expr | None:
    """``poly`` as a :class:`CompensatedSum` when it is a sum of 2 to 8 terms, each a float-exact
    number times at most four inputs, that can cancel (not all of one sign, not one float
    operation); else None."""
    if not poly.is_Add or len(poly.args) > _MAX_TERMS:
        return None
    for term in poly.args:
        coeff, factors = term.as_coeff_mul()
        if not (_float_exact(coeff) and all(f.as_base_exp()[0].is_Symbol and f.as_base_exp()[1].is_Integer
                                            and f.as_base_exp()[1] > 0 for f in factors)):
            return None
        if sum(int(f.as_base_exp()[1]) for f in factors) > _MAX_FACTORS:
            return None
    signs = {_sign(t, ranges) for t in poly.args}
    if len(signs) == 1 and None not in signs:
        return None  # like-signed: no cancellation
    if len(poly.args) == 2 and (_exact_sum(*poly.args) or _direct_difference(poly.args[0], poly.args[1], ranges) is not None):
        return None  # a - b: one rounding already; a b - c d: difference_of_products
    return compensated_sum(poly)


# --------------------------------------------------------------------------- rule 7
def reduce_phases(expr: sp.Expr, times: Iterable[sp.Symbol]) -> sp.Expr:
    """Reduce the phase of ``sin``, ``cos``, ``tan`` whose argument is ``c x y t + b``.

    ``c`` is a rational constant, at most three symbol factors, ``t`` one of ``times``;
    the product is evaluated in double-double arithmetic and reduced modulo 2 pi.  Other
    terms ``c t`` with ``c`` a rational function of inputs with exact coefficients
    (rationals, and numbers such as ``4 pi/5`` or ``sqrt(2)``, held in double-double), or
    an exact number alone, become :class:`LongPhase` (``c`` in double-double where the
    phase is long).

    >>> t, w = sp.symbols("t omega", real=True)
    >>> reduce_phases(sp.sin(w*t/2 + 1), [t])
    sin(ReducedPhase(1, 2, omega, t) + 1)
    """
    times = set(times)

    def rewrite(node: sp.Expr) -> sp.Expr:
        arg = node.args[0]
        if not (arg.free_symbols & times):
            return node
        new_terms = []
        for term in sp.Add.make_args(arg):
            if not (term.free_symbols & times):
                new_terms.append(term)
                continue
            coeff, factors = term.as_coeff_mul()
            if coeff.is_Rational and len(factors) <= 3 and all(f.is_Symbol for f in factors):
                ratio = _float_exact_ratio(coeff)
                new_terms.append(ReducedPhase(*ratio, *factors) if ratio else term)
                continue
            long = _long_phase(term, times)
            if long is None:
                return node
            new_terms.append(long)
        return node.func(sp.Add(*new_terms))

    return expr.replace(lambda n: isinstance(n, (sin, cos, tan)), rewrite)


#: The largest integer every float holds exactly next to its neighbours (p and q of a reduced phase are floats).
_EXACT_FLOAT_INTEGER = 2**53


def _float_exact_ratio(coeff: sp.Rational) -> tuple[int, int] | None:
    """``coeff`` as integers ``(p, q)`` that floats hold exactly (the reduced phase computes in
    floats): itself when both are below 2^53, else the correctly rounded float of ``coeff`` as a
    ratio (an integer below 2^53 over a power of 2, or a whole float over 1); None where that
    power of 2 has no float (a coefficient below about 1e-292: its phase needs no reduction).

    >>> _float_exact_ratio(sp.Rational(3, 7)), _float_exact_ratio(1 - sp.Rational(1, 10**300))
    ((3, 7), (1, 1))
    """
    p, q = int(coeff.p), int(coeff.q)
    if abs(p) <= _EXACT_FLOAT_INTEGER and q <= _EXACT_FLOAT_INTEGER:
        return p, q
    m, d = (p / q).as_integer_ratio()  # p / q: Python's true division of integers is correctly rounded
    return (m, d) if d.bit_length() <= 1000 else None


def _long_phase(term: sp.Expr, times: set[sp.Symbol]) -> sp.Expr | None:
    """``term`` as :class:`LongPhase` ``c t`` when it is one time symbol times a rational
    function ``c`` of other symbols with rational coefficients, else None."""
    ts = term.free_symbols & times
    if len(ts) != 1:
        return None
    (t,) = ts
    coeff = term / t
    if coeff.has(t) or not _rational_in_constants(plain_form(coeff)):
        return None
    return long_phase(coeff, t)


def _rational_in_constants(expr: sp.Expr) -> bool:
    """A rational function of symbols whose coefficients are exact numbers (rationals, pi,
    sqrt(2), ...: each held in double-double to 2^-106); a Float is not exact, so not one."""
    if expr.has(sp.Float):
        return False
    stack = [expr]
    while stack:
        node = stack.pop()
        if node.is_number or node.is_Symbol:
            continue
        if isinstance(node, sp.Function) or (node.is_Pow and not node.exp.is_Integer):
            return False
        stack.extend(node.args)
    return True


# --------------------------------------------------------------------------- all
#: What each rule does, as stated in a compiled function's docstring.
RULE_NOTES = {
    "compensated_sums": "sums of products that can cancel (w1 r1 r3 - w4 r2 r4) in double-double arithmetic, "
    "rounded once (within a few units in the last place of their exact value)",
    "relative_form": "linear law written relative to one input (removable singularity cancelled)",
    "unwrap_angles": "atan(k tan u) unwrapped to its continuous branch",
    "cosine_sums": "cosine sums written as sums of like-signed terms",
    "factor_differences": "small polynomial differences factored (1 - e^2 as (1 - e)(1 + e))",
    "exact_integer_parts": "integer parts evaluated exactly before one division",
    "difference_of_products": "differences of two products of inputs (a b - c d) in double-double arithmetic "
    "(relative error about 2^-53 however close a b and c d are)",
    "reduce_phases": "phases reduced mod 2 pi in double-double (error ~2^-52 pi at any number of turns; "
    "the plain product loses |phase| 2^-53 rad)",
}


def stable_form(
    expr: sp.Expr,
    *,
    ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None,
    reduce_phase: Iterable[sp.Symbol] = (),
    applied: list[str] | None = None,
) -> sp.Expr:
    """Apply every rule: relative form, unwrapped angles, cosine sums, factored
    differences, differences of products, exact integer parts, and (when ``reduce_phase`` names time symbols)
    reduced phases.  The names of the rules that changed something are appended to
    ``applied`` (see :data:`RULE_NOTES`).

    >>> w1, w4 = sp.symbols("omega_1 omega_4", real=True)
    >>> z1, z2, z3, z4 = sp.symbols("z1:5", integer=True, positive=True)
    >>> done = []
    >>> stable_form((w1*z1*z3 + w4*z2*z4)/(z1*z3 + z2*z4), applied=done)
    omega_4 + (omega_1 - omega_4)*ExactRatio(z1*z3, z1*z3 + z2*z4)
    >>> done
    ['relative_form', 'exact_integer_parts']
    """
    expr = sp.sympify(expr)
    # exp(-690) (a user's number) is E**-690 to SymPy's polynomials, a polynomial of degree 690 in E:
    # factoring it takes minutes.  The rules see such constants as positive symbols, put back after.
    opaque = {node: sp.Dummy(f"c{i}", positive=True)
              for i, node in enumerate(sorted((n for n in expr.atoms(sp.exp) if n.is_number), key=sp.default_sort_key))}
    expr = expr.xreplace(opaque)
    times = tuple(reduce_phase)
    rules = [
        ("compensated_sums", lambda e: compensated_sums(e, ranges)),
        ("relative_form", relative_form),
        ("unwrap_angles", lambda e: unwrap_angles(e, ranges)),
        ("cosine_sums", lambda e: cosine_sums(e, ranges)),
        ("factor_differences", factor_differences),
        ("difference_of_products", lambda e: difference_of_products(e, ranges)),
        ("exact_integer_parts", exact_integer_parts),
    ]
    if times:
        rules.append(("reduce_phases", lambda e: reduce_phases(e, times)))
    for name, rule in rules:
        # a rule factors and expands: its time follows the law's size and its numbers, so each has a
        # budget; past it the law keeps that rule's form unrewritten (exact, only less stable in floats)
        # with a note
        new = simplify_within(expr, RULE_SECONDS, None, simplifier=rule, what=f"the stable form ({name}) of a law")
        if new != expr and applied is not None:
            applied.append(name)
        expr = new
    return expr.xreplace({d: c for c, d in opaque.items()}) if opaque else expr
