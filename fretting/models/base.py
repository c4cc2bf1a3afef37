"""The model contract: what a discretisation of the tangential problem gives the engine.

A *model specification* (`ModelSpec`) is a value: which discretisation, with which parameters
(`fretting.models.Grid`, `Mesh`, `Exact`). Bound to a contact it builds a *model* (`Model`), the
fixed arrays every increment uses. The engine (`fretting.engine.stepper.Stepper`) holds a model
and a `fretting.models.state.State`, asks the model for one increment at a time and never asks
which class it holds.

Units: every per-node array is in ascending ``x`` [m]; slip [m], traction [Pa], energy [J/m]
(per unit length of the contact along ``y``), energy density [J/m^2]; stick intervals in the
normalised position ``t = (x - centre) / a`` [-].

Adding a model: one module (or package) with a `ModelSpec` subclass and its `Model` subclass; a
default model is one more entry of `fretting.engine.choice.DEFAULTS`.
"""

from __future__ import annotations

import abc
import dataclasses
import functools
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from fretting.errors import GrossSlipError
from fretting.loading.loads import CONVERTED, NAMED, LoadBlock, Loads
from fretting.physics.surface import SurfaceStress

if TYPE_CHECKING:
    from fretting.loading.history import History
    from fretting.models.state import State
    from fretting.physics.contact import Contact

#: The engine's loop over a history, ``run(model, history, state, observe=..., guess=..., tally=...)``
#: returning the last `State` (`fretting.engine.follow.follow`), which a spec that adapts its nodes runs.
Run = Callable[..., "State"]

__all__ = ["UNFOLLOWED", "Model", "ModelSpec", "Outcome"]


@dataclass(frozen=True, eq=False)
class Outcome:
    """What one increment did.

    Attributes
    ----------
    g : ndarray, shape (N,)
        The model's own measure of the shear traction after the increment; `Model.traction`
        turns it into [Pa] (only for recorded steps, since it may cost a recovery).
    ds : ndarray, shape (N,)
        Slip increment [m]; exactly zero at the nodes that stuck.
    slip : ndarray, shape (N,)
        Slip after the increment [m].
    dissipation : float
        Energy dissipated by the increment, ``int f p |ds| dx`` [J/m], never negative.
    memory : tuple
        What the model remembers beyond the slip field (the open turning points of the exact
        model of ``Q`` alone; empty for method 4).
    zones : list of (float, float), optional
        Stick intervals in ``t`` where the model knows them exactly (None: found from the slip).
    delta_Q : float, optional
        ``delta_Q`` [m] where the model gives it exactly (None: from the slip).
    slid : float
        Uniform slip [m] taken while the whole contact slid (gross slip under displacement control,
        `Model.slide`), summed since the contact was formed and included in `slip`; 0 for a model
        that does not slide.
    """

    g: np.ndarray
    ds: np.ndarray
    slip: np.ndarray
    dissipation: float
    memory: tuple = ()
    zones: list | None = None
    delta_Q: float | None = None
    slid: float = 0.0


class ModelSpec(abc.ABC):
    """A discretisation and its parameters: a value, recorded in the state and the dataset.

    A spec is *resolved* when it fixes its nodes (`resolved`), so that `build` needs only the
    contact; `model_for` resolves it for a history and builds its model. Every decision about a
    model is one of its spec's methods, so the engine never asks which class it holds: which
    histories it runs (`refusal`), its model for a history (`model_for`, `default_model`), how a
    state of it is continued (`continued`) and whether the default can give it (`is_default`).
    Subclasses register by their `name` (`registry`), so that a result recording a user's spec
    reads back with it.
    """

    #: Short name recorded as the dataset's ``model`` attribute.
    name: ClassVar[str]
    #: One line on what the model solves and how.
    description: ClassVar[str]
    #: Names the dataset's ``model`` attribute held for this spec in results of older releases.
    recorded_as: ClassVar[tuple[str, ...]] = ()
    #: The load inputs (fields of `fretting.loading.loads.Loads`) the model follows; a history that
    #: moves any other is refused (`refusal`).
    inputs: ClassVar[frozenset[str]] = frozenset({"Q", "sigma"})
    #: Dataset variable that records `State.memory` (None: the model keeps no memory beyond the slip).
    memory_variable: ClassVar[str | None] = None
    #: Every spec class by its `name` and its `recorded_as` names (`__init_subclass__`).
    registry: ClassVar[dict[str, type[ModelSpec]]] = {}
    #: Node angles [rad] of a resolved spec whose nodes are recorded as angles (None: not resolved,
    #: or nodes that follow from the parameters).
    theta: np.ndarray | None = None
    #: Why the model is coarser than its parameters ask (None: it is not); said as a fallback.
    fallback: str | None = None
    #: What part of a long history the model was resolved for, where not all of it (None: all).
    sample: str | None = None

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "name" not in cls.__dict__:
            return
        for name in (cls.name, *cls.recorded_as):
            known = ModelSpec.registry.get(name, cls)
            if known.__qualname__ != cls.__qualname__:  # the same class defined again (a reload) takes its place
                raise TypeError(f"the model name {name!r} of {cls.__qualname__} is {known.__qualname__}'s already")
            ModelSpec.registry[name] = cls

    @staticmethod
    def recorded(attrs: Mapping[str, Any], theta: np.ndarray | None) -> ModelSpec:
        """The resolved spec of the class the ``model`` attribute of `attrs` names (`registry`), from
        `attrs` and the node angles `theta` [rad] ascending (`from_record`)."""
        name = attrs.get("model")
        if name not in ModelSpec.registry:
            known = ", ".join(spec.name for spec in dict.fromkeys(ModelSpec.registry.values()))
            raise ValueError(f"the result records the model {name!r}, expected one of {known}")
        return ModelSpec.registry[name].from_record(attrs, theta)

    @classmethod
    @abc.abstractmethod
    def from_record(cls, attrs: Mapping[str, Any], theta: np.ndarray | None) -> ModelSpec:
        """The resolved spec recorded by a dataset's attributes `attrs` (`attributes`) and node angles `theta`."""

    @property
    @abc.abstractmethod
    def resolved(self) -> bool:
        """True when the nodes are fixed and `build` needs only the contact."""

    @abc.abstractmethod
    def build(self, contact: Contact) -> Model:
        """The `Model` of this resolved spec on `contact`."""

    @abc.abstractmethod
    def attributes(self) -> dict[str, Any]:
        """Dataset attributes of the spec: ``{"model": name, ...parameters}`` (numbers and strings)."""

    def holds_for(self, contact: Contact, history: History | None) -> str | None:
        """None if the model can run `history` on `contact`, else the reason why not (one line).

        A subclass states its own conditions here; `refusal` adds the inputs it follows."""
        return None

    def refusal(self, contact: Contact, history: History | None) -> str | None:
        """None if the model can run `history` on `contact`: it follows every input the history moves
        (`inputs`; an input the engine turns into another, `fretting.loading.loads.CONVERTED`, as that
        one) and `holds_for` it; else the reason why not (one line)."""
        moved = frozenset() if history is None else {CONVERTED.get(name, name) for name in history.moves(contact)}
        moved -= self.inputs
        if moved:
            followers = sorted(
                f"fretting.models.{spec.__name__}" for spec in set(self.registry.values()) if moved <= spec.inputs
            )
            names = " and ".join(NAMED[name] for name in sorted(moved))
            return f"the history varies {names}, which this model does not follow ({' or '.join(followers)} does)"
        return self.holds_for(contact, history)

    def resolved_for(self, contact: Contact, history: History | None) -> ModelSpec:
        """This spec with its nodes fixed for `history` on `contact` (None: no history known). A resolved spec:
        itself."""
        return self

    def model_for(self, contact: Contact, history: History, run: Run, recorded: np.ndarray | None = None) -> Model:
        """The built model of this spec for `history`: resolved (`resolved_for`) and built.

        `run` is the engine's loop over a history (`fretting.engine.follow.follow`), for a spec that
        adapts its nodes by running the history; `recorded` the steps whose fields are stored (None:
        all), for a spec that resolves them more finely.
        """
        return self.resolved_for(contact, history).build(contact)

    def default_model(self, contact: Contact, history: History, run: Run, recorded: np.ndarray | None = None) -> Model:
        """`model_for` as the default runs it (`fretting.engine.choice.choose_model`): a spec may bound its
        cost there and record why (`fallback`)."""
        return self.model_for(contact, history, run, recorded)

    def continued(self, contact: Contact, state: State, history: History, run: Run) -> tuple[Model | None, State]:
        """The model (None: the state's own, to build) and the state with which `state` of this spec
        goes on along `history`: the state as it is, by default."""
        return None, state

    def is_default(self) -> bool:
        """True if `fretting.engine.choice.choose_model` can give this resolved spec (one read from a result)."""
        return False

    def __repr__(self) -> str:
        """The spec as its constructor reads, without the parameters left at their defaults, and an
        array (the node angles of a resolved spec) by its size: printing a model stays one line.
        ``Mesh(rtol=0.0001)`` evaluates to the spec it prints; a resolved spec does not."""
        shown = []
        for field in dataclasses.fields(self):  # type: ignore[arg-type]  # every spec is a dataclass
            value = getattr(self, field.name)
            if isinstance(value, np.ndarray):
                shown.append(f"{field.name}=<{value.size} values>")
            elif value != field.default:
                shown.append(f"{field.name}={value!r}")
        return f"{type(self).__name__}({', '.join(shown)})"

    def __eq__(self, other: object) -> bool:
        """The same kind of model with the same parameters and nodes."""
        if not isinstance(other, ModelSpec) or type(other) is not type(self):
            return False
        if self.attributes() != other.attributes():
            return False
        mine, theirs = self.theta, other.theta
        if mine is None or theirs is None:
            return mine is None and theirs is None
        return np.array_equal(mine, theirs)

    def __hash__(self) -> int:
        return hash(
            (type(self), tuple(self.attributes().items()), None if self.theta is None else self.theta.tobytes())
        )


#: What a `fretting.errors.GrossSlipError` of displacement control adds where the model does not
#: slide (`Model.slides`).
UNFOLLOWED = (
    "under displacement control fretting.models.Exact (Q alone), Grid, Mesh and Varying (Q and sigma) follow "
    "gross slip, and Varying and Jaeger (P and Q) under a varying P"
)


class Model(abc.ABC):
    """A contact discretised: the fixed arrays of every increment, and the increment itself.

    Attributes every model sets
    ---------------------------
    spec : ModelSpec
        The resolved spec that built it.
    contact : Contact
    x : ndarray, shape (N,)
        Node positions [m], ascending.
    t : ndarray, shape (N,)
        ``(x - centre) / a`` [-].
    theta : ndarray or None
        Node angles [rad], ascending, where the nodes are ``x = centre + a cos(theta)`` and
        recorded as such (None for the Gauss-Chebyshev grid, whose nodes follow from `N`).
    friction_force : float
        The ``|Q|`` [N/m] at which the discrete contact has no stick zone left (``f P`` up to the
        quadrature of the pressure).
    """

    spec: ModelSpec
    contact: Contact
    x: np.ndarray
    t: np.ndarray
    theta: np.ndarray | None
    friction_force: float

    @abc.abstractmethod
    def at_rest(self, state: State) -> Outcome:
        """`Outcome` of no increment at all: the state as it stands under its own loads."""

    @abc.abstractmethod
    def increment(self, state: State, loads: Loads, guess: np.ndarray | None = None) -> Outcome:
        """`Outcome` of the increment from `state` to `loads` (`fretting.loading.loads.Loads`).

        The model reads the fields of `loads` that its spec follows (`ModelSpec.inputs`); the
        engine gives a model no loads that move an input it does not follow. `guess`, if given,
        is the slip direction (+1, -1, 0) to try first at each node; a start only, which the
        answer does not depend on. A model may ignore it.
        """

    #: True if the model follows gross slip under displacement control (`slide`): its `increment`
    #: reaches ``|Q| = sliding_force`` exactly (the exact model of ``Q`` alone, method 4's models, the cells).
    slides: bool = False

    def sliding_force(self, P: float | None = None) -> float:
        """The ``|Q|`` [N/m] at which no stick zone is left under the normal load `P` [N/m] (None: the
        contact's): the smaller of `friction_force` and ``f P``, which differ by the rounding of a
        quadrature of the pressure."""
        return min(self.friction_force, self.contact.f * (self.contact.P if P is None else P))

    def slide(self, state: State, loads: Loads, du: float) -> Outcome:
        """`Outcome` of the increment to ``loads.Q = +-sliding_force`` and a uniform slide `du` [m] of the
        whole contact (`slides`). By default the contact's gross slip, which the model does not follow:
        a `fretting.errors.GrossSlipError` naming the models that do (`UNFOLLOWED`)."""
        raise GrossSlipError(None, loads.Q, loads.sigma, self.friction_force, UNFOLLOWED)

    #: True if `window` steps a run of increments for less than `increment` one at a time does (the
    #: engine then takes the unrecorded steps a window at a time).
    windows: bool = False

    #: True if the increments solve linear systems (BLAS and LAPACK), which the engine runs on
    #: `fretting.engine.threads.BLAS_THREADS` threads; False for a model in closed form, whose
    #: increments `fretting.Stepper.step` then takes without setting the libraries' threads.
    linear_algebra: bool = True

    def window(self, state: State, loads: LoadBlock) -> tuple:
        """The increments from `state` through the `loads` (a `fretting.loading.loads.LoadBlock`) in
        turn, as rows: ``(slip, q, dissipation, memory, still)``, row ``k`` what `increment` gives
        for the ``k``-th loads from the state the rows before it leave, bit for bit
        (`fretting.models.exact.ExactModel.window` states the arrays). By default the increments
        one after another, ``still`` where one slipped nowhere; a model whose rows cost less sets
        `windows`."""
        slip, q, dissipation, memory, still = [], [], [], [], []
        for k in range(len(loads)):
            outcome = self.increment(state, loads[k])
            state = state.advance(outcome, loads[k], None, None, None, None)
            slip.append(outcome.slip)
            q.append(self.traction(outcome))
            dissipation.append(outcome.dissipation)
            memory.append(outcome.memory)
            still.append(not outcome.ds.any())
        return np.array(slip), np.array(q), dissipation, memory, np.array(still)

    def prepare(self, state: State, loads: LoadBlock) -> None:  # noqa: B027 (a neutral default: most models have nothing to prepare)
        """Prepare the increments from `state` through the `loads` (a `LoadBlock`) that are to come,
        so that `increment` finds them cheaper; what is prepared changes no result. Nothing by default."""

    @abc.abstractmethod
    def traction(self, outcome: Outcome) -> np.ndarray:
        """Shear traction [Pa] at the nodes after `outcome`."""

    @abc.abstractmethod
    def stick_zones(self, outcome: Outcome, state: State) -> list[tuple[float, float]]:
        """Stick intervals ``(start, end)`` in ``t`` of the increment `outcome`, which left `state`."""

    @abc.abstractmethod
    def delta_Q(self, outcome: Outcome) -> float:
        """``int s / (pi sqrt(a^2 - x^2)) dx`` [m] of the slip after `outcome` (docs: theory, conventions)."""

    @abc.abstractmethod
    def delta_sigma(self, outcome: Outcome) -> float:
        """``int s x / (4 sqrt(a^2 - x^2)) dx`` [m^2] of the slip after `outcome`."""

    @abc.abstractmethod
    def dissipation_density(self, ds: np.ndarray) -> np.ndarray:
        """``f p |ds|`` [J/m^2] at the nodes, consistent with the increment's `dissipation`."""

    @functools.cached_property
    def surface(self) -> tuple[SurfaceStress, np.ndarray]:
        """The surface direct stress at the nodes (`fretting.physics.surface.SurfaceStress`, its
        Hilbert matrix built at the first use) and the contact pressure there [Pa]."""
        return SurfaceStress(self.t), self.contact.pressure(self.x)

    def surface_at(self, outcome: Outcome) -> tuple[SurfaceStress, np.ndarray]:
        """`surface` under the normal load after `outcome` (the contact's: a model whose ``P`` varies overrides it)."""
        return self.surface

    def pressure_at(self, P: float) -> np.ndarray:
        """Contact pressure [Pa] at the nodes under the normal load `P` [N/m] (a model of a constant ``P``: the
        contact's)."""
        return self.contact.pressure(self.x)

    def energy_density(self, outcome: Outcome) -> np.ndarray:
        """`dissipation_density` of the increment `outcome` (at its normal load, where a model varies it)."""
        return self.dissipation_density(outcome.ds)
