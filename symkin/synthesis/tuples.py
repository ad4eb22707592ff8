"""Making the tuples of a chunk: only those with the ratio in the window.

For each outer tuple the dependents' parts and the ratio's coefficients come from the plan's
outer function; the ratio window ``lo <= (a x + b)/(c x + d) <= hi`` is solved for ``x`` in
closed form (at most two intervals, :func:`_window`), intersected with the limits of ``x``
and of every dependent, and every ``x`` left is made (:func:`make_tuples`).
"""

from __future__ import annotations

import math

import numpy as np

from symkin.synthesis.plan import SearchPlan

__all__ = ["make_tuples"]

#: Tuples made at once inside a chunk (memory).
_BATCH = 1 << 20


def make_tuples(plan: SearchPlan, outer: list[np.ndarray], n: int) -> tuple[list[tuple], float, float]:
    """The tuples (unknowns, slacks) with the ratio in the window, in batches; and the reachable ratios.

    ``outer`` holds the ``n`` outer tuples of a chunk, a column per outer tooth number and slack.
    """
    n_out = len(plan.outer)
    zcols = {name: outer[i] for i, name in enumerate(plan.outer)}
    scols = {name: outer[n_out + i] for i, name in enumerate(plan.slack_names)}
    vals: list[np.ndarray] = []
    if plan.f_outer is not None:
        out = plan.f_outer(*[np.asarray(c, dtype=float) for c in outer])
        vals = list(out) if isinstance(out, tuple) else [out]
        vals = [np.broadcast_to(np.asarray(v, dtype=float), (n,)) for v in vals]
    dep_parts = [vals[i] for i in plan.outer_layout["dependents"]]
    keep, lo_x, hi_x = _dependent_bounds(plan, dep_parts, n)
    if plan.last is None:
        idx = np.flatnonzero(keep)
        cols = _columns(plan, zcols, scols, idx, None, dep_parts)
        return _batches(cols), math.inf, -math.inf
    a, b, c, d = (vals[i] for i in plan.outer_layout["abcd"])
    eps = 1e-7
    L = np.ceil(lo_x - eps)
    U = np.floor(hi_x + eps)
    keep &= L <= U
    reach_lo, reach_hi = _reach(a, b, c, d, L, U, keep)
    lo, hi = float(plan.target.lo), float(plan.target.hi)
    pieces = []
    for wl, wh in _window(a - lo * c, b - lo * d, a - hi * c, b - hi * d):
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
    made = _expand(pieces, keep, n)
    if made is None:
        return [], reach_lo, reach_hi
    owner, x = made
    cols = _columns(plan, zcols, scols, owner, x, dep_parts)
    return _batches(cols), reach_lo, reach_hi


def _dependent_bounds(plan: SearchPlan, dep_parts: list[np.ndarray], n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Which outer tuples keep their dependents that do not involve ``x`` integral and within limits, and
    the range of ``x`` that keeps the others within theirs."""
    keep = np.ones(n, dtype=bool)
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
    return keep, lo_x, hi_x


def _reach(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray, L: np.ndarray, U: np.ndarray,
           keep: np.ndarray) -> tuple[float, float]:
    """The least and largest ratio ``(a x + b)/(c x + d)`` over ``L <= x <= U``: at the ends of ``x``'s
    range, and either side of a pole."""
    reach_lo, reach_hi = math.inf, -math.inf
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
    return reach_lo, reach_hi


def _expand(pieces: list[tuple[np.ndarray, np.ndarray]], keep: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray] | None:
    """Every ``x`` of each kept outer tuple's pieces ``start..stop``: the tuple's index and ``x``, or None."""
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
        return None
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


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
