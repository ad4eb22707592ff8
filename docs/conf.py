"""Sphinx configuration of symkin's documentation (the API reference, the guides, the
paper notebooks and the figure gallery).

Build it with warnings as errors (tests/project/test_docs.py does, so CI does)::

    pip install -e ".[docs]"
    python -m sphinx -W -b html docs docs/_build/html

The notebooks are the executed ones stored in ``notebooks/``: they are copied beside these
pages (``docs/notebooks/``, not tracked) and shown with their stored outputs, never executed
here.  The gallery's images are drawn by symkin itself at build time (``docs/gallery.py``,
into ``docs/gallery/``, not tracked).
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

from symkin._version import __version__  # noqa: E402

project = "symkin"
author = "The symkin developers"
copyright = "2026, The symkin developers"
release = version = __version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "myst_nb",
]
exclude_patterns = ["_build", "notebooks/src", "**.ipynb_checkpoints"]
# the notebooks are executed and stored by notebooks/build.py; the docs show what is stored
nb_execution_mode = "off"
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3

# A package re-exports names from its modules in __all__; each name is documented once, where it
# is defined (ignore-module-all: members are those whose __module__ is the module documented).
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": True,
                           "ignore-module-all": True}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_typehints_format = "short"
autoclass_content = "both"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
# an Attributes section as a field list, not a second description of each dataclass field
napoleon_use_ivar = True
# Docstrings are written for readers: type names there are prose, not references to resolve.
nitpicky = False
# Type fields written as prose ("tuple of (link name, kind, ...)") have words Sphinx tries to
# resolve against every attribute of that name ("more than one target found"): not a broken link.
suppress_warnings = ["mystnb.unknown_mime_type", "ref.python"]

html_theme = "alabaster"
html_title = f"symkin {release}"
html_static_path: list[str] = []


def _copy_notebooks() -> None:
    """The stored notebooks beside the pages (copied only when changed, so builds are incremental)."""
    target = HERE / "notebooks"
    target.mkdir(exist_ok=True)
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        dest = target / nb.name
        if not dest.exists() or dest.read_bytes() != nb.read_bytes():
            shutil.copyfile(nb, dest)


def _draw_gallery(app) -> None:
    sys.path.insert(0, str(HERE))
    import gallery

    gallery.draw(HERE / "gallery")


def setup(app):
    _copy_notebooks()
    app.connect("builder-inited", _draw_gallery)
