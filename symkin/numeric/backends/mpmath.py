"""The ``mpmath`` backend: the laws as given at ``digits`` significant digits, point by
point (the reference the float backends are tested against)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import InputError
from symkin.numeric.backends.base import Result
from symkin.numeric.backends.pointwise import PointwiseBackend
from symkin.values import refuse_text

__all__ = ["MpmathBackend"]


class MpmathBackend(PointwiseBackend):
    """mpmath at ``digits`` significant digits, point by point (the reference backend)."""

    key = "mpmath"
    precisions = ("mpmath",)

    def generate(self, exprs: list[sp.Expr]) -> Callable[..., Any]:
        """The laws as one function of mpmath numbers."""
        return sp.lambdify(list(self.plan.args), exprs, modules="mpmath", cse=self.plan.cse, docstring_limit=0)

    def convert(self, value: Any, name: str) -> Any:
        """One input as an mpf (a float's binary value exactly; decimal text parsed exactly)."""
        return _to_mpf(value, name)

    def result(self, value: Any) -> Any:
        """An output as mpmath gives it (an mpf, or an mpc where a law is complex there)."""
        return value

    def evaluate(self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None) -> Result:
        """The laws at every point, with mpmath at the plan's digits: object arrays of mpf."""
        import mpmath

        with mpmath.workdps(self.plan.digits or 50):
            return super().evaluate(values, outs)

    def evaluate_scalar(self, values: Sequence[Any]) -> list[Any]:
        """The laws at one point of scalars, with mpmath at the plan's digits."""
        import mpmath

        with mpmath.workdps(self.plan.digits or 50):
            return super().evaluate_scalar(values)


def _to_mpf(v: Any, name: str) -> Any:
    import mpmath

    if isinstance(v, (mpmath.mpf, mpmath.mpc)):
        return v
    if isinstance(v, (bool, np.bool_)):
        raise InputError(f"{name} must be a number, got {v!r}")
    if isinstance(v, (int, np.integer)):
        return mpmath.mpf(int(v))
    if isinstance(v, (float, np.floating)):
        return mpmath.mpf(float(v))  # the binary value, exactly
    if isinstance(v, Fraction):
        return mpmath.mpf(v.numerator) / v.denominator
    if isinstance(v, sp.Rational):
        return mpmath.mpf(int(v.p)) / int(v.q)
    if isinstance(v, str):
        raise refuse_text(v, name)
    if isinstance(v, sp.Expr) and v.is_number:
        return mpmath.mpf(sp.N(v, mpmath.mp.dps + 5))
    raise InputError(f"{name} must be a number (int, float or Fraction), got {v!r}")
