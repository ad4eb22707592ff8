"""Properties of the engine over random valid mechanisms (hypothesis)."""

import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from symkin import SingularConfigurationError, schemes
from symkin import symbols as S

KINDS = ["AI1", "AI", "AA", "II"]


def coaxial_teeth(kind, a, b, c):
    """A coaxial tooth set of the scheme, or None when these numbers cannot make one."""
    if kind == "AI1":
        return (a, b, a + 2 * b)
    if kind == "AI":
        return (a, b, c, a + b + c)
    if kind == "AA":
        return (a, b, c, a + b - c) if a + b - c > 0 else None
    return (a, b, c, a - b + c) if a > b else None


@settings(deadline=None)
@given(st.sampled_from(KINDS), st.integers(12, 400), st.integers(12, 400), st.integers(12, 400),
       st.integers(1, 10**6), st.fractions(-100, 100), st.fractions(-100, 100))
def test_laws_are_invariant_when_all_radii_are_scaled(kind, a, b, c, scale, w1, w4):
    teeth = coaxial_teeth(kind, a, b, c)
    if teeth is None:
        return
    m1 = schemes.scheme(kind, radii=teeth)
    m2 = schemes.scheme(kind, radii=tuple(sp.Integer(scale) * z / 7 for z in teeth))
    known = {"1": sp.Rational(w1.numerator, w1.denominator), "4": sp.Rational(w4.numerator, w4.denominator)}
    try:
        s1 = m1.speeds(known)
    except SingularConfigurationError:
        return
    s2 = m2.speeds(known)
    assert dict(s1) == dict(s2)
    assert m1.ratio("1", "H", fixed="4").rhs == m2.ratio("1", "H", fixed="4").rhs


@settings(deadline=None)
@given(st.sampled_from(KINDS), st.integers(12, 400), st.integers(12, 400), st.integers(12, 400))
def test_speeds_are_linear_in_the_known_speeds(kind, a, b, c):
    teeth = coaxial_teeth(kind, a, b, c)
    if teeth is None:
        return
    m = schemes.scheme(kind, teeth=teeth)
    try:
        one = m.speeds({"1": 1, "4": 0})
    except SingularConfigurationError:
        return
    other = m.speeds({"1": 0, "4": 1})
    both = m.speeds({"1": 3, "4": -2})
    for link in both:
        assert both[link] == 3 * one[link] - 2 * other[link]


def test_symbolic_laws_have_no_module():
    law = schemes.two_row("II", teeth=True).ratio("H", "1", fixed="4").rhs
    assert S.module() not in law.free_symbols


# ---- every scheme, every admissible choice of known speeds, exact contact at both pitch points
PLANET = {"AI1": "2", "AI": "23", "AA": "23", "II": "23"}
#: Is the central gear of mesh 1-2, and of the mesh with gear 4, internal?  (paper's fig. 1)
INTERNAL = {"AI1": (False, True), "AI": (False, True), "AA": (False, False), "II": (True, True)}
KNOWN = [("1", "4"), ("1", "H"), ("4", "H"), ("1", "planet"), ("H", "planet")]


def pitch_point_mismatch(kind, radii, w):
    """Tangential velocity of each pitch point as a point of the central gear minus as a point of
    the planet, exactly: a central gear of radius R at speed w_g moves it at w_g R; the planet,
    whose axis is at the arm a from the main axis, at w_H a + w_p (R - a); typed here from
    the geometry, independent of the engine's contact conditions."""
    r1, r2, _r3, r4 = radii
    in1, _in4 = INTERNAL[kind]
    arm = r1 - r2 if in1 else r1 + r2
    wp = w[PLANET[kind]]
    return [w[g] * R - (w["H"] * arm + wp * (R - arm)) for g, R in (("1", r1), ("4", r4))]


@settings(deadline=None)
@given(st.sampled_from(KINDS), st.integers(12, 400), st.integers(12, 400), st.integers(12, 400),
       st.sampled_from(KNOWN), st.fractions(-1000, 1000), st.fractions(-1000, 1000))
def test_every_scheme_satisfies_both_contacts_for_any_known_speeds(kind, a, b, c, known, wa, wb):
    teeth = coaxial_teeth(kind, a, b, c)
    if teeth is None:
        return
    m = schemes.scheme(kind, teeth=teeth, module=2)
    names = [PLANET[kind] if k == "planet" else k for k in known]
    given_speeds = dict(zip(names, (sp.Rational(wa.numerator, wa.denominator), sp.Rational(wb.numerator, wb.denominator))))
    try:
        w = dict(m.speeds(given_speeds))
    except SingularConfigurationError:
        return
    assert all(w[k] == v for k, v in given_speeds.items())
    radii = [z for z in teeth] if kind != "AI1" else [teeth[0], teeth[1], teeth[1], teeth[2]]
    assert pitch_point_mismatch(kind, radii, w) == [0, 0]


# ---- compiled functions agree with exact evaluation
@settings(deadline=None)
@given(st.sampled_from(KINDS), st.lists(st.integers(12, 400), min_size=4, max_size=4),
       st.fractions(-1000, 1000, max_denominator=1000), st.fractions(-1000, 1000, max_denominator=1000))
def test_compiled_speeds_agree_with_exact_evaluation(kind, teeth, w1, w4):
    import symkin

    m = schemes.scheme(kind, teeth=True)
    laws = m.speeds({"1": S.omega("1"), "4": S.omega("4")}).laws()
    f = symkin.compile(list(laws))
    values = {**{S.teeth(g): z for g, z in zip("1234", teeth)}, S.omega("1"): w1, S.omega("4"): w4}
    by_name = {str(s): v for s, v in values.items()}
    exact_values = {s: sp.Rational(v.numerator, v.denominator) if hasattr(v, "numerator") else v for s, v in values.items()}
    # not a singular tooth set (z2 = z3 in a two-row scheme), where both routes divide by zero
    assume(all(sp.fraction(sp.together(law.rhs))[1].subs(exact_values) != 0 for law in laws))
    exact = [law.rhs.subs(exact_values) for law in laws]
    got = f(*(float(by_name[a]) for a in f.args))
    scale = 1 + abs(float(w1)) + abs(float(w4))
    for g, e in zip(got, exact):
        assert float(g) == pytest.approx(float(e), rel=1e-9, abs=1e-9 * scale)


# ---- LaTeX output parses back (SymPy's parser, antlr backend) to the same law
def _undo_calls(expr):
    """SymPy's LaTeX parser reads ``r_{1} \\left(x\\right)`` as a call r_1(x): make it a product."""
    from sympy.core.function import AppliedUndef

    calls = {c: sp.Symbol(c.func.__name__) * c.args[0] for c in expr.atoms(AppliedUndef) if len(c.args) == 1}
    return expr.xreplace(calls) if calls else expr


@settings(deadline=None)
@given(st.sampled_from(KINDS), st.sampled_from(["ratio", "speed", "particle"]), st.sampled_from(["1", "4", "H"]),
       st.lists(st.fractions(1, 50, max_denominator=20), min_size=8, max_size=8))
def test_latex_output_parses_back_to_the_same_law(kind, what, link, point):
    pytest.importorskip("antlr4")
    from sympy.parsing.latex import parse_latex

    import symkin

    m = schemes.scheme(kind, teeth=what == "ratio")
    if what == "ratio":
        other = "H" if link != "H" else "1"
        expr = m.ratio(link, other, fixed="4" if "4" not in (link, other) else "1").rhs
    elif what == "speed":
        expr = m.speeds({"1": S.omega("1"), "4": S.omega("4")})[PLANET[kind] if link == "4" else link]
    else:  # a particle's velocity component: sums of products of trig functions
        motion = m.motion({"1": S.omega("1"), "4": S.omega("4")})
        expr = motion.particle(PLANET[kind], (sp.Rational(point[0]), sp.Rational(point[1]))).velocity[0]
    parsed = _undo_calls(parse_latex(symkin.latex(expr)))
    names = {sp.latex(s).lstrip("\\"): s for s in expr.free_symbols}
    assert {str(s) for s in parsed.free_symbols} <= set(names), (parsed, names)
    parsed = parsed.xreplace({s: names[str(s)] for s in parsed.free_symbols})
    at = {s: sp.Rational(v.numerator, v.denominator) for s, v in zip(sorted(expr.free_symbols, key=str), point)}
    if S.t in expr.free_symbols:
        at[S.t] = sp.Rational(3, 7)
    want = sp.N(expr.subs(at), 30)
    assume(want.is_finite)  # not at a singular point of the law (r2 = r3, say)
    assert sp.N(parsed.subs(at), 30) == pytest.approx(want, rel=1e-20, abs=1e-20)
