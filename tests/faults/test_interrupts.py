"""Ctrl-C that Python drops (issue 38): a KeyboardInterrupt raised inside a weakref callback or a
``__del__`` is reported as "Exception ignored" and lost, and the run went on to exit 0. The command
line remembers it and stops at the next chunk, in one line, with its progress kept."""

import signal
import weakref

import pytest
import xarray as xr
from conftest import HERTZ_TOML as CONTACT
from test_cli import SHEAR as CLI_SHEAR
from test_cli import data_of, run

import fretting as fr
from fretting.engine import runner
from fretting.results.io import load
from fretting.results.notes import UNRESOLVED

SHEAR = CONTACT + CLI_SHEAR


def dropped_interrupt():
    """Ctrl-C arriving while a weakref callback runs, as SIGINT's handler raises it there: Python
    reports the KeyboardInterrupt as unraisable and drops it."""

    class Held:
        pass

    held = Held()
    reference = weakref.ref(held, lambda _: signal.getsignal(signal.SIGINT)(signal.SIGINT, None))
    del held
    assert reference() is None


@pytest.mark.slow
def test_an_interrupt_dropped_in_a_weakref_callback_stops_the_run_at_the_next_chunk(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shear.toml").write_text(SHEAR)
    assert run("run", "shear.toml", "-o", "whole.h5", "--nodes", "32") == 0
    monkeypatch.setattr(runner, "CHUNK_STEPS", 20)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)  # chunks of 20 steps

    class Dropping(fr.Stepper):
        def run(self, *arguments, **options):
            state = super().run(*arguments, **options)
            dropped_interrupt()
            return state

    monkeypatch.setattr(runner, "Stepper", Dropping)
    capsys.readouterr()
    assert run("run", "shear.toml", "-o", "out.h5", "--nodes", "32", "--checkpoint-interval", "1e6") == 130
    assert capsys.readouterr().err == (
        "fretting: error: interrupted: progress kept in out.h5.checkpoint; continue with --resume\n"
    )
    assert runner.checkpointed(tmp_path / "out.h5.checkpoint").sizes["step"] == 21  # the first chunk, whole
    monkeypatch.setattr(runner, "Stepper", fr.Stepper)
    assert run("run", "shear.toml", "-o", "out.h5", "--nodes", "32", "--resume") == 0
    xr.testing.assert_identical(data_of(load(tmp_path / "out.h5")), data_of(load(tmp_path / "whole.h5")))


def test_an_interrupt_dropped_after_the_last_chunk_is_said_and_exits_130(tmp_path, capsys, monkeypatch):
    """Dropped while the result is written: the result stands (written whole), and the exit says the
    run was interrupted rather than 0."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shear.toml").write_text(SHEAR)
    joined = runner.save_joined

    def dropping(*arguments, **options):
        joined(*arguments, **options)
        dropped_interrupt()

    monkeypatch.setattr(runner, "save_joined", dropping)
    assert run("run", "shear.toml", "-o", "out.h5", "--nodes", "32") == 130
    out, err = capsys.readouterr()
    note = f"fretting: note: {load(tmp_path / 'out.h5').attrs[UNRESOLVED]}\n"  # the 32 nodes' (results.notes)
    assert err == note + "fretting: error: interrupted\n" and "Exception ignored" not in out + err
    assert load(tmp_path / "out.h5").attrs["steps"] == 83


def test_the_command_line_gives_back_the_interrupt_handler_it_found(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before = signal.getsignal(signal.SIGINT)
    assert run("validate", "nothing.toml") == 2
    assert signal.getsignal(signal.SIGINT) is before
