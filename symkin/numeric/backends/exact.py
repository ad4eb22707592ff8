"""The ``exact`` backend: rational laws in exact rational arithmetic (:class:`fractions.Fraction`)."""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import InputError, UnsupportedError
from symkin.numeric.backends.pointwise import PointwiseBackend
from symkin.numeric.codegen import ExactPrinter
from symkin.values import refuse_text

__all__ = ["ExactBackend"]


class ExactBackend(PointwiseBackend):
    """Exact rational arithmetic on :class:`fractions.Fraction` (rational laws only)."""

    key = "exact"
    precisions = ("exact",)

    def generate(self, exprs: list[sp.Expr]) -> Callable[..., Any]:
        """The laws as one function of Fractions; an UnsupportedError for a law that is not rational."""
        for e in exprs:
            bad = [n for n in sp.preorder_traversal(e)
                   if not (n.is_Symbol or n.is_Rational or n.is_Add or n.is_Mul or (n.is_Pow and n.exp.is_Integer))]
            if bad:
                raise UnsupportedError(
                    f"the exact backend evaluates rational laws only, and this one contains {bad[0]}; "
                    "use backend='mpmath' with digits=... instead"
                )
        return sp.lambdify(list(self.plan.args), exprs, modules=[{"Fraction": Fraction}], printer=ExactPrinter(),
                           cse=self.plan.cse, docstring_limit=0)

    def convert(self, value: Any, name: str) -> Any:
        """One input as a Fraction (an InputError for a float: it is not exact)."""
        return _to_fraction(value, name)


    def result(self, value: Any) -> Any:
        """An output as a Fraction (a law that is an integer constant gives an int)."""
        return value if type(value) is Fraction else Fraction(value)


def _to_fraction(v: Any, name: str) -> Any:
    kind = type(v)
    if kind is Fraction:  # the common cases first: this runs once per argument and call
        return v
    if kind is int:
        return Fraction(v)
    if isinstance(v, (bool, np.bool_)):
        raise InputError(f"{name} must be a number, got {v!r}")
    if isinstance(v, (int, np.integer)):
        return Fraction(int(v))  # so that / stays exact
    if isinstance(v, Fraction):
        return v
    if isinstance(v, sp.Rational):
        return Fraction(int(v.p), int(v.q))
    if isinstance(v, str):
        raise refuse_text(v, name)
    raise InputError(
        f"{name} must be exact for the exact backend (int or Fraction), got {v!r}; "
        "use backend='mpmath' for floats"
    )
