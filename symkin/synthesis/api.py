"""``synthesize``: tooth numbers of any train for a target ratio (the one entry point)."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

from symkin.errors import InputError
from symkin.model import Mechanism
from symkin.synthesis import runner
from symkin.synthesis.efficiency import DEFAULT_RANK
from symkin.synthesis.plan import SearchPlan
from symkin.synthesis.problem import Problem, derive
from symkin.synthesis.request import MAX_TOP, RUN_FIELDS, RunOptions, SynthesisRequest, Target
from symkin.synthesis.result import Design, SynthesisResult, empty_reason, funnel_of

__all__ = ["synthesize", "MAX_TOP"]

#: Outer tuples per chunk at most (a chunk makes its tuples in one go).
CHUNK = 1 << 15


def synthesize(train: Mechanism | str | Path, request: SynthesisRequest | None = None, *,
               run: RunOptions | None = None, **keywords: Any) -> SynthesisResult:
    """Tooth numbers that give a train a target ratio, with k planets assembled, clear and coaxial.

    The conditions are derived from the train's model (:func:`symkin.synthesis.problem.derive`);
    the search (:mod:`symkin.synthesis.search`) makes only tuples with the ratio and checks
    them exactly; designs are ranked by ratio error, then size, then tooth sum (or by the
    ``rank`` asked for, efficiency included).

    The request is a :class:`~symkin.synthesis.request.SynthesisRequest`, or its keywords
    below (:meth:`~symkin.synthesis.request.SynthesisRequest.of`); how the search runs is a
    :class:`~symkin.synthesis.request.RunOptions`, or its keywords (with a request too).

    Parameters
    ----------
    train : Train, Mechanism, or a train file / ready-made name
        Symbolic tooth numbers (``teeth = "z1"``) are the unknowns; a train that gives every
        tooth number as a number has every one searched.
    request : SynthesisRequest, optional
        Everything that decides the designs; or these keywords:
    ratio, tolerance : number
        The target ratio and its relative tolerance (default 0.01); or
    ratio_range : (lo, hi)
        Every ratio in a range.
    driver, driven, fixed : str
        The ratio omega_driver / omega_driven with the ``fixed`` link(s) held; or
    state : str
        A gear state of the train.
    planets : int or None
        Equally spaced copies of every planet kind (default 3; None: each planet's count in the file).
    zmin, zmax, pressure_angle, addendum, clearance, shift, ring_difference
        See :class:`~symkin.synthesis.request.Options`.
    top, rank, mesh_efficiency
        How many designs to list (default 10; None: all), their order (default ratio error, then
        size, then tooth sum; ``rank="efficiency"`` ranks by the train's efficiency law, exactly)
        and the meshes' efficiencies it uses: see :class:`~symkin.synthesis.request.SynthesisRequest`.
    run : RunOptions, optional
        How the search runs; or these keywords:
    scheduler, workers, chunk
        Run the chunks on Dask (``"local"``: a local cluster of ``workers`` processes;
        ``"auto"``: that cluster only where the search's projected time pays for starting it,
        else here; or a scheduler's address; the result is the same as without); outer tuples
        per chunk.
    time_limit : float, optional
        Seconds; a longer search raises :class:`~symkin.errors.TimeLimitError` with bounds to try.
    progress : callable(done, total, found), optional
    allow_empty : bool
        Return a result without designs instead of raising when nothing is found.

    Raises
    ------
    InputError
        Bad input; a ratio outside what the train gives (the message says the range); no
        design (the message says which condition removed the last candidates).

    Examples
    --------
    >>> res = synthesize("simple", driver="S", driven="C", fixed="R", ratio=4, planets=3, zmax=100)
    >>> [d.gear_teeth for d in res.designs[:2]], res.found
    ([(('s', 18), ('p', 18), ('r', 54)), (('s', 21), ('p', 21), ('r', 63))], 6)
    >>> eff = synthesize("simple", driver="S", driven="C", fixed="R", ratio_range=(3, 6), zmax=100, top=2,
    ...                  rank="efficiency")   # the least ratio loses least: (1 + 0.98*0.99*2)/3
    >>> [(d.ratio, d.ranked_efficiency, d.gear_teeth) for d in eff.designs]
    [(3, 7351/7500, (('s', 36), ('p', 18), ('r', 72))), (3, 7351/7500, (('s', 38), ('p', 19), ('r', 76)))]
    >>> synthesize("simple", driver="S", driven="C", fixed="R", ratio=40, zmax=100)
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: the ratio i = 40 +- 1 % is outside what this train gives with 18 <= z <= 100: i_{SC}^{(R)} = z_r/z_s + 1 ranges from 2.5625 to 6.55556 over coaxial tooth numbers; ask for a ratio in that range or widen the limits

    The same request as an object, run with a time limit:

    >>> from symkin.synthesis import Options, SynthesisRequest, Target
    >>> request = SynthesisRequest(Target.of(4), driver="S", driven="C", fixed="R", options=Options(zmax=100))
    >>> synthesize("simple", request, time_limit=60).found
    6
    """
    began = time.perf_counter()
    request, run = _asked(request, run, keywords)
    if isinstance(train, (str, Path)):
        from symkin.trains import load_train

        train = load_train(train)
    problem = derive(train, driver=request.driver, driven=request.driven, fixed=request.fixed, state=request.state,
                     options=request.options)
    plan = _chunked_plan(problem, request, run.chunk)
    runs: list[runner.Execution] = []
    merged = runner.run(plan, scheduler=run.scheduler, workers=run.workers, time_limit=run.time_limit,
                        progress=run.progress, execution=runs, spent=time.perf_counter() - began)
    designs = tuple(Design.from_record(plan, r) for r in merged.top)
    reason = "" if merged.found else empty_reason(plan, merged)
    if not merged.found and not run.allow_empty:
        raise InputError(reason)
    return SynthesisResult(problem, request.target, designs, merged.found, funnel_of(plan, merged), merged.reach,
                           time.perf_counter() - began, plan.describe(), runs[0].to_json() if runs else {},
                           plan.notes, reason, merged.made, plan.rank,
                           plan.efficiency.meshes if plan.efficiency is not None else ())


def _asked(request: SynthesisRequest | None, run: RunOptions | None,
           keywords: dict[str, Any]) -> tuple[SynthesisRequest, RunOptions]:
    """The request and the run options, from the objects or their keywords (a request's fields only without one)."""
    run_keywords = {k: keywords.pop(k) for k in RUN_FIELDS & keywords.keys()}
    if request is None:
        request = SynthesisRequest.of(**keywords)
    elif not isinstance(request, SynthesisRequest):
        raise InputError(f"the request is a SynthesisRequest, got {request!r}; or give its fields as keywords "
                         "(ratio=..., driver=...)")
    elif keywords:
        raise InputError(f"give either a SynthesisRequest or its fields, not both (got {', '.join(sorted(keywords))})")
    if run is None:
        run = RunOptions(**run_keywords)
    elif run_keywords:
        raise InputError(f"give either RunOptions or their fields, not both (got {', '.join(sorted(run_keywords))})")
    return request, run


def _chunked_plan(problem: Problem, request: SynthesisRequest, chunk: int | None) -> SearchPlan:
    """The plan, cut into about 64 chunks of 256 to :data:`CHUNK` outer tuples unless ``chunk`` says."""
    plan0 = _plan(problem, request.target, request.top, CHUNK, request.rank, request.mesh_efficiency)
    per = max(256, min(CHUNK, math.ceil(plan0.size / 64))) if chunk is None else chunk
    if per == plan0.chunk:
        return plan0
    return _plan(problem, request.target, request.top, per, request.rank, request.mesh_efficiency)


_PLANS: dict[Any, SearchPlan] = {}


def _plan(problem: Any, target: Target, top: int | None, chunk: int, rank: tuple[str, ...] = DEFAULT_RANK,
          mesh_efficiency: Any = "default") -> SearchPlan:
    """Plans are compiled once per problem, target, chunking and ranking (a command run again reuses them)."""
    key = (problem, target, top, chunk, rank, repr(mesh_efficiency))
    try:
        return _PLANS[key]
    except (KeyError, TypeError):
        pass
    plan = SearchPlan.build(problem, target, top=top, chunk=chunk, rank=rank, mesh_efficiency=mesh_efficiency)
    try:
        if len(_PLANS) > 8:
            _PLANS.pop(next(iter(_PLANS)))
        _PLANS[key] = plan
    except TypeError:  # pragma: no cover - unhashable
        pass
    return plan
