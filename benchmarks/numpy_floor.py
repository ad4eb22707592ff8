"""How fast can NumPy keep the near-pole guarantee?  The II differential in radii,
omega_H = omega_4 + (omega_1 - omega_4) r1 r3/(r1 r3 - r2 r4), three ways, side by side
in one run (methods in turn, medians of 7 rounds, as ratios to sympy.lambdify):

- ``sympy.lambdify``: no check;
- ``symkin numpy``: ``symkin.compile(law, backend="numpy")``;
- ``hand floor``: the least NumPy work that still certifies the difference r1 r3 - r2 r4
  (products, difference, g = r1 r3/difference, its minimum and maximum, one finiteness
  pass; the law rewritten as omega_4 + (omega_1 - omega_4) g, in place).  No implementation
  of the guarantee in NumPy can do less than this; it is the floor issue 18 item 1 meets
  with NumPy.

Run: ``python benchmarks/numpy_floor.py`` (about 20 s).  Results in
benchmarks/notes/numpy_floor.md.
"""

from __future__ import annotations

import os
import statistics
import sys

import numpy as np
import sympy as sp

sys.path.insert(0, os.path.dirname(__file__))
import run as R

import symkin


def hand_floor(w1, w4, r1, r2, r3, r4):
    with np.errstate(all="ignore"):
        p = r1 * r3
        diff = p - r2 * r4
        g = p / diff
        certified = np.minimum.reduce(g) >= -0.499 and np.maximum.reduce(g) <= 1.499  # noqa: F841 (the check's cost)
        out = (w1 - w4) * g
        out += w4
        finite = np.isfinite(np.add.reduce(out))  # noqa: F841
    return out


def main() -> None:
    case = R.cases(10**6)["differential omega_H (II, radii)"]
    methods = {
        "sympy.lambdify": sp.lambdify(case["args"], case["expr"], "numpy"),
        "symkin numpy": symkin.compile(case["expr"], case["args"], backend="numpy"),
        "hand floor": hand_floor,
    }
    print(f"load {os.getloadavg()[0]:.2f}")
    for n in (10**3, 10**5, 10**6):
        values = [np.ascontiguousarray(v[:n]) for v in case["values"]]
        samples: dict[str, list[float]] = {k: [] for k in methods}
        for _ in range(7):
            for name, fn in methods.items():
                samples[name].append(R.timed(fn, values, n))
        lam = statistics.median(samples["sympy.lambdify"])
        print(f"{n:>8d} points: lambdify {lam * 1e6:.1f} us; "
              + ", ".join(f"{k} {statistics.median(v) / lam:.2f}" for k, v in samples.items()))
    print(f"load {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
