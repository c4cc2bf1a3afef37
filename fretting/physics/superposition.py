"""Jaeger's superposition: a symmetric contact under a varying normal load ``P`` and shear ``Q`` (``sigma = 0``),
exactly.

Memory (Jaeger 1998; Barber, Davies & Hills 2011). The pressure of a symmetric convex profile grows by flat
punches, ``dp = P'(a) da / (pi sqrt(a^2 - x^2))`` as the half-width grows from ``a`` (``P(a)``: the profile's
`load`, ``P'``: its `load_slope`). Any even traction is a superposition of such punches, ``q(x) =
int_{|x|}^{a} lambda(c) P'(c) dc / (pi sqrt(c^2 - x^2))``: the band ``c`` of the contact remembers ``lambda(c)``,
the ratio of the shear to the normal load it carries. A punch of half-width ``c`` moves the surfaces rigidly
inside ``|x| < c``, so the slip at ``x`` depends on ``lambda`` below ``|x|`` alone, and ``|q| <= f p`` wherever
``|lambda| <= f``; ``q = s f p`` on ``|x| > c`` exactly where ``lambda = s f`` there (Abel inversion).
``lambda`` is piecewise constant (`Memory`: bands), so the traction is a sum of differences of the profile's
pressures (``p_c``: the pressure of the contact of half-width ``c``), and the slip gradient is
``ds/dx = (sign x) int lambda(c) m(c) dc / sqrt(x^2 - c^2)`` over ``c < |x|`` (the Hilbert transform of a flat
punch), with ``m(c) = 2 P'(c) / (pi E_star)`` [m] (``c / R`` on Hertz).

The bands start at ``b``, the half-width at no load (0 on Hertz, the flat's on a rounded flat, whose corners
alone carry the growing load). A slip zone ``lambda = s f`` on ``(c, a)`` leaves ``q = s f (p - p_c)``, the
Cattaneo-Mindlin traction of the profile: its stick end ``c`` cannot pass ``b`` before the shear reaches
``f P`` (Ciavarella, Hills & Monno 1998), where gross slip begins.

An increment to ``(P', Q')``, the loads straight between, is a sequence of phases (`Superposition.advance`),
each of which the memory follows in closed form:

- stuck (`Superposition._stuck`): a growing contact takes bands of ``lambda = dQ / dP`` while
  ``|dQ / dP| <= f`` (Jaeger's rule); a receding one gives up its outer bands with their shear while
  ``dQ = lambda dP`` of the band at its edge; ``P`` constant and ``dQ = 0``: nothing happens. Otherwise a
  slip zone starts, of the sign ``s`` of ``dQ - lambda dP`` (of ``dQ / dP`` where the contact grows, of
  ``dQ`` at a constant ``P``);
- slipping (`Superposition._slipping`, `Phase`): ``lambda = s f`` on ``(c, a)``, the bands entering
  included, and ``c`` falls from the inner end of the slip zone of sign ``s`` already at the edge (else
  from the edge) so that ``Q - s f P = g(c) = int_b^c lambda dP(c) - s f P(c)`` (`Bands`), linear in the
  increment's fraction, as long as ``s (dQ - s f dP) > 0``: to the increment's end, or until a receding
  edge overtakes ``c`` (stuck again).

Slip and energy. Moving the inner end from ``c`` to ``c - dc`` changes ``lambda`` there by ``s f -
lambda(c)``, so a point ``|x| > c`` in contact slips by ``ds = (s f - lambda(c)) m(c) arccosh(|x| / c) dc``.
The energy of a slipping phase is ``int f p |ds| dx`` with the pressure ``p`` at the load of each ``c``
(``P`` and ``c`` tied by ``g``), and as ``int_c^t arccosh(x / c) dx / sqrt(t^2 - x^2) = (pi / 2) ln(t / c)``,
``int_c^a p arccosh(x / c) dx = (1/2) int_c^a P'(t) ln(t / c) dt`` (`Geometry.punch_energy`):

    W = int 2 f |s f - lambda(c)| m(c) (1/2) int_c^a(c) P'(t) ln(t / c) dt dc,

by Gauss-Legendre quadrature in ``c`` between the band edges, at a point ``x`` the slip and the energy density
are the same integrals over ``c`` alone (`Phase.at`), and by the same swap of integrals ``delta_Q`` is
``sum_j lambda_j int m(c) ln(a / c) dc`` over the bands (`Memory.delta_Q`). On Hertz, the slip of the
bands and ``delta_Q`` are closed forms (`HertzGeometry`); otherwise, and for the punch energy, Gauss-Legendre
quadratures in variables that make their square roots smooth (`Geometry`). Exact to rounding on Hertz, to the
quadratures' convergence elsewhere (tests/physics/test_superposition.py: Cattaneo-Mindlin and Mindlin's energy on both
profiles, Jaeger's proportional loading, the limit of sums over ever finer parts, the quadratures against the
closed forms, and method 4 on cells converging to it).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from fretting.physics.profiles import Hertz, Profile

__all__ = ["Geometry", "HertzGeometry", "Memory", "Phase", "Step", "Superposition", "geometry"]

#: Gauss-Legendre points of each quadrature (`Geometry`'s, `Phase.energy`, `Phase.at`): their integrands
#: are smooth in the variables used, so that half as many change the energy by rounding only
#: (tests/physics/test_superposition.py).
POINTS = 48

#: Rate of ``Q`` off the ratio of the band at a receding edge [of ``|dQ| + f |dP|``] below which nothing slips,
#: the fraction of an increment within which its end counts as reached, and the share of ``f P`` within which
#: the shear counts as at it (`Bands.inverse`): rounding of the loads.
ROUNDING = 1e-12


def rule(n):
    """``(u, w, sin, cos, w_phi)``: the `n` Gauss-Legendre points ``u`` and weights ``w`` on [-1, 1], and
    ``sin``, ``cos`` of ``phi = pi (u + 1) / 4`` on [0, pi/2] with the weights there, ``w_phi``."""
    u, w = np.polynomial.legendre.leggauss(n)
    phi = (u + 1) * np.pi / 4
    return u, w, np.sin(phi), np.cos(phi), w * np.pi / 4


_U, _W, _SIN, _COS, _WPHI = rule(POINTS)


def _F(x, c):
    """``int_c^x sqrt(t^2 - c^2) dt`` [m^2] for ``x >= c >= 0``."""
    root = np.sqrt(np.maximum(x * x - c * c, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        log = np.where(c > 0, np.log(np.where(c > 0, (x + root) / np.where(c > 0, c, 1.0), 1.0)), 0.0)
    return (x * root - c * c * log) / 2


def _arccosh(x, c, width):
    """``arccosh(x / c)`` for ``x = c + width`` (``width >= 0``), without the cancellation of ``x / c - 1``."""
    return np.log1p((width + np.sqrt(width * (x + c))) / c)


def _stretched(low, width):
    """``(t, dt)``: the Gauss-Legendre nodes of ``[low, low + width]`` in ``t = low + width sin^2(theta)``, which
    makes a square root at either end smooth, and their weights in ``t`` (arrays, the nodes on a last axis)."""
    return low + width * _SIN**2, _WPHI * 2 * width * _SIN * _COS


#: Newton iterations at most of `Geometry.half_width`: from the right of a convex load they fall monotonically to
#: the root (from its left, the first step crosses it), quadratically but near the flat's edge, where
#: ``P ~ (a - b)^(3/2)`` takes a third off each; and the loads whose half-widths, interpolated, start the
#: iteration for more loads than these.
NEWTON = 200
STARTS = 64


@dataclass(frozen=True)
class Geometry:
    """A symmetric contact whose width grows with the load: its `profile` (``load``, ``load_slope``, ``pressure``,
    the latter evaluated elementwise at arrays of half-widths and loads), modulus `E_star` [Pa] and friction `f`;
    the integrals of the module by Gauss-Legendre quadrature."""

    profile: Profile
    E_star: float
    f: float

    def __post_init__(self):
        if not self.profile.grows_with_load():
            raise ValueError(f"{self.profile!r}: Jaeger's superposition needs a symmetric contact that grows with P")

    @functools.cached_property
    def b(self) -> float:
        """The half-width [m] of the contact at no load, where the bands begin."""
        return float(self.profile.half_width(0.0, self.E_star)[0])

    def load(self, c):
        """``P(c)`` [N/m], the load at which the contact reaches the half-width `c` [m] (arrays)."""
        return self.profile.load(c, self.E_star)

    def slope(self, c):
        """``m(c) = 2 P'(c) / (pi E_star)`` [m]: the slip at ``|x| > c`` per ``arccosh(|x| / c)`` of a band ``dc``
        of ``lambda = 1``, per ``dc`` (arrays)."""
        return 2 * self.profile.load_slope(c, self.E_star) / (np.pi * self.E_star)

    def half_width(self, P):
        """Half-width [m] of the contact under the load `P` [N/m] (arrays): Newton's iteration on `load`, each load
        until its step is rounding, from the half-width of the largest ``P`` (the profile's) or, for more than
        `STARTS` loads, from the interpolation of `STARTS` of them across their range; ``b`` where ``P <= 0``."""
        P = np.asarray(P, dtype=float)
        a, live = np.full(P.shape, self.b), P > 0
        if not live.any():
            return a
        loads = P[live]
        if loads.size > STARTS:
            table = np.linspace(loads.min(), loads.max(), STARTS)
            root = np.interp(loads, table, self.half_width(table))
        else:
            root = np.full(loads.size, float(self.profile.half_width(loads.max(), self.E_star)[0]))
        moving = np.arange(loads.size)
        for _ in range(NEWTON):
            step = (self.load(root[moving]) - loads[moving]) / self.profile.load_slope(root[moving], self.E_star)
            root[moving] = np.maximum(root[moving] - step, self.b)
            moving = moving[np.abs(step) > 4 * np.finfo(float).eps * root[moving]]
            if moving.size == 0:
                break
        a[live] = root
        return a

    def within(self, x, c):
        """``p_c(x)`` [Pa]: the pressure at `x` [m] from the centre of the contact of half-width `c` [m] (arrays,
        broadcast; zero outside it and where it carries no load)."""
        X, c = np.broadcast_arrays(np.abs(np.asarray(x, dtype=float)), np.asarray(c, dtype=float))
        load = self.load(c)
        inside = (X < c) & (load > 0)
        p = np.zeros(X.shape)
        p[inside] = self.profile.pressure(X[inside] / c[inside], c[inside], 0.0, load[inside], self.E_star)
        return p

    def pressure(self, x, P):
        """The pressure [Pa] at `x` [m] from the centre under the load `P` [N/m] (arrays, broadcast)."""
        return self.within(x, self.half_width(P))

    def slip(self, c, x):
        """``int_c^x m(t) arccosh(x / t) dt`` [m] (zero for ``x <= c``; arrays, broadcast): the slip at ``x`` of the
        bands from `c` up to ``x`` of ``lambda = 1``, by Gauss-Legendre in ``t = c + (x - c) sin^2(theta)``, which
        makes the root of ``arccosh`` at ``t = x`` and that of ``P'`` at ``t = b`` smooth."""
        c, x = np.broadcast_arrays(np.maximum(c, self.b), np.abs(np.asarray(x, dtype=float)))
        S, live = np.zeros(x.shape), x > c
        c, x = c[live][:, None], x[live][:, None]
        t, dt = _stretched(c, x - c)
        S[live] = np.sum(self.slope(t) * _arccosh(x, t, (x - c) * _COS**2) * dt, axis=-1)
        return S

    def punch_energy(self, c, a):
        """``int_c^a p_a(x) arccosh(x / c) dx = (1/2) int_c^a P'(t) ln(t / c) dt`` [N] for ``b <= c <= a`` (arrays;
        module docstring), by Gauss-Legendre in ``t = c + (a - c) sin^2(theta)``."""
        c = np.asarray(c, dtype=float)[..., None]
        width = np.maximum(np.asarray(a, dtype=float)[..., None] - c, 0.0)  # a >= c, but for rounding
        t, dt = _stretched(c, width)
        return np.sum(self.profile.load_slope(t, self.E_star) * np.log1p(width * _SIN**2 / c) * dt, axis=-1) / 2

    def compliance(self, low, high, a):
        """``int_low^high m(c) ln(a / c) dc`` [m^2] (arrays): the ``delta_Q`` of a band of ``lambda = 1`` of the
        contact of half-width `a` [m], by Gauss-Legendre in ``c = low + (high - low) sin^2(theta)``."""
        low = np.asarray(low, dtype=float)[..., None]
        c, dc = _stretched(low, np.asarray(high, dtype=float)[..., None] - low)
        return np.sum(self.slope(c) * np.log(a / c) * dc, axis=-1)


class HertzGeometry(Geometry):
    """A plane Hertz contact (`fretting.physics.profiles.Hertz`), whose slip of the bands and ``delta_Q`` are closed
    forms (``m(c) = c / R``, ``p_c(x) = (E_star / 2R) sqrt(c^2 - x^2)``): the slip is evaluated at every node of
    every step, and the quadrature of ``delta_Q`` would meet the logarithm at ``c = b = 0``. The punch energy is
    `Geometry`'s, whose integrand ``t ln(t / c)`` is smooth."""

    @property
    def R(self) -> float:
        return self.profile.R

    def half_width(self, P):
        return self.profile.half_width(np.maximum(P, 0.0), self.E_star)[0]

    def within(self, x, c):
        x = np.asarray(x, dtype=float)
        return self.E_star / (2 * self.R) * np.sqrt(np.maximum(np.square(c) - x * x, 0.0))

    def pressure(self, x, P):
        """Hertz's ``p = (E_star / 2R) sqrt(a^2 - x^2)`` [Pa], as ``a^2 - x^2 = 4 R (P - P(|x|)) / (pi E_star)``:
        without cancellation where ``x`` nears the edge."""
        return (
            self.E_star / (2 * self.R) * np.sqrt(np.maximum(4 * self.R * (P - self.load(x)) / (np.pi * self.E_star), 0))
        )

    def slip(self, c, x):
        """``int_c^x sqrt(t^2 - c^2) dt / R`` (`_F`), zero for ``x <= c``."""
        c, x = np.broadcast_arrays(np.asarray(c, dtype=float), np.abs(np.asarray(x, dtype=float)))
        return np.where(x > c, _F(np.maximum(x, c), c), 0.0) / self.R

    def compliance(self, low, high, a):
        """``(L(high) - L(low)) / R`` with ``L(c) = c^2 ln(a / c) / 2 + c^2 / 4``."""

        def L(c):
            c = np.asarray(c, dtype=float)
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.where(c > 0, c * c * np.log(a / np.where(c > 0, c, 1.0)) / 2 + c * c / 4, 0.0)

        return (L(high) - L(low)) / self.R


def geometry(profile, E_star, f) -> Geometry:
    """The `Geometry` of a contact of `profile`, `E_star` [Pa] and `f`: its closed forms on Hertz."""
    return (HertzGeometry if isinstance(profile, Hertz) else Geometry)(profile, E_star, f)


@dataclass(frozen=True)
class Memory:
    """``lambda``, piecewise constant: `ratio` on the bands between consecutive `edges` [m] (the first: ``b``; the
    last: the contact's edge), of a contact of `geometry`."""

    edges: np.ndarray
    ratio: np.ndarray
    geometry: Geometry

    @property
    def a(self) -> float:
        return float(self.edges[-1])

    def flat(self, scale) -> tuple:
        """The memory as one tuple of numbers (`fretting.models.state.State.memory`): the edges over `scale`
        [m], then the ratios."""
        return tuple(float(v) for v in np.concatenate([self.edges / scale, self.ratio]))

    @classmethod
    def from_flat(cls, values, geometry, scale):
        """The memory of `flat` `values`, its edges in units of `scale` [m]."""
        values = np.asarray(values, dtype=float)
        n = values.size // 2
        return cls(values[: n + 1] * scale, values[n + 1 :], geometry)

    def traction(self, x):
        """``q(x) = sum lambda_j (p_c_j+1(x) - p_c_j(x))`` [Pa] at `x` [m] (`Geometry.within`)."""
        p = self.geometry.within(np.asarray(x, dtype=float)[..., None], self.edges)
        return np.diff(p, axis=-1) @ self.ratio

    def slip(self, x):
        """``s(x) - s(0)`` [m], the relative tangential displacement of the surfaces at `x` [m] (even in ``x``;
        outside the contact, that of the free surfaces): ``sum lambda_j (S(c_j) - S(min(c_j+1, |x|)))`` with
        ``S(c)`` the `Geometry.slip` from ``c`` up to ``|x|``."""
        t = np.abs(np.asarray(x, dtype=float))[..., None]
        S = self.geometry.slip(np.minimum(self.edges, t), t)
        return -np.diff(S, axis=-1) @ self.ratio

    def delta_Q(self):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] over the contact: ``sum_j lambda_j int m(c) ln(a / c) dc`` over
        the bands (module docstring; `Geometry.compliance`)."""
        return float(self.ratio @ self.geometry.compliance(self.edges[:-1], self.edges[1:], self.a))

    def kinks(self, jump):
        """Band edges inside the contact where ``lambda`` jumps by more than `jump`: the traction kinks [m]."""
        return self.edges[1:-1][np.abs(np.diff(self.ratio)) > jump]


class Bands:
    """The bands ``(edges, ratio)`` of the memory below the inner end ``c0 = edges[-1]`` of a slip zone of
    ``lambda = limit`` (``s f``), and the relation ``g(c) = int_b^c lambda dP(c) - limit P(c) = Q - limit P``
    that places its inner end ``c`` (module docstring); `allowance` [N/m]: the rounding of ``Q - limit P`` within
    which a shear past ``f P`` counts as at it, the point of sliding."""

    def __init__(self, edges, ratio, limit, geometry, allowance=0.0):
        self.edges, self.ratio, self.limit, self.geometry, self.allowance = edges, ratio, limit, geometry, allowance
        self.loads = geometry.load(edges)
        self.cumulative = np.concatenate([[0.0], np.cumsum(np.diff(self.loads) * ratio)])

    def band(self, c):
        """Index of the band holding `c` [m] (arrays; its lower edge at or below)."""
        return np.clip(np.searchsorted(self.edges, c, side="right") - 1, 0, self.ratio.size - 1)

    def below(self, P):
        """``int_b^c lambda dP(c)`` [N/m] at the half-width ``c <= c0`` of the load `P` [N/m] (arrays)."""
        k = np.clip(np.searchsorted(self.loads, P, side="right") - 1, 0, self.ratio.size - 1)
        return self.cumulative[k] + self.ratio[k] * (P - self.loads[k])

    def g(self, c):
        load = self.geometry.load(c)
        return self.below(load) - self.limit * load

    def held(self, G):
        """``G = Q - limit P`` [N/m] (arrays), past the point of sliding within the `allowance` held at it. Raises
        ValueError where it is past it by more (gross slip)."""
        G, s = np.asarray(G, dtype=float), np.sign(self.limit)
        if np.any(s * G > self.allowance):
            raise ValueError("gross sliding: the shear passes f P, no stick zone is left")
        return s * np.minimum(s * G, 0.0)

    def inverse(self, G):
        """The largest ``c`` [m] with ``g(c) = G`` [N/m] (arrays; ``s g`` falls as ``c`` grows, flat over a band at
        the limit; ``b`` at ``G = 0``, the point of sliding, to the `allowance`). Raises ValueError where none is
        left (gross slip)."""
        G, s = self.held(G), np.sign(self.limit)
        falling = s * self.g(self.edges)
        k = falling.size - np.searchsorted(falling[::-1], s * G, side="left") - 1  # the last edge with s g >= s G
        band = np.minimum(k, self.ratio.size - 1)
        numerator = G - self.cumulative[band] + self.ratio[band] * self.loads[band]
        slope = self.ratio[band] - self.limit  # zero over a band at the limit: s g is flat there
        load = np.divide(numerator, slope, out=np.zeros(np.shape(numerator)), where=slope != 0)
        c = np.clip(self.geometry.half_width(np.maximum(load, 0.0)), self.edges[band], self.edges[band + 1])
        # A band at the limit is found only where the rounding of g puts its upper edge a hair below G: the
        # largest c is that edge, past which s g falls below G.
        c = np.where(slope == 0, self.edges[band + 1], c)
        return np.where(k == self.ratio.size, self.edges[-1], c)

    def pieces(self, c1, c0):
        """``(low, high, |limit - lambda|)`` of the pieces of ``[c1, c0]`` [m] between band edges that slip."""
        cuts = np.concatenate([[c1], self.edges[(self.edges > c1) & (self.edges < c0)], [c0]])
        for low, high in zip(cuts[:-1], cuts[1:], strict=True):
            jump = abs(self.limit - self.ratio[self.band(low)])
            if jump > 0 and high > low:
                yield float(low), float(high), float(jump)


@dataclass(frozen=True)
class Phase:
    """A slipping phase of an increment: the `bands` below its slip zone, whose inner end falls from `c0` to `c1`
    [m], along the loads ``P = P0 + tau dP``, ``Q - s f P = G0 + tau K`` [N/m] of the increment's fraction ``tau``."""

    bands: Bands
    c0: float
    c1: float
    P0: float
    dP: float
    G0: float
    K: float

    @property
    def end(self) -> float | None:
        """The innermost ``c`` [m] at which the phase slipped: the lower end of its innermost piece below the limit
        (None: its inner end passed bands at the limit alone, or moved by rounding only; where it comes to rest on
        the lower edge of such bands, they did not slip)."""
        return next((low for low, _, _ in self.bands.pieces(self.c1, self.c0)), None)

    def P(self, c):
        """The load [N/m] at which the inner end is at `c` [m] (arrays)."""
        return self.P0 + (self.bands.g(c) - self.G0) / self.K * self.dP

    def energy(self):
        """``int 2 f |s f - lambda(c)| m(c) (1/2) int_c^a(c) P'(t) ln(t / c) dt dc`` [J/m] (module docstring)."""
        h, total = self.bands.geometry, 0.0
        for low, high, jump in self.bands.pieces(self.c1, self.c0):
            c = low + (high - low) * (_U + 1) / 2
            total += (
                jump * (high - low) / 2 * float(np.sum(_W * h.slope(c) * h.punch_energy(c, h.half_width(self.P(c)))))
            )
        return 2 * h.f * total

    def at(self, x):
        """``(ds, w)``: the slip [m] and the energy density [J/m^2] of the phase at the points `x` [m] from the
        centre: ``ds = int s (s f - lambda) c arccosh(|x| / c) dc / R`` over the ``c < |x|`` passed while
        ``x`` is in contact, ``w`` the same of ``f p |ds|`` (module docstring)."""
        h, s = self.bands.geometry, np.sign(self.bands.limit)
        X = np.abs(np.asarray(x, dtype=float))
        low, high = np.full(X.size, self.c1), np.minimum(X, self.c0)
        if self.dP:  # x in contact while P(c) >= P(|x|): P moves with c one way or the other
            tau = (h.load(X) - self.P0) / self.dP  # where x enters (dP > 0) or leaves (dP < 0)
            c = np.where(tau <= 0, np.inf, -np.inf)  # in contact from the start (dP > 0), else never in it
            moves = (tau > 0) & (tau < 1)
            c[moves] = self.bands.inverse(self.G0 + tau[moves] * self.K)
            if self.dP > 0:
                high = np.minimum(high, c)
            else:
                low = np.maximum(low, c)
        ds, w = np.zeros(X.size), np.zeros(X.size)
        for start, end, jump in self.bands.pieces(self.c1, self.c0):
            lo, hi = np.maximum(low, start), np.minimum(high, end)
            live = np.flatnonzero(hi > lo)
            if live.size == 0:
                continue
            Xl, lo, span = X[live, None], lo[live, None], (hi - lo)[live, None]
            c, dc = _stretched(lo, span)  # both ends smooth: arccosh(|x|/c) and p vanish as square roots
            rate = jump * h.slope(c) * _arccosh(Xl, c, Xl - c) * dc
            p = h.pressure(Xl, self.P(c))
            ds[live] += s * np.sum(rate, axis=1)
            w[live] += h.f * np.sum(p * rate, axis=1)
        return ds, w


@dataclass(frozen=True)
class Step:
    """What one increment of `Superposition.advance` did: the innermost point at which it slipped [m] (`Phase.end`;
    None: it slipped nowhere), its energy [J/m] and its slipping phases."""

    stick: float | None
    energy: float
    phases: tuple


class Superposition:
    """A contact of `geometry` under the loads `P`, `Q` [N/m] with the `memory` they left (None: formed at `P`
    without shear), advanced by increments (module docstring)."""

    def __init__(self, geometry, P, Q=0.0, memory=None):
        self.geometry, self.P, self.Q = geometry, float(P), float(Q)
        edges = np.array([geometry.b, float(geometry.half_width(P))])
        self.memory = memory or Memory(edges, np.array([0.0]), geometry)

    def _set(self, edges, ratio):
        """The memory of bands `edges`, `ratio`, bands of no width dropped and neighbours of equal ratio merged
        (their edge puts no kink)."""
        wide = np.diff(edges) > 0
        edges, ratio = np.append(edges[:-1][wide], edges[-1]), ratio[wide]
        keep = np.concatenate([[True], ratio[1:] != ratio[:-1]])
        self.memory = Memory(np.append(edges[:-1][keep], edges[-1]), ratio[keep], self.geometry)

    def advance(self, P, Q):
        """The increment to `P`, `Q` [N/m] along the straight path from the present loads (module docstring): a
        sequence of phases, each stuck (`_stuck`) or slipping one way (`_slipping`). Raises ValueError where
        no stick zone is left (gross slip)."""
        self._path = (self.P, self.Q, P - self.P, Q - self.Q)
        tau, phases, ends = 0.0, [], []
        while tau < 1:
            tau, s = self._stuck(tau)
            if s:
                start = tau
                tau, phase = self._slipping(tau, s)
                if tau <= start:
                    raise RuntimeError(
                        f"no progress from the fraction {start!r} of the increment to P = {P!r}, Q = {Q!r}"
                    )
                if phase.c1 < phase.c0:
                    phases.append(phase)
                    end = phase.end
                    ends += [] if end is None else [min(end, self.memory.a)]
        self.P, self.Q = float(P), float(Q)
        return Step(min(ends) if ends else None, sum(phase.energy() for phase in phases), tuple(phases))

    def _at(self, tau):
        """``(P, Q)`` [N/m] at the fraction `tau` of the increment (arrays)."""
        P0, Q0, dP, dQ = self._path
        return P0 + tau * dP, Q0 + tau * dQ

    def _fraction(self, c):
        """The fraction of the increment at which ``P`` reaches the load of the half-width `c` [m] (inf: never)."""
        P0, _, dP, _ = self._path
        return (self.geometry.load(c) - P0) / dP if dP else np.inf

    def _stuck(self, tau):
        """Follow the increment from `tau` while nothing slips; returns the fraction reached and the sign of the
        slip that starts there (0: none, the increment done)."""
        _, _, dP, dQ = self._path
        f, edges, ratio = self.geometry.f, self.memory.edges, self.memory.ratio
        a1 = float(self.geometry.half_width(self._at(1.0)[0]))
        if dP > 0:
            r = dQ / dP
            if abs(r) > f * (1 + ROUNDING):
                return tau, np.sign(r)
            if abs(r) >= f * (1 - ROUNDING):  # at the limit to rounding: the band joins a slip zone at the edge
                r = np.sign(r) * f
            self._set(np.append(edges, a1), np.append(ratio, r))
            return 1.0, 0
        slope = dQ - ratio[-1] * dP
        if abs(slope) > ROUNDING * (abs(dQ) + f * abs(dP)):
            return tau, np.sign(slope)
        if dP == 0:
            return 1.0, 0
        below = self._fraction(edges[-2])  # the edge reaches the band's lower end
        if below >= 1 - ROUNDING:
            self._set(np.append(edges[:-1], a1), ratio)
            return 1.0, 0
        self._set(edges[:-1], ratio[:-1])
        return below, 0

    def _slipping(self, tau, s):
        """Follow the increment from `tau` while a slip zone of sign `s` grows inwards from the edge; returns the
        fraction reached (1, or earlier where the contact recedes past its inner end) and the `Phase`."""
        P0, Q0, dP, dQ = self._path
        f, edges, ratio = self.geometry.f, self.memory.edges, self.memory.ratio
        run = ratio[-1] == s * f  # the slip zone of sign s already at the edge goes on from its inner end
        c0 = float(edges[-2] if run else edges[-1])
        inner = np.count_nonzero(edges < c0)
        allowance = ROUNDING * f * max(P0, P0 + dP)
        bands = Bands(np.append(edges[:inner], c0), ratio[:inner], s * f, self.geometry, allowance)
        K = dQ - s * f * dP  # the rate of Q - s f P, which the slip zone's growth carries
        G0 = Q0 - s * f * P0
        if inner == 0:  # every band at the limit: on the point of sliding, held to the end within the allowance
            bands.held(G0 + K)
            self._set(np.array([c0, float(self.geometry.half_width(P0 + dP))]), np.array([s * f]))
            return 1.0, Phase(bands, c0, c0, P0, dP, G0, K)
        end = min(1.0, self._overtaken(bands, tau)) if dP < 0 else 1.0
        c1 = float(bands.inverse(G0 + end * K))
        a1 = float(self.geometry.half_width(self._at(end)[0]))
        if end < 1:  # the contact receded past the slip zone: the bands below its edge carry the shear
            keep = np.count_nonzero(bands.edges < a1)
            self._set(np.append(bands.edges[:keep], a1), bands.ratio[:keep])
        else:
            keep = np.count_nonzero(bands.edges < c1)
            self._set(np.concatenate([bands.edges[:keep], [c1, a1]]), np.append(bands.ratio[:keep], s * f))
        return end, Phase(bands, c0, c1, P0, dP, G0, K)

    def _overtaken(self, bands, tau):
        """The fraction of a receding increment, from `tau`, at which its edge reaches the inner end of the slip
        zone over `bands` (inf: not within it): where ``Q = int_0^a lambda dP(c)`` again, linear in the
        fraction while the edge crosses one band."""
        crossings = np.array([self._fraction(e) for e in bands.edges[::-1]])
        later = crossings[(crossings > tau) & (crossings < 1)]
        times = np.unique(np.concatenate([[max(tau, crossings[0])], later, [1.0]]))
        P, Q = self._at(times)
        phi = np.sign(bands.limit) * (Q - bands.below(P))
        over = np.flatnonzero(phi[1:] <= 0)
        if over.size == 0:
            return np.inf
        i = int(over[0])
        return float(times[i] + (times[i + 1] - times[i]) * phi[i] / (phi[i] - phi[i + 1]))
