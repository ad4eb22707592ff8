"""Cost of the time budget off the main thread against the main thread's timer.

Run: ``python benchmarks/bench_budget.py``.  Simplifies the same expressions under
``simplify_within`` on the main thread (SIGALRM), in a worker thread (the watchdog that
raises in the thread, CPython) and in a worker thread with the call-tracer fallback (other
Pythons), and without any budget; prints medians and the ratios to no budget.
"""

from __future__ import annotations

import statistics
import threading
import time

import sympy as sp

from symkin import schemes
from symkin._util import budget
from symkin._util.budget import simplify_within

x = sp.Symbol("x")
CASES = {
    "trig identity": lambda: (sp.sin(x) ** 4 - sp.cos(x) ** 4 + sp.cos(2 * x)) * (1 + sp.tan(x) ** 2),
    "AI speed law": lambda: sp.together(schemes.two_row("AI").speeds({"1": sp.Symbol("w1"), "4": sp.Symbol("w4")})["H"]),
}


def _median(fn, repeat: int = 7) -> float:
    times = []
    for _ in range(repeat):
        sp.core.cache.clear_cache()
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def _in_thread(fn) -> float:
    out: list[float] = []
    worker = threading.Thread(target=lambda: out.append(_median(fn)))
    worker.start()
    worker.join()
    return out[0]


def main() -> None:
    for name, make in CASES.items():
        expr = make()
        plain = _median(lambda: sp.simplify(expr))
        timer = _median(lambda: simplify_within(expr, seconds=60))
        watchdog = _in_thread(lambda: simplify_within(expr, seconds=60))
        found = budget._set_async_exc
        budget._set_async_exc = lambda: None
        try:
            traced = _in_thread(lambda: simplify_within(expr, seconds=60))
        finally:
            budget._set_async_exc = found
        print(f"{name:14s} no budget {plain * 1e3:7.1f} ms   main thread (SIGALRM) {timer / plain:5.2f}x   "
              f"worker thread: watchdog {watchdog / plain:5.2f}x, call tracer {traced / plain:5.2f}x")


if __name__ == "__main__":
    main()
