"""The runner's result against a run in one piece and against its history."""

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.engine import runner
from fretting.engine.recorder import Recorder
from fretting.models import Grid

#: A history of many chunks, with vertices where both loads vary.
LOADS = """
[[loading]]
kind = "sine"
Q_amplitude = 30e3
sigma_amplitude = 1e8
phase_deg = 90
cycles = 4
steps_per_cycle = 24

[[loading]]
kind = "linear"
Q = [10e3, -20e3]
sigma = [5e7, -3e7]
steps_per_segment = 7
"""


def test_a_run_in_chunks_keeps_the_loads_at_every_vertex(tmp_path, monkeypatch):
    """With the loads of every vertex the dataset holds the whole path, recorded steps or not:
    the same in chunks as in one run, and those of the history."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 5)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)
    history_file = tmp_path / "path.toml"
    history_file.write_text(HERTZ_TOML + LOADS)
    contact, history = fr.read_history(history_file)
    chunked = runner.run_file(history_file, tmp_path / "path.h5", Grid(32), record=[0, len(history) - 1]).result
    whole = fr.simulate(contact, history, nodes=32, record=[0, len(history) - 1])
    assert history.vertex_step.size == 8 and chunked.sizes["step"] == 2
    assert np.any(history.vertex_step[1:] % 5 == 0)  # a vertex at a chunk's end: in two chunks, kept once
    for name in ("vertex_step", "vertex_Q", "vertex_sigma"):
        np.testing.assert_array_equal(chunked[name].values, whole[name].values)
    np.testing.assert_array_equal(chunked.vertex_Q.values, history.Q[history.vertex_step])
    np.testing.assert_array_equal(chunked.vertex_sigma.values, history.sigma[history.vertex_step])
    assert chunked.vertex_Q.attrs["units"] == "N/m" and chunked.vertex_sigma.attrs["units"] == "Pa"


@pytest.mark.slow
def test_a_run_saved_in_parts_equals_the_run_in_one_piece(tmp_path, monkeypatch):
    """Parts of at most PART_CYCLES cycles, each saved as it fills and never held again: the
    result joined from them is the run in one piece; the checkpoint folder is gone after."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 5)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)
    monkeypatch.setattr(runner, "PART_CYCLES", 2)
    saved = []
    monkeypatch.setattr(runner, "save", lambda result, path: saved.append(result.sizes) or fr.save(result, path))
    history_file = tmp_path / "path.toml"
    history_file.write_text(HERTZ_TOML + LOADS)
    contact, history = fr.read_history(history_file)
    result = runner.run_file(history_file, tmp_path / "path.h5", Grid(32), checkpoint_interval=1e6).result
    whole = fr.simulate(contact, history, nodes=32)
    assert len(saved) >= 3 and max(sizes["cycle_number"] for sizes in saved) <= 3
    assert not runner.checkpoint_path(tmp_path / "path.h5").exists()
    for name, variable in whole.variables.items():
        if name != "cycle_copied":
            np.testing.assert_array_equal(result[name].values, variable.values, err_msg=name)


def test_a_skipping_run_in_chunks_equals_the_whole_skipping_run(tmp_path, monkeypatch):
    """Chunks end at steps the whole run solves, also inside straight stretches longer than a
    chunk: the chunked run, which skips the unrecorded steps, is the whole one bit for bit."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 5)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)
    history_file = tmp_path / "straight.toml"
    loads = '[[loading]]\nkind = "linear"\nQ = [30e3, -20e3, 25e3]\nsigma = [6e7, -4e7, 5e7]\nsteps_per_segment = 40\n'
    history_file.write_text(HERTZ_TOML + loads + LOADS)
    contact, history = fr.read_history(history_file)
    record = [0, 50, len(history) - 1]
    chunked = runner.run_file(history_file, tmp_path / "straight.h5", Grid(32), record=record).result
    stepper = fr.Stepper(contact, Grid(32))
    recorder = Recorder(stepper.model, history, np.array(record), skipping=True)
    whole = recorder.dataset(stepper.run(history, recorder))
    assert "not tallied" in chunked.attrs["cycle_peaks"]
    for name, variable in whole.variables.items():
        if name != "cycle_copied":
            np.testing.assert_array_equal(chunked[name].values, variable.values, err_msg=name)


@pytest.mark.slow
def test_chunks_begin_at_most_CHUNK_CYCLES_and_parts_never_exceed_PART_CYCLES(tmp_path, monkeypatch):
    """A part is saved before a chunk could take it past PART_CYCLES, and chunks larger in steps
    than CHUNK_CYCLES cycles are cut: every part saved holds at most PART_CYCLES cycles, and the
    result joined from them is the run in one piece bit for bit."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 1000)
    monkeypatch.setattr(runner, "CHUNK_CYCLES", 3)
    monkeypatch.setattr(runner, "PART_CYCLES", 5)
    saved, chunks = [], []
    monkeypatch.setattr(runner, "save", lambda result, path: saved.append(result.sizes) or fr.save(result, path))
    recorder = runner.Recorder
    monkeypatch.setattr(runner, "Recorder", lambda *args: chunks.append(args[1]) or recorder(*args))
    history_file = tmp_path / "random.toml"
    loads = '[[loading]]\nkind = "random"\ncycles = 20\nQ_amplitude = 30e3\nseed = 3\nsteps_per_segment = 2\n'
    history_file.write_text(HERTZ_TOML + loads)
    contact, history = fr.read_history(history_file)
    result = runner.run_file(history_file, tmp_path / "random.h5", Grid(32), checkpoint_interval=1e6).result
    whole = fr.simulate(contact, history, nodes=32)
    begun = [np.count_nonzero(np.diff(chunk.cycle)) for chunk in chunks]
    assert len(chunks) >= 7 and max(begun) == 3
    assert len(saved) >= 4 and max(sizes["cycle_number"] for sizes in saved) <= 5
    for name, variable in whole.variables.items():
        if name != "cycle_copied":
            np.testing.assert_array_equal(result[name].values, variable.values, err_msg=name)
