"""The threshold search (`fretting.analysis.fatigue.threshold`) against closed forms at the trailing edge.

Under ``Q`` alone cycling between ``+-Q*`` (Cattaneo-Mindlin and Masing's rule), the surface of the contact's edge
``x = +-a`` carries neither pressure nor shear, and the direct stress there is ``-+2 f p0 sqrt(Q / (f P))`` at
``Q = +-Q*`` (the sliding term ``-2 f p0`` and the stick zone's correction ``2 f p0 (1 - sqrt(1 - c^2 / a^2))``,
``c / a = sqrt(1 - Q / (f P))``): a fully reversed uniaxial ``sigma_xx`` of amplitude ``S = 2 f p0 sqrt(Q* / (f
P))``, with ``sigma_yy = nu sigma_xx`` in plane strain. A criterion read at that hot spot reaches a target value
``V(S)`` at ``Q* / (f P) = (S / (2 f p0))^2``.
"""

import math

import pytest

import fretting as fr
from fretting.analysis import fatigue
from fretting.analysis.fatigue import Material, threshold
from fretting.loading.examples import EXAMPLES

NU = 0.3
STEEL = Material.from_file(EXAMPLES / "materials" / "steel.toml")


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, NU), 0.6, 3.5e5)


def cycles(Q_a):
    return fr.History.sinusoidal(Q_a, cycles=2, steps_per_cycle=32)


def test_findley_threshold_at_the_hot_spot_is_the_push_pull_limit_at_the_edge(contact):
    """At the edge Findley's parameter is ``(S / 2) (sqrt(1 + k^2) + k)`` (uniaxial, on the planes that contain
    ``y``), which reaches its limit ``t_-1 sqrt(1 + k^2)`` at ``S = f_-1`` (the constant ``k`` makes push-pull
    and torsion limits equal): ``Q* / (f P) = (f_-1 / (2 f p0))^2``. The search stops within `THRESHOLD_XTOL`
    ``f P``."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    found = threshold(contact, cycles, "findley", STEEL, at="hot spot", nu=NU)
    assert found.amplitude / fP == pytest.approx((STEEL.sigma_limit / (2 * fp0)) ** 2, abs=fatigue.THRESHOLD_XTOL)
    assert abs(float(found.values.x)) == contact.a
    assert float(found.values.parameter) == pytest.approx(STEEL.findley_limit(), rel=1e-5)
    assert found.runs < 12


def test_swt_threshold_for_a_life_at_the_hot_spot(contact):
    """At the edge SWT is ``(1 - nu^2) S^2 / E`` in plane strain: the life ``N`` is reached at ``S = sqrt(E SWT(N)
    / (1 - nu^2))``, ``SWT(N)`` the strain-life curve."""
    fP, fp0, N, m = contact.f * contact.P, contact.f * contact.p0, 1e6, STEEL
    swt = m.sigma_f**2 / m.E * (2 * N) ** (2 * m.b) + m.sigma_f * m.eps_f * (2 * N) ** (m.b + m.c)
    S = math.sqrt(m.E * swt / (1 - NU**2))
    found = threshold(contact, cycles, "swt", m, life=N, at="hot spot", nu=NU)
    assert found.amplitude / fP == pytest.approx((S / (2 * fp0)) ** 2, abs=fatigue.THRESHOLD_XTOL)
    assert fatigue.life(found.values, m) == pytest.approx(N, rel=1e-4)


def test_point_method_threshold_reads_the_limit_at_half_the_critical_distance(contact):
    """Read ``L/2`` below the hot spot the parameter falls below its surface value: the threshold is higher than
    the hot spot's, and the parameter read there is the limit."""
    soft = Material(E=STEEL.E, nu=NU, sigma_limit=300e6, tau_limit=200e6, critical_distance=STEEL.critical_distance)
    surface = threshold(contact, cycles, "crossland", soft, at="hot spot", nu=NU)
    below = threshold(contact, cycles, "crossland", soft, at="point", nu=NU)
    assert below.amplitude > surface.amplitude
    assert float(below.values.parameter) == pytest.approx(soft.crossland_constants()[1], rel=1e-5)


def test_threshold_refuses_what_it_cannot_search(contact):
    with pytest.raises(ValueError, match="criterion: swt has no fatigue limit, give a life"):
        threshold(contact, cycles, "swt", STEEL)
    with pytest.raises(ValueError, match="at: found 'edge', expected 'point', 'line' or 'hot spot'"):
        threshold(contact, cycles, "findley", STEEL, at="edge")
    with pytest.raises(ValueError, match=r"bracket: the criterion less its limit is -[\d.e+]+ at Q_a = .* expected a"):
        threshold(contact, cycles, "findley", STEEL, at="hot spot", bracket=(0.01, 0.1), nu=NU)
    with pytest.raises(ValueError, match="material: threshold needs critical_distance, found None"):
        threshold(contact, cycles, "findley", Material(E=STEEL.E, nu=NU, sigma_limit=5e8, tau_limit=3.2e8))
