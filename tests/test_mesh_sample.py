"""A long history's mesh adapted to a sample of its turning points (issue 21): the sample is
enough for the whole history where the zones repeat, recorded, and said."""

import warnings

import numpy as np
import pytest

import fretting as fr
from fretting.engine import adaptation
from fretting.engine.choice import MeshSampleWarning

SAMPLE = 8


@pytest.fixture
def small_sample(monkeypatch):
    monkeypatch.setattr(adaptation, "SAMPLE_TURNS", SAMPLE)


@pytest.fixture
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)


def in_phase_cycles(contact, cycles, amplitudes=None):
    """Q and sigma in phase between +-amplitude (fractions of f P and f p0), one vertex a reversal."""
    amplitudes = np.full(cycles, 0.5) if amplitudes is None else amplitudes
    levels = np.r_[0.0, np.ravel(np.c_[amplitudes, -amplitudes])]
    return fr.History.piecewise_linear(levels * contact.f * contact.P, levels * 0.5 * contact.f * contact.p0, 4)


def turning(contact, history):
    return history.turning_points(adaptation.MAX_TURN, (np.pi * contact.a, 4.0))


def whole(contact, history, theta):
    """The model the passes over all of `history`'s turning points reach from the mesh `theta`."""
    run = adaptation._Adaptation(contact, history, fr.models.galerkin.DEFAULT_RTOL, None, False)
    return run(turning(contact, history), theta)


def test_repeating_cycles_adapt_to_a_sample_that_needs_nothing_more(contact, small_sample):
    history = in_phase_cycles(contact, 12)
    assert len(turning(contact, history)) > 2 * SAMPLE
    model = adaptation.adapted_model(contact, history)
    assert model.spec.sample is not None and f"first {2 * SAMPLE} of" in model.spec.sample
    # the passes over every turning point of the history refine nothing of the sampled mesh
    assert np.array_equal(whole(contact, history, model.theta).theta, model.theta)


def test_growing_zones_adapt_to_the_whole_history(contact, small_sample):
    amplitudes = np.linspace(0.1, 0.7, 10)  # each cycle's slip zones reach beyond the last's
    history = in_phase_cycles(contact, amplitudes.size, amplitudes)
    model = adaptation.adapted_model(contact, history)
    assert model.spec.sample is None
    assert np.array_equal(whole(contact, history, model.theta).theta, model.theta)


def test_short_histories_adapt_as_before(contact, monkeypatch):
    history = in_phase_cycles(contact, 3)
    default = adaptation.adapted_model(contact, history)
    monkeypatch.setattr(adaptation, "SAMPLE_TURNS", 10**6)
    assert np.array_equal(adaptation.adapted_model(contact, history).theta, default.theta)
    assert default.spec.sample is None


def test_the_sample_is_recorded_and_said(contact, small_sample):
    history = in_phase_cycles(contact, 12)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = fr.simulate(contact, history)
    said = [w for w in caught if issubclass(w.category, MeshSampleWarning)]
    assert len(said) == 1 and "turning points" in str(said[0].message)
    assert result.attrs["model_sample"] in str(said[0].message)
    assert "model_fallback" not in result.attrs
    again = fr.models.galerkin.Mesh.from_record(result.attrs, result.theta.values[::-1].copy())
    assert again.sample == result.attrs["model_sample"]
