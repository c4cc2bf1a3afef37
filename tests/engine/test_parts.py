"""The parts of a run that stores the fields of some cycles only: bounded by the fields they hold."""

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.engine import runner
from fretting.models import Exact

LOADS = '[[loading]]\nkind = "random"\ncycles = 12\nQ_amplitude = 30e3\nseed = 5\nsteps_per_segment = 3\n'


def _run(tmp_path, monkeypatch, name, part_cycles, scalar_cycles):
    """The result of the random history with `cycle_fields` ``first,last`` and the sizes of the parts saved."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 1000)
    monkeypatch.setattr(runner, "CHUNK_CYCLES", 2)
    monkeypatch.setattr(runner, "PART_CYCLES", part_cycles)
    monkeypatch.setattr(runner, "PART_SCALAR_CYCLES", scalar_cycles)
    saved = []
    monkeypatch.setattr(runner, "save", lambda result, path: saved.append(result.sizes) or fr.save(result, path))
    history_file = tmp_path / "random.toml"
    history_file.write_text(HERTZ_TOML + LOADS)
    run = runner.run_file(history_file, tmp_path / name, Exact(), cycle_fields="first,last", checkpoint_interval=1e6)
    return fr.load(run.output), saved


@pytest.mark.slow
def test_parts_are_bounded_by_the_fields_and_the_scalars_they_hold(tmp_path, monkeypatch):
    """With the fields of two cycles of 12 stored, a part holds more cycles than PART_CYCLES (it
    holds fewer fields) but never more than PART_SCALAR_CYCLES; the result is the run saved in
    one part, bit for bit."""
    result, saved = _run(tmp_path, monkeypatch, "parts.h5", 2, 5)
    whole, one = _run(tmp_path, monkeypatch, "whole.h5", 1000, 1000)
    cycles = [sizes["cycle_number"] for sizes in saved]
    assert len(one) == 1 and len(saved) >= 3 and max(cycles) > 2 and max(cycles) <= 5
    assert sum(sizes.get("field_cycle", 0) for sizes in saved) == 2
    assert result.field_cycle.values.tolist() == [1, 12]
    for name, variable in whole.variables.items():
        np.testing.assert_array_equal(result[name].values, variable.values, err_msg=name)
