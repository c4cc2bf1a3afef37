"""The incremental state machine: follow a load history with method 4 of the seed paper."""

from dataclasses import dataclass

import numpy as np

from fretting.contact import Contact
from fretting.errors import GrossSlipError, HistoryError
from fretting.history import History
from fretting.solver import Grid, solve_increment
from fretting.variables import build_dataset

__all__ = ["State", "simulate", "final_state", "DEFAULT_NODES"]

#: Collocation nodes by default: stick-zone ends, traction (/f p0) and slip (/max) within 5e-4
#: on the closed forms of the test suite (tests/test_closed_forms.py).
DEFAULT_NODES = 384


@dataclass(frozen=True, eq=False)
class State:
    """Everything the contact remembers of its history.

    Attributes
    ----------
    Q : float
        Shear force [N/m].
    sigma : float
        Bulk tension [Pa].
    slip : ndarray, shape (N,)
        Accumulated slip [m] at the collocation nodes, ascending in x.
    episode_start : ndarray, shape (N,)
        Slip [m] at which each node's current episode of slip in one direction began (equal
        to `slip` where the node sticks). Only the sub-grid stick-zone ends use it.
    """

    Q: float
    sigma: float
    slip: np.ndarray
    episode_start: np.ndarray

    @classmethod
    def virgin(cls, nodes):
        """The contact just formed: no load and no slip."""
        return cls(0.0, 0.0, np.zeros(nodes), np.zeros(nodes))

    def advance(self, Q, sigma, ds):
        """State after the slip increment `ds` [m] under the loads `Q`, `sigma`."""
        slip = self.slip + ds
        episode = self.slip - self.episode_start
        reversed_ = np.sign(ds) * np.sign(episode) < 0
        episode_start = np.where(ds == 0, slip, np.where(reversed_, self.slip, self.episode_start))
        return State(Q, sigma, slip, episode_start)


def final_state(result):
    """State at the last step of a result of `simulate`, to continue the history from."""
    last = result.isel(step=-1)
    return State(float(last.Q), float(last.sigma), np.array(last.slip.values), np.array(result.episode_start.values))


class _Scene:
    """A contact discretised on a grid: the fixed arrays that every increment uses."""

    def __init__(self, contact, nodes):
        self.contact = contact
        self.grid = Grid(nodes)
        self.x = contact.centre + contact.a * self.grid.t
        self.G = contact.E_star / contact.a * self.grid.stiffness
        self.limit = contact.f * contact.pressure_weighted(self.grid.t)
        self.w = contact.a * self.grid.weight  # quadrature weight of int F / sqrt(a^2 - x^2) dx times a
        self.friction_force = self.w * self.limit.sum()  # f P on the grid

    def g_stuck(self, Q, sigma):
        """``sqrt(1 - t^2) q_st`` [Pa], the fully stuck traction of eqs (9) and (20)."""
        a = self.contact.a
        return (Q / np.pi + sigma * a * self.grid.t / 4) / a

    def traction(self, g):
        return g / np.sqrt(1 - self.grid.t**2)

    def delta_Q(self, slip):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] (formulation.md section 5)."""
        return np.mean(slip)

    def delta_sigma(self, slip):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2] (formulation.md section 5)."""
        return self.w * np.dot(slip, self.grid.t) / 4

    def dissipation(self, ds):
        """``int f p |ds| dx`` [J/m]."""
        return self.w * np.dot(self.limit, np.abs(ds))


def simulate(contact, history, *, nodes=DEFAULT_NODES, state=None):
    """Follow a load history and record the contact at every step.

    Parameters
    ----------
    contact : Contact
    history : History
        Step 0 is the starting state. Without `state` the contact starts just formed,
        unloaded; a non-zero first vertex is then reached in one increment.
    nodes : int
        Gauss-Chebyshev collocation nodes.
    state : State, optional
        State to continue from (see `final_state`); its loads must be the history's first.

    Returns
    -------
    xarray.Dataset
        Variables of `fretting.variables.VARIABLES`.

    Raises
    ------
    GrossSlipError
        When a step leaves no stick zone.
    """
    if not isinstance(contact, Contact):
        raise ValueError(f"contact must be a fretting.Contact, found {contact!r}")
    if not isinstance(history, History):
        raise ValueError(f"history must be a fretting.History, found {history!r}")
    scene = _Scene(contact, nodes)
    if state is None:
        state = State.virgin(nodes)
    elif state.slip.shape != (nodes,):
        raise ValueError(f"state has {state.slip.size} nodes, the simulation {nodes}")
    elif (state.Q, state.sigma) != (history.Q[0], history.sigma[0]):
        raise HistoryError(
            f"history starts at Q = {float(history.Q[0])!r}, sigma = {float(history.sigma[0])!r}; "
            f"the state is at Q = {float(state.Q)!r}, sigma = {float(state.sigma)!r}"
        )
    return build_dataset(_run(scene, history, state), _attributes(contact, nodes))


def _run(scene, history, state):
    n = len(history)
    N = scene.grid.N
    data = {
        "q": np.empty((n, N)),
        "slip": np.empty((n, N)),
        "stick": np.empty((n, N), dtype=bool),
        "dissipation": np.zeros(n),
    }
    zones = []
    G = scene.G
    g = scene.g_stuck(state.Q, state.sigma) - G @ state.slip
    for step in range(n):
        Q, sigma = history.Q[step], history.sigma[step]
        if abs(Q) >= scene.friction_force:
            raise GrossSlipError(step, Q, sigma, scene.friction_force)
        if step > 0 or (Q, sigma) != (state.Q, state.sigma):
            increment = solve_increment(G, scene.g_stuck(Q, sigma) - G @ state.slip, scene.limit)
            g, ds = increment.g, increment.ds
        else:
            ds = np.zeros(N)
        state = state.advance(Q, sigma, ds)
        data["q"][step] = scene.traction(g)
        data["slip"][step] = state.slip
        data["stick"][step] = ds == 0
        data["dissipation"][step] = scene.dissipation(ds)
        zones.append(stick_zones(scene.grid.t, state.slip - state.episode_start))
    width = max(len(z) for z in zones)
    ends = np.full((n, width, 2), np.nan)
    for step, z in enumerate(zones):
        ends[step, : len(z)] = z
    ends = scene.contact.centre + scene.contact.a * ends
    if history.cycle is not None:
        data["cycle"] = history.cycle
        data["cycle_dissipation"] = np.bincount(history.cycle, data["dissipation"])[1:]
    return data | {
        "Q": history.Q,
        "sigma": history.sigma,
        "p": scene.contact.pressure(scene.x),
        "x": scene.x,
        "step": np.arange(n),
        "stick_start": ends[..., 0],
        "stick_end": ends[..., 1],
        "delta_Q": data["slip"].mean(axis=1),
        "delta_sigma": scene.w * data["slip"] @ scene.grid.t / 4,
        "vertex_step": history.vertex_step,
        "episode_start": state.episode_start,
    }


def stick_zones(t, ds):
    """Stick intervals ``(start, end)`` in normalised position, from the episode slip `ds`.

    `ds` is each node's slip since its current episode of slip in one direction began, zero
    where the node stuck in the last increment. Near a stick/slip boundary it grows like
    ``d^(3/2)`` with the distance ``d`` (eq 19; Masing for reversed zones), so ``|ds|^(2/3)`` is
    extrapolated linearly from the two nearest slipping nodes: about 0.05 node spacings on the
    closed forms. A run of stuck nodes that reaches the end of the grid ends at the contact edge.
    """
    stuck = ds == 0
    edges = np.flatnonzero(np.diff(np.concatenate([[0], stuck.astype(np.int8), [0]])))
    runs = edges.reshape(-1, 2)  # [first stuck node, one past the last]
    return [(_boundary(t, ds, first, -1), _boundary(t, ds, last - 1, +1)) for first, last in runs]


def _boundary(t, ds, inner, side):
    """Stick/slip boundary beyond the stuck node `inner` on `side` (-1 below, +1 above).

    The discrete stick zone may overshoot the true one by part of a node spacing, so the
    estimate may lie up to one spacing inside the last stuck node, never beyond the first
    slipping one.
    """
    outer = inner + side
    if outer < 0 or outer >= t.size:
        return float(side)
    beyond = outer + side
    d1 = abs(ds[outer]) ** (2 / 3)
    if 0 <= beyond < t.size and np.sign(ds[beyond]) == np.sign(ds[outer]):
        d2 = abs(ds[beyond]) ** (2 / 3)
        if d2 > d1:
            estimate = t[outer] - d1 * (t[beyond] - t[outer]) / (d2 - d1)
            deepest = t[inner] - (t[outer] - t[inner])
            return float(np.clip(estimate, *sorted((deepest, t[outer]))))
    return float((t[inner] + t[outer]) / 2)


def _attributes(contact, nodes):
    return {
        "a": contact.a,
        "p0": contact.p0,
        "E_star": contact.E_star,
        "f": contact.f,
        "P": contact.P,
        "centre": contact.centre,
        "profile": repr(contact.profile),
        "model": "method 4: dislocation correction to the fully adhered solution",
        "nodes": nodes,
    }
