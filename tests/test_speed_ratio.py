"""The yardstick of benchmarks/speed_ratio.py: the dense method-4 code against closed forms, and its scoring."""

import dense_method4
import harness
import numpy as np
import pytest
import speed_ratio

import fretting as fr
from fretting.models import Varying
from fretting.physics.closed_forms import cattaneo_mindlin_dissipation


@pytest.fixture(scope="module")
def hertz():
    return harness.hertz_contact()


@pytest.mark.parametrize("load", [0.3, 0.5, 0.8])
def test_dense_code_is_cattaneo_mindlin(hertz, load):
    """Hertz from the unloaded state to ``Q = load f P``: stick zone ``|x| < c = a sqrt(1 - Q/(f P))``,
    traction ``f p0 (sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2))`` (Johnson 1985, section 7.1;
    Cattaneo 1938, Mindlin 1949), energy of the Mindlin-Deresiewicz closed form.

    On 256 points (a spacing of 0.006-0.012 a at the stick ends) the errors are set by the
    square-root kinks at the stick ends: the bounds are 3 times the largest measured over the loads.
    """
    Q = load * hertz.f * hertz.P
    run = dense_method4.simulate(hertz, fr.History.piecewise_linear([0.0, Q], None, 4), 256)
    a, fp0 = hertz.a, hertz.f * hertz.p0
    c = a * np.sqrt(1 - load)
    zones = speed_ratio.stick_zones(run, 4, speed_ratio.episode_slip(run))
    np.testing.assert_allclose(zones, [[-c, c]], rtol=0, atol=1.5e-3 * a)
    x = run.x
    q = fp0 * (np.sqrt(1 - (x / a) ** 2) - c / a * np.sqrt(np.clip(1 - (x / c) ** 2, 0, None)))
    far = (np.abs(np.abs(x) - c) > 0.02 * a) & (np.abs(x) < 0.98 * a)
    assert np.abs(run.q[-1] - q)[far].max() < 1.5e-3 * fp0
    assert np.sum(run.dissipation) == pytest.approx(cattaneo_mindlin_dissipation(hertz, Q), rel=1.2e-3)
    assert run.stick[-1][np.abs(x) < c - 0.02 * a].all() and not run.stick[-1][np.abs(x) > c + 0.02 * a].any()


def test_dense_code_follows_jaeger_under_a_rising_normal_load(hertz):
    """``Q = lambda (P - P0)`` with ``lambda < f`` from a formed contact slips nowhere (Jaeger 1998;
    docs/theory/normal-load.md): the energy is rounding beside that of the same ``Q`` at constant ``P``."""
    P = [hertz.P, 1.3 * hertz.P]
    Q = 0.5 * hertz.f * (P[1] - P[0])
    run = dense_method4.simulate(hertz, fr.History.piecewise_linear([0.0, Q], None, 8, P=P), 128)
    assert run.a[-1] == pytest.approx(np.sqrt(1.3) * hertz.a, rel=1e-12)
    assert np.sum(run.dissipation) < 1e-6 * cattaneo_mindlin_dissipation(hertz, Q)
    assert np.all(run.q[:, run.p[-1] == 0] == 0) and np.abs(run.q[-1]).max() > 0


def test_bands_that_enter_under_jaegers_rule_count_as_stuck(hertz):
    """``P`` rising with ``Q`` and ``sigma`` such that ``|dQ -/+ (pi a / 4) dsigma| < f dP`` at both edges: every
    band sticks as it enters (Jaeger 1998), so every point in contact is stuck at every step and nothing
    dissipates. The free surfaces' motion before a point enters is not slip, and a point enters only at
    the end of a part (`dense_method4.part_ends`)."""
    P = np.array([hertz.P, 1.2 * hertz.P])
    dP = P[1] - P[0]
    Q, sigma = [0.0, 0.3 * hertz.f * dP], [0.0, 0.5 * hertz.f * dP * 4 / (np.pi * hertz.a)]
    run = dense_method4.simulate(hertz, fr.History.piecewise_linear(Q, sigma, 8, P=P), 256)
    assert all(stick[p > 0].all() for stick, p in zip(run.stick, run.p, strict=True))
    assert np.sum(run.dissipation) == 0
    assert np.count_nonzero(run.p[-1]) > np.count_nonzero(run.p[0])  # points entered


def test_traction_is_scored_away_from_the_edges_of_the_contacts_before(hertz):
    """Where ``P`` varies, a band that entered carries a traction that kinks at the edge it entered at: the
    traction is scored away from the edges of every step so far, as from the stick ends."""
    P = hertz.P * np.array([1.0, 1.2, 0.9])
    run = dense_method4.simulate(hertz, fr.History.piecewise_linear([0.0, 0.0, 0.0], None, 2, P=P), 64)
    kinks = speed_ratio.Truth.of(run).kinks
    for k in range(run.a.size):
        assert np.isin(np.concatenate([-run.a[: k + 1], run.a[: k + 1]]), kinks[k]).all()


@pytest.mark.parametrize("cells", [128, 256])
def test_slip_zones_narrower_than_a_spacing_are_located_by_the_traction_deficit(hertz, cells):
    """Cattaneo-Mindlin at ``Q = 0.003-0.05 f P`` on equal cells (`fretting.models.Varying`), whose slip zones
    at the edges, ``a - c`` with ``c = a sqrt(1 - Q / (f P))``, span from a fifth of a cell to a few: the
    ends are located within a quarter of a spacing (from the slip, or from the square-root law of the friction
    deficit where fewer than two points slip), where the middle of the last stuck and the first slipping
    point, or the contact edge, errs by up to two thirds of one."""
    for load in (0.003, 0.01, 0.02, 0.05):
        Q = load * hertz.f * hertz.P
        history = fr.History.piecewise_linear([0.0, Q], None, 1)
        run = speed_ratio.from_result(fr.simulate(hertz, history, model=Varying(cells)), hertz, history)
        c, spacing = hertz.a * np.sqrt(1 - load), 2 * hertz.a / cells
        zones = speed_ratio.stick_zones(run, 1, speed_ratio.episode_slip(run))
        np.testing.assert_allclose(zones, [[-c, c]], rtol=0, atol=spacing / 4)


def test_a_run_scored_against_itself_has_no_error_and_a_coarser_one_has(hertz):
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    history = fr.History.sinusoidal(0.5 * fP, 0.8 * fp0, 90.0, cycles=1, steps_per_cycle=16, ramp_steps=4)
    fine, coarse = (dense_method4.simulate(hertz, history, n) for n in (192, 64))
    truth = speed_ratio.Truth.of(fine)
    assert speed_ratio.score(fine, truth) == dict.fromkeys(speed_ratio.MEASURES, 0.0)
    errors = speed_ratio.score(coarse, truth)
    assert all(0 < errors[m] < 0.1 for m in speed_ratio.MEASURES)


def test_matching_takes_the_cheapest_N_from_which_every_finer_one_matches():
    def row(nodes, energy, ends):
        return {"nodes": nodes, "errors": {"energy": energy, "ends": ends}}

    default = row(None, 1e-4, 1e-3)
    rows = [row(64, 1e-2, 1e-2), row(128, 1e-4, 5e-3), row(256, 2e-4, 1e-3), row(512, 1e-5, 1e-4)]
    assert speed_ratio.matching(rows, default, ["energy"])["nodes"] == 512  # 128 matches, 256 does not
    assert speed_ratio.matching(rows, default, ["ends"])["nodes"] == 256
    assert speed_ratio.matching(rows, default, ["energy", "ends"])["nodes"] == 512
    assert speed_ratio.matching(rows[:-1], default, ["energy"]) is None
