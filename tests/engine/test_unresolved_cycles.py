"""Cycles a discretised model cannot resolve (slip zones nearer the edges than its outermost nodes, or
holding too few of its nodes for the energy's 1e-4) are said."""

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting import cli
from fretting.results.io import load
from fretting.results.notes import SLIP_NODES, UNRESOLVED, edge_slip_nodes, observed_slip_nodes

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
    """A hold between two cycles is a cycle whose loads do not move: it dissipates nothing, rightly. A cycle
    of ``sigma`` alone moves the two edges' loads ``Q -+ pi a sigma / 4`` (eqs 9 and 20 at ``x = -+a``). Each
    cycle's ``cycle_load_range`` spans the loads of its increments, the one it starts from included."""
    Q = np.array([0.0, TINY, TINY, TINY, 0.0])
    history = fr.History(Q, np.zeros(5), np.arange(5), np.array([0, 1, 2, 2, 3], dtype=np.int32))
    result = fr.simulate(CONTACT, history, fr.models.Grid(96))
    assert result.cycle_load_range.values.tolist() == [[TINY, TINY, 0.0], [0.0, 0.0, 0.0], [TINY, TINY, 0.0]]
    assert result.attrs[UNRESOLVED].startswith("2 load cycles (cycle 1 to 3) dissipated exactly nothing")
    sigma = fr.History(np.zeros(3), np.array([0.0, 4e3, -4e3]), np.arange(3), np.array([0, 1, 1], dtype=np.int32))
    ranges = fr.simulate(CONTACT, sigma, fr.models.Grid(96)).cycle_load_range.values
    np.testing.assert_allclose(ranges, [[8e3 * np.pi * CONTACT.a / 4, 8e3 * np.pi * CONTACT.a / 4, 0.0]], rtol=1e-15)


def test_a_joined_result_notes_the_cycles_of_every_part():
    """The note of a result joined from parts is the whole run's: a first part of a ramp alone has no note,
    the join of it and of tiny cycles after, cut inside a cycle, has the whole run's, from the cycles'
    ranges the state carries from part to part."""
    ramp = fr.History.piecewise_linear([0.0, 0.3 * CONTACT.f * CONTACT.P, 0.0], None, 8)
    history = fr.History.concatenate([ramp, fr.History.sinusoidal(TINY, cycles=3, steps_per_cycle=16)])
    grid = fr.models.Grid(96)
    whole = fr.simulate(CONTACT, history, grid)
    assert whole.attrs[UNRESOLVED].startswith("2 load cycles (cycle 2 to 3) dissipated exactly nothing")
    parts = [fr.simulate(CONTACT, history[:17], grid)]
    for start, stop in [(16, 40), (40, len(history) - 1)]:  # cut inside cycles 2 and 3
        parts.append(fr.simulate(CONTACT, history[start : stop + 1], grid, state=fr.final_state(parts[-1])))
    assert UNRESOLVED not in parts[0].attrs and parts[1].cycle_number.values.tolist() == [1, 2]
    joined = fr.join_results(parts)
    assert joined.attrs[UNRESOLVED] == whole.attrs[UNRESOLVED]
    np.testing.assert_array_equal(joined.cycle_load_range.values, whole.cycle_load_range.values)


def energy_error(model, amplitude):
    """The result of cycles of ``Q = amplitude f P sin`` on `model`, and its second cycle's energy relative
    to the exact model's, less one."""
    history = fr.History.sinusoidal(amplitude * CONTACT.f * CONTACT.P, cycles=2, steps_per_cycle=32)
    result = fr.simulate(CONTACT, history, model)
    exact = fr.simulate(CONTACT, history, fr.models.Exact()).cycle_dissipation.values[-1]
    return result, result.cycle_dissipation.values[-1] / exact - 1


@pytest.mark.parametrize(
    ("model", "amplitude", "said"),
    [
        (fr.models.Grid(384), 1e-2, True),  # 12 nodes in the slip zone: 6.2e-3
        (fr.models.Grid(384), 0.4, True),  # 84: 2.6e-4
        (fr.models.Grid(1536), 2e-2, True),  # 69: 1.2e-4
        (fr.models.Mesh(theta=np.linspace(0, np.pi, 800)), 0.1, True),  # 82: 1.4e-4
        (fr.models.Mesh(theta=np.linspace(0, np.pi, 800)), 0.2, False),  # 118: 6.9e-5
        (fr.models.Grid(1536), 5e-2, False),  # 110: 7.7e-5
        (fr.models.Mesh(), 1e-4, False),  # adapted to the energy, not counted: 1.7e-5
    ],
)
def test_cycles_of_too_few_nodes_in_their_slip_zones_are_said_and_the_others_within_1e_4(model, amplitude, said):
    """Either side of `SLIP_NODES` (benchmarks/unresolved_cycles.py): a cycle whose energy errs by more than
    the README's 1e-4 against the exact model is named in ``model_unresolved``; one that is not named is
    within 1e-4. Near the threshold on both sides, on a grid and on a given mesh."""
    result, error = energy_error(model, amplitude)
    note = result.attrs.get(UNRESOLVED, "")
    named = "(cycle 1 to 2) slipped over fewer than" in note
    ranges = np.array([[2.0, 2.0, 0.0]]) * amplitude * CONTACT.f * CONTACT.P
    estimated = edge_slip_nodes(result.attrs, result.x.values, result.p.values, ranges)[0]
    recorded = observed_slip_nodes(result.stick.values, result.cycle.values, np.array([2]))[0]
    # on Hertz under Q alone, the small-range estimate is a little short of Mindlin-Deresiewicz's zone
    assert estimated - 2 <= recorded <= 1.1 * estimated + 2
    assert named == said == ("rtol" not in result.attrs and max(estimated, recorded) < SLIP_NODES)
    assert named or abs(error) < 1e-4


@pytest.mark.parametrize(
    ("amplitude", "said"),
    [
        (TINY, "3 load cycles (cycle 1 to 3) dissipated exactly nothing"),
        (
            1e-2 * CONTACT.f * CONTACT.P,
            "3 load cycles (cycle 1 to 3) slipped over fewer than 100 of the grid model's 96",
        ),
    ],
)
def test_the_command_line_says_the_note_and_the_file_records_it(tmp_path, monkeypatch, capsys, amplitude, said):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "tiny.toml").write_text(
        HERTZ_TOML + f'\n[[loading]]\nkind = "sine"\nQ_amplitude = {amplitude!r}\ncycles = 3\nsteps_per_cycle = 16\n'
    )
    assert cli.main(["run", "tiny.toml", "--nodes", "96"]) == 0
    err = capsys.readouterr().err
    assert f"fretting: note: {said}" in err
    assert load(tmp_path / "tiny.h5").attrs[UNRESOLVED] in err


def test_the_recorded_slip_zone_of_a_cycle_is_its_longest_run_from_an_edge():
    """Per cycle, the most nodes slipping in a row from either edge at its recorded steps; 0 where none is
    recorded (a run recording no step)."""
    stick = np.array([[0, 0, 1, 1, 0], [1, 1, 1, 0, 0], [0, 1, 1, 1, 1]], dtype=bool)
    assert observed_slip_nodes(stick, np.array([1, 1, 2]), np.array([1, 2, 3])).tolist() == [2, 1, 0]
    assert observed_slip_nodes(np.zeros((0, 5), dtype=bool), np.zeros(0, int), np.array([1, 2])).tolist() == [0, 0]
