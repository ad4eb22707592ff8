"""Figures and animation, drawn from derived laws (matplotlib's object API, no pyplot state).

- :mod:`.figures`: particle trajectories with pitch circles, speed and acceleration
  curves, saving by suffix;
- :mod:`.animation`: a mechanism in motion (carrier, gears, particle paths) as GIF or MP4;
- :mod:`.split`: figures of the multistage ratio split.

Every number drawn is sampled through :mod:`symkin.numeric.sampling`, so the numeric
guarantees (no silent nan or inf) hold for figures too.
"""
