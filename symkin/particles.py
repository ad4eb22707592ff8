"""Position, velocity, acceleration and trajectory of any particle of any link.

A particle is named by its link and its Lagrange (initial, t = 0) coordinates (a, b).
Its motion is the superposition of its link's pole motion and the link's rotation,
eqs. (4)-(6) of the 2009 paper, applied link by link: the frame (which may itself move,
like a drill head on a manipulator), then a central link about the main axis, then a
planet about its axis, which is itself a particle of the carrier.  Laws are derived
only when asked for, and cached.

    >>> import sympy as sp
    >>> from symkin import schemes, symbols as S
    >>> m = schemes.single_row_AI(radii=(1, 1, 3))
    >>> motion = m.motion({"4": 0, "H": 1})
    >>> p = motion.particle("2", (1, 0))          # the planet's contact point with the sun
    >>> sp.simplify(p.position.subs(S.t, sp.pi))  # half a carrier turn later it touches the ring
    Matrix([
    [-3],
    [ 0]])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
import sympy as sp

from symkin import symbols as S
from symkin._util.display import short_repr
from symkin.drives import Drive, as_drive
from symkin.errors import InputError, UnsupportedError
from symkin.kinematics import check_known_links, solve_speeds
from symkin.model import FRAME, LinkKind, Mechanism
from symkin.numeric.sampling import on_grid, time_grid
from symkin.superposition import (
    acceleration,
    carried,
    position,
    rotation,
    rotation_about,
    spin_acceleration,
    spin_velocity,
    vec,
    vec3,
    velocity,
)
from symkin.values import as_expr, as_float, as_values, substitute

__all__ = ["FrameMotion", "SpaceFrame", "Motion", "Particle", "SpaceParticle"]


@dataclass(frozen=True)
class FrameMotion:
    """Prescribed plane motion of the mechanism frame: the main axis O at (x(t), y(t)),
    the frame turned by angle(t).  All three are expressions in :data:`symkin.symbols.t`.
    """

    x: Any = 0
    y: Any = 0
    angle: Any = 0

    def __post_init__(self) -> None:
        for name in ("x", "y", "angle"):
            object.__setattr__(self, name, as_expr(getattr(self, name), what=f"frame {name}(t)"))


@dataclass(frozen=True)
class SpaceFrame:
    """Prescribed motion of the mechanism frame in space: the main axis point O at
    (x(t), y(t), z(t)), the frame turned by ``rotation(t)`` (a 3 x 3 rotation matrix whose
    columns are the frame's x, y, z axes; the main axis is its z).  The 2009 paper's drill
    head on a manipulator: the manipulator's drives set O and the head's orientation.

    Build it with :meth:`euler` from yaw, pitch and roll, or give the matrix.

    >>> from symkin import symbols as S
    >>> f = SpaceFrame.euler(z=S.t, pitch=S.t / 10)   # the head advances and tilts
    >>> f.rotation[0, 2]
    sin(t/10)
    """

    x: Any = 0
    y: Any = 0
    z: Any = 0
    rotation: Any = None

    def __post_init__(self) -> None:
        for name in ("x", "y", "z"):
            object.__setattr__(self, name, as_expr(getattr(self, name), what=f"frame {name}(t)"))
        R = sp.eye(3) if self.rotation is None else self.rotation
        if not hasattr(R, "shape") or tuple(R.shape) != (3, 3):
            raise InputError(f"the frame's rotation is a 3 x 3 matrix (columns: its x, y, z axes), got {self.rotation!r}")
        R = sp.ImmutableMatrix([[as_expr(R[i, j], what="an entry of the frame's rotation") for j in range(3)]
                                for i in range(3)])
        for when in (sp.Integer(0), sp.Rational(7, 3), sp.Rational(-11, 5)):  # orthonormal and right-handed
            Rn = R.subs(S.t, when).evalf(30)
            if max(abs(e) for e in (Rn.T * Rn - sp.eye(3))) > 1e-20 or abs(Rn.det() - 1) > 1e-20:
                raise InputError(f"the frame's rotation is not a rotation at t = {when} (R^T R = I and det R = 1 fail); "
                                 "give a rotation matrix, or angles with SpaceFrame.euler")
        object.__setattr__(self, "rotation", R)

    @classmethod
    def euler(cls, x: Any = 0, y: Any = 0, z: Any = 0, *, yaw: Any = 0, pitch: Any = 0, roll: Any = 0) -> SpaceFrame:
        """The frame at (x, y, z) turned by yaw about z, then pitch about the new y, then roll
        about the newest x (R = R_z(yaw) R_y(pitch) R_x(roll)); expressions in t."""
        angles = [as_expr(a, what=f"frame {n}(t)") for n, a in (("yaw", yaw), ("pitch", pitch), ("roll", roll))]
        R = (rotation_about(vec3(0, 0, 1), angles[0]) * rotation_about(vec3(0, 1, 0), angles[1])
             * rotation_about(vec3(1, 0, 0), angles[2]))
        return cls(x, y, z, sp.ImmutableMatrix(R))

    @cached_property
    def origin(self) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
        """The position of the main axis point O in space, its velocity and its acceleration (column vectors in t)."""
        o = vec3(self.x, self.y, self.z)
        return o, sp.ImmutableMatrix(sp.diff(o, S.t)), sp.ImmutableMatrix(sp.diff(o, S.t, 2))

    @cached_property
    def turns(self) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
        """The rotation of the base, and its first and second time derivatives (3 x 3 matrices in t)."""
        R = self.rotation
        return R, sp.ImmutableMatrix(sp.diff(R, S.t)), sp.ImmutableMatrix(sp.diff(R, S.t, 2))

    @property
    def still(self) -> bool:
        """Whether the base does not move (no translation, no rotation).

        >>> SpaceFrame().still
        True
        """
        return self.x == 0 and self.y == 0 and self.z == 0 and self.rotation == sp.eye(3)


@dataclass(frozen=True)
class Motion:
    """The motion of every link of a mechanism under given input drives.

    Build it with :meth:`Mechanism.motion` (or :meth:`build`).  Inputs are exactly the
    mechanism's degrees of freedom; each is a :class:`~symkin.drives.Drive` or a speed
    (a number, or an expression in t).
    """

    mechanism: Mechanism
    inputs: tuple[tuple[str, Drive], ...]
    frame: FrameMotion = field(default_factory=FrameMotion)
    space: SpaceFrame | None = None
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __repr__(self) -> str:
        """``Motion(Mechanism('AI1', ...), inputs H, 4)``, under 200 characters."""
        return short_repr("Motion", f"mechanism {self.mechanism.name!r}", "inputs " + ", ".join(n for n, _ in self.inputs),
                          *(["in space"] if self.space is not None else []))

    @classmethod
    def build(cls, mechanism: Mechanism, inputs: Mapping[str, Any], frame: FrameMotion | SpaceFrame | None = None) -> Motion:
        """The motion of ``mechanism`` under ``inputs`` (link name to drive or speed) and an optional moving ``frame``; checks the inputs first."""
        if not isinstance(inputs, Mapping):
            raise InputError(f"inputs are a mapping of link name to drive or speed, got {inputs!r}")
        resolved: dict[str, Drive] = {}
        for name, value in inputs.items():
            link = mechanism.link(name).name
            if link == FRAME:
                raise InputError("the frame is moved with frame=FrameMotion(...), not as an input")
            if link in resolved:
                raise InputError(f"link {link} is given two drives; give it one")
            resolved[link] = as_drive(value, f"drive of link {link}")
        check_known_links(mechanism, tuple(resolved))
        if isinstance(frame, SpaceFrame):  # the planar motion in a still frame, carried by the frame's motion in space
            return cls(mechanism, tuple(resolved.items()), FrameMotion(), frame)
        if frame is not None and not isinstance(frame, FrameMotion):
            raise InputError(f"frame must be a FrameMotion (in the plane) or a SpaceFrame, got {frame!r}")
        return cls(mechanism, tuple(resolved.items()), frame or FrameMotion())

    # ---- link rotations (relative to the frame)
    @cached_property
    def _speeds(self):
        return solve_speeds(self.mechanism, {n: S.omega(n) for n, _ in self.inputs})

    def _combine(self, link: str, per_input) -> sp.Expr:
        link = self.mechanism.link(link).name
        if link == FRAME:
            return sp.Integer(0)
        return sp.Add(*(self._speeds.coefficient(link, n) * per_input(d) for n, d in self.inputs))

    def angle(self, link: str) -> sp.Expr:
        """Rotation of ``link`` relative to the frame since t = 0."""
        return self._combine(link, lambda d: d.angle(S.t))

    def omega(self, link: str) -> sp.Expr:
        """Angular velocity of ``link`` relative to the frame."""
        return self._combine(link, lambda d: d.speed(S.t))

    def epsilon(self, link: str) -> sp.Expr:
        """Angular acceleration of ``link`` relative to the frame."""
        return self._combine(link, lambda d: d.acceleration(S.t))

    def _absolute(self, link: str, order: int) -> sp.Expr:
        frame_turn = self.frame.angle - self.frame.angle.subs(S.t, 0)
        own = (self.angle, self.omega, self.epsilon)[order](link)
        return sp.diff(frame_turn, S.t, order) + own

    # ---- poles
    @cached_property
    def _origin0(self) -> sp.ImmutableMatrix:
        return vec(self.frame.x, self.frame.y).subs(S.t, 0)

    def pole(self, link: str) -> tuple[str, sp.ImmutableMatrix]:
        """The link whose particle is ``link``'s pole, and the pole's Lagrange coordinates."""
        L = self.mechanism.link(link)
        if L.kind is LinkKind.FRAME:
            return FRAME, self._origin0
        if L.kind is LinkKind.CENTRAL:
            return FRAME, self._origin0
        arm = self.mechanism.arm(L.name)
        assert L.carrier is not None  # a planet: Link.__post_init__ gives it a carrier
        turn0 = self.frame.angle.subs(S.t, 0)
        angle = self.mechanism.position_angle(L.name)
        offset = rotation(turn0) * vec(arm * sp.cos(angle), arm * sp.sin(angle))
        carrier = self.mechanism.link(L.carrier)
        # the carrier's own axis at t = 0: the main axis, or (a planet of a planet) its pole
        base = self._origin0 if carrier.kind is not LinkKind.PLANET else self.pole(carrier.name)[1]
        return L.carrier, sp.ImmutableMatrix(base + offset)

    def particle(self, link: str, point: Sequence[Any], *, relative_to: str = "frame") -> Particle | SpaceParticle:
        """A particle of ``link``.

        Parameters
        ----------
        link : str
        point : (a, b) or (a, b, c)
            Its Lagrange coordinates: where it is at t = 0, in the frame's coordinates
            (``relative_to="frame"``), or relative to the link's pole (``"pole"``); ``c``
            is its height along the main axis.  A bevel pinion's pole coordinates run along
            its axis, across it, and along the main axis.

        Returns
        -------
        Particle
            In the plane (eqs. 4-6), for two coordinates in a frame that moves in the plane;
        SpaceParticle
            In space, when the frame moves in space (a :class:`SpaceFrame`), the link is a
            bevel pinion, or three coordinates are given.
        """
        link_name = self.mechanism.link(link).name
        if not hasattr(point, "__len__") or len(point) not in (2, 3):
            raise InputError(f"a particle is given by two coordinates (a, b) or three (a, b, c), got {point!r}")
        if len(point) == 3 or self.space is not None or self.mechanism.link(link_name).axis == "radial":
            return self._space_particle(link_name, point, relative_to)
        xy = vec(*(as_expr(c, what="particle coordinate") for c in point))
        if relative_to == "pole":
            xy = sp.ImmutableMatrix(self.pole(link_name)[1] + rotation(self.frame.angle.subs(S.t, 0)) * xy)
        elif relative_to != "frame":
            raise InputError(f"relative_to must be 'frame' or 'pole', got {relative_to!r}")
        return self._planar(link_name, xy)

    def _planar(self, link: str, xy: sp.ImmutableMatrix) -> Particle:
        """The plane particle of ``link`` at ``xy`` (frame coordinates at t = 0), cached."""
        key = ("particle", link, tuple(xy))
        if key not in self._cache:
            self._cache[key] = Particle(self, link, xy)
        return self._cache[key]

    def _space_particle(self, link: str, point: Sequence[Any], relative_to: str) -> SpaceParticle:
        if self.frame.x != 0 or self.frame.y != 0 or self.frame.angle != 0:
            raise UnsupportedError("a particle in space needs the frame's motion as a SpaceFrame (it takes the plane's "
                                   "motion as x, y and a yaw): give frame=SpaceFrame(...)")
        coords = [as_expr(c, what="particle coordinate") for c in point] + ([sp.Integer(0)] * (3 - len(point)))
        L = self.mechanism.link(link)
        if relative_to == "pole":
            if L.axis == "radial":
                carrier = self.mechanism.link(L.carrier or FRAME)
                c0 = self.mechanism.axis_position(carrier.name)
                alpha = self.mechanism.position_angle(L.name)
                a_hat = vec3(sp.cos(alpha), sp.sin(alpha), 0)
                t_hat = vec3(-sp.sin(alpha), sp.cos(alpha), 0)
                start = vec3(c0[0], c0[1], 0) + coords[0] * a_hat + coords[1] * t_hat + coords[2] * vec3(0, 0, 1)
            else:
                x0, y0 = self.pole(link)[1]
                start = vec3(x0 + coords[0], y0 + coords[1], coords[2])
        elif relative_to == "frame":
            start = vec3(*coords)
        else:
            raise InputError(f"relative_to must be 'frame' or 'pole', got {relative_to!r}")
        key = ("space particle", link, tuple(start))
        if key not in self._cache:
            self._cache[key] = SpaceParticle(self, link, sp.ImmutableMatrix(start))
        return self._cache[key]

    def turn_time(self, turns: Any = 1, link: str | None = None, values: Mapping[Any, Any] | None = None) -> float:
        """The time ``link`` takes to make ``turns`` turns at its (constant) speed.

        Without ``link``: the carrier H when it moves, else the first moving carrier (a
        central link that carries planets), otherwise the fastest link.

        >>> from symkin import schemes
        >>> motion = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 2})
        >>> round(motion.turn_time(1), 6)
        3.141593
        """
        turns = as_float(turns, what="the number of turns", positive=True)
        subs = as_values(values)

        def speed(name: str) -> sp.Expr:
            return substitute(sp.sympify(self.omega(name)), subs)

        def constant(name: str) -> float:
            w = speed(name)
            if S.t in w.free_symbols or not w.is_number:
                raise InputError(f"link {name} has no constant numeric speed ({w}); give the time span instead of turns")
            return abs(float(w))

        if link is None:
            moving = {n: constant(n) for n in self.mechanism.link_names if not speed(n).has(S.t)}
            carriers = [L.name for L in self.mechanism.links if L.kind is LinkKind.CENTRAL and moving.get(L.name, 0) > 0
                        and any(X.carrier == L.name for X in self.mechanism.links)]
            if moving.get("H", 0) > 0:
                link = "H"
            elif carriers:
                link = carriers[0]
            elif moving and max(moving.values()) > 0:
                link = max(moving, key=lambda n: moving[n])
            else:
                raise InputError("no link turns at a constant non-zero speed; give the time span instead of turns")
        w = constant(self.mechanism.link(link).name)
        if w == 0:
            raise InputError(f"link {link} does not turn; count turns of a moving link or give the time span")
        return float(2 * np.pi * turns / w)




class _Letters:
    """The 2009 paper's letters and the usual ones for a particle's laws: ``V`` and ``v`` are
    its velocity, ``w`` and ``a`` its acceleration (the same cached laws)."""

    velocity: sp.ImmutableMatrix
    acceleration: sp.ImmutableMatrix

    @property
    def V(self) -> sp.ImmutableMatrix:
        """The velocity (the 2009 paper's V)."""
        return self.velocity

    v = V

    @property
    def w(self) -> sp.ImmutableMatrix:
        """The acceleration (the 2009 paper's w)."""
        return self.acceleration

    a = w


@dataclass(frozen=True)
class Particle(_Letters):
    """A particle of a link: its position, velocity and acceleration laws in t.

    Each is derived on first use by eqs. (4), (5), (6) and cached.  ``V`` (or ``v``) and
    ``w`` (or ``a``) are the same velocity and acceleration: the 2009 paper writes V and w,
    most readers v and a.

    >>> from symkin import schemes
    >>> p = schemes.single_row_AI(teeth=(20, 30, 80), module=1).motion({"4": 0, "H": 1}).particle("2", (15, 0))
    >>> p.w is p.a is p.acceleration, p.V is p.velocity
    (True, True)
    """

    motion: Motion
    link: str
    initial: sp.ImmutableMatrix

    def __repr__(self) -> str:
        """``Particle(link 2 at (15, 0), Mechanism 'AI1')``, under 200 characters."""
        return short_repr(type(self).__name__, f"link {self.link} at ({', '.join(str(c) for c in self.initial)})",
                          f"mechanism {self.motion.mechanism.name!r}")

    @cached_property
    def _pole(self) -> tuple[Particle | None, sp.ImmutableMatrix]:
        parent, pole0 = self.motion.pole(self.link)
        if self.link == FRAME:
            return None, pole0
        return self.motion._planar(parent, sp.ImmutableMatrix(pole0)), pole0

    def _pole_state(self, order: int) -> sp.ImmutableMatrix:
        parent, _ = self._pole
        if parent is None:  # the frame's pole: the prescribed motion of the main axis
            return sp.ImmutableMatrix(sp.diff(vec(self.motion.frame.x, self.motion.frame.y), S.t, order))
        return (parent.position, parent.velocity, parent.acceleration)[order]

    @cached_property
    def position(self) -> sp.ImmutableMatrix:
        """Eq. (4): (x, y) in t."""
        return position(self._pole_state(0), self._pole[1], self.initial, self.motion._absolute(self.link, 0))

    @cached_property
    def velocity(self) -> sp.ImmutableMatrix:
        """Eq. (5): (V_x, V_y) in t."""
        return velocity(self._pole_state(1), self.motion._absolute(self.link, 1), self.position, self._pole_state(0))

    @cached_property
    def acceleration(self) -> sp.ImmutableMatrix:
        """Eq. (6): (w_x, w_y) in t."""
        return acceleration(
            self._pole_state(2),
            self.motion._absolute(self.link, 1),
            self.motion._absolute(self.link, 2),
            self.position,
            self._pole_state(0),
        )

    def trajectory(
        self, t_end: Any, *, t_start: Any = 0.0, samples: int = 721, values: Mapping[Any, Any] | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Sampled path: arrays (t, x, y) on ``samples`` equal steps from ``t_start`` to ``t_end``.

        ``values`` gives numbers for every symbol other than t (radii, speeds, ...).

        >>> from symkin import schemes
        >>> p = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1}).particle("2", (1, 0))
        >>> t, x, y = p.trajectory(3.14159265358979, samples=3)
        >>> round(float(x[-1]), 9)   # half a carrier turn later the point touches the ring
        -3.0
        """
        t = time_grid(t_end, t_start=t_start, samples=samples)
        x, y = on_grid(list(self.position), t, values, what="sample the trajectory")
        return t, x, y

    def sample(
        self, t_end: Any, *, t_start: Any = 0.0, samples: int = 721, values: Mapping[Any, Any] | None = None
    ) -> dict[str, np.ndarray]:
        """Position, velocity and acceleration on ``samples`` equal steps of [t_start, t_end].

        Returns arrays ``t, x, y, vx, vy, speed, ax, ay, acceleration`` (magnitudes for
        speed and acceleration).  ``values`` gives numbers for every symbol other than t.

        >>> from symkin import schemes
        >>> p = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1}).particle("2", (2, 1))
        >>> data = p.sample(6.0, samples=5)
        >>> # axis velocity (0, 2) plus omega_2 = -2 turning the offset (0, 1): V = (2, 2)
        >>> round(float(data["speed"][0]), 12)
        2.828427124746
        """
        t = time_grid(t_end, t_start=t_start, samples=samples)
        exprs = [c for vec in (self.position, self.velocity, self.acceleration) for c in vec]
        x, y, vx, vy, ax, ay = on_grid(exprs, t, values, what="sample the particle")
        return {"t": t, "x": x, "y": y, "vx": vx, "vy": vy, "speed": np.hypot(vx, vy),
                "ax": ax, "ay": ay, "acceleration": np.hypot(ax, ay)}


@dataclass(frozen=True)
class SpaceParticle(_Letters):
    """A particle in space: its position, velocity and acceleration, 3 x 1 laws in t.

    Its motion in the mechanism's frame is planar (eqs. 4-6, at its height along the main
    axis) or, on a bevel pinion, the carrier's turn and the pinion's spin about its own
    axis superposed; the frame's motion in space (a :class:`SpaceFrame`) is then superposed
    on that (transport, relative and Coriolis parts: :func:`symkin.superposition.carried`).
    """

    motion: Motion
    link: str
    initial: sp.ImmutableMatrix

    def __repr__(self) -> str:
        """``Particle(link 2 at (15, 0), Mechanism 'AI1')``, under 200 characters."""
        return short_repr(type(self).__name__, f"link {self.link} at ({', '.join(str(c) for c in self.initial)})",
                          f"mechanism {self.motion.mechanism.name!r}")

    @cached_property
    def relative(self) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
        """Position, velocity and acceleration in the mechanism's own frame."""
        m = self.motion
        L = m.mechanism.link(self.link)
        if L.axis != "radial":
            flat = m._planar(self.link, vec(self.initial[0], self.initial[1]))
            height = self.initial[2]
            return (vec3(flat.position[0], flat.position[1], height), vec3(flat.velocity[0], flat.velocity[1], 0),
                    vec3(flat.acceleration[0], flat.acceleration[1], 0))
        # a bevel pinion: it spins about its radial axis, which its carrier turns about the carrier's axis
        carrier = L.carrier or FRAME
        centre = m._planar(carrier, vec(*m.mechanism.axis_position(carrier))) if carrier != FRAME else None
        c0 = m.mechanism.axis_position(carrier)
        alpha = m.mechanism.position_angle(L.name)
        a_hat = vec3(sp.cos(alpha), sp.sin(alpha), 0)
        sigma0 = sp.ImmutableMatrix(self.initial - vec3(c0[0], c0[1], 0))  # from the apex, at t = 0
        phi, w, eps = m.angle(L.name), m.omega(L.name), m.epsilon(L.name)  # the spin relative to the carrier
        sigma = sp.ImmutableMatrix(rotation_about(a_hat, phi) * sigma0)
        sigma_v = spin_velocity(w, a_hat, sigma)
        sigma_a = spin_acceleration(eps, w, a_hat, sigma)
        turn = m._absolute(carrier, 0) if carrier != FRAME else sp.Integer(0)
        Rk = rotation_about(vec3(0, 0, 1), turn)
        dRk, ddRk = sp.ImmutableMatrix(sp.diff(Rk, S.t)), sp.ImmutableMatrix(sp.diff(Rk, S.t, 2))
        if centre is None:
            origin = (vec3(0, 0, 0), vec3(0, 0, 0), vec3(0, 0, 0))
        else:
            origin = tuple(vec3(q[0], q[1], 0) for q in (centre.position, centre.velocity, centre.acceleration))
        return carried(origin, Rk, dRk, ddRk, (sigma, sigma_v, sigma_a))

    @cached_property
    def _absolute(self) -> tuple[sp.ImmutableMatrix, sp.ImmutableMatrix, sp.ImmutableMatrix]:
        space = self.motion.space
        if space is None or space.still:
            return self.relative
        R, dR, ddR = space.turns
        return carried(space.origin, R, dR, ddR, self.relative)

    @property
    def position(self) -> sp.ImmutableMatrix:
        """(x, y, z) in t."""
        return self._absolute[0]

    @property
    def velocity(self) -> sp.ImmutableMatrix:
        """(V_x, V_y, V_z) in t."""
        return self._absolute[1]

    @property
    def acceleration(self) -> sp.ImmutableMatrix:
        """(w_x, w_y, w_z) in t."""
        return self._absolute[2]

    def trajectory(
        self, t_end: Any, *, t_start: Any = 0.0, samples: int = 721, values: Mapping[Any, Any] | None = None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Sampled path: arrays (t, x, y, z) on ``samples`` equal steps from ``t_start`` to ``t_end``."""
        t = time_grid(t_end, t_start=t_start, samples=samples)
        x, y, z = on_grid(list(self.position), t, values, what="sample the trajectory")
        return t, x, y, z

    def sample(
        self, t_end: Any, *, t_start: Any = 0.0, samples: int = 721, values: Mapping[Any, Any] | None = None
    ) -> dict[str, np.ndarray]:
        """Position, velocity and acceleration on a time grid: ``t, x, y, z, vx, vy, vz, speed,
        ax, ay, az, acceleration`` (magnitudes for speed and acceleration)."""
        t = time_grid(t_end, t_start=t_start, samples=samples)
        exprs = [c for v in (self.position, self.velocity, self.acceleration) for c in v]
        x, y, z, vx, vy, vz, ax, ay, az = on_grid(exprs, t, values, what="sample the particle")
        return {"t": t, "x": x, "y": y, "z": z, "vx": vx, "vy": vy, "vz": vz, "speed": np.sqrt(vx**2 + vy**2 + vz**2),
                "ax": ax, "ay": ay, "az": az, "acceleration": np.sqrt(ax**2 + ay**2 + az**2)}
