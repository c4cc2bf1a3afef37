"""Displacement control under a varying normal load P(t) (docs/theory/displacement.md#varying-load): eq D13
(eq D4 at each instant with the half-width of the step's load), force and displacement control step by step on the
cells of `fretting.models.Varying`, a datum that the contact reaches, and gross slip under P(t): Q = +-f P,
each slide's energy by the trapezoidal rule in P, split runs resumed bit for bit."""

import numpy as np
import pytest
from displacement_speed import prescribed, sliding_cycle
from scipy.integrate import quad

import fretting as fr
from fretting.engine.recorder import final_state
from fretting.physics.contact import stuck_compliance

#: Datum [m] of the tests: about 21 half-widths from the middle of the Hertz contact below at P0.
L = 5e-3

#: Cells of the tests: few, since the checks compare two runs on the same cells.
SPEC = fr.models.Varying(64)


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=L)


def test_the_compliance_is_that_of_the_half_width_under_the_load(contact):
    """``C_L`` of ``a(P)`` (eq D3), the contact's own under its own load, and an error once ``a(P)`` reaches L."""
    for P in (0.5e5, 1e5, 2e5):
        a = float(contact.profile.half_width(P, contact.E_star)[0])
        assert contact.compliance_under(P) == stuck_compliance(L, a, contact.E_star)
    assert contact.compliance_under(None) == contact.displacement_compliance
    assert contact.displacement(2.0, 1e-9, 0.5e5) == contact.compliance_under(0.5e5) * 2.0 + 1e-9
    with pytest.raises(ValueError, match="not within the datum L = 0.005 m"):
        contact.compliance_under(1e9)


def test_proportional_loading_superposes_the_compliance_of_each_half_width(contact):
    """Jaeger: ``Q = lambda (P - P0)``, ``lambda < f``, slips nowhere and each ``dQ = lambda dP`` is a flat punch
    of the half-width ``a(P)`` then, so ``delta = lambda int_P0^P C_L(a(P')) dP'`` (eq D14; eq D13 counts the
    displacement at entry of the cells that entered in ``delta_Q``): to 1e-3 on 256 cells (the half-width of
    the cells in contact moves by pairs; 2e-4 on 1024), where ``C_L(a(P)) Q`` alone is 2.6 % short."""
    lam = 0.4
    P = np.linspace(1e5, 1.5e5, 6)
    history = fr.History(lam * (P - P[0]), np.zeros(P.size), [0, P.size - 1], None, P)
    result = fr.simulate(contact, history, fr.models.Varying(256))
    assert result.regime.values.tolist() == [0] * P.size
    superposed = [lam * quad(contact.compliance_under, P[0], p, epsrel=1e-12)[0] for p in P[1:]]
    assert np.allclose(result.delta.values[1:], superposed, rtol=1e-3, atol=0)


@pytest.mark.parametrize("phase", [None, 0.0, np.pi / 2], ids=["no-sigma", "sigma-in-phase", "sigma-out-of-phase"])
def test_force_and_displacement_control_agree_under_a_varying_load(contact, phase):
    """Run ``P = P0 (1 + 0.3 sin)``, ``Q = 0.5 f P0 sin`` (with ``sigma = 0.2 f p0 sin(. + phase)``) under force
    control, prescribe its recorded delta with the same P: the Q found at every step is the history's to 1e-14
    of ``f P0`` (Brent's bracket closes to ``5 eps f P``), the slip and each step's energy the same to 1e-12."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    t = np.linspace(0.0, 2 * np.pi, 25)
    sigma = np.zeros(t.size) if phase is None else 0.2 * fp0 * np.sin(t + phase)
    history = fr.History(0.5 * fP * np.sin(t), sigma, [0, t.size - 1], None, contact.P * (1 + 0.3 * np.sin(t)))
    forced = fr.simulate(contact, history, SPEC)
    assert 1 in forced.regime.values  # partial slip somewhere
    moved = fr.simulate(contact, prescribed(history, forced.delta.values), SPEC)
    assert np.max(np.abs(moved.Q.values - forced.Q.values)) < 1e-14 * fP
    assert np.max(np.abs(moved.slip.values - forced.slip.values)) < 1e-12 * np.abs(forced.slip.values).max()
    energy = forced.dissipation.values
    assert np.max(np.abs(moved.dissipation.values - energy)) < 1e-12 * energy.max()
    assert np.array_equal(moved.regime.values, forced.regime.values)


def test_a_datum_the_contact_reaches_is_a_one_line_error(contact):
    near = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=3e-4)  # a = 2.35e-4 m at P0
    history = fr.History([np.nan] * 3, [0.0] * 3, [0, 2], None, [1e5, 2e5, 3e5], [0.0, 1e-7, 2e-7])
    with pytest.raises(fr.HistoryError, match=r"^step 1: the normal load P = 200000.0 N/m forms a contact"):
        fr.simulate(near, history, SPEC)


@pytest.fixture(scope="module")
def slid(contact):
    return fr.simulate(contact, sliding_cycle(contact), SPEC)


def whole_cells(contact):
    """`SPEC` over the largest contact of the whole `sliding_cycle`, which its parts are run on."""
    return SPEC.resolved_for(contact, sliding_cycle(contact))


def test_gross_slip_under_a_varying_load_slides_at_f_P(contact, slid):
    assert_slides_at_f_P(contact, slid)


def assert_slides_at_f_P(contact, slid):
    """In and out of gross slip both ways: ``Q = +-f P`` of the step's load at every sliding step, and each
    step that slides from a sliding state dissipates ``f (P_begin + P_end) |du| / 2`` (``du`` the uniform slip
    increment, taken at the middle node; the trapezoidal rule in P of ``int f p |ds| dx``) to 1e-12."""
    P, Q, regime = slid.P.values, slid.Q.values, slid.regime.values
    sliding = regime == 2
    assert {0, 1, 2} <= set(regime.tolist()) and (Q[sliding] > 0).any() and (Q[sliding] < 0).any()
    assert np.diff(P[sliding]).min() < 0 < np.diff(P[sliding]).max()  # under a falling and a rising P
    assert np.array_equal(np.abs(Q[sliding]), contact.f * P[sliding])
    slip = slid.slip.values
    du = np.diff(slip[:, slip.shape[1] // 2])
    both = sliding[1:] & sliding[:-1]
    assert both.sum() >= 10
    trapezoidal = contact.f * (P[1:] + P[:-1]) / 2 * np.abs(du)
    assert np.allclose(slid.dissipation.values[1:][both], trapezoidal[both], rtol=1e-12, atol=0)


def test_a_slide_under_a_varying_load_moves_delta_by_eq_D16(contact):
    """While the Hertz contact slides, ``s = sign(Q) f x^2 / (2R) + u`` (eq D10) over the current contact, whose
    flat punch weighs ``x^2`` by ``a^2 / 2``, so by eq D13 a sliding step moves delta by
    ``d(C_L(a(P)) Q) + du + sign(Q) f d(a(P)^2) / (4R)`` (eq D16): to 1e-2 of the largest such step's change on
    256 cells (2.5e-2, 6.2e-3, 1.4e-3 on 64, 256, 1024: first order in the cell width, the cells in contact
    moving by pairs about ``a(P)``), where the last term alone is 2.6e-2 of it."""
    result = fr.simulate(contact, sliding_cycle(contact), fr.models.Varying(256))
    P, Q, delta, slip = result.P.values, result.Q.values, result.delta.values, result.slip.values
    both = (result.regime.values[1:] == 2) & (result.regime.values[:-1] == 2)
    elastic = np.array([contact.compliance_under(p) for p in P]) * Q
    a_squared = contact.profile.half_width(P, contact.E_star)[0] ** 2
    du = np.diff(slip[:, slip.shape[1] // 2])
    R = contact.profile.R
    moved = np.diff(elastic) + du + np.sign(Q[1:]) * contact.f * np.diff(a_squared) / (4 * R)
    scale = np.abs(np.diff(delta)[both]).max()
    assert np.abs(np.diff(delta) - moved)[both].max() < 1e-2 * scale
    assert np.abs(contact.f * np.diff(a_squared) / (4 * R))[both].max() > 2e-2 * scale


def test_gross_slip_under_a_varying_load_split_anywhere_resumes_bit_for_bit(contact, slid):
    history = sliding_cycle(contact)
    for k in (6, 14, 30):  # at the first slide, at the first step stuck again, in the middle of a slide
        first = fr.simulate(contact, history[: k + 1], whole_cells(contact))
        later = fr.simulate(contact, history[k:], state=final_state(first))
        for name in ("Q", "delta", "slip"):
            assert np.array_equal(later[name].values, slid[name].values[k:]), (k, name)
        for name in ("dissipation", "regime"):  # of the increments: the resumed run's step 0 is at rest
            assert np.array_equal(later[name].values[1:], slid[name].values[k + 1 :]), (k, name)


def test_force_control_still_refuses_f_P_under_a_varying_load(contact, slid):
    """The Q of the first sliding step, fed to force control with the same P: a `GrossSlipError` at that step."""
    first = int(np.argmax(slid.regime.values == 2))
    history = fr.History(slid.Q.values[: first + 1], np.zeros(first + 1), [0, first], None, slid.P.values[: first + 1])
    with pytest.raises(fr.GrossSlipError, match=f"gross slip at step {first}: "):
        fr.simulate(contact, history, whole_cells(contact))
