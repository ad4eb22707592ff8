"""The size of symkin's layers, its longest functions and its complexity counts, in one table.

Run on demand (``python benchmarks/layout.py [--json]``) to record a reorganisation before and
after; the numbers go into notes (benchmarks/notes/), never into code.

- lines per layer: physical lines of the modules of each layer (blank and comment lines included,
  as ``wc -l`` counts them);
- the functions of symkin/ of 60 lines or more, longest first;
- ruff's McCabe complexity (C901): how many functions pass 10 and 20.
"""

from __future__ import annotations

import argparse
import ast
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "symkin"

#: Layers as the issue of the edge names them: the machinery is the process, operating-system and
#: input-defence code; the engine is the kinematics proper.  A path is a module or a folder.
LAYERS = {
    "engine": ["model.py", "model", "linsolve.py", "kinematics.py", "particles.py", "superposition.py", "vectorloop.py", "drives.py",
               "laws.py", "symbols.py"],
    # the parser (symkin/parsing, once symkin/_util/parsing.py) and the file and process helpers
    # (symkin/_io, once in symkin/_util; papers/_pool.py until it went)
    "machinery": ["_util", "_io", "parsing", "papers/_pool.py", "papers/texbuild.py", "cli/__init__.py",
                  "_deprecated.py"],
    # the library's gate for values (not text): counted apart, so that the machinery row compares with before
    "values gate": ["values.py", "units.py"],
    "numeric": ["numeric"],
}


def _files(entry: str) -> list[Path]:
    path = PACKAGE / entry
    if path.is_dir():
        return sorted(path.rglob("*.py"))
    return [path] if path.exists() else []


def lines(path: Path) -> int:
    return len(path.read_text(encoding="utf-8").splitlines())


def layer_lines() -> dict[str, int]:
    out = {name: sum(lines(f) for e in entries for f in _files(e)) for name, entries in LAYERS.items()}
    out["symkin (all)"] = sum(lines(f) for f in PACKAGE.rglob("*.py"))
    return out


def long_functions(minimum: int = 60) -> list[tuple[int, str, str]]:
    rows = []
    for path in sorted(PACKAGE.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = node.end_lineno - node.lineno + 1
                if n >= minimum:
                    rows.append((n, str(path.relative_to(ROOT)), node.name))
    return sorted(rows, reverse=True)


def long_modules(minimum: int = 600) -> list[tuple[int, str]]:
    return sorted(((lines(p), str(p.relative_to(ROOT))) for p in PACKAGE.rglob("*.py") if lines(p) >= minimum),
                  reverse=True)


def complexity(threshold: int) -> int:
    proc = subprocess.run(
        [sys.executable, "-m", "ruff", "check", str(PACKAGE), "--select", "C901", "--output-format", "concise",
         "--config", f"lint.mccabe.max-complexity={threshold}", "--no-cache"],
        capture_output=True, text=True, check=False)
    return sum(1 for line in proc.stdout.splitlines() if "C901" in line)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    data = {
        "lines": layer_lines(),
        "modules_over_600": long_modules(),
        "functions_over_60": long_functions(),
        "complexity_over_10": complexity(10),
        "complexity_over_20": complexity(20),
    }
    if args.json:
        print(json.dumps(data, indent=2))
        return
    for name, n in data["lines"].items():
        print(f"{name:14} {n:6d} lines")
    print("modules of 600 lines or more:")
    for n, path in data["modules_over_600"]:
        print(f"  {n:5d} {path}")
    print("functions of 60 lines or more:")
    for n, path, name in data["functions_over_60"]:
        print(f"  {n:4d} {path}:{name}")
    print(f"ruff C901: {data['complexity_over_10']} functions over 10, {data['complexity_over_20']} over 20")


if __name__ == "__main__":
    main()
