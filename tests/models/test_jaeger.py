"""The exact model of a varying P and Q (fretting.models.Jaeger), on Hertz and on a rounded flat: the default where
it applies, method 4 on cells converging to it at every step, its energy density, a run continued from its state
and one stepped increment by increment, bit for bit; under displacement control, in and out of gross slip."""

import numpy as np
import pytest
from displacement_speed import prescribed, sliding_cycle
from engine.test_displacement_varying_load import L, assert_slides_at_f_P
from harness import hertz_contact, rounded_flat_contact
from varying_accuracy import SCENES, PackageRun, compare

import fretting as fr
from fretting.engine.choice import choose_model
from fretting.engine.recorder import final_state, recorded_spec
from fretting.models import Jaeger, Varying


@pytest.fixture(scope="module", params=["hertz", "flat"])
def contact(request):
    return {"hertz": hertz_contact, "flat": rounded_flat_contact}[request.param]()


@pytest.fixture(scope="module")
def recede(contact):
    """Cattaneo-Mindlin, the load lowered past the slip zones, Q reversed, the load raised over them and back
    (benchmarks/varying_accuracy.py), and the default's result."""
    history = SCENES["recede"](contact)
    return history, fr.simulate(contact, history)


def test_the_default_is_exact_where_jaeger_applies(contact):
    """A varying P with Q on Hertz or on a rounded flat, under force or displacement control: Jaeger's
    superposition; with sigma: method 4 on cells."""
    history = SCENES["recede"](contact)
    assert choose_model(contact, history) == Jaeger().resolved_for(contact, history)
    walk = SCENES["walk"](contact)
    assert choose_model(contact, walk).name == "varying"
    flat = rounded_flat_contact()
    assert choose_model(flat, SCENES["recede"](flat)).name == "jaeger"
    assert choose_model(flat, SCENES["walk"](flat)).name == "varying"
    assert choose_model(contact, history.displacements()).name == "jaeger"
    assert "bulk tension" in Jaeger().refusal(contact, walk)


def test_cells_converge_to_it_at_every_step(contact, recede):
    """Method 4 on cells (`Varying`), refined from 384 to 1536 cells, nears the exact model at every step: stick
    ends, traction and energy of benchmarks/varying_accuracy.py, each the worst over the steps, at least halved
    and within the targets at 1536 cells, and the slip a step adds nearer (its zone a few cells wide)."""
    history, exact = recede
    reference = PackageRun(exact)
    worst = [
        compare(fr.simulate(contact, history, model=Varying(cells)), reference, contact)[0] for cells in (384, 1536)
    ]
    for name in ("stick", "traction", "energy"):
        assert worst[1][name] < worst[0][name] / 2, name
    assert worst[1]["stick"] < 1e-3 and worst[1]["traction"] < 1e-3 and worst[1]["energy"] < 1e-4
    assert worst[1]["increment"] < worst[0]["increment"]


def test_a_slip_zone_that_reaches_a_band_at_the_limit_to_rounding_ends_past_it():
    """Nested loops of Q under P = P0 (1 + 0.05 |Q| / (f P0)) on Hertz: a slip zone's inner end solves
    ``g(c) = Q - s f P`` (`fretting.physics.superposition.Bands.inverse`), flat over a band that entered at
    the limit, and the rounding of ``g`` can put that band's upper edge a hair past the value sought, where
    the band's own formula has no answer. The run ends, its stick ends and energy at every step within the
    targets of method 4 on 1536 cells."""
    contact = hertz_contact()
    path = np.array([0.0, -0.49594927128908944, 0.3709192320216966, -0.1894695224532163, 0.04213907493920421])
    path = np.append(path, path[[3, 1]])
    history = fr.History.piecewise_linear(path * contact.f * contact.P, None, 3, P=contact.P * (1 + 0.05 * abs(path)))
    exact = fr.simulate(contact, history)
    assert exact.attrs["model"] == "jaeger"
    cells = fr.simulate(contact, history, model=Varying(1536))
    for end in ("stick_start", "stick_end"):
        np.testing.assert_allclose(exact[end].values, cells[end].values, rtol=0, atol=1e-3 * contact.a)
    energy = np.cumsum(exact.dissipation.values)
    np.testing.assert_allclose(np.cumsum(cells.dissipation.values), energy, rtol=0, atol=1e-4 * energy[-1])


def test_energy_density_sums_to_the_energy(contact, recede):
    """The energy density of each increment at the nodes, over the cells, sums to the increment's energy (the
    midpoint rule on cells 1/768 of the largest contact wide: to 1e-3 of the largest increment's)."""
    history, result = recede
    model = Jaeger().resolved_for(contact, history).build(contact)
    state = fr.State.virgin(model)
    dissipation = []
    for k in range(1, len(history)):
        outcome = model.increment(state, fr.Loads(float(history.Q[k]), 0.0, float(history.P[k])))
        dissipation.append((outcome.dissipation, float(np.sum(outcome.density) * model.h)))
        state = state.advance(outcome, fr.Loads(float(history.Q[k]), 0.0, float(history.P[k])), None, None, None, None)
    exact, summed = np.array(dissipation).T
    np.testing.assert_array_equal(exact, result.dissipation.values[1:])
    assert np.max(np.abs(summed - exact)) < 1e-3 * exact.max()


@pytest.mark.parametrize("k", [20, 45, 70])
def test_a_run_continued_from_its_state_is_the_same_bit_for_bit(contact, recede, k):
    """The history split at step `k` (the load receding, Q reversed, the load growing) and continued from the
    final state of the first part: the same slip, traction and displacement at every later step, and the same
    stick zones and energy of every later increment."""
    history, whole = recede
    first = fr.simulate(contact, history[: k + 1], model=Jaeger().resolved_for(contact, history))  # whole's cells
    later = fr.simulate(contact, history[k:], state=final_state(first))
    for name in ("slip", "q", "delta_Q"):
        np.testing.assert_array_equal(later[name].values, whole[name].values[k:], err_msg=name)
    for name in ("stick_start", "stick_end", "dissipation"):  # of the increments: the continued run's step 0 is at rest
        np.testing.assert_array_equal(later[name].values[1:], whole[name].values[k + 1 :], err_msg=name)
    assert float(later.total_dissipation) == float(whole.total_dissipation)


def test_stepping_one_increment_at_a_time_equals_simulate(contact, recede):
    """`fretting.Stepper` given the result's spec and each step's loads: the slip and energy of every step of the
    run, bit for bit."""
    history, whole = recede
    stepper = fr.Stepper(contact, recorded_spec(whole))
    slips, energy = [], []
    for Q, P in zip(history.Q, history.P, strict=True):
        outcome = stepper.step(Q, 0.0, P=P)
        slips.append(stepper.state.slip)
        energy.append(outcome.dissipation)
    np.testing.assert_array_equal(np.array(slips), whole.slip.values)
    np.testing.assert_array_equal(np.array(energy), whole.dissipation.values)


@pytest.fixture(scope="module")
def datum(contact):
    """`contact` with the datum of tests/engine/test_displacement_varying_load.py: displacement control."""
    return fr.Contact(contact.profile, contact.E_star, contact.f, contact.P, datum=L)


@pytest.fixture(scope="module")
def slid(datum):
    """`sliding_cycle`: ``delta`` to twice the transition displacement and back under a varying P, by default."""
    return fr.simulate(datum, sliding_cycle(datum))


def test_force_and_displacement_control_agree(datum):
    """``P = P0 (1 + 0.3 sin)``, ``Q = 0.5 f P0 sin`` under force control, then its recorded delta prescribed with
    the same P: the Q found at every step is the history's to 1e-14 of ``f P0`` (Brent's bracket), the slip and
    each step's energy the same to 1e-12 (`delta_Q` of the memory is the displacement's slip part)."""
    fP, t = datum.f * datum.P, np.linspace(0.0, 2 * np.pi, 25)
    history = fr.History(0.5 * fP * np.sin(t), np.zeros(t.size), [0, t.size - 1], None, datum.P * (1 + 0.3 * np.sin(t)))
    forced = fr.simulate(datum, history)
    assert forced.attrs["model"] == "jaeger" and 1 in forced.regime.values
    moved = fr.simulate(datum, prescribed(history, forced.delta.values))
    assert moved.attrs["model"] == "jaeger"
    assert np.max(np.abs(moved.Q.values - forced.Q.values)) < 1e-14 * fP
    assert np.max(np.abs(moved.slip.values - forced.slip.values)) < 1e-12 * np.abs(forced.slip.values).max()
    energy = forced.dissipation.values
    assert np.max(np.abs(moved.dissipation.values - energy)) < 1e-12 * energy.max()


def test_under_displacement_control_it_slides_at_f_P(datum, slid):
    """By default, the gross slip of the cells' test: ``Q = +-f P`` at every sliding step under a rising and a
    falling P, and the trapezoidal rule in P of a slide's energy (`assert_slides_at_f_P`)."""
    assert slid.attrs["model"] == "jaeger"
    assert_slides_at_f_P(datum, slid)


def test_cells_converge_to_it_under_displacement_control(datum, slid):
    """`Varying` on 128 then 512 cells, the same cycle: the regime of every step the default's, and the largest
    distance from it of ``Q`` [f P0] and of the energy up to a step [of the history's] at least halved."""
    fP, total = datum.f * datum.P, slid.dissipation.values.sum()
    distances = []
    for cells in (128, 512):
        cells_run = fr.simulate(datum, sliding_cycle(datum), Varying(cells))
        assert np.array_equal(cells_run.regime.values, slid.regime.values)
        energy = np.cumsum(cells_run.dissipation.values) - np.cumsum(slid.dissipation.values)
        distances.append((np.abs(cells_run.Q.values - slid.Q.values).max() / fP, np.abs(energy).max() / total))
    assert distances[1][0] < distances[0][0] / 2 and distances[1][1] < distances[0][1] / 2


@pytest.mark.parametrize("k", [6, 14, 30])
def test_a_slide_split_anywhere_resumes_bit_for_bit(datum, slid, k):
    """Split at the first slide, at the first step stuck again, in the middle of a slide: the same ``Q``, ``delta``
    and slip at every later step, and the same energy and regime of every later increment."""
    history = sliding_cycle(datum)
    first = fr.simulate(datum, history[: k + 1], Jaeger().resolved_for(datum, history))
    later = fr.simulate(datum, history[k:], state=final_state(first))
    for name in ("Q", "delta", "slip"):
        np.testing.assert_array_equal(later[name].values, slid[name].values[k:], err_msg=name)
    for name in ("dissipation", "regime"):
        np.testing.assert_array_equal(later[name].values[1:], slid[name].values[k + 1 :], err_msg=name)
