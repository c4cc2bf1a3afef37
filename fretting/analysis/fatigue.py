"""Multiaxial fatigue criteria on the critical plane, strain-life and the theory of critical distances.

Pure functions of a stress history at points: arrays ``sigma_xx``, ``sigma_zz``, ``tau_xz`` and
``sigma_yy`` [Pa] with the time axis first and any trailing shape of points (``x`` along the
surface, ``z`` the depth, ``y`` out of the plane; ``tau_xy = tau_yz = 0``, so ``sigma_yy`` is a
principal stress; plane strain gives ``sigma_yy = nu (sigma_xx + sigma_zz)``, the default). The
history is taken as one cycle. `apply` maps a criterion over a stress field, a Dataset on dims
``(step, z, x)``; `point_method` and `line_method` read such a map at a critical distance. Each
criterion has a life through a stated S-N relation (`life`). `threshold` runs a contact's history
over its amplitude of ``Q`` to find where a criterion read at the critical distance reaches its
fatigue limit or a life; `threshold_of` does so over any quantity of a scene (the amplitude of
``sigma``, a pad radius, ...). `materials` lists the shipped material files.

Planes. A plane is named by its unit normal ``n = (sin(theta) cos(phi), cos(theta), sin(theta)
sin(phi))`` in ``(x, y, z)``: ``phi`` [rad] from ``+x`` toward ``+z`` (depth), in ``[-pi/2,
pi/2)``, and ``theta`` [rad] from the out-of-plane axis ``y``. The in-plane family,
``theta = pi/2``, holds the planes that contain ``y``; on them

    sigma_n = (sigma_xx + sigma_zz)/2 + (sigma_xx - sigma_zz)/2 cos(2 phi) + tau_xz sin(2 phi),
    tau = tau_xz cos(2 phi) - (sigma_xx - sigma_zz)/2 sin(2 phi),

and the shear stress has the fixed direction ``(-sin(phi), 0, cos(phi))``, so its amplitude is half
its range. Its search: `SAMPLES` planes, then a golden-section search on either side of the `PEAKS`
best sampled peaks, to `XTOL`. Planes tilted out of the family (``theta < pi/2``) carry
``sigma_n = sin^2(theta) sigma_n(phi) + cos^2(theta) sigma_yy`` and a shear vector with components
``sin(theta) tau(phi)`` and ``sin(theta) cos(theta) (sigma_n(phi) - sigma_yy)``, which turns in the
plane when the loading is not proportional; its amplitude is then half the longest chord of its
path. They govern where the in-plane stresses are nearly equal (under the middle of a contact,
where ``sigma_xx ~ sigma_zz``, the shear of the x-z planes vanishes and that between ``x`` and
``y`` does not), so ``planes="all"`` adds them, sampled on the same angular step (no refine). The
normals with ``phi`` in ``[-pi/2, pi/2)`` and ``theta`` in ``[0, pi/2]`` stand for all planes: a normal
and its opposite name one plane, and the reflection ``y -> -y`` leaves the stress unchanged.

The strain on a plane is elastic (Hooke's law, isotropic): the normal strain
``eps_n = ((1 + nu) sigma_n - nu (sigma_xx + sigma_yy + sigma_zz)) / E`` and the engineering
shear strain ``gamma = tau / G``, ``G = E / (2 (1 + nu))``.

References
----------
.. [1] K. N. Smith, P. Watson and T. H. Topper, A stress-strain function for the fatigue of
   metals, Journal of Materials 5 (1970) 767-778.
.. [2] W. N. Findley, A theory for the effect of mean stress on fatigue of metals under combined
   torsion and axial load or bending, Journal of Engineering for Industry 81 (1959) 301-306.
.. [3] A. Fatemi and D. F. Socie, A critical plane approach to multiaxial fatigue damage
   including out-of-phase loading, Fatigue Fract. Engng Mater. Struct. 11 (1988) 149-165.
.. [4] L. Susmel and P. Lazzarin, A bi-parametric Wohler curve for high cycle multiaxial fatigue
   assessment, Fatigue Fract. Engng Mater. Struct. 25 (2002) 63-78.
.. [5] L. Susmel and D. Taylor, Two methods for predicting the multiaxial fatigue limits of sharp
   notches, Fatigue Fract. Engng Mater. Struct. 26 (2003) 821-833.
.. [6] B. Crossland, Effect of large hydrostatic pressures on the torsional fatigue strength of an
   alloy steel, Proc. Int. Conf. on Fatigue of Metals, IMechE, London (1956) 138-149.
.. [7] O. H. Basquin, The exponential law of endurance tests, Proc. ASTM 10 (1910) 625-630;
   L. F. Coffin, Trans. ASME 76 (1954) 931-950; S. S. Manson, NACA TN 2933 (1953).
.. [8] D. Taylor, Geometrical effects in fatigue: a unifying theoretical model, International
   Journal of Fatigue 21 (1999) 413-420.
.. [9] J. A. Araujo and D. Nowell, The effect of rapidly varying contact stress fields on
   fretting fatigue, International Journal of Fatigue 24 (2002) 763-775.
.. [10] D. F. Socie and G. B. Marquis, Multiaxial Fatigue, SAE International, Warrendale (2000),
   chapter 4 (critical plane models; the Fatemi-Socie parameter and its shear strain-life curve).
.. [11] P. Lazzarin and L. Susmel, A stress-based method to predict lifetime under multiaxial fatigue
   loadings, Fatigue Fract. Engng Mater. Struct. 26 (2003) 1171-1187.
.. [12] K. Dang Van, B. Griveau and O. Message, On a new multiaxial fatigue limit criterion: theory and
   application, in M. W. Brown and K. J. Miller (eds), Biaxial and Multiaxial Fatigue, EGF 3, Mechanical
   Engineering Publications, London (1989) 479-496.
.. [13] I. V. Papadopoulos, P. Davoli, C. Gorla, M. Filippini and A. Bernasconi, A comparative study of
   multiaxial high-cycle fatigue criteria for metals, International Journal of Fatigue 19 (1997) 219-235.
.. [14] E. Welzl, Smallest enclosing disks (balls and ellipsoids), in H. Maurer (ed), New Results and
   New Trends in Computer Science, Lecture Notes in Computer Science 555, Springer (1991) 359-370.
.. [15] M. H. El Haddad, T. H. Topper and K. N. Smith, Prediction of non propagating cracks, Engineering
   Fracture Mechanics 11 (1979) 573-584.
"""

from __future__ import annotations

import abc
import errno
import itertools
import math
import os
import re
import tomllib
from collections.abc import Callable
from dataclasses import dataclass, fields
from pathlib import Path
from typing import NamedTuple

import numpy as np
import xarray as xr
from scipy.interpolate import RegularGridInterpolator
from scipy.optimize import brentq

from fretting._validate import finite, positive
from fretting.analysis.nucleation import complete_cycles
from fretting.analysis.stress import field as stress_field
from fretting.engine.simulation import simulate
from fretting.errors import FrettingError
from fretting.loading.examples import EXAMPLES
from fretting.physics.contact import plane_strain_modulus

__all__ = [
    "CRITERIA",
    "PEAKS",
    "READINGS",
    "SAMPLES",
    "XTOL",
    "BracketError",
    "Criterion",
    "CriticalDistance",
    "Invariant",
    "Material",
    "MATERIALS",
    "MaterialFileError",
    "Plane",
    "THRESHOLD_GRID",
    "THRESHOLD_XTOL",
    "Threshold",
    "apply",
    "crossland",
    "crossland_life",
    "dang_van",
    "dang_van_life",
    "fatemi_socie",
    "fatemi_socie_life",
    "findley",
    "findley_life",
    "hot_spot",
    "life",
    "line_method",
    "material_path",
    "materials",
    "mwcm",
    "mwcm_life",
    "point_method",
    "read_last_cycle",
    "swt",
    "swt_life",
    "threshold",
    "threshold_of",
]

#: Planes sampled over ``phi`` in ``[-pi/2, pi/2)`` (0.5 degree apart) before the refine.
SAMPLES = 360

#: Sampled peaks refined, the best first: a history sampled in time can give the parameter twin peaks
#: closer than a sample step, and the sample nearer the lower one may be the higher.
PEAKS = 2

#: Width [rad] of the bracket that ends the golden-section refine of the in-plane family: near a smooth
#: maximum the parameter changes by less than its rounding over about 1e-8 rad, so no search locates the
#: angle more closely; the parameter itself is then found to rounding.
XTOL = 1e-8

#: Sampled planes whose searched quantity is within this fraction of the best are tied (`planes="all"`).
TIE_RTOL = 1e-9

#: Elements of the arrays of one block of planes: the sample stage's memory bound.
BLOCK = 2_000_000

#: Relative margin on squared distances within which a point counts as inside a ball (Dang Van's enclosing ball
#: of the deviatoric path): points on the sphere itself come out a few roundings either side of it.
ENCLOSED_RTOL = 1e-12

#: Directions sampled over ``[-pi/2, pi/2]`` by the critical distances' ``direction="max"``.
DIRECTIONS = 181


class MaterialFileError(FrettingError, ValueError):
    """A material file is malformed; the message reads ``file: key: problem``."""

    def __init__(self, path, key, problem):
        self.path, self.key, self.problem = path, key, problem
        super().__init__(f"{path}: {key}: {problem}" if key else f"{path}: {problem}")


@dataclass(frozen=True)
class Material:
    """Elastic and fatigue constants of the specimen's material. Only `E` and `nu` are required.

    Parameters
    ----------
    E : float
        Young's modulus [Pa].
    nu : float
        Poisson's ratio, in ``(-1, 0.5]``.
    sigma_f, b, eps_f, c : float, optional
        Strain-life constants [7]: fatigue strength coefficient ``sigma_f'`` [Pa] > 0 and exponent
        ``b`` < 0, fatigue ductility coefficient ``eps_f'`` > 0 and exponent ``c`` < 0 (`swt_life`).
    sigma_limit, tau_limit : float, optional
        Fully reversed fatigue limits [Pa] in bending (or push-pull), ``f_-1``, and in torsion,
        ``t_-1``: they give Findley's ``k`` (unless `findley_k` is given), the MWCM's ``kappa``,
        ``lambda`` and Crossland's ``alpha``, ``beta``.
    findley_k : float, optional
        Findley's normal stress sensitivity ``k`` >= 0 [2].
    fs_k, sigma_y : float, optional
        Fatemi-Socie's ``k`` >= 0 and the yield stress ``sigma_y`` [Pa] > 0 that normalises it [3].
    tau_f, b0, gamma_f, c0 : float, optional
        Shear strain-life constants [3, 10]: shear fatigue strength coefficient ``tau_f'`` [Pa] > 0 and
        exponent ``b0`` < 0 (the fully reversed torsion Basquin curve ``tau_a = tau_f' (2 N_f)^b0``), shear
        fatigue ductility coefficient ``gamma_f'`` > 0 and exponent ``c0`` < 0 (`fatemi_socie_life`; ``b0``
        also `mwcm_life`).
    N_A : float, optional
        Cycles > 0 at which the fatigue limits `sigma_limit` and `tau_limit` are taken, the reference life
        of the MWCM's curves [11] (`mwcm_life`), commonly 2e6.
    critical_distance : float, optional
        ``L`` [m] > 0 of the theory of critical distances [8], commonly
        ``(1/pi) (Delta K_th / Delta sigma_0)^2``; without it, `critical_length` gives that from
        `delta_K_th` and `sigma_limit`.
    delta_K_th : float, optional
        Threshold range of the stress intensity factor of long cracks ``Delta K_th`` [Pa m^0.5] > 0, at the
        stress ratio of `sigma_limit` (fully reversed): with `sigma_limit`, El Haddad's length [15, 8].

    Raises
    ------
    ValueError
        Naming the first constant out of its range.
    """

    E: float
    nu: float
    sigma_f: float | None = None
    b: float | None = None
    eps_f: float | None = None
    c: float | None = None
    sigma_limit: float | None = None
    tau_limit: float | None = None
    findley_k: float | None = None
    fs_k: float | None = None
    sigma_y: float | None = None
    tau_f: float | None = None
    b0: float | None = None
    gamma_f: float | None = None
    c0: float | None = None
    N_A: float | None = None
    critical_distance: float | None = None
    delta_K_th: float | None = None

    def __post_init__(self):
        plane_strain_modulus(self.E, self.nu)  # checks E and nu as a contact's
        for name in ("sigma_f", "eps_f", "sigma_limit", "tau_limit", "sigma_y", "tau_f", "gamma_f", "N_A"):
            self._check(name, positive)
        for name in ("critical_distance", "delta_K_th"):
            self._check(name, positive)
        for name in ("b", "c", "b0", "c0"):
            self._check(name, _negative)
        for name in ("findley_k", "fs_k"):
            self._check(name, _non_negative)

    def _check(self, name, validate):
        value = getattr(self, name)
        if value is not None:
            object.__setattr__(self, name, validate(name, value))

    @classmethod
    def from_file(cls, path: str | os.PathLike) -> Material:
        """The material of a TOML file whose top-level keys are the parameters' names.

        Raises
        ------
        OSError
            When the file cannot be read.
        MaterialFileError
            ``file: key: found ..., expected ...`` for a malformed file, an unknown or missing key,
            or a value out of range.
        """
        path = Path(path)
        try:
            data = tomllib.loads(path.read_text(encoding="utf-8"))
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
            raise MaterialFileError(path, None, f"found invalid TOML ({error}), expected key = number lines") from None
        names = [field.name for field in fields(cls)]
        for key, value in data.items():
            if key not in names:
                raise MaterialFileError(path, key, f"unknown key, expected one of: {', '.join(names)}")
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise MaterialFileError(path, key, f"found {value!r}, expected a number")
        for key in ("E", "nu"):
            if key not in data:
                raise MaterialFileError(path, key, "missing, expected a number")
        try:
            return cls(**data)
        except ValueError as error:
            parsed = re.match(r"(\w+) must (?:be )?(.*), found", str(error))
            key, expected = parsed.groups() if parsed else (None, str(error))
            raise MaterialFileError(path, key, f"found {data.get(key)!r}, expected {expected}") from None

    def critical_length(self, who="critical_length") -> float:
        """``L`` [m] of the theory of critical distances: `critical_distance`, else El Haddad's length.

        El Haddad, Topper & Smith [15] (in Taylor's form [8]): ``L = (1/pi) (Delta K_th / Delta sigma_0)^2``, the
        crack length at which a long crack at its threshold ``Delta K_th = Delta sigma sqrt(pi a)`` carries the
        plain fatigue limit; ``Delta sigma_0 = 2 f_-1``, the range of the fully reversed limit `sigma_limit`,
        with `delta_K_th` at the same stress ratio.

        Raises
        ------
        ValueError
            ``material: <who> needs critical_distance, found None (or delta_K_th and sigma_limit)``.
        """
        if self.critical_distance is not None:
            return self.critical_distance
        if self.delta_K_th is None or self.sigma_limit is None:
            raise ValueError(f"material: {who} needs critical_distance, found None (or delta_K_th and sigma_limit)")
        return (self.delta_K_th / (2 * self.sigma_limit)) ** 2 / math.pi

    @property
    def G(self) -> float:
        """Shear modulus ``E / (2 (1 + nu))`` [Pa]."""
        return self.E / (2 * (1 + self.nu))

    def _required(self, criterion, *names):
        missing = [name for name in names if getattr(self, name) is None]
        if missing:
            raise ValueError(f"material: {criterion} needs {', '.join(missing)}, found None")
        return [getattr(self, name) for name in names]

    def findley_constant(self) -> float:
        """Findley's ``k``: `findley_k`, or from the fatigue limits.

        With ``r = f_-1 / t_-1``, the fully reversed push-pull limit gives ``(f_-1/2)
        (sqrt(1 + k^2) + k)`` and the torsion limit ``t_-1 sqrt(1 + k^2)``; equal, they give
        ``k = (2 - r) / (2 sqrt(r - 1))``, for ``1 < r < 2``.
        """
        if self.findley_k is not None:
            return self.findley_k
        f, t = self._required("findley", "sigma_limit", "tau_limit")
        r = f / t
        if not 1 < r < 2:
            raise ValueError(f"material: findley needs 1 < sigma_limit / tau_limit < 2 for k, found {r:.6g}")
        return (2 - r) / (2 * math.sqrt(r - 1))

    def findley_limit(self) -> float:
        """Findley's parameter at the fatigue limit, ``t_-1 sqrt(1 + k^2)`` [Pa]: fully reversed torsion at ``t_-1``."""
        k = self.findley_constant()
        (t,) = self._required("findley", "tau_limit")
        return t * math.sqrt(1 + k * k)

    def mwcm_constants(self) -> tuple[float, float]:
        """``(kappa, lambda)`` [Pa] of the MWCM at the fatigue limit, ``tau_a + kappa rho <= lambda`` [4].

        ``lambda = t_-1``, ``kappa = t_-1 - f_-1 / 2``: the line through torsion (``rho = 0``) and push-pull
        (``rho = 1``).
        """
        f, t = self._required("mwcm", "sigma_limit", "tau_limit")
        return t - f / 2, t

    def crossland_constants(self) -> tuple[float, float]:
        """``(alpha, beta)`` of Crossland's limit ``sqrt(J2)_a + alpha sigma_h,max <= beta`` [6].

        ``beta = t_-1`` and ``alpha = 3 t_-1 / f_-1 - sqrt(3)`` (fully reversed torsion and push-pull).
        """
        f, t = self._required("crossland", "sigma_limit", "tau_limit")
        return 3 * t / f - math.sqrt(3), t

    def dang_van_constants(self) -> tuple[float, float]:
        """``(a, b)`` of Dang Van's limit ``tau(t) + a sigma_h(t) <= b`` [12].

        ``b = t_-1`` and ``a = 3 (t_-1 / f_-1 - 1/2)``, from fully reversed torsion (``tau = t_-1``,
        ``sigma_h = 0``) and push-pull (``tau = f_-1 / 2`` and ``sigma_h = f_-1 / 3`` at the peak); ``a >= 0``,
        so ``f_-1 / t_-1 <= 2``.
        """
        f, t = self._required("dang_van", "sigma_limit", "tau_limit")
        if f / t > 2:
            raise ValueError(f"material: dang_van needs sigma_limit / tau_limit <= 2 for a >= 0, found {f / t:.6g}")
        return 3 * (t / f - 0.5), t


def _negative(name, value):
    number = finite(name, value)
    if number >= 0:
        raise ValueError(f"{name} must be < 0, found {value!r}")
    return number


def _non_negative(name, value):
    number = finite(name, value)
    if number < 0:
        raise ValueError(f"{name} must be >= 0, found {value!r}")
    return number


class Plane(NamedTuple):
    """A critical-plane criterion at each point (arrays of the points' shape).

    Attributes
    ----------
    parameter : numpy.ndarray
        The criterion's parameter on its critical plane.
    phi, theta : numpy.ndarray
        The critical plane's normal [rad] (module docstring); ``theta = pi/2`` for the in-plane family.
    sigma_n_max : numpy.ndarray
        Largest normal stress on that plane over the history [Pa].
    amplitude : numpy.ndarray
        The criterion's amplitude on that plane: ``eps_a`` (SWT), ``tau_a`` [Pa] (Findley, MWCM),
        ``gamma_a`` (Fatemi-Socie).
    """

    parameter: np.ndarray
    phi: np.ndarray
    theta: np.ndarray
    sigma_n_max: np.ndarray
    amplitude: np.ndarray


class Invariant(NamedTuple):
    """A criterion on no plane at each point: `parameter`, its shear `amplitude` [Pa] (``sqrt(J2)_a`` for Crossland,
    the largest mesoscopic shear stress for Dang Van) and the largest mean stress ``sigma_h,max`` [Pa]."""

    parameter: np.ndarray
    amplitude: np.ndarray
    sigma_h_max: np.ndarray


class _History(NamedTuple):
    """A stress history flattened to ``(time, point)``: the terms of the plane stresses."""

    mean: np.ndarray  # (sigma_xx + sigma_zz) / 2
    half: np.ndarray  # (sigma_xx - sigma_zz) / 2
    tau_xz: np.ndarray
    sigma_yy: np.ndarray
    shape: tuple


def _history(sigma_xx, sigma_zz, tau_xz, sigma_yy, nu):
    arrays = {"sigma_xx": sigma_xx, "sigma_zz": sigma_zz, "tau_xz": tau_xz}
    if sigma_yy is not None:
        arrays["sigma_yy"] = sigma_yy
    arrays = {name: np.asarray(value, dtype=float) for name, value in arrays.items()}
    shape = arrays["sigma_xx"].shape
    if not shape:
        raise ValueError("sigma_xx: found a number, expected an array with the time axis first")
    for name, array in arrays.items():
        if array.shape != shape:
            raise ValueError(f"{name}: found shape {array.shape}, expected that of sigma_xx {shape}, time axis first")
        if not np.all(np.isfinite(array)):
            raise ValueError(f"{name}: expected finite stresses [Pa], found NaN or inf")
    xx, zz, xz = (arrays[name].reshape(shape[0], -1) for name in ("sigma_xx", "sigma_zz", "tau_xz"))
    yy = arrays["sigma_yy"].reshape(shape[0], -1) if sigma_yy is not None else nu * (xx + zz)
    return _History((xx + zz) / 2, (xx - zz) / 2, xz, yy, shape[1:])


def _plane_stresses(history, phi, theta):
    """Normal stress and shear components on the planes ``(phi, theta)``: arrays ``(time, point, plane)``."""
    c2, s2 = np.cos(2 * phi), np.sin(2 * phi)
    mean, half, xz, yy = (term[..., None] for term in history[:4])
    sigma_n = mean + half * c2 + xz * s2
    tau = xz * c2 - half * s2
    if np.all(theta == np.pi / 2):
        return sigma_n, (tau,)
    s, c = np.sin(theta), np.cos(theta)
    return s * s * sigma_n + c * c * yy, (s * tau, s * c * (sigma_n - yy))


def _half_range(values):
    return (values.max(axis=0) - values.min(axis=0)) / 2


def _half_longest_chord(components):
    """Half the longest chord of a path in time (axis 0), of one or more components."""
    if len(components) == 1:
        return _half_range(components[0])
    return _longest_chord(components, ends=False)[0]


def _longest_chord(components, ends=True):
    """Half the longest chord of a path in time (axis 0) of components ``(time, *points)`` and, with `ends`, the
    instants of its two ends (else None): arrays of the points' shape."""
    longest = np.zeros(components[0].shape[1:])
    first = second = np.zeros(longest.shape, dtype=int) if ends else None
    for i in range(components[0].shape[0] - 1):
        squared = sum((part[i + 1 :] - part[i]) ** 2 for part in components)
        if not ends:
            longest = np.maximum(longest, squared.max(axis=0))
            continue
        later = np.argmax(squared, axis=0)
        value = np.take_along_axis(squared, later[None], axis=0)[0]
        better = value > longest
        longest = np.where(better, value, longest)
        first, second = np.where(better, i, first), np.where(better, i + 1 + later, second)
    return np.sqrt(longest) / 2, first, second


class _Terms(NamedTuple):
    sigma_n_max: np.ndarray
    tau_a: np.ndarray
    eps_a: np.ndarray


def _terms(history, material, phi, theta, strain):
    """`_Terms` on the planes ``(phi, theta)`` at every point: arrays ``(point, plane)``.

    With `strain`, ``eps_a`` and not ``tau_a`` (None); without, the reverse: no criterion reads both.
    """
    sigma_n, shear = _plane_stresses(history, phi, theta)
    if not strain:
        return _Terms(sigma_n.max(axis=0), _half_longest_chord(shear), None)
    trace = (2 * history.mean + history.sigma_yy)[..., None]
    eps_n = ((1 + material.nu) * sigma_n - material.nu * trace) / material.E
    return _Terms(sigma_n.max(axis=0), None, _half_range(eps_n))


@dataclass(frozen=True)
class Criterion(abc.ABC):
    """A fatigue criterion, declared once, in `CRITERIA`: what it computes and the names of its results.

    Attributes
    ----------
    name : str
        Its key in `CRITERIA`, the name `apply` and ``fretting stress --criterion`` take.
    units, long_name : str
        Of its parameter.
    amplitude_units, amplitude_name : str
        Of its amplitude.
    life : callable
        ``(maps, material) -> N_f``: cycles to failure from the maps of `apply` (`life`), by `life_name`.
    life_name : str
        Its S-N relation.
    limit : callable or None
        ``material -> value``: the parameter at the fatigue limit [its units]; None for a criterion with none
        (SWT, Fatemi-Socie: a life only).
    """

    name: str
    units: str
    long_name: str
    amplitude_units: str
    amplitude_name: str
    life: Callable[[xr.Dataset, Material], np.ndarray]
    life_name: str
    limit: Callable[[Material], float] | None

    @abc.abstractmethod
    def evaluate(self, history: _History, material: Material, planes: str) -> Plane | Invariant:
        """The criterion at every point of `history` (`_history`), on `planes` where it has a plane."""


@dataclass(frozen=True)
class _OnPlane(Criterion):
    """A critical-plane criterion: its parameter and amplitude from `_Terms`, and what its plane maximises."""

    parameter: Callable[[_Terms, Material], np.ndarray]
    amplitude: Callable[[_Terms, Material], np.ndarray]
    strain: bool = False  # reads eps_a, not tau_a
    plane_by_shear: bool = False  # the plane of largest tau_a (ties: largest sigma_n_max), not of the parameter

    def evaluate(self, history, material, planes):
        return _critical_plane(self, history, material, planes)

    def searched(self, terms, material):
        return terms.tau_a if self.plane_by_shear else self.parameter(terms, material)


@dataclass(frozen=True)
class _Invariant(Criterion):
    """A criterion of stress invariants, on no plane: `invariant` gives it from `_History`."""

    invariant: Callable[[_History, Material], Invariant]

    def evaluate(self, history, material, planes):
        return self.invariant(history, material)


def _critical_plane(criterion, history, material, planes):
    if planes not in ("in-plane", "all"):
        raise ValueError(f"planes: found {planes!r}, expected 'in-plane' or 'all'")
    phi = _in_plane_search(criterion, history, material)
    theta = np.full(phi.shape, np.pi / 2)
    if planes == "all":
        step = np.pi / SAMPLES
        grid_phi, grid_theta = (
            grid.ravel() for grid in np.meshgrid(-np.pi / 2 + step * np.arange(SAMPLES), step * np.arange(SAMPLES // 2))
        )
        tilted_phi, tilted_theta = _best_sample(criterion, history, material, grid_phi, grid_theta)
        better = _searched_at(criterion, history, material, tilted_phi, tilted_theta) > _searched_at(
            criterion, history, material, phi, theta
        )
        phi, theta = np.where(better, tilted_phi, phi), np.where(better, tilted_theta, theta)
    terms = _terms_at(history, material, phi, theta, criterion.strain)
    values = (criterion.parameter(terms, material), phi, theta, terms.sigma_n_max, criterion.amplitude(terms, material))
    return Plane(*(value.reshape(history.shape) for value in values))


def _terms_at(history, material, phi, theta, strain):
    """`_Terms` on one plane per point: ``phi``, ``theta`` and the terms of shape ``(point,)``."""
    terms = _terms(history, material, phi[:, None], theta[:, None], strain)
    return _Terms(*(None if term is None else term[:, 0] for term in terms))


def _searched_at(criterion, history, material, phi, theta):
    return criterion.searched(_terms_at(history, material, phi, theta, criterion.strain), material)


def _sampled(criterion, history, material, phis, thetas):
    """The searched quantity and ``sigma_n,max`` on the planes ``(phis, thetas)``: arrays ``(point, plane)``."""
    nt, m = history.mean.shape
    per_block = max(1, BLOCK // (nt * m))
    searched, normal = [], []
    for start in range(0, phis.size, per_block):
        chunk = slice(start, start + per_block)
        terms = _terms(history, material, phis[chunk], thetas[chunk], criterion.strain)
        searched.append(criterion.searched(terms, material))
        normal.append(terms.sigma_n_max)
    return np.concatenate(searched, axis=1), np.concatenate(normal, axis=1)


def _best_sample(criterion, history, material, phis, thetas):
    """The sampled plane ``(phi, theta)`` of each point of largest searched quantity (ties: largest sigma_n,max)."""
    searched, normal = _sampled(criterion, history, material, phis, thetas)
    best = searched.max(axis=1, keepdims=True)
    tied = searched >= best - TIE_RTOL * np.abs(best)
    index = np.argmax(np.where(tied, normal, -np.inf), axis=1)
    return phis[index], thetas[index]


def _in_plane_search(criterion, history, material):
    """The in-plane normal [rad] of each point of largest searched quantity.

    `SAMPLES` normals over ``[-pi/2, pi/2)``, then a golden-section search on each side of the `PEAKS` best
    sampled peaks, every point at once (scipy's bounded scalar searches take one point per call). The MWCM's
    ``tau_a`` repeats every ``pi/2`` (``tau(phi + pi/2) = -tau(phi)``): it is searched over ``[-pi/2, 0)``,
    and of a normal and its conjugate ``phi + pi/2`` the one of larger ``sigma_n,max`` is kept.
    """
    step = np.pi / SAMPLES
    count = SAMPLES // 2 if criterion.plane_by_shear else SAMPLES
    phis = -np.pi / 2 + step * np.arange(count)
    theta = np.full(history.mean.shape[1], np.pi / 2)
    searched, _ = _sampled(criterion, history, material, phis, np.full(count, np.pi / 2))
    peak = (searched >= np.roll(searched, 1, axis=1)) & (searched >= np.roll(searched, -1, axis=1))
    ranked = np.argsort(np.where(peak, -searched, np.inf), axis=1)[:, :PEAKS]
    best, found = phis[ranked[:, 0]], searched[np.arange(searched.shape[0]), ranked[:, 0]]

    def function(angle):
        return _searched_at(criterion, history, material, angle, theta)

    for index in ranked.T:
        for low, high in ((phis[index] - step, phis[index]), (phis[index], phis[index] + step)):
            angle, value = _golden_section(function, low, high)
            better = value > found
            best, found = np.where(better, angle, best), np.where(better, value, found)
    best = (best + np.pi / 2) % np.pi - np.pi / 2
    if not criterion.plane_by_shear:
        return best
    other = (best + np.pi) % np.pi - np.pi / 2
    normal = [_terms_at(history, material, angle, theta, strain=False).sigma_n_max for angle in (best, other)]
    return np.where(normal[1] > normal[0], other, best)


def _golden_section(function, low, high):
    """A local maximum of `function` (vectorised) in each bracket ``[low, high]``, to `XTOL`, and its value."""
    ratio = (math.sqrt(5) - 1) / 2
    inner, outer = high - ratio * (high - low), low + ratio * (high - low)
    f_inner, f_outer = function(inner), function(outer)
    for _ in range(math.ceil(math.log(XTOL / np.max(high - low)) / math.log(ratio))):
        right = f_outer > f_inner
        low, high = np.where(right, inner, low), np.where(right, high, outer)
        trial = np.where(right, low + ratio * (high - low), high - ratio * (high - low))
        f_trial = function(trial)
        inner, outer, f_inner, f_outer = (
            np.where(right, outer, trial),
            np.where(right, trial, inner),
            np.where(right, f_outer, f_trial),
            np.where(right, f_trial, f_inner),
        )
    right = f_outer > f_inner
    return np.where(right, outer, inner), np.where(right, f_outer, f_inner)


def _swt(terms, material):
    return terms.sigma_n_max * terms.eps_a


def _findley(terms, material):
    return terms.tau_a + material.findley_constant() * terms.sigma_n_max


def _fatemi_socie(terms, material):
    k, sigma_y = material._required("fatemi_socie", "fs_k", "sigma_y")
    return terms.tau_a / material.G * (1 + k * terms.sigma_n_max / sigma_y)


def _mwcm(terms, material):
    kappa, _ = material.mwcm_constants()
    sheared = terms.tau_a > 0
    rho = np.divide(terms.sigma_n_max, terms.tau_a, out=np.zeros_like(terms.tau_a), where=sheared)
    return np.where(sheared, terms.tau_a + kappa * rho, 0.0)


def _deviator(history):
    """The mean stress ``sigma_h`` [Pa] and the deviator in coordinates whose norm is ``sqrt(J2)`` [Pa]:
    ``((sigma_xx - sigma_zz) / 2, (sqrt(3) / 2) (sigma_yy - sigma_h), tau_xz)``, each ``(time, point)``."""
    sigma_h = (2 * history.mean + history.sigma_yy) / 3
    return sigma_h, (history.half, math.sqrt(3) / 2 * (history.sigma_yy - sigma_h), history.tau_xz)


def _crossland(history, material):
    alpha, _ = material.crossland_constants()
    sigma_h, deviator = _deviator(history)
    amplitude = _half_longest_chord(deviator)
    sigma_h_max = sigma_h.max(axis=0)
    return Invariant(*(v.reshape(history.shape) for v in (amplitude + alpha * sigma_h_max, amplitude, sigma_h_max)))


def _dang_van(history, material):
    a, _ = material.dang_van_constants()
    sigma_h, deviator = _deviator(history)
    path = np.stack(deviator, axis=-1)  # (time, point, 3)
    half, first, second = _longest_chord(deviator)
    points = np.arange(path.shape[1])
    centre = (path[first, points] + path[second, points]) / 2
    outside = np.sum((path - centre) ** 2, axis=-1).max(axis=0) > half**2 * (1 + ENCLOSED_RTOL)
    for point in np.flatnonzero(outside):
        centre[point] = _enclosing_centre(path[:, point])
    u1, u2, u3 = np.moveaxis(path - centre, -1, 0)
    s_yy = 2 * u2 / math.sqrt(3)
    radius = np.hypot(u1, u3)
    shear = (np.maximum(s_yy, radius - s_yy / 2) - np.minimum(s_yy, -radius - s_yy / 2)) / 2
    parameter = (shear + a * sigma_h).max(axis=0)
    return Invariant(*(v.reshape(history.shape) for v in (parameter, shear.max(axis=0), sigma_h.max(axis=0))))


def _enclosing_centre(path):
    """The centre of the smallest ball enclosing the points `path` ``(n, 3)``: the randomised incremental algorithm
    (Welzl 1991 [14]), the points taken in a fixed shuffled order, at most four on the boundary in three dimensions."""
    points = path[np.random.default_rng(0).permutation(len(path))]

    def smallest(count, boundary):
        centre, squared = _ball_through(boundary) if boundary else (points[0], 0.0)
        if len(boundary) == 4:
            return centre, squared
        for i in range(0 if boundary else 1, count):
            if np.sum((points[i] - centre) ** 2) > squared * (1 + ENCLOSED_RTOL):
                centre, squared = smallest(i, [*boundary, points[i]])
        return centre, squared

    return smallest(len(points), [])[0]


def _ball_through(boundary):
    """The smallest ball with every point of `boundary` (1 to 4 points in three dimensions) on its surface: its
    centre, in their affine hull, and squared radius."""
    origin = boundary[0]
    if len(boundary) == 1:
        return origin, 0.0
    edges = np.array(boundary[1:]) - origin
    gram = edges @ edges.T
    weights = np.linalg.lstsq(2 * gram, np.diag(gram), rcond=None)[0]
    centre = origin + weights @ edges
    return centre, float(np.sum((centre - origin) ** 2))


def _eps_a(terms, material):
    return terms.eps_a


def _tau_a(terms, material):
    return terms.tau_a


def _gamma_a(terms, material):
    return terms.tau_a / material.G


#: Every criterion, by name: what `apply`, the functions below and ``fretting stress --criterion`` evaluate.
CRITERIA = {
    criterion.name: criterion
    for criterion in (
        _OnPlane(
            "swt",
            "Pa",
            "Smith-Watson-Topper parameter sigma_n,max eps_a",
            "1",
            "normal strain amplitude eps_a",
            lambda maps, material: swt_life(maps.parameter, material),
            "sigma_n,max eps_a = sigma_f'^2/E (2 N_f)^(2b) + sigma_f' eps_f' (2 N_f)^(b+c) "
            "(Smith, Watson & Topper 1970)",
            None,
            parameter=_swt,
            amplitude=_eps_a,
            strain=True,
        ),
        _OnPlane(
            "findley",
            "Pa",
            "Findley parameter tau_a + k sigma_n,max",
            "Pa",
            "shear stress amplitude tau_a",
            lambda maps, material: findley_life(maps.parameter, material),
            "tau_a + k sigma_n,max = (sqrt(1 + k^2) + k)/2 sigma_f' (2 N_f)^b "
            "(Findley 1959 on Basquin's push-pull curve)",
            lambda material: material.findley_limit(),
            parameter=_findley,
            amplitude=_tau_a,
        ),
        _OnPlane(
            "fatemi_socie",
            "1",
            "Fatemi-Socie parameter gamma_a (1 + k sigma_n,max/sigma_y), gamma_a = Delta gamma_max / 2",
            "1",
            "engineering shear strain amplitude gamma_a",
            lambda maps, material: fatemi_socie_life(maps.parameter, material),
            "gamma_a (1 + k sigma_n,max/sigma_y) = tau_f'/G (2 N_f)^b0 + gamma_f' (2 N_f)^c0 (Fatemi & Socie 1988)",
            None,
            parameter=_fatemi_socie,
            amplitude=_gamma_a,
        ),
        _OnPlane(
            "mwcm",
            "Pa",
            "MWCM equivalent shear tau_a + kappa rho",
            "Pa",
            "shear stress amplitude tau_a",
            lambda maps, material: mwcm_life(maps.amplitude, maps.sigma_n_max, material),
            "N_f = N_A ((lambda - kappa rho) / tau_a)^(k_0 + (k_1 - k_0) rho), k_0 = -1/b0, k_1 = -1/b "
            "(Lazzarin & Susmel 2003)",
            lambda material: material.mwcm_constants()[1],
            parameter=_mwcm,
            amplitude=_tau_a,
            plane_by_shear=True,
        ),
        _Invariant(
            "crossland",
            "Pa",
            "Crossland parameter sqrt(J2)_a + alpha sigma_h,max",
            "Pa",
            "sqrt(J2) amplitude",
            lambda maps, material: crossland_life(maps.parameter, material),
            "sqrt(J2)_a + alpha sigma_h,max = (1/sqrt(3) + alpha/3) sigma_f' (2 N_f)^b "
            "(Crossland 1956 on Basquin's push-pull curve)",
            lambda material: material.crossland_constants()[1],
            invariant=_crossland,
        ),
        _Invariant(
            "dang_van",
            "Pa",
            "Dang Van parameter max over t of tau(t) + a sigma_h(t)",
            "Pa",
            "largest mesoscopic shear stress (Tresca)",
            lambda maps, material: dang_van_life(maps.parameter, material),
            "max_t (tau + a sigma_h) = (1/2 + a/3) sigma_f' (2 N_f)^b (Dang Van 1989 on Basquin's push-pull curve)",
            lambda material: material.dang_van_constants()[1],
            invariant=_dang_van,
        ),
    )
}


def _evaluate(name, sigma_xx, sigma_zz, tau_xz, material, sigma_yy, planes):
    """The criterion `name` of `CRITERIA` on a stress history given as arrays (`swt`)."""
    return CRITERIA[name].evaluate(_history(sigma_xx, sigma_zz, tau_xz, sigma_yy, material.nu), material, planes)


def swt(sigma_xx, sigma_zz, tau_xz, material, sigma_yy=None, planes="in-plane") -> Plane:
    """Smith-Watson-Topper parameter ``sigma_n,max eps_a`` [Pa] on its critical plane [1].

    ``eps_a`` is half the range of the elastic normal strain on the plane; the critical plane is the one of
    largest parameter. Negative where no plane sees tension.

    Parameters
    ----------
    sigma_xx, sigma_zz, tau_xz : array_like
        Stress history [Pa], time axis first, then any shape of points.
    material : Material
        `E`, `nu`.
    sigma_yy : array_like, optional
        Out-of-plane stress [Pa]; plane strain ``nu (sigma_xx + sigma_zz)`` by default.
    planes : {"in-plane", "all"}
        The planes that contain ``y`` (exact search), or all planes (module docstring).

    Returns
    -------
    Plane
    """
    return _evaluate("swt", sigma_xx, sigma_zz, tau_xz, material, sigma_yy, planes)


def findley(sigma_xx, sigma_zz, tau_xz, material, sigma_yy=None, planes="in-plane") -> Plane:
    """Findley's parameter ``tau_a + k sigma_n,max`` [Pa] on its critical plane, the one of largest parameter [2].

    ``k`` is `Material.findley_constant`; the fatigue limit is ``t_-1 sqrt(1 + k^2)``. Arguments as `swt`.
    """
    return _evaluate("findley", sigma_xx, sigma_zz, tau_xz, material, sigma_yy, planes)


def fatemi_socie(sigma_xx, sigma_zz, tau_xz, material, sigma_yy=None, planes="in-plane") -> Plane:
    """Fatemi-Socie parameter ``(Delta gamma_max / 2) (1 + k sigma_n,max / sigma_y)`` on its critical plane [3].

    ``Delta gamma_max / 2 = gamma_a`` is the amplitude (half the range) of the engineering shear strain on the
    plane, ``gamma = 2 eps_nt = tau / G`` (elastic), as Fatemi & Socie define it [3, 10]: under uniaxial
    elastic loading ``gamma_a = (1 + nu) eps_a``, the amplitude of the difference of the largest and smallest
    principal strains, not half of it. ``sigma_n,max`` [Pa] is the largest normal stress on the plane over the
    cycle. The critical plane is the one of largest parameter; Fatemi & Socie take the plane of largest
    ``gamma_a`` and read ``sigma_n,max`` on it, which gives at most as much. Needs `Material.fs_k` and
    `Material.sigma_y`. Arguments as `swt`.
    """
    return _evaluate("fatemi_socie", sigma_xx, sigma_zz, tau_xz, material, sigma_yy, planes)


def mwcm(sigma_xx, sigma_zz, tau_xz, material, sigma_yy=None, planes="in-plane") -> Plane:
    """Modified Woehler curve method: the equivalent shear ``tau_a + kappa rho`` [Pa], ``rho = sigma_n,max / tau_a``.

    The critical plane is the one of largest shear stress amplitude ``tau_a``, of largest ``sigma_n,max``
    among ties [4, 5]. The fatigue limit is reached where ``tau_a`` reaches the threshold
    ``lambda - kappa rho``, i.e. the parameter reaches ``lambda`` (`Material.mwcm_constants`). Where no plane
    is sheared (``tau_a = 0``) the parameter is 0: the method ties damage to cyclic shear. `Plane.amplitude`
    is ``tau_a``, so ``rho = sigma_n_max / amplitude``. Arguments as `swt`.
    """
    return _evaluate("mwcm", sigma_xx, sigma_zz, tau_xz, material, sigma_yy, planes)


def crossland(sigma_xx, sigma_zz, tau_xz, material, sigma_yy=None) -> Invariant:
    """Crossland's parameter ``sqrt(J2)_a + alpha sigma_h,max`` [Pa], ``alpha`` of `Material.crossland_constants` [6].

    ``sqrt(J2)_a`` is half the longest chord of the deviatoric stress path in the norm ``sqrt(J2)``, which
    equals the radius of its smallest enclosing hypersphere for proportional and elliptical paths (such as
    90-degree out-of-phase tension-torsion); ``sigma_h`` is the mean stress ``(sigma_xx + sigma_yy +
    sigma_zz) / 3``. The fatigue limit is reached where the parameter reaches ``beta``. Arguments as `swt`
    (no planes).
    """
    return _evaluate("crossland", sigma_xx, sigma_zz, tau_xz, material, sigma_yy, planes=None)


def dang_van(sigma_xx, sigma_zz, tau_xz, material, sigma_yy=None) -> Invariant:
    """Dang Van's parameter ``max over t of tau(t) + a sigma_h(t)`` [Pa], ``a`` of `Material.dang_van_constants` [12].

    ``tau(t)`` is the Tresca shear stress (half the difference of the extreme principal stresses) of the
    mesoscopic deviator ``s(t) - s*``: the macroscopic deviator less the centre ``s*`` of the smallest ball that
    encloses its path over the cycle (Papadopoulos et al. [13]), in the norm ``sqrt(J2)``; ``sigma_h`` is the
    mean stress ``(sigma_xx + sigma_yy + sigma_zz) / 3`` at the same instant. The ball is that on the longest
    chord of the path where it encloses the path (a proportional or symmetric path), otherwise Welzl's algorithm
    [14] on the path's points. The fatigue limit is reached where the parameter reaches ``b = t_-1``.
    `Invariant.amplitude` is the largest ``tau``. Arguments as `swt` (no planes).
    """
    return _evaluate("dang_van", sigma_xx, sigma_zz, tau_xz, material, sigma_yy, planes=None)


def swt_life(parameter, material):
    """Cycles to failure ``N_f`` of a Smith-Watson-Topper parameter [Pa], by the strain-life curve [1, 7].

    ``sigma_n,max eps_a = sigma_f'^2 / E (2 N_f)^(2 b) + sigma_f' eps_f' (2 N_f)^(b + c)``: Basquin's and
    Coffin-Manson's curves in the form of Smith, Watson & Topper [1]. Solved for ``log(2 N_f)`` (brentq, to
    rounding). Returns ``inf`` where the parameter is <= 0, an array of the parameter's shape (a float for a
    number).

    Raises
    ------
    ValueError
        When the material lacks ``sigma_f``, ``b``, ``eps_f`` or ``c``, or a parameter exceeds the curve at
        ``2 N_f = 1``.
    """
    sigma_f, b, eps_f, c = material._required("swt_life", "sigma_f", "b", "eps_f", "c")
    return _curve_life(parameter, ((sigma_f**2 / material.E, 2 * b), (sigma_f * eps_f, b + c)), " Pa")


def fatemi_socie_life(parameter, material):
    """Cycles to failure ``N_f`` of a Fatemi-Socie parameter (dimensionless), by the shear strain-life curve [3, 10].

    ``gamma_a (1 + k sigma_n,max / sigma_y) = tau_f' / G (2 N_f)^b0 + gamma_f' (2 N_f)^c0``, ``gamma_a`` the
    engineering shear strain amplitude (`fatemi_socie`), ``G`` `Material.G`: the torsional Basquin and
    Coffin-Manson curves, which the parameter reduces to in fully reversed torsion (``sigma_n,max = 0`` on the
    planes of largest shear). Solved as `swt_life`, whose returns and errors it shares (constants ``tau_f``,
    ``b0``, ``gamma_f``, ``c0``).
    """
    tau_f, b0, gamma_f, c0 = material._required("fatemi_socie_life", "tau_f", "b0", "gamma_f", "c0")
    return _curve_life(parameter, ((tau_f / material.G, b0), (gamma_f, c0)), "")


def findley_life(parameter, material):
    """Cycles to failure ``N_f`` of a Findley parameter [Pa]: ``tau_a + k sigma_n,max = f_k sigma_f' (2 N_f)^b``.

    A Basquin line in the parameter, ``tau_f* (2 N_f)^b`` [2, 7, 10], its coefficient that of fully reversed
    push-pull on Basquin's curve ``sigma_a = sigma_f' (2 N_f)^b``: there Findley's parameter is ``f_k
    sigma_a``, ``f_k = (sqrt(1 + k^2) + k) / 2`` (`Material.findley_constant`). Returns and errors as
    `swt_life` (constants ``sigma_f``, ``b``, and those of ``k``).
    """
    k = material.findley_constant()
    return _basquin_life(parameter, (math.sqrt(1 + k * k) + k) / 2, material, "findley_life")


def crossland_life(parameter, material):
    """Cycles to failure ``N_f`` of a Crossland parameter [Pa]: ``sqrt(J2)_a + alpha sigma_h,max = f_c sigma_f'
    (2 N_f)^b``.

    Crossland's parameter [6] on Basquin's fully reversed push-pull curve ``sigma_a = sigma_f' (2 N_f)^b`` [7]:
    there ``sqrt(J2)_a = sigma_a / sqrt(3)`` and ``sigma_h,max = sigma_a / 3``, so ``f_c = 1 / sqrt(3) + alpha /
    3`` (``t_-1 / f_-1`` with ``alpha`` of `Material.crossland_constants`). Returns and errors as `swt_life`
    (constants ``sigma_f``, ``b``, ``sigma_limit``, ``tau_limit``).
    """
    alpha, _ = material.crossland_constants()
    return _basquin_life(parameter, 1 / math.sqrt(3) + alpha / 3, material, "crossland_life")


def dang_van_life(parameter, material):
    """Cycles to failure ``N_f`` of a Dang Van parameter [Pa]: ``max_t (tau + a sigma_h) = (1/2 + a/3) sigma_f'
    (2 N_f)^b``.

    Dang Van's parameter [12] on Basquin's fully reversed push-pull curve ``sigma_a = sigma_f' (2 N_f)^b`` [7]: at
    the tensile peak ``tau = sigma_a / 2`` and ``sigma_h = sigma_a / 3`` (``1/2 + a/3 = t_-1 / f_-1`` with ``a``
    of `Material.dang_van_constants`). Dang Van proposed a fatigue limit, not a life: this is the life at which
    the parameter reaches that of push-pull on Basquin's curve. Returns and errors as `swt_life` (constants
    ``sigma_f``, ``b``, ``sigma_limit``, ``tau_limit``).
    """
    a, _ = material.dang_van_constants()
    return _basquin_life(parameter, 0.5 + a / 3, material, "dang_van_life")


def mwcm_life(tau_a, sigma_n_max, material):
    """Cycles to failure ``N_f`` by the modified Woehler curve method: ``N_f = N_A (tau_ref(rho) / tau_a)^k(rho)``.

    Lazzarin & Susmel [11]: on the critical plane (`mwcm`), with ``rho = sigma_n,max / tau_a``, the Woehler
    curve of shear amplitude ``tau_a`` [Pa] has at ``N_A`` cycles the strength ``tau_ref(rho) = lambda - kappa
    rho`` (`Material.mwcm_constants`: ``t_-1`` in torsion, ``rho = 0``, ``f_-1 / 2`` in push-pull, ``rho = 1``)
    and the inverse slope ``k(rho) = k_0 + (k_1 - k_0) rho``, linear between those of the torsion curve,
    ``k_0 = -1 / b0``, and of the push-pull curve, ``k_1 = -1 / b``. Returns ``inf`` where ``tau_a = 0``, an
    array of the arguments' broadcast shape (a float for numbers).

    Raises
    ------
    ValueError
        When the material lacks ``sigma_limit``, ``tau_limit``, ``b``, ``b0`` or ``N_A``; where ``rho`` leaves
        the curves' range (``tau_ref(rho) <= 0`` or ``k(rho) <= 0``); or where the curve gives ``2 N_f < 1``.
    """
    kappa, lam = material.mwcm_constants()
    b, b0, N_A = material._required("mwcm_life", "b", "b0", "N_A")
    tau_a, sigma_n_max = np.broadcast_arrays(np.asarray(tau_a, dtype=float), np.asarray(sigma_n_max, dtype=float))
    sheared = tau_a > 0
    rho = np.divide(sigma_n_max, tau_a, out=np.zeros_like(tau_a), where=sheared)
    reference, inverse_slope = lam - kappa * rho, -1 / b0 + (1 / b0 - 1 / b) * rho
    outside = sheared & ((reference <= 0) | (inverse_slope <= 0))
    if outside.any():
        raise ValueError(
            f"rho: found {rho[outside].flat[0]:.6g}, outside the MWCM's curves (tau_ref = lambda - kappa rho > 0 and "
            f"k = k_0 + (k_1 - k_0) rho > 0)"
        )
    ratio = np.divide(reference, tau_a, out=np.ones_like(tau_a), where=sheared)
    lives = np.where(sheared, N_A * ratio**inverse_slope, np.inf)
    if np.any(lives < 0.5):
        raise ValueError(f"tau_a: found {tau_a[lives < 0.5].flat[0]:.6g} Pa, beyond the MWCM's curve at 2 N_f = 1")
    return float(lives) if lives.ndim == 0 else lives


def _basquin_life(parameter, factor, material, name):
    """`_curve_life` of Basquin's line ``factor sigma_f' (2 N_f)^b``."""
    sigma_f, b = material._required(name, "sigma_f", "b")
    return _curve_life(parameter, ((factor * sigma_f, b),), " Pa")


def _curve_life(parameter, terms, units):
    """Cycles ``N_f`` at which the curve ``sum C (2 N_f)^e`` over `terms` ``(C, e)``, every ``C > 0`` and ``e < 0``,
    meets each parameter (of `units`, e.g. " Pa", or "" for a number); ``inf`` where the parameter is <= 0."""

    def excess(log_reversals, target):
        return sum(C * math.exp(e * log_reversals) for C, e in terms) - target

    def life(target):
        if target <= 0:
            return math.inf
        if excess(0.0, target) < 0:
            raise ValueError(f"parameter: found {target:.6g}{units}, expected at most {excess(0.0, 0):.6g} (2 N_f = 1)")
        high = 1.0
        while excess(high, target) > 0:
            high *= 2
        return math.exp(brentq(excess, 0.0, high, args=(target,), xtol=1e-14, rtol=4 * np.finfo(float).eps)) / 2

    values = np.asarray(parameter, dtype=float)
    lives = np.array([life(float(value)) for value in values.ravel()]).reshape(values.shape)
    return float(lives) if lives.ndim == 0 else lives


def life(maps, material) -> xr.DataArray:
    """Cycles to failure ``N_f`` at every point of the maps of `apply`, by the S-N relation of their criterion.

    The relation of each criterion (`Criterion.life`): `swt_life`, `findley_life`, `fatemi_socie_life`,
    `mwcm_life` (which reads ``amplitude`` and ``sigma_n_max`` as well as the parameter), `crossland_life`,
    `dang_van_life`.

    Parameters
    ----------
    maps : xarray.Dataset
        A result of `apply` (its attribute ``criterion`` names the criterion).
    material : Material

    Returns
    -------
    xarray.DataArray
        ``N_f`` on the maps' dims and coordinates, ``inf`` where the parameter is <= 0; attributes ``units``,
        ``long_name``, ``definition`` (the relation).
    """
    criterion = CRITERIA[maps.attrs["criterion"]]
    values = criterion.life(maps, material)
    attrs = {"units": "1", "long_name": "cycles to failure", "definition": criterion.life_name}
    return xr.DataArray(values, coords=maps.parameter.coords, dims=maps.parameter.dims, name="N_f", attrs=attrs)


class CriticalDistance(NamedTuple):
    """A parameter read at a critical distance.

    Attributes
    ----------
    value : float
        The parameter at ``L/2`` (point method) or its mean over ``2 L`` (line method).
    x_hot : float
        The surface point the distance starts from [m].
    angle : float
        The direction [rad] from the depth axis ``+z`` toward ``+x``.
    """

    value: float
    x_hot: float
    angle: float


def point_method(parameter, L, direction="down", x_hot=None) -> CriticalDistance:
    """The point method of the theory of critical distances: the parameter at ``L/2`` from the hot spot [8, 9].

    Parameters
    ----------
    parameter : xarray.DataArray
        A map on dims ``z`` (depth [m], ascending from 0) and ``x`` [m] (ascending), e.g.
        ``apply(...).parameter``; read between grid points by bilinear interpolation.
    L : float
        The critical distance [m] (`Material.critical_distance`).
    direction : {"down", "max"} or float
        Straight down into the body (``+z``); the direction that maximises the value, sampled on
        `DIRECTIONS` angles over ``[-pi/2, pi/2]`` (1 degree apart; those that leave the grid are
        skipped); or an angle [rad] from ``+z`` toward ``+x``.
    x_hot : float, optional
        The surface point to start from [m]; by default that of the largest surface value (`hot_spot`).

    Raises
    ------
    ValueError
        When the grid does not reach ``L/2`` along the direction (or along any, for "max").
    """
    return _critical_distance(parameter, L, 0.5, direction, x_hot, _value_at_end)


def line_method(parameter, L, direction="down", x_hot=None) -> CriticalDistance:
    """The line method: the mean of the parameter over ``2 L`` from the hot spot [8, 9].

    The mean of the bilinear interpolant of the map, exact to rounding: along a straight line the
    interpolant is a quadratic in the distance within each grid cell, so Simpson's rule on each piece
    between the grid lines the segment crosses integrates it exactly. Arguments and errors as
    `point_method`, with ``2 L`` for ``L/2``.
    """
    return _critical_distance(parameter, L, 2.0, direction, x_hot, _mean_along)


def hot_spot(parameter) -> tuple[float, float]:
    """The largest surface value (``z = 0``) of a map and its ``x`` [m], the first of equal ones.

    The map's grid decides where the surface is read: a field of `fretting.analysis.stress.field` holds the
    contact's edges, where the surface value of a fatigue parameter usually peaks with a kink, so that the hot
    spot does not depend on the grid's spacing there. Arguments as `point_method`.
    """
    x, _, values = _grid(parameter)
    at = int(np.nanargmax(values[0]))
    return float(values[0, at]), float(x[at])


def _grid(parameter):
    if not isinstance(parameter, xr.DataArray) or set(parameter.dims) != {"z", "x"}:
        raise ValueError(f"parameter: expected a DataArray on dims (z, x), found {type(parameter).__name__}")
    values = parameter.transpose("z", "x")
    x, z = values.x.values.astype(float), values.z.values.astype(float)
    if z.size < 2 or x.size < 2 or np.any(np.diff(z) <= 0) or np.any(np.diff(x) <= 0) or z[0] != 0:
        raise ValueError("parameter: expected coordinates z and x ascending, 2 or more each, z from 0 (the surface)")
    return x, z, values.values


def _value_at_end(interpolate, x, z, x_hot, angle, reach):
    """The interpolated map at the distance `reach` [m] from ``(x_hot, 0)`` along `angle`."""
    return interpolate([[reach * math.cos(angle), x_hot + reach * math.sin(angle)]])[0]


def _mean_along(interpolate, x, z, x_hot, angle, reach):
    """The mean of the interpolated map over the segment of length `reach` [m] from ``(x_hot, 0)`` along `angle`:
    Simpson's rule between the grid lines it crosses, exact for the bilinear interpolant."""
    sin, cos = math.sin(angle), math.cos(angle)
    crossings = [np.array([0.0, reach])]
    if sin != 0:
        crossings.append((x - x_hot) / sin)
    if cos != 0:
        crossings.append(z / cos)
    r = np.concatenate(crossings)
    r = np.unique(r[(r >= 0) & (r <= reach)])
    middle = (r[:-1] + r[1:]) / 2
    ends, mids = (interpolate(np.stack([d * cos, x_hot + d * sin], axis=-1)) for d in (r, middle))
    return float(np.sum(np.diff(r) * (ends[:-1] + 4 * mids + ends[1:])) / 6 / reach)


def _critical_distance(parameter, L, fraction, direction, x_hot, read):
    """`CriticalDistance` of `read` (`_value_at_end` or `_mean_along`) over ``fraction L`` from the hot spot."""
    x, z, values = _grid(parameter)
    reach = fraction * positive("L", L)
    x_hot = finite("x_hot", hot_spot(parameter)[1] if x_hot is None else x_hot)
    if direction == "down":
        angles = np.array([0.0])
    elif direction == "max":
        angles = np.linspace(-np.pi / 2, np.pi / 2, DIRECTIONS)
    elif isinstance(direction, str):
        raise ValueError(f"direction: found {direction!r}, expected 'down', 'max' or an angle [rad]")
    else:
        angles = np.array([finite("direction", direction)])
    end_x, end_z = x_hot + reach * np.sin(angles), reach * np.cos(angles)
    inside = (x[0] <= x_hot <= x[-1]) & (end_x >= x[0]) & (end_x <= x[-1]) & (end_z >= 0) & (end_z <= z[-1])
    if not inside.any():
        along = "along any direction" if angles.size > 1 else f"at {np.degrees(angles[0]):.6g} deg from +z"
        raise ValueError(
            f"parameter: the grid spans x in [{x[0]:.6g}, {x[-1]:.6g}] m and z up to {z[-1]:.6g} m, expected it "
            f"to reach {reach:.6g} m from x = {x_hot:.6g} m {along}"
        )
    interpolate = RegularGridInterpolator((z, x), values)
    found = [read(interpolate, x, z, x_hot, angle, reach) for angle in angles[inside]]
    best = int(np.argmax(found))
    return CriticalDistance(float(found[best]), float(x_hot), float(angles[inside][best]))


_COMMON = {
    "phi": ("rad", "critical plane normal, from +x toward +z"),
    "theta": ("rad", "critical plane normal, from +y (pi/2: the plane contains y)"),
    "sigma_n_max": ("Pa", "largest normal stress on the critical plane"),
    "sigma_h_max": ("Pa", "largest mean stress (sigma_xx + sigma_yy + sigma_zz) / 3"),
}


def apply(field, criterion, material, planes="in-plane") -> xr.Dataset:
    """A criterion at every point of a stress field over its steps, taken as one cycle.

    Parameters
    ----------
    field : xarray.Dataset
        ``sigma_xx``, ``sigma_zz``, ``tau_xz`` [Pa] (and ``sigma_yy``; plane strain when absent) on dims
        ``step`` and the points' dims, e.g. ``(step, z, x)`` as `fretting.analysis.stress.field` returns.
    criterion : str
        A key of `CRITERIA`: ``swt``, ``findley``, ``fatemi_socie``, ``mwcm``, ``crossland``, ``dang_van``.
    material : Material
    planes : {"in-plane", "all"}
        As `swt` (ignored by a criterion on no plane, ``crossland`` and ``dang_van``).

    Returns
    -------
    xarray.Dataset
        On the points' dims and coordinates: ``parameter``, ``amplitude``, and ``phi``, ``theta``,
        ``sigma_n_max`` (critical-plane criteria) or ``sigma_h_max`` (Crossland, Dang Van), with ``units`` and
        ``long_name``; attributes: the field's (those of `fretting.analysis.stress.field`: ``body``,
        ``bulk_state``, ...) and ``criterion``.
    """
    if criterion not in CRITERIA:
        raise ValueError(f"criterion: found {criterion!r}, expected one of: {', '.join(CRITERIA)}")
    declared = CRITERIA[criterion]
    names = ["sigma_xx", "sigma_zz", "tau_xz"] + (["sigma_yy"] if "sigma_yy" in field else [])
    for name in names[:3]:
        if name not in field or "step" not in field[name].dims:
            raise ValueError(f"field: expected a variable {name} on dims including 'step', found {list(field)}")
    dims = ["step"] + [dim for dim in field["sigma_xx"].dims if dim != "step"]
    stresses = {name: field[name].transpose(*dims).values for name in names}
    result = _evaluate(
        criterion,
        stresses["sigma_xx"],
        stresses["sigma_zz"],
        stresses["tau_xz"],
        material,
        stresses.get("sigma_yy"),
        planes,
    )
    attributes = {
        "parameter": (declared.units, declared.long_name),
        "amplitude": (declared.amplitude_units, declared.amplitude_name),
        **_COMMON,
    }
    coords = {dim: field[dim] for dim in dims[1:] if dim in field.coords}
    variables = {
        name: xr.Variable(dims[1:], value, {"units": attributes[name][0], "long_name": attributes[name][1]})
        for name, value in result._asdict().items()
    }
    return xr.Dataset(variables, coords=coords, attrs={**field.attrs, "criterion": criterion})


#: Grid of `threshold`'s stress fields: points along ``x`` over ``centre +- SPAN a`` (and the contact's edges), and
#: depths from 0 to the reach of the reading (``L/2``, ``2 L``), the last at it.
THRESHOLD_GRID = {"nx": 151, "span": 1.5, "nz": 41}

#: Width of the bracket at which `threshold`'s search stops, in ``f P``; that of `threshold_of`, relative to the larger
#: end of its bracket.
THRESHOLD_XTOL = 1e-6

#: Depth [in ``a``] of the second row of the field that `threshold` reads at the hot spot (the map needs two).
HOT_SPOT_DEPTH = 0.05


class BracketError(ValueError):
    """The criterion does not cross its target between the ends of a search's bracket.

    Attributes
    ----------
    ends : (float, float)
        The searched function at the low and the high end: the criterion less its limit, or ``atan(log(life /
        N_f))``; both negative where the criterion stays below its target, both positive where above.
    """

    def __init__(self, message, ends):
        self.ends = tuple(ends)
        super().__init__(message)


class Threshold(NamedTuple):
    """The result of `threshold` and `threshold_of`.

    Attributes
    ----------
    amplitude : float
        The value of the searched quantity at which the criterion reaches its target: the amplitude of ``Q``
        [N/m] (`threshold`), or that of the scene of `threshold_of` (an amplitude of ``sigma`` [Pa], a radius
        [m], ...).
    values : xarray.Dataset
        The criterion's variables read there at the critical distance (``parameter``, ``amplitude``, ...: those of
        `apply`, read as the parameter), with `apply`'s attributes.
    runs : int
        Values of the searched quantity the search evaluated (each one run of the history, unless a `cache`
        held it).
    """

    amplitude: float
    values: xr.Dataset
    runs: int


#: The readings of `threshold` and `threshold_of`: ``at`` -> (reach in ``L``, method), None for the surface hot spot.
READINGS = {"point": (0.5, point_method), "line": (2.0, line_method), "hot spot": (None, None)}


def threshold(
    contact,
    history,
    criterion,
    material,
    life=None,
    at="point",
    bracket=(0.01, 0.99),
    nu=None,
    bulk_state="plane strain",
    model=None,
    cache=None,
) -> Threshold:
    """The amplitude of ``Q`` at which a criterion, read at the critical distance, reaches its fatigue limit or a life.

    `threshold_of` over the amplitude ``Q_a`` of ``Q``, the contact fixed, to `THRESHOLD_XTOL` ``f P``.

    Parameters
    ----------
    contact : fretting.Contact
    history : callable
        ``Q_a -> fretting.History``, the load history at the amplitude ``Q_a`` [N/m] of ``Q``, e.g. ``lambda Q_a:
        History.sinusoidal(Q_a, sigma_a, cycles=2)``; its last load cycle must be recorded whole.
    criterion, material, life, at, nu, bulk_state, model, cache
        As `threshold_of`.
    bracket : (float, float)
        The amplitudes searched between, in ``f P``.

    Returns
    -------
    Threshold

    Raises
    ------
    ValueError
        As `threshold_of`.
    """
    fP = contact.f * contact.P
    low, high = (fP * positive("bracket", end) for end in bracket)
    return threshold_of(
        lambda Q_a: (contact, history(Q_a)),
        (low, high),
        criterion,
        material,
        life=life,
        at=at,
        nu=nu,
        bulk_state=bulk_state,
        model=model,
        cache=cache,
        xtol=THRESHOLD_XTOL * fP,
        name="Q_a",
        units=" N/m",
    )


def threshold_of(
    scene,
    bracket,
    criterion,
    material,
    life=None,
    at="point",
    nu=None,
    bulk_state="plane strain",
    model=None,
    cache=None,
    xtol=None,
    name="x",
    units="",
) -> Threshold:
    """The value of a quantity of a test at which a criterion, read at the critical distance, reaches a target.

    The target is the criterion's fatigue limit, or a life.

    A bracketed search (Brent's method, `scipy.optimize.brentq`) over runs: each runs the scene at a value `x`
    (`fretting.simulate`), takes the specimen's stress field over the run's last load cycle
    (`fretting.analysis.stress.field` on `THRESHOLD_GRID`), maps the criterion over it (`apply`) and reads it at
    `at`: the surface hot spot (`hot_spot`), or the point or line method straight below it (`point_method`,
    `line_method`, with `Material.critical_length`). It finds the root of ``value - limit``, the limit that of
    the criterion (`Criterion.limit`), or with `life` that of ``atan(log(life / N_f))``, ``N_f`` the criterion's
    life of the values read (`life`; the MWCM's reads ``amplitude`` and ``sigma_n_max`` there as the parameter),
    which grows with the criterion and is finite where ``N_f`` is infinite. The criterion must cross its target
    once between the bracket's ends.

    Parameters
    ----------
    scene : callable
        ``x -> (fretting.Contact, fretting.History)``: the test at the value `x` of the searched quantity, e.g. the
        amplitude of ``sigma`` [Pa] (``lambda s: (contact, History.sinusoidal(Q_a, s, cycles=2))``) or a pad radius
        [m]; the history's last load cycle must be recorded whole.
    bracket : (float, float)
        The values searched between, in the units of `x`; a run that slides (``|Q| >= f P``) raises
        `fretting.GrossSlipError`, so keep the bracket within partial slip.
    criterion : str
        A key of `CRITERIA`.
    material : Material
    life : float, optional
        Cycles to failure > 0: the value at which the criterion's life is this. By default the one at which it
        reaches its fatigue limit (SWT and Fatemi-Socie have none: they need a life).
    at : {"point", "line", "hot spot"}
        Where the criterion is read (`READINGS`).
    nu, bulk_state
        As `fretting.analysis.stress.field`.
    model : fretting.models.ModelSpec, optional
        As `fretting.simulate`.
    cache : dict, optional
        Stress fields by value of `x` (and reading depth), filled by the search: give the same dict to searches of
        the same scene (another criterion, life or bracket) and a value already run is not run again.
    xtol : float, optional
        Width of the bracket at which the search stops, in the units of `x`; by default `THRESHOLD_XTOL` times the
        larger end of `bracket`.
    name, units : str
        The quantity's name and units (e.g. ``"sigma_a"``, ``" Pa"``) in error messages.

    Returns
    -------
    Threshold

    Raises
    ------
    ValueError
        On an unknown criterion or `at`, a criterion without a fatigue limit and no `life`, or a constant the
        material lacks.
    BracketError
        When the criterion does not cross its target between the bracket's ends (both values named).
    """
    _check_reading(criterion, at)
    declared = CRITERIA[criterion]
    if life is None and declared.limit is None:
        raise ValueError(f"criterion: {criterion} has no fatigue limit, give a life [cycles]")
    target = declared.limit(material) if life is None else positive("life", life)
    L = None if at == "hot spot" else material.critical_length("threshold")
    low, high = (finite("bracket", end) for end in bracket)
    if not low < high:
        raise ValueError(f"bracket: found ({low!r}, {high!r}), expected a low end below the high end")
    xtol = THRESHOLD_XTOL * max(abs(low), abs(high)) if xtol is None else positive("xtol", xtol)
    cache = {} if cache is None else cache
    read = {}

    def excess(x):
        if x not in read:
            stresses = _last_cycle_field(scene, x, READINGS[at][0], L, nu, bulk_state, model, cache)
            read[x] = _read(stresses, criterion, material, READINGS[at], L)
        if life is None:
            return float(read[x].parameter) - target
        return math.atan(math.log(target / float(declared.life(read[x], material))))

    ends = [excess(low), excess(high)]
    if ends[0] * ends[1] > 0:
        quantity = "the criterion less its limit" if life is None else "atan(log(life / N_f))"
        raise BracketError(
            f"bracket: {quantity} is {ends[0]:.6g} at {name} = {low:.6g}{units} and {ends[1]:.6g} at "
            f"{high:.6g}{units}, expected a change of sign between them",
            ends,
        )
    found = brentq(excess, low, high, xtol=xtol)
    excess(found)
    return Threshold(float(found), read[found], len(read))


def read_last_cycle(contact, history, criterion, material, at="point", nu=None, bulk_state="plane strain", model=None):
    """The criterion's variables over the last load cycle of a run of `history`, read at `at` as `threshold_of` reads.

    Arguments as `threshold_of`. Returns a Dataset of scalars (those of `apply`, with its attributes); `life` of
    it is the life there.
    """
    _check_reading(criterion, at)
    L = None if at == "hot spot" else material.critical_length("read_last_cycle")
    fraction = READINGS[at][0]
    stresses = _last_cycle_field(lambda _: (contact, history), 0.0, fraction, L, nu, bulk_state, model, {})
    return _read(stresses, criterion, material, READINGS[at], L)


def _check_reading(criterion, at):
    if criterion not in CRITERIA:
        raise ValueError(f"criterion: found {criterion!r}, expected one of: {', '.join(CRITERIA)}")
    if at not in READINGS:
        raise ValueError(f"at: found {at!r}, expected 'point', 'line' or 'hot spot'")


def _last_cycle_field(scene, x, fraction, L, nu, bulk_state, model, cache):
    """The specimen's stress field over the last load cycle of a run of ``scene(x)``, on `THRESHOLD_GRID` to the
    depth ``fraction L`` (two rows to `HOT_SPOT_DEPTH` ``a`` with `L` None); from `cache` when it holds it."""
    key = (x, None if L is None else fraction * L)
    if key in cache:
        return cache[key]
    contact, history = scene(x)
    result = simulate(contact, history, model)
    rows = complete_cycles(result)[-1]
    if rows is None:
        raise ValueError("history: its last load cycle is not recorded whole, expected every step of it recorded")
    a, centre = result.attrs["a"], result.attrs["centre"]
    x_grid = centre + a * np.linspace(-THRESHOLD_GRID["span"], THRESHOLD_GRID["span"], THRESHOLD_GRID["nx"])
    z = np.array([0.0, HOT_SPOT_DEPTH * a]) if L is None else np.linspace(0.0, fraction * L, THRESHOLD_GRID["nz"])
    cache[key] = stress_field(result, x_grid, z, step=result.step.values[rows].tolist(), nu=nu, bulk_state=bulk_state)
    return cache[key]


def _read(stresses, criterion, material, reading, L):
    """The criterion's variables over the field `stresses`, read at the hot spot (`L` None) or by `reading`,
    ``(fraction, method)``: `point_method` or `line_method`, whose reach is ``fraction L``."""
    _, method = reading
    maps = apply(stresses, criterion, material)
    _, x_hot = hot_spot(maps.parameter)
    if L is None:
        return maps.sel(x=x_hot).isel(z=0, drop=True)
    values = {name: ((), method(maps[name], L, x_hot=x_hot).value, maps[name].attrs) for name in maps.data_vars}
    return xr.Dataset(values, coords={"x": x_hot}, attrs=maps.attrs)


#: Where the shipped material files are: ``<name>.toml``, each constant with its source.
MATERIALS = EXAMPLES / "materials"


def materials() -> dict[str, tuple[Path, str]]:
    """The shipped material files: name (the file's stem) -> (path, the first paragraph of its opening comment,
    on one line)."""
    found = {}
    for path in sorted(MATERIALS.glob("*.toml")):
        with path.open(encoding="utf-8") as lines:
            paragraph = itertools.takewhile(lambda line: line.strip() not in ("", "#"), lines)
            found[path.stem] = (path, " ".join(line.removeprefix("#").strip() for line in paragraph))
    return found


def material_path(name_or_path: str | os.PathLike) -> Path:
    """The material file that `name_or_path` names: a file that exists, else a shipped material's name (`materials`).

    Raises
    ------
    FileNotFoundError
        When neither; its message lists the shipped names.
    """
    path = Path(name_or_path)
    if path.exists():
        return path
    shipped = materials()
    name = str(name_or_path).removesuffix(".toml")
    if name not in shipped:
        problem = f"no such file, nor a shipped material: expected a material file or one of: {', '.join(shipped)}"
        raise FileNotFoundError(errno.ENOENT, problem, str(name_or_path))
    return shipped[name][0]
