"""Public functions and classes of symkin without a docstring.

Public: every module of ``symkin/`` and ``derivations/`` whose path has no part starting
with ``_`` (``symkin/_util`` is internal; package ``__init__`` modules count), and in it every
function and class whose name does not start with ``_``, and every method and property of
such a class whose name does not start with ``_``.  Read from the source with :mod:`ast`, so
nothing is imported and the count is the same on any machine.

    python tests/support/docstrings.py          # the count and the list of what lacks one

tests/project/test_docstrings.py keeps the count at 0.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FOLDERS = (("symkin", ROOT / "symkin"), ("symkin.derivations", ROOT / "derivations"))
Def = (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)


def _module_name(package: str, folder: Path, path: Path) -> str | None:
    parts = list(path.relative_to(folder).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    if any(p.startswith("_") for p in parts):
        return None
    return ".".join([package, *parts])


def _public(node: ast.AST) -> bool:
    return isinstance(node, Def) and not node.name.startswith("_")


def _overload(node: ast.AST) -> bool:
    return any((isinstance(d, ast.Name) and d.id == "overload") or (isinstance(d, ast.Attribute) and d.attr in ("overload", "setter"))
               for d in getattr(node, "decorator_list", ()))


def public_objects() -> list[tuple[str, bool]]:
    """Every public function, class, method and property: (dotted name, has a docstring)."""
    found = []
    for package, folder in FOLDERS:
        for path in sorted(folder.rglob("*.py")):
            module = _module_name(package, folder, path)
            if module is None:
                continue
            tree = ast.parse(path.read_text(encoding="utf-8"))
            for node in tree.body:
                if not _public(node) or _overload(node):
                    continue
                assert isinstance(node, Def)
                found.append((f"{module}.{node.name}", ast.get_docstring(node) is not None))
                if isinstance(node, ast.ClassDef):
                    for member in node.body:
                        if _public(member) and not _overload(member):
                            assert isinstance(member, Def)
                            found.append((f"{module}.{node.name}.{member.name}", ast.get_docstring(member) is not None))
    return found


def missing() -> list[str]:
    """The public objects without a docstring."""
    return [name for name, documented in public_objects() if not documented]


if __name__ == "__main__":
    lacking = missing()
    print(f"{len(lacking)} of {len(public_objects())} public functions, classes, methods and properties have no docstring")
    print("\n".join(lacking))
    sys.exit(1 if lacking else 0)
