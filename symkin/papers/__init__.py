"""Reproducing published papers: checks and verdicts, the runner, the report and its PDF.

- :mod:`.checks`: a check of a derived result against a published one, and its computed
  verdict;
- :mod:`.registry`: the papers ``symkin reproduce`` knows, found through the entry-point
  group ``symkin.papers`` (the engine never imports a paper);
- :mod:`.reproduce`: derive and check papers, write the report folder atomically;
- :mod:`.document` and :mod:`.texbuild`: the LaTeX document of derived and published
  equations, and its PDF.

The papers themselves are the modules of ``derivations/`` (installed as
``symkin.derivations``), each registered under ``symkin.papers`` in ``pyproject.toml``.
"""
