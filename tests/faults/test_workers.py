"""A sweep whose dask worker is killed in the middle (issue 38), on a real scheduler and workers started
as `dask scheduler` and `dask worker` processes on loopback: the scheduler gives the killed worker's
case to the other worker, the sweep completes, and its dataset and case files are those of a sweep run
without a kill: none lost, none twice."""

import json
import signal
import subprocess
import sys
import time

import pytest
import xarray as xr
from conftest import HERTZ_TOML

from fretting import cli
from fretting.results.io import WRITTEN_ATTRIBUTES

pytest.importorskip("distributed")

#: A cyclic history of a second or so a case.
BASE = HERTZ_TOML + (
    '[[loading]]\nkind = "sine"\nQ_amplitude = 20e3\nsigma_amplitude = 10e6\ncycles = 25\nsteps_per_cycle = 24\n'
)
SWEEP = 'history = "base.toml"\n[grid]\n"loading[1].Q_amplitude" = [10e3, 25e3, 40e3]\n"contact.f" = [0.6, 0.7]\n'


def started(command, folder):
    return subprocess.Popen(command, cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def waited(condition, seconds, what):
    deadline = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < deadline, f"no {what} after {seconds} s"
        time.sleep(0.02)


def data_of(dataset):
    copy = dataset.copy()
    copy.attrs = {name: value for name, value in dataset.attrs.items() if name not in WRITTEN_ATTRIBUTES}
    return copy


@pytest.mark.slow
def test_a_killed_worker_leaves_a_sweep_that_completes_with_every_case_once(tmp_path):
    (tmp_path / "base.toml").write_text(BASE)
    (tmp_path / "map.toml").write_text(SWEEP)
    address_file = tmp_path / "scheduler.json"
    scheduler = started(
        [
            sys.executable,
            "-m",
            "distributed.cli.dask_scheduler",
            "--host",
            "127.0.0.1",
            "--port",
            "0",
            "--no-dashboard",
            "--scheduler-file",
            address_file,
        ],
        tmp_path,
    )
    workers = []
    try:
        waited(address_file.is_file, 30, "scheduler file")
        waited(lambda: json.loads(address_file.read_text() or "{}").get("address"), 30, "scheduler address")
        address = json.loads(address_file.read_text())["address"]
        workers = [
            started(
                [
                    sys.executable,
                    "-m",
                    "distributed.cli.dask_worker",
                    address,
                    "--nthreads",
                    "1",
                    "--no-nanny",
                    "--no-dashboard",
                    "--name",
                    f"w{k}",
                ],
                tmp_path,
            )
            for k in range(2)
        ]
        command = [sys.executable, "-m", "fretting", "sweep", "map.toml", "--scheduler", address]
        sweep = subprocess.Popen([*command, "-o", "killed.h5"], cwd=tmp_path, stderr=subprocess.PIPE, text=True)
        cases = tmp_path / "killed.cases"
        waited(lambda: cases.is_dir() and any(cases.glob("*.h5")), 60, "case file")
        done_at_kill = len(list(cases.glob("*.h5")))
        workers[0].send_signal(signal.SIGKILL)
        _, err = sweep.communicate(timeout=120)
        assert sweep.returncode == 0, err
        assert done_at_kill < 6, "the sweep ended before the kill: make its cases longer"

        assert (
            cli.main(["sweep", str(tmp_path / "map.toml"), "--scheduler", address, "-o", str(tmp_path / "whole.h5")])
            == 0
        )
    finally:
        for process in [*workers, scheduler]:
            process.kill()
            process.wait()
    killed, whole = (xr.load_dataset(tmp_path / name, engine="h5netcdf") for name in ("killed.h5", "whole.h5"))
    xr.testing.assert_identical(data_of(killed), data_of(whole))
    names = sorted(path.name for path in cases.iterdir())
    assert len(names) == 6 and names == sorted(path.name for path in (tmp_path / "whole.cases").iterdir())
