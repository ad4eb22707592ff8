"""Internal helpers shared across the library (not public API; they may change without notice).

- :mod:`.bounds`: rigorous bounds on the numbers of an expression (interval arithmetic), which
  the parser (:mod:`symkin.parsing`) uses to bound what a user types;
- :mod:`.budget`: simplification under a size and time budget, and time limits;
- :mod:`.jsonout`: the JSON shape of exact numbers;
- :mod:`.display`: compact HTML and Markdown tables for notebooks and reports.
"""
