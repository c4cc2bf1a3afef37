"""Jaeger's superposition, exact, for a Hertz contact under varying P and Q with ``sigma = 0``.

The reference of benchmarks/varying_accuracy.py and tests/models/test_varying_reference.py. Not
part of the installed package.

Memory (Jaeger 1998; Barber, Davies & Hills 2011). The 2D Hertz pressure grows by flat punches,
``dp/dP = 1 / (pi sqrt(a^2 - x^2))`` at the current half-width ``a`` (``P(a) = pi a^2 E_star / (4 R)``).
Any even traction is a superposition of such punches, ``q(x) = int_{|x|}^{a} lambda(c) P'(c) dc /
(pi sqrt(c^2 - x^2))``: the band ``c`` of the contact remembers ``lambda(c)``, the ratio of the shear
to the normal load it carries. A punch of half-width ``c`` moves the surfaces rigidly inside
``|x| < c``, so the slip at ``x`` depends on ``lambda`` below ``|x|`` alone, and ``|q| <= f p`` wherever
``|lambda| <= f``; ``q = s f p`` on ``|x| > c`` exactly where ``lambda = s f`` there (Abel inversion).
Hence the rules of an increment to ``(P', Q')`` (`Jaeger.advance`):

- the contact grows (``P' > P``): the bands entering carry ``r = dQ / dP``; where ``|r| > f`` a slip
  zone ``(c, a')`` takes ``lambda = sign(r) f``, with ``c`` from ``Q' = int_0^c lambda P' + s f (P' - P(c))``;
- it recedes (``P' < P``): the bands leaving take their shear with them; any ``Q'`` left over is
  carried by a slip zone ``(c, a')`` at ``s f``, ``s`` its sign;
- ``P`` constant: a slip zone from the edge carries ``dQ`` (Cattaneo-Mindlin, with memory).

``lambda`` is piecewise constant, so the traction (``int c / sqrt(c^2 - x^2) dc = sqrt(c^2 - x^2)``),
the slip gradient ``ds/dx = (sign x / R) int_0^{|x|} lambda(c) c dc / sqrt(x^2 - c^2)`` (the Hilbert
transform of a flat punch: ``(2 / (pi E_star)) sign x / sqrt(x^2 - c^2)`` per unit load outside it)
and the slip ``s(x) - s(0)`` are closed forms. A growing step is exact in one part; a receding one
removes bands of different ratios on the way, and is taken in `parts` parts, as are the energies of
both (benchmarks/varying_accuracy.py extrapolates the energy to infinitely many parts, `extrapolated`, and
prints how far that moves with half as many). The energy of a
part is ``2 int f p |ds| dx`` over its slip zone, ``p`` the mean of its ends (trapezoidal in ``P``, as
the package's).
"""

from dataclasses import dataclass

import numpy as np

#: Gauss-Legendre points in ``theta`` over a slip zone ``x = c + (a - c) sin^2(theta)`` (smooth integrand).
ENERGY_POINTS = 48


def _F(x, c):
    """``int_c^x sqrt(t^2 - c^2) dt`` for ``x >= c >= 0``."""
    root = np.sqrt(np.maximum(x * x - c * c, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        log = np.where(c > 0, np.log(np.where(c > 0, (x + root) / np.where(c > 0, c, 1.0), 1.0)), 0.0)
    return (x * root - c * c * log) / 2


@dataclass
class Step:
    """What one increment of `Jaeger.advance` did: the inner end of its slip zones [m] (None: it slipped nowhere)
    and its energy [J/m]."""

    stick: float | None
    energy: float


@dataclass(frozen=True)
class Memory:
    """``lambda``, piecewise constant: `ratio` on the bands between consecutive `edges` [m] (the last: the edge)."""

    edges: np.ndarray
    ratio: np.ndarray
    R: float
    E_star: float

    @property
    def a(self):
        return float(self.edges[-1])

    def pressure(self, x):
        """Hertz's ``p = (E_star / 2R) sqrt(a^2 - x^2)`` [Pa]."""
        return self.E_star / (2 * self.R) * np.sqrt(np.maximum(self.a**2 - np.asarray(x) ** 2, 0.0))

    def traction(self, x):
        """``q(x)`` [Pa]: ``(E_star / 2R) sum lambda_j [sqrt(c_j+1^2 - x^2) - sqrt(max(c_j, |x|)^2 - x^2)]``."""
        t = np.abs(np.asarray(x, dtype=float))[..., None]
        low, high = self.edges[:-1], self.edges[1:]
        part = np.sqrt(np.maximum(high**2 - t**2, 0)) - np.sqrt(np.maximum(np.maximum(low, t) ** 2 - t**2, 0))
        return self.E_star / (2 * self.R) * (part @ self.ratio)

    def slip(self, x):
        """``s(x) - s(0)`` [m], the relative tangential displacement of the surfaces (even in ``x``)."""
        x = np.asarray(x, dtype=float)
        t = np.abs(x)[..., None]
        low, high = self.edges[:-1], self.edges[1:]
        inner = np.where(t > low, _F(np.maximum(t, low), low), 0.0)
        outer = np.where(t > high, _F(np.maximum(t, high), high), 0.0)
        return (inner - outer) @ self.ratio / self.R

    def kinks(self, jump):
        """Band boundaries inside the contact where ``lambda`` jumps by more than `jump`: the traction kinks [m]."""
        return self.edges[1:-1][np.abs(np.diff(self.ratio)) > jump]


class Jaeger:
    """A 2D Hertz contact of radius `R` [m], modulus `E_star` [Pa] and friction `f`, formed at `P` [N/m]
    without shear, and its `memory` (module docstring)."""

    def __init__(self, R, E_star, f, P):
        self.R, self.E_star, self.f = R, E_star, f
        self.P, self.Q = P, 0.0
        self.memory = Memory(np.array([0.0, self.half_width(P)]), np.array([0.0]), R, E_star)

    def half_width(self, P):
        return float(np.sqrt(4 * P * self.R / (np.pi * self.E_star)))

    def load(self, c):
        """``P(c) = pi c^2 E_star / (4 R)`` [N/m], the load at which the contact reaches `c`."""
        return np.pi * np.asarray(c) ** 2 * self.E_star / (4 * self.R)

    def _set(self, edges, ratio):
        """The memory of bands `edges`, `ratio`, neighbours of equal ratio merged (their edge puts no kink)."""
        keep = np.concatenate([[True], ratio[1:] != ratio[:-1]])
        self.memory = Memory(np.append(edges[:-1][keep], edges[-1]), ratio[keep], self.R, self.E_star)

    def _slip_zone(self, Q, s):
        """Set ``lambda = s f`` on ``(c, a)``, ``c`` such that the contact carries `Q` [N/m]; returns ``c`` [m]."""
        edges, ratio, f = self.memory.edges, self.memory.ratio, self.f
        loads = self.load(edges)
        below = np.concatenate([[0.0], np.cumsum(np.diff(loads) * ratio)])
        total = below + s * f * (loads[-1] - loads)  # Q carried with the slip zone from each c_j: monotonic
        if s * (Q - total[0]) > 0:
            raise ValueError(f"gross sliding: |Q| > f P at P = {self.P!r}")
        j = int(np.flatnonzero(s * (total - Q) >= 0)[-1])  # edges[j] <= c: the band where total crosses Q
        j = min(j, ratio.size - 1)
        Pc = (Q - below[j] - s * f * loads[-1] + ratio[j] * loads[j]) / (ratio[j] - s * f)
        c = float(np.clip(np.sqrt(max(Pc, 0.0) * 4 * self.R / (np.pi * self.E_star)), edges[j], edges[j + 1]))
        keep = edges < c
        self._set(np.concatenate([edges[keep], [c, edges[-1]]]), np.concatenate([ratio[: keep.sum()], [s * f]]))
        return c

    def _part(self, P, Q):
        """One part to the loads `P`, `Q` [N/m]; returns the start of its slip zone (None: it slipped nowhere)."""
        dP, dQ, a = P - self.P, Q - self.Q, self.half_width(P)
        edges, ratio = self.memory.edges, self.memory.ratio
        if dP > 0:  # the bands entering carry dQ / dP, or the limit of its sign past it (a slip zone follows)
            self._set(np.append(edges, a), np.append(ratio, np.clip(dQ / dP, -self.f, self.f)))
        else:
            keep = edges < a
            self._set(np.concatenate([edges[keep], [a]]), ratio[: keep.sum()])
        self.P, self.Q = P, Q
        left = Q - float(np.diff(self.load(self.memory.edges)) @ self.memory.ratio)
        if abs(left) <= 1e-14 * self.f * P:
            return None
        return self._slip_zone(Q, float(np.sign(left)))

    def advance(self, P, Q, parts=1):
        """The increment to `P`, `Q` [N/m] in `parts` equal parts (one where ``P`` is constant).

        A growing increment is exact in one part; its energy, whose slip and pressure change together, is not."""
        P0, Q0 = self.P, self.Q
        parts = 1 if P == P0 else parts
        ends, energy = [], 0.0
        for k in range(1, parts + 1):
            before = self.memory
            end = self._part(P0 + (P - P0) * k / parts, Q0 + (Q - Q0) * k / parts)
            if end is not None:
                ends.append(end)
                energy += self._energy(end, before)
        return Step(min(ends) if ends else None, energy)

    def _energy(self, c, before):
        """``2 int_c^a f (p_before + p) / 2 |s - s_before| dx`` [J/m] over the slip zone ``(c, a)`` of a part
        (`before`: the memory before it), by Gauss-Legendre in ``x = c0 + (c1 - c0) sin^2(theta)`` on each
        piece between the band edges of `before` (the slip kinks there)."""
        theta, weight = np.polynomial.legendre.leggauss(ENERGY_POINTS)
        theta, weight = (theta + 1) * np.pi / 4, weight * np.pi / 4
        a = self.memory.a  # growing: the bands entering slip from the free surface's displacement at entry
        cuts = np.concatenate([[c], before.edges[(before.edges > c) & (before.edges < a)], [a]])
        total = 0.0
        for c0, c1 in zip(cuts[:-1], cuts[1:], strict=True):
            x = c0 + (c1 - c0) * np.sin(theta) ** 2
            dx = (c1 - c0) * 2 * np.sin(theta) * np.cos(theta)
            p = (self.memory.pressure(x) + before.pressure(x)) / 2
            total += float(np.sum(weight * dx * self.f * p * np.abs(self.memory.slip(x) - before.slip(x))))
        return 2 * total
