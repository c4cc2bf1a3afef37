"""Issue 6, numerical stability on hard cases: the engine at its default settings.

Every case runs through the public API with no resolution argument, ``fretting.simulate(contact,
history)``, and is checked against a closed form or a reference derived here, never against
the engine itself. A failure is a bug in the engine, never a reason to loosen a check.

"Resolved" means the same thing throughout: a feature (a stick zone of half-width ``b``, the
strip ``c - b`` between a stick-zone end and the end of a flat, a slip zone of width ``w``) is
located to 1 % of its own size, and never more loosely than the project's 1e-3 a. Tractions
and slips away from stick/slip boundaries keep the project's 1e-3 (of ``f p0``, of the largest
slip) of tests/physics/test_closed_forms.py.
"""

import functools
import warnings

import numpy as np
import pytest
import xarray as xr
from checks import (
    BOUNDARY_BAND,
    PROJECT,
    RESOLVED,
    assert_friction_conditions,
    assert_zone_ends_are_consistent,
    assert_zones,
    away_from,
    increments,
    simulate_as_a_user,
    zones,
)
from conftest import HERTZ_TOML
from harness import asymmetric_flat, hard_rounded_flat
from scipy import integrate, interpolate, optimize, special

import fretting as fr
from fretting import cli
from fretting.engine import runner
from fretting.models.galerkin import initial_theta
from fretting.physics import closed_forms as cf


def proportional(contact, psi, tau=0.0, steps=8, **model):
    """Result of a straight path from the virgin contact to ``Q = psi f P``, ``sigma = tau f p0``.

    `model`: keyword arguments of `fretting.simulate` that choose the model (the default if none).
    """
    history = fr.History.piecewise_linear(
        [0.0, psi * contact.f * contact.P], [0.0, tau * contact.f * contact.p0], steps
    )
    return fr.simulate(contact, history, **model)


# ----------------------------------------------------------------------------------------------
# Shear close to sliding: Hertz, Q/fP = 0.999 and 0.999999 (stick zone 0.032 a and 0.001 a)


@pytest.mark.slow
@pytest.mark.parametrize("model", [{}, {"rtol": fr.DEFAULT_RTOL}], ids=["default", "rtol"])
@pytest.mark.parametrize("psi", [0.999, 0.999999])
def test_hertz_shear_close_to_sliding_resolves_the_stick_zone(hertz, psi, model):
    """Cattaneo-Mindlin, eqs (7), (8), (19): b = a sqrt(1 - Q/fP); inside it the traction falls
    short of f p by f p0 (b/a) sqrt(1 - x^2/b^2), a dip of only 1e-3 f p0 at 0.999999.

    At the default settings (the exact model, with nodes added in the smallest stick zone) and on
    the mesh of the default rtol (method 4; the 384-node grid's centre spacing, 8e-3 a, could not
    hold a stick zone of 2e-3 a)."""
    Q = psi * hertz.f * hertz.P
    result = proportional(hertz, psi, **model).isel(step=-1)
    x, a = result.x.values, hertz.a
    b = cf.stick_half_width(hertz, Q)
    assert_zones(result, [[-b, b]], RESOLVED * b)
    inner = np.abs(x) < 0.8 * b
    assert np.count_nonzero(inner) >= 3, f"{np.count_nonzero(inner)} nodes inside 0.8 b: the stick zone is not resolved"
    deficit = (hertz.f * result.p.values - result.q.values) / (hertz.f * hertz.p0 * b / a)
    assert np.max(np.abs(deficit - np.sqrt(np.clip(1 - (x / b) ** 2, 0, None)))[inner]) < RESOLVED
    slip = cf.cattaneo_mindlin_slip(hertz, Q, x)
    assert np.max(np.abs(result.slip.values - slip)) < PROJECT * slip.max()
    assert np.all(result.slip.values[np.abs(x) < 0.9 * b] == 0)  # never slipped


# ----------------------------------------------------------------------------------------------
# Rounded flat punch close to sliding: the stick zone tends to the flat, not to zero


@pytest.mark.parametrize("psi", [0.999, 0.999999])
def test_ciavarella_jaeger_stick_zone_tends_to_the_flat(psi):
    """Check of the reference used below (fretting.physics.closed_forms): the stick zone is the contact
    of P_c = P - Q/f; for small P_c, with pi/2 - phi0 = e, P_c = E_star b^2 (2e - sin 2e) / (4R)
    -> E_star b^2 e^3 / (3R) and c - b -> b e^2 / 2, so c - b shrinks like (fP - Q)^(2/3)."""
    contact = hard_rounded_flat()
    flat, R = contact.profile.b, contact.profile.R
    Q = psi * contact.f * contact.P
    c = cf.ciavarella_jaeger(contact, Q, np.zeros(1))[1].a
    P_c = contact.P - Q / contact.f
    e = (3 * R * P_c / (contact.E_star * flat**2)) ** (1 / 3)
    assert c > flat
    np.testing.assert_allclose(c - flat, flat * e**2 / 2, rtol=1e-2)


#: Q / fP of the rounded flat close to sliding: the strip c - b beyond the flat is 1.3e-3 a, then 1.3e-5 a.
CLOSE_TO_SLIDING = (0.999, 0.999999)

#: Method 4 close to sliding on this flat (issue 6, measured): what decides stick in the strip is a
#: slip of f h0(c) = 2.6e-15 m at 0.999999, below the error of either discretisation's slip under
#: q = f p over the flat (4.9e-11 m on the 384-node grid, 1.6e-13 m on the rtol 1e-4 mesh; python
#: benchmarks/rounded_flat_near_sliding.py). The default runs Q alone on this symmetric profile
#: with the exact model (fretting.models.exact), whose stick zone is the corrective contact itself; the
#: mesh of the default rtol is held to the same checks where it resolves the strip, at 0.999.
MODELS_CLOSE_TO_SLIDING = [(CLOSE_TO_SLIDING[0], "rtol"), *((psi, "default") for psi in CLOSE_TO_SLIDING)]


@functools.cache
def rounded_flat_close_to_sliding(psi, model="default"):
    """Last step of `proportional` to ``Q = psi f P`` on `hard_rounded_flat()`, at the default settings
    or (`model` "rtol") on the mesh of the default rtol."""
    keywords = {"rtol": fr.DEFAULT_RTOL} if model == "rtol" else {}
    return proportional(hard_rounded_flat(), psi, **keywords).isel(step=-1)


def strip_beyond_the_flat(psi):
    """``c - b`` [m] of the default's stick zone at ``Q = psi f P`` (mean of its two ends) and of Ciavarella-Jaeger."""
    contact = hard_rounded_flat()
    start, end = zones(rounded_flat_close_to_sliding(psi))[0]
    c = cf.ciavarella_jaeger(contact, psi * contact.f * contact.P, np.zeros(1))[1].a
    return (end - start) / 2 - contact.profile.b, c - contact.profile.b


@pytest.mark.parametrize(("psi", "model"), MODELS_CLOSE_TO_SLIDING)
def test_rounded_flat_shear_close_to_sliding_sticks_beyond_the_flat(psi, model):
    """Ciavarella-Jaeger (its reference checked above): the stick zone is [-c, c] with c > b, the
    strip c - b located to 1 % of itself; the traction within 1e-3 f p0 of q = f (p(P) - p(P_c))
    away from the stick/slip boundaries."""
    contact = hard_rounded_flat()
    result = rounded_flat_close_to_sliding(psi, model)
    x = result.x.values
    q_exact, corrective = cf.ciavarella_jaeger(contact, psi * contact.f * contact.P, x)
    c, flat = corrective.a, contact.profile.b
    assert_zones(result, [[-c, c]], min(RESOLVED * (c - flat), PROJECT * contact.a))
    assert np.all(np.abs(zones(result)) > flat)  # the stick zone covers the flat
    band = away_from(x, [-c, c], contact.a)
    assert np.max(np.abs(result.q.values - q_exact)[band]) < PROJECT * contact.f * contact.p0


def test_rounded_flat_strip_beyond_the_flat_shrinks_like_the_two_thirds_power():
    """c - b -> b e^2 / 2 with P_c -> E_star b^2 e^3 / (3R) (test above): c - b follows (fP - Q)^(2/3).
    The default's strips at Q/fP = 0.999 and 0.999999 give that exponent to within what two
    strips each located to 1 % allow; Ciavarella-Jaeger's give it to 5e-5."""
    (low, low_exact), (high, high_exact) = (strip_beyond_the_flat(psi) for psi in CLOSE_TO_SLIDING)
    decades = np.log((1 - CLOSE_TO_SLIDING[0]) / (1 - CLOSE_TO_SLIDING[1]))
    assert np.log(low_exact / high_exact) / decades == pytest.approx(2 / 3, abs=5e-5)
    assert high > 0
    tolerance = np.log((1 + RESOLVED) / (1 - RESOLVED)) / decades
    assert np.log(low / high) / decades == pytest.approx(2 / 3, abs=tolerance)


# ----------------------------------------------------------------------------------------------
# The grid close to sliding: its pressure carries P, so every |Q| < fP leaves a stick zone


@pytest.mark.parametrize(("profile", "shortfall"), [("hertz", 0.0), ("rounded_flat", 1.954e-5), ("flat_punch", 0.0)])
def test_grid_friction_force_is_f_P(hertz, profile, shortfall):
    """Gauss-Chebyshev quadrature of p on the default grid: exact where p sqrt(1 - t^2) is a
    polynomial (Hertz: degree 2; the sharp flat punch: degree 0), `shortfall` of P below it on
    the rounded flat, whose pressure has a singular derivative at the flat's ends (measured). The
    grid's discrete pressure is scaled to carry P on all three, its friction force is f P."""
    contact = {"hertz": lambda: hertz, "rounded_flat": hard_rounded_flat, "flat_punch": flat_punch}[profile]()
    scene = fr.models.Grid().build(contact)
    quadrature = scene.w * contact.pressure_weighted(scene.t).sum()
    assert 1 - quadrature / contact.P == pytest.approx(shortfall, rel=1e-3, abs=1e-15)
    assert scene.friction_force == pytest.approx(contact.f * contact.P, rel=1e-15, abs=0)


#: Q / fP of the rounded flat on the grid: the quadrature of its unscaled pressure, 2.0e-5 short of
#: P, took both for gross slip.
GRID_CLOSE_TO_SLIDING = (0.99999, 0.999999)


@functools.cache
def grid_close_to_sliding(psi):
    """Every step of `proportional` to ``Q = psi f P`` on `hard_rounded_flat()`, on the default grid."""
    return proportional(hard_rounded_flat(), psi, nodes=fr.DEFAULT_NODES)


@pytest.mark.parametrize("psi", GRID_CLOSE_TO_SLIDING)
def test_grid_close_to_sliding_keeps_one_stick_zone(psi):
    """Every step keeps a stick zone, one at the last about the centre, and Coulomb's law holds
    at every node against the contact's pressure (the grid reports the discrete utilisation
    times the contact's f p)."""
    result = grid_close_to_sliding(psi)
    assert_friction_conditions(result, hard_rounded_flat())
    assert_zone_ends_are_consistent(result)
    assert np.all(np.any(result.stick.values, axis=1))
    (start, end), *others = zones(result.isel(step=-1))
    assert not others and start < 0 < end


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="issue 6: the grid's slip under q = f p everywhere is flat over the flat only to 4.9e-11 m, "
    "where f h0(c) is 5.7e-14 m at 0.99999 and 2.6e-15 m at 0.999999 (ends at 0.75 b and 0.31 b)",
)
@pytest.mark.parametrize("psi", GRID_CLOSE_TO_SLIDING)
def test_grid_close_to_sliding_sticks_over_the_flat(psi):
    """Ciavarella-Jaeger: the stick zone [-c, c] covers the flat, c > b, however close to fP."""
    (start, end), *_ = zones(grid_close_to_sliding(psi).isel(step=-1))
    flat = hard_rounded_flat().profile.b
    assert start < -flat and end > flat


# ----------------------------------------------------------------------------------------------
# Tiny amplitudes: the cubic law of the energy per cycle, and exactly zero for no slip


@pytest.mark.parametrize("model", [{}, {"rtol": fr.DEFAULT_RTOL}], ids=["default", "rtol"])
@pytest.mark.parametrize("psi", [1e-3, 1e-6])
def test_tiny_amplitude_energy_follows_the_cubic_law(hertz, psi, model):
    """Q* = 1e-3 fP and 1e-6 fP: the reversed slip zones are 5e-4 a and 5e-7 a wide. The energy
    of the steady cycle matches Mindlin-Deresiewicz to 1e-3 (no noise floor, no missed slip);
    the dwells at the turning points slip nowhere and dissipate exactly zero.

    At the default settings (the exact model) and the default rtol (method 4; the 384-node
    grid's first node lies 8e-6 a inside the edge)."""
    fP = hertz.f * hertz.P
    Q_star = psi * fP
    ramp = fr.History.piecewise_linear([0.0, Q_star], None, 16)
    cycle = fr.History.piecewise_linear([Q_star, Q_star, -Q_star, -Q_star, Q_star], None, [1, 16, 1, 16]).as_cycle()
    history = fr.History.concatenate([ramp, cycle])
    result = fr.simulate(hertz, history, **model)
    W = float(result.cycle_dissipation.values[0])
    assert W == pytest.approx(cf.mindlin_deresiewicz_energy(hertz, Q_star), rel=1e-3, abs=0)
    dwells = history.vertex_step[[1, 3]] + 1  # the increments that repeat a vertex
    np.testing.assert_array_equal(history.Q[dwells], history.Q[dwells - 1])
    assert np.all(result.dissipation.values[dwells] == 0.0)
    assert np.all(result.stick.values[dwells])
    np.testing.assert_array_equal(result.slip.values[dwells], result.slip.values[dwells - 1])


# ----------------------------------------------------------------------------------------------
# Large bulk tension alone: eq (23) down to b = 0.05 a


@pytest.mark.slow
@pytest.mark.parametrize("b_over_a", [0.2, 0.1, 0.05])
def test_large_bulk_tension_alone(hertz, b_over_a):
    """Eq (23): K(k) - E(k) = pi sigma / (8 f p0), k = sqrt(1 - (b/a)^2); b = 0.05 a needs
    sigma = 8.6 f p0. Slip follows the sign of sigma x and is exactly zero where none happened."""
    tau = _tension_for_stick_half_width(b_over_a)
    sigma = tau * hertz.f * hertz.p0
    result = proportional(hertz, 0.0, tau).isel(step=-1)
    b = cf.bulk_tension_stick_half_width(hertz, sigma)
    assert b == pytest.approx(b_over_a * hertz.a, rel=1e-12, abs=0)
    assert_zones(result, [[-b, b]], min(RESOLVED * b, PROJECT * hertz.a))
    x, slip = result.x.values, result.slip.values
    assert np.all(slip[np.abs(x) < 0.9 * b] == 0)
    outside = np.abs(x) > 1.1 * b
    assert np.all(np.sign(slip[outside]) == np.sign(x[outside]))


# ----------------------------------------------------------------------------------------------
# One-sided slip: the stick zone reaches the contact edge


def flat_punch():
    return fr.Contact(fr.FlatPunch(2e-3), 115e9, 0.5, 3e5)


@pytest.mark.parametrize(
    ("psi", "edge_share", "path"),
    [(0.8, 0.5, "sigma first"), (0.6, 0.9, "proportional")],
    ids=["sigma-first", "proportional"],
)
def test_one_sided_slip_of_the_sharp_flat_punch(psi, edge_share, path):
    """Sharp flat punch, sigma > 0 with Q: stick zone [-a, d], one slip zone (d, a).

    Derived here: with q = f p + phi, L[f p] = 0 for p = P / (pi sqrt(a^2 - x^2)) (L the finite
    Hilbert transform (1/pi) PV int ./(xi - x) dxi), so stick (L[q] = sigma/4 there) asks
    L[phi] = sigma/4 on (-a, d), phi bounded at d: phi = -(sigma/4) sqrt((d - x)/(x + a));
    equilibrium int phi = Q - fP gives d + a = 8 (fP - Q) / (pi sigma). Slip starts once
    Q + pi a sigma / 4 > fP (`edge_share`: pi a sigma / (4 fP)); the stick zone shrinks
    monotonically along both paths, so no slip is locked in.
    """
    contact = flat_punch()
    a, fP = contact.a, contact.f * contact.P
    Q, sigma = psi * fP, edge_share * fP * 4 / (np.pi * a)
    if path == "sigma first":
        history = fr.History.piecewise_linear([0.0, 0.0, Q], [0.0, sigma, sigma], 8)
    else:
        history = fr.History.piecewise_linear([0.0, Q], [0.0, sigma], 8)
    full = fr.simulate(contact, history)
    assert_friction_conditions(full, contact)
    result = full.isel(step=-1)
    d = -a + 8 * (fP - Q) / (np.pi * sigma)
    assert_zones(result, [[-a, d]], PROJECT * a)
    inner = np.abs(result.x.values) < a  # the traction is unbounded at the edges (the mesh's end nodes)
    x, q = result.x.values[inner], result.q.values[inner]
    stuck = x < d
    q_exact = fP / (np.pi * np.sqrt(a**2 - x**2)) - np.where(stuck, sigma / 4 * np.sqrt(np.abs(d - x) / (x + a)), 0.0)
    weight = np.pi * np.sqrt(a**2 - x**2) / fP  # q / (f p)
    band = away_from(x, [d], a)
    assert np.max(np.abs((q - q_exact) * weight)[band]) < PROJECT
    x = result.x.values
    slip = result.slip.values
    assert np.all(slip[x < d - BOUNDARY_BAND * a] == 0) and np.all(slip[x > d + BOUNDARY_BAND * a] > 0)


def _quad(function, low, high, **options):
    """``scipy.integrate.quad`` without its warnings: the reference's accuracy is checked by its residual."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        return integrate.quad(function, low, high, **options)[0]


def _hilbert_antiderivative(x, xi, xi_minus_x):
    """Antiderivative at ``xi`` of ``sqrt(1 - t^2) / (t - x)`` (|x| < 1), given ``xi - x`` exactly."""
    root = np.sqrt(1 - x**2)
    log = np.log(np.abs((1 - x * xi + root * np.sqrt(1 - xi**2)) / xi_minus_x))
    return -root * log + np.sqrt(1 - xi**2) - x * np.arcsin(xi)


def _stick_rhs(theta, d1, d2, tau):
    """``L[phi]`` that the stick-zone traction must give at ``x = m + h cos(theta)`` (units a, f p0).

    In the stick zone L[q] = sigma/4 (no slip gradient); the slip zones carry ``q = -f p`` on
    [-a, d1] and ``q = +f p`` on [d2, a], ``p = p0 sqrt(1 - t^2)``.
    """
    m, h = (d1 + d2) / 2, (d2 - d1) / 2
    x = m + h * np.cos(theta)
    right = _hilbert_antiderivative(x, 1.0, 1 - x) - _hilbert_antiderivative(x, d2, 2 * h * np.sin(theta / 2) ** 2)
    left = _hilbert_antiderivative(x, d1, -2 * h * np.cos(theta / 2) ** 2) - _hilbert_antiderivative(x, -1.0, -1 - x)
    return tau / 4 - (right - left) / np.pi


def _two_condition_residual(ends, psi, tau):
    """Consistency (phi bounded at both ends) and equilibrium of the stick interval ``ends``."""
    d1, d2 = ends
    options = {"epsabs": 1e-15, "epsrel": 1e-13, "limit": 400}
    c0 = _quad(lambda th: _stick_rhs(th, d1, d2, tau), 0, np.pi, **options)
    c1 = _quad(lambda th: _stick_rhs(th, d1, d2, tau) * np.cos(th), 0, np.pi, **options)
    area = lambda t: (t * np.sqrt(1 - t**2) + np.arcsin(t)) / 2  # noqa: E731 - int sqrt(1 - t^2)
    slip_force = (area(1.0) - area(d2)) - (area(d1) - area(-1.0))
    return [c0, -(d2 - d1) / 2 * c1 + slip_force - psi * np.pi / 2]


def _stick_traction(t, d1, d2, tau):
    """``q / (f p0)`` at ``x = t a`` inside the stick interval: bounded-bounded inversion."""
    m, h = (d1 + d2) / 2, (d2 - d1) / 2
    v = (t - m) / h
    theta_v = np.arccos(v)
    g_v = _stick_rhs(theta_v, d1, d2, tau)
    smooth = lambda th: (_stick_rhs(th, d1, d2, tau) - g_v) / (np.cos(th) - v)  # noqa: E731
    integral = _quad(smooth, 0, np.pi, points=[theta_v], epsabs=1e-14, epsrel=1e-12, limit=400)
    return -np.sqrt(1 - v**2) * integral / np.pi


def test_hertz_shear_with_tension_past_the_contact_edge(hertz):
    """Hertz, proportional Q = 0.5 fP with sigma = 2 f p0: Nowell-Hills would put the stick zone
    at e - b = -1.21 a, beyond the edge; the trailing edge slips backwards instead.

    Reference (derived, literature-notes "single stick interval"): slip zones [-a, d1] with
    q = -f p and [d2, a] with q = +f p; in the stick zone L[q] = sigma/4, solved by the
    bounded-bounded inversion; its consistency and equilibrium fix d1 = -0.8623 a,
    d2 = 0.2210 a (NH recovered exactly for same-direction slip). Exact here because along
    the path d1 rises and d2 falls monotonically (checked at 20 points of the path when this
    test was written), so no slip is locked in; |q| < 0.972 f p inside the stick zone.
    """
    psi, tau = 0.5, 2.0
    assert -tau / 4 - np.sqrt(1 - psi) < -1  # Nowell-Hills' stick zone crosses the edge
    solution = optimize.root(
        _two_condition_residual, [-0.95, 0.3], args=(psi, tau), method="lm", options={"xtol": 1e-15, "ftol": 1e-15}
    )
    d1, d2 = solution.x
    assert np.max(np.abs(_two_condition_residual(solution.x, psi, tau))) < 1e-7
    full = proportional(hertz, psi, tau)
    assert_friction_conditions(full, hertz)
    result = full.isel(step=-1)
    a, fp0 = hertz.a, hertz.f * hertz.p0
    assert_zones(result, [[d1 * a, d2 * a]], PROJECT * a)
    t = result.x.values / a
    inside = np.flatnonzero((t > d1 + BOUNDARY_BAND) & (t < d2 - BOUNDARY_BAND))
    sample = inside[:: max(1, inside.size // 12)]
    q_exact = np.array([_stick_traction(value, d1, d2, tau) for value in t[sample]])
    assert np.max(np.abs(result.q.values[sample] / fp0 - q_exact)) < PROJECT
    slip = result.slip.values
    assert np.all(slip[t < d1 - BOUNDARY_BAND] < 0) and np.all(slip[t > d2 + BOUNDARY_BAND] > 0)
    assert np.all(slip[(t > d1 + BOUNDARY_BAND) & (t < d2 - BOUNDARY_BAND)] == 0)


# ----------------------------------------------------------------------------------------------
# Non-proportional paths: several stick zones, slip zones of opposite direction side by side


def slip_runs(ds):
    """Signs of the runs of slipping nodes of one increment, in order along x."""
    signs = np.sign(ds)
    starts = np.flatnonzero((signs != 0) & (np.concatenate([[0], signs[:-1]]) != signs))
    return signs[starts]


@pytest.mark.slow
def test_several_stick_zones_and_opposite_slip_side_by_side(hertz):
    """A diamond in the (Q, sigma) plane: increments with two stick zones and neighbouring slip
    zones slipping in opposite directions. Coulomb's law holds at every node of every step."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    Q = np.array([0, 0.6, 0, -0.6, 0, 0.6]) * fP
    sigma = np.array([0, 0, 1.5, 0, -1.5, 0]) * fp0
    result = fr.simulate(hertz, fr.History.piecewise_linear(Q, sigma, 8))
    assert_friction_conditions(result, hertz)
    ds = increments(result)
    several = np.count_nonzero(~np.isnan(result.stick_start.values), axis=1) >= 2
    opposite = np.array([np.any(np.diff(slip_runs(d)) != 0) for d in ds])
    assert np.any(several & opposite), "the path was meant to give two stick zones and opposite slip in one increment"
    assert np.all(np.count_nonzero(result.stick.values, axis=1) > 0)


# ----------------------------------------------------------------------------------------------
# Sharp flat punch: exactly zero slip until sliding


def test_sharp_flat_punch_does_not_slip_until_sliding():
    """q_st / p = (Q + pi sigma x / 4) / P: no node slips while |Q| + pi a |sigma| / 4 < fP, on
    any path, up to 1e-10 from sliding; Q = fP is gross slip."""
    contact = flat_punch()
    a, fP = contact.a, contact.f * contact.P
    edge = 4 * fP / (np.pi * a)  # sigma alone that reaches f p at an edge
    psi = np.array([0, 0.5, 1 - 1e-10, 0.3, -(1 - 1e-10), 0.0, 0.4, -0.2])
    share = np.array([0, 0.4, 0.0, -0.69, 0.0, 1 - 1e-10, -0.59, 0.8 - 1e-10])
    history = fr.History.piecewise_linear(psi * fP, share * edge, 8)
    result = fr.simulate(contact, history)
    assert np.all(result.slip.values == 0) and np.all(result.stick.values)
    assert np.all(result.dissipation.values == 0)
    with pytest.raises(fr.GrossSlipError) as error:
        fr.simulate(contact, fr.History.piecewise_linear([0.0, fP], None, 4))
    assert error.value.step == 4


# ----------------------------------------------------------------------------------------------
# 1e5 cycles: the periodic state does not drift


@pytest.mark.slow
def test_periodic_state_does_not_drift_over_1e5_cycles(hertz):
    """Out-of-phase Q and sigma (0.5 fP, 0.5 f p0, 90 degrees, 64 steps per cycle): the state is
    periodic from cycle 5 (measured); after cycle 10 and after cycle 100000 the slip fields
    agree to 1e-12 of the largest slip."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    cycles = 100_000
    history = fr.History.sinusoidal(0.5 * fP, 0.5 * fp0, 90.0, cycles=cycles)
    tenth = int(np.flatnonzero(history.cycle == 10)[-1])
    with pytest.warns(fr.engine.choice.MeshSampleWarning, match="stopped growing"):  # 3.2e6 turning points
        result = fr.simulate(hertz, history, record=[tenth, len(history) - 1])
    assert result.cycle_dissipation.size == cycles
    early, late = result.slip.values
    np.testing.assert_allclose(late, early, rtol=0, atol=1e-12 * np.abs(early).max())
    energy = result.cycle_dissipation.values
    np.testing.assert_allclose(energy[9:], energy[9], rtol=1e-12)


# ----------------------------------------------------------------------------------------------
# Step size: vertex states, tiny increments at reversals, repeated vertices


def asymmetric_contact():
    return fr.Contact(fr.Gap(*asymmetric_flat()), 115e9, 0.5, 3e5)


@pytest.mark.slow
def test_vertex_states_do_not_depend_on_steps_per_segment_on_an_asymmetric_profile():
    """Q-only segments from the virgin state: every node slips one way per segment (Masing), so
    the vertex states are the same in 1, 8 or 1000 increments per segment."""
    contact = asymmetric_contact()
    Q = np.array([0, 0.7, -0.4, 0.5]) * contact.f * contact.P
    slips = []
    for steps in (1, 8, 1000):
        history = fr.History.piecewise_linear(Q, None, steps)
        slips.append(fr.simulate(contact, history, record=history.vertex_step).slip.values)
    scale = np.abs(slips[0]).max()
    for other in slips[1:]:
        np.testing.assert_allclose(other, slips[0], rtol=0, atol=1e-9 * scale)


def test_tiny_increments_at_reversals(hertz):
    """A first increment of 1e-12 fP after each reversal, and a 1e-9 fP minor loop at a peak,
    change no vertex state and no energy (the exact change is of order 1e-18 of them)."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    plain = fr.History.piecewise_linear(np.array([0, 0.6, -0.5, 0.4]) * fP, np.array([0, 0.3, -0.25, 0.2]) * fp0, 8)
    tiny = 1e-12
    psi = np.array([0, 0.6, 0.6 - 1e-9, 0.6, 0.6 - tiny, -0.5, -0.5 + tiny, 0.4])
    sigma = psi / 2
    history = fr.History.piecewise_linear(psi * fP, sigma * fp0, [8, 1, 1, 1, 8, 1, 8])
    reference = fr.simulate(hertz, plain)  # every step recorded, as below: both meshes locate every step's ends
    result = fr.simulate(hertz, history)
    vertices = history.vertex_step[[0, 1, 5, 7]]
    expected = reference.slip.values[plain.vertex_step]
    scale = np.abs(expected).max()
    np.testing.assert_allclose(result.slip.values[vertices], expected, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(result.dissipation.sum(), reference.dissipation.sum(), rtol=1e-9)
    assert_friction_conditions(result, hertz)


@pytest.mark.slow
def test_repeated_vertices_change_nothing_on_a_non_proportional_path(hertz):
    """Zero-length segments (dwells) between non-proportional segments: they slip nowhere and
    dissipate exactly zero, and every later step equals the run without them, bit for bit."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    Q = np.array([0, 0.5, -0.3, 0.4, 0.0]) * fP
    sigma = np.array([0, 1.0, 0.5, -0.8, 1.2]) * fp0
    plain = fr.simulate(hertz, fr.History.piecewise_linear(Q, sigma, 8))
    repeat = [0, 1, 1, 2, 3, 3, 3, 4]
    dwelling = fr.simulate(hertz, fr.History.piecewise_linear(Q[repeat], sigma[repeat], [8, 1, 8, 8, 1, 2, 8]))
    dwell_steps = np.array([9, 26, 27, 28])
    assert np.all(dwelling.dissipation.values[dwell_steps] == 0) and np.all(dwelling.stick.values[dwell_steps])
    keep = np.setdiff1d(np.arange(dwelling.sizes["step"]), dwell_steps)
    np.testing.assert_array_equal(dwelling.Q.values[keep], plain.Q.values)
    for name in ("slip", "q", "stick", "dissipation", "delta_Q", "delta_sigma"):
        np.testing.assert_array_equal(dwelling[name].values[keep], plain[name].values, err_msg=name)
    for name in ("stick_start", "stick_end"):
        width = min(dwelling.sizes["zone"], plain.sizes["zone"])
        np.testing.assert_array_equal(dwelling[name].values[keep, :width], plain[name].values[:, :width], err_msg=name)


# ----------------------------------------------------------------------------------------------
# Scale: SI and unit-free inputs, half-widths from micrometres to metres


def scaled_contact(kind, length, E_star):
    """The same normalised problem at the length scale `length` [m] and modulus `E_star` [Pa]."""
    if kind == "hertz":
        # a = length, p0 = 2e-3 E_star: P = pi a p0 / 2, R = pi E_star a^2 / (4 P)
        P = np.pi * length * 2e-3 * E_star / 2
        profile = fr.Hertz(np.pi * E_star * length**2 / (4 * P))
    else:
        P = 2e-3 * E_star * length
        profile = fr.RoundedFlat(0.8 * length, 40 * length)
    return fr.Contact(profile, E_star, 0.6, P)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["hertz", "rounded_flat"])
def test_si_and_unit_free_inputs_give_the_same_normalised_results(kind):
    """a from 1 um to 1 m with E_star 70 GPa to 400 GPa, against the unit-free scene: q / f p0,
    slip, dissipation, delta_Q, delta_sigma in f p0 a / E_star units, ends in a, agree to 1e-10."""
    psi = np.array([0, 0.7, -0.4, 0.5, 0.1])
    tau = np.array([0, 0.3, -0.6, 1.0, 0.2])

    def normalised(contact):
        fp0, a = contact.f * contact.p0, contact.a
        history = fr.History.piecewise_linear(psi * contact.f * contact.P, tau * fp0, 6)
        r = fr.simulate(contact, history)
        slip_unit = fp0 * a / contact.E_star
        return {
            "x": (r.x.values - contact.centre) / a,
            "q": r.q.values / fp0,
            "slip": r.slip.values / slip_unit,
            "dissipation": r.dissipation.values / (fp0 * slip_unit * a),
            "delta_Q": r.delta_Q.values / slip_unit,
            "delta_sigma": r.delta_sigma.values / (slip_unit * a),
            "stick_start": (r.stick_start.values - contact.centre) / a,
            "stick_end": (r.stick_end.values - contact.centre) / a,
        }

    unit_free = normalised(scaled_contact(kind, 1.0, 1.0))
    for length, E_star in ((1e-6, 70e9), (1e-3, 115e9), (1.0, 400e9)):
        contact = scaled_contact(kind, length, E_star)
        assert contact.a == pytest.approx(length, rel=0.3, abs=0)
        for name, values in normalised(contact).items():
            np.testing.assert_allclose(values, unit_free[name], rtol=0, atol=1e-10, err_msg=f"{name} at a = {length} m")


# ----------------------------------------------------------------------------------------------
# Asymmetric profile against a converged reference


class FineGap(fr.Gap):
    """The same profile, its normal contact expanded in 4 times as many Chebyshev points: its
    Ciavarella-Jaeger traction is within 8e-5 f p0 of that with 16 times as many (measured;
    with the engine's 1024 points the difference is 6e-4 f p0)."""

    ORDER = 4096


def tabulated_asymmetric():
    h0, _, _ = asymmetric_flat()
    x = np.linspace(-2e-3, 2e-3, 1601)
    return x, h0(x)


@pytest.mark.slow
@pytest.mark.parametrize(("given", "psi"), [("functions", 0.3), ("table", 0.8)])
def test_asymmetric_profile_against_a_converged_reference(given, psi):
    """Flat with corners of radius 10 mm and 40 mm (Gap, and Gap.from_table of it), monotonic Q.

    Ciavarella-Jaeger holds for any profile in this uncoupled problem: L[p] = -(E_star/2) h0'
    inside the contact of every load, so q = f (p(P) - p(P_c)), P_c = P - Q/f, has no slip
    gradient in the contact of P_c, which is the stick zone (off-centre here). The reference
    solves both normal contacts with 4 times the engine's expansion (`FineGap`).
    """
    if given == "functions":
        h0, slope, corners = asymmetric_flat()
        profile, fine = fr.Gap(h0, slope, corners), FineGap(h0, slope)
    else:
        x, h = tabulated_asymmetric()
        spline = interpolate.CubicSpline(x, h)
        profile, fine = fr.Gap.from_table(x, h, asymmetric_flat()[2]), FineGap(spline, spline.derivative())
    contact = fr.Contact(profile, 115e9, 0.5, 3e5)
    reference = fr.Contact(fine, 115e9, 0.5, 3e5)
    assert abs(contact.centre) > 0.1 * contact.a  # asymmetric indeed
    Q = psi * contact.f * contact.P
    result = proportional(contact, psi).isel(step=-1)
    x = result.x.values
    # at the same place relative to each contact: their edges differ by 3e-8 a, where p rises like a square root
    t = (x - contact.centre) / contact.a
    q_exact, corrective = cf.ciavarella_jaeger(reference, Q, reference.centre + reference.a * t)
    ends = [corrective.centre - corrective.a, corrective.centre + corrective.a]
    assert_zones(result, [ends], PROJECT * contact.a)
    band = away_from(x, ends, contact.a)
    assert np.max(np.abs(result.q.values - q_exact)[band]) < PROJECT * contact.f * contact.p0


def test_gap_normal_contact_against_adaptive_quadrature():
    """The asymmetric flat's `Gap` (its breakpoints given) against eqs (1)-(2) solved independently:
    ``b_0 = 0`` and ``P = pi a E_star b_1 / 4`` with ``b_n = (2/pi) int_0^pi h0'(c + a cos u) cos(n u) du``,
    and ``p = (E_star / 2 pi) sin theta int_0^pi (h0'(c + a cos u) - h0'(c + a cos theta)) / (cos u - cos theta) du``,
    each by scipy's adaptive quadrature split at the breakpoints. The Chebyshev expansion of a slope
    whose derivative jumps limits `Gap`'s a, within 3.9e-8 relative, not the 1e-10 of the root solve;
    its pressure next to a jump, the same integral by Gauss-Legendre on graded pieces, is within
    2.1e-6 p0 (measured), the share of the contact's a and centre: at the same a and centre 5e-15 p0."""
    h0, slope, corners = asymmetric_flat()
    E_star, P = 115e9, 3e5
    contact = fr.Contact(fr.Gap(h0, slope, corners), E_star, 0.5, P)

    def kinks(a, c, extra=()):
        t = (np.array(corners) - c) / a
        return sorted([*np.arccos(t[np.abs(t) < 1]), *extra])

    def b(n, a, c):
        integrand = lambda u: float(slope(c + a * np.cos(u))) * np.cos(n * u)  # noqa: E731
        with warnings.catch_warnings():  # quad notes its roundoff near 1e-16 of the slope: far below what is asserted
            warnings.simplefilter("ignore", integrate.IntegrationWarning)
            return 2 / np.pi * integrate.quad(integrand, 0, np.pi, points=kinks(a, c), epsabs=1e-16, epsrel=1e-13)[0]

    def centre(a):
        return optimize.brentq(lambda c: b(0, a, c), -0.9 * a, 0.9 * a, xtol=1e-16 * a, rtol=1e-15)

    a = optimize.brentq(lambda a: np.pi * a * E_star * b(1, a, centre(a)) / (4 * P) - 1, 6e-4, 5e-3, rtol=1e-15)
    c = centre(a)
    assert abs(contact.a / a - 1) < 5e-8 and abs(contact.centre - c) < 5e-7 * a  # measured 3.9e-8, 3.6e-7 a

    def pressure(t):
        theta, g = np.arccos(t), float(slope(c + a * t))
        difference = lambda u: (float(slope(c + a * np.cos(u))) - g) / (np.cos(u) - t)  # noqa: E731
        part = integrate.quad(difference, 0, np.pi, points=kinks(a, c, [theta]), epsabs=1e-18, epsrel=1e-12)[0]
        return E_star / (2 * np.pi) * np.sin(theta) * part

    jump = (corners[1] - c) / a
    t = jump + np.linspace(-1e-2, 1e-2, 21)
    reference = np.array([pressure(u) for u in t])
    p = contact.pressure(c + a * t)
    assert np.abs(p - reference).max() < 3e-6 * contact.p0


# ----------------------------------------------------------------------------------------------
# Gross sliding reached mid-history


@pytest.mark.parametrize("profile", ["hertz", "rounded_flat"])
def test_gross_slip_mid_history_names_the_first_sliding_step(hertz, profile):
    """Two cycles, then a slow rise through fP (steps of 1e-5 fP): GrossSlipError names the
    first step with |Q| >= fP, and the history up to the step before runs."""
    contact = hertz if profile == "hertz" else hard_rounded_flat()
    fP = contact.f * contact.P
    psi = np.array([0, 0.5, -0.5, 0.5, -0.5, 0.9999, 1.0001])
    history = fr.History.piecewise_linear(psi * fP, None, [8, 16, 16, 16, 16, 20])
    first = int(np.flatnonzero(np.abs(history.Q) >= fP)[0])
    with pytest.raises(fr.GrossSlipError, match=f"gross slip at step {first}:") as error:
        fr.simulate(contact, history)
    assert error.value.step == first and error.value.Q == history.Q[first]
    head = fr.simulate(contact, history[:first], record=[first - 1])
    start, end = head.stick_start.values[-1], head.stick_end.values[-1]  # a stick zone left, maybe between nodes
    assert np.isfinite(start[0]) and end[0] > start[0]


@pytest.mark.slow
def test_failed_cli_run_leaves_an_earlier_result_intact(tmp_path, monkeypatch, capsys):
    """A result saved with fretting.save; then a run of the same history name that reaches gross
    slip after several chunks and checkpoints: exit 3, the step named, the result untouched
    byte for byte, no checkpoint or temporary file left."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(runner, "CHUNK_STEPS", 200)
    toml = HERTZ_TOML + (
        '\n[[loading]]\nkind = "linear"\nQ = [30e3]\nsteps_per_segment = 16\n'
        '\n[[loading]]\nkind = "repeat"\ncount = 3\n'
        'blocks = [{ kind = "linear", Q = [-30e3, 30e3], steps_per_segment = 100, cycle = true }]\n'
        '\n[[loading]]\nkind = "linear"\nQ = [80e3]\nsteps_per_segment = 50\n'
    )
    (tmp_path / "slide.toml").write_text(toml)
    contact, history = fr.read_history(tmp_path / "slide.toml")
    first = int(np.flatnonzero(np.abs(history.Q) >= contact.f * contact.P)[0])
    assert first > 3 * 200  # after several chunks and checkpoints
    earlier = fr.simulate(contact, history[:200])
    path = tmp_path / "slide.h5"
    fr.save(earlier, path)
    written, loaded = path.read_bytes(), fr.load(path)
    assert cli.main(["run", "slide.toml", "--checkpoint-interval", "0"]) == 3
    err = capsys.readouterr().err
    assert err.startswith(f"fretting: error: slide.toml: gross slip at step {first}:") and err.count("\n") == 1
    assert path.read_bytes() == written
    xr.testing.assert_identical(fr.load(path), loaded)
    assert sorted(p.name for p in path.parent.iterdir()) == ["slide.h5", "slide.toml"]


@pytest.mark.slow
def test_tension_reversed_in_one_step_keeps_a_stick_zone_narrower_than_an_element():
    """Q = 0.5 fP with sigma = -2.2 f p0, then Q = 0, sigma = 2 f p0 in one increment, on the
    asymmetric flat: the stick zone left is 6e-7 a wide, so on the first meshes of the adaptation
    every node wants to slip, the two edges in opposite directions. The increment has a solution
    (the total friction force exceeds |Q|); found by a rigid shift that stops the first node
    slipping against it (found by hypothesis: it raised SolverError before)."""
    contact = fr.Contact(fr.Gap(*asymmetric_flat()), 115e9, 0.3, 3e4)
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.piecewise_linear(np.array([0, 0.5, 0]) * fP, np.array([0, -2.2055744280043355, 2]) * fp0, 1)
    for model in ({}, {"nodes": 64}, {"mesh": initial_theta()}):
        result = simulate_as_a_user(contact, history, **model)
        assert_friction_conditions(result, contact)
        assert np.all(result.dissipation.values >= 0)
        assert result.stick.values[-1].any()
        assert_zone_ends_are_consistent(result)


@pytest.mark.parametrize("nodes", [32, 64, 128, 256])
def test_a_stick_zone_narrower_than_a_spacing_keeps_its_ends_in_order(nodes):
    """The scene above on grids: the stick zone left by the reversal is narrower than a node
    spacing, between slip zones of opposite directions. Each side's d^(3/2) extrapolation
    overshot past the single stuck node (64 nodes: a zone from 0.038 a to -0.024 a about the
    centre, 32 and 128 nodes alike); the ends now stay ordered and hold the stuck node."""
    contact = fr.Contact(fr.Gap(*asymmetric_flat()), 115e9, 0.3, 3e4)
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.piecewise_linear(np.array([0, 0.5, 0]) * fP, np.array([0, -2.2055744280043355, 2]) * fp0, 1)
    assert_zone_ends_are_consistent(fr.simulate(contact, history, nodes=nodes))


# ----------------------------------------------------------------------------------------------
# Zero-length increments after hard states


def _tension_for_stick_half_width(b_over_a):
    """``sigma / (f p0)`` that leaves a Hertz stick zone of half-width ``b_over_a a`` (eq 23)."""
    m = 1 - b_over_a**2
    return 8 * (special.ellipk(m) - special.ellipe(m)) / np.pi


#: (profile, Q / fP, sigma / f p0) of states reached in 8 proportional steps.
DWELL_STATES = {
    "hertz-shear-0.999": ("hertz", 0.999, 0.0),
    "hertz-tension-b0.2a": ("hertz", 0.0, _tension_for_stick_half_width(0.2)),
    "hertz-tension-b0.05a": ("hertz", 0.0, _tension_for_stick_half_width(0.05)),
    "hertz-past-the-edge": ("hertz", 0.5, 2.0),
    "rounded-flat-shear-0.999": ("rounded_flat", 0.999, 0.0),
    "rounded-flat-shear-with-tension": ("rounded_flat", 0.5, 2.0),
    "flat-punch-one-sided": ("flat_punch", 0.6, 0.9 * 4),  # pi a sigma / 4 = 0.9 fP
    "asymmetric-flat-tension": ("asymmetric_flat", 0.0, 2.0),
}


@pytest.mark.slow
@pytest.mark.parametrize("state", sorted(DWELL_STATES))
def test_a_dwell_after_a_hard_state_slips_nowhere(hertz, state):
    """Repeating the last vertex changes no load, so nothing may slip: each of three dwell
    increments dissipates exactly zero, every node sticks and the slip is unchanged, bit for bit.
    (A single dwell increment passes since the warm-started solver of a611e3f; the second and
    third start cold again.)"""
    profile, psi, tau = DWELL_STATES[state]
    contact = {
        "hertz": lambda: hertz,
        "rounded_flat": hard_rounded_flat,
        "flat_punch": flat_punch,
        "asymmetric_flat": lambda: fr.Contact(fr.Gap(*asymmetric_flat()), 115e9, 0.3, 3e4),
    }[profile]()
    Q, sigma = psi * contact.f * contact.P, tau * contact.f * contact.p0
    history = fr.History.piecewise_linear([0.0, Q, Q], [0.0, sigma, sigma], [8, 3])
    result = fr.simulate(contact, history)
    dwell = slice(-3, None)
    assert np.all(result.dissipation.values[dwell] == 0.0)
    assert np.all(result.stick.values[dwell])
    for step in (-3, -2, -1):
        np.testing.assert_array_equal(result.slip.values[step], result.slip.values[-4])
