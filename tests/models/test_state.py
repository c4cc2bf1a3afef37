"""State.advance and Tally.add against their definitions written out elementwise, on fields with
every case of sign: sticking nodes, reversals, episodes that have not moved, and signed zeros."""

import numpy as np
import pytest

from fretting.loading.loads import Loads
from fretting.models.base import Outcome
from fretting.models.state import State, Tally

N = 64


@pytest.fixture
def fields():
    """Slip before, episode start and slip increment with zeros of both signs and every sign pairing."""
    rng = np.random.default_rng(21)
    before = rng.choice([-1e-6, -0.0, 0.0, 3e-7, 1e-6], N)
    start = np.where(rng.random(N) < 0.3, before, rng.choice([-2e-6, -0.0, 0.0, 2e-6], N))
    ds = rng.choice([-1e-7, -1e-300, 0.0, -0.0, 1e-300, 1e-7], N)
    return before, start, ds


def _episode_start(before, start, ds, slip):
    """The episode's start node by node: the slip where the node sticks, the slip before where it
    reverses (ds and the episode so far of strictly opposite signs), else unchanged."""
    out = np.empty(N)
    for k in range(N):
        episode = before[k] - start[k]
        if ds[k] == 0:
            out[k] = slip[k]
        elif (ds[k] > 0 and episode < 0) or (ds[k] < 0 and episode > 0):
            out[k] = before[k]
        else:
            out[k] = start[k]
    return out


def test_episode_start_is_its_definition_bit_for_bit(fields):
    before, start, ds = fields
    slip = before + ds
    state = State(Loads(1.0, 0.0), before, start, Tally.begin(1, before, np.array([1.0, 1.0, 1e5])), None)
    after = state.advance(Outcome(slip, ds, slip, 0.0), Loads(2.0, 0.0), None, None, None, None)
    expected = _episode_start(before, start, ds, slip)
    assert np.array_equal(after.episode_start, expected)
    assert np.array_equal(np.signbit(after.episode_start), np.signbit(expected))
    assert np.any(after.episode_start != start) and np.any(after.episode_start != slip)  # both cases met


def test_stress_not_known_leaves_the_sigma_xx_peaks_nan_as_a_nan_row_would(fields):
    before, _, ds = fields
    slip, w, shear = before + ds, np.abs(ds), np.abs(before)
    nothing = np.full(3, np.nan)
    tally = Tally(1, 0.5, np.ones(N), before, before, np.zeros(N), np.zeros(N), np.zeros(N), nothing, nothing)
    loads = np.array([-1.0, 3.0, 1e5])
    unknown = tally.add(0.25, w, slip, None, shear, loads)
    nan_row = tally.add(0.25, w, slip, np.full(N, np.nan), shear, loads)
    for name in ("w", "slip_min", "slip_max", "sigma_xx_peak", "q_peak", "sigma_xx_q_peak"):
        assert np.array_equal(getattr(unknown, name), getattr(nan_row, name), equal_nan=True), name
    assert unknown.dissipation == nan_row.dissipation == 0.75
    assert np.all(np.isnan(unknown.sigma_xx_peak)) and np.all(np.isnan(unknown.sigma_xx_q_peak))
    with pytest.raises(ValueError):  # the NaN row is shared between tallies: nobody may write into it
        unknown.sigma_xx_peak[0] = 1.0


def test_the_load_extremes_span_the_cycle_from_its_starting_loads(fields):
    """`Tally.load_low` and `load_high` are the elementwise least and greatest of the loads the cycle
    started from and of those after each increment; a tally read without them (NaN) stays unknown."""
    before, _, ds = fields
    w, shear, start = np.abs(ds), np.abs(before), np.array([0.0, 0.0, 1e5])
    steps = [np.array([2.0, -1.0, 1.2e5]), np.array([-3.0, 0.5, 0.9e5]), np.array([1.0, 4.0, 1e5])]
    tally = Tally.begin(1, before, start)
    for loads in steps:
        tally = tally.add(0.0, w, before, None, shear, loads)
    assert tally.load_low.tolist() == [-3.0, -1.0, 0.9e5] and tally.load_high.tolist() == [2.0, 4.0, 1.2e5]
    nothing = np.full(3, np.nan)  # as `fretting.engine.recorder.final_state` reads a result written without them
    unknown = Tally(1, 0.0, w, before, before, w, w, w, nothing, nothing).add(0.0, w, before, None, shear, steps[0])
    assert np.all(np.isnan(unknown.load_low)) and np.all(np.isnan(unknown.load_high))
