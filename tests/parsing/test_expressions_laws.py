"""Laws of t (an angle law, a base motion) are differentiated twice: they must be smooth, and
their acceleration small enough to derive, simplify and compile within seconds.

``Abs(t)`` in a law became a DiracDelta in its acceleration, which has no float code (an
internal error); ``sin`` nested 55 deep, or ``exp(t*exp(t*...))`` 20 deep, ran for minutes
downstream.  Both are refused where the law is read, with one line."""

import time

import pytest
import sympy as sp

from symkin import InputError
from symkin.parsing import MAX_LAW_SIZE, parse_expression
from symkin.symbols import t


@pytest.mark.parametrize("text", ["Abs(t)", "2*Abs(sin(t))", "sqrt(t**2)", "t + Abs(t - 5)"])
def test_a_law_with_a_kink_is_refused(text):
    with pytest.raises(InputError, match=r"^--angle-law: Abs\(.*\) is not smooth where .* = 0.*smooth law"):
        parse_expression(text, names=("t",), what="--angle-law")


def test_abs_of_a_constant_is_a_number_and_welcome():
    assert parse_expression("t*Abs(-2) + Abs(sin(1))", names=("t",)) == 2 * t + sp.sin(1)


NESTED = ["sin(" * 55 + "t" + ")" * 55, "exp(t*" * 20 + "t" + ")" * 20, "cos(" * 30 + "t" + ")" * 30]


@pytest.mark.parametrize("text", NESTED, ids=["sin 55 deep", "exp(t*exp(...)) 20 deep", "cos 30 deep"])
def test_a_law_too_involved_to_differentiate_is_refused_in_bounded_time(text):
    start = time.process_time()
    with pytest.raises(InputError) as info:
        parse_expression(text, names=("t",), what="--angle-law")
    assert time.process_time() - start < 5
    assert str(info.value).startswith("--angle-law ") and "\n" not in str(info.value)


@pytest.mark.parametrize("text", ["2*pi*t + 0.3*sin(2*t)", "sin(" * 10 + "t" + ")" * 10, "exp(t*" * 8 + "t" + ")" * 8,
                                  "+".join(f"sin({k}*t)/{k}" for k in range(1, 120))])
def test_ordinary_laws_are_read_with_their_acceleration_within_the_bound(text):
    law = parse_expression(text, names=("t",))
    acceleration = sp.diff(law, t, 2)
    assert sum(1 for _ in sp.preorder_traversal(acceleration)) <= MAX_LAW_SIZE  # counted here without a cap
