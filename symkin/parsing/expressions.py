"""Expressions typed by a user, built into SymPy from an allow-list: nothing is evaluated by Python.

``sympy.sympify`` and ``parse_expr`` evaluate Python, so a string from a user must never
reach them.  Here a string is parsed by :mod:`ast` and rebuilt node by node from an
allow-list of operators, names and functions, and every constant node is bounded
(:mod:`symkin._util.bounds`) before SymPy evaluates it.

    >>> parse_expression("2*pi*sin(t)", names=("t",))
    2*pi*sin(t)
    >>> parse_expression("__import__('os').system('echo hi')")
    Traceback (most recent call last):
    ...
    symkin.errors.InputError: expression: calling "__import__('os').system" is not allowed; allowed names: E, pi; functions: ...
"""

from __future__ import annotations

import ast
import itertools
from collections.abc import Callable, Iterable, Mapping

import sympy as sp

from symkin import symbols as S
from symkin._util import bounds
from symkin._util.budget import time_limit
from symkin.errors import InputError
from symkin.parsing.numbers import (
    _BARE_EXPONENT,
    _COMMA_DECIMAL,
    _NUMBER,
    SECONDS,
    _bounded,
    _check_text,
    exact_digits,
    parse_number,
)

__all__ = ["parse_expression", "FUNCTIONS", "CONSTANTS", "MAX_DEPTH", "MAX_EXPONENT", "MAX_LAW_SIZE"]

#: Functions a user expression may call.
FUNCTIONS: Mapping[str, Callable[..., sp.Expr]] = {
    "sin": sp.sin,
    "cos": sp.cos,
    "tan": sp.tan,
    "asin": sp.asin,
    "acos": sp.acos,
    "atan": sp.atan,
    "atan2": sp.atan2,
    "sinh": sp.sinh,
    "cosh": sp.cosh,
    "tanh": sp.tanh,
    "exp": sp.exp,
    "log": sp.log,
    "sqrt": sp.sqrt,
    "Abs": sp.Abs,
}
#: Constants a user expression may name.
CONSTANTS: Mapping[str, sp.Expr] = {"pi": sp.pi, "E": sp.E}
#: Nesting allowed in an expression (a flat sum or product of many terms counts as one level).
MAX_DEPTH = 60
MAX_EXPONENT = 1000
#: Nodes of the second derivative of a law of t (its acceleration), which symkin derives,
#: simplifies and compiles: a Fourier series of 150 terms has about 900; sin nested 20 deep
#: 5,000 (55 deep: 90,000 nodes, minutes of work downstream).  Its first derivative may have
#: a fifth of them.
MAX_LAW_SIZE = 6000

def parse_expression(
    text: str,
    *,
    names: Iterable[str] = (),
    symbols: Mapping[str, sp.Expr] | None = None,
    what: str = "expression",
) -> sp.Expr:
    """A SymPy expression from text, built from an allow-list only.

    Parameters
    ----------
    text : str
        Numbers, + - * / ** (or ^), parentheses, the constants pi and E, the functions
        in :data:`FUNCTIONS`, and the names allowed below.
    names : iterable of str
        Names allowed as symbols.  ``"t"`` maps to :data:`symkin.symbols.t`, the time: an
        expression in t is a law of motion, differentiated twice (velocity, acceleration), so it
        must be smooth (``Abs`` of an expression in t is refused: its kink has no acceleration) and
        its second derivative at most :data:`MAX_LAW_SIZE` nodes.
    symbols : mapping of str to expression, optional
        Names allowed with the value to put in their place.
    what : str
        What the expression is, for error messages.
    """
    s = _check_text(text, what)
    allowed: dict[str, sp.Expr] = dict(CONSTANTS)
    for n in names:
        allowed[n] = S.t if n == "t" else sp.Symbol(n, real=True)
    allowed.update(symbols or {})
    source = s.replace("^", "**")
    if _COMMA_DECIMAL.match(s):
        raise InputError(f"{what} {text!r} is not a number: write a decimal point, as in {s.replace(',', '.', 1)}")
    if _BARE_EXPONENT.match(s):
        raise InputError(f"{what} {text!r} is not a number: an exponent needs its digits, as in {s.strip()}3")
    try:
        tree = ast.parse(source, mode="eval")
    except (SyntaxError, ValueError):
        odd = next((c for c in source if not c.isascii() or not c.isprintable()), None)
        if odd is not None:  # a look-alike of an operator or a bracket: name it
            raise InputError(
                f"{what} {text!r} is not a valid expression: the character {odd!r} (U+{ord(odd):04X}) is "
                "not allowed; write it in ASCII (* for a product, - for minus, ( ) for brackets)"
            ) from None
        raise InputError(f"{what} {text!r} is not a valid expression") from None
    except (RecursionError, MemoryError):
        raise InputError(f"{what} is nested too deeply to read; at most {MAX_DEPTH} levels are accepted") from None
    with time_limit(SECONDS, f"{what} took longer than {SECONDS:g} s of CPU time to build and bound; write a simpler expression"):
        expr = _Builder(allowed, what, source).build(tree.body, 0)
        exact_digits(expr, what)  # every exact number in it, once (each step bounded its own on the way)
        if S.t in expr.free_symbols:
            _check_law(expr, what)
    return expr


def _check_law(expr: sp.Expr, what: str) -> None:
    """Refuse a law of t that is not smooth, or whose acceleration is too large to derive and compile."""
    for kink in expr.atoms(sp.Abs):
        if S.t in kink.free_symbols:
            raise InputError(
                f"{what}: {bounds.show(kink, 40)} is not smooth where {bounds.show(kink.args[0], 30)} = 0, and a law of t "
                "is differentiated twice (velocity, acceleration); write a smooth law (sqrt(x**2 + 1e-6) rounds the kink)"
            )
    velocity = sp.diff(expr, S.t)  # (its size, a fifth of the limit: the acceleration then costs seconds to derive)
    acceleration = None if _nodes(velocity, MAX_LAW_SIZE // 5) > MAX_LAW_SIZE // 5 else sp.diff(velocity, S.t)
    if acceleration is None or _nodes(acceleration, MAX_LAW_SIZE) > MAX_LAW_SIZE:
        raise InputError(
            f"{what} is too involved a law of t: its second derivative has more than {MAX_LAW_SIZE} terms and "
            "factors, which symkin derives, simplifies and compiles; write a simpler law (fewer nested functions of t)"
        )


#: Operators of one precedence level: a chain of them (a + b - c + ...) is one level of nesting.
_SUMS = (ast.Add, ast.Sub)
_PRODUCTS = (ast.Mult, ast.Div)


class _Builder:
    """Builds the SymPy expression node by node; every constant node is bounded before SymPy
    evaluates it (so neither its size nor the work to evaluate it can grow without limit)."""

    def __init__(self, allowed: Mapping[str, sp.Expr], what: str, source: str):
        self.allowed = allowed
        self.what = what
        self.source = source
        self.memo: dict[int, bounds.Encloser] = {}

    def fail(self, message: str) -> InputError:
        names = ", ".join(sorted(self.allowed, key=str.lower))
        return InputError(
            f"{self.what}: {message}; allowed names: {names}; functions: {', '.join(sorted(FUNCTIONS, key=str.lower))}"
        )

    def bounded(self, unevaluated: sp.Expr) -> None:
        """Refuse a constant that is not real, or is beyond 1e300 or below 1e-300 in size (not 0)."""
        if unevaluated.is_Rational:
            _bounded(unevaluated, self.what)
        elif not unevaluated.free_symbols:
            bounds.check(unevaluated, self.what, memo=self.memo)

    def sign(self, value: sp.Expr) -> int | None:
        """The sign of a constant (None for a symbolic value or one that is 0 to 1233 digits)."""
        if value.free_symbols:
            return None
        return bounds.sign(value, memo=self.memo)

    def build(self, node: ast.AST, depth: int) -> sp.Expr:
        if depth > MAX_DEPTH:
            raise InputError(f"{self.what} is nested more than {MAX_DEPTH} levels deep")
        if isinstance(node, ast.Constant):
            v = node.value
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise self.fail(f"{v!r} is not a number")
            # the literal as typed, exactly (a float would round long decimals and 1e-400)
            literal = ast.get_source_segment(self.source, node) or ""
            if not _NUMBER.match(literal) or "/" in literal:
                raise InputError(f"{self.what}: write numbers with decimal digits 0-9, got {literal!r}")
            return parse_number(literal, what=self.what)
        if isinstance(node, ast.Name):
            if node.id in self.allowed:
                return self.allowed[node.id]
            raise self.fail(f"{node.id!r} is not allowed here")
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
            operand = self.build(node.operand, depth + 1)
            return operand if isinstance(node.op, ast.UAdd) else -operand
        if isinstance(node, ast.BinOp):
            if isinstance(node.op, _SUMS + _PRODUCTS):
                return self.chain(node, depth)
            return self.binop(node, depth)
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                raise self.fail(f"calling {_show(node.func, self.source)} is not allowed")
            if node.keywords:
                raise self.fail("functions take no keyword arguments")
            args = [self.build(a, depth + 1) for a in node.args]
            function = FUNCTIONS[node.func.id]
            try:
                unevaluated = function(*args, evaluate=False)
            except TypeError:
                raise InputError(f"{self.what}: wrong number of arguments to {node.func.id}") from None
            self.bounded(unevaluated)
            return function(*args)
        raise self.fail(f"{_show(node, self.source)} ({type(node).__name__.lower()}) is not allowed")

    def chain(self, node: ast.BinOp, depth: int) -> sp.Expr:
        """A flat chain of + and - (or of * and /): one level of nesting however long, each
        partial result bounded."""
        kinds = _SUMS if isinstance(node.op, _SUMS) else _PRODUCTS
        steps: list[tuple[type, ast.AST]] = []
        first: ast.AST = node
        while isinstance(first, ast.BinOp) and isinstance(first.op, kinds):
            steps.append((type(first.op), first.right))
            first = first.left
        value = self.build(first, depth + 1)
        if kinds is _SUMS:
            terms = [value]
            for op, right in reversed(steps):
                term = self.build(right, depth + 1)
                terms.append(term if op is ast.Add else -term)
            total = sp.Add(*terms)  # at most MAX_LENGTH / 2 terms each below 1e300: only the total needs a bound
            self.bounded(total)
            exact_digits(total.as_coeff_Add()[0], self.what)
            return total
        for op, right in reversed(steps):
            factor = self.build(right, depth + 1)
            if op is ast.Div:
                if factor == 0 or self.sign(factor) == 0:
                    raise InputError(f"{self.what} divides by zero")
                inverse = sp.Pow(factor, -1, evaluate=False)
                self.bounded(inverse)
                self.bounded(sp.Mul(value, inverse, evaluate=False))
                value = value / factor
            else:
                self.bounded(sp.Mul(value, factor, evaluate=False))
                value = value * factor
            exact_digits(value.as_coeff_Mul()[0], self.what)  # a long product of exact numbers near 1
        return value

    def binop(self, node: ast.BinOp, depth: int) -> sp.Expr:
        left = self.build(node.left, depth + 1)
        right = self.build(node.right, depth + 1)
        if isinstance(node.op, ast.Pow):
            if not right.free_symbols and self.sign(sp.Add(sp.Abs(right, evaluate=False), -MAX_EXPONENT, evaluate=False)) == 1:
                raise InputError(f"{self.what} has an exponent larger than {MAX_EXPONENT}")
            if (left == 0 or self.sign(left) == 0) and self.sign(right) == -1:
                raise InputError(f"{self.what} divides by zero")
            self.bounded(sp.Pow(left, right, evaluate=False))
            if right.is_Rational:  # digits before SymPy (or a later expand) multiplies them out
                exact_digits(left, self.what, power=right)
            return left**right
        raise self.fail(f"the operator {type(node.op).__name__} is not allowed")


def _nodes(expr: sp.Expr, cap: int) -> int:
    """The nodes of ``expr``'s tree, counted up to ``cap`` + 1."""
    return sum(1 for _ in itertools.islice(sp.preorder_traversal(expr), cap + 1))


def _show(node: ast.AST, source: str) -> str:
    """The text of ``node`` as typed (never ast.unparse, which recurses: 400 chained ``~`` ran out of stack)."""
    text = " ".join((ast.get_source_segment(source, node) or type(node).__name__).split())
    return repr(text if len(text) <= 40 else text[:37] + "...")
