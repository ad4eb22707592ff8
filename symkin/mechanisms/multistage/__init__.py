"""Multistage trains of single-row AI stages sharing one fixed ring (KhAI 2014).

- :mod:`.stages`: the conditions of one stage (coaxiality, assembly, neighbours), derived
  from the engine's single-row AI scheme, and the exact enumeration of feasible stages;
- :mod:`.lostmotion`: the lost motion of an n-stage train carried to the output, derived
  from the engine's common-ring train, and stage error models;
- :mod:`.split`: the split of a total ratio over the stages for the least lost motion
  (continuous with its KKT analysis, and discrete over feasible stages).

The train itself is :func:`symkin.schemes.common_ring_train`.
"""
