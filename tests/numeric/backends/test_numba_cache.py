"""The kernel cache cannot be poisoned: Numba's cache files are pickles, which run code when
loaded, so the cache folder is private (made 0700, the user's own) and a folder others can
write is ignored with a warning (kernels compile in memory); a truncated or damaged entry is
discarded and compiled again instead of breaking every later compile of its law."""

from __future__ import annotations

import os
import pickle
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("numba")

import symkin
from symkin.errors import SymkinWarning
from symkin.numeric.backends import numba as numba_backend
from symkin.numeric.backends.numba import kernel_cache_folder

pytestmark = pytest.mark.skipif(os.name != "posix", reason="file modes and owners are POSIX's")


def ratio(scheme: str = "AI"):
    return symkin.schemes.two_row(scheme).ratio("1", "H", fixed="4")


def evaluate(law) -> tuple[np.ndarray, list[str]]:
    """The law on two points with a fresh compile (the kernel module forgotten, so its file and
    Numba's cache entries are read again, as in a new process), and the warnings."""
    for name in [n for n in sys.modules if n.startswith("symkin_kernel_")]:
        del sys.modules[name]
    f = symkin.compile(law, backend="numba")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        values = f(np.array([1.0, 2.0]), np.array([2.0, 3.0]), np.array([1.0, 1.0]), np.array([4.0, 5.0]))
    return values, [str(w.message) for w in caught if issubclass(w.category, SymkinWarning)]


#: the AI ratio i_1H^(4) = 1 + r2 r4 / (r1 r3) (Willis, the ring held), by hand at the two points
EXPECTED = np.array([1 + 2 * 4 / (1 * 1), 1 + 3 * 5 / (2 * 1)])


def test_the_default_folder_is_the_platforms_user_cache_made_private(tmp_path, monkeypatch):
    import platformdirs

    monkeypatch.delenv("SYMKIN_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    folder = kernel_cache_folder()
    assert folder == Path(platformdirs.user_cache_dir("symkin")) / "kernels"
    if sys.platform.startswith("linux"):
        assert folder == tmp_path / "xdg" / "symkin" / "kernels"  # $XDG_CACHE_HOME honoured
    assert folder.stat().st_mode & 0o777 == 0o700


@pytest.mark.parametrize("problem, make", [
    ("can be written by others", lambda d, mp: d.chmod(0o777)),
    ("can be written by others", lambda d, mp: d.chmod(0o770)),
    ("belongs to another user", lambda d, mp: mp.setattr(os, "getuid", lambda: os.stat(d).st_uid + 1)),
])
def test_a_folder_others_can_write_or_own_is_ignored_with_a_warning(problem, make, tmp_path, monkeypatch):
    shared = tmp_path / "shared"
    shared.mkdir()
    make(shared, monkeypatch)
    monkeypatch.setenv("SYMKIN_CACHE_DIR", str(shared))
    numba_backend._warn_not_private.cache_clear()
    with pytest.warns(SymkinWarning, match=f"{problem}.*compiled in memory"):
        assert kernel_cache_folder() is None


def test_numbas_own_subfolder_made_under_a_loose_umask_is_tightened_not_refused(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    (folder / "__pycache__").mkdir(parents=True)
    folder.chmod(0o700)
    (folder / "__pycache__").chmod(0o775)  # what Numba makes under a umask of 002
    monkeypatch.setenv("SYMKIN_CACHE_DIR", str(folder))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert kernel_cache_folder() == folder
    assert (folder / "__pycache__").stat().st_mode & 0o777 == 0o755


def test_a_poisoned_entry_in_a_shared_folder_never_runs(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    folder.mkdir(mode=0o700)
    monkeypatch.setenv("SYMKIN_CACHE_DIR", str(folder))
    law = ratio("AI")
    values, _ = evaluate(law)  # the kernel and Numba's entries written
    np.testing.assert_allclose(values, EXPECTED, rtol=1e-15)
    marker = tmp_path / "PWNED"

    class Poison:
        def __reduce__(self):
            return (open, (str(marker), "w"))

    entries = list((folder / "__pycache__").glob("*.nbi"))
    assert entries
    for entry in entries:
        entry.write_bytes(pickle.dumps(Poison()))
    folder.chmod(0o777)  # a folder anyone can write: its entries are never loaded
    numba_backend._warn_not_private.cache_clear()
    values, notes = evaluate(law)
    np.testing.assert_allclose(values, EXPECTED, rtol=1e-15)
    assert not marker.exists() and any("compiled in memory" in n for n in notes)
    # the control: in a private folder the same entry is loaded (and runs), so the test can fail
    folder.chmod(0o700)
    values, notes = evaluate(law)
    np.testing.assert_allclose(values, EXPECTED, rtol=1e-15)
    assert marker.exists()


@pytest.mark.parametrize("suffix, keep", [(".nbc", 100), (".nbi", 10), (".nbc", 0)])
def test_a_truncated_entry_is_discarded_and_rebuilt(suffix, keep, tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("SYMKIN_CACHE_DIR", str(folder))
    law = ratio("AI")
    evaluate(law)
    for entry in (folder / "__pycache__").glob(f"*{suffix}"):
        entry.write_bytes(entry.read_bytes()[:keep])
    values, notes = evaluate(law)  # UnpicklingError / EOFError before, at every later compile
    np.testing.assert_allclose(values, EXPECTED, rtol=1e-15)
    assert any("damaged entry of the kernel cache" in n for n in notes)
    values, notes = evaluate(law)  # rebuilt: loaded without a word
    np.testing.assert_allclose(values, EXPECTED, rtol=1e-15)
    assert not notes
