"""How long does a whole transmission take to synthesise, here and on Dask (issue 33)?

    python benchmarks/transmission_synthesis.py [--rounds 3] [--workers 2] [--case widest]

The ready-made eight-speed (ZF 8HP layout) with every tooth number unknown, the 8HP's published
ratio set, three planets per set, in four sizes: the 8HP target (within 0.0005 absolute, z <= 120)
and larger searches (within 0.005, 0.01 and 0.02, z <= 150). Each is run in this process and on a local Dask
cluster of ``--workers`` processes (the pruned search split into chunks of partial designs,
four per worker), each round in a fresh process, the rounds interleaved so that both modes see the same
load. Prints the median wall times side by side (the cluster's start-up apart), the designs
found and the partial designs kept after each state, and asserts that both modes give the same
designs. benchmarks/notes/transmission.md holds a run.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

RATIOS = {"first": "4.696", "second": "3.130", "third": "2.104", "fourth": "1.667", "fifth": "1.285", "sixth": "1",
          "seventh": "0.839", "eighth": "0.667", "reverse": "-3.297"}
#: (name, tolerance, zmax)
CASES = [("8HP target", "0.0005", 120), ("larger", "0.005", 150), ("larger still", "0.01", 150),
         ("widest", "0.02", 150)]


def child(tolerance: str, zmax: int, workers: int) -> None:
    import time
    from fractions import Fraction

    from symkin.synthesis.transmission import synthesize_transmission
    from symkin.trains import load_train

    cluster, startup = None, 0.0
    if workers:
        from symkin.synthesis.runner import local_cluster

        began = time.perf_counter()
        cluster = local_cluster(workers)
        startup = time.perf_counter() - began
    try:
        began = time.perf_counter()
        res = synthesize_transmission(load_train("eight-speed"), {k: Fraction(v) for k, v in RATIOS.items()},
                                      tolerance=Fraction(tolerance), absolute=True, zmax=zmax, top=5,
                                      scheduler=cluster.scheduler_address if cluster else None)
        seconds = time.perf_counter() - began
    finally:
        if cluster is not None:
            cluster.close()
    print(json.dumps({"seconds": seconds, "startup": startup, "found": res.found, "kept": list(res.kept),
                      "order": list(res.order), "where": res.where, "designs": [d.teeth for d in res.designs]}))


def _times(runs: list[dict]) -> str:
    return ", ".join(f"{r['seconds']:.2f}" for r in runs)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--case", action="append", help="run only this case (8HP target, larger, larger still, widest)")
    parser.add_argument("--child", nargs=3, metavar=("TOLERANCE", "ZMAX", "WORKERS"))
    args = parser.parse_args()
    if args.child:
        child(args.child[0], int(args.child[1]), int(args.child[2]))
        return
    for name, tolerance, zmax in CASES:
        if args.case and name not in args.case:
            continue
        runs: dict[int, list[dict]] = {0: [], args.workers: []}
        for _ in range(args.rounds):
            for workers in runs:
                out = subprocess.run([sys.executable, __file__, "--child", tolerance, str(zmax), str(workers)],
                                     capture_output=True, text=True, check=True).stdout
                runs[workers].append(json.loads(out.strip().splitlines()[-1]))
        here, there = runs[0], runs[args.workers]
        assert all(r["designs"] == here[0]["designs"] and r["found"] == here[0]["found"] for r in here + there)
        t_here = statistics.median(r["seconds"] for r in here)
        t_there = statistics.median(r["seconds"] for r in there)
        print(f"{name} (tolerance {tolerance}, z <= {zmax}): {here[0]['found']} designs; kept "
              + ", ".join(f"{s} {n}" for s, n in zip(here[0]["order"], here[0]["kept"])))
        print(f"  this process: median {t_here:.2f} s ({_times(here)})")
        print(f"  Dask, {there[0]['where']}: median {t_there:.2f} s "
              f"({_times(there)}), cluster start-up median "
              f"{statistics.median(r['startup'] for r in there):.2f} s apart; ratio {t_here / t_there:.2f} x")
        print(f"  best {here[0]['designs'][0]}")


if __name__ == "__main__":
    main()
