"""Result files: datasets written through xarray and h5netcdf, compressed, and replaced atomically.

The files are netCDF-4 (HDF5), readable by h5py, xarray and the netCDF tools.
"""

import datetime
import errno
import importlib.metadata
import itertools
import json
import os
import platform
import secrets
from pathlib import Path

import h5py
import numpy as np
import xarray as xr

from fretting.errors import FrettingError

__all__ = ["ENGINE", "ResultError", "join_results", "load", "provenance", "save", "source_attributes"]

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
    parts = list(parts)
    if not parts:
        raise ResultError("no results to join")
    pieces, vertices, end = [], [], 0
    for number, part in enumerate(parts):
        if number:
            _check_continues(parts[number - 1], part)
        piece = part.isel(step=part.step.values > 0) if number else part
        pieces.append(piece.assign_coords(step=piece.step + end))
        vertex_step = part.vertex_step.values
        vertices.append((vertex_step[vertex_step > 0] if number else vertex_step) + end)
        end += part.attrs["steps"] - 1
    stepwise = [name for name, variable in parts[0].data_vars.items() if "step" in variable.dims]
    zones = max(part.sizes["zone"] for part in parts)
    joined = xr.concat(
        [piece[stepwise].pad(zone=(0, zones - piece.sizes["zone"])) for piece in pieces],
        dim="step",
        data_vars="all",
        coords="minimal",
        compat="equals",
        join="exact",
        combine_attrs="override",
    )
    last = parts[-1]
    rest = [name for name, variable in last.data_vars.items() if not {"step", "cycle_number"} & set(variable.dims)]
    joined = joined.assign({name: last[name] for name in rest})
    joined = joined.assign(vertex_step=(last.vertex_step.dims, np.concatenate(vertices), last.vertex_step.attrs))
    if "cycle_number" in last.dims:
        per_cycle = [name for name, variable in last.data_vars.items() if "cycle_number" in variable.dims]
        pieces = [_before(part[per_cycle], later) for part, later in itertools.pairwise(parts)] + [last[per_cycle]]
        cycles = xr.concat(pieces, dim="cycle_number", combine_attrs="override")
        joined = joined.assign(cycles.variables)
    return joined.assign_attrs(steps=end + 1)


def _before(cycles, later):
    """`cycles` without a last cycle that the `later` part carries on (its tally there is the whole)."""
    numbers, following = cycles.cycle_number.values, later.cycle_number.values
    spans = numbers.size and following.size and numbers[-1] == following[0]
    return cycles.isel(cycle_number=slice(0, -1)) if spans else cycles  # a slice: a view, not a copy


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
