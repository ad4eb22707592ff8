"""The search: the derived conditions turned into a pruned, chunked enumeration of tooth numbers.

A :class:`SearchPlan` is built once from a :class:`~symkin.synthesis.problem.Problem` and a
:class:`Target`:

1. the coaxiality equations are solved for some tooth numbers (the *dependents*: an
   internal gear from its planet and sun, say), each within a slack of a few teeth when
   profile shift is allowed; the others are *free*;
2. the ratio law, with the dependents put in, is linear-fractional in one free tooth
   number ``x`` (ratio laws are, tooth by tooth): for the other free numbers (the *outer*
   tuple) the ratio window gives the values of ``x`` in closed form, so only tuples with
   the ratio are ever made;
3. every tuple made is checked against the other conditions, vectorised and exactly:
   integers are evaluated in binary floating point only where every value is an integer
   below 2^53 (so exactly), the ratio is reduced to a fraction and compared exactly,
   geometry in scaled integers, and an inequality with sin(pi/k) or a cosine is decided in
   floating point only with a margin, else at 60 digits.

The outer tuples are numbered; a chunk is a range of those numbers, and
:func:`evaluate_chunk` (a pure function of the plan and the range) returns the count of
tuples that pass each condition and the best designs of the chunk in the one exact order
(ratio error, then size, then tooth sum, then the tooth numbers; or the plan's ``rank``,
efficiency included: :mod:`symkin.synthesis.efficiency`), so any split into
chunks, run anywhere, merges to the same result.

    >>> from symkin.trains import load_train
    >>> from symkin.synthesis.problem import derive
    >>> plan = SearchPlan.build(derive(load_train("simple"), driver="S", driven="C", fixed="R", planets=3, zmax=80),
    ...                   Target.of(4, 0.01), top=3)
    >>> plan.last, plan.outer, plan.dependents
    ('z_p', ('z_s',), ('z_r',))
    >>> found = evaluate_chunk(plan, 0, plan.size)
    >>> [r.teeth for r in found.top], found.found, found.counts   # made with the ratio, then each condition
    ([(18, 18, 54), (21, 21, 63), (24, 24, 72)], 3, [9, 9, 9, 3, 3, 3])
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import InputError
from symkin.model import LinkKind
from symkin.numeric import compile
from symkin.synthesis.efficiency import DEFAULT_RANK, EfficiencyLaw, rank_order
from symkin.synthesis.integers import solvable
from symkin.synthesis.problem import Problem
from symkin.values import as_fraction

__all__ = ["Target", "SearchPlan", "Record", "ChunkResult", "evaluate_chunk", "merge", "STAGES"]

#: Integers below this are exact in binary64 (with a bit to spare).
_EXACT = 2.0**52
#: Relative margin of a float decision; closer calls are decided at 60 digits.
_BAND = 1e-9
#: Tuples made at once inside a chunk (memory).
_BATCH = 1 << 20
#: Names of the stages every tuple passes in order (the funnel).
STAGES = ("ratio", "internal gears", "coaxiality", "assembly", "neighbours", "placement")


@dataclass(frozen=True)
class Target:
    """The ratios a design may have: ``ratio`` within a relative ``tolerance``, or a range.

    >>> from fractions import Fraction
    >>> Target.of(Fraction(12, 5), 0.005).window
    (Fraction(597, 250), Fraction(603, 250))
    >>> Target.range(2, 3).error(Fraction(5, 2))
    Fraction(0, 1)
    """

    lo: Fraction
    hi: Fraction
    ratio: Fraction | None = None
    tolerance: Fraction | None = None

    @classmethod
    def of(cls, ratio: Any, tolerance: Any = Fraction(1, 100)) -> Target:
        """A target ratio with a relative tolerance (``0.01`` is 1 %), exact.

        >>> Target.of(4, 0.01).window
        (Fraction(99, 25), Fraction(101, 25))
        """
        r = as_fraction(ratio, what="the target ratio")
        t = as_fraction(tolerance, what="the ratio tolerance")
        if r == 0:
            raise InputError("the target ratio is 0: no train turns its output infinitely fast; give a non-zero ratio")
        if not 0 <= t < 1:
            raise InputError(f"the relative tolerance must be from 0 to less than 1, got {t}; 0.01 is 1 %")
        span = abs(r) * t
        return cls(r - span, r + span, r, t)

    @classmethod
    def range(cls, lo: Any, hi: Any) -> Target:
        """A target range ``lo <= i <= hi`` of ratios, exact."""
        a = as_fraction(lo, what="the least ratio")
        b = as_fraction(hi, what="the largest ratio")
        if a > b:
            raise InputError(f"the ratio range {a} .. {b} is empty; give the smaller ratio first")
        return cls(a, b)

    @property
    def window(self) -> tuple[Fraction, Fraction]:
        """The admissible ratios, ``(lo, hi)``."""
        return self.lo, self.hi

    def error(self, value: Fraction) -> Fraction:
        """Relative error from the target ratio (0 inside a range)."""
        if self.ratio is None:
            return Fraction(0)
        return abs(value - self.ratio) / abs(self.ratio)

    def text(self) -> str:
        """The target in words: ``i = R +- T %`` or ``lo <= i <= hi``."""
        if self.ratio is None:
            return f"{self.lo} <= i <= {self.hi}"
        return f"i = {self.ratio} +- {float(self.tolerance or 0) * 100:g} %"


@dataclass(frozen=True)
class Record:
    """One design found: everything exact, ordered by :attr:`key`."""

    error: Fraction
    size: int  # envelope diameter times the plan's length scale
    teeth: tuple[int, ...]
    slacks: tuple[int, ...]
    ratio: Fraction
    efficiency: Fraction | None = None  # when ranking by it
    rank: tuple[str, ...] = DEFAULT_RANK

    @property
    def key(self) -> tuple:
        """The ranking key of a found design: its plan's rank (by default ratio error, then size,
        then the sum of teeth), then the tooth numbers; an undefined efficiency comes last."""
        parts: list[Any] = []
        for name in self.rank:
            if name == "error":
                parts.append(self.error)
            elif name == "size":
                parts.append(self.size)
            elif name == "teeth":
                parts.append(sum(self.teeth))
            else:
                parts.append((0, -self.efficiency) if self.efficiency is not None else (1, 0))
        return (*parts, self.teeth, self.slacks)


@dataclass
class ChunkResult:
    """What one chunk found (see :func:`evaluate_chunk`)."""

    start: int
    stop: int
    counts: list[int]
    found: int
    top: list[Record]
    reach: tuple[float, float]
    made: int = 0
    exact_calls: int = 0
    seconds: float = 0.0


@dataclass(frozen=True)
class _Geometry:
    """Indices into the candidate function's outputs for the geometric checks."""

    planet_meshes: tuple[tuple[str, tuple[int, ...], tuple[int, ...], int | None], ...]
    rims: tuple[tuple[int, int, int], ...]  # planet index, tip radius output, module scaled
    pairs: tuple[tuple[int, int, int, int, int, int], ...]  # planet a, planet b, d, tip a, tip b, clearance scaled
    central: tuple[int, ...]  # outputs of central gears' outer radii (scaled)
    planet_tips: tuple[tuple[int, ...], ...]


@dataclass
class SearchPlan:
    """A search, compiled (see the module docstring); picklable, so Dask workers rebuild it once."""

    problem: Problem
    target: Target
    top: int | None
    unknowns: tuple[str, ...]
    outer: tuple[str, ...]
    last: str | None
    dependents: tuple[str, ...]
    lows: tuple[int, ...]
    highs: tuple[int, ...]
    size: int
    scale: int
    chunk: int
    f_outer: Any
    f_cand: Any
    outer_layout: dict[str, Any]
    cand_layout: dict[str, Any]
    slack_names: tuple[str, ...]
    slack_bounds: tuple[int, ...]
    planets: tuple[str, ...]
    k: dict[str, int]
    geometry: _Geometry
    internal_pairs: tuple[tuple[int, int], ...]
    filter_bounds: tuple[int, ...]
    assembly: tuple[Any, ...]
    f_sin: Any
    f_cross: Any
    notes: tuple[str, ...] = ()
    dependent_alpha: tuple[Fraction, ...] = ()
    dependent_limits: tuple[tuple[int, int], ...] = ()
    stages: tuple[str, ...] = field(default=STAGES)
    rank: tuple[str, ...] = DEFAULT_RANK
    efficiency: EfficiencyLaw | None = None

    # ------------------------------------------------------------------ build
    @classmethod
    def build(cls, problem: Problem, target: Target, *, top: int | None = 10, chunk: int = 1 << 15,
              rank: str | Sequence[str] | None = None, mesh_efficiency: Any = "default") -> SearchPlan:
        """Solve the coaxiality for the dependents, choose ``x``, compile (see the module docstring).

        ``rank`` orders the designs (:func:`symkin.synthesis.efficiency.rank_order`); ranking by
        ``"efficiency"`` derives the efficiency law with ``mesh_efficiency``
        (:class:`~symkin.synthesis.efficiency.EfficiencyLaw`).
        """
        order = rank_order(rank)
        eff = EfficiencyLaw.derive(problem, mesh_efficiency) if "efficiency" in order else None
        o = problem.options
        unknowns = problem.unknowns
        zlo = {z: o.zmin for z in unknowns}
        zhi = {z: o.zmax for z in unknowns}
        scale = _length_scale(problem)
        # ---- coaxiality rows: e = s*(lhs - rhs) integer-valued, |e| <= W
        slacks: list[tuple[sp.Symbol, int]] = []
        pivot_rows: list[tuple[sp.Expr, int, int]] = []
        filter_rows: list[tuple[sp.Expr, int, int]] = []
        for i, row in enumerate(problem.coaxiality):
            expr = row.expr
            s = _integer_scale(expr)
            w = math.floor(row.tolerance * s)
            (pivot_rows if row.pivot else filter_rows).append((sp.expand(expr * s), w, i))
        dependents: dict[sp.Symbol, sp.Expr] = {}
        internal = {z for z in unknowns if any(problem.train.gear(g).internal for g in problem.gears_of(z))}
        extra_filters: list[tuple[sp.Expr, int]] = []
        for expr, w, i in pivot_rows:
            sigma = sp.Symbol(f"sigma_{i}", integer=True)
            e = sp.expand(expr.subs(dependents) - (sigma if w else 0))
            free = [z for z in unknowns if z not in dependents and e.has(z)]
            if not free:
                extra_filters.append((sp.expand(expr.subs(dependents)), w))
                continue
            if w:
                slacks.append((sigma, w))

            def preference(z: sp.Symbol, e: sp.Expr = e) -> tuple:
                c = e.coeff(z)
                return (abs(c) != 1, z not in internal, -unknowns.index(z))

            z = min(free, key=preference)
            c = e.coeff(z)
            value = sp.expand(-(e - c * z) / c)
            dependents = {d: sp.expand(v.subs(z, value)) for d, v in dependents.items()}
            dependents[z] = value
        for expr, w, _ in filter_rows:
            extra_filters.append((sp.expand(expr.subs(dependents)), w))
        for e, w in extra_filters:
            if not e.free_symbols and abs(e) > w:
                raise InputError("the coaxiality conditions contradict each other for every tooth number; check the "
                                 "train's arms and centre distances")
        free = [z for z in unknowns if z not in dependents]
        ratio = sp.cancel(problem.ratio.rhs.subs(dependents))
        num, den = sp.fraction(ratio)
        last = _choose_last(num, den, free)
        notes = list(problem.notes)
        if last is None:
            notes.append("the ratio law is linear-fractional in no single free tooth number: every tuple of the free "
                         "numbers is made and its ratio checked")
        outer = [z for z in free if z != last]
        outer_syms = outer + [s for s, _ in slacks]
        lows = [zlo[z] for z in outer] + [-w for _, w in slacks]
        highs = [zhi[z] for z in outer] + [w for _, w in slacks]
        size = math.prod(h - lo + 1 for lo, h in zip(lows, highs))
        # ---- the outer function: the dependents' parts, and the ratio's coefficients in x
        outer_exprs: list[sp.Expr] = []
        outer_layout: dict[str, Any] = {}
        alphas, limits = [], []
        dep_names = tuple(str(d) for d in dependents)
        for d, v in dependents.items():
            alpha = v.coeff(last) if last is not None else sp.Integer(0)
            outer_exprs.append(sp.expand(v - alpha * last) if last is not None else v)
            alphas.append(Fraction(int(sp.Rational(alpha).p), int(sp.Rational(alpha).q)))
            limits.append((zlo[d], zhi[d]))
        outer_layout["dependents"] = list(range(len(outer_exprs)))
        if last is not None:
            pn, pd = sp.Poly(num, last), sp.Poly(den, last)
            a, b = (pn.all_coeffs() if pn.degree() == 1 else [sp.Integer(0), pn.as_expr()])
            c, d = (pd.all_coeffs() if pd.degree() == 1 else [sp.Integer(0), pd.as_expr()])
            outer_layout["abcd"] = list(range(len(outer_exprs), len(outer_exprs) + 4))
            outer_exprs += [a, b, c, d]
        else:
            outer_layout["abcd"] = []
        outer_exprs = [sp.sympify(e) for e in outer_exprs]
        f_outer = compile(outer_exprs, outer_syms, backend="numpy", stable=False, on_pole="return", cse=True) if outer_exprs else None
        # ---- the candidate function: every integer and scaled length the checks need
        cand_args = list(unknowns) + [s for s, _ in slacks]
        cand: list[sp.Expr] = []
        layout: dict[str, Any] = {}

        def put(name: str, exprs: Sequence[sp.Expr]) -> list[int]:
            idx = list(range(len(cand), len(cand) + len(exprs)))
            cand.extend(sp.expand(e) for e in exprs)
            layout[name] = idx
            return idx

        full_num, full_den = sp.fraction(sp.cancel(problem.ratio.rhs))
        put("ratio", [full_num, full_den])
        filters = [(e.subs({}), w) for e, w in extra_filters if e.free_symbols]
        put("filters", [e for e, _ in filters])
        # assembly
        assembly = []
        for group in problem.assembly:
            kk = problem.count[group.planets[0]]
            if kk < 2:
                continue
            rows = []
            for arow in group.rows:
                g_idx = put(f"G{len(layout)}", [c for _, c in arow.coefficients])
                r_idx = put(f"R{len(layout)}", [arow.numerator])[0]
                rows.append((arow.kind, g_idx, r_idx, arow.denominator * kk, [str(n) for n, _ in arow.coefficients]))
            assembly.append(tuple(rows))
        # geometry, in lengths times `scale` (integers)
        planets = tuple(a.planet for a in problem.arms)
        y = o.shift
        planet_meshes = []
        for arm in problem.arms:
            refs = put(f"arm {arm.planet}", [m.reference * scale for m in arm.meshes]) if arm.fixed is None else []
            halfwidths = tuple(int(y * m.module * scale) for m in arm.meshes) if arm.fixed is None else ()
            fixed = int(arm.fixed * scale) if arm.fixed is not None else None
            planet_meshes.append((arm.planet, tuple(refs), halfwidths, fixed))
        rims = []
        for rim in problem.rims:
            (tip,) = put(f"tip {rim.planet} {rim.gear}", [rim.tip_radius * scale])
            rims.append((planets.index(rim.planet), tip, int(o.clearance * rim.module * scale)))
        pairs = []
        for pair in problem.pairs:
            d_idx, ta, tb = put(f"pair {pair.first} {pair.second}",
                                [pair.centre_distance * scale, pair.tip_radii[0] * scale, pair.tip_radii[1] * scale])
            pairs.append((planets.index(pair.first), planets.index(pair.second), d_idx, ta, tb,
                          int(o.clearance * pair.module * scale)))
        central = []
        for L in problem.train.links:
            if L.kind is LinkKind.PLANET:
                continue
            for g in L.gears:
                outer_radius = g.radius if g.internal else g.radius + o.addendum * g.module
                central += put(f"central {g.name}", [outer_radius * scale])
        planet_tips = tuple(tuple(r[1] for r in rims if r[0] == i) for i in range(len(planets)))
        geometry = _Geometry(tuple(planet_meshes), tuple(rims), tuple(pairs), tuple(central), planet_tips)
        internal_pairs = []
        for im in problem.internal_meshes:
            if o.ring_difference and (im.internal_teeth.free_symbols or im.external_teeth.free_symbols):
                internal_pairs.append(tuple(put(f"internal {im.internal}", [im.internal_teeth, im.external_teeth])))
            elif o.ring_difference and im.internal_teeth - im.external_teeth < o.ring_difference:
                raise InputError(f"internal gear {im.internal} has {im.internal_teeth} teeth and {im.external} "
                                 f"{im.external_teeth}: fewer than {o.ring_difference} apart; change them or lower "
                                 "the ring difference")
        # integers must stay exact in binary64
        bounds = {str(z): zhi[z] for z in unknowns} | {str(s): w for s, w in slacks}
        for e in cand + outer_exprs:
            _check_exact(e, bounds, o.zmax)
        f_cand = compile(cand, cand_args, backend="numpy", stable=False, on_pole="return", cse=True)
        cc, ss, kk_, tt = sp.symbols("C S k t", real=True)
        f_sin = compile(cc + ss * sp.sin(sp.pi / kk_), [cc, ss, kk_], backend="mpmath", digits=60)
        aa, bb, dd, rr = sp.symbols("A B D R2", real=True)
        f_cross = compile(aa - bb * sp.cos(2 * sp.pi * tt / kk_) + sp.sin(2 * sp.pi * tt / kk_) * sp.sqrt(dd) - rr,
                          [aa, bb, dd, rr, tt, kk_], backend="mpmath", digits=60)
        k = problem.count
        return cls(
            problem=problem, target=target, top=top, unknowns=tuple(map(str, unknowns)),
            outer=tuple(map(str, outer)), last=None if last is None else str(last), dependents=dep_names,
            lows=tuple(lows), highs=tuple(highs), size=size, scale=scale, chunk=max(1, int(chunk)),
            f_outer=f_outer, f_cand=f_cand, outer_layout=outer_layout, cand_layout=layout,
            slack_names=tuple(str(s) for s, _ in slacks), slack_bounds=tuple(w for _, w in slacks),
            planets=planets, k=k, geometry=geometry, internal_pairs=tuple(internal_pairs),  # type: ignore[arg-type]
            filter_bounds=tuple(w for _, w in filters), assembly=tuple(assembly), f_sin=f_sin, f_cross=f_cross,
            notes=tuple(notes), dependent_alpha=tuple(alphas), dependent_limits=tuple(limits), rank=order,
            efficiency=eff,
        )

    @property
    def chunks(self) -> list[tuple[int, int]]:
        """The ranges of outer-tuple numbers, in order."""
        return [(s, min(s + self.chunk, self.size)) for s in range(0, self.size, self.chunk)] or [(0, 0)]

    def describe(self) -> str:
        """The search space in one line: the outer tuples and the unknowns solved from the ratio window and coaxiality."""
        dims = " x ".join(f"{n} {lo}..{hi}" for n, lo, hi in zip(self.outer + self.slack_names, self.lows, self.highs))
        tail = f", {self.last} from the ratio window" if self.last else ""
        dep = f", {', '.join(self.dependents)} from coaxiality" if self.dependents else ""
        return f"{self.size} outer tuples ({dims or 'one'}){tail}{dep}"


# --------------------------------------------------------------------------- helpers of the build
def _integer_scale(expr: sp.Expr) -> int:
    """The least positive integer that makes every coefficient of a linear expression whole."""
    q = 1
    for c in sp.Add.make_args(sp.expand(expr)):
        coeff = c.as_coeff_Mul()[0]
        q = math.lcm(q, int(sp.Rational(coeff).q))
    return q


def _length_scale(problem: Problem) -> int:
    """Lengths times this are whole numbers (radii, tip radii, arms, clearances, shifts and their midpoints)."""
    o = problem.options
    q = 1
    values = []
    for L in problem.train.links:
        for g in L.gears:
            m = sp.sympify(g.module)
            values += [m / 2, o.addendum * m, o.clearance * m, o.shift * m]
    for arm in problem.arms:
        if arm.fixed is not None:
            values.append(arm.fixed)
        for cm in arm.meshes:
            values += [c.as_coeff_Mul()[0] for c in sp.Add.make_args(cm.reference)]
    for pair in problem.pairs:
        values += [c.as_coeff_Mul()[0] for c in sp.Add.make_args(pair.centre_distance)]
    for v in values:
        q = math.lcm(q, int(sp.Rational(v).q))
    return q * 2 if o.shift else q  # the working arm is the midpoint of two such lengths


def _choose_last(num: sp.Expr, den: sp.Expr, free: Sequence[sp.Symbol]) -> sp.Symbol | None:
    best = None
    for z in free:
        dn, dd = sp.degree(num, z), sp.degree(den, z)
        if dn <= 1 and dd <= 1 and dn + dd >= 1:
            best = z
    return best


def _check_exact(expr: sp.Expr, bounds: dict[str, int], zmax: int) -> None:
    """Raise unless ``expr`` stays an exact integer in binary64 for every tooth number up to the bounds."""
    expr = sp.expand(expr)
    if not expr.free_symbols:
        return
    total = 0.0
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_coeff_Mul()
        size = abs(float(coeff))
        for base, power in rest.as_powers_dict().items():
            size *= float(bounds.get(str(base), zmax)) ** int(power) if base.free_symbols else abs(float(base)) ** int(power)
        total += size
    if total >= _EXACT:
        raise InputError(f"tooth numbers up to {zmax} make {sp.sstr(expr)[:60]} reach {total:.3g}, beyond the integers "
                         "binary64 holds exactly; lower zmax")


# --------------------------------------------------------------------------- a chunk
def evaluate_chunk(plan: SearchPlan, start: int, stop: int) -> ChunkResult:
    """Every tuple of outer numbers ``start`` to ``stop - 1``: the counts of the funnel and the best designs.

    A pure function of its arguments: Dask runs it on any worker.
    """
    began = time.perf_counter()
    counts = [0] * len(STAGES)
    top: list[Record] = []
    found = 0
    reach = (math.inf, -math.inf)
    made = 0
    exact_calls = [0]
    if stop <= start:
        return ChunkResult(start, stop, counts, 0, [], reach, 0, 0, 0.0)
    idx = np.arange(start, stop, dtype=np.int64)
    sizes = [h - lo + 1 for lo, h in zip(plan.lows, plan.highs)]
    if sizes:
        parts = np.unravel_index(idx, sizes)
        outer = [np.asarray(p, dtype=np.int64) + lo for p, lo in zip(parts, plan.lows)]
    else:
        outer = []
    tuples, r_lo, r_hi = _make_tuples(plan, outer, len(idx))
    reach = (r_lo, r_hi)
    for batch in tuples:
        made += len(next(iter(batch[0].values())))
        f, rec, c, (lo, hi) = _check(plan, batch, exact_calls)
        reach = (min(reach[0], lo), max(reach[1], hi))
        found += f
        for i, n in enumerate(c):
            counts[i] += n
        top = _best(plan, top + rec)
    return ChunkResult(start, stop, counts, found, top, reach, made, exact_calls[0], time.perf_counter() - began)


def _best(plan: SearchPlan, records: list[Record]) -> list[Record]:
    records.sort(key=lambda r: r.key)
    return records if plan.top is None else records[: plan.top]


def merge(plan: SearchPlan, results: Sequence[ChunkResult]) -> ChunkResult:
    """The chunks' results as one (the same for any split of the outer tuples)."""
    counts = [sum(r.counts[i] for r in results) for i in range(len(STAGES))]
    top = _best(plan, [rec for r in results for rec in r.top])
    lo = min((r.reach[0] for r in results), default=math.inf)
    hi = max((r.reach[1] for r in results), default=-math.inf)
    return ChunkResult(min((r.start for r in results), default=0), max((r.stop for r in results), default=0), counts,
                       sum(r.found for r in results), top, (lo, hi), sum(r.made for r in results),
                       sum(r.exact_calls for r in results), sum(r.seconds for r in results))


def _make_tuples(plan: SearchPlan, outer: list[np.ndarray], n: int) -> tuple[list[tuple], float, float]:
    """The tuples (unknowns, slacks) with the ratio in the window, in batches; and the reachable ratios."""
    n_out = len(plan.outer)
    zcols = {name: outer[i] for i, name in enumerate(plan.outer)}
    scols = {name: outer[n_out + i] for i, name in enumerate(plan.slack_names)}
    keep = np.ones(n, dtype=bool)
    vals: list[np.ndarray] = []
    if plan.f_outer is not None:
        out = plan.f_outer(*[np.asarray(c, dtype=float) for c in outer])
        vals = list(out) if isinstance(out, tuple) else [out]
        vals = [np.broadcast_to(np.asarray(v, dtype=float), (n,)) for v in vals]
    dep_parts = [vals[i] for i in plan.outer_layout["dependents"]]
    # dependents that do not involve x: integral and within limits now
    lo_x = np.full(n, float(plan.problem.options.zmin))
    hi_x = np.full(n, float(plan.problem.options.zmax))
    for j, (alpha, (dlo, dhi)) in enumerate(zip(plan.dependent_alpha, plan.dependent_limits)):
        beta = dep_parts[j]
        if alpha == 0:
            ok = (np.abs(beta - np.rint(beta)) < 1e-6) & (beta >= dlo - 1e-6) & (beta <= dhi + 1e-6)
            keep &= ok
        else:
            a = float(alpha)
            b1, b2 = (dlo - beta) / a, (dhi - beta) / a
            lo_x = np.maximum(lo_x, np.minimum(b1, b2))
            hi_x = np.minimum(hi_x, np.maximum(b1, b2))
    reach_lo, reach_hi = math.inf, -math.inf
    if plan.last is None:
        idx = np.flatnonzero(keep)
        cols = _columns(plan, zcols, scols, idx, None, dep_parts)
        return _batches(cols), reach_lo, reach_hi
    a, b, c, d = (vals[i] for i in plan.outer_layout["abcd"])
    eps = 1e-7
    L = np.ceil(lo_x - eps)
    U = np.floor(hi_x + eps)
    keep &= L <= U
    # the reachable ratios: ends of x's range (and either side of a pole)
    with np.errstate(divide="ignore", invalid="ignore"):
        pts = [L, U]
        pole = -d / np.where(c == 0, np.nan, c)
        inside = (pole > L) & (pole < U)
        pts += [np.where(inside, np.floor(pole), L), np.where(inside, np.ceil(pole), U)]
        for x in pts:
            fv = (a * x + b) / (c * x + d)
            fv = np.where(keep & np.isfinite(fv), fv, np.nan)
            if np.any(np.isfinite(fv)):
                reach_lo = min(reach_lo, float(np.nanmin(fv)))
                reach_hi = max(reach_hi, float(np.nanmax(fv)))
    lo, hi = float(plan.target.lo), float(plan.target.hi)
    a1, b1, a2, b2 = a - lo * c, b - lo * d, a - hi * c, b - hi * d
    intervals = _window(a1, b1, a2, b2)
    pieces = []
    for wl, wh in intervals:
        wl = np.where(np.isnan(wl), np.inf, wl)
        wh = np.where(np.isnan(wh), -np.inf, wh)
        with np.errstate(invalid="ignore"):
            start = np.ceil(np.maximum(L, np.where(np.isfinite(wl), wl - eps * (1 + np.abs(wl)), wl)))
            stop = np.floor(np.minimum(U, np.where(np.isfinite(wh), wh + eps * (1 + np.abs(wh)), wh)))
        pieces.append((start, stop))
    if len(pieces) == 2:  # keep the second clear of the first
        (_, e1), (s2, e2) = pieces
        s2 = np.where(s2 <= e1, np.maximum(s2, e1 + 1), s2)
        pieces[1] = (s2, e2)
    parts = []
    for s, e in pieces:
        cnt = np.where(keep & (e >= s), e - s + 1, 0).astype(np.int64)
        if cnt.sum() == 0:
            continue
        owner = np.repeat(np.arange(n), cnt)
        offset = np.arange(int(cnt.sum()), dtype=np.int64) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        x = s[owner].astype(np.int64) + offset
        parts.append((owner, x))
    if not parts:
        return [], reach_lo, reach_hi
    owner = np.concatenate([p[0] for p in parts])
    x = np.concatenate([p[1] for p in parts])
    cols = _columns(plan, zcols, scols, owner, x, dep_parts)
    return _batches(cols), reach_lo, reach_hi


def _window(a1: np.ndarray, b1: np.ndarray, a2: np.ndarray, b2: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """Where (a1 x + b1)(a2 x + b2) <= 0: up to two intervals per tuple (inf where open)."""
    inf = np.inf
    n = a1.shape[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = -b1 / a1
        r2 = -b2 / a2
    lo1, hi1 = np.full(n, inf), np.full(n, -inf)  # empty
    lo2, hi2 = np.full(n, inf), np.full(n, -inf)
    both = (a1 != 0) & (a2 != 0)
    s = a1 * a2
    between = both & (s > 0)
    lo1 = np.where(between, np.minimum(r1, r2), lo1)
    hi1 = np.where(between, np.maximum(r1, r2), hi1)
    rays = both & (s < 0)
    lo1 = np.where(rays, -inf, lo1)
    hi1 = np.where(rays, np.minimum(r1, r2), hi1)
    lo2 = np.where(rays, np.maximum(r1, r2), lo2)
    hi2 = np.where(rays, inf, hi2)
    for az, bz, r_other, a_other in ((a1 == 0, b1, r2, a2), (a2 == 0, b2, r1, a1)):
        one = az & (a_other != 0)
        if not one.any():
            continue
        # bz (a_other x + b_other) <= 0
        all_x = one & (bz == 0)
        below = one & (bz * a_other > 0)  # x <= r_other
        above = one & (bz * a_other < 0)
        lo1 = np.where(all_x, -inf, np.where(below, -inf, np.where(above, r_other, lo1)))
        hi1 = np.where(all_x, inf, np.where(below, r_other, np.where(above, inf, hi1)))
    none = (a1 == 0) & (a2 == 0)
    const_ok = none & (b1 * b2 <= 0)
    lo1 = np.where(const_ok, -inf, lo1)
    hi1 = np.where(const_ok, inf, hi1)
    return [(lo1, hi1), (lo2, hi2)]


def _columns(plan: SearchPlan, zcols: dict, scols: dict, owner: np.ndarray, x: np.ndarray | None,
             dep_parts: list[np.ndarray]) -> dict[str, np.ndarray]:
    cols: dict[str, np.ndarray] = {}
    for name in plan.outer:
        cols[name] = zcols[name][owner]
    for name in plan.slack_names:
        cols[name] = scols[name][owner]
    ok = np.ones(len(owner), dtype=bool)
    if x is not None and plan.last is not None:
        cols[plan.last] = x
    for j, name in enumerate(plan.dependents):
        alpha = float(plan.dependent_alpha[j])
        beta = dep_parts[j][owner]
        value = beta + (alpha * x if (x is not None and alpha) else 0.0)
        dlo, dhi = plan.dependent_limits[j]
        r = np.rint(value)
        ok &= (np.abs(value - r) < 1e-6) & (r >= dlo) & (r <= dhi)
        cols[name] = r.astype(np.int64)
    for name in cols:
        cols[name] = np.asarray(cols[name], dtype=np.int64)[ok]
    return cols


def _batches(cols: dict[str, np.ndarray]) -> list[tuple]:
    n = len(next(iter(cols.values()))) if cols else 0
    return [({k: v[s: s + _BATCH] for k, v in cols.items()},) for s in range(0, n, _BATCH)] if n else []


# --------------------------------------------------------------------------- checks of made tuples
def _check(plan: SearchPlan, batch: tuple, exact_calls: list[int]) -> tuple[int, list[Record], list[int], tuple[float, float]]:
    (cols,) = batch
    Z = np.stack([cols[u] for u in plan.unknowns], axis=1)
    sig = np.stack([cols[s] for s in plan.slack_names], axis=1) if plan.slack_names else np.zeros((len(Z), 0), np.int64)
    args = [Z[:, i].astype(float) for i in range(Z.shape[1])] + [sig[:, i].astype(float) for i in range(sig.shape[1])]
    out = plan.f_cand(*args)
    out = list(out) if isinstance(out, tuple) else [out]
    m = len(Z)
    vals = [np.broadcast_to(np.asarray(v, dtype=float), (m,)) for v in out]

    def ints(i: int) -> np.ndarray:
        return np.rint(vals[i]).astype(np.int64)

    counts = [0] * len(STAGES)
    lay = plan.cand_layout
    # ---- ratio: reduced fractions, compared exactly
    N, D = ints(lay["ratio"][0]), ints(lay["ratio"][1])
    ok = D != 0
    g = np.gcd(N, D)
    g = np.where(g == 0, 1, g)
    sign = np.where(D < 0, -1, 1)
    p, q = N // g * sign, np.abs(D) // g
    pairs = np.stack([p, q], axis=1)
    which = np.full(m, -1, dtype=np.int64)
    fr: list[Fraction] = []
    errors: list[Fraction] = []
    rank = np.zeros(0, dtype=np.int64)
    if ok.any():
        if np.abs(p[ok]).max() < 2**31 and q[ok].max() < 2**31:  # one int64 key per fraction: a fast 1-D sort
            packed, inverse = np.unique((p[ok] << 32) + q[ok], return_inverse=True)
            uniq = np.stack([packed >> 32, packed & (2**32 - 1)], axis=1)
        else:
            uniq, inverse = np.unique(pairs[ok], axis=0, return_inverse=True)
        which[ok] = np.asarray(inverse).reshape(-1)
        fr = [Fraction(int(a), int(b)) for a, b in uniq]
        inside = np.array([plan.target.lo <= v <= plan.target.hi for v in fr], dtype=bool)
        errors = [plan.target.error(v) for v in fr]
        levels = {e: i for i, e in enumerate(sorted(set(errors)))}  # equal errors rank equal (a range, or +-x)
        rank = np.array([levels[e] for e in errors], dtype=np.int64)
        ok &= inside[np.maximum(which, 0)]
        values = [float(v) for v in fr]
        reach = (min(values), max(values))
    else:
        reach = (math.inf, -math.inf)
    counts[0] = int(ok.sum())
    # ---- internal gears
    for ii, ie in plan.internal_pairs:
        ok &= ints(ii) - ints(ie) >= plan.problem.options.ring_difference
    counts[1] = int(ok.sum())
    # ---- coaxiality within the profile shift (pairs the dependents do not cover)
    for i, w in zip(lay["filters"], plan.filter_bounds):
        ok &= np.abs(ints(i)) <= w
    counts[2] = int(ok.sum())
    # ---- assembly
    for group in plan.assembly:
        system_rows = []
        for kind, g_idx, r_idx, modulus, _names in group:
            R = ints(r_idx)
            if kind == "integral":
                ok &= R % modulus == 0
            elif kind == "divisible":
                gg = np.zeros(m, dtype=np.int64)
                for gi in g_idx:
                    gg = np.gcd(gg, ints(gi))
                ok &= np.where(gg == 0, R == 0, R % (modulus * np.where(gg == 0, 1, gg)) == 0)
            elif kind == "zero":
                ok &= R == 0
            else:
                system_rows.append((g_idx, r_idx, modulus, _names))
        if system_rows:
            for i in np.flatnonzero(ok):
                exact_calls[0] += 1
                if not _system_ok(system_rows, ints, int(i)):
                    ok[i] = False
    counts[3] = int(ok.sum())
    # ---- neighbours of one kind
    arms = _arms(plan, ints, m)
    k = plan.k
    for planet_i, tip, clear in plan.geometry.rims:
        kk = k[plan.planets[planet_i]]
        if kk < 2:
            continue
        const = -(2 * ints(tip) + clear)
        slope = 2 * arms[planet_i]
        ok &= _sign_sin(plan, const, slope, kk, ok, exact_calls) > 0
    counts[4] = int(ok.sum())
    # ---- meshing planets: placed, and clear of the copies they do not mesh
    for pa, pb, di, ta, tb, clear in plan.geometry.pairs:
        a, b, dd = arms[pa], arms[pb], ints(di)
        ok &= ((a - b) ** 2 <= dd**2) & (dd**2 <= (a + b) ** 2)
        kk = k[plan.planets[pa]]
        if kk < 2:
            continue
        span = ints(ta) + ints(tb) + clear
        for t in range(1, kk):
            ok &= _cross_clear(plan, a, b, dd, span, t, kk, ok, exact_calls)
    counts[5] = int(ok.sum())
    found = int(ok.sum())
    if not found:
        return 0, [], counts, reach
    # ---- the best of this batch, in the exact order
    sel = np.flatnonzero(ok)
    size = np.zeros(m, dtype=np.int64)
    for i in plan.geometry.central:
        size = np.maximum(size, ints(i))
    for pi, tips in enumerate(plan.geometry.planet_tips):
        for ti in tips:
            size = np.maximum(size, arms[pi] + ints(ti))
    size = 2 * size
    tsum = Z.sum(axis=1)
    columns = {"error": rank[which[sel]], "size": size[sel], "teeth": tsum[sel]}
    eta: list[Fraction | None] = [None] * len(sel)
    if plan.efficiency is not None:  # exact values, ranked exactly (largest first, undefined last)
        eta = plan.efficiency.values(plan.problem, Z[sel])
        distinct = sorted({v for v in eta if v is not None}, reverse=True)
        place = {v: i for i, v in enumerate(distinct)}
        columns["efficiency"] = np.array([place[v] if v is not None else len(distinct) for v in eta], dtype=np.int64)
    keys = [Z[sel, j] for j in reversed(range(Z.shape[1]))] + [columns[name] for name in reversed(plan.rank)]
    order = np.lexsort(keys)
    if plan.top is not None:
        order = order[: plan.top]
    records = [Record(errors[which[i]], int(size[i]), tuple(int(v) for v in Z[i]), tuple(int(v) for v in sig[i]),
                      fr[which[i]], eta[j], plan.rank) for j, i in zip(order.tolist(), sel[order].tolist())]
    return found, records, counts, reach


def _system_ok(rows: list, ints: Callable[[int], np.ndarray], i: int) -> bool:
    names: list[str] = []
    for _, _, _, ns in rows:
        for nm in ns:
            if nm not in names:
                names.append(nm)
    G, h = [], []
    for g_idx, r_idx, modulus, ns in rows:
        coeff = dict.fromkeys(names, 0)
        for gi, nm in zip(g_idx, ns):
            coeff[nm] = int(ints(gi)[i])
        G.append([coeff[nm] for nm in names])
        h.append(Fraction(int(ints(r_idx)[i]), modulus))
    return solvable(G, h)


def _arms(plan: SearchPlan, ints: Callable[[int], np.ndarray], m: int) -> list[np.ndarray]:
    """Each planet's working arm times the length scale (integers)."""
    out = []
    for _planet, refs, halfwidths, fixed in plan.geometry.planet_meshes:
        if fixed is not None:
            out.append(np.full(m, fixed, dtype=np.int64))
            continue
        values = [ints(i) for i in refs]
        if not any(halfwidths):
            out.append(values[0])
            continue
        lo = np.max(np.stack([v - h for v, h in zip(values, halfwidths)]), axis=0)
        hi = np.min(np.stack([v + h for v, h in zip(values, halfwidths)]), axis=0)
        out.append((lo + hi) // 2)
    return out


def _sign_sin(plan: SearchPlan, const: np.ndarray, slope: np.ndarray, k: int, ok: np.ndarray, exact_calls: list[int]) -> np.ndarray:
    """Sign of const + slope sin(pi/k) (integers), exactly: floats with a margin, else 60 digits."""
    exact_sin = {1: Fraction(0), 2: Fraction(1), 6: Fraction(1, 2)}
    if k in exact_sin:
        s = exact_sin[k]
        value = const * s.denominator + slope * s.numerator
        return np.sign(value)
    v = const + slope * math.sin(math.pi / k)
    scale = np.abs(const) + np.abs(slope) + 1.0
    out = np.sign(v).astype(np.int64)
    close = ok & (np.abs(v) <= _BAND * scale)
    for i in np.flatnonzero(close):
        exact_calls[0] += 1
        precise = plan.f_sin(int(const[i]), int(slope[i]), k)
        out[i] = 0 if abs(precise) < 1e-40 * float(scale[i]) else (1 if precise > 0 else -1)
    return out


def _cross_clear(plan: SearchPlan, a: np.ndarray, b: np.ndarray, d: np.ndarray, reach: np.ndarray, t: int, k: int,
                 ok: np.ndarray, exact_calls: list[int]) -> np.ndarray:
    """Copies of two meshing planets, ``t`` spacings apart, clear each other: their axes (arms ``a``, ``b``,
    the angle between them 2 pi t/k more than the meshing pair's) are farther apart than ``reach``.

    With A = a^2 + b^2 and B = A - d^2 (law of cosines: 2ab cos(gamma) = B), the square of their
    distance is A - B cos(phi) + sin(phi) sqrt(4 a^2 b^2 - B^2), phi = 2 pi t/k.
    """
    phi = 2 * math.pi * t / k
    af, bf, df, rf = (np.asarray(v, dtype=float) for v in (a, b, d, reach))
    A = af**2 + bf**2
    B = A - df**2
    root = np.sqrt(np.maximum(4 * af**2 * bf**2 - B**2, 0.0))
    v = A - B * math.cos(phi) + math.sin(phi) * root - rf**2
    scale = A + np.abs(B) + root + rf**2 + 1.0
    out = v > 0
    close = ok & (np.abs(v) <= _BAND * scale)
    for i in np.flatnonzero(close):
        exact_calls[0] += 1
        ai, bi, di, ri = int(a[i]), int(b[i]), int(d[i]), int(reach[i])
        Ai = ai * ai + bi * bi
        Bi = Ai - di * di
        precise = plan.f_cross(Ai, Bi, max(4 * ai * ai * bi * bi - Bi * Bi, 0), ri * ri, t, k)
        out[i] = bool(precise > 1e-40 * float(scale[i]))
    return out
