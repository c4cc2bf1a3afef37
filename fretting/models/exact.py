"""Q alone on a symmetric profile, exactly: Ciavarella-Jaeger and Masing's rule on fixed nodes.

Under the constant normal load ``P`` and a shear force ``Q`` rising from the contact just
formed, on a symmetric profile, the traction is ``q = f (p(x; P) - p(x; P_c))`` with
``|Q| = f (P - P_c)`` (Ciavarella 1998, Jaeger 1998; section 2 of the seed): the stick zone is
the contact ``[-c, c]`` of the corrective load ``P_c``, and the slip is ``f`` times that
contact's gap, ``s = f g_c(x)`` (docs/theory/exact-model.md; for Hertz it is eq 19
integrated, `fretting.physics.closed_forms.cattaneo_mindlin_slip`). Masing's rule gives any history of
``Q`` from it (Mindlin & Deresiewicz 1953 for Hertz; docs/theory/exact-model.md):
from the last turning point ``Q_k`` the change is twice the monotonic solution of half the
change, ``P_c = P - |Q - Q_k| / (2f)``, until ``|Q - Q_k|`` reaches the range of the branch
before; that loop then closes and the older branch goes on (return-point memory). The memory is
the list of turning points still open; the slip at the nodes is a sum over its branches.

The gap outside a contact of half-width ``c`` follows from the profile's load ``P(c')``: as the
contact grows from ``c`` to ``X``, each increment ``dP`` is a flat punch of half-width ``c'``,
which closes the gap at ``X`` by ``(2 / (pi E_star)) dP arccosh(X / c')`` (eq 1 outside the
punch), and the gap at ``X`` is zero once the contact reaches it:

    g_c(X) = (2 / (pi E_star)) int_c^X P'(c') arccosh(X / c') dc'

(Hertz: ``g_0 = X^2 / (2R)``). The slope ``P' = dP/dc'`` (`Profile.load_slope`), rather than
differences of ``P``, keeps the relative precision in the thinnest slip zones: those of a tiny
reversal dissipate Masing's energy (tests/models/test_masing.py::test_tiny_reversal_slips_by_the_cubic_law).

On Hertz a branch is a closed form instead (`ExactModel._hertz_branches`): the slip is Cattaneo-Mindlin's
in a form without cancellation (`fretting.physics.closed_forms.hertz_slip_shape`), the energy and
``delta_Q`` are Mindlin's, so a new branch costs a few operations per node rather than the
quadratures, which serve every other symmetric profile.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar, NamedTuple

import numpy as np

from fretting._compiled import njit
from fretting.loading.loads import Loads
from fretting.models.base import Model, ModelSpec, Outcome
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.solver import chebyshev_angles
from fretting.models.state import State
from fretting.physics.closed_forms import (
    compliance_scale,
    dissipation_scale,
    masing_arrival,
    masing_increment,
    masing_origin,
    slip_series,
    slip_shape,
)
from fretting.physics.profiles import Hertz
from fretting.physics.surface import ClosedFormSurfaceStress, ellipse_stress

if TYPE_CHECKING:
    from fretting.loading.history import History
    from fretting.physics.contact import Contact

__all__ = ["Exact", "ExactModel", "ExactOutcome", "gap", "nodes_theta", "transition_displacement"]

#: Gauss-Legendre points of each quadrature (the gap along ``c'``, the energy and ``delta_Q``
#: along ``X``): on Hertz the slip meets the closed form to rounding
#: (tests/models/test_masing.py::test_gap_of_hertz_is_cattaneo_mindlin), and on the rounded flat more
#: points change neither the slip, the energy nor delta_Q, also close to sliding
#: (tests/models/test_masing.py::test_quadrature_has_converged).
GAUSS = 64
_U, _WEIGHTS = np.polynomial.legendre.leggauss(GAUSS)

#: Nodes added toward each edge, per halving of the distance in ``theta``, below the first node
#: of the Gauss-Chebyshev grid, and the halvings: slip zones down to ``a (2^-12 pi / 2N)^2 / 2``,
#: ``8e-12 a`` at 384 nodes, hold 4 nodes or more
#: (tests/models/test_masing.py::test_nodes_hold_thin_slip_zones_and_small_stick_zones).
EDGE_NODES_PER_OCTAVE = 4
EDGE_OCTAVES = 12

#: Nodes that the smallest stick zone of a history holds at least: where fewer of the grid's lie
#: in it (Hertz beyond Q/fP = 0.997), as many Gauss-Chebyshev points of that zone are added.
STICK_NODES = 16

#: Corrective contacts kept (the slip, traction, energy of each load change met), and as many
#: sums over open turning points; a run that needs more computes them again. Each entry holds
#: two fields of N nodes: the two caches take up to 65 MB at 496 nodes.
CACHED_BRANCHES = 4096


@dataclass(frozen=True, eq=False, repr=False)  # ModelSpec.__repr__
class Exact(ModelSpec):
    """The exact model of ``Q`` alone on a symmetric profile, on `nodes_theta` nodes (`theta` once resolved).

    Parameters
    ----------
    nodes : int
        Gauss-Chebyshev angles of the node set (`nodes_theta`).
    theta : array_like, optional
        The node angles [rad], ascending (resolved).
    """

    nodes: int = DEFAULT_NODES
    theta: np.ndarray | None = None

    name: ClassVar[str] = "exact"
    recorded_as: ClassVar[tuple[str, ...]] = (
        "Ciavarella-Jaeger with Masing's rule: exact for Q alone on a symmetric profile, at fixed nodes",
    )
    memory_variable: ClassVar[str] = "state_turning"
    description: ClassVar[str] = (
        "the exact model of Q alone: Ciavarella-Jaeger with Masing's rule on a symmetric profile, at fixed nodes"
    )

    def __post_init__(self):
        if self.theta is not None:
            object.__setattr__(self, "theta", np.array(self.theta, dtype=float))

    @property
    def resolved(self) -> bool:
        return self.theta is not None

    def resolved_for(self, contact: Contact, history: History | None) -> Exact:
        """This spec with the nodes of `history` (None: no history known, no stick-zone nodes)."""
        return self if self.resolved else Exact(self.nodes, nodes_theta(contact, history, self.nodes))

    def build(self, contact: Contact) -> ExactModel:
        return ExactModel(contact, self)

    def is_default(self) -> bool:
        return True

    def attributes(self) -> dict:
        return {"model": self.name, "grid_nodes": int(self.nodes)}

    def holds_for(self, contact: Contact, history: History | None) -> str | None:
        if not contact.profile.SYMMETRIC:
            return f"{contact.profile!r} is not symmetric"
        if history is not None and history.largest_loads()[1] > 0:
            return "the history has a bulk tension sigma"
        return None

    @classmethod
    def from_record(cls, attrs: dict, theta: np.ndarray | None) -> Exact:
        return cls(int(attrs.get("grid_nodes", DEFAULT_NODES)), theta)


def nodes_theta(contact, history, N, offset=0.0):
    """Node angles [rad] of the exact model for `history`, ``x = centre + a cos(theta)``, ascending.

    The `N` Gauss-Chebyshev angles ``(2k - 1) pi / (2N)``, `EDGE_OCTAVES` octaves of
    `EDGE_NODES_PER_OCTAVE` toward each edge, and `STICK_NODES` Gauss-Chebyshev points of the
    smallest stick zone ``[-c, c]`` where fewer lie in it: that of the largest ``|Q| < f P`` of
    the history (a branch from a turning point changes the load by at most twice that, and
    its corrective load, ``P - |Q - Q_k| / (2f)``, is no smaller), centred at `offset` [m] from the
    contact's centre (where ``sigma`` shifts it, `fretting.models.inphase`). Without a history
    (None), no stick-zone points are added.
    """
    grid = chebyshev_angles(N)
    edge = grid[0] * 2.0 ** (-np.arange(1, EDGE_OCTAVES * EDGE_NODES_PER_OCTAVE + 1) / EDGE_NODES_PER_OCTAVE)
    theta = np.concatenate([edge[::-1], grid, np.pi - edge])
    if history is None:
        return theta
    largest = history.largest_Q_below(contact.f * contact.P)
    c = contact.profile.half_width(contact.P - largest / contact.f, contact.E_star)[0] / contact.a
    centre = offset / contact.a
    if np.count_nonzero(np.abs(np.cos(theta) - centre) < c) < STICK_NODES:
        theta = np.union1d(theta, np.arccos(centre + c * np.cos(chebyshev_angles(STICK_NODES))))
    return theta


@dataclass(frozen=True, eq=False)
class ExactOutcome(Outcome):
    """An `Outcome` of `ExactModel`: also the shear force ``Q`` [N/m] after the increment, which with
    the open turning points (``memory``) names its branches (`ExactModel.surface_at`)."""

    Q: float = np.nan


class _Branch(NamedTuple):
    """The monotonic solution of one corrective load ``P_c``, per unit of the branch's factor.

    Attributes: ``c`` the stick half-width [m]; ``q`` the traction ``f (p - p_c)`` [Pa] and
    ``slip`` ``f g_c`` [m] at the nodes; ``energy`` ``int p g_c dx`` [J/m per unit f^2];
    ``delta_Q`` ``int f g_c / (pi sqrt(a^2 - x^2)) dx`` [m]. A named tuple: a window of the exact
    model makes hundreds of them at once (`ExactModel._hertz_branches`).
    """

    c: float
    q: np.ndarray
    slip: np.ndarray
    energy: float
    delta_Q: float


class _Walk(NamedTuple):
    """Masing's rule over several increments (`ExactModel._walk`), one entry per increment in each of
    ``walks`` (turning points before, ``Q`` before, ``Q`` after [N/m]), ``memory`` (open turning
    points after), ``first`` (its first entry of ``corrective``), ``pieces`` (number of branch pieces
    walked) and ``signed`` (the signed factor of the branch it ends on, `_signed`); per entry of
    ``factor`` and ``corrective``: the start and end of each piece in turn, then the load reached on
    the branch it ends on, with the branch's factor and its corrective load [N/m].
    """

    walks: list
    memory: list
    first: list
    pieces: list
    signed: list
    factor: list
    corrective: list


class ExactModel(Model):
    """The exact model of a contact on the nodes of a resolved `Exact` spec.

    Its memory (`Outcome.memory`, `State.memory`) is the tuple of open turning points [N/m],
    oldest first.
    """

    linear_algebra = False  # closed forms and quadratures: no linear system to solve

    def __init__(self, contact, spec):
        if not contact.profile.SYMMETRIC:
            raise ValueError(f"{contact.profile!r}: the exact model of Q alone needs a symmetric profile")
        self.spec = spec
        self.contact = contact
        self.theta = spec.theta
        self.x = contact.centre + contact.a * np.cos(self.theta[::-1])
        self._x = self.x.tolist()  # ascending: the nodes inside a half-width found by bisection
        self.t = (self.x - contact.centre) / contact.a
        self.friction_force = contact.f * contact.P
        self._p = contact.pressure(self.x)
        self._fp = contact.f * self._p
        self._branches = {}  # P_c -> _Branch
        self._memories = {}  # turning points -> (slip, q, delta_Q) summed over their branches
        self._stresses = {}  # turning points -> surface stress of their branches (`_memory_stress`)
        self._walks = {}  # (turning points, Q before, Q after) -> (turning points after, energy) of the steps prepared

    def traction(self, outcome):
        """The traction [Pa]: the model gives it at the nodes directly."""
        return outcome.g

    def stick_zones(self, outcome, state):
        return outcome.zones

    def delta_Q(self, outcome):
        return outcome.delta_Q

    def delta_sigma(self, outcome):
        """Zero: the slip of ``Q`` alone on a symmetric profile is even in ``x``."""
        return 0.0

    def dissipation_density(self, ds):
        """``f p |ds|`` [J/m^2] at the nodes."""
        return self._fp * np.abs(ds)

    def at_rest(self, state):
        return self.increment(state, state.loads)

    @property
    def slides(self):
        """True: the exact model of ``Q`` alone reaches ``|Q| = f P`` exactly and follows gross slip
        (`slide`); not a subclass with increments of its own (`fretting.models.inphase`)."""
        return type(self).increment is ExactModel.increment

    def increment(self, state, loads, guess=None):
        """`Outcome` from `state` (its ``Q``, slip and open turning points) to the shear force ``loads.Q`` [N/m].

        ``sigma`` must be zero (`Exact.holds_for`): a ValueError otherwise. `guess` is not needed.
        ``|Q| = f P`` is the contact on the point of sliding whole (the corrective load ``P_c = 0``,
        no stick zone).
        """
        if loads.sigma:
            raise ValueError(f"the exact model of Q alone follows no bulk tension: found sigma = {loads.sigma!r} Pa")
        return self._increment(state, loads.Q, state.slid, 0.0)

    def slide(self, state, loads, du):
        """`Outcome` of gross slip: the increment to ``loads.Q = +-f P`` [N/m], then the whole contact
        slides by the uniform `du` [m] (the sign of ``Q``) under ``q = +-f p``, dissipating ``f P |du|``.

        The Masing walk to ``+-f P`` closes every open turning point (return-point memory): the memory
        of the partial slip before is erased, and a reversal starts Mindlin & Deresiewicz's branch
        from ``+-f P`` (docs/theory/displacement.md#gross-slip). The uniform slip is kept apart
        (`fretting.models.state.State.slid`), so that the nodes a later increment leaves stuck keep
        their slip bit for bit.
        """
        return self._increment(state, loads.Q, state.slid + du, self.friction_force * abs(du))

    def _increment(self, state, Q, slid, sliding):
        """`Outcome` from `state` to `Q` [N/m] with the uniform slip `slid` [m] of gross slip (`State.slid`)
        added to the Masing sum, and the energy `sliding` [J/m] of its change added to the branch's."""
        if Q == state.Q:
            turning, dissipation = state.memory, 0.0
        else:
            turning, dissipation = self._walked(state.memory, state.Q, Q)
        slip, q, delta_Q = self._at(turning, Q)
        c = self._solution(*masing_arrival(state.memory, state.Q, Q), Q).c
        if slid:
            slip, delta_Q = slip + slid, delta_Q + slid  # a uniform slip is its own delta_Q (eq D4)
        a = self.contact.a
        # no stick zone where the whole contact slides by a slip `slid` added in the increment, nor at c = 0; the
        # corrective contact of a rounded flat on the point of sliding is the flat, c = b, which has not slipped yet
        zones = [] if c == 0 or slid != state.slid else [(-c / a, c / a)]
        if Q == state.Q and slid == state.slid:
            return ExactOutcome(q, np.zeros(slip.size), slip, 0.0, turning, [(-1.0, 1.0)], delta_Q, slid, Q=Q)
        return ExactOutcome(q, slip - state.slip, slip, dissipation + sliding, turning, zones, delta_Q, slid, Q=Q)

    def surface_at(self, outcome):
        """`Model.surface`; on Hertz, the surface stress of the traction's elliptical loads in closed form.

        Each branch of factor ``F`` (signed as its change of load) adds ``F f (p - p_c)``, and on a
        Hertz contact ``p_c`` of the corrective contact of half-width ``c``, centred at ``e``
        (`_offset_of`), is ``p0 (c / a) sqrt(1 - ((x - e) / c)^2)``: the stress of each such load is
        `fretting.physics.surface.ellipse_stress`, exact at every node, where the nodal Hilbert matrix
        of `Model.surface` misses the square root at each stick end. The branches of the open turning
        points are summed once per memory (`_memory_stress`), the last one at each step.
        """
        if not isinstance(self.contact.profile, Hertz):
            return self.surface
        turning = outcome.memory
        last = self._branch_stress(turning, outcome.Q)
        return ClosedFormSurfaceStress(self._memory_stress(turning) + last), self._p

    def _branch_stress(self, turning, Q):
        """Stress [Pa] at the nodes of the traction of the branch after the open `turning` points, at `Q` [N/m]."""
        origin, factor = masing_origin(turning)
        signed = _signed(origin, factor, Q)
        if not signed:
            return np.zeros(self.t.size)
        P_c = self._corrective(origin, factor, Q)
        c = self._branch(P_c).c / self.contact.a
        unit = ellipse_stress(self.t, 1.0)
        if c:  # none at the onset of gross slip (P_c = 0): q = f p
            unit = unit - c * ellipse_stress(self.t, c, self._offset_of(P_c) / self.contact.a)
        return signed * self.contact.f * self.contact.p0 * unit

    def _memory_stress(self, turning):
        """`_branch_stress` summed over the branches that end at the open `turning` points, from the longest
        of their beginnings already summed (as `_memory`)."""
        known = len(turning)
        while known and turning[:known] not in self._stresses:
            known -= 1
        summed = self._stresses[turning[:known]] if known else np.zeros(self.t.size)
        for k in range(known, len(turning)):
            summed = summed + self._branch_stress(turning[:k], turning[k])
            if len(self._stresses) >= CACHED_BRANCHES:
                self._stresses.clear()
            self._stresses[turning[: k + 1]] = summed
        return summed

    def _offset_of(self, P_c):
        """Centre [m] of the corrective contact of the load `P_c` [N/m] from the contact's: none under ``Q`` alone."""
        return 0.0

    def _walked(self, turning, before, Q):
        """(open turning points, energy dissipated [J/m]) of the change of the shear force from `before`
        to `Q` [N/m] with the open `turning` points: prepared (`prepare`), else walked here (`_walk`)."""
        prepared = self._walks.pop((turning, before, Q), None)
        if prepared is not None:
            return prepared
        walk = self._walk(turning, before, [Q])
        return walk.memory[0], self._dissipated(walk, self._solve(walk.corrective))[0]

    def _dissipated(self, walk, branches):
        """Energy [J/m] dissipated by each increment of `walk` (`_Walk`), with `branches` (a dict ``P_c ->
        _Branch`` holding those it meets): per increment, each loop that it closes, then the branch it
        ends on, ``factor (E(P_c end) - E(P_c start))`` summed in that order from 0, times ``f^2``.
        A loop over the increments, most of which walk one piece: no array is worth forming."""
        f2, factor, corrective = self.contact.f**2, walk.factor, walk.corrective
        energy = []
        for first, pieces in zip(walk.first, walk.pieces, strict=True):
            summed = 0.0
            for start in range(first, first + 2 * pieces, 2):
                summed += factor[start] * (branches[corrective[start + 1]].energy - branches[corrective[start]].energy)
            energy.append(f2 * summed)
        return energy

    @property
    def windows(self):
        """True if `window` gives this model's increments: those of `ExactModel.increment`, not a subclass's."""
        return type(self).increment is ExactModel.increment

    def window(self, state, loads):
        """The increments from `state` through the shear forces of `loads` (a `LoadBlock`) in turn, as rows.

        Row ``k`` is what `increment` gives for the ``k``-th load from the state the ``k - 1`` before
        it leave, bit for bit (the same sums in the same order, elementwise over the rows).

        Returns
        -------
        slip, q : ndarray, shape (len(loads), N)
            Slip [m] and traction [Pa] at the nodes after each increment.
        dissipation : list of float
            Energy dissipated by each increment [J/m].
        memory : list of tuple
            Open turning points [N/m] after each increment.
        still : ndarray of bool, shape (len(loads),)
            The increments that leave ``Q`` as it was (their ``ds`` is zero, `increment`).
        """
        loads = np.asarray(loads.Q, dtype=float)
        walk = self._walk(state.memory, state.Q, loads.tolist())
        branches = self._solve(walk.corrective)
        ends = [
            branches[walk.corrective[first + 2 * pieces]] for first, pieces in zip(walk.first, walk.pieces, strict=True)
        ]
        sums = [self._memory(turning) for turning in walk.memory]
        still = loads == np.append(state.Q, loads[:-1])
        factors = np.array(walk.signed)[:, None]  # factor x + y as `_added` forms it
        slip = np.array([branch.slip for branch in ends]) * factors + np.array([summed[0] for summed in sums])
        q = np.array([branch.q for branch in ends]) * factors + np.array([summed[1] for summed in sums])
        return slip, q, self._dissipated(walk, branches), walk.memory, still

    def _at(self, turning, Q):
        """Slip [m], traction [Pa] at the nodes and ``delta_Q`` [m] at `Q` with the open `turning` points.

        Summed branch by branch from the first, so a state reached again repeats bit for bit,
        and where the last branch sticks its terms are exact zeros: ``ds == 0`` exactly there.
        """
        origin, factor = masing_origin(turning)
        last = self._solution(origin, factor, Q)
        return _added(self._memory(tuple(turning)), last, _signed(origin, factor, Q))

    def _memory(self, turning):
        """Slip, traction and ``delta_Q`` at the last of the `turning` points, summed over their
        branches from the longest of its beginnings already summed (a loop, not a recursion: the
        open turning points of a decaying history can number thousands)."""
        summed = self._memories.get(turning)
        if summed is not None:
            return summed
        known = len(turning)
        while known and turning[:known] not in self._memories:
            known -= 1
        zero = np.zeros(self.x.size)
        summed = self._memories[turning[:known]] if known else (zero, zero, 0.0)
        for k in range(known, len(turning)):
            origin, factor = masing_origin(turning[:k])
            summed = _added(summed, self._solution(origin, factor, turning[k]), _signed(origin, factor, turning[k]))
            if len(self._memories) >= CACHED_BRANCHES:
                self._memories.clear()
            self._memories[turning[: k + 1]] = summed
        return summed

    def prepare(self, state, loads):
        """Solve together the branches that the increments from `state` through the shear forces of
        `loads` (a `LoadBlock`), in turn, meet, so that `increment` finds them solved.

        The Masing walk of `loads` is scalar (kept for `increment`), up to the first load of gross
        slip (``|Q| >= f P``, where the run stops); on Hertz the new branches are then one 2-D
        evaluation (`_hertz_branches`), whose rows equal those of branches solved one at a time bit
        for bit, so that what is prepared changes no result, only its cost. Other profiles
        (quadratures) and a subclass with branches of its own (`fretting.models.inphase`) gain
        nothing: nothing is done.
        """
        if not self._together:
            return
        loads = np.asarray(loads.Q, dtype=float)
        beyond = np.flatnonzero(np.abs(loads) >= self.friction_force)
        walk = self._walk(state.memory, state.Q, (loads[: beyond[0]] if beyond.size else loads).tolist())
        energy = self._dissipated(walk, self._solve(walk.corrective))
        self._walks = dict(zip(walk.walks, zip(walk.memory, energy, strict=True), strict=True))

    @property
    def _together(self):
        """True if the branches are solved together: on Hertz, with this class's `_solved`."""
        return isinstance(self.contact.profile, Hertz) and type(self)._solved is ExactModel._solved

    def _walk(self, turning, before, loads):
        """`_Walk` of Masing's rule from the open `turning` points and the shear force `before` through
        the shear forces `loads` [N/m] (a list) in turn: `masing_increment` of each, and the corrective
        loads of the branches met (`_corrective`)."""
        walks, memory, first, pieces, signed, factors, corrective = [], [], [], [], [], [], []
        for Q in loads:
            walks.append((turning, before, Q))
            turning, walked = masing_increment(turning, before, Q)
            first.append(len(corrective))
            for origin, factor, start, end in walked:
                factors += (factor, factor)
                corrective += (self._corrective(origin, factor, start), self._corrective(origin, factor, end))
            origin, factor = masing_origin(turning)
            factors.append(factor)
            corrective.append(self._corrective(origin, factor, Q))
            memory.append(turning)
            pieces.append(len(walked))
            signed.append(_signed(origin, factor, Q))
            before = Q
        return _Walk(walks, memory, first, pieces, signed, factors, corrective)

    def _solve(self, corrective):
        """A dict ``P_c -> _Branch`` holding the corrective loads `corrective` [N/m] (a list), solved in
        that order: on Hertz the new ones together (`_hertz_branches`), else one at a time (`_solved`);
        cached."""
        needed = dict.fromkeys(corrective)
        if not self._together:
            return {P_c: self._branch(P_c) for P_c in needed}
        if len(self._branches) + len(needed) > CACHED_BRANCHES:
            self._branches.clear()
        new = [P_c for P_c in needed if P_c not in self._branches]
        if new:
            self._branches |= zip(new, self._hertz_branches(np.array(new, dtype=float)), strict=True)
        return self._branches

    def _corrective(self, origin, factor, Q):
        """Corrective load ``P_c = P - |Q - origin| / (factor f)`` [N/m] of the branch from `origin` [N/m]
        at `Q` [N/m], a float; 0 at ``|Q| = f P`` and beyond."""
        return max(self.contact.P - abs(Q - origin) / (factor * self.contact.f), 0.0)

    def _solution(self, origin, factor, Q):
        """`_Branch` at `Q` [N/m] of the branch from `origin` [N/m] with `factor` (`_branch`)."""
        return self._branch(self._corrective(origin, factor, Q))

    def _branch(self, P_c):
        """`_Branch` of the corrective load `P_c` [N/m], computed once per ``P_c`` (while cached)."""
        branch = self._branches.get(P_c)
        if branch is None:
            if len(self._branches) >= CACHED_BRANCHES:
                self._branches.clear()
            branch = self._branches[P_c] = self._solved(P_c)
        return branch

    def _solved(self, P_c):
        """`_Branch` of the corrective load `P_c` [N/m]: its contact, traction, slip, energy and delta_Q,
        on Hertz in closed form (`_hertz_branches`), else by quadrature (`_quadrature_slip_zones`)."""
        contact, profile = self.contact, self.contact.profile
        if isinstance(profile, Hertz):
            return self._hertz_branches(np.array([P_c]))[0]
        a, f, E_star = contact.a, contact.f, contact.E_star
        c = float(profile.half_width(P_c, E_star)[0])  # a for the sharp flat punch, whose contact does not grow
        lo, hi = bisect.bisect_right(self._x, -c), bisect.bisect_left(self._x, c)  # x[lo:hi] in (-c, c)
        p_c, slip = np.zeros(self.x.size), np.zeros(self.x.size)
        p_c[lo:hi] = profile.pressure(self.x[lo:hi] / c, c, 0.0, P_c, E_star)
        q = f * (self._p - p_c)  # closed_forms.ciavarella_jaeger's, without the Contact (and its p0) it builds
        if c >= a:  # nothing slips
            return _Branch(a, q, slip, 0.0, 0.0)
        found, energy, delta_Q = _quadrature_slip_zones(contact, c, np.concatenate((self.x[:lo], self.x[hi:])))
        slip[:lo], slip[hi:] = found[:lo], found[lo:]
        return _Branch(c, q, slip, energy, delta_Q)

    def _hertz_branches(self, P_c):
        """`_Branch` of each corrective load of the array `P_c` [N/m] of a Hertz contact, in closed form
        (`_hertz_rows`, each branch as alone)."""
        contact = self.contact
        c = contact.profile.half_width(P_c, contact.E_star)[0]
        q, slip, c, energy, delta_Q = _hertz_rows(
            self.x, self._p, P_c, c, contact.a, contact.f, contact.profile.R,
            dissipation_scale(contact), compliance_scale(contact),
        )  # fmt: skip
        return list(map(_Branch, c.tolist(), q, slip, energy.tolist(), delta_Q.tolist()))


@njit
def _hertz_rows(x, p, P_c, c, a, f, R, dissipation, compliance):
    """Each branch of the corrective loads `P_c` [N/m] of half-widths `c` [m] on a Hertz contact
    (half-width `a` [m], friction `f`, radius `R` [m]), at the nodes `x` [m] of
    pressure `p` [Pa], in closed form; compiled: a step of `Stepper.step` solves one branch.

    Per branch: the traction ``q = f (p - p_c)`` with the corrective contact's elliptical
    pressure ``p_c = (2 P_c / (pi c)) sqrt(1 - (x / c)^2)`` (eq 6: `Hertz.pressure` and `Hertz.peak_pressure`,
    restated here so that a branch needs no array call beside the kernel); the slip
    ``f g_c = f slip_shape(x, c) / (2R)``, Cattaneo-Mindlin's at the load ``Q = f P psi`` with
    ``psi = 1 - (c/a)^2`` (the Ciavarella-Jaeger load ``f (P - P_c)``), formed as
    ``(a - c)(a + c) / a^2``, exact where ``c`` is close to ``a``; the energy over ``f^2`` and
    ``delta_Q``, `cattaneo_mindlin_dissipation` and `cattaneo_mindlin_compliance` of that load,
    from their scales `dissipation` [J/m] and `compliance` [m]. ``c = 0`` (``P_c = 0``) is the
    contact on the point of sliding whole: ``q = f p`` and the slip ``f x^2 / (2R)``. Where
    ``c >= a`` nothing slips: the half-width returned is ``a``, the energy and ``delta_Q`` 0.

    Returns q [Pa], slip [m] (rows: the branches), half-widths [m], energy [J/m per unit f^2], delta_Q [m].
    """
    rows, nodes = c.size, x.size
    q, slip = np.empty((rows, nodes)), np.empty((rows, nodes))
    energy, delta_Q, half_widths = np.zeros(rows), np.zeros(rows), np.full(rows, a)
    for i in range(rows):
        b = c[i]
        peak = 2 * P_c[i] / (np.pi * b) if b > 0 else 0.0
        for j in range(nodes):
            t = x[j] / b if b > 0 else 1.0
            if abs(t) < 1:
                q[i, j] = f * (p[j] - peak * math.sqrt(1 - t * t))
                slip[i, j] = 0.0
            else:
                q[i, j] = f * p[j]
                slip[i, j] = f * slip_shape(x[j], b) / (2 * R)
        if b < a:
            psi = (a - b) * (a + b) / a**2
            energy[i] = dissipation * slip_series(psi, 3) / f**2
            delta_Q[i] = compliance * slip_series(psi, 2)
            half_widths[i] = b
    return q, slip, half_widths, energy, delta_Q


def _quadrature_slip_zones(contact, c, x):
    """Slip [m] at the points `x` [m] of the slip zones, energy ``int p g_c dx`` [J/m per unit f^2] and
    ``delta_Q`` [m] of the corrective contact of half-width `c` [m], for any symmetric profile: the
    slip from `gap`, the energy and ``delta_Q`` by Gauss-Legendre quadrature along ``c < X < a``."""
    a, f, E_star = contact.a, contact.f, contact.E_star
    slip = f * gap(contact.profile, E_star, c, x)
    # X = c + (a - c) sin(phi/2)^2: smooth integrands at both ends (g_c ~ (X - c)^(3/2), p ~ sqrt(a - X))
    phi = np.pi * (_U + 1) / 2
    X = c + (a - c) * np.sin(phi / 2) ** 2
    dX = (np.pi / 2) * _WEIGHTS * (a - c) * np.sin(phi) / 2
    g = gap(contact.profile, E_star, c, X)
    root = np.sqrt((a - c) * np.cos(phi / 2) ** 2 * (a + X))  # sqrt(a^2 - X^2)
    energy = 2 * np.dot(contact.pressure(X) * g, dX)
    delta_Q = (2 / np.pi) * f * np.dot(g / root, dX)
    return slip, float(energy), float(delta_Q)


def _to_breakpoint(profile, c):
    """Distance [m] from `c` in to the nearest of the profile's breakpoints (infinite if none)."""
    inside = [c - abs(point) for point in profile.breakpoints if abs(point) <= c]
    return min(inside, default=np.inf)


def _signed(origin, factor, Q):
    """`factor` of the branch from `origin` [N/m], signed as its change of load to `Q` [N/m] (zero if none)."""
    return factor if Q > origin else -factor if Q < origin else 0.0


def _added(summed, branch, factor):
    """`summed` (slip, traction, delta_Q) plus `factor` times the `_Branch`, each field formed in place
    (``factor x + y``, the same bits as a sum of temporaries)."""
    slip, q = branch.slip * factor, branch.q * factor
    slip += summed[0]
    q += summed[1]
    return slip, q, summed[2] + factor * branch.delta_Q


def gap(profile, E_star, c, X):
    """Gap ``g_c(X)`` [m] at ``|X| >= c`` outside the contact of half-width `c` [m] of a symmetric profile.

    ``(2 / (pi E_star)) int_c^X P'(c') arccosh(X / c') dc'`` (module docstring) by Gauss-Legendre in
    ``sigma``, with ``c' = beta + tau^2`` and ``tau = tau_X - (tau_X - tau_c) (1 - sigma)^2``:
    ``beta``, the breakpoint of the profile next inside `c` (0 if none), is where ``P'`` has a
    square root (the rounded flat's ``sqrt(c'^2 - b^2)``), which ``tau`` makes smooth however
    close `c` is to it, and ``sigma`` makes the square root of ``arccosh`` at ``c' = X`` smooth.
    """
    X = np.abs(np.asarray(X, dtype=float))[:, None]
    beta = c - min(_to_breakpoint(profile, c), c)
    tau_c, tau_X = np.sqrt(c - beta), np.sqrt(X - beta)
    span = (X - c) / (tau_X + tau_c)  # tau_X - tau_c, without its cancellation as X -> c
    sigma = (_U + 1) / 2
    tau = tau_X - span * (1 - sigma) ** 2
    c_ = beta + tau**2
    arccosh = np.arcsinh(np.sqrt(span * (1 - sigma) ** 2 * (tau_X + tau) * (X + c_)) / c_)  # exact as c' -> X
    jacobian = 2 * tau * 2 * span * (1 - sigma) / 2  # dc'/dsigma times d(sigma)/du
    integrand = profile.load_slope(c_, E_star) * arccosh * jacobian
    return (2 / (np.pi * E_star)) * (integrand @ _WEIGHTS)


def transition_displacement(contact: Contact) -> float:
    """Displacement ``delta_t`` [m] at which `contact` (a `fretting.Contact` with a datum), loaded from rest,
    starts to slide whole (docs/theory/displacement.md).

    ``delta_t = (C_L + C) f P + delta_Q(f P)`` (eq D6), ``delta_Q`` that of the exact model at the
    onset of sliding (Hertz: ``f p0 a / (2 E_star)``). It is also the amplitude of ``+-delta*``
    cycles beyond which each cycle slides both ways: Masing's branch from ``+f P`` reaches ``-f P``
    after a change of ``2 delta_t`` (eq D7). Depends on the datum.
    """
    if contact.datum is None:
        raise ValueError("the contact has no datum: give fretting.Contact(..., datum=L)")
    model = Exact().resolved_for(contact, None).build(contact)
    fP = contact.f * contact.P
    return contact.displacement(fP, model.delta_Q(model.increment(State.virgin(model), Loads(fP))))
