"""Notes a run records and says where its model cannot resolve what the loads ask.

A cycle whose loads vary on a contact whose pressure vanishes at its edges slips there: the fully
stuck traction of eqs (9) and (20), ``q = (Q / pi + sigma x / 4) / sqrt(a^2 - x^2)``, is unbounded at
the edges while ``f p`` falls to zero, so every change of ``Q`` or ``sigma`` makes slip zones at the
edges. On Hertz a range ``Delta Q`` of ``Q`` slips over ``a - c = a (1 - sqrt(1 - Delta Q / (2 f P)))``
at an edge (Mindlin & Deresiewicz 1953, `fretting.physics.closed_forms.mindlin_deresiewicz_traction`),
``~ a Delta Q / (4 f P)`` for a small range. A discretised model resolves such a cycle only with enough
nodes in those zones: `unresolved_cycles` names the cycles whose slip zones (so estimated, or as
recorded where wider) hold fewer than `SLIP_NODES` nodes of a model that does not adapt its nodes to
the energy (a grid, a given mesh), and those of any model that dissipated exactly nothing; the run
records the note (``model_unresolved``) and says it, as it does a model's fallback. The note is a
function of the result alone (each cycle's ``cycle_load_range``, which the engine tallies and a state
carries from part to part), so a result joined from parts has the whole run's.
"""

from __future__ import annotations

import numpy as np

from fretting.physics.profiles import profile_class, recorded_profile

__all__ = ["SLIP_NODES", "UNRESOLVED", "edge_slip_nodes", "noted", "observed_slip_nodes", "unresolved_cycles"]

#: Attribute of a result that holds the note of `unresolved_cycles`.
UNRESOLVED = "model_unresolved"

#: Fewest nodes of a grid or a given mesh within a cycle's estimated slip zone (`edge_slip_nodes`, at the
#: edge of the larger) for its energy to be within the README's 1e-4: below it, the measured error of
#: benchmarks/unresolved_cycles.py exceeds 1e-4 on Grid(96) to Grid(1536) and on given meshes.
SLIP_NODES = 100

#: Models whose nodes are fixed whatever the loads: their cycles are counted (`edge_slip_nodes`). A mesh
#: adapted to the energy (a result with ``rtol``) and the exact models are not.
FIXED_NODES = ("grid", "mesh")


def edge_slip_nodes(attrs, x, p, ranges):
    """Nodes of a model at `x` [m] within the slip zone each cycle's `ranges` (its ``cycle_load_range``) make at the
    contact edge where it is wider, by Mindlin-Deresiewicz's small-range width: with the pressure
    ``p ~ K sqrt(2 d / a)`` at a distance ``d`` from an edge (``K = p0`` on Hertz), a range ``Delta`` of
    the edge's load slips over ``d < Delta / (2 pi f K)`` (``a Delta / (4 f P)`` on Hertz); ``K`` from the
    pressure `p` [Pa] at the outermost node inside each edge. ndarray of int, shape (cycles,)."""
    a, centre, f = float(attrs["a"]), float(attrs["centre"]), float(attrs["f"])
    counts = []
    for edge, side in enumerate((-1.0, 1.0)):
        d = a - side * (np.asarray(x) - centre)
        inside = np.flatnonzero((d > 0) & (d < a))
        outer = inside[np.argmin(d[inside])]
        K = p[outer] / np.sqrt(2 * d[outer] / a)
        width = ranges[:, edge] / (2 * np.pi * f * K)
        counts.append(np.searchsorted(np.sort(d[inside]), width))
    wider = np.argmax(ranges[:, :2], axis=1)
    return np.stack(counts, axis=1)[np.arange(len(ranges)), wider]


def observed_slip_nodes(stick, cycle, numbers):
    """The most nodes slipping in a row from either edge at a recorded step of each cycle of `numbers`,
    from the recorded `stick` (bool, shape (steps, nodes)) of steps of load cycle `cycle` (shape
    (steps,)): ndarray of int, shape (len(numbers),), 0 for a cycle with no step recorded."""
    stick = np.asarray(stick, dtype=bool)
    from_left = np.where(stick.any(axis=1), np.argmax(stick, axis=1), stick.shape[1])
    from_right = np.where(stick.any(axis=1), np.argmax(stick[:, ::-1], axis=1), stick.shape[1])
    observed = np.zeros(len(numbers), dtype=int)
    known = np.isin(cycle, numbers)
    np.maximum.at(observed, np.searchsorted(numbers, cycle[known]), np.maximum(from_left, from_right)[known])
    return observed


def unresolved_cycles(attrs, cycle_number, dissipation, ranges, x, p, observed):
    """The note [str] of the cycles whose loads move that the model does not resolve, or None.

    Parameters
    ----------
    attrs : mapping
        The result's attributes: its profile (``profile_class``), ``model``, ``nodes``, ``rtol``, ``a``,
        ``centre``, ``f``.
    cycle_number, dissipation : array_like, shape (cycles,)
        Each cycle's number and ``cycle_dissipation`` [J/m].
    ranges : array_like, shape (cycles, 3)
        Each cycle's ``cycle_load_range`` [N/m]: of the loads that make slip at the edges, and of ``P``.
    x, p : array_like, shape (nodes,)
        The model's nodes [m] and the pressure there [Pa] (`p` None: it varies from step to step). The
        cycles of a model with fixed nodes (`FIXED_NODES`) under a constant ``P`` whose slip zone holds
        fewer than `SLIP_NODES` (`edge_slip_nodes`, or `observed` where more) are named too.
    observed : array_like of int, shape (cycles,)
        Each cycle's `observed_slip_nodes`.

    Returns
    -------
    str or None
        None where the profile's pressure does not vanish at the edges (a sharp flat punch sticks
        until it slides) or is unknown, or where no cycle is unresolved.
    """
    profile = profile_class(recorded_profile(attrs)[0])
    if profile is None or not profile.VANISHING_EDGES:
        return None
    ranges = np.asarray(ranges, dtype=float).reshape(-1, 3)
    varied = np.any(ranges > 0, axis=1)
    numbers = np.asarray(cycle_number)
    silent = (np.asarray(dissipation) == 0) & varied
    few = np.zeros_like(silent)
    if p is not None and attrs["model"] in FIXED_NODES and "rtol" not in attrs:
        counted = varied & (ranges[:, 2] == 0) & ~silent
        slipping = np.maximum(edge_slip_nodes(attrs, x, np.asarray(p), ranges[counted]), np.asarray(observed)[counted])
        few[counted] = slipping < SLIP_NODES
    nodes = f"the {attrs['model']} model's {attrs['nodes']} nodes"
    said = []
    if silent.any():
        said.append(
            f"{_cycles(numbers[silent])} dissipated exactly nothing on {nodes}, though their loads move and the "
            "pressure vanishes at the contact edges: their slip zones lie nearer the edges than the outermost nodes"
        )
    if few.any():
        said.append(
            f"{_cycles(numbers[few])} slipped over fewer than {SLIP_NODES} of {nodes} at an edge "
            "(Mindlin-Deresiewicz's width of their load range, or their recorded slip where wider), too few for "
            "their energy to be within 1e-4"
        )
    if not said:
        return None
    return "; ".join(said) + ": more nodes, an adapted Mesh or an exact model resolve them"


def _cycles(numbers):
    """``"3 load cycles (cycle 1 to 3)"`` of the ascending cycle `numbers`."""
    which = f"cycle {numbers[0]}" + (f" to {numbers[-1]}" if numbers.size > 1 else "")
    return f"{numbers.size} load cycle{'s' * (numbers.size > 1)} ({which})"


def noted(result):
    """`result` (a dataset of `fretting.simulate`, or joined from parts) with the note of `unresolved_cycles`
    in its attribute `UNRESOLVED`, or without that attribute where there is none; as it is where it
    records no ``cycle_load_range`` (written before the ranges were)."""
    if "cycle_load_range" not in result:
        return result
    numbers = result.cycle_number.values
    pressure = result.p.values if result.p.dims == ("x",) else None
    observed = observed_slip_nodes(result.stick.values, result.cycle.values, numbers)
    note = unresolved_cycles(
        result.attrs,
        numbers,
        result.cycle_dissipation.values,
        result.cycle_load_range.values,
        result.x.values,
        pressure,
        observed,
    )
    if note is not None:
        return result.assign_attrs({UNRESOLVED: note})
    said = result.copy(deep=False)  # a shallow copy's attrs are its own
    said.attrs.pop(UNRESOLVED, None)
    return said
