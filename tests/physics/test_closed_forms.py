"""The engine against published closed forms, at default settings.

Targets of the core-engine issue: stick-zone ends within 1e-3 a; traction within 1e-3 f p0
away from the stick/slip boundaries; slip within 1e-3 of its maximum. "Away" excludes
0.02 a around each boundary: the traction has a square-root kink there, and the discrete
boundary sits up to a fraction of a node spacing (0.012 a at the centre with 256 nodes) from
the true one.
"""

import math

import numpy as np
import pytest
from checks import BOUNDARY_BAND, away_from, zones
from conftest import final
from scipy import integrate

import fretting as fr
from fretting.physics import closed_forms as cf


@pytest.mark.parametrize("psi", [0.05, 0.2, 0.5, 0.8, 0.95])
def test_cattaneo_mindlin(hertz, psi):
    Q = psi * hertz.f * hertz.P
    result = final(hertz, Q)
    x, a = result.x.values, hertz.a
    b = cf.stick_half_width(hertz, Q)
    np.testing.assert_allclose(zones(result), [[-b, b]], rtol=0, atol=1e-3 * a)
    band = away_from(x, [-b, b], a)
    q_exact = cf.cattaneo_mindlin_traction(hertz, Q, x)
    assert np.max(np.abs(result.q.values - q_exact)[band]) < 1e-3 * hertz.f * hertz.p0
    slip_exact = cf.cattaneo_mindlin_slip(hertz, Q, x)
    assert np.max(np.abs(result.slip.values - slip_exact)) < 1e-3 * slip_exact.max()
    assert np.all(result.slip.values[np.abs(x) < b - BOUNDARY_BAND * a] == 0)


@pytest.mark.parametrize("Q_end", [0.3, -0.2, -0.7])
def test_mindlin_deresiewicz_unloading(hertz, Q_end):
    fP = hertz.f * hertz.P
    Q_star = 0.8 * fP
    history = fr.History.piecewise_linear([0, Q_star, Q_end * fP], None, [8, 16])
    result = fr.simulate(hertz, history).isel(step=-1)
    x, a = result.x.values, hertz.a
    c = a * np.sqrt(1 - (Q_star - Q_end * fP) / (2 * fP))
    b = cf.stick_half_width(hertz, Q_star)
    np.testing.assert_allclose(zones(result), [[-c, c]], rtol=0, atol=1e-3 * a)
    band = away_from(x, [-c, c, -b, b], a)
    q_exact = cf.mindlin_deresiewicz_traction(hertz, Q_star, Q_end * fP, x)
    assert np.max(np.abs(result.q.values - q_exact)[band]) < 1e-3 * hertz.f * hertz.p0
    slip_exact = cf.mindlin_deresiewicz_slip(hertz, Q_star, Q_end * fP, x)
    assert np.max(np.abs(result.slip.values - slip_exact)) < 1e-3 * np.abs(slip_exact).max()


@pytest.mark.parametrize("tau", [0.3, 1.0, 2.5])
def test_bulk_tension_alone(hertz, tau):
    sigma = tau * hertz.f * hertz.p0
    result = final(hertz, 0.0, sigma)
    b = cf.bulk_tension_stick_half_width(hertz, sigma)
    np.testing.assert_allclose(zones(result), [[-b, b]], rtol=0, atol=1e-3 * hertz.a)
    # Seed section 3.2: the slip and the traction are odd in x.
    np.testing.assert_allclose(result.slip.values, -result.slip.values[::-1], rtol=0, atol=1e-12 * hertz.a)
    np.testing.assert_allclose(result.q.values, -result.q.values[::-1], rtol=0, atol=1e-9 * hertz.p0)


@pytest.mark.parametrize(("psi", "tau"), [(0.5, 0.5), (0.4, 0.8), (0.7, -0.3), (-0.5, 0.6)])
def test_nowell_hills_shear_with_tension(hertz, psi, tau):
    Q, sigma = psi * hertz.f * hertz.P, tau * hertz.f * hertz.p0
    result = final(hertz, Q, sigma)
    x, a = result.x.values, hertz.a
    b = cf.stick_half_width(hertz, Q)
    e = np.sign(Q) * cf.nowell_hills_offset(hertz, sigma)
    np.testing.assert_allclose(zones(result), [[e - b, e + b]], rtol=0, atol=1e-3 * a)
    band = away_from(x, [e - b, e + b], a)
    q_exact = cf.nowell_hills_traction(hertz, Q, sigma, x)
    assert np.max(np.abs(result.q.values - q_exact)[band]) < 1e-3 * hertz.f * hertz.p0


@pytest.mark.parametrize("psi", [0.2, 0.6, 0.9])
def test_rounded_flat_ciavarella_jaeger(psi):
    contact = fr.Contact(fr.RoundedFlat(b=1e-3, R=0.02), 115e9, 0.5, 3e5)
    Q = psi * contact.f * contact.P
    result = final(contact, Q)
    x, a = result.x.values, contact.a
    q_exact, corrective = cf.ciavarella_jaeger(contact, Q, x)
    c = corrective.a
    np.testing.assert_allclose(zones(result), [[-c, c]], rtol=0, atol=1e-3 * a)
    band = away_from(x, [-c, c], a)
    assert np.max(np.abs(result.q.values - q_exact)[band]) < 1e-3 * contact.f * contact.p0


def test_sharp_flat_punch_never_slips():
    contact = fr.Contact(fr.FlatPunch(2e-3), 115e9, 0.5, 3e5)
    fP = contact.f * contact.P
    history = fr.History.piecewise_linear([0, 0.99 * fP, -0.99 * fP, 0.5 * fP], None, 10)
    result = fr.simulate(contact, history)
    assert np.all(result.slip.values == 0)
    assert np.all(result.stick.values)
    assert np.all(result.dissipation.values == 0)
    # q = Q / (pi sqrt(a^2 - x^2)) = (Q / fP) f p: the utilisation q / (f p) is Q / fP at every node
    inner = np.abs(result.x.values) < contact.a  # the edges, where both are unbounded, carry q = p = 0
    utilisation = result.q.values[:, inner] / (contact.f * result.p.values[inner])
    np.testing.assert_allclose(utilisation, np.outer(result.Q.values / fP, np.ones(inner.sum())), rtol=0, atol=1e-12)
    assert np.all(result.q.values[:, ~inner] == 0)


@pytest.mark.slow
def test_si_and_unit_free_inputs_agree(hertz, unit_hertz):
    """Normalised by a, f p0 and f p0 a / E_star, the two scenes are the same problem."""
    history = [0, 0.7, -0.4, 0.5], [0, 0.3, -0.2, 0.6]

    def normalised(contact):
        fP, fp0 = contact.f * contact.P, contact.f * contact.p0
        path = fr.History.piecewise_linear(np.array(history[0]) * fP, np.array(history[1]) * fp0, 6)
        r = fr.simulate(contact, path)
        slip_scale = fp0 * contact.a / contact.E_star
        return r.q.values / fp0, r.slip.values / slip_scale, r.stick_end.values / contact.a

    for si, unit_free in zip(normalised(hertz), normalised(unit_hertz), strict=True):
        np.testing.assert_allclose(si, unit_free, rtol=0, atol=1e-9)


# -- The closed forms of the energy, checked against their derivations --------------------------


def mean_slip(contact, Q):
    """``(1/pi) int_0^pi s(a cos th) dth`` of `cattaneo_mindlin_slip` by quadrature [m]."""
    kink = math.acos(float(cf.stick_half_width(contact, Q)) / contact.a)
    slip = lambda th: float(cf.cattaneo_mindlin_slip(contact, Q, contact.a * math.cos(th)))  # noqa: E731
    return (
        integrate.quad(slip, 0, math.pi, points=[kink, math.pi - kink], epsabs=0, epsrel=1e-11, limit=200)[0] / math.pi
    )


@pytest.mark.parametrize(
    ("psi", "rel"),
    [(0.001, 1e-12), (0.01, 1e-12), (0.2, 1e-12), (0.3, 1e-12), (0.6, 1e-12), (0.9, 1e-12), (0.95, 1e-12)],
)
def test_compliance_is_the_mean_slip_of_cattaneo_mindlin(hertz, psi, rel):
    """Also at 0.001, where the slip zones are 5e-4 a thin (`cf.hertz_slip_shape` does not cancel)."""
    Q = psi * hertz.f * hertz.P
    assert cf.cattaneo_mindlin_compliance(hertz, Q) == pytest.approx(mean_slip(hertz, Q), rel=rel)
    assert cf.cattaneo_mindlin_compliance(hertz, -Q) == -cf.cattaneo_mindlin_compliance(hertz, Q)


@pytest.mark.parametrize("X", [1 + 1e-14, 1 + 1e-9, 1 + 1e-4, 1.1, 1.118, 1.119, 2.0, 1e3])
def test_hertz_slip_shape_is_its_integral_without_cancellation(X):
    """``X sqrt(X^2 - b^2) - b^2 arccosh(X / b) = 2 b^2 int_0^z t^2 / sqrt(1 + t^2) dt`` with
    ``z = sqrt(X^2 - b^2) / b`` (its derivative in ``X`` is ``2 sqrt(X^2 - b^2)``, eq 19), by
    adaptive quadrature, to 1e-13 of itself from ``X - b = 1e-14 b``, where the closed form's two
    terms are 1e13 times their difference, to ``1e3 b``, on both sides of the series' threshold
    (``z = 1/2`` at ``X = 1.118 b``); zero at ``X = b`` and ``X^2`` for ``b = 0``."""
    b = 3e-4
    z = math.sqrt((X - 1) * (X + 1))
    integral = 2 * b**2 * integrate.quad(lambda t: t**2 / math.sqrt(1 + t**2), 0, z, epsabs=0, epsrel=1e-13)[0]
    assert cf.hertz_slip_shape(np.array([X * b, -X * b]), b) == pytest.approx(integral, rel=1e-13)
    assert cf.hertz_slip_shape(b, b) == 0
    assert cf.hertz_slip_shape(X * b, 0.0) == (X * b) ** 2


@pytest.mark.parametrize("psi", [0.02, 0.05, 0.3, 0.5, 0.8, 0.9])
def test_cycle_energy_is_the_area_of_the_masing_loop(hertz, psi):
    """Mindlin-Deresiewicz ``W = 4 Q* dv(Q*) - 8 int_0^Q* dv``, the loop of ``Q`` against the
    compliance, by quadrature; and the logarithm form ``(2 fP f p0 a / E_star) ((1 - psi)
    ln(1 - psi) + psi - psi^2 / 2)``."""
    fP = hertz.f * hertz.P
    Q_star = psi * fP
    dv = lambda Q: cf.cattaneo_mindlin_compliance(hertz, Q)  # noqa: E731
    loop = 4 * Q_star * dv(Q_star) - 8 * integrate.quad(dv, 0, Q_star, epsabs=0, epsrel=1e-12)[0]
    W = cf.mindlin_deresiewicz_energy(hertz, Q_star)
    assert W == pytest.approx(loop, rel=1e-9)
    scale = 2 * fP * hertz.f * hertz.p0 * hertz.a / hertz.E_star
    assert W == pytest.approx(scale * ((1 - psi) * np.log1p(-psi) + psi - psi**2 / 2), rel=1e-12)


@pytest.mark.parametrize("psi", [1e-4, 1e-3, 1e-2])
def test_small_loops_dissipate_as_the_cube_of_the_amplitude(hertz, psi):
    """``W = (pi (f p0 a)^2 / E_star) psi^3 / 6 (1 + psi / 2 + 3 psi^2 / 10 + ...)``."""
    cubic = math.pi * (hertz.f * hertz.p0 * hertz.a) ** 2 / hertz.E_star * psi**3 / 6
    W = cf.mindlin_deresiewicz_energy(hertz, psi * hertz.f * hertz.P)
    assert W == pytest.approx(cubic * (1 + psi / 2), rel=psi**2)
    assert W / cubic - 1 == pytest.approx(psi / 2 + 3 * psi**2 / 10, rel=psi)


def test_masing_walk_keeps_and_erases_turning_points():
    """0 -> 6 -> -4 -> 2 -> -4 (loop closed) -> -6 (past -Q_1: virgin again) -> 0."""
    Q = [0, 3, 6, 1, -4, 2, -1, -4, -6, 0]
    stacks, pieces = cf.masing_walk(Q)
    assert stacks == [(), (), (), (6,), (6,), (6, -4), (6, -4, 2), (6,), (), (-6,)]
    assert pieces[1] == [(0.0, 1, 0, 3)]
    assert pieces[4] == [(6, 2, 1, -4)]
    assert pieces[7] == [(2, 2, -1, -4), (6, 2, -4, -4)]  # reaches -4: the minor loop closes there
    assert pieces[8] == [(6, 2, -4, -6), (0.0, 1, -6, -6)]
    with pytest.raises(ValueError, match="virgin state"):
        cf.masing_walk([1.0, 2.0])
