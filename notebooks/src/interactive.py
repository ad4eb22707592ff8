# %% [markdown]
# # Interactive: change the teeth and the speeds, watch the mechanism move
#
# A single-row AI planetary gear (sun 1, planets 2 on the carrier H, ring 4). The sliders
# set the tooth numbers and the speeds of the carrier and the ring; on every change symkin
# derives the speeds again, prints the laws, and animates the mechanism with its involute
# teeth (the animation is a self-contained HTML player, `Frames.html`).
#
# Run the notebook in Jupyter to move the sliders (they need a live kernel and
# `pip install ipywidgets`); the static output below the widget is the same function run
# once with the default values, so the page shows a result without a kernel.

# %%
import ipywidgets as widgets
import sympy as sp
from IPython.display import HTML, display

from symkin import schemes, symbols as S
from symkin.viz.animation import Frames


def show(z1=20, z2=30, omega_H=1.0, omega_4=0.0, frames=12):
    """Derive, print and animate the AI scheme with sun z1, planet z2 and the ring that fits them."""
    z4 = z1 + 2 * z2  # coaxiality of sun, planet and ring (the engine checks it too)
    mech = schemes.single_row_AI(teeth=(z1, z2, z4), module=1)
    display(mech.ratio("1", "H", fixed="4"))
    speeds = mech.speeds({"H": S.omega("H"), "4": S.omega("4")})
    display(speeds)
    values = {"H": sp.nsimplify(omega_H), "4": sp.nsimplify(omega_4)}
    motion = mech.motion(values)
    t_end = motion.turn_time(1, link="H") if omega_H else 2 * float(sp.pi)
    sampled = Frames.build(motion, [("2", (z2 / 2, 0))], t_end=t_end, frames=frames, length="mm",
                           labels=["a point on the planet's pitch circle"],
                           title=f"AI, z = ({z1}, {z2}, {z4}), m = 1 mm")
    display(HTML(sampled.html(fps=8, dpi=45, size=5.0)))


# %% [markdown]
# ## The sliders
#
# Each slider updates when it is released. The ring's teeth follow from the sun's and
# the planet's, so the three gears always mesh; the speeds are in rad/s.

# %%
ui = widgets.interactive(
    show,
    z1=widgets.IntSlider(value=20, min=12, max=60, description="sun z1", continuous_update=False),
    z2=widgets.IntSlider(value=30, min=12, max=60, description="planet z2", continuous_update=False),
    omega_H=widgets.FloatSlider(value=1.0, min=-3, max=3, step=0.5, description="omega_H", continuous_update=False),
    omega_4=widgets.FloatSlider(value=0.0, min=-3, max=3, step=0.5, description="omega_4", continuous_update=False),
    frames=widgets.fixed(12),
)
display(ui)

# %% [markdown]
# ## The same, without a kernel
#
# The default values, run once: the ratio with the ring fixed, every link's speed for
# given carrier and ring speeds, and the animation (press play).

# %%
show()
