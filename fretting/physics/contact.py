"""The contact: a profile pressed by a constant normal load, with friction."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from fretting._validate import finite, positive
from fretting.physics.profiles import Profile

__all__ = ["POISSON_RANGE", "SPECIMEN", "Contact", "plane_strain_modulus", "poisson_ratio", "stuck_compliance"]

#: Poisson's ratios of an isotropic elastic material, ``-1 < nu <= 0.5``: its bulk and shear moduli are
#: positive for ``-1 < nu < 0.5``, and 0.5 is the incompressible limit, where ``E_star`` stays finite.
POISSON_RANGE = (-1.0, 0.5)

#: The body that is the specimen when none is named: body 2, which carries the traction ``-q`` and,
#: since ``sigma = sigma_b2 - sigma_b1``, the bulk tension ``sigma`` of a pad that carries none.
SPECIMEN = 2


def poisson_ratio(nu: float) -> float:
    """`nu` as a float, checked to be a Poisson's ratio.

    Raises
    ------
    ValueError
        Unless `nu` is a number in `POISSON_RANGE`, ``(-1, 0.5]``.
    """
    nu = finite("nu", nu)
    low, high = POISSON_RANGE
    if not low < nu <= high:
        raise ValueError(
            f"nu must be in ({low:g}, {high:g}] (isotropic: positive bulk and shear moduli, 0.5 incompressible), "
            f"found {nu!r}"
        )
    return nu


def stuck_compliance(L: float, a: float, E_star: float) -> float:
    """Compliance ``C_L = (2 / (pi E_star)) arccosh(L / a)`` [m per N/m] of a fully stuck contact of
    half-width `a` [m] between two similar half-planes of modulus `E_star` [Pa], its displacement
    measured between surface points at the distance `L` > `a` [m] from its middle
    (docs/theory/displacement.md, eq D3): ``(2 / (pi E_star)) ln(2 L / a)`` for ``L >> a``."""
    return 2 * math.acosh(L / a) / (math.pi * E_star)


def plane_strain_modulus(E: float, nu: float) -> float:
    """``E_star = E / (2 (1 - nu^2))`` [Pa] of two bodies of Young's modulus `E` [Pa], Poisson's ratio `nu`.

    The composite modulus of the seed paper (section 2) for elastically similar bodies.

    Raises
    ------
    ValueError
        Unless `E` is a finite number > 0 and `nu` lies in `POISSON_RANGE`, ``(-1, 0.5]``.

    Examples
    --------
    >>> round(plane_strain_modulus(210e9, 0.3) / 1e9, 2)
    115.38
    """
    E, nu = positive("E", E, "Pa"), poisson_ratio(nu)
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
    specimen : {1, 2}
        The body that is the specimen; the other is the pad. Body 1 carries the shear traction
        ``q`` (resultant ``Q``), body 2 ``-q``, and ``sigma = sigma_b2 - sigma_b1``: a specimen in
        bulk tension ``S`` under an unstressed pad is body 2 with ``sigma = S`` (the default,
        `SPECIMEN`), or body 1 with ``sigma = -S``. It changes no mechanics: the nucleation
        quantities and figures are those of the specimen, with its bulk stress.
    nu : float, optional
        Poisson's ratio of the bodies [-], where it is known (a history file that gives ``E`` and
        ``nu``). It changes no mechanics, which `E_star` sets: a result records it (attribute
        ``nu``) for the stress out of the plane, ``sigma_yy = nu (sigma_xx + sigma_zz)``
        (`fretting.analysis.stress.field`).
    datum : float, optional
        Distance ``L`` [m] from the middle of the contact, along the surface, of the points of the
        pad and the specimen whose relative tangential displacement ``delta`` is measured
        (docs/theory/displacement.md); ``L > a``. None: no datum, no ``delta`` (force control only).
    compliance : float
        Rig compliance ``C`` [m per N/m] in series with the contact, ``>= 0``: it adds ``C Q`` to
        ``delta``. Only with a `datum`.

    Attributes
    ----------
    a : float
        Contact half-width [m], from `P`: closed form (`Hertz`), or solved to 1e-10 relative
        (`RoundedFlat`); a `Gap` is as accurate as its Chebyshev expansion (see `Gap`).
    centre : float
        Middle of the contact interval [m]; zero for symmetric profiles.
    p0 : float
        Peak contact pressure [Pa] (the centre pressure for the sharp flat punch).
    displacement_compliance : float or None
        ``d delta / dQ`` [m per N/m] of the fully stuck contact at the datum, with the rig:
        `stuck_compliance` of ``L`` and ``a`` plus ``C``; None without a datum.

    Raises
    ------
    ValueError
        On a bad value, or a profile whose pressure under `P` is not admissible: negative
        somewhere in the contact (a gap that is not convex where the bodies touch), or, for a
        tabulated `Gap`, a contact that leaves its table (`Profile.check`).

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> round(contact.a * 1e3, 4), round(contact.p0 / 1e6, 2)  # a [mm], p0 [MPa]
    (0.2353, 270.58)
    >>> float(contact.pressure(contact.a))  # zero at the edge and outside
    0.0
    """

    def __init__(
        self,
        profile: Profile,
        E_star: float,
        f: float,
        P: float,
        specimen: int = SPECIMEN,
        nu: float | None = None,
        *,
        datum: float | None = None,
        compliance: float = 0.0,
    ) -> None:
        if not isinstance(profile, Profile):
            raise ValueError(f"profile must be a fretting Profile, found {profile!r}")
        if isinstance(specimen, bool) or specimen not in (1, 2):
            raise ValueError(f"specimen must be 1 (the body with traction q) or 2 (traction -q), found {specimen!r}")
        self.profile = profile
        self.E_star = positive("E_star", E_star, "Pa")
        self.f = positive("f", f)
        self.P = positive("P", P, "N/m")
        self.specimen = int(specimen)
        self.nu = None if nu is None else poisson_ratio(nu)
        self.a, self.centre = (float(v) for v in profile.half_width(self.P, self.E_star))
        if not self.a > 0:  # a load so small that the half-width rounds to nothing
            raise ValueError(
                f"P = {P!r} N/m gives a contact half-width a = {self.a!r} m on E_star = {self.E_star!r} Pa; "
                f"expected a normal load that forms a contact of non-zero width"
            )
        profile.check(self.a, self.centre, self.P, self.E_star)
        self.p0 = float(profile.peak_pressure(self.a, self.centre, self.P, self.E_star))
        force = self.f * self.p0 * self.a  # [N/m]; squared by a product, which overflows to inf, not an error
        energy = force * force / self.E_star  # [J/m]: the scale of every energy of the contact
        if not math.isfinite(energy):
            raise ValueError(
                f"f = {f!r} with p0 = {self.p0:.4g} Pa, a = {self.a:.4g} m: the contact's energy scale "
                f"(f p0 a)^2 / E_star overflows a float; expected a friction coefficient that keeps it finite"
            )
        self.datum = None if datum is None else positive("datum", datum)
        if self.datum is not None and not self.datum > self.a:
            raise ValueError(
                f"datum must be a distance L > a = {self.a!r} m from the middle of the contact, found {datum!r}"
            )
        self.compliance = finite("compliance", compliance)
        if self.compliance < 0:
            raise ValueError(f"compliance must be >= 0 [m per N/m], found {compliance!r}")
        if self.compliance and self.datum is None:
            raise ValueError("compliance needs a datum: give datum=L, the distance at which delta is measured")
        self.displacement_compliance = (
            None if self.datum is None else stuck_compliance(self.datum, self.a, self.E_star) + self.compliance
        )

    def __repr__(self):
        nu = "" if self.nu is None else f", nu={self.nu!r}"
        datum = "" if self.datum is None else f", datum={self.datum!r}, compliance={self.compliance!r}"
        return (
            f"Contact({self.profile!r}, E_star={self.E_star!r}, f={self.f!r}, P={self.P!r}, "
            f"specimen={self.specimen!r}{nu}{datum})"
        )

    def displacement(self, Q: float, delta_Q: float, P: float | None = None) -> float:
        """Tangential displacement ``delta`` [m] of the pad relative to the specimen at the datum under
        the shear force `Q` [N/m] with the slip part `delta_Q` [m] and the normal load `P` [N/m] (None:
        the contact's): ``(C_L + C) Q + delta_Q`` (docs/theory/displacement.md, eq D4), ``C_L`` of the
        half-width under `P` (`compliance_under`). Only for a contact with a datum."""
        return self.compliance_under(P) * Q + delta_Q

    def compliance_under(self, P: float | None = None) -> float:
        """``d delta / dQ`` [m per N/m] of the fully stuck contact at the datum, with the rig, under the
        normal load `P` [N/m] (None: the contact's, `displacement_compliance`): `stuck_compliance` of
        ``L`` and the half-width ``a(P)`` plus ``C`` (docs/theory/displacement.md#varying-load). Only
        for a contact with a datum.

        Raises
        ------
        ValueError
            Where the contact under `P` reaches the datum, ``a(P) >= L``.
        """
        if P is None or P == self.P:
            return self.displacement_compliance
        a = float(self.profile.half_width(P, self.E_star)[0])
        if not a < self.datum:
            raise ValueError(
                f"the normal load P = {P!r} N/m forms a contact of half-width a = {a!r} m, "
                f"not within the datum L = {self.datum!r} m; expected a datum beyond the largest contact"
            )
        return stuck_compliance(self.datum, a, self.E_star) + self.compliance

    def pressure(self, x: ArrayLike) -> np.ndarray:
        """Contact pressure ``p(x)`` [Pa] at positions `x` [m]; zero outside the contact."""
        t = (np.asarray(x, dtype=float) - self.centre) / self.a
        inside = np.abs(t) < 1
        p = np.zeros(t.shape)
        p[inside] = self.profile.pressure(t[inside], self.a, self.centre, self.P, self.E_star)
        return p

    def pressure_weighted(self, t: ArrayLike) -> np.ndarray:
        """``p sqrt(1 - t^2)`` [Pa] at normalised positions ``t`` in (-1, 1), bounded for all profiles."""
        t = np.asarray(t, dtype=float)
        return self.profile.pressure(t, self.a, self.centre, self.P, self.E_star) * np.sqrt(1 - t**2)
