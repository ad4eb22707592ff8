"""unit_of: the unit a user typed after a number, for printing results back in it."""

from __future__ import annotations

from symkin.parsing.quantities import unit_of


def test_unit_of_finds_the_unit_typed_after_a_number():
    assert unit_of("300 rpm", "rad/s") == "rpm" and unit_of("300rpm", "rad/s") == "rpm"
    assert unit_of("2*pi rad/s", "rad/s") == "rad/s" and unit_of("1.5 mm", "m") == "mm"


def test_a_bare_number_or_no_quantity_has_no_unit():
    assert unit_of("10*pi", "rad/s") is None and unit_of("3 kg", "rad/s") is None
    assert unit_of("", "rad/s") is None and unit_of("rpm", "rad/s") is None
