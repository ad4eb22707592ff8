"""Exact solving of the linear conditions of a train: the linear algebra behind the kinematics.

The contact conditions are linear in the angular velocities with coefficients that are
rational functions of the dimensions (radii or tooth numbers).  These functions solve such
systems exactly: over the rationals with SymPy's sparse DomainMatrix where the entries are
numbers, by triangular blocks and Cramer-free elimination where they are symbols, and with a
canonical form (expanded, cancelled) while it stays small.  Whether a row is independent or a
coefficient vanishes is decided for generic dimensions (random rationals), then exactly.

    >>> import sympy as sp
    >>> a, b = sp.symbols("a b", positive=True)
    >>> solve_factored(sp.Matrix([[a, -b], [1, 1]]), sp.Matrix([[0], [1]]))[0].T
    Matrix([[b/(a + b), a/(a + b)]])
"""

from __future__ import annotations

import math
import random
from typing import Any

import sympy as sp

__all__ = ["generic_values", "nullspace", "independent_rows", "solve_rational", "solve_factored", "solve_whole",
           "triangular_blocks", "is_zero"]


def generic_values(symbols: set[sp.Symbol], seed: int) -> dict[sp.Symbol, sp.Rational]:
    """Random rationals (reproducible from ``seed``) for ``symbols``: "generic" dimensions, at
    which a rank or a zero seen is, with probability one, the rank or the zero for all.

    >>> generic_values({sp.Symbol("a")}, 1)
    {a: ...}
    """
    rng = random.Random(seed)
    return {s: sp.Rational(rng.randint(1000, 9999), rng.randint(100, 999)) for s in sorted(symbols, key=str)}


def nullspace(M: sp.Matrix) -> sp.Matrix:
    """A basis of the null space of a rational matrix, as columns: one per free column of
    its reduced row echelon form, 1 there and minus the pivots' entries (``Matrix.nullspace``)."""
    n = M.cols
    if not M.rows:
        return sp.eye(n)
    dM = _domain_matrix(M)
    if dM is None:  # irrational constants (sqrt(2), pi, exp(1000)): SymPy's general route
        basis = M.nullspace()
        return sp.Matrix.hstack(*basis) if basis else sp.zeros(n, 0)
    rref, pivots = dM.rref()
    rows = rref.to_sdm()
    columns = []
    for free in (j for j in range(n) if j not in set(pivots)):
        v = [sp.Integer(0)] * n
        v[free] = sp.Integer(1)
        for i, p in enumerate(pivots):
            entry = rows.get(i, {}).get(free)
            if entry:
                v[p] = -rref.domain.to_sympy(entry)
        columns.append(v)
    return sp.Matrix(n, len(columns), lambda i, j: columns[j][i]) if columns else sp.zeros(n, 0)


def independent_rows(A: sp.Matrix) -> list[int]:
    """Rows of A that are independent for generic dimensions, up to A's column count: the
    first row, then each row independent of those before it (the pivots of A's transpose
    in reduced row echelon form)."""
    generic = A.xreplace(generic_values(A.free_symbols, 1)) if A.free_symbols else A
    if not generic.rows:
        return []
    dM = _domain_matrix(generic.T)
    if dM is None:  # irrational constants: row by row with SymPy's rank
        chosen: list[int] = []
        for i in range(A.rows):
            if len(chosen) == A.cols:
                break
            if generic.extract([*chosen, i], list(range(A.cols))).rank() > len(chosen):
                chosen.append(i)
        return chosen
    _, pivots = dM.rref()
    return list(pivots)[: A.cols]


def _domain_matrix(M: sp.Matrix) -> Any:
    """A matrix of rational numbers as a sparse DomainMatrix over QQ (fast elimination);
    None when an entry is not rational (an irrational constant such as sqrt(2) or pi)."""
    from sympy.polys.domains import QQ
    from sympy.polys.matrices import DomainMatrix

    if any(not e.is_Rational for e in M.values()):
        return None
    rows = {}
    for i in range(M.rows):
        row = {j: QQ.from_sympy(M[i, j]) for j in range(M.cols) if M[i, j] != 0}
        if row:
            rows[i] = row
    return DomainMatrix(rows, M.shape, QQ)


def solve_rational(A: sp.Matrix, B: sp.Matrix) -> sp.Matrix | None:
    """X with A X = B, computed in the fraction field of A's and B's entries (see
    :func:`solve_factored`); None when A is singular."""
    solved = solve_factored(A, B)
    return None if solved is None else solved[0]


def solve_factored(A: sp.Matrix, B: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix] | None:
    """X with A X = B, computed in the fraction field of A's and B's entries, twice:
    cancelled where that is cheap, and as composed (products of the blocks' solutions).

    Non-polynomial atoms (cos(beta), sqrt(2), ...) are treated as independent generators.
    Returns None when A is singular.

    The system is first put in block triangular form (a matching of equations to
    unknowns, then the strongly connected components of the unknowns' dependencies): a
    train of stages in series splits into one small block per stage.  Each block is
    solved in the fraction field of its own entries, and the solutions are composed as
    products and sums without expanding them; an entry whose expanded form is small is
    then brought to the cancelled form of the whole fraction field (the form a single
    solve gives), a larger one keeps its factored form (the total ratio of n stages in
    series is a product of n stage ratios, whose expanded numerator has 2^n terms).
    """
    if A.rows != A.cols:
        single = solve_whole(A, B)
        return None if single is None else (single, single)
    entries = [e for e in list(A) + list(B) if e != 0]
    atoms = {a for e in entries for a in sp.preorder_traversal(e) if _is_generator(a)}
    to_dummy = {a: sp.Dummy() for a in atoms}
    back = {d: a for a, d in to_dummy.items()}
    if to_dummy:
        A, B = A.xreplace(to_dummy), B.xreplace(to_dummy)
    A, B = _without_denominators(A, B)
    blocks = triangular_blocks(A)
    if blocks is None:
        return None
    if len(blocks) == 1:  # nothing to split: one solve
        whole = solve_whole(A, B)
        if whole is None:
            return None
        whole = whole.xreplace(back) if back else whole
        return whole, whole
    composed = _composed(A, B, blocks)
    if composed is None:
        return None
    result = _canonical(composed, A, B)
    if back:
        return result.xreplace(back), composed.xreplace(back)
    return result, composed


def _composed(A: sp.Matrix, B: sp.Matrix, blocks: list[tuple[list[int], list[int]]]) -> sp.Matrix | None:
    """X with A X = B, block by block in the order of ``blocks`` (:func:`triangular_blocks`), each block's
    solution composed with the earlier blocks' without expanding; None when a block is singular."""
    X: list[list[sp.Expr]] = [[sp.Integer(0)] * B.cols for _ in range(A.cols)]
    nonzero: list[list[tuple[int, sp.Expr]]] = [[] for _ in range(A.rows)]
    for (r, c), value in sorted(A.todok().items()):
        nonzero[r].append((c, value))
    for rows, cols in blocks:
        inside = set(cols)
        outside = sorted({c for r in rows for c, _ in nonzero[r] if c not in inside})
        # the block's own solution: X_block = M - L X_outside, M = A_bb^-1 B_b, L = A_bb^-1 A_b,outside
        local = _block_solve(
            [[A[r, c] for c in cols] for r in rows],
            [[A[r, c] for c in outside] + [B[r, j] for j in range(B.cols)] for r in rows],
        )
        if local is None:
            return None
        for a, c in enumerate(cols):
            coefficients, given = local[a][: len(outside)], local[a][len(outside):]
            for j in range(B.cols):
                terms = [given[j]] + [-k * X[o][j] for k, o in zip(coefficients, outside) if k != 0 and X[o][j] != 0]
                X[c][j] = sp.Add(*terms)
    return sp.Matrix(X)


def _without_denominators(A: sp.Matrix, B: sp.Matrix) -> tuple[sp.Matrix, sp.Matrix]:
    """Each equation (a row of A and B) times the lcm of its entries' denominators, so the
    blocks are solved over polynomials (working pitch radii of a profile-shifted mesh,
    ``60 z_p/(z_p + z_s)``, are fractions); the solution is unchanged."""
    A, B = A.as_mutable(), B.as_mutable()
    for r in range(A.rows):
        row = [e for e in [*A.row(r), *B.row(r)] if e != 0]
        dens = [sp.fraction(sp.together(e))[1] for e in row]
        den = sp.lcm_list(dens) if any(d != 1 for d in dens) else sp.Integer(1)
        if den != 1:
            A[r, :] = (A.row(r) * den).applyfunc(sp.cancel)
            B[r, :] = (B.row(r) * den).applyfunc(sp.cancel)
    return A, B


def _block_solve(block: list[list[sp.Expr]], rhs: list[list[sp.Expr]]) -> list[list[sp.Expr]] | None:
    """``block^-1 rhs`` in the fraction field of the entries' symbols, each entry cancelled;
    None when the block is singular.  Solved without fractions (one denominator), then
    each entry cancelled once."""
    from sympy.polys.domains import QQ, ZZ
    from sympy.polys.matrices import DomainMatrix
    from sympy.polys.matrices.exceptions import DMNonInvertibleMatrixError
    from sympy.polys.polyerrors import CoercionFailed

    n = len(block)
    symbols = sorted({s for row in block + rhs for e in row for s in e.free_symbols}, key=sp.default_sort_key)
    for ground in (ZZ, QQ):  # integer polynomials, or rational coefficients
        ring = ground[tuple(symbols)] if symbols else QQ
        try:
            M = DomainMatrix([[ring.from_sympy(e) for e in row] for row in block], (n, n), ring)
            R = DomainMatrix([[ring.from_sympy(e) for e in row] for row in rhs], (n, len(rhs[0])), ring)
        except (CoercionFailed, ValueError):  # a rational coefficient in ZZ[...]
            continue
        break
    else:  # pragma: no cover - entries are polynomials with rational coefficients
        return None
    try:
        num, den = M.solve_den(R)
    except (DMNonInvertibleMatrixError, ZeroDivisionError):
        return None
    if den == ring.zero:
        return None
    out = []
    for row in num.to_list():
        values = []
        for e in row:
            if not symbols:
                values.append(ring.to_sympy(e) / ring.to_sympy(den))
                continue
            p, q = e.cancel(den)
            values.append(ring.to_sympy(p) / ring.to_sympy(q))
        out.append(values)
    if any(v.has(sp.zoo, sp.nan, sp.oo) for row in out for v in row):
        return None
    return out


def triangular_blocks(A: sp.Matrix) -> list[tuple[list[int], list[int]]] | None:
    """The blocks (rows, columns) of A in block triangular form, each block's columns
    depending only on its own and earlier blocks'; None when no assignment of one
    equation to each unknown exists (A is singular for every value of its symbols)."""
    n = A.cols
    pattern = [[c for c in range(n) if A[r, c] != 0] for r in range(A.rows)]
    row_of = _matching(pattern, n)
    if row_of is None:
        return None
    # unknown c depends on the other unknowns of its equation; Tarjan's components come
    # out dependencies first
    depends = [[d for d in pattern[row_of[c]] if d != c] for c in range(n)]
    return [([row_of[c] for c in cols], cols) for cols in _components(depends)]


def _matching(pattern: list[list[int]], n: int) -> list[int] | None:
    """The equation assigned to each of the ``n`` unknowns (``pattern[r]``: the unknowns of equation r), by
    Kuhn's augmenting paths; None when some equation finds none."""
    row_of: list[int | None] = [None] * n

    def augment(r: int) -> bool:  # Kuhn's augmenting path from equation r
        seen: set[int] = set()
        frames: list[list[Any]] = [[r, iter(pattern[r]), None]]  # equation, its unknowns left, the one taken
        while frames:
            frame = frames[-1]
            for c in frame[1]:
                if c in seen:
                    continue
                seen.add(c)
                frame[2] = c
                if row_of[c] is None:
                    for row, _, col in frames:
                        row_of[col] = row
                    return True
                frames.append([row_of[c], iter(pattern[row_of[c]]), None])
                break
            else:
                frames.pop()
        return False

    for r in range(len(pattern)):
        if not augment(r):
            return None
    return row_of  # type: ignore[return-value]  # (every unknown assigned once every equation is)


def _components(depends: list[list[int]]) -> list[list[int]]:
    """The strongly connected components of the graph ``v -> depends[v]``, each sorted, dependencies first
    (Tarjan's algorithm, without recursion)."""
    index: dict[int, int] = {}
    low: dict[int, int] = {}
    on_stack: set[int] = set()
    stack: list[int] = []
    blocks: list[list[int]] = []

    def visit(v: int) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)

    for root in range(len(depends)):
        if root in index:
            continue
        work = [(root, iter(depends[root]))]
        visit(root)
        while work:
            v, children = work[-1]
            for w in children:
                if w not in index:
                    visit(w)
                    work.append((w, iter(depends[w])))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    blocks.append(_pop_component(stack, on_stack, v))
    return blocks


def _pop_component(stack: list[int], on_stack: set[int], v: int) -> list[int]:
    """The component of root ``v``: the stack's top down to ``v``, taken off, sorted."""
    cols = []
    while True:
        w = stack.pop()
        on_stack.discard(w)
        cols.append(w)
        if w == v:
            break
    return sorted(cols)


_CANONICAL_TERMS = 32  # entries whose expanded numerator and denominator stay below this many terms


def _expanded_terms(e: sp.Expr, memo: dict) -> tuple[int, int]:
    """Upper bounds of the numbers of terms of ``e``'s numerator and denominator once
    brought to one fraction and expanded (without expanding anything)."""
    if e in memo:
        return memo[e]
    if e.is_Atom:
        size = (1, 1)
    elif e.is_Add:
        parts = [_expanded_terms(a, memo) for a in e.args]
        den = math.prod(d for _, d in parts)
        size = (sum(n * den // d for n, d in parts), den)
    elif e.is_Mul:
        parts = [_expanded_terms(a, memo) for a in e.args]
        size = (math.prod(n for n, _ in parts), math.prod(d for _, d in parts))
    elif e.is_Pow and e.exp.is_Integer:
        n, d = _expanded_terms(e.base, memo)
        k = int(e.exp)
        size = (n ** k, d ** k) if k >= 0 else (d ** -k, n ** -k)
    else:
        size = (1, 1)
    cap = 1 << 40
    memo[e] = size = (min(size[0], cap), min(size[1], cap))
    return size


def _canonical(X: sp.Matrix, A: sp.Matrix, B: sp.Matrix) -> sp.Matrix:
    """Each entry of X whose expanded form is small, as the cancelled element of the
    fraction field of A's and B's entries (what one solve of the whole system gives)."""
    from sympy.polys.constructor import construct_domain

    memo: dict = {}
    small = [
        (i, j) for i in range(X.rows) for j in range(X.cols)
        if not X[i, j].is_Number and max(_expanded_terms(X[i, j], memo)) <= _CANONICAL_TERMS
    ]
    if not small:
        return X
    # the domain one solve of the whole system works in (its generators' order sets the signs)
    domain = construct_domain([e for e in A.values() if e != 0] or [0])[0].unify(
        construct_domain([e for e in B.values() if e != 0] or [0])[0]
    )
    if domain.has_assoc_Field:
        domain = domain.get_field()
    gens = getattr(domain, "symbols", ())
    fields: dict[tuple, Any] = {}
    out = X.copy()
    for i, j in small:
        e = X[i, j]
        # the field of the entry's own symbols, in the whole field's order: the same
        # cancelled form (sign and content are set by the leading term in that order)
        own = tuple(g for g in gens if g in e.free_symbols)
        if own not in fields:
            fields[own] = domain.dom.frac_field(*own) if own and gens else domain
        field = fields[own]
        out[i, j] = field.to_sympy(field.from_sympy(e))
    return out


def solve_whole(A: sp.Matrix, B: sp.Matrix) -> sp.Matrix | None:
    """X with A X = B by one LU solve in the fraction field of A's and B's entries."""
    from sympy.polys.matrices import DomainMatrix
    from sympy.polys.matrices.exceptions import DMNonInvertibleMatrixError

    entries = list(A) + list(B)
    atoms = {a for e in entries for a in sp.preorder_traversal(e) if _is_generator(a)}
    to_dummy = {a: sp.Dummy() for a in atoms}
    back = {d: a for a, d in to_dummy.items()}
    dA = DomainMatrix.from_Matrix(A.xreplace(to_dummy))
    dB = DomainMatrix.from_Matrix(B.xreplace(to_dummy))
    domain = dA.domain.unify(dB.domain)
    if domain.has_assoc_Field:
        domain = domain.get_field()
    try:
        X = dA.convert_to(domain).lu_solve(dB.convert_to(domain)).to_Matrix()
    except DMNonInvertibleMatrixError:
        return None
    if any(e.has(sp.zoo, sp.nan, sp.oo) for e in X):
        return None
    return X.xreplace(back) if back else X


def _is_generator(expr: sp.Basic) -> bool:
    """A sub-expression that is neither a number, a symbol, nor built by + * and integer powers."""
    if expr.is_Symbol or expr.is_Rational or expr.is_Add or expr.is_Mul:
        return False
    if expr.is_Pow:
        return not expr.exp.is_Integer
    return isinstance(expr, sp.Expr) and not expr.is_Integer


def is_zero(e: sp.Expr) -> bool:
    """Whether a coefficient is identically zero: decided on its cancelled form when one
    generic value of its symbols does not already show that it is not."""
    if e.is_Number or not e.free_symbols:
        return bool(e == 0)
    if e.is_Mul:
        return any(is_zero(f) for f in e.args)
    if e.is_Pow:
        return is_zero(e.base) and bool(e.exp.is_positive)
    generic = e.xreplace(generic_values(e.free_symbols, 3))
    if generic.is_Number and generic != 0:
        return False
    return bool(sp.cancel(sp.together(e)) == 0)
