"""The package ships its PEP 561 marker, ``fretting/py.typed``, in the wheel and in the sdist.

Run from a checkout these read the source tree; CI runs them from the installed wheel (away from
the checkout) and from the unpacked sdist, where they check what was built.
"""

import importlib.metadata
import importlib.resources
from pathlib import Path

import fretting


def test_py_typed_is_package_data():
    assert (importlib.resources.files("fretting") / "py.typed").is_file()


def test_installed_package_lists_py_typed():
    """Installed from a wheel, the distribution's file list (RECORD) names the marker; from a
    source tree or sdist, pyproject.toml's package data and MANIFEST.in name it."""
    package = Path(fretting.__file__).resolve().parent
    tree = package.parent
    if (tree / "pyproject.toml").is_file() and (tree / "MANIFEST.in").is_file():
        assert '"py.typed"' in (tree / "pyproject.toml").read_text(encoding="utf-8")
        assert "include fretting/py.typed" in (tree / "MANIFEST.in").read_text(encoding="utf-8").splitlines()
    else:
        recorded = {str(f).replace("\\", "/") for f in importlib.metadata.files("fretting") or ()}
        assert "fretting/py.typed" in recorded, sorted(recorded)[:20]
