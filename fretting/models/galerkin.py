"""Method 4 of the seed paper by P1 Galerkin on a locally refinable mesh in ``theta``.

Positions in the contact are ``x = centre + a cos(theta)``, ``theta`` in ``[0, pi]``. The slip
``s(theta)`` is piecewise linear in ``theta`` on any mesh ``0 = theta_0 < ... < theta_M = pi``,
``s = sum_k s_k phi_k`` with hat functions ``phi_k``; both edge nodes are unknowns.

Elastic energy. With ``s = sum_n s_n cos(n theta)`` the dislocation traction of eq (A.4) does the
work ``int q_d s dx = -(pi E_star / 4) sum_n n s_n^2`` (docs/theory/method4.md#chebyshev), so the elastic
bilinear form is ``B(u, v) = (pi E_star / 4) sum_n n u_n v_n``. Since
``Cl1(theta - phi) - Cl1(theta + phi) = 2 sum_m sin(m theta) sin(m phi) / m`` with the Clausen
function ``Cl1(x) = -ln|2 sin(x/2)| = sum_m cos(m x) / m``,

    B(u, v) = (E_star / (2 pi)) int int u'(theta) v'(phi) [Cl1(theta - phi) - Cl1(theta + phi)] dtheta dphi.

Hats have constant derivatives on each element, so the stiffness ``K_kl = B(phi_k, phi_l)``
needs the mean of ``Cl1(theta -+ phi)`` over each pair of elements. ``F = zeta(3) - Cl3`` has
``F'' = Cl1``, so the integral over a rectangle is a four-corner combination of ``F``; away from
the singularities of ``Cl1`` that combination cancels, and a Taylor series about the
rectangle's centre takes over: a polynomial in ``cot^2`` of half the centre's argument whose
coefficients depend on the two element sizes only, so that both kernels share them. The means
lose accuracy in proportion to the ratio of the two sizes, which the grading of the meshes
bounds (tests/test_galerkin.py::test_pair_means_against_quadrature). Each mean is computed from
its own two elements alone, in operations that do not depend on the other elements, so that the
scene of a refined mesh copies the means of the pairs of elements it shares with the scene
before (`GalerkinModel`'s ``previous``) and its stiffness equals, bit for bit, one assembled
afresh (as a run resumed from a saved state assembles it).

Loads. The fully stuck traction of eqs (9) and (20) does the work
``F_k = int q_st phi_k dx = int (Q / pi + sigma a cos(theta) / 4) phi_k dtheta``, that is
``Q dQ_k + sigma dsig_k``, in closed form; by reciprocity (docs/theory/conventions.md#energy)
``delta_Q = dQ . s`` and ``delta_sigma = dsig . s`` exactly. The friction term
``int f p |ds| dx`` is lumped to ``sum_k L_k |ds_k|``, ``L_k = int f p phi_k dx`` (exact while
``ds`` keeps its sign on each element). An increment is then the problem that
`fretting.models.solver.solve_increment` solves,
``min 1/2 ds^T K ds - g_trial^T ds + sum_k L_k |ds_k|`` with ``g_trial = F(Q', sigma') - K s``,
and its ``g_k = int q phi_k dx`` are hat moments of the traction. `GalerkinModel.traction`
turns them into nodal values keeping Coulomb's law exactly at the nodes.

Mesh. `element_targets` reads the stick and slip zones of an increment and asks for element
sizes; `refine` bisects (old nodes stay nodes, so a P1 slip field carries over exactly) and
grades neighbours to a size ratio of at most 2. A driver (`fretting.engine.adaptation.adapted_model`)
runs the turning points of its history (curved stretches between them cut where the path has
turned by `fretting.engine.adaptation.MAX_TURN`), reduces the targets of every increment with
``np.minimum``, refines, and runs again until `refine` returns the same mesh, starting from
`initial_theta` (pass `GalerkinModel.breakpoints` on: the profile's, where the pressure has a
singular derivative). ``rtol`` is the relative accuracy asked of the energy dissipated in each
increment, with elements of at most ``ENERGY_SPAN rtol a`` in x in its slip zones; its second
stage bisects the elements that hold the recorded steps' stick ends to ``BOUNDARY_SPAN rtol a``,
which bounds the error of the located ends. An increment from one turning point (or cut) to the
next slips where the boundaries of the steps between have swept, so its slip zones get elements
of that size too. Accuracy on closed forms: benchmarks/galerkin_convergence.py;
at every step of general histories: benchmarks/trajectories.py.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar, NamedTuple

import numpy as np
from numpy.polynomial import polynomial
from scipy import special

from fretting._validate import positive
from fretting.models.base import ModelSpec
from fretting.models.method4 import Method4Model, extrapolated_end
from fretting.physics.profiles import Gap

if TYPE_CHECKING:
    from fretting.physics.contact import Contact

__all__ = [
    "DEFAULT_RTOL",
    "GalerkinModel",
    "Mesh",
    "boundaries",
    "boundary_fraction",
    "clausen1",
    "clausen3_complement",
    "element_targets",
    "initial_theta",
    "located_end",
    "refine",
    "stiffness",
    "tightened",
    "uniform_theta",
    "zone_fraction",
]

#: Terms of the zeta series of ``Cl3``: at ``|x| = pi`` term ``k`` is below ``4^-k / k^3``,
#: under 1e-19 of ``F(pi) = 2.10`` at ``k = 26``.
CLAUSEN_TERMS = 26

#: Pairs of elements whose centres lie farther than this many mean element sizes from a
#: singularity of ``Cl1`` use the Taylor series: its terms fall by ``(1/8)^2`` each, and the
#: four-corner formula nearer in loses at most ``~ 9^2`` rounding errors of ``F``.
FAR_PAIRS = 8.0
#: Even Taylor orders ``0, 2, ..., 2 (TAYLOR_TERMS - 1)`` of the far-pair series: the next term
#: is below ``8^-16 / 2000``, i.e. 1e-18.
TAYLOR_TERMS = 8
#: Pairs of elements per block of rows in which the series is summed: its temporaries then
#: stay in the cache.
BLOCK_PAIRS = 2**15

#: Gauss-Legendre points per element for the friction limit: exact for the polynomial part
#: of degree 15, far beyond the smoothness of the pressures on one element.
GAUSS_POINTS = 8
#: Ratio of the geometric pieces toward a point where the pressure has a singular derivative
#: (the ends of a rounded flat): each piece then lies its own length from the singularity,
#: where 8-point Gauss converges like ``5.8^-16``; the friction limits against adaptive quadrature,
#: beside larger ratios: docs/validation/galerkin-constants.md#grading_ratio.
GRADING_RATIO = 0.5
#: Levels of geometric pieces: the innermost ``2^-24`` of an element carries an error
#: ``~ d^2 ln d``, below 1e-13 of it.
GRADING_LEVELS = 24
#: Below this half-width ``w`` [rad] ``(sin w - w cos w) / w`` is summed as its Taylor series,
#: whose terms fall by ``w^2 / 20`` each: 12 terms reach 1e-20 at ``w = 0.5``.
SMALL_HALF_WIDTH = 0.5
_J1_TERMS = 12

#: Relative accuracy asked by default of the energy dissipated in an increment (`element_targets`):
#: the error it leaves on the cycles' energy, docs/validation/galerkin-constants.md#default_rtol; against
#: every closed form, benchmarks/galerkin_convergence.py.
DEFAULT_RTOL = 1e-4
#: Elements of the initial uniform mesh, the coarsest any zone gets. Close to sliding (Q/fP up to
#: 0.999999) half as many give the same slip and, at Q/fP = 0.95, a less accurate traction
#: (docs/validation/galerkin-constants.md#initial_elements).
INITIAL_ELEMENTS = 64
#: Size [rad] of the edge elements of the initial mesh: edge slip zones down to about this
#: width in theta (5e-9 a in x) make the edge node slip, and are then refined.
EDGE_SIZE = 1e-4
#: Smallest element size [rad] that `element_targets` asks for, so that refinement ends even
#: where a zone never resolves.
MIN_SIZE = 1e-7
#: Elements across every stick or slip zone, at least: half as many leave the slip of small zones
#: (Q/fP = 0.05, 0.2) less accurate (docs/validation/galerkin-constants.md#zone_elements).
ZONE_ELEMENTS = 10
#: Relative energy error assumed left inside zones of ``ZONE_ELEMENTS`` elements, which falls like
#: the square of the element size; a bound: the cycles' energy is as accurate with zones held at
#: ``ZONE_ELEMENTS`` elements at the page's smaller rtol (docs/validation/galerkin-constants.md#zone_error).
ZONE_ERROR = 1e-4
#: The worst relative energy error of an increment is about ``BOUNDARY_ERROR (size / w)^(5/2)``
#: with ``size`` the element holding a stick/slip boundary and ``w`` the narrower zone beside
#: it. Fitted with a margin to the worst energy per cycle over amplitudes Q*/fP in [0.05, 0.95];
#: the margin left, beside a quarter of it: docs/validation/galerkin-constants.md#boundary_error.
BOUNDARY_ERROR = 40.0
#: Elements holding a boundary, and those of the slip zones that the boundaries of the steps
#: between two turning points sweep, span at most ``BOUNDARY_SPAN rtol a`` in x: `located_end`
#: places most ends to a tenth of their element, but a slip zone that grows into slip locked in
#: before can leave its end up to about one element off, so the element itself is held to the
#: accuracy asked of the ends, ``1e-3 a`` at the default rtol (benchmarks/trajectories.py).
BOUNDARY_SPAN = 10.0
#: The span, in units of ``rtol a``, of those elements in the mesh adapted to the energy (the
#: first stage of `fretting.engine.adaptation.adapted_model`), and where no step between two
#: turning points is recorded: the energy of the histories of benchmarks/trajectories.py is then
#: within 1e-4, their located ends within about ``ENERGY_SPAN rtol a``.
ENERGY_SPAN = 50.0
#: Elements at a pressure breakpoint span this fraction of ``BOUNDARY_SPAN rtol a``: with a
#: larger span the traction's ``d ln d`` there errs most at the node nearest the end of a rounded
#: flat (tests/test_galerkin.py::test_rounded_flat).
BREAKPOINT_SPAN = 0.5
#: Around a boundary elements grow at most like this fraction of their distance from it, so
#: that the square-root kink of the traction is seen through gently graded elements.
BOUNDARY_GRADING = 0.5
#: Nodes slipping one way beyond a stick/slip boundary that `located_end` needs before it also
#: extrapolates from the second and third: with four, both lie inside the zone, off its far end.
RESOLVED_NODES = 4
#: A zone seen at fewer nodes has an unreliable width: its elements are only bisected.
MIN_ZONE_NODES = 3
#: Bisections asked of an element in one pass at most (a factor 4 in size).
LEVELS_PER_PASS = 2
#: Largest size ratio of neighbouring elements.
GRADING = 2.0
#: Rounding allowance on that ratio: bisected elements are halves up to rounding.
GRADING_SLACK = 1e-9


# --- Clausen functions --------------------------------------------------------------------


def clausen1(x):
    """``Cl1(x) = -ln|2 sin(x/2)| = sum_m cos(m x) / m`` [-], logarithmic at multiples of ``2 pi``."""
    return -np.log(2 * np.abs(np.sin(np.asarray(x, dtype=float) / 2)))


def _clausen_coefficients(terms):
    """``zeta(2k) / (k (2k+1) (2k+2))``, ``k = 1 .. terms``: the series of `clausen3_complement` [-]."""
    k = np.arange(1, terms + 1)
    return special.zeta(2.0 * k) / (k * (2 * k + 1) * (2 * k + 2))


_CLAUSEN_COEFFICIENTS = _clausen_coefficients(CLAUSEN_TERMS)


def clausen3_complement(x):
    """``F(x) = zeta(3) - Cl3(x)`` [-] with ``Cl3(x) = sum_m cos(m x) / m^3``: ``F'' = Cl1``, ``F(0) = 0``.

    For ``|x| <= pi`` (the rest by symmetry and period ``2 pi``), the series of ``Cl2`` about 0
    integrated once more,
    ``F(x) = x^2 (3/2 - ln|x|) / 2 + sum_k zeta(2k) x^(2k+2) / (k (2k+1) (2k+2) (2 pi)^(2k))``,
    accurate to a few units of rounding relative to ``F`` itself, also for tiny ``x``.
    """
    y = np.abs(np.asarray(x, dtype=float)) % (2 * np.pi)
    y = np.where(y > np.pi, 2 * np.pi - y, y)
    square = y * y
    series = polynomial.polyval(square / (2 * np.pi) ** 2, np.concatenate([[0.0], _CLAUSEN_COEFFICIENTS]))
    logarithmic = square * (1.5 - np.log(np.where(y > 0, y, 1.0))) / 2
    return logarithmic + square * series


def _clausen1_even_derivative_polynomials(terms):
    """Coefficients in ``s = cot(x/2)^2`` of ``d^(2j) Cl1 / dx^(2j)``, ``j = 1 .. terms - 1``.

    With ``c = cot(x/2)``, ``Cl1' = -c/2`` and ``dc/dx = -(1 + c^2)/2``, so each derivative is a
    polynomial in ``c``; the even ones are even in ``c``, of degree ``j`` in ``s``.
    """
    derivative = np.array([0.0, -0.5])
    half_one_plus_c2 = np.array([-0.5, 0.0, -0.5])
    even = []
    for order in range(2, 2 * terms - 1):
        derivative = polynomial.polymul(polynomial.polyder(derivative), half_one_plus_c2)
        if order % 2 == 0:
            even.append(derivative[::2])
    return even


def _series_hankel(terms):
    """``D[k, p, q]`` [rad^(-2p-2q)]: the coefficient of ``s^k`` in ``Cl1^(2p+2q)``, ``p + q = 1 .. terms - 1``.

    Zero for ``p + q = 0`` or ``>= terms``; each ``D[k]`` is a Hankel matrix (a function of ``p + q``).
    """
    hankel = np.zeros((terms, terms, terms))
    for j, derivative in enumerate(_clausen1_even_derivative_polynomials(terms), start=1):
        for p in range(j + 1):
            hankel[: j + 1, p, j - p] = derivative
    return hankel


_SERIES_HANKEL = _series_hankel(TAYLOR_TERMS)


def _taylor_factors(h):
    """Factors of the coefficients ``a_k(h_e, h_f) = sum_p x[e, p] y[k, p, f]`` [-] of `_series_means`.

    Over ``t``, ``t'`` uniform on ``[-h_e/2, h_e/2]``, ``[-h_f/2, h_f/2]`` (`h`: the element
    sizes [rad]), the mean of ``Cl1(u + t -+ t') = sum_n Cl1^(n)(u) (t -+ t')^n / n!`` keeps the
    even ``n``: ``sum_(p,q) x_p(h_e) x_q(h_f) Cl1^(2p+2q)(u)``, with ``x_p(h) = (h/2)^(2p) / (2p+1)!``
    the mean of ``t^(2p) / (2p)!``, summed over ``p + q < TAYLOR_TERMS``. The terms ``p + q >= 1``
    are polynomials in ``s = cot(u/2)^2`` (`_SERIES_HANKEL` ``D``), so
    ``y[k, p, f] = sum_q D[k, p, q] x_q(h_f)``, the same for both kernels. Both are products and
    sums in a fixed order, elementwise (``x_p = x_(p-1) (h/2)^2 / (2p (2p+1))``; no BLAS, whose
    rounding depends on the shapes of the arrays): each row of `x` and column of `y` depends on
    its own size alone, bit for bit.

    Returns
    -------
    x : ndarray, shape (M, TAYLOR_TERMS)
        ``x_p(h_e)`` [rad^(2p)].
    y : ndarray, shape (TAYLOR_TERMS, TAYLOR_TERMS, M)
        ``y[k, p, f]`` [rad^(-2p)].
    """
    half_squared = (h / 2) * (h / 2)
    x = np.empty((h.size, TAYLOR_TERMS))
    x[:, 0] = 1.0
    for p in range(1, TAYLOR_TERMS):
        x[:, p] = x[:, p - 1] * half_squared / ((2 * p) * (2 * p + 1))
    y = _SERIES_HANKEL[..., 0, None] * x[:, 0]
    for q in range(1, TAYLOR_TERMS):
        y += _SERIES_HANKEL[..., q, None] * x[:, q]
    return x, y


def _series_coefficients(sizes):
    """``a_k(h_e, h_f)`` [-] of `_series_means` for every pair of the distinct element `sizes` [rad].

    ``a_k = sum_p x_p(h_e) y[k, p](h_f)`` (`_taylor_factors`), summed over ``p`` in order for
    ``h_e <= h_f`` and mirrored: symmetric, and each entry a function of its two sizes alone, bit
    for bit, whatever other sizes there are. A mesh of bisected elements has few distinct sizes
    (48 among the 763 elements of the bench's baseline scene), so this table is cheap; one of
    ``M`` distinct sizes (random nodes) costs ``~ 64 M^2`` operations here, most of `stiffness`'s
    time on such a mesh.

    Returns
    -------
    ndarray, shape (TAYLOR_TERMS, U, U)
        ``a_k`` of the sizes ``(sizes[i], sizes[j])``.
    """
    x, y = _taylor_factors(sizes)
    a = x[:, 0, None] * y[:, 0, None, :]
    for p in range(1, TAYLOR_TERMS):
        a += x[:, p, None] * y[:, p, None, :]
    ascending = np.arange(sizes.size)[:, None] <= np.arange(sizes.size)
    return np.where(ascending, a, a.transpose(0, 2, 1))


def _series_means(u, coefficients):
    """Far-pair means [-] ``Cl1(u) + sum_k a_k s^k``, ``s = cot(u/2)^2``, at arguments `u` [rad] in ``(0, pi]``.

    One ``tan`` serves both parts: ``Cl1(u) = -ln|2 sin(u/2)| = ln(1 + s)/2 - ln 2``. The
    polynomial by Horner, its `coefficients` ``a_k`` (`_series_coefficients`) broadcast against `u`.
    """
    s = np.tan(0.5 * u)
    np.divide(1.0, s, out=s)
    s *= s
    means = coefficients[-1] * s
    for a in coefficients[-2:0:-1]:
        means += a
        means *= s
    means += coefficients[0] - np.log(2)
    np.log1p(s, out=s)
    s *= 0.5
    means += s
    return means


def _corner_means(lo, hi, e, f, plus):
    """Mean of ``Cl1(theta - phi)`` (or ``Cl1(theta + phi)`` if `plus`) over the pairs of elements ``(e, f)`` [-].

    The four-corner formula: over ``[a1, a2] x [b1, b2]``,
    ``((F(a2 - b1) + F(a1 - b2)) - (F(a1 - b1) + F(a2 - b2))) / (h_e h_f)``, and for `plus`
    ``((F(a2 + b2) + F(a1 + b1)) - (F(a2 + b1) + F(a1 + b2))) / (h_e h_f)``: swapping ``e`` and
    ``f`` swaps the two terms of a sum (``F`` is even), so the mean of ``(f, e)`` is that of
    ``(e, f)``, bit for bit. Pairs of `plus` nearer ``2 pi`` than 0 are reflected,
    ``theta -> pi - theta``, so that their small arguments are differences of nodes computed
    without rounding.

    Parameters
    ----------
    lo, hi : ndarray, shape (M,)
        Ends of the elements [rad], ``0 <= lo < hi <= pi``.
    e, f : ndarray of int
        The elements of each pair.
    plus : bool
        Kernel of the sum.
    """
    h = hi - lo
    if plus:
        centre = (lo + hi) / 2
        flip = centre[e] + centre[f] > np.pi
        a1 = np.where(flip, np.pi - hi[e], lo[e])
        a2 = np.where(flip, np.pi - lo[e], hi[e])
        b1 = np.where(flip, np.pi - hi[f], lo[f])
        b2 = np.where(flip, np.pi - lo[f], hi[f])
        corners = (a2 + b2, a1 + b1, a2 + b1, a1 + b2)
    else:
        a1, a2, b1, b2 = lo[e], hi[e], lo[f], hi[f]
        corners = (a2 - b1, a1 - b2, a1 - b1, a2 - b2)
    F = clausen3_complement(np.stack(corners))
    return ((F[0] + F[1]) - (F[2] + F[3])) / (h[e] * h[f])


def _arguments(centre_e, centre_f):
    """Arguments [rad] of the two kernels at the centres of pairs of elements, in ``[0, pi]``.

    ``|c_e - c_f|`` and ``c_e + c_f``, the latter reflected to ``2 pi - c_e - c_f`` beyond pi
    (``Cl1`` is even with period ``2 pi``); shape ``(2, *shape)`` of the centres broadcast.
    """
    u = np.empty((2, *np.broadcast_shapes(centre_e.shape, centre_f.shape)))
    np.abs(np.subtract(centre_e, centre_f, out=u[0]), out=u[0])
    np.add(centre_e, centre_f, out=u[1])
    np.minimum(u[1], 2 * np.pi - u[1], out=u[1])
    return u


class _Elements(NamedTuple):
    """The elements of a mesh as `_series_block` and `_near_pairs` read them."""

    lo: np.ndarray  #: ends [rad], shape (M,)
    hi: np.ndarray
    centre: np.ndarray  #: [rad]
    h: np.ndarray  #: sizes [rad]
    size_index: np.ndarray  #: of each element's size among the distinct ones
    coefficients: np.ndarray  #: `_series_coefficients` of the distinct sizes, shape (TAYLOR_TERMS, U, U)


def _elements(lo, hi):
    """`_Elements` of the elements ``[lo, hi]`` [rad]."""
    h = hi - lo
    sizes, size_index = np.unique(h, return_inverse=True)
    return _Elements(lo, hi, (lo + hi) / 2, h, size_index, _series_coefficients(sizes))


def _series_block(elements, rows, columns):
    """`_series_means` of both kernels over the pairs of elements `rows` x `columns` (slices or indices).

    Every mean is computed elementwise from its own two elements (arguments, nearness and the
    coefficients of its two sizes), the same for ``(e, f)`` and ``(f, e)``: it does not depend, to
    the last bit, on the block it is computed in.

    Returns
    -------
    block : ndarray, shape (2, R, C)
        The means [-] of ``Cl1(theta - phi)`` and of ``Cl1(theta + phi)``.
    near : ndarray of bool, shape (2, R, C)
        Where they are yet to be replaced by `_corner_means`.
    """
    centre, h = elements.centre, elements.h
    u = _arguments(centre[rows, None], centre[None, columns])
    near = u < FAR_PAIRS * (h[rows, None] + h[None, columns]) / 2
    np.copyto(u, np.pi, where=near)  # any argument away from 0 will do: `_near_pairs` replaces these
    sizes = elements.coefficients.shape[-1]
    pair_sizes = elements.size_index[rows, None] * sizes + elements.size_index[None, columns]
    block = _series_means(u, elements.coefficients.reshape(TAYLOR_TERMS, -1).take(pair_sizes, axis=1))
    return block, near


def _series_pairs(means, elements, rows, columns, computed):
    """Fill ``means[rows, columns]`` and its mirror image with the difference of the kernels' `_series_block`.

    Returns the pairs ``(e, f)`` among them that are near in either kernel, to be filled by
    `_near_pairs`, once each (``f >= e``, or `f` no row of `computed`): ``e``, ``f``, the two
    kernels' series means, shape (2, n), and where they are near.
    """
    block, near = _series_block(elements, rows, columns)
    difference = block[0] - block[1]
    means[rows, columns] = difference
    means[columns, rows] = difference.T
    i, j = np.nonzero(near[0] | near[1])
    element = np.arange(computed.size)
    e, f = element[rows][i], element[columns][j]
    once = (f >= e) | ~computed[f]
    i, j = i[once], j[once]
    return e[once], f[once], block[:, i, j], near[:, i, j]


def _near_pairs(means, elements, e, f, series, near):
    """Fill ``means[e, f]`` and ``means[f, e]``: `_corner_means` in a kernel where the pair is near, else `series`."""
    for plus in (0, 1):
        corner = near[plus]
        series[plus, corner] = _corner_means(elements.lo, elements.hi, e[corner], f[corner], plus=bool(plus))
    means[e, f] = means[f, e] = series[0] - series[1]


def _recurring_elements(lo, hi, previous):
    """Index of each element ``[lo, hi]`` [rad] among those of the mesh `previous` [rad], -1 if not one of them.

    An element recurs if `previous` has an element with the same two ends, exactly.
    """
    k = np.minimum(np.searchsorted(previous, lo), previous.size - 2)
    return np.where((previous[k] == lo) & (previous[k + 1] == hi), k, -1)


def _kernel_means(lo, hi, previous=None):
    """Means [-] of ``Cl1(theta - phi) - Cl1(theta + phi)`` over every pair of elements ``[lo, hi]`` [rad].

    In a border of zeros, shape ``(M + 2, M + 2)``, that `_stiffness` differences as it is.
    Symmetric: the series (`_series_pairs`) runs over blocks of about `BLOCK_PAIRS` pairs, rows
    ``e`` by columns ``f`` from the block's first row on, and is mirrored; the near pairs then
    get `_corner_means` (`_near_pairs`). With `previous` (any `GalerkinModel`: the means are
    geometry alone), the pairs of elements that recur in its mesh (`_recurring_elements`) copy
    its means and the series runs over the rows of the new elements by every column, unless half
    the elements or more are new (every pair, mirrored, is then the cheaper). Each mean is computed
    from its two elements alone, elementwise, so the result is the same, bit for bit, with any
    `previous` or none.
    """
    M = lo.size
    bordered = np.zeros((M + 2, M + 2))
    means = bordered[1:-1, 1:-1]
    origin = np.full(M, -1) if previous is None else _recurring_elements(lo, hi, previous.theta)
    computed = origin < 0
    step = max(1, BLOCK_PAIRS // M)
    if 2 * np.count_nonzero(computed) < M:
        source = np.maximum(origin, 0)  # the rows and columns of the new elements are overwritten
        means[...] = previous._kernel_means[1:-1, 1:-1].take(source, axis=0).take(source, axis=1)
        new = np.flatnonzero(computed)
        blocks = [(new[start : start + step], slice(None)) for start in range(0, new.size, step)]
    else:
        computed[:] = True
        blocks = [(slice(start, start + step), slice(start, None)) for start in range(0, M, step)]
    if blocks:  # none on the mesh of `previous` itself
        elements = _elements(lo, hi)
        near = [_series_pairs(means, elements, rows, columns, computed) for rows, columns in blocks]
        _near_pairs(means, elements, *(np.concatenate(part, axis=-1) for part in zip(*near, strict=True)))
    return bordered


def _stiffness(kernel_means, E_star):
    """``K = (E_star / (2 pi)) C^T W C`` [Pa] from the bordered `_kernel_means` ``W``, ``C`` the element differences.

    Of ``W`` reversed in both axes (a view), the same differences give ``K`` reversed, bit for
    bit: ``x - y = -(y - x)`` exactly.
    """
    K = np.diff(np.diff(kernel_means, axis=0), axis=1)
    K *= E_star / (2 * np.pi)
    return K


def stiffness(theta, E_star, previous=None):
    """``K_kl = B(phi_k, phi_l)`` [Pa] of the hats on the mesh `theta` (ascending, 0 to pi).

    ``K = (E_star / (2 pi)) C^T (means(theta - phi) - means(theta + phi)) C`` with ``C`` the
    element difference of nodal values: symmetric, positive semi-definite, ``K 1 = 0``.
    `previous`, any `GalerkinModel` (worth it when its mesh shares most elements with `theta`,
    as a coarser one that `refine` bisected does), lends the means of the pairs of elements with
    the same two ends: the result is the same, bit for bit, as without it (`_kernel_means`).
    """
    return _stiffness(_kernel_means(theta[:-1], theta[1:], previous), E_star)


# --- one-dimensional integrals of hats --------------------------------------------------------


def _j1(w):
    """``(sin w - w cos w) / w`` [-] without cancellation for small half-widths ``w``."""
    w = np.asarray(w, dtype=float)
    small = w < SMALL_HALF_WIDTH
    k = np.arange(1, _J1_TERMS + 1)
    coefficients = np.concatenate([[0.0], (-1.0) ** (k + 1) * 2 * k / special.factorial(2 * k + 1)])
    series = polynomial.polyval(w * w, coefficients)
    direct = (np.sin(w) - w * np.cos(w)) / np.where(small, 1.0, w)
    return np.where(small, series, direct)


def _hat_cos_integrals(theta):
    """``int cos(theta) phi_k dtheta`` [-] per node (theta order).

    On an element of centre ``m`` and half-width ``w`` the rising hat gives
    ``cos m sin w - sin m j(w)``, the falling one the same with ``-j``;
    ``j(w) = (sin w - w cos w) / w``.
    """
    m = (theta[:-1] + theta[1:]) / 2
    w = np.diff(theta) / 2
    j = _j1(w)
    sin_w = np.sin(w)
    return _assemble(np.cos(m) * sin_w + np.sin(m) * j, np.cos(m) * sin_w - np.sin(m) * j)


def _assemble(fall, rise):
    """Nodal sums of per-element integrals of the falling (left node) and rising (right node) hats."""
    nodal = np.zeros(fall.size + 1)
    nodal[:-1] += fall
    nodal[1:] += rise
    return nodal


def _pressure_breakpoints(contact):
    """Angles [rad] where ``p sqrt(1 - t^2)`` has a singular derivative: the profile's `breakpoints` in the contact."""
    t = (np.asarray(contact.profile.breakpoints, dtype=float) - contact.centre) / contact.a
    return np.arccos(t[np.abs(t) < 1])


def _pressure_wavelength(contact):
    """Shortest wavelength [rad] in ``p sqrt(1 - t^2)`` as a function of theta (inf if it is smooth).

    A `Gap` pressure is a sine series of ``Gap.ORDER`` terms, whose top terms matter when the
    gap's curvature jumps.
    """
    return 2 * np.pi / contact.profile.ORDER if isinstance(contact.profile, Gap) else np.inf


def _quadrature_pieces(theta, breakpoints, wavelength):
    """Subintervals ``(lo, hi, element)`` covering the mesh, on which 8-point Gauss is accurate.

    Elements are cut into equal pieces of at most half a `wavelength`. An element that holds a
    breakpoint, or lies within its own size of one, is instead cut into pieces that halve in
    length toward it, so that each piece lies at least its own length from the singularity.
    """
    lo, hi = theta[:-1], theta[1:]
    graded = np.zeros(lo.size, dtype=bool)
    pieces = []
    for point in breakpoints:
        nearest = np.clip(point, lo, hi)
        for k in np.flatnonzero(np.abs(nearest - point) < hi - lo):
            graded[k] = True
            for far_end in (lo[k], hi[k]):
                if far_end != nearest[k]:
                    fractions = np.concatenate([GRADING_RATIO ** np.arange(GRADING_LEVELS + 1), [0.0]])
                    cuts = np.sort(nearest[k] + (far_end - nearest[k]) * fractions)
                    pieces.append((cuts[:-1], cuts[1:], np.full(cuts.size - 1, k)))
    whole = np.flatnonzero(~graded)
    count = np.ones(whole.size, dtype=int)
    if np.isfinite(wavelength):
        count = np.ceil((hi[whole] - lo[whole]) / (wavelength / 2)).astype(int)
    element = np.repeat(whole, count)
    index = np.arange(element.size) - np.repeat(np.cumsum(count) - count, count)
    step = (hi - lo)[element] / np.repeat(count, count)
    pieces.append((lo[element] + index * step, lo[element] + (index + 1) * step, element))
    return tuple(np.concatenate(parts) for parts in zip(*pieces, strict=True))


def _pressure_moments(contact, theta):
    """``int (theta - theta_k)^j p sqrt(1 - t^2) phi_k dtheta``, ``j = 0, 1, 2`` [Pa rad^(j+1)] (theta order).

    By Gauss on `_quadrature_pieces`, with offsets measured from the node itself so that no
    moment is the small difference of large ones. ``f a`` times the zeroth is the friction
    limit ``L_k = int f p phi_k dx``.
    """
    lo, hi, element = _quadrature_pieces(theta, _pressure_breakpoints(contact), _pressure_wavelength(contact))
    nodes, weights = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    half = ((hi - lo) / 2)[:, None]
    from_left = (lo - theta[element])[:, None] + half * (1 + nodes)  # theta - theta_e, >= 0
    h = (theta[element + 1] - theta[element])[:, None]
    rise = from_left / h
    measure = contact.pressure_weighted(np.cos(theta[element][:, None] + from_left)) * weights * half
    moments = []
    for power in range(3):
        fall = np.sum(measure * (1 - rise) * from_left**power, axis=1)  # node e
        rise_part = np.sum(measure * rise * (from_left - h) ** power, axis=1)  # node e + 1
        M = theta.size - 1
        moments.append(_assemble(np.bincount(element, fall, minlength=M), np.bincount(element, rise_part, minlength=M)))
    return moments


def _recovery(theta, moments):
    """Stencils and weights [-] that turn hat means into nodal values (theta order).

    Node ``k`` takes the quadratic in ``theta`` whose means under the hats of nodes
    ``k - 1, k, k + 1`` (one-sided at the edges), weighted by `moments`, equal the given ones,
    and its value at ``theta_k``: exact for quadratics, where a hat mean itself is off by
    ``O(h)`` on unequal neighbouring elements and at the edges.
    """
    first, second = moments[1] / moments[0], moments[2] / moments[0]
    k = np.arange(theta.size)
    stencil = np.clip(k, 1, theta.size - 2)[:, None] + np.array([-1, 0, 1])
    scale = np.diff(theta)[np.minimum(k, theta.size - 2)][:, None]
    shift = (theta[stencil] - theta[k][:, None]) / scale
    mean = first[stencil] / scale
    square = second[stencil] / scale**2
    system = np.stack([np.ones_like(shift), mean + shift, square + 2 * shift * mean + shift**2], axis=-1)
    weights = np.linalg.inv(system)[:, 0, :]
    return stencil, weights


# --- the scene ---------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Mesh(ModelSpec):
    """Method 4 by P1 Galerkin on a mesh in ``theta``: the mesh `theta` as given, or one adapted to
    the history so that the energy of each increment is right to `rtol` (resolved by
    `fretting.engine.choice.resolve`).

    Parameters
    ----------
    rtol : float, optional
        Relative accuracy asked of the energy (`DEFAULT_RTOL` when neither is given).
    theta : array_like, optional
        Mesh nodes [rad], strictly increasing from 0 to pi.
    fallback : str, optional
        Why the mesh, or the energy on it, is coarser than `rtol` asks: the adaptation of a default
        stopped at one of its bounds (`fretting.engine.choice.MAX_DEFAULT_MESH`, `MAX_DEFAULT_WORK`;
        the reason holds `fretting.engine.choice.CAPPED`), an energy that could not settle, or
        increments below the solver's floor, slipping again too little or held stuck by its
        rounding allowance (`fretting.engine.adaptation`). None: the mesh is the one asked for.
    sample : str, optional
        What the adaptation ran when it ran a sample of a long history's turning points instead of
        all of them (`fretting.engine.adaptation.SAMPLE_TURNS`). None: it ran them all.
    """

    rtol: float | None = None
    theta: np.ndarray | None = None
    fallback: str | None = None
    sample: str | None = None

    name: ClassVar[str] = "mesh"
    description: ClassVar[str] = "method 4: dislocation correction to the fully adhered solution, P1 Galerkin in theta"

    def __post_init__(self):
        if self.theta is not None:
            object.__setattr__(self, "theta", _validated_mesh(self.theta))
        elif self.rtol is None:
            object.__setattr__(self, "rtol", DEFAULT_RTOL)
        if self.rtol is not None:
            object.__setattr__(self, "rtol", positive("rtol", self.rtol))

    @property
    def resolved(self) -> bool:
        return self.theta is not None

    def build(self, contact: Contact, previous: GalerkinModel | None = None) -> GalerkinModel:
        return GalerkinModel(contact, self, previous)

    def attributes(self) -> dict:
        attributes = {"model": self.name} | ({} if self.rtol is None else {"rtol": self.rtol})
        notes = {"model_fallback": self.fallback, "model_sample": self.sample}
        return attributes | {key: note for key, note in notes.items() if note is not None}

    @classmethod
    def from_record(cls, attrs: dict, theta: np.ndarray | None) -> Mesh:
        return cls(attrs.get("rtol"), theta, attrs.get("model_fallback"), attrs.get("model_sample"))


class GalerkinModel(Method4Model):
    """A contact discretised by P1 Galerkin on the mesh of a resolved `Mesh`; every per-node array
    in ascending ``x``, i.e. descending ``theta``.

    Parameters
    ----------
    contact : Contact
    spec : Mesh
        Resolved: its ``theta`` [rad], strictly increasing from 0 to pi, shape (M + 1,).
    previous : GalerkinModel, optional
        A model whose mesh shares elements with `theta` (one that `refine` bisected): its means
        over the pairs of shared elements are reused, and the model is the same, bit for bit, as
        without it (`stiffness`).

    Attributes
    ----------
    theta : ndarray, shape (N,)
        The mesh as given [rad], ascending in ``theta``.
    x, t : ndarray, shape (N,)
        Node positions [m] and ``(x - centre)/a`` [-], ascending.
    G : ndarray, shape (N, N)
        Stiffness ``K_kl = B(phi_k, phi_l)`` [Pa]: ``g = F - G s`` with ``g_k = int q phi_k dx``.
    limit : ndarray, shape (N,)
        ``L_k = int f p phi_k dx`` [N/m].
    friction_force : float
        ``sum_k L_k`` [N/m]: ``f P`` up to the quadrature of `limit`, since the hats sum to 1.
        The engine takes gross slip from the smaller of this and ``f P``.
    breakpoints : ndarray
        Angles [rad] where the pressure has a singular derivative (the profile's `breakpoints`
        inside the contact), for `element_targets`.
    """

    def __init__(self, contact, spec, previous=None):
        theta = spec.theta
        self.spec = spec
        self.contact = contact
        self.theta = theta
        a = contact.a
        order = slice(None, None, -1)  # theta descending: x ascending
        self.t = np.cos(theta[order])
        self.t[0], self.t[-1] = -1.0, 1.0
        self.x = contact.centre + a * self.t
        self._kernel_means = _kernel_means(theta[:-1], theta[1:], previous)  # for the model of a refined mesh
        self.G = _stiffness(self._kernel_means[order, order], contact.E_star)
        cos_integral = _hat_cos_integrals(theta)
        self._dQ = (_assemble(np.diff(theta) / 2, np.diff(theta) / 2) / np.pi)[order]
        self._dsig = (a / 4 * cos_integral)[order]
        moments = _pressure_moments(contact, theta)
        self.limit = (contact.f * a * moments[0])[order]
        self.friction_force = float(self.limit.sum())
        self.breakpoints = _pressure_breakpoints(contact)
        self._fp = contact.f * contact.pressure(self.x)
        stencil, weights = _recovery(theta, moments)
        self._stencil, self._recovery_weights = theta.size - 1 - stencil[order], weights[order]

    @property
    def nodes(self):
        """Number of nodes ``N = M + 1``."""
        return self.theta.size

    def g_stuck(self, Q, sigma):
        """``F_k = int q_st phi_k dx`` [N/m] of the fully stuck traction, eqs (9) and (20)."""
        return Q * self._dQ + sigma * self._dsig

    def traction(self, outcome):
        """Shear traction [Pa] at the nodes after `outcome` (`nodal_traction` of its ``g``, ``ds``)."""
        return self.nodal_traction(outcome.g, outcome.ds)

    def nodal_traction(self, g, ds=None):
        """Shear traction [Pa] at the nodes, from its hat moments `g` [N/m] (rows of a 2-D `g`).

        ``g_k / L_k`` is the mean of the utilisation ``u = q / (f p)`` under ``f p phi_k dx``;
        the quadratic in ``theta`` with the means of three neighbouring nodes gives its nodal
        value to ``O(h^3)`` where ``u`` is smooth (a mean itself is off by ``O(h)`` where
        neighbouring elements differ in size). It is clipped to ``[-1, 1]`` and, where the slip
        increment `ds` [m] is given and non-zero, set to ``sign(ds)``: ``q = u f p(x)`` then
        keeps Coulomb's law exactly at every node. At the contact edges ``p(x) = 0`` (as
        `Contact.pressure` has it), so ``q = 0`` there, also for the sharp flat punch whose
        edge traction is unbounded.
        """
        utilisation = np.clip(
            np.sum((np.asarray(g) / self.limit)[..., self._stencil] * self._recovery_weights, axis=-1), -1, 1
        )
        if ds is not None:
            utilisation = np.where(ds != 0, np.sign(ds), utilisation)
        return utilisation * self._fp

    def delta_Q(self, outcome):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] of the slip after `outcome`, exact for P1.

        A row-wise sum, not a matrix product, so that a row's value does not depend on how many
        rows there are.
        """
        return np.sum(outcome.slip * self._dQ, axis=-1)

    def delta_sigma(self, outcome):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2] of the slip after `outcome`, exact for P1."""
        return np.sum(outcome.slip * self._dsig, axis=-1)

    def locate_end(self, position, d, slipping, beyond):
        """Where the slip `d` of a slip zone reaches zero, from past the lagging node nearest the
        boundary (`located_end`)."""
        return located_end(position, d, slipping, beyond)

    def dissipation(self, ds):
        """``sum_k L_k |ds_k|`` [J/m], the lumped ``int f p |ds| dx``."""
        return float(np.dot(self.limit, np.abs(ds)))

    def dissipation_density(self, ds):
        """``f p(x_k) |ds_k|`` [J/m^2] at the nodes: the density of ``int f p |ds| dx`` at each node.

        Pointwise, not the hat-weighted mean ``L_k |ds_k| / area_k``: the mean of ``f p`` under
        ``phi_k`` differs from ``f p(x_k)`` by ``O(h^2 p'')`` on equal elements, ``O(h p')`` where
        neighbouring elements differ in size, and more next to the edges, where ``p`` falls as a
        square root; a mesh adapted to the energy of the increments (`element_targets`) leaves
        elements wide where that error is large. The nodal value is as accurate as the slip
        increment at the node, as the exact model's ``f p |ds|`` is. `dissipation`, the energy of
        the increment and of the cycle, stays the lumped sum that the solve balances.
        """
        return self._fp * np.abs(ds)


def _validated_mesh(theta):
    """`theta` [rad] as a float array, checked to be a mesh: finite, strictly increasing from 0 to pi."""
    theta = np.array(theta, dtype=float)
    if theta.ndim != 1 or theta.size < 3:
        raise ValueError(f"theta must be a 1-D mesh of at least 3 nodes, found shape {theta.shape}")
    if theta[0] != 0.0 or theta[-1] != np.pi or not np.all(np.diff(theta) > 0):  # NaN fails the comparison
        raise ValueError(f"theta must increase strictly from 0 to pi, found {_shown(theta)}")
    return theta


def _shown(theta):
    """The first nodes of `theta` that break its order, for an error message."""
    bad = np.flatnonzero(~(np.diff(theta) > 0))
    k = int(bad[0]) if bad.size else 0
    return f"theta[{k}:{k + 2}] = {theta[k : k + 2].tolist()}" if bad.size else f"ends {theta[0]!r}, {theta[-1]!r}"


# --- meshes --------------------------------------------------------------------------------


def uniform_theta(M):
    """``M`` equal elements on ``[0, pi]`` [rad]; the last node is exactly ``pi``."""
    if not isinstance(M, (int, np.integer)) or M < 2:
        raise ValueError(f"M must be an integer >= 2, found {M!r}")
    theta = np.linspace(0.0, np.pi, M + 1)
    theta[-1] = np.pi
    return theta


def initial_theta(M=None):
    """Uniform mesh of `M` elements whose edge elements are bisected down to `EDGE_SIZE` [rad].

    A slip zone much narrower than the edge element is invisible (the edge node sticks), so
    the mesh starts graded toward the edges: slip zones down to ``~ EDGE_SIZE`` in ``theta``,
    ``a EDGE_SIZE^2 / 2`` in ``x``, are seen and then refined by `element_targets`.
    """
    theta = uniform_theta(INITIAL_ELEMENTS if M is None else M)
    while theta[1] > EDGE_SIZE:
        theta = np.concatenate([[0.0, theta[1] / 2], theta[1:-1], [(theta[-2] + np.pi) / 2, np.pi]])
        theta = _graded(theta)
    return theta


def element_targets(
    theta, ds, rtol=DEFAULT_RTOL, breakpoints=(), swept=BOUNDARY_SPAN, end=BOUNDARY_SPAN, levels=LEVELS_PER_PASS
):
    """Largest element sizes [rad] that resolve the stick and slip zones of an increment.

    The nodes' status (stuck: ``ds == 0``, slipping forward, slipping backward) splits
    ``[0, pi]`` into zones; each boundary is placed inside its element by `_boundary_position`.
    Asked for:

    - inside a zone of width ``w``: ``zone_fraction(rtol) w`` (`ZONE_ELEMENTS` elements or more),
      and inside a slip zone at most ``swept rtol a`` in x: the boundaries of the steps between
      two turning points sweep it;
    - the element holding a boundary: ``boundary_fraction(rtol) w`` of the narrower zone beside
      it (or of its distance to the nearest of `breakpoints`, where the pressure has a singular
      derivative), since the energy error a boundary leaves falls like ``(size / w)^(5/2)``, and at most
      ``end rtol a`` in x, the accuracy asked of the located ends;
    - around a boundary, ``BOUNDARY_GRADING`` times the distance from it;
    - at each of `breakpoints`, ``BREAKPOINT_SPAN BOUNDARY_SPAN rtol a`` in x, graded the same way, whatever
      the increment: the traction inherits the pressure's singular derivative there;
    - a zone seen at fewer than `MIN_ZONE_NODES` nodes (its width is a guess), or neighbours
      slipping in opposite directions (a stick zone hides between them): half the element.

    No element is asked to shrink by more than ``2^levels`` in one pass (None: no limit, where the
    zones are located already), so that the zones are located again on the finer mesh, nor below
    `MIN_SIZE`.

    Parameters
    ----------
    theta : ndarray, shape (M + 1,)
        The mesh [rad], ascending from 0 to pi.
    ds : ndarray, shape (M + 1,) or (steps, M + 1)
        Slip increment [m] from a `GalerkinModel` on `theta`, in the scene's order (ascending
        ``x``, i.e. descending ``theta``), exactly zero where a node stuck (as
        `fretting.models.solver.solve_increment` leaves it). Rows are reduced with ``np.minimum``.
    rtol : float
        Relative accuracy asked of the energy dissipated in each increment.
    breakpoints : array_like of float
        Angles [rad] where the pressure has a singular derivative (`GalerkinModel.breakpoints`:
        the ends of a rounded flat, those a `Gap` is given), so that a stick zone ending near one
        is located to a fraction of its distance from it.

    swept, end : float
        Largest span, in units of ``rtol a`` in x, of the elements of the slip zones (swept by the
        boundaries of the steps inside the increment) and of those holding the increment's own
        boundaries: `BOUNDARY_SPAN` where those steps' stick ends are recorded, `ENERGY_SPAN`
        where only the energy is.

    Returns
    -------
    ndarray, shape (M,)
        Target size of each element [rad], ascending ``theta``; ``inf`` where any size will do.
    """
    ds = np.asarray(ds, dtype=float)
    if ds.shape[-1] != theta.size or ds.ndim not in (1, 2):
        raise ValueError(f"ds must have {theta.size} values a row, one per node of theta; found shape {ds.shape}")
    if ds.ndim == 2:
        rows = [element_targets(theta, row, rtol, breakpoints, swept, end, levels) for row in ds]
        return np.minimum.reduce(rows, initial=np.inf)
    d = ds[::-1]  # theta order
    h = np.diff(theta)
    targets = np.full(h.size, np.inf)
    for point in breakpoints:  # the traction has the pressure's singular derivative there
        targets = np.minimum(targets, _graded_toward(theta, point, BREAKPOINT_SPAN * _span(point, rtol)))
    status = np.sign(d)
    inside, positions = _boundaries(theta, d)
    if inside.size == 0:
        return np.maximum(targets, MIN_SIZE if levels is None else np.maximum(h / 2**levels, MIN_SIZE))
    ends = np.concatenate([[0.0], positions, [np.pi]])
    nodes = np.diff(np.concatenate([[0], inside + 1, [d.size]]))
    width = np.diff(ends)
    zone_status = status[np.concatenate([[0], inside + 1])]
    for zone in range(width.size):
        overlapping = (theta[:-1] < ends[zone + 1]) & (theta[1:] > ends[zone])
        if nodes[zone] < MIN_ZONE_NODES:
            size = h[overlapping] / 2
        else:
            size = width[zone] * zone_fraction(rtol)
        if zone_status[zone]:  # swept by the boundaries of the steps between: locate them too
            size = np.minimum(size, _span((theta[:-1] + theta[1:])[overlapping] / 2, rtol, swept))
            if zone in (0, width.size - 1):  # grown from the contact's edge through every width
                size = np.minimum(size, _graded_from_edge(theta, zone == 0, rtol)[overlapping])
        targets[overlapping] = np.minimum(targets[overlapping], size)
    for zone, (k, position) in enumerate(zip(inside, ends[1:-1], strict=True)):  # between zone and zone + 1
        scale = min(width[zone], width[zone + 1], *(abs(position - b) or np.inf for b in breakpoints))
        size = min(boundary_fraction(rtol) * scale, _span(position, rtol, end))
        targets = np.minimum(targets, _graded_toward(theta, position, size))
        if status[k] * status[k + 1] < 0:
            targets[k] = min(targets[k], h[k] / 2)
    return np.maximum(targets, MIN_SIZE if levels is None else np.maximum(h / 2**levels, MIN_SIZE))


def _span(position, rtol, span=BOUNDARY_SPAN):
    """Size [rad] of an element at `position` [rad] that spans ``span rtol a`` in x."""
    return span * rtol / np.maximum(np.sin(position), span * rtol / np.pi)


def _graded_from_edge(theta, left, rtol):
    """Targets [rad] growing like ``zone_fraction(rtol)`` times the distance from the contact's edge
    (``theta = 0`` if `left`, else ``pi``), from `EDGE_SIZE`.

    A slip zone at the edge grows through every width between two turning points, and the slip
    there is smooth in ``theta`` up to the edge, so that each of those widths is spanned by
    ``ZONE_ELEMENTS`` elements or more, as a zone at a turning point is: with only the elements a
    turning point's wide zone asks for, the slip of the narrow zones of the steps before it
    missed the slip target of benchmarks/trajectories.py.
    """
    distance = theta[:-1] if left else np.pi - theta[1:]
    return np.maximum(zone_fraction(rtol) * distance, EDGE_SIZE)


def _graded_toward(theta, position, size):
    """Targets [rad]: `size` at `position`, growing like ``BOUNDARY_GRADING`` times the distance from it."""
    distance = np.maximum(np.maximum(theta[:-1] - position, position - theta[1:]), 0.0)
    return np.maximum(size, BOUNDARY_GRADING * distance)


def zone_fraction(rtol):
    """Size of the elements inside a zone, as a fraction of its width [-]: 1/`ZONE_ELEMENTS` or less.

    The energy error left inside the zones, ``ZONE_ERROR`` at ``1 / ZONE_ELEMENTS``, falls like
    the square of the fraction.
    """
    return min(1.0, np.sqrt(rtol / ZONE_ERROR)) / ZONE_ELEMENTS


def boundary_fraction(rtol):
    """Size of the element holding a stick/slip boundary, as a fraction of the narrower zone's width [-].

    Inverts the worst energy error ``BOUNDARY_ERROR (size / w)^(5/2)``; never coarser than
    `zone_fraction`.
    """
    return min(zone_fraction(rtol), (rtol / BOUNDARY_ERROR) ** (2 / 5))


def boundaries(theta, ds):
    """Stick/slip boundaries [rad] of the slip increment `ds` [m] (scene order, as for
    `element_targets`) on the mesh `theta` [rad], ascending, each placed by `_boundary_position`."""
    return _boundaries(theta, np.asarray(ds, dtype=float)[::-1])[1]


def _boundaries(theta, d):
    """Elements holding a boundary of `d` (theta order) and the boundaries [rad] inside them."""
    status = np.sign(d)
    inside = np.flatnonzero(status[1:] != status[:-1])  # element k holds a boundary
    return inside, np.array([_boundary_position(theta, d, k) for k in inside], dtype=float)


def tightened(theta, positions, levels=LEVELS_PER_PASS):
    """Targets [rad] that bisect the elements holding `positions` [rad] `levels` times, graded
    around them like a boundary's (``BOUNDARY_GRADING``): where the energy of an increment whose
    boundaries these are still changes from one mesh to the next
    (`fretting.engine.adaptation.adapted_model`)."""
    h = np.diff(theta)
    targets = np.full(h.size, np.inf)
    for position in positions:
        k = min(int(np.searchsorted(theta, position, side="right")) - 1, h.size - 1)
        targets = np.minimum(targets, _graded_toward(theta, position, max(h[k] / 2**levels, MIN_SIZE)))
    return targets


def _boundary_position(theta, d, k):
    """Stick/slip boundary [rad] inside element ``k``, whose nodes ``k``, ``k + 1`` differ in status.

    Near a boundary the slip increment grows like ``dist^(3/2)`` (eq 19; Masing for reversed
    zones), so ``|d|^(2/3)`` is extrapolated linearly from the two nearest slipping nodes (the
    element's middle when there is one only); a change of slip direction is placed where ``d``
    interpolates to zero.
    """
    lo, hi = theta[k], theta[k + 1]
    if d[k] != 0 and d[k + 1] != 0:
        return lo + (hi - lo) * d[k] / (d[k] - d[k + 1])
    slipping, step = (k + 1, 1) if d[k] == 0 else (k, -1)
    estimate = extrapolated_end(theta, d, slipping, slipping + step)
    return (lo + hi) / 2 if estimate is None else float(np.clip(estimate, lo, hi))


def located_end(position, d, slipping, beyond):
    """Where the slip `d` of a slip zone on a Galerkin mesh reaches zero, or None if it cannot be told.

    The P1 slip is zero at the last stuck node, where the true slip is zero only inside the
    element beyond it, so the slipping node nearest the boundary may lag behind the
    ``dist^(3/2)`` law (eq 19), and `extrapolated_end` from it then places the end too far into
    the slip zone: by up to 0.32 of the element on Cattaneo-Mindlin on uniform meshes, never
    short of it. Where `RESOLVED_NODES` nodes from `slipping` (its neighbour `beyond` next,
    `position`: the nodes' coordinates) slip the same way, ``|d|^(2/3)`` is also extrapolated
    from the second and third of them, which keep the law, and the estimate nearer the stick
    zone is taken, since the nearest node's lag only ever moves its estimate outward: within 0.1
    of the element there (tests/test_trajectories.py).
    """
    nearest = extrapolated_end(position, d, slipping, beyond)
    step = beyond - slipping
    run = slipping + step * np.arange(RESOLVED_NODES)
    if nearest is None or not 0 <= run[-1] < d.size or np.any(np.sign(d[run]) != np.sign(d[slipping])):
        return nearest
    skipped = extrapolated_end(position, d, run[1], run[2])
    outward = np.sign(position[beyond] - position[slipping])
    return nearest if skipped is None else min(nearest, skipped, key=lambda end: end * outward)


def refine(theta, targets):
    """Bisect every element until it is no larger than its target, then grade the mesh.

    Parameters
    ----------
    theta : ndarray, shape (M + 1,)
        The mesh [rad], ascending from 0 to pi.
    targets : ndarray, shape (M,)
        Largest size of each element [rad], positive, ``inf`` for any (`element_targets`).

    Returns
    -------
    ndarray
        The refined mesh: the old nodes stay nodes, and neighbouring elements differ in size
        by a factor ``GRADING`` at most. `theta` itself when no element needed bisecting.
    """
    h = np.diff(theta)
    targets = np.asarray(targets, dtype=float)
    if targets.shape != h.shape or np.any(~(targets > 0)):
        raise ValueError(f"targets must be {h.size} positive sizes, one per element; found {targets!r}")
    coarse = h > targets
    levels = np.zeros(h.size, dtype=int)
    levels[coarse] = np.ceil(np.log2(h[coarse] / targets[coarse]))
    if not levels.any():
        return _graded(theta)
    count = 2**levels
    element = np.repeat(np.arange(h.size), count)
    index = np.arange(element.size) - np.repeat(np.cumsum(count) - count, count)
    inner = theta[element] + h[element] * index / count[element]
    return _graded(np.concatenate([inner, [np.pi]]))


def _graded(theta):
    """Bisect the elements more than ``GRADING`` times the size of a neighbour until none is; `theta` if none was."""
    while True:
        h = np.diff(theta)
        neighbour = np.minimum(np.concatenate([[np.inf], h[:-1]]), np.concatenate([h[1:], [np.inf]]))
        coarse = np.flatnonzero(h > GRADING * neighbour * (1 + GRADING_SLACK))
        if coarse.size == 0:
            return theta
        theta = np.insert(theta, coarse + 1, (theta[coarse] + theta[coarse + 1]) / 2)
