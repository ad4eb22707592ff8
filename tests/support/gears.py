"""Gear formulas typed by hand for the tests: the published conditions, not symkin's code."""

from __future__ import annotations

import math


def least_ring_shift(z1: int, z2: int) -> float:
    """The least shift of a ring of ``z2`` teeth free of involute interference with a pinion of ``z1`` at their
    reference centre distance (alpha_w = 20 deg): the published condition (KHK / SDP-SI eq. 5-5)
    z1/z2 >= 1 - tan(alpha_a2)/tan(alpha_w) puts the ring's tip radius at r_b2 sqrt(1 + ((1 - z1/z2) tan 20)^2)
    or more; its tip radius is m (z2/2 - 1 + x2), m = 1."""
    alpha = math.radians(20)
    r_a2 = z2 / 2 * math.cos(alpha) * math.sqrt(1 + ((1 - z1 / z2) * math.tan(alpha)) ** 2)
    return r_a2 - (z2 / 2 - 1)


def undercut_limit(z: int) -> float:
    """The textbook least shift without undercut, 1 - z sin^2(20 deg) / 2 (ISO 53 profile A: to 3e-5)."""
    return 1 - z * math.sin(math.radians(20)) ** 2 / 2
