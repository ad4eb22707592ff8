import os
import warnings

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")


@pytest.fixture
def no_coaxiality_warning():
    """Run a block where a CoaxialityWarning would be a failure."""
    from symkin import CoaxialityWarning

    with warnings.catch_warnings():
        warnings.simplefilter("error", CoaxialityWarning)
        yield


@pytest.fixture
def pdflatex():
    """The pdflatex executable; skipped with a clear message when absent locally, a failure in CI
    (.ci/run installs TeX Live's base packages)."""
    from symkin.texbuild import find_pdflatex

    exe = find_pdflatex()
    if exe is None:
        message = "pdflatex not installed: the LaTeX compile test needs TeX Live (apt-get install texlive-latex-base)"
        if os.environ.get("CI"):
            pytest.fail(message + "; CI must have it (.ci/run installs it)")
        pytest.skip(message)
    return exe
