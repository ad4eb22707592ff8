"""The compiled function a user calls: argument order, precision and backend stated.

    >>> import symkin
    >>> f = symkin.compile(symkin.schemes.two_row("AI", teeth=True).ratio("1", "H", fixed="4"), backend="numpy")
    >>> f
    <NumericFunction i_{1H}^{(4)}(z_1, z_2, z_3, z_4): numpy float64>
    >>> f(20, 30, 20, 70)
    np.float64(6.25)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np

from symkin.errors import (
    FloatOverflowWarning,
    InputError,
    NonFiniteInputWarning,
    PoleError,
    PoleWarning,
    PrecisionWarning,
)

__all__ = ["NumericFunction", "NonFiniteInputWarning"]  # the warning lives in symkin.errors



_REBUILT: dict[Any, NumericFunction] = {}

#: What a float function does where an output is not finite: warn (PoleWarning or
#: NonFiniteInputWarning), raise PoleError, or return the inf/nan values for a caller that
#: tests them itself (a sieve that discards such points).
ON_POLE = ("warn", "raise", "return")
_ARRAYS = (list, tuple, np.ndarray)


class NumericFunction:
    """A compiled law, or several sharing their common subexpressions.

    Call it with numbers or arrays in the order of :attr:`args` (they broadcast); it
    returns one array per law (a tuple when several), of the shape of the broadcast
    inputs, or a scalar for scalar inputs.

    Attributes
    ----------
    args : tuple of str
        Argument order.
    outputs : tuple of str
        What each output is (the laws' left-hand sides).
    backend : str
        ``"numpy"``, ``"numba"``, ``"mpmath"`` or ``"exact"``.
    precision : str
        ``"float64"``, ``"float32"``, ``"50 digits"`` (mpmath) or ``"exact"``.
    notes : tuple of str
        What the stable-form rewriting changed.
    source : str
        The generated code (for numba: the loop of the first call).

    Notes
    -----
    Float backends check every output value: a nan or inf is never silent.  Where an
    input is nan or infinite a :class:`NonFiniteInputWarning` counts the points; elsewhere
    a :class:`~symkin.errors.PoleWarning` does (``on_pole="raise"`` raises
    :class:`~symkin.errors.PoleError` instead).  Complex, boolean, text and None inputs
    are refused with an :class:`~symkin.errors.InputError`.

    Denominators that are integer polynomials of tooth numbers (exact), differences of
    two inputs, differences of two products of inputs ``a b - c d`` (double-double) or
    sums of like-signed terms, and products of these, are zero exactly where the law has
    a pole for the binary inputs given, and lose no digits near one: there the result is
    inf or nan at a pole, never a finite number.  Other denominators are evaluated as
    written and can lose digits near their poles (see ``docs/numerics.md``).
    """

    def __init__(self, evaluator: Any, plan: Any, backend: str, notes: Sequence[str], spec: Any, on_pole: str = "warn"):
        self._evaluator = evaluator
        self._plan = plan
        self._spec = spec
        self._token: str | None = None
        self._float64: NumericFunction | None = None  # the float64 twin that checks float32 results
        self.args: tuple[str, ...] = tuple(s.name for s in plan.args)
        self._arity = len(self.args)
        self.outputs: tuple[str, ...] = plan.names
        self.backend = backend
        self.precision = plan.precision if backend not in ("mpmath",) else f"{plan.digits} digits"
        self._narrow = self.precision == "float32"
        self.notes = tuple(notes)
        if on_pole not in ON_POLE:
            raise InputError(f"on_pole must be one of {', '.join(map(repr, ON_POLE))}, got {on_pole!r}")
        self.on_pole = on_pole
        # the exact and mpmath backends evaluate point by point: a call with scalars goes
        # straight to the generated function, without arrays
        # (the float backends: one float64 point in Python floats, or None for the array path)
        self._scalar: Any = getattr(evaluator, "evaluate_scalar", None)
        self._scalar_typed = bool(getattr(evaluator, "scalar_types_checked", False))
        # the common scalar call's own function (numpy, numba), built at the first call; False: none
        self._entry_builder: Any = getattr(evaluator, "scalar_entry", None)
        self._entry: Any = None if self._entry_builder is not None else False
        lines = [
            f"Compiled {', '.join(self.outputs)} ({self.backend}, {self.precision}).",
            "",
            f"Arguments, in order: {', '.join(self.args) or '(none)'}.",
        ]
        if self.notes:
            lines += ["", "Stable forms: " + "; ".join(self.notes) + "."]
        self.__doc__ = "\n".join(lines)

    @property
    def source(self) -> str:
        """The generated source of the function's backend (for reading; it states the argument order)."""
        return self._evaluator.source

    @property
    def exprs(self) -> tuple[Any, ...]:
        """The laws compiled, as given."""
        return self._plan.exprs

    @property
    def stable_exprs(self) -> tuple[Any, ...]:
        """The laws as the float code evaluates them (after the stable-form rewriting)."""
        return self._plan.stable

    def __repr__(self) -> str:
        how = self.backend if self.precision == self.backend else f"{self.backend} {self.precision}"
        return f"<NumericFunction {', '.join(self.outputs)}({', '.join(self.args)}): {how}>"

    def __reduce__(self) -> Any:
        # pickled as a digest and what it was compiled from; a process that has rebuilt it
        # once finds it by the digest and never unpickles the SymPy expressions again
        import pickle

        if self._token is None:
            self._token = self._spec.key()
        return (_rebuild, (self._token, pickle.dumps(self._spec)))

    def __call__(self, *values: Any, out: Sequence[np.ndarray] | np.ndarray | None = None) -> Any:
        if len(values) != self._arity:
            raise InputError(f"this function takes {len(self.args)} arguments ({', '.join(self.args)}), got {len(values)}")
        if out is None:
            if values and type(values[0]) is np.ndarray:
                fast = self._evaluator.array_entry  # the numba kernel's common small call, once it has run
                if fast is not None:
                    r = fast(values)
                    if r is not None:
                        return r
            elif self._entry is not False:
                entry = self._entry
                if entry is None:
                    entry = self._entry = self._entry_builder() or False
                if entry is not False:  # the float backends' common scalar call: one generated function
                    r = entry(values)
                    if r is not None:
                        return r
            # (the float backends' scalar path checks the types itself: no loop here)
            if (not (values and type(values[0]) is np.ndarray) if self._scalar_typed else (
                    self._scalar is not None and not any(isinstance(v, _ARRAYS) for v in values))):
                point = self._scalar(values)
                if point is not None:
                    return point[0] if len(point) == 1 else tuple(point)
        elif isinstance(out, np.ndarray):
            out = [out]
        shape, results, flagged = self._evaluator.evaluate(values, out)
        if flagged and self.on_pole != "return":
            self._check_poles(values, shape, results)
        if self._narrow:
            self._check_float32(values, shape, results)
        if out is None and len(results) == 1:  # (the common call: one output)
            r = results[0]
            if r.shape != shape:
                r = r.reshape(shape)
            return r[()] if shape == () else r
        return _shaped(results, shape, out)

    def _check_poles(self, values: Sequence[Any], shape: tuple[int, ...], results: Sequence[np.ndarray]) -> None:
        """Say where outputs are not finite: at non-finite inputs, or at a pole."""
        bad = [np.flatnonzero(~np.isfinite(r)) for r in results]
        if not any(b.size for b in bad):
            return
        arrays = [_reported(v, shape) for v in values]
        total = math.prod(shape)
        finite_in = np.logical_and.reduce([np.isfinite(a) for a in arrays]) if arrays else np.ones(total, bool)
        for name, b in zip(self.outputs, bad):
            if not b.size:
                continue
            given = b[~finite_in[b]]
            if given.size:
                msg = (
                    f"{name} is nan or infinite at {given.size} of {total} points where an input is nan or infinite "
                    f"(first at {_point(self.args, arrays, int(given[0]))}); those points hold nan or inf"
                )
                warnings.warn(msg, NonFiniteInputWarning, stacklevel=3)
            b = b[finite_in[b]]
            if not b.size:
                continue
            size = self._overflow(name, arrays, int(b[0]))
            if size is not None:
                value = "0" if size == -math.inf else f"about 10^{size:.0f}"
                msg = (
                    f"{name} overflows {self.precision} at {b.size} of {total} points (first at "
                    f"{_point(self.args, arrays, int(b[0]))}, where the law is finite, {value}): it, or a value on "
                    "the way to it, is too large for the float type, not a pole"
                )
                if self.on_pole == "raise":
                    raise InputError(msg + "; choose inputs of smaller size (other units), or the mpmath backend")
                warnings.warn(msg + "; those points hold inf or nan", FloatOverflowWarning, stacklevel=3)
                continue
            msg = (
                f"{name} is infinite or undefined at {b.size} of {total} points (first at {_point(self.args, arrays, int(b[0]))}): "
                f"a denominator vanishes there in {self.precision} (a pole of the law, or inputs closer to one "
                f"than {self.precision} resolves)"
            )
            if self.on_pole == "raise":
                raise PoleError(msg + "; choose inputs away from it")
            warnings.warn(msg + "; those points hold inf or nan", PoleWarning, stacklevel=3)


    #: Relative difference from the float64 evaluation beyond which a float32 result has
    #: lost its precision (float32 rounds at 2^-24: 8 of its 24 bits gone).
    F32_TOLERANCE = 2.0**-16

    def _check_float32(self, values: Sequence[Any], shape: tuple[int, ...], results: Sequence[np.ndarray]) -> None:
        """Warn (PrecisionWarning) where inputs given in more precision than float32 were
        rounded to float32 and that rounding moved the result by more than
        :attr:`F32_TOLERANCE` of the largest value of the call (near a pole, a few units
        of 2^-24 in an input are the whole denominator).  The float64 evaluation this
        takes is paid only for inputs float32 does not hold; float32 inputs cost nothing here."""
        try:
            arrays = [np.asarray(v, dtype=np.float64) for v in values]
        except (TypeError, ValueError, OverflowError):
            return
        if all(np.array_equal(a.astype(np.float32), a, equal_nan=True) for a in arrays):
            return  # the float32 inputs are the inputs: the stable forms hold
        if self._float64 is None:
            import dataclasses

            options = dict(self._spec.options)
            options.update(precision="float64", backend="numpy", on_pole="return")
            spec = dataclasses.replace(self._spec, options=tuple(sorted(options.items())))
            self._float64 = spec.build()
        wide = self._float64(*arrays)
        wide = wide if isinstance(wide, tuple) else (wide,)
        total = math.prod(shape)
        for name, narrow, w in zip(self.outputs, results, wide):
            w = np.reshape(w, -1)
            narrow = np.reshape(narrow, -1).astype(np.float64)
            finite = np.isfinite(w)
            if not finite.any():
                continue
            scale = float(np.max(np.abs(w[finite])))  # normwise: a zero crossing of an oscillating law is no loss
            with np.errstate(all="ignore"):
                lost = finite & (w != 0) & ~(np.abs(narrow - w) <= self.F32_TOLERANCE * scale)
            count = int(np.count_nonzero(lost))
            if not count:
                continue
            i = int(np.flatnonzero(lost)[0])
            flat = [np.broadcast_to(a, shape).reshape(-1) for a in arrays]
            warnings.warn(
                f"{name} in float32 differs from its float64 value by up to "
                f"{float(np.max(np.abs(narrow[lost] - w[lost]) / np.abs(w[lost]))):.2g} (relative) at {count} of {total} "
                f"points (first at {_point(self.args, flat, i)}): rounding the inputs to float32 moved them "
                "near a pole or a zero of the law, where float32 cannot hold the result; give float32 inputs, "
                "or compile with precision='float64'",
                PrecisionWarning, stacklevel=3,
            )

    def _overflow(self, name: str, arrays: Sequence[np.ndarray], i: int) -> float | None:
        """log10 of the size of output ``name`` at point ``i`` if the law is finite there and it,
        or a value on the way to it, is beyond the float range (an overflow, not a pole); else
        None.  Decided on intervals (:mod:`symkin._util.bounds`), so an exact pole (a
        denominator exactly 0) is never taken for an overflow."""
        import sympy as sp

        from symkin._util.bounds import Encloser, NotConstant, NotReal, Unbounded, Undecided, magnitude
        from symkin._util.budget import time_limit

        expr = self._plan.exprs[self.outputs.index(name)]
        env = {s: (sp.Rational(float(a[i])), sp.Rational(float(a[i]))) for s, a in zip(self._plan.args, arrays)}
        encloser = Encloser(64, env, limits=False)
        try:
            with time_limit(1.0, "too slow"):
                x = encloser.enclose(sp.sympify(expr))
        except (InputError, NotConstant, NotReal, Unbounded, Undecided, TypeError, ValueError, ZeroDivisionError):
            return None
        limit = math.log10(float(np.finfo(self._plan.dtype).max))
        largest = max(magnitude(v) for v in encloser.memo.values())
        return magnitude(x) if largest > limit else None


def _reported(v: Any, shape: tuple[int, ...]) -> np.ndarray:
    """An input as flat floats of ``shape``, for messages (Python integers too large for a
    float count as finite)."""
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError, OverflowError):
        items = np.asarray(v, dtype=object)
        a = np.array([_float_or_zero(x) for x in items.reshape(-1)]).reshape(items.shape)
    return np.broadcast_to(a, shape).reshape(-1)


def _float_or_zero(x: Any) -> float:
    try:
        return float(x)
    except (TypeError, ValueError, OverflowError):
        return 0.0


def _point(names: Sequence[str], arrays: Sequence[np.ndarray], i: int) -> str:
    return ", ".join(f"{n}={float(a[i]):.17g}" for n, a in zip(names, arrays))


def _rebuild(token: str, payload: bytes) -> NumericFunction:
    if token not in _REBUILT:
        import pickle

        function = pickle.loads(payload).build()
        function._token = token
        _REBUILT[token] = function
    return _REBUILT[token]


def _shaped(results: Sequence[np.ndarray], shape: tuple[int, ...], out: Sequence[np.ndarray] | None) -> Any:
    """What a call returns: the ``out=`` arrays, or the results in the shape of the call (a
    scalar each for scalar inputs), one array, or a tuple when there are several."""
    if out is not None:
        shaped = list(out)
    else:
        shaped = [r if r.shape == shape else r.reshape(shape) for r in _distinct(results)]
        if shape == ():
            shaped = [r[()] for r in shaped]
    return shaped[0] if len(shaped) == 1 else tuple(shaped)


def _distinct(results: Sequence[np.ndarray]) -> list[np.ndarray]:
    """The results with a copy of any array already among them: equal laws (``[x*y, x*y]``)
    come out of the generated code as one array, and a caller writing into one would change both."""
    seen: set[int] = set()
    out = []
    for r in results:
        out.append(r.copy() if id(r) in seen else r)
        seen.add(id(r))
    return out
