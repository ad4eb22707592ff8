"""Bounded symbolic work: simplification with a size and a time budget (CPU time).

SymPy's ``simplify`` can take minutes, or practically forever, on a large expression,
and the size of many expressions symkin simplifies depends on what a user typed (an
angle such as ``(sin(1) + cos(1) + tan(1) + sqrt(3))**30``, a custom mechanism).
:func:`simplify_within` refuses expressions above an operation count, stops the
simplification when its time is up, and then returns the expression as it was, with a
:class:`~symkin.errors.SimplificationBudgetWarning`: the law stays exact, only less tidy.

The time limit counts the CPU time of the process (all its threads), not the time on the
clock: on a loaded machine the same work gets the same budget, so whether a law is simplified,
or a value refused, does not depend on what else the machine is doing, and a block that
waits (on a sleep, a file, a lock) uses none of it.  It is kept by the profiling interval
timer (``ITIMER_PROF``, signal SIGPROF) of the main thread, which interrupts SymPy's
pure-Python work wherever it is, at no cost per call; an outer budget (one of these blocks
inside another) is kept and re-armed.  SIGALRM and the real-time timer are left alone, so a
test harness's or a user's alarm is not touched.  A profiler that samples with SIGPROF or
``ITIMER_PROF`` (vmprof, gperftools' CPU profiler) conflicts with these budgets: it should
not run together with them.  The interrupt is raised again every 0.1 s of CPU time until the
work has stopped, since one can land where Python drops exceptions (a weakref callback) or
in a bare ``except``.  Work inside one C call (a large integer product, say) is not
interrupted.  Off the main thread (a Dask worker, a Jupyter background thread, a web
server's request thread), or where the platform has no interval timer, signals cannot be
used and there is no time limit: the operation count of :func:`simplify_within` still
bounds what is simplified.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> simplify_within(sp.sin(x)**2 + sp.cos(x)**2)
    1
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     big = sum(x**k for k in range(300))
    ...     simplify_within(big, max_ops=100) is big
    True
    >>> caught[0].category.__name__
    'SimplificationBudgetWarning'
"""

from __future__ import annotations

import signal
import sys
import threading
import time
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import sympy as sp

from symkin.errors import InputError, SimplificationBudgetWarning
from symkin.values import as_rational

__all__ = ["simplify_within", "time_limit", "seconds_limit", "SECONDS", "MAX_OPS"]

#: Default time budget of one simplification, CPU seconds of the process.
SECONDS = 2.0
#: Default size budget: expressions with more operations than this are not simplified.
MAX_OPS = 4000


class _OutOfTime(BaseException):
    """Raised by the timer inside SymPy (not an Exception, so no ``except Exception`` there eats it)."""


def simplify_within(
    expr: Any,
    seconds: float | None = SECONDS,
    max_ops: int | None = MAX_OPS,
    *,
    simplifier: Callable[[Any], Any] = sp.simplify,
    what: str = "an expression",
) -> Any:
    """``simplifier(expr)`` if it fits the budget, else ``expr`` unchanged with a warning.

    Parameters
    ----------
    expr : sympy expression (or anything ``simplifier`` takes)
    seconds : float or None
        Time budget in CPU seconds of the process; None for no time limit.  Kept in the main
        thread only (see above).
    max_ops : int or None
        Largest :func:`sympy.count_ops` of an expression that is simplified at all.
    simplifier : callable
        ``sympy.simplify`` by default; ``sympy.trigsimp``, ``sympy.nsimplify`` or any
        one-argument function may be given.
    what : str
        What the expression is, for the warning.

    Returns
    -------
    The simplified expression, or ``expr`` itself when the budget ran out.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> simplify_within((x**2 - 1) / (x - 1), seconds=1)
    x + 1
    """
    if max_ops is not None:
        ops = sp.count_ops(expr)
        if ops > max_ops:
            warnings.warn(
                f"{what} has {ops} operations, more than the {max_ops} symkin simplifies; it is kept as derived "
                "(exact, not simplified)",
                SimplificationBudgetWarning,
                stacklevel=2,
            )
            return expr
    if seconds is None:
        return simplifier(expr)
    try:
        with _time_limit(seconds):
            return simplifier(expr)
    except _OutOfTime:
        warnings.warn(
            f"simplifying {what} took longer than {seconds:g} s of CPU time; it is kept as derived (exact, not simplified)",
            SimplificationBudgetWarning,
            stacklevel=2,
        )
        return expr


@contextmanager
def time_limit(seconds: float, message: str, error: type[Exception] = InputError) -> Iterator[None]:
    """Run the block for at most ``seconds`` of CPU time; past them, raise ``error(message)``.

    For work whose time follows what a user typed (evaluating an expression, deciding a
    sign) and that has no useful partial result: the user gets a one-line error instead of a
    hang.  The block is interrupted as :func:`simplify_within` is: by a CPU-time timer signal,
    in the main thread only (elsewhere the block runs to its end).  Time the block spends
    waiting (a sleep, a read) does not count.

    >>> with time_limit(0.05, "the angle took too long to evaluate; simplify it"):
    ...     while True:
    ...         _ = sum(range(1000))
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the angle took too long to evaluate; simplify it
    """
    try:
        with _time_limit(seconds):
            yield
    except _OutOfTime:
        raise error(message) from None


def seconds_limit(value: Any) -> float | None:
    """A search's ``time_limit`` as a user gives it: None (no limit), or a positive number of seconds.

    >>> seconds_limit(None), seconds_limit(2), seconds_limit(0.5)
    (None, 2.0, 0.5)
    """
    if value is None:
        return None
    limit = as_rational(value, what="the time limit")
    if limit <= 0:
        raise InputError(f"the time limit must be a positive number of seconds, got {value!r}")
    return float(limit)


#: CPU seconds between repeated interrupts once the time is up (until the block has stopped).
_REFIRE = 0.1


@contextmanager
def _time_limit(seconds: float) -> Iterator[None]:
    """Interrupt the block with :class:`_OutOfTime` once it has used ``seconds`` of the process's CPU time."""
    if threading.current_thread() is not threading.main_thread() or not hasattr(signal, "setitimer"):
        yield  # no signals here: no time limit
        return

    active = [True]

    def expire(signum: int, frame: Any) -> None:
        if active[0]:
            raise _OutOfTime

    # an outer budget (this block nested in another's) is kept: the inner one ends at the latest when
    # the outer one does, and the outer one is re-armed with the CPU time it has left
    def dropped(unraisable: Any) -> None:
        # an interrupt Python drops (it landed in a __del__ or a gc callback) comes again in 0.1 s: not
        # news to print ("Exception ignored in ..."), nor for a test harness's hook to format, where the
        # next one could land and break the hook itself
        if not isinstance(unraisable.exc_value, _OutOfTime):
            hook(unraisable)

    outer_left, outer_interval = signal.getitimer(signal.ITIMER_PROF)
    start = time.process_time()
    hook = sys.unraisablehook
    sys.unraisablehook = dropped
    previous = signal.signal(signal.SIGPROF, expire)
    # then again every _REFIRE s: an interrupt that lands where Python drops exceptions (a __del__, a
    # weakref or gc callback: "Exception ignored in ...") or that a bare except swallows is raised again
    signal.setitimer(signal.ITIMER_PROF, min(seconds, outer_left) if outer_left > 0 else seconds, _REFIRE)
    try:
        yield
    finally:
        active[0] = False  # a repeat that lands from here on is ignored
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)
        sys.unraisablehook = hook
        if outer_left > 0:  # re-arm the outer budget with what is left of it (at least a moment)
            left = outer_left - (time.process_time() - start)
            signal.setitimer(signal.ITIMER_PROF, max(left, 1e-6), outer_interval)
