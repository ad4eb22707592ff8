"""Running a search's chunks: here, one after another, or on Dask (a scheduler's address or a local cluster).

Either way every chunk is :func:`symkin.synthesis.search.evaluate_chunk` of the same plan,
and the results are merged in chunk order (:func:`~symkin.synthesis.search.merge`), so a
search gives the same answer with ``scheduler=None``, a local cluster, or a remote one.
Progress is reported as chunks finish, and a time limit stops the search with a
:class:`~symkin.errors.TimeLimitError` that says how far it got and suggests bounds.

    >>> from symkin.trains import load_train
    >>> from symkin.synthesis.problem import derive
    >>> from symkin.synthesis.plan import SearchPlan
    >>> from symkin.synthesis.request import Target
    >>> plan = SearchPlan.build(derive(load_train("simple"), driver="S", driven="C", fixed="R", zmax=80), Target.of(4),
    ...                   chunk=10)
    >>> run(plan).found, len(plan.chunks)
    (3, 7)
"""

from __future__ import annotations

import logging
import math
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from symkin.errors import InputError, TimeLimitError, UnsupportedError
from symkin.synthesis.plan import SearchPlan
from symkin.synthesis.search import ChunkResult, evaluate_chunk, merge

__all__ = ["run", "Execution", "local_cluster", "cluster_pays"]

#: Seconds to wait for a Dask scheduler to answer.
CONNECT_TIMEOUT = 5

#: Chunks in flight per Dask worker (the rest are submitted as these finish).
WINDOW = 3

#: Seconds a local cluster costs before it saves any: starting its worker processes (8.4 s on this
#: project's 2 shared cores) and each worker receiving and rebuilding the plan (2.5 s more for a
#: search of 0.07 s here; benchmarks/notes/numeric-backends.md, "Dask").
LOCAL_CLUSTER_COST = 10.0


def cluster_pays(projected: float, workers: int) -> bool:
    """Whether a local cluster of ``workers`` processes is expected to finish a search that
    would take ``projected`` seconds here sooner: at best it divides the time by the workers,
    and it first costs :data:`LOCAL_CLUSTER_COST`.

    >>> cluster_pays(5.0, 2), cluster_pays(60.0, 2), cluster_pays(60.0, 1)
    (False, True, False)
    """
    return workers > 1 and projected * (1 - 1 / workers) > LOCAL_CLUSTER_COST


@dataclass(frozen=True)
class Execution:
    """How a search ran: where, in how many chunks, and how long the chunks took."""

    scheduler: str
    workers: int
    chunks: int
    seconds: float
    chunk_seconds: float

    def to_json(self) -> dict[str, Any]:
        """How the search ran, as JSON: the scheduler, workers, chunks and times."""
        return {"scheduler": self.scheduler, "workers": self.workers, "chunks": self.chunks,
                "seconds": round(self.seconds, 4), "chunk_seconds": round(self.chunk_seconds, 4)}


def run(plan: SearchPlan, *, scheduler: str | None = None, workers: int | None = None, time_limit: float | None = None,
        progress: Callable[[int, int, int], None] | None = None, execution: list[Execution] | None = None,
        spent: float = 0.0) -> ChunkResult:
    """Evaluate every chunk of ``plan`` and merge them.

    Parameters
    ----------
    scheduler : str, optional
        None runs here; ``"local"`` starts a local Dask cluster of ``workers`` processes;
        ``"auto"`` times the first chunk here and starts that cluster only where the search's
        projected time pays for it (:func:`cluster_pays`), else goes on here; an address
        (``"tcp://host:8786"``) uses that Dask scheduler.
    workers : int, optional
        Processes of a local cluster (default: the machine's cores).
    time_limit : float, optional
        Seconds the search may take; longer raises :class:`~symkin.errors.TimeLimitError`.
    spent : float
        Seconds of the time limit already used (deriving and compiling).
    progress : callable(done, total, found), optional
        Called as chunks finish.
    execution : list, optional
        Receives an :class:`Execution` describing the run.
    """
    chunks = plan.chunks
    if time_limit is not None and not (isinstance(time_limit, (int, float)) and time_limit > 0):
        raise InputError(f"the time limit must be a positive number of seconds, got {time_limit!r}")
    if time_limit is not None and spent > time_limit:
        raise TimeLimitError(f"deriving the conditions and compiling the search took {spent:.1f} s, more than the time "
                             f"limit of {time_limit:g} s; raise the time limit")
    if scheduler is None and workers is not None:
        raise InputError("the number of workers is for a local Dask cluster: give the scheduler 'local' or 'auto' with it")
    first: ChunkResult | None = None
    if scheduler == "auto":
        began = time.perf_counter()
        first = evaluate_chunk(plan, *chunks[0])
        projected = (time.perf_counter() - began) * len(chunks)
        n = workers or os.cpu_count() or 1
        if cluster_pays(projected, n):
            scheduler, first = "local", None  # (the cluster searches every chunk: the answer does not depend on where)
        else:
            scheduler = None
            note = f"here (a local cluster of {n} would not pay: about {projected:.2g} s of search)"
    if first is not None:
        results, used, where = _local(plan, chunks, time_limit, progress, spent, first), 1, note
    elif scheduler is None:
        results, used = _local(plan, chunks, time_limit, progress, spent), 1
        where = "here"
    else:
        results, used, where = _dask(plan, chunks, scheduler, workers, time_limit, progress, spent)
    merged = merge(plan, results)
    if execution is not None:
        execution.append(Execution(where, used, len(chunks), _elapsed(results), merged.seconds))
    return merged


def _elapsed(results: list[ChunkResult]) -> float:
    return getattr(results, "elapsed", 0.0)


class _Results(list):
    elapsed = 0.0


def _local(plan: SearchPlan, chunks: list[tuple[int, int]], limit: float | None,
           progress: Callable[[int, int, int], None] | None, spent: float, first: ChunkResult | None = None) -> list[ChunkResult]:
    start = time.perf_counter()
    out = _Results()
    found = 0
    for n, (a, b) in enumerate(chunks, 1):
        out.append(first if n == 1 and first is not None else evaluate_chunk(plan, a, b))
        found += out[-1].found
        if progress is not None:
            progress(n, len(chunks), found)
        if limit is not None and n < len(chunks):
            _check_time(plan, spent, time.perf_counter() - start, b, limit)
    out.elapsed = time.perf_counter() - start
    return out


def _check_time(plan: SearchPlan, spent: float, searched: float, done: int, limit: float, *, final: bool = False) -> None:
    """Stop when the limit is passed (``final``: the search is over it).

    ``spent`` seconds went before the search (deriving, compiling), ``searched`` into the
    ``done`` outer tuples of the search so far.  The pace so far only words the message: the
    work of an outer tuple varies much along the search (for a fixed ratio the large suns
    make no tuples at all), so a projection stopped searches that would have finished in time.
    """
    fraction = done / max(plan.size, 1)
    elapsed = spent + searched
    if elapsed > limit or final:
        projected = spent + searched / fraction if fraction > 0 else math.inf
        raise TimeLimitError(_too_long(plan, elapsed, fraction, projected, limit))


def _too_long(plan: SearchPlan, elapsed: float, fraction: float, projected: float, limit: float) -> str:
    o = plan.problem.options
    dims = max(len(plan.outer), 1)
    span = o.zmax - o.zmin + 1
    shrink = (limit / projected) ** (1 / dims) if math.isfinite(projected) and projected > 0 else 0.5
    suggested = max(o.zmin, o.zmin + int(span * shrink * 0.8) - 1)
    when = f"about {projected:.0f} s in all at that pace" if math.isfinite(projected) else "longer than that"
    return (f"the search over {plan.size} tuples of {', '.join(plan.outer) or 'tooth numbers'} ({o.zmin} <= z <= "
            f"{o.zmax}) did {fraction:.0%} in {elapsed:.1f} s, {when}, more than the time limit of {limit:g} s; "
            f"narrow the tooth limits (e.g. zmax {suggested}), raise the time limit, or spread it over Dask workers")


# --------------------------------------------------------------------------- dask
def local_cluster(workers: int | None = None) -> Any:
    """A local Dask cluster of ``workers`` single-threaded processes, set up for the search.

    Its workers start without distributed's ``MALLOC_TRIM_THRESHOLD_=65536``: on glibc
    that setting makes every array above 128 kB an ``mmap`` of its own, and NumPy on the
    search's arrays then ran about 3 x slower than in the calling process (measured on
    this project's machine).  The dashboard takes a free port.
    """
    import dask
    import distributed

    n = workers or os.cpu_count() or 1
    with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
        return distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
                                        silence_logs=logging.ERROR)


def _client(scheduler: str, workers: int | None) -> tuple[Any, Any, str, int]:
    try:
        import distributed
    except ImportError:
        raise UnsupportedError("searching on Dask needs the dask extra: pip install 'symkin[dask]'") from None
    if scheduler == "local":
        n = workers or os.cpu_count() or 1
        cluster = local_cluster(n)
        return distributed.Client(cluster), cluster, f"local cluster of {n} worker{'s' * (n != 1)}", n
    if workers is not None:
        raise InputError("the number of workers is for a local cluster (scheduler 'local'); a scheduler at an "
                         "address has its own workers")
    if not isinstance(scheduler, str) or not scheduler.strip() or len(scheduler) > 300 or not scheduler.isprintable():
        raise InputError(f"the scheduler is 'local' or an address such as tcp://host:8786, got {scheduler!r}")
    try:
        client = distributed.Client(scheduler, timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError, ValueError, TypeError) as err:
        raise InputError(f"no Dask scheduler answered at {scheduler!r} within {CONNECT_TIMEOUT} s ({type(err).__name__}); "
                         "start one (dask scheduler) or use 'local'") from None
    n = len(client.scheduler_info().get("workers", {}))
    if n == 0:
        client.close()
        raise InputError(f"the Dask scheduler at {scheduler} has no workers; start some (dask worker {scheduler})")
    return client, None, f"Dask scheduler {scheduler} ({n} worker{'s' * (n != 1)})", n


def _dask(plan: SearchPlan, chunks: list[tuple[int, int]], scheduler: str, workers: int | None, limit: float | None,
          progress: Callable[[int, int, int], None] | None, spent: float) -> tuple[list[ChunkResult], int, str]:
    import distributed

    client, cluster, where, n = _client(scheduler, workers)
    try:
        start = time.perf_counter()  # the cluster's start-up is not counted
        shared = client.scatter(plan, broadcast=True)
        # A window of chunks in flight, refilled as they finish: a space of millions of chunks
        # costs no more memory than a few, and a time limit has little left to cancel.
        todo = iter(enumerate(chunks))
        index: dict[Any, int] = {}
        live: set[Any] = set()

        def submit() -> Any:
            nxt = next(todo, None)
            if nxt is None:
                return None
            i, (a, b) = nxt
            f = client.submit(evaluate_chunk, shared, a, b, pure=False)
            index[f.key] = i
            live.add(f)
            return f

        first = [f for f in (submit() for _ in range(min(len(chunks), WINDOW * n))) if f is not None]
        results: list[ChunkResult | None] = [None] * len(chunks)
        done_outer, found, finished = 0, 0, 0
        remaining = None if limit is None else max(limit - spent, 0.01)
        try:
            queue = distributed.as_completed(first, timeout=remaining)
            for f in queue:
                live.discard(f)
                r = f.result()
                results[index.pop(f.key)] = r
                done_outer += r.stop - r.start
                found += r.found
                finished += 1
                if progress is not None:
                    progress(finished, len(chunks), found)
                if limit is not None and finished < len(chunks):
                    _check_time(plan, spent, time.perf_counter() - start, done_outer, limit)
                g = submit()
                if g is not None:
                    queue.add(g)
        except (TimeoutError, getattr(distributed, "TimeoutError", TimeoutError)):
            client.cancel(list(live))
            assert limit is not None
            _check_time(plan, spent, time.perf_counter() - start, done_outer, limit, final=True)
        except TimeLimitError:
            client.cancel(list(live))
            raise
        out = _Results(r for r in results if r is not None)
        out.elapsed = time.perf_counter() - start
        return out, n, where
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
