"""The recorder: which steps of a run are stored, the per-cycle rows, and the dataset they make.

The stepper tells the recorder of every step and cycle (`Recorder.step`, `Recorder.copied`,
`Recorder.cycle`); the recorder keeps the fields of the steps it was asked to record and one row
per load cycle, and turns them into the variables of `fretting.results.variables.VARIABLES`
(`Recorder.dataset`). `final_state` reads the state back from such a dataset.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from fretting.loading.loads import Loads
from fretting.models.base import ModelSpec
from fretting.models.state import State, Tally
from fretting.results.loops import with_loops
from fretting.results.variables import ACCUMULATED, CYCLE_FIELDS, CYCLE_PEAKS, build_dataset, variable

__all__ = [
    "CYCLE_FIELDS_STORED",
    "RECORDED_ENDS",
    "RECORD_ALL_STEPS",
    "CycleFields",
    "FieldSelector",
    "Recorder",
    "final_state",
    "recorded_spec",
    "recorded_steps",
    "regime",
]

#: Default recording: every step of histories up to this many steps; of longer ones the first
#: and the last RECORDED_ENDS steps (64 cycles of 64 steps), so that the fields stored stay
#: bounded (about 6.5 kB per step at 384 nodes).
RECORD_ALL_STEPS = 20_000
RECORDED_ENDS = 4096

#: Per-cycle peaks that a run which skips steps does not tally: the surface ``sigma_xx`` is not
#: monotonic along a straight stretch (`fretting.engine.follow`).
SKIPPED_PEAKS = ("sigma_xx_peak", "sigma_xx_q_peak")

#: The dataset's ``cycle_peaks`` attribute, by whether the run skipped steps.
CYCLE_PEAKS_TALLIED = {
    False: "every step",
    True: "q_peak over every step (its largest is at the solved ends of a straight stretch); "
    "sigma_xx_peak and sigma_xx_q_peak not tallied: steps inside straight stretches were skipped",
}


#: Cycles whose fields the default policy stores about at most: histories of up to this many
#: cycles keep every cycle's; longer ones the first and the last, every k-th with
#: ``k = ceil(cycles / CYCLE_FIELDS_STORED)``, and those that set a new maximum of the energy per
#: cycle (a few: about the logarithm of the cycles on a random spectrum).
CYCLE_FIELDS_STORED = 1000

#: What `CycleFields.parse` accepts, for its error.
CYCLE_FIELDS_EXPECTED = '"all", "default", or a comma-separated list of first, last, every=K (K >= 1) and maxima'


@dataclass(frozen=True)
class CycleFields:
    """The policy that chooses the cycles whose per-cycle fields (`CYCLE_FIELDS`) a run stores.

    Per-cycle scalars (``cycle_dissipation``, ``cycle_copied``) are stored for every cycle
    whatever the policy. Written as text (`parse`, `str`): ``all``, or the cycles chosen,
    ``first,last,every=K,maxima`` (any of them).

    Attributes
    ----------
    all : bool
        Every cycle (the fields then keep their dims ``(cycle_number, x)``).
    first, last : bool
        The first cycle (number 1) and the history's last one.
    every : int
        Every cycle whose number is a multiple of `every` (0: none).
    maxima : bool
        Every cycle whose ``cycle_dissipation`` exceeds that of every cycle before it.
    """

    all: bool = False
    first: bool = False
    last: bool = False
    every: int = 0
    maxima: bool = False

    @classmethod
    def parse(cls, text: str, cycles: int) -> CycleFields:
        """The policy written `text` (`CYCLE_FIELDS_EXPECTED`) for a history of `cycles` cycles.

        ``default`` is every cycle for histories of up to `CYCLE_FIELDS_STORED` cycles, else
        ``first,last,every=K,maxima`` with ``K = ceil(cycles / CYCLE_FIELDS_STORED)``.

        Raises
        ------
        ValueError
            Naming ``cycle_fields`` and what is expected.
        """
        if text == "all" or (text == "default" and cycles <= CYCLE_FIELDS_STORED):
            return cls(all=True)
        if text == "default":
            return cls(first=True, last=True, every=math.ceil(cycles / CYCLE_FIELDS_STORED), maxima=True)
        items = text.split(",")
        flags = {item: True for item in items if item in ("first", "last", "maxima")}
        every = [item.removeprefix("every=") for item in items if item.startswith("every=")]
        if len(flags) + len(every) != len(items) or len(every) > 1 or not all(map(_positive_integer, every)):
            raise ValueError(f"cycle_fields must be {CYCLE_FIELDS_EXPECTED}, found {text!r}")
        return cls(every=int(every[0]) if every else 0, **flags)

    def __str__(self) -> str:
        if self.all:
            return "all"
        chosen = ["first"] * self.first + ["last"] * self.last + [f"every={self.every}"] * bool(self.every)
        return ",".join(chosen + ["maxima"] * self.maxima)

    def chosen(self, numbers: np.ndarray, new_maximum: np.ndarray, last: int) -> np.ndarray:
        """Which of the complete cycles `numbers` (with `new_maximum`: each sets one) are stored,
        in a history whose last cycle is `last`."""
        chosen = np.full(numbers.shape, self.all) | (self.maxima & new_maximum)
        chosen |= (self.first & (numbers == 1)) | (self.last & (numbers == last))
        return chosen | ((numbers % self.every == 0) if self.every else False)


def _positive_integer(text):
    return text.isdigit() and int(text) > 0


class FieldSelector:
    """The per-cycle fields of a run's chunks cut to the cycles its `CycleFields` policy chooses
    (not ``all``: a result of every cycle's fields is left as it is), and their accumulation over
    every complete cycle (`ACCUMULATED`, and ``cycle_dissipation_max``).

    A cycle's row is taken once the cycle is complete (the chunk reaches its last step); a chunk's
    row of a cycle still in progress is left for the chunk that completes it. Sums and maxima run
    over the complete cycles in their order, so a run cut anywhere accumulates the same bits.

    Parameters
    ----------
    policy : CycleFields
    ends : ndarray of int
        The last step of each cycle of the whole history, by cycle number (``History.cycle_ends``).
    done : xarray.Dataset, optional
        The result so far of a resumed run (its accumulated fields and ``cycle_dissipation_max``).
    """

    def __init__(self, policy, ends, done=None):
        self.policy, self.last, self.ends = policy, ends.size - 1, ends
        self.taken = 0 if done is None else int(np.searchsorted(self.ends[1:], done.attrs["steps"] - 1, "right"))
        self.accumulated = {} if done is None else {name: done[name].values for name in ACCUMULATED if name in done}
        self.peak = -np.inf if done is None else float(np.nan_to_num(done.cycle_dissipation_max, nan=-np.inf))

    def take(self, chunk, stop):
        """`chunk` (a result of the steps up to `stop` of the whole history) with the fields of the
        cycles chosen and the accumulated fields."""
        numbers = chunk.cycle_number.values
        complete = (numbers > self.taken) & (self.ends[numbers] <= stop)
        fields = [name for name in CYCLE_FIELDS if name in chunk]
        rows = {name: chunk[name].values[complete] for name in fields}
        energy = chunk.cycle_dissipation.values[complete]
        before = np.maximum.accumulate(np.append(self.peak, energy))
        chosen = self.policy.chosen(numbers[complete], energy > before[:-1], self.last)
        self.peak, self.taken = float(before[-1]), int(numbers[complete].max(initial=self.taken))
        for name, field in ACCUMULATED.items():
            if field in rows:
                self.accumulated[name] = self._accumulate(name, rows[field])
        data = {name: variable(name, values) for name, values in self.accumulated.items()}
        data["cycle_dissipation_max"] = variable("cycle_dissipation_max", self.peak if self.peak > -np.inf else np.nan)
        data |= {name: variable(name, rows[name][chosen], ("field_cycle", "x")) for name in fields}
        data["field_cycle"] = variable("field_cycle", numbers[complete][chosen], ("field_cycle",))
        return chunk.drop_vars(fields).assign(data).set_coords("field_cycle")

    def _accumulate(self, name, rows):
        """The accumulated field `name` after the complete cycles' `rows` (float32) of its field."""
        held = self.accumulated.get(name)
        if name == "w_total":  # summed cycle after cycle, in float64 (cumsum adds in order)
            start = np.zeros(rows.shape[1]) if held is None else held
            return np.cumsum(np.vstack([start, rows.astype(np.float64)]), axis=0)[-1]
        largest = rows.astype(np.float64).max(axis=0, initial=-np.inf)
        return largest if held is None else np.fmax(held, largest)


def recorded_steps(record, n):
    """Step numbers to record of an `n`-step history: `record` (increasing steps, or "all"), or
    by default every step of histories up to `RECORD_ALL_STEPS` steps, else the first and the
    last `RECORDED_ENDS` steps."""
    if record is None:
        if n <= RECORD_ALL_STEPS:
            return np.arange(n)
        return np.concatenate([np.arange(RECORDED_ENDS), np.arange(n - RECORDED_ENDS, n)])
    if isinstance(record, str) and record == "all":
        return np.arange(n)
    steps = np.asarray(record)
    if steps.ndim != 1 or not (steps.size == 0 or np.issubdtype(steps.dtype, np.integer)):
        raise ValueError(f'record must be a list of step numbers or "all", found {record!r}')
    if np.any(np.diff(steps) <= 0) or np.any(steps < 0) or np.any(steps >= n):
        raise ValueError(f"record must list increasing steps between 0 and {n - 1}")
    return steps.astype(np.int64)


class Recorder:
    """The fields of the recorded `steps` of a run of `model` over `history`, and a row per cycle.

    Parameters
    ----------
    model : Model
    history : History
    steps : ndarray of int
        Steps to record, increasing (`recorded_steps`).
    skipping : bool
        Have the run skip the steps inside straight stretches that are not recorded
        (`fretting.engine.follow.skippable`); the specimen's ``sigma_xx`` peaks per cycle are
        then not tallied and not stored, and the dataset's ``cycle_peaks`` attribute says so.
    """

    def __init__(self, model, history, steps, skipping=False):
        self.model, self.history, self.steps, self.skipping = model, history.explicit(), steps, skipping
        self.row = np.full(len(history), -1)
        self.row[steps] = np.arange(steps.size)
        N = model.x.size
        self.fields = {
            "q": np.empty((steps.size, N)),
            "slip": np.empty((steps.size, N)),
            "stick": np.empty((steps.size, N), dtype=bool),
            "dissipation": np.empty(steps.size),
            "Q": np.empty(steps.size),
            "delta_Q": np.empty(steps.size),
            "delta_sigma": np.empty(steps.size),
        }
        if model.contact.datum is not None:
            self.fields["delta"] = np.empty(steps.size)
            self.fields["regime"] = np.empty(steps.size, dtype=np.int8)
        self.zones = [()] * steps.size
        self.cycles = []  # (number, tally, copied) of every cycle the run touches

    def step(self, step, outcome, state):
        """The increment to `step` gave `outcome` and left `state`: store its fields if `step` is recorded."""
        k = self.row[step]
        if k < 0:
            return
        model = self.model
        self.fields["q"][k] = model.traction(outcome)
        self.fields["slip"][k] = state.slip
        self.fields["stick"][k] = outcome.ds == 0
        self.fields["dissipation"][k] = outcome.dissipation
        self.fields["Q"][k] = state.Q  # the history's, or the Q found for its delta
        self.fields["delta_Q"][k] = delta_Q = model.delta_Q(outcome)
        if "delta" in self.fields:
            self.fields["delta"][k] = model.contact.displacement(state.Q, delta_Q, state.P)
            self.fields["regime"][k] = regime(model, outcome, state)
        self.fields["delta_sigma"][k] = model.delta_sigma(outcome)
        self.zones[k] = model.stick_zones(outcome, state)

    def copied(self, step, copies, steps):
        """The `copies` cycles from `step` repeat the increments `steps` ((outcome, state) of one cycle)."""
        length = len(steps)
        rows = self.row[step : step + copies * length]
        for offset in np.flatnonzero(rows >= 0):
            self.step(step + offset, *steps[offset % length])

    def cycle(self, number, tally, copied):
        """Cycle `number` ended with `tally` (the same object for consecutive copies); `copied`: not solved."""
        self.cycles.append((number, tally, copied))

    def data(self, state):
        """The arrays of the result (names from `VARIABLES`) of a run that ended in `state`."""
        model, history, steps = self.model, self.history, self.steps
        spec = model.spec
        data = self.fields | _zone_ends(model.contact, self.zones)
        if history.cycle is not None:
            data["cycle"] = history.cycle[steps].astype(np.int64)  # the History holds it in 32 bits
            data |= _cycle_rows(self.cycles, model.x.size, SKIPPED_PEAKS if self.skipping else ())
        tally = state.tally
        return (
            data
            | {
                "sigma": history.sigma[steps],
                "p": model.pressure_at(model.contact.P),
                "x": model.x,
                "step": steps,
                "vertex_step": history.vertex_step,
                "vertex_Q": history.Q[history.vertex_step],
                "vertex_sigma": history.sigma[history.vertex_step],
                "state_Q": state.Q,
                "state_sigma": state.sigma,
                "state_slip": state.slip,
                "state_episode_start": state.episode_start,
                "state_cycle": tally.number,
                "state_cycle_dissipation": tally.dissipation,
                "state_w": tally.w,
                "state_slip_min": tally.slip_min,
                "state_slip_max": tally.slip_max,
                "state_load_low": tally.load_low,
                "state_load_high": tally.load_high,
                "total_dissipation": state.dissipated,
            }
            | {f"state_{name}": getattr(tally, name) for name in CYCLE_PEAKS}
            | ({} if model.theta is None else {"theta": model.theta[::-1]})
            | ({} if spec.memory_variable is None else {spec.memory_variable: np.array(state.memory, dtype=float)})
            | ({} if history.P is None else _normal_loads(model, history, steps, state))
            | ({} if state.loads.delta is None else {"state_delta": state.loads.delta})
            | ({} if not state.slid else {"state_slid": state.slid})
            | ({} if history.delta is None else {"vertex_delta": history.delta[history.vertex_step]})
        )

    def dataset(self, state):
        """The result dataset of a run that ended in `state`: `data` with the contact's and the model's attributes."""
        contact, spec = self.model.contact, self.model.spec
        attributes = {
            "a": contact.a,
            "p0": contact.p0,
            "E_star": contact.E_star,
            "f": contact.f,
            "P": contact.P,
            "centre": contact.centre,
            "profile": repr(contact.profile),
            **contact.profile.attributes(),
            **({} if contact.nu is None else {"nu": contact.nu}),
            **({} if contact.datum is None else {"datum": contact.datum, "compliance": contact.compliance}),
            "specimen": contact.specimen,
            "nodes": self.model.x.size,
            "model_description": spec.description,
            "steps": len(self.history),
            "cycle_peaks": CYCLE_PEAKS_TALLIED[self.skipping],
        }
        return with_loops(build_dataset(self.data(state), attributes | spec.attributes()))


def final_state(result: xr.Dataset) -> State:
    """State at the last step of a result of `fretting.simulate`, to continue the history from.

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> first = fr.History.piecewise_linear([0, 30e3], None, 8)
    >>> state = final_state(fr.simulate(contact, first, fr.models.Grid(32)))
    >>> state.Q, state.model
    (30000.0, Grid(nodes=32))
    >>> later = fr.simulate(contact, fr.History.piecewise_linear([30e3, -30e3], None, 8), state=state)
    >>> float(later.Q[-1])
    -30000.0
    """
    tally = Tally(
        int(result.state_cycle),
        float(result.state_cycle_dissipation),
        result.state_w.values.copy(),
        result.state_slip_min.values.copy(),
        result.state_slip_max.values.copy(),
        *(_tallied(result, f"state_{name}", result.sizes["x"]) for name in CYCLE_PEAKS),
        *(_tallied(result, name, 3) for name in ("state_load_low", "state_load_high")),
    )
    spec = recorded_spec(result)
    P = None if "state_P" not in result or float(result.state_P) == result.attrs["P"] else float(result.state_P)
    delta = float(result.state_delta) if "state_delta" in result else None
    memory = spec.memory_variable
    return State(
        Loads(float(result.state_Q), float(result.state_sigma), P, delta),
        result.state_slip.values.copy(),
        result.state_episode_start.values.copy(),
        tally,
        spec,
        float(result.total_dissipation),
        tuple(result[memory].values.tolist()) if memory is not None and memory in result else (),
        float(result.state_slid) if "state_slid" in result else 0.0,
    )


def regime(model, outcome, state):
    """The regime of the increment `outcome` that left `state`, an index of `fretting.results.variables.REGIMES`:
    stuck where no node slipped, gross slip where ``|Q|`` reached the friction force (the whole contact
    slides, or is on the point of sliding), partial slip otherwise."""
    if not outcome.ds.any():
        return 0
    return 2 if abs(state.Q) >= model.sliding_force(state.P) else 1


def recorded_spec(result: xr.Dataset) -> ModelSpec:
    """The resolved spec a result was run with, from its ``model`` attribute and nodes (`ModelSpec.recorded`)."""
    theta = result.theta.values[::-1].copy() if "theta" in result else None  # ascending in theta
    return ModelSpec.recorded(result.attrs, theta)


def _tallied(result, variable, size):
    """The tally's `variable` (a ``state_`` peak or load extreme, `size` values) of the cycle in progress in
    `result` (NaN, unknown, in results written without it)."""
    return result[variable].values.copy() if variable in result else np.full(size, np.nan)


def _cycle_rows(cycles, N, left_out):
    """Per-cycle variables from the ``(number, tally, copied)`` of every cycle of a run, but the
    peaks `left_out`.

    Copied cycles share the tallies of the cycles they copy, so each distinct tally object is turned
    into rows once.
    """
    numbers = np.array([number for number, _, _ in cycles], dtype=np.int64)
    repeated = np.array([copy for _, _, copy in cycles], dtype=bool)
    index = {}  # id of each distinct tally (all alive in `cycles`) -> its row
    which = np.array([index.setdefault(id(tally), len(index)) for _, tally, _ in cycles], dtype=np.int64)
    distinct = list({id(tally): tally for _, tally, _ in cycles}.values())

    def rows(values, dtype, width):
        return np.array(values, dtype=dtype).reshape(len(distinct), width)[which]

    return {
        "cycle_number": numbers,
        "cycle_dissipation": rows([t.dissipation for t in distinct], float, 1)[:, 0],
        "cycle_load_range": rows([t.load_high - t.load_low for t in distinct], float, 3),
        "cycle_copied": repeated,
        "w": rows([t.w for t in distinct], np.float32, N),
        "slip_amplitude": rows([t.slip_amplitude for t in distinct], np.float32, N),
    } | {
        name: rows([getattr(t, name) for t in distinct], np.float32, N) for name in CYCLE_PEAKS if name not in left_out
    }


def _normal_loads(model, history, steps, state):
    """``P``, ``a``, ``p_step`` of the recorded `steps` of a history of ``P``; its vertices' and the state's ``P``."""
    contact, P = model.contact, history.P[steps]
    return {
        "P": P,
        "a": np.array([contact.profile.half_width(load, contact.E_star)[0] for load in P]),
        "p_step": np.array([model.pressure_at(load) for load in P]).reshape(P.size, model.x.size),
        "vertex_P": history.P[history.vertex_step],
        "state_P": contact.P if state.P is None else state.P,
    }


def _zone_ends(contact, zones):
    """`stick_start` and `stick_end` [m] from per-step lists of normalised stick intervals."""
    ends = np.full((len(zones), max((len(z) for z in zones), default=0), 2), np.nan)
    for k, z in enumerate(zones):
        if z:  # none in gross slip
            ends[k, : len(z)] = z
    ends = contact.centre + contact.a * ends
    return {"stick_start": ends[..., 0], "stick_end": ends[..., 1]}
