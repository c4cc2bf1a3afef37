"""The spec `Mesh` and its `GalerkinModel`: method 4 by P1 Galerkin on a mesh in ``theta``.

The stiffness is `fretting.models.galerkin.kernels`'; the loads, friction limits and the nodal
traction are `fretting.models.galerkin.quadrature`'s; the mesh of a history is
`fretting.models.galerkin.adaptation`'s.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from fretting._validate import positive
from fretting.models.base import ModelSpec
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.galerkin.adaptation import MeshTooLarge, adapted_model, refined_for
from fretting.models.galerkin.kernels import kernel_means, stiffness_of_means
from fretting.models.galerkin.mesh import DEFAULT_RTOL, ENERGY_SPAN, SMALLEST_ELEMENT, located_end
from fretting.models.galerkin.quadrature import (
    assemble,
    hat_cos_integrals,
    pressure_breakpoints,
    pressure_moments,
    recovery,
)
from fretting.models.method4 import Method4Model

if TYPE_CHECKING:
    from fretting.physics.contact import Contact

__all__ = ["CAPPED", "MAX_DEFAULT_MESH", "MAX_DEFAULT_WORK", "GalerkinModel", "Mesh"]

#: Nodes at which the default's adaptation to the energy stops (`Mesh.default_model`); past it the
#: last mesh within the bound runs.
MAX_DEFAULT_MESH = 4 * DEFAULT_NODES

#: The default's bound of ``N^2 x increments`` of a run on the mesh of ``N`` nodes that locates the
#: recorded steps' stick ends (`fretting.models.galerkin.mesh.BOUNDARY_SPAN`): an increment costs about
#: ``N^2`` (products with the stiffness), and those meshes reach a few thousand nodes on general
#: Q/sigma histories (benchmarks/trajectories.py prints each with its nodes and run time). The bound
#: takes in every history of that benchmark; past it (long histories) the mesh adapted to the energy
#: runs.
MAX_DEFAULT_WORK = 3e9

#: What the reason of every mesh the default capped at its bounds says (`Mesh.default_model`); a state
#: of such a mesh is continued on it as it is (`Mesh.continued`). Other notes of a mesh's spec (the
#: increments below the solver's floor, an energy that could not settle) leave it refined for
#: the loads that continue it.
CAPPED = "over the default's bound of"


@dataclass(frozen=True, eq=False, repr=False)  # ModelSpec.__repr__
class Mesh(ModelSpec):
    """Method 4 by P1 Galerkin on a mesh in ``theta``: the mesh `theta` as given, or one adapted to
    the history so that the energy of each increment is right to `rtol` (resolved for a history by
    `model_for`).

    Parameters
    ----------
    rtol : float, optional
        Relative accuracy asked of the energy (`DEFAULT_RTOL` when neither is given).
    theta : array_like, optional
        Mesh nodes [rad], strictly increasing from 0 to pi.
    fallback : str, optional
        Why the mesh, or the energy on it, is coarser than `rtol` asks: the adaptation of a default
        stopped at one of its bounds (`MAX_DEFAULT_MESH`, `MAX_DEFAULT_WORK`; the reason holds
        `CAPPED`), an energy that could not settle, or increments below the solver's floor, slipping
        again too little or held stuck by its rounding allowance
        (`fretting.models.galerkin.adaptation`). None: the mesh is the one asked for.
    sample : str, optional
        What the adaptation ran when it ran a sample of a long history's turning points instead of
        all of them (`fretting.models.galerkin.adaptation.SAMPLE_TURNS`). None: it ran them all.
    """

    rtol: float | None = None
    theta: np.ndarray | None = None
    fallback: str | None = None
    sample: str | None = None

    name: ClassVar[str] = "mesh"
    recorded_as: ClassVar[tuple[str, ...]] = (
        "method 4: dislocation correction to the fully adhered solution, "
        "P1 Galerkin in theta on a mesh adapted to rtol",
    )
    description: ClassVar[str] = "method 4: dislocation correction to the fully adhered solution, P1 Galerkin in theta"

    def __post_init__(self):
        if self.theta is not None:
            object.__setattr__(self, "theta", _validated_mesh(self.theta))
        elif self.rtol is None:
            object.__setattr__(self, "rtol", DEFAULT_RTOL)
        if self.rtol is not None:
            object.__setattr__(self, "rtol", positive("rtol", self.rtol))

    @property
    def resolved(self) -> bool:
        return self.theta is not None

    def build(self, contact: Contact, previous: GalerkinModel | None = None) -> GalerkinModel:
        return GalerkinModel(contact, self, previous)

    def holds_for(self, contact, history):
        """A mesh still to adapt needs the ``Q`` of every step before the run, which a history of
        ``delta`` finds step by step (`fretting.engine.follow.displaced`)."""
        if not self.resolved and history is not None and history.displaced:
            return "the mesh adapts to the Q of every step, which a history of delta finds only as it runs"
        return None

    def model_for(self, contact, history, run, recorded=None):
        """The model on this mesh, or on the mesh adapted to `history` where it is not given
        (`fretting.models.galerkin.adaptation.adapted_model`, which locates the stick ends of the
        steps `recorded`, None: all)."""
        if self.resolved:
            return self.build(contact)
        return adapted_model(self, contact, history, run, recorded=recorded)

    def default_model(self, contact, history, run, recorded=None):
        """`model_for` within the default's bounds: where the energy's mesh would need more than
        `MAX_DEFAULT_MESH` nodes, the last mesh of the adaptation within that bound; where the run on
        the ends' mesh would cost more than `MAX_DEFAULT_WORK`, the energy's mesh; each with the
        reason in `fallback`."""
        try:
            return adapted_model(self, contact, history, run, MAX_DEFAULT_MESH, recorded, MAX_DEFAULT_WORK)
        except MeshTooLarge as error:
            model = error.model
            notes = model.spec.fallback  # the solver's floor, where the ends' stage counted it
            reason = _capped(error, model.theta.size, self.rtol)
            model.spec = replace(model.spec, fallback=reason if notes is None else f"{reason}; {notes}")
            return model

    def continued(self, contact, state, history, run):
        """A mesh adapted to an ``rtol`` is refined where the loads of `history` need it
        (`fretting.models.galerkin.adaptation.refined_for`); a mesh given as it is, or one the default
        capped (`CAPPED`: its ``fallback`` stays true of it), goes on as it is."""
        if self.rtol is None or CAPPED in (self.fallback or ""):
            return None, state
        return refined_for(contact, state, history, run)

    def is_default(self) -> bool:
        return self.rtol == DEFAULT_RTOL

    def attributes(self) -> dict:
        attributes = {"model": self.name} | ({} if self.rtol is None else {"rtol": self.rtol})
        notes = {"model_fallback": self.fallback, "model_sample": self.sample}
        return attributes | {key: note for key, note in notes.items() if note is not None}

    @classmethod
    def from_record(cls, attrs: dict, theta: np.ndarray | None) -> Mesh:
        return cls(attrs.get("rtol"), theta, attrs.get("model_fallback"), attrs.get("model_sample"))


def _capped(error, nodes, rtol):
    """The reason [str] that a default's mesh of `nodes` nodes was capped by the `MeshTooLarge` `error`."""
    if error.change is not None:
        return (
            f"{error}, {CAPPED} {MAX_DEFAULT_WORK:.2g}: runs the mesh before it, {nodes} nodes, whose energy per "
            f"cycle changed by up to {error.change:.1e} of itself from the mesh before that (rtol = {rtol:g})"
        )
    if error.ends is not None:
        return (
            f"{error}, {CAPPED} {MAX_DEFAULT_WORK:.2g}: runs the mesh adapted to the energy, {nodes} nodes, whose "
            f"stick ends between turning points err by up to about {ENERGY_SPAN * rtol:g} a"
        )
    return (
        f"{error}, {CAPPED} {MAX_DEFAULT_MESH}: runs the last mesh within it, {nodes} nodes, "
        f"coarser than rtol = {rtol:g} asks"
    )


class GalerkinModel(Method4Model):
    """A contact discretised by P1 Galerkin on the mesh of a resolved `Mesh`; every per-node array
    in ascending ``x``, i.e. descending ``theta``.

    Parameters
    ----------
    contact : Contact
    spec : Mesh
        Resolved: its ``theta`` [rad], strictly increasing from 0 to pi, shape (M + 1,).
    previous : GalerkinModel, optional
        A model whose mesh shares elements with `theta` (one that `refine` bisected): its means
        over the pairs of shared elements are reused, and the model is the same, bit for bit, as
        without it (`stiffness`).

    Attributes
    ----------
    theta : ndarray, shape (N,)
        The mesh as given [rad], ascending in ``theta``.
    x, t : ndarray, shape (N,)
        Node positions [m] and ``(x - centre)/a`` [-], ascending.
    G : ndarray, shape (N, N)
        Stiffness ``K_kl = B(phi_k, phi_l)`` [Pa]: ``g = F - G s`` with ``g_k = int q phi_k dx``.
    limit : ndarray, shape (N,)
        ``L_k = int f p phi_k dx`` [N/m].
    friction_force : float
        ``sum_k L_k`` [N/m]: ``f P`` up to the quadrature of `limit`, since the hats sum to 1.
        The engine takes gross slip from the smaller of this and ``f P``.
    breakpoints : ndarray
        Angles [rad] where the pressure has a singular derivative (the profile's `breakpoints`
        inside the contact), for `element_targets`.
    """

    def __init__(self, contact, spec, previous=None):
        theta = spec.theta
        self.spec = spec
        self.contact = contact
        self.theta = theta
        a = contact.a
        order = slice(None, None, -1)  # theta descending: x ascending
        self.t = np.cos(theta[order])
        self.t[0], self.t[-1] = -1.0, 1.0
        self.x = contact.centre + a * self.t
        self.kernel_means = kernel_means(theta[:-1], theta[1:], previous)  # for the model of a refined mesh
        self.G = stiffness_of_means(self.kernel_means[order, order], contact.E_star)
        cos_integral = hat_cos_integrals(theta)
        self._dQ = (assemble(np.diff(theta) / 2, np.diff(theta) / 2) / np.pi)[order]
        self._dsig = (a / 4 * cos_integral)[order]
        moments = pressure_moments(contact, theta)
        self.limit = (contact.f * a * moments[0])[order]
        self.friction_force = float(self.limit.sum())
        self.breakpoints = pressure_breakpoints(contact)
        self._fp = contact.f * contact.pressure(self.x)
        stencil, weights = recovery(theta, moments)
        self._stencil, self._recovery_weights = theta.size - 1 - stencil[order], weights[order]

    @property
    def nodes(self):
        """Number of nodes ``N = M + 1``."""
        return self.theta.size

    def g_stuck(self, Q, sigma):
        """``F_k = int q_st phi_k dx`` [N/m] of the fully stuck traction, eqs (9) and (20)."""
        return Q * self._dQ + sigma * self._dsig

    def traction(self, outcome):
        """Shear traction [Pa] at the nodes after `outcome` (`nodal_traction` of its ``g``, ``ds``)."""
        return self.nodal_traction(outcome.g, outcome.ds)

    def nodal_traction(self, g, ds=None):
        """Shear traction [Pa] at the nodes, from its hat moments `g` [N/m] (rows of a 2-D `g`).

        ``g_k / L_k`` is the mean of the utilisation ``u = q / (f p)`` under ``f p phi_k dx``;
        the quadratic in ``theta`` with the means of three neighbouring nodes gives its nodal
        value to ``O(h^3)`` where ``u`` is smooth (a mean itself is off by ``O(h)`` where
        neighbouring elements differ in size). It is clipped to ``[-1, 1]`` and, where the slip
        increment `ds` [m] is given and non-zero, set to ``sign(ds)``: ``q = u f p(x)`` then
        keeps Coulomb's law exactly at every node. At the contact edges ``p(x) = 0`` (as
        `Contact.pressure` has it), so ``q = 0`` there, also for the sharp flat punch whose
        edge traction is unbounded.
        """
        utilisation = np.clip(
            np.sum((np.asarray(g) / self.limit)[..., self._stencil] * self._recovery_weights, axis=-1), -1, 1
        )
        if ds is not None:
            utilisation = np.where(ds != 0, np.sign(ds), utilisation)
        return utilisation * self._fp

    def delta_Q(self, outcome):
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] of the slip after `outcome`, exact for P1.

        A row-wise sum, not a matrix product, so that a row's value does not depend on how many
        rows there are.
        """
        return np.sum(outcome.slip * self._dQ, axis=-1)

    def delta_sigma(self, outcome):
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2] of the slip after `outcome`, exact for P1."""
        return np.sum(outcome.slip * self._dsig, axis=-1)

    def locate_end(self, position, d, slipping, beyond):
        """Where the slip `d` of a slip zone reaches zero, from past the lagging node nearest the
        boundary (`located_end`)."""
        return located_end(position, d, slipping, beyond)

    def dissipation(self, ds):
        """``sum_k L_k |ds_k|`` [J/m], the lumped ``int f p |ds| dx``."""
        return float(np.dot(self.limit, np.abs(ds)))

    def dissipation_density(self, ds):
        """``f p(x_k) |ds_k|`` [J/m^2] at the nodes: the density of ``int f p |ds| dx`` at each node.

        Pointwise, not the hat-weighted mean ``L_k |ds_k| / area_k``: the mean of ``f p`` under
        ``phi_k`` differs from ``f p(x_k)`` by ``O(h^2 p'')`` on equal elements, ``O(h p')`` where
        neighbouring elements differ in size, and more next to the edges, where ``p`` falls as a
        square root; a mesh adapted to the energy of the increments (`element_targets`) leaves
        elements wide where that error is large. The nodal value is as accurate as the slip
        increment at the node, as the exact model's ``f p |ds|`` is. `dissipation`, the energy of
        the increment and of the cycle, stays the lumped sum that the solve balances.
        """
        return self._fp * np.abs(ds)


def _validated_mesh(theta):
    """`theta` [rad] as a float array, checked to be a mesh: finite, strictly increasing from 0 to pi,
    no element below `SMALLEST_ELEMENT`."""
    theta = np.array(theta, dtype=float)
    if theta.ndim != 1 or theta.size < 3:
        raise ValueError(f"theta must be a 1-D mesh of at least 3 nodes, found shape {theta.shape}")
    if theta[0] != 0.0 or theta[-1] != np.pi or not np.all(np.diff(theta) > 0):  # NaN fails the comparison
        raise ValueError(f"theta must increase strictly from 0 to pi, found {_shown(theta)}")
    k = int(np.argmin(np.diff(theta)))
    if theta[k + 1] - theta[k] < SMALLEST_ELEMENT:
        raise ValueError(
            f"theta's elements must span at least {SMALLEST_ELEMENT:g} rad "
            f"(fretting.models.galerkin.mesh.SMALLEST_ELEMENT), found theta[{k}:{k + 2}] = {theta[k : k + 2].tolist()}"
        )
    return theta


def _shown(theta):
    """The first nodes of `theta` that break its order, for an error message."""
    bad = np.flatnonzero(~(np.diff(theta) > 0))
    k = int(bad[0]) if bad.size else 0
    return f"theta[{k}:{k + 2}] = {theta[k : k + 2].tolist()}" if bad.size else f"ends {theta[0]!r}, {theta[-1]!r}"
