"""Which model runs: the one place that chooses the default, resolves a spec and reads a recorded one.

The default for a contact and a history (`choose_model`):

0. where the history varies the normal load ``P``, method 4 on cells fixed in ``x`` over its
   largest contact (`Varying()`), the one model that follows ``P``;
1. the exact model of ``Q`` alone (`Exact`) where it holds: no ``sigma`` in the history and a
   symmetric profile (`Exact.holds_for`); where the answer is known in closed form it is not
   solved for;
2. the exact model of in-phase ``Q`` and ``sigma`` (`InPhase`) where it holds: a Hertz contact,
   ``sigma = k Q`` at every step (a straight load path through the origin) and regime A,
   ``|k| <= 4 / (pi a)`` (`InPhase.holds_for`);
3. else method 4 on the Galerkin mesh adapted to the history (`Mesh()`, `DEFAULT_RTOL`): to
   the energy, then to the stick ends of the recorded steps
   (`fretting.engine.adaptation.adapted_model`);
4. where the energy's mesh would need more than `MAX_DEFAULT_MESH` nodes, the last mesh of the
   adaptation within that bound; where the run on the ends' mesh would cost more than
   `MAX_DEFAULT_WORK`, the energy's mesh; each with the reason recorded in the spec
   (`Mesh.fallback`, the dataset's ``model_fallback``) and a `ModelFallbackWarning`; the
   adaptation stops as soon as a bound is certain;
5. a long history's mesh is adapted to a sample of its turning points
   (`fretting.engine.adaptation.SAMPLE_TURNS`), said by a `MeshSampleWarning` and recorded
   (`Mesh.sample`, the dataset's ``model_sample``).
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from fretting.engine.adaptation import MeshTooLarge, adapted_model, refined_for
from fretting.errors import HistoryError
from fretting.models.base import ModelSpec
from fretting.models.collocation import DEFAULT_NODES, Grid
from fretting.models.exact import Exact
from fretting.models.galerkin import DEFAULT_RTOL, ENERGY_SPAN, Mesh
from fretting.models.inphase import InPhase
from fretting.models.normal import DEFAULT_CELLS, DEFAULT_LOAD_PART, Varying

if TYPE_CHECKING:
    from fretting.loading.history import History
    from fretting.physics.contact import Contact

__all__ = [
    "MAX_DEFAULT_MESH",
    "MAX_DEFAULT_WORK",
    "SPECS",
    "MeshSampleWarning",
    "ModelFallbackWarning",
    "check",
    "built_model",
    "choose_model",
    "continued",
    "could_be_default",
    "recorded_spec",
    "spec_from",
]

#: Every kind of model, by the name the dataset records: a new model adds its spec here.
SPECS = {spec.name: spec for spec in (Exact, InPhase, Mesh, Grid, Varying)}

#: The ``model`` attribute of results written by fretting 0.1.0, before models had names: the name
#: it stands for, so that a result kept from then can still be continued or resumed.
RECORDED_BEFORE = {
    "method 4: dislocation correction to the fully adhered solution, P1 Galerkin in theta on a mesh adapted to rtol": (
        Mesh.name
    ),
    "method 4: dislocation correction to the fully adhered solution, Gauss-Chebyshev collocation": Grid.name,
    "Ciavarella-Jaeger with Masing's rule: exact for Q alone on a symmetric profile, at fixed nodes": Exact.name,
}

#: Nodes at which the default's adaptation to the energy stops; past it the last mesh within the
#: bound runs.
MAX_DEFAULT_MESH = 4 * DEFAULT_NODES

#: The default's bound of ``N^2 x increments`` of a run on the mesh of ``N`` nodes that locates the
#: recorded steps' stick ends (`fretting.models.galerkin.BOUNDARY_SPAN`): an increment costs about
#: ``N^2`` (products with the stiffness), and those meshes reach a few thousand nodes on general
#: Q/sigma histories (benchmarks/trajectories.py prints each with its nodes and run time). The bound
#: takes in every history of that benchmark; past it (long histories) the mesh adapted to the energy
#: runs.
MAX_DEFAULT_WORK = 3e9


class ModelFallbackWarning(UserWarning):
    """The default model fell back to a coarser one; the message says why."""


class MeshSampleWarning(ModelFallbackWarning):
    """The mesh was adapted to a sample of a long history's turning points (`Mesh.sample`); the
    message says which. A note of the run, as a fallback is."""


def choose_model(contact: Contact, history: History) -> ModelSpec:
    """The default model for `contact` and `history`, resolved (module docstring).

    Returns
    -------
    ModelSpec
        `Exact`, `InPhase` or `Mesh`, with its nodes fixed.

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> fP = contact.f * contact.P
    >>> choose_model(contact, fr.History.piecewise_linear([0, 0.5 * fP, -0.5 * fP], None, 8)).name
    'exact'
    >>> choose_model(contact, fr.History.piecewise_linear([0, 0.5 * fP, -0.5 * fP], [0, 50e6, -50e6], 8)).name
    'inphase'
    >>> spec = choose_model(contact, fr.History.piecewise_linear([0, 0.5 * fP, -0.5 * fP], [0, 50e6, 0], 8))
    >>> spec.name, spec.resolved  # sigma off the line sigma = k Q: a Galerkin mesh adapted to the history
    ('mesh', True)
    """
    return _default_model(contact, history).spec


#: What the reason of every mesh the default capped at its bounds says (`_default_model`); a state
#: of such a mesh is continued on it as it is (`continued`). Other notes of a mesh's spec (the
#: increments below the solver's floor, an energy that could not settle) leave it refined for
#: the loads that continue it.
CAPPED = "over the default's bound of"


def _default_model(contact, history, recorded=None):
    """The built model of `choose_model` (a mesh's stiffness is assembled once, by its adaptation)."""
    if varies_P(contact, history):
        return Varying().resolved_for(contact, history).build(contact)
    for exact in (Exact(), InPhase()):
        if exact.holds_for(contact, history) is None:
            return exact.resolved_for(contact, history).build(contact)
    try:
        model = adapted_model(contact, history, DEFAULT_RTOL, MAX_DEFAULT_MESH, recorded, MAX_DEFAULT_WORK)
    except MeshTooLarge as error:
        model = error.model
        if error.change is not None:
            reason = (
                f"{error}, {CAPPED} {MAX_DEFAULT_WORK:.2g}: runs the mesh before it, "
                f"{model.theta.size} nodes, whose energy per cycle changed by up to {error.change:.1e} of itself "
                f"from the mesh before that (rtol = {DEFAULT_RTOL:g})"
            )
        elif error.ends is not None:
            span = ENERGY_SPAN * DEFAULT_RTOL
            reason = (
                f"{error}, {CAPPED} {MAX_DEFAULT_WORK:.2g}"
                f": runs the mesh adapted to the energy, {model.theta.size} nodes, whose stick ends between "
                f"turning points err by up to about {span:g} a"
            )
        else:
            reason = (
                f"{error}, {CAPPED} {MAX_DEFAULT_MESH}"
                f": runs the last mesh within it, {model.theta.size} nodes, coarser than rtol = {DEFAULT_RTOL:g} asks"
            )
        notes = model.spec.fallback  # the solver's floor, where the ends' stage counted it
        model.spec = replace(model.spec, fallback=reason if notes is None else f"{reason}; {notes}")
    return _said(model)


def varies_P(contact, history):
    """True if `history` moves the normal load away from the contact's ``P``."""
    return history is not None and history.P is not None and bool(np.any(history.P != contact.P))


def check(spec, contact, history):
    """Raise HistoryError if the model of `spec` cannot run `history` on `contact` (`ModelSpec.holds_for`)."""
    reason = spec.holds_for(contact, history)
    if reason is None and varies_P(contact, history) and not isinstance(spec, Varying):
        reason = "the history varies the normal load P (fretting.models.Varying follows it)"
    if reason is not None:
        raise HistoryError(f"{spec.description} cannot run this history: {reason}")


def could_be_default(spec):
    """True if `choose_model` can give the resolved `spec` (one read from a result, say)."""
    return (
        isinstance(spec, (Exact, InPhase))
        or (isinstance(spec, Mesh) and spec.rtol == DEFAULT_RTOL)
        or (isinstance(spec, Varying) and (spec.cells, spec.load_part) == (DEFAULT_CELLS, DEFAULT_LOAD_PART))
    )


def built_model(spec, contact, history, recorded=None):
    """The model of `spec` for `history`, its nodes fixed and built; None: the default's. A mesh
    adapted to the history locates the stick ends of the steps `recorded` (None: all).

    Raises HistoryError where the model cannot run the history (`ModelSpec.holds_for`).
    """
    if spec is None:
        return _default_model(contact, history, recorded)
    check(spec, contact, history)
    if spec.resolved:
        return spec.build(contact)
    if isinstance(spec, Mesh):
        return _said(adapted_model(contact, history, spec.rtol, recorded=recorded))
    return spec.resolved_for(contact, history).build(contact)


def _said(model):
    """`model`, with a `ModelFallbackWarning` where its mesh fell back (`Mesh.fallback`) and a
    `MeshSampleWarning` where it was adapted to a sample of the history."""
    if model.spec.fallback is not None:
        warnings.warn(f"the model falls back: {model.spec.fallback}", ModelFallbackWarning, stacklevel=4)
    if model.spec.sample is not None:
        warnings.warn(f"the mesh was {model.spec.sample}", MeshSampleWarning, stacklevel=4)
    return model


def continued(contact, state, history):
    """The model (None: the state's own, to build) and the state to continue `state` along `history`.

    A state of a `Mesh` adapted to an ``rtol`` has its mesh refined where the new loads need it
    (`fretting.engine.adaptation.refined_for`); any other is continued as it is, and so is a
    mesh the default capped (`CAPPED`: its ``fallback`` stays true of it).
    """
    spec = state.model
    if isinstance(spec, Mesh) and spec.rtol is not None and CAPPED not in (spec.fallback or ""):
        return refined_for(contact, state, history)
    return None, state


def spec_from(model=None, nodes=None, rtol=None, mesh=None):
    """The spec that `simulate`'s keywords ask for: `model` itself, or the shorthand `nodes` (`Grid`),
    `rtol` (`Mesh`, adapted) or `mesh` (`Mesh`, as given); None when none is given (the default)."""
    asked = [
        name
        for name, value in (("model", model), ("nodes", nodes), ("rtol", rtol), ("mesh", mesh))
        if value is not None
    ]
    if len(asked) > 1:
        raise ValueError(
            f"give one of model, nodes (Gauss-Chebyshev), rtol or mesh (Galerkin), found {' and '.join(asked)}"
        )
    if model is not None and not isinstance(model, ModelSpec):
        raise ValueError(f"model must be a fretting.models spec (Exact(), Grid(), Mesh()), found {model!r}")
    if nodes is not None:
        return Grid(nodes)
    if rtol is not None:
        return Mesh(rtol=rtol)
    if mesh is not None:
        return Mesh(theta=mesh)
    return model


def recorded_spec(result):
    """The resolved spec a result was run with, from its ``model`` attribute and nodes."""
    attrs = result.attrs
    name = RECORDED_BEFORE.get(attrs.get("model"), attrs.get("model"))
    if name not in SPECS:
        raise ValueError(f"the result records the model {name!r}, expected one of {', '.join(SPECS)}")
    theta = result.theta.values[::-1].copy() if "theta" in result else None  # ascending in theta
    return SPECS[name].from_record(attrs, theta)
