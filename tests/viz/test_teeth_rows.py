"""Two-row trains drawn legibly: the second row (a stepped planet's second rim, the gears it
meshes) stands apart from the first it overlaps, and legends show the lines as drawn.

References: the rows of the AA and Simpson trains typed here from their descriptions; the
gallery animation's carrier step per frame against the aliasing bound (under a quarter turn,
so that the planet's turn is not mistaken for another).
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

from symkin import schemes
from symkin.trains import load_train
from symkin.viz.animation import Frames, frame_figure
from symkin.viz.figures import default_particles
from symkin.viz.teeth import rear_gears

AA = schemes.two_row("AA", teeth=(54, 45, 44, 55), module=1)


def test_the_rear_row_is_the_second_rim_and_what_it_meshes():
    assert rear_gears(AA) == {"3", "4"}
    assert rear_gears(load_train("simpson")) == {"s2", "p2", "r2"}
    assert rear_gears(schemes.single_row_AI(teeth=(20, 30, 80), module=1)) == frozenset()


def test_an_animation_frame_draws_the_rear_row_dashed_and_its_legend_as_its_paths():
    motion = AA.motion({"1": 1, "4": 0})
    frames = Frames.build(motion, default_particles(AA), t_end=motion.turn_time(1), frames=9, length="mm")
    fig = frame_figure(frames, 6)
    ax = fig.axes[0]
    dashed = [ln for ln in ax.get_lines() if ln.get_linestyle() not in ("-", "None")]
    assert len(dashed) >= 2  # the pitch circles of rim 3 and gear 4
    paths = [ln for ln in ax.get_lines() if not ln.get_label().startswith("_")]
    legend = fig.legends[0] if fig.legends else ax.get_legend()
    assert [h.get_linestyle() for h in legend.legend_handles] == [p.get_linestyle() for p in paths]
    assert ax.get_xlabel() == "x [mm]"


def test_the_gallery_animation_samples_the_carrier_without_aliasing():
    path = Path(__file__).resolve().parents[2] / "docs" / "gallery.py"
    spec = importlib.util.spec_from_file_location("docs_gallery_rows", path)
    gallery = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("docs_gallery_rows", gallery)  # its dataclass looks its module up
    spec.loader.exec_module(gallery)
    frames = gallery._frames(path, gallery.FRAMES_PER_CARRIER_TURN)
    carrier = [name for name, *_ in frames.links].index("H")
    steps = abs(frames.angle[carrier][1:] - frames.angle[carrier][:-1])
    assert steps.max() < math.pi / 8  # 16 frames or more per carrier turn
    total = abs(frames.angle[carrier][-1] - frames.angle[carrier][0])
    assert math.isclose(total, 2 * math.pi, rel_tol=0.05)  # one carrier turn, as the caption says
