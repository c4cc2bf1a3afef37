"""Rainflow decomposition of a load history, with the energy dissipated in each counted cycle.

The cycles are those of ASTM E1049-85 (2011), section 5.4.4, as counted by the `rainflow`
package: each has a range, a mean, a count (1 for a closed loop, 0.5 for a half cycle) and the
indices of the two reversals that bound it.

Energy per counted cycle (the definition used here). Every increment's dissipation belongs to
the branch of the load path that it lies on:

- a **full cycle** with reversals at steps ``i < j`` owns its closed hysteresis loop: the
  increments from ``i`` to ``j`` (its first half) and from ``j`` until the load first returns to
  its value at ``i`` (its second half);
- a **half cycle** owns the increments from its first reversal to its second;

in both cases less the increments of the loops nested inside (counted as cycles of their own).
The increment in which a loop closes usually straddles the closing value: the loop gets the
part of it that makes its second half dissipate what its first half did (Masing's rule, below),
kept between nothing and the whole increment; when the load reaches the closing value exactly
at a step, the loop gets the whole increment. The rest goes on to the branch that continues.
The energies of the counted cycles add up to the dissipation of the series (steps 1 onwards).

Exact or approximate. For Q alone (sigma zero at every step) the memory rules of Masing and
Jaeger hold: from a reversal the change of traction is -2 times the monotonic one of half the
load change, and a closed loop restores the state it started from (Mindlin & Deresiewicz,
J. Appl. Mech. 20 (1953) 327-344; Jaeger, J. Tribol. 120 (1998) 677-684, who state them for
symmetric profiles; the engine obeys them to rounding on asymmetric ones too, see
tests/analysis/test_counting.py). Every full cycle of range ``DeltaQ`` then dissipates exactly the
energy of constant-amplitude cycling of that range, whatever its mean and whatever surrounds
it, and the decomposition is exact. With sigma it is an approximation: the state at a reversal
then depends on more than the counted load (beyond the Nowell-Hills regime
``|sigma| / (f p0) <= 2 |Q| / (f P)``, where slip reverses at one end, loops are not scaled
virgin curves), and on non-proportional paths the reversals of Q and sigma
differ while the counting follows one of them. Measured against ``4 D(DeltaQ / 2)`` along the
path's direction (random histories, 64 nodes): proportional paths ``sigma / (f p0) = k Q / (f P)``
keep the rule for ``|k| <= 2`` (regime A;
tests/analysis/test_counting.py::test_proportional_loads_in_regime_A_keep_the_rule) and nearly for
``|k| <= 3``; with a sigma mean, or where Q reverses and sigma does not, a small loop can be off
by a factor of two or more.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
import rainflow
import xarray as xr
from numpy.typing import ArrayLike

__all__ = ["counted_energy", "rainflow_cycles"]

#: Resolution of the counting, relative to the largest |load|: loads are rounded to it first.
#: The counting's reversal test multiplies two load differences, which underflows for
#: differences below 1e-154 and then pairs points that do not alternate; rounding turns such
#: rounding-level wiggles into plateaus. Loops narrower than this are not counted (their
#: energy, which falls like the cube of the range, stays with the loop around them).
RESOLUTION = 1e-12


def rainflow_cycles(series: ArrayLike) -> xr.Dataset:
    """Rainflow cycles of a series (ASTM E1049-85 section 5.4.4, `rainflow.extract_cycles`).

    Parameters
    ----------
    series : array_like, shape (n,)
        Load at each step, e.g. ``result.Q.values``.

    Returns
    -------
    xarray.Dataset
        Dim ``counted``, in the order the counting finds them: ``load_range``, ``load_mean``,
        ``cycle_count`` (1 or 0.5), ``start`` and ``end`` (indices of the two reversals, ``start < end``).
        The reversals are found on the loads rounded to `RESOLUTION` of the largest; ranges and
        means are those of the loads themselves at the reversals.
    """
    values = np.asarray(series, dtype=float)
    if values.ndim != 1:
        raise ValueError(f"series must be 1-dimensional, found shape {values.shape}")
    scale = np.abs(values).max(initial=0.0) or 1.0
    cycles = list(rainflow.extract_cycles(np.round(values / scale / RESOLUTION) * RESOLUTION))
    columns = np.array(cycles, dtype=float).reshape(-1, 5).T
    start, end = columns[3].astype(np.int64), columns[4].astype(np.int64)
    first, second = values[start], values[end]
    data = {
        "load_range": ("counted", np.abs(second - first), {"long_name": "range of the counted cycle"}),
        "load_mean": ("counted", (first + second) / 2, {"long_name": "mean of the counted cycle"}),
        "cycle_count": ("counted", columns[2], {"units": "1", "long_name": "1: full cycle, 0.5: half cycle"}),
        "start": ("counted", start, {"units": "1", "long_name": "index of the first reversal"}),
        "end": ("counted", end, {"units": "1", "long_name": "index of the second reversal"}),
    }
    return xr.Dataset(data, attrs={"method": "rainflow counting, ASTM E1049-85 (2011) section 5.4.4"})


def _closing(load: np.ndarray, start: int, end: int) -> tuple[int, float]:
    """Increment in which the load, after the reversal `end`, first returns to its value at `start`.

    Returns
    -------
    step : int
        The step that ends that increment.
    u : float
        Fraction of the increment's load change before the closing value, in (0, 1]: 1 when
        the load reaches it at `step` (to `RESOLUTION`).
    """
    level, direction = load[start], np.sign(load[start] - load[end])
    tolerance = RESOLUTION * np.abs(load).max()
    after = (load[end + 1 :] - level) * direction
    beyond = np.flatnonzero(after >= -tolerance)
    if direction == 0 or not beyond.size:  # a loop of no range, or one left open: closed at once
        return end, 1.0
    step = end + 1 + beyond[0]
    if after[beyond[0]] <= tolerance:
        return step, 1.0
    return step, float((level - load[step - 1]) / (load[step] - load[step - 1]))


@dataclass
class _Loop:
    """A full cycle being assigned its energy: first reversal, reversal, closing increment, shares."""

    start: int
    end: int
    step: int
    u: float
    share: float = 0.0  # dissipation of the closing increment inside the loop [J/m]
    total: float = 0.0  # dissipation inside the loop, nested loops included [J/m]
    own: float = 0.0  # its own energy [J/m]


def _loop_energies(loops: Iterable[_Loop], C: np.ndarray, D: np.ndarray) -> list[_Loop]:
    """Fill in each loop's share of its closing increment, total and own energy.

    `C` is the cumulative dissipation at the steps, `D` the dissipation of each increment. Loops
    are taken inner first (by closing increment, then latest start); the loops already done
    that start after a loop's first reversal are nested in it.
    """
    done = []  # loops not yet nested in another, by increasing start
    for loop in sorted(loops, key=lambda loop: (loop.step, -loop.start)):
        children = []
        while done and done[-1].start > loop.start:
            children.append(done.pop())
        first = sum(c.total for c in children if c.start < loop.end)
        second = sum(c.total for c in children if c.start >= loop.end)
        if loop.u == 1.0:
            loop.share = D[loop.step]
        else:
            masing = (C[loop.end] - C[loop.start] - first) - (C[loop.step - 1] - C[loop.end] - second)
            least = max((c.share for c in children if c.step == loop.step), default=0.0)
            loop.share = float(np.clip(masing, least, D[loop.step]))
        loop.total = C[loop.step - 1] - C[loop.start] + loop.share
        loop.own = loop.total - first - second
        done.append(loop)
    return done


def counted_energy(result: xr.Dataset, load: str = "Q") -> xr.Dataset:
    """Rainflow cycles of a load of a result and the energy dissipated in each (module docstring).

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation` recorded at every step.
    load : {"Q", "sigma"}
        The load whose reversals are counted.

    Returns
    -------
    xarray.Dataset
        `rainflow_cycles` of the load with steps for indices (``start``, ``end``), plus
        ``closing`` (fractional step where a full cycle's loop closes, NaN for half cycles) and
        ``energy`` [J/m]. Attribute ``decomposition``: "exact" (Q alone) or "approximate" (sigma
        present), with the reason. The energies add up to the dissipation of steps 1 onwards.

    Raises
    ------
    ValueError
        When some steps were not recorded (their loads and dissipation are needed).
    """
    if load not in ("Q", "sigma"):
        raise ValueError(f"load must be 'Q' or 'sigma', found {load!r}")
    steps = result.step.values
    if steps[0] != 0 or np.any(np.diff(steps) != 1):
        raise ValueError("counting needs every step recorded: run with record=None (the default for short runs)")
    series = result[load].values
    cycles = rainflow_cycles(series)
    start, end, full = cycles.start.values, cycles.end.values, cycles.cycle_count.values == 1
    D = result.dissipation.values
    C = np.cumsum(D)
    loops = [_Loop(i, j, *_closing(series, i, j)) for i, j in zip(start[full], end[full], strict=True)]
    outermost = _loop_energies(loops, C, D)
    energy = np.zeros(start.size)
    energy[full] = [loop.own for loop in loops]
    closing = np.full(start.size, np.nan)
    closing[full] = [loop.step - 1 + loop.u for loop in loops]
    for k in np.flatnonzero(~full):
        nested = sum(loop.total for loop in outermost if start[k] <= loop.start < end[k])
        energy[k] = C[end[k]] - C[start[k]] - nested
    exact = load == "Q" and not np.any(result.sigma.values)
    reason = "Q alone: Masing/Jaeger memory rules" if exact else "sigma present: loops depend on more than the range"
    units = {"Q": "N/m", "sigma": "Pa"}[load]
    cycles.load_range.attrs["units"] = cycles.load_mean.attrs["units"] = units
    definition = (
        "dissipation of the increments on the cycle's own branches (full cycle: its closed loop; half cycle: "
        "its reversal-to-reversal branch), less the loops nested inside"
    )
    return cycles.assign(
        closing=("counted", closing, {"units": "1", "long_name": "step at which a full cycle's loop closes"}),
        energy=(
            "counted",
            energy,
            {"units": "J/m", "long_name": "energy of the counted cycle", "definition": definition},
        ),
    ).assign_attrs(load=load, decomposition=f"{'exact' if exact else 'approximate'} ({reason})")
