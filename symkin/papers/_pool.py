"""Run the papers' checks and figures in worker processes, one per core.

Each paper gives two tasks: its checks (with its notes) and its figures.  A worker that
derived a paper's checks is given that paper's figures next when it is free, so what the
derivation module caches (curves, compiled laws) is computed once; another worker takes
them only when it would otherwise wait.  Workers are forked from the calling process (so
they see its state, patches included) and die with it; a task's exception is raised again
in the calling process.  Where ``fork`` is not available or not safe (:func:`can_fork`) the
tasks run in the calling process, one after the other.
"""

from __future__ import annotations

import contextlib
import copyreg
import gc
import io
import multiprocessing
import os
import pickle
import signal
import sys
import time
import traceback
from collections.abc import Callable, Iterator, Sequence
from multiprocessing.connection import Connection, wait
from pathlib import Path
from typing import Any, cast

from symkin._util import GC_THRESHOLDS
from symkin._util.atomic import STOP_SIGNALS, stop_signals_held
from symkin.errors import ToolError

#: A task: (paper, "checks" or "figures").
Task = tuple[str, str]
#: The garbage collector's thresholds in a worker (see :data:`symkin._util.GC_THRESHOLDS`).
_WORKER_GC_THRESHOLDS = GC_THRESHOLDS


def cores() -> int:
    """The number of cores this process may run on (at least 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def can_fork() -> bool:
    """Whether worker processes can be forked here: on Linux (macOS forks are unsafe with GUI
    libraries), from a process running one thread (a fork copies the locks other threads hold,
    as in a Jupyter kernel, and can deadlock)."""
    import threading

    return (sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods()
            and threading.active_count() == 1)


def _relation(cls: type, lhs: Any, rhs: Any) -> Any:
    """A SymPy relation rebuilt from its sides as it was made: not decided again."""
    return cls(lhs, rhs, evaluate=False)


def _reduce_relation(rel: Any) -> tuple[Any, tuple[Any, ...]]:
    return _relation, (type(rel), rel.lhs, rel.rhs)


def dumps(value: Any) -> bytes:
    """``pickle.dumps(value)``, with SymPy's relations (``Eq``, ``Lt``, ...) rebuilt unevaluated
    when loaded.  By default an ``Eq`` is rebuilt by calling ``Eq(lhs, rhs)``, which tries to
    decide it again from the assumptions: 90 % of the 0.1-0.13 s the calling process spent
    loading alyushin2009's or kladova2010's checks, on the cores the workers need.  A relation
    that exists was not decided when it was made, so it is rebuilt as it is."""
    import sympy as sp

    table = copyreg.dispatch_table.copy()
    for cls in (sp.Eq, sp.Ne, sp.Lt, sp.Le, sp.Gt, sp.Ge):
        table[cls] = _reduce_relation
    buffer = io.BytesIO()
    pickler = pickle.Pickler(buffer, pickle.HIGHEST_PROTOCOL)
    pickler.dispatch_table = table
    pickler.dump(value)
    return buffer.getvalue()


def run_task(modules: dict[str, Any], task: Task, figures_dir: Path) -> tuple[Any, float]:
    """Run one task in this process; returns its value and the seconds it took."""
    name, part = task
    mod = modules[name]
    start = time.perf_counter()
    if part == "checks":
        value: Any = (list(mod.checks()), list(getattr(mod, "notes", lambda: [])()))
    else:
        value = list(mod.figures(figures_dir))
    seconds = time.perf_counter() - start
    return value, seconds


@contextlib.contextmanager
def _collecting_as_a_worker() -> Iterator[None]:
    """The tasks run in this process with the garbage collector as in a worker: what exists
    now frozen, :data:`_WORKER_GC_THRESHOLDS`; both as before afterwards."""
    frozen_before, thresholds = gc.get_freeze_count(), gc.get_threshold()
    gc.freeze()
    gc.set_threshold(*_WORKER_GC_THRESHOLDS)
    try:
        yield
    finally:
        gc.set_threshold(*thresholds)
        if not frozen_before:
            gc.unfreeze()


def _die_with_parent(parent: int) -> None:
    """Ask Linux to kill this worker when the process that forked it ends (PR_SET_PDEATHSIG)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        pass
    if os.getppid() != parent:  # the parent ended before the request was made
        os._exit(1)


def _worker(conn: Connection, parent: int, modules: dict[str, Any], figures_dir: Path) -> None:
    _die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C and ends its workers
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)  # held by the parent while it forked
    gc.set_threshold(*_WORKER_GC_THRESHOLDS)
    while True:
        task = conn.recv()
        if task is None:
            return
        try:
            value, seconds = run_task(modules, task, figures_dir)
            message = dumps(("ok", task, value, seconds))
        except BaseException as err:  # sent to the parent, which raises it
            try:
                message = pickle.dumps(("error", task, err, traceback.format_exc()))
            except Exception:  # an exception that cannot be pickled: its text
                message = pickle.dumps(("error", task, ToolError(f"{type(err).__name__}: {err}"), traceback.format_exc()))
        conn.send_bytes(message)


def run_tasks(
    modules: dict[str, Any],
    tasks: Sequence[Task],
    figures_dir: Path,
    *,
    jobs: int,
    done: Callable[[Task, Any, float], None],
) -> None:
    """Run ``tasks`` on ``jobs`` worker processes (in this process when ``jobs`` is 1 or
    forking is not possible), calling ``done(task, value, seconds)`` in this process as each
    one ends, the next task already given to the worker that ran it (what ``done`` does while
    the workers run shares the cores with them: it falls on both).  The first task to fail
    stops the others and its exception is raised here."""
    jobs = min(jobs, len(tasks))
    if jobs <= 1 or not can_fork():
        with _collecting_as_a_worker():
            for task in tasks:
                value, seconds = run_task(modules, task, figures_dir)
                done(task, value, seconds)
        return
    ctx = multiprocessing.get_context("fork")
    parent = os.getpid()
    workers: list[tuple[Any, Connection]] = []
    pending = list(tasks)
    papers_of: dict[Connection, set[str]] = {}
    try:
        # Ctrl-C or SIGTERM during a fork would raise in the fork's own callbacks, where Python
        # ignores it: held until the workers are started, then raised here
        with stop_signals_held():
            # what the parent loaded (SymPy, matplotlib, the papers: ~130,000 objects) is kept out
            # of the workers' collections, which would otherwise walk it (and copy its pages) in
            # every full collection; the parent's own collector is as before once they are forked
            frozen_before = gc.get_freeze_count()
            gc.freeze()
            try:
                for _ in range(jobs):
                    here, there = ctx.Pipe()
                    proc = ctx.Process(target=_worker, args=(there, parent, modules, figures_dir),
                                       daemon=True)
                    proc.start()
                    there.close()
                    workers.append((proc, here))
                    papers_of[here] = set()
            finally:
                if not frozen_before:
                    gc.unfreeze()
        busy: dict[Connection, Task] = {}

        def give(conn: Connection) -> None:
            if not pending:
                return
            # the figures of a paper this worker derived, else the next task in order
            mine = [t for t in pending if t[1] == "figures" and t[0] in papers_of[conn]]
            task = mine[0] if mine else pending[0]
            pending.remove(task)
            papers_of[conn].add(task[0])
            busy[conn] = task
            conn.send(task)

        for _, conn in workers:
            give(conn)
        while busy:
            for ready in wait(list(busy)):
                conn = cast(Connection, ready)
                try:
                    message = conn.recv_bytes()
                except EOFError:
                    proc = next(p for p, c in workers if c is conn)
                    proc.join(5)
                    raise ToolError(f"a worker process ended during {busy[conn][0]}'s {busy[conn][1]} "
                                    f"(exit code {proc.exitcode})") from None
                del busy[conn]
                # its next task first: rebuilding the value here (the SymPy objects of a paper's
                # checks: up to 0.15 s) must not keep the worker waiting
                give(conn)
                status, task, value, extra = pickle.loads(message)
                if status == "error":
                    raise value
                done(task, value, extra)
    finally:
        for proc, conn in workers:
            if proc.is_alive():
                proc.kill()
            proc.join()
            conn.close()
