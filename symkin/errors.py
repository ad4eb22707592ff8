"""The exceptions symkin raises.

Every error symkin raises on bad input is a :class:`SymkinError`; its message is one
sentence that says what is wrong and how to fix it.  Users catch the base class, or a
more specific one::

    >>> import symkin
    >>> try:
    ...     symkin.schemes.two_row("AX")
    ... except symkin.SymkinError as err:
    ...     print(type(err).__name__)
    ModelError
"""

from __future__ import annotations

__all__ = [
    "NonFiniteInputWarning",
    "NullFloatWarning",
    "warn_user",
    "SymkinError",
    "ModelError",
    "TrainFileError",
    "InputError",
    "TextInputError",
    "DeterminacyError",
    "UnderdeterminedError",
    "OverdeterminedError",
    "SingularConfigurationError",
    "UnsupportedError",
    "TimeLimitError",
    "ToolError",
    "SymkinWarning",
    "CoaxialityWarning",
    "PoleError",
    "PoleWarning",
    "FloatOverflowWarning",
    "PrecisionWarning",
    "SimplificationBudgetWarning",
]


class SymkinError(Exception):
    """Base class of every error symkin raises on purpose."""


class ModelError(SymkinError, ValueError):
    """The mechanism description is invalid (teeth, radii, names, meshes)."""


class TrainFileError(ModelError):
    """A train file cannot be read as a train: the message names the file, the table and the key.

    Attributes
    ----------
    path : str
        The file (or the ready-made train's name).
    where : str
        The table and key, e.g. ``[links.P1] carrier``.
    """

    def __init__(self, path: str, where: str, problem: str):
        super().__init__(f"{path}: {where + ': ' if where else ''}{problem}")
        self.path, self.where = path, where


class InputError(SymkinError, ValueError):
    """A value given by the user (a number, a name, an expression) cannot be used."""


class TextInputError(InputError, TypeError):
    """Text was given to a library function where a value is meant: symkin's functions take
    numbers, SymPy expressions, Fractions and pint quantities; :func:`symkin.parse` reads text."""


class DeterminacyError(SymkinError, ValueError):
    """The chosen known speeds do not determine the mechanism's motion exactly once.

    Attributes
    ----------
    dof : int
        Degrees of freedom of the mechanism.
    admissible : tuple of str
        One admissible choice of links whose speeds determine all the others.
    """

    def __init__(self, message: str, *, dof: int, admissible: tuple[str, ...]):
        super().__init__(message)
        self.dof = dof
        self.admissible = admissible


class UnderdeterminedError(DeterminacyError):
    """Too few independent speeds are known."""


class OverdeterminedError(DeterminacyError):
    """More speeds are known than the mechanism's degrees of freedom allow."""


class SingularConfigurationError(DeterminacyError):
    """The law asked for is singular for these dimensions (a vanishing denominator)."""


class PoleError(InputError):
    """A compiled law was evaluated at a pole (a denominator vanishes at these inputs)."""


class TimeLimitError(InputError):
    """A search would not finish within its time limit: the message says how far it got and
    suggests narrower bounds (nothing the user had is lost; nothing partial is returned)."""


class UnsupportedError(SymkinError, NotImplementedError):
    """A valid description that this version of symkin cannot handle yet."""


class ToolError(SymkinError, RuntimeError):
    """An optional system tool symkin calls (pdflatex, ffmpeg) is missing or failed."""


class SymkinWarning(UserWarning):
    """Base class of symkin's warnings."""


class CoaxialityWarning(SymkinWarning):
    """The tooth numbers or radii put a planet's axis at two different distances."""


class NonFiniteInputWarning(SymkinWarning):
    """An input was nan or infinite, and the outputs at those points are nan or inf
    (never a finite number taken for a value of the law)."""


class NullFloatWarning(SymkinWarning):
    """A value written to JSON has no float (beyond the float range, not finite, or not
    real): its ``"float"`` is null.  The command line notes it with ``--json`` only."""


class PoleWarning(SymkinWarning):
    """A float evaluation met a pole: the points concerned hold inf or nan, never a finite wrong value."""


class FloatOverflowWarning(SymkinWarning):
    """A float evaluation overflowed: the law is finite there but beyond the float range; the
    points concerned hold inf or nan (use smaller inputs, other units, or the mpmath backend)."""


class PrecisionWarning(SymkinWarning):
    """A numeric request was served at a different speed or precision than asked (a fallback), or loses digits."""


class SimplificationBudgetWarning(SymkinWarning):
    """A simplification ran out of its time or size budget; the law is kept as derived (exact, untidy)."""


def warn_user(message: str, category: type[Warning]) -> None:
    """Issue a warning attributed to the first caller outside the symkin package."""
    import sys
    import warnings
    from types import FrameType

    level = 1
    frame: FrameType | None = sys._getframe(1)
    while frame is not None and str(frame.f_globals.get("__name__", "")).split(".")[0] == "symkin":
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level + 1)  # the first frame outside symkin
