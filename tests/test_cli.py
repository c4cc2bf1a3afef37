"""The command line: run, validate, info, plot; one-line errors and exit codes; nothing lost; resume."""

import hashlib
import importlib
import os
import shutil
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr
from conftest import HERTZ_TOML as CONTACT

import fretting as fr
from fretting import cli, plots
from fretting.engine import runner
from fretting.loading.history_file import read_history
from fretting.results.io import WRITTEN_ATTRIBUTES, load
from fretting.results.notes import UNRESOLVED

NODES = "32"


SHEAR = """
[[loading]]
kind = "linear"
Q = [30e3]
steps_per_segment = 10

[[loading]]
kind = "repeat"
count = 3
blocks = [{ kind = "linear", Q = [-30e3, 30e3], steps_per_segment = 12, cycle = true }]
"""


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def write(path, text):
    path.write_text(text)
    return path


def run(*arguments):
    return cli.main([str(argument) for argument in arguments])


def data_of(result):
    """`result` without what differs between runs: what writing adds (the time, the versions, the history)
    and which cycles were copied."""
    copy = result.drop_vars("cycle_copied", errors="ignore")
    copy.attrs = {name: value for name, value in result.attrs.items() if name not in WRITTEN_ATTRIBUTES}
    return copy


def test_run_writes_a_self_describing_result(workdir, capsys):
    history = write(workdir / "shear.toml", CONTACT + SHEAR)
    assert run("run", "shear.toml", "--nodes", NODES) == 0
    out, err = capsys.readouterr()
    result = load(workdir / "shear.h5")
    # the only note: the coarse grid's slip zones (fretting.results.notes)
    assert out.startswith("shear.h5: 82 steps, 3 cycles") and err == f"fretting: note: {result.attrs[UNRESOLVED]}\n"
    assert result.attrs["history_toml"] == history.read_text()
    assert result.attrs["history_sha256"] == hashlib.sha256(history.read_bytes()).hexdigest()
    assert result.attrs["history_file"] == "shear.toml" and result.attrs["nodes"] == int(NODES)
    contact, loads = read_history(history)
    expected = fr.simulate(contact, loads, nodes=int(NODES))  # one chunk: the same computation
    engine = result.copy()
    engine.attrs = {name: result.attrs[name] for name in expected.attrs}
    xr.testing.assert_identical(engine, expected)
    # in the current folder, not results/ (shipped results); no checkpoint, temporary or lock file left
    assert sorted(path.name for path in workdir.iterdir()) == ["shear.h5", "shear.toml"]


@pytest.mark.slow
def test_validate_info_and_plot(workdir, capsys):
    write(workdir / "shear.toml", CONTACT + SHEAR)
    assert run("validate", "shear.toml") == 0
    assert "82 steps, 8 vertices, 3 cycles" in capsys.readouterr().out
    assert run("run", "shear.toml", "-o", "out/shear.h5", "--nodes", NODES) == 0
    capsys.readouterr()
    assert run("info", "out/shear.h5") == 0
    info = capsys.readouterr().out
    assert "history   shear.toml (sha256 " in info and "32 nodes" in info and "max |Q| / (f P) = 0.429" in info
    assert run("plot", "out/shear.h5", "-o", "figures") == 0
    names = sorted(path.name for path in (workdir / "figures").iterdir())
    expected = {"energy", "hysteresis", "slip", "traction", "loops", "dissipation_density", "slip_amplitude"}
    assert names == sorted(f"shear_{name}.png" for name in plots.figures_for(load(workdir / "out/shear.h5")))
    assert expected <= {name.removeprefix("shear_").removesuffix(".png") for name in names}
    assert all((workdir / "figures" / name).read_bytes().startswith(b"\x89PNG") for name in names)


def test_plot_writes_vector_files_and_the_size_and_resolution_asked(workdir, capsys):
    """`fretting plot --format svg|pdf` writes vector files, `--size` and `--dpi` set a png's pixels (issue 37)."""
    write(workdir / "ramp.toml", CONTACT + '[[loading]]\nkind = "linear"\nQ = [30e3]\nsigma = [50e6]\n')
    assert run("run", "ramp.toml", "--nodes", NODES) == 0
    assert run("plot", "ramp.h5", "--format", "svg", "-o", "svg") == 0
    assert run("plot", "ramp.h5", "--format", "pdf", "-o", "pdf") == 0
    assert run("plot", "ramp.h5", "--size", "3", "2", "--dpi", "50", "-o", "png") == 0
    assert (workdir / "svg" / "ramp_traction.svg").read_text().lstrip().startswith("<?xml")
    assert (workdir / "pdf" / "ramp_traction.pdf").read_bytes().startswith(b"%PDF")
    header = (workdir / "png" / "ramp_traction.png").read_bytes()[16:24]  # the IHDR chunk's width, height
    assert (int.from_bytes(header[:4], "big"), int.from_bytes(header[4:], "big")) == (150, 100)


def test_plot_without_cycles(workdir, capsys):
    write(workdir / "ramp.toml", CONTACT + '[[loading]]\nkind = "linear"\nQ = [30e3]\nsigma = [50e6]\n')
    assert run("run", "ramp.toml", "--nodes", NODES) == 0
    assert run("plot", "ramp.h5") == 0
    assert sorted(path.name for path in workdir.glob("*.png")) == [
        "ramp_hysteresis.png",
        "ramp_slip.png",
        "ramp_surface_stress.png",
        "ramp_traction.png",
    ]


@pytest.mark.parametrize(
    ("text", "words"),
    [
        (None, "bad.toml: No such file or directory"),
        (CONTACT + "[[loading]\n", "bad.toml:8: TOML syntax"),
        (CONTACT + SHEAR.replace("steps_per_segment = 10", "step = 10"), "bad.toml:12: loading[1].step: unknown key"),
        (CONTACT.replace('"hertz"', '"sphere"'), 'bad.toml:2: contact.profile: found "sphere", expected one of'),
        (CONTACT.replace("f = 0.7", "f = -0.7") + SHEAR, "bad.toml:6: contact.f: found -0.7, expected a number > 0"),
        (CONTACT.replace("E = 210e9", "E = true") + SHEAR, "bad.toml:4: contact.E: found true, expected a number"),
        (CONTACT, "bad.toml: found no [[loading]] blocks, expected at least one"),
        (CONTACT.replace("f = 0.7", "f = 1e300") + SHEAR, "(f p0 a)^2 / E_star overflows a float"),
    ],
    ids=["missing", "syntax", "unknown-key", "unknown-profile", "negative", "non-numeric", "empty", "overflow"],
)
@pytest.mark.parametrize("command", ["run", "validate"])
def test_bad_input_is_one_line_and_exit_2(workdir, capsys, command, text, words):
    if text is not None:
        write(workdir / "bad.toml", text)
    assert run(command, "bad.toml") == 2
    out, err = capsys.readouterr()
    assert err.startswith("fretting: error: ") and words in err
    assert err.count("\n") == 1 and "Traceback" not in err and out == ""
    assert [path.name for path in workdir.iterdir()] == ([] if text is None else ["bad.toml"])


def test_gross_slip_exit_3_leaves_the_old_result(workdir, capsys):
    write(workdir / "slide.toml", CONTACT + '[[loading]]\nkind = "linear"\nQ = [30e3, -80e3]\nsteps_per_segment = 10\n')
    (workdir / "slide.h5").write_bytes(b"an earlier result")
    assert run("validate", "slide.toml") == 3
    assert "gross slip at step 20: Q = -80000" in capsys.readouterr().err
    assert run("run", "slide.toml", "--nodes", NODES) == 3
    err = capsys.readouterr().err
    assert err.startswith("fretting: error: slide.toml: gross slip at step 20") and err.count("\n") == 1
    assert (workdir / "slide.h5").read_bytes() == b"an earlier result"
    assert sorted(path.name for path in workdir.iterdir()) == ["slide.h5", "slide.toml"]


def test_gross_slip_in_a_later_chunk_names_the_whole_history_step(workdir, capsys, monkeypatch):
    monkeypatch.setattr(runner, "CHUNK_STEPS", 4)
    write(workdir / "slide.toml", CONTACT + '[[loading]]\nkind = "linear"\nQ = [30e3, -80e3]\nsteps_per_segment = 10\n')
    assert run("run", "slide.toml", "--nodes", NODES, "--checkpoint-interval", "0") == 3
    assert "gross slip at step 20: Q = -80000" in capsys.readouterr().err
    assert not (workdir / "slide.h5.checkpoint").exists()


def test_debug_shows_the_exception(workdir):
    write(workdir / "bad.toml", CONTACT)
    with pytest.raises(fr.HistoryError, match="no \\[\\[loading\\]\\] blocks"):
        run("validate", "bad.toml", "--debug")


@pytest.mark.parametrize("nodes", ["3", "many"])
def test_bad_arguments(workdir, capsys, nodes):
    with pytest.raises(SystemExit) as exit_:
        run("run", "x.toml", "--nodes", nodes)
    assert exit_.value.code == 2 and "--nodes" in capsys.readouterr().err


def test_bad_result_file(workdir, capsys):
    write(workdir / "notes.h5", "not a result")
    assert run("info", "notes.h5") == 2
    assert capsys.readouterr().err.startswith("fretting: error: notes.h5: ")


@pytest.mark.slow
@pytest.mark.parametrize("model", [("--nodes", NODES), ("--rtol", "1e-3"), ()])
def test_interrupted_run_keeps_its_progress_and_resumes(workdir, capsys, monkeypatch, model):
    """Ctrl-C in the third chunk: a checkpoint of two chunks; --resume then equals an uninterrupted run
    (on the grid, on the mesh adapted once to the whole history, and with the default model)."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 20)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)  # chunks of 20 steps each
    write(workdir / "shear.toml", CONTACT + SHEAR)
    assert run("run", "shear.toml", "-o", "whole.h5", *model) == 0
    capsys.readouterr()  # the whole run's notes (the grid's: fretting.results.notes)
    monkeypatch.setattr(runner, "Stepper", _interrupt_after(2))
    assert run("run", "shear.toml", "-o", "part.h5", *model, "--checkpoint-interval", "1e6") == 130
    err = capsys.readouterr().err
    assert err == "fretting: error: interrupted: progress kept in part.h5.checkpoint; continue with --resume\n"
    assert (
        runner.checkpointed(workdir / "part.h5.checkpoint").sizes["step"] == 41 and not (workdir / "part.h5").exists()
    )

    assert run("run", "shear.toml", "-o", "part.h5", *model) == 2  # not without --resume
    assert "--resume" in capsys.readouterr().err
    assert run("run", "shear.toml", "-o", "part.h5", *model, "--resume") == 0
    xr.testing.assert_identical(data_of(load(workdir / "part.h5")), data_of(load(workdir / "whole.h5")))
    assert not (workdir / "part.h5.checkpoint").exists()


def test_an_interrupt_while_joining_the_parts_says_to_resume(workdir, capsys, monkeypatch):
    """Ctrl-C after the last chunk, while the parts are joined into the result (issue 38: the hint to
    resume was given only inside the loop over the chunks): the parts stay, the message says
    --resume, and the resumed run writes the result an uninterrupted run writes."""
    write(workdir / "shear.toml", CONTACT + SHEAR)
    assert run("run", "shear.toml", "-o", "whole.h5", "--nodes", NODES) == 0
    joined = runner.save_joined

    def interrupted(*arguments, **options):
        raise KeyboardInterrupt

    monkeypatch.setattr(runner, "save_joined", interrupted)
    capsys.readouterr()
    assert run("run", "shear.toml", "-o", "part.h5", "--nodes", NODES) == 130
    assert capsys.readouterr().err == (
        "fretting: error: interrupted: progress kept in part.h5.checkpoint; continue with --resume\n"
    )
    monkeypatch.setattr(runner, "save_joined", joined)
    assert run("run", "shear.toml", "-o", "part.h5", "--nodes", NODES, "--resume") == 0
    xr.testing.assert_identical(data_of(load(workdir / "part.h5")), data_of(load(workdir / "whole.h5")))


@pytest.mark.slow
def test_resume_refuses_another_history_or_grid(workdir, capsys, monkeypatch):
    monkeypatch.setattr(runner, "CHUNK_STEPS", 20)
    history = write(workdir / "shear.toml", CONTACT + SHEAR)
    monkeypatch.setattr(runner, "Stepper", _interrupt_after(2))
    assert run("run", "shear.toml", "--nodes", NODES, "--checkpoint-interval", "0") == 130
    monkeypatch.setattr(runner, "Stepper", fr.Stepper)
    assert run("run", "shear.toml", "--nodes", "40", "--resume") == 2
    assert "found a run with model = grid, nodes = 32, expected model = grid, nodes = 40" in capsys.readouterr().err
    assert run("run", "shear.toml", "--rtol", "1e-4", "--resume") == 2
    assert "found a run with model = grid, nodes = 32, expected model = mesh, rtol = 0.0001" in capsys.readouterr().err
    assert run("run", "shear.toml", "--resume") == 2  # the default runs rtol 1e-4 or 384 nodes
    assert "found a run with model = grid, nodes = 32, expected the default model" in capsys.readouterr().err
    write(history, history.read_text() + "# edited\n")
    assert run("run", "shear.toml", "--nodes", NODES, "--resume") == 2
    assert "found a run of another version of shear.toml" in capsys.readouterr().err


@pytest.mark.slow
def test_long_runs_record_their_ends_and_every_cycle_and_resume(workdir, capsys, monkeypatch):
    """Past the recording threshold only the first and last steps keep their fields; energy and
    slip range per cycle cover every cycle; an interrupted run resumes to the same result."""
    engine = importlib.import_module("fretting.engine.recorder")
    monkeypatch.setattr(engine, "RECORD_ALL_STEPS", 100)
    monkeypatch.setattr(engine, "RECORDED_ENDS", 30)
    monkeypatch.setattr(runner, "CHUNK_STEPS", 20)
    text = CONTACT + SHEAR.replace("count = 3", "count = 40")
    write(workdir / "long.toml", text)
    assert run("run", "long.toml", "-o", "every.h5", "--nodes", NODES, "--every-step") == 0
    assert "are skipped" not in capsys.readouterr().err
    every = load(workdir / "every.h5")
    contact, history = read_history(workdir / "long.toml")
    direct = fr.simulate(contact, history, nodes=int(NODES))
    direct = data_of(direct)
    xr.testing.assert_identical(data_of(every)[list(direct.variables)].drop_attrs(), direct.drop_attrs())
    assert every.attrs["cycle_peaks"] == "every step"
    steps = len(history)
    # by default the unrecorded steps inside straight stretches are skipped: the same energy, w,
    # slip range and q_peak, to rounding (float32 rows: bit for bit here); no sigma_xx peaks
    assert run("run", "long.toml", "-o", "whole.h5", "--nodes", NODES) == 0
    assert "fretting: note: the unrecorded steps inside straight stretches are skipped" in capsys.readouterr().err
    whole = load(workdir / "whole.h5")
    assert "not tallied" in whole.attrs["cycle_peaks"] and "sigma_xx_peak" not in whole
    for name in ("w", "slip_amplitude", "q_peak"):
        np.testing.assert_array_equal(whole[name].values, every[name].values, err_msg=name)
    np.testing.assert_allclose(whole.cycle_dissipation.values, every.cycle_dissipation.values, rtol=1e-13, atol=0)
    assert not np.array_equal(whole.cycle_dissipation.values, every.cycle_dissipation.values)  # not solved alike
    np.testing.assert_array_equal(whole.step.values, [*range(30), *range(steps - 30, steps)])
    assert whole.sizes["cycle_number"] == 40 and np.all(whole.cycle_dissipation.values > 0)
    assert whole.w.dims == ("cycle_number", "x")

    monkeypatch.setattr(runner, "Stepper", _interrupt_after(3))
    assert run("run", "long.toml", "-o", "resumed.h5", "--nodes", NODES, "--checkpoint-interval", "0") == 130
    monkeypatch.setattr(runner, "Stepper", fr.Stepper)
    assert run("run", "long.toml", "-o", "resumed.h5", "--nodes", NODES, "--resume") == 0
    xr.testing.assert_identical(data_of(load(workdir / "resumed.h5")), data_of(whole))
    assert run("run", "long.toml", "-o", "all.h5", "--nodes", NODES, "--record", "all") == 0
    assert load(workdir / "all.h5").sizes["step"] == steps


def _interrupt_after(chunks):
    """A Stepper class whose runs raise KeyboardInterrupt once, after `chunks` of them (a chunk each)."""
    made = []

    class Interrupted(fr.Stepper):
        def run(self, *arguments, **options):
            made.append(1)
            if len(made) == chunks + 1:
                raise KeyboardInterrupt
            return super().run(*arguments, **options)

    return Interrupted


@pytest.mark.slow
def test_resume_after_a_killed_process_equals_an_uninterrupted_run(workdir):
    """SIGKILL a real `python -m fretting run` once its first checkpoint exists, then --resume it."""
    text = CONTACT + '[[loading]]\nkind = "sine"\nQ_amplitude = 35e3\nsigma_amplitude = 1e8\nphase_deg = 90\n'
    write(workdir / "long.toml", text + "cycles = 100\nsteps_per_cycle = 40\n")
    command = [sys.executable, "-m", "fretting", "run", "long.toml", "-o", "killed.h5", "--nodes", NODES]
    process = subprocess.Popen([*command, "--checkpoint-interval", "0"], stderr=subprocess.PIPE)
    checkpoint = workdir / "killed.h5.checkpoint"
    deadline = time.monotonic() + 60
    while not list(checkpoint.glob("*.h5")) and process.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    process.send_signal(signal.SIGKILL)
    _, err = process.communicate()
    assert process.returncode == -signal.SIGKILL, err.decode()
    done = runner.checkpointed(checkpoint).attrs["steps"]
    assert 1 < done < 4017 and not (workdir / "killed.h5").exists()

    assert run("run", "long.toml", "-o", "killed.h5", "--nodes", NODES, "--resume") == 0
    assert run("run", "long.toml", "-o", "whole.h5", "--nodes", NODES) == 0
    resumed, whole = load(workdir / "killed.h5"), load(workdir / "whole.h5")
    xr.testing.assert_identical(data_of(resumed), data_of(whole))
    assert resumed.sizes["step"] == 4017 and np.all(resumed.cycle_dissipation.values > 0)


@pytest.fixture
def not_stepped(monkeypatch):
    """Make any stepping fail the test: what is checked before a run must be checked before its first step."""

    class Unreachable:
        def __init__(self, *arguments, **options):
            raise AssertionError("a run stepped before checking its output")

    monkeypatch.setattr(runner, "Stepper", Unreachable)


def read_only_folder(workdir):
    """A folder this process cannot write in: modes 555, or /sys for root, whom modes do not stop."""
    if os.geteuid() == 0:
        return "/sys"
    folder = workdir / "locked"
    folder.mkdir()
    folder.chmod(0o555)
    return folder


@pytest.mark.parametrize(
    ("output", "why"),
    [
        (lambda workdir: (workdir / "out").mkdir() or "out", "it is a folder"),
        (lambda workdir: write(workdir / "notes.txt", "") and "notes.txt/out.h5", "notes.txt is a file, not a folder"),
        (lambda workdir: f"{read_only_folder(workdir)}/out.h5", "Permission denied"),
    ],
    ids=["a-folder", "under-a-file", "read-only-folder"],
)
def test_an_output_that_cannot_be_written_is_refused_before_the_run(workdir, capsys, not_stepped, output, why):
    write(workdir / "shear.toml", CONTACT + SHEAR)
    path = output(workdir)
    assert run("run", "shear.toml", "-o", path, "--nodes", NODES) == 2
    out, err = capsys.readouterr()
    assert err.startswith(f"fretting: error: {path}: ") and why in err and err.count("\n") == 1 and out == ""
    assert ".tmp" not in err and "HDF5" not in err and "h5py" not in err


#: A process that holds the lock of the output named by its argument until its stdin closes.
HOLD = """
import sys
from fretting.engine.runner import holding
with holding(sys.argv[1]):
    print(1, flush=True)
    sys.stdin.read()
"""


@pytest.mark.slow
def test_a_second_run_of_the_same_output_is_refused_while_the_first_holds_it(workdir, capsys):
    """Another process holds the output's lock: the run is refused at once, its checkpoint and the
    holder's temporaries untouched; once the holder is killed the lock is free again."""
    write(workdir / "shear.toml", CONTACT + SHEAR)
    temporary = write(workdir / ".shear.h5.0123456789ab.tmp", "the other run's file in the writing")
    holder = subprocess.Popen([sys.executable, "-c", HOLD, "shear.h5"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
    try:
        assert holder.stdout.readline() == b"1\n"
        assert run("run", "shear.toml", "--nodes", NODES) == 2
        out, err = capsys.readouterr()
        assert err == (
            "fretting: error: shear.h5: another run is writing it (it holds .shear.h5.lock): "
            "wait for it to end, or write elsewhere\n"
        )
        assert temporary.exists() and not (workdir / "shear.h5").exists()
    finally:
        holder.kill()  # SIGKILL: the system releases its lock; its lock file stays
        holder.communicate()
    assert (workdir / ".shear.h5.lock").exists()
    assert run("run", "shear.toml", "--nodes", NODES) == 0
    assert sorted(path.name for path in workdir.iterdir()) == ["shear.h5", "shear.toml"]


@pytest.mark.slow
def test_a_run_removes_the_temporaries_of_a_killed_run_of_its_output(workdir, capsys, monkeypatch):
    """A SIGKILL while a checkpoint or the result was being saved leaves their temporary files;
    the next run of that output (resumed or not) deletes them, and no file of another output."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 20)
    write(workdir / "shear.toml", CONTACT + SHEAR)
    monkeypatch.setattr(runner, "Stepper", _interrupt_after(2))
    assert run("run", "shear.toml", "--nodes", NODES, "--checkpoint-interval", "0") == 130
    monkeypatch.setattr(runner, "Stepper", fr.Stepper)
    stale = [".shear.h5.checkpoint.0123456789ab.tmp", ".shear.h5.a1b2c3d4e5f6.tmp"]
    others = [".shear.h5.bak.0123456789ab.tmp", ".shear.h5.notes.tmp", ".other.h5.0123456789ab.tmp"]
    for name in stale + others:
        write(workdir / name, "half a file")
    assert run("run", "shear.toml", "--nodes", NODES, "--resume") == 0
    assert sorted(path.name for path in workdir.iterdir()) == sorted(["shear.h5", "shear.toml", *others])


def test_resume_without_a_checkpoint_says_so(workdir, capsys):
    write(workdir / "shear.toml", CONTACT + SHEAR)
    assert run("run", "shear.toml", "--nodes", NODES, "--resume") == 0
    out, err = capsys.readouterr()
    assert err == (
        "fretting: note: shear.h5.checkpoint: no checkpoint to resume from: the run starts at step 0\n"
        f"fretting: note: {load(workdir / 'shear.h5').attrs[UNRESOLVED]}\n"
    )
    assert out.startswith("shear.h5: 82 steps")


def test_resume_refuses_a_run_that_solved_its_steps_otherwise(workdir, capsys, monkeypatch):
    """A checkpoint of a run that skipped steps is not continued solving every step (nor the
    converse): the whole run would do neither. A checkpoint file of fretting 0.1 is refused."""
    engine = importlib.import_module("fretting.engine.recorder")
    monkeypatch.setattr(engine, "RECORD_ALL_STEPS", 10)
    monkeypatch.setattr(engine, "RECORDED_ENDS", 5)
    monkeypatch.setattr(runner, "CHUNK_STEPS", 20)
    write(workdir / "shear.toml", CONTACT + SHEAR)
    monkeypatch.setattr(runner, "Stepper", _interrupt_after(2))
    assert run("run", "shear.toml", "--nodes", NODES, "--checkpoint-interval", "0") == 130
    monkeypatch.setattr(runner, "Stepper", fr.Stepper)
    capsys.readouterr()
    assert run("run", "shear.toml", "--nodes", NODES, "--resume", "--every-step") == 2
    assert capsys.readouterr().err.endswith(
        "found a run with steps skipped (without --every-step), expected every step solved (--every-step)\n"
    )
    shutil.rmtree(workdir / "shear.h5.checkpoint")
    write(workdir / "shear.h5.checkpoint", "a result written by fretting 0.1")
    assert run("run", "shear.toml", "--nodes", NODES) == 2
    assert "found the checkpoint file of an earlier version of fretting: delete it" in capsys.readouterr().err


def test_output_closed_by_its_reader_ends_quietly():
    """``fretting examples | head -1``: when the reader has gone, the command stops with the shell's
    SIGPIPE code and no error line (not "Broken pipe" as a bad input)."""
    read, write = os.pipe()
    os.close(read)
    try:
        done = subprocess.run(
            [sys.executable, "-m", "fretting", "examples"], stdout=write, stderr=subprocess.PIPE, text=True, timeout=60
        )
    finally:
        os.close(write)
    assert (done.returncode, done.stderr) == (cli.EXIT_PIPE, "")
