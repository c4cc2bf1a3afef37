"""A varying normal load and shear on a symmetric contact, exactly: Jaeger's superposition at fixed nodes.

Where ``P`` varies with ``Q`` and no ``sigma`` on a symmetric profile whose contact grows with the load (Hertz, the
rounded flat), every band of the contact remembers the ratio
of the shear to the normal load it carries, and an increment moves that memory in closed form
(`fretting.physics.superposition`; Jaeger 1998, Barber, Davies & Hills 2011). This model keeps the memory as
the state's (`State.memory`, recorded as ``state_bands``: the band edges over ``a``, then their ratios) and gives the
fields at nodes fixed in ``x``, the cells of `fretting.models.normal.Varying` over the history's largest
contact: the slip and the traction there, the slip and the energy density of each increment integrated
over its slipping phases, the stick zone and the energy of the increment exactly
(docs/theory/normal-load.md#jaegers-superposition).

Method 4 on those cells (`Varying`) converges to it at every step (tests/models/test_jaeger.py,
benchmarks/varying_accuracy.py), and runs where this model does not: with ``sigma`` and on other profiles.
Under a prescribed displacement the contact may slide whole (`JaegerModel.slide`), as on the cells.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fretting.errors import GrossSlipError
from fretting.models.base import Model, ModelSpec
from fretting.models.normal import DEFAULT_CELLS, CellFields, NormalOutcome, Varying, cell_centres
from fretting.physics.superposition import Memory, Superposition, geometry

if TYPE_CHECKING:
    from fretting.loading.history import History
    from fretting.physics.contact import Contact

__all__ = ["Jaeger", "JaegerModel"]


@dataclass(frozen=True, eq=False, repr=False)  # ModelSpec.__repr__
class Jaeger(ModelSpec):
    """The exact model of a varying ``P`` and ``Q`` on a symmetric contact that grows with the load, its fields at
    `cells` cell centres.

    Parameters
    ----------
    cells : int
        Cells over ``[-A, A]``, even, at least 8 (as `Varying`'s).
    half_width : float, optional
        ``A`` [m], the half-width of the largest contact (resolved for a history by `resolved_for`).
    """

    cells: int = DEFAULT_CELLS
    half_width: float | None = None

    name: ClassVar[str] = "jaeger"
    inputs: ClassVar[frozenset[str]] = frozenset({"Q", "sigma", "P"})
    memory_variable: ClassVar[str] = "state_bands"
    description: ClassVar[str] = (
        "the exact model of a varying P and Q without sigma: Jaeger's superposition of flat punches, at fixed nodes"
    )

    def __post_init__(self):
        Varying(self.cells, self.half_width)  # the same cells: the same checks

    @property
    def resolved(self) -> bool:
        return self.half_width is not None

    def resolved_for(self, contact: Contact, history: History | None) -> Jaeger:
        """This spec over the largest contact of `history` (`Varying.resolved_for`)."""
        return (
            self if self.resolved else Jaeger(self.cells, Varying(self.cells).resolved_for(contact, history).half_width)
        )

    def build(self, contact: Contact) -> JaegerModel:
        return JaegerModel(contact, self)

    def is_default(self) -> bool:
        return self.cells == DEFAULT_CELLS

    def attributes(self) -> dict:
        spans = {} if self.half_width is None else {"half_width": float(self.half_width)}
        return {"model": self.name, "cells": int(self.cells)} | spans

    def holds_for(self, contact: Contact, history: History | None) -> str | None:
        if not contact.profile.grows_with_load():
            return f"{contact.profile!r} is not a symmetric profile whose contact grows with the load"
        if history is not None and history.largest_loads()[1] > 0:
            return "the history has a bulk tension sigma"
        return Varying(self.cells, self.half_width).holds_for(contact, history)

    @classmethod
    def from_record(cls, attrs: dict, theta: np.ndarray | None) -> Jaeger:
        return cls(int(attrs["cells"]), float(attrs["half_width"]))


class JaegerModel(CellFields, Model):
    """Jaeger's superposition on a symmetric contact, at the cell centres of a resolved `Jaeger` spec (module
    docstring). Its memory (`Outcome.memory`) is `fretting.physics.superposition.Memory.flat`."""

    theta = None
    linear_algebra = False

    def __init__(self, contact, spec):
        self.contact, self.spec = contact, spec
        self.h, self.x, self.t = cell_centres(contact, spec.cells, spec.half_width)
        self.friction_force = np.inf  # f P at each step: the engine checks the load of the step
        self.geometry = geometry(contact.profile, contact.E_star, contact.f)

    def _contact(self, state):
        """The `Superposition` of `state`: its loads and its memory (None: the contact just formed)."""
        P = self.contact.P if state.P is None else state.P
        memory = Memory.from_flat(state.memory, self.geometry, self.contact.a) if state.memory else None
        return Superposition(self.geometry, P, state.Q, memory)

    def _outcome(self, superposition, ds, dissipation, density, zone, slid):
        """The fields of the memory as the state keeps it (`Memory.flat`), so that a run continued from the state
        gives the same at its first step, the slip offset by the uniform slide `slid` [m] of the contact; `zone`:
        the half-width [m] of the stick zone (None: none is left, the contact slides)."""
        flat, X = superposition.memory.flat(self.contact.a), self.x - self.contact.centre
        memory = Memory.from_flat(flat, self.geometry, self.contact.a)
        return NormalOutcome(
            memory.traction(X),
            ds,
            memory.slip(X) + slid,
            dissipation,
            slid=slid,
            memory=flat,
            zones=[] if zone is None else [(-zone / self.contact.a, zone / self.contact.a)],
            P=superposition.P,
            density=density,
        )

    def at_rest(self, state):
        superposition, zero = self._contact(state), np.zeros(self.x.size)
        return self._outcome(superposition, zero, 0.0, zero, superposition.memory.a, state.slid)

    def increment(self, state, loads, guess=None):
        """The increment to the loads ``Q``, ``P`` [N/m] (`Superposition.advance`): its slip and energy density at
        the nodes, summed over its slipping phases (`Phase.at`); exactly zero slip where a node stuck. At ``|Q| =
        f P``, the contact on the point of sliding (`slide`). The loads' ``sigma`` must be zero."""
        if abs(loads.Q) >= self.sliding_force(loads.normal(self.contact)):
            return self.slide(state, loads, 0.0)
        return self._advanced(state, loads, loads.Q, 0.0)

    #: The contact follows gross slip under displacement control (`slide`).
    slides = True

    def slide(self, state, loads, du):
        """`Outcome` of gross slip: the increment to ``Q = +-f P`` of the loads' ``P``, where every band of the
        memory is at the limit, then the uniform slide `du` [m] (the sign of ``Q``) of the contact. The slide
        dissipates ``f P |du|`` under the step's end load, or ``f (P_begin + P_end) |du| / 2`` (the trapezoidal rule
        in ``P``) where the contact slid that way already at the step's beginning, as `Varying` takes it."""
        P = loads.normal(self.contact)
        return self._advanced(state, loads, np.copysign(self.sliding_force(P), loads.Q), du)

    def _advanced(self, state, loads, Q, du):
        """The increment from `state` to `Q` [N/m] and the loads' ``P``, then slid by `du` [m] (`slide`)."""
        if loads.sigma:
            raise ValueError(f"sigma = {loads.sigma!r} Pa: Jaeger's superposition holds without a bulk tension")
        superposition, P = self._contact(state), loads.normal(self.contact)
        try:
            step = superposition.advance(P, Q)
        except ValueError:
            raise GrossSlipError(None, loads.Q, loads.sigma, self.contact.f * P) from None
        X = self.x - self.contact.centre
        ds, density = np.zeros(self.x.size), np.zeros(self.x.size)
        for phase in step.phases:
            slip, w = phase.at(X)
            ds += slip
            density += w
        if not du:
            zone = superposition.memory.a if step.stick is None else step.stick
            return self._outcome(superposition, ds, step.energy, density, zone, state.slid)
        slide, slide_density, slide_energy = self._slid(state, P, Q, du)
        energy = step.energy + slide_energy
        return self._outcome(superposition, ds + slide, energy, density + slide_density, None, state.slid + du)

    def _slid(self, state, P, Q, du):
        """``(ds, w, W)`` of the uniform slide `du` [m] of the contact at the load `P` [N/m] in the direction of `Q`:
        ``du`` at the nodes in contact, ``f p |du|`` [J/m^2] there and ``f P |du|`` [J/m], the pressure and the load
        the mean of the step's ends where the contact slid that way at its beginning (`slide`)."""
        P_begin = self.contact.P if state.P is None else state.P
        already = np.sign(Q) * state.Q >= self.sliding_force(P_begin)
        p = self.pressure_at(P)
        inside = p > 0
        mean = (self.pressure_at(P_begin) + p) / 2 if already else p
        load = (P_begin + P) / 2 if already else P
        return (
            np.where(inside, du, 0.0),
            self.contact.f * mean * np.where(inside, abs(du), 0.0),
            self.contact.f * load * abs(du),
        )

    def traction(self, outcome):
        """Shear traction [Pa] at the nodes (the memory's, exact)."""
        return outcome.g

    def stick_zones(self, outcome, state):
        """The stick zone ``[-c, c]`` in ``t`` of the increment: the innermost point that slipped (the contact where
        it slipped nowhere; none where it slid whole)."""
        return outcome.zones

    def delta_Q(self, outcome):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m]: the memory's (`Memory.delta_Q`, of ``s - s(0)``) and the uniform
        slide of the contact, ``s(0)``."""
        return Memory.from_flat(outcome.memory, self.geometry, self.contact.a).delta_Q() + outcome.slid

    def delta_sigma(self, outcome):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2]: zero, the slip being even in ``x``."""
        return 0.0

    def pressure_at(self, P):
        """The pressure [Pa] at the nodes under the load `P` [N/m] (`Geometry.pressure`)."""
        return self.geometry.pressure(self.x - self.contact.centre, P)
