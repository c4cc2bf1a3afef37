"""The solved steps of a window of the exact model, all at once, against the same steps one by one."""

import numpy as np
import pytest
import xarray as xr

import fretting as fr
from fretting.engine import follow
from fretting.engine.follow import skippable
from fretting.engine.recorder import Recorder
from fretting.loading.loads import LoadBlock
from fretting.models.exact import ExactModel


def _run(contact, history, record, state=None, calls=None):
    """The dataset of a skipping run of `history` on the exact model from `state`; `calls` (a list)
    gets one entry per window solved."""
    stepper = fr.Stepper(contact, fr.models.Exact(64) if state is None else None, state)
    stepper.resolve(history)
    if calls is not None:
        window = stepper.model.window
        stepper.model.window = lambda *arguments: calls.append(1) or window(*arguments)
    recorder = Recorder(stepper.model, history, np.asarray(record, dtype=np.int64), skipping=True)
    return recorder.dataset(stepper.run(history, recorder))


def _history(contact):
    """Random cycles of Q alone, then six equal ones (which a run copies), then random ones again."""
    fP = contact.f * contact.P
    first, later = (fr.History.random_amplitude(30, 0.7 * fP, seed=seed, steps_per_segment=6) for seed in (3, 4))
    equal = fr.History.piecewise_linear([first.Q[-1], *[0.5 * fP, -0.5 * fP] * 6, later.Q[0]], None, 6)
    Q = np.concatenate([first.Q, equal.Q[1:], later.Q[1:]])
    n, m = len(first), len(equal) - 1
    vertex = np.concatenate([first.vertex_step, n - 1 + equal.vertex_step[1:], n + m - 1 + later.vertex_step[1:]])
    cycle = np.concatenate([first.cycle, 31 + np.minimum(np.arange(m) // 12, 5), 36 + later.cycle[1:]])
    return fr.History(Q, np.zeros_like(Q), vertex, cycle)


@pytest.mark.parametrize("prepared", [5, follow.PREPARED_STEPS])
def test_a_window_equals_its_steps_one_by_one(hertz, monkeypatch, prepared):
    """Windowed (of `prepared` steps), split at a solved step inside a window and continued from
    its state, with recorded steps and copied cycles, the run is the run step by step bit for bit."""
    monkeypatch.setattr(follow, "PREPARED_STEPS", prepared)
    history = _history(hertz)
    record = np.array([0, 7, 100, 101, 250, len(history) - 1])
    recorded = np.zeros(len(history), dtype=bool)
    recorded[record] = True
    solved = np.flatnonzero(~skippable(history, recorded, hertz))
    cut = int(solved[np.searchsorted(solved, 150)])  # inside a window: neither recorded nor a cycle's end
    assert not recorded[cut] and history.cycle[cut] == history.cycle[cut + 1]
    calls = []
    first = _run(hertz, history[: cut + 1], record[record <= cut], calls=calls)
    mine = record[record >= cut] - cut
    split = fr.join_results([first, _run(hertz, history[cut:], mine, fr.final_state(first), calls)])
    assert len(calls) >= 2
    monkeypatch.setattr(ExactModel, "windows", False)
    assert split.cycle_copied.values.sum() >= 2
    for windowed, one_by_one in (
        (first, _run(hertz, history[: cut + 1], record[record <= cut])),
        (split, _run(hertz, history, record)),
    ):
        xr.testing.assert_identical(windowed, one_by_one)
        for name in ("state_slip", "state_episode_start", "state_w", "state_slip_min", "state_slip_max"):
            assert np.array_equal(np.signbit(windowed[name].values), np.signbit(one_by_one[name].values))


def test_the_default_window_is_the_increments_one_after_another(hertz):
    """`Model.window` of a model that does not set `windows` (method 4 on the grid): its rows are the
    increments stepped one at a time, bit for bit, and ``still`` marks an increment that slipped nowhere."""
    fP = hertz.f * hertz.P
    model = fr.models.Grid(32).build(hertz)
    Q = fP * np.array([0.3, 0.3, -0.2, 0.4])
    slip, q, dissipation, memory, still = model.window(fr.State.virgin(model), LoadBlock(Q, np.zeros(Q.size)))
    stepper = fr.Stepper(hertz, fr.models.Grid(32))
    for k, load in enumerate(Q):
        outcome = stepper.step(load)
        assert np.array_equal(slip[k], outcome.slip) and np.array_equal(q[k], model.traction(outcome))
        assert dissipation[k] == outcome.dissipation and memory[k] == outcome.memory
    assert still.tolist() == [False, True, False, False]
