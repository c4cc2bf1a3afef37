"""How right a run is: its errors against a reference, closed-form or a more resolved run.

A `Reference` gives, at every step of a history, the stick zones, the places where the traction
has square-root kinks, the traction and the energy of each cycle. `masing_reference` builds one
from the closed forms (a Hertz contact under proportional loads), `run_reference` from a run that
recorded every step; `score` gives a run's errors against either:

- stick ends [a]: `zone_distance` between the run's stick zones and the reference's;
- energy per cycle [-]: `energy_error`, ``|W / W_ref - 1|``;
- traction [f p0]: `traction_error`, ``|q - q_ref|`` at the run's own points, leaving out `BAND`
  around every stick/slip boundary of the reference, those its memory keeps (`memory_kinks`)
  and inside each contact edge: the traction has square-root kinks there, and a boundary that
  sits a fraction of a node spacing off the true one gives an error of order one at them.

Each error is the largest over the recorded steps (or cycles) of the run.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from fretting.physics import closed_forms as cf
from fretting.physics.contact import Contact

if TYPE_CHECKING:
    import xarray as xr

    from fretting.loading.history import History

__all__ = [
    "BAND",
    "Reference",
    "energy_error",
    "masing_reference",
    "memory_kinks",
    "monotonic_dissipation",
    "run_reference",
    "run_zones",
    "score",
    "traction_error",
    "zone_distance",
    "zone_pairs",
]

#: Band left out of the traction error around each stick/slip boundary and inside each edge [a].
BAND = 0.02

#: Gauss-Legendre points of each slip zone in `monotonic_dissipation` with bulk tension.
SLIP_WORK_ORDER = 64


@dataclass(frozen=True, eq=False)
class Reference:
    """What a run is scored against, per step of the history.

    Attributes
    ----------
    label : str
        What the reference is: "closed form (Masing)" or the label of the reference run.
    zones : list of ndarray, shape (n_zones, 2)
        Stick zones ``(start, end)`` of the increment ending at each step [m].
    kinks : list of ndarray
        Where the traction has a square-root kink at each step [m]: left out of the traction error.
    cycle_energy : ndarray
        Energy dissipated in each cycle [J/m].
    tractions : callable
        ``tractions(step, x)``: the traction [Pa] at positions ``x`` [m].
    """

    label: str
    zones: list
    kinks: list
    cycle_energy: np.ndarray
    tractions: object


# -- Error metrics ----------------------------------------------------------------------------


def zone_distance(zones: ArrayLike, reference: ArrayLike) -> float:
    """Distance between two sets of stick zones [m, or the unit of the zones].

    The ends of `zones` are matched in order to those of `reference` (starts to starts, ends to
    ends), where a zone that one side lacks, a stick zone or the slip zone between two stick
    zones, may instead close up, at half its width: a zone that nucleates or vanishes between two
    discretisations counts by its size, not by its distance from the other zones. The distance is
    the smallest, over such matchings, of the largest distance an end moves (dynamic programming).

    Parameters
    ----------
    zones, reference : array_like, shape (n, 2) and (m, 2)
        Stick zones ``(start, end)`` [m]; either may be empty.

    Returns
    -------
    float
    """
    u, v = (np.sort(np.asarray(z, dtype=float).reshape(-1, 2), axis=0).ravel() for z in (zones, reference))
    cost = np.full((u.size + 1, v.size + 1), math.inf)
    cost[0, 0] = 0.0
    for i, j in itertools.product(range(u.size + 1), range(v.size + 1)):
        here = cost[i, j]
        if here == math.inf:
            continue
        if i < u.size and j < v.size and (i - j) % 2 == 0:
            cost[i + 1, j + 1] = min(cost[i + 1, j + 1], max(here, abs(u[i] - v[j])))
        if i + 1 < u.size:
            cost[i + 2, j] = min(cost[i + 2, j], max(here, (u[i + 1] - u[i]) / 2))
        if j + 1 < v.size:
            cost[i, j + 2] = min(cost[i, j + 2], max(here, (v[j + 1] - v[j]) / 2))
    return float(cost[-1, -1])


def energy_error(W: ArrayLike, W_ref: ArrayLike) -> float:
    """Largest relative error ``|W / W_ref - 1|`` [-] of the energies per cycle.

    Parameters
    ----------
    W, W_ref : array_like, shape (n_cycles,)
        Energy dissipated in each cycle by the run and by the reference [J/m]; ``W_ref > 0``.

    Raises
    ------
    ValueError
        The two have different numbers of cycles, or a reference energy is not positive.
    """
    W, W_ref = np.asarray(W, dtype=float), np.asarray(W_ref, dtype=float)
    if W.shape != W_ref.shape or np.any(W_ref <= 0):
        raise ValueError(f"need as many cycles, each with positive reference energy, found {W.shape}, {W_ref.shape}")
    return float(np.max(np.abs(W / W_ref - 1), initial=0.0))


def traction_error(x: ArrayLike, q: ArrayLike, q_ref: ArrayLike, exclude: ArrayLike, width: float) -> float:
    """Largest ``|q - q_ref|`` [Pa] at the positions farther than `width` from all of `exclude`.

    Parameters
    ----------
    x : array_like, shape (N,)
        Positions [m].
    q, q_ref : array_like, shape (N,)
        Traction of the run and of the reference at `x` [Pa]; where `q` is NaN (a run without a
        value there) the position is skipped.
    exclude : array_like
        Positions [m] around which the error is not taken (kinks, contact edges).
    width : float
        Half-width [m] of the band left out around each of `exclude`.
    """
    x = np.asarray(x, dtype=float)
    far = np.all(np.abs(np.subtract.outer(x, np.asarray(exclude, dtype=float).ravel())) > width, axis=-1)
    far &= ~np.isnan(np.asarray(q, dtype=float))
    return float(np.max(np.abs(np.asarray(q) - np.asarray(q_ref))[far], initial=0.0))


def memory_kinks(x: np.ndarray, stick: np.ndarray) -> list[np.ndarray]:
    """Former stick/slip boundaries where the locked-in slip still puts a kink in the traction [m], per step.

    Where a point that slipped at step ``k`` meets one that last slipped before ``k - 1`` (or
    never), the slip of the later episode starts like ``d^(3/2)`` and the traction has a
    square-root kink; a boundary that sweeps outward step by step leaves none. The kink is placed
    midway between the two points.

    Parameters
    ----------
    x : ndarray, shape (N,)
        Positions [m], ascending.
    stick : ndarray of bool, shape (n_steps, N)
        The point did not slip in the increment ending at each step (step 0: the start).

    Returns
    -------
    list of ndarray
        The kinks [m] at each step.
    """
    steps = np.arange(stick.shape[0])[:, None]
    last = np.maximum.accumulate(np.where(stick, -2, steps), axis=0)  # -2: never slipped
    middle = (x[1:] + x[:-1]) / 2
    return [middle[np.abs(np.diff(row)) > 1] for row in last]


def zone_pairs(start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Stick zones ``(start, end)`` [m], shape (n_zones, 2), from one step's ``stick_start`` and ``stick_end`` [m]
    (NaN past its zones)."""
    pairs = np.stack([start, end], axis=-1)
    return pairs[~np.isnan(pairs[:, 0])]


def run_zones(result: xr.Dataset, k: int) -> np.ndarray:
    """Stick zones ``(start, end)`` [m] of row `k` of a result of `fretting.simulate`, shape (n_zones, 2)."""
    return zone_pairs(result.stick_start.values[k], result.stick_end.values[k])


def score(result: xr.Dataset, reference: Reference) -> dict[str, float]:
    """Errors of a run against a reference, each the largest over the run's recorded steps after the first.

    Parameters
    ----------
    result : xarray.Dataset
        A run of `fretting.simulate` (attributes ``a``, ``f``, ``p0``, optionally ``centre``);
        its steps index the reference's.
    reference : Reference

    Returns
    -------
    dict
        ``stick_ends_a``: `zone_distance` / a; ``energy_rel``: `energy_error` of the energy per
        cycle; ``traction_fp0``: `traction_error` / (f p0) at the run's own points, leaving out
        `BAND` a around the reference's kinks and inside the contact edges.
    """
    attrs = result.attrs
    a, centre, fp0 = attrs["a"], attrs.get("centre", 0.0), attrs["f"] * attrs["p0"]
    x, q = result.x.values, result.q.values
    edges = [centre - a, centre + a]
    stick, traction = 0.0, 0.0
    for k, step in enumerate(result.step.values.tolist()):
        if step == 0:
            continue
        stick = max(stick, zone_distance(run_zones(result, k), reference.zones[step]))
        exclude = np.concatenate([reference.kinks[step], edges])
        traction = max(traction, traction_error(x, q[k], reference.tractions(step, x), exclude, BAND * a))
    energy = energy_error(result.cycle_dissipation.values, reference.cycle_energy)
    return {"stick_ends_a": stick / a, "energy_rel": energy, "traction_fp0": traction / fp0}


# -- References -------------------------------------------------------------------------------


def run_reference(result: xr.Dataset, label: str) -> Reference:
    """Reference from a (most resolved) run that recorded every step: its stick zones, energies and traction.

    The traction is interpolated linearly to the scored run's points. Kinks are the stick-zone
    ends of the step and the boundaries the memory keeps, `memory_kinks`.

    Raises
    ------
    ValueError
        `result` did not record every step.
    """
    if not np.array_equal(result.step.values, np.arange(result.sizes["step"])):
        raise ValueError("a reference run must record every step")
    zones = [run_zones(result, k) for k in range(result.sizes["step"])]
    x, q = result.x.values, result.q.values
    kinks = [np.concatenate([z.ravel(), m]) for z, m in zip(zones, memory_kinks(x, result.stick.values), strict=True)]

    def tractions(step: int, at: ArrayLike) -> np.ndarray:
        return np.interp(at, x, q[step])

    return Reference(label, zones, kinks, result.cycle_dissipation.values, tractions)


def monotonic_dissipation(contact: Contact, Q: float, ratio: float = 0.0) -> float:
    """Energy [J/m] a Hertz contact dissipates loaded from zero along ``sigma = ratio Q`` to ``Q`` [N/m].

    ``int f p |s| dx`` of the Nowell-Hills slip (every point slips one way only):
    `fretting.physics.closed_forms.cattaneo_mindlin_dissipation` when ``ratio = 0``, otherwise by
    quadrature. Each slip zone, from its stick end ``L`` to the contact edge ``E``, is mapped by
    ``x = L + (E - L) sin^2(phi / 2)``: the ``(x - L)^(3/2)`` of the slip and the ``sqrt(E - x)``
    of the pressure become analytic in ``phi``, so Gauss-Legendre of `SLIP_WORK_ORDER` points
    converges exponentially (tests/analysis/test_accuracy.py::test_slip_work_by_quadrature_is_the_closed_form).

    Parameters
    ----------
    ratio : float
        ``sigma / Q`` [1/m], within Nowell-Hills' range ``|ratio| <= 2 p0 / P``.
    """
    if ratio == 0.0:
        return cf.cattaneo_mindlin_dissipation(contact, Q)
    return _slip_work(contact, Q, ratio)


def _slip_work(contact: Contact, Q: float, ratio: float) -> float:
    """``int f p |s| dx`` [J/m] of the Nowell-Hills slip at ``Q``, ``sigma = ratio Q``, by quadrature."""
    if Q == 0:
        return 0.0
    a = contact.a
    b = float(cf.stick_half_width(contact, Q))
    e = float(np.sign(Q) * cf.nowell_hills_offset(contact, ratio * Q))
    node, weight = np.polynomial.legendre.leggauss(SLIP_WORK_ORDER)
    phi = np.pi * (node + 1) / 2
    total = 0.0
    for stick_end, edge in ((e + b, a), (e - b, -a)):
        x = stick_end + (edge - stick_end) * np.sin(phi / 2) ** 2
        dx = (edge - stick_end) * np.sin(phi / 2) * np.cos(phi / 2) * np.pi / 2
        slip = np.abs(cf.cattaneo_mindlin_slip(contact, Q, x - e))
        total += np.sum(weight * contact.f * contact.pressure(x) * slip * np.abs(dx))
    return float(total)


@dataclass(frozen=True, eq=False)
class _Monotonic:
    """Hertz contact loaded from zero along ``sigma = ratio Q``: Nowell-Hills (Cattaneo-Mindlin if ``ratio = 0``)."""

    contact: Contact
    ratio: float

    def traction(self, Q: float, x: ArrayLike) -> np.ndarray:
        return cf.nowell_hills_traction(self.contact, Q, self.ratio * Q, x)

    def zone(self, Q: float) -> tuple[float, float]:
        """Stick zone ``(start, end)`` [m]."""
        centre = float(np.sign(Q) * cf.nowell_hills_offset(self.contact, self.ratio * Q))
        b = float(cf.stick_half_width(self.contact, Q))
        return centre - b, centre + b

    def dissipation(self, Q: float, cache: dict[float, float]) -> float:
        key = abs(Q)
        if key not in cache:
            cache[key] = monotonic_dissipation(self.contact, key, self.ratio)
        return cache[key]


def _proportional_ratio(history: History) -> float:
    """``sigma / Q`` of a proportional history (raises if it is not)."""
    k = int(np.argmax(np.abs(history.Q)))
    ratio = float(history.sigma[k] / history.Q[k])
    if not np.allclose(history.sigma, ratio * history.Q, rtol=1e-12, atol=1e-12 * np.abs(history.sigma).max()):
        raise ValueError("the Masing reference needs proportional loads, sigma = ratio Q")
    return ratio


def masing_reference(contact: Contact, history: History) -> Reference:
    """Closed-form reference of a Hertz contact under proportional loads ``sigma = ratio Q`` from zero.

    Masing's rule (`fretting.physics.closed_forms.masing_walk`) over the Nowell-Hills solution
    (Cattaneo-Mindlin and Mindlin-Deresiewicz when ``sigma = 0``): valid while Nowell-Hills is,
    ``|ratio| <= 2 p0 / P`` and the stick zone inside the contact.

    Parameters
    ----------
    contact : fretting.Contact
        On a Hertz profile.
    history : fretting.History
        Starting at ``Q = 0``, with cycles (the energy is per cycle).

    Returns
    -------
    Reference
        Kinks include the stick-zone ends of every branch the memory keeps.

    Raises
    ------
    ValueError
        The loads are not proportional, or ``Q`` does not start at zero.
    """
    mono = _Monotonic(contact, _proportional_ratio(history))
    stacks, pieces = cf.masing_walk(history.Q)
    cache = {}
    dissipation = np.array([sum(_piece_dissipation(mono, piece, cache) for piece in walk) for walk in pieces])
    zones = [np.array([_last_zone(mono, walk)]) for walk in pieces]
    paths = [_branches(stack, load) for stack, load in zip(stacks, history.Q.tolist(), strict=True)]
    kinks = [np.array([end for o, s, to in path if to != o for end in mono.zone((to - o) / s)]) for path in paths]

    def tractions(step: int, x: ArrayLike) -> np.ndarray:
        return sum((s * mono.traction((to - o) / s, x) for o, s, to in paths[step]), np.zeros(np.shape(x)))

    energy = np.bincount(history.cycle, weights=dissipation)[1:]
    return Reference("closed form (Masing)", zones, kinks, energy, tractions)


def _piece_dissipation(mono: _Monotonic, piece: cf.Piece, cache: dict[float, float]) -> float:
    """Energy [J/m] dissipated along a piece ``(origin, factor, Q_from, Q_to)`` of a Masing branch."""
    origin, factor, start, end = piece
    return factor * (
        mono.dissipation((end - origin) / factor, cache) - mono.dissipation((start - origin) / factor, cache)
    )


def _last_zone(mono: _Monotonic, walk: list[cf.Piece]) -> tuple[float, float]:
    """Stick zone [m] of an increment: that of the branch it ends on; the whole contact if nothing moved."""
    if not walk:
        return (-mono.contact.a, mono.contact.a)
    origin, factor, _, end = walk[-1]
    return mono.zone((end - origin) / factor)


def _branches(stack: tuple[float, ...], load: float) -> list[tuple[float, int, float]]:
    """Branches ``(origin, factor, end)`` from the virgin state through the turning points to ``load``."""
    points = [0.0, *stack, load]
    return [(o, 1 if i == 0 else 2, to) for i, (o, to) in enumerate(itertools.pairwise(points))]
