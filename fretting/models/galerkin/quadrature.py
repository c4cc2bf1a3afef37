"""Integrals of the hats of a mesh in ``theta``: the loads, the friction limits and the nodal recovery.

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

"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import polynomial
from scipy import special

from fretting.physics.profiles import Gap

__all__ = ["assemble", "hat_cos_integrals", "pressure_breakpoints", "pressure_moments", "recovery"]
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


def _j1(w):
    """``(sin w - w cos w) / w`` [-] without cancellation for small half-widths ``w``."""
    w = np.asarray(w, dtype=float)
    small = w < SMALL_HALF_WIDTH
    k = np.arange(1, _J1_TERMS + 1)
    coefficients = np.concatenate([[0.0], (-1.0) ** (k + 1) * 2 * k / special.factorial(2 * k + 1)])
    series = polynomial.polyval(w * w, coefficients)
    direct = (np.sin(w) - w * np.cos(w)) / np.where(small, 1.0, w)
    return np.where(small, series, direct)


def hat_cos_integrals(theta):
    """``int cos(theta) phi_k dtheta`` [-] per node (theta order).

    On an element of centre ``m`` and half-width ``w`` the rising hat gives
    ``cos m sin w - sin m j(w)``, the falling one the same with ``-j``;
    ``j(w) = (sin w - w cos w) / w``.
    """
    m = (theta[:-1] + theta[1:]) / 2
    w = np.diff(theta) / 2
    j = _j1(w)
    sin_w = np.sin(w)
    return assemble(np.cos(m) * sin_w + np.sin(m) * j, np.cos(m) * sin_w - np.sin(m) * j)


def assemble(fall, rise):
    """Nodal sums of per-element integrals of the falling (left node) and rising (right node) hats."""
    nodal = np.zeros(fall.size + 1)
    nodal[:-1] += fall
    nodal[1:] += rise
    return nodal


def pressure_breakpoints(contact):
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


def pressure_moments(contact, theta):
    """``int (theta - theta_k)^j p sqrt(1 - t^2) phi_k dtheta``, ``j = 0, 1, 2`` [Pa rad^(j+1)] (theta order).

    By Gauss on `_quadrature_pieces`, with offsets measured from the node itself so that no
    moment is the small difference of large ones. ``f a`` times the zeroth is the friction
    limit ``L_k = int f p phi_k dx``.
    """
    lo, hi, element = _quadrature_pieces(theta, pressure_breakpoints(contact), _pressure_wavelength(contact))
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
        moments.append(assemble(np.bincount(element, fall, minlength=M), np.bincount(element, rise_part, minlength=M)))
    return moments


def recovery(theta, moments):
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
