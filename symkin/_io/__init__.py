"""Where symkin meets the operating system: files and the terminal (internal, not public API).

Only the borders import these, the command line (:mod:`symkin.cli`) and the papers' reports
(:mod:`symkin.papers`); the library returns objects and figures and writes nothing of its own
(``tests/project/test_architecture.py`` holds this).

- :mod:`.atomic`: outputs that appear whole or not at all (files, and report folders with
  their manifest);
- :mod:`.progress`: the one progress display of long work.
"""
