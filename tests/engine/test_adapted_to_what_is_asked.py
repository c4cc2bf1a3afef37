"""The mesh adapted to what a run asks of it: the stick ends of the recorded steps only (issue 18),
and a long history's turning points through a sample of them (issue 21), recorded and said."""

import warnings

import numpy as np
import pytest

import fretting as fr
from fretting.engine.choice import MeshSampleWarning
from fretting.engine.follow import follow
from fretting.models.galerkin import Mesh, adaptation
from fretting.models.galerkin import model as galerkin_model

SAMPLE = 8


@pytest.fixture
def small_sample(monkeypatch):
    monkeypatch.setattr(adaptation, "SAMPLE_TURNS", SAMPLE)


@pytest.fixture
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)


def in_phase_cycles(contact, cycles, amplitudes=None, sigma_mean=0.0):
    """Q and sigma in phase between +-amplitude (fractions of f P and f p0), one vertex a reversal; sigma
    about `sigma_mean` (of f p0; not zero: the load path misses the origin, and the default meshes it)."""
    amplitudes = np.full(cycles, 0.5) if amplitudes is None else amplitudes
    levels = np.r_[0.0, np.ravel(np.c_[amplitudes, -amplitudes])]
    sigma = levels * 0.5 + np.where(levels != 0, sigma_mean, 0.0)
    return fr.History.piecewise_linear(levels * contact.f * contact.P, sigma * contact.f * contact.p0, 4)


def turning(contact, history):
    return history.turning_points(adaptation.MAX_TURN, (np.pi * contact.a, 4.0))


def whole(contact, history, theta):
    """The model the energy passes (`adapted_model`'s first stage) over all of `history`'s turning
    points reach from the mesh `theta`."""
    points = turning(contact, history)
    run = adaptation._Adaptation(Mesh(), contact, history, follow, None, False)
    return run(points, theta)


def test_repeating_cycles_adapt_to_a_sample_that_needs_nothing_more(contact, small_sample):
    history = in_phase_cycles(contact, 12)
    assert len(turning(contact, history)) > 2 * SAMPLE
    model = adaptation.adapted_model(Mesh(), contact, history, follow, recorded=[])  # the energy's mesh alone
    assert model.spec.sample is not None and f"first {2 * SAMPLE} of" in model.spec.sample
    # the passes over every turning point of the history refine nothing of the sampled mesh
    assert np.array_equal(whole(contact, history, model.theta).theta, model.theta)


def test_growing_zones_adapt_to_the_whole_history(contact, small_sample):
    amplitudes = np.linspace(0.1, 0.7, 6)  # each cycle's slip zones reach beyond the last's
    history = in_phase_cycles(contact, amplitudes.size, amplitudes)
    model = adaptation.adapted_model(Mesh(), contact, history, follow, recorded=[])
    assert model.spec.sample is None  # every doubling grew the mesh, up to the whole history


def test_short_histories_adapt_as_before(contact, monkeypatch):
    history = in_phase_cycles(contact, 3)
    default = adaptation.adapted_model(Mesh(), contact, history, follow)
    monkeypatch.setattr(adaptation, "SAMPLE_TURNS", 10**6)
    assert np.array_equal(adaptation.adapted_model(Mesh(), contact, history, follow).theta, default.theta)
    assert default.spec.sample is None


@pytest.mark.slow
def test_the_sample_is_recorded_and_said(contact, small_sample):
    history = in_phase_cycles(contact, 12, sigma_mean=0.05)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = fr.simulate(contact, history)
    said = [w for w in caught if issubclass(w.category, MeshSampleWarning)]
    assert len(said) == 1 and "turning points" in str(said[0].message)
    assert result.attrs["model_sample"] in str(said[0].message)
    assert "model_fallback" not in result.attrs
    again = fr.models.galerkin.Mesh.from_record(result.attrs, result.theta.values[::-1].copy())
    assert again.sample == result.attrs["model_sample"]


def walk(contact):
    """Straight segments of Q and sigma, none proportional to the one before."""
    vertices = np.array([(0, 0), (0.5, 0.6), (-0.3, 0.9), (0.4, -0.8), (-0.6, -0.2)])
    return fr.History.piecewise_linear(
        vertices[:, 0] * contact.f * contact.P, vertices[:, 1] * contact.f * contact.p0, 8
    )


def ends(result):
    return np.stack([result.stick_start.values, result.stick_end.values])


@pytest.mark.slow
def test_steps_not_recorded_are_resolved_for_their_energy_alone(contact):
    """Recording the vertices only, the steps between need no located ends: a coarser mesh, the
    same energy to rtol, the vertices' stick ends as located as with every step recorded."""
    history = walk(contact)
    every = fr.simulate(contact, history)
    vertices = fr.simulate(contact, history, record=history.vertex_step)
    assert vertices.sizes["x"] < 0.7 * every.sizes["x"]
    np.testing.assert_allclose(vertices.total_dissipation, every.total_dissipation, rtol=1e-4)
    located = ends(every)[:, history.vertex_step]
    np.testing.assert_allclose(ends(vertices), located, rtol=0, atol=1e-3 * contact.a, equal_nan=True)


def test_a_step_recorded_inside_a_stretch_refines_that_stretch(contact):
    history = walk(contact)
    middle = (history.vertex_step[2] + history.vertex_step[3]) // 2
    vertices = adaptation.adapted_model(Mesh(), contact, history, follow, recorded=history.vertex_step)
    with_middle = adaptation.adapted_model(
        Mesh(), contact, history, follow, recorded=np.sort(np.r_[history.vertex_step, middle])
    )
    every = adaptation.adapted_model(Mesh(), contact, history, follow)
    assert vertices.theta.size < with_middle.theta.size < every.theta.size


def test_ends_past_the_bound_run_the_energy_mesh_and_say_so(contact, monkeypatch):
    """Where the mesh that locates the recorded steps' stick ends would pass the default's bound,
    the mesh adapted to the energy runs: recorded and said, with the accuracy its ends reach."""
    history = walk(contact)
    energy_only = adaptation.adapted_model(Mesh(), contact, history, follow, recorded=[])
    located = adaptation.adapted_model(Mesh(), contact, history, follow)
    increments = history.Q.size - 1
    monkeypatch.setattr(galerkin_model, "MAX_DEFAULT_WORK", (located.theta.size - 1) ** 2 * increments)
    with pytest.warns(fr.ModelFallbackWarning, match="locates the stick ends") as said:
        result = fr.simulate(contact, history)
    assert result.sizes["x"] == energy_only.theta.size < located.theta.size
    assert result.attrs["model_fallback"] in str(said[0].message)
    assert f"times the run's {increments} increments" in result.attrs["model_fallback"]
    assert "err by up to about 0.005 a" in result.attrs["model_fallback"]


def test_a_sampled_mesh_that_falls_back_says_both(contact, small_sample, monkeypatch):
    """Past the bound, the energy's mesh of a sample runs: the fallback and the sample are both said."""
    history = in_phase_cycles(contact, 12, sigma_mean=0.05)
    energy_only = adaptation.adapted_model(Mesh(), contact, history, follow, recorded=[])
    monkeypatch.setattr(galerkin_model, "MAX_DEFAULT_WORK", energy_only.theta.size**2 * (history.Q.size - 1))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = fr.simulate(contact, history)
    said = " | ".join(str(w.message) for w in caught if issubclass(w.category, fr.ModelFallbackWarning))
    assert result.attrs["model_fallback"] in said and result.attrs["model_sample"] in said


@pytest.mark.slow
def test_an_energy_check_past_the_bound_runs_the_mesh_before_and_says_so(contact, monkeypatch):
    """Small cycles on a locked-in slip (tests/test_trajectories.py) refine the mesh that locates
    the ends until their energy per cycle settles; where that would pass the default's bound, the
    mesh that locates the ends runs, with the change of the energy it still showed."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.sinusoidal(1e-4 * fP, 1e-4 * fp0, 90, 2, 16, Q_mean=0.3 * fP, sigma_mean=0.2 * fp0)
    checked = adaptation.adapted_model(Mesh(), contact, history, follow)
    monkeypatch.setattr(adaptation, "RESLIP", 0.0)
    located = adaptation.adapted_model(Mesh(), contact, history, follow)
    assert located.theta.size < checked.theta.size
    monkeypatch.undo()
    monkeypatch.setattr(galerkin_model, "MAX_DEFAULT_WORK", located.theta.size**2 * (history.Q.size - 1))
    with pytest.warns(fr.ModelFallbackWarning, match="settles the energy per cycle") as said:
        result = fr.simulate(contact, history)
    assert result.sizes["x"] == located.theta.size
    assert result.attrs["model_fallback"] in str(said[0].message)
    assert "energy per cycle changed by up to" in result.attrs["model_fallback"]


@pytest.mark.parametrize("cycle", [np.array([0, 1, 1, 1, 2, 2, 2]), None])
def test_energy_check_refines_the_increments_of_the_cycle_that_changed(cycle):
    """Each cycle (each stretch between vertices without cycles) is held to rtol of its own energy,
    not of the whole history's: 1e-3 of one increment fails the second cycle (3.3e-4 of it), not
    the history (1.7e-4 of its energy to the last vertex), and only that increment is refined."""
    turning = fr.History(np.zeros(7), np.zeros(7), np.array([0, 3, 6]), cycle)
    energy = np.array([0.0, 1, 1, 1, 1, 1, 1])
    change = np.array([0.0, 0, 0, 0, 0, 1e-3, 0])
    rows, worst = adaptation._unsettled(turning, energy, change, 2e-4)
    np.testing.assert_array_equal(rows, [5])
    assert worst == pytest.approx(1e-3 / 3)
    rows, worst = adaptation._unsettled(turning, energy, change, 4e-4)
    assert rows.size == 0 and worst == 0.0


def test_an_energy_check_that_cannot_refine_further_says_so(contact, monkeypatch):
    """Where the elements holding the boundaries of the increments whose energy still changes can be
    bisected no further, the mesh runs as it is: recorded and said, with the change it still showed."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.sinusoidal(1e-4 * fP, 1e-4 * fp0, 90, 2, 16, Q_mean=0.3 * fP, sigma_mean=0.2 * fp0)
    monkeypatch.setattr(adaptation, "tightened", lambda theta, positions: np.full(theta.size - 1, np.inf))
    with pytest.warns(fr.ModelFallbackWarning, match="can be bisected no further") as said:
        result = fr.simulate(contact, history)
    assert result.attrs["model_fallback"] in str(said[0].message)
    assert "energy per cycle still changed by up to" in result.attrs["model_fallback"]


def test_the_load_change_of_a_first_increment_is_from_the_contact_just_formed(contact):
    """A history that starts at non-zero loads reaches them in one increment from the contact just
    formed (`follow`), so the load change of its step 0, which `_unseen_edges` and
    `held_by_allowance` read, is the whole fully stuck traction of its loads, not the change from
    its last step (here back at the first loads: none)."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.piecewise_linear(np.array([0.3, 0.1, 0.3]) * fP, np.array([0.2, 0.0, 0.2]) * fp0, 1)
    model = fr.models.Mesh(theta=fr.models.galerkin.initial_theta()).build(contact)
    np.testing.assert_array_equal(adaptation._push(model, history, 0), model.g_stuck(history.Q[0], history.sigma[0]))
    np.testing.assert_array_equal(
        adaptation._push(model, history, 1),
        model.g_stuck(history.Q[1], history.sigma[1]) - model.g_stuck(history.Q[0], history.sigma[0]),
    )


def test_a_mesh_past_the_default_bound_still_says_the_solvers_floor(contact, monkeypatch):
    """Cycles of 1e-10 f P on a locked-in slip are held stuck by the solver's rounding allowance,
    which the adapted mesh's spec says (tests/test_trajectories.py). Where the mesh that locates
    the ends passes the default's bound of work, the mesh the default runs instead says that
    bound and the floor both."""
    import small_loops  # benchmarks/, on the path by conftest

    history = small_loops.cycles(contact, 1e-10, "Q")
    located = adaptation.adapted_model(Mesh(), contact, history, follow)
    assert "slip nowhere" in located.spec.fallback
    monkeypatch.setattr(galerkin_model, "MAX_DEFAULT_WORK", (located.theta.size // 2) ** 2 * (history.Q.size - 1))
    with pytest.warns(fr.ModelFallbackWarning, match="runs the mesh adapted to the energy"):
        result = fr.simulate(contact, history)
    assert result.sizes["x"] < located.theta.size
    assert fr.models.galerkin.CAPPED in result.attrs["model_fallback"]
    assert "slip nowhere: what they would dissipate is lost" in result.attrs["model_fallback"]
