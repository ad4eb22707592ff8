"""Tooth-number equations, assembly, existence regions and synthesis, each against an
independent route: the engine's ratio on the built mechanism, a tooth-phase brute force,
a sampled Willis ratio, and a plain enumeration with helix angles found by bisection."""

import math
import random
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from symkin import InputError
from symkin.mechanisms.helical import HelicalTrain
from symkin.mechanisms.helical import balanced as HS
from symkin.mechanisms.helical.balanced import (
    DELTA,
    RATIO,
    HelicalRequest,
    K,
    P,
    Q,
    X,
    Z,
    synthesize_helical,
)
from symkin.statics import planet_forces

SCHEMES = ("AI", "AA", "II")
INTERNAL = {"AI": (False, True), "AA": (False, False), "II": (True, True)}


# ---------------------------------------------------------------- independent routes (test-only)
def phase_assembles(scheme, teeth, k):
    """Can k identical planets sit at azimuths j/k (turns)?  Tooth phases at each contact:
    an external mesh keeps Zc psi + Zp (psi - theta_p) fixed mod 1, an internal one
    Zc psi - Zp (psi - theta_p); search the planet's rotation among the rim-2 pitches."""
    z1, z2, z3, z4 = teeth
    in1, in4 = INTERNAL[scheme]
    for j in range(1, k):
        psi = Fraction(j, k)
        # mesh 1-2 fixes z2 * delta mod 1
        t12 = (z1 - z2) * psi if in1 else (z1 + z2) * psi
        found = False
        for n in range(z2):
            delta = (-t12 + n) / z2 if in1 else (t12 + n) / z2
            t34 = (z4 - z3) * psi + z3 * delta if in4 else (z4 + z3) * psi - z3 * delta
            if t34.denominator == 1:
                found = True
                break
        if not found:
            return False
    return True


def willis_ratio(scheme, r1, r2, r3, r4):
    """Textbook: i_1H^(4) = 1 - i_14^(H), i_14^(H) = -+ r2 r4 / (r1 r3)."""
    return 1 + r2 * r4 / (r1 * r3) if scheme == "AI" else 1 - r2 * r4 / (r1 * r3)


def centre_sums(scheme, teeth):
    z1, z2, z3, z4 = teeth
    return {"AI": (z1 + z2, z4 - z3), "AA": (z1 + z2, z3 + z4), "II": (z1 - z2, z4 - z3)}[scheme]


# ---------------------------------------------------------------- tooth equations
@pytest.mark.parametrize("scheme", SCHEMES)
def test_tooth_equations_rebuild_random_tooth_sets_with_the_engines_ratio(scheme):
    rng = random.Random(5 + len(scheme) * 3 + ord(scheme[1]))
    sol = HS.tooth_equations(scheme).solution
    done = 0
    while done < 2:
        z2, z3 = rng.randint(17, 70), rng.randint(17, 70)
        z1 = rng.randint(17, 90) if scheme != "II" else z2 + rng.randint(8, 60)
        z4 = rng.randint(17, 90) if scheme == "AA" else z3 + rng.randint(8, 60)
        teeth = (z1, z2, z3, z4)
        ks = [kk for kk in range(1, 7) if HS.assembly_integers(scheme, teeth, kk)]
        if not ks or (scheme != "AI" and z1 * z3 == z2 * z4):  # not assemblable, or i = 0
            continue
        t = HelicalTrain(scheme, teeth, (2, 2), (0.2, 0.2))
        law = t.mechanism.ratio("1", "H", fixed="4").rhs  # the engine on the built mechanism
        r = t.working_radii_exact
        kk = max(ks)
        p, q = HS.assembly_integers(scheme, teeth, kk)
        params = {RATIO: law, X: sp.Rational(z2, z3), DELTA: sp.Rational(r[1]) / sp.Rational(r[2]), K: kk, P: p, Q: q}
        rebuilt = tuple(sp.nsimplify(sol[Z[n]].subs(params)) for n in (1, 2, 3, 4))
        assert rebuilt == teeth, (scheme, teeth, params)
        done += 1


def test_tooth_chain_is_the_solution_step_by_step():
    for scheme in SCHEMES:
        eqs = HS.tooth_equations(scheme)
        z1 = eqs.solution[Z[1]]
        assert sp.simplify(eqs.chain[Z[4]].subs(Z[1], z1) - eqs.solution[Z[4]]) == 0
        assert sp.simplify(eqs.chain[Z[2]].subs(Z[1], z1) - eqs.solution[Z[2]]) == 0


# ---------------------------------------------------------------- assembly
@pytest.mark.parametrize("scheme", SCHEMES)
def test_assembly_condition_against_a_tooth_phase_brute_force(scheme):
    rng = random.Random(11)
    agree = {True: 0, False: 0}
    for _ in range(150):
        z2, z3 = rng.randint(12, 40), rng.randint(12, 40)
        z1 = rng.randint(12, 60) if scheme != "II" else z2 + rng.randint(5, 40)
        z4 = rng.randint(12, 60) if scheme == "AA" else z3 + rng.randint(5, 40)
        teeth = (z1, z2, z3, z4)
        k = rng.randint(2, 6)
        pq = HS.assembly_integers(scheme, teeth, k)
        brute = phase_assembles(scheme, teeth, k)
        assert (pq is not None) == brute, (scheme, teeth, k)
        agree[brute] += 1
        if pq is not None:  # and P, Q satisfy the derived condition exactly
            p, q = pq
            i = Fraction(z1 * z3 + (1 if scheme == "AI" else -1) * z2 * z4, z1 * z3)
            assert Fraction(z1) * i / k - q * Fraction(z2, z3) == p
    assert agree[True] > 5 and agree[False] > 5  # both outcomes exercised


# ---------------------------------------------------------------- existence regions
@pytest.mark.parametrize("scheme", SCHEMES)
def test_existence_interval_against_sampled_willis_ratios(scheme):
    r1s = np.geomspace(1e-3, 1e5, 20001)
    for delta in (0.3, 0.7, 0.95, 1.05, 1.6, 2.8):
        for k in (2, 3, 4, 6):
            r2, r3 = delta, 1.0
            r4 = {"AI": r1s + r2 + r3, "AA": r1s + r2 - r3, "II": r1s - r2 + r3}[scheme]
            arm = r1s - r2 if scheme == "II" else r1s + r2
            ok = (r4 > 0) & (arm > 0) & (arm * math.sin(math.pi / k) > max(r2, r3))
            if scheme == "AI":
                ok &= r4 - r3 > 0
            i = willis_ratio(scheme, r1s, r2, r3, r4)[ok]
            interval = HS.existence_interval(scheme, k, sp.nsimplify(delta))
            lo, hi = float(interval[0]), float(interval[1])
            assert i.min() >= lo - 1e-12 * abs(lo) and i.max() <= hi + 1e-12 * abs(hi)
            if math.isinf(hi):  # k = 2: no neighbour limit on this side
                assert i.max() > 100 * abs(lo) and i.min() - lo < 1e-3 * abs(lo)
            elif math.isinf(lo):
                assert i.min() < -100 * abs(hi) and hi - i.max() < 1e-3 * abs(hi)
            else:
                span = hi - lo
                assert i.min() - lo < 1e-3 * span and hi - i.max() < 1e-3 * span


def test_closed_form_bounds_agree_with_the_evaluated_interval():
    rng = random.Random(3)
    for scheme in SCHEMES:
        lower_case, upper_case = HS.existence_bounds(scheme)
        for _ in range(4):
            k = rng.choice([2, 3, 4, 5, 6, 8])
            for b, d in ((lower_case, sp.Rational(rng.randint(1, 99), 100)), (upper_case, sp.Rational(rng.randint(101, 400), 100))):
                interval = HS.existence_interval(scheme, k, d)
                lo, hi = (b.lower.subs({DELTA: d, K: k}), b.upper.subs({DELTA: d, K: k}))
                if hi.has(sp.zoo) or lo.has(sp.zoo):  # k = 2: unbounded on one side
                    continue
                assert float(interval[0]) == pytest.approx(float(lo), rel=1e-12)
                assert float(interval[1]) == pytest.approx(float(hi), rel=1e-12)


def test_existence_range_of_each_scheme():
    assert HS.existence_range("AI") == ((1, sp.oo),)
    assert HS.existence_range("AA") == ((-sp.oo, 0), (0, 1))
    assert HS.existence_range("II") == ((-sp.oo, 0), (0, 1))


# ---------------------------------------------------------------- synthesis vs plain enumeration
def brute_force(scheme, ratio, tol, k, mods, beta_lim, zlim, dmin=8):
    """Every tooth set in the limits (all Z1..Z4, exact integer ratio test); helix angles by
    bisection on coaxiality along beta12 = asin(mu sin beta34) (equal leads); assembly by
    tooth phases; neighbours by tip circles."""
    m12, m34 = mods
    bmin, bmax = (math.radians(b) for b in beta_lim)
    sign = 1 if scheme == "AI" else -1
    in1, in4 = INTERNAL[scheme]
    zs = np.arange(zlim[0], zlim[1] + 1, dtype=np.int64)
    b2, b3, b4 = (a.ravel() for a in np.meshgrid(zs, zs, zs, indexing="ij"))
    p, q = ratio.numerator, ratio.denominator
    hits = []
    for one in zs:  # every Z1, and all Z2, Z3, Z4 at once
        num, den = one * b3 + sign * b2 * b4, one * b3
        ok = np.abs(num * q - p * den) * tol.denominator <= tol.numerator * abs(p) * den
        if in1:
            ok &= one - b2 >= dmin
        if in4:
            ok &= b4 - b3 >= dmin
        hits.append(np.stack([np.full(ok.sum(), one), b2[ok], b3[ok], b4[ok]]))
    z1, z2, z3, z4 = np.concatenate(hits, axis=1).astype(float)
    s12 = z1 - z2 if in1 else z1 + z2
    s34 = z4 - z3 if in4 else z4 + z3
    mu = m12 * z2 / (m34 * z3)

    def f(b34):  # a_12 - a_34 (times 2), beta12 from equal leads; nan where no beta12 exists
        s = mu * np.sin(b34)
        with np.errstate(invalid="ignore"):
            return m12 * s12 / np.sqrt(1 - s * s) - m34 * s34 / np.cos(b34)

    grid = np.linspace(bmin, bmax, 801)
    values = np.array([f(np.full_like(mu, g)) for g in grid])  # grid x candidates
    found = {}
    for n in range(len(grid) - 1):
        a, b = values[n], values[n + 1]
        hit = np.nonzero(a * b <= 0)[0]
        if not len(hit):
            continue
        lo, hi = np.full(len(hit), grid[n]), np.full(len(hit), grid[n + 1])
        sub = (mu[hit], s12[hit], s34[hit])
        for _ in range(60):
            mid = (lo + hi) / 2
            sm = sub[0] * np.sin(mid)
            fm = m12 * sub[1] / np.sqrt(1 - sm * sm) - m34 * sub[2] / np.cos(mid)
            sl = sub[0] * np.sin(lo)
            fl = m12 * sub[1] / np.sqrt(1 - sl * sl) - m34 * sub[2] / np.cos(lo)
            left = fl * fm <= 0
            lo, hi = np.where(left, lo, mid), np.where(left, mid, hi)
        for j, b34 in zip(hit, (lo + hi) / 2):
            b12 = math.asin(mu[j] * math.sin(b34))
            teeth = (int(z1[j]), int(z2[j]), int(z3[j]), int(z4[j]))
            if not (bmin <= b12 <= bmax) or not phase_assembles(scheme, teeth, k):
                continue
            a_w = m12 * s12[j] / (2 * math.cos(b12))
            tips = (m12 * z2[j] / math.cos(b12) + 2 * m12, m34 * z3[j] / math.cos(b34) + 2 * m34)
            if k > 1 and not 2 * a_w * math.sin(math.pi / k) > max(tips):
                continue
            found[teeth] = (b12, b34)
    return found


@pytest.mark.parametrize("scheme, ratio, mods, k, zlim", [
    ("AI", Fraction(4), (2, 3), 3, (17, 50)),
    ("AA", Fraction(1, 5), (2, 2.5), 3, (17, 40)),
    ("II", Fraction(1, 5), (2, 2.5), 2, (17, 56)),
])
def test_synthesis_finds_exactly_what_plain_enumeration_finds(scheme, ratio, mods, k, zlim):
    tol, beta = Fraction(3, 100), (8, 30)
    res = synthesize_helical(scheme=scheme, ratio=ratio, tolerance=tol, satellites=k,
                     normal_modules=(Fraction(mods[0]).limit_denominator(), Fraction(str(mods[1]))),
                     beta_min_deg=beta[0], beta_max_deg=beta[1], teeth_min=zlim[0], teeth_max=zlim[1], top=None)
    brute = brute_force(scheme, ratio, tol, k, mods, beta, zlim)
    got = {d.teeth: d for d in res.designs}
    assert set(got) == set(brute) and len(got) == res.found > 0
    for teeth, (b12, b34) in brute.items():
        assert got[teeth].train.betas[0] == pytest.approx(b12, abs=1e-9)
        assert got[teeth].train.betas[1] == pytest.approx(b34, abs=1e-9)


# ---------------------------------------------------------------- every design, re-checked from its integers
@pytest.fixture(scope="module")
def designs():
    out = []
    for scheme, ratio, mods, zmax in (("AI", 25, (2, Fraction("2.5")), 120), ("AA", Fraction(1, 50), (2, Fraction("2.5")), 100),
                                      ("II", Fraction(1, 50), (2, Fraction("2.5")), 100), ("AI", 9, (3, 2), 90)):
        res = synthesize_helical(scheme=scheme, ratio=ratio, tolerance=Fraction("0.05"), satellites=3, normal_modules=mods,
                         teeth_max=zmax, top=None)
        assert res.designs, (scheme, ratio, res.reason)
        out += [(res.request, d) for d in res.designs]
    return out


def test_every_design_is_coaxial_assembles_and_has_room(designs):
    for req, d in designs:
        teeth, (b12, b34) = d.teeth, d.train.betas
        m12, m34 = (float(m) for m in req.normal_modules)
        s12, s34 = centre_sums(req.scheme, teeth)
        a12, a34 = m12 * s12 / (2 * math.cos(b12)), m34 * s34 / (2 * math.cos(b34))
        assert abs(a12 - a34) <= 1e-12 * a12  # coaxial
        assert phase_assembles(req.scheme, teeth, req.satellites)  # assembly, by tooth phases
        z1, z2, z3, z4 = teeth
        tips = (m12 * z2 / math.cos(b12) + 2 * m12, m34 * z3 / math.cos(b34) + 2 * m34)
        assert 2 * a12 * math.sin(math.pi / req.satellites) > max(tips)  # neighbours
        lo, hi = (math.radians(float(b)) for b in (req.beta_min_deg, req.beta_max_deg))
        assert lo <= b12 <= hi and lo <= b34 <= hi
        assert req.teeth_min <= min(teeth) and max(teeth) <= req.teeth_max
        i = Fraction(z1 * z3 + (1 if req.scheme == "AI" else -1) * z2 * z4, z1 * z3)
        assert i == d.ratio and abs(i - req.ratio) <= req.tolerance * abs(req.ratio)
        p, q = d.assembly
        assert Fraction(z1) * i / req.satellites - q * Fraction(z2, z3) == p


def test_every_design_passes_the_independent_force_check(designs):
    worst = 0.0
    for _, d in designs:
        f = planet_forces(d.train)
        worst = max(worst, f.axial_residual)
        assert f.hand_mismatch == 0
        assert f.ratio == pytest.approx(float(d.ratio), rel=1e-11)
    assert worst <= 1e-12


def test_every_design_lies_in_its_existence_region(designs):
    for req, d in designs[::7]:
        interval = HS.existence_interval(req.scheme, req.satellites, sp.nsimplify(d.train.working_diameter_ratio, rational=True))
        assert float(interval[0]) < float(d.ratio) < float(interval[1])


def test_designs_are_ranked_by_error_then_size():
    res = synthesize_helical(scheme="AI", ratio=12, tolerance=Fraction("0.02"), satellites=3, normal_modules=(2, Fraction("2.5")), teeth_max=90, top=None)
    keys = [(d.relative_error, d.envelope_diameter) for d in res.designs]
    assert keys == sorted(keys)
    top = synthesize_helical(scheme="AI", ratio=12, tolerance=Fraction("0.02"), satellites=3, normal_modules=(2, Fraction("2.5")), teeth_max=90, top=5)
    assert [d.teeth for d in top.designs] == [d.teeth for d in res.designs[:5]] and top.found == res.found


def test_equal_rims_leave_the_helix_angle_free():
    res = synthesize_helical(scheme="AI", ratio=5, tolerance=0, satellites=2, normal_modules=(2, 2), teeth_max=90, top=None)
    free = [d for d in res.designs if d.helix_free]
    assert (20, 30, 30, 80) in [d.teeth for d in free]
    for d in free:
        assert d.betas_deg[0] == pytest.approx(8) and d.betas_deg[1] == pytest.approx(8)
        assert planet_forces(d.train).axial_residual < 1e-14


# ---------------------------------------------------------------- input and empty results
@pytest.mark.parametrize("change, message", [
    (dict(beta_max_deg=45), "strictly between 0 and 45"),
    (dict(beta_min_deg=0), "strictly between 0 and 45"),
    (dict(beta_min_deg=-5), "strictly between 0 and 45"),
    (dict(beta_min_deg=30, beta_max_deg=10), "exclude every design"),
    (dict(teeth_min=60, teeth_max=20), "exclude every design"),
    (dict(normal_modules=(0, 2)), "must be positive"),
    (dict(normal_modules=(2, -1)), "must be positive"),
    (dict(satellites=0), "at least 1"),
    (dict(satellites=2.5), "whole number"),
    (dict(tolerance=-0.1), "from 0 to less than 1"),
    (dict(tolerance=1), "from 0 to less than 1"),
    (dict(ratio=0), "must not be 0"),
    (dict(ratio="abc"), "is the text 'abc'.*symkin.parse"),
    (dict(ratio="__import__('os')"), "is the text .*symkin.parse"),
    (dict(ratio=[25]), "must be a number"),
    (dict(teeth_min=1, teeth_max=2000), "narrow the range"),
    (dict(scheme="AX"), "unknown scheme"),
])
def test_bad_input_is_refused_with_one_sentence(change, message):
    args = dict(scheme="AI", ratio=25, tolerance=Fraction("0.02"), satellites=3, normal_modules=(2, 2.5))
    args.update(change)
    with pytest.raises(InputError, match=message) as err:
        HelicalRequest(**args)
    assert "\n" not in str(err.value)


def test_a_ratio_in_no_region_names_the_nearest():
    with pytest.raises(InputError, match=r"no existence region of scheme AI.*nearest is its end i = 1; schemes AA and II"):
        synthesize_helical(scheme="AI", ratio=Fraction("0.5"), satellites=3, normal_modules=(2, 2))
    with pytest.raises(InputError, match=r"scheme AA.*nearest is its end i = 1"):
        synthesize_helical(scheme="AA", ratio=3, satellites=3, normal_modules=(2, 2))


def test_an_empty_result_says_why():
    res = synthesize_helical(scheme="AI", ratio=200, tolerance=Fraction("0.01"), satellites=3, normal_modules=(2, 2), teeth_max=60)
    assert res.found == 0 and not res.designs and "no tooth set" in res.reason
    res = synthesize_helical(scheme="II", ratio=Fraction("1/50"), tolerance=Fraction("0.05"), satellites=3, normal_modules=(2, 2), teeth_max=80)
    assert res.found == 0 and "helix angles" in res.reason
    res = synthesize_helical(scheme="AI", ratio=25, tolerance=Fraction("0.02"), satellites=12, normal_modules=(2, Fraction("2.5")), teeth_max=120)
    assert res.found == 0 and ("neighbour" in res.reason or "assembled" in res.reason)
