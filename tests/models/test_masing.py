"""The exact model of Q alone on a symmetric profile (fretting.models.exact): Ciavarella-Jaeger and Masing's rule.

Checked against the closed forms of Hertz (Cattaneo-Mindlin, the Masing cycle energy and
delta_Q), against quadratures of eq (1) on the rounded flat, and against method 4 on a history
of nested loops.
"""

import numpy as np
import pytest
from checks import assert_friction_conditions
from harness import hard_rounded_flat
from scipy import integrate

import fretting as fr
from fretting.loading.loads import LoadBlock
from fretting.models import exact as masing
from fretting.physics import closed_forms as cf

#: Nested loops: 0.8 fP, back to -0.5, up to 0.6, down to -0.2, then through both closing points
#: to 0.9 and to -0.9 fP.
NESTED = [0.0, 0.8, -0.5, 0.6, -0.2, 0.9, -0.9]


def exact(contact, history, **keywords):
    """`fr.simulate` at its default, checked to be the exact model."""
    result = fr.simulate(contact, history, **keywords)
    assert result.attrs["model"] == masing.Exact.name
    return result


def nested(contact, steps=4):
    return fr.History.piecewise_linear(np.array(NESTED) * contact.f * contact.P, None, steps)


@pytest.mark.parametrize("psi", [1e-4, 0.1, 0.3, 0.999999])
def test_gap_of_hertz_is_cattaneo_mindlin(hertz, psi):
    """``s = f g_c`` is eq (19) integrated (closed_forms.cattaneo_mindlin_slip), to 1e-12 of itself
    at every point, also just outside ``c`` and in the thin slip zones of small ``psi``."""
    Q = psi * hertz.f * hertz.P
    c = cf.stick_half_width(hertz, Q)
    x = np.linspace(c, hertz.a, 300)
    reference = cf.cattaneo_mindlin_slip(hertz, Q, x)
    slip = hertz.f * masing.gap(hertz.profile, hertz.E_star, c, x)
    np.testing.assert_allclose(slip, reference, rtol=1e-12, atol=0)


@pytest.mark.parametrize("ratio", [1e-6, 1e-4, 1e-2, 0.5, 0.9, 0.999, 1 - 1e-6])
def test_hertz_closed_forms_are_the_quadrature(hertz, ratio):
    """On Hertz the exact model's branches are closed forms (`ExactModel._hertz_branches`); the
    quadrature of any other symmetric profile (`masing._quadrature_slip_zones`) gives them, from a
    stick zone of 1e-6 a to a slip zone of 1e-6 a: the slip at every node of the slip zones to 1e-12
    of itself (zero in the stick zone), the energy and delta_Q to ``1e-12 + 1e-15 / (1 - (c/a)^2)``
    (the quadrature's pressure ``p0 sqrt(1 - (X/a)^2)`` near the edge is known to ``eps / (1 - (X/a)^2)``)."""
    c = ratio * hertz.a
    theta = np.arccos(np.linspace(c, hertz.a, 301) / hertz.a)
    model = masing.Exact(theta=np.union1d(theta, np.pi - theta)).build(hertz)
    closed = model._hertz_branches(np.array([hertz.profile.load(c, hertz.E_star)]))[0]
    outside = np.abs(model.x) >= closed.c
    slip, energy, delta_Q = masing._quadrature_slip_zones(hertz, closed.c, model.x[outside])
    np.testing.assert_allclose(closed.slip[outside], slip, rtol=1e-12, atol=0)
    assert np.all(closed.slip[~outside] == 0)
    rtol = 1e-12 + 1e-15 / (1 - ratio**2)
    assert closed.energy == pytest.approx(energy, rel=rtol)
    assert closed.delta_Q == pytest.approx(delta_Q, rel=rtol)


def test_branches_solved_together_are_those_solved_alone(hertz):
    """`ExactModel.prepare` solves the branches of many steps in one 2-D evaluation: each equals,
    bit for bit, the branch solved alone (so that where a run is cut changes no result), and a
    run prepared is the run solved branch by branch, bit for bit."""
    Q = hertz.f * hertz.P * np.array([0.0, 0.5, -0.2, 0.3, 0.1, 0.45, -0.6, 0.2, 0.9999])
    spec = masing.Exact(64).resolved_for(hertz, None)
    together, alone = spec.build(hertz), spec.build(hertz)
    together.prepare(fr.State.virgin(together), LoadBlock(Q[1:], np.zeros(Q.size - 1)))
    assert len(together._branches) >= len(Q) - 1  # a branch at each load at least
    for P_c, branch in together._branches.items():
        single = alone._solved(P_c)
        assert (branch.c, branch.energy, branch.delta_Q) == (single.c, single.energy, single.delta_Q)
        assert np.array_equal(branch.slip, single.slip) and np.array_equal(branch.q, single.q)


@pytest.mark.parametrize("psi", [0.5, 0.99, 0.999999])
def test_gap_of_the_rounded_flat_solves_eq_1(psi):
    """Eq (1) outside the corrective contact ``[-c, c]``: with the surface displacement's log
    potential ``L(x) = int p_c(xi) ln|x - xi| dxi``, the gap is
    ``g(X) = h0(X) - h0(c) - (2 / (pi E_star)) (L(X) - L(c))``; by adaptive quadrature of ``L``
    it is the model's gap to 1e-9 at 0.1, 0.5 and 1 of the way from ``c`` to ``a``, also where
    ``c`` is 1.5e-8 m beyond the flat."""
    contact = hard_rounded_flat()
    b, R, E_star = contact.profile.b, contact.profile.R, contact.E_star
    corrective = cf.ciavarella_jaeger(contact, psi * contact.f * contact.P, np.zeros(1))[1]
    c = corrective.a

    def potential(X):  # L(X) - L(c), in one integral: its log singularity at xi = c is the endpoint's
        integrand = lambda xi: corrective.pressure(xi) * np.log((X - xi) / (c - xi))  # noqa: E731
        return integrate.quad(integrand, -c, c, points=[-b, b], epsabs=0, epsrel=1e-11, limit=400)[0]

    h0 = lambda x: (abs(x) - b) ** 2 / (2 * R)  # noqa: E731 - |x| > b
    for X in c + (contact.a - c) * np.array([0.1, 0.5, 1.0]):
        reference = h0(X) - h0(c) - 2 / (np.pi * E_star) * potential(X)
        assert masing.gap(contact.profile, E_star, c, np.array([X]))[0] == pytest.approx(reference, rel=1e-9)


@pytest.mark.parametrize("psi", [1e-6, 1e-3, 0.3, 0.95])
def test_cycle_energy_and_delta_Q_of_hertz(hertz, psi):
    """Steady cycles of ``Q = +-Q*``: the energy per cycle is Masing's closed form and ``delta_Q``
    at the first peak Cattaneo-Mindlin's, from 1e-6 fP (the cubic law, no noise floor) to
    0.95 fP, to ``1e-12 + 1e-15 / psi``: a branch is solved for its corrective load
    ``P_c = P - |Q - Q_k| / (k f)``, known to ``eps P``, so its ``psi = 1 - P_c / P`` is known to
    ``eps / psi``."""
    Q_star = psi * hertz.f * hertz.P
    rtol = 1e-12 + 1e-15 / psi
    result = exact(hertz, fr.History.sinusoidal(Q_star, cycles=3, steps_per_cycle=16))
    np.testing.assert_allclose(
        result.cycle_dissipation.values[1:], cf.mindlin_deresiewicz_energy(hertz, Q_star), rtol=rtol
    )
    peak = int(np.argmax(result.Q.values))
    assert result.delta_Q.values[peak] == pytest.approx(cf.cattaneo_mindlin_compliance(hertz, Q_star), rel=rtol)
    assert np.all(result.delta_sigma.values == 0)


def test_tiny_reversal_slips_by_the_cubic_law(hertz):
    """0.5 fP, then back by 1e-9 fP: the reversed slip zones are 2.5e-10 a wide (method 4 sees
    none, tests/engine/test_engine.py); the energy is half a Masing cycle of amplitude 5e-10 fP, and the
    outermost nodes slip backward."""
    fP = hertz.f * hertz.P
    result = exact(hertz, fr.History.piecewise_linear(np.array([0, 0.5, 0.5 - 1e-9]) * fP, None, [4, 1]))
    assert result.dissipation.values[-1] == pytest.approx(
        cf.mindlin_deresiewicz_energy(hertz, 0.5e-9 * fP) / 2, rel=1e-9
    )
    ds = result.slip.values[-1] - result.slip.values[-2]
    assert ds[-1] < 0 and not result.stick.values[-1, -1] and result.stick.values[-1, ds.size // 2]


@pytest.mark.parametrize("psi", [1e-6, 0.5, 0.999999])
def test_quadrature_has_converged(monkeypatch, psi):
    """Rounded flat: 256 Gauss-Legendre points instead of `masing.GAUSS` change the slip, the energy
    and delta_Q of a branch by less than 1e-12 of them."""
    contact = hard_rounded_flat()
    P_c = contact.P - psi * contact.P

    history = fr.History.piecewise_linear([0.0, psi * contact.f * contact.P], None, 1)
    theta = masing.nodes_theta(contact, history, fr.DEFAULT_NODES)

    def branch():
        return masing.Exact(theta=theta).build(contact)._solved(P_c)

    coarse = branch()
    monkeypatch.setattr(masing, "_U", np.polynomial.legendre.leggauss(256)[0])
    monkeypatch.setattr(masing, "_WEIGHTS", np.polynomial.legendre.leggauss(256)[1])
    fine = branch()
    assert coarse.energy == pytest.approx(fine.energy, rel=1e-12)
    assert coarse.delta_Q == pytest.approx(fine.delta_Q, rel=1e-12)
    np.testing.assert_allclose(coarse.slip, fine.slip, rtol=0, atol=1e-12 * np.abs(fine.slip).max())


@pytest.mark.slow
def test_method_4_converges_to_it():
    """Rounded flat, nested loops: the Galerkin meshes of rtol 1e-4 and 1e-5 give the exact
    model's total energy to within rtol (measured: 7.5e-6, 4.8e-8); the energy of each increment
    and delta_Q come 10 times closer on the finer mesh (energy: 1.3e-4 and 7.8e-6 of the largest
    increment's, the worst just after the first reversal); at 1e-4 the stick ends are within 2e-3 a."""
    contact = hard_rounded_flat()
    history = nested(contact)
    reference = exact(contact, history)
    dissipation, delta_Q = reference.dissipation.values, reference.delta_Q.values
    errors = []
    for rtol in (1e-4, 1e-5):
        result = fr.simulate(contact, history, rtol=rtol)
        assert result.total_dissipation.values == pytest.approx(reference.total_dissipation.values, rel=rtol)
        errors.append(
            (
                np.abs(result.dissipation.values - dissipation).max() / dissipation.max(),
                np.abs(result.delta_Q.values - delta_Q).max() / np.abs(delta_Q).max(),
            )
        )
        if rtol == 1e-4:
            for end in ("stick_start", "stick_end"):
                np.testing.assert_allclose(result[end].values[:, 0], reference[end].values[:, 0], atol=2e-3 * contact.a)
    assert np.all(np.array(errors[1]) < 0.1 * np.array(errors[0])), errors


@pytest.mark.parametrize("profile", ["hertz", "rounded_flat", "flat_punch"])
def test_friction_conditions_and_memory(hertz, profile):
    """Nested loops: Coulomb's law at every node, and each loop that closes restores the state of its
    first visit bit for bit (the slip is summed over the open branches in one order)."""
    flat_punch = fr.Contact(fr.FlatPunch(2e-3), 115e9, 0.5, 3e5)
    contact = {"hertz": hertz, "rounded_flat": hard_rounded_flat(), "flat_punch": flat_punch}[profile]
    psi = np.array([0.0, 0.8, -0.5, 0.6, -0.2, 0.6, -0.5, 0.8])
    history = fr.History.piecewise_linear(psi * contact.f * contact.P, None, 4)
    result = exact(contact, history)
    assert_friction_conditions(result, contact)
    vertex = history.vertex_step
    for first, again in ((3, 5), (2, 6), (1, 7)):
        np.testing.assert_array_equal(result.slip.values[vertex[again]], result.slip.values[vertex[first]])
    assert result.state_turning.values.size == 0  # back at 0.8 fP every loop has closed: the first loading's state
    if profile == "flat_punch":
        assert np.all(result.slip.values == 0) and np.all(result.dissipation.values == 0)


def test_periodic_cycles_are_copied(hertz):
    """The state after a cycle repeats the state before it bit for bit, so the cycles after the
    second are copied, and 10^4 of them take about as long as 3."""
    history = fr.History.sinusoidal(0.6 * hertz.f * hertz.P, cycles=10_000, steps_per_cycle=16)
    result = exact(hertz, history, record=[len(history) - 1])
    assert result.cycle_copied.values[2:].all() and not result.cycle_copied.values[:2].any()
    np.testing.assert_array_equal(result.cycle_dissipation.values[2:], result.cycle_dissipation.values[1])


def test_continued_run_equals_the_whole_run(hertz, tmp_path):
    """Cut at a vertex, saved, loaded and continued from its state (open turning points included):
    the same slip and energy, bit for bit. A continuation with sigma is refused."""
    history = nested(hertz)
    whole = exact(hertz, history)
    cut = int(history.vertex_step[4])
    fr.save(exact(hertz, history[: cut + 1]), tmp_path / "head.h5")
    state = fr.final_state(fr.load(tmp_path / "head.h5"))
    assert state.memory == (0.8 * hertz.f * hertz.P, -0.5 * hertz.f * hertz.P, 0.6 * hertz.f * hertz.P)
    tail = fr.simulate(hertz, history[cut:], state=state)
    np.testing.assert_array_equal(tail.slip.values, whole.slip.values[cut:])
    assert tail.total_dissipation.values == whole.total_dissipation.values
    mixed = fr.History.piecewise_linear([history.Q[cut], 0.0], [0.0, 1e6], 2)
    with pytest.raises(fr.HistoryError, match="exact model of Q alone"):
        fr.simulate(hertz, mixed, state=state)


def test_a_decaying_history_keeps_every_turning_point(hertz):
    """Reversals of shrinking range, 0 -> +A_1 -> -A_2 -> ... (1500 of them, none closing a loop):
    1500 open turning points, and the energy is the first loading's plus Masing's of each range,
    a quarter and half the closed-form cycle energy of the amplitudes Q_1 and r_k / 2, to 1e-9."""
    fP = hertz.f * hertz.P
    amplitude = 0.9 * fP * np.linspace(1.0, 0.1, 1501)
    Q = np.concatenate([[0.0], amplitude * np.where(np.arange(amplitude.size) % 2, -1.0, 1.0)])
    result = exact(hertz, fr.History.piecewise_linear(Q, None, 1), record=[Q.size - 1])
    assert result.state_turning.size == Q.size - 2
    ranges = np.abs(np.diff(Q[1:]))
    expected = cf.mindlin_deresiewicz_energy(hertz, Q[1]) / 4 + sum(
        cf.mindlin_deresiewicz_energy(hertz, r / 2) / 2 for r in ranges
    )
    assert result.total_dissipation.values == pytest.approx(expected, rel=1e-9)


def test_a_step_that_closes_a_loop_has_the_closing_branch_s_stick_zone(hertz):
    """0 -> 0.8 -> -0.8 -> 0.4 -> -0.4 -> 0.4 -> 0.5 f P: the step to 0.4 f P closes the inner loop. The
    points between the older branch's stick end and the closing branch's do not slip in it, so the stick
    zone of that increment is the closing branch's, ``a sqrt(1 - 0.8 / 2)``, the nodes with ``ds = 0``;
    past it the older branch from -0.8 f P goes on, ``a sqrt(1 - 1.3 / 2)`` at 0.5 f P."""
    path = np.array([0.0, 0.8, -0.8, 0.4, -0.4, 0.4, 0.5])
    history = fr.History.piecewise_linear(path * hertz.f * hertz.P, None, 1)
    result = exact(hertz, history)
    x = result.x.values - hertz.centre
    for step, c in ((5, hertz.a * np.sqrt(1 - 0.4)), (6, hertz.a * np.sqrt(1 - 0.65))):
        zone = result.isel(step=step)
        ends = np.array([zone.stick_start.item(), zone.stick_end.item()]) - hertz.centre
        np.testing.assert_allclose(ends, [-c, c], rtol=1e-12)
        np.testing.assert_array_equal(zone.stick.values.astype(bool), np.abs(x) < c)


def test_nodes_hold_thin_slip_zones_and_small_stick_zones(hertz):
    """The edge nodes: a slip zone 8e-12 a wide holds 4 or more (measured 9), the reversed zones
    of a 1e-6 fP cycle (1 - c/a = 5e-7) about 40; the stick-zone nodes: none added at Q/fP = 0.996
    (480 nodes), 16 from 0.997 on Hertz, where fewer grid nodes than that lie in the stick zone."""
    fP = hertz.f * hertz.P
    t = np.cos(masing.nodes_theta(hertz, fr.History.sinusoidal(1e-6 * fP, cycles=1), fr.DEFAULT_NODES))
    assert np.count_nonzero(t > 1 - 8e-12) >= 4
    assert 36 <= np.count_nonzero(t > np.sqrt(1 - 1e-6)) <= 44
    sizes = []
    for psi in (0.996, 0.997):
        theta = masing.nodes_theta(hertz, fr.History.piecewise_linear([0.0, psi * fP], None, 1), fr.DEFAULT_NODES)
        sizes.append(theta.size)
        assert np.count_nonzero(np.abs(np.cos(theta)) < np.sqrt(1 - psi)) >= masing.STICK_NODES
    assert sizes == [480, 496]


def test_a_run_prepared_is_the_run_solved_branch_by_branch(hertz):
    """A random history of Q run with its branches prepared (`fretting.engine.follow.PREPARED_STEPS`
    steps at a time) and branch by branch ends in the same state bit for bit: slip, tally, energy."""
    draws = np.random.default_rng(3).uniform(-0.8, 0.8, 40) * hertz.f * hertz.P
    history = fr.History.piecewise_linear(np.concatenate([[0.0], draws]), None, 3)
    spec = masing.Exact(64).resolved_for(hertz, history)
    alone = spec.build(hertz)
    alone.prepare = lambda state, loads: None  # the stepper then solves each branch as the increment meets it
    prepared, unprepared = (fr.Stepper(hertz, model).run(history) for model in (spec.build(hertz), alone))
    assert np.array_equal(prepared.slip, unprepared.slip) and prepared.memory == unprepared.memory
    assert prepared.dissipated == unprepared.dissipated and np.array_equal(prepared.tally.w, unprepared.tally.w)


def test_closed_forms_of_an_array_are_those_of_each_load(hertz):
    """Mindlin's energy and compliance and the slip shape take arrays (`ExactModel._hertz_branches`):
    each element is the scalar call's bit for bit, on both sides of the series' switch at psi = 1/4,
    and at psi = 1 the energy is the closed form's ``pi (f p0 a)^2 / (8 E_star)``."""
    Q = hertz.f * hertz.P * np.array([1e-6, 0.1, 0.2499, 0.25, 0.7, 1.0])
    for closed_form in (cf.cattaneo_mindlin_dissipation, cf.cattaneo_mindlin_compliance):
        assert closed_form(hertz, Q).tolist() == [closed_form(hertz, load) for load in Q.tolist()]
    ends = hertz.f * hertz.p0 * hertz.a
    assert cf.cattaneo_mindlin_dissipation(hertz, Q[-1]) == pytest.approx(np.pi * ends**2 / (8 * hertz.E_star), 1e-15)
    b, x = hertz.a * np.array([0.3, 0.9, 0.999]), np.linspace(-hertz.a, hertz.a, 101)
    rows = cf.hertz_slip_shape(x, b[:, None])
    assert all(np.array_equal(row, cf.hertz_slip_shape(x, half_width)) for row, half_width in zip(rows, b, strict=True))


def test_prepared_loads_past_gross_slip_are_left_to_the_run(hertz):
    """`prepare` stops its walk at the first load of ``|Q| >= f P`` (no corrective contact there:
    the run stops with a GrossSlipError naming the step, tests/engine/test_engine.py), having solved the
    branches before it."""
    model = masing.Exact(64).resolved_for(hertz, None).build(hertz)
    with np.errstate(all="raise"):
        model.prepare(fr.State.virgin(model), LoadBlock(hertz.f * hertz.P * np.array([0.5, -1.2, 0.3]), np.zeros(3)))
    assert list(model._branches) == [hertz.P, hertz.P - 0.5 * hertz.P]  # the branch from Q = 0 to 0.5 f P
