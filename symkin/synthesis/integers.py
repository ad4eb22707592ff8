"""Integer linear algebra for the assembly conditions: does ``G n = h`` have a solution in integers?

The assembly of equally spaced planets asks for whole numbers of tooth pitches (the
integers ``n``) that satisfy linear equations whose coefficients are tooth numbers
(:mod:`symkin.synthesis.problem` derives them).  These helpers decide such systems exactly
with Python integers: column operations bring ``G`` to a lower echelon form without
changing the lattice it spans (a Hermite form), and the system is then solved row by row.

    >>> from fractions import Fraction
    >>> solvable([[4, 6]], [Fraction(10)])          # 4 a + 6 b = 10: a = 1, b = 1
    True
    >>> solvable([[4, 6]], [Fraction(9)])           # gcd 2 does not divide 9
    False
    >>> solvable([[1, 1], [3, -2]], [Fraction(2), Fraction(1)])   # a + b = 2, 3a - 2b = 1: a = b = 1
    True
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction

__all__ = ["solvable", "divides"]


def solvable(G: Sequence[Sequence[int]], h: Sequence[Fraction | int]) -> bool:
    """True when integers ``n`` exist with ``G n = h`` (``G`` integer, ``h`` rational).

    Parameters
    ----------
    G : rows of integers
        m rows of p coefficients each (p may be 0: then ``h`` must vanish).
    h : sequence of Fraction or int
        The m right-hand sides.

    Examples
    --------
    >>> solvable([[2, 0], [0, 3]], [4, 9]), solvable([[2, 0], [0, 3]], [4, 8])
    (True, False)
    >>> solvable([[3, 5]], [Fraction(1, 2)])    # a sum of integers is never a half
    False
    >>> solvable([], [])
    True
    """
    rows = len(G)
    if len(h) != rows:
        raise ValueError(f"{rows} rows and {len(h)} right-hand sides")
    b = []
    for value in h:
        value = Fraction(value)
        if value.denominator != 1:
            return False  # G n is an integer for every integer n
        b.append(value.numerator)
    cols = len(G[0]) if rows else 0
    M = [[int(x) for x in row] for row in G]
    if any(len(row) != cols for row in M):
        raise ValueError("the rows of G differ in length")
    y: list[int] = []  # values of the pivot columns, in order
    col = 0
    for i in range(rows):
        row = M[i]
        _reduce(M, i, col)
        known = sum(M[i][c] * y[c] for c in range(col))
        rest = b[i] - known
        if col < cols and row[col] != 0:
            value, remainder = divmod(rest, row[col])
            if remainder:
                return False
            y.append(value)
            col += 1
        elif rest != 0:
            return False
    return True


def divides(coefficients: Sequence[int], value: Fraction | int) -> bool:
    """True when ``value`` is an integer combination of ``coefficients``: a multiple of their gcd.

    >>> divides([6, 10], 4), divides([6, 10], 3), divides([0], 0)
    (True, False, True)
    """
    value = Fraction(value)
    if value.denominator != 1:
        return False
    g = 0
    for c in coefficients:
        g = math.gcd(g, int(c))
    return value.numerator == 0 if g == 0 else value.numerator % g == 0


def _reduce(M: list[list[int]], i: int, col: int) -> None:
    """Column operations (unimodular) that leave one entry, the gcd, in row ``i`` from column ``col`` on."""
    row = M[i]
    for j in range(col + 1, len(row)):
        while row[j] != 0:
            if row[col] == 0 or abs(row[j]) < abs(row[col]):
                _swap(M, col, j)
                continue
            q = row[j] // row[col]
            for r in M:
                r[j] -= q * r[col]


def _swap(M: list[list[int]], a: int, b: int) -> None:
    for r in M:
        r[a], r[b] = r[b], r[a]
