"""What every backend offers (:class:`Backend`), what it is given (:class:`Plan`), and the
input checks the float backends share.

A backend is a class with a ``key``, the ``precisions`` it offers and ``floats`` (whether it
computes in binary floating point: :func:`symkin.compile` then hands it the stable forms);
it is built from a :class:`Plan` and evaluates with ``evaluate(values, outs)``.

    >>> import numpy as np
    >>> broadcast_flat([np.ones((2, 3)), np.array(2.0)], ["x", "y"])[0]
    (2, 3)
"""

from __future__ import annotations

import inspect
import math
from abc import ABC, abstractmethod
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import sympy as sp

from symkin.errors import InputError

__all__ = ["Plan", "Backend", "Result", "as_array", "as_floats", "as_integers", "broadcast_flat", "common_shape",
           "allocate", "lambdify_source"]

#: What ``evaluate`` returns: the broadcast shape of the inputs, one flat array per output (or
#: arrays of that shape), and whether any output value is not finite.
Result = tuple[tuple[int, ...], list[np.ndarray], bool]


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
    #: numba only: "eager" compiles a kernel at its first call; "auto" evaluates with the NumPy
    #: code until the time spent there pays for the compile (see backends/numba.py, compile_pays)
    jit: str = "eager"

    @property
    def dtype(self) -> Any:
        """The NumPy float type of the plan's precision (float32 or float64)."""
        return np.float32 if self.precision == "float32" else np.float64


class Backend(ABC):
    """The interface of a backend (a class in :data:`symkin.numeric.backends.BACKENDS`).

    A backend that evaluates one point of scalars faster than arrays may also define
    ``evaluate_scalar(values) -> list | None`` (None: take the array path);
    :class:`~symkin.numeric.function.NumericFunction` calls it for calls without arrays.
    One that has a faster path for its common array call sets :attr:`array_entry`."""

    key: ClassVar[str]  # its name in BACKENDS
    #: A function of the call's values for a call whose first value is an array, returning what
    #: the call returns, or None for :meth:`evaluate` to take the call (set by a backend once it
    #: has one; the numba backend's small calls).
    array_entry: Callable[[Sequence[Any]], Any] | None = None
    precisions: ClassVar[tuple[str, ...]]  # what precision= may be; the first is the default
    floats: ClassVar[bool]  # computes in binary floating point: given the stable forms

    def __init__(self, plan: Plan):
        self.plan = plan

    @property
    @abstractmethod
    def source(self) -> str:
        """The generated source, for reading."""

    @abstractmethod
    def evaluate(self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None) -> Result:
        """The laws at ``values`` (numbers or arrays in the order of the plan's arguments),
        written into ``outs`` when given."""


def lambdify_source(func: Callable[..., Any]) -> str:
    """The source of a function made by ``sympy.lambdify`` (empty where it cannot be read)."""
    try:
        return inspect.getsource(func)
    except (OSError, TypeError):  # pragma: no cover
        return ""


# --------------------------------------------------------------------------- input checks
#: What each refused NumPy dtype kind holds, for the error message.
_KIND_WORDS = {"c": "complex", "b": "boolean", "U": "text", "S": "bytes", "M": "date", "m": "time-span", "V": "raw"}
_INT64_MAX = np.iinfo(np.int64).max
_REFUSED = (bool, np.bool_, complex, np.complexfloating, str, bytes)


def _refusal(name: str, got: str, integer: bool) -> InputError:
    if integer:
        return InputError(f"{name} is a tooth number (an integer), got {got}; give whole numbers below 2^63 in magnitude")
    return InputError(f"{name} must be a real number or an array of them, got {got}; give int or float values")


def _describe(v: Any) -> str:
    text = repr(v)
    return text if len(text) <= 40 else text[:37] + "..."


def _real_item(v: Any, name: str) -> float:
    """One element of an object array as a Python float, or an InputError."""
    if v is None or isinstance(v, _REFUSED):
        raise _refusal(name, _describe(v), False)
    try:
        return float(v)  # Fraction, Decimal, SymPy and mpmath reals; a SymPy symbol or I raises
    except (TypeError, ValueError, OverflowError):
        raise _refusal(name, _describe(v), False) from None


def _integer_item(v: Any, name: str) -> int:
    """One element of an object array as a Python int, or an InputError."""
    if isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_)):
        return int(v)
    if v is None or isinstance(v, _REFUSED):
        raise _refusal(name, _describe(v), True)
    try:
        as_int = int(v)
        whole = as_int == v
    except (TypeError, ValueError, OverflowError):
        whole = False
    if not whole:
        raise _refusal(name, _describe(v), True)
    return as_int


def _integer_objects(a: np.ndarray, name: str) -> np.ndarray:
    """An object array of tooth numbers as int64, or as Python integers where int64 cannot hold them."""
    values = [_integer_item(v, name) for v in a.reshape(-1)]
    if all(-_INT64_MAX <= v <= _INT64_MAX for v in values):
        return np.array(values, dtype=np.int64).reshape(a.shape)
    out = np.empty(len(values), dtype=object)
    out[:] = values
    return out.reshape(a.shape)


def as_integers(a: np.ndarray, name: str) -> np.ndarray:
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
        return _integer_objects(a, name)
    raise _refusal(name, f"{_KIND_WORDS.get(kind, a.dtype.name)} values", True)


def as_floats(a: np.ndarray, name: str, dtype: Any) -> np.ndarray:
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


def allocate(outs: Sequence[np.ndarray] | None, count: int, n: int, dtype: Any) -> list[np.ndarray]:
    """``count`` flat output arrays of ``n`` values: new ones, or the caller's ``out=`` arrays
    (checked: one per output, C-contiguous, of the size and type of the call)."""
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
