"""The incremental state machine: follow a load history with method 4 of the seed paper."""

from dataclasses import dataclass

import numpy as np

from fretting.contact import Contact
from fretting.errors import GrossSlipError, HistoryError
from fretting.history import History
from fretting.solver import Grid, solve_increment
from fretting.variables import build_dataset

__all__ = ["State", "simulate", "final_state", "DEFAULT_NODES"]

#: Collocation nodes by default: worst errors 3.7e-4 a (stick-zone ends), 2.6e-4 f p0 (traction)
#: and 4.5e-4 of the maximum slip on the closed forms of benchmarks/accuracy_vs_nodes.py; the
#: tests hold them to 1e-3. 256 nodes miss that (1.2e-3).
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

    def advance(self, Q, sigma, slip, ds):
        """State with the new `slip` [m], reached by the increment `ds` [m], under the loads `Q`, `sigma`."""
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
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] of each row of `slip` (formulation.md section 5)."""
        return np.mean(slip, axis=-1)

    def delta_sigma(self, slip):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2] of each row of `slip` (formulation.md section 5).

        A row-wise sum, not a matrix product, so that a row's value does not depend on how
        many rows there are (a run split in parts equals the whole run bit for bit).
        """
        return self.w * np.sum(slip * self.grid.t, axis=-1) / 4

    def dissipation(self, ds):
        """``int f p |ds| dx`` [J/m]."""
        return self.w * np.dot(self.limit, np.abs(ds))


def simulate(contact, history, *, nodes=DEFAULT_NODES, state=None, record=None):
    """Follow a load history and record the contact.

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
    record : array_like of int, optional
        Steps to store, increasing (default: every step). The dataset's `step` coordinate
        holds their numbers; `cycle_dissipation` always covers every step.

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
    elif (state.Q, state.sigma) != history.start:
        Q, sigma = history.start
        raise HistoryError(
            f"history starts at Q = {Q!r}, sigma = {sigma!r}; "
            f"the state is at Q = {float(state.Q)!r}, sigma = {float(state.sigma)!r}"
        )
    steps = _recorded_steps(record, len(history))
    return build_dataset(_run(scene, history, state, steps), _attributes(contact, nodes))


def _recorded_steps(record, n):
    if record is None:
        return np.arange(n)
    steps = np.asarray(record)
    if steps.ndim != 1 or not np.issubdtype(steps.dtype, np.integer) or steps.size == 0:
        raise ValueError(f"record must be a non-empty list of step numbers, found {record!r}")
    if np.any(np.diff(steps) <= 0) or steps[0] < 0 or steps[-1] >= n:
        raise ValueError(f"record must list increasing steps between 0 and {n - 1}")
    return steps


def _run(scene, history, state, steps):
    N = scene.grid.N
    row = np.full(len(history), -1)
    row[steps] = np.arange(steps.size)
    fields = {
        "q": np.empty((steps.size, N)),
        "slip": np.empty((steps.size, N)),
        "stick": np.empty((steps.size, N), dtype=bool),
        "dissipation": np.empty(steps.size),
    }
    cycle_dissipation = np.zeros(0 if history.cycle is None else history.cycle.max() + 1)
    zones = []
    G = scene.G
    g = scene.g_stuck(state.Q, state.sigma) - G @ state.slip
    for step in range(len(history)):
        Q, sigma = history.Q[step], history.sigma[step]
        if abs(Q) >= scene.friction_force:
            raise GrossSlipError(step, Q, sigma, scene.friction_force)
        if step > 0 or (Q, sigma) != (state.Q, state.sigma):
            increment = solve_increment(G, scene.g_stuck(Q, sigma), scene.limit, state.slip)
            g, ds = increment.g, increment.ds
            state = state.advance(Q, sigma, increment.slip, ds)
        else:  # the starting state itself: nothing moves, and its slip episodes go on
            ds = np.zeros(N)
        dissipation = scene.dissipation(ds)
        if cycle_dissipation.size:
            cycle_dissipation[history.cycle[step]] += dissipation
        k = row[step]
        if k >= 0:
            fields["q"][k] = scene.traction(g)
            fields["slip"][k] = state.slip
            fields["stick"][k] = ds == 0
            fields["dissipation"][k] = dissipation
            zones.append(stick_zones(scene.grid.t, state.slip - state.episode_start))
    data = fields | _zone_ends(scene, zones)
    if history.cycle is not None:
        data["cycle"] = history.cycle[steps]
        data["cycle_dissipation"] = cycle_dissipation[1:]
        data["cycle_number"] = np.arange(1, cycle_dissipation.size)
    return data | {
        "Q": history.Q[steps],
        "sigma": history.sigma[steps],
        "p": scene.contact.pressure(scene.x),
        "x": scene.x,
        "step": steps,
        "delta_Q": scene.delta_Q(fields["slip"]),
        "delta_sigma": scene.delta_sigma(fields["slip"]),
        "vertex_step": history.vertex_step,
        "episode_start": state.episode_start,
    }


def _zone_ends(scene, zones):
    """`stick_start` and `stick_end` [m] from per-step lists of normalised stick intervals."""
    ends = np.full((len(zones), max(len(z) for z in zones), 2), np.nan)
    for k, z in enumerate(zones):
        ends[k, : len(z)] = z
    ends = scene.contact.centre + scene.contact.a * ends
    return {"stick_start": ends[..., 0], "stick_end": ends[..., 1]}


def stick_zones(t, ds):
    """Stick intervals ``(start, end)`` in normalised position, from the episode slip `ds`.

    `ds` is each node's slip since its current episode of slip in one direction began, zero
    where the node stuck in the last increment. Near a stick/slip boundary it grows like
    ``d^(3/2)`` with the distance ``d`` (eq 19; Masing for reversed zones), so ``|ds|^(2/3)`` is
    extrapolated linearly from the two nearest slipping nodes: 0.05 to 0.1 of the node spacing
    at the centre on the closed forms (benchmarks/accuracy_vs_nodes.py). A run of stuck nodes
    that reaches the end of the grid ends at the contact edge.
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
