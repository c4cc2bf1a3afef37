"""Loads as values: one point of the load path (`Loads`) and the loads of a run of steps (`LoadBlock`).

A model reads the fields it follows (`fretting.models.base.ModelSpec.inputs`) and nothing else; a
new load input is a field here, a column of the history file and the model that reads it
(docs/developer/architecture.md).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

__all__ = ["CONVERTED", "INPUTS", "NAMED", "LoadBlock", "Loads", "edge_loads"]


@dataclass(frozen=True, slots=True)
class Loads:
    """The loads at one point of the history.

    Attributes
    ----------
    Q : float
        Shear force per unit length [N/m].
    sigma : float
        Differential bulk tension [Pa].
    P : float, optional
        Normal load per unit length [N/m]; None: the contact's ``P`` (the load it was formed at),
        which every model runs.
    delta : float, optional
        Tangential displacement of the pad relative to the specimen at the contact's datum [m]
        (docs/theory/displacement.md), where it is prescribed: the engine then finds ``Q``
        (`fretting.engine.follow.displaced`) and gives the model the loads with ``Q`` and without
        ``delta``. None: ``Q`` is prescribed.
    """

    Q: float
    sigma: float = 0.0
    P: float | None = None
    delta: float | None = None

    def normal(self, contact):
        """The normal load [N/m] on `contact`: `P`, or the contact's where it is None."""
        return contact.P if self.P is None else self.P

    def given(self):
        """Names of the inputs these loads set: ``Q`` and ``sigma`` always, the optional ones where not None."""
        return frozenset(name for name in INPUTS if getattr(self, name) is not None)

    def force(self):
        """These loads as a model is given them: without ``delta`` (the engine has found ``Q``)."""
        return self if self.delta is None else replace(self, delta=None)


#: Every load input a history can move, in the order of `Loads`' fields, with the words that name it.
NAMED = {
    "Q": "the shear force Q",
    "sigma": "the bulk tension sigma",
    "P": "the normal load P",
    "delta": "the tangential displacement delta",
}
INPUTS = tuple(NAMED)

#: Inputs the engine turns into another before a model sees the loads: a prescribed ``delta`` is met
#: by the ``Q`` it solves for, so a model that follows ``Q`` runs it (`fretting.engine.follow.displaced`).
CONVERTED = {"delta": "Q"}


@dataclass(frozen=True, eq=False)
class LoadBlock:
    """The loads of a run of steps: each field of `Loads` as an array over the steps (None: not given).

    Where ``delta`` is given, a step prescribes either ``Q`` or ``delta``: the other is NaN there.

    ``block[k]`` is the `Loads` of step ``k``, ``block[steps]`` (a slice or an index array) the
    block of those steps.
    """

    Q: np.ndarray
    sigma: np.ndarray
    P: np.ndarray | None = None
    delta: np.ndarray | None = None

    def __len__(self):
        return len(self.Q)

    def __getitem__(self, steps):
        P, delta = self.P, self.delta
        if isinstance(steps, (int, np.integer)):
            displaced = delta is not None and not np.isnan(delta[steps])
            return Loads(
                float(self.Q[steps]),
                float(self.sigma[steps]),
                None if P is None else float(P[steps]),
                float(delta[steps]) if displaced else None,
            )
        return LoadBlock(
            self.Q[steps], self.sigma[steps], None if P is None else P[steps], None if delta is None else delta[steps]
        )


def edge_loads(loads, contact):
    """The loads that make slip at the edges of `contact` and its normal load [N/m]: ``Q - pi a sigma / 4``
    (at ``x = -a``), ``Q + pi a sigma / 4`` (at ``+a``) and ``P``, the last axis of the ndarray returned.

    The first two are the numerators of the fully stuck traction of eqs (9) and (20), ``q = (Q / pi +
    sigma x / 4) / sqrt(a^2 - x^2)``, at the edges, with the half-width ``a`` at the contact's ``P``:
    a change of either makes a slip zone at its edge wherever the pressure vanishes there.
    `loads` is a `Loads` (shape (3,)) or a `LoadBlock` (shape (steps, 3)); ``P`` None is the contact's.
    The same operations on floats (one step: the engine tallies them at every increment, where numpy's
    call on small arrays would cost more than the sums) or elementwise on arrays: a step's row is the
    same either way, bit for bit.
    """
    a, P = contact.a, contact.P if loads.P is None else loads.P
    if isinstance(loads, Loads):
        return np.array(_at_edges(loads.Q, loads.sigma, P, a))
    Q = np.asarray(loads.Q, dtype=float)
    return np.stack(_at_edges(Q, np.asarray(loads.sigma, dtype=float), np.broadcast_to(P, Q.shape), a), axis=-1)


def _at_edges(Q, sigma, P, a):
    """``(Q - pi a sigma / 4, Q + pi a sigma / 4, P)`` of floats, or of arrays elementwise (`edge_loads`)."""
    return Q - np.pi * a * sigma / 4, Q + np.pi * a * sigma / 4, P
