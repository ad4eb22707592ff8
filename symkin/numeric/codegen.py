"""Printers and generated source for the compiled laws.

:class:`FloatPrinter` prints NumPy code (vectorised) or, with ``kernel=True``, scalar
code for a Numba loop; it knows the stable-form nodes of :mod:`symkin.numeric.stable`.
:func:`kernel_source` writes the fused loop.  :class:`ExactPrinter` prints rational
arithmetic on :class:`fractions.Fraction`.

    >>> import sympy as sp
    >>> from symkin.numeric.stable import ExactRatio
    >>> z = sp.Symbol("z", integer=True)
    >>> FloatPrinter().doprint(ExactRatio(z - 1, z) + sp.Rational(1, 3))
    '_symkin_exact_ratio(z - 1, z) + 1/3'
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.pycode import PythonCodePrinter

from symkin.numeric.runtime import EXACT_FLOATS, LONG_PHASE
from symkin.numeric.stable import (
    ExactRatio,
    Group,
    LongPhase,
    ProductDifference,
    ReducedPhase,
    plain_form,
)

__all__ = ["FloatPrinter", "ScalarPrinter", "ExactPrinter", "kernel_source", "abs_bound", "phase_sources", "product_ratios"]


class ProductRatio(sp.Function):
    """``a*b / (a*b - c*d)`` with the difference a :class:`ProductDifference`: what the NumPy
    float64 code computes anyway to certify the difference (``g`` of
    :func:`symkin.numeric.runtime.product_difference`), so a law that multiplies by ``a*b``
    and divides by the difference takes it as it is (:func:`product_ratios`)."""

    nargs = 4
    is_real = True

    def doit(self, **hints: Any) -> sp.Expr:
        """The ratio with its difference: ``a*b / ProductDifference(a, b, c, d)``."""
        a, b, c, d = self.args
        return a * b / ProductDifference(a, b, c, d)


def product_ratios(exprs: Sequence[sp.Expr]) -> list[sp.Expr]:
    """``exprs`` with each product ``a*b*X / ProductDifference(a, b, c, d)`` written
    ``X * ProductRatio(a, b, c, d)``: two passes over the points fewer (the product ``a*b``
    again, and a division) for the Willis forms ``r1 r3/(r1 r3 - r2 r4)``.  A difference
    that also appears elsewhere is left as it is (it would be computed twice); so is every
    one inside a :class:`LongPhase`, whose coefficient stays whole.

    >>> r1, r2, r3, r4, w = sp.symbols("r1:5 w")
    >>> product_ratios([w * r1 * r3 / ProductDifference(r1, r3, r2, r4)])
    [w*ProductRatio(r1, r3, r2, r4)]
    """

    def take(factors: list[sp.Expr] | None, x: sp.Expr) -> list[sp.Expr] | None:
        if factors is None or x.is_Number:
            return None
        for k, f in enumerate(factors):
            if f == x:
                return factors[:k] + factors[k + 1:]
            base, exp = f.as_base_exp()
            if base == x and exp.is_Integer and exp > 1:
                return factors[:k] + [base ** (exp - 1)] + factors[k + 1:]
        return None

    def rewrite(e: sp.Expr, skip: set[tuple[sp.Expr, ...]]) -> sp.Expr:
        if e.is_Atom or isinstance(e, LongPhase):
            return e
        args = [rewrite(a, skip) for a in e.args]
        e = e.func(*args) if any(x is not y for x, y in zip(args, e.args)) else e
        if not e.is_Mul:
            return e
        factors = list(e.args)
        for k, f in enumerate(factors):
            if not (f.is_Pow and f.exp == -1 and isinstance(f.base, ProductDifference)) or f.base.args in skip:
                continue
            a, b, c, d = f.base.args
            rest = take(take(factors[:k] + factors[k + 1:], a), b)
            if rest is not None:
                return sp.Mul(*rest) * ProductRatio(a, b, c, d)
        return e

    def bare(e: sp.Expr) -> set[tuple[sp.Expr, ...]]:
        if isinstance(e, ProductDifference):
            return {e.args}
        if e.is_Atom or isinstance(e, (LongPhase, ProductRatio)):
            return set()
        return set().union(*(bare(a) for a in e.args))

    skip: set[tuple[sp.Expr, ...]] = set()
    while True:
        out = [rewrite(e, skip) for e in exprs]
        taken = {n.args for e in out for n in sp.preorder_traversal(e) if isinstance(n, ProductRatio)}
        shared = (taken & set().union(*(bare(e) for e in out))) - skip
        if not shared:
            return out
        skip |= shared


def phase_sources(exprs: Sequence[sp.Expr]) -> dict[str, str]:
    """The double-double source of every :class:`LongPhase` in ``exprs``, by function name
    (see :func:`symkin.numeric.runtime.dd_source`)."""
    from symkin.numeric.runtime import dd_source

    out: dict[str, str] = {}
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, LongPhase) and node.name not in out:
                _key, coeff, _t, *syms = node.args
                out[node.name] = dd_source(node.name, plain_form(coeff), syms)
    return out


def _print_long_phase(printer: Any, expr: LongPhase, kernel: bool) -> str:
    _key, coeff, t, *syms = expr.args
    plain = f"({printer._print(coeff)})*{printer._print(t)}"
    args = [printer._print(a) for a in syms]
    call = f"_dd_reduce_pair({expr.name}({', '.join(args)}), {printer._print(t)})"
    fixed = getattr(printer, "phase_fixed", None) if kernel else None
    if fixed is not None:  # a block whose coefficients are its inputs' at its first point: every phase reduced
        return f"_dd_reduce(_mh{fixed[expr.name]}, _ml{fixed[expr.name]}, {printer._print(t)})"
    memo = getattr(printer, "phase_memo", None) if kernel else None
    if memo is not None:  # a kernel's loop: the coefficient kept while its inputs repeat (below)
        k = memo.setdefault(expr.name, (len(memo), len(args)))[0]
        same = " and ".join([f"_mv{k}"] + [f"{a} == _mk{k}_{i}" for i, a in enumerate(args)])
        lines = [f"if not abs({plain}) <= {LONG_PHASE!r} and not ({same}):",
                 f"    _mh{k}, _ml{k} = {expr.name}({', '.join(args)})",
                 f"    _mv{k} = True"]
        lines += [f"    _mk{k}_{i} = {a}" for i, a in enumerate(args)]
        if lines[0] not in printer.pending:
            printer.pending += lines
        return f"(({plain}) if abs({plain}) <= {LONG_PHASE!r} else _dd_reduce(_mh{k}, _ml{k}, {printer._print(t)}))"
    if kernel:  # one point: the double-double path only where the phase is long (see runtime.LONG_PHASE)
        return f"(({plain}) if abs({plain}) <= {LONG_PHASE!r} else {call})"
    return f"_symkin_long_phase({plain}, {expr.name}, {', '.join(printer._print(a) for a in (t, *syms))})"


class _ProductCalls:
    """The float printers' calls of the runtime's differences and ratios of products."""

    _print: Any

    def _print_ProductDifference(self, expr: ProductDifference) -> str:
        return f"_symkin_product_difference({', '.join(self._print(a) for a in expr.args)})"

    def _print_ProductRatio(self, expr: ProductRatio) -> str:
        return f"_symkin_product_ratio({', '.join(self._print(a) for a in expr.args)})"


class FloatPrinter(_ProductCalls, NumPyPrinter):
    """NumPy printer for float32/float64 code, vectorised or scalar (``kernel=True``)."""

    def __init__(self, precision: str = "float64", kernel: bool = False, settings: dict | None = None):
        super().__init__(settings or {})
        self.precision = precision
        self.kernel = kernel
        self._integer_mode = False
        #: In a kernel's blocked loop: the long phases met, by name -> (index of their memo
        #: variables, number of coefficient inputs) (``None``: no memo), and the statements
        #: to put before the line printed.
        self.phase_memo: dict[str, tuple[int, int]] | None = None
        #: In a kernel's blocked loop where every long phase's coefficient is the same at every
        #: point (its inputs scalars): the phases by name -> index of their coefficient variables.
        self.phase_fixed: dict[str, int] | None = None
        #: In a float64 kernel's second pass: exact ratios in int64 (else in float64, exact below 2^53).
        self.exact_ints = False
        self.pending: list[str] = []

    # numbers: a float32 kernel wraps constants so that Numba keeps float32
    def _wrap(self, text: str) -> str:
        if self.kernel and self.precision == "float32" and not self._integer_mode:
            return f"_F({text})"
        return text

    def _print_Integer(self, expr: sp.Integer) -> str:
        return self._wrap(str(expr.p))

    def _print_Rational(self, expr: sp.Rational) -> str:
        return self._wrap(f"{expr.p}/{expr.q}")

    def _print_Float(self, expr: sp.Float) -> str:
        return self._wrap(repr(float(expr)))

    def _print_NumberSymbol(self, expr: Any) -> str:
        return self._wrap(repr(float(expr)))

    _print_Pi = _print_NumberSymbol
    _print_Exp1 = _print_NumberSymbol

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exp = expr.as_base_exp()
        if self.kernel and exp.is_Integer and 0 < abs(int(exp)) <= 4:
            b = self.parenthesize(base, 100)
            prod = "*".join([b] * abs(int(exp)))
            return f"({prod})" if exp > 0 else f"({self._print(sp.Integer(1))}/({prod}))"
        if self.kernel and self.precision == "float32" and not (exp.is_Rational and exp.q == 2):
            return f"{self.parenthesize(base, 100)}**{self._print(exp)}"
        return super()._print_Pow(expr, rational=rational)

    def _print_Group(self, expr: Group) -> str:
        return f"({self._print(expr.args[0])})"

    def _print_ExactRatio(self, expr: ExactRatio) -> str:
        saved, self._integer_mode = self._integer_mode, True
        try:
            num, den = (self._print(a) for a in expr.args)
        finally:
            self._integer_mode = saved
        if self.kernel:
            bn, bd = (self._print(abs_bound(a)) for a in expr.args)
            if self.precision == "float64" and not self.exact_ints:  # in the float twins: exact in a block kernel_source found below 2^53
                twins = {s: sp.Symbol(FLOAT_TWIN + s.name) for a in expr.args for s in a.free_symbols}
                num, den = (self._print(a.xreplace(twins)) for a in expr.args)
                return f"(({num})/({den}))"
            return f"_symkin_exact_ratio({num}, {den}, {bn}, {bd})"
        return f"_symkin_exact_ratio({num}, {den})"

    def _print_ReducedPhase(self, expr: ReducedPhase) -> str:
        p, q, *xs = expr.args
        xs = list(xs) + [sp.Integer(1)] * (3 - len(xs))
        saved, self._integer_mode = self._integer_mode, True
        try:
            parts = [self._print(x) for x in xs]
        finally:
            self._integer_mode = saved
        return f"_symkin_reduced_phase({int(p)}, {int(q)}, {', '.join(parts)})"

    def _print_LongPhase(self, expr: LongPhase) -> str:
        return _print_long_phase(self, expr, self.kernel)


#: Name prefix of the float twin of an integer symbol inside a kernel.
FLOAT_TWIN = "_f_"


def abs_bound(poly: sp.Expr) -> sp.Expr:
    """``sum |c| prod |z|^d`` over the terms of an integer polynomial, in the float twins of
    its symbols: an upper bound of every partial sum met while evaluating it."""
    terms = []
    for term in sp.Add.make_args(sp.expand(poly)):
        coeff, factors = term.as_coeff_mul()
        mags = []
        for f in factors:
            base, exp = f.as_base_exp()
            mags.append(sp.Abs(sp.Symbol(FLOAT_TWIN + base.name)) ** exp)
        terms.append(sp.Float(abs(float(coeff))) * sp.Mul(*mags))
    return sp.Add(*terms)


#: Points per block of a kernel's loop: each block reads its arguments as contiguous slices
#: (scalars from a block-sized copy), so that the compiler can vectorise the inner loop.
KERNEL_BLOCK = 1024


def _hoist_differences(exprs: Sequence[sp.Expr]) -> tuple[list[sp.Expr], list[tuple[sp.Symbol, sp.Expr]]]:
    """``exprs`` with every :class:`ProductDifference` (innermost first; none inside a
    :class:`LongPhase`, whose coefficient stays whole for its double-double code) replaced
    by a symbol ``_hK``, and the pairs ``(_hK, node)`` in an order that computes each
    before its use."""
    names: dict[sp.Expr, sp.Symbol] = {}
    order: list[tuple[sp.Symbol, sp.Expr]] = []

    def hoist(e: sp.Expr) -> sp.Expr:
        if e.is_Atom or isinstance(e, LongPhase):
            return e
        if e in names:
            return names[e]
        args = [hoist(a) for a in e.args]
        node = e.func(*args) if any(x is not y for x, y in zip(args, e.args)) else e
        if not isinstance(node, ProductDifference):
            return node
        sym = names[e] = sp.Symbol(f"_h{len(order)}")
        order.append((sym, node))
        return sym

    return [hoist(e) for e in exprs], order


def kernel_source(
    exprs: Sequence[sp.Expr],
    args: Sequence[sp.Symbol],
    integer_args: Sequence[bool],
    scalar: Sequence[bool],
    precision: str,
    cse: bool,
    float_integers: Sequence[bool] = (),
    steps: bool = False,
) -> str:
    """Source of ``_kernel(A0, ..., O0, ..., n)``: one fused loop over n points writing
    every output, returning how many output values are not finite, how many integer
    inputs given as floats are not whole numbers and how many points a second pass must
    redo (below).

    Integer arguments arrive as int64 (their float values are ``_f_<name>``), or, where
    ``float_integers`` says so, as float64 arrays checked and cast in the loop; scalar
    arguments arrive as numbers.  With ``steps`` every argument arrives as an array and
    the kernel takes one step per argument after ``n`` (``_kernel(A0, ..., O0, ..., n,
    S0, ...)``): 0 for a scalar, given as an array of at least ``min(n, KERNEL_BLOCK)``
    copies of it, 1 for an array, so that one compiled kernel serves every mix of scalars
    and arrays.  That kernel runs over blocks of :data:`KERNEL_BLOCK` points, each
    argument read as a contiguous slice, so that the compiler vectorises the inner loop.
    In float64 it takes every difference of products ``a b - c d`` plainly, counting the
    points where that is not certified (the test of
    :func:`symkin.numeric.runtime.product_difference`); ``_kernel_redo`` (same arguments,
    compiled only when a call needs it) redoes those points with the double-double form (a
    branch the compiler cannot vectorise) and returns the change in the count of
    non-finite outputs.  Elsewhere both compute the same operations.  A long phase's
    double-double coefficient is computed at the first point of a block that needs it and
    kept while its inputs are the same as that point's (a scalar radius, a run of equal
    speeds): a sweep of t pays for it once per block, not at every point.
    """
    float_integers = tuple(float_integers) or (False,) * len(args)
    if steps:
        scalar = (False,) * len(args)
    names = [f"a{i}" for i in range(len(args))]
    ren = {}
    for s, nm in zip(args, names):
        ren[s] = sp.Symbol(nm)  # in ExactRatio: the integer value; elsewhere: its float twin
    exprs = [e.xreplace(ren) for e in exprs]
    # each long phase's double-double coefficient, from the inputs themselves (the renamings
    # below put float twins and ratio variables into its coefficient)
    phases = phase_sources(exprs)
    float_ren = {sp.Symbol(nm): sp.Symbol(FLOAT_TWIN + nm) for nm, is_int in zip(names, integer_args) if is_int}

    def floats_outside_exact(e: sp.Expr) -> sp.Expr:
        if not float_ren:
            return e
        if isinstance(e, ExactRatio) or e.is_Atom:
            return float_ren.get(e, e)
        if isinstance(e, ReducedPhase):
            return e.func(*(float_ren.get(a, a) for a in e.args))
        return e.func(*(floats_outside_exact(a) for a in e.args))

    exprs = [floats_outside_exact(e) for e in exprs]
    # exact ratios first, each into its own variable: cse must not move integer arithmetic
    ratios: dict[sp.Expr, sp.Symbol] = {}
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, ExactRatio) and node not in ratios:
                ratios[node] = sp.Symbol(f"_r{len(ratios)}")
    exprs = [e.xreplace(ratios) for e in exprs]
    blocked = steps
    two_pass = blocked and precision == "float64"
    branches: list[tuple[sp.Symbol, sp.Expr]] = []
    if two_pass:
        exprs, branches = _hoist_differences(exprs)
        two_pass = bool(branches)
    if cse:
        repl, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_x"), optimizations=None)
    else:
        repl, reduced = [], list(exprs)
    printer = FloatPrinter(precision, kernel=True)
    # a float64 kernel's exact ratios: in float64 where a bound of every partial sum is below 2^53
    # (exact there), the block again in int64 where it is not at some point
    ratio_bounds = [f"{printer.doprint(abs_bound(a))} >= {EXACT_FLOATS!r}" for node in ratios for a in node.args] \
        if blocked and precision == "float64" else []
    outs = [f"O{k}" for k in range(len(exprs))]
    n_ops = sum(sp.count_ops(v) for _, v in repl) + sum(sp.count_ops(e) for e in reduced)
    n_ops += sum(sp.count_ops(a) + 1 for node in ratios for a in node.args)
    n_ops += sum(sp.count_ops(node) for _, node in branches)
    lines = [
        "# generated by symkin.numeric.codegen.kernel_source: do not edit",
        f"# arguments: {', '.join(f'{nm} = {s}' for nm, s in zip(names, args))}; {len(reduced)} outputs, {n_ops} operations per point",
    ]
    for name, text in phases.items():
        lines += [text.rstrip("\n"), f"{name} = _njit_inline({name})", ""]
    lines += [
        f"def _kernel({', '.join([n.upper() for n in names] + outs + ['n'] + ([f'S{k}' for k in range(len(names))] if steps else []))}):",
        "    _bad = 0",
        "    _nonwhole = 0",
    ]

    def body(pad: str, at: Any, mode: str) -> list[str]:
        """The lines of one point (``at(k)``: how argument k is read).  ``mode``: "plain"
        (the hoisted differences plain, uncertified ones counted in ``_lu``), "redo" (the
        same test, then, for an uncertified point only, the double-double forms and the
        outputs again, the count of non-finite outputs mended) or "" (one pass)."""
        out: list[str] = []
        for k, (nm, is_int, sc, as_float) in enumerate(zip(names, integer_args, scalar, float_integers)):
            if not sc and is_int and as_float:  # a tooth number given as a float: whole, and below 2^63
                out += [
                    f"_w = {at(k)}",
                    "if _w != numpy.floor(_w) or not (abs(_w) < 9.2e18):",
                    "    _lnw += 1",
                    "    _w = 0.0",
                    f"{nm} = numpy.int64(_w)",
                    f"{FLOAT_TWIN}{nm} = _F(_w)",
                ]
            elif not sc:
                out.append(f"{nm} = {at(k)}")
                if is_int:
                    out.append(f"{FLOAT_TWIN}{nm} = _F({nm})")
        def printed(node: sp.Expr) -> str:
            text = printer.doprint(node)
            out.extend(printer.pending)  # a long phase's coefficient, kept while its inputs repeat
            printer.pending.clear()
            return text

        def assign(target: str, node: sp.Expr) -> None:
            text = printed(node)
            out.append(f"{target} = {text}")

        for node, sym in ratios.items():
            assign(str(sym), node)
        if ratio_bounds and not printer.exact_ints:  # (points whose ratios float64 may not hold exactly)
            out.append(f"_nb += {' | '.join(f'({b})' for b in ratio_bounds)}")
        if mode:
            if mode == "redo":
                out.append("_lu = 0")
            for sym, node in branches:  # runtime's difference() without its branch
                args = ", ".join(printed(x) for x in node.args)
                out += [f"{sym}, _ok = _symkin_plain_difference({args})", "_lu += not _ok"]
            if mode == "redo":
                out.append("if _lu == 0:")
                out.append("    continue")
        if mode != "plain":
            for sym, node in branches:
                assign(str(sym), node)
        for sym, value in repl:
            assign(str(sym), value)
        for k, e in enumerate(reduced):
            assign("_v", e if not e.is_Number else sp.Float(e))
            if mode == "redo":
                out.append(f"_lb -= not numpy.isfinite(W{k}[_j])")
            out.append(f"W{k}[_j] = _v" if blocked else f"O{k}[_i] = _v")
            out.append("_lb += not numpy.isfinite(_v)")
        return [pad + line for line in out]

    if not blocked:
        for nm, is_int, sc in zip(names, integer_args, scalar):
            if sc:
                lines.append(f"    {nm} = {nm.upper()}")
                if is_int:
                    lines.append(f"    {FLOAT_TWIN}{nm} = _F({nm})")
        lines += ["    _lb = 0", "    _lnw = 0", "    for _i in prange(n):"]
        lines += body("        ", lambda k: f"{names[k].upper()}[_i]", "")
        lines += ["    _bad += _lb", "    _nonwhole += _lnw", "    return _bad, _nonwhole, 0"]
        return "\n".join(lines) + "\n"

    # the long phases: name -> indices of the arguments of their coefficient (as a value or a float twin)
    index = {sp.Symbol(nm): k for k, nm in enumerate(names)} | {sp.Symbol(FLOAT_TWIN + nm): k for k, nm in enumerate(names)}
    long_args: dict[str, list[int]] = {}
    for e in exprs:
        for node in sp.preorder_traversal(e):
            if isinstance(node, LongPhase) and node.name not in long_args:
                long_args[node.name] = [index[a] for a in node.args[3:]]

    def point_loops(pad: str, mode: str) -> list[str]:
        """The loop over a block's points at indentation ``pad``: where every long phase's
        coefficient comes from scalars (a sweep of t), computed once for the block and every
        phase reduced, a loop without branches; else kept while the inputs repeat."""
        out: list[str] = []
        if long_args and mode != "redo":
            used = sorted({k for ks in long_args.values() for k in ks})
            out.append(f"{pad}if not ({' or '.join(f'S{k}' for k in used)}):")
            for i, (name, ks) in enumerate(long_args.items()):
                out.append(f"{pad}    _mh{i}, _ml{i} = {name}({', '.join(f'V{k}[0]' for k in ks)})")
            printer.phase_fixed = {name: i for i, name in enumerate(long_args)}
            out.append(f"{pad}    for _j in range(_e - _s):")
            out += body(pad + "        ", lambda k: f"V{k}[_j]", mode)
            printer.phase_fixed = None
            out.append(f"{pad}else:")
            pad += "    "
        printer.phase_memo = {}
        inner = body(pad + "    ", lambda k: f"V{k}[_j]", mode)
        for k, inputs in printer.phase_memo.values():  # no coefficient yet in this block
            out += [f"{pad}_mv{k} = False", f"{pad}_mh{k} = 0.0", f"{pad}_ml{k} = 0.0"]
            out += [f"{pad}_mk{k}_{i} = 0.0" for i in range(inputs)]
        printer.phase_memo = None
        out.append(f"{pad}for _j in range(_e - _s):")
        return out + inner

    def block_loop(mode: str) -> list[str]:
        out = ["    for _b in prange((n + _B - 1) // _B):",
               "        _s = _b * _B",
               "        _e = min(n, _s + _B)"]
        # a scalar arrives as a block of copies of it: every read is contiguous
        out += [f"        V{k} = {nm.upper()}[_s:_e] if S{k} else {nm.upper()}[:_e - _s]" for k, nm in enumerate(names)]
        out += [f"        W{k} = O{k}[_s:_e]" for k in range(len(reduced))]
        counts = ["_lb = 0", "_lnw = 0"] + (["_lu = 0"] if mode == "plain" else [])
        out += ["        " + c for c in counts]
        if ratio_bounds and mode != "redo":
            # exact ratios in float64 (a loop that vectorises), counting the points where a bound of a
            # partial sum passes 2^53; where there are any, the block again with them in int64
            out.append("        _nb = 0")
            out += point_loops("        ", mode)
            out.append("        if _nb:")
            out += ["            " + c for c in counts]
            printer.exact_ints = True
            out += point_loops("            ", mode)
            printer.exact_ints = False
        else:
            printer.exact_ints = mode == "redo"  # (the rare second pass: integers, no test)
            out += point_loops("        ", mode)
            printer.exact_ints = False
        out.append("        _bad += _lb")
        if mode != "redo":  # (the redo reads the same inputs again)
            out.append("        _nonwhole += _lnw")
        if mode == "plain":
            out.append("        _uncertain += _lu")
        return out

    head = next(x for x in lines if x.startswith("def _kernel("))
    lines.append(f"    _B = {KERNEL_BLOCK}")
    if two_pass:
        lines.append("    _uncertain = 0")
        lines += block_loop("plain")
        lines += ["    return _bad, _nonwhole, _uncertain", ""]
        lines += [head.replace("def _kernel(", "def _kernel_redo("),
                  "    # the points whose differences of products the plain form does not certify",
                  "    _bad = 0", "    _nonwhole = 0", f"    _B = {KERNEL_BLOCK}"]
        lines += block_loop("redo")
        lines.append("    return _bad")
    else:
        lines += block_loop("")
        lines.append("    return _bad, _nonwhole, 0")
    return "\n".join(lines) + "\n"


class ScalarPrinter(_ProductCalls, PythonCodePrinter):
    """Python code on floats (the ``math`` module) for one point of a float64 law: the
    scalar path of a compiled law, with the stable-form nodes of :mod:`symkin.numeric.stable`
    called as scalar helpers (exact ratios on Python integers are correctly rounded).

    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> ScalarPrinter().doprint(sp.sin(x) / 3 + ProductDifference(x, y, y, 2))
    '(1/3)*math.sin(x) + _symkin_product_difference(x, y, y, 2)'
    """

    def _print_Rational(self, expr: sp.Rational) -> str:
        return f"{expr.p}/{expr.q}"  # one correctly rounded division of exact integers

    def _print_Float(self, expr: sp.Float) -> str:
        return repr(float(expr))

    def _print_NumberSymbol(self, expr: Any) -> str:
        return repr(float(expr))

    _print_Pi = _print_NumberSymbol
    _print_Exp1 = _print_NumberSymbol

    def _print_Group(self, expr: Group) -> str:
        return f"({self._print(expr.args[0])})"

    def _print_ExactRatio(self, expr: ExactRatio) -> str:
        return f"_symkin_exact_ratio({', '.join(self._print(a) for a in expr.args)})"

    def _print_ReducedPhase(self, expr: ReducedPhase) -> str:
        p, q, *xs = expr.args
        xs = list(xs) + [sp.Integer(1)] * (3 - len(xs))
        return f"_symkin_reduced_phase({int(p)}, {int(q)}, {', '.join(self._print(x) for x in xs)})"

    def _print_LongPhase(self, expr: LongPhase) -> str:
        return _print_long_phase(self, expr, False)


class ExactPrinter(PythonCodePrinter):
    """Python code on :class:`fractions.Fraction`: rationals stay exact.

    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> ExactPrinter().doprint(x / 3 + sp.Rational(1, 2))
    '(Fraction(1, 3))*x + Fraction(1, 2)'
    """

    def _print_Rational(self, expr: sp.Rational) -> str:
        return f"Fraction({expr.p}, {expr.q})" if expr.q != 1 else str(expr.p)

    def _print_Integer(self, expr: sp.Integer) -> str:
        return str(expr.p)

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exp = expr.as_base_exp()
        return f"{self.parenthesize(base, 100)}**({int(exp)})"
