"""Exceptions raised by `fretting`."""

__all__ = ["FrettingError", "GrossSlipError", "HistoryError", "MissingDependencyError", "SolverError"]


class FrettingError(Exception):
    """Base class of the errors that `fretting` raises on purpose."""


class GrossSlipError(FrettingError, RuntimeError):
    """No stick zone is left: the contact slides, which force control cannot follow.

    Attributes
    ----------
    step : int or None
        The step whose load reaches gross slip (None: a single increment, `Stepper.step`).
    Q, sigma : float
        The loads of that step [N/m], [Pa].
    limit : float
        ``f P`` on the collocation grid [N/m].
    note : str or None
        What else the message says (which model would follow it).
    """

    def __init__(self, step, Q, sigma, limit, note=None):
        self.step, self.Q, self.sigma, self.limit, self.note = step, Q, sigma, limit, note
        where = "in this increment" if step is None else f"at step {step}"
        super().__init__(
            f"gross slip {where}: Q = {Q:.6g}, sigma = {sigma:.6g} leave no stick zone "
            f"(|Q| must stay below f P = {limit:.6g})" + ("" if note is None else f"; {note}")
        )


class HistoryError(FrettingError, ValueError):
    """A load history is malformed."""


class SolverError(FrettingError, RuntimeError):
    """An increment could not be solved to the friction conditions."""


class MissingDependencyError(FrettingError, ImportError):
    """A package of an optional extra (``pip install 'fretting[<extra>]'``) is not installed."""
