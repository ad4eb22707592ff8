"""The search: integer tooth sets and balancing helix angles for a target ratio.

A NumPy sieve bounds Z4 for each (Z1, Z2, Z3) from the ratio window and the helix
limits; every survivor is then checked exactly (integers, Fractions).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from typing import Any

import numpy as np
import sympy as sp

from symkin._util.budget import seconds_limit
from symkin.errors import InputError, TimeLimitError
from symkin.mechanisms.helical import SCHEME_MESHES, HelicalTrain
from symkin.mechanisms.helical.balanced.conditions import (
    M12,
    M34,
    MU,
    NU,
    RATIO,
    SCHEMES,
    U34,
    Z,
    assembly_integers,
    coaxial_cosine_ratio,
    helix_angle_solution,
    ratio_function,
    ratio_law,
)
from symkin.mechanisms.helical.balanced.regions import _as_float, existence_range
from symkin.mechanisms.helical.balanced.request import (
    HelicalDesign,
    HelicalRequest,
    HelicalResult,
)
from symkin.numeric import compile

__all__ = ["synthesize_helical"]


@dataclass(frozen=True)
class _Compiled:
    """Derived laws compiled for the search (NumPy for the sieve, Fractions for exact checks)."""

    ratio: Callable[..., Fraction]
    z4_of_ratio: Callable[..., Any]
    z4_of_nu: Callable[..., Any]
    mu: Callable[..., Any]
    nu: Callable[..., Any]
    sin2_34: Callable[..., Any]
    nu2_of_sin2_34: Callable[..., Any]
    internal1: bool
    internal4: bool


#: Points of the largest tooth plane the sieve evaluates in one call.
_PLANE = 1 << 22


@cache
def _compiled(scheme: str) -> _Compiled:
    z1, z2, z3, z4 = (Z[n] for n in (1, 2, 3, 4))
    law = ratio_law(scheme).rhs
    (z4_of_ratio,) = sp.solve(sp.Eq(law, RATIO), z4)
    nu = coaxial_cosine_ratio(scheme)
    (z4_of_nu,) = sp.solve(sp.Eq(nu, NU), z4)
    sol = helix_angle_solution()
    in1, in4 = SCHEME_MESHES[scheme]
    # the sieve's laws (backend="numpy", stable=False, on_pole="return", chunk=_PLANE): their bounds are inf or nan where a
    # tooth set makes a denominator vanish, and the sieve compares them itself and discards
    # such sets; one call per tooth plane (chunk=_PLANE), whose inputs broadcast a column
    # against a row, is cheaper than chunks of copies; the checks are exact
    return _Compiled(
        ratio=ratio_function(scheme),
        z4_of_ratio=compile(z4_of_ratio, [RATIO, z1, z2, z3], backend="numpy", stable=False, on_pole="return", chunk=_PLANE),
        z4_of_nu=compile(z4_of_nu, [NU, M12, M34, z1, z2, z3], backend="numpy", stable=False, on_pole="return", chunk=_PLANE),
        mu=compile(sol.mu, [M12, M34, z2, z3], backend="exact"),
        nu=compile(nu, [M12, M34, z1, z2, z3, z4], backend="exact"),
        sin2_34=compile(sol.sin2_34, [MU, NU], backend="exact"),
        nu2_of_sin2_34=compile(sol.nu2_of_sin2_34, [MU, U34], backend="numpy", stable=False, on_pole="return", chunk=_PLANE),
        internal1=in1,
        internal4=in4,
    )


def _nearest_region(scheme: str, ratio: Fraction) -> str:
    spans = existence_range(scheme)
    text = " or ".join(f"{lo} < i < {hi}" for lo, hi in spans)
    best = None
    for lo, hi in spans:
        for end in (lo, hi):
            if end.is_finite:
                d = abs(float(end) - float(ratio))
                if best is None or d < best[0]:
                    best = (d, end)
    assert best is not None  # the ratio lies in no region, so no region is (-oo, oo): some end is finite
    others = [s for s in SCHEMES if s != scheme and any(_as_float(lo) < float(ratio) < _as_float(hi) for lo, hi in existence_range(s))]
    where = f"; scheme{'s' if len(others) > 1 else ''} {' and '.join(others)} realise{'s' if len(others) == 1 else ''} it" if others else ""
    return (
        f"the target ratio i_1H^(4) = {ratio} lies in no existence region of scheme {scheme} ({text}); "
        f"the nearest is its end i = {best[1]}{where}"
    )


def synthesize_helical(request: HelicalRequest | None = None, *, progress: Callable[[int, int], None] | None = None,
                       time_limit: float | None = None, **kwargs: Any) -> HelicalResult:
    """Integer tooth sets and balancing helix angles for a target ratio.

    For every tooth set with Z in [teeth_min, teeth_max]: the ratio must lie within the
    tolerance; both meshes unshifted, the helix angles are those that cancel the planet's
    axial forces (equal leads) and make the two centre distances equal
    (:func:`helix_angle_solution`), and both must lie within the limits; the set must be
    assemblable with k satellites (:func:`assembly_integers`); neighbouring planets' tip
    circles must clear (``2 a_w sin(pi/k) > max(d_a2, d_a3)``); internal gears must have
    at least ``min_ring_difference`` more teeth than their rims.  Designs are ranked by
    ratio error, then by envelope diameter.

    A NumPy sieve bounds Z4 for each (Z1, Z2, Z3) from the ratio window and the helix
    limits (each bound is monotone in the parameter it comes from); every survivor is then
    checked exactly (integers, Fractions).

    Parameters
    ----------
    request : HelicalRequest, optional
        Or give its fields as keyword arguments.
    progress : callable(done, total), optional
        Called after each value of Z2.
    time_limit : float, optional
        Seconds; a longer search raises :class:`~symkin.errors.TimeLimitError` (checked after each
        value of Z2).

    Returns
    -------
    HelicalResult
        A :class:`~symkin.synthesis.searches.SearchResult`: the designs, and the reason when
        there are none.

    Raises
    ------
    InputError
        Bad input, or a target ratio in no existence region of the scheme.

    Examples
    --------
    >>> res = synthesize_helical(scheme="AI", ratio=12, tolerance=0.01, satellites=3, normal_modules=(2, 2.5),
    ...                  teeth_min=17, teeth_max=80, top=3)
    >>> res.found, res.designs[0].teeth, [round(b, 3) for b in res.designs[0].betas_deg]
    (14, (17, 51, 21, 77), [15.905, 8.109])
    """
    if request is None:
        request = HelicalRequest(**kwargs)
    elif kwargs:
        raise InputError("give either a HelicalRequest or its fields, not both")
    limit = seconds_limit(time_limit)
    start = time.perf_counter()
    req = request
    if not any(_as_float(lo) < float(req.ratio) < _as_float(hi) for lo, hi in existence_range(req.scheme)):
        raise InputError(_nearest_region(req.scheme, req.ratio))
    sieve = _Sieve.of(req)
    # "ratio window" is counted by the sieve; the others by the exact checks
    counts = dict.fromkeys(("ratio window", "ratio", "helix", "assembly", "neighbour"), 0)
    records: list[tuple] = []
    total = len(sieve.teeth)
    for n2, z2 in enumerate(sieve.teeth):
        for teeth in sieve.plane(z2, counts):
            rec = _check_candidate(req, sieve.c, teeth, counts, sieve.u_min, sieve.u_max, sieve.alpha_n)
            if rec is not None:
                records.append(rec)
        if progress is not None:
            progress(n2 + 1, total)
        elapsed = time.perf_counter() - start
        if limit is not None and n2 + 1 < total and elapsed > limit:
            raise TimeLimitError(f"the search over Z2 in [{req.teeth_min}, {req.teeth_max}] did {n2 + 1} of {total} "
                                 f"values in {elapsed:.1f} s, more than the time limit of {limit:g} s; narrow the "
                                 "tooth limits or raise the time limit")
    return _result(req, sieve, records, counts, time.perf_counter() - start)


@dataclass(frozen=True)
class _Sieve:
    """A request's laws and limits as the sieve uses them, in floats (the checks are exact)."""

    c: _Compiled
    teeth: np.ndarray
    bounds: tuple[float, float, float, float, float, float]  # i_lo, i_hi, m12, m34, sin beta_min, sin beta_max
    u_min: float
    u_max: float
    alpha_n: float
    ring_difference: int

    @classmethod
    def of(cls, req: HelicalRequest) -> _Sieve:
        i_lo, i_hi = req.ratio_window
        m12, m34 = req.normal_modules
        s_min, s_max = math.sin(math.radians(req.beta_min_deg)), math.sin(math.radians(req.beta_max_deg))
        return cls(_compiled(req.scheme), np.arange(req.teeth_min, req.teeth_max + 1, dtype=float),
                   (float(i_lo), float(i_hi), float(m12), float(m34), s_min, s_max), s_min**2, s_max**2,
                   math.radians(req.alpha_n_deg), req.min_ring_difference)

    def plane(self, z2: float, counts: dict[str, int]) -> Iterator[tuple[int, int, int, int]]:
        """The tooth sets with this Z2 whose Z4 the ratio window and the helix limits leave (each bound is
        monotone in the parameter it comes from), counting those in the ratio window."""
        c, teeth, dmin = self.c, self.teeth, self.ring_difference
        i_lo, i_hi, m12f, m34f, s_min, s_max = self.bounds
        zmin, zmax = teeth[0], teeth[-1]
        z1c, z3r = teeth[:, None], teeth[None, :]
        eps = 1e-9
        col_ok = z1c >= z2 + dmin if c.internal1 else np.ones_like(z1c, dtype=bool)
        # Z4 from the ratio window (linear in i)
        with np.errstate(divide="ignore", invalid="ignore"):
            za, zb = c.z4_of_ratio(i_lo, z1c, z2, z3r), c.z4_of_ratio(i_hi, z1c, z2, z3r)
        r_lo, r_hi = np.minimum(za, zb), np.maximum(za, zb)
        floor4 = np.maximum(zmin, z3r + dmin) if c.internal4 else np.full_like(z3r, zmin)
        lo_r = np.ceil(np.maximum(r_lo * (1 - eps) - eps, floor4))
        hi_r = np.floor(np.minimum(r_hi * (1 + eps) + eps, zmax))
        in_window = col_ok & (lo_r <= hi_r)
        counts["ratio window"] += int(np.where(in_window, hi_r - lo_r + 1, 0).sum())
        # helix limits -> sin(beta34) interval -> nu interval -> Z4 interval
        mu = m12f * z2 / (m34f * z3r)
        s_lo, s_hi = np.maximum(s_min, s_min / mu), np.minimum(s_max, s_max / mu)
        row_ok = s_lo <= s_hi * (1 + eps)
        with np.errstate(divide="ignore", invalid="ignore"):
            nu2a, nu2b = c.nu2_of_sin2_34(mu, s_lo**2), c.nu2_of_sin2_34(mu, s_hi**2)
            nu_lo, nu_hi = np.sqrt(np.minimum(nu2a, nu2b)), np.sqrt(np.maximum(nu2a, nu2b))
            ya, yb = c.z4_of_nu(nu_lo, m12f, m34f, z1c, z2, z3r), c.z4_of_nu(nu_hi, m12f, m34f, z1c, z2, z3r)
        h_lo, h_hi = np.minimum(ya, yb), np.maximum(ya, yb)
        lo4 = np.maximum(lo_r, np.ceil(h_lo * (1 - eps) - eps))
        hi4 = np.minimum(hi_r, np.floor(h_hi * (1 + eps) + eps))
        cand = in_window & row_ok & (lo4 <= hi4)
        z2i = int(z2)
        for a, b in zip(*np.nonzero(cand)):
            z1i, z3i = int(teeth[a]), int(teeth[b])
            for z4i in range(int(lo4[a, b]), int(hi4[a, b]) + 1):
                yield z1i, z2i, z3i, z4i


def _result(req: HelicalRequest, sieve: _Sieve, records: list[tuple], counts: dict[str, int],
            seconds: float) -> HelicalResult:
    """The designs ranked by ratio error, then envelope diameter, and how many tooth sets passed each condition."""
    records.sort(key=lambda r: (r[0], r[1], r[2]))
    listed = records if req.top is None else records[: req.top]
    designs = tuple(_design(req, r, sieve.alpha_n) for r in listed)
    c = sieve.c
    ring = f" (internal gears >= {sieve.ring_difference} teeth more than their rims)" if c.internal1 or c.internal4 else ""
    stages = (
        ("ratio within tolerance" + ring, counts["ratio window"]),
        ("and balancing coaxial helix angles within limits", counts["helix"]),
        (f"and assembly with k = {req.satellites} satellites", counts["assembly"]),
        ("and neighbouring planets clear", counts["neighbour"]),
    )
    reason = "" if records else _empty_reason(req, counts)
    return HelicalResult(req, designs, len(records), stages, reason, seconds)


def _check_candidate(req: HelicalRequest, c: _Compiled, teeth: tuple[int, int, int, int], counts: dict[str, int],
                     u_min: float, u_max: float, alpha_n: float) -> tuple | None:
    z1, z2, z3, z4 = teeth
    ratio = c.ratio(z1, z2, z3, z4)
    error = abs(ratio - req.ratio) / abs(req.ratio)
    if error > req.tolerance:
        return None
    counts["ratio"] += 1
    m12, m34 = req.normal_modules
    F = Fraction
    mu = F(c.mu(m12, m34, F(z2), F(z3)))
    nu = F(c.nu(m12, m34, F(z1), F(z2), F(z3), F(z4)))
    free = False
    if mu == 1 and nu == 1:  # equal leads and centre distances at any common helix angle
        u, free = F(repr(u_min)), True
    elif mu == nu or nu <= 0:
        return None
    else:
        u = F(c.sin2_34(mu, nu))
    v = mu * mu * u
    if not (0 < u < 1 and 0 < v < 1):
        return None
    uf, vf = float(u), float(v)
    if not (u_min <= uf <= u_max and u_min <= vf <= u_max):
        return None
    counts["helix"] += 1
    pq = assembly_integers(req.scheme, teeth, req.satellites)
    if pq is None:
        return None
    counts["assembly"] += 1
    b12, b34 = math.asin(math.sqrt(vf)), math.asin(math.sqrt(uf))
    train = HelicalTrain(req.scheme, teeth, req.normal_modules, (b12, b34), satellites=req.satellites,
                         alpha_n=alpha_n, addendum=float(req.addendum))
    if not train.neighbour_margin > 0:
        return None
    counts["neighbour"] += 1
    return (error, train.envelope_diameter, teeth, b12, b34, pq, ratio, free)


def _design(req: HelicalRequest, rec: tuple, alpha_n: float) -> HelicalDesign:
    error, _, teeth, b12, b34, pq, ratio, free = rec
    train = HelicalTrain(req.scheme, teeth, req.normal_modules, (b12, b34), satellites=req.satellites,
                         alpha_n=alpha_n, addendum=float(req.addendum))
    return HelicalDesign(train, ratio, error, pq, free)


def _empty_reason(req: HelicalRequest, counts: Mapping[str, int]) -> str:
    lo, hi = req.ratio_window
    if counts["ratio window"] == 0:
        return (
            f"no tooth set with every Z in [{req.teeth_min}, {req.teeth_max}] gives i_1H^(4) in [{lo}, {hi}] "
            f"for scheme {req.scheme}; widen the tolerance or the tooth limits"
        )
    if counts["helix"] == 0:
        return (
            f"{counts['ratio window']} tooth sets give the ratio, but for none are the helix angles that balance the axial "
            f"forces and make unshifted meshes coaxial within [{float(req.beta_min_deg):g}, {float(req.beta_max_deg):g}] "
            f"degrees with m_n12 = {req.normal_modules[0]}, m_n34 = {req.normal_modules[1]}; widen the helix-angle "
            "limits or change the module ratio"
        )
    if counts["assembly"] == 0:
        return (
            f"{counts['helix']} tooth sets have the ratio and balancing coaxial helix angles, but none can be "
            f"assembled with k = {req.satellites} equally spaced satellites; try another k"
        )
    return (
        f"{counts['assembly']} tooth sets have the ratio, balancing helix angles and assemble, but in none do "
        f"{req.satellites} planets fit side by side (neighbour condition); use fewer satellites or other limits"
    )
