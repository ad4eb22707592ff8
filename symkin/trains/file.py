"""Train files: any train symkin can model, written as TOML and read into a :class:`Train`.

The file reads like a stick diagram: the links, the gears each holds, which link carries
each planet, which gears mesh, and the gear states.  The minimal form::

    name = "Ravigneaux"
    module = 1                        # in mm ("1.5 mm", "0.06 in" with a unit); pitch radius = module * teeth / 2
    meshes = [["s1", "p1"], ["p1", "p2"], ["p2", "s2"], ["p2", "r"]]
    [links.S1]                        # a link turning about the main axis
    gears = { s1 = 30 }               # gear name = teeth (an integer, or a string naming a symbol)
    [links.C]                         # a carrier needs no gears
    [links.P1]
    carrier = "C"                     # a planet, carried by C; its position is solved from its meshes
    gears = { p1 = 18 }
    [links.R]
    gears = { r = { teeth = 72, internal = true } }
    [links.frame]                     # gears fixed to the frame, if any
    [states.first]                    # a gear state: brakes hold links, clutches join links
    input = "S1"
    output = "R"
    brakes = ["S2"]
    clutches = []                     # e.g. [["S1", "S2"]]

Beyond it (all optional):

- top level: ``description``;
- a gear as a table: ``teeth``, ``internal``, ``module`` (its own), ``radius`` (a pitch
  radius given directly, e.g. a working one), ``bevel = true`` (a bevel gear) and, for a
  bevel side gear, ``side = 1`` or ``-1`` (it meets the pinions above or below their axes);
  its tooth form for ``symkin geometry``: ``shift`` (the profile shift coefficient x, 0),
  ``addendum`` (h_a*, 1), ``dedendum`` (h_f*, 1.25), ``pressure_angle`` (degrees, 20),
  ``fillet`` (the rack's tip radius rho_f*, 0.38) and ``tip_diameter`` (mm, a tip turned down);
- a planet: ``angle`` (its position on the carrier at t = 0, radians; text such as
  ``"pi/3"`` is exact), ``arm`` (its distance from its carrier's axis; ``0``: it turns
  about its carrier's own axis), ``count`` (equal planets of this kind, equally spaced);
  its ``carrier`` may be a planet (nested carriers, a planet of a planet); ``axis =
  "radial"`` makes it a bevel pinion (its axis perpendicular to its carrier's);
- a mesh as a table: ``{ gears = ["p", "s2"], centre_distance = 60 }``: a working centre
  distance other than the pitch circles give, i.e. a profile-shifted mesh (the working
  circles keep the tooth ratio, so the ratio is exact and the planet axis coaxial);
  ``efficiency = 0.985``: the mesh's efficiency for the statics (symkin efficiency);
  ``stiffness = 3e8``: its stiffness along the line of action (N/m), for the torsional model;
- mass properties, for symkin dynamics and symkin modes (SI; a number, or a name such as
  ``"J_S"`` for a symbol): a link's ``inertia`` (kg m^2, about its own axis; of one planet),
  a planet's ``mass`` (kg, of one planet) and a main-axis link's ``stiffness`` (N m/rad, a
  shaft to the frame);
- a state: ``description``, ``released`` (one-way clutches held out of engagement in it);
- ``[one_way.NAME]``: a one-way clutch (freewheel, sprag, pawls), ``links = ["C2", "frame"]``
  and ``blocks = "negative"`` (the first link may not turn backwards relative to the second;
  the default) or ``"positive"``: each state engages it when it can carry the torque;
- ``[base]``: the base (the frame) moving in space, expressions in t: ``x``, ``y``, ``z``
  of the main axis point O and ``yaw``, ``pitch``, ``roll`` of the frame (the motion the
  drawing commands use; a drill head on a manipulator).

Numbers are exact as written (``0.8`` is 4/5); text values are parsed from symkin's
allow-list (never evaluated).  A bad file is a :class:`~symkin.errors.TrainFileError`
naming the file, the table and the key.

    >>> train = load_train("double-pinion")
    >>> train.ratio("S", "R", fixed="C").rhs     # two external meshes and an internal one: positive
    3
"""

from __future__ import annotations

import importlib.resources
import os
import re
import stat
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import sympy as sp

from symkin.errors import ModelError, SymkinError, TrainFileError
from symkin.model import FRAME, Gear, Link, Mesh
from symkin.parsing import CONSTANTS, FUNCTIONS, parse_expression, parse_real
from symkin.trains.one_way import OneWay
from symkin.trains.train import State, Train
from symkin.values import as_rational

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib  # type: ignore[import-not-found]  # (Python 3.10 only)

__all__ = ["load_train", "read_train", "ready_made", "READY_MADE", "MAX_FILE_BYTES"]

#: The largest train file read (a train of hundreds of links is a few kB).
MAX_FILE_BYTES = 1_000_000
#: Tables and lists inside each other (a train file needs 5: links, a link, its gears, a gear, ...).
MAX_NESTING = 16
#: Parts of one dotted key (``a.b.c``): TOML makes a table of each, and a key of 50,000 parts took 2 GB.
MAX_KEY_PARTS = MAX_NESTING
#: Keys and values in a file, all tables together (a train of 100 links has about 1,000).
MAX_ENTRIES = 20_000
#: Links in a train (the largest ready-made one has 8; each link is a column of the equations).
MAX_LINKS = 200
#: Keys each table may hold.
_TOP = {"name", "description", "module", "meshes", "links", "states", "base", "one_way"}
_ONE_WAY = {"links", "blocks"}
_BASE = {"x", "y", "z", "yaw", "pitch", "roll"}
_LINK = {"gears", "carrier", "angle", "arm", "count", "axis", "inertia", "mass", "stiffness"}
_GEAR = {"teeth", "internal", "module", "radius", "bevel", "side"}
#: The tooth form keys of a gear table (symkin.geometry): profile shift, h_a*, h_f*, degrees, rho_f*, mm.
_FORM = {"shift", "addendum", "dedendum", "pressure_angle", "fillet", "tip_diameter"}
_MESH = {"gears", "centre_distance", "efficiency", "stiffness"}
_STATE = {"input", "output", "brakes", "clutches", "description", "released"}
_SYMBOL = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
#: Names a symbolic tooth number may not take: they print as (or parse to) something else.
_RESERVED = frozenset({*CONSTANTS, *FUNCTIONS, "I", "oo", "zoo", "nan", "inf", "infinity", "t"})
#: The link name of the frame in a file.
FRAME_TABLE = "frame"


def _library() -> Any:
    return importlib.resources.files("symkin.trains") / "library"


def ready_made() -> dict[str, str]:
    """The ready-made train files shipped with symkin: name -> description.

    >>> sorted(ready_made())[:4]
    ['bevel-differential', 'bevel-epicyclic', 'double-pinion', 'eight-speed']
    """
    out = {}
    for entry in sorted(_library().iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            data = tomllib.loads(entry.read_text(encoding="utf-8"))
            out[entry.name[: -len(".toml")]] = str(data.get("description", "")).split("\n")[0]
    return out


#: Names of the ready-made trains (``--train NAME``).
READY_MADE = tuple(ready_made())


def load_train(source: str | Path) -> Train:
    """A train from a TOML file, or a ready-made one by name (:func:`ready_made`).

    A path to an existing file is read; a bare name such as ``"ravigneaux"`` is a
    ready-made train.  Raises :class:`~symkin.errors.TrainFileError` with the file, the
    table and the key when the file is not a train.

    >>> load_train("wolfrom").shift("drive").ratio.rhs
    76
    """
    if isinstance(source, Path) or (isinstance(source, str) and (source.endswith(".toml") or _exists(source))):
        path = Path(source)
        return read_train(_read_file(path), str(path))
    if not isinstance(source, str):
        raise TrainFileError(repr(source), "", "a train is a file path or a ready-made name")
    entry = _library() / f"{source}.toml"
    if len(source) > 100 or not _SYMBOL.match(source.replace("-", "_")) or not entry.is_file():
        raise TrainFileError(source, "", f"no such file, and no ready-made train of that name; the ready-made "
                             f"trains are {', '.join(READY_MADE)}")
    return read_train(entry.read_text(encoding="utf-8"), source)


def _read_file(path: Path) -> str:
    """The text of a train file: a regular file only (a device such as /dev/zero, a pipe that
    never ends, a folder refused, links followed), opened without waiting (a FIFO with no writer
    would block the open), and at most :data:`MAX_FILE_BYTES` read."""
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0))
    except (OSError, ValueError) as err:  # (ValueError: a NUL in the name)
        reason = getattr(err, "strerror", None) or err
        raise TrainFileError(repr(str(path))[1:-1], "", f"cannot be read ({reason}); give a readable UTF-8 TOML "
                             "file") from None
    mode = os.fstat(fd).st_mode
    if not stat.S_ISREG(mode):
        os.close(fd)
        if stat.S_ISDIR(mode):
            raise TrainFileError(str(path), "", "is a folder; give a train file (TOML)")
        raise TrainFileError(str(path), "", "is not a regular file (a device, a pipe or a socket); give a train "
                             "file (TOML)")
    with os.fdopen(fd, "rb") as f:
        try:
            data = f.read(MAX_FILE_BYTES + 1)
        except OSError as err:
            raise TrainFileError(str(path), "", f"cannot be read ({err.strerror or err}); give a readable UTF-8 TOML "
                                 "file") from None
    if len(data) > MAX_FILE_BYTES:
        raise TrainFileError(str(path), "", f"the file is larger than {MAX_FILE_BYTES} bytes; a train file is a few kB")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise TrainFileError(str(path), "", f"is not UTF-8 text ({err.reason} at byte {err.start}); give a UTF-8 "
                             "TOML file") from None


#: TOML strings and comments (where a dot is not a key's); outside them, the text between two of
#: = , [ ] { } or line ends holds at most one key (a number has one dot).
_STRINGS = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:\\.|[^"\\\n])*"|\'[^\'\n]*\'|#[^\n]*')
_KEY_ENDS = re.compile(r"[=,{}\[\]\n]")


def _check_keys(text: str, path: str) -> None:
    """Refuse a dotted key of more than :data:`MAX_KEY_PARTS` parts before TOML reads it
    (tomllib's time and memory grow with the square of the parts).

    >>> _check_keys("a.b.c = 1\\nx = { y.z = 0.5 }\\n", "f")
    >>> _check_keys("x = {" + "a." * 20 + "b = 1}", "f")
    Traceback (most recent call last):
    ...
    symkin.errors.TrainFileError: f: a key of more than 16 dotted parts; a train file nests at most 16 tables
    """
    if max((part.count(".") for part in _KEY_ENDS.split(_STRINGS.sub('""', text))), default=0) >= MAX_KEY_PARTS:
        raise TrainFileError(path, "", f"a key of more than {MAX_KEY_PARTS} dotted parts; a train file nests at "
                             f"most {MAX_NESTING} tables")


def _check_shape(data: Mapping[str, Any], path: str) -> None:
    """Refuse data nested more than :data:`MAX_NESTING` deep or of more than :data:`MAX_ENTRIES` entries."""
    entries = 0
    stack: list[tuple[Any, int]] = [(data, 1)]
    while stack:
        value, depth = stack.pop()
        if depth > MAX_NESTING:
            raise TrainFileError(path, "", f"tables or lists nested more than {MAX_NESTING} deep; a train file needs 5")
        children = value.values() if isinstance(value, Mapping) else value
        for child in children:
            entries += 1
            if isinstance(child, (Mapping, list)):
                stack.append((child, depth + 1))
        if entries > MAX_ENTRIES:
            raise TrainFileError(path, "", f"more than {MAX_ENTRIES} keys and values; a train of 100 links has about "
                                 "1,000")


def _exists(path: str) -> bool:
    try:
        return Path(path).exists()
    except (OSError, ValueError):  # a name too long for a path, or with a NUL: not a file
        return False


def read_train(text: str, path: str = "<train>") -> Train:
    """A train from the text of a train file (``path`` names it in errors)."""
    if len(text) > MAX_FILE_BYTES:
        raise TrainFileError(path, "", f"the text is longer than {MAX_FILE_BYTES} characters; a train file is a few kB")
    _check_keys(text, path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise TrainFileError(path, "", f"not valid TOML ({err})") from None
    except RecursionError:
        raise TrainFileError(path, "", f"tables or lists nested too deeply to read; a train file nests at most "
                             f"{MAX_NESTING} deep") from None
    _check_shape(data, path)
    return _Reader(path, data).train()


class _Reader:
    def __init__(self, path: str, data: Mapping[str, Any]):
        self.path, self.data = path, data
        self.forms: dict[str, tuple[tuple[str, Any], ...]] = {}

    def fail(self, where: str, problem: str) -> TrainFileError:
        return TrainFileError(self.path, where, problem)

    # ---- values
    def keys(self, table: Any, allowed: set[str], where: str) -> Mapping[str, Any]:
        if not isinstance(table, Mapping):
            raise self.fail(where, f"must be a table (key = value lines), got {_show(table)}")
        unknown = sorted(set(table) - allowed)
        if unknown:
            raise self.fail(where, f"unknown key {unknown[0]!r}; the keys here are {', '.join(sorted(allowed))}")
        return table

    def number(self, value: Any, where: str, *, positive: bool = True) -> sp.Expr:
        try:
            if isinstance(value, str):
                expr = parse_expression(value, what="the value")
                if not expr.is_number or expr.is_extended_real is False:
                    raise self.fail(where, f"must be a number, got {value!r}")
            elif isinstance(value, bool) or not isinstance(value, (int, float)):
                raise self.fail(where, f"must be a number, got {_show(value)}")
            else:
                expr = as_rational(value, what="the value")
        except TrainFileError:
            raise
        except SymkinError as err:
            raise self.fail(where, str(err)) from None
        if positive and not expr.is_positive:
            raise self.fail(where, f"must be positive, got {_show(value)}")
        return expr

    def mass_properties(self, table: Mapping[str, Any], where: str) -> dict[str, sp.Expr]:
        """``inertia``, ``mass``, ``stiffness`` of a link (or mesh): a number >= 0, or a name (a symbol)."""
        out = {}
        for key in ("inertia", "mass", "stiffness"):
            if key in table:
                value = table[key]
                if isinstance(value, str) and _SYMBOL.match(value) and value not in _RESERVED:
                    out[key] = sp.Symbol(value, positive=True)
                else:
                    out[key] = self.number(value, f"{where} {key}", positive=False)
                    if out[key].is_negative:
                        raise self.fail(f"{where} {key}", f"must be 0 or more, got {_show(value)}")
        return out

    def module(self, value: Any, where: str) -> sp.Expr:
        """A module in millimetres (ISO 54): a number, or text with a unit ("1.5 mm", "0.06 in")."""
        if not isinstance(value, str):
            return self.number(value, where)
        try:
            return parse_real(value, what="the module", unit="mm", positive=True)
        except SymkinError as err:
            raise self.fail(where, str(err)) from None

    def angle(self, value: Any, where: str) -> sp.Expr:
        return self.number(value, where, positive=False)

    def arm(self, value: Any, where: str) -> sp.Expr:
        """A planet's arm: a positive length, or 0 (it turns about its carrier's own axis)."""
        return sp.Integer(0) if value == 0 else self.number(value, where)

    def text(self, value: Any, where: str) -> str:
        if not isinstance(value, str):
            raise self.fail(where, f"must be a string, got {_show(value)}")
        return value

    def teeth(self, value: Any, where: str) -> sp.Expr:
        if isinstance(value, str):
            if not _SYMBOL.match(value):
                raise self.fail(where, f"a symbolic tooth number is a name such as \"z1\", got {value!r}")
            if value in _RESERVED:
                raise self.fail(where, f"{value!r} names a constant, a function or the time in symkin's laws, and would "
                                       "print as one; name the tooth number otherwise, such as \"z1\"")
            return sp.Symbol(value, positive=True, integer=True)
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(where, f"a tooth number is a whole number (or a name such as \"z1\"), got {_show(value)}")
        if value < 1 or value > 10**9:
            raise self.fail(where, f"a tooth number is from 1 to 10^9, got {value}")
        return sp.Integer(value)

    def name(self, value: Any, where: str) -> str:
        if not isinstance(value, str) or not value:
            raise self.fail(where, f"must be a name (a string), got {_show(value)}")
        return value

    def form(self, spec: Mapping[str, Any], where: str) -> tuple[tuple[str, Any], ...]:
        """A gear's tooth form keys, exact (their ranges are checked by symkin.geometry.ToothForm)."""
        out = []
        for key in sorted(_FORM & set(spec)):
            value = self.number(spec[key], f"{where} {key}", positive=key != "shift")
            if not value.is_Rational:
                raise self.fail(f"{where} {key}", f"must be a plain number such as 0.25, got {_show(spec[key])}")
            if key == "pressure_angle" and not 5 <= value <= 45:
                raise self.fail(f"{where} {key}", f"is in degrees, from 5 to 45 (usually 20), got {_show(spec[key])}")
            if key in ("shift", "fillet") and abs(value) > 5:  # (a positive fillet; 0 is refused: rho_f* > 0)
                raise self.fail(f"{where} {key}", f"is a coefficient times the module, within -5 and 5, got {_show(spec[key])}")
            out.append((key, value))
        return tuple(out)

    # ---- tables
    def gear(self, name: str, spec: Any, module: sp.Expr, where: str) -> Gear:
        try:
            if isinstance(spec, Mapping):
                spec = self.keys(spec, _GEAR | _FORM, where)
                self.forms[name] = self.form(spec, where)
                internal = spec.get("internal", False)
                bevel = spec.get("bevel", False)
                side = spec.get("side", 0)
                for key, value in (("internal", internal), ("bevel", bevel)):
                    if not isinstance(value, bool):
                        raise self.fail(f"{where} {key}", f"must be true or false, got {_show(value)}")
                if isinstance(side, bool) or side not in (-1, 0, 1):
                    raise self.fail(f"{where} side", f"is 1 (the side gear meets the bevel pinions above their axes) or "
                                    f"-1 (below), got {_show(side)}")
                m = self.module(spec["module"], f"{where} module") if "module" in spec else module
                z = self.teeth(spec["teeth"], f"{where} teeth") if "teeth" in spec else None
                if "radius" in spec:
                    return Gear(name, self.number(spec["radius"], f"{where} radius"), teeth=z, internal=internal, module=m,
                                bevel=bevel, side=side)
                if z is None:
                    raise self.fail(where, "give the gear's teeth (or its radius)")
                return Gear.from_teeth(name, z, internal=internal, module=m, bevel=bevel, side=side)
            return Gear.from_teeth(name, self.teeth(spec, where), module=module)
        except ModelError as err:
            if isinstance(err, TrainFileError):
                raise
            raise self.fail(where, str(err)) from None

    def train(self) -> Train:
        data = self.keys(self.data, _TOP, "top level")
        name = self.text(data.get("name", ""), "name")
        description = self.text(data.get("description", ""), "description")
        module = self.module(data["module"], "module") if "module" in data else sp.Integer(1)
        links_table = self.links_table(data.get("links"))
        specs, gear_owner = self.link_specs(links_table)
        self._check_carriers(specs)
        links = [self.link(link_name, table, module) for link_name, table in specs.items()]
        meshes = self.meshes(data.get("meshes"), gear_owner)
        states = self.states(data.get("states", {}), set(links_table) | set(gear_owner))
        base = self.base(data["base"]) if "base" in data else None
        one_ways = self.one_ways(data.get("one_way", {}), set(links_table) | set(gear_owner))
        try:
            train = Train(tuple(links), tuple(meshes), name=name, states=tuple(states), description=description,
                          source=self.path, base=base, tooth_forms=tuple((g, f) for g, f in self.forms.items() if f),
                          one_ways=one_ways)
        except TrainFileError:
            raise
        except ModelError as err:
            raise self.fail(self._where_of(str(err), specs), str(err)) from None
        self._check_joined(specs, meshes, [*states, *(State("", "", "", (), ((o.link, o.other),)) for o in one_ways)], gear_owner)
        return train

    def links_table(self, links_table: Any) -> Mapping[str, Any]:
        """The [links] table: at least one link, at most :data:`MAX_LINKS`."""
        if not isinstance(links_table, Mapping) or not links_table:
            raise self.fail("[links]", "the file names no links; add a [links.NAME] table for each link")
        if len(links_table) > MAX_LINKS:
            raise self.fail("[links]", f"{len(links_table)} links, more than the {MAX_LINKS} symkin models; equal planets "
                                       "are one link with count = N")
        return links_table

    def link_specs(self, links_table: Mapping[str, Any]) -> tuple[dict[str, Mapping[str, Any]], dict[str, str]]:
        """Each link's table (its keys checked) and the link that holds each gear (gear names unique, no link's)."""
        gear_owner: dict[str, str] = {}
        specs: dict[str, Mapping[str, Any]] = {}
        for link_name, table in links_table.items():
            where = f"[links.{link_name}]"
            specs[link_name] = self.keys(table, _LINK, where)
            gears = specs[link_name].get("gears", {})
            if not isinstance(gears, Mapping):
                raise self.fail(f"{where} gears", f"must be a table of gear = teeth, got {_show(gears)}")
            for g in gears:
                if g in gear_owner:
                    raise self.fail(f"{where} gears", f"gear {g!r} is also on link {gear_owner[g]!r}; give every gear its own name")
                if g in links_table:
                    raise self.fail(f"{where} gears", f"gear {g!r} has the name of a link; give gears and links different names")
                gear_owner[g] = link_name
        return specs, gear_owner

    def link(self, link_name: str, table: Mapping[str, Any], module: sp.Expr) -> Link:
        """One [links.NAME] table: the frame, a planet (it names a carrier) or a link about the main axis."""
        where = f"[links.{link_name}]"
        gears = [self.gear(g, spec, module, f"{where} gears.{g}") for g, spec in table.get("gears", {}).items()]
        try:
            props = self.mass_properties(table, where)
            if link_name == FRAME_TABLE:
                return self.frame_link(table, gears, where)
            if "carrier" in table:
                return self.planet(link_name, table, gears, props, where)
            return self.central(link_name, table, gears, props, where)
        except TrainFileError:
            raise
        except ModelError as err:
            raise self.fail(where, str(err)) from None

    def frame_link(self, table: Mapping[str, Any], gears: Sequence[Gear], where: str) -> Link:
        extra = sorted(set(table) - {"gears"})
        if extra:
            raise self.fail(f"{where} {extra[0]}", "the frame holds fixed gears only")
        return Link.frame(*gears)

    def planet(self, link_name: str, table: Mapping[str, Any], gears: Sequence[Gear], props: Mapping[str, sp.Expr],
               where: str) -> Link:
        carrier = _model_name(self.name(table["carrier"], f"{where} carrier"))
        count = table.get("count", 1)
        if isinstance(count, bool) or not isinstance(count, int):
            raise self.fail(f"{where} count", f"must be a whole number of planets, got {_show(count)}")
        if "stiffness" in props:
            raise self.fail(f"{where} stiffness", "a planet takes no shaft stiffness: a stiffness holds a "
                                                  "link about the main axis to the frame")
        axis = table.get("axis", "parallel")
        if axis not in ("parallel", "radial"):
            raise self.fail(f"{where} axis", f"is \"parallel\" (a planet) or \"radial\" (a bevel pinion), got {_show(axis)}")
        arm = self.arm(table["arm"], f"{where} arm") if "arm" in table else None
        angle = self.angle(table["angle"], f"{where} angle") if "angle" in table else None
        return Link.planet(link_name, *gears, carrier=carrier, axis=axis, arm=arm, position_angle=angle, count=count,
                           **props)

    def central(self, link_name: str, table: Mapping[str, Any], gears: Sequence[Gear], props: Mapping[str, sp.Expr],
                where: str) -> Link:
        extra = sorted(set(table) & {"angle", "arm", "count", "axis"})
        if extra:
            raise self.fail(f"{where} {extra[0]}", "only a planet (a link with a carrier) takes this key")
        if "mass" in props:
            raise self.fail(f"{where} mass", "only a planet takes a mass (its centre moves); give a link "
                                             "about the main axis its inertia")
        return Link.central(link_name, *gears, **props)

    def base(self, table: Any) -> Any:
        from symkin.particles import SpaceFrame

        table = self.keys(table, _BASE, "[base]")
        values = {}
        for key, value in table.items():
            where = f"[base] {key}"
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                values[key] = self.number(value, where, positive=False)
            elif isinstance(value, str):
                try:
                    values[key] = parse_expression(value, names=("t",), what="the value")
                except SymkinError as err:
                    raise self.fail(where, str(err)) from None
            else:
                raise self.fail(where, f"must be a number or an expression in t, got {_show(value)}")
        try:
            return SpaceFrame.euler(values.get("x", 0), values.get("y", 0), values.get("z", 0), yaw=values.get("yaw", 0),
                                    pitch=values.get("pitch", 0), roll=values.get("roll", 0))
        except SymkinError as err:
            raise self.fail("[base]", str(err)) from None

    def _check_joined(self, specs: Mapping[str, Mapping[str, Any]], meshes: Sequence[Mesh], states: Sequence[Any],
                      gear_owner: Mapping[str, str]) -> None:
        """Every link joined to the others by meshes, carriers and clutches (the frame, held,
        joins nothing): a link that nothing joins is a free speed no state can fix (50 of them
        took minutes before the states said so, by the degrees of freedom)."""
        names = [n for n in specs if n not in (FRAME_TABLE, FRAME)]
        pairs = [*((m.a, m.b) for m in meshes), *((n, specs[n].get("carrier")) for n in names),
                 *(pair for st in states for pair in st.clutches)]
        groups = _connected(names, [(gear_owner.get(a, a), gear_owner.get(b, b)) for a, b in pairs
                                    if isinstance(a, str) and isinstance(b, str)])
        if len(groups) < 2:
            return
        loose = [g[0] for g in groups[1:] if len(g) == 1]
        if len(loose) == len(groups) - 1:
            it = "it" if len(loose) == 1 else "them"
            raise self.fail("links", f"{', '.join(loose)} {'connects' if len(loose) == 1 else 'connect'} to nothing: no "
                                     f"mesh, carrier or clutch joins {it} to the rest; remove {it}, or give {it} a gear "
                                     "in a mesh")
        raise self.fail("links", f"the train falls apart into {len(groups)} parts that no mesh, carrier or clutch joins "
                                 f"({'; '.join(', '.join(g) for g in groups)}); join them, or give each its own file")

    def _check_carriers(self, specs: Mapping[str, Mapping[str, Any]]) -> None:
        for link_name, table in specs.items():
            if "carrier" not in table:
                continue
            carrier = table["carrier"]
            where = f"[links.{link_name}] carrier"
            if not isinstance(carrier, str):
                raise self.fail(where, f"must name a link, got {_show(carrier)}")
            if carrier not in specs and carrier != FRAME_TABLE:
                raise self.fail(where, f"names no link {carrier!r}; the links are {', '.join(specs)}")
            chain, at = [link_name], carrier
            while at in specs and "carrier" in specs[at]:
                chain.append(at)
                if at == link_name or len(chain) > len(specs):
                    raise self.fail(where, "carrier cycle: " + " -> ".join(chain + [specs[at]["carrier"]]) +
                                    "; a chain of carriers must end on a link about the main axis")
                at = specs[at]["carrier"]

    def meshes(self, items: Any, owner: Mapping[str, str]) -> list[Mesh]:
        if items is None:
            raise self.fail("meshes", "the file lists no meshes; add meshes = [[\"a\", \"b\"], ...] before the first [table]")
        if not isinstance(items, list):
            raise self.fail("meshes", f"must be a list of gear pairs, got {_show(items)}")
        return [self.mesh(item, owner, f"meshes[{k}]") for k, item in enumerate(items, 1)]

    def mesh(self, item: Any, owner: Mapping[str, str], where: str) -> Mesh:
        """One mesh: a pair of gear names, or a table of its gears and options."""
        options: dict[str, sp.Expr] = {}
        if isinstance(item, Mapping):
            item, options = self.mesh_table(item, where)
        if not isinstance(item, list) or len(item) != 2:
            raise self.fail(where, f"a mesh is a pair of gear names [\"a\", \"b\"], got {_show(item)}")
        for g in item:
            if g not in owner:
                raise self.fail(where, f"names no gear {g!r}; the gears are {', '.join(owner)}")
        try:
            return Mesh(item[0], item[1], **options)
        except ModelError as err:
            raise self.fail(where, str(err)) from None

    def mesh_table(self, table: Mapping[str, Any], where: str) -> tuple[Any, dict[str, sp.Expr]]:
        """A mesh as a table: its gears, and its centre distance, efficiency and stiffness (as Mesh takes them)."""
        table = self.keys(table, _MESH, where)
        options = self.mass_properties(table, where)
        if "centre_distance" in table:
            options["centre_distance"] = self.number(table["centre_distance"], f"{where} centre_distance")
        if "efficiency" in table:
            options["efficiency"] = self.number(table["efficiency"], f"{where} efficiency")
            if not options["efficiency"] <= 1:
                raise self.fail(f"{where} efficiency", f"must lie in (0, 1], got {_show(table['efficiency'])}")
        return table.get("gears"), options

    def states(self, table: Any, names: set[str]) -> list[State]:
        if not isinstance(table, Mapping):
            raise self.fail("[states]", f"must be tables [states.NAME], got {_show(table)}")
        out = []
        for state_name, spec in table.items():
            where = f"[states.{state_name}]"
            spec = self.keys(spec, _STATE, where)
            for key in ("input", "output"):
                if key not in spec:
                    raise self.fail(where, f"give the {key} link ({key} = \"LINK\")")
            brakes = spec.get("brakes", [])
            clutches = spec.get("clutches", [])
            if not isinstance(brakes, list) or not all(isinstance(b, str) for b in brakes):
                raise self.fail(f"{where} brakes", f"must be a list of link names, got {_show(brakes)}")
            if not isinstance(clutches, list) or not all(
                    isinstance(c, list) and len(c) == 2 and all(isinstance(x, str) for x in c) for c in clutches):
                raise self.fail(f"{where} clutches", f"must be a list of link pairs [[\"A\", \"B\"], ...], got {_show(clutches)}")
            used = [spec["input"], spec["output"], *brakes, *(x for c in clutches for x in c)]
            for n in used:
                if not isinstance(n, str) or (n not in names and n != FRAME_TABLE):
                    raise self.fail(where, f"names no link {n!r}; the links are {', '.join(sorted(names))}")
            description = self.text(spec.get("description", ""), f"{where} description")
            released = spec.get("released", [])
            if not isinstance(released, list) or not all(isinstance(r, str) for r in released):
                raise self.fail(f"{where} released", f"must be a list of one-way clutch names, got {_show(released)}")
            out.append(State(state_name, spec["input"], spec["output"], tuple(_model_name(b) for b in brakes),
                             tuple((_model_name(a), _model_name(b)) for a, b in clutches), description, tuple(released)))
        return out

    def one_ways(self, table: Any, names: set[str]) -> tuple[OneWay, ...]:
        """[one_way.NAME]: links = ["A", "B"] (B may be "frame"), blocks = "negative" or "positive"."""
        if not isinstance(table, Mapping):
            raise self.fail("[one_way]", f"must be tables [one_way.NAME], got {_show(table)}")
        out = []
        for ow_name, spec in table.items():
            where = f"[one_way.{ow_name}]"
            spec = self.keys(spec, _ONE_WAY, where)
            pair = spec.get("links")
            if not isinstance(pair, list) or len(pair) != 2 or not all(isinstance(n, str) for n in pair):
                raise self.fail(f"{where} links", f"is the pair of links it joins, [\"C2\", \"frame\"], got {_show(pair)}")
            for n in pair:
                if n not in names and n != FRAME_TABLE:
                    raise self.fail(f"{where} links", f"names no link {n!r}; the links are {', '.join(sorted(names))}")
            blocks = spec.get("blocks", "negative")
            if blocks not in ("negative", "positive"):
                raise self.fail(f"{where} blocks", f"is \"negative\" (the first link may not turn backwards relative to "
                                f"the second) or \"positive\", got {_show(blocks)}")
            try:
                link, other = (_model_name(n) for n in pair)
                out.append(OneWay(ow_name, link, other, blocks=blocks))
            except ModelError as err:
                raise self.fail(where, str(err)) from None
        return tuple(out)

    def _where_of(self, message: str, specs: Mapping[str, Any]) -> str:
        """The table an error of the model is about, when it names a link or a state."""
        state = re.match(r"state '([^']+)'", message)
        if state:
            return f"[states.{state.group(1)}]"
        named = [(m.start(), name) for name in specs
                 for m in [re.search(rf"\b(planets?|links?|carrier) {re.escape(name)}\b", message)] if m]
        if named:
            return f"[links.{min(named)[1]}]"
        return "meshes" if "mesh" in message or "gears" in message else ""


def _connected(names: Sequence[str], pairs: Sequence[tuple[str, str]]) -> list[list[str]]:
    """The groups of ``names`` that ``pairs`` join (a pair naming anything else joins nothing), largest first,
    each in the order of ``names``.

    >>> _connected(["A", "B", "C", "D"], [("A", "C"), ("C", "x")])
    [['A', 'C'], ['B'], ['D']]
    """
    parent = {n: n for n in names}

    def root(n: str) -> str:
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n

    for a, b in pairs:
        if a in parent and b in parent:
            parent[root(a)] = root(b)
    parts: dict[str, list[str]] = {}
    for n in names:
        parts.setdefault(root(n), []).append(n)
    return sorted(parts.values(), key=len, reverse=True)


def _model_name(name: str) -> str:
    """The model's name of a link named in a file: the file's "frame" is the model's frame :data:`FRAME`.

    >>> _model_name("frame"), _model_name("C")
    ('0', 'C')
    """
    return FRAME if name == FRAME_TABLE else name


def _show(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."
