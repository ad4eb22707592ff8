"""Every public function, class, method and property of symkin has a docstring
(counted by tests/support/docstrings.py; 108 lacked one before issue 20)."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _audit():
    spec = importlib.util.spec_from_file_location("docstring_audit", ROOT / "tests" / "support" / "docstrings.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


audit = _audit()


def test_every_public_object_has_a_docstring():
    lacking = audit.missing()
    assert not lacking, f"{len(lacking)} public objects have no docstring (python tests/support/docstrings.py lists them): {lacking}"


def test_the_audit_sees_the_public_api_and_skips_private_names():
    names = {name for name, _ in audit.public_objects()}
    assert len(names) > 500
    assert {"symkin.model.mechanism.Mechanism", "symkin.model.mechanism.Mechanism.ratio", "symkin.units.quantity",
            "symkin.derivations.khai2014.figures", "symkin.viz.figures.trajectory_figure"} <= names
    assert not any(part.startswith("_") for name in names for part in name.split("."))


def test_the_audit_finds_a_missing_docstring(tmp_path, monkeypatch):
    package = tmp_path / "pkg"
    (package / "_hidden").mkdir(parents=True)
    (package / "mod.py").write_text('def shown():\n    pass\n\n\ndef _private():\n    pass\n\n\nclass K:\n    """K."""\n\n'
                                    '    def method(self):\n        return 1\n')
    (package / "_hidden" / "inner.py").write_text("def undocumented():\n    pass\n")
    monkeypatch.setattr(audit, "FOLDERS", (("pkg", package),))
    assert audit.missing() == ["pkg.mod.shown", "pkg.mod.K.method"]
