"""Tables of a result for spreadsheets and pandas: a row per load cycle or per recorded step, as CSV.

The CSV file opens with comment lines (``#``): what it was taken from, then one line per column
with its units and meaning; then a header row of the column names and a row of numbers per cycle
or step. ``pandas.read_csv(path, comment="#")`` reads it (every digit from pandas 3.1 on); a
spreadsheet shows the comments as the first rows. Numbers are written in the shortest
form that reads back to the same value of their type (float64, or float32 for the fields stored
in single precision).
"""

import csv
import os
from pathlib import Path

import numpy as np
import xarray as xr

from fretting.results.io import CYCLE_DIMS

__all__ = ["cycle_table", "step_table", "write_csv"]


def cycle_table(result: xr.Dataset) -> xr.Dataset:
    """The result's quantities of each load cycle, one row per cycle (dim ``cycle_number``).

    The variables of the cycle alone (the energy dissipated in it, whether it was copied) and,
    for each field stored per cycle along x (``w``, ``slip_amplitude``, the peaks), its largest
    value over x, named ``<field>_max``: NaN for a cycle whose fields the run's ``cycle_fields``
    policy did not store.

    Raises
    ------
    ValueError
        When the result counts no load cycles.
    """
    if not result.sizes.get("cycle_number"):
        raise ValueError("found no load cycles, expected a result of a history with cycles (or the per-step table)")
    columns = {name: variable for name, variable in result.data_vars.items() if variable.dims == ("cycle_number",)}
    for name, variable in result.data_vars.items():
        if len(variable.dims) == 2 and variable.dims[0] in CYCLE_DIMS and variable.dims[1] == "x":
            largest = variable.max("x").rename({variable.dims[0]: "cycle_number"})
            largest = largest.reindex(cycle_number=result.cycle_number, fill_value=np.nan).astype(variable.dtype)
            attrs = variable.attrs
            largest.attrs = {"units": attrs.get("units", "1"), "long_name": f"largest over x of: {attrs['long_name']}"}
            columns[f"{name}_max"] = largest
    return xr.Dataset(columns, coords={"cycle_number": result.cycle_number})


def step_table(result: xr.Dataset) -> xr.Dataset:
    """The result's loads and scalars of each recorded step, one row per step (dim ``step``): the
    variables whose only dimension is ``step`` (``Q``, ``sigma``, the energy dissipated, ...)."""
    columns = {name: variable for name, variable in result.data_vars.items() if variable.dims == ("step",)}
    return xr.Dataset(columns, coords={"step": result.step})


def write_csv(table: xr.Dataset, path: str | os.PathLike, source: str = "") -> None:
    """Write `table` (one dimension: its coordinate the first column) as the CSV file at `path`.

    `source` says in the first comment line what the table was taken from. The file is written
    beside `path` and renamed into place: an interrupted write leaves no partial file.
    """
    (dim,) = table.dims
    columns = {dim: table[dim].variable, **{name: variable.variable for name, variable in table.data_vars.items()}}
    path = Path(path)
    temporary = path.with_name(f".{path.name}.tmp")
    try:
        with temporary.open("w", newline="", encoding="utf-8") as handle:
            handle.write(f"# {source or 'fretting table'}: one row per {dim.replace('_number', '')}\n")
            for name, variable in columns.items():
                handle.write(f"# {name} [{variable.attrs.get('units', '1')}]: {variable.attrs.get('long_name', '')}\n")
            rows = csv.writer(handle)
            rows.writerow(columns)
            values = [variable.values for variable in columns.values()]
            for row in zip(*values, strict=True):
                rows.writerow([_cell(value) for value in row])
        temporary.replace(path)
    finally:
        temporary.unlink(missing_ok=True)


def _cell(value):
    """`value` (a NumPy scalar) as text that reads back to it: the shortest form of its own type."""
    if isinstance(value, np.floating) and np.isnan(value):
        return "nan"
    return str(value.item()) if isinstance(value, (np.bool_, np.integer)) else str(value)
