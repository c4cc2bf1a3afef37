"""Parameter sweeps on dask.distributed, and fretting maps.

A sweep runs a base history file once for every combination of the values of a grid of its
keys and gathers a few numbers of each run (`VARIABLES`) into one dataset, one dimension per key.
Keys are dotted paths into the history file, with blocks counted from 1 as in its errors:
``contact.f``, ``contact.P``, ``loading[1].Q_amplitude``, ``loading[2].blocks[1].Q``. Each case
is read through the checks of `fretting.read_history` and run by `fretting.engine.simulation` with its
defaults, on the workers of a dask.distributed cluster: a `distributed.LocalCluster` of one
single-threaded worker process per core, or the scheduler at a given address.

Each case is read here, on the machine that submits it: the workers get its contact and load
history, and read no file. With an output file, each finished case is written to its own file in
``OUT.cases/`` (named by a digest of the base history, the case's values, the release of fretting
and the contents of the tables the case reads, which the file also records), so that a sweep run
again, interrupted or extended, only runs the cases it has no file for; a case also runs alone
(`run_one`), as a task of a job array.

A sweep file (TOML) names its base history, ``history = "FILE"`` (relative to the sweep file),
or holds it (``[contact]`` and ``[[loading]]`` tables), and lists the values in a ``[grid]``
table (format: docs/guide/sweeps.md).
"""

from __future__ import annotations

import contextlib
import copy
import errno
import functools
import hashlib
import itertools
import json
import logging
import math
import os
import re
import time
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from fretting._version import __version__
from fretting.analysis import nucleation
from fretting.engine.simulation import simulate
from fretting.errors import FrettingError, GrossSlipError, MissingDependencyError
from fretting.loading.examples import EXAMPLES
from fretting.loading.history import History
from fretting.loading.history_file import (
    ANGLE_KEYS,
    KEY_KINDS,
    UNIT_KINDS,
    HistoryFileError,
    read_history_data,
    read_history_source,
)
from fretting.models.exact import transition_displacement
from fretting.physics.contact import Contact
from fretting.results.io import ENGINE, ResultError, recorded_path, save, with_current_units
from fretting.results.variables import REGIMES

__all__ = [
    "KEY",
    "REGIMES",
    "SWEEPS",
    "VARIABLES",
    "Base",
    "Case",
    "NoWorkersError",
    "Sweep",
    "case_file",
    "curves",
    "dimension",
    "figures_for",
    "fretting_map",
    "gathered",
    "is_sweep_file",
    "keys",
    "load_sweep",
    "put",
    "read_sweep",
    "resolve_sweep",
    "run_case",
    "run_cases",
    "run_one",
    "run_sweep",
    "save_map",
    "summarize",
    "sweep",
    "value_text",
]

#: The folder of the sweep files shipped with the package, which run by name (`resolve_sweep`).
SWEEPS = EXAMPLES / "sweeps"

#: Contact regimes, by their code in the variable ``regime``.
STUCK, PARTIAL_SLIP, GROSS_SLIP = range(len(REGIMES))

#: Variables of a case that follow from its last load cycle (NaN without cycles).
LAST_CYCLE = ("energy_per_cycle", "w_max", "slip_amplitude_max")

#: Variables of a case that follow from its last load cycle's fretting loop (`fretting.results.loops`):
#: NaN (regime -1) without ``delta`` recorded.
LAST_LOOP = ("cycle_regime", "Q_amplitude", "loop_opening", "energy_ratio", "sliding_ratio")

#: Contact quantities of a case, from the contact alone (gross-slip cases have them too).
CONTACT = ("a", "p0", "f", "P")

#: Variables of each case: name -> (units, long_name, definition).
VARIABLES = {
    "regime": (
        "1",
        "contact regime over the history",
        "0 stuck: no energy dissipated at any step, so no point ever slipped; 1 partial slip; "
        "2 gross slip: a step left no stick zone (|Q| reached f P: the end of a force-controlled run; "
        "under displacement control the contact slides and the run goes on)",
    ),
    "total_dissipation": (
        "J/m",
        "energy dissipated over the whole history",
        "total_dissipation of the run: int f p |ds| dx summed over every increment (NaN: gross slip)",
    ),
    "energy_per_cycle": (
        "J/m",
        "energy dissipated in the last load cycle",
        "cycle_dissipation of the last cycle: the steady energy per cycle once the cycles repeat "
        "(NaN: no load cycles, or gross slip)",
    ),
    "w_max": (
        "J/m^2",
        "peak dissipated energy density of the last load cycle",
        "max over x of w(x) of the last cycle, w the energy dissipated per unit area in it "
        "(fretting.analysis.nucleation.peak_dissipation_density; NaN: no load cycles, or gross slip)",
    ),
    "slip_amplitude_max": (
        "m",
        "peak slip amplitude of the last load cycle",
        "max over x of delta(x) of the last cycle, half the range of the slip over it "
        "(fretting.analysis.nucleation.slip_amplitude; NaN: no load cycles, or gross slip)",
    ),
    "gross_slip_step": ("1", "step that reached gross slip", "first step whose loads leave no stick zone (-1: none)"),
    "cycle_regime": (
        "1",
        "contact regime of the last load cycle",
        "cycle_regime of the last cycle: the largest regime of its increments (-1: no delta recorded, as without "
        "a datum, no load cycles, or force control that reached gross slip)",
    ),
    "Q_amplitude": (
        "N/m",
        "shear force amplitude Q* of the last load cycle",
        "Q_amplitude of the last cycle, half the range of Q over it (NaN where cycle_regime is -1)",
    ),
    "loop_opening": (
        "m",
        "opening of the fretting loop of the last load cycle at Q = 0",
        "loop_opening of the last cycle, 2 delta_0 (NaN where cycle_regime is -1 or the loop does not cross Q = 0)",
    ),
    "energy_ratio": (
        "1",
        "Fouvry's energy ratio A of the last load cycle",
        "energy_ratio of the last cycle, E_d / (4 Q* delta*) (depends on the datum; NaN where cycle_regime is -1)",
    ),
    "sliding_ratio": (
        "1",
        "Fouvry's sliding ratio B of the last load cycle",
        "sliding_ratio of the last cycle, delta_0 / delta* (depends on the datum; NaN where cycle_regime is -1)",
    ),
    "transition": (
        "m",
        "displacement amplitude at the partial-slip / gross-slip boundary",
        "delta_t of the case's contact (fretting.models.exact.transition_displacement, eq D6 of "
        "docs/theory/displacement.md; NaN without a datum)",
    ),
    "a": ("m", "contact half-width", "a of the case's contact"),
    "p0": ("Pa", "peak pressure", "p0 of the case's contact"),
    "f": ("1", "coefficient of friction", "f of the case's contact"),
    "P": ("N/m", "normal load per unit length", "P of the case's contact"),
}

#: SI units of the history-file keys, by name (`fretting.loading.history_file.KEY_KINDS`); angles in
#: degrees; other numeric keys are counts, flags or unit-free.
UNITS = {name: UNIT_KINDS[kind] for name, kind in KEY_KINDS.items()} | dict.fromkeys(ANGLE_KEYS, "degree")

#: Loads drawn relative to what slides the contact (docs/theory/conventions.md): psi = Q / (f P), tau = sigma / (f p0).
SCALES = {"Q": ("f P", lambda cases: cases.f * cases.P), "sigma": ("f p0", lambda cases: cases.f * cases.p0)}

#: Colours of the regimes on a fretting map: stuck, partial slip, gross slip.
REGIME_COLOURS = ("#eeeeee", "#cfe2f3", "#f4c7c3")

#: Resolution of the map that `save_map` writes, as `fretting plot`'s figures.
MAP_DPI = 100

#: Seconds between two questions to the scheduler, while no case completes, of whether it has workers.
WORKER_POLL_SECONDS = 1.0

#: Seconds a sweep waits on a scheduler without workers (every one killed) before it stops: longer
#: than a local cluster's nanny takes to restart a killed worker, or a batch system to start one.
NO_WORKERS_SECONDS = 60.0

#: Seconds a sweep waits for the file of its scheduler to appear (`sweep`'s `scheduler_file`).
SCHEDULER_FILE_SECONDS = 60.0

#: Variables of a sweep that `fretting plot` draws against the swept values (`curves`).
CURVES = ("energy_per_cycle", "w_max", "slip_amplitude_max", "total_dissipation")

#: Most curves of one figure that `curves` gives a legend: more would hide the figure.
CURVE_LEGEND = 10

#: A grid key: names with block numbers from 1, joined by dots.
KEY = re.compile(r"[A-Za-z_]\w*(\[[1-9]\d*\])*(\.[A-Za-z_]\w*(\[[1-9]\d*\])*)*")
_PART = re.compile(r"\[(\d+)\]|(\w+)")


@dataclass(frozen=True, eq=False)
class Base:
    """The history a sweep varies.

    Attributes
    ----------
    path : pathlib.Path
        The file it was read from: errors name it, and the tables it names are read next to it.
    text : str
        That file's text: errors give the line of a key in it.
    data : dict
        The ``[contact]`` table and the ``[[loading]]`` blocks, parsed.
    """

    path: Path
    text: str
    data: dict

    @property
    def sha256(self):
        """Hex digest of `data` (canonical JSON): what a case file must have been run from to be reused."""
        return hashlib.sha256(json.dumps(self.data, sort_keys=True).encode()).hexdigest()


@dataclass(frozen=True, eq=False)
class Sweep:
    """A base history and a checked grid of its values.

    Attributes
    ----------
    base : Base
    grid : dict
        Key -> list of distinct values, in the order of the dimensions.
    origin : pathlib.Path
        The file that gave the grid: errors about its values name it.
    """

    base: Base
    grid: dict
    origin: Path

    def cases(self):
        """``{key: value}`` of every case, the last key varying fastest."""
        return [dict(zip(self.grid, values, strict=True)) for values in itertools.product(*self.grid.values())]

    def case(self, values):
        """The `Case` of the values `values` (``{key: value}``), read from the base history and its tables.

        Raises HistoryFileError as `read_sweep` does, when the values fail together.
        """
        tables = []
        contact, history = _scene(self.base, values, self.origin, tables)
        digests = dict.fromkeys(hashlib.sha256(Path(table).read_bytes()).hexdigest() for table in tables)
        return Case(values, contact, history, tuple(digests))


@dataclass(frozen=True, eq=False)
class Case:
    """One case of a sweep, read on the machine that submits it: what a worker runs reads no file.

    Attributes
    ----------
    values : dict
        Key -> its value in this case.
    contact : fretting.Contact
    history : fretting.History
        The base history with these values, as `fretting.read_history` reads it.
    tables : tuple of str
        Hex SHA-256 digests of the table files (CSV) the case was read from, in the order read.
    """

    values: dict
    contact: Contact
    history: History
    tables: tuple

    def identity(self, base):
        """What the case's file records to say what it was run from, on the base history `base`: the
        base, the case's values, the release of fretting that ran it and its tables' digests (a case
        run by another release, or from another table, is run again)."""
        identity = {"base_sha256": base.sha256, "case": json.dumps(self.values, sort_keys=True)}
        identity["fretting_version"] = __version__
        return identity | ({"tables_sha256": " ".join(self.tables)} if self.tables else {})


def sweep(
    path: str | os.PathLike,
    grid: Mapping[str, list],
    scheduler: str | None = None,
    *,
    output: str | os.PathLike | None = None,
    scheduler_file: str | os.PathLike | None = None,
) -> xr.Dataset:
    """Run a history file for every combination of values of some of its keys.

    Parameters
    ----------
    path : str or os.PathLike
        History file (format of `fretting.read_history`).
    grid : mapping
        Dotted key of the file (``"contact.f"``, ``"loading[1].Q_amplitude"``: blocks counted from
        1) -> list of its values; one dimension per key, in this order. A key may be one the file
        leaves at its default, in a table the file has. A value may be a list (NumPy arrays are
        lists), for a key that takes one: the vertices of a ``linear`` block.
    scheduler : str, optional
        Address of a dask.distributed scheduler, e.g. ``"tcp://host:8786"`` (of a
        `dask_jobqueue.SLURMCluster`: its ``scheduler_address``); its workers must import `fretting`.
        Default: a `distributed.LocalCluster` of ``min(cores, cases)`` single-threaded worker
        processes, closed on return.
    output : str or os.PathLike, optional
        Dataset file to write (`fretting.save`); each case goes to its own file in the folder
        ``output`` with the suffix ``.cases``, and a case that has one there is not run again.
    scheduler_file : str or os.PathLike, optional
        The file of the scheduler to use instead of `scheduler`, as ``dask scheduler
        --scheduler-file FILE`` writes it.

    Returns
    -------
    xarray.Dataset
        The variables of `VARIABLES`, one dimension per key of `grid` (`dimension` names it) whose
        coordinate holds its values.

    Raises
    ------
    OSError
        When the file or a table it names cannot be read, or the scheduler does not answer.
    HistoryFileError
        When the file is malformed, a key is not in it, or a value is not one the key takes.
    MissingDependencyError
        When dask.distributed, of the extra ``fretting[sweep]``, is not installed.
    """
    source = read_history_source(path)
    base = Base(source.path, source.text, tomllib.loads(source.text))
    plan = Sweep(base, _checked_grid(base, grid, source.path), source.path)
    return run_sweep(plan, scheduler, output, scheduler_file=scheduler_file)


def resolve_sweep(file):
    """The sweep file that `file` names: a path, or the name of a shipped sweep (`SWEEPS`), as a `pathlib.Path`.

    A file that exists wins over a shipped sweep of the same name.

    Raises
    ------
    FileNotFoundError
        When neither exists; its message lists the shipped sweeps.
    """
    path = Path(file)
    if path.exists():
        return path
    shipped = SWEEPS / f"{str(file).removesuffix('.toml')}.toml"
    if "/" in str(file) or "\\" in str(file) or not shipped.is_file():
        names = ", ".join(path.stem for path in sorted(SWEEPS.glob("*.toml")))
        problem = f"{os.strerror(errno.ENOENT)}, nor a shipped sweep: expected a sweep file or one of: {names}"
        raise FileNotFoundError(errno.ENOENT, problem, str(file))
    return shipped


def read_sweep(path):
    """The base history and grid of a sweep file (format: docs/guide/sweeps.md).

    Raises
    ------
    OSError
        When the file, or the history it names, cannot be read.
    HistoryFileError
        When either is malformed.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise HistoryFileError(path, None, None, "found bytes that are not UTF-8, expected UTF-8 text") from None
    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise HistoryFileError(path, None, None, f"TOML syntax: {error}") from None
    allowed = ("history", "contact", "loading", "grid")
    for key in document:
        if key not in allowed:
            raise HistoryFileError(path, None, key, f"unknown key, expected one of: {', '.join(allowed)}")
    if not isinstance(document.get("grid"), dict):
        raise HistoryFileError(path, None, "grid", "found no [grid] table, expected one listing the values of keys")
    base = _base(path, text, document)
    return Sweep(base, _checked_grid(base, _flat(document["grid"]), path), path)


def _base(path, text, document):
    """The base history that the sweep file `document` names or holds."""
    inline = [key for key in ("contact", "loading") if key in document]
    if "history" in document:
        if inline:
            raise HistoryFileError(path, None, inline[0], "found it beside history, expected one base history")
        name = document["history"]
        if not isinstance(name, str) or not name:
            raise HistoryFileError(path, None, "history", "found no file name, expected a history file in quotes")
        source = read_history_source(path.parent / name)
        return Base(source.path, source.text, tomllib.loads(source.text))
    if not inline:
        raise HistoryFileError(path, None, None, 'found no base history, expected history = "FILE" or its tables')
    base = Base(path, text, {key: document[key] for key in inline})
    read_history_data(base.path, base.text, base.data)  # the base alone, checked as a history file
    return base


def _flat(table, prefix=""):
    """``{dotted key: values}`` of a [grid] table, whose bare dotted keys TOML reads as nested tables."""
    flat = {}
    for key, value in table.items():
        if isinstance(value, dict):
            flat |= _flat(value, f"{prefix}{key}.")
        else:
            flat[f"{prefix}{key}"] = value
    return flat


def _checked_grid(base, grid, origin):
    """`grid` as ``{key: list of values}``, each value checked in the base history alone.

    Values that only fail together (say a load and a radius) are found when their case is read.
    """
    if not isinstance(grid, Mapping) or not grid:
        raise HistoryFileError(origin, None, "grid", f"found {_show(grid)}, expected keys and lists of their values")
    checked = {}
    for key, values in grid.items():
        label = f"grid.{key}"
        if not isinstance(key, str) or not KEY.fullmatch(key):
            problem = 'found a malformed key, expected one like "loading[1].Q_amplitude"'
            raise HistoryFileError(origin, None, label, problem)
        if not isinstance(values, (list, tuple, np.ndarray)) or not len(values):
            raise HistoryFileError(origin, None, label, f"found {_show(values)}, expected a list of values")
        plain = [_plain(value) for value in values]
        for given, value in zip(values, plain, strict=True):
            if value is _NOT_PLAIN:
                problem = "expected numbers, booleans, text or lists of them"
                raise HistoryFileError(origin, None, label, f"found {_show(given)}, {problem}")
            if plain.count(value) > 1:
                raise HistoryFileError(origin, None, label, f"found {_show(value)} twice, expected distinct values")
            _scene(base, {key: value}, origin)
        checked[key] = plain
    return checked


#: What `_plain` returns for a value that is not a number, boolean, text or a list of them.
_NOT_PLAIN = object()


def _plain(value):
    """`value` as TOML holds it: NumPy scalars as Python numbers, arrays and tuples as lists; `_NOT_PLAIN` for
    anything but numbers, booleans, text and lists of them."""
    if isinstance(value, (list, tuple, np.ndarray)):
        items = [_plain(item) for item in value]
        return _NOT_PLAIN if any(item is _NOT_PLAIN for item in items) else items
    value = value.item() if isinstance(value, np.generic) else value
    return value if isinstance(value, (bool, int, float, str)) else _NOT_PLAIN


def _show(value):
    """`value` as JSON, cut short."""
    text = json.dumps(value, default=repr)
    return text if len(text) <= 40 else f"{text[:37]}..."


def _scene(base, case, origin, tables=None):
    """Contact and history of the base history with the values of `case` in place of its own; the
    path of each table file read is appended to the list `tables`, when given.

    Raises HistoryFileError naming `origin` and the key when a value of `case` is at fault, and
    the base history and the case when the values fail together.
    """
    data = copy.deepcopy(base.data)
    for key, value in case.items():
        if not put(data, key, value):
            problem = f"found no such table in {base.path}, expected a key of one of its tables (blocks from 1)"
            raise HistoryFileError(origin, None, f"grid.{key}", problem)
    try:
        return read_history_data(base.path, base.text, data, tables)
    except HistoryFileError as error:
        if error.key in case:
            raise HistoryFileError(origin, None, f"grid.{error.key}", error.problem) from None
        values = ", ".join(f"{key} = {_show(value)}" for key, value in case.items())
        raise HistoryFileError(error.path, error.line, error.key, f"{error.problem} (in the case {values})") from None


def put(data, key, value):
    """Set the dotted `key` (`KEY`) to `value` in the TOML mapping `data` of a history file; False when the
    table that holds the key is missing."""
    parts = [int(number) - 1 if number else name for number, name in _PART.findall(key)]
    table = data
    for part in parts[:-1]:
        if isinstance(part, int):
            found = isinstance(table, list) and part < len(table)
        else:
            found = isinstance(table, dict) and part in table
        if not found:
            return False
        table = table[part]
    if not isinstance(table, dict) or isinstance(parts[-1], int):
        return False
    table[parts[-1]] = value
    return True


def run_case(contact, history):
    """The variables of `VARIABLES` of a case, the contact `contact` under the history `history`: what the workers run.

    Returns
    -------
    xarray.Dataset
        Scalars; a gross-slip case has regime 2, the step that slid and NaN energies.
    """
    try:
        return summarize(simulate(contact, history), _transition(contact))
    except GrossSlipError as error:
        nan = dict.fromkeys(("total_dissipation", *LAST_CYCLE, *LAST_LOOP[1:]), math.nan)
        contact_values = {name: getattr(contact, name) for name in CONTACT}
        return _summary(contact_values, GROSS_SLIP, error.step, nan | _NO_LOOP | {"transition": _transition(contact)})


def summarize(result, transition=math.nan):
    """The variables of `VARIABLES` of a result of `fretting.engine.simulation`, as a Dataset of scalars;
    `transition` [m] that of its contact (`fretting.models.exact.transition_displacement`)."""
    total = float(result.total_dissipation)
    energies = {"total_dissipation": total, "transition": transition} | dict.fromkeys(LAST_CYCLE, math.nan)
    energies |= _NO_LOOP
    if "cycle_number" in result.dims and result.sizes["cycle_number"]:
        energies |= {
            "energy_per_cycle": float(result.cycle_dissipation[-1]),
            "w_max": float(nucleation.peak_dissipation_density(result).w_max[-1]),
            "slip_amplitude_max": float(nucleation.slip_amplitude(result)[-1].max()),
        }
        energies |= {name: result[name].values[-1] for name in LAST_LOOP if name in result}
    return _summary(result.attrs, *_regime(result, total), energies)


#: The `LAST_LOOP` variables of a case without a loop.
_NO_LOOP = {"cycle_regime": np.int8(-1)} | dict.fromkeys(LAST_LOOP[1:], math.nan)


def _transition(contact):
    """``delta_t`` [m] of `contact` (`transition_displacement`), NaN without a datum."""
    return math.nan if contact.datum is None else transition_displacement(contact)


def _regime(result, total):
    """``(regime, first step of gross slip or -1)`` of a run that finished: from its steps' regimes where
    it records them (displacement control, under which the contact slides and the run goes on), else
    partial slip where it dissipated energy and stuck where not."""
    if "regime" not in result:
        return (PARTIAL_SLIP if total > 0 else STUCK), -1
    regimes = result.regime.values
    sliding = np.flatnonzero(regimes == GROSS_SLIP)
    return int(regimes.max(initial=STUCK)), int(result.step.values[sliding[0]]) if sliding.size else -1


def _summary(contact, regime, step, energies):
    """Dataset of the case variables from the contact's `a`, `p0`, `f`, `P` (a mapping) and the rest."""
    values = {"regime": np.int8(regime), "gross_slip_step": np.int64(step)} | energies
    values |= {name: float(contact[name]) for name in CONTACT}
    values["cycle_regime"] = np.int8(values["cycle_regime"])
    return xr.Dataset({name: ((), values[name], _attrs(name)) for name in VARIABLES})


def _attrs(name):
    units, long_name, definition = VARIABLES[name]
    attrs = {"units": units, "long_name": long_name, "definition": definition}
    if name in ("regime", "cycle_regime"):  # CF flags
        attrs |= {"flag_values": np.arange(len(REGIMES), dtype=np.int8), "flag_meanings": " ".join(REGIMES)}
    return attrs


def run_sweep(plan, scheduler=None, output=None, *, scheduler_file=None, progress=None):
    """Run every case of the `Sweep` `plan` that has no file yet; the dataset of all (see `sweep`).

    `progress`, when given, is called as ``progress(done, total)`` with the cases done, those that
    have a file first, and after each case that finishes.
    """
    cases = [plan.case(values) for values in plan.cases()]
    summaries = run_cases(cases, plan.base, scheduler, output, scheduler_file=scheduler_file, progress=progress)
    dataset = _combine(plan, summaries)
    if output is not None:
        save(dataset, output)
    return dataset


def run_cases(cases, base, scheduler=None, output=None, *, scheduler_file=None, progress=None, in_process=False):
    """The variables (`run_case`) of each `Case` of `cases`, in order: read from its file where a sweep of
    `base` written to `output` has one (`case_file`), else run on dask.distributed (see `sweep`) and
    kept in its file; with `in_process`, run one after another in this process, without dask.

    `progress` as in `run_sweep`. Raises NoWorkersError, saying what is kept, where the scheduler
    has had no worker for `NO_WORKERS_SECONDS`.
    """
    files = [None] * len(cases) if output is None else [case_file(output, base, case) for case in cases]
    summaries = [_finished(file, base, case) for file, case in zip(files, cases, strict=True)]
    todo = [k for k, summary in enumerate(summaries) if summary is None]
    progress = progress or (lambda done, total: None)
    finished = len(cases) - len(todo)
    progress(finished, len(cases))
    ran = _in_process(cases, todo) if in_process else _on_dask(cases, todo, scheduler, scheduler_file)
    try:
        with contextlib.closing(ran):  # a client and its cluster closed on an interrupt too
            for k, summary in ran:
                summaries[k] = summary
                _keep(summary, files[k], base, cases[k])
                finished += 1
                progress(finished, len(cases))
    except NoWorkersError as error:
        raise NoWorkersError(f"{error}; {_kept_cases(finished, len(cases), output)}") from None
    return summaries


def _in_process(cases, todo):
    """``(k, variables)`` of the cases numbered `todo` of `cases`, run here one after another."""
    for k in todo:
        yield k, run_case(cases[k].contact, cases[k].history)


def _on_dask(cases, todo, scheduler, scheduler_file):
    """``(k, variables)`` of the cases numbered `todo` of `cases`, run on dask.distributed, as each finishes."""
    if not todo:
        return
    distributed = _distributed()
    with _client(distributed, scheduler, scheduler_file, len(todo)) as client:
        futures = {client.submit(run_case, cases[k].contact, cases[k].history, pure=False): k for k in todo}
        for future, summary in _completed(distributed, client, futures):
            yield futures[future], summary


class NoWorkersError(FrettingError, RuntimeError):
    """The scheduler of a sweep has had no worker for `NO_WORKERS_SECONDS`: its cases would wait forever."""


def _completed(distributed, client, futures):
    """``(future, result)`` of the futures `futures` of `client` as each completes, while the scheduler has
    workers.

    A result is fetched within `NO_WORKERS_SECONDS`, else its future waits again with the others: a
    worker killed after its case finished takes the result with it, and the scheduler runs that case
    again (the future is pending once more: an unbounded fetch would wait forever with no worker left).
    Every `WORKER_POLL_SECONDS` without a future completed, asks the scheduler for its workers;
    raises NoWorkersError once it has had none for `NO_WORKERS_SECONDS` (each worker killed, and
    none restarted or added: a future would wait forever).
    """
    pending, alone = set(futures), None
    while pending:
        try:
            done, pending = distributed.wait(pending, timeout=WORKER_POLL_SECONDS, return_when="FIRST_COMPLETED")
        except TimeoutError:
            done = ()
        for future in done:
            try:
                summary = future.result(timeout=NO_WORKERS_SECONDS)
            except TimeoutError:
                if future.status == "error":  # the case's own error
                    raise
                pending.add(future)
                continue
            yield future, summary
        if client.scheduler_info()["workers"]:
            alone = None
        elif alone is None:
            alone = time.monotonic()
        elif time.monotonic() - alone > NO_WORKERS_SECONDS:
            raise NoWorkersError(f"the dask scheduler has had no workers for {NO_WORKERS_SECONDS:g} s")


def _kept_cases(finished, total, output):
    """What became of the cases of a sweep stopped with `finished` of `total` done: where they are, how to go on."""
    if output is None:
        return f"{finished} of {total} cases finished, none kept (no output file)"
    folder = Path(output).with_suffix(".cases")
    return f"{finished} of {total} cases finished, kept in {folder}; run the sweep again with workers to run the rest"


def run_one(plan, k, output):
    """Run the case number `k` (from 0, in the order of `Sweep.cases`) of `plan` alone, in this process, into
    the folder of case files of the sweep dataset `output`, unless its file is there already.

    Returns
    -------
    file : pathlib.Path
        The case's file.
    summary : xarray.Dataset
        Its variables.
    ran : bool
        False when the file was there already.
    """
    case = plan.case(plan.cases()[k])
    file = case_file(output, plan.base, case)
    summary = _finished(file, plan.base, case)
    if summary is not None:
        return file, summary, False
    summary = run_case(case.contact, case.history)
    _keep(summary, file, plan.base, case)
    return file, summary, True


def _keep(summary, file, base, case):
    """Write the variables `summary` of the `Case` `case` to its `file` (None: none kept)."""
    if file is not None:
        title = f"fretting sweep case: {json.dumps(case.values)}"
        save(summary.assign_attrs(case.identity(base), title=title), file)


def case_file(output, base, case):
    """``OUT.cases/<digest>.h5``: the file of the `Case` `case` of a sweep of `base` written to `output`,
    named by a digest of what it is run from (`Case.identity`)."""
    digest = hashlib.sha256(json.dumps(case.identity(base), sort_keys=True).encode()).hexdigest()
    return Path(output).with_suffix(".cases") / f"{digest[:24]}.h5"


def _finished(file, base, case):
    """The case variables in `file` if it holds the `Case` `case` of this base history, else None."""
    if file is None or not file.is_file():
        return None
    summary = with_current_units(xr.load_dataset(file, engine=ENGINE))  # a case file of fretting 0.1.0 too
    identity = case.identity(base)
    same = all(summary.attrs.get(name) == value for name, value in identity.items())
    return summary if same and all(name in summary for name in VARIABLES) else None  # else of fewer variables


def _distributed():
    """The module ``distributed``, imported here: half a second of imports that only sweeps need, and an extra.

    Raises
    ------
    MissingDependencyError
        When dask.distributed is not installed.
    """
    try:
        import distributed
    except ImportError as error:
        raise MissingDependencyError(
            f"sweeps run on dask.distributed, which is not installed ({error}): pip install 'fretting[sweep]'"
        ) from None
    return distributed


@contextlib.contextmanager
def _client(distributed, scheduler, scheduler_file, cases):
    """A client of the module `distributed` to the scheduler at `scheduler`, or of `scheduler_file`, or to
    a local cluster for `cases` cases."""
    import dask.config  # dask comes with distributed
    from dask.system import CPU_COUNT  # the cores this process may use

    Client, LocalCluster = distributed.Client, distributed.LocalCluster
    if scheduler_file is not None:
        _wait_for(Path(scheduler_file))
    if scheduler is not None or scheduler_file is not None:
        default = dask.config.get("scheduler", None)
        try:
            client = Client(scheduler, scheduler_file=None if scheduler_file is None else os.fspath(scheduler_file))
        except ValueError as error:  # a malformed address; one that does not answer raises OSError
            # the client that failed has made itself dask's default scheduler, for every later
            # computation of this process (an xarray write included): put back the one before
            dask.config.set(scheduler=default)
            raise OSError(errno.EINVAL, f"scheduler {scheduler or scheduler_file}: {error}") from None
        with client:
            yield client
        return
    workers = min(CPU_COUNT, cases)
    with (
        LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=":0",  # a free port: with None it still serves HTTP on 8787, and warns if that is taken
            silence_logs=logging.ERROR,  # not the warnings of cancelled tasks and killed workers when interrupted
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client


def _wait_for(scheduler_file):
    """Return once the file `scheduler_file` is there: a scheduler started beside the sweep, in the same batch
    job, writes it within seconds. Raises FileNotFoundError after `SCHEDULER_FILE_SECONDS` (dask would wait on)."""
    deadline = time.monotonic() + SCHEDULER_FILE_SECONDS
    while not scheduler_file.is_file():
        if time.monotonic() > deadline:
            problem = f"no scheduler wrote it in {SCHEDULER_FILE_SECONDS:g} s (dask scheduler --scheduler-file FILE)"
            raise FileNotFoundError(errno.ENOENT, problem, str(scheduler_file))
        time.sleep(0.1)


def gathered(grid, summaries):
    """One dataset of the case datasets `summaries` (in the order of `Sweep.cases`) of the grid `grid`
    (key -> values), one dim per key (`dimension`)."""
    dims, shape = tuple(dimension(key) for key in grid), tuple(len(values) for values in grid.values())
    first = summaries[0]
    data = {
        name: (dims, np.array([summary[name].values for summary in summaries]).reshape(shape), first[name].attrs)
        for name in VARIABLES
    }
    coords = {
        dim: (dim, _coordinate(values), _key_attrs(key, values))
        for dim, (key, values) in zip(dims, grid.items(), strict=True)
    }
    return xr.Dataset(data, coords=coords)


def _combine(plan, summaries):
    """`gathered` of the case datasets `summaries` of `plan`, with what the sweep ran from."""
    attrs = {
        "title": f"fretting sweep of {plan.base.path.name} over {' x '.join(plan.grid)}",
        "history_file": recorded_path(plan.base.path),
        "history_toml": plan.base.text,
        "base_sha256": plan.base.sha256,
        "grid": json.dumps(plan.grid),
    }
    return gathered(plan.grid, summaries).assign_attrs(attrs)


def dimension(key):
    """The name of the dimension of the grid key `key` in a sweep dataset, valid in CF (letters, digits and
    underscores, from a letter): its runs of other characters as one underscore.

    Examples
    --------
    >>> dimension("loading[1].Q_amplitude"), dimension("contact.f")
    ('loading_1_Q_amplitude', 'contact_f')
    """
    return re.sub(r"\W+", "_", key).strip("_")


def _coordinate(values):
    """The values of a key as a coordinate: lists (a vertex list is one value) as their JSON text."""
    if any(isinstance(value, list) for value in values):
        return np.array([json.dumps(value) for value in values])
    return np.array(values)


def _key_attrs(key, values):
    """``long_name`` and ``key`` (the grid key, dotted) and, for numbers, ``units`` of the coordinate of `key`."""
    name = key.rsplit(".", 1)[-1]
    attrs = {"long_name": key, "key": key}
    if any(isinstance(value, list) for value in values):
        return attrs | {"comment": "each value is a list, written as JSON"}
    numeric = all(isinstance(value, (int, float)) and not isinstance(value, bool) for value in values)
    return attrs | ({"units": UNITS.get(name, "1")} if numeric else {})


def load_sweep(path):
    """The dataset of a sweep file written by `sweep` or ``fretting sweep``, read into memory; a file of
    an earlier release, whose dimensions are the dotted keys, too.

    Raises
    ------
    FileNotFoundError
        When there is no file at `path`.
    ResultError
        When it is not a sweep of fretting.
    """
    if not Path(path).is_file():
        raise FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), str(path))
    if not is_sweep_file(path):
        raise ResultError(f"{path}: found no variable regime or attribute grid, expected a sweep of fretting")
    return with_current_units(xr.load_dataset(path, engine=ENGINE))


def is_sweep_file(path):
    """Whether `path` is a sweep dataset's file: a netCDF file with a variable ``regime`` and an attribute ``grid``."""
    try:
        with xr.open_dataset(path, engine=ENGINE) as dataset:
            return "regime" in dataset.variables and "grid" in dataset.attrs
    except (OSError, ValueError):
        return False


def keys(cases):
    """The grid key of each dimension of the sweep dataset `cases`: ``{dimension: dotted key}``."""
    return {dim: cases[dim].attrs.get("key", dim) for dim in cases.regime.dims}


# -- Figures -----------------------------------------------------------------------------------


def figures_for(cases):
    """The figures of the sweep dataset `cases`: ``{name: draw}``, each drawn by ``draw(cases, ax)``.

    The `fretting_map` of a sweep over two keys of numbers, as ``map``; then the `curves` of each
    variable of `CURVES` that some case has a value of, named as the variable.
    """
    dims = cases.regime.dims
    figures = {}
    if len(dims) == 2 and all(cases[dim].dtype.kind in "iuf" for dim in dims):
        figures["map"] = fretting_map
    for name in CURVES:
        if np.isfinite(cases[name].values).any():
            figures[name] = functools.partial(curves, name=name)
    return figures


def fretting_map(cases, ax):
    """Draw the regime (shaded) and the energy per cycle (contours) of a two-key sweep on `ax`.

    The first key runs along x, the second along y. Keys of Q or sigma (``Q``, ``Q_amplitude``,
    ``sigma_mean``, ...) are drawn relative to ``f P`` and ``f p0`` of each case.

    Parameters
    ----------
    cases : xarray.Dataset
        A dataset of `sweep` with two dimensions.
    ax : matplotlib.axes.Axes

    Returns
    -------
    matplotlib.axes.Axes
    """
    if len(cases.dims) != 2:
        raise ValueError(f"a fretting map needs a sweep over two keys, found {len(cases.dims)}: {list(cases.dims)}")
    x_dim, y_dim = cases.regime.dims
    (x, x_label), (y, y_label) = (_axis(cases, dim) for dim in (x_dim, y_dim))
    x, y = (values.transpose(y_dim, x_dim).values for values in xr.broadcast(x, y))
    regime = cases.regime.transpose(y_dim, x_dim).values
    from matplotlib.colors import BoundaryNorm, ListedColormap  # here: `import fretting` does without matplotlib
    from matplotlib.patches import Patch
    from matplotlib.ticker import LogLocator

    colours = ListedColormap(REGIME_COLOURS)
    ax.pcolormesh(x, y, regime, cmap=colours, norm=BoundaryNorm(np.arange(len(REGIMES) + 1) - 0.5, len(REGIMES)))
    energy = cases.energy_per_cycle.transpose(y_dim, x_dim).values
    positive = energy[energy > 0]
    if positive.size and positive.min() < positive.max():
        levels = LogLocator(subs=(1, 3)).tick_values(positive.min(), positive.max())
        lines = ax.contour(x, y, energy, levels=levels, colors="k", linewidths=0.8)
        ax.clabel(lines, fmt="%.2g", fontsize=7)
    patches = [Patch(color=c, label=name.replace("_", " ")) for c, name in zip(REGIME_COLOURS, REGIMES, strict=True)]
    ax.legend(handles=patches, loc="upper left", bbox_to_anchor=(1.01, 1), title="regime")
    ax.set(xlabel=x_label, ylabel=y_label, title="regime and energy per cycle [J/m] (contours)")
    return ax


def curves(cases, name, ax):
    """Draw the variable `name` of the sweep dataset `cases` against the values of one key, a curve for each
    combination of the values of the others; cases without a value (gross slip, no cycles) leave gaps.

    Along x: the first key of numbers with more than one value (loads relative to what slides the
    contact, as in `fretting_map`), else the first key, its values as labels.

    Returns
    -------
    matplotlib.axes.Axes
    """
    dims = cases.regime.dims
    numeric = [dim for dim in dims if cases[dim].dtype.kind in "iuf" and cases.sizes[dim] > 1]
    x_dim = (numeric or list(dims))[0]
    others = [dim for dim in dims if dim != x_dim]
    if x_dim in numeric:
        x, x_label = _axis(cases, x_dim)
    else:
        x, x_label = xr.DataArray(np.arange(cases.sizes[x_dim]), dims=x_dim), keys(cases)[x_dim]
        ax.set_xticks(x.values, [value_text(value) for value in cases[x_dim].values], rotation=30, ha="right")
    names = keys(cases)
    for index in itertools.product(*(range(cases.sizes[dim]) for dim in others)):
        where = dict(zip(others, index, strict=True))
        label = ", ".join(f"{names[dim]} = {value_text(cases[dim].values[k])}" for dim, k in where.items())
        xs = x.isel({dim: k for dim, k in where.items() if dim in x.dims}).transpose(x_dim).values
        ax.plot(xs, cases[name].isel(where).transpose(x_dim).values, marker="o", label=label or None)
    if others and len(ax.lines) <= CURVE_LEGEND:
        ax.legend(fontsize=7)
    attrs = cases[name].attrs
    ax.set(xlabel=x_label, ylabel=f"{name} [{attrs.get('units', '?')}]", title=attrs.get("long_name", name))
    return ax


def value_text(value):
    """A value of a key as a legend, a tick or `fretting info` shows it: floats to 4 digits."""
    return f"{value:.4g}" if isinstance(value, (float, np.floating)) else str(value)


def _axis(cases, dim):
    """Values of the coordinate `dim` to draw (relative to what slides the contact, for loads) and its label."""
    key = keys(cases)[dim]
    load = key.rsplit(".", 1)[-1].split("_")[0]
    units = cases[dim].attrs.get("units")
    if load not in SCALES:
        return cases[dim], f"{key} [{units}]" if units else key
    scale_name, scale = SCALES[load]
    values = scale(cases)
    same = f" = {float(values.min()):.3g} {units}" if values.min() == values.max() else ""
    return cases[dim] / values, f"{key} / ({scale_name}{same})"


def save_map(cases, path):
    """Write the `fretting_map` of `cases` to the PNG file `path` (6.4 x 4.4 inches, 100 dpi); return `path`."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(6.4, 4.4), layout="constrained")
    fretting_map(cases, figure.subplots())
    figure.savefig(path, dpi=MAP_DPI)
    return path
