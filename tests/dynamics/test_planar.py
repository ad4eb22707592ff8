"""symkin.dynamics.planar against Lin and Parker's (1999) printed Table 2 (Table 1's parameters),
Cooley and Parker's (2012) printed frequencies, the mode structure Lin and Parker proved, rigid
motions, and, with stiff bearings, the purely rotational model (symkin.dynamics.torsional)."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest
import sympy as sp

from symkin.dynamics import natural_modes, planar_geometry, planar_model, planar_modes
from symkin.dynamics.bodies import carrier_chain
from symkin.errors import InputError
from symkin.trains import read_train

# Lin, J. and Parker, R. G., "Analytical characterization of the unique properties of planetary
# gear free vibration", J. Vib. Acoust. 121 (1999) 316-321, Table 1, as transcribed (citing the
# paper and Lin's thesis, Table C.1) in gfsReboucas/Drivetrain-python, tests/test_lin_parker_1999.py:
# masses (kg), I / r^2 (kg), base diameters (mm; the carrier's, of the pins' circle), stiffnesses
# (N/m; the ring's torsional k_ru in N/m, on u = r theta), pressure angle 24.6 degrees.
LP_MASS = {"sun": 0.4, "ring": 2.35, "carrier": 5.43, "planet": 0.66}
LP_I_R2 = {"sun": 0.39, "ring": 3.0, "carrier": 6.29, "planet": 0.61}
LP_DIAMETER = {"sun": 77.4, "ring": 275.0, "carrier": 176.8, "planet": 100.3}
# Table 2, as transcribed there: (rotational, translational (multiplicity 2), planet modes) in Hz.
LP_TABLE_2 = {
    3: ([0.0, 1475.7, 1930.3, 2658.3, 7462.8, 11775.3], [743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9], []),
    4: ([0.0, 1536.6, 1970.6, 2625.7, 7773.6, 13071.1], [727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6],
        [1808.2, 5963.8, 6981.7]),
    5: ([0.0, 1567.4, 2006.1, 2614.8, 8065.4, 14253.1], [710.0, 1072.0, 1888.1, 2425.3, 7382.4, 11172.3],
        [1808.2, 5963.8, 6981.7]),
}


def _radius(body: str) -> sp.Expr:
    return sp.Rational(str(LP_DIAMETER[body])) / 2000


def _lin_parker(count: int) -> dict:
    r = {b: _radius(b) for b in LP_MASS}
    return dict(
        base_radii={b: r[b] for b in ("sun", "ring", "planet")}, carrier_radius=r["carrier"],
        pressure_angle=sp.pi * sp.Rational(246, 1800), masses=LP_MASS,
        inertias={b: sp.Rational(str(LP_I_R2[b])) * r[b] ** 2 for b in LP_MASS},
        bearings={b: 10 ** 8 for b in LP_MASS}, mesh_stiffness=(5 * 10 ** 8, 5 * 10 ** 8),
        torsional={"ring": 10 ** 9 * r["ring"] ** 2})


def _kinds(modes, count: int, tol: float = 1e-6) -> list[str]:
    """Each mode's kind by its shape: planet (sun, ring, carrier still), rotational (the central
    members only turn), translational (they only translate)."""
    kinds = []
    for shape in modes.shapes:
        v = np.array(shape)
        central, turns = v[:9], v[[2, 5, 8]]
        moves = np.delete(central, [2, 5, 8])
        if np.abs(central).max() < tol:
            kinds.append("planet")
        elif np.abs(moves).max() < tol:
            kinds.append("rotational")
        elif np.abs(turns).max() < tol:
            kinds.append("translational")
        else:
            kinds.append("mixed")
    return kinds


@pytest.mark.parametrize("count", [3, 4, 5])
def test_lin_and_parkers_table_2(count):
    modes = planar_modes(count, **_lin_parker(count))
    kinds = _kinds(modes, count)
    derived = {k: sorted(round(f, 1) for f, kind in zip(modes.frequencies_hz, kinds) if kind == k)
               for k in ("rotational", "translational", "planet")}
    rotational, translational, planet = LP_TABLE_2[count]
    printed = {"rotational": rotational, "translational": sorted(translational * 2), "planet": sorted(planet * (count - 3))}
    assert Counter(kinds) == {"rotational": 6, "translational": 12, **({"planet": 3 * (count - 3)} if count > 3 else {})}
    differ = {(k, p, d) for k in printed for p, d in zip(printed[k], derived[k]) if p != d}
    if count == 4:
        # the verdict (docs/dynamics.md): every printed digit matches for three and five planets with
        # the same parameters; for four, three entries differ in the last printed digits, by 0.05 %
        # at most (727.3 printed 727.0, 1091.2 printed 1091.0, 1536.5 printed 1536.6)
        assert differ == {("translational", 727.0, 727.3), ("translational", 1091.0, 1091.2),
                          ("rotational", 1536.6, 1536.5)}
        assert all(abs(d - p) / p < 5e-4 for _, p, d in differ)
    else:
        assert differ == set()


@pytest.mark.parametrize("count", [3, 4, 5])
def test_cooley_and_parkers_frequencies_at_rest(count):
    # Cooley, C. G. and Parker, R. G., "Vibration properties of high-speed planetary gears with
    # gyroscopic effects", J. Vib. Acoust. 134 (2012) 061014, Table 1's parameters and its
    # frequencies at carrier speed 0, omega / sqrt(k_p / m_p), as transcribed in
    # gfsReboucas/Drivetrain-python, tests/test_lin_parker_1999.py (four significant digits).
    printed = {
        3: [0.9296, 1.090, 1.358, 1.931, 5.566, 7.741, *[0.7432, 1.018, 1.265, 1.487, 4.976, 6.282] * 2],
        4: [0.9077, 1.046, 1.317, 2.013, 5.809, 8.383, *[0.7199, 1.001, 1.317, 1.481, 5.153, 6.488] * 2,
            0.9617, 4.320, 5.672],
        5: [0.8802, 1.019, 1.281, 2.090, 6.030, 8.986, *[0.6992, 0.9863, 1.344, 1.496, 5.317, 6.693] * 2,
            *[0.9617, 4.320, 5.672] * 2],
    }[count]
    r = {"sun": 55.75, "ring": 109.7, "carrier": 88.6, "planet": 27.0}  # base diameters, mm
    r = {b: sp.Rational(str(d)) / 2000 for b, d in r.items()}
    i_r2 = {"sun": 1.75, "ring": 8.09, "carrier": 6.80, "planet": 1.25}
    modes = planar_modes(
        count, base_radii={b: r[b] for b in ("sun", "ring", "planet")}, carrier_radius=r["carrier"],
        pressure_angle=sp.pi / 9, masses={"sun": 3, "ring": 7.64, "carrier": 12, "planet": 1.86},
        inertias={b: sp.Rational(str(i_r2[b])) * r[b] ** 2 for b in r},
        bearings={"sun": 2e7, "ring": 1e8, "carrier": 5e7, "planet": 1e7}, mesh_stiffness=(1e8, 1e8),
        torsional={"sun": 2e7 * r["sun"] ** 2, "ring": 1e8 * r["ring"] ** 2, "carrier": 1e8 * r["carrier"] ** 2})
    scale = 2 * math.pi / math.sqrt(1e7 / 1.86)
    off = []
    for p, f in zip(sorted(printed), modes.frequencies_hz):
        last = 10.0 ** (math.floor(math.log10(p)) - 3)  # the printed value's last digit
        assert abs(f * scale - p) <= 0.6 * last
        if abs(f * scale - p) > 0.5 * last:
            off.append(p)
    # every value rounds to the printed one but 1.046 (derived 1.045497), 2.013 (2.012490) and
    # 1.281 (1.280460): 0.54 thousandths at most, at the rounding boundary
    assert off == {3: [], 4: [1.046, 2.013], 5: [1.281]}[count]


def test_rigid_motions_store_no_energy():
    # with radii of one tooth geometry (r_c cos(alpha) = r_bs + r_bp = r_br - r_bp) and no
    # bearings or torsional springs, the whole set turning as one, and translating as one, is free
    a, rs, rp = sp.symbols("alpha r_s r_p", positive=True)
    k = sp.symbols("k_sp k_rp", positive=True)
    one = {"sun": 1, "ring": 1, "carrier": 1, "planet": 1}
    model = planar_model(4, base_radii={"sun": rs * sp.cos(a), "ring": (rs + 2 * rp) * sp.cos(a),
                                        "planet": rp * sp.cos(a)},
                         carrier_radius=rs + rp, pressure_angle=a, masses=one, inertias=one,
                         bearings=dict.fromkeys(one, 0), mesh_stiffness=k)
    turn = [0, 0, 1] * 3 + [0, rs + rp, 1] * 4
    assert sp.simplify(model.stiffness_matrix * sp.Matrix(turn)) == sp.zeros(21, 1)
    psi = [2 * sp.pi * n / 4 for n in range(4)]
    slide = [1, 0, 0] * 3 + [c for p in psi for c in (sp.cos(p), -sp.sin(p), 0)]
    assert sp.simplify(model.stiffness_matrix * sp.Matrix(slide)) == sp.zeros(21, 1)
    assert model.stiffness_matrix == model.stiffness_matrix.T


SIMPLE = """
module = 2
meshes = [{ gears = ["s", "p"], stiffness = 5e8 }, { gears = ["p", "r"], stiffness = 6e8 }]
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
"""


def test_stiff_bearings_give_the_rotational_model():
    # the geometry from symkin's assembly of the train (pitch radii x cos 20 degrees, the planets'
    # arm and places), read here by hand and by planar_geometry; bearings a million times stiffer
    # than the meshes leave the rotational model
    train = read_train(SIMPLE)
    alpha = sp.pi / 9
    radius = {b: train.gear(g).radius / 1000 for b, g in (("sun", "s"), ("ring", "r"), ("planet", "p"))}
    arm = carrier_chain(train, "P")[0]
    geometry = planar_geometry(train)
    assert geometry["planets"] == [arm.angle + 2 * sp.pi * n / 3 for n in range(3)] == [0, 2 * sp.pi / 3, 4 * sp.pi / 3]
    assert geometry["base_radii"] == {b: r * sp.cos(alpha) for b, r in radius.items()}
    assert geometry["carrier_radius"] == sp.Rational(48, 1000) == arm.length / 1000
    assert geometry["inertias"] == {"sun": sp.Rational(1, 100), "ring": sp.Rational(1, 10), "carrier": sp.Rational(1, 20),
                                    "planet": sp.Rational(1, 500)}
    stiff = 10 ** 14
    modes = planar_modes(**geometry, masses={"sun": 1, "ring": 3, "carrier": 2, "planet": 0.5},
                         bearings=dict.fromkeys(("sun", "ring", "carrier", "planet"), stiff), mesh_stiffness=(5e8, 6e8))
    rotational = natural_modes(train).frequencies_hz
    assert len(rotational) == 6
    assert modes.frequencies_hz[:6] == pytest.approx(rotational, rel=1e-5, abs=1e-3)
    assert modes.frequencies_hz[6] > 100 * rotational[-1]


def test_bad_input_is_one_line():
    geometry = _lin_parker(3)
    with pytest.raises(InputError, match="give the planet's"):
        planar_model(3, **{**geometry, "masses": {"sun": 1, "ring": 1, "carrier": 1}})
    with pytest.raises(InputError, match="unknown bodies moon"):
        planar_model(3, **{**geometry, "bearings": {**geometry["bearings"], "moon": 1}})
    with pytest.raises(InputError, match="turns freely"):
        planar_model(3, **{**geometry, "torsional": {"planet": 1}})
    with pytest.raises(InputError, match="at least one planet"):
        planar_model(0, **geometry)
    with pytest.raises(InputError, match="pairs"):
        planar_model(3, **{**geometry, "mesh_stiffness": (1,)})
    with pytest.raises(InputError, match="name the planet"):
        planar_geometry(read_train(SIMPLE.replace("[links.R]", "[links.Q]\ncarrier = \"C\"\ngears = { q = 10 }\n[links.R]")))
    with pytest.raises(InputError, match="two suns"):
        planar_geometry(read_train(SIMPLE.replace("r = { teeth = 72, internal = true }", "r = 24")))


def test_planar_geometry_takes_the_train_files_pressure_angle():
    train = read_train("""
module = 2
meshes = [["s", "p"], ["p", "r"]]
[links.S]
gears = { s = { teeth = 24, pressure_angle = 25 } }
[links.C]
[links.P]
carrier = "C"
count = 3
gears = { p = { teeth = 24, pressure_angle = 25 } }
[links.R]
gears = { r = { teeth = 72, internal = true, pressure_angle = 25 } }
""")
    g = planar_geometry(train)
    # base radius = m z cos(alpha) / 2, in metres, by hand
    expected = {b: z * math.cos(math.radians(25)) / 1000 for b, z in (("sun", 24), ("planet", 24), ("ring", 72))}
    assert {b: float(r) for b, r in g["base_radii"].items()} == pytest.approx(expected, rel=1e-15)
    assert float(g["pressure_angle"]) == pytest.approx(math.radians(25), rel=1e-15)
