"""A running-condition map through the sweep machinery: the shipped sweep over the normal load and the
displacement amplitude (histories/sweeps/hertz_running_map.toml), its cases' last loops and the
partial-slip / gross-slip boundary, and `fretting sweep` then `fretting plot` of it on a local cluster."""

import numpy as np
import pytest

import fretting as fr
from fretting import cli
from fretting.loading.examples import EXAMPLES
from fretting.studies import running, sweeps

SHIPPED = EXAMPLES / "sweeps" / "hertz_running_map.toml"

#: Part of the shipped grid: two loads, an amplitude below both boundaries, one between, one above both.
GRID = {"contact.P": [50e3, 150e3], "loading[1].delta_amplitude": [0.5e-6, 1.5e-6, 4e-6]}


@pytest.fixture(scope="module")
def mapped():
    """The sweep of the shipped base over `GRID`, run in this process, as a sweep dataset and as a map."""
    plan = sweeps.read_sweep(SHIPPED)
    plan = sweeps.Sweep(plan.base, GRID, plan.origin)
    cases = [plan.case(values) for values in plan.cases()]
    summaries = sweeps.run_cases(cases, plan.base, in_process=True)
    swept = sweeps.gathered(plan.grid, summaries)
    return plan, cases, swept, running.running_cases(swept)


def test_the_map_of_a_sweep_is_split_by_the_boundary(mapped):
    """Each load's boundary is `transition_displacement` of its contact; the last cycle runs in partial slip
    below it and in gross slip above it; the energy and Fouvry's A grow with the amplitude."""
    plan, cases, _, result = mapped
    amplitudes = np.array(GRID["loading[1].delta_amplitude"])
    boundary = [running.transition_displacement(case.contact) for case in cases[:: amplitudes.size]]
    np.testing.assert_array_equal(result.transition.values, boundary)
    expected = np.where(amplitudes[None, :] > np.array(boundary)[:, None], 2, 1)
    np.testing.assert_array_equal(result.cycle_regime.values, expected)
    assert expected.tolist() == [[1, 2, 2], [1, 1, 2]]
    assert np.all(np.diff(result.cycle_dissipation.values, axis=1) > 0)
    assert np.all(np.diff(result.energy_ratio.values, axis=1) > 0)
    assert list(result.P.values) == GRID["contact.P"] and list(result.delta_amplitude.values) == list(amplitudes)


def test_each_case_keeps_the_last_loop_its_run_wrote(mapped):
    """A case's loop numbers are those the run wrote for its last cycle (fretting.results.loops)."""
    _, cases, swept, _ = mapped
    case = cases[4]  # P = 150 kN/m, delta* = 1.5 um
    result = fr.simulate(case.contact, case.history)
    point = swept.isel(contact_P=1, loading_1_delta_amplitude=1)
    for name in running.MAPPED.values():
        source = "cycle_dissipation" if name == "energy_per_cycle" else name
        assert point[name].values == result[source].values[-1], name


def test_only_a_sweep_over_P_and_a_displacement_amplitude_is_a_running_map(mapped):
    _, _, swept, _ = mapped
    assert running.running_dims(swept) == ("contact_P", "loading_1_delta_amplitude")
    other = swept.rename(contact_P="contact_f").assign_coords(contact_f=("contact_f", [0.6, 0.7], {"key": "contact.f"}))
    assert running.running_dims(other) is None
    with pytest.raises(ValueError, match="needs a sweep over contact.P and a delta_amplitude"):
        running.running_cases(other)


@pytest.mark.slow
def test_the_shipped_sweep_runs_and_plots_from_the_command_line(tmp_path, monkeypatch, capsys):
    """`fretting sweep` of a 2 x 2 sweep of the shipped base (dask, a local cluster), run again (every case
    read from its file), and `fretting plot` of its file: the fretting map and the running-condition maps."""
    text = SHIPPED.read_text().split("[grid]")[0].replace("cycles = 3", "cycles = 2")
    grid = '[grid]\n"contact.P" = [50e3, 150e3]\n"loading[1].delta_amplitude" = [0.5e-6, 4e-6]\n'
    (tmp_path / "running.toml").write_text(text + grid)
    monkeypatch.chdir(tmp_path)
    assert cli.main(["sweep", "running.toml", "-o", "running.h5"]) == 0
    written = {path.name: path.stat().st_mtime_ns for path in (tmp_path / "running.cases").iterdir()}
    assert cli.main(["sweep", "running.toml", "-o", "running.h5"]) == 0
    assert {path.name: path.stat().st_mtime_ns for path in (tmp_path / "running.cases").iterdir()} == written
    swept = sweeps.load_sweep(tmp_path / "running.h5")
    np.testing.assert_array_equal(swept.cycle_regime.values, [[1, 2], [1, 2]])
    capsys.readouterr()
    assert cli.main(["plot", "running.h5"]) == 0
    drawn = capsys.readouterr().out.split()
    for name in ("map", "running_cycle_regime", "running_energy_ratio"):
        assert f"running_{name}.png" in drawn and (tmp_path / f"running_{name}.png").stat().st_size > 0
