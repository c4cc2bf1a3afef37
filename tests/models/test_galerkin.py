"""The P1 Galerkin scene and its mesh refinement (fretting.models.galerkin) against closed forms.

Targets: energy per cycle of a Hertz contact under Q = +-Q* within 1e-4 relative for Q*/fP in
[0.05, 0.95] and 1e-3 at 0.001; stick-zone ends within 1e-3 a (Cattaneo-Mindlin up to
Q = 0.999999 fP, Ciavarella-Jaeger, bulk tension); traction within 1e-3 f p0 away from 0.02 a
of the stick/slip boundaries; slip within 1e-3 of its maximum; the sharp flat punch never
slips below f P. The adaptive driver here is the loop of the issue: run, reduce the element
targets of every increment, refine, until the mesh stays.
"""

import harness
import numpy as np
import pytest
import xarray as xr
from harness import adapt, cycle_energy, cycles, ends, hertz_contact, increments, monotonic
from scipy import integrate, special

import fretting as fr
from fretting.analysis import accuracy
from fretting.models import Grid, Outcome
from fretting.models import galerkin as gk
from fretting.models.galerkin import kernels, mesh
from fretting.models.solver import solve_increment
from fretting.physics import closed_forms as cf


def scene_of(contact, theta, previous=None):
    """The Galerkin model of `contact` on the mesh `theta`."""
    return gk.Mesh(theta=theta).build(contact, previous)


def slipped(slip):
    """An outcome that left the slip `slip` [m] (rows of a 2-D `slip`), for the model's delta_Q and delta_sigma."""
    return Outcome(None, None, slip, 0.0)


BOUNDARY_BAND = 0.02  # [a]: the traction has a square-root kink at a stick/slip boundary


# --- helpers ---------------------------------------------------------------------------------


def away(x, boundaries, a):
    return np.all(np.abs(np.subtract.outer(x, np.asarray(boundaries))) > BOUNDARY_BAND * a, axis=-1)


# --- kernel and scene --------------------------------------------------------------------------


def test_clausen_against_direct_sums():
    x = np.array([1e-9, 1e-3, 0.5, 2.0, np.pi, 4.0, 6.0, -2.5, 10.0])
    m = np.arange(1, 200_001)[:, None]
    direct = special.zeta(3) - np.sum(np.cos(m * x) / m**3.0, axis=0)  # tail < 1e-11
    np.testing.assert_allclose(gk.clausen3_complement(x), direct, rtol=0, atol=1e-10)
    # Cl1 is F'': central second differences
    step = 1e-4
    for point in (0.3, 1.0, 2.9):
        second = (
            gk.clausen3_complement(point + step)
            - 2 * gk.clausen3_complement(point)
            + gk.clausen3_complement(point - step)
        ) / step**2
        np.testing.assert_allclose(second, gk.clausen1(point), rtol=1e-6)


def test_pair_means_series_meets_corners(monkeypatch):
    """The far-pair Taylor series and the four-corner formula agree where both are accurate."""
    lo, hi = np.array([0.2, 1.0, 2.0]), np.array([0.25, 1.04, 2.1])
    series = kernels.kernel_means(lo, hi)
    monkeypatch.setattr(kernels, "FAR_PAIRS", np.inf)
    np.testing.assert_allclose(series, kernels.kernel_means(lo, hi), rtol=1e-11)


def test_pair_means_against_quadrature(monkeypatch):
    """Means of ``Cl1(theta - phi) - Cl1(theta + phi)`` on a graded mesh, summed a row at a time
    (mirrored across blocks), against quadrature: Gauss-Legendre on the pairs the series serves in
    both kernels, nested adaptive quadrature on pairs that touch a singularity of ``Cl1``."""
    monkeypatch.setattr(kernels, "BLOCK_PAIRS", 1)
    theta = gk.initial_theta(8)  # 8 elements, the edge ones bisected down to 1e-4: sizes differ 4096-fold
    lo, hi = theta[:-1], theta[1:]
    means = kernels.kernel_means(lo, hi)[1:-1, 1:-1]
    centre, h = (lo + hi) / 2, hi - lo
    points, weights = np.polynomial.legendre.leggauss(24)
    at = centre[:, None] + h[:, None] / 2 * points  # (M, 24)
    distance = {  # from the centre of a pair to the nearest singularity
        -1: np.abs(centre[:, None] - centre[None, :]),
        1: np.minimum(centre[:, None] + centre[None, :], 2 * np.pi - centre[:, None] - centre[None, :]),
    }
    far = np.all([distance[sign] >= kernels.FAR_PAIRS * (h[:, None] + h[None, :]) / 2 for sign in (-1, 1)], axis=0)
    e, f = np.nonzero(far)
    kernel = gk.clausen1(at[e, :, None] - at[f, None, :]) - gk.clausen1(at[e, :, None] + at[f, None, :])
    np.testing.assert_allclose(means[e, f], kernel @ weights @ weights / 4, rtol=0, atol=1e-14)
    M = h.size
    for e, f in ((0, 0), (1, 0), (0, 1), (M // 2, M // 2), (M - 1, M - 2)):
        minus, plus = (nested_mean(lo[e], hi[e], lo[f], hi[f], sign) for sign in (-1, 1))
        np.testing.assert_allclose(means[e, f], minus - plus, rtol=0, atol=1e-12 * (abs(minus) + abs(plus)))


def nested_mean(a1, a2, b1, b2, sign):
    """Mean of ``Cl1(theta + sign phi)`` over ``[a1, a2] x [b1, b2]`` by nested adaptive quadrature."""

    def inner(t):
        singular = [t] if sign < 0 and b1 < t < b2 else None
        return integrate.quad(
            lambda p: gk.clausen1(t + sign * p), b1, b2, points=singular, epsabs=1e-15, epsrel=1e-13, limit=200
        )[0]

    return integrate.quad(inner, a1, a2, epsabs=1e-15, epsrel=1e-13, limit=200)[0] / ((a2 - a1) * (b2 - b1))


def refinement_chain(seed, refinements=4):
    """`initial_theta` refined again and again, one element in 20 at random to a quarter of its size (and graded)."""
    rng = np.random.default_rng(seed)
    chain = [gk.initial_theta()]
    for _ in range(refinements):
        h = np.diff(chain[-1])
        chain.append(gk.refine(chain[-1], np.where(rng.random(h.size) < 0.05, h / 4, np.inf)))
    return chain


def test_series_coefficients_of_two_sizes_do_not_depend_on_the_others():
    """The table entry of two element sizes is the same, bit for bit, among any other sizes (BLAS would round
    the products of a 5-size table and of a 40-size one differently)."""
    sizes = np.sort(np.random.default_rng(0).uniform(1e-6, 0.05, 40))
    table = kernels._series_coefficients(sizes)
    for subset in (slice(1), slice(5), slice(9), slice(17), slice(None, None, 3)):
        np.testing.assert_array_equal(kernels._series_coefficients(sizes[subset]), table[:, subset, subset])


@pytest.mark.parametrize("block_pairs", [1, 2**9, 2**20])
def test_pair_means_do_not_depend_on_the_blocks(monkeypatch, block_pairs):
    """Each mean is its two elements' alone, bit for bit, whatever block it is summed in (not so with a BLAS
    product over the block, whose rounding depends on its shape)."""
    theta = refinement_chain(seed=0)[-1]
    default = kernels.kernel_means(theta[:-1], theta[1:])
    monkeypatch.setattr(kernels, "BLOCK_PAIRS", block_pairs)
    np.testing.assert_array_equal(kernels.kernel_means(theta[:-1], theta[1:]), default)


@pytest.mark.parametrize("seed", [0, 3])
def test_stiffness_reusing_the_mesh_before_is_bit_for_bit_fresh(hertz, seed):
    """Along a refinement chain each scene reuses most pairs of the one before and equals the scene assembled afresh."""
    previous = None
    for theta in refinement_chain(seed):
        scene = scene_of(hertz, theta, previous=previous)
        np.testing.assert_array_equal(scene.G, scene_of(hertz, theta).G)
        if previous is not None:
            recurring = kernels._recurring_elements(theta[:-1], theta[1:], previous.theta) >= 0
            assert 0.5 < recurring.mean() < 1
            reused = gk.stiffness(theta, hertz.E_star, previous=previous)
            np.testing.assert_array_equal(reused, gk.stiffness(theta, hertz.E_star))
        previous = scene


def test_stiffness_reusing_a_mesh_without_common_elements(hertz):
    """Every other node of the mesh (the last element spans 2 or 3): no element has both ends in common."""
    theta = refinement_chain(seed=1)[-1]
    previous = scene_of(hertz, np.append(theta[:-2:2], np.pi))
    assert np.all(kernels._recurring_elements(theta[:-1], theta[1:], previous.theta) < 0)
    reused = scene_of(hertz, theta, previous=previous)
    np.testing.assert_array_equal(reused.G, scene_of(hertz, theta).G)


def test_stiffness_reusing_the_same_mesh(hertz):
    theta = refinement_chain(seed=2)[-1]
    scene = scene_of(hertz, theta)
    np.testing.assert_array_equal(scene_of(hertz, theta, previous=scene).G, scene.G)
    np.testing.assert_array_equal(gk.stiffness(theta, hertz.E_star, previous=scene), scene.G[::-1, ::-1])


def test_stiffness_energy_of_smooth_slip(hertz):
    """``s^T K s -> (pi E_star / 4) sum n s_n^2`` for ``s = a cos(n theta)`` (h^2), like the Chebyshev energy."""
    scene = scene_of(hertz, gk.uniform_theta(256))
    K = scene.G
    np.testing.assert_allclose(K, K.T, rtol=0, atol=1e-14 * np.abs(K).max())
    np.testing.assert_allclose(K.sum(axis=1), 0, atol=1e-13 * np.abs(K).max())
    assert np.linalg.eigvalsh(K)[0] > -1e-13 * np.abs(K).max()
    theta = scene.theta[::-1]
    for n in (1, 2, 5):
        s = hertz.a * np.cos(n * theta)
        np.testing.assert_allclose(s @ K @ s, np.pi * hertz.E_star / 4 * n * hertz.a**2, rtol=1e-3)
    chebyshev = Grid(128).build(hertz)
    slip = lambda t: hertz.a * (0.05 * t + 0.3 * t**2 + 0.1 * t**3 - 0.2 * t**4)  # noqa: E731
    energy = chebyshev.w * slip(chebyshev.grid.t) @ chebyshev.G @ slip(chebyshev.grid.t)
    np.testing.assert_allclose(slip(scene.t) @ K @ slip(scene.t), energy, rtol=2e-4)


PROFILES = {
    "hertz": lambda: fr.Hertz(0.05),
    "rounded flat": lambda: fr.RoundedFlat(1e-3, 0.02),
    "flat punch": lambda: fr.FlatPunch(1e-3),
    "gap": lambda: fr.Gap(lambda x: np.where(x > 0, 1, 2) * x**2 / 0.1, lambda x: np.where(x > 0, 1, 2) * x / 0.05),
}


@pytest.mark.parametrize("name", PROFILES)
def test_loads_and_limits(hertz, name):
    """``sum L = f P`` to 1e-10 on coarse and graded meshes, for every profile."""
    contact = fr.Contact(PROFILES[name](), hertz.E_star, hertz.f, hertz.P)
    for theta in (gk.uniform_theta(8), gk.initial_theta()):
        scene = scene_of(contact, theta)
        np.testing.assert_allclose(scene.friction_force, contact.f * contact.P, rtol=1e-10)
        assert np.all(np.diff(scene.x) > 0) and np.all(scene.limit > 0)


def test_displacements_exact_for_P1(hertz):
    """``delta_Q``, ``delta_sigma`` and the loads integrate a P1 slip exactly (reciprocity)."""
    theta = gk.initial_theta()
    scene = scene_of(hertz, theta)
    slip = np.random.default_rng(0).normal(size=theta.size) * hertz.a  # ascending x
    points, weights = np.polynomial.legendre.leggauss(8)  # per element: exact to rounding here
    lo, h = theta[:-1, None], np.diff(theta)[:, None]
    at = lo + h * (1 + points) / 2
    s_at, measure = np.interp(at, theta, slip[::-1]), weights * h / 2
    delta_Q = np.sum(s_at * measure) / np.pi
    delta_sigma = np.sum(s_at * hertz.a * np.cos(at) / 4 * measure)
    scale = np.sum(np.abs(s_at) * measure)  # the size of the terms that cancel
    np.testing.assert_allclose(scene.delta_Q(slipped(slip)), delta_Q, rtol=0, atol=1e-14 * scale)
    np.testing.assert_allclose(scene.delta_sigma(slipped(slip)), delta_sigma, rtol=0, atol=1e-14 * hertz.a * scale)
    Q, sigma = 0.3 * hertz.f * hertz.P, 0.7 * hertz.f * hertz.p0
    work = Q * delta_Q + sigma * delta_sigma
    np.testing.assert_allclose(scene.g_stuck(Q, sigma) @ slip, work, rtol=0, atol=1e-14 * Q * scale)
    rows = np.vstack([slip, 2 * slip, slip])
    assert (
        scene.delta_sigma(slipped(rows))[0]
        == scene.delta_sigma(slipped(rows[:1]))[0]
        == scene.delta_sigma(slipped(slip))
    )
    assert scene.delta_Q(slipped(rows))[2] == scene.delta_Q(slipped(slip))


def test_traction_keeps_coulomb_and_recovers_third_order(hertz):
    """``g = L`` gives ``f p`` (to rounding); a smooth utilisation comes back to O(h^3), also graded."""
    scene = scene_of(hertz, gk.initial_theta(32))
    np.testing.assert_allclose(scene.nodal_traction(scene.limit), hertz.f * hertz.pressure(scene.x), rtol=1e-13)
    ds = np.where(scene.x > 0, 1.0, 0.0)
    sliding = scene.nodal_traction(0.5 * scene.limit, ds)
    np.testing.assert_array_equal(sliding[scene.x > 0], hertz.f * hertz.pressure(scene.x)[scene.x > 0])
    errors = []
    for M in (32, 64):
        scene = scene_of(hertz, gk.initial_theta(M))
        u = lambda th: 0.8 * np.cos(2 * th)  # noqa: E731 - a utilisation |u| < 1
        points, weights = np.polynomial.legendre.leggauss(8)
        theta = scene.theta
        at = theta[:-1, None] + np.diff(theta)[:, None] * (1 + points) / 2
        rise = (1 + points) / 2
        w = weights * np.diff(theta)[:, None] / 2 * u(at) * hertz.f * hertz.a * hertz.pressure_weighted(np.cos(at))
        g = np.zeros(theta.size)
        g[:-1] += np.sum(w * (1 - rise), axis=1)
        g[1:] += np.sum(w * rise, axis=1)
        q = scene.nodal_traction(g[::-1])
        errors.append(np.abs(q - u(theta[::-1]) * hertz.f * hertz.pressure(scene.x)).max() / (hertz.f * hertz.p0))
    assert errors[1] < 1e-4 and errors[0] / errors[1] > 6


@pytest.mark.parametrize(("psi", "tau"), [(0.3, 0.0), (0.5, 0.5)])
def test_the_traction_next_to_a_stick_end_is_read_through_graded_elements(hertz, monkeypatch, psi, tau):
    """The nodal traction (a quadratic through three hat means) follows the square-root kink next to a stick end
    only through elements a small fraction of their distance from it: the mesh of recorded steps, graded at
    `BOUNDARY_GRADING`, reads Nowell-Hills in the stick zone within 1e-4 f p0 away from the ends, where the
    energy's grading, `ENERGY_GRADING`, leaves more than twice that."""
    Q, sigma = psi * hertz.f * hertz.P, tau * hertz.f * hertz.p0
    history = fr.History.piecewise_linear([0.0, Q], [0.0, sigma], 32)
    b, e = cf.stick_half_width(hertz, Q), cf.nowell_hills_offset(hertz, sigma)

    def traction_error():
        step = fr.simulate(hertz, history, rtol=gk.DEFAULT_RTOL).isel(step=-1)
        exact = cf.nowell_hills_traction(hertz, Q, sigma, step.x.values)
        ends = [e - b, e + b, -hertz.a, hertz.a]
        band = accuracy.BAND * hertz.a
        return accuracy.traction_error(step.x.values, step.q.values, exact, ends, band) / (hertz.f * hertz.p0)

    graded = traction_error()
    monkeypatch.setattr(gk.adaptation, "BOUNDARY_GRADING", gk.ENERGY_GRADING)
    assert graded < 1e-4 and traction_error() > 2e-4


# --- closed forms --------------------------------------------------------------------------------


@pytest.mark.parametrize("psi", [0.05, 0.3, 0.95])
def test_hertz_cycle_energy(hertz, psi):
    steps = 4
    Q_star = psi * hertz.f * hertz.P
    scene, ds, _, _ = adapt(hertz, cycles(Q_star, steps))
    np.testing.assert_allclose(cycle_energy(scene, ds, steps), cf.mindlin_deresiewicz_energy(hertz, Q_star), rtol=1e-4)


def test_hertz_cycle_energy_tiny_amplitude(hertz):
    steps = 4
    Q_star = 1e-3 * hertz.f * hertz.P
    scene, ds, _, _ = adapt(hertz, cycles(Q_star, steps))
    np.testing.assert_allclose(cycle_energy(scene, ds, steps), cf.mindlin_deresiewicz_energy(hertz, Q_star), rtol=1e-3)


@pytest.mark.parametrize("psi", [0.2, 0.8, 0.999, 0.999999])
def test_cattaneo_mindlin(hertz, psi):
    Q = psi * hertz.f * hertz.P
    scene, ds, g, _ = adapt(hertz, monotonic(Q)[0])
    slip, x, a = ds.sum(axis=0), scene.x, hertz.a
    b = cf.stick_half_width(hertz, Q)
    np.testing.assert_allclose(ends(scene, slip), [[-b, b]], rtol=0, atol=1e-3 * a)
    q = scene.nodal_traction(g[-1], ds[-1])
    q_exact = cf.cattaneo_mindlin_traction(hertz, Q, x)
    band = away(x, [-b, b], a)
    assert np.abs(q - q_exact)[band].max() < 1e-3 * hertz.f * hertz.p0
    slip_exact = cf.cattaneo_mindlin_slip(hertz, Q, x)
    assert np.abs(slip - slip_exact).max() < 1e-3 * slip_exact.max()


def test_mindlin_deresiewicz_unloading(hertz):
    """0 -> 0.8 f P -> -0.2 f P: reversed slip zones, c/a = sqrt(1 - (Q* - Q)/(2 f P)) (Masing)."""
    fP, a = hertz.f * hertz.P, hertz.a
    Q_star, Q_end = 0.8 * fP, -0.2 * fP
    Q = np.concatenate([np.linspace(0, Q_star, 5), np.linspace(Q_star, Q_end, 9)[1:]])
    scene, ds, g, _ = adapt(hertz, Q)
    c = a * np.sqrt(1 - (Q_star - Q_end) / (2 * fP))
    b = cf.stick_half_width(hertz, Q_star)
    np.testing.assert_allclose(ends(scene, ds[4:].sum(axis=0)), [[-c, c]], rtol=0, atol=1e-3 * a)
    q_exact = cf.mindlin_deresiewicz_traction(hertz, Q_star, Q_end, scene.x)
    band = away(scene.x, [-c, c, -b, b], a)
    assert np.abs(scene.nodal_traction(g[-1], ds[-1]) - q_exact)[band].max() < 1e-3 * hertz.f * hertz.p0
    slip_exact = cf.mindlin_deresiewicz_slip(hertz, Q_star, Q_end, scene.x)
    assert np.abs(ds.sum(axis=0) - slip_exact).max() < 1e-3 * np.abs(slip_exact).max()


def test_nowell_hills_shear_with_tension(hertz):
    """Proportional Q = 0.5 f P, sigma = 0.5 f p0: the stick zone moves by -sigma a / (4 f p0)."""
    Q, sigma = monotonic(0.5 * hertz.f * hertz.P, sigma_end=0.5 * hertz.f * hertz.p0)
    scene, ds, g, _ = adapt(hertz, Q, sigma)
    b = cf.stick_half_width(hertz, Q[-1])
    e = cf.nowell_hills_offset(hertz, sigma[-1])
    np.testing.assert_allclose(ends(scene, ds.sum(axis=0)), [[e - b, e + b]], rtol=0, atol=1e-3 * hertz.a)
    q_exact = cf.nowell_hills_traction(hertz, Q[-1], sigma[-1], scene.x)
    band = away(scene.x, [e - b, e + b], hertz.a)
    assert np.abs(scene.nodal_traction(g[-1], ds[-1]) - q_exact)[band].max() < 1e-3 * hertz.f * hertz.p0


@pytest.mark.parametrize("psi", [0.2, 0.8])
def test_rounded_flat(hertz, psi):
    contact = fr.Contact(fr.RoundedFlat(1e-3, 0.02), hertz.E_star, hertz.f, hertz.P)
    Q = psi * contact.f * contact.P
    scene, ds, g, _ = adapt(contact, monotonic(Q)[0])
    q_exact, corrective = cf.ciavarella_jaeger(contact, Q, scene.x)
    c = corrective.a
    np.testing.assert_allclose(ends(scene, ds.sum(axis=0)), [[-c, c]], rtol=0, atol=1e-3 * contact.a)
    band = away(scene.x, [-c, c], contact.a)
    assert np.abs(scene.nodal_traction(g[-1], ds[-1]) - q_exact)[band].max() < 1e-3 * contact.f * contact.p0


@pytest.mark.parametrize("tau", [0.3, 2.5, 8.6])
def test_bulk_tension(hertz, tau):
    sigma = tau * hertz.f * hertz.p0
    Q, sigmas = monotonic(0.0, sigma_end=sigma)
    scene, ds, _, _ = adapt(hertz, Q, sigmas)
    c = cf.bulk_tension_stick_half_width(hertz, sigma)
    np.testing.assert_allclose(ends(scene, ds.sum(axis=0)), [[-c, c]], rtol=0, atol=1e-3 * hertz.a)


def test_coulomb_at_every_node(hertz):
    """Reported tractions keep |q| <= f p, and q = f p sign(ds) where a node slipped, exactly."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    Q = np.array([0.0, 0.6, -0.3, 0.5]) * fP
    sigma = np.array([0.0, 0.5, -1.0, 0.2]) * fp0
    scene = scene_of(hertz, gk.initial_theta())
    ds, g = increments(scene, Q, sigma)
    q, fp = scene.nodal_traction(g, ds), hertz.f * hertz.pressure(scene.x)
    assert np.all(np.abs(q) <= fp)
    np.testing.assert_array_equal(q[ds != 0], (fp * np.sign(ds))[ds != 0])


def test_sharp_flat_punch_never_slips(hertz):
    contact = fr.Contact(fr.FlatPunch(1e-3), hertz.E_star, hertz.f, hertz.P)
    Q = np.array([0.0, 0.5, 0.9, 0.999, 0.999999, -0.999999, 0.3]) * contact.f * contact.P
    scene = scene_of(contact, gk.initial_theta())
    ds, _ = increments(scene, Q)
    assert np.all(ds == 0)


# --- mesh functions ------------------------------------------------------------------------------


def test_refine_is_nested_and_graded():
    theta = gk.initial_theta()
    targets = np.full(theta.size - 1, np.inf)
    assert gk.refine(theta, targets) is theta
    targets[40] = 1e-5
    refined = gk.refine(theta, targets)
    assert np.all(np.isin(theta, refined))
    h = np.diff(refined)
    assert np.all(h[1:] <= 2 * h[:-1] * (1 + 1e-9)) and np.all(h[:-1] <= 2 * h[1:] * (1 + 1e-9))
    assert np.diff(refined).min() < np.diff(theta)[40] / 3


def test_refined_mesh_carries_a_P1_slip_exactly(hertz):
    theta = gk.initial_theta()
    slip = np.random.default_rng(1).normal(size=theta.size)  # theta order
    targets = np.full(theta.size - 1, np.inf)
    targets[[3, 30, 60]] = np.diff(theta)[[3, 30, 60]] / 5
    refined = gk.refine(theta, targets)
    carried = np.interp(refined, theta, slip)
    np.testing.assert_array_equal(carried[np.searchsorted(refined, theta)], slip)
    coarse, fine = scene_of(hertz, theta), scene_of(hertz, refined)
    # the same P1 field: same energy, same delta_Q
    np.testing.assert_allclose(carried[::-1] @ fine.G @ carried[::-1], slip[::-1] @ coarse.G @ slip[::-1], rtol=1e-12)
    np.testing.assert_allclose(fine.delta_Q(slipped(carried[::-1])), coarse.delta_Q(slipped(slip[::-1])), rtol=1e-12)


def test_targets_of_several_increments_are_their_minimum():
    theta = gk.uniform_theta(32)
    ds = np.zeros((2, theta.size))
    ds[0, :3], ds[1, -5:] = 1e-9, -1e-9
    both = gk.element_targets(theta, ds)
    np.testing.assert_array_equal(both, np.minimum(gk.element_targets(theta, ds[0]), gk.element_targets(theta, ds[1])))
    assert np.all(np.isinf(gk.element_targets(theta, np.zeros(theta.size))))


def test_invalid_meshes_and_targets(hertz):
    with pytest.raises(ValueError, match="from 0 to pi"):
        scene_of(hertz, [0.0, 2.0, 1.0, np.pi])
    with pytest.raises(ValueError, match="one per node"):
        gk.element_targets(gk.uniform_theta(4), np.zeros(3))
    with pytest.raises(ValueError, match="positive sizes"):
        gk.refine(gk.uniform_theta(4), np.zeros(4))


def test_a_slip_zone_at_one_edge_node_is_refined():
    theta = gk.uniform_theta(16)
    ds = np.zeros(theta.size)
    ds[-1] = 1e-9  # the node at theta = 0 slipped (ascending x: last)
    targets, h = gk.element_targets(theta, ds), np.diff(theta)
    # the boundary lies in the edge element: past h / BOUNDARY_GRADING from it the grading asks no smaller element
    far = theta[:-1] >= h[0] * (1 + 1 / gk.mesh.BOUNDARY_GRADING)
    assert targets[0] < h[0] and far.sum() > theta.size // 2 and np.all(targets[far] >= h[far])
    ds[8], ds[9] = 1e-9, -1e-9  # opposite directions side by side hide a stick zone
    assert gk.element_targets(theta, ds)[16 - 9] < np.diff(theta)[16 - 9]


def test_slips_of_the_size_of_rounding_are_read_as_stuck(monkeypatch):
    """Nodes back at their limit where a loop closes, started slipping, slip by the solve's rounding either
    way (`mesh.settled`): they make no zones, which would otherwise each be refined down to MIN_SIZE."""
    theta = gk.uniform_theta(32)
    ds = np.zeros(theta.size)
    ds[:4], ds[-4:] = -1e-9 * np.arange(4, 0, -1), 1e-9 * np.arange(1, 5)
    chattering = ds.copy()
    chattering[10:20:2], chattering[11:20:4] = 3e-25, -2e-25
    np.testing.assert_array_equal(gk.element_targets(theta, chattering), gk.element_targets(theta, ds))
    np.testing.assert_array_equal(mesh.boundaries(theta, chattering), mesh.boundaries(theta, ds))
    monkeypatch.setattr(mesh, "CHATTER", 0.0)
    assert mesh.boundaries(theta, chattering).size > mesh.boundaries(theta, ds).size == 2


def test_a_loop_closed_at_a_turning_point_is_refined_for_no_zone_of_rounding():
    """Q alone, 0 -> -0.82 -> 0.15 -> -0.82 f P on a Hertz contact, the mesh asked for: the last step closes
    the loop (Masing), where the nodes that slipped on the first branch and stuck since are back at their
    limit. No element of the adapted mesh is refined toward the smallest size the targets allow."""
    contact = harness.family_contact("hertz", (0.5,), 0.3, 3e5)
    path = np.array([0.0, -0.8245680769766501, 0.15002777154926972, -0.8245680769766501])
    history = fr.History.piecewise_linear(path * contact.f * contact.P, None, 4)
    result = fr.simulate(contact, history, rtol=fr.DEFAULT_RTOL)
    assert np.abs(np.diff(result.theta.values)).min() > 100 * mesh.MIN_SIZE


def test_settled_mesh_resolves_tiny_stick_zone():
    """Q = 0.999999 f P: the stick zone of half-width 0.001 a has several elements."""
    contact = hertz_contact()
    Q = 0.999999 * contact.f * contact.P
    scene, ds, _, _ = adapt(contact, monotonic(Q)[0])
    stuck = np.flatnonzero(ds.sum(axis=0) == 0)
    assert stuck.size >= mesh.MIN_ZONE_NODES


# --- meshes adapted at the turning points of a history --------------------------------------------


def test_turning_points_keep_reversals_stops_and_vertices():
    history = fr.History.concatenate(
        [
            fr.History.sinusoidal(1.0, 0.5, 90, cycles=2, steps_per_cycle=16),
            fr.History.piecewise_linear([0, 0.3, 0.3], [0.5, 0.5, 0.5], 3),
        ]
    )
    turning = history.turning_points()
    Q, sigma = history.Q, history.sigma
    kept = [0, len(history) - 1, *history.vertex_step]
    for load in (Q, sigma):
        for k in range(1, len(history) - 1):
            before, after = np.sign(load[k] - load[k - 1]), np.sign(load[k + 1] - load[k])
            if before != 0 and after != before:
                kept.append(k)
    steps = np.unique(kept)
    np.testing.assert_array_equal(turning.Q, Q[steps])
    np.testing.assert_array_equal(turning.sigma, sigma[steps])
    np.testing.assert_array_equal(turning.cycle, history.cycle[steps])
    np.testing.assert_array_equal(steps[turning.vertex_step], history.vertex_step)
    assert steps.size < len(history) // 2  # a 90-degree sinusoid turns 4 times a cycle


def test_turning_points_cut_curved_stretches_only():
    """A 90-degree cycle of 24 steps is a circle in units (2, 3): its direction turns 15 degrees a
    step, so with cuts every 40 degrees each quarter between turning points is cut once, at the
    increment that has turned 45 degrees. In-phase cycles and straight segments are not cut, however
    small the turn: their directions differ by rounding only."""
    units = (2.0, 3.0)
    circle = fr.History.sinusoidal(*units, phase_deg=90, cycles=2, steps_per_cycle=24)
    ramp = circle.vertex_step[1]  # the straight ramp from (0, 0) to the top of the circle
    turning = np.concatenate([[0], ramp + 6 * np.arange(9)])  # Q or sigma reverses every quarter
    np.testing.assert_array_equal(circle.turning_points().Q, circle.Q[turning])
    cut = circle.turning_points(np.radians(40), units)
    steps = np.union1d(turning, ramp + 3 + 6 * np.arange(8))
    np.testing.assert_array_equal(cut.Q, circle.Q[steps])
    np.testing.assert_array_equal(cut.sigma, circle.sigma[steps])
    np.testing.assert_array_equal(steps[cut.vertex_step], circle.vertex_step)
    vertices = np.random.default_rng(2).uniform(-1, 1, (2, 8))
    for straight in (
        fr.History.sinusoidal(*units, cycles=2, steps_per_cycle=24, Q_mean=0.5, sigma_mean=-1.0),
        fr.History.piecewise_linear(*vertices, steps_per_segment=7),
    ):
        np.testing.assert_array_equal(straight.turning_points(1e-9, units).Q, straight.turning_points().Q)
    with pytest.raises(ValueError, match="max_turn"):
        circle.turning_points(0.0, units)


@pytest.mark.slow
def test_default_energy_of_a_90_degree_cycle(hertz):
    """Q = 0.5 fP sin, sigma = 0.8 f p0 sin(+90 deg), 2 cycles of 32 steps: 20 steps of a cycle slip
    between 0.64 a and 0.71 a from the centre, where no increment from one turning point to the
    next does. With each quarter cut at 45 degrees, energy per cycle and traction meet the targets
    of this module against the 1024-node grid (measured 4.0e-6 and 3.0e-4 f p0; without cuts
    5.6e-4 and 1.5e-3 f p0); the grid itself is within 3.3e-6 and 2.2e-4 f p0 of 1536 nodes."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    history = fr.History.sinusoidal(0.5 * fP, 0.8 * fp0, 90, cycles=2, steps_per_cycle=32)
    result = fr.simulate(hertz, history)
    assert result.attrs["rtol"] == gk.DEFAULT_RTOL  # a mesh, not the grid it falls back to
    errors = accuracy.score(result, accuracy.run_reference(fr.simulate(hertz, history, nodes=1024), "grid"))
    assert errors["energy_rel"] < gk.DEFAULT_RTOL
    assert errors["traction_fp0"] < 1e-3


@pytest.mark.slow
@pytest.mark.parametrize("psi", [1e-6, 0.001, 0.05, 0.2, 0.5, 0.95])
def test_many_steps_per_cycle_at_the_default_rtol(hertz, psi):
    """Issue-4 targets at the default rtol with 64 steps per cycle: each cycle's energy is within
    1e-4 of the Masing reference, also at 1e-6 fP, where the steps near the peaks move the slip
    zones of 5e-7 a by loads 1e-13 of f P (measured: 2e-5 or better). (Q alone on Hertz runs the
    exact model by default, tests/models/test_masing.py; the mesh is asked for here.)"""
    Q_star = psi * hertz.f * hertz.P
    result = fr.simulate(hertz, fr.History.sinusoidal(Q_star, cycles=3, steps_per_cycle=64), rtol=gk.DEFAULT_RTOL)
    assert result.attrs["rtol"] == gk.DEFAULT_RTOL
    steady = result.cycle_dissipation.values[1:]  # the first cycle starts from the virgin contact
    np.testing.assert_allclose(steady, cf.mindlin_deresiewicz_energy(hertz, Q_star), rtol=1e-4)


def test_default_runs_its_last_mesh_where_the_adapted_mesh_would_be_too_large(monkeypatch):
    """Out-of-phase Q = 0.47 fP, sigma = 1.19 f p0 (103 degrees) on a rounded flat: at rtol 1e-4
    the mesh would take more than MAX_DEFAULT_MESH nodes; the default stops adapting as soon as
    that is certain and runs the last mesh within the bound, the same run as that mesh asked for,
    saying so in a warning and in the dataset. The bound is lowered to 768 nodes to keep the test short."""
    monkeypatch.setattr(gk.model, "MAX_DEFAULT_MESH", 768)
    contact = fr.Contact(fr.RoundedFlat(1e-3, 0.02), 115e9, 0.3, 3e4)
    history = fr.History.sinusoidal(
        0.474 * contact.f * contact.P, 1.187 * contact.f * contact.p0, 103.6, cycles=3, steps_per_cycle=32
    )
    assert fr.adapted_mesh(contact, history, max_nodes=gk.model.MAX_DEFAULT_MESH) is None
    with pytest.warns(fr.ModelFallbackWarning, match="runs the last mesh within it"):
        result = fr.simulate(contact, history)
    assert result.attrs["model"] == "mesh" and result.sizes["x"] <= gk.model.MAX_DEFAULT_MESH
    state = fr.final_state(result)
    back = fr.History.piecewise_linear([state.Q, 0.0], [state.sigma, 0.0], 4)
    continued = fr.simulate(contact, back, state=state)  # the capped mesh goes on as it is, and says so
    np.testing.assert_array_equal(continued.theta.values, result.theta.values)
    assert continued.attrs["model_fallback"] == result.attrs["model_fallback"]
    reason = result.attrs.pop("model_fallback")
    assert f"over the default's bound of {gk.model.MAX_DEFAULT_MESH}" in reason
    given = fr.simulate(contact, history, mesh=result.theta.values[::-1])
    assert result.attrs.pop("rtol") == fr.DEFAULT_RTOL
    xr.testing.assert_identical(result, given)


@pytest.mark.parametrize(("Q", "sigma"), [(0.6, 0.0), (0.0, 0.9)])
def test_mesh_is_symmetric_under_one_load(hertz, Q, sigma):
    """Q alone (even) or sigma alone (odd) on Hertz: the adapted mesh is symmetric exactly, and so
    the slip is even or odd to rounding (the targets alone, mirrored, bisect differently by rounding)."""
    history = fr.History.piecewise_linear([0, Q * hertz.f * hertz.P], [0, sigma * hertz.f * hertz.p0], 8)
    theta = fr.adapted_mesh(hertz, history)
    np.testing.assert_array_equal(theta[theta > np.pi / 2], np.pi - theta[theta < np.pi / 2][::-1])
    slip = fr.simulate(hertz, history, mesh=theta).slip.values[-1]
    parity = 1 if Q else -1
    np.testing.assert_allclose(slip, parity * slip[::-1], rtol=0, atol=1e-12 * np.abs(slip).max())


def test_mesh_of_a_history_that_slides_is_that_of_the_steps_before(hertz):
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear([0, 0.8 * fP, 1.2 * fP], None, [4, 4])
    np.testing.assert_array_equal(fr.adapted_mesh(hertz, history), fr.adapted_mesh(hertz, history[:6]))
    with pytest.raises(fr.GrossSlipError) as error:
        fr.simulate(hertz, history, rtol=gk.DEFAULT_RTOL)
    assert error.value.step == 6  # Q = 1.0 fP


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_increment_does_not_depend_on_the_solver_s_start(hertz, seed):
    """`solve_increment`'s guess is a start only (the adaptation starts each pass from the slip
    directions of the pass before): from random directions the increment of a reversed,
    non-proportional load sticks at the same nodes and slips the same to 1e-12 of its largest."""
    rng = np.random.default_rng(seed)
    scene = scene_of(hertz, gk.refine(gk.initial_theta(), np.full(gk.initial_theta().size - 1, 0.02)))
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    loaded = solve_increment(scene.G, scene.g_stuck(0.7 * fP, 0.5 * fp0), scene.limit)
    g_stuck, slip = scene.g_stuck(-0.2 * fP, 0.9 * fp0), loaded.slip
    plain = solve_increment(scene.G, g_stuck, scene.limit, slip)
    started = solve_increment(scene.G, g_stuck, scene.limit, slip, rng.integers(-1, 2, slip.size).astype(np.int8))
    assert np.count_nonzero(plain.ds) and np.count_nonzero(plain.ds == 0)  # partial slip
    np.testing.assert_array_equal(started.ds == 0, plain.ds == 0)
    assert np.max(np.abs(started.slip - plain.slip)) <= 1e-12 * np.max(np.abs(plain.slip))


def test_the_energy_stage_skips_the_pass_after_a_small_refinement(monkeypatch):
    """On the harness's 10-vertex random scene the energy stage's last refinement adds under
    `SETTLED` of the nodes: the stage ends there, one pass fewer, on the mesh that the pass it skips
    would have confirmed (node for node)."""
    contact = harness.hertz_contact()
    history = harness.baseline_history(contact, 2)
    passes, run = [], gk.adaptation._Adaptation.run

    def counted(adapt, *args, **options):
        passes.append(adapt)
        return run(adapt, *args, **options)

    monkeypatch.setattr(gk.adaptation._Adaptation, "run", counted)
    settled = fr.adapted_mesh(contact, history)
    skipping = len(passes)
    monkeypatch.setattr(gk.adaptation, "SETTLED", 0.0)
    passes.clear()
    np.testing.assert_array_equal(fr.adapted_mesh(contact, history), settled)
    assert len(passes) == skipping + 1


@pytest.mark.slow
def test_adaptation_started_from_the_pass_before_settles_on_the_same_mesh(monkeypatch):
    """Starting each pass's active sets from the directions the pass before found (the default)
    or from the increment before's (as `simulate` does) gives the same mesh, node for node, on
    the harness's 10-vertex random scene."""
    contact = harness.hertz_contact()
    history = harness.baseline_history(contact, 2)
    warm = fr.adapted_mesh(contact, history)
    monkeypatch.setattr(gk.adaptation, "_interpolated_directions", lambda *args: None)
    np.testing.assert_array_equal(warm, fr.adapted_mesh(contact, history))
