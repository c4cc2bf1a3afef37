"""Result files: datasets written through xarray and h5netcdf, compressed, and replaced atomically.

The files are netCDF-4 (HDF5), readable by h5py, xarray and the netCDF tools.
"""

import datetime
import errno
import importlib.metadata
import json
import os
import platform
import secrets
from pathlib import Path

import h5py
import numpy as np
import xarray as xr

from fretting.errors import FrettingError

__all__ = ["ENGINE", "Joiner", "ResultError", "join_results", "load", "provenance", "save", "source_attributes"]

#: The xarray backend, named explicitly so that files never depend on what else is installed.
ENGINE = "h5netcdf"

#: zlib level 4 with byte shuffling. On results/hertz_shear_cycling.h5 level 9 saves 0.7 % of the
#: bytes (1.99 MB) and takes 1.3 times as long (0.107 s against 0.081 s).
COMPRESSION = {"zlib": True, "complevel": 4, "shuffle": True}

#: Distributions whose versions a result records.
DEPENDENCIES = ("fretting", "numpy", "scipy", "xarray", "h5netcdf", "h5py")

#: Variables and attributes that every result has.
REQUIRED_VARIABLES = ("Q", "sigma", "p", "q", "slip", "stick", "dissipation", "delta_Q", "vertex_step", "state_slip")
REQUIRED_ATTRIBUTES = ("a", "centre", "p0", "E_star", "f", "P", "profile", "model", "nodes", "steps")


class ResultError(FrettingError, ValueError):
    """A file is not a result of `fretting`, or results do not join."""


def save(result, path):
    """Write a result to a netCDF-4 file, atomically.

    The dataset goes to a temporary file in the same directory, is flushed to disk and then
    renamed over `path`: an existing file at `path` is replaced whole or left untouched.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `simulate`; `provenance` attributes are added to it in the file.
    path : str or os.PathLike
        Output file; its directory is created if needed.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(f".{path.name}.{secrets.token_hex(6)}.tmp")
    try:
        _write(result.assign_attrs(provenance()), temporary, path)
        os.replace(temporary, path)
    finally:
        temporary.unlink(missing_ok=True)


def _write(result, temporary, path):
    """Write `result` to the file `temporary` and flush it to disk; errors name `path`, the file asked for."""
    encoding = {name: COMPRESSION for name, variable in result.variables.items() if variable.dtype.kind in "biuf"}
    try:
        result.to_netcdf(temporary, engine=ENGINE, encoding=encoding)
        with open(temporary, "rb") as handle:
            os.fsync(handle.fileno())
    except OSError as error:
        raise OSError(error.errno, f"cannot write: {error.strerror or error}", str(path)) from error


def load(path):
    """The result in a file written by `save`, read fully into memory; the file is closed on return.

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
        result = xr.load_dataset(path, engine=ENGINE)
    except OSError as error:
        raise ResultError(f"{path}: found no netCDF-4 data ({error}), expected a result of fretting") from None
    missing = [f"variable {name}" for name in REQUIRED_VARIABLES if name not in result.variables]
    missing += [f"attribute {name}" for name in REQUIRED_ATTRIBUTES if name not in result.attrs]
    if missing:
        raise ResultError(f"{path}: found no {missing[0]}, expected a result of fretting")
    return result


def join_results(parts):
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
        part); the state is the last part's. Attributes are the first part's.
    """
    joiner = Joiner()
    for part in parts:
        joiner.add(part)
    return joiner.result()


class Joiner:
    """`join_results` of parts that arrive one at a time, holding each cycle's fields once.

    A long run's per-cycle fields outweigh the rest of its result (10^5 cycles of ``w`` and
    ``slip_amplitude`` at 384 nodes: 307 MB), so each part's rows are copied into arrays for
    the whole run as the part is added, and the part itself need not be kept.

    Parameters
    ----------
    cycles : int
        Rows to allocate at first (the history's cycle count); the arrays grow if more arrive.
    """

    def __init__(self, cycles=0):
        self._capacity = cycles
        self._pieces, self._vertices, self._end = [], [], 0
        self._first_attrs, self._last = None, None
        self._rows, self._numbers, self._count = {}, None, 0

    def __len__(self):
        """Number of parts added."""
        return len(self._pieces)

    def add(self, part):
        """Join `part`, which continues the parts added before (see `join_results`)."""
        per_cycle = [name for name, variable in part.variables.items() if "cycle_number" in variable.dims]
        if self._last is not None:
            _check_continues(self._last, part)
        later = self._last is not None
        piece = part.isel(step=part.step.values > 0) if later else part
        stepwise = [name for name, variable in part.data_vars.items() if "step" in variable.dims]
        self._pieces.append(piece[stepwise].assign_coords(step=piece.step + self._end))
        vertex_step = part.vertex_step.values
        self._vertices.append((vertex_step[vertex_step > 0] if later else vertex_step) + self._end)
        self._end += part.attrs["steps"] - 1
        if self._first_attrs is None:
            self._first_attrs = part.attrs
        if per_cycle:
            self._add_rows({name: part[name].variable for name in per_cycle})
        self._last = part.drop_vars(per_cycle)

    def _add_rows(self, cycles):
        """Copy the per-cycle variables `cycles` (name -> xarray.Variable) of a part into the run's rows."""
        numbers = cycles["cycle_number"].values
        spans = self._count and numbers.size and self._numbers[self._count - 1] == numbers[0]  # the later row is whole
        start = self._count - 1 if spans else self._count
        stop = start + numbers.size
        if not self._rows or stop > self._numbers.size:
            self._grow(cycles, max(stop, 2 * self._count, self._capacity))
        for name, variable in cycles.items():
            self._rows[name][2][start:stop] = variable.values
        self._count = stop

    def _grow(self, cycles, size):
        """Room for `size` rows in every per-cycle array, keeping the rows held so far."""
        for name, variable in cycles.items():
            rows = np.empty((size, *variable.shape[1:]), dtype=variable.dtype)
            if name in self._rows:
                rows[: self._count] = self._rows[name][2][: self._count]
            self._rows[name] = (variable.dims, variable.attrs, rows)
        self._numbers = self._rows["cycle_number"][2]

    def result(self):
        """The joined result of the parts added so far; its per-cycle arrays are views of the joiner's
        own, valid until the next `add`.
        """
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
            vertex_step=(last.vertex_step.dims, np.concatenate(self._vertices), last.vertex_step.attrs)
        )
        cycles = {
            name: xr.Variable(dims, rows[: self._count], attrs) for name, (dims, attrs, rows) in self._rows.items()
        }
        return joined.assign(cycles).assign_attrs(self._first_attrs | {"steps": self._end + 1})


def _check_continues(previous, part):
    """Refuse `part` unless it starts where `previous` ends (checked where its step 0 is recorded)."""
    end = float(previous.state_Q), float(previous.state_sigma)
    if 0 in part.step.values:
        start = float(part.Q.sel(step=0)), float(part.sigma.sel(step=0))
        if start != end:
            raise ResultError(f"a part starts at (Q, sigma) = {start}, not where the previous one ends, {end}")


def provenance():
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


def _version(distribution):
    try:
        return importlib.metadata.version(distribution)
    except importlib.metadata.PackageNotFoundError:  # run from a source tree
        return "not installed"


def source_attributes(source):
    """Attributes that record the history file a result was run from.

    Parameters
    ----------
    source : fretting.history_file.HistorySource

    Returns
    -------
    dict
        ``history_file`` (its path as given), ``history_toml`` (its text) and ``history_sha256``.
    """
    return {"history_file": str(source.path), "history_toml": source.text, "history_sha256": source.sha256}
