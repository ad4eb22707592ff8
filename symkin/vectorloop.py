"""Vector loops: a closed chain of link vectors, solved in closed form.

A planar mechanism's geometry closes: the link vectors around any loop add up to the
same point.  Written in complex form, sum_k l_k e^{i theta_k} = sum_j l_j e^{i theta_j}
(the "complex vector method" of mechanism textbooks), the real and imaginary parts give
two scalar equations, so a loop determines two unknowns: lengths (a slider's travel) or
angles (a link's orientation).  This module knows nothing of any particular mechanism.

Each unknown is the length or the angle of one vector, and may enter that slot linearly
(``theta_H + theta_1`` with ``theta_1`` unknown).  The four classical cases are solved:

- a length and an angle of one vector (the loop's closing vector): its modulus and
  argument, two branches (signed length);
- two lengths of vectors with known directions: Cramer's rule, one branch;
- a length of one vector and the angle of another: a quadratic, two branches;
- two angles: the triangle of the two vectors and their resultant, two branches;

and with one unknown a length along a known direction (a slider on a fixed guide),
which leaves one equation over: the loop closes only when that condition holds.

    >>> import sympy as sp
    >>> from symkin.vectorloop import LinkVector, VectorLoop
    >>> a, b, phi, s = sp.symbols("a b phi s", real=True)
    >>> loop = VectorLoop([LinkVector(a, 0), LinkVector(b, phi)], [LinkVector(s, 0)])
    >>> loop.components()
    (Eq(a + b*cos(phi), s), Eq(b*sin(phi), 0))
    >>> (sol,) = loop.solve(s)       # s on the x axis: b sin(phi) = 0 is left over
    >>> sol[s], sol.conditions
    (a + b*cos(phi), (b*sin(phi),))
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from symkin._util.budget import simplify_within
from symkin.errors import InputError, SingularConfigurationError, UnsupportedError
from symkin.values import as_expr

__all__ = ["LinkVector", "VectorLoop", "LoopSolution", "harmonics", "solve_linear"]




def _sym(value: Any, what: str) -> sp.Expr:
    return as_expr(value, what=what, finite=False)


@dataclass(frozen=True)
class LinkVector:
    """A plane vector ``length * e^{i angle}``; the angle is measured from +x, CCW positive.

    >>> import sympy as sp
    >>> v = LinkVector(2, sp.pi / 2, "arm")
    >>> v.x, v.y
    (0, 2)
    """

    length: sp.Expr
    angle: sp.Expr
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", _sym(self.length, f"length of vector {self.name or '?'}"))
        object.__setattr__(self, "angle", _sym(self.angle, f"angle of vector {self.name or '?'}"))

    @property
    def x(self) -> sp.Expr:
        """The vector's x component, ``length cos(angle)``."""
        return self.length * sp.cos(self.angle)

    @property
    def y(self) -> sp.Expr:
        """The vector's y component, ``length sin(angle)``."""
        return self.length * sp.sin(self.angle)

    @property
    def complex(self) -> sp.Expr:
        """``length * exp(i angle)``."""
        return self.length * sp.exp(sp.I * self.angle)

    def subs(self, *args: Any, **kwargs: Any) -> LinkVector:
        """The vector with ``subs`` applied to its length and angle (SymPy's ``subs`` arguments)."""
        return LinkVector(self.length.subs(*args, **kwargs), self.angle.subs(*args, **kwargs), self.name)


@dataclass(frozen=True)
class LoopSolution:
    """One branch of a loop's solution.

    Attributes
    ----------
    values : mapping of unknown -> expression
    conditions : tuple of expressions
        Expressions that must vanish for the loop to close with these values (an
        equation left over when there are fewer unknowns than equations).
    """

    values: Mapping[sp.Symbol, sp.Expr]
    conditions: tuple[sp.Expr, ...] = ()

    def __getitem__(self, unknown: sp.Symbol) -> sp.Expr:
        return self.values[unknown]


@dataclass(frozen=True)
class VectorLoop:
    """A closed loop ``sum(left) = sum(right)`` of link vectors.

    Parameters
    ----------
    left, right : sequences of LinkVector
        The two paths from a common start to a common end point, e.g. the carrier and
        the crank on the left, the slider's travel on the right.
    """

    left: tuple[LinkVector, ...]
    right: tuple[LinkVector, ...] = ()
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __post_init__(self) -> None:
        for side in ("left", "right"):
            vectors = tuple(getattr(self, side))
            for v in vectors:
                if not isinstance(v, LinkVector):
                    raise InputError(f"a vector loop is built of LinkVector objects, got {v!r}")
            object.__setattr__(self, side, vectors)
        if not self.left and not self.right:
            raise InputError("a vector loop needs at least one vector")

    # ---- the equations
    def _signed(self) -> list[tuple[int, LinkVector]]:
        return [(1, v) for v in self.left] + [(-1, v) for v in self.right]

    def complex_equation(self) -> sp.Eq:
        """The loop in complex form, sum l e^{i theta} on each side."""
        return sp.Eq(sp.Add(*(v.complex for v in self.left)), sp.Add(*(v.complex for v in self.right)), evaluate=False)

    def components(self) -> tuple[sp.Eq, sp.Eq]:
        """The real and the imaginary part of the complex equation (x and y components)."""
        return (
            sp.Eq(sp.Add(*(v.x for v in self.left)), sp.Add(*(v.x for v in self.right)), evaluate=False),
            sp.Eq(sp.Add(*(v.y for v in self.left)), sp.Add(*(v.y for v in self.right)), evaluate=False),
        )

    def components_along(self, angle: Any) -> tuple[sp.Expr, sp.Expr]:
        """``left - right`` resolved along the direction ``angle`` and across it.

        Multiplying the loop by e^{-i angle} turns every vector by -angle; the real part
        is the component along the direction, the imaginary part the one across it.

        >>> import sympy as sp
        >>> a, th = sp.symbols("a theta", real=True)
        >>> VectorLoop([LinkVector(a, th)]).components_along(th)
        (a, 0)
        """
        angle = _sym(angle, "direction")
        along = sp.Add(*(sign * v.length * sp.cos(v.angle - angle) for sign, v in self._signed()))
        across = sp.Add(*(sign * v.length * sp.sin(v.angle - angle) for sign, v in self._signed()))
        return along, across

    def subs(self, *args: Any, **kwargs: Any) -> VectorLoop:
        """The loop with values substituted into every length and angle."""
        return VectorLoop(tuple(v.subs(*args, **kwargs) for v in self.left), tuple(v.subs(*args, **kwargs) for v in self.right))

    # ---- solving
    def _slots(self, unknown: sp.Symbol) -> list[tuple[int, str]]:
        slots = []
        for k, (_, v) in enumerate(self._signed()):
            for slot in ("length", "angle"):
                if getattr(v, slot).has(unknown):
                    slots.append((k, slot))
        return slots

    def solve(self, *unknowns: sp.Symbol) -> tuple[LoopSolution, ...]:
        """Solve the loop for one or two unknowns, each a length or an angle of one vector.

        Returns the branches as :class:`LoopSolution` objects (two for the quadratic
        cases; which one a mechanism takes is its assembly mode).

        Raises
        ------
        UnsupportedError
            An unknown appears in more than one slot, or non-linearly in its slot.
        SingularConfigurationError
            Two unknown lengths along parallel directions.

        Examples
        --------
        The two-angle case (a four-bar's coupler and rocker; here a triangle 3-4-5):

        >>> import sympy as sp
        >>> p, q = sp.symbols("p q", real=True)
        >>> loop = VectorLoop([LinkVector(3, p), LinkVector(4, q)], [LinkVector(5, 0)])
        >>> sorted(sp.N(sol[p], 6) for sol in loop.solve(p, q))
        [-0.927295, 0.927295]
        """
        key = ("solve", unknowns)
        if key in self._cache:
            return self._cache[key]
        if not 1 <= len(unknowns) <= 2:
            raise InputError(f"a vector loop gives two equations: solve it for one or two unknowns, got {len(unknowns)}")
        for u in unknowns:
            if not isinstance(u, sp.Symbol):
                raise InputError(f"an unknown must be a SymPy symbol, got {u!r}")
        if len(set(unknowns)) != len(unknowns):
            raise InputError("the unknowns must be different symbols")
        signed = self._signed()
        located = []
        for u in unknowns:
            slots = self._slots(u)
            if len(slots) != 1:
                where = "no vector" if not slots else f"{len(slots)} places"
                raise UnsupportedError(
                    f"the unknown {u} appears in {where} of the loop; each unknown must be the length or the angle "
                    "of exactly one vector"
                )
            located.append(slots[0])
        involved = {k for k, _ in located}
        # C: what the vectors holding unknowns must add up to (signs folded in)
        known = [(sign, v) for k, (sign, v) in enumerate(signed) if k not in involved]
        cx = -sp.Add(*(sign * v.x for sign, v in known))
        cy = -sp.Add(*(sign * v.y for sign, v in known))
        if len(unknowns) == 1:
            result = self._solve_one(unknowns[0], located[0], signed, cx, cy)
        elif len(involved) == 1:
            result = self._solve_same_vector(unknowns, located, signed, cx, cy)
        else:
            result = self._solve_two_vectors(unknowns, located, signed, cx, cy)
        self._cache[key] = result
        return result

    def _solve_one(self, u, slot, signed, cx, cy) -> tuple[LoopSolution, ...]:
        k, which = slot
        sign, v = signed[k]
        if which == "length":  # along the vector's direction; the across part is left over
            others = [(sg, w) for j, (sg, w) in enumerate(signed) if j != k]
            along = -sign * sp.Add(*(sg * w.length * sp.cos(w.angle - v.angle) for sg, w in others))
            across = sp.Add(*(sg * w.length * sp.sin(w.angle - v.angle) for sg, w in others))  # left - right
            return (LoopSolution({u: solve_linear(v.length, u, along)}, (across,)),)
        phi = sp.atan2(sign * cy, sign * cx)  # the vector's direction; its length must fit
        return (LoopSolution({u: solve_linear(v.angle, u, phi)}, (cx**2 + cy**2 - v.length**2,)),)

    def _solve_same_vector(self, unknowns, located, signed, cx, cy) -> tuple[LoopSolution, ...]:
        sign, v = signed[located[0][0]]
        modulus = sp.sqrt(cx**2 + cy**2)
        out = []
        for branch in (1, -1):  # l e^{i phi} = sign C: |C| at arg(sign C), or -|C| at the opposite angle
            length = branch * modulus
            angle = sp.atan2(branch * sign * cy, branch * sign * cx)
            values = {}
            for u, (_, which) in zip(unknowns, located):
                values[u] = solve_linear(v.length if which == "length" else v.angle, u, length if which == "length" else angle)
            out.append(LoopSolution(values))
        return tuple(out)

    def _solve_two_vectors(self, unknowns, located, signed, cx, cy) -> tuple[LoopSolution, ...]:
        (ka, wa), (kb, wb) = located
        ua, ub = unknowns
        sa, va = signed[ka]
        sb, vb = signed[kb]
        if wa == "length" and wb == "length":
            a, b = va.angle, vb.angle
            det = sp.sin(a - b)
            if det == 0 or simplify_within(det, what="the determinant of the loop") == 0:
                raise SingularConfigurationError(
                    f"the unknown lengths {ua} and {ub} lie along parallel directions, so the loop cannot fix them; "
                    "choose an angle as one of the unknowns",
                    dof=0,
                    admissible=(),
                )
            la = (cy * sp.cos(b) - cx * sp.sin(b)) / (sa * det)
            lb = (cy * sp.cos(a) - cx * sp.sin(a)) / (-sb * det)
            return (LoopSolution({ua: solve_linear(va.length, ua, la), ub: solve_linear(vb.length, ub, lb)}),)
        if wa == "angle" and wb == "length":  # put the length first
            return tuple(
                LoopSolution({ua: s.values[ua], ub: s.values[ub]})
                for s in self._solve_two_vectors((ub, ua), [located[1], located[0]], signed, cx, cy)
            )
        if wa == "length":  # length of a (direction known), angle of b (length known)
            a = va.angle
            p = cx * sp.cos(a) + cy * sp.sin(a)  # C along a
            q = cy * sp.cos(a) - cx * sp.sin(a)  # C across a
            root = sp.sqrt(vb.length**2 - q**2)
            out = []
            for branch in (1, -1):
                signed_la = p + branch * root  # sa * length of a
                bx, by = sb * (cx - signed_la * sp.cos(a)), sb * (cy - signed_la * sp.sin(a))
                phi = sp.atan2(by / vb.length, bx / vb.length) if not vb.length.is_positive else sp.atan2(by, bx)
                out.append(LoopSolution({ua: solve_linear(va.length, ua, sa * signed_la), ub: solve_linear(vb.angle, ub, phi)}))
            return tuple(out)
        # two angles: the triangle of A = sa*la, B = sb*lb and C
        A, B = sa * va.length, sb * vb.length
        c2 = cx**2 + cy**2
        gamma = sp.acos((A**2 + c2 - B**2) / (2 * A * sp.sqrt(c2)))
        base = sp.atan2(cy, cx)
        out = []
        for branch in (1, -1):
            phi_a = base + branch * gamma
            phi_b = sp.atan2((cy - A * sp.sin(phi_a)) / B, (cx - A * sp.cos(phi_a)) / B)
            out.append(LoopSolution({ua: solve_linear(va.angle, ua, phi_a), ub: solve_linear(vb.angle, ub, phi_b)}))
        return tuple(out)


def solve_linear(slot: sp.Expr, unknown: sp.Symbol, value: Any = 0) -> sp.Expr:
    """Solve ``slot(unknown) = value`` for an unknown that enters ``slot`` linearly.

    >>> x, y = sp.symbols("x y")
    >>> solve_linear(y + 2 * x, x, 1)
    1/2 - y/2
    """
    coeff = sp.diff(slot, unknown)
    if coeff == 0 or coeff.has(unknown):
        raise UnsupportedError(
            f"the unknown {unknown} enters {slot} non-linearly; give it as a length or an angle, or a sum with one"
        )
    return (value - slot.subs(unknown, 0)) / coeff


def harmonics(expr: Any, var: sp.Symbol) -> dict[sp.Expr, sp.Expr]:
    """Write ``expr`` as sum_nu c_nu e^{i nu var}: a map frequency -> coefficient.

    ``expr`` is a sum of sines and cosines whose arguments are linear in ``var`` (for
    example the across-component of a loop whose angles turn uniformly with ``var``).
    Exponentials of different frequencies are linearly independent, so ``expr``
    vanishes for every ``var`` exactly when every coefficient vanishes; frequencies
    that are equal only for special values of the parameters are kept apart, so the
    caller can ask when they coincide.

    >>> import sympy as sp
    >>> x, a = sp.symbols("x a", real=True)
    >>> sorted(harmonics(2 * sp.cos(x) + sp.sin(a * x), x).items(), key=str)
    [(-1, 1), (-a, I/2), (1, 1), (a, -I/2)]
    """
    expr = sp.expand(_sym(expr, "expression").rewrite(sp.exp))
    out: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(expr):
        factors = sp.Mul.make_args(sp.powsimp(term))
        exponent = sp.Add(*(f.exp for f in factors if isinstance(f, sp.exp)))
        rest = sp.Mul(*(f for f in factors if not isinstance(f, sp.exp)))
        if rest.has(var):
            raise UnsupportedError(f"{term} is not a sinusoid in {var}")
        freq = sp.expand(sp.diff(exponent, var) / sp.I)
        if freq.has(var):
            raise UnsupportedError(f"the phase of {term} is not linear in {var}")
        coeff = rest * sp.exp(sp.expand(exponent - sp.I * freq * var))
        match = next((f for f in out if sp.expand(f - freq) == 0), freq)
        out[match] = out.get(match, 0) + coeff
    return {f: c for f, c in out.items() if sp.expand(sp.powsimp(c)) != 0}
