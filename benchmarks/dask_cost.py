"""What a local Dask cluster costs before it saves anything, and when scheduler="auto" takes one.

    python benchmarks/dask_cost.py [repeats]

The Ravigneaux request of benchmarks/synthesis.py (zmax 150): the search here, the search on a
local cluster of 2 workers counted from before the cluster starts (what ``scheduler="local"``
costs a user), and ``scheduler="auto"`` (which times the first chunk here and starts the
cluster only where :func:`symkin.synthesis.runner.cluster_pays`).  The cluster's start-up is
timed on its own too: with the search's set-up on the workers it is the basis of
``LOCAL_CLUSTER_COST``.  Runs interleaved, wall time (a cluster is processes), medians.
"""

from __future__ import annotations

import os
import statistics
import sys
import time
from fractions import Fraction

from symkin.synthesis import synthesize
from symkin.synthesis.runner import LOCAL_CLUSTER_COST, cluster_pays, local_cluster

REQUEST = dict(driver="S1", driven="R", fixed="C", ratio=Fraction(12, 5), tolerance=Fraction(1, 200), planets=3,
               zmax=150, top=None, time_limit=600)


def main() -> None:
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    load = os.getloadavg()[0]
    synthesize("ravigneaux", **REQUEST)  # derive and compile once (cached for the runs below)
    times: dict[str, list[float]] = {"here": [], "local cluster (2), with its start": [], "auto": [], "cluster start alone": []}
    found = set()
    for _ in range(repeats):
        t = time.perf_counter()
        found.add(synthesize("ravigneaux", **REQUEST).found)
        times["here"].append(time.perf_counter() - t)
        t = time.perf_counter()
        found.add(synthesize("ravigneaux", scheduler="local", workers=2, **REQUEST).found)
        times["local cluster (2), with its start"].append(time.perf_counter() - t)
        t = time.perf_counter()
        found.add(synthesize("ravigneaux", scheduler="auto", workers=2, **REQUEST).found)
        times["auto"].append(time.perf_counter() - t)
        t = time.perf_counter()
        local_cluster(2).close()
        times["cluster start alone"].append(time.perf_counter() - t)
    assert len(found) == 1, found
    here = statistics.median(times["here"])
    print(f"load {load:.1f} -> {os.getloadavg()[0]:.1f}; medians of {repeats}, wall s; ratio to here")
    for name, xs in times.items():
        print(f"{name:36s} {statistics.median(xs):7.2f} s  x{statistics.median(xs) / here:.2f}")
    print(f"LOCAL_CLUSTER_COST = {LOCAL_CLUSTER_COST} s: a cluster of 2 pays from {2 * LOCAL_CLUSTER_COST:.0f} s of search here; "
          f"this search ({here:.1f} s): {'pays' if cluster_pays(here, 2) else 'does not pay'}")


if __name__ == "__main__":
    main()
