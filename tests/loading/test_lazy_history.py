"""A history file's histories formed when read (`PiecewiseLinear` from its vertices, `Periodic` from
one cycle, `Joined` from its blocks): equal bit for bit to the history of every step's arrays, and
costing memory per vertex or per cycle, not per step."""

import dataclasses
import tracemalloc

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.engine import runner
from fretting.loading import history as history_module
from fretting.loading.history import History, Joined, Periodic, PiecewiseLinear
from fretting.loading.history_file import read_history_source
from fretting.models import Grid

#: Random in-phase cycles, a curved path of straight segments and a repeat: every block a PiecewiseLinear builds.
LOADS = """
[[loading]]
kind = "random"
cycles = 60
Q_amplitude = 30e3
sigma_amplitude = 5e7
seed = 3
steps_per_segment = 5

[[loading]]
kind = "linear"
Q = [20e3, 0.0, -20e3, 0.0, 20e3]
sigma = [0.0, 4e7, 0.0, -4e7, 0.0]
steps_per_segment = [3, 9, 2, 6, 4]
cycle = true

[[loading]]
kind = "repeat"
count = 3
[[loading.blocks]]
kind = "linear"
Q = [-10e3, 10e3]
steps_per_segment = 7
cycle = true
"""

#: A first loading, sinusoids with a ramp and a varying normal load, and a repeat of a sinusoid and
#: a straight block: a `Joined` of `Periodic` and `PiecewiseLinear` histories.
SINES = """
[[loading]]
kind = "linear"
Q = [10e3]
sigma = [2e7]
P = [1.1e5]
steps_per_segment = 4

[[loading]]
kind = "sine"
Q_amplitude = 30e3
sigma_amplitude = 5e7
phase_deg = 40.0
cycles = 9
steps_per_cycle = 13
Q_mean = 2e3
P_amplitude = 2e4
P_mean = 1.2e5
P_phase_deg = 15.0
ramp_steps = 3

[[loading]]
kind = "repeat"
count = 2
[[loading.blocks]]
kind = "sine"
Q_amplitude = 20e3
cycles = 3
steps_per_cycle = 8
P_mean = 1.2e5
ramp_steps = 2
[[loading.blocks]]
kind = "linear"
Q = [0.0]
sigma = [0.0]
P = [1e5]
steps_per_segment = 5
"""


def sine(k, steps, amplitude, mean, *phases):
    """``mean + amplitude sin(2 pi (k mod steps) / steps + phases)`` [N/m or Pa] at steps `k` of a
    sinusoid, the `phases` [rad] added one after the other, as `History.sinusoidal` does."""
    theta = np.remainder(np.asarray(k, dtype=float), steps) * (2 * np.pi) / steps
    for phase in phases:
        theta += phase
    return np.sin(theta) * amplitude + mean


def assert_same(lazy, explicit):
    """Every array of `lazy` equals that of `explicit` bit for bit (values, signs of zeros, types)."""
    for name in ("Q", "sigma", "cycle", "P", "vertex_step"):
        found, expected = getattr(lazy, name), getattr(explicit, name)
        assert (found is None) == (expected is None), name
        if expected is not None:
            assert found.dtype == expected.dtype, name
            np.testing.assert_array_equal(found, expected, err_msg=name)
            np.testing.assert_array_equal(np.signbit(found), np.signbit(expected), err_msg=name)


@pytest.fixture
def small_blocks(monkeypatch):
    """Blocks of a few steps, so that a short history is read in many blocks and slices."""
    monkeypatch.setattr(history_module, "BLOCK_STEPS", 23)


def test_a_file_of_straight_segments_gives_a_PiecewiseLinear_with_the_arrays_of_the_explicit_history(
    tmp_path, small_blocks
):
    path = tmp_path / "loads.toml"
    path.write_text(HERTZ_TOML + LOADS)
    contact, lazy = fr.read_history(path)
    assert isinstance(lazy, PiecewiseLinear)
    explicit = History(lazy.Q, lazy.sigma, lazy.vertex_step, lazy.cycle)
    # the random block against the public function, which forms every step (a different path through the code)
    random = History.random_amplitude(60, 30e3, 5e7, seed=3, steps_per_segment=5)
    assert_same(lazy[: len(random)], random)
    for start, stop in [(0, 1), (0, 37), (5, 6), (len(lazy) - 2, len(lazy)), (17, len(lazy) - 40)]:
        assert_same(lazy[start:stop], explicit[start:stop])
    assert_reads_as_explicit(lazy, explicit, contact)
    assert lazy.cycle_count == 64
    assert lazy.first_step(lambda Q, sigma: Q < -19e3) == np.flatnonzero(explicit.Q < -19e3)[0]


def assert_reads_as_explicit(lazy, explicit, contact):
    """Slices, turning steps and points, cycle ends, largest loads and blocks (of 23 steps) of
    `lazy` equal those of `explicit` bit for bit."""
    for start, stop in [(0, 1), (0, 37), (5, 6), (len(lazy) - 2, len(lazy)), (17, len(lazy) - 40)]:
        assert_same(lazy[start:stop], explicit[start:stop])
    units = (contact.f * contact.P, contact.f * contact.p0)
    np.testing.assert_array_equal(lazy.turning_steps(0.2, units), explicit.turning_steps(0.2, units))
    assert_same(lazy.turning_points(0.2, units), explicit.turning_points(0.2, units))
    np.testing.assert_array_equal(lazy.cycle_ends()[1:], explicit.cycle_ends()[1:])  # entry 0 is not a cycle
    assert lazy.cycle_count == explicit.cycle_count
    assert lazy.largest_loads() == (np.abs(explicit.Q).max(), np.abs(explicit.sigma).max())
    for (Q, sigma), start in zip(lazy.blocks(), range(0, len(lazy), 23), strict=True):
        np.testing.assert_array_equal(Q, explicit.Q[start : start + 23])
        np.testing.assert_array_equal(sigma, explicit.sigma[start : start + 23])


def test_a_file_of_sinusoids_gives_histories_held_by_one_cycle_with_the_arrays_of_the_explicit_history(
    tmp_path, small_blocks
):
    path = tmp_path / "loads.toml"
    path.write_text(HERTZ_TOML + SINES)
    contact, lazy = fr.read_history(path)
    assert isinstance(lazy, Joined) and isinstance(lazy.parts[1].parts[1], Periodic)
    explicit = History(lazy.Q, lazy.sigma, lazy.vertex_step, lazy.cycle, lazy.P)
    assert len(lazy) == 1 + 4 + 3 + 9 * 13 + 2 * (2 + 3 * 8 + 5) and lazy.cycle_count == 15
    # the sinusoids against their formula at every step, the cycles counted on through the repeat
    first = np.arange(7, 7 + 9 * 13 + 1)  # after the first loading (4 steps) and the ramp (3)
    phase = np.radians(40.0)
    np.testing.assert_array_equal(lazy.Q[first], sine(first - 7, 13, 30e3, 2e3))
    np.testing.assert_array_equal(lazy.sigma[first], sine(first - 7, 13, 5e7, 0.0, phase))
    np.testing.assert_array_equal(lazy.P[first], sine(first - 7, 13, 2e4, 1.2e5, phase, np.radians(15.0) - phase))
    np.testing.assert_array_equal(lazy.cycle[first[1:]], (first[1:] - 8) // 13 + 1)
    second = 7 + 9 * 13 + 2 + np.arange(1, 3 * 8 + 1)  # after the repeat's ramp (2 steps)
    np.testing.assert_array_equal(lazy.Q[second], sine(np.arange(1, 3 * 8 + 1), 8, 20e3, 0.0))
    np.testing.assert_array_equal(lazy.cycle[second], 9 + (np.arange(3 * 8) // 8 + 1))
    assert lazy.cycle_ends()[-1] == len(lazy) - 6 and lazy.cycle[-1] == 0 and lazy.P[-1] == 1e5  # a straight block last
    assert_reads_as_explicit(lazy, explicit, contact)
    assert_same(
        History.sinusoidal(30e3, 5e7, 40.0, 9, 13, 2e3, by_cycle=True), History.sinusoidal(30e3, 5e7, 40.0, 9, 13, 2e3)
    )


def test_a_periodic_history_repeats_a_closed_cycle_only():
    with pytest.raises(fr.errors.HistoryError, match="repeats a closed cycle"):
        Periodic(History.piecewise_linear([0.0, 1.0, 0.5], None, 2), 3)


def test_cycle_ends_are_the_last_step_of_each_cycle():
    history = History.sinusoidal(100.0, cycles=3, steps_per_cycle=4, start=(5.0, 0.0), ramp_steps=2)
    np.testing.assert_array_equal(history.cycle_ends()[1:], [6, 10, 14])  # a ramp of 2 steps, then 4 a cycle
    lazy = History.random_amplitude(3, 100.0, steps_per_segment=2, vertices=True)
    np.testing.assert_array_equal(lazy.cycle_ends()[1:], [4, 8, 12])


def test_a_normal_load_that_lifts_off_is_named_at_its_first_step_as_for_the_explicit_history():
    """The load crosses zero inside the last segment, at its middle step."""
    with pytest.raises(fr.errors.HistoryError, match=r"P = 0.0 at step 3$"):
        PiecewiseLinear.through([0.0, 1.0, 2.0], None, 2, [100.0, 60.0, -60.0])
    with pytest.raises(fr.errors.HistoryError, match=r"P = 0.0 at step 3$"):
        History(np.zeros(5), np.zeros(5), [0, 2, 4], None, [100.0, 80.0, 60.0, 0.0, -60.0])


#: `SINES` at the contact's constant normal load.
SINES_AT_CONSTANT_P = "\n".join(line for line in SINES.splitlines() if not line.startswith("P"))


@pytest.mark.slow
@pytest.mark.parametrize(("loads", "cycles"), [(LOADS, 64), (SINES_AT_CONSTANT_P, 15)], ids=["straight", "sines"])
def test_a_run_of_the_lazy_history_writes_the_arrays_of_the_run_of_the_explicit_one(
    tmp_path, monkeypatch, loads, cycles
):
    """The runner through chunks and blocks of a `Formed` history, and through those of the same
    history held step by step: the result files' variables are equal bit for bit."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 40)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)
    monkeypatch.setattr(history_module, "BLOCK_STEPS", 64)
    path = tmp_path / "loads.toml"
    path.write_text(HERTZ_TOML + loads)
    policy = "first,last,every=7,maxima"
    lazy = runner.run_file(path, tmp_path / "lazy.h5", Grid(32), cycle_fields=policy).result

    def explicit(history_path):
        source = read_history_source(history_path)
        return dataclasses.replace(source, history=source.history.explicit())

    monkeypatch.setattr(runner, "read_history_source", explicit)
    whole = runner.run_file(path, tmp_path / "explicit.h5", Grid(32), cycle_fields=policy).result
    assert set(lazy.variables) == set(whole.variables) and lazy.sizes["cycle_number"] == cycles
    for name, variable in whole.variables.items():
        np.testing.assert_array_equal(lazy[name].values, variable.values, err_msg=name)


#: One long block of each kind a `Formed` history holds: random in-phase cycles (a vertex every 16
#: steps) and in-phase sinusoids (a vertex, the cycle's end, every 32 steps), `{cycles}` cycles.
LONG_BLOCKS = {
    "random": LOADS.split("[[loading]]")[1].replace("cycles = 60", "cycles = {cycles}").replace("= 5\n", "= 16\n"),
    "sine": "\nkind = 'sine'\ncycles = {cycles}\nsteps_per_cycle = 32\nQ_amplitude = 30e3\nsigma_amplitude = 5e7\n",
}


def _peak_of_a_pass(tmp_path, kind, cycles):
    """tracemalloc peak [bytes] of reading a file of one long block of `kind` and `cycles` cycles
    (32 steps each) and passing over it as a run does: its blocks, turning steps, cycle ends and chunks."""
    path = tmp_path / f"{kind}_{cycles}.toml"
    path.write_text(HERTZ_TOML + "[[loading]]" + LONG_BLOCKS[kind].format(cycles=cycles))
    tracemalloc.start()
    try:
        history = read_history_source(path).history
        history.largest_loads()
        history.turning_steps()
        history.cycle_ends()
        for start in range(0, len(history) - 1, 4096):
            history[start : start + 4097]
        return len(history), tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("kind", sorted(LONG_BLOCKS))
def test_the_memory_of_a_pass_over_a_long_history_grows_by_its_vertices_not_its_steps(tmp_path, monkeypatch, kind):
    """Doubling the cycles adds the vertex arrays (about 40 bytes a vertex of a random block, 8 of
    a sinusoid's) and the turning steps, a few bytes a step; a history held step by step would
    add 20 bytes a step (Q, sigma, cycle)."""
    monkeypatch.setattr(history_module, "BLOCK_STEPS", 2**14)
    steps, peak = _peak_of_a_pass(tmp_path, kind, 10_000)
    twice, peak_twice = _peak_of_a_pass(tmp_path, kind, 20_000)
    assert (peak_twice - peak) / (twice - steps) < 6
