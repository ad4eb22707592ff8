"""Tooth numbers for a target ratio, for any train: conditions derived from the model, an exact pruned search.

- :mod:`.request`: what is asked, in request objects (:class:`SynthesisRequest` of a
  :class:`Target` and :class:`Options`; :class:`RunOptions` for how the search runs);
- :mod:`.problem`: the conditions derived from a train whose tooth numbers are symbols
  (coaxiality, assembly of k planets, neighbours, limits: :func:`derive`), made of the parts of
  :mod:`.parts`, the assembly of :mod:`.assembly`, printable as LaTeX (:mod:`.conditions`);
- :mod:`.search`: a chunk of the space searched, exact in integers and rationals: the plan
  (:mod:`.plan`: the coaxiality solved for some tooth numbers, the ratio window for one more,
  compiled), the tuples with the ratio (:mod:`.tuples`) and the checks (:mod:`.funnel`);
- :mod:`.efficiency`: the train's efficiency law, for ranking designs by it exactly;
- :mod:`.runner`: chunks run here or on Dask, with progress and a time limit;
- :mod:`.result`: the designs, each re-checked by building its train;
- :mod:`.searches`: what this search shares with the helical synthesis and the multistage
  split (:class:`SearchResult`);
- :func:`synthesize`: all of it in one call.

    >>> from symkin.synthesis import synthesize
    >>> from fractions import Fraction
    >>> res = synthesize("ravigneaux", driver="S1", driven="R", fixed="C", ratio=Fraction(12, 5), tolerance=0, planets=3,
    ...                  zmax=72)
    >>> res.designs[0].gear_teeth, res.designs[0].check().passed
    ((('s1', 30), ('s2', 24), ('p1', 18), ('p2', 24), ('r', 72)), True)
"""

from __future__ import annotations

from symkin.synthesis.api import synthesize
from symkin.synthesis.conditions import Condition
from symkin.synthesis.problem import Problem, derive
from symkin.synthesis.request import Options, RunOptions, SynthesisRequest, Target, undercut_minimum
from symkin.synthesis.result import Design, DesignCheck, SynthesisResult
from symkin.synthesis.searches import SearchResult

__all__ = ["synthesize", "SynthesisRequest", "Target", "Options", "RunOptions", "derive", "Problem", "Condition", "Design",
           "DesignCheck", "SynthesisResult", "SearchResult", "undercut_minimum"]
