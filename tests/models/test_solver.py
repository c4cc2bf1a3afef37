"""The active-set solver's two ways of solving the slipping block: a Cholesky factor of it, and,
where few nodes stick, the stuck nodes' block of the regularised inverse (`Stiffness.solve_slipping`)."""

import warnings

import numpy as np
import pytest
from scipy import linalg

import fretting as fr
from fretting.models import solver


@pytest.fixture(scope="module")
def model():
    """A Galerkin model graded toward the edges and a stick zone, as adapted meshes are."""
    contact = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)
    theta = np.unique(np.r_[np.linspace(0, np.pi, 301), np.pi / 2 + np.geomspace(1e-4, 0.2, 60)])
    return fr.models.Mesh(theta=theta).build(contact)


@pytest.mark.parametrize("stuck", [slice(140, 150), slice(0, 3), slice(200, 201)])
def test_the_slipping_block_solved_through_the_stuck_nodes_as_by_cholesky(model, stuck):
    N = model.G.shape[0]
    slipping = np.delete(np.arange(N), np.arange(N)[stuck])
    rhs = np.random.default_rng(1).standard_normal(slipping.size) * 1e7
    block = model.G[np.ix_(slipping, slipping)]
    exact = linalg.cho_solve(linalg.cho_factor(block), rhs)
    found = solver.Stiffness(model.G).solve_slipping(slipping, rhs)
    assert np.abs(found - exact).max() <= 1e-11 * np.abs(exact).max()
    residual = np.abs(block @ found - rhs).max()
    assert residual <= 2 * np.abs(block @ exact - rhs).max() + 1e-15 * np.abs(rhs).max()


def test_an_increment_near_sliding_is_the_same_by_either_way(model):
    """Q at 0.999 f P with sigma: most nodes slip, so a kept stiffness solves through the stuck ones;
    the slip agrees with the Cholesky factor's to rounding, and the stick set is the same."""
    contact = model.contact
    g_stuck = model.g_stuck(0.999 * contact.f * contact.P, 0.3 * contact.f * contact.p0)
    kept = solver.Stiffness(model.G)
    by_complement = solver.solve_increment(kept, g_stuck, model.limit)
    by_cholesky = solver.solve_increment(solver.Stiffness(model.G, kept=False), g_stuck, model.limit)
    assert "regularised_inverse" in kept.__dict__  # the complement was taken
    np.testing.assert_array_equal(by_complement.ds == 0, by_cholesky.ds == 0)
    assert np.abs(by_complement.slip - by_cholesky.slip).max() <= 1e-11 * np.abs(by_cholesky.slip).max()


@pytest.mark.parametrize("tension", [0.0, 0.3])
def test_an_increment_given_the_product_it_returned_is_the_increment_that_forms_it(model, tension):
    """`Increment.product` is ``G slip`` of its slip (by rows, to rounding), and a next solve given it (the
    parts of a varying load's increment on the same cells) is the solve that forms it, bit for bit, and
    leaves it as it was: from a slipped state, on to further slip and back, under Q alone and with sigma."""
    contact, kept = model.contact, solver.Stiffness(model.G)
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    first = solver.solve_increment(kept, model.g_stuck(0.5 * fP, tension * fp0), model.limit)
    exact = model.G @ first.slip
    assert np.abs(first.product - exact).max() <= 1e-13 * np.abs(exact).max()
    guess, kept_product = np.sign(first.ds).astype(np.int8), first.product.copy()
    for Q in (0.6 * fP, 0.2 * fP):
        g_stuck = model.g_stuck(Q, tension * fp0)
        given = solver.solve_increment(kept, g_stuck, model.limit, first.slip, guess, first.product)
        formed = solver.solve_increment(kept, g_stuck, model.limit, first.slip, guess)
        assert given.ds.any()
        for name in ("slip", "ds", "g", "product"):
            np.testing.assert_array_equal(getattr(given, name), getattr(formed, name))
    np.testing.assert_array_equal(first.product, kept_product)


@pytest.mark.parametrize("complement", [0.0, solver.COMPLEMENT])
def test_one_ulp_below_sliding_settles_by_either_way(monkeypatch, complement):
    """Q = nextafter(f P, 0) on the adapted mesh: the one node left stuck closes the equilibrium and
    takes the sum of the slipping nodes' residuals, over its limit by rounding; releasing it sticks
    it again where it was. By the Cholesky factor alone (complement 0) that cycled until the
    solver gave up. A result, or GrossSlipError where the discrete friction force is below f P by
    rounding (it is, with other versions of numpy and scipy)."""
    monkeypatch.setattr(solver, "COMPLEMENT", complement)
    hertz = fr.Contact(fr.Hertz(0.05), fr.plane_strain_modulus(210e9, 0.3), 0.6, 1e5)
    Q = np.nextafter(hertz.f * hertz.P, 0)
    try:
        result = fr.simulate(hertz, fr.History.piecewise_linear([0, Q], None, 4), rtol=1e-4)
    except fr.GrossSlipError as error:
        assert error.step == 4 and error.limit <= hertz.f * hertz.P
    else:
        assert result.stick.values[-1].any() and np.all(np.isfinite(result.slip.values))


def test_the_solves_leave_slipping_nodes_well_within_the_rounding_allowance(model):
    """Out of phase near sliding (Q 0.9 f P, sigma 1.5 f p0), both ways of solving: at every step,
    every slipping node's traction is at the limit to a tenth of `solver.ROUNDING` of the largest
    term of its traction, so that the allowance holds the rounding the solves leave with a margin."""
    contact = model.contact
    history = fr.History.sinusoidal(0.9 * contact.f * contact.P, 1.5 * contact.f * contact.p0, 90, 1, 32)
    for stiffness in (model.stiffness, solver.Stiffness(model.G, kept=False)):
        slip, worst = np.zeros(model.limit.size), 0.0
        for Q, sigma in zip(history.Q[1:], history.sigma[1:], strict=True):
            g_stuck = model.g_stuck(Q, sigma)
            solved = solver.solve_increment(stiffness, g_stuck, model.limit, slip)
            slipping = solved.ds != 0
            scale = model.limit + np.abs(g_stuck) + stiffness.G_abs @ np.abs(solved.slip)
            residual = np.abs(solved.g - np.sign(solved.ds) * model.limit)[slipping] / scale[slipping]
            worst, slip = max(worst, residual.max(initial=0.0)), solved.slip
        assert 0 < worst <= solver.ROUNDING / 10


@pytest.mark.slow
@pytest.mark.parametrize(("moving", "power"), [("Q", 3), ("sigma", 1)])
def test_small_cycles_on_a_large_locked_in_slip_keep_their_law(moving, power):
    """After loading to (0.3 f P, 0.2 f p0), cycles of 1e-7 of f P (Q, sigma held) or of f p0 (sigma,
    Q held) dissipate as cycles of 1e-5 do, to 1e-4: ``W / A^3`` for Q (a small loop at the edges),
    ``W / A`` for sigma (the slip zones at the two edges driven on in turn). Both rest on the
    rounding allowance `solver.ROUNDING`: a cycle of Q dissipates only where its traction change
    exceeds the allowance on the traction of the locked-in slip, and the adaptation settles the
    energy of the increments of a cycle of sigma only where they slip again by more than
    ``ROUNDING / rtol`` of that slip (`_Energies.checkable`); benchmarks/small_loops.py prints
    where each kind loses its law."""
    import small_loops  # benchmarks/, on the path by conftest

    contact = small_loops.hertz()
    with warnings.catch_warnings():  # an increment below the floor is said (tests/test_trajectories.py)
        warnings.simplefilter("ignore", fr.ModelFallbackWarning)
        W = {A: small_loops.second_cycle(contact, A, moving)[0] / A**power for A in (1e-5, 1e-7)}
    assert W[1e-7] == pytest.approx(W[1e-5], rel=1e-4)
