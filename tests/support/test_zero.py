"""The tests' zero-ness helper (tests/support/zero.py): right on identities and non-identities, and quick
on a wrong law, where sp.simplify of the residual never returned (issue 19, item 8)."""

import time

import sympy as sp

from symkin import drives, schemes
from symkin import symbols as S
from tests.support.zero import shown, zero

t = S.t
x = sp.Symbol("x", real=True)
r = sp.Symbol("r", positive=True)
theta = sp.Function("theta")(t)


def test_identities_are_zero_and_near_identities_are_not():
    assert zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1)
    assert zero(sp.sqrt(r**2) - r)  # r is positive: the helper gives symbols the sign they are declared with
    assert zero(sp.diff(sp.sin(theta) ** 2, t) - 2 * sp.sin(theta) * sp.cos(theta) * theta.diff(t))
    assert zero(sp.Matrix([sp.cos(2 * x) - 1 + 2 * sp.sin(x) ** 2, 0]))
    assert not zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1 + sp.Rational(1, 10**20))
    assert not zero(sp.diff(theta**2, t) - 2 * theta)  # theta' is independent of theta
    assert not zero(sp.diff(theta, t, 2))
    assert not zero(sp.Matrix([0, x * 1e-12]))


def test_a_dropped_centripetal_term_is_found_in_seconds():
    # the hand-made bug of issue 19: eq. (6) with one centripetal component dropped; the residual
    # against the derivative of the velocity is not zero, and sp.simplify of it ran > 9 CPU-minutes
    motion = schemes.scheme("AI1").motion({"1": drives.AngleLaw(theta), "4": 0})
    p = motion.particle("2", (sp.Symbol("a", real=True), sp.Symbol("b", real=True)))
    right = p.velocity.diff(t) - p.acceleration
    start = time.process_time()
    assert zero(right)
    # the broken law: the planet's own omega^2 (X - X_P) loses its y component
    planet_omega = motion.omega("2")
    _, centre = motion.pole("2")
    rel = p.position - motion.particle("2", tuple(centre)).position
    assert zero(p.acceleration - (motion.particle("2", tuple(centre)).acceleration
                                  + motion.epsilon("2") * sp.Matrix([-rel[1], rel[0]]) - planet_omega**2 * rel))  # eq. (6) itself
    broken = p.acceleration + planet_omega**2 * sp.Matrix([0, rel[1]])
    assert not zero(p.velocity.diff(t) - broken)
    assert time.process_time() - start < 20


def test_shown_prints_a_residual_within_its_budget():
    assert shown(sp.sin(x) ** 2 + sp.cos(x) ** 2) == "1"
    start = time.process_time()
    text = shown(sp.exp(sp.sin(x) ** 7 * sp.cos(x) ** 9 / (1 + sp.tan(x) ** 5)) ** 3 - 1, seconds=1)
    assert text and time.process_time() - start < 10
