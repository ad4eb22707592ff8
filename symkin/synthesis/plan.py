"""The search plan: the derived conditions compiled into the functions a chunk evaluates.

:meth:`SearchPlan.build` takes a :class:`~symkin.synthesis.problem.Problem` and a
:class:`~symkin.synthesis.request.Target`, solves the coaxiality for the dependent tooth
numbers (within a slack when profile shift is allowed), chooses the free tooth number ``x``
the ratio window gives in closed form, and compiles two functions: the *outer* one (the
dependents' parts and the ratio's coefficients in ``x``, for each outer tuple) and the
*candidate* one (every integer and scaled length the checks of :mod:`symkin.synthesis.funnel`
read).  Integers are kept exact in binary64 (a larger ``zmax`` is refused).

    >>> from symkin.trains import load_train
    >>> from symkin.synthesis.problem import derive
    >>> plan = SearchPlan.build(derive(load_train("simple"), driver="S", driven="C", fixed="R", planets=3, zmax=80),
    ...                         Target.of(4, 0.01), top=3)
    >>> plan.describe()
    '63 outer tuples (z_s 18..80), z_p from the ratio window, z_r from coaxiality'
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import sympy as sp

from symkin.errors import InputError
from symkin.model import LinkKind
from symkin.numeric import compile
from symkin.synthesis.efficiency import DEFAULT_RANK, EfficiencyLaw, rank_order
from symkin.synthesis.problem import Problem
from symkin.synthesis.request import Target

__all__ = ["SearchPlan", "STAGES"]

#: Integers below this are exact in binary64 (with a bit to spare).
_EXACT = 2.0**52
#: Names of the stages every tuple passes in order (the funnel).
STAGES = ("ratio", "internal gears", "coaxiality", "assembly", "neighbours", "placement")


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
        scale = _length_scale(problem)
        coax = _solve_coaxiality(problem)
        slacks = coax.slacks
        free = [z for z in unknowns if z not in coax.dependents]
        num, den = sp.fraction(sp.cancel(problem.ratio.rhs.subs(coax.dependents)))
        last = _choose_last(num, den, free)
        notes = list(problem.notes)
        if last is None:
            notes.append("the ratio law is linear-fractional in no single free tooth number: every tuple of the free "
                         "numbers is made and its ratio checked")
        outer = [z for z in free if z != last]
        lows = [o.zmin for _ in outer] + [-w for _, w in slacks]
        highs = [o.zmax for _ in outer] + [w for _, w in slacks]
        size = math.prod(h - lo + 1 for lo, h in zip(lows, highs))
        f_outer, outer_exprs, outer_layout, alphas, limits = _outer_function(
            coax.dependents, last, num, den, outer + [s for s, _ in slacks], (o.zmin, o.zmax))
        cand = _Outputs()
        full_num, full_den = sp.fraction(sp.cancel(problem.ratio.rhs))
        cand.put("ratio", [full_num, full_den])
        filters = [(e.subs({}), w) for e, w in coax.filters if e.free_symbols]
        cand.put("filters", [e for e, _ in filters])
        assembly = _assembly_outputs(cand, problem)
        planets, geometry = _geometry_outputs(cand, problem, scale)
        internal_pairs = _internal_outputs(cand, problem)
        # integers must stay exact in binary64
        bounds = {str(z): o.zmax for z in unknowns} | {str(s): w for s, w in slacks}
        for e in cand.exprs + outer_exprs:
            _check_exact(e, bounds, o.zmax)
        f_cand = compile(cand.exprs, list(unknowns) + [s for s, _ in slacks], backend="numpy", stable=False,
                         on_pole="return", cse=True)
        f_sin, f_cross = _exact_deciders()
        return cls(
            problem=problem, target=target, top=top, unknowns=tuple(map(str, unknowns)),
            outer=tuple(map(str, outer)), last=None if last is None else str(last),
            dependents=tuple(str(d) for d in coax.dependents),
            lows=tuple(lows), highs=tuple(highs), size=size, scale=scale, chunk=max(1, int(chunk)),
            f_outer=f_outer, f_cand=f_cand, outer_layout=outer_layout, cand_layout=cand.layout,
            slack_names=tuple(str(s) for s, _ in slacks), slack_bounds=tuple(w for _, w in slacks),
            planets=planets, k=problem.count, geometry=geometry, internal_pairs=tuple(internal_pairs),  # type: ignore[arg-type]
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


# --------------------------------------------------------------------------- steps of the build
@dataclass
class _Coaxiality:
    """The coaxiality rows solved: the dependents in the other unknowns and the slacks, each slack
    ``sigma`` within ``+-w``; the rows left to check, ``|e| <= w`` (integer-valued)."""

    dependents: dict[sp.Symbol, sp.Expr]
    slacks: list[tuple[sp.Symbol, int]]
    filters: list[tuple[sp.Expr, int]]


def _solve_coaxiality(problem: Problem) -> _Coaxiality:
    """Each pivot row ``e = s (lhs - rhs)``, integer-valued, solved for one unknown it still has (a unit
    coefficient and an internal gear preferred), within a slack of ``floor(s y m)`` when shift is allowed."""
    unknowns = problem.unknowns
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
    return _Coaxiality(dependents, slacks, extra_filters)


def _outer_function(dependents: dict[sp.Symbol, sp.Expr], last: sp.Symbol | None, num: sp.Expr, den: sp.Expr,
                    outer_syms: list[sp.Symbol], teeth: tuple[int, int]
                    ) -> tuple[Any, list[sp.Expr], dict[str, Any], list[Fraction], list[tuple[int, int]]]:
    """The function of the outer tuple: each dependent's part without ``x`` (``alpha x`` added later) and
    the ratio's coefficients ``a, b, c, d`` in ``(a x + b)/(c x + d)``; with the layout of its outputs,
    the dependents' ``alpha`` and their limits."""
    outer_exprs: list[sp.Expr] = []
    outer_layout: dict[str, Any] = {}
    alphas, limits = [], []
    for v in dependents.values():
        alpha = v.coeff(last) if last is not None else sp.Integer(0)
        outer_exprs.append(sp.expand(v - alpha * last) if last is not None else v)
        alphas.append(Fraction(int(sp.Rational(alpha).p), int(sp.Rational(alpha).q)))
        limits.append(teeth)
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
    return f_outer, outer_exprs, outer_layout, alphas, limits


class _Outputs:
    """The candidate function's outputs as they are put in: every integer and scaled length the checks
    need, each group under a name in ``layout`` (its indices)."""

    def __init__(self) -> None:
        self.exprs: list[sp.Expr] = []
        self.layout: dict[str, Any] = {}

    def put(self, name: str, exprs: Sequence[sp.Expr]) -> list[int]:
        idx = list(range(len(self.exprs), len(self.exprs) + len(exprs)))
        self.exprs.extend(sp.expand(e) for e in exprs)
        self.layout[name] = idx
        return idx


def _assembly_outputs(cand: _Outputs, problem: Problem) -> list[tuple]:
    """The assembly rows of each group of more than one copy: (kind, G outputs, R output, q k, integer names)."""
    assembly = []
    for group in problem.assembly:
        kk = problem.count[group.planets[0]]
        if kk < 2:
            continue
        rows = []
        for arow in group.rows:
            g_idx = cand.put(f"G{len(cand.layout)}", [c for _, c in arow.coefficients])
            r_idx = cand.put(f"R{len(cand.layout)}", [arow.numerator])[0]
            rows.append((arow.kind, g_idx, r_idx, arow.denominator * kk, [str(n) for n, _ in arow.coefficients]))
        assembly.append(tuple(rows))
    return assembly


def _geometry_outputs(cand: _Outputs, problem: Problem, scale: int) -> tuple[tuple[str, ...], _Geometry]:
    """The planets' arms, rims, meshing pairs and the central gears' outer radii, in lengths times ``scale``."""
    o = problem.options
    planets = tuple(a.planet for a in problem.arms)
    y = o.shift
    planet_meshes = []
    for arm in problem.arms:
        refs = cand.put(f"arm {arm.planet}", [m.reference * scale for m in arm.meshes]) if arm.fixed is None else []
        halfwidths = tuple(int(y * m.module * scale) for m in arm.meshes) if arm.fixed is None else ()
        fixed = int(arm.fixed * scale) if arm.fixed is not None else None
        planet_meshes.append((arm.planet, tuple(refs), halfwidths, fixed))
    rims = []
    for rim in problem.rims:
        (tip,) = cand.put(f"tip {rim.planet} {rim.gear}", [rim.tip_radius * scale])
        rims.append((planets.index(rim.planet), tip, int(o.clearance * rim.module * scale)))
    pairs = []
    for pair in problem.pairs:
        d_idx, ta, tb = cand.put(f"pair {pair.first} {pair.second}",
                                 [pair.centre_distance * scale, pair.tip_radii[0] * scale, pair.tip_radii[1] * scale])
        pairs.append((planets.index(pair.first), planets.index(pair.second), d_idx, ta, tb,
                      int(o.clearance * pair.module * scale)))
    central = []
    for L in problem.train.links:
        if L.kind is LinkKind.PLANET:
            continue
        for g in L.gears:
            outer_radius = g.radius if g.internal else g.radius + o.addendum * g.module
            central += cand.put(f"central {g.name}", [outer_radius * scale])
    planet_tips = tuple(tuple(r[1] for r in rims if r[0] == i) for i in range(len(planets)))
    return planets, _Geometry(tuple(planet_meshes), tuple(rims), tuple(pairs), tuple(central), planet_tips)


def _internal_outputs(cand: _Outputs, problem: Problem) -> list[tuple[int, ...]]:
    """The tooth numbers of each internal mesh with an unknown (internal, external); a numeric pair is checked now."""
    o = problem.options
    internal_pairs = []
    for im in problem.internal_meshes:
        if o.ring_difference and (im.internal_teeth.free_symbols or im.external_teeth.free_symbols):
            internal_pairs.append(tuple(cand.put(f"internal {im.internal}", [im.internal_teeth, im.external_teeth])))
        elif o.ring_difference and im.internal_teeth - im.external_teeth < o.ring_difference:
            raise InputError(f"internal gear {im.internal} has {im.internal_teeth} teeth and {im.external} "
                             f"{im.external_teeth}: fewer than {o.ring_difference} apart; change them or lower "
                             "the ring difference")
    return internal_pairs


def _exact_deciders() -> tuple[Any, Any]:
    """At 60 digits: ``C + S sin(pi/k)`` (neighbours) and the squared distance of two meshing planets' copies less
    their reach (placement), for the decisions floats leave within their margin."""
    cc, ss, kk_, tt = sp.symbols("C S k t", real=True)
    f_sin = compile(cc + ss * sp.sin(sp.pi / kk_), [cc, ss, kk_], backend="mpmath", digits=60)
    aa, bb, dd, rr = sp.symbols("A B D R2", real=True)
    f_cross = compile(aa - bb * sp.cos(2 * sp.pi * tt / kk_) + sp.sin(2 * sp.pi * tt / kk_) * sp.sqrt(dd) - rr,
                      [aa, bb, dd, rr, tt, kk_], backend="mpmath", digits=60)
    return f_sin, f_cross


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

