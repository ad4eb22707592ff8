"""Helpers shared by the CLI commands: parsing values, printing text or JSON."""

from __future__ import annotations

import json
import math
import sys
import warnings
from contextlib import contextmanager
from typing import Any, Iterator

import sympy as sp

from ..errors import InputError, SymkinWarning
from ..parsing import parse_expression, parse_integer

__all__ = ["teeth_list", "link_value", "exact_json", "emit", "collect_warnings", "add_json_flag"]


def add_json_flag(parser: Any) -> None:
    parser.add_argument("--json", action="store_true", help="print machine-readable JSON instead of text")


def teeth_list(text: str, counts: tuple[int, ...], what: str = "--teeth") -> list[sp.Integer]:
    """Comma-separated tooth numbers, exactly ``counts`` of them."""
    if not isinstance(text, str) or not text.strip():
        raise InputError(f"{what} is empty; give {' or '.join(map(str, counts))} comma-separated tooth numbers")
    parts = [p.strip() for p in text.split(",")]
    if len(parts) not in counts:
        raise InputError(f"{what} needs {' or '.join(map(str, counts))} comma-separated tooth numbers, got {len(parts)}")
    values = [parse_integer(p, what=f"tooth number {i} in {what}") for i, p in enumerate(parts, 1)]
    for i, v in enumerate(values, 1):
        if v <= 0:
            raise InputError(f"tooth number {i} in {what} must be positive, got {v}")
    return values


def link_value(text: str, what: str = "--omega") -> tuple[str, sp.Expr]:
    """``LINK=VALUE``; VALUE is a number or a constant expression such as 2*pi."""
    if not isinstance(text, str) or "=" not in text:
        raise InputError(f"{what} takes LINK=VALUE (for example 1=100), got {text!r}")
    link, _, value = text.partition("=")
    link = link.strip()
    if not link:
        raise InputError(f"{what} {text!r} names no link; write LINK=VALUE, for example 1=100")
    return link, parse_expression(value, what=f"{what} value for link {link}")


def exact_json(value: sp.Expr) -> dict[str, Any]:
    """An exact value as {'exact': text, 'float': number or null}."""
    out: dict[str, Any] = {"exact": str(value)}
    try:
        f = float(sp.N(value, 17)) if value.is_number else None
    except (TypeError, ValueError, OverflowError):
        f = None
    out["float"] = f if f is not None and math.isfinite(f) else None
    return out


def fmt_float(value: sp.Expr) -> str:
    if not value.is_number:
        return ""
    try:
        return f"{float(sp.N(value, 17)):.10g}"
    except (TypeError, ValueError, OverflowError):
        return str(sp.N(value, 10))


def emit(args: Any, text: str, data: dict[str, Any]) -> None:
    if getattr(args, "json", False):
        json.dump(data, sys.stdout, indent=2, ensure_ascii=False, allow_nan=False)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")


@contextmanager
def collect_warnings() -> Iterator[list[str]]:
    """Collect symkin warnings as one-line messages instead of printing them."""
    messages: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", SymkinWarning)
        yield messages
    messages.extend(str(w.message) for w in caught if issubclass(w.category, SymkinWarning))
