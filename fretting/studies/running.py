"""Fretting loops and running-condition maps under displacement control (docs/guide/displacement.md).

A rig that imposes ``+-delta*`` records, cycle by cycle, the loop of ``Q`` against ``delta``;
`loop_cycles` gives the numbers of Fouvry, Kapsa & Vincent (1995) that the run wrote for each loop
(`fretting.results.loops`): the amplitudes ``Q*`` and ``delta*``, the opening ``2 delta_0`` at
``Q = 0``, the energy ``E_d``, the energy ratio ``A = E_d / (4 Q* delta*)``, the sliding ratio
``B = delta_0 / delta*`` and the regime of the cycle. `running_map` runs the exact model over a grid
of normal loads and displacement amplitudes as the cases of a sweep, and `running_cases` maps a
sweep dataset over them, with the partial-slip / gross-slip boundary ``delta_t(P)``
(`transition_displacement`, eq D6 of docs/theory/displacement.md). `fit_datum` finds the datum of a
rig from a measured loop.

Which numbers depend on the datum ``L`` and the rig compliance ``C``: ``delta*``, ``A`` and ``B``
do; for a given history of ``Q``, ``Q*``, the opening and ``E_d`` do not (docs/theory/displacement.md#datum-dependence).
"""

from __future__ import annotations

import csv
import itertools
import math
from pathlib import Path

import numpy as np
import xarray as xr

from fretting.engine.simulation import simulate
from fretting.loading.history import History
from fretting.models.exact import Exact, transition_displacement
from fretting.physics.contact import Contact
from fretting.results.loops import LOOP_VARIABLES, with_loops
from fretting.results.variables import REGIMES, variable
from fretting.studies import sweeps

__all__ = [
    "fit_datum",
    "loop_cycles",
    "read_loop",
    "running_cases",
    "running_dims",
    "running_map",
    "sliding_cycles",
    "transition_displacement",
]

#: Steps per quarter cycle of the histories of `running_map`: the loop opening, interpolated at
#: ``Q = 0`` by a cubic through four steps, is then within 1e-6 of its closed form on Hertz
#: (tests/studies/test_running.py).
QUARTER_STEPS = 16


def sliding_cycles(delta_star: float, cycles: int, steps: int = QUARTER_STEPS) -> History:
    """A ramp from rest to `delta_star` [m], then `cycles` load cycles ``+delta* -> -delta* -> +delta*``,
    `steps` steps per quarter cycle."""
    ramp = History.piecewise_linear(delta=[0.0, delta_star], steps_per_segment=steps)
    cycle = History.piecewise_linear(delta=[delta_star, -delta_star, delta_star], steps_per_segment=2 * steps)
    return History.concatenate([ramp, *[cycle.as_cycle()] * cycles])


def loop_cycles(result: xr.Dataset) -> xr.Dataset:
    """The fretting loop of each load cycle of a displacement-controlled `result`.

    The variables on ``cycle_number`` that the run wrote (`fretting.results.loops.LOOP_VARIABLES`:
    ``Q_amplitude``, ``delta_amplitude``, ``loop_opening``, ``energy_ratio``, ``sliding_ratio``,
    ``cycle_regime``; NaN, and regime -1, for a cycle not recorded whole), with
    ``cycle_dissipation``; computed from the recorded steps of a result written without them.

    Raises
    ------
    ValueError
        Where the result has no ``delta`` (its contact has no datum) or no load cycles.
    """
    if "delta" not in result or "cycle_number" not in result.dims:
        raise ValueError("the result has no delta or no load cycles: run a history of delta cycles on a datum")
    if not all(name in result for name in LOOP_VARIABLES):  # written before the run wrote them
        result = with_loops(result)
    data = {name: result[name].variable for name in ("cycle_dissipation", *LOOP_VARIABLES)}
    return xr.Dataset(data, coords={"cycle_number": result.cycle_number.variable}, attrs=_datum(result.attrs))


def _datum(attrs):
    return {name: attrs[name] for name in ("datum", "compliance", "f") if name in attrs}


def running_map(contact: Contact, P, delta_amplitude, cycles: int = 2, steps: int = QUARTER_STEPS) -> xr.Dataset:
    """Running-condition map of `contact` over the normal loads `P` [N/m] and displacement amplitudes
    `delta_amplitude` [m]: each point runs the exact model over `sliding_cycles`, in this process, as a
    case of a sweep (`fretting.studies.sweeps.run_cases`), and keeps its last cycle's loop.

    Returns a dataset on ``(P, delta_amplitude)`` of ``Q_amplitude``, ``cycle_dissipation``,
    ``loop_opening``, ``energy_ratio``, ``sliding_ratio`` and ``cycle_regime``, with the boundary
    ``transition`` (`transition_displacement`) on ``P`` (`running_cases`). The contact's profile,
    moduli, ``f``, datum and compliance are kept; its ``P`` is replaced by each of `P`.
    """
    grid = {"contact.P": [float(load) for load in P], "delta_amplitude": [float(value) for value in delta_amplitude]}
    cases = [
        sweeps.Case(values, _at_load(contact, values["contact.P"]), _run_by(values, cycles, steps), ())
        for values in (dict(zip(grid, point, strict=True)) for point in itertools.product(*grid.values()))
    ]
    mapped = running_cases(sweeps.gathered(grid, sweeps.run_cases(cases, None, in_process=True)))
    return mapped.assign_attrs({"cycles": cycles} | _datum(vars(contact)))


def _run_by(values, cycles, steps):
    """`sliding_cycles` of the amplitude of `values` on the exact model, as a case of a sweep runs it."""
    return sliding_cycles(values["delta_amplitude"], cycles, steps)


#: The variables of a running-condition map (`running_cases`) -> those of a sweep's that they are.
MAPPED = {
    "Q_amplitude": "Q_amplitude",
    "cycle_dissipation": "energy_per_cycle",
    "loop_opening": "loop_opening",
    "energy_ratio": "energy_ratio",
    "sliding_ratio": "sliding_ratio",
    "cycle_regime": "cycle_regime",
}


def running_dims(cases: xr.Dataset) -> tuple[str, str] | None:
    """The dimensions ``(of P, of delta_amplitude)`` of a sweep dataset over the normal load (a key
    ``contact.P``) and the displacement amplitude (a key ending in ``delta_amplitude``), and no other;
    None for any other sweep."""
    ends = {dim: cases[dim].attrs.get("key", dim).rsplit(".", 1)[-1] for dim in cases.regime.dims}
    found = [next((dim for dim, end in ends.items() if end == name), None) for name in ("P", "delta_amplitude")]
    if len(ends) != 2 or None in found or any(cases[dim].dtype.kind not in "iuf" for dim in found):
        return None
    return tuple(found)


def running_cases(cases: xr.Dataset) -> xr.Dataset:
    """The running-condition map (as `running_map` gives it) of a sweep dataset over the normal load and
    the displacement amplitude (`running_dims`): the last cycle's loop of each case, and the boundary
    ``transition`` on ``P``.

    Raises
    ------
    ValueError
        Where `cases` is not such a sweep.
    """
    dims = running_dims(cases)
    if dims is None:
        raise ValueError("a running-condition map needs a sweep over contact.P and a delta_amplitude, and no other key")
    order = ("P", "delta_amplitude")
    data = {name: variable(name, cases[swept].transpose(*dims).values, order) for name, swept in MAPPED.items()}
    data["transition"] = variable("transition", cases.transition.transpose(*dims).values[:, 0])
    coords = {
        "P": xr.Variable(
            "P",
            cases[dims[0]].values,
            {"units": "N/m", "long_name": "normal load per unit length of each row of the map"},
        ),
        "delta_amplitude": variable("delta_amplitude", cases[dims[1]].values, ("delta_amplitude",)),
    }
    attrs = {"regimes": ", ".join(f"{k} {name}" for k, name in enumerate(REGIMES))}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _at_load(contact, P):
    """`contact` formed at the normal load `P` [N/m] instead, with its datum and compliance."""
    return Contact(
        contact.profile,
        contact.E_star,
        contact.f,
        P,
        contact.specimen,
        contact.nu,
        datum=contact.datum,
        compliance=contact.compliance,
    )


def read_loop(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """``(delta [m], Q [N/m])`` of a measured loop: a CSV file with a header naming the columns
    ``delta`` and ``Q`` (others are ignored), one row per sample in time order.

    Raises
    ------
    ValueError
        Naming the file, the column and what was expected.
    """
    path = Path(path)
    with path.open(newline="") as file:
        rows = list(csv.DictReader(file))
    columns = {}
    for name in ("delta", "Q"):
        try:
            columns[name] = np.array([float(row[name]) for row in rows])
        except (KeyError, TypeError):
            raise ValueError(f"{path}: no column {name!r}, expected a header with delta and Q") from None
        except ValueError as error:
            raise ValueError(f"{path}: column {name!r}: {error}, expected numbers") from None
        if columns[name].size < 3 or not np.all(np.isfinite(columns[name])):
            raise ValueError(f"{path}: column {name!r} must hold at least 3 finite numbers")
    return columns["delta"], columns["Q"]


def fit_datum(contact: Contact, delta, Q) -> tuple[float, float]:
    """Datum ``L`` [m] and stuck compliance ``K = C_L + C`` [m per N/m] that reproduce the elastic slope
    of a measured loop of ``delta`` [m] against ``Q`` [N/m] in partial slip on `contact`.

    ``delta = K Q + delta_Q + delta_0`` (eq D4) with ``delta_Q`` the exact model's for the measured
    history of ``Q`` (force control, from rest at the first sample): ``K`` and the offset
    ``delta_0`` are the least-squares line of ``delta - delta_Q`` against ``Q``. ``L`` is eq D3
    inverted for ``K`` less the contact's rig compliance ``C``: ``a cosh(pi E_star (K - C) / 2)``.

    Raises
    ------
    ValueError
        Where the loop reaches gross slip, or its slope leaves no positive ``C_L`` for a datum.
    """
    delta, Q = np.asarray(delta, dtype=float), np.asarray(Q, dtype=float)
    fP = contact.f * contact.P
    if np.abs(Q).max() >= fP:
        raise ValueError(f"the loop reaches |Q| = {np.abs(Q).max():.6g} >= f P = {fP:.6g}: fit a partial-slip loop")
    bare = Contact(contact.profile, contact.E_star, contact.f, contact.P, contact.specimen, contact.nu)
    history = History(np.concatenate([[0.0], Q]), np.zeros(Q.size + 1), [0, Q.size])
    slip = simulate(bare, history, Exact()).delta_Q.values[1:]
    K, offset = np.polyfit(Q, delta - slip, 1)
    C_L = K - contact.compliance
    if not C_L > 0:
        raise ValueError(f"the loop's elastic slope gives K = {K:.6g} m per N/m, not above the rig compliance")
    return contact.a * math.cosh(math.pi * contact.E_star * C_L / 2), float(K)
