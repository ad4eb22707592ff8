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
from symkin._util.parsing import as_expr, as_float, as_values, substitute
from symkin.drives import Drive, as_drive
from symkin.errors import InputError
from symkin.kinematics import check_known_links, solve_speeds
from symkin.model import FRAME, LinkKind, Mechanism
from symkin.numeric.sampling import on_grid, time_grid
from symkin.superposition import acceleration, position, rotation, vec, velocity

__all__ = ["FrameMotion", "Motion", "Particle"]


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
            object.__setattr__(self, name, as_expr(getattr(self, name), what=f"frame {name}(t)", names=("t",)))


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
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    @classmethod
    def build(cls, mechanism: Mechanism, inputs: Mapping[str, Any], frame: FrameMotion | None = None) -> Motion:
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
        if frame is not None and not isinstance(frame, FrameMotion):
            raise InputError(f"frame must be a FrameMotion, got {frame!r}")
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
        return L.carrier, sp.ImmutableMatrix(self._origin0 + offset)

    def particle(self, link: str, point: Sequence[Any], *, relative_to: str = "frame") -> Particle:
        """A particle of ``link``.

        Parameters
        ----------
        link : str
        point : (a, b)
            Its Lagrange coordinates: where it is at t = 0, in the frame's coordinates
            (``relative_to="frame"``), or relative to the link's pole (``"pole"``).
        """
        link_name = self.mechanism.link(link).name
        if not hasattr(point, "__len__") or len(point) != 2:
            raise InputError(f"a particle is given by two coordinates (a, b), got {point!r}")
        xy = vec(*(as_expr(c, what="particle coordinate") for c in point))
        if relative_to == "pole":
            xy = sp.ImmutableMatrix(self.pole(link_name)[1] + rotation(self.frame.angle.subs(S.t, 0)) * xy)
        elif relative_to != "frame":
            raise InputError(f"relative_to must be 'frame' or 'pole', got {relative_to!r}")
        key = ("particle", link_name, tuple(xy))
        if key not in self._cache:
            self._cache[key] = Particle(self, link_name, xy)
        return self._cache[key]

    def turn_time(self, turns: Any = 1, link: str | None = None, values: Mapping[Any, Any] | None = None) -> float:
        """The time ``link`` takes to make ``turns`` turns at its (constant) speed.

        Without ``link``: the carrier H when it moves, otherwise the fastest link.

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
            if moving.get("H", 0) > 0:
                link = "H"
            elif moving and max(moving.values()) > 0:
                link = max(moving, key=lambda n: moving[n])
            else:
                raise InputError("no link turns at a constant non-zero speed; give the time span instead of turns")
        w = constant(self.mechanism.link(link).name)
        if w == 0:
            raise InputError(f"link {link} does not turn; count turns of a moving link or give the time span")
        return float(2 * np.pi * turns / w)




@dataclass(frozen=True)
class Particle:
    """A particle of a link: its position, velocity and acceleration laws in t.

    Each is derived on first use by eqs. (4), (5), (6) and cached.
    """

    motion: Motion
    link: str
    initial: sp.ImmutableMatrix

    @cached_property
    def _pole(self) -> tuple[Particle | None, sp.ImmutableMatrix]:
        parent, pole0 = self.motion.pole(self.link)
        if self.link == FRAME:
            return None, pole0
        return self.motion.particle(parent, tuple(pole0)), pole0

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
