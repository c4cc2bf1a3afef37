"""The runner: a history file run to a result file in chunks, with checkpoints and resume.

`run_file` steps one `Stepper` through the history chunk by chunk, so the model's set-up (the
stiffness, the exact model's branches) is built once per run. Chunks are joined as they come
(`fretting.results.io.Joiner`) into a *part*, which is saved to the checkpoint folder
``OUTPUT.checkpoint/`` every `CHECKPOINT_SECONDS`, before it would hold the fields of more than
`PART_CYCLES` cycles (or more than `PART_SCALAR_CYCLES` cycles), and on an interruption; a part
saved is never rewritten, so memory does not grow with the run's cycles and a checkpoint costs
only the part. At the end the parts are joined into the result file
(`fretting.results.io.save_joined`: the per-cycle rows appended part by part) and the folder is
deleted. A run resumed from its checkpoint goes on from its last part's final state, to the same
result bit for bit.

Before any stepping a run checks that it can write its output and takes the output's lock
(`holding`): a second run of the same output is refused at once, and the temporary files of a
killed run are deleted, since no live run can own them.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from filelock import FileLock, Timeout

from fretting.engine.choice import ModelFallbackWarning
from fretting.engine.follow import skippable
from fretting.engine.recorder import (
    CYCLE_PEAKS_TALLIED,
    CycleFields,
    FieldSelector,
    Recorder,
    final_state,
    recorded_spec,
    recorded_steps,
)
from fretting.engine.stepper import Stepper
from fretting.errors import GrossSlipError
from fretting.loading.history_file import read_history_source
from fretting.results.io import (
    Joiner,
    ResultError,
    join_results,
    joined_steps,
    load,
    open_result,
    remove_temporaries,
    save,
    save_joined,
    source_attributes,
)
from fretting.results.notes import UNRESOLVED, observed_slip_nodes, unresolved_cycles

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

    from fretting.models.base import ModelSpec

__all__ = ["CHECKPOINT_SECONDS", "PART_CYCLES", "PART_SCALAR_CYCLES", "Run", "checkpointed", "holding", "run_file"]

#: Steps of the first chunk run at a time: how often progress is reported and a checkpoint can be
#: written. A chunk that takes less than CHUNK_SECONDS doubles the next one's steps, so that runs
#: whose cycles repeat (copied, not solved) are not cut into many short runs, each of which
#: solves its first cycles anew.
CHUNK_STEPS = 200
CHUNK_SECONDS = 1.0
#: Most steps of one chunk: 4096 cycles of 64 steps, whose per-cycle fields are held twice while
#: the chunk is joined. Each chunk solves its first cycles anew.
MAX_CHUNK_STEPS = 2**18

#: Seconds between checkpoints by default: at most a minute of work lost in a crash. Each
#: checkpoint saves the part joined since the last one.
CHECKPOINT_SECONDS = 60.0

#: Cycles whose per-cycle fields a part holds at most, whatever the time: the rows held in memory
#: (5 rows of N float32 each: 80 MB at 500 nodes). Each part costs a file written and read again
#: at the end, whatever its size, so parts are made large.
PART_CYCLES = 8192

#: Cycles a part holds at most where a `CycleFields` policy stores the fields of some cycles only:
#: their per-cycle scalars (17 bytes a cycle: 18 MB) and the fields of the cycles chosen, at most
#: `PART_CYCLES` of them.
PART_SCALAR_CYCLES = 2**20

#: Cycles that one chunk begins at most: its per-cycle tallies (six fields of N float64 each)
#: are held until the chunk is joined into the part.
CHUNK_CYCLES = 1024


@dataclass(frozen=True)
class Run:
    """What `run_file` did: the result written, where, and what the user should be told.

    Attributes
    ----------
    output : Path
    notes : list of str
        One line each: a model that fell back, a resume that found no checkpoint.
    """

    output: Path
    notes: list

    @property
    def result(self):
        """The result written (xarray.Dataset), opened lazily: its variables are read when used."""
        return open_result(self.output)


def checkpoint_path(output):
    """The checkpoint folder of the result file `output`: its parts, ``000001.h5``, ``000002.h5``, ..."""
    output = Path(output)
    return output.with_name(f"{output.name}.checkpoint")


def _parts(checkpoint):
    """The part files in the folder `checkpoint`, in order (none if there is no folder)."""
    return sorted(checkpoint.glob("[0-9]" * 6 + ".h5")) if checkpoint.is_dir() else []


def checkpointed(checkpoint: str | os.PathLike):
    """The partial result kept in the checkpoint folder `checkpoint` (its parts joined, in memory).

    Raises
    ------
    FileNotFoundError
        When the folder holds no part.
    """
    parts = _parts(Path(checkpoint))
    if not parts:
        raise FileNotFoundError(errno.ENOENT, "no checkpoint parts", str(checkpoint))
    return join_results([load(part) for part in parts])


def lock_path(output):
    """The lock file of the result file `output`: hidden beside it."""
    output = Path(output)
    return output.with_name(f".{output.name}.lock")


@contextlib.contextmanager
def holding(output):
    """Hold the lock of the result file `output` while a run writes it and its checkpoint.

    The lock is `filelock.FileLock` on `lock_path`: an ``flock`` on Unix, which the system
    releases when the process ends, killed or not, so a killed run never blocks the next. It is
    taken without waiting: a run whose output another run is writing is refused.

    filelock's Unix lock keeps its file on release in some versions (so that processes waiting on
    one name never lock two files), so it is deleted here, while still held: no lock file is left
    after a run. That is safe because no run waits for the lock and because filelock, from 3.21 on
    (the version required), refuses a lock it got on a file deleted since it opened it: a run
    that opened the file just before the deletion is refused as if the lock were held.

    Raises
    ------
    OSError
        When another run holds the lock (EBUSY), or the lock file cannot be created (why, and
        the folder); ``filename`` is `output`.
    """
    output, path = Path(output), lock_path(output)
    lock = FileLock(path)
    try:
        lock.acquire(blocking=False)
    except Timeout:
        raise OSError(
            errno.EBUSY,
            f"another run is writing it (it holds {path.name}): wait for it to end, or write elsewhere",
            str(output),
        ) from None
    except OSError as error:
        raise OSError(error.errno, f"cannot write in {path.parent}: {error.strerror}", str(output)) from None
    try:
        yield
    finally:
        with contextlib.suppress(OSError):  # Windows refuses while it is open; its filelock deletes it on release
            path.unlink()
        lock.release()


def writable(output):
    """`output` as a Path, once its folder exists; refused if it is a folder or lies under a file.

    Raises
    ------
    OSError
        ``filename`` `output`, ``strerror`` why it cannot be written.
    """
    output = Path(output)
    try:
        output.parent.mkdir(parents=True, exist_ok=True)
    except (FileExistsError, NotADirectoryError):
        blocking = next(parent for parent in reversed(output.parents) if parent.exists() and not parent.is_dir())
        raise OSError(errno.ENOTDIR, f"cannot write: {blocking} is a file, not a folder", str(output)) from None
    except OSError as error:
        raise OSError(error.errno, f"cannot create its folder: {error.strerror}", str(output)) from None
    if output.is_dir():
        raise OSError(errno.EISDIR, "cannot write: it is a folder, expected a file name", str(output))
    return output


def run_file(
    history_path: str | os.PathLike,
    output: str | os.PathLike,
    model: ModelSpec | None = None,
    *,
    record: ArrayLike | str | None = None,
    resume: bool = False,
    checkpoint_interval: float = CHECKPOINT_SECONDS,
    progress: Callable[[int, int], object] | None = None,
    every_step: bool = False,
    cycle_fields: str = "default",
) -> Run:
    """Run a history file and write its result to `output`, checkpointed and resumable.

    Parameters
    ----------
    history_path : str or Path
        History file (TOML, `fretting.read_history`).
    output : str or Path
        Result file (netCDF-4/HDF5), written atomically at the end; its checkpoint is
        ``OUTPUT.checkpoint`` beside it.
    model : ModelSpec, optional
        The model (`fretting.models`); default `fretting.choose_model`'s.
    record : array_like of int or "all", optional
        Steps whose fields are stored (`fretting.engine.recorder.recorded_steps`).
    resume : bool
        Continue from the checkpoint of an interrupted run of the same history file and model.
    checkpoint_interval : float
        Seconds between checkpoints (0: after every chunk).
    progress : callable, optional
        ``progress(done, total)``: steps done so far and in all, after each chunk.
    every_step : bool
        Solve every step. By default the steps inside straight stretches of the load path that
        are not recorded (`record`) are skipped (`fretting.engine.follow.skippable`): the energy, ``w`` and
        slip range are the same to rounding, but the specimen's ``sigma_xx`` peaks per cycle
        are not tallied (the result's ``cycle_peaks`` attribute says which are).
    cycle_fields : str
        The cycles whose per-cycle fields (``w``, ``slip_amplitude``, the peaks) are stored
        (`fretting.engine.recorder.CycleFields.parse`): ``"default"`` (every cycle of histories
        of up to `fretting.engine.recorder.CYCLE_FIELDS_STORED` cycles, else the first, the last,
        every k-th and those of a new maximum of the energy), ``"all"``, or a list such as
        ``"first,last,every=100,maxima"``. Cycles chosen from all of them have their fields on
        dims ``(field_cycle, x)``, beside the accumulated fields over every complete cycle
        (``w_total``, ``slip_amplitude_max``, ...: with every cycle's fields stored, the sums and
        maxima of their rows). The per-cycle scalars cover every cycle whatever the policy; the
        result's ``cycle_fields`` attribute records the policy.

    Returns
    -------
    Run

    Raises
    ------
    OSError
        Before any step, when `output` cannot be written (`writable`) or another run is writing
        it (`holding`).
    ValueError
        When `cycle_fields` is not a policy.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import fretting as fr
    >>> from fretting.loading.examples import example_path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     run = fr.run_file(example_path("hertz_shear_cycling"), Path(folder) / "result.nc", fr.models.Grid(32))
    ...     print(run.output.name, run.output.is_file(), run.result.sizes["cycle_number"], len(run.notes))
    result.nc True 5 1
    >>> run.notes[0].startswith("5 load cycles (cycle 1 to 5) slipped over fewer than 100 of the grid model's 32")
    True
    """
    source = read_history_source(history_path)
    policy = CycleFields.parse(cycle_fields, source.history.cycle_count)
    output = writable(output)
    with holding(output):
        checkpoint = checkpoint_path(output)
        for path in (output, checkpoint):  # those of `save`; beside the checkpoint: of fretting 0.1
            remove_temporaries(path)
        if checkpoint.is_dir():
            remove_temporaries(_next_part(checkpoint))
        history = source.history
        record = recorded_steps(record, len(history))
        skipping = not every_step and record.size < len(history)  # a recorded step is solved
        attributes = source_attributes(source) | {"cycle_fields": str(policy)}
        start, state, notes, done = _started(checkpoint, source, model, resume, skipping, attributes)
        if history.has_cycles and not policy.all:
            notes.append(
                f"per-cycle fields (w, slip_amplitude, the peaks) are stored for the cycles {policy} only "
                "(field_cycle); w_total and the *_max fields add up every cycle (--cycle-fields all stores each)"
            )
        if skipping:
            notes.append(
                "the unrecorded steps inside straight stretches are skipped: sigma_xx_peak and sigma_xx_q_peak "
                "are not tallied (--every-step solves every step)"
            )
        with _resume_said(checkpoint):
            stepper = Stepper(source.contact, model if state is None else None, state)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", ModelFallbackWarning)
                stepper.resolve(history, record)
            for warning in caught:  # a fallback becomes a note of the run; any other warning goes on
                if issubclass(warning.category, ModelFallbackWarning):
                    notes.append(str(warning.message))
                else:
                    warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
            selector = (
                None if not history.has_cycles or policy.all else FieldSelector(policy, history.cycle_ends(), done)
            )
            part, written = Joiner(), time.monotonic()
            try:
                for chunk in _chunks(stepper, history, record, start, skipping):
                    start += chunk.attrs["steps"] - 1
                    part.add(chunk if selector is None else selector.take(chunk, start))
                    if progress is not None:
                        progress(start, len(history) - 1)
                    if time.monotonic() - written >= checkpoint_interval or _full(part, selector is not None):
                        _save_part(part, checkpoint, attributes)
                        part, written = Joiner(), time.monotonic()
            except KeyboardInterrupt:
                if len(part):
                    _save_part(part, checkpoint, attributes)
                raise
            except GrossSlipError:
                shutil.rmtree(checkpoint, ignore_errors=True)  # resuming would only reach it again
                raise
            del source, history  # the loads of every step: the result holds what it records
            if len(part):
                _save_part(part, checkpoint, attributes)
            note = parts_note(_parts(checkpoint))
            if note is not None:
                notes.append(note)
                attributes[UNRESOLVED] = note
            save_joined(_parts(checkpoint), output, attributes)
            shutil.rmtree(checkpoint)
    return Run(output, notes)


@contextlib.contextmanager
def _resume_said(checkpoint):
    """A block whose interrupt or failure to write (a full disk, a folder turned read-only), wherever
    it comes, says to resume where parts of the run are on disk."""
    try:
        yield
    except KeyboardInterrupt:
        if _parts(checkpoint):
            raise KeyboardInterrupt(_kept(checkpoint)) from None
        raise
    except OSError as error:
        if _parts(checkpoint):
            raise OSError(error.errno, f"{error.strerror or error}; {_kept(checkpoint)}", error.filename) from None
        raise


def _kept(checkpoint):
    """What to do with the parts of a run left in `checkpoint`."""
    return f"progress kept in {checkpoint}; continue with --resume"


def _started(checkpoint, source, model, resume, skipping, attributes):
    """``(start, state, notes, done)`` a run begins with: the checkpoint's last step, state and
    result so far (its steps, state and accumulated fields) when resumed, else step 0 and None."""
    if checkpoint.is_file():
        raise ResultError(f"{checkpoint}: found the checkpoint file of an earlier version of fretting: delete it")
    if _parts(checkpoint) and not resume:
        raise ResultError(
            f"{checkpoint}: found the checkpoint of an interrupted run: continue it with --resume, or delete it"
        )
    if resume and _parts(checkpoint):
        done = _resumable(checkpoint, source, model, skipping, attributes)
        return done.attrs["steps"] - 1, final_state(done), [], done
    shutil.rmtree(checkpoint, ignore_errors=True)  # a folder without parts: killed before its first
    notes = [f"{checkpoint}: no checkpoint to resume from: the run starts at step 0"] if resume else []
    return 0, None, notes, None


def _damaged(checkpoint):
    """What to do with a part of `checkpoint` that cannot be read (a part is written whole or not at
    all, so only a change made outside the run damages one)."""
    return f"delete it and the parts after it to resume from those before, or delete {checkpoint} to start again"


def _save_part(part, checkpoint, attributes):
    """Save the joined chunks `part` as the next part file of the folder `checkpoint`."""
    checkpoint.mkdir(exist_ok=True)
    save(part.result().assign_attrs(attributes), _next_part(checkpoint))


def _next_part(checkpoint):
    """The file of the next part saved to the folder `checkpoint`."""
    return checkpoint / f"{len(_parts(checkpoint)) + 1:06d}.h5"


def _chunks(stepper, history, record, start, skipping):
    """Results of successive chunks of `history` from step `start`, stepped by `stepper`.

    Each chunk records the steps of `record` (numbers in the whole history) that it reaches; a
    later chunk's step 0 is the last one's end. Only the stepper's state is kept between chunks.
    `skipping`: skip the steps inside straight stretches that are not recorded (`Recorder`).
    """
    steps, first = CHUNK_STEPS, start
    while first == start == 0 or start < len(history) - 1:
        stop = _cut(history, record, start, min(start + steps, len(history) - 1), stepper.model.contact, skipping)
        began = time.monotonic()
        mine = record[(record >= first) & (record <= stop)] - start
        chunk = history[start : stop + 1]
        recorder = Recorder(stepper.model, chunk, mine, skipping)
        try:
            state = stepper.run(chunk, recorder)
        except GrossSlipError as error:
            raise GrossSlipError(start + error.step, error.Q, error.sigma, error.limit, error.note) from None
        yield recorder.dataset(state)
        start, first = stop, stop + 1
        fast = time.monotonic() - began < CHUNK_SECONDS
        steps = min(2 * steps, MAX_CHUNK_STEPS) if fast else max(steps // 2, CHUNK_STEPS)
        if stop == len(history) - 1:
            return


def _cut(history, record, start, stop, contact, skipping):
    """`stop`, or an earlier step, at which the chunk from `start` ends: one that begins at most
    `_chunk_cycles` cycles and, when `skipping`, ends at a step that the whole run solves too (not
    `fretting.engine.follow.skippable` in the whole history), so that cutting keeps the run bit
    for bit; a straight stretch longer than the chunk is cut at its end."""
    if history.has_cycles:
        cycle = history[start : stop + 1].cycle  # the chunk's: a long history's loads are formed per chunk
        begins = np.flatnonzero(np.diff(cycle)) + start + 1  # steps that begin a stretch
        most = _chunk_cycles()
        stop = stop if begins.size < most else int(begins[most - 1])
    if not skipping:
        return stop
    end = stop
    while True:  # a straight stretch longer than the chunk: the chunk ends where the stretch does
        solved = _solved(history, record, start, end, contact)
        if solved.size:
            below = solved[solved <= stop]
            return int(below[-1] if below.size else solved[0])
        end = min(2 * end - start, len(history) - 1)


def _full(part, selected):
    """True if the next chunk could take the Joiner `part` past `PART_CYCLES` cycles of fields (on
    ``field_cycle`` where `selected`: a policy chose some cycles) or `PART_SCALAR_CYCLES` cycles."""
    fields = part.rows("field_cycle" if selected else "cycle_number")
    return fields + _chunk_cycles() > PART_CYCLES or part.cycles + _chunk_cycles() > PART_SCALAR_CYCLES


def _chunk_cycles():
    """Cycles that a chunk begins at most: `CHUNK_CYCLES`, and no more than a part holds, so that a
    part saved before it would overflow holds at most `PART_CYCLES`."""
    return min(CHUNK_CYCLES, PART_CYCLES)


def _solved(history, record, start, end, contact):
    """Steps in ``(start, end]`` that a run skipping steps solves (not `skippable` in the whole history)."""
    near = history[start : min(end + 2, len(history))]  # the step after `end` decides if `end` is skippable
    recorded = np.zeros(len(near), dtype=bool)
    recorded[record[(record >= start) & (record < start + len(near))] - start] = True
    return np.flatnonzero(~skippable(near, recorded, contact)[1 : end - start + 1]) + start + 1


def parts_note(parts):
    """The note of `fretting.results.notes.unresolved_cycles` of a run kept in the result files `parts` (in
    order), or None: as `fretting.results.notes.noted` of their join, read a part at a time. A cycle that
    spans two parts is the later part's, whose tally carries on from the earlier; its recorded steps
    are counted in each."""
    cycles, observed, attrs, x, p = {}, {}, None, None, None
    for part in parts:
        with open_result(part) as opened:
            if attrs is None:
                attrs, x = dict(opened.attrs), opened.x.values
                p = opened.p.values if "p" in opened and opened.p.dims == ("x",) else None
            if "cycle_number" not in opened.dims:
                continue
            numbers = opened.cycle_number.values
            unknown = np.full((numbers.size, 3), np.nan)  # a part written before the ranges were
            ranges = opened.cycle_load_range.values if "cycle_load_range" in opened else unknown
            energies = opened.cycle_dissipation.values
            cycles |= zip(numbers.tolist(), zip(energies.tolist(), ranges, strict=True), strict=True)
            seen = observed_slip_nodes(opened.stick.values, opened.cycle.values, numbers)
            for number, count in zip(numbers.tolist(), seen.tolist(), strict=True):
                observed[number] = max(observed.get(number, 0), count)
    if not cycles:
        return None
    numbers = np.array(sorted(cycles))
    energies, ranges = zip(*(cycles[number] for number in numbers.tolist()), strict=True)
    seen = [observed[number] for number in numbers.tolist()]
    return unresolved_cycles(attrs, numbers, energies, np.array(ranges), x, p, seen)


def _resumable(checkpoint, source, model, skipping, attributes):
    """The recorded steps and state of the parts in `checkpoint` (their per-cycle rows left on disk),
    checked to belong to this history file, the `model` asked (None: any), to have `skipping`
    steps or not and to store the per-cycle fields of `attributes`' ``cycle_fields`` policy."""
    try:
        done = joined_steps(_parts(checkpoint))
    except ResultError as error:  # a part damaged, or missing between two others
        raise ResultError(f"{error}; {_damaged(checkpoint)}") from None
    if done.attrs.get("history_sha256") != source.sha256:
        raise ResultError(f"{checkpoint}: found a run of another version of {source.path}, expected this one")
    if done.attrs.get("cycle_fields") != attributes["cycle_fields"]:
        raise ResultError(
            f"{checkpoint}: found a run with cycle_fields = {done.attrs.get('cycle_fields')}, "
            f"expected {attributes['cycle_fields']}"
        )
    if done.attrs.get("cycle_peaks") != CYCLE_PEAKS_TALLIED[skipping]:
        ways = ["every step solved (--every-step)", "steps skipped (without --every-step)"]
        raise ResultError(f"{checkpoint}: found a run with {ways[not skipping]}, expected {ways[skipping]}")
    found = recorded_spec(done)
    if model is None and not found.is_default():
        raise ResultError(
            f"{checkpoint}: found a run with {_described(found.attributes())}, expected the default model"
        )
    if model is not None and not model.attributes().items() <= found.attributes().items():
        raise ResultError(
            f"{checkpoint}: found a run with {_described(found.attributes())}, "
            f"expected {_described(model.attributes())}"
        )
    history, steps = source.history, done.step.values
    same = done.attrs["steps"] <= len(history)
    if same:
        Q, sigma = history.at(steps)[:2]
        given = ~np.isnan(Q)  # NaN where the history prescribes delta: the run found its Q
        same = np.array_equal(done.Q.values[given], Q[given]) and np.array_equal(done.sigma.values, sigma)
    if not same:
        raise ResultError(f"{checkpoint}: found loads that {source.path} no longer gives (NumPy's random draws?)")
    return done


def _described(attributes):
    """``model = name, parameter = value, ...`` of a spec's attributes."""
    return ", ".join(f"{name} = {value}" for name, value in attributes.items())
