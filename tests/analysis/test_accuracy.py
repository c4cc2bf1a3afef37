"""fretting.analysis.accuracy: the error metrics and the references a run is scored against."""

import math

import harness
import numpy as np
import pytest

import fretting as fr
from fretting.analysis import accuracy
from fretting.physics import closed_forms as cf

# -- Error metrics -----------------------------------------------------------------------------


def test_zone_distance():
    zones = [[-0.5, 0.2], [0.4, 0.6]]
    assert accuracy.zone_distance(zones, [[0.41, 0.6], [-0.5, 0.17]]) == pytest.approx(0.03)
    assert accuracy.zone_distance([[-0.5, 0.2]], zones) == pytest.approx(0.1)  # [0.4, 0.6] closes up
    assert accuracy.zone_distance([[-0.5, 0.6]], zones) == pytest.approx(0.1)  # the slip zone (0.2, 0.4) closes up
    assert accuracy.zone_distance([[-0.5, 0.25]], zones) == pytest.approx(0.1)
    nucleated = [[-0.405, 0.547], [0.549, 0.918]]  # a slip zone one node wide appears
    assert accuracy.zone_distance([[-0.405, 0.918]], nucleated) == pytest.approx(0.001)
    assert accuracy.zone_distance(np.zeros((0, 2)), zones) == pytest.approx(0.35)
    assert accuracy.zone_distance(np.zeros((0, 2)), np.zeros((0, 2))) == 0


def test_energy_error():
    assert accuracy.energy_error([1.0, 2.004], [1.0, 2.0]) == pytest.approx(2e-3)
    with pytest.raises(ValueError, match="positive reference energy"):
        accuracy.energy_error([1.0], [0.0])


def test_traction_error_leaves_out_the_bands():
    x = np.linspace(-1, 1, 201)
    q_ref = np.sqrt(1 - x**2)
    q = q_ref.copy()
    q[np.isclose(x, 0.3)] += 0.5  # next to a kink: left out
    q[np.isclose(x, -0.6)] += 0.1
    assert accuracy.traction_error(x, q, q_ref, [0.31, -1, 1], 0.02) == pytest.approx(0.1)
    assert accuracy.traction_error(x, q, q_ref, [0.31, -0.6], 0.02) == pytest.approx(0.0)
    assert accuracy.traction_error(x, q, q_ref, [], 0.02) == pytest.approx(0.5)
    q[np.isclose(x, 0.3)] = np.nan
    assert accuracy.traction_error(x, q, q_ref, [], 0.02) == pytest.approx(0.1)


def test_memory_kinks_mark_where_old_slip_meets_newer():
    """Nodes 0-5; step 1 slips 0-1 and 4-5, step 2 slips 5 only, step 3 nothing."""
    x = np.arange(6.0)
    stick = np.array(
        [
            [1, 1, 1, 1, 1, 1],
            [0, 0, 1, 1, 0, 0],
            [1, 1, 1, 1, 1, 0],
            [1, 1, 1, 1, 1, 1],
        ],
        dtype=bool,
    )
    kinks = accuracy.memory_kinks(x, stick)
    np.testing.assert_array_equal(kinks[0], [])
    np.testing.assert_array_equal(kinks[1], [1.5, 3.5])  # slipped at 1 against never
    np.testing.assert_array_equal(kinks[2], [1.5, 3.5])  # 4 stuck one step after 5: no kink between them
    np.testing.assert_array_equal(kinks[3], [1.5, 3.5])


# -- References --------------------------------------------------------------------------------


def test_a_reference_scores_zero_against_itself(hertz):
    history = harness.baseline_history(hertz, steps_per_segment=2)
    result = fr.simulate(hertz, history, nodes=32)
    errors = accuracy.score(result, accuracy.run_reference(result, "itself"))
    assert errors == {"stick_ends_a": 0.0, "energy_rel": 0.0, "traction_fp0": 0.0}
    with pytest.raises(ValueError, match="every step"):
        accuracy.run_reference(result.isel(step=[0, 2]), "every other step")


def test_masing_reference_of_constant_cycles(hertz):
    """Q cycling between +-Q*: stick zones of Cattaneo-Mindlin and Mindlin-Deresiewicz, energies per cycle."""
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear(np.array([0, 0.6, -0.6, 0.6, -0.6]) * fP, None, 4).as_cycle()
    reference = accuracy.masing_reference(hertz, history)
    a = hertz.a
    np.testing.assert_allclose(reference.zones[4], [[-a * math.sqrt(0.4), a * math.sqrt(0.4)]], rtol=1e-14)
    c = a * math.sqrt(1 - 0.3 / 2)  # step 5: unloaded by 0.3 fP from the peak
    np.testing.assert_allclose(reference.zones[5], [[-c, c]], rtol=1e-14)
    x = np.linspace(-a, a, 9)
    np.testing.assert_allclose(
        reference.tractions(5, x), cf.mindlin_deresiewicz_traction(hertz, 0.6 * fP, 0.3 * fP, x), atol=1e-9 * hertz.p0
    )
    W = cf.mindlin_deresiewicz_energy(hertz, 0.6 * fP)
    first = cf.cattaneo_mindlin_dissipation(hertz, 0.6 * fP) + 3 * (2 * W / 4)  # virgin rise, then three half loops
    assert reference.cycle_energy == pytest.approx([first], rel=1e-12)


def test_in_phase_reference_matches_nowell_hills(hertz):
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    history = fr.History.piecewise_linear([0, 0.6 * fP], [0, 0.6 * fp0], 3).as_cycle()
    reference = accuracy.masing_reference(hertz, history)
    x = np.linspace(-hertz.a, hertz.a, 11)
    np.testing.assert_allclose(reference.tractions(3, x), cf.nowell_hills_traction(hertz, 0.6 * fP, 0.6 * fp0, x))
    e, b = cf.nowell_hills_offset(hertz, 0.6 * fp0), cf.stick_half_width(hertz, 0.6 * fP)
    np.testing.assert_allclose(reference.zones[3], [[e - b, e + b]])
    with pytest.raises(ValueError, match="proportional"):
        accuracy.masing_reference(hertz, fr.History.piecewise_linear([0, fP / 2, 0], [0, 0, fp0], 2).as_cycle())


@pytest.mark.parametrize("psi", [0.001, 0.1, 0.2499, 0.25, 0.7, 0.99])
def test_slip_work_by_quadrature_is_the_closed_form(hertz, psi):
    """``int f p |s| dx`` of Cattaneo-Mindlin by the quadrature `monotonic_dissipation` takes with
    bulk tension, at ``sigma = 0``: the closed form, two derivations of one number."""
    Q = psi * hertz.f * hertz.P
    assert accuracy._slip_work(hertz, Q, 0.0) == pytest.approx(cf.cattaneo_mindlin_dissipation(hertz, Q), rel=1e-9)
