"""Jaeger's superposition (fretting.physics.superposition) against the closed forms, against sums over ever finer
parts of its own increments, and its slip and energy density at points against its memory and its energy; on
Hertz and on a rounded flat, whose quadratures are checked against Hertz's closed forms too."""

from decimal import Decimal, getcontext

import numpy as np
import pytest

import fretting as fr
from fretting.analysis.accuracy import monotonic_dissipation
from fretting.physics import closed_forms as cf
from fretting.physics import superposition
from fretting.physics.superposition import Geometry, Superposition, geometry

CONTACT = fr.Contact(fr.Hertz(0.05), 115e9, 0.5, 1e5)
#: A flat half as wide as `CONTACT`'s contact with its corners: under the same load its contact is 2.7 flats wide.
FLAT = fr.Contact(fr.RoundedFlat(0.5 * CONTACT.a, 0.05), 115e9, 0.5, 1e5)
BOTH = pytest.mark.parametrize("contact", [CONTACT, FLAT], ids=["hertz", "flat"])


def formed(contact=CONTACT):
    """The superposition of `contact` formed at its load without shear."""
    return Superposition(geometry(contact.profile, contact.E_star, contact.f), contact.P)


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


@pytest.mark.parametrize("psi", [0.2, 0.6, 0.95])
def test_on_a_rounded_flat_at_constant_load_it_is_ciavarella_and_jaeger(psi):
    """Q = psi f P on the rounded flat: the traction ``f (p(P) - p(P - Q/f))`` and the stick zone of the
    corrective contact (Ciavarella 1998, Jaeger 1998), to rounding; the energy of one increment that of fifty."""
    Q, c = psi * FLAT.f * FLAT.P, FLAT
    x = np.linspace(-c.a, c.a, 201)
    once = formed(c)
    step = once.advance(c.P, Q)
    traction, corrective = cf.ciavarella_jaeger(c, Q, x)
    assert step.stick == pytest.approx(corrective.a, rel=1e-12)
    np.testing.assert_allclose(once.memory.traction(x), traction, rtol=0, atol=1e-12 * c.p0)
    stepped = formed(c)
    energy = sum(stepped.advance(c.P, Q * k / 50).energy for k in range(1, 51))
    assert energy == pytest.approx(step.energy, rel=1e-12)


def hertz_punch_energy(c, a, contact=CONTACT):
    """``(pi E_star / 4R) (a^2 ln(a / c) / 2 - (a^2 - c^2) / 4)`` [N] at the half-widths `c` [m], in 50-digit
    decimals: its two terms cancel as ``c`` nears ``a``."""
    getcontext().prec = 50
    A, scale = Decimal(a), Decimal(np.pi * contact.E_star / (4 * contact.profile.R))
    terms = [scale * (A * A * (A / Decimal(v)).ln() / 2 - (A * A - Decimal(v) ** 2) / 4) for v in np.ravel(c)]
    return np.reshape(np.array(terms, dtype=float), np.shape(c))


def test_the_quadratures_on_a_hertz_profile_are_its_closed_forms():
    """`Geometry`'s quadratures (of a rounded flat's) given a Hertz profile: the half-width, the pressure, the slip
    of bands and their compliance of `HertzGeometry`'s closed forms, and the punch energy of its closed form on
    Hertz, ``(pi E_star / 4R) (a^2 ln(a / c) / 2 - (a^2 - c^2) / 4)`` (`hertz_punch_energy`), to 1e-13."""
    closed, quadrature = (
        geometry(CONTACT.profile, CONTACT.E_star, CONTACT.f),
        Geometry(CONTACT.profile, CONTACT.E_star, CONTACT.f),
    )
    a, P = CONTACT.a, CONTACT.P * np.array([0.1, 0.5, 1.0, 2.0])
    c, x = a * np.array([0.1, 0.5, 0.9, 0.999])[:, None], a * np.array([0.3, 0.6, 0.95, 1.0, 1.3])
    np.testing.assert_allclose(quadrature.half_width(P), closed.half_width(P), rtol=1e-13)
    X = np.linspace(0, 1.1 * a, 50)[:, None]
    np.testing.assert_allclose(quadrature.pressure(X, P), closed.pressure(X, P), rtol=0, atol=1e-13 * CONTACT.p0)
    slip = closed.slip(c, x)
    np.testing.assert_allclose(quadrature.slip(c, x), slip, rtol=0, atol=1e-13 * np.max(slip))
    np.testing.assert_allclose(quadrature.punch_energy(c, a), hertz_punch_energy(c, a), rtol=1e-13)
    np.testing.assert_allclose(quadrature.compliance(c / 2, c, a), closed.compliance(c / 2, c, a), rtol=1e-13)


@BOTH
def test_proportional_loading_slips_nowhere_and_unloading_leaves_cattaneo_mindlin(contact):
    """Q = lambda (P - P0) slips nowhere and carries lambda (p(P) - p(P0)) (Jaeger's rule); lowering the normal
    load to 0.8 P0 under the same Q leaves Cattaneo-Mindlin at the lower load (Ciavarella-Jaeger's on the flat)."""
    c, lam = contact, 0.3
    exact = formed(c)
    step = exact.advance(2 * c.P, lam * c.P)
    assert step.stick is None and step.energy == 0.0 and step.phases == ()
    raised = fr.Contact(c.profile, c.E_star, c.f, 2 * c.P)
    x = np.linspace(-raised.a, raised.a, 201)[1:-1]  # at the edge, the flat's p ~ sqrt(a - x) magnifies a's rounding
    np.testing.assert_allclose(exact.memory.traction(x), lam * (raised.pressure(x) - c.pressure(x)), atol=1e-9 * c.p0)
    Q0 = 0.6 * c.f * c.P
    cm = formed(c)
    cm.advance(c.P, Q0)
    cm.advance(0.8 * c.P, Q0)
    lowered = fr.Contact(c.profile, c.E_star, c.f, 0.8 * c.P)
    x = np.linspace(-lowered.a, lowered.a, 201)
    np.testing.assert_allclose(
        cm.memory.traction(x), cf.ciavarella_jaeger(lowered, Q0, x)[0], rtol=0, atol=1e-7 * c.f * c.p0
    )  # both square roots at the stick end c: a rounding of c by 1e-16 a moves them by sqrt(1e-16)


def trapezoidal_energy(contact, P, Q, parts):
    """The energy [J/m] of the increments through `P`, `Q` [N/m] from `P[0]`, each in `parts` equal parts, summed
    as ``2 int f (p_before + p_after) / 2 |s_after - s_before| dx`` over each part (the memories at the ends of
    the parts, the integral by the trapezoidal rule on 10001 points over the largest contact): independent of the
    energy `advance` integrates, and converging to it as the parts shrink."""
    exact, energy = formed(contact), 0.0
    exact.advance(P[0], Q[0])
    x = np.linspace(0, float(exact.geometry.half_width(np.max(P))), 10001)
    p, s = exact.geometry.pressure(x, exact.P), exact.memory.slip(x)
    for k in range(1, len(P)):
        for u in np.arange(1, parts + 1) / parts:
            exact.advance(P[k - 1] + u * (P[k] - P[k - 1]), Q[k - 1] + u * (Q[k] - Q[k - 1]))
            p_after, s_after = exact.geometry.pressure(x, exact.P), exact.memory.slip(x)
            energy += 2 * np.trapezoid(contact.f * (p + p_after) / 2 * np.abs(s_after - s), x)
            p, s = p_after, s_after
    return energy


@BOTH
def test_energy_is_the_limit_of_the_parts(contact):
    """`loops` above the limit ratio: the energy of each increment, its slip rate integrated, is the limit of
    sums over ever more parts of the slip each part adds times the mean pressure; their distance from it
    shrinks by more than 8 times for 4 times the parts (as the square of the parts: were the energy off, the
    distance would stall at that error), at 64 parts to within 1e-3."""
    P, Q = loops(contact)
    exact = formed(contact)
    energy = sum(exact.advance(float(p), float(q)).energy for p, q in zip(P[1:], Q[1:], strict=True))
    errors = [abs(trapezoidal_energy(contact, P, Q, parts) / energy - 1) for parts in (4, 16, 64)]
    assert errors[0] > 8 * errors[1] > 64 * errors[2]
    assert errors[2] < 1e-3


@BOTH
@pytest.mark.parametrize("ratio", [1.05, 0.9])
def test_phases_give_the_slip_of_the_memory_and_the_energy_at_points(contact, ratio):
    """Along `loops` (above the limit ratio, and below it: there the contact slips only as it recedes), the
    slip `Phase.at` integrates at points in contact over a whole increment is the change of the memory's slip
    there, and twice the integral of its energy density over ``x > 0`` (the trapezoidal rule on 10001 points
    from the stick end) is the increment's energy."""
    P, Q = loops(contact, ratio=ratio, steps=12)
    exact = formed(contact)
    slipped = 0
    for p, q in zip(P[1:], Q[1:], strict=True):
        before = exact.memory
        step = exact.advance(float(p), float(q))
        if step.stick is None:
            continue
        x = np.linspace(step.stick, max(before.a, exact.memory.a), 10001)
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


@BOTH
def test_delta_Q_is_the_slip_weighted_by_the_flat_punch(contact):
    """``delta_Q = int s / (pi sqrt(a^2 - x^2)) dx`` of the memory after a receding, reversed and growing history:
    its quadrature per band against Gauss-Chebyshev's on 2e5 points (the slip kinks at the band edges, which
    that rule does not see, so it converges slowly)."""
    exact, P0, fP0 = formed(contact), contact.P, contact.f * contact.P
    for P, Q in [(P0, 0.3 * fP0), (0.8 * P0, 0.2 * fP0), (1.2 * P0, -0.1 * fP0), (1.1 * P0, 0.25 * fP0)]:
        exact.advance(P, Q)
        memory = exact.memory
        theta = (np.arange(200000) + 0.5) * np.pi / 200000
        assert memory.delta_Q() == pytest.approx(np.mean(memory.slip(memory.a * np.cos(theta))), rel=1e-9)


@BOTH
@pytest.mark.parametrize("ratio", [1.05, 0.9])
def test_half_the_quadrature_points_change_the_energy_by_rounding_only(contact, ratio, monkeypatch):
    """The energy of every increment of `loops` (above the limit ratio, and below it) with half the module's
    Gauss-Legendre points: the same to 1e-13 of the history's, as the quadratures' smooth integrands make it."""
    P, Q = loops(contact, ratio=ratio, steps=12)

    def energies():
        exact = formed(contact)
        return np.array([exact.advance(float(p), float(q)).energy for p, q in zip(P[1:], Q[1:], strict=True)])

    full = energies()
    for name, value in zip(
        ("_U", "_W", "_SIN", "_COS", "_WPHI"), superposition.rule(superposition.POINTS // 2), strict=True
    ):
        monkeypatch.setattr(superposition, name, value)
    assert full.sum() > 0
    np.testing.assert_allclose(energies(), full, rtol=0, atol=1e-13 * full.sum())


@BOTH
def test_gross_slip_is_refused(contact):
    """|Q| past f P leaves no stick zone: a ValueError, the memory left as it was."""
    exact = formed(contact)
    before = exact.memory
    with pytest.raises(ValueError, match="gross sliding"):
        exact.advance(contact.P, 1.01 * contact.f * contact.P)
    assert exact.memory is before
