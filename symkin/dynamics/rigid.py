"""Rigid-body equations of motion of any train, in closed form: ``M(q) q'' = f``.

Every link's speed is a linear law of the independent speeds (the engine's
:func:`~symkin.kinematics.solve_speeds`, brakes and clutches of a state included), so the
kinetic energy is a quadratic form in them (:mod:`symkin.dynamics.bodies`); Lagrange's
equations give the generalised mass matrix, and the torques applied to links give the
generalised forces by virtual power (ideal meshes: no losses).

    >>> from symkin.trains import load_train
    >>> eom = equations_of_motion(load_train("simple"), state="low")
    >>> eom.coordinates
    ('S',)
    >>> eom.mass_matrix[0, 0]
    J_C/16 + 3*J_P/4 + J_S + 27*m_P/250000
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin._util.jsonout import exact_json
from symkin.dynamics.bodies import (
    MILLIMETRE,
    angles_of,
    base_motion,
    by_name,
    link_speeds,
    moving_base_kinetic_energy,
    multiplicity,
    rigid_kinetic_energy,
)
from symkin.errors import InputError
from symkin.model import FRAME, Mechanism
from symkin.values import as_expr

__all__ = ["equations_of_motion", "EquationsOfMotion", "Simulation", "state_constraints"]


def state_constraints(mech: Mechanism, state: Any) -> tuple[dict[str, Any], tuple[tuple[str, str], ...], Any]:
    """The held links (speed 0), the joined pairs and the state object of a train's gear state (or none)."""
    if state is None:
        return {}, (), None
    if not hasattr(mech, "state"):
        raise InputError("a state is a train's ([states.NAME] of a train file); this mechanism has none")
    st = mech.state(state) if isinstance(state, str) else state
    held = {mech.link(b).name: 0 for b in st.brakes if mech.link(b).name != FRAME}
    joined = tuple((mech.link(a).name, mech.link(b).name) for a, b in st.clutches)
    return held, joined, st


def _coordinates(mech: Mechanism, held: Mapping[str, Any], joined: Any, st: Any, coordinates: Any) -> tuple[str, ...]:
    from symkin.kinematics import kinematic_system

    if coordinates is not None:
        if isinstance(coordinates, str) or not isinstance(coordinates, Sequence):
            raise InputError(f"coordinates are a list of link names, got {coordinates!r}")
        names = tuple(mech.link(c).name for c in coordinates)
        if len(set(names)) != len(names):
            raise InputError(f"a link is named twice among the coordinates {', '.join(names)}; name each once")
        for n in names:
            if n == FRAME or n in held:
                raise InputError(f"link {n} does not move{' in this state' if n in held else ''}; choose moving links "
                                 "as coordinates")
        return names
    if st is not None:
        return (mech.link(st.input).name,)
    return tuple(kinematic_system(mech).admissible_choice())


def equations_of_motion(train: Mechanism, state: Any = None, coordinates: Sequence[str] | None = None,
                        torques: Mapping[str, Any] | None = None, *, length: Any = MILLIMETRE,
                        values: Mapping[Any, Any] | None = None, base: bool = True) -> EquationsOfMotion:
    """The rigid-body equations of motion ``M q'' = f`` of a train, exact and symbolic.

    Parameters
    ----------
    train : Train or Mechanism
        Inertias and planet masses from its links (``inertia``, ``mass``); a link without
        one gets the symbol ``J_<link>`` (``m_<planet>``).
    state : str or State, optional
        A gear state: its brakes hold links, its clutches join them.
    coordinates : sequence of link names, optional
        The independent coordinates (their turns ``varphi`` and speeds ``omega``).  Default:
        the state's input, or else the fewest links that fix the motion.
    torques : mapping of link name to torque, optional
        External torques (N m) on links, about their axes (on each body of a planet): numbers,
        symbols, expressions (of ``t`` too) or pint quantities.
    length : number
        Metres per model length unit: 1/1000 for a train file's millimetres (the default),
        1 for a model in metres.
    values : mapping of symbol name to value, optional
        Numbers for the symbols of mass properties and torques (``{"J_C": 0.05}``).
    base : bool
        Take the base's prescribed motion (a train's ``[base]``: O's position in model lengths,
        the yaw, pitch and roll) into the kinetic energy, as the motion of a non-inertial frame
        (True, the default); False takes the frame as still.

    Returns
    -------
    EquationsOfMotion

    Examples
    --------
    >>> from symkin.trains import load_train
    >>> eom = equations_of_motion(load_train("simple"), coordinates=["S", "R"], torques={"S": 1})
    >>> eom.forcing.T
    Matrix([[1, 0]])
    """
    held, joined, st = state_constraints(train, state)
    coords = _coordinates(train, held, joined, st, coordinates)
    length = as_expr(length, what="length (metres per model length unit)")
    known = {**held, **{c: S.omega(c) for c in coords}}
    speeds = link_speeds(train, known, joined)
    angles = angles_of(speeds, coords)
    moving = base_motion(getattr(train, "base", None), length) if base else None
    if moving is None:
        T = rigid_kinetic_energy(train, speeds, angles, length)
    else:
        T = moving_base_kinetic_energy(train, speeds, angles, length, *moving)
    T = sp.expand(by_name(T, values))
    u = [S.omega(c) for c in coords]
    q = [S.angle(c) for c in coords]
    M = sp.ImmutableMatrix(len(u), len(u), lambda i, j: sp.factor_terms(sp.expand(sp.diff(T, u[i], u[j]))))
    applied = {}
    for name, value in (torques or {}).items():
        link = train.link(name).name
        if link == FRAME:
            raise InputError("a torque on the frame does no work; apply torques to moving links")
        if link in applied:
            raise InputError(f"the torque on link {link} is given twice; give it once")
        applied[link] = by_name(as_expr(value, what=f"torque on link {link}", unit="N*m"), values)
    Q = [sp.expand(sum((multiplicity(train, n) * tau * sp.diff(speeds[n], ui) for n, tau in applied.items()),
                       sp.Integer(0))) for ui in u]
    dTdu = [sp.diff(T, ui) for ui in u]
    forcing = []
    for i in range(len(u)):
        coriolis = sum((sp.diff(dTdu[i], qj) * uj for qj, uj in zip(q, u)), sp.diff(dTdu[i], S.t))
        forcing.append(sp.factor_terms(sp.expand(Q[i] + sp.diff(T, q[i]) - coriolis)))
    return EquationsOfMotion(train, st, coords, tuple(q), tuple(u), dict(speeds), T, M,
                             sp.ImmutableMatrix(forcing), sp.ImmutableMatrix(Q), dict(applied), length)


@dataclass(frozen=True)
class EquationsOfMotion:
    """``M(q) q'' = f(q, q', t)`` of a train (:func:`equations_of_motion`).

    Attributes
    ----------
    coordinates : tuple of str
        The links whose turns are the generalised coordinates, in M's order.
    angles, speeds_symbols : tuple of Symbol
        ``varphi_<link>`` and ``omega_<link>`` of each coordinate.
    speeds : dict
        Every moving link's speed in terms of the coordinates' speeds.
    kinetic_energy : sympy expression
    mass_matrix : sympy ImmutableMatrix
    forcing : sympy ImmutableMatrix
        The right-hand side: generalised forces, less the velocity terms of a mass matrix that
        depends on the configuration (a single planet carrying planets).
    generalised_forces : sympy ImmutableMatrix
        The applied torques' share: sum over links of torque * d omega_link / d omega_coordinate.
    """

    train: Mechanism
    state: Any
    coordinates: tuple[str, ...]
    angles: tuple[sp.Symbol, ...]
    speeds_symbols: tuple[sp.Symbol, ...]
    speeds: dict[str, sp.Expr]
    kinetic_energy: sp.Expr
    mass_matrix: sp.ImmutableMatrix
    forcing: sp.ImmutableMatrix
    generalised_forces: sp.ImmutableMatrix
    torques: dict[str, sp.Expr]
    length: sp.Expr
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    @property
    def accelerations(self) -> sp.ImmutableMatrix:
        """``q'' = M^-1 f`` in closed form (``epsilon`` of each coordinate)."""
        if "acc" not in self._cache:
            M, f = sp.Matrix(self.mass_matrix), sp.Matrix(self.forcing)
            if M.det() == 0:
                raise InputError("the mass matrix is singular: give the links inertias (a train of massless links "
                                 "has no accelerations)")
            self._cache["acc"] = sp.ImmutableMatrix(M.LUsolve(f).applyfunc(sp.cancel))
        return self._cache["acc"]

    @property
    def equations(self) -> tuple[sp.Eq, ...]:
        """One equation per coordinate: ``sum_j M_ij epsilon_j = f_i``."""
        eps = sp.Matrix([S.epsilon(c) for c in self.coordinates])
        lhs = self.mass_matrix * eps
        return tuple(sp.Eq(lhs[i], self.forcing[i], evaluate=False) for i in range(len(self.coordinates)))

    def latex(self) -> str:
        """The coordinates, M, f and the equations as LaTeX (an ``align*`` body).

        >>> from symkin.trains import load_train
        >>> print(equations_of_motion(load_train("simple"), state="low").latex().splitlines()[0])
        \\mathbf{q} &= \\left[\\begin{matrix}\\varphi_{S}\\end{matrix}\\right] \\\\
        """
        q = sp.Matrix(self.angles)
        lines = [rf"\mathbf{{q}} &= {sp.latex(q)} \\",
                 rf"T &= {sp.latex(self.kinetic_energy)} \\",
                 rf"\mathbf{{M}} &= {sp.latex(self.mass_matrix)} \\",
                 rf"\mathbf{{f}} &= {sp.latex(self.forcing)} \\"]
        lines += [rf"{sp.latex(e.lhs)} &= {sp.latex(e.rhs)} \\" for e in self.equations]
        lines[-1] = lines[-1].removesuffix(r" \\")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """Coordinates, mass matrix, forcing and (when they are numbers) accelerations, as ``{exact, float}``."""
        acc: Any = None
        if all(v.is_number for v in self.forcing) and all(v.is_number for v in self.mass_matrix):
            acc = [exact_json(a) for a in self.accelerations]
        return {
            "train": getattr(self.train, "name", ""),
            "state": self.state.name if self.state is not None else None,
            "coordinates": list(self.coordinates),
            "kinetic_energy": str(self.kinetic_energy),
            "mass_matrix": [[_value(v) for v in self.mass_matrix.row(i)] for i in range(self.mass_matrix.rows)],
            "forcing": [_value(v) for v in self.forcing],
            "accelerations": acc,
        }

    def text(self) -> str:
        """The equations as ``symkin dynamics`` prints them."""
        name = getattr(self.train, "name", "") or "train"
        where = f", state {self.state.name}" if self.state is not None else ""
        lines = [f"{name}{where}: M q'' = f, coordinates q = ({', '.join(str(a) for a in self.angles)}) [rad], "
                 "SI units (kg m^2, N m)", f"T = {self.kinetic_energy}", "M ="]
        for i in range(self.mass_matrix.rows):
            lines.append("  [" + ", ".join(_show(v) for v in self.mass_matrix.row(i)) + "]")
        lines.append("f = [" + ", ".join(_show(v) for v in self.forcing) + "]")
        js = self.to_json()
        if js["accelerations"] is not None:
            lines.append("q'' = [" + ", ".join(_show(v) for v in self.accelerations) + "] rad/s^2")
        return "\n".join(lines)

    def to_mechanics(self) -> Any:
        """The same equations as a :class:`sympy.physics.mechanics.System`, formed: a bridge to
        PyDy and the rest of the mechanics ecosystem.

        The system's frame ``N`` turns with the frame of the train; its coordinates are the
        turns ``varphi_<link>(t)``, its speeds ``omega_<link>(t)`` (with ``varphi' = omega``);
        each coordinate's generalised force is a torque on a frame ``A_<link>`` turning with it;
        the equations are formed by Lagrange's method from the kinetic energy (the Lagrangian:
        no potential energy), so ``system.mass_matrix`` and ``system.forcing`` are this object's
        M and f with ``varphi'`` for ``omega``.  The system holds no bodies: the kinetic energy
        comes from the engine's speed laws, so ``system.eom_method`` is a
        :class:`~sympy.physics.mechanics.LagrangesMethod` that takes it as the Lagrangian
        (``system.form_eoms(type(system.eom_method))`` forms the equations again).

        >>> from symkin.trains import load_train
        >>> system = equations_of_motion(load_train("simple"), state="low").to_mechanics()
        >>> system.q, system.mass_matrix.shape
        (Matrix([[varphi_S(t)]]), (1, 1))
        """
        from sympy.physics import mechanics as me

        t = me.dynamicsymbols._t
        q = [me.dynamicsymbols(str(a)) for a in self.angles]
        u = [me.dynamicsymbols(str(w)) for w in self.speeds_symbols]
        swap = {**{a: qi for a, qi in zip(self.angles, q)}, **{w: qi.diff(t) for w, qi in zip(self.speeds_symbols, q)},
                S.t: t}
        N = me.ReferenceFrame("N")
        system = me.System(N)
        system.add_coordinates(*q)
        system.add_speeds(*u)
        system.add_kdes(*(qi.diff(t) - ui for qi, ui in zip(q, u)))
        for c, qi, Qi in zip(self.coordinates, q, self.generalised_forces):
            A = N.orientnew(f"A_{c}", "Axis", (qi, N.z))
            system.add_loads(me.Torque(A, Qi.xreplace(swap) * N.z))
        energy = self.kinetic_energy.xreplace(swap)

        class TrainLagrangesMethod(me.LagrangesMethod):
            """Lagrange's method with the train's kinetic energy as the Lagrangian."""

            def __init__(self, Lagrangian: Any, qs: Any, **kwargs: Any) -> None:
                # System.form_eoms passes the Lagrangian of its bodies (it has none): the train's energy stands in
                super().__init__(energy, qs, **kwargs)

        system.form_eoms(TrainLagrangesMethod)
        return system

    def simulate(self, t_span: tuple[float, float], initial_speeds: Sequence[float] | None = None,
                 initial_angles: Sequence[float] | None = None, values: Mapping[Any, Any] | None = None,
                 **options: Any) -> Simulation:
        """Integrate ``M q'' = f`` in time (SciPy ``solve_ivp``; the right-hand side compiled
        through :func:`symkin.compile`).

        ``values`` gives numbers to the symbols left (inertias, masses, torques' names);
        ``options`` go to ``solve_ivp`` (``t_eval``, ``rtol``, ``atol``, ``method``).

        >>> from symkin.trains import load_train
        >>> eom = equations_of_motion(load_train("simple"), state="low", torques={"S": 2})
        >>> run = eom.simulate((0, 1), values={"J_S": 1, "J_C": 0, "J_P": 0, "m_P": 0})
        >>> round(float(run.speeds["S"][-1]), 6)     # 2 N m on 1 kg m^2 for 1 s
        2.0
        """
        import numpy as np
        from scipy.integrate import solve_ivp

        from symkin.numeric import compile as compile_laws

        subs = {(sp.Symbol(k, positive=True) if isinstance(k, str) else k): as_expr(v, what=f"value of {k}")
                for k, v in (values or {}).items()}
        subs.update({sp.Symbol(k.name): v for k, v in list(subs.items())})  # the symbol under any assumptions
        acc = [sp.sympify(a).xreplace(subs) for a in self.accelerations]
        energy = self.kinetic_energy.xreplace(subs)
        args = [S.t, *self.angles, *self.speeds_symbols]
        left = set().union(*(a.free_symbols for a in acc), energy.free_symbols) - set(args)
        if left:
            raise InputError(f"give values to {', '.join(sorted(map(str, left)))} (values={{name: number}}) to simulate")
        f = compile_laws([*acc, energy], args=args, backend="numpy")
        n = len(self.coordinates)

        def rhs(t: float, y: Any) -> Any:
            out = f(t, *y)
            return np.concatenate([y[n:], np.asarray(out[:n], dtype=float)])

        y0 = np.concatenate([np.zeros(n) if initial_angles is None else np.asarray(initial_angles, dtype=float),
                             np.zeros(n) if initial_speeds is None else np.asarray(initial_speeds, dtype=float)])
        if y0.shape != (2 * n,):
            raise InputError(f"give {n} initial angles and {n} initial speeds, one per coordinate")
        options.setdefault("rtol", 1e-10)
        options.setdefault("atol", 1e-12)
        sol = solve_ivp(rhs, t_span, y0, **options)
        if not sol.success:
            raise InputError(f"the integration failed: {sol.message}")
        T = np.asarray(f(sol.t, *sol.y)[n], dtype=float) * np.ones_like(sol.t)
        return Simulation(sol.t, {c: sol.y[i] for i, c in enumerate(self.coordinates)},
                          {c: sol.y[n + i] for i, c in enumerate(self.coordinates)}, T)


@dataclass(frozen=True)
class Simulation:
    """A run of :meth:`EquationsOfMotion.simulate`: times (s), each coordinate's turn (rad) and
    speed (rad/s), and the kinetic energy (J) at each time."""

    t: Any
    angles: dict[str, Any]
    speeds: dict[str, Any]
    kinetic_energy: Any


def _value(v: sp.Expr) -> Any:
    return exact_json(v) if v.is_number else {"exact": str(v), "float": None}


def _show(v: sp.Expr) -> str:
    if v.is_number and not v.is_Rational:
        return f"{v} ({float(v):.6g})"
    if v.is_Rational and not v.is_Integer:
        return f"{v} ({float(v):.6g})"
    return str(v)
