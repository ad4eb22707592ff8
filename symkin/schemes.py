"""Ready-made schemes of the 2009 paper, each a few lines on top of the model.

Names (paper's fig. 1): ``"AI1"`` single-row AI (fig. 1a); ``"AI"``, ``"AA"``, ``"II"``
two-row (figs. 1b-1d): A = external, I = internal, first letter for mesh 1-2, second
for mesh 3-4.  Links: central gears ``"1"`` and ``"4"``, carrier ``"H"``, planet
``"23"`` carrying rims 2 and 3 (``"2"`` for the single-row planet).

Dimensions: by default symbolic pitch radii r_1 ... r_4; ``teeth=True`` symbolic tooth
numbers z_1 ... z_4 with a common module m; ``teeth=(z1, z2, z3, z4)`` numbers; or
``radii=(...)`` explicit radii.

    >>> from symkin import schemes
    >>> print(schemes.two_row("AA", teeth=True).ratio("1", "H", fixed="4"))
    i_{1H}^{(4)} = 1 - z_2*z_4/(z_1*z_3)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from symkin import symbols as S
from symkin.errors import ModelError
from symkin.model import Gear, Link, Mechanism, Mesh

__all__ = ["single_row_AI", "two_row", "common_ring_train", "cardan", "scheme", "SCHEMES", "TWO_ROW"]

#: For each two-row scheme: is the central gear of mesh 1-2 (gear 1), and of mesh 3-4 (gear 4), internal?
TWO_ROW: dict[str, tuple[bool, bool]] = {"AI": (False, True), "AA": (False, False), "II": (True, True)}


def _gears(names: Sequence[str], internal: Sequence[bool], radii: Any, teeth: Any, module: Any) -> list[Gear]:
    n = len(names)
    if radii is not None and teeth not in (None, False):
        raise ModelError("give either radii or teeth, not both")
    if radii is not None:
        values = _sequence(radii, n, "radii", names)
        return [Gear(g, r, internal=i) for g, r, i in zip(names, values, internal)]
    if teeth is None or teeth is False:
        return [Gear.symbolic(g, internal=i) for g, i in zip(names, internal)]
    values = [S.teeth(g) for g in names] if teeth is True else _sequence(teeth, n, "teeth", names)
    return [Gear.from_teeth(g, z, internal=i, module=module) for g, z, i in zip(names, values, internal)]


def _sequence(values: Any, n: int, what: str, names: Sequence[str]) -> list[Any]:
    if isinstance(values, (str, bytes)) or not hasattr(values, "__len__"):
        raise ModelError(f"{what} must be a sequence of {n} values (gears {', '.join(names)}), got {values!r}")
    if len(values) != n:
        raise ModelError(f"{what} must give {n} values (gears {', '.join(names)}), got {len(values)}")
    return list(values)


def single_row_AI(*, radii: Any = None, teeth: Any = None, module: Any = None) -> Mechanism:
    """Single-row AI (fig. 1a): sun 1, planet 2 meshing sun and ring, ring 4, carrier H.

    ``teeth``/``radii`` give three values: gears 1, 2, 4.

    >>> print(single_row_AI(teeth=True).ratio("1", "H", fixed="4"))
    i_{1H}^{(4)} = 1 + z_4/z_1
    """
    g1, g2, g4 = _gears(("1", "2", "4"), (False, False, True), radii, teeth, module)
    return Mechanism(
        links=(Link.central("1", g1), Link.planet("2", g2, carrier="H"), Link.central("H"), Link.central("4", g4)),
        meshes=(Mesh("1", "2"), Mesh("2", "4")),
        name="AI1",
    )


def two_row(kind: str, *, radii: Any = None, teeth: Any = None, module: Any = None) -> Mechanism:
    """Two-row scheme ``kind`` in {"AI", "AA", "II"} (figs. 1b-1d) with a stepped planet 23.

    >>> two_row("II").coaxiality
    (Eq(r_1 - r_2, -r_3 + r_4),)
    """
    if kind not in TWO_ROW:
        raise ModelError(f"unknown two-row scheme {kind!r}; choose one of {', '.join(TWO_ROW)}")
    in1, in4 = TWO_ROW[kind]
    g1, g2, g3, g4 = _gears(("1", "2", "3", "4"), (in1, False, False, in4), radii, teeth, module)
    return Mechanism(
        links=(Link.central("1", g1), Link.planet("23", g2, g3, carrier="H"), Link.central("H"), Link.central("4", g4)),
        meshes=(Mesh("1", "2"), Mesh("3", "4")),
        name=kind,
    )


def common_ring_train(
    stages: int | None = None, *, teeth: Sequence[tuple[Any, Any]] | None = None, ring: Any = None, module: Any = None
) -> Mechanism:
    """Single-row AI stages in series sharing one ring gear ``"4"``.

    Stage i has sun ``s<i>``, planet ``p<i>`` and carrier ``H<i>``; carrier ``H<i>`` holds
    the sun of stage i + 1.  The input is ``s1``, the output ``H<n>``; fix the ring with
    ``ratio("s1", "H<n>", fixed="4")``.

    Parameters
    ----------
    stages : int, optional
        Number of stages, with symbolic radii (r_s1, r_p1, ..., r_4).
    teeth : sequence of (sun, planet) tooth numbers, optional
        One pair per stage; ``ring`` is then the ring's tooth number.

    >>> train = common_ring_train(teeth=[(20, 30), (40, 20)], ring=80)
    >>> train.ratio("s1", "H2", fixed="4").rhs
    15
    """
    if (stages is None) == (teeth is None):
        raise ModelError("give either the number of stages or the teeth of every stage")
    if teeth is not None:
        if ring is None:
            raise ModelError("give the ring's tooth number with ring=...")
        if isinstance(teeth, (str, bytes)) or not hasattr(teeth, "__iter__"):
            raise ModelError(f"teeth must be a sequence of (sun, planet) pairs, one per stage, got {teeth!r}")
        pairs = list(teeth)
        n = len(pairs)
    else:
        if not isinstance(stages, int) or isinstance(stages, bool) or stages < 1:
            raise ModelError(f"the number of stages must be a positive integer, got {stages!r}")
        n = stages
    if n < 1:
        raise ModelError("a train needs at least one stage")
    names = [(f"s{i}", f"p{i}") for i in range(1, n + 1)]
    if teeth is not None:
        for i, pair in enumerate(pairs, 1):
            if not hasattr(pair, "__len__") or len(pair) != 2:
                raise ModelError(f"stage {i} needs a (sun, planet) pair of tooth numbers, got {pair!r}")
        gears = [Gear.from_teeth(nm, z, module=module) for (s, p), pair in zip(names, pairs) for nm, z in zip((s, p), pair)]
        ring_gear = Gear.from_teeth("4", ring, internal=True, module=module)
    else:
        gears = [Gear.symbolic(nm) for s, p in names for nm in (s, p)]
        ring_gear = Gear.symbolic("4", internal=True)
    links: list[Link] = [Link.central("s1", gears[0])]
    meshes: list[Mesh] = []
    for i in range(1, n + 1):
        sun, planet = gears[2 * (i - 1)], gears[2 * (i - 1) + 1]
        links.append(Link.planet(f"p{i}", planet, carrier=f"H{i}"))
        next_sun = (gears[2 * i],) if i < n else ()
        links.append(Link.central(f"H{i}", *next_sun))
        meshes += [Mesh(sun.name, planet.name), Mesh(planet.name, "4")]
    links.append(Link.central("4", ring_gear))
    return Mechanism(links=tuple(links), meshes=tuple(meshes), name=f"{n} x AI1")


def cardan(*, radii: Any = None, teeth: Any = None, module: Any = None, carrier_angle: Any = 0) -> Mechanism:
    """Planet ``"1"`` rolling inside the fixed internal gear ``"3"``, carried by ``"H"``.

    The Cardan-circle mechanism of the 2018 paper when gear 3 is twice gear 1 (then every
    point of the planet's pitch circle moves on a straight line).  ``teeth``/``radii``
    give two values: gears 1 and 3; ``carrier_angle`` is the carrier's angle at t = 0.
    The slider and its vector loop are in :mod:`symkin.mechanisms.cardan`.

    >>> m = cardan(teeth=(20, 40), module=2)
    >>> m.arm("1"), m.ratio("1", "H", fixed="0").rhs
    (20, -1)
    """
    g1, g3 = _gears(("1", "3"), (False, True), radii, teeth, module)
    return Mechanism(
        links=(Link.frame(g3), Link.central("H"), Link.planet("1", g1, carrier="H", position_angle=carrier_angle)),
        meshes=(Mesh("1", "3"),),
        name="Cardan",
    )


SCHEMES: dict[str, Callable[..., Mechanism]] = {
    "AI1": single_row_AI,
    "AI": lambda **kw: two_row("AI", **kw),
    "AA": lambda **kw: two_row("AA", **kw),
    "II": lambda **kw: two_row("II", **kw),
}


def scheme(name: str, **kwargs: Any) -> Mechanism:
    """A ready-made scheme by name: ``"AI1"`` (single-row), ``"AI"``, ``"AA"`` or ``"II"``.

    >>> scheme("AI1", teeth=(20, 30, 80)).ratio("1", "H", fixed="4").rhs
    5
    """
    try:
        build = SCHEMES[name]
    except (KeyError, TypeError):
        raise ModelError(f"unknown scheme {name!r}; choose one of {', '.join(SCHEMES)}") from None
    return build(**kwargs)
