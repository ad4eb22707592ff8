"""Operating points against the power-split literature, hand statics and a second route.

- The Toyota power split (THS, Prius; sun 30, ring 78): the published speed relation
  omega_MG1 = (1 + k) omega_engine - k omega_ring with k = 78/30 and the published torque
  split (78/108 of the engine's torque to the ring, 30/108 reacted by the generator), typed here.
- With losses, by hand (basic-train method in the carrier's frame): the ring drives the sun
  through both meshes, so the sun gets eta = eta_sp eta_pr of the ring's relative power;
  with the torque balance this gives T_R = -T_C / (1 + eta (w_R - w_C)/(w_C - w_S)) ... typed
  below; the loss is (1 - eta) times the ring's relative power, and never negative.
- The Wolfrom train at an operating point against symkin.statics per unit torque (scaled).
"""

from __future__ import annotations

import json

import pytest
import sympy as sp

from symkin.cli import main
from symkin.errors import DeterminacyError, InputError, ModelError
from symkin.statics import operating_point, statics
from symkin.trains import load_train

RPM = sp.pi / 30


def test_the_prius_power_split_speeds_and_torque_split():
    op = statics(load_train("power-split"), speeds={"C": 2000 * RPM, "R": 1500 * RPM}, torques={"C": 100}, efficiency=1)
    k = sp.Rational(78, 30)
    assert op.speeds["S"] == (1 + k) * 2000 * RPM - k * 1500 * RPM           # 3300 rpm
    assert op.torques["R"] == -100 * sp.Rational(78, 108)
    assert op.torques["S"] == -100 * sp.Rational(30, 108)
    assert sum(op.powers.values()) == 0 and op.loss == 0 and op.housing == 0


def test_the_power_split_with_losses_by_hand():
    eta_sp, eta_pr = sp.Rational(98, 100), sp.Rational(99, 100)
    op = operating_point(load_train("power-split"), {"C": 2000 * RPM, "R": 1500 * RPM}, {"C": 100},
                         efficiency={"s-p": eta_sp, "p-r": eta_pr})
    w_s, w_c, w_r = 3300 * RPM, 2000 * RPM, 1500 * RPM
    eta = eta_sp * eta_pr
    # carrier frame: the ring's relative power T_R (w_R - w_C) > 0 flows to the sun, which gets eta of it:
    # -T_S (w_S - w_C) = eta T_R (w_R - w_C), and T_S + T_R + 100 = 0
    t_r, t_s = sp.symbols("t_r t_s")
    hand = sp.solve([sp.Eq(-t_s * (w_s - w_c), eta * t_r * (w_r - w_c)), sp.Eq(t_s + t_r + 100, 0)], [t_r, t_s])
    assert op.torques_with_losses["R"] == hand[t_r] and op.torques_with_losses["S"] == hand[t_s]
    assert op.loss == sp.cancel((1 - eta) * hand[t_r] * (w_r - w_c)) and op.loss > 0
    assert op.loss == sum(op.powers_with_losses.values())
    assert {m.driver for m in op.meshes} == {"p", "r"}  # the ring drives the planet, the planet the sun


def test_an_operating_point_of_a_one_dof_train_is_the_per_unit_statics_scaled():
    train = load_train("wolfrom")
    op = operating_point(train, {"S": 100}, {"S": 3, "C": 0}, efficiency="default")
    unit = statics(train, input="S", output="R2", efficiency="default")
    assert op.torques["R2"] == 3 * unit.torques["R2"]
    assert op.torques_with_losses["R2"] == 3 * unit.lossy_torques["R2"]
    assert op.housing_with_losses == 3 * unit.housing_with_losses
    assert op.loss == 300 * (1 - unit.efficiency.rhs)


def test_bad_operating_points_are_one_line_errors():
    train = load_train("power-split")
    with pytest.raises(ModelError, match="leaves the torques on S, C, R free"):
        operating_point(train, {"C": 1, "R": 1}, {})
    with pytest.raises(ModelError, match="more torques given"):
        operating_point(train, {"C": 1, "R": 1}, {"C": 1, "R": 1, "S": 1})
    with pytest.raises(InputError, match="no shaft of its own"):
        operating_point(train, {"C": 1, "R": 1}, {"P": 1})
    with pytest.raises(DeterminacyError):
        operating_point(train, {"C": 1}, {"C": 1})
    with pytest.raises(InputError, match="not both"):
        statics(train, input="C", output="R", speeds={"C": 1})


def test_the_cli_operating_point(capsys):
    assert main(["efficiency", "--train", "power-split", "--omega", "C=2000rpm", "--omega", "R=1500rpm",
                 "--torque", "C=100", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["torques"]["R"]["exact"] == "-650/9"
    assert data["torques_with_losses"]["R"]["float"] < -650 / 9 < 0
    assert data["loss"]["float"] > 0 and set(data["powers"]) == {"S", "C", "R"}
    assert main(["efficiency", "--train", "power-split", "--omega", "C=2000rpm", "--torque", "C=100"]) == 2
    assert "degrees of freedom" in capsys.readouterr().err
    assert main(["efficiency", "--train", "simpson-oneway", "--state", "D1", "--omega", "R1=100", "--torque",
                 "R1=10", "--torque", "S=0"]) == 0
    assert "C2" in capsys.readouterr().out


def test_the_housing_torque_is_the_brakes_reaction_as_in_the_per_unit_statics():
    # simple 24/72, ring held, 1 N m on the sun: the carrier gives -4 N m (Willis: 1 + 72/24), the
    # ring's brake takes 3 N m; the housing's torque on the train is that reaction, -(T_S + T_C)
    # (it was the sum of every port's torque, the reaction included: always 0)
    op = statics(load_train("simple"), speeds={"S": 4}, torques={"S": 1}, fixed=("R",))
    assert op.torques == {"S": 1, "C": -4, "R": 3}
    assert op.housing == 3 == statics(load_train("simple"), input="S", output="C", fixed=("R",)).housing
    assert op.housing_with_losses == op.torques_with_losses["R"]


def test_a_mesh_that_carries_no_power_has_no_driver():
    # simpson's third gear is direct drive: the rear set's meshes carry no force and no power
    st = statics(load_train("simpson"), input="R1", output="C1", joined=[("R1", "S")])
    idle = [m for m in st.meshes if m.mesh.a in ("s2", "p2")]
    assert idle and all(m.power == 0 and m.driver is None for m in idle)
    assert "p2-r2          0             0             0          -" in st.text()
