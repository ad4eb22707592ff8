"""Internal helpers shared across symkin (not public API; they may change without notice).

- :mod:`.parsing`: the one gate for user numbers and expressions (safe parsing, bounds);
- :mod:`.bounds`: rigorous bounds on the numbers of an expression (interval arithmetic);
- :mod:`.budget`: simplification under a size and time budget, and time limits;
- :mod:`.atomic`: outputs that appear whole or not at all;
- :mod:`.jsonout`: the JSON shape of exact numbers;
- :mod:`.progress`: the one progress display of long work.
"""

#: The garbage collector's thresholds of the symkin program and of reproduce's workers: SymPy
#: allocates (and drops) objects by the million, and collecting every 700 net allocations
#: (Python's default) spent about 1 s of a reproduce run's CPU in the collector; every 10,000
#: about half that, with the same results.
GC_THRESHOLDS = (10_000, 10, 10)
