"""Following a history: one increment (`advance`) and a pass over a history (`follow`) with its
load cycles tallied and repeating cycles copied.

A cycle whose loads repeat those of the cycle just completed, from a state that repeats the
state before that cycle bit for bit, would repeat its increments bit for bit (the increment
depends on the loads and the state only); such cycles are copied instead of solved, and the
recorder is told so (`Recorder.copied`). Rounding can leave the state periodic over a few cycles
rather than one (bit for bit every few cycles, with rounding-level differences in between, as the
CPU's BLAS kernels have it): where the state before a cycle
repeats the state before one of the last `PERIOD_CYCLES` cycles, those cycles are solved once more
as a block and the blocks that follow are copied.

A recorder that skips (`Recorder.skipping`) has the steps inside straight stretches of the load
path solved only where they are recorded (`skippable`): along a straight (proportional) stretch
every node slips one way only, so one increment from the stretch's start reaches the state at
its end, and its energy, energy density and slip range are those of the steps it spans, to
rounding. ``q`` is monotonic along such a stretch, so the largest ``|q|`` over it is at one of
its ends, but the surface ``sigma_xx`` is not (tests/engine/test_skipping.py): the specimen's
``sigma_xx`` peaks are then not tallied (NaN), only ``q_peak`` is.

A model that steps several increments as rows (`ExactModel.window`: the exact model of ``Q``
alone) has the solved steps that nothing records or copies taken a window at a time
(`_Run._window`), with the tallies and each node's episode formed as step by step would, bit for
bit (tests/engine/test_window.py).
"""

import math
from collections import deque
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq

from fretting.errors import GrossSlipError, HistoryError, SolverError
from fretting.loading.loads import Loads, edge_loads
from fretting.models.base import UNFOLLOWED
from fretting.models.state import State, Tally
from fretting.physics.surface import SurfaceStress, bulk_stress

__all__ = ["BRACKET", "STRAIGHT", "advance", "displaced", "follow", "skippable", "slid"]

#: Largest ``|sin|`` of the turn between two increments, in units of ``(f P, f p0)``, that counts
#: as straight: the steps of a linear segment meet it to rounding, and a sampled curve with a
#: million steps per turn (a turn of 6e-6 rad a step) does not.
STRAIGHT = 1e-9

#: Solved steps whose loads a model that prepares (``model.prepare(state, Q)``, the exact model)
#: is given at once, ahead of solving them: its branches are then solved together.
PREPARED_STEPS = 512


#: Most cycles over which a state that repeats bit for bit is looked for (`_Run.follow`).
PERIOD_CYCLES = 8


#: Relative distance below the friction force at which `displaced` brackets ``Q``: a trial increment
#: nearer to sliding may find no stick zone within rounding, and a displacement beyond the bracket's
#: is taken as gross slip.
BRACKET = 1e-9


def displaced(model, state, loads, step=None):
    """``(loads, trial)``: `loads` (`Loads`) with the ``Q`` [N/m] that meets their prescribed displacement
    ``delta`` [m] from `state`, and the `Outcome` of the trial increment to that ``Q`` (None where none was
    solved: `advance` solves it); `loads` as they are where ``delta`` is None.

    ``delta(Q) = (C_L + C) Q + delta_Q(Q)`` (`fretting.physics.contact.Contact.displacement`, eq D4
    of docs/theory/displacement.md), ``C_L`` of the half-width under the step's ``P`` and
    ``delta_Q(Q)`` that of the model's increment from `state` to ``Q`` with the loads' ``sigma`` and
    ``P``: a trial increment, which leaves `state` as it is (models are pure). ``delta(Q)`` increases
    with ``Q``, so ``Q`` is bracketed between the state's ``Q`` and ``+-(1 - BRACKET)`` times the
    friction force of the step's ``P`` and found by Brent's method to the precision of a float. Its
    slip part ``delta_Q`` does not fall as ``Q`` grows either, so the ``Q`` that would meet ``delta``
    if nothing more slipped, ``(C_L + C) dQ = ddelta``, lies at or past the one sought: the nearer
    end of the bracket where it is nearer than the friction force (a small step then solves no trial
    close to sliding); where rounding leaves it short, the search goes on from it. Each trial's
    ``delta`` is kept for the step (Brent's method asks again for the bracket's ends), and the increment
    to the ``Q`` found is that trial: the step solves it once.
    Loads that hold the state's ``delta``, ``sigma`` and ``P`` hold its ``Q``. The increment to the
    loads returned is the force-controlled one (`advance`), so the memory is carried as under force
    control. `step` names the step in an error.

    A model that slides (`Model.slides`, the exact model) is tried at ``+-f P`` itself where the
    bracket holds no root: ``Q`` is found between the bracket's end and ``+-f P``, or, beyond
    ``delta(+-f P)``, is ``+-f P``: gross slip, which `advance` takes as a uniform slide
    (docs/theory/displacement.md#gross-slip).

    Raises
    ------
    HistoryError
        Where the contact has no datum, or its contact under the step's ``P`` reaches the datum.
    GrossSlipError
        Where ``delta`` is not reached below the friction force by a model that does not slide.
    """
    if loads.delta is None:
        return loads, None
    contact = model.contact
    where = "" if step is None else f"step {step}: "
    if contact.displacement_compliance is None:
        raise HistoryError(
            f"{where}the history prescribes delta, but the contact has no datum: give fretting.Contact(..., datum=L)"
        )
    try:
        contact.compliance_under(loads.P)
    except ValueError as error:
        raise HistoryError(f"{where}{error}") from None
    held = state.loads
    if (held.delta, held.sigma, held.P) == (loads.delta, loads.sigma, loads.P):
        return replace(loads, Q=held.Q), None
    sliding = model.sliding_force(loads.normal(contact))
    tried = {}  # Q: (missed(Q), the trial increment's Outcome)

    def missed(Q):
        """``delta(Q) - delta`` [m] of the trial increment to `Q` [N/m] under the step's ``sigma`` and ``P``."""
        if Q not in tried:
            trial = model.increment(state, Loads(Q, loads.sigma, loads.P))
            tried[Q] = contact.displacement(Q, model.delta_Q(trial), loads.P) - loads.delta, trial
        return tried[Q][0]

    def found(Q):
        return replace(loads, Q=float(Q)), tried[Q][1] if Q in tried else None

    begin = min(max(held.Q, -sliding), sliding)  # the state's Q, or the step's friction force where P fell
    start = missed(begin)
    if start == 0:
        return found(begin)
    end = math.copysign(sliding * (1 - BRACKET), -start)
    stuck = begin - start / contact.compliance_under(loads.P)  # meets delta if nothing more slips
    if abs(stuck - begin) < abs(end - begin):  # the nearer end, where it brackets Q
        if missed(stuck) * start > 0:  # short of Q by rounding: the search goes on from it
            begin, start = stuck, missed(stuck)
        else:
            end = stuck
    eps = np.finfo(float).eps
    if missed(end) * start > 0:
        if not model.slides:
            raise GrossSlipError(step, math.copysign(sliding, end), loads.sigma, sliding, UNFOLLOWED)
        limit = math.copysign(sliding, end)
        if missed(limit) * start > 0:
            return found(limit)  # gross slip
        begin, end = end, limit
    return found(brentq(missed, begin, end, xtol=eps * sliding, rtol=4 * eps))


def slid(model, state, loads, reached=None):
    """`Outcome` of gross slip from `state` to `loads` (``Q = +-friction_force``, found by `displaced`):
    the increment to ``+-f P``, then the uniform slide ``du`` [m] that meets ``loads.delta``
    (`Model.slide`). ``du`` has the sign of ``Q``, or is 0: where Brent's method found ``Q`` at ``+-f P``
    within its tolerance, or the step holds the state's delta. `reached`: the increment to ``+-f P``, where
    solved already."""
    contact, force = model.contact, loads.force()
    reached = model.increment(state, force) if reached is None else reached
    du = loads.delta - contact.displacement(loads.Q, model.delta_Q(reached), loads.P)
    return model.slide(state, force, du if du * loads.Q > 0 else 0.0)


def advance(model, state, loads, step=None, guess=None, at_rest=False, tally=True, stress=True, solved=None):
    """(outcome, state after) of the increment of `model` from `state` to `loads` (`Loads`; with a
    prescribed ``delta``, its ``Q`` found by `displaced`: the model is given the loads without it).

    `at_rest`: no increment, the state as it stands (the starting state of a history). `step`
    names the step in a `GrossSlipError`. An increment that reports negative dissipation is a
    solver failure (`SolverError`), never a result. `tally`: add the increment to the cycle in
    progress (its energy density and peaks); False where only the slip matters (mesh adaptation).
    `stress`: tally the specimen's surface stress peaks (False: NaN, not known, as for a run that
    skips steps). ``loads.P`` None: the contact's normal load, which the models of a constant ``P``
    are given no other. `solved`: the `Outcome` of the increment to `loads`, where `displaced` solved it
    as a trial (models are pure: the same increment, whose answer does not depend on `guess`).
    """
    Q, sigma = loads.Q, loads.sigma
    sliding = model.sliding_force(loads.normal(model.contact))  # no stick zone from here on
    sliding_whole = loads.delta is not None and model.slides and abs(Q) == sliding
    if abs(Q) >= sliding and not sliding_whole:
        raise GrossSlipError(step, Q, sigma, sliding)
    if at_rest:
        return model.at_rest(state), state
    try:
        if sliding_whole:
            outcome = slid(model, state, loads, solved)
        else:
            outcome = model.increment(state, loads.force(), guess) if solved is None else solved
    except GrossSlipError:  # within rounding of the friction force: the increment found no stick zone
        raise GrossSlipError(step, Q, sigma, sliding) from None
    if not outcome.dissipation >= 0:
        raise SolverError(f"the increment to Q = {Q!r}, sigma = {sigma!r} dissipated {outcome.dissipation!r} J/m")
    if not (tally and state.tally.number):
        return outcome, state.advance(outcome, loads, None, None, None, None)
    if stress:
        surface, shear = specimen_surface(model, outcome, sigma)
    else:
        surface, shear = None, np.abs(model.traction(outcome))
    edges = edge_loads(loads, model.contact)
    return outcome, state.advance(outcome, loads, model.energy_density(outcome), surface, shear, edges)


def specimen_surface(model, outcome, sigma):
    """The specimen's surface direct stress [Pa], with its bulk stress, and ``|q|`` [Pa] at the nodes after `outcome`.

    `sigma` [Pa] is the differential bulk tension after the increment; the specimen is the
    contact's (`Contact.specimen`). One product with the model's precomputed Hilbert matrix
    (`Model.surface`) with the square-root profile at the stick ends, today's and those earlier turning
    points left in the stick zone, fitted to the slip
    (`fretting.physics.surface.SurfaceStress.at_stick_ends`), the formula
    `fretting.analysis.nucleation.surface_stress` evaluates at the recorded steps.
    """
    surface, p = model.surface_at(outcome)
    contact, q = model.contact, model.traction(outcome)
    if isinstance(surface, SurfaceStress):  # nodal tractions' or closed form's: the stick ends from the slip
        modulus, fp0 = contact.E_star / contact.a, contact.f * contact.p0
        surface = surface.at_stick_ends(q, p, outcome.slip, outcome.ds == 0, sigma, modulus, fp0)
    body = contact.specimen
    return surface(q, p, bulk_stress(sigma, body, specimen=body), body), np.abs(q)


def follow(model, history, state, recorder=None, observe=None, guess=None, tally=True):
    """Run `history` on `model` from `state` (whose loads are the history's first); return the last state.

    `recorder` is told of every step and cycle, and says whether steps are skipped
    (`Recorder.skipping`, `skippable`); ``observe(step, outcome)`` sees the `Outcome` of every
    step solved (its slip increment ``ds``, traction ``g`` and slip); ``guess(step)`` gives the
    slip directions to start the solver from, or None; `tally` as for `advance`.
    """
    return _Run(model, history.explicit(), recorder, observe, guess, tally).follow(state)


def skippable(history, recorded, contact):
    """Steps of `history` that a run need not solve: those strictly inside a straight stretch.

    A step is skippable when the increments to it and from it point the same way (their turn
    below `STRAIGHT` in units of ``(f P, f p0)`` of `contact`) and it is not the first or last
    step, a vertex, a step in the boolean mask `recorded`, or the first or last step of a load
    cycle or of the steps outside cycles (the cycle's ``|q|`` peak is over its steps, not its
    starting state: with its first step solved, it is at solved steps, since ``q`` is monotonic
    along a straight stretch). Which steps are skippable depends on the step and its two
    neighbours only, so a run cut at steps that are not skippable solves the same steps as
    the whole run, which keeps a run continued from its state equal to the whole run bit for bit.

    Returns
    -------
    ndarray of bool, shape (len(history),)
    """
    dQ = np.diff(history.Q) / (contact.f * contact.P)
    dsigma = np.diff(history.sigma) / (contact.f * contact.p0)
    dot = dQ[:-1] * dQ[1:] + dsigma[:-1] * dsigma[1:]
    turn = np.abs(dQ[:-1] * dsigma[1:] - dsigma[:-1] * dQ[1:])
    skip = np.zeros(len(history), dtype=bool)
    if history.P is not None:  # a straight stretch of (Q, sigma) need not be one of P
        return skip
    skip[1:-1] = (dot > 0) & (turn <= STRAIGHT * np.hypot(dQ[:-1], dsigma[:-1]) * np.hypot(dQ[1:], dsigma[1:]))
    skip[history.vertex_step] = False
    if history.cycle is not None:
        same = history.cycle[1:] == history.cycle[:-1]
        skip[:-1] &= same
        skip[1:] &= same
    return skip & ~recorded


def engine_loads(loads, contact):
    """`loads` as the engine gives them to a model: ``P`` None where it is the contact's, which every model runs."""
    return loads if loads.P is None or loads.P != contact.P else replace(loads, P=None)


@dataclass(frozen=True, eq=False)
class _Cycle:
    """Complete cycles solved in a row, one or a period of them: the first step, the state before
    them, each increment's (outcome, state after), None for a step skipped, and each cycle's tally."""

    first: int
    before: State
    steps: list
    tallies: list


class _Run:
    """One pass over a history: increments, cycles, copies, and what the recorder is told."""

    def __init__(self, model, history, recorder, observe, guess, tally):
        self.model, self.history, self.recorder = model, history, recorder
        self.observe, self.guess, self.tally = observe, guess, tally
        self.cycle = history.cycle if history.cycle is not None else np.zeros(len(history), dtype=np.int64)
        self.stress = recorder is None or not recorder.skipping
        if self.stress:
            self.skip = np.zeros(len(history), dtype=bool)
        else:
            self.skip = skippable(history, recorder.row >= 0, model.contact)
        self.solved = np.flatnonzero(~self.skip)  # the last step is never skipped
        self.loads = history.loads
        # the steps before it are prepared; none where Q is found step by step (`displaced`)
        self.prepared = len(history) if history.displaced else 0
        windows = model.windows and not self.stress and tally and observe is None and guess is None
        windows = windows and not history.displaced
        if windows and history.P is None:
            self.windowed = ~self.skip & (recorder.row < 0) & ~self._copyable()
            self.windowed[0] = False  # it may be the state at rest
        else:
            self.windowed = np.zeros(len(history), dtype=bool)

    def follow(self, state):
        """Run from `state`; return the state at the end."""
        previous = None  # the last cycles solved whole in this run: the block a repeating block copies
        # the state before the block in progress (if it began here), its increments, its closed cycles' tallies
        before, steps, tallies = None, [], []
        period = 1  # cycles in the block in progress
        starts = deque(maxlen=PERIOD_CYCLES)  # the states before the last cycles solved here, in order
        repeated = False  # the cycle in progress is a copy
        step, solved = 0, 0  # solved: index in self.solved of the first solved step from `step`
        history, cycle, skip, recorder = self.history, self.cycle, self.skip, self.recorder
        while step < len(history):
            number = int(cycle[step])
            if number != state.tally.number:  # the increment to `step` begins a new stretch
                if state.tally.number:
                    self._cycle(state.tally.number, state.tally, repeated)
                    if before is not None and not repeated:
                        tallies.append(state.tally)
                else:  # steps outside the cycles: nothing to copy
                    before = None
                    starts.clear()
                state = state.begun(number, self.model.contact)
                if before is not None and len(tallies) == period:
                    previous = _Cycle(step - len(steps), before, steps, tallies)
                    before = None
                repeated = False
                copies = self._repeats(previous, state, step) if number and before is None else 0
                if copies:
                    state = self._copy(previous, step, copies)
                    step += copies * len(previous.steps)
                    solved = int(np.searchsorted(self.solved, step))
                    repeated, before = True, None
                    starts.clear()
                    continue
                if before is None:
                    period = _period(starts, state)
                    before, steps, tallies = state, [], []
                if number:
                    starts.append(state)
            if skip[step]:  # a straight stretch: on to its next solved step, in the same cycle
                after = int(self.solved[solved])
                steps.extend([None] * (after - step))
                step = after
                continue
            if self.windowed[step]:
                windowed = self._window(state, solved)
                if windowed is not None:
                    state, solved = windowed
                    step = int(self.solved[solved - 1]) + 1
                    before = previous = None  # no copies of cycles solved in a window (`_copyable`)
                    starts.clear()
                    continue
            if step >= self.prepared:
                ahead = self.solved[solved : solved + PREPARED_STEPS]
                self.model.prepare(state, self.loads[ahead])
                self.prepared = int(ahead[-1]) + 1
            guess = None if self.guess is None else self.guess(step)
            loads, trial = displaced(self.model, state, self._at(step), step)
            at_rest = step == 0 and loads == state.loads
            outcome, state = advance(self.model, state, loads, step, guess, at_rest, self.tally, self.stress, trial)
            if self.observe is not None and not at_rest:
                self.observe(step, outcome)
            steps.append((outcome, state))
            if recorder is not None:
                recorder.step(step, outcome, state)
            step += 1
            solved += 1
        if state.tally.number:
            self._cycle(state.tally.number, state.tally, repeated)
        return state

    def _at(self, step):
        """The `Loads` of `step` (`engine_loads`)."""
        return engine_loads(self.loads[step], self.model.contact)

    def _copyable(self):
        """Steps of the stretches (load cycles, or the steps outside them) that the stretch after might
        copy (`_repeats`): it has their length, loads and skipped steps. They are solved step by step,
        so that a copy has the increments of each."""
        history, n = self.history, len(self.history)
        bounds = np.concatenate([[0], np.flatnonzero(np.diff(self.cycle)) + 1, [n]])
        length = np.diff(bounds)
        behind = np.repeat(np.append(0, length[:-1]), length)  # the length of the stretch before each step's
        earlier = np.arange(n) - behind
        same = (history.Q == history.Q[earlier]) & (history.sigma == history.sigma[earlier])
        same &= self.skip == self.skip[earlier]
        copies = np.logical_and.reduceat(same, bounds[:-1]) & (length == np.append(0, length[:-1]))
        return np.repeat(np.append(copies[1:], False), length)

    def _window(self, state, solved):
        """(state, index in `self.solved` of the next step) after the solved steps from `solved` on that
        are windowed (`self.windowed`, at most `PREPARED_STEPS`), all at once: the model's rows
        (`ExactModel.window`), the cycles they complete told to the recorder. None where the first of
        them is not a sound increment (gross slip, negative energy), for `advance` to raise.

        The results are those of `advance` step by step, bit for bit: the tallies add the rows of
        each cycle in order (`_folded`), and each node's episode begins again at the last step where it
        sticks or reverses (`State.episode_after`).
        """
        history, model = self.history, self.model
        if state.slid:  # the rows are the Masing sums alone: after gross slip, step by step
            return None
        ahead = self.solved[solved : solved + PREPARED_STEPS]
        sliding = model.sliding_force()
        ahead = ahead[: _leading(self.windowed[ahead] & (np.abs(history.Q[ahead]) < sliding))]
        if ahead.size == 0:
            return None
        slip, q, dissipation, memory, still = model.window(state, self.loads[ahead])
        ahead = ahead[: _leading(np.array(dissipation) >= 0)]
        K = ahead.size
        if K == 0:
            return None
        slips = np.vstack([state.slip, slip[:K]])  # the slip before each step, then after the last
        ds = slips[1:] - slips[:-1]
        ds[still[:K]] = 0.0
        edges = np.vstack([edge_loads(state.loads, model.contact), edge_loads(self.loads[ahead], model.contact)])
        tally = self._tallies(
            state, self.cycle[ahead], slips, model.dissipation_density(ds), np.abs(q[:K]), dissipation, edges
        )
        dissipated = state.dissipated
        for energy in dissipation[:K]:  # in order, as step by step
            dissipated += energy
        step = ahead[-1]
        after = State(
            self._at(step), slips[-1], state.episode_after(slips, ds), tally, state.model, dissipated, memory[K - 1]
        )
        return after, solved + K

    def _tallies(self, state, numbers, slips, w, shear, dissipation, edges):
        """The tally of the cycle in progress after the rows of a window (`_window`) whose steps are in
        the cycles `numbers`; the cycles they complete are told to the recorder. `edges` [N/m] holds the
        `edge_loads` before the first row, then after each (as `slips` the slip)."""
        bounds = np.concatenate([[0], np.flatnonzero(np.diff(numbers)) + 1, [numbers.size]])
        first, length, number = bounds[:-1], np.diff(bounds), numbers[bounds[:-1]]
        tally = state.tally
        folded = tally.folded(slips, w, shear, first, length)
        for k, (n, start, stop) in enumerate(zip(number.tolist(), first.tolist(), bounds[1:].tolist(), strict=True)):
            if k:
                if tally.number:
                    self._cycle(tally.number, tally, False)
                tally = Tally.begin(n, slips[start], edges[start])
            if n:
                energy = tally.dissipation
                for row in range(start, stop):
                    energy += dissipation[row]
                w, slip_min, slip_max, q_peak = (folded[name][k] for name in ("w", "slip_min", "slip_max", "q_peak"))
                low = np.minimum(tally.load_low, edges[start + 1 : stop + 1].min(axis=0))
                high = np.maximum(tally.load_high, edges[start + 1 : stop + 1].max(axis=0))
                tally = Tally.without_stress(n, energy, w, slip_min, slip_max, q_peak, low, high)
        return tally

    def _cycle(self, number, tally, repeated):
        if self.recorder is not None:
            self.recorder.cycle(number, tally, repeated)

    def _repeats(self, previous, state, step):
        """Number of whole blocks of cycles from `step` that repeat the complete block `previous` (one
        cycle or a period of them) bit for bit.

        They must follow `previous` directly, start from its starting state, have its loads,
        its number of steps and its skipped steps, and the last of them must end where a new
        stretch begins.
        """
        if previous is None or not state.repeats(previous.before):
            return 0
        length = len(previous.steps)
        if previous.first + length != step:
            return 0
        n, cycle = len(self.history), self.cycle
        later, earlier = slice(step, n), slice(step - length, n - length)
        same = (
            (self.history.Q[later] == self.history.Q[earlier])
            & (self.history.sigma[later] == self.history.sigma[earlier])
            & (True if self.history.P is None else self.history.P[later] == self.history.P[earlier])
            & (cycle[later] == cycle[earlier] + len(previous.tallies))
            & (self.skip[later] == self.skip[earlier])
        )
        copies = (same.size if same.all() else int(np.argmin(same))) // length
        stop = step + copies * length
        if copies and stop < n and cycle[stop] == cycle[stop - 1]:
            copies -= 1  # the last one goes on beyond the steps of `previous`
        return copies

    def _copy(self, previous, step, copies):
        """Copy the block of cycles `previous` `copies` times from `step`; the state after the last copy.

        The last cycle copied is left to be closed as the cycle in progress.
        """
        last, period = previous.steps[-1][1], len(previous.tallies)
        first = int(self.cycle[step])
        for k in range(copies * period - 1):  # the block's tally objects: the recorder stores their rows once
            self._cycle(first + k, previous.tallies[k % period], True)
        if self.recorder is not None:
            self.recorder.copied(step, copies, previous.steps)
        per_step = np.array([solved[0].dissipation for solved in previous.steps if solved is not None])
        # summed step by step, in order, as solving the cycles would: np.cumsum adds sequentially
        dissipated = np.cumsum(np.concatenate([[last.dissipated], np.tile(per_step, copies)]))[-1]
        number = first + copies * period - 1
        return replace(last, tally=replace(last.tally, number=number), dissipated=float(dissipated))


def _period(starts, state):
    """The fewest cycles, at least 2 and at most ``len(starts)``, after which `state` repeats the
    state before a cycle bit for bit (`starts`: the states before the last cycles, in order); 1 if
    none."""
    for k in range(2, len(starts) + 1):
        if state.repeats(starts[-k]):
            return k
    return 1


def _leading(mask):
    """Number of leading True in the boolean array `mask`."""
    return mask.size if mask.all() else int(np.argmin(mask))
