"""Vector loops: every solved case closes the loop again; singular and unsupported cases refuse."""

import itertools
import random

import pytest
import sympy as sp

from symkin import SingularConfigurationError, UnsupportedError
from symkin.errors import InputError
from symkin.vectorloop import LinkVector, VectorLoop, harmonics
from tests.support.zero import shown, zero

a, b, c = sp.symbols("a b c", real=True)
p, q, r = sp.symbols("p q r", real=True)


def residual(loop, values):
    """|left - right| with the solution put back: an independent check of the closed form."""
    x, y = loop.components()
    return [sp.N((eq.lhs - eq.rhs).subs(values), 30) for eq in (x, y)]


def four_bar_like(lengths, angles):
    """Three vectors on the left, one on the right, all symbols: the unknowns are chosen per case."""
    return VectorLoop(
        [LinkVector(lengths[0], angles[0]), LinkVector(lengths[1], angles[1] + sp.Rational(1, 3))],
        [LinkVector(lengths[2], angles[2]), LinkVector(sp.Rational(7, 2), sp.Rational(2, 5))],
    )


CASES = [
    ("length and angle of one vector", (a, r)),
    ("two lengths", (a, c)),
    ("length of one, angle of another", (a, q)),
    ("angle of one, length of another", (q, a)),
    ("two angles", (p, q)),
]


@pytest.mark.parametrize("name, unknowns", CASES, ids=[c[0] for c in CASES])
def test_each_case_closes_the_loop_on_every_branch(name, unknowns):
    rng = random.Random(7)
    loop = four_bar_like((a, b, c), (p, q, r))
    given = {s: sp.Float(rng.randint(15, 40) / 10, 30) for s in (a, b, c)}
    given.update({s: sp.Float(rng.randint(-300, 300) / 100, 30) for s in (p, q, r)})
    for u in unknowns:
        given.pop(u)
    solutions = loop.subs(given).solve(*unknowns)
    assert len(solutions) in (1, 2)
    closed = 0
    for sol in solutions:
        values = {**given, **sol.values}
        if any(not sp.N(v).is_real for v in sol.values.values()):
            continue  # this branch does not assemble for these lengths
        assert all(abs(x) < 1e-20 for x in residual(loop, values)), (name, sol.values)
        closed += 1
    assert closed >= 1


def test_one_unknown_length_leaves_the_across_condition():
    loop = VectorLoop([LinkVector(a, p), LinkVector(b, q)], [LinkVector(c, r)])
    (sol,) = loop.solve(c)
    along, across = loop.components_along(r)
    assert zero(sol[c] - (along + c))  # along = left - right = value - c
    assert zero(sol.conditions[0] - across)


def test_one_unknown_angle_leaves_the_length_condition():
    loop = VectorLoop([LinkVector(3, 0), LinkVector(4, q)], [LinkVector(5, sp.atan(sp.Rational(4, 3)))])
    (sol,) = loop.solve(q)
    assert sp.simplify(sol.conditions[0]) == 0  # 3-4-5: the length fits
    assert sp.simplify(sol[q]) == sp.pi / 2
    too_short = VectorLoop([LinkVector(3, 0), LinkVector(4, q)], [LinkVector(5, sp.pi / 2)])
    assert too_short.solve(q)[0].conditions[0] == 18  # |5i - 3|^2 - 4^2: it cannot close


def test_unknown_inside_an_angle_sum_is_inverted():
    loop = VectorLoop([LinkVector(1, p), LinkVector(1, p + q)], [LinkVector(c, 0)])
    sols = loop.solve(c, q)
    values = {p: sp.Rational(1, 5), **{k: v.subs(p, sp.Rational(1, 5)) for k, v in sols[0].values.items()}}
    assert all(abs(x) < 1e-25 for x in residual(loop, values))


def test_parallel_unknown_lengths_are_singular():
    loop = VectorLoop([LinkVector(a, 0), LinkVector(b, sp.pi)], [LinkVector(1, 1)])
    with pytest.raises(SingularConfigurationError, match="parallel"):
        loop.solve(a, b)


@pytest.mark.parametrize(
    "loop, unknowns, message",
    [
        (VectorLoop([LinkVector(a, p), LinkVector(a, q)]), (a,), "2 places"),
        (VectorLoop([LinkVector(a, p)]), (b,), "no vector"),
        (VectorLoop([LinkVector(a**2, p)], [LinkVector(1, 0)]), (a,), "non-linearly"),
    ],
)
def test_unsupported_unknowns_are_refused(loop, unknowns, message):
    with pytest.raises(UnsupportedError, match=message):
        loop.solve(*unknowns)


def test_bad_arguments():
    with pytest.raises(InputError):
        VectorLoop([])
    with pytest.raises(InputError):
        VectorLoop([LinkVector(a, p)]).solve(a, p, q)
    with pytest.raises(InputError):
        LinkVector("1", 0)


def test_harmonics_rebuild_the_expression_and_separate_frequencies():
    x, k = sp.symbols("x k", real=True)
    expr = 3 * sp.sin(2 * x + a) - b * sp.cos((1 - k) * x) + 5
    parts = harmonics(expr, x)
    rebuilt = sum(coef * sp.exp(sp.I * nu * x) for nu, coef in parts.items())
    assert zero(residual := rebuilt - expr), shown(residual)
    assert set(parts) == {0, 2, -2, 1 - k, k - 1}
    with pytest.raises(UnsupportedError):
        harmonics(x * sp.sin(x), x)


def test_two_branches_of_the_triangle_are_mirror_images():
    loop = VectorLoop([LinkVector(3, p), LinkVector(4, q)], [LinkVector(5, 0)])
    angles = sorted(float(sol[p]) for sol in loop.solve(p, q))
    assert angles == pytest.approx([-0.9272952180016122, 0.9272952180016122])
    for (s1, s2) in itertools.combinations(loop.solve(p, q), 2):
        assert float(s1[q]) == pytest.approx(-float(s2[q]))
