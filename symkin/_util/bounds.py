"""Rigorous bounds on the numbers in an expression: interval arithmetic under a precision budget.

A number a user writes as an expression can be astronomically large or small although
its text is short (``exp(exp(9))`` has 3520 digits, ``((sqrt(2)**999)**999)**999``
about 150 million), or need millions of digits to evaluate (``sin(exp(exp(exp(3))))``
asks for the sine of a number of 230 million digits).  SymPy's ``evalf`` then runs for
minutes or fills the memory.  Here a constant expression is enclosed in an interval whose
end points are binary floating-point numbers rounded outwards (mpmath's interval
arithmetic), so the true value is certainly inside: the size of a number is known without
evaluating it exactly, and without trusting a float that cancelled.

The working precision starts at 64 bits and grows (256, 1024, 4096 bits) only while an
answer is undecided (an interval that straddles 0 or a domain boundary).  The parser
(:mod:`symkin.parsing`) checks every node of an expression as it builds it, so every
operation here sees operands already known to lie between 1e-300 and 1e300 in size, and
each step costs microseconds whatever the expression.

    >>> import sympy as sp
    >>> check(sp.exp(sp.exp(9), evaluate=False), "the speed")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the speed: exp(exp(9)) is about 10^3519; numbers from 1e-300 to 1e300 in size are accepted (this one is beyond the float64 range, about 1.8e308)
    >>> sign(sp.sin(1)**2 + sp.cos(1)**2 - 1) is None    # zero to 1233 digits: undecided
    True
    >>> sign(sp.pi - sp.Rational(314159265358979, 10**14))
    1
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from typing import Any

import sympy as sp
from mpmath.libmp import (
    fnan,
    fone,
    from_int,
    from_rational,
    fzero,
    libmpi,
    mpf_abs,
    mpf_acos,
    mpf_add,
    mpf_asin,
    mpf_cmp,
    mpf_ge,
    mpf_gt,
    mpf_le,
    mpf_lt,
    mpf_neg,
    mpf_shift,
    mpf_tanh,
    round_ceiling,
    round_floor,
)

from symkin.errors import InputError

__all__ = [
    "PRECISIONS",
    "MAX_DIGITS",
    "NotReal",
    "Unbounded",
    "Undecided",
    "NotConstant",
    "Encloser",
    "check",
    "sign",
    "OutOfRange",
    "magnitude",
    "show",
]

#: Working precisions in bits, tried in turn while an answer is undecided (4096 bits are 1233 digits).
PRECISIONS = (64, 256, 1024, 4096)
#: Numbers are accepted between 10^-MAX_DIGITS and 10^MAX_DIGITS in size (or 0).
MAX_DIGITS = 300

_HUGE = from_int(10**MAX_DIGITS)
_TINY = from_rational(1, 10**MAX_DIGITS, 64, round_floor)
_ZERO = (fzero, fzero)

Interval = tuple[Any, Any]  # (lower, upper) end points, mpmath mpf tuples


class NotReal(Exception):
    """The value is certainly not a real number (the square root of a negative number, ...)."""

    def __init__(self, node: Any, reason: str):
        super().__init__(reason)
        self.node = node
        self.reason = reason


class Unbounded(Exception):
    """An interval with an infinite end at this precision: a pole, an overflow, or too little precision."""

    def __init__(self, node: Any):
        super().__init__("unbounded")
        self.node = node


class Undecided(Exception):
    """An interval straddles a domain boundary (0 under a square root, ...) at this precision."""

    def __init__(self, node: Any, question: str):
        super().__init__(question)
        self.node = node
        self.question = question


_FLOAT64_LOG10 = math.log10(sys.float_info.max)  # 308.25


class OutOfRange(Exception):
    """The value is certainly larger than 1e300 or smaller than 1e-300 (and not 0) in size."""

    def __init__(self, node: Any, interval: Interval, large: bool):
        super().__init__("out of range")
        self.node = node
        self.interval = interval
        self.large = large

    def size(self) -> str:
        small, big = _sizes(self.interval)
        return f"about 10^{math.floor(_log10(small if self.large else big) + 1e-9)}"

    def beyond(self) -> str:
        """' (beyond the float64 range ...)' for a number no float can hold, else ''."""
        large = self.large and _log10(_sizes(self.interval)[0]) > _FLOAT64_LOG10
        return " (this one is beyond the float64 range, about 1.8e308)" if large else ""


class NotConstant(Exception):
    """The expression holds a symbol that has no interval."""


def show(expr: Any, width: int = 60) -> str:
    """``expr`` as short text for a message (never fails on a number of 10^5000).

    >>> show(sp.Integer(10) ** 5000)
    'a number of 5001 digits'
    """
    if isinstance(expr, sp.Integer) or (isinstance(expr, int) and not isinstance(expr, bool)):
        n = abs(int(expr))
        if n.bit_length() > 4000:
            return f"a number of {_digits(n)} digits"
    try:
        text = str(expr)
    except ValueError:  # an integer beyond Python's int-to-str limit inside an expression
        return "an expression with a number of more than 4300 digits"
    text = " ".join(text.split())
    return text if len(text) <= width else text[: width - 3] + "..."


def _digits(n: int) -> int:
    """Decimal digits of a positive integer, without converting it to text."""
    d = int(n.bit_length() * math.log10(2))
    return d + 1 if n >= 10**d else d


def _point(x: Any) -> Interval:
    return (x, x)


def _rational(p: int, q: int, prec: int) -> Interval:
    if q == 1 and abs(p).bit_length() <= prec:
        return _point(from_int(p))
    return (from_rational(p, q, prec, round_floor), from_rational(p, q, prec, round_ceiling))


def _is_finite(x: Interval) -> bool:
    a, b = x
    return a not in _INFINITE and b not in _INFINITE


_INFINITE = {libmpi.finf, libmpi.fninf, fnan}


def _contains_zero(x: Interval) -> bool:
    return mpf_le(x[0], fzero) and mpf_ge(x[1], fzero)


def _widen(x: Any, prec: int, up: bool) -> Any:
    """``x`` moved outwards by 2^-(prec-4) of itself (covers a few ulps of a function's error)."""
    if x == fzero:
        return x
    step = mpf_shift(mpf_abs(x), -(prec - 4))
    return mpf_add(x, step if up else mpf_neg(step), prec, round_ceiling if up else round_floor)


def _monotone(f: Callable[..., Any], x: Interval, prec: int, increasing: bool = True) -> Interval:
    """An increasing (or decreasing) function of an interval from its end points, widened outwards."""
    lo = f(x[0] if increasing else x[1], prec + 20, round_floor)
    hi = f(x[1] if increasing else x[0], prec + 20, round_ceiling)
    return (_widen(lo, prec, up=False), _widen(hi, prec, up=True))


class Encloser:
    """Intervals of SymPy expressions at one precision, memoised by node.

    Parameters
    ----------
    prec : int
        Working precision in bits.
    env : mapping of Symbol to (lower, upper), optional
        Intervals for symbols (as Python numbers or SymPy rationals).
    limits : bool
        Refuse every value beyond 1e300 or below 1e-300 in size on the way (:class:`OutOfRange`);
        False measures values of any size (an overflow of float64, say).
    """

    def __init__(self, prec: int, env: Mapping[Any, tuple[Any, Any]] | None = None, *, limits: bool = True):
        self.prec = prec
        self.limits = limits
        self.memo: dict[Any, Interval] = {}
        self.env = {s: self._number_interval(lo, hi) for s, (lo, hi) in (env or {}).items()}

    def _number_interval(self, lo: Any, hi: Any) -> Interval:
        a = self.enclose(sp.Rational(lo))[0]
        b = self.enclose(sp.Rational(hi))[1]
        return (a, b)

    def enclose(self, expr: Any) -> Interval:
        """The interval holding ``expr``; raises NotReal, Unbounded, Undecided or NotConstant."""
        try:
            return self.memo[expr]
        except KeyError:
            pass
        x = self._enclose(expr)
        if not _is_finite(x):
            raise Unbounded(expr)
        if not self.limits:
            self.memo[expr] = x
            return x
        # every number on the way is bounded, so the next operation works on numbers of sane size
        small, big = _sizes(x)
        if mpf_gt(small, _HUGE):
            raise OutOfRange(expr, x, large=True)
        if mpf_lt(big, _TINY) and small != fzero:
            raise OutOfRange(expr, x, large=False)
        if mpf_gt(big, _HUGE):
            raise Undecided(expr, f"is at most 1e{MAX_DIGITS} in size")
        self.memo[expr] = x
        return x

    def _enclose(self, e: Any) -> Interval:
        p = self.prec
        if e.is_Rational:
            return _rational(int(e.p), int(e.q), p)
        if e.is_Float:
            return _point(e._mpf_)
        if e is sp.pi:
            return libmpi.mpi_pi(p)
        if e is sp.E:
            return libmpi.mpi_exp(libmpi.mpi_one, p)
        if e.is_Symbol:
            if e in self.env:
                return self.env[e]
            raise NotConstant(e)
        if e in (sp.nan, sp.zoo, sp.oo, -sp.oo, sp.S.ComplexInfinity):
            if e is sp.nan:
                raise NotReal(e, "it is undefined (nan)")
            raise Unbounded(e)
        if e is sp.I:
            raise NotReal(e, "it is imaginary")
        if e.is_Add:
            x = self.enclose(e.args[0])
            for a in e.args[1:]:
                x = libmpi.mpi_add(x, self.enclose(a), p)
            return x
        if e.is_Mul:
            x = self.enclose(e.args[0])
            for a in e.args[1:]:
                x = libmpi.mpi_mul(x, self.enclose(a), p)
            return x
        if e.is_Pow:
            return self._pow(e)
        handler = _FUNCTIONS.get(type(e).__name__)
        if handler is not None:
            return handler(self, e, *[self.enclose(a) for a in e.args])
        if e.is_number:  # another constant (GoldenRatio, zeta(3), ...): SymPy's evalf, widened
            return self._evalf(e)
        raise NotConstant(e)

    def _evalf(self, e: Any) -> Interval:
        value = e.evalf(int(self.prec * 0.30103) + 5)
        if not value.is_Float:
            if value.is_number and value.is_extended_real is False:
                raise NotReal(e, "it is not a real number")
            raise Unbounded(e)
        m = value._mpf_
        return (_widen(m, self.prec - 10, up=False), _widen(m, self.prec - 10, up=True)) if m != fzero else _ZERO

    def _pow(self, e: Any) -> Interval:
        p = self.prec
        base, exp = e.args
        if exp.is_Integer:
            x = self.enclose(base)
            n = int(exp)
            if n >= 0:
                return libmpi.mpi_pow_int(x, n, p)
            if _contains_zero(x):
                if x == _ZERO:
                    raise Unbounded(e)  # 0 to a negative power
                raise Undecided(base, "is zero")
            return libmpi.mpi_div(libmpi.mpi_one, libmpi.mpi_pow_int(x, -n, p), p)
        x = self.enclose(base)
        y = self.enclose(exp)
        if mpf_lt(x[1], fzero):
            if exp == sp.S.Half:
                raise NotReal(e, "the square root of a negative number is not real")
            raise NotReal(e, f"a negative number ({show(base)}) to a fractional power is not real")
        if mpf_lt(x[0], fzero):
            raise Undecided(base, "is negative")
        if exp == sp.S.Half:
            return libmpi.mpi_sqrt(x, p)
        if x[0] == fzero:  # a base that may be 0: only a positive exponent is defined there
            if not mpf_gt(y[0], fzero):
                if x == _ZERO:
                    raise Unbounded(e)
                raise Undecided(base, "is zero")
            if x == _ZERO:
                return _ZERO
            upper = libmpi.mpi_pow((x[1], x[1]), y, p)
            return (fzero, upper[1])
        return libmpi.mpi_pow(x, y, p)

    def _log(self, e: Any, x: Interval, *rest: Interval) -> Interval:
        if rest:  # log(x, b) SymPy left unevaluated: log(x) / log(b)
            return libmpi.mpi_div(self._log(e, x), self._log(e, rest[0]), self.prec)
        if mpf_le(x[1], fzero):
            raise NotReal(e, "the logarithm of a number that is not positive is not real")
        if mpf_le(x[0], fzero):
            raise Undecided(e.args[0], "is positive")
        return libmpi.mpi_log(x, self.prec)

    def _arcsine(self, e: Any, x: Interval, inverse: Callable[..., Any], increasing: bool) -> Interval:
        if mpf_lt(x[1], mpf_neg(fone)) or mpf_gt(x[0], fone):
            raise NotReal(e, f"{type(e).__name__} of a number outside [-1, 1] is not real")
        if mpf_lt(x[0], mpf_neg(fone)) or mpf_gt(x[1], fone):
            raise Undecided(e.args[0], "lies in [-1, 1]")
        return _monotone(inverse, x, self.prec, increasing)

    def _atan2(self, e: Any, y: Interval, x: Interval) -> Interval:
        if _contains_zero(y) and _contains_zero(x):
            if y == _ZERO and x == _ZERO:
                raise NotReal(e, "atan2(0, 0) is undefined")
            raise Undecided(e, "has a point other than the origin")
        return libmpi.mpi_atan2(y, x, self.prec)

    def _reciprocal(self, e: Any, x: Interval) -> Interval:
        if _contains_zero(x):
            raise Unbounded(e)
        return libmpi.mpi_div(libmpi.mpi_one, x, self.prec)


_FUNCTIONS: dict[str, Callable[..., Interval]] = {
    "exp": lambda self, e, x: libmpi.mpi_exp(x, self.prec),
    "log": Encloser._log,
    "sin": lambda self, e, x: libmpi.mpi_sin(x, self.prec),
    "cos": lambda self, e, x: libmpi.mpi_cos(x, self.prec),
    "tan": lambda self, e, x: libmpi.mpi_tan(x, self.prec),
    "cot": lambda self, e, x: libmpi.mpi_cot(x, self.prec),
    "sec": lambda self, e, x: self._reciprocal(e, libmpi.mpi_cos(x, self.prec)),
    "csc": lambda self, e, x: self._reciprocal(e, libmpi.mpi_sin(x, self.prec)),
    "asin": lambda self, e, x: self._arcsine(e, x, mpf_asin, True),
    "acos": lambda self, e, x: self._arcsine(e, x, mpf_acos, False),
    "atan": lambda self, e, x: libmpi.mpi_atan(x, self.prec),
    "atan2": Encloser._atan2,
    "sinh": lambda self, e, x: libmpi.mpi_cosh_sinh(x, self.prec)[1],
    "cosh": lambda self, e, x: libmpi.mpi_cosh_sinh(x, self.prec)[0],
    "tanh": lambda self, e, x: _monotone(mpf_tanh, x, self.prec),
    "Abs": lambda self, e, x: libmpi.mpi_abs(x, self.prec),
}


# --------------------------------------------------------------------------- verdicts
def _log10(x: Any) -> float:
    """log10 |x| of a non-zero mpf, roughly (enough to print 'about 10^k')."""
    _, man, exp, bc = x
    return (exp + bc) * math.log10(2) + (math.log10(man / 2**bc) if bc < 1000 else 0.0)


def magnitude(x: Interval) -> float:
    """log10 of the largest |value| in an interval (-inf for [0, 0]).

    >>> magnitude(Encloser(64, limits=False).enclose(sp.Integer(10) ** 400))
    400.0...
    """
    big = _sizes(x)[1]
    return -math.inf if big == fzero else _log10(big)


def _sizes(x: Interval) -> tuple[Any, Any]:
    """(smallest, largest) |value| over the interval."""
    a, b = mpf_abs(x[0]), mpf_abs(x[1])
    big = b if mpf_cmp(b, a) >= 0 else a
    small = fzero if _contains_zero(x) else (a if mpf_cmp(a, b) <= 0 else b)
    return small, big


def _limits() -> str:
    return f"numbers from 1e-{MAX_DIGITS} to 1e{MAX_DIGITS} in size are accepted"


def _digits_of(bits: int) -> int:
    return int(bits * math.log10(2))


def _encloser(memo: dict[int, Encloser], prec: int) -> Encloser:
    enc = memo.get(prec)
    if enc is None:
        enc = memo[prec] = Encloser(prec)
    return enc


def check(expr: Any, what: str, *, memo: dict[int, Encloser] | None = None, error: type[Exception] = InputError) -> None:
    """Raise ``error`` unless the constant ``expr`` is a real number, 0 or between 1e-300 and
    1e300 in size, and so is every number on the way to it (decided on intervals).

    ``memo`` (a dict of :class:`Encloser` by precision) may be kept between calls on the
    parts of one expression, so that each part is enclosed once.

    >>> check(sp.exp(700), "the speed")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the speed: exp(700) is about 10^304; numbers from 1e-300 to 1e300 in size are accepted
    >>> check(sp.sqrt(2) - sp.Rational(14142135623730951, 10**16), "x")   # about -4.9e-17: fine
    """
    memo = {} if memo is None else memo
    last: Exception | None = None
    for prec in PRECISIONS:
        try:
            x = _encloser(memo, prec).enclose(expr)
        except NotReal as err:
            raise error(f"{what}: {show(err.node)} is not a real number: {err.reason}") from None
        except OutOfRange as err:
            raise error(f"{what}: {show(err.node)} is {err.size()}; {_limits()}{err.beyond()}") from None
        except (Undecided, Unbounded) as err:
            last = err
            continue
        if _contains_zero(x) and x != _ZERO:
            last = None  # 0, or a number so close to 0 that more precision must tell its size
            continue
        return
    if isinstance(last, Unbounded):
        raise error(f"{what}: {show(last.node)} is infinite or cannot be bounded (a pole or an overflow); {_limits()}")
    if isinstance(last, Undecided):
        if "in size" in last.question:
            raise error(f"{what}: {show(last.node)} cannot be bounded: it may be larger than 1e{MAX_DIGITS}; {_limits()}")
        raise error(
            f"{what}: cannot tell whether {show(last.node)} {last.question}: it is 0 to "
            f"{_digits_of(PRECISIONS[-1])} digits; write it exactly (0 if it is zero)"
        )
    # 0 to 1233 digits (an exact zero such as sin(1)**2 + cos(1)**2 - 1): accepted


def sign(expr: Any, *, memo: dict[int, Encloser] | None = None) -> int | None:
    """-1, 0 or 1 for a constant expression, or None when it is 0 to 1233 digits without being
    exactly 0 (``sin(1)**2 + cos(1)**2 - 1``), or cannot be bounded, or a part of it (not
    the whole) is beyond 1e300 or below 1e-300 in size.

    Raises NotReal or NotConstant (the caller words the message).

    >>> sign(sp.Rational(-1, 3)), sign(sp.Integer(0)), sign(sp.exp(-800)), sign(-sp.exp(800))
    (-1, 0, 1, None)
    """
    memo = {} if memo is None else memo
    for prec in PRECISIONS:
        try:
            a, b = _encloser(memo, prec).enclose(expr)
        except OutOfRange as err:
            if err.node is not expr and err.node != expr:
                return None
            a, b = err.interval
        except (Undecided, Unbounded):
            continue
        if mpf_gt(a, fzero):
            return 1
        if mpf_lt(b, fzero):
            return -1
        if a == b == fzero:
            return 0
    return None
