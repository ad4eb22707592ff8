# %% [markdown]
# # Tutorial: a two-stage AA reducer, from description to LaTeX, numbers and pictures
#
# None of the papers treats this mechanism, which is the point: symkin derives laws for any
# train you describe, not only for the ready-made schemes. We build a **two-stage AA
# reducer**: two two-row AA stages (external meshes only, stepped planets) in series.
#
# * Stage a: the input carrier `H1` carries planet `P1` (rims 2a, 3a); rim 2a meshes with
#   gear 1a, rim 3a with gear 4a, which is fixed to the housing.
# * Gear 1a is on link `M`, which is also the carrier of stage b: planet `P2` (rims 2b, 3b)
#   meshes with gear 1b on the output link `S` and with the fixed gear 4b.
#
# Driving the carrier of an AA stage and taking the output from gear 1 gives a large
# reduction from a few teeth of difference. We will derive the reducer's law, print it in
# LaTeX, check it by a second route, compile it into a fast function, use it to choose
# tooth numbers, and look at the motion.

# %%
%matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Math, display

import symkin
from symkin import Gear, Link, Mechanism, schemes, symbols as S

# %% [markdown]
# ## 1. Describe the mechanism
#
# A `Gear` has a pitch radius (here from its tooth number and a module), a `Link` holds
# gears, a planet names its carrier, and meshes pair gears by name. Tooth numbers may be
# numbers or symbols (`True` below means the symbol $z_{1a}$ and so on).

# %%
def reducer(stage_a, stage_b, module=None):
    """Two-stage AA reducer; each stage's teeth are (z1, z2, z3, z4), or True for symbols."""
    gears = {}
    for stage, teeth in (("a", stage_a), ("b", stage_b)):
        teeth = [S.teeth(f"{n}{stage}") for n in "1234"] if teeth is True else teeth
        for n, z in zip("1234", teeth):
            gears[n + stage] = Gear.from_teeth(n + stage, z, module=module)
    return Mechanism(
        links=[
            Link.central("H1"),                                         # input: carrier of stage a
            Link.planet("P1", gears["2a"], gears["3a"], carrier="H1"),
            Link.central("M", gears["1a"]),                             # gear 1a = carrier of stage b
            Link.planet("P2", gears["2b"], gears["3b"], carrier="M", position_angle=sp.pi),  # drawn opposite P1
            Link.central("S", gears["1b"]),                             # output
            Link.frame(gears["4a"], gears["4b"]),                       # both gears 4 fixed
        ],
        meshes=[("1a", "2a"), ("3a", "4a"), ("1b", "2b"), ("3b", "4b")],
        name="two-stage AA reducer",
    )


symbolic = reducer(True, True)
print("degrees of freedom:", symbolic.dof)
for cond in symbolic.coaxiality:
    display(Math(symkin.latex(cond)))

# %% [markdown]
# One degree of freedom: the input carrier's speed fixes everything. The coaxiality
# conditions, derived from where each mesh puts each planet axis, say
# $z_1 + z_2 = z_3 + z_4$ in each stage (equal modules).
#
# ## 2. Derive the law and print it for a paper
#
# `ratio("H1", "S")` is $\omega_{H1}/\omega_S$ with the housing fixed:

# %%
law = symbolic.ratio("H1", "S")
display(Math(symkin.latex(law)))

# %% [markdown]
# For the paper, the author's own notation ($u_\Sigma$ for the ratio), display-size fractions
# and an equation number. (A law whose sums are too wide for a line is broken at `+` and `-`
# with `width=`; the 2009 paper's notebook shows one.)

# %%
notation = {law.lhs: "u_{\\Sigma}"}
print(symkin.latex(law, symbol_names=notation, number="1", frac="dfrac"))

# %% [markdown]
# ## 3. Check it by a second route
#
# The reducer is two AA stages in series, so its ratio must be the product of two
# single-stage ratios $i_{H1}^{(4)}$ of the ready-made AA scheme, with the stage's tooth
# symbols renamed. Two independent derivations, one comparison:

# %%
stage = schemes.two_row("AA", teeth=True).ratio("H", "1", fixed="4").rhs
z = {n: S.teeth(str(n)) for n in range(1, 5)}
product = stage.subs({z[n]: S.teeth(f"{n}a") for n in z}, simultaneous=True) * stage.subs(
    {z[n]: S.teeth(f"{n}b") for n in z}, simultaneous=True
)
display(Math(r"i_{H1}^{(4)} = " + symkin.latex(stage)))
print("reducer law - product of stage laws =", sp.cancel(law.rhs - product))

# %% [markdown]
# ## 4. Numbers, exactly
#
# With z = (54, 45, 44, 55) in both stages each stage turns the output 24 times slower,
# backwards; two stages give 576, forwards. The speeds of every link for an input of
# 1500 rpm (in rad/s, exact):

# %%
numeric = reducer((54, 45, 44, 55), (54, 45, 44, 55), module=1)
print("i =", numeric.ratio("H1", "S").rhs)
omega_in = sp.Rational(1500) * 2 * sp.pi / 60
for link, value in numeric.speeds({"H1": omega_in}).items():
    print(f"omega_{link:3} = {str(value):>12} = {float(value):10.4f} rad/s")

# %% [markdown]
# ## 5. A fast numeric function, and a design question
#
# `symkin.compile` turns the law into a numeric function (by default a compiled numba loop where
# numba is installed, else NumPy; for the one call here, `backend="numpy"`: nothing to compile);
# `f.args` gives the argument order. Which coaxial tooth sets (z1 + z2 = z3 + z4, 30 to 70 teeth, z3 != z2) give a
# stage ratio between 20 and 30 in magnitude? One call evaluates them all:

# %%
f = symkin.compile(stage, backend="numpy")
print("arguments:", f.args)
z1, z2, z3 = np.meshgrid(np.arange(30, 71), np.arange(30, 71), np.arange(30, 71), indexing="ij")
z4 = z1 + z2 - z3
ok = (z4 >= 30) & (z4 <= 70) & (z3 != z2) & (z1 * z3 != z2 * z4)
sets = np.stack([z1[ok], z2[ok], z3[ok], z4[ok]])
ratios = f(*sets)
chosen = (np.abs(ratios) >= 20) & (np.abs(ratios) <= 30)
print(f"{sets.shape[1]} coaxial sets, {chosen.sum()} with 20 <= |i| <= 30; the first five:")
for zs, i in list(zip(sets[:, chosen].T, ratios[chosen]))[:5]:
    exact = stage.subs(dict(zip((z[1], z[2], z[3], z[4]), map(int, zs))))
    print(f"  z = {tuple(int(v) for v in zs)}: i = {i:9.4f} (exact {exact})")

# %% [markdown]
# ## 6. Look at the motion
#
# A particle is named by its link and its position at t = 0 (here relative to its link's
# axis). The outer point of rim 2b and the axis of the second planet, seen from the housing,
# while the input makes 24 turns (one turn of the intermediate link M):

# %%
from symkin.viz import figures

motion = numeric.motion({"H1": 1})
t_end = motion.turn_time(1, link="M")
fig = figures.trajectory_figure(numeric, {"H1": 1}, [("P2", (-22.5, 0)), ("P2", (0, 0))], t_end, relative_to="pole",
                                 labels=["rim 2b, outer point", "planet P2 axis"], title="two-stage AA reducer: one turn of M")
fig

# %% [markdown]
# Its speed and acceleration against time (eqs. 5 and 6 of the 2009 paper, link by link):

# %%
figures.kinematics_figure(motion, [("P2", (-22.5, 0)), ("P2", (0, 0))], t_end, relative_to="pole",
                           labels=["rim 2b, outer point", "planet P2 axis"])

# %% [markdown]
# ## 7. Animate it
#
# `symkin.viz.animation` samples every link's axis and orientation from the derived laws and
# draws the frames; `animate` writes a GIF (or an MP4 with ffmpeg), complete or not at all.
# Here the first stage, during one turn of the input carrier, and three of its frames:

# %%
from matplotlib.figure import Figure

from symkin.viz.animation import Frames, animate, draw_frame

frames = Frames.build(motion, [("P1", (22.5, 0)), ("P2", (-22.5, 0))], t_end=2 * np.pi, frames=48,
                    labels=["rim 2a, outer point", "rim 2b, outer point"], title="two-stage AA reducer")
path = animate(frames, "reducer.gif", fps=16, dpi=60)
print(path, path.stat().st_size > 10_000)
fig = Figure(figsize=(12, 4))
for k, n in enumerate((0, 16, 32)):
    draw_frame(fig.add_subplot(1, 3, k + 1), frames, n)
fig

# %% [markdown]
# The same from the command line, for the ready-made schemes:
#
# ```
# symkin animate AA --teeth 54,45,44,55 --omega 1=1 --omega 4=0 --out aa.gif
# symkin trajectory AI1 --teeth 20,30,80 --omega 4=0 --omega H=1 --out hypocycloid.png
# ```
