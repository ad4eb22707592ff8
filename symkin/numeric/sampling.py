"""Laws in time on a time grid: the one sampler of figures, trajectories and tables.

Every time grid symkin samples (a particle's path, the frames of an animation, the
Cardan slider's table) is checked here, once, the same way, and evaluated through
:func:`symkin.compile`, so the numeric guarantees hold for figures too: a law that is
infinite or undefined on the grid raises :class:`~symkin.errors.PoleError` naming the
first time where it happens, never a silent nan.

    >>> import sympy as sp
    >>> from symkin import symbols as S
    >>> t = time_grid(sp.pi, samples=3)
    >>> [round(float(v), 6) for v in t]
    [0.0, 1.570796, 3.141593]
    >>> x, = on_grid([sp.sin(S.t)], t)
    >>> [round(float(v), 12) + 0.0 for v in x]
    [0.0, 1.0, 0.0]
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError
from symkin.laws import Law
from symkin.numeric import compile
from symkin.values import as_float, as_values, substitute

__all__ = ["MAX_SAMPLES", "time_grid", "as_times", "on_grid"]

#: The most points a time grid may hold (ten million: hundreds of MB of arrays).
MAX_SAMPLES = 10_000_000


def _count(samples: Any, low: int) -> int:
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or not low <= samples <= MAX_SAMPLES:
        raise InputError(f"samples must be an integer from {low} to {MAX_SAMPLES}, got {samples!r}")
    return int(samples)


def time_grid(t_end: Any, *, t_start: Any = 0.0, samples: Any = 721) -> np.ndarray:
    """``samples`` equally spaced times from ``t_start`` to ``t_end`` (both included).

    Times are numbers (exact ones too: ``sp.pi``), finite, and increasing; ``samples``
    an integer from 2 to :data:`MAX_SAMPLES`.

    >>> time_grid(2, samples=5)
    array([0. , 0.5, 1. , 1.5, 2. ])
    >>> time_grid(0, samples=5)
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the time span must be increasing, got 0.0 to 0.0; give an end time after the start
    """
    start = as_float(t_start, what="the start time")
    end = as_float(t_end, what="the end time")
    n = _count(samples, 2)
    if not end > start:
        raise InputError(f"the time span must be increasing, got {start} to {end}; give an end time after the start")
    return np.linspace(start, end, n)


def as_times(times: Any) -> np.ndarray:
    """A time grid a caller gives: a non-empty 1-D array of finite, strictly increasing times.

    >>> as_times([0, 0.5, 1.0])
    array([0. , 0.5, 1. ])
    >>> as_times([1, 0])
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the times must be strictly increasing (time 2 is 0.0, after 1.0)
    """
    try:
        ts = np.asarray(times, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise InputError(f"times must be a sequence of numbers, got {str(times)[:40]!r}") from None
    if ts.ndim == 0:
        ts = ts.reshape(1)
    if ts.ndim != 1 or ts.size == 0:
        raise InputError("the time grid is empty or not one-dimensional; give at least one time")
    if ts.size > MAX_SAMPLES:
        raise InputError(f"the time grid holds {ts.size} times; at most {MAX_SAMPLES}")
    if not np.all(np.isfinite(ts)):
        raise InputError("the time grid holds a value that is not a finite number")
    steps = np.diff(ts)
    if ts.size > 1 and not np.all(steps > 0):
        k = int(np.argmax(~(steps > 0)))
        raise InputError(f"the times must be strictly increasing (time {k + 2} is {ts[k + 1]}, after {ts[k]})")
    return ts


def on_grid(
    exprs: Sequence[Any], t: Any, values: Mapping[Any, Any] | None = None, *, what: str = "sample the laws",
    names: Sequence[str] | None = None,
) -> list[np.ndarray]:
    """Each expression in :data:`symkin.symbols.t` evaluated on the grid ``t``.

    ``values`` gives numbers for every other symbol ({symbol or name: number}); a symbol
    left without one is an :class:`~symkin.errors.InputError` that names it (and says it
    was needed to ``what``).  The laws are compiled together by :func:`symkin.compile`
    (shared subexpressions, stable forms); a non-finite value anywhere on the grid raises
    :class:`~symkin.errors.PoleError`.  ``names`` (one per expression) name the laws in a
    refusal ("the slider's acceleration a holds a number of about 10^600").  Returns one
    float64 array per expression, of the grid's shape.
    """
    grid = t if isinstance(t, np.ndarray) and t.dtype == np.float64 else as_times(t)
    subs = as_values(values)
    laws = [substitute(sp.sympify(e), subs) for e in exprs]
    free = set().union(*(e.free_symbols for e in laws)) - {S.t}
    if free:
        raise InputError(f"give values for {', '.join(sorted(map(str, free)))} to {what}")
    if not laws:
        return []
    if names is not None:
        laws = [Law(sp.Symbol(name), law) for name, law in zip(names, laws, strict=True)]
    f = compile(laws, [S.t], backend="numpy", on_pole="raise")
    out = f(grid)
    columns = out if isinstance(out, tuple) else (out,)
    return [np.array(np.broadcast_to(np.asarray(c, dtype=float), grid.shape)) for c in columns]
