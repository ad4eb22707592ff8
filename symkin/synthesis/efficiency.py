"""The efficiency law of a searched train, derived once, for ranking designs by it.

The law is the train's statics (:func:`symkin.statics.statics`, the basic-train method)
with the tooth numbers left as symbols: a rational function of the teeth, or a
``Piecewise`` of them where the direction of the power through a mesh depends on the
teeth.  The search evaluates it exactly (:class:`fractions.Fraction`) at every design that
passes the conditions, its pieces and the conditions between them held as ratios of
integer polynomials evaluated over the designs at once, so the ranking is one exact total
order whatever the chunking.

At a boundary of the ``Piecewise`` (a relative power exactly zero) no condition holds:
there the mesh carries no relative power and loses none, and the design's efficiency is
taken from the statics of its own train (the route :meth:`symkin.synthesis.Design.efficiency`
takes). Where a condition is itself undefined (a pole of a relative power: a degenerate
train, such as a double-pinion set with z_r = z_s, whose sun stands still) the efficiency is
undefined, as the statics of that train says, and such designs rank last.

    >>> from symkin.trains import load_train
    >>> from symkin.synthesis.problem import derive
    >>> law = EfficiencyLaw.derive(derive(load_train("simple"), driver="S", driven="C", fixed="R"), 0.98)
    >>> law.law
    (2401*z_r + 2500*z_s)/(2500*(z_r + z_s))
    >>> law.exact([(18, 18, 54), (21, 21, 63), (18, 36, 90)])
    [Fraction(9703, 10000), Fraction(9703, 10000), Fraction(967, 1000)]
"""

from __future__ import annotations

import math
import operator
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import CoaxialityWarning, InputError, SymkinError
from symkin.numeric import compile

__all__ = ["EfficiencyLaw", "RANK_KEYS", "DEFAULT_RANK", "rank_order", "power_path"]

#: The keys a search can rank designs by, and what each means.
RANK_KEYS = {
    "error": "ratio error (smallest first)",
    "efficiency": "efficiency of the driver-to-driven power path (largest first)",
    "size": "envelope diameter (smallest first)",
    "teeth": "sum of the tooth numbers (smallest first)",
}
#: The order without a request: ratio error, then size, then tooth sum.
DEFAULT_RANK = ("error", "size", "teeth")

_OPS = {"<": operator.lt, ">": operator.gt, "<=": operator.le, ">=": operator.ge, "==": operator.eq,
        "!=": operator.ne}


def rank_order(rank: str | Sequence[str] | None) -> tuple[str, ...]:
    """The full ranking order for a request: the keys asked for, then the rest of :data:`DEFAULT_RANK`.

    ``rank`` is a sequence of keys of :data:`RANK_KEYS` or one string of them separated by
    commas; ties left after every key are broken by the tooth numbers themselves.

    >>> rank_order("efficiency")
    ('efficiency', 'error', 'size', 'teeth')
    >>> rank_order(["error", "efficiency"])
    ('error', 'efficiency', 'size', 'teeth')
    """
    if rank is None:
        return DEFAULT_RANK
    if isinstance(rank, str):
        keys = [k.strip().lower() for k in rank.split(",")]
    elif isinstance(rank, Sequence) and all(isinstance(k, str) for k in rank):
        keys = [k.strip().lower() for k in rank]
    else:
        raise InputError(f"rank by keys among {', '.join(RANK_KEYS)} (a string such as 'efficiency,error' or a list "
                         f"of them), got {rank!r}")
    if not keys or any(not k for k in keys):
        raise InputError(f"rank by one or more of {', '.join(RANK_KEYS)} separated by commas, got {rank!r}")
    for k in keys:
        if k not in RANK_KEYS:
            raise InputError(f"cannot rank by {k!r}: the keys are {', '.join(RANK_KEYS)}")
    if len(set(keys)) != len(keys):
        raise InputError(f"rank names a key twice: {rank!r}")
    return tuple(keys) + tuple(k for k in DEFAULT_RANK if k not in keys)


def _tree(cond: Any, put: Any) -> tuple:
    """A condition as a small tree of ('and'|'or'|'not'|'rel'|'const', ...); ``put`` numbers each
    relation's difference lhs - rhs (a ratio of polynomials)."""
    if cond is sp.true or cond is True:
        return ("const", True)
    if cond is sp.false or cond is False:
        return ("const", False)
    if isinstance(cond, sp.And):
        return ("and", tuple(_tree(a, put) for a in cond.args))
    if isinstance(cond, sp.Or):
        return ("or", tuple(_tree(a, put) for a in cond.args))
    if isinstance(cond, sp.Not):
        return ("not", _tree(cond.args[0], put))
    if isinstance(cond, sp.core.relational.Relational):
        return ("rel", put(cond.lhs - cond.rhs), cond.rel_op)
    raise InputError(f"the efficiency law has a condition symkin cannot decide exactly: {cond}")


def _integer_fraction(expr: sp.Expr, args: Sequence[sp.Symbol]) -> tuple[sp.Poly, sp.Poly]:
    """``expr`` as P/Q with P and Q polynomials in ``args`` with integer coefficients."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    p, q = sp.Poly(num, *args, domain="QQ"), sp.Poly(den, *args, domain="QQ")
    scale = 1
    for c in p.coeffs() + q.coeffs():
        scale = math.lcm(scale, int(sp.Rational(c).q))
    return (sp.Poly(p * scale, *args, domain="ZZ"), sp.Poly(q * scale, *args, domain="ZZ"))


def _bound(poly: sp.Poly, zmax: int) -> float:
    """An upper bound of |poly| for every argument in 0..zmax."""
    return sum(abs(float(c)) * float(zmax) ** sum(m) for m, c in poly.terms())


_DERIVED: dict[Any, EfficiencyLaw] = {}


@dataclass
class EfficiencyLaw:
    """The efficiency of a problem's power path as a law of its unknown tooth numbers.

    Every piece of the law and every condition between pieces is held as a ratio of two
    polynomials with integer coefficients, evaluated exactly over many designs at once:
    in binary64 where every value stays an integer below 2^53 for the search's tooth
    limits (checked once, from the coefficients), else in Python integers.

    Attributes
    ----------
    law : sympy expression
        Exact, in the unknowns (a ``Piecewise`` where the power flow depends on them).
    mesh_efficiency : str or number or dict
        What the meshes were given (:func:`symkin.statics.statics`' ``efficiency``).
    meshes : tuple of (str, sympy.Expr)
        Each mesh's efficiency as the statics took it (``"default"``: the train file's value
        where a mesh has one, else 0.98 external, 0.99 internal).
    """

    law: sp.Expr
    args: tuple[sp.Symbol, ...]
    mesh_efficiency: Any
    polys: tuple[tuple[tuple[tuple[int, ...], ...], tuple[int, ...]], ...]  # monomials, coefficients of each
    pieces: tuple[tuple[int, int], ...]  # each piece: polynomial numbers of P and Q
    conditions: tuple[tuple, ...]  # each piece's condition, as a tree over (P, Q) pairs
    f_float: Any  # every polynomial in binary64, or None when they do not stay exact
    meshes: tuple[tuple[str, sp.Expr], ...] = ()

    @classmethod
    def derive(cls, problem: Any, mesh_efficiency: Any = "default") -> EfficiencyLaw:
        """Derive the law from the statics of ``problem.train`` (teeth as symbols) and prepare it
        (once per problem and mesh efficiencies: a search builds two plans)."""
        key = (problem, repr(mesh_efficiency))
        try:
            return _DERIVED[key]
        except (KeyError, TypeError):
            pass
        law = cls._derive(problem, mesh_efficiency)
        try:
            if len(_DERIVED) > 8:
                _DERIVED.pop(next(iter(_DERIVED)))
            _DERIVED[key] = law
        except TypeError:  # pragma: no cover - an unhashable problem
            pass
        return law

    @classmethod
    def _derive(cls, problem: Any, mesh_efficiency: Any) -> EfficiencyLaw:
        from symkin.statics import statics

        train = problem.train
        driver, driven, held, joined = power_path(problem, train)
        result = statics(train, input=driver, output=driven, fixed=held, joined=joined, efficiency=mesh_efficiency)
        law = sp.piecewise_fold(result.efficiency.rhs)
        args = tuple(problem.unknowns)
        extra = law.free_symbols - set(args)
        if extra:
            names = ", ".join(sorted(map(str, extra)))
            raise InputError(f"ranking by efficiency needs a number for every mesh efficiency, and {names} has none; "
                             "give one (--efficiency 0.98) or leave 'default'")
        for mesh, value in result.efficiencies.items():
            if value.is_number and not value.is_Rational:
                raise InputError(f"ranking by efficiency orders designs exactly and needs each mesh efficiency as a "
                                 f"rational number, and mesh {mesh} has {value}; give a decimal such as "
                                 f"{float(value):.6g}")
        meshes = tuple(result.efficiencies.items())
        pieces = law.args if isinstance(law, sp.Piecewise) else ((law, sp.true),)
        polys: list[sp.Poly] = []

        def put(expr: sp.Expr) -> int:
            p, q = _integer_fraction(expr, args)
            polys.extend((p, q))
            return len(polys) - 2

        values, conditions = [], []
        for expr, cond in pieces:
            values.append(put(expr))
            conditions.append(_tree(cond, put))
        zmax = problem.options.zmax
        exact = all(_bound(p, zmax) < 2.0**52 for p in polys)
        f_float = compile([p.as_expr() for p in polys], list(args), backend="numpy", stable=False, on_pole="return", cse=True) \
            if exact else None
        held_polys = tuple((tuple(m for m, _ in p.terms()), tuple(int(c) for _, c in p.terms())) for p in polys)
        return cls(law, args, mesh_efficiency, held_polys, tuple((v, v + 1) for v in values), tuple(conditions),
                   f_float, meshes)

    def _evaluate(self, teeth: np.ndarray) -> list[np.ndarray]:
        """Every polynomial at each row of ``teeth``, exactly (int64 or Python-int object arrays)."""
        m = len(teeth)
        if self.f_float is not None:
            out = self.f_float(*[teeth[:, j].astype(float) for j in range(teeth.shape[1])])
            out = list(out) if isinstance(out, (tuple, list)) else [out]
            return [np.rint(np.broadcast_to(np.asarray(v, dtype=float), (m,))).astype(np.int64) for v in out]
        cols = [teeth[:, j].astype(object) for j in range(teeth.shape[1])]
        result = []
        for monomials, coeffs in self.polys:
            total = np.zeros(m, dtype=object)
            for mono, c in zip(monomials, coeffs):
                term = np.full(m, c, dtype=object)
                for col, e in zip(cols, mono):
                    if e:
                        term = term * col**e
                total = total + term
            result.append(total)
        return result

    def exact(self, teeth: np.ndarray) -> list[Fraction | None]:
        """The law exactly at each row of ``teeth`` (one column per unknown); None on a boundary
        of its pieces or at a pole (see :meth:`values`)."""
        return self._exact(teeth)[0]

    def _exact(self, teeth: np.ndarray) -> tuple[list[Fraction | None], np.ndarray]:
        """:meth:`exact`, and where a condition between pieces is itself undefined (a pole of a
        mesh's relative power: a degenerate train, e.g. a driver that stands still)."""
        teeth = np.asarray(teeth, dtype=np.int64).reshape(-1, len(self.args))
        m = len(teeth)
        vals = self._evaluate(teeth)
        degenerate = np.zeros(m, dtype=bool)
        for node in _relations(self.conditions):
            degenerate |= vals[node[1] + 1] == 0

        chosen = np.full(m, -1, dtype=np.int64)
        for b, cond in enumerate(self.conditions):
            chosen = np.where((chosen < 0) & _holds(cond, vals, m), b, chosen)
        found: list[Fraction | None] = [None] * m
        memo: dict[tuple[int, int], Fraction] = {}
        for b, (pi, qi) in enumerate(self.pieces):
            rows = np.flatnonzero(chosen == b)
            for r, p, q in zip(rows.tolist(), vals[pi][rows].tolist(), vals[qi][rows].tolist()):
                if q:
                    key = (int(p), int(q))
                    if key not in memo:
                        memo[key] = Fraction(*key)
                    found[r] = memo[key]
        return found, degenerate

    def values(self, problem: Any, teeth: np.ndarray) -> list[Fraction | None]:
        """The efficiency at each row of ``teeth``: :meth:`exact`, or on a boundary of the law's
        pieces (a mesh's relative power exactly zero) the statics of the train built with those
        numbers; None where the relative power itself is undefined (a degenerate train, which
        the statics refuses too) or the statics has none."""
        teeth = np.asarray(teeth, dtype=np.int64).reshape(-1, len(self.args))
        found, degenerate = self._exact(teeth)
        for r, v in enumerate(found):
            if v is None and not degenerate[r]:
                found[r] = _concrete(problem, tuple(int(x) for x in teeth[r]), dict(self.meshes))
        return found


def power_path(problem: Any, train: Any) -> tuple[str, str, tuple[str, ...], tuple]:
    """The searched power path of ``problem`` in ``train``: driver, driven, held links and joined
    pairs (the request's, or its gear state's brakes and clutches)."""
    driver, driven, fixed, state = problem.request
    joined: tuple = ()
    if state is not None:
        st = train.state(state)
        driver, driven, fixed, joined = st.input, st.output, st.brakes, st.clutches
    return driver, driven, tuple(f for f in (fixed or ()) if f is not None), tuple(joined)


def _holds(node: tuple, vals: list[np.ndarray], m: int) -> np.ndarray:
    """Where a condition between pieces holds, at each of ``m`` rows: ``vals`` holds each relation's
    numerator and denominator; a relation holds only where it is defined."""
    kind = node[0]
    if kind == "const":
        return np.full(m, bool(node[1]))
    if kind == "and":
        out = np.ones(m, dtype=bool)
        for a in node[1]:
            out &= _holds(a, vals, m)
        return out
    if kind == "or":
        out = np.zeros(m, dtype=bool)
        for a in node[1]:
            out |= _holds(a, vals, m)
        return out
    if kind == "not":
        return ~_holds(node[1], vals, m)
    p, q = vals[node[1]], vals[node[1] + 1]
    s = np.sign(p).astype(np.int64) * np.sign(q).astype(np.int64)  # 0 where undefined or on the boundary
    defined = q != 0
    return defined & _OPS[node[2]](s, 0)


def _relations(nodes: Sequence[tuple]) -> list[tuple]:
    """Every ('rel', index, op) node of condition trees."""
    out: list[tuple] = []
    for node in nodes:
        if node[0] == "rel":
            out.append(node)
        elif node[0] in ("and", "or"):
            out += _relations(node[1])
        elif node[0] == "not":
            out += _relations([node[1]])
    return out


def _concrete(problem: Any, teeth: tuple[int, ...], mesh_efficiency: Any) -> Fraction | None:
    """The efficiency from the statics of the train with these tooth numbers (a boundary point)."""
    import dataclasses

    from symkin.model import Gear
    from symkin.statics import statics

    values = dict(zip(problem.unknowns, teeth))
    train = problem.train
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", CoaxialityWarning)  # positions do not enter the statics
        links = []
        for L in train.links:
            gears = tuple(Gear.from_teeth(g.name, int(sp.sympify(g.teeth).subs(values)), internal=g.internal,
                                          module=g.module) for g in L.gears)
            links.append(dataclasses.replace(L, gears=gears))
        meshes = tuple(m if m.centre_distance is None else dataclasses.replace(
            m, centre_distance=sp.sympify(m.centre_distance).subs(values)) for m in train.meshes)
        built = dataclasses.replace(train, links=tuple(links), meshes=meshes)
    driver, driven, held, joined = power_path(problem, built)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", CoaxialityWarning)  # positions do not enter the statics
            eta = statics(built, input=driver, output=driven, fixed=held, joined=joined,
                          efficiency=mesh_efficiency).efficiency.rhs
    except SymkinError:  # a degenerate train (locked, or at a pole of the ratio): nothing to rank by
        return None
    return Fraction(int(eta.p), int(eta.q)) if eta.is_Rational else None
