"""The exact model of in-phase Q and sigma on Hertz (fretting.models.inphase): Nowell-Hills and Masing's rule.

Checked against the closed form of Nowell & Hills at the first loading, against Mindlin's energy
and compliance where sigma vanishes, against the area of a closed loop of ``Q`` and ``sigma``
against their generalised displacements (docs/theory/conventions.md), and against method 4 on a
fine mesh at every step of a random-amplitude history.
"""

import numpy as np
import pytest
from harness import END_BAND, hard_rounded_flat, hertz_contact
from scipy import integrate

import fretting as fr
from fretting.engine.recorder import recorded_spec
from fretting.loading import history as history_module
from fretting.loading.loads import Loads
from fretting.models.inphase import InPhase, on_line, proportional_ratio, regime_bound
from fretting.models.state import State
from fretting.physics import closed_forms as cf

#: The fine mesh of method 4 (uniform in theta) that the model is compared with, and how far [a]
#: from every stick end of the history its nodal traction is compared: within that band the
#: traction's square root at the end errs by about 1e-2 f p0 on that mesh.
FINE = np.linspace(0, np.pi, 4001)


def in_phase(contact, loads, share, steps):
    """The history through `loads` [f P] with ``sigma = share * 4 / (pi a) * Q`` (regime A for share <= 1)."""
    Q = np.asarray(loads) * contact.f * contact.P
    return fr.History.piecewise_linear(Q, share * regime_bound(contact) * Q, steps)


@pytest.mark.parametrize("sign", [1, -1])
@pytest.mark.parametrize("share", [0.5, -1.0])
def test_first_loading_is_nowell_hills(sign, share):
    """Q rising from zero to 0.6 f P (or falling to -0.6 f P) in phase with sigma: the traction at every
    node is Nowell-Hills's to 1e-12 f p0, the stick zone is ``[e - b, e + b]``, the slip is ``f`` times
    the gap outside the shifted corrective contact, and delta_sigma and delta_Q are quadratures of it."""
    contact = hertz_contact()
    history = in_phase(contact, [0.0, sign * 0.6], share, 5)
    result = fr.simulate(contact, history)
    assert result.attrs["model"] == InPhase.name
    Q, sigma = history.Q[-1], history.sigma[-1]
    fp0, a = contact.f * contact.p0, contact.a
    reference = cf.nowell_hills_traction(contact, Q, sigma, result.x.values)
    np.testing.assert_allclose(result.q.values[-1] / fp0, reference / fp0, rtol=0, atol=1e-12)
    e, b = sign * cf.nowell_hills_offset(contact, sigma), cf.stick_half_width(contact, Q)
    assert result.stick_start.values[-1, 0] == pytest.approx(e - b, abs=1e-12 * a)
    assert result.stick_end.values[-1, 0] == pytest.approx(e + b, abs=1e-12 * a)

    def slip(x):
        X = np.maximum(np.abs(x - e), b)
        return sign * contact.f * (X * np.sqrt(X**2 - b**2) - b**2 * np.arccosh(X / b)) / (2 * contact.profile.R)

    np.testing.assert_allclose(result.slip.values[-1], slip(result.x.values), rtol=1e-10, atol=1e-14 * a)
    moments = [
        integrate.quad(
            lambda th, n=n: slip(a * np.cos(th)) * np.cos(th) ** n, 0, np.pi, epsabs=0, epsrel=1e-12, limit=400
        )[0]
        for n in (0, 1)
    ]
    assert result.delta_Q.values[-1] == pytest.approx(moments[0] / np.pi, rel=1e-9)
    assert result.delta_sigma.values[-1] == pytest.approx(a * moments[1] / 4, rel=1e-9)


def test_without_sigma_it_is_mindlin():
    """ratio 0: the energy of a first loading to 0.7 f P and delta_Q are Mindlin's closed forms to 1e-12."""
    contact = hertz_contact()
    Q = 0.7 * contact.f * contact.P
    model = InPhase(ratio=0.0).resolved_for(contact, None).build(contact)
    branch = model._solved(contact.P - Q / contact.f)
    assert contact.f**2 * branch.energy == pytest.approx(cf.cattaneo_mindlin_dissipation(contact, Q), rel=1e-12)
    assert branch.delta_Q == pytest.approx(cf.cattaneo_mindlin_compliance(contact, Q), rel=1e-12)


def test_a_closed_loop_dissipates_its_area():
    """An in-phase cycle between 0.7 and -0.4 f P after the first loading: the energy it dissipates is the area
    ``loop Q d(delta_Q) + sigma d(delta_sigma)`` of its loop (docs/theory/conventions.md), by the
    trapezoidal rule over 2000 steps a branch (its error ~1e-7 of the area)."""
    contact = hertz_contact()
    result = fr.simulate(contact, in_phase(contact, [0.0, 0.7, -0.4, 0.7], 0.8, [1, 2000, 2000]))
    cycle = slice(1, 4002)
    Q, sigma = result.Q.values[cycle], result.sigma.values[cycle]
    delta_Q, delta_sigma = result.delta_Q.values[cycle], result.delta_sigma.values[cycle]
    area = np.trapezoid(Q, delta_Q) + np.trapezoid(sigma, delta_sigma)
    assert result.dissipation.values[cycle][1:].sum() == pytest.approx(area, rel=1e-6)


@pytest.mark.slow
def test_random_amplitudes_agree_with_method_4_on_a_fine_mesh():
    """Four random-amplitude in-phase cycles (nested loops opened and wiped): at every step, on the
    nodes of a uniform mesh of 4001 angles, the traction and the slip are method 4's to 1e-4 f p0
    and 1e-5 of the largest slip farther than `END_BAND` from the stick ends of the history, the
    energy of each increment, delta_Q and delta_sigma to 1e-6 of their largest, the stick ends to
    1e-4 a. (At the nodes next to a stick end the mesh's slip errs by about 1e-5 of the largest,
    falling as the mesh is refined: benchmarks/inphase_accuracy.py.)"""
    contact = hertz_contact()
    k = 0.9 * regime_bound(contact)
    history = fr.History.random_amplitude(4, 0.8 * contact.f * contact.P, 0.0, seed=3, steps_per_segment=2)
    history = fr.History.piecewise_linear(history.Q, k * history.Q, 1)
    model = InPhase(ratio=k, theta=FINE)
    exact, reference = fr.simulate(contact, history, model=model), fr.simulate(contact, history, mesh=FINE)
    a, fp0 = contact.a, contact.f * contact.p0
    ends = np.concatenate([exact.stick_start.values, exact.stick_end.values], axis=1).ravel() / a
    far = np.abs(exact.x.values[:, None] / a - ends[None, :]).min(axis=1) > END_BAND
    np.testing.assert_allclose(exact.q.values[:, far] / fp0, reference.q.values[:, far] / fp0, rtol=0, atol=1e-4)
    slip = np.abs(exact.slip.values[:, far] - reference.slip.values[:, far])
    assert slip.max() <= 1e-5 * np.abs(reference.slip.values).max()
    for name in ("dissipation", "delta_Q", "delta_sigma"):
        found, expected = exact[name].values, reference[name].values
        assert np.abs(found - expected).max() <= 1e-6 * np.abs(expected).max(), name
    for end in ("stick_start", "stick_end"):
        np.testing.assert_allclose(exact[end].values, reference[end].values, rtol=0, atol=1e-4 * a)


def test_the_default_takes_it_in_regime_a_and_records_it():
    """In phase through the origin in regime A: the default is `InPhase` with the history's ratio,
    recorded in the dataset (name, description, ratio) and read back from it."""
    contact = hertz_contact()
    result = fr.simulate(contact, in_phase(contact, [0.0, 0.5, -0.5, 0.3], 1.0, 4))
    assert result.attrs["model"] == "inphase"
    assert result.attrs["model_description"] == InPhase.description
    assert result.attrs["sigma_per_Q"] == regime_bound(contact)
    spec = recorded_spec(result)
    assert isinstance(spec, InPhase) and spec.ratio == regime_bound(contact)
    assert np.array_equal(spec.theta, fr.choose_model(contact, in_phase(contact, [0.0, 0.5, -0.5, 0.3], 1.0, 4)).theta)


@pytest.mark.parametrize(
    ("history", "reason"),
    [
        (lambda c: in_phase(c, [0.0, 0.3], 1.01, 1), "regime A"),
        (lambda c: fr.History.piecewise_linear([0.0, 1e4, -1e4], [0.0, 1e7, 0.0], 1), "not proportional"),
        (lambda c: fr.History.sinusoidal(1e4, 1e7, cycles=1, steps_per_cycle=8, sigma_mean=1e6), "not proportional"),
    ],
)
def test_the_default_does_not_take_it_off_regime_a_or_off_the_line(history, reason):
    """Past regime A, or a load path that is not one straight line through the origin: method 4's
    mesh, and `InPhase.holds_for` says why."""
    contact = hertz_contact()
    found = history(contact)
    assert reason in InPhase().holds_for(contact, found)
    assert fr.choose_model(contact, found).name == "mesh"


def test_it_holds_only_for_hertz():
    """A rounded flat under in-phase loads: not Hertz, said."""
    contact = hard_rounded_flat()
    assert "not a Hertz profile" in InPhase().holds_for(contact, in_phase(contact, [0.0, 0.5], 0.5, 2))


def test_an_increment_off_the_line_is_refused():
    """An increment to loads off ``sigma = ratio Q``: a ValueError that says so."""
    contact = hertz_contact()
    model = InPhase(ratio=regime_bound(contact)).resolved_for(contact, None).build(contact)
    state = State.virgin(model)
    with pytest.raises(ValueError, match="not in phase"):
        model.increment(state, Loads(1e4, 0.0))


def test_a_continued_run_equals_the_whole_run(tmp_path):
    """Cut at a vertex, saved, loaded and continued from its state (the ratio and the open turning points
    read back): the same slip, delta_sigma and energy, bit for bit. Loads off the line are refused."""
    contact = hertz_contact()
    history = in_phase(contact, [0.0, 0.8, -0.5, 0.6, -0.2, 0.9, -0.9], 0.7, 3)
    whole = fr.simulate(contact, history)
    cut = int(history.vertex_step[4])
    fr.save(fr.simulate(contact, history[: cut + 1]), tmp_path / "head.h5")
    state = fr.final_state(fr.load(tmp_path / "head.h5"))
    assert state.memory == tuple(history.Q[history.vertex_step[1:4]])
    tail = fr.simulate(contact, history[cut:], state=state)
    np.testing.assert_array_equal(tail.slip.values, whole.slip.values[cut:])
    np.testing.assert_array_equal(tail.delta_sigma.values, whole.delta_sigma.values[cut:])
    assert tail.total_dissipation.values == whole.total_dissipation.values
    off = fr.History.piecewise_linear([history.Q[cut], 0.0], [history.sigma[cut], 1e6], 2)
    with pytest.raises(fr.HistoryError, match="leaves the model's line"):
        fr.simulate(contact, off, state=state)


def test_the_ratio_is_read_block_by_block(monkeypatch):
    """Blocks of 4 steps: the ratio is read at the largest |Q| of the whole history (in its third
    block), and a step off the line in any block, also the last, is found, as one pass over all
    the steps finds them."""
    monkeypatch.setattr(history_module, "BLOCK_STEPS", 4)
    Q = np.array([0.0, 3.0, -9.0, 2.0, -5.0, 12.0, -7.5, 4.0, -14.0, 1.0, 6.0])
    k = 2.5e-3
    history = fr.History(Q, k * Q * (1 + 1e-14 * np.arange(Q.size)), [0])  # on the line to rounding
    ratios = history.sigma / np.where(Q == 0, 1.0, Q)
    assert np.argmax(np.abs(Q)) == 8 and np.unique(ratios[1:]).size == Q.size - 1
    assert proportional_ratio(history) == ratios[8]
    assert on_line(history, k) and not on_line(history, 1.01 * k)
    for step in (2, 5, 10):
        sigma = k * Q
        sigma[step] *= 1 + 1e-9
        assert proportional_ratio(fr.History(Q, sigma, [0])) is None
    assert proportional_ratio(fr.History(np.zeros(9), np.zeros(9), [0])) == 0.0
    assert proportional_ratio(fr.History(np.zeros(9), np.eye(9)[6], [0])) is None


def test_a_ratio_past_the_largest_float_is_not_in_phase():
    """``Q`` of 4e-301 N/m with ``sigma`` of 1e8 Pa: ``sigma / Q`` is no float, so the history is not
    in phase; the default says so and takes method 4's mesh (no invalid arithmetic on the way)."""
    contact = hertz_contact()
    history = fr.History.piecewise_linear([0.0, 4.1e-301], [0.0, 1e8], 1)
    assert proportional_ratio(history) is None
    assert "not proportional" in InPhase().holds_for(contact, history)
    assert fr.choose_model(contact, history).name == "mesh"
