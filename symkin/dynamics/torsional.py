"""Torsional vibration: a purely rotational lumped-parameter model of a train and its natural modes.

Every body is a rotational coordinate: each link about the main axis, and each of a planet's
``count`` copies on its own (the product of the counts for a planet of a planet).  A mesh is a
linear spring along its line of action between the base circles (base radius = reference
radius m z / 2 x cos of the pressure angle: the gears' ``pressure_angle`` in the train file, 20 degrees where
it gives none, or the one given): its deflection is the mesh's contact condition
(:func:`~symkin.kinematics.contact_condition`, the relative motion of the working pitch circles
in the frame of the link that carries both axes) written in turns instead of speeds, times the
cosine of the working pressure angle (:func:`~symkin.dynamics.bodies.working_pressure_angle`;
the pressure angle itself but at a working centre distance), so it is zero in every rigid
motion of the train; its energy is ``k d^2 / 2``.
A link's ``stiffness`` is a shaft holding it to the frame.  A planet's centre moves with its
carrier's coordinate (its mass adds ``m a^2`` there, in the model's position at t = 0).
Brakes hold links; clutches join them into one coordinate.

    >>> from symkin.trains import read_train
    >>> train = read_train('''
    ... module = 1
    ... meshes = [{ gears = ["a", "b"], stiffness = 1e8 }]
    ... [links.A]
    ... gears = { a = 20 }
    ... inertia = 0.01
    ... [links.B]
    ... carrier = "frame"
    ... gears = { b = 40 }
    ... inertia = 0.04
    ... ''')
    >>> modes = natural_modes(train, pressure_angle=0)
    >>> [round(f, 3) for f in modes.frequencies_hz]   # omega^2 = k (r_A^2/J_A + r_B^2/J_B): a rigid mode and one
    [0.0, 225.079]
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin.dynamics.bodies import MILLIMETRE, by_name, carrier_chain, inertia_of, mass_of, working_pressure_angle
from symkin.dynamics.rigid import state_constraints
from symkin.errors import InputError
from symkin.model import FRAME, LinkKind, Mechanism
from symkin.values import as_expr

__all__ = ["torsional_model", "TorsionalModel", "natural_modes", "modes_of", "Modes"]

Body = tuple[str, tuple[int, ...]]
#: The most coordinates whose characteristic polynomial the commands expand in symbols (seven
#: took over a minute for the double-pinion set; six, about a second).
MAX_SYMBOLIC = 6


def mesh_stiffness(mesh: Any) -> sp.Expr:
    """A mesh's stiffness (N/m): as given, else the symbol ``k_<a>_<b>``."""
    return sp.Symbol(f"k_{mesh.a}_{mesh.b}", positive=True) if mesh.stiffness is None else mesh.stiffness


def torsional_model(train: Mechanism, state: Any = None, *, pressure_angle: Any = None,
                    length: Any = MILLIMETRE, values: Mapping[Any, Any] | None = None) -> TorsionalModel:
    """The rotational lumped-parameter model of a train: its coordinates, mass matrix M and stiffness matrix K.

    Parameters
    ----------
    train : Train or Mechanism
        Inertias, planet masses and shaft stiffnesses from its links, mesh stiffnesses from its
        meshes; what is not given is a symbol (``J_<link>``, ``m_<planet>``, ``k_<a>_<b>``; a
        link without a stiffness has no shaft to the frame).
    state : str or State, optional
        A gear state: its brakes hold links, its clutches join them.
    pressure_angle : number, optional
        Radians, for every mesh: base radius = reference radius m z / 2 x cos(pressure angle).  Default: each
        mesh's from its gears' ``pressure_angle`` in the train file (degrees), 20 degrees where it
        gives none.
    length : number
        Metres per model length unit (1/1000: millimetres).
    values : mapping of symbol name to value, optional
        Numbers for the symbols left (``{"J_S": 0.01, "k_s_p": 5e8}``).
    """
    held, joined, _ = state_constraints(train, state)
    length = as_expr(length, what="length (metres per model length unit)")
    bodies, chains = _bodies(train, held, joined)
    coordinates = tuple(dict.fromkeys(v for v in bodies.values() if v != 0))
    if not coordinates:
        raise InputError("every link is held: the train has no coordinate to vibrate; release a brake")
    rates = {c: sp.Symbol(f"d{c.name}") for c in coordinates}

    def turn(link: str, index: tuple[int, ...]) -> sp.Expr:
        if link == FRAME:
            return sp.Integer(0)
        return bodies[(link, index[: len(chains[link])])]

    T = _kinetic_energy(train, bodies, rates, turn, chains, length)
    V = _mesh_energy(train, turn, chains, pressure_angle, length)
    for L in train.moving_links:  # the shafts holding links to the frame
        if L.stiffness is not None:
            V += L.stiffness * turn(L.name, ()) ** 2 / 2
    u = [rates[c] for c in coordinates]
    T, V = by_name(T, values), by_name(V, values)
    M = sp.ImmutableMatrix(len(u), len(u), lambda i, j: sp.expand(sp.diff(T, u[i], u[j])))
    K = sp.ImmutableMatrix(len(u), len(u), lambda i, j: sp.expand(sp.diff(V, coordinates[i], coordinates[j])))
    return TorsionalModel(train, tuple(c.name.removeprefix("varphi_") for c in coordinates), tuple(coordinates), M, K)


def _bodies(train: Mechanism, held: dict[str, Any], joined: Any) -> tuple[dict[Body, Any], dict[str, Any]]:
    """Every body (a link, or one copy of a planet) and its coordinate: 0 where a brake holds it,
    one shared coordinate for the links a clutch joins, one for each copy of a planet; and each
    link's chain of carriers."""
    parent = {L.name: L.name for L in train.moving_links}

    def root(n: str) -> str:
        while parent[n] != n:
            n = parent[n]
        return n

    for a, b in joined:
        for n in (a, b):
            if n != FRAME and train.link(n).kind is LinkKind.PLANET:
                raise InputError(f"a clutch joins planet {n}; the torsional model joins links about the main axis only")
        if FRAME in (a, b):
            held[a if b == FRAME else b] = 0
        else:
            parent[root(a)] = root(b)
    held_roots = {root(n) for n in held}
    bodies: dict[Body, Any] = {}
    chains = {L.name: carrier_chain(train, L.name) for L in train.moving_links}
    for L in train.moving_links:
        chain = chains[L.name]
        for index in itertools.product(*(range(arm.count) for arm in chain)):
            if root(L.name) in held_roots:
                bodies[(L.name, index)] = sp.Integer(0)
            elif not chain:
                bodies[(L.name, index)] = S.angle(root(L.name))
            else:
                label = L.name + ("" if all(arm.count == 1 for arm in chain) else "_" + "".join(str(i + 1) for i in index))
                bodies[(L.name, index)] = S.angle(label)
    return bodies, chains


def _kinetic_energy(train: Mechanism, bodies: Mapping[Body, Any], rates: Mapping[sp.Symbol, sp.Symbol],
                    turn: Callable[[str, tuple[int, ...]], sp.Expr], chains: Mapping[str, Any], length: sp.Expr) -> sp.Expr:
    """The kinetic energy: the bodies' spins, and the planets' centres moving with their carriers'
    coordinates (each copy at its place at t = 0)."""
    T = sp.Integer(0)
    for (link, index), theta in bodies.items():
        L = train.link(link)
        rate = rates.get(theta, sp.Integer(0))
        J = inertia_of(train, link)
        if L.axis == "radial":
            assert L.carrier is not None
            carried = rates.get(turn(L.carrier, index), sp.Integer(0))
            T += J * (rate ** 2 + carried ** 2 / 2) / 2
        else:
            T += J * rate ** 2 / 2
        chain = chains[link]
        if not chain:
            continue
        vx = vy = offset = sp.Integer(0)
        for k, arm in enumerate(chain):
            w = rates.get(turn(arm.carrier, index[:k]), sp.Integer(0))
            offset += 2 * sp.pi * sp.Integer(index[k]) / arm.count  # a copy turned with the copy carrying it
            psi = arm.angle + offset
            vx -= w * arm.length * length * sp.sin(psi)
            vy += w * arm.length * length * sp.cos(psi)
        T += mass_of(train, link) * (vx ** 2 + vy ** 2) / 2
    return T


def _mesh_energy(train: Mechanism, turn: Callable[[str, tuple[int, ...]], sp.Expr], chains: Mapping[str, Any],
                 pressure_angle: Any, length: sp.Expr) -> sp.Expr:
    """The potential energy of the mesh springs: one for each copy of the deepest planet of a mesh,
    its deflection the mesh's contact condition in turns along the line of action."""
    from symkin.kinematics import contact_condition

    V = sp.Integer(0)
    for mesh in train.meshes:
        line = sp.cos(working_pressure_angle(train, mesh, pressure_angle)) * length  # pitch-line turns to the line of action
        geo = train.mesh_geometry(mesh)
        eq = contact_condition(train, mesh)
        relative = sp.expand(eq.lhs - eq.rhs)
        names = [n for n in dict.fromkeys((geo.link_a.name, geo.link_b.name, geo.holder)) if n != FRAME]
        deepest = max(names, key=lambda n: (len(chains[n]), math.prod(arm.count for arm in chains[n])))
        for index in itertools.product(*(range(arm.count) for arm in chains[deepest])):
            d = sp.Integer(0)
            for n in names:
                d += relative.coeff(S.omega(n)) * turn(n, _index_for(chains, n, deepest, index))
            V += mesh_stiffness(mesh) * (line * d) ** 2 / 2
    return V


def _index_for(chains: Mapping[str, Any], link: str, deepest: str, index: tuple[int, ...]) -> tuple[int, ...]:
    """The copy of ``link`` that the copy ``index`` of ``deepest`` meets: the same copy at each level
    where the two chains hold planets of equal counts, the only one where ``link``'s count is 1."""
    out = []
    for k, arm in enumerate(chains[link]):
        other = chains[deepest][k]
        if arm.count == other.count:
            out.append(index[k])
        elif arm.count == 1:
            out.append(0)
        else:
            raise InputError(f"planets {arm.planet} ({arm.count}) and {other.planet} ({other.count}) mesh but differ "
                             "in count: which copy meets which is unknown; give them equal counts")
    return tuple(out)


@dataclass(frozen=True)
class TorsionalModel:
    """``M theta'' + K theta = 0`` of a train (:func:`torsional_model`): the coordinates by body
    (``P_2``: the second copy of planet P) and the matrices, exact."""

    train: Mechanism
    names: tuple[str, ...]
    coordinates: tuple[sp.Symbol, ...]
    mass_matrix: sp.ImmutableMatrix
    stiffness_matrix: sp.ImmutableMatrix
    #: What the model is, as ``symkin modes`` names it.
    kind = "torsional model"
    unit = "rad"

    def characteristic_polynomial(self, variable: sp.Symbol | None = None) -> sp.Expr:
        """``det(K - lambda M)`` in ``lambda`` = omega^2 (rad^2/s^2), exact."""
        lam = variable if variable is not None else sp.Symbol("lambda")
        return sp.expand((self.stiffness_matrix - lam * self.mass_matrix).det(method="berkowitz"))


def natural_modes(train: Mechanism, state: Any = None, *, pressure_angle: Any = None, length: Any = MILLIMETRE,
                  values: Mapping[Any, Any] | None = None, rigid_tolerance: float = 1e-9) -> Modes:
    """Natural frequencies (Hz) and mode shapes of a train's torsional model (:func:`torsional_model`).

    With every value a number, SciPy's ``eigh`` on K and M (frequencies below
    ``rigid_tolerance`` x the largest are rigid-body modes, 0); with symbols left, the
    characteristic polynomial only (``frequencies_hz`` is None).  ``values`` gives numbers to
    symbols, as for :func:`torsional_model`.

    >>> from symkin.trains import load_train
    >>> J = {"J_S": 0.01, "J_C": 0.05, "J_P": 0.002, "m_P": 0.5, "k_s_p": 5e8, "k_p_r": 5e8}
    >>> [round(f) for f in natural_modes(load_train("simple"), "low", values=J).frequencies_hz]
    [0, 968, 1269, 1269, 1384]
    """
    model = torsional_model(train, state, pressure_angle=pressure_angle, length=length, values=values)
    return modes_of(model, rigid_tolerance)


def modes_of(model: TorsionalModel, rigid_tolerance: float = 1e-9) -> Modes:
    """The natural frequencies and mode shapes of a model's exact M and K (SciPy's ``eigh``; the
    characteristic polynomial only, ``frequencies_hz`` None, where symbols are left)."""
    M, K = model.mass_matrix, model.stiffness_matrix
    if M.free_symbols or K.free_symbols:
        return Modes(model, None, None)
    import numpy as np
    from scipy.linalg import eigh

    Mf = np.array(M.evalf(30).tolist(), dtype=float)
    Kf = np.array(K.evalf(30).tolist(), dtype=float)
    if np.linalg.eigvalsh(Mf).min() <= 0:
        raise InputError("the mass matrix is singular: a body has no inertia; give every link an inertia above 0")
    lam, vectors = eigh(Kf, Mf)
    top = max(abs(lam).max(), 1.0)
    lam = np.where(abs(lam) <= rigid_tolerance * top, 0.0, lam)
    if lam.min() < 0:
        raise InputError("the stiffness matrix is not positive semidefinite; check the stiffnesses")
    freqs = tuple(float(math.sqrt(x) / (2 * math.pi)) for x in lam)
    shapes = []
    for k in range(len(freqs)):
        v = vectors[:, k]
        big = v[np.argmax(abs(v))]
        shapes.append(tuple(float(x) for x in v / big))
    return Modes(model, freqs, tuple(shapes))


@dataclass(frozen=True)
class Modes:
    """Natural frequencies (Hz, ascending; rigid-body modes 0) and mode shapes (by coordinate,
    the largest entry 1) of a :class:`TorsionalModel`; ``None`` where symbols are left."""

    model: TorsionalModel
    frequencies_hz: tuple[float, ...] | None
    shapes: tuple[tuple[float, ...], ...] | None

    def to_json(self) -> dict[str, Any]:
        """The coordinates, M and K (exact), the frequencies and the mode shapes by body."""
        from symkin._util.jsonout import exact_json

        def cell(v: sp.Expr) -> Any:
            return exact_json(v) if v.is_number else {"exact": str(v), "float": None}

        M, K = self.model.mass_matrix, self.model.stiffness_matrix
        out: dict[str, Any] = {
            "train": getattr(self.model.train, "name", ""),
            "coordinates": list(self.model.names),
            "mass_matrix": [[cell(v) for v in M.row(i)] for i in range(M.rows)],
            "stiffness_matrix": [[cell(v) for v in K.row(i)] for i in range(K.rows)],
            "frequencies_hz": list(self.frequencies_hz) if self.frequencies_hz is not None else None,
            "mode_shapes": [dict(zip(self.model.names, s)) for s in self.shapes] if self.shapes is not None else None,
        }
        if self.frequencies_hz is None:
            out["characteristic_polynomial"] = str(self.model.characteristic_polynomial()) \
                if len(self.model.names) <= MAX_SYMBOLIC else None
        return out

    def text(self) -> str:
        """The modes as ``symkin modes`` prints them."""
        name = getattr(self.model.train, "name", "") or "train"
        lines = [f"{name}: {self.model.kind}, coordinates {', '.join(self.model.names)} [{self.model.unit}]"]
        if self.frequencies_hz is None:
            symbols = sorted(map(str, self.model.mass_matrix.free_symbols | self.model.stiffness_matrix.free_symbols))
            lines.append(f"symbols left ({', '.join(symbols)}): give inertias, masses and stiffnesses in the file for "
                         "numbers; det(K - lambda M) =")
            if len(self.model.names) > MAX_SYMBOLIC:
                lines[-1] = lines[-1].removesuffix(" det(K - lambda M) =") + f" {len(self.model.names)} coordinates " \
                    f"are too many for the determinant in symbols (at most {MAX_SYMBOLIC}); M and K are in --json"
                return "\n".join(lines)
            poly = str(self.model.characteristic_polynomial())
            lines.append(f"  {poly}" if len(poly) <= 2000 else f"  ({len(poly)} characters: --json gives it)")
            return "\n".join(lines)
        width = max(len(n) for n in self.model.names)
        lines.append("mode  frequency [Hz]  shape (" + ", ".join(self.model.names) + ")")
        for k, (f, s) in enumerate(zip(self.frequencies_hz, self.shapes or ())):
            lines.append(f"{k + 1:>4}  {f:>14.6g}  " + "  ".join(f"{x:+.4f}".rjust(max(width, 7)) for x in s))
        return "\n".join(lines)
