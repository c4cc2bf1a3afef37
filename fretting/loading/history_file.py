"""History files: a contact and a load history written in TOML (format: docs/guide/histories.md).

Every value is checked here, at the boundary, and every problem raises `HistoryFileError`
naming the file, the line where it can be found, the key, what was found and what was expected.
"""

from __future__ import annotations

import csv
import hashlib
import math
import os
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fretting.errors import HistoryError
from fretting.loading.history import RAMP_STEPS, History, PiecewiseLinear
from fretting.physics.contact import POISSON_RANGE, SPECIMEN, Contact, plane_strain_modulus
from fretting.physics.profiles import FlatPunch, Gap, Hertz, RoundedFlat

__all__ = ["HistoryFileError", "HistorySource", "read_history", "read_history_data", "read_history_source"]

#: Keys of the [contact] table besides those of the profile.
CONTACT_KEYS = ("profile", "E_star", "E", "nu", "f", "P", "specimen", "datum", "compliance")

#: Largest table file (`csv` blocks, tabulated profiles) read [bytes]: a device, a pipe or a file
#: larger than this would hang the run or fill the memory before any error could be said.
MAX_TABLE_BYTES = 2**30

#: Default steps per segment of a `linear` block, and of a `csv` block: one row, one step.
LINEAR_STEPS, CSV_STEPS = 16, 1


class HistoryFileError(HistoryError):
    """A history file, or a table it names, is malformed.

    Attributes
    ----------
    path : pathlib.Path
        The file at fault.
    line : int or None
        Its line (from 1) where the problem is, when known.
    key : str or None
        The key at fault, e.g. ``loading[2].Q_amplitude`` (blocks counted from 1).
    problem : str
        What was found and what was expected.
    """

    def __init__(self, path, line, key, problem):
        self.path, self.line, self.key, self.problem = path, line, key, problem
        where = f"{path}:{line}" if line else f"{path}"
        super().__init__(f"{where}: {key}: {problem}" if key else f"{where}: {problem}")


@dataclass(frozen=True, eq=False)
class HistorySource:
    """A history file, read and checked.

    Attributes
    ----------
    path : pathlib.Path
    text : str
        The file's text.
    sha256 : str
        Hex digest of the file's bytes.
    contact : Contact
    history : History
    """

    path: Path
    text: str
    sha256: str
    contact: Contact
    history: History


def read_history(path: str | os.PathLike) -> tuple[Contact, History]:
    """Contact and load history of a history file.

    Parameters
    ----------
    path : str or os.PathLike
        TOML file; the tables it names are read next to it.

    Returns
    -------
    contact : Contact
    history : History
        Starts unloaded, at step 0, and follows the ``[[loading]]`` blocks in order.

    Raises
    ------
    OSError
        When the file cannot be read.
    HistoryFileError
        When its content is malformed.

    Examples
    --------
    >>> from fretting.loading.examples import example_path
    >>> contact, history = read_history(example_path("hertz_shear_cycling"))
    >>> contact.profile, history.start, history.cycle_count
    (Hertz(R=0.05), (0.0, 0.0), 5)
    """
    source = read_history_source(path)
    return source.contact, source.history


def read_history_source(path):
    """`HistorySource` of the file at `path` (raises as `read_history`)."""
    path = Path(path)
    data = path.read_bytes()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise HistoryFileError(path, None, None, f"found byte {data[error.start]:#x}, expected UTF-8 text") from None
    contact, history = _Document(path, text).read()
    return HistorySource(path, text, hashlib.sha256(data).hexdigest(), contact, history)


def read_history_data(path, text, data, tables=None):
    """Contact and load history of `data`: the TOML `text` of the history file at `path`, parsed and possibly changed.

    Checked as `read_history` checks a file; errors name `path` and the line of the key in `text`,
    and tables named by `data` are read next to `path`. The path of each table file read is
    appended to the list `tables`, when given (what a sweep's case depends on besides `data`).
    """
    return _Document(path, text, data, tables).read()


class _Document:
    """The parsed TOML of one file, with the line of every key written on a line of its own.

    `data` is `text` already parsed (and possibly changed); when None, `text` is parsed here. The
    path of each table file read is appended to `tables`.
    """

    def __init__(self, path, text, data=None, tables=None):
        self.path = path
        try:
            self.data = tomllib.loads(text) if data is None else data
        except tomllib.TOMLDecodeError as error:
            line = re.search(r"at line (\d+)", str(error))
            raise HistoryFileError(path, int(line[1]) if line else None, None, f"TOML syntax: {error}") from None
        self.lines = _key_lines(text)
        self.tables = [] if tables is None else tables

    def read(self):
        top = _Table(self, (), self.data)
        top.reject_unknown(("contact", "loading"))
        contact = _contact(top.table("contact"))
        if "loading" not in self.data:
            raise self.error((), "found no [[loading]] blocks, expected at least one")
        history = _sequence(top.tables("loading"), start=(0.0, 0.0, contact.P, 0.0))
        if history.displaced and contact.datum is None:
            raise self.error(
                ("contact",), "the loading prescribes delta, expected a datum L (key 'datum') to measure it at"
            )
        return contact, history.without_P(contact.P)  # the contact's constant P: the history of Q and sigma alone

    def error(self, path, problem):
        """`HistoryFileError` at the key `path` (a tuple of names and indices)."""
        located = next((self.lines[path[:n]] for n in range(len(path), 0, -1) if path[:n] in self.lines), None)
        key = "".join(f"[{part + 1}]" if isinstance(part, int) else f".{part}" for part in path).lstrip(".")
        return HistoryFileError(self.path, located, key or None, problem)


_REQUIRED = object()


class _Table:
    """One TOML table at `path` in `document`, read key by key."""

    def __init__(self, document, path, data):
        self.document, self.path, self.data = document, path, data

    def error(self, key, problem):
        return self.document.error(self.path + ((key,) if key else ()), problem)

    def reject_unknown(self, allowed):
        for key in self.data:
            if key not in allowed:
                raise self.error(key, f"unknown key, expected one of: {', '.join(allowed)}")

    def get(self, key, convert, default=_REQUIRED):
        """``convert(value)`` of `key`, or `default` when absent (required when no default)."""
        if key not in self.data:
            if default is _REQUIRED:
                raise self.error(None, f"missing key '{key}'")
            return default
        value = self.data[key]
        try:
            return convert(value)
        except _Expected as expected:
            raise self.error(key, f"found {_show(value)}, expected {expected}") from None

    def table(self, key):
        return _Table(self.document, self.path + (key,), self.get(key, _mapping))

    def tables(self, key):
        return [_Table(self.document, self.path + (key, n), data) for n, data in enumerate(self.get(key, _mappings))]

    def file(self, key):
        """Path of the file named by `key`, relative to the history file's directory."""
        path = self.document.path.parent / self.get(key, _text)
        self.document.tables.append(path)
        return path


def _contact(table):
    name = table.get("profile", _choice(PROFILES))
    keys, read_profile = PROFILES[name]
    table.reject_unknown(CONTACT_KEYS + keys)
    if "E_star" in table.data and ("E" in table.data or "nu" in table.data):
        raise table.error("E_star", "found E_star with E or nu, expected either E_star or both E and nu")
    nu = None
    if "E_star" in table.data:
        E_star = table.get("E_star", _positive)
    elif "E" in table.data or "nu" in table.data:
        E, nu = table.get("E", _positive), table.get("nu", _poisson)
        E_star = plane_strain_modulus(E, nu)
    else:
        raise table.error(None, "missing key 'E_star', expected E_star or both E and nu")
    profile, f, P = read_profile(table), table.get("f", _positive), table.get("P", _positive)
    specimen = table.get("specimen", _choice((1, 2)), SPECIMEN)
    datum, compliance = table.get("datum", _positive, None), table.get("compliance", _non_negative, 0.0)
    if compliance and datum is None:
        raise table.error("compliance", "found a rig compliance without a datum, expected a datum L (key 'datum')")
    try:
        contact = Contact(profile, E_star, f, P, specimen, nu)
    except ValueError as error:
        key = "table" if isinstance(profile, Gap) else None
        raise table.error(key, f"found no admissible contact for this profile and load: {error}") from None
    if datum is None:
        return contact
    if not datum > contact.a:
        raise table.error("datum", f"found {_show(datum)}, expected a distance L > a = {contact.a:.6g} m")
    return Contact(profile, E_star, f, P, specimen, nu, datum=datum, compliance=compliance)


def _gap(table):
    path = table.file("table")
    columns = _read_columns(table, "table", path, ("x", "h0"), all_required=True)
    x, h0 = columns["x"], columns["h0"]
    if x.size < 4:
        raise table.error("table", f"{path}: found {x.size} rows, expected at least 4")
    back = np.flatnonzero(np.diff(x) <= 0)
    if back.size:
        k = back[0]
        raise table.error("table", f"{path}: found x = {x[k + 1]:.6g} after {x[k]:.6g}, expected x increasing")
    return Gap.from_table(x, h0, table.get("breakpoints", _numbers, default=None))


#: profile name -> (its keys, reader of the profile from the [contact] table).
PROFILES = {
    "hertz": (("R",), lambda table: Hertz(table.get("R", _positive))),
    "rounded_flat": (("b", "R"), lambda table: RoundedFlat(table.get("b", _positive), table.get("R", _positive))),
    "flat": (("a",), lambda table: FlatPunch(table.get("a", _positive))),
    "gap": (("table", "breakpoints"), _gap),
}


def _sequence(tables, start):
    """History from `start` ``(Q, sigma, P, delta)`` through the blocks of `tables` in order."""
    histories = []
    for table in tables:
        kind = table.get("kind", _choice(BLOCKS))
        keys, build = BLOCKS[kind]
        table.reject_unknown(("kind", *keys))
        if np.isnan(start[0]) and kind not in ("linear", "repeat"):
            raise table.error(
                "kind", f"found a {kind} block of Q after a block of delta, expected a linear block of delta"
            )
        histories.append(build(table, start))
        start = _end(histories[-1])
    return History.concatenate(histories)


def _end(history):
    """``(Q, sigma, P, delta)`` at the last step of `history`: ``Q`` NaN where it prescribes ``delta``,
    ``delta`` None where it prescribes ``Q`` (not known before the run)."""
    delta = float(history.delta[-1]) if history.displaced else None
    return (*history.end, history.normal_end, delta)


def _linear(table, start):
    loads = [table.get(name, _numbers, None) for name in LOADS]
    delta = table.get("delta", _numbers, None)
    if delta is not None and loads[0] is not None:
        raise table.error("delta", "found both Q and delta, expected the vertices of one of them")
    if delta is None and np.isnan(start[0]):
        raise table.error(None, "found neither Q nor delta after a block of delta, expected the vertices of delta")
    if delta is None:
        return _polyline(table, loads, start[:3], LINEAR_STEPS)
    if start[3] is None:
        raise table.error(
            "delta", "found delta after a block of Q, whose delta is not known before the run; expected Q"
        )
    return _polyline(table, [delta, *loads[1:]], (start[3], *start[1:3]), LINEAR_STEPS).explicit().displacements()


def _series(table, start):
    path = table.file("file")
    columns = _read_columns(table, "file", path, LOADS, all_required=False)
    return _polyline(table, [columns.get(name) for name in LOADS], start[:3], CSV_STEPS)


def _polyline(table, loads, start, default_steps):
    """Straight segments from `start` through the vertices `loads` (of `LOADS`); an absent one holds its value."""
    given = [(name, values) for name, values in zip(LOADS, loads, strict=True) if values is not None]
    if not given:
        raise table.error(None, "missing key 'Q', 'sigma' or 'P', expected the vertices of at least one")
    first, n = given[0][0], len(given[0][1])
    for name, other in given[1:]:
        if len(other) != n:
            raise table.error(name, f"found {len(other)} values, expected one for each of the {n} values of {first}")
    vertices = [
        np.concatenate([[held], np.full(n, held) if values is None else values])
        for held, values in zip(start, loads, strict=True)
    ]
    steps = table.get("steps_per_segment", _counts, default_steps)
    if np.ndim(steps) and len(steps) != n:
        raise table.error("steps_per_segment", f"found {len(steps)} values, expected one for each of the {n} vertices")
    history = PiecewiseLinear.through(*vertices[:2], steps, vertices[2])
    return history.as_cycle() if table.get("cycle", _boolean, False) else history


def _sine(table, start):
    return History.sinusoidal(
        table.get("Q_amplitude", _non_negative, 0.0),
        table.get("sigma_amplitude", _non_negative, 0.0),
        table.get("phase_deg", _number, 0.0),
        table.get("cycles", _count, 1),
        table.get("steps_per_cycle", _count_from(4), 64),
        table.get("Q_mean", _number, 0.0),
        table.get("sigma_mean", _number, 0.0),
        start=start[:3],
        ramp_steps=table.get("ramp_steps", _count, RAMP_STEPS),
        P_amplitude=table.get("P_amplitude", _non_negative, 0.0),
        P_mean=table.get("P_mean", _positive, start[2]),
        P_phase_deg=table.get("P_phase_deg", _number, 0.0),
        by_cycle=True,
    )


def _random(table, start):
    return History.random_amplitude(
        table.get("cycles", _count),
        table.get("Q_amplitude", _non_negative, 0.0),
        table.get("sigma_amplitude", _non_negative, 0.0),
        table.get("Q_mean", _number, 0.0),
        table.get("sigma_mean", _number, 0.0),
        table.get("seed", _count_from(0)),
        table.get("steps_per_segment", _count, LINEAR_STEPS),
        start=start[:3],
        P_amplitude=table.get("P_amplitude", _non_negative, 0.0),
        P_mean=table.get("P_mean", _positive, start[2]),
        vertices=True,
    )


def _repeat(table, start):
    count, blocks = table.get("count", _count), table.tables("blocks")
    histories = []
    for _ in range(count):
        histories.append(_sequence(blocks, start))
        start = _end(histories[-1])
    return History.concatenate(histories)


#: The loads a block may give the vertices (or columns) of; an absent one holds its value.
LOADS = ("Q", "sigma", "P")

#: block kind -> (its keys besides `kind`, builder of its history from the table and the start ``(Q, sigma, P)``).
BLOCKS = {
    "linear": (("Q", "delta", "sigma", "P", "steps_per_segment", "cycle"), _linear),
    "csv": (("file", "steps_per_segment", "cycle"), _series),
    "sine": (
        (
            "Q_amplitude",
            "sigma_amplitude",
            "phase_deg",
            "cycles",
            "steps_per_cycle",
            "Q_mean",
            "sigma_mean",
            "ramp_steps",
            "P_amplitude",
            "P_mean",
            "P_phase_deg",
        ),
        _sine,
    ),
    "random": (
        (
            "cycles",
            "Q_amplitude",
            "sigma_amplitude",
            "Q_mean",
            "sigma_mean",
            "seed",
            "steps_per_segment",
            "P_amplitude",
            "P_mean",
        ),
        _random,
    ),
    "repeat": (("count", "blocks"), _repeat),
}


def _read_columns(table, key, path, names, all_required):
    """Columns of the CSV file at `path`, named by `key` of `table`, by column name.

    The file holds a header row naming the columns (all of `names`, or any of them), then rows
    of numbers; rows starting with ``#`` are comments.
    """
    try:
        size = os.stat(path).st_size
        if not os.path.isfile(path) or size > MAX_TABLE_BYTES:
            found = "not a regular file" if not os.path.isfile(path) else f"{size} bytes"
            raise table.error(key, f"{path} is {found}, expected a regular file of at most {MAX_TABLE_BYTES} bytes")
        with open(path, newline="", encoding="utf-8-sig") as handle:  # a spreadsheet's "CSV UTF-8" starts with a BOM
            rows = [(n, [cell.strip() for cell in row]) for n, row in enumerate(csv.reader(handle), start=1)]
    except (OSError, UnicodeDecodeError) as error:
        raise table.error(key, f"cannot read {path}: {getattr(error, 'strerror', None) or error}") from None
    rows = [(n, row) for n, row in rows if row and not row[0].startswith("#")]
    expected = f"{'the' if all_required else 'one or more of the'} columns {', '.join(names)}"
    if not rows:
        raise HistoryFileError(path, None, None, f"found no header row, expected one naming {expected}")
    line, header = rows[0]
    if not set(header) <= set(names) or len(set(header)) < len(header) or (all_required and len(header) < len(names)):
        raise HistoryFileError(path, line, None, f"found columns {', '.join(header)}, expected {expected}")
    if len(rows) == 1:
        raise HistoryFileError(path, line, None, "found no data rows, expected a row of numbers after the header")
    values = np.empty((len(rows) - 1, len(header)))
    for index, (line, row) in enumerate(rows[1:]):
        if len(row) != len(header):
            raise HistoryFileError(path, line, None, f"found {len(row)} values, expected {len(header)}")
        for column, (name, cell) in enumerate(zip(header, row, strict=True)):
            try:
                values[index, column] = _number(float(cell))
            except (ValueError, _Expected):
                raise HistoryFileError(path, line, name, f"found {cell!r}, expected a finite number") from None
    return dict(zip(header, values.T, strict=True))


def _key_lines(text):
    """Line of each table header and of each key written as ``key = ...``, by key path.

    Key paths are tuples of names and array-of-table indices, e.g. ``("loading", 2, "Q")``.
    Keys inside inline tables are not located; their errors point at the enclosing key.
    """
    lines, counts, table = {}, {}, ()
    for number, line in enumerate(text.splitlines(), start=1):
        header = _HEADER.match(line)
        key = _KEY.match(line)
        if header:
            table = _table_path(header["name"], header["open"] == "[[", counts)
            lines.setdefault(table, number)
        elif key:
            lines.setdefault(table + (key["key"].strip("\"'"),), number)
    return lines


_HEADER = re.compile(r"^\s*(?P<open>\[\[?)\s*(?P<name>[\w\-.\"' ]+?)\s*\]\]?\s*(#.*)?$")
_KEY = re.compile(r"^\s*(?P<key>[\w-]+|\"[^\"]*\"|'[^']*')\s*=")


def _table_path(name, is_array, counts):
    """Key path of a table header; `counts` holds the tables seen so far of each array of tables."""
    parts = [part.strip().strip("\"'") for part in name.split(".")]
    path = ()
    for part in parts[:-1]:
        path += (part,)
        if path in counts:
            path += (counts[path] - 1,)
    path += (parts[-1],)
    if is_array:
        counts[path] = counts.get(path, 0) + 1
        path += (counts[path] - 1,)
    return path


class _Expected(Exception):
    """A value is not what its key needs; the message says what is expected."""


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _number(value):
    if not _is_number(value):
        raise _Expected("a finite number")
    return float(value)


def _positive(value):
    if not (_is_number(value) and value > 0):
        raise _Expected("a number > 0")
    return float(value)


def _non_negative(value):
    if not (_is_number(value) and value >= 0):
        raise _Expected("a number >= 0")
    return float(value)


def _poisson(value):
    low, high = POISSON_RANGE
    if not (_is_number(value) and low < value <= high):
        raise _Expected(f"a Poisson ratio in ({low:g}, {high:g}]")
    return float(value)


def _count_from(minimum):
    def count(value):
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            raise _Expected(f"an integer >= {minimum}")
        return value

    return count


_count = _count_from(1)


def _counts(value):
    """An integer >= 1, or a non-empty list of them."""
    try:
        return [_count(item) for item in value] if isinstance(value, list) and value else _count(value)
    except _Expected:
        raise _Expected("an integer >= 1, or a list of them") from None


def _numbers(value):
    if not isinstance(value, list) or not value:
        raise _Expected("a list of numbers")
    try:
        return np.array([_number(item) for item in value])
    except _Expected:
        raise _Expected("a list of finite numbers") from None


def _boolean(value):
    if not isinstance(value, bool):
        raise _Expected("true or false")
    return value


def _text(value):
    if not isinstance(value, str) or not value:
        raise _Expected("a file name in quotes")
    return value


def _mapping(value):
    if not isinstance(value, dict):
        raise _Expected("a table")
    return value


def _mappings(value):
    if not isinstance(value, list) or not value or not all(isinstance(item, dict) for item in value):
        raise _Expected("at least one block, as [[...]] tables or a list of inline tables")
    return value


def _choice(options):
    def choose(value):
        if isinstance(value, bool) or not isinstance(value, type(next(iter(options)))) or value not in options:
            raise _Expected("one of " + ", ".join(_show(option) for option in options))
        return value

    return choose


def _show(value):
    """A TOML-like rendering of `value`, kept short."""
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, list):
        items = ", ".join(_show(item) for item in value[:4])
        return f"[{items}{', ...' if len(value) > 4 else ''}]"
    if isinstance(value, dict):
        return "a table"
    return repr(value)
