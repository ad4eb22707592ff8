"""``symkin cardan``: the Cardan-circle slider on a time grid (constant, elliptical or any carrier law)."""

from __future__ import annotations

import argparse
import warnings
from typing import TYPE_CHECKING, Any

from symkin.cli.common import (
    add_command,
    add_teeth_argument,
    emit,
    parse_expression,
    parse_integer,
    parse_real,
    sign_of,
    teeth_list,
)
from symkin.errors import InputError, SymkinWarning

if TYPE_CHECKING:
    from symkin.drives import Drive
    from symkin.mechanisms.cardan import CardanSlider

#: The most times ``--samples`` takes.
MAX_SAMPLES = 100_000

DESCRIPTION = (
    "Evaluate the Cardan-circle mechanism (carrier H, planet 1 rolling in the fixed ring 3, slider 2 pinned on the "
    "planet, guide through the centre at angle theta_2) on a time grid and print the slider's s, v, a. The carrier "
    "turns at a constant speed, through a pair of identical elliptical gears (eccentricity e, order m, input speed "
    "--speed), or by a law theta_H(t) you give. Values are exact where possible (0.02, 0.8*pi, pi/6); angles in "
    "radians, lengths in any unit (speeds come out in that unit per second). A pin off the pitch circle or a ratio "
    "other than 1:2 is not an error: the output says which path the pin traces."
)


def register(sub: Any) -> None:
    """Add the ``cardan`` command to the ``symkin`` subparsers ``sub`` (called by :func:`symkin.cli.build_parser`)."""
    p = add_command(sub, "cardan", help="slider displacement, velocity, acceleration of the Cardan-circle mechanism",
                    description=DESCRIPTION, run=run_cardan)
    p.add_argument("--length", required=True, metavar="L", help="carrier length l_H (= planet pitch radius for 1:2), in m or with a unit (20mm)")
    p.add_argument("--speed", metavar="W",
                   help="carrier speed (constant drive) or input gear speed (elliptical), in rad/s or with a unit (24rpm)")
    p.add_argument("--omega", dest="omega_deprecated", metavar="W", help=argparse.SUPPRESS)  # the former name of --speed
    p.add_argument("--guide-angle", default="0", metavar="RAD", help="guide angle theta_2, in radians or with a unit (30deg) (default 0)")
    p.add_argument("--carrier-angle", default="0", metavar="RAD", help="carrier angle at t = 0, in radians or with a unit (default 0)")
    add_teeth_argument(p, "20,40", required=False, default="20,40", metavar="Z1,Z3",
                       help="planet and ring tooth numbers (default 20,40)")
    p.add_argument("--pin-radius", metavar="L1", help="pin distance from the planet axis, in m or with a unit (default: on the pitch circle)")
    p.add_argument("--pin-angle", metavar="RAD",
                   help="pin angle on the planet from the carrier at t = 0, in radians or with a unit (default: the installation "
                   "angle the guide needs)")
    p.add_argument("--drive", choices=("constant", "elliptical", "law"),
                   help="carrier drive (default: elliptical if -e is given, law if --angle-law is given, else constant)")
    p.add_argument("-e", "--eccentricity", metavar="E", help="eccentricity of the elliptical gears, 0 <= e < 1")
    p.add_argument("--order", metavar="M", help="order of the elliptical gears (default 1)")
    p.add_argument("--angle-law", metavar="EXPR",
                   help="carrier angle law theta_H(t) in radians, in t (seconds), e.g. '0.8*pi*t + 0.2*sin(t)'")
    p.add_argument("--t-start", default="0", metavar="T0", help="first time, in seconds or with a unit (default 0)")
    p.add_argument("--t-end", metavar="T1", help="last time, in seconds or with a unit (500ms) (default: one period of the motion)")
    p.add_argument("--samples", default="9", metavar="N", help="number of equally spaced times (default 9)")
    p.add_argument("--times", metavar="T,T,...", help="explicit increasing times instead of --t-start/--t-end/--samples")


# ---- values
def _drive(args: Any) -> Drive:
    from symkin.drives import AngleLaw, ConstantSpeed, EllipticalGears

    kind = args.drive or ("elliptical" if args.eccentricity is not None else "law" if args.angle_law is not None else "constant")
    if kind != "elliptical" and (args.eccentricity is not None or args.order is not None):
        raise InputError(f"-e/--eccentricity and --order belong to the elliptical drive, not the {kind} drive")
    if kind != "law" and args.angle_law is not None:
        raise InputError(f"--angle-law belongs to the law drive, not the {kind} drive")
    if kind == "law":
        if args.angle_law is None:
            raise InputError("the law drive needs --angle-law EXPR, the carrier angle theta_H(t)")
        if args.speed is not None:
            raise InputError("--speed does not apply to the law drive: the law gives the carrier's speed")
        return AngleLaw(parse_expression(args.angle_law, names=("t",), what="--angle-law"))
    if args.speed is None:
        raise InputError(f"the {kind} drive needs --speed W, the {'carrier' if kind == 'constant' else 'input gear'} "
                         "speed in rad/s")
    omega = parse_real(args.speed, what="--speed", positive=True, unit="rad/s")
    if kind == "constant":
        return ConstantSpeed(omega)
    if args.eccentricity is None:
        raise InputError("the elliptical drive needs -e/--eccentricity E with 0 <= E < 1")
    e = parse_real(args.eccentricity, what="--eccentricity")
    if sign_of(e, what="--eccentricity") is None:
        raise InputError(f"--eccentricity {args.eccentricity!r} is 0 to 1233 digits without being 0; write 0 for "
                         "circular gears")
    if sign_of(e, what="--eccentricity") == -1 or sign_of(1 - e, what="--eccentricity") != 1:
        raise InputError(f"--eccentricity must lie in [0, 1), got {args.eccentricity!r}; 0 gives circular gears")
    m = parse_real(args.order, what="--order", positive=True) if args.order is not None else 1
    return EllipticalGears(omega, e, m)


def _times(args: Any, slider: CardanSlider) -> Any:
    from symkin.numeric.sampling import as_times

    if args.times is not None:
        if args.t_end is not None:
            raise InputError("give either --times or --t-end/--samples, not both")
        parts = [p for p in args.times.split(",") if p.strip()]
        if not parts:
            raise InputError("--times is empty; give at least one time, e.g. --times 0,0.5,1")
        return as_times([float(parse_real(p, what=f"time {i} in --times", unit="s")) for i, p in enumerate(parts, 1)])
    n = parse_integer(args.samples, what="--samples")
    if n < 1:
        raise InputError(f"--samples must be at least 1, got {n}")
    if n > MAX_SAMPLES:
        raise InputError(f"--samples is at most {MAX_SAMPLES}, got {n}")
    end = parse_real(args.t_end, what="--t-end", unit="s") if args.t_end is not None else None
    return slider.times(t_start=parse_real(args.t_start, what="--t-start", unit="s"), t_end=end, samples=int(n))


def run_cardan(args: Any) -> Any:
    """Run ``symkin cardan`` with the parsed ``args``: the Cardan slider's table s, v, a on a time grid; returns its output, :func:`symkin.cli.common.emit` (bad input raises a :class:`~symkin.errors.SymkinError`, exit 2)."""
    from symkin.mechanisms.cardan import CardanSlider

    if args.omega_deprecated is not None:
        if args.speed is not None:
            raise InputError("give --speed only (--omega is its former name)")
        warnings.warn("symkin cardan --omega W is deprecated: it is now --speed W (--omega LINK=VALUE names a link's "
                      "speed in the other commands)", SymkinWarning, stacklevel=1)
        args.speed = args.omega_deprecated
    length = parse_real(args.length, what="--length", positive=True, unit="m")
    z1, z3 = teeth_list(args.teeth, (2,))
    if z3 <= z1:
        raise InputError(f"the ring needs more teeth than the planet: got z1 = {z1}, z3 = {z3}")
    drive = _drive(args)
    pin_radius = parse_real(args.pin_radius, what="--pin-radius", positive=True, unit="m") if args.pin_radius is not None else None
    pin_angle = parse_real(args.pin_angle, what="--pin-angle", unit="rad") if args.pin_angle is not None else None
    slider = CardanSlider.build(length, drive=drive, teeth=(z1, z3), pin_radius=pin_radius, pin_angle=pin_angle,
                                guide_angle=parse_real(args.guide_angle, what="--guide-angle", unit="rad"),
                                carrier_angle=parse_real(args.carrier_angle, what="--carrier-angle", unit="rad"))
    table = slider.table(_times(args, slider))
    data = table.to_json()
    data["units"] = {"length": "m", "pin_radius": "m", "period_s": "s", "pin_angle_rad": "rad", "guide_angle_rad": "rad",
                     "carrier_angle_rad": "rad", "columns": {"t": "s", "s": "m", "v": "m/s", "a": "m/s^2", "x": "m", "y": "m",
                                                             "deviation": "m"}}
    return emit(table.text(), data)
