"""Kladova, Saprykin & Shebanov (2010): helical stepped planets with balanced axial forces, reproduced.

Everything on the "derived" side comes from symkin: the planet statics
(:mod:`symkin.statics`), the ratio, coaxiality and assembly conditions of the engine,
the tooth-number equations solved from them, the existence regions and the synthesis
(:mod:`symkin.mechanisms.helical.synthesis`).  The published forms below are transcribed from the
paper (OCR in shared/papers), for comparison only; where the OCR is damaged, both the
form as printed and the reconstruction are kept, and the reconstruction is justified by
the derivation.

Section 1.1 of the paper is headed "AA", but its equations (1)-(3) are those of the
stepped external-internal (AI) planet; they are compared with the AI derivation, the
label is recorded as a slip, and the true AA equations (which the paper does not write)
are derived and checked on the 2009 paper's AA example.
"""

from __future__ import annotations

import math
from functools import cache
from pathlib import Path

import sympy as sp

from symkin import schemes
from symkin import symbols as S
from symkin.mechanisms.helical import synthesis as HS
from symkin.mechanisms.helical.synthesis import DELTA, LAMBDA, RATIO, K, P, Q, X, Z
from symkin.papers.checks import Check, Comparison, Verdict, compare_symbolic, slip
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
PUBLISHED_BALANCE = 2 * r2 / (2 * r3)  # tan(beta12)/tan(beta34) = d_w2/d_w3 (d_w = 2 r_w)
PUBLISHED = {
    "(1)": 1 + z2 * z4 / (z1 * z3),
    "(2)": sp.Eq(lam * (z1 + z2) * sp.cos(a_tw34) / sp.cos(a_tw12), (z4 - z3) * sp.cos(b12) / sp.cos(b34)),
    "(3)": sp.Eq(z1 / k * (1 + z2 * z4 / (z1 * z3)) - z2 / z3 * Q, P),
    "(3) with (1)": sp.Eq(z1 / k * i - x * Q, P),  # printed after "from (34)"
    "(4)": z1 * (i - 1) / x,  # Z4
    "(5)": k * (P + Q * x) / i,  # Z1
    "(6) step": z1 * (i - 1 - x * lam * C) / (x * lam * C + 1),  # Z2, the product the OCR printed as "Z1 - ..."
    "(6) step as printed": z1 - (i - 1 - x * lam * C) / (x * lam * C + 1),
    "(6) identity": x * lam * C,  # = d_w2/d_w3
    "(6) identity as printed": i - 1 - C,
    "(6)": z1 * (i - 1 - delta) / (delta + 1),  # Z2, reconstructed
    "(6) as printed": z1 * (delta + 1) / (delta + 1),
    "(7)": z2 / x,  # Z3
    "(8)": k * (P - Q * x) / i,  # Z1 (II)
    "(9)": z1 * (1 - i - delta) / (1 - delta),  # Z2 (II), reconstructed
    "(9) as printed": z2 * (1 - i * delta) / (1 - delta),  # printed as Z1 = Z2 (...)
    "(10)": z2 / x,  # Z3 (II)
    "(11)": z1 * (1 - i) / x,  # Z4 (II)
}
# Table 1: (lower, upper) bounds of i_1H^(4), columns "x <= 1" and "x >= 1" (the OCR prints "xx")
PUBLISHED_TABLE = {
    ("AA", "delta < 1"): (1 + delta, (1 - delta) / (1 - delta * s)),
    ("AA", "delta > 1"): ((1 - delta) / (1 - delta * s), 1 - delta),
    ("II", "delta < 1"): ((1 - delta) / (1 + delta * s), 1 - delta),
    ("II", "delta > 1"): (1 - delta, (1 - delta) / (1 + s)),
    ("AI", "delta < 1"): (1 + delta, (1 + delta) / (1 - delta * s)),
    ("AI", "delta > 1"): (1 + delta, (1 + delta) / (1 - s)),
}
#: Examples of the 2009 paper (equal modules, spur, coaxial), rebuilt from the tooth equations.
EXAMPLE_AA_2009 = (54, 45, 44, 55)
EXAMPLE_II_2009 = (200, 99, 100, 201)
#: The synthesis example: AI, i = 25 within 2 %, 3 satellites, m_n12 = 2 mm, m_n34 = 2.5 mm.
SYNTHESIS_EXAMPLE = dict(scheme="AI", ratio=25, tolerance="0.02", satellites=3, normal_modules=(2, "2.5"),
                         beta_min_deg=8, beta_max_deg=30, teeth_min=17, teeth_max=110, top=20)


def _check(label: str, description: str, derived, published, comparison: Comparison, **extra) -> Check:
    return Check.make(KEY, label, description, derived, published, comparison, **extra)


def _lambda_definition():
    return {lam: m12 * sp.cos(a_t12) / (m34 * sp.cos(a_t34))}


def checks() -> list[Check]:
    """Every equation and table entry of the paper, derived and compared; the synthesis example."""
    out: list[Check] = []
    out += _balance_checks()
    out += _section_11_checks()
    out += _section_12_checks()
    out += _true_aa_checks()
    out += _table_checks()
    out += _synthesis_checks()
    return out


# --------------------------------------------------------------------------- balance
def _balance_checks() -> list[Check]:
    out = []
    st = planet_statics(schemes.two_row("AI"))
    ft2, ft3 = sp.Symbol("F_t2", positive=True), sp.Symbol("F_t3", positive=True)
    dw2, dw3 = sp.Symbol("d_w2", positive=True), sp.Symbol("d_w3", positive=True)
    published_torque = sp.Eq(ft2 * dw2, ft3 * dw3)
    out.append(_check(
        "planet torque balance", "AI planet: moments of the two tangential forces about its axis cancel",
        st.magnitudes, published_torque,
        compare_symbolic(st.magnitudes.lhs - st.magnitudes.rhs,
                         (published_torque.lhs - published_torque.rhs).subs({dw2: 2 * r2, dw3: 2 * r3})),
    ))
    out.append(_check(
        "balance", "axial forces cancel: tan(beta_w2)/tan(beta_w3) = d_w2/d_w3 (helix angles on the working cylinders)",
        st.condition, sp.Eq(sp.tan(bw2) / sp.tan(bw3), PUBLISHED_BALANCE, evaluate=False),
        compare_symbolic(st.condition.rhs, PUBLISHED_BALANCE),
    ))
    for kind in ("AA", "II"):
        other = planet_statics(schemes.two_row(kind))
        out.append(_check(
            f"balance {kind}", f"{kind} planet: the same condition (only the force directions differ)",
            other.condition, sp.Eq(sp.tan(bw2) / sp.tan(bw3), PUBLISHED_BALANCE, evaluate=False),
            compare_symbolic(other.condition.rhs, PUBLISHED_BALANCE),
        ))
    ref = HS.balance_condition()
    dw_ratio = HS.working_diameter_ratio(shifted=True)
    out.append(_check(
        "balance, reference angles", "tan(beta12)/tan(beta34) with reference helix angles vs d_w2/d_w3",
        ref, sp.Eq(sp.tan(b12) / sp.tan(b34), dw_ratio, evaluate=False),
        compare_symbolic(ref.rhs, dw_ratio, under={a_tw12: a_t12, a_tw34: a_t34}),
    ))
    hands = {kind: balancing_hands(kind) for kind in HS.SCHEMES}
    names = "; ".join(f"{kd}: " + ", ".join(f"{g} {'R' if h > 0 else 'L'}" for g, h in zip("1234", hd)) for kd, hd in hands.items())
    out.append(_check(
        "balance hands", "rims 2 and 3 must have the same hand (equal leads, paper summary); central gears follow",
        f"same hand on both rims; {names}", "both rims of the same hand",
        Comparison(Verdict.MATCH if st.same_hand else Verdict.DIFFERS,
                   "derived from the statics (h2 = h3) and the helix tangency at each pitch point: an external "
                   "mesh takes opposite hands, an internal one equal hands"),
    ))
    return out


# --------------------------------------------------------------------------- section 1.1
def _section_11_checks() -> list[Check]:
    out = []
    law = {kd: HS.ratio_law(kd).rhs for kd in HS.SCHEMES}
    out.append(_check("(1)", "ratio i_1H^(4) of the stepped planet in section 1.1 (derived for AI)",
                      law["AI"], PUBLISHED["(1)"], compare_symbolic(law["AI"], PUBLISHED["(1)"])))
    coax_aa = HS.helical_coaxiality("AA")
    evidence = (
        f"section 1.1 is headed 'AA' (two external meshes) but (1) equals the derived AI law {law['AI']}; the derived "
        f"AA law is {law['AA']} (they differ by {sp.simplify(PUBLISHED['(1)'] - law['AA'])}); (2) has Z4 - Z3, the "
        "centre distance of rim 3 inside an internal gear 4, while AA coaxiality has Z3 + Z4; (3) carries "
        "1 + Z2 Z4/(Z1 Z3) again.  The paper's Table 1 row AA, by contrast, uses 1 - d_w2/d_w3, the true AA.  "
        "Equations (1)-(7) describe the AI planet."
    )
    out.append(_check("(1)-(7) scheme label", "section 1.1 is labelled AA", law["AA"], PUBLISHED["(1)"], slip(evidence)))
    # (2): coaxiality of helical meshes
    coax = HS.helical_coaxiality("AI")
    pub = PUBLISHED["(2)"]
    out.append(_check(
        "(2)", "coaxiality of helical meshes a_w12 = a_w34 (AI), with lambda = m_n12 cos(alpha_t12)/(m_n34 cos(alpha_t34))",
        coax, pub, compare_symbolic(coax.lhs / coax.rhs, pub.lhs / pub.rhs, under=_lambda_definition()),
    ))
    plain = compare_symbolic(coax.lhs / coax.rhs, pub.lhs / pub.rhs, under={lam: m12 / m34})
    factor = sp.simplify((coax.lhs / coax.rhs) / (pub.lhs / pub.rhs).subs(lam, m12 / m34))
    out.append(_check(
        "(2) with lambda = m_n12/m_n34", "coaxiality with lambda read as the plain module ratio",
        coax, pub,
        slip(f"with lambda = m_n12/m_n34 derived/published = {factor}: (2) drops the transverse pressure angles, "
             "exact only when beta12 = beta34, which the balance allows only for d_w2 = d_w3; with lambda = "
             "m_n12 cos(alpha_t12)/(m_n34 cos(alpha_t34)) it is exact (check (2))") if plain.verdict is Verdict.DIFFERS
        else plain,
    ))
    out.append(_check(
        "(2) label", "the coaxiality of a true AA planet", coax_aa, pub,
        Comparison(Verdict.SLIP, "AA coaxiality has z_3 + z_4 where (2) has Z4 - Z3: see '(1)-(7) scheme label'"),
    ))
    # (3) assembly
    asm = HS.assembly_condition("AI")
    derived_teeth = (asm.lhs - asm.rhs).subs(RATIO, law["AI"])
    pub3 = PUBLISHED["(3)"]
    out.append(_check("(3)", "assembly of k satellites with integers P, Q (AI)", sp.Eq(derived_teeth + P, P),
                      pub3, compare_symbolic(derived_teeth, pub3.lhs - pub3.rhs)))
    with_ratio = (asm.lhs - asm.rhs).subs(z2, x * z3)
    pub31 = PUBLISHED["(3) with (1)"]
    out.append(_check(
        "from (34)", "the line after 'Iz (34)': (3) with the ratio (1) put in",
        asm, pub31,
        slip("the OCR reads 'from (34)'; the paper has no equation (34) (it numbers (1)-(11)); the line that follows "
             f"is (3) with i = (1) put in, and the derived assembly {sp.simplify(with_ratio)} = 0 equals it "
             f"(difference {sp.simplify(with_ratio - (pub31.lhs - pub31.rhs))}): read 'from (3)'"),
    ))
    # (4)-(7): the tooth chain
    ch = HS.tooth_equations("AI").chain
    for label, zz, what in (("(4)", z4, "Z4 from the ratio"), ("(5)", z1, "Z1 from assembly"), ("(7)", z3, "Z3 = Z2/x")):
        out.append(_check(label, f"AI: {what}", sp.Eq(zz, ch[zz]), sp.Eq(zz, PUBLISHED[label]),
                          compare_symbolic(ch[zz], PUBLISHED[label])))
    z2_derived = ch[z2]
    step = z2_derived.subs(delta, x * lam * C)
    out.append(_check("(6) step", "AI: Z2 from coaxiality, before d_w2/d_w3 is introduced", sp.Eq(z2, step),
                      sp.Eq(z2, PUBLISHED["(6) step"]), compare_symbolic(step, PUBLISHED["(6) step"])))
    out.append(_check(
        "(6) step as printed", "the same line as the OCR prints it", sp.Eq(z2, step), sp.Eq(z2, PUBLISHED["(6) step as printed"]),
        slip("printed 'Z2 = Z1 - (i - 1 - x lambda C)/(x lambda C + 1)'; the line above it, "
             "Z2 (x lambda C + 1) = Z1 (i - 1 - x lambda C), gives a product, and the printed difference is not even "
             "homogeneous in the tooth numbers (doubling every Z does not double Z2): the '-' is an OCR loss of the product"),
    ))
    identity = HS.working_diameter_ratio(shifted=True)
    out.append(_check(
        "(6) identity", "x lambda cos(a_tw34) cos(b34)/(cos(a_tw12) cos(b12)) = d_w2/d_w3",
        identity, PUBLISHED["(6) identity"],
        compare_symbolic(identity, PUBLISHED["(6) identity"], under={**_lambda_definition(), x: z2 / z3}),
    ))
    out.append(_check(
        "(6) identity as printed", "the OCR's 'i - 1 - cos.../cos... = d_w2/d_w3'", identity, PUBLISHED["(6) identity as printed"],
        slip("printed 'i - 1 - C = d_w2/d_w3' with C the cosine group; a diameter ratio cannot depend on i, and for "
             "unshifted spur gears of one module (C = 1) it would give d_w2/d_w3 = i - 2 instead of Z2/Z3.  The "
             "derived d_w2/d_w3 is x lambda C: the OCR turned 'x lambda' into 'i - 1 -'"),
    ))
    out.append(_check("(6)", "AI: Z2 from Z1, i and d_w2/d_w3 (reconstructed)", sp.Eq(z2, z2_derived),
                      sp.Eq(z2, PUBLISHED["(6)"]), compare_symbolic(z2_derived, PUBLISHED["(6)"])))
    out.append(_check(
        "(6) as printed", "the OCR's Z2 = Z1 (d_w2/d_w3 + 1)/(d_w2/d_w3 + 1)", sp.Eq(z2, z2_derived),
        sp.Eq(z2, PUBLISHED["(6) as printed"]),
        slip("the printed fraction has equal numerator and denominator (Z2 = Z1 for every ratio); substituting the "
             "identity d_w2/d_w3 = x lambda C into the step line gives Z2 = Z1 (i - 1 - d_w2/d_w3)/(d_w2/d_w3 + 1), "
             "which the derivation reproduces: the OCR lost 'i - 1 -' from the numerator"),
    ))
    return out


# --------------------------------------------------------------------------- section 1.2 (II)
def _section_12_checks() -> list[Check]:
    out = []
    ch = HS.tooth_equations("II").chain
    flipped = compare_symbolic(ch[z1].subs(Q, -Q), PUBLISHED["(8)"])
    out.append(_check("(8)", "II: Z1 from assembly (the sign of the free integer Q is a convention)",
                      sp.Eq(z1, ch[z1]), sp.Eq(z1, PUBLISHED["(8)"]),
                      Comparison(flipped.verdict, f"{flipped.detail} with Q -> -Q in the derived form (Q is any integer)")))
    out.append(_check("(9)", "II: Z2 from Z1, i and d_w2/d_w3 (reconstructed)", sp.Eq(z2, ch[z2]),
                      sp.Eq(z2, PUBLISHED["(9)"]), compare_symbolic(ch[z2], PUBLISHED["(9)"])))
    # evidence for the printed (9): the 2009 II example, spur, equal modules, coaxial
    zz = EXAMPLE_II_2009
    vals = {z1: zz[0], z2: zz[1], z3: zz[2], z4: zz[3]}
    i_ex = HS.ratio_law("II").rhs.subs(vals)
    d_ex = sp.Rational(zz[1], zz[2])
    printed_z1 = (PUBLISHED["(9) as printed"]).subs({z2: zz[1], i: i_ex, delta: d_ex})
    derived_z1 = sp.solve(sp.Eq(zz[1], ch[z2].subs({i: i_ex, delta: d_ex})), z1)[0]
    out.append(_check(
        "(9) as printed", "the OCR's Z1 = Z2 (1 - i d_w2/d_w3)/(1 - d_w2/d_w3)", sp.Eq(z2, ch[z2]),
        sp.Eq(z1, PUBLISHED["(9) as printed"]),
        slip(f"on the 2009 paper's II example z = {zz} (unshifted spur gears of one module, coaxial, so "
             f"d_w2/d_w3 = Z2/Z3 = {d_ex}, i = {i_ex}) the printed form gives Z1 = {printed_z1} = {float(printed_z1):g}, the derived one "
             f"Z1 = {derived_z1}.  The derivation reads Z2 = Z1 (1 - i - d_w2/d_w3)/(1 - d_w2/d_w3): the OCR swapped "
             "Z1 and Z2 and lost a minus sign ('1 - i - d' printed '1 - i d')"),
    ))
    for label, zz_, what in (("(10)", z3, "Z3 = Z2/x"), ("(11)", z4, "Z4 from the ratio")):
        out.append(_check(label, f"II: {what}", sp.Eq(zz_, ch[zz_]), sp.Eq(zz_, PUBLISHED[label]),
                          compare_symbolic(ch[zz_], PUBLISHED[label])))
    out.append(_rebuild_example("II", EXAMPLE_II_2009, 1, "(8)-(11) rebuild the 2009 II example"))
    return out


def _rebuild_example(kind: str, teeth: tuple[int, int, int, int], k_value: int, label: str) -> Check:
    """Put an example's i, x, d_w2/d_w3, k, P, Q into the derived tooth equations."""
    vals = dict(zip((z1, z2, z3, z4), teeth))
    i_ex = HS.ratio_law(kind).rhs.subs(vals)
    p_ex, q_ex = HS.assembly_integers(kind, teeth, k_value)
    params = {i: i_ex, x: sp.Rational(teeth[1], teeth[2]), delta: sp.Rational(teeth[1], teeth[2]),
              k: k_value, P: p_ex, Q: q_ex}
    sol = HS.tooth_equations(kind).solution
    rebuilt = tuple(sp.simplify(sol[zz].subs(params)) for zz in (z1, z2, z3, z4))
    ok = all(int(r) == t for r, t in zip(rebuilt, teeth)) if all(r.is_Integer for r in rebuilt) else False
    detail = (f"i = {i_ex}, x = d_w2/d_w3 = {teeth[1]}/{teeth[2]} (spur, one module, coaxial), k = {k_value}, "
              f"P = {p_ex}, Q = {q_ex} give Z = {rebuilt}")
    return _check(label, f"{kind}: the derived tooth equations on the 2009 paper's example {teeth}", list(rebuilt),
                  list(teeth), Comparison(Verdict.MATCH if ok else Verdict.DIFFERS, detail))


# --------------------------------------------------------------------------- true AA
def _true_aa_checks() -> list[Check]:
    ch = HS.tooth_equations("AA").chain
    out = [_rebuild_example("AA", EXAMPLE_AA_2009, 3, "AA (not in the paper) rebuilds the 2009 AA example")]
    ii = HS.tooth_equations("II").chain
    rel = sp.simplify(ch[z2] + ii[z2])
    out.append(_check(
        "AA (not in the paper) vs II", "true AA: Z2 = -(II's Z2), Z4 = II's Z4, Z1 and Z3 as in II",
        [sp.Eq(zz, ch[zz]) for zz in (z1, z4, z2, z3)], [sp.Eq(zz, ii[zz]) for zz in (z1, z4, z2, z3)],
        Comparison(Verdict.MATCH if rel == 0 and all(sp.simplify(ch[zz] - ii[zz]) == 0 for zz in (z1, z3, z4)) else Verdict.DIFFERS,
                   f"derived AA Z2 + II Z2 = {rel}: the two schemes share (8), (10), (11) and differ in the sign of (9)"),
    ))
    return out


# --------------------------------------------------------------------------- Table 1
def _table_checks() -> list[Check]:
    out = []
    for kind in ("AA", "II", "AI"):
        for b in HS.existence_bounds(kind):
            pub_lo, pub_hi = PUBLISHED_TABLE[kind, b.case]
            c_lo, c_hi = compare_symbolic(b.lower, pub_lo), compare_symbolic(b.upper, pub_hi)
            label = f"Table 1 {kind}, {b.case}"
            if c_lo.verdict.ok and c_hi.verdict.ok:
                comparison = Comparison(Verdict.MATCH, f"both bounds: {c_lo.detail}; range ended by the {b.binding} condition")
            else:
                evidence = _table_evidence(kind, b, c_hi)
                # a slip only where there is an argument beyond the difference itself
                comparison = slip(evidence) if evidence else Comparison(
                    Verdict.DIFFERS, f"lower: {c_lo.detail}; upper: {c_hi.detail}")
            out.append(_check(label, f"{kind}: admissible i_1H^(4) for d_w2/d_w3 {b.case[6:]}, k satellites",
                              [b.lower, b.upper], [pub_lo, pub_hi], comparison))
    empty = [HS.existence_interval(kd, kk, 1) is None for kd in ("AA", "II") for kk in (2, 3, 4, 6)]
    out.append(_check(
        "Table 1, d_w2 = d_w3", "AA and II need d_w2/d_w3 != 1 (the paper's conclusion)",
        "empty for k = 2, 3, 4, 6" if all(empty) else "not empty", "d_w2/d_w3 != 1",
        Comparison(Verdict.MATCH if all(empty) else Verdict.DIFFERS,
                   "at d_w2 = d_w3 both bounds of AA and II collapse to i = 0"),
    ))
    return out


def _table_evidence(kind: str, b, c_hi: Comparison) -> str:
    """Why a printed Table 1 bound is wrong, for the rows where we have an argument ('' otherwise)."""
    pub_lo, pub_hi = PUBLISHED_TABLE[kind, b.case]
    if kind == "AA" and b.case == "delta < 1":
        d, kk = sp.Rational(1, 2), 3
        p = (pub_lo.subs({delta: d, k: kk}), sp.nsimplify(pub_hi.subs({delta: d, k: kk})))
        return (f"the printed lower bound 1 + d_w2/d_w3 is the AI one; with it the interval is empty for every "
                f"d_w2/d_w3 < 1 (e.g. d = 1/2, k = 3: {p[0]} < i < {float(p[1]):.4f}), since (1 - d)/(1 - d sin(pi/k)) "
                f"< 1 < 1 + d.  The derived lower end, the limit of ever larger central gears, is {b.lower}; the upper "
                f"bound matches ({c_hi.detail})")
    if kind == "AA" and b.case == "delta > 1":
        return (f"the printed lower bound (1 - d)/(1 - d sin(pi/k)) applies the neighbour condition to rim 3, the "
                f"smaller rim when d_w2 > d_w3; the derived bound {b.lower} uses rim 2, the larger, as the II and AI "
                "rows of the same column do (1 + sin(pi/k), 1 - sin(pi/k) without d).  For d > 1/sin(pi/k) the printed "
                "bound is positive and exceeds the upper bound 1 - d < 0: the interval would be empty; the upper bound "
                f"matches ({c_hi.detail})")
    return ""


# --------------------------------------------------------------------------- synthesis example
@cache
def synthesis_example() -> HS.SynthesisResult:
    """The synthesis example, every design found (the report lists the best ``top``)."""
    return HS.synthesise(**{**SYNTHESIS_EXAMPLE, "top": None})


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
        Comparison(Verdict.MATCH if ok else Verdict.DIFFERS,
                   f"largest relative axial residual {worst:.1e} over the {len(forces)} listed designs"),
    )]
    ok_ratio = bool(listed) and worst_ratio <= 1e-12 and all(engine)
    out.append(_check(
        "synthesis: statics vs kinematics", "carrier torque per input torque (statics) vs the engine's i_1H^(4)",
        f"equal to 1e-12 for all {len(forces)}" if ok_ratio else "differ", "i_1H^(4) of each design",
        Comparison(Verdict.MATCH if ok_ratio else Verdict.DIFFERS,
                   f"virtual work: output torque = i x input torque, i from the engine on the built mechanism; "
                   f"largest relative gap {worst_ratio:.1e}"),
    ))
    return out


# --------------------------------------------------------------------------- figures
def figures(folder: Path) -> list[Path]:
    """Existence regions (Table 1) for k = 3, 4, 6, derived and as published; the synthesis example."""
    return _region_figure(folder) + _synthesis_figure(folder)


def _region_figure(folder: Path) -> list[Path]:
    import numpy as np
    from matplotlib.figure import Figure

    from symkin.viz import figures

    fig = Figure(figsize=(13, 4.6), layout="constrained")
    limits = {"AI": (1, 25), "AA": (-6, 2.2), "II": (-1.6, 1.1)}
    colours = {3: "tab:blue", 4: "tab:orange", 6: "tab:green", 12: "tab:purple"}
    for n, kind in enumerate(("AI", "AA", "II"), 1):
        ax = fig.add_subplot(1, 3, n)
        flagged = False
        for b in HS.existence_bounds(kind):
            first = b.case == "delta < 1"
            d = np.linspace(0.01, 0.999, 400) if first else np.linspace(1.001, 3.5, 400)
            # the end that does not depend on k is the limit of large central gears (r_1 -> oo)
            free_end = b.lower if not b.lower.has(K) else b.upper
            k_end = b.upper if free_end is b.lower else b.lower

            def curve(expr, kk=3, d=d):
                v = sp.lambdify(DELTA, expr.subs(K, kk), "numpy")(d) * np.ones_like(d)
                return np.where(np.abs(v) < 1e3, v, np.nan)  # do not join the branches of a pole

            ax.fill_between(d, curve(free_end), curve(k_end), color="tab:blue", alpha=0.15, lw=0,
                            label="region, k = 3" if first else None)
            ax.plot(d, curve(free_end), color="k", lw=1.0, label="large central gears ($r_1 \\to \\infty$)" if first else None)
            for kk, col in colours.items():
                ax.plot(d, curve(k_end, kk), color=col, lw=1.0, label=f"neighbour bound, k = {kk}" if first else None)
            pub_lo, pub_hi = PUBLISHED_TABLE[kind, b.case]
            for bound, drv in ((pub_lo, b.lower), (pub_hi, b.upper)):
                if np.nanmax(np.abs(curve(bound) - curve(drv))) > 1e-9:  # the checks compare them exactly
                    ax.plot(d, curve(bound), "r--", lw=1.2, label=None if flagged else "published bound (differs), k = 3")
                    flagged = True
        ax.axvline(1, color="0.5", lw=0.6)
        ax.set_ylim(*limits[kind])
        if kind == "AI":
            ax.set_yscale("log")
        ax.set_xlabel(r"$d_{w2}/d_{w3}$")
        ax.set_ylabel(r"$i_{1H}^{(4)}$")
        ax.set_title(f"{kind}", fontsize=10)
        ax.legend(fontsize=7, loc="lower right" if kind == "AI" else "lower left")
        ax.grid(alpha=0.3)
    fig.suptitle("Kladova et al. 2010, Table 1 derived: ratios realisable with balanced helical planets "
                 "(ratio, coaxiality, neighbour condition on pitch circles)", fontsize=10)
    return figures.save(fig, folder / "kladova2010_existence_regions")


def _synthesis_figure(folder: Path) -> list[Path]:
    from matplotlib.figure import Figure

    from symkin.viz import figures

    full = synthesis_example()
    fig = Figure(figsize=(10, 4.2))
    ax1, ax2 = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    err = [100 * float(d.relative_error) for d in full.designs]
    env = [d.envelope_diameter for d in full.designs]
    b12 = [d.betas_deg[0] for d in full.designs]
    b34 = [d.betas_deg[1] for d in full.designs]
    sc = ax1.scatter(env, err, c=b12, s=10, cmap="viridis")
    top = _listed()
    ax1.scatter([d.envelope_diameter for d in top], [100 * float(d.relative_error) for d in top], s=30,
                facecolors="none", edgecolors="red", label=f"listed (best {len(top)})")
    fig.colorbar(sc, ax=ax1, label=r"$\beta_{12}$ (deg)")
    ax1.set_xlabel("planet envelope diameter 2 a_w + max(d_a2, d_a3) (mm)")
    ax1.set_ylabel("ratio error (%)")
    ax1.set_title(f"{full.found} designs: AI, i = 25 +- 2 %, k = 3", fontsize=9)
    ax1.legend(fontsize=7)
    ax2.scatter(b34, b12, s=10, c="tab:blue")
    ax2.set_xlabel(r"$\beta_{34}$ (deg)")
    ax2.set_ylabel(r"$\beta_{12}$ (deg)")
    ax2.set_title("helix angles that balance the axial forces (equal leads)", fontsize=9)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.suptitle("Synthesis: unshifted helical meshes, m_n12 = 2 mm, m_n34 = 2.5 mm, Z in [17, 110]", fontsize=10)
    return figures.save(fig, folder / "kladova2010_synthesis")


def notes() -> list[str]:
    hands = {kd: balancing_hands(kd) for kd in HS.SCHEMES}
    return [
        "Balance: the torque balance of the planet gives F_t2 d_w2 = F_t3 d_w3; the axial force of a helical rim is "
        "F_t tan(beta) on any one cylinder (one lead per gear), so the axial forces cancel when the rims have the same "
        "hand and equal leads: tan(beta_w2)/tan(beta_w3) = d_w2/d_w3 on the working cylinders, tan(beta12)/tan(beta34) "
        "= d2/d3 on the reference ones, i.e. m_n12 Z2 / sin(beta12) = m_n34 Z3 / sin(beta34).  The paper writes the "
        "reference angles with working diameters: exact for unshifted meshes, approximate for shifted ones.",
        "Hands (R right, L left; rims right-handed): " + "; ".join(
            f"{kd}: " + " ".join(f"{g}{'R' if h > 0 else 'L'}" for g, h in zip("1234", hd)) for kd, hd in hands.items()),
        "lambda in (2) must carry the transverse pressure angles, lambda = m_n12 cos(alpha_t12)/(m_n34 cos(alpha_t34)), "
        "for (2) to be exact.",
        "Table 1's column heads read 'xx <= 1' / 'xx >= 1' in the OCR; the derivation shows the columns are "
        "d_w2/d_w3 <= 1 and >= 1 (which rim is larger decides the neighbour condition).",
        "The synthesis uses unshifted (zero) meshes: for each tooth set the two helix angles follow from balance and "
        "coaxiality; profile shift is modelled (symkin.mechanisms.helical) but not searched.",
    ]
