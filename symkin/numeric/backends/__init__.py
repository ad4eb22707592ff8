"""The backends :func:`symkin.compile` chooses by name: one module each, one interface
(:class:`~symkin.numeric.backends.base.Backend`), and :data:`BACKENDS`, key -> class.

========  ==========================================  =====================
key       what                                        precision
========  ==========================================  =====================
numpy     vectorised NumPy, cse, in chunks            float64 or float32
numba     one fused compiled loop per call, threads   float64 or float32
mpmath    arbitrary precision, point by point         ``digits`` digits
exact     rational arithmetic (fractions.Fraction)    exact
========  ==========================================  =====================

A backend is built from a :class:`~symkin.numeric.backends.base.Plan` and evaluates with
``evaluate(values, outs) -> (shape, outputs, flagged)``;
:class:`~symkin.numeric.function.NumericFunction` wraps it.  Adding one: docs/architecture.md
("A numeric backend").

    >>> sorted(BACKENDS)
    ['exact', 'mpmath', 'numba', 'numpy']
"""

from __future__ import annotations

from symkin.numeric.backends.base import Backend, Plan
from symkin.numeric.backends.exact import ExactBackend
from symkin.numeric.backends.mpmath import MpmathBackend
from symkin.numeric.backends.numba import NumbaBackend, kernel_cache_folder, numba_available, warn_no_numba
from symkin.numeric.backends.numpy import NumpyBackend

__all__ = ["Plan", "Backend", "BACKENDS", "NumpyBackend", "NumbaBackend", "MpmathBackend", "ExactBackend",
           "numba_available", "kernel_cache_folder", "warn_no_numba"]

#: Backends by key (see the module docstring).
BACKENDS: dict[str, type[Backend]] = {
    "numpy": NumpyBackend,
    "numba": NumbaBackend,
    "mpmath": MpmathBackend,
    "exact": ExactBackend,
}
