"""The varying-load model (method 4 on cells) against Jaeger's exact superposition: its energy on a history that
slips nowhere, whatever ``f`` (issue 38), and its stick zones at the limit ratio; and the scenes with a bulk
tension that the varying-load page scores it on."""

import numpy as np
import pytest
from harness import hertz_contact, rounded_flat_contact
from varying_accuracy import SCENES, TENSION, ExactRun, PackageRun, boundary

import fretting as fr
from fretting.models.normal import Varying

CONTACT = fr.Contact(fr.Hertz(0.05), 115e9, 0.5, 1e5)


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
    own, exact = PackageRun(result), ExactRun(contact, history)
    for k in range(1, len(history)):
        assert own.zones(k).shape == exact.zones(k).shape == (1, 2)
        np.testing.assert_allclose(own.zones(k), exact.zones(k), rtol=0, atol=1e-3 * result.a.values[k])


@pytest.mark.parametrize("scene", ["inphase", "boundary", "recede"])
@pytest.mark.parametrize("contact", [hertz_contact(), rounded_flat_contact()], ids=["hertz", "flat"])
def test_a_tensioned_scene_loads_one_edge_as_the_scene_without_tension(scene, contact):
    """The ``_sigma`` scenes of benchmarks/varying_accuracy.py: ``sigma / (f p0) = TENSION Q / (f P0)``, under the
    scene's ``P``, and at each step the fully stuck traction's increment at the edge the tension loads most,
    ``dQ + (pi a / 4) dsigma`` (``a`` the contact's), is the scene's ``dQ``: loops near the shakedown boundary
    stay near it there."""
    plain, tensioned = SCENES[scene](contact), SCENES[f"{scene}_sigma"](contact)
    np.testing.assert_array_equal(tensioned.P, plain.P)
    np.testing.assert_allclose(
        tensioned.sigma / (contact.f * contact.p0), TENSION * tensioned.Q / (contact.f * contact.P), rtol=1e-12
    )
    edge = np.diff(tensioned.Q) + np.pi * contact.a / 4 * np.diff(tensioned.sigma)
    np.testing.assert_allclose(edge, np.diff(plain.Q), rtol=1e-9, atol=1e-9 * contact.f * contact.P)
    assert np.abs(tensioned.sigma).max() > 0.1 * contact.f * contact.p0
