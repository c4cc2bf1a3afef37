"""The four solution methods of Table A of the seed paper, for monotonic pure shear.

A symmetric contact is pressed by ``P`` and held; the shear force ``Q`` then grows from zero to
``Q < f P``. The stick zone is ``|x - centre| < c`` and the slip zones carry ``q = f p``. The four
routes of Table A reach the same state:

1. corrective traction on the sliding solution (Ciavarella-Jaeger, section 2, eqs 3-5);
2. corrective traction on the adhered solution (section 4, eqs 24-25, kernel B.1);
3. corrective dislocations on the sliding solution (section 5, eqs 26-28, kernel B.2);
4. corrective dislocations on the adhered solution: the engine, `fretting.engine.simulation`.

Conventions of docs/theory/conventions.md: the slip ``s`` is what ``q`` drives, ``Q > 0`` gives ``s > 0``, and
the slip gradient (dislocation density) of a traction is
``B = ds/dx = -(2 / (pi E_star)) PV int q(xi) / (xi - x) dxi`` (eq A.1 with ``s = -u``).

A density bounded at both ends of ``[-l, l]`` is a sine series in ``theta``, ``x = l cos(theta)``:
``F = sum_n alpha_n sin(n theta) = sqrt(1 - t^2) sum_n alpha_n U_{n-1}(t)``, ``t = x / l``. Its Hilbert
transform ``(1/pi) PV int F(xi) / (xi - x) dxi`` is ``-sum_n alpha_n T_n(t)`` inside the interval and
``-sum_n alpha_n w^n`` outside it, ``w = t - sign(t) sqrt(t^2 - 1)``.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import xarray as xr
from numpy.polynomial import chebyshev, legendre
from numpy.typing import ArrayLike
from scipy import fft, linalg, optimize

from fretting._validate import finite
from fretting.engine.simulation import simulate
from fretting.loading.history import History
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.solver import chebyshev_angles
from fretting.physics import closed_forms
from fretting.physics.contact import Contact
from fretting.physics.profiles import Hertz
from fretting.results.variables import VARIABLES

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["METHODS", "partial_slip", "comparison_figure"]

#: Sine modes of the pressure (methods 1 and 3): a pressure whose slope has kinks (rounded
#: flat) converges slowly in them, and half as many leave method 3's traction visibly farther
#: from method 1's (both held against Ciavarella-Jaeger by
#: tests/analysis/test_methods.py::test_rounded_flat_ciavarella_jaeger).
MODES = 4096

#: Gauss-Chebyshev nodes in the stick zone (method 2): enough for the closed forms of
#: tests/analysis/test_methods.py (test_hertz_cattaneo_mindlin, test_rounded_flat_ciavarella_jaeger).
QUADRATURE = 256

#: Gauss-Legendre points in each slip zone (method 2): the integrand is smooth in ``theta``. On the
#: rounded flat 32 points give method 1's traction as closely as 128
#: (tests/analysis/test_methods.py::test_rounded_flat_ciavarella_jaeger).
ORDER = 32

#: Load increments of method 4: under monotonic loading the stick zone only shrinks, so the
#: final state does not depend on their number.
STEPS = 8

#: Largest asymmetry of ``p sqrt(1 - t^2)`` [p0] accepted as a symmetric contact.
SYMMETRY_TOLERANCE = 1e-6

#: Tolerance [a] of the root solve for the stick-zone end.
ROOT_TOLERANCE = 1e-13

#: Route of each method, after Table A of the seed paper.
NAMES = {
    1: "corrective traction on the sliding solution",
    2: "corrective traction on the adhered solution",
    3: "corrective dislocations on the sliding solution",
    4: "corrective dislocations on the adhered solution",
}

#: Scene of `comparison_figure`: Hertz, R = 50 mm, E_star = 115 GPa, f = 0.6, P = 100 N/mm.
FIGURE_SCENE = {"R": 0.05, "E_star": 115e9, "f": 0.6, "P": 1e5, "Q/fP": 0.6}


class _Solution(NamedTuple):
    """A method's answer at normalised positions ``t = (x - centre) / a``."""

    t: np.ndarray
    c: float
    q: np.ndarray
    stick: np.ndarray
    slip: np.ndarray | None


# Series and quadrature rules ------------------------------------------------------------------


def _second_kind_angles(n: int) -> np.ndarray:
    """``theta_k = k pi / (n + 1)``, k = 1..n: nodes of the bounded Gauss-Chebyshev rule."""
    return np.arange(1, n + 1) * np.pi / (n + 1)


def _grid(nodes: int) -> np.ndarray:
    """Output positions ``t``: the engine's Gauss-Chebyshev nodes (first kind), ascending."""
    return np.cos(chebyshev_angles(nodes))[::-1]


def _sine_coefficients(values: np.ndarray) -> np.ndarray:
    """``alpha_n``, n = 1..N, of the sine series through `values` at `_second_kind_angles` (N)."""
    return fft.dst(values, type=1) / (values.size + 1)


def _sine_series(alpha: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``sum_n alpha_n sin(n theta)`` at ``t = cos(theta)`` in [-1, 1]."""
    theta = np.arccos(np.clip(t, -1, 1))
    return np.sin(np.multiply.outer(theta, np.arange(1, alpha.size + 1))) @ alpha


def _chebyshev_coefficients(values: np.ndarray) -> np.ndarray:
    """``b_n``, n = 0..N-1, through `values` at `chebyshev_angles` (N), ``t`` descending.

    The N-point Gauss-Chebyshev rule of the first kind: ``b_n = (2/N) sum_k F(t_k) T_n(t_k)``,
    ``b_0`` half of that.
    """
    b = fft.dct(values, type=2) / values.size
    b[0] /= 2
    return b


def _outer_integral(b: np.ndarray, t: np.ndarray) -> np.ndarray:
    """``int_1^t sum_{n>=1} b_n w(tau)^n dtau`` at ``t >= 1``, ``w = tau - sqrt(tau^2 - 1)``.

    With ``tau = cosh(u)``, ``w^n = exp(-n u)``, each mode integrates to ``(r_{n-1} - r_{n+1}) / 2``
    with ``r_m(u) = (1 - exp(-m u)) / m`` and ``r_0(u) = u``.
    """
    u = np.arccosh(t)[:, None]
    n = np.arange(1, b.size)

    def ramp(m: np.ndarray) -> np.ndarray:
        return np.where(m == 0, u, -np.expm1(-m * u) / np.maximum(m, 1))

    return ((ramp(n - 1) - ramp(n + 1)) / 2) @ b[1:]


class _BoundedRule(NamedTuple):
    """Bounded-both-ends Gauss-Chebyshev rule for ``(1/pi) PV int_{-1}^{1} F(s) / (s - t) ds = G(t)``.

    ``F`` at the N nodes ``cos(theta_k)``, ``theta_k = k pi/(N+1)``; ``G`` at the N + 1 collocation
    points ``cos((2j-1) pi/(2N+2))``; the system ``sum_k sin(theta_k) F_k / ((N+1) (s_k - t_j)) = G_j``,
    factorised for least squares (the extra equation is the consistency condition).
    """

    theta: np.ndarray
    collocation: np.ndarray
    orthogonal: np.ndarray
    triangular: np.ndarray

    @classmethod
    def of_size(cls, n: int) -> _BoundedRule:
        theta = _second_kind_angles(n)
        collocation = np.cos(chebyshev_angles(n + 1))
        system = np.sin(theta) / ((n + 1) * (np.cos(theta) - collocation[:, None]))
        return cls(theta, collocation, *linalg.qr(system, mode="economic"))

    def solve(self, G: np.ndarray) -> np.ndarray:
        """``F`` at the nodes."""
        return linalg.solve_triangular(self.triangular, self.orthogonal.T @ G)

    def integral(self, F: np.ndarray) -> float:
        """``int_{-1}^{1} F ds``."""
        return np.pi / (self.theta.size + 1) * np.dot(np.sin(self.theta), F)


# Pieces shared by the methods -----------------------------------------------------------------


def _pressure_coefficients(contact: Contact, modes: int) -> np.ndarray:
    """Sine coefficients [Pa] of ``p(centre + a cos(theta))``, eqs (1)-(2), any bounded pressure."""
    t = np.cos(_second_kind_angles(modes))
    return _sine_coefficients(contact.pressure(contact.centre + contact.a * t))


def _sliding_slip_gradient(contact: Contact, alpha: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Slip gradient [-] of the sliding traction ``q = f p`` at ``x = centre + a t``, eq (26).

    ``B_sl = -(2 f / (pi E_star)) PV int p / (xi - x) dxi = (2 f / E_star) sum_n alpha_n T_n(t)``.
    """
    return 2 * contact.f / contact.E_star * chebyshev.chebval(t, np.concatenate([[0.0], alpha]))


def _slip(contact: Contact, alpha: np.ndarray, c: float, b: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Slip [m] at ``x = centre + a t``: zero in the stick zone, ``int_c^|x| B dx`` in the slip zones.

    The slip gradient there is the sliding one (eq 26) plus that of the stick-zone correction,
    whose Chebyshev coefficients on ``[-c, c]`` are `b`: ``sum_n b_n w((x - centre)/c)^n`` outside
    it. The slip is even in x.
    """
    X = np.abs(t) * contact.a
    slipping = X > c
    antiderivative = chebyshev.chebint(np.concatenate([[0.0], alpha]))
    sliding = chebyshev.chebval(X[slipping] / contact.a, antiderivative) - chebyshev.chebval(
        c / contact.a, antiderivative
    )
    slip = np.zeros_like(t)
    slip[slipping] = 2 * contact.f * contact.a / contact.E_star * sliding + c * _outer_integral(b, X[slipping] / c)
    return slip


def _traction(
    contact: Contact, t: np.ndarray, c: float, stick_traction: Callable[[np.ndarray], np.ndarray]
) -> tuple[np.ndarray, np.ndarray]:
    """``q = f p`` [Pa] in the slip zones and ``stick_traction(x - centre)`` in the stick zone."""
    x = contact.centre + contact.a * t
    q = contact.f * contact.pressure(x)
    stick = np.abs(t) * contact.a < c
    q[stick] = stick_traction(x[stick] - contact.centre)
    return q, stick


def _adhered_holds(contact: Contact, Q: float, t: np.ndarray) -> bool:
    """True when the fully stuck traction (eq 9) is below ``f p`` at every node: nothing slips.

    Compared as ``q_st sqrt(1 - t^2) = Q / (pi a)`` against ``f p sqrt(1 - t^2)``, which stays
    bounded for the sharp flat punch too, where the two are in the ratio ``Q / (f P)`` everywhere.
    """
    return bool(np.all(Q / (np.pi * contact.a) < contact.f * contact.pressure_weighted(t)))


def _fully_stuck(contact: Contact, Q: float, t: np.ndarray) -> _Solution:
    """The adhered solution, eq (9): ``c = a``, no slip."""
    q = Q / (np.pi * contact.a * np.sqrt(1 - t**2))
    return _Solution(t, contact.a, q, np.ones(t.shape, bool), np.zeros_like(t))


def _stick_end(contact: Contact, Q: float, force: Callable[[float], float]) -> float:
    """Stick-zone half-width [m] at which the traction carrying `force` (c) [N/m] is bounded.

    The slip zones carry ``f p`` and the stick zone the bounded solution of its integral
    equation, together ``force(c)``. The general stick-zone solution adds
    ``K / (pi sqrt(c^2 - x^2))``, and equilibrium sets ``K = Q - force(c)``: bounded only at the
    root of K, which runs from ``Q - f P < 0`` at ``c = 0`` to ``Q`` at ``c = a``.
    """
    a = contact.a

    def K(c: float) -> float:
        return Q - force(c)

    if K(a) <= 0:
        return a
    return optimize.brentq(K, ROOT_TOLERANCE * a, a, xtol=ROOT_TOLERANCE * a)


# The four methods ------------------------------------------------------------------------------


def _method_1(contact: Contact, Q: float, *, nodes: int = DEFAULT_NODES, modes: int = MODES) -> _Solution:
    """Corrective traction on the sliding solution (Ciavarella-Jaeger), eqs (3)-(5).

    ``q = f (p(x; P) - p(x; P_c))`` with ``P_c = P - Q / f``; the stick zone is the contact of
    ``P_c``. The slip is ``f`` times the gap ``g_c`` of that corrective contact, whose slope is
    ``h0' + (2 / (pi E_star)) PV int p_c / (xi - x) dxi``, with ``h0'`` from eq (1) at ``P``.
    """
    t = _grid(nodes)
    q, corrective = closed_forms.ciavarella_jaeger(contact, Q, contact.centre + contact.a * t)
    c = corrective.a
    stick = np.abs(t) * contact.a < c
    if c >= contact.a:
        return _Solution(t, c, q, stick, np.zeros_like(t))
    p_c = corrective.pressure(corrective.centre + c * np.cos(_second_kind_angles(modes)))
    b = np.concatenate([[0.0], -2 * contact.f / contact.E_star * _sine_coefficients(p_c)])
    return _Solution(t, c, q, stick, _slip(contact, _pressure_coefficients(contact, modes), c, b, t))


def _method_2(
    contact: Contact, Q: float, *, nodes: int = DEFAULT_NODES, quadrature: int = QUADRATURE, order: int = ORDER
) -> _Solution:
    """Corrective traction on the adhered solution, eqs (24)-(25).

    The slip zones get ``q_c1 = f p - q_st`` (eq 24, ``q_st`` of eq 9), and the stick zone the
    traction ``q_c2`` that cancels their strain there (eq 25, kernel B.1, bounded solution):

        (1/pi) PV int_{-c}^{c} q_c2(xi) / (xi - x) dxi = -(1/pi) int_{c<|xi|<a} q_c1(xi) / (xi - x) dxi.

    ``q_c1`` ends with a jump at ``|x| = c``; writing ``q_c2 = f p(c) - q_st + chi`` (``q_c1`` continued
    with ``p`` frozen at ``p(c)``) removes it and, as ``q_st`` strains nothing inside the contact,
    leaves for the bounded ``chi``

        (1/pi) PV int_{-c}^{c} chi / (xi - x) dxi
            = -(f/pi) int_{c<|xi|<a} (p(xi) - p(c)) / (xi - x) dxi - (f p(c) / pi) ln((a - x) / (a + x)),

    integrated over the slip zones by Gauss-Legendre in ``xi = a cos(theta)`` and solved for
    ``chi`` by `_BoundedRule`. The stick zone carries ``q = f p(c) + chi``.
    """
    t = _grid(nodes)
    if _adhered_holds(contact, Q, t):
        return _fully_stuck(contact, Q, t)
    rule = _BoundedRule.of_size(quadrature)
    a, f = contact.a, contact.f

    def pressure(r: np.ndarray) -> np.ndarray:
        return contact.pressure(contact.centre + r)

    def solve(c: float) -> tuple[np.ndarray, float, float]:
        """``chi`` [Pa] at the nodes, ``p(c)`` [Pa] and the force [N/m] of the whole traction."""
        xi, weight = _slip_zone_quadrature(a, c, order)
        x = c * rule.collocation
        p_c = pressure(np.array([c]))[0]
        slip_zones = (weight * (pressure(xi) - p_c)) @ (2 * x / np.subtract.outer(xi**2, x**2))  # both zones
        chi = rule.solve(-f / np.pi * (slip_zones + p_c * np.log((a - x) / (a + x))))
        force = 2 * c * f * p_c + c * rule.integral(chi) + 2 * f * weight @ pressure(xi)
        return chi, p_c, force

    c = _stick_end(contact, Q, lambda c: solve(c)[2])
    chi, p_c, _ = solve(c)
    alpha = _sine_coefficients(chi)
    q, stick = _traction(contact, t, c, lambda r: f * p_c + _sine_series(alpha, r / c))
    return _Solution(t, c, q, stick, None)


def _slip_zone_quadrature(a: float, c: float, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes ``xi`` [m] in ``[c, a]`` and weights [m], uniform in ``theta``, ``xi = a cos(theta)``."""
    u, w = legendre.leggauss(order)
    theta_c = np.arccos(c / a)
    xi = a * np.cos(theta_c * (u + 1) / 2)
    return xi, theta_c / 2 * w * np.sqrt(a**2 - xi**2)


def _method_3(contact: Contact, Q: float, *, nodes: int = DEFAULT_NODES, modes: int = MODES) -> _Solution:
    """Corrective dislocations on the sliding solution, eqs (26)-(28).

    In the stick zone the dislocations ``B = -B_sl`` (eq 28) cancel the sliding slip gradient
    (eq 26). The traction they need, bounded at both ends, is eq (B.2),

        q_c(x) = (E_star sqrt(c^2 - x^2) / (2 pi)) int_{-c}^{c} B(xi) / (sqrt(c^2 - xi^2) (xi - x)) dxi,

    by the Gauss-Chebyshev rule of the first kind (the weight of B.2) with ``modes + 1`` nodes,
    exact for the interpolated pressure; in Chebyshev form ``B = sum b_n T_n(x/c)`` gives
    ``q_c = (E_star / 2) sum b_n sin(n theta)``, with force ``(pi E_star c / 4) b_1``; the
    consistency condition ``b_0 = 0`` holds by symmetry. ``q_c`` is confined to the stick zone, so
    the slip zones keep ``q = f p``: the dislocations there are the slip gradient ``q_c`` induces
    outside the stick zone, ``sum b_n w(x/c)^n`` (eq B.1), bounded at ``|x| = c`` at the root of
    `_stick_end`.
    """
    t = _grid(nodes)
    if _adhered_holds(contact, Q, t):
        return _fully_stuck(contact, Q, t)
    alpha = _pressure_coefficients(contact, modes)
    rule_nodes = np.cos(chebyshev_angles(modes + 1))

    def b(c: float) -> np.ndarray:
        return _chebyshev_coefficients(-_sliding_slip_gradient(contact, alpha, c * rule_nodes / contact.a))

    def force(c: float) -> float:
        return contact.f * contact.P + np.pi * contact.E_star * c / 4 * b(c)[1]

    c = _stick_end(contact, Q, force)
    b_c = b(c)

    def stick_traction(r: np.ndarray) -> np.ndarray:
        return contact.f * contact.pressure(contact.centre + r) + contact.E_star / 2 * _sine_series(b_c[1:], r / c)

    q, stick = _traction(contact, t, c, stick_traction)
    return _Solution(t, c, q, stick, _slip(contact, alpha, c, b_c, t))


def _method_4(contact: Contact, Q: float, *, nodes: int = DEFAULT_NODES, steps: int = STEPS) -> _Solution:
    """Corrective dislocations on the adhered solution: `fretting.engine.simulation` (eqs 9-12), last step."""
    last = simulate(contact, History.piecewise_linear([0.0, Q], None, steps), nodes=nodes).isel(step=-1)
    t = (last.x.values - contact.centre) / contact.a
    c = float(last.stick_end[0] - last.stick_start[0]) / 2
    return _Solution(t, c, last.q.values, last.stick.values, last.slip.values)


#: Method number -> solver.
METHODS = {1: _method_1, 2: _method_2, 3: _method_3, 4: _method_4}


def partial_slip(contact: Contact, Q: float, method: int, **options: int) -> xr.Dataset:
    """Partial slip of a symmetric contact under monotonic shear, by one method of Table A.

    Parameters
    ----------
    contact : Contact
        A contact whose pressure is symmetric about its centre.
    Q : float
        Shear force per unit length [N/m], reached from zero: ``0 <= Q < f P``.
    method : {1, 2, 3, 4}
        1 corrective traction on the sliding solution (Ciavarella-Jaeger, eqs 3-5); 2 corrective
        traction on the adhered solution (eqs 24-25); 3 corrective dislocations on the sliding
        solution (eqs 26-28); 4 corrective dislocations on the adhered solution (the engine).
    **options
        ``nodes``: output positions, the engine's Gauss-Chebyshev nodes (all methods);
        ``modes``: sine modes of the pressure (1, 3); ``quadrature``: Gauss-Chebyshev nodes in
        the stick zone (2); ``order``: Gauss-Legendre points in the slip zones (2); ``steps``:
        load increments (4).

    Returns
    -------
    xarray.Dataset
        Coordinate ``x`` [m]; ``q`` [Pa], ``stick`` (bool) and ``slip`` [m], except for method 2,
        which corrects tractions only and gives no slip. Attributes ``method``, ``model``, ``c``
        (stick-zone half-width [m], below the grid scale), ``Q``, ``a``, ``p0``, ``E_star``, ``f``,
        ``P``, ``profile``.

    Raises
    ------
    ValueError
        For an unknown method, an asymmetric contact, or ``Q`` outside ``[0, f P)``.

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> exact = partial_slip(contact, 0.5 * contact.f * contact.P, 1)
    >>> round(exact.attrs["c"] / contact.a, 6)  # c/a = sqrt(1 - Q/(f P)) on Hertz
    0.707107
    >>> engine = partial_slip(contact, 0.5 * contact.f * contact.P, 4, nodes=32)
    >>> engine.sizes["x"], bool(engine.stick.any() and not engine.stick.all())
    (32, True)
    """
    if isinstance(method, bool) or method not in tuple(METHODS):
        raise ValueError(f"method must be one of {', '.join(map(str, METHODS))}, found {method!r}")
    _check_symmetric(contact)
    Q = finite("Q", Q)
    limit = contact.f * contact.P
    if not 0 <= Q < limit:
        raise ValueError(f"Q must lie in [0, f P) = [0, {limit:.6g}) N/m, found Q = {Q!r}")
    return _dataset(contact, Q, int(method), METHODS[method](contact, Q, **options))


def _check_symmetric(contact: Contact) -> None:
    if not isinstance(contact, Contact):
        raise ValueError(f"contact must be a fretting.Contact, found {contact!r}")
    t = _grid(DEFAULT_NODES)
    asymmetry = np.max(np.abs(contact.pressure_weighted(t) - contact.pressure_weighted(-t)))
    if asymmetry > SYMMETRY_TOLERANCE * contact.p0:
        raise ValueError(f"the pressure of {contact.profile!r} is not symmetric about its centre")


def _dataset(contact: Contact, Q: float, method: int, solution: _Solution) -> xr.Dataset:
    """Dataset with the units and long names of `fretting.results.variables.VARIABLES`."""

    def variable(name: str, values: ArrayLike) -> xr.Variable:
        _, units, long_name = VARIABLES[name]
        return xr.Variable(("x",), np.asarray(values), {"units": units, "long_name": long_name})

    data = {"q": solution.q, "stick": solution.stick, "slip": solution.slip}
    attrs = {
        "method": method,
        "model": f"method {method}: {NAMES[method]}",
        "c": float(solution.c),
        "Q": Q,
        "a": contact.a,
        "p0": contact.p0,
        "E_star": contact.E_star,
        "f": contact.f,
        "P": contact.P,
        "profile": repr(contact.profile),
    }
    return xr.Dataset(
        {name: variable(name, values) for name, values in data.items() if values is not None},
        coords={"x": variable("x", contact.centre + contact.a * solution.t)},
        attrs=attrs,
    )


def comparison_figure(path: str | os.PathLike) -> Figure:
    """Write a PNG of the tractions and slips of the four methods (Hertz, ``Q = 0.6 f P``).

    Parameters
    ----------
    path : str or path-like
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
    """
    scene = FIGURE_SCENE
    contact = Contact(Hertz(scene["R"]), scene["E_star"], scene["f"], scene["P"])
    Q = scene["Q/fP"] * contact.f * contact.P
    fp0, a = contact.f * contact.p0, contact.a
    from matplotlib.figure import Figure  # here: `import fretting` does without matplotlib

    figure = Figure(figsize=(11, 5), layout="constrained")
    traction, slip = figure.subplots(1, 2)
    styles = {1: ("-", ""), 2: ("--", "o"), 3: (":", "s"), 4: ("-.", "^")}
    for method, (line, marker) in styles.items():
        result = partial_slip(contact, Q, method)
        label = f"{result.attrs['model']} (c/a = {result.attrs['c'] / a:.4f})"
        style = {
            "color": f"C{method - 1}",
            "linestyle": line,
            "marker": marker,
            "markevery": (6 * method, 32),
            "label": label,
        }
        traction.plot(result.x / a, result.q / fp0, **style)
        if "slip" in result:
            slip.plot(result.x / a, result.slip * contact.E_star / (fp0 * a), **style)
    traction.set(xlabel="x / a", ylabel="q / (f p0)", title=f"Hertz, Q = {scene['Q/fP']} f P: shear traction")
    slip.set(xlabel="x / a", ylabel="s E* / (f p0 a)", title="slip (method 2 corrects tractions only)")
    figure.legend(*traction.get_legend_handles_labels(), loc="outside lower center", ncols=2, fontsize="small")
    figure.savefig(path, dpi=150)
    return figure
