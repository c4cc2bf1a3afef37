"""In-phase ``Q`` and ``sigma`` on a Hertz contact, exactly: Nowell-Hills and Masing's rule on fixed nodes.

Along a load path ``sigma = k Q`` (a straight line through the origin of the ``(Q, sigma)``
plane), from the contact just formed, the traction of a Hertz contact is that of Nowell & Hills
(1987): ``q = f (p(x) - p_c(x - e))``, the corrective pressure ``p_c`` a Hertz pressure of
half-width ``c = a sqrt(1 - |Q| / (f P))`` centred at the offset ``e = -k |Q| a / (4 f p0)``
(signs of docs/theory/conventions.md; `fretting.physics.closed_forms.nowell_hills_traction`).
The corrective load is ``P_c = P (c / a)^2``, so ``e = -k (P - P_c) a / (4 p0)`` is fixed by
``P_c`` alone. Inside the contact ``p(x)`` closes the gap ``x^2 / (2R)`` and ``p_c(x - e)`` the
gap ``(x - e)^2 / (2R)``; the difference of the two strains is uniform and carries the bulk
strain mismatch of ``sigma``, so the slip is ``f`` times the gap outside the shifted corrective
contact, ``s = f hertz_slip_shape(x - e, c) / (2R)`` (docs/theory/exact-model.md).

The solution is the incremental one while the stick zone ``[e - c, e + c]`` shrinks into itself
as ``|Q|`` grows, ``|de/dQ| <= -dc/dQ``; its tightest point is the start, ``c = a``, where it reads
``|k| <= 4 / (pi a)``: the two edge coefficients ``Q/pi +- sigma a/4`` of the fully stuck traction
(eq 9, 20) keep the sign of ``Q`` (regime A of docs/theory/exact-model.md). Then every point slips
one way along a branch, and Masing's rule holds as it does for ``Q`` alone: from a turning point
the change is twice the monotonic solution of half the change of ``Q`` and ``sigma``. A branch of
factor ``F`` from ``Q_k`` is the monotonic solution of the load ``|Q - Q_k| / F``, whose offset
``-k |Q - Q_k| a / (4 F f p0)`` has the same sign in both directions. So the memory is the stack
of turning points of ``Q`` (`fretting.physics.closed_forms.masing_increment`), as in
`fretting.models.exact`, whose machinery runs here with the branch of a shifted corrective
contact (`InPhaseModel._solved`).

Per branch of the monotonic load ``Q`` with ``psi = |Q| / (f P)``:

- ``delta_sigma = pi k Q |Q| a^2 / (16 E_star f P)``: by the Chebyshev identities of
  docs/theory/conventions.md, ``delta_sigma = -(1 / (2 E_star)) int q_d x dx`` with ``q_d`` the
  traction less the fully stuck one, and the first moment of the shifted ellipse is ``e`` times
  its force;
- the energy ``int p g_c dx`` and ``delta_Q`` by Gauss-Legendre quadrature of the closed-form
  slip over the two slip zones, in a variable that makes both ends smooth (the shifted ellipse
  and the contact's make the integrals elliptic).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fretting.models.base import ModelSpec
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.exact import _U, _WEIGHTS, ExactModel, _Branch, nodes_theta
from fretting.physics.closed_forms import hertz_slip_shape
from fretting.physics.profiles import Hertz

if TYPE_CHECKING:
    from fretting.loading.history import History
    from fretting.physics.contact import Contact

__all__ = ["InPhase", "InPhaseModel", "on_line", "proportional_ratio", "regime_bound"]

#: Largest departure of ``sigma`` from ``k Q``, relative to ``|k| max |Q|``, that a history (and an
#: increment) may show and still be in phase: rounding of loads formed separately, as the steps
#: of `fretting.History.piecewise_linear` are.
PROPORTIONAL_RTOL = 1e-12


def regime_bound(contact: Contact) -> float:
    """Largest ``|sigma / Q|`` [1/m] of regime A on `contact`: ``4 / (pi a)``, where ``Q/pi - |sigma| a/4 = 0``."""
    return 4 / (np.pi * contact.a)


def proportional_ratio(history: History) -> float | None:
    """``k = sigma / Q`` [1/m] of a history whose every step has ``sigma = k Q`` (to `PROPORTIONAL_RTOL`), else None.

    ``k`` is read at the step of the largest ``|Q|`` (the first such step); a history without ``Q``
    is in phase only without ``sigma`` (``k = 0``), and one whose ``sigma / Q`` there passes the
    largest float (``Q`` of a few 1e-300 N/m) has no ratio.
    """
    Q, sigma = _peak(history)
    ratio = float(sigma / Q) if Q else 0.0
    return ratio if np.isfinite(ratio) and on_line(history, ratio) else None


def on_line(history: History, ratio: float) -> bool:
    """True where every step of `history` has ``sigma = ratio Q`` to `PROPORTIONAL_RTOL` of ``|ratio| max |Q|``.

    Checked `History.blocks` at a time: no temporary array of a long history's length.
    """
    scale = abs(_peak(history)[0])
    return all(_on_path(Q, sigma, ratio, scale) for Q, sigma in history.blocks())


def _peak(history):
    """``(Q, sigma)`` [N/m], [Pa] at the first step of the largest ``|Q|``, found `History.blocks` at a time."""
    peak = (0.0, 0.0)
    for Q, sigma in history.blocks():
        step = int(np.argmax(np.abs(Q)))
        if abs(Q[step]) > abs(peak[0]):
            peak = (float(Q[step]), float(sigma[step]))
    return peak


def _on_path(Q, sigma, ratio, scale):
    """True where ``|sigma - ratio Q| <= PROPORTIONAL_RTOL |ratio| scale`` at every load (`scale` [N/m])."""
    return bool(np.all(np.abs(sigma - ratio * Q) <= PROPORTIONAL_RTOL * abs(ratio) * scale))


@dataclass(frozen=True, eq=False, repr=False)  # ModelSpec.__repr__
class InPhase(ModelSpec):
    """The exact model of in-phase ``Q`` and ``sigma = ratio Q`` on a Hertz contact, on `nodes_theta` nodes.

    Parameters
    ----------
    nodes : int
        Gauss-Chebyshev angles of the node set (`fretting.models.exact.nodes_theta`).
    ratio : float, optional
        ``k = sigma / Q`` [1/m] of the load path (resolved: read from the history).
    theta : array_like, optional
        The node angles [rad], ascending (resolved).
    """

    nodes: int = DEFAULT_NODES
    ratio: float | None = None
    theta: np.ndarray | None = None

    name: ClassVar[str] = "inphase"
    memory_variable: ClassVar[str] = "state_turning"
    description: ClassVar[str] = (
        "the exact model of in-phase Q and sigma on Hertz: Nowell-Hills with Masing's rule, at fixed nodes"
    )

    def __post_init__(self):
        if self.theta is not None:
            object.__setattr__(self, "theta", np.array(self.theta, dtype=float))
        if self.ratio is not None:
            object.__setattr__(self, "ratio", float(self.ratio))

    @property
    def resolved(self) -> bool:
        return self.theta is not None and self.ratio is not None

    def resolved_for(self, contact: Contact, history: History | None) -> InPhase:
        """This spec with the ratio and nodes of `history` (None: the spec's own ratio, no stick-zone nodes)."""
        if self.resolved:
            return self
        ratio = self.ratio if history is None else proportional_ratio(history)
        if ratio is None:
            raise ValueError("InPhase needs a ratio sigma/Q: give one, or a history in phase through the origin")
        return InPhase(self.nodes, ratio, _stick_theta(contact, history, self.nodes, ratio))

    def build(self, contact: Contact) -> InPhaseModel:
        return InPhaseModel(contact, self)

    def is_default(self) -> bool:
        return True

    def attributes(self) -> dict:
        found = {"model": self.name, "grid_nodes": int(self.nodes)}
        return found | ({} if self.ratio is None else {"sigma_per_Q": self.ratio})

    def holds_for(self, contact: Contact, history: History | None) -> str | None:
        if not isinstance(contact.profile, Hertz):
            return f"{contact.profile!r} is not a Hertz profile"
        if history is None:
            return None if self.ratio is not None else "no history gives the ratio sigma/Q"
        if self.ratio is not None and not on_line(history, self.ratio):
            return f"the history leaves the model's line sigma = {self.ratio:g} 1/m * Q"
        ratio = self.ratio if self.ratio is not None else proportional_ratio(history)
        if ratio is None:
            return "sigma is not proportional to Q (the load path is not a straight line through the origin)"
        if abs(ratio) > regime_bound(contact):
            return (
                f"|sigma/Q| = {abs(ratio):g} 1/m passes regime A's 4/(pi a) = {regime_bound(contact):g} 1/m "
                "(an edge of the fully stuck traction changes sign)"
            )
        return None

    @classmethod
    def from_record(cls, attrs: dict, theta: np.ndarray | None) -> InPhase:
        return cls(int(attrs.get("grid_nodes", DEFAULT_NODES)), float(attrs["sigma_per_Q"]), theta)


def _stick_theta(contact, history, N, ratio):
    """Node angles [rad] of `nodes_theta`, its stick-zone points in the smallest stick zone, shifted."""
    if history is None:
        return nodes_theta(contact, None, N)
    largest = history.largest_Q_below(contact.f * contact.P)
    return nodes_theta(contact, history, N, _offset(contact, ratio, largest / contact.f))


def _offset(contact, ratio, deficit):
    """Offset ``e = -k (P - P_c) a / (4 p0)`` [m] of the stick zone of the corrective load ``P - deficit`` [N/m]."""
    return -ratio * deficit * contact.a / (4 * contact.p0)


class InPhaseModel(ExactModel):
    """The exact model of a Hertz contact under ``sigma = ratio Q`` on the nodes of a resolved `InPhase` spec.

    Its memory is the tuple of open turning points of ``Q`` [N/m], oldest first, as `ExactModel`'s.
    """

    def __init__(self, contact, spec):
        if not isinstance(contact.profile, Hertz):
            raise ValueError(f"{contact.profile!r}: the exact model of in-phase Q and sigma needs a Hertz profile")
        super().__init__(contact, spec)
        self.ratio = spec.ratio

    def increment(self, state, loads, guess=None):
        """`Outcome` from `state` to the loads ``Q`` [N/m] and ``sigma`` [Pa], which must be ``ratio Q``."""
        Q, sigma = loads.Q, loads.sigma
        if not _on_path(Q, sigma, self.ratio, self.friction_force):
            raise ValueError(f"sigma = {sigma!r} Pa is not {self.ratio!r} 1/m times Q = {Q!r} N/m: not in phase")
        return self._increment(state, Q, state.slid, 0.0)

    def stick_zones(self, outcome, state):
        """The stick zone of the last branch, ``[e - c, e + c]`` in ``t``."""
        ((low, high),) = outcome.zones
        c = high * self.contact.a
        shift = self._shift((self.contact.a - c) * (self.contact.a + c) / self.contact.a**2 * self.contact.P)
        return [(low + shift / self.contact.a, high + shift / self.contact.a)]

    def delta_sigma(self, outcome):
        """``pi k a^2 / (16 E_star f P) sum_i F_i (dQ_i / F_i) |dQ_i / F_i|`` [m^2] over the branches
        (module docstring), ``dQ_i`` the change of ``Q`` along branch ``i`` of factor ``F_i``."""
        turning = outcome.memory
        loads = np.array([*turning, outcome.Q])
        change = np.diff(loads, prepend=0.0)
        factor = np.full(change.size, 2.0)
        factor[0] = 1.0  # the virgin branch (masing_origin)
        contact = self.contact
        scale = np.pi * self.ratio * contact.a**2 / (16 * contact.E_star * contact.f * contact.P)
        return float(scale * np.sum(change * np.abs(change) / factor))

    def _offset_of(self, P_c):
        """Centre [m] of the corrective contact of the load `P_c` [N/m] (`_shift`)."""
        return self._shift(self.contact.P - P_c)

    def _shift(self, deficit):
        """Offset [m] of the corrective contact of the load ``P - deficit`` (`_offset`)."""
        return _offset(self.contact, self.ratio, deficit)

    def _solved(self, P_c):
        """`_Branch` of the corrective load `P_c` [N/m]: a Hertz contact of half-width ``c`` centred at ``e``."""
        contact = self.contact
        a, f, R = contact.a, contact.f, contact.profile.R
        c = float(contact.profile.half_width(P_c, contact.E_star)[0])
        e = self._offset_of(P_c)
        X = self.x - contact.centre - e
        inside = np.abs(X) < c
        p_c = np.zeros(self.x.size)
        p_c[inside] = contact.profile.pressure(X[inside] / c, c, 0.0, P_c, contact.E_star)
        q = f * (self._p - p_c)
        if c >= a:
            return _Branch(a, q, np.zeros(self.x.size), 0.0, 0.0)
        slip = np.zeros(self.x.size)
        slip[~inside] = f * hertz_slip_shape(X[~inside], c) / (2 * R)
        X, dX, root = (np.concatenate(pair) for pair in zip(_zone(-a, e - c, a), _zone(e + c, a, a), strict=True))
        g = hertz_slip_shape(X - e, c) / (2 * R)  # both slip zones at once
        energy, delta_Q = np.dot(contact.p0 * root / a * g, dX), f / np.pi * np.dot(g / root, dX)
        return _Branch(c, q, slip, float(energy), float(delta_Q))


#: ``X = low + (high - low) sin(phi / 2)^2`` with ``phi = pi (u + 1) / 2`` at the Gauss-Legendre points ``u``
#: (`_zone`): ``sin(phi/2)^2``, ``cos(phi/2)^2`` and ``dX / (high - low)`` times the weights.
_PHI = np.pi * (_U + 1) / 2
_SIN2, _COS2 = np.sin(_PHI / 2) ** 2, np.cos(_PHI / 2) ** 2
_DX = (np.pi / 2) * _WEIGHTS * np.sin(_PHI) / 2


def _zone(low, high, a):
    """Gauss-Legendre points ``X`` [m], weights ``dX`` [m] and ``sqrt(a^2 - X^2)`` [m] on the slip zone [`low`, `high`].

    ``X = low + (high - low) sin(phi / 2)^2``: the slip ``~ (X - c)^(3/2)`` at the stick end and the
    pressure ``~ sqrt(a -+ X)`` at the contact's edge become smooth in ``phi``; the distance to that
    edge is formed without cancellation.
    """
    width = high - low
    X = low + width * _SIN2
    if high == a:
        root = np.sqrt(width * _COS2 * (a + X))
    else:
        root = np.sqrt((a - X) * width * _SIN2)
    return X, width * _DX, root
