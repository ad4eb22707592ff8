"""Tooth outlines: radii, the involute flanks found again from the base circle's involute, the fillet
that meets the flank where the rack's straight flank ends, and no outline that crosses itself."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from symkin.geometry import ToothForm, gear_geometry, tooth_outline
from tests.support.segments import crossings


def flank_classes(gear, x, y, *, skip: float = 1e-6):
    """Points strictly between the form and the tip circles sorted by flank: the polar angle minus
    (one flank) or plus (the other) the involute's own polar angle inv(acos(r_b / r)), reduced to one
    pitch, takes a single value per flank along an involute of the base circle."""
    rb, ra = float(gear.base_diameter) / 2, float(gear.tip_diameter) / 2
    r = np.hypot(x, y)
    theta = np.arctan2(y, x)
    if gear.internal:
        on = (r < float(gear.root_diameter) / 2 - skip) & (r > max(ra, rb) + skip)
    else:  # above the form circle, where the rack's straight flank begins to cut (no undercut here):
        # sqrt(r_b^2 + (r sin a - (h_a0* - x) m / sin a)^2), h_a0* = 1.25 - 0.38 (1 - sin a)
        a, m, x = math.pi / 9, float(gear.module), float(gear.shift)
        form = math.hypot(rb, float(gear.reference_diameter) / 2 * math.sin(a) - (1.25 - 0.38 * (1 - math.sin(a)) - x) * m
                          / math.sin(a))
        on = (r > form + skip) & (r < ra - skip)
    roll = np.sqrt(r[on] ** 2 / rb**2 - 1)
    polar = roll - np.arctan(roll)  # the involute r_b (cos t + t sin t, sin t - t cos t) at radius r
    pitch = 2 * math.pi / int(gear.teeth)
    return np.mod(theta[on] - polar, pitch), np.mod(theta[on] + polar, pitch)


@pytest.mark.parametrize("z, x, internal", [(20, "0", False), (13, "0.4", False), (31, "-0.2", False),
                                            (60, "0", True), (45, "0.3", True), (30, "0", True)])
def test_outline_radii_and_involute_flanks(z, x, internal):
    g = gear_geometry(z, 2, ToothForm(shift=sp.Rational(x)), internal=internal)
    X, Y = tooth_outline(g, phase=0.3, points=24)
    r = np.hypot(X, Y)
    assert (X[0], Y[0]) == (X[-1], Y[-1])
    assert r.max() == pytest.approx(float(max(g.tip_diameter, g.root_diameter)) / 2, abs=1e-9)
    assert r.min() == pytest.approx(float(min(g.tip_diameter, g.root_diameter)) / 2, abs=1e-9)
    one, other = flank_classes(g, X, Y)
    # every flank point lies on one of two involutes of the base circle (one per flank direction), repeated
    # each pitch: theta - inv(acos(r_b/r)) is one value on one flank, theta + inv(...) on the other
    pitch = 2 * math.pi / z
    assert one.size > 4 * z
    on_one, on_other = _on_the_most_common_value(one, pitch), _on_the_most_common_value(other, pitch)
    assert np.all(on_one | on_other)
    assert on_one.sum() == on_other.sum()  # as many points on either flank


def _on_the_most_common_value(values, period, tol=1e-9):
    gap = np.abs((values[:, None] - values[None, :] + period / 2) % period - period / 2) < tol
    return gap[np.argmax(gap.sum(axis=1))]


def test_the_fillet_ends_on_the_involute_where_there_is_no_undercut():
    from symkin.geometry.outline import _fillet, _flank_angle

    g = gear_geometry(20, 1)
    r, theta = _fillet(g, 40)
    assert r[0] == pytest.approx(float(g.root_diameter) / 2, abs=1e-12)  # the rack's tip line cuts the root circle
    assert theta[-1] == pytest.approx(float(_flank_angle(g, np.array([r[-1]]))[0]), abs=1e-12)
    # the form circle: where the straight flank's lowest point (depth h_a0* m) generates the involute,
    # sqrt(r_b^2 + (r sin a - (h_a0* - x) m / sin a)^2), typed here
    a, rr = math.pi / 9, 10.0
    a0 = 1.25 - 0.38 * (1 - math.sin(a))
    assert r[-1] == pytest.approx(math.hypot(rr * math.cos(a), rr * math.sin(a) - a0 / math.sin(a)), abs=1e-12)


@pytest.mark.parametrize("z, x", [(8, "0"), (12, "0"), (12, "0.5"), (40, "0")])
def test_outlines_do_not_cross_themselves_undercut_or_not(z, x):
    g = gear_geometry(z, 1, ToothForm(shift=sp.Rational(x)))
    X, Y = tooth_outline(g, points=20)
    assert crossings(X, Y) == 0
