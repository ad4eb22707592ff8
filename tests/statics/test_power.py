"""Torques, power flow and efficiency of any train, against independent routes.

- Ideal torques against virtual work: every admissible motion does no work.
- Efficiencies against the textbook closed forms of the simple planetary set (the basic
  train's efficiency applied to the relative power, both ways), worked by hand.
- Efficiencies of random trains against a numeric solve written here: Willis' relation per
  mesh for the torques, every assignment of driving gears tried, and the one whose relative
  powers agree with it kept (no symbolic branch logic of symkin's).
- As every mesh efficiency tends to 1, every efficiency tends to 1.
"""

from __future__ import annotations

import itertools
import json
import random

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symkin import schemes
from symkin.cli import main
from symkin.errors import DeterminacyError, ModelError
from symkin.model import FRAME, LinkKind
from symkin.statics import statics
from symkin.trains import load_train, read_train

#: random tooth numbers need not be coaxial (profile shift): the laws hold, the warning is noise here
pytestmark = pytest.mark.filterwarnings("ignore::symkin.CoaxialityWarning")

PARALLEL = ["simple", "wolfrom", "simpson", "ravigneaux", "double-pinion", "ferguson", "nested"]


def _configurations():
    for name in PARALLEL + ["bevel-differential", "bevel-epicyclic"]:
        train = load_train(name)
        for state in train.states:
            yield pytest.param(train, state, id=f"{name}-{state.name}")


@pytest.mark.parametrize("train, state", list(_configurations()))
def test_ideal_torques_do_no_work_in_any_admissible_motion(train, state):
    res = statics(train, input=state.input, output=state.output, fixed=state.brakes, joined=state.clutches)
    power = sum(res.torques[n] * res.speeds[n] for n in res.torques)
    assert sp.simplify(power) == 0
    # and the torques of the frame's reaction balance: the whole train is in equilibrium
    assert sp.simplify(sum(res.torques.values()) + _frame_reaction(res)) == 0


def _frame_reaction(res):
    """The torque the frame takes: minus the sum of the external torques on the moving links."""
    return -sum(res.torques.values())


def test_simple_planetary_efficiency_by_the_textbook_forms():
    train = load_train("simple")
    k = sp.Rational(72, 24)  # z_r / z_s
    eta0 = sp.Symbol("eta_sp", positive=True) * sp.Symbol("eta_pr", positive=True)
    forward = statics(train, input="S", output="C", fixed=("R",))
    # sun drives carrier, ring held: the basic train (carrier frame) runs sun -> ring, eta = (1 + eta0 k)/(1 + k)
    assert sp.simplify(forward.efficiency.rhs - (1 + eta0 * k) / (1 + k)) == 0
    # carrier drives sun: the basic train runs ring -> sun, eta = (1 + k) eta0 / (eta0 + k)
    assert sp.simplify(forward.backward.efficiency.rhs - (1 + k) * eta0 / (eta0 + k)) == 0
    # carrier held: an ordinary train, eta = eta0 both ways
    held = statics(train, input="S", output="R", fixed=("C",))
    assert sp.simplify(held.efficiency.rhs - eta0) == 0 and sp.simplify(held.backward.efficiency.rhs - eta0) == 0
    assert forward.torques == {"S": 1, "C": -(1 + k), "P": 0, "R": k}


# --------------------------------------------------------------------------- a numeric route
def numeric_efficiency(mech, inp, out, fixed, joined, eta_of):
    """Willis per mesh in the carrier's frame: with gear a's torque tau_a, the other gear's is
    -lambda tau_a (lambda = the basic ratio omega_a,rel / omega_b,rel), times eta or divided by
    it as the driving gear gives; the carrier takes the rest.  Every assignment of drivers
    is solved and the one whose relative powers agree with it is kept."""
    links = list(mech.link_names)
    idx = {n: i for i, n in enumerate(links)}
    speeds = mech.speeds({**{f: 0 for f in fixed if f != FRAME}, inp: 1}) if not joined else None
    if speeds is None:
        from symkin.kinematics import solve_speeds

        speeds = solve_speeds(mech, {**{f: 0 for f in fixed}, inp: 1}, joined=joined)
    w = {n: float(speeds[n]) for n in links}
    w[FRAME] = 0.0
    by_gear = {g.name: (g, L) for L in mech.links for g in L.gears}
    meshes = []
    for m in mech.meshes:
        (ga, la), (gb, lb) = by_gear[m.a], by_gear[m.b]
        carrier = (lb if lb.kind is LinkKind.PLANET and lb.arm != 0 else la).carrier
        if la.kind is LinkKind.PLANET and lb.kind is LinkKind.PLANET:
            deeper = lb if (lb.arm != 0 and lb.carrier != la.name and la.arm == 0) else la
            carrier = deeper.carrier if deeper.arm != 0 else mech.link(deeper.carrier).carrier
        lam = (float(gb.radius.subs("m", 1)) / float(ga.radius.subs("m", 1))) * (1 if (ga.internal or gb.internal) else -1)
        meshes.append((m, la.name, lb.name, carrier, lam, eta_of(m)))
    unknowns = len(meshes) + 1 + len(fixed) + len(joined)
    best = None
    for drivers in itertools.product((1, -1), repeat=len(meshes)):
        A = np.zeros((len(links), unknowns))
        b = np.zeros(len(links))
        for k, (_, a, bl, c, lam, eta) in enumerate(meshes):
            factor = -lam * (eta if drivers[k] > 0 else 1 / eta)
            for link, coeff in ((a, 1.0), (bl, factor), (c, -(1.0 + factor))):
                if link != FRAME:
                    A[idx[link], k] += coeff
        A[idx[out], len(meshes)] = 1.0
        for j, f in enumerate(fixed):
            A[idx[f], len(meshes) + 1 + j] = 1.0
        for j, (p, q) in enumerate(joined):
            A[idx[p], len(meshes) + 1 + len(fixed) + j] = 1.0
            A[idx[q], len(meshes) + 1 + len(fixed) + j] = -1.0
        b[idx[inp]] = -1.0
        x, *_ = np.linalg.lstsq(A, b, rcond=None)
        if np.linalg.norm(A @ x - b) > 1e-9:
            continue
        # the assumed driver of each mesh delivers the relative power (a mesh without relative motion or load
        # loses nothing, whichever gear is called its driver)
        consistent = all(-x[k] * (w[a] - w[c]) * d > -1e-12 for k, ((m, a, bl, c, lam, eta), d) in enumerate(zip(meshes, drivers)))
        if consistent:
            eff = -x[len(meshes)] * w[out]
            assert best is None or abs(best - eff) < 1e-9, "two consistent power flows"
            best = eff
    return best


@pytest.mark.parametrize("seed", range(6))
def test_efficiency_of_random_trains_against_a_numeric_power_balance(seed):
    rng = random.Random(seed)
    scheme = rng.choice(["AI", "AA", "II"])
    z = [rng.randint(18, 90) for _ in range(4)]
    if scheme == "II":
        z[0], z[3] = z[1] + rng.randint(8, 40), z[2] + rng.randint(8, 40)
    elif scheme == "AI":
        z[3] = z[2] + rng.randint(10, 60)
    mech = schemes.two_row(scheme, teeth=tuple(z), module=1)
    etas = {"1-2": sp.Rational(rng.randint(940, 999), 1000), "3-4": sp.Rational(rng.randint(940, 999), 1000)}
    for inp, out in (("1", "H"), ("H", "1"), ("4", "H")):
        fixed = tuple(x for x in ("1", "4", "H") if x not in (inp, out))
        ours = statics(mech, input=inp, output=out, fixed=fixed, efficiency=etas).efficiency.rhs
        theirs = numeric_efficiency(mech, inp, out, fixed, (), lambda m: float(etas[f"{m.a}-{m.b}"]))
        assert theirs is not None
        assert float(ours) == pytest.approx(theirs, rel=1e-9, abs=1e-12), (scheme, z, inp, out)


@pytest.mark.parametrize("name", ["ravigneaux", "simpson", "wolfrom", "double-pinion"])
def test_efficiency_of_the_ready_made_trains_against_the_numeric_power_balance(name):
    train = load_train(name)
    for state in train.states:
        ours = statics(train, input=state.input, output=state.output, fixed=state.brakes, joined=state.clutches,
                       efficiency="default").efficiency.rhs
        defaults = {m: 0.99 if any(g.internal for L in train.links for g in L.gears if g.name in (m.a, m.b)) else 0.98
                    for m in train.meshes}
        theirs = numeric_efficiency(train, train.link(state.input).name, train.link(state.output).name,
                                    tuple(train.link(b).name for b in state.brakes),
                                    tuple((train.link(a).name, train.link(b).name) for a, b in state.clutches),
                                    lambda m: defaults[m])
        assert float(ours) == pytest.approx(theirs, rel=1e-9), state.name


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(["AI", "AA", "II"]), st.lists(st.integers(18, 80), min_size=4, max_size=4),
       st.sampled_from([("1", "H"), ("H", "1")]))
def test_efficiency_tends_to_one_as_every_mesh_does(scheme, z, drive):
    if scheme == "II":
        z[0], z[3] = z[1] + 10, z[2] + 12
    if scheme == "AI":
        z[3] = z[2] + 10
    mech = schemes.two_row(scheme, teeth=tuple(z), module=1)
    try:
        res = statics(mech, input=drive[0], output=drive[1], fixed=("4",))
    except (ModelError, DeterminacyError) as err:  # a degenerate train (1:1 AA): nothing to measure
        assert "stands still" in str(err) or "not independent" in str(err)
        return
    law = res.efficiency.rhs
    etas = [s for s in law.free_symbols if s.name.startswith("eta_")]
    one = law.subs({e: 1 for e in etas})
    if isinstance(one, sp.Piecewise):
        one = sp.piecewise_fold(one).args[0][0]
    assert sp.simplify(one) == 1


def test_circulating_power_and_self_locking_of_the_2009_ii_example():
    res = statics(schemes.two_row("II", teeth=(200, 99, 100, 201)), input="H", output="1", fixed=("4",),
                  efficiency="default")
    # the planet's meshes roll i - 1 times the input power relative to the carrier (by hand: gear 1's torque is
    # -i by the power balance, its speed relative to the carrier 1/i - 1), and gear 1 cannot drive the carrier
    i = sp.Rational(200 * 100, 101)  # the ratio omega_H/omega_1 of the 2009 paper's II train, 1 - (201*99)/(200*100)
    assert res.speeds["1"] == 1 / i
    assert res.circulating == i - 1 and res.self_locking is True
    assert float(res.backward.efficiency.rhs) < 0


def test_a_train_file_gives_mesh_efficiencies_and_the_cli_prints_both_ways(tmp_path, capsys):
    import importlib.resources

    text = (importlib.resources.files("symkin.trains") / "library" / "simple.toml").read_text()
    text = text.replace('meshes = [["s", "p"], ["p", "r"]]', 'meshes = [{ gears = ["s", "p"], efficiency = 0.97 }, ["p", "r"]]')
    path = tmp_path / "lossy.toml"
    path.write_text(text)
    train = read_train(text)
    assert train.meshes[0].efficiency == sp.Rational(97, 100)
    assert main(["efficiency", "--train", str(path), "--state", "low", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    # (1 + eta0 k)/(1 + k) with eta0 = 0.97 * 0.99 (the file's and the internal default), k = 3
    assert data["efficiency"]["exact"] == str((1 + sp.Rational(97, 100) * sp.Rational(99, 100) * 3) / 4)
    assert data["self_locking"] is False and data["torques"]["C"]["exact"] == "-4"
    # the Python API's "default" means the same: the file's value where given, else the defaults
    lossy = statics(train, input="S", output="C", fixed=("R",), efficiency="default")
    assert lossy.efficiency.rhs == (1 + sp.Rational(97, 100) * sp.Rational(99, 100) * 3) / 4
    assert main(["efficiency", "II", "--teeth", "200,99,100,201", "--driver", "H", "--driven", "1", "--fixed", "4",
                 "--mesh-efficiency", "1-2=0.995", "--latex"]) == 0
    out = capsys.readouterr().out
    assert "self-locking: yes" in out and r"\eta^{(4)}_{H1}" in out
    # gear 1 driving the same train: efficiency (20000 eta0 - 19899)/(101 eta0) < 0 at 0.99^2, said so
    assert main(["efficiency", "II", "--teeth", "200,99,100,201", "--driver", "1", "--driven", "H", "--fixed", "4"]) == 0
    out = capsys.readouterr().out
    assert "-10000/3333" in out and "this way it locks: 1 cannot drive H" in out and "H can drive 1" in out
    assert main(["efficiency", "--train", "simple", "--state", "low", "--mesh-efficiency", "1.5"]) == 2
    assert "must lie in (0, 1]" in capsys.readouterr().err


def test_a_train_left_free_says_which_link_to_hold(capsys):
    """The simple set with nothing held turns freely: the message said 'give exactly 2 link
    speeds, for example S and C', advice for speeds, not for a load case."""
    simple = load_train("simple")
    with pytest.raises(DeterminacyError, match=r"still turns freely: hold more links \(fixed=, --fixed; for example R\)"):
        statics(simple, input="S", output="C")
    assert main(["efficiency", "--train", "simple", "--driver", "S", "--driven", "C"]) == 2
    assert "hold more links" in capsys.readouterr().err
    # a locked train keeps the solver's own message (it was told to hold more links)
    with pytest.raises(DeterminacyError, match="locked"):
        statics(simple, input="S", output="C", joined=[("R", "C"), ("R", "0")])
    # holding the link it names is the remedy: the textbook ratio 1 + 72/24 and a positive efficiency
    st = statics(simple, input="S", output="C", fixed=("R",), efficiency="default")
    assert st.speeds["C"] == sp.Rational(1, 4) and 0 < float(st.efficiency.rhs) < 1
