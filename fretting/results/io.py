"""Result files: datasets written through xarray and h5netcdf, compressed, and replaced atomically.

The files are netCDF-4 (HDF5), readable by h5py, xarray and the netCDF tools, and follow the CF
conventions (`cf_encoded`): every file of `fretting`, result, stress field or sweep, is written here.
"""

from __future__ import annotations

import contextlib
import datetime
import errno
import importlib.metadata
import io
import json
import os
import platform
import re
import secrets
import shutil
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import h5netcdf
import h5py
import numpy as np
import xarray as xr
from xarray.backends import H5NetCDFStore

from fretting._version import __version__
from fretting.errors import FrettingError
from fretting.results.loops import recorded_loops, with_loops
from fretting.results.notes import noted
from fretting.results.variables import AXES, VARIABLES

try:
    import resource  # the file size limit of `ulimit -f` (Unix)

    resource_unlimited = resource.RLIM_INFINITY
except ImportError:  # Windows
    resource = resource_unlimited = None

if TYPE_CHECKING:
    from fretting.loading.history_file import HistorySource

__all__ = [
    "CONVENTIONS",
    "ENGINE",
    "LEGACY_UNITS",
    "WRITTEN_ATTRIBUTES",
    "Joiner",
    "ResultError",
    "cf_encoded",
    "join_results",
    "joined_steps",
    "load",
    "open_result",
    "provenance",
    "recorded_path",
    "remove_temporaries",
    "save",
    "save_joined",
    "source_attributes",
    "with_current_units",
]

#: The xarray backend, named explicitly so that files never depend on what else is installed.
ENGINE = "h5netcdf"

#: zlib level 4 with byte shuffling: a higher level saves few bytes of a result and takes longer
#: to write.
COMPRESSION = {"zlib": True, "complevel": 4, "shuffle": True}

#: Rows of a per-cycle variable in one HDF5 chunk: the `CYCLE_DIMS` are unlimited, so that rows are
#: appended (`save_joined`), and a chunk of 256 rows of 500 float32 nodes is 0.5 MB.
CYCLE_CHUNK_ROWS = 256

#: Dimensions of per-cycle rows: every cycle (``cycle_number``), and the cycles whose fields a
#: run's ``cycle_fields`` policy chose (``field_cycle``; a cycle's row comes once, complete).
CYCLE_DIMS = ("cycle_number", "field_cycle")

#: Random bytes in the name of `save`'s temporary file, ``.NAME.<hex>.tmp``: two saves of one
#: path never share it.
TOKEN_BYTES = 6

#: Distributions whose versions a result records.
DEPENDENCIES = ("fretting", "numpy", "scipy", "xarray", "h5netcdf", "h5py")

#: Units as the files of fretting 0.1.0 spell them -> as they are spelled now, which both pint and UDUNITS
#: parse (pint takes ``m2`` for a unit named "m2"). Files are read (`open_result`) with the new spelling.
LEGACY_UNITS = {"m2": "m^2", "Pa2": "Pa^2", "J/m2": "J/m^2", "Pa J/m2": "Pa J/m^2"}

#: The conventions that the files follow: their global attribute ``Conventions``.
CONVENTIONS = "CF-1.11"

#: The method that results are computed by: the files' global attribute ``references``.
REFERENCES = (
    "D. A. Hills, R. Ramesh, J. R. Barber and M. R. Moore, Methods to solve half-plane partial slip contact "
    "problems (method 4)"
)

#: Global attributes that writing a file adds (`provenance`, `cf_encoded`): two writes of one dataset
#: differ in ``created`` and ``history``.
WRITTEN_ATTRIBUTES = ("created", "versions", "Conventions", "title", "source", "references", "history")

#: Variables and attributes that every result has.
REQUIRED_VARIABLES = ("Q", "sigma", "p", "q", "slip", "stick", "dissipation", "delta_Q", "vertex_step", "state_slip")
REQUIRED_ATTRIBUTES = ("a", "centre", "p0", "E_star", "f", "P", "profile", "model", "nodes", "steps")


class ResultError(FrettingError, ValueError):
    """A file is not a result of `fretting`, or results do not join."""


def save(result: xr.Dataset, path: str | os.PathLike) -> None:
    """Write a result to a netCDF-4 file, atomically.

    The dataset goes to a temporary file in the same directory, is flushed to disk and then
    renamed over `path`: an existing file at `path` is replaced whole or left untouched.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `simulate`; `provenance` attributes are added to it in the file.
    path : str or os.PathLike
        Output file; its directory is created if needed.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> result = fr.simulate(contact, fr.History.piecewise_linear([0, 30e3], None, 8), fr.models.Grid(32))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     save(result, Path(folder) / "result.nc")
    ...     again = load(Path(folder) / "result.nc")
    >>> bool(again.q.equals(result.q)), again.attrs["model"]
    (True, 'grid')
    """
    with _replacing(path) as temporary:
        _write(result.assign_attrs(provenance()), temporary, path, "fretting.save")


@contextlib.contextmanager
def _replacing(path):
    """The temporary file beside `path` to write; renamed over `path` when the block ends without error."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(f".{path.name}.{secrets.token_hex(TOKEN_BYTES)}.tmp")
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        with contextlib.suppress(OSError):  # a folder turned read-only: left to `remove_temporaries`
            temporary.unlink(missing_ok=True)


def save_joined(parts: Sequence[str | os.PathLike], path: str | os.PathLike, attributes: dict) -> None:
    """Write `join_results` of the result files `parts` to `path`, atomically (as `save`), holding
    in memory the recorded steps of the run and the per-cycle rows of one part at a time.

    The parts' steps and state are joined in memory (`Joiner`): their size is set by the steps
    recorded. The per-cycle variables are appended to the file part by part along its unlimited
    `CYCLE_DIMS`; a cycle that spans two parts is rewritten with the later part's row, as
    `join_results` takes it.

    Parameters
    ----------
    parts : sequence of path
        Result files of successive parts of a run, in order (see `join_results`).
    path : str or os.PathLike
        Output file.
    attributes : dict
        Attributes added to the first part's.
    """
    head = joined_steps(parts).assign_attrs(attributes | provenance())
    loops = recorded_loops(head)
    with _replacing(path) as temporary:
        rows = (with_loops(found, loops) for found in map(_rows, parts) if found.variables)
        first = next(rows, None)
        wrote = f"fretting.results.io.save_joined of {len(parts)} part{'s' * (len(parts) != 1)}"
        _write(head if first is None else head.assign(first.variables), temporary, path, wrote, fsync=False)
        try:
            with h5netcdf.File(temporary, "r+") as file:
                for found in rows:
                    _room(temporary, found.nbytes, path)
                    _append_cycles(file, found)
        except (OSError, RuntimeError) as error:  # HDF5's write errors come as either
            if getattr(error, "filename", None) == str(path):  # said already, by _room
                raise
            raise OSError(getattr(error, "errno", None), f"cannot write: {_reason(error)}", str(path)) from None
        _synced(temporary, path)


#: Bytes that HDF5 may add to a file for its own records as rows are appended (B-tree nodes, heaps).
HDF5_SLACK = 2**16


def _room(temporary, needed, path):
    """Refuse to add `needed` bytes (and `HDF5_SLACK`) to the file `temporary`, written for `path`,
    where its disk has less room or the process may not make a file that large (``ulimit -f``).

    Said before HDF5 writes, whose failure in the middle of a file may take the process down as it
    closes the file. `needed` bounds what is written: the rows uncompressed.
    """
    needed += HDF5_SLACK
    free = shutil.disk_usage(temporary.parent).free
    if needed > free:
        raise OSError(errno.ENOSPC, f"cannot write: its disk has {free} bytes free, about {needed} needed", str(path))
    largest = resource.getrlimit(resource.RLIMIT_FSIZE)[0] if resource is not None else resource_unlimited
    if largest != resource_unlimited and temporary.stat().st_size + needed > largest:
        why = f"this process may write files of at most {largest} bytes (ulimit -f), about {needed} more needed"
        raise OSError(errno.EFBIG, f"cannot write: {why}", str(path))


def joined_steps(parts: Sequence[str | os.PathLike]) -> xr.Dataset:
    """`join_results` of the result files `parts` without their per-cycle variables, which are
    not read: the recorded steps, vertices and final state of a run in parts."""
    joiner = Joiner()
    for part in parts:
        with open_result(part) as opened, _reading(part):
            joiner.add(opened.drop_vars(_per_cycle(opened)).load())
    return joiner.result()


def _rows(part):
    """The per-cycle variables of the result file `part`, read into memory."""
    with open_result(part) as opened, _reading(part):
        return opened[_per_cycle(opened)].load()


def _per_cycle(result, dims=CYCLE_DIMS):
    """Names of the per-cycle variables of `result` (those along one of `dims`)."""
    return [name for name, variable in result.variables.items() if variable.dims[:1] in [(dim,) for dim in dims]]


def _append_cycles(file, rows):
    """Append the per-cycle variables `rows` (a dataset) to the open h5netcdf `file`; a first row
    whose cycle is the file's last one replaces it."""
    for dim in set(CYCLE_DIMS) & set(rows.dims):
        held = file.dimensions[dim].size
        numbers = rows[dim].values
        spans = held and numbers.size and file.variables[dim][held - 1] == numbers[0]
        start = held - 1 if spans else held
        file.resize_dimension(dim, start + numbers.size)
        for name in _per_cycle(rows, (dim,)):
            stored, variable = file.variables[name], rows[name]
            stored[start : start + numbers.size] = variable.values.astype(stored.dtype)


def remove_temporaries(path: str | os.PathLike) -> list[Path]:
    """Delete the temporary files that `save` left beside `path` when its process was killed.

    Only names ``.NAME.<hex>.tmp`` of `path` itself go, not those of other files whose names start
    with NAME. The caller must know that no other process is saving to `path` (it holds the run's
    lock), or it would pull a live temporary from under that process.

    Returns
    -------
    list of Path
        The files deleted.
    """
    path = Path(path)
    pattern = re.compile(rf"\.{re.escape(path.name)}\.[0-9a-f]{{{2 * TOKEN_BYTES}}}\.tmp")
    stale = [found for found in path.parent.iterdir() if pattern.fullmatch(found.name)]
    for found in stale:
        found.unlink(missing_ok=True)
    return stale


def _write(result: xr.Dataset, temporary: Path, path: Path, wrote: str, fsync: bool = True) -> None:
    """Write `result` to the file `temporary`, as `cf_encoded` by `wrote`, and (`fsync`) flush it to disk;
    errors name `path`, the file asked for. Its `CYCLE_DIMS` are unlimited, in chunks of `CYCLE_CHUNK_ROWS` rows."""
    result, encoding = cf_encoded(result, wrote)
    for name, variable in result.variables.items():
        if variable.dtype.kind in "biuf":
            encoding.setdefault(name, {}).update(COMPRESSION)
    for name in _per_cycle(result):
        encoding.setdefault(name, {})["chunksizes"] = (CYCLE_CHUNK_ROWS, *result[name].shape[1:])
    image = io.BytesIO()
    with h5netcdf.File(
        image, "w"
    ) as file:  # in memory: not xarray's to_netcdf, whose lock under dask.distributed names a file
        result.dump_to_store(
            H5NetCDFStore(file, mode="w"), encoding=encoding, unlimited_dims=set(result.dims) & set(CYCLE_DIMS)
        )
    _put(image.getbuffer(), temporary, path, fsync)


def _put(image, temporary: Path, path: Path, fsync: bool) -> None:
    """Write the bytes `image` to the file `temporary` and (`fsync`) flush them to disk; errors name `path`.

    A file is formed in memory and written here, not by HDF5: a disk that fills or a folder that
    turns read-only then fails this write with the system's reason, where HDF5 would fail in the
    middle of its file and may take the process down as it closes it.
    """
    try:
        with open(temporary, "wb") as handle:
            handle.write(image)
            handle.flush()
            if fsync:
                os.fsync(handle.fileno())
    except OSError as error:
        raise OSError(error.errno, f"cannot write: {error.strerror or error}", str(path)) from None


def cf_encoded(dataset: xr.Dataset, wrote: str) -> tuple[xr.Dataset, dict[str, dict]]:
    """`dataset` as a file of `fretting` holds it, following the CF conventions (`CONVENTIONS`), and
    the encoding that keeps fill values off its coordinates. Every file is written through here.

    Parameters
    ----------
    dataset : xarray.Dataset
        A result, a stress field, a sweep or any dataset of `fretting`; not changed.
    wrote : str
        What writes it, for its ``history``: ``"fretting.save"``.

    Returns
    -------
    dataset : xarray.Dataset
        With the global attributes ``Conventions``, ``title`` (the dataset's own, else one said
        from what it is), ``source`` (fretting and its version) and ``references`` (the method);
        a line ``<time, ISO 8601 UTC> <wrote> (fretting <version>)`` appended to its ``history``;
        the units of `LEGACY_UNITS` spelled as now; its coordinates ``x`` and ``z`` with their
        `fretting.results.variables.AXES` attributes (``axis``, and ``positive`` for the depth), and
        a coordinate of `fretting.results.variables.VARIABLES` that has no long name with that
        entry's units and long name.
    encoding : dict
        Variable name -> ``{"_FillValue": None}`` for each coordinate variable (a variable named as
        its dimension), which CF forbids to have one; xarray gives one to floating-point variables.
    """
    dataset = with_current_units(dataset.copy())
    for name, attrs in AXES.items():
        if name in dataset.coords:
            dataset[name].attrs.update(attrs)
    for name in dataset.coords:
        if "long_name" not in dataset[name].attrs and name in VARIABLES:
            _, units, long_name = VARIABLES[name]
            dataset[name].attrs.update(units=units, long_name=long_name)
    time = dataset.attrs.get("created") or datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    line = f"{time} {wrote} (fretting {__version__})"
    history = dataset.attrs.get("history")
    dataset.attrs.update(
        Conventions=CONVENTIONS,
        title=dataset.attrs.get("title") or _title(dataset),
        source=f"fretting {__version__}",
        references=REFERENCES,
        history=f"{history}\n{line}" if history else line,
    )
    encoding = {name: {"_FillValue": None} for name in dataset.dims if name in dataset.variables}
    return dataset, encoding


def _title(dataset: xr.Dataset) -> str:
    """A title for `dataset`, which has none: of a result of `simulate`, a stress field (on depths ``z``), or other."""
    attrs = dataset.attrs
    if all(name in attrs for name in REQUIRED_ATTRIBUTES):
        return f"fretting result: {attrs['profile']} contact, {attrs['model']} model"
    if "z" in dataset.dims:
        return f"fretting stress field under the surface of body {attrs.get('body', '?')} ({attrs.get('role', '?')})"
    return "fretting dataset"


def _synced(temporary: Path, path: Path) -> None:
    """Flush the file `temporary` to disk; errors name `path`."""
    try:
        with open(temporary, "rb") as handle:
            os.fsync(handle.fileno())
    except OSError as error:
        raise OSError(error.errno, f"cannot write: {error.strerror or error}", str(path)) from error


def load(path: str | os.PathLike) -> xr.Dataset:
    """The result in a file written by `save`, read fully into memory; the file is closed on return.

    Raises the errors of `open_result`.

    Examples
    --------
    See `save`.
    """
    with open_result(path) as result, _reading(path):
        return result.load()


@contextlib.contextmanager
def _reading(path):
    """A block that reads the data of the file `path`: HDF5's errors (a damaged file: a chunk that
    does not inflate) become one `ResultError` naming it."""
    try:
        yield
    except (OSError, RuntimeError) as error:
        raise ResultError(f"{path}: found data that cannot be read ({_reason(error)}): the file is damaged") from None


def _reason(error):
    """The first line of HDF5's account of `error`, without the file and the time it names."""
    return (getattr(error, "strerror", None) or str(error)).splitlines()[0].split(" (file write failed")[0]


def open_result(path: str | os.PathLike) -> xr.Dataset:
    """The result in a file written by `save`, opened lazily: variables are read when used, and
    the file stays open until the dataset is closed (``with open_result(path) as result:``).

    Raises
    ------
    FileNotFoundError
        When there is no file at `path`.
    ResultError
        When it is not a result of `fretting`.
    """
    if not Path(path).is_file():
        raise FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), str(path))
    try:
        result = xr.open_dataset(path, engine=ENGINE)
    except OSError as error:
        raise ResultError(f"{path}: found no netCDF-4 data ({error}), expected a result of fretting") from None
    missing = [f"variable {name}" for name in REQUIRED_VARIABLES if name not in result.variables]
    missing += [f"attribute {name}" for name in REQUIRED_ATTRIBUTES if name not in result.attrs]
    if missing:
        result.close()
        raise ResultError(f"{path}: found no {missing[0]}, expected a result of fretting")
    return with_current_units(result)


def with_current_units(dataset: xr.Dataset) -> xr.Dataset:
    """`dataset` with the units of its variables spelled as they are now: those of `LEGACY_UNITS`
    replaced, in place (a lazily opened dataset stays open); the dataset is returned."""
    for variable in dataset.variables.values():
        units = variable.attrs.get("units")
        if isinstance(units, str) and units in LEGACY_UNITS:
            variable.attrs["units"] = LEGACY_UNITS[units]
    return dataset


def join_results(parts: Sequence[xr.Dataset]) -> xr.Dataset:
    """One result from the results of a run made in parts.

    Parameters
    ----------
    parts : sequence of xarray.Dataset
        Results of `simulate`: the first one of a history's first steps, each later one run with
        ``state=final_state(previous)`` on the slice of the history that starts at the previous
        one's last step. Each may record any of its steps.

    Returns
    -------
    xarray.Dataset
        The result of the uninterrupted run with the union of the recorded steps, bit for bit:
        a later part's step 0, which repeats the previous one's last step, is dropped; steps,
        vertex steps and cycles are numbered as in the whole history; a cycle that spans
        parts is taken from the last part that has it (its tally carries on from part to
        part), and the rows along ``field_cycle`` (each cycle's once) are concatenated; the
        state and the accumulated fields are the last part's. Attributes are the first part's, but
        the note of the cycles the model does not resolve, which is the whole run's
        (`fretting.results.notes.noted`).
    """
    joiner = Joiner()
    for part in parts:
        joiner.add(part)
    return noted(with_loops(joiner.result()))


class Joiner:
    """`join_results` of parts that arrive one at a time, holding each run of equal cycle rows once.

    A long run's per-cycle fields, cycles times nodes of them, outweigh the rest of its result, yet
    the cycles of a periodic state repeat them exactly. Each part's rows are taken into `_Rows` as
    the part is added, so the part itself need not be kept and a repeated row is held once;
    `result` expands them.
    """

    def __init__(self) -> None:
        self._pieces, self._vertices, self._end = [], {}, 0
        self._first_attrs, self._last = None, None
        self._rows, self._counts = {}, dict.fromkeys(CYCLE_DIMS, 0)

    def __len__(self) -> int:
        """Number of parts added."""
        return len(self._pieces)

    @property
    def cycles(self) -> int:
        """Cycles of the joined result so far."""
        return self._counts["cycle_number"]

    def rows(self, dim: str) -> int:
        """Rows along the per-cycle dimension `dim` (one of `CYCLE_DIMS`) of the joined result so far."""
        return self._counts[dim]

    @property
    def steps(self) -> int:
        """Steps of the joined result so far (its ``steps`` attribute)."""
        return self._end + 1

    def add(self, part: xr.Dataset) -> None:
        """Join `part`, which continues the parts added before (see `join_results`)."""
        per_cycle = _per_cycle(part)
        if self._last is not None:
            _check_continues(self._last, part)
        later = self._last is not None
        piece = part.isel(step=part.step.values > 0) if later else part
        stepwise = [name for name, variable in part.data_vars.items() if "step" in variable.dims]
        step = piece.step.variable.copy(data=piece.step.values + self._end)  # its attributes kept in any xarray
        self._pieces.append(piece[stepwise].assign_coords(step=step))
        self._add_vertices(part, later)
        self._end += part.attrs["steps"] - 1
        if self._first_attrs is None:
            self._first_attrs = part.attrs
        for dim in set(CYCLE_DIMS) & set(part.dims):
            self._add_rows(dim, {name: part[name].variable for name in _per_cycle(part, (dim,))})
        self._last = part.drop_vars(per_cycle)

    def _add_vertices(self, part: xr.Dataset, later: bool) -> None:
        """Take the per-vertex variables of `part` (``vertex_step``, the loads) into the run's; a
        later part's vertex at its step 0 is the previous part's last one, and is dropped."""
        steps = part.vertex_step.values
        kept = steps > 0 if later else np.ones(steps.size, dtype=bool)
        for name, variable in part.data_vars.items():
            if variable.dims == ("vertex",):
                values = variable.values[kept]
                self._vertices.setdefault(name, []).append(values + self._end if name == "vertex_step" else values)

    def _add_rows(self, dim: str, cycles: dict[str, xr.Variable]) -> None:
        """Take the per-cycle variables `cycles` (name -> xarray.Variable) along `dim` of a part into the run's rows."""
        numbers, count = cycles[dim].values, self._counts[dim]
        spans = count and numbers.size and self._rows[dim].last == numbers[0]  # the later row is whole
        start = count - 1 if spans else count
        for name, variable in cycles.items():
            self._rows.setdefault(name, _Rows(variable)).put(start, variable.values)
        self._counts[dim] = start + numbers.size

    def result(self) -> xr.Dataset:
        """The joined result of the parts added so far."""
        if self._last is None:
            raise ResultError("no results to join")
        zones = max(piece.sizes["zone"] for piece in self._pieces)
        joined = xr.concat(
            [piece.pad(zone=(0, zones - piece.sizes["zone"])) for piece in self._pieces],
            dim="step",
            data_vars="all",
            coords="minimal",
            compat="equals",
            join="exact",
            combine_attrs="override",
        )
        last = self._last
        rest = [name for name, variable in last.data_vars.items() if "step" not in variable.dims]
        joined = joined.assign({name: last[name] for name in rest})
        joined = joined.assign(
            {
                name: (last[name].dims, np.concatenate(values), last[name].attrs)
                for name, values in self._vertices.items()
            }
        )
        cycles = {name: rows.variable() for name, rows in self._rows.items()}
        return joined.assign(cycles).assign_attrs(self._first_attrs | {"steps": self._end + 1})


class _Rows:
    """The rows of one per-cycle variable of a run: each run of equal rows held once, and the
    index of every cycle's row among them."""

    def __init__(self, variable: xr.Variable) -> None:
        self._dims, self._attrs = variable.dims, variable.attrs
        self._distinct = np.empty((1, *variable.shape[1:]), dtype=variable.dtype)
        self._held = 0  # rows of _distinct in use
        self._index = np.empty(0, dtype=np.int64)

    @property
    def last(self) -> np.ndarray:
        """The row of the last cycle held."""
        return self._distinct[self._index[-1]]

    def put(self, start: int, values: np.ndarray) -> None:
        """Rows `values` for the cycles from number `start` (counted from 0) on, replacing any held there."""
        replaced = self._index[start:]
        if replaced.size and replaced[0] == self._held - 1 and (start == 0 or self._index[start - 1] != replaced[0]):
            self._held -= 1  # the replaced row was the last one taken and no earlier cycle has it
        changed = np.ones(len(values), dtype=bool)
        if len(values) > 1:
            changed[1:] = (values[1:] != values[:-1]).reshape(len(values) - 1, -1).any(axis=1)
        if start and len(values):
            changed[0] = not np.array_equal(values[0], self._distinct[self._index[start - 1]])
        new = values[changed]
        if self._held + len(new) > len(self._distinct):
            grown = np.empty((max(self._held + len(new), 2 * len(self._distinct)), *values.shape[1:]), values.dtype)
            grown[: self._held] = self._distinct[: self._held]
            self._distinct = grown
        self._distinct[self._held : self._held + len(new)] = new
        index = self._held - 1 + np.cumsum(changed)  # row held - 1 is cycle start - 1's
        self._held += len(new)
        self._index = np.concatenate([self._index[:start], index])

    def variable(self) -> xr.Variable:
        """The rows of every cycle, as an xarray.Variable."""
        return xr.Variable(self._dims, self._distinct[self._index], self._attrs)


def _check_continues(previous: xr.Dataset, part: xr.Dataset) -> None:
    """Refuse `part` unless it starts where `previous` ends (checked where its step 0 is recorded)."""
    end = float(previous.state_Q), float(previous.state_sigma)
    if 0 in part.step.values:
        start = float(part.Q.sel(step=0)), float(part.sigma.sel(step=0))
        if start != end:
            raise ResultError(f"a part starts at (Q, sigma) = {start}, not where the previous one ends, {end}")


def provenance() -> dict[str, str]:
    """Attributes that say when and with what a result was written.

    Returns
    -------
    dict
        ``created``: the time, ISO 8601 in UTC; ``versions``: a JSON object of the versions of
        Python, HDF5 and the packages of `DEPENDENCIES`.
    """
    versions = {"python": platform.python_version(), "hdf5": h5py.version.hdf5_version}
    versions |= {name: _version(name) for name in DEPENDENCIES}
    created = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    return {"created": created, "versions": json.dumps(versions)}


def _version(distribution: str) -> str:
    try:
        return importlib.metadata.version(distribution)
    except importlib.metadata.PackageNotFoundError:  # run from a source tree
        return "not installed"


def source_attributes(source: HistorySource) -> dict[str, str]:
    """Attributes that record the history file a result was run from.

    Parameters
    ----------
    source : fretting.loading.history_file.HistorySource

    Returns
    -------
    dict
        ``history_file`` (its `recorded_path`), ``history_toml`` (its text) and ``history_sha256``.
    """
    return {"history_file": recorded_path(source.path), "history_toml": source.text, "history_sha256": source.sha256}


def recorded_path(path: str | os.PathLike) -> str:
    """`path` as a file records it: as given when relative, else its name alone, so that a file says
    nothing of the folders of the machine that wrote it (the text and digest it records beside the
    name say which file it was).

    Examples
    --------
    >>> recorded_path("runs/shear.toml"), recorded_path("/home/someone/runs/shear.toml")
    ('runs/shear.toml', 'shear.toml')
    """
    path = Path(path)
    return path.as_posix() if not path.is_absolute() else path.name
