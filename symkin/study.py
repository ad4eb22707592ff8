"""A study: say what you need of a mechanism, and only that is derived, compiled once, and cached.

:class:`Study` is the orchestrator of the path of data: it takes a request (ratios, link
speeds, particle positions, velocities, accelerations), asks the engine for just those
laws, compiles them together with :func:`symkin.compile`, and evaluates them.  It names
the laws a study evaluates (ratios, link speeds, particle positions,
velocities, accelerations), the inputs, the time grid and the precision.  Nothing is
derived until the study is first evaluated (or its :attr:`Study.laws` read); then only
the laws asked for are derived, compiled together (shared subexpressions), and cached
on the mechanism, so a second study with the same request reuses them.  Laws are not
simplified (``sympy.simplify`` costs seconds and makes slower code).

    >>> import numpy as np, symkin
    >>> from symkin import schemes
    >>> study = symkin.Study(schemes.two_row("AA", teeth=True), ratios=[("H", "1", "4")])
    >>> study.args
    ('z_1', 'z_2', 'z_3', 'z_4')
    >>> out = study.evaluate({"z_1": 100, "z_2": 99, "z_3": 100, "z_4": np.array([101, 102])})
    >>> out["i_{H1}^{(4)}"]
    array([10000.        ,  -102.04081633])
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, TypedDict

import numpy as np
import sympy as sp

from symkin import symbols as S
from symkin.errors import InputError
from symkin.kinematics import kinematic_system
from symkin.laws import Law
from symkin.model import Mechanism
from symkin.numeric import DEFAULT_CHUNK, compile

__all__ = ["Study"]

_QUANTITIES = ("position", "velocity", "acceleration")
#: Other names a reader uses: the 2009 paper's V and w, and the usual v and a.
_ALIASES = {"V": "velocity", "v": "velocity", "w": "acceleration", "a": "acceleration"}


class _CompileOptions(TypedDict):
    """The keyword arguments a study passes to :func:`symkin.compile` (part of its cache key too)."""

    backend: str | None
    precision: str
    digits: int
    ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None
    reduce_phase: Sequence[sp.Symbol]
    chunk: int
    threads: int | None


@dataclass(frozen=True, eq=False)
class Study:
    """What a study evaluates on one mechanism.

    Parameters
    ----------
    mechanism : Mechanism
    ratios : sequence of (driver, driven, fixed)
        Ratios i_ab^(c); ``fixed`` is a link name or a tuple of them.
    speeds : sequence of str
        Links whose angular velocity law is wanted, given ``inputs``.
    particles : sequence of (link, (a, b)) or (link, (a, b), quantities)
        Particles by link and Lagrange coordinates; ``quantities`` from "position",
        "velocity" (or "V", "v"), "acceleration" (or "w", "a") (default: position).  Each
        gives x and y laws in t, named ``x[...]``, ``Vx[...]``, ``wx[...]`` (the 2009 paper's
        letters).
    inputs : mapping of link to speed or drive, optional
        Known speeds (for ``speeds``) and input drives (for ``particles``); default: the
        symbols omega_k of an admissible choice of links.
    frame : FrameMotion or SpaceFrame, optional
        The frame's own motion (a base moving in the plane, or in space: then each
        particle gives x, y and z laws).
    t : array, optional
        Time grid used when the laws depend on t and no ``t`` is given to :meth:`evaluate`.
    backend, precision, digits, ranges, chunk, threads
        Passed to :func:`symkin.compile` (``backend``: its default when None).
    reduce_phase : bool
        Reduce phases in t in double-double arithmetic (default): the rounding of
        omega t is otherwise most of the float64 error of a law in time.
    """

    mechanism: Mechanism
    ratios: Sequence[tuple[str, str, Any]] = ()
    speeds: Sequence[str] = ()
    particles: Sequence[tuple[Any, ...]] = ()
    inputs: Mapping[str, Any] | None = None
    frame: Any = None
    t: Any = None
    backend: str | None = None
    precision: str = "float64"
    digits: int = 50
    ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None
    reduce_phase: bool = True
    chunk: int | None = None
    threads: int | None = None
    _buffers: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        if not isinstance(self.mechanism, Mechanism):
            raise InputError(f"a study needs a Mechanism, got {self.mechanism!r}")
        for r in self.ratios:
            if not isinstance(r, (tuple, list)) or len(r) != 3:
                raise InputError(f"a ratio is (driver, driven, fixed), got {r!r}")
        for p in self.particles:
            if not isinstance(p, (tuple, list)) or len(p) not in (2, 3):
                raise InputError(f"a particle is (link, (a, b)) or (link, (a, b), quantities), got {p!r}")
            for q in (p[2] if len(p) == 3 else ()):
                if _ALIASES.get(q, q) not in _QUANTITIES:
                    raise InputError(f"a particle quantity is one of {', '.join(_QUANTITIES)} (or V, v, w, a), "
                                     f"got {q!r}")
        if not (self.ratios or self.speeds or self.particles):
            raise InputError("an empty study: ask for ratios=, speeds= or particles=")

    # ---- what is derived
    def _inputs(self) -> dict[str, Any]:
        if self.inputs is not None:
            return dict(self.inputs)
        choice = kinematic_system(self.mechanism).admissible_choice()
        return {n: S.omega(n) for n in choice}

    def _derive(self) -> tuple[Law, ...]:
        mech = self.mechanism
        laws: list[Law] = [mech.ratio(a, b, fixed=c) for a, b, c in self.ratios]
        if self.speeds:
            solved = mech.speeds(self._inputs())
            laws += [solved.law(n) for n in self.speeds]
        if self.particles:
            motion = mech.motion(self._inputs(), self.frame)
            for item in self.particles:
                link, point = item[0], item[1]
                quantities = item[2] if len(item) == 3 else ("position",)
                p = motion.particle(link, point)
                tag = f"{motion.mechanism.link(link).name}@({', '.join(map(str, point))})"
                for q in (_ALIASES.get(q, q) for q in quantities):
                    vec = getattr(p, q)
                    sym = {"position": "", "velocity": "V", "acceleration": "w"}[q]
                    for axis, comp in zip("xyz", vec):
                        laws.append(Law(sp.Symbol(f"{sym or ''}{axis}[{tag}]" if sym else f"{axis}[{tag}]"), comp, f"{q} {axis} of {tag}"))
        return tuple(laws)

    def _key(self) -> Any:
        fixed = lambda c: tuple(c) if isinstance(c, (tuple, list)) else c  # noqa: E731
        return (
            "study",
            tuple((a, b, fixed(c)) for a, b, c in self.ratios),
            tuple(self.speeds),
            tuple((p[0], tuple(map(str, p[1])), tuple(_ALIASES.get(q, q) for q in p[2]) if len(p) == 3 else ("position",))
                  for p in self.particles),
            tuple(sorted((k, str(v)) for k, v in (self.inputs or {}).items())),
            repr(self.frame),
        )

    @cached_property
    def laws(self) -> tuple[Law, ...]:
        """The laws asked for, derived on first use (cached on the mechanism)."""
        return self.mechanism._memo(self._key(), self._derive)

    @cached_property
    def function(self) -> Any:
        """The laws compiled together, once (cached on the mechanism per backend)."""
        free = set().union(*(law.rhs.free_symbols for law in self.laws))
        args = sorted(free - {S.t}, key=lambda s: s.name) + ([S.t] if S.t in free else [])
        options = _CompileOptions(
            backend=self.backend, precision=self.precision, digits=self.digits, ranges=self.ranges,
            reduce_phase=(S.t,) if self.reduce_phase else (), chunk=self.chunk or DEFAULT_CHUNK, threads=self.threads,
        )
        key = self._key() + (tuple(sorted((k, str(v)) for k, v in options.items())),)
        return self.mechanism._memo(key, lambda: compile(list(self.laws), args, **options))

    @property
    def args(self) -> tuple[str, ...]:
        """Argument names, in order (t last when the laws depend on time)."""
        return self.function.args

    @property
    def outputs(self) -> tuple[str, ...]:
        """The names of the outputs, in the order :meth:`evaluate` returns them."""
        return self.function.outputs

    def evaluate(self, values: Mapping[Any, Any] | None = None, *, t: Any = None, reuse: bool = False) -> dict[str, Any]:
        """Every law of the study at ``values`` ({name or symbol: number or array}).

        ``t`` (or the study's grid) is used for laws in time.  With ``reuse=True`` the
        results are written into buffers the study keeps and reuses on the next call of
        the same shape (no fresh allocation; earlier results are overwritten).
        """
        given = {str(k): v for k, v in (values or {}).items()}
        if "t" in self.args:
            grid = t if t is not None else self.t
            if grid is None and "t" not in given:
                raise InputError("these laws depend on t: give a time grid with t=... or Study(..., t=...)")
            if grid is not None:
                given["t"] = grid
        missing = [a for a in self.args if a not in given]
        if missing:
            raise InputError(f"give values for {', '.join(missing)} (the study's arguments are {', '.join(self.args)})")
        unknown = sorted(set(given) - set(self.args) - {"t"})
        if unknown:
            raise InputError(f"{', '.join(unknown)} {'is' if len(unknown) == 1 else 'are'} not an argument of this study; its arguments are {', '.join(self.args)}")
        ordered = [given[a] for a in self.args]
        out = None
        if reuse and self.function.backend in ("numpy", "numba"):
            shape = np.broadcast_shapes(*(np.shape(v) for v in ordered))
            dtype = np.float32 if self.precision == "float32" else np.float64
            key = (shape, dtype)
            if key not in self._buffers:
                self._buffers.clear()
                self._buffers[key] = [np.empty(shape, dtype) for _ in self.outputs]
            out = self._buffers[key]
        result = self.function(*ordered, out=out)
        if len(self.outputs) == 1:
            result = (result,)
        return dict(zip(self.outputs, result))
