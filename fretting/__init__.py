"""fretting: partial-slip half-plane contacts under arbitrary shear and bulk-tension histories."""

from fretting import models
from fretting._version import __version__ as __version__
from fretting.analysis.methods import partial_slip
from fretting.engine.choice import ModelFallbackWarning, choose_model
from fretting.engine.recorder import final_state
from fretting.engine.runner import run_file
from fretting.engine.simulation import adapted_mesh, simulate
from fretting.engine.stepper import Stepper
from fretting.errors import FrettingError, GrossSlipError, HistoryError, SolverError
from fretting.loading.history import History
from fretting.loading.history_file import HistoryFileError, read_history
from fretting.loading.loads import Loads
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.galerkin import DEFAULT_RTOL, MAX_DEFAULT_MESH, MAX_DEFAULT_WORK
from fretting.models.state import State
from fretting.physics.contact import Contact, plane_strain_modulus
from fretting.physics.profiles import FlatPunch, Gap, Hertz, Profile, RoundedFlat
from fretting.results.io import ResultError, join_results, load, save
from fretting.studies.sweeps import sweep

__all__ = [
    "Contact",
    "DEFAULT_NODES",
    "DEFAULT_RTOL",
    "MAX_DEFAULT_MESH",
    "MAX_DEFAULT_WORK",
    "FlatPunch",
    "FrettingError",
    "Gap",
    "GrossSlipError",
    "Hertz",
    "History",
    "HistoryError",
    "HistoryFileError",
    "Loads",
    "ModelFallbackWarning",
    "Profile",
    "ResultError",
    "RoundedFlat",
    "SolverError",
    "State",
    "Stepper",
    "adapted_mesh",
    "choose_model",
    "final_state",
    "join_results",
    "load",
    "models",
    "partial_slip",
    "plane_strain_modulus",
    "read_history",
    "run_file",
    "save",
    "simulate",
    "sweep",
]
