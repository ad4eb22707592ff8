"""``synthesize``: tooth numbers of any train for a target ratio (the one entry point)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

from symkin.errors import InputError
from symkin.model import Mechanism
from symkin.synthesis.efficiency import DEFAULT_RANK, rank_order
from symkin.synthesis.plan import SearchPlan
from symkin.synthesis.problem import derive
from symkin.synthesis.request import Options, Target
from symkin.synthesis.result import Design, SynthesisResult, empty_reason, funnel_of
from symkin.synthesis.runner import Execution, run
from symkin.values import as_integer, as_rational

__all__ = ["synthesize", "MAX_TOP"]

#: The most designs a result lists.
MAX_TOP = 100_000
#: Outer tuples per chunk at most (a chunk makes its tuples in one go).
CHUNK = 1 << 15


def synthesize(
    train: Mechanism | str | Path,
    *,
    ratio: Any = None,
    tolerance: Any = Fraction(1, 100),
    ratio_range: Sequence[Any] | None = None,
    driver: str | None = None,
    driven: str | None = None,
    fixed: str | Sequence[str] | None = None,
    state: str | None = None,
    planets: int | None = 3,
    zmin: int | None = None,
    zmax: int = 150,
    pressure_angle: Any = 20,
    addendum: Any = 1,
    clearance: Any = 0,
    shift: Any = 0,
    ring_difference: int = 8,
    top: int | None = 10,
    scheduler: str | None = None,
    workers: int | None = None,
    chunk: int | None = None,
    time_limit: float | None = None,
    progress: Callable[[int, int, int], None] | None = None,
    allow_empty: bool = False,
    rank: str | Sequence[str] | None = None,
    mesh_efficiency: Any = "default",
) -> SynthesisResult:
    """Tooth numbers that give a train a target ratio, with k planets assembled, clear and coaxial.

    The conditions are derived from the train's model (:func:`symkin.synthesis.problem.derive`);
    the search (:mod:`symkin.synthesis.search`) makes only tuples with the ratio and checks
    them exactly; designs are ranked by ratio error, then size, then tooth sum (or by the
    ``rank`` asked for, efficiency included).

    Parameters
    ----------
    train : Train, Mechanism, or a train file / ready-made name
        Symbolic tooth numbers (``teeth = "z1"``) are the unknowns; a train that gives every
        tooth number as a number has every one searched.
    ratio, tolerance : number
        The target ratio and its relative tolerance (default 0.01); or
    ratio_range : (lo, hi)
        Every ratio in a range.
    driver, driven, fixed : str
        The ratio omega_driver / omega_driven with the ``fixed`` link(s) held; or
    state : str
        A gear state of the train.
    planets : int or None
        Equally spaced copies of every planet kind (None: each planet's count in the file).
    zmin, zmax, pressure_angle, addendum, clearance, shift, ring_difference
        See :class:`~symkin.synthesis.request.Options`.
    top : int or None
        How many designs to list (None: all).
    scheduler : str, optional
        Run the chunks on Dask: ``"local"`` (a local cluster of ``workers`` processes) or a
        scheduler's address; the result is the same as without.
    chunk : int, optional
        Outer tuples per chunk.
    time_limit : float, optional
        Seconds; a longer search raises :class:`~symkin.errors.TimeLimitError` with bounds to try.
    progress : callable(done, total, found), optional
    allow_empty : bool
        Return a result without designs instead of raising when nothing is found.
    rank : str or sequence of str, optional
        The order of the designs: keys among ``"error"``, ``"efficiency"`` (largest first),
        ``"size"`` and ``"teeth"`` (tooth sum), the rest of error, size, teeth following
        (:func:`symkin.synthesis.efficiency.rank_order`); ties go by the tooth numbers.
        Ranking by efficiency evaluates the train's efficiency law, derived from its statics,
        exactly at every design found.
    mesh_efficiency : str, number or dict
        The meshes' efficiencies when ranking by efficiency (:func:`symkin.statics.statics`'
        ``efficiency``): ``"default"`` (the train file's value where a mesh has one, else 0.98
        external and 0.99 internal), one number, or ``{"a-b": value}``; rational numbers (a
        decimal, a fraction), since the order is exact. The values used are in
        :attr:`SynthesisResult.mesh_efficiency`; a design whose efficiency is zero or below is
        marked (:attr:`Design.locks`: the driver cannot drive the driven) and, with efficiency
        the first key, ranks after every design that drives.

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
    """
    began = time.perf_counter()
    order = rank_order(rank)  # before any derivation: a bad key is refused at once
    if isinstance(train, (str, Path)):
        from symkin.trains import load_train

        train = load_train(train)
    if ratio_range is not None:
        if ratio is not None:
            raise InputError("give either a target ratio (with a tolerance) or a ratio range, not both")
        try:
            lo, hi = ratio_range
        except (TypeError, ValueError):
            raise InputError(f"a ratio range is two numbers (lo, hi), got {ratio_range!r}") from None
        target = Target.range(lo, hi)
    elif ratio is not None:
        target = Target.of(ratio, tolerance)
    else:
        raise InputError("give the target ratio (and a tolerance), or a ratio range")
    top_n = None if top is None else int(as_integer(top, what="top", minimum=1, maximum=MAX_TOP))
    if time_limit is not None:
        limit = as_rational(time_limit, what="the time limit")
        if limit <= 0:
            raise InputError(f"the time limit must be a positive number of seconds, got {time_limit!r}")
        time_limit = float(limit)
    if workers is not None:
        workers = int(as_integer(workers, what="the number of workers", minimum=1, maximum=1024))
    options = Options(planets=planets, zmin=zmin, zmax=zmax, pressure_angle=pressure_angle, addendum=addendum,
                      clearance=clearance, shift=shift, ring_difference=ring_difference)
    problem = derive(train, driver=driver, driven=driven, fixed=fixed, state=state, options=options)
    plan0 = _plan(problem, target, top_n, CHUNK, order, mesh_efficiency)
    if chunk is None:
        per = max(256, min(CHUNK, math.ceil(plan0.size / 64)))
    else:
        per = int(as_integer(chunk, what="the chunk size", minimum=1, maximum=1 << 24))
    plan = plan0 if per == plan0.chunk else _plan(problem, target, top_n, per, order, mesh_efficiency)
    runs: list[Execution] = []
    merged = run(plan, scheduler=scheduler, workers=workers, time_limit=time_limit, progress=progress, execution=runs,
                 spent=time.perf_counter() - began)
    designs = tuple(Design.from_record(plan, r) for r in merged.top)
    reason = "" if merged.found else empty_reason(plan, merged)
    if not merged.found and not allow_empty:
        raise InputError(reason)
    return SynthesisResult(problem, target, designs, merged.found, funnel_of(plan, merged), merged.reach,
                           time.perf_counter() - began, plan.describe(), runs[0].to_json() if runs else {},
                           plan.notes, reason, merged.made, plan.rank,
                           plan.efficiency.meshes if plan.efficiency is not None else ())


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
