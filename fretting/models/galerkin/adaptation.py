"""The Galerkin mesh adapted to a history: `adapted_model`.

The passes run the history on a mesh with the engine's own loop, which the engine hands in as
``run(model, history, state, observe=..., guess=..., tally=False)`` (`fretting.engine.follow.follow`),
so that the adaptation lives with its model and imports nothing of the engine.

Runs the history's turning points (`History.turning_points`, from the contact just formed), each
curved stretch between them cut where its direction has turned by `MAX_TURN`, on a mesh graded
toward the edges; refines every element that `fretting.models.galerkin.mesh.element_targets` finds too
coarse at any of them, and runs them again until no element is, or until a refinement adds
fewer than `SETTLED` of the nodes. The other steps are not run:
along a proportional stretch each node slips one way only, so its dissipation is
``f p |s_end - s_start|`` and depends on the states at the turning points alone, and the
boundaries of the steps between lie in the slip zones of the increment from one turning point
to the next, which `element_targets` fills with elements small enough to locate them. Along a
curved stretch the loads of the steps between lie off the straight increment and their slip
zones reach where it sticks; cut into pieces that turn by less than `MAX_TURN`, the stretch is
nearly proportional again. An edge element whose edge node a load change leaves stuck within its
limit hides the zone that change slips at the edge, and is bisected (`_unseen_edges`). Under ``Q``
alone or ``sigma`` alone on a symmetric profile the mesh is kept symmetric, as the solution is. A
history that reaches gross slip is adapted to the steps before it.

Each pass, of either stage, starts the active set at a turning point from the slip directions the
pass before found there (`_guess`), which the answer does not depend on and which saves most of
the releases of the passes after the first (benchmarks/adaptation_passes.py).
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from fretting.errors import GrossSlipError, SolverError
from fretting.models.galerkin.mesh import (
    BOUNDARY_GRADING,
    BOUNDARY_SPAN,
    ENERGY_GRADING,
    ENERGY_SPAN,
    LEVELS_PER_PASS,
    MIN_SIZE,
    boundaries,
    element_targets,
    initial_theta,
    refine,
    tightened,
)
from fretting.models.solver import ROUNDING, held_by_allowance
from fretting.models.state import State

if TYPE_CHECKING:
    pass

__all__ = [
    "END_TURN",
    "MAX_TURN",
    "REFINEMENTS",
    "RESLIP",
    "SAMPLE_TURNS",
    "SETTLED",
    "MeshTooLarge",
    "adapted_model",
    "refined_for",
    "remapped",
]

#: Refinements of the mesh before `adapted_model` gives up: each at least halves an element, and 60
#: halvings take pi below 1e-17.
REFINEMENTS = 60

#: A refinement of the energy stage (`adapted_model`) that adds fewer nodes than this fraction of
#: the mesh ends it, with no pass on the mesh it gives: the pass after such a refinement adds
#: little or nothing (`python benchmarks/adaptation_passes.py --log` prints each pass), and the
#: stage of the ends refines that mesh again in any case.
SETTLED = 0.05

#: Turn [rad] of the load path's direction after which a curved stretch between turning points is
#: cut, the direction taken in the plane of ``Q / (pi a)`` and ``sigma / 4`` [Pa], the mean and the
#: slope of the fully stuck traction ``sqrt(1 - t^2) q_st = Q / (pi a) + sigma t / 4`` of eqs (9)
#: and (20). A quarter of a 90-degree out-of-phase cycle is then run as two increments, which
#: resolves the energy per cycle (results/speed_vs_error.md).
MAX_TURN = np.pi / 4

#: The turn between cuts of the pass that locates the stick ends (`adapted_model`'s second
#: stage): the steps between two cuts then stick where the increment from one cut to the next
#: sticks, within the elements that locate their ends; with `MAX_TURN` the stick ends of
#: elliptical paths fell outside them (benchmarks/trajectories.py, the ``ellipse_*`` histories).
END_TURN = np.pi / 16


class MeshTooLarge(Exception):
    """The adapted mesh would exceed its bound of nodes: raised as soon as that is certain.

    Attributes: ``nodes`` it would need at least, ``step`` of the turning points where that
    became certain, ``model`` the `GalerkinModel` of the last mesh within the bound (that of the
    pass under way), ``ends`` the number of increments of the run where it is the second stage of
    `adapted_model` that passes its bound of work (None otherwise): ``model`` then resolves the
    energy to rtol, and the stick ends to about ``ENERGY_SPAN rtol a`` only; or, with
    ``change``, the largest relative change of a cycle's energy from the mesh before to
    ``model``, which locates the stick ends but whose energy `_energy_checked` had not settled.
    """

    def __init__(self, nodes, step, model, ends=None, change=None):
        if ends is not None:
            task = "locates the stick ends of the recorded steps" if change is None else "settles the energy per cycle"
            message = (
                f"the mesh that {task} would need {nodes} nodes, "
                f"{nodes**2 * ends:.2g} nodes squared times the run's {ends} increments"
            )
        else:
            message = f"the adapted mesh would need {nodes} nodes or more (at step {step} of the turning points)"
        super().__init__(message)
        self.nodes, self.step, self.model, self.ends, self.change = nodes, step, model, ends, change


def adapted_model(spec, contact, history, run, max_nodes=None, recorded=None, max_work=None):
    """The `GalerkinModel` (built once, for the run to use) whose mesh ``theta`` [rad] resolves the
    stick and slip zones of `history` to the ``rtol`` of the unresolved `spec` (a `Mesh`), its
    passes run by the engine's loop `run` (module docstring).

    Two stages. The energy: passes over the turning points (`MAX_TURN`) refine every element
    that `fretting.models.galerkin.element_targets` finds too coarse, with elements of
    ``ENERGY_SPAN rtol a`` in the slip zones, until none is or a refinement adds fewer than
    `SETTLED` of the nodes. The ends (`_located`): one pass on
    that mesh over the turning points cut finer (`END_TURN`) refines, in one go, the elements
    that hold the stick ends of the steps in `recorded` (step numbers; None: every step), or that
    those ends sweep, to ``BOUNDARY_SPAN rtol a``; the zones are already located, so no pass on
    the finer mesh is needed, except where an increment slips again by less than ``RESLIP rtol``
    of the slip locked in: passes on the finer meshes then refine until each cycle's energy
    settles to `rtol` (`_energy_checked`).

    A history of more than `SAMPLE_TURNS` turning points is adapted to a sample of them: the
    first `SAMPLE_TURNS`, then twice as many from the mesh found, and so on, until a doubling
    adds no node or the sample is the whole history; the spec says which (`Mesh.sample`, the
    dataset's ``model_sample``). Each sample's passes start from the last sample's mesh, so
    none is thrown away.

    Raises `MeshTooLarge` as soon as a refinement of the energy stage is certain to give more than
    `max_nodes` nodes (the targets only shrink within a pass, so the mesh they ask for only grows:
    `_bisected_size`), or where the ends' mesh of ``N`` nodes would make the run's work
    ``N^2 x increments`` exceed `max_work` (an increment costs about ``N^2``: the products with the
    stiffness of each release of the active set), with the model of the energy stage, or the
    mesh before it where it is a refinement of `_energy_checked`.
    """
    fP = contact.f * contact.P
    sliding = history.first_step(lambda Q, sigma: np.abs(Q) >= fP)
    if sliding is not None:  # the run will stop there: adapt to the steps before
        history = history[: max(sliding, 1)]
    steps = history.turning_steps(MAX_TURN, _units(contact))
    turning = history.turning_points(MAX_TURN, _units(contact))
    mirrored = contact.profile.SYMMETRIC and not all(history.largest_loads())
    adapt = _Adaptation(spec, contact, history, run, max_nodes, mirrored, max_work)
    size = min(SAMPLE_TURNS, len(turning))
    model = adapt(turning[:size], initial_theta())
    while size < len(turning):
        size = min(2 * size, len(turning))
        grown = adapt(turning[:size], model.theta)
        if np.array_equal(grown.theta, model.theta) and size < len(turning):
            sample = (
                f"adapted to the first {size} of the history's {len(turning)} turning points: the mesh "
                f"stopped growing from the first {size // 2}"
            )
            grown.spec = replace(grown.spec, sample=sample)
            return _located(grown, adapt, history[: steps[size - 1] + 1], recorded, _by_step(adapt, steps))
        model = grown
    return _located(model, adapt, history, recorded, _by_step(adapt, steps))


def _by_step(adapt, steps):
    """The slip directions (and nodes [m]) of `adapt`'s last pass, by the step of the history of
    each of its turning points, at the history's `steps`."""
    return {int(steps[turn]): found for turn, found in adapt.directions.items()}


def _push(model, turning, step):
    """The change of `model`'s fully stuck traction (eqs 9 and 20, in its measure) that the increment
    to `turning`'s `step` makes: from the loads of the step before, or at step 0 from the contact
    just formed, where the adaptation's passes start (`follow` reaches non-zero first loads in one
    increment)."""
    after = model.g_stuck(turning.Q[step], turning.sigma[step])
    return after if step == 0 else after - model.g_stuck(turning.Q[step - 1], turning.sigma[step - 1])


def _unseen_edges(model, outcome, turning, step):
    """Targets [rad] of `model`'s elements after the increment to `turning`'s `step`:
    ``2^-LEVELS_PER_PASS`` of an edge element whose edge node the increment left stuck within its
    friction limit under a load change (`_push`); ``inf`` elsewhere; None where neither is.

    Where the pressure vanishes at the edges (`fretting.physics.profiles.Profile.VANISHING_EDGES`)
    the fully stuck traction there is unbounded (eqs 9 and 20), so any load change slips a zone at
    each edge: one about ``A a / 4`` wide for a reversal of ``Q`` by ``A f P`` at an edge that
    slipped. The edge node slips once its element is about as narrow as the zone; until then the
    zone and its energy are unseen. An edge node over its limit that sticks is held there by the
    solver's rounding allowance (`fretting.models.solver.held_by_allowance`), which no smaller
    element undoes.
    """
    edges = np.array([-1, 0])  # nodes in ascending x: theta = 0 (x = a) is the last
    if outcome.ds[edges].all() or not model.contact.profile.VANISHING_EDGES:
        return None
    h = np.diff(model.theta)[[0, -1]]  # their elements
    unseen = (
        (outcome.ds[edges] == 0)
        & (_push(model, turning, step)[edges] != 0)
        & (np.abs(outcome.g[edges]) <= model.limit[edges])
        & (h > MIN_SIZE)
    )
    if not unseen.any():
        return None
    targets = np.full(model.theta.size - 1, np.inf)
    targets[[0, -1]] = np.where(unseen, np.maximum(h / 2**LEVELS_PER_PASS, MIN_SIZE), np.inf)
    return targets


def _units(contact):
    """Units [N/m, Pa] of Q and sigma in which the load path's turns are measured (`MAX_TURN`)."""
    return np.pi * contact.a, 4.0


def _located(model, adapt, history, recorded, by_step):
    """`model`'s mesh refined so that the stick ends of the steps `recorded` of `history` are located
    (`adapted_model`, second stage), then until the energies agree (`_energy_checked`); `model`
    itself where nothing needs refining. Its pass starts from the slip directions `by_step` (step of
    `history`: directions, nodes [m]) of the energy stage's last pass where a turning point is one of
    those. Either way its spec, or that of the `MeshTooLarge`'s model
    where the refinement passes its bound, says where increments fall below the solver's floor
    (`_below_floor_said`)."""
    units = _units(model.contact)
    steps = history.turning_steps(END_TURN, units)
    turning = history.turning_points(END_TURN, units)
    spans = _spans(steps, recorded)
    targets = np.full(model.theta.size - 1, np.inf)

    def observe(step, outcome):
        found = element_targets(model.theta, outcome.ds, adapt.rtol, model.breakpoints, *spans[step], levels=None)
        np.minimum(targets, found, out=targets)

    known = {turn: by_step[step] for turn, step in enumerate(steps.tolist()) if step in by_step}
    before = _Energies.of(model, turning, adapt.run, observe, with_ends=False, known=known)
    theta = adapt.refined(model.theta, targets)
    try:
        if not np.array_equal(theta, model.theta):
            adapt.check_work(theta, model, len(steps) - 1)
            located = _finer(model, theta)
            if np.any(before.checkable(adapt.rtol) & (before.reslip < RESLIP * adapt.rtol)):
                located = _energy_checked(located, adapt, turning, before)
            model = located
    except MeshTooLarge as error:  # the mesh it runs instead says the floor as well
        error.model = _below_floor_said(error.model, before, adapt.rtol)
        raise
    return _below_floor_said(model, before, adapt.rtol)


def _finer(model, theta):
    """The `GalerkinModel` on `theta` [rad], refined from `model`'s mesh, keeping its ``rtol`` and sample."""
    return replace(model.spec, theta=theta, fallback=None).build(model.contact, previous=model)


def _below_floor_said(model, energies, rtol):
    """`model`, its spec's ``fallback`` saying how many increments of `energies` fall below the
    solver's floor: those that slip again by too little for any mesh to hold their energy to `rtol`
    (`_Energies.below_floor`), and those whose load change the rounding allowance held stuck
    (`_Energies.held`), whose energy is lost."""
    notes = []
    if below := np.count_nonzero(energies.below_floor(rtol)):
        notes.append(
            f"the energy of {below} increment(s) between turning points that slip again by less than "
            f"{ROUNDING / rtol:.0e} of the slip locked in is left to the solver's rounding allowance, "
            f"not held to rtol = {rtol:g}"
        )
    if held := np.count_nonzero(energies.held):
        notes.append(
            f"{held} increment(s) between turning points take the traction over the friction limit by "
            f"less than the solver's rounding allowance ({ROUNDING:.0e} of the largest term of the "
            f"traction) and slip nowhere: what they would dissipate is lost"
        )
    if not notes:
        return model
    fallback = "; ".join(([] if model.spec.fallback is None else [model.spec.fallback]) + notes)
    model.spec = replace(model.spec, fallback=fallback)
    return model


#: `_energy_checked` runs where an increment slips, at the nodes that slipped before, by less than
#: ``RESLIP rtol`` of the slip locked in there: the load change that drives it is then within a few
#: times the mesh's traction error (about ``rtol f p0``, the ``traction_fp0`` column of
#: benchmarks/trajectories.py), which places the zone's end. The ``tiny_*`` histories of that
#: benchmark are of this kind; its other histories re-slip by far more and are not checked.
RESLIP = 10.0


class _Energies(NamedTuple):
    """A pass over the turning points on one mesh: per increment between them (row 0, the start:
    none), the energy [J/m] dissipated, its stick/slip boundaries [rad], the ratio of its slip
    to the slip locked in before, at the nodes that slip again [-] (`RESLIP`; ``inf`` where none
    does), and whether it slipped nowhere though its load change took the traction over the limit
    by less than the solver's rounding allowance (`fretting.models.solver.held_by_allowance`)."""

    energy: np.ndarray
    ends: list
    reslip: np.ndarray
    held: np.ndarray
    directions: dict

    @classmethod
    def of(cls, model, turning, run, observe=None, with_ends=True, known=None):
        """Run `turning` on `model` from the virgin state with the engine's loop `run`, the active
        set of each increment started from the slip directions `known` of a pass on a coarser mesh
        (`_guess`; None: from the increment before); ``observe(step, outcome)`` sees each increment
        too. Without `with_ends`, ``ends`` is left empty (the pass whose mesh is refined before any
        is needed)."""
        energy, ends, reslip = np.zeros(len(turning)), [()] * len(turning), np.full(len(turning), np.inf)
        held, directions = np.zeros(len(turning), dtype=bool), {}

        def watch(step, outcome):
            ds, before = outcome.ds, outcome.slip - outcome.ds  # exactly the slip before where ds = 0
            energy[step] = model.dissipation(ds)
            if not ds.any():
                held[step] = held_by_allowance(outcome.g, model.limit, _push(model, turning, step)).size > 0
            if with_ends:
                ends[step] = boundaries(model.theta, ds)
            directions[step] = np.sign(ds).astype(np.int8), model.x
            again = (ds != 0) & (before != 0)
            if again.any():
                reslip[step] = np.max(np.abs(ds[again])) / np.max(np.abs(before[again]))
            if observe is not None:
                observe(step, outcome)

        guess = None if known is None else _guess(known, model.x)
        run(model, turning, State.virgin(model), observe=watch, guess=guess, tally=False)
        return cls(energy, ends, reslip, held, directions)

    def below_floor(self, rtol):
        """The increments that re-slip by less than ``ROUNDING / rtol`` of the slip locked in
        (`RESLIP`): their driving load change is then within ``rtol`` of the solver's rounding
        allowance on the friction limit (`fretting.models.solver.ROUNDING`) on any mesh."""
        return self.reslip < ROUNDING / rtol

    def checkable(self, rtol):
        """The increments whose energy a finer mesh can settle to `rtol`: neither `below_floor` nor
        `held`, where the allowance, not the mesh, decides what they dissipate."""
        return ~self.below_floor(rtol) & ~self.held


def _energy_checked(model, adapt, turning, before):
    """`model`, its mesh refined at the boundaries of the increments whose energy still changes.

    `before` is the pass on the mesh `model` was refined from. The energy of each load cycle (of
    each stretch between two vertices where the history counts no cycles), and the energy from
    the start to each vertex, must change by less than ``rtol`` of itself from one mesh to the
    next (`_unsettled`); where one changes more, the elements holding the boundaries of its
    increments that changed most are bisected `LEVELS_PER_PASS` times (`tightened`) and the
    turning points run again. Increments below the solver's floor on either mesh
    (`_Energies.checkable`) are not held to it. A slip zone that a small load change drives on
    through slip locked in before can end an element off on the mesh that locates the ends: its
    energy then errs in proportion to that element, not to its ``5/2`` power
    (`fretting.models.galerkin.mesh.BOUNDARY_ERROR`), and such zones can carry most of a cycle's
    energy (a ratchet: benchmarks/small_loops.py).
    """
    for _ in range(REFINEMENTS):
        now = _Energies.of(model, turning, adapt.run, known=before.directions)
        checkable = now.checkable(adapt.rtol) & before.checkable(adapt.rtol)
        change = np.where(checkable, np.abs(now.energy - before.energy), 0.0)
        unsettled, worst = _unsettled(turning, now.energy, change, adapt.rtol)
        if unsettled.size == 0:
            return model
        theta = adapt.refined(model.theta, tightened(model.theta, np.concatenate([now.ends[i] for i in unsettled])))
        if np.array_equal(theta, model.theta):  # its elements there are as small as any (MIN_SIZE)
            reason = (
                f"the energy per cycle still changed by up to {worst:.1e} of itself (rtol = {adapt.rtol:g}) "
                f"where the elements holding its boundaries can be bisected no further"
            )
            model.spec = replace(model.spec, fallback=reason)
            return model
        adapt.check_work(theta, model, len(turning) - 1, worst)
        model, before = _finer(model, theta), now
    raise SolverError(f"the energy still changed after {REFINEMENTS} refinements ({model.theta.size} nodes)")


def _unsettled(turning, energy, change, rtol):
    """The increments (rows of `turning`) whose boundaries to refine, and the largest relative
    change of a group [-].

    A group is a load cycle (a stretch between two vertices where the history counts no cycles),
    or the increments from the start to the first vertex where the energy so far changed by more
    than ``rtol`` of itself; in each group whose summed `change` [J/m] exceeds ``rtol`` of its
    summed `energy` [J/m], the increments that changed by its mean change or more.
    """
    rows = np.arange(1, len(turning))
    if turning.cycle is not None:
        label = turning.cycle[1:]
    else:  # the stretch each increment ends
        label = np.searchsorted(turning.vertex_step, rows)
    _, group = np.unique(label, return_inverse=True)
    group = group.ravel()
    changed, dissipated = np.bincount(group, change[1:]), np.bincount(group, energy[1:])
    over = changed > rtol * dissipated
    picked = over[group] & (change[1:] >= (changed / np.bincount(group))[group])
    ratios = [_ratio(moved, total) for moved, total in zip(changed[over], dissipated[over], strict=True)]
    so_far_changed, so_far = np.cumsum(change), np.cumsum(energy)
    vertices = turning.vertex_step[turning.vertex_step > 0]
    failing = vertices[so_far_changed[vertices] > rtol * so_far[vertices]]
    if failing.size:
        vertex = failing[0]
        picked |= (rows <= vertex) & (change[1:] >= so_far_changed[vertex] / vertex)
        ratios.append(_ratio(so_far_changed[vertex], so_far[vertex]))
    return rows[picked], max(ratios, default=0.0)


def _ratio(change, energy):
    """``change / energy`` [-], infinite where nothing was dissipated."""
    return change / energy if energy > 0 else np.inf


#: Turning points of a history beyond which the mesh is adapted to a sample of them (`adapted_model`):
#: a pass costs in proportion to the turning points it runs, and the zones of a long spectrum's
#: later cycles repeat those of its first.
SAMPLE_TURNS = 256


class _Adaptation:
    """The energy passes of `adapted_model` (its first stage, elements of ``ENERGY_SPAN rtol a``) over
    the turning points of (a part of) one history, and the bounds of both stages: `max_nodes` of the
    energy's mesh, `max_work` of the run's ``N^2 x increments`` on the ends' mesh."""

    def __init__(self, spec, contact, history, run, max_nodes, mirrored, max_work=None):
        self.spec, self.contact, self.history, self.follow, self.rtol = spec, contact, history, run, spec.rtol
        self.max_nodes, self.mirrored, self.max_work = max_nodes, mirrored, max_work
        self.increments = len(history) - 1  # the run's, up to gross slip
        self.directions = {}  # of the last pass: turning point: (slip directions, nodes [m])

    def __call__(self, turning, theta):
        """The model whose mesh, refined from `theta` [rad], resolves the increments of `turning`."""
        rtol, max_nodes, directions, model = self.rtol, self.max_nodes, {}, None
        for _ in range(REFINEMENTS):
            model = replace(self.spec, theta=theta).build(self.contact, previous=model)
            targets, known, directions = np.full(theta.size - 1, np.inf), directions, {}

            def observe(step, outcome, model=model, targets=targets, found=directions):
                ds = outcome.ds
                np.minimum(
                    targets,
                    element_targets(model.theta, ds, rtol, model.breakpoints, ENERGY_SPAN, ENERGY_SPAN, ENERGY_GRADING),
                    out=targets,
                )
                if (edges := _unseen_edges(model, outcome, turning, step)) is not None:
                    np.minimum(targets, edges, out=targets)
                found[step] = np.sign(ds).astype(np.int8), model.x
                if max_nodes is not None and (size := _bisected_size(model.theta, targets)) > max_nodes:
                    raise MeshTooLarge(size, step, model)

            self.run(model, turning, State.virgin(model), observe=observe, guess=_guess(known, model.x), tally=False)
            self.directions = directions
            refined = self.refined(theta, targets)
            if np.array_equal(refined, theta):
                return model
            if max_nodes is not None and refined.size > max_nodes:
                raise MeshTooLarge(refined.size, len(turning) - 1, model)
            if refined.size < (1 + SETTLED) * theta.size:  # the pass on it would add next to nothing
                return replace(self.spec, theta=refined).build(self.contact, previous=model)
            theta = refined
        raise SolverError(f"the mesh still needed refining after {REFINEMENTS} refinements ({theta.size} nodes)")

    def run(self, model, turning, state, **options):
        """The engine's loop over `turning`, a `GrossSlipError` named by the first step of the history
        whose loads reached it, not by the step of `turning`."""
        try:
            return self.follow(model, turning, state, **options)
        except GrossSlipError as error:
            Q, sigma = error.Q, error.sigma
            at = self.history.first_step(lambda loads, tensions: (loads == Q) & (tensions == sigma))
            raise GrossSlipError(at, Q, sigma, error.limit) from None

    def check_work(self, theta, model, step, change=None):
        """Raise `MeshTooLarge` (with `model`, the mesh before, and `change`) if a run on `theta`
        would pass `max_work`."""
        if self.max_work is not None and theta.size**2 * self.increments > self.max_work:
            raise MeshTooLarge(theta.size, step, model, ends=self.increments, change=change)

    def refined(self, theta, targets):
        """`refine` of `theta` [rad] to `targets`, kept symmetric under Q alone or sigma alone."""
        refined = refine(theta, np.minimum(targets, targets[::-1]) if self.mirrored else targets)
        if self.mirrored:  # the zones are even or odd in x, and so is the mesh, exactly
            lower = refined[refined <= np.pi / 2]
            refined = np.concatenate([lower, np.pi - lower[::-1][int(lower[-1] == np.pi / 2) :]])
        return refined


def refined_for(contact, state, history, run):
    """The model and state to continue `state` along `history` with, on the state's mesh refined
    where the increments of `history` need it (run by the engine's loop `run`).

    The state's `Mesh` was adapted to ``rtol`` for the history it came from; a history that goes
    on with larger or other loads may need a finer one. The turning points of `history` (from
    `state`) are run as the adaptation runs them, the elements that `element_targets` finds too
    coarse are bisected, and the state is carried over to the new nodes (`remapped`: exact for
    the slip, which is P1 in ``theta``), until no element is.

    Returns
    -------
    model : GalerkinModel or None
        None where the state's mesh needs nothing more (the caller builds the state's model).
    state : State
    """
    spec = state.model
    turning = history.turning_points(MAX_TURN, _units(contact))
    model, refined = spec.build(contact), False
    for _ in range(REFINEMENTS):
        targets = np.full(model.theta.size - 1, np.inf)

        def observe(step, outcome, model=model, targets=targets):
            np.minimum(targets, element_targets(model.theta, outcome.ds, spec.rtol, model.breakpoints), out=targets)

        run(model, turning, state, observe=observe, tally=False)
        theta = refine(model.theta, targets)
        if np.array_equal(theta, model.theta):
            return (model if refined else None), state
        state = remapped(state, model.theta, theta)
        model, refined = state.model.build(contact, previous=model), True
    raise SolverError(f"the mesh still needed refining after {REFINEMENTS} refinements ({model.theta.size} nodes)")


def remapped(state, theta, finer):
    """`state` on the mesh `finer` [rad], which `refine` made from `theta` by bisection.

    Every nodal field is interpolated linearly in ``theta``: exactly for the slip and the
    episode starts, which are P1 in ``theta`` and whose nodes `finer` keeps; the tally of the
    cycle in progress (its energy density, slip range and peaks) is interpolated as well, an
    approximation at the new nodes only.
    """

    def onto(values):  # per-node arrays are in ascending x, i.e. descending theta
        return np.interp(finer, theta, np.asarray(values)[::-1])[::-1]

    fields = ("w", "slip_min", "slip_max", "sigma_xx_peak", "q_peak", "sigma_xx_q_peak")
    tally = replace(state.tally, **{name: onto(getattr(state.tally, name)) for name in fields})
    model = replace(state.model, theta=finer)
    return replace(state, slip=onto(state.slip), episode_start=onto(state.episode_start), tally=tally, model=model)


def _spans(steps, recorded):
    """The spans and the grading (``swept``, ``end``, ``grading`` of `element_targets`) of each increment
    between the turning points at the history's `steps`, shape (len(steps), 3): `BOUNDARY_SPAN` where a
    step strictly inside the increment (``swept``), or its last step (``end``), is in `recorded` (None:
    all are), else `ENERGY_SPAN`; `BOUNDARY_GRADING` where either is (the traction of those steps is
    read next to their stick ends), else `ENERGY_GRADING`. Row 0, the starting state, is never solved."""
    if recorded is None:
        return np.tile([BOUNDARY_SPAN, BOUNDARY_SPAN, BOUNDARY_GRADING], (steps.size, 1))
    recorded = np.asarray(recorded, dtype=np.int64)
    marks = np.zeros(int(steps[-1]) + 2, dtype=np.int64)
    marks[recorded[recorded <= steps[-1]] + 1] = 1  # a run stopped by gross slip records no later step
    counted = np.cumsum(marks)  # counted[s + 1]: recorded steps up to s
    first = np.concatenate([[0], steps[:-1] + 1])  # one past the turning point before
    inside = counted[steps] - counted[first]  # steps first .. steps - 1
    last = counted[steps + 1] - counted[steps]
    located = np.stack([inside, last], axis=1) > 0
    spans = np.where(located, BOUNDARY_SPAN, ENERGY_SPAN)
    return np.column_stack([spans, np.where(located.any(axis=1), BOUNDARY_GRADING, ENERGY_GRADING)])


def _bisected_size(theta, targets):
    """Nodes of `theta` [rad] once every element is bisected down to its target size [rad]: a lower
    bound of `refine`'s, which grades the mesh after (so a bound passed here is passed for certain)."""
    halvings = np.ceil(np.log2(np.maximum(np.diff(theta) / targets, 1.0)))
    return 1 + int(np.sum(2.0**halvings))


def _guess(known, at):
    """The ``guess(step)`` of the engine's loop for a pass on the mesh of nodes `at` [m]: the slip
    directions `known` (step: directions, nodes [m]) that a pass on a coarser mesh found at that
    step, interpolated (`_interpolated_directions`); None at steps it did not solve."""

    def guess(step):
        return _interpolated_directions(*known[step], at) if step in known else None

    return guess


def _interpolated_directions(directions, x, at):
    """Slip directions (+1, -1, 0) at the points `at` [m] from those at the nodes `x` [m] of a coarser mesh.

    A start for the solver only (the ``guess`` of `Model.increment`): a node between two of `x`
    that differ in direction takes the direction of the linear interpolation, zero between
    opposite ones.
    """
    return np.sign(np.interp(at, x, directions)).astype(np.int8)
