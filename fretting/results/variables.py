"""The dataset contract: every variable of a result, declared once, and the dataset built from it."""

from __future__ import annotations

from collections.abc import Mapping
from typing import NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

__all__ = ["ACCUMULATED", "AXES", "CYCLE_FIELDS", "CYCLE_PEAKS", "REGIMES", "VARIABLES", "build_dataset", "variable"]

#: Coordinate name -> its CF attributes in every dataset of `fretting` that has it (results, stress
#: fields): the axis it runs along, by which CF tools such as cf_xarray find the axes, and for the
#: depth ``z`` into a body that it grows into the body. CF has a ``standard_name`` for neither.
AXES = {"x": {"axis": "X"}, "z": {"axis": "Z", "positive": "down"}}


class _Field(NamedTuple):
    """A per-cycle field, as declared: its entries of `VARIABLES` follow from it.

    They are ``<name>`` on dims (cycle_number, x), its value so far in the cycle in progress
    ``state_<name>`` on (x,) where the state keeps one, and its accumulated field of `ACCUMULATED`
    on (x,), all in `units`.
    """

    units: str
    long_name: str  # of each cycle's value
    state: str | None  # long name of state_<name>; None: the state keeps no such value
    accumulated: str | None = None  # long name of its accumulated field; None: "largest <name> over every ..."


_PEAKS = {
    "sigma_xx_peak": _Field(
        "Pa",
        "largest surface direct stress of the specimen, with its bulk stress, over the steps of each load cycle",
        "largest surface direct stress of the specimen so far in the cycle in progress",
    ),
    "q_peak": _Field(
        "Pa",
        "largest magnitude of the shear traction over the steps of each load cycle",
        "largest |q| so far in the cycle in progress",
    ),
    "sigma_xx_q_peak": _Field(
        "Pa^2",
        "largest product of the specimen's surface direct stress and |q| over the steps of each load cycle",
        "largest sigma_xx |q| of the specimen so far in the cycle in progress",
    ),
}

#: Per-node peaks over every step of each load cycle that the engine tallies (`fretting.models.state.Tally`);
#: each is also recorded as ``state_<name>`` for the cycle in progress at the last step.
CYCLE_PEAKS = tuple(_PEAKS)

#: Per-cycle field -> `_Field`: the peaks, and the energy density and slip amplitude of each cycle.
_FIELDS = {
    "w": _Field(
        "J/m^2",
        "energy dissipated per unit area in each load cycle",
        "energy dissipated per unit area so far in the cycle in progress",
        "energy dissipated per unit area, summed over every complete load cycle",
    ),
    # the state keeps the least and greatest slip of the cycle instead (state_slip_min, state_slip_max)
    "slip_amplitude": _Field(
        "m",
        "half the range of the slip over each load cycle",
        None,
        "largest slip amplitude over every complete load cycle",
    ),
} | _PEAKS

#: Per-cycle fields (dims cycle_number, x): of every cycle, or of the cycles a run's ``cycle_fields``
#: policy chose (dims field_cycle, x; `fretting.engine.recorder.CycleFields`).
CYCLE_FIELDS = tuple(_FIELDS)

#: Accumulated field -> the per-cycle field it accumulates over every complete cycle of a run of
#: `fretting.run_file` whose ``cycle_fields`` policy leaves cycles out: ``w_total`` their sum, the others
#: their maxima. Each is on dims (x,), in the units of its per-cycle field.
ACCUMULATED = {"w_total": "w"} | {f"{name}_max": name for name in CYCLE_FIELDS[1:]}

#: The regimes of an increment (the per-step ``regime``) and of a cycle (``cycle_regime``), by their
#: code: no node slipped; some slipped; ``|Q|`` reached ``f P``, the whole contact slides. The words
#: are the CF ``flag_meanings`` of ``regime``, as those of a sweep's (`fretting.studies.sweeps`).
REGIMES = ("stuck", "partial_slip", "gross_slip")

#: The loads along the dimension ``load`` (`fretting.loading.loads.edge_loads`): the numerators of the fully
#: stuck traction of eqs (9) and (20) at the two contact edges, then the normal load.
_EDGE_LOADS = "load 0: Q - pi a sigma / 4 (at x = -a), 1: Q + pi a sigma / 4 (at x = +a), 2: P"

#: What the long names of the loop's per-cycle variables add (`fretting.results.loops`).
_LOOP = ", from the recorded steps where the contact has a datum (NaN: the cycle's steps not all recorded)"

#: name -> (dims, units, long_name) of the variables that follow from no other.
_DECLARED = {
    "Q": (("step",), "N/m", "shear force per unit length (prescribed, or found for the prescribed delta)"),
    "sigma": (("step",), "Pa", "differential bulk tension"),
    "p": (("x",), "Pa", "contact pressure (of the contact formed, where P varies)"),
    "P": (("step",), "N/m", "normal load per unit length, where the history varies it"),
    "a": (("step",), "m", "contact half-width at each step, where the history varies P"),
    "p_step": (("step", "x"), "Pa", "contact pressure at each step, where the history varies P"),
    "q": (("step", "x"), "Pa", "shear traction"),
    "slip": (("step", "x"), "m", "relative slip accumulated since the contact was formed"),
    "stick": (("step", "x"), "1", "point did not slip during the increment ending at this step"),
    "stick_start": (("step", "zone"), "m", "lower end of each stick zone of the increment (sub-grid)"),
    "stick_end": (("step", "zone"), "m", "upper end of each stick zone of the increment (sub-grid)"),
    "dissipation": (("step",), "J/m", "energy dissipated in the increment ending at this step"),
    "delta_Q": (("step",), "m", "slip part of the generalized displacement conjugate to Q"),
    "delta_sigma": (("step",), "m^2", "slip part of the generalized displacement conjugate to sigma"),
    "delta": (
        ("step",),
        "m",
        "tangential displacement of the pad relative to the specimen at the datum (depends on the datum L "
        "and the rig compliance, attributes datum and compliance), where the contact has a datum",
    ),
    "regime": (
        ("step",),
        "1",
        "regime of the increment ending at this step: 0 stuck, 1 partial slip, 2 gross slip (|Q| reached f P: "
        "the whole contact slides), where the contact has a datum",
    ),
    "vertex_step": (("vertex",), "1", "step at which each vertex of the load path is reached"),
    "vertex_Q": (("vertex",), "N/m", "shear force at each vertex of the load path"),
    "vertex_sigma": (("vertex",), "Pa", "bulk tension at each vertex of the load path"),
    "vertex_P": (("vertex",), "N/m", "normal load at each vertex of the load path, where the history varies it"),
    "vertex_delta": (
        ("vertex",),
        "m",
        "tangential displacement at the datum prescribed at each vertex, where the history prescribes it "
        "(NaN where Q is)",
    ),
    "cycle": (("step",), "1", "load cycle of the increment ending at this step (0: outside any cycle)"),
    "cycle_dissipation": (("cycle_number",), "J/m", "energy dissipated in each load cycle"),
    "cycle_load_range": (
        ("cycle_number", "load"),
        "N/m",
        "range over each load cycle of the loads that make slip at the contact edges and of the normal load: "
        + _EDGE_LOADS
        + " (NaN: not known, a cycle continued from a state written without it)",
    ),
    "cycle_number": (("cycle_number",), "1", "load cycle (1, 2, ...)"),
    "cycle_copied": (
        ("cycle_number",),
        "1",
        "cycle copied, not solved: its loads and starting state repeat those of the cycle before bit for bit "
        "(which cycles a run copies depends on where it was cut into parts; the values do not)",
    ),
    "Q_amplitude": (
        ("cycle_number",),
        "N/m",
        "half the range of Q over each load cycle (Q*; for a given history of Q independent of the datum)" + _LOOP,
    ),
    "delta_amplitude": (
        ("cycle_number",),
        "m",
        "half the range of delta over each load cycle (delta*; depends on the datum and the rig compliance)" + _LOOP,
    ),
    "loop_opening": (
        ("cycle_number",),
        "m",
        "distance between the two crossings of Q = 0 of each cycle's loop of delta (2 delta_0; for a given "
        "history of Q independent of the datum)" + _LOOP,
    ),
    "energy_ratio": (
        ("cycle_number",),
        "1",
        "Fouvry's energy ratio A = cycle_dissipation / (4 Q* delta*) of each cycle (depends on the datum)" + _LOOP,
    ),
    "sliding_ratio": (
        ("cycle_number",),
        "1",
        "Fouvry's sliding ratio B = delta_0 / delta* of each cycle, delta_0 half the loop opening (depends on "
        "the datum)" + _LOOP,
    ),
    "cycle_regime": (
        ("cycle_number",),
        "1",
        "largest regime of the increments of each cycle: 0 stuck, 1 partial slip, 2 gross slip (-1: not recorded "
        "whole), where the contact has a datum",
    ),
    "transition": (
        ("P",),
        "m",
        "displacement amplitude at the partial-slip / gross-slip boundary, delta_t (depends on the datum)",
    ),
    "field_cycle": (("field_cycle",), "1", "load cycle whose fields are stored (the cycle_fields policy's choice)"),
    "cycle_dissipation_max": ((), "J/m", "largest energy dissipated in one complete load cycle (NaN: none yet)"),
    "state_Q": ((), "N/m", "shear force at the last step"),
    "state_sigma": ((), "Pa", "bulk tension at the last step"),
    "state_P": ((), "N/m", "normal load at the last step, where the history varies it"),
    "state_delta": ((), "m", "tangential displacement at the datum prescribed at the last step, where it is"),
    "state_slip": (("x",), "m", "slip at the last step"),
    "state_slid": (
        (),
        "m",
        "uniform slip taken while the whole contact slid (gross slip), part of state_slip, where it slid",
    ),
    "state_episode_start": (("x",), "m", "slip at which each point's current slip episode began, at the last step"),
    "state_cycle": ((), "1", "load cycle in progress at the last step (0: none)"),
    "state_cycle_dissipation": ((), "J/m", "energy dissipated so far in the cycle in progress"),
    "state_slip_min": (("x",), "m", "least slip so far in the cycle in progress"),
    "state_slip_max": (("x",), "m", "greatest slip so far in the cycle in progress"),
    "state_load_low": (("load",), "N/m", "least of the loads so far in the cycle in progress: " + _EDGE_LOADS),
    "state_load_high": (("load",), "N/m", "greatest of the loads so far in the cycle in progress: " + _EDGE_LOADS),
    "state_turning": (
        ("turning",),
        "N/m",
        "turning points of Q still remembered at the last step, oldest first (exact model of Q alone only)",
    ),
    "state_bands": (
        ("band",),
        "1",
        "memory of the exact model of a varying P at the last step: the edges of its bands over the contact's"
        " half-width a, then the ratio of shear to normal load each band carries (Jaeger's superposition)",
    ),
    "total_dissipation": ((), "J/m", "energy dissipated since the contact was formed, up to the last step"),
    "x": (("x",), "m", "position along the contact"),
    "theta": (("x",), "rad", "angle of each node, x = centre + a cos(theta): Galerkin mesh or exact model"),
    "step": (("step",), "1", "load step (0 is the starting state)"),
}

#: name -> (dims, units, long_name). Units assume SI inputs; any consistent set works. They are written
#: as pint and UDUNITS both parse them: ``m^2``, not ``m2`` (`fretting.results.io.LEGACY_UNITS`).
VARIABLES = (
    _DECLARED
    | {name: (("cycle_number", "x"), field.units, field.long_name) for name, field in _FIELDS.items()}
    | {
        name: (
            ("x",),
            _FIELDS[source].units,
            _FIELDS[source].accumulated or f"largest {source} over every complete load cycle",
        )
        for name, source in ACCUMULATED.items()
    }
    | {f"state_{name}": (("x",), field.units, field.state) for name, field in _FIELDS.items() if field.state}
)


def variable(name: str, values: ArrayLike, dims: tuple[str, ...] | None = None) -> xr.Variable:
    """The variable `name` of `VARIABLES` holding `values`, with its units and long name (and its
    `AXES` attributes), on its dims or on `dims` (a per-cycle field of chosen cycles:
    ``("field_cycle", "x")``)."""
    declared, units, long_name = VARIABLES[name]
    attrs = {"units": units, "long_name": long_name} | AXES.get(name, {})
    if name == "regime":  # CF flags
        attrs |= {"flag_values": np.arange(len(REGIMES), dtype=np.int8), "flag_meanings": " ".join(REGIMES)}
    return xr.Variable(declared if dims is None else dims, np.asarray(values), attrs)


def build_dataset(data: Mapping[str, ArrayLike], attrs: dict) -> xr.Dataset:
    """Dataset of the arrays in `data` (names from `VARIABLES`), with units and long names."""
    variables = {name: variable(name, values) for name, values in data.items()}
    coords = {name: variables.pop(name) for name in ("x", "step", "cycle_number") if name in variables}
    return xr.Dataset(variables, coords=coords, attrs=attrs)
