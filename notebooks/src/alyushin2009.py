# %% [markdown]
# # Alyushin & Verzhanskiy (2009), *Kinematics of planetary transmissions*, reproduced
#
# The paper derives the kinematics of planetary trains without Willis' inversion: each
# link's plane motion is the superposition of a pole's motion and a rotation (its
# eqs. 4-6), and at each pitch point the two gears in mesh have one velocity. symkin's
# engine is built on exactly these two ideas. This notebook walks through the paper:
#
# 1. the four schemes of its fig. 1 and their coaxiality conditions,
# 2. the transmission ratios (13), (13a), (13b), (17), (22), (22a),
# 3. the general differential (23a)-(25a), printed as LaTeX ready for a paper,
# 4. the numeric examples at the end of the paper, as exact rationals,
# 5. the one slip of the published text, explained by a computed alternative, and a digit
#    the OCR lost,
# 6. planet-particle trajectories and their speed and acceleration,
# 7. the full verification table that `symkin reproduce alyushin2009` prints.
#
# Everything below is *derived* by symkin; the published forms come from
# `symkin.derivations.alyushin2009` and are only compared against.

# %%
%matplotlib inline
import sympy as sp
from IPython.display import Math, display

import symkin
from symkin import schemes, symbols as S
from symkin.derivations import alyushin2009 as paper

print(paper.CITATION)

# %% [markdown]
# ## 1. The schemes and their coaxiality
#
# Central gears 1 and 4 share the main axis; the planet carries rims 2 (meshing with 1)
# and 3 (meshing with 4) on carrier H. A = external mesh, I = internal; `AI1` is the
# single-row AI (rims 2 and 3 are one gear). Each mesh puts the planet axis at a centre
# distance from the main axis; coaxiality says they agree.

# %%
for kind in ("AI1", "AI", "AA", "II"):
    mech = schemes.scheme(kind)
    (cond,) = mech.coaxiality
    display(Math(rf"\text{{{kind}:}}\quad " + symkin.latex(cond)))

# %% [markdown]
# ## 2. Transmission ratios with gear 4 fixed
#
# `ratio("1", "H", fixed="4")` is the paper's $i_{1H}^{(4)} = \omega_1/\omega_H$. In tooth
# numbers (a common module cancels):

# %%
for kind in ("AI1", "AI", "AA", "II"):
    law = schemes.scheme(kind, teeth=True).ratio("1", "H", fixed="4")
    display(Math(rf"\text{{{kind}:}}\quad " + symkin.latex(law)))

# %% [markdown]
# The published forms, (13b) for the single row and (13a)/(22a) for the two-row schemes,
# agree with the derived laws exactly (the difference cancels to zero):

# %%
for kind, (label, published) in paper.PUBLISHED_RATIO_TEETH.items():
    derived = schemes.scheme(kind, teeth=True).ratio("1", "H", fixed="4").rhs
    print(f"{kind:4} {label:6} derived - published = {sp.cancel(derived - published)}")

# %% [markdown]
# ## 3. The general differential: omega_1 and omega_4 given
#
# With both central gears driven, the carrier and planet speeds follow from the two
# contact conditions. `symkin.latex` prints them aligned at `=`, with the paper's
# equation numbers, and breaks long right-hand sides over lines (`width=`):

# %%
speeds = schemes.two_row("AI").speeds({"1": S.omega("1"), "4": S.omega("4")})
print(symkin.latex(speeds, number=["23a.1", "23a.2"]))
display(Math(symkin.latex(speeds)))

# %% [markdown]
# A law too long for one line, such as the acceleration (eq. 6) of a planet particle
# (a, b) with both central gears driven, is broken at `+` and `-`, inside brackets too:

# %%
a, b = sp.symbols("a b", real=True)
motion = schemes.two_row("AI").motion({"1": S.omega("1"), "4": S.omega("4")})
w_x = motion.particle("23", (a, b)).acceleration[0]
display(Math(symkin.latex(sp.Eq(sp.Symbol("w_x"), w_x), width=60)))

# %% [markdown]
# The paper writes these laws for a coaxial mechanism, r4 = r1 + r2 + r3. Substituting the
# coaxiality condition that the engine derived turns the derived law into the published one:

# %%
for kind, (label, pub_H, pub_23) in paper.PUBLISHED_DIFFERENTIAL.items():
    mech = schemes.two_row(kind)
    sol = mech.speeds({"1": S.omega("1"), "4": S.omega("4")})
    under = paper.coaxial_substitution(mech)
    same_H = sp.cancel((sol["H"] - pub_H).subs(under)) == 0
    same_23 = sp.cancel((sol["23"] - pub_23).subs(under)) == 0
    print(f"{kind} {label}: omega_H agrees: {same_H}, omega_23 agrees: {same_23}, under {under}")

# %% [markdown]
# ## 4. The numeric examples, exactly
#
# Ratios from tooth numbers are exact rationals. The paper's "more than 50 times" is an
# inequality (the derived i_H1 is 101/2); its 198 is 20000/101 rounded.

# %%
import warnings

rows = []
kind, teeth, bound = paper.FIFTY_TIMES
value = schemes.two_row(kind, teeth=teeth).ratio("H", "1", fixed="4").rhs
rows.append(f"{kind} z = {str(teeth):22} i_H1^(4) = {str(value):>10} = {float(value):>12.6g}   published: more than {bound}")
for label, kind, teeth, driver, driven, published in paper.EXAMPLES:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", symkin.CoaxialityWarning)  # the 10000 set: see section 5
        mech = schemes.two_row(kind, teeth=teeth)
    value = mech.ratio(driver, driven, fixed="4").rhs
    rows.append(f"{kind} z = {str(teeth):22} i_{driver}{driven}^(4) = {str(value):>10} = {float(value):>12.6g}   published {published}")
print("\n".join(rows))

# %% [markdown]
# ## 5. A slip of the published text, and a digit the OCR lost
#
# **The 10000 example is not coaxial.** With equal modules, z = (100, 99, 100, 101) puts the
# planet axis at 199 m/2 by mesh 1-2 and at 201 m/2 by mesh 3-4. The paper computes the
# ratio anyway (so does symkin, with a warning: the laws hold for working pitch radii), and
# says the centre distances differ by 2 m; they differ by one module. The verdict is a slip
# because a computed alternative reproduces the printed 2m: the same distances read as
# diameters, the gap between the pitch-diameter sums m(z1 + z2) and m(z3 + z4).

# %%
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always", symkin.CoaxialityWarning)
    mech = schemes.two_row("AA", teeth=(100, 99, 100, 101))
print(caught[0].message)
(planet, d12, d34), = mech.coaxiality_defects()
print("gap between the centre distances:", sp.simplify(d34 - d12))
checks = {c.label: c for c in paper.checks()}
gap = checks["example AA 100/99/100/101 centre-distance gap"]
print(gap.verdict.value, "| alternative:", gap.comparison.alternative.assumption, "->", gap.comparison.alternative.value)

# %% [markdown]
# **z1 = ?00 and z4 = ?01 in the II example.** The OCR lost a digit of each. Coaxiality
# r1 - r2 = r4 - r3 with equal modules gives z4 = z1 + 1, and among three-digit z1 only 200
# gives the printed i_H1 = 198 (rounded); both agree with every legible digit:

# %%
for label in ("example II z1", "example II z4"):
    c = checks[label]
    print(f"{label}: derived {c.derived}, printed {c.published}: {c.verdict.value} ({c.comparison.detail})")

# %% [markdown]
# ## 6. Trajectories, speed and acceleration of planet particles
#
# A particle is named by its link and its position at t = 0; eq. (4) gives its path. Here
# one carrier turn of each scheme with gear 4 fixed (the figure `symkin reproduce` writes).
# On the pitch circle of rim 2 the single-row AI traces a hypocycloid, cusps on the ring.

# %%
paper.trajectories_figure()

# %% [markdown]
# Eqs. (5) and (6) give velocity and acceleration. For the two-row AI of the figure, driven
# by gear 1 at 10 rad/s, a particle on the pitch circle of rim 2 touches the sun once per
# relative turn: its speed peaks at the sun's pitch-line speed, 10 x 10 = 100.

# %%
from symkin.viz import figures

mech = schemes.two_row("AI", teeth=paper.FIGURE_TEETH["AI"], module=1)
motion = mech.motion({"1": 10, "4": 0})
t_end = motion.turn_time(1)
fig = figures.kinematics_figure(motion, [("23", (15, 0)), ("23", (7.5, 0))], t_end, relative_to="pole",
                                 labels=["rim 2 pitch circle", "half its radius"])
data = motion.particle("23", (15, 0), relative_to="pole").sample(t_end, samples=2001)
print(f"max speed {data['speed'].max():.4f}, min speed {data['speed'].min():.4f}")
fig

# %% [markdown]
# ## 7. Efficiency statements and the drill head
#
# The paper's remarks on efficiency are checked on laws `symkin.statics` derives (the
# relative-power method, mesh losses only), in the basic-train efficiency eta_0: the AI
# band 0.98 ... 0.96, the II siren "below 1 %" (gear 1 driving the fast carrier), and "II
# trains are more efficient than AA". The paper's drill head on a manipulator follows a tooth
# of a planet-borne bit while the head feeds and nods, by the same superposition in space.

# %%
for label in ("AI ratios and efficiency", "II efficiency", "II against AA efficiency", "drill head",
              "drill head in space"):
    c = checks[label]
    print(f"{label}: {c.verdict.value}\n  {c.comparison.detail}\n")

# %%
paper.drill_head_figure()

# %% [markdown]
# ## 8. The verification table
#
# `symkin reproduce alyushin2009` runs every check below and writes the report folder
# (LaTeX, PDF, figures, JSON). The same from Python:

# %%
from symkin.papers.reproduce import PaperResult, format_table

print(format_table([PaperResult(paper.KEY, paper.CITATION, list(checks.values()), items=list(paper.PRINTED_ITEMS))]))
