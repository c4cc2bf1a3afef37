"""The fretting loop of each cycle written by the run (fretting.results.loops): in `simulate`'s result
and `run_file`'s, the same bit for bit however the run is cut into chunks, parts and resumed runs;
NaN for the cycles whose steps are not all recorded; read back by `loop_cycles`, which computes them
for a result written without them."""

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.engine import runner
from fretting.engine.recorder import final_state
from fretting.results.io import join_results
from fretting.results.loops import LOOP_VARIABLES
from fretting.studies import running


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=5e-3, compliance=1e-12)


@pytest.fixture(scope="module")
def mixed(contact):
    """Two partial-slip cycles at 0.7 delta_t, then two gross-slip cycles at 1.5 delta_t, 4 steps a quarter."""
    small, large = 0.7 * running.transition_displacement(contact), 1.5 * running.transition_displacement(contact)
    cycle = fr.History.piecewise_linear(delta=[small, -small, small], steps_per_segment=8).as_cycle()
    sliding = fr.History.piecewise_linear(delta=[large, -large, large], steps_per_segment=8).as_cycle()
    ramps = [fr.History.piecewise_linear(delta=ends, steps_per_segment=4) for ends in ([0, small], [small, large])]
    history = fr.History.concatenate([ramps[0], cycle, cycle, ramps[1], sliding, sliding])
    return history, fr.simulate(contact, history, fr.models.Exact())


def test_the_run_writes_the_loop_of_each_cycle(mixed):
    """Every cycle recorded whole has its loop; the regimes are those of its steps."""
    _, result = mixed
    assert all(name in result for name in LOOP_VARIABLES)
    assert result.cycle_regime.values.tolist() == [1, 1, 2, 2]
    assert np.all(np.isfinite(result.loop_opening.values)) and np.all(result.energy_ratio.values > 0)
    assert result.delta_amplitude.attrs["units"] == "m" and "datum" in result.energy_ratio.attrs["long_name"]


def test_a_result_written_without_them_still_gives_them(tmp_path, mixed):
    """A file without the loop variables (an older version's) loads, and `loop_cycles` computes the same."""
    _, result = mixed
    fr.save(result.drop_vars(list(LOOP_VARIABLES)), tmp_path / "old.h5")
    old = fr.load(tmp_path / "old.h5")
    assert "loop_opening" not in old
    computed, written = running.loop_cycles(old), running.loop_cycles(result)
    for name in LOOP_VARIABLES:
        np.testing.assert_array_equal(computed[name].values, written[name].values, err_msg=name)


def test_parts_joined_are_the_whole_run(contact, mixed):
    """A run cut at any step and joined (`join_results`) has the loops of the whole run bit for bit;
    each part alone has those of the cycles it holds whole, NaN (regime -1) for the one it cuts."""
    history, whole = mixed
    for k in (10, 30, 50, 60):  # inside each cycle
        first = fr.simulate(contact, history[: k + 1], fr.models.Exact())
        later = fr.simulate(contact, history[k:], state=final_state(first))
        joined = join_results([first, later])
        for name in LOOP_VARIABLES:
            np.testing.assert_array_equal(joined[name].values, whole[name].values, err_msg=f"{name} at {k}")
        assert later.cycle_regime.values[0] == -1 and np.isnan(later.Q_amplitude.values[0])


def test_unrecorded_cycles_have_none(contact, mixed):
    """Recording every step but one of cycle 2: its loop is NaN and its regime -1, the others the whole run's."""
    history, whole = mixed
    steps = np.delete(np.arange(len(history)), int(np.flatnonzero(history.cycle == 2)[3]))
    result = fr.simulate(contact, history, fr.models.Exact(), record=steps)
    assert result.cycle_regime.values.tolist() == [1, -1, 2, 2]
    for name in LOOP_VARIABLES[:-1]:
        values = result[name].values
        assert np.isnan(values[1]), name
        np.testing.assert_array_equal(np.delete(values, 1), np.delete(whole[name].values, 1), err_msg=name)


def delta_cycles(amplitude, count):
    """History-file blocks: up to `amplitude` [m] in 5 steps, then `count` cycles of +-`amplitude`."""
    cycle = f'{{ kind = "linear", delta = [{-amplitude}, {amplitude}], steps_per_segment = 7, cycle = true }}'
    up = f'[[loading]]\nkind = "linear"\ndelta = [{amplitude}]\nsteps_per_segment = 5\n'
    return up + f'[[loading]]\nkind = "repeat"\ncount = {count}\nblocks = [{cycle}]\n'


#: Four cycles of +-1 um in partial slip, then three of +-3 um in gross slip (delta_t = 1.64 um).
FILE = HERTZ_TOML + "datum = 5e-3\n" + delta_cycles(1e-6, 4) + delta_cycles(3e-6, 3)


def test_a_file_run_in_chunks_interrupted_and_resumed_is_the_run_in_one_piece(tmp_path, monkeypatch):
    """`run_file` in chunks of 9 steps, a part saved after each, interrupted and resumed: the file's
    loops are those of `simulate` of the whole history, bit for bit, partial and gross slip both."""
    source = tmp_path / "cycles.toml"
    source.write_text(FILE)
    whole = fr.simulate(*fr.read_history(source), fr.models.Exact())
    assert set(whole.cycle_regime.values.tolist()) == {1, 2}
    monkeypatch.setattr(runner, "CHUNK_STEPS", 9)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)

    def stop(done, total):
        if 40 <= done < total:
            raise KeyboardInterrupt

    output = tmp_path / "cycles.h5"
    with pytest.raises(KeyboardInterrupt):
        runner.run_file(source, output, fr.models.Exact(), checkpoint_interval=0, progress=stop)
    resumed = runner.run_file(source, output, fr.models.Exact(), checkpoint_interval=0, resume=True)
    assert not any("no checkpoint" in note for note in resumed.notes)
    result = fr.load(output)
    for name in LOOP_VARIABLES:
        np.testing.assert_array_equal(result[name].values, whole[name].values, err_msg=name)


def test_a_run_that_skips_steps_has_the_loops_of_the_cycles_it_records(tmp_path):
    """`run_file` of a force-controlled history on a datum, recording cycle 2 only (with the steps either
    side, which show it whole): the other cycles' steps are skipped or not recorded, their loops NaN;
    cycle 2's is the whole run's."""
    source = tmp_path / "forced.toml"
    blocks = '[[loading]]\nkind = "sine"\nQ_amplitude = 40e3\ncycles = 3\nsteps_per_cycle = 16\n'
    source.write_text(HERTZ_TOML + "datum = 5e-3\n" + blocks)
    contact, history = fr.read_history(source)
    whole = fr.simulate(contact, history, fr.models.Exact())
    steps = np.flatnonzero(history.cycle == 2)
    run = runner.run_file(
        source, tmp_path / "forced.h5", fr.models.Exact(), record=np.r_[steps[0] - 1, steps, steps[-1] + 1]
    )
    result = fr.load(run.output)
    assert "skipped" in " ".join(run.notes)
    assert result.cycle_regime.values.tolist() == [-1, 1, -1]
    for name in LOOP_VARIABLES[:-1]:
        assert np.isnan(result[name].values[[0, 2]]).all(), name
        np.testing.assert_allclose(result[name].values[1], whole[name].values[1], rtol=1e-12, err_msg=name)
