"""Property-based checks of the invariants over random histories and profiles.

A coarse grid (64 nodes) keeps the examples fast: the properties hold at any resolution.
"""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import fretting as fr

NODES = 64
PROFILES = {
    "hertz": fr.Hertz(0.05),
    "rounded_flat": fr.RoundedFlat(2e-4, 0.02),
    "flat": fr.FlatPunch(3e-4),
}


def scene(name):
    return fr.Contact(PROFILES[name], 115e9, 0.6, 1e5)


loads = st.lists(st.tuples(st.floats(-0.95, 0.95), st.floats(-2.0, 2.0)), min_size=1, max_size=6)


@settings(max_examples=30, deadline=None)
@given(name=st.sampled_from(sorted(PROFILES)), vertices=loads, steps=st.integers(1, 6))
def test_friction_conditions_and_dissipation(name, vertices, steps):
    contact = scene(name)
    psi, tau = np.array([(0.0, 0.0), *vertices]).T
    history = fr.History.piecewise_linear(psi * contact.f * contact.P, tau * contact.f * contact.p0, steps)
    result = fr.simulate(contact, history, nodes=NODES)
    fp, q = contact.f * result.p.values, result.q.values
    ds = np.diff(result.slip.values, axis=0, prepend=0.0)
    rounding = 1e-9 * contact.f * contact.p0
    assert np.all(np.abs(q) <= fp + rounding)
    slipping = ~result.stick.values
    assert np.all(np.abs(q - fp * np.sign(ds))[slipping] <= rounding)
    assert np.all(ds[result.stick.values] == 0)
    assert np.all(result.dissipation.values >= 0)
    assert np.any(result.stick.values, axis=1).all()


@settings(max_examples=30, deadline=None)
@given(
    name=st.sampled_from(["hertz", "rounded_flat"]),
    peak=st.floats(0.1, 0.9),
    low=st.floats(-0.9, 0.9),
    high=st.floats(-0.9, 0.9),
)
def test_return_point_memory_for_shear(name, peak, low, high):
    """Q-only, symmetric profile: 0 -> peak -> low -> high -> low -> peak, with the minor loop
    inside the major one (peak >= high >= low >= -peak), restores the state at low and at peak."""
    low, high = np.clip(sorted((low, high)), -peak, peak)
    contact = scene(name)
    fP = contact.f * contact.P
    history = fr.History.piecewise_linear(np.array([0, peak, low, high, low, peak]) * fP, None, 4)
    slip = fr.simulate(contact, history, nodes=NODES, record=history.vertex_step).slip.values
    scale = np.abs(slip).max()
    np.testing.assert_allclose(slip[4], slip[2], rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(slip[5], slip[1], rtol=0, atol=1e-9 * scale)


@settings(max_examples=20, deadline=None)
@given(amplitude=st.floats(0.1, 0.9), tau=st.floats(-1.5, 1.5), steps=st.integers(8, 24))
def test_loop_work_equals_dissipation_on_closed_cycles(amplitude, tau, steps):
    """Work of the loads over a closed in-phase cycle equals the dissipation, to the
    trapezoidal error of the polygonal loop (second order in the step)."""
    contact = scene("hertz")
    fP, fp0 = contact.f * contact.P, contact.f * contact.p0
    Q = np.array([0, 1, -1, 1]) * amplitude * fP
    history = fr.History.piecewise_linear(Q, tau * fp0 * Q / fP, steps)
    result = fr.simulate(contact, history, nodes=NODES)
    first, last = history.vertex_step[1], history.vertex_step[3]
    part = result.isel(step=slice(first, last + 1))
    work = np.trapezoid(part.Q.values, part.delta_Q.values) + np.trapezoid(part.sigma.values, part.delta_sigma.values)
    dissipated = part.dissipation.values[1:].sum()
    assert dissipated > 0
    assert abs(work / dissipated - 1) < 2.0 / steps**2
