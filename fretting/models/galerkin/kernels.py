"""The stiffness of the P1 Galerkin discretisation in ``theta`` (`stiffness`).

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
bounds (tests/models/test_galerkin.py::test_pair_means_against_quadrature). Each mean is computed from
its own two elements alone, in operations that do not depend on the other elements, so that the
scene of a refined mesh copies the means of the pairs of elements it shares with the scene
before (`GalerkinModel`'s ``previous``) and its stiffness equals, bit for bit, one assembled
afresh (as a run resumed from a saved state assembles it).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.polynomial import polynomial
from scipy import special

__all__ = ["clausen1", "clausen3_complement", "kernel_means", "stiffness", "stiffness_of_means"]

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


def kernel_means(lo, hi, previous=None):
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
        means[...] = previous.kernel_means[1:-1, 1:-1].take(source, axis=0).take(source, axis=1)
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


def stiffness_of_means(kernel_means, E_star):
    """``K = (E_star / (2 pi)) C^T W C`` [Pa] from the bordered `kernel_means` ``W``, ``C`` the element differences.

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
    the same two ends: the result is the same, bit for bit, as without it (`kernel_means`).
    """
    return stiffness_of_means(kernel_means(theta[:-1], theta[1:], previous), E_star)
