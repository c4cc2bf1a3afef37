"""Validators for the public constructors: each returns the cleaned value or raises ValueError."""

import math

import numpy as np


def positive(name, value):
    """Return `value` as a float, or raise if it is not a finite number > 0."""
    number = finite(name, value)
    if number <= 0:
        raise ValueError(f"{name} must be > 0, found {value!r}")
    return number


def finite(name, value):
    """Return `value` as a float, or raise if it is not a finite real number."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"{name} must be a number, found {value!r}")
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, found {value!r}")
    return number


def finite_array(name, values, ndim=1):
    """Return `values` as a float array of `ndim` dimensions with finite entries."""
    try:
        array = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of numbers, found {values!r}") from None
    if array.ndim != ndim:
        raise ValueError(f"{name} must be {ndim}-dimensional, found shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise ValueError(f"{name} must hold finite numbers only")
    return array
