"""A sweep whose dask worker is killed in the middle (issue 38), on a real scheduler and workers started
as `dask scheduler` and `dask worker` processes on loopback: the scheduler gives the killed worker's
case to the other worker, the sweep completes, and its dataset and case files are those of a sweep run
without a kill: none lost, none twice. A sweep whose every worker dies stops, and resumes."""

import json
import os
import signal
import subprocess
import sys
import threading
import time

import pytest
import xarray as xr
from conftest import HERTZ_TOML

from fretting import cli
from fretting.results.io import WRITTEN_ATTRIBUTES
from fretting.studies import sweeps

distributed = pytest.importorskip("distributed")

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


def killed_for_good(cluster):
    """Kill every worker process of the `distributed.LocalCluster` `cluster` with SIGKILL, its nanny told
    not to start another (as a batch system that ends the workers' jobs)."""
    from distributed.core import Status

    for nanny in list(cluster.workers.values()):
        nanny.status = Status.closing_gracefully  # the nanny closes once its worker is gone
        os.kill(nanny.process.process.pid, signal.SIGKILL)


@pytest.mark.slow
def test_a_sweep_whose_every_worker_dies_stops_and_resumes(tmp_path, monkeypatch, capsys):
    """On a real local cluster whose only worker is killed for good after the first case: the sweep stops
    after `NO_WORKERS_SECONDS` with a one-line error that counts the cases kept and says how to go on;
    run again, it runs only the others."""
    monkeypatch.setattr(sweeps, "NO_WORKERS_SECONDS", 1.0)
    monkeypatch.setattr(sweeps, "WORKER_POLL_SECONDS", 0.1)
    (tmp_path / "base.toml").write_text(BASE)
    (tmp_path / "map.toml").write_text(SWEEP)
    cases = tmp_path / "dead.cases"
    command = ["sweep", str(tmp_path / "map.toml"), "-o", str(tmp_path / "dead.h5")]
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=":0"
    ) as cluster:

        def kill():
            waited(lambda: cases.is_dir() and any(cases.glob("*.h5")), 60, "case file")
            killed_for_good(cluster)

        killer = threading.Thread(target=kill, daemon=True)
        killer.start()
        began = time.monotonic()
        code = cli.main([*command, "--scheduler", cluster.scheduler_address])
        killer.join()
        assert time.monotonic() - began < 60
    err = capsys.readouterr().err.strip().splitlines()[-1]
    kept = {path.name: path.stat().st_mtime_ns for path in cases.iterdir()}
    assert code == cli.EXIT_FAILURE and not (tmp_path / "dead.h5").exists()
    assert err.startswith("fretting: error: ") and "no workers for 1 s" in err, err
    assert f"{len(kept)} of 6 cases finished, kept in {cases}; run the sweep again" in err, err
    assert 1 <= len(kept) < 6

    assert cli.main(command) == 0  # a local cluster of its own
    again = {path.name: path.stat().st_mtime_ns for path in cases.iterdir()}
    assert len(again) == 6 and all(again[name] == written for name, written in kept.items())
    assert xr.load_dataset(tmp_path / "dead.h5", engine="h5netcdf").regime.size == 6


class LostResult:
    """A future whose case finished on a worker that was then killed: `distributed.wait` saw it done, its
    result can no longer be fetched (the scheduler runs the case again, on no worker)."""

    status = "lost"

    def result(self, timeout=None):
        assert timeout is not None, "an unbounded fetch waits forever on a lost result"
        raise TimeoutError(f"timed out after {timeout} s.")


class NoWorkers:
    """A client of a scheduler whose every worker was killed."""

    def scheduler_info(self):
        return {"workers": {}}


def test_a_result_lost_with_its_worker_stops_the_sweep_as_no_workers(monkeypatch):
    """The race of a worker killed between its case finishing and the sweep fetching the result: the
    sweep waits on the future again, bounded by the no-worker check, and stops."""
    monkeypatch.setattr(sweeps, "NO_WORKERS_SECONDS", 0.05)
    lost = LostResult()

    def wait(pending, timeout, return_when):
        time.sleep(timeout)
        return set(pending), set()

    monkeypatch.setattr(sweeps, "WORKER_POLL_SECONDS", 0.01)
    fake = type("FakeDistributed", (), {"wait": staticmethod(wait)})
    with pytest.raises(sweeps.NoWorkersError, match="no workers for 0.05 s"):
        list(sweeps._completed(fake, NoWorkers(), {lost: 0}))


def test_a_case_that_fails_on_its_own_timeout_error_raises_it(monkeypatch):
    """A case whose own error is a TimeoutError (status "error") is raised, not taken for a lost result and
    waited on again (until the no-worker check stopped the sweep)."""
    monkeypatch.setattr(sweeps, "NO_WORKERS_SECONDS", 0.05)

    class Failed(LostResult):
        status = "error"

    def wait(pending, timeout, return_when):
        return set(pending), set()

    fake = type("FakeDistributed", (), {"wait": staticmethod(wait)})
    with pytest.raises(TimeoutError, match="timed out after"):
        list(sweeps._completed(fake, NoWorkers(), {Failed(): 0}))
