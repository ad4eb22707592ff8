"""The AA train's ratio i_1H^(4) in tooth numbers: the law symkin derives, and Willis's formula by hand."""

from __future__ import annotations

from fractions import Fraction

from symkin import schemes


def law():
    """symkin's law of the AA train's ratio i_1H^(4), tooth numbers symbolic."""
    return schemes.two_row("AA", teeth=True).ratio("1", "H", fixed="4")


def exact(z1, z2, z3, z4):
    """i_1H^(4) of the AA train by Willis's formula: 1 - i_14^H, i_14^H = z2 z4/(z1 z3)."""
    return [float(1 - Fraction(int(b) * int(d), int(a) * int(c))) for a, b, c, d in zip(z1, z2, z3, z4)]
