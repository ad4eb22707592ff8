"""Draw the figure gallery of the docs with symkin itself.

Every figure type symkin draws has an entry in :data:`GALLERY`: the function that draws it,
a caption, and a small script that calls it.  ``docs/conf.py`` runs :func:`draw` when the
docs are built, so the gallery shows what the installed symkin draws today, never a stale
image; ``python docs/gallery.py [FOLDER]`` draws them by hand (default ``docs/gallery``).
tests/project/test_docs.py checks that every public figure function of :mod:`symkin.viz` has an
entry here and a place on the gallery page.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent


@dataclass(frozen=True)
class Entry:
    """One gallery image: the file name (without suffix), the symkin functions it shows, and how
    to draw it (its caption is on the gallery page, docs/gallery.md)."""

    name: str
    functions: tuple[str, ...]
    make: Callable[[Path], Path]


def _save(fig: Any, path: Path) -> Path:
    from symkin.viz.figures import save

    return save(fig, path, formats=("png",))[0]


def _trajectory(path: Path) -> Path:
    from symkin import schemes
    from symkin.viz.figures import default_particles, trajectory_figure

    mech = schemes.two_row("AI", teeth=(20, 30, 20, 70), module=1)
    fig = trajectory_figure(mech, {"4": 0, "H": 1}, default_particles(mech), 6.2832)
    return _save(fig, path)


def _kinematics(path: Path) -> Path:
    from symkin import schemes
    from symkin.viz.figures import default_particles, kinematics_figure

    mech = schemes.two_row("AI", teeth=(20, 30, 20, 70), module=1)
    fig = kinematics_figure(mech.motion({"4": 0, "H": 1}), default_particles(mech), 6.2832)
    return _save(fig, path)


def _space(path: Path) -> Path:
    from symkin import schemes
    from symkin import symbols as S
    from symkin.particles import SpaceFrame
    from symkin.viz.figures import space_figure

    head = schemes.single_row_AI(teeth=(20, 30, 80), module=1)
    motion = head.motion({"4": 0, "H": 1}, frame=SpaceFrame.euler(z=5 * S.t, pitch=S.t / 10))
    fig = space_figure(motion, [("2", (15, 0))], 6.2832)
    return _save(fig, path)


#: Frames per turn of the carrier in the animation: the carrier of the AA reducer turns 24 times
#: for one turn of gear 1, so frames spread over gear 1's turn would alias (the carrier seemed
#: to stand still); one carrier turn is sampled, finely enough for the planet's 4 lobes.
FRAMES_PER_CARRIER_TURN = 48


def _frames(path: Path, frames: int) -> Any:
    from symkin import schemes
    from symkin.viz.animation import Frames
    from symkin.viz.figures import default_particles

    mech = schemes.two_row("AA", teeth=(54, 45, 44, 55), module=1)
    motion = mech.motion({"1": 1, "4": 0})
    return Frames.build(motion, default_particles(mech), t_end=motion.turn_time(1), frames=frames, length="mm")


def _frame(path: Path) -> Path:
    from symkin.viz.animation import frame_figure

    frames = _frames(path, FRAMES_PER_CARRIER_TURN + 1)
    return _save(frame_figure(frames, 3 * FRAMES_PER_CARRIER_TURN // 4), path)


def _animation(path: Path) -> Path:
    from symkin.viz.animation import animate

    return animate(_frames(path, FRAMES_PER_CARRIER_TURN), path.with_suffix(".gif"), fps=12, dpi=60)


def _split(path: Path) -> Path:
    from symkin.mechanisms.multistage import StageErrorModel, best_designs, enumerate_stages, optimize_split
    from symkin.viz.split import split_figure

    model = StageErrorModel.linear(0.854, 0.858)
    best = optimize_split(6000, 4, lower=2.25, upper=11, model=model)
    designs = best_designs(6000, enumerate_stages(180, 3, zmin=18, zmax=180), 4, model=model, tolerance=0.05, top=10)
    return _save(split_figure(best, designs), path)


def _stage_model(path: Path) -> Path:
    from symkin.mechanisms.multistage import StageErrorModel, enumerate_stages
    from symkin.viz.split import stage_model_figure

    models = {"0.854 + 0.858 u": StageErrorModel.linear(0.854, 0.858)}
    return _save(stage_model_figure(enumerate_stages(180, 3, zmin=18, zmax=180), models, module=1), path)


def _geometry(path: Path) -> Path:
    from symkin.geometry import train_geometry
    from symkin.trains import load_train
    from symkin.viz.teeth import outline_figure

    geo = train_geometry(load_train("simple"))
    return _save(outline_figure(geo, title="simple planetary, module 1", zoom=(36.0, 0.0, 3.0)), path)


GALLERY: tuple[Entry, ...] = (
    Entry("trajectory", ("symkin.viz.figures.trajectory_figure", "symkin.viz.figures.draw_pitch_circles",
                         "symkin.viz.figures.draw_trajectories"), _trajectory),
    Entry("kinematics", ("symkin.viz.figures.kinematics_figure",), _kinematics),
    Entry("space", ("symkin.viz.figures.space_figure",), _space),
    Entry("frame", ("symkin.viz.animation.frame_figure", "symkin.viz.animation.draw_frame"), _frame),
    Entry("animation", ("symkin.viz.animation.animate",), _animation),
    Entry("split", ("symkin.viz.split.split_figure",), _split),
    Entry("stage_model", ("symkin.viz.split.stage_model_figure",), _stage_model),
    Entry("geometry", ("symkin.viz.teeth.outline_figure",), _geometry),
)


def draw(folder: Path = HERE / "gallery", *, quiet: bool = False) -> list[Path]:
    """Draw every gallery image into ``folder``; returns the files, in the order of :data:`GALLERY`.

    An image newer than every source file of symkin and than this script is kept (a rebuild of
    the docs does not redraw what cannot have changed).
    """
    import matplotlib

    matplotlib.use("Agg")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    newest = max(f.stat().st_mtime for f in [*(HERE.parent / "symkin").rglob("*.py"), Path(__file__)])
    paths = []
    for entry in GALLERY:
        done = [f for f in folder.glob(entry.name + ".*") if f.suffix in (".png", ".gif")]
        if done and done[0].stat().st_mtime > newest:  # drawn by this symkin already
            paths.append(done[0])
            continue
        start = time.perf_counter()
        paths.append(entry.make(folder / entry.name))
        if not quiet:
            print(f"gallery: {paths[-1].name} ({time.perf_counter() - start:.1f} s)", file=sys.stderr)
    return paths


def draw_trains(folder: Path = HERE / "trains") -> list[Path]:
    """Draw the kinematic scheme and the lever diagram of every ready-made train into ``folder``
    (``NAME-scheme.svg``, ``NAME-lever.svg``: the pictures of docs/trains.md, tracked in git so
    that they show where the page is read; ``python docs/gallery.py --trains`` redraws them)."""
    import matplotlib

    matplotlib.use("Agg")
    from symkin.trains import load_train, ready_made
    from symkin.viz.diagram import diagram, text_as_text

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for name in ready_made():
        train = load_train(name)
        for kind in ("scheme", "lever"):
            fig = diagram(train, lever=kind == "lever")
            path = folder / f"{name}-{kind}.svg"
            with text_as_text():
                fig.savefig(path, format="svg", metadata={"Date": None})
            paths.append(path)
    return paths


if __name__ == "__main__":
    if sys.argv[1:2] == ["--trains"]:
        draw_trains(Path(sys.argv[2]) if len(sys.argv) > 2 else HERE / "trains")
    else:
        draw(Path(sys.argv[1]) if len(sys.argv) > 1 else HERE / "gallery")
