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
and starting state alone, and a repeating state repeats bit for bit. The products with ``G``
take only the rows a step needs (the slipping nodes' for a solve, the stuck nodes' for the
releases). The stuck nodes' traction ``G held`` is multiplied anew at every solve, not updated
by the rows of the nodes that join or leave the stuck ones: an update's rounding would depend on
the working sets before, and a periodic state would no longer repeat bit for bit (tests/test_hard_cases.py,
`test_periodic_state_does_not_drift_over_1e5_cycles`).
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy import linalg

from fretting.errors import GrossSlipError, SolverError

__all__ = ["ChebyshevGrid", "Increment", "Stiffness", "chebyshev_angles", "held_by_allowance", "solve_increment"]

#: Rounding allowance on the friction limit, relative to the largest term of the traction: the
#: solves leave slipping nodes off the limit by a few units of rounding of that term, at least ten
#: times less than this on an out-of-phase path near sliding (tests/models/test_solver.py). A load cycle
#: on a large locked-in slip whose traction changes by less dissipates nothing, so the allowance
#: is held no larger than that margin asks (benchmarks/small_loops.py).
ROUNDING = 2e-14


#: Runs of consecutive nodes past which a product with some rows or columns of a matrix gathers
#: them instead of multiplying each run as a view (`_runs`): stick and slip zones make a few runs;
#: many short ones cost a product each.
MAX_RUNS = 16

#: A kept `Stiffness` solves the slipping block through the stuck nodes where they are fewer than
#: this fraction of the slipping ones: ``|K|^3 / 3`` and a few ``N^2`` products against the
#: ``|S|^3 / 3`` of a Cholesky factor of the slipping block.
COMPLEMENT = 0.25

#: Rounds of iterative refinement of a solve through the stuck nodes, against ``G_SS`` itself: the
#: inverse ``B`` carries rounding of the size of its condition number, and one round brings the
#: residual to that of a Cholesky factor of ``G_SS`` (tests/models/test_solver.py).
REFINEMENT_ROUNDS = 1


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


class Stiffness:
    """The slip-to-traction matrix ``G`` [Pa/m] and what the solver derives from it once.

    ``G`` is symmetric positive semi-definite with the rigid shift as its null space
    (``G 1 = 0``), so ``A = G + c 1 1^T`` is positive definite (``c N``, the mean of ``diag G``, lies
    inside its spectrum). Where few nodes stick, the slipping nodes' block ``G_SS`` is solved
    through the stuck ones ``K`` (`solve_slipping`): by the inverse of a partitioned matrix,
    ``A_SS^-1 = B_SS - B_SK B_KK^-1 B_KS`` with ``B = A^-1``, and ``G_SS = A_SS - c 1 1^T`` by
    Sherman-Morrison; each solve then costs ``|K|^3 / 3`` and products of order ``N^2``. ``B`` is
    formed once, when first needed, by a stiffness that is `kept` across increments (a model's),
    where its ``N^3`` pays.
    """

    def __init__(self, G, kept=True):
        self.G, self.kept = G, kept

    @cached_property
    def G_abs(self):
        """``|G|``, elementwise, for the rounding allowance of a `kept` stiffness (`abs_rows_times`)."""
        return np.abs(self.G)

    def abs_rows_times(self, rows, v):
        """``|G|[rows] @ v`` for ascending `rows`: from `G_abs`, formed once, where the stiffness is `kept`;
        else of the rows asked for alone, which an unkept stiffness's few solves need (the same numbers)."""
        if self.kept:
            return _rows_times(self.G_abs, rows, v)
        return _rows_times(self.G, rows, v, np.abs)

    @cached_property
    def regularised_inverse(self):
        """``(c, B)``: ``B = (G + c 1 1^T)^-1`` [m/Pa], ``c`` [Pa/m]."""
        c = np.trace(self.G) / self.G.shape[0] ** 2
        L, info = linalg.lapack.dpotrf(self.G + c, lower=1, clean=1)
        if info == 0:
            B, info = linalg.lapack.dpotri(L, lower=1)
        if info != 0:
            raise SolverError(f"G + c 1 1^T is not positive definite (info {info})")
        return c, np.tril(B) + np.tril(B, -1).T

    def by_complement(self, slipping):
        """True if the block of the nodes `slipping` is solved through the stuck ones (`COMPLEMENT`)."""
        return self.kept and self.G.shape[0] - slipping.size < COMPLEMENT * slipping.size

    def solve_slipping(self, slipping, rhs):
        """``G_SS^-1 rhs`` for the ascending nodes `slipping` ``S`` (at least one node sticks), through
        the stuck nodes, refined `REFINEMENT_ROUNDS` times against ``G_SS``."""
        c, B = self.regularised_inverse
        is_stuck = np.ones(self.G.shape[0], dtype=bool)
        is_stuck[slipping] = False
        stuck = np.flatnonzero(is_stuck)
        factor = linalg.cho_factor(B[np.ix_(stuck, stuck)], lower=True)

        def A_SS_inverse(v):  # B_SS v - B_SK B_KK^-1 B_KS v
            u = _columns_times(B, slipping, v)
            return (u - _columns_times(B, stuck, linalg.cho_solve(factor, u[stuck])))[slipping]

        y, shift = A_SS_inverse(np.column_stack([rhs, np.ones(slipping.size)])).T  # one pass over B for both

        def G_SS_inverse(y):  # Sherman-Morrison, from y = A_SS^-1 v
            return y + shift * (c * y.sum() / (1.0 - c * shift.sum()))

        x = G_SS_inverse(y)
        for _ in range(REFINEMENT_ROUNDS):
            full = np.zeros(self.G.shape[0])
            full[slipping] = x
            x = x + G_SS_inverse(A_SS_inverse(rhs - _rows_times(self.G, slipping, full)))
        return x


@dataclass(frozen=True, eq=False)
class Increment:
    """Solution of one increment: new slip [m], its increment ``ds`` [m] and the traction ``g`` [Pa] at the nodes;
    ``product``, ``G slip`` [Pa] of the new slip (``g = g_stuck - product``), for a next solve on the same ``G``
    (None: not formed)."""

    slip: np.ndarray
    ds: np.ndarray
    g: np.ndarray
    iterations: int
    product: np.ndarray | None = None


def solve_increment(G, g_stuck, limit, slip=None, guess=None, product=None):
    """Slip increment that restores the friction conditions at every node.

    Parameters
    ----------
    G : ndarray, shape (N, N), or Stiffness
        Slip-to-traction matrix [Pa/m], ``g = g_stuck - G slip``; a `Stiffness` kept by a caller
        that solves many increments with one ``G`` keeps what is derived from it once.
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
    product : ndarray, shape (N,), optional
        ``G slip`` [Pa], where the caller has it (`Increment.product` of a solve on the same ``G`` that
        ended at `slip`): spares the product with the whole of ``G``.

    Returns
    -------
    Increment
        ``ds = 0`` exactly at the nodes that stick. The new slip of the slipping nodes is solved
        for from the loads and the slip of the stuck nodes alone, never as old slip plus an
        increment, so a state that repeats a cycle later repeats bit for bit (the periodic
        shortcut of `fretting.engine.simulation` relies on it).
    """
    stiffness = G if isinstance(G, Stiffness) else Stiffness(G, kept=False)
    G = stiffness.G
    slip = np.zeros_like(g_stuck) if slip is None else slip
    new = slip
    factor = _Factor(stiffness)
    direction = np.zeros(g_stuck.size, dtype=np.int8)  # +1, -1: slipping; 0: stuck
    product = G @ slip if product is None else product.copy()  # its rows follow the slip below: the caller's stays
    g = g_stuck - product
    over = _over(stiffness, np.arange(g.size), g, g_stuck, limit, slip)
    if over.size == 0:  # Coulomb's law holds without slip: nothing moves, not even by rounding
        return Increment(slip, np.zeros_like(slip), g, 0, product)
    if guess is not None:  # and the nodes whose traction exceeds the limit already
        direction[:] = guess
        direction[over] = np.sign(g[over])
        if direction.all():
            direction[:] = 0
        new = _minimise(factor, g_stuck, limit, slip, new, direction)
        product = G @ new
        g = g_stuck - product
    single, iteration = False, 0
    while (released := _over(stiffness, np.flatnonzero(direction == 0), g, g_stuck, limit, new)).size:
        iteration += 1
        if iteration > 4 * g_stuck.size:
            raise SolverError("the active set did not settle: the increment has no solution on this grid")
        if single or released.size == np.count_nonzero(direction == 0):
            released = released[[np.argmax(np.abs(g[released]) - limit[released])]]
        direction[released] = np.sign(g[released])
        before, new = new, _minimise(factor, g_stuck, limit, slip, new, direction)
        single = not direction[released].all()  # a node just released stuck again on the way
        if not direction[released].any() and np.array_equal(new, before):
            # All stuck again where they were: J could not fall, and the same release would
            # follow. Their excess is rounding of the equilibrium they close (the stuck nodes'
            # traction takes the sum of the slipping ones' residuals, near sliding).
            break
        _rows_of(G, np.flatnonzero(direction == 0), new, g_stuck, product, g)
    _rows_of(G, np.flatnonzero(direction), new, g_stuck, product, g)
    return Increment(new, new - slip, g, iteration, product)


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
        rhs = _rows_product(G, slipping, held, g_stuck) - direction[slipping] * limit[slipping]
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


def _over(stiffness, nodes, g, g_stuck, limit, slip):
    """The nodes of `nodes` (ascending) whose traction ``g = g_stuck - G slip`` exceeds the limit by
    more than its rounding.

    ``g`` is a difference of terms that may be far larger than the limit (locked-in slip under
    large sigma, or the slip of an increment close to sliding): its rounding at each node scales
    with the largest of them there, ``|g_stuck| + |G| |slip|`` for the slip it was computed from,
    and only there (a node at the edge, where the limit is small, slips under loads of its own
    size).
    """
    candidates = nodes[np.abs(g[nodes]) > limit[nodes]]
    scale = limit[candidates] + np.abs(g_stuck[candidates]) + stiffness.abs_rows_times(candidates, np.abs(slip))
    return candidates[np.abs(g[candidates]) - limit[candidates] > ROUNDING * scale]


def held_by_allowance(g, limit, push):
    """The nodes an increment that slipped nowhere left over the friction limit by its load change.

    `g` [as `limit`] is the traction after the increment, `push` the change of the fully stuck
    traction it made (``g_stuck`` after less before). A node over its limit after an increment that
    slipped nowhere is within the rounding allowance (`ROUNDING`); it is over by the load change,
    not by the rounding of its traction, where the change moved it toward its limit by more than it
    was over before: what the change would have dissipated there is lost to the allowance
    (benchmarks/small_loops.py).
    """
    excess = np.abs(g) - limit
    toward = push * np.sign(g)
    return np.flatnonzero((excess > 0) & (toward > excess - toward))


def _rows_product(G, rows, v, g_stuck):
    """``(g_stuck - G v)[rows]`` for ascending node numbers `rows`: only the rows asked for are
    multiplied, those of the stuck nodes for the releases, those of the slipping ones for a solve."""
    return g_stuck[rows] - _rows_times(G, rows, v)


def _rows_of(G, rows, new, g_stuck, product, g):
    """Write ``(G new)[rows]`` into `product` and the traction ``(g_stuck - G new)[rows]`` into `g`, for ascending
    node numbers `rows` (as `_rows_product`)."""
    product[rows] = _rows_times(G, rows, new)
    g[rows] = g_stuck[rows] - product[rows]


def _rows_times(M, rows, v, of=None):
    """``M[rows] @ v`` for ascending `rows`, each run of consecutive rows a view of `M` (`_runs`); with `of`,
    an elementwise function, ``of(M[rows]) @ v``."""
    runs = _runs(rows)
    blocks = [M[rows]] if runs is None else [M[start:end] for start, end, _ in runs]
    products = [(block if of is None else of(block)) @ v for block in blocks]
    return products[0] if runs is None else np.concatenate(products)


def _columns_times(M, columns, v):
    """``M[:, columns] @ v`` for a symmetric `M` and ascending `columns`: ``M[run].T @ v[run]`` summed
    over the runs of consecutive columns (`_runs`), rows of a C-ordered `M` being contiguous."""
    runs = _runs(columns)
    if runs is None:
        return M[columns].T @ v
    total = 0.0
    for start, end, offset in runs:
        total = total + M[start:end].T @ v[offset : offset + end - start]
    return total


def _runs(nodes):
    """``(start, end, offset)`` of each run ``nodes[offset:offset + end - start] == range(start, end)``
    of the ascending `nodes`; None where they are empty or more than `MAX_RUNS`."""
    breaks = np.flatnonzero(np.diff(nodes) != 1) + 1
    if nodes.size == 0 or breaks.size >= MAX_RUNS:
        return None
    offsets, ends = [0, *breaks.tolist()], [*breaks.tolist(), nodes.size]
    return [(nodes[o], nodes[e - 1] + 1, o) for o, e in zip(offsets, ends, strict=True)]


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

    def __init__(self, stiffness):
        self.stiffness, self.G = stiffness, stiffness.G
        self.order = np.zeros(0, dtype=np.int64)
        self.factored = np.zeros(self.G.shape[0], dtype=bool)  # the nodes of `order`
        self.blocks = []  # (X, L_new) of each bordering, in order

    def solve(self, slipping, rhs):
        """``G[slipping][:, slipping]^-1 rhs`` for ascending node numbers `slipping`; through the stuck
        nodes where they are few (`Stiffness.by_complement`)."""
        if self.stiffness.by_complement(slipping):
            return self.stiffness.solve_slipping(slipping, rhs)
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
