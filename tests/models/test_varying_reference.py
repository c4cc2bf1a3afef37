"""The exact reference of the varying-load benchmark (benchmarks/jaeger.py) against the package's closed forms,
and the varying-load model's energy on a history that slips nowhere, whatever ``f`` (issue 38)."""

from types import SimpleNamespace

import numpy as np
import pytest
from harness import hertz_contact
from jaeger import Jaeger
from varying_accuracy import ExactRun, PackageRun, boundary, extrapolated

import fretting as fr
from fretting.analysis.accuracy import monotonic_dissipation
from fretting.models.normal import Varying
from fretting.physics import closed_forms as cf

CONTACT = fr.Contact(fr.Hertz(0.05), 115e9, 0.5, 1e5)


def jaeger(contact=CONTACT):
    return Jaeger(contact.profile.R, contact.E_star, contact.f, contact.P)


@pytest.mark.parametrize("psi", [0.2, 0.6, 0.95])
def test_jaeger_at_constant_load_is_cattaneo_mindlin(psi):
    """Q = psi f P at the load the contact was formed at: McEwen/Cattaneo-Mindlin's traction and stick zone,
    and Mindlin's energy of the monotonic loading, in one increment or in 50."""
    Q, c = psi * CONTACT.f * CONTACT.P, CONTACT
    x = np.linspace(-c.a, c.a, 201)
    once = jaeger()
    step = once.advance(c.P, Q)
    assert step.stick == pytest.approx(cf.stick_half_width(c, Q), rel=1e-12)
    np.testing.assert_allclose(
        once.memory.traction(x), cf.cattaneo_mindlin_traction(c, Q, x), rtol=0, atol=1e-12 * c.p0
    )
    assert step.energy == pytest.approx(monotonic_dissipation(c, Q), rel=1e-12)
    stepped = jaeger()
    energy = sum(stepped.advance(c.P, Q * k / 50).energy for k in range(1, 51))
    assert energy == pytest.approx(monotonic_dissipation(c, Q), rel=1e-5)


def test_jaeger_proportional_loading_and_cattaneo_mindlin_after_unloading():
    """Q = lambda (P - P0) slips nowhere and carries lambda (p(P) - p(P0)); unloading the normal load to 0.8 P0
    under the same Q leaves Cattaneo-Mindlin at the lower load (tests/models/test_normal_load.py, on the package)."""
    c, lam = CONTACT, 0.3
    exact = jaeger()
    step = exact.advance(2 * c.P, lam * c.P)
    assert step.stick is None and step.energy == 0.0
    raised = fr.Contact(c.profile, c.E_star, c.f, 2 * c.P)
    x = np.linspace(-raised.a, raised.a, 201)
    np.testing.assert_allclose(exact.memory.traction(x), lam * (raised.pressure(x) - c.pressure(x)), atol=1e-9 * c.p0)
    Q0 = 0.6 * c.f * c.P
    cm = jaeger()
    cm.advance(c.P, Q0)
    cm.advance(0.8 * c.P, Q0, parts=64)
    lowered = fr.Contact(c.profile, c.E_star, c.f, 0.8 * c.P)
    x = np.linspace(-lowered.a, lowered.a, 201)
    np.testing.assert_allclose(
        cm.memory.traction(x), cf.cattaneo_mindlin_traction(lowered, Q0, x), rtol=0, atol=1e-7 * c.f * c.p0
    )  # both square roots at the stick end c: a rounding of c by 1e-16 a moves them by sqrt(1e-16)


def dovetail(f, cells=384):
    """The contact and energy [J/m] of the in-phase cycle of fretting/examples/hertz_dovetail_cycle.toml
    (``|dQ| / dP = 0.75``) at friction `f`, on `cells` cells."""
    contact = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), f, 6e4)
    history = fr.History.sinusoidal(
        3e4, 50e6, 0, 1, 16, 3e4, 50e6, ramp_steps=4, P_mean=1e5, P_amplitude=4e4, start=(0.0, 0.0, 6e4)
    )
    return contact, float(fr.simulate(contact, history, model=Varying(cells)).total_dissipation)


def test_energy_of_a_history_that_slips_nowhere_does_not_grow_with_f():
    """At f = 1e3 and 1e10 the dovetail cycle slips nowhere (Jaeger); what its leaving nodes slip by rounding
    (384 cells: some do) dissipates the same at both, below 1e-15 of the energy scale ``pi (p0 a)^2 / (4 E_star)``
    of friction 1 (at 1e10 it was 1e7 times that at 1e3, 3.5e-10 J/m: proportional to f)."""
    contact, low = dovetail(1e3)
    _, high = dovetail(1e10)
    assert high == pytest.approx(low, rel=1e-6, abs=1e-300)
    assert high < 1e-15 * np.pi * (contact.p0 * contact.a) ** 2 / (4 * contact.E_star)


def test_stick_zone_at_the_limit_ratio_is_one_zone_with_jaeger_s_ends():
    """In-phase loops at ``|dQ/dP| = 0.98 f`` then 1.02 f about a mean shear (benchmarks/varying_accuracy.py,
    ``boundary``): the bands that entered at the limit ratio ``f`` stay at the limit without slipping, and the
    solver moves them by its rounding only; read as slip, those nodes split the stick zone (one step's end was
    off by 2.5e-2 a). Every step has one stick zone, its ends within the promised 1e-3 a of Jaeger's."""
    contact = hertz_contact()
    history = boundary(contact, cycles=1)
    result = fr.simulate(contact, history, model=Varying())
    assert np.all(np.sum(~np.isnan(result.stick_start.values), axis=1) == 1)
    own, exact = PackageRun(result), ExactRun(contact, history, 64)
    for k in range(1, len(history)):
        for found, expected in zip(own.ends(k), exact.ends(k), strict=True):
            assert abs(found - expected) < 1e-3 * result.a.values[k]


def test_extrapolated_energy_removes_the_error_of_the_parts():
    """`varying_accuracy.extrapolated`: energies converging as ``n^-p`` in the parts ``n`` are extrapolated to their
    limit; on Jaeger's runs of a growing contact slipping at its edges (``|dQ/dP| = 1.05 f``), the extrapolation
    from 16, 32 and 64 parts per step lies nearer the run of 512 parts than the run of 64 does, by at least five
    times."""
    limit, C, p = np.array([0.0, 1.0, 3.0]), np.array([0.0, 0.2, 0.5]), 1.4
    runs = [SimpleNamespace(energy=limit + C * n**-p) for n in (16, 32, 64)]
    reference, order = extrapolated(runs)
    assert order == pytest.approx(p, rel=1e-12)
    assert reference.energy == pytest.approx(limit, rel=1e-12)
    assert runs[-1].energy[-1] != limit[-1]  # the runs are not changed

    contact = hertz_contact()
    theta = 2 * np.pi * np.arange(5) / 16
    P, Q = contact.P * (1 + 0.3 * np.sin(theta)), 1.05 * 0.3 * contact.f * contact.P * np.sin(theta)
    history = fr.History(Q, 0 * Q, np.array([0]), np.zeros(Q.size, dtype=np.int64), P)
    runs = [ExactRun(contact, history, n) for n in (16, 32, 64)]
    fine = ExactRun(contact, history, 512)
    reference, _ = extrapolated(runs)
    assert np.max(np.abs(reference.energy - fine.energy)) < np.max(np.abs(runs[-1].energy - fine.energy)) / 5
