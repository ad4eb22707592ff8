"""``symkin trajectory``, ``curves`` and ``animate`` in millimetres: the module's unit (ISO 54).

References: a module with a unit equals the same module in mm typed as a number (pint's
conversion against the factor 1000 mm = 1 m typed here); --length-unit m draws every length
at 1/1000 of its value in mm; the axes and the legend say their unit.
"""

from __future__ import annotations

import json

import pytest

from symkin.cli import main

_AI1 = ("AI1", "--teeth", "20,30,80", "--omega", "4=0", "--omega", "H=1")


def _json(capsys, *argv):
    code = main([*argv, "--json"])
    out = capsys.readouterr().out
    assert code == 0, out
    return json.loads(out)


@pytest.mark.parametrize("module", ["1.5 mm", "1.5mm", "0.0015 m", "3/2", "0.15 cm"])
def test_a_module_with_a_unit_is_the_same_module_in_mm(module, tmp_path, capsys):
    data = _json(capsys, "trajectory", *_AI1, "--module", module, "--out", str(tmp_path / "t.png"))
    # default particles: on the planet's pitch circle, module * 30 / 2 = 22.5 mm, and half of it
    assert [p["a"] for p in data["particles"]] == [22.5, 11.25]
    assert data["units"]["length"] == "mm" and data["units"]["speed"] == "mm/s"


def test_length_unit_m_draws_every_length_a_thousand_times_smaller(tmp_path, capsys):
    mm = _json(capsys, "trajectory", "--train", "simple", "--omega", "S=1", "--omega", "R=0", "--out",
               str(tmp_path / "a.png"))
    m = _json(capsys, "trajectory", "--train", "simple", "--omega", "S=1", "--omega", "R=0", "--length-unit", "m",
              "--out", str(tmp_path / "b.png"))
    assert [p["a"] for p in m["particles"]] == pytest.approx([p["a"] / 1000 for p in mm["particles"]])
    assert m["t_end"] == pytest.approx(mm["t_end"])  # times do not change with the unit of length
    assert m["units"]["length"] == "m"


def test_the_axes_and_the_legend_say_their_unit(tmp_path, monkeypatch):
    from symkin.viz import figures

    caught = []
    real = figures.save
    monkeypatch.setattr(figures, "save", lambda fig, path, *a, **k: (caught.append(fig), real(fig, path, *a, **k))[1])
    assert main(["trajectory", *_AI1, "--out", str(tmp_path / "t.png")]) == 0
    assert main(["curves", *_AI1, "--t-end", "1", "--out", str(tmp_path / "c.png")]) == 0
    trajectory, curves = caught
    ax = trajectory.axes[0]
    assert ax.get_xlabel() == "x [mm]" and ax.get_ylabel() == "y [mm]"
    legend = [t.get_text() for t in trajectory.legends[0].get_texts()]
    assert all(" mm from its axis" in t for t in legend)
    labels = [a.get_ylabel() for a in curves.axes]
    assert any("[mm/s]" in t for t in labels) and any("[mm/s$^2$]" in t for t in labels)


@pytest.mark.parametrize("argv, message", [
    (("--module", "2 s"), "--module: s is not a unit of mm"),
    (("--module", "-1"), "--module must be positive"),
    (("--length-unit", "km"), "--length-unit 'km': choose one of mm, m"),
])
def test_bad_lengths_are_one_line_and_exit_2(argv, message, tmp_path, capsys):
    code = main(["trajectory", *_AI1, *argv, "--out", str(tmp_path / "t.png")])
    err = capsys.readouterr().err
    assert code == 2 and message in err and err.count("\n") == 1
    assert not (tmp_path / "t.png").exists()
