"""KhAI (2014), multistage common-ring train: feasible stages and the ratio split of least lost motion.

The n-stage train is built with the engine (:func:`symkin.schemes.common_ring_train`);
its total ratio, each stage's ratio and the transfer of each stage's angular error to
the output carrier are derived from it (:mod:`symkin.mechanisms.multistage.lostmotion`).  The stage
enumeration derives coaxiality, assembly and neighbour conditions from the single-row
AI scheme (:mod:`symkin.mechanisms.multistage.stages`).  The continuous optimum and the discrete designs come
from :mod:`symkin.mechanisms.multistage.split`.  The published forms and numbers below are transcribed
from the paper (OCR in shared/papers) and are only compared against.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import sympy as sp

from symkin import schemes
from symkin import symbols as S
from symkin.mechanisms.multistage import StageErrorModel, best_designs, enumerate_stages, lost_motion, optimize_split
from symkin.mechanisms.multistage.lostmotion import backlash_symbol, diameter_symbol, stage_ratio_symbol
from symkin.mechanisms.multistage.stages import stage_laws
from symkin.papers.checks import (
    Check,
    Kind,
    PrintedItem,
    alternative,
    compare_claim,
    compare_exact,
    compare_rounded,
    compare_symbolic,
    confirmation,
    gather,
    judge,
)
from symkin.parsing import parse_number

KEY = "khai2014"
CITATION = (
    "National Aerospace University \"Kharkiv Aviation Institute\" (KhAI), Optimisation of the kinematic scheme "
    "of a multistage planetary mechanism by the criterion of minimum lost motion, 2014 (the authors' names are "
    "not in the available text)"
)

# ---- published inputs and results (for comparison only)
RING, SATELLITES, Z_MIN, Z_MAX = 180, 3, 18, 180  # "z3 = 180, S = 3, 18 <= z <= 180"
PUBLISHED_STAGE_COUNT = 22
PUBLISHED_U_MIN, PUBLISHED_U_MAX = "2.25", "11"
TOTAL, STAGES = 6000, 4  # fig. 4, step 1
U_LOWER, U_UPPER = parse_number("2.25"), parse_number("11")  # fig. 4, step 3
START = 3  # fig. 4, step 2: u_1 = ... = u_4 = 3
A_LINEAR, B_LINEAR = parse_number("0.854"), parse_number("0.858")  # (5) for curve 1 of fig. 3 (grade 8, mating F, m = 0.5 mm)
PUBLISHED_OPTIMUM = ("4.508", "11", "11", "11")  # fig. 4, step 7
PUBLISHED_OBJECTIVE = "0.343"  # fig. 4, step 8
LINE_J0, LINE_J_END, LINE_A_END = 50, 120, 180  # (7): j_n max(a_w) = 50 + (120 - 50)/180 a_w
PUBLISHED_SLOPE = "0.389"
REGRESSION = ("51.932", "0.352")  # MathCAD line() on the GOST data (not given in the paper)
MODULE = sp.Rational(1, 2)

a, b = sp.symbols("a b", real=True)  # the paper's abi_1, abi_2

#: The paper's figure captions (transcribed): which figure shows what.
FIGURE_CAPTIONS = {
    1: "the mechanism studied",
    2: "j_n max(a_w): 1 - GOST 9178-81 data; 2 - linear regression; 3 - line through the two end points",
    3: "(Phi_i/d_(3i-2))(u) and a_w(u)",
    4: "minimisation of the objective function",
}
#: What the text says is where: (item, what it refers to, the figure printed, the caption words that identify it,
#: the figure a second sentence of the paper names for the same thing).
FIGURE_REFERENCES = (
    ("fig. 1 regression line", "the linear regression line 'marked 2' (MathCAD line())", 1, "linear regression",
     2, "the next paragraph: 'the line marked 3 in fig. 2' (the same plot)"),
    ("fig. 3 optimisation result", "the optimisation result (the distribution of the stage ratios)", 3, "minimisation",
     4, "the text before fig. 4: 'fig. 4 shows a fragment of the minimisation program'"),
)
#: (3): Phi_i = j_n max^(3i-2, 3i-1) + j_n max^(3i-1, 3i), the backlashes of the stage's two meshes.
J_SUN, J_RING = sp.Symbol("j_12", positive=True), sp.Symbol("j_23", positive=True)
PUBLISHED_3 = J_SUN + J_RING
#: Algorithm step 1: a_w12 = m/2 (z_(3i-2) + z_(3i-1)), a_w23 = m/2 (z_(3i) - z_(3i-1)) (paper numbering: sun, planet, ring).
z_sun, z_planet, z_ring = sp.symbols("z_1 z_2 z_3", positive=True)
PUBLISHED_CENTRE_DISTANCES = (S.module() / 2 * (z_sun + z_planet), S.module() / 2 * (z_ring - z_planet))

PRINTED_ITEMS = (
    PrintedItem("(1)", "the objective: each carrier's error Delta phi_Hi carried to the output"),
    PrintedItem("Delta phi_Hi", "Delta phi_Hi = Phi_i/(d_(3i-2) u_i), stage i's error at its carrier"),
    PrintedItem("(2) line 1", "(2), first form: Phi_i/(d_(3i-2) u_i ... u_n) summed"),
    PrintedItem("(2) line 2", "(2), expanded form (1/u_S)(Phi_1/d_1 + Phi_2/d_4 u_1 + ...)"),
    PrintedItem("(2) closed sum", "(2), closed form with prod_(j=1)^(i) u_j"),
    PrintedItem("u_S", "u_S = prod u_i, the total ratio"),
    PrintedItem("(3)", "Phi_i = sum of the probable maximum backlashes of the stage's two meshes"),
    PrintedItem("(4)", "Phi_i/d_(3i-2) = Phi d_i(p_i): the objective depends on the stages only through these ratios"),
    PrintedItem("(5)", "Phi_i/d_(3i-2) = a_i + b_i u, a linear model",
                "a model the paper posits; its coefficients come from GOST tables not in the paper"),
    PrintedItem("(6)", "GOST 9178-81: j_n max = j_n min + sqrt(0.5 (T_H1^2 + T_H2^2)) + 2 f_a^2",
                "a quoted standard formula, not derivable by symkin; its printing is checked as an extension"),
    PrintedItem("regression a, b", "MathCAD line() on the GOST data: a = 51.932, b = 0.352",
                "needs the GOST 9178-81 table, not in the paper"),
    PrintedItem("(7) slope", "(7): the two-point line 50 + (120 - 50)/180 a_w = 50 + 0.389 a_w",
                "arithmetic on the paper's own two points (the consistency check '(7) slope' does it); the points "
                "come from the GOST table, not in the paper"),
    PrintedItem("(7) end points", "j_n max = 50 at a_w = 0 and 120 at a_w = 180 (fig. 2)",
                "read from the GOST table, not in the paper"),
    PrintedItem("fig. 1 regression line", "the regression line is attributed to fig. 1"),
    PrintedItem("(8)", "GOST 21098-82: J_t max = 0.7 (E_HS1 + E_HS2) + sqrt(...)",
                "a quoted standard formula, not derivable by symkin; its printing is checked as an extension"),
    PrintedItem("E_HS sign", "E_HS negative for external, positive for internal gears",
                "a sign convention of GOST 21098-82, not available here"),
    PrintedItem("step 1 centre distances", "a_w12 = m/2 (z_(3i-2) + z_(3i-1)), a_w23 = m/2 (z_(3i) - z_(3i-1))"),
    PrintedItem("steps 2-4", "tolerances from GOST 9178-81 tables 5 and 10", "the GOST tables are not in the paper"),
    PrintedItem("stages: count", "22 feasible stage ratios (ring 180, 3 satellites, 18 <= z <= 180)"),
    PrintedItem("stages: u min", "smallest stage ratio 2.25"),
    PrintedItem("stages: u max", "largest stage ratio 11"),
    PrintedItem("(5) a, b", "curve 1 of fig. 3: a = 0.854, b = 0.858", "needs the GOST tables, not in the paper"),
    PrintedItem("fig. 4 FF", "fig. 4 step 6: FF(u) = (1/U_S)(Fd1 + Fd2 u1 + Fd3 u1 u2 + Fd4 u1 u2 u3)"),
    *(PrintedItem(f"fig. 4 u_{n}", f"fig. 4 step 7: optimal u_{n}") for n in range(1, 5)),
    PrintedItem("fig. 4 FF value", "fig. 4 step 8: FF at the optimum = 0.343"),
    PrintedItem("fig. 3 optimisation result", "the optimisation result is attributed to fig. 3"),
    PrintedItem("agreement with [4]", "the optimum agrees with the conclusions of [4]", "[4] is not available here"),
)


def _published_1(n: int) -> sp.Expr:
    """(1): sum_i Delta phi_Hi / (u_(i+1) ... u_n), Delta phi_Hi = Phi_i / (d_(3i-2) u_i)."""
    u = [stage_ratio_symbol(i) for i in range(1, n + 1)]
    carrier = [backlash_symbol(i) / (diameter_symbol(i) * u[i - 1]) for i in range(1, n + 1)]
    return sp.Add(*(carrier[i - 1] / sp.Mul(*u[i:]) for i in range(1, n + 1)))


def _published_2_first(n: int) -> sp.Expr:
    """(2), first line: Phi_1/(d_1 u_1 ... u_n) + Phi_2/(d_4 u_2 ... u_n) + ... + Phi_n/(d_(3n-2) u_n)."""
    u = [stage_ratio_symbol(i) for i in range(1, n + 1)]
    return sp.Add(*(backlash_symbol(i) / (diameter_symbol(i) * sp.Mul(*u[i - 1:])) for i in range(1, n + 1)))


def _published_2_expanded(n: int) -> sp.Expr:
    """(2), second line: (1/u_S)(Phi_1/d_1 + Phi_2/d_4 u_1 + ... + Phi_n/d_(3n-2) u_1 ... u_(n-1))."""
    u = [stage_ratio_symbol(i) for i in range(1, n + 1)]
    inner = sp.Add(*(backlash_symbol(i) / diameter_symbol(i) * sp.Mul(*u[: i - 1]) for i in range(1, n + 1)))
    return inner / sp.Mul(*u)


def _published_2_closed(n: int, upper: str) -> sp.Expr:
    """(2), closed sum: (1/u_S)(Phi_1/d_1 + sum_(i=2)^n Phi_i/d_(3i-2) prod_(j=1)^(upper) u_j)."""
    u = [stage_ratio_symbol(i) for i in range(1, n + 1)]
    top = (lambda i: i) if upper == "i" else (lambda i: i - 1)
    inner = backlash_symbol(1) / diameter_symbol(1) + sp.Add(
        *(backlash_symbol(i) / diameter_symbol(i) * sp.Mul(*u[: top(i)]) for i in range(2, n + 1))
    )
    return inner / sp.Mul(*u)


def _published_fig4_FF(Fd: list) -> sp.Expr:
    """Fig. 4, step 6: FF(u) = (1/U_S)(Fd1 + Fd2 u1 + Fd3 u1 u2 + Fd4 u1 u2 u3)."""
    u1, u2, u3, _u4 = (stage_ratio_symbol(i) for i in range(1, 5))
    U_S = sp.Symbol("U_Sigma", positive=True)
    return (Fd[0] + Fd[1] * u1 + Fd[2] * u1 * u2 + Fd[3] * u1 * u2 * u3) / U_S, U_S


def _published_6() -> sp.Expr:
    """(6) as printed: j_n max = j_n min + sqrt(0.5 (T_H1^2 + T_H2^2)) + 2 f_a^2 (f_a outside the root)."""
    j, t1, t2, fa = sp.symbols("j_min T_H1 T_H2 f_a", positive=True)
    return j + sp.sqrt(sp.Rational(1, 2) * (t1**2 + t2**2)) + 2 * fa**2


def _published_8() -> sp.Expr:
    """(8): J_t max = 0.7 (E_HS1 + E_HS2) + sqrt(0.5 (T_H1^2 + T_H2^2) + 2 f_a^2 + G_r1^2 + G_r2^2)."""
    e1, e2, t1, t2, fa, g1, g2 = sp.symbols("E_HS1 E_HS2 T_H1 T_H2 f_a G_r1 G_r2")
    return sp.Rational(7, 10) * (e1 + e2) + sp.sqrt(sp.Rational(1, 2) * (t1**2 + t2**2) + 2 * fa**2 + g1**2 + g2**2)


def _check(label: str, description: str, derived, published, comparison, **extra) -> Check:
    return Check.make(KEY, label, description, derived, published, comparison, **extra)


# ---------------------------------------------------------------------------- shared results
def stage_set():
    """The feasible stages of the paper's ring (180 teeth, 3 satellites, the paper's tooth limits), enumerated exactly."""
    return enumerate_stages(RING, SATELLITES, zmin=Z_MIN, zmax=Z_MAX)


def paper_model() -> StageErrorModel:
    """The paper's stage error model, the regression line Phi/d = a + b u."""
    return StageErrorModel.linear(A_LINEAR, B_LINEAR)


def mathcad_model() -> StageErrorModel:
    """Fd_i as MathCAD evaluated it: the assignment Fd_i := abi_1 + abi_2 u_i at the start values u_i = 3."""
    return StageErrorModel(paper_model().at(START), f"Fd frozen at the start value u = {START}")


def line_model() -> StageErrorModel:
    """Phi/d from the straight backlash line (7) through the engine's centre distances (m = 0.5 mm)."""
    slope = sp.Rational(LINE_J_END - LINE_J0, LINE_A_END)
    return StageErrorModel.from_backlash_line(LINE_J0, slope, module=MODULE, ring=RING)


_CACHE: dict = {}


def optimum():
    """The continuous optimum of the paper's fig. 4 case (cached)."""
    if "optimum" not in _CACHE:
        _CACHE["optimum"] = optimize_split(TOTAL, STAGES, lower=U_LOWER, upper=U_UPPER, model=paper_model())
    return _CACHE["optimum"]


def discrete(tolerance: str):
    """The best discrete designs from :func:`stage_set` within ``tolerance`` (a decimal, as the text
    prints it; cached)."""
    key = ("discrete", tolerance)
    if key not in _CACHE:
        _CACHE[key] = best_designs(TOTAL, stage_set(), STAGES, model=paper_model(), tolerance=parse_number(tolerance),
                                   top=5)
    return _CACHE[key]


# ---------------------------------------------------------------------------- checks
def checks() -> list[Check]:
    """Every result of the paper, derived and compared."""
    return gather(KEY, _train_checks, _stage_checks, _objective_checks, _optimum_checks, _model_checks)


def _train_checks() -> list[Check]:
    out = []
    laws = stage_laws()
    z1, z2, z4 = (S.teeth(g) for g in ("1", "2", "4"))
    out.append(_check("stage ratio", "single-row AI stage: u = omega_sun/omega_carrier, ring fixed (2009 paper (13b))",
                      laws.ratio.rhs, 1 + z4 / z1, compare_symbolic(laws.ratio.rhs, 1 + z4 / z1), kind=Kind.EXTENSION))
    out.append(_check("coaxiality", "single-row AI: ring teeth from coaxiality with equal modules",
                      laws.ring_from_coaxiality, z1 + 2 * z2, compare_symbolic(laws.ring_from_coaxiality, z1 + 2 * z2),
                      kind=Kind.EXTENSION))
    geometry = schemes.single_row_AI(teeth=True)
    distances = tuple(geometry.mesh_geometry(mesh).centre_distance for mesh in geometry.meshes)
    paper_names = {z1: z_sun, z2: z_planet, z4: z_ring}
    derived_distances = [sp.expand(d.subs(paper_names)) for d in distances]
    out.append(_check("step 1 centre distances", "single-row AI stage: centre distances of the meshes sun-planet and "
                      "planet-ring (equal modules; the paper numbers the stage's gears sun, planet, ring)",
                      derived_distances, list(PUBLISHED_CENTRE_DISTANCES),
                      compare_claim(all(sp.expand(d - q) == 0 for d, q in zip(derived_distances, PUBLISHED_CENTRE_DISTANCES)),
                                    f"engine mesh geometry {derived_distances}")))
    for n in (2, 3, STAGES):
        train = schemes.common_ring_train(n)
        total = train.ratio("s1", f"H{n}", fixed="4").rhs
        r4 = train.gear("4").radius
        stage_product = sp.Mul(*[1 + r4 / train.gear(f"s{i}").radius for i in range(1, n + 1)])
        out.append(_check(f"(2) u_S, n = {n}", f"{n}-stage common-ring train: total ratio i_s1Hn^(4) = prod u_i",
                          total, stage_product, compare_symbolic(total, stage_product), item="u_S"))
    return out


def _stage_checks() -> list[Check]:
    found = stage_set()
    out = [
        _check("stages: count", f"feasible single-row AI stages, ring {RING}, {SATELLITES} satellites, {Z_MIN} <= z <= {Z_MAX}",
               len(found), PUBLISHED_STAGE_COUNT, compare_exact(len(found), PUBLISHED_STAGE_COUNT)),
        _check("stages: u min", "smallest feasible stage ratio", found[0].ratio, PUBLISHED_U_MIN,
               compare_rounded(found[0].ratio, PUBLISHED_U_MIN), teeth=(found[0].sun, found[0].planet, found[0].ring)),
        _check("stages: u max", "largest feasible stage ratio", found[-1].ratio, PUBLISHED_U_MAX,
               compare_rounded(found[-1].ratio, PUBLISHED_U_MAX), teeth=(found[-1].sun, found[-1].planet, found[-1].ring)),
    ]
    return out


def _objective_checks() -> list[Check]:
    out = []
    for n in (2, 3, STAGES, 5):
        lm = lost_motion(n)
        out.append(_check(f"(1) n = {n}", f"objective (1): each carrier's error carried to H_{n}",
                          lm.objective, _published_1(n), compare_symbolic(lm.objective, _published_1(n)), item="(1)"))
    lm = lost_motion(STAGES)
    n = STAGES
    u = lm.ratios
    for i in range(1, n + 1):
        pub = backlash_symbol(i) / (diameter_symbol(i) * u[i - 1])
        out.append(_check(f"(1) Delta phi_H{i}", f"stage {i}: its error Phi_{i}/d_{3 * i - 2} carried from sun to carrier H_{i}",
                          lm.carrier_errors[i - 1], pub, compare_symbolic(lm.carrier_errors[i - 1], pub), item="Delta phi_Hi"))
    sun_route = sp.Add(*(e * t for e, t in zip(lm.sun_errors, lm.sun_transfers)))
    out.append(_check("(2) line 1", "(2) first form: each stage's error at its sun carried to the output",
                      sun_route, _published_2_first(n), compare_symbolic(sun_route, _published_2_first(n))))
    out.append(_check("(2) line 2", "(2) expanded form (1/u_S)(Phi_1/d_1 + Phi_2/d_4 u_1 + ...)",
                      lm.objective, _published_2_expanded(n), compare_symbolic(lm.objective, _published_2_expanded(n))))
    printed = _published_2_closed(n, "i")
    # by hand: an angular error at a shaft reaches the output divided by the ratios of the stages between;
    # stage i's error at its sun passes stages i..n
    by_hand = sp.Add(*(backlash_symbol(i) / diameter_symbol(i) / sp.Mul(*u[i - 1:]) for i in range(1, n + 1)))
    out.append(_check(
        "(2) closed sum", "(2) closed form as printed, prod_(j=1)^(i) u_j",
        lm.objective, printed,
        judge(compare_symbolic(lm.objective, printed),
              confirmation=confirmation("by hand: stage i's error at its sun, Phi_i/d_(3i-2), divided by the ratios "
                                        "u_i ... u_n of the stages it passes", by_hand, lm.objective),
              hypothesis="the upper limit of the product should be i - 1, as the paper's own first and expanded forms "
                         "and fig. 4 step 6 have it"),
    ))
    Fd = [a + b * ui for ui in u]
    FF, U_S = _published_fig4_FF(Fd)
    derived = lm.objective.subs({p: d * (a + b * ui) for p, d, ui in zip(lm.backlash, lm.diameters, u)})
    out.append(_check("fig. 4 FF", "fig. 4 step 6: FF with Fd_i = abi_1 + abi_2 u_i, on u_1 u_2 u_3 u_4 = U_S",
                      derived, FF, compare_symbolic(derived, FF, under={U_S: sp.Mul(*u)})))
    # (4): the objective depends on Phi_i and d_(3i-2) only through Phi_i/d_(3i-2)
    fd = [sp.Symbol(f"Phi_d_{i}", positive=True) for i in range(1, n + 1)]
    in_fd = sp.simplify(lm.objective.subs({p: f * d for p, f, d in zip(lm.backlash, fd, lm.diameters)}))
    left = sorted(str(d) for d in in_fd.free_symbols & set(lm.diameters))
    out.append(_check("(4)", "the objective with Phi_i = Phi d_i d_(3i-2): the diameters cancel, so Phi d_i(p_i) is all a "
                      "stage contributes", in_fd, "a function of Phi d_i and u_i only",
                      compare_claim(not left, f"diameters left: {left or 'none'}")))
    out.append(_backlash_check())
    return out


def _backlash_check() -> Check:
    """(3) from the engine's contact conditions of one stage, written for small turns with backlash.

    With the carrier held and the ring fixed, each mesh lets its two pitch points part by
    its backlash along the pitch line: the contact condition (equal pitch-point
    velocities, here equal small displacements) holds up to +- j.  The sun's lost angle
    times its pitch radius d_(3i-2)/2 is the stage's Phi_i, the quantity (1) divides by d.
    """
    stage = schemes.single_row_AI()
    turn = {S.omega(n): sp.Symbol(f"dphi_{n}", real=True) for n in ("1", "2", "H", "4")}
    held = {turn[S.omega("H")]: 0, turn[S.omega("4")]: 0}
    r1 = stage.gear("1").radius
    lost = []
    for s1, s2 in itertools.product((1, -1), repeat=2):
        eqs = [(e.lhs - e.rhs).xreplace(turn).subs(held) - sign * j
               for e, sign, j in zip(stage.contact_conditions(), (s1, s2), (J_SUN, J_RING))]
        sol = sp.solve(eqs, [turn[S.omega("1")], turn[S.omega("2")]], dict=True)[0]
        lost.append(sp.expand(r1 * sol[turn[S.omega("1")]]))
    # the largest lost displacement at the sun's pitch circle, chosen at sample values of every symbol
    sample = {x: n + 2 for n, x in enumerate(sorted(set().union(*(e.free_symbols for e in lost)), key=str))}
    derived = max(lost, key=lambda e: float(e.subs(sample)))
    return _check("(3)", "a stage's lost motion at the sun's pitch circle, carrier held and ring fixed, from the engine's "
                  "contact conditions with backlashes j_12 (sun-planet) and j_23 (planet-ring)",
                  derived, PUBLISHED_3, compare_symbolic(derived, PUBLISHED_3),
                  extra_cases=[str(x) for x in lost])


def _optimum_checks() -> list[Check]:
    out = []
    best = optimum()
    for i, pub in enumerate(PUBLISHED_OPTIMUM, 1):
        value = best.exact_ratios[i - 1]
        out.append(_check(f"fig. 4 u_{i}", f"optimal u_{i} (U = {TOTAL}, {U_LOWER} <= u <= {U_UPPER}), bound: {best.active[i - 1]}",
                          value, pub, compare_rounded(value, pub)))
    derived_value = best.exact_objective
    frozen = optimize_split(TOTAL, STAGES, lower=U_LOWER, upper=U_UPPER, model=mathcad_model())
    frozen_value = frozen.exact_objective
    out.append(_check(
        "fig. 4 FF value", "objective at the optimum with Fd_i = a + b u_i as (5) and fig. 4 step 4 define it",
        derived_value, PUBLISHED_OBJECTIVE,
        judge(compare_rounded(derived_value, PUBLISHED_OBJECTIVE),
              alternative=alternative(
                  f"MathCAD evaluates the assignments Fd_i := abi_1 + abi_2 u_i of step 4 once, at the start values "
                  f"u_i = {START} of step 2, so FF uses the constant Fd = {sp.N(mathcad_model().expr, 6)}",
                  frozen_value, PUBLISHED_OBJECTIVE, compare_rounded)),
    ))
    same = tuple(frozen.exact_ratios) == tuple(best.exact_ratios)
    out += _kkt_checks()
    out.append(_check("fig. 4 optimum (MathCAD)", "the frozen-Fd objective has the same minimiser as the objective of (5)",
                      tuple(frozen.exact_ratios), tuple(best.exact_ratios), compare_exact(int(same), 1),
                      kind=Kind.CONSISTENCY))
    return out


def _kkt_checks() -> list[Check]:
    """Why the output stages take the upper bound: the gradient in ln u falls along the train."""
    lm = lost_motion(STAGES)
    u, n = lm.ratios, STAGES
    ai = sp.symbols(f"a_1:{n + 1}", real=True)
    bi = sp.symbols(f"b_1:{n + 1}", real=True)
    f = lm.objective.subs({p: d * (ai[i] + bi[i] * u[i]) for i, (p, d) in enumerate(zip(lm.backlash, lm.diameters))})
    g = [u[j] * sp.diff(f, u[j]) for j in range(n)]
    out = []
    for j in range(n - 1):
        derived = sp.factor(g[j] - g[j + 1])
        closed = (ai[j + 1] + bi[j]) / sp.Mul(*u[j + 1:])
        out.append(_check(f"KKT g_{j + 1} - g_{j + 2}", "gradient difference in x = ln u for linear models a_i + b_i u "
                          "(closed form of the notes, not in the paper)", derived, closed, compare_symbolic(derived, closed),
                          kind=Kind.EXTENSION))
    return out


def _model_checks() -> list[Check]:
    out = []
    slope = sp.Rational(LINE_J_END - LINE_J0, LINE_A_END)
    out.append(_check("(7) slope", "(7): slope (120 - 50)/180 of the two-point line: arithmetic on the paper's own "
                      "numbers, so a consistency check", slope, PUBLISHED_SLOPE, compare_rounded(slope, PUBLISHED_SLOPE),
                      kind=Kind.CONSISTENCY))
    # (6) and (8) are GOST formulas the paper quotes: symkin.mechanisms.multistage.lostmotion holds them as given inputs
    # (transcribed, not derived).  What can be checked is the paper's printing (extensions): a length formula
    # must scale with its lengths, and (8) without bearing clearances must reduce to (6).
    lam = sp.Symbol("lambda", positive=True)
    j, t1, t2, fa = sp.symbols("j_min T_H1 T_H2 f_a", positive=True)
    e1, e2, g1, g2 = sp.symbols("E_HS1 E_HS2 G_r1 G_r2", positive=True)
    printed6, printed8 = _published_6(), _published_8().xreplace(
        {sp.Symbol(n): v for n, v in (("T_H1", t1), ("T_H2", t2), ("f_a", fa), ("E_HS1", e1), ("E_HS2", e2),
                                       ("G_r1", g1), ("G_r2", g2))})

    def scaling_defect(expr):
        lengths = expr.free_symbols - {lam}
        return sp.factor(sp.expand(expr.xreplace({x: lam * x for x in lengths}) - lam * expr))

    defect8 = scaling_defect(printed8)
    reduced8 = printed8.subs({g1: 0, g2: 0}).subs(sp.Rational(7, 10) * (e1 + e2), j)
    out.append(_check(
        "(8)", "(8) as printed scales as a length (GOST 21098-82, quoted in the paper, not derived)",
        defect8, 0, compare_exact(defect8, 0), kind=Kind.EXTENSION,
    ))
    # the alternative reading of (6): the radical's bar ends before the last term of its argument
    (root,) = [term for term in sp.Add.make_args(reduced8) if term.is_Pow and term.exp == sp.Rational(1, 2)]
    tail = sp.Add(*(term for term in sp.Add.make_args(root.base) if term.has(fa)))
    short_bar = reduced8 - root + sp.sqrt(root.base - tail) + tail
    out.append(_check(
        "(6)", "(6) as printed against (8) with no bearing clearances and its guaranteed part as j_min (GOST 9178-81, "
        "quoted, not derived)", reduced8, printed6,
        judge(compare_symbolic(reduced8, printed6),
              alternative=alternative("the radical's bar ends before '+ 2 f_a^2' (as printed, a length plus a squared "
                                      f"length: scaling every length by lambda changes it by {scaling_defect(printed6)} "
                                      "beyond lambda times itself)", short_bar, printed6)),
        kind=Kind.EXTENSION,
    ))
    out += _figure_reference_checks()
    return out


def _figure_reference_checks() -> list[Check]:
    """The figures the text names, against the figure whose caption shows the thing."""
    out = []
    for label, what, printed, words, second, where in FIGURE_REFERENCES:
        shown = [n for n, caption in FIGURE_CAPTIONS.items() if words in caption]
        derived = shown[0] if len(shown) == 1 else sp.nan
        out.append(_check(
            label, f"the figure that shows {what}, from the paper's captions", derived, printed,
            judge(compare_exact(derived, printed),
                  confirmation=confirmation(where, second, derived, compare_exact),
                  hypothesis="a figure number left from an earlier numbering of the figures"),
            captions={str(n): c for n, c in FIGURE_CAPTIONS.items()},
            rests_on="the paper's own captions and text (settled by looking them up, not by the engine)",
        ))
    return out


# ---------------------------------------------------------------------------- notes and figures
def notes() -> list[str]:
    """Remarks printed under the paper's checks in the report: the feasible stages, the continuous optimum and why its bounds are active."""
    found = stage_set()
    best = optimum()
    line = line_model()
    out = [
        "Stages (ring 180, 3 satellites, 18 <= z <= 180), sun/planet teeth and ratio: "
        + "; ".join(f"{s.sun}/{s.planet}: {s.ratio}" for s in found) + ".",
        f"Candidate suns rejected (first failing condition): {', '.join(f'{k} {v}' for k, v in found.rejected.items())}. The assembly condition makes the sun a "
        "multiple of 6 and cuts 64 coaxial suns to 22; with 3 satellites the neighbour condition binds only below "
        "z_sun = 16, so it never rejects a sun of at least 18 teeth.",
        "Continuous optimum (fig. 4 case): " + " | ".join(best.explain()),
        "Why the bounds are active, for any linear model Phi/d = a_i + b_i u: in x = ln u the objective is "
        "sum_i [a_i exp(-S_i) + b_i exp(-S_(i+1))] with S_i = x_i + ... + x_n, so g_j - g_(j+1) = (a_(j+1) + b_j) exp(-S_(j+1)) "
        "(the KKT checks): with a_(j+1) + b_j > 0 moving ratio toward the output always helps, the "
        "output stages sit on their upper bounds and one input stage takes what is left. The minimiser does not depend on "
        "a and b, which is why the MathCAD slip in the objective value leaves the optimum intact.",
        f"Line (7) through the engine's centre distances gives exactly Phi/d = {line.expr} for m = 0.5 mm and ring 180 "
        "(each centre distance is m z_ring u/(4(u - 1))); curve 2 of fig. 3. The coefficients of (5) (0.854, 0.858) "
        "and the regression (51.932, 0.352) need the GOST 9178-81 tables, which are not in the paper: not reproduced.",
        "Delta phi is 'relative': Phi_i/d_(3i-2) is half the angle in radians that a circular backlash Phi_i turns the "
        "sun (2 Phi/d); the factor cancels from the optimum.",
        "Sign of E_HS in (8): the paper takes E_HS negative for external gears; two external gears would then give a "
        "negative guaranteed part. GOST 21098-82 is not available here; symkin takes E_HS as given.",
    ]
    for tol in ("0.01", "0.05"):
        d = discrete(tol)
        rows = "; ".join(
            f"{', '.join(f'{s.sun}/{s.planet}' for s in x.stages)} u = ({', '.join(str(r) for r in x.ratios)}) total {x.total} "
            f"({float(x.deviation):+.2%}) objective {float(x.objective):.6f}"
            for x in d.designs
        )
        out.append(f"Discrete designs, tolerance {tol}: {d.message()}: {rows}")
    return out


#: Captions of the figures in the report, and the checks (label prefixes) each illustrates.
REPORT_FIGURES = {
    "khai2014_stages": ("The feasible stages of one ring: Phi/d of each stage error model and the centre distance "
                        "a_w against the stage ratio u.", ("stages:",)),
    "khai2014_split": ("The split of the total ratio over the stages: the least objective with one stage ratio held, "
                       "and the best discrete designs.", ("fig. 4",)),
}


def figures(folder: Path) -> list[Path]:
    """Draw the paper's figures into ``folder`` (the stage model and the ratio split); returns the files written."""
    from symkin.viz.figures import save
    from symkin.viz.split import split_figure, stage_model_figure

    paths = []
    fig = stage_model_figure(
        stage_set(),
        {"(5): 0.854 + 0.858 u (fig. 3, curve 1)": paper_model(), "from line (7), derived (fig. 3, curve 2 analogue)": line_model()},
        module=float(MODULE),
        title="KhAI 2014: 22 feasible stages (ring 180, 3 satellites), Phi/d and a_w (mm, m = 0.5)",
    )
    paths += save(fig, folder / "khai2014_stages")
    fig = split_figure(optimum(), discrete("0.05"), title="KhAI 2014 fig. 4 case: least objective with u_i held")
    paths += save(fig, folder / "khai2014_split")
    return paths
