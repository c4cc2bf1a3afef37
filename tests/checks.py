"""Checks the tests share: the friction conditions and stick zones of a result, a run as a user makes it."""

import warnings

import numpy as np

import fretting as fr
from fretting.analysis.accuracy import zone_pairs
from fretting.models.method4 import INWARD

RESOLVED = 1e-2  # of the feature's own size
PROJECT = 1e-3  # of a (ends), of f p0 (traction), of the largest slip
BOUNDARY_BAND = 0.02  # [a] excluded around stick/slip boundaries for traction checks (square-root kink)
ROUNDING = 1e-10  # of f p0: rounding allowance of the friction conditions


def simulate_as_a_user(contact, history, **options):
    """`fr.simulate` where the default may fall back to the grid: if it does, it says so once in a
    `ModelFallbackWarning` and in the dataset's ``model_fallback``, and never otherwise."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", fr.ModelFallbackWarning)
        result = fr.simulate(contact, history, **options)
    said = [warning for warning in caught if issubclass(warning.category, fr.ModelFallbackWarning)]
    assert len(said) == ("model_fallback" in result.attrs)
    assert all(result.attrs["model_fallback"] in str(warning.message) for warning in said)
    return result


def zones(result):
    """Stick zones of the increment ending at `result`'s step, as (start, end) rows [m]."""
    return zone_pairs(result.stick_start.values, result.stick_end.values)


def assert_zones(result, expected, tolerance):
    found = zones(result)
    assert found.shape == np.shape(expected), f"stick zones {found.tolist()}, expected {np.asarray(expected).tolist()}"
    np.testing.assert_allclose(found, expected, rtol=0, atol=tolerance)


def increments(result):
    """Slip increment of every step [m] (step 0: the slip itself, zero from a virgin start)."""
    return np.diff(result.slip.values, axis=0, prepend=0.0)


def assert_friction_conditions(result, contact):
    """|q| <= f p; q = f p sign(ds) where a node slips; ds = 0 exactly where it sticks; dissipation
    >= 0, and exactly 0 where the stick zone is the whole contact. (Where every node sticks the
    exact model of Q alone may still slip beyond the outermost node, 5e-13 a from the edge.)"""
    fp = contact.f * result.p.values
    rounding = ROUNDING * np.maximum(contact.f * contact.p0, fp)  # the sharp flat punch: p unbounded at the ends
    q, stick, ds = result.q.values, result.stick.values, increments(result)
    assert np.all(np.abs(q) <= fp + rounding), "|q| > f p"
    assert np.all((np.abs(q - fp * np.sign(ds)) <= rounding)[~stick]), "q != f p sign(ds) where slipping"
    assert np.all(ds[stick] == 0), "a node marked stuck moved"
    assert np.all(ds[~stick] != 0), "a node marked slipping did not move"
    assert np.all(result.dissipation.values >= 0)
    edges = result.attrs["centre"] + result.attrs["a"] * np.array([-1.0, 1.0])
    whole = (result.stick_start.values[:, 0] == edges[0]) & (result.stick_end.values[:, 0] == edges[1])
    assert np.all(result.dissipation.values[whole] == 0), "the whole contact stuck, yet energy was dissipated"


def assert_zone_ends_are_consistent(result):
    """At every step, over the nodes in contact (those within the step's half-width ``a``, where ``P``
    varies): one stick zone per run of stuck nodes, in order along x; ``start <= end``; each zone
    overlaps its run and lies between the slipping nodes around it (or the contact's ends), so zones do
    not overlap and lie within the contact; and it covers its run but for at most `INWARD` of the
    spacing beyond each end of it, as far inside as an end is ever placed."""
    centre, nodes = result.attrs["centre"], result.x.values
    varies = "a" in result.data_vars and result["a"].dims == ("step",)
    for step, stuck in enumerate(result.stick.values):
        a = float(result["a"].values[step]) if varies else result.attrs["a"]
        inside = np.abs(nodes - centre) < a
        x, stick = nodes[inside], stuck[inside]
        rounding = 1e-12 if varies else 0.0  # a zone end at the edge is scaled to the step's a
        edge = np.array([-1.0, 1.0]) * a * (1 + rounding) + centre
        bounded = np.concatenate([[edge[0]], x, [edge[1]]])  # a slipping node's place, or the contact's end
        runs = np.flatnonzero(np.diff(np.concatenate([[0], stick.astype(np.int8), [0]]))).reshape(-1, 2)
        first, last = runs[:, 0], runs[:, 1] - 1
        start, end = result.stick_start.values[step], result.stick_end.values[step]
        recorded = ~np.isnan(start)
        assert np.array_equal(recorded, ~np.isnan(end)) and np.count_nonzero(recorded) == first.size, f"step {step}"
        start, end = start[recorded], end[recorded]
        if not start.size:
            continue
        assert np.all(start <= end), f"step {step}: inverted zones {np.stack([start, end], axis=-1).tolist()}"
        assert np.all(end[:-1] <= start[1:]), f"step {step}: overlapping zones"
        assert np.all(bounded[first] <= start) and np.all(end <= bounded[last + 2]), f"step {step}: past a slip node"
        assert np.all(start <= x[last]) and np.all(x[first] <= end), f"step {step}: a zone misses its stuck nodes"
        assert edge[0] <= start.min() and end.max() <= edge[1], f"step {step}: outside the contact"
        inward = INWARD * (1 + 1e-9) * np.diff(bounded)
        covered = (start <= x[first] + inward[first]) & (x[last] - inward[last + 1] <= end)
        assert covered.all(), f"step {step}: a zone leaves stuck nodes out"


def away_from(x, ends, a):
    return np.all(np.abs(np.subtract.outer(x, np.asarray(ends))) > BOUNDARY_BAND * a, axis=-1)
