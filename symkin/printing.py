"""LaTeX for derived laws, as a paper prints them.

One function, :func:`latex`, behind a :class:`~sympy.printing.latex.LatexPrinter`
subclass; laws print themselves through their ``_latex`` method.  No global state.

    >>> import symkin
    >>> law = symkin.schemes.two_row("AI", teeth=True).ratio("1", "H", fixed="4")
    >>> print(symkin.latex(law))
    i_{1H}^{(4)} = 1 + \\frac{z_{2} z_{4}}{z_{1} z_{3}}
    >>> print(symkin.latex(law, number="13a"))
    \\begin{equation}
    i_{1H}^{(4)} = 1 + \\frac{z_{2} z_{4}}{z_{1} z_{3}} \\tag{13a}
    \\end{equation}
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, Iterable

import sympy as sp
from sympy.printing.latex import LatexPrinter

from .laws import Law

__all__ = ["SymkinLatexPrinter", "latex"]


class SymkinLatexPrinter(LatexPrinter):
    """LaTeX printer for symkin: polynomial terms in the paper's order (1 + ... first)."""

    printmethod = "_latex"
    _default_settings = {**LatexPrinter._default_settings, "order": "none"}

    def _print_Add(self, expr: sp.Add, order: Any = None) -> str:
        # constants first, as a paper writes 1 + z2 z4 / (z1 z3)
        terms = sorted(expr.args, key=lambda a: (not a.is_number, sp.default_sort_key(a)))
        tex = ""
        for i, term in enumerate(terms):
            if i == 0:
                pass
            elif sp.Mul(term).could_extract_minus_sign():
                tex += " - "
                term = -term
            else:
                tex += " + "
            term_tex = self._print(term)
            if self._needs_add_brackets(term):
                term_tex = r"\left(%s\right)" % term_tex
            tex += term_tex
        return tex


def _laws(obj: Any) -> list[Law] | None:
    if isinstance(obj, Law):
        return [obj]
    if hasattr(obj, "laws") and callable(obj.laws):
        return list(obj.laws())
    if isinstance(obj, (list, tuple)) and obj and all(isinstance(x, Law) for x in obj):
        return list(obj)
    return None


def latex(
    obj: Any,
    *,
    symbol_names: Mapping[sp.Symbol, str] | None = None,
    number: str | int | Iterable[str | int] | None = None,
    aligned: bool | None = None,
    **settings: Any,
) -> str:
    """LaTeX of a law, a set of laws (e.g. a :class:`~symkin.kinematics.Speeds`), or an expression.

    Parameters
    ----------
    obj : Law, Speeds, sequence of Law, or sympy expression
    symbol_names : mapping of Symbol to str, optional
        LaTeX to print for given symbols (e.g. ``{S.omega("23"): r"\\omega_{sat}"}``).
    number : str or int, or a sequence of them, optional
        Equation number(s): wraps the result in an ``equation`` environment with ``\\tag``
        (or an ``align`` environment with one tag per law).
    aligned : bool, optional
        Several laws: align them at ``=`` (default True for several laws).
    **settings
        Passed to SymPy's LatexPrinter (e.g. ``fold_short_frac=True``).
    """
    printer = SymkinLatexPrinter({"symbol_names": dict(symbol_names or {}), **settings})
    laws = _laws(obj)
    if laws is None:
        body = printer.doprint(sp.sympify(obj, strict=True) if not isinstance(obj, sp.Basic) else obj)
        return _wrap(body, number)
    if len(laws) == 1 and aligned is not True:
        return _wrap(printer.doprint(laws[0]), number)
    lines = [f"{printer.doprint(L.lhs)} &= {printer.doprint(L.rhs)}" for L in laws]
    if number is not None:
        tags = [number] * len(laws) if isinstance(number, (str, int)) else list(number)
        if len(tags) != len(laws):
            raise ValueError(f"{len(laws)} laws need {len(laws)} equation numbers, got {len(tags)}")
        body = " \\\\\n".join(f"{line} \\tag{{{tag}}}" for line, tag in zip(lines, tags))
        return "\\begin{align}\n" + body + "\n\\end{align}"
    return "\\begin{aligned}\n" + " \\\\\n".join(lines) + "\n\\end{aligned}"


def _wrap(body: str, number: Any) -> str:
    if number is None:
        return body
    return f"\\begin{{equation}}\n{body} \\tag{{{number}}}\n\\end{{equation}}"
