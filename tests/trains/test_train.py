"""Train files, states and shift tables, against independent references.

- Every state of every ready-made train against Willis' formula applied mesh by mesh and
  solved in Fractions here (no symkin kinematics), and against the textbook closed forms
  of the simple planetary, the Simpson, Wolfrom and Ferguson trains worked by hand.
- Planet positions of meshing planets against the triangle of arms and centre distance,
  and the particle laws of a planet placed that way against sympy.physics.mechanics.
- States that leave a link free or lock the train; bad files; the value-keyed cache.
"""

from __future__ import annotations

import dataclasses
import json
import random
import warnings
from fractions import Fraction

import pytest
import sympy as sp
from sympy.physics import mechanics as me

import symkin
from symkin import symbols as S
from symkin.cli import main
from symkin.errors import CoaxialityWarning, DeterminacyError, ModelError, TrainFileError
from symkin.model import FRAME, LinkKind
from symkin.trains import load_train, read_train, ready_made

READY = sorted(ready_made())


# --------------------------------------------------------------------------- Willis, by hand
def willis_speeds(train, state, teeth=None):
    """Every link's speed per unit input speed: Willis' formula for each mesh (the relative
    speeds of two meshing gears to their carrier are in the inverse ratio of their teeth,
    opposite for an external mesh), brakes, clutches, solved by Gaussian elimination in
    Fractions."""
    links = [L.name for L in train.links if L.kind is not LinkKind.FRAME]
    index = {n: i for i, n in enumerate(links)}
    owner = {g.name: L for L in train.links for g in L.gears}
    gear = {g.name: g for L in train.links for g in L.gears}
    z = {g.name: Fraction(int((teeth or {}).get(g.name, g.teeth))) for L in train.links for g in L.gears}
    rows = []

    def row(coeffs, rhs=Fraction(0)):
        r = [Fraction(0)] * (len(links) + 1)
        for name, c in coeffs:
            if name != FRAME:
                r[index[name]] += c
        r[-1] = rhs
        rows.append(r)

    by_name = {L.name: L for L in train.links}

    def axis_owner(L):  # the planet whose axis a link turns about (None: the main axis)
        if L.kind is not LinkKind.PLANET:
            return None
        return L if L.arm != 0 else axis_owner(by_name[L.carrier])

    def depth(L):
        return 0 if L is None or L.kind is not LinkKind.PLANET else 1 + depth(by_name[L.carrier])

    for mesh in train.meshes:
        A, B = owner[mesh.a], owner[mesh.b]
        za, zb = z[mesh.a], z[mesh.b]
        if A.axis == "radial" or B.axis == "radial":
            # a bevel side gear and a pinion: z_side (w_side - w_C) = -side z_p w_p (w_p: the spin relative to C)
            pin, side_link, zp, zs, side = (A, B, za, zb, gear[mesh.b].side) if A.axis == "radial" else (B, A, zb, za, gear[mesh.a].side)
            row([(side_link.name, zs), (pin.carrier, -zs), (pin.name, side * zp)])
            continue
        # the link holding both axes: the carrier of the deeper axis
        deeper = max((axis_owner(A), axis_owner(B)), key=depth)
        carrier = deeper.carrier
        sign = 1 if gear[mesh.a].internal or gear[mesh.b].internal else -1
        # w_A - w_C = sign * (z_b / z_a) * (w_B - w_C)  ->  z_a (w_A - w_C) - sign z_b (w_B - w_C) = 0
        row([(A.name, za), (carrier, -za), (B.name, -sign * zb), (carrier, sign * zb)])
    for b in state.brakes:
        row([(train.link(b).name, Fraction(1))])
    for a, b in state.clutches:
        row([(train.link(a).name, Fraction(1)), (train.link(b).name, Fraction(-1))])
    row([(train.link(state.input).name, Fraction(1))], Fraction(1))
    # Gaussian elimination, exact
    n = len(links)
    m = [r[:] for r in rows]
    pivots = []
    r0 = 0
    for c in range(n):
        p = next((i for i in range(r0, len(m)) if m[i][c] != 0), None)
        if p is None:
            continue
        m[r0], m[p] = m[p], m[r0]
        m[r0] = [v / m[r0][c] for v in m[r0]]
        for i in range(len(m)):
            if i != r0 and m[i][c] != 0:
                f = m[i][c]
                m[i] = [a - f * b for a, b in zip(m[i], m[r0])]
        pivots.append(c)
        r0 += 1
    assert len(pivots) == n, "the hand solution leaves a link free"
    assert all(all(v == 0 for v in r) for r in m[r0:]), "the hand solution is inconsistent"
    return {links[c]: m[k][-1] for k, c in enumerate(pivots)}


def symkin_per_input(shift):
    w = S.omega(shift.state.input)
    return {n: sp.Rational(sp.cancel(v / w)) for n, v in shift.speeds.items()}


@pytest.mark.parametrize("name", READY)
def test_every_state_of_every_ready_made_train_is_willis_per_mesh(name):
    train = load_train(name)
    assert train.states, f"{name} has no states"
    for shift in train.shift_table():
        brakes, clutches = train.engaged(shift.state)  # with the one-way clutches that hold
        hand = willis_speeds(train, dataclasses.replace(shift.state, brakes=brakes, clutches=clutches))
        ours = symkin_per_input(shift)
        assert ours == {k: sp.Rational(v.numerator, v.denominator) for k, v in hand.items()}, shift.state.name
        out = train.link(shift.state.output).name
        assert shift.ratio.rhs == sp.Rational(1) / sp.Rational(hand[out].numerator, hand[out].denominator)


def test_random_tooth_numbers_in_a_ravigneaux_file_against_willis():
    rng = random.Random(7)
    text = _library_text("ravigneaux")
    for _ in range(8):
        s1, s2, p = rng.randint(17, 40), rng.randint(17, 40), rng.randint(14, 30)
        r = s2 + 2 * p
        t = (text.replace("s1 = 30", f"s1 = {s1}").replace("s2 = 36", f"s2 = {s2}")
             .replace("p1 = 18", f"p1 = {p}").replace("p2 = 18", f"p2 = {p}").replace("teeth = 72", f"teeth = {r}"))
        try:
            train = read_train(t, "random ravigneaux")
        except ModelError:
            continue  # the short pinion cannot reach the long one for these teeth: refused, tested elsewhere
        for shift in train.shift_table():
            hand = willis_speeds(train, shift.state)
            assert symkin_per_input(shift) == {k: sp.Rational(v.numerator, v.denominator) for k, v in hand.items()}


def _library_text(name):
    import importlib.resources

    return (importlib.resources.files("symkin.trains") / "library" / f"{name}.toml").read_text()


# --------------------------------------------------------------------------- textbook forms, by hand
def test_simple_planetary_textbook_ratios():
    ratios = {s.state.name: s.ratio.rhs for s in load_train("simple").shift_table()}
    zs, zr = 24, 72
    assert ratios == {"low": 1 + sp.Rational(zr, zs), "reverse": -sp.Rational(zr, zs), "overdrive": sp.Rational(zr, zr + zs)}


def test_simpson_shift_table_by_hand():
    # identical sets, k = Zr/Zs: first (2k + 1)/k, second (k + 1)/k, third 1, reverse -k
    k = sp.Rational(72, 30)
    ratios = [s.ratio.rhs for s in load_train("simpson").shift_table()]
    assert ratios == [(2 * k + 1) / k, (k + 1) / k, 1, -k]


def test_wolfrom_by_its_closed_form():
    # i = (1 + z_r1/z_s) / (1 - z_r1 z_p2 / (z_p1 z_r2)) (the Wolfrom train's classical form)
    zs, zp1, zp2, zr1, zr2 = 12, 24, 21, 60, 57
    expected = (1 + sp.Rational(zr1, zs)) / (1 - sp.Rational(zr1 * zp2, zp1 * zr2))
    assert load_train("wolfrom").shift("drive").ratio.rhs == expected == 76


def test_ferguson_paradox_and_its_profile_shift():
    with warnings.catch_warnings():
        warnings.simplefilter("error", CoaxialityWarning)  # the working centre distances make it coaxial
        train = load_train("ferguson")
    # with sun 1 fixed, sun k turns at 1 - z1/zk per carrier turn (Ferguson's paradox)
    shifts = {s.state.name: s for s in train.shift_table()}
    assert shifts["s2"].ratio.rhs == 1 / (1 - sp.Rational(100, 99)) == -99
    assert shifts["s3"].ratio.rhs == 1 / (1 - sp.Rational(100, 101)) == 101
    assert train.arm("P") == 60
    assert not train.coaxiality_defects()
    with pytest.warns(CoaxialityWarning, match="planet P is not coaxial"):
        plain = read_train(_library_text("ferguson").replace('{ gears = ["p", "s2"], centre_distance = 60 }', '["p", "s2"]'))
    # without the shift the same ratios, and the model says the planet is not coaxial
    assert plain.coaxiality_defects()


def test_a_locked_state_is_exactly_one():
    for name, state in (("ravigneaux", "third"), ("simpson", "third"), ("double-pinion", "direct")):
        shift = load_train(name).shift(state)
        assert shift.ratio.rhs == 1 and all(v == S.omega(shift.state.input) for v in shift.speeds.values())


# --------------------------------------------------------------------------- planet positions
def test_meshing_planets_are_placed_by_the_triangle_and_stay_in_mesh():
    train = load_train("double-pinion")
    a1, a2, d = train.arm("P1"), train.arm("P2"), sp.Integer(18)
    assert (a1, a2) == (24, 36)
    theta = train.position_angle("P2") - train.position_angle("P1")
    assert sp.simplify(a1**2 + a2**2 - 2 * a1 * a2 * sp.cos(theta) - d**2) == 0
    motion = train.motion({"S": 1, "R": sp.Rational(1, 3)})
    c1, c2 = (motion.particle(p, (0, 0), relative_to="pole").position for p in ("P1", "P2"))
    for t in (0, sp.Rational(7, 10), 3):
        gap = (c1 - c2).subs(S.t, t)
        assert sp.N(gap.dot(gap), 30) == pytest.approx(324, rel=1e-25)


def test_a_given_angle_that_contradicts_a_mesh_is_refused():
    given = _library_text("double-pinion").replace('gears = { p1 = 18 }', 'angle = 0\ngears = { p1 = 18 }')
    placed = read_train(given, "dp.toml")  # one angle given: the other placed from it
    # law of cosines: (24^2 + 36^2 - 18^2)/(2 24 36) = 1548/1728 = 43/48
    assert placed.position_angle("P1") == 0 and placed.position_angle("P2") == sp.acos(sp.Rational(43, 48))
    bad = given.replace('gears = { p2 = 18 }', 'angle = 0.3\ngears = { p2 = 18 }')
    with pytest.raises(TrainFileError, match=r"dp.toml: \[links.P1\]: planets P1 and P2 mesh but their given position angles put their axes"):
        read_train(bad, "dp.toml")


def test_planets_that_cannot_reach_each_other_are_refused():
    far = _library_text("double-pinion").replace("teeth = 90", "teeth = 130")  # P2 at 56: 56 - 24 > 18
    with pytest.raises(TrainFileError, match=r"cannot mesh: their axes are at .* no position puts them 18 apart"):
        read_train(far, "far.toml")


def test_particle_of_a_placed_planet_against_sympy_mechanics():
    """The double pinion with the carrier and the sun turning: a point of the outer pinion, by
    sympy.physics.mechanics (frames, the pinion's axis on the carrier, its own rotation)."""
    train = load_train("double-pinion")
    wS, wC = sp.Rational(3, 2), sp.Rational(-1, 3)
    # outer pinion speed by Willis for S and C given: (wP1 - wC) 18 = -(wS - wC) 30, (wP2 - wC) 18 = -(wP1 - wC) 18
    wP1 = wC - (wS - wC) * sp.Rational(30, 18)
    wP2 = wC - (wP1 - wC)
    N = me.ReferenceFrame("N")
    t = me.dynamicsymbols._t
    C = N.orientnew("C", "Axis", [wC * t, N.z])
    P2 = N.orientnew("P2", "Axis", [wP2 * t, N.z])
    O = me.Point("O")
    O.set_vel(N, 0)
    theta2 = train.position_angle("P2")
    axis = O.locatenew("A2", 36 * (sp.cos(theta2) * C.x + sp.sin(theta2) * C.y))
    point = axis.locatenew("Q", sp.Rational(5) * P2.x + sp.Rational(-2) * P2.y)
    r = point.pos_from(O)
    v = r.dt(N)
    a = v.dt(N)
    motion = train.motion({"S": wS, "C": wC})
    ours = motion.particle("P2", (5, -2), relative_to="pole")
    for tt in (0, sp.Rational(1, 3), sp.Rational(17, 5)):
        for vec_sym, vec_me in ((ours.position, r), (ours.velocity, v), (ours.acceleration, a)):
            for k, axis_vec in enumerate((N.x, N.y)):
                got = sp.N(vec_sym[k].subs(S.t, tt), 30)
                want = sp.N(vec_me.dot(axis_vec).subs(t, tt), 30)
                assert abs(got - want) < 1e-20, (tt, k, got, want)


# --------------------------------------------------------------------------- states that do not work
def test_a_state_that_leaves_a_link_free_names_the_state_and_the_links():
    text = _library_text("simple") + '\n[states.neutral]\ninput = "S"\noutput = "C"\n'
    train = read_train(text, "simple+neutral.toml")
    with pytest.raises(DeterminacyError, match=r"state 'neutral': the mechanism has 2 degrees of freedom but only 1 link speed is given \(S\)"):
        train.shift("neutral")


def test_a_state_that_holds_the_train_names_the_state():
    text = _library_text("simple") + '\n[states.stuck]\ninput = "S"\noutput = "C"\nbrakes = ["R", "P"]\n'
    train = read_train(text, "stuck.toml")
    with pytest.raises(DeterminacyError, match=r"state 'stuck': the mechanism has 2 degrees of freedom but 3 link speeds are given"):
        train.shift("stuck")


# --------------------------------------------------------------------------- bad files
BAD = [
    ('meshes = [["s", "x"]]', "meshes[1]: names no gear 'x'"),
    ('meshes = [["r", "r2"]]\n[links.R2]\ngears = { r2 = { teeth = 80, internal = true } }', "both internal and cannot mesh"),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "Q"\ngears = { p = 20 }', "[links.P] carrier: names no link 'Q'"),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "Q"\ngears = { p = 20 }\n[links.Q]\ncarrier = "P"', "carrier cycle: P -> Q -> P"),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "C"\ngears = { p = 20.5 }', "[links.P] gears.p: a tooth number is a whole number"),
    # a tooth named like a constant, a function or the time printed as one: (pi + 72)/pi looked like pi's ratio
    *((f'meshes = [["s", "p"]]\n[links.P]\ncarrier = "C"\ngears = {{ p = "{name}" }}', "names a constant, a function or the time")
      for name in ("pi", "E", "I", "oo", "nan", "t", "sin")),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "C"\ngears = { s = 20 }', "gear 's' is also on link 'S'"),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "C"\ngears = { p = 20 }\ncolour = "red"', "[links.P]: unknown key 'colour'"),
    # nothing joins them: free speeds no state can fix (50 such links took minutes to be told so by the states)
    ('meshes = [["s", "p"], ["p", "r"]]\n[links.P]\ncarrier = "C"\ngears = { p = 20 }\n[links.X1]\n[links.X2]',
     "links: X1, X2 connect to nothing"),
    ('meshes = [["s", "p"], ["p", "r"], ["s9", "p9"]]\n[links.P]\ncarrier = "C"\ngears = { p = 20 }\n[links.S9]\n'
     'gears = { s9 = 20 }\n[links.P9]\ncarrier = "C9"\ngears = { p9 = 20 }\n[links.C9]',
     "the train falls apart into 2 parts that no mesh, carrier or clutch joins (S, C, R, P; S9, P9, C9)"),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "C"\ngears = { p = 20 }\n[links.P]\ncarrier = "C"', "not valid TOML"),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "C"\ngears = { p = 20 }\n[states.x]\ninput = "S"', "[states.x]: give the output link"),
    ('meshes = [["s", "p"]]\n[links.P]\ncarrier = "C"\ngears = { p = 20 }\n[states.x]\ninput = "S"\noutput = "Z"', "[states.x]: names no link 'Z'"),
]
BASE = 'name = "t"\n{meshes}\n[links.S]\ngears = {{ s = 20 }}\n[links.C]\n[links.R]\ngears = {{ r = {{ teeth = 60, internal = true }} }}\n'


def _bad_text(case):
    meshes, _, rest = case.partition("\n")
    return BASE.format(meshes=meshes) + rest + "\n"


@pytest.mark.parametrize("case, message", BAD)
def test_a_bad_file_is_one_line_naming_the_file_table_and_key(case, message, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(_bad_text(case))
    with pytest.raises(TrainFileError) as err:
        load_train(path)
    text = str(err.value)
    assert text.startswith(str(path)) and message in text and "\n" not in text, text


@pytest.mark.parametrize("case, message", BAD[:4])
def test_a_bad_file_on_the_command_line_exits_2_and_writes_nothing(case, message, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "bad.toml"
    path.write_text(_bad_text(case))
    before = sorted(p.name for p in tmp_path.iterdir())
    code = main(["trajectory", "--train", str(path), "--omega", "S=1", "--omega", "R=0", "--out", "fig.png"])
    err = capsys.readouterr().err
    assert code == 2 and message in err and err.count("\n") == 1, err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_an_unknown_ready_made_name_lists_the_ready_made_ones():
    with pytest.raises(TrainFileError, match="the ready-made trains are bevel-differential, bevel-epicyclic, double-pinion"):
        load_train("ravignaux")


# --------------------------------------------------------------------------- the cache and the CLI
def test_an_equal_train_built_again_derives_nothing_again(monkeypatch):
    import symkin.kinematics as kin

    first = load_train("ravigneaux")
    first.shift_table()
    calls = []
    real = kin.contact_condition
    monkeypatch.setattr(kin, "contact_condition", lambda *a: calls.append(1) or real(*a))
    again = load_train("ravigneaux")
    assert again is not first and again == first
    table = again.shift_table()
    assert calls == [] and table[0].ratio.rhs == sp.Rational(12, 5)


def test_cli_ratio_speeds_states_and_trains(capsys):
    assert main(["ratio", "--train", "ravigneaux", "--driver", "S1", "--driven", "R", "--fixed", "C", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["train"] == "Ravigneaux" and data["ratio"]["exact"] == "12/5"
    assert main(["speeds", "--train", "ferguson", "--omega", "H=99"]) == 0
    out = capsys.readouterr().out
    assert "omega_S2  = -1   (derived)" in out and "omega_S3  = 99/101" in out
    assert main(["states", "--train", "simpson", "--json"]) == 0
    states = json.loads(capsys.readouterr().out)["states"]
    assert [s["ratio"]["exact"] for s in states] == ["29/12", "17/12", "1", "-12/5"]
    assert main(["trains", "--json"]) == 0
    assert {t["name"] for t in json.loads(capsys.readouterr().out)["trains"]} == set(READY)
    assert main(["ratio", "AA", "--train", "simple", "--driver", "S", "--driven", "C", "--fixed", "R"]) == 2
    assert "not both" in capsys.readouterr().err


def test_a_train_is_a_mechanism_everywhere():
    train = load_train("wolfrom")
    assert isinstance(train, symkin.Mechanism)
    study = symkin.Study(train, ratios=[("S", "R2", ())])
    assert float(study.evaluate({})["i_{SR2}"]) == 76.0


def test_profile_shifted_meshes_with_unknown_teeth_give_willis_ratio():
    # Ferguson's train with tooth numbers left as symbols: the working pitch radii of the shifted meshes,
    # 60 z/(z_p + z), are fractions; the ratio must still be Willis': with s1 held and the arm driving,
    # (w_s2 - w_H)/(0 - w_H) = z_s1/z_s2, so i_H,S2 = z_s2/(z_s2 - z_s1)
    text = _library_text("ferguson")
    for gear, teeth in (("p", 20), ("s1", 100), ("s2", 99), ("s3", 101)):
        text = text.replace(f"{gear} = {teeth} }}", f'{gear} = "z_{gear}" }}')
    train = read_train(text)
    z = {g: sp.Symbol(f"z_{g}", integer=True, positive=True) for g in ("s1", "s2", "s3")}
    assert sp.simplify(train.shift("s2").ratio.rhs - z["s2"] / (z["s2"] - z["s1"])) == 0
    assert sp.simplify(train.shift("s3").ratio.rhs - z["s3"] / (z["s3"] - z["s1"])) == 0
