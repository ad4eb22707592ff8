import os
import warnings

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")
# symkin.compile's default backend is numba where it is installed; its first call of each law
# compiles a kernel (1-5 s).  The tests compile hundreds of laws to test what the laws give,
# so they take NumPy by default; the numba backend is tested where a test names it (the float
# backends' tests run both), and the default's choice in tests/numeric/test_numeric.py.
os.environ.setdefault("SYMKIN_BACKEND", "numpy")
if "SYMKIN_CACHE_DIR" not in os.environ:  # compiled Numba kernels of the tests: not in the user's cache
    import tempfile

    os.environ["SYMKIN_CACHE_DIR"] = tempfile.mkdtemp(prefix="symkin-test-kernels-")


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
    from symkin.papers.texbuild import find_pdflatex

    exe = find_pdflatex()
    if exe is None:
        message = "pdflatex not installed: the LaTeX compile test needs TeX Live (apt-get install texlive-latex-base)"
        if os.environ.get("CI"):
            pytest.fail(message + "; CI must have it (.ci/run installs it)")
        pytest.skip(message)
    return exe


# Hypothesis: the default profile keeps the suite fast; `pytest --hypothesis-profile=long` tries
# ten times as many examples (property tests set no max_examples of their own, so the profile rules).
from hypothesis import HealthCheck, settings  # noqa: E402

settings.register_profile("default", max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("long", max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("debug", max_examples=40, deadline=None, phases=[p for p in __import__("hypothesis").Phase
                                                                          if p.name != "shrink"])
settings.load_profile("default")
