"""runtime.sum_source (issue 34): the error-free sum of products against exact rational
arithmetic (Fraction) on the same binary inputs, where the terms cancel to a few units."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp

from symkin.numeric import runtime

X = sp.symbols("x0:4", real=True)


def _exact(poly, point):
    return Fraction(sp.Rational(poly.subs(dict(zip(X, map(sp.Rational, map(Fraction, point)))))))


def test_a_cancelling_polynomial_is_rounded_once_on_arrays_and_on_floats():
    x0, x1, x2, x3 = X
    # integer coefficients, powers, a one-factor term: x0 x1 x2 - x3 x1 (x0 - x1 + x2) and more
    cancelling = sp.expand(x0 * x1 * x2 - x3 * x1 * (x0 - x1 + x2))
    rng = np.random.default_rng(34)
    n = 300
    xs = [rng.uniform(1, 2, n) for _ in X]
    xs[3] = xs[0] * xs[2] / (xs[0] - xs[1] + xs[2]) * (1 + rng.uniform(-1e-9, 1e-9, n))  # the terms cancel to 1e-9
    plain = sp.lambdify(X, cancelling)(*xs)
    worst = 0.0
    for poly in (cancelling, cancelling + 3 * x0**2 * x3 - 2 * x2 - x1):
        fn = runtime.dd_function(runtime.sum_source("_s", poly, X), "_s")
        hi, _lo = fn(*xs)
        for k in range(n):
            point = [float(x[k]) for x in xs]
            exact = _exact(poly, point)
            assert abs(Fraction(float(hi[k])) - exact) <= Fraction(2) ** -52 * abs(exact)  # within one rounding (and a little)
            assert float(fn(*point)[0]) == float(hi[k])  # Python floats: the same arithmetic
            if poly is cancelling:
                worst = max(worst, float(abs(Fraction(float(plain[k])) - exact) / abs(exact)))
    assert worst > 2.0**-30  # (the plain sum loses digits on these points: the test can fail)


def test_a_coefficient_that_is_not_an_integer_is_left_to_the_double_double_code():
    assert runtime.sum_source("_s", X[0] * X[1] / 3, X) is None
