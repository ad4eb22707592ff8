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
