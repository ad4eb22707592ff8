"""``--omega LINK=EXPR`` in t for trajectory, curves and animate, and ``--fixed frame``.

The carrier's angle under a sun speed 10 t (rad/s) against the integral by hand with
Willis' ratio of the AI train typed here: i_1H = 1 + z2 z4 / (z1 z3).
"""

from __future__ import annotations

import sympy as sp

from symkin import symbols as S
from symkin.cli import build_parser, main
from symkin.cli.plots import _setup


def test_a_speed_in_t_on_the_command_line_gives_the_motion_python_gives(tmp_path):
    args = build_parser().parse_args(["trajectory", "AI", "--teeth", "20,30,20,70", "--omega", "1=10*t",
                                      "--omega", "4=0", "--t-end", "2", "--out", str(tmp_path / "p.png")])
    _, motion, _, t_end, _, _, _ = _setup(args)
    i_1h = 1 + sp.Rational(30 * 70, 20 * 20)   # Willis, gear 4 held
    assert t_end == 2.0
    assert sp.simplify(motion.angle("H") - 5 * S.t**2 / i_1h) == 0   # the integral of 10 t / i_1H


def test_trajectory_and_curves_take_a_speed_in_t(tmp_path, capsys):
    for command in ("trajectory", "curves"):
        out = tmp_path / f"{command}.png"
        assert main([command, "AI", "--teeth", "20,30,20,70", "--omega", "1=10*t", "--omega", "4=0", "--t-end", "1",
                     "--out", str(out)]) == 0
        assert out.stat().st_size > 1000
    # a speed in t with turns (no constant speed to count turns by), or not finite: a one-line error, exit 2
    assert main(["trajectory", "AI", "--teeth", "20,30,20,70", "--omega", "1=1/t", "--omega", "4=0", "--t-end", "1",
                 "--out", str(tmp_path / "x.png")]) == 2
    assert "not finite" in capsys.readouterr().err
    assert not (tmp_path / "x.png").exists()


def test_fixed_frame_is_the_frame(capsys):
    import json

    def run(*extra: str) -> dict:
        assert main(["efficiency", "--train", "simple", "--driver", "S", "--driven", "C", *extra, "--json"]) == 0
        return json.loads(capsys.readouterr().out)

    assert run("--fixed", "R", "--fixed", "frame")["efficiency"] == run("--fixed", "R")["efficiency"]
    assert main(["efficiency", "--train", "wolfrom", "--driver", "S", "--driven", "R2", "--fixed", "frame", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["torques"]["R2"]["exact"] == "-76"
