"""The package ships its PEP 561 marker, ``fretting/py.typed``, and the example histories of the
top-level ``histories/`` folder (as ``fretting/histories/``), in the wheel and in the sdist.

Run from a checkout these read the source tree; CI runs them from the installed wheel (away from
the checkout) and from the unpacked sdist, where they check what was built.
"""

import importlib.metadata
import importlib.resources
import tomllib
from pathlib import Path

import fretting
from fretting.loading.examples import EXAMPLES, examples

PACKAGE = Path(fretting.__file__).resolve().parent


def _source_tree():
    """The source tree (or unpacked sdist) the package is imported from; None where it is installed."""
    tree = PACKAGE.parent
    return tree if (tree / "pyproject.toml").is_file() and (tree / "MANIFEST.in").is_file() else None


def test_py_typed_is_package_data():
    assert (importlib.resources.files("fretting") / "py.typed").is_file()


def test_installed_package_lists_py_typed():
    """Installed from a wheel, the distribution's file list (RECORD) names the marker; from a
    source tree or sdist, pyproject.toml's package data and MANIFEST.in name it."""
    tree = _source_tree()
    if tree is not None:
        assert '"py.typed"' in (tree / "pyproject.toml").read_text(encoding="utf-8")
        assert "include fretting/py.typed" in (tree / "MANIFEST.in").read_text(encoding="utf-8").splitlines()
    else:
        recorded = {str(f).replace("\\", "/") for f in importlib.metadata.files("fretting") or ()}
        assert "fretting/py.typed" in recorded, sorted(recorded)[:20]


def test_the_example_histories_are_found_where_they_ship():
    """``histories/`` beside the package in a source tree, ``fretting/histories/`` once installed;
    the histories, their tables, the sweep and the material are all there."""
    tree = _source_tree()
    assert EXAMPLES == (PACKAGE / "histories" if tree is None else tree / "histories")
    assert len(examples()) >= 7 and (EXAMPLES / "hertz_shear_cycling.toml").is_file()
    for shipped in ("asymmetric_pad_gap.csv", "sweeps/hertz_fretting_map.toml", "materials/steel.toml"):
        assert (EXAMPLES / shipped).is_file(), shipped
    if tree is None:
        recorded = {str(f).replace("\\", "/") for f in importlib.metadata.files("fretting") or ()}
        assert "fretting/histories/hertz_shear_cycling.toml" in recorded


def test_the_listed_packages_are_those_of_the_source_tree():
    """pyproject.toml lists the packages (histories/ is mapped to one): every package of the tree is
    listed, and the mapped folder with it, so none is left out of the wheel."""
    tree = _source_tree()
    if tree is None:  # installed: the wheel holds a module of every package the source tree had
        found = {path.parent for path in PACKAGE.rglob("__init__.py")}
        assert {path.name for path in found} >= {"analysis", "engine", "galerkin", "loading", "results", "studies"}
        return
    setuptools = tomllib.loads((tree / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]
    found = {".".join(path.parent.relative_to(tree).parts) for path in (tree / "fretting").rglob("__init__.py")}
    shipped = {
        "fretting.histories",
        *(f"fretting.histories.{d.name}" for d in (tree / "histories").iterdir() if d.is_dir()),
    }
    assert set(setuptools["packages"]) == found | shipped
    assert setuptools["package-dir"] == {"fretting.histories": "histories"}
    assert "graft histories" in (tree / "MANIFEST.in").read_text(encoding="utf-8").splitlines()


def test_the_compiled_kernels_run_where_numba_can_write_no_cache():
    """A read-only installation run by a user whose home is read-only too: numba finds no folder for its
    cache (no locator) and refuses ``cache=True``; the package imports all the same, its kernels compiled
    in the process, and gives the same numbers (checked on a read-only mount: fretting/_compiled.py)."""
    import subprocess
    import sys

    run = (
        "import fretting as fr; "
        "c = fr.Contact(fr.Hertz(0.05), 115e9, 0.6, 1e5); "
        "h = fr.History.piecewise_linear([0.0, 4e4, -2e4, 3e4], None, 8); "
        "print(repr(float(fr.simulate(c, h).total_dissipation)))"
    )
    no_cache = "import numba.core.caching as caching; caching.CacheImpl._locator_classes = []; "
    energies = [
        subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()[-1]
        for code in (run, no_cache + run)
    ]
    assert energies[0] == energies[1] and float(energies[0]) > 0
