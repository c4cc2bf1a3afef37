"""The load cycles recorded whole in a result, and the fretting loop of each (docs/guide/displacement.md).

A rig that imposes ``+-delta*`` records, cycle by cycle, the loop of ``Q`` against ``delta``;
`with_loops` reduces each loop whose steps a result holds to the numbers of Fouvry, Kapsa &
Vincent (1995): the amplitudes ``Q*`` and ``delta*``, the opening ``2 delta_0`` at ``Q = 0``, the
energy ratio ``A = E_d / (4 Q* delta*)``, the sliding ratio ``B = delta_0 / delta*`` and the
regime of the cycle (the variables ``LOOP_VARIABLES`` of `fretting.results.variables`). They are
read from the recorded steps only, so that a result joined from parts has those of the run in one
piece, bit for bit; a cycle whose steps are not all recorded has NaN (and regime -1).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from fretting.results.variables import variable

__all__ = ["LOOP_VARIABLES", "complete_cycles", "loop_rows", "recorded_loops", "with_loops"]

#: The per-cycle variables of the loop (`VARIABLES`), where the result records ``delta``.
LOOP_VARIABLES = ("Q_amplitude", "delta_amplitude", "loop_opening", "energy_ratio", "sliding_ratio", "cycle_regime")


def _last_step(result: xr.Dataset) -> int:
    """Last step of the run (recorded or not)."""
    if "steps" in result.attrs:
        return int(result.attrs["steps"]) - 1
    return int(result.vertex_step.max())


def _recorded_rows(result: xr.Dataset) -> dict[int, tuple[int, int]]:
    """Recorded rows of each cycle: ``{number: (first row, last row)}`` for the cycles with a recorded step."""
    cycle = result.cycle.values
    inside = np.flatnonzero(cycle > 0)
    if not inside.size:
        return {}
    numbers, first = np.unique(cycle[inside], return_index=True)  # non-zero cycle numbers never decrease
    last = np.append(first[1:], inside.size) - 1
    return {int(n): (int(i), int(j)) for n, i, j in zip(numbers, inside[first], inside[last], strict=True)}


def _whole(result: xr.Dataset) -> dict[int, slice]:
    """``{number: rows}`` of the cycles recorded whole: the rows of the recorded steps from the step
    before the cycle's first increment (its starting state) to its last step."""
    steps, last = result.step.values, _last_step(result)
    rows = {}
    for number, (i, j) in _recorded_rows(result).items():
        contiguous = steps[j] - steps[i] == j - i and i > 0 and steps[i - 1] == steps[i] - 1
        closed = steps[j] == last or (j + 1 < steps.size and steps[j + 1] == steps[j] + 1)
        if contiguous and closed:
            rows[number] = slice(i - 1, j + 1)
    return rows


def complete_cycles(result: xr.Dataset) -> list[slice | None]:
    """Rows of the recorded steps that cover each load cycle whole.

    Parameters
    ----------
    result : xarray.Dataset
        A result of `fretting.engine.simulation` with load cycles.

    Returns
    -------
    list of slice or None
        One entry per cycle (in `cycle_number` order): the rows of the recorded steps from the
        step before the cycle's first increment (its starting state) to its last step, when
        all of them are recorded; None when some are not.
    """
    if "cycle_number" not in result.dims or result.sizes["cycle_number"] == 0:
        raise ValueError("the result has no load cycles: its history counts none")
    rows = _whole(result)
    return [rows.get(int(number)) for number in result.cycle_number.values]


def recorded_loops(steps: xr.Dataset) -> dict[int, tuple[float, float, float, int]] | None:
    """``{number: (Q* [N/m], delta* [m], opening [m], regime)}`` of each cycle recorded whole in
    `steps` (a result's recorded steps: ``Q``, ``delta``, ``regime``, ``cycle``, ``step``); None
    where they record no ``delta`` (the contact has no datum) or no cycles.

    ``Q*`` and ``delta*`` are half the ranges of ``Q`` and ``delta`` over the cycle and its starting
    state; the opening is the distance between the loop's two crossings of ``Q = 0`` (`_opening`);
    the regime is the largest of its increments' (`fretting.results.variables.REGIMES`).
    """
    if "delta" not in steps or "cycle" not in steps:
        return None
    Q, delta, regime = steps.Q.values, steps.delta.values, steps.regime.values
    return {
        number: (np.ptp(Q[row]) / 2, np.ptp(delta[row]) / 2, _opening(Q[row], delta[row]), int(regime[row][1:].max()))
        for number, row in _whole(steps).items()
    }


def loop_rows(loops: dict, numbers: np.ndarray, energy: np.ndarray) -> dict[str, xr.Variable]:
    """The `LOOP_VARIABLES` of the cycles `numbers` whose energies [J/m] are `energy`, from the
    `recorded_loops` `loops` (NaN and regime -1 for a cycle not among them)."""
    found = np.array([loops.get(int(number), _UNRECORDED) for number in numbers], dtype=float).reshape(-1, 4)
    Q_star, delta_star, opening, regime = found.T
    data = {
        "Q_amplitude": Q_star,
        "delta_amplitude": delta_star,
        "loop_opening": opening,
        "cycle_regime": regime.astype(np.int8),
    }
    with np.errstate(divide="ignore", invalid="ignore"):  # a cycle that does not move: A and B undefined
        data["energy_ratio"] = energy / (4 * Q_star * delta_star)  # Fouvry's A
        data["sliding_ratio"] = opening / 2 / delta_star  # Fouvry's B
    return {name: variable(name, values) for name, values in data.items()}


#: The loop of a cycle not recorded whole.
_UNRECORDED = (np.nan, np.nan, np.nan, -1)


def with_loops(result: xr.Dataset, loops: dict | None = None) -> xr.Dataset:
    """`result` with the `LOOP_VARIABLES` of its cycles, from `loops` (the `recorded_loops` of the
    run's recorded steps; default those of `result`'s own steps); `result` as it is where there
    are none (no ``delta`` recorded) or it has no per-cycle rows."""
    loops = recorded_loops(result) if loops is None else loops
    if loops is None or "cycle_number" not in result.dims:
        return result
    return result.assign(loop_rows(loops, result.cycle_number.values, result.cycle_dissipation.values))


def _opening(Q, delta):
    """Distance [m] between the ``delta`` of the falling and of the rising crossing of ``Q = 0`` of
    one loop (NaN where it does not cross both ways)."""
    at = {}
    for i in np.flatnonzero((Q[:-1] > 0) & (Q[1:] <= 0) | (Q[:-1] < 0) & (Q[1:] >= 0)):
        way = int(np.sign(Q[i + 1] - Q[i]))
        if way not in at:
            at[way] = _crossing(Q, delta, i, way)
    return abs(at[-1] - at[1]) if len(at) == 2 else np.nan


def _crossing(Q, delta, i, way):
    """``delta`` [m] at ``Q = 0`` between steps `i` and ``i + 1``, where ``Q`` moves `way` (+-1): a
    cubic in ``Q`` through up to four steps around them along which ``Q`` moves strictly that way."""
    lo, hi = i, i + 1
    while hi - lo < 3:
        if lo > 0 and (Q[lo] - Q[lo - 1]) * way > 0:
            lo -= 1
        elif hi + 1 < Q.size and (Q[hi + 1] - Q[hi]) * way > 0:
            hi += 1
        else:
            break
    scale = np.abs(Q[lo : hi + 1]).max()
    fit = np.polyfit(Q[lo : hi + 1] / scale, delta[lo : hi + 1], hi - lo)
    return float(np.polyval(fit, 0.0))
