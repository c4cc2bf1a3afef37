"""Method 4 of the seed paper, discretised: the slip field and the increment that updates it.

The slip ``s`` is interpolated by a polynomial of degree ``N - 1`` through its values at the
Gauss-Chebyshev points ``t_k = cos((2k - 1) pi / (2N))`` of ``x = centre + a t``. Writing
``s = a sum_n c_n T_n(t)``, the dislocation traction of eq (A.4) is diagonal in this basis
(formulation.md section 4), ``sqrt(1 - t^2) q_d = -(E_star / 2) sum_n n c_n T_n(t)``, and at the
nodes, by the discrete orthogonality of ``T_n``,

    sqrt(1 - t_j^2) q_d(t_j) = -sum_k G_jk s_k,   G = (E_star / (a N)) sum_n n T_n(t_j) T_n(t_k),

a symmetric positive semi-definite matrix whose null space is the rigid shift. The fully
stuck traction (eqs 9, 20) is ``sqrt(1 - t^2) q_st = (Q / pi + sigma a t / 4) / a``.

One increment is the convex problem of formulation.md section 3 restricted to the nodes,

    min_ds  J(ds) = 1/2 ds^T G ds - g_trial^T ds + sum_k limit_k |ds_k|,

with ``g_trial`` the traction (times ``sqrt(1 - t^2)``) if nothing slipped and
``limit = f p sqrt(1 - t^2)``. Its minimiser satisfies the friction conditions exactly at the
nodes: ``|g| <= limit``, ``ds = 0`` where the inequality is strict and
``g = limit sign(ds)`` where ``ds != 0``, with ``g = g_trial - G ds``. It is found by a primal
active-set method: on a working set of stuck nodes and fixed slip directions ``J`` is a
quadratic, minimised by one linear solve; a node that would reverse its slip direction
blocks the step and sticks; at a minimiser every stuck node whose traction exceeds the limit
is released in the direction of its traction. ``J`` falls at every step, so no working set
repeats and the method ends, exactly, in finitely many steps.
"""

from dataclasses import dataclass

import numpy as np
from scipy import linalg

from fretting.errors import SolverError

__all__ = ["Grid", "Increment", "solve_increment"]

#: Rounding allowance on the friction limit, relative to its largest value.
ROUNDING = 1e-13


@dataclass(frozen=True, eq=False)
class Grid:
    """Gauss-Chebyshev nodes and the dimensionless slip-to-traction matrix of `N` nodes."""

    N: int

    def __post_init__(self):
        if not isinstance(self.N, (int, np.integer)) or self.N < 4:
            raise ValueError(f"nodes must be an integer >= 4, found {self.N!r}")
        theta = (2 * np.arange(self.N, 0, -1) - 1) * np.pi / (2 * self.N)  # ascending t
        T = np.cos(np.multiply.outer(theta, np.arange(self.N)))
        object.__setattr__(self, "t", np.cos(theta))
        object.__setattr__(self, "stiffness", (T * np.arange(self.N)) @ T.T / self.N)

    @property
    def weight(self):
        """Gauss-Chebyshev weight ``pi / N`` of ``int_{-1}^{1} F(t) / sqrt(1 - t^2) dt``."""
        return np.pi / self.N


@dataclass(frozen=True, eq=False)
class Increment:
    """Solution of one increment: slip increment ``ds`` [m] and traction ``g`` [Pa] at the nodes."""

    ds: np.ndarray
    g: np.ndarray
    iterations: int


def solve_increment(G, g_trial, limit):
    """Slip increment that restores the friction conditions at every node.

    Parameters
    ----------
    G : ndarray, shape (N, N)
        Slip-to-traction matrix [Pa/m], ``g = g_trial - G ds``.
    g_trial : ndarray, shape (N,)
        ``sqrt(1 - t^2) q`` [Pa] if no node slipped during the increment.
    limit : ndarray, shape (N,)
        ``f p sqrt(1 - t^2)`` [Pa], positive.

    Returns
    -------
    Increment
        ``ds = 0`` exactly at the nodes that stick.
    """
    tolerance = ROUNDING * limit.max()
    ds = np.zeros_like(g_trial)
    direction = np.zeros(g_trial.size, dtype=np.int8)  # +1, -1: slipping; 0: stuck
    g = g_trial
    single = False
    for iteration in range(1, 4 * g_trial.size + 2):
        excess = np.abs(g) - limit
        released = np.flatnonzero((direction == 0) & (excess > tolerance))
        if released.size == 0:
            return Increment(ds, g, iteration - 1)
        if single or released.size == np.count_nonzero(direction == 0):
            released = released[[np.argmax(excess[released])]]
        direction[released] = np.sign(g[released])
        ds, blocked = _minimise(G, g_trial, limit, ds, direction)
        single = bool(np.intersect1d(blocked, released).size)
        g = g_trial - G @ ds
    raise SolverError("the active set did not settle: the increment has no solution on this grid")


def _minimise(G, g_trial, limit, ds, direction):
    """Minimise ``J`` from `ds` with stuck nodes and slip directions fixed where they hold.

    Steps toward the quadratic's minimiser on the slipping nodes; a node whose slip would
    change sign on the way stops at zero and joins the stuck nodes (`direction` is updated in
    place). Returns the new ``ds`` and the nodes that stuck this way.
    """
    blocked = []
    while True:
        slipping = np.flatnonzero(direction)
        if slipping.size == direction.size:
            raise SolverError("every node would slip although |Q| < f P")
        target = np.zeros_like(ds)
        rhs = g_trial[slipping] - direction[slipping] * limit[slipping]
        target[slipping] = linalg.solve(G[np.ix_(slipping, slipping)], rhs, assume_a="pos")
        wrong = slipping[direction[slipping] * target[slipping] < 0]
        if wrong.size == 0:
            return target, np.array(blocked, dtype=int)
        fractions = ds[wrong] / (ds[wrong] - target[wrong])
        alpha = fractions.min()
        ds = ds + alpha * (target - ds)
        stops = wrong[fractions <= alpha]
        ds[stops] = 0.0
        direction[stops] = 0
        blocked.extend(stops)
