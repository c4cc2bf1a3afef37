"""Cycles a discretised model cannot resolve (slip zones nearer the edges than its outermost nodes) are said."""

import numpy as np
from conftest import HERTZ_TOML

import fretting as fr
from fretting import cli
from fretting.engine.notes import UNRESOLVED, varied_cycles
from fretting.results.io import load

CONTACT = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.7, 1e5)
TINY = 1e-6 * CONTACT.f * CONTACT.P  # slip zones of a - c ~ 2.5e-7 a (Mindlin-Deresiewicz); Grid(96): 1.3e-4 a


def test_a_coarse_grid_says_that_tiny_cycles_dissipate_nothing_on_its_nodes():
    """Grid(96) dissipates exactly nothing in cycles of 1e-6 f P, which the exact model resolves (a positive
    energy): the result says so in ``model_unresolved``; the exact model's result has no such note, nor the
    grid's on a sharp flat punch, whose pressure is unbounded at its edges and which sticks until it slides."""
    history = fr.History.sinusoidal(TINY, cycles=3, steps_per_cycle=16)
    grid = fr.simulate(CONTACT, history, fr.models.Grid(96))
    exact = fr.simulate(CONTACT, history)
    assert np.all(grid.cycle_dissipation.values == 0) and np.all(exact.cycle_dissipation.values > 0)
    assert grid.attrs[UNRESOLVED].startswith("3 load cycles (cycle 1 to 3) dissipated exactly nothing")
    assert "grid model's 96 nodes" in grid.attrs[UNRESOLVED] and UNRESOLVED not in exact.attrs
    punch = fr.Contact(fr.FlatPunch(1e-3), CONTACT.E_star, CONTACT.f, CONTACT.P)
    flat = fr.simulate(punch, history, fr.models.Grid(96))
    assert np.all(flat.cycle_dissipation.values == 0) and UNRESOLVED not in flat.attrs


def test_only_cycles_whose_loads_move_count():
    """A hold between two cycles is a cycle whose loads do not move: it dissipates nothing, rightly."""
    Q = np.array([0.0, TINY, TINY, TINY, 0.0])
    history = fr.History(Q, np.zeros(5), np.arange(5), np.array([0, 1, 2, 2, 3], dtype=np.int32))
    assert varied_cycles(history).tolist() == [True, False, True]


def test_the_command_line_says_the_note_and_the_file_records_it(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "tiny.toml").write_text(
        HERTZ_TOML + f'\n[[loading]]\nkind = "sine"\nQ_amplitude = {TINY!r}\ncycles = 3\nsteps_per_cycle = 16\n'
    )
    assert cli.main(["run", "tiny.toml", "--nodes", "96"]) == 0
    err = capsys.readouterr().err
    assert "fretting: note: 3 load cycles (cycle 1 to 3) dissipated exactly nothing" in err
    assert load(tmp_path / "tiny.h5").attrs[UNRESOLVED] in err
