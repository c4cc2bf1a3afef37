"""Displacement control in partial slip (docs/theory/displacement.md): the stuck compliance at the
datum against a quadrature of the half-plane's Green's function, force and displacement control
step by step, Mindlin-Deresiewicz's loop energy under +-delta* cycles, split runs, bad input."""

import math

import harness
import numpy as np
import pytest
from checks import assert_friction_conditions
from scipy.integrate import quad

import fretting as fr
from fretting.engine import follow, runner
from fretting.engine.recorder import final_state
from fretting.loading.history_file import HistoryFileError
from fretting.physics.closed_forms import cattaneo_mindlin_compliance, mindlin_deresiewicz_energy
from fretting.physics.contact import stuck_compliance

#: Datum [m] of the tests: about 21 half-widths from the middle of the Hertz contact below.
L = 5e-3


@pytest.fixture(scope="module")
def contact():
    return fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, datum=L)


def displaced_twin(history, delta):
    """`history` with the displacements `delta` [m] prescribed at its steps instead of its Q."""
    return fr.History(np.full(len(history), np.nan), history.sigma, history.vertex_step, history.cycle, None, delta)


def cycles_of(delta_star, count, steps):
    """A ramp from rest to `delta_star` [m], then `count` cycles +delta* -> -delta* -> +delta*."""
    ramp = fr.History.piecewise_linear(delta=[0.0, delta_star], steps_per_segment=steps)
    cycle = fr.History.piecewise_linear(delta=[delta_star, -delta_star, delta_star], steps_per_segment=steps)
    return fr.History.concatenate([ramp, *[cycle.as_cycle()] * count])


@pytest.mark.parametrize("x_over_a", [-0.9, -0.3, 0.0, 0.5, 0.99])
@pytest.mark.parametrize("L_over_a", [1.5, 4.0, 100.0])
def test_stuck_compliance_is_the_quadrature_of_the_green_function(x_over_a, L_over_a):
    """Eq D3: the relative tangential displacement of a point of the stuck contact and the datum
    under the stuck traction ``Q / (pi sqrt(a^2 - xi^2))``, from the surface displacement
    ``-(1 / (pi E_star)) Q ln|x|`` of each half-plane under a line force (Johnson 1985, §2.3),
    is ``C_L Q`` wherever the point lies in the contact."""
    a, E_star, Q = 2e-4, 115e9, 3e4
    x, datum = x_over_a * a, L_over_a * a
    # xi = a cos(theta): d xi / sqrt(a^2 - xi^2) = d theta; a log singularity at theta = arccos(x / a)
    kernel = lambda theta: math.log(abs(datum - a * math.cos(theta))) - math.log(abs(x - a * math.cos(theta)))  # noqa: E731
    integral, _ = quad(kernel, 0.0, math.pi, points=[math.acos(x_over_a)], epsabs=0.0, epsrel=1e-13, limit=200)
    quadrature = 2 / (math.pi * E_star) * (Q / math.pi) * integral
    assert quadrature == pytest.approx(stuck_compliance(datum, a, E_star) * Q, rel=1e-11)


def test_far_datum_gives_the_logarithm():
    """``C_L -> (2 / (pi E_star)) ln(2 L / a)`` for ``L >> a``, to ``O((a / L)^2)``."""
    a, E_star = 2e-4, 115e9
    for ratio in (10.0, 100.0, 1000.0):
        log = 2 * math.log(2 * ratio) / (math.pi * E_star)
        assert abs(stuck_compliance(ratio * a, a, E_star) / log - 1) < 1 / ratio**2


@pytest.mark.parametrize("spec", [fr.models.Grid(64), fr.models.Exact()], ids=["grid", "exact"])
def test_force_and_displacement_control_agree_step_by_step(contact, spec):
    """Run a force history, prescribe its recorded delta: the Q found at every step is the history's
    to 1e-9 of f P and the slip the same to 1e-9 of its largest value."""
    fP = contact.f * contact.P
    history = fr.History.piecewise_linear([0, 0.6 * fP, -0.4 * fP, 0.7 * fP, 0.1 * fP], None, 12)
    forced = fr.simulate(contact, history, spec)
    moved = fr.simulate(contact, displaced_twin(history, forced.delta.values), spec)
    assert np.max(np.abs(moved.Q.values - forced.Q.values)) < 1e-9 * fP
    assert np.max(np.abs(moved.slip.values - forced.slip.values)) <= 1e-9 * np.abs(forced.slip.values).max()
    assert np.array_equal(moved.delta.values, forced.delta.values) or np.allclose(
        moved.delta.values, forced.delta.values, rtol=0, atol=1e-12 * np.abs(forced.delta.values).max()
    )


def test_force_and_displacement_control_agree_with_bulk_tension(contact):
    """The same with a bulk tension that moves out of phase (method 4 on a grid)."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.piecewise_linear([0, 0.5 * fP, -0.3 * fP, 0.4 * fP], [0, 0.3 * fp0, 0.3 * fp0, -0.2 * fp0], 10)
    spec = fr.models.Grid(48)
    forced = fr.simulate(contact, history, spec)
    moved = fr.simulate(contact, displaced_twin(history, forced.delta.values), spec)
    assert np.max(np.abs(moved.Q.values - forced.Q.values)) < 1e-9 * fP


def test_a_step_tries_no_shear_beyond_what_meets_its_delta_without_slip(contact, monkeypatch):
    """Each step's trials lie between the state's Q and the Q that would meet its delta with no more slip
    (docs/theory/displacement.md#solve), where that is nearer than the friction force: on sinusoids of Q
    and sigma within 0.5 f P, no trial comes near f P, where most of the contact slips (the bracket's
    end at (1 - 1e-9) f P was tried at every step before); the Q found is force control's."""
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    history = fr.History.sinusoidal(0.5 * fP, 0.3 * fp0, 90.0, cycles=1, steps_per_cycle=24)
    spec = fr.models.Grid(48)
    forced = fr.simulate(contact, history, spec)
    tried = []

    class Trial(follow.Loads):
        def __init__(self, Q, *loads):
            tried.append(Q)
            super().__init__(Q, *loads)

    monkeypatch.setattr(follow, "Loads", Trial)
    moved = fr.simulate(contact, displaced_twin(history, forced.delta.values), spec)
    assert len(tried) >= 2 * (len(history) - 1)  # a bracket's two ends a step at least
    assert np.max(np.abs(tried)) < 0.6 * fP
    assert np.max(np.abs(moved.Q.values - forced.Q.values)) < 1e-9 * fP


def test_first_loading_follows_mindlin(contact):
    """On first loading delta = C_L Q + Mindlin's delta_Q(Q) (eq D4 with `cattaneo_mindlin_compliance`)."""
    delta = np.linspace(0.0, 1e-6, 9)
    history = fr.History(np.full(delta.size, np.nan), np.zeros(delta.size), [0, delta.size - 1], delta=delta)
    result = fr.simulate(contact, history, fr.models.Exact())
    Q = result.Q.values
    expected = contact.displacement_compliance * Q + cattaneo_mindlin_compliance(contact, Q)
    assert np.max(np.abs(expected - delta)) < 1e-12 * delta.max()


@pytest.mark.parametrize("spec,rtol", [(fr.models.Exact(), 1e-6), (fr.models.Grid(96), 1e-3)], ids=["exact", "grid"])
def test_cycles_of_displacement_dissipate_mindlin_deresiewicz(contact, spec, rtol):
    """+-delta* cycles in partial slip: each cycle dissipates Mindlin-Deresiewicz's energy at the Q*
    the run finds (the exact model to 1e-6; the grid's own discretisation error beside it)."""
    result = fr.simulate(contact, cycles_of(1e-6, 3, 16), spec)
    Q_star = float(np.abs(result.Q.values).max())
    assert 0.5 < Q_star / (contact.f * contact.P) < 0.95  # partial slip, well into it
    expected = mindlin_deresiewicz_energy(contact, Q_star)
    assert np.allclose(result.cycle_dissipation.values, expected, rtol=rtol, atol=0)
    assert float(result.Q.values[-1]) == pytest.approx(Q_star, rel=1e-12)  # each cycle closes on +Q*


@pytest.mark.parametrize("spec", [fr.models.Grid(32), fr.models.Exact()], ids=["grid", "exact"])
def test_split_runs_resume_bit_for_bit(contact, spec):
    """A displacement history split at any step and resumed from `final_state` is the whole run bit for bit."""
    history = cycles_of(9e-7, 2, 6)
    whole = fr.simulate(contact, history, spec)
    for k in range(1, len(history) - 1, 5):
        first = fr.simulate(contact, history[: k + 1], spec)
        later = fr.simulate(contact, history[k:], state=final_state(first))
        for name in ("Q", "delta", "slip"):
            assert np.array_equal(later[name].values, whole[name].values[k:]), (k, name)
        assert np.array_equal(later.dissipation.values[1:], whole.dissipation.values[k + 1 :])  # step 0: at rest
        assert np.array_equal(
            later.cycle_dissipation.values, whole.cycle_dissipation.values[-later.cycle_number.size :]
        )


def test_default_model_of_a_displacement_history(contact):
    """The exact model for delta alone; with sigma, not a mesh to adapt (its Q is found as it runs)."""
    alone = fr.History.piecewise_linear(delta=[0, 8e-7, -8e-7], steps_per_segment=4)
    assert fr.choose_model(contact, alone).name == "exact"
    tension = fr.History.piecewise_linear(delta=[0, 8e-7, -8e-7], sigma=[0, 3e7, -3e7], steps_per_segment=4)
    assert fr.choose_model(contact, tension).name == "varying"
    with pytest.raises(fr.HistoryError, match="a history of delta finds only as it runs"):
        fr.simulate(contact, tension, fr.models.Mesh())


def test_the_cells_keep_coulomb_s_law_in_the_pressure_the_result_holds(contact):
    """A displacement with sigma runs on the cells (`Varying`), whose friction limit is f times their own
    pressure, Jaeger's superposition of discrete flat punches: the result's p is that pressure, so that
    |q| <= f p, and q = f p sign(ds) where a node slips, at every node of every step, also at the
    outermost cells in contact, where the closed form at the cell centres differs from it."""
    history = fr.History.piecewise_linear(delta=[0, 8e-7, -8e-7, 4e-7], sigma=[0, 6e7, -6e7, 2e7], steps_per_segment=4)
    result = fr.simulate(contact, history)
    assert result.attrs["model"] == "varying"
    assert_friction_conditions(result, contact)
    np.testing.assert_array_equal(
        result.p.values, fr.models.Varying().resolved_for(contact, history).build(contact).pressure_at(contact.P)
    )


def test_a_history_no_default_runs_is_a_one_line_error_naming_why():
    """On an asymmetric profile the displacement (the mesh adapts to the Q of every step, which delta finds only
    as it runs) and a varying P (Jaeger's model and the cells need a symmetric profile that grows with P) have
    no default: a HistoryError with each default's reason, and the grid where it runs the history."""
    asymmetric = harness.family_contact("asymmetric", (5e-4, 0.01, 0.04), 0.6, 3e5)
    contact = fr.Contact(asymmetric.profile, asymmetric.E_star, asymmetric.f, asymmetric.P, datum=L)
    displaced = fr.History.piecewise_linear(delta=[0, -5.7e-7, 1.2e-6], steps_per_segment=4)
    with pytest.raises(
        fr.HistoryError, match=r"no default model runs this history \(method 4 on a grid does: .*nodes="
    ) as error:
        fr.simulate(contact, displaced)
    assert "\n" not in str(error.value) and "mesh: the mesh adapts to the Q of every step" in str(error.value)
    assert fr.simulate(contact, displaced, nodes=64).attrs["model"] == "grid"
    loaded = fr.History.piecewise_linear([0, 1e4, -1e4], None, 4, P=[3e5, 3.3e5, 2.9e5])
    with pytest.raises(fr.HistoryError, match="no default model runs this history: exact, inphase, mesh: .* varies"):
        fr.simulate(contact, loaded)


def test_stepper_steps_a_displacement(contact):
    stepper = fr.Stepper(contact, fr.models.Grid(32))
    stepper.step(delta=5e-7)
    assert stepper.state.loads.delta == 5e-7
    assert contact.displacement(stepper.state.Q, 0.0) < 5e-7  # part of delta is slip
    with pytest.raises(fr.HistoryError, match="either Q or delta, found both"):
        stepper.step(1e3, delta=5e-7)
    with pytest.raises(fr.HistoryError, match="found delta = inf, sigma = 0.0"):
        stepper.step(delta=np.inf)
    with pytest.raises(fr.HistoryError, match="found Q = nan, sigma = 0.0"):
        stepper.step(np.nan)


def test_beyond_sliding_is_gross_slip(contact):
    """Method 4's grid slides from step 2 on; fed to force control, that step is an error."""
    history = fr.History.piecewise_linear(delta=[0, 4e-6], steps_per_segment=4)
    slid = fr.simulate(contact, history, fr.models.Grid(32))
    assert slid.regime.values.tolist() == [0, 1, 2, 2, 2]
    assert np.all(slid.Q.values[2:] == fr.models.Grid(32).build(contact).sliding_force())
    with pytest.raises(fr.GrossSlipError, match="gross slip at step 2: Q = 60000"):
        fr.simulate(contact, fr.History(slid.Q.values, np.zeros(5), [0, 4]), fr.models.Grid(32))


def test_bad_input_is_one_line_error(contact):
    with pytest.raises(fr.HistoryError, match="either Q or delta, found both"):
        fr.History.piecewise_linear([0, 1.0], delta=[0, 1e-7])
    with pytest.raises(fr.HistoryError, match="either Q or delta, found neither"):
        fr.History.piecewise_linear(sigma=[0, 1.0])
    with pytest.raises(fr.HistoryError, match="step 1 gives both Q and delta"):
        fr.History([np.nan, 1.0], [0, 0], [0, 1], delta=[0.0, 1e-7])
    with pytest.raises(fr.HistoryError, match="step 0 gives neither Q nor delta"):
        fr.History([np.nan, np.nan], [0, 0], [0, 1], delta=[np.nan, 1e-7])
    bare = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    with pytest.raises(fr.HistoryError, match="no datum"):
        fr.simulate(bare, fr.History.piecewise_linear(delta=[0, 1e-7], steps_per_segment=2), fr.models.Grid(16))
    for keywords, message in (
        ({"datum": -1.0}, "datum must be"),
        ({"datum": 1e-4}, "datum must be a distance L > a"),
        ({"datum": L, "compliance": -1e-12}, "compliance must be >= 0"),
        ({"compliance": 1e-12}, "compliance needs a datum"),
    ):
        with pytest.raises(ValueError, match=message):
            fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5, **keywords)


FILE = """
[contact]
profile = "hertz"
R = 0.05
E_star = 115e9
f = 0.6
P = 1e5
{contact}

[[loading]]
kind = "linear"
{first}
steps_per_segment = 4
{second}
"""


def test_history_file_reads_delta(tmp_path, contact):
    path = tmp_path / "moved.toml"
    second = '[[loading]]\nkind = "linear"\ndelta = [-8e-7, 8e-7]\ncycle = true'
    path.write_text(FILE.format(contact=f"datum = {L}\ncompliance = 1e-12", first="delta = [8e-7]", second=second))
    read, history = fr.read_history(path)
    assert (read.datum, read.compliance) == (L, 1e-12)
    assert history.delta[[0, 4, -1]].tolist() == [0.0, 8e-7, 8e-7] and np.isnan(history.Q).all()
    result = fr.simulate(read, history, fr.models.Grid(32))
    assert (result.attrs["datum"], result.attrs["compliance"]) == (L, 1e-12)
    assert result.delta.values[-1] == pytest.approx(8e-7, rel=1e-12)


@pytest.mark.parametrize(
    "contact_keys,first,second,message",
    [
        ("", "delta = [8e-7]", "", r"moved.toml.*contact.*datum"),
        (f"datum = {L}", "Q = [1e3]\ndelta = [8e-7]", "", r"moved.toml.*loading\[1\]\.delta.*both Q and delta"),
        (
            f"datum = {L}",
            "delta = [8e-7]",
            '[[loading]]\nkind = "linear"\nsigma = [1e6]',
            r"loading\[2\].*neither Q nor delta",
        ),
        (
            f"datum = {L}",
            "Q = [1e3]",
            '[[loading]]\nkind = "linear"\ndelta = [1e-7]',
            r"loading\[2\]\.delta.*after a block of Q",
        ),
        ("datum = -1.0", "delta = [8e-7]", "", r"contact\.datum"),
        ("datum = 1e-4", "delta = [8e-7]", "", r"contact\.datum.*L > a"),
        ("compliance = 1e-12", "Q = [1e3]", "", r"contact\.compliance.*without a datum"),
    ],
)
def test_history_file_errors_name_file_and_key(tmp_path, contact_keys, first, second, message):
    path = tmp_path / "moved.toml"
    path.write_text(FILE.format(contact=contact_keys, first=first, second=second))
    with pytest.raises(HistoryFileError, match=message) as caught:
        fr.read_history(path)
    assert "\n" not in str(caught.value)


def test_a_file_of_delta_run_in_chunks_is_the_run_in_one_piece(tmp_path, monkeypatch):
    """`run_file` cuts the history into chunks, each continued from the state the one before left."""
    monkeypatch.setattr(runner, "CHUNK_STEPS", 5)
    monkeypatch.setattr(runner, "CHUNK_SECONDS", 0.0)
    path = tmp_path / "moved.toml"
    second = '[[loading]]\nkind = "linear"\ndelta = [-8e-7, 8e-7]\ncycle = true'
    path.write_text(FILE.format(contact=f"datum = {L}", first="delta = [8e-7]", second=second))
    read, history = fr.read_history(path)
    chunked = runner.run_file(path, tmp_path / "moved.h5", fr.models.Grid(32), record="all").result
    whole = fr.simulate(read, history, fr.models.Grid(32))
    for name in ("Q", "delta", "slip"):
        assert np.array_equal(chunked[name].values, whole[name].values), name
    assert float(chunked.state_delta) == 8e-7
