"""History files: a contact and a load history written in TOML (format: docs/guide/histories.md).

Every value is checked here, at the boundary, and every problem raises `HistoryFileError`
naming the file, the line where it can be found, the key, what was found and what was expected.
Values are SI unless the file says otherwise: a value written with its units (``R = "50 mm"``),
or a ``[units]`` table giving the units of its plain numbers (`UNIT_KINDS`); both are converted
to SI floats here, by pint (an optional dependency, needed only by a file that says units).
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

__all__ = [
    "HistoryFileError",
    "HistorySource",
    "read_history",
    "read_history_data",
    "read_history_source",
]

#: The kinds of quantity a history file's numbers are, each with its SI unit, in which plain numbers
#: are read unless the file's ``[units]`` table names another unit of that kind.
UNIT_KINDS = {"length": "m", "stress": "Pa", "line_load": "N/m", "compliance": "m^2/N"}

#: The kind (`UNIT_KINDS`) of each key of a history file that holds a dimensional quantity, and of
#: each column of the tables it names; angles are in degrees (``*_deg``), other keys are unit-free.
KEY_KINDS = {
    **dict.fromkeys(("R", "b", "a", "datum", "delta", "delta_amplitude", "delta_mean", "x", "h0"), "length"),
    **dict.fromkeys(("E", "E_star", "sigma", "sigma_amplitude", "sigma_mean"), "stress"),
    **dict.fromkeys(("P", "Q", "Q_amplitude", "Q_mean", "P_amplitude", "P_mean"), "line_load"),
    "compliance": "compliance",
}

#: The error of a file nested deeper than the reader can follow: ``repeat`` blocks, inline tables or
#: arrays within one another some hundreds of levels deep (each level is a call of the reader).
TOO_DEEP = "found tables nested deeper than can be read (repeat blocks within repeat blocks?), expected a few levels"

#: Keys whose value is an angle in degrees; a value with units (``"1.5 rad"``) is converted to them.
ANGLE_KEYS = ("phase_deg", "P_phase_deg")

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
    contact, history = read_history_data(path, text, None)
    return HistorySource(path, text, hashlib.sha256(data).hexdigest(), contact, history)


def read_history_data(path, text, data, tables=None):
    """Contact and load history of `data`: the TOML `text` of the history file at `path`, parsed and possibly changed.

    Checked as `read_history` checks a file; errors name `path` and the line of the key in `text`,
    and tables named by `data` are read next to `path`. The path of each table file read is
    appended to the list `tables`, when given (what a sweep's case depends on besides `data`).
    """
    try:
        return _Document(path, text, data, tables).read()
    except RecursionError:  # blocks read into their nested blocks
        raise HistoryFileError(path, None, None, TOO_DEEP) from None


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
        except RecursionError:  # the TOML reader recurses into inline tables and arrays
            raise HistoryFileError(path, None, None, TOO_DEEP) from None
        self.lines = _key_lines(text)
        self.tables = [] if tables is None else tables
        self.units = {}  # kind -> (the unit of the file's plain numbers of that kind, its factor to SI)

    def read(self):
        top = _Table(self, (), self.data)
        top.reject_unknown(("contact", "loading", "units"))
        if "units" in self.data:
            self.units = _units(top.table("units"))
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
            return convert(self.in_si(key, value))
        except _Expected as expected:
            raise self.error(key, f"found {_show(value)}, expected {expected}") from None

    def in_si(self, key, value):
        """`value` of `key` in SI: each number with units converted, each plain number scaled by the
        file's ``[units]`` of its kind; unchanged for a key without units (`KEY_KINDS`)."""
        if isinstance(value, list):
            return [self.in_si(key, item) for item in value]
        if key in ANGLE_KEYS and isinstance(value, str):
            return _quantity(value, "deg", f'a number [deg], or an angle with units, e.g. "{_EXAMPLES["an angle"]}"')
        kind = KEY_KINDS.get(key)
        if kind is None:
            return value
        unit, factor = self.document.units.get(kind, (UNIT_KINDS[kind], None))
        if isinstance(value, str):
            expected = f'a number [{unit}], or a {_named(kind)} with units, e.g. "{_EXAMPLES[kind]}"'
            return _quantity(value, UNIT_KINDS[kind], expected)
        return value * factor if factor is not None and _is_number(value) else value

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
        histories.append(build(table, start))
        start = _end(histories[-1])
    return History.concatenate(histories)


def _end(history):
    """``(Q, sigma, P, delta)`` at the last step of `history`: ``Q`` NaN where it prescribes ``delta``,
    ``delta`` None where it prescribes ``Q`` (not known before the run)."""
    delta = float(history.delta[-1]) if history.displaced else None
    return (*history.end, history.normal_end, delta)


def _displaced(table, start, Q_key, delta_key, Q_given, delta_given, at=None):
    """True if the block `table` prescribes ``delta`` (`delta_key` given) rather than ``Q`` (`Q_key`), from
    `start` ``(Q, sigma, P, delta)``; a HistoryFileError naming the key `at` (default `delta_key`) where it
    gives both, neither after a block of ``delta``, or ``delta`` after a block of ``Q`` (whose ``delta`` is
    not known before the run)."""
    at = delta_key if at is None else at
    if delta_given and Q_given:
        raise table.error(at, f"found both {Q_key} and {delta_key}, expected one of them")
    if not delta_given and np.isnan(start[0]):
        raise table.error(None, f"found neither Q nor delta after a block of delta, expected {delta_key}")
    if delta_given and start[3] is None:
        raise table.error(
            at, f"found {delta_key} after a block of Q, whose delta is not known before the run; expected Q"
        )
    return delta_given


def _from(start, displaced):
    """The start ``(Q, sigma, P)`` of a block, its ``Q`` the ``delta`` reached where it prescribes ``delta``."""
    return (start[3], *start[1:3]) if displaced else start[:3]


def _moved(history, displaced):
    """`history` built as one of ``Q``, read as one of ``delta`` where the block prescribes it."""
    return history.explicit().displacements() if displaced else history


def _linear(table, start):
    loads = [table.get(name, _numbers, None) for name in LOADS]
    delta = table.get("delta", _numbers, None)
    displaced = _displaced(table, start, "Q", "delta", loads[0] is not None, delta is not None)
    loads[0] = delta if displaced else loads[0]
    return _moved(_polyline(table, loads, _from(start, displaced), LINEAR_STEPS), displaced)


def _series(table, start):
    path = table.file("file")
    columns = _read_columns(table, "file", path, (*LOADS, "delta"), all_required=False)
    displaced = _displaced(table, start, "column Q", "column delta", "Q" in columns, "delta" in columns, "file")
    loads = [columns.get("delta" if displaced and name == "Q" else name) for name in LOADS]
    return _moved(_polyline(table, loads, _from(start, displaced), CSV_STEPS), displaced)


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


def _tangential(table, start):
    """(prescribes delta, amplitude, mean) of the tangential load of a `sine` or `random` block: its
    ``Q_amplitude`` and ``Q_mean`` [N/m], or its ``delta_amplitude`` and ``delta_mean`` [m]."""
    given = {name: name in table.data for name in ("Q_amplitude", "Q_mean", "delta_amplitude", "delta_mean")}
    delta_key = "delta_mean" if given["delta_mean"] and not given["delta_amplitude"] else "delta_amplitude"
    Q_given = given["Q_amplitude"] or given["Q_mean"]
    delta_given = given["delta_amplitude"] or given["delta_mean"]
    displaced = _displaced(table, start, "Q_amplitude", delta_key, Q_given, delta_given)
    prefix = "delta" if displaced else "Q"
    return displaced, table.get(f"{prefix}_amplitude", _non_negative, 0.0), table.get(f"{prefix}_mean", _number, 0.0)


def _sine(table, start):
    displaced, amplitude, mean = _tangential(table, start)
    history = History.sinusoidal(
        amplitude,
        table.get("sigma_amplitude", _non_negative, 0.0),
        table.get("phase_deg", _number, 0.0),
        table.get("cycles", _count, 1),
        table.get("steps_per_cycle", _count_from(4), 64),
        mean,
        table.get("sigma_mean", _number, 0.0),
        start=_from(start, displaced),
        ramp_steps=table.get("ramp_steps", _count, RAMP_STEPS),
        P_amplitude=table.get("P_amplitude", _non_negative, 0.0),
        P_mean=table.get("P_mean", _positive, start[2]),
        P_phase_deg=table.get("P_phase_deg", _number, 0.0),
        by_cycle=True,
    )
    return _moved(history, displaced)


def _random(table, start):
    displaced, amplitude, mean = _tangential(table, start)
    history = History.random_amplitude(
        table.get("cycles", _count),
        amplitude,
        table.get("sigma_amplitude", _non_negative, 0.0),
        mean,
        table.get("sigma_mean", _number, 0.0),
        table.get("seed", _count_from(0)),
        table.get("steps_per_segment", _count, LINEAR_STEPS),
        start=_from(start, displaced),
        P_amplitude=table.get("P_amplitude", _non_negative, 0.0),
        P_mean=table.get("P_mean", _positive, start[2]),
        vertices=True,
    )
    return _moved(history, displaced)


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
            "delta_amplitude",
            "delta_mean",
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
            "delta_amplitude",
            "delta_mean",
            "P_amplitude",
            "P_mean",
        ),
        _random,
    ),
    "repeat": (("count", "blocks"), _repeat),
}


#: What a header row's cell must look like to be echoed in an error: a short name. A file that is
#: no table (a key file, the process environment) has its first line said, not shown.
_COLUMN = re.compile(r"[A-Za-z_]\w{0,31}")


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
        named = all(map(_COLUMN.fullmatch, header))
        found = f"columns {', '.join(header)}" if named else "a first row of no column names"
        raise HistoryFileError(path, line, None, f"found {found}, expected {expected}")
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
    units = table.document.units  # the file's [units] hold for its tables' columns too
    columns = dict(zip(header, values.T, strict=True))
    return {
        name: column * units[KEY_KINDS[name]][1] if KEY_KINDS[name] in units else column
        for name, column in columns.items()
    }


def _units(table):
    """Kind -> (unit, its factor to SI) of each kind (`UNIT_KINDS`) that the ``[units]`` table `table` gives."""
    table.reject_unknown(tuple(UNIT_KINDS))
    return {kind: (table.data[kind], table.get(kind, _unit_of(kind))) for kind in UNIT_KINDS if kind in table.data}


#: A value with units of each kind, as the errors show one.
_EXAMPLES = {
    "length": "50 mm",
    "stress": "200 MPa",
    "line_load": "30 kN/m",
    "compliance": "1e-9 m/(N/m)",
    "an angle": "90 deg",
}

#: The start of a number with units: a number.
_NUMBER = re.compile(r"\s*[-+]?(\d|\.\d)")


def _unit_of(kind):
    """Converter of a ``[units]`` entry: a unit of `kind` in quotes -> its factor to the SI unit."""

    def factor(text):
        expected = f'a unit of {_named(kind)} in quotes, e.g. "{_EXAMPLES[kind].split(" ", 1)[1]}"'
        if not isinstance(text, str) or _NUMBER.match(text):
            raise _Expected(expected)
        return _quantity(f"1 {text}", UNIT_KINDS[kind], expected)

    return factor


def _quantity(text, unit, expected):
    """The number with units `text` (e.g. ``"12 N/mm"``) in `unit`, as a float; `expected` says what
    the key takes when `text` is not that (a number, units pint knows, of the dimension of `unit`)."""
    try:
        import pint
    except ImportError:
        raise _Expected(f"{expected} (a value with units needs pint: pip install pint)") from None
    if not _NUMBER.match(text):
        raise _Expected(expected)
    try:
        quantity = pint.get_application_registry().Quantity(text)
    except Exception:  # pint's errors of an unknown unit or of a malformed expression
        raise _Expected(f"{expected} (pint knows no such unit)") from None
    try:
        magnitude = quantity.to(unit).magnitude
    except pint.DimensionalityError:
        raise _Expected(f"{expected}; {quantity.units:~} does not convert to {unit}") from None
    if not _is_number(magnitude):
        raise _Expected(expected)
    return float(magnitude)


def _named(kind):
    """A kind of `UNIT_KINDS` in words."""
    return kind.replace("_", " ")


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
