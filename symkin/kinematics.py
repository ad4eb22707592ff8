"""Angular velocities of every link from contact conditions at the pitch points.

Each mesh gives one condition: the pitch point, taken as a point of either gear's link,
has one velocity (eq. 5 of the 2009 paper, with the link's axis as pole).  No Willis
inversion is used: the carrier's motion enters through the velocity of the planet axis.
The conditions are linear in the angular velocities; the solver returns every unknown
speed in closed form, or refuses with the degrees of freedom and an admissible choice.

    >>> from symkin import schemes
    >>> aa = schemes.two_row("AA", teeth=(100, 100, 101, 99))
    >>> aa.ratio("H", "1", fixed="4").rhs
    101/2
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Mapping, Sequence
from collections.abc import Mapping as MappingABC
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from symkin import symbols as S
from symkin._util.display import short_repr
from symkin.errors import (
    InputError,
    OverdeterminedError,
    SingularConfigurationError,
    UnderdeterminedError,
)
from symkin.laws import Law
from symkin.linsolve import generic_values, independent_rows, is_zero, nullspace, solve_factored, solve_rational
from symkin.model import FRAME, LinkKind, Mechanism, Mesh
from symkin.superposition import vec, velocity
from symkin.values import as_expr, is_quantity

__all__ = ["contact_condition", "kinematic_system", "KinematicSystem", "solve_speeds", "Speeds", "ratio"]


# --------------------------------------------------------------------------- conditions
def _omega(mech: Mechanism, link_name: str) -> sp.Expr:
    return sp.Integer(0) if link_name == FRAME else S.omega(link_name)


def contact_condition(mech: Mechanism, mesh: Mesh) -> sp.Eq:
    """Equal velocities of both gears of ``mesh`` at its pitch point.

    The mesh is drawn as in the paper's fig. 2: the line of centres along y, the pitch
    point on it, and the tangential component V_x of eq. (5) is equated.  Each gear's
    link has its own axis as pole; a planet axis moves with its carrier (eq. 5 again).
    For a mesh of a second level (both axes fixed on a planet, which carries planets
    itself) the velocities are taken in that planet's frame, where both axes stand still.

    >>> from symkin import schemes
    >>> ai = schemes.two_row("AI")
    >>> contact_condition(ai, ai.meshes[0])
    Eq(-omega_1*r_1, omega_23*r_2 + omega_H*(-r_1 - r_2))
    """
    geo = mech.mesh_geometry(mesh)
    if geo.kind == "bevel":
        return _bevel_condition(mech, geo)
    A, B, P = vec(0, 0), vec(0, geo.centre_distance), vec(0, geo.pitch_y)
    holder = mech.link(geo.holder) if geo.holder != FRAME else None

    def direct(link: Any) -> bool:  # on the main axis, or a planet on the holder with an axis of its own
        return link.kind is not LinkKind.PLANET or (link.carrier == geo.holder and link.arm != 0)

    if holder is not None and (holder.kind is LinkKind.PLANET or not (direct(geo.link_a) and direct(geo.link_b))):
        # a second level: both axes are fixed on a link (a planet carrying planets, or a
        # carrier whose planet carries the gear's link); in its frame each gear turns about
        # its fixed axis at its speed relative to it, and the link's own motion adds the
        # same velocity to both at the pitch point
        w_k = S.omega(holder.name)
        va = velocity(vec(0, 0), _omega(mech, geo.link_a.name) - w_k, P, A)
        vb = velocity(vec(0, 0), _omega(mech, geo.link_b.name) - w_k, P, B)
        omegas = [S.omega(n) for n in (geo.link_a.name, geo.link_b.name, holder.name) if n != FRAME]
        return sp.Eq(*(_collect(v[0], omegas) for v in (va, vb)), evaluate=False)
    # the main axis: where the non-planet gear turns (any point will do for two planets
    # on one carrier: the carrier's own velocity cancels between them)
    main_axis = B if geo.link_a.kind is LinkKind.PLANET and geo.link_b.kind is not LinkKind.PLANET else A

    def pitch_velocity(link, axis):
        if link.kind is LinkKind.PLANET:
            axis_velocity = velocity(vec(0, 0), _omega(mech, link.carrier), axis, main_axis)
        else:
            axis_velocity = vec(0, 0)
        return velocity(axis_velocity, _omega(mech, link.name), P, axis)

    va = pitch_velocity(geo.link_a, A)
    vb = pitch_velocity(geo.link_b, B)
    omegas = [S.omega(n) for n in (geo.link_a.name, geo.link_b.name, geo.link_a.carrier, geo.link_b.carrier) if n and n != FRAME]
    return sp.Eq(*(_collect(v[0], omegas) for v in (va, vb)), evaluate=False)


def _collect(expr: sp.Expr, omegas: Sequence[sp.Symbol]) -> sp.Expr:
    """``sp.collect(sp.expand(expr), omegas, sp.factor)`` for an expression linear in the
    angular velocities, without collect's general machinery: each speed's coefficient is
    factored (a monomial is its own factored form)."""
    expanded = sp.expand(expr)
    groups: dict[sp.Expr, list[sp.Expr]] = {}
    for term in sp.Add.make_args(expanded):
        rest, speed = term.as_independent(*omegas, as_Add=False)
        if speed != 1 and speed not in omegas:  # not linear: the general route
            return sp.collect(expanded, omegas, sp.factor)
        groups.setdefault(speed, []).append(rest)
    return sp.Add(*(speed * _factor(sp.Add(*terms)) for speed, terms in groups.items()))


def _factor(expr: sp.Expr) -> sp.Expr:
    """``sp.factor(expr)``, with a monomial returned as it is and a linear polynomial with
    integer coefficients as its content times its primitive part (leading coefficient
    positive in the order of its symbols): what ``sp.factor`` gives, a few times faster."""
    if expr.is_Atom or (expr.is_Mul and all(f.is_Atom or (f.is_Pow and f.base.is_Atom and f.exp.is_Integer) for f in expr.args)):
        return expr
    if expr.is_Add and all(t.is_Symbol or (t.is_Mul and len(t.args) == 2 and t.args[0].is_Integer and t.args[1].is_Symbol)
                           for t in expr.args):
        from sympy.core.mul import _keep_coeff

        content, primitive = sp.Poly(expr).primitive()
        if primitive.LC() < 0:
            content, primitive = -content, -primitive
        return _keep_coeff(sp.Integer(content), primitive.as_expr())
    return sp.factor(expr)


def _bevel_condition(mech: Mechanism, geo: Any) -> sp.Eq:
    """Equal velocities of a bevel side gear and a bevel pinion at their contact point.

    In the frame of the pinion's carrier (x along the pinion's radial axis, z along the
    main axis), the side gear turns about z at its speed relative to the carrier, the
    pinion about x at its own (relative) speed; the contact is at the side gear's pitch
    radius along x and the pinion's pitch radius above (+z) or below (-z) its axis.  Both
    velocities there are along y; the carrier's motion adds the same to both.
    """
    pinion, side = (geo.link_a, geo.link_b) if geo.link_a.axis == "radial" else (geo.link_b, geo.link_a)
    carrier = geo.holder
    w_side = _omega(mech, side.name) - _omega(mech, carrier)
    w_pin = S.omega(pinion.name)
    contact = sp.Matrix([geo.centre_distance, 0, geo.pitch_y])
    v_side = sp.Matrix([0, 0, w_side]).cross(contact)  # about the carrier's axis, through the origin
    v_pin = sp.Matrix([w_pin, 0, 0]).cross(contact)  # about the pinion's axis, the x axis through the origin
    omegas = [S.omega(n) for n in (side.name, pinion.name, carrier) if n != FRAME]
    sides = (v_side, v_pin) if side is geo.link_a else (v_pin, v_side)
    return sp.Eq(*(_collect(v[1], omegas) for v in sides), evaluate=False)


# --------------------------------------------------------------------------- the system
@dataclass(frozen=True)
class KinematicSystem:
    """The contact conditions of a mechanism as a linear system M omega = 0.

    Attributes
    ----------
    links : tuple of str
        The moving links, in the column order of :attr:`matrix`.
    equations : tuple of sympy.Eq
        One contact condition per mesh.
    matrix : sympy.ImmutableMatrix
        Coefficients of the angular velocities, one row per mesh.
    motions : sympy.ImmutableMatrix
        A basis of the admissible speed vectors (columns), for generic dimensions.
    dof : int
        Degrees of freedom.
    """

    mechanism: Mechanism
    links: tuple[str, ...]
    equations: tuple[sp.Eq, ...]
    matrix: sp.ImmutableMatrix
    motions: sp.ImmutableMatrix
    dof: int

    def rows(self, names: Sequence[str]) -> sp.Matrix:
        """The rows of the motion matrix for the links ``names``: each link's speed in terms of the independent motions."""
        return sp.Matrix([list(self.motions.row(self.links.index(n))) for n in names]) if names else sp.zeros(0, self.dof)

    def rank_of(self, names: Sequence[str]) -> int:
        """How many independent speeds the links ``names`` have."""
        return self.rows(names).rank() if names else 0

    def admissible_choice(self, prefer: Sequence[str] = ()) -> tuple[str, ...]:
        """A set of ``dof`` links whose speeds determine all the others.

        Links in ``prefer`` are kept when possible, then central links before planets.
        """
        order = list(dict.fromkeys([p for p in prefer if p in self.links] + self._by_preference()))
        combos = sorted(
            itertools.combinations(order, self.dof),
            key=lambda combo: (-sum(c in prefer for c in combo), [order.index(c) for c in combo]),
        )
        return next((c for c in combos if self.rank_of(c) == self.dof), ())

    def _by_preference(self) -> list[str]:
        mech = self.mechanism
        central = [n for n in self.links if mech.link(n).kind is LinkKind.CENTRAL]
        return central + [n for n in self.links if n not in central]


def kinematic_system(mech: Mechanism) -> KinematicSystem:
    """The contact conditions of ``mech`` and its degrees of freedom (cached).

    Ranks are computed exactly; when the dimensions are symbolic, for generic values of
    the symbols (random rationals, twice).

    >>> from symkin import schemes
    >>> kinematic_system(schemes.two_row("II")).dof
    2
    """

    def build() -> KinematicSystem:
        links = mech.link_names
        omegas = [S.omega(n) for n in links]
        equations = tuple(contact_condition(mech, mesh) for mesh in mech.meshes)
        if equations:
            matrix, _ = sp.linear_eq_to_matrix([e.lhs - e.rhs for e in equations], omegas)
        else:
            matrix = sp.zeros(0, len(links))
        matrix = sp.ImmutableMatrix(matrix.applyfunc(sp.expand))
        best = None
        for seed in (1, 2):
            generic = matrix.xreplace(generic_values(matrix.free_symbols, seed))
            basis = nullspace(generic)
            if best is None or basis.cols < best.cols:
                best = basis
            if not matrix.free_symbols:
                break
        assert best is not None  # the first seed always sets it
        return KinematicSystem(mech, links, equations, matrix, sp.ImmutableMatrix(best), best.cols)

    return mech._memo("kinematic_system", build)


# --------------------------------------------------------------------------- solving
def _resolve(mech: Mechanism, name: Any) -> str:
    if not isinstance(name, str):
        raise InputError(f"a link is named by a string such as '1' or 'H', got {name!r}")
    link = mech.link(name)
    return link.name




def _fmt_links(names: Sequence[str]) -> str:
    names = list(names)
    return " and ".join([", ".join(names[:-1]), names[-1]]) if len(names) > 1 else (names[0] if names else "none")


def check_known_links(mech: Mechanism, known: Sequence[str]) -> KinematicSystem:
    """Raise unless the speeds of ``known`` determine every other link exactly once."""
    system = kinematic_system(mech)
    dof = system.dof
    rank = system.rank_of(known)
    if rank == len(known) == dof:
        return system
    choice = system.admissible_choice(prefer=known)
    example = _fmt_links(choice)
    if rank < len(known):
        relation = _dependency(system, known)
        if len(known) <= dof:
            raise SingularConfigurationError(
                f"the speeds of {_fmt_links(known)} are not independent in this mechanism ({relation} "
                f"for every motion), so they cannot determine the other links: the law is singular for "
                f"these dimensions; give the speeds of {example} instead, or change the dimensions",
                dof=dof,
                admissible=choice,
            )
        raise OverdeterminedError(
            f"the mechanism has {dof} degree{'s' * (dof != 1)} of freedom but {len(known)} link speeds "
            f"are given ({relation} for every motion); give exactly {dof}, for example {example}",
            dof=dof,
            admissible=choice,
        )
    raise UnderdeterminedError(
        f"the mechanism has {dof} degree{'s' * (dof != 1)} of freedom but only {len(known)} link "
        f"speed{'s' * (len(known) != 1)} {'is' if len(known) == 1 else 'are'} given"
        f"{' (' + _fmt_links(known) + ')' if known else ''}; give exactly {dof}, for example {example}",
        dof=dof,
        admissible=choice,
    )


def _dependency(system: KinematicSystem, known: Sequence[str]) -> str:
    """The relation that ties the known speeds, derived exactly: one known link's speed in
    terms of the others (e.g. ``omega_4 = omega_1``)."""
    basis: list[str] = []
    for name in known:
        if system.rank_of(basis + [name]) > len(basis):
            basis.append(name)
    dependent = next((n for n in known if n not in basis), None)
    full = system.admissible_choice(prefer=basis)
    if dependent is None or not set(basis) <= set(full):
        return "they are tied"
    order = tuple(sorted(full))
    row = _coefficient_table(system.mechanism, order)[dependent]
    relation = _tidy(sp.Add(*(c * S.omega(n) for c, n in zip(row, order))))
    return f"{S.omega(dependent)} = {relation}"


@dataclass(frozen=True)
class Speeds(MappingABC):
    """Angular velocity of every link of a mechanism for given known speeds.

    A read-only mapping from link name to its angular velocity (the known ones included);
    gear names are accepted for the link that holds the gear.  Each link's law is put in
    its printed form only when it is asked for.

    Attributes
    ----------
    mechanism : Mechanism
    known : tuple of (str, sympy expression)
        The given speeds.
    coefficients : tuple of (str, tuple of sympy expression)
        For every moving link, d omega_link / d omega_k for each known link k, in the
        order of ``known``: constant laws (the speeds are linear in the known ones).
    unit : pint unit or None
        The unit of the first known speed given as a pint quantity (``rpm``), or None: the
        speeds are in rad/s; :meth:`quantities` gives them back in that unit.
    """

    mechanism: Mechanism
    known: tuple[tuple[str, sp.Expr], ...]
    coefficients: tuple[tuple[str, tuple[sp.Expr, ...]], ...]
    unit: Any = None
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)

    def __repr__(self) -> str:
        """``Speeds('AI1', 1=1, 2=-1/3, H=1/5, 4=0)``, under 200 characters."""
        return short_repr("Speeds", repr(self.mechanism.name), *(f"{n}={self[n]}" for n in self))

    def __getitem__(self, name: str) -> sp.Expr:
        link = self.mechanism.link(name).name
        if link == FRAME:
            return sp.Integer(0)
        if link not in self._cache:
            given = dict(self.known)
            if link in given:
                self._cache[link] = given[link]
            else:
                row = dict(self.coefficients)[link]
                self._cache[link] = _tidy(sp.Add(*(c * v for c, (_, v) in zip(row, self.known))))
        return self._cache[link]

    def __iter__(self) -> Iterator[str]:
        return (n for n, _ in self.coefficients)

    def __len__(self) -> int:
        return len(self.coefficients)

    @property
    def link_speeds(self) -> tuple[tuple[str, sp.Expr], ...]:
        """(link, speed) for every moving link, in the mechanism's order."""
        return tuple((n, self[n]) for n in self)

    def law(self, name: str) -> Law:
        """The speed of one link as a :class:`~symkin.laws.Law`."""
        link = self.mechanism.link(name).name
        given = ", ".join(f"{n}" for n, _ in self.known)
        return Law(S.omega(link), self[link], f"angular velocity of link {link}, given the speeds of {given}")

    def laws(self) -> tuple[Law, ...]:
        """The laws of every link whose speed was not given."""
        known = {n for n, _ in self.known}
        return tuple(self.law(n) for n in self if n not in known)

    def _repr_latex_(self) -> str:
        """Every link's speed as aligned display math, for Jupyter (:func:`symkin.latex`).

        >>> from symkin import schemes
        >>> print(schemes.single_row_AI(teeth=(20, 30, 80)).speeds({"1": 1, "4": 0})._repr_latex_())
        $\\displaystyle \\begin{aligned}
        \\omega_{2} &= - \\frac{1}{3} \\\\
        \\omega_{H} &= \\frac{1}{5}
        \\end{aligned}$
        """
        from symkin.printing import latex

        return f"$\\displaystyle {latex(self, aligned=True)}$"

    def in_unit(self, unit: Any) -> dict[str, sp.Expr]:
        """Every link's speed in ``unit`` (a pint unit or its name, ``"rpm"``), exact.

        >>> from symkin import schemes
        >>> schemes.two_row("AA", teeth=(54, 45, 44, 55)).speeds({"1": 10 * sp.pi, "4": 0}).in_unit("rpm")["H"]
        -7200
        """
        from symkin.values import unit_factor

        f = unit_factor(unit, "rad/s", what="the unit of the speeds")
        return {n: sp.cancel(self[n] / f) for n in self}

    def quantities(self, unit: Any = None) -> dict[str, Any]:
        """Every link's speed as a pint quantity: in ``unit``, or in the unit the known speeds were
        given in (rad/s when they were bare numbers); magnitudes exact (SymPy).

        >>> import pint
        >>> from symkin import schemes
        >>> rpm = pint.get_application_registry().rpm
        >>> speeds = schemes.two_row("AA", teeth=(54, 45, 44, 55)).speeds({"1": 300 * rpm, "4": 0})
        >>> speeds["H"], speeds.quantities()["H"]
        (-240*pi, <Quantity(-7200, 'revolutions_per_minute')>)
        """
        import pint

        unit = unit if unit is not None else (self.unit if self.unit is not None else "rad/s")
        reg = getattr(unit, "_REGISTRY", None) or pint.get_application_registry()
        return {n: reg.Quantity(v, unit) for n, v in self.in_unit(unit).items()}

    def coefficient(self, link: str, known_link: str) -> sp.Expr:
        """d omega_link / d omega_known: the constant factor in the linear law."""
        names = [n for n, _ in self.known]
        return dict(self.coefficients)[self.mechanism.link(link).name][names.index(self.mechanism.link(known_link).name)]


def _omega_symbols(expr: sp.Expr) -> list[sp.Symbol]:
    return sorted((s for s in expr.free_symbols if s.name.startswith("omega_")), key=str)


def _tidy(expr: sp.Expr) -> sp.Expr:
    """A law in the form a paper prints.

    One fraction, cancelled.  A numerator that factors into several sums is printed as
    their product ((r4 + r_s1)(r4 + r_s2)/(r_s1 r_s2) for two stages); over a monomial
    denominator a law with a constant term is split (1 + z2 z4/(z1 z3)); a numerator with
    angular velocities is grouped by them.
    """
    if (expr.is_Mul or expr.is_Pow) and not _omega_symbols(expr) and _small_factors(expr):
        # a product of small factors (n stages in series): factored factor by factor, never expanded
        factored = sp.factor(expr)
        num = sp.fraction(factored)[0]
        sums = [f for f in sp.Mul.make_args(num) if (f.base if f.is_Pow else f).is_Add]
        if len(sums) >= 2 or (sums and sums[0].is_Pow):
            return factored
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    speeds = _omega_symbols(num)
    if not speeds and num.is_Add:
        factored = sp.factor(num)
        sums = [f for f in sp.Mul.make_args(factored) if (f.base if f.is_Pow else f).is_Add]
        if len(sums) >= 2 or (sums and sums[0].is_Pow):
            return factored / sp.factor(den)
    if not den.is_Add:
        split = sp.expand(num / den)
        if any(term.is_number for term in sp.Add.make_args(split)):
            return split
    if speeds:
        num = sp.collect(sp.expand(num), speeds, sp.factor)
    return sp.factor_terms(num) / sp.factor_terms(den)


def _small_factors(expr: sp.Expr, terms: int = 8) -> bool:
    """Every factor of the product ``expr`` is a sum of at most ``terms`` terms, built
    without nested sums (so that factoring it alone is cheap)."""
    for f in sp.Mul.make_args(expr):
        base = f.base if f.is_Pow else f
        if base.is_Add and (len(base.args) > terms or any(a.has(sp.Add) for a in base.args)):
            return False
        if base.is_Mul and not _small_factors(base, terms):
            return False
    return True


def solve_speeds(mech: Mechanism, known: Mapping[str, Any], *, joined: Sequence[tuple[str, str]] = ()) -> Speeds:
    """Every link's angular velocity, in closed form, from the known speeds.

    Parameters
    ----------
    mech : Mechanism
    known : mapping of link name to speed
        Exactly ``mech.dof`` independent links (fewer with ``joined``); a fixed link has
        speed 0.  Values may be numbers (rad/s), symbols or expressions (of time too), or
        pint quantities (``300 * ureg.rpm``), converted to rad/s.
    joined : sequence of (link, link)
        Pairs of links made to turn together (an engaged clutch).

    Returns
    -------
    Speeds

    Raises
    ------
    UnderdeterminedError, OverdeterminedError, SingularConfigurationError
        When the known speeds do not determine the motion exactly once.

    Examples
    --------
    >>> import sympy as sp
    >>> from symkin import schemes, symbols as S
    >>> ai = schemes.two_row("AI")
    >>> sp.factor(ai.speeds({"1": S.omega("1"), "4": 0})["H"])
    omega_1*r_1*r_3/(r_1*r_3 + r_2*r_4)
    >>> import pint
    >>> rpm = pint.get_application_registry().rpm
    >>> schemes.two_row("AA", teeth=(54, 45, 44, 55)).speeds({"1": 300 * rpm, "4": 0})["H"]
    -240*pi
    """
    if not isinstance(known, MappingABC):
        raise InputError(f"known speeds are a mapping of link name to speed, got {known!r}")
    resolved: dict[str, sp.Expr] = {}
    unit = next((v.units for v in known.values() if is_quantity(v)), None)
    for name, value in known.items():
        link = _resolve(mech, name)
        if link == FRAME:
            raise InputError("the frame (link 0) does not move; give the speeds of moving links")
        if link in resolved:
            raise InputError(f"the speed of link {link} is given twice (as {name!r} too); give it once")
        resolved[link] = as_expr(value, what=f"speed of link {link}", unit="rad/s")
    names = tuple(resolved)
    pairs = _joined_pairs(mech, joined)
    order = tuple(sorted(names))
    if pairs:
        table = _joined_table(mech, order, pairs)
    else:
        check_known_links(mech, names)
        table = _coefficient_table(mech, order)
    permutation = [order.index(n) for n in names]
    coefficients = tuple((n, tuple(table[n][i] for i in permutation)) for n in mech.link_names)
    return Speeds(mech, tuple(resolved.items()), coefficients, unit)


def _coefficient_table(mech: Mechanism, names: tuple[str, ...]) -> dict[str, tuple[sp.Expr, ...]]:
    """d omega_link / d omega_k for every link and every known link k (cached).

    The contact conditions M omega = 0 split into A omega_unknown = B omega_known; A and B
    hold polynomials in the dimensions, so the system is solved in their fraction field,
    block by block (:func:`solve_factored`): a train of n stages in series is n small
    solves, and an entry keeps its factored form where the cancelled one would be large.
    The composed forms are kept beside the table (:func:`_factored_coefficient`).
    """
    Table = dict[str, tuple[sp.Expr, ...]]

    def build() -> tuple[Table, Table]:
        system = kinematic_system(mech)
        unknown = [n for n in system.links if n not in names]
        table = {n: tuple(sp.Integer(int(n == k)) for k in names) for n in names}
        if not unknown:
            return table, table
        column = {n: i for i, n in enumerate(system.links)}
        rows = independent_rows(system.matrix.extract(list(range(system.matrix.rows)), [column[u] for u in unknown]))
        if len(rows) < len(unknown):
            raise SingularConfigurationError(
                f"the speeds of {_fmt_links(names)} do not determine every other link",
                dof=system.dof,
                admissible=system.admissible_choice(prefer=names),
            )
        A = system.matrix.extract(rows, [column[u] for u in unknown])
        B = -system.matrix.extract(rows, [column[k] for k in names])
        solved = solve_factored(A, B)
        if solved is None:  # (an infinite or undefined entry is refused where it is solved)
            raise SingularConfigurationError(
                f"the contact conditions cannot be solved for the speeds of {_fmt_links(names)} with these dimensions",
                dof=system.dof,
                admissible=system.admissible_choice(prefer=names),
            )
        X, composed = solved
        factored = dict(table)
        for i, n in enumerate(unknown):
            table[n] = tuple(X[i, j] for j in range(len(names)))
            factored[n] = tuple(composed[i, j] for j in range(len(names)))
        return table, factored

    return mech._memo(("coefficients", names), build)[0]


def _factored_coefficient(mech: Mechanism, known_links: Sequence[str], link: str, known: str) -> sp.Expr:
    """d omega_link / d omega_known, the links in ``known_links`` given (no clutch joined), as the
    block solve composed it (a product of the stages' factors for a train in series), for laws
    that factor it anyway (ratios, a multistage train's speeds)."""
    names = tuple(sorted(_resolve(mech, k) for k in known_links))  # the table's key, as solve_speeds makes it
    link, known = _resolve(mech, link), _resolve(mech, known)
    _coefficient_table(mech, names)
    factored = mech._memo(("coefficients", names), lambda: None)[1]
    return factored[link][names.index(known)]


def _joined_pairs(mech: Mechanism, joined: Sequence[tuple[str, str]]) -> tuple[tuple[str, str], ...]:
    pairs = []
    for pair in joined:
        if isinstance(pair, (str, bytes)) or not hasattr(pair, "__len__") or len(pair) != 2:
            raise InputError(f"a clutch joins two links, given as a pair (A, B), got {pair!r}")
        a, b = (_resolve(mech, x) for x in pair)
        if a == b:
            raise InputError(f"a clutch joins two different links, got {a} twice")
        pairs.append(tuple(sorted((a, b))))
    return tuple(sorted(set(pairs)))  # type: ignore[arg-type]


def _joined_table(
    mech: Mechanism, names: tuple[str, ...], pairs: tuple[tuple[str, str], ...]
) -> dict[str, tuple[sp.Expr, ...]]:
    """d omega_link / d omega_k with the contact conditions and ``omega_a = omega_b`` for each
    joined pair; the frame (link 0) may be joined too (a brake).  Raises when the known
    speeds do not set every link, or contradict the joints."""

    def build() -> dict[str, tuple[sp.Expr, ...]]:
        system = kinematic_system(mech)
        links = list(system.links)
        column = {n: i for i, n in enumerate(links)}
        rows = [list(system.matrix.row(i)) for i in range(system.matrix.rows)]
        for a, b in pairs:
            row = [sp.Integer(0)] * len(links)
            if a != FRAME:
                row[column[a]] += 1
            if b != FRAME:
                row[column[b]] -= 1
            rows.append(row)
        N = sp.Matrix(rows) if rows else sp.zeros(0, len(links))
        unknown = [n for n in links if n not in names]
        A = N.extract(list(range(N.rows)), [column[u] for u in unknown])
        B = -N.extract(list(range(N.rows)), [column[k] for k in names])
        generic = generic_values(N.free_symbols, 1)
        Ag, Bg = A.subs(generic), B.subs(generic)
        rank = Ag.rank() if unknown else 0
        joints = ", ".join(f"{a} = {b}" for a, b in pairs)
        if rank < len(unknown):
            free = sorted({unknown[i] for v in Ag.nullspace() for i, x in enumerate(v) if x != 0})
            raise UnderdeterminedError(
                f"with {_fmt_links(names) if names else 'no link'} given and {joints} turning together, "
                f"{_fmt_links(free)} can still turn freely: hold or join more links",
                dof=system.dof, admissible=(),
            )
        if Ag.row_join(Bg).rank() > rank:
            raise OverdeterminedError(
                f"{_fmt_links(names)} cannot turn as given with {joints} turning together: the joints and the "
                "contact conditions hold them (the train is locked); release a clutch or a brake",
                dof=system.dof, admissible=(),
            )
        table = {n: tuple(sp.Integer(int(n == k)) for k in names) for n in names}
        if not unknown:
            return table
        chosen = independent_rows(A)
        X = solve_rational(A.extract(chosen, list(range(A.cols))), B.extract(chosen, list(range(B.cols))))
        if X is None:
            raise SingularConfigurationError(
                f"the joints {joints} and the contact conditions cannot be solved for these dimensions",
                dof=system.dof, admissible=(),
            )
        for i, n in enumerate(unknown):
            table[n] = tuple(sp.cancel(X[i, j]) for j in range(len(names)))
        return table

    return mech._memo(("joined", names, pairs), build)


def ratio(mech: Mechanism, driver: str, driven: str, fixed: str | Sequence[str] | None = None) -> Law:
    """The ratio i_ab^(c) = omega_a / omega_b with the link(s) c fixed.

    Parameters
    ----------
    driver, driven : str
        Links a and b (gear names are accepted for their links).
    fixed : str or sequence of str, optional
        Link(s) held still; together with the driver they must determine the motion.

    Examples
    --------
    >>> from symkin import schemes
    >>> print(schemes.two_row("AI", teeth=True).ratio("1", "H", fixed="4"))
    i_{1H}^{(4)} = 1 + z_2*z_4/(z_1*z_3)
    """
    fixed_names: tuple[str, ...]
    if fixed is None:
        fixed_names = ()
    elif isinstance(fixed, str):
        fixed_names = (fixed,)
    elif hasattr(fixed, "__iter__"):
        fixed_names = tuple(fixed)
    else:
        raise InputError(f"fixed names a link or a sequence of links, got {fixed!r}")
    a, b = _resolve(mech, driver), _resolve(mech, driven)
    cs = tuple(_resolve(mech, c) for c in fixed_names)
    if a == b:
        raise InputError(f"driver and driven are the same link {a}; name two different links")
    if a in cs or b in cs:
        raise InputError(f"link {a if a in cs else b} cannot be both fixed and {'driver' if a in cs else 'driven'}")
    if a == FRAME:
        raise InputError("the frame (link 0) cannot drive; name a moving link as driver")
    if b == FRAME:
        raise InputError("the frame (link 0) does not turn, so it cannot be driven; name a moving link as driven")
    return mech._memo(("ratio", a, b, cs), lambda: _ratio(mech, a, b, cs))


def _ratio(mech: Mechanism, a: str, b: str, cs: tuple[str, ...]) -> Law:
    known: dict[str, Any] = {c: 0 for c in cs if c != FRAME}
    fixed_links = tuple(known)
    system = kinematic_system(mech)

    def drives(link: str) -> bool:  # with the fixed links still, does this link's speed set the motion?
        chosen = fixed_links + (link,)
        return system.rank_of(chosen) == len(chosen) == system.dof

    def coefficient(of: str, by: str) -> sp.Expr:  # d omega_of / d omega_by, as composed (factored)
        solve_speeds(mech, {**known, by: S.omega(by)})
        return _factored_coefficient(mech, (*fixed_links, by), of, by)

    if drives(a):  # the usual case: omega_b = c omega_a
        c = coefficient(b, a)
        if is_zero(c):
            raise SingularConfigurationError(
                f"link {b} stays still when {a} drives with {_fmt_links(cs)} fixed, so the ratio is infinite",
                dof=system.dof,
                admissible=(a,) + cs,
            )
        value = _tidy(1 / c)
    elif drives(b):  # the driver cannot move while b turns: the ratio is zero, or b sets a
        value = _tidy(coefficient(a, b))
    else:
        check_known_links(mech, fixed_links + (a,))  # raises with the degrees of freedom and a choice
        raise SingularConfigurationError(  # pragma: no cover - check_known_links has raised
            f"neither {a} nor {b} moves with {_fmt_links(cs)} fixed", dof=system.dof, admissible=()
        )
    desc = f"ratio omega_{a}/omega_{b} with {_fmt_links(cs) if cs else 'nothing'} fixed"
    return Law(S.ratio_symbol(a, b, cs), value, desc)
