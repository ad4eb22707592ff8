"""Multistage trains of single-row AI stages sharing one fixed ring (KhAI 2014).

- :mod:`.stages`: the conditions of one stage (coaxiality, assembly, neighbours), derived
  from the engine's single-row AI scheme, and the exact enumeration of feasible stages;
- :mod:`.lostmotion`: the lost motion of an n-stage train carried to the output, derived
  from the engine's common-ring train, and stage error models;
- :mod:`.split`: the split of a total ratio over the stages for the least lost motion
  (continuous with its KKT analysis, and discrete over feasible stages).

The train itself is :func:`symkin.schemes.common_ring_train`.  The names a user needs are
importable from here (each loads its module on first use):

    >>> from symkin.mechanisms.multistage import StageErrorModel, best_designs, enumerate_stages
    >>> stages = enumerate_stages(72, 3, zmin=12, zmax=72)
    >>> best_designs(20, stages, 2, model=StageErrorModel.linear(1, 1), tolerance=0.05, top=1).designs[0].ratios
    (3, 7)
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # what the names loaded on first use are, for type checkers and IDEs
    from symkin.mechanisms.multistage.lostmotion import (
        LostMotion,
        StageErrorModel,
        lost_motion,
        max_lost_motion,
        probable_max_backlash,
    )
    from symkin.mechanisms.multistage.split import (
        MAX_STAGES,
        ContinuousSplit,
        DiscreteSplit,
        SplitDesign,
        SplitProblem,
        best_designs,
        optimize_split,
    )
    from symkin.mechanisms.multistage.stages import Stage, StageSet, check_stage, enumerate_stages, max_satellites

#: The modules that hold the names of ``__all__``, each imported when one of its names is first used
#: (so that ``symkin stages`` imports no split, and the modules load in the order they always did).
_MODULES = ("stages", "lostmotion", "split")

__all__ = [
    "Stage",
    "StageSet",
    "enumerate_stages",
    "check_stage",
    "max_satellites",
    "LostMotion",
    "StageErrorModel",
    "lost_motion",
    "probable_max_backlash",
    "max_lost_motion",
    "SplitProblem",
    "ContinuousSplit",
    "DiscreteSplit",
    "SplitDesign",
    "optimize_split",
    "best_designs",
    "MAX_STAGES",
]


def __getattr__(name: str) -> Any:
    if name in __all__:
        for home in _MODULES:
            module = importlib.import_module(f"{__name__}.{home}")
            if name in module.__all__:
                value = getattr(module, name)
                globals()[name] = value
                return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
