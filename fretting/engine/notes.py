"""Notes a run records and says where its model cannot resolve what the loads ask.

A cycle whose loads vary on a contact whose pressure vanishes at its edges slips there: the fully
stuck traction of eqs (9) and (20) is unbounded at the edges while ``f p`` falls to zero, so every
change of ``Q`` or ``sigma`` makes slip zones at the edges (Mindlin-Deresiewicz on Hertz: half-width
``a - c ~ a Delta Q / (4 f P)`` for a small range ``Delta Q``). A discretised model whose outermost
nodes lie further in than those zones solves such a cycle as stuck throughout, with exactly zero
energy: `unresolved_cycles` names those cycles, and the run records the note (``model_unresolved``)
and says it, as it does a model's fallback.
"""

from __future__ import annotations

import numpy as np

from fretting.physics.profiles import profile_class, recorded_profile
from fretting.results.io import open_result

__all__ = ["UNRESOLVED", "noted", "parts_note", "unresolved_cycles", "varied_cycles"]

#: Attribute of a result that holds the note of `unresolved_cycles`.
UNRESOLVED = "model_unresolved"

#: Steps of a history read at once by `varied_cycles`.
BLOCK = 2**18


def varied_cycles(history):
    """Whether the loads (``Q``, ``sigma``, ``P`` where it varies) move in each load cycle of `history`,
    1 to its ``cycle_count``: ndarray of bool, shape (cycles,)."""
    varied = np.zeros(history.cycle_count + 1, dtype=bool)
    if not history.has_cycles:
        return varied[1:]
    for start in range(1, len(history), BLOCK):
        Q, sigma, cycle, P = history.at(np.arange(start - 1, min(start + BLOCK, len(history))))
        moved = (np.diff(Q) != 0) | (np.diff(sigma) != 0) | (False if P is None else np.diff(P) != 0)
        varied[cycle[1:][moved]] = True  # the cycle of the increment ending at each step
    return varied[1:]


def unresolved_cycles(attrs, cycle_number, dissipation, varied):
    """The note [str] of the cycles whose loads move that dissipated nothing, or None.

    Parameters
    ----------
    attrs : mapping
        The result's attributes: its profile (``profile_class``), ``model`` and ``nodes``.
    cycle_number, dissipation, varied : array_like, shape (cycles,)
        Each cycle's number, ``cycle_dissipation`` [J/m] and whether its loads move (`varied_cycles`).

    Returns
    -------
    str or None
        None where the profile's pressure does not vanish at the edges (a sharp flat punch sticks
        until it slides) or is unknown, or where every cycle whose loads move dissipated energy.
    """
    profile = profile_class(recorded_profile(attrs)[0])
    if profile is None or not profile.VANISHING_EDGES:
        return None
    silent = np.flatnonzero((np.asarray(dissipation) == 0) & np.asarray(varied, dtype=bool))
    if not silent.size:
        return None
    numbers = np.asarray(cycle_number)[silent]
    which = f"cycle {numbers[0]}" + (f" to {numbers[-1]}" if silent.size > 1 else "")
    return (
        f"{silent.size} load cycle{'s' * (silent.size > 1)} ({which}) dissipated exactly nothing on the "
        f"{attrs['model']} model's {attrs['nodes']} nodes, though their loads move and the pressure vanishes at "
        "the contact edges: their slip zones lie nearer the edges than the outermost nodes; more nodes, a Mesh "
        "or an exact model resolve them"
    )


def noted(result, history):
    """`result` (a dataset of `fretting.engine.simulation` of `history`) with the note of
    `unresolved_cycles` in its attribute `UNRESOLVED`, where there is one."""
    if "cycle_number" not in result.dims:
        return result
    varied = varied_cycles(history)[result.cycle_number.values - 1]
    note = unresolved_cycles(result.attrs, result.cycle_number.values, result.cycle_dissipation.values, varied)
    return result if note is None else result.assign_attrs({UNRESOLVED: note})


def parts_note(parts, varied):
    """The note of `unresolved_cycles` of a run kept in the result files `parts` (in order; a cycle that
    spans two parts is the later part's), whose cycles' loads move as `varied` (`varied_cycles`) says;
    or None."""
    cycles, attrs = {}, None
    for part in parts:
        with open_result(part) as opened:
            attrs = dict(opened.attrs) if attrs is None else attrs
            if "cycle_number" in opened.dims:
                rows = zip(opened.cycle_number.values.tolist(), opened.cycle_dissipation.values.tolist(), strict=True)
                cycles |= dict(rows)
    if not cycles:
        return None
    numbers = np.array(sorted(cycles))
    return unresolved_cycles(attrs, numbers, [cycles[number] for number in numbers], varied[numbers - 1])
