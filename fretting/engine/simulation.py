"""The incremental state machine: follow a load history with method 4 of the seed paper, or,
under Q alone on a symmetric profile, with the exact model of `fretting.models.exact`."""

import itertools
from dataclasses import dataclass, replace

import numpy as np
from threadpoolctl import threadpool_limits

from fretting._validate import positive
from fretting.physics.contact import Contact
from fretting.errors import GrossSlipError, HistoryError, SolverError
from fretting.models.galerkin import (
    DEFAULT_RTOL,
    GalerkinScene,
    element_targets,
    extrapolated_end,
    initial_theta,
    located_end,
    refine,
)
from fretting.loading.history import History
from fretting.models.exact import MODEL as MASING_MODEL
from fretting.models.exact import MasingScene, applies, nodes_theta
from fretting.models.solver import Grid, solve_increment
from fretting.results.variables import build_dataset

__all__ = [
    "DEFAULT_NODES",
    "MAX_DEFAULT_MESH",
    "RECORD_ALL_STEPS",
    "RECORDED_ENDS",
    "State",
    "Tally",
    "default_model",
    "final_state",
    "recorded_steps",
    "simulate",
]

MODEL = "method 4: dislocation correction to the fully adhered solution"
GALERKIN = "P1 Galerkin in theta on a mesh adapted to rtol"
COLLOCATION = "Gauss-Chebyshev collocation"

#: Refinements of the Galerkin mesh before `adapted_mesh` gives up: each at least halves an
#: element, and 60 halvings take pi below 1e-17.
REFINEMENTS = 60

#: Turn [rad] of the load path's direction after which `adapted_mesh` cuts a curved stretch
#: between turning points (`History.turning_points`), the direction taken in the plane of
#: ``Q / (pi a)`` and ``sigma / 4`` [Pa], the mean and the slope of the fully stuck traction
#: ``sqrt(1 - t^2) q_st = Q / (pi a) + sigma t / 4`` of eqs (9) and (20). A quarter of a
#: 90-degree out-of-phase cycle is then run as two increments: on the bench's scene
#: (`fretting.bench.scenes`, hertz_out_of_phase) the energy per cycle is within 4.7e-6 of the
#: 1536-node grid on 380 nodes, without cuts 5.8e-4 on 287 (results/speed_vs_error.md, before
#: and after); in one scratch comparison on that scene a turn of 60 degrees gave 6.6e-5 (355
#: nodes) and of 30 degrees 5.4e-6 (445 nodes), not rerun.
MAX_TURN = np.pi / 4

#: Collocation nodes of the Gauss-Chebyshev model: worst errors 3.7e-4 a (stick-zone ends), 2.6e-4 f p0 (traction)
#: and 4.5e-4 of the maximum slip on the closed forms of benchmarks/accuracy_vs_nodes.py; the
#: tests hold them to 1e-3. 256 nodes miss that (1.2e-3).
DEFAULT_NODES = 384
#: Nodes beyond which the default model gives up adapting a Galerkin mesh and runs on the grid of
#: `DEFAULT_NODES` instead: a mesh's passes cost ``N^3`` per turning point, and the non-periodic
#: turning points of out-of-phase cycles can drive it past 1000 nodes (the rounded-flat scene of
#: tests/test_galerkin.py's `test_default_runs_the_grid_where_the_mesh_would_be_too_large`, 30
#: cycles: 1333 nodes in 31 s, the grid 3.9 s; measured 2026-11-21). A bound of 1024, tried the
#: same day, put 4 more of the 40 scenes of benchmarks/default_out_of_phase.py on meshes (at most
#: 11.7 s against 3.6 s) and the rounded flat at Q/fP = 0.999999 on its 897-node mesh, which
#: covers the flat where the grid's stick zone does not; but under CI=true (hypothesis's fixed
#: examples) tests/test_hard_properties.py's loop-work test ran for more than 4 minutes.
MAX_DEFAULT_MESH = 2 * DEFAULT_NODES


#: BLAS and LAPACK threads while the engine runs. Its work is many small products and
#: factorisations, one after another, which threads only slow down: on the bench's 10-vertex
#: random scene (764 nodes) the default takes 68 ms per step with OpenBLAS's two threads on this
#: 2-core machine and 3.5 ms with one (wall time, benchmarks/blas_threads.py). Limited with
#: threadpoolctl, which reaches the BLAS already loaded (an environment variable acts only before
#: numpy is imported).
BLAS_THREADS = 1
_engine_threads = threadpool_limits.wrap(limits=BLAS_THREADS, user_api="blas")


#: Default recording: every step of histories up to this many steps; of longer ones the first
#: and the last RECORDED_ENDS steps (64 cycles of 64 steps). At 384 nodes 20,000 recorded steps take 130 MB.
RECORD_ALL_STEPS = 20_000
RECORDED_ENDS = 4096


@dataclass(frozen=True, eq=False)
class Tally:
    """What the cycle in progress has done so far.

    Attributes
    ----------
    number : int
        Load cycle (0: the steps outside any cycle, which are not tallied).
    dissipation : float
        Energy dissipated [J/m].
    w : ndarray, shape (N,)
        Energy dissipated per unit area [J/m^2] at the nodes.
    slip_min, slip_max : ndarray, shape (N,)
        Extremes of the slip [m] over the cycle, its starting state included.
    """

    number: int
    dissipation: float
    w: np.ndarray
    slip_min: np.ndarray
    slip_max: np.ndarray

    @classmethod
    def begin(cls, number, slip):
        """Nothing done yet in cycle `number`, which starts from `slip` [m]."""
        return cls(number, 0.0, np.zeros(slip.size), slip, slip)

    def add(self, dissipation, w, slip):
        """The tally after an increment that dissipated `dissipation` [J/m], `w` [J/m^2] and left `slip` [m]."""
        return Tally(
            self.number,
            self.dissipation + dissipation,
            self.w + w,
            np.minimum(self.slip_min, slip),
            np.maximum(self.slip_max, slip),
        )

    @property
    def slip_amplitude(self):
        """Half the range of the slip over the cycle [m]."""
        return (self.slip_max - self.slip_min) / 2


@dataclass(frozen=True, eq=False)
class State:
    """Everything the contact remembers of its history, and the tally of the cycle in progress.

    Attributes
    ----------
    Q : float
        Shear force [N/m].
    sigma : float
        Bulk tension [Pa].
    slip : ndarray, shape (N,)
        Accumulated slip [m] at the nodes, ascending in x.
    episode_start : ndarray, shape (N,)
        Slip [m] at which each node's current episode of slip in one direction began (equal
        to `slip` where the node sticks). Only the sub-grid stick-zone ends use it.
    tally : Tally
        Energy and slip range of the cycle in progress, so that a run continued from this
        state reports that cycle whole.
    dissipated : float
        Energy dissipated since the contact was formed [J/m], summed step by step.
    theta : ndarray, shape (N,), optional
        Galerkin mesh or nodes of the exact model [rad] on which the fields live, ascending
        (None: Gauss-Chebyshev collocation).
    turning : tuple of float, optional
        Turning points [N/m] that the exact model of ``Q`` alone (`fretting.models.exact`) still
        remembers, oldest first (None: a state of method 4).
    """

    Q: float
    sigma: float
    slip: np.ndarray
    episode_start: np.ndarray
    tally: Tally
    dissipated: float = 0.0
    theta: np.ndarray | None = None
    turning: tuple | None = None

    @classmethod
    def virgin(cls, scene):
        """The contact of `scene` just formed: no load and no slip."""
        slip = np.zeros(scene.x.size)
        turning = () if isinstance(scene, MasingScene) else None
        return cls(0.0, 0.0, slip, slip, Tally.begin(0, slip), theta=getattr(scene, "theta", None), turning=turning)

    def advance(self, Q, sigma, slip, ds):
        """State with the new `slip` [m], reached by the increment `ds` [m], under the loads `Q`, `sigma`."""
        episode = self.slip - self.episode_start
        reversed_ = np.sign(ds) * np.sign(episode) < 0
        episode_start = np.where(ds == 0, slip, np.where(reversed_, self.slip, self.episode_start))
        return replace(self, Q=Q, sigma=sigma, slip=slip, episode_start=episode_start)

    def repeats(self, other):
        """True if this state is `other`'s memory bit for bit: the same loads, slip fields and turning points."""
        return (
            (self.Q, self.sigma, self.turning) == (other.Q, other.sigma, other.turning)
            and np.array_equal(self.slip, other.slip)
            and np.array_equal(self.episode_start, other.episode_start)
        )


def final_state(result):
    """State at the last step of a result of `simulate`, to continue the history from."""
    tally = Tally(
        int(result.state_cycle),
        float(result.state_cycle_dissipation),
        result.state_w.values.copy(),
        result.state_slip_min.values.copy(),
        result.state_slip_max.values.copy(),
    )
    return State(
        float(result.state_Q),
        float(result.state_sigma),
        result.state_slip.values.copy(),
        result.state_episode_start.values.copy(),
        tally,
        float(result.total_dissipation),
        result.theta.values[::-1].copy() if "theta" in result else None,  # ascending in theta
        tuple(result.state_turning.values.tolist()) if "state_turning" in result else None,
    )


class _Scene:
    """A contact discretised on Gauss-Chebyshev nodes: the fixed arrays that every increment uses.

    The discrete pressure is the contact's times `pressure_scale`, so that its quadrature
    carries ``P``. Equilibrium on the grid is the quadrature ``Q = w sum g``, so the stick zone
    vanishes where ``|Q|`` reaches the friction force ``w sum limit``: scaled, that is ``f P``,
    and every ``|Q| < f P`` leaves one. The Gauss-Chebyshev quadrature of ``p`` is exact where
    ``p sqrt(1 - t^2)`` is a polynomial of degree below ``2N``: Hertz (degree 2) and the sharp
    flat punch (degree 0), within 2.2e-16 of ``P`` at 16 to 1536 nodes. A rounded flat's
    pressure has a singular derivative at the flat's ends: for tests/test_hard_cases.py's
    ``rounded_flat()`` the quadrature falls 2.0e-5 short of ``P`` at 384 nodes (6.1e-4 at 64,
    9.1e-7 at 1536), and unscaled, the loads 0.99999 and 0.999999 f P raised GrossSlipError.
    """

    def __init__(self, contact, nodes):
        self.contact = contact
        self.grid = Grid(nodes)
        self.t = self.grid.t
        self.x = contact.centre + contact.a * self.t
        self.G = contact.E_star / contact.a * self.grid.stiffness
        self.w = contact.a * self.grid.weight  # quadrature weight of int F / sqrt(a^2 - x^2) dx times a
        self.area = self.w * np.sqrt(1 - self.t**2)  # quadrature weight of int F dx [m]
        weighted = contact.pressure_weighted(self.t)  # p sqrt(1 - t^2) [Pa]
        self.pressure_scale = contact.P / (self.w * weighted.sum())  # [-]
        self.limit = contact.f * self.pressure_scale * weighted  # f p sqrt(1 - t^2) of the discrete pressure [Pa]
        self.friction_force = self.w * self.limit.sum()  # f P to rounding [N/m]

    def g_stuck(self, Q, sigma):
        """``sqrt(1 - t^2) q_st`` [Pa], the fully stuck traction of eqs (9) and (20)."""
        a = self.contact.a
        return (Q / np.pi + sigma * a * self.t / 4) / a

    def traction(self, g, ds=None):
        """Shear traction [Pa] at the nodes (``ds`` is not needed on this grid).

        The utilisation ``g / limit`` times the contact's ``f p``, as the Galerkin scene gives
        it: Coulomb's law then holds at the nodes against the contact's pressure, not only
        against the discrete one.
        """
        return g / (self.pressure_scale * np.sqrt(1 - self.t**2))

    def delta_Q(self, slip):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] of each row of `slip` (formulation.md section 5)."""
        return np.mean(slip, axis=-1)

    def delta_sigma(self, slip):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2] of each row of `slip` (formulation.md section 5).

        A row-wise sum, not a matrix product, so that a row's value does not depend on how
        many rows there are (a run split in parts equals the whole run bit for bit).
        """
        return self.w * np.sum(slip * self.t, axis=-1) / 4

    def dissipation(self, ds):
        """``int f p |ds| dx`` [J/m] of the discrete pressure."""
        return self.w * np.dot(self.limit, np.abs(ds))

    def dissipation_density(self, ds):
        """``f p |ds|`` [J/m^2] at the nodes, of the discrete pressure: its quadrature is `dissipation`."""
        return self.limit / np.sqrt(1 - self.t**2) * np.abs(ds)


@_engine_threads
def simulate(contact, history, *, nodes=None, rtol=None, mesh=None, state=None, record=None):
    """Follow a load history and record the contact.

    Parameters
    ----------
    contact : Contact
    history : History
        Step 0 is the starting state. Without `state` the contact starts just formed,
        unloaded; a non-zero first vertex is then reached in one increment.
    nodes : int, optional
        Solve on the fixed grid of this many Gauss-Chebyshev collocation nodes instead
        (`DEFAULT_NODES` is the usual choice).
    rtol : float, optional
        Relative accuracy of the energy asked of the P1 Galerkin model: the mesh is refined where
        the stick and slip zones of the history need it (`adapted_mesh`). When none of `nodes`,
        `rtol`, `mesh`, `state` is given, `default_model` chooses: the exact model of ``Q``
        alone (`fretting.models.exact`) where the history has no ``sigma`` and the profile is
        symmetric; else `DEFAULT_RTOL`, or the grid of `DEFAULT_NODES` where that mesh would
        exceed `MAX_DEFAULT_MESH` nodes.
    mesh : array_like, optional
        Galerkin mesh ``theta`` [rad] to use as it is (see `adapted_mesh`).
    state : State, optional
        State to continue from (see `final_state`); its loads must be the history's first.
        The run keeps its mesh or grid, or the exact model (then with ``sigma`` zero throughout).
    record : array_like of int or "all", optional
        Steps whose fields and loads are stored, increasing; the dataset's `step` coordinate
        holds their numbers. Default: every step of histories of up to `RECORD_ALL_STEPS`
        steps, else the first and the last `RECORDED_ENDS` steps. Energy and slip range per
        cycle and the final state always cover every step.

    Returns
    -------
    xarray.Dataset
        Variables of `fretting.results.variables.VARIABLES`.

    Raises
    ------
    GrossSlipError
        When a step leaves no stick zone.
    """
    if not isinstance(contact, Contact):
        raise ValueError(f"contact must be a fretting.Contact, found {contact!r}")
    if not isinstance(history, History):
        raise ValueError(f"history must be a fretting.History, found {history!r}")
    if state is not None and (state.Q, state.sigma) != history.start:
        Q, sigma = history.start
        raise HistoryError(
            f"history starts at Q = {Q!r}, sigma = {sigma!r}; "
            f"the state is at Q = {float(state.Q)!r}, sigma = {float(state.sigma)!r}"
        )
    recorded_rtol = rtol
    if all(value is None for value in (nodes, rtol, mesh, state)):
        scene = _default_scene(contact, history)
        recorded_rtol = DEFAULT_RTOL if isinstance(scene, GalerkinScene) else None
    else:
        scene = _scene(contact, history, rtol, nodes, mesh, state)
    steps = recorded_steps(record, len(history))
    run = _Run(scene, history, steps)
    data = run.data(run.follow(State.virgin(scene) if state is None else state))
    return build_dataset(data, _attributes(scene, recorded_rtol) | {"steps": len(history)})


@_engine_threads
def default_model(contact, history):
    """Keywords of `simulate` for its default model.

    ``{}`` where the exact model of ``Q`` alone applies (`fretting.models.exact.applies`: it needs
    none); else ``{"mesh": theta}``, the Galerkin mesh adapted to `DEFAULT_RTOL`, unless that
    mesh would need more than `MAX_DEFAULT_MESH` nodes; then ``{"nodes": DEFAULT_NODES}``, the grid.
    """
    scene = _default_scene(contact, history)
    if isinstance(scene, MasingScene):
        return {}
    return {"mesh": scene.theta} if isinstance(scene, GalerkinScene) else {"nodes": scene.x.size}


def _default_scene(contact, history):
    """The scene of the default model (see `default_model`)."""
    if applies(contact, history):
        return MasingScene(contact, nodes_theta(contact, history, DEFAULT_NODES))
    scene = _adapted_scene(contact, history, DEFAULT_RTOL, max_nodes=MAX_DEFAULT_MESH)
    return _Scene(contact, DEFAULT_NODES) if scene is None else scene


def _scene(contact, history, rtol, nodes, mesh, state):
    """The discretisation a run asks for: the state's, a grid, a given mesh or a mesh adapted to `rtol`."""
    asked = [name for name, value in (("nodes", nodes), ("rtol", rtol), ("mesh", mesh)) if value is not None]
    if len(asked) > 1:
        raise ValueError(f"give one of nodes (Gauss-Chebyshev), rtol or mesh (Galerkin), found {' and '.join(asked)}")
    if state is not None:
        if state.turning is not None:
            return _exact_scene(contact, history, state, asked)
        if state.theta is not None and asked:
            raise ValueError(f"the state has its own Galerkin mesh: give no {asked[0]}")
        if state.theta is not None:
            return GalerkinScene(contact, state.theta)
        if asked not in ([], ["nodes"]) or (nodes is not None and nodes != state.slip.size):
            raise ValueError(f"the state has its own grid of {state.slip.size} nodes: give no {asked[0]}")
        return _Scene(contact, state.slip.size)
    if mesh is not None:
        return GalerkinScene(contact, mesh)
    if nodes is not None:
        return _Scene(contact, nodes)
    return _adapted_scene(contact, history, rtol)


def _exact_scene(contact, history, state, asked):
    """The scene that continues `state`, a state of the exact model of ``Q`` alone."""
    if asked:
        raise ValueError(f"the state is of the exact model of Q alone ({MASING_MODEL}): give no {asked[0]}")
    if not applies(contact, history):
        raise HistoryError(
            "the state is of the exact model of Q alone, which this history leaves (sigma is not zero): "
            "run the whole history with nodes= or rtol= instead"
        )
    return MasingScene(contact, state.theta)


@_engine_threads
def adapted_mesh(contact, history, rtol=DEFAULT_RTOL, max_nodes=None):
    """Galerkin mesh ``theta`` [rad] that resolves the stick and slip zones of `history` to `rtol`.

    None, without running it, as soon as a refinement would give more than `max_nodes` nodes.

    Runs the history's turning points (`History.turning_points`, from the contact just formed),
    each curved stretch between them cut where its direction has turned by `MAX_TURN`, on a
    mesh graded toward the edges, refines every element that `fretting.models.galerkin.element_targets`
    finds too coarse at any of them, and runs them again until no element is; each run copies
    repeating cycles as `simulate` does. The other steps are not run: along a proportional
    stretch each node slips one way only, so its dissipation is ``f p |s_end - s_start|`` and
    depends on the states at the turning points alone, and the boundaries of the steps between
    lie in the slip zones of the increment from one turning point to the next, which
    `element_targets` fills with elements small enough to locate them. Along a curved stretch
    the loads of the steps between lie off the straight increment, and their slip zones reach
    where it sticks: on the bench's 90-degree scene 74 of the 128 steps of a cycle slip within
    0.64 a to 0.71 a of the centre, where no increment between turning points does; the
    elements there stayed 0.02 a to 0.05 a long and the energy per cycle erred by 5.8e-4.
    Cut into pieces that turn by less than `MAX_TURN`, the stretch is nearly proportional again.
    Refining about the zones of every step instead costs, on the scenes of
    benchmarks/turning_points.py, 2 to 5 times the nodes and 20 to 110 times the time.
    Under Q alone or sigma alone on a symmetric profile the mesh is kept symmetric, as the
    solution is. A history that reaches gross slip is adapted to the steps before it.

    Each pass starts the active set at a turning point from the slip directions the pass before
    found there (`_interpolated_directions`), which the answer does not depend on: on the bench's
    10-vertex random scene, after the first pass, 0 to 2 releases follow the first solve at a
    turning point instead of 3 to 9, the passes' runs take 0.07 s instead of 0.17 s and the whole
    default run 0.28 s instead of 0.38 s (CPU, one core; benchmarks/adaptation_passes.py).
    """
    scene = _adapted_scene(contact, history, rtol, max_nodes)
    return None if scene is None else scene.theta


def _adapted_scene(contact, history, rtol, max_nodes=None):
    """`GalerkinScene` of the last pass of `adapted_mesh` (the run then uses it, assembled once), or None."""
    rtol = positive("rtol", rtol)
    sliding = np.flatnonzero(np.abs(history.Q) >= contact.f * contact.P)
    if sliding.size:  # the run will stop there: adapt to the steps before
        history = history[: max(sliding[0], 1)]
    turning = history.turning_points(MAX_TURN, (np.pi * contact.a, 4.0))
    mirrored = contact.profile.SYMMETRIC and not (history.Q.any() and history.sigma.any())
    theta = initial_theta()
    directions = {}  # step: the slip directions the last pass found there, and its nodes' x
    scene = None
    for _ in range(REFINEMENTS):
        scene = GalerkinScene(contact, theta, previous=scene)
        targets, known, directions = np.full(theta.size - 1, np.inf), directions, {}

        def observe(step, ds, scene=scene, targets=targets, found=directions):
            np.minimum(targets, element_targets(scene.theta, ds, rtol, scene.breakpoints), out=targets)
            found[step] = np.sign(ds).astype(np.int8), scene.x

        def guess(step, known=known, x=scene.x):
            return _interpolated_directions(*known[step], x) if step in known else None

        _Run(scene, turning, np.zeros(0, dtype=np.int64), observe, guess).follow(State.virgin(scene))
        refined = refine(theta, np.minimum(targets, targets[::-1]) if mirrored else targets)
        if mirrored:  # Q alone or sigma alone: the zones are even or odd in x, and so is the mesh, exactly
            lower = refined[refined <= np.pi / 2]
            refined = np.concatenate([lower, np.pi - lower[::-1][int(lower[-1] == np.pi / 2) :]])
        if np.array_equal(refined, theta):
            return scene
        if max_nodes is not None and refined.size > max_nodes:
            return None
        theta = refined
    raise SolverError(f"the mesh still needed refining after {REFINEMENTS} refinements ({theta.size} nodes)")


def _interpolated_directions(directions, x, at):
    """Slip directions (+1, -1, 0) at the points `at` [m] from those at the nodes `x` [m] of a coarser mesh.

    A start for the solver only (`solve_increment`'s ``guess``): a node between two of `x` that
    differ in direction takes the direction of the linear interpolation, zero between opposite ones.
    """
    return np.sign(np.interp(at, x, directions)).astype(np.int8)


def recorded_steps(record, n):
    """Step numbers to record of an `n`-step history (see `simulate`)."""
    if record is None:
        if n <= RECORD_ALL_STEPS:
            return np.arange(n)
        return np.concatenate([np.arange(RECORDED_ENDS), np.arange(n - RECORDED_ENDS, n)])
    if isinstance(record, str) and record == "all":
        return np.arange(n)
    steps = np.asarray(record)
    if steps.ndim != 1 or not (steps.size == 0 or np.issubdtype(steps.dtype, np.integer)):
        raise ValueError(f'record must be a list of step numbers or "all", found {record!r}')
    if np.any(np.diff(steps) <= 0) or np.any(steps < 0) or np.any(steps >= n):
        raise ValueError(f"record must list increasing steps between 0 and {n - 1}")
    return steps.astype(np.int64)


@dataclass(frozen=True, eq=False)
class _Outcome:
    """One increment: the traction ``g`` after it, its slip increment ``ds`` and the state it leaves.

    The exact model of ``Q`` alone also gives the increment's stick `zones` (in ``t``) and the
    state's `delta_Q` [m]; method 4 leaves them None, to be found from the slip.
    """

    g: np.ndarray
    ds: np.ndarray
    dissipation: float
    state: State
    zones: list | None = None
    delta_Q: float | None = None


@dataclass(frozen=True, eq=False)
class _Cycle:
    """A complete cycle: its first step, the state before it and the outcome of each of its increments."""

    first: int
    before: State
    outcomes: list


class _Run:
    """One pass over a history: increments, the rows of the recorded steps and one row per cycle.

    A cycle whose loads repeat those of the cycle just completed, from a state that repeats
    the state before that cycle bit for bit, would repeat its increments bit for bit (the
    increment depends on the loads and the state only); such cycles are copied instead of
    solved, and marked in `cycle_copied`.

    `observe(step, ds)`, if given, sees the slip increment of every step solved; `guess(step)`,
    if given, returns the slip directions to start the solver from at `step`, or None for the
    state's (those of the increment before).
    """

    def __init__(self, scene, history, steps, observe=None, guess=None):
        self.scene, self.history, self.steps = scene, history, steps
        self.observe, self.guess = observe, guess
        self.cycle = history.cycle if history.cycle is not None else np.zeros(len(history), dtype=np.int64)
        self.row = np.full(len(history), -1)
        self.row[steps] = np.arange(steps.size)
        N = scene.x.size
        self.fields = {
            "q": np.empty((steps.size, N)),
            "slip": np.empty((steps.size, N)),
            "stick": np.empty((steps.size, N), dtype=bool),
            "dissipation": np.empty(steps.size),
            "delta_Q": np.empty(steps.size),
            "delta_sigma": np.empty(steps.size),
        }
        self.zones = [()] * steps.size
        self.cycles = []  # (number, tally, repeated) of every cycle the run touches

    def follow(self, state):
        """Run from `state` (whose loads are the history's first); return the state at the end."""
        previous = None  # the last cycle solved whole in this run: the one a repeating cycle copies
        before, outcomes = None, []  # state before the cycle in progress (if it began here), its increments
        repeated = False  # the cycle in progress is a copy
        step = 0
        while step < len(self.history):
            number = int(self.cycle[step])
            if number != state.tally.number:  # the increment to `step` begins a new stretch
                if state.tally.number:
                    self.cycles.append((state.tally.number, state.tally, repeated))
                    if before is not None and not repeated:
                        previous = _Cycle(step - len(outcomes), before, outcomes)
                state = replace(state, tally=Tally.begin(number, state.slip))
                before, outcomes, repeated = state, [], False
                copies = self._repeats(previous, state, step) if number else 0
                if copies:
                    state = self._copy(previous, step, copies)
                    step += copies * len(previous.outcomes)
                    repeated = True
                    continue
            outcome = self._increment(step, state)
            state = outcome.state
            outcomes.append(outcome)
            self._record(step, outcome)
            step += 1
        if state.tally.number:
            self.cycles.append((state.tally.number, state.tally, repeated))
        return state

    def _increment(self, step, state):
        scene = self.scene
        Q, sigma = self.history.Q[step], self.history.sigma[step]
        sliding = min(scene.friction_force, scene.contact.f * scene.contact.P)  # no stick zone from here on
        if abs(Q) >= sliding:
            raise GrossSlipError(step, Q, sigma, sliding)
        if isinstance(scene, MasingScene):
            exact = scene.increment(state, Q)
            outcome = _Outcome(exact.q, exact.ds, exact.dissipation, state, exact.zones, exact.delta_Q)
            return self._advanced(outcome, exact.slip, Q, sigma, turning=exact.turning)
        if step == 0 and (Q, sigma) == (state.Q, state.sigma):  # the starting state: nothing moves
            ds = np.zeros(state.slip.size)
            return _Outcome(scene.g_stuck(Q, sigma) - scene.G @ state.slip, ds, 0.0, state)
        guess = None if self.guess is None else self.guess(step)
        if guess is None:  # the last increment's directions
            guess = np.sign(state.slip - state.episode_start).astype(np.int8)
        increment = solve_increment(scene.G, scene.g_stuck(Q, sigma), scene.limit, state.slip, guess)
        if self.observe is not None:
            self.observe(step, increment.ds)
        outcome = _Outcome(increment.g, increment.ds, scene.dissipation(increment.ds), state)
        return self._advanced(outcome, increment.slip, Q, sigma)

    def _advanced(self, outcome, slip, Q, sigma, **memory):
        """`outcome`, whose state is the one before it, with the state it leaves: `slip` [m] under `Q`, `sigma`."""
        state, ds, dissipation = outcome.state, outcome.ds, outcome.dissipation
        tally = state.tally
        if tally.number:
            tally = tally.add(dissipation, self.scene.dissipation_density(ds), slip)
        new = state.advance(Q, sigma, slip, ds)
        return replace(outcome, state=replace(new, tally=tally, dissipated=state.dissipated + dissipation, **memory))

    def _repeats(self, previous, state, step):
        """Number of whole cycles from `step` that repeat the complete cycle `previous` bit for bit.

        They must follow `previous` directly, start from its starting state, have its loads
        and its number of steps, and the last of them must end where a new stretch begins.
        """
        if previous is None or not state.repeats(previous.before):
            return 0
        length = len(previous.outcomes)
        if previous.first + length != step:
            return 0
        n, cycle = len(self.history), self.cycle
        later, earlier = slice(step, n), slice(step - length, n - length)
        same = (
            (self.history.Q[later] == self.history.Q[earlier])
            & (self.history.sigma[later] == self.history.sigma[earlier])
            & (cycle[later] == cycle[earlier] + 1)
        )
        copies = (same.size if same.all() else int(np.argmin(same))) // length
        stop = step + copies * length
        if copies and stop < n and cycle[stop] == cycle[stop - 1]:
            copies -= 1  # the last one goes on beyond the steps of `previous`
        return copies

    def _copy(self, previous, step, copies):
        """Copy the cycle `previous` over `copies` cycles from `step`; the state after the last copy.

        The last copy's row is left to be closed as the cycle in progress.
        """
        length = len(previous.outcomes)
        last = previous.outcomes[-1].state
        first = int(self.cycle[step])
        self.cycles.extend((number, last.tally, True) for number in range(first, first + copies - 1))
        rows = self.row[step : step + copies * length]
        for offset in np.flatnonzero(rows >= 0):
            self._record(step + offset, previous.outcomes[offset % length])
        per_step = np.array([outcome.dissipation for outcome in previous.outcomes])
        # summed step by step, in order, as solving the cycles would: np.cumsum adds sequentially
        dissipated = np.cumsum(np.concatenate([[last.dissipated], np.tile(per_step, copies)]))[-1]
        return replace(last, tally=replace(last.tally, number=first + copies - 1), dissipated=float(dissipated))

    def _record(self, step, outcome):
        k = self.row[step]
        if k < 0:
            return
        state, scene = outcome.state, self.scene
        self.fields["q"][k] = scene.traction(outcome.g, outcome.ds)
        self.fields["slip"][k] = state.slip
        self.fields["stick"][k] = outcome.ds == 0
        self.fields["dissipation"][k] = outcome.dissipation
        exact = outcome.zones is not None
        end = located_end if isinstance(scene, GalerkinScene) else extrapolated_end
        self.zones[k] = outcome.zones if exact else stick_zones(scene.t, state.slip - state.episode_start, end)
        self.fields["delta_Q"][k] = outcome.delta_Q if exact else scene.delta_Q(state.slip)
        self.fields["delta_sigma"][k] = 0.0 if exact else scene.delta_sigma(state.slip)  # even slip: zero

    def data(self, state):
        """The arrays of the result (names from `fretting.results.variables.VARIABLES`) of a run that ended in `state`."""
        scene, history, steps = self.scene, self.history, self.steps
        data = self.fields | _zone_ends(scene, self.zones)
        if history.cycle is not None:
            data["cycle"] = history.cycle[steps]
            data |= _cycle_rows(self.cycles, scene.x.size)
        tally = state.tally
        return (
            data
            | {
                "Q": history.Q[steps],
                "sigma": history.sigma[steps],
                "p": scene.contact.pressure(scene.x),
                "x": scene.x,
                "step": steps,
                "vertex_step": history.vertex_step,
                "state_Q": state.Q,
                "state_sigma": state.sigma,
                "state_slip": state.slip,
                "state_episode_start": state.episode_start,
                "state_cycle": tally.number,
                "state_cycle_dissipation": tally.dissipation,
                "state_w": tally.w,
                "state_slip_min": tally.slip_min,
                "state_slip_max": tally.slip_max,
                "total_dissipation": state.dissipated,
            }
            | ({} if state.theta is None else {"theta": state.theta[::-1]})
            | ({} if state.turning is None else {"state_turning": np.array(state.turning, dtype=float)})
        )


def _cycle_rows(cycles, N):
    """Per-cycle variables from the ``(number, tally, repeated)`` of every cycle of a run.

    Copied cycles share their tally, so each distinct tally is turned into rows once.
    """
    numbers = np.array([number for number, _, _ in cycles], dtype=np.int64)
    repeated = np.array([copy for _, _, copy in cycles], dtype=bool)
    tallies = [tally for _, tally, _ in cycles]
    new = np.ones(len(tallies), dtype=bool)
    new[1:] = [later is not earlier for earlier, later in itertools.pairwise(tallies)]
    distinct = [tally for tally, first in zip(tallies, new, strict=True) if first]
    copies = np.diff(np.append(np.flatnonzero(new), len(tallies)))

    def rows(values, dtype, width):
        return np.repeat(np.array(values, dtype=dtype).reshape(len(distinct), width), copies, axis=0)

    return {
        "cycle_number": numbers,
        "cycle_dissipation": rows([t.dissipation for t in distinct], float, 1)[:, 0],
        "cycle_copied": repeated,
        "w": rows([t.w for t in distinct], np.float32, N),
        "slip_amplitude": rows([t.slip_amplitude for t in distinct], np.float32, N),
    }


def _zone_ends(scene, zones):
    """`stick_start` and `stick_end` [m] from per-step lists of normalised stick intervals."""
    ends = np.full((len(zones), max((len(z) for z in zones), default=0), 2), np.nan)
    for k, z in enumerate(zones):
        ends[k, : len(z)] = z
    ends = scene.contact.centre + scene.contact.a * ends
    return {"stick_start": ends[..., 0], "stick_end": ends[..., 1]}


def stick_zones(t, ds, end=extrapolated_end):
    """Stick intervals ``(start, end)`` in normalised position, from the episode slip `ds`.

    `ds` is each node's slip since its current episode of slip in one direction began, zero
    where the node stuck in the last increment. Near a stick/slip boundary it grows like
    ``d^(3/2)`` with the distance ``d`` (eq 19; Masing for reversed zones), so ``|ds|^(2/3)`` is
    extrapolated linearly by `end`: `extrapolated_end`, from the two nearest slipping nodes (0.05
    to 0.1 of the node spacing at the centre on the closed forms, benchmarks/accuracy_vs_nodes.py),
    or on a Galerkin mesh `fretting.models.galerkin.located_end`. A run of stuck nodes that
    reaches the end of the grid ends at the contact edge.

    One interval per run of stuck nodes, in order: each lies between the slipping nodes around
    its run and holds the run's middle, so ``start <= end`` and intervals do not overlap.
    """
    stuck = ds == 0
    edges = np.flatnonzero(np.diff(np.concatenate([[0], stuck.astype(np.int8), [0]])))
    runs = edges.reshape(-1, 2)  # [first stuck node, one past the last]
    return [_zone(t, ds, first, last - 1, end) for first, last in runs]


def _zone(t, ds, first, last, end):
    """Stick interval of the run of stuck nodes `first` .. `last`."""
    middle = (t[first] + t[last]) / 2
    return _boundary(t, ds, first, -1, middle, end), _boundary(t, ds, last, +1, middle, end)


def _boundary(t, ds, inner, side, middle, end):
    """Stick/slip boundary beyond the stuck node `inner` on `side` (-1 below, +1 above).

    The discrete stick zone may overshoot the true one by part of a node spacing, so the
    estimate may lie up to one spacing inside the last stuck node, but never past `middle`, the
    middle of the run of stuck nodes, nor beyond the first slipping node. The bound at `middle`
    keeps the two ends of a zone ordered where the d^(3/2) law fails at the node scale: a stick
    zone narrower than a spacing between slip zones of opposite directions, whose episode slips
    cross zero nearly linearly, so that each side's extrapolation overshoots past the other's.
    """
    outer = inner + side
    if outer < 0 or outer >= t.size:
        return float(side)
    estimate = end(t, ds, outer, outer + side)
    if estimate is None:
        return float((t[inner] + t[outer]) / 2)
    deepest = t[inner] - side * min(abs(t[outer] - t[inner]), abs(t[inner] - middle))
    return float(np.clip(estimate, *sorted((deepest, t[outer]))))


def _attributes(scene, rtol):
    contact = scene.contact
    attributes = {
        "a": contact.a,
        "p0": contact.p0,
        "E_star": contact.E_star,
        "f": contact.f,
        "P": contact.P,
        "centre": contact.centre,
        "profile": repr(contact.profile),
        "nodes": scene.x.size,
    }
    if isinstance(scene, MasingScene):
        return attributes | {"model": MASING_MODEL}
    if isinstance(scene, GalerkinScene):
        return attributes | {"model": f"{MODEL}, {GALERKIN}"} | ({} if rtol is None else {"rtol": rtol})
    return attributes | {"model": f"{MODEL}, {COLLOCATION}"}
