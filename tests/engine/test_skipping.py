"""Runs that skip the unrecorded steps inside straight stretches of the load path (issue 21):
which steps are skipped, what stays the same, and the bit-for-bit guarantees."""

import itertools

import numpy as np
import pytest
import xarray as xr

import fretting as fr
from fretting.engine.follow import skippable
from fretting.engine.recorder import Recorder
from fretting.models import Grid
from fretting.results.notes import noted

NODES = 64


def _run(contact, history, record=(), skipping=True, state=None, counted=None):
    """The dataset of `history` run from `state` by a stepper whose recorder skips (or not), with its note
    as `fr.simulate` writes it; `counted` (a list) gets one entry per increment solved."""
    stepper = fr.Stepper(contact, Grid(NODES) if state is None else None, state)
    stepper.resolve(history)
    if counted is not None:
        increment = stepper.model.increment
        stepper.model.increment = lambda *arguments: counted.append(1) or increment(*arguments)
    recorder = Recorder(stepper.model, history, np.asarray(record, dtype=np.int64), skipping)
    return noted(recorder.dataset(stepper.run(history, recorder)))


def _random(contact, cycles=12, sigma=0.5, steps=8):
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    return fr.History.random_amplitude(cycles, 0.7 * fP, sigma * fp0, seed=3, steps_per_segment=steps)


def _periodic(contact, cycles, steps=6):
    """`cycles` equal in-phase cycles Q: +A -> -A -> +A after a ramp to +A (cycle 0)."""
    A = 0.5 * contact.f * contact.P
    path = fr.History.piecewise_linear([0.0, *[A, -A] * cycles, A], [0.0, *[6e7, -6e7] * cycles, 6e7], steps)
    cycle = np.concatenate([np.zeros(steps + 1, dtype=np.int64), np.repeat(np.arange(1, cycles + 1), 2 * steps)])
    return fr.History(path.Q, path.sigma, path.vertex_step, cycle)


def test_the_steps_skipped_are_those_inside_straight_stretches(hertz):
    """Two random cycles of 4 steps a segment: vertices at 0, 4, ..., 16; cycle 1 is steps 1-8,
    cycle 2 steps 9-16. Not skipped: the ends, vertices, each cycle's first and last step,
    recorded steps; a curved path (a sine with 2048 steps per turn) and a pause keep every step."""
    history = _random(hertz, cycles=2, steps=4)
    none = np.zeros(len(history), dtype=bool)
    np.testing.assert_array_equal(np.flatnonzero(skippable(history, none, hertz)), [2, 3, 5, 6, 7, 10, 11, 13, 14, 15])
    recorded = none.copy()
    recorded[[6, 14]] = True
    np.testing.assert_array_equal(np.flatnonzero(skippable(history, recorded, hertz)), [2, 3, 5, 7, 10, 11, 13, 15])
    Q_alone = fr.History.piecewise_linear([0.0, 3e4, 3e4, -1e4], None, 5)  # its second segment is a pause
    np.testing.assert_array_equal(np.flatnonzero(skippable(Q_alone, none[:16], hertz)), [1, 2, 3, 4, 11, 12, 13, 14])
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    curved = fr.History.sinusoidal(0.5 * fP, 0.5 * fp0, phase_deg=90, cycles=2, steps_per_cycle=4096)
    skip = skippable(curved, np.zeros(len(curved), dtype=bool), hertz)
    np.testing.assert_array_equal(np.flatnonzero(skip), np.arange(1, 16))  # inside the straight ramp (steps 0-16)


def test_skipping_keeps_the_energy_slip_range_and_q_peak(hertz):
    """Against solving every step: the energy per cycle to rounding; w, slip amplitude and q_peak
    (stored as float32) equal; the sigma_xx peaks not stored, and the attribute says so; a
    third of the increments solved."""
    history = _random(hertz)
    solved, skipped = [], []
    every = _run(hertz, history, skipping=False, counted=solved)
    fast = _run(hertz, history, counted=skipped)
    assert len(skipped) < len(solved) / 2
    np.testing.assert_allclose(fast.cycle_dissipation.values, every.cycle_dissipation.values, rtol=1e-13, atol=0)
    np.testing.assert_allclose(fast.total_dissipation.values, every.total_dissipation.values, rtol=1e-13)
    np.testing.assert_allclose(fast.state_slip.values, every.state_slip.values, rtol=0, atol=1e-12 * hertz.a)
    for name in ("w", "slip_amplitude", "q_peak"):
        np.testing.assert_array_equal(fast[name].values, every[name].values, err_msg=name)
    assert "sigma_xx_peak" in every and "sigma_xx_peak" not in fast and "sigma_xx_q_peak" not in fast
    assert every.attrs["cycle_peaks"] == "every step" and "not tallied" in fast.attrs["cycle_peaks"]
    assert np.isnan(fast.state_sigma_xx_peak.values).all() and np.isfinite(fast.state_q_peak.values).all()


def test_the_sigma_xx_peak_of_a_straight_stretch_is_not_at_its_ends(hertz):
    """Why the sigma_xx peaks are not tallied when steps are skipped: solved step by step, the
    specimen's surface sigma_xx peak over a cycle exceeds its value at every turning point."""
    history = _random(hertz, cycles=3)
    every = _run(hertz, history, record=history.vertex_step, skipping=False)
    ends = _run(hertz, history, record=np.arange(len(history)), skipping=False)
    stress = fr.analysis.nucleation.surface_stress(ends).values
    for k, number in enumerate(every.cycle_number.values):
        steps = np.flatnonzero(history.cycle == number)
        turning = np.intersect1d(steps, history.vertex_step)
        assert np.any(every.sigma_xx_peak.values[k] > stress[turning].max(axis=0).astype(np.float32) * (1 + 1e-3))


@pytest.mark.parametrize("cuts", [1, 3, 7])
def test_a_run_cut_at_steps_it_solves_equals_the_whole_run(hertz, cuts):
    """Continued from its state at steps that it solves, a skipping run is the whole run bit for bit."""
    history = _random(hertz)
    record = np.array([0, 5, 40, len(history) - 1])
    whole = _run(hertz, history, record)
    recorded = np.zeros(len(history), dtype=bool)
    recorded[record] = True
    solved = np.flatnonzero(~skippable(history, recorded, hertz))
    bounds = [0, *solved[1:-1][:: max(1, (solved.size - 2) // cuts)][:cuts], len(history) - 1]
    parts, state = [], None
    for start, stop in itertools.pairwise(bounds):
        mine = record[(record >= start) & (record <= stop)] - start
        parts.append(_run(hertz, history[start : stop + 1], mine if parts else record[record <= stop], state=state))
        state = fr.final_state(parts[-1])
    xr.testing.assert_identical(fr.join_results(parts), whole)


def test_copied_cycles_of_a_skipping_run_equal_solved_ones(hertz):
    """Cycles that repeat are copied with their skipped steps; solved one by one instead they
    give the same result bit for bit."""
    history = _periodic(hertz, 8)
    whole = _run(hertz, history, [0, len(history) - 1])
    assert whole.cycle_copied.values.sum() >= 3
    bounds = [0, *np.flatnonzero(np.diff(history.cycle)), len(history) - 1]
    parts, state = [], None
    for start, stop in itertools.pairwise(bounds):
        mine = [0] if start == 0 else ([stop - start] if stop == len(history) - 1 else [])
        parts.append(_run(hertz, history[start : stop + 1], mine, state=state))
        state = fr.final_state(parts[-1])
    solved = fr.join_results(parts)
    assert not solved.cycle_copied.values.any()
    xr.testing.assert_identical(solved.drop_vars("cycle_copied"), whole.drop_vars("cycle_copied"))
