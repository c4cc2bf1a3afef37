"""A varying normal load P(t) (issue 22): closed forms of Jaeger's superposition and Melan's shakedown, on method 4
on cells (`fretting.models.Varying`) and, on Hertz without sigma, on the default there, the exact model
(`fretting.models.Jaeger`; `MODELS`).

Traction is compared within 1e-3 f p0 away (0.02 a) from the points where it has a square-root kink,
as in tests/physics/test_closed_forms.py: the edges of the contacts met and the stick/slip boundaries.
"""

import numpy as np
import pytest

import fretting as fr
from fretting.errors import HistoryError
from fretting.loading.history import History
from fretting.models.normal import Varying
from fretting.physics import closed_forms as cf

E_STAR, F = 115e9, 0.5
BAND = 0.02  # [a]


def contact(profile, P=1e5):
    return fr.Contact(profile, E_star=E_STAR, f=F, P=P)


def away_from(x, ends, a):
    return np.all(np.abs(np.subtract.outer(x, np.asarray(ends))) > BAND * a, axis=-1)


def energy_scale(c):
    """``pi (f p0 a)^2 / (4 E_star)`` [J/m], the scale of the energy of Cattaneo-Mindlin."""
    return np.pi * (c.f * c.p0 * c.a) ** 2 / (4 * c.E_star)


PROFILES = [fr.Hertz(0.05), fr.RoundedFlat(0.0002, 0.05)]

#: The models of a varying P: method 4 on cells, and the default (on Hertz without sigma: Jaeger's superposition).
MODELS = [pytest.param(Varying(), id="cells"), pytest.param(None, id="default")]


@pytest.mark.parametrize(
    ("profile", "model"),
    [(fr.Hertz(0.05), Varying()), (fr.Hertz(0.05), None), (fr.RoundedFlat(0.0002, 0.05), None)],
    ids=["hertz-cells", "hertz-default", "rounded-flat"],
)
def test_proportional_loading_slips_nowhere_and_follows_the_pressure(profile, model):
    """Q = lambda (P - P0), lambda = 0.3 < f: no dissipation, q = lambda (p(P) - p(P0)) (Jaeger)."""
    formed = contact(profile)
    P0, lam = formed.P, 0.3
    result = fr.simulate(formed, History.piecewise_linear([0.0, lam * P0], None, 16, P=[P0, 2 * P0]), model=model)
    assert float(result.total_dissipation) == 0.0
    final = contact(profile, 2 * P0)
    x = result.x.values
    expected = lam * (final.pressure(x) - formed.pressure(x))
    band = away_from(x, [-formed.a, formed.a, -final.a, final.a], final.a)
    assert np.max(np.abs(result.q.values[-1] - expected)[band]) < 1e-3 * F * formed.p0
    ends = np.stack([result.stick_start.values[:, 0], result.stick_end.values[:, 0]], axis=-1)
    np.testing.assert_allclose(ends, np.outer(result.a.values, [-1, 1]), rtol=1e-12)  # the edges grow stuck


@pytest.mark.parametrize("model", MODELS)
def test_cattaneo_mindlin_then_the_normal_load_up_and_down(model):
    """CM at (P0, Q0): P up to 1.5 P0 and back slips nowhere and keeps the traction; down to 0.8 P0 gives CM there."""
    formed = contact(fr.Hertz(0.05))
    P0, Q0 = formed.P, 0.6 * F * formed.P
    history = History.piecewise_linear([0.0, Q0, Q0, Q0, Q0], None, 16, P=[P0, P0, 1.5 * P0, P0, 0.8 * P0])
    result = fr.simulate(formed, history, model=model)
    x, q, dissipation = result.x.values, result.q.values, result.dissipation.values
    start, up, back, down = history.vertex_step[1:]
    assert np.all(dissipation[start + 1 : back + 1] == 0)  # no slip until back at P0
    b = cf.stick_half_width(formed, Q0)
    cm = cf.cattaneo_mindlin_traction(formed, Q0, x)  # zero on the band the contact gains
    raised = contact(fr.Hertz(0.05), 1.5 * P0)
    for step, a_now in ((up, raised.a), (back, formed.a)):
        band = away_from(x, [-b, b, -formed.a, formed.a, -a_now, a_now], a_now)
        assert np.max(np.abs(q[step] - cm)[band]) < 1e-3 * F * formed.p0
    lowered = contact(fr.Hertz(0.05), 0.8 * P0)
    c = cf.stick_half_width(lowered, Q0)
    band = away_from(x, [-c, c, -lowered.a, lowered.a], lowered.a)
    assert np.max(np.abs(q[down] - cf.cattaneo_mindlin_traction(lowered, Q0, x))[band]) < 1e-3 * F * formed.p0
    zones = np.stack([result.stick_start.values[down], result.stick_end.values[down]], axis=-1)
    np.testing.assert_allclose(zones[~np.isnan(zones[:, 0])], [[-c, c]], rtol=0, atol=1e-3 * lowered.a)


@pytest.mark.parametrize("ratio", [0.9, 1.1])
def test_increment_criterion(ratio):
    """Increments with dP > 0 and |dQ| + (pi a / 4) |dsigma| = ratio f dP slip nowhere for 0.9, and do for 1.1.

    Half of the budget goes to Q and half to sigma, their signs alternating between the two
    segments; ``a`` is the largest half-width of the segment for 0.9, the smallest for 1.1.
    """
    formed = contact(fr.Hertz(0.05))
    P = formed.P * np.array([1.0, 1.25, 1.5])
    widths = [formed.profile.half_width(load, E_STAR)[0] for load in P]
    Q, sigma = [0.0], [0.0]
    for k, sign in enumerate((1.0, -1.0)):
        dP = P[k + 1] - P[k]
        a = widths[k + 1] if ratio < 1 else widths[k]
        Q.append(Q[-1] + sign * ratio * F * dP / 2)
        sigma.append(sigma[-1] - sign * ratio * F * dP / 2 / (np.pi * a / 4))
    result = fr.simulate(formed, History.piecewise_linear(Q, sigma, 16, P=P))
    if ratio < 1:
        assert float(result.total_dissipation) == 0.0
    else:
        assert float(result.total_dissipation) > 1e-6 * energy_scale(formed)


def cycles(formed, Q_over_P, shift, count=4, steps=32, sigma_amplitude=0.0, before=None):
    """``P = Pm + 0.3 Pm sin``, ``Q = Qa sin(theta + shift) - Qa sin(shift)``, ``sigma = sigma_a sin``,
    ``Qa = Q_over_P f 0.3 Pm``, from the contact formed at ``Pm`` (after the history `before`)."""
    Pm, Pa = formed.P, 0.3 * formed.P
    theta = 2 * np.pi * np.remainder(np.arange(count * steps + 1), steps) / steps
    Qa = Q_over_P * F * Pa
    Q = Qa * (np.sin(theta + shift) - np.sin(shift))
    number = np.concatenate([[0], np.repeat(np.arange(1, count + 1), steps)])
    waves = History(Q, sigma_amplitude * np.sin(theta), np.arange(0, Q.size, steps), number, Pm + Pa * np.sin(theta))
    return waves if before is None else History.concatenate([before, waves])


@pytest.mark.slow
@pytest.mark.parametrize("model", MODELS)
def test_shakedown_in_phase_below_f(model):
    """Qa / Pa = 0.67 f in phase: nothing dissipated after the first cycle (Melan; Barber, Davies & Hills 2011)."""
    formed = contact(fr.Hertz(0.05))
    energy = fr.simulate(formed, cycles(formed, 0.67, 0.0), model=model).cycle_dissipation.values
    assert energy[0] > 0
    assert np.all(energy[1:] <= 1e-9 * energy[0])


@pytest.mark.slow
@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize(("Q_over_P", "shift"), [(1.07, 0.0), (0.67, 0.3)])
def test_no_shakedown_above_f_or_out_of_phase(Q_over_P, shift, model):
    """Qa / Pa = 1.07 f, or Q shifted by 0.3 rad: a steady energy per cycle, that does not vanish."""
    formed = contact(fr.Hertz(0.05))
    energy = fr.simulate(formed, cycles(formed, Q_over_P, shift), model=model).cycle_dissipation.values
    assert energy[-1] > 1e-2 * energy[0]
    np.testing.assert_allclose(energy[-1], energy[-2], rtol=1e-6)


@pytest.mark.slow
def test_steady_energy_does_not_depend_on_the_path_before():
    """The same (P, Q, sigma) cycle reached directly or after a detour has the same steady energy per cycle."""
    formed = contact(fr.Hertz(0.05))
    P0, fP = formed.P, F * formed.P
    detour = History.piecewise_linear([0.0, 0.4 * fP, -0.3 * fP, 0.0], [0.0, 40e6, -20e6, 0.0], 8, P=[P0] * 4)
    detour = History(detour.Q, detour.sigma, detour.vertex_step, np.zeros(len(detour), dtype=np.int64), detour.P)
    energies = [
        fr.simulate(
            formed, cycles(formed, 1.0, 0.3, count=5, sigma_amplitude=30e6, before=before)
        ).cycle_dissipation.values[-1]
        for before in (None, detour)
    ]
    np.testing.assert_allclose(energies[0], energies[1], rtol=1e-6)


def test_lift_off_and_start_are_refused():
    formed = contact(fr.Hertz(0.05))
    with pytest.raises(HistoryError, match="step 1"):  # P = 0 there
        History.piecewise_linear([0.0, 1.0], None, 2, P=[formed.P, -formed.P])
    with pytest.raises(HistoryError, match="history starts at P"):
        fr.simulate(formed, History.piecewise_linear([0.0, 1.0], None, 2, P=[2 * formed.P, formed.P]))
    with pytest.raises(HistoryError, match="varies the normal load"):
        fr.simulate(formed, History.piecewise_linear([0.0, 1.0], None, 2, P=[formed.P, 2 * formed.P]), nodes=64)


def test_gross_slip_when_P_falls():
    """|Q| > f P names the step also when it is P that falls under a constant Q."""
    formed = contact(fr.Hertz(0.05))
    Q = 0.5 * F * formed.P
    history = History.piecewise_linear([0.0, Q, Q], None, 4, P=[formed.P, formed.P, 0.3 * formed.P])
    first = int(np.argmax(F * history.P <= Q))  # step 7: P = 0.475 P0
    with pytest.raises(fr.GrossSlipError, match=f"step {first}"):
        fr.simulate(formed, history)


def test_constant_P_is_bit_for_bit_the_history_without_P():
    formed = contact(fr.Hertz(0.05))
    fP = F * formed.P
    Q = [0.0, 0.5 * fP, -0.4 * fP]
    without = fr.simulate(formed, History.piecewise_linear(Q, [0.0, 30e6, 0.0], 8))
    held = fr.simulate(formed, History.piecewise_linear(Q, [0.0, 30e6, 0.0], 8, P=[formed.P] * 3))
    assert without.attrs["model"] == held.attrs["model"]
    np.testing.assert_array_equal(without.q.values, held.q.values)
    np.testing.assert_array_equal(without.dissipation.values, held.dissipation.values)


@pytest.mark.slow
def test_dataset_records_the_normal_load_and_a_split_run_continues_bit_for_bit():
    formed = contact(fr.Hertz(0.05))
    history = cycles(formed, 1.07, 0.3, count=2, steps=16)
    whole = fr.simulate(formed, history, model=Varying())
    np.testing.assert_array_equal(whole.P.values, history.P)
    widths = [formed.profile.half_width(load, E_STAR)[0] for load in history.P]
    np.testing.assert_allclose(whole.a.values, widths, rtol=1e-12)
    h = whole.x.values[1] - whole.x.values[0]
    np.testing.assert_allclose(whole.p_step.values.sum(axis=1) * h, history.P, rtol=1e-12)  # the pressure carries P
    np.testing.assert_allclose(whole.w.values.sum(axis=1) * h, whole.cycle_dissipation.values, rtol=1e-5)  # float32 w
    assert np.all(whole.p_step.values[:, np.abs(whole.x.values) > whole.a.values.max()] == 0)
    first = fr.simulate(formed, history[:21], model=Varying().resolved_for(formed, history))
    later = fr.simulate(formed, history[20:], state=fr.final_state(first))
    np.testing.assert_array_equal(later.q.values, whole.q.values[20:])
    assert float(later.total_dissipation) == float(whole.total_dissipation)


HERTZ = """\
[contact]
profile = "hertz"
R = 0.05
E_star = 115e9
f = 0.5
P = 1e5
"""


def read(tmp_path, text, csv=None):
    from fretting.loading.history_file import read_history

    if csv is not None:
        (tmp_path / "loads.csv").write_text(csv)
    (tmp_path / "history.toml").write_text(HERTZ + text)
    return read_history(tmp_path / "history.toml")


def test_history_files_take_P(tmp_path):
    """`linear` P vertices, a `csv` P column, `sine` and `random` P_amplitude / P_mean: the same loads as History."""
    _, linear = read(tmp_path, '[[loading]]\nkind = "linear"\nQ = [1e4, 0]\nP = [1.5e5, 1e5]\nsteps_per_segment = 4\n')
    expected = History.piecewise_linear([0.0, 1e4, 0.0], None, 4, P=[1e5, 1.5e5, 1e5])
    np.testing.assert_array_equal(linear.P, expected.P)
    np.testing.assert_array_equal(linear.Q, expected.Q)
    _, series = read(
        tmp_path, '[[loading]]\nkind = "csv"\nfile = "loads.csv"\nsteps_per_segment = 4\n', "P,Q\n1.5e5,1e4\n1e5,0\n"
    )
    np.testing.assert_array_equal(series.P, expected.P)
    sine = '[[loading]]\nkind = "sine"\nQ_amplitude = 1e4\nP_amplitude = 2e4\nP_phase_deg = 90\ncycles = 2\n'
    _, waves = read(tmp_path, sine)
    theta = 2 * np.pi * np.remainder(np.arange(2 * 64 + 1), 64) / 64
    np.testing.assert_allclose(waves.P[-129:], 1e5 + 2e4 * np.cos(theta), rtol=1e-15)  # ramped up from P = 1e5
    assert waves.P[0] == 1e5
    _, drawn = read(
        tmp_path, '[[loading]]\nkind = "random"\ncycles = 3\nQ_amplitude = 1e4\nP_amplitude = 2e4\nseed = 1\n'
    )
    u = (drawn.Q[drawn.vertex_step] / 1e4)[1:]
    np.testing.assert_allclose(drawn.P[drawn.vertex_step][1:], 1e5 + 2e4 * u, rtol=1e-15)  # in phase with Q
    _, held = read(tmp_path, '[[loading]]\nkind = "linear"\nQ = [1e4, 0]\n')
    assert held.P is None  # the contact's constant P: no P column, the results of a history without P


@pytest.mark.slow
def test_dovetail_example_runs_the_varying_model():
    from fretting.loading.examples import example_path
    from fretting.loading.history_file import read_history

    formed, history = read_history(example_path("hertz_dovetail_cycle"))
    result = fr.simulate(formed, history)
    assert result.attrs["model"] == "varying"
    assert result.a.values.max() > 1.5 * formed.a  # the contact grows in every cycle
    energy = result.cycle_dissipation.values
    assert np.all(energy > 0)


@pytest.mark.slow
def test_figures_of_a_varying_P():
    import matplotlib

    matplotlib.use("Agg")
    from fretting import plots

    formed = contact(fr.Hertz(0.05))
    result = fr.simulate(formed, cycles(formed, 1.07, 0.0, count=1, steps=16))
    assert "contact_edges" in plots.figures_for(result)
    ax = plots.contact_edges(result)
    upper = ax.lines[0].get_ydata()
    np.testing.assert_allclose(upper, result.a.values / formed.a)  # the edges move with P
    assert upper.max() > 1.1 and upper.min() < 0.9
    plots.traction(result)
    with pytest.raises(ValueError, match="does not vary P"):
        plots.contact_edges(fr.simulate(formed, History.piecewise_linear([0.0, 1e3], None, 2)))


@pytest.mark.slow
def test_stepping_with_P_equals_the_run():
    formed = contact(fr.Hertz(0.05))
    history = cycles(formed, 1.07, 0.3, count=1, steps=16)
    stepper = fr.Stepper(formed, Varying().resolved_for(formed, history))
    for Q, sigma, P in zip(history.Q[1:], history.sigma[1:], history.P[1:], strict=True):
        stepper.step(Q, sigma, P=P)
    whole = fr.final_state(fr.simulate(formed, history, model=Varying().resolved_for(formed, history)))
    np.testing.assert_array_equal(stepper.state.slip, whole.slip)
    with pytest.raises(HistoryError, match="P must be a finite normal load > 0"):
        stepper.step(0.0, 0.0, P=-1.0)


@pytest.mark.slow
def test_surface_stress_of_a_varying_P_is_the_engine_tally():
    """`nucleation.surface_stress` of each recorded step (the pressure of that step) peaks as the engine's tally."""
    from fretting.analysis import nucleation

    formed = contact(fr.Hertz(0.05))
    result = fr.simulate(formed, cycles(formed, 1.07, 0.3, count=1, steps=16, sigma_amplitude=30e6))
    stress = nucleation.surface_stress(result).values
    cycle = result.cycle.values == 1
    np.testing.assert_allclose(
        result.sigma_xx_peak.values[0], stress[cycle].max(axis=0), rtol=1e-6, atol=1e-6 * formed.p0
    )


@pytest.mark.slow
def test_nucleation_of_a_varying_P_uses_each_step_or_refuses():
    """Ruiz from the recorded steps (pressure of each step) equals the engine's tally; what would assume the
    contact formed (w and slip amplitude without their tally, loop work) is refused."""
    from fretting.analysis import nucleation

    formed = contact(fr.Hertz(0.05))
    result = fr.simulate(formed, cycles(formed, 1.07, 0.3, count=2, steps=16, sigma_amplitude=30e6))
    tallied = nucleation.ruiz(result)
    recorded = nucleation.ruiz(result, bulk=0.0)  # the same bulk stresses, from the recorded steps
    np.testing.assert_allclose(recorded.F2.values, tallied.F2.values, rtol=1e-5)
    assert np.all(np.isfinite(nucleation.per_cycle(result).sigma_xx_max.values))
    with pytest.raises(ValueError, match="varies P"):
        nucleation.dissipation_density(result.drop_vars("w"))
    with pytest.raises(ValueError, match="varies P"):
        nucleation.slip_amplitude(result.drop_vars("slip_amplitude"))
    with pytest.raises(ValueError, match="loop_work assumes"):
        nucleation.loop_work(result)


@pytest.fixture(scope="module")
def random_walk():
    """A random (P, Q, sigma) walk, run on the default and on twice the cells with parts a quarter as large."""
    from fretting.models.normal import DEFAULT_CELLS, DEFAULT_LOAD_PART

    formed = contact(fr.Hertz(0.05))
    rng = np.random.default_rng(3)
    P = np.concatenate([[1.0], rng.uniform(0.7, 1.3, 4)]) * formed.P
    Q = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, 4)]) * F * formed.P
    sigma = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, 4)]) * F * formed.p0
    history = History.piecewise_linear(Q, sigma, 16, P=P)
    finer = Varying(2 * DEFAULT_CELLS, load_part=DEFAULT_LOAD_PART / 4)
    return fr.simulate(formed, history), fr.simulate(formed, history, model=finer)


@pytest.mark.slow
def test_default_stick_ends_follow_a_finer_run_at_every_step(random_walk):
    """Issue 22 test 6, stick ends: at every step of the walk, within 1e-3 a of the finer run (its edges
    recede and grow; benchmarks/normal_load.py: the table)."""
    default, finer = random_walk
    for name in ("stick_start", "stick_end"):
        found, reference = default[name].values, finer[name].values
        np.testing.assert_array_equal(np.isnan(found), np.isnan(reference))
        error = np.abs(found - reference) / default.a.values[:, None]
        assert np.nanmax(error) < 1e-3


@pytest.mark.slow
def test_default_energy_converges_on_a_random_history(random_walk):
    """Issue 22 test 6, energy: the default's total energy within 1e-4 (relative) of the finer run."""
    default, finer = random_walk
    energy = float(finer.total_dissipation)
    assert abs(float(default.total_dissipation) - energy) < 1e-4 * energy


def test_stick_end_between_two_nodes_from_the_kink_of_cattaneo_mindlin():
    """`kink_end` on the closed-form traction and slip of Cattaneo-Mindlin at nodes a cell apart, about the
    stick-zone edge b, on either side: b to 0.005 of the spacing (the local laws hold to higher order)."""
    from fretting.models.normal import kink_end

    formed = contact(fr.Hertz(0.05))
    Q = 0.6 * F * formed.P
    b, h = cf.stick_half_width(formed, Q), formed.a / 256
    for share in (0.05, 0.5, 0.95):
        x = np.array([b - share * h, b + (1 - share) * h])
        deficit = F * formed.pressure(x) - cf.cattaneo_mindlin_traction(formed, Q, x)
        slip = cf.cattaneo_mindlin_slip(formed, Q, x)
        assert abs(kink_end(x, slip, deficit, 0, 1, E_STAR) - b) < 0.005 * h
        assert abs(kink_end(-x[::-1], -slip[::-1], deficit[::-1], 1, 0, E_STAR) + b) < 0.005 * h


@pytest.mark.parametrize("n", [8, 64, 512])
def test_slip_to_traction_is_the_dense_one_and_symmetric(n):
    """Trench's recursion less the flat punch against LAPACK's inverse of the dense flexibility, ``B - b b^T / beta``
    (1e-12 relative), exactly symmetric and persymmetric, with the rigid shift in its null space; given the first
    column of ``B`` that a model keeps (`NormalModel.inverse_column`), the same bit for bit."""
    from scipy import linalg

    from fretting.models.normal import flexibility, slip_to_traction

    column = flexibility(n, 1e-5, E_STAR)
    B = np.linalg.inv(linalg.toeplitz(column))
    b = B.sum(axis=1)
    punch = linalg.solve_toeplitz(column, np.ones(n)) / b.sum()
    G = slip_to_traction(column, punch)
    np.testing.assert_array_equal(slip_to_traction(column, punch, linalg.solve_toeplitz(column, np.eye(n, 1)[:, 0])), G)
    expected = B - np.outer(b, b) / b.sum()
    scale = np.max(np.abs(expected))
    assert np.max(np.abs(G - expected)) < 1e-12 * scale
    np.testing.assert_array_equal(G, G.T)
    np.testing.assert_array_equal(G, G[::-1, ::-1])
    assert np.max(np.abs(G.sum(axis=1))) < 1e-12 * scale
    with pytest.raises(ValueError, match="even number"):
        slip_to_traction(column[:-1], np.ones(n - 1) / (n - 1))


def test_a_model_is_dropped_with_what_it_keeps():
    """The arrays a varying-load model keeps per run of cells go when the model goes (a cache on the class's
    methods would keep every model built alive, a few MB a run, without bound in a long sweep)."""
    import gc
    import weakref

    c = contact(fr.Hertz(0.05))
    model = Varying(64).resolved_for(c, None).build(c)
    model.stiffness(model.pairs(c.P))
    gone = weakref.ref(model)
    del model
    gc.collect()
    assert gone() is None


def test_the_stiffness_formed_again_from_kept_rows_is_the_same_and_they_stay_within_their_bytes(monkeypatch):
    """`NormalModel.stiffness` of a contact met again, formed from its kept rows or from nothing, is the same bit for
    bit as `slip_to_traction`'s; the rows kept never exceed `CACHED_HALVES` bytes, the least recently used dropped,
    and the whole stiffnesses `CACHED_STIFFNESSES`, but for one larger alone, kept by itself."""
    from fretting.models import normal

    c = contact(fr.Hertz(0.05))
    model = Varying(64).resolved_for(c, None).build(c)
    # The first m rows of G of m pairs, 2 m^2 floats: the halves of the runs of 13 to 24 pairs, more than the
    # stiffnesses kept whole (G, 4 m^2 floats) in the bytes of those of 29 to 32 pairs; down and up again, some
    # are formed from kept rows.
    monkeypatch.setattr(normal, "CACHED_HALVES", sum(16 * m**2 for m in range(13, 25)))
    monkeypatch.setattr(normal, "CACHED_STIFFNESSES", sum(32 * m**2 for m in range(29, 33)))
    runs = list(range(32, 12, -1)) + list(range(13, 33))
    for m in runs:
        G = model.stiffness(m).G
        expected = normal.slip_to_traction(model.column[: 2 * m], model.punch(m))
        np.testing.assert_array_equal(G, expected)
        assert sum(half.nbytes for half in model._halves.values()) <= normal.CACHED_HALVES
        assert sum(stiffness.G.nbytes for stiffness in model._stiffnesses.values()) <= normal.CACHED_STIFFNESSES
    kept = list(model._halves)
    assert len(kept) >= 4 and kept == runs[-len(kept) :]  # the most recently used, oldest first
    monkeypatch.setattr(normal, "CACHED_HALVES", 16 * 12**2)  # the rows of 12 pairs, fewer than any run's here
    monkeypatch.setattr(normal, "CACHED_STIFFNESSES", 32 * 12**2)  # G of 12 pairs, smaller than any run's here
    np.testing.assert_array_equal(model.stiffness(14).G, normal.slip_to_traction(model.column[:28], model.punch(14)))
    assert not model._halves  # rows over the bytes alone are not kept
    assert list(model._stiffnesses) == [14]  # a stiffness over its bytes is kept alone: the parts ask for it again
    assert model.stiffness(14) is model._stiffnesses[14]


@pytest.mark.slow
@pytest.mark.parametrize("shift", [1.001, 1.002])
def test_slip_zone_stops_at_a_former_edge(shift):
    """A slip zone that advances onto a former edge of the contact ends there (`fretting.models.normal.pinned`).

    A random (P, Q, sigma) walk on a Hertz contact, f = 0.6: the contact grows from step 96 under another
    ratio of shear to normal load than before it, then recedes; at step 124 the slip zone at the left edge
    reaches the edge of step 96, where the locked-in traction has its trough, and stops there. Its end
    is that edge, ``-a(P_96)``, within 1e-3 a, with the cells over the largest contact widened by `shift`
    (two positions of the cells against that edge).
    """
    formed = fr.Contact(fr.Hertz(0.05), E_STAR, 0.6, 1e5)
    rng = np.random.default_rng(1)
    P = np.concatenate([[1.0], rng.uniform(0.7, 1.3, 10)]) * formed.P
    Q = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, 10)]) * formed.f * formed.P
    sigma = np.concatenate([[0.0], rng.uniform(-0.4, 0.4, 10)]) * formed.f * formed.p0
    history = History.piecewise_linear(Q, sigma, 16, P=P)
    largest = Varying().resolved_for(formed, history).half_width
    result = fr.simulate(formed, history[:125], model=Varying(half_width=shift * largest))
    former = formed.profile.half_width(history.P[96], E_STAR)[0]
    a = result.a.values[124]
    assert abs(result.stick_start.values[124, 0] + former) < 1e-3 * a
