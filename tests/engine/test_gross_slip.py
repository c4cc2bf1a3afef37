"""Gross slip under displacement control on Hertz (docs/theory/displacement.md#gross-slip): the
transition displacement, every step of a history that slides both ways against the closed-form
branches, the energy of the gross-slip loop, the memory erased by sliding, force control still
refusing it, and split runs resumed bit for bit."""

import numpy as np
import pytest
from conftest import HERTZ_TOML

import fretting as fr
from fretting.engine import runner
from fretting.engine.recorder import final_state
from fretting.physics.closed_forms import cattaneo_mindlin_compliance, cattaneo_mindlin_slip
from fretting.results.variables import REGIMES
from fretting.studies.running import loop_cycles, sliding_cycles, transition_displacement

#: Datum [m]: about 21 half-widths from the middle of the contact below.
L = 5e-3


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=L, compliance=2e-12)


def transition(contact):
    """``delta_t = K f P + f p0 a / (2 E_star)`` [m] (eq D6): the displacement at which the contact,
    loaded from rest, starts to slide whole; ``K = C_L + C``."""
    fP = contact.f * contact.P
    return contact.displacement_compliance * fP + contact.f * contact.p0 * contact.a / (2 * contact.E_star)


def branch_delta(contact, Q, origin, delta_origin, factor):
    """``delta`` [m] on the branch from (`origin` [N/m], `delta_origin` [m]) with Masing's `factor` at `Q`
    (eq D7): ``delta_origin + K (Q - origin) + factor D((Q - origin) / factor)``, ``D`` Mindlin's."""
    K = contact.displacement_compliance
    return delta_origin + K * (Q - origin) + factor * cattaneo_mindlin_compliance(contact, (Q - origin) / factor)


def test_transition_displacement_is_the_closed_form(contact):
    """Loaded from rest, ``Q`` reaches ``f P`` exactly at ``delta_t``; a hair below, it does not."""
    fP, delta_t = contact.f * contact.P, transition(contact)
    at = fr.simulate(contact, fr.History.piecewise_linear(delta=[0, delta_t], steps_per_segment=3), fr.models.Exact())
    assert float(at.Q[-1]) == pytest.approx(fP, rel=1e-12)
    below = fr.simulate(contact, fr.History.piecewise_linear(delta=[0, 0.999 * delta_t], steps_per_segment=3))
    assert float(below.Q[-1]) < 0.9999 * fP and REGIMES[int(below.regime[-1])] == "partial_slip"


def test_every_step_follows_the_closed_form_branches(contact):
    """A ramp to 1.5 delta_t and two cycles +-1.5 delta_t: at every step ``Q`` is on Mindlin's virgin
    curve, on Mindlin & Deresiewicz's branch from the last sliding extreme (factor 2), or at ``+-f P``
    sliding; the regime says which."""
    fP = contact.f * contact.P
    result = fr.simulate(contact, sliding_cycles(1.5 * transition(contact), 2, 8), fr.models.Exact())
    Q, delta, regime = result.Q.values, result.delta.values, result.regime.values
    origin, delta_origin, factor = 0.0, 0.0, 1.0
    for k in range(1, Q.size):
        if abs(Q[k]) == fP:
            assert regime[k] == 2, k
            if abs(Q[k - 1]) == fP and Q[k - 1] == Q[k]:  # sliding on: the whole step is a uniform slide
                slid = delta[k] - delta[k - 1]
                assert slid * Q[k] > 0
                assert result.dissipation.values[k] == pytest.approx(fP * abs(slid), rel=1e-9)
        else:
            assert regime[k] == 1, k
            if abs(Q[k - 1]) == fP:  # a reversal from sliding: Mindlin & Deresiewicz's branch
                origin, delta_origin, factor = Q[k - 1], delta[k - 1], 2.0
            expected = branch_delta(contact, Q[k], origin, delta_origin, factor)
            assert expected == pytest.approx(delta[k], rel=1e-12, abs=1e-12 * transition(contact)), k
    assert np.count_nonzero(regime == 2) > 10 and np.count_nonzero(regime == 1) > 10


@pytest.mark.parametrize("ratio", [1.2, 3.0])
def test_gross_slip_loop_energy(contact, ratio):
    """Each cycle +-delta* beyond delta_t dissipates ``4 f P delta* - 4 K (f P)^2 - f P f p0 a / E_star``
    (eq D8), to 1e-6; of it, ``4 f P (delta* - delta_t)`` by sliding."""
    fP, K = contact.f * contact.P, contact.displacement_compliance
    star = ratio * transition(contact)
    result = fr.simulate(contact, sliding_cycles(ratio * transition(contact), 2, 16), fr.models.Exact())
    expected = 4 * fP * star - 4 * K * fP**2 - fP * contact.f * contact.p0 * contact.a / contact.E_star
    assert np.allclose(result.cycle_dissipation.values, expected, rtol=1e-6, atol=0)


def test_sliding_erases_the_memory_of_partial_slip(contact):
    """Two pasts of partial slip, then gross slip: from then on the traction is the same, the slip the
    same up to a uniform shift, and after a reversal it is Mindlin & Deresiewicz's from full sliding."""
    delta_t = transition(contact)
    pasts = ([0.0, 0.5 * delta_t, -0.3 * delta_t], [0.0, -0.8 * delta_t, 0.6 * delta_t, 0.1 * delta_t])
    after = [1.4 * delta_t, 0.9 * delta_t]
    runs = [
        fr.simulate(contact, fr.History.piecewise_linear(delta=past + after, steps_per_segment=6), fr.models.Exact())
        for past in pasts
    ]
    final = [final_state(run) for run in runs]
    assert final[0].memory == final[1].memory == (contact.f * contact.P,)  # only the sliding extreme is open
    q = [run.q.values[-1] for run in runs]
    assert np.array_equal(q[0], q[1])
    shift = runs[0].slip.values[-1] - runs[1].slip.values[-1]
    assert np.ptp(shift) < 1e-12 * np.abs(runs[0].slip.values[-1]).max()
    run, x = runs[0], runs[0].x.values
    fP, Q = contact.f * contact.P, float(runs[0].Q[-1])
    full = contact.f * x**2 / (2 * contact.profile.R)  # Cattaneo-Mindlin's slip at Q = f P
    expected = full + final[0].slid - 2 * cattaneo_mindlin_slip(contact, (fP - Q) / 2, x)
    assert np.max(np.abs(run.slip.values[-1] - expected)) < 1e-9 * np.abs(expected).max()


def test_force_control_still_refuses_gross_slip(contact):
    """Feed the Q a displacement run found to force control: the same up to the first sliding step,
    where force control stops with GrossSlipError."""
    moved = fr.simulate(contact, sliding_cycles(1.5 * transition(contact), 1, 8), fr.models.Exact())
    first = int(np.argmax(moved.regime.values == 2))
    history = fr.History(moved.Q.values[:first], np.zeros(first), [0, first - 1])
    forced = fr.simulate(contact, history, fr.models.Exact())
    assert np.array_equal(forced.delta.values, moved.delta.values[:first]) or np.allclose(
        forced.delta.values, moved.delta.values[:first], rtol=1e-12, atol=0
    )
    history = fr.History(moved.Q.values[: first + 1], np.zeros(first + 1), [0, first])
    with pytest.raises(fr.GrossSlipError, match=f"gross slip at step {first}"):
        fr.simulate(contact, history, fr.models.Exact())


def test_a_model_that_does_not_slide_says_so(contact):
    """A model whose `slides` is False: a user's (the package's models that run delta slide under a constant P)."""
    model = fr.models.Grid(32).build(contact)
    model.slides = False
    stepper = fr.Stepper(contact, model)
    with pytest.raises(
        fr.GrossSlipError, match=r"fretting\.models\.Exact \(Q alone\), Grid, Mesh and Varying"
    ) as caught:
        stepper.step(delta=1.5 * transition(contact))
    assert "\n" not in str(caught.value)


def test_mixed_history_split_anywhere_resumes_bit_for_bit(contact):
    """Partial-slip loops, gross slip both ways and reversals inside partial slip, split at every step."""
    delta_t = transition(contact)
    vertices = [0.0, 0.6, -0.4, 1.3, 0.7, 1.1, -1.6, -0.9, -1.2, 0.2]
    history = fr.History.piecewise_linear(delta=[v * delta_t for v in vertices], steps_per_segment=2)
    whole = fr.simulate(contact, history, fr.models.Exact())
    assert set(whole.regime.values.tolist()) == {0, 1, 2}
    for k in range(1, len(history) - 1):
        first = fr.simulate(contact, history[: k + 1], fr.models.Exact())
        later = fr.simulate(contact, history[k:], state=final_state(first))
        for name in ("Q", "delta", "slip", "q", "regime"):
            assert np.array_equal(later[name].values[1:], whole[name].values[k + 1 :]), (k, name)
        assert np.array_equal(later.dissipation.values[1:], whole.dissipation.values[k + 1 :])
        assert float(later.total_dissipation) == float(whole.total_dissipation)


def test_stepper_slides_and_sticks_again(contact):
    """`Stepper.step(delta=...)` slides past delta_t and sticks again on the way back."""
    fP, delta_t = contact.f * contact.P, transition(contact)
    stepper = fr.Stepper(contact, fr.models.Exact().resolved_for(contact, None))
    stepper.step(delta=1.5 * delta_t)
    assert stepper.state.Q == fP and stepper.state.slid == pytest.approx(0.5 * delta_t, rel=1e-9)
    outcome = stepper.step(delta=1.4 * delta_t)
    assert stepper.state.Q < fP and np.count_nonzero(outcome.ds == 0) > 0  # stuck in the middle


FILE = (
    HERTZ_TOML
    + """datum = 5e-3

[[loading]]
kind = "linear"
delta = [3e-6]
steps_per_segment = 6

[[loading]]
kind = "linear"
delta = [-3e-6, 3e-6]
steps_per_segment = 9
cycle = true
"""
)


def test_a_file_that_slides_run_in_chunks_is_the_run_in_one_piece(tmp_path, monkeypatch):
    """`run_file` continues each chunk from the state the one before left, its uniform slide included."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 9)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)
    path = tmp_path / "slides.toml"
    path.write_text(FILE)
    read, history = fr.read_history(path)
    chunked = runner.run_file(path, tmp_path / "slides.h5", fr.models.Exact(), record="all").result
    whole = fr.simulate(read, history, fr.models.Exact())
    assert 2 in whole.regime.values
    for name in ("Q", "delta", "slip", "regime", "dissipation"):
        assert np.array_equal(chunked[name].values, whole[name].values), name
    assert float(chunked.state_slid) == float(whole.state_slid) != 0


@pytest.mark.parametrize("profile", [fr.RoundedFlat(2e-4, 0.02), fr.FlatPunch(3e-4)], ids=["rounded_flat", "flat"])
def test_other_symmetric_profiles_slide(profile):
    """Beyond the transition each cycle's energy grows by ``4 f P`` per unit of delta* (eq D8, whatever
    the profile); the sharp flat punch, which sticks whole until it slides, starts to slide at
    ``delta_t = K f P`` and dissipates only by sliding, ``4 f P (delta* - delta_t)``."""
    contact = fr.Contact(profile, 115e9, 0.6, 1e5, datum=L)
    fP, delta_t = contact.f * contact.P, transition_displacement(contact)
    energy = [
        float(
            loop_cycles(fr.simulate(contact, sliding_cycles(r * delta_t, 1, 8), fr.models.Exact())).cycle_dissipation[0]
        )
        for r in (1.3, 1.7)
    ]
    assert energy[1] - energy[0] == pytest.approx(4 * fP * 0.4 * delta_t, rel=1e-9)
    if isinstance(profile, fr.FlatPunch):
        assert delta_t == pytest.approx(contact.displacement_compliance * fP, rel=1e-12)
        assert energy[0] == pytest.approx(4 * fP * 0.3 * delta_t, rel=1e-9)


@pytest.mark.parametrize("profile", [fr.Hertz(0.05), fr.RoundedFlat(2e-4, 0.02)], ids=["hertz", "rounded_flat"])
def test_a_step_that_slides_has_no_stick_zone(profile):
    """Every node of a step in gross slip slides by its uniform slip: no node sticks and no stick zone is
    reported, also on a rounded flat, whose corrective contact on the point of sliding is its flat; the
    steps in partial slip keep theirs."""
    contact = fr.Contact(profile, 115e9, 0.6, 1e5, datum=L)
    result = fr.simulate(contact, sliding_cycles(1.5 * transition_displacement(contact), 1, 8), fr.models.Exact())
    sliding = result.regime.values == REGIMES.index("gross_slip")
    assert sliding.any() and (~sliding[1:]).any()
    assert not result.stick.values[sliding].any()
    assert np.isnan(result.stick_start.values[sliding]).all() and np.isnan(result.stick_end.values[sliding]).all()
    assert not np.isnan(result.stick_start.values[~sliding]).any()


def test_a_model_that_does_not_slide_refuses_a_slide_with_the_contract_error():
    """`Model.slide`'s default is the gross-slip error naming the model that follows it, not a stub."""
    contact = fr.Contact(fr.Hertz(0.05), 115e9, 0.6, 1e5)
    model = fr.models.Grid(32).build(contact)
    assert not fr.models.Model.slides
    with pytest.raises(fr.GrossSlipError, match="Mesh and Varying .Q and sigma. follow gross slip"):
        fr.models.Model.slide(model, fr.State.virgin(model), fr.Loads(contact.f * contact.P), 1e-6)
