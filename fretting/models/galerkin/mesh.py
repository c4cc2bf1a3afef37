"""Meshes in ``theta``: the element sizes a history's zones ask for (`element_targets`) and refinement (`refine`).

sizes; `refine` bisects (old nodes stay nodes, so a P1 slip field carries over exactly) and
grades neighbours to a size ratio of at most 2. A driver (`fretting.models.galerkin.adaptation.adapted_model`)
runs the turning points of its history (curved stretches between them cut where the path has
turned by `fretting.models.galerkin.adaptation.MAX_TURN`), reduces the targets of every increment with
``np.minimum``, refines, and runs again until `refine` returns the same mesh, starting from
`initial_theta` (pass `GalerkinModel.breakpoints` on: the profile's, where the pressure has a
singular derivative). ``rtol`` is the relative accuracy asked of the energy dissipated in each
"""

from __future__ import annotations

import numpy as np

from fretting.models.method4 import extrapolated_end

__all__ = [
    "DEFAULT_RTOL",
    "boundaries",
    "boundary_fraction",
    "element_targets",
    "initial_theta",
    "located_end",
    "refine",
    "settled",
    "tightened",
    "uniform_theta",
    "zone_fraction",
]

#: Relative accuracy asked by default of the energy dissipated in an increment (`element_targets`):
#: the error it leaves on the cycles' energy, docs/validation/galerkin-constants.md#default_rtol; against
#: every closed form, benchmarks/galerkin_convergence.py.
DEFAULT_RTOL = 1e-4
#: Elements of the initial uniform mesh, the coarsest any zone gets. Close to sliding (Q/fP up to
#: 0.999999) half as many give the same slip and, at Q/fP = 0.95, a less accurate traction
#: (docs/validation/galerkin-constants.md#initial_elements).
INITIAL_ELEMENTS = 64
#: Size [rad] of the edge elements of the initial mesh: edge slip zones down to about this
#: width in theta (5e-9 a in x) make the edge node slip, and are then refined.
EDGE_SIZE = 1e-4
#: Smallest element size [rad] that `element_targets` asks for, so that refinement ends even
#: where a zone never resolves.
MIN_SIZE = 1e-7
#: Smallest element [rad] of any mesh a model is built on. In an edge element narrower than
#: ``sqrt(2 eps)`` (2.1e-8 rad) ``cos(theta)`` rounds to 1 at every quadrature point, so the pressure
#: and the edge node's friction limit vanish and its traction is 0/0; `refine` bisects down to
#: ``MIN_SIZE / 2`` at least, and a quarter keeps a margin above the rounding.
SMALLEST_ELEMENT = MIN_SIZE / 4
#: Elements across every stick or slip zone, at least: half as many leave the slip of small zones
#: (Q/fP = 0.05, 0.2) less accurate (docs/validation/galerkin-constants.md#zone_elements).
ZONE_ELEMENTS = 10
#: Relative energy error assumed left inside zones of ``ZONE_ELEMENTS`` elements, which falls like
#: the square of the element size; a bound: the cycles' energy is as accurate with zones held at
#: ``ZONE_ELEMENTS`` elements at the page's smaller rtol (docs/validation/galerkin-constants.md#zone_error).
ZONE_ERROR = 1e-4
#: The worst relative energy error of an increment is about ``BOUNDARY_ERROR (size / w)^(5/2)``
#: with ``size`` the element holding a stick/slip boundary and ``w`` the narrower zone beside
#: it. Fitted with a margin to the worst energy per cycle over amplitudes Q*/fP in [0.05, 0.95];
#: the margin left, beside a quarter of it: docs/validation/galerkin-constants.md#boundary_error.
BOUNDARY_ERROR = 40.0
#: Elements holding a boundary, and those of the slip zones that the boundaries of the steps
#: between two turning points sweep, span at most ``BOUNDARY_SPAN rtol a`` in x: `located_end`
#: places most ends to a tenth of their element, but a slip zone that grows into slip locked in
#: before can leave its end up to about one element off, so the element itself is held to the
#: accuracy asked of the ends, ``1e-3 a`` at the default rtol (benchmarks/trajectories.py).
BOUNDARY_SPAN = 10.0
#: The span, in units of ``rtol a``, of those elements in the mesh adapted to the energy (the
#: first stage of `fretting.models.galerkin.adaptation.adapted_model`), and where no step between two
#: turning points is recorded: the energy of the histories of benchmarks/trajectories.py is then
#: within 1e-4, their located ends within about ``ENERGY_SPAN rtol a``.
ENERGY_SPAN = 50.0
#: Elements at a pressure breakpoint span this fraction of ``BOUNDARY_SPAN rtol a``: with a
#: larger span the traction's ``d ln d`` there errs most at the node nearest the end of a rounded
#: flat (tests/models/test_galerkin.py::test_rounded_flat).
BREAKPOINT_SPAN = 0.5
#: Around a boundary of an increment whose steps are recorded, elements grow at most like this
#: fraction of their distance from it, so that the square-root kink of the traction is seen through
#: gently graded elements: the nodal traction (`fretting.models.galerkin.quadrature.recovery`, a
#: quadratic through three hat means) cannot follow the kink across elements of a size near their
#: distance from it, and in the stick zone next to an end it errs less the smaller this fraction,
#: for more nodes: the traction and the nodes at other values,
#: docs/validation/galerkin-constants.md#boundary_grading.
BOUNDARY_GRADING = 0.25
#: The same fraction where only the energy is asked for (the mesh adapted to the energy, and the
#: increments none of whose steps is recorded): the hat moments, and so the slip and the energy,
#: are right through coarser grading than the traction read from them (the slip at either fraction,
#: docs/validation/galerkin-constants.md#boundary_grading; the energy, docs/validation/speed-ratio.md).
ENERGY_GRADING = 0.5
#: Nodes slipping one way beyond a stick/slip boundary that `located_end` needs before it also
#: extrapolates from the second and third: with four, both lie inside the zone, off its far end.
RESOLVED_NODES = 4
#: A zone seen at fewer nodes has an unreliable width: its elements are only bisected.
MIN_ZONE_NODES = 3
#: Bisections asked of an element in one pass at most (a factor 4 in size).
LEVELS_PER_PASS = 2
#: Slip increment, as a fraction of the increment's largest, at or below which a node counts as stuck
#: where the zones of an increment are read (`settled`): the rounding of the solver's slips is about
#: 1e-16 of them, and a slip zone whose slip is this small lies within about ``CHATTER^(2/3)`` of its
#: width from its end (eq 19), far inside the accuracy asked of any end.
CHATTER = 1e-10
#: Largest size ratio of neighbouring elements.
GRADING = 2.0
#: Rounding allowance on that ratio: bisected elements are halves up to rounding.
GRADING_SLACK = 1e-9


def uniform_theta(M):
    """``M`` equal elements on ``[0, pi]`` [rad]; the last node is exactly ``pi``."""
    if not isinstance(M, (int, np.integer)) or M < 2:
        raise ValueError(f"M must be an integer >= 2, found {M!r}")
    theta = np.linspace(0.0, np.pi, M + 1)
    theta[-1] = np.pi
    return theta


def initial_theta(M=None):
    """Uniform mesh of `M` elements whose edge elements are bisected down to `EDGE_SIZE` [rad].

    A slip zone much narrower than the edge element is invisible (the edge node sticks), so
    the mesh starts graded toward the edges: slip zones down to ``~ EDGE_SIZE`` in ``theta``,
    ``a EDGE_SIZE^2 / 2`` in ``x``, are seen and then refined by `element_targets`.
    """
    theta = uniform_theta(INITIAL_ELEMENTS if M is None else M)
    while theta[1] > EDGE_SIZE:
        theta = np.concatenate([[0.0, theta[1] / 2], theta[1:-1], [(theta[-2] + np.pi) / 2, np.pi]])
        theta = _graded(theta)
    return theta


def element_targets(
    theta,
    ds,
    rtol=DEFAULT_RTOL,
    breakpoints=(),
    swept=BOUNDARY_SPAN,
    end=BOUNDARY_SPAN,
    grading=None,
    levels=LEVELS_PER_PASS,
):
    """Largest element sizes [rad] that resolve the stick and slip zones of an increment.

    The nodes' status (stuck: ``ds == 0``, slipping forward, slipping backward) splits
    ``[0, pi]`` into zones; each boundary is placed inside its element by `_boundary_position`.
    Asked for:

    - inside a zone of width ``w``: ``zone_fraction(rtol) w`` (`ZONE_ELEMENTS` elements or more),
      and inside a slip zone at most ``swept rtol a`` in x: the boundaries of the steps between
      two turning points sweep it;
    - the element holding a boundary: ``boundary_fraction(rtol) w`` of the narrower zone beside
      it (or of its distance to the nearest of `breakpoints`, where the pressure has a singular
      derivative), since the energy error a boundary leaves falls like ``(size / w)^(5/2)``, and at most
      ``end rtol a`` in x, the accuracy asked of the located ends;
    - around a boundary, `grading` times the distance from it;
    - at each of `breakpoints`, ``BREAKPOINT_SPAN BOUNDARY_SPAN rtol a`` in x, graded the same way, whatever
      the increment: the traction inherits the pressure's singular derivative there;
    - a zone seen at fewer than `MIN_ZONE_NODES` nodes (its width is a guess), or neighbours
      slipping in opposite directions (a stick zone hides between them): half the element.

    No element is asked to shrink by more than ``2^levels`` in one pass (None: no limit, where the
    zones are located already), so that the zones are located again on the finer mesh, nor below
    `MIN_SIZE`.

    Parameters
    ----------
    theta : ndarray, shape (M + 1,)
        The mesh [rad], ascending from 0 to pi.
    ds : ndarray, shape (M + 1,) or (steps, M + 1)
        Slip increment [m] from a `GalerkinModel` on `theta`, in the scene's order (ascending
        ``x``, i.e. descending ``theta``), exactly zero where a node stuck (as
        `fretting.models.solver.solve_increment` leaves it). Rows are reduced with ``np.minimum``.
    rtol : float
        Relative accuracy asked of the energy dissipated in each increment.
    breakpoints : array_like of float
        Angles [rad] where the pressure has a singular derivative (`GalerkinModel.breakpoints`:
        the ends of a rounded flat, those a `Gap` is given), so that a stick zone ending near one
        is located to a fraction of its distance from it.

    swept, end : float
        Largest span, in units of ``rtol a`` in x, of the elements of the slip zones (swept by the
        boundaries of the steps inside the increment) and of those holding the increment's own
        boundaries: `BOUNDARY_SPAN` where those steps' stick ends are recorded, `ENERGY_SPAN`
        where only the energy is.
    grading : float, optional
        Largest element around a boundary or a breakpoint, as a fraction of its distance from it:
        `BOUNDARY_GRADING` (None, read when called) where the steps' traction is recorded,
        `ENERGY_GRADING` where only the energy is.

    Returns
    -------
    ndarray, shape (M,)
        Target size of each element [rad], ascending ``theta``; ``inf`` where any size will do.
    """
    ds = np.asarray(ds, dtype=float)
    if ds.shape[-1] != theta.size or ds.ndim not in (1, 2):
        raise ValueError(f"ds must have {theta.size} values a row, one per node of theta; found shape {ds.shape}")
    if ds.ndim == 2:
        rows = [element_targets(theta, row, rtol, breakpoints, swept, end, grading, levels) for row in ds]
        return np.minimum.reduce(rows, initial=np.inf)
    grading = BOUNDARY_GRADING if grading is None else grading
    d = settled(ds)[::-1]  # theta order
    h = np.diff(theta)
    targets = np.full(h.size, np.inf)
    for point in breakpoints:  # the traction has the pressure's singular derivative there
        targets = np.minimum(targets, _graded_toward(theta, point, BREAKPOINT_SPAN * _span(point, rtol), grading))
    status = np.sign(d)
    inside, positions = _boundaries(theta, d)
    if inside.size == 0:
        return np.maximum(targets, MIN_SIZE if levels is None else np.maximum(h / 2**levels, MIN_SIZE))
    ends = np.concatenate([[0.0], positions, [np.pi]])
    nodes = np.diff(np.concatenate([[0], inside + 1, [d.size]]))
    width = np.diff(ends)
    zone_status = status[np.concatenate([[0], inside + 1])]
    for zone in range(width.size):
        overlapping = (theta[:-1] < ends[zone + 1]) & (theta[1:] > ends[zone])
        if nodes[zone] < MIN_ZONE_NODES:
            size = h[overlapping] / 2
        else:
            size = width[zone] * zone_fraction(rtol)
        if zone_status[zone]:  # swept by the boundaries of the steps between: locate them too
            size = np.minimum(size, _span((theta[:-1] + theta[1:])[overlapping] / 2, rtol, swept))
            if zone in (0, width.size - 1):  # grown from the contact's edge through every width
                size = np.minimum(size, _graded_from_edge(theta, zone == 0, rtol)[overlapping])
        targets[overlapping] = np.minimum(targets[overlapping], size)
    for zone, (k, position) in enumerate(zip(inside, ends[1:-1], strict=True)):  # between zone and zone + 1
        scale = min(width[zone], width[zone + 1], *(abs(position - b) or np.inf for b in breakpoints))
        size = min(boundary_fraction(rtol) * scale, _span(position, rtol, end))
        targets = np.minimum(targets, _graded_toward(theta, position, size, grading))
        if status[k] * status[k + 1] < 0:
            targets[k] = min(targets[k], h[k] / 2)
    return np.maximum(targets, MIN_SIZE if levels is None else np.maximum(h / 2**levels, MIN_SIZE))


def _span(position, rtol, span=BOUNDARY_SPAN):
    """Size [rad] of an element at `position` [rad] that spans ``span rtol a`` in x."""
    return span * rtol / np.maximum(np.sin(position), span * rtol / np.pi)


def _graded_from_edge(theta, left, rtol):
    """Targets [rad] growing like ``zone_fraction(rtol)`` times the distance from the contact's edge
    (``theta = 0`` if `left`, else ``pi``), from `EDGE_SIZE`.

    A slip zone at the edge grows through every width between two turning points, and the slip
    there is smooth in ``theta`` up to the edge, so that each of those widths is spanned by
    ``ZONE_ELEMENTS`` elements or more, as a zone at a turning point is: with only the elements a
    turning point's wide zone asks for, the slip of the narrow zones of the steps before it
    missed the slip target of benchmarks/trajectories.py.
    """
    distance = theta[:-1] if left else np.pi - theta[1:]
    return np.maximum(zone_fraction(rtol) * distance, EDGE_SIZE)


def _graded_toward(theta, position, size, grading):
    """Targets [rad]: `size` at `position`, growing like `grading` times the distance from it."""
    distance = np.maximum(np.maximum(theta[:-1] - position, position - theta[1:]), 0.0)
    return np.maximum(size, grading * distance)


def zone_fraction(rtol):
    """Size of the elements inside a zone, as a fraction of its width [-]: 1/`ZONE_ELEMENTS` or less.

    The energy error left inside the zones, ``ZONE_ERROR`` at ``1 / ZONE_ELEMENTS``, falls like
    the square of the fraction.
    """
    return min(1.0, np.sqrt(rtol / ZONE_ERROR)) / ZONE_ELEMENTS


def boundary_fraction(rtol):
    """Size of the element holding a stick/slip boundary, as a fraction of the narrower zone's width [-].

    Inverts the worst energy error ``BOUNDARY_ERROR (size / w)^(5/2)``; never coarser than
    `zone_fraction`.
    """
    return min(zone_fraction(rtol), (rtol / BOUNDARY_ERROR) ** (2 / 5))


def boundaries(theta, ds):
    """Stick/slip boundaries [rad] of the slip increment `ds` [m] (scene order, as for
    `element_targets`) on the mesh `theta` [rad], ascending, each placed by `_boundary_position`."""
    return _boundaries(theta, settled(ds)[::-1])[1]


def settled(ds):
    """The slip increment `ds` [m] with every slip of at most `CHATTER` of its largest set to zero.

    Where a load path closes a loop at a turning point, the nodes that slipped on the branch before and
    stuck since are back at their friction limit exactly (Masing's rule; Mindlin & Deresiewicz 1953): the
    increment leaves them stuck in exact arithmetic, but a solve started with them slipping (from the
    directions of a coarser mesh) may leave some slipping by the rounding of the solve, either way. Read
    as zones, they would split the stick zone into zones a node wide, each refined down to `MIN_SIZE`.
    """
    ds = np.asarray(ds, dtype=float)
    return np.where(np.abs(ds) > CHATTER * np.max(np.abs(ds), initial=0.0), ds, 0.0)


def _boundaries(theta, d):
    """Elements holding a boundary of `d` (theta order) and the boundaries [rad] inside them."""
    status = np.sign(d)
    inside = np.flatnonzero(status[1:] != status[:-1])  # element k holds a boundary
    return inside, np.array([_boundary_position(theta, d, k) for k in inside], dtype=float)


def tightened(theta, positions, levels=LEVELS_PER_PASS):
    """Targets [rad] that bisect the elements holding `positions` [rad] `levels` times, graded
    around them like a boundary's where only the energy is asked for (``ENERGY_GRADING``): where
    the energy of an increment whose boundaries these are still changes from one mesh to the next
    (`fretting.models.galerkin.adaptation.adapted_model`)."""
    h = np.diff(theta)
    targets = np.full(h.size, np.inf)
    for position in positions:
        k = min(int(np.searchsorted(theta, position, side="right")) - 1, h.size - 1)
        targets = np.minimum(targets, _graded_toward(theta, position, max(h[k] / 2**levels, MIN_SIZE), ENERGY_GRADING))
    return targets


def _boundary_position(theta, d, k):
    """Stick/slip boundary [rad] inside element ``k``, whose nodes ``k``, ``k + 1`` differ in status.

    Near a boundary the slip increment grows like ``dist^(3/2)`` (eq 19; Masing for reversed
    zones), so ``|d|^(2/3)`` is extrapolated linearly from the two nearest slipping nodes (the
    element's middle when there is one only); a change of slip direction is placed where ``d``
    interpolates to zero.
    """
    lo, hi = theta[k], theta[k + 1]
    if d[k] != 0 and d[k + 1] != 0:
        return lo + (hi - lo) * d[k] / (d[k] - d[k + 1])
    slipping, step = (k + 1, 1) if d[k] == 0 else (k, -1)
    estimate = extrapolated_end(theta, d, slipping, slipping + step)
    return (lo + hi) / 2 if estimate is None else float(np.clip(estimate, lo, hi))


def located_end(position, d, slipping, beyond):
    """Where the slip `d` of a slip zone on a Galerkin mesh reaches zero, or None if it cannot be told.

    The P1 slip is zero at the last stuck node, where the true slip is zero only inside the
    element beyond it, so the slipping node nearest the boundary may lag behind the
    ``dist^(3/2)`` law (eq 19), and `extrapolated_end` from it then places the end too far into
    the slip zone: by up to 0.32 of the element on Cattaneo-Mindlin on uniform meshes, never
    short of it. Where `RESOLVED_NODES` nodes from `slipping` (its neighbour `beyond` next,
    `position`: the nodes' coordinates) slip the same way, ``|d|^(2/3)`` is also extrapolated
    from the second and third of them, which keep the law, and the estimate nearer the stick
    zone is taken, since the nearest node's lag only ever moves its estimate outward: within 0.1
    of the element there (tests/test_trajectories.py).
    """
    nearest = extrapolated_end(position, d, slipping, beyond)
    step = beyond - slipping
    run = slipping + step * np.arange(RESOLVED_NODES)
    if nearest is None or not 0 <= run[-1] < d.size or np.any(np.sign(d[run]) != np.sign(d[slipping])):
        return nearest
    skipped = extrapolated_end(position, d, run[1], run[2])
    outward = np.sign(position[beyond] - position[slipping])
    return nearest if skipped is None else min(nearest, skipped, key=lambda end: end * outward)


def refine(theta, targets):
    """Bisect every element until it is no larger than its target, then grade the mesh.

    Parameters
    ----------
    theta : ndarray, shape (M + 1,)
        The mesh [rad], ascending from 0 to pi.
    targets : ndarray, shape (M,)
        Largest size of each element [rad], positive, ``inf`` for any (`element_targets`).

    Returns
    -------
    ndarray
        The refined mesh: the old nodes stay nodes, and neighbouring elements differ in size
        by a factor ``GRADING`` at most. `theta` itself when no element needed bisecting.
    """
    h = np.diff(theta)
    targets = np.asarray(targets, dtype=float)
    if targets.shape != h.shape or np.any(~(targets > 0)):
        raise ValueError(f"targets must be {h.size} positive sizes, one per element; found {targets!r}")
    coarse = h > targets
    levels = np.zeros(h.size, dtype=int)
    levels[coarse] = np.ceil(np.log2(h[coarse] / targets[coarse]))
    if not levels.any():
        return _graded(theta)
    count = 2**levels
    element = np.repeat(np.arange(h.size), count)
    index = np.arange(element.size) - np.repeat(np.cumsum(count) - count, count)
    inner = theta[element] + h[element] * index / count[element]
    return _graded(np.concatenate([inner, [np.pi]]))


def _graded(theta):
    """Bisect the elements more than ``GRADING`` times the size of a neighbour until none is; `theta` if none was."""
    while True:
        h = np.diff(theta)
        neighbour = np.minimum(np.concatenate([[np.inf], h[:-1]]), np.concatenate([h[1:], [np.inf]]))
        coarse = np.flatnonzero(h > GRADING * neighbour * (1 + GRADING_SLACK))
        if coarse.size == 0:
            return theta
        theta = np.insert(theta, coarse + 1, (theta[coarse] + theta[coarse + 1]) / 2)
