"""Load histories: sinusoids, random amplitudes, cycles, slices and concatenation."""

import numpy as np
import pytest

import fretting as fr
from fretting.loading import history as history_module
from fretting.loading.history import RAMP_STEPS
from fretting.loading.loads import CONVERTED
from fretting.models.base import ModelSpec

History = fr.History


def test_sinusoid_values_phase_and_cycles():
    history = History.sinusoidal(3.0, 2.0, phase_deg=90, cycles=2, steps_per_cycle=8, Q_mean=1.0, sigma_mean=-1.0)
    ramp = RAMP_STEPS  # from (0, 0) to the first point, (Q_mean, sigma_mean + sigma_amplitude)
    assert len(history) == ramp + 2 * 8 + 1
    theta = 2 * np.pi * np.arange(17) / 8
    np.testing.assert_allclose(history.Q[ramp:], 1.0 + 3.0 * np.sin(theta), atol=1e-15)
    np.testing.assert_allclose(history.sigma[ramp:], -1.0 + 2.0 * np.cos(theta), atol=1e-15)  # leads Q by 90 deg
    np.testing.assert_array_equal(history.cycle, [0] * (ramp + 1) + [1] * 8 + [2] * 8)
    np.testing.assert_array_equal(history.vertex_step, [0, ramp, ramp + 8, ramp + 16])
    np.testing.assert_allclose(history.Q[: ramp + 1], np.linspace(0, 1.0, ramp + 1), rtol=1e-15)


def test_sinusoid_cycles_close_exactly():
    history = History.sinusoidal(0.7, 0.3, phase_deg=33, cycles=3, steps_per_cycle=12)
    ends = history.vertex_step[1:]
    for loads in (history.Q, history.sigma):
        assert np.all(loads[ends] == loads[ends[0]])  # bit for bit: every cycle ends where it starts


def test_sinusoid_from_its_first_point_needs_no_ramp():
    history = History.sinusoidal(2.0, 5.0, steps_per_cycle=4)  # theta = 0 is (0, 0)
    np.testing.assert_allclose(history.Q, [0, 2, 0, -2, 0], atol=1e-15)
    assert history.cycle[0] == 0 and np.all(history.cycle[1:] == 1)


@pytest.mark.parametrize(
    "arguments",
    [
        {"Q_amplitude": -1.0},
        {"Q_amplitude": 1.0, "cycles": 0},
        {"Q_amplitude": 1.0, "steps_per_cycle": 3},
        {"Q_amplitude": 1.0, "steps_per_cycle": 8.0},
        {"Q_amplitude": "1"},
        {"Q_amplitude": 1.0, "sigma_mean": np.nan},
        {"Q_amplitude": 1.0, "ramp_steps": 0},
        {"Q_amplitude": 1.0, "start": (0.0,)},
    ],
)
def test_sinusoid_rejects_bad_parameters(arguments):
    with pytest.raises(fr.HistoryError):
        History.sinusoidal(**arguments)


def test_random_amplitude_peaks_valleys_and_cycles():
    history = History.random_amplitude(6, 2.0, 4.0, Q_mean=1.0, sigma_mean=10.0, seed=7, steps_per_segment=3)
    peaks, valleys = history.vertex_step[1::2], history.vertex_step[2::2]
    assert len(history) == 6 * 2 * 3 + 1
    assert np.all((history.Q[peaks] >= 1.0) & (history.Q[peaks] < 3.0))
    assert np.all((history.Q[valleys] <= 1.0) & (history.Q[valleys] > -1.0))
    turns = history.vertex_step[1:]  # sigma in phase with Q: the same random fraction of its amplitude
    np.testing.assert_allclose((history.sigma[turns] - 10.0) / 4.0, (history.Q[turns] - 1.0) / 2.0, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(history.cycle, np.repeat(np.arange(7), [1] + [6] * 6))
    again = History.random_amplitude(6, 2.0, 4.0, Q_mean=1.0, sigma_mean=10.0, seed=7, steps_per_segment=3)
    np.testing.assert_array_equal(again.Q, history.Q)
    other = History.random_amplitude(6, 2.0, 4.0, Q_mean=1.0, sigma_mean=10.0, seed=8, steps_per_segment=3)
    assert not np.array_equal(other.Q, history.Q)


def test_as_cycle():
    history = History.piecewise_linear([0, 1, -1], steps_per_segment=2).as_cycle()
    np.testing.assert_array_equal(history.cycle, [0, 1, 1, 1, 1])


def test_concatenate_numbers_cycles_on_and_joins_vertices():
    first = History.sinusoidal(1.0, cycles=2, steps_per_cycle=4)
    ramp = History.piecewise_linear([0.0, 0.5], steps_per_segment=2)
    second = History.sinusoidal(1.0, cycles=1, steps_per_cycle=4, Q_mean=0.5, start=(0.5, 0.0))
    history = History.concatenate([first, ramp, second])
    np.testing.assert_array_equal(history.Q, np.concatenate([first.Q, ramp.Q[1:], second.Q[1:]]))
    np.testing.assert_array_equal(history.cycle, [0] + [1] * 4 + [2] * 4 + [0, 0] + [3] * 4)
    np.testing.assert_array_equal(history.vertex_step, [0, 4, 8, 10, 14])  # each junction once
    assert history.cycle_count == 3


def test_concatenate_without_cycles_and_single():
    history = History.piecewise_linear([0, 1], steps_per_segment=3)
    back = History.piecewise_linear([1, 0], steps_per_segment=2)
    joined = History.concatenate([history, history[-1:], back])
    np.testing.assert_array_equal(joined.Q, np.concatenate([history.Q, back.Q[1:]]))
    assert joined.cycle is None
    np.testing.assert_array_equal(History.concatenate([history]).Q, history.Q)


def test_concatenate_rejects_a_jump():
    with pytest.raises(fr.HistoryError, match="history 2 starts at"):
        History.concatenate([History.piecewise_linear([0, 1]), History.piecewise_linear([0, 2])])
    with pytest.raises(fr.HistoryError, match="no histories"):
        History.concatenate([])


def test_slices_keep_vertices_and_cycle_numbers():
    history = History.sinusoidal(1.0, cycles=3, steps_per_cycle=4)
    tail = history[6:]
    np.testing.assert_array_equal(tail.Q, history.Q[6:])
    np.testing.assert_array_equal(tail.vertex_step, [2, 6])  # steps 8 and 12 of the whole
    np.testing.assert_array_equal(tail.cycle, history.cycle[6:])
    middle = history[5:7]
    assert len(middle) == 2 and middle.vertex_step.size == 0
    assert len(history[-1:]) == 1


def test_a_slice_keeps_the_vertices_inside_it():
    """Every slice of a history with repeated vertex steps keeps the vertices ``start <= step < stop``,
    renumbered, and no other."""
    vertex_step = np.array([0, 2, 2, 3, 5, 5, 5, 7, 9])
    history = History(np.arange(10.0), np.zeros(10), vertex_step)
    for start in range(10):
        for stop in range(start + 1, 11):
            inside = vertex_step[(vertex_step >= start) & (vertex_step < stop)]
            np.testing.assert_array_equal(history[start:stop].vertex_step, inside - start)


@pytest.mark.parametrize("key", [3, slice(0, 4, 2)])
def test_only_contiguous_slices(key):
    with pytest.raises(TypeError, match="contiguous"):
        History.piecewise_linear([0, 1], steps_per_segment=4)[key]


def test_empty_slice():
    with pytest.raises(fr.HistoryError, match="empty"):
        History.piecewise_linear([0, 1], steps_per_segment=4)[3:3]


def test_cycles_may_pause_but_not_go_back():
    History([0, 1, 2, 3, 4], [0] * 5, [0], cycle=[0, 1, 0, 0, 2])  # a ramp between cycles 1 and 2
    with pytest.raises(fr.HistoryError, match="cycle"):
        History([0, 1, 2], [0] * 3, [0], cycle=[0, 2, 1])
    with pytest.raises(fr.HistoryError, match="cycle"):
        History([0, 1, 2], [0] * 3, [0], cycle=[0, -1, 1])
    with pytest.raises(fr.HistoryError, match="at most 2147483647"):
        History([0, 1, 2], [0] * 3, [0], cycle=[0, 1, 2**31])
    with pytest.raises(fr.HistoryError, match="cycle"):
        History([0, 1, 2], [0] * 3, [0], cycle=[0, 1.0, 1.0])


def test_engine_counts_energy_per_cycle(hertz):
    """Cycles 2 and 3 of a steady shear cycle dissipate the same energy; the first less (it starts unloaded)."""
    fP = hertz.f * hertz.P
    history = History.sinusoidal(0.5 * fP, cycles=3, steps_per_cycle=32)
    result = fr.simulate(hertz, history, nodes=64)
    np.testing.assert_array_equal(result.cycle.values, history.cycle)
    assert result.cycle.dtype == np.int64  # the result's, whatever the History holds them in
    energy = result.cycle_dissipation.values
    assert energy.shape == (3,)
    assert energy[1] == pytest.approx(energy[2], rel=1e-9)
    assert energy[0] < energy[1]
    assert energy.sum() == pytest.approx(float(result.dissipation.sum()), rel=1e-12)


def test_engine_counts_cycles_of_a_history_that_ends_outside_them(hertz):
    """Cycles, then an unloading ramp outside any cycle."""
    fP = hertz.f * hertz.P
    waves = History.sinusoidal(0.4 * fP, cycles=2, steps_per_cycle=16, Q_mean=0.2 * fP)
    history = History.concatenate([waves, History.piecewise_linear([0.2 * fP, 0.0], steps_per_segment=4)])
    assert history.cycle[-1] == 0 and history.cycle_count == 2
    result = fr.simulate(hertz, history, nodes=48)
    assert result.cycle_dissipation.shape == (2,)
    assert float(result.cycle_dissipation.sum()) < float(result.dissipation.sum())  # the ramps dissipate too


def test_segments_hold_equal_vertices_exactly():
    """A segment between equal vertices holds their value bit for bit (a unit in the last place
    is a load change the exact model of Q alone slips under), and every segment ends on its vertex."""
    Q = [0.0, 0.999 * 0.6 * 1e5, 0.999 * 0.6 * 1e5, 0.1, 0.3]
    history = fr.History.piecewise_linear(Q, [0.0, 0.7, 0.7, 0.7, -0.2], [8, 3, 5, 7])
    dwell = slice(history.vertex_step[1], history.vertex_step[2] + 1)
    assert np.all(history.Q[dwell] == Q[1]) and np.all(history.sigma[history.vertex_step[1] :][:9] == 0.7)
    np.testing.assert_array_equal(history.Q[history.vertex_step], Q)


@pytest.mark.parametrize("steps", [[3, 1, 7, 3, 7], 5])
def test_segments_are_the_straight_line_of_each(steps):
    """``v_i + (v_(i+1) - v_i) (k / n)`` on each segment, bit for bit, computed segment by segment
    here, with one step count for all segments (the output filled row by row) or several."""
    Q = np.array([0.0, 1.5, -2.25, 3.125, 0.1, 7.3])
    history = History.piecewise_linear(Q, Q / 3, steps)
    counts = np.broadcast_to(steps, (Q.size - 1,))
    expected = [Q[:1]]
    for i, n in enumerate(counts):
        line = Q[i] + (Q[i + 1] - Q[i]) * (np.arange(1, n + 1) / n)
        line[-1] = Q[i + 1]
        expected.append(line)
    np.testing.assert_array_equal(history.Q, np.concatenate(expected))
    np.testing.assert_array_equal(history.vertex_step, np.concatenate([[0], np.cumsum(counts)]))


def test_a_load_that_never_changes_takes_no_memory_per_step():
    """10^5 random cycles of Q alone: sigma is one zero broadcast to every step (stride 0), the
    cycle numbers take 4 bytes a step, and they are those of the segments, two to a cycle."""
    history = History.random_amplitude(10**5, 4e4, steps_per_segment=3)
    assert history.sigma.strides == (0,) and history.sigma.shape == history.Q.shape and not history.sigma.any()
    assert history.Q.strides == (8,) and history.cycle.dtype == np.int32
    np.testing.assert_array_equal(history.cycle, np.concatenate([[0], np.repeat(np.arange(1, 10**5 + 1), 6)]))


def test_passes_over_a_history_by_blocks(monkeypatch):
    """Blocks of 4 steps: the largest |Q| below a bound and the check of the cycle numbers see
    every step, also across the blocks' ends."""
    monkeypatch.setattr(history_module, "BLOCK_STEPS", 4)
    Q = np.array([0.0, 3.0, -9.0, 2.0, -5.0, 12.0, -7.5, 4.0, 10.0, 1.0])
    history = History(Q, np.zeros(Q.size), [0])
    assert history.largest_Q_below(8.0) == 7.5 and history.largest_Q_below(100.0) == 12.0
    assert history.largest_Q_below(1.0) == 0.0
    History(Q, np.zeros(Q.size), [0], cycle=[0, 1, 1, 1, 0, 0, 2, 2, 3, 3])
    with pytest.raises(fr.HistoryError, match="cycle"):
        History(Q, np.zeros(Q.size), [0], cycle=[0, 1, 1, 2, 0, 1, 2, 2, 3, 3])  # back to 1 in the second block


def test_a_history_of_delta_moves_delta_which_a_model_of_Q_runs():
    """``delta`` is an input `History.moves` reports; the engine turns it into ``Q`` (`CONVERTED`), so
    a spec that follows ``Q`` runs it and no spec lists ``delta`` in its inputs."""
    contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=5e-3)
    history = fr.History.piecewise_linear(delta=[0, 1e-7, -1e-7], steps_per_segment=2)
    assert history.moves(contact) == {"Q", "sigma", "delta"} and CONVERTED == {"delta": "Q"}
    assert fr.models.Grid(16).refusal(contact, history) is None
    assert not any("delta" in spec.inputs for spec in ModelSpec.registry.values())
    last = history.loads[4]
    assert np.isnan(last.Q) and (last.sigma, last.P, last.delta) == (0.0, None, -1e-7)
    assert last.force().delta is None and fr.History.piecewise_linear([0, 1.0], None, 1).loads[1].delta is None
    tail = history[2:]
    assert tail.delta.tolist() == [1e-7, 0.0, -1e-7] and tail.vertex_step.tolist() == [0, 2]


def test_histories_of_delta_concatenate():
    first = fr.History.piecewise_linear(delta=[0, 1e-7], steps_per_segment=2)
    cycle = fr.History.piecewise_linear(delta=[1e-7, -1e-7, 1e-7], steps_per_segment=2).as_cycle()
    joined = fr.History.concatenate([first, cycle, cycle])
    assert joined.delta.tolist() == [0, 5e-8, 1e-7, 0, -1e-7, 0, 1e-7, 0, -1e-7, 0, 1e-7]
    assert joined.cycle.tolist() == [0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2]
    assert joined.vertex_step.tolist() == [0, 2, 4, 6, 8, 10]
    with pytest.raises(fr.HistoryError, match=r"history 2 starts at \(delta, sigma\) = \(0.0, 0.0\)"):
        fr.History.concatenate([first, fr.History.piecewise_linear(delta=[0, 1e-7], steps_per_segment=2)])
    with pytest.raises(fr.HistoryError, match="histories of Q and histories of delta"):
        fr.History.concatenate([first, fr.History.piecewise_linear([0, 1.0], None, 2)])
