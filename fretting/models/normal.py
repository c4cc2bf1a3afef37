"""A normal load that varies: the contact grows and recedes over cells fixed in ``x``.

For elastically similar half-planes the normal and tangential problems uncouple (seed paper,
section 2) and both are governed by the same kernel: a traction ``q`` on the contact moves the
two surfaces apart tangentially by

    s(x) = -(2 / (pi E_star)) int q(xi) ln(L / |x - xi|) dxi + s_sigma(x) + c,

with ``s_sigma = sigma x / (2 E_star)`` the relative displacement of the bulk tension (the slip
that cancels the fully stuck traction ``sigma x / (4 sqrt(a^2 - x^2))`` of eq 20), ``c`` a rigid
shift and ``L`` any length (it changes ``c`` only); the pressure obeys the same law normally (eq 1).

Discretisation. The interval ``[-A, A]`` of the largest contact of the history is cut into ``N``
equal cells of width ``h``, a node at the middle of each, the traction constant on each. The
flexibility ``D_ij = (2 / (pi E_star h)) int_{cell j} ln(L / |x_i - xi|) dxi`` (`flexibility`)
is a symmetric Toeplitz matrix, the same for every contact: a contact is a run of ``2m`` cells
about the centre (``m`` pairs), and only which cells are in contact changes with ``P``. On them,
with ``B = D^-1``, ``b = B 1`` and ``beta = 1^T b``, the nodal forces ``g = h q`` [N/m] are

    g = Q b / beta - G (s - s_sigma),    G = B - b b^T / beta,

the discrete method 4 (eqs 9, 20, A.4): ``b / beta`` is the flat punch of unit load (the fully
stuck traction of ``Q``), ``G`` the slip-to-traction matrix, symmetric positive semi-definite
with ``G 1 = 0``; an increment is the problem `fretting.models.solver.solve_increment` solves,
with the limit ``f p h``.

Normal problem (Jaeger 1998). The pressure is built by superposing flat punches on the same
cells: each ``dP`` adds ``dP b / beta`` of the cells in contact. The ``m`` pairs carry the load
added while ``a(P)`` is nearer their effective half-width than their neighbours' (`NormalModel.start`):
that of the continuous flat punch with the same compliance, ``c_m = 2L exp(-pi E_star delta_m / 2)``
with ``delta_m`` the rigid displacement of ``b / beta`` (a continuous flat punch of half-width ``c``
displaces by ``(2 / (pi E_star)) ln(2L / c)``). The pressure is a function of ``P`` alone, sums to
``P``, is zero at the nodes of a pair when it enters or leaves, and its increments are the same
flat punches as the fully stuck traction increments of ``Q``. An increment is solved in parts that
cross no change of the cells in contact, so that Jaeger's rule holds exactly on the grid: an
increment with ``|dQ| + (pi a / 4) |dsigma| <= f dP`` slips nowhere, and proportional loading
``Q = lambda (P - P0)``, ``lambda < f``, carries ``q = lambda (p(P) - p(P0))``. The parts also
change ``P`` by at most ``load_part`` of the load (`DEFAULT_LOAD_PART`): each is one implicit
step of the solver, under the friction limit of its end load. Its energy ``int f p(P) |ds|`` is
taken by the trapezoidal rule in ``P``, ``f (p_start + p_end) h |ds| / 2``: the pressure at the
nodes is linear in ``P`` over a part, and the slip grows with ``P`` nearly linearly over it, so the
energy errs at second order in ``load_part`` where the end load alone (an implicit Euler rule)
errs at first order. ``p_start`` is the pressure at the part's start, but where the pressure falls
a node that was stuck then starts to slip only once its limit has fallen to the traction it carried
(`slip_start`): a node that leaves the contact at the part's end, under a limit that falls to exactly
zero, may take a slip of the size of the solver's rounding on a history that slips nowhere (its
traction is zero there in exact arithmetic), and that slip dissipates in proportion to the traction
it carried, not to ``f`` (issue 38).

Memory. ``s`` at a node in contact is its relative displacement since the contact was formed; at
a node out of contact it is that of the two free surfaces there, computed after every part of
an increment (`NormalModel.free_surface`). A node that enters sticks with the displacement it had
just before (continuity) under a traction that starts from zero; a node that leaves carries no
traction and forgets its slip. Everything depends on the loads and the slip alone, so a periodic
history that shakes down repeats its cycles bit for bit.

Stick ends. A node at the limit that does not slip (a band that entered at the limit ratio ``f``) is moved by
the solver's rounding only, and counts as stuck (`ROUNDING`). An end between a stuck and a slipping node is placed
by the square-root kink of the
traction, from the friction deficit of the one and the slip of the other (`kink_end`); slip zones one
cell wide are common here, as an edge recedes. The deficit is taken against the limit of the slip
zone's direction, ``f p - s q`` with ``s f p`` the slip zone's traction: a receding edge often slips
against the traction locked in beside it, and ``f p - |q|`` would then read a stuck node near the
opposite limit as one near the slip zone's. A slip zone that has reached a former edge of the
contact ends there (`pinned`), and its end is extrapolated from the slip alone. A stick zone that
reaches the outermost node in contact ends at the edge, unless that edge slips in the increment
(`NormalModel.edges_slip`: it recedes, or grows under more shear than Jaeger's rule carries); its
slip zone is then narrower than a cell, and `edge_end` extrapolates the deficit to it, against the
limit of the sign of the outermost node's traction.
"""

from __future__ import annotations

import functools
import math
import operator
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from scipy import linalg, optimize

from fretting._compiled import njit
from fretting.models.base import Model, ModelSpec, Outcome
from fretting.models.method4 import deficit_end, extrapolated_end, on_the_point, stick_zones
from fretting.models.solver import Increment, Stiffness, solve_increment
from fretting.physics.surface import SurfaceStress

if TYPE_CHECKING:
    from fretting.loading.history import History
    from fretting.physics.contact import Contact

__all__ = [
    "DEFAULT_CELLS",
    "DEFAULT_LOAD_PART",
    "CellSurfaceStress",
    "NormalModel",
    "NormalOutcome",
    "Varying",
    "cell_centres",
    "flexibility",
    "slip_to_traction",
]

#: Cells over the largest contact of `Varying()`: the closed forms of tests/models/test_normal_load.py hold
#: to 1e-3 at this many, and the energy of a random history to 1e-4 of a finer run wherever the
#: cells lie against the contact's edges, which at fewer cells it does not (benchmarks/normal_load.py
#: prints the convergence and the shifted cells).
DEFAULT_CELLS = 768

#: Largest change of ``P`` in one part of an increment, relative to the smaller load at its ends,
#: of `Varying()`. A part is solved as one step of the solver, under the friction limit of its end
#: load, and its energy by the trapezoidal rule in ``P`` (module docstring); the energy of a history
#: converges with this share (benchmarks/normal_load.py prints the table).
DEFAULT_LOAD_PART = 1 / 400

#: Bytes of the `Stiffness` of the contacts (runs of cells) `NormalModel` keeps whole (``G``, ``(2m)^2``
#: floats, 4.7 MB at 768 cells), the least recently used dropped first: the parts of an increment and the
#: cycles of a history meet the same contacts again, and one not kept is formed again from its kept rows
#: (`CACHED_HALVES`) by a copy, or else by Trench's recursion.
CACHED_STIFFNESSES = 2**27

#: Bytes of the first ``m`` rows of ``G`` (`half_stiffness`, ``2 m^2`` floats, 2.4 MB at 768 cells) that
#: `NormalModel` keeps for the contacts it has met, the least recently used dropped first: a history whose
#: ``P`` varies meets the same contacts again and again, and the whole ``G`` is one flipped copy of those
#: rows (`whole`), which takes a fraction of the time of the recursion that forms them (`_trench_rows`).
CACHED_HALVES = 2**27

#: Episode slip [of the largest at the step's nodes in contact] at or below which a node counts as stuck when its
#: stick zones are read (`NormalModel.stick_zones`): nodes at the limit that do not slip (bands that entered at the
#: limit ratio ``f`` and stay there, Jaeger 1998) take slips of the size of the solver's rounding, far below this,
#: and would otherwise split a stick zone into pieces a node wide.
ROUNDING = 1e-9


@dataclass(frozen=True, eq=False, repr=False)  # ModelSpec.__repr__
class Varying(ModelSpec):
    """Method 4 on `cells` equal cells fixed in ``x`` over the largest contact of a history of ``P``.

    Parameters
    ----------
    cells : int
        Cells over ``[-A, A]``, even, at least 8.
    half_width : float, optional
        ``A`` [m], the half-width of the largest contact (resolved for a history by `resolved_for`).
    load_part : float
        Largest relative change of ``P`` in one part of an increment (`DEFAULT_LOAD_PART`), in (0, 1].
    """

    cells: int = DEFAULT_CELLS
    half_width: float | None = None
    load_part: float = DEFAULT_LOAD_PART

    name: ClassVar[str] = "varying"
    inputs: ClassVar[frozenset[str]] = frozenset({"Q", "sigma", "P"})
    description: ClassVar[str] = (
        "method 4 under a varying normal load: cells fixed in x over the largest contact, Jaeger's superposition"
    )

    def __post_init__(self):
        cells = self.cells
        if isinstance(cells, bool) or not isinstance(cells, (int, np.integer)) or cells < 8 or cells % 2:
            raise ValueError(f"cells must be an even integer >= 8, found {cells!r}")
        if self.half_width is not None and not (np.isfinite(self.half_width) and self.half_width > 0):
            raise ValueError(f"half_width must be a positive length [m], found {self.half_width!r}")
        if not 0 < self.load_part <= 1:
            raise ValueError(f"load_part must be in (0, 1], found {self.load_part!r}")

    @property
    def resolved(self) -> bool:
        return self.half_width is not None

    def resolved_for(self, contact: Contact, history: History | None) -> Varying:
        """This spec over the largest contact of `history` (None, or no ``P`` in it: the contact's own)."""
        if self.resolved:
            return self
        P = contact.P if history is None or history.P is None else max(float(history.P.max()), contact.P)
        return Varying(self.cells, float(contact.profile.half_width(P, contact.E_star)[0]), self.load_part)

    def build(self, contact: Contact) -> NormalModel:
        return NormalModel(contact, self)

    def is_default(self) -> bool:
        return (self.cells, self.load_part) == (DEFAULT_CELLS, DEFAULT_LOAD_PART)

    def attributes(self) -> dict:
        """The model's name, cells and load part, and the half-width its cells span once resolved."""
        spans = {} if self.half_width is None else {"half_width": float(self.half_width)}
        return {"model": self.name, "cells": int(self.cells)} | spans | {"load_part": float(self.load_part)}

    def holds_for(self, contact: Contact, history: History | None) -> str | None:
        if not contact.profile.grows_with_load():
            return f"{contact.profile!r} is not a symmetric profile whose contact grows with P (Hertz, RoundedFlat)"
        if self.resolved and history is not None and history.P is not None:
            largest = float(contact.profile.half_width(float(history.P.max()), contact.E_star)[0])
            if largest > self.half_width:
                return f"its largest contact, a = {largest!r} m, is wider than the cells, A = {self.half_width!r} m"
        return None

    @classmethod
    def from_record(cls, attrs: dict, theta: np.ndarray | None) -> Varying:
        return cls(int(attrs["cells"]), float(attrs["half_width"]), float(attrs["load_part"]))


def cell_centres(contact, N, A):
    """``(h, x, t)``: the width [m] of `N` equal cells over ``[-A, A]`` about the centre of `contact` (`A` [m]),
    their centres ``x`` [m] and ``t = (x - centre) / a`` [-]."""
    h = 2 * A / N
    x = (np.arange(N) + 0.5) * h - A + contact.centre
    return h, x, (x - contact.centre) / contact.a


def flexibility(N, h, E_star):
    """First column of the Toeplitz flexibility ``D`` [m/(N/m)] of `N` cells of width `h` [m].

    ``D_k = (2 / (pi E_star h)) int_{(k - 1/2) h}^{(k + 1/2) h} ln(L / |u|) du`` with ``L = 2 N h``,
    twice the cells' length, so that ``D`` is positive definite (the logarithmic capacity of an
    interval is a quarter of its length); ``int ln(L / |u|) du = u (1 + ln(L / |u|))``.
    """
    L = 2 * N * h
    u = (np.arange(N + 1) - 0.5) * h
    F = u * (1 + np.log(L / np.abs(u)))
    return 2 / (np.pi * E_star * h) * np.diff(F)


@dataclass(frozen=True, eq=False)
class NormalOutcome(Outcome):
    """An `Outcome` of `NormalModel`: also the normal load ``P`` [N/m] after the increment, its energy
    density [J/m^2] (the pressure changes within the increment), whether each contact edge (``x < 0``,
    ``x > 0``) slips in it (`NormalModel.edges_slip`), and the nodal forces [N/m] locked in before it
    (`locked`: the stick ends read former edges from them, `pinned`)."""

    P: float = np.nan
    edges: tuple = (False, False)
    density: np.ndarray | None = None
    locked: np.ndarray | None = None


class CellFields:
    """The energy density and the surface stress of a model of a varying ``P`` on the cells of `cell_centres`
    (`t`), from its `pressure_at(P)` [Pa] at them: `NormalModel`'s and `fretting.models.jaeger.JaegerModel`'s."""

    def dissipation_density(self, ds):
        """``f p |ds|`` [J/m^2] under the contact's own load (`energy_density`: under an increment's)."""
        return self.contact.f * self.pressure_at(self.contact.P) * np.abs(ds)

    def energy_density(self, outcome):
        return outcome.density

    @functools.cached_property
    def surface(self):
        """The surface direct stress at the nodes (`CellSurfaceStress`) and the pressure of the contact's ``P`` [Pa]."""
        return CellSurfaceStress(self.t), self.pressure_at(self.contact.P)

    def surface_at(self, outcome):
        return self.surface[0], self.pressure_at(outcome.P)


class NormalModel(CellFields, Model):
    """A contact whose normal load varies, on the cells of a resolved `Varying` spec (module docstring).

    Attributes
    ----------
    h : float
        Cell width [m].
    start : ndarray, shape (N // 2 + 1,)
        ``start[m]``: the load [N/m] from which the ``m`` central pairs of cells carry the load added
        (zero for the first pair and for the pairs inside the contact of no load, such as a rounded
        flat's flat); ``start[0]`` is unused.
    """

    theta = None

    def __init__(self, contact, spec):
        self.contact, self.spec = contact, spec
        self.h, self.x, self.t = cell_centres(contact, spec.cells, spec.half_width)
        self.friction_force = np.inf  # f P at each step: the engine checks the load of the step
        self.column = flexibility(spec.cells, self.h, contact.E_star)
        # m -> what the model keeps of the run of m central pairs (`_recent`), dropped with the model:
        self._punches, self._columns, self._stiffnesses, self._halves, self._bulk = {}, {}, {}, {}, {}
        self._kernel = np.concatenate([self.column[:0:-1], self.column])  # D_ij = kernel[N - 1 + i - j]
        self.start = self._starts()
        self._sums = self._cumulative()

    def _starts(self):
        """`start`: the loads at the midpoints of consecutive effective half-widths (module docstring)."""
        N, L = self.x.size, 2 * self.x.size * self.h
        delta = np.array([self.column[: 2 * m] @ self.punch(m) for m in range(1, N // 2 + 1)])
        effective = 2 * L * np.exp(-np.pi * self.contact.E_star * delta / 2)
        between = (effective[:-1] + effective[1:]) / 2
        loads = np.array([self.contact.profile.load(c, self.contact.E_star) for c in between])
        return np.concatenate([[0.0, 0.0], np.maximum.accumulate(loads)])

    def pairs(self, P):
        """Pairs of cells in contact under the load `P` [N/m] (`start`)."""
        return max(1, int(np.searchsorted(self.start[1:], P, side="left")))

    def cells(self, m):
        """Slice of the nodes of the `m` central pairs."""
        middle = self.x.size // 2
        return slice(middle - m, middle + m)

    def punch(self, m):
        """``b / beta``: the nodal forces of the unit load on the `m` central pairs, flat punch (Levinson), kept."""
        return _recent(self._punches, m, lambda: _unit_load(self.column[: 2 * m]))

    def inverse_column(self, m):
        """First column of ``B = D^-1`` [(N/m)/m] of the `m` central pairs (Levinson), kept: the `stiffness` of a
        contact met again, once its rows have left the cache (`_half`), is formed from it (`half_stiffness`)."""
        return _recent(self._columns, m, lambda: linalg.solve_toeplitz(self.column[: 2 * m], np.eye(2 * m, 1)[:, 0]))

    def stiffness(self, m):
        """``G = B - b b^T / beta`` [(N/m)/m: nodal force per slip] of the `m` central pairs (module docstring,
        `slip_to_traction`), as a `Stiffness` (not `kept` for the solver's inverse), kept within
        `CACHED_STIFFNESSES` bytes, or alone where one is larger: the parts of an increment ask for it
        several times."""
        return _recent(
            self._stiffnesses,
            m,
            lambda: Stiffness(whole(self._half(m)), kept=False),
            CACHED_STIFFNESSES,
            lambda stiffness: stiffness.G.nbytes,
            alone=True,
        )

    def _half(self, m):
        """`half_stiffness` of the `m` central pairs, kept within `CACHED_HALVES` bytes."""
        return _recent(
            self._halves,
            m,
            lambda: half_stiffness(self.column[: 2 * m], self.punch(m), self.inverse_column(m)),
            CACHED_HALVES,
            operator.attrgetter("nbytes"),
        )

    def _cumulative(self):
        """Nodal forces ``p h`` [N/m] at each load `start` (Jaeger's superposition of the `punch` of each run)."""
        N = self.x.size
        sums = np.zeros((N // 2 + 1, N))
        for m in range(2, N // 2 + 1):
            sums[m] = sums[m - 1]
            sums[m, self.cells(m - 1)] += (self.start[m] - self.start[m - 1]) * self.punch(m - 1)
        return sums

    def force(self, P, m=None):
        """``p h`` [N/m] at the nodes under the load `P` [N/m], carried by `m` pairs (default: those of `P`)."""
        m = self.pairs(P) if m is None else m
        force = self._sums[m].copy()
        force[self.cells(m)] += (P - self.start[m]) * self.punch(m)
        return force

    def pressure_at(self, P):
        """Contact pressure [Pa] at the nodes under the load `P` [N/m] (`force` over the cell width)."""
        return self.force(P) / self.h

    def half_width(self, P):
        """Contact half-width [m] under the load `P` [N/m]."""
        return float(self.contact.profile.half_width(P, self.contact.E_star)[0])

    def bulk_slip(self, sigma):
        """``s_sigma = sigma x / (2 E_star)`` [m], the relative displacement of the bulk tension `sigma` [Pa]."""
        return sigma * (self.x - self.contact.centre) / (2 * self.contact.E_star)

    def bulk_forces(self, m):
        """``G s_1`` [N/m per Pa]: the nodal forces of the `m` pairs held stuck under the relative displacement of
        a unit bulk tension (`bulk_slip` of 1 Pa), kept: those of ``sigma`` are ``sigma`` times them (`bulk_slip`
        is linear in ``sigma``)."""
        return _recent(self._bulk, m, lambda: self.stiffness(m).G @ self.bulk_slip(1.0)[self.cells(m)])

    def load(self, state):
        """The normal load [N/m] of `state` (the contact's where the state records none)."""
        return self.contact.P if state.P is None else state.P

    def forces(self, slip, Q, sigma, P, m=None):
        """Nodal forces ``g = h q`` [N/m] of the slip `slip` [m] under `Q`, `sigma`, `P` on `m` pairs."""
        m = self.pairs(P) if m is None else m
        nodes, g = self.cells(m), np.zeros(self.x.size)
        g[nodes] = Q * self.punch(m) - self.stiffness(m).G @ (slip[nodes] - self.bulk_slip(sigma)[nodes])
        return g

    def free_surface(self, slip, g, sigma, m):
        """`slip` [m] with the nodes out of the `m` pairs in contact given the relative displacement of
        the free surfaces there, under the nodal forces `g` [N/m] and the bulk tension `sigma` [Pa]."""
        nodes = self.cells(m)
        forces = np.zeros(self.x.size)
        forces[nodes] = g[nodes]
        # D g, D Toeplitz (`_kernel`): the correlation's N outputs of full overlap, each one dot product
        elastic = self.bulk_slip(sigma) - np.correlate(self._kernel, forces[::-1], "valid")
        shift = np.mean(slip[nodes] - elastic[nodes])
        out = np.ones(self.x.size, dtype=bool)
        out[nodes] = False
        return np.where(out, elastic + shift, slip)

    def at_rest(self, state):
        P = self.load(state)
        g = self.forces(state.slip, state.Q, state.sigma, P)
        zero = np.zeros(self.x.size)
        return NormalOutcome(g, zero, state.slip, 0.0, slid=state.slid, P=P, density=zero, locked=g)

    def increment(self, state, loads, guess=None):
        """The increment to the loads ``Q``, ``sigma``, ``P`` [N/m], solved in parts at the loads where cells enter
        or leave (`parts`), each on the cells in contact over it; the energy of a part is
        ``(f p_start h + f p_end h) |ds| / 2`` summed over its nodes (`slip_start`), the trapezoidal rule in ``P``
        (module docstring)."""
        after = (loads.Q, loads.sigma, loads.normal(self.contact))
        if abs(after[0]) >= self.sliding_force(after[2]):  # on the point of sliding
            return self.slide(state, loads, 0.0)
        return self._in_parts(state, after, guess)

    def _in_parts(self, state, after, guess=None, du=None):
        """The increment from `state` to the loads `after`, ``(Q, sigma, P)``, in parts (`increment`). `du`
        [m]: the loads are on the point of sliding (`slide`), and so is every part from the first that ends
        there, on the point of sliding under its own loads (`on_the_point`), then slid by its share of the
        uniform `du`, in proportion to its change of the loads: all of it in the last part where `state`
        does not slide in the direction of ``Q``."""
        if guess is None:
            guess = np.sign(state.slip - state.episode_start).astype(np.int8)
        before = (state.Q, state.sigma, self.load(state))
        locked = self.forces(state.slip, *before)
        slip, ds, density = state.slip, np.zeros(self.x.size), np.zeros(self.x.size)
        g, dissipation, P_begin, done = locked, 0.0, before[2], 0.0  # done: the fraction of the increment solved
        solved, m_before = None, None  # the part before, on m_before pairs: its G slip serves the next on as many
        sign = np.sign(after[0])
        sliding = du is not None and sign * before[0] >= self.sliding_force(before[2])  # every part slides
        for fraction, m in self.parts(before[2], after[2]):
            Q_, sigma_, P_ = (
                end if fraction == 1 else begin + fraction * (end - begin)
                for begin, end in zip(before, after, strict=True)
            )
            nodes, limit = self.cells(m), self.contact.f * self.force(P_, m)
            if du is not None and (sliding or fraction == 1):
                share = du * (fraction - done) if sliding else du
                solved = self._on_the_point(slip, sign, sigma_, m, limit, share)
            else:
                g_stuck = Q_ * self.punch(m) + sigma_ * self.bulk_forces(m)
                product = solved.product if m == m_before else None
                solved = solve_increment(self.stiffness(m), g_stuck, limit[nodes], slip[nodes], guess[nodes], product)
            g_begin, slip, g = g, slip.copy(), np.zeros(self.x.size)
            slip[nodes], g[nodes] = solved.slip, solved.g
            ds[nodes] += solved.ds
            start = slip_start(self.contact.f * self.force(P_begin, m)[nodes], np.abs(g_begin[nodes]), limit[nodes])
            mean = (start + limit[nodes]) / 2  # trapezoidal rule in P
            density[nodes] += mean / self.h * np.abs(solved.ds)
            dissipation += float(np.dot(mean, np.abs(solved.ds)))
            P_begin, done, m_before = P_, fraction, m
            slip = self.free_surface(slip, g, sigma_, m)
        edges = (True, True) if du is not None else self.edges_slip(before, after)
        slid = state.slid if du is None else state.slid + du
        return NormalOutcome(
            g, ds, slip, dissipation, slid=slid, P=after[2], density=density, edges=edges, locked=locked
        )

    #: The cells follow gross slip (`slide`), under a constant or a varying ``P``
    #: (docs/theory/displacement.md#sliding-sigma, #varying-load).
    slides = True

    def slide(self, state, loads, du):
        """`Outcome` of gross slip: the cells in contact on the point of sliding in the direction of ``loads.Q``
        under ``loads.sigma`` (`fretting.models.method4.on_the_point`), slid by the uniform `du` [m], the free
        surface outside them carried as by `increment`. Where the increment changes ``P``, in its parts
        (`_in_parts`), each part that slides ending on the point of sliding under its own load."""
        P = loads.normal(self.contact)
        if P != self.load(state):
            return self._in_parts(state, (loads.Q, loads.sigma, P), du=du)
        m, sign = self.pairs(P), np.sign(loads.Q)
        nodes, limit = self.cells(m), self.contact.f * self.force(P, m)
        slip = state.slip.copy()
        if (loads.Q, loads.sigma) == (state.Q, state.sigma):  # on the point of sliding already
            slip[nodes] += du
        else:
            slip[nodes] = self._on_the_point(state.slip, sign, loads.sigma, m, limit, du).slip
        g, ds = np.zeros(self.x.size), np.zeros(self.x.size)
        g[nodes], ds[nodes] = sign * limit[nodes], slip[nodes] - state.slip[nodes]
        locked = self.forces(state.slip, state.Q, state.sigma, self.load(state))
        density = limit / self.h * np.abs(ds)
        slip = self.free_surface(slip, g, loads.sigma, m)
        dissipation = float(np.dot(limit, np.abs(ds)))
        return NormalOutcome(
            g, ds, slip, dissipation, slid=state.slid + du, P=P, density=density, edges=(True, True), locked=locked
        )

    def _on_the_point(self, slip, sign, sigma, m, limit, du):
        """`Increment` (``slip``, ``ds``, ``g`` [m, m, N/m] at the `m` pairs in contact) of the increment from the nodal
        `slip` to the contact on the point of sliding in the direction `sign` of ``Q`` under `sigma` [Pa] and the
        nodal friction limits `limit` [N/m] (`fretting.models.method4.on_the_point`), slid by the uniform `du` [m]."""
        nodes, stiffness = self.cells(m), self.stiffness(m)
        load = sign * limit[nodes].sum() * self.punch(m) + sigma * self.bulk_forces(m) - sign * limit[nodes]
        after = on_the_point(stiffness, load, slip[nodes], sign) + du
        return Increment(after, after - slip[nodes], sign * limit[nodes], 0)

    def edges_slip(self, before, after):
        """Whether each edge of the contact (``x = -a``, ``x = a``) slips in the increment from the loads
        `before` to `after`, ``(Q, sigma, P)``: always where the contact recedes (its traction must vanish at
        the new edge), else where ``|dQ -/+ (pi a / 4) dsigma| > f dP``, the fully stuck traction increment
        (eqs 9, 20) exceeding ``f`` times the flat-punch pressure increment at that edge (Jaeger 1998)."""
        dQ, dsigma, dP = (b - a for a, b in zip(before, after, strict=True))
        moment = np.pi * self.half_width(after[2]) / 4 * dsigma
        return tuple(bool(dP < 0 or abs(dQ + side * moment) > self.contact.f * dP) for side in (-1, 1))

    def parts(self, P_from, P_to):
        """``(fraction, pairs)`` of the parts of the increment from `P_from` to `P_to` [N/m]: the end of each
        part as a fraction of the increment (the last is 1), and the pairs in contact over it (those of
        its middle load). Parts end where cells enter or leave, and at equal steps of ``P`` no larger
        than ``load_part`` of the smaller load."""
        low, high = sorted((P_from, P_to))
        count = int(np.ceil((high - low) / (self.spec.load_part * low)))
        even = low + (high - low) * np.arange(1, count) / count
        crossed = np.union1d(self.start[2:][(self.start[2:] > low) & (self.start[2:] < high)], even)
        ends = np.concatenate([crossed[:: 1 if P_to > P_from else -1], [P_to]])
        begins = np.concatenate([[P_from], ends[:-1]])
        fractions = np.ones(ends.size)
        fractions[:-1] = (ends[:-1] - P_from) / (P_to - P_from)
        return [(float(u), self.pairs((b + e) / 2)) for u, b, e in zip(fractions, begins, ends, strict=True)]

    def traction(self, outcome):
        """Shear traction [Pa]: the nodal forces over the cell width."""
        return outcome.g / self.h

    def stick_zones(self, outcome, state):
        """Stick intervals in ``t = (x - centre) / a`` of the contact formed, within the contact of the
        increment's load. A node whose episode slip is within `ROUNDING` of the largest is stuck. An end between a
        stuck and a slipping node is `kink_end`, from the traction
        deficit of one and the slip of the other, unless the slip zone has reached a former edge
        (`pinned`): there it is extrapolated from the slip of two slipping nodes
        (`fretting.models.method4.extrapolated_end`). An end at the outermost node in contact is `edge_end`."""
        m = self.pairs(outcome.P)
        nodes, a = self.cells(m), self.half_width(outcome.P)
        t = (self.x[nodes] - self.contact.centre) / a
        limit, g = self.contact.f * self.force(outcome.P, m)[nodes], outcome.g[nodes]
        locked = np.divide(outcome.locked[nodes], limit, out=np.zeros(t.size), where=limit > 0)

        def deficit(node):
            """``f p - q`` [Pa] against the limit of the sign of the traction at `node` (the slip zone's)."""
            return (limit - np.sign(g[node]) * g) / self.h

        def located(position, d, slipping, beyond):
            stuck = 2 * slipping - beyond
            if pinned(np.sign(g[slipping]) * locked, stuck, slipping, beyond):
                end = extrapolated_end(position, d, slipping, beyond)
                if end is not None:
                    return end
            return kink_end(position * a, d, deficit(slipping), stuck, slipping, self.contact.E_star) / a

        episode = (outcome.slip - state.episode_start)[nodes]
        episode = np.where(np.abs(episode) > ROUNDING * np.max(np.abs(episode), initial=0.0), episode, 0.0)
        zones = stick_zones(t, episode, located)
        outer = (0, t.size - 1)
        zones = [
            tuple(
                edge_end(t, deficit(node), side) if bound == side and slips else bound
                for bound, side, slips, node in zip(zone, (-1.0, 1.0), outcome.edges, outer, strict=True)
            )
            for zone in zones
        ]
        scale = a / self.contact.a
        return [(start * scale, end * scale) for start, end in zones]

    def delta_Q(self, outcome):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m]: the slip weighted by the flat punch of unit load."""
        m = self.pairs(outcome.P)
        return float(np.dot(self.punch(m), outcome.slip[self.cells(m)]))

    def delta_sigma(self, outcome):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2]: ``pi / 4`` of the flat punch's moment of the slip."""
        m = self.pairs(outcome.P)
        x = self.x[self.cells(m)] - self.contact.centre
        return float(np.pi / 4 * np.dot(self.punch(m), outcome.slip[self.cells(m)] * x))


def _recent(kept, key, compute, limit=math.inf, size=None, alone=False):
    """``kept[key]``, computed by `compute()` where `kept` (a dict, least recently used first) lacks it, and
    moved to the end. A new value first drops the least recently used while, with it, they would number (or,
    by `size`, a function of a value, measure) more than `limit`; one over `limit` by itself is kept alone
    where `alone` (its caller asks for it again), else not kept."""
    value = kept.pop(key, None)
    if value is None:
        value = compute()
        while kept and _measure(kept.values(), size) + _measure([value], size) > limit:
            del kept[next(iter(kept))]
    if alone or _measure([value], size) <= limit:
        kept[key] = value
    return value


def _measure(values, size):
    """How many `values` there are, or the sum of their `size` (`_recent`)."""
    return len(values) if size is None else sum(map(size, values))


def _unit_load(column):
    """``b / beta`` [-]: the nodal forces of a unit load on the cells of the Toeplitz flexibility ``D`` of first
    column `column` that move them rigidly, ``b = D^-1 1`` over its sum (a flat punch; Levinson)."""
    b = linalg.solve_toeplitz(column, np.ones(column.size))
    return b / b.sum()


def slip_start(begin, carried, end):
    """The friction limit [N/m] at which a node starts to slip in a part of an increment: that at the part's
    start, `begin`, but where the limit falls no more than the force the node `carried` then (a stuck node
    slips once the falling limit reaches its traction), nor less than that at its end, `end`."""
    return np.minimum(begin, np.maximum(carried, end))


def kink_end(x, slip, deficit, stuck, slipping, E_star):
    """Stick/slip boundary [m] between the stuck node `stuck` and its neighbour `slipping` (positions `x` [m]).

    Near a boundary ``c`` the traction of the stick zone falls short of its limit by ``K sqrt(|x - c|)``
    (`deficit`, ``f p - s q`` [Pa] with ``s = +/-1`` the sign of the slip zone's traction ``s f p``: the
    square-root kink), and the slip since the episode began grows in
    the slip zone as ``(4 K / (3 E_star)) |x - c|^(3/2)``: the slip gradient of the kink is
    ``(2 / (pi E_star))`` times its Hilbert transform, ``-pi K sqrt(|x - c|)`` (eq 19 for
    Cattaneo-Mindlin). The deficit of one node and the slip `slip` [m] of the other eliminate ``K``:
    with ``w = |c - x_stuck| / h``, ``h`` their spacing, ``(1 - w)^3 = rho^2 w``, ``rho = 3 E_star |slip| /
    (4 deficit h)``, whose one root in ``[0, 1]`` is found by Brent's method. Local to one spacing, it
    holds for slip zones narrower than two spacings, where an extrapolation of the slip alone has one node.
    """
    h = x[slipping] - x[stuck]
    if deficit[stuck] <= 0:
        return float(x[stuck])
    rho = 3 * E_star * abs(slip[slipping]) / (4 * deficit[stuck] * abs(h))
    w = optimize.brentq(lambda w: (1 - w) ** 3 - rho**2 * w, 0.0, 1.0)
    return float(x[stuck] + w * h)


def pinned(locked, stuck, slipping, beyond):
    """Whether the slip zone that ends between the nodes `stuck` and `slipping` has reached a former edge.

    `locked` is the traction locked in before the increment over the limit ``f p`` of the
    increment's load, signed so that the slip zone's traction is +1. A former edge of the contact
    (the contact receded to it, or grew on from it under another ratio of shear to normal load)
    leaves a trough in it: outside, the traction of the band that entered after, from zero;
    inside, the limit traction of the edge then, rising as the pressure did,
    ``sqrt(|x - x_edge|)``. The trough lies at the slipping node, ``locked`` rising both into
    the slip zone (`beyond`) and into the stick zone (`stuck`). Its steep inner rise is carried
    over into the stick zone's traction, so the stuck node's deficit is not the kink's
    ``K sqrt(|x - c|)`` that `kink_end` reads; the slip, zero on the stuck side whatever was
    locked in, still grows from the end by its own law (`NormalModel.stick_zones`).
    """
    if not 0 <= beyond < locked.size:
        return False
    return bool(locked[beyond] > locked[slipping] < locked[stuck])


def edge_end(t, deficit, side):
    """End on `side` (-1 or +1) of a stick zone that reaches the outermost node in contact, in ``t = x / a``,
    where that edge slips in the increment (`NormalModel.edges_slip`).

    Its slip zone then lies between that node and the contact edge ``t = side``, narrower than a cell
    (as a receding edge leaves it), with no slipping node: ``deficit^2`` (`kink_end`; against the limit
    of the sign of the outermost node's traction, which leans towards the edge's slip zone) is extrapolated
    linearly to zero from the two outermost nodes (`fretting.models.method4.deficit_end`), within
    ``[t_outer, side]``. Where the deficit does
    not fall outwards (a step that moves the edge by several cells leaves the outermost node far
    from its limit) nothing places the end: it is the middle of ``[t_outer, side]``, as
    `fretting.models.method4.stick_zones` takes the middle between two nodes it cannot tell apart.
    The end is the edge itself where the node lies at or beyond it.
    """
    outer, inner = (t.size - 1, t.size - 2) if side > 0 else (0, 1)
    if side * t[outer] >= 1:
        return side
    estimate = deficit_end(t, deficit, outer, inner)
    if estimate is None:
        return float((t[outer] + side) / 2)
    return float(np.clip(estimate, *sorted((t[outer], side))))


def slip_to_traction(column, punch, first=None):
    """``G = B - b b^T / beta`` of the symmetric positive definite Toeplitz matrix ``D`` of first column
    `column` (an even number ``n`` of cells), ``B = D^-1``, ``b = B 1``, ``beta = 1^T b`` (module docstring),
    in ``O(n^2)``, given ``punch = b / beta`` (`NormalModel.punch`) and, if known, the first column `first` of
    ``B`` (`NormalModel.inverse_column`; else one Levinson solve): the `whole` of its `half_stiffness`."""
    return whole(half_stiffness(column, punch, first))


def whole(half):
    """The persymmetric ``G`` (``G[n - 1 - i, n - 1 - j] = G[i, j]``, in the units of `half`) whose first
    ``n / 2`` rows are `half`, of shape ``(n / 2, n)``."""
    n = half.shape[1]
    G = np.empty((n, n))
    G[: n // 2] = half
    G[n // 2 :] = half[::-1, ::-1]
    return G


def half_stiffness(column, punch, first=None):
    """The first ``n / 2`` rows of `slip_to_traction`'s ``G``, ``(n / 2, n)`` (arguments as there).

    ``B`` by Trench's recursion (Trench 1964; Gohberg & Semencul 1972): with ``v`` the first column of
    ``B``, ``B[i + 1, j + 1] = B[i, j] + (v[i + 1] v[j + 1] - v[n - 1 - i] v[n - 1 - j]) / v[0]``, one
    row from the row before; ``v`` is one Levinson solve. Each row of ``B`` is kept only until the next
    is formed, and written to ``G`` less ``c_i c``, ``c = b / sqrt(beta) = sqrt(beta) punch``, with
    ``beta = 1 / (D punch)_0`` (``D punch = 1 / beta`` at every node). ``G`` is symmetric and
    persymmetric (``G[i, j] = G[n - 1 - i, n - 1 - j]``), as ``D`` is, so the recursion forms only the
    entries ``i + j <= n - 1`` of the first ``n / 2`` rows and the rest are copies of them: ``G`` is
    exactly symmetric and persymmetric. The products are taken of ``w = v / sqrt(v[0])`` and of ``c``,
    so that each term is symmetric in ``i, j`` to the last bit.
    """
    n = column.size
    if n % 2:
        raise ValueError(f"column must have an even number of entries, found {n}")
    if first is None:
        first = linalg.solve_toeplitz(column, np.eye(n, 1)[:, 0])
    G = np.empty((n // 2, n))
    _trench_rows(first, first / np.sqrt(first[0]), punch / np.sqrt(column @ punch), G)
    return G


@njit
def _trench_rows(first, w, c, G):
    """Write into `G` (``(n / 2, n)``) the rows of `half_stiffness` from the first column `first` of ``B``, ``w =
    first / sqrt(first[0])`` and ``c = sqrt(beta) punch``: row ``i`` of ``B`` from row ``i - 1`` (Trench's
    recursion), less ``c_i c``, its entries ``j >= n - i`` copied from ``G[n - 1 - j, n - 1 - i]``. Compiled: a
    varying load forms a stiffness for many of the contacts it meets, and row by row in numpy the calls cost
    more than the arithmetic."""
    n = first.size
    row, previous = first.copy(), np.empty(n)
    for i in range(n // 2):
        width = n - i  # the entries i + j <= n - 1 of row i
        if i:
            row, previous = previous, row
            row[0] = first[i]
            for j in range(1, width):
                row[j] = w[j] * w[i] - w[width] * w[n - j] + previous[j - 1]
            for j in range(width, n):
                G[i, j] = G[n - 1 - j, n - 1 - i]
        for j in range(width):
            G[i, j] = c[j] * -c[i] + row[j]


class CellSurfaceStress(SurfaceStress):
    """``sigma_xx`` [Pa] along the surface of either body at the centres `t` of equal cells, ``(x - centre) / a``.

    The formula of `fretting.physics.surface.SurfaceStress` (Johnson 1985, section 2.3) with the
    traction constant on each cell, whose principal value is exact:
    ``(2/pi) int_cell dxi / (xi - x_i) = (2/pi) ln|(k + 1/2) / (k - 1/2)|`` for the cell ``k``
    cells from the node (zero on its own cell). At the stick ends, as there, the slip's fitted gradient
    (`SurfaceStress.at_stick_ends`), among the cells in contact under the step's pressure (`in_contact`).
    """

    def __init__(self, t):
        N = t.size
        k = np.arange(1 - N, N, dtype=float)
        column = 2 / np.pi * np.log(np.abs((k + 0.5) / (k - 0.5)))
        self._t = t
        self._kernel = linalg.toeplitz(column[N - 1 :], column[N - 1 :: -1])  # [j, i]: cell j at node i

    def of_traction(self, q):
        """``-(2/pi) PV int q(xi) / (x - xi) dxi`` [Pa] at the cell centres, of `q` [Pa] constant on each cell."""
        return q @ self._kernel

    def away_from_ends(self, q, p, slip, sigma, modulus):
        """`SurfaceStress.away_from_ends`: in contact ``sigma / 2 - modulus ds/dt`` (the module docstring's law of
        the slip differentiated: ``ds/dx = (2 / (pi E_star)) PV int q / (x - xi) dxi + sigma / (2 E_star)``),
        ``ds/dt`` by second-order differences over the cells in contact, where the principal value of the
        traction's constant cells misses the square roots at the stick ends and the edges (accuracy:
        benchmarks/surface_stress.py, tests/analysis/test_nucleation.py); outside, `of_traction`."""
        stress = np.array(self.of_traction(q), dtype=float, ndmin=2)
        rows = np.broadcast_to(np.asarray(p, dtype=float), stress.shape)
        slips, tensions = np.broadcast_to(slip, stress.shape), np.broadcast_to(sigma, (stress.shape[0], 1))
        for row, (pressure, s, tension) in enumerate(zip(rows, slips, tensions[:, 0], strict=True)):
            lower, upper = self.in_contact(pressure)
            if upper - lower >= 3:
                gradient = np.gradient(s[lower:upper], self._t[lower:upper], edge_order=2)
                stress[row, lower:upper] = tension / 2 - modulus * gradient
        return stress.reshape(np.shape(q))

    def in_contact(self, p):
        """The first cell and the one past the last under the pressure `p` [Pa]: the relative displacement of the
        surfaces outside has a square root at the contact's edges, which differences across them do not resolve."""
        inside = np.flatnonzero(p > 0)
        return (int(inside[0]), int(inside[-1]) + 1) if inside.size else (0, 0)
