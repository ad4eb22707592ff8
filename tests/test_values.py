"""Value mappings (values=...) never reach SymPy's string parser, and keys match by name."""

import pytest
import sympy as sp

from symkin import InputError, schemes
from symkin import symbols as S
from symkin.parsing import parse
from symkin.values import as_values, substitute

INJECTION = "__import__('os').system('touch PWNED') or 1"


@pytest.fixture
def particle():
    return schemes.single_row_AI().motion({"4": 0, "H": 1}).particle("2", (S.radius("1"), 0))


def test_trajectory_values_are_never_executed(particle, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(InputError, match="is the text .*symkin.parse"):
        particle.trajectory(1.0, values={"r_1": INJECTION, "r_2": 1, "r_4": 3})
    with pytest.raises(InputError, match="not allowed"):
        parse(INJECTION)
    assert not (tmp_path / "PWNED").exists()


def test_keys_match_by_name_whatever_the_assumptions(particle):
    plain = {sp.Symbol("r_1"): 1, "r_2": sp.Rational(1), sp.Symbol("r_4", real=True): 3.0}
    _t, x, y = particle.trajectory(2.0, samples=3, values=plain)
    exact = substitute(particle.position, {"r_1": 1, "r_2": 1, "r_4": 3})
    assert x[-1] == pytest.approx(float(exact[0].subs(S.t, 2)))
    assert y[-1] == pytest.approx(float(exact[1].subs(S.t, 2)))


@pytest.mark.parametrize("bad", ["1", None, [1], {1: 2}])
def test_bad_time_spans_and_mappings_are_symkin_errors(particle, bad):
    with pytest.raises(InputError):
        if isinstance(bad, (dict, list)):
            particle.trajectory(1.0, values=bad)
        else:
            particle.trajectory(bad, t_start=2.0, values={"r_1": 1, "r_2": 1, "r_4": 3})


def test_as_values_refuses_strange_keys():
    with pytest.raises(InputError, match="key"):
        as_values({3.5: 1})


@pytest.mark.parametrize("text", ["E**1000", "-exp(800)"])
def test_typed_values_beyond_float64_are_refused_with_the_range(text):
    from symkin.parsing import parse_real

    with pytest.raises(InputError, match="beyond the float64 range"):
        parse_real(text, what="--carrier-angle")
    assert parse_real("E**690") == sp.E**690  # large, still within the 1e300 bound on every number (E**700 is 1e304)
