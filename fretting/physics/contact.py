"""The contact: a profile pressed by a constant normal load, with friction."""

import numpy as np

from fretting._validate import positive
from fretting.physics.profiles import Profile

__all__ = ["Contact", "plane_strain_modulus"]


def plane_strain_modulus(E, nu):
    """``E_star = E / (2 (1 - nu^2))`` [Pa] of two bodies of Young's modulus `E` [Pa], Poisson's ratio `nu`.

    The composite modulus of the seed paper (section 2) for elastically similar bodies.
    """
    return E / (2 * (1 - nu**2))


class Contact:
    """Two elastically similar half-planes pressed together by a constant normal load.

    Parameters
    ----------
    profile : Profile
        Shape of the gap, e.g. ``Hertz(R)``, ``RoundedFlat(b, R)``, ``FlatPunch(a)``, ``Gap(h0)``.
    E_star : float
        Plane-strain composite modulus ``E / (2 (1 - nu^2))`` of the seed paper [Pa].
    f : float
        Coulomb friction coefficient [-].
    P : float
        Normal load per unit length [N/m].

    Attributes
    ----------
    a : float
        Contact half-width [m], from `P` (closed form, or solved to 1e-10 relative).
    centre : float
        Middle of the contact interval [m]; zero for symmetric profiles.
    p0 : float
        Peak contact pressure [Pa] (the centre pressure for the sharp flat punch).
    """

    def __init__(self, profile, E_star, f, P):
        if not isinstance(profile, Profile):
            raise ValueError(f"profile must be a fretting Profile, found {profile!r}")
        self.profile = profile
        self.E_star = positive("E_star", E_star)
        self.f = positive("f", f)
        self.P = positive("P", P)
        self.a, self.centre = (float(v) for v in profile.half_width(self.P, self.E_star))
        self.p0 = float(profile.peak_pressure(self.a, self.centre, self.P, self.E_star))

    def __repr__(self):
        return f"Contact({self.profile!r}, E_star={self.E_star!r}, f={self.f!r}, P={self.P!r})"

    def pressure(self, x):
        """Contact pressure ``p(x)`` [Pa] at positions `x` [m]; zero outside the contact."""
        t = (np.asarray(x, dtype=float) - self.centre) / self.a
        inside = np.abs(t) < 1
        p = np.zeros(t.shape)
        p[inside] = self.profile.pressure(t[inside], self.a, self.centre, self.P, self.E_star)
        return p

    def pressure_weighted(self, t):
        """``p sqrt(1 - t^2)`` [Pa] at normalised positions ``t`` in (-1, 1), bounded for all profiles."""
        t = np.asarray(t, dtype=float)
        return self.profile.pressure(t, self.a, self.centre, self.P, self.E_star) * np.sqrt(1 - t**2)
