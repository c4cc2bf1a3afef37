"""The stepper: a model and a state, advanced one load increment at a time or over a history.

`Stepper.step` solves one increment; `Stepper.run` follows a history (`fretting.engine.follow`).
What is stored of the steps is the recorder's business (`fretting.engine.recorder.Recorder`),
which `run` tells of every step and cycle.
"""

from __future__ import annotations

from collections.abc import Callable
from contextlib import nullcontext
from typing import TYPE_CHECKING

import numpy as np

from fretting.engine import choice
from fretting.engine.follow import advance, displaced, follow
from fretting.engine.threads import one_blas_thread
from fretting.errors import HistoryError
from fretting.loading.history import History
from fretting.loading.loads import CONVERTED, NAMED, Loads
from fretting.models.base import Model, ModelSpec, Outcome
from fretting.models.state import State
from fretting.physics.contact import Contact

if TYPE_CHECKING:
    from fretting.engine.recorder import Recorder

__all__ = ["Stepper"]


class Stepper:
    """A contact's model and state, advanced by load increments.

    Parameters
    ----------
    contact : Contact
    model : ModelSpec or Model, optional
        The model: a spec (`fretting.models.Exact`, `Grid`, `Mesh`), resolved at the first `run`
        when it adapts its nodes to a history, or a model already built. Default: the state's
        model, else the default for the first history run (`fretting.choose_model`).
    state : State, optional
        State to continue from (`fretting.final_state`); default the contact just formed.

    Examples
    --------
    >>> import fretting as fr
    >>> contact = fr.Contact(fr.Hertz(0.05), E_star=115e9, f=0.6, P=1e5)
    >>> stepper = fr.Stepper(contact, fr.models.Grid(64))
    >>> outcome = stepper.step(0.3 * contact.f * contact.P)
    >>> bool(outcome.dissipation > 0)
    True
    """

    def __init__(self, contact: Contact, model: ModelSpec | Model | None = None, state: State | None = None) -> None:
        if not isinstance(contact, Contact):
            raise ValueError(f"contact must be a fretting.Contact, found {contact!r}")
        if model is not None and not isinstance(model, (ModelSpec, Model)):
            raise ValueError(f"model must be a fretting.models spec (Exact(), Grid(), Mesh()), found {model!r}")
        if state is not None and not isinstance(state, State):
            raise ValueError(f"state must be a fretting.State, found {state!r}")
        if state is not None and model is not None and _spec(model) != state.model:
            raise ValueError(f"the state has its own model ({state.model.name}): give no other")
        self.contact = contact
        self._spec = _spec(model) if model is not None else (None if state is None else state.model)
        self._model = model if isinstance(model, Model) else None
        self._state = state
        self._fresh = state is None  # the contact just formed: a history may start at any loads
        if self._model is None and self._spec is not None and self._spec.resolved:
            with one_blas_thread():
                self._built(self._spec.build(contact))
        elif self._model is not None:
            self._build_state()

    @property
    def model(self) -> Model | None:
        """The built `fretting.models.base.Model` (None until a history has chosen or resolved it)."""
        return self._model

    @property
    def state(self) -> State | None:
        """The current `State` (None until a model is built)."""
        return self._state

    def step(
        self,
        Q: float | None = None,
        sigma: float = 0.0,
        cycle: int = 0,
        P: float | None = None,
        *,
        delta: float | None = None,
    ) -> Outcome:
        """Advance by one increment to the loads `Q` [N/m], `sigma` [Pa]; return its `Outcome`.

        `delta` [m], instead of `Q`: the tangential displacement at the contact's datum to reach, for
        which the step finds ``Q`` (`fretting.engine.follow.displaced`; ``state.Q`` holds it).

        `cycle` is the load cycle the increment belongs to (0: none): its energy, ``w`` and slip
        range are tallied in `State.tally` from the increment that begins it. `P` [N/m] is the
        normal load after the increment, for a model that follows it (`fretting.models.Varying`);
        None: the contact's.
        """
        if self._model is None:
            raise ValueError("the stepper has no model yet: give model= (e.g. fretting.models.Grid()) or run a history")
        if (Q is None) == (delta is None):
            raise HistoryError("give either Q or delta, found " + ("both" if Q is not None else "neither"))
        Q, sigma = (np.nan, float(sigma)) if Q is None else (float(Q), float(sigma))
        delta = None if delta is None else float(delta)
        if not (np.isfinite(sigma) and np.isfinite(Q if delta is None else delta)):
            given = f"Q = {Q!r}" if delta is None else f"delta = {delta!r}"
            raise HistoryError(f"loads must be finite, found {given}, sigma = {sigma!r}")
        with one_blas_thread() if self._model.linear_algebra else nullcontext():
            if cycle != self._state.tally.number:
                self._state = self._state.begun(cycle, self.contact)
            P = None if P is None or P == self.contact.P else positive_load(P)
            loads = Loads(Q, sigma, P, delta)
            if unfollowed := {CONVERTED.get(name, name) for name in loads.given()} - self._spec.inputs:
                names = " and ".join(NAMED[name] for name in sorted(unfollowed))
                raise HistoryError(
                    f"{self._spec.description} does not follow {names}: give it no other than the contact's"
                )
            loads, trial = displaced(self._model, self._state, loads)
            outcome, self._state = advance(self._model, self._state, loads, solved=trial)
        self._fresh = False
        return outcome

    def run(
        self,
        history: History,
        recorder: Recorder | None = None,
        *,
        observe: Callable | None = None,
        guess: Callable | None = None,
    ) -> State:
        """Follow `history` from the current state (whose loads are the history's first); return the last state.

        Parameters
        ----------
        history : History
            Step 0 is the current state; a non-zero first vertex is reached in one increment
            from the contact just formed.
        recorder : Recorder, optional
            Told of every step (`Recorder.step`, `Recorder.copied`) and every cycle (`Recorder.cycle`);
            a recorder that skips (`Recorder.skipping`) has the steps of
            `fretting.engine.follow.skippable` skipped.
        observe : callable, optional
            ``observe(step, outcome)`` sees the `fretting.models.base.Outcome` of every step
            solved (mesh adaptation).
        guess : callable, optional
            ``guess(step)``: the slip directions to start the solver from at `step`, or None.
        """
        self.resolve(history)
        first = history.loads[0]
        if not self._fresh and first.delta is not None:
            if (self._state.loads.delta, self._state.sigma) != (first.delta, first.sigma):
                raise HistoryError(
                    f"history starts at delta = {first.delta!r}, sigma = {first.sigma!r}; the state is at "
                    f"delta = {self._state.loads.delta!r}, sigma = {float(self._state.sigma)!r}"
                )
        elif not self._fresh and (self._state.Q, self._state.sigma) != history.start:
            Q, sigma = history.start
            raise HistoryError(
                f"history starts at Q = {Q!r}, sigma = {sigma!r}; "
                f"the state is at Q = {float(self._state.Q)!r}, sigma = {float(self._state.sigma)!r}"
            )
        held = self.contact.P if self._fresh or self._state.P is None else self._state.P
        if history.P is not None and history.P[0] != held:
            raise HistoryError(f"history starts at P = {float(history.P[0])!r}; the contact is at P = {held!r}")
        with one_blas_thread():
            self._state = follow(self._model, history, self._state, recorder, observe, guess)
        self._fresh = False
        return self._state

    def resolve(self, history: History, recorded: np.ndarray | None = None) -> None:
        """Fix the model for `history` without stepping: choose the default, or adapt the spec's
        nodes to it (`fretting.engine.choice.built_model`; an adapted mesh locates the stick ends of
        the steps `recorded`, None: every step); with a model built already, check that it can run
        `history`."""
        if self._model is None:
            with one_blas_thread():
                self._built(choice.built_model(self._spec, self.contact, history, recorded))
        else:
            choice.check(self._spec, self.contact, history)

    def _built(self, model):
        self._spec, self._model = model.spec, model
        self._build_state()

    def _build_state(self):
        if self._state is None:
            self._state = State.virgin(self._model)
        else:
            self._state.check(self.contact, self._model)


def positive_load(P):
    """`P` [N/m] as a float, or a HistoryError unless it is a finite number > 0."""
    P = float(P)
    if not (np.isfinite(P) and P > 0):
        raise HistoryError(f"P must be a finite normal load > 0 (the contact lifts off otherwise), found {P!r}")
    return P


def _spec(model):
    return model.spec if isinstance(model, Model) else model
