"""The state of the contact: the slip field, the model's memory, the tally of the cycle in progress.

A run continued from a state equals, bit for bit, the run of the whole history: the state holds
everything an increment depends on (`State.repeats` is the test of that), and the model it was
computed with (`State.model`, a resolved `fretting.models.base.ModelSpec`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cache
from typing import Any, Protocol

import numpy as np

from fretting.errors import HistoryError
from fretting.loading.loads import Loads, edge_loads
from fretting.results.variables import CYCLE_PEAKS

__all__ = ["Continued", "Nodes", "Solved", "State", "Tally"]


class Nodes(Protocol):
    """What a `State` reads of the model it is formed on (a `fretting.models.base.Model`): the
    nodes ``x`` [m] of its slip field, its resolved spec and whether it follows gross slip.

    The state lies below the model contract, which holds states: it names what it needs of a model
    rather than importing the contract."""

    @property
    def x(self) -> np.ndarray: ...

    @property
    def spec(self) -> Any: ...

    @property
    def slides(self) -> bool: ...


class Solved(Protocol):
    """What `State.advance` reads of an increment solved (a `fretting.models.base.Outcome`): the
    slip [m] after it and its increment, the energy it dissipated [J/m], the model's memory and the
    uniform slip of gross slip [m]."""

    @property
    def slip(self) -> np.ndarray: ...

    @property
    def ds(self) -> np.ndarray: ...

    @property
    def dissipation(self) -> float: ...

    @property
    def memory(self) -> tuple: ...

    @property
    def slid(self) -> float: ...


class Continued(Nodes, Protocol):
    """What `State.check` reads of the model a state is continued on (a `fretting.models.base.Model`):
    the increment of no load change (`at_rest`), its traction [Pa] and the pressure [Pa] under a
    normal load. A model of method 4 also has ``limit``, ``f p`` in its own measure beside the ``g``
    of its outcomes, and ``dissipation(ds)``, ``int f p |ds| dx`` [J/m] on its nodes."""

    def at_rest(self, state: State) -> Solved: ...

    def traction(self, outcome: Solved) -> np.ndarray: ...

    def pressure_at(self, P: float) -> np.ndarray: ...


@cache
def _unknown(N):
    """A read-only row of `N` NaN: a peak or load extremes not known, shared by the tallies that do not know them."""
    row = np.full(N, np.nan)
    row.flags.writeable = False
    return row


@dataclass(frozen=True, eq=False)
class Tally:
    """What the cycle in progress has done so far.

    Attributes
    ----------
    number : int
        Load cycle (0: the steps outside any cycle, which are not tallied).
    dissipation : float
        Energy dissipated [J/m].
    w : ndarray, shape (N,)
        Energy dissipated per unit area [J/m^2] at the nodes.
    slip_min, slip_max : ndarray, shape (N,)
        Extremes of the slip [m] over the cycle, its starting state included.
    sigma_xx_peak : ndarray, shape (N,)
        Largest surface direct stress ``sigma_xx`` [Pa] of the specimen, with its bulk stress,
        over the steps of the cycle (`fretting.physics.surface.SurfaceStress`).
    q_peak : ndarray, shape (N,)
        Largest ``|q|`` [Pa] over the steps of the cycle.
    sigma_xx_q_peak : ndarray, shape (N,)
        Largest ``sigma_xx |q|`` [Pa^2] over the steps of the cycle.
    load_low, load_high : ndarray, shape (3,)
        Least and greatest `fretting.loading.loads.edge_loads` [N/m] over the cycle's increments,
        both ends of each (the loads of its starting state included): their difference is the range
        of the loads that make slip at each contact edge, and of ``P``.

    The three peaks are ``-inf`` before the cycle's first increment, and NaN where they are not
    known (a state read from a result written without them): a NaN stays NaN. So are the load
    extremes of a state read from a result written without them.
    """

    number: int
    dissipation: float
    w: np.ndarray
    slip_min: np.ndarray
    slip_max: np.ndarray
    sigma_xx_peak: np.ndarray
    q_peak: np.ndarray
    sigma_xx_q_peak: np.ndarray
    load_low: np.ndarray
    load_high: np.ndarray

    @classmethod
    def begin(cls, number: int, slip: np.ndarray, loads: np.ndarray) -> Tally:
        """Nothing done yet in cycle `number`, which starts from `slip` [m] under the `loads` [N/m]
        (`fretting.loading.loads.edge_loads`)."""
        nothing = np.full(slip.size, -np.inf)
        return cls(number, 0.0, np.zeros(slip.size), slip, slip, nothing, nothing, nothing, loads, loads)

    @classmethod
    def without_stress(cls, number, dissipation, w, slip_min, slip_max, q_peak, load_low, load_high):
        """A tally whose two peaks of ``sigma_xx`` are not known (NaN): that of a run that skips steps."""
        unknown = _unknown(w.size)
        return cls(number, dissipation, w, slip_min, slip_max, unknown, q_peak, unknown, load_low, load_high)

    def add(self, dissipation, w, slip, stress, shear, loads):
        """The tally after an increment to the `loads` [N/m] (`fretting.loading.loads.edge_loads`) that
        dissipated `dissipation` [J/m], `w` [J/m^2] and left `slip` [m], the specimen's surface stress
        `stress` [Pa] and the traction's magnitude `shear` [Pa].

        `stress` None: not known (a run that skips steps), so the two peaks of ``sigma_xx`` are
        NaN, as the maximum with a NaN row would make them, without forming that row.
        """
        if stress is None:
            sigma_xx_peak = sigma_xx_q_peak = _unknown(slip.size)
        else:
            sigma_xx_peak = np.maximum(self.sigma_xx_peak, stress)
            sigma_xx_q_peak = np.maximum(self.sigma_xx_q_peak, stress * shear)
        return Tally(
            self.number,
            self.dissipation + dissipation,
            self.w + w,
            np.minimum(self.slip_min, slip),
            np.maximum(self.slip_max, slip),
            sigma_xx_peak,
            np.maximum(self.q_peak, shear),
            sigma_xx_q_peak,
            np.minimum(self.load_low, loads),
            np.maximum(self.load_high, loads),
        )

    def folded(self, slips, w, shear, first, length):
        """The fields ``w``, ``slip_min``, ``slip_max``, ``q_peak`` of the stretches of a run of increments
        taken as rows (`fretting.models.base.Model.window`), one row per stretch: this tally's for the
        first, a new one's (`begin`) for each later one.

        `slips` [m] holds the slip before the first row, then after each row; `w` [J/m^2] and `shear`
        [Pa] are each row's energy density and ``|q|``; stretch ``k`` is the `length` [k] rows from
        `first` [k]. Each field is added or compared row after row in order, as `add` would step by
        step, bit for bit (a reduction along the rows might add them in another order).
        """
        begun = slips[first[1:]]  # the slip at the start of each later stretch
        fields = {
            "w": (np.vstack([self.w, np.zeros_like(begun)]), w, np.add),
            "slip_min": (np.vstack([self.slip_min, begun]), slips[1:], np.minimum),
            "slip_max": (np.vstack([self.slip_max, begun]), slips[1:], np.maximum),
            "q_peak": (np.vstack([self.q_peak, np.full_like(begun, -np.inf)]), shear, np.maximum),
        }
        return {name: _folded(op, held, rows, first, length) for name, (held, rows, op) in fields.items()}

    @property
    def slip_amplitude(self):
        """Half the range of the slip over the cycle [m]."""
        return (self.slip_max - self.slip_min) / 2


@dataclass(frozen=True, eq=False)
class State:
    """Everything the contact remembers of its history, and the tally of the cycle in progress.

    Attributes
    ----------
    loads : Loads
        The loads of the state (`fretting.loading.loads.Loads`; ``loads.P`` None: the contact's ``P``).
    slip : ndarray, shape (N,)
        Accumulated slip [m] at the nodes, ascending in x.
    episode_start : ndarray, shape (N,)
        Slip [m] at which each node's current episode of slip in one direction began (equal
        to `slip` where the node sticks). The sub-grid stick-zone ends use it.
    tally : Tally
        Energy and slip range of the cycle in progress, so that a run continued from this
        state reports that cycle whole.
    model : fretting.models.base.ModelSpec
        The resolved model the state was computed with (its nodes are those of `slip`).
    dissipated : float
        Energy dissipated since the contact was formed [J/m], summed step by step.
    memory : tuple of float
        What the model remembers beyond the slip (the open turning points [N/m] of the exact
        model of ``Q`` alone, oldest first; empty for method 4).
    slid : float
        Uniform slip [m] the contact has taken sliding whole (gross slip, `Outcome.slid`), part of
        `slip`; 0 where it never slid.
    """

    loads: Loads
    slip: np.ndarray
    episode_start: np.ndarray
    tally: Tally
    model: Any  # a resolved fretting.models.base.ModelSpec
    dissipated: float = 0.0
    memory: tuple = ()
    slid: float = 0.0

    @property
    def Q(self) -> float:
        """Shear force [N/m]."""
        return self.loads.Q

    @property
    def sigma(self) -> float:
        """Bulk tension [Pa]."""
        return self.loads.sigma

    @property
    def P(self) -> float | None:
        """Normal load [N/m] where the history varies it (None: the contact's ``P``)."""
        return self.loads.P

    @classmethod
    def virgin(cls, model: Nodes) -> State:
        """The contact of `model` (a `fretting.models.base.Model`) just formed: no load and no slip."""
        slip = np.zeros(model.x.size)
        return cls(Loads(0.0, 0.0), slip, slip, Tally.begin(0, slip, _unknown(3)), model.spec)  # cycle 0: not tallied

    def begun(self, number: int, contact: Any) -> State:
        """This state with the tally of cycle `number` begun from it: from its slip and from its loads at the
        edges of `contact` (a `fretting.physics.contact.Contact`, `fretting.loading.loads.edge_loads`)."""
        return replace(self, tally=Tally.begin(number, self.slip, edge_loads(self.loads, contact)))

    def advance(
        self,
        outcome: Solved,
        loads: Loads,
        w: np.ndarray | None,
        stress: np.ndarray | None,
        shear: np.ndarray | None,
        edges: np.ndarray | None,
    ) -> State:
        """The state after the increment `outcome` to `loads`, which dissipated `w` [J/m^2]
        and left the specimen's surface stress `stress` [Pa] and the traction's magnitude `shear` [Pa]
        (`w` None where nothing is tallied: outside a load cycle, or where only the slip matters;
        `stress` None where it is not known, `Tally.add`); `edges` [N/m], `loads` as the tally
        takes them (`fretting.loading.loads.edge_loads`; None with `w`).

        A node's episode begins again where it sticks (at its slip) or reverses (at its slip before).
        """
        slip, ds, before = outcome.slip, outcome.ds, self.slip
        # reversed where ds and the episode so far have strictly opposite signs (sign(ds) times it: exact)
        episode_start = np.where(np.sign(ds) * (before - self.episode_start) < 0, before, self.episode_start)
        np.copyto(episode_start, slip, where=ds == 0)
        tally = self.tally if w is None else self.tally.add(outcome.dissipation, w, slip, stress, shear, edges)
        dissipated = self.dissipated + outcome.dissipation
        return State(loads, slip, episode_start, tally, self.model, dissipated, outcome.memory, outcome.slid)

    def episode_after(self, slips: np.ndarray, ds: np.ndarray) -> np.ndarray:
        """`episode_start` [m] after a run of increments taken as rows: `slips` the slip before the
        first, then after each; `ds` each row's slip increment, exactly zero where a node stuck.

        Row by row as `advance` would: a node's episode begins again at the last row where it
        sticks (at its slip after) or reverses (at its slip before); a node reverses where the sign
        of ``ds`` flips (the sign of the episode so far is that of the ``ds`` before, or zero where it
        stuck), and on the first row against this state's episode.
        """
        stuck = ds == 0
        sign = np.sign(ds)
        turned = np.empty_like(stuck)
        turned[0] = sign[0] * (self.slip - self.episode_start) < 0
        turned[1:] = sign[1:] * sign[:-1] < 0
        begins = stuck | turned
        last = ds.shape[0] - 1 - np.argmax(begins[::-1], axis=0)
        nodes = np.arange(ds.shape[1])
        start = np.where(stuck[last, nodes], slips[last + 1, nodes], slips[last, nodes])
        return np.where(begins[last, nodes], start, self.episode_start)

    def repeats(self, other: State) -> bool:
        """True if this state is `other`'s memory bit for bit: the same loads, slip fields and model memory."""
        return (
            (self.loads, self.memory, self.slid) == (other.loads, other.memory, other.slid)
            and np.array_equal(self.slip, other.slip)
            and np.array_equal(self.episode_start, other.episode_start)
        )

    def check(self, contact, model: Continued) -> None:
        """Raise HistoryError unless this state can be continued on `contact` with `model` (a `Model`).

        Besides its fields' shapes, finite values and non-negative energies, the state must be one
        the contact can be in, as far as that is cheap to tell (one product of the model's stiffness
        with the slip, `consistency`): under its own loads its traction obeys Coulomb's law,
        ``|q| <= f p`` at every node; a model that derives the slip from what it remembers (the
        exact models: their turning points) gives back its slip; and, under a constant ``P``, the
        energy it records since the contact was formed is at least ``int f p |s| dx``, since every
        node's slip ``s`` was reached by increments each of which dissipated ``f p |ds|`` (method 4's
        models, whose ``dissipation`` is that integral on their nodes). A slip far beyond what the
        recorded loads and energy can produce, such as a uniform slip of 1e10 m, fails one of them.
        """
        N = model.x.size
        fields = {"slip": self.slip, "episode_start": self.episode_start, "tally.w": self.tally.w}
        fields |= {"tally.slip_min": self.tally.slip_min, "tally.slip_max": self.tally.slip_max}
        peaks = {f"tally.{name}": getattr(self.tally, name) for name in CYCLE_PEAKS}
        for name, values in (fields | peaks).items():
            values = np.asarray(values)
            if values.shape != (N,):
                raise HistoryError(
                    f"state.{name} has shape {values.shape}, expected ({N},): the nodes of {model.spec.name}"
                )
            if name not in peaks and not np.all(np.isfinite(values)):
                raise HistoryError(f"state.{name} is not finite at node {int(np.argmin(np.isfinite(values)))}")
        if np.any(self.tally.w < 0):
            raise HistoryError(
                f"state.tally.w is negative at node {int(np.argmax(self.tally.w < 0))}: energy is dissipated"
            )
        numbers = {
            "Q": self.Q,
            "sigma": self.sigma,
            "dissipated": self.dissipated,
            "tally.dissipation": self.tally.dissipation,
            "slid": self.slid,
        }
        numbers |= {f"memory[{k}]": value for k, value in enumerate(self.memory)}
        for name, value in numbers.items():
            if not np.isfinite(value):
                raise HistoryError(f"state.{name} = {value!r}, expected a finite number")
        for name in ("dissipated", "tally.dissipation"):
            if numbers[name] < 0:
                raise HistoryError(
                    f"state.{name} = {numbers[name]!r}, expected a finite number >= 0 (energy dissipated)"
                )
        P = contact.P if self.P is None else self.P
        if abs(self.Q) > contact.f * P or (abs(self.Q) == contact.f * P and not model.slides):
            raise HistoryError(f"state.Q = {self.Q!r} leaves no stick zone on this contact (f P = {contact.f * P!r})")
        self.consistency(contact, model)

    def consistency(self, contact, model: Continued) -> None:
        """Raise HistoryError unless the slip agrees with the loads, the model's memory and the energy (`check`)."""
        outcome = model.at_rest(self)
        scale = float(np.max(np.abs(self.slip), initial=0.0))
        off = np.abs(outcome.slip - self.slip) > SLIP_RTOL * scale
        if off.any():
            node = int(np.argmax(off))
            raise HistoryError(
                f"state.slip = {self.slip[node]!r} m at node {node}, where the model's memory gives "
                f"{float(outcome.slip[node])!r} m: a slip the recorded turning points cannot produce"
            )
        excess = _excess(outcome, contact, model, contact.P if self.P is None else self.P)
        if np.max(excess) > COULOMB_TOLERANCE:
            node = int(np.argmax(excess))
            raise HistoryError(
                f"state.slip leaves a traction above f p by {float(excess[node]):.6g} f p0 at node {node} under "
                f"the state's loads, expected at most f p (Coulomb): a slip the loads cannot produce"
            )
        if self.P is None and hasattr(model, "dissipation"):
            least = model.dissipation(self.slip)
            if least > self.dissipated * (1 + ENERGY_RTOL):
                raise HistoryError(
                    f"state.slip needs at least {least!r} J/m dissipated (int f p |slip| dx), "
                    f"state.dissipated = {self.dissipated!r}: a slip the recorded energy cannot produce"
                )


#: How far the slip that a model derives from its memory may differ from the state's, relative to the
#: largest slip: rounding of the closed forms.
SLIP_RTOL = 1e-9
#: How far beyond ``f p`` a state's traction may be, relative to the largest ``f p``: the rounding of
#: the slip-to-traction product at the edges.
COULOMB_TOLERANCE = 1e-9
#: How far ``int f p |s| dx`` may exceed the energy dissipated, relative: rounding of the sums.
ENERGY_RTOL = 1e-9


def _excess(outcome, contact, model, P):
    """``(|q| - f p) / max(f p)`` at the nodes after `outcome` under the normal load `P` [N/m]: in the
    model's own measure where it has one (method 4: its ``g`` against its ``limit``), else from its
    traction. Relative to the largest limit, since at the edges, where ``f p`` vanishes, ``g`` is
    the difference of large numbers."""
    if hasattr(model, "limit"):
        g, limit = np.abs(outcome.g), model.limit
    else:
        g, limit = np.abs(model.traction(outcome)), contact.f * model.pressure_at(P)
    return (g - limit) / np.max(limit)


def _folded(op, held, rows, first, length):
    """``op`` of each stretch's `held` row with its `rows` (the `length` rows from `first`), applied
    row after row in order, one stretch per row of the result."""
    folded = held.copy()
    for k in range(int(length.max())):
        live = length > k
        if live.all():
            folded = op(folded, rows[first + k])
        else:
            folded[live] = op(folded[live], rows[first[live] + k])
    return folded
