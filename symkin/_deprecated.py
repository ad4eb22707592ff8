"""Modules and names that moved in symkin 0.2, kept working for one release.

symkin 0.2 gave each mechanism family, the papers' machinery and the internal helpers
a home of their own (``docs/architecture.md``).  Every module path and name a user could
script against in 0.1 still works in 0.2: importing an old module gives the new one's
contents, and an old name gives the new object, each with a :class:`DeprecationWarning`
that names the new place.  They go in symkin 0.3.

    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     from symkin.stages import enumerate_stages
    >>> enumerate_stages.__module__
    'symkin.mechanisms.multistage.stages'
    >>> print(caught[0].message)
    symkin.stages is now symkin.mechanisms.multistage.stages; the old name goes in symkin 0.3
"""

from __future__ import annotations

import importlib
import importlib.machinery
import sys
import warnings
from types import FrameType, ModuleType
from typing import Any

__all__ = ["MODULES", "NAMES", "REMOVED_IN", "renamed", "install"]

#: The release that drops the old names.
REMOVED_IN = "0.3"

#: Old module -> new module.
MODULES: dict[str, str] = {
    "symkin.cardan": "symkin.mechanisms.cardan",
    "symkin.helical": "symkin.mechanisms.helical",
    "symkin.helical_synthesis": "symkin.mechanisms.helical.balanced",
    "symkin.helical_synthesis.laws": "symkin.mechanisms.helical.balanced.conditions",
    "symkin.helical_synthesis.regions": "symkin.mechanisms.helical.balanced.regions",
    "symkin.helical_synthesis.request": "symkin.mechanisms.helical.balanced.request",
    "symkin.helical_synthesis.search": "symkin.mechanisms.helical.balanced.search",
    "symkin.lostmotion": "symkin.mechanisms.multistage.lostmotion",
    "symkin.ratiosplit": "symkin.mechanisms.multistage.split",
    "symkin.ratiosplit.problem": "symkin.mechanisms.multistage.split.problem",
    "symkin.ratiosplit.continuous": "symkin.mechanisms.multistage.split.continuous",
    "symkin.ratiosplit.discrete": "symkin.mechanisms.multistage.split.discrete",
    "symkin.stages": "symkin.mechanisms.multistage.stages",
    "symkin.plotting": "symkin.viz.figures",
    "symkin.animation": "symkin.viz.animation",
    "symkin.splitplot": "symkin.viz.split",
    "symkin.report": "symkin.papers.checks",
    "symkin.reproduce": "symkin.papers.reproduce",
    "symkin.latex_report": "symkin.papers.document",
    "symkin.texbuild": "symkin.papers.texbuild",
    "symkin.budget": "symkin._util.budget",
    "symkin.jsonout": "symkin._util.jsonout",
    "symkin.atomic": "symkin._io.atomic",
    "symkin.numeric.scene": "symkin.study",
}

#: Old name -> ``"new.module:attribute"`` (names that were renamed, or moved apart from
#: their module), and how the warning names the new place when that is not the target.
NAMES: dict[str, str | tuple[str, str]] = {
    "symkin.Scene": ("symkin.study:Study", "symkin.Study"),
    "symkin.numeric.Scene": ("symkin.study:Study", "symkin.Study"),
    "symkin.numeric.scene.Scene": ("symkin.study:Study", "symkin.Study"),
    "symkin.animation.Scene": "symkin.viz.animation:Frames",
    "symkin.lostmotion.ratio_symbol": "symkin.mechanisms.multistage.lostmotion:stage_ratio_symbol",
    "symkin.plotting.sample": ("symkin._deprecated:_plotting_sample", "the method Particle.sample"),
    "symkin.plotting.turn_time": ("symkin._deprecated:_plotting_turn_time", "the method Motion.turn_time"),
    "symkin.ratiosplit._solve": "symkin.mechanisms.multistage.split:solve_continuous",
    # spelt -ize, as SymPy; named apart from symkin.synthesis's synthesize, SynthesisResult and Design
    "symkin.helical_synthesis.synthesise": "symkin.mechanisms.helical:synthesize_helical",
    "symkin.helical_synthesis.search.synthesise": "symkin.mechanisms.helical:synthesize_helical",
    "symkin.helical_synthesis.SynthesisRequest": "symkin.mechanisms.helical:HelicalRequest",
    "symkin.helical_synthesis.request.SynthesisRequest": "symkin.mechanisms.helical:HelicalRequest",
    "symkin.helical_synthesis.SynthesisResult": "symkin.mechanisms.helical:HelicalResult",
    "symkin.helical_synthesis.request.SynthesisResult": "symkin.mechanisms.helical:HelicalResult",
    "symkin.ratiosplit.optimise_split": "symkin.mechanisms.multistage:optimize_split",
    "symkin.ratiosplit.continuous.optimise_split": "symkin.mechanisms.multistage:optimize_split",
    "symkin.ratiosplit.Design": "symkin.mechanisms.multistage:SplitDesign",
    "symkin.ratiosplit.discrete.Design": "symkin.mechanisms.multistage:SplitDesign",
}


def _caller_level() -> int:
    """The stack level of the first frame outside the import machinery and symkin's
    own re-export layers, so that a warning points at the line that used the old name."""
    level = 1
    frame: FrameType | None = sys._getframe(1)
    while frame is not None and (frame.f_globals.get("__name__", "") in _LAYERS or
                                 frame.f_globals.get("__name__", "").startswith("importlib")):
        internal = "importlib" in frame.f_code.co_filename and "_bootstrap" in frame.f_code.co_filename
        frame = frame.f_back
        if not internal:  # warnings.warn does not count the import system's own frames
            level += 1
    return level


#: Modules whose frames stand between a user's line and the warning.
_LAYERS = frozenset({"symkin", "symkin._deprecated", "symkin.numeric"})


def _warn(old: str, new: str) -> None:
    warnings.warn(f"{old} is now {new}; the old name goes in symkin {REMOVED_IN}", DeprecationWarning,
                  stacklevel=_caller_level())


def _resolve(target: str) -> Any:
    module, _, attribute = target.partition(":")
    return getattr(importlib.import_module(module), attribute)


def renamed(old: str, target: str | tuple[str, str]) -> Any:
    """The object ``target`` (``"module:attribute"``, or that and the new name to show)
    that ``old`` names, with a warning."""
    where, shown = target if isinstance(target, tuple) else (target, target.replace(":", "."))
    _warn(old, shown)
    return _resolve(where)


class _Finder:  # a meta path finder and loader (importlib.abc's protocols; importing it costs ~20 ms)
    """Imports an old module path as a stand-in that forwards to the new module."""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> importlib.machinery.ModuleSpec | None:
        if fullname not in MODULES:
            return None
        new = importlib.import_module(MODULES[fullname])
        is_package = hasattr(new, "__path__")
        return importlib.machinery.ModuleSpec(fullname, self, is_package=is_package)  # type: ignore[arg-type]

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType | None:
        return None  # a plain module, filled by exec_module

    def exec_module(self, module: ModuleType) -> None:
        old = module.__name__
        new_name = MODULES[old]
        new = importlib.import_module(new_name)
        _warn(old, new_name)

        def __getattr__(name: str) -> Any:
            if f"{old}.{name}" in NAMES:
                return renamed(f"{old}.{name}", NAMES[f"{old}.{name}"])
            try:
                return getattr(new, name)
            except AttributeError:
                raise AttributeError(f"module {old!r} (now {new_name!r}) has no attribute {name!r}") from None

        def __dir__() -> list[str]:
            return sorted(set(dir(new)) | {n.rpartition(".")[2] for n in NAMES if n.rpartition(".")[0] == old})

        module.__getattr__ = __getattr__  # type: ignore[method-assign]
        module.__dir__ = __dir__  # type: ignore[method-assign]
        module.__doc__ = f"Deprecated: {old} is now {new_name} (goes in symkin {REMOVED_IN})."
        module.__dict__["__all__"] = list(getattr(new, "__all__", []))  # ModuleType declares no __all__
        if hasattr(new, "__path__"):
            module.__path__ = []


_FINDER = _Finder()


def install() -> None:
    """Let the old module paths import (called once by ``import symkin``)."""
    if not any(isinstance(f, _Finder) for f in sys.meta_path):
        sys.meta_path.insert(0, _FINDER)


# --------------------------------------------------------------------------- old signatures
def _plotting_sample(particle: Any, t_end: float, *, samples: int = 721, values: Any = None) -> Any:
    """``symkin.plotting.sample(particle, t_end, ...)``: now ``particle.sample(t_end, ...)``."""
    return particle.sample(t_end, samples=samples, values=values)


def _plotting_turn_time(motion: Any, turns: float = 1.0, link: str | None = None, values: Any = None) -> float:
    """``symkin.plotting.turn_time(motion, ...)``: now ``motion.turn_time(...)``."""
    return motion.turn_time(turns, link=link, values=values)
