"""symkin.latex options a paper author needs: notation, numbers, alignment, line breaking,
display fractions; and text escaping."""

import pytest
import sympy as sp

import symkin
from symkin import InputError, schemes
from symkin import symbols as S
from symkin.printing import escape_text, estimated_width, latex_lines


def unbreak(lines):
    return " ".join(lines).replace(r"\Bigl(", r"\left(").replace(r"\Bigr)", r"\right)")


def test_a_broken_sum_rejoins_to_the_unbroken_law():
    x = sp.symbols("x0:12")
    expr = sum((i + 1) * x[i] * x[(i + 5) % 12] for i in range(12))
    whole = symkin.latex(expr)
    lines = latex_lines(expr, width=25)
    assert len(lines) > 2 and all(estimated_width(line) <= 25 for line in lines)
    assert unbreak(lines) == whole
    assert all(line.startswith(("+ ", "- ")) for line in lines[1:])


def test_a_product_with_a_long_sum_opens_it_over_lines():
    a, b, c, d, e = sp.symbols("a b c d e")
    lines = latex_lines(e * (a * b + b * c + c * d + d * a + a * c), width=10)
    assert lines[0].startswith(r"e \Bigl(") and lines[-1].endswith(r"\Bigr)")
    assert unbreak(lines) == symkin.latex(e * (a * b + b * c + c * d + d * a + a * c))


def test_a_fraction_with_a_long_numerator_is_written_one_over_d():
    w1, w4, r1, r2 = S.omega("1"), S.omega("4"), S.radius("1"), S.radius("2")
    lines = latex_lines((w1 * r1 * r2 + w4 * r2**2 + w1 * r1**2) / (r1 + r2), width=12)
    assert lines[0].startswith(r"\frac{1}{r_{1} + r_{2}} \Bigl(") and lines[-1].endswith(r"\Bigr)")


def test_width_applies_to_every_law_of_an_aligned_set_with_tags_on_first_lines():
    speeds = schemes.two_row("AI").speeds({"1": S.omega("1"), "4": S.omega("4")})
    tex = symkin.latex(speeds, number=["a", "b"], width=15)
    rows = tex.split(" \\\\\n")
    assert tex.startswith(r"\begin{align}") and sum(r"\tag" in r for r in rows) == 2
    assert all(r"\notag" in r for r in rows if r"\tag" not in r and "&\\qquad" in r)


def test_notation_by_symbol_or_by_name_and_display_fractions():
    law = schemes.two_row("AI", teeth=True).ratio("1", "H", fixed="4")
    by_name = symkin.latex(law, symbol_names={"z_2": "Z_{s}"}, frac="dfrac")
    by_symbol = symkin.latex(law, symbol_names={S.teeth("2"): "Z_{s}"}, frac="dfrac")
    assert by_name == by_symbol == r"i_{1H}^{(4)} = 1 + \dfrac{Z_{s} z_{4}}{z_{1} z_{3}}"


@pytest.mark.parametrize(
    "kwargs, message",
    [({"frac": "sfrac"}, "frac must be"), ({"width": 0}, "width must be"), ({"symbol_names": {1: "x"}}, "keys are"),
     ({"number": ["1", "2"]}, "one equation number")],
)
def test_bad_options_are_input_errors(kwargs, message):
    with pytest.raises(InputError, match=message):
        symkin.latex(S.omega("1") + 1, **kwargs)


def test_latex_refuses_raw_strings():
    with pytest.raises(InputError, match="not strings"):
        symkin.latex("__import__('os')")


@pytest.mark.parametrize("char", list("\\&%$#_{}~^<>|\""))
def test_every_special_character_is_escaped(char):
    out = escape_text(f"a{char}b")
    assert out != f"a{char}b"
    body = out[1:-1]
    assert body.startswith("\\") or body == "''"
