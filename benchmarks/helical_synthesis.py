"""Helical synthesis: the NumPy sieve against plain enumeration of every tooth set, and the
search time for the README's example.

Run: python benchmarks/helical_synthesis.py [repeats]

1. Same request, two routes, side by side in one run: ``synthesize_helical`` (sieve on Z4, then exact
   checks) and a plain loop over every (Z1, Z2, Z3, Z4) in the limits with the same exact
   checks (``_check_candidate``).  Both must list the same designs; prints medians and the ratio.
2. The README / CLI example (AI, i = 25 +- 2 %, k = 3, m_n 2 / 2.5 mm, Z in [17, 150]):
   median search time (the laws are derived once per process, before timing).
"""

from __future__ import annotations

import itertools
import math
import statistics
import sys
import time
from fractions import Fraction

from symkin.mechanisms.helical import HelicalRequest, synthesize_helical
from symkin.mechanisms.helical.balanced.search import _check_candidate, _compiled

SMALL = dict(scheme="AI", ratio=4, tolerance=Fraction(3, 100), satellites=3, normal_modules=(2, 3), teeth_min=17,
             teeth_max=50, top=None)
EXAMPLE = dict(scheme="AI", ratio=25, tolerance=Fraction(1, 50), satellites=3, normal_modules=(2, Fraction(5, 2)), teeth_max=150,
               top=20)


def plain(req: HelicalRequest) -> set:
    c = _compiled(req.scheme)
    u_min = math.sin(math.radians(req.beta_min_deg)) ** 2
    u_max = math.sin(math.radians(req.beta_max_deg)) ** 2
    counts = dict.fromkeys(("ratio window", "ratio", "helix", "assembly", "neighbour"), 0)
    span = range(req.teeth_min, req.teeth_max + 1)
    found = set()
    for teeth in itertools.product(span, repeat=4):
        if c.internal4 and teeth[3] - teeth[2] < req.min_ring_difference:
            continue
        if c.internal1 and teeth[0] - teeth[1] < req.min_ring_difference:
            continue
        rec = _check_candidate(req, c, teeth, counts, u_min, u_max, math.radians(req.alpha_n_deg))
        if rec is not None:
            found.add(teeth)
    return found


def timed(f, *args):
    start = time.perf_counter()
    out = f(*args)
    return time.perf_counter() - start, out


def main(repeats: int = 5) -> None:
    req = HelicalRequest(**SMALL)
    synthesize_helical(req)  # derive and compile the laws once
    sieve_times, plain_times = [], []
    for _ in range(repeats):
        t, res = timed(synthesize_helical, req)
        sieve_times.append(t)
        t, found = timed(plain, req)
        plain_times.append(t)
        assert found == {d.teeth for d in res.designs}, "the two routes disagree"
    n = (req.teeth_max - req.teeth_min + 1) ** 4
    ms, mp = statistics.median(sieve_times), statistics.median(plain_times)
    print(f"AI, i = 4 +- 3 %, Z in [17, 50] ({n} tooth sets, {len(found)} designs), median of {repeats}:")
    print(f"  sieve + exact checks  {ms:8.3f} s")
    print(f"  plain enumeration     {mp:8.3f} s   ({mp / ms:.0f} x the sieve)")
    example = HelicalRequest(**EXAMPLE)
    first = time.perf_counter()
    import subprocess  # the first search in a fresh process also derives and compiles the laws

    subprocess.run([sys.executable, "-c", "from fractions import Fraction; "
                    "from symkin.mechanisms.helical import synthesize_helical; "
                    f"synthesize_helical(**{EXAMPLE!r})"], check=True)
    first = time.perf_counter() - first
    times = [timed(synthesize_helical, example)[0] for _ in range(repeats)]
    res = synthesize_helical(example)
    print(f"README example, Z in [17, 150] ({(150 - 17 + 1) ** 4:.2e} tooth sets, {res.found} designs): "
          f"median {statistics.median(times):.3f} s (min {min(times):.3f}, max {max(times):.3f}); "
          f"a fresh process (import, derivations, search): {first:.2f} s")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
