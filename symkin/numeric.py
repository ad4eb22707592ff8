"""Compile derived laws into vectorised numeric functions.

    >>> import numpy as np, symkin
    >>> law = symkin.schemes.two_row("AI").ratio("1", "H", fixed="4")
    >>> f = symkin.compile(law)
    >>> f.args
    ('r_1', 'r_2', 'r_3', 'r_4')
    >>> float(f(1, 2, 1, 4))
    9.0
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np
import sympy as sp

from .errors import InputError
from .laws import Law

__all__ = ["compile", "NumericFunction"]


@dataclass(frozen=True)
class NumericFunction:
    """A compiled law: call it with arrays in the order of :attr:`args`."""

    func: Callable[..., Any] = field(repr=False)
    args: tuple[str, ...]
    outputs: tuple[str, ...]
    backend: str
    precision: str

    def __post_init__(self) -> None:
        object.__setattr__(
            self,
            "__doc__",
            f"Compiled {', '.join(self.outputs)} ({self.backend}, {self.precision}).\n\n"
            f"Arguments, in order: {', '.join(self.args) or '(none)'}.",
        )

    def __call__(self, *values: Any) -> Any:
        if len(values) != len(self.args):
            raise InputError(f"this function takes {len(self.args)} arguments ({', '.join(self.args)}), got {len(values)}")
        return self.func(*values)


def _exprs(laws: Any) -> tuple[list[sp.Expr], list[str]]:
    items = list(laws) if isinstance(laws, (list, tuple)) else [laws]
    exprs, names = [], []
    for item in items:
        if isinstance(item, Law):
            exprs.append(item.rhs)
            names.append(str(item.lhs))
        elif isinstance(item, sp.Basic):
            exprs.append(item)
            names.append(str(item))
        else:
            raise InputError(f"can only compile laws or SymPy expressions, got {item!r}")
    return exprs, names


def compile(laws: Any, args: Sequence[sp.Symbol] | None = None, *, cse: bool = True) -> NumericFunction:
    """A vectorised NumPy (float64) function of one law or several (sharing subexpressions).

    Parameters
    ----------
    laws : Law, sympy expression, or a sequence of them
    args : sequence of Symbol, optional
        Argument order; default: every free symbol, sorted by name.
    cse : bool
        Eliminate common subexpressions first.
    """
    exprs, names = _exprs(laws)
    free = set().union(*(e.free_symbols for e in exprs)) if exprs else set()
    if args is None:
        args = sorted(free, key=lambda s: s.name)
    missing = free - set(args)
    if missing:
        raise InputError(f"the law depends on {', '.join(sorted(map(str, missing)))}, which are not among the arguments")
    target = exprs[0] if len(exprs) == 1 else exprs
    func = sp.lambdify(list(args), target, modules="numpy", cse=cse)
    if len(exprs) == 1 and not free:
        constant = float(exprs[0])
        func = lambda *a: np.float64(constant)  # noqa: E731
    return NumericFunction(func, tuple(str(a) for a in args), tuple(names), "numpy", "float64")
