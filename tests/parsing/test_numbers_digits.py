"""Every exact number a user types is bounded in digits as well as in size.

A number near 1 raised to a large power stays near 1 in size but carries a vast number of
digits (``(1 - 10**-300)**1000`` has 300,000 in its numerator): within the size bounds, it
hung every command that took it, or printed an internal error past Python's 4300-digit
limit.  The parser refuses it, before SymPy computes it, with one line that names the option
and the limit; the digits it states are checked against the number's own text, computed
here where it is small enough to compute."""

import math
import time

import pytest
import sympy as sp

from symkin import InputError
from symkin.parsing import MAX_EXACT_DIGITS, parse_expression, parse_number

#: (text, the digits of the largest numerator or denominator in it, counted independently)
NEAR_ONE = [
    ("(1-10**-300)**1000", 300 * 1000),  # (10^300 - 1)^1000 / 10^300000
    ("(1+10**-300)**4", 1201),  # numerator (10^300 + 1)^4, denominator 10^1200 (1201 digits)
    ("(999/1000)**400", 1200),  # 1000^400 = 10^1200
    ("t*(1-10**-300)**1000", 300 * 1000),  # beside the time, in a law
    ("(t*(1-10**-300))**1000", 300 * 1000),  # a product raised to a power: SymPy raises each factor
    ("*".join(["(1-10**-300)"] * 4), 1201),  # a flat product of exact numbers near 1
    ("(1-10**-300)**(1000/3)", 100 * 1000),  # a fractional power: its whole part is multiplied out
]


@pytest.mark.parametrize("text, digits", NEAR_ONE, ids=[n[0][:30] for n in NEAR_ONE])
def test_numbers_near_one_with_too_many_digits_are_refused_quickly(text, digits):
    assert digits > MAX_EXACT_DIGITS
    start = time.process_time()
    with pytest.raises(InputError) as info:
        parse_expression(text, names=("t",), what="--length")
    assert time.process_time() - start < 2
    message = str(info.value)
    assert message.startswith("--length holds an exact number of about ") and "\n" not in message
    assert f"at most {MAX_EXACT_DIGITS} are accepted" in message
    stated = int(message.split("about ")[1].split()[0])
    assert stated == pytest.approx(digits, rel=0.02)  # estimated from bit lengths before computing


def test_the_digit_estimate_matches_the_number_where_it_can_be_computed():
    # (10^300 - 1)^4 / 10^1200 computed with Python integers, its denominator's digits counted as text
    exact = sp.Rational(10**300 - 1, 10**300) ** 4
    assert len(str(exact.q)) == 1201 > MAX_EXACT_DIGITS
    with pytest.raises(InputError, match=r"about 120\d digits"):
        parse_expression("(1-10**-300)**4")


@pytest.mark.parametrize("text", ["(1-10**-300)**3", "(1+2**-300)**10", "0.999**300", "(7/9)**1000"])
def test_numbers_within_the_digit_bound_are_exact(text):
    value = parse_expression(text)
    base, _, power = text.rpartition("**")
    reference = sp.sympify(base, rational=True) ** int(power)
    assert value == reference  # SymPy's rationals from the text, as a second route
    assert max(len(str(value.p)), len(str(value.q))) <= MAX_EXACT_DIGITS


def test_a_long_literal_is_within_the_digit_bound():
    # the longest literal the number parser takes: 300 digits and an exponent that keeps it above 1e-300
    text = "1." + "3" * 299 + "e-299"
    value = parse_number(text)
    assert len(str(value.q)) == 599 and math.isclose(float(value), 1.333333333e-299, rel_tol=1e-9)
