"""Every dotted name ``fretting.xxx.yyy`` written in backticks in the docs and the README imports.

A name is found in an inline code span (```fretting.engine.runner.run_file```, also inside a
longer span such as ```fretting.save(result, path)```) of ``docs/**/*.md`` and ``README.md``;
fenced code blocks are examples, not names, and are left out, as is ``CHANGELOG.md``, which
records what the names were. A name imports if it is a module, an attribute of a module, or an
attribute of a class (a method, a class attribute, or a field of a dataclass or named tuple).
One test per page, so that a failure says which page to fix.
"""

import dataclasses
import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted((ROOT / "docs").rglob("*.md")) + [p for p in [ROOT / "README.md"] if p.is_file()]

FENCE = re.compile(r"^[ \t]*(`{3,}|~{3,}).*?^[ \t]*\1", re.MULTILINE | re.DOTALL)
SPAN = re.compile(r"(`+)(.+?)(?<!`)\1(?!`)", re.DOTALL)
NAME = re.compile(r"(?<![\w./-])fretting(?:\.[A-Za-z_]\w*)+")


def names(text):
    """[(line, name)] of the dotted names in the inline code spans of a Markdown text."""
    text = FENCE.sub(lambda block: "\n" * block.group(0).count("\n"), text)  # keep the line numbers
    found = []
    for span in SPAN.finditer(text):
        for name in NAME.finditer(span.group(2)):
            found.append((text.count("\n", 0, span.start(2) + name.start()) + 1, name.group(0)))
    return found


def has_attribute(owner, name):
    if hasattr(owner, name):
        return True
    if isinstance(owner, type):  # fields without a class-level value
        if dataclasses.is_dataclass(owner) and name in {f.name for f in dataclasses.fields(owner)}:
            return True
        return any(name in getattr(base, "__annotations__", {}) for base in owner.__mro__)
    return False


def why_not(name):
    """None if `name` imports, else why not."""
    parts = name.split(".")
    for end in range(len(parts), 0, -1):
        module_name = ".".join(parts[:end])
        try:
            owner = importlib.import_module(module_name)
        except ModuleNotFoundError as error:
            if error.name is not None and module_name.startswith(error.name) and error.name.startswith("fretting"):
                continue  # not a module: an attribute of a shorter prefix
            return f"importing {module_name} fails: {error!r}"
        break
    for depth, attribute in enumerate(parts[end:], start=end):
        if not has_attribute(owner, attribute):
            return f"{'.'.join(parts[:depth])} has no attribute {attribute!r}"
        owner = getattr(owner, attribute, None)
    return None


def test_the_pages_are_there():
    """The docs sit beside the tests (in the checkout, the sdist, and CI's copy of the tests)."""
    assert ROOT / "README.md" in PAGES and len(PAGES) > 10, f"docs/ and README.md not found beside {ROOT / 'tests'}"


@pytest.mark.parametrize("page", PAGES, ids=lambda page: page.relative_to(ROOT).as_posix())
def test_dotted_names_import(page):
    found = names(page.read_text(encoding="utf-8"))
    failures = {f"{line}: `{name}`: {reason}" for line, name in found if (reason := why_not(name)) is not None}
    where = page.relative_to(ROOT).as_posix()
    assert not failures, f"{where}: names that do not import:\n" + "\n".join(
        sorted(failures, key=lambda text: int(text.split(":")[0]))
    )
