"""What the two discretisations of method 4 share: the increment by the active-set solver and
the stick zones read off the slip.

Method 4 of the seed paper corrects the fully stuck traction of eqs (9) and (20) by the
traction of a distribution of glide dislocations, the slip ``s``; one increment minimises the
convex functional of `fretting.models.solver` over the slip increment. A discretisation gives
the slip-to-traction matrix ``G``, the fully stuck traction ``g_stuck(Q, sigma)`` and the friction
limit ``limit`` in its own measure (`CollocationModel`: ``sqrt(1 - t^2)`` times the traction [Pa];
`GalerkinModel`: hat moments [N/m]); everything else here is in the contract's units.
"""

import abc
from functools import cached_property

import numpy as np

from fretting.models.base import Model, Outcome
from fretting.models.solver import Stiffness, solve_increment

__all__ = ["Method4Model", "deficit_end", "extrapolated_end", "on_the_point", "stick_zones"]


class Method4Model(Model):
    """A discretisation of method 4: subclasses set ``G``, ``limit``, ``friction_force`` and the
    nodes, and give `g_stuck`, `dissipation` and the contract's conversions."""

    G: np.ndarray
    limit: np.ndarray

    @abc.abstractmethod
    def g_stuck(self, Q, sigma):
        """The fully stuck traction of eqs (9) and (20) under `Q` [N/m], `sigma` [Pa], in the model's measure."""

    @abc.abstractmethod
    def dissipation(self, ds):
        """``int f p |ds| dx`` [J/m] of the slip increment `ds` [m]."""

    @cached_property
    def stiffness(self):
        """``G`` with what the solver derives from it, formed once per model."""
        return Stiffness(self.G)

    def at_rest(self, state):
        ds = np.zeros(state.slip.size)
        return Outcome(self.g_stuck(state.Q, state.sigma) - self.G @ state.slip, ds, state.slip, 0.0, slid=state.slid)

    #: Method 4 follows gross slip under displacement control (`slide`, docs/theory/displacement.md#sliding-sigma).
    slides = True

    def increment(self, state, loads, guess=None):
        """`Model.increment`; at ``|Q| = sliding_force``, the contact on the point of sliding (`on_the_point`)."""
        if abs(loads.Q) >= self.sliding_force():
            return self._sliding(state, loads, 0.0)
        if guess is None:  # the directions of the increment before
            guess = np.sign(state.slip - state.episode_start).astype(np.int8)
        solved = solve_increment(self.stiffness, self.g_stuck(loads.Q, loads.sigma), self.limit, state.slip, guess)
        return Outcome(solved.g, solved.ds, solved.slip, self.dissipation(solved.ds), slid=state.slid)

    def slide(self, state, loads, du):
        """`Outcome` of gross slip: the increment to ``loads.Q = +-sliding_force`` (`on_the_point`), then the
        uniform slide `du` [m] (the sign of ``Q``) of every node under ``g = +-limit``; its energy
        ``int f p |ds| dx`` (`dissipation`) holds ``friction_force |du|``."""
        return self._sliding(state, loads, du)

    def _sliding(self, state, loads, du):
        """`Outcome` of the increment from `state` to the contact on the point of sliding in the direction
        of ``loads.Q`` under ``loads.sigma`` (`on_the_point`), then slid by `du` [m], every node at its limit."""
        sign = np.sign(loads.Q)
        if (loads.Q, loads.sigma) == (state.Q, state.sigma):  # on the point of sliding already
            slip = state.slip + du
        else:
            load = self.g_stuck(sign * self.friction_force, loads.sigma) - sign * self.limit
            slip = on_the_point(self.stiffness, load, state.slip, sign) + du
        ds = slip - state.slip
        return Outcome(sign * self.limit, ds, slip, self.dissipation(ds), slid=state.slid + du)

    def stick_zones(self, outcome, state):
        return stick_zones(self.t, state.slip - state.episode_start, self.locate_end)

    def locate_end(self, position, d, slipping, beyond):
        """Where the slip `d` of a slip zone reaches zero between the nodes (`extrapolated_end`)."""
        return extrapolated_end(position, d, slipping, beyond)


def on_the_point(stiffness, load, slip, sign):
    """Slip [m] after the increment from `slip` [m] to the loads at which the contact is on the point of
    sliding whole, every node at its limit in the direction `sign` (+1, -1) of ``Q``
    (docs/theory/displacement.md#sliding-sigma).

    `load` is ``g_stuck - sign limit`` at ``Q = sign friction_force``, in the model's measure: its sum is
    zero (to rounding), and a slip ``s`` with ``G s = load`` leaves ``g = sign limit`` at every node,
    whatever its uniform part (``G 1 = 0``). Of those, the increment keeps the one of least uniform part
    whose slip increment never goes against ``Q``: the limit of the increments to ``|Q|`` below the
    friction force, whose functional differs from this one by ``F - |Q|`` times the mean of the slip
    increment, which selects the least. The node where the slip lags most behind the sliding field
    sticks (``ds = 0`` exactly there), every other one slips with ``Q`` and none against it: a node that
    a change of ``sigma`` would reverse sticks instead. ``s`` is ``B load``, ``B`` the inverse of ``G``
    made regular (`fretting.models.solver.Stiffness.regularised_inverse`), which solves ``G s = load``
    for a load of zero sum.
    """
    sliding = stiffness.regularised_inverse[1] @ load
    lag = sign * (slip - sliding)
    shift = lag.max()
    ahead = sign * np.maximum(sign * sliding + shift, sign * slip)  # never against Q, also by rounding
    return np.where(lag == shift, slip, ahead)


def stick_zones(t, ds, end=None):
    """Stick intervals ``(start, end)`` in normalised position, from the episode slip `ds`.

    `ds` is each node's slip since its current episode of slip in one direction began, zero
    where the node stuck in the last increment. Near a stick/slip boundary it grows like
    ``d^(3/2)`` with the distance ``d`` (eq 19; Masing for reversed zones), so ``|ds|^(2/3)`` is
    extrapolated linearly by `end` (default `extrapolated_end`, from the two nearest slipping
    nodes; on a Galerkin mesh `fretting.models.galerkin.located_end`; accuracy:
    benchmarks/accuracy_vs_nodes.py and benchmarks/trajectories.py). A run of stuck nodes that
    reaches the end of the grid ends at the contact edge.

    One interval per run of stuck nodes, in order: each lies between the slipping nodes around
    its run and holds the run's middle, so ``start <= end`` and intervals do not overlap.
    """
    stuck = ds == 0
    edges = np.flatnonzero(np.diff(np.concatenate([[0], stuck.astype(np.int8), [0]])))
    runs = edges.reshape(-1, 2)  # [first stuck node, one past the last]
    end = extrapolated_end if end is None else end
    return [_zone(t, ds, first, last - 1, end) for first, last in runs]


def _zone(t, ds, first, last, end):
    """Stick interval of the run of stuck nodes `first` .. `last`."""
    middle = (t[first] + t[last]) / 2
    return _boundary(t, ds, first, -1, middle, end), _boundary(t, ds, last, +1, middle, end)


#: How far inside the last stuck node [its spacing to the first slipping node] a stick end may be
#: placed. Where a zone grows monotonically the discrete stick zone overshoots the true one by
#: part of a spacing, and the ``d^(3/2)`` law places the end inside it (exact in-phase model
#: against method 4 on a fine mesh: tests/models/test_inphase.py); where the law fails (a slip zone
#: growing into slip locked in before) the extrapolation runs further in while the converged end
#: lies beyond the stuck node (references with the elements at their ends bisected:
#: benchmarks/trajectories.py, `BANDED`, which scores the stick ends of both kinds).
INWARD = 0.25


def _boundary(t, ds, inner, side, middle, end):
    """Stick/slip boundary beyond the stuck node `inner` on `side` (-1 below, +1 above).

    The estimate of `end` is kept between the first slipping node and `INWARD` of a spacing
    inside `inner`, never past `middle`, the middle of the run of stuck nodes, which keeps the two
    ends of a zone ordered where a stick zone narrower than a spacing lies between slip zones of
    opposite directions.
    """
    outer = inner + side
    if outer < 0 or outer >= t.size:
        return float(side)
    estimate = end(t, ds, outer, outer + side)
    if estimate is None:
        return float((t[inner] + t[outer]) / 2)
    deepest = t[inner] - side * min(INWARD * abs(t[outer] - t[inner]), abs(t[inner] - middle))
    return float(np.clip(estimate, *sorted((deepest, t[outer]))))


def extrapolated_end(position, d, slipping, beyond):
    """Where the slip increment `d` of a slip zone reaches zero, or None if it cannot be told.

    Near a stick/slip boundary ``d`` grows like ``dist^(3/2)`` (eq 19; Masing for reversed
    zones), so ``|d|^(2/3)`` is extrapolated linearly from the slipping node `slipping` and its
    neighbour `beyond` further into the zone (`position`: the nodes' coordinates). None when
    `beyond` is off the grid, slips the other way or has the smaller ``|d|``.
    """
    if not 0 <= beyond < d.size or np.sign(d[beyond]) != np.sign(d[slipping]):
        return None
    v1, v2 = abs(d[slipping]) ** (2 / 3), abs(d[beyond]) ** (2 / 3)
    if v2 <= v1:
        return None
    return position[slipping] - v1 * (position[beyond] - position[slipping]) / (v2 - v1)


def deficit_end(position, deficit, stuck, inner):
    """Where the friction deficit of a stick zone reaches zero past its node `stuck`, or None if it cannot be told.

    Next to a stick end ``c`` the traction of the stick zone falls short of its limit by ``K sqrt(|x - c|)``
    (the square-root kink of eq 19 for Cattaneo-Mindlin), so ``deficit^2`` (``f p - s q``, ``s`` the sign of the
    slip zone's traction) is extrapolated linearly from `stuck` and its neighbour `inner` further into the stick
    zone (`position`: the nodes' coordinates). None when `inner` is off the grid or has the smaller deficit.
    """
    if not 0 <= inner < deficit.size:
        return None
    v1, v2 = deficit[stuck] ** 2, deficit[inner] ** 2
    if v2 <= v1:
        return None
    return position[stuck] + v1 * (position[stuck] - position[inner]) / (v2 - v1)
