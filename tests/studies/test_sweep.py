"""Sweeps on a real dask.distributed cluster: every case equals a direct simulate, resume, errors, command line."""

import os
import subprocess
import sys
from pathlib import Path

import dask.config
import numpy as np
import pytest
import xarray as xr
from conftest import HERTZ_TOML
from distributed import LocalCluster

import fretting as fr
from fretting import cli
from fretting.loading.examples import EXAMPLES
from fretting.loading.history_file import HistoryFileError
from fretting.studies import sweeps
from fretting.studies.sweeps import REGIMES, VARIABLES, dimension, read_sweep, save_map, summarize

#: A short cyclic history: f P = 70 kN/m, so Q = 75 kN/m slides and Q = sigma = 0 sticks.
BASE = (
    HERTZ_TOML
    + """
[[loading]]
kind = "sine"
Q_amplitude = {Q}
sigma_amplitude = {sigma}
cycles = 2
steps_per_cycle = 16
ramp_steps = 4
"""
)
Q_KEY, SIGMA_KEY = "loading[1].Q_amplitude", "loading[1].sigma_amplitude"
Q_DIM, SIGMA_DIM = "loading_1_Q_amplitude", "loading_1_sigma_amplitude"  # the dimensions, named as CF allows
GRID = {Q_KEY: [0.0, 30e3, 75e3], SIGMA_KEY: [0.0, 60e6]}


@pytest.fixture(scope="module")
def cluster():
    """Address of a local cluster of two single-threaded worker processes on loopback."""
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=":0"
    ) as local:
        yield local.scheduler_address


@pytest.fixture(scope="module")
def swept(cluster, tmp_path_factory):
    """(base history, output file, dataset) of the sweep of GRID."""
    folder = tmp_path_factory.mktemp("sweep")
    base = write(folder / "base.toml", BASE.format(Q=20e3, sigma=10e6))
    output = folder / "out.h5"
    return base, output, fr.sweep(base, GRID, scheduler=cluster, output=output)


def write(path, text):
    path.write_text(text)
    return path


def direct(folder, Q, sigma):
    """Case variables of `simulate` run directly on the scene (Q, sigma), or the GrossSlipError it raises."""
    contact, history = fr.read_history(write(folder / "direct.toml", BASE.format(Q=Q, sigma=sigma)))
    try:
        return summarize(fr.simulate(contact, history))
    except fr.GrossSlipError as error:
        return error


@pytest.mark.slow
def test_every_case_is_a_direct_simulate_of_its_scene(swept, tmp_path):
    base, output, cases = swept
    assert list(cases.dims) == [Q_DIM, SIGMA_DIM] == [dimension(key) for key in GRID]
    for key, values in GRID.items():
        np.testing.assert_array_equal(cases[dimension(key)].values, values)
    assert cases[Q_DIM].attrs == {"long_name": Q_KEY, "key": Q_KEY, "units": "N/m"}
    np.testing.assert_array_equal(cases.regime.values, [[0, 1], [1, 1], [2, 2]])  # stuck, partial, gross slip
    for Q in GRID[Q_KEY]:
        for sigma in GRID[SIGMA_KEY]:
            case, expected = cases.sel({Q_DIM: Q, SIGMA_DIM: sigma}), direct(tmp_path, Q, sigma)
            if isinstance(expected, fr.GrossSlipError):
                assert int(case.gross_slip_step) == expected.step > 0
                assert all(np.isnan(case[name]) for name in ("total_dissipation", "energy_per_cycle", "w_max"))
                continue
            for name in VARIABLES:
                np.testing.assert_array_equal(case[name].values, expected[name].values, err_msg=name)
    stuck = cases.isel({Q_DIM: 0, SIGMA_DIM: 0})
    assert float(stuck.total_dissipation) == float(stuck.slip_amplitude_max) == 0.0
    assert cases.regime.attrs["flag_meanings"] == " ".join(REGIMES)
    xr.testing.assert_identical(xr.load_dataset(output, engine="h5netcdf").drop_attrs(), cases.drop_attrs())


@pytest.mark.slow
def test_resume_runs_only_the_cases_without_a_file(swept, cluster):
    base, output, cases = swept
    files = sorted(output.with_suffix(".cases").iterdir())
    assert len(files) == 6
    written = {file: file.stat().st_mtime_ns for file in files}
    files[2].unlink()
    again = fr.sweep(base, GRID, scheduler=cluster, output=output)
    xr.testing.assert_identical(again, cases)
    assert files[2].is_file()
    assert [file for file in files if file.stat().st_mtime_ns != written[file]] == [files[2]]

    write(base, BASE.format(Q=20e3, sigma=10e6).replace("cycles = 2", "cycles = 3"))  # another base: nothing reused
    fr.sweep(base, GRID, scheduler=cluster, output=output)
    assert len(list(output.with_suffix(".cases").iterdir())) == 12


def test_a_case_run_by_another_release_is_run_again(swept, cluster, monkeypatch):
    """The case files say which release of fretting ran them (issue 37: an upgrade reused old cases)."""
    base, output, _ = swept
    before = set(output.with_suffix(".cases").iterdir())
    monkeypatch.setattr(sweeps, "__version__", "0.0.1")  # as if the cases on disk were of a later release
    again = fr.sweep(base, GRID, scheduler=cluster, output=output)
    new = set(output.with_suffix(".cases").iterdir()) - before
    assert len(new) == 6  # none of the six cases reused
    assert {xr.load_dataset(file, engine="h5netcdf").attrs["fretting_version"] for file in new} == {"0.0.1"}
    xr.testing.assert_identical(again.drop_attrs(), fr.sweep(base, GRID, scheduler=cluster).drop_attrs())


@pytest.mark.parametrize(
    ("grid", "message"),
    [
        (
            {"loading[1].Q_amplitud": [1.0]},
            "grid.loading[1].Q_amplitud: unknown key, expected one of: kind, Q_amplitude",
        ),
        ({"loading[2].Q_amplitude": [1.0]}, "grid.loading[2].Q_amplitude: found no such table in"),
        ({"contact.f": [-0.7]}, "grid.contact.f: found -0.7, expected a number > 0"),
        ({"contact.f": ["high"]}, 'grid.contact.f: found "high", expected a number > 0'),
        ({"contact.f": [[0.5]]}, "grid.contact.f: found [0.5], expected a number > 0"),
        ({"contact.f": [{"a": 0.5}]}, 'grid.contact.f: found {"a": 0.5}, expected numbers, booleans, text or lists'),
        ({"contact.f": []}, "grid.contact.f: found [], expected a list of values"),
        ({"contact.f": [0.5, 0.5]}, "grid.contact.f: found 0.5 twice, expected distinct values"),
        ({"contact.f": np.array([0.6, 0.6])}, "grid.contact.f: found 0.6 twice, expected distinct values"),
        ({"contact f": [0.5]}, "grid.contact f: found a malformed key"),
        ({}, "grid: found {}, expected keys and lists of their values"),
        (
            {"contact.profile": ["flat"]},
            "contact.R: unknown key, expected one of: profile, E_star, E, nu, f, P, specimen, datum, compliance, a "
            "(in the case contact.profile",
        ),
    ],
)
def test_bad_grids_are_one_line_errors_naming_file_and_key(tmp_path, grid, message):
    base = write(tmp_path / "base.toml", BASE.format(Q=20e3, sigma=0.0))
    with pytest.raises(HistoryFileError) as error:
        fr.sweep(base, grid)  # raised before any cluster starts
    assert str(error.value).startswith(f"{base}") and message in str(error.value)
    assert "\n" not in str(error.value)


@pytest.mark.slow
def test_command_line_on_a_local_cluster(tmp_path, capsys):
    write(tmp_path / "base.toml", BASE.format(Q=20e3, sigma=0.0))
    grid = f'[grid]\n"{Q_KEY}" = [10e3, 80e3]\ncontact.f = [0.7]\n'
    sweep_file = write(tmp_path / "map.toml", f'history = "base.toml"\n{grid}')
    output = tmp_path / "map.h5"
    assert cli.main(["sweep", str(sweep_file), "-o", str(output)]) == 0
    assert capsys.readouterr().out == (
        f"{output}: 2 cases over {Q_KEY} (2) x contact.f (1): 0 stuck, 1 partial slip, 1 gross slip\n"
    )
    cases = xr.load_dataset(output, engine="h5netcdf")
    assert list(cases.dims) == [Q_DIM, "contact_f"] and cases.attrs["history_file"] == "base.toml"
    assert len(list(output.with_suffix(".cases").iterdir())) == 2


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('history = "base.toml"\nname = "x"\n[grid]\n"contact.f" = [0.5]\n', "name: unknown key"),
        ('history = "base.toml"\n', "grid: found no [grid] table"),
        ('[grid]\n"contact.f" = [0.5]\n', "found no base history"),
        ('history = "base.toml"\n[grid]\n"contact.f" = 0.5\n', "grid.contact.f: found 0.5, expected a list of values"),
        ('history = "missing.toml"\n[grid]\n"contact.f" = [0.5]\n', "missing.toml: No such file or directory"),
        (
            HERTZ_TOML.replace("f = 0.7", "f = -1")
            + '[[loading]]\nkind = "linear"\nQ = [1.0]\n[grid]\n"contact.P" = [1e5]\n',
            "map.toml:6: contact.f: found -1, expected a number > 0",
        ),
        ("[grid\n", "map.toml: TOML syntax"),
    ],
)
def test_bad_sweep_files_exit_2_with_one_line(tmp_path, capsys, text, message):
    write(tmp_path / "base.toml", BASE.format(Q=20e3, sigma=0.0))
    assert cli.main(["sweep", str(write(tmp_path / "map.toml", text))]) == 2
    error = capsys.readouterr().err
    assert error.startswith("fretting: error: ") and message in error and error.count("\n") == 1


def test_malformed_scheduler_address_exits_2(tmp_path, capsys):
    write(tmp_path / "base.toml", BASE.format(Q=20e3, sigma=0.0))
    sweep_file = write(tmp_path / "map.toml", 'history = "base.toml"\n[grid]\n"contact.f" = [0.5]\n')
    default = dask.config.get("scheduler", None)
    assert cli.main(["sweep", str(sweep_file), "--scheduler", "nonsense"]) == 2
    assert capsys.readouterr().err == (
        f"fretting: error: {sweep_file}: scheduler nonsense: missing port number in address 'nonsense'\n"
    )
    # the client that failed leaves dask's default scheduler as it was: a later write of this
    # process does not go to the scheduler that never answered
    assert dask.config.get("scheduler", None) == default


@pytest.mark.slow
def test_without_dask_distributed_a_sweep_names_the_extra(tmp_path, capsys, monkeypatch):
    """Without the extra ``fretting[sweep]``, `fretting.sweep` and ``fretting sweep`` fail with one
    line naming it (exit code 2), and nothing else needs it: ``import fretting`` loads no dask."""
    monkeypatch.setitem(sys.modules, "distributed", None)  # `import distributed` raises ImportError
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    base = write(tmp_path / "base.toml", BASE.format(Q=20e3, sigma=0.0))
    with pytest.raises(fr.FrettingError, match=r"fretting\[sweep\]") as error:
        fr.sweep(base, {"contact.f": [0.5]})
    assert isinstance(error.value, ImportError) and "\n" not in str(error.value)
    sweep_file = write(tmp_path / "map.toml", 'history = "base.toml"\n[grid]\n"contact.f" = [0.5]\n')
    assert cli.main(["sweep", str(sweep_file)]) == 2
    message = capsys.readouterr().err
    assert message.startswith("fretting: error: ") and "pip install 'fretting[sweep]'" in message
    assert message.count("\n") == 1
    here = str(Path(fr.__file__).resolve().parents[1])  # the fretting this test imports
    loaded = subprocess.run(
        [sys.executable, "-c", "import sys, fretting; print(sorted({m.split('.')[0] for m in sys.modules}))"],
        capture_output=True, text=True, check=True, env=os.environ | {"PYTHONPATH": here},
    ).stdout  # fmt: skip
    assert "'dask'" not in loaded and "'distributed'" not in loaded and "'matplotlib'" not in loaded


def test_inline_base_and_keys_inside_repeated_blocks(tmp_path):
    repeat = '[[loading]]\nkind = "repeat"\ncount = 2\nblocks = [{ kind = "linear", Q = [1e3, -1e3], cycle = true }]\n'
    grid = '[grid]\n"loading[2].blocks[1].steps_per_segment" = [4, 8]\n'
    plan = read_sweep(write(tmp_path / "inline.toml", BASE.format(Q=20e3, sigma=0.0) + repeat + grid))
    assert plan.grid == {"loading[2].blocks[1].steps_per_segment": [4, 8]}
    assert plan.base.path == plan.origin == tmp_path / "inline.toml" and set(plan.base.data) == {"contact", "loading"}


@pytest.mark.slow
def test_shipped_fretting_map(swept, tmp_path):
    plan = read_sweep(EXAMPLES / "sweeps" / "hertz_fretting_map.toml")
    assert plan.base.path.name == "hertz_fretting_fatigue.toml"
    assert [len(values) for values in plan.grid.values()] == [8, 8]
    assert save_map(swept[2], tmp_path / "map.png").stat().st_size > 0
