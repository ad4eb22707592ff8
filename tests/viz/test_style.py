"""Every figure symkin draws is fit to print: each axis labelled with its unit, no text box
over another, no legend over a drawn line, text legible at a page's width
(:func:`symkin.viz.style.layout_problems`, which measures the boxes with matplotlib's
renderer); teeth that mesh; vector output by suffix; the animation as an HTML page."""

import importlib
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from symkin import Gear, InputError, Link, Mechanism, schemes
from symkin.cli import main
from symkin.viz import figures, style
from symkin.viz.animation import Frames, animate, frame_figure
from symkin.viz.split import split_figure, stage_model_figure
from symkin.viz.teeth import involute_outline, mesh_phases


def _captured(monkeypatch):
    """Figures passed to viz.figures.save (by the derivations and the CLI), still saved."""
    caught = []
    real = figures.save

    def spy(fig, path, formats=None):
        caught.append((Path(path).name, fig))
        return real(fig, path, formats)

    monkeypatch.setattr(figures, "save", spy)
    return caught


def library_figures():
    m = schemes.single_row_AI(teeth=(20, 30, 80), module=1)
    motion = m.motion({"4": 0, "H": 1})
    yield "trajectory", figures.trajectory_figure(m, {"4": 0, "H": 1}, [("2", (15, 0)), ("2", (7, 0))], 6.3, length="mm")
    yield "kinematics", figures.kinematics_figure(motion, [("2", (15, 0)), ("2", (7, 0))], 6.3)
    from symkin import symbols as S
    from symkin.particles import SpaceFrame

    space = m.motion({"4": 0, "H": 1}, frame=SpaceFrame(z=S.t))
    yield "space", figures.space_figure(space, [("2", (15, 0))], 6.3)
    aa = schemes.two_row("AA", teeth=(54, 45, 44, 55), module=1)
    frames = Frames.build(aa.motion({"4": 0, "H": 1}), [("23", (45, 0)), ("23", (20, 0))], t_end=0.3, frames=3)
    yield "animation frame", frame_figure(frames, 2)
    from symkin.mechanisms.multistage.lostmotion import StageErrorModel
    from symkin.mechanisms.multistage.split import optimize_split
    from symkin.mechanisms.multistage.stages import enumerate_stages

    best = optimize_split(100, 2, lower=2, upper=20, model=StageErrorModel.linear(1, 1))
    yield "split", split_figure(best, points=9)
    yield "stage models", stage_model_figure(enumerate_stages(100, 4, zmin=15), {"a + b u": StageErrorModel.linear(1, 1)}, module=1)


@pytest.mark.parametrize("name, fig", list(library_figures()), ids=lambda v: v if isinstance(v, str) else "")
def test_library_figures_have_units_and_no_overlapping_text(name, fig):
    assert style.layout_problems(fig) == []


@pytest.mark.parametrize("key", ["alyushin2009", "khai2014", "kladova2010", "luo2018"])
def test_paper_figures_have_units_and_no_overlapping_text(key, tmp_path, monkeypatch):
    caught = _captured(monkeypatch)
    written = importlib.import_module(f"symkin.derivations.{key}").figures(tmp_path)
    assert caught and all(p.exists() for p in written)
    problems = {name: style.layout_problems(fig) for name, fig in caught}
    assert problems == {name: [] for name, _ in caught}


@pytest.mark.parametrize("command", ["trajectory", "curves"])
def test_cli_figures_have_units_and_no_overlapping_text(command, tmp_path, monkeypatch):
    caught = _captured(monkeypatch)
    out = tmp_path / "f.svg"
    assert main([command, "AA", "--teeth", "54,45,44,55", "--omega", "4=0", "--omega", "H=1", "--out", str(out)]) == 0
    assert out.read_text().lstrip().startswith("<?xml") and "<svg" in out.read_text()[:2000]
    assert [style.layout_problems(fig) for _, fig in caught] == [[]]


def test_the_checker_finds_what_it_looks_for():
    """The checker is not vacuous: each fault it names is found in a figure made with it."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(9, 4))
    ax = fig.add_subplot()
    ax.plot(np.linspace(0, 1, 50), np.full(50, np.sqrt(20)), label="a line through the middle")
    ax.set_xlabel("x")
    ax.set_ylabel("speed [m/s]")
    ax.legend(loc="center")
    ax.text(0.1, 0.9, "here")
    ax.text(0.1, 0.9, "there")
    ax.set_yscale("log")
    ax.set_ylim(1, 20)
    problems = "\n".join(style.layout_problems(fig))
    for fault in ("more than 7.2 in", "x axis has no label", "legend covers", "'here' and 'there' overlap",
                  "logarithmic with 2 labelled ticks"):
        assert fault in problems
    assert "y axis has no label" not in problems


def test_the_palette_is_told_apart_in_grey_and_by_colour_blind_viewers():
    """Okabe-Ito: every pair of the first six colours differs (CIE76 distance > 10) under a
    deuteranopia simulation (Vienot 1999 on linear RGB), the lines differ in style too."""
    def linear(hex_):
        c = np.array([int(hex_[i : i + 2], 16) / 255 for i in (1, 3, 5)])
        return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)

    deut = np.array([[0.29275, 0.70725, 0], [0.29275, 0.70725, 0], [-0.02234, 0.02234, 1]])
    rgb2xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])

    def lab(c):
        x, y, z = rgb2xyz @ c / np.array([0.9505, 1.0, 1.089])
        f = lambda t: np.cbrt(t) if t > 0.008856 else 7.787 * t + 16 / 116  # noqa: E731
        return np.array([116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))])

    seen = [lab(deut @ linear(c)) for c in style.PALETTE[:6]]
    gaps = [np.linalg.norm(a - b) for i, a in enumerate(seen) for b in seen[i + 1 :]]
    assert min(gaps) > 10   # measured: 17.6 at the closest pair; 2.3 is a just noticeable difference
    assert len(set(map(str, style.LINESTYLES[:6]))) == 6


def test_involute_teeth_have_the_standard_proportions_and_thickness():
    r, z = 20.0, 40
    x, y = involute_outline(r, z)
    rho = np.hypot(x, y)
    m = 2 * r / z
    assert rho.max() == pytest.approx(r + m) and rho.min() == pytest.approx(r - 1.25 * m)
    # on the pitch circle a tooth is half a pitch thick: the outline crosses it 2 z times, equally spaced by half pitches
    ang = np.unwrap(np.arctan2(y, x))
    cross = [ang[i] + (ang[i + 1] - ang[i]) * (r - rho[i]) / (rho[i + 1] - rho[i])
             for i in range(len(rho) - 1) if (rho[i] - r) * (rho[i + 1] - r) < 0]
    assert len(cross) == 2 * z
    assert np.allclose(np.diff(cross), np.pi / z, atol=2e-3)
    with pytest.raises(InputError, match="at least 3 teeth"):
        involute_outline(1, 2)


def _material(x, y, px, py, internal):
    """Whether point (px, py) (relative to the gear axis) is in the gear's material."""
    from matplotlib.path import Path as MPath

    inside = MPath(np.column_stack([x, y])).contains_point((px, py))
    return not inside if internal else inside


@pytest.mark.parametrize("scheme, teeth", [("AI1", (20, 30, 80)), ("AA", (54, 45, 44, 55)), ("II", (40, 19, 20, 41))])
def test_meshing_teeth_interleave_and_stay_meshed(scheme, teeth):
    """At every mesh's pitch point no point is inside both gears, at t = 0 and after the
    derived motion has turned the links (an independent overlap test with matplotlib paths)."""
    mech = schemes.two_row(scheme, teeth=teeth, module=1) if scheme != "AI1" else schemes.single_row_AI(teeth=teeth, module=1)
    frames = Frames.build(mech.motion({"4": 0, "H": 1}), t_end=0.37, frames=4)
    names = [name for name, *_ in frames.links]
    where = {g: (names.index(link), r, internal) for link, _, gears, _ in frames.links for g, r, internal in gears
             if "#" not in link}
    for mesh in mech.meshes:
        for n in range(len(frames.t)):
            outlines = []
            for g in (mesh.a, mesh.b):
                i, r, internal = where[g]
                zt, phase = frames.teeth[g]
                outlines.append((frames.axis_xy[i, n], frames.angle[i, n], *involute_outline(r, zt, internal=internal, phase=phase), internal))
            (ca, phia, xa, ya, ia), (cb, phib, xb, yb, ib) = outlines
            # sample points around the pitch point of the mesh, in the plane
            d = cb - ca
            u = d / np.hypot(*d)
            ra = where[mesh.a][1]
            p = ca + (-u if ib else u) * ra
            grid = p + np.stack(np.meshgrid(np.linspace(-3, 3, 41), np.linspace(-3, 3, 41)), -1).reshape(-1, 2)
            both = 0
            for q in grid:
                qa = _rot(q - ca, -phia)
                qb = _rot(q - cb, -phib)
                both += _material(xa, ya, *qa, ia) and _material(xb, yb, *qb, ib)
            assert both == 0, (mesh, n)


def _rot(v, phi):
    c, s = np.cos(phi), np.sin(phi)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def test_mesh_phases_skip_gears_without_teeth():
    mech = Mechanism(links=[Link.frame(Gear("3", 2, internal=True)), Link.central("H"), Link.planet("1", Gear("1", 1))],
                     meshes=[("1", "3")])
    assert mesh_phases(mech) == {}


@pytest.mark.parametrize("suffix", ["pdf", "svg", "eps", "png"])
def test_save_writes_the_format_its_suffix_names(suffix, tmp_path):
    fig = figures.trajectory_figure(schemes.single_row_AI(teeth=(20, 30, 80), module=1), {"4": 0, "H": 1}, [("2", (15, 0))], 1.0)
    (path,) = figures.save(fig, tmp_path / f"t.{suffix}")
    head = path.read_bytes()[:16]
    assert {"pdf": b"%PDF", "svg": b"<?xml", "eps": b"%!PS-Adobe", "png": b"\x89PNG"}[suffix] in head
    with pytest.raises(InputError, match="one of png, pdf, svg, eps"):
        figures.save(fig, tmp_path / "t", formats=("jpg",))


def _frames(n=5):
    return Frames.build(schemes.single_row_AI(teeth=(20, 30, 80), module=1).motion({"4": 0, "H": 1}),
                        [("2", (15, 0))], t_end=1.0, frames=n)


def test_the_animation_page_is_self_contained_with_every_frame(tmp_path):
    out = animate(_frames(5), tmp_path / "a.html", dpi=30)
    page = out.read_text()
    assert page.startswith("<!DOCTYPE html>") and "</html>" in page
    assert len(re.findall(r"data:image/png;base64", page)) == 5     # every frame embedded, nothing fetched
    assert not re.search(r"""src=["']https?://""", page)
    assert [p.name for p in tmp_path.iterdir()] == ["a.html"]


def _browser():
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        if shutil.which(name):
            return shutil.which(name)
    return None


@pytest.mark.skipif(_browser() is None, reason="no headless Chromium or Chrome installed")
def test_the_animation_page_runs_in_a_headless_browser(tmp_path):
    out = animate(_frames(4), tmp_path / "a.html", dpi=30)
    dom = subprocess.run([_browser(), "--headless", "--no-sandbox", "--disable-gpu", "--virtual-time-budget=3000",
                          "--dump-dom", out.as_uri()], capture_output=True, text=True, timeout=120).stdout
    # the script ran: the player set its frame image (the page as written has none) and its slider
    assert not re.search(r'<img id="_anim_img\w+" src=', out.read_text())
    assert re.search(r'<img id="_anim_img\w+" src="data:image/png;base64', dom)
    assert re.search(r'type="range"[^>]+max="3"', dom)       # 4 frames: 0 ... 3


def test_the_cli_writes_an_html_animation(tmp_path):
    out = tmp_path / "a.html"
    assert main(["animate", "AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1", "--frames", "3",
                 "--dpi", "20", "--out", str(out)]) == 0
    assert out.read_text().count("data:image/png;base64") == 3
