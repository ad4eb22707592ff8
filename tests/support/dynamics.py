"""Train files the dynamics tests share."""

#: One head P on the arm C (fixed sun s0), one gear G on the head's own axis, one tool Q on the
#: head: no equally spaced copies, so the mass matrix depends on the configuration.
NESTED_ONE = """
module = 1
meshes = [["s0", "p"], ["g", "q"]]
[links.frame]
gears = { s0 = 60 }
[links.C]
[links.P]
carrier = "C"
gears = { p = 30 }
[links.G]
carrier = "P"
arm = 0
gears = { g = 18 }
[links.Q]
carrier = "P"
gears = { q = 12 }
"""
