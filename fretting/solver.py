"""Method 4 of the seed paper, discretised: the slip field and the increment that updates it.

The slip ``s`` is interpolated by a polynomial of degree ``N - 1`` through its values at the
Gauss-Chebyshev points ``t_k = cos((2k - 1) pi / (2N))`` of ``x = centre + a t``. Writing
``s = a sum_n c_n T_n(t)``, the dislocation traction of eq (A.4) is diagonal in this basis
(formulation.md section 4), ``sqrt(1 - t^2) q_d = -(E_star / 2) sum_n n c_n T_n(t)``, and at the
nodes, by the discrete orthogonality of ``T_n``,

    sqrt(1 - t_j^2) q_d(t_j) = -sum_k G_jk s_k,   G = (E_star / (a N)) sum_n n T_n(t_j) T_n(t_k),

a symmetric positive semi-definite matrix whose null space is the rigid shift. The fully
stuck traction (eqs 9, 20) is ``sqrt(1 - t^2) q_st = (Q / pi + sigma a t / 4) / a``.

One increment is the convex problem of formulation.md section 3 restricted to the nodes:
find the slip increment ``ds`` with ``g = sqrt(1 - t^2) q`` such that ``|g| <= f p sqrt(1 - t^2)``
everywhere, ``ds = 0`` where the inequality is strict and ``g = f p sqrt(1 - t^2) sign(ds)``
where ``ds != 0``. It is solved by a primal-dual active-set (semismooth Newton) iteration,
which stops only when the active set repeats, that is when the conditions hold exactly.
"""

from dataclasses import dataclass

import numpy as np
from scipy import linalg

from fretting.errors import SolverError

__all__ = ["Grid", "Increment", "solve_increment"]

#: Active-set iterations allowed per increment; convergence takes a handful.
MAX_ITERATIONS = 200


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
    direction = _direction(g_trial, np.zeros_like(g_trial), limit, 0.0)
    if not direction.any():
        return Increment(np.zeros_like(g_trial), g_trial, 0)
    scale = float(np.mean(np.diag(G)))  # makes the traction and the slip terms commensurate
    for iteration in range(1, MAX_ITERATIONS + 1):
        slipping = direction != 0
        ds = np.zeros_like(g_trial)
        block = G[np.ix_(slipping, slipping)]
        ds[slipping] = linalg.solve(block, g_trial[slipping] - direction[slipping] * limit[slipping], assume_a="pos")
        g = g_trial - G[:, slipping] @ ds[slipping]
        updated = _direction(g, ds, limit, scale)
        if np.array_equal(updated, direction):
            return Increment(ds, g, iteration)
        direction = updated
    raise SolverError(f"the active set did not settle in {MAX_ITERATIONS} iterations")


def _direction(g, ds, limit, scale):
    """Slip direction (+1, -1, 0 for stick) predicted at each node by ``g + scale ds``.

    At least one node sticks: the traction then carries the load without a rigid shift.
    """
    z = g + scale * ds
    direction = np.where(z > limit, 1, np.where(z < -limit, -1, 0))
    if np.all(direction):
        direction[np.argmin(np.abs(z) - limit)] = 0
    return direction
