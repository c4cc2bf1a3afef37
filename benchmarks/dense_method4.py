"""A dense method-4 code of our own: Chebyshev-Gauss collocation, one dense solve per active-set iteration.

The yardstick of benchmarks/speed_ratio.py (and, as `harness.baseline_simulate`, of
benchmarks/speed_vs_error.py): method 4 of the seed paper written the way the field writes it by
hand, independent of `fretting.models` (it takes from the package only the contact's profile, for
the pressure of the normal problem). Not part of the installed package.

The slip ``s_k`` lives at the ``N`` points ``t_k = cos((2k - 1) pi / (2N))``, ``x = centre + A t``,
on the interval ``[centre - A, centre + A]`` of the largest contact of the history. With
``g = sqrt(1 - t^2) q`` the weighted traction, the dislocation part of the traction is
``g_d = -G s`` with ``G_jk = (E_star / (A N)) sum_n n T_n(t_j) T_n(t_k)`` (formulation.md section
4: the slip-to-traction operator is diagonal in the Chebyshev basis, and Gauss-Chebyshev quadrature
turns it into this matrix; Erdogan & Gupta 1972), the fully stuck part that of eqs 9 and 20 of the
seed paper, ``g_st = (Q / pi + sigma (x - centre) / 4) / A``.

Each increment starts from the previous increment's slip set and iterates: solve ``G_SS ds_S =
g_trial_S - dir_S f p_S sqrt(1 - t_S^2)`` with `numpy.linalg.solve`, stick the slipping points whose
slip went against its direction, release the stuck points whose traction exceeds the friction limit,
until nothing moves (the stationarity conditions of the convex increment, formulation.md section 3).

A varying normal load ``P`` (docs/theory/normal-load.md): the normal and tangential problems
uncouple for similar materials, so the pressure at each load is that of the constant-load problem.
Points of the grid outside the current contact carry a friction limit of zero: they move freely
(zero traction), and a point that enters the contact sticks with the relative displacement it had.
Each step is cut into parts that change ``P`` by at most `LOAD_PART` of the contact's ``P``, and at the
loads where points enter or leave (`part_ends`), each an implicit increment under the friction limit
of its end load, its energy ``int f (p_begin + p_end) |ds| / 2 dx`` (trapezoidal in ``P``). A point
slips in a step where it moves in a part that ends with it in contact: the free surfaces' motion
before it enters is not slip, so a band that enters and sticks counts as stuck.
"""

import math
from dataclasses import dataclass

import numpy as np

#: Working-set changes one increment may take before it gives up.
ITERATIONS = 200

#: Rounding allowance of the friction test, relative to the largest limit.
ROUNDING = 1e-13

#: Largest change of ``P`` in one part of a step, as a fraction of the contact's ``P``.
LOAD_PART = 1 / 400


class GrossSlip(RuntimeError):
    """Every point of the contact slips, or the slip set does not settle: force control cannot go on."""


@dataclass(frozen=True, eq=False)
class Run:
    """What a run gives at every step of its history, on its own points ``x``.

    Attributes
    ----------
    x : ndarray, shape (N,)
        Positions [m], ascending.
    q, slip, p : ndarray, shape (n_steps, N)
        Shear traction [Pa], slip (relative tangential displacement) [m] and pressure [Pa] at the
        end of each step (zero pressure: out of contact).
    stick : ndarray of bool, shape (n_steps, N)
        The point did not slip in the increment ending at each step (step 0: the start).
    dissipation : ndarray, shape (n_steps,)
        Energy dissipated in the increment ending at each step [J/m].
    a, centre : ndarray, shape (n_steps,)
        Contact half-width and middle at each step [m].
    f, p0 : float
        Friction coefficient [-] and the peak pressure of the contact as given [Pa].
    """

    x: np.ndarray
    q: np.ndarray
    slip: np.ndarray
    p: np.ndarray
    stick: np.ndarray
    dissipation: np.ndarray
    a: np.ndarray
    centre: np.ndarray
    f: float
    p0: float


def stiffness(E_star, A, nodes):
    """The points ``t`` of the grid (ascending) and the slip-to-weighted-traction matrix ``G`` [Pa/m]."""
    theta = (2 * np.arange(nodes, 0, -1) - 1) * np.pi / (2 * nodes)
    n = np.arange(nodes)
    T = np.cos(np.outer(theta, n))
    return np.cos(theta), E_star / (A * nodes) * (T * n) @ T.T


def normal(contact, P, x):
    """``(a, centre, p)``: half-width [m], middle [m] and pressure [Pa] at `x` of `contact`'s profile under `P`."""
    profile = contact.profile
    a, centre = (float(v) for v in profile.half_width(P, contact.E_star))
    t = (x - centre) / a
    p = np.zeros_like(x)
    inside = np.abs(t) < 1
    p[inside] = profile.pressure(t[inside], a, centre, P, contact.E_star)
    return a, centre, p


def increment(G, g_trial, limit, direction, tolerance):
    """Iterate the slip set until the friction conditions hold; returns ``ds``, ``g``, the slip directions.

    Points of zero `limit` (out of contact) always move, in either direction.
    """
    free = limit <= 0
    direction = np.where(free, 0.0, direction)
    for _ in range(ITERATIONS):
        moving = np.flatnonzero(free | (direction != 0))
        if moving.size == direction.size:
            raise GrossSlip("dense method 4: every point slips")
        ds = np.zeros_like(g_trial)
        if moving.size:
            rhs = g_trial[moving] - direction[moving] * limit[moving]
            ds[moving] = np.linalg.solve(G[np.ix_(moving, moving)], rhs)
        g = g_trial - G @ ds
        backwards = (direction != 0) & (direction * ds < 0)
        released = ~free & (direction == 0) & (np.abs(g) - limit > tolerance)
        if not backwards.any() and not released.any():
            return ds, g, direction
        direction[backwards] = 0
        direction[released] = np.sign(g[released])
    raise GrossSlip(f"dense method 4: the slip set did not settle in {ITERATIONS} iterations")


def entry_loads(contact, x):
    """The load [N/m] at which each point `x` [m from the centre] enters the contact of a symmetric profile
    whose half-width grows with ``P`` (``P(a)``, the profile's ``load``; zero inside the contact of no load);
    ``-inf`` at every point of any other profile (its parts are not cut, `part_ends`)."""
    if not contact.profile.grows_with_load():
        return np.full(x.size, -np.inf)
    return contact.profile.load(np.abs(x), contact.E_star)


def part_ends(P_from, P_to, largest, entries):
    """``(fraction, load)`` at the end of each part of a step from `P_from` to `P_to` [N/m]: equal parts that
    change ``P`` by at most `largest` [N/m], cut also at the `entries` crossed (`entry_loads`), so that a
    point enters or leaves the contact only at the end of a part, free up to it and stuck from it with
    its relative displacement then (Jaeger 1998: a band that enters under ``|dQ -/+ (pi a / 4) dsigma|
    <= f dP`` sticks). The load of a cut is the entry itself, at which the point is still out of contact."""
    count = max(1, math.ceil(abs(P_to - P_from) / largest))
    fractions = np.arange(1, count + 1) / count
    if P_to == P_from:
        return [(float(w), P_to) for w in fractions]
    loads = np.concatenate([P_from + fractions[:-1] * (P_to - P_from), [P_to]])
    crossed = entries[(entries > min(P_from, P_to)) & (entries < max(P_from, P_to))]
    loads = np.unique(np.concatenate([loads, crossed]))[:: 1 if P_to > P_from else -1]
    return [(float((load - P_from) / (P_to - P_from)), float(load)) for load in loads]


def simulate(contact, history, nodes, load_part=LOAD_PART):
    """Method 4 on `nodes` Chebyshev-Gauss points over the history's largest contact: a `Run`.

    Parameters
    ----------
    contact : fretting.Contact
        Profile, ``E_star``, ``f``; its ``P`` where the history gives none.
    history : fretting.History
        ``Q`` [N/m], ``sigma`` [Pa] and optionally ``P`` [N/m] at every step; starting from zero
        ``Q`` and ``sigma`` where ``P`` varies.
    nodes : int
    load_part : float
        Largest change of ``P`` in one part of a step, a fraction of ``contact.P``.
    """
    P = np.full(len(history), contact.P) if history.P is None else np.asarray(history.P, float)
    normals = {load: normal(contact, load, np.zeros(0))[:2] for load in np.unique(P)}
    centre = normals[P[0]][1]
    A = max(abs(c - centre) + a for a, c in normals.values())
    t, G = stiffness(contact.E_star, A, nodes)
    x, root, weight = centre + A * t, np.sqrt(1 - t**2), A * np.pi / nodes
    entries = entry_loads(contact, x - centre)
    limit_at = lambda load: contact.f * normal(contact, load, x)[2] * root * (entries < load)  # noqa: E731
    stuck = lambda Q, sigma: (Q / np.pi + sigma * A * t / 4) / A  # noqa: E731
    steps = len(history)
    q, slips, p, stick = (np.zeros((steps, nodes)) for _ in range(4))
    dissipation = np.zeros(steps)
    limit = limit_at(P[0])
    if np.any(limit <= 0) and (history.Q[0] or history.sigma[0]):
        raise ValueError("dense method 4: a history whose P varies must start from Q = sigma = 0")
    q[0], p[0], stick[0] = stuck(history.Q[0], history.sigma[0]) / root, limit / (contact.f * root), 1
    slip, direction = np.zeros(nodes), np.zeros(nodes)
    tolerance = ROUNDING * limit.max()
    for k in range(1, steps):
        moved = np.zeros(nodes)
        for w, load in part_ends(P[k - 1], P[k], load_part * contact.P, entries):
            Q, sigma = ((1 - w) * v[k - 1] + w * v[k] for v in (history.Q, history.sigma))
            end = limit if P[k] == P[k - 1] else limit_at(load)
            g_trial = stuck(Q, sigma) - G @ slip
            ds, g, direction = increment(G, g_trial, end, direction, tolerance)
            dissipation[k] += weight * np.abs(ds) @ ((limit + end) / 2)
            slip, limit, moved = slip + ds, end, moved + np.abs(ds) * (end > 0)
        q[k], slips[k], p[k], stick[k] = g / root, slip, limit / (contact.f * root), moved == 0
    a, centres = np.array([normals[load] for load in P]).T
    return Run(x, q, slips, p, stick.astype(bool), dissipation, a, centres, contact.f, contact.p0)
