"""Published closed-form partial-slip solutions, used as references.

Conventions of docs/theory/conventions.md: positive Q gives positive slip; positive Q and sigma together
move the stick zone toward negative x.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike
from scipy import optimize, special

from fretting._compiled import njit, vectorize
from fretting.physics.contact import Contact

__all__ = [
    "cattaneo_mindlin_traction",
    "cattaneo_mindlin_slip",
    "hertz_slip_shape",
    "stick_half_width",
    "mindlin_deresiewicz_traction",
    "mindlin_deresiewicz_slip",
    "bulk_tension_stick_half_width",
    "nowell_hills_traction",
    "nowell_hills_offset",
    "ciavarella_jaeger",
    "cattaneo_mindlin_compliance",
    "cattaneo_mindlin_dissipation",
    "mindlin_deresiewicz_energy",
    "masing_arrival",
    "masing_origin",
    "masing_increment",
    "masing_walk",
]

#: A branch piece of Masing's rule, ``(origin, factor, Q_start, Q_end)``: origin and loads [N/m], factor [-].
Piece = tuple[float, float, float, float]

#: Terms of the power series of `slip_series`, which it sums below ``psi = 1/4``: ``4^-80`` is
#: far below rounding.
SERIES_TERMS = 80

#: Below this ``z = sqrt(X^2 - b^2) / b`` `hertz_slip_shape` sums the power series of ``sinh w - w``
#: (`SHAPE_TERMS` terms: at ``w = 2 arcsinh(1/2)`` the next is ``3e-17`` of the sum); above it its
#: closed form loses less than a factor 8 to cancellation.
SHAPE_SERIES_BELOW = 0.5
SHAPE_TERMS = 9

#: ``1 / (2k + 3)!``: ``sinh w - w = w^3 sum_k w^(2k) / (2k + 3)!``.
_SINH_SERIES = 1 / special.factorial(2 * np.arange(SHAPE_TERMS) + 3)


def stick_half_width(contact: Contact, Q: float) -> float:
    """Stick-zone half-width ``b = a sqrt(1 - |Q|/(f P))`` of a Hertz contact [m], eq (8)."""
    return contact.a * np.sqrt(1 - abs(Q) / (contact.f * contact.P))


def _ellipse(x: ArrayLike, half_width: float, centre: float = 0.0) -> np.ndarray:
    """``sqrt(1 - ((x - centre)/half_width)^2)`` inside the interval, zero outside."""
    return np.sqrt(np.clip(1 - ((np.asarray(x) - centre) / half_width) ** 2, 0, None))


def cattaneo_mindlin_traction(contact: Contact, Q: float, x: ArrayLike) -> np.ndarray:
    """Shear traction [Pa] of a Hertz contact under monotonic ``Q`` [N/m], eq (7)."""
    b = stick_half_width(contact, Q)
    shape = _ellipse(x, contact.a) - (b / contact.a) * _ellipse(x, b)
    return np.sign(Q) * contact.f * contact.p0 * shape


def cattaneo_mindlin_slip(contact: Contact, Q: float, x: ArrayLike) -> np.ndarray:
    """Slip [m] of a Hertz contact under monotonic ``Q`` [N/m]: eq (19) integrated from ``b``.

    ``s(x) = (f p0 / (E_star a)) [X sqrt(X^2 - b^2) - b^2 arccosh(X / b)]`` with ``X = |x| >= b``
    (`hertz_slip_shape`).
    """
    b = stick_half_width(contact, Q)
    return np.sign(Q) * contact.f * contact.p0 / (contact.E_star * contact.a) * hertz_slip_shape(x, b)


def hertz_slip_shape(x: ArrayLike, b: ArrayLike) -> np.ndarray:
    """``X sqrt(X^2 - b^2) - b^2 arccosh(X / b)`` [m^2] with ``X = max(|x|, b)``, `x` and `b` [m], without cancellation.

    The slip of eq (19) integrated from the stick-zone edge ``b`` (`cattaneo_mindlin_slip`), and
    ``2R`` times the gap outside a Hertz contact of half-width ``b``; ``X^2`` for ``b = 0``.
    Elementwise (`slip_shape`) over `x` and `b` broadcast together, e.g. ``b[:, None]`` against
    nodes ``x``: several half-widths in one evaluation, each element computed as it would be alone.
    """
    return np.asarray(_slip_shapes(np.asarray(x, dtype=float), np.asarray(b, dtype=float)))


@njit
def slip_shape(x: float, b: float) -> float:
    """`hertz_slip_shape` of one point `x` and half-width `b` [m]; compiled, for the exact model's branches.

    With ``z = sqrt((X - b)(X + b)) / b`` the shape is ``b^2 (z sqrt(1 + z^2) - arcsinh z)``, whose
    two terms cancel to ``2 z^3 / 3`` as ``X -> b``; with ``z = sinh(w / 2)`` the bracket is
    ``(sinh w - w) / 2``, summed as its power series below ``z = SHAPE_SERIES_BELOW``, so thin slip
    zones keep their relative precision.
    """
    if b == 0.0:
        return x * x
    X = max(abs(x), b)
    z = math.sqrt((X - b) * (X + b)) / b
    if z >= SHAPE_SERIES_BELOW:
        bracket = z * math.sqrt(1 + z * z) - math.asinh(z)
    elif z > 0:
        w = 2 * math.asinh(z)
        w2 = w * w
        series = _SINH_SERIES[-1]
        for k in range(SHAPE_TERMS - 2, -1, -1):  # Horner in w^2
            series = series * w2 + _SINH_SERIES[k]
        bracket = w * w * w * series / 2
    else:  # inside b
        bracket = 0.0
    return b * b * bracket


@vectorize
def _slip_shapes(x, b):
    """`slip_shape` as a ufunc."""
    return slip_shape(x, b)


def mindlin_deresiewicz_traction(contact: Contact, Q_star: float, Q: float, x: ArrayLike) -> np.ndarray:
    """Traction [Pa] after ``Q`` [N/m] rises to ``Q_star`` and falls back to ``Q``.

    Masing: the change from the turning point is ``-2`` times the monotonic traction of
    ``(Q_star - Q)/2``; the reversed slip zones have ``c/a = sqrt(1 - (Q* - Q)/(2 f P))``.
    """
    return cattaneo_mindlin_traction(contact, Q_star, x) - 2 * cattaneo_mindlin_traction(contact, (Q_star - Q) / 2, x)


def mindlin_deresiewicz_slip(contact: Contact, Q_star: float, Q: float, x: ArrayLike) -> np.ndarray:
    """Slip [m] after ``Q`` [N/m] rises to ``Q_star`` and falls back to ``Q`` (Masing rule)."""
    return cattaneo_mindlin_slip(contact, Q_star, x) - 2 * cattaneo_mindlin_slip(contact, (Q_star - Q) / 2, x)


def bulk_tension_stick_half_width(contact: Contact, sigma: float) -> float:
    """Stick half-width [m] of a Hertz contact under bulk tension ``sigma`` [Pa] alone, eq (23).

    ``K(k) - E(k) = pi |sigma| / (8 f p0)`` with modulus ``k = sqrt(1 - (b/a)^2)`` (SciPy's
    ``ellipk`` and ``ellipe`` take ``m = k^2``).
    """
    target = np.pi * abs(sigma) / (8 * contact.f * contact.p0)
    residual = lambda m: special.ellipk(m) - special.ellipe(m) - target  # noqa: E731 - increasing in m
    m = optimize.brentq(residual, 0.0, 1 - 1e-16, xtol=1e-15)
    return contact.a * np.sqrt(1 - m)


def nowell_hills_offset(contact: Contact, sigma: float) -> float:
    """Stick-zone centre [m] of a Hertz contact under proportional Q > 0 and sigma: ``-sigma a/(4 f p0)``."""
    return -sigma * contact.a / (4 * contact.f * contact.p0)


def nowell_hills_traction(contact: Contact, Q: float, sigma: float, x: ArrayLike) -> np.ndarray:
    """Traction [Pa] of a Hertz contact under proportional ``Q`` [N/m] and ``sigma`` [Pa] from zero.

    Nowell & Hills (1987): ``q = f p0 [sqrt(1 - x^2/a^2) - (b/a) sqrt(1 - (x - e)^2/b^2)]`` with
    ``b = a sqrt(1 - Q/(f P))``, ``e = -sigma a / (4 f p0)`` (signs of docs/theory/conventions.md); valid while
    ``|sigma| <= 2 f p0 Q / (f P)`` and ``|e| + b <= a``. For ``Q < 0`` the signs of ``q`` and ``e`` flip.
    """
    b = stick_half_width(contact, Q)
    e = np.sign(Q) * nowell_hills_offset(contact, sigma)
    return np.sign(Q) * contact.f * contact.p0 * (_ellipse(x, contact.a) - (b / contact.a) * _ellipse(x, b, e))


def ciavarella_jaeger(contact: Contact, Q: float, x: ArrayLike) -> tuple[np.ndarray, Contact]:
    """Traction [Pa] of any symmetric profile under monotonic ``Q`` [N/m], and its corrective contact.

    Ciavarella (1998), Jaeger (1998), section 2 of the seed: ``q = f (p(x; P) - p(x; P_c))`` with
    ``Q = f (P - P_c)``; the stick zone is the contact of the corrective load ``P_c``, so its
    half-width is the returned contact's ``a``.
    """
    corrective = Contact(contact.profile, contact.E_star, contact.f, contact.P - abs(Q) / contact.f)
    q = contact.f * (contact.pressure(x) - corrective.pressure(x))
    return np.sign(Q) * q, corrective


@njit
def slip_series(psi: float, first: int) -> float:
    """``sum_{n >= first} psi^n / (n (n - 1))`` for ``0 <= psi <= 1``, `first` 2 or 3, without cancellation; compiled.

    For ``first = 2`` the sum is ``psi + (1 - psi) ln(1 - psi)``; that form cancels for small
    ``psi`` (to ``psi^2 / 2``), so below ``psi = 1/4`` the series (`SERIES_TERMS` terms) is summed
    instead, by Horner's rule from its smallest term.
    """
    if psi < 0.25:
        summed = 0.0
        for n in range(first + SERIES_TERMS - 1, first - 1, -1):
            summed = summed * psi + 1.0 / (n * (n - 1.0))
        return summed * psi**first
    two = psi + (1 - psi) * math.log1p(-psi) if psi < 1 else 1.0  # at 1 the sum is 1
    return two if first == 2 else two - psi * psi / 2


@vectorize
def _slip_series(psi, first):
    """`slip_series` as a ufunc."""
    return slip_series(psi, first)


def compliance_scale(contact: Contact) -> float:
    """``f p0 a / (2 E_star)`` [m]: `cattaneo_mindlin_compliance` per unit of ``slip_series(psi, 2)``."""
    return contact.f * contact.p0 * contact.a / (2 * contact.E_star)


def dissipation_scale(contact: Contact) -> float:
    """``pi (f p0 a)^2 / (4 E_star)`` [J/m]: `cattaneo_mindlin_dissipation` per unit of ``slip_series(psi, 3)``."""
    return math.pi * (contact.f * contact.p0 * contact.a) ** 2 / (4 * contact.E_star)


def cattaneo_mindlin_compliance(contact: Contact, Q: ArrayLike) -> float | np.ndarray:
    """Tangential displacement ``delta_Q`` [m] of a Hertz contact under monotonic ``Q`` [N/m] (Mindlin 1949).

    The mean slip ``(1/pi) int_0^pi s(a cos th) dth`` of `cattaneo_mindlin_slip`:
    ``delta_Q = (f p0 a / (2 E_star)) (psi + (1 - psi) ln(1 - psi))`` with ``psi = |Q| / (f P)``,
    signed as ``Q``; ``f p0 a psi^2 / (4 E_star)`` to leading order. Elementwise over an array `Q`.
    """
    psi = np.abs(Q) / (contact.f * contact.P)
    return _scalar(np.copysign(compliance_scale(contact) * _slip_series(psi, 2), Q))


def cattaneo_mindlin_dissipation(contact: Contact, Q: ArrayLike) -> float | np.ndarray:
    """Energy [J/m] that a Hertz contact dissipates as ``Q`` [N/m] rises monotonically from zero.

    ``int f p |s| dx`` of `cattaneo_mindlin_slip` (every point slips one way only):
    ``(pi (f p0 a)^2 / (4 E_star)) sum_{n >= 3} psi^n / (n (n - 1))``, ``psi = |Q| / (f P)``.
    Elementwise over an array `Q`.
    """
    psi = np.abs(Q) / (contact.f * contact.P)
    return _scalar(dissipation_scale(contact) * _slip_series(psi, 3))


def _scalar(values: np.ndarray) -> float | np.ndarray:
    """`values` as a float where it is a single number (0-d), else the array."""
    return float(values) if np.ndim(values) == 0 else values


def mindlin_deresiewicz_energy(contact: Contact, Q_star: float) -> float:
    """Energy [J/m] a Hertz contact dissipates per steady cycle of ``Q`` between ``-Q_star`` and ``Q_star`` [N/m].

    Mindlin & Deresiewicz (1953): the area of the Masing loop of ``Q`` against ``delta_Q``,
    ``W = 4 Q* delta_Q(Q*) - 8 int_0^Q* delta_Q(u) du`` with `cattaneo_mindlin_compliance`; each
    of the loop's two branches dissipates twice `cattaneo_mindlin_dissipation` of ``Q*``, so
    ``W = (pi (f p0 a)^2 / E_star) sum_{n >= 3} psi^n / (n (n - 1))``: the cubic law
    ``(pi (f p0 a)^2 / E_star) psi^3 / 6 (1 + psi / 2 + ...)`` for small ``psi = Q* / (f P)``.
    """
    return 4 * cattaneo_mindlin_dissipation(contact, Q_star)


def masing_origin(turning: Sequence[float]) -> tuple[float, float]:
    """Start [N/m] and factor of the branch after the open `turning` points: the last of them and 2
    (Masing), or the virgin state ``Q = 0`` and 1."""
    return (turning[-1], 2.0) if turning else (0.0, 1.0)


def masing_increment(turning: Sequence[float], Q_from: float, Q_to: float) -> tuple[tuple[float, ...], list[Piece]]:
    """Turning-point memory of Masing's rule over one change of the load ``Q`` [N/m].

    The memory is the stack of open turning points ``Q_1, Q_2, ...``: the path from ``0`` to
    ``Q_1`` is the virgin (monotonic) curve, every later branch ``Q_i -> Q_(i+1)`` is twice the
    virgin curve at half the load change (`masing_origin`). A reversal makes ``Q_from`` a
    turning point; a branch that reaches the turning point before its own start closes that
    loop, both points leave the stack and the older branch goes on (return-point memory;
    the virgin curve's bound is ``-Q_1``).

    Parameters
    ----------
    turning : sequence of float
        Open turning points before the change [N/m].
    Q_from, Q_to : float
        Load before and after the change [N/m].

    Returns
    -------
    turning : tuple of float
        Open turning points after the change.
    pieces : list of tuple
        Branch pieces ``(origin, factor, Q_start, Q_end)`` walked, in order; empty if ``Q`` did
        not change.
    """
    turning = list(turning)
    if Q_to == Q_from:
        return tuple(turning), []
    rising = Q_to > Q_from
    origin = masing_origin(turning)[0]
    if Q_from != origin and (Q_from > origin) != rising:  # a reversal
        turning.append(Q_from)
    pieces, start = [], Q_from
    while True:
        closes = None if not turning else (turning[-2] if len(turning) > 1 else -turning[0])
        passes = closes is not None and (Q_to >= closes if rising else Q_to <= closes)
        end = closes if passes else Q_to
        pieces.append((*masing_origin(turning), start, end))
        if not passes:
            return tuple(turning), pieces
        start, turning = end, turning[:-2]


def masing_arrival(turning: Sequence[float], Q_from: float, Q_to: float) -> tuple[float, float]:
    """Start [N/m] and factor of the branch along which the load reaches `Q_to` from `Q_from`, with the open
    `turning` points before the change (`masing_increment`): the stick zone of the change is that branch's.

    It is the branch after the turning points left open, except where the change ends exactly at the turning
    point at which it closes a loop: it arrives there on the closing branch, and the older branch goes on only
    past that point.
    """
    walked = [piece for piece in masing_increment(turning, Q_from, Q_to)[1] if piece[2] != piece[3]]
    return walked[-1][:2] if walked else masing_origin(turning)


def masing_walk(Q: ArrayLike) -> tuple[list[tuple[float, ...]], list[list[Piece]]]:
    """`masing_increment` along a whole history of ``Q`` [N/m] from the virgin state ``Q[0] = 0``.

    Returns
    -------
    stacks : list of tuple
        Open turning points after each step.
    pieces : list of list of tuple
        Branch pieces ``(origin, factor, Q_start, Q_end)`` walked in the increment ending at each
        step (none at step 0).
    """
    Q = np.asarray(Q, dtype=float)
    if Q[0] != 0:
        raise ValueError(f"the Masing walk starts from the virgin state Q = 0, found {Q[0]!r}")
    stacks, pieces = [()], [[]]
    for before, after in itertools.pairwise(Q.tolist()):
        stack, walked = masing_increment(stacks[-1], before, after)
        stacks.append(stack)
        pieces.append(walked)
    return stacks, pieces
