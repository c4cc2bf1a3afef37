"""Gross slip of method 4's models (`Grid`, `Mesh`, the cells of `Varying`) under displacement control,
with a bulk tension ``sigma`` (docs/theory/displacement.md#sliding-sigma): the energy of a slide
against its closed form, the slip of a slide against the strain mismatch of ``sigma``, a point that
``sigma`` would reverse sticking instead, the regime of every step, force control still refusing
``|Q| >= f P``, a history in and out of gross slip split and resumed bit for bit, and the mesh
against the exact model at ``sigma = 0``."""

import numpy as np
import pytest

import fretting as fr
from fretting.engine.recorder import final_state
from fretting.models.galerkin import uniform_theta
from fretting.results.variables import REGIMES
from fretting.studies.running import sliding_cycles, transition_displacement

GROSS, PARTIAL = REGIMES.index("gross_slip"), REGIMES.index("partial_slip")

MODELS = [fr.models.Grid(64), fr.models.Mesh(theta=uniform_theta(64)), fr.models.Varying(64)]
IDS = ["grid", "mesh", "cells"]


def resolved(spec, contact):
    """`spec` with its nodes fixed on `contact` (the cells over its own contact), for a `fr.Stepper`."""
    return spec.resolved_for(contact, None)


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=5e-3, compliance=2e-12)


def tension_then_sliding(contact, steps=4):
    """``sigma`` to ``0.3 f p0`` at ``delta = 0``, ``delta`` past the transition, then ``delta`` and ``sigma``
    on together (to ``0.5 f p0``) while the contact slides."""
    delta_t, fp0 = transition_displacement(contact), contact.f * contact.p0
    delta = [0.0, 0.0, 1.5 * delta_t, 1.8 * delta_t]
    sigma = [0.0, 0.3 * fp0, 0.3 * fp0, 0.5 * fp0]
    return fr.History.piecewise_linear(delta=delta, sigma=sigma, steps_per_segment=steps)


@pytest.mark.parametrize("spec", MODELS, ids=IDS)
def test_a_slide_dissipates_f_P_per_unit_of_displacement(contact, spec):
    """Under a constant ``sigma = 0.3 f p0`` every step that slides on slides every node by the step's
    ``d delta`` and dissipates ``int f p |d delta| dx = f P |d delta|`` (eq D5), to 1e-6; ``Q`` sits at ``f P``."""
    fP = contact.f * contact.P
    result = fr.simulate(contact, tension_then_sliding(contact), spec)
    regime, delta, Q = result.regime.values, result.delta.values, result.Q.values
    sliding = np.flatnonzero(regime == GROSS)
    assert sliding.size >= 4 and regime[sliding[0] - 1] == PARTIAL
    assert Q[sliding] == pytest.approx(fP, rel=1e-15)
    for k in sliding[1:]:
        slide = delta[k] - delta[k - 1]
        assert slide > 0 and not result.stick.values[k].any(), k
        assert float(result.dissipation[k]) == pytest.approx(fP * slide, rel=1e-6), k
    constant = sliding[1:][result.sigma.values[sliding[1:]] == result.sigma.values[sliding[1:] - 1]]
    assert constant.size >= 1
    for k in constant:  # sigma held: a uniform slide
        ds = result.slip.values[k] - result.slip.values[k - 1]
        assert np.ptp(ds) < 1e-9 * ds.mean()


def strain_mismatch_error(contact, spec):
    """Largest ``|ds - (d delta + d sigma x / (2 E_star))|`` over the nodes of the last step of
    `tension_then_sliding` (a slide while ``sigma`` rises), in units of ``d sigma a / (2 E_star)``."""
    result = fr.simulate(contact, tension_then_sliding(contact), spec)
    assert result.regime.values[-1] == GROSS
    x = result.x.values - contact.centre
    ds = result.slip.values[-1] - result.slip.values[-2]
    d_delta, d_sigma = np.diff(result.delta.values[-2:])[0], np.diff(result.sigma.values[-2:])[0]
    expected = d_delta + d_sigma * x / (2 * contact.E_star)
    return np.max(np.abs(ds - expected)) / (d_sigma * contact.a / (2 * contact.E_star))


def test_a_slide_under_a_changing_tension_takes_the_strain_mismatch(contact):
    """With the traction held at ``f p``, the slip changes by the slide plus the bulk strain mismatch,
    ``ds = d delta + d sigma x / (2 E_star)``: on the Chebyshev grid to rounding (``x`` is its first
    polynomial), on the cells to rounding (their stuck load of ``sigma`` is that of this slip); on a mesh in
    ``theta``, which holds ``x = a cos(theta)`` to second order, the error falls four times as the elements
    halve."""
    assert strain_mismatch_error(contact, fr.models.Grid(64)) < 1e-10
    assert strain_mismatch_error(contact, fr.models.Varying(64)) < 1e-10
    coarse, fine = (strain_mismatch_error(contact, fr.models.Mesh(theta=uniform_theta(n))) for n in (32, 64))
    assert fine < 1e-3 and coarse / fine > 3.5


@pytest.mark.parametrize("spec", MODELS, ids=IDS)
def test_a_tension_that_would_reverse_an_edge_sticks_it(contact, spec):
    """From a slide at ``+f P``, a step that raises ``sigma`` by ``d sigma`` and ``delta`` by ``d delta``: where
    ``d delta`` exceeds ``d sigma |x| / (2 E_star)`` at every node, the contact slides on; where it is half that,
    the side ``x < 0`` would slip back, so it sticks: ``Q`` falls below ``f P``, partial slip, the stuck nodes
    on that side, and beyond them, where ``f p`` is smallest, the edge slipping back."""
    fP, delta_t, fp0 = contact.f * contact.P, transition_displacement(contact), contact.f * contact.p0
    d_sigma = 0.2 * fp0
    outcomes = {}
    for share in (1.2, 0.5):
        stepper = fr.Stepper(contact, resolved(spec, contact))
        stepper.step(delta=1.5 * delta_t)
        assert stepper.state.Q == pytest.approx(fP, rel=1e-15)
        reach = d_sigma * np.max(np.abs(stepper.model.x - contact.centre)) / (2 * contact.E_star)
        outcomes[share] = stepper.step(delta=1.5 * delta_t + share * reach, sigma=d_sigma), stepper.state.Q
    (slid, Q_slid), (stuck, Q_stuck) = outcomes[1.2], outcomes[0.5]
    assert Q_slid == pytest.approx(fP, rel=1e-15) and np.all(slid.ds > 0)
    assert Q_stuck < fP * (1 - 1e-6)
    x = stepper.model.x - contact.centre
    held, back = x[stuck.ds == 0], x[stuck.ds < 0]
    assert held.size and np.all(held < 0)
    assert np.all(back < held.min())


def test_sliding_erases_the_memory_of_partial_slip(contact):
    """Two pasts of partial slip under different tensions, then the same slide under ``sigma = 0.2 f p0`` and
    a reversal: from the slide on, the slip fields agree to rounding (the sliding field of eq D10, its
    uniform part fixed by ``delta``), and so do ``Q`` and the slip after the reversal."""
    delta_t, fp0 = transition_displacement(contact), contact.f * contact.p0
    pasts = (([0.0, 0.6, -0.4], [0.0, 0.4, -0.3]), ([0.0, -0.8, 0.5, 0.1], [0.0, -0.2, 0.1, 0.2]))
    spec = fr.models.Grid(48)
    runs = []
    for delta, sigma in pasts:
        delta, sigma = delta + [1.4, 1.6, 0.9], sigma + [0.2, 0.2, 0.2]
        history = fr.History.piecewise_linear(
            delta=[d * delta_t for d in delta], sigma=[s * fp0 for s in sigma], steps_per_segment=4
        )
        runs.append(fr.simulate(contact, history, spec))
    slid = [int(np.argmax(run.regime.values == GROSS)) for run in runs]
    scale = np.abs(runs[0].slip.values).max()
    for back in (9, 1):  # the last slide, and the last step of the reversal
        slips = [run.slip.values[-back] for run in runs]
        assert np.max(np.abs(slips[0] - slips[1])) < 1e-9 * scale, back
    assert runs[0].Q.values[-1] == pytest.approx(runs[1].Q.values[-1], rel=1e-9)
    assert runs[0].regime.values[-1] == PARTIAL and all(run.regime.values[-9] == GROSS for run in runs)
    assert slid[0] != slid[1] or not np.array_equal(runs[0].slip.values[slid[0] - 1], runs[1].slip.values[slid[1] - 1])


@pytest.mark.parametrize("spec", MODELS, ids=IDS)
def test_force_control_still_refuses_gross_slip(contact, spec):
    """The ``Q`` and ``sigma`` a displacement run found, fed to force control: the run stops with
    GrossSlipError at the step that slid."""
    moved = fr.simulate(contact, tension_then_sliding(contact, 3), spec)
    first = int(np.argmax(moved.regime.values == GROSS))
    history = fr.History(moved.Q.values[: first + 1], moved.sigma.values[: first + 1], [0, first])
    with pytest.raises(fr.GrossSlipError, match=f"gross slip at step {first}"):
        fr.simulate(contact, history, spec)


def test_a_history_in_and_out_of_gross_slip_split_anywhere_resumes_bit_for_bit(contact):
    """Partial slip under a tension, gross slip both ways with ``sigma`` moving, a reversal by ``sigma``
    and partial slip again, on a Galerkin mesh: each split and resumed run equals the whole."""
    delta_t, fp0 = transition_displacement(contact), contact.f * contact.p0
    delta = [0.0, 0.5, 1.4, 1.6, 1.6, -1.5, -0.8, 0.3]
    sigma = [0.0, 0.3, 0.3, 0.5, -0.5, -0.5, 0.2, 0.2]
    history = fr.History.piecewise_linear(
        delta=[d * delta_t for d in delta], sigma=[s * fp0 for s in sigma], steps_per_segment=2
    )
    spec = fr.models.Mesh(theta=uniform_theta(32))
    whole = fr.simulate(contact, history, spec)
    assert set(whole.regime.values.tolist()) == {0, PARTIAL, GROSS}
    assert np.any((whole.regime.values == GROSS) & (whole.Q.values < 0))
    for k in range(1, len(history) - 1):
        first = fr.simulate(contact, history[: k + 1], spec)
        later = fr.simulate(contact, history[k:], state=final_state(first))
        for name in ("Q", "delta", "slip", "q", "regime", "dissipation"):
            assert np.array_equal(later[name].values[1:], whole[name].values[k + 1 :]), (k, name)
        assert float(later.total_dissipation) == float(whole.total_dissipation)


def cycle_errors(contact, exact, elements):
    """Largest error of ``Q`` [f P] over the steps, and of the cycle's energy [relative], of the uniform mesh
    of `elements` elements against the `exact` result of one gross-slip cycle."""
    mesh = fr.simulate(
        contact,
        sliding_cycles(1.5 * transition_displacement(contact), 1, 16),
        fr.models.Mesh(theta=uniform_theta(elements)),
    )
    assert np.array_equal(mesh.regime.values, exact.regime.values)
    fP = contact.f * contact.P
    return (
        np.max(np.abs(mesh.Q.values - exact.Q.values)) / fP,
        abs(float(mesh.cycle_dissipation[0]) / float(exact.cycle_dissipation[0]) - 1),
    )


def test_mesh_and_exact_model_agree_on_a_gross_slip_cycle(contact):
    """At ``sigma = 0`` a cycle of +-1.5 delta_t on a uniform mesh follows the exact model: the same regime at
    every step, ``Q`` within 1e-4 f P and the energy within 1e-5 on 64 elements, both errors falling as the
    elements halve (the mesh's own convergence, not a tolerance)."""
    exact = fr.simulate(contact, sliding_cycles(1.5 * transition_displacement(contact), 1, 16), fr.models.Exact())
    assert GROSS in exact.regime.values
    coarse, fine = cycle_errors(contact, exact, 32), cycle_errors(contact, exact, 64)
    assert fine[0] < 1e-4 and fine[1] < 1e-5
    assert coarse[0] > 2 * fine[0] and coarse[1] > 4 * fine[1]
