"""Bevel gears and motion in space, against independent references.

- Bevel trains: Willis' relation for bevel gears worked by hand (the differential's case
  turns at the mean of its side gears; the bevel epicyclic's closed form).
- A base moving in space (the 2009 paper's drill head on a manipulator): a planet particle
  against a sympy.physics.mechanics model (a body frame turned by yaw, pitch and roll, the
  carrier and the planet turning in it), at random rational parameters.
- A point of a bevel pinion against sympy.physics.mechanics (the case turning about N.z,
  the pinion about the case's x axis).
- What is out of scope: one clear error.
"""

from __future__ import annotations

import json
import random

import pytest
import sympy as sp
from sympy.physics import mechanics as me

from symkin import schemes
from symkin import symbols as S
from symkin.cli import main
from symkin.errors import ModelError
from symkin.model import Gear, Link, Mechanism
from symkin.particles import SpaceFrame
from symkin.trains import load_train, read_train


def _close(ours, ref, t, frame_axes, times):
    for tt in times:
        for k, e in enumerate(frame_axes):
            got, want = sp.N(ours[k].subs(S.t, tt), 30), sp.N(ref.dot(e).subs(t, tt), 30)
            assert abs(got - want) < 1e-18 * (1 + abs(want)), (tt, k, got, want)


# --------------------------------------------------------------------------- bevel kinematics by hand
def test_the_differential_case_turns_at_the_mean_of_its_side_gears():
    train = load_train("bevel-differential")
    speeds = train.speeds({"L": S.omega("L"), "R": S.omega("R")})
    assert sp.simplify(speeds["C"] - (S.omega("L") + S.omega("R")) / 2) == 0
    # the pinion spins relative to the case: (omega_L - omega_C) z_L = -omega_P z_P (L above the pinion)
    assert sp.simplify(speeds["P"] + (S.omega("L") - speeds["C"]) * sp.Rational(16, 10)) == 0
    assert [s.ratio.rhs for s in train.shift_table()] == [1, sp.Rational(1, 2)]


@pytest.mark.parametrize("seed", range(3))
def test_a_bevel_epicyclic_by_its_closed_form(seed):
    rng = random.Random(seed)
    zf, zs, zp1, zp2 = (rng.randint(15, 60) for _ in range(4))
    mech = Mechanism(
        links=(Link.frame(Gear.from_teeth("f", zf, module=1, bevel=True, side=1)), Link.central("H"),
               Link.planet("P", Gear.from_teeth("p1", zp1, module=1, bevel=True), Gear.from_teeth("p2", zp2, module=1, bevel=True),
                           carrier="H", axis="radial"),
               Link.central("S", Gear.from_teeth("s", zs, module=1, bevel=True, side=1))),
        meshes=(("f", "p1"), ("s", "p2")),
    )
    # both side gears above the pinion: (omega_S - omega_H)/(omega_F - omega_H) = (z_F z_p2)/(z_p1 z_S), omega_F = 0
    expected = 1 - sp.Rational(zf * zp2, zp1 * zs)
    if expected == 0:
        pytest.skip("these teeth stand the output still")
    assert mech.speeds({"H": 1})["S"] == expected
    assert load_train("bevel-epicyclic").shift("reduce").ratio.rhs == 1 / (1 - sp.Rational(40 * 19, 20 * 36)) == -18


# --------------------------------------------------------------------------- particles in space
@pytest.mark.parametrize("seed", range(3))
def test_a_planet_particle_on_a_base_moving_in_space_against_sympy_mechanics(seed):
    rng = random.Random(seed)
    q = lambda: sp.Rational(rng.randint(-9, 9), rng.randint(1, 5))  # noqa: E731
    r1, r2 = sp.Rational(rng.randint(2, 9)), sp.Rational(rng.randint(1, 6))
    mech = schemes.single_row_AI(radii=(r1, r2, r1 + 2 * r2))
    wH = q() or 1
    t = me.dynamicsymbols._t
    x, y, z = q() * S.t, q() + q() * S.t**2, q() * S.t
    yaw, pitch, roll = q() * S.t, q() * S.t / 7, q() + q() * S.t / 3
    frame = SpaceFrame.euler(x, y, z, yaw=yaw, pitch=pitch, roll=roll)
    a, b, c = q(), q(), q()
    ours = mech.motion({"4": 0, "H": wH}, frame=frame).particle("2", (a, b, c), relative_to="pole")

    w2 = wH * (1 - (r1 + 2 * r2) / r2)  # by hand: the planet rolls in the fixed ring (omega_2 - omega_H) r2 = -omega_H r4
    to_t = {S.t: t}
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Body", [yaw.subs(to_t), pitch.subs(to_t), roll.subs(to_t)], "ZYX")
    H = B.orientnew("H", "Axis", [wH * t, B.z])
    P = B.orientnew("P", "Axis", [w2 * t, B.z])
    O0 = me.Point("N0")
    O0.set_vel(N, 0)
    O = O0.locatenew("O", x.subs(to_t) * N.x + y.subs(to_t) * N.y + z.subs(to_t) * N.z)
    axis = O.locatenew("A", (r1 + r2) * H.x)
    X = axis.locatenew("X", a * P.x + b * P.y + c * B.z)
    rpos = X.pos_from(O0)
    v = rpos.dt(N)
    acc = v.dt(N)
    times = (0, sp.Rational(5, 7), sp.Rational(-3, 2))
    _close(ours.position, rpos, t, (N.x, N.y, N.z), times)
    _close(ours.velocity, v, t, (N.x, N.y, N.z), times)
    _close(ours.acceleration, acc, t, (N.x, N.y, N.z), times)


def test_a_point_of_a_bevel_pinion_against_sympy_mechanics():
    train = load_train("bevel-differential")
    wC, wR = sp.Rational(3, 2), sp.Rational(-1, 3)
    motion = train.motion({"C": wC, "R": wR})
    a, b, c = sp.Rational(8), sp.Rational(-2), sp.Rational(5, 2)
    ours = motion.particle("P", (a, b, c), relative_to="pole")
    # by hand: R below the pinion, (omega_R - omega_C) z_R = +omega_P z_P; the pinion spins about the case's x axis
    wP = (wR - wC) * sp.Rational(16, 10)
    t = me.dynamicsymbols._t
    N = me.ReferenceFrame("N")
    C = N.orientnew("C", "Axis", [wC * t, N.z])
    P = C.orientnew("P", "Axis", [wP * t, C.x])
    O = me.Point("O")
    O.set_vel(N, 0)
    X = O.locatenew("X", a * P.x + b * P.y + c * P.z)
    r = X.pos_from(O)
    v = r.dt(N)
    acc = v.dt(N)
    times = (0, sp.Rational(1, 3), sp.Rational(11, 4))
    _close(ours.position, r, t, (N.x, N.y, N.z), times)
    _close(ours.velocity, v, t, (N.x, N.y, N.z), times)
    _close(ours.acceleration, acc, t, (N.x, N.y, N.z), times)


def test_a_still_space_frame_is_the_plane():
    mech = schemes.single_row_AI(radii=(1, 1, 3))
    flat = mech.motion({"4": 0, "H": 1}).particle("2", (1, 0), relative_to="pole")
    space = mech.motion({"4": 0, "H": 1}, frame=SpaceFrame()).particle("2", (1, 0), relative_to="pole")
    assert list(space.position) == [*flat.position, 0] and list(space.acceleration) == [*flat.acceleration, 0]


# --------------------------------------------------------------------------- files, CLI, errors
def test_a_train_file_with_a_moving_base_draws_in_space(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    text = (load_train("simple").source and "") or ""
    import importlib.resources

    text = (importlib.resources.files("symkin.trains") / "library" / "simple.toml").read_text()
    text += '\n[base]\nz = "10*t"\nyaw = "t/2"\n'
    (tmp_path / "drill.toml").write_text(text)
    train = read_train(text, "drill.toml")
    assert train.base.z == 10 * S.t
    assert main(["trajectory", "--train", "drill.toml", "--omega", "S=1", "--omega", "R=0", "--out", "d.png", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["file"] == "d.png" and (tmp_path / "d.png").stat().st_size > 10_000
    code = main(["animate", "--train", "drill.toml", "--omega", "S=1", "--omega", "R=0", "--out", "d.gif"])
    err = capsys.readouterr().err
    assert code == 2 and "use trajectory, which draws the paths in 3-D" in err and err.count("\n") == 1


@pytest.mark.parametrize("build, message", [
    (lambda: Mechanism((Link.central("C"), Link.planet("P", Gear("p", 5, bevel=True), carrier="C", axis="radial"),
                        Link.central("L", Gear("l", 8))), (("l", "p"),)), "gear l is not a bevel gear"),
    (lambda: Mechanism((Link.central("C"), Link.planet("P", Gear("p", 5, bevel=True), carrier="C", axis="radial"),
                        Link.central("L", Gear("l", 8, bevel=True))), (("l", "p"),)), r"needs side = \+1"),
    (lambda: Mechanism((Link.central("C"), Link.planet("P", Gear("p", 5, bevel=True), carrier="C"),
                        Link.central("L", Gear("l", 8, bevel=True, side=1))), (("l", "p"),)), "neither is"),
    (lambda: Link.planet("P", Gear("p", 5), carrier="C", axis="radial"), "its gears must be bevel gears"),
    (lambda: Mechanism((Link.central("C"), Link.planet("P", Gear("p", 5, bevel=True), carrier="C", axis="radial"),
                        Link.central("L", Gear("l", 8, bevel=True, side=1)), Link.central("R", Gear("r", 9, bevel=True, side=-1))),
                       (("l", "p"), ("r", "p"))), "one pitch cone cannot"),
    (lambda: SpaceFrame(rotation=sp.Matrix([[1, 0, 0], [0, 1, 0], [0, 0, 2]])), "not a rotation"),
])
def test_what_cannot_be_built_is_one_clear_error(build, message):
    with pytest.raises((ModelError, Exception), match=message) as err:
        build()
    assert "\n" not in str(err.value)
