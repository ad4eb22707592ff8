"""Bounded simplification: a size and a time budget, with the unsimplified law kept and a warning."""

import signal
import threading
import time
import warnings

import pytest
import sympy as sp

from symkin import SimplificationBudgetWarning
from symkin._util.budget import simplify_within
from symkin.mechanisms.cardan import CardanSlider
from symkin.parsing import parse_expression

#: A number whose simplification takes about a minute with SymPy 1.14 (trigsimp of the expanded power).
SLOW = (sp.sin(1) + sp.cos(1) + sp.tan(1) + sp.sqrt(3)) ** 30 / (2 * sp.pi)


def test_a_slow_simplification_is_stopped_and_the_expression_kept():
    start = time.perf_counter()
    with pytest.warns(SimplificationBudgetWarning, match="longer than 0.5 s"):
        out = simplify_within(SLOW, seconds=0.5, what="the slow number")
    assert out is SLOW
    assert time.perf_counter() - start < 3


def test_the_same_expression_really_is_slow():
    """Twice the budget is not enough either: the cut-off above is not for show."""
    with pytest.warns(SimplificationBudgetWarning):
        simplify_within(SLOW, seconds=1.0)


def test_a_quick_simplification_is_done_and_silent():
    x = sp.Symbol("x")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert simplify_within(sp.sin(x) ** 2 + sp.cos(x) ** 2, seconds=5) == 1
        assert simplify_within(sp.Integer(4) / 6, simplifier=sp.nsimplify) == sp.Rational(2, 3)


def test_the_size_budget_refuses_without_trying():
    x = sp.Symbol("x")
    big = sp.Add(*(sp.sin(k * x) ** k for k in range(1, 400)))
    start = time.perf_counter()
    with pytest.warns(SimplificationBudgetWarning, match="operations"):
        assert simplify_within(big, max_ops=500) is big
    assert time.perf_counter() - start < 1


def test_an_outer_timer_survives_and_still_fires():
    fired = []

    def outer(signum, frame):
        fired.append(time.perf_counter())

    previous = signal.signal(signal.SIGALRM, outer)
    try:
        start = time.perf_counter()
        signal.setitimer(signal.ITIMER_REAL, 1.0)
        assert simplify_within(sp.sqrt(8), seconds=5) == 2 * sp.sqrt(2)
        assert signal.getitimer(signal.ITIMER_REAL)[0] > 0.5  # re-armed with what was left
        while not fired and time.perf_counter() - start < 5:
            time.sleep(0.01)
        assert fired and fired[0] - start == pytest.approx(1.0, abs=0.3)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _in_a_thread(fn):
    out, caught = [], []

    def work():
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            start = time.perf_counter()
            out.append(fn())
            out.append(time.perf_counter() - start)
        caught.extend(seen)

    worker = threading.Thread(target=work)
    worker.start()
    worker.join(60)
    assert not worker.is_alive()
    return out[0], out[1], caught


def test_off_the_main_thread_there_is_no_time_limit_but_the_size_budget_holds():
    # a Dask worker or a Jupyter background thread has no SIGALRM: the work runs to its end
    from symkin._util.budget import time_limit

    handler = signal.getsignal(signal.SIGALRM)

    def sleep_past_the_limit():
        with time_limit(0.05, "too long"):
            time.sleep(0.3)
        return "done"

    out, seconds, caught = _in_a_thread(sleep_past_the_limit)
    assert out == "done" and seconds >= 0.3 and not caught
    x = sp.Symbol("x")
    out, _, caught = _in_a_thread(lambda: simplify_within(sp.sin(x) ** 2 + sp.cos(x) ** 2, seconds=0.5))
    assert out == 1 and not caught
    big = sp.Add(*(sp.sin(k * x) ** k for k in range(1, 400)))
    out, seconds, caught = _in_a_thread(lambda: simplify_within(big, max_ops=500))
    assert out is big and seconds < 1 and [w.category for w in caught] == [SimplificationBudgetWarning]
    assert signal.getsignal(signal.SIGALRM) is handler  # the main thread's timer signal was left alone


def test_the_cardan_path_for_a_slow_angle_is_decided_within_the_budget():
    # unbudgeted, deciding the installation condition for this pin angle took 69 s
    start = time.process_time()  # CPU time: a loaded machine slows the wall clock, not the work
    slider = CardanSlider.build(1, drive=1, pin_angle=parse_expression("(sin(1)+cos(1)+tan(1)+sqrt(3))**30"))
    with pytest.warns(SimplificationBudgetWarning, match="kept as derived"):
        path = slider.path()
    assert time.process_time() - start < 15
    # the pin must sit at angle 0 (mod 2 pi) for the slider to follow; this angle (about 1.2e20 rad) is
    # 0.41 turns away from a whole number of turns, so the pin draws a line off the guide
    assert sp.N(SLOW, 60) % 1 == pytest.approx(0.4096, abs=1e-3)
    assert path.kind == "line off the guide"


def _stubborn(swallowed):
    def stubborn(expr):
        deadline = time.perf_counter() + 30
        while time.perf_counter() < deadline:
            try:
                while time.perf_counter() < deadline:
                    sum(range(1000))
            except BaseException as exc:  # what careless code does
                if swallowed:
                    raise
                swallowed.append(type(exc).__name__)
        return expr

    return stubborn


def test_an_interrupt_that_is_swallowed_comes_again():
    # the first interrupt can land where Python drops exceptions (a __del__, a gc callback) or in a
    # bare except; the budget must still stop the work
    swallowed = []
    start = time.perf_counter()
    with pytest.warns(SimplificationBudgetWarning, match="longer than 0.2 s"):
        simplify_within(sp.Integer(1), seconds=0.2, simplifier=_stubborn(swallowed))
    assert swallowed == ["_OutOfTime"] and time.perf_counter() - start < 5
