"""Contact profiles and their normal-contact solutions (seed paper, eqs 1-2).

Each profile turns the normal load into a contact interval and a pressure. The gap between the
undeformed bodies is ``h0(x) >= 0``; the pressure solves eq (1) bounded at both ends,
``E_star h0'(x) = -(2/pi) PV int p(xi) / (xi - x) dxi``, with ``P = int p dx`` (eq 2).
Positions inside the contact are written ``x = centre + a t`` with ``-1 <= t <= 1``.
"""

from __future__ import annotations

import abc
import ast
import itertools
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import NoReturn

import numpy as np
from numpy.typing import ArrayLike
from scipy import fft, optimize, special

from fretting._validate import positive

__all__ = [
    "Profile",
    "Hertz",
    "RoundedFlat",
    "FlatPunch",
    "Gap",
    "profile_class",
    "recorded_profile",
    "table_breakpoints",
]

#: A gap ``h0(x)`` [m] or its slope [-] at positions ``x`` [m] (vectorised).
GapFunction = Callable[[np.ndarray], np.ndarray]

# Root-finding tolerance on lengths and angles, relative: well inside the 1e-10 asked of a.
_RTOL = 4 * np.finfo(float).eps

#: What every profile gives: method -> its signature and what it returns [units].
_EVERY_PROFILE = {
    "half_width": "half_width(P, E_star) -> (a, centre) [m]",
    "pressure": "pressure(t, a, centre, P, E_star) -> p [Pa]",
}

#: What a symmetric profile whose contact grows with the load gives besides.
_GROWING = {"load": "load(a, E_star) -> P [N/m]", "load_slope": "load_slope(a, E_star) -> dP/da [N/m^2]"}
_GROWING_KIND = "a symmetric profile whose contact grows with the load (SYMMETRIC and VANISHING_EDGES)"

#: Dataset attributes ``profile_<name>`` hold the profile's parameters (`Profile.attributes`).
PARAMETER_PREFIX = "profile_"


class Profile(abc.ABC):
    """Base class: a profile gives the contact interval and the pressure for a normal load.

    Every profile gives `half_width` and `pressure`; a symmetric one whose contact grows with the
    load (`SYMMETRIC` and `VANISHING_EDGES`) also gives `load` and `load_slope`. A subclass that
    lacks one of them is refused when it is constructed, by a ``TypeError`` naming what it lacks.

    A profile states its facts, which a result records (`attributes`): its class's name and its
    `parameters`, from which `from_parameters` builds it again.

    Examples
    --------
    >>> import numpy as np
    >>> import fretting as fr
    >>> class Cylinder(fr.Profile):
    ...     SYMMETRIC = True
    ...     def half_width(self, P, E_star):
    ...         return np.sqrt(4 * P * 0.05 / (np.pi * E_star)), 0.0
    ...     def pressure(self, t, a, centre, P, E_star):
    ...         return 2 * P / (np.pi * a) * np.sqrt(1 - t**2)
    >>> Cylinder()
    Traceback (most recent call last):
    ...
    TypeError: Cylinder lacks load(a, E_star) -> P [N/m] and load_slope(a, E_star) -> dP/da [N/m^2], which ...
    """

    #: The gap, and so the pressure, is even about the centre of the contact. A symmetric profile
    #: whose contact grows with the load gives `load_slope`, from which `fretting.models.exact` builds
    #: the gap outside a contact, and `load`, at which `fretting.models.normal` lets nodes enter
    #: (`Hertz`, `RoundedFlat`; the sharp `FlatPunch`, whose contact does not grow, gives neither).
    SYMMETRIC = False
    #: Positions [m] where the gap's curvature jumps: the pressure's derivative is singular there.
    breakpoints = ()
    #: The pressure vanishes at the edges of the contact (it is bounded there, eq 1), where the
    #: fully stuck traction is unbounded: any change of the loads slips a zone at each edge. Such a
    #: contact grows with the load. Not so under the sharp `FlatPunch`, whose pressure is unbounded
    #: there as the traction is, and whose contact keeps its width.
    VANISHING_EDGES = True
    #: The pressure is Hertz's ellipse ``p0 sqrt(1 - t^2)`` at every load, whose stress field has
    #: McEwen's closed form (`fretting.analysis.stress.mcewen`).
    ELLIPTICAL = False

    #: ``load(a, E_star) -> P`` [N/m]: the load of the contact of half-width ``a`` [m] and modulus
    #: ``E_star`` [Pa], vectorised in ``a``. Given by a symmetric profile whose contact grows with the
    #: load, and by no other: the base class declares it and defines none, so that a profile has it
    #: only where it holds.
    load: Callable[[ArrayLike, float], np.ndarray]
    #: ``load_slope(a, E_star) -> dP/da`` [N/m^2], the derivative of `load`; given where `load` is.
    load_slope: Callable[[ArrayLike, float], np.ndarray]

    def __new__(cls, *args, **kwargs):
        """Refuse a class that lacks a method it must give (`required`), naming them and what they return."""
        missing = {
            kind: [text for name, text in methods.items() if _lacks(cls, name)]
            for kind, methods in cls.required().items()
        }
        problems = [f"{' and '.join(texts)}, which {kind} must give" for kind, texts in missing.items() if texts]
        if problems:
            raise TypeError(f"{cls.__name__} lacks {'; and '.join(problems)}")
        return super().__new__(cls)

    @classmethod
    def grows_with_load(cls) -> bool:
        """Whether the profile is symmetric and its contact grows with the load (`SYMMETRIC` and
        `VANISHING_EDGES`): it then gives `load` and `load_slope` (`required`)."""
        return bool(cls.SYMMETRIC and cls.VANISHING_EDGES)

    @classmethod
    def required(cls) -> dict[str, dict[str, str]]:
        """What the class must give: ``{which profiles: {method: its signature and what it returns [units]}}``."""
        return {"every profile": _EVERY_PROFILE} | ({_GROWING_KIND: _GROWING} if cls.grows_with_load() else {})

    @abc.abstractmethod
    def half_width(self, P: float, E_star: float) -> tuple[float, float]:
        """Contact half-width `a` [m] and centre [m] for load `P` [N/m] and modulus `E_star` [Pa]."""

    @abc.abstractmethod
    def pressure(self, t: np.ndarray, a: float, centre: float, P: float, E_star: float) -> np.ndarray:
        """Contact pressure [Pa] at the normalised positions ``t`` in (-1, 1)."""

    def parameters(self) -> dict[str, float | np.ndarray]:
        """The numbers that define the profile [m], by the names of its constructor's arguments.

        The base class knows none: a profile of the user's that gives them has them recorded in a
        result and rebuilt by `from_parameters`.
        """
        return {}

    @classmethod
    def from_parameters(cls, parameters: Mapping[str, float | np.ndarray]) -> Profile:
        """The profile of `parameters` (`parameters` of one of this class): ``cls(**parameters)``."""
        return cls(**parameters)

    def attributes(self) -> dict[str, str | float | np.ndarray]:
        """The profile's facts as dataset attributes: ``profile_class``, the class's name, and
        ``profile_<name>`` for each of its `parameters` (read back by `recorded_profile`)."""
        return {"profile_class": type(self).__name__} | {
            f"{PARAMETER_PREFIX}{name}": value for name, value in self.parameters().items()
        }

    def check(self, a: float, centre: float, P: float, E_star: float) -> None:  # noqa: B027 (a default: closed-form profiles pass)
        """Raise ValueError unless the pressure of the contact `a`, `centre` is admissible.

        The closed-form profiles (`Hertz`, `RoundedFlat`, `FlatPunch`) are convex for any
        positive parameters, so their pressure is positive over the one interval; `Gap` checks.
        """

    def peak_pressure(self, a: float, centre: float, P: float, E_star: float) -> float:
        """Largest contact pressure [Pa], found numerically unless a subclass knows it."""
        p = lambda t: self.pressure(np.atleast_1d(t), a, centre, P, E_star)  # noqa: E731
        t = np.linspace(-1, 1, 4097)[1:-1]
        k = int(np.argmax(p(t)))
        result = optimize.minimize_scalar(
            lambda s: -p(s)[0],
            bounds=(t[max(k - 1, 0)], t[min(k + 1, t.size - 1)]),
            method="bounded",
            options={"xatol": 1e-12},
        )
        return float(max(-result.fun, p(t[k])[0]))


class Hertz(Profile):
    """Cylinders of relative radius ``R`` [m]: gap ``h0 = x^2 / (2R)``.

    ``a = sqrt(4 P R / (pi E_star))``, ``p = p0 sqrt(1 - t^2)``, ``p0 = 2P / (pi a)`` (eq 6).

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(R=0.05), E_star=115e9, f=0.6, P=1e5)
    >>> import math
    >>> math.isclose(contact.p0, 2 * contact.P / (math.pi * contact.a))
    True
    """

    SYMMETRIC = True
    ELLIPTICAL = True

    def __init__(self, R: float) -> None:
        self.R = positive("R", R, "m")

    def __repr__(self) -> str:
        return f"Hertz(R={self.R!r})"

    def parameters(self) -> dict[str, float]:
        return {"R": self.R}

    def half_width(self, P: float, E_star: float) -> tuple[float, float]:
        return np.sqrt(4 * P * self.R / (np.pi * E_star)), 0.0

    def load(self, a: ArrayLike, E_star: float) -> np.ndarray:
        """``P = pi E_star a^2 / (4R)`` [N/m], the load of the contact of half-width `a` [m] (eq 6 inverted)."""
        return np.pi * E_star * np.square(a) / (4 * self.R)

    def load_slope(self, a: ArrayLike, E_star: float) -> np.ndarray:
        """``dP/da = pi E_star a / (2R)`` [N/m^2], from ``a = sqrt(4 P R / (pi E_star))``."""
        return np.pi * E_star * np.asarray(a) / (2 * self.R)

    def pressure(self, t: np.ndarray, a: float, centre: float, P: float, E_star: float) -> np.ndarray:
        return self.peak_pressure(a, centre, P, E_star) * np.sqrt(1 - np.square(t))

    def peak_pressure(self, a: float, centre: float, P: float, E_star: float) -> float:
        return 2 * P / (np.pi * a)


class FlatPunch(Profile):
    """Sharp-edged flat of half-width ``a`` [m]: ``p = P / (pi sqrt(a^2 - x^2))``.

    The pressure is unbounded at the edges, so ``p0`` is taken as the pressure at the centre,
    ``P / (pi a)``.
    """

    SYMMETRIC = True
    VANISHING_EDGES = False

    def __init__(self, a: float) -> None:
        self.a = positive("a", a, "m")

    def __repr__(self) -> str:
        return f"FlatPunch(a={self.a!r})"

    def parameters(self) -> dict[str, float]:
        return {"a": self.a}

    def half_width(self, P: float, E_star: float) -> tuple[float, float]:
        return self.a, 0.0

    def pressure(self, t: np.ndarray, a: float, centre: float, P: float, E_star: float) -> np.ndarray:
        return self.peak_pressure(a, centre, P, E_star) / np.sqrt(1 - np.square(t))

    def peak_pressure(self, a: float, centre: float, P: float, E_star: float) -> float:
        return P / (np.pi * a)


class RoundedFlat(Profile):
    """Flat of half-width ``b`` [m] with corners of radius ``R`` [m].

    Gap ``h0 = (|x| - b)^2 / (2R)`` for ``|x| > b``. Closed form of Ciavarella, Hills & Monno
    (1998) with ``x = a sin(phi)``, ``sin(phi0) = b/a``:
    ``P = E_star a^2 (pi - 2 phi0 - sin 2phi0) / (4R)`` and the pressure of `pressure`.

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.RoundedFlat(b=0.002, R=0.05), E_star=115e9, f=0.6, P=1e5)
    >>> round(contact.a * 1e3, 3), contact.a > contact.profile.b  # a [mm]: the corners are in contact
    (2.101, True)
    """

    SYMMETRIC = True

    def __init__(self, b: float, R: float) -> None:
        self.b = positive("b", b, "m")
        self.R = positive("R", R, "m")
        self.breakpoints = (-self.b, self.b)

    def __repr__(self) -> str:
        return f"RoundedFlat(b={self.b!r}, R={self.R!r})"

    def parameters(self) -> dict[str, float]:
        return {"b": self.b, "R": self.R}

    def load(self, a: ArrayLike, E_star: float) -> np.ndarray:
        """``P = E_star a^2 (2e - sin 2e) / (4R)`` [N/m], the load of the contact of half-width `a` [m],
        with ``e = pi/2 - phi0 = arctan(sqrt(a^2 - b^2) / b)``.

        Written in ``e`` so that it keeps its relative precision as ``a -> b``, where
        ``P ~ E_star b^2 (2e)^3 / (24 R)``; zero for ``a <= b``.
        """
        e = np.arctan2(self._root(a), self.b)
        return E_star * np.square(a) * _x_minus_sin(2 * e) / (4 * self.R)

    def _root(self, a: ArrayLike) -> np.ndarray:
        """``sqrt(a^2 - b^2)`` [m], zero for ``a <= b``."""
        a = np.asarray(a, dtype=float)
        return np.sqrt(np.clip((a - self.b) * (a + self.b), 0, None))

    def load_slope(self, a: ArrayLike, E_star: float) -> np.ndarray:
        """``dP/da = E_star a e / R`` [N/m^2]: `load` differentiated with ``de/da = b / (a sqrt(a^2 - b^2))``,
        ``E_star (2a (2e - sin 2e) + 4 b sqrt(a^2 - b^2) / a) / (4R)``, whose terms in ``sin 2e = 2 b sqrt(a^2 -
        b^2) / a^2`` cancel; zero for ``a <= b``."""
        return E_star * np.asarray(a, dtype=float) * np.arctan2(self._root(a), self.b) / self.R

    def half_width(self, P: float, E_star: float) -> tuple[float, float]:
        if P == 0:  # the flat touches at no load (the corrective contact at the onset of gross slip)
            return self.b, 0.0
        high = 2 * self.b
        while self.load(high, E_star) < P:
            high *= 2
        a = optimize.brentq(lambda a: self.load(a, E_star) / P - 1, self.b, high, xtol=1e-300, rtol=_RTOL, maxiter=500)
        return a, 0.0

    def pressure(self, t: np.ndarray, a: float, centre: float, P: float, E_star: float) -> np.ndarray:
        phi = np.arcsin(t)
        phi0 = np.arcsin(self.b / a)
        s, s0 = np.sin(phi), np.sin(phi0)
        log = lambda u, v: special.xlogy(u, np.abs(v))  # noqa: E731 - u log|v|, 0 when u = 0
        bracket = (
            (np.pi - 2 * phi0) * np.cos(phi)
            + log(s - s0, np.cos((phi + phi0) / 2))
            - log(s - s0, np.sin((phi - phi0) / 2))
            - log(s + s0, np.cos((phi - phi0) / 2))
            + log(s + s0, np.sin((phi + phi0) / 2))
        )
        return E_star * a / (2 * np.pi * self.R) * bracket


#: Pressure below ``-NEGATIVE_PRESSURE`` times the largest one refuses a `Gap`: the truncation of its
#: Chebyshev series stays well inside this (a bounded pressure is a sum of terms that fall off).
NEGATIVE_PRESSURE = 1e-6

#: Narrowest contact of a table, relative to the spacing of its rows there, that `Gap.check` accepts: on a
#: contact of a share r of an interval the spline's slope loses a factor 1/r to the cancellation of its
#: terms and the table's rounding (7 digits: 1e-4 relative in the contact's a at r = 2e-3).
TABLE_RESOLUTION = 1e-2

#: Points, in theta, where `Gap.check` looks for a negative pressure.
CHECK_POINTS = 4096

#: `Gap.check` looks for an undeclared cusp (`Gap.undeclared_cusp`) by halving each interval between the
#: `Gap.ORDER` Chebyshev points of the contact toward its steeper half, down to this share of ``a``: the slope's
#: difference quotient converges to the curvature where it is bounded (a jump of it included) and grows like
#: ``2^(k (2 - n))`` after ``k`` halvings at a cusp ``|x|^n``, like ``2^k`` at a corner. Rounding moves the
#: quotient of a slope by central differences (step ``1e-6 |x|``) by ~1e-2 of the curvature at this width.
CUSP_WIDTH = 1e-8
#: A quotient that ends above this many times the largest over the unhalved intervals is unbounded: a
#: bounded curvature ends at most at its largest there (a little above, where it peaks inside an interval),
#: ``|x|^1.5`` at ``2^10``, ``|x|^1.8`` at ``2^4`` times its interval's.
CUSP_GROWTH = 4.0

#: Gauss-Legendre points on each piece of the pressure's integral of a `Gap` with breakpoints in its contact
#: (`Gap.pressure`), and the points evaluated at once (a chunk's integrands take ~25 MB per three pieces).
PRESSURE_GAUSS = 16
PRESSURE_CHUNK = 4096
#: Octaves of the pieces cut toward a point next to a breakpoint, or at it (`Gap._pressure_integral`): down
#: to ``pi 2^-60``, 3e-18 rad, below which the point is the breakpoint to rounding.
PRESSURE_OCTAVES = 60
_PSI = np.pi * (np.polynomial.legendre.leggauss(PRESSURE_GAUSS)[0] + 1) / 2
_PSI_WEIGHTS = (np.pi / 2) * np.polynomial.legendre.leggauss(PRESSURE_GAUSS)[1] * np.sin(_PSI) / 2


class Gap(Profile):
    """Any convex profile, symmetric or not, given by its gap ``h0(x) >= 0`` [m].

    Parameters
    ----------
    h0 : callable
        Gap between the undeformed surfaces [m] as a function of ``x`` [m] (vectorised).
    slope : callable, optional
        ``h0'(x)`` [-]; by central differences when omitted.
    breakpoints : sequence of float, optional
        Positions [m] where the slope of ``h0`` is not smooth: its curvature jumps (the ends of a
        flat, say) or is unbounded (a cusp such as ``|x|^(3/2)``). The pressure's derivative is
        singular there; the pressure of a contact that holds one is integrated about it (`pressure`),
        and the Galerkin mesh resolves the traction about them
        (tests/models/test_galerkin.py::test_rounded_flat). Neither is done for a point it is not told
        of: an undeclared cusp in the contact, where the pressure would come out low (by about a percent
        at ``|x|^(3/2)``), is refused with its position when the `Contact` is built (`undeclared_cusp`;
        tests/physics/test_profiles.py::test_the_pressure_at_a_cusp_is_the_closed_form); so is an undeclared
        jump of a table's curvature (`undeclared_jump`), while one in a gap of functions is not found. A
        table finds its own (`from_table`).

    Notes
    -----
    With ``h0'(centre + a t) = sum_n b_n T_n(t)``, eq (1) bounded at both ends gives
    ``p = (E_star / 2) sum_{n>=1} b_n sin(n theta)`` with ``t = cos(theta)``, the consistency
    condition ``b_0 = 0`` (which fixes the centre) and ``P = pi a E_star b_1 / 4``, with `ORDER`
    points. Where the slope is not smooth its expansion converges only algebraically: ``a`` is held
    against eqs (1)-(2) integrated adaptively, split at the breakpoints, on the asymmetric flat of
    tests/test_hard_cases.py::test_gap_normal_contact_against_adaptive_quadrature, and the pressure
    of a contact holding a breakpoint is its integral instead of the series (`pressure`), held
    there and against the closed form of a cusp (tests/physics/test_profiles.py); a smooth gap
    converges fast. The solution is admissible only where this pressure is nowhere negative: a
    gap that is not convex where the bodies touch (a hollow, a wear scar) is refused by `check`
    when the `Contact` is built.
    """

    #: Chebyshev points for the expansion of the slope.
    ORDER = 1024

    def __init__(self, h0: GapFunction, slope: GapFunction | None = None, breakpoints: Sequence[float] = ()) -> None:
        if not callable(h0) or (slope is not None and not callable(slope)):
            raise ValueError("Gap needs callables h0(x) and, optionally, slope(x)")
        self.h0, self._slope, self.breakpoints = h0, slope, tuple(_positions(breakpoints).tolist())
        #: ``(x, h0)`` [m] of a profile made by `from_table`, else None.
        self.table = None

    def __repr__(self) -> str:
        """``Gap.from_table(x=[...], h0=[...], breakpoints=[...])`` of a table, every value to the last bit."""
        points = _floats(self.breakpoints)
        if self.table is None:
            return f"Gap({self.h0!r}, slope={self._slope!r}, breakpoints={points})"
        x, h0 = (_floats(column) for column in self.table)
        return f"Gap.from_table(x={x}, h0={h0}, breakpoints={points})"

    @classmethod
    def from_table(cls, x: ArrayLike, h0: ArrayLike, breakpoints: Sequence[float] | None = None) -> Gap:
        """Profile from a table of gaps ``h0`` [m] at increasing positions ``x`` [m], by cubic splines.

        A cubic spline has a continuous curvature, so across a jump of the table's curvature (the end
        of a flat, two radii meeting) it rings, and the pressure and traction next to the jump with it.
        The table is therefore interpolated by one spline between each two `breakpoints` (`_Segments`),
        each carried on to the breakpoints from its side. `breakpoints` None: those the table shows
        (`table_breakpoints`); a sequence, those (empty: none, one spline over the whole table); a jump the
        rows show that is not among them is refused when the `Contact` is built (`undeclared_jump`).
        """
        from scipy.interpolate import CubicSpline

        x, h0 = np.asarray(x, float), np.asarray(h0, float)
        points = table_breakpoints(x, h0) if breakpoints is None else _positions(breakpoints)
        inside = points[(points > x[0]) & (points < x[-1])]
        spline = CubicSpline(x, h0) if not inside.size else _Segments.fit(x, h0, inside)
        profile = cls(spline, spline.derivative(), points)
        profile.table = (x, h0)
        return profile

    def parameters(self) -> dict[str, np.ndarray]:
        """``breakpoints`` [m], and the table's ``x`` and ``h0`` [m] of a profile made by `from_table`.

        The functions of a profile made from them are not numbers: its parameters are only its
        breakpoints, and `from_parameters` refuses them.
        """
        table = {} if self.table is None else {"x": self.table[0].copy(), "h0": self.table[1].copy()}
        return table | {"breakpoints": np.array(self.breakpoints, dtype=float)}

    @classmethod
    def from_parameters(cls, parameters: Mapping[str, float | np.ndarray]) -> Gap:
        """The tabulated profile of `parameters` (`from_table`); a ValueError for a profile of functions."""
        if "x" not in parameters or "h0" not in parameters:
            raise ValueError(
                f"a Gap is rebuilt from its table x, h0 [m], found only {', '.join(parameters) or 'no parameters'}: "
                "a Gap of functions h0(x) records none"
            )
        x, h0, breakpoints = (np.atleast_1d(parameters.get(name, ())) for name in ("x", "h0", "breakpoints"))
        return cls.from_table(x, h0, breakpoints.tolist())

    def check(self, a: float, centre: float, P: float, E_star: float) -> None:  # noqa: B027 (a default: closed-form profiles pass)
        """Raise ValueError naming where the contact fails: outside the table, too narrow for its rows
        (`TABLE_RESOLUTION`), an undeclared cusp (`undeclared_cusp`) or jump of a table's curvature
        (`undeclared_jump`), or a negative pressure.

        The pressure is sampled at `CHECK_POINTS` Chebyshev angles; one below `NEGATIVE_PRESSURE`
        of the largest is negative. For a table, the message starts with the first knot in the
        contact (in the table, if the contact leaves it) where the spline's curvature is negative.
        """
        low, high = centre - a, centre + a
        if self.table is not None and not self.table[0][0] <= low < high <= self.table[0][-1]:
            x = self.table[0]
            table = f"[{x[0]:.6g}, {x[-1]:.6g}] m"
            self._refuse(x[0], x[-1], f"the contact [{low:.6g}, {high:.6g}] m leaves the table's x in {table}")
        if self.table is not None:
            x = self.table[0]
            row = min(max(int(np.searchsorted(x, centre)), 1), x.size - 1)
            spacing = x[row] - x[row - 1]
            if 2 * a < TABLE_RESOLUTION * spacing:
                raise ValueError(
                    f"the contact [{low:.6g}, {high:.6g}] m is narrower than {TABLE_RESOLUTION:g} of the spacing "
                    f"{spacing:.6g} m of the table's rows there, where the spline's slope is lost to rounding: "
                    "tabulate the gap finer where the bodies touch"
                )
        undeclared = (
            (
                self.undeclared_cusp,
                "the gap's curvature is unbounded",
                " (a cusp or a corner), where the pressure "
                "would come out low: declare it, Gap(h0, slope, breakpoints=[{x}])",
            ),
            (
                self.undeclared_jump,
                "the table's curvature jumps",
                ", where one spline across it rings and the "
                "traction next to it errs: declare it, Gap.from_table(x, h0, breakpoints=[..., {x}]) (breakpoints = "
                "[..., {x}] in a history file), or leave breakpoints out to use those the table shows",
            ),
        )
        for find, problem, remedy in undeclared:
            x = find(a, centre)
            if x is not None:
                where = f"at x = {x:.6g} m in the contact [{low:.6g}, {high:.6g}] m"
                raise ValueError(f"{problem} {where}{remedy.format(x=f'{x:.6g}')}")
        t = np.cos((np.arange(CHECK_POINTS) + 0.5) * np.pi / CHECK_POINTS)[::-1]
        p = self.pressure(t, a, centre, P, E_star)
        negative = np.flatnonzero(p < -NEGATIVE_PRESSURE * p.max())
        if negative.size:
            k = negative[0]
            where = f"the pressure is negative at x = {centre + a * t[k]:.6g} m ({p[k]:.4g} Pa) in the contact"
            self._refuse(low, high, f"{where} [{low:.6g}, {high:.6g}] m")

    def undeclared_cusp(self, a: float, centre: float) -> float | None:
        """Position [m] in the contact ``centre +- a`` [m] where the curvature of ``h0`` is unbounded (a cusp
        such as ``|x|^(3/2)``, or a corner) and no breakpoint is declared within a spacing of the
        contact's Chebyshev points; None where there is none.

        Each interval between the `ORDER` Chebyshev points of the contact is halved toward its half of
        the larger slope difference quotient, down to `CUSP_WIDTH` ``a``; a final quotient above
        `CUSP_GROWTH` times the largest of the unhalved intervals is unbounded. The position is the
        shortest decimal in the final interval. The sine series of
        `pressure` converges slowly at such a point and leaves the pressure there low (by about a
        percent at ``|x|^(3/2)``), which its declared breakpoint avoids.
        """
        x = centre + a * np.cos((np.arange(self.ORDER) + 0.5) * np.pi / self.ORDER)[::-1]
        low, high = x[:-1], x[1:]
        slope_low, slope_high = self.slope(low), self.slope(high)
        start = np.abs(slope_high - slope_low) / (high - low)
        for _ in range(int(np.log2(np.diff(x).max() / (CUSP_WIDTH * a)))):
            middle = (low + high) / 2
            slope_middle = self.slope(middle)
            halve = high - low >= 2 * CUSP_WIDTH * a
            left = np.abs(slope_middle - slope_low) >= np.abs(slope_high - slope_middle)
            low, slope_low = np.where(halve & ~left, middle, low), np.where(halve & ~left, slope_middle, slope_low)
            high, slope_high = np.where(halve & left, middle, high), np.where(halve & left, slope_middle, slope_high)
        quotient = np.abs(slope_high - slope_low) / (high - low)
        spacing = np.diff(x).max()
        declared = np.asarray(self.breakpoints, dtype=float)
        near = np.abs((low + high)[:, None] / 2 - declared).min(axis=1, initial=np.inf) <= spacing
        cusps = np.flatnonzero((quotient > CUSP_GROWTH * start.max()) & ~near)
        if not cusps.size:
            return None
        k = cusps[np.argmax(quotient[cusps])]
        digits = range(int(np.floor(-np.log10(a))) - 1, 340)
        return next(float(np.round(low[k], d)) + 0.0 for d in digits if low[k] <= np.round(low[k], d) <= high[k])

    def undeclared_jump(self, a: float, centre: float) -> float | None:
        """Position [m] in the contact ``centre +- a`` [m] where the curvature of a table jumps
        (`table_breakpoints` of its rows) and no breakpoint is declared within a row's spacing of it;
        None where there is none, and for a gap of functions.

        The spline is continuous in its curvature across an undeclared jump, so it rings there and the
        pressure and traction next to the jump with it (tests/physics/test_profiles.py).
        """
        if self.table is None:
            return None
        x = self.table[0]
        jumps = table_breakpoints(*self.table)
        spacing = np.diff(x)[np.clip(np.searchsorted(x, jumps) - 1, 0, x.size - 2)]
        declared = np.asarray(self.breakpoints, dtype=float)
        away = np.abs(jumps[:, None] - declared).min(axis=1, initial=np.inf) > spacing
        undeclared = jumps[away & (np.abs(jumps - centre) < a)]
        return float(undeclared[0]) if undeclared.size else None

    def _refuse(self, low: float, high: float, problem: str) -> NoReturn:
        """Raise ValueError with `problem`, after the first knot of a table in [low, high] where it is concave."""
        concave = np.zeros(0)
        if self.table is not None:
            x = self.table[0][(self.table[0] >= low) & (self.table[0] <= high)]
            concave = x[self.h0(x, 2) < 0]
        first = f"the table's curvature is first negative at x = {concave[0]:.6g} m, so " if concave.size else ""
        raise ValueError(f"{first}{problem}: a gap must be convex where the bodies touch")

    def slope(self, x: np.ndarray) -> np.ndarray:
        if self._slope is not None:
            return np.asarray(self._slope(x), float)
        step = 1e-6 * max(np.max(np.abs(x)), np.finfo(float).tiny)
        return (np.asarray(self.h0(x + step), float) - np.asarray(self.h0(x - step), float)) / (2 * step)

    def _coefficients(self, a: float, centre: float) -> np.ndarray:
        """Chebyshev coefficients ``b_n`` of ``h0'(centre + a t)``."""
        theta = (np.arange(self.ORDER) + 0.5) * np.pi / self.ORDER
        coefficients = fft.dct(self.slope(centre + a * np.cos(theta)), type=2) / self.ORDER
        coefficients[0] /= 2
        return coefficients

    def _centre(self, a: float) -> float:
        """Centre that makes the pressure bounded at both ends (``b_0 = 0``)."""
        b0 = lambda c: self._coefficients(a, c)[0]  # noqa: E731 - increasing in c for convex h0
        low, high = _bracket(b0, -a, a, lower=-np.inf)
        return optimize.brentq(b0, low, high, xtol=1e-14 * a, rtol=_RTOL)

    def half_width(self, P: float, E_star: float) -> tuple[float, float]:
        load = lambda a: np.pi * a * E_star * self._coefficients(a, self._centre(a))[1] / 4  # noqa: E731
        try:
            with np.errstate(over="ignore"):  # an overflowing load is above P: the bracket narrows
                low, high = _bracket(lambda a: load(a) - P, 0.5, 2.0, lower=0.0)
                a = optimize.brentq(lambda a: load(a) / P - 1, low, high, xtol=1e-300, rtol=_RTOL)
            return a, self._centre(a)
        except RuntimeError:  # brentq's: the load, or b_0 of the centre, is not monotonic to rounding
            raise ValueError(
                f"profile: no contact solution found for P = {P:g} N/m: the load does not converge in the half-width "
                "(rounding of the slope on a contact far narrower than the gap's features, such as a table's rows)"
            ) from None

    def pressure(self, t: np.ndarray, a: float, centre: float, P: float, E_star: float) -> np.ndarray:
        """The pressure [Pa]: the sine series of the Notes, or where the contact holds a breakpoint, its integral.

        Next to a breakpoint the series converges slowly (at a cusp its terms leave the pressure low:
        tests/physics/test_profiles.py::test_the_pressure_at_a_cusp_is_the_closed_form), so there the
        pressure is the integral of eq (1) bounded at both ends,
        ``p = (E_star / 2 pi) sin(theta) int_0^pi (h0'(centre + a cos u) - h0'(centre + a t)) / (cos u - t) du``
        (the principal value taken out by the subtracted slope, since ``PV int_0^pi du / (cos u - t) = 0``),
        by Gauss-Legendre on the pieces between ``theta`` and the breakpoints, graded toward each end
        (`_pressure_integral`).
        """
        breaks = (np.asarray(self.breakpoints, dtype=float) - centre) / a
        breaks = breaks[np.abs(breaks) < 1]
        if breaks.size:
            return self._pressure_integral(np.asarray(t, dtype=float), a, centre, E_star, np.arccos(breaks))
        coefficients = self._coefficients(a, centre)
        n = np.arange(1, coefficients.size)
        theta = np.arccos(np.clip(t, -1, 1))
        return E_star / 2 * np.sin(np.multiply.outer(theta, n)) @ coefficients[1:]

    def _pressure_integral(self, t: np.ndarray, a: float, centre: float, E_star: float, kinks: np.ndarray):
        """`pressure` [Pa] at `t` by its integral, split at ``theta = arccos(t)`` and the angles `kinks` [rad].

        On each piece ``[lo, hi]``, ``u = lo + (hi - lo) sin(psi / 2)^2`` at `PRESSURE_GAUSS` Gauss-Legendre
        points ``psi`` in ``(0, pi)``: the integrand's singularities at the ends (``|u - kink|^(-1/2)`` at a
        cusp, a jump at a curvature jump) become smoother in ``psi``. A ``theta`` at a distance ``d`` from the
        nearest kink makes the integrand vary on the scale ``d`` between the two, so the pieces are also cut
        at ``d 2^j`` on either side of their midpoint, out to ``[0, pi]``: each piece then lies at least its
        own length from both, and at a kink itself (``d`` taken as ``pi 2^-PRESSURE_OCTAVES``) the pieces
        that halve toward it integrate its singularity (``|u - kink|^(n - 2)`` at a cusp ``|x|^n``).
        """
        flat = np.clip(t.ravel(), -1.0, 1.0)
        theta = np.arccos(flat)
        d = np.maximum(np.min(np.abs(theta[:, None] - kinks), axis=1), np.pi * 2.0**-PRESSURE_OCTAVES)
        octaves = np.ceil(np.log2(np.pi / d)).astype(int)
        p = np.empty(flat.size)
        for count in np.unique(octaves).tolist():
            group = np.flatnonzero(octaves == count)
            for chunk in np.array_split(group, -(-group.size // PRESSURE_CHUNK)):
                nearest = kinks[np.argmin(np.abs(theta[chunk, None] - kinks), axis=1)]
                middle, offsets = (theta[chunk] + nearest) / 2, d[chunk, None] * 2.0 ** np.arange(count)
                cuts = np.column_stack(
                    [
                        np.broadcast_to(np.concatenate([[0.0, np.pi], kinks]), (chunk.size, kinks.size + 2)),
                        theta[chunk],
                        middle[:, None] - offsets,
                        middle[:, None] + offsets,
                    ]
                )
                cuts = np.sort(np.clip(cuts, 0.0, np.pi), axis=1)
                p[chunk] = self._pieces(flat[chunk], cuts, a, centre) * E_star / (2 * np.pi) * np.sin(theta[chunk])
        return p.reshape(t.shape)

    def _pieces(self, t: np.ndarray, cuts: np.ndarray, a: float, centre: float) -> np.ndarray:
        """``int_0^pi (h0'(centre + a cos u) - h0'(centre + a t)) / (cos u - t) du`` [-] at each of `t` (n,), on
        the pieces between its ascending `cuts` (n, K) [rad], graded toward both ends (`_pressure_integral`)."""
        lo, width = cuts[:, :-1, None], np.diff(cuts, axis=1)[:, :, None]
        u = lo + width * np.sin(_PSI / 2) ** 2
        apart = np.cos(u) - t[:, None, None]  # zero only where u rounds to theta, at an end: a bounded point dropped
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = (self.slope(centre + a * np.cos(u)) - self.slope(centre + a * t)[:, None, None]) / apart
        return np.sum(np.where((width > 0) & (apart != 0), ratio * width * _PSI_WEIGHTS, 0.0), axis=(1, 2))


#: A jump of the table's curvature (`table_breakpoints`) is a change of its second divided differences across an
#: interval larger than `JUMP_RATIO` times their changes over as many rows on either side, and than
#: `JUMP_FLOOR` times their largest magnitude (above rounding).
JUMP_RATIO = 10.0
JUMP_FLOOR = 1e-3


def _positions(breakpoints: Sequence[float]) -> np.ndarray:
    """`breakpoints` [m] as an ascending array without repeats; ValueError unless a list of finite numbers."""
    points = np.asarray(breakpoints, dtype=float)
    if points.ndim != 1 or not np.all(np.isfinite(points)):
        raise ValueError(f"breakpoints must be a list of positions [m], found {breakpoints!r}")
    return np.unique(points)


def table_breakpoints(x: np.ndarray, h0: np.ndarray) -> np.ndarray:
    """Positions [m] where the curvature of the table ``h0(x)`` [m] jumps, found from its rows.

    ``D_i``, twice the second divided difference of rows ``i - 1, i, i + 1``, is the curvature there for a
    smooth gap, and changes little from row to row (by the third derivative times the spacing). Across a
    jump between rows ``k`` and ``k + 1`` the curvature to its left, ``D_(k-1)``, and to its right,
    ``D_(k+2)``, differ by the jump, far more (`JUMP_RATIO`) than over as many rows on either side. The
    jump is then placed where the parabolas through rows ``k - 2 .. k`` and ``k + 1 .. k + 3`` meet with a
    common slope, the vertex of their difference, which is ``(J / 2) (x - b)^2`` for a gap continuous
    with its slope and of constant curvature on either side; a vertex outside ``[x_k, x_(k+1)]`` is no
    jump there. Tables of fewer than 8 rows show none. Cusps (an unbounded curvature) are not looked for.
    """
    if x.size < 8:
        return np.zeros(0)
    D = 2 * np.diff(np.diff(h0) / np.diff(x)) / (x[2:] - x[:-2])  # D[i - 1] at row i
    k = np.arange(3, x.size - 4)  # intervals [x_k, x_(k+1)] with 3 rows left and 4 right of them
    change = np.abs(D[k + 1] - D[k - 2])
    beside = np.maximum(np.abs(D[k - 2] - D[k - 3]), np.abs(D[k + 2] - D[k + 1])) * 3
    found = []
    for i in k[(change > JUMP_RATIO * beside) & (change > JUMP_FLOOR * np.abs(D).max())].tolist():
        left = np.polyfit(x[i - 2 : i + 1], h0[i - 2 : i + 1], 2)
        right = np.polyfit(x[i + 1 : i + 4], h0[i + 1 : i + 4], 2)
        difference = right - left
        if difference[0] != 0:
            spacing = x[i + 1] - x[i]
            vertex = -difference[1] / (2 * difference[0])  # a jump at a row: its rounding may leave it just outside
            if x[i] - 1e-3 * spacing <= vertex <= x[i + 1] + 1e-3 * spacing:
                vertex = min(max(vertex, x[i]), x[i + 1])
                if not any(abs(vertex - b) <= spacing for b in found):
                    found.append(float(vertex))
    return np.array(found)


class _Segments:
    """Cubic splines of a table between its breakpoints, called as a `scipy.interpolate.CubicSpline` is.

    Each spline is fitted to the rows from one breakpoint to the next (a row at a breakpoint ends both
    of its pieces) and carried on to them from its side (`Gap.from_table`).
    """

    def __init__(self, splines, bounds):
        self.splines, self.bounds = splines, bounds

    @classmethod
    def fit(cls, x: np.ndarray, h0: np.ndarray, bounds: np.ndarray) -> _Segments:
        """The splines of the table `x`, `h0` [m] between the ascending `bounds` [m] inside it."""
        from scipy.interpolate import CubicSpline

        edges = np.concatenate([[x[0]], bounds, [x[-1]]])
        splines = []
        for low, high in itertools.pairwise(edges.tolist()):
            rows = (x >= low) & (x <= high)
            if np.count_nonzero(rows) < 2:
                raise ValueError(
                    f"breakpoints: fewer than 2 rows of the table lie in [{low:.6g}, {high:.6g}] m, between two of "
                    f"the breakpoints {bounds.tolist()}, expected a spline's worth on each piece"
                )
            splines.append(CubicSpline(x[rows], h0[rows]))
        return cls(splines, bounds)

    def __call__(self, x: ArrayLike, nu: int = 0) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        piece = np.searchsorted(self.bounds, x)
        values = np.empty(x.shape)
        for k, spline in enumerate(self.splines):
            on = piece == k
            values[on] = spline(x[on], nu)
        return values

    def derivative(self) -> _Segments:
        return _Segments([spline.derivative() for spline in self.splines], self.bounds)


#: Taylor coefficients of ``x - sin x = sum_k (-1)^k x^(2k+3) / (2k+3)!``, k = 0 .. 7.
_X_MINUS_SIN = [(-1) ** k / special.factorial(2 * k + 3) for k in range(8)]


def _x_minus_sin(x: ArrayLike) -> np.ndarray:
    """``x - sin(x)`` for ``x >= 0`` without the cancellation of the difference at small ``x``.

    Below 0.5 its Taylor series to ``x^17`` (the next term is ``1e-21`` of the sum there), above
    it the difference; both are held to rounding against a 60-digit sum of the series by
    tests/physics/test_profiles.py::test_x_minus_sin_keeps_its_relative_precision.
    """
    x = np.asarray(x, dtype=float)
    series = np.polynomial.polynomial.polyval(x**2, _X_MINUS_SIN) * x**3
    return np.where(x < 0.5, series, x - np.sin(x))


def _lacks(cls: type, name: str) -> bool:
    """The class has no method `name`, or only the abstract one of its base."""
    method = getattr(cls, name, None)
    return not callable(method) or getattr(method, "__isabstractmethod__", False)


def profile_class(name: str | None) -> type[Profile] | None:
    """The profile class called `name`: this package's, or one defined in this session; None where
    no class, or more than one, has that name."""
    found, classes = set(), [Profile]
    while classes:
        cls = classes.pop()
        classes += cls.__subclasses__()
        if cls.__name__ == name:
            found.add(cls)
    return found.pop() if len(found) == 1 else None


def recorded_profile(attrs: Mapping[str, object]) -> tuple[str | None, dict[str, object]]:
    """The class name and the parameters of the profile that a result's attributes `attrs` record.

    A result records ``profile_class`` and ``profile_<name>`` (`Profile.attributes`); one written
    before it did has only ``profile``, the profile's repr, read instead by `_read_repr`.

    Examples
    --------
    >>> import fretting as fr
    >>> recorded_profile(fr.Hertz(0.05).attributes())
    ('Hertz', {'R': 0.05})
    >>> recorded_profile({"profile": "RoundedFlat(b=0.002, R=0.05)"})  # a result written before the facts
    ('RoundedFlat', {'b': 0.002, 'R': 0.05})
    """
    if "profile_class" not in attrs:
        return _read_repr(str(attrs["profile"]))
    parameters = {
        name.removeprefix(PARAMETER_PREFIX): value
        for name, value in attrs.items()
        if name.startswith(PARAMETER_PREFIX) and name != "profile_class"
    }
    return str(attrs["profile_class"]), parameters


def _read_repr(text: str) -> tuple[str | None, dict[str, object]]:
    """The class name and parameters in a profile's repr, such as ``Hertz(R=0.05)`` or
    ``Gap.from_table(x=[...], h0=[...], breakpoints=[...])``: the keyword arguments whose values are
    numbers or lists of them; the name alone where the repr is no expression (a `Gap` of functions),
    and None for a repr of no class."""
    try:
        call = ast.parse(text, mode="eval").body
    except SyntaxError:
        call = None
    if not isinstance(call, ast.Call):
        named = re.match(r"(\w+)[.(]", text)
        return (named.group(1) if named else None), {}
    function = call.func.value if isinstance(call.func, ast.Attribute) else call.func
    parameters = {}
    for keyword in call.keywords:
        try:
            value = ast.literal_eval(keyword.value)
        except ValueError:
            continue
        if isinstance(value, int | float):
            parameters[keyword.arg] = value
        elif isinstance(value, list) and all(isinstance(item, int | float) for item in value):
            parameters[keyword.arg] = np.array(value, dtype=float)
    return getattr(function, "id", None), parameters


def _floats(values: Iterable[float]) -> str:
    """``[v, ...]``: each value's shortest repr that reads back to the same float."""
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


def _bracket(function: Callable[[float], float], low: float, high: float, lower: float) -> tuple[float, float]:
    """Widen ``[low, high]`` geometrically until the increasing `function` changes sign."""
    for _ in range(400):
        f_low, f_high = function(low), function(high)
        if f_low <= 0 <= f_high:
            return low, high
        width = high - low
        if f_low > 0:
            low = low / 2 if lower == 0.0 else low - width
        if f_high < 0:
            high = high * 2 if lower == 0.0 else high + width
    raise ValueError("profile: no contact solution found; is the gap convex with a minimum?")
