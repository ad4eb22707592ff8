# %% [markdown]
# # A Ravigneaux gear set from a train file: shift table, laws, motion
#
# A train file describes a train the way a stick diagram does: links, the gears each holds,
# the carrier of each planet, the meshes, and the gear states (brakes hold links, clutches
# join them). symkin derives the rest. Here the Ravigneaux set of a four-speed automatic
# transmission: a small sun `S1` drives short pinions `P1`, which mesh long pinions `P2`,
# which mesh the large sun `S2` and the ring `R`; both pinions ride on one carrier `C`.
# The file ships with symkin (`symkin trains` lists the ready-made ones); any file of yours
# loads the same way. The format: `docs/trains.md`.

# %%
%matplotlib inline
import importlib.resources

import sympy as sp
from IPython.display import Math, display

import symkin
from symkin import symbols as S
from symkin.trains import load_train, read_train

print((importlib.resources.files("symkin.trains") / "library" / "ravigneaux.toml").read_text())

# %% [markdown]
# ## 1. Load it
#
# A `Train` is a `Mechanism`: everything that takes a mechanism takes it. The long pinion's
# place on the carrier is not in the file: it follows from its mesh with the short pinion
# (the arms 24 and 27 and the centre distance 18 form a triangle).

# %%
train = load_train("ravigneaux")
print(train.dof, "degrees of freedom; planets of each kind:", train.link("P1").count)
print("arms:", train.arm("P1"), train.arm("P2"))
angle = train.position_angle("P2")
print("P2 on the carrier at", angle, "=", sp.N(angle, 6), "rad from P1")
print("check, law of cosines:", sp.simplify(24**2 + 27**2 - 2 * 24 * 27 * sp.cos(angle)) == 18**2)

# %% [markdown]
# ## 2. The shift table
#
# In each state the brakes hold their links, the clutches join theirs, and the input turns;
# every other link is then determined exactly once (symkin refuses a state that leaves a link
# free or locks the train). The ratio is omega_input / omega_output, exact.

# %%
table = train.shift_table()
print(table.text())

# %% [markdown]
# A second route for one state, by hand: with the carrier held, the small sun drives the
# ring through two external meshes and an internal one, so the ring turns the same way at
# `z_s1 / z_r` of the sun's speed: the first gear is `72/30 = 12/5`.

# %%
print(table[0].ratio.rhs == sp.Rational(72, 30))

# %% [markdown]
# ## 3. Laws in closed form
#
# With the tooth numbers as symbols the laws hold for every Ravigneaux set of this layout.
# Give each gear a symbol instead of a number (`teeth = "z_s1"` in a file); here the
# published file is rewritten on the fly.

# %%
text = (importlib.resources.files("symkin.trains") / "library" / "ravigneaux.toml").read_text()
for gear, teeth in (("s1 = 30", 's1 = "z_s1"'), ("s2 = 36", 's2 = "z_s2"'), ("p1 = 18", 'p1 = "z_p1"'),
                    ("p2 = 18", 'p2 = "z_p2"'), ("teeth = 72", 'teeth = "z_r"')):
    text = text.replace(gear, teeth)
general = read_train(text, "ravigneaux, symbolic teeth")
for shift in general.shift_table():
    display(Math(symkin.latex(shift.ratio)))

# %% [markdown]
# Every link's speed in the second gear (the large sun held), per unit speed of the small sun:

# %%
speeds = general.shift("second").speeds
display(Math(symkin.latex([speeds.law(n) for n in ("C", "P1", "P2", "R")])))

# %% [markdown]
# ## 4. Motion
#
# A point on a long pinion's pitch circle, in the second gear with the small sun at 1 rad/s:
# its position, velocity and acceleration follow from eqs. (4)-(6) of Alyushin &
# Verzhanskiy, link by link. The animation draws every planet (three of each kind).

# %%
motion = train.motion({"S1": 1, "S2": 0})
point = motion.particle("P2", (9, 0), relative_to="pole")
v0 = [sp.radsimp(sp.simplify(v.subs(S.t, 0))) for v in point.velocity]
print("velocity at t = 0:", v0, "=", [round(float(v), 6) for v in v0])

# %%
from matplotlib.figure import Figure

from symkin.viz.animation import Frames, animate, draw_frame

frames = Frames.build(motion, [("P2", (9, 0))], t_end=6.0, frames=60, labels=["long pinion, pitch circle"],
                      title="Ravigneaux, second gear")
path = animate(frames, "ravigneaux.gif", fps=15, dpi=60)
print(path, path.stat().st_size > 10_000)
fig = Figure(figsize=(12, 4))
for k, n in enumerate((0, 20, 40)):
    draw_frame(fig.add_subplot(1, 3, k + 1), frames, n)
fig

# %% [markdown]
# The same from the command line:
#
# ```
# symkin states --train ravigneaux
# symkin ratio --train ravigneaux --driver S1 --driven R --fixed S2
# symkin animate --train ravigneaux --omega S1=1 --omega S2=0 --out ravigneaux.gif
# ```

# %% [markdown]
# ## 5. Beyond one plane and one carrier level
#
# **Nested carriers.** The ready-made `nested` file is a double-planetary polisher: an arm
# `C` carries heads `P` that roll on a fixed sun; on each head a gear `G` turns about the
# head's own axis (`arm = 0`), driven by a second fixed sun, and drives three tools `Q`
# carried by the head. A tool's point superposes three rotations.

# %%
nested = load_train("nested")
print(nested.shift_table().text())
tool = nested.motion({"C": 1}).particle("Q", (4, 0), relative_to="pole")
display(Math(r"x_{tool}(t) = " + symkin.latex(tool.position[0])))

from symkin.viz.figures import trajectory_figure

trajectory_figure(nested, {"C": 1}, [("Q", (4, 0)), ("Q", (0, 0))], 2 * sp.pi, relative_to="pole",
                  labels=["tool point, 4 from the tool's axis", "tool axis"])

# %% [markdown]
# **Bevel gears.** In the `bevel-differential` file the case `C` carries pinions `P` on a
# radial axis (`axis = "radial"`); the side gears `L` and `R` meet them above and below. The
# contact condition is the equality of velocities at the contact point, in space; the case
# turns at the mean of the side gears:

# %%
diff = load_train("bevel-differential")
speeds = diff.speeds({"L": S.omega("L"), "R": S.omega("R")})
display(Math(symkin.latex([speeds.law("C"), speeds.law("P")])))

# %% [markdown]
# **A base moving in space.** The 2009 paper's drill head: the manipulator moves the main
# axis; the planet's teeth superpose that motion on their own. Here the head advances along
# its axis and tilts slowly; a point on the planet's pitch circle moves in 3-D.

# %%
from symkin import schemes
from symkin.particles import SpaceFrame
from symkin.viz.figures import space_figure

head = schemes.single_row_AI(teeth=(20, 30, 80), module=1)
motion = head.motion({"4": 0, "H": 1}, frame=SpaceFrame.euler(z=5 * S.t, pitch=S.t / 10))
tooth = motion.particle("2", (15, 0, 0), relative_to="pole")
print([sp.count_ops(c) for c in tooth.acceleration], "operations in the acceleration laws")
space_figure(motion, [("2", (15, 0, 0))], 4 * sp.pi, labels=["a point on the planet's pitch circle"])
