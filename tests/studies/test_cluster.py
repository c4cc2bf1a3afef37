"""A sweep on a real ``dask scheduler`` whose worker runs in another folder than the one the sweep is
submitted from: the tables its history names are read where it is submitted, never by the worker."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from conftest import HERTZ_TOML
from distributed import Client

import fretting as fr
from fretting import cli
from fretting.studies.sweeps import read_sweep, run_sweep, summarize

#: A history of a table: two cycles of Q and sigma, read from loads.csv (f P = 70 kN/m).
TABLE = "Q,sigma\n0,0\n20e3,10e6\n-20e3,-10e6\n20e3,10e6\n-20e3,-10e6\n"
HISTORY = HERTZ_TOML + '[[loading]]\nkind = "csv"\nfile = "loads.csv"\nsteps_per_segment = 8\n'

#: Seconds the scheduler and its worker have to start.
START = 60


@pytest.fixture(scope="module")
def scheduler_file(tmp_path_factory):
    """The file of a ``dask scheduler`` process with one single-threaded ``dask worker`` process, both
    started in folders of their own and importing the `fretting` that the tests import."""
    folder = tmp_path_factory.mktemp("cluster")
    (folder / "workers").mkdir()
    file = folder / "scheduler.json"
    dask = Path(sys.executable).parent / "dask"
    here = str(Path(fr.__file__).resolve().parents[1])
    options = {"env": os.environ | {"PYTHONPATH": here}, "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    started = [
        subprocess.Popen(
            [dask, "scheduler", "--scheduler-file", file, "--host", "127.0.0.1", "--port", "0", "--no-dashboard"],
            cwd=folder,
            **options,
        ),
        subprocess.Popen(
            [dask, "worker", "--scheduler-file", file, "--nthreads", "1", "--nworkers", "1", "--no-dashboard"],
            cwd=folder / "workers",
            **options,
        ),
    ]
    try:
        with Client(scheduler_file=str(file), timeout=START) as client:
            client.wait_for_workers(1, timeout=START)
        yield file
    finally:
        for process in started[::-1]:
            process.terminate()
            process.wait(timeout=START)


@pytest.mark.slow  # 10 to 15 s on 2 cores: a scheduler and a worker process start
def test_a_sweep_of_tables_on_a_scheduler_whose_worker_is_elsewhere(scheduler_file, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    study = tmp_path / "study"
    study.mkdir()
    (study / "loads.csv").write_text(TABLE)
    (study / "history.toml").write_text(HISTORY)
    (study / "map.toml").write_text('history = "history.toml"\n[grid]\ncontact.f = [0.6, 0.7]\n')
    with Client(scheduler_file=str(scheduler_file)) as client:
        (cwd,) = client.run(os.getcwd).values()
        assert Path(cwd) == scheduler_file.parent / "workers" and not (Path(cwd) / "study").exists()
    assert cli.main(["sweep", "study/map.toml", "--scheduler-file", str(scheduler_file)]) == 0
    assert (
        capsys.readouterr().out == "results/map.h5: 2 cases over contact.f (2): 0 stuck, 2 partial slip, 0 gross slip\n"
    )
    cases = xr.load_dataset("results/map.h5", engine="h5netcdf")
    for f in (0.6, 0.7):
        (study / "direct.toml").write_text(HISTORY.replace("f = 0.7", f"f = {f}"))
        expected = summarize(fr.simulate(*fr.read_history(study / "direct.toml")))
        for name, variable in expected.items():
            np.testing.assert_array_equal(cases.sel(contact_f=f)[name].values, variable.values, err_msg=name)

    calls = []  # the Python function, the scheduler by address; nothing kept, so every case runs
    with Client(scheduler_file=str(scheduler_file)) as client:
        address = client.scheduler.address
    again = run_sweep(read_sweep(study / "map.toml"), address, progress=lambda *call: calls.append(call))
    assert calls == [(0, 2), (1, 2), (2, 2)]
    xr.testing.assert_identical(again.drop_attrs(), cases.drop_attrs())
