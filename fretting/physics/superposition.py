"""Jaeger's superposition: a Hertz contact under a varying normal load ``P`` and shear ``Q`` (``sigma = 0``), exactly.

Memory (Jaeger 1998; Barber, Davies & Hills 2011). The plane Hertz pressure grows by flat punches,
``dp/dP = 1 / (pi sqrt(a^2 - x^2))`` at the current half-width ``a`` (``P(a) = pi a^2 E_star / (4 R)``).
Any even traction is a superposition of such punches, ``q(x) = int_{|x|}^{a} lambda(c) P'(c) dc /
(pi sqrt(c^2 - x^2))``: the band ``c`` of the contact remembers ``lambda(c)``, the ratio of the shear
to the normal load it carries. A punch of half-width ``c`` moves the surfaces rigidly inside
``|x| < c``, so the slip at ``x`` depends on ``lambda`` below ``|x|`` alone, and ``|q| <= f p`` wherever
``|lambda| <= f``; ``q = s f p`` on ``|x| > c`` exactly where ``lambda = s f`` there (Abel inversion).
``lambda`` is piecewise constant (`Memory`: bands), so the traction (``int c / sqrt(c^2 - x^2) dc =
sqrt(c^2 - x^2)``), the slip gradient ``ds/dx = (sign x / R) int_0^{|x|} lambda(c) c dc / sqrt(x^2 - c^2)``
(the Hilbert transform of a flat punch) and the slip ``s(x) - s(0)`` are closed forms.

An increment to ``(P', Q')``, the loads straight between, is a sequence of phases (`Superposition.advance`),
each of which the memory follows in closed form:

- stuck (`Superposition._stuck`): a growing contact takes bands of ``lambda = dQ / dP`` while
  ``|dQ / dP| <= f`` (Jaeger's rule); a receding one gives up its outer bands with their shear while
  ``dQ = lambda dP`` of the band at its edge; ``P`` constant and ``dQ = 0``: nothing happens. Otherwise a
  slip zone starts, of the sign ``s`` of ``dQ - lambda dP`` (of ``dQ / dP`` where the contact grows, of
  ``dQ`` at a constant ``P``);
- slipping (`Superposition._slipping`, `Phase`): ``lambda = s f`` on ``(c, a)``, the bands entering
  included, and ``c`` falls from the inner end of the slip zone of sign ``s`` already at the edge (else
  from the edge) so that ``Q - s f P = g(c) = int_0^c lambda dP(c) - s f P(c)`` (`Bands`), linear in the
  increment's fraction, as long as ``s (dQ - s f dP) > 0``: to the increment's end, or until a receding
  edge overtakes ``c`` (stuck again).

Slip and energy. Moving the inner end from ``c`` to ``c - dc`` changes ``lambda`` there by ``s f -
lambda(c)``, and ``d/dc int_c^x sqrt(t^2 - c^2) dt = -c arccosh(x / c)``, so a point ``|x| > c`` in
contact slips by ``ds = (s f - lambda(c)) c arccosh(|x| / c) dc / R``. The energy of a slipping phase
is ``int f p |ds| dx`` with Hertz's pressure ``p`` at the load of each ``c`` (``P`` and ``c`` tied by
``g``):

    W = int (2 f / R) |s f - lambda(c)| c int_c^a p(x) arccosh(x / c) dx dc,

by Gauss-Legendre quadrature in ``c`` between the band edges and in ``x = c + (a - c) sin^2(theta)``
(`J`), and at a point ``x`` the slip and the energy density are the same integrals over ``c`` alone
(`Phase.at`): exact to rounding, as are the stick end ``c`` and the memory
(tests/physics/test_superposition.py: Cattaneo-Mindlin and Mindlin's energy, Jaeger's proportional
loading, the limit of sums over ever finer parts, and method 4 on cells converging to it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fretting.physics.profiles import Hertz

__all__ = ["Memory", "Phase", "Step", "Superposition"]

#: Gauss-Legendre points of each quadrature (`J`, `Bands.energy`, `Phase.at`, `Memory.delta_Q`): their integrands
#: are smooth in the variables used, so that half as many change the energy by rounding only
#: (tests/physics/test_superposition.py).
POINTS = 48

#: Rate of ``Q`` off the ratio of the band at a receding edge [of ``|dQ| + f |dP|``] below which nothing slips,
#: and the fraction of an increment within which its end counts as reached: rounding of the loads.
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


def J(c, a):
    """``int_c^a sqrt(a^2 - x^2) arccosh(x / c) dx`` [m^2] for ``0 < c <= a`` (arrays), by Gauss-Legendre in
    ``x = c + (a - c) sin^2(theta)``, which makes both ends smooth."""
    c, width = np.asarray(c)[..., None], np.maximum(np.asarray(a) - np.asarray(c), 0.0)[..., None]  # a >= c, rounded
    x = c + width * _SIN**2
    root = _COS * np.sqrt(width * (x + c + width))  # sqrt(a^2 - x^2): a - x = width cos^2, a + x = x + c + width
    return np.sum(_WPHI * root * _arccosh(x, c, width * _SIN**2) * 2 * width * _SIN * _COS, axis=-1)


@dataclass(frozen=True)
class Hertz2D:
    """A plane Hertz contact: its `profile` (`fretting.physics.profiles.Hertz`, whose half-width and load it
    uses), modulus `E_star` [Pa] and friction `f`."""

    profile: Hertz
    E_star: float
    f: float

    @property
    def R(self) -> float:
        return self.profile.R

    def half_width(self, P):
        """Half-width [m] of the contact under the load `P` [N/m] (arrays)."""
        return self.profile.half_width(P, self.E_star)[0]

    def load(self, c):
        """``P(c)`` [N/m], the load at which the contact reaches the half-width `c` [m] (arrays)."""
        return self.profile.load(c, self.E_star)

    def pressure(self, x, P):
        """Hertz's ``p = (E_star / 2R) sqrt(a^2 - x^2)`` [Pa] at `x` [m] from the centre under the load `P` [N/m],
        as ``a^2 - x^2 = 4 R (P - P(|x|)) / (pi E_star)``: without cancellation where ``x`` nears the edge."""
        return (
            self.E_star / (2 * self.R) * np.sqrt(np.maximum(4 * self.R * (P - self.load(x)) / (np.pi * self.E_star), 0))
        )


@dataclass(frozen=True)
class Memory:
    """``lambda``, piecewise constant: `ratio` on the bands between consecutive `edges` [m] (the last: the
    contact's edge), of a contact of geometry `hertz`."""

    edges: np.ndarray
    ratio: np.ndarray
    hertz: Hertz2D

    @property
    def a(self) -> float:
        return float(self.edges[-1])

    def flat(self, scale) -> tuple:
        """The memory as one tuple of numbers (`fretting.models.state.State.memory`): the edges over `scale`
        [m], then the ratios."""
        return tuple(float(v) for v in np.concatenate([self.edges / scale, self.ratio]))

    @classmethod
    def from_flat(cls, values, hertz, scale):
        """The memory of `flat` `values`, its edges in units of `scale` [m]."""
        values = np.asarray(values, dtype=float)
        n = values.size // 2
        return cls(values[: n + 1] * scale, values[n + 1 :], hertz)

    def traction(self, x):
        """``q(x)`` [Pa]: ``(E_star / 2R) sum lambda_j [sqrt(c_j+1^2 - x^2) - sqrt(max(c_j, |x|)^2 - x^2)]``."""
        t = np.abs(np.asarray(x, dtype=float))[..., None]
        low, high = self.edges[:-1], self.edges[1:]
        part = np.sqrt(np.maximum(high**2 - t**2, 0)) - np.sqrt(np.maximum(np.maximum(low, t) ** 2 - t**2, 0))
        return self.hertz.E_star / (2 * self.hertz.R) * (part @ self.ratio)

    def slip(self, x):
        """``s(x) - s(0)`` [m], the relative tangential displacement of the surfaces (even in ``x``); outside
        the contact, that of the free surfaces."""
        t = np.abs(np.asarray(x, dtype=float))[..., None]
        low, high = self.edges[:-1], self.edges[1:]
        inner = np.where(t > low, _F(np.maximum(t, low), low), 0.0)
        outer = np.where(t > high, _F(np.maximum(t, high), high), 0.0)
        return (inner - outer) @ self.ratio / self.hertz.R

    def delta_Q(self):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] over the contact: ``(2 / (pi R)) sum_j lambda_j (K(c_j) -
        K(c_j+1))`` with ``K(c) = int_c^a sqrt(t^2 - c^2) arccos(t / a) dt`` (the slip's ``int_c^x`` and the
        punch's ``int_t^a`` swapped), by Gauss-Legendre in ``t = c + (a - c) sin^2(theta)``."""
        c, a = self.edges[:, None], self.a
        width = a - c
        t = c + width * _SIN**2
        arccos = 2 * np.arcsin(_COS * np.sqrt(width / (2 * a)))  # arccos(t / a), a - t = width cos^2
        K = np.sum(_WPHI * _SIN * np.sqrt(width * (t + c)) * arccos * 2 * width * _SIN * _COS, axis=1)
        return float(2 / (np.pi * self.hertz.R) * self.ratio @ (K[:-1] - K[1:]))

    def kinks(self, jump):
        """Band edges inside the contact where ``lambda`` jumps by more than `jump`: the traction kinks [m]."""
        return self.edges[1:-1][np.abs(np.diff(self.ratio)) > jump]


class Bands:
    """The bands ``(edges, ratio)`` of the memory below the inner end ``c0 = edges[-1]`` of a slip zone of
    ``lambda = limit`` (``s f``), and the relation ``g(c) = int_0^c lambda dP(c) - limit P(c) = Q - limit P``
    that places its inner end ``c`` (module docstring)."""

    def __init__(self, edges, ratio, limit, hertz):
        self.edges, self.ratio, self.limit, self.hertz = edges, ratio, limit, hertz
        self.loads = hertz.load(edges)
        self.cumulative = np.concatenate([[0.0], np.cumsum(np.diff(self.loads) * ratio)])

    def band(self, c):
        """Index of the band holding `c` [m] (arrays; its lower edge at or below)."""
        return np.clip(np.searchsorted(self.edges, c, side="right") - 1, 0, self.ratio.size - 1)

    def below(self, P):
        """``int_0^c lambda dP(c)`` [N/m] at the half-width ``c <= c0`` of the load `P` [N/m] (arrays)."""
        k = np.clip(np.searchsorted(self.loads, P, side="right") - 1, 0, self.ratio.size - 1)
        return self.cumulative[k] + self.ratio[k] * (P - self.loads[k])

    def g(self, c):
        load = self.hertz.load(c)
        return self.below(load) - self.limit * load

    def inverse(self, G):
        """The largest ``c`` [m] with ``g(c) = G`` [N/m] (arrays; ``s g`` falls as ``c`` grows, flat over a band at
        the limit). Raises ValueError where none is left (gross slip)."""
        G, s = np.asarray(G, dtype=float), np.sign(self.limit)
        if np.any(s * G > 0):
            raise ValueError("gross sliding: the shear passes f P, no stick zone is left")
        falling = s * self.g(self.edges)
        k = falling.size - np.searchsorted(falling[::-1], s * G, side="left") - 1  # the last edge with s g >= s G
        band = np.minimum(k, self.ratio.size - 1)
        load = (G - self.cumulative[band] + self.ratio[band] * self.loads[band]) / (self.ratio[band] - self.limit)
        c = np.clip(self.hertz.half_width(np.maximum(load, 0.0)), self.edges[band], self.edges[band + 1])
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

    def P(self, c):
        """The load [N/m] at which the inner end is at `c` [m] (arrays)."""
        return self.P0 + (self.bands.g(c) - self.G0) / self.K * self.dP

    def energy(self):
        """``int (2 f / R) |s f - lambda(c)| c (E_star / 2R) J(c, a(c)) dc`` [J/m] (module docstring)."""
        h, total = self.bands.hertz, 0.0
        for low, high, jump in self.bands.pieces(self.c1, self.c0):
            c = low + (high - low) * (_U + 1) / 2
            total += jump * (high - low) / 2 * float(np.sum(_W * c * J(c, h.half_width(self.P(c)))))
        return 2 * h.f / h.R * h.E_star / (2 * h.R) * total

    def at(self, x):
        """``(ds, w)``: the slip [m] and the energy density [J/m^2] of the phase at the points `x` [m] from the
        centre: ``ds = int s (s f - lambda) c arccosh(|x| / c) dc / R`` over the ``c < |x|`` passed while
        ``x`` is in contact, ``w`` the same of ``f p |ds|`` (module docstring)."""
        h, s = self.bands.hertz, np.sign(self.bands.limit)
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
            c = lo + span * _SIN**2  # both ends smooth: arccosh(|x|/c) and p vanish as square roots
            dc = _WPHI * 2 * span * _SIN * _COS
            rate = jump * c * _arccosh(Xl, c, Xl - c) / h.R * dc
            p = h.pressure(Xl, self.P(c))
            ds[live] += s * np.sum(rate, axis=1)
            w[live] += h.f * np.sum(p * rate, axis=1)
        return ds, w


@dataclass(frozen=True)
class Step:
    """What one increment of `Superposition.advance` did: the innermost end of its slip zones [m] (None: it slipped
    nowhere), its energy [J/m] and its slipping phases."""

    stick: float | None
    energy: float
    phases: tuple


class Superposition:
    """A plane Hertz contact of geometry `hertz` under the loads `P`, `Q` [N/m] with the `memory` they left (None:
    formed at `P` without shear), advanced by increments (module docstring)."""

    def __init__(self, hertz, P, Q=0.0, memory=None):
        self.hertz, self.P, self.Q = hertz, float(P), float(Q)
        self.memory = memory or Memory(np.array([0.0, float(hertz.half_width(P))]), np.array([0.0]), hertz)

    def _set(self, edges, ratio):
        """The memory of bands `edges`, `ratio`, bands of no width dropped and neighbours of equal ratio merged
        (their edge puts no kink)."""
        wide = np.diff(edges) > 0
        edges, ratio = np.append(edges[:-1][wide], edges[-1]), ratio[wide]
        keep = np.concatenate([[True], ratio[1:] != ratio[:-1]])
        self.memory = Memory(np.append(edges[:-1][keep], edges[-1]), ratio[keep], self.hertz)

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
                    ends.append(min(phase.c1, self.memory.a))
        self.P, self.Q = float(P), float(Q)
        return Step(min(ends) if ends else None, sum(phase.energy() for phase in phases), tuple(phases))

    def _at(self, tau):
        """``(P, Q)`` [N/m] at the fraction `tau` of the increment (arrays)."""
        P0, Q0, dP, dQ = self._path
        return P0 + tau * dP, Q0 + tau * dQ

    def _fraction(self, c):
        """The fraction of the increment at which ``P`` reaches the load of the half-width `c` [m] (inf: never)."""
        P0, _, dP, _ = self._path
        return (self.hertz.load(c) - P0) / dP if dP else np.inf

    def _stuck(self, tau):
        """Follow the increment from `tau` while nothing slips; returns the fraction reached and the sign of the
        slip that starts there (0: none, the increment done)."""
        _, _, dP, dQ = self._path
        f, edges, ratio = self.hertz.f, self.memory.edges, self.memory.ratio
        a1 = float(self.hertz.half_width(self._at(1.0)[0]))
        if dP > 0:
            r = dQ / dP
            if abs(r) > f:
                return tau, np.sign(r)
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
        f, edges, ratio = self.hertz.f, self.memory.edges, self.memory.ratio
        run = ratio[-1] == s * f  # the slip zone of sign s already at the edge goes on from its inner end
        c0 = float(edges[-2] if run else edges[-1])
        inner = np.count_nonzero(edges < c0)
        bands = Bands(np.append(edges[:inner], c0), ratio[:inner], s * f, self.hertz)
        K = dQ - s * f * dP  # the rate of Q - s f P, which the slip zone's growth carries
        end = min(1.0, self._overtaken(bands, tau)) if dP < 0 else 1.0
        G0 = Q0 - s * f * P0
        c1 = float(bands.inverse(G0 + end * K))
        a1 = float(self.hertz.half_width(self._at(end)[0]))
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
