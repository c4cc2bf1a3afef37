"""The layer rules of the architecture page hold in the code: no import upward, no cycle.

The rules are read from the "Layers" table of ``docs/developer/architecture.md``, so that this
test follows the table when it is rewritten. How the table is read:

- Each row is a layer. Its "package" cell names one or more packages (```fretting.xxx``` in
  backticks); its "depends on" cell names what they build on: packages of the table
  (``physics``, ``fretting.models``, ``models.base`` for the row holding it), outside libraries
  (numpy: not checked here), or "everything above" (every earlier row).
- The table lists the layers from the bottom up ("arrows point down the table"): a layer is above
  every earlier row, and above the rows its "depends on" cell names even where the table lists
  them later (the engine depends on ``results``, listed after it). The order of the layers is the
  table's order with each row moved just after the rows it depends on.
- A module belongs to the package of the table whose name is the longest prefix of its own
  (``fretting.models.galerkin.mesh`` to ``fretting.models.galerkin`` if a row names it, else to
  ``fretting.models``).

The rules:

- A module may import its own package, the packages of its own row, and the layers below its
  own: no arrow up.
- Every import counts: at the top of a module, inside a function (made when it is called), and
  under ``if TYPE_CHECKING:``. An annotation that names a class of a layer above is an arrow up all
  the same: the module cannot be read, type-checked or moved without that layer. An import under
  ``TYPE_CHECKING`` is allowed only downward, like any other.
- Modules in no row of the table (the facade ``fretting/__init__.py``, ``__main__``, ``errors``,
  ``_validate``, and the top-level modules the table does not place) are not layers: importing
  one counts as making the imports it makes, transitively. ``errors``, which imports nothing of
  ``fretting``, may be imported from anywhere; a module that imports the facade (``import
  fretting``, ``from fretting import __version__``) imports every layer the facade loads. That
  importing ``fretting.physics.contact`` runs ``fretting/__init__.py`` first is Python's doing, not
  an arrow, and does not count.
- No cycle between packages: the imports between the table's packages and the modules in no row
  form no cycle (the packages of one row may import each other, but not both ways).
"""

from __future__ import annotations

import ast
import heapq
import re
from dataclasses import dataclass
from itertools import pairwise
from pathlib import Path

import pytest

import fretting

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "developer" / "architecture.md"
#: The package as imported: the source tree, or the installed wheel (CI).
SOURCE = Path(fretting.__file__).resolve().parent
WHERE = "the Layers table of docs/developer/architecture.md"


@dataclass(frozen=True)
class Row:
    index: int  #: position in the table, from 0
    packages: tuple[str, ...]  #: dotted names, e.g. ("fretting.plots", "fretting.cli")
    depends_on: str  #: the cell as written


@dataclass(frozen=True)
class Import:
    importer: str  #: dotted name of the importing module
    target: str  #: dotted name of the module imported (a module of `fretting`)
    line: int
    where: str  #: "", "inside a function" or "under TYPE_CHECKING"

    def site(self):
        path = modules()[self.importer].relative_to(SOURCE.parent)
        return f"{self.importer} ({path}:{self.line}{', ' + self.where if self.where else ''})"


# -- the table ---------------------------------------------------------------------------------


def cells(line):
    return [cell.strip() for cell in re.split(r"(?<!\\)\|", line.strip().strip("|"))]  # not at a \|


def read_table(text):
    """The rows of the first table after a heading that says "Layers"."""
    lines = text.splitlines()
    start = next((i for i, line in enumerate(lines) if re.match(r"#+\s.*\blayers\b", line, re.IGNORECASE)), None)
    assert start is not None, f"{PAGE.name}: no heading that says 'Layers'"
    level = len(lines[start]) - len(lines[start].lstrip("#"))
    table = []
    for line in lines[start + 1 :]:
        heading = re.match(r"(#+)\s", line)
        if heading and len(heading.group(1)) <= level:
            break
        if line.lstrip().startswith("|"):
            table.append(line)
        elif table:
            break
    assert len(table) >= 3, f"{PAGE.name}: no table under the 'Layers' heading"
    header = [cell.lower() for cell in cells(table[0])]
    package_column = next((i for i, cell in enumerate(header) if cell.startswith("package")), None)
    if package_column is None:
        package_column = next((i for i, cell in enumerate(header) if "package" in cell), None)
    depends_column = next((i for i, cell in enumerate(header) if "depend" in cell), None)
    assert package_column is not None and depends_column is not None, (
        f"{WHERE}: no column 'package' and 'depends on' in its header {cells(table[0])}"
    )
    rows = []
    for line in table[2:]:  # past the header and the |---| line
        row = cells(line)
        spans = re.findall(r"`([^`]+)`", row[package_column])
        names = [re.sub(r"[/.]+", ".", name).strip(".") for name in spans if re.match(r"fretting\b", name)]
        assert names, f"{WHERE}: the row {line.strip()!r} names no package (`fretting.xxx` in backticks)"
        rows.append(Row(len(rows), tuple(names), row[depends_column] if depends_column < len(row) else ""))
    return rows


def owner_among(packages, module):
    """The package of `packages` whose name is the longest prefix of `module`, or None."""
    found = [p for p in packages if module == p or module.startswith(p + ".")]
    return max(found, key=len, default=None)


def declared(rows):
    """{row index: indices of the rows its "depends on" cell names}."""
    packages = {package: row.index for row in rows for package in row.packages}
    result = {}
    for row in rows:
        cell = re.sub(r"\([^)]*\)", " ", row.depends_on.replace("`", ""))
        depends = set()
        for token in re.split(r",|;|\band\b", cell):
            token = token.strip().strip(".").strip()
            if re.search(r"\b(everything|all)\b.*\babove\b", token, re.IGNORECASE):
                depends.update(range(row.index))
                continue
            if not re.fullmatch(r"[A-Za-z_][\w./]*", token):
                continue  # prose or a dash: names no package
            name = re.sub(r"[/.]+", ".", token).strip(".")
            name = name if name.split(".")[0] == "fretting" else f"fretting.{name}"
            package = owner_among(packages, name)
            if package is not None:
                depends.add(packages[package])
            elif module_exists(name):
                pytest.fail(
                    f"{WHERE}: the row of {', '.join(row.packages)} depends on {token!r}, "
                    f"a part of fretting that no row of the table places"
                )
            # else an outside library (numpy, xarray): not checked here
        depends.discard(row.index)
        result[row.index] = depends
    return result


def layer_order(rows):
    """The rows from the bottom up: the table's order, each row just after what it depends on."""
    depends = declared(rows)
    order, placed = [], set()
    waiting = [row.index for row in rows]
    heapq.heapify(waiting)
    while waiting:
        ready = [i for i in waiting if depends[i] <= placed]
        if not ready:
            stuck = ", ".join(" and ".join(rows[i].packages) for i in sorted(waiting))
            pytest.fail(f"{WHERE} contradicts itself: its 'depends on' column makes a cycle among {stuck}")
        first = min(ready)
        waiting.remove(first)
        heapq.heapify(waiting)
        order.append(first)
        placed.add(first)
    return order


# -- the code ----------------------------------------------------------------------------------

_modules = {}


def modules():
    """{dotted name: path} of every module of the package."""
    if not _modules:
        for path in sorted(SOURCE.rglob("*.py")):
            parts = path.relative_to(SOURCE.parent).with_suffix("").parts
            name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
            _modules[name] = path
    return _modules


def module_exists(name):
    return name in modules()


def containing_module(name):
    """The longest prefix of `name` that is a module of the package."""
    parts = name.split(".")
    for end in range(len(parts), 0, -1):
        if ".".join(parts[:end]) in modules():
            return ".".join(parts[:end])
    return None


class _Imports(ast.NodeVisitor):
    def __init__(self, module, is_package):
        self.module, self.is_package = module, is_package
        self.found, self.context = [], []

    def _add(self, target, node):
        target = containing_module(target) if target.split(".")[0] == "fretting" else None
        if target is not None:
            where = next((c for c in reversed(self.context) if c == "under TYPE_CHECKING"), None)
            where = where or (self.context[-1] if self.context else "")
            self.found.append(Import(self.module, target, node.lineno, where))

    def visit_If(self, node):
        test = ast.unparse(node.test)
        if test in ("TYPE_CHECKING", "typing.TYPE_CHECKING"):
            self.context.append("under TYPE_CHECKING")
            for child in node.body:
                self.visit(child)
            self.context.pop()
            for child in node.orelse:
                self.visit(child)
        else:
            self.generic_visit(node)

    def _function(self, node):
        self.context.append("inside a function")
        self.generic_visit(node)
        self.context.pop()

    visit_FunctionDef = visit_AsyncFunctionDef = visit_Lambda = _function

    def visit_Import(self, node):
        for alias in node.names:
            self._add(alias.name, node)

    def visit_ImportFrom(self, node):
        if node.level:
            package = self.module.split(".") if self.is_package else self.module.split(".")[:-1]
            base = ".".join(package[: len(package) - node.level + 1] + ([node.module] if node.module else []))
        else:
            base = node.module
        for alias in node.names:
            submodule = f"{base}.{alias.name}"
            self._add(submodule if submodule in modules() else base, node)


_imports = {}


def imports():
    """{module: its imports of modules of the package}, from the source with `ast`."""
    if not _imports:
        for module, path in modules().items():
            visitor = _Imports(module, path.name == "__init__.py")
            visitor.visit(ast.parse(path.read_text(encoding="utf-8"), str(path)))
            unique = {(i.target, i.line): i for i in visitor.found if i.target != module}  # one per statement
            _imports[module] = list(unique.values())
    return _imports


# -- the rules ---------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def rows():
    assert PAGE.is_file(), f"{PAGE}: not found (the test reads the layer rules from it)"
    rows = read_table(PAGE.read_text(encoding="utf-8"))
    named = [package for row in rows for package in row.packages]
    assert len(named) == len(set(named)), f"{WHERE}: a package is named in two rows: {named}"
    missing = [package for package in named if not module_exists(package)]
    assert not missing, f"{WHERE} names {', '.join(missing)}, which {SOURCE} does not hold"
    return rows


def test_the_table_is_read(rows):
    """The table names packages of the package, and its "depends on" column makes no cycle."""
    assert len(rows) >= 2
    assert len(layer_order(rows)) == len(rows)


def reached(module, packages, seen=None):
    """[(package, chain)]: the packages of the table an import of `module` makes, through the
    modules in no row; `chain` is the list of imports from `module` on."""
    owner = owner_among(packages, module)
    if owner is not None:
        return [(owner, [])]
    seen = set() if seen is None else seen
    if module in seen:
        return []
    seen.add(module)
    result = []
    for imported in imports()[module]:
        result += [(package, [imported, *chain]) for package, chain in reached(imported.target, packages, seen)]
    return result


def test_no_import_upward(rows):
    order = layer_order(rows)
    rank = {package: order.index(row.index) for row in rows for package in row.packages}
    row_of = {package: row for row in rows for package in row.packages}
    below = " < ".join(" & ".join(rows[i].packages) for i in order)
    errors = []
    for module, found in imports().items():
        mine = owner_among(rank, module)
        if mine is None:
            continue  # a module in no row: counted where it is imported
        for made in found:
            for package, chain in reached(made.target, rank):
                if package == mine or package in row_of[mine].packages or rank[package] < rank[mine]:
                    continue
                via = "".join(f", which imports {step.target} ({step.site().split(' (', 1)[1]}" for step in chain)
                allowed = sorted(p for p in rank if rank[p] < rank[mine] or p in row_of[mine].packages and p != mine)
                errors.append(
                    f"{made.site()} imports {made.target}{via}: {package} is a layer above {mine} in {WHERE} "
                    f"(layers from the bottom up: {below}); {mine} may import "
                    f"{'only ' + ', '.join(allowed) if allowed else 'no other package of fretting'}"
                )
    assert not errors, "import upward:\n" + "\n".join(errors)


def test_no_cycle_between_packages(rows):
    packages = [package for row in rows for package in row.packages]

    def node(module):
        return owner_among(packages, module) or module

    edges = {}  # {(from, to): the first import that makes the arrow}
    for module, found in imports().items():
        for made in found:
            a, b = node(module), node(made.target)
            if a != b:
                edges.setdefault((a, b), made)
    successors = {}
    for a, b in edges:
        successors.setdefault(a, set()).add(b)

    def path(start, goal):
        """Shortest list of nodes from start to goal, or None."""
        paths, seen = [[start]], {start}
        while paths:
            current = paths.pop(0)
            for nxt in sorted(successors.get(current[-1], ())):
                if nxt == goal:
                    return current + [nxt]
                if nxt not in seen:
                    seen.add(nxt)
                    paths.append(current + [nxt])
        return None

    cycles, reported = [], set()
    for start in sorted(successors):
        cycle = path(start, start)
        if cycle and frozenset(cycle) not in reported:
            reported.add(frozenset(cycle))
            steps = [f"{a} -> {b} ({edges[a, b].site()} imports {edges[a, b].target})" for a, b in pairwise(cycle)]
            cycles.append("\n  ".join(steps))
    assert not cycles, f"import cycle between packages (rules of {WHERE}):\n  " + "\n\n  ".join(cycles)
