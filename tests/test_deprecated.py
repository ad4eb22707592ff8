"""The module paths and names of symkin 0.1 keep working for one release, with a warning.

Each old path must import in a fresh interpreter, give the very objects of its new home,
and warn once with a DeprecationWarning that names the new place and points at the line
that used the old name.  Each old name (symkin.Scene, animation.Scene, ...) likewise.
"""

from __future__ import annotations

import importlib
import subprocess
import sys
import warnings

import pytest

from symkin import _deprecated

OLD_MODULES = sorted(_deprecated.MODULES)


def _fresh(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-W", "always::DeprecationWarning", "-c", code],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("old", OLD_MODULES)
def test_an_old_module_path_imports_the_new_module_with_a_warning(old):
    new = _deprecated.MODULES[old]
    code = (
        "import importlib, sys\n"
        f"old = importlib.import_module({old!r})\n"
        f"new = importlib.import_module({new!r})\n"
        "names = [n for n in getattr(new, '__all__', []) if not n.startswith('_')]\n"
        "assert names, 'the new module names nothing public'\n"
        "assert all(getattr(old, n) is getattr(new, n) for n in names), 'a name differs'\n"
        "print(len(names))\n"
    )
    proc = _fresh(code)
    assert proc.returncode == 0, proc.stderr
    assert int(proc.stdout) > 0
    assert f"DeprecationWarning: {old} is now {new}; the old name goes in symkin 0.3" in proc.stderr
    assert "<string>:2:" in proc.stderr, f"the warning should point at the importing line:\n{proc.stderr}"


def test_from_import_of_an_old_module_warns_at_the_users_line():
    proc = _fresh("x = 1\nfrom symkin.stages import enumerate_stages\nprint(enumerate_stages.__module__)")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "symkin.mechanisms.multistage.stages"
    assert "<string>:2: DeprecationWarning: symkin.stages is now symkin.mechanisms.multistage.stages" in proc.stderr


def test_an_old_module_as_an_attribute_of_symkin():
    import symkin
    from symkin.mechanisms import cardan

    with pytest.warns(DeprecationWarning, match=r"symkin\.cardan is now symkin\.mechanisms\.cardan"):
        old = symkin.cardan
    assert old.CardanSlider is cardan.CardanSlider


@pytest.mark.parametrize("old", sorted(_deprecated.NAMES))
def test_an_old_name_gives_the_new_object_with_a_warning(old):
    module, _, name = old.rpartition(".")
    target = _deprecated.NAMES[old]
    where = target[0] if isinstance(target, tuple) else target
    new_module, _, new_name = where.partition(":")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        value = getattr(importlib.import_module(module), name)
    assert value is getattr(importlib.import_module(new_module), new_name)
    messages = [str(w.message) for w in caught if issubclass(w.category, DeprecationWarning)]
    assert any(m.startswith(f"{old} is now ") for m in messages), messages
    assert all(w.filename == __file__ for w in caught if str(w.message).startswith(f"{old} is now ")), \
        [w.filename for w in caught]


def test_the_old_signatures_of_sample_and_turn_time_give_the_new_results():
    from symkin import schemes

    motion = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 2})
    particle = motion.particle("2", (2, 1))
    with pytest.warns(DeprecationWarning):
        from symkin.plotting import sample, turn_time
    old = sample(particle, 3.0, samples=7)
    new = particle.sample(3.0, samples=7)
    assert all((old[k] == new[k]).all() for k in new)
    assert turn_time(motion, 2) == motion.turn_time(2)


def test_an_unknown_name_of_an_old_module_is_an_attribute_error_naming_both_paths():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        import symkin.lostmotion as old
    with pytest.raises(AttributeError, match=r"symkin\.lostmotion.*symkin\.mechanisms\.multistage\.lostmotion.*no_such"):
        old.no_such


def test_the_library_uses_no_old_path():
    # the test configuration turns symkin's own DeprecationWarnings into errors; this makes
    # sure the new paths are what the library and its papers import
    proc = _fresh(
        "import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
        "import symkin.cli, symkin.study, symkin.viz.figures, symkin.viz.animation, symkin.viz.split\n"
        "import symkin.mechanisms.cardan, symkin.mechanisms.helical.balanced, symkin.mechanisms.multistage.split\n"
        "import symkin.papers.reproduce\n"
        "from symkin.papers.registry import load, paper_names\n"
        "[load(n) for n in paper_names()]\n"
    )
    assert proc.returncode == 0, proc.stderr
