"""Method 4 of the seed paper, discretised: the slip field and the increment that updates it.

The slip ``s`` is interpolated by a polynomial of degree ``N - 1`` through its values at the
Gauss-Chebyshev points ``t_k = cos((2k - 1) pi / (2N))`` of ``x = centre + a t``. Writing
``s = a sum_n c_n T_n(t)``, the dislocation traction of eq (A.4) is diagonal in this basis
(docs/theory/method4.md#chebyshev), ``sqrt(1 - t^2) q_d = -(E_star / 2) sum_n n c_n T_n(t)``, and at the
nodes, by the discrete orthogonality of ``T_n``,

    sqrt(1 - t_j^2) q_d(t_j) = -sum_k G_jk s_k,   G = (E_star / (a N)) sum_n n T_n(t_j) T_n(t_k),

a symmetric positive semi-definite matrix whose null space is the rigid shift. The fully
stuck traction (eqs 9, 20) is ``sqrt(1 - t^2) q_st = (Q / pi + sigma a t / 4) / a``.

One increment is the convex problem of docs/theory/method4.md#increment restricted to the nodes,

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

The releases of one increment grow the slip zones a few nodes at a time, one solve after
another, so the Cholesky factor of the slipping nodes' block of ``G`` is kept through an
increment and bordered by the nodes released (`_Factor`); a working set that loses nodes is
factored anew. Each increment starts a new factor, so what it computes depends on its loads
and starting state alone, and a repeating state repeats bit for bit. The stuck nodes' traction
``G held`` is multiplied anew at every solve, not updated by the rows of the nodes that join or
leave the stuck ones: an update's rounding would depend on the working sets before, and a
periodic state would no longer repeat bit for bit (tests/test_hard_cases.py,
`test_periodic_state_does_not_drift_over_1e5_cycles`).
"""

from dataclasses import dataclass

import numpy as np
from scipy import linalg

from fretting.errors import GrossSlipError, SolverError

__all__ = ["ChebyshevGrid", "Increment", "chebyshev_angles", "solve_increment"]

#: Rounding allowance on the friction limit, relative to the largest term of the traction: the
#: Cholesky solves leave nodes at the limit over it by rounding of that term (measured on the
#: hard states of tests/test_hard_cases.py); 1e-11 keeps a wide margin over that rounding.
ROUNDING = 1e-11


@dataclass(frozen=True, eq=False)
class ChebyshevGrid:
    """Gauss-Chebyshev nodes and the dimensionless slip-to-traction matrix of `N` nodes (validated by
    `fretting.models.Grid`)."""

    N: int

    def __post_init__(self):
        theta = chebyshev_angles(self.N)[::-1]  # ascending t
        T = np.cos(np.multiply.outer(theta, np.arange(self.N)))
        object.__setattr__(self, "t", np.cos(theta))
        object.__setattr__(self, "stiffness", (T * np.arange(self.N)) @ T.T / self.N)

    @property
    def weight(self):
        """Gauss-Chebyshev weight ``pi / N`` of ``int_{-1}^{1} F(t) / sqrt(1 - t^2) dt``."""
        return np.pi / self.N


def chebyshev_angles(N):
    """``theta_k = (2k - 1) pi / (2N)``, k = 1..N [rad]: ``cos(theta_k)`` are the `N` Gauss-Chebyshev
    points of the first kind (the unbounded rule), descending."""
    return (2 * np.arange(1, N + 1) - 1) * np.pi / (2 * N)


@dataclass(frozen=True, eq=False)
class Increment:
    """Solution of one increment: new slip [m], its increment ``ds`` [m] and the traction ``g`` [Pa] at the nodes."""

    slip: np.ndarray
    ds: np.ndarray
    g: np.ndarray
    iterations: int


def solve_increment(G, g_stuck, limit, slip=None, guess=None, G_abs=None):
    """Slip increment that restores the friction conditions at every node.

    Parameters
    ----------
    G : ndarray, shape (N, N)
        Slip-to-traction matrix [Pa/m], ``g = g_stuck - G slip``.
    g_stuck : ndarray, shape (N,)
        ``sqrt(1 - t^2) q_st`` [Pa], the fully stuck traction at the new loads.
    limit : ndarray, shape (N,)
        ``f p sqrt(1 - t^2)`` [Pa], positive.
    slip : ndarray, shape (N,), optional
        Slip [m] before the increment (default zero).
    guess : ndarray of int, shape (N,), optional
        Slip directions (+1, -1; 0: stuck) to try first, e.g. those of the increment before.
        A start only: the answer does not depend on it (the last working set fixes it), the
        number of linear solves does.
    G_abs : ndarray, shape (N, N), optional
        ``|G|``, elementwise, for the rounding allowance; given by a caller that solves many
        increments with one `G`, since forming it costs as much as a product with ``G``.

    Returns
    -------
    Increment
        ``ds = 0`` exactly at the nodes that stick. The new slip of the slipping nodes is solved
        for from the loads and the slip of the stuck nodes alone, never as old slip plus an
        increment, so a state that repeats a cycle later repeats bit for bit (the periodic
        shortcut of `fretting.engine.simulation` relies on it).
    """
    slip = np.zeros_like(g_stuck) if slip is None else slip
    new = slip
    factor = _Factor(G)
    direction = np.zeros(g_stuck.size, dtype=np.int8)  # +1, -1: slipping; 0: stuck
    locked = G @ slip
    g = g_stuck - locked
    # g is a difference of terms that may be far larger than the limit (locked-in slip under
    # large sigma): its rounding at each node scales with the largest of them there, and only
    # there (a node at the edge, where the limit is small, slips under loads of its own size).
    G_abs = np.abs(G) if G_abs is None else G_abs
    tolerance = ROUNDING * (limit + np.abs(g_stuck) + G_abs @ np.abs(slip))
    over = np.abs(g) - limit > tolerance
    if not over.any():  # Coulomb's law holds without slip: nothing moves, not even by rounding
        return Increment(slip, np.zeros_like(slip), g, 0)
    if guess is not None:  # and the nodes whose traction exceeds the limit already
        direction[:] = np.where(over, np.sign(g), guess)
        if direction.all():
            direction[:] = 0
        new = _minimise(factor, g_stuck, limit, slip, new, direction)
        g = g_stuck - G @ new
    single = False
    for iteration in range(1, 4 * g_stuck.size + 2):
        excess = np.abs(g) - limit
        released = np.flatnonzero((direction == 0) & (excess > tolerance))
        if released.size == 0:
            return Increment(new, new - slip, g, iteration - 1)
        if single or released.size == np.count_nonzero(direction == 0):
            released = released[[np.argmax(excess[released])]]
        direction[released] = np.sign(g[released])
        new = _minimise(factor, g_stuck, limit, slip, new, direction)
        single = not direction[released].all()  # a node just released stuck again on the way
        g = g_stuck - G @ new
    raise SolverError("the active set did not settle: the increment has no solution on this grid")


def _minimise(factor, g_stuck, limit, slip, new, direction):
    """Minimise ``J`` from the slip `new` with stuck nodes and slip directions fixed where they hold.

    Steps toward the quadratic's minimiser on the slipping nodes; a node whose slip increment
    would change sign on the way stops at its old slip and joins the stuck nodes (`direction`
    is updated in place: no node starts slipping here). Returns the new slip.
    """
    G = factor.G
    while True:
        if direction.all():
            new = _rigid_shift(g_stuck, limit, slip, new, direction)
            continue
        slipping = np.flatnonzero(direction)
        if slipping.size == 0:
            return slip
        held = np.where(direction == 0, slip, 0.0)  # the stuck nodes' slip, which stays
        rhs = (g_stuck - G @ held - direction * limit)[slipping]
        target = slip.copy()
        target[slipping] = factor.solve(slipping, rhs)
        ds, target_ds = new - slip, target - slip
        wrong = slipping[direction[slipping] * target_ds[slipping] < 0]
        if wrong.size == 0:
            return target
        fractions = ds[wrong] / (ds[wrong] - target_ds[wrong])
        alpha = fractions.min()
        new = slip + (ds + alpha * (target_ds - ds))
        stops = wrong[fractions <= alpha]
        new[stops] = slip[stops]
        direction[stops] = 0


def _rigid_shift(g_stuck, limit, slip, new, direction):
    """With every node slipping, move the slip `new` rigidly downhill until a node stops.

    ``G 1 = 0``, so along the rigid shift ``ds -> ds + alpha 1`` the quadratic has no curvature
    and ``J`` falls at the rate ``|sum_k (g_stuck_k - direction_k limit_k)|`` (``sum_k g_k`` is
    the same for every slip). The nodes slipping against the shift stop one after the other;
    the first whose increment reaches zero sticks (`direction` is updated in place). None
    slipping against it: ``J`` is unbounded, the contact slides (`GrossSlipError`: the loads are
    within rounding of the friction force, though below it).
    """
    shift = np.sign(np.sum(g_stuck) - np.sum(direction * limit))
    against = np.flatnonzero(direction == -shift)
    if shift == 0 or against.size == 0:  # |Q| is within rounding of the friction force: the contact slides
        raise GrossSlipError(None, float(np.sum(g_stuck)), 0.0, float(np.sum(limit)))
    ds = new - slip
    alpha = np.abs(ds[against]).min()
    stops = against[np.abs(ds[against]) <= alpha]
    new = new + alpha * shift
    new[stops] = slip[stops]
    direction[stops] = 0
    return new


class _Factor:
    """Cholesky factor ``L L^T = G[order][:, order]`` on a set of nodes that grows by bordering.

    Adding ``k`` nodes to ``n`` costs ``n^2 k`` (a triangular solve) instead of the ``(n + k)^3 / 3``
    of a new factorisation; it is the same Cholesky factorisation, of the nodes in the order
    they came. ``L`` is kept as the rows each bordering added, ``[X, L_new]``, so that bordering
    copies nothing already factored.
    """

    def __init__(self, G):
        self.G = G
        self.order = np.zeros(0, dtype=np.int64)
        self.factored = np.zeros(G.shape[0], dtype=bool)  # the nodes of `order`
        self.blocks = []  # (X, L_new) of each bordering, in order

    def solve(self, slipping, rhs):
        """``G[slipping][:, slipping]^-1 rhs`` for ascending node numbers `slipping`."""
        if np.count_nonzero(self.factored[slipping]) < self.order.size:  # nodes left the set: factor anew
            self.order, self.blocks = self.order[:0], []
            self.factored[:] = False
        new = slipping[~self.factored[slipping]]
        if new.size:
            self._border(new)
        position = np.searchsorted(slipping, self.order)  # rows of `rhs` in factor order
        solution = np.empty_like(rhs)
        solution[position] = self._back(self._forward(rhs[position]))
        return solution

    def _forward(self, b):
        """``L^-1 b``, block row by block row (`b`: a vector or the columns of a matrix)."""
        y, start = np.empty_like(b), 0
        for X, L in self.blocks:
            end = start + L.shape[0]
            y[start:end] = _triangular(L, b[start:end] - X @ y[:start], transposed=False)
            start = end
        return y

    def _back(self, y):
        """``L^-T y``, block row by block row from the last."""
        x, end = y.copy(), y.shape[0]
        for X, L in reversed(self.blocks):
            start = end - L.shape[0]
            x[start:end] = _triangular(L, x[start:end], transposed=True)
            x[:start] -= X.T @ x[start:end]
            end = start
        return x

    def _border(self, new):
        """Extend the factor by the nodes `new`: ``[[L, 0], [X, L_new]]`` with ``L X^T = G[order][:, new]``.

        Rows are gathered whole and then columns (``G[rows][:, columns]``), which numpy does
        faster than one ``np.ix_`` gather (benchmarks/adaptation_passes.py times both);
        ``G`` is symmetric.
        """
        rows = self.G[new]
        X = self._forward(rows[:, self.order].T).T
        L_new, info = linalg.lapack.dpotrf(rows[:, new] - X @ X.T, lower=1, clean=1, overwrite_a=1)
        if info != 0:
            raise SolverError(f"the slipping nodes' block of G is not positive definite (info {info})")
        self.blocks.append((X, L_new))
        self.order = np.concatenate([self.order, new])
        self.factored[new] = True


def _triangular(L, b, transposed):
    """``L^-1 b``, or ``L^-T b`` if `transposed`, for a lower triangular `L` (LAPACK ``trtrs``)."""
    x, info = linalg.lapack.dtrtrs(L, b, lower=1, trans=int(transposed))
    if info != 0:
        raise SolverError(f"a diagonal block of the Cholesky factor is singular (info {info})")
    return x
