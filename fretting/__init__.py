"""fretting: partial-slip half-plane contacts under arbitrary shear and bulk-tension histories."""

from fretting.physics.contact import Contact, plane_strain_modulus
from fretting.errors import FrettingError, GrossSlipError, HistoryError, SolverError
from fretting.loading.history import History
from fretting.loading.history_file import HistoryFileError, read_history
from fretting.results.io import ResultError, join_results, load, save
from fretting.physics.methods import partial_slip
from fretting.physics.profiles import FlatPunch, Gap, Hertz, Profile, RoundedFlat
from fretting.engine.simulation import (
    DEFAULT_NODES,
    DEFAULT_RTOL,
    MAX_DEFAULT_MESH,
    State,
    adapted_mesh,
    final_state,
    simulate,
)
from fretting.studies.sweeps import sweep

__all__ = [
    "Contact",
    "DEFAULT_NODES",
    "DEFAULT_RTOL",
    "MAX_DEFAULT_MESH",
    "FlatPunch",
    "FrettingError",
    "Gap",
    "GrossSlipError",
    "Hertz",
    "History",
    "HistoryError",
    "HistoryFileError",
    "Profile",
    "ResultError",
    "RoundedFlat",
    "SolverError",
    "State",
    "adapted_mesh",
    "final_state",
    "join_results",
    "load",
    "partial_slip",
    "plane_strain_modulus",
    "read_history",
    "save",
    "simulate",
    "sweep",
]

__version__ = "0.1.0"
