"""Train files typed for tests."""

from __future__ import annotations

#: A simple planetary set whose tooth numbers are symbols: nothing in it can be drawn to scale.
SYMBOLIC_SIMPLE = """name = "x"
meshes = [["s", "p"], ["p", "r"]]
[links.S]
gears = { s = "z1" }
[links.C]
[links.P]
carrier = "C"
gears = { p = "z2" }
[links.R]
gears = { r = { teeth = "z3", internal = true } }
"""
