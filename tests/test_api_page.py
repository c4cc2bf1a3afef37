"""Every public module of `fretting` has an entry on the API reference page (docs/api.md): a
mkdocstrings directive ``::: module`` or ``::: module.name``, so that no module goes undocumented.

Public: no part of its dotted name starts with an underscore. A package counts as a module where its
``__init__`` defines an ``__all__`` of its own (the others only hold their modules).
"""

import importlib
import pkgutil
import re
from pathlib import Path

import pytest

import fretting

PAGE = Path(__file__).resolve().parents[1] / "docs" / "api.md"
DIRECTIVE = re.compile(r"^::: (fretting(?:\.\w+)*)\s*$", re.MULTILINE)


def public_modules():
    found = ["fretting"]
    for module in pkgutil.walk_packages(fretting.__path__, "fretting."):
        if any(part.startswith("_") for part in module.name.split(".")):
            continue
        if not module.ispkg or hasattr(importlib.import_module(module.name), "__all__"):
            found.append(module.name)
    return found


def documented():
    return DIRECTIVE.findall(PAGE.read_text(encoding="utf-8"))


def test_the_walk_finds_the_modules_of_every_layer():
    modules = public_modules()
    for expected in ("fretting.cli", "fretting.models", "fretting.models.galerkin.mesh", "fretting.results.tables"):
        assert expected in modules
    assert "fretting.loading" not in modules and "fretting._validate" not in modules


@pytest.mark.parametrize("module", public_modules())
def test_every_public_module_has_an_entry(module):
    """The module itself, or a name of it that is not a module (``::: fretting.models.galerkin.Mesh``)."""
    entries, modules = documented(), public_modules()
    of_it = [
        entry for entry in entries if entry == module or entry.rsplit(".", 1)[0] == module and entry not in modules
    ]
    assert of_it, f"docs/api.md has no '::: {module}' (nor '::: {module}.NAME')"


def test_a_module_left_out_is_found(monkeypatch):
    entries = [entry for entry in documented() if entry != "fretting.results.tables"]
    monkeypatch.setitem(globals(), "documented", lambda: entries)
    with pytest.raises(AssertionError, match="no '::: fretting.results.tables'"):
        test_every_public_module_has_an_entry("fretting.results.tables")
