"""Invariants of the method-4 state machine: memory, energy, splits, friction conditions."""

import contextlib
import itertools
import sys
from dataclasses import replace

import numpy as np
import pytest
import xarray as xr
from threadpoolctl import threadpool_info, threadpool_limits

import fretting as fr
from fretting.engine import follow
from fretting.engine.threads import BLAS_THREADS
from fretting.models.collocation import CollocationModel
from fretting.results.notes import UNRESOLVED

RANDOM_VERTICES = 12

#: Accuracy of the adapted meshes of the tests of the engine's properties (which hold on any mesh):
#: coarser than the default's, so that they run in a fraction of its time.
COARSE = 1e-3


def random_history(contact, seed, steps=5):
    """A non-proportional (Q, sigma) path with |Q| < 0.8 f P and |sigma| < 1.5 f p0."""
    rng = np.random.default_rng(seed)
    Q = rng.uniform(-0.8, 0.8, RANDOM_VERTICES) * contact.f * contact.P
    sigma = rng.uniform(-1.5, 1.5, RANDOM_VERTICES) * contact.f * contact.p0
    Q[0] = sigma[0] = 0.0
    return fr.History.piecewise_linear(Q, sigma, steps)


def test_return_point_memory(hertz):
    """0 -> 0.6 -> 0.2 -> 0.5 -> 0.2 -> 0.6 fP: closing a minor loop restores the state."""
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear(np.array([0, 0.6, 0.2, 0.5, 0.2, 0.6]) * fP, None, 12)
    result = fr.simulate(hertz, history)
    slip = result.slip.values[history.vertex_step]
    for before, after in ((1, 5), (2, 4)):
        np.testing.assert_allclose(slip[after], slip[before], rtol=0, atol=1e-9 * np.abs(slip[before]).max())
    assert np.abs(slip[3] - slip[2]).max() > 1e-3 * np.abs(slip[2]).max()  # the loop did slip


def loop_work(result, first, last):
    """Trapezoidal ``loop Q d(delta_Q) + loop sigma d(delta_sigma)`` over steps first..last."""
    part = result.isel(step=slice(first, last + 1))
    return sum(
        np.trapezoid(part[load].values, part[displacement].values)
        for load, displacement in (("Q", "delta_Q"), ("sigma", "delta_sigma"))
    )


@pytest.mark.parametrize("tau", [0.0, 0.8])
def test_loop_area_equals_dissipation(hertz, tau):
    """Over a closed cycle the work of the loads is the dissipation; the trapezoidal area of
    the polygonal loop converges to it as the square of the step."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    Q = np.array([0, 0.7, -0.7, 0.7]) * fP
    errors = []
    for steps in (32, 64):
        history = fr.History.piecewise_linear(Q, tau * fp0 * Q / fP, steps)
        result = fr.simulate(hertz, history, rtol=COARSE)
        first, last = history.vertex_step[1], history.vertex_step[3]
        dissipated = result.dissipation.values[first + 1 : last + 1].sum()
        errors.append(abs(loop_work(result, first, last) / dissipated - 1))
    assert errors[1] < 1e-3
    assert errors[1] < errors[0] / 3


def test_dissipation_does_not_depend_on_the_step(hertz):
    """Along a proportional cycle each point slips one way per half cycle, so the dissipation
    of the discrete solution does not depend on the number of increments."""
    fP = hertz.f * hertz.P
    totals = [
        fr.simulate(hertz, fr.History.piecewise_linear(np.array([0, 0.5, -0.5, 0.5]) * fP, None, n)).dissipation.sum()
        for n in (1, 7, 40)
    ]
    np.testing.assert_allclose(totals, totals[0], rtol=1e-10)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_friction_conditions_hold_at_every_node(hertz, seed):
    result = fr.simulate(hertz, random_history(hertz, seed), rtol=COARSE)
    fp = hertz.f * result.p.values
    q, slip, stick = result.q.values, result.slip.values, result.stick.values
    ds = np.diff(slip, axis=0, prepend=0.0)
    rounding = 1e-10 * hertz.f * hertz.p0
    assert np.all(np.abs(q) <= fp + rounding)
    slipping = ~stick
    assert np.all(np.abs(q - fp * np.sign(ds))[slipping] <= rounding)
    assert np.all(ds[stick] == 0)
    assert np.all(result.dissipation.values >= 0)
    # Non-proportional paths do give opposite slip directions side by side in one increment.
    opposite = [np.any(d[s] > 0) and np.any(d[s] < 0) for d, s in zip(ds, slipping, strict=True)]
    assert any(opposite)


def split_history(history, k):
    return fr.History(history.Q[k:], history.sigma[k:], [0])


@pytest.mark.parametrize("k", [1, 7, 20, 33, 54])
def test_chunked_run_equals_whole_run(hertz, k):
    """run(h) == run(h[:k]) followed by run(h[k:], state=final_state(...)), bit for bit."""
    history = random_history(hertz, seed=4)
    mesh = fr.adapted_mesh(hertz, history, rtol=COARSE)  # one adapted mesh for the whole and its parts
    whole = fr.simulate(hertz, history, mesh=mesh)
    head = fr.simulate(hertz, fr.History(history.Q[: k + 1], history.sigma[: k + 1], [0]), mesh=mesh)
    tail = fr.simulate(hertz, split_history(history, k), state=fr.final_state(head))
    for name in ("q", "slip", "stick", "dissipation", "stick_end", "delta_Q"):
        joined = np.concatenate([head[name].values, tail[name].values[1:]])
        width = min(joined.shape[-1], whole[name].shape[-1]) if joined.ndim == 2 else None
        np.testing.assert_array_equal(joined[..., :width], whole[name].values[..., :width])


def test_state_must_match_the_history_start(hertz):
    state = fr.final_state(fr.simulate(hertz, fr.History.piecewise_linear([0, 0.3 * hertz.f * hertz.P], None, 4)))
    with pytest.raises(fr.HistoryError, match="history starts at Q = 0.0"):
        fr.simulate(hertz, fr.History.piecewise_linear([0.0, 1.0]), state=state)


def test_gross_slip_names_the_step(hertz):
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear([0, 0.5 * fP, -1.2 * fP], None, 10)
    with pytest.raises(fr.GrossSlipError, match="gross slip at step 19") as error:
        fr.simulate(hertz, history)
    assert error.value.step == 19 and error.value.Q < -fP


@pytest.mark.parametrize("model", [{"rtol": fr.DEFAULT_RTOL}, {"nodes": fr.DEFAULT_NODES}])
def test_an_unloading_step_below_the_solvers_floor_dissipates_exactly_zero(hertz, model):
    """Method 4: after a reversal, an unloading step of 1e-9 f P reverses zones about 2.5e-10 a wide
    at the edges. The grid's edge nodes lie beyond them, and nothing slips. The adapted mesh bisects
    its edge elements until its edge nodes reach their limit (`adaptation._unseen_edges`), by less
    than the solver's rounding allowance, which holds them: nothing slips either, and the dataset
    and a warning say that the step's energy is lost. The exact model slips there, by the cubic law
    (tests/models/test_masing.py)."""
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear(np.array([0, 0.5, 0.5 - 1e-9]) * fP, None, [4, 1])
    adapted = "rtol" in model
    with pytest.warns(fr.ModelFallbackWarning, match="slip nowhere") if adapted else contextlib.nullcontext():
        result = fr.simulate(hertz, history, **model)
    assert ("slip nowhere: what they would dissipate is lost" in result.attrs.get("model_fallback", "")) == adapted
    assert result.dissipation.values[-1] == 0.0
    assert np.all(result.stick.values[-1])
    np.testing.assert_array_equal(result.slip.values[-1], result.slip.values[-2])


def test_the_sharp_flat_punch_keeps_its_edges_unrefined():
    """Under the sharp flat punch ``q / p = Q / P`` at the edges when all sticks, so under ``Q`` alone
    below ``f P`` nothing slips, however small the edge elements: the mesh is not bisected toward
    the edges for the load changes that stick there (`Profile.VANISHING_EDGES`), and stays the
    initial one."""
    punch = fr.Contact(fr.FlatPunch(1e-3), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)
    fP = punch.f * punch.P
    result = fr.simulate(punch, fr.History.piecewise_linear(np.array([0, 0.5, 0.5 - 1e-9]) * fP, None, 4), rtol=1e-4)
    assert result.attrs["nodes"] == fr.models.galerkin.initial_theta().size
    assert np.all(result.stick.values) and np.all(result.dissipation.values == 0)


def test_zero_length_segment_and_repeated_vertices(hertz):
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear(np.array([0, 0.4, 0.4, 0.4]) * fP, None, [3, 2, 1])
    result = fr.simulate(hertz, history)
    np.testing.assert_array_equal(result.slip.values[-1], result.slip.values[3])
    assert np.all(result.dissipation.values[4:] == 0)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: fr.History.piecewise_linear([0, np.nan]), "finite"),
        (lambda: fr.History.piecewise_linear([0, 1], [0]), "one value per vertex"),
        (lambda: fr.History.piecewise_linear([0, 1], None, 0), "steps_per_segment"),
        (lambda: fr.History.piecewise_linear([]), "empty"),
    ],
)
def test_bad_history(call, message):
    with pytest.raises(fr.HistoryError, match=message):
        call()


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        ((fr.Hertz(1.0), -1.0, 0.5, 1.0), "E_star must be > 0"),
        ((fr.Hertz(1.0), 1.0, "0.5", 1.0), "f must be a number"),
        ((fr.Hertz(1.0), 1.0, 0.5, np.inf), "P must be finite"),
        (("hertz", 1.0, 0.5, 1.0), "profile must be"),
    ],
)
def test_bad_contact(arguments, message):
    with pytest.raises(ValueError, match=message):
        fr.Contact(*arguments)


def test_dataset_contract(hertz):
    result = fr.simulate(hertz, fr.History.piecewise_linear([0, 0.5 * hertz.f * hertz.P], None, 4))
    for name in ("Q", "sigma", "p", "q", "slip", "stick", "dissipation", "delta_Q", "delta_sigma", "vertex_step"):
        assert name in result.variables
        assert result[name].attrs["units"] and result[name].attrs["long_name"]
    assert result.q.dims == ("step", "x") and result.p.dims == ("x",) and result.vertex_step.dims == ("vertex",)
    assert result.stick.dtype == bool
    for name in ("a", "p0", "E_star", "f", "P"):
        assert result.attrs[name] == getattr(hertz, name)
    assert np.all(result.stick.values[0]) and np.all(result.slip.values[0] == 0)


@pytest.mark.slow
def test_off_centre_profile_follows_its_contact(hertz):
    """A cylinder displaced by x0, solved as a general gap, slips like the centred one."""
    x0 = 0.3 * hertz.a
    gap = fr.Gap(lambda x: (x - x0) ** 2 / (2 * hertz.profile.R))
    shifted = fr.Contact(gap, hertz.E_star, hertz.f, hertz.P)
    history = random_history(hertz, seed=5, steps=3)
    centred, moved = fr.simulate(hertz, history, rtol=COARSE), fr.simulate(shifted, history, rtol=COARSE)
    np.testing.assert_allclose(moved.x.values - x0, centred.x.values, rtol=0, atol=1e-9 * hertz.a)
    fp0 = hertz.f * hertz.p0
    np.testing.assert_allclose(moved.q.values / fp0, centred.q.values / fp0, rtol=0, atol=1e-6)
    np.testing.assert_array_equal(moved.stick.values, centred.stick.values)


def test_recording_a_subset_of_steps(hertz):
    """Recorded steps equal those of a full run; the energy per cycle still covers every step."""
    fP = hertz.f * hertz.P
    Q = np.array([0, 0.5, -0.5, 0.5, -0.5]) * fP
    base = fr.History.piecewise_linear(Q, None, 8)
    cycle = np.concatenate([[0] * 9, [1] * 16, [2] * 8])
    history = fr.History(base.Q, base.sigma, base.vertex_step, cycle)
    full = fr.simulate(hertz, history)
    record = [0, 8, 24, 32]
    part = fr.simulate(hertz, history, record=record)
    np.testing.assert_array_equal(part.step.values, record)
    for name in ("q", "slip", "stick", "dissipation", "delta_Q", "Q", "cycle"):
        np.testing.assert_array_equal(part[name].values, full[name].values[record])
    np.testing.assert_array_equal(part.cycle_dissipation.values, full.cycle_dissipation.values)
    per_cycle = [full.dissipation.values[cycle == k].sum() for k in (1, 2)]
    np.testing.assert_allclose(full.cycle_dissipation.values, per_cycle, rtol=1e-14)
    with pytest.raises(ValueError, match="increasing steps"):
        fr.simulate(hertz, history, record=[3, 2])


@pytest.mark.slow
@pytest.mark.parametrize("tau", [0.0, 0.5])
def test_vertex_states_do_not_depend_on_steps_per_segment(hertz, tau):
    """Along proportional segments (in-phase Q and sigma, same-direction slip) the state at a
    vertex is the same whether a segment takes 1, 8 or 1000 increments."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    Q = np.array([0, 0.6, -0.3, 0.4]) * fP
    slips = []
    for steps in (1, 8, 1000):
        history = fr.History.piecewise_linear(Q, tau * fp0 * Q / fP, steps)
        slips.append(fr.simulate(hertz, history, record=history.vertex_step, rtol=COARSE).slip.values)
    scale = np.abs(slips[0]).max()
    for other in slips[1:]:
        np.testing.assert_allclose(other, slips[0], rtol=0, atol=1e-9 * scale)


@pytest.mark.parametrize("phase_deg", [0.0, 90.0])
def test_copied_cycles_equal_solved_ones(hertz, phase_deg):
    """Cycles whose loads and starting state repeat are copied; solving each one instead (a run
    cut into one part per cycle cannot copy) gives the same result bit for bit."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    history = fr.History.sinusoidal(0.6 * fP, 0.4 * fp0, phase_deg=phase_deg, cycles=8, steps_per_cycle=16)
    whole = fr.simulate(hertz, history, nodes=64)
    assert whole.cycle_copied.values.sum() >= 3
    bounds = [0, *np.flatnonzero(np.diff(history.cycle)), len(history) - 1]
    parts = [fr.simulate(hertz, history[: bounds[1] + 1], nodes=64)]
    for start, stop in itertools.pairwise(bounds[1:]):
        parts.append(fr.simulate(hertz, history[start : stop + 1], nodes=64, state=fr.final_state(parts[-1])))
    solved = fr.join_results(parts)
    assert not solved.cycle_copied.values.any()
    # the note of the cycles the 64 nodes do not resolve is the whole run's, each part's cycles in it
    assert whole.attrs[UNRESOLVED].startswith("8 load cycles (cycle 1 to 8) slipped over fewer than 100")
    xr.testing.assert_identical(solved.drop_vars("cycle_copied"), whole.drop_vars("cycle_copied"))


def test_a_state_periodic_over_three_cycles_has_blocks_of_them_copied(hertz, monkeypatch):
    """Rounding can leave a state that comes back bit for bit only every few cycles (every third
    cycle with some BLAS kernels). Here the model remembers a phase that each increment advances
    (16 increments a cycle: the phase before a cycle repeats every third cycle): blocks of three
    cycles are copied, and the result is the one of solving each cycle, bit for bit."""
    solve = CollocationModel.increment

    def increment(self, state, loads, guess=None):
        phase = state.memory[0] if state.memory else 0
        return replace(solve(self, state, loads, guess), memory=((phase + 1) % 3,))

    monkeypatch.setattr(CollocationModel, "increment", increment)
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    history = fr.History.sinusoidal(0.6 * fP, 0.4 * fp0, phase_deg=90, cycles=20, steps_per_cycle=16)
    whole = fr.simulate(hertz, history, nodes=64)
    assert whole.cycle_copied.values.sum() >= 9
    monkeypatch.setattr(follow, "PERIOD_CYCLES", 1)  # a state that repeats after one cycle only
    solved = fr.simulate(hertz, history, nodes=64)
    assert not solved.cycle_copied.values.any()
    xr.testing.assert_identical(solved.drop_vars("cycle_copied"), whole.drop_vars("cycle_copied"))


def test_energy_density_and_slip_amplitude_per_cycle(hertz):
    """`w` sums f p |ds| over each cycle's increments, `slip_amplitude` is half the slip range
    over the cycle and its starting state; both are kept for every cycle."""
    fP, fp0 = hertz.f * hertz.P, hertz.f * hertz.p0
    history = fr.History.sinusoidal(0.5 * fP, 0.3 * fp0, phase_deg=90, cycles=3, steps_per_cycle=24)
    result = fr.simulate(hertz, history, nodes=64)
    slip, cycle, p = result.slip.values, result.cycle.values, result.p.values
    density = hertz.f * p * np.abs(np.diff(slip, axis=0, prepend=slip[:1]))
    for k, number in enumerate(result.cycle_number.values):
        mine = np.flatnonzero(cycle == number)
        around = slip[mine[0] - 1 : mine[-1] + 1]
        np.testing.assert_allclose(result.w.values[k], density[mine].sum(axis=0), rtol=1e-6, atol=0)
        amplitude = (around.max(axis=0) - around.min(axis=0)) / 2
        np.testing.assert_allclose(result.slip_amplitude.values[k], amplitude, rtol=1e-6, atol=0)
    total = float(result.dissipation.sum())
    assert float(result.total_dissipation) == pytest.approx(total, rel=1e-14)


def blas_threads():
    """Threads of every BLAS library loaded (numpy's, scipy's)."""
    return {info["filepath"]: info["num_threads"] for info in threadpool_info() if info["user_api"] == "blas"}


@pytest.mark.parametrize("model", [{}, {"nodes": 64}])
def test_the_engine_runs_blas_on_one_thread_and_gives_the_threads_back(hertz, monkeypatch, model):
    """Its many small products and factorisations only slow down on more threads (68 against 3.5
    ms per step on the bench's random scene, benchmarks/blas_threads.py): every increment,
    adaptation passes included, runs with BLAS_THREADS per library; the caller's setting is back
    after the run."""
    engine = sys.modules["fretting.models.method4"]
    solve, seen = engine.solve_increment, []

    def spying(*args):
        seen.append(blas_threads())
        return solve(*args)

    monkeypatch.setattr(engine, "solve_increment", spying)
    with threadpool_limits(limits=2, user_api="blas"):  # the caller's, whatever the environment's
        before = blas_threads()
        loads = 0.5 * hertz.f * hertz.P, 0.2 * hertz.f * hertz.p0  # sigma out of phase: the default adapts a mesh
        fr.simulate(hertz, fr.History.sinusoidal(*loads, 90.0, cycles=2, steps_per_cycle=8), **model)
        after = blas_threads()
    assert set(before.values()) == {2} and after == before
    assert seen and all(set(threads.values()) == {BLAS_THREADS} for threads in seen)


@pytest.mark.parametrize("sigma", [0.0, 0.3])
@pytest.mark.parametrize("model", [{}, {"rtol": 1e-4}, {"nodes": 384}])
def test_a_load_one_ulp_below_sliding_gives_a_result_or_gross_slip(hertz, sigma, model):
    """Q = nextafter(f P, 0): a result, or GrossSlipError where the discrete friction force is
    smaller than f P by rounding; never a solver failure (issue 18)."""
    Q = np.nextafter(hertz.f * hertz.P, 0)
    history = fr.History.piecewise_linear([0, Q], [0, sigma * hertz.f * hertz.p0], 4)
    try:
        result = fr.simulate(hertz, history, **model)
    except fr.GrossSlipError as error:
        assert error.step == 4 and error.limit <= hertz.f * hertz.P
    else:
        assert result.stick.values[-1].any()


def test_a_state_is_checked_before_it_is_continued(hertz):
    """A hand-made state holding NaN, or one with another number of nodes, is refused (issue 18)."""
    history = fr.History.piecewise_linear([0, 0.3 * hertz.f * hertz.P], None, 4)
    state = fr.final_state(fr.simulate(hertz, history, nodes=64))
    more = fr.History.piecewise_linear([0.3 * hertz.f * hertz.P, 0.0], None, 4)
    with pytest.raises(fr.HistoryError, match="state.slip is not finite at node 3"):
        fr.simulate(hertz, more, state=replace(state, slip=np.where(np.arange(64) == 3, np.nan, state.slip)))
    with pytest.raises(fr.HistoryError, match=r"state.slip has shape \(32,\), expected \(64,\)"):
        fr.simulate(hertz, more, state=replace(state, slip=state.slip[:32]))


def test_a_mesh_with_nan_is_refused(hertz):
    history = fr.History.piecewise_linear([0, 0.3 * hertz.f * hertz.P], None, 4)
    with pytest.raises(ValueError, match="theta must increase strictly from 0 to pi"):
        fr.simulate(hertz, history, mesh=[0, np.nan, np.pi])


def test_a_mesh_finer_than_the_rounding_of_its_edge_is_refused_and_one_at_the_bound_runs(hertz):
    """An edge element below ``sqrt(2 eps)`` rad sees ``cos(theta) = 1`` at every quadrature point: its
    edge node's friction limit vanishes and its traction was NaN (issue 38). Such a mesh is refused
    in one line; a mesh whose edge elements are `SMALLEST_ELEMENT` runs with a finite traction."""
    fP = hertz.f * hertz.P
    history = fr.History.piecewise_linear([0, 0.5 * fP, -0.3 * fP], [0, 50e6, 0], 8)
    theta = fr.models.galerkin.initial_theta()
    with pytest.raises(ValueError, match=r"theta's elements must span at least 2.5e-08 rad .* theta\[0:2\]"):
        fr.simulate(hertz, history, mesh=np.sort(np.r_[theta, 1e-300]))
    edge = fr.models.galerkin.mesh.SMALLEST_ELEMENT * (1 + 1e-6)  # pi - edge rounds off the last digits
    result = fr.simulate(hertz, history, mesh=np.sort(np.r_[theta, edge, np.pi - edge]))
    assert np.isfinite(result.q).all() and result.total_dissipation > 0


def test_a_state_with_negative_energy_is_refused(hertz):
    """A hand-made state that has dissipated less than nothing is refused, not run on (issue 38)."""
    history = fr.History.piecewise_linear([0, 0.3 * hertz.f * hertz.P], None, 4)
    state = fr.final_state(fr.simulate(hertz, history, nodes=64))
    more = fr.History.piecewise_linear([0.3 * hertz.f * hertz.P, 0.0], None, 4)
    with pytest.raises(fr.HistoryError, match=r"state.dissipated = -1.0, expected a finite number >= 0"):
        fr.simulate(hertz, more, state=replace(state, dissipated=-1.0))
    negative = replace(state.tally, w=np.where(np.arange(64) == 5, -1.0, state.tally.w))
    with pytest.raises(fr.HistoryError, match=r"state.tally.w is negative at node 5"):
        fr.simulate(hertz, more, state=replace(state, tally=negative))


def test_a_friction_coefficient_that_overflows_the_energy_is_refused_and_a_large_one_scales():
    """``f = 1e300`` ended in an OverflowError traceback (issue 38): the contact refuses an ``f`` whose
    energy scale ``(f p0 a)^2 / E_star`` overflows, in one line. Below that bound the answer is
    right: under ``Q`` proportional to ``f P`` the slip is proportional to ``f`` and the energy to ``f^2``
    (Mindlin and Deresiewicz's, ``(f p0 a)^2 / E_star`` times a function of ``Q / f P``)."""
    with pytest.raises(ValueError, match=r"\(f p0 a\)\^2 / E_star overflows a float"):
        fr.Contact(fr.Hertz(0.05), 115e9, 1e150, 1e5)
    energies = []
    for f in (0.6, 0.6e140):
        contact = fr.Contact(fr.Hertz(0.05), 115e9, f, 1e5)
        fP = contact.f * contact.P
        history = fr.History.piecewise_linear([0, 0.5 * fP, -0.5 * fP, 0.5 * fP], None, 8)
        energies.append(float(fr.simulate(contact, history).total_dissipation))
    assert energies[1] == pytest.approx(1e280 * energies[0], rel=1e-12)
