"""The model: validation of gears, links, meshes and mechanisms; immutability; coaxiality."""

import dataclasses

import pytest
import sympy as sp

from symkin import CoaxialityWarning, Gear, Link, Mechanism, ModelError, schemes
from symkin import symbols as S


def test_objects_are_immutable():
    g = Gear.from_teeth("1", 20)
    with pytest.raises(dataclasses.FrozenInstanceError):
        g.radius = 3
    m = schemes.two_row("AI")
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.links = ()
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.link("H").kind = None


def test_derived_laws_are_cached_on_the_mechanism():
    m = schemes.two_row("AA")
    first = m.ratio("1", "H", fixed="4")
    assert m.ratio("1", "H", fixed="4") == first
    assert any(k[0] == "coefficients" for k in m._cache if isinstance(k, tuple))


@pytest.mark.parametrize(
    "build, message",
    [
        (lambda: Gear.from_teeth("1", 0), "must be positive"),
        (lambda: Gear.from_teeth("1", -5), "must be positive"),
        (lambda: Gear.from_teeth("1", 20.5), "whole number"),
        (lambda: Gear.from_teeth("1", 20.0), "whole number"),
        (lambda: Gear("1", -2), "must be positive"),
        (lambda: Gear("1", 0), "must be positive"),
        (lambda: Gear("1", sp.nan), "finite"),
        (lambda: Gear("1", sp.oo), "finite"),
        (lambda: Gear("", 3), "gear name"),
        (lambda: schemes.two_row("AX"), "unknown two-row scheme"),
        (lambda: schemes.scheme("nope"), "unknown scheme"),
        (lambda: schemes.two_row("AA", teeth=(1, 2, 3)), "4 values"),
        (lambda: schemes.two_row("AA", teeth=(10, 20, 30, 0)), "must be positive"),
        (lambda: schemes.two_row("AI", teeth=(20, 30, 20, 10)), "must be larger"),
    ],
)
def test_bad_descriptions_raise_a_model_error(build, message):
    with pytest.raises(ModelError, match=message):
        build()


def test_text_in_place_of_a_value_points_to_the_parser():
    from symkin.errors import TextInputError

    with pytest.raises(TextInputError, match=r"symkin.parse\('3'\)"):
        Gear("1", "3")


def test_two_internal_gears_cannot_mesh():
    with pytest.raises(ModelError, match="both internal"):
        Mechanism(
            links=[Link.central("1", Gear("1", 5, internal=True)), Link.central("H"), Link.planet("2", Gear("2", 2, internal=True))],
            meshes=[("1", "2")],
        )


def test_two_central_gears_cannot_mesh():
    with pytest.raises(ModelError, match="both turn about the main axis"):
        Mechanism(links=[Link.central("1", Gear("1", 5)), Link.central("4", Gear("4", 2))], meshes=[("1", "4")])


def test_unknown_names_are_refused_with_the_valid_ones():
    m = schemes.two_row("AI")
    with pytest.raises(ModelError, match="no link 'X'.*1, 2, 23, 3, 4, H"):
        m.link("X")
    with pytest.raises(ModelError, match="carrier 'K'"):
        Mechanism(links=[Link.central("1", Gear("1", 1)), Link.planet("2", Gear("2", 1), carrier="K")], meshes=[("1", "2")])
    with pytest.raises(ModelError, match="no gear '9'"):
        Mechanism(links=[Link.central("1", Gear("1", 1)), Link.central("H"), Link.planet("2", Gear("2", 1))], meshes=[("1", "9")])


def test_gear_names_resolve_to_their_link():
    m = schemes.two_row("AA")
    assert m.link("2") is m.link("23") is m.link("3")


def test_coaxiality_is_derived_from_the_meshes():
    r1, r2, r3, r4 = (S.radius(str(i)) for i in range(1, 5))
    cases = {"AI": r1 + r2 + r3, "AA": r1 + r2 - r3, "II": r1 - r2 + r3}
    for kind, ring in cases.items():
        (cond,) = schemes.two_row(kind).coaxiality
        assert sp.solve(cond, r4) == [ring]
    (cond,) = schemes.single_row_AI().coaxiality
    assert sp.solve(cond, r4) == [r1 + 2 * r2]


def test_non_coaxial_teeth_warn_but_still_give_the_ratio():
    with pytest.warns(CoaxialityWarning, match=r"199\*m/2 and at 201\*m/2"):
        m = schemes.two_row("AA", teeth=(100, 99, 100, 101))
    assert m.ratio("H", "1", fixed="4").rhs == 10000


def test_coaxial_teeth_do_not_warn(no_coaxiality_warning):
    for kind, z in {"AI": (20, 30, 20, 70), "AA": (54, 45, 44, 55), "II": (200, 99, 100, 201)}.items():
        assert schemes.two_row(kind, teeth=z).coaxiality_defects() == ()


def test_planet_arm_is_the_first_mesh_centre_distance():
    m = schemes.two_row("II", radii=(10, 3, 4, 11))
    assert m.arm("23") == 7


def test_carrier_can_hold_the_next_stage_sun():
    train = schemes.common_ring_train(2)
    assert [g.name for g in train.link("H1").gears] == ["s2"]
    assert train.dof == 2


def test_reserved_link_names_are_refused_and_frame_names_the_frame():
    import pytest as _pytest

    from symkin.errors import TrainFileError
    from symkin.model import FRAME
    from symkin.trains import load_train, read_train

    assert load_train("simple").link("frame").name == FRAME
    text = """meshes = [["s", "p"], ["p", "r"]]
[links.S]
gears = { s = 20 }
[links.C]
[links.P]
carrier = "C"
gears = { p = 20 }
[links.R]
gears = { r = { teeth = 60, internal = true } }
"""
    assert read_train(text).ratio("S", "C", fixed="R").rhs == 4
    for old, new, word in (("[links.P]", "[links.O]", "main axis"), ("[links.C]", "[links.0]", "frame")):
        changed = text.replace(old, new).replace('carrier = "C"', 'carrier = "0"' if new == "[links.0]" else 'carrier = "C"')
        with _pytest.raises(TrainFileError, match=f"reserved .symkin's name for the {word}"):
            read_train(changed)
    with _pytest.raises(ModelError, match="reserved"):
        Mechanism([Link.frame(), Link.central("O", Gear.from_teeth("x", 20))], [])
