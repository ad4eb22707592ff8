"""Mutations of the engine for tests/derivations/test_mutations.py: patch one engine result, run papers' checks.

Run as ``python tests/support/mutations.py MUTATION PAPER[:PART] ...``: applies the named patch
in this fresh process (so no cache of an earlier run hides it), runs each paper's
``checks()`` (or only the function ``PART`` of its module, for a patch that makes another
part unable to build its mechanism) and prints one JSON object per check (paper, label,
kind, verdict, derived).  ``none`` runs the papers unpatched.  Each patch perturbs a result
the derivations take from the engine, by more than the printed digits of a number can absorb.

``python tests/support/mutations.py --report OUT MUTATION PAPER ...`` applies the patch and
runs ``symkin reproduce``'s :func:`~symkin.papers.reproduce.run` on the papers (one process,
no PDF), writing the report folder OUT; it prints nothing and exits 0 when ``run`` returns.
"""

from __future__ import annotations

import dataclasses
import json
import sys
from collections.abc import Callable

import sympy as sp

PERTURB = sp.Rational(11, 10)


def _wrap(owner: object, name: str, change: Callable) -> None:
    original = getattr(owner, name)

    def patched(*args, **kwargs):
        return change(original(*args, **kwargs), *args, **kwargs)

    setattr(owner, name, patched)


def pitch_point() -> None:
    """Every mesh's pitch point moved off the line of centres' true contact (speeds, ratios)."""
    from symkin.model import Mechanism

    _wrap(Mechanism, "mesh_geometry", lambda geo, *a, **k: dataclasses.replace(geo, pitch_y=geo.pitch_y * PERTURB))


def particle_laws() -> None:
    """Eq. (4) turns a particle by 11/10 of its link's rotation; eq. (6) gains a stray term
    omega^2/10 along the radius turned a quarter (as if Coriolis were added to a rigid link)."""
    import symkin.particles
    from symkin.superposition import vec

    position, acceleration = symkin.particles.position, symkin.particles.acceleration
    symkin.particles.position = lambda now, pole0, point0, dphi: position(now, pole0, point0, dphi * PERTURB)

    def wrong_acceleration(pole_acc, w, eps, point, pole):
        rel = point - pole
        return acceleration(pole_acc, w, eps, point, pole) + w**2 / 10 * vec(-rel[1], rel[0])

    symkin.particles.acceleration = wrong_acceleration


def coaxiality_defects() -> None:
    """The centre distance a planet's second mesh implies, off by 10 %."""
    from symkin.model import Mechanism

    original = Mechanism._centre_distance_pairs
    Mechanism._centre_distance_pairs = lambda self: [(p, ref, d * PERTURB) for p, ref, d in original(self)]


def slider_displacement() -> None:
    """The Cardan slider's displacement along the guide (vector loop), 13/10 of the loop's
    (more than the two printed digits of Table 1's 0.04 m can absorb)."""
    from symkin.mechanisms.cardan import CardanSlider

    original = CardanSlider.displacement
    CardanSlider.displacement = property(lambda self: original.fget(self) * sp.Rational(13, 10))


def line_conditions() -> None:
    """The Cardan installation rule for motion along the guide, off by pi/7."""
    import symkin.mechanisms.cardan as cardan

    def change(c):
        return dataclasses.replace(c, installation=sp.Eq(c.installation.lhs, c.installation.rhs + sp.pi / 7))

    _wrap(cardan, "line_conditions", lambda c: change(c))


def slider_period() -> None:
    """The period of the Cardan slider's motion, 11/10 of one carrier turn."""
    from symkin.mechanisms.cardan import CardanSlider

    _wrap(CardanSlider, "period", lambda period, *a, **k: None if period is None else period * PERTURB)


def elliptical_drive() -> None:
    """Elliptical gears: the driven radius at the pitch point and the carrier angle, perturbed."""
    from symkin.drives import EllipticalGears

    _wrap(EllipticalGears, "_radii", lambda radii, self, alpha: (radii[0], radii[1] * (1 + self.eccentricity / 10)))
    _wrap(EllipticalGears, "angle", lambda angle, self, t: angle + self.eccentricity * sp.sin(self.order * self.omega * t) / 10)


def stage_ratio() -> None:
    """A single-row AI stage's ratio law (sun to carrier, ring fixed), 11/10 of the engine's."""
    import symkin.mechanisms.multistage.stages as stages

    def change(laws):
        return dataclasses.replace(laws, ratio=type(laws.ratio)(laws.ratio.lhs, laws.ratio.rhs * PERTURB, laws.ratio.description))

    _wrap(stages, "stage_laws", lambda laws, *a, **k: change(laws))


def lost_motion() -> None:
    """Lost motion of a common-ring train: the last stage's error reaches the output 11/10 as strongly."""
    import symkin.mechanisms.multistage.lostmotion as lm

    def change(result, stages):
        return dataclasses.replace(
            result,
            carrier_errors=(*result.carrier_errors[:-1], result.carrier_errors[-1] * PERTURB),
            sun_transfers=(*result.sun_transfers[:-1], result.sun_transfers[-1] * PERTURB),
        )

    _wrap(lm, "lost_motion", change)


def tooth_equations() -> None:
    """Helical trains: the coaxiality in working radii with d_w2/d_w3 off by 10 %."""
    import symkin.mechanisms.helical.balanced.conditions as conditions

    _wrap(conditions, "working_coaxiality", lambda expr, *a, **k: expr.subs(conditions.DELTA, conditions.DELTA * PERTURB))


def diameter_ratio() -> None:
    """Helical rims: the working diameter ratio d_w2/d_w3, 11/10 of the engine's."""
    import symkin.mechanisms.helical.balanced as HS

    _wrap(HS, "working_diameter_ratio", lambda ratio, *a, **k: ratio * PERTURB)


def helical_ratio() -> None:
    """Two-row trains: the ratio law i_1H^(4) in tooth numbers, 11/10 of the engine's."""
    import symkin.mechanisms.helical.balanced as HS

    _wrap(HS, "ratio_law", lambda law, *a, **k: type(law)(law.lhs, law.rhs * PERTURB, law.description))


def existence_bounds() -> None:
    """Table 1 of the 2010 paper: every derived lower bound raised by 1/10."""
    import symkin.mechanisms.helical.balanced as HS

    _wrap(HS, "existence_bounds", lambda bounds, *a, **k: tuple(
        dataclasses.replace(b, lower=b.lower + sp.Rational(1, 10)) for b in bounds))


def helical_coaxiality() -> None:
    """Helical coaxiality with the mesh 3-4 distance off by a tooth-dependent amount."""
    import symkin.mechanisms.helical.balanced as HS
    from symkin.mechanisms.helical.balanced import Z

    _wrap(HS, "helical_coaxiality", lambda eq, *a, **k: sp.Eq(eq.lhs, eq.rhs * (1 + Z[3] / (10 * Z[4])), evaluate=False))


def mesh_sign() -> None:
    """The mesh condition (equal velocities at the pitch point) with the first gear's velocity negated."""
    import symkin.kinematics as kinematics
    import symkin.synthesis.assembly as assembly

    original = kinematics.contact_condition

    def flipped(mech, mesh):
        cond = original(mech, mesh)
        return sp.Eq(-cond.lhs, cond.rhs, evaluate=False)

    kinematics.contact_condition = assembly.contact_condition = flipped


def stage_limits() -> None:
    """The 2014 stage enumeration: the lower tooth limit off by one (zmin + 1)."""
    import symkin.mechanisms.multistage.stages as stages

    original = stages._limits
    stages._limits = lambda ring, satellites, zmin, zmax, ha: original(ring, satellites, zmin + 1, zmax, ha)


def centripetal() -> None:
    """Eq. (6) with the centripetal term's sign flipped: w = w_P + eps k x r + omega^2 r."""
    import symkin.particles
    from symkin.superposition import vec

    def wrong_acceleration(pole_acc, w, eps, point, pole):
        rel = point - pole
        return sp.ImmutableMatrix(pole_acc + eps * vec(-rel[1], rel[0]) + w**2 * rel)

    symkin.particles.acceleration = wrong_acceleration


def pitch_radius() -> None:
    """A gear of z teeth gets the pitch radius m (z + 1)/2 instead of m z/2."""
    from symkin.model.parts import Gear

    original = Gear.from_teeth.__func__

    def from_teeth(cls, name, teeth, **kw):
        gear = original(cls, name, teeth, **kw)
        return dataclasses.replace(gear, radius=gear.radius * (gear.teeth + 1) / gear.teeth)

    Gear.from_teeth = classmethod(from_teeth)


MUTATIONS: dict[str, Callable[[], None]] = {
    "none": lambda: None,
    "pitch point": pitch_point,
    "particle laws": particle_laws,
    "coaxiality defects": coaxiality_defects,
    "slider displacement": slider_displacement,
    "line conditions": line_conditions,
    "slider period": slider_period,
    "elliptical drive": elliptical_drive,
    "stage ratio": stage_ratio,
    "lost motion": lost_motion,
    "tooth equations": tooth_equations,
    "diameter ratio": diameter_ratio,
    "helical ratio": helical_ratio,
    "existence bounds": existence_bounds,
    "helical coaxiality": helical_coaxiality,
    "mesh sign": mesh_sign,
    "stage limits": stage_limits,
    "centripetal": centripetal,
    "pitch radius": pitch_radius,
}


def report(out: str, name: str, papers: list[str]) -> int:
    """Apply mutation ``name`` and write the report of ``papers`` to ``out``."""
    from pathlib import Path

    from symkin.papers.reproduce import run

    MUTATIONS[name]()
    run(papers, Path(out), quiet=True, pdf=False, jobs=1)
    return 0


def main(argv: list[str]) -> int:
    if argv[0] == "--report":
        return report(argv[1], argv[2], argv[3:])
    name, *papers = argv
    MUTATIONS[name]()
    from symkin.papers.registry import load

    for spec in papers:
        paper, _, part = spec.partition(":")
        module = load(paper)
        found = getattr(module, part)() if part else module.checks()
        for c in found if isinstance(found, list) else [found]:
            print(json.dumps({"paper": paper, "label": c.label, "kind": c.kind.value, "verdict": c.verdict.value,
                              "derived": str(c.derived)}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
