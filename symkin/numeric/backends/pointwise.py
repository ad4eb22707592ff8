"""What the arbitrary-precision backends (``mpmath``, ``exact``) share: the laws as given,
lambdified once, evaluated point by point on converted values.

A subclass defines ``generate(exprs)`` (the lambdified function), ``convert(value, name)``
(one input as its number) and ``result(value)`` (one output as its number).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import sympy as sp

from symkin.errors import InputError, PoleError
from symkin.numeric.backends.base import Backend, Plan, Result, lambdify_source
from symkin.numeric.nodes import plain_form

__all__ = ["PointwiseBackend"]


class PointwiseBackend(Backend):
    """Evaluate the laws as given (their plain forms), point by point on object arrays."""

    floats = False

    def __init__(self, plan: Plan):
        super().__init__(plan)
        self.names = [s.name for s in plan.args]
        self.func = self.generate([plain_form(e) for e in plan.exprs])
        self.code = lambdify_source(self.func)

    @property
    def source(self) -> str:
        """The generated Python code."""
        return self.code

    def generate(self, exprs: list[sp.Expr]) -> Callable[..., Any]:
        """The laws as one function of the arguments (``sympy.lambdify``)."""
        raise NotImplementedError

    def convert(self, value: Any, name: str) -> Any:
        """One input as this backend's number (an InputError for what it cannot take)."""
        raise NotImplementedError

    def result(self, value: Any) -> Any:
        """One output as this backend's number."""
        raise NotImplementedError

    def evaluate(self, values: Sequence[Any], outs: Sequence[np.ndarray] | None = None) -> Result:
        """The laws at every point of the broadcast inputs: object arrays of this backend's numbers."""
        shape, arrays = _object_points(values)
        results = [np.empty(shape, dtype=object) for _ in self.plan.exprs]
        for idx in np.ndindex(shape):
            out = self._at([a[idx] for a in arrays])
            for r, v in zip(results, out):
                r[idx] = self.result(v)
        return shape, [r.reshape(-1) for r in results], False

    def evaluate_scalar(self, values: Sequence[Any]) -> list[Any]:
        """The laws at one point of scalars, one value per law."""
        return [self.result(v) for v in self._at(values)]

    def _at(self, values: Sequence[Any]) -> Any:
        point = [self.convert(v, name) for v, name in zip(values, self.names)]
        try:
            return self.func(*point)
        except ZeroDivisionError:
            at = ", ".join(f"{n}={v}" for n, v in zip(self.names, point))
            raise PoleError(f"{', '.join(self.plan.names)} has a pole at {at} (a denominator vanishes); "
                            "choose inputs away from it") from None


def _object_points(values: Sequence[Any]) -> tuple[tuple[int, ...], list[np.ndarray]]:
    """The inputs as object arrays broadcast to one shape (each value kept as it was given)."""
    arrays = []
    for v in values:
        if isinstance(v, (list, tuple, np.ndarray)):
            a = np.asarray(v, dtype=object)
        else:
            a = np.empty((), dtype=object)
            a[()] = v
        arrays.append(a)
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays))
    except ValueError:
        raise InputError("the argument arrays do not broadcast to one shape; give arrays of matching shapes") from None
    return shape, [np.broadcast_to(a, shape) for a in arrays]
