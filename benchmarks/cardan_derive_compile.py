"""Time to derive and compile the Cardan slider laws (s, v, a, pin x, y) and evaluate 1000 times.

Run: python benchmarks/cardan_derive_compile.py [repeats]
Each repeat builds a fresh CardanSlider (laws derived anew; the line conditions are derived once
per process and cached) and evaluates it; prints the median and the spread per drive, and the
first-call cost in this process (including the derivation of the line conditions).
"""

from __future__ import annotations

import statistics
import sys
import time

import numpy as np
import sympy as sp

from symkin.drives import ConstantSpeed, EllipticalGears
from symkin.mechanisms.cardan import CardanSlider, line_conditions

OMEGA = sp.Rational(4, 5) * sp.pi
DRIVES = {
    "constant": lambda: ConstantSpeed(OMEGA),
    "elliptical e=2/5 m=2": lambda: EllipticalGears(OMEGA, sp.Rational(2, 5), 2),
}


def once(make_drive) -> float:
    start = time.perf_counter()
    slider = CardanSlider.build(sp.Rational(1, 50), drive=make_drive(), carrier_angle=sp.pi / 6)
    slider.evaluate(np.linspace(0.0, 2.5, 1000))
    return time.perf_counter() - start


def main(repeats: int = 15) -> None:
    start = time.perf_counter()
    line_conditions()
    print(f"line conditions (once per process): {time.perf_counter() - start:.3f} s")
    for name, make in DRIVES.items():
        times = [once(make) for _ in range(repeats)]
        print(f"{name:22s} derive + compile + 1000 points: median {statistics.median(times):.3f} s "
              f"(min {min(times):.3f}, max {max(times):.3f}, n = {repeats})")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 15)
