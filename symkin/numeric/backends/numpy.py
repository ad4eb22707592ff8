"""The ``numpy`` backend: the stable forms as vectorised NumPy code (``sympy.lambdify`` with
:class:`~symkin.numeric.codegen.FloatPrinter`), one call for a small call, chunks of
``plan.chunk`` points for a large one; one point of Python floats in ``math`` code.

Tooth numbers are given to the generated code twice: as floats where the law uses them as
numbers, and as integers (int64, or Python integers where a bound says int64 could
overflow) inside :class:`~symkin.numeric.nodes.ExactRatio`.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import sympy as sp

from symkin.numeric import runtime
from symkin.numeric.backends.base import (
    Backend,
    Plan,
    Result,
    allocate,
    as_array,
    as_floats,
    as_integers,
    broadcast_flat,
    common_shape,
    lambdify_source,
)
from symkin.numeric.codegen import FloatPrinter, ScalarPrinter, phase_sources, product_ratios
from symkin.numeric.nodes import ExactRatio

__all__ = ["NumpyBackend", "Int64Bound"]

_INT64 = np.dtype(np.int64)
_FLOAT_INT = 2**1023  # Python integers below this convert to finite floats
_THREADS_FROM = 1 << 15  # fewer points are evaluated on the calling thread


@functools.cache
def _pool(threads: int) -> Any:
    """A process-wide pool of ``threads`` threads (NumPy ufuncs release the GIL)."""
    from concurrent.futures import ThreadPoolExecutor

    return ThreadPoolExecutor(max_workers=threads, thread_name_prefix="symkin")


_PRIME_FROM = 1 << 13  # points: below this a call's temporaries stay under 64 KiB


@functools.cache
def _prime_allocator() -> None:
    """Free one 16 MiB block, once per process: glibc's malloc then keeps the freed temporaries
    of large calls for the next ones instead of unmapping them after each operation (it raises
    its thresholds when a mapped block of up to 32 MiB is freed).  No memory is written; other
    allocators ignore it.  Why it is kept, measured: benchmarks/notes/numeric-backends.md."""
    np.empty(1 << 21)


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


class Int64Bound:
    """Whether the integer polynomials of a law's exact ratios could overflow int64 for
    given tooth numbers: ``sum |c| prod |z|^d`` over each polynomial's terms, from a bound of
    each tooth-number array."""

    _SAFE = 2**62

    def __init__(self, polys: Sequence[sp.Expr], integer_syms: Sequence[sp.Symbol]):
        index = {sym: k for k, sym in enumerate(integer_syms)}
        #: per polynomial: (the absolute value of a coefficient, ((integer argument, power), ...)) per term
        self.terms: list[list[tuple[int, tuple[tuple[int, int], ...]]]] = []
        for poly in polys:
            terms = []
            for term in sp.Add.make_args(sp.expand(poly)):
                c, factors = term.as_coeff_mul()
                terms.append((abs(int(c)), tuple((index[f.as_base_exp()[0]], int(f.as_base_exp()[1])) for f in factors)))
            self.terms.append(terms)
        self._memo: tuple[tuple[int, ...], bool] | None = None

    def overflows(self, ints: Sequence[np.ndarray]) -> bool:
        """True when an integer polynomial could overflow int64 for these inputs."""
        if not self.terms or not ints:
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
        if any(b < 0 for b in big) or self._over(big):
            # |z| from the extremes in Python integers (np.abs wraps -2^63 to itself in int64)
            big = [max(int(i.max()), -int(i.min())) if i.size else 0 for i in ints]
            return self._over(big)
        return False

    def _over(self, big: Sequence[int]) -> bool:
        """True when some polynomial may reach 2^62 for inputs bounded by ``big`` (the answer
        for the last bounds is remembered: calls with like inputs repeat them)."""
        key = tuple(big)
        memo = self._memo
        if memo is not None and memo[0] == key:
            return memo[1]
        over = any(sum(c * math.prod(big[k] ** e for k, e in powers) for c, powers in terms) >= self._SAFE
                   for terms in self.terms)
        self._memo = (key, over)  # one assignment: another thread sees the old pair or the new one
        return over


class NumpyBackend(Backend):
    """Vectorised NumPy code (``sympy.lambdify`` with a printer for the stable forms),
    evaluated in chunks so that temporaries stay small and are reused."""

    key = "numpy"
    precisions = ("float64", "float32")
    floats = True  # evaluates stable forms in binary floating point

    def __init__(self, plan: Plan):
        super().__init__(plan)
        used: set[sp.Symbol] = set()
        polys = []
        for node in (n for e in plan.stable for n in sp.preorder_traversal(e)):
            if isinstance(node, ExactRatio):
                used |= node.free_symbols
                polys += node.args
        self.integer_syms = tuple(s for s in plan.args if s in used)
        self.twins = {s: sp.Symbol(f"_int_{s.name}", integer=True) for s in self.integer_syms}
        self.bound = Int64Bound(polys, self.integer_syms)
        self.phases = {name: runtime.dd_function(text, name) for name, text in phase_sources(plan.stable).items()}
        # the printer writes every NumPy name as numpy.<name>: the module itself is the namespace
        # ("numpy" would run `from numpy import *`, which imports numpy.f2py, slowly)
        exprs = [self._twin(e) for e in plan.stable]
        self.func = sp.lambdify(
            [*plan.args, *self.twins.values()], product_ratios(exprs) if plan.precision == "float64" else exprs,
            modules=[{**runtime.NAMESPACE[plan.precision], **self.phases, "numpy": np}],
            printer=FloatPrinter(plan.precision), cse=plan.cse, docstring_limit=0,
        )
        self.numpy_source = lambdify_source(self.func)
        outside = set().union(*(e.replace(lambda n: isinstance(n, ExactRatio), lambda n: sp.Integer(1)).free_symbols
                                for e in plan.stable))
        self.float_used = tuple(s in outside for s in plan.args)
        self.names = [s.name for s in plan.args]
        self.integer_flags = tuple(s in self.twins for s in plan.args)
        self.dtype = plan.dtype
        self._np_dtype = np.dtype(plan.dtype)  # (arrays of it carry this very object: compared by identity)
        zero = np.zeros((), dtype=plan.dtype)
        zero.flags.writeable = False
        self._placeholder = zero  # a tooth number's float where only its integer value is used

    @property
    def source(self) -> str:
        """The generated NumPy code."""
        return self.numpy_source

    def _twin(self, e: sp.Expr) -> sp.Expr:
        if not self.twins:
            return e
        return e.replace(lambda n: isinstance(n, ExactRatio), lambda n: n.xreplace(self.twins))

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
                [*self.plan.args, *self.twins.values()], exprs,
                modules=[{**runtime.SCALAR_NAMESPACE, **self.phases, "math": math}, "math"], printer=ScalarPrinter({"strict": True}),
                cse=self.plan.cse, docstring_limit=0,
            )
        except Exception:  # a function the math module lacks: arrays only
            return False

    def evaluate_scalar(self, values: Sequence[Any]) -> list[Any] | None:
        """The outputs at one point given as Python or NumPy float64 numbers, without
        arrays; None when this point needs the array path (another input type, a value
        that is not finite, an output that is not: the array path checks, converts and
        reports)."""
        code = self._scalar_code
        if code is None:
            code = self._scalar_code = self._build_scalar()
        if code is False:
            return None
        point: Sequence[Any] | None = values
        if self.twins:
            point = self._scalar_arguments(values)
        else:  # real inputs only: floats pass as they are (one type test each)
            for v in values:
                kind = type(v)
                if kind is not float and kind is not np.float64:
                    point = self._scalar_arguments(values)
                    break
        if point is None:
            return None
        try:
            out = code(*point)
        except (ArithmeticError, ValueError, TypeError):  # a pole or a domain error: reported by the array path
            return None
        return self._scalar_results(out)

    def scalar_entry(self) -> Any:
        """A function of the call's values for the common scalar call, or None: every input a
        Python float or a NumPy float64 number (tooth numbers: Python integers), the outputs
        as NumPy float64 numbers, one bare number for one law; :meth:`evaluate_scalar`'s
        answer for any other point (its types, conversions and checks, once).  Generated once,
        so a call pays one type test per input and no loop (issue 34: scalar call overhead)."""
        code = self._scalar_code
        if code is None:
            code = self._scalar_code = self._build_scalar()
        if code is False:
            return None
        names = [f"v{k}" for k in range(len(self.plan.args))]
        # (a Python integer beyond the float range: float() raises OverflowError, and the slow path takes it)
        tests = [f"type({v}) is int" if integer else f"(type({v}) is float or type({v}) is _f64)"
                 for v, integer in zip(names, self.integer_flags)]
        point = [f"float({v})" if integer else v for v, integer in zip(names, self.integer_flags)]
        point += [v for v, integer in zip(names, self.integer_flags) if integer]
        n = len(self.plan.stable)
        outs = [f"r{k}" for k in range(n)]
        finite = " and ".join(f"type({r}) is float and {r} - {r} == 0.0" for r in outs)  # (inf - inf, nan - nan: nan)
        # (several outputs come back as a tuple, as from every other path: callers test for one)
        back = f"(None if (p := _slow(values)) is None else {'tuple(p)' if n > 1 else 'p[0]'})"
        result = f"({', '.join(f'_f64({r})' for r in outs)},)" if n > 1 else "_f64(r0)"
        lines = [
            "def _entry(values):",
            f"    {', '.join(names)}{',' if len(names) == 1 else ''} = values" if names else "    pass",
            f"    if {' and '.join(tests) or 'True'}:",
            "        try:",
            f"            {', '.join(outs)}{',' if n == 1 else ''} = _code({', '.join(point)})",
            "        except (ArithmeticError, ValueError, TypeError):",
            f"            return {back}",
            f"        if {finite}:",
            f"            return {result}",
            f"    return {back}",
        ]
        ns = {"_code": code, "_f64": np.float64, "_slow": self.evaluate_scalar}
        exec(compile("\n".join(lines) + "\n", "<symkin scalar entry>", "exec"), ns)  # generated here, no user text
        return ns["_entry"]

    def _scalar_arguments(self, values: Sequence[Any]) -> list[Any] | None:
        """The scalar code's arguments: every value as a float, then each tooth number's exact
        integer value; None for a value of another type (the array path converts or refuses it)."""
        floats = []
        ints = []
        for v, integer in zip(values, self.integer_flags):
            kind = type(v)
            if kind is float or kind is np.float64:
                x = v
            elif kind is int and -_FLOAT_INT < v < _FLOAT_INT:
                x = float(v)
            else:
                return None
            floats.append(x)
            if not integer:
                continue
            if kind is int:
                ints.append(v)
            elif x.is_integer() and abs(x) < 2.0**63:
                ints.append(int(x))
            else:
                return None
        return floats + ints

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

    # ------------------------------------------------------------------ inputs
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
                floats.append(as_floats(a, s.name, plan.dtype))
                continue
            i = a if a.dtype.kind == "f" and a.ndim else as_integers(a, s.name)
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

    def _real_inputs(self, values: Sequence[Any]) -> tuple[tuple[int, ...], list[Any]]:
        """The shape of a call without tooth numbers and its inputs in the working type, as given
        (a float64 number stays a NumPy number: IEEE arithmetic, x/0 is inf, not an exception,
        and cheaper in the generated code than a 0-d array's ufunc call per operation)."""
        dtype, dt = self.dtype, self._np_dtype
        floats: list[Any] = []
        shape = None
        same = True  # every array of one shape (the common call): no broadcasting to decide
        wide = dtype is np.float64
        for v, nm in zip(values, self.names):
            kind = type(v)
            if wide and (kind is float or kind is np.float64):
                floats.append(np.float64(v))
                continue
            if kind is not np.ndarray or v.dtype is not dt:
                v = as_floats(as_array(v, nm), nm, dtype)
            floats.append(v)
            if shape is None:
                shape = v.shape
            elif v.shape != shape:
                same = False
        if shape is None:
            return (), floats
        if not same:
            arrays = [(f, nm) for f, nm in zip(floats, self.names) if type(f) is np.ndarray]
            shape = common_shape([f for f, _ in arrays], [nm for _, nm in arrays])
        return shape, floats

    def integer_chunk(self, ints: Sequence[np.ndarray]) -> list[np.ndarray]:
        """Integer inputs of one chunk as int64 (float arrays checked and cast here), or
        as Python integers where an integer polynomial could overflow int64."""
        part = [as_integers(i, s.name) if i.dtype.kind == "f" else i for i, s in zip(ints, self.twins)]
        if self.bound.overflows(part):
            part = [np.asarray(i).astype(object) for i in part]
        return part

    # ------------------------------------------------------------------ arrays
    def evaluate(self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None) -> Result:
        """``(shape, outputs, flagged)``: the outputs (flat, or of ``shape``) and whether
        any of their values is not finite."""
        ints: list[np.ndarray] = []
        if self.twins:
            shape, floats, ints = self._prepare_flat(values) or self.prepare(values)
        else:
            shape, floats = self._real_inputs(values)
        n = math.prod(shape)
        if n > _PRIME_FROM:
            _prime_allocator()
        if outs is None and n <= self.plan.chunk:  # one call on the arrays as given: no copies, no chunks
            if self.twins:
                results, flagged = self._whole(floats + self.integer_chunk(ints), (n,) if shape else ())
            else:
                results, flagged = self._whole(floats, shape)
            return shape, results, flagged
        if not self.twins:
            shape, floats = broadcast_flat([np.asarray(f, self.dtype) for f in floats], self.names)
        results = allocate(outs, len(self.plan.stable), n, self.plan.dtype)
        return shape, results, self._chunks(floats, ints, results, n)

    def _whole(self, args: list[Any], shape: tuple[int, ...]) -> tuple[list[np.ndarray], bool]:
        """The generated code called once on ``args``: its outputs, each a fresh array of
        ``shape``, and whether any value is not finite (one finiteness pass)."""
        dt = self._np_dtype
        with np.errstate(all="ignore"):  # one context for the call and its finiteness pass
            results = self.func(*args)
            finite = True
            for k, r in enumerate(results):
                # (a fresh array of the call's shape is the output as it is; see _own)
                if type(r) is not np.ndarray or r.dtype is not dt or r.shape != shape or r.base is not None or any(
                        r is a for a in args):
                    r = results[k] = _own(r, shape, self.dtype, args)
                if finite and not math.isfinite(np.add.reduce(r, axis=None)):  # a finite sum proves every value finite
                    finite = bool(np.isfinite(r).all())
        return results, not finite

    def _chunks(self, floats: list[np.ndarray], ints: list[np.ndarray], results: list[np.ndarray], n: int) -> bool:
        """Evaluate in chunks of ``plan.chunk`` points into ``results``, on ``plan.threads``
        threads (contiguous blocks of chunks, one per thread) for a large call; whether any
        value is not finite."""
        chunk = max(1, self.plan.chunk)
        starts = list(range(0, n, chunk))
        work = functools.partial(self._chunk_block, floats, ints, results, n, chunk)
        threads = min(self.plan.threads or 1, len(starts))
        if threads > 1 and n >= _THREADS_FROM:
            per = -(-len(starts) // threads)
            return any(_pool(threads).map(work, [starts[k * per:(k + 1) * per] for k in range(threads)]))
        return work(starts)

    def _chunk_block(self, floats: list[np.ndarray], ints: list[np.ndarray], results: list[np.ndarray], n: int, chunk: int,
                     starts: Sequence[int]) -> bool:
        """The chunks beginning at ``starts``; whether any value is not finite."""
        flagged = False
        with np.errstate(all="ignore"):  # one context for the block: non-finite outputs are flagged here
            for start in starts:
                stop = min(n, start + chunk)
                part = [f[start:stop] if f.ndim else f for f in floats]
                if ints:  # tooth numbers checked (one bitwise-or reduction each) while the chunk is in cache
                    part += self.integer_chunk([i[start:stop] if i.ndim else i for i in ints])
                for o, r in zip(results, self.func(*part)):
                    seg = o[start:stop]
                    seg[...] = r
                    # a finite sum (one pass, no temporary) proves every value finite
                    if not flagged and not (math.isfinite(np.add.reduce(seg, axis=None)) or np.isfinite(seg).all()):
                        flagged = True
        return flagged

    def evaluate_points(self, values: Sequence[Any], index: np.ndarray) -> list[np.ndarray]:
        """Re-evaluate a few points (given by flat index) with Python integers."""
        _shape, floats, ints = self.prepare(values)
        take = lambda a: a[index] if a.ndim else a  # noqa: E731
        ints = [i.astype(object) for i in self.integer_chunk([take(i) for i in ints])]
        with np.errstate(all="ignore"):
            part = list(self.func(*[take(f) for f in floats], *ints))
        return [np.broadcast_to(np.asarray(r, dtype=self.plan.dtype), index.shape) for r in part]
