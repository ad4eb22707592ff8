# %% [markdown]
# # Dynamics of a planetary set: equations of motion, a run-up, torsional modes
#
# symkin knows every link's speed as an exact linear law of the independent speeds, so the
# kinetic energy of a train, its generalised mass matrix and its equations of motion follow
# in closed form (`symkin.dynamics`, `docs/dynamics.md`). Here a simple planetary set
# (sun 24, three planets 24, ring 72, module 2 mm) with its mass properties in the train file,
# in SI units; the module is in millimetres and symkin converts lengths to metres.

# %%
%matplotlib inline
import numpy as np
import sympy as sp
from IPython.display import Math, display

from symkin.dynamics import equations_of_motion, natural_modes
from symkin.trains import read_train

FILE = """
name = "planetary set"
module = 2
meshes = [{ gears = ["s", "p"], stiffness = 5e8 }, { gears = ["p", "r"], stiffness = 6e8 }]
[links.S]
gears = { s = 24 }
inertia = 0.01
[links.C]
inertia = 0.05
[links.P]
carrier = "C"
count = 3
gears = { p = 24 }
inertia = 0.002
mass = 0.5
[links.R]
gears = { r = { teeth = 72, internal = true } }
inertia = "J_R"
[states.low]
input = "S"
output = "C"
brakes = ["R"]
"""
train = read_train(FILE)

# %% [markdown]
# ## 1. Equations of motion with both suns free
#
# Without a brake the set has two degrees of freedom; take the sun's and the ring's turns as
# coordinates. The ring's inertia is left as a symbol (`"J_R"` in the file), the torques too.

# %%
T_S, T_R = sp.symbols("T_S T_R", real=True)
eom = equations_of_motion(train, coordinates=["S", "R"], torques={"S": T_S, "R": T_R})
display(Math(r"\mathbf{M} = " + sp.latex(eom.mass_matrix)))
display(Math(r"\mathbf{f} = " + sp.latex(eom.forcing)))

# %% [markdown]
# A second route for one entry, by hand: with the ring held the carrier turns at a quarter
# of the sun's speed and the planets at minus a half, and the planet centres (48 mm from the
# axis) move with the carrier, so the inertia the sun sees is
# `J_S + J_C/16 + 3 (J_P/4 + m_P r_c^2/16)`.

# %%
low = equations_of_motion(train, state="low")
by_hand = sp.Rational(1, 100) + sp.Rational(5, 100) / 16 + 3 * (sp.Rational(2, 1000) / 4 + sp.Rational(1, 2) * sp.Rational(48, 1000) ** 2 / 16)
print(low.mass_matrix[0, 0], low.mass_matrix[0, 0] == by_hand)

# %% [markdown]
# ## 2. A run-up
#
# The ring held, a motor on the sun whose torque falls linearly with its speed (20 N m at
# rest, none at 300 rad/s) and a load on the carrier proportional to the carrier's speed
# (0.2 N m s, on the carrier: a quarter of the sun's speed). The equations are integrated by
# SciPy from rest; the right-hand side is compiled by `symkin.compile`.

# %%
from symkin import symbols as S

w = S.omega("S")
runup = equations_of_motion(train, state="low", torques={"S": 20 * (1 - w / 300), "C": -sp.Rational(2, 10) * w / 4})
print("q'' =", runup.accelerations[0])
run = runup.simulate((0, 1.5), t_eval=np.linspace(0, 1.5, 301))
print(f"sun speed after 1.5 s: {run.speeds['S'][-1]:.2f} rad/s")

# the steady speed, by hand: 20 (1 - w/300) = 0.2 (w/4)/4 on the sun's side
steady = float(sp.solve(sp.Eq(20 * (1 - w / 300), sp.Rational(2, 10) * w / 16), w)[0])
print(f"steady speed: {steady:.2f} rad/s")

# %%
from matplotlib.figure import Figure

fig = Figure(figsize=(8, 3.5))
ax = fig.add_subplot(1, 1, 1)
ax.plot(run.t, run.speeds["S"], label="sun")
ax.plot(run.t, run.speeds["S"] / 4, label="carrier")
ax.axhline(steady, ls=":", color="grey", label="steady sun speed")
ax.set_xlabel("t [s]")
ax.set_ylabel("omega [rad/s]")
ax.legend(loc="lower right")
fig

# %% [markdown]
# ## 3. Torsional modes
#
# The purely rotational lumped-parameter model: each planet is its own coordinate, each mesh
# a spring along its line of action between the base circles (pressure angle 20 degrees), the
# ring held. The rigid-body mode (the set turning as a train, 0 Hz) and, with three equally
# spaced planets, a planet mode of multiplicity two (Lin and Parker, 1999).

# %%
modes = natural_modes(train, state="low")
print("coordinates:", ", ".join(modes.model.names))
print("frequencies [Hz]:", ", ".join(f"{f:.2f}" for f in modes.frequencies_hz))
f = np.array(modes.frequencies_hz)
repeated = [k for k in range(len(f)) if any(np.isclose(f[k], f[j], rtol=1e-9) for j in range(len(f)) if j != k)]
print("a repeated pair (planet modes):", [f"{f[k]:.2f}" for k in repeated])
for k in range(len(f)):
    if k not in repeated:  # a repeated pair's vectors are any basis of their plane: not printed
        print(f"{f[k]:8.2f} Hz:", "  ".join(f"{x + 0.0:+.3f}" for x in np.round(modes.shapes[k], 3)))

# %%
fig = Figure(figsize=(10, 3))
for k in range(1, len(modes.frequencies_hz)):
    ax = fig.add_subplot(1, len(modes.frequencies_hz) - 1, k)
    ax.bar(modes.model.names, modes.shapes[k])
    ax.set_title(f"{modes.frequencies_hz[k]:.0f} Hz")
    ax.set_ylim(-1.1, 1.1)
fig

# %% [markdown]
# The same from the command line:
#
# ```
# symkin dynamics --train FILE --state low --torque S=20 --json
# symkin modes --train FILE --state low
# ```
