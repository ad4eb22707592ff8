"""Synthesis of two-row planetary trains whose stepped helical planet carries no axial load.

Everything here is derived from the engine and then used:

* :func:`ratio_law`, :func:`assembly_condition`, :func:`working_coaxiality` and
  :func:`helical_coaxiality` come from the mechanism model (contact conditions, mesh
  geometry);
* :func:`balance_condition` comes from the planet statics (:mod:`symkin.statics`),
  restated for reference helix angles;
* :func:`tooth_equations` solves ratio, coaxiality, balance and assembly for the tooth
  numbers, given the ratio i, x = Z2/Z3, k, the assembly integers P, Q and
  delta = d_w2/d_w3;
* :func:`existence_bounds` and :func:`existence_interval` give, for k satellites and a
  diameter ratio delta, the ratios a scheme can realise (ratio, coaxiality and the
  neighbour condition on pitch circles);
* :func:`synthesize_helical` enumerates integer tooth sets for a target ratio, with the helix
  angles that cancel the planet's axial forces for unshifted (zero) meshes, and keeps
  those that are coaxial, can be assembled and leave room between the planets.

    >>> eqs = tooth_equations("AI")
    >>> eqs.chain[Z[1]]
    k*(P + Q*x)/i_{1H}^{(4)}

The derived laws and tooth equations (:mod:`.conditions`), the existence regions
(:mod:`.regions`), the request and result types (:mod:`.request`) and the search
(:mod:`.search`) are separate modules; every public name is importable from here.
"""

from __future__ import annotations

from symkin.mechanisms.helical.balanced.conditions import (
    ALPHA_T12,
    ALPHA_T34,
    ALPHA_TW12,
    ALPHA_TW34,
    BETA12,
    BETA34,
    DELTA,
    LAMBDA,
    M12,
    M34,
    MU,
    NU,
    RATIO,
    SCHEMES,
    SIN_PI_K,
    U34,
    HelixAngleSolution,
    K,
    P,
    Q,
    ToothEquations,
    X,
    Z,
    assembly_condition,
    assembly_integers,
    balance_condition,
    coaxial_cosine_ratio,
    helical_coaxiality,
    helix_angle_solution,
    ratio_function,
    ratio_law,
    tooth_equations,
    working_coaxiality,
    working_diameter_ratio,
)
from symkin.mechanisms.helical.balanced.regions import (
    ExistenceBounds,
    existence_bounds,
    existence_interval,
    existence_range,
)
from symkin.mechanisms.helical.balanced.request import (
    HelicalDesign,
    HelicalRequest,
    HelicalResult,
)
from symkin.mechanisms.helical.balanced.search import synthesize_helical

__all__ = [
    "ALPHA_T12",
    "ALPHA_T34",
    "ALPHA_TW12",
    "ALPHA_TW34",
    "BETA12",
    "BETA34",
    "DELTA",
    "LAMBDA",
    "M12",
    "M34",
    "MU",
    "NU",
    "RATIO",
    "SCHEMES",
    "SIN_PI_K",
    "U34",
    "HelixAngleSolution",
    "K",
    "P",
    "Q",
    "ToothEquations",
    "X",
    "Z",
    "assembly_condition",
    "assembly_integers",
    "balance_condition",
    "coaxial_cosine_ratio",
    "helical_coaxiality",
    "helix_angle_solution",
    "ratio_function",
    "ratio_law",
    "tooth_equations",
    "working_coaxiality",
    "working_diameter_ratio",
    "ExistenceBounds",
    "existence_bounds",
    "existence_interval",
    "existence_range",
    "HelicalRequest",
    "HelicalDesign",
    "HelicalResult",
    "synthesize_helical",
]
