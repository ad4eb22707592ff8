"""symkin dynamics and symkin modes: text and JSON against values worked by hand, and bad input."""

from __future__ import annotations

import json
import math

import pytest

from symkin.cli import main

FILE = """
module = 1
meshes = [{ gears = ["s", "p"], stiffness = 4e8 }, { gears = ["p", "r"], stiffness = 4e8 }]
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
inertia = 0.1
[states.low]
input = "S"
output = "C"
brakes = ["R"]
"""


@pytest.fixture
def train_file(tmp_path):
    path = tmp_path / "simple.toml"
    path.write_text(FILE)
    return str(path)


def test_dynamics_json_gives_the_hand_worked_inertia_and_acceleration(train_file, capsys):
    assert main(["dynamics", "--train", train_file, "--state", "low", "--torque", "S=2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    # J_S + J_C/16 + 3 (J_P/4 + m r_c^2/16), r_c = 24 mm
    J = 0.01 + 0.05 / 16 + 3 * (0.002 / 4 + 0.5 * 0.024**2 / 16)
    assert data["coordinates"] == ["S"]
    assert data["mass_matrix"][0][0]["float"] == pytest.approx(J, rel=1e-12)
    assert data["accelerations"][0]["float"] == pytest.approx(2 / J, rel=1e-12)
    assert data["forcing"][0]["exact"] == "2"


def test_dynamics_text_and_latex_of_a_ready_made_train(capsys):
    assert main(["dynamics", "--train", "simple", "--coordinates", "S,R", "--torque", "S=T_in", "--latex"]) == 0
    out = capsys.readouterr().out
    assert "coordinates q = (varphi_S, varphi_R)" in out and "J_S" in out and "T_in" in out
    assert r"\mathbf{M} &=" in out


def test_modes_json_matches_the_two_gear_closed_form(tmp_path, capsys):
    path = tmp_path / "pair.toml"
    path.write_text('module = 1\nmeshes = [{ gears = ["a", "b"], stiffness = 1e8 }]\n[links.A]\ngears = { a = 20 }\n'
                    'inertia = 0.01\n[links.B]\ncarrier = "frame"\ngears = { b = 30 }\ninertia = 0.03\n')
    assert main(["modes", "--train", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    c2 = math.cos(math.radians(20)) ** 2
    w = math.sqrt(1e8 * c2 * (0.01**2 / 0.01 + 0.015**2 / 0.03))
    assert data["frequencies_hz"] == pytest.approx([0, w / (2 * math.pi)], rel=1e-9, abs=1e-9)
    assert set(data["mode_shapes"][1]) == {"A", "B"}


def test_modes_text_of_a_planetary_set_lists_each_planet(train_file, capsys):
    assert main(["modes", "--train", train_file, "--state", "low"]) == 0
    out = capsys.readouterr().out
    assert "coordinates S, C, P_1, P_2, P_3" in out and "frequency [Hz]" in out


@pytest.mark.parametrize("argv, message", [
    (["dynamics", "--train", "simple", "--torque", "S"], "LINK=VALUE"),
    (["dynamics", "--train", "simple", "--torque", "S=1", "--torque", "S=2"], "twice"),
    (["dynamics", "--train", "simple", "--coordinates", "S,,R"], "--coordinates"),
    (["dynamics", "--train", "simple", "--state", "low", "--coordinates", "R"], "does not move"),
    (["dynamics", "--train", "simple", "--torque", "S=1kg"], "--torque"),
    (["modes", "--train", "simple", "--state", "nope"], "no state"),
    (["modes", "--train", "simple", "--value", "J_S=-1"], "0 or more"),
    (["modes", "--train", "simple", "--value", "J_S"], "NAME=NUMBER"),
])
def test_bad_input_is_one_line_and_exit_2(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_values_give_numbers_to_a_ready_made_train(capsys):
    values = ["J_S=0.01", "J_C=0.05", "J_P=0.002", "m_P=0.5", "k_s_p=5e8", "k_p_r=5e8"]
    assert main(["modes", "--train", "simple", "--state", "low", *(f"--value={v}" for v in values), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["frequencies_hz"]) == 5 and data["frequencies_hz"][0] == 0
    assert main(["dynamics", "--train", "simple", "--state", "low", "--torque", "S=2", *(f"--value={v}" for v in values),
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    J = 0.01 + 0.05 / 16 + 3 * (0.002 / 4 + 0.5 * 0.024**2 / 16)  # module 1: planet axes at 24 mm
    assert data["accelerations"][0]["float"] == pytest.approx(2 / J, rel=1e-12)


def test_a_large_symbolic_model_answers_at_once_without_its_determinant(capsys):
    assert main(["modes", "--train", "ravigneaux", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["frequencies_hz"] is None and data["characteristic_polynomial"] is None
    assert len(data["coordinates"]) == 10
