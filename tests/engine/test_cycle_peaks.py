"""Per-cycle peaks over every step of each cycle: the engine's tallies of the specimen's surface
stress and of |q| (issue 19 item 3), against the recorded fields, with few steps recorded, in
chunks and on the shipped out-of-phase example."""

import numpy as np
import pytest

import fretting as fr
from fretting.analysis import nucleation as nu
from fretting.engine import runner
from fretting.loading.examples import EXAMPLES
from fretting.loading.history_file import read_history_source
from fretting.results.variables import CYCLE_PEAKS

NODES = 64
#: Float32 rows: relative rounding 6e-8 of the largest magnitude of the row.
FLOAT32 = 1e-7

OUT_OF_PHASE = """
[contact]
profile = "hertz"
R = 0.05
E_star = 115.38e9
f = 0.7
P = 1e5

[[loading]]
kind = "sine"
Q_amplitude = 35e3
sigma_amplitude = 100e6
phase_deg = 90
cycles = 6
steps_per_cycle = 24
"""


@pytest.fixture(scope="module")
def source(tmp_path_factory):
    path = tmp_path_factory.mktemp("peaks") / "out_of_phase.toml"
    path.write_text(OUT_OF_PHASE)
    return read_history_source(path)


@pytest.fixture(scope="module")
def everything(source):
    """Q and sigma 90 degrees out of phase, every step recorded; its later cycles are copied."""
    return fr.simulate(source.contact, source.history, nodes=NODES, record="all")


def step_by_step(result):
    """Per cycle and node, the largest specimen sigma_xx [Pa], |q| [Pa] and their product over the
    cycle's steps, from `surface_stress` of the recorded fields of a result recorded at every step."""
    assert np.array_equal(result.step.values, np.arange(result.sizes["step"]))
    stress, shear = nu.surface_stress(result).values, np.abs(result.q.values)
    cycle = result.cycle.values
    rows = [cycle == number for number in result.cycle_number.values]
    return {
        "sigma_xx_peak": np.array([stress[r].max(axis=0) for r in rows]),
        "q_peak": np.array([shear[r].max(axis=0) for r in rows]),
        "sigma_xx_q_peak": np.array([(stress[r] * shear[r]).max(axis=0) for r in rows]),
    }


def test_tallies_are_the_maxima_over_every_step(everything):
    assert everything.cycle_copied.values.any()  # copied cycles get the rows of the cycle they repeat
    reference = step_by_step(everything)
    for name in CYCLE_PEAKS:
        expected = reference[name]
        atol = FLOAT32 * np.abs(expected).max()
        np.testing.assert_allclose(everything[name].values, expected, rtol=0, atol=atol, err_msg=name)
    summary = nu.per_cycle(everything)
    np.testing.assert_allclose(summary.sigma_xx_max.values, reference["sigma_xx_peak"].max(axis=1), rtol=FLOAT32)
    delta = nu.slip_amplitude(everything).values
    np.testing.assert_allclose(summary.F1.values, (reference["q_peak"] * delta).max(axis=1), rtol=FLOAT32)
    np.testing.assert_allclose(summary.F2.values, (reference["sigma_xx_q_peak"] * delta).max(axis=1), rtol=FLOAT32)


def test_results_without_tallies_take_every_recorded_step(everything):
    reference = step_by_step(everything)
    untallied = nu.per_cycle(everything.drop_vars(list(CYCLE_PEAKS)))
    np.testing.assert_allclose(untallied.sigma_xx_max.values, reference["sigma_xx_peak"].max(axis=1), rtol=1e-12)
    delta = nu.slip_amplitude(everything).values
    np.testing.assert_allclose(untallied.F2.values, (reference["sigma_xx_q_peak"] * delta).max(axis=1), rtol=1e-12)
    pad = nu.per_cycle(everything, body=1)  # not tallied: the pad's stress from the recorded steps
    stress = nu.surface_stress(everything, body=1).values
    expected = [stress[everything.cycle.values == n].max() for n in everything.cycle_number.values]
    np.testing.assert_allclose(pad.sigma_xx_max.values, expected, rtol=1e-12)


def test_tallies_do_not_depend_on_the_recorded_steps(source, everything):
    few = fr.simulate(source.contact, source.history, nodes=NODES, record=[0, 7, 50])  # no cycle whole
    for name in CYCLE_PEAKS:
        np.testing.assert_array_equal(few[name].values, everything[name].values, err_msg=name)
    for name in ("sigma_xx_max", "x_sigma_xx_max", "F1", "F2", "x_F1", "x_F2"):
        np.testing.assert_array_equal(nu.per_cycle(few)[name].values, nu.per_cycle(everything)[name].values)


@pytest.mark.slow
def test_a_run_in_chunks_tallies_each_cycle_whole(source, everything, tmp_path, monkeypatch):
    """The runner cuts the run at steps 5, 15, 35, 75, 155 (chunks of 5 steps, doubling while fast), inside cycles."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 5)
    run = runner.run_file(source.path, tmp_path / "out.h5", fr.models.Grid(NODES), checkpoint_interval=0)
    for name in CYCLE_PEAKS:
        np.testing.assert_array_equal(run.result[name].values, everything[name].values, err_msg=name)


def test_a_state_read_from_a_result_without_tallies_leaves_that_cycle_unknown(source, everything):
    """A result written before the tallies existed: the cycle in progress at its end has no known
    peaks (NaN); the later cycles are tallied whole."""
    cut = int(np.argmax(source.history.cycle == 2)) + 5  # inside cycle 2
    head = fr.simulate(source.contact, source.history[: cut + 1], nodes=NODES)
    old = head.drop_vars([f"state_{name}" for name in CYCLE_PEAKS])
    tail = fr.simulate(source.contact, source.history[cut:], nodes=NODES, state=fr.final_state(old))
    assert np.isnan(tail.sigma_xx_peak.values[0]).all() and tail.cycle_number.values[0] == 2
    np.testing.assert_array_equal(tail.sigma_xx_peak.values[1:], everything.sigma_xx_peak.values[2:])


def load_extreme_peak(result, number):
    """The former `per_cycle` value: the largest specimen sigma_xx at the steps of cycle `number` where Q or sigma
    is largest or least."""
    rows = np.flatnonzero(result.cycle.values == number)
    extremes = [rows[f(load[rows])] for load in (result.Q.values, result.sigma.values) for f in (np.argmax, np.argmin)]
    return nu.surface_stress(result).values[extremes].max()


@pytest.mark.slow
def test_the_shipped_out_of_phase_example_peaks_between_the_load_extremes():
    """Issue 19: in cycle 8 of hertz_out_of_phase the specimen's sigma_xx peaks (at x = a) at a step
    between the load extremes, more than 10 % above the largest value at the load extremes."""
    shipped = read_history_source(EXAMPLES / "hertz_out_of_phase.toml")
    result = fr.simulate(shipped.contact, shipped.history)
    peak = nu.per_cycle(result).sigma_xx_max.values[-1]
    stress = nu.surface_stress(result).values[result.cycle.values == 8]
    assert peak == pytest.approx(stress.max(), rel=FLOAT32)
    assert load_extreme_peak(result, 8) < peak / 1.1
