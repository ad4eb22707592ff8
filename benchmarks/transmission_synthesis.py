"""How long does a whole transmission take to synthesise (issue 33)?

    python benchmarks/transmission_synthesis.py [--rounds 3] [--zmax 120]

The ready-made eight-speed (ZF 8HP layout) with every tooth number unknown, the 8HP's published
ratio set within 0.0005 (absolute), three planets per set; each round in a fresh process. Prints the
median wall time, the designs found and the partial designs kept after each state.
benchmarks/notes/transmission.md holds a run.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys

RATIOS = {"first": "4.696", "second": "3.130", "third": "2.104", "fourth": "1.667", "fifth": "1.285", "sixth": "1",
          "seventh": "0.839", "eighth": "0.667", "reverse": "-3.297"}


def child(zmax: int) -> None:
    import time
    from fractions import Fraction

    from symkin.synthesis.transmission import synthesize_transmission
    from symkin.trains import load_train

    began = time.perf_counter()
    res = synthesize_transmission(load_train("eight-speed"), {k: Fraction(v) for k, v in RATIOS.items()},
                                  tolerance=Fraction(5, 10000), absolute=True, zmax=zmax, top=5)
    print(json.dumps({"seconds": time.perf_counter() - began, "found": res.found, "kept": list(res.kept),
                      "order": list(res.order), "best": res.designs[0].teeth}))


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--zmax", type=int, default=120)
    parser.add_argument("--child", action="store_true")
    args = parser.parse_args()
    if args.child:
        child(args.zmax)
        return
    runs = []
    for _ in range(args.rounds):
        out = subprocess.run([sys.executable, __file__, "--child", "--zmax", str(args.zmax)], capture_output=True,
                             text=True, check=True).stdout
        runs.append(json.loads(out.strip().splitlines()[-1]))
    times = ", ".join(f"{r['seconds']:.2f}" for r in runs)
    print(f"median {statistics.median(r['seconds'] for r in runs):.2f} s over {args.rounds} rounds "
          f"({times}); {runs[0]['found']} designs; kept "
          + ", ".join(f"{s} {n}" for s, n in zip(runs[0]["order"], runs[0]["kept"])) + f"; best {runs[0]['best']}")


if __name__ == "__main__":
    main()
