"""Internal helpers shared across symkin (not public API; they may change without notice).

- :mod:`.parsing`: the one gate for user numbers and expressions (safe parsing, bounds);
- :mod:`.bounds`: rigorous bounds on the numbers of an expression (interval arithmetic);
- :mod:`.budget`: simplification under a size and time budget, and time limits;
- :mod:`.atomic`: outputs that appear whole or not at all;
- :mod:`.jsonout`: the JSON shape of exact numbers;
- :mod:`.progress`: the one progress display of long work.
"""
