"""Which model runs: the default rule, and the engine's calls that resolve and continue a spec.

The default for a contact and a history (`choose_model`) is the first spec of `DEFAULTS` that can
run the history (`fretting.models.base.ModelSpec.refusal`: it follows every load input the
history moves, and its own conditions hold):

1. the exact model of ``Q`` alone (`Exact`): no ``sigma`` in the history and a symmetric profile;
   where the answer is known in closed form it is not solved for;
2. the exact model of in-phase ``Q`` and ``sigma`` (`InPhase`): a Hertz contact, ``sigma = k Q``
   at every step (a straight load path through the origin) and regime A, ``|k| <= 4 / (pi a)``;
3. method 4 on the Galerkin mesh adapted to the history (`Mesh()`): to the energy, then to the
   stick ends of the recorded steps, within the default's bounds of nodes and work, a fallback
   recorded and said where it passes them (`fretting.models.galerkin.model.Mesh.default_model`);
4. where the history varies the normal load ``P``, which none of those follows, on a symmetric contact
   that grows with the load (Hertz, the rounded flat) without ``sigma``, under force or displacement
   control: the exact model of Jaeger's superposition (`Jaeger()`); where the answer is known in closed
   form it is not solved for;
5. otherwise where it varies ``P``, method 4 on cells fixed in ``x`` over its largest contact
   (`Varying()`); so too where it prescribes the displacement ``delta`` with a ``sigma`` off the
   in-phase line, whose ``Q`` of every step the mesh cannot adapt to before the run (`Mesh.holds_for`).

Where none of them runs the history (an asymmetric profile under a varying ``P``, or under a prescribed
``delta``), a HistoryError gives each one's reason, and says where method 4 on a grid runs it.

Every other decision is the spec's own (`ModelSpec.model_for`, `continued`, `is_default`); the
engine hands a spec its loop (`fretting.engine.follow.follow`) for the passes of an adaptation.
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

from fretting.engine.follow import follow
from fretting.errors import HistoryError
from fretting.models.base import ModelSpec
from fretting.models.collocation import Grid
from fretting.models.exact import Exact
from fretting.models.galerkin import Mesh
from fretting.models.inphase import InPhase
from fretting.models.jaeger import Jaeger
from fretting.models.normal import Varying

if TYPE_CHECKING:
    import numpy as np

    from fretting.loading.history import History
    from fretting.models.base import Model
    from fretting.models.state import State
    from fretting.physics.contact import Contact

__all__ = [
    "DEFAULTS",
    "MeshSampleWarning",
    "ModelFallbackWarning",
    "built_model",
    "check",
    "choose_model",
    "continued",
    "spec_from",
]

#: The default models in the order they are tried (module docstring).
DEFAULTS = (Exact(), InPhase(), Mesh(), Jaeger(), Varying())


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
        A spec of `DEFAULTS`, with its nodes fixed.

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
    return built_model(None, contact, history).spec


def built_model(
    spec: ModelSpec | None, contact: Contact, history: History, recorded: np.ndarray | None = None
) -> Model:
    """The model of `spec` for `history`, its nodes fixed and built (`ModelSpec.model_for`); None: the
    default's (`ModelSpec.default_model` of the first of `DEFAULTS` that runs it). A mesh adapted to
    the history locates the stick ends of the steps `recorded` (None: all). A fallback or a sample
    of the model is said by a warning.

    Raises HistoryError where the model cannot run the history (`ModelSpec.refusal`).
    """
    if spec is None:
        default = next((spec for spec in DEFAULTS if spec.refusal(contact, history) is None), None)
        if default is None:
            raise HistoryError(_no_default(contact, history))
        return _said(default.default_model(contact, history, follow, recorded))
    check(spec, contact, history)
    return _said(spec.model_for(contact, history, follow, recorded))


def _no_default(contact: Contact, history: History) -> str:
    """Why no spec of `DEFAULTS` runs `history` on `contact`: each one's reason (`ModelSpec.refusal`), told once
    and naming the profile by its class (a table's repr holds the table), and the grid where it would run it
    (not a default: its accuracy is that of the nodes asked for)."""
    reasons, profile = {}, contact.profile
    for spec in DEFAULTS:
        reason = spec.refusal(contact, history).replace(repr(profile), f"the {type(profile).__name__} profile")
        reasons.setdefault(reason, []).append(spec.name)
    told = "; ".join(f"{', '.join(names)}: {reason}" for reason, names in reasons.items())
    runs = Grid().refusal(contact, history) is None
    grid = " (method 4 on a grid does: ask for it with nodes=, --nodes)" if runs else ""
    return f"no default model runs this history{grid}: {told}"


def check(spec: ModelSpec, contact: Contact, history: History) -> None:
    """Raise HistoryError if the model of `spec` cannot run `history` on `contact` (`ModelSpec.refusal`)."""
    reason = spec.refusal(contact, history)
    if reason is not None:
        raise HistoryError(f"{spec.description} cannot run this history: {reason}")


def _said(model):
    """`model`, with a `ModelFallbackWarning` where it fell back (`ModelSpec.fallback`) and a
    `MeshSampleWarning` where it was resolved for a sample of the history (`ModelSpec.sample`)."""
    if model.spec.fallback is not None:
        warnings.warn(f"the model falls back: {model.spec.fallback}", ModelFallbackWarning, stacklevel=4)
    if model.spec.sample is not None:
        warnings.warn(f"the mesh was {model.spec.sample}", MeshSampleWarning, stacklevel=4)
    return model


def continued(contact: Contact, state: State, history: History) -> tuple[Model | None, State]:
    """The model (None: the state's own, to build) and the state to continue `state` along `history`
    (`ModelSpec.continued` of the state's spec)."""
    return state.model.continued(contact, state, history, follow)


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
