"""The cycles whose per-cycle fields a long run stores (its cycle_fields policy), and the fields
accumulated over every cycle, against a run that stores every cycle's."""

import contextlib

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.analysis import nucleation
from fretting.cli import main
from fretting.engine import recorder, runner
from fretting.engine.recorder import CycleFields
from fretting.models import Grid
from fretting.plots import figures_for

#: Random amplitudes of Q alone (the exact model): cycles of unequal energy, so some set new maxima.
RANDOM = '[[loading]]\nkind = "random"\ncycles = 16\nQ_amplitude = 40e3\nseed = 3\nsteps_per_segment = 4\n'

CHOSEN = "first,last,every=5,maxima"

#: A small grid: the policy, not the model, is tested.
MODEL = Grid(16)


@pytest.fixture(scope="module")
def history_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("cycle_fields") / "random.toml"
    path.write_text(HERTZ_TOML + RANDOM)
    return path


def _run(history_file, name, policy, **options):
    output = history_file.with_name(name)
    return fr.run_file(history_file, output, MODEL, cycle_fields=policy, **options).result.load()


@pytest.fixture(scope="module")
def every(history_file):
    """The run that stores every cycle's fields, in one chunk."""
    return _run(history_file, "all.h5", "all")


@contextlib.contextmanager
def small_chunks():
    """Chunks of a few steps and parts of a few cycles: cycles span chunks and parts."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(runner, "CHUNK_STEPS", 5)
        patch.setattr(runner, "CHUNK_SECONDS", 0.0)
        patch.setattr(runner, "MAX_CHUNK_STEPS", 21)
        patch.setattr(runner, "CHUNK_CYCLES", 3)
        patch.setattr(runner, "PART_CYCLES", 6)
        yield


@pytest.fixture(scope="module")
def some(history_file):
    """The run that stores the fields of the cycles `CHOSEN`, in small chunks and parts."""
    with small_chunks():
        return _run(history_file, "some.h5", CHOSEN)


def test_the_policy_stores_the_first_last_every_kth_and_maxima_cycles(every, some):
    energy, numbers = every.cycle_dissipation.values, every.cycle_number.values
    maxima = [n for k, n in enumerate(numbers) if k == 0 or energy[k] > energy[:k].max()]
    expected = sorted({1, int(numbers[-1]), *range(5, int(numbers[-1]) + 1, 5), *maxima})
    assert numbers[-1] == 16 and 2 < len(maxima) < 10  # a few new maxima, not every cycle
    assert some.field_cycle.values.tolist() == expected and some.attrs["cycle_fields"] == CHOSEN
    assert "field_cycle" not in every.dims and every.attrs["cycle_fields"] == "all"
    for name in ("w", "slip_amplitude", "q_peak"):
        assert some[name].dims == ("field_cycle", "x")
        np.testing.assert_array_equal(some[name].values, every[name].sel(cycle_number=expected).values, err_msg=name)
    np.testing.assert_array_equal(some.cycle_dissipation.values, energy)  # the scalars of every cycle


def test_accumulated_fields_are_the_sums_and_maxima_of_every_cycle(every, some):
    assert every.w.sizes["cycle_number"] == 16
    np.testing.assert_array_equal(some.w_total.values, nucleation.accumulated_dissipation_density(every)[-1].values)
    for name in ("slip_amplitude", "q_peak", "sigma_xx_peak", "sigma_xx_q_peak"):
        np.testing.assert_array_equal(some[f"{name}_max"].values, every[name].values.max(axis=0), err_msg=name)
    assert float(some.cycle_dissipation_max) == every.cycle_dissipation.values.max()


def test_every_cycle_is_the_run_of_today_and_the_default_of_short_histories(history_file, every):
    contact, history = fr.read_history(history_file)
    whole = fr.simulate(contact, history, MODEL)
    default = _run(history_file, "default.h5", "default")
    for result in (every, default):
        assert result.attrs["cycle_fields"] == "all" and set(result.variables) == set(whole.variables)
        for name, variable in whole.variables.items():
            if name != "cycle_copied":
                np.testing.assert_array_equal(result[name].values, variable.values, err_msg=name)


@pytest.mark.slow
def test_the_default_past_CYCLE_FIELDS_STORED_cycles(history_file, monkeypatch):
    assert CycleFields.parse("default", recorder.CYCLE_FIELDS_STORED).all
    assert str(CycleFields.parse("default", 3 * recorder.CYCLE_FIELDS_STORED + 1)) == "first,last,every=4,maxima"
    monkeypatch.setattr(recorder, "CYCLE_FIELDS_STORED", 10)
    run = fr.run_file(history_file, history_file.with_name("default.h5"), MODEL, cycle_fields="default")
    result = run.result.load()
    assert result.attrs["cycle_fields"] == "first,last,every=2,maxima"
    assert any("stored for the cycles first,last,every=2,maxima only" in note for note in run.notes)
    every_cycle = fr.run_file(history_file, history_file.with_name("each.h5"), MODEL, cycle_fields="all")
    assert not any("per-cycle fields" in note for note in every_cycle.notes)
    assert {1, 2, 4, 14, 16} <= set(result.field_cycle.values.tolist()) and result.sizes["cycle_number"] == 16


@pytest.mark.slow
def test_a_resumed_run_stores_the_cycles_of_the_uninterrupted_one(history_file, some):
    output, calls = history_file.with_name("cut.h5"), []

    def interrupt(done, total):
        calls.append(done)
        if len(calls) == 8:
            raise KeyboardInterrupt

    with small_chunks(), pytest.raises(KeyboardInterrupt):
        fr.run_file(history_file, output, MODEL, cycle_fields=CHOSEN, progress=interrupt, checkpoint_interval=0)
    with pytest.raises(fr.results.io.ResultError, match="cycle_fields = first,last,every=5,maxima, expected all"):
        fr.run_file(history_file, output, MODEL, cycle_fields="all", resume=True)
    assert len(runner._parts(runner.checkpoint_path(output))) >= 2
    resumed = fr.run_file(history_file, output, MODEL, cycle_fields=CHOSEN, resume=True).result.load()
    for name, variable in some.variables.items():
        if name != "cycle_copied":
            np.testing.assert_array_equal(resumed[name].values, variable.values, err_msg=name)


def test_analysis_of_every_cycle_refuses_a_result_of_chosen_cycles(history_file):
    some = _run(history_file, "some.h5", "first,last")
    for function in (nucleation.dissipation_density, nucleation.slip_amplitude, nucleation.ruiz):
        with pytest.raises(ValueError, match="cycle_fields policy \\(first,last\\) chose"):
            function(some)


@pytest.mark.parametrize("policy", ["some", "every=0", "first,every=2,every=3", "every=x", "all,first", ""])
def test_a_bad_policy_is_a_one_line_error(history_file, policy, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["run", str(history_file), "--cycle-fields", policy])
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert exit_.value.code == 2 and "argument --cycle-fields: expected" in err and repr(policy) in err
    with pytest.raises(ValueError, match="cycle_fields must be"):
        CycleFields.parse(policy, 10)


def test_figures_of_a_result_with_some_cycles_leave_out_the_per_cycle_fields(some, every):
    """`fretting plot` draws what a result with some cycles' fields can give, without the per-cycle
    densities that `fretting.analysis.nucleation` refuses for it."""
    names = figures_for(some)
    assert "energy" in names and "dissipation_density" not in names and "slip_amplitude" not in names
    assert "dissipation_density" in figures_for(every)
