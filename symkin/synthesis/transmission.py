"""Tooth numbers of a whole transmission: every state's ratio at once, pruned state by state.

A transmission is a train with several gear states and a target ratio for each.  The
conditions of every set (coaxiality, assembly of ``k`` planets, neighbours, internal gears,
limits) are derived once from the model (:func:`symkin.synthesis.problem.derive`) and split
into independent **groups** of tooth numbers: the unknowns that a condition ties together
(one simple planetary set is one group).  Each group's admissible tuples are enumerated
once, the coaxiality solved for the tooth numbers it fixes.  Then the states are taken in the
order that brings in the fewest new groups: a state's ratio law (derived by the kinematics
in the unknowns) is evaluated for every partial design extended by the new group's tuples,
and only those within the tolerance go on.  Every design found is exact: its ratios are
evaluated again exactly, and its train, built with the numbers, is solved again state by
state.  Designs are ranked by their largest ratio error, then by their largest error in the
steps between consecutive states, then by size (the largest tooth number), then tooth sum.

    >>> from symkin.trains import load_train
    >>> res = synthesize_transmission(load_train("simple"), {"low": 4, "overdrive": 0.75}, tolerance=0, zmax=60)
    >>> res.designs[0].teeth, res.designs[0].ratios
    ({'z_s': 18, 'z_p': 18, 'z_r': 54}, {'low': 4, 'overdrive': 3/4})
"""

from __future__ import annotations

import dataclasses
import functools
import itertools
import os
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from symkin._util.jsonout import exact_json, float_text
from symkin.errors import InputError, TimeLimitError
from symkin.model import Gear, Mechanism
from symkin.numeric import compile as compile_law
from symkin.numeric.backends.exact import exact_value
from symkin.synthesis.problem import Problem, derive
from symkin.synthesis.request import Options
from symkin.values import as_rational

__all__ = ["TransmissionDesign", "TransmissionResult", "synthesize_transmission"]

#: Partial designs of one chunk between two states at most (beyond it the search says to tighten the target).
MAX_PARTIAL = 2_000_000
#: The relative tolerance on every ratio unless one is given (1 %).
DEFAULT_TOLERANCE = sp.Rational(1, 100)


@dataclass(frozen=True)
class TransmissionDesign:
    """Tooth numbers for every state at once: ``teeth`` (unknown -> number), each state's exact ratio."""

    teeth: dict[str, int]
    ratios: dict[str, sp.Rational]
    error: sp.Rational
    step_error: sp.Rational

    def to_json(self) -> dict[str, Any]:
        """The design as JSON: its teeth, ratios and errors."""
        return {"teeth": dict(self.teeth), "ratios": {k: exact_json(v) for k, v in self.ratios.items()},
                "error": exact_json(self.error), "step_error": exact_json(self.step_error)}


@dataclass(frozen=True)
class TransmissionResult:
    """The designs of :func:`synthesize_transmission`, best first, and how the search went."""

    problem: Problem
    targets: dict[str, sp.Rational]
    tolerance: sp.Rational
    absolute: bool
    designs: tuple[TransmissionDesign, ...]
    found: int
    order: tuple[str, ...]
    groups: tuple[tuple[str, ...], ...]
    candidates: tuple[int, ...]
    kept: tuple[int, ...]
    seconds: float
    where: str = "this process"

    def train(self, design: TransmissionDesign) -> Any:
        """The train built with ``design``'s tooth numbers (for its geometry, statics, drawings)."""
        return _built(self.problem, design.teeth)

    def text(self, extra: Sequence[str | None] = ()) -> str:
        """The search and the designs as ``symkin synthesize --ratios`` prints them (``extra``: a line more
        under each design, such as its geometry)."""
        tol = f"+- {float_text(self.tolerance)}" + ("" if self.absolute else " (relative)")
        lines = [f"{self.problem.train.name or 'train'}: {len(self.targets)} states at once, "
                 + ", ".join(f"{k} {float_text(v)}" for k, v in self.targets.items()) + f" {tol}"]
        lines.append("groups of tooth numbers (tuples meeting their sets' conditions): " + "; ".join(
            f"{', '.join(g)} ({n})" for g, n in zip(self.groups, self.candidates)))
        lines.append("pruned state by state: " + ", ".join(f"{s} {n}" for s, n in zip(self.order, self.kept)))
        lines.append(f"{self.found} design{'s' * (self.found != 1)} in {self.seconds:.2f} s (search: {self.where})")
        for d, more in itertools.zip_longest(self.designs, extra[:len(self.designs)]):
            lines.append("  " + " ".join(f"{k}={v}" for k, v in d.teeth.items()))
            lines.append("    " + ", ".join(f"{k} {float_text(v)}" for k, v in d.ratios.items())
                         + f"; largest error {float_text(d.error)}, steps {float_text(d.step_error)}")
            if more:
                lines.append(f"    {more}")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """The result as JSON."""
        return {"train": self.problem.train.name, "targets": {k: exact_json(v) for k, v in self.targets.items()},
                "tolerance": exact_json(self.tolerance),
                "absolute": self.absolute, "found": self.found, "order": list(self.order),
                "groups": [list(g) for g in self.groups], "candidates": list(self.candidates), "kept": list(self.kept),
                "seconds": self.seconds, "where": self.where, "designs": [d.to_json() for d in self.designs]}


def synthesize_transmission(train: Mechanism, ratios: Mapping[str, Any], *, tolerance: Any = DEFAULT_TOLERANCE,
                            absolute: bool = False, planets: int | None = 3, zmin: int | None = None, zmax: int = 150,
                            top: int | None = 10, time_limit: float = 600.0, scheduler: str | None = None,
                            workers: int | None = None, **options: Any) -> TransmissionResult:
    """Tooth numbers that give every named state of ``train`` its target ratio at once.

    Parameters
    ----------
    train : Train
        A train with states; symbolic tooth numbers are the unknowns (all, when it gives numbers).
    ratios : mapping of state name to ratio
    tolerance : number
        Relative (default) or, with ``absolute``, absolute tolerance on every ratio.
    planets, zmin, zmax, options
        As for :func:`symkin.synthesis.synthesize` (:class:`~symkin.synthesis.request.Options`).
    top : int or None
        How many designs to keep (None: all).
    time_limit : float
        Seconds; a longer search raises :class:`~symkin.errors.TimeLimitError`.
    scheduler, workers : optional
        Run the search on Dask (``"local"``: a local cluster of ``workers`` processes, or a
        scheduler's address): the partial designs, once there are enough, in contiguous chunks
        (four per worker), each pruned state by state and evaluated exactly in a task, merged in
        order; the result is the same as without (which runs four chunks in turn). ``"auto"``: the
        first chunk timed here, the others on a local cluster only where their projected time pays
        for starting one, else here.
    """
    began = time.perf_counter()
    if not ratios:
        raise InputError("give a target ratio for at least one state (ratios={state: ratio})")
    targets = {str(k): as_rational(v, what=f"the ratio of state {k}") for k, v in ratios.items()}
    tol = as_rational(tolerance, what="the tolerance")
    if tol < 0:
        raise InputError(f"the tolerance must be zero or positive, got {tolerance}")
    zero = [s for s, t in targets.items() if t == 0]
    if zero and not absolute:
        raise InputError(f"state {zero[0]} has the target ratio 0, which a relative tolerance cannot hold; give an "
                         "absolute tolerance (absolute=True, --absolute)")
    first = next(iter(targets))
    problem = derive(train, state=first, options=Options(planets=planets, zmin=zmin, zmax=zmax, **options))
    laws = {s: dataclasses.replace(problem, request=(None, None, (), s)).ratio_of(problem.train).rhs for s in targets}
    groups = _groups(problem)
    lo, hi = int(problem.options.zmin), int(problem.options.zmax)
    tables = [_candidates(problem, g, lo, hi) for g in groups]
    for g, t in zip(groups, tables):
        if not len(t):
            raise InputError(f"no tooth numbers of {', '.join(map(str, g))} meet their set's conditions within "
                             f"{lo} <= z <= {hi}; widen the limits")
    search = _Search(tuple(groups), tuple(tables), laws, targets, tol, absolute, _plan(targets, laws, groups))
    deadline = time.time() + time_limit - (time.perf_counter() - began)  # wall clock: Dask workers keep it too
    if scheduler is None:
        kept, designs, _ = _search(search, CHUNKS_PER_WORKER, deadline,
                                   lambda starts, lead: [_chunk(search, p, lead, deadline) for p in starts])
        where = "this process"
    elif scheduler == "auto":
        kept, designs, where = _auto(search, deadline, workers)
    else:
        kept, designs, where = _dask(search, deadline, scheduler, workers)
    order = [s for s, _ in search.plan]
    designs.sort(key=lambda d: (d.error, d.step_error, max(d.teeth.values()), sum(d.teeth.values())))
    kept_designs = tuple(designs if top is None else designs[:top])
    for d in kept_designs:
        _recheck(train, problem, d)
    return TransmissionResult(problem, targets, tol, absolute, kept_designs, len(designs), tuple(order),
                              tuple(tuple(map(str, g)) for g in groups), tuple(len(t) for t in tables), tuple(kept),
                              time.perf_counter() - began, where)


def _groups(problem: Problem) -> list[tuple[sp.Symbol, ...]]:
    """The unknowns in groups that the conditions (limits aside) tie together, in the file's order."""
    parent = {z: z for z in problem.unknowns}

    def root(z: sp.Symbol) -> sp.Symbol:
        while parent[z] != z:
            z = parent[z]
        return z

    for c in problem.conditions():
        if c.kind == "limits":
            continue
        zs = [z for z in problem.unknowns if z in c.relation.free_symbols]
        for a, b in itertools.pairwise(zs):
            parent[root(a)] = root(b)
    out: dict[sp.Symbol, list[sp.Symbol]] = {}
    for z in problem.unknowns:
        out.setdefault(root(z), []).append(z)
    return [tuple(g) for g in out.values()]


def _candidates(problem: Problem, group: Sequence[sp.Symbol], lo: int, hi: int) -> np.ndarray:
    """Every tuple of the group's tooth numbers in [lo, hi] that meets its conditions (an array, one row each)."""
    own = [c for c in problem.conditions() if c.kind != "limits" and c.relation.free_symbols & set(group)]
    equalities = [c.relation for c in own if isinstance(c.relation, sp.Equality)]
    solved = sp.solve(equalities, list(group)[::-1], dict=True) if equalities else [{}]
    if len(solved) != 1:
        raise InputError(f"the conditions of {', '.join(map(str, group))} do not fix a unique tooth number")
    fixed = solved[0]
    free = [z for z in group if z not in fixed]
    grid = np.array(list(itertools.product(range(lo, hi + 1), repeat=len(free))), dtype=np.int64).reshape(-1, len(free))
    columns = {z: grid[:, k] for k, z in enumerate(free)}
    keep = np.ones(len(grid), dtype=bool)
    for z, expr in fixed.items():
        value = _evaluate(expr, free, [columns[f] for f in free], len(grid))
        whole = np.isclose(value, np.round(value), rtol=0, atol=1e-9)
        columns[z] = np.round(value).astype(np.int64)
        keep &= whole & (columns[z] >= lo) & (columns[z] <= hi)
    for c in own:
        rel = c.relation
        if isinstance(rel, sp.Equality):
            continue
        args = [columns[z] for z in group]
        if isinstance(rel, sp.Contains):
            value = _evaluate(rel.args[0], group, args, len(grid))
            keep &= np.isclose(value, np.round(value), rtol=0, atol=1e-9)
        elif not c.integers:
            keep &= _evaluate(rel, group, args, len(grid))
    table = np.stack([columns[z] for z in group], axis=1)[keep]
    if any(c.integers for c in own):  # assembly with integers to find: decided exactly, row by row
        ok = [problem.assembles({**{z: 1 for z in problem.unknowns}, **dict(zip(group, map(int, row)))}) for row in table]
        table = table[np.asarray(ok, dtype=bool)]
    return table


def _evaluate(expr: Any, symbols: Sequence[sp.Symbol], columns: Sequence[np.ndarray], n: int) -> np.ndarray:
    """``expr`` at every row of ``columns`` (floats; a relation: where it holds)."""
    if isinstance(expr, sp.core.relational.Relational):
        difference = _evaluate(expr.lhs - expr.rhs, symbols, columns, n)
        op = {"<": np.less, "<=": np.less_equal, ">": np.greater, ">=": np.greater_equal}[expr.rel_op]
        return op(difference, 0)
    expr = sp.sympify(expr)
    if not expr.free_symbols:
        return np.full(n, float(expr))
    used = [k for k, z in enumerate(symbols) if z in expr.free_symbols]
    f = _compiled(expr, tuple(symbols[k] for k in used))
    with np.errstate(all="ignore"):
        return np.asarray(f(*[np.asarray(columns[k], dtype=float) for k in used]), dtype=float) * np.ones(n)


@functools.lru_cache(maxsize=256)
def _compiled(expr: sp.Expr, symbols: tuple[sp.Symbol, ...]) -> Any:
    """``expr`` compiled once per process (every chunk of a search, on a Dask worker too, prunes with the same laws)."""
    return compile_law(expr, list(symbols), backend="numpy", on_pole="return")


def _extend(partial: np.ndarray, n: int) -> np.ndarray:
    """Every partial design with each of a new group's ``n`` tuples (one column more)."""
    rows = np.repeat(partial, n, axis=0)
    return np.concatenate([rows, np.tile(np.arange(n), len(partial))[:, None]], axis=1)


def _within(law: sp.Expr, target: sp.Rational, tol: sp.Rational, absolute: bool, groups: list, tables: list,
            assigned: list[int], partial: np.ndarray) -> np.ndarray:
    """Which partial designs give ``law`` within the tolerance (in floats, with a margin; exact later)."""
    symbols, columns = [], []
    for col, i in enumerate(assigned):
        for k, z in enumerate(groups[i]):
            if z in law.free_symbols:
                symbols.append(z)
                columns.append(tables[i][partial[:, col], k].astype(float))
    value = _evaluate(law, symbols, columns, len(partial))
    bound = float(tol) if absolute else float(tol) * abs(float(target))
    return np.abs(value - float(target)) <= bound * (1 + 1e-9) + 1e-12


@dataclass(frozen=True)
class _Search:
    """What every chunk of the search needs (sent once to each Dask worker)."""

    groups: tuple[tuple[sp.Symbol, ...], ...]
    tables: tuple[np.ndarray, ...]
    laws: dict[str, sp.Expr]
    targets: dict[str, sp.Rational]
    tol: sp.Rational
    absolute: bool
    plan: tuple[tuple[str, tuple[int, ...]], ...]

    @property
    def assigned(self) -> list[int]:
        """The groups in the order the states bring them in (the columns of a partial design)."""
        return [i for _, new in self.plan for i in new]


def _plan(targets: dict[str, sp.Rational], laws: dict[str, sp.Expr],
          groups: list[tuple[sp.Symbol, ...]]) -> tuple[tuple[str, tuple[int, ...]], ...]:
    """The states in the order that brings in the fewest new groups, each with the groups it brings in."""
    assigned: list[int] = []
    remaining = list(targets)
    plan = []
    while remaining:
        def new_groups(s: str) -> list[int]:
            used = {i for i, g in enumerate(groups) if set(g) & laws[s].free_symbols}
            return sorted(used - set(assigned))
        s = min(remaining, key=lambda s: (len(new_groups(s)), remaining.index(s)))
        remaining.remove(s)
        new = new_groups(s)
        assigned.extend(new)
        plan.append((s, tuple(new)))
    return tuple(plan)


def _prune(search: _Search, partial: np.ndarray, first: int, last: int, deadline: float) -> tuple[np.ndarray, list[int]]:
    """The partial designs (index rows into the tables) after states ``first`` to ``last`` of the plan, and how
    many each state kept; a partial design's columns are the groups in ``search.assigned`` order, those it
    has already are not added again."""
    assigned = search.assigned
    kept = []
    for s, new in search.plan[first:last]:
        for i in new:
            if assigned.index(i) < partial.shape[1]:
                continue
            partial = _extend(partial, len(search.tables[i]))
            if len(partial) > MAX_PARTIAL:
                raise InputError(f"state {s}: {len(partial)} partial designs before its ratio prunes them; name states "
                                 "whose ratios involve fewer sets first, or narrow the limits")
        partial = partial[_within(search.laws[s], search.targets[s], search.tol, search.absolute, list(search.groups),
                                  list(search.tables), assigned[:partial.shape[1]], partial)]
        kept.append(len(partial))
        if time.time() > deadline:
            raise TimeLimitError(f"the search ran past its time limit after state {s} ({len(partial)} partial "
                                 "designs); narrow the limits or the tolerance")
    return partial, kept


def _rows(search: _Search, partial: np.ndarray) -> list[dict[sp.Symbol, int]]:
    """Each partial design's tooth numbers (groups no ratio names: their least tuple)."""
    assigned = search.assigned
    free = [i for i in range(len(search.groups)) if i not in assigned]
    rows: list[dict[sp.Symbol, int]] = []
    for row in partial:
        values: dict[sp.Symbol, int] = {}
        for col, i in enumerate(assigned):
            values.update(zip(search.groups[i], (int(x) for x in search.tables[i][row[col]])))
        for i in free:
            values.update(zip(search.groups[i], (int(x) for x in search.tables[i][0])))
        rows.append(values)
    return rows


def _chunk(search: _Search, start: np.ndarray, lead: int, deadline: float) -> tuple[list[int], list[TransmissionDesign]]:
    """One chunk of the search: partial designs ``start`` pruned by every state from ``lead`` on, then evaluated
    exactly; how many each state kept, and the designs in the search's order."""
    partial, kept = _prune(search, start, lead, len(search.plan), deadline)
    return kept, _exact_chunk(_rows(search, partial), search)


#: Chunks per Dask worker, and in the calling process (:data:`MAX_PARTIAL` bounds each chunk's partial designs).
CHUNKS_PER_WORKER = 4


def _search(search: _Search, count: int, deadline: float,
            run: Callable[[list[np.ndarray], int], list[tuple[list[int], list[TransmissionDesign]]]]
            ) -> tuple[list[int], list[TransmissionDesign], int]:
    """The search in ``count`` chunks: states are taken here until at least ``count`` partial designs are left,
    these are split into ``count`` contiguous chunks that ``run(chunks, next state)`` prunes by the remaining
    states and evaluates exactly (here or on Dask), merged in order; how many each state kept, the designs in
    the order of the search in one piece, and the number of chunks."""
    partial, kept, j = np.zeros((1, 0), dtype=np.int64), [], 0
    while j < len(search.plan) and 0 < len(partial) < count:
        partial, k = _prune(search, partial, j, j + 1, deadline)
        kept += k
        j += 1
    if j == len(search.plan) or not len(partial):
        return kept + [len(partial)] * (len(search.plan) - j), _exact_chunk(_rows(search, partial), search), 0
    parts = run(np.array_split(partial, count), j)
    kept += [sum(col) for col in zip(*(k for k, _ in parts))]
    return kept, [d for _, part in parts for d in part], len(parts)


def _on_dask(client: Any, search: _Search, starts: list[np.ndarray], lead: int,
             deadline: float) -> list[tuple[list[int], list[TransmissionDesign]]]:
    """The chunks ``starts`` pruned and evaluated on ``client``'s workers (``client.map``, the search
    scattered once to each), in their order."""
    shared = client.scatter(search, broadcast=True)
    return client.gather(client.map(_chunk, [shared] * len(starts), starts, lead=lead, deadline=deadline, pure=False))


def _dask(search: _Search, deadline: float, scheduler: str,
          workers: int | None) -> tuple[list[int], list[TransmissionDesign], str]:
    """:func:`_search` on Dask, four chunks per worker."""
    from symkin.synthesis.runner import _client

    client, cluster, where, count = _client(scheduler, workers)
    try:
        kept, designs, chunks = _search(search, CHUNKS_PER_WORKER * count, deadline,
                                        lambda starts, lead: _on_dask(client, search, starts, lead, deadline))
        return kept, designs, f"{where}, {chunks} chunks"
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _auto(search: _Search, deadline: float, workers: int | None) -> tuple[list[int], list[TransmissionDesign], str]:
    """:func:`_search` here, its first chunk timed: the other chunks go to a local Dask cluster only where
    their projected time pays for starting one (:func:`symkin.synthesis.runner.cluster_pays`); the
    chunks and their order are the same either way, so the designs are too."""
    from symkin.synthesis.runner import _client, cluster_pays

    n = workers or os.cpu_count() or 1
    where = ["this process"]

    def run(starts: list[np.ndarray], lead: int) -> list[tuple[list[int], list[TransmissionDesign]]]:
        began = time.perf_counter()
        first = _chunk(search, starts[0], lead, deadline)
        projected = (time.perf_counter() - began) * (len(starts) - 1)
        if not cluster_pays(projected, n):
            where[0] = f"this process (a local cluster of {n} would not pay: about {projected:.2g} s of search left)"
            return [first, *(_chunk(search, p, lead, deadline) for p in starts[1:])]
        client, cluster, where[0], _ = _client("local", n)
        try:
            return [first, *_on_dask(client, search, starts[1:], lead, deadline)]
        finally:
            client.close()
            cluster.close()

    kept, designs, _ = _search(search, CHUNKS_PER_WORKER * n, deadline, run)
    return kept, designs, where[0]


def _exact_chunk(rows: list[dict[sp.Symbol, int]], search: _Search) -> list[TransmissionDesign]:
    return [d for d in (_design(v, search.laws, search.targets, search.tol, search.absolute) for v in rows)
            if d is not None]


def _design(values: dict[sp.Symbol, int], laws: dict[str, sp.Expr], targets: dict[str, sp.Rational], tol: sp.Rational,
            absolute: bool) -> TransmissionDesign | None:
    """The design with exact ratios, or None when one misses the tolerance exactly (or has no finite value)."""
    ratios: dict[str, Fraction] = {}
    for s, law in laws.items():
        ratio = exact_value(law, values)
        if ratio is None:
            return None
        ratios[s] = ratio
    goal = {s: Fraction(int(t.p), int(t.q)) for s, t in targets.items()}
    errors = [abs(ratios[s] - t) if absolute else abs(ratios[s] - t) / abs(t) for s, t in goal.items()]
    if max(errors) > Fraction(int(tol.p), int(tol.q)):
        return None
    names = list(goal)
    steps = [abs(ratios[a] / ratios[b] - goal[a] / goal[b]) / abs(goal[a] / goal[b])
             for a, b in itertools.pairwise(names) if ratios[b] != 0 and goal[a] != 0 and goal[b] != 0]
    return TransmissionDesign({str(z): v for z, v in values.items()}, {s: sp.Rational(r.numerator, r.denominator)
                              for s, r in ratios.items()}, sp.Rational(max(errors)), sp.Rational(max(steps, default=0)))


def _built(problem: Problem, teeth: Mapping[str, int]) -> Any:
    """The problem's train with the tooth numbers ``teeth`` (unknown name -> number)."""
    links = []
    for L in problem.train.links:
        gears = tuple(Gear.from_teeth(g.name, teeth[str(g.teeth)], internal=g.internal, module=g.module)
                      if isinstance(g.teeth, sp.Symbol) else g for g in L.gears)
        links.append(dataclasses.replace(L, gears=gears))
    return dataclasses.replace(problem.train, links=tuple(links))


def _recheck(train: Any, problem: Problem, design: TransmissionDesign) -> None:
    """Build the train with the design's numbers and solve every state again: the same exact ratios."""
    built = _built(problem, design.teeth)
    for s, ratio in design.ratios.items():
        again = built.shift(s).ratio.rhs
        if again != ratio:  # pragma: no cover - a failure of the search, not of the input
            raise AssertionError(f"state {s}: the built train gives {again}, the search {ratio}")
