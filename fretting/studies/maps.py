"""Fretting-fatigue maps: the nucleation boundary and life against contact size.

Two maps of a test programme, each a set of runs of one test shape:

- `nucleation_boundary`: for each bulk stress amplitude ``sigma_a``, the shear force amplitude ``Q_a`` at which
  a criterion read at the critical distance reaches its fatigue limit or a life (a threshold search,
  `fretting.analysis.fatigue.threshold_of`): the boundary between nucleation and none in the ``(Q_a,
  sigma_a)`` plane, the map fretting-fatigue programmes draw (e.g. Araujo & Nowell 2002 plot their tests on
  it).
- `life_against_size`: the criterion's life for each contact size at the same loads, against a run-out life:
  the size effect of Nowell & Hills (1990), where contacts below a critical size did not fail.

A test shape is a callable giving ``(fretting.Contact, fretting.History)`` for the varied values, e.g. a
`FileScene`: a history file whose dotted keys (``loading[1].Q_amplitude``, ``contact.R``, as in sweep files,
docs/guide/sweeps.md) take the values. The points of a map are independent: with ``scheduler`` they run as
`dask.delayed` tasks (``"processes"``, ``"threads"``, or a ``distributed.Client``); a `FileScene` can be sent to
other processes, a lambda only to threads.

References
----------
D. Nowell and D. A. Hills, Crack initiation criteria in fretting fatigue, Wear 136 (1990) 329-343.
J. A. Araujo and D. Nowell, The effect of rapidly varying contact stress fields on fretting fatigue,
International Journal of Fatigue 24 (2002) 763-775.
"""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from fretting.analysis import fatigue
from fretting.analysis.fatigue import BracketError, read_last_cycle, threshold_of
from fretting.errors import MissingDependencyError
from fretting.loading.history_file import HistoryFileError, read_history_data, read_history_source
from fretting.studies.sweeps import KEY, put

__all__ = ["FileScene", "RUNOUT", "life_against_size", "nucleation_boundary"]

#: Default run-out life [cycles] of `life_against_size`: tests that reach it unbroken are stopped (10^7 is the usual
#: end of fretting-fatigue tests on aluminium alloys, e.g. Nowell & Hills 1990).
RUNOUT = 1e7


@dataclass(frozen=True)
class FileScene:
    """A history file whose keys take values: ``scene(*values) -> (contact, history)``.

    Each call reads the file again and checks it with the values in place, as `fretting.read_history` does.

    Parameters
    ----------
    path : str or os.PathLike
        History file (format of `fretting.read_history`).
    keys : tuple of str
        Dotted keys as a sweep's grid has them (`fretting.studies.sweeps.KEY`: ``contact.NAME``,
        ``loading[N].NAME`` with blocks counted from 1), one per value; a key may be one the file leaves at its
        default, in a table the file has.

    Raises
    ------
    OSError
        When the file cannot be read.
    HistoryFileError
        ``file: key: problem`` for a malformed key or a table the file lacks; on a call, for a value the key does
        not take.
    """

    path: Path
    keys: tuple[str, ...]

    def __post_init__(self):
        source = read_history_source(self.path)
        object.__setattr__(self, "path", Path(source.path))
        object.__setattr__(self, "keys", tuple(self.keys))
        data = tomllib.loads(source.text)
        for key in self.keys:
            _with(self.path, data, key, None)

    def __call__(self, *values):
        if len(values) != len(self.keys):
            raise ValueError(f"values: found {len(values)}, expected one for each of {', '.join(self.keys)}")
        text = self.path.read_text(encoding="utf-8")
        data = tomllib.loads(text)
        for key, value in zip(self.keys, values, strict=True):
            data = _with(self.path, data, key, value.item() if isinstance(value, np.generic) else value)
        return read_history_data(self.path, text, data)


def _with(path, data, key, value):
    """A copy of the history file's `data` with the dotted `key` set to `value` (None: only check that its
    table exists), as a sweep sets its grid keys (`fretting.studies.sweeps.put`)."""
    if not (isinstance(key, str) and KEY.fullmatch(key)):
        raise HistoryFileError(path, None, key, 'found a malformed key, expected one like "loading[1].Q_amplitude"')
    data = copy.deepcopy(data)
    if not put(data, key, value):
        raise HistoryFileError(path, None, key, "found no such table, expected a key of one of the file's tables")
    return data


def nucleation_boundary(
    scene,
    sigma_amplitudes,
    bracket,
    criterion,
    material,
    life=None,
    at="point",
    nu=None,
    bulk_state="plane strain",
    model=None,
    scheduler=None,
) -> xr.Dataset:
    """The nucleation boundary for a life in the ``(Q_a, sigma_a)`` plane: for each ``sigma_a``, the threshold ``Q_a``.

    Parameters
    ----------
    scene : callable
        ``(Q_a, sigma_a) -> (fretting.Contact, fretting.History)``, the test at the amplitudes ``Q_a`` [N/m] of
        ``Q`` and ``sigma_a`` [Pa] of the bulk stress, e.g. ``FileScene(path, ("loading[1].Q_amplitude",
        "loading[1].sigma_amplitude"))``.
    sigma_amplitudes : sequence of float
        The bulk stress amplitudes [Pa] of the map's points.
    bracket : (float, float)
        The ``Q_a`` [N/m] searched between, at every point, below ``f P`` (a run that slides raises
        `fretting.GrossSlipError`).
    criterion, material, life, at, nu, bulk_state, model
        As `fretting.analysis.fatigue.threshold_of`: the target is the criterion's fatigue limit, or `life`.
    scheduler : str or distributed.Client, optional
        Run the points as `dask.delayed` tasks on this scheduler (``"processes"``, ``"threads"``, a Client);
        None runs them one after another.

    Returns
    -------
    xarray.Dataset
        On dim ``sigma_amplitude`` [Pa]: ``Q_threshold`` [N/m] (NaN where the criterion does not cross its target
        within the bracket), ``side`` (0 a threshold found; 1 the target is exceeded over the whole bracket, so the
        test nucleates at every ``Q_a`` of it; -1 never reached), ``runs``; attributes ``criterion``, ``target``,
        ``at``, ``bracket``.
    """
    sigmas = [float(value) for value in sigma_amplitudes]
    search = (tuple(float(end) for end in bracket), criterion, material, life, at, nu, bulk_state, model)
    points = _computed(scheduler, _boundary_point, [(scene, sigma, *search) for sigma in sigmas])
    Q, side, runs = (np.array(values) for values in zip(*points, strict=True))
    target = "fatigue limit" if life is None else f"life {life:.6g} cycles"
    return xr.Dataset(
        {
            "Q_threshold": ("sigma_amplitude", Q, {"units": "N/m", "long_name": "threshold shear force amplitude"}),
            "side": (
                "sigma_amplitude",
                side.astype(np.int8),
                {"units": "1", "long_name": "0: threshold found; 1: above the target over the bracket; -1: below"},
            ),
            "runs": ("sigma_amplitude", runs.astype(np.int64), {"units": "1", "long_name": "values searched"}),
        },
        coords={"sigma_amplitude": ("sigma_amplitude", sigmas, {"units": "Pa", "long_name": "bulk stress amplitude"})},
        attrs={"criterion": criterion, "target": target, "at": at, "bracket": list(search[0])},
    )


def _boundary_point(scene, sigma, bracket, criterion, material, life, at, nu, bulk_state, model):
    """``(Q_a threshold or NaN, side, runs)`` of one point of `nucleation_boundary`."""
    try:
        found = threshold_of(
            lambda Q_a: scene(Q_a, sigma),
            bracket,
            criterion,
            material,
            life=life,
            at=at,
            nu=nu,
            bulk_state=bulk_state,
            model=model,
            name="Q_a",
            units=" N/m",
        )
    except BracketError as error:
        return math.nan, 1 if error.ends[0] > 0 else -1, 2
    return found.amplitude, 0, found.runs


def life_against_size(
    scene,
    sizes,
    criterion,
    material,
    at="point",
    runout=RUNOUT,
    nu=None,
    bulk_state="plane strain",
    model=None,
    scheduler=None,
) -> xr.Dataset:
    """The criterion's life read at `at` for each contact size, against a run-out life.

    Parameters
    ----------
    scene : callable
        ``size -> (fretting.Contact, fretting.History)``, e.g. ``FileScene(path, ("contact.R",))``, or a function
        that scales ``R``, ``P`` and ``Q`` together to keep ``p0`` and ``Q / (f P)`` (the size effect at constant
        peak pressure of Araujo & Nowell 2002).
    sizes : sequence of float
        The values given to `scene` (e.g. pad radii [m]).
    criterion, material, at, nu, bulk_state, model
        As `fretting.analysis.fatigue.read_last_cycle`.
    runout : float
        Life [cycles] at which a test stops unbroken.
    scheduler : str or distributed.Client, optional
        As `nucleation_boundary`.

    Returns
    -------
    xarray.Dataset
        On dim ``size`` (the values of `sizes`): ``N_f`` (the criterion's life, `fretting.analysis.fatigue.life`),
        ``parameter`` (with its units), ``a`` [m] and ``p0`` [Pa] of the contact, and ``run_out`` (``N_f >=
        runout``); attributes ``criterion``, ``at``, ``runout``.
    """
    sizes = [float(value) for value in sizes]
    options = (criterion, material, at, nu, bulk_state, model)
    points = _computed(scheduler, _size_point, [(scene, size, *options) for size in sizes])
    lives, parameters, a, p0 = (np.array(values, dtype=float) for values in zip(*(p[:4] for p in points), strict=True))
    units = points[0][4]
    data = {
        "N_f": (lives, "1", "cycles to failure"),
        "parameter": (parameters, units, f"{criterion} parameter read at {at}"),
        "a": (a, "m", "contact half-width"),
        "p0": (p0, "Pa", "peak pressure"),
        "run_out": (lives >= runout, "1", f"life at least the run-out life {runout:.6g} cycles"),
    }
    return xr.Dataset(
        {name: ("size", value, {"units": u, "long_name": text}) for name, (value, u, text) in data.items()},
        coords={"size": ("size", sizes, {"long_name": "contact size given to the scene"})},
        attrs={"criterion": criterion, "at": at, "runout": float(runout)},
    )


def _size_point(scene, size, criterion, material, at, nu, bulk_state, model):
    """``(N_f, parameter, a, p0, units)`` of one point of `life_against_size`."""
    contact, history = scene(size)
    values = read_last_cycle(contact, history, criterion, material, at=at, nu=nu, bulk_state=bulk_state, model=model)
    return float(fatigue.life(values, material)), float(values.parameter), contact.a, contact.p0, values.parameter.units


def _computed(scheduler, function, arguments):
    """``[function(*a) for a in arguments]``, one after another (`scheduler` None) or as dask tasks on `scheduler`."""
    if scheduler is None:
        return [function(*each) for each in arguments]
    try:
        import dask
    except ImportError as error:
        raise MissingDependencyError(
            f"maps run on dask when a scheduler is given, and dask is not installed ({error}): "
            f"pip install 'fretting[sweep]'"
        ) from None
    tasks = [dask.delayed(function)(*each) for each in arguments]
    return list(dask.compute(*tasks, scheduler=scheduler))
