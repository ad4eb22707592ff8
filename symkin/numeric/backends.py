"""The backends :func:`symkin.compile` chooses by name, and how each evaluates.

Each backend is a class in :data:`BACKENDS` whose ``build(plan)`` returns an evaluator
``evaluate(values) -> list of outputs``; :class:`~symkin.numeric.function.NumericFunction`
wraps it.  Adding a backend means adding a class and a key.

========  ==========================================  =====================
key       what                                        precision
========  ==========================================  =====================
numpy     vectorised NumPy, cse, in chunks            float64 or float32
numba     one fused compiled loop per call, threads   float64 or float32
mpmath    arbitrary precision, point by point         ``digits`` digits
exact     rational arithmetic (fractions.Fraction)    exact
========  ==========================================  =====================

    >>> sorted(BACKENDS)
    ['exact', 'mpmath', 'numba', 'numpy']
"""

from __future__ import annotations

import contextlib
import math
import os
import threading
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import InputError, PoleError, PrecisionWarning, UnsupportedError
from symkin.numeric import runtime
from symkin.numeric.codegen import (
    KERNEL_BLOCK,
    ExactPrinter,
    FloatPrinter,
    ScalarPrinter,
    kernel_source,
    phase_sources,
    product_ratios,
)
from symkin.numeric.stable import ExactRatio, plain_form
from symkin.values import refuse_text

__all__ = ["Plan", "BACKENDS", "NumpyBackend", "NumbaBackend", "MpmathBackend", "ExactBackend", "numba_available"]

_INT64_SAFE = 2**62
_FLOAT_INT = 2**1023  # Python integers below this convert to finite floats
_THREADS_FROM = 1 << 15  # fewer points are evaluated on the calling thread
_POOLS: dict[int, Any] = {}


def _pool(threads: int) -> Any:
    """A process-wide pool of ``threads`` threads (NumPy ufuncs release the GIL)."""
    from concurrent.futures import ThreadPoolExecutor

    if threads not in _POOLS:
        _POOLS[threads] = ThreadPoolExecutor(max_workers=threads, thread_name_prefix="symkin")
    return _POOLS[threads]


@dataclass(frozen=True)
class Plan:
    """What to compile: the laws as given, their stable forms, and the options."""

    exprs: tuple[sp.Expr, ...]  # as given
    stable: tuple[sp.Expr, ...]  # rewritten (float backends) or as given
    args: tuple[sp.Symbol, ...]
    names: tuple[str, ...]
    precision: str
    digits: int | None
    cse: bool
    chunk: int
    threads: int | None

    @property
    def dtype(self) -> Any:
        """The NumPy float type of the plan's precision (float32 or float64)."""
        return np.float32 if self.precision == "float32" else np.float64


# --------------------------------------------------------------------------- inputs
#: What each refused NumPy dtype kind holds, for the error message.
_KIND_WORDS = {"c": "complex", "b": "boolean", "U": "text", "S": "bytes", "M": "date", "m": "time-span", "V": "raw"}
_INT64_MAX = np.iinfo(np.int64).max
_INT64 = np.dtype(np.int64)
_FLOAT64 = np.dtype(np.float64)


def _refusal(name: str, got: str, integer: bool) -> InputError:
    if integer:
        return InputError(f"{name} is a tooth number (an integer), got {got}; give whole numbers below 2^63 in magnitude")
    return InputError(f"{name} must be a real number or an array of them, got {got}; give int or float values")


def _describe(v: Any) -> str:
    text = repr(v)
    return text if len(text) <= 40 else text[:37] + "..."


def _real_item(v: Any, name: str) -> float:
    """One element of an object array as a Python float, or an InputError."""
    if v is None or isinstance(v, (bool, np.bool_, complex, np.complexfloating, str, bytes)):
        raise _refusal(name, _describe(v), False)
    try:
        return float(v)  # Fraction, Decimal, SymPy and mpmath reals; a SymPy symbol or I raises
    except (TypeError, ValueError, OverflowError):
        raise _refusal(name, _describe(v), False) from None


def _integer_item(v: Any, name: str) -> int:
    """One element of an object array as a Python int, or an InputError."""
    if isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_)):
        return int(v)
    if v is None or isinstance(v, (bool, np.bool_, complex, np.complexfloating, str, bytes)):
        raise _refusal(name, _describe(v), True)
    try:
        as_int = int(v)
        whole = as_int == v
    except (TypeError, ValueError, OverflowError):
        whole = False
    if not whole:
        raise _refusal(name, _describe(v), True)
    return as_int


def _as_integers(a: np.ndarray, name: str) -> np.ndarray:
    """Tooth numbers as int64, or as Python integers (object) when int64 cannot hold them.

    Float arrays cost one cast and one comparison (a value that is not whole, nan or
    infinite fails the comparison); booleans, complex numbers, text and None are refused."""
    kind = a.dtype.kind
    if kind == "i":
        return a.astype(np.int64, copy=False)
    if kind == "u":
        if a.dtype.itemsize == 8 and a.size and a.max() > _INT64_MAX:
            return a.astype(object)
        return a.astype(np.int64)
    if kind == "f":
        with np.errstate(invalid="ignore"):
            ints = a.astype(np.int64)
        if (ints == a).all():
            return ints
        bad = a.reshape(-1)[np.flatnonzero(ints.reshape(-1) != a.reshape(-1))[0]]
        raise _refusal(name, f"{float(bad)!r}", True)
    if kind == "O":
        values = [_integer_item(v, name) for v in a.reshape(-1)]
        if all(-_INT64_MAX <= v <= _INT64_MAX for v in values):
            return np.array(values, dtype=np.int64).reshape(a.shape)
        out = np.empty(len(values), dtype=object)
        out[:] = values
        return out.reshape(a.shape)
    raise _refusal(name, f"{_KIND_WORDS.get(kind, a.dtype.name)} values", True)


def _as_floats(a: np.ndarray, name: str, dtype: Any) -> np.ndarray:
    """Real inputs in the working precision; complex, boolean, text and None are refused
    (a complex value would lose its imaginary part, None would become nan)."""
    kind = a.dtype.kind
    if kind in "fiu":
        return a.astype(dtype, copy=False)
    if kind == "O":
        out = np.empty(a.shape, dtype=dtype)
        out.reshape(-1)[:] = [_real_item(v, name) for v in a.reshape(-1)]
        return out
    raise _refusal(name, f"{_KIND_WORDS.get(kind, a.dtype.name)} values", False)


def as_array(v: Any, name: str) -> np.ndarray:
    """``np.asarray(v)``, with ragged nested lists refused as an InputError."""
    if isinstance(v, np.ndarray):
        return v
    try:
        return np.asarray(v)
    except (ValueError, TypeError):
        raise InputError(f"{name} must be a number or a rectangular array of numbers, got {_describe(v)}") from None


def common_shape(values: Sequence[np.ndarray], names: Sequence[str]) -> tuple[int, ...]:
    """The shape the arguments broadcast to (an InputError when they do not)."""
    shape = values[0].shape if values else ()
    if all(v.shape == shape for v in values):
        return shape
    try:
        return np.broadcast_shapes(*(v.shape for v in values))
    except ValueError:
        shapes = ", ".join(f"{n} {v.shape}" for n, v in zip(names, values))
        raise InputError(f"the argument arrays do not broadcast to one shape ({shapes}); give arrays of matching shapes") from None


def broadcast_flat(values: Sequence[np.ndarray], names: Sequence[str]) -> tuple[tuple[int, ...], list[np.ndarray]]:
    """The common shape and each value as a flat array of that size, or a 0-d scalar."""
    shape = common_shape(values, names)
    n = math.prod(shape)
    flat: list[np.ndarray] = []
    for v in values:
        if (v.size == 1 and n != 1) or v.ndim == 0:
            flat.append(v.reshape(()))
        elif v.shape == shape:
            flat.append(np.ascontiguousarray(v).reshape(-1))
        else:
            flat.append(np.ascontiguousarray(np.broadcast_to(v, shape)).reshape(-1))
    return shape, flat


def _own(r: Any, shape: tuple[int, ...], dtype: Any, inputs: Sequence[np.ndarray]) -> np.ndarray:
    """One output of the generated code as a fresh array of ``shape`` and ``dtype`` (a
    constant law gives a number, a law ``x`` gives its input back)."""
    r = np.asarray(r)
    if r.dtype != dtype:
        return np.broadcast_to(r, shape).astype(dtype)
    if r.shape != shape:
        return np.broadcast_to(r, shape).copy()
    if r.base is not None or any(r is a for a in inputs):
        return r.copy()
    return r


def _all_finite(results: Sequence[np.ndarray]) -> bool:
    """True when every value is finite.  A finite sum (one pass, no temporary: an inf or
    nan makes the sum inf or nan) proves it; otherwise (a non-finite value, or a sum of
    huge values overflowing) each value is checked.  (A BLAS dot, used before, took 14 ms
    instead of 0.02 ms for 16384 points on a busy 2-core machine: OpenBLAS threads.)"""
    with np.errstate(over="ignore", invalid="ignore"):  # a sum of huge finite values overflows: checked below
        return _finite(results)


def _finite(results: Sequence[np.ndarray]) -> bool:
    """:func:`_all_finite` for a caller inside ``np.errstate(all="ignore")``."""
    return all(math.isfinite(np.add.reduce(r, axis=None)) or np.isfinite(r).all() for r in results)


_PRIMED: list[bool] = []
_PRIME_FROM = 1 << 13  # points: below this a call's temporaries stay under 64 KiB


def _prime_allocator() -> None:
    """Free one 16 MiB block once per process, so that the C allocator keeps the temporaries of
    large calls instead of returning them to the system after each operation.

    glibc's malloc maps blocks of 128 KiB and more on their own and unmaps them when freed, and
    gives freed memory above 128 KiB at the top of its heap back to the system; each temporary
    of a large call then costs page faults (about 5 ns per point instead of 0.3-1 ns).  glibc
    raises both thresholds when a mapped block of up to 32 MiB is freed -- what any NumPy
    program does once it frees a 16 MiB array; a process that has not (one that only made
    80 MB arrays) evaluated the II differential at 10^7 points in 270 ms instead of 83 ms
    (lambdify: 134-143 ms, same process).  Untouched pages: no memory is written.  Other
    allocators ignore it."""
    if not _PRIMED:
        _PRIMED.append(True)
        np.empty(1 << 21)  # 16 MiB, allocated and freed at once (never touched)


# --------------------------------------------------------------------------- numpy
class NumpyBackend:
    """Vectorised NumPy code (``sympy.lambdify`` with a printer for the stable forms),
    evaluated in chunks so that temporaries stay small and are reused."""

    key = "numpy"
    precisions = ("float64", "float32")
    floats = True  # evaluates stable forms in binary floating point

    def __init__(self, plan: Plan):
        self.plan = plan
        self.integer_syms = self._exact_integer_symbols(plan)
        self.twins = {s: sp.Symbol(f"_int_{s.name}", integer=True) for s in self.integer_syms}
        exprs = [self._twin(e) for e in plan.stable]
        printer = FloatPrinter(plan.precision)
        self.phases = {name: runtime.dd_function(text, name) for name, text in phase_sources(plan.stable).items()}
        # the printer writes every NumPy name as numpy.<name>: the module itself is the namespace
        # ("numpy" would run `from numpy import *`, which imports numpy.f2py: ~0.1 s per process)
        modules = [{**runtime.NAMESPACE[plan.precision], **self.phases, "numpy": np}]
        target = product_ratios(exprs) if plan.precision == "float64" else list(exprs)
        self.func = sp.lambdify(
            list(plan.args) + list(self.twins.values()), target, modules=modules, printer=printer, cse=plan.cse, docstring_limit=0
        )
        self.source = _lambdify_source(self.func)
        self.polys = [a for e in plan.stable for node in sp.preorder_traversal(e) if isinstance(node, ExactRatio) for a in node.args]
        index = {sym: k for k, sym in enumerate(self.integer_syms)}
        self.bound_terms = []  # per polynomial: (|coefficient|, ((integer argument, power), ...)) per term
        for poly in self.polys:
            terms = []
            for term in sp.Add.make_args(sp.expand(poly)):
                c, factors = term.as_coeff_mul()
                terms.append((abs(int(c)), tuple((index[f.as_base_exp()[0]], int(f.as_base_exp()[1])) for f in factors)))
            self.bound_terms.append(terms)
        outside = set()
        for e in plan.stable:
            outside |= e.replace(lambda n: isinstance(n, ExactRatio), lambda n: sp.Integer(1)).free_symbols
        self.float_used = tuple(s in outside for s in plan.args)
        self.names = [s.name for s in plan.args]
        self.integer_flags = tuple(s in self.twins for s in plan.args)
        self.dtype = plan.dtype
        self._np_dtype = np.dtype(plan.dtype)  # (arrays of it carry this very object: compared by identity)

    # ------------------------------------------------------------------ one point
    _scalar_code: Any = None  # built on the first scalar call; False where it cannot be
    scalar_types_checked = True  # evaluate_scalar takes any values and returns None for what it cannot take

    def _build_scalar(self) -> Any:
        """The laws as Python code on floats (``math``) for one float64 point, or False."""
        if self.plan.precision != "float64":
            return False
        try:
            exprs = product_ratios([self._twin(e) for e in self.plan.stable])  # (as the array code: the same roundings)
            return sp.lambdify(
                list(self.plan.args) + list(self.twins.values()), exprs,
                modules=[{**runtime.SCALAR_NAMESPACE, **self.phases, "math": math}, "math"], printer=ScalarPrinter({"strict": True}),
                cse=self.plan.cse, docstring_limit=0,
            )
        except Exception:  # a function the math module lacks: arrays only
            return False

    def evaluate_scalar(self, values: Sequence[Any]) -> list[Any] | None:
        """The outputs at one point given as Python or NumPy float64 numbers, without
        arrays (about 1-2 us); None when this point needs the array path (another input
        type, a value that is not finite, an output that is not: the array path checks,
        converts and reports)."""
        code = self._scalar_code
        if code is None:
            code = self._scalar_code = self._build_scalar()
        if code is False:
            return None
        if not self.twins:  # real inputs only: floats pass as they are (one type test each)
            for v in values:
                kind = type(v)
                if kind is not float and kind is not np.float64:
                    break
            else:
                try:
                    out = code(*values)
                except (ArithmeticError, ValueError, TypeError):
                    return None
                return self._scalar_results(out)
        floats = []
        ints = []
        for v, integer in zip(values, self.integer_flags):
            kind = type(v)
            if kind is float or kind is np.float64:
                x = v
            elif kind is int:
                if not -_FLOAT_INT < v < _FLOAT_INT:
                    return None
                x = float(v)
            else:
                return None
            floats.append(x)
            if integer:  # a tooth number: its exact integer value too
                if kind is int:
                    ints.append(v)
                elif x.is_integer() and abs(x) < 2.0**63:
                    ints.append(int(x))
                else:
                    return None
        try:
            out = code(*floats, *ints)
        except (ArithmeticError, ValueError, TypeError):  # a pole or a domain error: reported by the array path
            return None
        return self._scalar_results(out)

    @staticmethod
    def _scalar_results(out: Sequence[Any]) -> list[Any] | None:
        """The outputs of the scalar code as NumPy float64 numbers, or None where one is not a
        finite real (the array path then says what it is)."""
        results = []
        for r in out:
            if type(r) is not float:
                if type(r) is int or isinstance(r, float):
                    r = float(r)
                else:  # a complex number from x**(1/3) of a negative x: the array path says nan
                    return None
            if not math.isfinite(r):
                return None
            results.append(np.float64(r))
        return results

    @staticmethod
    def _exact_integer_symbols(plan: Plan) -> tuple[sp.Symbol, ...]:
        used: set[sp.Symbol] = set()
        for e in plan.stable:
            for node in sp.preorder_traversal(e):
                if isinstance(node, ExactRatio):
                    used |= node.free_symbols
        return tuple(s for s in plan.args if s in used)

    def _twin(self, e: sp.Expr) -> sp.Expr:
        if not self.twins:
            return e
        return e.replace(lambda n: isinstance(n, ExactRatio), lambda n: n.xreplace(self.twins))

    def prepare(self, values: Sequence[Any]) -> tuple[tuple[int, ...], list[np.ndarray], list[np.ndarray]]:
        """The common shape, the float inputs and the integer inputs, flat.

        Integer inputs given as float arrays stay floats here: :meth:`integer_chunk`
        checks and converts them chunk by chunk, while the chunk is in cache."""
        plan = self.plan
        arrays = [as_array(v, s.name) for v, s in zip(values, plan.args)]
        floats, int_list = [], []
        placeholder = self._placeholder
        for a, s, used in zip(arrays, plan.args, self.float_used):
            if s not in self.twins:
                floats.append(_as_floats(a, s.name, plan.dtype))
                continue
            i = a if a.dtype.kind == "f" and a.ndim else _as_integers(a, s.name)
            int_list.append(i)
            if not used:  # only its exact integer value is needed: a 0-d zero that takes no part in the broadcast
                floats.append(placeholder)
            elif i.dtype.kind == "f":
                floats.append(i.astype(plan.dtype, copy=False))
            else:
                floats.append(np.asarray(i, dtype=np.float64).astype(plan.dtype, copy=False))
        real = [k for k, f in enumerate(floats) if f is not placeholder]
        shape, flat = broadcast_flat([floats[k] for k in real] + int_list,
                                     [plan.args[k].name for k in real] + [s.name for s in self.twins])
        out = [placeholder] * len(floats)
        for j, k in enumerate(real):
            out[k] = flat[j]
        return shape, out, flat[len(real):]

    def _prepare_flat(self, values: Sequence[Any]) -> tuple[tuple[int, ...], list[np.ndarray], list[np.ndarray]] | None:
        """:meth:`prepare` for the common call, without its conversions: every tooth number an
        int64 array and every other input a float array of the working type, all of one flat
        contiguous shape; None otherwise."""
        shape = None
        floats: list[np.ndarray] = []
        ints: list[np.ndarray] = []
        dt = self._np_dtype
        for v, integer, used in zip(values, self.integer_flags, self.float_used):
            if type(v) is not np.ndarray or v.ndim != 1 or v.strides[0] != v.itemsize:  # (flat, contiguous)
                return None
            if shape is None:
                shape = v.shape
            elif v.shape != shape:
                return None
            if integer:
                if v.dtype is not _INT64:
                    return None
                ints.append(v)
                floats.append(v.astype(self.dtype) if used else self._placeholder)
            elif v.dtype is dt:
                floats.append(v)
            else:
                return None
        return (shape, floats, ints) if shape is not None else None

    @property
    def _placeholder(self) -> np.ndarray:
        value = self.__dict__.get("_zero")
        if value is None:
            value = self.__dict__["_zero"] = np.zeros((), dtype=self.plan.dtype)
            value.flags.writeable = False
        return value

    def integer_chunk(self, ints: Sequence[np.ndarray]) -> list[np.ndarray]:
        """Integer inputs of one chunk as int64 (float arrays checked and cast here), or
        as Python integers where an integer polynomial could overflow int64."""
        part = [_as_integers(i, s.name) if i.dtype.kind == "f" else i for i, s in zip(ints, self.twins)]
        if self.needs_python_integers(part):
            part = [np.asarray(i).astype(object) for i in part]
        return part

    def needs_python_integers(self, ints: Sequence[np.ndarray]) -> bool:
        """True when an integer polynomial could overflow int64 for these inputs."""
        if not self.bound_terms or not ints:
            return False
        if any(i.dtype.kind == "O" for i in ints):
            return True
        # one reduction per array: the bitwise or of values that are all >= 0 is >= 0 and bounds
        # their maximum (below twice it); where that bound is too coarse, |z| and its maximum
        if len(ints) > 1 and ints[0].size <= 4096 and all(i.dtype is _INT64 and i.ndim == 1 for i in ints):
            # small arrays: one reduction of them all (a reduction's call costs more than its work)
            one = int(np.bitwise_or.reduce(np.concatenate(ints), axis=None))
            big = [one] * len(ints)
        else:
            big = [int(np.bitwise_or.reduce(i, axis=None)) if i.size and i.dtype.kind in "iu" else -1 for i in ints]
        if any(b < 0 for b in big) or self._over_bound(big):
            # |z| from the extremes in Python integers (np.abs wraps -2^63 to itself in int64)
            big = [max(int(i.max()), -int(i.min())) if i.size else 0 for i in ints]
            return self._over_bound(big)
        return False

    def _over_bound(self, big: Sequence[int]) -> bool:
        """True when some integer polynomial may reach 2^62 for inputs bounded by ``big`` (the
        answer for the last bounds is remembered: calls with like inputs repeat them)."""
        key = tuple(big)
        memo = self.__dict__.get("_bound_memo")
        if memo is not None and memo[0] == key:
            return memo[1]
        over = self._over_bound_of(big)
        self.__dict__["_bound_memo"] = (key, over)  # one assignment: another thread sees the old pair or the new one
        return over

    def _over_bound_of(self, big: Sequence[int]) -> bool:
        for terms in self.bound_terms:
            bound = 0
            for coeff, powers in terms:
                mag = coeff
                for k, e in powers:
                    mag *= big[k] ** e
                bound += mag
            if bound >= _INT64_SAFE:
                return True
        return False

    def run(self, floats: Sequence[Any], ints: Sequence[Any]) -> list[Any]:
        """Call the generated function on float and integer arguments with NumPy's floating-point warnings off (non-finite results are flagged by the caller)."""
        with np.errstate(all="ignore"):
            out = self.func(*floats, *ints)
        return list(out)

    def evaluate(
        self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None
    ) -> tuple[tuple[int, ...], list[np.ndarray], bool]:
        """``(shape, outputs, flagged)``: the outputs (flat, or of ``shape``) and whether
        any of their values is not finite."""
        plan = self.plan
        if not self.twins:  # real inputs only
            names, dtype, dt = self.names, self.dtype, self._np_dtype
            floats: list[Any] = []
            shape = None
            same = True  # every array of one shape (the common call): no broadcasting to decide
            wide = dtype is np.float64
            for v, nm in zip(values, names):
                kind = type(v)
                if wide and (kind is float or kind is np.float64):
                    # a number stays a NumPy number (IEEE: x/0 is inf, not an exception): its arithmetic
                    # in the generated code is cheaper than a 0-d array's ufunc call per operation
                    floats.append(np.float64(v))
                    continue
                if kind is not np.ndarray or v.dtype is not dt:
                    v = _as_floats(as_array(v, nm), nm, dtype)
                floats.append(v)
                if shape is None:
                    shape = v.shape
                elif v.shape != shape:
                    same = False
            if shape is None:
                shape = ()
            elif not same:
                shape = common_shape([f for f in floats if type(f) is np.ndarray],
                                     [nm for f, nm in zip(floats, names) if type(f) is np.ndarray])
            n = math.prod(shape)
            if n > _PRIME_FROM and not _PRIMED:
                _prime_allocator()
            if outs is None and n <= plan.chunk:
                # one call on the arrays as given: no copies, no chunks, one finiteness pass
                with np.errstate(all="ignore"):
                    results = self.func(*floats)
                    finite = True
                    for k, r in enumerate(results):
                        # (a fresh array of the call's shape is the output as it is; see _own)
                        if type(r) is not np.ndarray or r.dtype is not dt or r.shape != shape or r.base is not None or any(r is a for a in floats):
                            r = results[k] = _own(r, shape, dtype, floats)
                        if finite and not math.isfinite(np.add.reduce(r, axis=None)):
                            finite = bool(np.isfinite(r).all())
                    return shape, results, not finite
            shape, floats = broadcast_flat([np.asarray(f, dtype) for f in floats], names)
            ints: list[np.ndarray] = []
        else:
            shape, floats, ints = self._prepare_flat(values) or self.prepare(values)
            n = math.prod(shape)
            if n > _PRIME_FROM and not _PRIMED:
                _prime_allocator()
            if outs is None and n <= plan.chunk:
                ints = self.integer_chunk(ints)
                flat_shape = (n,) if shape else ()
                dt = self._np_dtype
                with np.errstate(all="ignore"):  # one context for the call and its finiteness pass
                    results = self.func(*floats, *ints)
                    finite = True
                    for k, r in enumerate(results):
                        # (a fresh array of the call's shape is the output as it is; see _own)
                        if type(r) is not np.ndarray or r.dtype is not dt or r.shape != flat_shape or r.base is not None or any(
                            r is a for a in floats) or any(r is a for a in ints):
                            r = results[k] = _own(r, flat_shape, plan.dtype, floats + ints)
                        if finite and not math.isfinite(np.add.reduce(r, axis=None)):
                            finite = bool(np.isfinite(r).all())
                    return shape, results, not finite
        results = _allocate(outs, len(plan.stable), n, plan.dtype)
        chunk = max(1, plan.chunk)
        starts = list(range(0, n, chunk))
        func = self.func

        def work(block: Sequence[int]) -> bool:
            flagged = False
            with np.errstate(all="ignore"):  # one context for the block: non-finite outputs are flagged here
                for start in block:
                    stop = min(n, start + chunk)
                    part = [f[start:stop] if f.ndim else f for f in floats]
                    if ints:  # tooth numbers checked (one bitwise-or reduction each) while the chunk is in cache
                        out = func(*part, *self.integer_chunk([i[start:stop] if i.ndim else i for i in ints]))
                    else:
                        out = func(*part)
                    for o, r in zip(results, out):
                        seg = o[start:stop]
                        seg[...] = r
                        # a finite sum (one pass, no temporary) proves every value finite
                        if not flagged and not (math.isfinite(np.add.reduce(seg, axis=None)) or np.isfinite(seg).all()):
                            flagged = True
            return flagged

        threads = min(plan.threads or 1, len(starts))
        if threads > 1 and n >= _THREADS_FROM:
            per = -(-len(starts) // threads)  # contiguous blocks of chunks, one per thread
            blocks = [starts[k * per:(k + 1) * per] for k in range(threads)]
            flagged = any(_pool(threads).map(work, blocks))
        else:
            flagged = work(starts)
        return shape, results, flagged

    def evaluate_points(self, values: Sequence[Any], index: np.ndarray) -> list[np.ndarray]:
        """Re-evaluate a few points (given by flat index) with Python integers."""
        _shape, floats, ints = self.prepare(values)
        take = lambda a: a[index] if a.ndim else a  # noqa: E731
        ints = [i.astype(object) for i in self.integer_chunk([take(i) for i in ints])]
        part = self.run([take(f) for f in floats], ints)
        return [np.broadcast_to(np.asarray(r, dtype=self.plan.dtype), index.shape) for r in part]


def _allocate(outs: Sequence[np.ndarray] | None, count: int, n: int, dtype: Any) -> list[np.ndarray]:
    if outs is None:
        return [np.empty(n, dtype=dtype) for _ in range(count)]
    outs = list(outs)
    if len(outs) != count:
        raise InputError(f"out= needs {count} arrays, one per output, got {len(outs)}")
    flat = []
    for o in outs:
        if not isinstance(o, np.ndarray) or o.size != n or o.dtype != dtype or not o.flags.c_contiguous:
            raise InputError(f"each out= array must be a C-contiguous {np.dtype(dtype).name} array of {n} elements")
        flat.append(o.reshape(-1))
    return flat


def _lambdify_source(func: Callable[..., Any]) -> str:
    import inspect

    try:
        return inspect.getsource(func)
    except (OSError, TypeError):  # pragma: no cover
        return ""


# --------------------------------------------------------------------------- numba
def numba_available() -> bool:
    """True when Numba can be imported."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


_NUMBA_LOCK = threading.Lock()
_PARALLEL_FROM = 1 << 15
#: Held while a parallel kernel runs: one at a time, each on every thread (calls from several
#: threads at once, as a Dask scheduler's, would oversubscribe the cores, and Numba's workqueue
#: threading layer, where no OpenMP is found, aborts on them).
_PARALLEL_LOCK = threading.Lock()


def _passive_openmp() -> None:
    """Ask OpenMP threads to sleep rather than spin while they wait, unless the user
    chose otherwise.  With GNU OpenMP's default (spin, then sleep) a parallel loop on a
    busy 2-core machine took 16-32 ms per call instead of 0.03 ms (benchmarks/run.py).
    Must run before Numba first loads its OpenMP pool; only OMP_WAIT_POLICY is touched."""
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")


def kernel_cache_folder() -> Path | None:
    """Where compiled Numba kernels are kept between processes: ``$SYMKIN_CACHE_DIR``, or
    ``symkin/kernels`` in ``$XDG_CACHE_HOME`` (default ``~/.cache``); None when it cannot
    be created (kernels are then compiled in each process)."""
    base = os.environ.get("SYMKIN_CACHE_DIR")
    folder = Path(base) if base else Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "symkin" / "kernels"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return folder if os.access(folder, os.W_OK) else None


_KERNEL_MODULE = """# generated by symkin.numeric.backends: a compiled law's loop, cached by Numba beside this file
import numpy
from numba import njit, prange

from symkin.numeric.runtime import numba_namespace as _namespace

globals().update(_namespace({precision!r}))
_F = numpy.{precision}

{source}
_jit = njit(parallel={parallel}, error_model="numpy", fastmath=False, nogil=True, cache=True)(_kernel)
_jit_redo = (njit(parallel={parallel}, error_model="numpy", fastmath=False, nogil=True, cache=True)(_kernel_redo)
             if "_kernel_redo" in globals() else None)  # compiled on its first call
"""


def _kernel_from_file(source: str, precision: str, parallel: bool) -> Any:
    """The kernel of ``source`` and its redo pass (or None) jitted with ``cache=True`` from a
    module file named by its digest (Numba caches only functions defined in files), or None
    without a cache folder."""
    import hashlib
    import importlib.util
    import sys

    import numba

    folder = kernel_cache_folder()
    if folder is None:
        return None
    text = _KERNEL_MODULE.format(precision=precision, source=source, parallel=parallel)
    digest = hashlib.sha256(f"{numba.__version__}\n{text}".encode()).hexdigest()[:32]
    name = f"symkin_kernel_{digest}"
    if name in sys.modules:
        return sys.modules[name]._jit, sys.modules[name]._jit_redo
    path = folder / f"{name}.py"
    try:
        if not path.exists() or path.read_text() != text:
            # written whole under a private name, then renamed: another process never reads half a file
            import tempfile

            fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".py", dir=folder)
            try:
                with os.fdopen(fd, "w") as f:
                    f.write(text)
                os.replace(tmp, path)
            finally:
                if os.path.exists(tmp):
                    os.unlink(tmp)
    except OSError:
        return None
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:  # pragma: no cover - a .py file always has a loader
        return None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # Numba caches functions whose globals are a module's
    try:
        spec.loader.exec_module(module)
    except Exception:
        del sys.modules[name]
        raise
    return module._jit, module._jit_redo


class NumbaBackend(NumpyBackend):
    """One fused loop per call, compiled by Numba (``parallel=True`` over the available
    threads for large calls); integer parts in int64, checked in the loop for overflow,
    and re-evaluated with Python integers where int64 could overflow."""

    key = "numba"

    def __init__(self, plan: Plan):
        _passive_openmp()
        super().__init__(plan)  # the NumPy code re-evaluates flagged points exactly
        self.kernels: dict[tuple[bool, tuple[bool, ...]], Any] = {}
        self.broken = False
        self.kernel_sources: dict[tuple[bool, tuple[bool, ...]], str] = {}
        self.namespace = runtime.numba_namespace(plan.precision)
        #: the type each argument's array has in the common call (int64 for tooth numbers)
        self._wanted = tuple(_INT64 if integer else self._np_dtype for integer in self.integer_flags)
        #: argument -> (value, block of copies of it), the last scalar given there
        self._blocks: dict[int, tuple[Any, np.ndarray]] = {}
        self._outputs = len(plan.stable)
        #: the key of the serial kernel of int64 and float inputs (the common small call's)
        self._serial_key = (False, (False,) * len(plan.args))

    def _kernel(self, parallel: bool, float_integers: tuple[bool, ...] = ()) -> Any:
        """The compiled loop and its redo pass (or None): one per law, threading and float
        tooth arrays, for every mix of scalar and array arguments (a step of 0 or 1 each),
        cached on disk (see :func:`_kernel_from_file`) so that another process loads it
        instead of compiling."""
        key = (parallel, float_integers)
        if key not in self.kernels:
            import numba

            plan = self.plan
            integer = tuple(s in self.twins for s in plan.args)
            scalar = (False,) * len(plan.args)
            src = kernel_source(plan.stable, plan.args, integer, scalar, plan.precision, plan.cse, float_integers, steps=True)
            self.kernel_sources[key] = src
            with _NUMBA_LOCK:
                kernel = _kernel_from_file(src, plan.precision, parallel)
                if kernel is None:  # no writable cache folder: compiled in this process only
                    ns: dict[str, Any] = {"numpy": np, "prange": numba.prange, "_F": plan.dtype, **self.namespace}
                    exec(compile(src, "<symkin kernel>", "exec"), ns)  # generated from SymPy, no user text
                    jit = numba.njit(parallel=parallel, error_model="numpy", fastmath=False, nogil=True)
                    kernel = jit(ns["_kernel"]), (jit(ns["_kernel_redo"]) if "_kernel_redo" in ns else None)
                self.kernels[key] = kernel
        return self.kernels[key]

    @property
    def source(self) -> str:
        """The generated kernel source (the first kernel compiled), or a note that it is compiled on first call."""
        return next(iter(self.kernel_sources.values()), "(compiled on first call)")

    @source.setter
    def source(self, value: str) -> None:
        pass

    def _common_call(self, values: Sequence[Any]) -> tuple[int, list[np.ndarray], list[int]] | None:
        """``(n, inputs, steps)`` for the common call, without conversions: every argument a
        flat contiguous array of one length (int64 for tooth numbers, the working float type
        otherwise) or, in float64, a float for a real argument, given to the kernel as a block of
        :data:`KERNEL_BLOCK` copies of it (the block of the last call kept when the number is the
        same, its sign of zero too: a parameter held while an array sweeps); None for any other call."""
        n = -1
        inputs: list[np.ndarray] = []
        steps: list[int] = []
        blocks = self._blocks
        for k, (v, want) in enumerate(zip(values, self._wanted)):
            kind = type(v)
            if kind is np.ndarray:
                if v.dtype is not want or v.ndim != 1 or v.strides[0] != v.itemsize:
                    return None
                if n < 0:
                    n = v.shape[0]
                elif v.shape[0] != n:
                    return None
                inputs.append(v)
                steps.append(1)
            elif want is _FLOAT64 and (kind is float or kind is np.float64):
                held = blocks.get(k)
                if held is None or not (held[0] is v or (held[0] == v and math.copysign(1.0, held[0]) == math.copysign(1.0, v))):
                    held = blocks[k] = (v, np.full(KERNEL_BLOCK, v, dtype=np.float64))
                inputs.append(held[1])
                steps.append(0)
            else:
                return None
        return (n, inputs, steps) if n >= 0 else None

    def evaluate(
        self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None
    ) -> tuple[tuple[int, ...], list[np.ndarray], bool]:
        """Evaluate the laws at ``values`` in one fused loop; returns the broadcast shape, the outputs and whether any is not finite."""
        if self.broken:
            return super().evaluate(values, outs)
        plan = self.plan
        common = self._common_call(values) if outs is None else None
        serial = self.kernels.get(self._serial_key)
        if common is not None and serial is not None and common[0] < _PARALLEL_FROM:
            # the common small call: the serial kernel compiled, nothing to convert or switch
            n, inputs, steps = common
            results = [np.empty(n, self._np_dtype) for _ in range(self._outputs)] if self._outputs > 1 else [np.empty(n, self._np_dtype)]
            bad, nonwhole, uncertain = serial[0](*inputs, *results, n, *steps)
            if not (bad or uncertain):
                return (n,), results, False
            # (else poles, or differences of products to redo: the general path below, again)
        if common is not None:
            n, inputs, steps = common
            shape: tuple[int, ...] = (n,)
            float_integers = (False,) * len(inputs)
            results = [np.empty(n, dtype=plan.dtype) for _ in plan.stable]
            flat: list[np.ndarray] = inputs
        else:
            arrays = [as_array(v, s.name) for v, s in zip(values, plan.args)]
            conv = [
                (a if a.dtype.kind == "i" or (a.dtype == np.float64 and a.ndim) else _as_integers(a, s.name))
                if integer else _as_floats(a, s.name, plan.dtype)
                for a, s, integer in zip(arrays, plan.args, self.integer_flags)
            ]  # narrow signed integers pass as they are (Numba computes integer products in int64), float64
            # tooth arrays too (checked and cast in the loop)
            if any(c.dtype == object for c in conv):
                return super().evaluate(values, outs)
            shape, flat = broadcast_flat(conv, self.names)
            n = math.prod(shape)
            results = _allocate(outs, len(plan.stable), n, plan.dtype)
            flat = [_as_integers(f, s.name) if f.ndim == 0 and f.dtype.kind == "f" and integer else f
                    for f, s, integer in zip(flat, plan.args, self.integer_flags)]
            float_integers = tuple(f.dtype.kind == "f" and integer for f, integer in zip(flat, self.integer_flags))
            inputs = [np.full(min(n, KERNEL_BLOCK), f) if f.ndim == 0 else f for f in flat]  # a scalar: a block of copies
            steps = [0 if f.ndim == 0 else 1 for f in flat]
        import numba

        parallel = n >= _PARALLEL_FROM and (plan.threads or numba.get_num_threads()) > 1
        switch = False
        if parallel and plan.threads:
            before = numba.get_num_threads()
            switch = plan.threads != before
        try:
            kernel, redo = self.kernels.get((parallel, float_integers)) or self._kernel(parallel, float_integers)
            if switch:
                # numba.core.config defines its settings at run time (globals().update), which
                # numba's inline types (py.typed) do not show
                numba.set_num_threads(min(plan.threads, numba.config.NUMBA_NUM_THREADS))  # type: ignore[attr-defined]
            with _PARALLEL_LOCK if parallel else contextlib.nullcontext():
                bad, nonwhole, uncertain = kernel(*inputs, *results, n, *steps)
                if uncertain:  # points near a pole: their differences of products again, in double-double
                    bad += redo(*inputs, *results, n, *steps)
        except numba.core.errors.NumbaError as err:  # a construct Numba cannot compile: NumPy instead
            self.broken = True
            warnings.warn(
                f"numba could not compile {', '.join(plan.names)} ({type(err).__name__}); evaluating it with NumPy instead",
                PrecisionWarning,
                stacklevel=4,
            )
            return super().evaluate(values, outs)
        finally:
            if switch:
                numba.set_num_threads(before)
        if nonwhole:  # the message names the first value that is not a whole number
            for f, s, as_float in zip(flat, plan.args, float_integers):
                if as_float:
                    _as_integers(f, s.name)
        if bad and self.twins:
            index = np.flatnonzero(np.logical_or.reduce([~np.isfinite(r) for r in results]))
            fixed = self.evaluate_points(values, index)
            for r, f in zip(results, fixed):
                r[index] = f
        return shape, results, bool(bad)


# --------------------------------------------------------------------------- mpmath
def _to_mpf(v: Any, name: str) -> Any:
    import mpmath

    if isinstance(v, (mpmath.mpf, mpmath.mpc)):
        return v
    if isinstance(v, (bool, np.bool_)):
        raise InputError(f"{name} must be a number, got {v!r}")
    if isinstance(v, (int, np.integer)):
        return mpmath.mpf(int(v))
    if isinstance(v, (float, np.floating)):
        return mpmath.mpf(float(v))  # the binary value, exactly
    if isinstance(v, Fraction):
        return mpmath.mpf(v.numerator) / v.denominator
    if isinstance(v, sp.Rational):
        return mpmath.mpf(int(v.p)) / int(v.q)
    if isinstance(v, str):
        raise refuse_text(v, name)
    if isinstance(v, sp.Expr) and v.is_number:
        return mpmath.mpf(sp.N(v, mpmath.mp.dps + 5))
    raise InputError(f"{name} must be a number (int, float or Fraction), got {v!r}")


def _object_points(values: Sequence[Any], names: Sequence[str]) -> tuple[tuple[int, ...], list[np.ndarray]]:
    arrays = []
    for v, _nm in zip(values, names):
        a = np.empty((), dtype=object)
        if isinstance(v, (list, tuple, np.ndarray)):
            a = np.asarray(v, dtype=object)
        else:
            a[()] = v
        arrays.append(a)
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays))
    except ValueError:
        raise InputError("the argument arrays do not broadcast to one shape; give arrays of matching shapes") from None
    return shape, [np.broadcast_to(a, shape) for a in arrays]


class MpmathBackend:
    """mpmath at ``digits`` significant digits, point by point (the reference backend)."""

    key = "mpmath"
    precisions = ("mpmath",)
    floats = False

    def __init__(self, plan: Plan):
        self.plan = plan
        exprs = [plain_form(e) for e in plan.exprs]
        self.func = sp.lambdify(list(plan.args), exprs, modules="mpmath", cse=plan.cse, docstring_limit=0)
        self.source = _lambdify_source(self.func)

    def evaluate(
        self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None
    ) -> tuple[tuple[int, ...], list[np.ndarray], bool]:
        """Evaluate the laws at ``values`` point by point with mpmath at the plan's digits; returns the shape, the outputs (object arrays of mpf) and whether any is not finite."""
        import mpmath

        with mpmath.workdps(self.plan.digits or 50):
            return _pointwise(self.plan, self.func, values, _to_mpf, lambda v: v)

    def evaluate_scalar(self, values: Sequence[Any]) -> list[Any]:
        """Evaluate the laws at one point of scalars with mpmath."""
        import mpmath

        with mpmath.workdps(self.plan.digits or 50):
            return _point(self.plan, self.func, values, _to_mpf, lambda v: v)


# --------------------------------------------------------------------------- exact
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


class ExactBackend:
    """Exact rational arithmetic on :class:`fractions.Fraction` (rational laws only)."""

    key = "exact"
    precisions = ("exact",)
    floats = False

    def __init__(self, plan: Plan):
        self.plan = plan
        exprs = [plain_form(e) for e in plan.exprs]
        for e in exprs:
            bad = [n for n in sp.preorder_traversal(e) if not (n.is_Symbol or n.is_Rational or n.is_Add or n.is_Mul or (n.is_Pow and n.exp.is_Integer))]
            if bad:
                raise UnsupportedError(
                    f"the exact backend evaluates rational laws only, and this one contains {bad[0]}; "
                    "use backend='mpmath' with digits=... instead"
                )
        self.func = sp.lambdify(
            list(plan.args), exprs, modules=[{"Fraction": Fraction}], printer=ExactPrinter(), cse=plan.cse, docstring_limit=0
        )
        self.source = _lambdify_source(self.func)

    def evaluate(
        self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None
    ) -> tuple[tuple[int, ...], list[np.ndarray], bool]:
        """Evaluate the laws at ``values`` point by point in exact rationals (:class:`fractions.Fraction`)."""
        return _pointwise(self.plan, self.func, values, _to_fraction, Fraction)

    def evaluate_scalar(self, values: Sequence[Any]) -> list[Any]:
        """Evaluate the laws at one point of scalars in exact rationals."""
        return _point(self.plan, self.func, values, _to_fraction, Fraction)


def _pointwise(
    plan: Plan, func: Any, values: Sequence[Any], convert: Any, result: Any
) -> tuple[tuple[int, ...], list[np.ndarray], bool]:
    """Evaluate ``func`` point by point (object arrays), for the arbitrary-precision backends."""
    names = [s.name for s in plan.args]
    shape, arrays = _object_points(values, names)
    results = [np.empty(shape, dtype=object) for _ in plan.exprs]
    for idx in np.ndindex(shape):
        point = [convert(a[idx], nm) for a, nm in zip(arrays, names)]
        try:
            out = func(*point)
        except ZeroDivisionError:
            raise PoleError(_pole_message(plan, names, point)) from None
        for r, v in zip(results, out):
            r[idx] = result(v)
    return shape, [r.reshape(-1) for r in results], False


def _point(plan: Plan, func: Any, values: Sequence[Any], convert: Any, result: Any) -> list[Any]:
    """One point: scalars in, one value per law out (the arbitrary-precision backends)."""
    point = [convert(v, s.name) for v, s in zip(values, plan.args)]
    try:
        out = func(*point)
    except ZeroDivisionError:
        raise PoleError(_pole_message(plan, [s.name for s in plan.args], point)) from None
    return [v if type(v) is result else result(v) for v in out]


def _pole_message(plan: Plan, names: Sequence[str], point: Sequence[Any]) -> str:
    at = ", ".join(f"{n}={v}" for n, v in zip(names, point))
    return f"{', '.join(plan.names)} has a pole at {at} (a denominator vanishes); choose inputs away from it"


#: Backends by key (see the module docstring).
BACKENDS: dict[str, type[NumpyBackend] | type[MpmathBackend] | type[ExactBackend]] = {
    "numpy": NumpyBackend,
    "numba": NumbaBackend,
    "mpmath": MpmathBackend,
    "exact": ExactBackend,
}


def warn_no_numba() -> None:
    """Warn (a :class:`~symkin.errors.PrecisionWarning`) that numba is missing and NumPy is used instead."""
    warnings.warn(
        "numba is not installed (pip install 'symkin[numba]'); compiling with NumPy instead",
        PrecisionWarning,
        stacklevel=4,
    )
