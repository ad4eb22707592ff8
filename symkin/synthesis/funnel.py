"""The funnel: the made tuples checked against every condition, vectorised and exactly, and ranked.

In the order of :data:`~symkin.synthesis.plan.STAGES`: the ratio (reduced to a fraction and
compared exactly with the target), internal gears, coaxiality within the profile shift,
assembly (integer rows; shared integers decided by :func:`~symkin.synthesis.integers.solvable`),
neighbours and placement (lengths in scaled integers; an inequality with ``sin(pi/k)`` or a
cosine decided in floating point only outside a relative margin of 1e-9, else at 60 digits).
The designs that pass are ranked in one exact order (:attr:`Record.key`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property
from typing import Any

import numpy as np

from symkin.synthesis.efficiency import DEFAULT_RANK
from symkin.synthesis.integers import solvable
from symkin.synthesis.plan import SearchPlan

__all__ = ["Record", "check_batch"]

#: Relative margin of a float decision; closer calls are decided at 60 digits.
_BAND = 1e-9


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


def check_batch(plan: SearchPlan, batch: tuple, exact_calls: list[int]
                ) -> tuple[int, list[Record], list[int], tuple[float, float]]:
    """Check a batch of made tuples through the funnel: how many pass, the best of them as records, the count
    after each stage (:data:`~symkin.synthesis.plan.STAGES`) and the reachable ratios.  ``exact_calls[0]``
    counts the decisions taken exactly (an integer system, a float too near its margin)."""
    (cols,) = batch
    b = _Batch(plan, cols)
    ratios = _ratios(plan, b)
    ok = ratios.ok
    counts = [int(ok.sum())]
    for stage in (_internal_gears, _coaxiality, _assembly, _neighbours, _placement):
        stage(plan, b, ok, exact_calls)  # each narrows ok in place
        counts.append(int(ok.sum()))
    found = int(ok.sum())
    if not found:
        return 0, [], counts, ratios.reach
    return found, _ranked(plan, b, ok, ratios), counts, ratios.reach


class _Batch:
    """A batch of made tuples (tooth numbers ``Z``, slacks ``sig``) and the candidate function's outputs on it."""

    def __init__(self, plan: SearchPlan, cols: dict[str, np.ndarray]) -> None:
        self.plan = plan
        self.Z = np.stack([cols[u] for u in plan.unknowns], axis=1)
        self.sig = (np.stack([cols[s] for s in plan.slack_names], axis=1) if plan.slack_names
                    else np.zeros((len(self.Z), 0), np.int64))
        args = ([self.Z[:, i].astype(float) for i in range(self.Z.shape[1])]
                + [self.sig[:, i].astype(float) for i in range(self.sig.shape[1])])
        out = plan.f_cand(*args)
        out = list(out) if isinstance(out, tuple) else [out]
        self.m = len(self.Z)
        self.vals = [np.broadcast_to(np.asarray(v, dtype=float), (self.m,)) for v in out]

    def ints(self, i: int) -> np.ndarray:
        """Output ``i`` as integers (exact: the plan keeps every integer output below 2^53)."""
        return np.rint(self.vals[i]).astype(np.int64)

    @cached_property
    def arms(self) -> list[np.ndarray]:
        """Each planet's working arm times the length scale."""
        return _arms(self.plan, self.ints, self.m)


@dataclass
class _Ratios:
    """The ratios of a batch, reduced fractions compared exactly: which tuples have one in the window, the
    index of each tuple's fraction among the distinct ones, their errors and error levels (equal errors
    rank equal: a range, or +-x about the target), and the least and largest ratio met."""

    ok: np.ndarray
    which: np.ndarray
    fractions: list[Fraction]
    errors: list[Fraction]
    levels: np.ndarray
    reach: tuple[float, float]


def _ratios(plan: SearchPlan, b: _Batch) -> _Ratios:
    m = b.m
    lay = plan.cand_layout
    N, D = b.ints(lay["ratio"][0]), b.ints(lay["ratio"][1])
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
    return _Ratios(ok, which, fr, errors, rank, reach)


def _internal_gears(plan: SearchPlan, b: _Batch, ok: np.ndarray, exact_calls: list[int]) -> None:
    for ii, ie in plan.internal_pairs:
        ok &= b.ints(ii) - b.ints(ie) >= plan.problem.options.ring_difference


def _coaxiality(plan: SearchPlan, b: _Batch, ok: np.ndarray, exact_calls: list[int]) -> None:
    """Within the profile shift: the pairs of meshes the dependents do not cover."""
    for i, w in zip(plan.cand_layout["filters"], plan.filter_bounds):
        ok &= np.abs(b.ints(i)) <= w


def _assembly(plan: SearchPlan, b: _Batch, ok: np.ndarray, exact_calls: list[int]) -> None:
    for group in plan.assembly:
        system_rows = []
        for kind, g_idx, r_idx, modulus, _names in group:
            R = b.ints(r_idx)
            if kind == "integral":
                ok &= R % modulus == 0
            elif kind == "divisible":
                gg = np.zeros(b.m, dtype=np.int64)
                for gi in g_idx:
                    gg = np.gcd(gg, b.ints(gi))
                ok &= np.where(gg == 0, R == 0, R % (modulus * np.where(gg == 0, 1, gg)) == 0)
            elif kind == "zero":
                ok &= R == 0
            else:
                system_rows.append((g_idx, r_idx, modulus, _names))
        if system_rows:
            for i in np.flatnonzero(ok):
                exact_calls[0] += 1
                if not _system_ok(system_rows, b.ints, int(i)):
                    ok[i] = False


def _neighbours(plan: SearchPlan, b: _Batch, ok: np.ndarray, exact_calls: list[int]) -> None:
    """Copies of one planet kind clear each other."""
    arms = b.arms
    for planet_i, tip, clear in plan.geometry.rims:
        kk = plan.k[plan.planets[planet_i]]
        if kk < 2:
            continue
        const = -(2 * b.ints(tip) + clear)
        slope = 2 * arms[planet_i]
        ok &= _sign_sin(plan, const, slope, kk, ok, exact_calls) > 0


def _placement(plan: SearchPlan, b: _Batch, ok: np.ndarray, exact_calls: list[int]) -> None:
    """Meshing planets: placed, and clear of the copies they do not mesh."""
    arms = b.arms
    for pa, pb, di, ta, tb, clear in plan.geometry.pairs:
        a, c, dd = arms[pa], arms[pb], b.ints(di)
        ok &= ((a - c) ** 2 <= dd**2) & (dd**2 <= (a + c) ** 2)
        kk = plan.k[plan.planets[pa]]
        if kk < 2:
            continue
        span = b.ints(ta) + b.ints(tb) + clear
        for t in range(1, kk):
            ok &= _cross_clear(plan, a, c, dd, span, t, kk, ok, exact_calls)


def _ranked(plan: SearchPlan, b: _Batch, ok: np.ndarray, ratios: _Ratios) -> list[Record]:
    """The best of the batch's designs, in the exact order of the plan's rank."""
    Z, arms = b.Z, b.arms
    sel = np.flatnonzero(ok)
    size = np.zeros(b.m, dtype=np.int64)
    for i in plan.geometry.central:
        size = np.maximum(size, b.ints(i))
    for pi, tips in enumerate(plan.geometry.planet_tips):
        for ti in tips:
            size = np.maximum(size, arms[pi] + b.ints(ti))
    size = 2 * size
    tsum = Z.sum(axis=1)
    which = ratios.which
    columns = {"error": ratios.levels[which[sel]], "size": size[sel], "teeth": tsum[sel]}
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
    return [Record(ratios.errors[which[i]], int(size[i]), tuple(int(v) for v in Z[i]), tuple(int(v) for v in b.sig[i]),
                   ratios.fractions[which[i]], eta[j], plan.rank) for j, i in zip(order.tolist(), sel[order].tolist())]


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
