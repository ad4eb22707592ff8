"""Run-time helpers of compiled laws: exact integer ratios, reduced phases, and
differences of products in double-double arithmetic.

They are written with plain arithmetic so that one source serves NumPy arrays and, once
jitted, Numba's scalar loops.

    >>> import numpy as np
    >>> exact_ratio(np.array([1, 1, 0]), np.array([3, 0, 0]))
    array([0.33333333,        inf,        nan])
    >>> # the float nearest 2 pi is 2.449e-16 short of 2 pi; 10^6 turns of it, exactly:
    >>> print(f"{float(reduced_phase(1, 1, 2 * np.pi, 10**6, 1.0)):.4g}")
    -2.449e-10
    >>> # 0.7*0.3 - 0.1*2.1 of the binary inputs is -4.163e-17; plain float64 says -2.776e-17
    >>> print(f"{float(product_difference(0.7, 0.3, 0.1, 2.1)):.4g}", f"{0.7 * 0.3 - 0.1 * 2.1:.4g}")
    -4.163e-17 -2.776e-17
"""

from __future__ import annotations

import functools
import math
from typing import Any

import mpmath
import numpy as np

__all__ = ["exact_ratio", "reduced_phase", "product_difference", "long_phase", "dd_source", "sum_source", "TWO_PI_PARTS", "NAMESPACE"]

_SPLIT = 134217729.0  # 2^27 + 1, Dekker's splitter for float64


def _two_pi_parts() -> tuple[float, float, float, float]:
    with mpmath.workdps(60):
        two_pi = 2 * mpmath.pi
        c1 = float(mpmath.nint(two_pi * 2**23)) / 2**23  # 26 significant bits: k * c1 exact for k < 2^27
        c2 = float(mpmath.nint((two_pi - c1) * 2**49)) / 2**49
        c3 = float(two_pi - c1 - c2)
        return c1, c2, c3, float(1 / two_pi)


#: 2 pi = C1 + C2 + C3 (Cody-Waite parts) and 1 / (2 pi).
TWO_PI_PARTS = _two_pi_parts()
_C1, _C2, _C3, _INV_2PI = TWO_PI_PARTS


def _two_prod(a: Any, b: Any) -> tuple[Any, Any]:
    p = a * b
    c = _SPLIT * a
    ah = c - (c - a)
    al = a - ah
    c = _SPLIT * b
    bh = c - (c - b)
    bl = b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def _two_sum(a: Any, b: Any) -> tuple[Any, Any]:
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


def _product_difference_core(a: Any, b: Any, c: Any, d: Any) -> Any:
    """``a*b - c*d``: each product split exactly (Dekker), the parts added in double-double
    arithmetic (Joldes, Muller & Popescu 2017, AccurateDWPlusDW: relative error at most
    3 2^-106 before the final rounding to float64)."""
    p, e = _two_prod(a, b)
    q, f = _two_prod(c, d)
    sh, sl = _two_sum(p, -q)
    th, tl = _two_sum(e, -f)
    sl = sl + th
    vh = sh + sl  # Fast2Sum(sh, sl)
    vl = sl - (vh - sh)
    return vh + (tl + vl)


#: A point whose ``g = a b / (a b - c d)`` (plain difference) lies in this interval is certified
#: far from cancellation: ``g`` in [-1/2, 3/2] is ``2 |a b - c d| >= |a b + c d|`` (the ratio
#: ``c d / a b`` outside (1/3, 3)), where the plain difference is within 3 units of 2^-53; the
#: bounds are pulled in by 1/1000 so that the rounding of ``g`` cannot move a point across.
_CERTIFIED = _LO, _HI = (-0.499, 1.499)
#: Integers up to this size, and their sums and products while they stay below it, are exact in float64.
EXACT_FLOATS = float(2**53)


def _product_ratio(a: Any, b: Any, c: Any, d: Any) -> tuple[Any, Any, Any]:
    """``(p, diff, g)``: ``p = a b``, ``diff = a b - c d`` within 3 units of 2^-53 and
    ``g = p / diff``, for arrays (or 0-d arrays), inside ``np.errstate(all="ignore")``.

    The plain ``diff = p - q`` is kept where ``g`` is certified (:data:`_CERTIFIED`); two
    reductions of ``g`` (min and max, no temporary) decide that for the whole call, and only
    when they do not are the points outside the interval (or nan) found and redone in
    double-double arithmetic (:func:`_product_difference_core`)."""
    p = a * b
    diff = p - c * d
    g = p / diff
    lo, hi = _CERTIFIED
    if g.size == 0 or (lo <= np.minimum.reduce(g, axis=None) and np.maximum.reduce(g, axis=None) <= hi):  # nan: False
        return p, diff, g
    if g.ndim == 0:
        exact = _product_difference_core(a, b, c, d)
        if exact == exact:
            diff = exact
            g = p / diff
        return p, diff, g
    near = (g >= lo) & (g <= hi)
    np.logical_not(near, out=near)
    shape = g.shape
    parts = [x[near] if type(x) is np.ndarray and x.shape == shape else np.broadcast_to(x, shape)[near] for x in (a, b, c, d)]
    exact = _product_difference_core(*parts)
    keep = np.isnan(exact)
    if diff.shape != shape:
        diff = np.broadcast_to(diff, shape).copy()
    if p.shape != shape:
        p = np.broadcast_to(p, shape).copy()
    diff[near] = np.where(keep, diff[near], exact)
    g[near] = p[near] / diff[near]
    return p, diff, g


def _arrays(a: Any, b: Any, c: Any, d: Any) -> tuple[Any, Any, Any, Any]:
    f = np.float64
    if type(a) is not np.ndarray or type(b) is not np.ndarray or type(c) is not np.ndarray or type(d) is not np.ndarray:
        return tuple(np.asarray(x, f) for x in (a, b, c, d))  # type: ignore[return-value]
    return a, b, c, d


def product_difference(a: Any, b: Any, c: Any, d: Any) -> Any:
    """``a*b - c*d`` of float64 values within 3 units of 2^-53 of the exact value
    (relative), however much the two products cancel.

    The plain ``p - q`` (``p = a*b``, ``q = c*d``) is within ``2^-53 (|p| + |q| + |p - q|)``
    of the exact value: 3 units where the products cancel to no less than half their
    sum (``2 |p - q| >= |p + q|``, the common case).  That is decided from ``g = p/(p - q)``
    (in [-1/2, 3/2] exactly there), for a whole array by its minimum and maximum; only the
    points where the products cancel more are redone in double-double arithmetic
    (:func:`_product_difference_core`, about 50 operations: within one unit), so the result
    keeps its digits at any distance from a pole and is zero exactly where ``a b = c d``.  The
    double-double is exact while the inputs are below 2^995 and the products above 2^-969 in
    magnitude (or zero); where its splitting overflows the plain difference is kept.
    """
    with np.errstate(all="ignore"):
        return _product_ratio(*_arrays(a, b, c, d))[1]


def _product_difference_quiet(a: Any, b: Any, c: Any, d: Any) -> Any:
    """:func:`product_difference` for generated code (inside ``np.errstate(all="ignore")``)."""
    return _product_ratio(*_arrays(a, b, c, d))[1]


def _product_ratio_quiet(a: Any, b: Any, c: Any, d: Any) -> Any:
    """``a b / (a b - c d)`` with the difference of :func:`product_difference` (the ``g`` it
    certifies the plain difference by), for generated code inside ``np.errstate(all="ignore")``."""
    return _product_ratio(*_arrays(a, b, c, d))[2]


def product_difference_scalar(a: float, b: float, c: float, d: float) -> float:
    """:func:`product_difference` of Python floats (the scalar path of a compiled law)."""
    p = a * b
    r = p - c * d
    if r == 0 or not (_LO <= p / r <= _HI):  # not certified (see _CERTIFIED): double-double
        exact = _product_difference_core(a, b, c, d)
        if exact == exact:
            return exact
    return r


def _product_ratio_scalar(a: float, b: float, c: float, d: float) -> float:
    """``a b / (a b - c d)`` of Python floats, as the array code computes it."""
    return (a * b) / product_difference_scalar(a, b, c, d)


def product_difference_f32(a: Any, b: Any, c: Any, d: Any) -> Any:
    """:func:`product_difference` of float32 values: their products are exact in float64,
    so one float64 subtraction and one rounding to float32 keep every float32 digit."""
    f = np.float64
    return np.asarray(np.asarray(a, f) * np.asarray(b, f) - np.asarray(c, f) * np.asarray(d, f), dtype=np.float32)


def _reduced_phase_core(p: Any, q: Any, x1: Any, x2: Any, x3: Any) -> Any:
    h, lo = _two_prod(x1, x2)
    h2, e2 = _two_prod(h, x3)
    lo = lo * x3 + e2
    h = h2
    h2, e2 = _two_prod(h, p)
    lo = lo * p + e2
    h = h2
    qh = h / q
    ph, pl = _two_prod(qh, q)
    ql = (((h - ph) - pl) + lo) / q
    h = qh + ql
    lo = ql - (h - qh)
    k = np.floor(h * _INV_2PI + 0.5)
    return (((h - k * _C1) - k * _C2) - k * _C3) + lo


def reduced_phase(p: int, q: int, x1: Any, x2: Any, x3: Any) -> Any:
    """``p/q x1 x2 x3`` modulo 2 pi, in [-pi, pi], from double-double arithmetic.

    The error is about 2^-52 pi for any number of turns below 2^27 (the plain product
    loses ``|p/q x1 x2 x3| 2^-53`` radians).
    """
    f = np.float64
    return _reduced_phase_core(f(p), f(q), np.asarray(x1, f), np.asarray(x2, f), np.asarray(x3, f))


def _python_ratio(a: Any, b: Any) -> float:
    try:
        return a / b  # exact integers: Python's true division is correctly rounded
    except ZeroDivisionError:
        return math.copysign(math.inf, a) if a else math.nan


_ratio_ufunc = np.frompyfunc(_python_ratio, 2, 1)


def exact_ratio(num: Any, den: Any) -> Any:
    """``num / den`` of exact integers (int64 or Python integers) as float64; inf or nan
    at a zero denominator."""
    num, den = np.asarray(num), np.asarray(den)
    if num.dtype == object or den.dtype == object:
        return np.asarray(_ratio_ufunc(num, den), dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.true_divide(num, den)


def _exact_ratio_quiet(num: Any, den: Any) -> Any:
    """:func:`exact_ratio` for generated code, which runs inside ``np.errstate(all="ignore")``."""
    if type(num) is np.ndarray and type(den) is np.ndarray and num.dtype != object and den.dtype != object:
        return np.true_divide(num, den)
    return exact_ratio(num, den)


def exact_ratio_f32(num: Any, den: Any) -> Any:
    """:func:`exact_ratio` rounded to float32."""
    return np.asarray(exact_ratio(num, den), dtype=np.float32)


def reduced_phase_f32(p: int, q: int, x1: Any, x2: Any, x3: Any) -> Any:
    """:func:`reduced_phase` rounded to float32."""
    return np.asarray(reduced_phase(p, q, x1, x2, x3), dtype=np.float32)


def _exact_ratio_scalar(num: int, den: int) -> float:
    return num / den  # Python integers: correctly rounded; a zero denominator raises (the array path reports it)


def _reduced_phase_scalar(p: int, q: int, x1: float, x2: float, x3: float) -> float:
    return float(_reduced_phase_core(float(p), float(q), float(x1), float(x2), float(x3)))


#: Names the generated scalar code (one point, Python floats) calls.
SCALAR_NAMESPACE = {
    "_symkin_exact_ratio": _exact_ratio_scalar, "_symkin_reduced_phase": _reduced_phase_scalar,
    "_symkin_product_difference": product_difference_scalar, "_symkin_product_ratio": _product_ratio_scalar,
}

class _ElementwiseMath:
    """The ``math`` module applied element by element: SymPy's NumPy printer writes functions
    NumPy lacks (``erf``, ``gamma``, ...) as ``math.<name>``, which takes one number only.

    >>> _ElementwiseMath().erf(np.array([0.0, 1.0])).round(6).tolist()
    [0.0, 0.842701]
    """

    def __getattr__(self, name: str) -> Any:
        fn = np.vectorize(getattr(math, name), otypes=[np.float64])
        setattr(self, name, fn)  # found as an attribute from now on
        return fn


#: What the generated NumPy code names besides ``numpy`` (SymPy's printer writes Max and Min
#: as ``functools.reduce(numpy.maximum, ...)``).
_MODULES = {"functools": functools, "math": _ElementwiseMath()}

#: Names the generated NumPy code calls, by precision.
NAMESPACE = {
    "float64": {
        "_symkin_exact_ratio": _exact_ratio_quiet, "_symkin_reduced_phase": reduced_phase,
        "_symkin_product_difference": _product_difference_quiet, "_symkin_product_ratio": _product_ratio_quiet,
        **_MODULES,
    },
    "float32": {
        "_symkin_exact_ratio": exact_ratio_f32, "_symkin_reduced_phase": reduced_phase_f32,
        "_symkin_product_difference": product_difference_f32, **_MODULES,
    },
}


@functools.cache
def numba_namespace(precision: str) -> dict[str, Any]:
    """The same helpers, jitted for Numba scalar loops (once per process and precision:
    the kernels cached on disk find the same helpers)."""
    import numba

    two_prod = numba.njit(inline="always")(_two_prod)
    dtype = np.float32 if precision == "float32" else np.float64
    if precision == "float32":
        difference, plain_difference = _jit_differences_f32(numba, dtype)
    else:
        difference, plain_difference = _jit_differences(numba, two_prod)
    return {"_symkin_exact_ratio": _jit_ratio(numba, dtype), "_symkin_reduced_phase": _jit_phase(numba, two_prod, dtype),
            "_symkin_product_difference": difference, "_symkin_plain_difference": plain_difference,
            **_numba_dd_helpers(numba)}


def _jit_phase(numba: Any, two_prod: Any, dtype: Any) -> Any:
    """:func:`_reduced_phase_core` for Numba's scalar loops, rounded to ``dtype``."""

    @numba.njit(inline="always")
    def phase(p, q, x1, x2, x3):  # pragma: no cover - compiled
        h, lo = two_prod(np.float64(x1), np.float64(x2))
        h2, e2 = two_prod(h, np.float64(x3))
        lo = lo * np.float64(x3) + e2
        h = h2
        h2, e2 = two_prod(h, np.float64(p))
        lo = lo * np.float64(p) + e2
        h = h2
        qh = h / q
        ph, pl = two_prod(qh, np.float64(q))
        ql = (((h - ph) - pl) + lo) / q
        h = qh + ql
        lo = ql - (h - qh)
        k = np.floor(h * _INV_2PI + 0.5)
        return dtype((((h - k * _C1) - k * _C2) - k * _C3) + lo)

    return phase


def _jit_ratio(numba: Any, dtype: Any) -> Any:
    """An exact ratio's division for Numba's scalar loops."""

    @numba.njit(inline="always")
    def ratio(num, den, bound_num, bound_den):  # pragma: no cover - compiled
        """``num/den`` of integer polynomials in int64 (a float64 kernel computes them in float64
        where a bound of every partial sum is below 2^53, symkin.numeric.kernel)."""
        if bound_num > 4.6e18 or bound_den > 4.6e18:  # int64 could overflow: nan, redone with Python integers
            return dtype(np.nan)
        return dtype(num / den)

    return ratio


def _jit_differences_f32(numba: Any, dtype: Any) -> tuple[Any, Any]:
    """``a b - c d`` of float32 values for Numba's scalar loops (the products exact in float64),
    and the same as ``(difference, True)``: always certified."""

    @numba.njit(inline="always")
    def difference(a, b, c, d):  # pragma: no cover - compiled
        return dtype(np.float64(a) * np.float64(b) - np.float64(c) * np.float64(d))

    @numba.njit(inline="always")
    def plain_difference(a, b, c, d):  # pragma: no cover - compiled
        return difference(a, b, c, d), True

    return difference, plain_difference


def _jit_differences(numba: Any, two_prod: Any) -> tuple[Any, Any]:
    """:func:`product_difference_scalar` for Numba's scalar loops, and its plain difference
    with the certification test (no branch, for the loops that vectorise)."""
    core = _jit_product_difference(numba, two_prod)

    @numba.njit(inline="always")
    def plain_difference(a, b, c, d):  # pragma: no cover - compiled
        """``(a b - c d, certified)``: the plain difference, and whether it is within 3 units
        (see product_difference); no branch, so that a loop of it vectorises."""
        a, b, c, d = np.float64(a), np.float64(b), np.float64(c), np.float64(d)
        p = a * b
        r = p - c * d
        return r, r != 0 and _LO <= p / r <= _HI

    @numba.njit(inline="always")
    def difference(a, b, c, d):  # pragma: no cover - compiled
        r, certified = plain_difference(a, b, c, d)
        if not certified:  # the products may cancel: double-double (see product_difference)
            e = core(np.float64(a), np.float64(b), np.float64(c), np.float64(d))
            if e == e:  # else the splitting overflowed: the plain form
                r = e
        return r

    return difference, plain_difference


def _numba_dd_helpers(numba: Any) -> dict[str, Any]:
    """The double-double helpers of the generated phase coefficients, jitted (same source)."""
    import inspect

    ns: dict[str, Any] = {"Any": Any, "np": np, "_INV_2PI": _INV_2PI, "_C1": _C1, "_C2": _C2, "_C3": _C3, "_SPLIT": _SPLIT}
    for fn in (_two_prod, _two_sum, _fast_two_sum, _dd_add, _dd_mul, _dd_div, _dd_reduce, _dd_reduce_pair):
        exec(compile(inspect.getsource(fn), f"<symkin {fn.__name__}>", "exec"), ns)
        ns[fn.__name__] = numba.njit(inline="always")(ns[fn.__name__])
    out = {name: ns[name] for name in DD_HELPERS}
    out["_dd_reduce"] = ns["_dd_reduce"]  # a kernel's long phase from its kept coefficient
    out["_f64"] = np.float64
    out["_njit_inline"] = numba.njit(inline="always")
    return out


def _jit_product_difference(numba: Any, two_prod: Any) -> Any:
    """:func:`_product_difference_core` for Numba's scalar loops (same operations)."""

    @numba.njit(inline="always")
    def two_sum(a, b):  # pragma: no cover - compiled
        s = a + b
        bb = s - a
        return s, (a - (s - bb)) + (b - bb)

    @numba.njit(inline="always")
    def core(a, b, c, d):  # pragma: no cover - compiled
        p, e = two_prod(a, b)
        q, f = two_prod(c, d)
        sh, sl = two_sum(p, -q)
        th, tl = two_sum(e, -f)
        sl = sl + th
        vh = sh + sl
        vl = sl - (vh - sh)
        return vh + (tl + vl)

    return core


# --------------------------------------------------------------------------- long phases
#: A phase ``c t`` of at most this many radians is used as the plain float product; beyond it
#: the points are redone with ``c`` in double-double and the product reduced mod 2 pi (the
#: plain product loses about ``|c t| 2^-53`` times the condition of ``c``: below 4e-15 rad here).
LONG_PHASE = 8.0


def _fast_two_sum(a: Any, b: Any) -> tuple[Any, Any]:
    s = a + b
    return s, b - (s - a)


def _dd_add(ah: Any, al: Any, bh: Any, bl: Any) -> tuple[Any, Any]:
    """Double-double sum (AccurateDWPlusDW of Joldes, Muller & Popescu 2017)."""
    sh, sl = _two_sum(ah, bh)
    th, tl = _two_sum(al, bl)
    sl = sl + th
    vh, vl = _fast_two_sum(sh, sl)
    vl = vl + tl
    return _fast_two_sum(vh, vl)


def _dd_mul(ah: Any, al: Any, bh: Any, bl: Any) -> tuple[Any, Any]:
    """Double-double product (DWTimesDW1: relative error below 7 2^-106)."""
    p, e = _two_prod(ah, bh)
    e = e + (ah * bl + al * bh)
    return _fast_two_sum(p, e)


def _dd_div(ah: Any, al: Any, bh: Any, bl: Any) -> tuple[Any, Any]:
    """Double-double quotient (one correction step: relative error about 2^-100)."""
    q1 = ah / bh
    p, e = _dd_mul(q1, 0.0, bh, bl)
    rh, rl = _dd_add(ah, al, -p, -e)
    q2 = (rh + rl) / bh
    return _fast_two_sum(q1, q2)


def _dd_reduce(ch: Any, cl: Any, t: Any) -> Any:
    """``(ch + cl) t`` modulo 2 pi, in [-pi, pi], from the double-double ``c`` and float ``t``
    (exact reduction while the phase is below 2^27 turns)."""
    h, e = _two_prod(ch, t)
    e = e + cl * t
    h, e = _fast_two_sum(h, e)
    k = np.floor(h * _INV_2PI + 0.5)
    return (((h - k * _C1) - k * _C2) - k * _C3) + e


def _dd_reduce_pair(c: Any, t: Any) -> Any:
    """:func:`_dd_reduce` of a coefficient given as the pair ``(ch, cl)``."""
    return _dd_reduce(c[0], c[1], t)


#: The double-double helpers a generated phase coefficient calls (see :func:`dd_source`).
DD_HELPERS = {"_dd_add": _dd_add, "_dd_mul": _dd_mul, "_dd_div": _dd_div, "_dd_reduce_pair": _dd_reduce_pair}


def _two_pi_dd() -> tuple[float, float]:
    with mpmath.workdps(60):
        hi = float(2 * mpmath.pi)
        return hi, float(2 * mpmath.pi - hi)


_TWO_PI_HI, _TWO_PI_LO = _two_pi_dd()


def _turns(fn: Any, args: tuple[float, ...]) -> tuple[float, float]:
    """``c / (2 pi)`` in double-double (turns per unit of t) for ``c = fn(*args)``; the last
    coefficient is remembered on ``fn`` (a sweep of t with the same other inputs computes it once)."""
    memo = getattr(fn, "_symkin_memo", None)
    if memo is not None and memo[0] == args:
        return memo[1]
    ch, cl = fn(*args)
    u = _dd_div(float(ch), float(cl), _TWO_PI_HI, _TWO_PI_LO)
    fn._symkin_memo = (args, u)  # one assignment: another thread sees the old pair or the new one
    return u


def _reduce_turns(u: tuple[float, float], t: Any) -> Any:
    """``2 pi frac(u t)`` for the double-double ``u`` (turns) and float ``t``: the product split
    exactly, the whole turns removed exactly (Sterbenz), one rounding in the fraction."""
    y, e = _two_prod(u[0], t)
    e = e + u[1] * t
    k = np.rint(y)
    f = (y - k) + e
    return f * _TWO_PI_HI + f * _TWO_PI_LO


def _reduce_turns_all(u: tuple[float, float], t: np.ndarray) -> np.ndarray:
    """:func:`_reduce_turns` for a whole array of times, branch-free (no gather or scatter):
    ``t = th + tl`` and ``u[0] = uh + ul`` split exactly (Veltkamp), the three products
    ``uh th``, ``uh tl``, ``ul th`` exact, each with its whole turns removed exactly, then the
    small ``ul tl + u[1] t`` added; within about 2^-52 pi at any phase below 2^53 turns."""
    u0, u1 = u[0], u[1]
    cu = _SPLIT * u0
    uh = cu - (cu - u0)
    ul = u0 - uh
    c = np.multiply(t, _SPLIT)
    th = np.subtract(c, t)
    np.subtract(c, th, out=th)  # th = c - (c - t)
    tl = np.subtract(t, th, out=c)
    y = np.multiply(th, uh)  # exact
    p = np.rint(y)
    np.subtract(y, p, out=y)  # the fraction of uh th, exact
    for a, b in ((tl, uh), (th, ul)):
        np.multiply(a, b, out=p)  # exact
        np.subtract(p, np.rint(p), out=p)
        np.add(y, p, out=y)
    np.multiply(tl, ul, out=p)
    np.add(y, p, out=y)
    np.multiply(t, u1, out=p)
    np.add(y, p, out=y)  # the phase in turns, within a few turns of 0
    np.subtract(y, np.rint(y), out=y)
    np.multiply(y, _TWO_PI_LO, out=p)
    np.multiply(y, _TWO_PI_HI, out=y)
    return np.add(y, p, out=y)


def long_phase(x: Any, fn: Any, t: Any, *args: Any) -> Any:
    """The phase ``x = c t`` (evaluated plainly) where ``|x| <= LONG_PHASE``; elsewhere the
    same phase from ``c = fn(*args)`` in double-double, reduced mod 2 pi.  Where the
    coefficient's inputs are numbers (an array of times only) ``c`` is computed once, in
    Python floats, and, when any phase of the call is long, every phase of the call is
    reduced in turns, branch-free (:func:`_reduce_turns_all`: a masked gather and scatter of
    the long ones cost more than the reduction of all)."""
    if type(x) is not np.ndarray or x.ndim == 0:
        if not abs(x) > LONG_PHASE:
            return x
        return _reduce_turns(_turns(fn, tuple(float(a) for a in args)), float(t))
    if not x.size or (x.max() <= LONG_PHASE and x.min() >= -LONG_PHASE):  # (two passes, no temporary)
        return x
    shape = x.shape
    if all(isinstance(a, float) or np.ndim(a) == 0 for a in args):  # (np.float64 is a float)
        t = np.asarray(t, np.float64)
        return _reduce_turns_all(_turns(fn, tuple(map(float, args))), t if t.shape == shape else np.broadcast_to(t, shape))
    big = np.abs(x) > LONG_PHASE
    x = x if x.dtype == np.float64 else x.astype(np.float64)  # (a fresh product c*t: written in place)
    t = np.asarray(t, np.float64)
    tb = t[big] if t.shape == shape else np.broadcast_to(t, shape)[big]
    c = fn(*(a[big] if a.shape == shape else np.broadcast_to(a, shape)[big] for a in (np.asarray(v, np.float64) for v in args)))
    x[big] = _dd_reduce_pair(c, tb)
    return x


def long_phase_f32(x: Any, fn: Any, t: Any, *args: Any) -> Any:
    """:func:`long_phase` of float32 values (reduced in float64, rounded to float32)."""
    return np.asarray(long_phase(np.asarray(x, np.float64), fn, t, *args), dtype=np.float32)


def _long_phase_scalar(x: float, fn: Any, t: float, *args: float) -> float:
    if not abs(x) > LONG_PHASE:
        return x
    return float(_reduce_turns(_turns(fn, args), t))


SCALAR_NAMESPACE["_symkin_long_phase"] = _long_phase_scalar
NAMESPACE["float64"]["_symkin_long_phase"] = long_phase
NAMESPACE["float32"]["_symkin_long_phase"] = long_phase_f32


def dd_source(name: str, coeff: Any, params: Any) -> str:
    """Python source of ``name(*params)``: the rational function ``coeff`` of ``params``
    in double-double arithmetic, returned as ``(hi, lo)``.  Straight-line arithmetic and
    calls of :data:`DD_HELPERS`: one source serves NumPy arrays, Python floats and Numba."""
    import sympy as sp

    writer = _DoubleDouble({p: f"p{k}" for k, p in enumerate(params)})
    ch, cl = writer.emit(sp.sympify(coeff))
    head = [f"def {name}({', '.join(writer.names.values())}):"]
    head += [f"    {v} = _f64({v})" for v in writer.names.values()]
    return "\n".join(head + writer.lines + [f"    return {ch}, {cl}"]) + "\n"


def sum_source(name: str, poly: Any, params: Any) -> str | None:
    """Python source of ``name(*params)``: the polynomial ``poly`` of ``params`` (integer
    coefficients) as ``(hi, lo)``, error-free up to the last additions (issue 34): every input
    split once (Veltkamp), each term's product chain by TwoProduct (Dekker) with its rounding
    errors carried as a low part, the terms' high parts added by TwoSum and the errors in one
    float sum (Sum2 of Ogita, Rump & Oishi 2005).  Its error before the final rounding is a few
    units of ``n^2 2^-106`` of the sum of the terms' magnitudes (``n`` the terms).  Plain
    arithmetic only (no calls): the same source serves NumPy arrays, Python floats and Numba.
    Half the operations of :func:`dd_source`'s double-double products.  None where a
    coefficient is not an integer below 2^26 (:func:`dd_source` then)."""
    import sympy as sp

    names = {p: f"p{k}" for k, p in enumerate(params)}
    lines = [f"    {v} = _f64({v})" for v in names.values()]
    terms = []
    for t in sp.Add.make_args(sp.expand(poly)):
        c, factors = t.as_coeff_mul()
        if not c.is_Integer or abs(c) >= 2**26:
            return None
        chain = [f"{float(abs(c))!r}"] if abs(c) != 1 else []
        for f in factors:
            base, e = f.as_base_exp()
            if base not in names or not e.is_Integer or e < 1:
                return None
            chain += [names[base]] * int(e)
        terms.append((c < 0, chain))
    split = {}  # each input split once: (hi, lo)

    def halves(x: str) -> tuple[str, str]:
        if x not in split:
            if x[0] == "p":
                lines.append(f"    _c = {_SPLIT!r} * {x}")
                lines.append(f"    {x}h = _c - (_c - {x})")
                lines.append(f"    {x}l = {x} - {x}h")
                split[x] = (f"{x}h", f"{x}l")
            else:  # a coefficient below 2^26: exact in 26 bits, its own high half
                split[x] = (x, "0.0")
        return split[x]

    for k, (negative, chain) in enumerate(terms):
        if not chain:
            chain = ["1.0"]
        q, lo = chain[0], None
        for j, g in enumerate(chain[1:]):
            gh, gl = halves(g)
            if not q.startswith("_q"):  # an input or the coefficient: split once
                qh, ql = halves(q)
            else:  # a fresh product: split here
                lines.append(f"    _c = {_SPLIT!r} * {q}")
                lines.append(f"    _h = _c - (_c - {q})")
                lines.append(f"    _l = {q} - _h")
                qh, ql = "_h", "_l"
            r = f"_q{k}_{j}"
            lines.append(f"    {r} = {q} * {g}")
            e = f"((({qh} * {gh} - {r}) + {qh} * {gl} + {ql} * {gh}) + {ql} * {gl})"
            lo = e if lo is None else f"({e} + {lo} * {g})"
            lines.append(f"    _e{k} = {lo}")
            q, lo = r, f"_e{k}"
        sign = "-" if negative else ""
        if k == 0:
            lines.append(f"    _s = {sign}{q}")
            lines.append(f"    _err = {sign}({lo})" if lo else "    _err = 0.0 * _s")
            continue
        lines.append(f"    _b = {sign}{q}")
        lines.append("    _t = _s + _b")
        lines.append("    _bb = _t - _s")
        lines.append("    _err = _err + ((_s - (_t - _bb)) + (_b - _bb))" + (f" {'-' if negative else '+'} {lo}" if lo else ""))
        lines.append("    _s = _t")
    if not terms:
        return None
    lines += ["    _h = _s + _err", "    _bb = _h - _s", "    return _h, (_s - (_h - _bb)) + (_err - _bb)"]
    return "\n".join([f"def {name}({', '.join(names.values())}):", *lines]) + "\n"


class _DoubleDouble:
    """The statements of :func:`dd_source`: each operation into a fresh pair ``(hK, lK)``."""

    def __init__(self, names: dict[Any, str]):
        self.names = names
        self.lines: list[str] = []

    def call(self, op: str, a: tuple[str, str], b: tuple[str, str]) -> tuple[str, str]:
        """``op(a, b)`` into a fresh pair."""
        k = len(self.lines) + 1
        self.lines.append(f"    h{k}, l{k} = {op}({a[0]}, {a[1]}, {b[0]}, {b[1]})")
        return f"h{k}", f"l{k}"

    def emit(self, e: Any) -> tuple[str, str]:
        """The pair holding ``e`` (a parameter, an exact number, a sum, a product or an integer power)."""
        if e in self.names:
            return self.names[e], "0.0"
        if e.is_number:  # a rational, or an exact constant such as 4 pi/5 or sqrt(2): to 2^-106
            with mpmath.workdps(60):
                v = mpmath.mpf(int(e.p)) / int(e.q) if e.is_Rational else mpmath.mpf(str(e.evalf(40)))
                return repr(float(v)), repr(float(v - float(v)))
        if e.is_Add or e.is_Mul:
            op = "_dd_add" if e.is_Add else "_dd_mul"
            acc = self.emit(e.args[0])
            for a in e.args[1:]:
                acc = self.call(op, acc, self.emit(a))
            return acc
        if e.is_Pow and e.exp.is_Integer and e.exp != 0:
            base = acc = self.emit(e.base)
            for _ in range(abs(int(e.exp)) - 1):
                acc = self.call("_dd_mul", acc, base)
            return self.call("_dd_div", ("1.0", "0.0"), acc) if e.exp < 0 else acc
        raise ValueError(f"not a rational function of the inputs: {e}")


_GATHER_FROM = 4096  # points: below this the compensated sum is evaluated at every point (see compensated_sum)


def compensated_sum(value: Any, bound: Any, fn: Any, *args: Any) -> Any:
    """A :class:`~symkin.numeric.nodes.CompensatedSum` for the NumPy code: the plain sum
    ``value`` where ``|value| >= bound`` (a bound the printer derives from the sum of the
    terms' magnitudes: there the plain sum is within 8 units of 2^-53, see
    :func:`symkin.numeric.codegen.compensated_bound`), and elsewhere (where the terms cancel,
    and at nan) ``fn``, the error-free sum (:func:`sum_source`), at those points only (at every
    point for a small call or where most points cancel; the certified points keep the plain sum)."""
    if type(value) is not np.ndarray or value.ndim == 0:
        if abs(value) >= bound:
            return value
        return fn(*(np.float64(a) for a in args))[0]
    keep = np.abs(value) >= bound
    count = int(np.count_nonzero(keep))
    if count == keep.size:
        return value
    shape = value.shape
    floats = [np.asarray(x, np.float64) for x in args]
    if keep.size <= _GATHER_FROM or 2 * count <= keep.size:
        # a small call (the operations' calls cost more than their work) or most points cancel:
        # the compensated sum of every point, without the gathers and the scatter
        out = np.array(np.broadcast_to(fn(*floats)[0], shape), dtype=np.float64)  # (a point's value of arrays of 1)
        np.copyto(out, value, where=keep)  # (certified points: the plain sum, as below)
        return out
    redo = ~keep
    value = np.array(value, dtype=np.float64)  # (a fresh array: the caller's temporaries are not written)
    parts = [a if a.ndim == 0 else (a if a.shape == shape else np.broadcast_to(a, shape))[redo] for a in floats]
    value[redo] = fn(*parts)[0]
    return value


def _compensated_sum_scalar(value: float, bound: float, fn: Any, *args: float) -> float:
    return value if abs(value) >= bound else float(fn(*args)[0])


SCALAR_NAMESPACE["_symkin_compensated_sum"] = _compensated_sum_scalar
NAMESPACE["float64"]["_symkin_compensated_sum"] = compensated_sum


def _same(v: Any) -> Any:
    return v


def dd_function(source: str, name: str) -> Any:
    """The function of :func:`dd_source` for NumPy arrays and Python floats."""
    ns: dict[str, Any] = {**DD_HELPERS, "_f64": _same}  # the callers give float64 arrays or Python floats
    exec(compile(source, f"<symkin phase {name}>", "exec"), ns)  # generated from SymPy, no user text
    return ns[name]
