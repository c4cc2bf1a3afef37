"""Published closed-form partial-slip solutions, used as references.

Conventions of docs/theory/conventions.md: positive Q gives positive slip; positive Q and sigma together
move the stick zone toward negative x.
"""

import numpy as np
from scipy import optimize, special

from fretting.physics.contact import Contact

__all__ = [
    "cattaneo_mindlin_traction",
    "cattaneo_mindlin_slip",
    "stick_half_width",
    "mindlin_deresiewicz_traction",
    "mindlin_deresiewicz_slip",
    "bulk_tension_stick_half_width",
    "nowell_hills_traction",
    "nowell_hills_offset",
    "ciavarella_jaeger",
]


def stick_half_width(contact, Q):
    """Stick-zone half-width ``b = a sqrt(1 - |Q|/(f P))`` of a Hertz contact [m], eq (8)."""
    return contact.a * np.sqrt(1 - abs(Q) / (contact.f * contact.P))


def _ellipse(x, half_width, centre=0.0):
    """``sqrt(1 - ((x - centre)/half_width)^2)`` inside the interval, zero outside."""
    return np.sqrt(np.clip(1 - ((np.asarray(x) - centre) / half_width) ** 2, 0, None))


def cattaneo_mindlin_traction(contact, Q, x):
    """Shear traction [Pa] of a Hertz contact under monotonic ``Q`` [N/m], eq (7)."""
    b = stick_half_width(contact, Q)
    shape = _ellipse(x, contact.a) - (b / contact.a) * _ellipse(x, b)
    return np.sign(Q) * contact.f * contact.p0 * shape


def cattaneo_mindlin_slip(contact, Q, x):
    """Slip [m] of a Hertz contact under monotonic ``Q`` [N/m]: eq (19) integrated from ``b``.

    ``s(x) = (f p0 / (E_star a)) [X sqrt(X^2 - b^2) - b^2 arccosh(X / b)]`` with ``X = |x| >= b``.
    """
    b = stick_half_width(contact, Q)
    X = np.maximum(np.abs(np.asarray(x, dtype=float)), b)
    root = np.sqrt(X**2 - b**2)
    integral = X * root - b**2 * np.arccosh(X / b) if b > 0 else X**2
    return np.sign(Q) * contact.f * contact.p0 / (contact.E_star * contact.a) * integral


def mindlin_deresiewicz_traction(contact, Q_star, Q, x):
    """Traction [Pa] after ``Q`` [N/m] rises to ``Q_star`` and falls back to ``Q``.

    Masing: the change from the turning point is ``-2`` times the monotonic traction of
    ``(Q_star - Q)/2``; the reversed slip zones have ``c/a = sqrt(1 - (Q* - Q)/(2 f P))``.
    """
    return cattaneo_mindlin_traction(contact, Q_star, x) - 2 * cattaneo_mindlin_traction(contact, (Q_star - Q) / 2, x)


def mindlin_deresiewicz_slip(contact, Q_star, Q, x):
    """Slip [m] after ``Q`` [N/m] rises to ``Q_star`` and falls back to ``Q`` (Masing rule)."""
    return cattaneo_mindlin_slip(contact, Q_star, x) - 2 * cattaneo_mindlin_slip(contact, (Q_star - Q) / 2, x)


def bulk_tension_stick_half_width(contact, sigma):
    """Stick half-width [m] of a Hertz contact under bulk tension ``sigma`` [Pa] alone, eq (23).

    ``K(k) - E(k) = pi |sigma| / (8 f p0)`` with modulus ``k = sqrt(1 - (b/a)^2)`` (SciPy's
    ``ellipk`` and ``ellipe`` take ``m = k^2``).
    """
    target = np.pi * abs(sigma) / (8 * contact.f * contact.p0)
    residual = lambda m: special.ellipk(m) - special.ellipe(m) - target  # noqa: E731 - increasing in m
    m = optimize.brentq(residual, 0.0, 1 - 1e-16, xtol=1e-15)
    return contact.a * np.sqrt(1 - m)


def nowell_hills_offset(contact, sigma):
    """Stick-zone centre [m] of a Hertz contact under proportional Q > 0 and sigma: ``-sigma a/(4 f p0)``."""
    return -sigma * contact.a / (4 * contact.f * contact.p0)


def nowell_hills_traction(contact, Q, sigma, x):
    """Traction [Pa] of a Hertz contact under proportional ``Q`` [N/m] and ``sigma`` [Pa] from zero.

    Nowell & Hills (1987): ``q = f p0 [sqrt(1 - x^2/a^2) - (b/a) sqrt(1 - (x - e)^2/b^2)]`` with
    ``b = a sqrt(1 - Q/(f P))``, ``e = -sigma a / (4 f p0)`` (signs of docs/theory/conventions.md); valid while
    ``|sigma| <= 2 f p0 Q / (f P)`` and ``|e| + b <= a``. For ``Q < 0`` the signs of ``q`` and ``e`` flip.
    """
    b = stick_half_width(contact, Q)
    e = np.sign(Q) * nowell_hills_offset(contact, sigma)
    return np.sign(Q) * contact.f * contact.p0 * (_ellipse(x, contact.a) - (b / contact.a) * _ellipse(x, b, e))


def ciavarella_jaeger(contact, Q, x):
    """Traction [Pa] of any symmetric profile under monotonic ``Q`` [N/m], and its corrective contact.

    Ciavarella (1998), Jaeger (1998), section 2 of the seed: ``q = f (p(x; P) - p(x; P_c))`` with
    ``Q = f (P - P_c)``; the stick zone is the contact of the corrective load ``P_c``, so its
    half-width is the returned contact's ``a``.
    """
    corrective = Contact(contact.profile, contact.E_star, contact.f, contact.P - abs(Q) / contact.f)
    q = contact.f * (contact.pressure(x) - corrective.pressure(x))
    return np.sign(Q) * q, corrective
