"""The layout of the package holds: imports run down the layers, no cycles, one numeric path.

docs/architecture.md draws the layers; this test reads every import of symkin/ (module
level and inside functions) from the source and checks:

- every import goes to the same layer or a lower one, except the one deliberate
  convenience layer (the model's methods calling the kinematics and particles, imported
  inside those methods);
- the modules import each other without a cycle (module level and function level alike,
  less that one documented exception);
- laws become numbers only in symkin/numeric (no lambdify, no exec of generated code
  elsewhere);
- no module of the library imports the papers (derivations/), and the command-line
  modules do no symbolic work of their own (no module-level SymPy import);
- the edge: text and the operating system enter and leave at three borders only, the
  command line (symkin/cli), train files (symkin/trains/file.py) and the papers' reports
  (symkin/papers): only they import the parser (symkin.parsing) and the process and file
  helpers (symkin._io).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "symkin"

#: Layers from the bottom up: a module may import its own layer or a lower one.
LAYERS: list[tuple[str, ...]] = [
    ("symkin._version", "symkin.errors", "symkin.symbols", "symkin.laws"),
    ("symkin._util", "symkin._deprecated", "symkin.values", "symkin.units", "symkin.parsing", "symkin._io"),
    ("symkin.numeric", "symkin.printing", "symkin.superposition", "symkin.linsolve"),
    ("symkin.model",),
    ("symkin.kinematics", "symkin.particles", "symkin.drives", "symkin.vectorloop"),
    ("symkin.schemes", "symkin.trains"),
    ("symkin.study", "symkin.statics", "symkin.dynamics", "symkin.geometry"),
    ("symkin.synthesis",),
    ("symkin.mechanisms",),
    ("symkin.viz",),
    ("symkin.papers",),
    ("symkin.cli",),
    ("symkin", "symkin.__main__"),
]

#: The deliberate convenience layer: Mechanism.speeds/ratio/motion call the kinematics
#: and the particle laws (like sympy's Point.v2pt_theory), imported inside those methods.
CONVENIENCE = {("symkin.model.mechanism", "symkin.kinematics"), ("symkin.model.mechanism", "symkin.particles"),
               # and a mechanism shows in Jupyter as its kinematic scheme (Mechanism._repr_html_)
               ("symkin.model.mechanism", "symkin.viz.diagram")}


def _module(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {_module(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _layer(module: str) -> int:
    best, rank = -1, None
    for k, prefixes in enumerate(LAYERS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best:
                best, rank = len(prefix), k
    assert rank is not None, f"{module} is in no layer of tests/project/test_architecture.py: add it to LAYERS"
    return rank


def _target(name: str) -> str | None:
    """The module of symkin an imported name lands in (a module, or the package holding it)."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def _imports(module: str) -> list[tuple[str, int, bool]]:
    """(imported module of symkin, line, inside a function) for every import in ``module``."""
    path = MODULES[module]
    tree = ast.parse(path.read_text(), str(path))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    type_checking = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.dump(node.test):
            type_checking |= {id(n) for n in ast.walk(node)}
    functions = {id(n) for f in ast.walk(tree) if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef))
                 for n in ast.walk(f)}
    for node in ast.walk(tree):
        if id(node) in type_checking:
            continue
        names: list[str] = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                base = ".".join(anchor + ([base] if base else []))
            names = [f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base for a in node.names]
        for name in names:
            target = _target(name) if name.startswith("symkin") else None
            if target and target != module:
                found.append((target, node.lineno, id(node) in functions))
    return found


EDGES = {m: _imports(m) for m in MODULES}


def test_every_import_runs_down_the_layers():
    upward = [
        f"{m}:{line} imports {target} ({'inside a function' if inner else 'at module level'})"
        for m, edges in EDGES.items() for target, line, inner in edges
        if _layer(target) > _layer(m) and (m, target) not in CONVENIENCE
    ]
    assert not upward, "imports that run up the layers:\n" + "\n".join(upward)


def test_the_convenience_layer_is_imported_inside_methods_only():
    for m, edges in EDGES.items():
        for target, line, inner in edges:
            if (m, target) in CONVENIENCE:
                assert inner, f"{m}:{line} imports {target} at module level: the convenience layer imports inside methods"


def test_no_import_cycles():
    graph = {m: {t for t, _, _ in edges if (m, t) not in CONVENIENCE} for m, edges in EDGES.items()}
    # a package's __init__ that re-exports its modules is not a cycle with them
    graph = {m: {t for t in ts if not (t.startswith(m + ".") and MODULES[m].name == "__init__.py")} for m, ts in graph.items()}
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(m: str) -> None:
        state[m] = 1
        stack.append(m)
        for t in sorted(graph[m]):
            if state.get(t) == 1:
                cycle = stack[stack.index(t):] + [t]
                pytest.fail("import cycle: " + " -> ".join(cycle))
            if t not in state:
                visit(t)
        stack.pop()
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m)


@pytest.mark.parametrize("needle", ["lambdify(", "exec(compile("])
def test_laws_become_numbers_in_symkin_numeric_only(needle):
    outside = [f"{m} ({p.relative_to(ROOT)})" for m, p in MODULES.items()
               if not m.startswith("symkin.numeric") and needle in p.read_text()]
    assert not outside, f"{needle} outside symkin/numeric: " + ", ".join(outside)


#: The borders where text and the operating system enter and leave (with the parser itself).
BORDERS = ("symkin.cli", "symkin.papers", "symkin.trains.file", "symkin.parsing", "symkin._io")
#: What only the borders may import: the parser of text, the process and file helpers.
EDGE = ("symkin.parsing", "symkin._io")


def _within(module: str, prefixes: tuple[str, ...]) -> bool:
    return any(module == p or module.startswith(p + ".") for p in prefixes)


def test_only_the_borders_import_the_parser_and_the_process_and_file_helpers():
    inside = [
        f"{m}:{line} imports {target}"
        for m, edges in EDGES.items() if not _within(m, BORDERS)
        for target, line, _ in edges if _within(target, EDGE)
    ]
    assert not inside, "library modules that read text or handle processes and files:\n" + "\n".join(inside)


def test_the_library_never_imports_the_papers():
    for m, p in MODULES.items():
        text = p.read_text()
        assert "symkin.derivations" not in {t for t, _, _ in EDGES[m]}, m
        assert "import_module(\"symkin.derivations" not in text and "derivations." not in text.replace("symkin.derivations", ""), m


def test_command_line_modules_import_no_sympy_at_module_level():
    for m, p in MODULES.items():
        if not m.startswith("symkin.cli"):
            continue
        tree = ast.parse(p.read_text())
        for node in tree.body:
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
                assert not any(n.split(".")[0] == "sympy" for n in names), f"{m}:{node.lineno} imports SymPy"


def _imported_after(code: str, modules: str) -> str:
    """Which of ``modules`` (a Python expression of a set of names) a fresh interpreter has
    imported after running ``code`` (a sorted list, printed)."""
    import subprocess
    import sys

    code += f"\nprint(sorted(m for m in {modules} if m in sys.modules or m in {{n.split('.')[0] for n in sys.modules}}))\n"
    return subprocess.run([sys.executable, "-c", "import sys\n" + code], capture_output=True, text=True, check=True).stdout.strip()


def test_help_and_the_parser_load_no_sympy():
    # `symkin --help` and building any command's parser stay light: what a command's
    # module imports at module level (directly or through symkin.cli.common, symkin._util,
    # symkin.papers.registry) is checked by running it, not only by reading its imports
    code = (
        "import io, contextlib\n"
        "from symkin.cli import COMMANDS, build_parser, main\n"
        "build_parser()\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n"
        "        main(['--help'])\n"
        "    except SystemExit:\n"
        "        pass\n"
    )
    assert _imported_after(code, "('sympy', 'numpy', 'mpmath', 'matplotlib', 'scipy')") == "[]"


def test_compiling_a_law_imports_no_more_of_numpy_than_it_calls():
    # the NumPy code of a compiled law runs in a namespace holding the numpy module itself:
    # sympy.lambdify(modules="numpy") runs `from numpy import *`, which imports numpy.f2py and
    # what it needs (about 0.1 s in every process that compiles a law)
    code = (
        "import numpy as np, sympy as sp, symkin\n"
        "x, y = sp.symbols('x y')\n"
        "f = symkin.compile([sp.sin(x) * y / (x - y), sp.atan2(y, x)], [x, y])\n"
        "f(np.linspace(0.1, 1, 5), 2.0)\n"
        "f(0.5, 2.0)\n"
    )
    assert _imported_after(code, "('numpy.f2py', 'numpy.testing', 'scipy')") == "[]"


#: Folders of tests/ that hold suites across the package rather than one module's tests.
CROSS_CUTTING = {"project", "hostile", "properties", "derivations", "support"}


def test_the_tests_mirror_the_package():
    # tests/<package path>/test_<module>[_<aspect>].py for symkin/<package path>/<module>.py (the package's
    # own __init__: test_<package>.py), so that a module's tests are found by its path; the cross-cutting
    # suites have folders of their own
    tests = ROOT / "tests"
    stray = []
    for path in sorted(tests.rglob("test_*.py")):
        parts = path.relative_to(tests).parts
        if parts[0] in CROSS_CUTTING:
            continue
        folder = PACKAGE.joinpath(*parts[:-1])
        stem = path.stem.removeprefix("test_")
        names = {p.stem.lstrip("_") for p in folder.glob("*.py") if p.stem != "__init__"} if folder.is_dir() else set()
        names |= {p.name.lstrip("_") for p in folder.iterdir() if p.is_dir()} if folder.is_dir() else set()
        names.add(folder.name if parts[:-1] else "symkin")  # the package's own __init__: tests/cli/test_cli.py
        if not any(stem == n or stem.startswith(n + "_") for n in names):
            stray.append(str(path.relative_to(ROOT)))
    assert not stray, "test files that name no module of symkin at their path:\n" + "\n".join(stray)


#: The house limits of issue 30: a module of symkin/ is at most this many lines long (as ``wc -l``
#: counts them), a function (its def to its last line, docstring included) at most this many.
MAX_MODULE_LINES, MAX_FUNCTION_LINES = 800, 100


def test_no_module_or_function_of_symkin_is_over_the_house_limits():
    # a module past 800 lines holds two subjects, a function past 100 several steps: split them where
    # their logic splits (benchmarks/layout.py lists the longest)
    long_modules, long_functions = [], []
    for path in MODULES.values():
        text = path.read_text()
        name = path.relative_to(ROOT).as_posix()
        lines = len(text.splitlines())
        if lines > MAX_MODULE_LINES:
            long_modules.append(f"{name} ({lines} lines)")
        for node in ast.walk(ast.parse(text, name)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                length = (node.end_lineno or node.lineno) - node.lineno + 1
                if length > MAX_FUNCTION_LINES:
                    long_functions.append(f"{name}:{node.name} (line {node.lineno}, {length} lines)")
    assert not long_modules and not long_functions, (
        f"modules over {MAX_MODULE_LINES} lines: {', '.join(long_modules) or 'none'}; "
        f"functions over {MAX_FUNCTION_LINES} lines: {', '.join(long_functions) or 'none'}"
    )
