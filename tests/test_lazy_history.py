"""A history file's piecewise-linear history (`PiecewiseLinear`): formed from its vertices, equal
bit for bit to the history of every step's arrays, and costing memory per vertex, not per step."""

import dataclasses
import tracemalloc

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.engine import runner
from fretting.loading import history as history_module
from fretting.loading.history import History, PiecewiseLinear
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
    for start, stop in [(0, 1), (0, 37), (5, 6), (299, 301), (17, len(lazy))]:
        assert_same(lazy[start:stop], explicit[start:stop])
    units = (contact.f * contact.P, contact.f * contact.p0)
    np.testing.assert_array_equal(lazy.turning_steps(0.2, units), explicit.turning_steps(0.2, units))
    assert_same(lazy.turning_points(0.2, units), explicit.turning_points(0.2, units))
    np.testing.assert_array_equal(lazy.cycle_ends(), explicit.cycle_ends())
    assert lazy.cycle_count == explicit.cycle_count == 64
    assert lazy.largest_loads() == (np.abs(explicit.Q).max(), np.abs(explicit.sigma).max())
    assert lazy.first_step(lambda Q, sigma: Q < -19e3) == np.flatnonzero(explicit.Q < -19e3)[0]
    for (Q, sigma), start in zip(lazy.blocks(), range(0, len(lazy), 23), strict=True):
        np.testing.assert_array_equal(Q, explicit.Q[start : start + 23])
        np.testing.assert_array_equal(sigma, explicit.sigma[start : start + 23])


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


def test_a_run_of_the_lazy_history_writes_the_arrays_of_the_run_of_the_explicit_one(tmp_path, monkeypatch):
    """The runner through chunks and blocks of a PiecewiseLinear, and through those of the same
    history held step by step: the result files' variables are equal bit for bit."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 40)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)
    monkeypatch.setattr(history_module, "BLOCK_STEPS", 64)
    path = tmp_path / "loads.toml"
    path.write_text(HERTZ_TOML + LOADS)
    policy = "first,last,every=7,maxima"
    lazy = runner.run_file(path, tmp_path / "lazy.h5", Grid(32), cycle_fields=policy).result

    def explicit(history_path):
        source = read_history_source(history_path)
        return dataclasses.replace(source, history=source.history.explicit())

    monkeypatch.setattr(runner, "read_history_source", explicit)
    whole = runner.run_file(path, tmp_path / "explicit.h5", Grid(32), cycle_fields=policy).result
    assert set(lazy.variables) == set(whole.variables) and lazy.sizes["cycle_number"] == 64
    for name, variable in whole.variables.items():
        np.testing.assert_array_equal(lazy[name].values, variable.values, err_msg=name)


def _peak_of_a_pass(tmp_path, cycles):
    """tracemalloc peak [bytes] of reading a file of `cycles` random in-phase cycles (32 steps
    each) and passing over it as a run does: its blocks, turning steps, cycle ends and chunks."""
    path = tmp_path / f"random_{cycles}.toml"
    block = LOADS.split("[[loading]]")[1].replace("cycles = 60", f"cycles = {cycles}").replace("= 5\n", "= 16\n")
    path.write_text(HERTZ_TOML + "[[loading]]" + block)
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


def test_the_memory_of_a_pass_over_a_long_history_grows_by_its_vertices_not_its_steps(tmp_path, monkeypatch):
    """Doubling the cycles adds the vertex arrays (about 40 bytes a vertex, a vertex every 16
    steps) and the turning steps, a few bytes a step; a history held step by step would add
    20 bytes a step (Q, sigma, cycle)."""
    monkeypatch.setattr(history_module, "BLOCK_STEPS", 2**14)
    steps, peak = _peak_of_a_pass(tmp_path, 10_000)
    twice, peak_twice = _peak_of_a_pass(tmp_path, 20_000)
    assert (peak_twice - peak) / (twice - steps) < 6
