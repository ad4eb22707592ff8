"""The derived conditions as a reader sees them: each a relation, printable as text and LaTeX.

:class:`Condition` is one condition (limits, internal gear, coaxiality, assembly,
neighbours, placement); :func:`derived_conditions` lists every condition of a
:class:`~symkin.synthesis.problem.Problem` with its planet count put in
(:meth:`~symkin.synthesis.problem.Problem.conditions`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy as sp

from symkin.model import FRAME
from symkin.synthesis.parts import AssemblyGroup, AssemblyRow
from symkin.synthesis.request import undercut_minimum

if TYPE_CHECKING:
    from symkin.synthesis.problem import Problem

__all__ = ["Condition", "derived_conditions", "gcd"]


class gcd(sp.Function):
    """The greatest common divisor of integers, as printed in a condition (never evaluated)."""

    def _latex(self, printer: Any) -> str:
        return r"\gcd\left(" + ", ".join(printer._print(a) for a in self.args) + r"\right)"

    def _sympystr(self, printer: Any) -> str:
        return "gcd(" + ", ".join(printer._print(a) for a in self.args) + ")"


@dataclass(frozen=True)
class Condition:
    """One derived condition, printable as text and LaTeX.

    Attributes
    ----------
    kind : str
        ``"limits"``, ``"internal gear"``, ``"coaxiality"``, ``"assembly"``, ``"neighbours"``,
        ``"placement"`` or ``"ratio"``.
    subject : str
        What it is about (a planet, a carrier and its planets, a gear).
    relation : sympy relation
        The condition (an equation, an inequality, or ``Contains(x, Integers)``).
    description : str
    integers : tuple of Symbol
        Integers that must exist for the relation to hold (assembly).
    """

    kind: str
    subject: str
    relation: Any
    description: str = ""
    integers: tuple[sp.Symbol, ...] = ()

    def text(self) -> str:
        """The relation as one line of text."""
        rel = self.relation
        if isinstance(rel, sp.Contains):
            body = f"{sp.sstr(rel.args[0])} is an integer"
        elif isinstance(rel, sp.And) and _is_range(rel):
            lo, x, hi = _range_parts(rel)
            body = f"{lo} <= {x} <= {hi}"
        elif isinstance(rel, sp.Equality):
            body = f"{sp.sstr(rel.lhs)} = {sp.sstr(rel.rhs)}"
        else:
            body = sp.sstr(rel)
        if self.integers:
            body += f" for some integers {', '.join(map(str, self.integers))}"
        return body

    def latex(self) -> str:
        r"""The relation in LaTeX (:func:`symkin.latex`).

        >>> from symkin.trains import load_train
        >>> from symkin.synthesis.problem import derive
        >>> print(derive(load_train("simple"), driver="S", driven="C", fixed="R").conditions()[3].latex())
        \frac{z_{r} + z_{s}}{3} \in \mathbb{Z}
        """
        from symkin.printing import latex

        rel = self.relation
        if isinstance(rel, sp.And) and _is_range(rel):
            lo, x, hi = _range_parts(rel)
            tex = rf"{latex(lo)} \leq {latex(x)} \leq {latex(hi)}"
        elif isinstance(rel, sp.Contains):
            tex = latex(rel.args[0]) + r" \in \mathbb{Z}"
        else:
            tex = latex(rel)
        if self.integers:
            tex += r", \quad " + ", ".join(latex(n) for n in self.integers) + r" \in \mathbb{Z}"
        return tex

    def __str__(self) -> str:
        return f"{self.kind} ({self.subject}): {self.text()}" if self.subject else f"{self.kind}: {self.text()}"

    def to_json(self) -> dict[str, Any]:
        """The condition as JSON: its kind, subject, text, LaTeX and description."""
        return {"kind": self.kind, "subject": self.subject, "text": self.text(), "latex": self.latex(),
                "description": self.description}


def _is_range(rel: sp.And) -> bool:
    a, b = rel.args if len(rel.args) == 2 else (None, None)
    return isinstance(a, sp.LessThan) and isinstance(b, sp.LessThan) and (a.rhs == b.lhs or a.lhs == b.rhs)


def _range_parts(rel: sp.And) -> tuple[Any, Any, Any]:
    a, b = rel.args
    if a.rhs == b.lhs:
        return a.lhs, a.rhs, b.rhs
    return b.lhs, b.rhs, a.rhs


def derived_conditions(problem: Problem) -> tuple[Condition, ...]:
    """Every derived condition of a problem, the planet count substituted (:meth:`Problem.conditions`)."""
    return (*_limits(problem), *_coaxiality(problem), *_assembly(problem), *_neighbours(problem),
            *_meshing_planets(problem))


def _limits(problem: Problem) -> list[Condition]:
    o = problem.options
    z = sp.Symbol("z", positive=True, integer=True)
    out = [Condition("limits", "every gear", sp.And(sp.Le(o.zmin, z), sp.Le(z, o.zmax)),
                     f"every unknown tooth number; z >= {undercut_minimum(o.pressure_angle, o.addendum)} "
                     f"cuts no undercut at alpha = {o.pressure_angle} deg, h_a* = {o.addendum}")]
    for im in problem.internal_meshes:
        if o.ring_difference and (im.internal_teeth.free_symbols or im.external_teeth.free_symbols):
            out.append(Condition("internal gear", im.internal,
                                 sp.Ge(im.internal_teeth, im.external_teeth + o.ring_difference),
                                 f"internal gear {im.internal} at least {o.ring_difference} teeth more than "
                                 f"{im.external} (no tip interference)"))
    return out


def _coaxiality(problem: Problem) -> list[Condition]:
    out = []
    for row in problem.coaxiality:
        if row.tolerance == 0:
            rel: Any = sp.Eq(row.lhs, row.rhs, evaluate=False)
            what = "both meshes put the planet axis at one distance"
        else:
            rel = sp.Le(sp.Abs(row.expr), row.tolerance)
            what = f"the reference centre distances within {row.tolerance} of each other (profile shift)"
        if rel is not sp.true:
            out.append(Condition("coaxiality", f"planet {row.planet}", rel, what))
    return out


def _assembly(problem: Problem) -> list[Condition]:
    out = []
    for group in problem.assembly:
        k = problem.count[group.planets[0]]
        if k < 2:
            continue
        for arow in group.rows:
            out.append(_assembly_condition(group, arow, k))
    return out


def _neighbours(problem: Problem) -> list[Condition]:
    """Copies of one planet kind clear each other, gear by gear."""
    o = problem.options
    out = []
    for rim in problem.rims:
        k = problem.count[rim.planet]
        if k < 2:
            continue
        arm = problem.arm_of(rim.planet)
        a = arm.arm if o.shift == 0 else sp.Symbol(f"a_w{rim.planet}", positive=True)
        rel = sp.StrictGreaterThan(2 * a * sp.sin(sp.pi / k), 2 * rim.tip_radius + o.clearance * rim.module)
        out.append(Condition("neighbours", f"planet {rim.planet}, gear {rim.gear}", rel,
                             f"{k} copies of {rim.planet}: the chord between neighbouring axes exceeds the tip "
                             f"diameter of {rim.gear}" + (f" plus a clearance of {o.clearance} m" if o.clearance else "")))
    return out


def _meshing_planets(problem: Problem) -> list[Condition]:
    """Two meshing planet kinds: placed (a triangle), and clear of the copies they do not mesh."""
    o = problem.options
    out = []
    for pair in problem.pairs:
        k = problem.count[pair.first]
        a, b = problem.arm_of(pair.first).arm, problem.arm_of(pair.second).arm
        d = pair.centre_distance
        out.append(Condition("placement", f"planets {pair.first}, {pair.second}",
                             sp.And(sp.Le(sp.Abs(a - b), d), sp.Le(d, a + b)),
                             f"the arms of {pair.first} and {pair.second} and their centre distance form a triangle"))
        if k >= 2:
            gamma = sp.Symbol(f"gamma_{pair.first}{pair.second}")
            t = sp.Symbol("t", positive=True, integer=True)
            A, B = sp.Symbol(f"a_{pair.first}", positive=True), sp.Symbol(f"a_{pair.second}", positive=True)
            ra, rb = pair.tip_radii
            dist2 = A**2 + B**2 - 2 * A * B * sp.cos(gamma + 2 * sp.pi * t / k)
            rel = sp.StrictGreaterThan(dist2, (ra + rb + o.clearance * pair.module) ** 2)
            out.append(Condition("neighbours", f"planets {pair.first}, {pair.second}", rel,
                                 f"for t = 1 .. {k - 1}: copy t of {pair.second} clears {pair.first} (tip circles "
                                 f"of {pair.gears[0]} and {pair.gears[1]}); {A} = {sp.sstr(a)}, {B} = {sp.sstr(b)}, "
                                 f"{gamma} = {sp.sstr(pair.angle)} (the angle between their axes)"))
    return out


def _assembly_condition(group: AssemblyGroup, row: AssemblyRow, k: int) -> Condition:
    subject = f"{', '.join(group.planets)} on carrier {group.carrier if group.carrier != FRAME else 'the frame'}"
    rhs = sp.factor_terms(row.rhs(k))
    coeffs = [c for _, c in row.coefficients]
    if row.kind == "integral":
        return Condition("assembly", subject, sp.Contains(rhs, sp.Integers, evaluate=False),
                         f"{k} copies can be assembled (whole pitches of the gears on the main axis)")
    if row.kind == "divisible":
        g = coeffs[0] if len(coeffs) == 1 else gcd(*coeffs)
        return Condition("assembly", subject, sp.Contains(sp.factor_terms(row.numerator / (row.denominator * k * g)),
                                                          sp.Integers, evaluate=False),
                         f"{k} copies can be assembled: the pitches to make up are a multiple of the gcd")
    if row.kind == "zero":
        return Condition("assembly", subject, sp.Eq(row.numerator, 0), f"{k} copies can be assembled")
    lhs = sp.Add(*(c * n for n, c in row.coefficients))
    return Condition("assembly", subject, sp.Eq(lhs, rhs, evaluate=False),
                     f"{k} copies can be assembled (these integers are shared with the other rows of the group)",
                     integers=tuple(n for n, _ in row.coefficients))
