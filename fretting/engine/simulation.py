"""`simulate`: follow a load history with a model and record the contact; `adapted_mesh`: the mesh it would adapt."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from fretting._validate import positive
from fretting.engine.choice import continued, spec_from
from fretting.engine.follow import follow
from fretting.engine.recorder import Recorder, recorded_steps
from fretting.engine.stepper import Stepper
from fretting.engine.threads import one_blas_thread
from fretting.loading.history import History
from fretting.models.galerkin import DEFAULT_RTOL, Mesh
from fretting.models.galerkin.adaptation import MeshTooLarge, adapted_model
from fretting.results.notes import noted

if TYPE_CHECKING:
    from fretting.models.base import ModelSpec
    from fretting.models.state import State
    from fretting.physics.contact import Contact

__all__ = ["adapted_mesh", "simulate"]


def simulate(
    contact: Contact,
    history: History,
    model: ModelSpec | None = None,
    *,
    nodes: int | None = None,
    rtol: float | None = None,
    mesh: ArrayLike | None = None,
    state: State | None = None,
    record: ArrayLike | str | None = None,
) -> xr.Dataset:
    """Follow a load history and record the contact.

    Parameters
    ----------
    contact : Contact
    history : History
        Step 0 is the starting state. Without `state` the contact starts just formed,
        unloaded; a non-zero first vertex is then reached in one increment.
    model : ModelSpec, optional
        The model (`fretting.models.Exact`, `Grid`, `Mesh`). Default: the state's, else
        `fretting.choose_model`'s for this contact and history (the exact model of ``Q`` alone
        where it holds, else method 4 on a Galerkin mesh adapted to the history).
    nodes : int, optional
        Shorthand for ``model=Grid(nodes)``: the fixed grid of this many Gauss-Chebyshev points.
    rtol : float, optional
        Shorthand for ``model=Mesh(rtol=rtol)``: a Galerkin mesh adapted to the history, the
        energy of each increment asked to this relative accuracy.
    mesh : array_like, optional
        Shorthand for ``model=Mesh(theta=mesh)``: the Galerkin mesh ``theta`` [rad] as it is.
    state : State, optional
        State to continue from (`final_state`); its loads must be the history's first, and the
        run keeps its model, except that a Galerkin mesh adapted to an ``rtol`` is refined where
        the new loads need it (the result records the mesh it ran).
    record : array_like of int or "all", optional
        Steps whose fields and loads are stored, increasing (`recorded_steps`); the dataset's
        `step` coordinate holds their numbers. Energy and slip range per cycle and the final
        state always cover every step. A mesh adapted to the history locates the stick ends of
        the recorded steps; the increments with none recorded are resolved for their energy
        (`fretting.models.galerkin.adaptation.adapted_model`).

    Returns
    -------
    xarray.Dataset
        Variables of `fretting.results.variables.VARIABLES`; attributes of the contact and the
        model (``model``, its parameters, ``model_fallback`` where the default fell back,
        ``model_unresolved`` where cycles whose ``Q`` varies dissipated nothing on its nodes:
        `fretting.results.notes`).

    Raises
    ------
    GrossSlipError
        When a step leaves no stick zone.

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> fP = contact.f * contact.P
    >>> history = fr.History.piecewise_linear([0, 0.5 * fP, -0.5 * fP, 0.5 * fP], None, 8)
    >>> result = fr.simulate(contact, history)
    >>> result.attrs["model"]
    'exact'
    """
    if not isinstance(history, History):
        raise ValueError(f"history must be a fretting.History, found {history!r}")
    asked = spec_from(model, nodes, rtol, mesh)
    if state is not None and asked is None:  # the state's model: a model on a refined mesh, or None
        with one_blas_thread():
            asked, state = continued(contact, state, history)
    stepper = Stepper(contact, asked, state)
    recorded = recorded_steps(record, len(history))
    stepper.resolve(history, recorded)
    recorder = Recorder(stepper.model, history, recorded)
    return noted(recorder.dataset(stepper.run(history, recorder)))


def adapted_mesh(
    contact: Contact, history: History, rtol: float = DEFAULT_RTOL, max_nodes: int | None = None
) -> np.ndarray | None:
    """Galerkin mesh ``theta`` [rad] that resolves the stick and slip zones of `history` to `rtol`
    (`fretting.models.galerkin.adaptation.adapted_model`); None as soon as it is certain to need
    more than `max_nodes` nodes.

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> fP = contact.f * contact.P
    >>> history = fr.History.piecewise_linear([0, 0.5 * fP], [0, 50e6], 8)
    >>> theta = adapted_mesh(contact, history)
    >>> bool(theta[0] == 0 and theta[-1] == np.pi and np.all(np.diff(theta) > 0))
    True
    >>> adapted_mesh(contact, history, max_nodes=16) is None
    True
    >>> result = fr.simulate(contact, history, mesh=theta)  # the mesh as it is
    """
    try:
        with one_blas_thread():
            return adapted_model(Mesh(rtol=positive("rtol", rtol)), contact, history, follow, max_nodes).theta
    except MeshTooLarge:
        return None
