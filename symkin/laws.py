"""Derived laws: an equation ``lhs = rhs`` with a description.

A :class:`Law` is what the engine returns for a ratio, a link speed, or any other
closed-form result; :func:`symkin.latex` prints it and :func:`symkin.compile` turns its
right-hand side into a numeric function.

    >>> import sympy as sp
    >>> from symkin.laws import Law
    >>> x = sp.Symbol("x")
    >>> print(Law(sp.Symbol("y"), 2 * x, "doubling"))
    y = 2*x
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import sympy as sp

__all__ = ["Law"]


@dataclass(frozen=True)
class Law:
    """A derived closed-form law ``lhs = rhs``.

    Attributes
    ----------
    lhs : sympy expression
        What the law gives (e.g. ``omega_H`` or the ratio symbol ``i_{1H}^{(4)}``).
    rhs : sympy expression
        The derived expression.
    description : str
        One line saying what the law is, in words.
    """

    lhs: sp.Expr
    rhs: sp.Expr
    description: str = ""

    @property
    def equation(self) -> sp.Eq:
        """The law as an unevaluated SymPy equation ``lhs = rhs``.

        >>> from symkin import schemes
        >>> schemes.two_row("AA", teeth=(100, 100, 101, 99)).ratio("H", "1", fixed="4").equation
        Eq(i_{H1}^{(4)}, 101/2)
        """
        return sp.Eq(self.lhs, self.rhs, evaluate=False)

    @property
    def free_symbols(self) -> set:
        """Symbols the right-hand side depends on."""
        return self.rhs.free_symbols

    def subs(self, *args: Any, **kwargs: Any) -> Law:
        """The law with values substituted into its right-hand side."""
        return Law(self.lhs, self.rhs.subs(*args, **kwargs), self.description)

    def _latex(self, printer: Any) -> str:
        return f"{printer._print(self.lhs)} = {printer._print(self.rhs)}"

    def _sympystr(self, printer: Any) -> str:
        return f"{printer._print(self.lhs)} = {printer._print(self.rhs)}"

    def __str__(self) -> str:
        return sp.sstr(self)

    def _repr_latex_(self) -> str:
        """The law as display math, for Jupyter (``lhs = rhs``; SymPy's LaTeX printer).

        >>> x = sp.Symbol("x")
        >>> print(Law(sp.Symbol("y"), x**2)._repr_latex_())
        $\\displaystyle y = x^{2}$
        """
        return f"$\\displaystyle {sp.latex(self)}$"
