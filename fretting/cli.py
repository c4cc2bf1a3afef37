"""The command line: ``fretting run | validate | info | plot | stress | export | examples | sweep | materials |
threshold | map`` (also ``python -m fretting``).

Exit codes: 0 success, 2 bad input (files, keys, values, arguments), 3 gross slip, 1 a solver
failure, 130 interrupted. Errors are one line on stderr; ``--debug`` shows the traceback.
"""

import argparse
import contextlib
import dataclasses
import json
import signal
import sys
import threading
from pathlib import Path

import numpy as np
import xarray as xr
from tqdm import tqdm

from fretting import __version__
from fretting._validate import positive
from fretting.analysis import nucleation
from fretting.analysis.fatigue import (
    CRITERIA,
    READINGS,
    BracketError,
    Material,
    MaterialFileError,
    apply,
    hot_spot,
    line_method,
    material_path,
    materials,
    point_method,
    threshold_of,
)
from fretting.analysis.stress import BULK_STATES, COMPONENTS, field
from fretting.engine.recorder import (
    CYCLE_FIELDS_EXPECTED,
    CYCLE_FIELDS_STORED,
    RECORD_ALL_STEPS,
    RECORDED_ENDS,
    CycleFields,
)
from fretting.engine.runner import CHECKPOINT_SECONDS, run_file
from fretting.errors import FrettingError, GrossSlipError, HistoryError, MissingDependencyError
from fretting.loading.examples import copy_example, examples, resolve_history
from fretting.loading.history_file import HistoryFileError, read_history_source
from fretting.models import Grid, Mesh
from fretting.models.collocation import DEFAULT_NODES
from fretting.models.galerkin import DEFAULT_RTOL, MAX_DEFAULT_MESH, MAX_DEFAULT_WORK
from fretting.results.io import ResultError, load, save
from fretting.results.tables import cycle_table, step_table, write_csv
from fretting.studies import running
from fretting.studies.maps import FileScene, nucleation_boundary
from fretting.studies.sweeps import (
    REGIMES,
    case_file,
    figures_for,
    is_sweep_file,
    keys,
    load_sweep,
    read_sweep,
    resolve_sweep,
    run_one,
    run_sweep,
    value_text,
)

__all__ = ["main"]

EXIT_FAILURE, EXIT_INPUT, EXIT_GROSS_SLIP, EXIT_INTERRUPTED = 1, 2, 3, 130

#: The variables of a running-condition sweep that `fretting plot` maps over (delta*, P), with the boundary.
RUNNING_MAPS = ("cycle_regime", "energy_ratio")

#: Default resolution of `fretting plot` and `fretting stress --figure` (raster formats): 6.4 x 4.4
#: inch figures at 100 dpi keep results/ of eight examples near 5 MB (7.9 MB at 150 dpi).
FIGURE_DPI = 100
#: Default size [inch] of those figures, and the formats they can be written in (vector: svg, pdf).
FIGURE_SIZE = (6.4, 4.4)
FIGURE_FORMATS = ("png", "svg", "pdf")

#: Default grid of `fretting stress`: points along x and in depth, the depth and the half-span in
#: half-widths a (two half-widths hold the peak shear under the contact and the edge gradients).
STRESS_NX, STRESS_NZ, STRESS_DEPTH, STRESS_SPAN = 201, 101, 2.0, 2.0

#: Criterion of `fretting stress --material` without --criterion: SWT needs only E and nu.
DEFAULT_CRITERION = "swt"

#: Seconds a run or a sweep lasts before its progress bar appears: short runs show none.
PROGRESS_DELAY = 2.0


def main(argv=None):
    """Run the command line with the arguments `argv` (``sys.argv[1:]`` when None); return the exit code.

    Ctrl-C is `_Interrupts`': never lost, and said in one line. With `argv` None (the process's own
    command line), an interrupt after the work is done is ignored: it would only kill the exiting
    interpreter, with a traceback or none.
    """
    args = _parser().parse_args(argv)
    with _Interrupts() as interrupts:
        code = _main(args, interrupts)
    if argv is None and threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    return code


class _Interrupts:
    """SIGINT, while the block runs in the main thread: KeyboardInterrupt as Python's own handler raises
    it, and remembered, so that one raised where Python cannot pass it on (a weakref callback or a
    ``__del__``, which it reports as "Exception ignored" and drops: h5py and xarray run both) is
    raised again at the next `check`, not lost, and is not reported there."""

    def __init__(self):
        self.lost = False

    def __enter__(self):
        self._main = threading.current_thread() is threading.main_thread()
        if self._main:
            self._handler = signal.signal(signal.SIGINT, self._interrupted)
            self._hook, sys.unraisablehook = sys.unraisablehook, self._unraisable
        return self

    def __exit__(self, *exception):
        if self._main:
            signal.signal(signal.SIGINT, self._handler)
            sys.unraisablehook = self._hook

    def _interrupted(self, signum, frame):
        self.lost = True  # until it is seen to pass (`passed`)
        raise KeyboardInterrupt

    def _unraisable(self, unraisable):
        if not issubclass(unraisable.exc_type, KeyboardInterrupt):
            self._hook(unraisable)

    def passed(self):
        """The interrupt raised was caught where it is handled: none is lost."""
        self.lost = False

    def check(self):
        """Raise KeyboardInterrupt if an interrupt was dropped since the last `passed`."""
        if self.lost:
            raise KeyboardInterrupt


def _main(args, interrupts):
    """`main` of the parsed arguments `args`."""
    args.interrupts = interrupts
    try:
        args.command(args)
        interrupts.check()
    except KeyboardInterrupt as interrupt:
        interrupts.passed()
        return _fail(args, interrupt, f"interrupted{f': {interrupt}' if interrupt.args else ''}", EXIT_INTERRUPTED)
    except GrossSlipError as error:
        return _fail(args, error, f"{args.file}: {error}", EXIT_GROSS_SLIP)
    except OSError as error:
        return _fail(args, error, f"{error.filename or args.file}: {error.strerror or error}", EXIT_INPUT)
    except (HistoryError, ResultError, MaterialFileError, MissingDependencyError) as error:
        return _fail(args, error, str(error), EXIT_INPUT)
    except FrettingError as error:
        return _fail(args, error, f"{args.file}: {error}", EXIT_FAILURE)
    return 0


def _fail(args, error, message, code):
    if args.debug:
        raise error
    print(f"fretting: error: {message}", file=sys.stderr)
    return code


def _parser():
    parser = argparse.ArgumentParser(
        prog="fretting", description="Partial-slip half-plane contacts under shear and bulk-tension histories."
    )
    parser.add_argument("--version", action="version", version=f"fretting {__version__}")
    commands = parser.add_subparsers(title="commands", required=True, metavar="COMMAND")
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--debug", action="store_true", help="show the traceback of an error")
    figures = argparse.ArgumentParser(add_help=False)
    figures.add_argument(
        "--format", choices=FIGURE_FORMATS, default="png", help="file format of the figures (default: png)"
    )
    figures.add_argument(
        "--dpi", type=_at_least(1, int), default=FIGURE_DPI, help=f"resolution of png figures (default {FIGURE_DPI})"
    )
    figures.add_argument(
        "--size",
        nargs=2,
        type=_at_least(0.5, float),
        default=FIGURE_SIZE,
        metavar=("WIDTH", "HEIGHT"),
        help=f"figure size in inches (default {FIGURE_SIZE[0]:g} {FIGURE_SIZE[1]:g})",
    )

    run = commands.add_parser("run", parents=[common], help="run a history file and write its result")
    run.add_argument("file", metavar="HISTORY", help="history file (TOML), or the name of a shipped example")
    run.add_argument(
        "-o", "--output", metavar="OUT", help="result file (default: <history stem>.h5 in the current folder)"
    )
    run.add_argument("--resume", action="store_true", help="continue an interrupted run from its checkpoint")
    model = run.add_mutually_exclusive_group()
    model.add_argument(
        "--nodes",
        type=_at_least(4, int),
        help=f"solve on a fixed grid of this many Gauss-Chebyshev collocation nodes instead (e.g. {DEFAULT_NODES})",
    )
    model.add_argument(
        "--rtol",
        type=_positive,
        help=f"relative accuracy of the energy asked of the P1 Galerkin model, on a mesh adapted to "
        f"the whole history (default: the exact model where Q alone loads a symmetric profile, else "
        f"{DEFAULT_RTOL:g}; a coarser mesh, said in a note, where that mesh would exceed {MAX_DEFAULT_MESH} "
        f"nodes or its run {MAX_DEFAULT_WORK:.2g} nodes squared times increments)",
    )
    run.add_argument(
        "--record",
        choices=("default", "all"),
        default="default",
        help=f"steps whose fields are stored: default every step of histories up to {RECORD_ALL_STEPS} steps, "
        f"else the first and last {RECORDED_ENDS}; energy and slip range per cycle always cover every cycle",
    )
    run.add_argument(
        "--checkpoint-interval",
        type=_at_least(0, float),
        default=CHECKPOINT_SECONDS,
        metavar="SECONDS",
        help=f"seconds between checkpoints (default {CHECKPOINT_SECONDS:g}; 0: after every chunk of steps)",
    )
    run.add_argument(
        "--every-step",
        action="store_true",
        help="solve every step (default: the steps inside straight stretches that are not recorded are skipped; "
        "the energy, w, slip range and q_peak are the same, the sigma_xx peaks per cycle are then not tallied)",
    )
    run.add_argument(
        "--cycle-fields",
        type=_cycle_fields,
        default="default",
        metavar="POLICY",
        help=f"cycles whose fields (w, slip amplitude, peaks) are stored: default every cycle of histories up to "
        f"{CYCLE_FIELDS_STORED} cycles, else first,last,every=K,maxima with K = cycles / {CYCLE_FIELDS_STORED} "
        f"rounded up; all; or a list of first, last, every=K, maxima. Energy per cycle, w_total and the fields' "
        f"maxima always cover every cycle",
    )
    run.set_defaults(command=_run)

    validate = commands.add_parser("validate", parents=[common], help="check a history file without running it")
    validate.add_argument("file", metavar="HISTORY", help="history file (TOML), or the name of a shipped example")
    validate.set_defaults(command=_validate)

    info = commands.add_parser("info", parents=[common], help="describe a result or sweep file")
    info.add_argument("file", metavar="RESULT", help="result file written by `fretting run`, or of `fretting sweep`")
    info.set_defaults(command=_info)

    plot = commands.add_parser("plot", parents=[common, figures], help="draw a result or sweep as figure files")
    plot.add_argument("file", metavar="RESULT", help="result file written by `fretting run`, or of `fretting sweep`")
    plot.add_argument("-o", "--output", metavar="DIR", help="directory of the figures (default: the result's)")
    plot.add_argument(
        "--body",
        type=int,
        choices=(1, 2),
        help="body of the surface-stress figure: 1 (traction q) or 2 (-q) "
        "(default: the specimen, with its bulk stress)",
    )
    plot.set_defaults(command=_plot)

    _stress_parser(commands, common, figures)

    export = commands.add_parser(
        "export", parents=[common], help="write a result's per-cycle (or per-step) table as CSV"
    )
    export.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    export.add_argument(
        "-o", "--output", metavar="FILE", help="CSV file (default: <result stem>_cycles.csv, or _steps.csv, beside it)"
    )
    export.add_argument(
        "--steps", action="store_true", help="the loads and scalars of each recorded step instead of each cycle"
    )
    export.set_defaults(command=_export)

    listing = commands.add_parser(
        "examples", parents=[common], help="list the shipped example histories, or copy one to edit"
    )
    listing.add_argument(
        "--copy", metavar="NAME", help="copy the example NAME, with the tables it names, into DIR to edit"
    )
    listing.add_argument("folder", nargs="?", metavar="DIR", help="folder of the copies (default: the current one)")
    listing.set_defaults(command=_examples, file="examples", usage_error=listing.error)

    _sweep_parser(commands, common)
    _fatigue_parsers(commands, common, figures)
    return parser


def _sweep_parser(commands, common):
    sweep = commands.add_parser(
        "sweep", parents=[common], help="run a sweep file on dask.distributed, or one case of it (job arrays)"
    )
    sweep.add_argument("file", metavar="SWEEP", help="sweep file (TOML), or the name of a shipped sweep")
    sweep.add_argument(
        "-o", "--output", metavar="OUT", help="dataset (default: results/<sweep stem>.h5); cases go to OUT.cases/"
    )
    how = sweep.add_mutually_exclusive_group()
    how.add_argument(
        "--scheduler",
        metavar="ADDR",
        help="dask scheduler address, e.g. tcp://host:8786 (default: a local cluster, one worker per core)",
    )
    how.add_argument(
        "--scheduler-file", metavar="FILE", help="file of a running dask scheduler (dask scheduler --scheduler-file)"
    )
    how.add_argument(
        "--case",
        type=int,
        metavar="K",
        help="run case K (from 0) alone, in this process, into OUT.cases/: a task of a job array "
        "(--case $SLURM_ARRAY_TASK_ID); then a sweep without --case joins the cases",
    )
    how.add_argument("--list-cases", action="store_true", help="list the cases: number, values, file in OUT.cases/")
    sweep.set_defaults(command=_sweep)


def _stress_parser(commands, common, figures):
    stress = commands.add_parser(
        "stress", parents=[common, figures], help="write the stress field under the surface of a result (and a figure)"
    )
    stress.add_argument("file", metavar="RESULT", help="result file written by `fretting run`")
    stress.add_argument("-o", "--output", metavar="OUT", help="field file (default: <result stem>_stress.h5 beside it)")
    stress.add_argument("--nx", type=_at_least(2, int), default=STRESS_NX, help=f"points along x (default {STRESS_NX})")
    stress.add_argument("--nz", type=_at_least(2, int), default=STRESS_NZ, help=f"depths (default {STRESS_NZ})")
    stress.add_argument(
        "--depth",
        type=_positive,
        default=STRESS_DEPTH,
        help=f"largest depth, in half-widths a (default {STRESS_DEPTH:g})",
    )
    stress.add_argument(
        "--span",
        type=_positive,
        default=STRESS_SPAN,
        help=f"x from centre - SPAN a to centre + SPAN a (default {STRESS_SPAN:g})",
    )
    stress.add_argument(
        "--step",
        type=_at_least(0, int),
        nargs="+",
        help="recorded steps (default: those of the last load cycle recorded whole, from its starting state, "
        "else the last step)",
    )
    stress.add_argument(
        "--body", choices=("specimen", "pad"), default="specimen", help="body of the field (default: the specimen)"
    )
    stress.add_argument("--nu", type=float, help="Poisson's ratio (default: the nu the result records)")
    stress.add_argument(
        "--bulk-state",
        choices=tuple(state.replace(" ", "-") for state in BULK_STATES),
        default="plane-strain",
        help="state of the specimen's bulk stress: plane-strain (held across its width, the default) or "
        "plane-stress (free across it, as a bar in tension); the contact's field is in plane strain either way",
    )
    stress.add_argument(
        "--material",
        metavar="FILE",
        help="material file (TOML, keys of fretting.analysis.fatigue.Material): map fatigue criteria over the steps, "
        "taken as one cycle, and read them at the critical distance when it gives critical_distance",
    )
    stress.add_argument(
        "--criterion",
        nargs="+",
        choices=tuple(CRITERIA),
        help=f"criteria mapped with --material (default: {DEFAULT_CRITERION})",
    )
    stress.add_argument(
        "--figure",
        choices=(*COMPONENTS, *CRITERIA),
        help="also draw this component at the last step, or this criterion's map (with --material), "
        "as <OUT stem>_<name>.<format>",
    )
    stress.set_defaults(command=_stress, usage_error=stress.error)


def _at_least(minimum, kind):
    """Argument type: a number of `kind` >= `minimum`."""

    def convert(text):
        try:
            value = kind(text)
        except ValueError:
            value = None
        if value is None or not value >= minimum:
            raise argparse.ArgumentTypeError(f"found {text!r}, expected a {kind.__name__} >= {minimum}")
        return value

    return convert


def _positive(text):
    """Argument type: a finite number > 0 (`fretting._validate.positive`)."""
    try:
        return positive("value", float(text))
    except ValueError:
        raise argparse.ArgumentTypeError(f"found {text!r}, expected a number > 0") from None


def _model(args):
    """The model spec the arguments ask for (None: the default)."""
    if args.nodes is not None:
        return Grid(args.nodes)
    return None if args.rtol is None else Mesh(rtol=args.rtol)


def _examples(args):
    if args.copy is not None:
        for path in copy_example(args.copy, args.folder or "."):
            print(path)
        return
    if args.folder is not None:
        args.usage_error(f"DIR {args.folder!r}: a folder is for --copy NAME")
    for name, description in examples().items():
        print(f"{name:<32} {description}")


def _cycle_fields(text):
    """`text` once `fretting.engine.recorder.CycleFields` reads it as a policy; argparse's error otherwise."""
    try:
        CycleFields.parse(text, 0)
    except ValueError as error:
        raise argparse.ArgumentTypeError(f"expected {CYCLE_FIELDS_EXPECTED}, found {text!r}") from error
    return text


def _run(args):
    history = resolve_history(args.file)
    output = Path(args.output or f"{history.stem}.h5")
    record = None if args.record == "default" else args.record
    with _progress("step", args.interrupts) as progress:
        run = run_file(
            history,
            output,
            _model(args),
            record=record,
            resume=args.resume,
            checkpoint_interval=args.checkpoint_interval,
            progress=progress,
            every_step=args.every_step,
            cycle_fields=args.cycle_fields,
        )
    for note in run.notes:
        print(f"fretting: note: {note}", file=sys.stderr)
    result = run.result
    print(f"{output}: {result.attrs['steps'] - 1} steps, {_cycles(result)} cycles, {_dissipated(result)}")


@contextlib.contextmanager
def _progress(unit, interrupts):
    """``progress(done, total)``, drawing a bar of `unit` on stderr when it is a terminal and the work
    lasts `PROGRESS_DELAY` seconds; each call raises an interrupt dropped since the last one
    (`_Interrupts.check`), so that the work stops there."""
    with tqdm(unit=unit, delay=PROGRESS_DELAY, disable=not sys.stderr.isatty(), file=sys.stderr) as bar:

        def progress(done, total):
            interrupts.check()
            bar.total, bar.n = total, done
            bar.refresh()

        yield progress


def _validate(args):
    source = read_history_source(resolve_history(args.file))
    contact, history = source.contact, source.history
    print(f"{source.path}: {contact.profile!r}, a = {contact.a:.4g} m, p0 = {contact.p0:.4g} Pa")
    print(f"  {len(history) - 1} steps, {history.vertex_step.size} vertices, {history.cycle_count} cycles")
    print(f"  {_peaks(*history.largest_loads(), contact.f, contact.P, contact.p0)}")
    fP = contact.f * contact.P
    step = history.first_step(lambda Q, sigma: np.abs(Q) >= fP)
    if step is not None:
        Q, sigma, _, _ = history.at([step])
        raise GrossSlipError(step, float(Q[0]), float(sigma[0]), fP)


def _info(args):
    if is_sweep_file(args.file):
        return _sweep_info(args)
    result = load(args.file)
    attrs = result.attrs
    versions = json.loads(attrs.get("versions", "{}"))
    lines = {
        "history": f"{attrs.get('history_file', '?')} (sha256 {attrs.get('history_sha256', '?')})",
        "contact": f"{attrs['profile']}, E_star = {attrs['E_star']:.4g} Pa, f = {attrs['f']:.4g}, "
        f"P = {attrs['P']:.4g} N/m",
        "solution": f"a = {attrs['a']:.4g} m, centre = {attrs['centre']:.4g} m, p0 = {attrs['p0']:.4g} Pa",
        "model": f"{attrs['model']} ({attrs.get('model_description', '')}), {attrs['nodes']} nodes"
        + (f"; fell back: {attrs['model_fallback']}" if "model_fallback" in attrs else "")
        + (f"; mesh {attrs['model_sample']}" if "model_sample" in attrs else ""),
        "steps": f"{result.attrs['steps'] - 1} steps ({result.sizes['step']} recorded), "
        f"{result.sizes['vertex']} vertices, {_cycles(result)} cycles",
        "loads": _peaks(result.Q.values, result.sigma.values, attrs["f"], attrs["P"], attrs["p0"]),
        "energy": _dissipated(result),
        "created": attrs.get("created", "?"),
        "versions": ", ".join(f"{name} {version}" for name, version in versions.items()),
    }
    print(args.file)
    for name, text in lines.items():
        print(f"  {name:<9} {text}")


def _plot(args):
    if is_sweep_file(args.file):
        return _sweep_plot(args)
    import matplotlib  # here, not at the top: the other commands do without its start-up time

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from fretting import plots

    result = load(args.file)
    directory = Path(args.output) if args.output else Path(args.file).parent
    directory.mkdir(parents=True, exist_ok=True)
    for name in plots.figures_for(result):
        figure = Figure(figsize=args.size, layout="constrained")
        options = {"body": args.body} if name == "surface_stress" else {}
        plots.FIGURES[name](result, ax=figure.subplots(), **options)
        _saved(figure, directory / f"{Path(args.file).stem}_{name}", args)


def _saved(figure, stem, args):
    """Write `figure` as ``<stem>.<args.format>`` at ``args.dpi`` and print its path."""
    path = stem.with_name(f"{stem.name}.{args.format}")
    figure.savefig(path, dpi=args.dpi, format=args.format)
    print(path)


def _export(args):
    result = load(args.file)
    kind = "steps" if args.steps else "cycles"
    try:
        table = step_table(result) if args.steps else cycle_table(result)
    except ValueError as error:
        raise ResultError(f"{args.file}: {error}") from None
    output = Path(args.output or Path(args.file).with_name(f"{Path(args.file).stem}_{kind}.csv"))
    write_csv(table, output, f"fretting export of {Path(args.file).name}")
    print(f"{output}: {table.sizes[next(iter(table.dims))]} {kind}, {len(table.data_vars) + 1} columns")


def _sweep(args):
    file = resolve_sweep(args.file)
    plan = read_sweep(file)
    output = Path(args.output) if args.output else Path("results") / f"{file.stem}.h5"
    cases = plan.cases()
    if args.list_cases:
        for k, values in enumerate(cases):
            print(f"{k}\t{_values(values)}\t{case_file(output, plan.base, plan.case(values))}")
        return
    if args.case is not None:
        if not 0 <= args.case < len(cases):
            expected = f"expected a case from 0 to {len(cases) - 1} (--list-cases lists them)"
            raise HistoryFileError(file, None, "--case", f"found {args.case}, {expected}")
        path, summary, ran = run_one(plan, args.case, output)
        regime = REGIMES[int(summary.regime)].replace("_", " ")
        again = "" if ran else " (its file was there: not run again)"
        print(f"{path}: case {args.case} of {len(cases)}, {_values(cases[args.case])}: {regime}{again}")
        return
    with _progress("case", args.interrupts) as progress:
        swept = run_sweep(plan, args.scheduler, output, scheduler_file=args.scheduler_file, progress=progress)
    dims = " x ".join(f"{key} ({len(values)})" for key, values in plan.grid.items())
    print(f"{output}: {swept.regime.size} cases over {dims}: {_regimes(swept)}")


def _regimes(cases):
    """The cases of the sweep dataset `cases` in each regime, e.g. ``0 stuck, 2 partial slip, 1 gross slip``."""
    counts = np.bincount(cases.regime.values.ravel(), minlength=len(REGIMES))
    return ", ".join(f"{count} {name.replace('_', ' ')}" for count, name in zip(counts, REGIMES, strict=True))


def _values(values):
    """The values of a case, ``key = value`` joined by commas (lists as JSON)."""
    return ", ".join(f"{key} = {json.dumps(value)}" for key, value in values.items())


def _sweep_info(args):
    cases = load_sweep(args.file)
    attrs, names = cases.attrs, keys(cases)
    print(args.file)
    print(f"  {'history':<9} {attrs.get('history_file', '?')} (base sha256 {attrs.get('base_sha256', '?')})")
    for n, (dim, key) in enumerate(names.items()):
        units = cases[dim].attrs.get("units")
        shown = ", ".join(value_text(value) for value in cases[dim].values) + (f" [{units}]" if units else "")
        print(f"  {'grid' if n == 0 else '':<9} {key} ({cases.sizes[dim]}): {shown}")
    print(f"  {'cases':<9} {cases.regime.size}: {_regimes(cases)}")
    for n, (name, variable) in enumerate(cases.data_vars.items()):
        values = variable.values[np.isfinite(variable.values)]
        found = f"{values.min():.4g} to {values.max():.4g}" if values.size else "none"
        missing = variable.size - values.size
        what = f"{variable.attrs.get('long_name', name)} [{variable.attrs.get('units', '?')}]"
        print(f"  {'recorded' if n == 0 else '':<9} {name}: {what}: {found}" + (f" ({missing} NaN)" if missing else ""))
    print(f"  {'created':<9} {attrs.get('created', '?')}")


def _sweep_plot(args):
    import matplotlib  # as in _plot

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    cases = load_sweep(args.file)
    directory = Path(args.output) if args.output else Path(args.file).parent
    directory.mkdir(parents=True, exist_ok=True)
    for name, draw in figures_for(cases).items():
        figure = Figure(figsize=args.size, layout="constrained")
        draw(cases, ax=figure.subplots())
        _saved(figure, directory / f"{Path(args.file).stem}_{name}", args)
    if running.running_dims(cases) is not None:  # a sweep over P and a displacement amplitude
        from fretting import plots

        mapped = running.running_cases(cases)
        for name in RUNNING_MAPS:
            figure = Figure(figsize=args.size, layout="constrained")
            plots.running_condition_map(mapped, name, ax=figure.subplots())
            _saved(figure, directory / f"{Path(args.file).stem}_running_{name}", args)


def _stress(args):
    criteria = _stress_criteria(args)
    material = Material.from_file(args.material) if criteria else None
    result = load(args.file)
    a, centre = result.attrs["a"], result.attrs["centre"]
    x = centre + a * np.linspace(-args.span, args.span, args.nx)
    z = a * np.linspace(0.0, args.depth, args.nz)
    specimen = nucleation.specimen(result)
    body = specimen if args.body == "specimen" else 3 - specimen
    try:
        stresses = field(
            result,
            x,
            z,
            step=args.step or _last_cycle(result),
            body=body,
            nu=args.nu,
            bulk_state=args.bulk_state.replace("-", " "),
        )
    except ValueError as error:
        raise ResultError(f"{args.file}: {error}") from None
    written = xr.merge([stresses, *(_criterion_map(stresses, name, material, args.material) for name in criteria)])
    output = Path(args.output or Path(args.file).with_name(f"{Path(args.file).stem}_stress.h5"))
    save(written, output)
    print(
        f"{output}: {stresses.sizes['step']} steps, {stresses.sizes['z']} x {stresses.sizes['x']} points, "
        f"body {body} ({args.body}), "
        f"bulk stress in {stresses.attrs['bulk_state']}"
    )
    for name in criteria:
        print(_critical_distances(name, written[name]))
    if args.figure:
        import matplotlib  # as in _plot: only when a figure is asked for

        matplotlib.use("Agg")
        from matplotlib.figure import Figure

        from fretting import plots

        figure = Figure(figsize=args.size, layout="constrained")
        plots.stress_map(written[args.figure], result, step=int(written.step[-1]), ax=figure.subplots())
        _saved(figure, output.with_name(f"{output.stem}_{args.figure}"), args)


def _stress_criteria(args):
    """The criteria `fretting stress` maps: --criterion (default `DEFAULT_CRITERION`) and a --figure of one."""
    if args.material is None:
        if args.criterion or args.figure in CRITERIA:
            option = "--criterion" if args.criterion else f"--figure {args.figure}"
            args.usage_error(f"{option}: a criterion needs --material FILE (the material's constants)")
        return []
    criteria = list(dict.fromkeys(args.criterion or [DEFAULT_CRITERION]))
    return criteria + ([args.figure] if args.figure in CRITERIA and args.figure not in criteria else [])


def _criterion_map(stresses, name, material, path):
    """`fretting.analysis.fatigue.apply` over the field's steps, its variables renamed ``<name>`` (the parameter)
    and ``<name>_<variable>``, the parameter's attributes holding its critical distances."""
    try:
        maps = apply(stresses, name, material)
    except ValueError as error:  # a constant the criterion needs is missing from the file
        raise MaterialFileError(path, None, str(error).removeprefix("material: ")) from None
    maps = maps.rename({variable: name if variable == "parameter" else f"{name}_{variable}" for variable in maps})
    maps[name].attrs.update(_distances(maps[name], material, path))
    return maps


def _distances(parameter, material, path):
    """The surface hot spot, and the point and line methods below it (`fretting.analysis.fatigue`) when the material
    gives ``L``, as attributes [the parameter's units, m]."""
    value, x_hot = hot_spot(parameter)
    attributes = {"hot_spot": value, "x_hot": x_hot}
    L = material.critical_distance
    if L is None:
        return attributes
    try:
        point, line = point_method(parameter, L, x_hot=x_hot), line_method(parameter, L, x_hot=x_hot)
    except ValueError:
        reach = f"expected 2 L = {2 * L:.6g} m within the grid's depth {float(parameter.z[-1]):.6g} m (raise --depth)"
        raise MaterialFileError(path, "critical_distance", f"found {L!r} m, {reach}") from None
    return attributes | {"critical_distance": L, "point_method": point.value, "line_method": line.value}


def _critical_distances(name, parameter):
    """One line: a criterion's hot spot and its values at the critical distance."""
    attrs, units = parameter.attrs, parameter.attrs["units"]
    line = f"{name}: hot spot {attrs['hot_spot']:.6g} {units} at x = {attrs['x_hot']:.6g} m"
    if "critical_distance" not in attrs:
        return f"{line}; no critical distance (the material gives none)"
    return (
        f"{line}; point method (L/2 = {attrs['critical_distance'] / 2:.6g} m below it) "
        f"{attrs['point_method']:.6g} {units}; line method (mean over 2 L) {attrs['line_method']:.6g} {units}"
    )


def _last_cycle(result):
    """Steps of the last load cycle recorded whole, from its starting state; else the last step."""
    if "cycle_number" in result.dims and result.sizes["cycle_number"]:
        rows = nucleation.complete_cycles(result)[-1]
        if rows is not None:
            return result.step.values[rows].tolist()
    return [int(result.step[-1])]


def _peaks(Q, sigma, f, P, p0):
    """The largest loads of a history, relative to those of gross slip."""
    psi, tau = np.abs(Q).max() / (f * P), np.abs(sigma).max() / (f * p0)
    return f"max |Q| / (f P) = {psi:.3g}, max |sigma| / (f p0) = {tau:.3g}"


def _cycles(result):
    return result.cycle_dissipation.size if "cycle_dissipation" in result else 0


def _dissipated(result):
    total = f"dissipated {float(result.total_dissipation):.4g} J/m"
    if _cycles(result):
        return f"{total}, {float(result.cycle_dissipation[-1]):.4g} J/m in the last cycle"
    return total


def _fatigue_parsers(commands, common, figures):
    """The subcommands of a test programme: ``materials``, ``threshold`` and ``map``."""
    listing = commands.add_parser(
        "materials", parents=[common], help="list the shipped material files and their sources"
    )
    listing.set_defaults(command=_materials, file="materials")

    search = argparse.ArgumentParser(add_help=False)
    search.add_argument(
        "file", metavar="HISTORY", help="history file (TOML), or a shipped example's name: the test's shape"
    )
    search.add_argument(
        "--bracket",
        nargs=2,
        type=float,
        required=True,
        metavar=("LOW", "HIGH"),
        help="the values searched between, in the units of the varied key (e.g. N/m for Q_amplitude)",
    )
    search.add_argument("--criterion", choices=tuple(CRITERIA), required=True, help="fatigue criterion")
    search.add_argument(
        "--material", required=True, metavar="FILE", help="material file (TOML), or a name of `fretting materials`"
    )
    length = search.add_mutually_exclusive_group()
    length.add_argument(
        "--critical-distance", type=_positive, metavar="L", help="critical distance L [m] (overrides the file's)"
    )
    length.add_argument(
        "--delta-K-th",
        type=_positive,
        metavar="DK",
        help="threshold range of the stress intensity factor [Pa m^0.5]: L = (1/pi) (DK / (2 sigma_limit))^2 "
        "(El Haddad)",
    )
    search.add_argument(
        "--at",
        choices=tuple(name.replace(" ", "-") for name in READINGS),
        default="point",
        help="where the criterion is read: point (L/2 below the hot spot, the default), line (mean over 2 L), hot-spot",
    )
    search.add_argument("--nu", type=float, help="Poisson's ratio for sigma_yy (default: the history's)")
    search.add_argument(
        "--bulk-state",
        choices=tuple(state.replace(" ", "-") for state in BULK_STATES),
        default="plane-strain",
        help="state of the specimen's bulk stress (as fretting stress)",
    )
    search.add_argument(
        "--nodes", type=_at_least(4, int), help="solve on a fixed grid of this many nodes (default: the default model)"
    )

    threshold = commands.add_parser(
        "threshold",
        parents=[common, search],
        help="the value of a history key (Q or sigma amplitude, pad radius, P) at which a criterion reaches its limit "
        "or a life",
    )
    threshold.add_argument(
        "--vary",
        required=True,
        metavar="KEY",
        help="dotted key of the history file searched over, e.g. loading[1].Q_amplitude, contact.R",
    )
    threshold.add_argument(
        "--life",
        type=_positive,
        nargs="+",
        metavar="N",
        help="target lives [cycles] (default: the criterion's fatigue limit)",
    )
    threshold.set_defaults(command=_threshold)

    fatigue_map = commands.add_parser(
        "map",
        parents=[common, search, figures],
        help="the nucleation boundary: the threshold Q amplitude for each bulk stress amplitude",
    )
    fatigue_map.add_argument(
        "--q-key",
        default="loading[1].Q_amplitude",
        metavar="KEY",
        help="key of the Q amplitude [N/m] (default loading[1].Q_amplitude)",
    )
    fatigue_map.add_argument(
        "--sigma-key",
        default="loading[1].sigma_amplitude",
        metavar="KEY",
        help="key of the bulk stress amplitude [Pa] (default loading[1].sigma_amplitude)",
    )
    fatigue_map.add_argument(
        "--sigma", type=float, nargs="+", required=True, metavar="S", help="bulk stress amplitudes [Pa] of the map"
    )
    fatigue_map.add_argument(
        "--life", type=_positive, metavar="N", help="target life [cycles] (default: the fatigue limit)"
    )
    fatigue_map.add_argument(
        "--dask", metavar="SCHEDULER", choices=("processes", "threads"), help="run the points as dask tasks"
    )
    fatigue_map.add_argument(
        "-o", "--output", metavar="OUT", help="map file (default: <history stem>_map.h5 in the current folder)"
    )
    fatigue_map.add_argument("--figure", action="store_true", help="also draw the boundary as <OUT stem>.<format>")
    fatigue_map.set_defaults(command=_map)


def _materials(args):
    for name, (path, description) in materials().items():
        print(f"{name:<16} {description}")
        print(f"{'':<16} {path}")


def _search_inputs(args):
    """The material (with --critical-distance or --delta-K-th), model and reading of a threshold or map command."""
    path = material_path(args.material)
    material = Material.from_file(path)
    override = {"critical_distance": args.critical_distance} if args.critical_distance else {}
    if args.delta_K_th:
        override = {"critical_distance": None, "delta_K_th": args.delta_K_th}
    material = dataclasses.replace(material, **override)
    low, high = args.bracket
    if not low < high:
        raise HistoryError(f"{args.file}: --bracket: found {low:g} {high:g}, expected LOW < HIGH")
    return path, material, None if args.nodes is None else Grid(args.nodes), args.at.replace("-", " ")


def _searched(args, path, search):
    """`search()` with its errors as one line: a constant the material lacks, or a bracket with no crossing."""
    try:
        return search()
    except BracketError as error:
        raise HistoryError(f"{args.file}: --{error}") from None
    except FrettingError:
        raise
    except ValueError as error:
        raise MaterialFileError(path, None, str(error).removeprefix("material: ")) from None


def _threshold(args):
    path, material, model, at = _search_inputs(args)
    scene = FileScene(resolve_history(args.file), (args.vary,))
    cache = {}
    for life in args.life or [None]:
        found = _searched(
            args,
            path,
            lambda life=life: threshold_of(
                scene,
                tuple(args.bracket),
                args.criterion,
                material,
                life=life,
                at=at,
                nu=args.nu,
                bulk_state=args.bulk_state.replace("-", " "),
                model=model,
                cache=cache,
                name=args.vary,
            ),
        )
        target = "its fatigue limit" if life is None else f"a life of {life:.6g} cycles"
        units = found.values.parameter.attrs["units"]
        print(
            f"{args.criterion} at {at} reaches {target} at {args.vary} = {found.amplitude:.6g} "
            f"(parameter {float(found.values.parameter):.6g} {units}; {found.runs} values searched, "
            f"{len(cache)} runs in all)"
        )


def _map(args):
    path, material, model, at = _search_inputs(args)
    history = resolve_history(args.file)
    scene = FileScene(history, (args.q_key, args.sigma_key))
    boundary = _searched(
        args,
        path,
        lambda: nucleation_boundary(
            scene,
            args.sigma,
            tuple(args.bracket),
            args.criterion,
            material,
            life=args.life,
            at=at,
            nu=args.nu,
            bulk_state=args.bulk_state.replace("-", " "),
            model=model,
            scheduler=args.dask,
        ),
    )
    output = Path(args.output or f"{history.stem}_map.h5")
    save(boundary, output)
    print(f"{output}: {boundary.sizes['sigma_amplitude']} bulk stress amplitudes, {int(boundary.runs.sum())} runs")
    for sigma, Q, side in zip(
        boundary.sigma_amplitude.values, boundary.Q_threshold.values, boundary.side.values, strict=True
    ):
        where = {
            0: f"Q_a = {Q:.6g} N/m",
            1: "above the target over the bracket",
            -1: "below the target over the bracket",
        }
        print(f"  sigma_a = {sigma:.6g} Pa: {where[int(side)]}")
    if args.figure:
        import matplotlib  # as in _plot: only when a figure is asked for

        matplotlib.use("Agg")
        from matplotlib.figure import Figure

        from fretting import plots_maps

        figure = Figure(figsize=args.size, layout="constrained")
        plots_maps.nucleation_boundary(boundary, figure.subplots())
        _saved(figure, output.with_name(output.stem), args)
