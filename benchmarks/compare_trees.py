"""symkin at a git ref and this tree in one process, the same calls interleaved: per-call time ratios.

    python benchmarks/compare_trees.py --before REF [--rounds 15] [--backends numpy,numba] [--sizes 1,1000,100000]

The ref's ``symkin/`` (``git archive``) is unpacked into a temporary folder as the package
``symkin_before`` (every ``symkin`` module name in its source rewritten), so that both trees
compile the same laws (benchmarks/laws.py, ``timed_cases``) and run in one process on the same
inputs.  Each round times the best of 3 loops of each tree, in alternating order; a cell is the
median over rounds of after / before, with the smallest and largest: a busy machine slows both
sides of a round alike, which separate processes do not (benchmarks/default_path.py compares
trees that way, and times a numba kernel's compilation in fresh processes).
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def unpack(ref: str, folder: Path) -> None:
    """``symkin/`` at ``ref`` as the package ``symkin_before`` in ``folder``."""
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", ref, "symkin"], capture_output=True, check=True).stdout
    subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    package = folder / "symkin_before"
    (folder / "symkin").rename(package)
    for path in package.rglob("*.py"):  # symkin.x, from symkin import, import symkin (the kernel template's text too)
        text = path.read_text()
        path.write_text(re.sub(r"\bsymkin\b(?=\.\w|\s+import\b)|(?<=import )symkin\b", "symkin_before", text))


def best(fn, loops: int) -> float:
    out = []
    for _ in range(3):
        t0 = time.perf_counter()
        for _ in range(loops):
            fn()
        out.append((time.perf_counter() - t0) / loops)
    return min(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", required=True, help="git ref of the tree to compare with")
    ap.add_argument("--rounds", type=int, default=15)
    ap.add_argument("--backends", default="numpy,numba")
    ap.add_argument("--sizes", default="1,1000,100000")
    opts = ap.parse_args()
    sizes = [int(s) for s in opts.sizes.split(",")]
    os.environ.setdefault("SYMKIN_CACHE_DIR", tempfile.mkdtemp(prefix="symkin-compare-kernels-"))
    folder = Path(tempfile.mkdtemp(prefix="symkin-before-"))
    unpack(opts.before, folder)
    sys.path[:0] = [str(folder), str(HERE)]
    import laws as L
    import numpy as np
    import symkin_before  # type: ignore[import-not-found]

    import symkin

    print(f"before = {opts.before}, after = this tree; 1-minute load {os.getloadavg()[0]:.1f}; {opts.rounds} rounds")
    print("| law | backend | points | before | after | after / before, median of rounds (min - max) |")
    print("|---|---|---:|---:|---:|---:|")
    for name, (expr, args, values) in L.timed_cases(max(sizes)).items():
        for backend in opts.backends.split(","):
            fs = {tree: mod.compile(expr, args, backend=backend, ranges=L.RANGES)
                  for tree, mod in (("before", symkin_before), ("after", symkin))}
            for n in sizes:
                v = [float(x[0]) if np.ndim(x) else x for x in values] if n == 1 else [x[:n] if np.ndim(x) else x for x in values]
                loops = max(1, min(2000, 200_000 // n))
                times: dict[str, list[float]] = {"before": [], "after": []}
                with np.errstate(all="ignore"):
                    for tree in fs:
                        fs[tree](*v)  # (numba: compiles the kernel)
                    for r in range(opts.rounds):
                        for tree in (("before", "after") if r % 2 else ("after", "before")):
                            times[tree].append(best(lambda tree=tree: fs[tree](*v), loops))
                b, a = times["before"], times["after"]
                ratios = [x / y for x, y in zip(a, b)]
                print(f"| {name} | {backend} | {n:.0e} | {statistics.median(b) * 1e6:.2f} us | {statistics.median(a) * 1e6:.2f} us "
                      f"| {statistics.median(ratios):.3f} ({min(ratios):.2f} - {max(ratios):.2f}) |", flush=True)
    print(f"1-minute load at the end {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    sys.exit(main())
