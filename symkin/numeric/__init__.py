"""Compile derived laws into numeric functions: one entry point, backends by name.

:func:`compile` takes one law or several (they share common subexpressions) and a
backend: ``"numpy"`` (vectorised, float64 or float32), ``"numba"`` (one fused compiled
loop, an optional extra), ``"mpmath"`` (``digits`` significant digits) or ``"exact"``
(rationals).  Without one it takes :func:`default_backend`: numba where it is installed
(unnamed, ``jit="auto"``: the NumPy code first, the kernel compiled once the time spent there
pays for it, kept on disk for later processes; its speed against ``sympy.lambdify``:
docs/numerics.md), else numpy.  Float backends evaluate a *stable form* of each law
(:mod:`symkin.numeric.stable`): integer parts exactly, removable singularities
cancelled, angles unwrapped, cosine sums well conditioned.

    >>> import numpy as np, symkin
    >>> law = symkin.schemes.two_row("AI").ratio("1", "H", fixed="4")
    >>> f = symkin.compile(law, backend="numpy")
    >>> f.args
    ('r_1', 'r_2', 'r_3', 'r_4')
    >>> float(f(1, 2, 1, 4))
    9.0
    >>> aa = symkin.schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4")
    >>> g = symkin.compile(aa, backend="numpy")   # z1 z3 - z2 z4 in exact integer arithmetic
    >>> float(g(10**8, 10**8 - 1, 10**8, 10**8 + 1))
    1e+16
    >>> symkin.compile(aa, backend="exact")(100, 99, 100, 101)
    Fraction(10000, 1)
"""

from __future__ import annotations

import functools
import os
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin._util.bounds import show
from symkin.errors import InputError
from symkin.laws import Law
from symkin.numeric.backends import BACKENDS, Backend, Plan, numba_available, warn_no_numba
from symkin.numeric.function import NonFiniteInputWarning, NumericFunction
from symkin.numeric.stable import RULE_NOTES, stable_form

__all__ = ["compile", "default_backend", "NumericFunction", "NonFiniteInputWarning", "BACKENDS", "dask_map"]

#: Points per chunk of the NumPy backend: a call of up to this many points is one call of the
#: generated code on the arrays as given (no copy of the outputs), larger calls go in chunks of it.
#: 2^17 (temporaries of 1 MiB): smaller chunks were slower at 10^5 points and no faster at 10^6
#: on the benchmark laws (benchmarks/notes/numeric-backends.md).
DEFAULT_CHUNK = 1 << 17


#: The environment variable that names the backend :func:`compile` takes when none is given.
BACKEND_VARIABLE = "SYMKIN_BACKEND"


def default_backend() -> str:
    """The backend :func:`compile` uses when none is named: ``$SYMKIN_BACKEND`` when set
    (``numpy`` or ``numba``), else ``numba`` where Numba is installed (one fused loop per
    law; unnamed, it starts with the NumPy code and compiles the kernel once the time spent
    there pays for it (``jit="auto"`` of :func:`compile`), and the kernel is kept on disk for
    later processes; its speed: docs/numerics.md), else ``numpy``.

    Numba runs calls of 2^15 points and more on every thread, with OpenMP where it is found
    (symkin sets ``OMP_WAIT_POLICY=PASSIVE`` unless it is set: waiting threads sleep); GNU
    OpenMP's threads do not survive a ``fork``: a process that forks workers after such a call
    (multiprocessing's default start method on Linux) should compile with ``threads=1`` (one
    thread, no OpenMP) or ``backend="numpy"``.

    >>> default_backend() in ("numpy", "numba")
    True
    """
    named = os.environ.get(BACKEND_VARIABLE, "").strip()
    if named:
        if named not in ("numpy", "numba"):
            raise InputError(f"{BACKEND_VARIABLE}={named!r} is not a float backend; set it to numpy or numba, or unset it")
        return named
    return "numba" if _numba_imports() else "numpy"


@functools.cache
def _numba_imports() -> bool:
    """Whether Numba is installed (found, not imported: importing it costs 0.2-0.3 s, paid only
    when a default function compiles a kernel; one that does not import then, a Numba built for
    another NumPy, leaves the NumPy code, without a word, as where Numba is not installed)."""
    import importlib.util

    return importlib.util.find_spec("numba") is not None


def _exprs(laws: Any) -> tuple[list[sp.Expr], list[str]]:
    items = list(laws) if isinstance(laws, (list, tuple)) else [laws]
    if not items:
        raise InputError("nothing to compile: give a law, an expression, or a list of them")
    exprs, names = [], []
    for item in items:
        if isinstance(item, Law):
            exprs.append(sp.sympify(item.rhs))
            names.append(str(item.lhs))
        elif isinstance(item, sp.MatrixBase):
            for k, e in enumerate(item):
                exprs.append(e)
                names.append(f"[{k}]")
        elif isinstance(item, sp.Basic) and isinstance(item, sp.Expr):
            exprs.append(item)
            text = show(item, 41)
            names.append(text if len(text) <= 40 else f"law {len(names)}")
        else:
            raise InputError(f"can only compile laws or SymPy expressions, got {item!r}")
    for e, n in zip(exprs, names):
        if e.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
            raise InputError(f"{n} is infinite or undefined ({show(e)}); there is nothing finite to compile")
        _check_constants(e, n)
    return exprs, names


def _check_constants(expr: sp.Expr, name: str) -> None:
    """Refuse a constant part of a law that has no finite float (an unevaluated ``log(0)``,
    ``tan(pi/2)``, ``sqrt(2)**(10**6)``): float code would compute a nan, an inf, or a wrong
    finite number from it.  An exact rational may be of any size: whether a float holds it is
    decided after the stable rewriting (tooth-number products are computed in integers)."""
    stack = [expr]
    while stack:
        e = stack.pop()
        if e.is_Atom or not isinstance(e, sp.Expr):
            continue
        if not e.is_number:
            stack.extend(e.args)
            continue
        value = e.evalf(17)
        if not (value.is_Float and value.is_finite and abs(value) < _FLOAT_MAX):
            raise InputError(f"{name}: its constant {show(e)} has no finite float value ({show(value)}); "
                             "there is nothing finite to compile")


#: The largest float64.
_FLOAT_MAX = sp.Float(1.7976931348623157e308)


@dataclass(frozen=True)
class _Spec:
    """What a function was compiled from: enough to rebuild it (pickling, Dask workers)."""

    exprs: tuple[sp.Expr, ...]
    names: tuple[str, ...]
    args: tuple[sp.Symbol, ...]
    options: tuple[tuple[str, Any], ...]

    def key(self) -> str:
        """A digest of everything compiled: equal keys compile to the same function."""
        import hashlib

        text = repr((tuple(sp.srepr(e) for e in self.exprs), self.names, tuple(sp.srepr(a) for a in self.args), self.options))
        return hashlib.sha256(text.encode()).hexdigest()

    def build(self) -> NumericFunction:
        laws = [Law(sp.Symbol(n), e) for n, e in zip(self.names, self.exprs)]
        options = dict(self.options)
        options["ranges"] = dict(options.get("ranges") or ())  # kept as pairs (hashable), given as a mapping
        return compile(laws, list(self.args), **options)


def compile(
    laws: Any,
    args: Sequence[sp.Symbol] | None = None,
    *,
    backend: str | None = None,
    precision: str = "float64",
    digits: int = 50,
    cse: bool = True,
    stable: bool = True,
    ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None,
    reduce_phase: Sequence[sp.Symbol] | None = None,
    chunk: int = DEFAULT_CHUNK,
    threads: int | None = None,
    on_pole: str = "warn",
    jit: str | None = None,
) -> NumericFunction:
    """A numeric function of one law or several (sharing common subexpressions).

    Parameters
    ----------
    laws : Law, sympy expression, Matrix, or a sequence of them
    args : sequence of Symbol, optional
        Argument order; default: every free symbol, sorted by name.
    backend : {"numpy", "numba", "mpmath", "exact"}, optional
        Default: :func:`default_backend` (numba where it is installed, else numpy; the
        environment variable ``SYMKIN_BACKEND`` chooses).  ``"numba"`` needs the ``numba``
        extra; named without it, symkin warns once and uses NumPy.
    precision : {"float64", "float32"}
        For the numpy and numba backends.  float32 inputs are the inputs; other inputs are
        rounded to float32, and where that rounding moves a result near a pole or zero by
        more than 2^-16 of the call's largest value a PrecisionWarning says so (checked by
        a float64 evaluation, paid only when inputs are not float32 already).
    digits : int
        Significant digits of the mpmath backend.
    cse : bool
        Eliminate common subexpressions (results are equal either way).
    stable : bool
        Rewrite into stable forms before float evaluation (see :mod:`symkin.numeric.stable`).
        ``False``: the laws as written, lambdify's accuracy, faster on NumPy for small arrays
        (docs/numerics.md, "Speed or accuracy: what to choose"; the numba backend keeps both).
    ranges : {symbol: (lo, hi)}, optional
        Known ranges of symbols, which let the rewriting decide signs (e.g. an
        eccentricity in (0, 1)).
    reduce_phase : sequence of Symbol, optional
        Time symbols whose phases (``sin(c omega t)``, ``c`` a rational function of
        inputs) are reduced mod 2 pi in double-double arithmetic, for long times.  Default: the arguments named ``t`` (the elliptical
        drive's slider at e = 0.999999 keeps 1e-13 normwise at its speed peaks only so);
        ``()`` turns the reduction off.
    chunk : int
        Points per chunk of the NumPy backend.
    threads : int, optional
        Threads for large calls: numba default all (Numba's setting); numpy default 1
        (chunks are shared among this many threads; NumPy releases the GIL).
    on_pole : {"warn", "raise", "return"}
        At a pole, float backends return inf/nan with a PoleWarning, raise PoleError, or
        (``"return"``) return inf/nan without a word, for a caller that tests the
        outputs itself (a sieve discarding such points).
    jit : {"auto", "eager"}, optional
        For the numba backend: ``"eager"`` compiles a kernel at its first call; ``"auto"``
        evaluates with the NumPy code until the time spent there pays for compiling the kernel
        (docs/numerics.md, "First use").  Default: ``"auto"`` where the backend is not named
        (neither ``backend=`` nor ``$SYMKIN_BACKEND``), else ``"eager"``.

    Returns
    -------
    NumericFunction

    Examples
    --------
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> f = compile(sp.sin(x) / x, backend="mpmath", digits=30)
    >>> f
    <NumericFunction sin(x)/x(x): mpmath 30 digits>
    >>> import mpmath
    >>> mpmath.nstr(f(0.5), 30)   # mpf values carry 30 digits; print them with nstr
    '0.958851077208406000546575870431'
    """
    backend, jit = _backend_and_jit(backend, jit)
    exprs, names = _exprs(laws)
    args = _arguments(exprs, args)
    if reduce_phase is None:  # time, by its name: phases of t are reduced unless asked not to
        reduce_phase = tuple(a for a in args if a.name == "t")
    options = dict(
        backend=backend, precision=precision, digits=digits, cse=cse, stable=stable, ranges=dict(ranges or {}),
        reduce_phase=tuple(reduce_phase), chunk=chunk, threads=threads, on_pole=on_pole, jit=jit,
    )
    spec = _Spec(tuple(exprs), tuple(names), args, tuple(sorted((k, _hashable(v)) for k, v in options.items())))
    cls = _backend_class(backend, jit, precision, digits, chunk)
    applied: list[str] = []
    rewritten = exprs
    if cls.floats:
        exprs, rewritten = _float_forms(exprs, names, precision, stable, ranges, reduce_phase, applied)
    plan = Plan(
        tuple(exprs), tuple(rewritten), args, tuple(names),
        precision if cls.floats else cls.precisions[0],
        digits if backend == "mpmath" else None, cse, chunk, threads, jit,
    )
    notes = [note for name, note in RULE_NOTES.items() if name in applied]
    return NumericFunction(cls(plan), plan, cls.key, notes, spec, on_pole=on_pole)


def _backend_and_jit(backend: str | None, jit: str | None) -> tuple[str, str]:
    """The backend and the jit mode that run a compiled law: as given, checked, or the defaults
    (:func:`default_backend`; ``"auto"`` where no backend is named, neither ``backend=`` nor
    ``$SYMKIN_BACKEND``, else ``"eager"``)."""
    if jit is None:
        jit = "auto" if backend is None and not os.environ.get(BACKEND_VARIABLE, "").strip() else "eager"
    if jit not in ("auto", "eager"):
        raise InputError(f"jit must be 'auto' or 'eager', got {jit!r}")
    if backend is None:
        backend = default_backend()
    if backend not in BACKENDS:
        raise InputError(f"unknown backend {backend!r}; choose one of {', '.join(BACKENDS)}")
    return backend, jit


def _backend_class(backend: str, jit: str, precision: str, digits: Any, chunk: Any) -> type[Backend]:
    """The class of ``backend`` (NumPy's, with one notice, for an eager numba without numba
    installed), its options checked."""
    cls = BACKENDS[backend]
    if backend == "numba" and jit == "eager" and not numba_available():
        warn_no_numba()
        cls = BACKENDS["numpy"]
    _check_options(cls, backend, precision, digits, chunk)
    return cls


def _arguments(exprs: Sequence[sp.Expr], args: Any) -> tuple[sp.Symbol, ...]:
    """The argument order: ``args`` checked (symbols, every free symbol of the laws among
    them), or every free symbol sorted by name."""
    free = set().union(*(e.free_symbols for e in exprs))
    if args is None:
        args = sorted(free, key=lambda s: s.name)
    if isinstance(args, (str, bytes)) or not isinstance(args, Iterable):
        raise InputError(f"args is a sequence of SymPy symbols (the argument order), got {args!r}")
    args = tuple(args)
    for a in args:
        if not isinstance(a, sp.Symbol):
            raise InputError(f"arguments are SymPy symbols, got {a!r}")
    missing = free - set(args)
    if missing:
        raise InputError(f"the law depends on {', '.join(sorted(map(str, missing)))}, which are not among the arguments")
    return args


def _check_options(cls: type[Backend], backend: str, precision: str, digits: Any, chunk: Any) -> None:
    """An InputError for an option the backend does not take."""
    if cls.floats and precision not in cls.precisions:
        raise InputError(f"precision {precision!r} is not offered by the {backend} backend; choose "
                         f"{' or '.join(cls.precisions)}")
    if backend == "mpmath" and (not isinstance(digits, int) or isinstance(digits, bool) or digits < 1):
        raise InputError(f"digits must be a positive integer, got {digits!r}")
    if not isinstance(chunk, int) or chunk < 1:
        raise InputError(f"chunk must be a positive number of points, got {chunk!r}")


def _float_forms(
    exprs: list[sp.Expr], names: Sequence[str], precision: str, stable: bool,
    ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None, reduce_phase: Sequence[sp.Symbol], applied: list[str],
) -> tuple[list[sp.Expr], list[sp.Expr]]:
    """The laws for a float backend: with every function of numbers alone evaluated (to 30
    digits), and rewritten into their stable forms (the rules that changed something are
    appended to ``applied``); an InputError for a number no float can hold."""
    exprs = [_constants(e) for e in exprs]
    if stable:
        rewritten = [stable_form(e, ranges=ranges, reduce_phase=reduce_phase, applied=applied) for e in exprs]
    else:
        rewritten = list(exprs)
    _refuse_constants_beyond_floats(rewritten, names, precision)
    return exprs, rewritten


def _refuse_constants_beyond_floats(exprs: Sequence[sp.Expr], names: Sequence[str], precision: str) -> None:
    """InputError for a law holding a number no float of ``precision`` can hold (10^600 from
    a speed of 10^300 squared): float code could not even start, so say so, and how to avoid it."""
    import numpy as np

    largest = float(np.finfo(np.float32 if precision == "float32" else np.float64).max)
    for expr, name in zip(exprs, names):
        for number in expr.atoms(sp.Rational, sp.Float):
            if abs(number) > largest:
                exponent = int(abs(int(number)).bit_length() * 0.30103)
                raise InputError(
                    f"{name} holds a number of about 10^{exponent}, beyond the {precision} range (at most "
                    f"{largest:.3g}); give inputs of smaller size (other units), or compile with backend='mpmath'"
                )


def _constants(e: sp.Expr) -> sp.Expr:
    """``e`` with every function of numbers alone, and every power of numbers alone holding an
    integer beyond int64, replaced by its value (a Float of 30 digits): float code then never
    meets an integer too large for NumPy (``sqrt(10**40 + 1)``, ``cos(10**30)``), which takes
    Python integers beyond int64 as objects with no ``sqrt`` or ``cos``."""
    found = [n for n in sp.preorder_traversal(e)
             if not n.free_symbols and (isinstance(n, sp.Function) or (n.is_Pow and _beyond_int64(n)))]
    if not found:
        return e
    values = {}
    for n in found:
        value = sp.N(n, 30)
        if value.is_Float:
            values[n] = value
    return e.xreplace(values) if values else e


def _beyond_int64(e: sp.Expr) -> bool:
    """Whether ``e`` holds an exact number whose numerator or denominator int64 cannot hold."""
    return any(max(abs(int(r.p)), int(r.q)) >= 2**63 for r in e.atoms(sp.Rational))


def _hashable(v: Any) -> Any:
    if isinstance(v, dict):
        return tuple(sorted(((k, tuple(val)) for k, val in v.items()), key=lambda kv: str(kv[0])))
    return v


def __getattr__(name: str) -> Any:  # dask_map loads its module on first use
    if name == "dask_map":
        from symkin.numeric.parallel import dask_map

        return dask_map
    if name == "Scene":  # moved out of numeric (numeric knows no mechanism): symkin.Study
        from symkin._deprecated import renamed

        return renamed("symkin.numeric.Scene", ("symkin.study:Study", "symkin.Study"))
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
