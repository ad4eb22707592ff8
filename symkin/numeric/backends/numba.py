"""The ``numba`` backend: one fused loop per law (:func:`symkin.numeric.kernel.kernel_source`),
compiled by Numba from a file in the kernel cache folder so that Numba keeps it on disk.

Calls of :data:`_PARALLEL_FROM` points and more run on every thread (one such call at a time).
Where Numba cannot compile a law, or tooth numbers need Python integers, the NumPy code of
:class:`~symkin.numeric.backends.numpy.NumpyBackend` (its base class) evaluates the call.
"""

from __future__ import annotations

import contextlib
import functools
import math
import os
import stat
import tempfile
import threading
import time
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from symkin.errors import PrecisionWarning, SymkinWarning
from symkin.numeric import runtime
from symkin.numeric.backends.base import Plan, Result, allocate, as_array, as_floats, as_integers, broadcast_flat
from symkin.numeric.backends.numpy import NumpyBackend
from symkin.numeric.kernel import KERNEL_BLOCK, kernel_source

__all__ = ["NumbaBackend", "numba_available", "kernel_cache_folder", "warn_no_numba", "compile_pays", "compile_estimate"]

#: In ``jit="auto"`` (the default backend's mode) a kernel is compiled once the NumPy code has
#: spent this many times the kernel's estimated compile time (:func:`compile_estimate`) on the
#: calls it would serve: whatever happens next, the first use costs at most a fifth more than
#: the NumPy path alone, and a long run of work reaches the compiled speed.
COMPILE_PAYBACK = 5.0


def compile_estimate(operations: int, parallel: bool) -> float:
    """Seconds (CPU) Numba takes to compile the kernel of a law of ``operations`` operations
    per point, with an empty cache: 0.5 s + 0.05 s per operation for the serial kernel, ten
    times that for the parallel one (measured on the benchmark laws: serial 0.3-3 s, parallel
    1.3-27 s; benchmarks/notes/numeric-backends.md).  Deliberately on the high side: an
    estimate too high delays the kernel, one too low could make first use slower than NumPy."""
    return (0.5 + 0.05 * operations) * (10.0 if parallel else 1.0)


def compile_pays(numpy_seconds: float, operations: int, parallel: bool) -> bool:
    """Whether a ``jit="auto"`` function compiles its (serial or parallel) kernel now, having
    spent ``numpy_seconds`` in the NumPy code on calls that kernel would serve (small calls
    for the serial kernel, calls of 2^15 points and more for the parallel one).

    >>> compile_pays(0.4, 6, False), compile_pays(20.0, 6, False), compile_pays(20.0, 6, True)
    (False, True, False)
    """
    return numpy_seconds >= COMPILE_PAYBACK * compile_estimate(operations, parallel)


_INT64 = np.dtype(np.int64)
_FLOAT64 = np.dtype(np.float64)
_NUMBA_LOCK = threading.Lock()
_PARALLEL_FROM = 1 << 15
#: Held while a parallel kernel runs: one at a time, each on every thread (calls from several
#: threads at once, as a Dask scheduler's, would oversubscribe the cores, and Numba's workqueue
#: threading layer, where no OpenMP is found, aborts on them).
_PARALLEL_LOCK = threading.Lock()


def numba_available() -> bool:
    """True when Numba can be imported."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def warn_no_numba() -> None:
    """Warn (a :class:`~symkin.errors.PrecisionWarning`) that numba is missing and NumPy is used instead."""
    warnings.warn(
        "numba is not installed (pip install 'symkin[numba]'); compiling with NumPy instead",
        PrecisionWarning,
        stacklevel=4,
    )


#: The environment variable that names the kernel cache folder.
CACHE_VARIABLE = "SYMKIN_CACHE_DIR"


def kernel_cache_folder() -> Path | None:
    """Where compiled Numba kernels are kept between processes: ``$SYMKIN_CACHE_DIR``, or
    ``kernels`` in the user's cache folder (:func:`platformdirs.user_cache_dir`: ``~/.cache/symkin``
    on Linux, ``$XDG_CACHE_HOME`` honoured).  A folder it makes is private (0700).

    None, and kernels are compiled in memory in each process, when the folder cannot be made or
    written, or is not private: Numba's cache files are pickles, which run code when they are
    loaded, so a folder another user owns or can write to is refused (with a warning, once).
    """
    import platformdirs

    base = os.environ.get(CACHE_VARIABLE)
    folder = Path(base) if base else Path(platformdirs.user_cache_dir("symkin")) / "kernels"
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
    except OSError:
        return None
    problem = _not_private(folder) or _not_private(_tightened(folder / "__pycache__"))
    if problem:
        _warn_not_private(str(folder), problem)
        return None
    return folder if os.access(folder, os.W_OK) else None


def _not_private(folder: Path) -> str:
    """What makes ``folder`` unsafe for pickles ("" if nothing, or if it does not exist)."""
    try:
        st = folder.stat()
    except FileNotFoundError:
        return ""
    except OSError as err:
        return f"cannot be examined ({err.strerror})"
    if not stat.S_ISDIR(st.st_mode):
        return "is not a folder"
    if hasattr(os, "getuid") and st.st_uid != os.getuid():
        return "belongs to another user"
    if os.name == "posix" and st.st_mode & 0o022:
        return "can be written by others (group or all)"
    return ""


def _tightened(folder: Path) -> Path:
    """``folder`` (Numba's ``__pycache__``, made with the umask's permissions: 0775 under a umask
    of 002) without write permission for others, where it is the user's own."""
    with contextlib.suppress(OSError, AttributeError):
        st = folder.stat()
        if st.st_uid == os.getuid() and st.st_mode & 0o022:
            folder.chmod(stat.S_IMODE(st.st_mode) & ~0o022)
    return folder


@functools.cache
def _warn_not_private(folder: str, problem: str) -> None:
    warnings.warn(
        f"the kernel cache {folder} {problem}, and a cache file there can run code when loaded: kernels are "
        f"compiled in memory instead; give {CACHE_VARIABLE} a folder of your own that only you can write "
        "(chmod 700)",
        SymkinWarning,
        stacklevel=2,
    )


def _discard_cached(name: str) -> None:
    """Remove Numba's cache entries of kernel module ``name`` (a truncated or damaged one is
    then compiled and saved afresh) and forget the module."""
    import sys

    sys.modules.pop(name, None)
    folder = kernel_cache_folder()
    if folder is None:
        return
    for entry in (folder / "__pycache__").glob(f"{name}.*"):
        with contextlib.suppress(OSError):
            entry.unlink()


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
    name = "symkin_kernel_" + hashlib.sha256(f"{numba.__version__}\n{text}".encode()).hexdigest()[:32]
    if name in sys.modules:
        return sys.modules[name]._jit, sys.modules[name]._jit_redo
    path = folder / f"{name}.py"
    try:
        if not path.exists() or path.read_text() != text:
            # written whole under a private name, then renamed: another process never reads half a file
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


def _kernel_in_process(source: str, precision: str, parallel: bool, namespace: dict[str, Any]) -> Any:
    """The kernel of ``source`` and its redo pass (or None), jitted in this process only."""
    import numba

    ns: dict[str, Any] = {"numpy": np, "prange": numba.prange, "_F": np.dtype(precision).type, **namespace}
    exec(compile(source, "<symkin kernel>", "exec"), ns)  # generated from SymPy, no user text
    jit = numba.njit(parallel=parallel, error_model="numpy", fastmath=False, nogil=True)
    return jit(ns["_kernel"]), (jit(ns["_kernel_redo"]) if "_kernel_redo" in ns else None)


class _Call(NamedTuple):
    """One call as the kernel takes it."""

    shape: tuple[int, ...]
    n: int
    flat: list[np.ndarray]  # every argument flat, or a 0-d scalar
    inputs: list[np.ndarray]  # ... with each scalar as a block of copies of it
    steps: list[int]  # 0 for a scalar, 1 for an array
    float_integers: tuple[bool, ...]  # tooth numbers given as float arrays (checked in the loop)
    results: list[np.ndarray]


class NumbaBackend(NumpyBackend):
    """One fused loop per call, compiled by Numba (``parallel=True`` over the available
    threads for large calls); integer parts in int64, checked in the loop for overflow,
    and re-evaluated with Python integers where int64 could overflow."""

    key = "numba"

    def __init__(self, plan: Plan):
        # OpenMP threads sleep rather than spin while they wait (unless the user chose otherwise):
        # spinning threads made parallel loops far slower on a busy machine.  Set before Numba
        # first loads its OpenMP pool.
        os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
        super().__init__(plan)  # the NumPy code re-evaluates flagged points exactly
        self.kernels: dict[tuple[bool, tuple[bool, ...]], Any] = {}
        self.broken = False
        self.kernel_sources: dict[tuple[bool, tuple[bool, ...]], str] = {}
        #: the type each argument's array has in the common call (int64 for tooth numbers)
        self._wanted = tuple(_INT64 if integer else self._np_dtype for integer in self.integer_flags)
        #: argument -> (value, block of copies of it), the last scalar given there
        self._blocks: dict[int, tuple[Any, np.ndarray]] = {}
        self._outputs = len(plan.stable)
        #: the key of the serial kernel of int64 and float inputs (the common small call's)
        self._serial_key = (False, (False,) * len(plan.args))
        #: jit="auto": seconds spent in the NumPy code on the calls of the serial kernel and of the parallel one
        self.numpy_seconds = {False: 0.0, True: 0.0}
        self._paying: set[bool] = set()  # ... and the kernels (serial: False, parallel: True) whose compile pays
        self._operations: int | None = None
        #: kernels loaded from the disk cache and not yet discarded once (see :meth:`_discard`)
        self._from_disk: set[tuple[bool, tuple[bool, ...]]] = set()

    @property
    def source(self) -> str:
        """The generated kernel source (the first kernel compiled), or a note of when it is compiled."""
        when = "once the NumPy code has spent what compiling it costs" if self.plan.jit == "auto" else "on first call"
        return next(iter(self.kernel_sources.values()), f"(compiled {when})")

    def _kernel(self, parallel: bool, float_integers: tuple[bool, ...]) -> Any:
        """The compiled loop and its redo pass (or None): one per law, threading and float
        tooth arrays, for every mix of scalar and array arguments (a step of 0 or 1 each),
        cached on disk (see :func:`_kernel_from_file`) so that another process loads it
        instead of compiling."""
        key = (parallel, float_integers)
        if key not in self.kernels:
            plan = self.plan
            src = kernel_source(plan.stable, plan.args, self.integer_flags, plan.precision, plan.cse, float_integers)
            self.kernel_sources[key] = src
            with _NUMBA_LOCK:
                kernel = _kernel_from_file(src, plan.precision, parallel)
                if kernel is None:  # no writable, private cache folder: compiled in this process only
                    kernel = _kernel_in_process(src, plan.precision, parallel, runtime.numba_namespace(plan.precision))
                else:
                    self._from_disk.add(key)
                self.kernels[key] = kernel
        return self.kernels[key]

    def _discard(self, key: tuple[bool, tuple[bool, ...]], err: Exception) -> bool:
        """After ``err`` from a kernel the disk cache gave (Numba loads a cache entry at the first
        call of each signature; a truncated or damaged one raises UnpicklingError, EOFError, ...):
        remove its entries, so that the next call compiles and saves it afresh, and say so (True).
        False for an error the cache cannot explain (a Numba error, or a kernel discarded before)."""
        import numba

        if isinstance(err, numba.core.errors.NumbaError) or key not in self._from_disk:
            return False
        self._from_disk.discard(key)
        kernel = self.kernels.pop(key)
        if key == self._serial_key:
            self.array_entry = None  # (it calls the discarded kernel: made again once the new one has run)
        _discard_cached(kernel[0].py_func.__module__)
        warnings.warn(f"a damaged entry of the kernel cache ({type(err).__name__}) was discarded and compiled again",
                      SymkinWarning, stacklevel=4)
        return True

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

    def evaluate(self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None) -> Result:
        """Evaluate the laws at ``values`` in one fused loop; returns the broadcast shape, the outputs and whether any is not finite."""
        if self.broken:
            return super().evaluate(values, outs)
        serial = self.kernels.get(self._serial_key) if outs is None else None
        common = None
        if serial is not None:  # (compiled: jit="auto" has nothing to decide for a small call)
            common = self._common_call(values)
            if common is not None and common[0] < _PARALLEL_FROM:
                # the common small call: the serial kernel compiled, nothing to convert or switch
                n, inputs, steps = common
                results = [np.empty(n, self._np_dtype) for _ in range(self._outputs)]
                try:
                    bad, _nonwhole, uncertain = serial[0](*inputs, *results, n, *steps)
                except Exception as err:  # a new signature, whose cache entry may be damaged
                    if not self._discard(self._serial_key, err):
                        raise
                    return self.evaluate(values, outs)
                if not (bad or uncertain):
                    return (n,), results, False
                # (else poles, or differences of products to redo: the general path below, again)
        if self.plan.jit == "auto" and len(self._paying) < 2:
            waited = self._numpy_until_it_pays(values, outs)
            if waited is not None:
                return waited
        if common is None and outs is None:
            common = self._common_call(values)
        call = self._as_given(common) if common is not None else self._converted(values, outs)
        bad = None if call is None else self._run(call)
        if call is None or bad is None:  # Python integers, or a law Numba cannot compile: the NumPy code
            return super().evaluate(values, outs)
        serial = self.kernels.get(self._serial_key)
        if serial is not None and self.array_entry is None and self.plan.precision == "float64":
            self.array_entry = self._array_entry(serial[0])  # (the serial kernel has run: loaded, not damaged)
        if bad and self.twins:  # int64 could overflow there: those points again with Python integers
            index = np.flatnonzero(np.logical_or.reduce([~np.isfinite(r) for r in call.results]))
            for r, f in zip(call.results, self.evaluate_points(values, index)):
                r[index] = f
        return call.shape, call.results, bool(bad)

    def _array_entry(self, kernel: Any) -> Any:
        """The common small call of arrays as one generated function of the call's values (issue
        34, item 4: a small call's overhead): every argument a flat contiguous array of one
        length below :data:`_PARALLEL_FROM` (int64 for tooth numbers, float64 otherwise) goes
        straight to the serial ``kernel``; its outputs when every value is finite and certified,
        else None (the general path then takes the call: poles, redo, reports, a damaged cache
        entry), as :meth:`evaluate`'s own fast path.  Only the type tests of
        :meth:`_common_call`, written out."""
        names = [f"v{k}" for k in range(len(self._wanted))]
        tests = [f"type({v}) is _nd and {v}.dtype is _w{k} and {v}.strides == _one" for k, v in enumerate(names)]
        tests[1:] = [f"{t} and {v}.shape == _s" for t, v in zip(tests[1:], names[1:])]
        outs = [f"r{k}" for k in range(self._outputs)]
        lines = [
            "def _entry(values):",
            f"    {', '.join(names)}, = values",
            f"    if {tests[0]}:",
            f"        _s = {names[0]}.shape",
            f"        if {' and '.join(tests[1:]) or 'True'}:",
            "            n = _s[0]",
            "            if n < _PAR:",
            *(f"                {r} = _empty(n)" for r in outs),
            "                try:",
            f"                    bad, _nw, unc = _kernel({', '.join(names + outs)}, n, {', '.join('1' for _ in names)})",
            "                except Exception:  # a signature not run yet whose cache entry is damaged: evaluate's",
            "                    return None  # general path discards it",
            "                if not (bad or unc):",
            f"                    return {outs[0] if len(outs) == 1 else '(' + ', '.join(outs) + ',)'}",
            "    return None",
        ]
        ns = {"_nd": np.ndarray, "_one": (8,), "_PAR": _PARALLEL_FROM, "_empty": np.empty, "_kernel": kernel,
              **{f"_w{k}": w for k, w in enumerate(self._wanted)}}
        exec(compile("\n".join(lines) + "\n", "<symkin array entry>", "exec"), ns)  # generated here, no user text
        return ns["_entry"]

    def _numpy_until_it_pays(self, values: Sequence[Any], outs: Sequence[np.ndarray] | None) -> Result | None:
        """jit="auto": the call by the NumPy code (timed) while the kernel it needs is not compiled
        and the time spent so does not pay for compiling it (:func:`compile_pays`); else None."""
        try:
            n = math.prod(np.broadcast_shapes(*(np.shape(v) for v in values)))
        except (ValueError, TypeError):
            n = 0  # (the NumPy code says what is wrong with the inputs)
        parallel = n >= _PARALLEL_FROM and self.plan.threads != 1
        if parallel in self._paying:
            return None
        if self._operations is None:
            import sympy as sp

            self._operations = int(sum(sp.count_ops(e) for e in self.plan.stable))
        if compile_pays(self.numpy_seconds[parallel], self._operations, parallel):
            if not numba_available():  # (installed but not importable, a Numba built for another NumPy: NumPy, as without it)
                self.broken = True
            self._paying.add(parallel)
            return None
        start = time.process_time()
        try:
            return super().evaluate(values, outs)
        finally:
            self.numpy_seconds[parallel] += time.process_time() - start

    def _as_given(self, common: tuple[int, list[np.ndarray], list[int]]) -> _Call:
        """The common call (see :meth:`_common_call`) with new output arrays."""
        n, inputs, steps = common
        results = [np.empty(n, dtype=self.plan.dtype) for _ in self.plan.stable]
        return _Call((n,), n, inputs, inputs, steps, (False,) * len(inputs), results)

    def _converted(self, values: Sequence[Any], outs: Sequence[np.ndarray] | None) -> _Call | None:
        """Any other call, its inputs converted and broadcast; None where tooth numbers need
        Python integers.  Narrow signed integers pass as they are (Numba computes integer
        products in int64), float64 tooth arrays too (checked and cast in the loop)."""
        plan = self.plan
        arrays = [as_array(v, s.name) for v, s in zip(values, plan.args)]
        conv = [
            (a if a.dtype.kind == "i" or (a.dtype == np.float64 and a.ndim) else as_integers(a, s.name))
            if integer else as_floats(a, s.name, plan.dtype)
            for a, s, integer in zip(arrays, plan.args, self.integer_flags)
        ]
        if any(c.dtype == object for c in conv):
            return None
        shape, flat = broadcast_flat(conv, self.names)
        n = math.prod(shape)
        results = allocate(outs, len(plan.stable), n, plan.dtype)
        flat = [as_integers(f, s.name) if f.ndim == 0 and f.dtype.kind == "f" and integer else f
                for f, s, integer in zip(flat, plan.args, self.integer_flags)]
        float_integers = tuple(f.dtype.kind == "f" and integer for f, integer in zip(flat, self.integer_flags))
        inputs = [np.full(min(n, KERNEL_BLOCK), f) if f.ndim == 0 else f for f in flat]  # a scalar: a block of copies
        return _Call(shape, n, flat, inputs, [0 if f.ndim == 0 else 1 for f in flat], float_integers, results)

    def _launch(self, key: tuple[bool, tuple[bool, ...]], call: _Call) -> tuple[int, int]:
        """The kernel of ``key`` (compiled on first use) on ``call``, and its redo pass where differences of
        products are not certified: the count of values that are not finite, and the whole-number flag."""
        parallel = key[0]
        kernel, redo = self.kernels.get(key) or self._kernel(*key)
        with _PARALLEL_LOCK if parallel else contextlib.nullcontext():
            bad, nonwhole, uncertain = kernel(*call.inputs, *call.results, call.n, *call.steps)
            if uncertain:  # points near a pole: their differences of products again, in double-double
                bad += redo(*call.inputs, *call.results, call.n, *call.steps)
        return bad, nonwhole

    def _run(self, call: _Call) -> int | None:
        """Run the call's kernel (compiled on first use) and, where differences of products are
        not certified, its redo pass: the count of values that are not finite, or None (with a
        warning) where Numba cannot compile the law."""
        import numba

        parallel = call.n >= _PARALLEL_FROM and (self.plan.threads or numba.get_num_threads()) > 1
        threads = self.plan.threads
        restore = 0  # Numba's number of threads, to restore after a parallel call on plan.threads threads
        if parallel and threads and threads != numba.get_num_threads():
            restore = numba.get_num_threads()
        key = (parallel, call.float_integers)
        try:
            if restore and threads:  # (numba's config defines its settings at run time: its inline types miss them)
                numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))  # type: ignore[attr-defined]
            try:
                bad, nonwhole = self._launch(key, call)
            except Exception as err:  # a damaged cache entry: discarded, and the kernel compiled again
                if not self._discard(key, err):
                    raise
                bad, nonwhole = self._launch(key, call)
        except numba.core.errors.NumbaError as err:  # a construct Numba cannot compile: NumPy instead
            self.broken = True
            warnings.warn(
                f"numba could not compile {', '.join(self.plan.names)} ({type(err).__name__}); evaluating it with NumPy instead",
                PrecisionWarning,
                stacklevel=5,
            )
            return None
        finally:
            if restore:
                numba.set_num_threads(restore)
        if nonwhole:  # the message names the first value that is not a whole number
            for f, s, as_float in zip(call.flat, self.plan.args, call.float_integers):
                if as_float:
                    as_integers(f, s.name)
        return bad
