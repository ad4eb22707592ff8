"""Kladova, Saprykin & Shebanov (2010): helical stepped planets with balanced axial forces, reproduced.

Everything on the "derived" side comes from symkin: the planet statics
(:mod:`symkin.statics`), the ratio, coaxiality and assembly conditions of the engine,
the tooth-number equations solved from them, the existence regions and the synthesis
(:mod:`symkin.mechanisms.helical.balanced`).  The published forms below are transcribed from the
paper (OCR in shared/papers), for comparison only.  Where a printed form disagrees, the
verdict says whether an alternative reading reproduces it (a slip) or an independent
route (a hand derivation typed here, never the engine) confirms the derived form (an
error); OCR damage, when suspected, is named as a hypothesis.

Section 1.1 of the paper is headed "AA", but its equations (1)-(7) are those of the
stepped external-internal (AI) planet: they are compared with the AI derivation, and the
heading is a check of its own.  The true AA equations (which the paper does not write)
are derived and checked on the 2009 paper's AA example (extensions).
"""

from __future__ import annotations

import itertools
import math
from functools import cache
from pathlib import Path

import numpy as np
import sympy as sp

from symkin import schemes
from symkin import symbols as S
from symkin.mechanisms.helical import balanced as HS
from symkin.mechanisms.helical.balanced import DELTA, LAMBDA, RATIO, K, P, Q, X, Z
from symkin.numeric import compile
from symkin.papers.checks import (
    Check,
    Comparison,
    Kind,
    PrintedItem,
    alternative,
    annotate,
    compare_claim,
    compare_symbolic,
    confirmation,
    gather,
    judge,
    vanishes,
)
from symkin.parsing import parse_number
from symkin.statics import balancing_hands, planet_forces, planet_statics

KEY = "kladova2010"
CITATION = (
    "O. Yu. Kladova, V. N. Saprykin, I. G. Shebanov (KhAI), Synthesis of planetary mechanisms of types AA "
    "and II with helical cylindrical gears whose axial forces are balanced, 2010"
)

i, x, k, delta, lam = RATIO, X, K, DELTA, LAMBDA
z1, z2, z3, z4 = (Z[n] for n in (1, 2, 3, 4))
s = sp.sin(sp.pi / k)
a_tw12, a_tw34 = HS.ALPHA_TW12, HS.ALPHA_TW34
a_t12, a_t34 = HS.ALPHA_T12, HS.ALPHA_T34
b12, b34 = HS.BETA12, HS.BETA34
m12, m34 = HS.M12, HS.M34
bw2, bw3 = sp.Symbol("beta_w2", positive=True), sp.Symbol("beta_w3", positive=True)
r2, r3 = S.radius("2"), S.radius("3")
C = sp.cos(a_tw34) * sp.cos(b34) / (sp.cos(a_tw12) * sp.cos(b12))  # the paper's cosine group in (6)

# ---- published forms (for comparison only)
PUBLISHED_BALANCE = 2 * r2 / (2 * r3)  # tan(beta12)/tan(beta34) = d_w2/d_w3 (d_w = 2 r_w): the paper's [1], not printed here
PUBLISHED_HEADING = "AA"  # "1.1. Simple planetary mechanism of type AA [2]"
PUBLISHED = {
    "(1)": 1 + z2 * z4 / (z1 * z3),
    "(2)": sp.Eq(lam * (z1 + z2) * sp.cos(a_tw34) / sp.cos(a_tw12), (z4 - z3) * sp.cos(b12) / sp.cos(b34)),
    "(3)": sp.Eq(z1 / k * (1 + z2 * z4 / (z1 * z3)) - z2 / z3 * Q, P),
    "(4)": z1 * (i - 1) / x,  # Z4
    "from (34) line": sp.Eq(z1 / k * i - x * Q, P),  # printed after "from (34)"
    "(5)": k * (P + Q * x) / i,  # Z1
    # "transform (2)": the lines before the product line (the first printed line holds two equations)
    "(2) transformed": (
        sp.Eq(z1 + z2, (z4 - z2 / x) / lam * sp.cos(a_tw12) / sp.cos(a_tw34) * sp.cos(b12) / sp.cos(b34)),
        sp.Eq(z1 + z2, (z4 * x - z2) / (x * lam) * sp.cos(a_tw12) / sp.cos(a_tw34) * sp.cos(b12) / sp.cos(b34)),
        sp.Eq(x * lam * (z1 + z2) * sp.cos(a_tw34) / sp.cos(a_tw12) * sp.cos(b34) / sp.cos(b12), z1 * (i - 1) / x * x - z2),
        sp.Eq(x * lam * z1 * C + x * lam * z2 * C, z1 * (i - 1) - z2),
    ),
    "(6) step": sp.Eq(z2 * (x * lam * C + 1), z1 * (i - 1 - x * lam * C)),  # the product line
    "(6) step solved": z1 - (i - 1 - x * lam * C) / (x * lam * C + 1),  # Z2, "Z2 = Z1 - ..." as printed
    "(6) identity": (i - 1 - C, sp.Symbol("d_w2") / sp.Symbol("d_w3")),  # "i - 1 - C = d_w2/d_w3" as printed
    "(6)": z1 * (delta + 1) / (delta + 1),  # Z2 as printed (evaluates to Z1)
    "(7)": z2 / x,  # Z3
    "(8)": k * (P - Q * x) / i,  # Z1 (II)
    "(9)": z2 * (1 - i * delta) / (1 - delta),  # printed as "Z1 = Z2 (1 - i d)/(1 - d)"
    "(10)": z2 / x,  # Z3 (II)
    "(11)": z1 * (1 - i) / x,  # Z4 (II)
}
#: The equation references of section 1.1 that the line after "from (34)" may rest on.
SECTION_EQUATIONS = ("(1)", "(2)", "(3)", "(4)")
PRINTED_REFERENCE = "(34)"
# Table 1: (lower, upper) bounds of i_1H^(4), columns "x <= 1" and "x >= 1" (the OCR prints "xx")
PUBLISHED_TABLE = {
    ("AA", "delta < 1"): (1 + delta, (1 - delta) / (1 - delta * s)),
    ("AA", "delta > 1"): ((1 - delta) / (1 - delta * s), 1 - delta),
    ("II", "delta < 1"): ((1 - delta) / (1 + delta * s), 1 - delta),
    ("II", "delta > 1"): (1 - delta, (1 - delta) / (1 + s)),
    ("AI", "delta < 1"): (1 + delta, (1 + delta) / (1 - delta * s)),
    ("AI", "delta > 1"): (1 + delta, (1 + delta) / (1 - s)),
}
#: Where the brute-force route of Table 1 is evaluated: d_w2/d_w3 and satellite counts.
TABLE_SAMPLES = {"delta < 1": (sp.Rational(1, 4), sp.Rational(1, 2), sp.Rational(4, 5)),
                 "delta > 1": (sp.Rational(6, 5), sp.Rational(3, 2), sp.Integer(3))}
TABLE_K = (3, 4, 6)
#: Examples of the 2009 paper (equal modules, spur, coaxial), rebuilt from the tooth equations.
EXAMPLE_AA_2009 = (54, 45, 44, 55)
EXAMPLE_II_2009 = (200, 99, 100, 201)
#: The synthesis example: AI, i = 25 within 2 %, 3 satellites, m_n12 = 2 mm, m_n34 = 2.5 mm.
SYNTHESIS_EXAMPLE = dict(scheme="AI", ratio=25, tolerance=parse_number("0.02"), satellites=3,
                         normal_modules=(2, parse_number("2.5")),
                         beta_min_deg=8, beta_max_deg=30, teeth_min=17, teeth_max=110, top=20)

PRINTED_ITEMS = (
    PrintedItem("1.1 heading", "section 1.1 is headed 'simple planetary mechanism of type AA'"),
    PrintedItem("(1)", "ratio condition i_1H^(4) = 1 + Z2 Z4/(Z1 Z3)"),
    PrintedItem("(2)", "coaxiality of the helical meshes with lambda, transverse working pressure and helix angles"),
    PrintedItem("(3)", "assembly condition with integers P, Q and k satellites"),
    PrintedItem("(4)", "Z4 = Z1 (i - 1)/x from (1)"),
    PrintedItem("from (34)", "the reference 'from (34)' before the assembly condition in i"),
    PrintedItem("from (34) line", "Z1 i/k - x Q = P"),
    PrintedItem("(5)", "Z1 = k (P + Q x)/i"),
    PrintedItem("(2) transformed", "three lines rewriting (2) with x and (4)"),
    PrintedItem("(6) step", "Z2 (x lambda C + 1) = Z1 (i - 1 - x lambda C), C the cosine group"),
    # one garbled block (possibly OCR damage), three lines: one item, so its error counts once
    PrintedItem("(6)", "the block printed as (6): Z2 = Z1 - (i - 1 - x lambda C)/(x lambda C + 1), "
                       "i - 1 - C = d_w2/d_w3 and Z2 = Z1 (d_w2/d_w3 + 1)/(d_w2/d_w3 + 1), as printed"),
    PrintedItem("(7)", "Z3 = Z2/x"),
    PrintedItem("1.2 II", "II: the expressions follow as for AA from ratio, coaxiality and assembly [2]",
                "a statement of method; its results (8)-(11) are checked"),
    PrintedItem("(8)", "II: Z1 = k (P - Q x)/i"),
    PrintedItem("(9)", "II: Z1 = Z2 (1 - i d_w2/d_w3)/(1 - d_w2/d_w3) as printed"),
    PrintedItem("(10)", "II: Z3 = Z2/x"),
    PrintedItem("(11)", "II: Z4 = Z1 (1 - i)/x"),
    *(PrintedItem(f"Table 1 {kd}, {case}", f"{kd}: the interval of i_1H^(4) for d_w2/d_w3 {case[6:]}")
      for kd in ("AA", "II", "AI") for case in ("delta < 1", "delta > 1")),
    PrintedItem("Table 1 heads", "the column heads 'xx <= 1', 'xx >= 1'",
                "OCR-damaged heads; the derivation splits on d_w2/d_w3 (the larger rim), and the rows are compared so"),
    PrintedItem("Table 1 analysis", "AA and II need d_w2/d_w3 != 1; AI exists for d_w2/d_w3 <= 1 and >= 1"),
    PrintedItem("neighbour condition", "the neighbour condition is taken as for unshifted spur gears [2]",
                "a modelling choice the derivation of Table 1 adopts, not a result"),
    PrintedItem("conclusions", "helical trains transmit more power than spur ones of the same size",
                "needs a load-capacity model the paper does not give"),
)


def _check(label: str, description: str, derived, published, comparison: Comparison, **kw) -> Check:
    return Check.make(KEY, label, description, derived, published, comparison, **kw)


def checks() -> list[Check]:
    """Every equation and table entry of the paper, derived and compared; the synthesis example."""
    return gather(KEY, _balance_checks, _section_11_checks, _section_12_checks, _true_aa_checks, _table_checks,
                  _synthesis_checks)


# --------------------------------------------------------------------------- balance (the paper's [1]: extensions)
def _balance_checks() -> list[Check]:
    out = []
    ext = {"kind": Kind.EXTENSION}
    st = planet_statics(schemes.two_row("AI"))
    ft2, ft3 = sp.Symbol("F_t2", positive=True), sp.Symbol("F_t3", positive=True)
    dw2, dw3 = sp.Symbol("d_w2", positive=True), sp.Symbol("d_w3", positive=True)
    published_torque = sp.Eq(ft2 * dw2, ft3 * dw3)
    out.append(_check(
        "planet torque balance", "AI planet: moments of the two tangential forces about its axis cancel (the paper's [1])",
        st.magnitudes, published_torque,
        compare_symbolic(st.magnitudes.lhs - st.magnitudes.rhs,
                         (published_torque.lhs - published_torque.rhs).subs({dw2: 2 * r2, dw3: 2 * r3})), **ext,
    ))
    out.append(_check(
        "balance", "axial forces cancel: tan(beta_w2)/tan(beta_w3) = d_w2/d_w3 (helix angles on the working cylinders; [1])",
        st.condition, sp.Eq(sp.tan(bw2) / sp.tan(bw3), PUBLISHED_BALANCE, evaluate=False),
        compare_symbolic(st.condition.rhs, PUBLISHED_BALANCE), **ext,
    ))
    for kind in ("AA", "II"):
        other = planet_statics(schemes.two_row(kind))
        out.append(_check(
            f"balance {kind}", f"{kind} planet: the same condition (only the force directions differ)",
            other.condition, sp.Eq(sp.tan(bw2) / sp.tan(bw3), PUBLISHED_BALANCE, evaluate=False),
            compare_symbolic(other.condition.rhs, PUBLISHED_BALANCE), **ext,
        ))
    ref = HS.balance_condition()
    dw_ratio = HS.working_diameter_ratio(shifted=True)
    out.append(_check(
        "balance, reference angles", "tan(beta12)/tan(beta34) with reference helix angles vs d_w2/d_w3",
        ref, sp.Eq(sp.tan(b12) / sp.tan(b34), dw_ratio, evaluate=False),
        compare_symbolic(ref.rhs, dw_ratio, under={a_tw12: a_t12, a_tw34: a_t34}), **ext,
    ))
    hands = {kind: balancing_hands(kind) for kind in HS.SCHEMES}
    names = "; ".join(f"{kd}: " + ", ".join(f"{g} {'R' if h > 0 else 'L'}" for g, h in zip("1234", hd)) for kd, hd in hands.items())
    out.append(_check(
        "balance hands", "rims 2 and 3 must have the same hand (equal leads); central gears follow",
        f"same hand on both rims; {names}", "both rims of the same hand",
        compare_claim(bool(st.same_hand), "derived from the statics (h2 = h3) and the helix tangency at each pitch point: "
                      "an external mesh takes opposite hands, an internal one equal hands"), **ext,
    ))
    return out


# --------------------------------------------------------------------------- section 1.1
def _lambda_from_2(coax: sp.Eq) -> sp.Expr | None:
    """lambda for which the printed (2) equals a derived coaxiality, None if no constant does."""
    pub = PUBLISHED["(2)"]
    # simplified once, here (sp.solve's own simplification of the root is ~10x the solve)
    (value,) = sp.solve(sp.Eq(coax.lhs / coax.rhs, pub.lhs / pub.rhs), lam, simplify=False) or (None,)
    if value is None:
        return None
    value = sp.simplify(value)
    varying = {z1, z2, z3, z4, a_tw12, a_tw34, b12, b34}
    return None if value.free_symbols & varying else value


def _scheme_of(printed_relation, derived_of) -> list[str]:
    """The schemes whose derived relation reproduces a printed one."""
    return [kd for kd in HS.SCHEMES if derived_of(kd, printed_relation)]


def _section_11_checks() -> list[Check]:
    out = []
    law = {kd: HS.ratio_law(kd).rhs for kd in HS.SCHEMES}
    coax = {kd: HS.helical_coaxiality(kd) for kd in HS.SCHEMES}
    # the heading: which scheme do (1) and (2) describe?
    by_ratio = [kd for kd in HS.SCHEMES if compare_symbolic(law[kd], PUBLISHED["(1)"]).verdict.agrees]
    lams = {kd: _lambda_from_2(coax[kd]) for kd in HS.SCHEMES}
    by_coax = [kd for kd in HS.SCHEMES if lams[kd] is not None]
    derived_scheme = by_ratio[0] if len(by_ratio) == 1 else f"{by_ratio}"
    coax_scheme = by_coax[0] if len(by_coax) == 1 else f"{by_coax}"
    same = lambda a_, b_: compare_claim(a_ == b_, f"{a_} and {b_}")  # noqa: E731
    out.append(_check(
        "1.1 heading", "the scheme equations (1)-(7) describe, from the ratio law (1)",
        derived_scheme, PUBLISHED_HEADING,
        judge(compare_claim(derived_scheme == PUBLISHED_HEADING,
                            f"of the derived ratio laws ({'; '.join(f'{kd}: {v}' for kd, v in law.items())}) only "
                            f"{' and '.join(by_ratio) or 'none'} equal{'s' if len(by_ratio) == 1 else ''} the printed (1)"),
              confirmation=confirmation(f"the coaxiality (2): only {' and '.join(by_coax) or 'none'} "
                                        f"admit{'s' if len(by_coax) == 1 else ''} a constant lambda", coax_scheme,
                                        derived_scheme, same),
              hypothesis="the equations of the AI paper [1] were carried over under an AA heading"),
    ))
    out.append(_check("(1)", "ratio i_1H^(4) of the stepped planet in section 1.1 (the AI derivation)",
                      law["AI"], PUBLISHED["(1)"], compare_symbolic(law["AI"], PUBLISHED["(1)"])))
    # (2): lambda is not defined in the paper: solve for it; (2) has the derived form if it is a constant
    lam_value = lams["AI"]
    pub = PUBLISHED["(2)"]
    out.append(_check(
        "(2)", "coaxiality a_w12 = a_w34 of helical meshes (AI); lambda, undefined in the paper, solved from the comparison",
        coax["AI"], pub,
        compare_claim(lam_value is not None,
                      f"(2) equals the derived coaxiality exactly when lambda = {lam_value}, a constant of the two tool "
                      "profiles (free of the tooth numbers, helix and working pressure angles); with lambda read as the "
                      "plain module ratio m_n12/m_n34 it would hold only when alpha_t12 = alpha_t34"
                      if lam_value is not None else "no lambda free of the tooth numbers and angles makes (2) the derived coaxiality"),
        rests_on="lambda, which the paper does not define, solved from this very comparison (the check shows that "
                 "one constant lambda makes (2) hold, not that the paper's lambda is that constant)",
    ))
    # (3) assembly
    asm = HS.assembly_condition("AI")
    derived_teeth = (asm.lhs - asm.rhs).subs(RATIO, law["AI"])
    pub3 = PUBLISHED["(3)"]
    out.append(_check("(3)", "assembly of k satellites with integers P, Q (AI)", sp.Eq(derived_teeth + P, P),
                      pub3, compare_symbolic(derived_teeth, pub3.lhs - pub3.rhs)))
    # the line after "from (34)", and the reference itself
    line = PUBLISHED["from (34) line"]
    with_x = (asm.lhs - asm.rhs).subs(z2, x * z3)
    out.append(_check("from (34) line", "the assembly condition written with i and x = Z2/Z3", sp.Eq(sp.expand(with_x + P), P),
                      line, compare_symbolic(with_x, line.lhs - line.rhs)))
    sources = _line_sources()
    joined = ["(" + "".join(n.strip("()") for n in pair) + ")" for pair in sources]
    derived_refs = " or ".join(" with ".join(pair) for pair in sources)
    out.append(_check(
        "from (34)", "the equations the line 'Z1 i/k - x Q = P' follows from (substituted and compared)",
        derived_refs, f"from {PRINTED_REFERENCE}",
        judge(compare_claim(any(PRINTED_REFERENCE in pair for pair in sources),
                            f"the line follows from {derived_refs}; the paper numbers its equations (1)-(11)"),
              alternative=alternative("the reference is the pair of equation numbers written without a separator",
                                      joined, PRINTED_REFERENCE,
                                      lambda v, p: compare_claim(p in v, f"the pairs read {', '.join(v)}, printed {p}"))),
    ))
    # (4)-(7): the tooth chain
    ch = HS.tooth_equations("AI").chain
    for label, zz, what in (("(4)", z4, "Z4 from the ratio"), ("(5)", z1, "Z1 from assembly"), ("(7)", z3, "Z3 = Z2/x")):
        out.append(_check(label, f"AI: {what}", sp.Eq(zz, ch[zz]), sp.Eq(zz, PUBLISHED[label]),
                          compare_symbolic(ch[zz], PUBLISHED[label])))
    out += _six_checks(ch, lam_value)
    return out


def _line_sources() -> list[tuple[str, str]]:
    """Pairs of section 1.1's printed equations from which the printed line follows.

    Each pair is tried by substitution: (3) with (1) or (4) solved for Z4, and x = Z2/Z3.
    """
    line = PUBLISHED["from (34) line"]
    target = sp.expand((line.lhs - line.rhs).subs(x, z2 / z3))
    printed = {
        "(1)": sp.Eq(i, PUBLISHED["(1)"]),
        "(2)": PUBLISHED["(2)"],
        "(3)": PUBLISHED["(3)"],
        "(4)": sp.Eq(z4, PUBLISHED["(4)"].subs(x, z2 / z3)),
    }
    found = []
    # Z4 from each printed equation that has it, solved once (each is tried with every other);
    # not simplified: the pair is decided on the expanded difference by exact means
    z4_from = {n: (sp.solve(eq, z4, simplify=False) or (None,)) for n, eq in printed.items() if eq.has(z4)}
    for first, second in itertools.permutations(SECTION_EQUATIONS, 2):
        a_eq, b_eq = printed[first], printed[second]
        if not a_eq.has(P) or not b_eq.has(z4):
            continue
        (z4_value,) = z4_from[second]
        if z4_value is None:
            continue
        result = sp.expand((a_eq.lhs - a_eq.rhs).subs(z4, z4_value))
        if vanishes(result - target):  # exact; a rational function is decided by cancelling
            found.append((first, second))
    return found


def _six_checks(ch: dict, lam_value: sp.Expr | None) -> list[Check]:
    """(6): the product line, its solution as printed, the identity and Z2, against the AI chain."""
    out = []
    z2_derived = ch[z2]  # Z2 in Z1, i and delta = d_w2/d_w3
    dw_ratio = HS.working_diameter_ratio(shifted=True)
    paper = {x: z2 / z3, lam: lam_value} if lam_value is not None else {x: z2 / z3}
    step_printed = PUBLISHED["(6) step"]
    # the root as one fraction (sp.solve's own simplification takes ~50x as long for the same form)
    (step_solved,) = sp.solve(step_printed, z2, simplify=False)
    step_solved = sp.together(step_solved)
    derived_step = z2_derived.subs(delta, dw_ratio)
    out.append(_check(
        "(6) step", "AI: coaxiality with Z4 from (4), the product line before d_w2/d_w3 is introduced",
        sp.Eq(z2, derived_step), step_printed,
        compare_symbolic(derived_step, step_solved.subs(paper)),
    ))
    # the lines that transform (2) into the product line: each solved for Z2 (Z4 where it stands from the derived
    # chain, the paper's (4)), against the derived Z2; lambda as solved in (2)
    for n, line in enumerate(PUBLISHED["(2) transformed"], 1):
        (solved,) = sp.solve(line.subs(z4, ch[z4]), z2, simplify=False)
        out.append(_check(
            f"(2) transformed, line {n}", f"AI: line {n} of the transformation of (2) (x = Z2/Z3, Z4 from (4)), solved for Z2",
            sp.Eq(z2, derived_step), line, compare_symbolic(derived_step, sp.together(solved).subs(paper)),
            item="(2) transformed"))
    printed_solved = PUBLISHED["(6) step solved"]
    out.append(_check(
        "(6) step solved", "the product line solved for Z2, as printed ('Z2 = Z1 - ...'): the first line of the block (6)",
        sp.Eq(z2, derived_step), sp.Eq(z2, printed_solved),
        judge(compare_symbolic(derived_step, printed_solved.subs(paper)),
              confirmation=confirmation("the paper's own product line (6) step, solved for Z2 by SymPy",
                                        step_solved.subs(paper), derived_step),
              hypothesis="the product Z1 (...) lost its multiplication and gained a '-' (OCR damage or a typo)"),
        item="(6)",
    ))
    lhs_printed, _ = PUBLISHED["(6) identity"]
    printed_identity = lhs_printed.subs(paper)
    # by hand: d_w = m_n z cos(alpha_t) / (cos(beta) cos(alpha_tw)) for each rim (textbook, typed here)
    hand = (m12 * z2 * sp.cos(a_t12) / (sp.cos(b12) * sp.cos(a_tw12))) / (m34 * z3 * sp.cos(a_t34) / (sp.cos(b34) * sp.cos(a_tw34)))
    out.append(_check(
        "(6) identity", "d_w2/d_w3 of the helical rims, against the printed 'i - 1 - C = d_w2/d_w3'",
        sp.Eq(sp.Symbol("d_w2") / sp.Symbol("d_w3"), dw_ratio), sp.Eq(PUBLISHED["(6) identity"][1], lhs_printed, evaluate=False),
        judge(compare_symbolic(dw_ratio, printed_identity),
              confirmation=confirmation("working pitch diameters by hand, d_w = m_n z cos(alpha_t)/(cos(beta) cos(alpha_tw))",
                                        hand, dw_ratio),
              hypothesis="the factor x lambda became 'i - 1 -' (the fragment missing from (6)'s numerator one line below)"),
        item="(6)",
    ))
    # (6): Z2 from Z1, i, delta; the hand route: spur gears of one module (delta = x = Z2/Z3)
    printed6 = PUBLISHED["(6)"]
    out.append(_check(
        "(6)", "AI: Z2 from Z1, i and d_w2/d_w3, against the printed Z1 (d + 1)/(d + 1)",
        sp.Eq(z2, z2_derived), sp.Eq(z2, printed6),
        judge(compare_symbolic(z2_derived, printed6),
              confirmation=confirmation("by hand for unshifted spur gears of one module (d_w2/d_w3 = Z2/Z3): "
                                        "Z1 + Z2 = Z4 - Z3, i = 1 + Z2 Z4/(Z1 Z3)", _spur_by_hand("AI"), z2_derived),
              hypothesis="the numerator i - 1 - d_w2/d_w3 was replaced by a copy of the denominator (OCR damage)"),
    ))
    return out


def _spur_by_hand(kind: str) -> sp.Expr:
    """Z2 in Z1, i and delta for spur gears of one module, from textbook relations typed here.

    AI: z1 + z2 = z4 - z3, i = 1 + z2 z4/(z1 z3); II: z1 - z2 = z4 - z3, i = 1 - z2 z4/(z1 z3);
    delta = d_w2/d_w3 = z2/z3 (one module, unshifted).
    """
    zz1, zz2, zz3, zz4, ii, dd = sp.symbols("zz1 zz2 zz3 zz4 ii dd", positive=True)
    if kind == "AI":
        eqs = [zz1 + zz2 - (zz4 - zz3), ii - (1 + zz2 * zz4 / (zz1 * zz3)), dd - zz2 / zz3]
    else:
        eqs = [zz1 - zz2 - (zz4 - zz3), ii - (1 - zz2 * zz4 / (zz1 * zz3)), dd - zz2 / zz3]
    (sol,) = sp.solve(eqs, [zz2, zz3, zz4], dict=True, simplify=False)  # factored below
    return sp.factor(sol[zz2].subs({zz1: z1, ii: i, dd: delta}))


# --------------------------------------------------------------------------- section 1.2 (II)
def _section_12_checks() -> list[Check]:
    out = []
    ch = HS.tooth_equations("II").chain
    flipped = compare_symbolic(ch[z1].subs(Q, -Q), PUBLISHED["(8)"])
    out.append(_check("(8)", "II: Z1 from assembly (the sign of the free integer Q is a convention)",
                      sp.Eq(z1, ch[z1]), sp.Eq(z1, PUBLISHED["(8)"]),
                      annotate(flipped, "with Q -> -Q in the derived form (Q runs over all integers, so both describe "
                                        "the same tooth sets)")))
    # (9) as printed: Z1 = Z2 (1 - i d)/(1 - d); derived Z2 = Z1 (...)/(...), solved for Z1
    (z1_of_z2,) = sp.solve(sp.Eq(z2, ch[z2]), z1)
    zz = EXAMPLE_II_2009
    vals = {z1: zz[0], z2: zz[1], z3: zz[2], z4: zz[3]}
    i_ex = HS.ratio_law("II").rhs.subs(vals)
    d_ex = sp.Rational(zz[1], zz[2])
    printed_z1 = PUBLISHED["(9)"].subs({z2: zz[1], i: i_ex, delta: d_ex})
    derived_z1 = z1_of_z2.subs({z2: zz[1], i: i_ex, delta: d_ex})
    by_hand = _spur_by_hand("II")
    (hand_z1,) = sp.solve(sp.Eq(z2, by_hand), z1)
    out.append(_check(
        "(9)", "II: Z1 from Z2, i and d_w2/d_w3, against the printed Z2 (1 - i d)/(1 - d)",
        sp.Eq(z1, sp.factor(z1_of_z2)), sp.Eq(z1, PUBLISHED["(9)"]),
        annotate(judge(compare_symbolic(z1_of_z2, PUBLISHED["(9)"]),
                       confirmation=confirmation("by hand for unshifted spur gears of one module: Z1 - Z2 = Z4 - Z3, "
                                                 "i = 1 - Z2 Z4/(Z1 Z3), d_w2/d_w3 = Z2/Z3", hand_z1, z1_of_z2),
                       hypothesis="Z1 and Z2 swapped and '1 - i - d' printed '1 - i d' (OCR damage or typos)"),
                 f"on the 2009 paper's II example z = {zz} (d_w2/d_w3 = {d_ex}, i = {i_ex}) the printed form gives "
                 f"Z1 = {printed_z1} = {float(printed_z1):g}, the derived one Z1 = {derived_z1}"),
    ))
    for label, zz_, what in (("(10)", z3, "Z3 = Z2/x"), ("(11)", z4, "Z4 from the ratio")):
        out.append(_check(label, f"II: {what}", sp.Eq(zz_, ch[zz_]), sp.Eq(zz_, PUBLISHED[label]),
                          compare_symbolic(ch[zz_], PUBLISHED[label])))
    out.append(_rebuild_example("II", EXAMPLE_II_2009, 1, "(8)-(11) rebuild the 2009 II example"))
    return out


def _rebuild_example(kind: str, teeth: tuple[int, int, int, int], k_value: int, label: str) -> Check:
    """Put an example's i, x, d_w2/d_w3, k, P, Q into the derived tooth equations (an extension)."""
    vals = dict(zip((z1, z2, z3, z4), teeth))
    i_ex = HS.ratio_law(kind).rhs.subs(vals)
    p_ex, q_ex = HS.assembly_integers(kind, teeth, k_value)
    params = {i: i_ex, x: sp.Rational(teeth[1], teeth[2]), delta: sp.Rational(teeth[1], teeth[2]),
              k: k_value, P: p_ex, Q: q_ex}
    sol = HS.tooth_equations(kind).solution
    rebuilt = tuple(sp.simplify(sol[zz].subs(params)) for zz in (z1, z2, z3, z4))
    ok = all(r.is_Integer and int(r) == t for r, t in zip(rebuilt, teeth))
    detail = (f"i = {i_ex}, x = d_w2/d_w3 = {teeth[1]}/{teeth[2]} (spur, one module, coaxial), k = {k_value}, "
              f"P = {p_ex}, Q = {q_ex} give Z = {rebuilt}")
    return _check(label, f"{kind}: the derived tooth equations on the 2009 paper's example {teeth}", list(rebuilt),
                  list(teeth), compare_claim(ok, detail), kind=Kind.EXTENSION)


# --------------------------------------------------------------------------- true AA (not in the paper)
def _true_aa_checks() -> list[Check]:
    ch = HS.tooth_equations("AA").chain
    out = [_rebuild_example("AA", EXAMPLE_AA_2009, 3, "AA (not in the paper) rebuilds the 2009 AA example")]
    ii = HS.tooth_equations("II").chain
    rel = sp.simplify(ch[z2] + ii[z2])
    same = rel == 0 and all(sp.simplify(ch[zz] - ii[zz]) == 0 for zz in (z1, z3, z4))
    out.append(_check(
        "AA (not in the paper) vs II", "true AA: Z2 = -(II's Z2), Z4 = II's Z4, Z1 and Z3 as in II",
        [sp.Eq(zz, ch[zz]) for zz in (z1, z4, z2, z3)], [sp.Eq(zz, ii[zz]) for zz in (z1, z4, z2, z3)],
        compare_claim(same, f"derived AA Z2 + II Z2 = {rel}: the two schemes share (8), (10), (11) and differ in the sign of (9)"),
        kind=Kind.EXTENSION,
    ))
    return out


# --------------------------------------------------------------------------- Table 1
#: The ends of an interval of i_1H^(4), named where they are printed (the document, report.json).
I_MIN, I_MAX = sp.Symbol("i_min"), sp.Symbol("i_max")


def _bounds(lower, upper) -> list:
    """An interval's two ends labelled: i_min = lower, i_max = upper."""
    return [sp.Eq(I_MIN, lower, evaluate=False), sp.Eq(I_MAX, upper, evaluate=False)]


def _table_checks() -> list[Check]:
    out = []
    for kind in ("AA", "II", "AI"):
        for b in HS.existence_bounds(kind):
            pub_lo, pub_hi = PUBLISHED_TABLE[kind, b.case]
            c_lo, c_hi = compare_symbolic(b.lower, pub_lo), compare_symbolic(b.upper, pub_hi)
            label = f"Table 1 {kind}, {b.case}"
            agree = c_lo.verdict.agrees and c_hi.verdict.agrees
            primary = compare_claim(agree, f"lower: {c_lo.detail}; upper: {c_hi.detail}; range ended by the {b.binding} "
                                           "condition")
            evidence = {}
            if not agree:
                sampled, route_ok, detail = _brute_force(kind, b)
                evidence["confirmation"] = confirmation(
                    "brute force over explicit designs with hand-typed relations (coaxiality, the Willis ratio of the "
                    f"2009 paper, neighbour condition on pitch circles): {detail}",
                    sampled, (b.lower, b.upper), lambda v, d, ok=route_ok: compare_claim(ok, "sampled ranges within "
                                                                                           "1e-3 of the derived ends"))
            out.append(_check(label, f"{kind}: admissible i_1H^(4) for d_w2/d_w3 {b.case[6:]}, k satellites",
                              _bounds(b.lower, b.upper), _bounds(pub_lo, pub_hi),
                              judge(primary, hypothesis=_table_hypothesis(kind, b.case), **evidence)))
    empty = [HS.existence_interval(kd, kk, 1) is None for kd in ("AA", "II") for kk in (2, 3, 4, 6)]
    ai = [HS.existence_interval("AI", kk, d) is not None for kk in (3, 4, 6) for d in (sp.Rational(1, 2), 1, 2)]
    out.append(_check(
        "Table 1 analysis", "AA and II need d_w2/d_w3 != 1; AI exists for d_w2/d_w3 <= 1 and >= 1",
        f"AA, II at d_w2 = d_w3: {'empty' if all(empty) else 'not empty'} for k = 2, 3, 4, 6; AI at d_w2/d_w3 = 1/2, 1, 2: "
        f"{'not empty' if all(ai) else 'empty for some'} for k = 3, 4, 6",
        "AA, II: d_w2/d_w3 != 1; AI: both", compare_claim(all(empty) and all(ai), "at d_w2 = d_w3 both bounds of AA and II "
                                                                                "collapse to i = 0 (exact intervals of the constraints)"),
    ))
    return out


def _table_hypothesis(kind: str, case: str) -> str:
    if kind == "AA" and case == "delta < 1":
        return "the lower bound 1 + d_w2/d_w3 of the AI row was carried into the AA row"
    if kind == "AA" and case == "delta > 1":
        return "the neighbour condition was applied to rim 3, the smaller rim when d_w2 > d_w3"
    return ""


def _brute_force(kind: str, bounds) -> tuple[list, bool, str]:
    """The realisable range of i_1H^(4) at sample (delta, k), sampled over explicit designs.

    Relations typed here (not the engine's): r3 = 1, r2 = delta; coaxiality r1 + r2 = r4 + r3
    (AA), r1 - r2 = r4 - r3 (II), r1 + r2 = r4 - r3 (AI); the ratio of the 2009 paper (17),
    (22), (13): i = 1 -+ r2 r4/(r1 r3); positive radii, internal gears larger; neighbours
    (arm) sin(pi/k) > max(r2, r3).  Returns the sampled (min, max) per sample, whether they
    agree with the derived ends within 1e-3 (relative), and a summary with the count of
    designs outside the printed interval.
    """
    r1 = np.geomspace(1e-3, 1e7, 400_001)
    sampled, ok, outside = [], True, 0
    pub_lo, pub_hi = PUBLISHED_TABLE[kind, bounds.case]
    for d in TABLE_SAMPLES[bounds.case]:
        for kk in TABLE_K:
            dd, sn = float(d), math.sin(math.pi / kk)
            r2_, r3_ = dd, 1.0
            if kind == "AA":
                r4_, arm, sign = r1 + r2_ - r3_, r1 + r2_, -1.0
                valid = (r4_ > 0)
            elif kind == "II":
                r4_, arm, sign = r1 - r2_ + r3_, r1 - r2_, -1.0
                valid = (r4_ > r3_) & (r1 > r2_)
            else:
                r4_, arm, sign = r1 + r2_ + r3_, r1 + r2_, 1.0
                valid = r4_ > r3_
            valid &= arm * sn > max(r2_, r3_)
            ratio = 1.0 + sign * r2_ * r4_ / (r1 * r3_)
            ratio = ratio[valid]
            lo, hi = float(ratio.min()), float(ratio.max())
            sampled.append((d, kk, round(lo, 6), round(hi, 6)))
            ends = [float(e.subs({DELTA: d, K: kk})) for e in (bounds.lower, bounds.upper)]
            for got, want in zip(sorted((lo, hi)), sorted(ends)):
                ok &= abs(got - want) <= 1e-3 * max(1.0, abs(want))
            plo, phi_ = sorted(float(e.subs({DELTA: d, K: kk})) for e in (pub_lo, pub_hi))
            outside += int(np.count_nonzero((ratio < plo) | (ratio > phi_)))
    summary = (f"{len(sampled)} (d_w2/d_w3, k) samples, r_1 from 1e-3 to 1e7; {outside} sampled designs lie outside "
               f"the printed interval; sampled (d, k, min, max): {sampled}")
    return sampled, ok, summary


# --------------------------------------------------------------------------- synthesis example
@cache
def synthesis_example() -> HS.HelicalResult:
    """The synthesis example, every design found (the report lists the best ``top``)."""
    return HS.synthesize_helical(**{**SYNTHESIS_EXAMPLE, "top": None})


def _listed() -> tuple:
    return synthesis_example().designs[: SYNTHESIS_EXAMPLE["top"]]


def _synthesis_checks() -> list[Check]:
    res = synthesis_example()
    listed = _listed()
    forces = [planet_forces(d.train) for d in listed]
    worst = max((f.axial_residual for f in forces), default=math.inf)
    worst_ratio = max((abs(f.ratio - float(d.ratio)) / float(d.ratio) for f, d in zip(forces, listed)), default=math.inf)
    engine = [d.train.ratio == d.ratio for d in listed]
    desc = (f"AI, i = 25 +- 2 %, k = 3, m_n = 2 / 2.5 mm, beta in [8, 30] deg, Z in [17, 110]: "
            f"{res.found} designs, {len(listed)} listed")
    ok = bool(listed) and worst <= 1e-12
    out = [_check(
        "synthesis: axial balance", desc + "; independent 3-D force check, unit input torque",
        f"|F_a2 + F_a3| / max|F_a| <= 1e-12 for all {len(forces)}" if ok else "axial residual above 1e-12",
        "0 (axial forces balanced)",
        compare_claim(ok, f"largest relative axial residual {worst:.1e} over the {len(forces)} listed designs"),
        kind=Kind.EXTENSION,
    )]
    ok_ratio = bool(listed) and worst_ratio <= 1e-12 and all(engine)
    out.append(_check(
        "synthesis: statics vs kinematics", "carrier torque per input torque (statics) vs the engine's i_1H^(4)",
        f"equal to 1e-12 for all {len(forces)}" if ok_ratio else "differ", "i_1H^(4) of each design",
        compare_claim(ok_ratio, f"virtual work: output torque = i x input torque, i from the engine on the built mechanism; "
                                f"largest relative gap {worst_ratio:.1e}"),
        kind=Kind.CONSISTENCY,
    ))
    return out


# --------------------------------------------------------------------------- figures
#: Captions of the figures in the report, and the checks (label prefixes) each illustrates.
REPORT_FIGURES = {
    "kladova2010_existence_regions": ("Existence regions of Table 1 derived: the ratios i_1H^(4) realisable with "
                                      "balanced helical planets against d_w2/d_w3, for k = 3, 4, 6, 12 planets.",
                                      ("Table 1",)),
    "kladova2010_synthesis": ("The synthesis example: every design found, its envelope and ratio error, and the helix "
                              "angles that balance the axial forces.", ("synthesis",)),
}


def figures(folder: Path) -> list[Path]:
    """Existence regions (Table 1) for k = 3, 4, 6, derived and as published; the synthesis example."""
    return _region_figure(folder) + _synthesis_figure(folder)


def region_curve(expr: sp.Expr, d: np.ndarray) -> np.ndarray:
    """``expr`` (a bound of Table 1 in d_w2/d_w3) on the grid ``d`` for a figure, nan where a
    line drawn through the values would join the two branches of a pole: at the sample after
    each sign change of the denominator (the grid need not come near enough to the pole for
    the values to be large there), and where the value is beyond 1e3."""
    v = compile(expr, [DELTA], backend="numpy", stable=False, on_pole="return")(d) * np.ones_like(d)
    den = sp.denom(sp.together(expr))
    if den.has(DELTA):
        dv = compile(den, [DELTA], backend="numpy", stable=False, on_pole="return")(d) * np.ones_like(d)
        v[1:][np.sign(dv[1:]) * np.sign(dv[:-1]) < 0] = np.nan
    return np.where(np.abs(v) < 1e3, v, np.nan)


def _region_figure(folder: Path) -> list[Path]:
    import numpy as np
    from matplotlib.ticker import LogLocator, ScalarFormatter

    from symkin.viz import figures, style

    fig = style.new_figure(style.PAGE, 3.6)
    limits = {"AI": (1, 25), "AA": (-6, 2.2), "II": (-1.6, 1.1)}
    colours = {3: style.PALETTE[0], 4: style.PALETTE[4], 6: style.PALETTE[2], 12: style.PALETTE[3]}
    dashes = {3: "-", 4: "--", 6: "-.", 12: ":"}
    for n, kind in enumerate(("AI", "AA", "II"), 1):
        ax = fig.add_subplot(1, 3, n)
        style.style_axes(ax)
        flagged = False
        for b in HS.existence_bounds(kind):
            first = b.case == "delta < 1"
            d = np.linspace(0.01, 0.999, 400) if first else np.linspace(1.001, 3.5, 400)
            # the end that does not depend on k is the limit of large central gears (r_1 -> oo)
            free_end = b.lower if not b.lower.has(K) else b.upper
            k_end = b.upper if free_end is b.lower else b.lower

            drawn: dict = {}  # a bound drawn again (the region's edge, the published one's comparison): computed once

            def curve(expr, kk=3, d=d, drawn=drawn):
                key = expr.subs(K, kk)
                if key not in drawn:
                    drawn[key] = region_curve(key, d)
                return drawn[key]

            ax.fill_between(d, curve(free_end), curve(k_end), color=style.PALETTE[5], alpha=0.25, lw=0,
                            label="region, k = 3" if first else None)
            ax.plot(d, curve(free_end), color="k", ls="-", lw=1.0, label="large central gears ($r_1 \\to \\infty$)" if first else None)
            for kk, col in colours.items():
                ax.plot(d, curve(k_end, kk), color=col, ls=dashes[kk], lw=1.0,
                        label=f"neighbour bound, k = {kk}" if first else None)
            pub_lo, pub_hi = PUBLISHED_TABLE[kind, b.case]
            for bound, drv in ((pub_lo, b.lower), (pub_hi, b.upper)):
                if np.nanmax(np.abs(curve(bound) - curve(drv))) > 1e-9:  # the checks compare them exactly
                    ax.plot(d, curve(bound), color=style.PALETTE[1], ls=(0, (2, 1)), lw=1.4,
                            label=None if flagged else "published bound (differs), k = 3")
                    flagged = True
        ax.axvline(1, color="0.5", lw=0.6)
        ax.set_ylim(*limits[kind])
        if kind == "AI":
            ax.set_yscale("log")
            ax.yaxis.set_major_locator(LogLocator(subs=(1, 2, 5)))
            ax.yaxis.set_major_formatter(ScalarFormatter())
        ax.set_xlabel(r"$d_{w2}/d_{w3}$ [-]", fontsize=style.FONT)
        ax.set_ylabel(r"$i_{1H}^{(4)}$ [-]", fontsize=style.FONT)
        ax.set_title(f"{kind}", fontsize=style.FONT)
    handles: dict = {}
    for ax in fig.axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles), loc="outside lower center", ncol=3, fontsize=style.SMALL,
               frameon=False)
    fig.suptitle("Kladova et al. 2010, Table 1 derived: ratios realisable with balanced helical planets\n"
                 "(ratio, coaxiality, neighbour condition on pitch circles)", fontsize=style.FONT)
    return figures.save(style.finish(fig), folder / "kladova2010_existence_regions")


def _synthesis_figure(folder: Path) -> list[Path]:
    from symkin.viz import figures, style

    full = synthesis_example()
    fig = style.new_figure(style.PAGE, 3.6)
    ax1, ax2 = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    for ax in (ax1, ax2):
        style.style_axes(ax)
    err = [100 * float(d.relative_error) for d in full.designs]
    env = [d.envelope_diameter for d in full.designs]
    b12 = [d.betas_deg[0] for d in full.designs]
    b34 = [d.betas_deg[1] for d in full.designs]
    sc = ax1.scatter(env, err, c=b12, s=10, cmap="viridis")
    top = _listed()
    ax1.scatter([d.envelope_diameter for d in top], [100 * float(d.relative_error) for d in top], s=30,
                facecolors="none", edgecolors=style.PALETTE[1], label=f"listed (best {len(top)})")
    bar = fig.colorbar(sc, ax=ax1)
    bar.set_label(r"$\beta_{12}$ [deg]", fontsize=style.FONT)
    bar.ax.tick_params(labelsize=style.SMALL)
    ax1.set_xlabel("planet envelope diameter\n$2 a_w + \\max(d_{a2}, d_{a3})$ [mm]", fontsize=style.FONT)
    ax1.set_ylabel("ratio error [%]", fontsize=style.FONT)
    ax1.set_title(f"{full.found} designs: AI, i = 25 $\\pm$ 2 %, k = 3", fontsize=style.FONT)
    style.legend_outside(ax1)
    ax2.scatter(b34, b12, s=10, c=style.PALETTE[0])
    ax2.set_xlabel(r"$\beta_{34}$ [deg]", fontsize=style.FONT)
    ax2.set_ylabel(r"$\beta_{12}$ [deg]", fontsize=style.FONT)
    ax2.set_title("helix angles that balance the axial\nforces (equal leads)", fontsize=style.FONT)
    fig.suptitle("Synthesis: unshifted helical meshes, $m_{n12}$ = 2 mm, $m_{n34}$ = 2.5 mm, Z in [17, 110]",
                 fontsize=style.FONT)
    return figures.save(style.finish(fig), folder / "kladova2010_synthesis")


def notes() -> list[str]:
    """Remarks printed under the paper's checks in the report, with the helix hands that balance the axial forces in each scheme."""
    hands = {kd: balancing_hands(kd) for kd in HS.SCHEMES}
    return [
        "Balance: the torque balance of the planet gives F_t2 d_w2 = F_t3 d_w3; the axial force of a helical rim is "
        "F_t tan(beta) on any one cylinder (one lead per gear), so the axial forces cancel when the rims have the same "
        "hand and equal leads: tan(beta_w2)/tan(beta_w3) = d_w2/d_w3 on the working cylinders, tan(beta12)/tan(beta34) "
        "= d2/d3 on the reference ones, i.e. m_n12 Z2 / sin(beta12) = m_n34 Z3 / sin(beta34).  The paper writes the "
        "reference angles with working diameters: exact for unshifted meshes, approximate for shifted ones.",
        "Hands (R right, L left; rims right-handed): " + "; ".join(
            f"{kd}: " + " ".join(f"{g}{'R' if h > 0 else 'L'}" for g, h in zip("1234", hd)) for kd, hd in hands.items()),
        "lambda is not defined in the paper; solved from the comparison it is m_n12 cos(alpha_t12)/(m_n34 cos(alpha_t34)), "
        "a constant of the two tool profiles, with which (2) is exact.",
        "Table 1's column heads read 'xx <= 1' / 'xx >= 1' in the OCR; the derivation shows the columns are "
        "d_w2/d_w3 <= 1 and >= 1 (which rim is larger decides the neighbour condition).",
        "The synthesis uses unshifted (zero) meshes: for each tooth set the two helix angles follow from balance and "
        "coaxiality; profile shift is modelled (symkin.mechanisms.helical) but not searched.",
    ]
