"""Fretting loops and running-condition maps (fretting.studies.running) against the closed forms of
docs/theory/displacement.md on Hertz: the loop opening, Fouvry's ratios, the transition displacement,
the quantities that do not depend on the datum, and the datum found from a measured loop."""

import numpy as np
import pytest

import fretting as fr
from fretting.physics.closed_forms import cattaneo_mindlin_compliance, mindlin_deresiewicz_energy
from fretting.studies import running

L = 5e-3


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=L, compliance=1e-12)


def opening(contact, Q_star):
    """Loop opening at Q = 0 of a partial-slip loop +-Q* (eq D9): ``2 (D(Q*) - 2 D(Q*/2))``."""
    D = cattaneo_mindlin_compliance
    return 2 * (D(contact, Q_star) - 2 * D(contact, Q_star / 2))


def test_transition_is_the_closed_form(contact):
    """``delta_t = K f P + f p0 a / (2 E_star)`` (eq D6) from the exact model's delta_Q at the onset of sliding."""
    fP = contact.f * contact.P
    expected = contact.displacement_compliance * fP + contact.f * contact.p0 * contact.a / (2 * contact.E_star)
    assert running.transition_displacement(contact) == pytest.approx(expected, rel=1e-12)


def test_partial_slip_loop(contact):
    """+-delta* below delta_t: the opening at Q = 0 is eq D9 to 1e-6 (a cubic through the steps of each
    branch), the energy Mindlin & Deresiewicz's, A and B their ratios to 4 Q* delta* and delta*."""
    star = 0.7 * running.transition_displacement(contact)
    loops = running.loop_cycles(fr.simulate(contact, running.sliding_cycles(star, 2), fr.models.Exact()))
    Q_star = loops.Q_amplitude.values
    assert np.allclose(loops.delta_amplitude.values, star, rtol=1e-12, atol=0)
    assert np.allclose(loops.loop_opening.values, opening(contact, Q_star), rtol=1e-6, atol=0)
    energy = np.array([mindlin_deresiewicz_energy(contact, Q) for Q in Q_star])
    assert np.allclose(loops.energy_ratio.values, energy / (4 * Q_star * star), rtol=1e-6, atol=0)
    assert np.allclose(loops.sliding_ratio.values, opening(contact, Q_star) / (2 * star), rtol=1e-6, atol=0)
    assert loops.cycle_regime.values.tolist() == [1, 1]


def test_gross_slip_loop(contact):
    """+-delta* beyond delta_t: Q* = f P, the opening is the slide ``2 (delta* - delta_t)`` plus eq D9 at
    f P, the energy eq D8, and the cycle's regime gross slip."""
    fP, delta_t = contact.f * contact.P, running.transition_displacement(contact)
    star = 1.8 * delta_t
    loops = running.loop_cycles(fr.simulate(contact, running.sliding_cycles(star, 2), fr.models.Exact()))
    assert np.array_equal(loops.Q_amplitude.values, [fP, fP])
    expected = 2 * (star - delta_t) + opening(contact, fP)
    assert np.allclose(loops.loop_opening.values, expected, rtol=1e-6, atol=0)
    energy = 4 * fP * (star - delta_t) + mindlin_deresiewicz_energy(contact, fP)
    assert np.allclose(loops.cycle_dissipation.values, energy, rtol=1e-6, atol=0)
    assert loops.cycle_regime.values.tolist() == [2, 2]


def test_what_does_not_depend_on_the_datum(contact):
    """One history of Q on two datums: Q*, the opening and the energy are the same; delta*, A and B differ."""
    fP = contact.f * contact.P
    cycle = fr.History.piecewise_linear([0.6 * fP, -0.6 * fP, 0.6 * fP], None, 32).as_cycle()
    history = fr.History.concatenate([fr.History.piecewise_linear([0, 0.6 * fP], None, 16), cycle, cycle])
    far = fr.Contact(contact.profile, contact.E_star, contact.f, contact.P, datum=40 * L, compliance=5e-12)
    near, away = (running.loop_cycles(fr.simulate(c, history, fr.models.Exact())) for c in (contact, far))
    for name in ("Q_amplitude", "cycle_dissipation"):
        assert np.array_equal(near[name].values, away[name].values), name
    assert np.allclose(near.loop_opening.values, away.loop_opening.values, rtol=1e-9, atol=0)
    for name in ("delta_amplitude", "energy_ratio", "sliding_ratio"):
        assert np.all(away[name].values / near[name].values - 1 > 0.1) or np.all(
            near[name].values / away[name].values - 1 > 0.1
        ), name


def test_running_map_boundary(contact):
    """Below each P's delta_t every point runs in partial slip, above it in gross slip, and the energy
    grows with delta*."""
    P = np.array([5e4, 1e5])
    boundary = [running.transition_displacement(running._at_load(contact, load)) for load in P]
    amplitudes = np.array([0.3, 0.9, 1.6]) * max(boundary)
    result = running.running_map(contact, P, amplitudes, cycles=1, steps=8)
    assert np.array_equal(result.transition.values, boundary)
    expected = np.where(amplitudes[None, :] > np.array(boundary)[:, None], 2, 1)
    assert np.array_equal(result.cycle_regime.values, expected)
    assert np.all(np.diff(result.cycle_dissipation.values, axis=1) > 0)


def test_datum_from_a_measured_loop(tmp_path, contact):
    """A loop computed on the datum L, written as CSV of delta and Q, gives back L and K (to 1e-9)."""
    fP = contact.f * contact.P
    Q = 0.5 * fP * np.sin(np.linspace(0, 4 * np.pi, 161))
    history = fr.History(Q, np.zeros(Q.size), [0, Q.size - 1])
    loop = fr.simulate(contact, history, fr.models.Exact())
    path = tmp_path / "loop.csv"
    np.savetxt(path, np.column_stack([loop.delta.values, loop.Q.values]), delimiter=",", header="delta,Q", comments="")
    guess = fr.Contact(contact.profile, contact.E_star, contact.f, contact.P, datum=2 * L, compliance=1e-12)
    datum, K = running.fit_datum(guess, *running.read_loop(path))
    assert datum == pytest.approx(L, rel=1e-9)
    assert K == pytest.approx(contact.displacement_compliance, rel=1e-9)
    path.write_text("delta,force\n1,2\n3,4\n5,6\n")
    with pytest.raises(ValueError, match=r"loop.csv: no column 'Q'"):
        running.read_loop(path)
