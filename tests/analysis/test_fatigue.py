"""Multiaxial fatigue criteria, strain-life and critical distances against references derived by hand.

Notation: a history sampled at ``T`` evenly spaced instants of one period, ``t_j = 2 pi j / T``.
Where the maximum over time of a sinusoid ``R cos(t - t0)`` falls between samples, the sampled maximum
is at least ``R cos(pi / T)``: the tolerance `SAMPLED` below.
"""

import argparse
import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from fretting import cli
from fretting.analysis.fatigue import (
    CRITERIA,
    Material,
    MaterialFileError,
    apply,
    crossland,
    crossland_life,
    dang_van,
    dang_van_life,
    fatemi_socie,
    fatemi_socie_life,
    findley,
    findley_life,
    life,
    line_method,
    mwcm,
    mwcm_life,
    point_method,
    swt,
    swt_life,
)
from fretting.loading.examples import EXAMPLES

T = 400
t = 2 * np.pi * np.arange(T) / T
ZERO = np.zeros(T)
#: 16 instants: enough where the extremes fall on multiples of pi/2, for the costlier search over all planes.
COARSE = 2 * np.pi * np.arange(16) / 16
#: Relative shortfall of the sampled maximum of a sinusoid (module docstring).
SAMPLED = 1 - math.cos(math.pi / T)
#: Relative error of a quantity read on a plane located to about 1e-8 rad (`fretting.analysis.fatigue.XTOL`) that is
#: not stationary there (MWCM's sigma_n,max on the plane of largest tau_a): first order, 10 times 1e-8.
PLANE_FIRST_ORDER = 1e-7

STEEL = Material(
    E=200e9,
    nu=0.3,
    sigma_f=900e6,
    b=-0.09,
    eps_f=0.6,
    c=-0.6,
    sigma_limit=300e6,
    tau_limit=200e6,
    fs_k=0.6,
    sigma_y=600e6,
    tau_f=520e6,
    b0=-0.1,
    gamma_f=1.0,
    c0=-0.65,
    N_A=2e6,
    critical_distance=1e-4,
)
CRITICAL_PLANE = (swt, findley, fatemi_socie, mwcm)


def uniaxial(sigma_a):
    """``sigma_xx = sigma_a sin t`` and nothing else (``sigma_yy = 0`` given: not plane strain)."""
    return sigma_a * np.sin(t), ZERO, ZERO, ZERO


def test_swt_uniaxial_is_sigma_a_squared_over_E_on_the_normal_plane():
    """Uniaxial: ``sigma_n = sigma cos^2 phi``, ``eps_n = sigma (cos^2 phi - nu sin^2 phi) / E``.

    Their product's maximum is at ``phi = 0``: ``sigma_a * sigma_a / E``.
    """
    sigma_xx, sigma_zz, tau_xz, sigma_yy = uniaxial(150e6)
    result = swt(sigma_xx, sigma_zz, tau_xz, STEEL, sigma_yy=sigma_yy)
    assert result.parameter == pytest.approx(150e6**2 / STEEL.E, rel=1e-13)
    assert result.phi == pytest.approx(0.0, abs=1e-7)
    assert result.sigma_n_max == pytest.approx(150e6, rel=1e-13)


def test_swt_in_plane_strain_uses_the_constrained_strain():
    """Plane strain adds ``sigma_yy = nu sigma``: ``eps_n = (1 + nu) sigma (cos^2 phi - nu) / E``.

    With ``|cos^2 phi - nu| <= 1 - nu`` the maximum is at ``phi = 0``: ``(1 - nu^2) sigma_a^2 / E``.
    """
    sigma_xx, sigma_zz, tau_xz, _ = uniaxial(150e6)
    result = swt(sigma_xx, sigma_zz, tau_xz, STEEL)
    assert result.parameter == pytest.approx((1 - STEEL.nu**2) * 150e6**2 / STEEL.E, rel=1e-13)
    assert result.amplitude == pytest.approx((1 - STEEL.nu**2) * 150e6 / STEEL.E, rel=1e-13)


def test_findley_uniaxial():
    """Uniaxial: ``tau_a = (sigma_a / 2) |sin 2 phi|``, ``sigma_n,max = (sigma_a / 2) (1 + cos 2 phi)``.

    ``F = (sigma_a / 2) (|sin 2 phi| + k + k cos 2 phi)``; ``sin u + k cos u`` peaks at ``sqrt(1 + k^2)``
    where ``tan u = 1 / k``: ``F = (sigma_a / 2) (sqrt(1 + k^2) + k)`` at ``|phi| = atan(1 / k) / 2``.
    """
    k = STEEL.findley_constant()
    result = findley(*uniaxial(150e6)[:3], STEEL, sigma_yy=ZERO)
    assert result.parameter == pytest.approx(150e6 / 2 * (math.sqrt(1 + k * k) + k), rel=1e-13)
    assert abs(result.phi) == pytest.approx(math.atan(1 / k) / 2, abs=1e-7)


def test_findley_k_from_the_fatigue_limits_makes_both_limits_critical():
    """At the push-pull limit ``f`` and at the torsion limit ``t`` Findley's parameter is the same.

    Torsion ``tau_xz = t sin t``: ``tau_a = t |cos 2 phi|``, ``sigma_n,max = t |sin 2 phi|``, so
    ``F = t sqrt(1 + k^2)``.
    """
    k = STEEL.findley_constant()
    push_pull = findley(*uniaxial(STEEL.sigma_limit)[:3], STEEL, sigma_yy=ZERO).parameter
    torsion = findley(ZERO, ZERO, STEEL.tau_limit * np.sin(t), STEEL).parameter
    assert torsion == pytest.approx(STEEL.tau_limit * math.sqrt(1 + k * k), rel=1e-13)
    assert push_pull == pytest.approx(torsion, rel=1e-13)


def test_pure_shear():
    """``tau_xz = tau_a sin t`` (``sigma_yy = 0``): on ``phi``, ``sigma_n = tau sin 2 phi``, ``tau cos 2 phi``.

    SWT: ``eps_n = (1 + nu) sigma_n / E`` (zero trace), so ``(1 + nu) tau_a^2 / E`` at ``|phi| = pi/4``.
    MWCM: largest ``tau_a`` on ``phi = 0``, where ``sigma_n = 0``: ``rho = 0``, parameter ``tau_a``.
    Fatemi-Socie: ``(tau_a / G) cos u (1 + m sin u)``, ``u = 2 phi``, ``m = k tau_a / sigma_y``; its
    derivative vanishes where ``2 m sin^2 u + sin u - m = 0``.
    Crossland: ``sqrt(J2) = |tau|``, ``sigma_h = 0``: ``tau_a``.
    """
    tau_a = 120e6
    stress = (ZERO, ZERO, tau_a * np.sin(t), ZERO)
    kwargs = {"sigma_yy": stress[3]}
    result = swt(*stress[:3], STEEL, **kwargs)
    assert result.parameter == pytest.approx((1 + STEEL.nu) * tau_a**2 / STEEL.E, rel=1e-13)
    assert abs(result.phi) == pytest.approx(math.pi / 4, abs=1e-7)
    result = mwcm(*stress[:3], STEEL, **kwargs)
    assert result.amplitude == pytest.approx(tau_a, rel=1e-13)
    assert result.parameter == pytest.approx(tau_a, rel=PLANE_FIRST_ORDER)
    assert min(abs(result.phi), abs(abs(result.phi) - math.pi / 2)) == pytest.approx(0, abs=1e-7)
    m = STEEL.fs_k * tau_a / STEEL.sigma_y
    sin_u = (math.sqrt(1 + 8 * m * m) - 1) / (4 * m)
    expected = tau_a / STEEL.G * math.sqrt(1 - sin_u**2) * (1 + m * sin_u)
    assert fatemi_socie(*stress[:3], STEEL, **kwargs).parameter == pytest.approx(expected, rel=1e-13)
    assert crossland(*stress[:3], STEEL, **kwargs).parameter == pytest.approx(tau_a, rel=1e-13)


def test_fatemi_socie_reads_the_engineering_shear_strain_amplitude():
    """Fatemi & Socie (1988): ``(Delta gamma_max / 2) (1 + k sigma_n,max / sigma_y)``, ``gamma`` the engineering
    shear strain. Uniaxial ``sigma_xx = sigma_a sin t`` (``sigma_yy = 0``): on ``phi``, ``tau_a = (sigma_a / 2)
    |sin u|``, ``u = 2 phi``, and ``sigma_n,max = (sigma_a / 2) (1 + cos u)``, so the parameter is
    ``(sigma_a / 2 G) sin u (1 + m (1 + cos u))``, ``m = k sigma_a / (2 sigma_y)``. With ``k = 0`` its largest,
    at ``u = pi/2``, is ``sigma_a / (2 G) = (1 + nu) sigma_a / E``: the amplitude of ``eps_1 - eps_3``, the
    largest engineering shear strain. With ``k > 0`` the derivative vanishes where ``2 m c^2 + (1 + m) c - m
    = 0``, ``c = cos u``."""
    sigma_a = 300e6
    stress = (sigma_a * np.sin(t), ZERO, ZERO)
    no_normal = Material(E=STEEL.E, nu=STEEL.nu, fs_k=0.0, sigma_y=STEEL.sigma_y)
    result = fatemi_socie(*stress, no_normal, sigma_yy=ZERO)
    assert result.parameter == pytest.approx((1 + STEEL.nu) * sigma_a / STEEL.E, rel=1e-13)
    assert result.amplitude == pytest.approx(result.parameter, rel=1e-13)
    m = STEEL.fs_k * sigma_a / (2 * STEEL.sigma_y)
    c = (math.sqrt((1 + m) ** 2 + 8 * m * m) - (1 + m)) / (4 * m)
    expected = sigma_a / (2 * STEEL.G) * math.sqrt(1 - c * c) * (1 + m * (1 + c))
    assert fatemi_socie(*stress, STEEL, sigma_yy=ZERO).parameter == pytest.approx(expected, rel=1e-13)


def test_mwcm_and_crossland_reach_their_thresholds_at_both_fatigue_limits():
    """Push-pull at ``f``: MWCM ``tau_a = f/2``, ``rho = 1``, parameter ``f/2 + kappa = lambda``; Crossland
    ``f/sqrt(3) + alpha f/3 = beta``. Torsion at ``t``: MWCM ``t = lambda``; Crossland ``t = beta``."""
    f, tau = STEEL.sigma_limit, STEEL.tau_limit
    _, lam = STEEL.mwcm_constants()
    _, beta = STEEL.crossland_constants()
    push_pull, torsion = uniaxial(f), (ZERO, ZERO, tau * np.sin(t), ZERO)
    assert mwcm(*push_pull[:3], STEEL, sigma_yy=ZERO).parameter == pytest.approx(lam, rel=PLANE_FIRST_ORDER)
    assert mwcm(*torsion[:3], STEEL, sigma_yy=ZERO).parameter == pytest.approx(lam, rel=PLANE_FIRST_ORDER)
    assert crossland(*push_pull[:3], STEEL, sigma_yy=ZERO).parameter == pytest.approx(beta, rel=1e-13)
    assert crossland(*torsion[:3], STEEL, sigma_yy=ZERO).parameter == pytest.approx(beta, rel=1e-13)


def test_dang_van_reaches_its_limit_at_both_fatigue_limits_and_centres_a_mean_stress():
    """Push-pull at ``f``: Tresca ``f/2`` with ``sigma_h = f/3`` at the peak, ``f/2 + a f/3 = t = b``; torsion at
    ``t``: Tresca ``t``, ``sigma_h = 0``. With a mean ``S``, ``sigma_xx = S + sigma_a sin t``, the deviatoric path
    is a segment whose midpoint is the mean's deviator: the mesoscopic shear is ``sigma_a |sin t| / 2``, and the
    parameter ``sigma_a / 2 + a (S + sigma_a) / 3``."""
    a, b = STEEL.dang_van_constants()
    assert (a, b) == pytest.approx((3 * (STEEL.tau_limit / STEEL.sigma_limit - 0.5), STEEL.tau_limit))
    assert dang_van(*uniaxial(STEEL.sigma_limit)[:3], STEEL, sigma_yy=ZERO).parameter == pytest.approx(b, rel=1e-13)
    torsion = dang_van(ZERO, ZERO, STEEL.tau_limit * np.sin(t), STEEL, sigma_yy=ZERO)
    assert (torsion.parameter, torsion.amplitude) == pytest.approx((b, b), rel=1e-13)
    S, sigma_a = -80e6, 150e6
    result = dang_van(S + sigma_a * np.sin(t), ZERO, ZERO, STEEL, sigma_yy=ZERO)
    assert result.parameter == pytest.approx(sigma_a / 2 + a * (S + sigma_a) / 3, rel=1e-13)
    assert result.sigma_h_max == pytest.approx((S + sigma_a) / 3, rel=1e-13)
    with pytest.raises(ValueError, match="dang_van needs sigma_limit / tau_limit <= 2 for a >= 0, found 2.5"):
        Material(E=1e9, nu=0.3, sigma_limit=2.5e8, tau_limit=1e8).dang_van_constants()


@pytest.mark.parametrize("offset", [0.0, 70e6], ids=["centred", "with a mean deviator"])
def test_dang_van_centres_a_triangular_path_on_its_enclosing_ball(offset):
    """Three states ``sigma_xx = -sigma_zz = D + R cos w``, ``tau_xz = R sin w``, ``w`` at 90, 210 and 330 degrees:
    in the coordinates ``((sigma_xx - sigma_zz) / 2, tau_xz)`` the deviator visits an equilateral triangle on the
    circle of radius ``R`` about ``(D, 0)``, whose enclosing ball is that circle, not the ball on a side
    (radius ``R sqrt(3) / 2``). About its centre each state has principal stresses ``+-R`` in the plane and 0 out
    of it, no mean stress: the parameter is ``R``, whatever the mean deviator ``D``."""
    R, angles = 120e6, np.radians([90.0, 210.0, 330.0])
    xx, xz = offset + R * np.cos(angles), R * np.sin(angles)
    result = dang_van(xx, -xx, xz, STEEL, sigma_yy=0 * xx)
    assert result.parameter == pytest.approx(R, rel=1e-13)


@pytest.mark.parametrize("seed", range(6))
def test_enclosing_ball_is_the_smallest_that_encloses(seed):
    """Random clouds in three dimensions, a flat one and one with repeated points. A ball that encloses the points
    is the smallest exactly when its centre lies in the convex hull of the points on its surface (the optimality
    condition of the minimax problem): non-negative weights summing to 1 on those points (within 1e-9 of the
    radius) rebuild the centre, by scipy's NNLS, to 1e-9 of the cloud's size."""
    from scipy.optimize import nnls

    from fretting.analysis.fatigue import _enclosing_centre

    rng = np.random.default_rng(seed)
    cloud = rng.normal(size=(rng.integers(5, 40), 3)) * [1.0, 0.5, 0.0 if seed == 4 else 2.0]
    if seed == 5:
        cloud = np.concatenate([cloud, cloud[:4]])
    centre = _enclosing_centre(cloud)
    distance = np.sqrt(np.sum((cloud - centre) ** 2, axis=1))
    surface = cloud[distance >= distance.max() * (1 - 1e-9)]
    weights, residual = nnls(np.vstack([surface.T, np.ones(len(surface))]), np.append(centre, 1.0))
    assert residual < 1e-9 * distance.max()
    assert 2 <= len(surface) <= 8 and np.all(weights >= 0)


def tension_torsion(sigma_a, tau_a, delay):
    """``sigma_xx = sigma_a sin t``, ``tau_xz = tau_a sin(t - delay)``, ``sigma_yy = 0``."""
    return sigma_a * np.sin(t), ZERO, tau_a * np.sin(t - delay), ZERO


def plane_amplitudes(sigma_a, tau_a, delay, phi):
    """Amplitudes of ``sigma_n`` and ``tau`` on ``phi`` under `tension_torsion`, as phasors.

    ``sigma_n = sigma_a cos^2(phi) sin t + tau_a sin(2 phi) sin(t - delay)`` and
    ``tau = tau_a cos(2 phi) sin(t - delay) - (sigma_a / 2) sin(2 phi) sin t``: a sum
    ``A sin t + B sin(t - d)`` has amplitude ``|A + B exp(-i d)|``; both are fully reversed.
    """
    turn = np.exp(-1j * delay)
    sigma_n = np.abs(sigma_a * np.cos(phi) ** 2 + tau_a * np.sin(2 * phi) * turn)
    tau = np.abs(tau_a * np.cos(2 * phi) * turn - sigma_a / 2 * np.sin(2 * phi))
    return sigma_n, tau


@pytest.mark.parametrize("delay", [0.0, math.pi / 2], ids=["proportional", "out-of-phase"])
def test_findley_and_mwcm_under_tension_torsion(delay):
    """Reference: the phasor amplitudes of `plane_amplitudes` over 2,000,001 planes (1.6e-6 rad apart)."""
    sigma_a, tau_a = 200e6, 70e6
    phi = np.linspace(-math.pi / 2, math.pi / 2, 2_000_001)
    sigma_n, tau = plane_amplitudes(sigma_a, tau_a, delay, phi)
    k = STEEL.findley_constant()
    reference = np.max(tau + k * sigma_n)
    result = findley(*tension_torsion(sigma_a, tau_a, delay)[:3], STEEL, sigma_yy=ZERO)
    assert result.parameter == pytest.approx(reference, rel=SAMPLED + 1e-11)
    assert result.parameter <= reference * (1 + 1e-11)
    kappa, _ = STEEL.mwcm_constants()
    plane = np.argmax(tau)
    expected = tau[plane] + kappa * sigma_n[plane] / tau[plane]
    assert mwcm(*tension_torsion(sigma_a, tau_a, delay)[:3], STEEL, sigma_yy=ZERO).parameter == pytest.approx(
        expected, rel=SAMPLED + PLANE_FIRST_ORDER
    )


@pytest.mark.parametrize(
    ("delay", "sqrt_j2_a"),
    [(0.0, math.sqrt(200e6**2 / 3 + 70e6**2)), (math.pi / 2, max(200e6 / math.sqrt(3), 70e6))],
    ids=["proportional", "out-of-phase"],
)
def test_crossland_under_tension_torsion(delay, sqrt_j2_a):
    """``J2 = sigma^2 / 3 + tau^2`` (deviator ``(2, -1, -1) sigma / 3`` plus the shear).

    In phase: ``sqrt(J2) = sqrt(sigma_a^2 / 3 + tau_a^2) |sin t|``. Out of phase the deviatoric path is an
    ellipse of semi-axes ``sigma_a / sqrt(3)`` and ``tau_a``, whose longest chord is its major axis. Both
    have ``sigma_h,max = sigma_a / 3``; the instants of the extremes (multiples of pi/2) are sampled.
    """
    alpha, _ = STEEL.crossland_constants()
    result = crossland(*tension_torsion(200e6, 70e6, delay)[:3], STEEL, sigma_yy=ZERO)
    assert result.amplitude == pytest.approx(sqrt_j2_a, rel=1e-13)
    assert result.parameter == pytest.approx(sqrt_j2_a + alpha * 200e6 / 3, rel=1e-13)


def random_history(seed, points=(), steps=T):
    """A non-proportional plane-strain history: three harmonics with random amplitudes, phases, means."""
    rng = np.random.default_rng(seed)
    components = []
    for _ in range(3):
        time = 2 * np.pi * np.arange(steps).reshape(steps, *(1 for _ in points)) / steps
        terms = [rng.normal(0, 100e6, points) * np.sin(n * time + rng.uniform(0, 7)) for n in (1, 2, 3)]
        components.append(rng.normal(0, 50e6, points) + sum(terms))
    return components


def rotate(sigma_xx, sigma_zz, tau_xz, beta):
    """The stress components on axes turned by ``beta`` about ``y`` (``R sigma R^T``, ``R`` a rotation by beta)."""
    c, s = math.cos(beta), math.sin(beta)
    return (
        c * c * sigma_xx + s * s * sigma_zz - 2 * s * c * tau_xz,
        s * s * sigma_xx + c * c * sigma_zz + 2 * s * c * tau_xz,
        s * c * (sigma_xx - sigma_zz) + (c * c - s * s) * tau_xz,
    )


@pytest.mark.parametrize("criterion", CRITICAL_PLANE)
def test_rotation_of_axes_shifts_the_plane_and_keeps_the_parameter(criterion):
    """Turning the stress by ``beta`` turns the critical plane by ``beta`` (mod pi); the parameter stays."""
    stress = [component[:, 0] for component in random_history(7, (1,))]
    beta = 0.7
    before = criterion(*stress, STEEL)
    after = criterion(*rotate(*stress, beta), STEEL, sigma_yy=STEEL.nu * (stress[0] + stress[1]))
    assert after.parameter == pytest.approx(before.parameter, rel=1e-7)
    shift = (after.phi - before.phi - beta + math.pi / 2) % math.pi - math.pi / 2
    assert shift == pytest.approx(0, abs=1e-6)


def test_crossland_is_invariant_under_a_rotation_of_axes():
    stress = random_history(8, (1,))
    before = crossland(*stress, STEEL)
    after = crossland(*rotate(*stress, 1.1), STEEL, sigma_yy=STEEL.nu * (stress[0] + stress[1]))
    assert after.parameter == pytest.approx(before.parameter, rel=1e-12)


def test_planes_out_of_the_x_z_family_govern_under_equibiaxial_stress():
    """``sigma_xx = sigma_zz = s sin t``, plane strain ``sigma_yy = 2 nu s sin t``: no x-z plane is sheared.

    A plane tilted ``theta`` from ``y``: ``sigma_n = s (sin^2 theta + 2 nu cos^2 theta) sin t`` and shear
    ``(1 - 2 nu) s sin theta cos theta sin t``, so Findley's parameter is
    ``s (k (1 + 2 nu) / 2 + ((1 - 2 nu) / 2) (sin 2 theta - k cos 2 theta))``, largest
    ``s (k (1 + 2 nu) + (1 - 2 nu) sqrt(1 + k^2)) / 2``. The tilted planes are sampled 1 degree apart:
    ``2 theta`` within 1 degree of the optimum costs at most a fraction ``1 - cos(1 deg)`` of that term.
    """
    s, nu, k = 100e6, STEEL.nu, STEEL.findley_constant()
    stress = (s * np.sin(COARSE), s * np.sin(COARSE), 0 * COARSE)
    in_plane = findley(*stress, STEEL)
    assert in_plane.parameter == pytest.approx(k * s, rel=1e-13)
    every = findley(*stress, STEEL, planes="all")
    best = s * (k * (1 + 2 * nu) + (1 - 2 * nu) * math.sqrt(1 + k * k)) / 2
    assert every.parameter <= best * (1 + 1e-13)
    assert every.parameter >= best - s * (1 - 2 * nu) / 2 * math.sqrt(1 + k * k) * (1 - math.cos(math.radians(1)))
    assert every.parameter > in_plane.parameter
    assert math.degrees(every.theta) == pytest.approx(45 + math.degrees(math.atan(k)) / 2, abs=0.5)


@pytest.mark.parametrize("criterion", CRITICAL_PLANE)
def test_the_x_z_planes_govern_a_plane_strain_surface_in_tension(criterion):
    """The free surface beside a contact: ``sigma_xx`` alone in the x-z plane, ``sigma_yy = nu sigma_xx``.

    Out of the family the shear between ``x`` and ``y`` is ``(1 - nu)`` times that between ``x`` and ``z``
    and the normal stresses no larger, so the search over all planes finds the in-plane result.
    """
    stress = (80e6 + 150e6 * np.sin(COARSE), 0 * COARSE, 0 * COARSE)
    in_plane, every = criterion(*stress, STEEL), criterion(*stress, STEEL, planes="all")
    assert every.theta == math.pi / 2
    assert every.parameter == in_plane.parameter


def test_points_are_independent_and_keep_their_shape():
    stress = random_history(3, (2, 3))
    whole = findley(*stress, STEEL)
    assert whole.parameter.shape == whole.phi.shape == (2, 3)
    alone = findley(*(component[:, 1, 2] for component in stress), STEEL)
    assert whole.parameter[1, 2] == pytest.approx(alone.parameter, rel=1e-12)


def test_swt_life_round_trip():
    """``SWT(N) = sigma_f'^2 / E (2N)^(2b) + sigma_f' eps_f' (2N)^(b + c)`` written out here, then inverted."""
    lives = np.array([1e1, 3e3, 1e5, 2e7, 1e10])
    m = STEEL
    reversals = 2 * lives
    parameter = m.sigma_f**2 / m.E * reversals ** (2 * m.b) + m.sigma_f * m.eps_f * reversals ** (m.b + m.c)
    assert swt_life(parameter, m) == pytest.approx(lives, rel=1e-10)
    assert swt_life(parameter[2], m) == pytest.approx(lives[2], rel=1e-10)
    assert swt_life(0.0, m) == math.inf
    with pytest.raises(ValueError, match="parameter: found .* expected at most"):
        swt_life(2 * (m.sigma_f**2 / m.E + m.sigma_f * m.eps_f), m)


def test_fatemi_socie_life_round_trip_and_fully_reversed_torsion():
    """``gamma_a (1 + k sigma_n,max / sigma_y) = tau_f' / G (2N)^b0 + gamma_f' (2N)^c0`` written out here, then
    inverted. In fully reversed torsion with ``k = 0`` the parameter is ``gamma_a = tau_a / G``: a torsion
    amplitude ``tau_a = G`` times the curve at ``N`` lives ``N``."""
    m, lives = STEEL, np.array([1e2, 1e4, 1e6, 1e9])
    parameter = m.tau_f / m.G * (2 * lives) ** m.b0 + m.gamma_f * (2 * lives) ** m.c0
    assert fatemi_socie_life(parameter, m) == pytest.approx(lives, rel=1e-10)
    torsion_only = Material(E=m.E, nu=m.nu, fs_k=0.0, sigma_y=m.sigma_y, tau_f=m.tau_f, b0=m.b0, gamma_f=1.0, c0=-0.65)
    tau_a = m.G * parameter[2]
    result = fatemi_socie(ZERO, ZERO, tau_a * np.sin(t), torsion_only, sigma_yy=ZERO)
    assert fatemi_socie_life(result.parameter, torsion_only) == pytest.approx(lives[2], rel=1e-10)
    with pytest.raises(ValueError, match="fatemi_socie_life needs tau_f, b0, gamma_f, c0"):
        fatemi_socie_life(1e-3, Material(E=m.E, nu=m.nu))
    with pytest.raises(ValueError, match=r"parameter: found 2, expected at most 1.0\d+ \(2 N_f = 1\)"):
        fatemi_socie_life(2.0, m)


@pytest.mark.parametrize(
    ("criterion", "criterion_life"),
    [(findley, findley_life), (crossland, crossland_life), (dang_van, dang_van_life)],
    ids=["findley", "crossland", "dang_van"],
)
def test_stress_lives_are_basquins_curve_in_push_pull(criterion, criterion_life):
    """Fully reversed push-pull of amplitude ``sigma_a = sigma_f' (2N)^b`` (Basquin) lives ``N`` by either
    criterion's relation: the parameter is ``f sigma_a``, with ``f = (sqrt(1 + k^2) + k) / 2`` (Findley,
    `test_findley_uniaxial`), ``1 / sqrt(3) + alpha / 3 = t_-1 / f_-1`` (Crossland: ``sqrt(J2)_a = sigma_a /
    sqrt(3)``, ``sigma_h,max = sigma_a / 3``) or ``1/2 + a/3 = t_-1 / f_-1`` (Dang Van: Tresca ``sigma_a / 2``
    and ``sigma_h = sigma_a / 3`` at the peak), and its curve ``f sigma_f' (2 N_f)^b``; ``2N`` is 1.2e6 here."""
    m, N = STEEL, 6e5
    k = m.findley_constant()
    factor = (math.sqrt(1 + k * k) + k) / 2 if criterion is findley else m.tau_limit / m.sigma_limit
    sigma_a = m.sigma_f * (2 * N) ** m.b
    parameter = criterion(*uniaxial(sigma_a)[:3], m, sigma_yy=ZERO).parameter
    assert parameter == pytest.approx(factor * sigma_a, rel=1e-13)
    assert criterion_life(parameter, m) == pytest.approx(N, rel=1e-10)
    assert criterion_life(np.array([parameter, 0.0]), m) == pytest.approx([N, math.inf], rel=1e-10)
    with pytest.raises(ValueError, match="_life needs sigma_f, b, found None"):
        criterion_life(parameter, Material(E=m.E, nu=m.nu, sigma_limit=m.sigma_limit, tau_limit=m.tau_limit))


def test_mwcm_life_by_hand():
    """``N_f = N_A ((lambda - kappa rho) / tau_a)^(k_0 + (k_1 - k_0) rho)``, ``k_0 = -1/b0 = 10``, ``k_1 = -1/b``:
    torsion (``rho = 0``) at ``t_-1 / 2`` lives ``N_A 2^10``; push-pull (``rho = 1``) at the fatigue limit
    ``f_-1`` lives ``N_A``; and ``rho = 1/2`` by hand."""
    m = STEEL
    kappa, lam = m.mwcm_constants()
    assert mwcm_life(m.tau_limit / 2, 0.0, m) == pytest.approx(m.N_A * 2**10, rel=1e-13)
    torsion = mwcm(ZERO, ZERO, m.tau_limit / 2 * np.sin(t), m, sigma_yy=ZERO)
    assert mwcm_life(torsion.amplitude, torsion.sigma_n_max, m) == pytest.approx(m.N_A * 2**10, rel=1e-12)
    push_pull = mwcm(*uniaxial(m.sigma_limit)[:3], m, sigma_yy=ZERO)
    assert mwcm_life(push_pull.amplitude, push_pull.sigma_n_max, m) == pytest.approx(m.N_A, rel=1e-6)
    tau_a, rho = 90e6, 0.5
    k = -1 / m.b0 + (1 / m.b0 - 1 / m.b) * rho
    expected = m.N_A * ((lam - kappa * rho) / tau_a) ** k
    assert mwcm_life(np.array([tau_a, 0.0]), np.array([rho * tau_a, 1e8]), m) == pytest.approx([expected, math.inf])
    with pytest.raises(ValueError, match="rho: found 20, outside the MWCM's curves"):
        mwcm_life(1e6, 2e7, m)
    with pytest.raises(ValueError, match="mwcm_life needs b0, N_A, found None"):
        mwcm_life(tau_a, 0.0, Material(E=m.E, nu=m.nu, b=m.b, sigma_limit=m.sigma_limit, tau_limit=m.tau_limit))


def test_life_maps_every_criterion_by_its_relation():
    """`life` of the maps of `apply` is each criterion's life function at every point."""
    z, x = np.linspace(0, 1e-3, 3), np.linspace(-1e-3, 1e-3, 4)
    amplitude = 250e6 * np.exp(-z[:, None] / 5e-4) * (1 + x[None, :] / 4e-3)
    history = amplitude * np.sin(COARSE)[:, None, None]
    field = xr.Dataset(
        {
            "sigma_xx": (("step", "z", "x"), history),
            "sigma_zz": (("step", "z", "x"), 0.3 * history),
            "tau_xz": (("step", "z", "x"), 0.2 * history),
        },
        coords={"z": z, "x": x},
    )
    by_parameter = {"swt": swt_life, "findley": findley_life, "fatemi_socie": fatemi_socie_life}
    by_parameter |= {"crossland": crossland_life, "dang_van": dang_van_life}
    for name in CRITERIA:
        maps = apply(field, name, STEEL)
        lives = life(maps, STEEL)
        assert lives.dims == ("z", "x") and lives.attrs["definition"] == CRITERIA[name].life_name
        if name == "mwcm":
            expected = mwcm_life(maps.amplitude, maps.sigma_n_max, STEEL)
        else:
            expected = by_parameter[name](maps.parameter, STEEL)
        np.testing.assert_array_equal(lives, expected)
        assert np.all(np.isfinite(lives)) and np.all(np.diff(lives.values, axis=0) > 0)  # longer deeper down


def linear_map(psi0, z_max=1e-3):
    """``1 + (x - 2e-4) sin psi0 + z cos psi0``, exact under linear interpolation: along the direction
    ``psi`` from ``x = 2e-4`` it is ``1 + r cos(psi - psi0)``."""
    x, z = np.linspace(-1e-3, 1e-3, 81), np.linspace(0, z_max, 41)
    values = 1 + (x[None, :] - 2e-4) * math.sin(psi0) + z[:, None] * math.cos(psi0)
    return xr.DataArray(values, coords={"z": z, "x": x}, dims=("z", "x"))


def test_critical_distances_on_an_exponential_gradient():
    """``A exp(-z / d) (1 - (x / w)^2)``: the hot spot is ``x = 0`` (a node); down from it the point method
    gives ``A exp(-L / (2 d))``, the line method ``A (d / (2 L)) (1 - exp(-2 L / d))``. Linear interpolation
    between nodes ``h`` apart errs by at most ``h^2 / 8`` times the second derivative, ``A / d^2``."""
    A, d, L = 300e6, 2e-4, 1e-4
    z, x = np.linspace(0, 1e-3, 2001), np.linspace(-1e-3, 1e-3, 201)
    values = A * np.exp(-z[:, None] / d) * (1 - (x[None, :] / 2e-3) ** 2)
    field = xr.DataArray(values, coords={"z": z, "x": x}, dims=("z", "x"))
    bound = (z[1] - z[0]) ** 2 / 8 * A / d**2
    point = point_method(field, L)
    assert (point.x_hot, point.angle) == (0.0, 0.0)
    assert point.value == pytest.approx(A * math.exp(-L / (2 * d)), abs=bound)
    line = line_method(field, L)
    assert line.value == pytest.approx(A * d / (2 * L) * (1 - math.exp(-2 * L / d)), abs=bound)
    assert abs(line.value - A * math.exp(-L / (2 * d))) > 10 * bound


def test_line_method_integrates_the_interpolant_exactly_down_a_grid_of_rounded_spacing():
    """``exp(-z / d)`` on 21 depths 0.025 apart, whose computed spacing is below 0.025 (``0.2 / h = 8 + 1e-14``):
    down a column the bilinear interpolant is the piecewise-linear one through the nodes, whose integral over
    ``2 L = 0.2`` (eight cells) is the trapezoid sum over the nodes ``z <= 0.2``, to rounding."""
    d, L = 0.1, 0.1
    z, x = np.linspace(0, 0.5, 21), np.linspace(-1, 1, 81)
    assert 2 * L / np.diff(z).min() > 8
    field = xr.DataArray(np.exp(-z[:, None] / d) * np.ones(x.size), coords={"z": z, "x": x}, dims=("z", "x"))
    nodes = z[:9]
    exact = np.sum(np.diff(nodes) * (np.exp(-nodes[:-1] / d) + np.exp(-nodes[1:] / d)) / 2) / (2 * L)
    assert line_method(field, L).value == pytest.approx(exact, rel=1e-14)


@pytest.mark.parametrize("degrees", [-60, -17, 0, 25, 80])
def test_line_method_integrates_a_bilinear_map_exactly_in_any_direction(degrees):
    """``1 + 4e6 (x - x0) z``, bilinear, so its own interpolant: along ``psi`` from ``x_hot`` it is
    ``1 + 4e6 (x_hot - x0 + r sin psi) r cos psi``, whose mean over ``[0, R]`` is
    ``1 + 4e6 cos psi ((x_hot - x0) R / 2 + sin psi R^2 / 3)``: quadratic in ``r``, which no trapezoid rule
    integrates exactly."""
    x, z = np.linspace(-1e-3, 1e-3, 81), np.linspace(0, 1e-3, 41)
    x0, x_hot, L, psi = -3e-4, 1.3e-4, 2e-4, math.radians(degrees)
    field = xr.DataArray(1 + 4e6 * (x[None, :] - x0) * z[:, None], coords={"z": z, "x": x}, dims=("z", "x"))
    R = 2 * L
    exact = 1 + 4e6 * math.cos(psi) * ((x_hot - x0) * R / 2 + math.sin(psi) * R**2 / 3)
    line = line_method(field, L, direction=psi, x_hot=x_hot)
    assert line.value == pytest.approx(exact, rel=1e-14)


def test_critical_distance_directions():
    L = 4e-4
    field = linear_map(math.radians(30))
    assert point_method(field, L, x_hot=2e-4).value == pytest.approx(1 + L / 2 * math.cos(math.radians(30)))
    best = point_method(field, L, direction="max", x_hot=2e-4)
    assert (best.value, math.degrees(best.angle)) == pytest.approx((1 + L / 2, 30))
    line = line_method(field, L, direction="max", x_hot=2e-4)
    assert (line.value, math.degrees(line.angle)) == pytest.approx((1 + L, 30))
    chosen = point_method(field, L, direction=math.radians(-20), x_hot=2e-4)
    assert chosen.value == pytest.approx(1 + L / 2 * math.cos(math.radians(50)))


def test_critical_distance_needs_a_grid_that_reaches_it():
    field = linear_map(0.0, z_max=1e-4)
    assert point_method(field, 2e-4).value == pytest.approx(1 + 1e-4)
    with pytest.raises(ValueError, match="parameter: the grid spans .* expected it to reach 0.0004 m"):
        line_method(field, 2e-4)
    with pytest.raises(ValueError, match="expected it to reach 0.0004 m from x = 0 m along any direction"):
        line_method(linear_map(0.0, z_max=1e-4).sel(x=slice(0, 1e-4)), 2e-4, direction="max", x_hot=0.0)
    with pytest.raises(ValueError, match="direction: found 'up'"):
        point_method(field, 2e-4, direction="up")
    with pytest.raises(ValueError, match="L must be > 0"):
        point_method(field, -1.0)
    with pytest.raises(ValueError, match="parameter: expected coordinates"):
        point_method(field.isel(z=slice(1, None)), 1e-5)


def test_apply_maps_a_criterion_over_a_field():
    """``sigma_xx = A(z, x) sin t`` with ``sigma_yy = 0``: the SWT map is ``A^2 / E``."""
    z, x = np.linspace(0, 1e-3, 4), np.linspace(-1e-3, 1e-3, 5)
    amplitude = 100e6 * np.exp(-z[:, None] / 5e-4) * (1 + x[None, :] / 2e-3)
    nothing = ("step", "z", "x"), np.zeros((T, z.size, x.size))
    dataset = xr.Dataset(
        {
            "sigma_xx": (("step", "z", "x"), amplitude * np.sin(t)[:, None, None]),
            "sigma_zz": nothing,
            "tau_xz": nothing,
            "sigma_yy": nothing,
        },
        coords={"z": z, "x": x},
    )
    maps = apply(dataset, "swt", STEEL)
    assert maps.parameter.dims == ("z", "x") and maps.parameter.attrs["units"] == "Pa"
    np.testing.assert_allclose(maps.parameter.values, amplitude**2 / STEEL.E, rtol=1e-13)
    np.testing.assert_allclose(maps.z, z)
    invariant = apply(dataset, "crossland", STEEL)
    assert set(invariant) == {"parameter", "amplitude", "sigma_h_max"}
    alpha, _ = STEEL.crossland_constants()
    np.testing.assert_allclose(invariant.parameter, amplitude / math.sqrt(3) + alpha * amplitude / 3, rtol=1e-13)
    with pytest.raises(ValueError, match="criterion: found 'papadopoulos', expected one of: swt, findley"):
        apply(dataset, "papadopoulos", STEEL)
    with pytest.raises(ValueError, match="field: expected a variable tau_xz"):
        apply(dataset.drop_vars("tau_xz"), "swt", STEEL)


def test_one_registry_declares_every_criterion():
    """`CRITERIA` is the one declaration of the criteria: the command line accepts exactly its names (for
    ``--criterion`` and ``--figure``), `apply` maps each with the units and names it declares, and the
    guides list each."""
    stress = next(action for action in cli._parser()._actions if isinstance(action, argparse._SubParsersAction))
    options = {action.dest: action.choices for action in stress.choices["stress"]._actions}
    assert list(options["criterion"]) == list(CRITERIA) and set(CRITERIA) <= set(options["figure"])
    assert cli.stress.DEFAULT_CRITERION in CRITERIA
    tension = 100e6 * np.sin(COARSE)[:, None, None] * np.ones((1, 2, 3))
    field = xr.Dataset(
        {name: (("step", "z", "x"), tension * (name == "sigma_xx")) for name in ("sigma_xx", "sigma_zz", "tau_xz")}
    )
    for name, criterion in CRITERIA.items():
        maps = apply(field, name, STEEL)
        declared = (criterion.units, criterion.long_name, criterion.amplitude_units, criterion.amplitude_name)
        assert (criterion.name, maps.attrs["criterion"]) == (name, name)
        assert tuple(maps[v].attrs[k] for v in ("parameter", "amplitude") for k in ("units", "long_name")) == declared
    guides = Path(__file__).parents[2] / "docs" / "guide"
    table = re.findall(r"^\| `(\w+)` \|", (guides / "fatigue.md").read_text(), re.MULTILINE)
    assert table == list(CRITERIA)
    row = next(line for line in (guides / "cli.md").read_text().splitlines() if line.startswith("| `--criterion"))
    assert re.findall(r"`(\w+)`", row.split("|")[2].split("(")[0]) == list(CRITERIA)


def test_material_checks_its_constants():
    with pytest.raises(ValueError, match="E must be > 0"):
        Material(E=-1.0, nu=0.3)
    with pytest.raises(ValueError, match=r"nu must be in \(-1, 0.5\]"):
        Material(E=1e9, nu=0.7)
    with pytest.raises(ValueError, match="b must be < 0, found 0.1"):
        Material(E=1e9, nu=0.3, b=0.1)
    with pytest.raises(ValueError, match="material: findley needs sigma_limit, tau_limit, found None"):
        findley(*uniaxial(1e6)[:3], Material(E=1e9, nu=0.3))
    with pytest.raises(ValueError, match="findley needs 1 < sigma_limit / tau_limit < 2 for k, found 3"):
        Material(E=1e9, nu=0.3, sigma_limit=3e8, tau_limit=1e8).findley_constant()
    with pytest.raises(ValueError, match="material: fatemi_socie needs fs_k, sigma_y"):
        fatemi_socie(*uniaxial(1e6)[:3], Material(E=1e9, nu=0.3))


def test_bad_histories_are_refused():
    with pytest.raises(ValueError, match=r"sigma_zz: found shape \(3,\), expected that of sigma_xx \(400,\)"):
        swt(np.sin(t), np.zeros(3), ZERO, STEEL)
    with pytest.raises(ValueError, match="tau_xz: expected finite stresses"):
        swt(np.sin(t), ZERO, np.full(T, np.nan), STEEL)
    with pytest.raises(ValueError, match="sigma_xx: found a number, expected an array with the time axis first"):
        swt(1.0, 0.0, 0.0, STEEL)
    with pytest.raises(ValueError, match="planes: found 'some', expected 'in-plane' or 'all'"):
        swt(np.sin(t), ZERO, ZERO, STEEL, planes="some")


def test_material_file(tmp_path):
    shipped = Material.from_file(EXAMPLES / "materials" / "steel.toml")
    assert shipped.E > 0 and shipped.critical_distance > 0
    path = tmp_path / "material.toml"
    for text, message in [
        ("E = 2e11\nnu = 0.3\nsigma_u = 1e9\n", "material.toml: sigma_u: unknown key, expected one of: E, nu"),
        ("E = 2e11\nnu = '0.3'\n", "material.toml: nu: found '0.3', expected a number"),
        ("nu = 0.3\n", "material.toml: E: missing, expected a number"),
        ("E = 2e11\nnu = 0.3\nb = 0.1\n", "material.toml: b: found 0.1, expected < 0"),
        ("E = 2e11\nnu = 0.3\nb = \n", "material.toml: found invalid TOML"),
    ]:
        path.write_text(text)
        with pytest.raises(MaterialFileError, match=message):
            Material.from_file(path)


def dense_search(stress, planes=9000):
    """``sigma_n,max``, ``tau_a``, ``eps_a`` [Pa, Pa, 1] on ``planes`` in-plane normals, at one point."""
    xx, zz, xz = stress
    phi = np.pi * np.arange(planes)[:, None] / planes
    c, s = np.cos(phi), np.sin(phi)
    sigma_n = xx * c * c + zz * s * s + 2 * xz * s * c
    tau = (zz - xx) * s * c + xz * (c * c - s * s)
    eps_n = ((1 + STEEL.nu) * sigma_n - STEEL.nu * (1 + STEEL.nu) * (xx + zz)) / STEEL.E
    return sigma_n.max(axis=1), np.ptp(tau, axis=1) / 2, np.ptp(eps_n, axis=1) / 2


@pytest.mark.slow
def test_the_search_finds_the_dense_maximum_of_non_proportional_histories():
    """200 points of random three-harmonic histories (32 instants), whose parameters can have twin peaks: with
    this seed, at some point the best sample lies next to the lower one (refining the best sampled peak
    alone falls short by 1.4e-5 there). The dense search, 0.02 degrees apart, falls short of the maximum by
    ``O(spacing^2)`` relative, about 1e-7 here: the search must never find less than it by more."""
    stress = random_history(19, (200,), steps=32)
    k, G = STEEL.findley_constant(), STEEL.G
    formulas = {
        swt: lambda n, tau_a, eps_a: n * eps_a,
        findley: lambda n, tau_a, eps_a: tau_a + k * n,
        fatemi_socie: lambda n, tau_a, eps_a: tau_a / G * (1 + STEEL.fs_k * n / STEEL.sigma_y),
    }
    dense = [dense_search([component[:, point] for component in stress]) for point in range(200)]
    for criterion, formula in formulas.items():
        reference = np.array([formula(*terms).max() for terms in dense])
        found = criterion(*stress, STEEL).parameter
        assert np.all(found >= reference * (1 - 1e-7)), criterion.__name__
        assert np.all(found <= reference * (1 + 1e-6)), criterion.__name__


def test_mwcm_keeps_the_conjugate_plane_of_larger_normal_stress():
    """``sigma_xx = S + a sin t``, ``tau_xz = b sin t``, ``S < 0``: ``tau(phi)`` swings by
    ``(a/2) sin 2 phi - b cos 2 phi``, largest ``tau_a = sqrt(a^2/4 + b^2)`` on ``2 phi = atan2(-a/2, b)``
    and on its conjugate ``phi + pi/2``. Their ``sigma_n`` have the same amplitude (the two add up to
    ``sigma_xx``) and means ``S cos^2 phi``, ``S sin^2 phi``: the compressive mean picks the plane of
    smaller ``cos^2 phi``."""
    S, a, b = -100e6, 200e6, 60e6
    stress = (S + a * np.sin(t), ZERO, b * np.sin(t))
    phi = math.atan2(-a / 2, b) / 2
    phi = phi + math.pi / 2 if math.cos(phi) ** 2 > 0.5 else phi
    amplitude = abs(a * math.cos(phi) ** 2 + b * math.sin(2 * phi))
    tau_a, sigma_n_max = math.hypot(a / 2, b), S * math.cos(phi) ** 2 + amplitude
    kappa, _ = STEEL.mwcm_constants()
    result = mwcm(*stress, STEEL)
    assert result.phi == pytest.approx(phi, abs=1e-7)
    assert result.parameter == pytest.approx(tau_a + kappa * sigma_n_max / tau_a, rel=PLANE_FIRST_ORDER)


def sphere_findley(xx, zz, xz):
    """Findley's parameter by brute force over normals 2 degrees apart over the whole sphere, in 3-D:
    traction ``s n``, ``sigma_n = n . s n``, shear vector ``s n - sigma_n n``, ``tau_a`` half the longest
    chord of its path (plane strain ``sigma_yy``)."""
    stress = np.zeros((xx.size, 3, 3))
    stress[:, 0, 0], stress[:, 1, 1], stress[:, 2, 2] = xx, STEEL.nu * (xx + zz), zz
    stress[:, 0, 2] = stress[:, 2, 0] = xz
    phi, theta = np.meshgrid(np.radians(np.arange(0, 360, 2)), np.radians(np.arange(0, 181, 2)))
    n = np.stack([np.sin(theta) * np.cos(phi), np.cos(theta), np.sin(theta) * np.sin(phi)], axis=-1).reshape(-1, 3)
    traction = np.einsum("tij,pj->tpi", stress, n)
    sigma_n = np.einsum("tpi,pi->tp", traction, n)
    shear = traction - sigma_n[..., None] * n
    chords = np.linalg.norm(shear[:, None] - shear[None, :], axis=-1)
    return np.max(chords.max(axis=(0, 1)) / 2 + STEEL.findley_constant() * sigma_n.max(axis=0))


@pytest.mark.parametrize("mirror", [1, -1], ids=["history", "mirrored x"])
def test_the_search_over_all_planes_covers_the_whole_sphere(mirror):
    """The normals of `sphere_findley`, folded by ``n ~ -n`` and ``y -> -y``, are among the samples of
    ``planes="all"``, so it finds at least as much. The history is nearly equi-biaxial, so that tilted
    planes govern (the x-z family alone finds less); mirrored (``x -> -x``), its best normal turns to
    ``-phi``: a search missing either half of ``phi`` fails one of the two."""
    biaxial = 150e6 * np.sin(2 * np.pi * np.arange(16) / 16)
    xx, zz, xz = random_history(5, steps=16)
    xx, zz, xz = biaxial + 0.05 * xx, biaxial + 0.05 * zz, 0.05 * mirror * xz
    reference = sphere_findley(xx, zz, xz)
    found = findley(xx, zz, xz, STEEL, planes="all").parameter
    assert reference * (1 - 1e-12) <= found <= reference * (1 + 1e-3)
    assert findley(xx, zz, xz, STEEL).parameter < reference * 0.9
