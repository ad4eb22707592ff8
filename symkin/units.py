"""Quantities with units at symkin's boundary.

symkin computes in exact numbers whose units are fixed by convention: angular velocities in
rad/s, angles in rad, lengths in m (the gear geometry of a scheme in the length unit of its
module), times in s.  Where a user thinks in other units, symkin takes a pint quantity (from
pint's application registry, or any registry) and converts it once, exactly, on the way in.
A bare number keeps its documented unit.  Text with a unit (``"300 rpm"``) is read by
:func:`symkin.parse` (``symkin.parse("300 rpm", unit="rad/s")``).

    >>> import pint
    >>> from symkin import schemes
    >>> from symkin.units import quantity
    >>> ureg = pint.get_application_registry()
    >>> quantity(ureg.Quantity(300, "rpm"), "rad/s")
    10*pi
    >>> aa = schemes.two_row("AA", teeth=(54, 45, 44, 55))
    >>> aa.speeds({"1": ureg.Quantity(300, "rpm"), "4": 0})["H"]        # the same as {"1": 10*pi, "4": 0}
    -240*pi

Where quantities are accepted:

- known speeds and inputs (``Mechanism.speeds``, ``Mechanism.motion``,
  :func:`symkin.kinematics.solve_speeds`, the drives of :mod:`symkin.drives`): rad/s;
- angles of drives: rad;
- the Cardan slider (:meth:`symkin.mechanisms.cardan.CardanSlider.build`): lengths in m,
  angles in rad, and the times of its tables in s;
- the command line: ``--omega LINK=VALUE`` (rad/s), ``symkin cardan``'s ``--length`` and
  ``--pin-radius`` (m), ``--speed`` (rad/s), its angles (rad) and times (s), ``--t-end`` of
  the figure commands (s).  With ``--json`` the output's ``"units"`` names the unit of every
  dimensional key.

pint is imported only when a value has a unit, so a run without units never loads it.
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from symkin.values import as_expr, is_quantity, unit_factor

__all__ = ["UNITS", "quantity", "factor", "is_quantity"]

#: symkin's unit of each kind of quantity: what a bare number means.
UNITS: dict[str, str] = {
    "angular velocity": "rad/s",
    "angular acceleration": "rad/s^2",
    "angle": "rad",
    "length": "m",
    "time": "s",
    "velocity": "m/s",
    "acceleration": "m/s^2",
}


def quantity(value: Any, unit: str, *, what: str = "value") -> sp.Expr:
    """The exact value of ``value`` in ``unit``.

    Parameters
    ----------
    value : pint quantity, number or SymPy expression
        A quantity (``ureg.Quantity(300, "rpm")``) is converted; a bare number is taken to be
        in ``unit`` already.
    unit : str
        The unit wanted, in pint's spelling (``"rad/s"``, ``"rad"``, ``"m"``, ``"s"``).
    what : str
        What the value is, for error messages.

    Returns
    -------
    sympy.Expr
        Exact: the conversion factor is a rational or a rational times pi when pint's factor
        is one (see :func:`factor`).

    Raises
    ------
    InputError
        A unit of another kind (kg for a length), or a bad number; text
        (:class:`~symkin.errors.TextInputError`: read it with :func:`symkin.parse`).

    Examples
    --------
    >>> import pint
    >>> ureg = pint.get_application_registry()
    >>> quantity(ureg.Quantity(90, "deg/s"), "rad/s"), quantity(ureg.Quantity(5, "mm"), "m"), quantity(2, "rad")
    (pi/2, 1/200, 2)
    """
    return as_expr(value, what=what, unit=unit)


def factor(unit_from: str, unit_to: str) -> sp.Expr:
    """The exact factor from ``unit_from`` to ``unit_to`` (pint's float made exact when it is a
    rational, or a rational times pi, with a denominator up to 10^6).

    >>> factor("rpm", "rad/s"), factor("deg", "rad"), factor("inch", "mm")
    (pi/30, pi/180, 127/5)
    """
    return unit_factor(unit_from, unit_to)
