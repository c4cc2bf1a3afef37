"""fretting: partial-slip half-plane contacts under arbitrary shear and bulk-tension histories."""

from fretting.contact import Contact
from fretting.errors import FrettingError, GrossSlipError, HistoryError, SolverError
from fretting.history import History
from fretting.methods import partial_slip
from fretting.profiles import FlatPunch, Gap, Hertz, Profile, RoundedFlat
from fretting.simulate import DEFAULT_NODES, State, final_state, simulate

__all__ = [
    "Contact",
    "DEFAULT_NODES",
    "FlatPunch",
    "FrettingError",
    "Gap",
    "GrossSlipError",
    "Hertz",
    "History",
    "HistoryError",
    "Profile",
    "RoundedFlat",
    "SolverError",
    "State",
    "final_state",
    "partial_slip",
    "simulate",
]

__version__ = "0.1.0"
