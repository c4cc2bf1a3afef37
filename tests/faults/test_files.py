"""Faults of the files a run writes and reads (issue 38): a disk that fills, a folder turned read-only,
damaged checkpoint parts and results. Each ends with the earlier result intact, one line on stderr,
a non-zero exit, and a resume or a rerun that writes what an uninterrupted run writes, bit for bit."""

import contextlib
import hashlib
import os
import resource
import shutil
import subprocess
import sys
import time

import h5py
import pytest
import xarray as xr
from conftest import HERTZ_TOML as CONTACT
from test_cli import _interrupt_after, data_of, run

from fretting.engine import runner
from fretting.results.io import ResultError, load

#: Each test runs fretting two to four times, in this process or another: seconds each.
pytestmark = pytest.mark.slow


def sine(cycles):
    """A history of `cycles` cycles of Q and sigma out of phase, 40 steps each (100 cycles: about two
    seconds on 32 nodes), saved in several parts."""
    return CONTACT + (
        '[[loading]]\nkind = "sine"\nQ_amplitude = 35e3\nsigma_amplitude = 1e8\nphase_deg = 90\n'
        f"cycles = {cycles}\nsteps_per_cycle = 40\n"
    )


#: A shorter history, whose result stands for the earlier result in the output's place.
EARLIER = CONTACT + '[[loading]]\nkind = "linear"\nQ = [20e3]\nsteps_per_segment = 4\n'
NODES = ("--nodes", "32")


def digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


#: The files of `folder`: the histories, the uninterrupted result and the earlier result.
FOLDER_FILES = ("long.toml", "earlier.toml", "whole.h5", "out.h5")


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """``cycles -> folder`` holding `FOLDER_FILES` for `sine` of `cycles`, each run once in this module
    (by the same commands, from the same relative names, as a test's folder would)."""
    made = {}

    def folder_of(cycles):
        if cycles not in made:
            where = tmp_path_factory.mktemp(f"sine_{cycles}")
            (where / "long.toml").write_text(sine(cycles))
            (where / "earlier.toml").write_text(EARLIER)
            with contextlib.chdir(where):
                assert run("run", "long.toml", "-o", "whole.h5", *NODES) == 0
                assert run("run", "earlier.toml", "-o", "out.h5", *NODES) == 0
            assert sorted(path.name for path in where.iterdir()) == sorted(FOLDER_FILES)
            made[cycles] = where
        return made[cycles]

    return folder_of


@pytest.fixture
def folder(request, tmp_path, monkeypatch, runs):
    """A working folder with the history ``long.toml`` (`sine` of 20 cycles, or of the parameter), its
    uninterrupted result ``whole.h5`` and an earlier result ``out.h5`` in the place the faulty runs write:
    copies of the files `runs` wrote, a fresh folder for each test."""
    monkeypatch.chdir(tmp_path)
    source = runs(getattr(request, "param", 20))
    for name in FOLDER_FILES:
        shutil.copy2(source / name, tmp_path / name)
    return tmp_path


def fretting_process(folder, output="out.h5", limit=None):
    """`python -m fretting run long.toml -o OUTPUT` in `folder`, checkpointed after every chunk, its
    files limited to `limit` bytes (``ulimit -f``, which stops root too: a write past it fails with EFBIG)."""

    def start():
        if limit is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    command = [sys.executable, "-m", "fretting", "run", "long.toml", "-o", output, *NODES]
    return subprocess.Popen(
        [*command, "--checkpoint-interval", "0"], cwd=folder, stderr=subprocess.PIPE, text=True, preexec_fn=start
    )


def assert_one_line(err, *words):
    assert err.startswith("fretting: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err and ".tmp" not in err and "HDF5" not in err, err
    for word in words:
        assert word in err, err


def assert_resumes_to_the_whole_run(folder, resume):
    """The run of out.h5 completed (resumed or run again) writes what the uninterrupted run wrote."""
    assert run("run", "long.toml", "-o", "out.h5", *NODES, *(["--resume"] if resume else [])) == 0
    xr.testing.assert_identical(data_of(load(folder / "out.h5")), data_of(load(folder / "whole.h5")))
    assert not (folder / "out.h5.checkpoint").exists()
    assert sorted(path.name for path in folder.iterdir() if path.name.startswith(".")) == []  # no temporaries


@pytest.mark.parametrize("where", ["first-part", "joining"])
def test_a_disk_that_fills_leaves_the_earlier_result_and_the_run_resumes(folder, where):
    """Files limited below the first part (nothing kept: a rerun), or between the largest part and the
    result (the parts kept: a resume). The limit is that of ``ulimit -f``, which stops root too."""
    earlier = digest(folder / "out.h5")
    whole = (folder / "whole.h5").stat().st_size
    limit = 4096 if where == "first-part" else whole - 1
    process = fretting_process(folder, limit=limit)
    _, err = process.communicate(timeout=120)
    assert process.returncode == 2, err
    assert_one_line(err, "out.h5", "cannot write")
    assert digest(folder / "out.h5") == earlier
    parts = runner._parts(folder / "out.h5.checkpoint")
    if where == "first-part":
        assert not parts and "--resume" not in err
    else:
        assert len(parts) > 1 and err.rstrip().endswith("progress kept in out.h5.checkpoint; continue with --resume")
        assert all(path.stat().st_size <= limit for path in parts)
    assert_resumes_to_the_whole_run(folder, resume=where == "joining")


@contextlib.contextmanager
def read_only(folder):
    """Turn `folder` read-only for the block: modes 555, or for root, whom modes do not stop, a
    read-only bind mount over it (seen by paths that cross it, not by a process whose current folder
    it is); skipped, with the reason printed, where root may not mount."""
    if os.geteuid() != 0:
        folder.chmod(0o555)
        try:
            yield
        finally:
            folder.chmod(0o755)
        return
    mounted = subprocess.run(["mount", "--bind", folder, folder], capture_output=True, text=True)
    if mounted.returncode:
        why = f"running as root, whom folder modes do not stop, and mount --bind fails: {mounted.stderr.strip()}"
        print(why)
        pytest.skip(why)
    try:
        subprocess.run(["mount", "-o", "remount,bind,ro", folder, folder], check=True)
        yield
    finally:
        subprocess.run(["umount", folder], check=True)


@pytest.mark.parametrize("folder", [100], indirect=True)  # time to turn the folder read-only
def test_a_folder_turned_read_only_in_the_middle_of_a_run_keeps_its_parts_and_resumes(folder):
    """The output's folder turns read-only once the first part is saved: the run stops at its next
    write, the earlier result and the parts saved kept, and resumes once the folder is writable."""
    earlier = digest(folder / "out.h5")
    process = fretting_process(folder, output=folder / "out.h5")
    checkpoint = folder / "out.h5.checkpoint"
    deadline = time.monotonic() + 60
    while not runner._parts(checkpoint) and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.002)
    with read_only(folder):
        _, err = process.communicate(timeout=120)
    assert process.returncode == 2, err
    assert_one_line(err, "Read-only file system" if os.geteuid() == 0 else "Permission denied")
    assert err.rstrip().endswith(f"progress kept in {checkpoint}; continue with --resume")
    assert digest(folder / "out.h5") == earlier and runner._parts(checkpoint)
    assert_resumes_to_the_whole_run(folder, resume=True)


def flip_data(path, variable):
    """Flip bytes in the middle of the first stored chunk of `variable` in the HDF5 file `path`."""
    with h5py.File(path, "r") as file:
        chunk = file[variable].id.get_chunk_info(0)
    with open(path, "r+b") as handle:
        handle.seek(chunk.byte_offset + chunk.size // 2)
        data = handle.read(8)
        handle.seek(chunk.byte_offset + chunk.size // 2)
        handle.write(bytes(byte ^ 0xFF for byte in data))


#: Ways a file is damaged: truncated, its data flipped, emptied.
DAMAGES = {
    "truncated": lambda path: path.write_bytes(path.read_bytes()[: path.stat().st_size // 2]),
    "flipped": lambda path: flip_data(path, "q"),
    "emptied": lambda path: path.write_bytes(b""),
}


@pytest.mark.parametrize("damage", DAMAGES)
def test_a_damaged_part_is_named_and_the_run_resumes_from_the_parts_before(folder, capsys, monkeypatch, damage):
    monkeypatch.setattr(runner, "CHUNK_STEPS", 200)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)  # chunks of 200 steps, a part each
    earlier = digest(folder / "out.h5")
    stepper = runner.Stepper
    monkeypatch.setattr(runner, "Stepper", _interrupt_after(3))
    assert run("run", "long.toml", "-o", "out.h5", *NODES, "--checkpoint-interval", "0") == 130
    monkeypatch.setattr(runner, "Stepper", stepper)
    checkpoint = folder / "out.h5.checkpoint"
    parts = runner._parts(checkpoint)
    assert len(parts) == 3
    DAMAGES[damage](parts[1])
    capsys.readouterr()
    assert run("run", "long.toml", "-o", "out.h5", *NODES, "--resume") == 2
    err = capsys.readouterr().err
    assert_one_line(err, f"{parts[1].relative_to(folder)}: ", "delete it and the parts after it")
    assert digest(folder / "out.h5") == earlier and runner._parts(checkpoint) == parts
    for part in parts[1:]:
        part.unlink()
    assert_resumes_to_the_whole_run(folder, resume=True)


@pytest.mark.parametrize("damage", DAMAGES)
def test_a_damaged_result_is_one_line_for_info_plot_and_load(folder, capsys, damage):
    path = folder / "damaged.h5"
    shutil.copyfile(folder / "whole.h5", path)
    DAMAGES[damage](path)
    for command in (["info", path], ["plot", path, "-o", folder / "figures"]):
        assert run(*command) == 2
        assert_one_line(capsys.readouterr().err, f"{path}: ")
    assert not (folder / "figures").exists() or not list((folder / "figures").iterdir())
    with pytest.raises(ResultError, match=f"^{path}: "):
        load(path)
    assert run("run", "long.toml", "-o", path, *NODES) == 0  # a rerun replaces it
    xr.testing.assert_identical(data_of(load(path)), data_of(load(folder / "whole.h5")))


def test_joining_parts_on_a_disk_without_room_for_them_is_refused_before_hdf5_writes(folder, capsys, monkeypatch):
    """The rows of the parts are appended to the result by HDF5, whose failure in the middle of a file
    may take the process down: a disk with less room than the rows is said first, the parts kept."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 200)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)  # chunks of 200 steps, a part each
    earlier = digest(folder / "out.h5")
    disk_usage = shutil.disk_usage
    monkeypatch.setattr(shutil, "disk_usage", lambda path: disk_usage(path)._replace(free=1000))
    assert run("run", "long.toml", "-o", "out.h5", *NODES, "--checkpoint-interval", "0") == 2
    assert_one_line(
        capsys.readouterr().err, "out.h5: cannot write: its disk has 1000 bytes free", "continue with --resume"
    )
    assert digest(folder / "out.h5") == earlier and len(runner._parts(folder / "out.h5.checkpoint")) == 5
    monkeypatch.setattr(shutil, "disk_usage", disk_usage)
    assert_resumes_to_the_whole_run(folder, resume=True)
