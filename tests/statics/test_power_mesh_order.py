"""The power through a mesh and the housing's torque, against hand statics and the order of the meshes.

- The power through a contact does not depend on the order the file lists the meshes in, nor
  on the order of a mesh's gears (a property test: any permutation, any swaps).
- The Wolfrom train's mesh powers by hand: the sun's mesh carries the sun's torque times its
  speed relative to the carrier, the output ring's mesh the ring's torque times its relative speed.
- The housing's torque closes the balance of the whole train: -(T_in + T_out), the brake's
  reaction in a Simpson first gear (lever analogy, typed here).
"""

from __future__ import annotations

import importlib.resources

import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symkin.statics import statics
from symkin.trains import read_train

_WOLFROM = (importlib.resources.files("symkin.trains") / "library" / "wolfrom.toml").read_text()
_MESHES = [["s", "p1"], ["p1", "r1"], ["p2", "r2"]]


def _powers(meshes: list[list[str]]) -> dict[frozenset[str], sp.Expr]:
    listed = ", ".join(f'["{a}", "{b}"]' for a, b in meshes)
    text = _WOLFROM.replace('meshes = [["s", "p1"], ["p1", "r1"], ["p2", "r2"]]', f"meshes = [{listed}]")
    res = statics(read_train(text), input="S", output="R2", efficiency=sp.Rational(49, 50))
    return {frozenset((m.mesh.a, m.mesh.b)): (m.power, m.driver) for m in res.meshes} | {"eta": res.efficiency.rhs}


_REFERENCE = _powers(_MESHES)


@settings(max_examples=8, deadline=None)
@given(st.permutations(range(3)), st.lists(st.booleans(), min_size=3, max_size=3))
def test_mesh_powers_do_not_depend_on_the_order_of_the_meshes(order, swaps):
    meshes = [_MESHES[k][::-1] if swap else _MESHES[k] for k, swap in zip(order, swaps)]
    assert _powers(meshes) == _REFERENCE


def test_wolfrom_mesh_powers_by_hand():
    # ratio 76 (the file's), carrier speed by Willis on the fixed ring: w_C = w_S * 12/(12 + 60) = 1/6
    w_s, w_c, w_r2 = 1, sp.Rational(1, 6), sp.Rational(1, 76)
    t_r2 = -76  # ideal: the output's torque by the power balance
    ideal = statics(read_train(_WOLFROM), input="S", output="R2", efficiency=1)
    powers = {frozenset((m.mesh.a, m.mesh.b)): m.power for m in ideal.meshes}
    assert powers[frozenset(("s", "p1"))] == abs(1 * (w_s - w_c))          # 5/6
    assert powers[frozenset(("p2", "r2"))] == abs(t_r2 * (w_r2 - w_c))     # 35/3
    assert ideal.circulating == max(powers.values()) > 1


def test_housing_torque_is_the_brake_reaction_of_simpson_first():
    import importlib.resources as res

    train = read_train((res.files("symkin.trains") / "library" / "simpson.toml").read_text())
    st_ = statics(train, input="R1", output="C1", fixed=("C2",), efficiency=1)
    # lever analogy (hand): front set R1 72, S 30; rear set with C2 held: w_S = -(72/30) w_C1.
    # front: 102 w_C1 = 72 w_R1 + 30 w_S = 72 - 72 w_C1  ->  w_C1 = 72/174 = 12/29, ratio 29/12
    assert st_.speeds["C1"] == sp.Rational(12, 29)
    assert st_.torques["C1"] == -sp.Rational(29, 12)
    assert st_.housing == -(1 - sp.Rational(29, 12)) == st_.torques["C2"]
    lossy = statics(train, input="R1", output="C1", fixed=("C2",), efficiency="default")
    assert lossy.housing_with_losses == -(1 + lossy.lossy_torques["C1"])
    assert 0 < lossy.housing_with_losses < lossy.housing  # less output torque, less reaction
