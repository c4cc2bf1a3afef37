"""Jaeger's superposition (fretting.physics.superposition) against the closed forms, against sums over ever finer
parts of its own increments, and its slip and energy density at points against its memory and its energy."""

import numpy as np
import pytest

import fretting as fr
from fretting.analysis.accuracy import monotonic_dissipation
from fretting.physics import closed_forms as cf
from fretting.physics import superposition
from fretting.physics.superposition import Hertz2D, Superposition

CONTACT = fr.Contact(fr.Hertz(0.05), 115e9, 0.5, 1e5)


def formed(contact=CONTACT):
    """The contact of `contact` formed at its load without shear."""
    return Superposition(Hertz2D(contact.profile, contact.E_star, contact.f), contact.P)


def loops(contact=CONTACT, ratio=1.05, steps=8):
    """``P = P0 (1 + 0.3 sin)``, ``Q = ratio 0.3 f P0 sin`` over half a cycle and a little (`steps` of 16 a cycle):
    a growing contact slipping at its edges above ``ratio = 1``, then receding under the reversed shear."""
    theta = 2 * np.pi * np.arange(steps + 1) / 16
    return contact.P * (1 + 0.3 * np.sin(theta)), ratio * 0.3 * contact.f * contact.P * np.sin(theta)


@pytest.mark.parametrize("psi", [0.2, 0.6, 0.95])
def test_at_constant_load_it_is_cattaneo_mindlin(psi):
    """Q = psi f P at the load the contact was formed at: McEwen/Cattaneo-Mindlin's traction and stick zone,
    and Mindlin's energy of the monotonic loading, in one increment or in 50, to rounding."""
    Q, c = psi * CONTACT.f * CONTACT.P, CONTACT
    x = np.linspace(-c.a, c.a, 201)
    once = formed()
    step = once.advance(c.P, Q)
    assert step.stick == pytest.approx(cf.stick_half_width(c, Q), rel=1e-12)
    np.testing.assert_allclose(
        once.memory.traction(x), cf.cattaneo_mindlin_traction(c, Q, x), rtol=0, atol=1e-12 * c.p0
    )
    assert step.energy == pytest.approx(monotonic_dissipation(c, Q), rel=1e-12)
    stepped = formed()
    energy = sum(stepped.advance(c.P, Q * k / 50).energy for k in range(1, 51))
    assert energy == pytest.approx(monotonic_dissipation(c, Q), rel=1e-12)


def test_proportional_loading_slips_nowhere_and_unloading_leaves_cattaneo_mindlin():
    """Q = lambda (P - P0) slips nowhere and carries lambda (p(P) - p(P0)) (Jaeger's rule); lowering the normal
    load to 0.8 P0 under the same Q leaves Cattaneo-Mindlin at the lower load."""
    c, lam = CONTACT, 0.3
    exact = formed()
    step = exact.advance(2 * c.P, lam * c.P)
    assert step.stick is None and step.energy == 0.0 and step.phases == ()
    raised = fr.Contact(c.profile, c.E_star, c.f, 2 * c.P)
    x = np.linspace(-raised.a, raised.a, 201)
    np.testing.assert_allclose(exact.memory.traction(x), lam * (raised.pressure(x) - c.pressure(x)), atol=1e-9 * c.p0)
    Q0 = 0.6 * c.f * c.P
    cm = formed()
    cm.advance(c.P, Q0)
    cm.advance(0.8 * c.P, Q0)
    lowered = fr.Contact(c.profile, c.E_star, c.f, 0.8 * c.P)
    x = np.linspace(-lowered.a, lowered.a, 201)
    np.testing.assert_allclose(
        cm.memory.traction(x), cf.cattaneo_mindlin_traction(lowered, Q0, x), rtol=0, atol=1e-7 * c.f * c.p0
    )  # both square roots at the stick end c: a rounding of c by 1e-16 a moves them by sqrt(1e-16)


def trapezoidal_energy(P, Q, parts):
    """The energy [J/m] of the increments through `P`, `Q` [N/m] from `P[0]`, each in `parts` equal parts, summed
    as ``2 int f (p_before + p_after) / 2 |s_after - s_before| dx`` over each part (the memories at the ends of
    the parts, the integral by the trapezoidal rule on 20001 points): independent of the energy `advance`
    integrates, and converging to it as the parts shrink."""
    exact, energy = formed(), 0.0
    exact.advance(P[0], Q[0])
    for k in range(1, len(P)):
        for u in np.arange(1, parts + 1) / parts:
            before, P_before = exact.memory, exact.P
            exact.advance(P[k - 1] + u * (P[k] - P[k - 1]), Q[k - 1] + u * (Q[k] - Q[k - 1]))
            x = np.linspace(0, max(before.a, exact.memory.a), 20001)
            p = (exact.hertz.pressure(x, P_before) + exact.hertz.pressure(x, exact.P)) / 2
            energy += 2 * np.trapezoid(CONTACT.f * p * np.abs(exact.memory.slip(x) - before.slip(x)), x)
    return energy


def test_energy_is_the_limit_of_the_parts():
    """`loops` above the limit ratio: the energy of each increment, its slip rate integrated, is the limit of
    sums over ever more parts of the slip each part adds times the mean pressure; their distance from it
    shrinks by more than 8 times for 4 times the parts (as the square of the parts: were the energy off, the
    distance would stall at that error), at 64 parts to within 1e-3."""
    P, Q = loops()
    exact = formed()
    energy = sum(exact.advance(float(p), float(q)).energy for p, q in zip(P[1:], Q[1:], strict=True))
    errors = [abs(trapezoidal_energy(P, Q, parts) / energy - 1) for parts in (4, 16, 64)]
    assert errors[0] > 8 * errors[1] > 64 * errors[2]
    assert errors[2] < 1e-3


@pytest.mark.parametrize("ratio", [1.05, 0.9])
def test_phases_give_the_slip_of_the_memory_and_the_energy_at_points(ratio):
    """Along `loops` (above the limit ratio, and below it: there the contact slips only as it recedes), the
    slip `Phase.at` integrates at points in contact over a whole increment is the change of the memory's slip
    there, and twice the integral of its energy density over ``x > 0`` (the trapezoidal rule on 40001 points
    from the stick end) is the increment's energy."""
    P, Q = loops(ratio=ratio, steps=12)
    exact = formed()
    slipped = 0
    for p, q in zip(P[1:], Q[1:], strict=True):
        before = exact.memory
        step = exact.advance(float(p), float(q))
        if step.stick is None:
            continue
        x = np.linspace(step.stick, max(before.a, exact.memory.a), 40001)
        ds, w = np.zeros(x.size), np.zeros(x.size)
        for phase in step.phases:
            slip, density = phase.at(x)
            ds, w = ds + slip, w + density
        inside = x < min(before.a, exact.memory.a)
        scale = np.max(np.abs(exact.memory.slip(x[inside])))
        np.testing.assert_allclose(ds[inside], (exact.memory.slip(x) - before.slip(x))[inside], atol=1e-12 * scale)
        assert 2 * np.trapezoid(w, x) == pytest.approx(step.energy, rel=1e-7)
        slipped += 1
    assert slipped >= 4


def test_delta_Q_is_the_slip_weighted_by_the_flat_punch():
    """``delta_Q = int s / (pi sqrt(a^2 - x^2)) dx`` of the memory after a receding, reversed and growing history:
    its quadrature per band against Gauss-Chebyshev's on 2e5 points (the slip kinks at the band edges, which
    that rule does not see, so it converges slowly)."""
    exact, P0, fP0 = formed(), CONTACT.P, CONTACT.f * CONTACT.P
    for P, Q in [(P0, 0.3 * fP0), (0.8 * P0, 0.2 * fP0), (1.2 * P0, -0.1 * fP0), (1.1 * P0, 0.25 * fP0)]:
        exact.advance(P, Q)
        memory = exact.memory
        theta = (np.arange(200000) + 0.5) * np.pi / 200000
        assert memory.delta_Q() == pytest.approx(np.mean(memory.slip(memory.a * np.cos(theta))), rel=1e-9)


@pytest.mark.parametrize("ratio", [1.05, 0.9])
def test_half_the_quadrature_points_change_the_energy_by_rounding_only(ratio, monkeypatch):
    """The energy of every increment of `loops` (above the limit ratio, and below it) with half the module's
    Gauss-Legendre points: the same to 1e-13 of the history's, as the quadratures' smooth integrands make it."""
    P, Q = loops(ratio=ratio, steps=12)

    def energies():
        exact = formed()
        return np.array([exact.advance(float(p), float(q)).energy for p, q in zip(P[1:], Q[1:], strict=True)])

    full = energies()
    for name, value in zip(
        ("_U", "_W", "_SIN", "_COS", "_WPHI"), superposition.rule(superposition.POINTS // 2), strict=True
    ):
        monkeypatch.setattr(superposition, name, value)
    assert full.sum() > 0
    np.testing.assert_allclose(energies(), full, rtol=0, atol=1e-13 * full.sum())


def test_gross_slip_is_refused():
    """|Q| past f P leaves no stick zone: a ValueError, the memory left as it was."""
    exact = formed()
    before = exact.memory
    with pytest.raises(ValueError, match="gross sliding"):
        exact.advance(CONTACT.P, 1.01 * CONTACT.f * CONTACT.P)
    assert exact.memory is before
