"""Load histories: the trajectory of the shear force Q and the bulk tension sigma."""

from dataclasses import dataclass

import numpy as np

from fretting._validate import finite_array
from fretting.errors import HistoryError

__all__ = ["History"]


@dataclass(frozen=True, eq=False)
class History:
    """Loads at every step; step 0 is the starting state.

    Attributes
    ----------
    Q : ndarray, shape (n_steps,)
        Shear force per unit length [N/m].
    sigma : ndarray, shape (n_steps,)
        Differential bulk tension [Pa].
    vertex_step : ndarray of int, shape (n_vertices,)
        Step at which each vertex of the path is reached.
    cycle : ndarray of int, shape (n_steps,), optional
        Load cycle (1, 2, ...) that the increment ending at each step belongs to; 0 for
        steps outside any cycle (the starting state, ramps). None for histories without cycles.
    """

    Q: np.ndarray
    sigma: np.ndarray
    vertex_step: np.ndarray
    cycle: np.ndarray | None = None

    def __post_init__(self):
        Q = _loads("Q", self.Q)
        sigma = _loads("sigma", self.sigma)
        if Q.shape != sigma.shape:
            raise HistoryError(f"Q and sigma must have the same length, found {Q.size} and {sigma.size}")
        vertex_step = np.asarray(self.vertex_step, dtype=np.int64)
        if vertex_step.ndim != 1 or np.any(np.diff(vertex_step) < 0) or np.any(vertex_step >= Q.size):
            raise HistoryError("vertex_step must be non-decreasing steps of the history")
        arrays = {"Q": Q, "sigma": sigma, "vertex_step": vertex_step}
        if self.cycle is not None:
            cycle = np.asarray(self.cycle, dtype=np.int64)
            if cycle.shape != Q.shape or np.any(np.diff(cycle) < 0) or np.any(cycle < 0):
                raise HistoryError("cycle must give a non-decreasing cycle number >= 0 for every step")
            arrays["cycle"] = cycle
        for name, value in arrays.items():
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    def __len__(self):
        return self.Q.size

    @classmethod
    def piecewise_linear(cls, Q, sigma=None, steps_per_segment=16):
        """Straight segments between vertices of the (Q, sigma) path.

        Parameters
        ----------
        Q : array_like
            Shear force at the vertices [N/m]; the first vertex is the starting state.
        sigma : array_like, optional
            Bulk tension at the vertices [Pa]; zero when omitted.
        steps_per_segment : int or array_like of int
            Equal increments of each segment (one number for all, or one per segment).
        """
        Q = _loads("Q", Q)
        sigma = np.zeros_like(Q) if sigma is None else _loads("sigma", sigma)
        if Q.shape != sigma.shape:
            raise HistoryError(f"Q and sigma need one value per vertex, found {Q.size} and {sigma.size}")
        steps = np.broadcast_to(np.asarray(steps_per_segment), (Q.size - 1,))
        if steps.size and (not np.issubdtype(steps.dtype, np.integer) or np.any(steps < 1)):
            raise HistoryError(f"steps_per_segment must be integers >= 1, found {steps_per_segment!r}")
        fractions = [np.arange(1, n + 1) / n for n in steps]
        return cls(_segments(Q, fractions), _segments(sigma, fractions), np.concatenate([[0], np.cumsum(steps)]))


def _segments(vertices, fractions):
    """Values along straight segments; each segment ends exactly on its vertex."""
    pieces = [vertices[i] * (1 - u) + vertices[i + 1] * u for i, u in enumerate(fractions)]
    return np.concatenate([vertices[:1], *pieces])


def _loads(name, values):
    try:
        values = finite_array(name, values)
    except ValueError as error:
        raise HistoryError(str(error)) from None
    if values.size == 0:
        raise HistoryError(f"{name} is empty: a history needs at least its starting state")
    return values
