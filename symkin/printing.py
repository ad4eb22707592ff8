"""LaTeX for derived laws, as a paper prints them.

One function, :func:`latex`, behind a :class:`~sympy.printing.latex.LatexPrinter`
subclass; laws print themselves through their ``_latex`` method.  No global state.
Everything it returns compiles with base TeX Live (``amsmath`` only).

    >>> import symkin
    >>> law = symkin.schemes.two_row("AI", teeth=True).ratio("1", "H", fixed="4")
    >>> print(symkin.latex(law))
    i_{1H}^{(4)} = 1 + \\frac{z_{2} z_{4}}{z_{1} z_{3}}
    >>> print(symkin.latex(law, number="13a"))
    \\begin{equation}
    i_{1H}^{(4)} = 1 + \\frac{z_{2} z_{4}}{z_{1} z_{3}} \\tag{13a}
    \\end{equation}

Options a paper needs: the paper's own symbols (``symbol_names``), equation numbers
(``number``), laws aligned at ``=`` (``aligned``), long right-hand sides broken over
lines at ``+`` and ``-`` (``width``), and display fractions (``frac="dfrac"``).
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Iterable, Mapping
from typing import Any

import sympy as sp
from sympy.printing.latex import LatexPrinter

from symkin.errors import InputError
from symkin.laws import Law

__all__ = ["SymkinLatexPrinter", "latex", "latex_lines", "estimated_width", "escape_text"]

_FRACS = ("frac", "dfrac", "tfrac")


class SymkinLatexPrinter(LatexPrinter):
    """LaTeX printer for symkin: polynomial terms in the paper's order (1 + ... first)."""

    printmethod = "_latex"
    _default_settings = {**LatexPrinter._default_settings, "order": "none"}  # noqa: RUF012 (SymPy printers declare settings so)

    def _print_Add(self, expr: sp.Add, order: Any = None) -> str:
        return "".join(self._add_pieces(expr))

    def _add_pieces(self, expr: sp.Add) -> list[str]:
        """The terms of a sum, each with its sign (" + ..." / " - ..."), the first bare."""
        # constants first, as a paper writes 1 + z2 z4 / (z1 z3)
        terms = sorted(expr.args, key=lambda a: (not a.is_number, sp.default_sort_key(a)))
        # and a positive term first, as a reader writes r_4 - r_2 (not -r_2 + r_4)
        if sp.Mul(terms[0]).could_extract_minus_sign():
            first = next((t for t in terms if not sp.Mul(t).could_extract_minus_sign()), None)
            if first is not None:
                terms.remove(first)
                terms.insert(0, first)
        pieces = []
        for i, term in enumerate(terms):
            sign = ""
            if i == 0:
                pass
            elif sp.Mul(term).could_extract_minus_sign():
                sign = " - "
                term = -term
            else:
                sign = " + "
            term_tex = self._print(term)
            if self._needs_add_brackets(term):
                term_tex = rf"\left({term_tex}\right)"
            pieces.append(sign + term_tex)
        return pieces


def _laws(obj: Any) -> list[Law] | None:
    if isinstance(obj, Law):
        return [obj]
    if isinstance(obj, sp.Equality):
        return [Law(obj.lhs, obj.rhs)]
    if hasattr(obj, "laws") and callable(obj.laws):
        return list(obj.laws())
    if isinstance(obj, (list, tuple)) and obj and all(isinstance(x, (Law, sp.Equality)) for x in obj):
        return [x if isinstance(x, Law) else Law(x.lhs, x.rhs) for x in obj]
    return None


class _Names(dict):
    """symbol_names for the printer: keys are Symbols, or names matching every symbol so named."""

    def __init__(self, mapping: Mapping[Any, str] | None):
        super().__init__()
        self.by_name: dict[str, str] = {}
        for key, tex in dict(mapping or {}).items():
            if not isinstance(tex, str):
                raise InputError(f"symbol_names maps a symbol to its LaTeX text, got {tex!r} for {key!r}")
            if isinstance(key, str):
                self.by_name[key] = tex
            elif isinstance(key, sp.Symbol):
                self[key] = tex
            else:
                raise InputError(f"symbol_names keys are SymPy symbols or symbol names, got {key!r}")

    def get(self, key: Any, default: Any = None) -> Any:
        if key in self:
            return self[key]
        if isinstance(key, sp.Symbol):
            return self.by_name.get(key.name, default)
        return default


def _printer(symbol_names: Mapping[Any, str] | None, settings: Mapping[str, Any]) -> SymkinLatexPrinter:
    printer = SymkinLatexPrinter(dict(settings))
    printer._settings["symbol_names"] = _Names(symbol_names)
    return printer


def _tokens(printer: SymkinLatexPrinter, expr: sp.Expr, width: float) -> list[str]:
    """Pieces of LaTeX whose concatenation prints ``expr``; a line may break before any
    piece that starts with a sign (" + " or " - ") or opens a factor (\\Bigl().

    Sums break between terms; a product keeps its plain factors together and opens its
    sum factors in \\Bigl( ... \\Bigr), which may span lines; a fraction N/D with a sum
    N too wide for one line is written (1/D)(N).  Pieces narrower than ``width`` are
    printed whole.
    """
    expr = sp.sympify(expr, strict=True)
    whole = printer._print(expr)
    if estimated_width(whole) <= width:
        return [whole]
    if isinstance(expr, sp.Add):
        out: list[str] = []
        for piece, term in zip(printer._add_pieces(expr), _add_terms(expr)):
            sign = piece[:3] if piece[:3] in (" + ", " - ") else ""
            inner = _tokens(printer, term, width)
            if len(inner) == 1:
                out.append(piece)
            else:
                out += [sign + inner[0]] + inner[1:]
        return out
    if isinstance(expr, sp.Mul):
        coeff, _ = expr.as_coeff_Mul()
        sign = ""
        if coeff.is_negative:
            sign, expr = "- ", -expr
            coeff, _ = expr.as_coeff_Mul()
        num, den = sp.fraction(expr)
        if den != 1:
            if isinstance(num, sp.Add):
                return _bracketed(printer, sign + rf"\frac{{1}}{{{printer._print(den)}}} ", num, "", width)
            return [sign + printer._print(expr)]
        factors = sp.Mul.make_args(expr)
        plain = [f for f in factors if not _is_sum_factor(f)]
        sums = [f for f in factors if _is_sum_factor(f)]
        if not sums:
            return [sign + printer._print(expr)]
        head = sign + (printer._print(sp.Mul(*plain)) + " " if plain else "")
        out = []
        for i, f in enumerate(sums):
            base, power = (f.base, f.exp) if isinstance(f, sp.Pow) else (f, sp.Integer(1))
            tail = "" if power == 1 else f"^{{{printer._print(power)}}}"
            out += _bracketed(printer, head if i == 0 else "", base, tail, width)
        return out
    return [whole]


def _add_terms(expr: sp.Add) -> list[sp.Expr]:
    """The terms of a sum in the order and with the signs _add_pieces prints them."""
    terms = sorted(expr.args, key=lambda a: (not a.is_number, sp.default_sort_key(a)))
    return [t if i == 0 or not sp.Mul(t).could_extract_minus_sign() else -t for i, t in enumerate(terms)]


def _is_sum_factor(f: sp.Expr) -> bool:
    return isinstance(f, sp.Add) or (isinstance(f, sp.Pow) and isinstance(f.base, sp.Add) and f.exp.is_Integer and f.exp > 0)


def _bracketed(printer: SymkinLatexPrinter, head: str, add: sp.Add, tail: str, width: float) -> list[str]:
    inner = _tokens(printer, add, width)
    inner[0] = head + r"\Bigl(" + inner[0]
    inner[-1] = inner[-1] + r"\Bigr)" + tail
    return inner


def latex_lines(expr: Any, width: float, *, symbol_names: Mapping[Any, str] | None = None, **settings: Any) -> list[str]:
    """The LaTeX of ``expr`` cut into lines of at most about ``width`` characters.

    Lines break before a ``+`` or ``-``: of the top-level sum, or of a sum inside a
    product (opened in \\Bigl( ... \\Bigr), which may span lines), or of the numerator of
    a fraction (written as (1/D)(...)).  A piece wider than ``width`` with no sum to
    break stays whole.  Continuation lines start with the sign; join the lines in an
    ``aligned`` environment.

    >>> import sympy as sp
    >>> a, b, c, d = sp.symbols("a b c d")
    >>> latex_lines(a + b + c, width=100)
    ['a + b + c']
    >>> latex_lines(a + b + c, width=6)
    ['a + b', '+ c']
    >>> print("\\n".join(latex_lines(d * (a + b + c), width=6)))
    d \\Bigl(a + b
    + c\\Bigr)
    """
    printer = _printer(symbol_names, settings)
    tokens = _tokens(printer, _strict(expr), width)
    lines: list[str] = []
    current = ""
    for tok in tokens:
        if current and tok.startswith((" + ", " - ", "\\Bigl(")) and estimated_width(current + tok) > width:
            lines.append(current)
            current = ""
        current += tok
    lines.append(current)
    return [line.strip() for line in lines]


def latex(
    obj: Any,
    *,
    symbol_names: Mapping[Any, str] | None = None,
    number: str | int | Iterable[str | int] | None = None,
    aligned: bool | None = None,
    width: float | None = None,
    frac: str = "frac",
    **settings: Any,
) -> str:
    """LaTeX of a law, a set of laws (e.g. a :class:`~symkin.kinematics.Speeds`), or an expression.

    Parameters
    ----------
    obj : Law, sympy.Eq, Speeds, sequence of Law, or sympy expression
    symbol_names : mapping of Symbol (or symbol name) to str, optional
        The paper's notation: LaTeX to print for given symbols, e.g.
        ``{"omega_23": r"\\omega_{\\mathrm{sat}}"}``.
    number : str or int, or a sequence of them, optional
        Equation number(s): wraps the result in an ``equation`` environment with ``\\tag``
        (or an ``align`` environment with one tag per law).
    aligned : bool, optional
        Several laws: align them at ``=`` (default True for several laws).
    width : float, optional
        Break right-hand sides wider than about ``width`` characters into lines at
        ``+`` and ``-`` (see :func:`latex_lines`); about 70 fills a 16 cm text width.
    frac : {"frac", "dfrac", "tfrac"}
        The fraction command (``dfrac`` keeps display size inside sums and tables).
    **settings
        Passed to SymPy's LatexPrinter (e.g. ``fold_short_frac=True``).

    Examples
    --------
    >>> import symkin
    >>> from symkin import schemes, symbols as S
    >>> speeds = schemes.two_row("AI").speeds({"1": S.omega("1"), "4": S.omega("4")})
    >>> print(symkin.latex(speeds.law("H"), symbol_names={"omega_H": r"\\Omega"}, frac="dfrac"))
    \\Omega = \\dfrac{\\omega_{1} r_{1} r_{3} + \\omega_{4} r_{2} r_{4}}{r_{1} r_{3} + r_{2} r_{4}}
    >>> print(symkin.latex(speeds.law("H"), width=12))
    \\begin{aligned}
    \\omega_{H} &= \\frac{1}{r_{1} r_{3} + r_{2} r_{4}} \\Bigl(\\omega_{1} r_{1} r_{3} \\\\
    &\\qquad + \\omega_{4} r_{2} r_{4}\\Bigr)
    \\end{aligned}
    """
    if frac not in _FRACS:
        raise InputError(f"frac must be one of {', '.join(_FRACS)}, got {frac!r}")
    if width is not None and (not isinstance(width, (int, float)) or isinstance(width, bool) or width <= 0):
        raise InputError(f"width must be a positive number of characters, got {width!r}")
    printer = _printer(symbol_names, settings)
    laws = _laws(obj)
    if laws is None:
        expr = obj if isinstance(obj, sp.Basic) else _strict(obj)
        if width is None:
            return _frac(_wrap(printer.doprint(expr), number), frac)
        lines = latex_lines(expr, width, symbol_names=symbol_names, **settings)
        if len(lines) == 1:
            return _frac(_wrap(lines[0], number), frac)
        body = "\\begin{aligned}\n" + " \\\\\n".join(("&" if i == 0 else "&\\qquad ") + line for i, line in enumerate(lines)) + "\n\\end{aligned}"
        return _frac(_wrap(body, number), frac)
    rows = [_law_rows(printer, L, width, symbol_names, settings) for L in laws]
    if len(laws) == 1 and aligned is not True and len(rows[0]) == 1:
        return _frac(_wrap(printer.doprint(laws[0]), number), frac)
    if number is not None and len(laws) > 1:
        tags = [number] * len(laws) if isinstance(number, (str, int)) else list(number)
        if len(tags) != len(laws):
            raise InputError(f"{len(laws)} laws need {len(laws)} equation numbers, got {len(tags)}")
        lines = []
        for law_rows, tag in zip(rows, tags):
            law_rows = list(law_rows)
            law_rows[0] += f" \\tag{{{tag}}}"
            lines += law_rows[:1] + [r + r" \notag" for r in law_rows[1:]]
        return _frac("\\begin{align}\n" + " \\\\\n".join(lines) + "\n\\end{align}", frac)
    body = "\\begin{aligned}\n" + " \\\\\n".join(r for law_rows in rows for r in law_rows) + "\n\\end{aligned}"
    return _frac(_wrap(body, number), frac)


def _strict(obj: Any) -> sp.Basic:
    if isinstance(obj, str):
        raise InputError("latex() prints laws and SymPy expressions, not strings; parse text with symkin.parse")
    try:
        return sp.sympify(obj, strict=True)
    except (sp.SympifyError, TypeError):
        raise InputError(f"latex() prints laws and SymPy expressions, got {obj!r}") from None


def _law_rows(printer: SymkinLatexPrinter, law: Law, width: float | None, names: Any, settings: Any) -> list[str]:
    lhs = printer.doprint(law.lhs)
    if width is None:
        return [f"{lhs} &= {printer.doprint(law.rhs)}"]
    lines = latex_lines(law.rhs, width, symbol_names=names, **settings)
    return [f"{lhs} &= {lines[0]}"] + [f"&\\qquad {line}" for line in lines[1:]]


def _wrap(body: str, number: Any) -> str:
    if number is None:
        return body
    if not isinstance(number, (str, int)) or isinstance(number, bool):
        raise InputError(f"one expression takes one equation number, got {number!r}")
    return f"\\begin{{equation}}\n{body} \\tag{{{escape_text(str(number))}}}\n\\end{{equation}}"


def _frac(tex: str, frac: str) -> str:
    return tex if frac == "frac" else tex.replace("\\frac{", f"\\{frac}{{")


# --------------------------------------------------------------------------- width
_ZERO = {"left", "right", "bigl", "bigr", "Bigl", "Bigr", "biggl", "biggr", "displaystyle", "textstyle", "notag", "limits"}
_SPACES = {"quad": 2.0, "qquad": 4.0, ",": 0.3, ";": 0.5, ":": 0.4, "!": 0.0, " ": 0.5}
_TEXT = {"text", "mathrm", "textbf", "mathbf", "operatorname", "mathit"}


def _group(tex: str, i: int) -> tuple[str, int]:
    """The brace group (or single token) starting at ``tex[i]``, and the index after it."""
    while i < len(tex) and tex[i] == " ":
        i += 1
    if i >= len(tex):
        return "", i
    if tex[i] == "{":
        depth = 0
        for j in range(i, len(tex)):
            if tex[j] == "{" and (j == 0 or tex[j - 1] != "\\"):
                depth += 1
            elif tex[j] == "}" and tex[j - 1] != "\\":
                depth -= 1
                if depth == 0:
                    return tex[i + 1 : j], j + 1
        return tex[i + 1 :], len(tex)
    m = re.match(r"\\[A-Za-z]+|\\.|.", tex[i:])
    assert m is not None
    return m.group(0), i + len(m.group(0))


def estimated_width(tex: str) -> float:
    """A rough typeset width of math LaTeX, in characters (a letter is 1, a sub/superscript
    0.7, a fraction its wider part, a binary operator 2).

    >>> estimated_width(r"\\omega_{1} r_{1} + \\frac{a b c}{d}")
    8.8
    """
    w, i = 0.0, 0
    while i < len(tex):
        c = tex[i]
        if c == "\\":
            m = re.match(r"\\([A-Za-z]+|.)", tex[i:])
            assert m is not None
            name = m.group(1)
            i += len(m.group(0))
            if name in _FRACS:
                a, i = _group(tex, i)
                b, i = _group(tex, i)
                w += max(estimated_width(a), estimated_width(b)) + 0.4
            elif name in _ZERO:
                continue
            elif name in _SPACES:
                w += _SPACES[name]
            elif name in _TEXT:
                g, i = _group(tex, i)
                w += 0.9 * len(re.sub(r"\\[A-Za-z]+|[{}]", "", g))
            elif name in ("\\",):
                continue
            elif name in ("sin", "cos", "tan", "log", "exp"):
                w += len(name)
            else:
                w += 1.0
        elif c in "_^":
            g, i = _group(tex, i + 1)
            w += 0.7 * estimated_width(g)
        elif c in "{} &":
            i += 1
        elif c in "+-=<>":
            w += 2.0
            i += 1
        else:
            w += 1.0
            i += 1
    return round(w, 6)


# --------------------------------------------------------------------------- text
_SPECIAL = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
            "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
            "<": r"\textless{}", ">": r"\textgreater{}", "|": r"\textbar{}", '"': "''"}
_UNICODE = {"\u2013": "--", "\u2014": "---", "\u2018": "`", "\u2019": "'", "\u201c": "``", "\u201d": "''",
            "\u2212": "-", "\u00d7": r"$\times$", "\u2248": r"$\approx$", "\u2264": r"$\leq$", "\u2265": r"$\geq$",
            "\u00b1": r"$\pm$", "\u00b0": r"$^\circ$", "\u2026": r"\dots{}", "\u00a0": "~", "\u2192": r"$\to$"}
_BREAK_AFTER = set("/*=,;")
_CYRILLIC = dict(zip(
    "абвгдеёжзийклмнопрстуфхцчшщъыьэюяіїєґ",
    ["a", "b", "v", "g", "d", "e", "e", "zh", "z", "i", "y", "k", "l", "m", "n", "o", "p", "r", "s", "t", "u",
     "f", "kh", "ts", "ch", "sh", "shch", "", "y", "", "e", "yu", "ya", "i", "yi", "ye", "g"],
))


def escape_text(text: Any, *, breakable: bool = False) -> str:
    """Text safe to put in a LaTeX paragraph (or ``\\text{...}``) with base TeX Live.

    Special characters are escaped; Greek letters and common symbols become math;
    Cyrillic is transliterated (base TeX Live has no Cyrillic fonts); any other
    non-ASCII character is spelled out.  ``breakable`` allows line breaks after
    ``/ * = , ;`` so long formulas in prose do not overflow.

    >>> print(escape_text("50% of z_1 & {x} ~ 2^3 \\\\ ω"))
    50\\% of z\\_1 \\& \\{x\\} \\textasciitilde{} 2\\textasciicircum{}3 \\textbackslash{} $\\omega$
    >>> print(escape_text("Кинематика"))
    Kinematika
    >>> print(escape_text("1/(1-2)", breakable=True))
    1/\\allowbreak{}(1-2)
    """
    out = []
    for ch in str(text):
        if ch in _SPECIAL:
            out.append(_SPECIAL[ch])
        elif ch in _UNICODE:
            out.append(_UNICODE[ch])
        elif ord(ch) < 128:
            out.append(ch if ch.isprintable() or ch in "\n\t" else " ")
        else:
            out.append(_unicode(ch))
        if breakable and ch in _BREAK_AFTER:
            out.append(r"\allowbreak{}")
    return "".join(out)


def _unicode(ch: str) -> str:
    name = unicodedata.name(ch, "")
    m = re.match(r"GREEK (SMALL|CAPITAL) LETTER (\w+)$", name)
    if m:
        letter = m.group(2).lower()
        if m.group(1) == "CAPITAL":
            letter = letter.capitalize()
            if letter in ("Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi", "Omega"):
                return rf"$\{letter}$"
            return escape_text(unicodedata.normalize("NFKD", ch).encode("ascii", "ignore").decode() or "?")
        if letter == "omicron":
            return "o"
        return rf"$\{letter}$"
    if ch.lower() in _CYRILLIC:  # base TeX Live has no Cyrillic fonts: transliterate
        latin = _CYRILLIC[ch.lower()]
        return latin.capitalize() if ch.isupper() else latin
    plain = unicodedata.normalize("NFKD", ch).encode("ascii", "ignore").decode()
    if plain and plain.isprintable():
        return escape_text(plain)
    return rf"\texttt{{[U+{ord(ch):04X}]}}"
