"""Validators for the public constructors: each returns the cleaned value or raises ValueError.

A value may be a quantity with units (a `pint` Quantity, or any object with ``to(unit)`` and
``magnitude``, as pint's and its kin give): it is converted to the SI `unit` the parameter is in,
so ``fr.Hertz(R=50 * ureg.mm)`` is ``fr.Hertz(R=0.05)``, and a quantity of another dimension is
refused. Plain numbers are taken in SI units, as everywhere in fretting.
"""

import math

import numpy as np


def positive(name, value, unit="1"):
    """Return `value` as a float in `unit` (SI), or raise if it is not a finite number > 0."""
    number = finite(name, value, unit)
    if number <= 0:
        raise ValueError(f"{name} must be > 0, found {value!r}")
    return number


def finite(name, value, unit="1"):
    """Return `value` as a float in `unit` (SI), or raise if it is not a finite real number."""
    value = in_unit(name, value, unit)
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"{name} must be a number, found {value!r}")
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, found {value!r}")
    return number


def finite_array(name, values, ndim=1, unit="1"):
    """Return `values` as a float array in `unit` (SI) of `ndim` dimensions with finite entries.

    `values` may be an array quantity (``[10, 20] * ureg("kN/m")``) or a sequence of quantities.
    """
    array = array_in_unit(name, values, unit)
    if array.ndim != ndim:
        raise ValueError(f"{name} must be {ndim}-dimensional, found shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must hold finite numbers only")
    return array


def array_in_unit(name, values, unit):
    """`values` (numbers, an array quantity, or a sequence of numbers and quantities) as a float
    array in `unit` (SI); NaN and infinite entries are kept."""
    if isinstance(values, (list, tuple)):
        values = [in_unit(name, value, unit) for value in values]
    else:
        values = in_unit(name, values, unit)
    try:
        return np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of numbers, found {values!r}") from None


def in_unit(name, value, unit):
    """The magnitude of `value` in `unit` where it is a quantity with units (module docstring), else `value`."""
    if not (hasattr(value, "magnitude") and hasattr(value, "to")):
        return value
    try:
        return value.to(unit).magnitude
    except Exception:  # the quantity library's own error: a dimension that does not convert
        expected = (
            "a dimensionless number" if unit == "1" else f"a number in {unit} (SI) or a quantity in units of {unit}"
        )
        raise ValueError(f"{name} must be {expected}, found {value}") from None
