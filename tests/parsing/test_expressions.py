"""Every number in a user expression is bounded, and deciding so takes bounded time.

Short expressions whose value is astronomically large or small, or needs millions of
digits to evaluate (nested exponentials inside a trigonometric function, towers of
powers of an irrational base), are refused within seconds with one line; the enclosures
that decide it hold the true value (checked against mpmath at 60 digits); long flat sums
are one level of nesting; the parser's helpers refuse with a SymkinError, never a
TypeError, OverflowError, ValueError or a nan.  The library's value gate (symkin.values) takes
values, not text, and bounds nothing: that is the parser's work."""

import random
import time
from decimal import Decimal
from fractions import Fraction

import mpmath
import pytest
import sympy as sp

from symkin import InputError, ModelError, SymkinError
from symkin._util import bounds
from symkin.parsing import MAX_DEPTH, parse_expression, parse_integer, parse_number, parse_real
from symkin.values import as_expr, as_float, as_integer, as_rational, as_real, sign_of

#: Hostile shapes: (text, the size the refusal must state, worked out independently below).
HUGE = [
    # exp(exp(exp(3))) = 10^(exp(exp(3)) / ln 10): the sine of it would need 230 million digits
    ("sin(exp(exp(exp(3))))", mpmath.exp(mpmath.exp(3)) / mpmath.log(10)),
    ("cos(exp(exp(exp(2.9))))", mpmath.exp(mpmath.exp(mpmath.mpf("2.9"))) / mpmath.log(10)),
    # (sqrt(2)**999)**999 = 2^(999*999/2)
    ("((sqrt(2)**999)**999)**999", mpmath.mpf(999 * 999) / 2 * mpmath.log10(2)),
    ("(pi**99)**99", 99 * 99 * mpmath.log10(mpmath.pi)),
    ("exp(700)", 700 / mpmath.log(10)),
    ("10**300*10", mpmath.mpf(301)),
    ("exp(-800)", -800 / mpmath.log(10)),
    ("1e-200*1e-200", mpmath.mpf(-400)),
]


@pytest.mark.parametrize("text, log10", HUGE, ids=[h[0][:30] for h in HUGE])
def test_numbers_beyond_the_bounds_are_refused_quickly_with_their_size(text, log10):
    start = time.perf_counter()
    with pytest.raises(InputError) as info:
        parse_expression(text, what="--speed")
    assert time.perf_counter() - start < 2
    message = str(info.value)
    assert "\n" not in message and "numbers from 1e-300 to 1e300 in size are accepted" in message
    assert f"about 10^{int(mpmath.floor(log10))};" in message


@pytest.mark.parametrize("text, why", [
    ("sqrt(-1)", "square root of a negative number"),
    ("acos(2)", "outside [-1, 1]"),
    ("asin(-1.5)", "outside [-1, 1]"),
    ("log(0)", "logarithm of a number that is not positive"),
    ("log(-2)", "logarithm of a number that is not positive"),
    ("atan2(0, 0)", "atan2(0, 0) is undefined"),
    ("(-8)**(1/3)", "fractional power"),
    ("tan(pi/2)", "infinite or cannot be bounded"),
    ("1/(sin(1)**2 + cos(1)**2 - 1)", "cannot tell whether"),
    ("0**-1", "divides by zero"),
])
def test_numbers_that_are_not_finite_reals_are_refused(text, why):
    with pytest.raises(InputError, match=why.replace("(", r"\(").replace(")", r"\)").replace("[", r"\[")):
        parse_expression(text)


def test_numbers_inside_the_bounds_are_kept_exact():
    # the limits themselves, products that stay inside them, and values that only look large
    assert parse_expression("1e300") == sp.Integer(10) ** 300
    assert parse_expression("1e-300") == sp.Rational(1, 10**300)
    assert parse_expression("exp(690)") == sp.exp(690)
    assert parse_expression("sqrt(2)**999") == sp.sqrt(2) ** 999
    assert parse_expression("sin(10**300)") == sp.sin(sp.Integer(10) ** 300)  # evaluable: 1000 digits suffice
    assert parse_expression("pi**pi**pi") == sp.pi ** (sp.pi**sp.pi)  # about 1.3e18
    # zero in disguise is accepted as given: it is 0 (to 1233 digits), a valid value
    assert parse_expression("sin(1)**2+cos(1)**2-1") == sp.sin(1) ** 2 + sp.cos(1) ** 2 - 1
    # a tiny difference of two irrationals is not taken for 0
    assert parse_expression("1/(sqrt(2) - 1.4142135623730951)") == 1 / (sp.sqrt(2) - sp.Rational(14142135623730951, 10**16))


def test_symbols_keep_their_laws_and_only_their_constant_parts_are_bounded():
    t = sp.Symbol("t", real=True)
    assert parse_expression("exp(exp(exp(t)))", names=("t",)).has(sp.exp)
    with pytest.raises(InputError, match="about 10"):
        parse_expression("t + exp(exp(9))", names=("t",))
    with pytest.raises(InputError, match="cannot tell whether"):
        parse_expression("t/(sin(1)**2 + cos(1)**2 - 1)", names=("t",))
    assert t.name == "t"


def test_a_long_flat_sum_is_one_level_and_real_nesting_is_still_counted():
    total = parse_expression("+".join(["1"] * 999))  # 1997 characters
    assert total == 999
    assert parse_expression(" - ".join(["t"] * 61), names=("t",)) == -59 * sp.Symbol("t", real=True)
    assert parse_expression("*".join(["2"] * 60)) == 2**60
    deep = "exp(" * (MAX_DEPTH + 1) + "0" + ")" * (MAX_DEPTH + 1)
    with pytest.raises(InputError, match=f"nested more than {MAX_DEPTH} levels deep"):
        parse_expression(deep)
    with pytest.raises(InputError, match="nested"):
        parse_expression("-" * 1999 + "1")


def random_expression(rng: random.Random, depth: int) -> tuple[str, object]:
    """A random constant expression as text, and its value computed by mpmath (60 digits) along
    the same tree: an independent route to the number (None where mpmath finds no real value)."""
    if depth == 0 or rng.random() < 0.25:
        leaf = rng.choice(["pi", "E", "int", "fraction", "0.5"])
        if leaf == "int":
            n = rng.randint(-9, 9)
            return str(n), mpmath.mpf(n)
        if leaf == "fraction":
            p, q = rng.randint(1, 99), rng.randint(1, 99)
            return f"{p}/{q}", mpmath.mpf(p) / q
        return leaf, {"pi": mpmath.pi, "E": mpmath.e, "0.5": mpmath.mpf("0.5")}[leaf]
    kind = rng.random()
    a, va = random_expression(rng, depth - 1)
    if kind < 0.45:
        b, vb = random_expression(rng, depth - 1)
        op = rng.choice("+-*/")
        value = None
        if va is not None and vb is not None and not (op == "/" and vb == 0):
            value = {"+": va + vb, "-": va - vb, "*": va * vb, "/": va / vb if vb != 0 else None}[op]
        return f"({a}) {op} ({b})", value
    if kind < 0.55:
        n = rng.randint(-4, 4)
        return f"({a})**{n}", None if va is None or (va == 0 and n < 0) else va**n
    name = rng.choice(sorted(MPMATH))
    value = None
    if va is not None:
        try:
            value = MPMATH[name](va)
        except (ValueError, ZeroDivisionError):
            value = None
        if isinstance(value, mpmath.mpc) or (value is not None and not mpmath.isfinite(value)):
            value = None
    return f"{name}({a})", value


MPMATH = {"sin": mpmath.sin, "cos": mpmath.cos, "tan": mpmath.tan, "atan": mpmath.atan, "exp": mpmath.exp,
          "sqrt": mpmath.sqrt, "log": mpmath.log, "Abs": abs, "sinh": mpmath.sinh, "cosh": mpmath.cosh,
          "tanh": mpmath.tanh, "asin": mpmath.asin, "acos": mpmath.acos}


def test_enclosures_hold_the_value_mpmath_computes_at_60_digits():
    rng = random.Random(19)
    checked = 0
    with mpmath.workdps(60):
        for _ in range(400):
            text, reference = random_expression(rng, 4)
            if reference is None or abs(reference) > 10**290:
                continue
            try:
                expr = parse_expression(text)
            except InputError:
                continue
            for prec in bounds.PRECISIONS[:2]:
                try:
                    lo, hi = bounds.Encloser(prec).enclose(expr)
                except (bounds.Undecided, bounds.Unbounded, bounds.OutOfRange):
                    continue
                tolerance = mpmath.mpf(10) ** -50 * max(1, abs(reference))
                assert mpmath.mpf(lo) - tolerance <= reference <= mpmath.mpf(hi) + tolerance, (text, lo, hi, reference)
            checked += 1
    assert checked > 150


def test_signs_are_decided_on_intervals_not_on_floats():
    # pi - 3.14159265358979 is positive: 3.2e-15; sqrt(2)**2 - 2 is exactly 0 for SymPy already
    assert sign_of(sp.pi - sp.Rational(314159265358979, 10**14)) == 1
    assert sign_of(sp.Rational(314159265358979, 10**14) - sp.pi) == -1
    # agreement to 300 digits and still decided
    with mpmath.workdps(400):
        close = sp.Rational(int(mpmath.floor(mpmath.sqrt(2) * mpmath.mpf(10) ** 300)), 10**300)
    assert sign_of(sp.sqrt(2) - close) == 1
    assert sign_of(sp.sin(1) ** 2 + sp.cos(1) ** 2 - 1) is None  # 0 to 1233 digits, not written as 0


#: Text no parser helper may return a value for: not real, not finite, or beyond the bounds.
TEXT_REFUSALS = ["tan(pi/2)", "log(0)", "acos(2)", "sqrt(-1)", "atan2(0, 0)", "((sqrt(2)**999)**999)**999",
                 "exp(10**6)", "1e-320", "1e-999", "10**5000", "1e400", "nan", "inf", "I", "zoo"]


@pytest.mark.parametrize("helper", [parse_real, parse_expression, parse_number, parse_integer],
                         ids=lambda f: f.__name__)
def test_the_parse_helpers_refuse_with_one_symkin_line_and_never_return_nan(helper):
    problems = []
    for text in TEXT_REFUSALS:
        try:
            result = helper(text, what="the value")
        except SymkinError as err:
            if "\n" in str(err) or len(str(err)) > 400:
                problems.append(f"{text!r:.40}: message {str(err)[:100]!r}")
            continue
        except Exception as err:
            problems.append(f"{text!r:.40}: {type(err).__name__}: {str(err)[:100]}")
            continue
        problems.append(f"{text!r:.40}: accepted as {result!r:.60}")
    assert not problems, "\n".join(problems)


#: Values the library's gate refuses at every helper: not finite, not real, or text.
VALUE_REFUSALS = [sp.nan, sp.zoo, sp.oo, sp.I, float("nan"), float("inf"), Decimal("NaN"), None, True, "0.5",
                  sp.sqrt(-1, evaluate=False), sp.acos(2)]


@pytest.mark.parametrize("helper", [as_float, as_real, as_expr, as_rational, as_integer], ids=lambda f: f.__name__)
def test_the_value_gate_refuses_what_is_not_a_finite_real_with_a_symkin_error(helper):
    problems = []
    for value in VALUE_REFUSALS:
        try:
            result = helper(value, what="the value")
        except SymkinError as err:
            if "\n" in str(err):
                problems.append(f"{value!r:.40}: message {str(err)[:100]!r}")
            continue
        except Exception as err:
            problems.append(f"{value!r:.40}: {type(err).__name__}: {str(err)[:100]}")
            continue
        problems.append(f"{value!r:.40}: accepted as {result!r:.60}")
    assert not problems, "\n".join(problems)


def test_the_value_gate_bounds_no_size_the_parser_does():
    # a Python caller's exact number is taken as it is (SymPy computes with it); typed, it is refused
    assert as_rational(10**5000) == sp.Integer(10) ** 5000
    assert as_real(sp.Integer(10) ** 400) == sp.Integer(10) ** 400
    with pytest.raises(InputError, match="numbers from 1e-300 to 1e300 in size are accepted"):
        parse_number("1e5000")


def test_as_float_is_the_nearest_float_of_the_exact_value():
    for text in ["pi/2", "sqrt(2)", "exp(-1)", "1/3", "sin(10**300)", "atan2(1, -1)"]:
        exact = parse_expression(text)
        assert as_float(exact, what="x") == float(mpmath.mpf(sp.N(exact, 40)))
    # an exact zero in disguise is 0.0, not a rounding residue
    assert as_float(sp.sin(1) ** 2 + sp.cos(1) ** 2 - 1, what="x") == 0.0


def test_decimal_teeth_are_taken_exactly_like_fractions():
    from symkin.model import as_teeth

    assert as_teeth(Decimal("20"), "teeth") == as_teeth(Fraction(20, 1), "teeth") == 20
    with pytest.raises(ModelError, match="whole number"):
        as_teeth(Decimal("20.5"), "teeth")


@pytest.mark.parametrize("radius, message", [
    (sp.sin(1) ** 2 + sp.cos(1) ** 2 - 1, "which is 0 to"),
    (-sp.pi, "must be positive"),
    (sp.Integer(0), "must be positive"),
])
def test_radii_that_are_zero_in_disguise_or_not_positive_are_refused(radius, message):
    from symkin.model import Gear

    with pytest.raises(ModelError, match=message):
        Gear("1", radius)


def test_a_time_budget_stops_work_that_follows_a_users_expression(monkeypatch):
    # a builder stuck on one node (as SymPy's evaluation was on sin(exp(exp(exp(3))))): the gate's
    # time limit turns it into a one-line InputError
    import symkin.parsing.expressions as parsing

    def stuck(self, node):
        while True:
            sum(range(1000))  # busy: the budget counts CPU time

    monkeypatch.setattr(parsing, "SECONDS", 0.3)
    monkeypatch.setattr(parsing._Builder, "bounded", stuck)
    start = time.process_time()
    with pytest.raises(InputError, match="took longer than 0.3 s of CPU time"):
        parse_expression("sin(2) + 1")
    assert 0.25 <= time.process_time() - start < 3  # CPU time, counted in ticks of a few ms
